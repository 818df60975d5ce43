/* Tests of the case-file parser (host/case.c).
 *
 * 1. Bad inputs: each must fail with exactly the expected one-line message.
 * 2. Good inputs: parsed values are checked (defaults, vectors, face bits,
 *    normalised axis, key order not mattering).
 * 3. Robustness: deep nesting, huge keys and numbers, NUL bytes, and a
 *    deterministic fuzz loop of byte mutations; every failure must give a
 *    "case.yaml:LINE: ..." message on one line.
 * Prints one line per failure and ends with "N passed, M failed". */
#include "case.h"
#include "material.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NAME "case.yaml"
/* the magnitudes a number may take besides 0 (host/case.c parse_number) */
#if AMSPH_DOUBLE
#define REAL_RANGE "2.22507e-308 to 1.79769e+308 in magnitude"
#else
#define REAL_RANGE "1.17549e-38 to 3.40282e+38 in magnitude"
#endif

static int passed, failed;
static amsph_case parsed; /* large; kept out of the stack */

static void report(int ok, const char *test, const char *what)
{
    if (ok) {
        passed++;
        return;
    }
    failed++;
    printf("FAIL %s: %s\n", test, what);
}

/* ---- bad inputs ---------------------------------------------------------- */

/* A valid 2D case, in pieces, so that bad cases can swap one piece. Lines:
 * 1-7 settings, 8-10 materials, 11-16 geometry. */
#define DOMAIN2                                                                                    \
    "dimension: 2\n"                                                                               \
    "domain:\n"                                                                                    \
    "  min: [0, 0]\n"                                                                              \
    "  max: [1, 1]\n"
#define HEAD2                                                                                      \
    DOMAIN2                                                                                        \
    "dx: 0.01\n"                                                                                   \
    "end_time: 1\n"                                                                                \
    "output_interval: 0.1\n"
#define MATS                                                                                       \
    "materials:\n"                                                                                 \
    "  - name: water\n"                                                                            \
    "    density: 1000\n"
#define GEO_BOX                                                                                    \
    "geometry:\n"                                                                                  \
    "  - shape: box\n"                                                                             \
    "    kind: fluid\n"                                                                            \
    "    material: water\n"                                                                        \
    "    min: [0, 0]\n"                                                                            \
    "    max: [0.5, 0.5]\n"
#define GEO_START                                                                                  \
    "geometry:\n"                                                                                  \
    "  - kind: fluid\n"                                                                            \
    "    material: water\n"
#define BASE2 HEAD2 MATS GEO_BOX
/* for the grains module: a fluid section (line 8), a material with a sound
 * speed (9-10), a grain block (11-12) */
#define FLUID_MATS                                                                                 \
    "fluid: {}\n"                                                                                   \
    "materials:\n"                                                                                 \
    "  - {name: water, density: 1000, sound_speed: 10}\n"
#define GEO_GRAIN                                                                                  \
    "geometry:\n"                                                                                  \
    "  - {shape: box, kind: grain, material: water, min: [0.1, 0.1], max: [0.2, 0.2]}\n"
#define HEAD3                                                                                      \
    "dimension: 3\n"                                                                               \
    "domain:\n"                                                                                    \
    "  min: [0, 0, 0]\n"                                                                           \
    "  max: [1, 1, 1]\n"                                                                           \
    "dx: 0.01\n"                                                                                   \
    "end_time: 1\n"                                                                                \
    "output_interval: 0.1\n"

typedef struct {
    const char *name;
    const char *text;
    const char *expected; /* the whole message */
} bad_case;

