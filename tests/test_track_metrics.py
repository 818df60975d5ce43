#!/usr/bin/env python3
"""tools/track_metrics.py on two snapshots of a made-up 2D track with known
answers (dx = 1 um, so the tool's um are spacings).

A substrate of fixed solid on the lattice x = 0.5..39.5 dx, y = -0.5..-9.5
dx (its surface at y = 0), held wall rows below it (y = -10.5..-12.5 dx),
and at the snapshot of 0.26 ms these peak temperatures (the rest 300 K):
  - along the track, column x = 20.5 dx: 1800 K (past the liquidus) down to
    y = -1.5 dx and 1700 K (past the solidus only) at -2.5 and -3.5 dx;
  - at the ends, within --end-margin 5 dx of the side faces (x = 0.5 and
    39.5 dx): 1700 K at (4.5, -7.5) and (35.5, -8.5) dx;
  - just outside the margin, (6.5, -2.5) dx: 1700 K;
  - a wall particle at y = -11.5 dx: 2000 K (walls never count).
Every melted particle has moved 6 dx up by then: the depth is read from its
initial position. Expected penetration 3.5 dx at the solidus and 1.5 dx at
the liquidus along the track, 8.5 dx at the ends; a tool that counted the
ends would read 8.5, one that counted walls 11.5, one that read the present
positions nothing. Skipped (exit 77) where numpy or h5py is missing.

usage: test_track_metrics.py SOURCE_DIR WORK_DIR
"""
import os
import shutil
import sys

from tool_checks import check_readings, h5py, last_csv_row, np

DX = 1.0e-6


def write(path, time, ids, kind, position, peak):
    n = len(ids)
    with h5py.File(path, "w") as f:
        f.attrs["time"] = time
        f.attrs["dim"] = 2
        f.attrs["dx"] = DX
        f["id"] = ids
        f["kind"] = kind
        f["position"] = position
        f["velocity"] = np.zeros((n, 3))
        f["temperature"] = peak
        f["peak_temperature"] = peak
        f["liquid_fraction"] = np.zeros(n)


def main():
    source, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    xs, ys = np.meshgrid(np.arange(40) + 0.5, -(np.arange(13) + 0.5))
    position = np.zeros((xs.size, 3))
    position[:, 0], position[:, 1] = xs.ravel() * DX, ys.ravel() * DX
    kind = np.where(position[:, 1] < -10 * DX, 1, 2)
    ids = np.arange(xs.size)
    peak = np.full(xs.size, 300.0)

    def at(x, y):
        return int(np.argmin(np.hypot(position[:, 0] - x * DX, position[:, 1] - y * DX)))

    for y, t in ((-0.5, 1800.0), (-1.5, 1800.0), (-2.5, 1700.0), (-3.5, 1700.0)):
        peak[at(20.5, y)] = t
    for x, y in ((4.5, -7.5), (35.5, -8.5), (6.5, -2.5)):
        peak[at(x, y)] = 1700.0
    peak[at(20.5, -11.5)] = 2000.0
    write(os.path.join(work, "snap_000000.h5"), 0.0, ids, kind, position, np.full(xs.size, 300.0))
    moved = position.copy()
    moved[peak > 1000.0, 1] += 6 * DX
    write(os.path.join(work, "snap_000001.h5"), 0.26e-3, ids, kind, moved, peak)
    got = last_csv_row(source, "track_metrics", work, "--end-margin", "5e-6")
    return check_readings("made-up track", got, {"penetration_solidus_um": (3.5, 1e-6),
                                                 "penetration_liquidus_um": (1.5, 1e-6),
                                                 "penetration_ends_um": (8.5, 1e-6)})


if __name__ == "__main__":
    sys.exit(1 if main() else 0)
