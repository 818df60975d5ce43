#!/usr/bin/env python3
"""Writes cases/am/binder_jetting_{1,10,50}ms_{2,3}d.yaml, the binder-jetting
scene of Fuchs et al. 2022 Sec. 4.2 at the droplet speeds, and
binder_jetting_{1,10,50}ms_gas_{2,3}d.yaml with the gas phase, from one
template (the
settings that follow from the speed, the dimension and the gas are worked
out here)."""
import math
import pathlib
import re

TEMPLATE = '''# Binder jetting after Fuchs et al. 2022 §4.2, in @DIM@D and @WITH@ the gas
# phase: a binder droplet of 80 um diameter (rho 1000, eta 1e-3, sigma 0.5,
# Fuchs Table 4) falls at @SPEED@ m/s onto a bed of @GRAINS@mobile steel grains
# (log-normal diameters 16 to 32 um, settled by the powder-bed generator,
# each grain a rigid body of the `grains:` module) on a 20 um substrate,
# in a closed box @BOX@. Its centre starts 100 um above the
# substrate, as Fuchs's. The binder meets the grains, the substrate and
# the walls at Fuchs's equilibrium wetting angle theta0 = 60 degrees
# (Fuchs Table 4; `contact_angle`, normal correction of their Eqs. 27-29:
# grains count as solid in the solid colour c_sf, as Fuchs's). The surface
# terms take the support of 4.5 dx (h_over_dx 2.25 with Wendland C2) and
# the interface viscosity of Fuchs's Eqs. 31-32, the settings that hold the
# angle on the sessile cap (README): at the default 3.6 dx and without it,
# the 1 m/s droplet slid off the centre at 2-4 m/s and flung particles off
# its contact lines at 11 m/s. Its alpha0 = @ALPHA0@ is Fuchs's binder 1.8
# (Table 4) times their speed of sound over ours, 100 / @SOUND@ (their
# c = sqrt(p0 / rho0) with p0 = 1e7 Pa, Sec. 4.1): the viscosity grows
# with alpha0 c (Eq. 31), so this keeps theirs at the same h / dx (with
# 1.8 at c0 = 1000 m/s the 50 m/s droplet did not splash; BENCHMARKS.md).
# The speed of sound (@SOUND@ m/s for the binder) is the larger of twenty
# times the impact speed (the impact's water hammer compresses by v / c,
# the first particle to hit a grain by up to twice that) and ten times a
# particle's capillary speed sqrt(sigma / (rho dx)) = @CAPILLARY@ m/s. A binder
# particle caught between a grain and its neighbour was pressed by 20% at
# 87 us at 10 m/s, hence the density bound of 35% (as the tracks'). The
# grains get the binder's bulk modulus rho0 c0^2, as the buoyancy test of
# test_grains needs. Negative pressures are not clamped: spray holds no
# tension (README, fluid: spray). Before that rule spray torn off the
# grains went into tension (-21% density, 80 m/s at 21 us at 10 m/s) and
# the cases clamped it. Monaghan's artificial viscosity (alpha 0.1, as
# the tracks; Fuchs et al. add an artificial viscosity at interfaces, Eqs.
# 31-33) in place of the binder's laminar one: with the laminar viscosity
# a spray particle hit the wall at 60 m/s at 17.5 us (20% compression).
# k_c stops a grain hit at the
# droplet's speed within half a dx on two contacts, with a damping ratio
# near 0.5.@NOTE@@RUN_NOTE@@GAS_NOTE@ Written by tools/binder_variants.py.
dimension: @DIM@
@DOMAIN@
dx: @DX@
end_time: @END@
output_interval: @OUTPUT@
@GRAVITY@
fluid: {@MULTIPHASE@viscosity: artificial, artificial_alpha: 0.1, shifting: 0.5, max_density_error: 0.35,
        barrier: {stiffness: @BARRIER@, damping: 0, distance: @BARRIER_DISTANCE@}}
surface: {h_over_dx: 2.25, interface_viscosity: @ALPHA0@}
grains: {contact_stiffness: @STIFFNESS@, contact_damping: @DAMPING@}
materials:
  - {name: binder, density: 1000, viscosity: 1.0e-3, surface_tension: 0.5, sound_speed: @SOUND@,
     contact_angle: 60}   # Fuchs et al. 2022 Table 4: theta0 = 60 degrees
  - {name: steel, density: 7430, sound_speed: @STEEL_SOUND@}@GAS_MATERIAL@
geometry:
@GEOMETRY@@GAS_FILL@
'''