static const bad_case bad_cases[] = {
    /* YAML syntax */
    {"syntax: unclosed flow map", "dimension: 2\ndomain: {min: [0, 0]\ndx: 1\n",
     NAME ":3: YAML syntax error: did not find expected ',' or '}' "
          "(while parsing a flow mapping on line 2)"},
    {"syntax: bad indentation", "dimension: 2\n  dx: 1\n",
     NAME ":2: YAML syntax error: mapping values are not allowed in this context"},
    {"syntax: tab indentation", "dimension: 2\n\tdx: 1\n",
     NAME ":2: YAML syntax error: found a tab character that violates indentation "
          "(while scanning a plain scalar on line 1)"},
    {"syntax: undefined alias", DOMAIN2 "dx: *spacing\n",
     NAME ":5: YAML syntax error: found undefined alias"},
    {"syntax: control character", DOMAIN2 "dx: \001\n",
     NAME ":5: unreadable text: control characters are not allowed"},
    {"syntax: invalid UTF-8", "dimension: 2\nd\377x: 1\n",
     NAME ":2: unreadable text: invalid leading UTF-8 octet"},

    /* documents */
    {"empty file", "", NAME ":1: the case file is empty; expected keys such as 'dimension'"},
    {"only comments", "# nothing here\n\n",
     NAME ":1: the case file is empty; expected keys such as 'dimension'"},
    {"root is a list", "- dimension: 2\n",
     NAME ":1: a case file must be a map of keys, got a list"},
    {"root is a scalar", "hello\n", NAME ":1: a case file must be a map of keys, got 'hello'"},
    {"two documents", BASE2 "---\n" BASE2,
     NAME ":17: a second YAML document starts here; a case file holds exactly one"},

    /* more outputs than anyone means */
    {"too many outputs", DOMAIN2 "dx: 0.01\nend_time: 1\noutput_interval: 1e-8\n" MATS GEO_BOX,
     NAME ":7: 'output_interval' (1e-08 s) gives 1e+08 outputs up to 'end_time' (1 s); at most 1e+07 are "
          "allowed"},
    {"outputs beyond any count", DOMAIN2 "dx: 0.01\nend_time: 1e38\noutput_interval: 1e-37\n" MATS GEO_BOX,
     NAME ":7: 'output_interval' (1e-37 s) gives 1e+75 outputs up to 'end_time' (1e+38 s); at most 1e+07 "
          "are allowed"},

    /* unknown keys, duplicate keys */
    {"unknown key with suggestion", BASE2 "end_tme: 3\n",
     NAME ":17: unknown key 'end_tme' in top level; did you mean 'end_time'?"},
    {"unknown key without suggestion", BASE2 "colour: red\n",
     NAME ":17: unknown key 'colour' in top level (allowed: dimension, domain, dx, h_over_dx, "
          "kernel, end_time, output_interval, backend, device, gravity, fluid, thermal, surface, "
          "grains, laser, temperature_history, materials, geometry)"},
    {"unknown key in domain",
     "dimension: 2\ndomain:\n  min: [0, 0]\n  max: [1, 1]\n  periodc: "
     "[true, true]\n",
     NAME ":5: unknown key 'periodc' in domain; did you mean 'periodic'?"},
    {"unknown key in material", HEAD2 "materials:\n  - name: water\n    densty: 1000\n" GEO_BOX,
     NAME ":10: unknown key 'densty' in materials[0]; did you mean 'density'?"},
    {"unknown key in geometry",
     HEAD2 MATS GEO_START "    shape: circle\n    center: [0.5, 0.5]\n    radus: 0.1\n",
     NAME ":16: unknown key 'radus' in geometry[0]; did you mean 'radius'?"},
    {"long unknown key is cut", BASE2 "abcdefghijklmnopqrstuvwxyzabcdefghijklmnopqrstuvwxyz: 1\n",
     NAME ":17: unknown key 'abcdefghijklmnopqrstuvwxyzabcdefghijklmn...' in top level "
          "(allowed: dimension, domain, dx, h_over_dx, kernel, end_time, output_interval, "
          "backend, device, gravity, fluid, thermal, surface, grains, laser, temperature_history, "
          "materials, geometry)"},
    {"key that is a list", BASE2 "[a]: 1\n",
     NAME ":17: keys in top level must be names, got a list"},
    {"duplicate key", BASE2 "dx: 0.02\n",
     NAME ":17: duplicate key 'dx' in top level (first on line 5)"},
    {"duplicate key in geometry", BASE2 "    kind: wall\n",
     NAME ":17: duplicate key 'kind' in geometry[0] (first on line 13)"},

    /* types */
    {"number is a word", DOMAIN2 "dx: abc\n", NAME ":5: 'dx' must be a number, got 'abc'"},
    {"number is inf", DOMAIN2 "dx: 1\nend_time: inf\n",
     NAME ":6: 'end_time' must be a number, got 'inf'"},
    {"number is .nan", DOMAIN2 "dx: 1\nend_time: .nan\n",
     NAME ":6: 'end_time' must be a number, got '.nan'"},
    {"number is hex", DOMAIN2 "dx: 0x10\n", NAME ":5: 'dx' must be a number, got '0x10'"},
    {"number overflows", DOMAIN2 "dx: 1e999\n", NAME ":5: 'dx' is out of range (0, or " REAL_RANGE "), got '1e999'"},
    /* the particles' float would hold 1e39 as inf and 1e-46 as 0 */
    {"number beyond the particles' real", DOMAIN2 "dx: 1e39\n",
     NAME ":5: 'dx' is out of range (0, or " REAL_RANGE "), got '1e39'"},
    {"number below the particles' real", "dimension: 2\ndomain:\n  min: [0, 0]\n  max: [1, -1e-46]\n",
     NAME ":4: 'domain.max[1]' is out of range (0, or " REAL_RANGE "), got '-1e-46'"},
    {"number is empty", DOMAIN2 "dx:\n", NAME ":5: 'dx' must be a number, got an empty value"},
    {"number is a list", DOMAIN2 "dx: [1]\n", NAME ":5: 'dx' must be a number, got a list"},
    {"integer is a float", "dimension: 2.5\n",
     NAME ":1: 'dimension' must be an integer, got '2.5'"},
    {"integer overflows", BASE2 "device: 99999999999999999999\n",
     NAME ":17: 'device' is out of range, got '99999999999999999999'"},
    {"boolean is yes",
     "dimension: 2\ndomain:\n  min: [0, 0]\n  max: [1, 1]\n  periodic: [yes, "
     "false]\n",
     NAME ":5: 'domain.periodic[0]' must be true or false, got 'yes'"},
    {"vector is a number", BASE2 "gravity: 9.81\n",
     NAME ":17: 'gravity' must be a list of 2 numbers, got '9.81'"},
    {"vector component is a word", "dimension: 2\ndomain:\n  min: [0, 0]\n  max: [1, x]\n",
     NAME ":4: 'domain.max[1]' must be a number, got 'x'"},
    {"vector component is a cycle", "dimension: 2\ndomain:\n  min: &a [*a, 0]\n  max: [1, 1]\n",
     NAME ":3: 'domain.min[0]' must be a number, got a list"},
    {"domain is a list", "dimension: 2\ndomain: [0, 1]\n",
     NAME ":2: 'domain' must be a map, got a list"},
    {"materials is a word", HEAD2 "materials: water\n",
     NAME ":8: 'materials' must be a list of maps, got 'water'"},
    {"material entry is a word", HEAD2 "materials:\n  - water\n",
     NAME ":9: 'materials[0]' must be a map, got 'water'"},
    {"material name is a map", HEAD2 "materials:\n  - name: {a: 1}\n    density: 1\n",
     NAME ":9: 'materials[0].name' must be a non-empty name, got a map"},
    {"material name too long",
     HEAD2
     "materials:\n  - name: abcdefghijklmnopqrstuvwxyzabcdefghijklmnopqrstuvwxyz0123456789ab\n"
     "    density: 1\n",
     NAME ":9: 'materials[0].name' is too long (64 characters, at most 63): "
          "'abcdefghijklmnopqrstuvwxyzabcdefghijklmn...'"},
    {"material name with newline", HEAD2 "materials:\n  - name: \"wa\\nter\"\n    density: 1\n",
     NAME ":9: 'materials[0].name' must not contain control characters"},

    /* ranges */
    {"dx negative", DOMAIN2 "dx: -1\n", NAME ":5: 'dx' must be > 0, got -1"},
    {"dx zero", DOMAIN2 "dx: 0.0\n", NAME ":5: 'dx' must be > 0, got 0.0"},
    {"h_over_dx too large", BASE2 "h_over_dx: 5\n",
     NAME ":17: 'h_over_dx' must be in [1, 3], got 5"},
    {"dimension 4", "dimension: 4\n", NAME ":1: 'dimension' must be 2 or 3, got 4"},
    {"device negative", BASE2 "device: -2\n", NAME ":17: 'device' must be >= -1, got -2"},
    /* the fluid module */
    {"fluid needs a sound speed", BASE2 "fluid: {}\n",
     NAME ":9: material 'water' needs 'sound_speed' > 0 for the fluid module (about 10 times the "
          "largest expected flow speed)"},
    {"fluid unknown key", BASE2 "fluid: {delta_sph: 0.1}\n",
     NAME ":17: unknown key 'delta_sph' in fluid (allowed: density_diffusion, delta, "
          "continuity, pressure_gradient, viscosity, artificial_alpha, background_pressure, "
          "clamp_negative_pressure, tensile_correction, wall_slip, cfl, dt_min, min_pair_distance, max_density_error, damping_rate, damping_end, shifting, gas_density, transport_pressure, smoothing_length, max_smoothing_ratio, integration, verlet_steps, barrier)"},
    {"fluid bad choice", BASE2 "fluid: {density_diffusion: antuono}\n",
     NAME ":17: 'fluid.density_diffusion' must be one of none, molteni, russell, fourtakas; got "
          "'antuono'"},
    {"continuity unknown form", BASE2 "fluid: {continuity: renormalised}\n",
     NAME ":17: 'fluid.continuity' must be one of plain, corrected; got 'renormalised'"},
    {"fluid cfl above 1", BASE2 "fluid: {cfl: 2}\n", NAME ":17: 'fluid.cfl' must be in (0, 1], got 2"},
    {"fluid shifting negative", BASE2 "fluid: {shifting: -1}\n",
     NAME ":17: 'fluid.shifting' must be in [0, 10], got -1"},
    {"fluid gas density unknown form", BASE2 "fluid: {gas_density: summed}\n",
     NAME ":17: 'fluid.gas_density' must be one of continuity, summation; got 'summed'"},
    {"fluid transport pressure negative", BASE2 "fluid: {transport_pressure: -1e4}\n",
     NAME ":17: 'fluid.transport_pressure' must be >= 0, got -1e4"},
    {"fluid not a map", BASE2 "fluid: [1]\n", NAME ":17: 'fluid' must be a map, got a list"},
    {"smoothing length unknown form", BASE2 "fluid: {smoothing_length: adaptive}\n",
     NAME ":17: 'fluid.smoothing_length' must be one of fixed, volume; got 'adaptive'"},
    {"smoothing ratio not above 1", BASE2 "fluid: {smoothing_length: volume, max_smoothing_ratio: 1}\n",
     NAME ":17: 'fluid.max_smoothing_ratio' must be in (1, 2], got 1"},
    {"pressure gradient unknown form", BASE2 "fluid: {pressure_gradient: adami}\n",
     NAME ":17: 'fluid.pressure_gradient' must be one of renormalised, symmetric, multiphase; got 'adami'"},
    /* barrier forces (Fuchs et al. 2022 Eq. 34) */
    {"barrier without stiffness", BASE2 "fluid:\n  barrier: {distance: 0.005}\n",
     NAME ":18: missing required key 'stiffness' in fluid.barrier"},
    {"barrier stiffness zero", BASE2 "fluid:\n  barrier: {stiffness: 0, distance: 0.005}\n",
     NAME ":18: 'fluid.barrier.stiffness' must be > 0, got 0"},
    {"barrier damping negative", BASE2 "fluid:\n  barrier: {stiffness: 1, damping: -1, distance: 0.005}\n",
     NAME ":18: 'fluid.barrier.damping' must be >= 0, got -1"},
    {"barrier distance beyond h", BASE2 "fluid:\n  barrier: {stiffness: 1, distance: 0.012}\n",
     NAME ":18: 'fluid.barrier.distance' (0.012 m) must be below the smoothing length h_over_dx dx = 0.012 m"},
    {"barrier unknown key", BASE2 "fluid:\n  barrier: {stiffness: 1, distance: 0.005, range: 1}\n",
     NAME ":18: unknown key 'range' in fluid.barrier (allowed: stiffness, damping, distance)"},
    /* a gas phase (Fuchs et al. 2022 Sec. 4.1) */
    {"phase unknown", HEAD2 "materials:\n  - {name: water, density: 1, phase: vapour}\n" GEO_BOX,
     NAME ":9: 'materials[0].phase' must be one of liquid, gas; got 'vapour'"},
    {"gas that melts", HEAD2 "materials:\n  - {name: air, density: 1, phase: gas,\n     melting_temperature: 300, melting_range: 1}\n" GEO_BOX,
     NAME ":10: material 'air' is a gas ('phase: gas'), which neither melts nor evaporates: it must not have 'materials[0].melting_temperature' (given here or by its preset)"},
    {"gas that evaporates", HEAD2 "materials:\n  - {name: air, density: 1, phase: gas, preset: steel_fuchs}\n" GEO_BOX,
     NAME ":9: material 'air' is a gas ('phase: gas'), which neither melts nor evaporates: it must not have 'materials[0].melting_temperature' (given here or by its preset)"},
    {"gas with a recoil pressure", HEAD2 "materials:\n  - {name: air, density: 1, phase: gas, recoil_pressure_constant: 1}\n" GEO_BOX,
     NAME ":9: material 'air' is a gas ('phase: gas'), which neither melts nor evaporates: it must not have 'materials[0].recoil_pressure_constant' (given here or by its preset)"},
    {"gas without the multiphase force", HEAD2 "fluid: {}\nmaterials:\n  - {name: air, density: 1, sound_speed: 10, phase: gas}\n"
     "geometry:\n  - {shape: box, kind: fluid, material: air, min: [0, 0], max: [1, 1]}\n",
     NAME ":10: material 'air' is a gas: it needs the fluid module with 'fluid.pressure_gradient: multiphase' (Fuchs et al. 2022 Eq. 23)"},
    {"gas wall", HEAD2 "materials:\n  - {name: air, density: 1, phase: gas}\n"
     "geometry:\n  - {shape: box, kind: wall, material: air, min: [0, 0], max: [1, 1], layers: 3}\n",
     NAME ":11: 'geometry[0].kind' must be fluid: material 'air' is a gas (its particles are fluid)"},
    {"fill on the first block", BASE2 "    fill: true\n",
     NAME ":17: 'geometry[0].fill' fills around the blocks before it, and this is the first block: list it after the shapes it surrounds"},
    {"fill not a boolean", BASE2 "    fill: gas\n",
     NAME ":17: 'geometry[0].fill' must be one of false, true; got 'gas'"},
    {"hydrostatic not a boolean", BASE2 "    hydrostatic: yes\n",
     NAME ":17: 'geometry[0].hydrostatic' must be one of false, true; got 'yes'"},
    {"viscosity negative",
     HEAD2 "materials:\n  - name: water\n    density: 1\n    viscosity: "
           "-1e-3\n",
     NAME ":11: 'materials[0].viscosity' must be >= 0, got -1e-3"},
    {"temperature negative", BASE2 "    temperature: -1\n",
     NAME ":17: 'geometry[0].temperature' must be >= 0, got -1"},
#define THERMAL_MAT HEAD2 "materials:\n  - name: water\n    density: 1\n"
    {"property temperatures decrease", THERMAL_MAT "    specific_heat: [[300, 1], [200, 2]]\n",
     NAME ":11: 'materials[0].specific_heat[1]': temperatures must be >= 0 K and increasing, got '200' after 300"},
    {"property is a map", THERMAL_MAT "    specific_heat: {a: 1}\n",
     NAME ":11: 'materials[0].specific_heat' must be a number or a list of 2 to 16 [temperature, value] pairs, got a map"},
    {"property table of one", THERMAL_MAT "    specific_heat: [[300, 1]]\n",
     NAME ":11: 'materials[0].specific_heat' must be a number or a list of 2 to 16 [temperature, value] pairs, got a list"},
    {"property value out of range", THERMAL_MAT "    conductivity: [[0, 1], [10, -1]]\n",
     NAME ":11: 'materials[0].conductivity[1]' value must be >= 0, got '-1'"},
    {"property not a pair", THERMAL_MAT "    specific_heat: [[0, 1], [10]]\n",
     NAME ":11: 'materials[0].specific_heat[1]' must be a pair [temperature, value], got a list"},
    {"property constant zero", THERMAL_MAT "    specific_heat: 0\n",
     NAME ":11: 'materials[0].specific_heat' must be > 0, got 0"},
    {"melting without range", THERMAL_MAT "    melting_temperature: 1700\n",
     NAME ":11: 'materials[0].melting_temperature' needs 'melting_range' (> 0 K)"},
    {"melting range too wide", THERMAL_MAT "    melting_temperature: 10\n    melting_range: 30\n",
     NAME ":12: 'materials[0].melting_range' (30 K) must be below 2 'melting_temperature' (10 K)"},
    {"emissivity above 1", THERMAL_MAT "    emissivity: 1.5\n",
     NAME ":11: 'materials[0].emissivity' must be in [0, 1], got 1.5"},
    /* material presets: unknown names are listed; a preset's value reads
     * as written on the preset's line */
    {"unknown preset", HEAD2 "materials:\n  - name: steel\n    density: 1\n    preset: steel_316\n" GEO_BOX,
     NAME ":11: 'materials[0].preset' must be one of none, steel_304, steel_fuchs; got 'steel_316'"},
    {"preset is a list", HEAD2 "materials:\n  - name: steel\n    preset: [steel_304]\n" GEO_BOX,
     NAME ":10: 'materials[0].preset' must be one of none, steel_304, steel_fuchs; got a list"},
    {"steel_304 without density", HEAD2 "materials:\n  - name: steel\n    preset: steel_304\n" GEO_BOX,
     NAME ":9: missing required key 'density' in materials[0]"},
    {"preset's melting range against a given melting temperature",
     HEAD2 "materials:\n  - name: steel\n    preset: steel_304\n    density: 1\n    melting_temperature: 40\n",
     NAME ":10: 'materials[0].melting_range' (100 K) must be below 2 'melting_temperature' (40 K)"},
    {"preset with a bad key of its own", HEAD2 "materials:\n  - {name: steel, preset: steel_fuchs, conductivity: -1}\n",
     NAME ":9: 'materials[0].conductivity' must be >= 0, got -1"},
    {"thermal without specific heat", BASE2 "    temperature: 300\nthermal: {}\n",
     NAME ":9: material 'water' needs 'specific_heat' for the thermal module"},
    {"thermal without temperature",
     HEAD2 "materials:\n  - {name: water, density: 1, specific_heat: 1, conductivity: 1}\n" GEO_BOX "thermal: {}\n",
     NAME ":11: geometry[0] needs 'temperature' for the thermal module"},
    {"viscous heating without fluid",
     HEAD2 "materials:\n  - {name: water, density: 1, specific_heat: 1, conductivity: 1}\n" GEO_BOX
           "    temperature: 300\nthermal: {viscous_heating: true}\n",
     NAME ":17: 'thermal.viscous_heating' needs the fluid module (a 'fluid:' section)"},
#define EVAPORATION_MAT(extra)                                                                     \
    HEAD2 "materials:\n  - {name: water, density: 1, sound_speed: 1, specific_heat: 1, conductivity: 1" extra "}\n" \
        GEO_BOX "    temperature: 300\n"
    {"recoil without fluid", EVAPORATION_MAT(", recoil_pressure_constant: 1") "thermal: {recoil_pressure: true}\n",
     NAME ":17: 'thermal.recoil_pressure' needs the fluid module (a 'fluid:' section)"},
    {"evaporation without an evaporating material", EVAPORATION_MAT("") "thermal: {evaporative_cooling: true}\n",
     NAME ":17: 'thermal.evaporative_cooling' needs a material that evaporates: give one a "
          "'recoil_pressure_constant' > 0 (or the preset steel_fuchs)"},
    {"evaporating material without boiling temperature",
     EVAPORATION_MAT(", recoil_pressure_constant: 5.4e4, recoil_temperature_constant: 5e4") "fluid: {}\n"
         "thermal: {recoil_pressure: true}\n",
     NAME ":9: material 'water' evaporates (recoil_pressure_constant > 0) and needs 'boiling_temperature' > 0"},
    {"evaporative cooling without the vapour mass constant",
     EVAPORATION_MAT(", recoil_pressure_constant: 5.4e4, recoil_temperature_constant: 5e4, boiling_temperature: 3000")
         "thermal: {evaporative_cooling: true}\n",
     NAME ":9: material 'water' evaporates (recoil_pressure_constant > 0) and needs 'vapour_mass_constant' > 0"},
    {"sticking coefficient above 1", EVAPORATION_MAT(", sticking_coefficient: 1.5") "thermal: {}\n",
     NAME ":9: 'materials[0].sticking_coefficient' must be in [0, 1], got 1.5"},
    {"evaporation temperature not positive", EVAPORATION_MAT("") "thermal: {evaporation_temperature: 0}\n",
     NAME ":17: 'thermal.evaporation_temperature' must be > 0, got 0"},
#define SURFACE_MAT(extra) HEAD2 "materials:\n  - {name: water, density: 1, sound_speed: 1" extra "}\n" GEO_BOX
    {"surface without fluid", BASE2 "surface: {}\n", NAME ":17: 'surface' needs the fluid module (a 'fluid:' section)"},
    {"marangoni without temperatures", SURFACE_MAT("") "fluid: {}\nsurface: {marangoni: true}\n",
     NAME ":17: 'surface.marangoni' needs temperatures: give every geometry block a 'temperature' "
          "(or add the thermal module)"},
    {"conservative tension with Marangoni",
     SURFACE_MAT("") "    temperature: 300\nfluid: {}\nsurface: {tension_form: conservative, marangoni: true}\n",
     NAME ":18: 'surface.tension_form: conservative' has no Marangoni force: use 'tension_form: csf' with "
          "'marangoni: true'"},
    {"conservative tension with a temperature-dependent sigma",
     SURFACE_MAT(", surface_tension: 1, surface_tension_slope: -1e-4") "    temperature: 300\nfluid: {}\n"
         "surface: {tension_form: conservative}\n",
     NAME ":9: material 'water': 'surface.tension_form: conservative' needs a constant surface tension (no "
          "'surface_tension_slope' or 'surfactant_excess'); use 'tension_form: csf'"},
    {"unknown tension form", SURFACE_MAT("") "fluid: {}\nsurface: {tension_form: stress}\n",
     NAME ":17: 'surface.tension_form' must be one of csf, conservative; got 'stress'"},
    {"surface smoothing below the fluid's", SURFACE_MAT("") "fluid: {}\nsurface: {h_over_dx: 1.1}\n",
     NAME ":17: 'surface.h_over_dx' (1.1) must be at least 'h_over_dx' (1.2)"},
    {"surface normal cut-off above 1", SURFACE_MAT("") "fluid: {}\nsurface: {normal_cutoff: 2}\n",
     NAME ":17: 'surface.normal_cutoff' must be in (0, 1], got 2"},
    {"surface interface viscosity negative", SURFACE_MAT("") "fluid: {}\nsurface: {interface_viscosity: -1}\n",
     NAME ":17: 'surface.interface_viscosity' must be >= 0, got -1"},
    {"sigma slope without temperatures", SURFACE_MAT(", surface_tension_slope: -1e-3") "fluid: {}\nsurface: {}\n",
     NAME ":9: material 'water': a temperature-dependent surface tension needs temperatures: give "
          "every geometry block a 'temperature'"},
    {"surfactant without activity",
     SURFACE_MAT(", surfactant_excess: 1.3e-5, surfactant_segregation: 0.0032") "    temperature: 300\n"
     "fluid: {}\nsurface: {}\n",
     NAME ":9: material 'water': 'surfactant_excess' needs 'surfactant_segregation' and "
          "'surfactant_activity' > 0 (and 'surfactant_enthalpy')"},
    {"negative surface tension", SURFACE_MAT(", surface_tension: -1") "fluid: {}\nsurface: {}\n",
     NAME ":9: 'materials[0].surface_tension' must be >= 0, got -1"},
    {"contact angle above 180", SURFACE_MAT(", contact_angle: 190") "fluid: {}\nsurface: {}\n",
     NAME ":9: 'materials[0].contact_angle' must be in (0, 180], got 190"},
    {"contact angle zero", SURFACE_MAT(", contact_angle: 0") "fluid: {}\nsurface: {}\n",
     NAME ":9: 'materials[0].contact_angle' must be in (0, 180], got 0"},
    {"contact angle without surface", SURFACE_MAT(", contact_angle: 60") "fluid: {}\n",
     NAME ":9: material 'water' has a 'contact_angle', which needs the surface module (a 'surface:' section)"},
    {"wetting transition range not positive", SURFACE_MAT(", wetting_transition_range: 0") "fluid: {}\nsurface: {}\n",
     NAME ":9: 'materials[0].wetting_transition_range' must be > 0, got 0"},
    {"fluid integration unknown", SURFACE_MAT("") "fluid: {integration: euler}\n",
     NAME ":16: 'fluid.integration' must be one of leapfrog, verlet; got 'euler'"},
    {"verlet with the renormalised pressure force", SURFACE_MAT("") "fluid: {integration: verlet}\n",
     NAME ":16: 'fluid.integration: verlet' serves the fluid module alone with 'pressure_gradient: symmetric', "
          "and this case has a pressure_gradient other than 'symmetric'; use 'integration: leapfrog'"},
    {"verlet with surface tension",
     SURFACE_MAT("") "fluid:\n  pressure_gradient: symmetric\n  integration: verlet\nsurface: {}\n",
     NAME ":18: 'fluid.integration: verlet' serves the fluid module alone with 'pressure_gradient: symmetric', "
          "and this case has a 'surface:' section; use 'integration: leapfrog'"},
    {"verlet with shifting", SURFACE_MAT("") "fluid: {integration: verlet, pressure_gradient: symmetric, shifting: 2}\n",
     NAME ":16: 'fluid.integration: verlet' serves the fluid module alone with 'pressure_gradient: symmetric', "
          "and this case has 'shifting'; use 'integration: leapfrog'"},
    {"verlet with the transport velocity",
     SURFACE_MAT("") "fluid: {integration: verlet, pressure_gradient: symmetric, transport_pressure: 1e4}\n",
     NAME ":16: 'fluid.integration: verlet' serves the fluid module alone with 'pressure_gradient: symmetric', "
          "and this case has 'transport_pressure'; use 'integration: leapfrog'"},
    {"verlet above its CFL", SURFACE_MAT("") "fluid: {integration: verlet, pressure_gradient: symmetric, cfl: 0.25}\n",
     NAME ":16: 'fluid.cfl' is 0.25; with 'integration: verlet' it must be at most 0.2 (the two-step scheme's "
          "stability limit, omega dt < 1, is half the leapfrog's)"},
    {"verlet steps zero", SURFACE_MAT("") "fluid: {verlet_steps: 0}\n",
     NAME ":16: 'fluid.verlet_steps' must be >= 1, got 0"},
    {"thermal integration unknown", BASE2 "thermal: {integration: implicit}\n",
     NAME ":17: 'thermal.integration' must be one of explicit, midpoint; got 'implicit'"},

    /* rho0(T) and the temperature history */
    {"density table without temperatures", HEAD2 "materials:\n  - name: water\n    density: [[300, 1000], [400, 900]]\n" GEO_BOX,
     NAME ":9: material 'water' has a temperature-dependent 'density', but the particles have no temperature: "
          "give the geometry blocks a 'temperature' or add a 'temperature_history'"},
    {"density table value not positive", HEAD2 "materials:\n  - name: water\n    density: [[300, 1000], [400, 0]]\n" GEO_BOX,
     NAME ":10: 'materials[0].density[1]' value must be > 0, got '0'"},
    {"temperature history with thermal",
     HEAD2 "materials:\n  - {name: water, density: 1, specific_heat: 1, conductivity: 1}\n" GEO_BOX
           "    temperature: 300\ntemperature_history: {reference: 300, amplitude: 10, frequency: 1}\nthermal: {}\n",
     NAME ":17: 'temperature_history' prescribes the temperature; it cannot be used with the thermal module (the "
          "'thermal:' section on line 18)"},
    {"temperature history with a block temperature",
     BASE2 "    temperature: 300\ntemperature_history: {reference: 300, amplitude: 10, frequency: 1}\n",
     NAME ":12: geometry[0] has a 'temperature', but 'temperature_history' (line 18) sets every particle's "
          "temperature; remove one of them"},
    {"temperature history below 0 K", BASE2 "temperature_history: {reference: 30, amplitude: -50, frequency: 1}\n",
     NAME ":17: 'temperature_history.amplitude' (-50 K) takes the temperature to -20 K, below 0 K"},
    {"ramp without duration", BASE2 "temperature_history: {form: ramp, reference: 300, amplitude: 10}\n",
     NAME ":17: missing required key 'duration' in temperature_history (form 'ramp')"},
    {"frequency of a ramp",
     BASE2 "temperature_history: {form: ramp, reference: 300, amplitude: 10, duration: 1, frequency: 2}\n",
     NAME ":17: 'temperature_history.frequency' does not apply to form 'ramp'"},
    {"layers negative", BASE2 "    layers: -2\n",
     NAME ":17: 'geometry[0].layers' must be >= 0, got -2"},
    {"domain max not above min", "dimension: 2\ndomain:\n  min: [0, 0]\n  max: [1, 0]\n",
     NAME ":4: 'domain.max[1]' (0) must be > 'domain.min[1]' (0)"},
    {"box max below min",
     HEAD2 MATS GEO_START "    shape: box\n    min: [0, 0]\n"
                          "    max: [-0.5, 0.5]\n",
     NAME ":16: 'geometry[0].max[0]' (-0.5) must be > 'geometry[0].min[0]' (0)"},
#define BED GEO_START "    shape: powder_bed\n    min: [0, 0]\n    max: [1, 0.2]\n"
    {"powder bed without grain radius", HEAD2 MATS BED,
     NAME ":12: missing required key 'grain_radius' in geometry[0] (shape 'powder_bed')"},
    {"powder bed log-normal without log_sd",
     HEAD2 MATS BED "    distribution: lognormal\n    grain_radius: 0.05\n"
                    "    grain_radius_min: 0.04\n    grain_radius_max: 0.06\n",
     NAME ":12: missing required key 'log_sd' in geometry[0] (distribution 'lognormal')"},
    {"powder bed log_sd on a regular bed", HEAD2 MATS BED "    grain_radius: 0.05\n    log_sd: 0.2\n",
     NAME ":18: 'geometry[0].log_sd' does not apply to distribution 'regular'"},
    {"powder bed seed on a regular bed", HEAD2 MATS BED "    grain_radius: 0.05\n    seed: 3\n",
     NAME ":18: 'geometry[0].seed' does not apply to distribution 'regular'"},
    {"powder bed small_radius on a log-normal bed",
     HEAD2 MATS BED "    distribution: lognormal\n    grain_radius: 0.05\n    log_sd: 0.2\n"
                    "    grain_radius_min: 0.04\n    grain_radius_max: 0.06\n    small_radius: 0.01\n",
     NAME ":22: 'geometry[0].small_radius' does not apply to distribution 'lognormal'"},
    {"powder bed log-normal radii out of order",
     HEAD2 MATS BED "    distribution: lognormal\n    grain_radius: 0.05\n    log_sd: 0.2\n"
                    "    grain_radius_min: 0.06\n    grain_radius_max: 0.08\n",
     NAME ":21: 'geometry[0].grain_radius_min' (0.06 m), 'grain_radius' (0.05 m) and "
          "'grain_radius_max' (0.08 m) must be in increasing order, min below max"},
#if !AMSPH_DOUBLE
    /* floats 1e4 m from the origin are 1.2 mm apart, 0.12 dx */
    {"domain too far from the origin for its dx",
     "dimension: 2\ndomain:\n  min: [0, 0]\n  max: [1e4, 1]\ndx: 0.01\nend_time: 1\noutput_interval: 0.1\n" MATS
         GEO_BOX,
     NAME ":3: the domain reaches 10000 m from the origin along x, where the particles' positions (float) are "
          "0.0012 m = 0.12 dx apart (at most 0.01 dx); move the domain next to the origin or make dx larger"},
#endif
    /* 1.6e-9 of the draws within the range: the deposit would redraw without end */
    {"powder bed log-normal too wide for its range",
     HEAD2 MATS BED "    distribution: lognormal\n    grain_radius: 0.05\n    log_sd: 1e8\n"
                    "    grain_radius_min: 0.04\n    grain_radius_max: 0.06\n",
     NAME ":19: 'geometry[0].log_sd' (1e+08) leaves a fraction 1.62e-09 of the log-normal's draws within "
          "[grain_radius_min, grain_radius_max] (at least 0.001: the others are drawn again); make log_sd "
          "smaller or the range wider"},
    {"powder bed mixed without small radius",
     HEAD2 MATS BED "    distribution: mixed\n    grain_radius: 0.05\n",
     NAME ":12: missing required key 'small_radius' in geometry[0] (distribution 'mixed')"},
    {"powder bed mixed small radius not smaller",
     HEAD2 MATS BED "    distribution: mixed\n    grain_radius: 0.05\n    small_radius: 0.05\n",
     NAME ":19: 'geometry[0].small_radius' (0.05 m) must be < 'grain_radius' (0.05 m)"},
    {"powder bed small fraction above 1",
     HEAD2 MATS BED "    distribution: mixed\n    grain_radius: 0.05\n    small_radius: 0.02\n"
                    "    small_fraction: 1.5\n",
     NAME ":20: 'geometry[0].small_fraction' must be in [0, 1], got 1.5"},
    {"powder bed region thinner than a grain", HEAD2 MATS BED "    grain_radius: 0.15\n",
     NAME ":16: the powder bed's region is 0.2 m across along y, less than the diameter 0.3 m of its "
          "largest grain"},
    {"powder bed distribution unknown", HEAD2 MATS BED "    grain_radius: 0.05\n    distribution: gaussian\n",
     NAME ":18: 'geometry[0].distribution' must be one of regular, lognormal, mixed; got 'gaussian'"},
    {"grain radius on a box", BASE2 "    grain_radius: 0.05\n",
     NAME ":17: 'geometry[0].grain_radius' does not apply to shape 'box'"},
#undef BED
    {"cylinder axis zero",
     HEAD3 MATS GEO_START "    shape: cylinder\n    center: [0, 0, 0]\n"
                          "    axis: [0, 0, 0]\n    radius: 0.1\n    length: 0.2\n",
     NAME ":16: 'geometry[0].axis' must not be zero"},

    /* the laser module */
    {"laser missing power", BASE2 "laser: {radius: 1e-4, absorption_coefficient: 10, start: [0.5, 0.5]}\n",
     NAME ":17: missing required key 'power' in laser"},
    /* a beam narrower than its bins: the sampled Gaussian misses its power */
    {"laser narrower than its bins",
     BASE2 "laser: {power: 1, radius: 0.005, absorption_coefficient: 10, start: [0.5, 0.5]}\n",
     NAME ":17: 'laser.radius' (0.005 m) is below the spacing at which the beam is sampled, laser.bin_size "
          "(0.01 m): the samples would not hold the beam's power; make the radius at least that, or the "
          "spacing smaller"},
    {"laser unknown key", BASE2 "laser: {powr: 1}\n",
     NAME ":17: unknown key 'powr' in laser; did you mean 'power'?"},
    {"laser power zero", BASE2 "laser: {power: 0, radius: 1, absorption_coefficient: 1, start: [0, 0]}\n",
     NAME ":17: 'laser.power' must be > 0, got 0"},
    {"laser absorption unknown", BASE2 "laser: {power: 1, radius: 1, absorption: ray, start: [0, 0]}\n",
     NAME ":17: 'laser.absorption' must be one of volumetric, surface; got 'ray'"},
    {"laser volumetric without coefficient", BASE2 "laser: {power: 1, radius: 1, start: [0, 0]}\n",
     NAME ":17: missing required key 'absorption_coefficient' in laser (absorption 'volumetric')"},
    {"laser coefficient for surface",
     BASE2 "laser: {power: 1, radius: 1, absorption: surface, absorption_coefficient: 5, start: [0, 0]}\n",
     NAME ":17: 'laser.absorption_coefficient' does not apply to absorption 'surface'"},
    {"laser absorptivity above 1, volumetric (default)",
     BASE2 "laser: {power: 1, radius: 1, absorption_coefficient: 5, absorptivity: 1.5, start: [0, 0]}\n",
     NAME ":17: 'laser.absorptivity' must be in (0, 1], got 1.5"},
    {"laser absorptivity above 1",
     BASE2 "laser: {power: 1, radius: 1, absorption: surface, absorptivity: 1.5, start: [0, 0]}\n",
     NAME ":17: 'laser.absorptivity' must be in (0, 1], got 1.5"},
    {"laser absorptivity zero",
     BASE2 "laser: {power: 1, radius: 1, absorption: surface, absorptivity: 0, start: [0, 0]}\n",
     NAME ":17: 'laser.absorptivity' must be in (0, 1], got 0"},
    {"laser bins for surface",
     BASE2 "laser: {power: 1, radius: 1, absorption: surface, bin_size: 0.01, start: [0, 0]}\n",
     NAME ":17: 'laser.bin_size' does not apply to absorption 'surface'"},
    {"laser window below 1",
     BASE2 "laser: {power: 1, radius: 1, absorption_coefficient: 1, window: 0.5, start: [0, 0]}\n",
     NAME ":17: 'laser.window' must be >= 1, got 0.5"},
    {"laser direction zero",
     BASE2 "laser: {power: 1, radius: 1, absorption_coefficient: 1, direction: [0, 0], start: [0, 0]}\n",
     NAME ":17: 'laser.direction' must not be zero"},
    {"laser direction along a periodic axis",
     "dimension: 2\ndomain: {min: [0, 0], max: [1, 1], periodic: [true, false]}\ndx: 0.01\nend_time: 1\n"
     "output_interval: 0.1\n" MATS GEO_BOX
     "laser: {power: 1, radius: 1, absorption_coefficient: 1, direction: [1, -1], start: [0, 0]}\n",
     NAME ":15: 'laser.direction' must be perpendicular to the periodic direction x (a beam along it "
          "would wrap around the domain)"},
    {"laser default direction along a periodic axis",
     "dimension: 2\ndomain: {min: [0, 0], max: [1, 1], periodic: [false, true]}\ndx: 0.01\nend_time: 1\n"
     "output_interval: 0.1\n" MATS GEO_BOX "laser:\n  power: 1\n  radius: 1\n"
     "  absorption_coefficient: 1\n  start: [0, 0]\n",
     NAME ":16: 'laser.direction' must be perpendicular to the periodic direction y (a beam along it "
          "would wrap around the domain)"},
    {"laser off before on",
     BASE2 "laser: {power: 1, radius: 1, absorption_coefficient: 1, start: [0, 0], on_time: 2, off_time: 1}\n",
     NAME ":17: 'laser.off_time' (1 s) must be > 'laser.on_time' (2 s)"},
    {"laser off at on",
     BASE2 "laser: {power: 1, radius: 1, absorption_coefficient: 1, start: [0, 0], on_time: 1, off_time: 1}\n",
     NAME ":17: 'laser.off_time' (1 s) must be > 'laser.on_time' (1 s)"},
    {"laser ramps overlap",
     BASE2 "laser: {power: 1, radius: 1, absorption_coefficient: 1, start: [0, 0], off_time: 1,\n"
           "        ramp_time: 0.6}\n",
     NAME ":18: 'laser.ramp_time' (0.6 s) must be at most half of off_time - on_time (1 s): the ramps "
          "up and down would overlap"},
    {"laser start missing", BASE2 "laser: {power: 1, radius: 1, absorption_coefficient: 1}\n",
     NAME ":17: missing required key 'start' in laser"},
    {"laser path empty",
     BASE2 "laser: {power: 1, radius: 1, absorption_coefficient: 1, start: [0, 0], path: []}\n",
     NAME ":17: 'laser.path' must have at least 1 entry"},
    {"laser path speed zero",
     BASE2 "laser:\n  power: 1\n  radius: 1\n  absorption_coefficient: 1\n  start: [0, 0]\n"
           "  path:\n    - {to: [1, 0], speed: 1}\n    - {to: [1, 1], speed: 0}\n",
     NAME ":24: 'laser.path[1].speed' must be > 0, got 0"},
    {"laser path point in 3 numbers",
     BASE2 "laser:\n  power: 1\n  radius: 1\n  absorption_coefficient: 1\n  start: [0, 0]\n"
           "  path: [{to: [1, 0, 0], speed: 1}]\n",
     NAME ":22: 'laser.path[0].to' must have 2 numbers (dimension 2), got 3"},
    {"laser path entry missing speed",
     BASE2 "laser:\n  power: 1\n  radius: 1\n  absorption_coefficient: 1\n  start: [0, 0]\n"
           "  path:\n    - to: [1, 0]\n",
     NAME ":23: missing required key 'speed' in laser.path[0]"},

    /* list lengths */
    {"domain.min too long", "dimension: 2\ndomain:\n  min: [0, 0, 0]\n  max: [1, 1]\n",
     NAME ":3: 'domain.min' must have 2 numbers (dimension 2), got 3"},
    {"periodic too short",
     "dimension: 3\ndomain:\n  min: [0, 0, 0]\n  max: [1, 1, 1]\n"
     "  periodic: [true]\n",
     NAME ":5: 'domain.periodic' must have 3 booleans (dimension 3), got 1"},
    {"cylinder centre in 2 numbers",
     HEAD3 MATS GEO_START "    shape: cylinder\n"
                          "    center: [0, 0]\n",
     NAME ":15: 'geometry[0].center' must have 3 numbers (dimension 3), got 2"},
    {"no materials", HEAD2 "materials: []\n" GEO_BOX,
     NAME ":8: 'materials' must have at least 1 entry"},

    /* missing keys */
    {"missing dx",
     "dimension: 2\ndomain:\n  min: [0, 0]\n  max: [1, 1]\nend_time: 1\n"
     "output_interval: 0.1\n" MATS GEO_BOX,
     NAME ":1: missing required key 'dx' in top level"},
    {"missing dimension", "dx: 1\n", NAME ":1: missing required key 'dimension' in top level"},
    {"missing domain.max", "dimension: 2\ndomain:\n  min: [0, 0]\n",
     NAME ":3: missing required key 'max' in domain"},
    {"missing density", HEAD2 "materials:\n  - name: water\n" GEO_BOX,
     NAME ":9: missing required key 'density' in materials[0]"},
    {"missing shape", HEAD2 MATS GEO_START,
     NAME ":12: missing required key 'shape' in geometry[0]"},
    {"missing radius of circle", HEAD2 MATS GEO_START "    shape: circle\n    center: [0, 0]\n",
     NAME ":12: missing required key 'radius' in geometry[0] (shape 'circle')"},
    {"missing geometry", HEAD2 MATS, NAME ":1: missing required key 'geometry' in top level"},

    /* choices */
    {"kernel cubic", BASE2 "kernel: cubic\n",
     NAME ":17: 'kernel' must be one of wendland, quintic; got 'cubic'"},
    {"backend cuda", BASE2 "backend: cuda\n",
     NAME ":17: 'backend' must be one of openmp, opencl; got 'cuda'"},
    {"kind gas", HEAD2 MATS "geometry:\n  - shape: box\n    kind: gas\n",
     NAME ":13: 'geometry[0].kind' must be one of fluid, wall, solid, grain; got 'gas'"},
    {"grain block without grains", HEAD2 FLUID_MATS GEO_GRAIN,
     NAME ":12: geometry[0] is of kind 'grain', which needs a 'grains:' section (with 'contact_stiffness')"},
    {"grains without a grain block", HEAD2 FLUID_MATS GEO_BOX "grains: {contact_stiffness: 1}\n",
     NAME ":17: 'grains' is set, but no geometry block is of kind 'grain'"},
    {"grains without fluid", HEAD2 MATS GEO_GRAIN "grains: {contact_stiffness: 1}\n",
     NAME ":13: 'grains' needs the fluid module (a 'fluid:' section)"},
    {"grains without stiffness", HEAD2 FLUID_MATS GEO_GRAIN "grains: {contact_damping: 1}\n",
     NAME ":13: missing required key 'contact_stiffness' in grains"},
    {"negative contact damping", HEAD2 FLUID_MATS GEO_GRAIN "grains: {contact_stiffness: 1, contact_damping: -1}\n",
     NAME ":13: 'grains.contact_damping' must be >= 0, got -1"},
    {"grains on a periodic axis",
     "dimension: 2\ndomain:\n  min: [0, 0]\n  max: [1, 1]\n  periodic: [true, false]\n"
     "dx: 0.01\nend_time: 1\noutput_interval: 0.1\n" FLUID_MATS GEO_GRAIN "grains: {contact_stiffness: 1}\n",
     NAME ":14: 'grains' cannot be used with a periodic axis (x)"},
    {"shape is a list", HEAD2 MATS GEO_START "    shape: [box]\n",
     NAME ":14: 'geometry[0].shape' must be one of box, circle, sphere, cylinder, powder_bed; got a list"},
    {"sphere in 2D", HEAD2 MATS GEO_START "    shape: sphere\n",
     NAME ":14: 'geometry[0].shape': 'sphere' exists only in 3D, but dimension is 2"},
    {"circle in 3D", HEAD3 MATS GEO_START "    shape: circle\n",
     NAME ":14: 'geometry[0].shape': 'circle' exists only in 2D, but dimension is 3"},
    {"key not for the shape", BASE2 "    radius: 0.1\n",
     NAME ":17: 'geometry[0].radius' does not apply to shape 'box'"},
    {"layers on a circle",
     HEAD2 MATS GEO_START "    shape: circle\n    center: [0, 0]\n"
                          "    radius: 0.1\n    layers: 2\n",
     NAME ":17: 'geometry[0].layers' does not apply to shape 'circle'"},

    /* materials */
    {"duplicate material name", HEAD2 MATS "  - name: water\n    density: 1\n" GEO_BOX,
     NAME ":11: duplicate material name 'water' (first on line 9)"},
    {"unknown material",
     HEAD2 MATS "  - name: air\n    density: 1.2\n"
                "geometry:\n  - shape: box\n    kind: fluid\n    material: oil\n",
     NAME ":16: unknown material 'oil' in 'geometry[0].material'; known materials: water, air"},
    {"material is empty", HEAD2 MATS "geometry:\n  - shape: box\n    kind: fluid\n    material:\n",
     NAME ":14: 'geometry[0].material' must be a material name, got an empty value"},

    /* open faces */
    {"open without layers", BASE2 "    open: [+y]\n",
     NAME ":17: 'geometry[0].open' needs 'layers' > 0 (open faces of a wall)"},
    {"open unknown face", BASE2 "    layers: 3\n    open: [-x, top]\n",
     NAME ":18: 'geometry[0].open[1]' must be one of -x, +x, -y, +y, -z, +z; got 'top'"},
    {"open z face in 2D", BASE2 "    layers: 3\n    open:\n      - +z\n",
     NAME ":19: 'geometry[0].open[0]': '+z' exists only in 3D, but dimension is 2"},
    {"open face twice", BASE2 "    layers: 3\n    open: [+y, -x, +y]\n",
     NAME ":18: 'geometry[0].open[2]': face '+y' is listed twice"},
    {"open is a word", BASE2 "    layers: 3\n    open: +y\n",
     NAME ":18: 'geometry[0].open' must be a list of faces (-x, +x, -y, +y, -z, +z), got '+y'"},
};

