#!/usr/bin/env python3
"""The benchmark of BENCHMARKS.md in one command (issue 8):

  - throughput: `amsph bench throughput` on the fluid dam break
    (cases/validation/dambreak_{2d,3d}.yaml), the additive-manufacturing
    scene (cases/bench/am_dambreak_{2d,3d}.yaml) and that scene on a powder bed
    of mobile grains (cases/bench/am_grains_{2d,3d}.yaml) on every backend,
    from 1e4 to 1e6 particles (--max-particles caps them): particle-steps/s, ms per module, device bytes per particle,
    and the least-squares exponent of time per step against particles;
  - speed against error: tools/convergence.py on every case with a known
    answer at three resolutions: error, wall time, observed order.

Writes OUT/throughput.csv, OUT/convergence.csv, OUT/throughput.png (throughput
and time per step against particles), OUT/error_vs_wall.png and OUT/tables.md
(the Markdown tables for BENCHMARKS.md, also printed), from the repository root:

    tools/bench.py --out bench-out            # the full sweep (estimated over an hour on 2 cores)
    tools/bench.py --out bench-out --quick    # a regression check, under two minutes
    tools/bench.py --out bench-out --max-particles 3e5   # the full sweep without the 1e6 rows

The threads are the environment's (OMP_NUM_THREADS; pocl: POCL_MAX_PTHREAD_COUNT).
Numbers are measurements, never assertions; the load average before and after
goes into the tables, as other work on the machine slows every figure.
Needs numpy, h5py and matplotlib (Debian: python3-numpy python3-h5py python3-matplotlib)."""
import argparse, csv, datetime, io, math, os, platform, re, subprocess, sys, time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import convergence  # noqa: E402

SCENES = [("fluid", "cases/validation/dambreak_2d.yaml"), ("fluid", "cases/validation/dambreak_3d.yaml"),
          ("am", "cases/bench/am_dambreak_2d.yaml"), ("am", "cases/bench/am_dambreak_3d.yaml"),
          ("grains", "cases/bench/am_grains_2d.yaml"), ("grains", "cases/bench/am_grains_3d.yaml")]
TITLES = {"fluid": "fluid dam break", "am": "AM dam break (every module but the grains)",
          "grains": "AM dam break on a bed of mobile grains (every module)"}
STYLES = {"fluid": "o-", "am": "s--", "grains": "^:"}
# Spacings of the convergence sweeps (coarsest first is not required).
FULL_SWEEPS = {
    "poiseuille": [1e-4, 5e-5, 2.5e-5],
    "couette": [1e-4, 5e-5, 2.5e-5],
    "hydrostatic": [0.0667, 0.05, 0.025],
    "dambreak": [0.0146, 0.0073, 0.00487],
    "conduction": [0.05, 0.025, 0.0125],
    "interface": [0.04, 0.02, 0.01],
    "stefan": [0.04, 0.02, 0.01],
    "young_laplace": [0.1, 0.05, 0.025],
    # Russell's Tests 1, 3 and 4 stop at dx = 0.05: at 0.025 they took 3943, 4776 and 912 s
    # (BENCHMARKS.md, issue 5's section; `tools/convergence.py expansion_cycle 0.1 0.05 0.025`)
    "expansion_cycle": [0.1, 0.0707, 0.05],
    "expansion_column": [0.1, 0.0707, 0.05],
    "sinking": [0.1, 0.0707, 0.05],
}
QUICK_SWEEPS = {"poiseuille": [1e-4, 7.07e-5, 5e-5], "conduction": [0.0667, 0.05, 0.04]}
FULL_COUNTS, QUICK_COUNTS = [1e4, 3e4, 1e5, 3e5, 1e6], [1e4, 2e4]
PHASES = ["sort", "density", "forces", "surface", "thermal", "laser", "grains", "integration", "guards"]


def machine():
    model = "unknown CPU"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    system = platform.platform()
    if os.path.exists("/etc/os-release"):
        with open("/etc/os-release") as f:
            system = re.search(r'PRETTY_NAME="([^"]*)"', f.read()).group(1)
    return f"{model}, {os.cpu_count()} cores, {system}"