GEOMETRY = {
    2: '''  - {shape: box, kind: wall, material: steel, min: [0, 0], max: [3.2e-4, 2.0e-4], layers: 3}
  - {shape: box, kind: solid, material: steel, min: [0, 0], max: [3.2e-4, 2.0e-5]}
  - {shape: powder_bed, kind: grain, material: steel, min: [0, 2.0e-5], max: [3.2e-4, 6.0e-5],
     distribution: lognormal, grain_radius: 1.1e-5, log_sd: 0.2, grain_radius_min: 8.0e-6,
     grain_radius_max: 1.6e-5, seed: 1}
  - {shape: circle, kind: fluid, material: binder, center: [1.6e-4, 1.2e-4], radius: 4.0e-5,
     velocity: [0, @VELOCITY@]}''',
    # the bed's top face (the spreader's height) at 78 um lays 486 grains,
    # about Fuchs's 500, below the droplet's lowest point at 80 um
    3: '''  - {shape: box, kind: wall, material: steel, min: [0, 0, 0], max: [3.2e-4, 3.2e-4, 2.0e-4], layers: 3}
  - {shape: box, kind: solid, material: steel, min: [0, 0, 0], max: [3.2e-4, 3.2e-4, 2.0e-5]}
  - {shape: powder_bed, kind: grain, material: steel, min: [0, 0, 2.0e-5], max: [3.2e-4, 3.2e-4, 7.8e-5],
     distribution: lognormal, grain_radius: 1.1e-5, log_sd: 0.2, grain_radius_min: 8.0e-6,
     grain_radius_max: 1.6e-5, seed: 1}
  - {shape: sphere, kind: fluid, material: binder, center: [1.6e-4, 1.6e-4, 1.2e-4], radius: 4.0e-5,
     velocity: [0, 0, @VELOCITY@]}''',
}

# dx: 2D at 1.2 Fuchs's 1.67 um; 3D at the coarsest spacing that resolves the
# smallest grain (8 um) by 2 dx, which keeps a run within an hour on 2 cores
SCENE = {
    2: {"DX": 2.0e-6, "DOMAIN": "domain: {min: [-1.0e-5, -1.0e-5], max: [3.3e-4, 2.1e-4]}",
        "GRAVITY": "gravity: [0, -9.81]", "BOX": "320 um wide", "GRAINS": "", "NOTE": ""},
    3: {"DX": 4.0e-6, "DOMAIN": "domain: {min: [-1.6e-5, -1.6e-5, -1.6e-5], max: [3.36e-4, 3.36e-4, 2.16e-4]}",
        "GRAVITY": "gravity: [0, 0, -9.81]", "BOX": "320 x 320 x 200 um", "GRAINS": "486 ",
        "NOTE": "\n# dx = 4 um, the coarsest that resolves the smallest grain by 2 dx."},
}
# the end of the run and the output interval (s): in 3D the end of Fuchs's
# figures, 0.1 ms at 1 m/s and 0.05 ms at 10 m/s; at 50 m/s (c0 = 1000 m/s,
# five times the steps per microsecond) the first 10 us, the impact: 8410
# steps, about 36 min on 2 cores at the rate of the run's first minutes alone
# (it ran 92 min beside other runs); the 2D slices all run to 0.1 ms
RUN = {(2, 1): (1.0e-4, 2.0e-6), (2, 10): (1.0e-4, 2.0e-6), (2, 50): (1.0e-4, 2.0e-6),
       (3, 1): (1.0e-4, 2.5e-6), (3, 10): (5.0e-5, 2.5e-6), (3, 50): (1.0e-5, 5.0e-7)}