static void run_bad_cases(void)
{
    char err[1024];
    for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
        const bad_case *t = &bad_cases[i];
        int rc = amsph_case_parse(t->text, strlen(t->text), NAME, &parsed, err, sizeof err);
        char what[2400];
        if (rc == 0)
            snprintf(what, sizeof what, "parsed, expected \"%s\"", t->expected);
        else
            snprintf(what, sizeof what, "got      \"%s\"\n     expected \"%s\"", err, t->expected);
        report(rc != 0 && strcmp(err, t->expected) == 0, t->name, what);
    }
}

/* A list with one entry too many (entry: a format for entry number i + 1). */
static void run_too_many(const char *head, const char *what, int count, const char *entry,
                         const char *expected)
{
    static char text[16384];
    size_t used = (size_t)snprintf(text, sizeof text, "%s%s:\n", head, what);
    for (int i = 0; i < count; i++)
        used += (size_t)snprintf(text + used, sizeof text - used, entry, i + 1);
    char err[512];
    int rc = amsph_case_parse(text, used, NAME, &parsed, err, sizeof err);
    char label[64];
    snprintf(label, sizeof label, "too many %s", what);
    report(rc != 0 && strcmp(err, expected) == 0, label, err);
}

/* amsph_case_load: errors reading the file, and a file read to its end. */
static void run_load(void)
{
    char err[512];
    int rc = amsph_case_load("no/such/case.yaml", &parsed, err, sizeof err);
    report(rc != 0 && strcmp(err, "no/such/case.yaml: cannot read case file: No such file or "
                                  "directory") == 0,
           "load missing file", err);
    rc = amsph_case_load("/dev/null", &parsed, err, sizeof err);
    report(rc != 0 && strcmp(err, "/dev/null:1: the case file is empty; expected keys such as "
                                  "'dimension'") == 0,
           "load empty file", err);
}

