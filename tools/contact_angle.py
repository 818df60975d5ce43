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

A second reading, "geometric", fits the sphere (circle) to the free-surface
particles more than 1 dx above the wall by least squares of their distances
from it (Gauss-Newton from Kasa's fit), its centre on the vertical through the
fluid's centroid, and takes its radius dx/2 out as above. Kasa's algebraic fit
of a short arc drifts with the staircase; the geometric fit, with the longer
arc and two unknowns, reads the 60-degree lattice caps at 59.7 and 59.6
degrees (3D, 2D) at 20 dx, 59.8 and 59.0 at 14 dx, 60.1 and 60.6 at 12 dx, and
the 120-degree caps within 0.8 degree from 12 dx up; below 12 dx its 60-degree
readings fall low (56.4 and 55.3 at 8.5 dx). Where a cap is not round near the
wall the two readings part (BENCHMARKS.md, "A second reading of the contact angle").
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


def geometric_fit(points, centre, radius, up):
    """Centre and radius of the sphere (circle) through the points by least
    squares of their distances from it, Gauss-Newton from (centre, radius);
    the centre moves along axis `up` only."""
    for _ in range(50):
        offset = points - centre
        distance = np.linalg.norm(offset, axis=1)
        jacobian = np.stack([-offset[:, up] / distance, -np.ones(len(points))], axis=1)
        step, *_ = np.linalg.lstsq(jacobian, radius - distance, rcond=None)
        centre = centre.copy()
        centre[up] += step[0]
        radius += step[1]
        if np.abs(step).max() < 1e-12 * radius:
            break
    return centre, radius


def cap_angle(wall, centre_up, radius):
    """Contact angle (degrees, in the liquid) and base radius of the cap of a
    sphere of this centre height and radius on the wall face."""
    height = wall - centre_up
    angle = np.degrees(np.arccos(np.clip(height / radius, -1.0, 1.0)))
    return angle, np.sqrt(max(radius ** 2 - height ** 2, 0.0))


def surface_above(x, fluid, height, dim, dx):
    """The free-surface fluid particles above `height` on the last axis."""
    surface = fluid & (x[:, dim - 1] > height)
    surface[surface] = neighbour_counts(x, 2.1 * dx, of=x[surface]) < INTERIOR[dim]
    return surface


def sessile_angle(s, wall):
    """(angle in degrees, its geometric reading, base radius, radius, RMS
    misfit / dx, fastest speed) of the fluid of snapshot s on the wall face at
    height `wall`."""
    dim, dx = s["dim"], s["dx"]
    x = s["position"][:, :dim].astype(float)
    up = dim - 1
    fluid = s["kind"] == FLUID
    arc = surface_above(x, fluid, wall + dx, dim, dx)
    surface = arc & (x[:, up] > wall + 2.0 * dx)
    if surface.sum() < dim + 2:
        raise SystemExit(f"t = {s['time']:g} s: {surface.sum()} free-surface particles above the wall, "
                         f"too few to fit a {'circle' if dim == 2 else 'sphere'}")
    centre, radius = kasa_fit(x[surface])
    misfit = np.sqrt(((np.linalg.norm(x[surface] - centre, axis=1) - radius) ** 2).mean()) / dx
    angle, base = cap_angle(wall, centre[up], radius + 0.5 * dx)
    axis = centre.copy()
    axis[:up] = x[fluid, :up].mean(axis=0)
    axis, arc_radius = geometric_fit(x[arc], axis, np.linalg.norm(x[arc] - axis, axis=1).mean(), up)
    geometric, _ = cap_angle(wall, axis[up], arc_radius + 0.5 * dx)
    speed = np.linalg.norm(s["velocity"][fluid, :dim].astype(float), axis=1).max()
    return angle, geometric, base, radius + 0.5 * dx, misfit, speed


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir", help="output folder of amsph run (snap_*.h5)")
    ap.add_argument("--wall", type=float, default=0.0, help="height of the wall face on the last axis, m")
    ap.add_argument("--csv", help="also write the table to this CSV file")
    args = ap.parse_args()

    paths = sorted(glob.glob(os.path.join(args.outdir, "snap_*.h5")))
    if not paths:
        raise SystemExit(f"{args.outdir} holds no snap_*.h5: give the output folder of 'amsph run'")
    rows = ["time_s,angle_deg,geometric_angle_deg,base_radius_m,radius_m,misfit_dx,fastest_m_s"]
    print(f"{'t (s)':>9} {'angle':>7} {'geometric':>9} {'base r':>9} {'radius':>9} {'misfit/dx':>9} {'fastest':>10}")
    for path in paths:
        s = snapshot(path)
        values = sessile_angle(s, args.wall)
        rows.append(f"{s['time']:.6g}," + ",".join(f"{v:.6g}" for v in values))
        print(f"{s['time']:9.4g} {values[0]:7.2f} {values[1]:9.2f} {values[2]:9.4g} {values[3]:9.4g} "
              f"{values[4]:9.3f} {values[5]:10.3e}")
    write_csv(args.csv, rows)


if __name__ == "__main__":
    main()
