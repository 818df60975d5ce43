#!/usr/bin/env python3
"""tools/contact_angle.py on snapshots of caps with a known contact angle.
A cubic (square in 2D) lattice, dx = 0.05 m, fills the spherical (circular)
cap of radius R = 1 m (20 dx) whose centre lies at up = -R cos(theta)
below the wall face up = 0, so that the cap meets the face at theta; four
wall layers lie below the face. For theta = 60 and 120 degrees, in 3D and
2D, the tool's angle is checked to within 2 degrees (the fitted surface is
the outer particles' staircase, which the radius + dx/2 of the reading puts
back on the cap), its base radius R sin(theta) to 2 dx, and the fastest
fluid particle (one is given 0.25 m/s; a wall particle faster) exactly. On
a shallow cap the staircase biases the fit: at 60 degrees the lattice cap
reads 60.5 / 60.2 (3D / 2D) at R = 20 dx, 60.7 / 60.8 at 18 dx, 62.2 /
65.3 at 14 dx and 64.0 / 67.0 at 12 dx (120 degrees: within 0.6 at each).
The geometric reading (distances fitted over the arc from 1 dx up, the
centre on the fluid's axis) is checked to within 1 degree on these caps and
on the same caps at dx = R / 12, where Kasa's fit is 4 to 7 degrees high at
60 degrees: it reads 59.7 / 59.6 at 20 dx, 60.1 / 60.6 at 12 dx (59.8 /
59.0 at 14 dx), and 120.2 / 120.1 and 120.5 / 120.5 at 120 degrees.
Skipped (exit 77) where numpy or h5py is missing.

usage: test_contact_angle.py SOURCE_DIR WORK_DIR
"""
import os
import shutil
import sys

from tool_checks import check_readings, h5py, last_csv_row, np

DX, R, FASTEST = 0.05, 1.0, 0.25
FLUID, WALL = 0, 1  # kernels/kinds.h


def cap(dim, theta, dx):
    """Particle centres of the cap at angle theta (degrees) on a lattice of
    spacing dx and of the wall below it, 3 coordinates each as snapshots
    store them, and their kinds."""
    centre_up = -R * np.cos(np.radians(theta))
    x = np.arange(-1.1 + 0.5 * dx, 1.1, dx)
    up = np.arange(-4.0 * dx + 0.5 * dx, 1.6, dx)
    axes = (x, x, up) if dim == 3 else (x, up, np.zeros(1))
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    offset = grid.copy()
    offset[:, dim - 1] -= centre_up
    inside = (offset[:, :dim] ** 2).sum(axis=1) <= R * R
    fluid = inside & (grid[:, dim - 1] > 0.0)
    wall = grid[:, dim - 1] < 0.0
    keep = fluid | wall
    return grid[keep], np.where(fluid[keep], FLUID, WALL).astype(np.int32)


def check(source, work, dim, theta, dx):
    """Runs the tool on one cap; returns (checks, failed checks). At DX every
    reading is checked, on a coarser lattice the geometric angle only."""
    folder = os.path.join(work, f"{dim}d_{theta:g}_{R / dx:g}dx")
    os.makedirs(folder)
    position, kind = cap(dim, theta, dx)
    velocity = np.zeros_like(position)
    velocity[np.flatnonzero(kind == FLUID)[0], 0] = FASTEST
    velocity[np.flatnonzero(kind == WALL)[0], 0] = 10.0 * FASTEST  # walls do not count
    with h5py.File(os.path.join(folder, "snap_000000.h5"), "w") as f:
        f.attrs["dim"], f.attrs["dx"], f.attrs["time"] = dim, dx, 1.0
        f["position"], f["kind"] = position.astype(np.float32), kind
        f["velocity"] = velocity.astype(np.float32)
    got = last_csv_row(source, "contact_angle", folder)
    expected = {"geometric_angle_deg": (theta, 1.0)}
    if dx == DX:
        expected.update({"angle_deg": (theta, 2.0), "base_radius_m": (R * np.sin(np.radians(theta)), 2.0 * DX),
                         "fastest_m_s": (FASTEST, 1e-6)})
    return len(expected), check_readings(f"{dim}D theta {theta:g}, {R / dx:g} dx:", got, expected)


def main():
    source, work = sys.argv[1:3]
    shutil.rmtree(work, ignore_errors=True)
    runs = [(dim, theta, dx) for dim in (3, 2) for theta in (60.0, 120.0) for dx in (DX, R / 12.0)]
    checks, failed = np.sum([check(source, work, *run) for run in runs], axis=0)
    print(f"{checks - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