/* ---- good inputs --------------------------------------------------------- */

static char failure[512]; /* first mismatch of the current check */

static void expect(int ok, const char *what)
{
    if (!ok && !failure[0])
        snprintf(failure, sizeof failure, "%s", what);
}

static int near(double a, double b)
{
    return fabs(a - b) <= 1e-12 * (1 + fabs(b));
}

static int vec_is(const double v[3], double x, double y, double z)
{
    return near(v[0], x) && near(v[1], y) && near(v[2], z);
}

/* Everything optional left out: the defaults. */
static void check_default_values(const amsph_case *c)
{
    expect(c->dim == 2, "dim");
    expect(strcmp(c->path, NAME) == 0, "path");
    expect(vec_is(c->domain_min, 0, 0, 0) && vec_is(c->domain_max, 1, 1, 0), "domain");
    expect(!c->periodic[0] && !c->periodic[1] && !c->periodic[2], "periodic default");
    expect(near(c->dx, 0.01) && near(c->end_time, 1) && near(c->output_interval, 0.1), "times");
    expect(near(c->h_over_dx, 1.2), "h_over_dx default");
    expect(c->kernel == AMSPH_KERNEL_WENDLAND, "kernel default");
    expect(c->backend == AMSPH_BACKEND_OPENMP, "backend default");
    expect(c->device == -1, "device default");
    expect(vec_is(c->gravity, 0, 0, 0), "gravity default");
    expect(c->n_materials == 1 && strcmp(c->materials[0].name, "water") == 0, "materials");
    expect(c->materials[0].density.n == 1 && near(c->materials[0].density.v[0], 1000), "density");
    expect(c->materials[0].viscosity == 0 && c->materials[0].sound_speed == 0, "material defaults");
    expect(c->materials[0].phase == AMSPH_MATERIAL_LIQUID, "phase default");
    const amsph_geometry *g = &c->geometry[0];
    expect(c->n_geometry == 1, "n_geometry");
    expect(g->shape == AMSPH_SHAPE_BOX && g->kind == AMSPH_KIND_FLUID && g->material == 0, "box");
    expect(vec_is(g->min, 0, 0, 0) && vec_is(g->max, 0.5, 0.5, 0), "box corners");
    expect(g->layers == 0 && g->open_faces == 0, "layers default");
    expect(vec_is(g->velocity, 0, 0, 0), "velocity default");
    expect(!g->has_temperature, "temperature not set");
    expect(!g->fill, "fill default");
}