def commit():
    """The source's commit, marked when the work tree differs from it."""
    git = lambda *a: subprocess.run(["git", "-C", ROOT, *a], capture_output=True, text=True).stdout.strip()
    head = git("rev-parse", "--short", "HEAD") or "unknown"
    return head + (" (modified)" if git("status", "--porcelain", "--untracked-files=no") else "")


def backends(amsph):
    listed = subprocess.run([amsph, "devices"], capture_output=True, text=True).stdout
    return ["openmp"] + (["opencl"] if "opencl --device" in listed else [])


def throughput(amsph, out, names, counts, steps, warmup):
    rows = []
    for physics, case in SCENES:
        for backend in names:
            path = os.path.join(out, f"throughput_{physics}_{os.path.basename(case)[:-5]}_{backend}.csv")
            command = [amsph, "bench", "throughput", case, "--backend", backend, "--steps", str(steps),
                       "--warmup", str(warmup), "--csv", path]
            for n in counts:
                command += ["--particles", f"{n:g}"]
            print("+", " ".join(command), file=sys.stderr, flush=True)
            subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
            with open(path) as f:
                for row in csv.DictReader(f):
                    row["physics"], row["backend_name"] = physics, backend
                    rows.append(row)
    return rows


def sweeps(amsph, plan, backend):
    rows = []
    for case, dxs in plan.items():
        print(f"+ tools/convergence.py {case} {' '.join(f'{d:g}' for d in dxs)} --backend {backend}",
              file=sys.stderr, flush=True)
        for r in convergence.sweep(case, dxs, amsph, backend):
            rows.append(dict(r, case=case, backend=backend))
    return rows


def write_csv(path, rows, fields):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)


def series(rows):
    """Throughput rows grouped by (physics, dim, backend), by particles."""
    groups = {}
    for r in rows:
        groups.setdefault((r["physics"], int(r["dim"]), r["backend_name"]), []).append(r)
    for g in groups.values():
        g.sort(key=lambda r: int(r["particles"]))
    return groups


def exponent(group):
    n = np.log([float(r["particles"]) for r in group])
    t = np.log([float(r["ms_per_step"]) for r in group])
    return np.polyfit(n, t, 1)[0] if len(group) > 1 else float("nan")


def tables(thr, conv, header):
    out = io.StringIO()
    out.write(header + "\n\n")
    for (physics, dim, backend), group in series(thr).items():
        out.write(f"{TITLES[physics]}, {dim}D, {group[0]['backend']} ({group[0]['build']}), "
                  f"{group[0]['steps']} timed steps; module columns in ms per step:\n\n")
        out.write("| particles | ms/step | particle-steps/s | device B/particle | " +
                  " | ".join(PHASES) + " | other |\n|" + "---|" * (len(PHASES) + 5) + "\n")
        for r in group:
            cells = [r[f"ms_{p}"] for p in PHASES]
            known = sum(float(c) for c in cells if c)
            cells = [f"{float(c):.3g}" if c else "-" for c in cells]
            other = float(r["timed_ms_per_step"]) - known
            out.write(f"| {r['particles']} | {float(r['ms_per_step']):.4g} | {float(r['particle_steps_per_s']):.3g} | "
                      f"{float(r['device_bytes_per_particle']):.0f} | " + " | ".join(cells) + f" | {other:.3g} |\n")
        out.write("\n")
    out.write("Cost growth (least squares of log time per step against log particles):\n\n"
              "| scene | dim | backend | particles | exponent |\n|---|---|---|---|---|\n")
    for (physics, dim, backend), group in series(thr).items():
        out.write(f"| {physics} | {dim}D | {backend} | {group[0]['particles']}-{group[-1]['particles']} | "
                  f"{exponent(group):.2f} |\n")
    if conv:
        out.write("\nSpeed against error (wall time includes scene setup and snapshot output):\n\n"
                  "| case | backend | dx (m) | particles | steps | wall (s) | particle-steps/s | error | order | other error |\n"
                  "|---|---|---|---|---|---|---|---|---|---|\n")
        for r in conv:
            order = "" if r["order"] is None else f"{r['order']:.2f}"
            out.write(f"| {r['case']} | {r['backend']} | {r['dx']:g} | {r['particles']} | {r['steps']} | "
                      f"{r['wall']:.1f} | {r['particles'] * r['steps'] / r['wall']:.3g} | {r['error']:.3e} | {order} | "
                      f"{r['extra'] or ''} |\n")
    return out.getvalue()


