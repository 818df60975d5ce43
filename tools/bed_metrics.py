#!/usr/bin/env python3
"""What a droplet did to a bed of mobile grains, from the first and last snapshots of a run
(the binder-jetting scenes, cases/am/binder_jetting_*_2d.yaml, Fuchs et al. 2022 Sec. 4.2).

    tools/bed_metrics.py OUTDIR [--speed 5]

Prints, at the last snapshot against the first:
  grains        how many grains moved more than dx (centre of mass of the grain's
                particles), the median and largest displacement, and how many rose
                by more than dx (lifted off the bed);
  fastest       the largest speed of a fluid particle, and how many are faster
                than --speed m/s;
  spread        the x-span of the fluid particles that touch a solid (a grain, a
                fixed solid or a wall particle within 1.5 dx): the wetted width,
                and the grains touched;
  walls         the fluid particles within 2 dx of the side walls' inner faces
                (the walls' innermost particles), and the highest of them above
                the substrate's top (the climb);
  depth         the lowest fluid particle's height above the substrate's top;
  drift         the fluid's mean x (its centre of mass) at the first and last snapshot,
                and the x-momentum of the fluid and of the grains at the last;
  lone          fluid particles with fewer than 3 fluid neighbours within 1.5 dx
                (spray and particles left on the grains).
Lengths in um.
"""
import argparse
import glob
import os

import h5py
import numpy as np

FLUID, WALL, SOLID, GRAIN = 0, 1, 2, 3


def snapshot(path):
    with h5py.File(path, "r") as f:
        return {name: f[name][()] for name in f} | {"time": float(f.attrs["time"]), "dx": float(f.attrs["dx"])}


def within(points, others, reach):
    """For each point: how many of `others` lie within `reach` (brute force, in blocks)."""
    counts = np.empty(len(points), dtype=int)
    for start in range(0, len(points), 512):
        block = points[start:start + 512]
        d2 = ((block[:, None, :] - others[None, :, :]) ** 2).sum(axis=2)
        counts[start:start + 512] = (d2 < reach * reach).sum(axis=1)
    return counts


def grain_centres(s):
    ids = np.unique(s["grain"][s["kind"] == GRAIN])
    centres = {}
    for g in ids:
        m = (s["kind"] == GRAIN) & (s["grain"] == g)
        centres[int(g)] = (s["position"][m, :2] * s["mass"][m, None]).sum(axis=0) / s["mass"][m].sum()
    return centres


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--speed", type=float, default=5.0, help="speed counted as fast, m/s (default 5)")
    args = ap.parse_args()
    paths = sorted(glob.glob(os.path.join(args.outdir, "snap_*.h5")))
    if len(paths) < 2:
        raise SystemExit(f"{args.outdir}: needs at least two snapshots")
    first, last = snapshot(paths[0]), snapshot(paths[-1])
    dx, um = last["dx"], 1e6

    start, end = grain_centres(first), grain_centres(last)
    kept = [g for g in start if g in end]
    shift = np.array([np.linalg.norm(end[g] - start[g]) for g in kept])
    rise = np.array([end[g][1] - start[g][1] for g in kept])
    print(f"t = {last['time']:.4g} s, {len(last['kind'])} particles, {len(paths)} snapshots")
    print(f"grains: {np.sum(shift > dx)} of {len(kept)} moved > dx; displacement median {np.median(shift) * um:.1f}"
          f" / max {shift.max() * um:.1f} um; {np.sum(rise > dx)} rose > dx")

    kind, x = last["kind"], last["position"][:, :2]
    fluid = kind == FLUID
    speed = np.linalg.norm(last["velocity"][fluid], axis=1)
    print(f"fastest fluid particle: {speed.max():.1f} m/s ({np.sum(speed > args.speed)} above {args.speed:g} m/s)")

    solid = kind != FLUID
    xf = x[fluid]
    touching = within(xf, x[solid], 1.5 * dx) > 0
    grains_touched = set()
    if touching.any():
        grain_particles = kind == GRAIN
        near = within(x[grain_particles], xf, 1.5 * dx) > 0
        grains_touched = set(last["grain"][grain_particles][near].tolist())
        print(f"spread: wetted width {(xf[touching, 0].max() - xf[touching, 0].min()) * um:.1f} um"
              f" (x {xf[touching, 0].min() * um:.1f} to {xf[touching, 0].max() * um:.1f}); "
              f"{len(grains_touched)} grains touched")
    walls = x[kind == WALL]
    substrate_top = (x[kind == SOLID, 1].max() if np.any(kind == SOLID) else walls[:, 1].min()) + 0.5 * dx
    left, right = walls[:, 0].min(), walls[:, 0].max()
    inner_left = walls[walls[:, 0] < left + 2.5 * dx, 0].max()
    inner_right = walls[walls[:, 0] > right - 2.5 * dx, 0].min()
    on_wall = (xf[:, 0] < inner_left + 2 * dx) | (xf[:, 0] > inner_right - 2 * dx)
    climb = f", highest {(xf[on_wall, 1].max() - substrate_top) * um:.1f} um above the substrate" if on_wall.any() else ""
    print(f"walls: {np.sum(on_wall)} fluid particles within 2 dx of the side walls{climb}")
    print(f"depth: lowest fluid particle {(xf[:, 1].min() - substrate_top) * um:.1f} um above the substrate")
    mass, u = last["mass"], last["velocity"][:, 0]
    mean_x = [(s["mass"][s["kind"] == FLUID] * s["position"][s["kind"] == FLUID, 0]).sum()
              / s["mass"][s["kind"] == FLUID].sum() for s in (first, last)]
    print(f"drift: fluid mean x {mean_x[0] * um:.1f} -> {mean_x[1] * um:.1f} um; x-momentum fluid "
          f"{(mass[fluid] * u[fluid]).sum():.3g}, grains {(mass[kind == GRAIN] * u[kind == GRAIN]).sum():.3g} kg m/s"
          f"{' per m' if last['position'][:, 2].max() == last['position'][:, 2].min() else ''}")
    lone = within(xf, xf, 1.5 * dx) - 1 < 3
    print(f"lone: {np.sum(lone)} fluid particles with fewer than 3 fluid neighbours within 1.5 dx")


if __name__ == "__main__":
    main()