# with the gas phase (the gas's barrier makes the steps six to ten times
# shorter than without it): at 1 m/s the whole 0.1 ms, at 10 m/s the impact
# and the spreading, 0.04 ms, at 50 m/s the splash, 10 us; in 3D to the end
# of the cases without the gas (0.1 ms, 0.05 ms and 10 us: GPU runs, 1.4 to
# 1.7 steps/s on 2 cores)
GAS_RUN = {(2, 1): (1.0e-4, 2.0e-6), (2, 10): (4.0e-5, 2.0e-6), (2, 50): (1.0e-5, 5.0e-7),
           (3, 1): (1.0e-4, 2.5e-6), (3, 10): (5.0e-5, 2.5e-6), (3, 50): (1.0e-5, 5.0e-7)}

# what a case's header adds about its own run
NOTES = {(3, 50): ("\n# At dx = 4 um this droplet does not splash as Fuchs's does (without the"
                   "\n# interface viscosity its sheet was one or two particles thick); the 2D"
                   "\n# slice at 2 um does (BENCHMARKS.md, \"The interface viscosity at Fuchs's"
                   "\n# speed of sound\").")}

FUCHS_SOUND = 100.0     # m/s, sqrt(p0 / rho0) of Fuchs's binder, p0 = 1e7 Pa (Sec. 4.1)
FUCHS_ALPHA0 = 1.8      # their binder's interface viscosity (Table 4)
GRAIN_RADIUS = 1.1e-5   # m, the bed's median grain
STEEL = 7430.0          # kg/m^3
BINDER = 1000.0
SURFACE_TENSION = 0.5   # N/m, the binder's (Fuchs Table 4)
GAS = 10.0              # kg/m^3: density ratio 100 (Fuchs Sec. 4.1)
GAS_VISCOSITY = 1.0e-4  # Pa s: viscosity ratio 10 to the binder's 1e-3
GAS_NOTE = """
# With the gas phase (Fuchs Sec. 4.1): the free space of the box, the bed's
# pores included, filled (`fill`) with a gas of density @GAS@ kg/m^3 and
# viscosity @GAS_VISCOSITY@ Pa s (density ratio 100, viscosity ratio 10 to the
# binder) and a bulk modulus rho c^2 a quarter of the binder's (c = @GAS_SOUND@
# m/s, as cases/validation/young_laplace_gas_2d.yaml); the multiphase
# pressure force (Fuchs Eq. 23). No background pressure in the equation of
# state: p_b drags a liquid or a grain moving through the gas's disordered
# particles (C_d 7.8 at 3e4 Pa and 66 at 1.2e6 Pa in
# cases/validation/drag_gas_2d.yaml; a grain coasting at 2 m/s through the
# 50 m/s scene's gas lost 22% of its speed in 5 us at 7.5e5 Pa, 3.3%
# without), and at 1.2e6 Pa the 10 m/s droplet came to rest on a gas film
# on the bed's top. The gas takes the background pressure in the transport
# velocity instead (Adami, Hu & Adams 2013; `transport_pressure`, its rho0
# c0^2 = @GAS_TRANSPORT@ Pa), which keeps its particles evenly spaced
# without that force, and its density summed over its neighbours
# (`gas_density: summation`), which does not drift as the continuity's
# does with p_b = 0 (BENCHMARKS.md, "The transport velocity in place of
# p_b"). The barrier on the gas's light particles sets the step.@GAS_RESULT@
#"""

