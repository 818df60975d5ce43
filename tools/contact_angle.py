#!/usr/bin/env python3
"""Contact angle of a sessile drop on a flat wall, from its particles.

    tools/contact_angle.py OUTDIR [--wall 0] [--csv angle.csv]

For each snapshot of OUTDIR: a circle (2D) or sphere (3D) is fitted by Kasa's
algebraic least squares through the free-surface fluid particles more than
2 dx above the wall face (up the last axis, at --wall), its radius taken dx/2
out (the surface lies half a spacing beyond the outer particles), and

    cos theta = (wall - centre_up) / radius          (theta in the liquid)

A free-surface particle has fewer particles of any kind within 2.1 dx than a
lattice's interior (12 in 2D, 32 in 3D; fewer than 11 and 29 are taken). The
same reading as tests/test_surface.c's sessile_angle. Printed per snapshot:
time, the angle, the base radius sqrt(R^2 - (wall - centre)^2), the fitted
radius, the RMS distance of the surface particles from the fitted circle or
sphere (in dx: a cap that is no longer round shows here), and the fastest
fluid particle. On a lattice the outer particles form a staircase, which biases
the fit of a shallow cap: a 60-degree lattice cap reads 60.5 degrees (3D) and
60.2 (2D) at a radius of 20 dx, 62.2 and 65.3 at 14 dx (tests/test_contact_angle.py).
"""
import argparse
import glob
import os

import numpy as np

from track_metrics import neighbour_counts, snapshot, write_csv

FLUID = 0  # particle kind of a fluid (kernels/kinds.h)
INTERIOR = {2: 11, 3: 29}  # fewer neighbours within 2.1 dx than this: on the surface


def kasa_fit(points):
    """Centre and radius of the circle or sphere |x - c|^2 = R^2 closest to the
    points in the algebraic sense: x.x + a.x + b = 0 by linear least squares."""
    rows = np.hstack([points, np.ones((len(points), 1))])
    coeff, *_ = np.linalg.lstsq(rows, -(points ** 2).sum(axis=1), rcond=None)
    centre = -0.5 * coeff[:-1]
    return centre, np.sqrt(centre @ centre - coeff[-1])


def sessile_angle(s, wall):
    """(angle in degrees, base radius, radius, RMS misfit / dx, fastest speed)
    of the fluid of snapshot s on the wall face at height `wall`."""
    dim, dx = s["dim"], s["dx"]
    x = s["position"][:, :dim].astype(float)
    up = dim - 1
    fluid = s["kind"] == FLUID
    surface = fluid & (x[:, up] > wall + 2.0 * dx)
    surface[surface] = neighbour_counts(x, 2.1 * dx, of=x[surface]) < INTERIOR[dim]
    if surface.sum() < dim + 2:
        raise SystemExit(f"t = {s['time']:g} s: {surface.sum()} free-surface particles above the wall, "
                         f"too few to fit a {'circle' if dim == 2 else 'sphere'}")
    centre, radius = kasa_fit(x[surface])
    misfit = np.sqrt(((np.linalg.norm(x[surface] - centre, axis=1) - radius) ** 2).mean()) / dx
    radius += 0.5 * dx
    height = wall - centre[up]
    angle = np.degrees(np.arccos(np.clip(height / radius, -1.0, 1.0)))
    base = np.sqrt(max(radius ** 2 - height ** 2, 0.0))
    speed = np.linalg.norm(s["velocity"][fluid, :dim].astype(float), axis=1).max()
    return angle, base, radius, misfit, speed


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir", help="output folder of amsph run (snap_*.h5)")
    ap.add_argument("--wall", type=float, default=0.0, help="height of the wall face on the last axis, m")
    ap.add_argument("--csv", help="also write the table to this CSV file")
    args = ap.parse_args()

    paths = sorted(glob.glob(os.path.join(args.outdir, "snap_*.h5")))
    if not paths:
        raise SystemExit(f"{args.outdir} holds no snap_*.h5: give the output folder of 'amsph run'")
    rows = ["time_s,angle_deg,base_radius_m,radius_m,misfit_dx,fastest_m_s"]
    print(f"{'t (s)':>9} {'angle':>7} {'base r':>9} {'radius':>9} {'misfit/dx':>9} {'fastest':>10}")
    for path in paths:
        s = snapshot(path)
        values = sessile_angle(s, args.wall)
        rows.append(f"{s['time']:.6g}," + ",".join(f"{v:.6g}" for v in values))
        print(f"{s['time']:9.4g} {values[0]:7.2f} {values[1]:9.4g} {values[2]:9.4g} {values[3]:9.3f} "
              f"{values[4]:10.3e}")
    write_csv(args.csv, rows)


if __name__ == "__main__":
    main()
