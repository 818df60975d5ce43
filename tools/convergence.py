#!/usr/bin/env python3
"""Convergence study of a validation case: runs amsph at several particle
spacings and prints a Markdown table of particles, steps, wall time,
particle-steps per second, error against the known answer and observed order.

    tools/convergence.py CASE DX [DX ...] [--amsph build/amsph] [--backend openmp]

CASE is one of: poiseuille, couette (L2 velocity error relative to the peak
speed, largest over the output times; Morris, Fox & Zhu 1997), hydrostatic
(largest pressure error below the top tenth at the end, relative to rho g H)
and dambreak, dambreak_3d (largest drift of the fluid volume sum m/rho);
conduction, interface (largest temperature error over the output times,
relative to the 1 K step; Fourier series and the erf solution) and stefan
(largest relative error of the melting front against Neumann's solution);
young_laplace (the mean pressure inside r < R/2 at the end against sigma/R);
expansion_cycle, expansion_column, sinking (Russell's Tests 1, 3 and 4,
measured by `build/tests/test_isothermal sweep`: Voronoi volumes against
m / rho0(T) of the interior, and of the band 0.8-0.9 R as the extra column;
of the lower fluid, and of the upper one as the extra column; the
particle-scale pressure noise over rho g H with delta-SPH);
laser_slab (largest relative error of the absorbed power density against
Beer-Lambert, alpha I0 exp(-2 r^2/r_l^2) exp(-alpha z), within 2 r_l of the
axis and below the outer bin layers, with bins of dx and the beam moved half
a spacing onto a particle column as in tests/test_laser.c; the extra column
is the error of the enthalpy gained in series.csv against
P (1 - exp(-alpha L)) t).
The 1D strips (interface, stefan) are resized to 12 dx across, so that the
periodic axis spans three kernel supports at every dx.
Needs numpy and h5py (Debian: python3-numpy python3-h5py)."""
import argparse, csv, glob, math, os, re, subprocess, tempfile, time

import h5py
import numpy as np

L, NU = 1e-3, 1e-6


def poiseuille(y, t, F=2e-4):
    u = F / (2 * NU) * y * (L - y)
    for n in range(200):
        k = 2 * n + 1
        u -= 4 * F * L * L / (NU * math.pi**3 * k**3) * np.sin(k * math.pi * y / L) * \
            math.exp(-k * k * math.pi**2 * NU * t / L**2)
    return u


def couette(y, t, V=2.5e-5):
    u = V * y / L
    for n in range(1, 400):
        u += 2 * V * (-1)**n / (n * math.pi) * np.sin(n * math.pi * y / L) * \
            math.exp(-n * n * math.pi**2 * NU * t / L**2)
    return u


def snapshots(outdir):
    for name in sorted(glob.glob(os.path.join(outdir, "snap_*.h5"))):
        with h5py.File(name) as f:
            yield f.attrs["time"], {k: f[k][:] for k in f.keys()}


def channel_error(outdir, exact, scale):
    worst = 0.0
    for t, s in snapshots(outdir):
        if t == 0:  # the series is exact there only in the limit of infinitely many terms
            continue
        fluid = s["kind"] == 0
        e = s["velocity"][fluid, 0] - exact(s["position"][fluid, 1], t)
        worst = max(worst, math.sqrt(np.mean(e * e)) / scale)
    return worst


def volume_drift(outdir):
    volumes = []
    for _, s in snapshots(outdir):
        fluid = s["kind"] == 0
        volumes.append(np.sum(s["mass"][fluid] / s["density"][fluid]))
    return max(abs(v / volumes[0] - 1) for v in volumes)


def hydrostatic_error(outdir, g=9.81, H=1.0, rho0=1000.0):
    """Pressure error at the end, below the top tenth, relative to rho g H."""
    *_, (t, s) = snapshots(outdir)
    below = (s["kind"] == 0) & (s["position"][:, 1] < 0.9 * H)
    exact = rho0 * g * (H - s["position"][below, 1])
    return np.max(np.abs(s["pressure"][below] - exact)) / (rho0 * g * H)


def droplet_pressure_error(outdir, expected, radius=1.0):
    """Young-Laplace: the mean pressure inside r < R/2 at the end against (d - 1) sigma / R."""
    *_, (t, s) = snapshots(outdir)
    inside = np.linalg.norm(s["position"], axis=1) < 0.5 * radius
    return abs(np.mean(s["pressure"][inside]) / expected - 1)


def temperature_error(outdir, exact):
    worst = 0.0
    for t, s in snapshots(outdir):
        if t == 0:
            continue
        solid = s["kind"] != 1
        x = s["position"][solid]
        worst = max(worst, np.max(np.abs(s["temperature"][solid] - exact(x[:, 0], x[:, 1], t))))
    return worst