# what a gas case's header adds about its own run
GAS_RESULTS = {
    (2, 1): ("\n# At 1 m/s: 3.5e-10 s, 0.1 ms in 287500 steps, 69 min on 2 cores. The"
             "\n# droplet soaks into the bed as without the gas, to 2.4 to 4.1 um above"
             "\n# the substrate, and loosens it under itself from 0.636 to 0.36 to 0.45"
             "\n# (2026-12-05 and -07). Its bottom starts 20 um above the bed, and the"
             "\n# gas film it closes slows it before it lands (docs/RESULTS.md)."),
    (2, 10): ("\n# At 10 m/s: 3.5e-10 s, 0.04 ms in 115000 steps, 25 min on 2 cores"
              "\n# (47 to 67 min on one beside other runs, 2026-12-07). The gas's pressure (1st to 99th"
              "\n# percentile) stays between -12 and 31 kPa. The droplet soaks into the"
              "\n# bed (its lowest particle 4.0 to 4.7 um above the substrate at 0.04 ms)"
              "\n# and loosens it, from 0.636 to 0.41 under the droplet, less than"
              "\n# without the gas (0.385; docs/RESULTS.md, BENCHMARKS.md \"The 10 and 1"
              "\n# m/s binder scenes with the gas on the current build\")."),
    (2, 50): ("\n# At 50 m/s: 1.1e-10 s, the splash's first 10 us in 91060 steps, 62 min on"
              "\n# one core beside another run (20 min on 2 cores, 2026-12-05). The sheets"
              "\n# reach the side walls at 3.5 us and the lid at 5.5 us, and the bed under"
              "\n# the droplet loosens from 0.636 to 0.379 (0.434 on 2026-12-05), as"
              "\n# without the gas (0.406; docs/RESULTS.md, BENCHMARKS.md \"The 50 m/s"
              "\n# binder scene with the gas under the same test\")."),
    (3, 10): ("\n# In 3D at 10 m/s: 9.8e-10 s, 0.05 ms in about 51000 steps of 414176"
              "\n# particles, a GPU's run (1.7 steps/s on 2 cores, 8 h). Its first 4 us"
              "\n# (4072 steps): the droplet slows and spreads as without the gas (at 4 us its"
              "\n# kinetic energy within 0.2%, its lowest point 2 um higher, its wetted"
              "\n# width 3.5 um narrower; docs/RESULTS.md)."),
    (3, 1): ("\n# In 3D at 1 m/s: 9.8e-10 s (the barrier), 0.1 ms in about 102000 steps of"
             "\n# 414176 particles, a GPU's run (1.4 steps/s on 2 cores, 20 h); its first"
             "\n# 100 steps ran on 2 cores."),
    (3, 50): ("\n# In 3D at 50 m/s: 2.2e-10 s (the barrier), 10 us in about 45500 steps of"
              "\n# 414176 particles, a GPU's run (1.4 steps/s on 2 cores, 9 h); its first"
              "\n# 100 steps ran on 2 cores."),
}


# the gas fills the box up to its lid
GAS_BOX = {2: "min: [0, 0], max: [3.2e-4, 2.0e-4]", 3: "min: [0, 0, 0], max: [3.2e-4, 3.2e-4, 2.0e-4]"}


def gas_settings(speed, dim, sound, gas):
    """The template's gas keys: empty without the gas phase."""
    if not gas:
        return {"WITH": "without", "MULTIPHASE": "", "GAS_MATERIAL": "", "GAS_FILL": "", "GAS_NOTE": ""}
    gas_sound = f"{float(f'{sound * math.sqrt(BINDER / (4.0 * GAS)):.3g}'):g}"
    transport = GAS * float(gas_sound) ** 2
    note = GAS_NOTE
    for key, value in (("GAS", f"{GAS:g}"), ("GAS_VISCOSITY", f"{GAS_VISCOSITY:.0e}"), ("GAS_SOUND", gas_sound),
                       ("GAS_TRANSPORT", f"{transport:.3g}".replace("e+0", "e")), ("GAS_RESULT", GAS_RESULTS.get((dim, speed), ""))):
        note = note.replace("@" + key + "@", value)
    return {"WITH": "with", "GAS_NOTE": note,
            "MULTIPHASE": f"pressure_gradient: multiphase, transport_pressure: {transport:.3g}, gas_density: summation,\n"
                          "        ",
            "GAS_MATERIAL": f"\n  - {{name: gas, phase: gas, density: {GAS:g}, viscosity: {GAS_VISCOSITY:.1e}, "
                            f"sound_speed: {gas_sound}}}",
            "GAS_FILL": f"\n  - {{shape: box, kind: fluid, material: gas, {GAS_BOX[dim]}, fill: true}}"}