static void check_defaults(const amsph_case *c)
{
    check_default_values(c);
    expect(c->geometry[0].line == 12, "geometry line");
    expect(!c->laser.enabled, "no laser");
}

/* The sections of the defaults case in reverse order: geometry comes first. */
static void check_reversed(const amsph_case *c)
{
    check_default_values(c);
    expect(c->geometry[0].line == 2, "geometry line");
}

/* A 3D case with every key, written in an unusual order. */
static const char full3d[] =
    "geometry:\n"
    "  - radius: 0.1\n"
    "    length: 0.5\n"
    "    axis: [0, 0, 2]\n"
    "    center: [0.5, 0.5, 0]\n"
    "    material: oil\n"
    "    kind: solid\n"
    "    shape: cylinder\n"
    "    velocity: [0, 0, -1.5]\n"
    "  - shape: box\n"
    "    kind: wall\n"
    "    material: water\n"
    "    open: [+z, -x]\n"
    "    layers: 3\n"
    "    max: [1, 1, 0.8]\n"
    "    min: [0, 0, 0]\n"
    "  - {shape: sphere, kind: fluid, material: oil, center: [0.2, 0.3, 0.4],"
    " radius: 5e-2, temperature: 293.15}\n"
    "  - shape: cylinder\n"
    "    kind: fluid\n"
    "    material: water\n"
    "    center: [0, 0, 0]\n"
    "    axis: [1, 1, 0]\n"
    "    radius: 1\n"
    "    length: 1\n"
    "laser:\n"
    "  window: 4\n"
    "  bin_size: 0.015\n"
    "  ramp_time: 1e-4\n"
    "  off_time: 2e-3\n"
    "  on_time: 1e-3\n"
    "  path:\n"
    "    - {speed: 2, to: [0.5, 0.6, 0.8]}\n"
    "    - speed: 0.5\n"
    "      to: [0.7, 0.6, 0.8]\n"
    "  start: [0.5, 0.5, 0.8]\n"
    "  direction: [0, -2.5, 0]\n"
    "  absorption_coefficient: 2e3\n"
    "  absorption: volumetric\n"
    "  radius: 0.02\n"
    "  power: 150\n"
    "materials:\n"
    "  - name: water\n"
    "    sound_speed: 20\n"
    "    density: 1e3\n"
    "    viscosity: 1.0e-3\n"
    "  - density: 900\n"
    "    name: oil\n"
    "gravity: [0, 0, -9.81]\n"
    "device: 2\n"
    "backend: opencl\n"
    "kernel: quintic\n"
    "h_over_dx: 1.5\n"
    "output_interval: .05\n"
    "end_time: 2.\n"
    "dx: +0.02\n"
    "domain:\n"
    "  periodic: [true, false, true]\n"
    "  max: [1, 1, 1]\n"
    "  min: [0, 0, 0]\n"
    "dimension: 3\n";

