#!/usr/bin/env python3
"""tools/fusion_zone.py on snapshots with a known fusion zone. A 3D lattice
(dx = 0.05 m) under a flat surface at z = 0 has a peak temperature whose
solidus isotherm is the half-ellipsoid (r / R)^2 + (z / D)^2 = 1, R = 0.97 m,
D = 0.485 m (between lattice layers); in the second snapshot the fused
particles of the top layer have moved 0.3 m along x. Checked:
  - isotherm: the radius and depth of that ellipsoid in the lattice's top
    layer and nearest columns, R sqrt(1 - (dx / 2D)^2) and
    D sqrt(1 - (dx / sqrt(2) R)^2), to dx / 4 (the lattice's fused extremes
    are 0.02 and 0.015 m off);
  - initial: the lattice's fused extremes plus dx / 2, to the CSV's six
    digits (the moved particles are found by id where they started);
  - final: the moved particles' largest distance from the axis plus dx / 2.
Skipped (exit 77) where numpy or h5py is missing.

usage: test_fusion_zone.py SOURCE_DIR WORK_DIR
"""
import csv
import os
import shutil
import subprocess
import sys

try:
    import h5py
    import numpy as np
except ImportError as e:
    print(f"skipped: {e}")
    sys.exit(77)

DX, R, D, SOLIDUS, SHIFT = 0.05, 0.97, 0.485, 1673.0, 0.3
WALL, SOLID = 1, 2  # kernels/kinds.h


def lattice():
    """Particle centres of a 3 x 3 x 1 m block whose top face is z = 0, and
    one wall layer below it."""
    x = np.arange(-1.5 + 0.5 * DX, 1.5, DX)
    z = np.arange(-1.0 - 0.5 * DX, 0.0, DX)
    grid = np.stack(np.meshgrid(x, x, z, indexing="ij"), axis=-1).reshape(-1, 3)
    grid = grid.astype(np.float32).astype(float)  # as a float build writes them
    kind = np.where(grid[:, 2] < -1.0, WALL, SOLID).astype(np.int32)
    return grid, kind


def ellipsoid_peak(position):
    """Peak temperature with its solidus isotherm on the half-ellipsoid."""
    rho = np.sqrt((position[:, 0] ** 2 + position[:, 1] ** 2) / R ** 2 + position[:, 2] ** 2 / D ** 2)
    return 293.0 + (SOLIDUS - 293.0) * np.exp(2.0 * (1.0 - rho))


def write(path, time, position, kind, ident, peak):
    with h5py.File(path, "w") as f:
        f.attrs["dim"], f.attrs["dx"], f.attrs["time"] = 3, DX, time
        f["position"], f["kind"], f["id"] = position.astype(np.float32), kind, ident
        f["peak_temperature"] = peak.astype(np.float32)


def main():
    source, work = sys.argv[1:3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    start, kind = lattice()
    ident = np.arange(len(start), dtype=np.uint32)
    peak = np.where(kind == WALL, 293.0, ellipsoid_peak(start))
    fused = peak >= SOLIDUS
    top = start[:, 2] > -DX
    moved = start.copy()
    moved[fused & top, 0] += SHIFT
    moved = moved.astype(np.float32).astype(float)
    order = np.random.default_rng(1).permutation(len(start))  # the sort reorders particles
    write(os.path.join(work, "snap_000000.h5"), 0.0, start, kind, ident, np.full(len(start), 293.0))
    write(os.path.join(work, "snap_000001.h5"), 1.0, moved[order], kind[order], ident[order], peak[order])

    table = os.path.join(work, "fusion_zone.csv")
    proc = subprocess.run([sys.executable, os.path.join(source, "tools", "fusion_zone.py"), work, "--csv", table],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"fusion_zone.py failed:\n{proc.stdout}{proc.stderr}")
    with open(table) as f:
        row = list(csv.DictReader(f))[-1]
    got = {k: float(v) for k, v in row.items()}

    across = np.hypot(start[:, 0], start[:, 1])
    expected = {
        "fused_particles": fused.sum(),
        "radius_initial_m": across[fused].max() + 0.5 * DX,
        "depth_initial_m": -start[fused, 2].min() + 0.5 * DX,
        "radius_final_m": np.hypot(moved[fused, 0], moved[fused, 1]).max() + 0.5 * DX,
        "radius_isotherm_m": R * np.sqrt(1.0 - (0.5 * DX / D) ** 2),
        "depth_isotherm_m": D * np.sqrt(1.0 - (DX / np.sqrt(2.0) / R) ** 2),
    }
    tolerance = {"radius_isotherm_m": 0.25 * DX, "depth_isotherm_m": 0.25 * DX}
    failed = 0
    for name, value in expected.items():
        ok = abs(got[name] - value) <= tolerance.get(name, 1e-5 * max(1.0, abs(value)))  # the CSV has 6 digits
        print(f"{'ok' if ok else 'FAILED'}: {name} {got[name]:.6g}, expected {value:.6g}")
        failed += not ok
    print(f"{len(expected) - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
