#!/usr/bin/env python3
"""What a droplet did to a bed of mobile grains, from the first and last snapshots of a run
(and, for the grains the fluid touched, every snapshot between; the binder-jetting scenes,
cases/am/binder_jetting_*.yaml, Fuchs et al. 2022 Sec. 4.2), in 2D (up is y) or 3D (up is z).

    tools/bed_metrics.py OUTDIR [--speed 5] [--csv FILE] [--gas MATERIAL]

Prints, at the last snapshot against the first:
  grains        how many grains moved more than dx (centre of mass of the grain's
                particles), the median and largest displacement, and how many rose
                by more than dx (lifted off the bed), and how many of those the fluid never
                touched (no fluid particle within 1.5 dx of one of theirs in any snapshot:
                lifted through the bed's contacts, not by the liquid);
  fastest       the largest speed of a fluid particle, and how many are faster
                than --speed m/s;
  spread        the span along each horizontal axis of the fluid particles that touch
                a solid (a grain, a fixed solid or a wall particle within 1.5 dx): the
                wetted width, and the grains touched;
  walls         the fluid particles within 2 dx of the side walls' inner faces
                (the walls' innermost particles), and the highest of them above
                the substrate's top (the climb);
  depth         the lowest fluid particle's height above the substrate's top;
  packing       the grains' share of the column under the droplet as it starts (the
                column of the droplet's radius about its centre, from the substrate's top
                to the top of the bed, the highest grain particle's top at the first
                snapshot; the radius from the droplet's volume, its fluid particles
                times dx^d, as a circle or sphere), at the first and the last snapshot:
                compressed below the droplet, the bed packs it more densely;
  drift         the fluid's mean horizontal position (its centre of mass) at the first
                and last snapshot, and the horizontal momentum of the fluid and of the
                grains at the last;
  lone          fluid particles with fewer than 3 fluid neighbours within 1.5 dx
                (spray and particles left on the grains).
Lengths in um. --csv FILE writes the readings as one row of a table as well. --gas MATERIAL
(the material's index in the case file, from 0) leaves that gas phase out of every snapshot:
the readings are those of the liquid, and the gas counts as the void.
"""
import argparse
import csv
import glob
import os

import h5py
import numpy as np

FLUID, WALL, SOLID, GRAIN = 0, 1, 2, 3


def snapshot(path, gas=None):
    """A snapshot's datasets and attributes, without the particles of material `gas`."""
    with h5py.File(path, "r") as f:
        s = {name: f[name][()] for name in f}
        attrs = {"time": float(f.attrs["time"]), "dx": float(f.attrs["dx"]), "dim": int(f.attrs["dim"])}
    if gas is not None:
        kept = s["material"] != gas
        s = {name: values[kept] for name, values in s.items()}
    return s | attrs


def within(points, others, reach):
    """For each point: how many of `others` lie within `reach` (brute force, in blocks, over the
    others inside the points' bounding box widened by reach)."""
    counts = np.zeros(len(points), dtype=int)
    if len(points) == 0:
        return counts
    near = np.all((others >= points.min(axis=0) - reach) & (others <= points.max(axis=0) + reach), axis=1)
    others = others[near]
    for start in range(0, len(points), 128):
        block = points[start:start + 128]
        d2 = ((block[:, None, :] - others[None, :, :]) ** 2).sum(axis=2)
        counts[start:start + 128] = (d2 < reach * reach).sum(axis=1)
    return counts


def grain_centres(s):
    dim = s["dim"]
    ids = np.unique(s["grain"][s["kind"] == GRAIN])
    centres = {}
    for g in ids:
        m = (s["kind"] == GRAIN) & (s["grain"] == g)
        centres[int(g)] = (s["position"][m, :dim] * s["mass"][m, None]).sum(axis=0) / s["mass"][m].sum()
    return centres


def touched_grains(s, reach):
    """The grains with a particle within `reach` of a fluid particle in snapshot s."""
    fluid, x = s["kind"] == FLUID, s["position"]
    if not fluid.any():
        return set()
    lo, hi = x[fluid].min(axis=0) - reach, x[fluid].max(axis=0) + reach
    grain = (s["kind"] == GRAIN) & np.all((x >= lo) & (x <= hi), axis=1)
    near = within(x[grain], x[fluid], reach) > 0
    return set(s["grain"][grain][near].tolist())


