#!/usr/bin/env python3
"""Plot the particles of one amsph snapshot coloured by a field.

    tools/plot_snapshot.py OUTDIR/snap_000010.h5 -o snap.png --field pressure
    tools/plot_snapshot.py OUTDIR/snap_000010.h5 -o slice.png --field velocity --slice y=0.05

2D snapshots are drawn in the x-y plane. 3D snapshots are drawn as a slab of
one particle spacing (dx) around a plane normal to an axis (--slice AXIS=VALUE,
default: z through the middle of the particles). A vector field is coloured
by its magnitude. Wall and solid particles are drawn in grey unless
--all-kinds is given.
"""
import argparse

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

AXES = "xyz"


def field_values(f, name):
    if name not in f:
        raise SystemExit(f"{f.filename} has no field '{name}'; it has: {', '.join(sorted(f))}")
    values = f[name][()]
    unit = f[name].attrs.get("unit", b"")
    unit = unit.decode() if isinstance(unit, bytes) else str(unit)
    if values.ndim == 2:
        return np.linalg.norm(values, axis=1), f"|{name}| [{unit}]"
    return values.astype(float), f"{name} [{unit}]"


def parse_slice(text):
    axis, _, value = text.partition("=")
    if axis not in AXES or not value:
        raise SystemExit(f"--slice takes AXIS=VALUE with AXIS one of x, y, z, got '{text}'")
    return AXES.index(axis), float(value)


def select(position, dim, dx, plane):
    """Mask of the particles drawn and the two axes of the picture."""
    if dim == 2:
        return np.ones(len(position), bool), (0, 1), ""
    axis, value = plane if plane else (2, float(np.median(position[:, 2])))
    shown = [a for a in range(3) if a != axis]
    mask = np.abs(position[:, axis] - value) <= 0.5 * dx
    return mask, tuple(shown), f", slab {AXES[axis]} = {value:g} ± {0.5 * dx:g} m"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("snapshot", help="snap_NNNNNN.h5 written by amsph run")
    ap.add_argument("-o", "--output", required=True, help="PNG file to write")
    ap.add_argument("--field", default="velocity", help="field to colour by (default: velocity)")
    ap.add_argument("--slice", help="3D: the plane AXIS=VALUE (m) of the slab drawn")
    ap.add_argument("--all-kinds", action="store_true", help="colour walls and solids too")
    args = ap.parse_args()

    with h5py.File(args.snapshot, "r") as f:
        position = f["position"][()]
        kind = f["kind"][()]
        values, label = field_values(f, args.field)
        dim, dx, time = int(f.attrs["dim"]), float(f.attrs["dx"]), float(f.attrs["time"])
    mask, (a, b), where = select(position, dim, dx, parse_slice(args.slice) if args.slice else None)
    coloured = mask & ((kind == 0) | args.all_kinds)
    grey = mask & ~coloured
    if not mask.any():
        raise SystemExit(f"no particles in the slab{where}")

    extent = np.ptp(position[mask][:, [a, b]], axis=0) + dx
    fig, ax = plt.subplots(figsize=(7, 7 * min(2.0, max(0.3, extent[1] / extent[0])) + 0.5))
    size = max(1.0, (0.9 * 72 * 4.5 * dx / extent[0]) ** 2)  # marker area, points^2: 0.9 dx across
    ax.scatter(position[grey, a], position[grey, b], s=size, c="0.7", marker="s", lw=0)
    points = ax.scatter(position[coloured, a], position[coloured, b], s=size, c=values[coloured],
                        cmap="viridis", marker="o", lw=0)
    fig.colorbar(points, ax=ax, label=label, shrink=0.8)
    ax.set_aspect("equal")
    ax.margins(0.05)
    ax.set_xlabel(f"{AXES[a]} [m]")
    ax.set_ylabel(f"{AXES[b]} [m]")
    ax.set_title(f"t = {time:.6g} s{where}", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)


if __name__ == "__main__":
    main()