def settings(speed, dim, gas):
    scene = SCENE[dim]
    dx = scene["DX"]
    # twenty times the impact speed (the water-hammer pressure rho c v of the
    # impact compresses by v / c), and ten times the capillary speed of a
    # particle, sqrt(sigma / (rho dx)): at 1 m/s with ten times that of the
    # droplet, sqrt(sigma / (rho R)), binder particles flung off the contact
    # lines at 17 m/s were pressed by 37% at 23 us
    capillary = math.sqrt(SURFACE_TENSION / (BINDER * dx))
    sound = max(20.0 * speed, 10.0 * capillary)
    sound_shown = float(f"{sound:.3g}")   # as the case file states it
    # per metre of depth in 2D
    grain_mass = (math.pi * GRAIN_RADIUS ** 2 if dim == 2 else 4.0 / 3.0 * math.pi * GRAIN_RADIUS ** 3) * STEEL
    stiffness = grain_mass * speed ** 2 / (2 * (0.5 * dx) ** 2)
    particle_mass = STEEL * dx ** dim
    damping = 0.5 * 2.0 * math.sqrt(stiffness * particle_mass)
    # the barrier stops a binder pair (reduced mass m / 2) closing at twice
    # the droplet's or a particle's capillary speed within dx/8 (at dx/4,
    # spray pairs at the walls closed to 0.3 dx at 10 m/s)
    closing = 2 * max(speed, capillary)
    barrier = 0.25 * BINDER * dx ** dim * closing ** 2 / (0.125 * dx) ** 2
    # Its reach r_b: dx/2, and 0.7 dx in the gas at 50 m/s. There a gas pair
    # (reduced mass 1/100 of a binder pair's) came at each other at about
    # 1760 m/s, sucked into a pocket opening between grains under -15 MPa,
    # and closed to 0.285 dx at 1.76 us; from 0.7 dx to the guard's 0.3 dx
    # the same k_b stops such a pair closing at g sqrt(k_b / mu) = 2260 m/s
    # (1130 from dx/2), with the step unchanged. At most 9 of the 11131 gas
    # particles lie within 0.7 dx of another in a snapshot of those runs.
    reach = 0.7 if gas and speed >= 50 else 0.5
    end, output = (GAS_RUN if gas else RUN)[dim, speed]
    values = {"SPEED": f"{speed:g}", "VELOCITY": f"{-speed:g}", "SOUND": f"{sound_shown:g}",
              "STEEL_SOUND": f"{sound * math.sqrt(BINDER / STEEL):.3g}", "CAPILLARY": f"{capillary:.2g}",
              "STIFFNESS": f"{stiffness:.3g}", "DAMPING": f"{damping:.3g}", "BARRIER": f"{barrier:.3g}",
              "BARRIER_DISTANCE": f"{reach * dx:.1e}", "DIM": f"{dim}", "END": f"{end:.1e}",
              "OUTPUT": f"{output:.1e}", "ALPHA0": f"{FUCHS_ALPHA0 * FUCHS_SOUND / sound_shown:.3g}",
              "RUN_NOTE": NOTES.get((dim, speed), "")}
    return scene | {"DX": f"{dx:.1e}"} | values | gas_settings(speed, dim, sound, gas)


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    for gas, runs in ((False, RUN), (True, GAS_RUN)):
        for (dim, speed) in runs:
            text = TEMPLATE.replace("@GEOMETRY@", GEOMETRY[dim])
            for key, value in settings(speed, dim, gas).items():
                text = text.replace("@" + key + "@", value)
            text = re.sub(r"e-0(\d)", r"e-\1", text)   # 2.0e-6, not 2.0e-06
            name = f"binder_jetting_{speed}ms_{'gas_' if gas else ''}{dim}d.yaml"
            (root / "cases" / "am" / name).write_text(text)


if __name__ == "__main__":
    main()