def packing_under_drop(first, snapshots, substrate_top):
    """The grain particles' volume (dx^d each) over that of the column under the droplet as it
    starts in `first`, in each of `snapshots`."""
    dx, dim = first["dx"], first["dim"]
    up = dim - 1
    fluid = first["kind"] == FLUID
    drop = first["position"][fluid, :up]
    centre = (first["mass"][fluid, None] * drop).sum(axis=0) / first["mass"][fluid].sum()
    volume = np.sum(fluid) * dx ** dim
    radius = np.sqrt(volume / np.pi) if dim == 2 else (3.0 * volume / (4.0 * np.pi)) ** (1.0 / 3.0)
    bed_top = first["position"][first["kind"] == GRAIN, up].max() + 0.5 * dx
    column = (2.0 * radius if dim == 2 else np.pi * radius ** 2) * (bed_top - substrate_top)
    shares = []
    for s in snapshots:
        x = s["position"][s["kind"] == GRAIN]
        inside = (np.linalg.norm(x[:, :up] - centre, axis=1) < radius) & (x[:, up] > substrate_top) \
            & (x[:, up] < bed_top)
        shares.append(np.sum(inside) * dx ** dim / column)
    return shares


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--speed", type=float, default=5.0, help="speed counted as fast, m/s (default 5)")
    ap.add_argument("--csv", help="also write the readings to this CSV file")
    ap.add_argument("--gas", type=int, help="material index of a gas phase to leave out")
    args = ap.parse_args()
    paths = sorted(glob.glob(os.path.join(args.outdir, "snap_*.h5")))
    if len(paths) < 2:
        raise SystemExit(f"{args.outdir}: needs at least two snapshots")
    first, last = snapshot(paths[0], args.gas), snapshot(paths[-1], args.gas)
    dx, dim, um = last["dx"], last["dim"], 1e6
    up, across = dim - 1, range(dim - 1)
    names = "xyz"

    start, end = grain_centres(first), grain_centres(last)
    kept = [g for g in start if g in end]
    shift = np.array([np.linalg.norm(end[g] - start[g]) for g in kept])
    rise = np.array([end[g][up] - start[g][up] for g in kept])
    wetted = touched_grains(first, 1.5 * dx) | touched_grains(last, 1.5 * dx)
    wetted = wetted.union(*(touched_grains(snapshot(p, args.gas), 1.5 * dx) for p in paths[1:-1]))
    dry = sum(1 for g, lift in zip(kept, rise) if lift > dx and g not in wetted)
    r = {"time_s": last["time"], "grains": len(kept), "grains_moved": np.sum(shift > dx),
         "displacement_median_um": np.median(shift) * um, "displacement_max_um": shift.max() * um,
         "grains_rose": np.sum(rise > dx), "grains_rose_dry": dry}
    print(f"t = {last['time']:.4g} s, {len(last['kind'])} particles, {len(paths)} snapshots")
    print(f"grains: {np.sum(shift > dx)} of {len(kept)} moved > dx; displacement median {np.median(shift) * um:.1f}"
          f" / max {shift.max() * um:.1f} um; {np.sum(rise > dx)} rose > dx, {dry} of them never touched by the fluid")

    kind, x = last["kind"], last["position"][:, :dim]
    fluid = kind == FLUID
    speed = np.linalg.norm(last["velocity"][fluid], axis=1)
    r |= {"fastest_m_s": speed.max(), "fast_particles": np.sum(speed > args.speed)}
    print(f"fastest fluid particle: {speed.max():.1f} m/s ({np.sum(speed > args.speed)} above {args.speed:g} m/s)")

    xf = x[fluid]
    touching = within(xf, x[~fluid], 1.5 * dx) > 0
    if touching.any():
        grains_touched = touched_grains(last, 1.5 * dx)
        wet = xf[touching]
        spans = "; ".join(f"{names[a]} {wet[:, a].min() * um:.1f} to {wet[:, a].max() * um:.1f}" for a in across)
        widths = " by ".join(f"{(wet[:, a].max() - wet[:, a].min()) * um:.1f}" for a in across)
        r |= {f"wetted_width_{names[a]}_um": (wet[:, a].max() - wet[:, a].min()) * um for a in across}
        r["grains_touched"] = len(grains_touched)
        print(f"spread: wetted width {widths} um ({spans}); {len(grains_touched)} grains touched")
    walls = x[kind == WALL]
    substrate_top = (x[kind == SOLID, up].max() if np.any(kind == SOLID) else walls[:, up].min()) + 0.5 * dx
    on_wall = np.zeros(len(xf), dtype=bool)
    for a in across:
        low, high = walls[:, a].min(), walls[:, a].max()
        inner_low = walls[walls[:, a] < low + 2.5 * dx, a].max()
        inner_high = walls[walls[:, a] > high - 2.5 * dx, a].min()
        on_wall |= (xf[:, a] < inner_low + 2 * dx) | (xf[:, a] > inner_high - 2 * dx)
    r |= {"on_walls": np.sum(on_wall), "depth_um": (xf[:, up].min() - substrate_top) * um}
    if on_wall.any():
        r["wall_climb_um"] = (xf[on_wall, up].max() - substrate_top) * um
    climb = f", highest {r['wall_climb_um']:.1f} um above the substrate" if on_wall.any() else ""
    print(f"walls: {np.sum(on_wall)} fluid particles within 2 dx of the side walls{climb}")
    print(f"depth: lowest fluid particle {r['depth_um']:.1f} um above the substrate")
    packing = packing_under_drop(first, (first, last), substrate_top)
    r |= {"packing_under_drop_start": packing[0], "packing_under_drop_end": packing[1]}
    print(f"packing: grains fill {packing[0]:.3f} -> {packing[1]:.3f} of the column under the droplet")
    mass, u = last["mass"], last["velocity"]
    for a in across:
        mean = [(s["mass"][s["kind"] == FLUID] * s["position"][s["kind"] == FLUID, a]).sum()
                / s["mass"][s["kind"] == FLUID].sum() for s in (first, last)]
        r |= {f"fluid_mean_{names[a]}_start_um": mean[0] * um, f"fluid_mean_{names[a]}_end_um": mean[1] * um}
        print(f"drift: fluid mean {names[a]} {mean[0] * um:.1f} -> {mean[1] * um:.1f} um; {names[a]}-momentum fluid "
              f"{(mass[fluid] * u[fluid, a]).sum():.3g}, grains {(mass[kind == GRAIN] * u[kind == GRAIN, a]).sum():.3g}"
              f" kg m/s{' per m' if dim == 2 else ''}")
    lone = within(xf, xf, 1.5 * dx) - 1 < 3
    r["lone"] = np.sum(lone)
    print(f"lone: {np.sum(lone)} fluid particles with fewer than 3 fluid neighbours within 1.5 dx")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            table = csv.DictWriter(f, fieldnames=list(r))
            table.writeheader()
            table.writerow({k: f"{float(v):.9g}" for k, v in r.items()})


if __name__ == "__main__":
    main()