static void check_full3d(const amsph_case *c)
{
    expect(c->dim == 3, "dim");
    expect(vec_is(c->domain_min, 0, 0, 0) && vec_is(c->domain_max, 1, 1, 1), "domain");
    expect(c->periodic[0] == 1 && c->periodic[1] == 0 && c->periodic[2] == 1, "periodic");
    expect(near(c->dx, 0.02) && near(c->end_time, 2) && near(c->output_interval, 0.05), "times");
    expect(near(c->h_over_dx, 1.5) && c->kernel == AMSPH_KERNEL_QUINTIC, "kernel");
    expect(c->backend == AMSPH_BACKEND_OPENCL && c->device == 2, "backend");
    expect(vec_is(c->gravity, 0, 0, -9.81), "gravity");
    expect(c->n_materials == 2, "n_materials");
    expect(strcmp(c->materials[0].name, "water") == 0 && near(c->materials[0].density.v[0], 1000) &&
               near(c->materials[0].viscosity, 1e-3) && near(c->materials[0].sound_speed, 20),
           "water");
    expect(strcmp(c->materials[1].name, "oil") == 0 && near(c->materials[1].density.v[0], 900) &&
               c->materials[1].viscosity == 0,
           "oil");
    expect(c->n_geometry == 4, "n_geometry");
    const amsph_geometry *cyl = &c->geometry[0], *box = &c->geometry[1];
    const amsph_geometry *ball = &c->geometry[2], *tilted = &c->geometry[3];
    expect(cyl->shape == AMSPH_SHAPE_CYLINDER && cyl->kind == AMSPH_KIND_SOLID &&
               cyl->material == 1,
           "cylinder");
    expect(vec_is(cyl->axis, 0, 0, 1) && vec_is(cyl->center, 0.5, 0.5, 0), "cylinder axis");
    expect(near(cyl->radius, 0.1) && near(cyl->length, 0.5), "cylinder size");
    expect(vec_is(cyl->velocity, 0, 0, -1.5) && cyl->line == 2, "cylinder velocity, line");
    expect(box->shape == AMSPH_SHAPE_BOX && box->kind == AMSPH_KIND_WALL && box->material == 0,
           "box");
    expect(box->layers == 3 && box->open_faces == (AMSPH_FACE_BIT(2, 1) | AMSPH_FACE_BIT(0, 0)),
           "open faces");
    expect(vec_is(box->min, 0, 0, 0) && vec_is(box->max, 1, 1, 0.8) && box->line == 10,
           "box corners, line");
    expect(ball->shape == AMSPH_SHAPE_SPHERE && ball->kind == AMSPH_KIND_FLUID &&
               ball->material == 1 && near(ball->radius, 0.05),
           "sphere");
    expect(ball->has_temperature && near(ball->temperature, 293.15), "temperature");
    expect(vec_is(ball->center, 0.2, 0.3, 0.4) && ball->line == 17, "sphere centre, line");
    expect(!cyl->has_temperature && !box->has_temperature, "no temperature");
    double r = 1 / sqrt(2);
    expect(vec_is(tilted->axis, r, r, 0), "axis normalised");
    const amsph_laser_settings *l = &c->laser;
    expect(l->enabled && near(l->power, 150) && near(l->radius, 0.02), "laser power, radius");
    expect(l->absorption == AMSPH_ABSORPTION_VOLUMETRIC && near(l->absorption_coefficient, 2000),
           "laser absorption");
    expect(vec_is(l->direction, 0, -1, 0), "laser direction normalised");
    expect(vec_is(l->start, 0.5, 0.5, 0.8) && l->n_path == 2, "laser start, path length");
    expect(vec_is(l->path[0].to, 0.5, 0.6, 0.8) && near(l->path[0].speed, 2), "laser path[0]");
    expect(vec_is(l->path[1].to, 0.7, 0.6, 0.8) && near(l->path[1].speed, 0.5), "laser path[1]");
    expect(near(l->on_time, 1e-3) && near(l->off_time, 2e-3) && near(l->ramp_time, 1e-4), "laser times");
    expect(near(l->bin_size, 0.015) && near(l->window, 4), "laser bins");
}

