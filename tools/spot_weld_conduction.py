#!/usr/bin/env python3
"""Conduction-only reference for the spot weld (cases/am/spot_weld_304_3d.yaml).

    tools/spot_weld_conduction.py [--cell 10e-6] [--radius 0.57e-3] [--absorptivity 0.27]

An axisymmetric finite-volume solution, independent of amsph, of the heat
equation in enthalpy form, rho dh/dt = div(k grad T), on a cylinder of the
case's plate (1.5 mm radius, 1 mm deep): the case's 304 steel (Russell 2018
Table 4.1: c_p 711.17 / 937.35 and k 20 / 209.3 J, W per kg, m K, solid /
liquid, blended by the liquid fraction across 1673-1773 K; latent heat
2.7e5 J/kg spread over that interval), its mass density at 293 K
(fixed particles keep their mass), the Gaussian flux
2 zeta P / (pi r_l^2) exp(-2 r^2 / r_l^2) of 1967 W on the top face for 3 ms
less the radiation eps sigma (T^4 - 293^4) (eps 0.4), 293 K half a cell below
the bottom, the side adiabatic; explicit steps to 5 ms. No flow: it is the
fusion zone the pool would have if the melt stood still, the limit amsph's
run with the fluid and surface modules off approaches as dx falls.

Prints the solidus isotherm of the peak temperature: its radius on the top
cells and at the depth of the top particle layer of an amsph run at dx =
50 um (25 um), and its depth on the axis, each linear between cell centres.
The error is first order in the cell (5 / 10 / 20 um give depths 0.169 /
0.164 / 0.158 mm). Below melting the problem is linear, and the centre's
temperature matches the closed form for a Gaussian flux on a half-space to
7e-4 (tests/test_spot_weld_conduction.py).
"""
import argparse

import numpy as np

POWER, PULSE, END = 1967.0, 3e-3, 5e-3           # W, s, s
PLATE_RADIUS, PLATE_DEPTH = 1.5e-3, 1.0e-3       # m
K_SOLID, K_LIQUID = 20.0, 209.3                  # W/(m K)
C_SOLID, C_LIQUID = 711.17, 937.35               # J/(kg K)
LATENT, SOLIDUS, MELTING_RANGE = 2.7e5, 1673.0, 100.0
DENSITY = 8020.0 - 0.501 * (293.0 - 298.0)      # kg/m^3 at 293 K (Russell's solid law)
EMISSIVITY, STEFAN_BOLTZMANN, AMBIENT = 0.4, 5.670374419e-8, 293.0


def liquid_fraction(t):
    return np.clip((t - SOLIDUS) / MELTING_RANGE, 0.0, 1.0)


def enthalpy_table():
    """h(T) from 0 K on a 0.1 K grid: the integral of c_p plus L times the liquid fraction."""
    t = np.linspace(0.0, 6000.0, 60001)
    c = C_SOLID + (C_LIQUID - C_SOLID) * liquid_fraction(t)
    h = np.concatenate([[0.0], np.cumsum(0.5 * (c[1:] + c[:-1]) * np.diff(t))])
    return t, h + LATENT * liquid_fraction(t)


def harmonic(a, b):
    return 2.0 * a * b / (a + b)


def peak_temperature(cell, beam_radius, absorptivity):
    """The peak temperature of every cell (rows from the top, columns from the axis)."""
    nr, nz = int(round(PLATE_RADIUS / cell)), int(round(PLATE_DEPTH / cell))
    r = (np.arange(nr) + 0.5) * cell
    faces = np.arange(1, nr) * cell
    table_t, table_h = enthalpy_table()
    temp = np.full((nz, nr), AMBIENT)
    h = np.interp(temp, table_t, table_h)
    peak = temp.copy()
    flux = 2.0 * absorptivity * POWER / (np.pi * beam_radius**2) * np.exp(-2.0 * r**2 / beam_radius**2)
    dt = 0.2 * cell * cell * DENSITY * C_SOLID / K_LIQUID
    time = 0.0
    while time < END:
        k = K_SOLID + (K_LIQUID - K_SOLID) * liquid_fraction(temp)
        radial = harmonic(k[:, 1:], k[:, :-1]) * (temp[:, 1:] - temp[:, :-1]) / cell * faces
        vertical = harmonic(k[1:, :], k[:-1, :]) * (temp[1:, :] - temp[:-1, :]) / cell
        rate = np.zeros_like(temp)
        rate[:, :-1] += radial / (r[:-1] * cell)
        rate[:, 1:] -= radial / (r[1:] * cell)
        rate[:-1, :] += vertical / cell
        rate[1:, :] -= vertical / cell
        top = (flux if time < PULSE else 0.0) - EMISSIVITY * STEFAN_BOLTZMANN * (temp[0] ** 4 - AMBIENT**4)
        rate[0, :] += top / cell
        rate[-1, :] += 2.0 * k[-1, :] * (AMBIENT - temp[-1, :]) / cell**2
        h += dt * rate / DENSITY
        temp = np.interp(h, table_h, table_t)
        np.maximum(peak, temp, out=peak)
        time += dt
    return peak


def crossing(values, step):
    """Where values (cell centres step apart from step / 2) fall through the solidus."""
    i = int(np.argmax(values < SOLIDUS))
    if i == 0:
        return 0.0
    return (i - 0.5) * step + (values[i - 1] - SOLIDUS) / (values[i - 1] - values[i]) * step


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cell", type=float, default=10e-6, help="cell size, m (default 10e-6)")
    parser.add_argument("--radius", type=float, default=0.57e-3, help="1/e^2 beam radius, m (default 0.57e-3)")
    parser.add_argument("--absorptivity", type=float, default=0.27, help="absorbed fraction (default 0.27)")
    args = parser.parse_args()
    peak = peak_temperature(args.cell, args.radius, args.absorptivity)
    row = 25e-6 / args.cell - 0.5  # 25 um deep, between cell centres
    lower = int(row)
    layer = peak[lower] + (row - lower) * (peak[lower + 1] - peak[lower])
    print("cell %g um, r_l %g mm, absorptivity %g: solidus isotherm radius %.4f mm on top, %.4f mm at 25 um "
          "deep; depth %.4f mm; peak %.0f K" % (args.cell * 1e6, args.radius * 1e3, args.absorptivity,
                                                 crossing(peak[0], args.cell) * 1e3,
                                                 crossing(layer, args.cell) * 1e3,
                                                 crossing(peak[:, 0], args.cell) * 1e3, peak.max()))


if __name__ == "__main__":
    main()