def square(x, y, t):
    T = np.ones_like(x)
    for m in range(1, 200, 2):
        for n in range(1, 200, 2):
            T -= 16 / (math.pi**2 * m * n) * np.sin(m * math.pi * x) * np.sin(n * math.pi * y) * \
                math.exp(-math.pi**2 * (m * m + n * n) * t)
    return T


def interface(x, y, t):
    erf = np.vectorize(math.erf)
    contact = 1 / (1 + math.sqrt(10))
    return np.where(x < 0, contact + (1 - contact) * erf(-x / (2 * math.sqrt(t))),
                    contact * (1 - erf(x / (2 * math.sqrt(10 * t)))))


def stefan_error(outdir, stefan=1.0):
    lo, hi = 1e-3, 3.0
    for _ in range(100):
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if mid * math.exp(mid * mid) * math.erf(mid) > stefan / math.sqrt(math.pi) else (mid, hi)
    lam, worst = (lo + hi) / 2, 0.0
    for t, s in snapshots(outdir):
        if t == 0:
            continue
        solid = s["kind"] != 1
        x, frac = s["position"][solid, 0], s["liquid_fraction"][solid]
        columns = np.unique(np.round(x, 12))
        mean = np.array([frac[np.abs(x - c) < 1e-12].mean() for c in columns])
        k = np.argmax(mean < 0.5)
        front = columns[k - 1] + (mean[k - 1] - 0.5) / (mean[k - 1] - mean[k]) * (columns[k] - columns[k - 1])
        exact = 2 * lam * math.sqrt(t)
        worst = max(worst, abs(front - exact) / exact)
    return worst


SLAB = dict(power=100.0, radius=1e-4, alpha=2000.0, depth=5e-4, top=5e-4, centre=5e-4, on=1e-3)


def laser_slab_profile(outdir):
    """Largest relative error of laser_power against Beer-Lambert (first snapshot)."""
    with h5py.File(os.path.join(outdir, "snap_000000.h5")) as f:
        dx, x, power = f.attrs["dx"], f["position"][:], f["laser_power"][:]
    axis = SLAB["centre"] - dx / 2
    r2 = (x[:, 0] - axis) ** 2 + (x[:, 1] - axis) ** 2
    z = SLAB["top"] - x[:, 2]
    inside = (r2 <= (2 * SLAB["radius"]) ** 2) & (z >= dx) & (z <= SLAB["depth"] - dx)
    peak = 2 * SLAB["power"] / (math.pi * SLAB["radius"] ** 2)
    exact = SLAB["alpha"] * peak * np.exp(-2 * r2[inside] / SLAB["radius"] ** 2) * np.exp(-SLAB["alpha"] * z[inside])
    return np.max(np.abs(power[inside] / exact - 1))


def laser_slab_energy(outdir):
    """Relative error of the enthalpy gained over the run against P (1 - e^-alpha L) t."""
    with open(os.path.join(outdir, "series.csv")) as f:
        rows = list(csv.DictReader(f))
    gained = float(rows[-1]["enthalpy"]) - float(rows[0]["enthalpy"])
    exact = SLAB["power"] * (1 - math.exp(-SLAB["alpha"] * SLAB["depth"])) * SLAB["on"]
    return f"{gained / exact - 1:+.1e}"


def laser_slab_text(text, dx):
    """Bins of dx and the beam half a spacing across, onto a particle column."""
    start = SLAB["centre"] - dx / 2
    return re.sub(r"^  start: .*$", f"  start: [{start:g}, {start:g}, {SLAB['top']:g}]", text, flags=re.M)


CASES = {
    "poiseuille": ("cases/validation/poiseuille_2d.yaml", lambda d: channel_error(d, poiseuille, 2.5e-5)),
    "couette": ("cases/validation/couette_2d.yaml", lambda d: channel_error(d, couette, 2.5e-5)),
    "dambreak": ("cases/validation/dambreak_2d.yaml", volume_drift),
    "hydrostatic": ("cases/validation/hydrostatic_2d.yaml", hydrostatic_error),
    "dambreak_3d": ("cases/validation/dambreak_3d.yaml", volume_drift),
    "conduction": ("cases/validation/conduction_2d.yaml", lambda d: temperature_error(d, square)),
    "interface": ("cases/validation/conduction_interface_1d.yaml", lambda d: temperature_error(d, interface)),
    "stefan": ("cases/validation/stefan_1d.yaml", stefan_error),
    "laser_slab": ("cases/validation/laser_slab_3d.yaml", laser_slab_profile),
    "young_laplace": ("cases/validation/young_laplace_2d.yaml", lambda d: droplet_pressure_error(d, 10.0)),
}
EXTRA = {"laser_slab": ("energy error", laser_slab_energy)}
# Cases measured by tests/test_isothermal's sweep (Voronoi cells in C):
# its case name, and the name of its second error (the extra column).
ISOTHERMAL = {"expansion_cycle": ("cycle", "band 0.8-0.9 R"), "expansion_column": ("column", "upper fluid"),
              "sinking": ("sinking", None)}