/* A surface-absorbing laser with every optional key left out. */
static const char laser2d[] = BASE2 "laser: {power: 100, radius: 0.02, absorption: surface, start: [0.5, 0.5]}\n";

static void check_laser2d(const amsph_case *c)
{
    check_default_values(c);
    const amsph_laser_settings *l = &c->laser;
    expect(l->enabled && near(l->power, 100) && near(l->radius, 0.02), "laser power, radius");
    expect(l->absorption == AMSPH_ABSORPTION_SURFACE && near(l->absorptivity, 1), "absorptivity default");
    expect(vec_is(l->direction, 0, -1, 0), "direction default: -y");
    expect(vec_is(l->start, 0.5, 0.5, 0) && l->n_path == 0, "start, no path");
    expect(l->on_time == 0 && isinf(l->off_time) && l->ramp_time == 0, "schedule defaults");
    expect(near(l->bin_size, c->dx), "bin_size default: dx");
    static amsph_case finer;
    finer = *c;
    amsph_case_set_spacing(&finer, 0.5 * c->dx);
    expect(near(finer.dx, 0.5 * c->dx) && near(finer.laser.bin_size, 0.5 * c->dx), "bin_size follows the spacing");
}

/* 2D with a circle, a tank open at the top, periodic x and gravity. */
static const char tank2d[] = "dimension: 2\n"
                             "domain: {min: [-1, -1], max: [1, 1], periodic: [true, false]}\n"
                             "dx: 1e-3\n"
                             "end_time: 10\n"
                             "output_interval: 20\n"
                             "gravity: [0, -9.81]\n"
                             "materials: [{name: water, density: 1000}]\n"
                             "geometry:\n"
                             "  - shape: box\n"
                             "    kind: wall\n"
                             "    material: water\n"
                             "    min: [-0.5, -0.5]\n"
                             "    max: [0.5, 0.5]\n"
                             "    layers: 2\n"
                             "    open: [+y]\n"
                             "  - shape: circle\n"
                             "    kind: fluid\n"
                             "    material: water\n"
                             "    center: [0, 0]\n"
                             "    radius: 0.25\n"
                             "    velocity: [1, 0]\n";

static void check_tank2d(const amsph_case *c)
{
    expect(vec_is(c->domain_min, -1, -1, 0) && vec_is(c->domain_max, 1, 1, 0), "domain");
    expect(c->periodic[0] == 1 && c->periodic[1] == 0, "periodic");
    expect(near(c->dx, 1e-3) && near(c->output_interval, 20), "dx, interval > end_time");
    expect(vec_is(c->gravity, 0, -9.81, 0), "gravity");
    expect(c->geometry[0].layers == 2 && c->geometry[0].open_faces == AMSPH_FACE_BIT(1, 1),
           "open top");
    const amsph_geometry *g = &c->geometry[1];
    expect(g->shape == AMSPH_SHAPE_CIRCLE && near(g->radius, 0.25), "circle");
    expect(vec_is(g->center, 0, 0, 0) && vec_is(g->velocity, 1, 0, 0), "circle vectors");
}

/* Material presets against PHYSICS.md "Materials": 304 steel (Russell 2018
 * Table 4.1), with its own density and one key overridden; Fuchs et al.'s
 * simplified steel alone; `none`. */
static const char presets2d[] = HEAD2 "materials:\n"
                                      "  - {name: a, preset: steel_304, density: 7900, viscosity: 0.02}\n"
                                      "  - {name: b, preset: steel_fuchs}\n"
                                      "  - {name: c, preset: none, density: 1000}\n"
                                      "geometry:\n"
                                      "  - {shape: box, kind: fluid, material: b, min: [0, 0], max: [0.5, 0.5]}\n";

static int constant_is(const amsph_property *p, double v)
{
    return p->n == 1 && near(p->v[0], v);
}

static void check_presets2d(const amsph_case *c)
{
    const amsph_material *a = &c->materials[0], *b = &c->materials[1], *none = &c->materials[2];
    expect(a->preset == AMSPH_PRESET_STEEL_304 && b->preset == AMSPH_PRESET_STEEL_FUCHS &&
               none->preset == AMSPH_PRESET_NONE,
           "preset values");
    expect(constant_is(&a->density, 7900) && near(a->viscosity, 0.02), "304: the material's own density and viscosity");
    expect(near(a->mushy_viscosity, 1.0), "304: mushy viscosity 1.0 Pa s (solid)");
    expect(constant_is(&a->specific_heat, 711.17) && constant_is(&a->liquid_specific_heat, 937.35),
           "304: c_p 711.17 -> 937.35");
    expect(constant_is(&a->conductivity, 20) && constant_is(&a->liquid_conductivity, 209.3), "304: k 20 -> 209.3");
    expect(near(a->melting_temperature, 1723) && near(a->melting_range, 100), "304: T_m 1723 K over 100 K");
    expect(a->latent_heat == 0 && a->emissivity == 0 && a->sound_speed == 0, "304: the other keys' defaults");
    expect(constant_is(&b->density, 7430) && near(b->viscosity, 6e-3) && near(b->mushy_viscosity, 6e-3),
           "Fuchs: rho0 7430, eta 6e-3 (mushy: the same)");
    expect(constant_is(&b->specific_heat, 965) && constant_is(&b->liquid_specific_heat, 965), "Fuchs: c_p 965");
    expect(constant_is(&b->conductivity, 35.95) && constant_is(&b->liquid_conductivity, 35.95), "Fuchs: k 35.95");
    expect(near(b->melting_temperature, 1700) && near(b->melting_range, 1) && b->latent_heat == 0,
           "Fuchs: T_m 1700 K, no latent heat");
    expect(constant_is(&none->density, 1000) && none->viscosity == 0 && none->specific_heat.n == 0 &&
               none->melting_temperature == 0,
           "none: defaults");
}

/* A density table and a ramp of the temperature. */
static const char isothermal2d[] = HEAD2 "materials:\n  - name: water\n    density: [[250, 1050], [350, 950]]\n    sound_speed: 10\n" GEO_BOX
    "temperature_history: {form: ramp, reference: 300, amplitude: -20, duration: 2}\n"
    "fluid: {smoothing_length: volume, max_smoothing_ratio: 1.25, continuity: corrected}\n";

static void check_isothermal2d(const amsph_case *c)
{
    expect(c->fluid.smoothing_length == SMOOTHING_VOLUME && near(c->fluid.max_smoothing_ratio, 1.25),
           "smoothing length following the volume");
    expect(c->fluid.continuity == CONTINUITY_CORRECTED, "corrected continuity");
    const amsph_property *rho0 = &c->materials[0].density;
    expect(rho0->n == 2 && near(rho0->T[0], 250) && near(rho0->v[0], 1050) && near(rho0->T[1], 350) &&
               near(rho0->v[1], 950),
           "density table");
    expect(near(amsph_material_density(&c->materials[0], 320), 980) &&
               near(amsph_material_density(&c->materials[0], 400), 950),
           "rho0(T), constant beyond the table");
    const amsph_temperature_history *h = &c->temperature_history;
    expect(h->enabled && h->form == AMSPH_HISTORY_RAMP && near(h->reference, 300) && near(h->amplitude, -20) &&
               near(h->duration, 2),
           "history");
    expect(near(amsph_temperature_history_at(h, 1), 290) && near(amsph_temperature_history_at(h, 5), 280),
           "T(t) of the ramp");
}

/* A droplet in a gas with barrier forces: the keys of the gas phase. */
static const char gas2d[] = HEAD2 "fluid:\n  pressure_gradient: multiphase\n"
                            "  barrier: {stiffness: 2, damping: 0.5, distance: 0.005}\n"
                            "materials:\n  - {name: water, density: 1000, sound_speed: 10}\n"
                            "  - {name: air, density: 10, sound_speed: 100, phase: gas}\n"
                            "geometry:\n  - {shape: circle, kind: fluid, material: water, center: [0.5, 0.5], radius: 0.2}\n"
                            "  - {shape: box, kind: fluid, material: air, min: [0, 0], max: [1, 1], fill: true}\n";

/* The Verlet scheme: its CFL defaults to 0.2, its Euler steps to one in 40. */
static const char verlet2d[] = HEAD2 "fluid: {integration: verlet, pressure_gradient: symmetric}\n"
                               "materials:\n  - {name: water, density: 1000, sound_speed: 10}\n" GEO_BOX;

static void check_verlet2d(const amsph_case *c)
{
    expect(c->fluid.integration == INTEGRATION_VERLET && c->fluid.pressure_gradient == PRESSURE_SYMMETRIC,
           "integration");
    expect(near(c->fluid.cfl, 0.2) && c->fluid.verlet_steps == 40, "verlet defaults");
}

