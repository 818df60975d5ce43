#!/usr/bin/env python3
"""tools/fusion_zone.py on snapshots with a known fusion zone, in 3D and 2D.
A lattice (dx = 0.05 m) under a flat surface at up = 0 (z in 3D, y in 2D)
has a peak temperature whose solidus isotherm is the half-ellipsoid (half
ellipse) (r / R)^2 + (up / D)^2 = 1, R = 0.97 m, D = 0.485 m (between
lattice layers); in the second snapshot the fused particles of the top layer
have moved 0.3 m along x. Checked:
  - isotherm: the radius and depth of that ellipsoid in the lattice's top
    layer and nearest columns, R sqrt(1 - (dx / 2D)^2) and
    D sqrt(1 - (c / R)^2) (c = dx / sqrt(2) in 3D, dx / 2 in 2D), the depth
    to dx / 4, the radius to dx / 4 in 3D (the lattice's fused extremes are
    0.02 and 0.015 m off) and dx / 2 in 2D (a width of whole particles);
  - initial: the lattice's fused extremes plus dx / 2, to the CSV's six
    digits (the moved particles are found by id where they started);
  - final: the moved particles' largest distance from the axis plus dx / 2;
  - --base-top 0 with a molten droplet (peak 2500 K, radius 0.5 m) resting
    on the surface: the same readings, the droplet left out (without the
    option the surface would be read at the droplet's top).
Skipped (exit 77) where numpy or h5py is missing.

usage: test_fusion_zone.py SOURCE_DIR WORK_DIR
"""
import os
import shutil
import sys

from tool_checks import check_readings, h5py, last_csv_row, np

DX, R, D, SOLIDUS, SHIFT = 0.05, 0.97, 0.485, 1673.0, 0.3
FLUID, WALL, SOLID = 0, 1, 2  # kernels/kinds.h


def lattice(dim):
    """Particle centres of a 3 m wide (3 x 3 m in 3D), 1 m deep block whose
    top face is up = 0, and one wall layer below it; 3 coordinates each, as
    snapshots store them."""
    x = np.arange(-1.5 + 0.5 * DX, 1.5, DX)
    up = np.arange(-1.0 - 0.5 * DX, 0.0, DX)
    axes = (x, x, up) if dim == 3 else (x, up, np.zeros(1))
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    grid = grid.astype(np.float32).astype(float)  # as a float build writes them
    kind = np.where(grid[:, dim - 1] < -1.0, WALL, SOLID).astype(np.int32)
    return grid, kind


def ellipsoid_peak(position, dim):
    """Peak temperature with its solidus isotherm on the half-ellipsoid."""
    across2 = (position[:, :dim - 1] ** 2).sum(axis=1)
    rho = np.sqrt(across2 / R ** 2 + position[:, dim - 1] ** 2 / D ** 2)
    return 293.0 + (SOLIDUS - 293.0) * np.exp(2.0 * (1.0 - rho))


def write(path, dim, time, position, kind, ident, peak):
    with h5py.File(path, "w") as f:
        f.attrs["dim"], f.attrs["dx"], f.attrs["time"] = dim, DX, time
        f["position"], f["kind"], f["id"] = position.astype(np.float32), kind, ident
        f["peak_temperature"] = peak.astype(np.float32)


def droplet(dim):
    """Centres of a molten droplet of radius 0.5 m resting on the surface."""
    x = np.arange(-0.5 + 0.5 * DX, 0.5, DX)
    axes = (x, x, x + 0.5) if dim == 3 else (x, x + 0.5, np.zeros(1))
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    centre = np.array([0.0, 0.0, 0.5]) if dim == 3 else np.array([0.0, 0.5, 0.0])
    return grid[((grid - centre) ** 2).sum(axis=1) < 0.25]


def check(source, work, dim, with_droplet=False):
    """Runs the tool on the dim-D zone (under a molten droplet, read with
    --base-top 0); returns the number of failed checks."""
    os.makedirs(work)
    start, kind = lattice(dim)
    peak = np.where(kind == WALL, 293.0, ellipsoid_peak(start, dim))
    fused = peak >= SOLIDUS
    top = start[:, dim - 1] > -DX
    if with_droplet:
        drop = droplet(dim)
        start = np.concatenate([start, drop])
        kind = np.concatenate([kind, np.full(len(drop), FLUID, dtype=np.int32)])
        peak = np.concatenate([peak, np.full(len(drop), 2500.0)])
        fused = np.concatenate([fused, np.zeros(len(drop), dtype=bool)])
        top = np.concatenate([top, np.zeros(len(drop), dtype=bool)])
    ident = np.arange(len(start), dtype=np.uint32)
    moved = start.copy()
    moved[fused & top, 0] += SHIFT
    moved = moved.astype(np.float32).astype(float)
    order = np.random.default_rng(1).permutation(len(start))  # the sort reorders particles
    write(os.path.join(work, "snap_000000.h5"), dim, 0.0, start, kind, ident, np.full(len(start), 293.0))
    write(os.path.join(work, "snap_000001.h5"), dim, 1.0, moved[order], kind[order], ident[order], peak[order])

    got = last_csv_row(source, "fusion_zone", work, *(["--base-top", "0"] if with_droplet else []))

    def across(p):
        return np.sqrt((p[:, :dim - 1] ** 2).sum(axis=1))

    nearest_column = DX / np.sqrt(2.0) if dim == 3 else 0.5 * DX
    expected = {
        "fused_particles": fused.sum(),
        "radius_initial_m": across(start)[fused].max() + 0.5 * DX,
        "depth_initial_m": -start[fused, dim - 1].min() + 0.5 * DX,
        "radius_final_m": across(moved)[fused].max() + 0.5 * DX,
        "radius_isotherm_m": R * np.sqrt(1.0 - (0.5 * DX / D) ** 2),
        "depth_isotherm_m": D * np.sqrt(1.0 - (nearest_column / R) ** 2),
    }
    tolerance = {"radius_isotherm_m": (0.25 if dim == 3 else 0.5) * DX, "depth_isotherm_m": 0.25 * DX}
    # the CSV has 6 digits
    return check_readings(f"{dim}D{' under a droplet' if with_droplet else ''}", got, {name: (value, tolerance.get(name, 1e-5 * max(1.0, abs(value))))
                                           for name, value in expected.items()})


def main():
    source, work = sys.argv[1:3]
    shutil.rmtree(work, ignore_errors=True)
    failed = sum(check(source, os.path.join(work, f"{dim}d"), dim) for dim in (3, 2))
    failed += check(source, os.path.join(work, "3d_droplet"), 3, with_droplet=True)
    print(f"{18 - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
