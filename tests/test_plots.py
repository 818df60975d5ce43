#!/usr/bin/env python3
"""The plotting tools on real output: a 2D and a 3D run, the series and a
snapshot of each (a slab for 3D) drawn to PNG, and the melt-pool analysis of
a short run of the recoil pool plotted by `amsph analyze --plot`. Skipped (exit 77) where numpy,
h5py or matplotlib is missing.

usage: test_plots.py AMSPH SOURCE_DIR WORK_DIR
"""
import os
import shutil
import subprocess
import sys

try:
    import h5py  # noqa: F401
    import matplotlib  # noqa: F401
    import numpy  # noqa: F401
except ImportError as e:
    print(f"skipped: {e}")
    sys.exit(77)

CUBE_3D = """dimension: 3
domain: {min: [0, 0, 0], max: [1, 1, 1]}
dx: 0.1
end_time: 0.2
output_interval: 0.1
gravity: [0, 0, -9.81]
materials:
  - {name: water, density: 1000}
geometry:
  - {shape: box, kind: fluid, material: water, min: [0.2, 0.2, 0.5], max: [0.5, 0.5, 0.8]}
"""


def run(*command):
    proc = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"`{' '.join(map(str, command))}` failed:\n{proc.stdout}{proc.stderr}")


def check_png(path):
    with open(path, "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            sys.exit(f"{path} is not a PNG")


def main():
    amsph, source, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    tools = os.path.join(source, "tools")
    cube = os.path.join(work, "cube.yaml")
    with open(cube, "w") as f:
        f.write(CUBE_3D)
    cases = {"2d": (os.path.join(source, "cases/examples/falling_block_2d.yaml"), []),
             "3d": (cube, ["--slice", "z=0.6"])}
    for name, (case, slab) in cases.items():
        out = os.path.join(work, name)
        run(amsph, "run", case, "-o", out, "--quiet", "--max-steps", "5")
        series_png, snap_png = os.path.join(work, f"{name}_series.png"), os.path.join(work, f"{name}_snap.png")
        run(sys.executable, os.path.join(tools, "plot_series.py"), os.path.join(out, "series.csv"), "-o",
            series_png, "--amsph", amsph)
        run(sys.executable, os.path.join(tools, "plot_snapshot.py"), os.path.join(out, "snap_000001.h5"), "-o",
            snap_png, "--field", "pressure", *slab)
        check_png(series_png)
        check_png(snap_png)
    pool = os.path.join(work, "recoil_pool")
    pool_png = os.path.join(work, "recoil_pool.png")
    run(amsph, "run", os.path.join(source, "cases/am/recoil_pool_2d.yaml"), "-o", pool, "--quiet", "--max-steps", "400")
    proc = subprocess.run([amsph, "analyze", pool, "--plot", pool_png], capture_output=True, text=True,
                          env=dict(os.environ, AMSPH_PYTHON=sys.executable, AMSPH_SOURCE_DIR=source))
    if proc.returncode != 0:
        sys.exit(f"amsph analyze --plot failed:\n{proc.stdout}{proc.stderr}")
    check_png(pool_png)
    print("5 passed, 0 failed")


if __name__ == "__main__":
    main()
