"""Shared by the tests of tools/*.py: numpy and h5py (the test is skipped,
exit 77, where either is missing), a tool's run with --csv and its last row,
and readings checked against known values."""
import csv
import os
import subprocess
import sys

try:
    import h5py  # noqa: F401 (re-exported to the tests)
    import numpy as np  # noqa: F401
except ImportError as e:
    print(f"skipped: {e}")
    sys.exit(77)


def last_csv_row(source, tool, folder, *args):
    """Runs tools/TOOL.py on the output folder with --csv and returns the
    table's last row as floats by column name; exits where the tool fails."""
    table = os.path.join(folder, f"{tool}.csv")
    proc = subprocess.run([sys.executable, os.path.join(source, "tools", f"{tool}.py"), folder, "--csv", table,
                           *args], capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"{tool}.py failed:\n{proc.stdout}{proc.stderr}")
    with open(table) as f:
        return {k: float(v) for k, v in list(csv.DictReader(f))[-1].items()}


def check_readings(label, got, expected):
    """Prints each reading against expected[name] = (value, tolerance);
    returns the number that miss."""
    failed = 0
    for name, (value, tolerance) in expected.items():
        ok = abs(got[name] - value) <= tolerance
        print(f"{'ok' if ok else 'FAILED'}: {label} {name} {got[name]:.6g}, expected {value:.6g}")
        failed += not ok
    return failed
