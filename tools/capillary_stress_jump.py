#!/usr/bin/env python3
"""Laplace jump of a 2D drop from the divergence of the capillary stress.

    tools/capillary_stress_jump.py SNAPSHOT [--surface-h 0.06] [--sigma 10] [--centre 0,0]

Reads a snapshot of a round 2D drop (material 0; young_laplace_gas_2d.yaml's
first snapshot, which has the liquid's colour-gradient normals n_a) and sums,
as kernels/surface.cl would, the force of the capillary stress
T = sigma |n| (c I - n^ n^) over the drop's own pairs (the gas carries none),

    F_a = V_a sum_b V_b (T_a w_b + T_b w_a) . grad_a W_ab,

with the quintic kernel at the surface smoothing length h. It prints the
pressure jump that force holds, sum_a (-F_a . r^_a) / (2 pi r_a), for four
forms (target sigma / R):

  Lafaurie          c = 1 (Lafaurie et al. 1994), w = 1
  Lafaurie / Gamma  c = 1, w = 1 / Gamma (free-surface consistent, as the
                    colour gradient of Russell 2018 Eq. 3.26)
  Hu-Adams          c = 1/d (Hu & Adams 2006), w = 1
  Hu-Adams / Gamma  c = 1/d, w = 1 / Gamma

Gamma_a = sum_b V_b W_ab over the drop. BENCHMARKS.md, "Where the push comes
from", has the numbers and why no stress form is in the code yet.
"""
import argparse

import h5py
import numpy as np
from scipy.spatial import cKDTree


def quintic(h):
    """W(r) and the factor f(r) of grad_a W_ab = f r_ab, 2D quintic spline of support 3h."""
    alpha = 7.0 / (478.0 * np.pi * h * h)

    def pieces(r, power):
        q = r / h
        return sum(c * np.where(q < k, (k - q) ** power, 0.0) for c, k in ((1, 3), (-6, 2), (15, 1)))

    def w(r):
        return alpha * pieces(r, 5)

    def f(r):
        return np.where(r > 0, -5.0 * alpha * pieces(r, 4) / (h * np.maximum(r, 1e-30)), 0.0)

    return w, f


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("snapshot")
    parser.add_argument("--surface-h", type=float, default=0.06, help="h of the surface terms (m)")
    parser.add_argument("--sigma", type=float, default=10.0, help="surface tension (N/m)")
    parser.add_argument("--centre", default="0,0", help="the drop's centre x,y (m)")
    args = parser.parse_args()
    with h5py.File(args.snapshot, "r") as snap:
        liquid = snap["material"][()] == 0
        x = snap["position"][()][liquid, :2] - np.array([float(v) for v in args.centre.split(",")])
        n = snap["normal"][()][liquid, :2]
        volume = (snap["mass"][()] / snap["density"][()])[liquid]
    w, f = quintic(args.surface_h)
    pairs = np.array(sorted(cKDTree(x).query_pairs(3.0 * args.surface_h)))
    a = np.concatenate([pairs[:, 0], pairs[:, 1]])
    b = np.concatenate([pairs[:, 1], pairs[:, 0]])
    r_ab = x[a] - x[b]
    r = np.linalg.norm(r_ab, axis=1)
    gamma = volume * w(0.0) + np.bincount(a, volume[b] * w(r), len(x))
    size = np.linalg.norm(n, axis=1)
    n_hat = n / np.maximum(size, 1e-30)[:, None]
    radius = np.linalg.norm(x, axis=1)
    r_hat = x / radius[:, None]

    def stress_dot(c, k):
        along = (n_hat[k] * r_ab).sum(1)
        return (args.sigma * size[k])[:, None] * (c * r_ab - along[:, None] * n_hat[k])

    for name, c, consistent in (("Lafaurie", 1.0, False), ("Lafaurie / Gamma", 1.0, True),
                                ("Hu-Adams", 0.5, False), ("Hu-Adams / Gamma", 0.5, True)):
        w_b = 1.0 / gamma[b] if consistent else np.ones(len(a))
        w_a = 1.0 / gamma[a] if consistent else np.ones(len(a))
        term = (stress_dot(c, a) * w_b[:, None] + stress_dot(c, b) * w_a[:, None]) * (volume[b] * f(r))[:, None]
        force = np.zeros_like(x)
        np.add.at(force, a, term)
        force *= volume[:, None]
        jump = -((force * r_hat).sum(1) / (2.0 * np.pi * radius)).sum()
        print(f"{name:17s} jump {jump:8.4f} Pa, net force ({force[:, 0].sum():+.2e}, {force[:, 1].sum():+.2e}) N/m")


if __name__ == "__main__":
    main()
