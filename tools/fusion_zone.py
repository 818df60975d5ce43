#!/usr/bin/env python3
"""Fusion zone of a spot weld: radius and depth of the metal that melted.

    tools/fusion_zone.py OUTDIR [--solidus 1673] [--axis 0,0] [--base-top Z] [--csv fz.csv]

The fusion zone is every fluid or solid particle whose peak_temperature
reached the solidus (He, Fuerschbach & DebRoy 2003 etch the weld's cross
section; Russell 2018 §4.4 reads it from the particles the same way). For each
snapshot of OUTDIR it prints three readings, each particle standing for a cell
dx wide:

  final    the particles where they are: radius = the largest distance from
           the beam axis + dx/2, depth = the initial surface - the lowest
           particle + dx/2. Liquid that flowed out over the solid before it
           froze counts where it froze.
  initial  the same particles where they started (matched by id in the first
           snapshot): the fusion boundary in the base metal, which no flow
           moves.
  isotherm the solidus isotherm of the peak temperature in the base metal,
           read between lattice points: radius = sqrt(A / pi) of the area A
           (dx^2 each) of the top layer's fused particles (3D; 2D: half their
           width), depth = where the peak temperature, averaged over the
           columns nearest the axis, falls through the solidus (linear
           between layers; 0 if the top layer did not reach it, the lowest
           layer's bottom if every layer did).

The initial surface is the highest non-wall particle of the first snapshot +
dx/2. With --base-top Z it is Z, and only the particles that started below Z
count (the remelt depth of a substrate under a droplet that was molten from
the start, as in material jetting). The beam axis is vertical (the last axis: y in 2D, z in 3D) through
--axis.
"""
import argparse
import glob
import os

import numpy as np

from track_metrics import snapshot, write_csv

WALL = 1  # particle kind of a wall (kernels/kinds.h)


def positions(s):
    """The snapshot's positions in its dimension (2D files carry z = 0)."""
    return s["position"][:, :s["dim"]].astype(float)


def extent(position, axis, surface, dx):
    """Radius from the vertical axis through `axis` and depth below `surface`."""
    up = position.shape[1] - 1
    across = position[:, :up] - axis[:up]
    radius = np.sqrt((across ** 2).sum(axis=1)).max() + 0.5 * dx
    depth = surface - position[:, up].min() + 0.5 * dx
    return radius, depth


def isotherm(start, peak, solidus, axis, surface, dx):
    """Radius and depth of the solidus isotherm of the peak temperature in the
    initial lattice (start: initial positions of the non-wall particles)."""
    up = start.shape[1] - 1
    across = np.sqrt(((start[:, :up] - axis[:up]) ** 2).sum(axis=1))
    fused = peak >= solidus
    top = start[:, up] > surface - dx
    count = (fused & top).sum()
    radius = dx * np.sqrt(count / np.pi) if up == 2 else 0.5 * dx * count
    column = across < across.min() + 0.01 * dx
    layers = np.unique(np.round(start[column, up] / (0.01 * dx)))[::-1] * 0.01 * dx
    profile = [(z, peak[column][np.abs(start[column, up] - z) < 0.1 * dx].mean()) for z in layers]
    if profile[0][1] < solidus:
        return radius, 0.0
    for (z0, t0), (z1, t1) in zip(profile, profile[1:]):
        if t1 < solidus:
            return radius, surface - (z0 + (solidus - t0) * (z1 - z0) / (t1 - t0))
    return radius, surface - (profile[-1][0] - 0.5 * dx)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir", help="output folder of amsph run (snap_*.h5)")
    ap.add_argument("--solidus", type=float, default=1673.0, help="solidus temperature, K (304 steel: 1673)")
    ap.add_argument("--axis", help="beam axis: its horizontal coordinates, m (x,y in 3D, x in 2D; default 0)")
    ap.add_argument("--base-top", type=float,
                    help="top of the base metal, m (vertical coordinate): only particles that started below it "
                         "count, depths are read from it (default: the first snapshot's highest non-wall particle "
                         "+ dx/2, all non-wall particles count)")
    ap.add_argument("--csv", help="also write the table to this CSV file")
    args = ap.parse_args()

    snapshots = sorted(glob.glob(os.path.join(args.outdir, "snap_*.h5")))
    if not snapshots:
        raise SystemExit(f"{args.outdir} holds no snap_*.h5: give the output folder of 'amsph run'")
    first = snapshot(snapshots[0])
    up = first["dim"] - 1
    across = [float(v) for v in args.axis.split(",")] if args.axis else [0.0] * up
    if len(across) != up:
        raise SystemExit(f"--axis takes {up} coordinate(s) for a {first['dim']}D run, got '{args.axis}'")
    axis = np.array(across + [0.0])
    start = np.full((int(first["id"].max()) + 1, first["dim"]), np.nan)
    start[first["id"]] = positions(first)
    if args.base_top is None:
        surface = positions(first)[first["kind"] != WALL, up].max() + 0.5 * first["dx"]
    else:
        surface = args.base_top

    rows = ["time_s,fused_particles,radius_final_m,depth_final_m,radius_initial_m,depth_initial_m,"
            "radius_isotherm_m,depth_isotherm_m"]
    print(f"{'t (ms)':>8} {'fused':>6} {'radius: final':>14} {'initial':>8} {'isotherm':>9} "
          f"{'depth: final':>13} {'initial':>8} {'isotherm':>9}  (mm)")
    for path in snapshots:
        s = snapshot(path)
        origin = start[s["id"]]
        material = (s["kind"] != WALL) & (origin[:, up] < surface)
        peak = s["peak_temperature"].astype(float)
        fused = material & (peak >= args.solidus)
        if not fused.any():
            continue
        final = extent(positions(s)[fused], axis, surface, s["dx"])
        initial = extent(origin[fused], axis, surface, s["dx"])
        iso = isotherm(origin[material], peak[material], args.solidus, axis, surface, s["dx"])
        rows.append(f"{s['time']:.6g},{fused.sum()}," + ",".join(f"{v:.6g}" for v in (*final, *initial, *iso)))
        print(f"{s['time'] * 1e3:8.3f} {fused.sum():6d} {final[0] * 1e3:14.3f} {initial[0] * 1e3:8.3f} "
              f"{iso[0] * 1e3:9.3f} {final[1] * 1e3:13.3f} {initial[1] * 1e3:8.3f} {iso[1] * 1e3:9.3f}")
    write_csv(args.csv, rows)


if __name__ == "__main__":
    main()
