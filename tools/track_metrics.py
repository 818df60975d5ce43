#!/usr/bin/env python3
"""Russell's track metrics (2018 Table 5.3) from the snapshots of a run.

    tools/track_metrics.py OUTDIR [--time 0.26e-3] [--surface 0] [--solidus 1673] [--liquidus 1773]
                           [--end-margin 50e-6] [--csv FILE]

At the snapshot nearest --time (Russell: 0.26 ms, mid-lasering):
  penetration  the deepest initial position, below the substrate's initial
               surface (y or z = --surface), of a substrate particle whose
               peak temperature has reached the solidus (and the liquidus),
               in um: particle centres, followed by id from the first snapshot;
               over the track, leaving out the substrate within --end-margin
               of its side faces across the scan (x), where melt that runs
               over the edge heats the face from the side; their own
               penetration is printed apart;
  max T        the largest temperature at that time, K;
  max speed    the largest particle speed at that time, m/s;
both over the bed (particles with at least 3 others within 1.5 dx) and over
lone particles thrown off it (spatter), and the number of particles more
than half liquid.
"""
import argparse
import glob
import os

import h5py
import numpy as np


def snapshot(path):
    with h5py.File(path, "r") as f:
        return {name: f[name][()] for name in f} | {"time": float(f.attrs["time"]),
                                                     "dim": int(f.attrs["dim"]), "dx": float(f.attrs["dx"])}


def write_csv(path, rows):
    """Write the lines `rows` (a header, then one line per row) to `path`; nothing without one."""
    if path:
        with open(path, "w") as f:
            f.write("\n".join(rows) + "\n")


def neighbour_counts(position, reach, of=None):
    """Other particles of `position` within `reach` of each particle, or of
    each of the points `of` (particles among `position`; brute force, in blocks)."""
    of = position if of is None else of
    counts = np.empty(len(of), dtype=int)
    for start in range(0, len(of), 1024):
        block = of[start:start + 1024]
        d2 = ((block[:, None, :] - position[None, :, :]) ** 2).sum(axis=2)
        counts[start:start + 1024] = (d2 < reach * reach).sum(axis=1) - 1
    return counts


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("outdir")
    parser.add_argument("--time", type=float, default=0.26e-3)
    parser.add_argument("--surface", type=float, default=0.0)
    parser.add_argument("--solidus", type=float, default=1673.0)
    parser.add_argument("--liquidus", type=float, default=1773.0)
    parser.add_argument("--end-margin", type=float, default=50e-6)
    parser.add_argument("--csv", help="write the readings as one row of a table as well")
    args = parser.parse_args()
    paths = sorted(glob.glob(os.path.join(args.outdir, "snap_*.h5")))
    if not paths:
        raise SystemExit(f"no snapshots in {args.outdir}")
    first = snapshot(paths[0])
    times = []
    for path in paths:
        with h5py.File(path, "r") as f:
            times.append(float(f.attrs["time"]))
    now = snapshot(paths[int(np.argmin(np.abs(np.array(times) - args.time)))])
    up = first["dim"] - 1
    initial = np.full((int(first["id"].max()) + 1, first["position"].shape[1]), np.nan)
    initial[first["id"]] = first["position"]
    depth = args.surface - initial[now["id"], up]  # initial depth below the surface, m
    fixed = now["kind"] != 1  # not wall
    substrate_x = first["position"][(first["kind"] != 1) & (first["position"][:, up] < args.surface), 0]
    x = initial[now["id"], 0]
    at_ends = (x < substrate_x.min() + args.end_margin) | (x > substrate_x.max() - args.end_margin)
    peak = now["peak_temperature"]

    def penetration(threshold, where):
        melted = fixed & where & (depth > 0) & (peak >= threshold)
        return 1e6 * depth[melted].max() if melted.any() else 0.0

    speed = np.linalg.norm(now["velocity"], axis=1)
    bed = neighbour_counts(now["position"], 1.5 * now["dx"]) >= 3

    def largest(values, where):
        return values[where].max() if where.any() else float("nan")

    reading = {"time_ms": now["time"] * 1e3, "penetration_solidus_um": penetration(args.solidus, ~at_ends),
               "penetration_liquidus_um": penetration(args.liquidus, ~at_ends),
               "penetration_ends_um": penetration(args.solidus, at_ends),
               "bed_max_temperature_K": largest(now["temperature"], bed), "bed_max_speed": largest(speed, bed),
               "spatter": int((~bed).sum()), "spatter_max_temperature_K": largest(now["temperature"], ~bed),
               "spatter_max_speed": largest(speed, ~bed),
               "over_half_liquid": int((now["liquid_fraction"] > 0.5).sum())}
    print(f"t = {reading['time_ms']:.4f} ms ({os.path.basename(paths[times.index(now['time'])])}): "
          f"penetration {reading['penetration_solidus_um']:.1f} um (solidus), "
          f"{reading['penetration_liquidus_um']:.1f} um (liquidus), at the ends (within "
          f"{args.end_margin * 1e6:.0f} um) {reading['penetration_ends_um']:.1f} um (solidus); "
          f"bed: max T {reading['bed_max_temperature_K']:.0f} K, max speed "
          f"{reading['bed_max_speed']:.2f} m/s; {reading['spatter']} spatter particles: max T "
          f"{reading['spatter_max_temperature_K']:.0f} K, max speed {reading['spatter_max_speed']:.2f} m/s; "
          f"{reading['over_half_liquid']} particles over half liquid")
    write_csv(args.csv, [",".join(reading), ",".join(f"{v:g}" for v in reading.values())])


if __name__ == "__main__":
    main()