static void check_gas2d(const amsph_case *c)
{
    const amsph_fluid_settings *f = &c->fluid;
    expect(f->pressure_gradient == PRESSURE_MULTIPHASE, "pressure_gradient");
    expect(f->continuity == CONTINUITY_PLAIN, "continuity default");
    expect(f->smoothing_length == SMOOTHING_FIXED && near(f->max_smoothing_ratio, 1.1), "smoothing length default");
    expect(near(f->barrier_stiffness, 2) && near(f->barrier_damping, 0.5) && near(f->barrier_distance, 0.005),
           "barrier");
    static amsph_case finer;
    finer = *c;
    amsph_case_set_spacing(&finer, 0.5 * c->dx);
    expect(near(finer.fluid.barrier_distance, 0.0025), "barrier distance follows the spacing");
    expect(c->materials[0].phase == AMSPH_MATERIAL_LIQUID && c->materials[1].phase == AMSPH_MATERIAL_GAS, "phase");
    expect(!c->geometry[0].fill && c->geometry[1].fill, "fill");
}

typedef struct {
    const char *name;
    const char *text;
    void (*check)(const amsph_case *c);
} good_case;

static const good_case good_cases[] = {
    {"defaults", BASE2, check_defaults},
    {"defaults, sections reversed", GEO_BOX MATS HEAD2, check_reversed},
    {"every key, 3D, shuffled", full3d, check_full3d},
    {"2D tank and circle", tank2d, check_tank2d},
    {"2D laser, surface absorption, defaults", laser2d, check_laser2d},
    {"material presets", presets2d, check_presets2d},
    {"2D density table, temperature ramp", isothermal2d, check_isothermal2d},
    {"2D droplet in a gas, barrier forces", gas2d, check_gas2d},
    {"2D Verlet, its defaults", verlet2d, check_verlet2d},
};

static void run_good_case(const char *name, const char *text, size_t len,
                          void (*check)(const amsph_case *c))
{
    char err[512], what[1024];
    failure[0] = '\0';
    if (amsph_case_parse(text, len, NAME, &parsed, err, sizeof err) != 0) {
        snprintf(what, sizeof what, "unexpected error \"%s\"", err);
        report(0, name, what);
        return;
    }
    check(&parsed);
    snprintf(what, sizeof what, "wrong %s", failure);
    report(!failure[0], name, what);
}

/* Same as BASE2 but with "\r\n" line ends. */
static size_t crlf_base(char *out, size_t size)
{
    size_t used = 0;
    for (const char *s = BASE2; *s && used + 2 < size; s++) {
        if (*s == '\n')
            out[used++] = '\r';
        out[used++] = *s;
    }
    return used;
}

static void run_good_cases(void)
{
    for (size_t i = 0; i < sizeof good_cases / sizeof good_cases[0]; i++) {
        const good_case *t = &good_cases[i];
        run_good_case(t->name, t->text, strlen(t->text), t->check);
    }
    char crlf[1024];
    run_good_case("defaults, CRLF line ends", crlf, crlf_base(crlf, sizeof crlf), check_defaults);
}

/* ---- robustness ---------------------------------------------------------- */

/* A failure message must be "case.yaml:LINE: text", on one line. */
static int well_formed(const char *err)
{
    size_t n = strlen(NAME);
    if (strncmp(err, NAME ":", n + 1) != 0 || !isdigit((unsigned char)err[n + 1]))
        return 0;
    const char *s = err + n + 1;
    while (isdigit((unsigned char)*s))
        s++;
    if (strncmp(s, ": ", 2) != 0 || s[2] == '\0')
        return 0;
    for (; *s; s++)
        if ((unsigned char)*s < 0x20)
            return 0;
    return 1;
}

/* Parses text that may or may not be valid; reports if a failure message
 * is malformed. Returns 1 if it parsed; the message is left in err. */
static int parse_any(const char *test, const char *text, size_t len, char err[256])
{
    if (amsph_case_parse(text, len, NAME, &parsed, err, 256) == 0)
        return 1;
    if (!well_formed(err)) {
        char what[512];
        snprintf(what, sizeof what, "malformed message \"%s\"", err);
        report(0, test, what);
    }
    return 0;
}

/* head, open repeated count times, middle, close repeated count times, tail. */
static char *build(const char *head, const char *open, size_t count, const char *middle,
                   const char *close, const char *tail, size_t *len)
{
    size_t hl = strlen(head), ol = strlen(open), ml = strlen(middle), cl = strlen(close);
    size_t total = hl + (ol + cl) * count + ml + strlen(tail);
    char *text = malloc(total + 1), *at = text;
    if (!text)
        exit(2);
    at += sprintf(at, "%s", head);
    for (size_t i = 0; i < count; i++)
        at += sprintf(at, "%s", open);
    at += sprintf(at, "%s", middle);
    for (size_t i = 0; i < count; i++)
        at += sprintf(at, "%s", close);
    sprintf(at, "%s", tail);
    *len = total;
    return text;
}

/* Inputs built to stress limits: each must fail quickly, without crashing,
 * with a message that contains `expected`. */
static void run_extremes(void)
{
    static const struct {
        const char *name, *head, *open;
        size_t count;
        const char *middle, *close, *tail, *expected;
    } extremes[] = {
        {"deep nesting", "dimension: 2\ndx: ", "[", 100000, "", "", "\n",
         ":2: lists or maps nested more than 1000 levels deep"},
        {"deep closed nesting", "dimension: 2\ndx: ", "[", 100000, "1", "]", "\n",
         ":2: lists or maps nested more than 1000 levels deep"},
        {"deep maps", "dimension: 2\ndomain: ", "{a: ", 100000, "1", "}", "\n",
         ":2: lists or maps nested more than 1000 levels deep"},
        {"nesting just allowed", DOMAIN2 "dx: ", "[", 1000, "1", "]", "\n",
         ":5: 'dx' must be a number, got a list"},
        {"huge key", "", "k", 2000000, "", "", ": 1\n", ":1: YAML syntax error"},
        {"long key", "", "k", 1000, "", "", ": 1\n", ":1: unknown key 'kkkk"},
        {"long number", DOMAIN2 "dx: 1.", "0", 100000, "", "", "\nend_time: -1\n",
         ":6: 'end_time' must be > 0, got -1"},
        {"long material name", HEAD2 "materials:\n  - name: ", "n", 100000, "", "", "\n",
         ":9: 'materials[0].name' is too long (100000 characters, at most 63)"},
        {"many keys", "", "dx: 1\n", 100000, "", "", "", ":2: duplicate key 'dx'"},
        {"many documents", "", "---\n", 10000, "", "", "", ":2: a second YAML document"},
    };
    for (size_t i = 0; i < sizeof extremes / sizeof extremes[0]; i++) {
        size_t len;
        char err[256];
        char *text = build(extremes[i].head, extremes[i].open, extremes[i].count,
                           extremes[i].middle, extremes[i].close, extremes[i].tail, &len);
        int ok = !parse_any(extremes[i].name, text, len, err) && strstr(err, extremes[i].expected);
        report(ok, extremes[i].name, err);
        free(text);
    }
    static const char with_nul[] = "dimension: 2\ndx: 1\0\nend_time: 1\n";
    char err[256];
    int ok = !parse_any("NUL byte", with_nul, sizeof with_nul - 1, err) &&
             strstr(err, ":2: unreadable text: control characters are not allowed");
    report(ok, "NUL byte", err);
}

/* A small linear congruential generator: the fuzz run is the same every time. */
static unsigned long long lcg_state = 20240601;

static unsigned next_random(unsigned bound)
{
    lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
    return (unsigned)((lcg_state >> 33) % bound);
}

/* One random edit of text (length *len, room for size bytes). */
static void mutate(char *text, size_t *len, size_t size)
{
    static const char interesting[] = "[]{}:,-#&*!|>'\"\n \t0123456789.e+";
    unsigned op = next_random(5);
    size_t at = *len ? next_random((unsigned)*len) : 0;
    char byte =
        next_random(2) ? interesting[next_random(sizeof interesting - 1)] : (char)next_random(256);
    if (op == 0 && *len) {
        text[at] = byte;
    } else if (op == 1 && *len) {
        memmove(text + at, text + at + 1, *len - at - 1);
        (*len)--;
    } else if (op == 2 && *len + 1 < size) {
        memmove(text + at + 1, text + at, *len - at);
        text[at] = byte;
        (*len)++;
    } else if (op == 3) {
        *len = at;
    } else if (*len) {
        /* duplicate a line-sized chunk somewhere else */
        size_t from = next_random((unsigned)*len), n = next_random(40);
        if (from + n > *len)
            n = *len - from;
        if (*len + n < size) {
            memmove(text + at + n, text + at, *len - at);
            memmove(text + at, text + (from >= at ? from + n : from), n);
            *len += n;
        }
    }
}

static void run_fuzz(void)
{
    enum { RUNS = 20000 };
    const char *seeds[] = {BASE2, full3d, tank2d};
    int parsed_ok = 0, before = failed;
    char text[8192], err[256];
    for (int run = 0; run < RUNS; run++) {
        const char *seed = seeds[run % 3];
        size_t len = strlen(seed);
        memcpy(text, seed, len);
        for (unsigned edits = 1 + next_random(4); edits > 0; edits--)
            mutate(text, &len, sizeof text);
        parsed_ok += parse_any("fuzz", text, len, err);
    }
    report(failed == before, "fuzz", "see above");
    printf("fuzz: %d runs, %d still valid\n", RUNS, parsed_ok);
}

int main(void)
{
    run_bad_cases();
    run_too_many(HEAD2, "materials", AMSPH_MAX_MATERIALS + 1, "  - {name: m%d, density: 1}\n",
                 NAME ":8: 'materials' has 17 entries; at most 16 are allowed");
    run_too_many(BASE2 "laser:\n  power: 1\n  radius: 1\n  absorption_coefficient: 1\n  start: [0, 0]\n",
                 "  path", AMSPH_MAX_LASER_PATH + 1, "    - {to: [0, %d], speed: 1}\n",
                 NAME ":22: 'laser.path' has 65 entries; at most 64 are allowed");
    run_too_many(HEAD2 MATS, "geometry", AMSPH_MAX_GEOMETRY + 1,
                 "  - {shape: box, kind: fluid, material: water, min: [0, 0], max: [1, %d]}\n",
                 NAME ":11: 'geometry' has 65 entries; at most 64 are allowed");
    run_load();
    run_good_cases();
    run_extremes();
    run_fuzz();
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