def plot(thr, conv, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    for (physics, dim, backend), group in series(thr).items():
        n = [int(r["particles"]) for r in group]
        label = f"{physics} {dim}D {backend}"
        style = STYLES[physics]  # a line style per scene: the colour cycle repeats after ten series
        left.plot(n, [float(r["particle_steps_per_s"]) for r in group], style, label=label)
        right.plot(n, [float(r["ms_per_step"]) for r in group], style, label=f"{label}: N^{exponent(group):.2f}")
    left.set(xscale="log", yscale="log", xlabel="particles", ylabel="particle-steps / s", title="Throughput")
    right.set(xscale="log", yscale="log", xlabel="particles", ylabel="ms per step", title="Cost growth")
    for ax in (left, right):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "throughput.png"), dpi=120)
    if conv:
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        for case in dict.fromkeys(r["case"] for r in conv):
            for backend in dict.fromkeys(r["backend"] for r in conv):
                rs = [r for r in conv if r["case"] == case and r["backend"] == backend]
                ax.plot([r["wall"] for r in rs], [r["error"] for r in rs], "o-", label=f"{case} ({backend})")
        ax.set(xscale="log", yscale="log", xlabel="wall time (s)", ylabel="error (relative)",
               title="Speed against error")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "error_vs_wall.png"), dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--amsph", default="build/amsph")
    ap.add_argument("--out", default="bench-out")
    ap.add_argument("--quick", action="store_true", help="small counts and sweeps: under two minutes")
    ap.add_argument("--backend", action="append", choices=["openmp", "opencl"],
                    help="throughput backends (repeatable; default: openmp and opencl where present)")
    ap.add_argument("--particles", type=float, action="append", help="throughput counts (repeatable)")
    ap.add_argument("--max-particles", type=float, help="leave out the throughput counts above this")
    ap.add_argument("--steps", type=int, help="timed steps per count (default 10, quick 3)")
    ap.add_argument("--convergence-backend", default="openmp", choices=["openmp", "opencl"])
    ap.add_argument("--no-convergence", action="store_true")
    args = ap.parse_args()
    amsph, out = os.path.abspath(args.amsph), os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    os.chdir(ROOT)  # the case paths are relative to the repository
    start, load = time.monotonic(), os.getloadavg()[0]
    names = args.backend or backends(amsph)
    counts = args.particles or (QUICK_COUNTS if args.quick else FULL_COUNTS)
    counts = [n for n in counts if args.max_particles is None or n <= args.max_particles]
    steps = args.steps or (3 if args.quick else 10)
    thr = throughput(amsph, out, names, counts, steps, 1 if args.quick else 3)
    conv = [] if args.no_convergence else sweeps(amsph, QUICK_SWEEPS if args.quick else FULL_SWEEPS,
                                                 args.convergence_backend)
    header = (f"Machine: {machine()}; commit {commit()}; {thr[0]['build']}; OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}, "
              f"POCL_MAX_PTHREAD_COUNT={os.environ.get('POCL_MAX_PTHREAD_COUNT', 'unset')}; "
              f"{datetime.date.today()}; load average {load:.2f} at the start, {os.getloadavg()[0]:.2f} at the end; "
              f"{time.monotonic() - start:.0f} s in all")
    write_csv(os.path.join(out, "throughput.csv"), thr, ["physics", "backend_name"] + list(thr[0].keys())[:-2])
    write_csv(os.path.join(out, "convergence.csv"), conv,
              ["case", "backend", "dx", "particles", "steps", "wall", "error", "order", "extra"])
    text = tables(thr, conv, header)
    with open(os.path.join(out, "tables.md"), "w") as f:
        f.write(text)
    plot(thr, conv, out)
    print(text)


if __name__ == "__main__":
    main()
