#!/usr/bin/env python3
"""tools/bed_metrics.py on three snapshots of a made-up bed with known answers,
in 2D and in 3D (dx = 1 um, so the tool's um are spacings).

On the lattice of spacing dx: side walls outside 0 <= x (and y) <= 20 dx
and below up = 0, three layers each; a substrate of fixed solid from up =
0.5 to 1.5 dx (its top at 2 dx); three grains of 3 particles a side resting
on it at x = 3..5, 14..16 and 9..11 dx (y = 8..10, 8..10 and 9..11 dx); a
fluid block at x (and y) = 8..12 dx, up = 8.5..10.5 dx, above grain 2; and
one lone fluid particle at x = 18.7 dx, up = 10.5 dx (1.7 dx from the
wall's inner face, so it touches no solid), moving at 7 m/s along x in the
last snapshot. Between the first and the last snapshot grain 0 rises by 3
dx, grain 1 slides by 0.5 dx, grain 2 rises by 6 dx and the block falls
onto the substrate (up = 2.5..4.5 dx); in the middle snapshot the grains
have gone half way and the block is where it started, 1 dx above grain 2,
the only time the fluid touches a grain. Expected: 2 of 3 grains moved and
rose, one of them (grain 0) never touched by the fluid, displacements
median 3 and largest 6 dx; the fastest fluid 7 m/s, one above 5; the
wetted width 4 dx along each horizontal axis, no grain touched; one fluid
particle by the walls, 8.5 dx above the substrate; the lowest fluid 0.5 dx
above it; the fluid's mean x (10 n + 18.7) / (n + 1) from the n block
particles at mean 10 dx and the lone one; one lone particle; under the
droplet of n + 1 particles (radius sqrt((n + 1) / pi) dx in 2D, (3 (n + 1)
/ (4 pi))^(1/3) dx in 3D, about its mean x and y), from the substrate's
top to the bed's top at 5 dx, grain 2's 3^d particles at first (its
farthest 1.5 dx from the axis, within either radius), none at the last. A
fast wall particle must not count. The same bed again with a gas phase
(material 1, fluid particles) in a layer above it and one gas particle by
each grain, moving at 9 m/s in the last snapshot: with --gas 1 the readings
must be the bed's without gas.
Skipped (exit 77) where numpy or h5py is missing.

usage: test_bed_metrics.py SOURCE_DIR WORK_DIR
"""
import os
import shutil
import sys

from tool_checks import check_readings, h5py, last_csv_row, np

DX = 1e-6
FLUID, WALL, SOLID, GRAIN = 0, 1, 2, 3  # kernels/kinds.h
LONE = (18.7, 10.5)                     # x and up of the lone fluid particle, dx


def lattice(dim, lo, hi, up_lo, up_hi):
    """Centres (in dx) of the lattice points with horizontal coordinates in
    [lo, hi] and up in [up_lo, up_hi], 3 coordinates each."""
    across = np.arange(lo, hi + 0.01)
    axes = (across, across, np.arange(up_lo, up_hi + 0.01)) if dim == 3 else \
        (across, np.arange(up_lo, up_hi + 0.01), np.zeros(1))
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)


def scene(dim, stage):
    """Positions (m), kinds and grain indices of the bed; `stage`: how far
    the grains have gone (0 at the first snapshot, 1 at the last), the
    block fallen at 1 only."""
    up = dim - 1
    box = lattice(dim, -2.5, 22.5, -2.5, 14.5)
    outside = (box[:, :dim - 1] < 0).any(axis=1) | (box[:, :dim - 1] > 20).any(axis=1) | (box[:, up] < 0)
    substrate = ~outside & (box[:, up] < 2)
    parts = [(box[outside], WALL, -1), (box[substrate], SOLID, -1)]
    for g, (x0, shift) in enumerate(((3.0, (0.0, 3.0)), (14.0, (0.5, 0.0)), (9.0, (0.0, 6.0)))):
        grain = lattice(dim, 0, 2, 2.5, 4.5)
        grain[:, 0] += x0
        grain[:, 1:dim - 1] += 9.0 if g == 2 else 8.0
        grain[:, 0] += stage * shift[0]
        grain[:, up] += stage * shift[1]
        parts.append((grain, GRAIN, g))
    block = lattice(dim, 8, 12, 2.5, 4.5) if stage == 1 else lattice(dim, 8, 12, 8.5, 10.5)
    lone = np.zeros((1, 3))
    lone[0, 0], lone[0, 1:dim - 1], lone[0, up] = LONE[0], 10.0, LONE[1]
    parts += [(block, FLUID, -1), (lone, FLUID, -1)]
    position = np.concatenate([p for p, _, _ in parts]) * DX
    kind = np.concatenate([np.full(len(p), k, dtype=np.int32) for p, k, _ in parts])
    grain = np.concatenate([np.full(len(p), g, dtype=np.int32) for p, _, g in parts])
    return position, kind, grain, len(block)


