#!/usr/bin/env python3
"""Write the parameter studies of Russell 2018 §5.1.1.1 from the base track.

    tools/track_variants.py [--cases cases/am]

From cases/am/track_2d_150W.yaml (150 W, r_l 27 um, grains of 25 um) it writes
cases/am/track_2d_<variant>.yaml, each changing one thing:
  laser power     50W, 100W, 200W                    (Table 5.3)
  powder radius   r15um, r30um, mixed_15_30um         (one layer of 2 r_p; mixed:
                  15 and 30 um grains in equal numbers, settled from seed 1)
  beam width      w27um, w81um (2 sigma widths; r_l = 13.5 and 40.5 um)
Run it again after changing the base case; ctest checks every case file.
"""
import argparse
import os
import re

BED = re.compile(r"  - \{shape: powder_bed.*?temperature: 293\}\n", re.S)


def bed(spec, top):
    return (f"  - {{shape: powder_bed, kind: solid, material: steel, min: [-0.6e-3, 0], max: [0.6e-3, {top}],\n"
            f"     {spec}, temperature: 293}}\n")


def variants():
    for power in (50, 100, 200):
        yield f"{power}W", f"laser power {power} W", [(r"  power: 150\n", f"  power: {power}\n")]
    for radius in (15, 30):
        spec = f"distribution: regular, grain_radius: {radius}.0e-6"
        yield f"r{radius}um", f"powder radius {radius} um", [(BED, bed(spec, f"{2 * radius}.0e-6"))]
    spec = "distribution: mixed, grain_radius: 30.0e-6, small_radius: 15.0e-6, small_fraction: 0.5, seed: 1"
    yield "mixed_15_30um", "mixed powder of 15 and 30 um radius", [(BED, bed(spec, "60.0e-6"))]
    for width in (27, 81):
        radius = width / 2
        yield f"w{width}um", f"beam 2 sigma width {width} um (r_l = {radius} um)", [
            (r"  radius: 27.0e-6\n", f"  radius: {radius}e-6\n")]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cases", default=os.path.normpath(os.path.join(os.path.dirname(__file__), "..", "cases", "am")))
    args = parser.parse_args()
    with open(os.path.join(args.cases, "track_2d_150W.yaml")) as f:
        base = f.read()
    for name, change, edits in variants():
        text = base
        for pattern, replacement in edits:
            text, count = re.subn(pattern, lambda _: replacement, text)
            if count != 1:
                raise SystemExit(f"{name}: '{pattern}' matched {count} times in the base case")
        header = (f"# Written by tools/track_variants.py from track_2d_150W.yaml: {change}\n"
                  f"# (Russell 2018 §5.1.1.1); the rest as the base case below.\n")
        path = os.path.join(args.cases, f"track_2d_{name}.yaml")
        with open(path, "w") as f:
            f.write(header + text)
        print(path)


if __name__ == "__main__":
    main()
