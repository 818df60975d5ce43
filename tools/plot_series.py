#!/usr/bin/env python3
"""Plot columns of an amsph diagnostics series (OUTDIR/series.csv) against time.

    tools/plot_series.py OUTDIR/series.csv -o series.png
    tools/plot_series.py OUTDIR/series.csv -o energy.png --columns kinetic_energy total_mass
    tools/plot_series.py OUTDIR/melt_pool.csv -o pool.png --units-from metrics --columns melt_depth

Each column gets its own panel, labelled with its unit (from `amsph columns`,
or `amsph analyze --metrics` for a melt-pool analysis, when the amsph binary
is given, else the name alone). Empty cells (a column that does not apply to
the case) are skipped, and a column with no value at all gets no panel.
"""
import argparse
import csv
import math
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

DEFAULT_COLUMNS = ["max_speed", "kinetic_energy", "total_mass", "fluid_particles", "dt",
                   "particle_steps_per_second"]


def read_series(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise SystemExit(f"{path}: empty")
    header, body = rows[0], rows[1:]
    columns = {}
    for k, name in enumerate(header):
        columns[name] = np.array([float(r[k]) if k < len(r) and r[k] != "" else math.nan for r in body])
    return columns


REFERENCES = {"columns": ["columns"], "metrics": ["analyze", "--metrics"]}


def units_from(amsph, reference):
    """Column units from `amsph columns` or `amsph analyze --metrics` (a Markdown table)."""
    if not amsph:
        return {}
    text = subprocess.run([amsph] + REFERENCES[reference], capture_output=True, text=True, check=True).stdout
    units = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) >= 2 and cells[0].startswith("`"):
            units[cells[0].strip("`")] = cells[1]
    return units


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("series", help="series.csv written by amsph run")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--columns", nargs="+", help=f"columns to plot (default: {' '.join(DEFAULT_COLUMNS)})")
    ap.add_argument("--amsph", help="amsph binary, for the units of the columns")
    ap.add_argument("--units-from", choices=sorted(REFERENCES), default="columns",
                    help="the reference the units come from: the series columns (default) or the "
                         "melt-pool metrics")
    args = ap.parse_args()

    data = read_series(args.series)
    wanted = args.columns or [c for c in DEFAULT_COLUMNS if c in data]
    missing = [c for c in wanted if c not in data]
    if missing:
        raise SystemExit(f"{args.series} has no column {', '.join(missing)}; it has: {', '.join(data)}")
    if "time" not in data:
        raise SystemExit(f"{args.series} has no time column")
    units = units_from(args.amsph, args.units_from)
    wanted = [c for c in wanted if not np.all(np.isnan(data[c]))]  # columns that do not apply
    if not wanted:
        raise SystemExit(f"{args.series}: every column asked for is empty")

    fig, axes = plt.subplots(len(wanted), 1, sharex=True, figsize=(7, 1.8 * len(wanted) + 0.6), squeeze=False)
    for ax, name in zip(axes[:, 0], wanted):
        y = data[name]
        keep = ~np.isnan(y)
        ax.plot(data["time"][keep], y[keep], marker=".", lw=1)
        ax.set_ylabel(f"{name}\n[{units[name]}]" if name in units else name, fontsize=8)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)


if __name__ == "__main__":
    main()