EDIT = {"laser_slab": laser_slab_text}
STRIPS = ("interface", "stefan")


def run(amsph, case_text, dx, backend, work, strip, edit):
    path = os.path.join(work, f"case_{dx}.yaml")
    text = re.sub(r"^dx: .*$", f"dx: {dx}", case_text, flags=re.M)
    if strip:
        text = text.replace(", 0.1]", f", {12 * dx:g}]")
    if edit:
        text = edit(text, dx)
    with open(path, "w") as f:
        f.write(text)
    outdir = os.path.join(work, f"out_{dx}")
    start = time.monotonic()
    proc = subprocess.run([amsph, "run", path, "-o", outdir, "--backend", backend],
                          capture_output=True, text=True)
    wall = time.monotonic() - start
    if proc.returncode != 0:
        raise SystemExit(f"dx {dx}: amsph failed:\n{proc.stderr}")
    particles = int(re.search(r"(\d+) particles", proc.stderr).group(1))
    steps = int(re.search(r"done, (\d+) steps", proc.stderr).group(1))
    return outdir, particles, steps, wall


def isothermal_run(amsph, case, dx, backend):
    """One run of tests/test_isothermal's sweep (OpenMP only): particles,
    steps, wall, the first error and the second (or None), from its row."""
    if backend != "openmp":
        raise SystemExit(f"{case}: test_isothermal's sweep runs on the openmp backend only")
    binary = os.path.join(os.path.dirname(os.path.abspath(amsph)), "tests", "test_isothermal")
    proc = subprocess.run([binary, "sweep", ISOTHERMAL[case][0], f"{dx:g}"], capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"dx {dx}: {binary} failed:\n{proc.stderr}")
    cells = [c.strip() for c in proc.stdout.splitlines()[2].strip("|").split("|")]
    second = float(cells[8]) if ISOTHERMAL[case][1] else None
    return int(cells[2]), int(cells[3]), float(cells[4]), float(cells[7]), second


def case_runs(case, dxs, amsph, backend):
    """(dx, particles, steps, wall, error, extra) of each run, coarsest first."""
    if case in ISOTHERMAL:
        for dx in sorted(dxs, reverse=True):
            particles, steps, wall, error, second = isothermal_run(amsph, case, dx, backend)
            yield dx, particles, steps, wall, error, None if second is None else f"{second:.3e}"
        return
    case_file, measure = CASES[case]
    with open(case_file) as f:
        text = f.read()
    extra = EXTRA.get(case)
    with tempfile.TemporaryDirectory() as work:
        for dx in sorted(dxs, reverse=True):
            outdir, particles, steps, wall = run(amsph, text, dx, backend, work, case in STRIPS, EDIT.get(case))
            yield dx, particles, steps, wall, measure(outdir), extra[1](outdir) if extra else None


def sweep(case, dxs, amsph="build/amsph", backend="openmp"):
    """Runs CASE at each spacing, coarsest first, and yields one dict per run:
    dx, particles, steps, wall (s), error and the observed order against the
    previous run (None for the first), and the case's extra measure (or None)."""
    previous = None
    for dx, particles, steps, wall, error, extra in case_runs(case, dxs, amsph, backend):
        order = None
        if previous and error > 0 and previous[1] > 0:
            order = math.log(previous[1] / error) / math.log(previous[0] / dx)
        yield {"dx": dx, "particles": particles, "steps": steps, "wall": wall, "error": error, "order": order,
               "extra": extra}
        previous = (dx, error)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", choices=sorted(list(CASES) + list(ISOTHERMAL)))
    ap.add_argument("dx", type=float, nargs="+")
    ap.add_argument("--amsph", default="build/amsph")
    ap.add_argument("--backend", default="openmp", choices=["openmp", "opencl"])
    args = ap.parse_args()
    extra_name = EXTRA[args.case][0] if args.case in EXTRA else ISOTHERMAL.get(args.case, (None, None))[1]
    print(f"| case | backend | dx (m) | particles | steps | wall (s) | particle-steps/s | error | order |"
          + (f" {extra_name} |" if extra_name else ""))
    print(f"|---|---|---|---|---|---|---|---|---|" + ("---|" if extra_name else ""))
    for r in sweep(args.case, args.dx, args.amsph, args.backend):
        order = "" if r["order"] is None else f"{r['order']:.2f}"
        print(f"| {args.case} | {args.backend} | {r['dx']:g} | {r['particles']} | {r['steps']} | {r['wall']:.1f} | "
              f"{r['particles'] * r['steps'] / r['wall']:.3g} | {r['error']:.3e} | {order} |"
              + (f" {r['extra']} |" if extra_name else ""), flush=True)


if __name__ == "__main__":
    main()