def with_gas(dim, position, kind, grain):
    """The scene with a gas phase added: a layer at up = 12.5..13.5 dx and a
    particle 3 dx above each grain's centre; returns the arrays and the
    materials (0, the gas 1)."""
    up = dim - 1
    layer = lattice(dim, 0, 20, 12.5, 13.5) * DX
    by_grains = np.array([position[grain == g].mean(axis=0) for g in range(3)])
    by_grains[:, up] += 3.0 * DX
    gas = np.concatenate([layer, by_grains])
    material = np.concatenate([np.zeros(len(kind), dtype=np.int32), np.ones(len(gas), dtype=np.int32)])
    return (np.concatenate([position, gas]), np.concatenate([kind, np.full(len(gas), FLUID, dtype=np.int32)]),
            np.concatenate([grain, np.full(len(gas), -1, dtype=np.int32)]), material)


def check(source, work, dim, gas):
    """Runs the tool on the three snapshots (with a gas phase that --gas
    leaves out if `gas`); returns the number of failed checks."""
    folder = os.path.join(work, f"{dim}d{'_gas' if gas else ''}")
    os.makedirs(folder)
    for index, stage in enumerate((0.0, 0.5, 1.0)):
        position, kind, grain, n_block = scene(dim, stage)
        material = np.zeros(len(kind), dtype=np.int32)
        if gas:
            position, kind, grain, material = with_gas(dim, position, kind, grain)
        velocity = np.zeros_like(position)
        if stage == 1:
            velocity[np.flatnonzero(material == 0)[-1], 0] = 7.0  # the lone fluid particle
            velocity[np.flatnonzero(kind == WALL)[0], 0] = 70.0  # walls do not count
            velocity[material == 1, 0] = 9.0                   # nor does the gas
        with h5py.File(os.path.join(folder, f"snap_{index:06d}.h5"), "w") as f:
            f.attrs["dim"], f.attrs["dx"], f.attrs["time"], f.attrs["step"] = dim, DX, 1e-6 * index, index
            f["position"], f["kind"], f["grain"] = position.astype(np.float32), kind, grain
            f["velocity"], f["mass"] = velocity.astype(np.float32), np.ones(len(kind), dtype=np.float32)
            f["material"] = material
    got = last_csv_row(source, "bed_metrics", folder, *(["--gas", "1"] if gas else []))
    mean_x = (10.0 * n_block + LONE[0]) / (n_block + 1)
    drop = n_block + 1
    radius = np.sqrt(drop / np.pi) if dim == 2 else (3.0 * drop / (4.0 * np.pi)) ** (1.0 / 3.0)
    column = (2.0 * radius if dim == 2 else np.pi * radius ** 2) * (5.0 - 2.0)
    expected = {"grains": (3, 0), "grains_moved": (2, 0), "grains_rose": (2, 0), "grains_rose_dry": (1, 0),
                "displacement_median_um": (3.0, 1e-3), "displacement_max_um": (6.0, 1e-3),
                "fastest_m_s": (7.0, 1e-6), "fast_particles": (1, 0), "wetted_width_x_um": (4.0, 1e-3),
                "grains_touched": (0, 0), "on_walls": (1, 0), "wall_climb_um": (LONE[1] - 2.0, 1e-3),
                "depth_um": (0.5, 1e-3), "fluid_mean_x_start_um": (mean_x, 1e-3),
                "fluid_mean_x_end_um": (mean_x, 1e-3), "lone": (1, 0),
                "packing_under_drop_start": (3 ** dim / column, 1e-4), "packing_under_drop_end": (0.0, 0)}
    if dim == 3:
        expected["wetted_width_y_um"] = (4.0, 1e-3)
    return check_readings(f"{dim}D with gas:" if gas else f"{dim}D:", got, expected), len(expected)


def main():
    source, work = sys.argv[1:3]
    shutil.rmtree(work, ignore_errors=True)
    results = [check(source, work, dim, gas) for dim in (2, 3) for gas in (False, True)]
    failed, total = sum(f for f, _ in results), sum(n for _, n in results)
    print(f"{total - failed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
