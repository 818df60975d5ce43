/* Case files: YAML → validated amsph_case (see case.h).
 *
 * One schema table (`specs` below) describes every key: where it lives, its
 * type, unit, range, default and the variants (shapes) it applies to. The same table
 * drives parsing, validation, defaults and the Markdown key reference.
 *
 * Each map is read in two passes. The first collects the value node of every
 * key and rejects unknown and duplicate keys; the second walks the schema in
 * table order. So the order of keys in the file never matters: `dimension` is
 * always known before any vector is read, and all materials before geometry
 * refers to them by name. Rules that tie several keys together (max > min,
 * unique material names, ...) run after a map's keys are loaded. */
#include "case.h"
#include "real.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

#include "hash.h"

#define CASE_ERROR 2
#define MAX_FILE_BYTES (64u << 20) /* a case file is a few kB; refuse absurd ones */
#define SHOWN_MAX 40               /* user text longer than this is cut in messages */
#define PATH_LEN 96                /* key paths such as "geometry[12].open[3]" */
#define MAX_FLOW_DEPTH 1000        /* libyaml slows down quadratically with [ { nesting */

#if defined(__GNUC__)
#define PRINTF_LIKE(fmt, args) __attribute__((format(printf, fmt, args)))
#else
#define PRINTF_LIKE(fmt, args)
#endif

/* Enum fields are filled through int pointers. */
_Static_assert(sizeof(amsph_kernel_type) == sizeof(int), "enum size");
_Static_assert(sizeof(amsph_backend_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(amsph_shape) == sizeof(int), "enum size");
_Static_assert(sizeof(amsph_powder_distribution) == sizeof(int), "enum size");
_Static_assert(sizeof(amsph_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(amsph_absorption) == sizeof(int), "enum size");
_Static_assert(sizeof(amsph_material_preset) == sizeof(int), "enum size");
_Static_assert(sizeof(amsph_history_form) == sizeof(int), "enum size");
_Static_assert(sizeof(amsph_material_phase) == sizeof(int), "enum size");

/* ---- schema ------------------------------------------------------------ */

typedef enum {
    SEC_TOP,
    SEC_DOMAIN,
    SEC_FLUID,
    SEC_BARRIER,
    SEC_THERMAL,
    SEC_SURFACE,
    SEC_LASER,
    SEC_LASER_PATH,
    SEC_HISTORY,
    SEC_GRAINS,
    SEC_MATERIAL,
    SEC_GEOMETRY
} section_id;

/* How each section is named in the key reference. */
static const char *const section_prefix[] = {
    "",       "domain.",       "fluid.",       "fluid.barrier.", "thermal.", "surface.", "laser.", "laser.path[].",
    "temperature_history.", "grains.", "materials[].", "geometry[]."};

typedef enum {
    VT_INT,      /* int */
    VT_NUMBER,   /* double */
    VT_VECTOR,   /* double[3]: `dimension` numbers, the rest 0 */
    VT_BOOLS,    /* int[3]: `dimension` booleans, the rest 0 */
    VT_CHOICE,   /* int: the value of one of `choices` */
    VT_NAME,     /* char[AMSPH_NAME_LEN] */
    VT_MATERIAL, /* int: index of the material with the given name */
    VT_FACES,    /* unsigned: OR of the values of a list of `choices` */
    VT_MAP,      /* a nested map with the keys of section `sub` */
    VT_LIST,     /* a list of lo..hi maps with the keys of section `sub` */
    VT_PROPERTY  /* amsph_property: a number, or a list of [T, value] pairs */
} value_type;

enum {
    F_REQUIRED = 1u << 0,
    F_ABOVE_LO = 1u << 1,     /* value > lo */
    F_FROM_LO = 1u << 2,      /* value >= lo */
    F_UP_TO_HI = 1u << 3,     /* value <= hi */
    F_NO_DEFAULT = 1u << 4,   /* optional; absence is recorded (temperature) */
    F_SELECTS_VARIANT = 1u << 5 /* the value decides which variant-specific keys of the section
                                   apply (geometry: shape; laser: absorption) */
};

typedef struct {
    const char *name;
    int value;
    int dim; /* 0: any dimension; otherwise only this one */
} choice;

static const choice kernel_choices[] = {
    {"wendland", AMSPH_KERNEL_WENDLAND, 0}, {"quintic", AMSPH_KERNEL_QUINTIC, 0}, {NULL, 0, 0}};
static const choice backend_choices[] = {
    {"openmp", AMSPH_BACKEND_OPENMP, 0}, {"opencl", AMSPH_BACKEND_OPENCL, 0}, {NULL, 0, 0}};
static const choice shape_choices[] = {{"box", AMSPH_SHAPE_BOX, 0},
                                       {"circle", AMSPH_SHAPE_CIRCLE, 2},
                                       {"sphere", AMSPH_SHAPE_SPHERE, 3},
                                       {"cylinder", AMSPH_SHAPE_CYLINDER, 3},
                                       {"powder_bed", AMSPH_SHAPE_POWDER_BED, 0},
                                       {NULL, 0, 0}};
static const choice distribution_choices[] = {{"regular", AMSPH_POWDER_REGULAR, 0},
                                              {"lognormal", AMSPH_POWDER_LOGNORMAL, 0},
                                              {"mixed", AMSPH_POWDER_MIXED, 0},
                                              {NULL, 0, 0}};
static const choice kind_choices[] = {{"fluid", AMSPH_KIND_FLUID, 0},
                                      {"wall", AMSPH_KIND_WALL, 0},
                                      {"solid", AMSPH_KIND_SOLID, 0},
                                      {"grain", AMSPH_KIND_GRAIN, 0},
                                      {NULL, 0, 0}};
static const choice face_choices[] = {{"-x", (int)AMSPH_FACE_BIT(0, 0), 0},
                                      {"+x", (int)AMSPH_FACE_BIT(0, 1), 0},
                                      {"-y", (int)AMSPH_FACE_BIT(1, 0), 0},
                                      {"+y", (int)AMSPH_FACE_BIT(1, 1), 0},
                                      {"-z", (int)AMSPH_FACE_BIT(2, 0), 3},
                                      {"+z", (int)AMSPH_FACE_BIT(2, 1), 3},
                                      {NULL, 0, 0}};

static const choice diffusion_choices[] = {{"none", DIFFUSION_NONE, 0},
                                           {"molteni", DIFFUSION_MOLTENI, 0},
                                           {"russell", DIFFUSION_RUSSELL, 0},
                                           {"fourtakas", DIFFUSION_FOURTAKAS, 0},
                                           {NULL, 0, 0}};
static const choice gas_density_choices[] = {
    {"continuity", GAS_DENSITY_CONTINUITY, 0}, {"summation", GAS_DENSITY_SUMMATION, 0}, {NULL, 0, 0}};
static const choice continuity_choices[] = {
    {"plain", CONTINUITY_PLAIN, 0}, {"corrected", CONTINUITY_CORRECTED, 0}, {NULL, 0, 0}};
static const choice pressure_choices[] = {{"renormalised", PRESSURE_RENORMALISED, 0},
                                          {"symmetric", PRESSURE_SYMMETRIC, 0},
                                          {"multiphase", PRESSURE_MULTIPHASE, 0},
                                          {NULL, 0, 0}};
static const choice viscosity_choices[] = {{"laminar", VISCOSITY_LAMINAR, 0},
                                           {"artificial", VISCOSITY_ARTIFICIAL, 0},
                                           {NULL, 0, 0}};
static const choice tension_form_choices[] = {
    {"csf", TENSION_FORM_CSF, 0}, {"conservative", TENSION_FORM_CONSERVATIVE, 0}, {NULL, 0, 0}};
static const choice bool_choices[] = {{"false", 0, 0}, {"true", 1, 0}, {NULL, 0, 0}};
static const choice integration_choices[] = {{"explicit", AMSPH_THERMAL_EXPLICIT, 0},
                                             {"midpoint", AMSPH_THERMAL_MIDPOINT, 0},
                                             {NULL, 0, 0}};
static const choice slip_choices[] = {
    {"no_slip", WALL_NO_SLIP, 0}, {"free_slip", WALL_FREE_SLIP, 0}, {NULL, 0, 0}};
static const choice smoothing_choices[] = {
    {"fixed", SMOOTHING_FIXED, 0}, {"volume", SMOOTHING_VOLUME, 0}, {NULL, 0, 0}};
static const choice fluid_integration_choices[] = {
    {"leapfrog", INTEGRATION_LEAPFROG, 0}, {"verlet", INTEGRATION_VERLET, 0}, {NULL, 0, 0}};
static const choice absorption_choices[] = {{"volumetric", AMSPH_ABSORPTION_VOLUMETRIC, 0},
                                            {"surface", AMSPH_ABSORPTION_SURFACE, 0},
                                            {NULL, 0, 0}};
static const choice history_choices[] = {
    {"sine", AMSPH_HISTORY_SINE, 0}, {"ramp", AMSPH_HISTORY_RAMP, 0}, {NULL, 0, 0}};

static const choice phase_choices[] = {
    {"liquid", AMSPH_MATERIAL_LIQUID, 0}, {"gas", AMSPH_MATERIAL_GAS, 0}, {NULL, 0, 0}};

static const choice preset_choices[] = {{"none", AMSPH_PRESET_NONE, 0},
                                        {"steel_304", AMSPH_PRESET_STEEL_304, 0},
                                        {"steel_fuchs", AMSPH_PRESET_STEEL_FUCHS, 0},
                                        {NULL, 0, 0}};

/* The keys a material preset fills (PHYSICS.md "Materials"), as they would
 * be written in the case file. */
#define MAX_PRESET_KEYS 12
typedef struct {
    const char *key, *value;
} preset_key;

typedef struct {
    const char *source;
    preset_key keys[MAX_PRESET_KEYS];
} preset;

static const preset presets[] = {
    [AMSPH_PRESET_STEEL_304] =
        {"304 stainless steel, Russell 2018 §4.4 Table 4.1 (solid → liquid, blended by the liquid "
         "fraction; liquid conductivity ×10 for unresolved convection); its density law is not a "
         "preset value: give `density`",
         {{"viscosity", "0.01"},
          {"mushy_viscosity", "1.0"},
          {"specific_heat", "711.17"},
          {"liquid_specific_heat", "937.35"},
          {"conductivity", "20"},
          {"liquid_conductivity", "209.3"},
          {"melting_temperature", "1723"},
          {"melting_range", "100"}}},
    [AMSPH_PRESET_STEEL_FUCHS] =
        {"simplified stainless steel, Fuchs et al. 2022 Tables 1 and 2 (no latent heat; its phase "
         "switch at T_m becomes a 1 K mushy interval), with its evaporation constants",
         {{"density", "7430"},
          {"viscosity", "6.0e-3"},
          {"specific_heat", "965"},
          {"conductivity", "35.95"},
          {"melting_temperature", "1700"},
          {"melting_range", "1"},
          {"boiling_temperature", "3000"},
          {"recoil_pressure_constant", "5.4e4"},
          {"recoil_temperature_constant", "5e4"},
          {"evaporation_latent_heat", "6.583e6"},
          {"vapour_mass_constant", "1.1095e-3"},
          {"evaporation_enthalpy_reference", "663.731"}}},
};

#define VARIANT_BIT(v) (1u << (v))
#define BOX_ONLY VARIANT_BIT(AMSPH_SHAPE_BOX)
#define CYLINDER_ONLY VARIANT_BIT(AMSPH_SHAPE_CYLINDER)
#define POWDER_ONLY VARIANT_BIT(AMSPH_SHAPE_POWDER_BED)
#define ROUND_SHAPES (VARIANT_BIT(AMSPH_SHAPE_CIRCLE) | VARIANT_BIT(AMSPH_SHAPE_SPHERE) | CYLINDER_ONLY)
#define VOLUMETRIC_ONLY VARIANT_BIT(AMSPH_ABSORPTION_VOLUMETRIC)
#define SURFACE_ONLY VARIANT_BIT(AMSPH_ABSORPTION_SURFACE)
#define SINE_ONLY VARIANT_BIT(AMSPH_HISTORY_SINE)
#define RAMP_ONLY VARIANT_BIT(AMSPH_HISTORY_RAMP)

typedef struct {
    section_id section;
    const char *key;
    value_type type;
    const char *unit;      /* NULL: dimensionless */
    unsigned flags;        /* F_* */
    double lo, hi;         /* bounds per flags; VT_LIST: entry counts */
    double def;            /* default of an optional number, integer or choice */
    const choice *choices; /* VT_CHOICE, VT_FACES */
    section_id sub;        /* VT_MAP, VT_LIST: section of the nested keys */
    unsigned variants;     /* values of the section's F_SELECTS_VARIANT key (geometry: shapes)
                              the key applies to, as VARIANT_BITs; 0 = all */
    size_t offset;         /* field in amsph_case (top, domain, fluid, laser), amsph_material,
                              amsph_geometry or amsph_laser_segment */
    const char *rule;      /* rule across keys, checked in code; for the reference */
    const char *doc;
} key_spec;

#define CASE(field) offsetof(amsph_case, field)
#define FLUID(field) offsetof(amsph_case, fluid.field)
#define THERMAL(field) offsetof(amsph_case, thermal.field)
#define SURFACE(field) offsetof(amsph_case, surface.field)
#define LASER(field) offsetof(amsph_case, laser.field)
#define GRAINS(field) offsetof(amsph_case, grains.field)
#define SEGMENT(field) offsetof(amsph_laser_segment, field)
#define HISTORY(field) offsetof(amsph_case, temperature_history.field)
#define MAT(field) offsetof(amsph_material, field)
#define GEO(field) offsetof(amsph_geometry, field)

/* Table order is processing order (a section's keys are read in this order)
 * and the order of the reference. */
/* clang-format off */
static const key_spec specs[] = {
    {.section = SEC_TOP, .key = "dimension", .type = VT_INT,
     .flags = F_REQUIRED | F_FROM_LO | F_UP_TO_HI, .lo = 2, .hi = 3, .offset = CASE(dim),
     .doc = "Number of space dimensions"},
    {.section = SEC_TOP, .key = "domain", .type = VT_MAP, .flags = F_REQUIRED, .sub = SEC_DOMAIN,
     .doc = "Simulation domain (an axis-aligned box)"},
    {.section = SEC_DOMAIN, .key = "min", .type = VT_VECTOR, .unit = "m", .flags = F_REQUIRED,
     .offset = CASE(domain_min), .doc = "Lower corner of the domain"},
    {.section = SEC_DOMAIN, .key = "max", .type = VT_VECTOR, .unit = "m", .flags = F_REQUIRED,
     .offset = CASE(domain_max), .rule = "each > `min`", .doc = "Upper corner of the domain"},
    {.section = SEC_DOMAIN, .key = "periodic", .type = VT_BOOLS, .offset = CASE(periodic),
     .doc = "Per direction: whether the domain wraps around"},
    {.section = SEC_TOP, .key = "dx", .type = VT_NUMBER, .unit = "m",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = CASE(dx),
     .rule = "at least 100 times the spacing of the particles' float (or double) positions at the domain's "
             "far corner",
     .doc = "Initial particle spacing"},
    {.section = SEC_TOP, .key = "h_over_dx", .type = VT_NUMBER, .flags = F_FROM_LO | F_UP_TO_HI,
     .lo = 1, .hi = 3, .def = 1.2, .offset = CASE(h_over_dx),
     .doc = "Smoothing length divided by `dx`"},
    {.section = SEC_TOP, .key = "kernel", .type = VT_CHOICE, .choices = kernel_choices,
     .def = AMSPH_KERNEL_WENDLAND, .offset = CASE(kernel),
     .doc = "Smoothing kernel: Wendland C2 or quintic spline"},
    {.section = SEC_TOP, .key = "end_time", .type = VT_NUMBER, .unit = "s",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = CASE(end_time),
     .doc = "Simulated time at which the run stops"},
    {.section = SEC_TOP, .key = "output_interval", .type = VT_NUMBER, .unit = "s",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = CASE(output_interval),
     .rule = "at most 1e7 outputs (`end_time` / `output_interval`)",
     .doc = "Simulated time between snapshots"},
    {.section = SEC_TOP, .key = "backend", .type = VT_CHOICE, .choices = backend_choices,
     .def = AMSPH_BACKEND_OPENMP, .offset = CASE(backend),
     .doc = "Compute backend; `--backend` overrides"},
    {.section = SEC_TOP, .key = "device", .type = VT_INT, .flags = F_FROM_LO, .lo = -1, .def = -1,
     .offset = CASE(device), .doc = "OpenCL device index; -1: the first; `--device` overrides"},
    {.section = SEC_TOP, .key = "gravity", .type = VT_VECTOR, .unit = "m/s²",
     .offset = CASE(gravity), .doc = "Gravitational acceleration"},
    {.section = SEC_TOP, .key = "fluid", .type = VT_MAP, .sub = SEC_FLUID,
     .doc = "Weakly compressible fluid module; present: on"},
    {.section = SEC_FLUID, .key = "density_diffusion", .type = VT_CHOICE,
     .choices = diffusion_choices, .def = DIFFUSION_RUSSELL, .offset = FLUID(density_diffusion),
     .doc = "delta-SPH density diffusion: none, of rho (Molteni-Colagrossi), of rho - rho0 (Russell Eq. 3.53), of rho - rho_hydrostatic (Fourtakas et al. 2019)"},
    {.section = SEC_FLUID, .key = "delta", .type = VT_NUMBER, .flags = F_FROM_LO | F_UP_TO_HI,
     .lo = 0, .hi = 1, .def = 0.1, .offset = FLUID(delta), .doc = "delta-SPH coefficient"},
    {.section = SEC_FLUID, .key = "continuity", .type = VT_CHOICE, .choices = continuity_choices,
     .def = CONTINUITY_PLAIN, .offset = FLUID(continuity),
     .doc = "Velocity divergence of the continuity equation: plain (Russell Eq. 3.14), or with the kernel "
            "gradient corrected (Bonet & Lok 1999), exact for linear velocity fields at free surfaces too"},
    {.section = SEC_FLUID, .key = "pressure_gradient", .type = VT_CHOICE,
     .choices = pressure_choices, .def = PRESSURE_RENORMALISED, .offset = FLUID(pressure_gradient),
     .doc = "Pressure force: free-surface renormalised (Russell Eq. 3.17), plain symmetric, or "
            "multiphase: pressure and laminar viscosity in the (V_a² + V_b²) form with the "
            "density-weighted pair pressure (Fuchs et al. 2022 Eq. 23; for a gas phase)"},
    {.section = SEC_FLUID, .key = "viscosity", .type = VT_CHOICE, .choices = viscosity_choices,
     .def = VISCOSITY_LAMINAR, .offset = FLUID(viscosity),
     .doc = "Viscous force: laminar (Morris 1997, harmonic-mean mu) or Monaghan artificial"},
    {.section = SEC_FLUID, .key = "artificial_alpha", .type = VT_NUMBER, .flags = F_FROM_LO,
     .lo = 0, .def = 0.02, .offset = FLUID(artificial_alpha),
     .doc = "Monaghan's alpha for `viscosity: artificial`"},
    {.section = SEC_FLUID, .key = "background_pressure", .type = VT_NUMBER, .unit = "Pa",
     .def = 0, .offset = FLUID(background_pressure), .doc = "Pressure added to the equation of state"},
    {.section = SEC_FLUID, .key = "clamp_negative_pressure", .type = VT_CHOICE,
     .choices = bool_choices, .def = 0, .offset = FLUID(clamp_negative_pressure),
     .doc = "Fluid pressure below the background pressure is raised to it (no tension: "
            "suppresses the tensile instability of free-surface flows)"},
    {.section = SEC_FLUID, .key = "tensile_correction", .type = VT_NUMBER, .flags = F_FROM_LO | F_UP_TO_HI,
     .lo = 0, .hi = 1, .def = 0, .offset = FLUID(tensile_correction),
     .doc = "Monaghan (2000) artificial pressure epsilon: pairs under tension (p below the background "
            "pressure) repel as (W(r)/W(dx))^4 (fluid pairs only); 0: off"},
    {.section = SEC_FLUID, .key = "wall_slip", .type = VT_CHOICE, .choices = slip_choices,
     .def = WALL_NO_SLIP, .offset = FLUID(wall_slip), .doc = "Wall condition for the velocity"},
    {.section = SEC_FLUID, .key = "cfl", .type = VT_NUMBER, .flags = F_ABOVE_LO | F_UP_TO_HI,
     .lo = 0, .hi = 1, .def = 0.25, .offset = FLUID(cfl),
     .rule = "with `integration: verlet` at most 0.2, its default there",
     .doc = "Acoustic CFL number: dt <= cfl h / (c0 + max |u|)"},
    {.section = SEC_FLUID, .key = "dt_min", .type = VT_NUMBER, .unit = "s", .flags = F_FROM_LO,
     .lo = 0, .def = 0, .offset = FLUID(dt_min),
     .doc = "A time step below this stops the run; 0: 1e-6 of the first step"},
    {.section = SEC_FLUID, .key = "min_pair_distance", .type = VT_NUMBER,
     .flags = F_FROM_LO | F_UP_TO_HI, .lo = 0, .hi = 1, .def = 0.3,
     .offset = FLUID(min_pair_distance),
     .doc = "Guard: two particles closer than this times dx stop the run"},
    {.section = SEC_FLUID, .key = "max_density_error", .type = VT_NUMBER, .flags = F_ABOVE_LO,
     .lo = 0, .def = 0.1, .offset = FLUID(max_density_error),
     .doc = "Guard: |rho - rho0| / rho0 above this stops the run; with `clamp_negative_pressure`, "
            "(rho - rho0) / rho0 (an expanded particle has no pressure then)"},
    {.section = SEC_FLUID, .key = "damping_rate", .type = VT_NUMBER, .unit = "1/s",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = FLUID(damping_rate),
     .doc = "Relaxation to rest: fluid velocities decay as exp(-rate t) until `damping_end`"},
    {.section = SEC_FLUID, .key = "damping_end", .type = VT_NUMBER, .unit = "s",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = FLUID(damping_end),
     .doc = "Time the relaxation damping stops"},
    {.section = SEC_FLUID, .key = "shifting", .type = VT_NUMBER, .flags = F_FROM_LO | F_UP_TO_HI,
     .lo = 0, .hi = 10, .def = 0, .offset = FLUID(shifting),
     .doc = "Particle shifting coefficient A: fluid particles move by -A h |u| dt grad C after each step "
            "(Skillen et al. 2013; Lind et al. 2012, tangential only near free surfaces); 2 is usual; 0: off"},
    {.section = SEC_FLUID, .key = "gas_density", .type = VT_CHOICE, .choices = gas_density_choices,
     .def = GAS_DENSITY_CONTINUITY, .offset = FLUID(gas_density),
     .doc = "Density of a gas material: from the continuity equation (as a liquid's), or summed over the "
            "neighbours, rho_a = m_a sum_b W_ab over that sum on the initial lattice (Adami et al. 2013), "
            "which follows the positions, the transport velocity's displacement included; where a void cuts "
            "the support (Shepard sum below 0.98 of the lattice's) blended with the continuity's, which alone "
            "stands below 0.93"},
    {.section = SEC_FLUID, .key = "transport_pressure", .type = VT_NUMBER, .unit = "Pa", .flags = F_FROM_LO,
     .lo = 0, .def = 0, .offset = FLUID(transport_pressure),
     .doc = "Background pressure of the transport velocity (Adami et al. 2013 Eq. 13): fluid particles move "
            "by dt^2 / 2 times -(p_tv / m_a) sum_b (V_a^2 + V_b^2) grad_a W_ab after each step, which keeps "
            "them evenly spaced without the force `background_pressure` exerts on a body moving through "
            "them, less where a void cuts the support and none at its edge; 0: off"},
    {.section = SEC_FLUID, .key = "smoothing_length", .type = VT_CHOICE, .choices = smoothing_choices,
     .def = SMOOTHING_FIXED, .offset = FLUID(smoothing_length),
     .doc = "Smoothing length of the fluid's pair terms: fixed h0 = `h_over_dx` dx, or following each fluid "
            "particle's volume, h = h0 (V / dx^d)^(1/d) (Russell Eq. 3.54), pairs taking (h_a + h_b) / 2; "
            "walls and the other modules keep h0"},
    {.section = SEC_FLUID, .key = "max_smoothing_ratio", .type = VT_NUMBER, .flags = F_ABOVE_LO | F_UP_TO_HI,
     .lo = 1, .hi = 2, .def = 1.1, .offset = FLUID(max_smoothing_ratio),
     .rule = "with `smoothing_length: volume`: a particle whose h exceeds it times h0 stops the run",
     .doc = "Largest h / h0 of `smoothing_length: volume`: the neighbour grid's cells are laid out for it"},
    {.section = SEC_FLUID, .key = "integration", .type = VT_CHOICE, .choices = fluid_integration_choices,
     .def = INTEGRATION_LEAPFROG, .offset = FLUID(integration),
     .rule = "verlet: the fluid module alone (no thermal, surface, grains or temperature history), "
             "pressure_gradient symmetric, smoothing_length fixed, no shifting or damping",
     .doc = "Time integration: leapfrog (kick-drift-kick with the density after the drift, Russell Eq. 3.55; "
            "two neighbour passes per step) or verlet (Verlet 1967 as in DualSPHysics: density and "
            "acceleration from one neighbour pass, v and rho over two steps, an Euler step every "
            "`verlet_steps`)"},
    {.section = SEC_FLUID, .key = "verlet_steps", .type = VT_INT, .flags = F_FROM_LO, .lo = 1, .def = 40,
     .offset = FLUID(verlet_steps),
     .doc = "With `integration: verlet`: one step in this many is an Euler step, which keeps the two "
            "interleaved sequences of the Verlet scheme from drifting apart"},
    {.section = SEC_FLUID, .key = "barrier", .type = VT_MAP, .sub = SEC_BARRIER,
     .doc = "Barrier forces between pairs closer than `distance` (Fuchs et al. 2022 Eq. 34); "
            "present: on. In 2D, stiffness and damping are per metre of depth"},
    {.section = SEC_BARRIER, .key = "stiffness", .type = VT_NUMBER, .unit = "kg/s²",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = FLUID(barrier_stiffness),
     .rule = "adds the step limit 0.22 sqrt(m/k_b) (Fuchs Eq. 42), m the lightest fluid particle",
     .doc = "Stiffness k_b of the elastic part k_b (r_b - r)"},
    {.section = SEC_BARRIER, .key = "damping", .type = VT_NUMBER, .unit = "kg/(m·s)",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = FLUID(barrier_damping),
     .doc = "Damping d_b of the viscous part d_b |r_b - r| dr/dt (approach speed)"},
    {.section = SEC_BARRIER, .key = "distance", .type = VT_NUMBER, .unit = "m",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = FLUID(barrier_distance),
     .rule = "< the smoothing length `h_over_dx` dx",
     .doc = "Interaction distance r_b: pairs closer than this repel (Fuchs: dx / 2)"},
    {.section = SEC_TOP, .key = "thermal", .type = VT_MAP, .sub = SEC_THERMAL,
     .doc = "Heat transfer and phase change module; present: on"},
    {.section = SEC_THERMAL, .key = "integration", .type = VT_CHOICE,
     .choices = integration_choices, .def = AMSPH_THERMAL_EXPLICIT, .offset = THERMAL(integration),
     .doc = "Enthalpy update: explicit Euler, or implicit midpoint by fixed-point iteration "
            "(Russell Alg. 3.1)"},
    {.section = SEC_THERMAL, .key = "tolerance", .type = VT_NUMBER, .flags = F_ABOVE_LO, .lo = 0,
     .def = 1e-6, .offset = THERMAL(tolerance),
     .doc = "Midpoint: iterate until max |T(i+1) - T(i)| / max T(n) is below this"},
    {.section = SEC_THERMAL, .key = "max_iterations", .type = VT_INT, .flags = F_FROM_LO, .lo = 1,
     .def = 20, .offset = THERMAL(max_iterations),
     .doc = "Midpoint: iteration cap; a step that does not converge stops the run"},
    {.section = SEC_THERMAL, .key = "diffusion_number", .type = VT_NUMBER,
     .flags = F_ABOVE_LO | F_UP_TO_HI, .lo = 0, .hi = 1, .def = 0.1,
     .offset = THERMAL(diffusion_number),
     .doc = "Diffusion limit dt <= diffusion_number rho c h^2 / k (Fuchs et al. Eq. 42)"},
    {.section = SEC_THERMAL, .key = "radiation", .type = VT_CHOICE, .choices = bool_choices,
     .def = 0, .offset = THERMAL(radiation),
     .doc = "Free surfaces radiate sigma eps (T^4 - T_inf^4) (Russell Eq. 3.39)"},
    {.section = SEC_THERMAL, .key = "ambient_temperature", .type = VT_NUMBER, .unit = "K",
     .flags = F_FROM_LO, .lo = 0, .def = 300, .offset = THERMAL(ambient_temperature),
     .doc = "Temperature T_inf the surfaces radiate to"},
    {.section = SEC_THERMAL, .key = "viscous_heating", .type = VT_CHOICE, .choices = bool_choices,
     .def = 0, .offset = THERMAL(viscous_heating), .rule = "needs `fluid`",
     .doc = "Viscous dissipation tau : grad u heats the fluid (renormalised velocity gradient)"},
    {.section = SEC_THERMAL, .key = "evaporative_cooling", .type = VT_CHOICE, .choices = bool_choices,
     .def = 0, .offset = THERMAL(evaporative_cooling), .rule = "needs an evaporating material",
     .doc = "Free surfaces of fluid and solid lose the vapour's heat m_v (h_v + h(T) - h(T_h,0)) "
            "(Fuchs et al. 2022 Eq. 18) with the surface delta of the radiation"},
    {.section = SEC_THERMAL, .key = "recoil_pressure", .type = VT_CHOICE, .choices = bool_choices,
     .def = 0, .offset = THERMAL(recoil_pressure),
     .rule = "needs `fluid` and an evaporating material",
     .doc = "The recoil pressure p_v(T) pushes free surfaces of fluid inward: -p_v n delta per volume "
            "(Fuchs et al. 2022 Eqs. 10, 30)"},
    {.section = SEC_THERMAL, .key = "evaporation_temperature", .type = VT_NUMBER, .unit = "K",
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .offset = THERMAL(evaporation_temperature),
     .doc = "Fluid and solid particles hotter than this evaporate: they are removed, counted and their "
            "enthalpy booked in the energy ledger (the damage parameter Russell 2018 proposes in the "
            "opening of ch. 3, not implemented there); not set: never"},
    {.section = SEC_TOP, .key = "surface", .type = VT_MAP, .sub = SEC_SURFACE,
     .rule = "needs `fluid`",
     .doc = "Surface tension and Marangoni force on free surfaces (Russell 2018 §3.1.2); present: on"},
    {.section = SEC_SURFACE, .key = "tension", .type = VT_CHOICE, .choices = bool_choices,
     .def = 1, .offset = SURFACE(tension),
     .doc = "The curvature force -σ κ n (Russell Eq. 3.31)"},
    {.section = SEC_SURFACE, .key = "tension_form", .type = VT_CHOICE, .choices = tension_form_choices,
     .def = TENSION_FORM_CSF, .offset = SURFACE(tension_form), .rule = "conservative: a constant surface tension",
     .doc = "How the tension acts: `csf`, the force σ κ on each liquid particle along its colour gradient "
            "(Russell Eq. 3.31; with a gas Fuchs et al. 2022 Eq. 24), whose sum over a closed drop is the "
            "curvature's error, not zero; `conservative`, that force plus its difference to the divergence "
            "of the capillary stress σ |n| (1 - n̂ n̂) (Lafaurie et al. 1994), summed pair by pair, "
            "smoothed three times over the liquid: the tension's net on a body of liquid is then zero, or "
            "the pull of the solids it wets"},
    {.section = SEC_SURFACE, .key = "marangoni", .type = VT_CHOICE, .choices = bool_choices,
     .def = 0, .offset = SURFACE(marangoni), .rule = "needs temperatures",
     .doc = "The Marangoni force dσ/dT ∇_s T |n| (Russell Eq. 3.35)"},
    {.section = SEC_SURFACE, .key = "h_over_dx", .type = VT_NUMBER,
     .flags = F_ABOVE_LO | F_UP_TO_HI | F_NO_DEFAULT, .lo = 0, .hi = 4,
     .offset = SURFACE(h_over_dx), .rule = ">= `h_over_dx`",
     .doc = "Smoothing length of the surface terms / dx; not set: a support of 3.6 dx (Russell's "
            "1.5 × 1.2 dx with Wendland C2, §3.1.2; 1.2 dx with the quintic), at least `h_over_dx`"},
    {.section = SEC_SURFACE, .key = "normal_cutoff", .type = VT_NUMBER,
     .flags = F_ABOVE_LO | F_UP_TO_HI, .lo = 0, .hi = 1, .def = 0.1,
     .offset = SURFACE(normal_cutoff),
     .doc = "Cut-off of the normals (Russell Eq. 3.27): a normal n enters the curvature with "
            "weight 0 at |n| h = this, rising linearly to 1 at twice this"},
    {.section = SEC_SURFACE, .key = "min_shepard", .type = VT_NUMBER,
     .flags = F_FROM_LO | F_UP_TO_HI, .lo = 0, .hi = 1, .def = 0.2,
     .offset = SURFACE(min_shepard),
     .doc = "Particles whose kernel sum Σ V W (at the surface smoothing length) is below this "
            "(lone particles, films a particle thick) carry no surface force"},
    {.section = SEC_SURFACE, .key = "interface_viscosity", .type = VT_NUMBER,
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = SURFACE(interface_viscosity),
     .rule = "adds the step limit 0.125 h_st^2 / nu, nu = alpha0 n_max h_st^2 c0 / (2 (d + 2)), n_max the largest colour gradient",
     .doc = "Factor α0 of the interface viscosity (Fuchs et al. 2022 Eqs. 31-32): an artificial "
            "viscosity α0 h |n| on the liquid at its free surface that damps spurious interface "
            "flows (7.2 in Fuchs's Table 1); a pair takes the larger factor of its two, so "
            "momentum is kept; 0: off"},
    {.section = SEC_TOP, .key = "grains", .type = VT_MAP, .sub = SEC_GRAINS,
     .rule = "needs `fluid`, a block of kind `grain`, no periodic axis",
     .doc = "Mobile powder: each block of kind `grain` (each grain of a `powder_bed` of that kind) "
            "is a rigid body of particles that the fluid and contacts move (Fuchs et al. 2022 "
            "§2.2, §3.4); present: on"},
    {.section = SEC_GRAINS, .key = "contact_stiffness", .type = VT_NUMBER, .unit = "kg/s²",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = GRAINS(stiffness),
     .doc = "k_c of the contact force between particles of different grains, and of a grain and "
            "a wall or fixed solid (Fuchs Eqs. 39-40); sets the time step 0.22 √(m/k_c) (Eq. 42)"},
    {.section = SEC_GRAINS, .key = "contact_damping", .type = VT_NUMBER, .unit = "kg/s",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = GRAINS(damping),
     .doc = "d_c of the contact force, on the closing speed"},
    {.section = SEC_GRAINS, .key = "contact_distance", .type = VT_NUMBER, .unit = "m",
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .offset = GRAINS(distance),
     .rule = "at most the kernel support (checked when the scene is built)",
     .doc = "Particles closer than this are in contact; not set: `dx` (Fuchs Eq. 40)"},
    {.section = SEC_TOP, .key = "laser", .type = VT_MAP, .sub = SEC_LASER,
     .doc = "Laser heat source: a Gaussian beam (Russell 2018 Eq. 3.42) absorbed into the particles' "
            "`laser_power`; present: on. In 2D the plane is a slice through the beam axis, so "
            "absorbed powers are per metre of depth"},
    {.section = SEC_LASER, .key = "power", .type = VT_NUMBER, .unit = "W",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = LASER(power), .doc = "Beam power P"},
    {.section = SEC_LASER, .key = "radius", .type = VT_NUMBER, .unit = "m",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = LASER(radius),
     .rule = "at least the spacing the beam is sampled at: `dx` (surface), `laser.bin_size` (volumetric)",
     .doc = "1/e² radius r_l: irradiance 2P/(π r_l²) exp(-2 r²/r_l²) at distance r from the axis"},
    {.section = SEC_LASER, .key = "absorption", .type = VT_CHOICE, .choices = absorption_choices,
     .flags = F_SELECTS_VARIANT, .def = AMSPH_ABSORPTION_VOLUMETRIC, .offset = LASER(absorption),
     .doc = "Beer-Lambert through a beam-aligned bin grid (Russell 2018 §3.2.2) or a flux on the "
            "surface facing the beam (Fuchs et al. 2022 Eq. 17)"},
    {.section = SEC_LASER, .key = "absorption_coefficient", .type = VT_NUMBER, .unit = "1/m",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .variants = VOLUMETRIC_ONLY,
     .offset = LASER(absorption_coefficient),
     .doc = "Beer-Lambert absorption coefficient α (Russell 2018 Eq. 3.40)"},
    {.section = SEC_LASER, .key = "absorptivity", .type = VT_NUMBER,
     .flags = F_ABOVE_LO | F_UP_TO_HI, .lo = 0, .hi = 1, .def = 1,
     .offset = LASER(absorptivity),
     .doc = "Fraction ζ of the irradiance that is not reflected: `surface` absorbs it on the faces "
            "(Fuchs et al. 2022 Eq. 17), `volumetric` sends it down the Beer-Lambert columns "
            "(Russell 2018 §4.4: all non-reflected power absorbed)"},
    {.section = SEC_LASER, .key = "direction", .type = VT_VECTOR, .flags = F_NO_DEFAULT,
     .offset = LASER(direction),
     .rule = "nonzero; normalised on reading; perpendicular to periodic directions",
     .doc = "Direction the beam travels; not set: -y (2D), -z (3D)"},
    {.section = SEC_LASER, .key = "start", .type = VT_VECTOR, .unit = "m", .flags = F_REQUIRED,
     .offset = LASER(start), .doc = "Beam centre at t = 0 (any point on the beam axis)"},
    {.section = SEC_LASER, .key = "path", .type = VT_LIST, .lo = 1, .hi = AMSPH_MAX_LASER_PATH,
     .sub = SEC_LASER_PATH,
     .doc = "Segments the beam centre follows in order from `start` (from t = 0); afterwards "
            "it stays at the last end point"},
    {.section = SEC_LASER_PATH, .key = "to", .type = VT_VECTOR, .unit = "m", .flags = F_REQUIRED,
     .offset = SEGMENT(to), .doc = "End point of the segment"},
    {.section = SEC_LASER_PATH, .key = "speed", .type = VT_NUMBER, .unit = "m/s",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = SEGMENT(speed),
     .doc = "Speed of the beam centre along the segment"},
    {.section = SEC_LASER, .key = "on_time", .type = VT_NUMBER, .unit = "s", .flags = F_FROM_LO,
     .lo = 0, .def = 0, .offset = LASER(on_time), .doc = "Time the laser switches on"},
    {.section = SEC_LASER, .key = "off_time", .type = VT_NUMBER, .unit = "s", .flags = F_NO_DEFAULT,
     .offset = LASER(off_time), .rule = "> `on_time`",
     .doc = "Time the laser switches off; not set: never"},
    {.section = SEC_LASER, .key = "ramp_time", .type = VT_NUMBER, .unit = "s", .flags = F_FROM_LO,
     .lo = 0, .def = 0, .offset = LASER(ramp_time),
     .rule = "at most half of `off_time` - `on_time`",
     .doc = "The power ramps linearly from 0 over this time after `on_time` and back to 0 over "
            "this time before `off_time`"},
    {.section = SEC_LASER, .key = "bin_size", .type = VT_NUMBER, .unit = "m",
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .offset = LASER(bin_size),
     .variants = VOLUMETRIC_ONLY,
     .rule = "bin_size √dimension <= the kernel support (checked when the run starts)",
     .doc = "Side of the bins of the Beer-Lambert grid; not set: `dx`"},
    {.section = SEC_LASER, .key = "window", .type = VT_NUMBER, .flags = F_FROM_LO, .lo = 1,
     .def = 3, .variants = VOLUMETRIC_ONLY, .offset = LASER(window),
     .doc = "The bin columns reach this many radii r_l from the axis (the beam power beyond: "
            "below exp(-2 window²))"},
    {.section = SEC_TOP, .key = "temperature_history", .type = VT_MAP, .sub = SEC_HISTORY,
     .rule = "not with `thermal` or `geometry[].temperature`",
     .doc = "A temperature prescribed on every particle, uniform in space, for cases without the "
            "thermal module (it drives rho0(T)); present: on"},
    {.section = SEC_HISTORY, .key = "form", .type = VT_CHOICE, .choices = history_choices,
     .flags = F_SELECTS_VARIANT, .def = AMSPH_HISTORY_SINE, .offset = HISTORY(form),
     .doc = "`sine`: T = reference + amplitude sin(2π frequency t); `ramp`: T = reference + "
            "amplitude min(t / duration, 1)"},
    {.section = SEC_HISTORY, .key = "reference", .type = VT_NUMBER, .unit = "K",
     .flags = F_REQUIRED | F_FROM_LO, .lo = 0, .offset = HISTORY(reference),
     .doc = "Temperature at t = 0"},
    {.section = SEC_HISTORY, .key = "amplitude", .type = VT_NUMBER, .unit = "K", .flags = F_REQUIRED,
     .offset = HISTORY(amplitude), .rule = "the temperature stays >= 0 K",
     .doc = "Amplitude of the sine, or the change over the ramp"},
    {.section = SEC_HISTORY, .key = "frequency", .type = VT_NUMBER, .unit = "Hz",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .variants = SINE_ONLY, .offset = HISTORY(frequency),
     .doc = "Frequency of the sine"},
    {.section = SEC_HISTORY, .key = "duration", .type = VT_NUMBER, .unit = "s",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .variants = RAMP_ONLY, .offset = HISTORY(duration),
     .doc = "Time over which the ramp changes the temperature; constant afterwards"},
    {.section = SEC_TOP, .key = "materials", .type = VT_LIST, .flags = F_REQUIRED, .lo = 1,
     .hi = AMSPH_MAX_MATERIALS, .sub = SEC_MATERIAL,
     .doc = "Materials, referred to by name from `geometry`"},
    {.section = SEC_MATERIAL, .key = "name", .type = VT_NAME, .flags = F_REQUIRED,
     .offset = MAT(name), .rule = "unique; at most 63 characters",
     .doc = "Name by which geometry refers to the material"},
    {.section = SEC_MATERIAL, .key = "preset", .type = VT_CHOICE, .choices = preset_choices,
     .def = AMSPH_PRESET_NONE, .offset = MAT(preset),
     .doc = "A named material (the presets below) that gives the keys this material does not"},
    {.section = SEC_MATERIAL, .key = "density", .type = VT_PROPERTY, .unit = "kg/m³",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .offset = MAT(density),
     .rule = "a table needs particle temperatures (`geometry[].temperature` or `temperature_history`)",
     .doc = "Reference density rho0 of the equation of state: a number, or a list of [T, rho0] pairs "
            "(isothermally incompressible fluid, Russell Eq. 3.52: the linear law rho_ref - alpha_T "
            "(T - T_ref) is a two-point table; constant beyond the table's ends)"},
    {.section = SEC_MATERIAL, .key = "phase", .type = VT_CHOICE, .choices = phase_choices,
     .def = AMSPH_MATERIAL_LIQUID, .offset = MAT(phase),
     .rule = "`gas`: only `kind: fluid`, no `melting_temperature`, no evaporation",
     .doc = "`liquid`: the melt (solid too, as its temperature says); `gas`: an atmosphere of its own "
            "fluid phase (Fuchs et al. 2022 Sec. 4.1), outside the liquid for the surface terms, "
            "transparent to the laser, never melting or evaporating"},
    {.section = SEC_MATERIAL, .key = "viscosity", .type = VT_NUMBER, .unit = "Pa·s",
     .flags = F_FROM_LO, .lo = 0, .offset = MAT(viscosity), .doc = "Dynamic viscosity"},
    {.section = SEC_MATERIAL, .key = "sound_speed", .type = VT_NUMBER, .unit = "m/s",
     .flags = F_FROM_LO, .lo = 0, .offset = MAT(sound_speed),
     .doc = "Artificial speed of sound; 0: not set"},
    {.section = SEC_MATERIAL, .key = "specific_heat", .type = VT_PROPERTY, .unit = "J/(kg·K)",
     .flags = F_ABOVE_LO, .lo = 0, .offset = MAT(specific_heat), .rule = "needed by `thermal`",
     .doc = "Specific heat capacity (of the solid): a number or a list of [T, value] pairs"},
    {.section = SEC_MATERIAL, .key = "liquid_specific_heat", .type = VT_PROPERTY,
     .unit = "J/(kg·K)", .flags = F_ABOVE_LO, .lo = 0, .offset = MAT(liquid_specific_heat),
     .rule = "default: `specific_heat`",
     .doc = "Specific heat capacity of the liquid; blended by the liquid fraction"},
    {.section = SEC_MATERIAL, .key = "conductivity", .type = VT_PROPERTY, .unit = "W/(m·K)",
     .flags = F_FROM_LO, .lo = 0, .offset = MAT(conductivity), .rule = "needed by `thermal`",
     .doc = "Thermal conductivity (of the solid): a number or a list of [T, value] pairs"},
    {.section = SEC_MATERIAL, .key = "liquid_conductivity", .type = VT_PROPERTY, .unit = "W/(m·K)",
     .flags = F_FROM_LO, .lo = 0, .offset = MAT(liquid_conductivity),
     .rule = "default: `conductivity`",
     .doc = "Thermal conductivity of the liquid; blended by the liquid fraction"},
    {.section = SEC_MATERIAL, .key = "melting_temperature", .type = VT_NUMBER, .unit = "K",
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .offset = MAT(melting_temperature),
     .doc = "Melting temperature T_m; not set: the material does not melt"},
    {.section = SEC_MATERIAL, .key = "melting_range", .type = VT_NUMBER, .unit = "K",
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .offset = MAT(melting_range),
     .rule = "needed with `melting_temperature`; < 2 `melting_temperature`",
     .doc = "Width of the mushy interval [T_m - range/2, T_m + range/2] (apparent heat capacity)"},
    {.section = SEC_MATERIAL, .key = "latent_heat", .type = VT_NUMBER, .unit = "J/kg",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(latent_heat),
     .doc = "Latent heat of melting, released over the mushy interval"},
    {.section = SEC_MATERIAL, .key = "mushy_viscosity", .type = VT_NUMBER, .unit = "Pa·s",
     .flags = F_FROM_LO | F_NO_DEFAULT, .lo = 0, .offset = MAT(mushy_viscosity),
     .rule = "default: `viscosity`",
     .doc = "Viscosity at liquid fraction 0; blended linearly to `viscosity` at 1"},
    {.section = SEC_MATERIAL, .key = "emissivity", .type = VT_NUMBER,
     .flags = F_FROM_LO | F_UP_TO_HI, .lo = 0, .hi = 1, .def = 0, .offset = MAT(emissivity),
     .doc = "Emissivity of free surfaces (with `thermal.radiation`)"},
    {.section = SEC_MATERIAL, .key = "surface_tension", .type = VT_NUMBER, .unit = "N/m",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(surface_tension),
     .doc = "Surface tension σ0 at `surface_tension_reference_temperature` (with `surface`)"},
    {.section = SEC_MATERIAL, .key = "surface_tension_slope", .type = VT_NUMBER, .unit = "N/(m·K)",
     .def = 0, .offset = MAT(surface_tension_slope), .rule = "nonzero: needs temperatures",
     .doc = "dσ/dT of the clean surface: σ = σ0 + slope (T - T_ref) (Sahoo: -A)"},
    {.section = SEC_MATERIAL, .key = "surface_tension_reference_temperature", .type = VT_NUMBER,
     .unit = "K", .flags = F_FROM_LO, .lo = 0, .def = 0,
     .offset = MAT(surface_tension_reference_temperature),
     .doc = "Temperature T_ref at which σ = σ0 (Sahoo: the melting temperature)"},
    {.section = SEC_MATERIAL, .key = "surface_tension_minimum", .type = VT_NUMBER, .unit = "N/m",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(surface_tension_minimum),
     .doc = "σ(T) is held at no less than this (Fuchs et al. α_min)"},
    {.section = SEC_MATERIAL, .key = "surfactant_excess", .type = VT_NUMBER, .unit = "mol/m²",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(surfactant_excess),
     .rule = "> 0 needs the other `surfactant_` keys and temperatures",
     .doc = "Surface excess at saturation Γ_s of Sahoo's adsorption term -R T Γ_s ln(1 + k_l a_s "
            "exp(-ΔH0/(R T))) (Russell Eq. 4.2); 0: no term"},
    {.section = SEC_MATERIAL, .key = "surfactant_segregation", .type = VT_NUMBER,
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(surfactant_segregation),
     .doc = "Segregation entropy factor k_l of the adsorption term"},
    {.section = SEC_MATERIAL, .key = "surfactant_activity", .type = VT_NUMBER,
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(surfactant_activity),
     .doc = "Activity a_s of the surface-active solute (wt%, as Sahoo et al.)"},
    {.section = SEC_MATERIAL, .key = "surfactant_enthalpy", .type = VT_NUMBER, .unit = "J/mol",
     .def = 0, .offset = MAT(surfactant_enthalpy),
     .doc = "Standard heat of adsorption ΔH0 of the adsorption term"},
    {.section = SEC_MATERIAL, .key = "recoil_pressure_constant", .type = VT_NUMBER, .unit = "Pa",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(recoil_pressure_constant),
     .rule = "> 0 needs `boiling_temperature` and `recoil_temperature_constant`",
     .doc = "C_P of the recoil pressure p_v(T) = C_P exp(-C_T (1/T - 1/T_v)) (Fuchs et al. 2022 Eq. "
            "10; 0.54 times the ambient pressure); 0: the material does not evaporate"},
    {.section = SEC_MATERIAL, .key = "recoil_temperature_constant", .type = VT_NUMBER, .unit = "K",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(recoil_temperature_constant),
     .doc = "C_T of p_v(T): the molar latent heat of evaporation over R"},
    {.section = SEC_MATERIAL, .key = "boiling_temperature", .type = VT_NUMBER, .unit = "K",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(boiling_temperature),
     .doc = "Boiling temperature T_v of p_v(T)"},
    {.section = SEC_MATERIAL, .key = "evaporation_latent_heat", .type = VT_NUMBER, .unit = "J/kg",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(evaporation_latent_heat),
     .doc = "Latent heat of evaporation h_v (Fuchs et al. 2022 Eq. 18)"},
    {.section = SEC_MATERIAL, .key = "vapour_mass_constant", .type = VT_NUMBER, .unit = "K·s²/m²",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(vapour_mass_constant),
     .rule = "> 0 for `thermal.evaporative_cooling`",
     .doc = "C_M = M / (2π R) of the vapour mass flux m_v = 0.82 c_s p_v(T) sqrt(C_M / T) (Fuchs et "
            "al. 2022 Eq. 18)"},
    {.section = SEC_MATERIAL, .key = "sticking_coefficient", .type = VT_NUMBER,
     .flags = F_FROM_LO | F_UP_TO_HI, .lo = 0, .hi = 1, .def = 1, .offset = MAT(sticking_coefficient),
     .doc = "Sticking coefficient c_s of the vapour mass flux (close to 1 for metals)"},
    {.section = SEC_MATERIAL, .key = "evaporation_enthalpy_reference", .type = VT_NUMBER, .unit = "K",
     .flags = F_FROM_LO, .lo = 0, .def = 0, .offset = MAT(evaporation_enthalpy_reference),
     .doc = "Reference temperature T_h,0 of the vapour's specific enthalpy h(T) - h(T_h,0) in Eq. 18"},
    {.section = SEC_MATERIAL, .key = "contact_angle", .type = VT_NUMBER, .unit = "degree",
     .flags = F_ABOVE_LO | F_UP_TO_HI | F_NO_DEFAULT, .lo = 0, .hi = 180, .offset = MAT(contact_angle),
     .rule = "needs `surface`",
     .doc = "Equilibrium contact angle θ0 that this liquid makes on solids and walls, measured "
            "inside the liquid: its surface normals near the contact line are turned to the angle "
            "(Fuchs et al. 2022 Eqs. 27-29); not set: the liquid wets completely (solids and "
            "walls count as the same material)"},
    {.section = SEC_MATERIAL, .key = "wetting_transition_range", .type = VT_NUMBER, .unit = "K",
     .flags = F_ABOVE_LO, .lo = 0, .def = 5, .offset = MAT(wetting_transition_range),
     .doc = "Temperature interval ΔT_s below the solidus over which a fixed solid of this melting "
            "material fades out of the solid colour that the contact angle reads: weight 1 below "
            "T_sol - ΔT_s, 0 at T_sol, where it melts (Fuchs et al. 2022 §3.3.3; 5 K in their "
            "Table 1)"},
    {.section = SEC_TOP, .key = "geometry", .type = VT_LIST, .flags = F_REQUIRED, .lo = 1,
     .hi = AMSPH_MAX_GEOMETRY, .sub = SEC_GEOMETRY,
     .doc = "Bodies filled with particles"},
    {.section = SEC_GEOMETRY, .key = "shape", .type = VT_CHOICE, .choices = shape_choices,
     .flags = F_REQUIRED | F_SELECTS_VARIANT, .offset = GEO(shape),
     .doc = "Shape of the body; decides which keys below apply"},
    {.section = SEC_GEOMETRY, .key = "kind", .type = VT_CHOICE, .choices = kind_choices,
     .flags = F_REQUIRED, .offset = GEO(kind), .rule = "`grain` needs `grains`",
     .doc = "Kind of the particles: `fluid`; `wall` (boundary particles); `solid` (fixed, melts "
            "into fluid with the thermal module); `grain` (the block, or each grain of a powder "
            "bed, is one mobile rigid grain)"},
    {.section = SEC_GEOMETRY, .key = "material", .type = VT_MATERIAL, .flags = F_REQUIRED,
     .offset = GEO(material), .rule = "name of a material",
     .doc = "Material of the particles"},
    {.section = SEC_GEOMETRY, .key = "min", .type = VT_VECTOR, .unit = "m", .flags = F_REQUIRED,
     .variants = BOX_ONLY | POWDER_ONLY, .offset = GEO(min),
     .doc = "Lower corner of the box; of a powder bed's region, whose bottom face the grains rest on"},
    {.section = SEC_GEOMETRY, .key = "max", .type = VT_VECTOR, .unit = "m", .flags = F_REQUIRED,
     .variants = BOX_ONLY | POWDER_ONLY, .offset = GEO(max),
     .rule = "each > `min`; a powder bed's region holds a grain of the largest radius",
     .doc = "Upper corner of the box; of a powder bed's region (its top face: the spreader's height)"},
    {.section = SEC_GEOMETRY, .key = "center", .type = VT_VECTOR, .unit = "m",
     .flags = F_REQUIRED, .variants = ROUND_SHAPES, .offset = GEO(center),
     .doc = "Centre; for a cylinder the centre of its base"},
    {.section = SEC_GEOMETRY, .key = "axis", .type = VT_VECTOR, .flags = F_REQUIRED,
     .variants = CYLINDER_ONLY, .offset = GEO(axis), .rule = "nonzero; normalised on reading",
     .doc = "Direction of the cylinder axis"},
    {.section = SEC_GEOMETRY, .key = "radius", .type = VT_NUMBER, .unit = "m",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .variants = ROUND_SHAPES, .offset = GEO(radius),
     .doc = "Radius"},
    {.section = SEC_GEOMETRY, .key = "length", .type = VT_NUMBER, .unit = "m",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .variants = CYLINDER_ONLY, .offset = GEO(length),
     .doc = "Length of the cylinder along `axis`"},
    {.section = SEC_GEOMETRY, .key = "layers", .type = VT_INT, .flags = F_FROM_LO, .lo = 0,
     .variants = BOX_ONLY, .offset = GEO(layers),
     .doc = "0: a filled box; n > 0: n layers of particles outside the box faces (a tank)"},
    {.section = SEC_GEOMETRY, .key = "open", .type = VT_FACES, .choices = face_choices,
     .variants = BOX_ONLY, .offset = GEO(open_faces), .rule = "only with `layers` > 0",
     .doc = "Faces of the tank left without wall"},
    {.section = SEC_GEOMETRY, .key = "distribution", .type = VT_CHOICE,
     .choices = distribution_choices, .def = AMSPH_POWDER_REGULAR, .variants = POWDER_ONLY,
     .offset = GEO(distribution),
     .doc = "Grain radii: `regular` touching grains of `grain_radius` on a square array (Russell "
            "2018 §5.1.1); `lognormal` and `mixed` random, settled by sequential deposition from "
            "`seed` (host/powder.h)"},
    {.section = SEC_GEOMETRY, .key = "grain_radius", .type = VT_NUMBER, .unit = "m",
     .flags = F_REQUIRED | F_ABOVE_LO, .lo = 0, .variants = POWDER_ONLY,
     .offset = GEO(grain_radius), .rule = "at least 2 `dx` (checked when the scene is built)",
     .doc = "`regular`: radius of every grain; `lognormal`: exp of the mean of ln r (the median "
            "before truncation); `mixed`: radius of the large grains"},
    {.section = SEC_GEOMETRY, .key = "log_sd", .type = VT_NUMBER,
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .variants = POWDER_ONLY, .offset = GEO(log_sd),
     .rule = "required for `lognormal`, only there",
     .doc = "Standard deviation of ln r of the log-normal radii"},
    {.section = SEC_GEOMETRY, .key = "grain_radius_min", .type = VT_NUMBER, .unit = "m",
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .variants = POWDER_ONLY,
     .offset = GEO(grain_radius_min),
     .rule = "required for `lognormal`, only there; <= `grain_radius`; at least 2 `dx`",
     .doc = "Smallest radius of the truncated log-normal radii"},
    {.section = SEC_GEOMETRY, .key = "grain_radius_max", .type = VT_NUMBER, .unit = "m",
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .variants = POWDER_ONLY,
     .offset = GEO(grain_radius_max),
     .rule = "required for `lognormal`, only there; >= `grain_radius`, > `grain_radius_min`",
     .doc = "Largest radius of the truncated log-normal radii"},
    {.section = SEC_GEOMETRY, .key = "small_radius", .type = VT_NUMBER, .unit = "m",
     .flags = F_ABOVE_LO | F_NO_DEFAULT, .lo = 0, .variants = POWDER_ONLY,
     .offset = GEO(small_radius),
     .rule = "required for `mixed`, only there; < `grain_radius`; at least 2 `dx`",
     .doc = "Radius of the small grains of a mixed bed"},
    {.section = SEC_GEOMETRY, .key = "small_fraction", .type = VT_NUMBER,
     .flags = F_FROM_LO | F_UP_TO_HI, .lo = 0, .hi = 1, .def = 0.5, .variants = POWDER_ONLY,
     .offset = GEO(small_fraction), .rule = "only for `mixed`",
     .doc = "Probability that a grain of a mixed bed is small (number fraction)"},
    {.section = SEC_GEOMETRY, .key = "seed", .type = VT_INT, .flags = F_FROM_LO, .lo = 0,
     .def = 1, .variants = POWDER_ONLY, .offset = GEO(seed),
     .rule = "only for `lognormal` and `mixed`",
     .doc = "Seed of the random radii and drop positions: the same seed gives the same bed"},
    {.section = SEC_GEOMETRY, .key = "velocity", .type = VT_VECTOR, .unit = "m/s",
     .offset = GEO(velocity), .doc = "Initial velocity"},
    {.section = SEC_GEOMETRY, .key = "temperature", .type = VT_NUMBER, .unit = "K",
     .flags = F_FROM_LO | F_NO_DEFAULT, .lo = 0, .offset = GEO(temperature),
     .rule = "not with `temperature_history`", .doc = "Initial temperature"},
    {.section = SEC_GEOMETRY, .key = "hydrostatic", .type = VT_CHOICE, .choices = bool_choices,
     .def = 0, .offset = GEO(hydrostatic),
     .doc = "Fluid starts in hydrostatic balance under the hydrostatic fluid above it in its lattice "
            "column (stacked blocks of different density too)"},
    {.section = SEC_GEOMETRY, .key = "fill", .type = VT_CHOICE, .choices = bool_choices,
     .def = 0, .offset = GEO(fill), .rule = "not on the first block",
     .doc = "The block places only its lattice points farther than 0.75 dx from every particle of the "
            "blocks before it: a gas box filling the space around the other shapes (seamless where "
            "their lattices line up with its own). Without it a block may not place a particle within "
            "0.3 dx of one placed before it (blocks that overlap are refused)"},
};
/* clang-format on */

#define N_SPECS (sizeof specs / sizeof specs[0])

/* ---- parser state and messages ----------------------------------------- */

typedef struct {
    const char *name; /* file name for messages */
    char *err;
    size_t errlen;
    yaml_document_t *doc;
    amsph_case *c;
    size_t material_line[AMSPH_MAX_MATERIALS]; /* where each material's name is */
    size_t thermal_line;                       /* where the thermal section starts */
    size_t surface_line;                       /* where the surface section starts */
    yaml_node_t preset_key[MAX_PRESET_KEYS];   /* the keys and values a preset fills into */
    yaml_node_t preset_value[MAX_PRESET_KEYS]; /* the material being read */
    size_t history_line;
    size_t grains_line;                        /* where the grains section starts */
    size_t integration_line;                   /* fluid.integration, or where the fluid section starts */
} parser;

/* One map being read: its keys found so far and the struct they fill. */
typedef struct {
    section_id section;
    char label[PATH_LEN];  /* "top level", "domain", "materials[2]", ... */
    char prefix[PATH_LEN]; /* "", "domain.", "materials[2].", ...: key paths */
    size_t index;          /* list entry number */
    void *target;
    const yaml_node_t *map;
    unsigned variant;         /* VARIANT_BIT of the selected variant; all bits before one is */
    const char *variant_key;  /* the key that selected it: "shape", "absorption" */
    const char *variant_name; /* its value: "box", "surface" */
    const yaml_node_t *key[N_SPECS];   /* key node per spec, NULL if absent */
    const yaml_node_t *value[N_SPECS]; /* its value node */
} scope;

/* A short text for a message (a quoted value, a range, a list of names). */
typedef struct {
    char s[128];
} shown;

static size_t line_of(const yaml_node_t *n)
{
    return n->start_mark.line + 1;
}

/* Replaces control characters, so that a message stays one line. */
static void make_one_line(char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f)
            *s = '?';
}

static int fail(const parser *p, size_t line, const char *fmt, ...) PRINTF_LIKE(3, 4);

/* Writes "name:line: message" into the caller's buffer; returns CASE_ERROR. */
static int fail(const parser *p, size_t line, const char *fmt, ...)
{
    if (!p->err || p->errlen == 0)
        return CASE_ERROR;
    int n = snprintf(p->err, p->errlen, "%s:%zu: ", p->name, line);
    if (n >= 0 && (size_t)n < p->errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(p->err + n, p->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    make_one_line(p->err);
    return CASE_ERROR;
}

static void set_path(char *out, const char *fmt, ...) PRINTF_LIKE(2, 3);

/* Formats a key path into a PATH_LEN buffer; a longer one is cut. */
static void set_path(char *out, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out, PATH_LEN, fmt, ap);
    va_end(ap);
}

/* User text, cut to SHOWN_MAX bytes (at a UTF-8 character boundary). */
static shown clip(const char *s, size_t len, int quote)
{
    shown out;
    size_t n = len;
    if (n > SHOWN_MAX) {
        n = SHOWN_MAX;
        while (n > 0 && ((unsigned char)s[n] & 0xC0) == 0x80)
            n--;
    }
    const char *q = quote ? "'" : "";
    snprintf(out.s, sizeof out.s, "%s%.*s%s%s", q, (int)n, s, n < len ? "..." : "", q);
    return out;
}

static const char *scalar_text(const yaml_node_t *n)
{
    return (const char *)n->data.scalar.value;
}

/* What a node is, for "got ...": 'text', a list, a map or an empty value. */
static shown describe(const yaml_node_t *n)
{
    shown out;
    if (n->type == YAML_SEQUENCE_NODE)
        snprintf(out.s, sizeof out.s, "a list");
    else if (n->type == YAML_MAPPING_NODE)
        snprintf(out.s, sizeof out.s, "a map");
    else if (n->data.scalar.length == 0)
        snprintf(out.s, sizeof out.s, "an empty value");
    else
        return clip(scalar_text(n), n->data.scalar.length, 1);
    return out;
}

static int is_scalar(const yaml_node_t *n, const char *s)
{
    return n->type == YAML_SCALAR_NODE && n->data.scalar.length == strlen(s) &&
           memcmp(n->data.scalar.value, s, n->data.scalar.length) == 0;
}

static size_t list_length(const yaml_node_t *n)
{
    return (size_t)(n->data.sequence.items.top - n->data.sequence.items.start);
}

static const yaml_node_t *list_item(const parser *p, const yaml_node_t *n, size_t i)
{
    return yaml_document_get_node(p->doc, n->data.sequence.items.start[i]);
}

/* ---- scalars ------------------------------------------------------------ */

typedef enum { NUM_OK, NUM_BAD, NUM_HUGE } number_status;

/* A whole scalar as a finite decimal number: 1, -2.5, 1e-3. Words such as
 * inf, nan or hex are not numbers. Particle data are amsph_real (float
 * unless built with AMSPH_DOUBLE), so a number is 0 or of a magnitude that
 * it holds as a normal number (1.2e-38 to 3.4e38 for float): 1e39 would
 * become inf on the particles, 1e-46 zero. */
static number_status parse_number(const yaml_node_t *n, double *out)
{
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.length == 0)
        return NUM_BAD;
    const char *s = scalar_text(n);
    size_t len = n->data.scalar.length;
    if (strspn(s, "0123456789+-.eE") != len)
        return NUM_BAD;
    char *end;
    double v = strtod(s, &end);
    if (end != s + len)
        return NUM_BAD;
    if (!(fabs(v) <= AMSPH_REAL_MAX) || (v != 0.0 && fabs(v) < AMSPH_REAL_MIN))
        return NUM_HUGE;
    *out = v;
    return NUM_OK;
}

/* A whole scalar as a decimal integer that fits an int. */
static number_status parse_int(const yaml_node_t *n, int *out)
{
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.length == 0)
        return NUM_BAD;
    const char *s = scalar_text(n);
    size_t len = n->data.scalar.length;
    if (strspn(s, "0123456789+-") != len)
        return NUM_BAD;
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (end != s + len)
        return NUM_BAD;
    if (errno == ERANGE || v < INT_MIN || v > INT_MAX)
        return NUM_HUGE;
    *out = (int)v;
    return NUM_OK;
}

/* The bounds of a number as text: "> 0", ">= 0", "in [1, 3]", "2 or 3". */
static shown range_text(const key_spec *k)
{
    shown out = {{0}};
    if ((k->flags & F_FROM_LO) && (k->flags & F_UP_TO_HI)) {
        const char *fmt = (k->type == VT_INT && k->hi - k->lo == 1) ? "%g or %g" : "in [%g, %g]";
        snprintf(out.s, sizeof out.s, fmt, k->lo, k->hi);
    } else if ((k->flags & F_ABOVE_LO) && (k->flags & F_UP_TO_HI))
        snprintf(out.s, sizeof out.s, "in (%g, %g]", k->lo, k->hi);
    else if (k->flags & F_ABOVE_LO)
        snprintf(out.s, sizeof out.s, "> %g", k->lo);
    else if (k->flags & F_FROM_LO)
        snprintf(out.s, sizeof out.s, ">= %g", k->lo);
    return out;
}

static int within_bounds(const key_spec *k, double v)
{
    if ((k->flags & F_ABOVE_LO) && !(v > k->lo))
        return 0;
    if ((k->flags & F_FROM_LO) && !(v >= k->lo))
        return 0;
    return !((k->flags & F_UP_TO_HI) && !(v <= k->hi));
}

static shown choice_list(const choice *choices)
{
    shown out = {{0}};
    size_t used = 0;
    for (const choice *c = choices; c->name && used < sizeof out.s; c++) {
        int n =
            snprintf(out.s + used, sizeof out.s - used, "%s%s", c == choices ? "" : ", ", c->name);
        used += n > 0 ? (size_t)n : 0;
    }
    return out;
}

/* ---- loaders: one per value type ---------------------------------------- */

/* A key's value being loaded. */
typedef struct {
    scope *sc;
    const key_spec *spec;
    const yaml_node_t *key;
    const yaml_node_t *node; /* the value */
    char path[PATH_LEN];     /* "geometry[2].radius", for messages */
    void *dst;               /* the field to fill */
} slot;

static int load_scope(parser *p, scope *sc);

/* Where a message about a whole value points: at a scalar itself, at the key
 * of a list or map (their nodes start at their first entry). */
static size_t value_line(const slot *s)
{
    return line_of(s->node->type == YAML_SCALAR_NODE ? s->node : s->key);
}

/* A number without bounds: a vector component, or a number checked later. */
static int read_number(parser *p, const yaml_node_t *n, size_t line, const char *path, double *out)
{
    number_status st = parse_number(n, out);
    if (st == NUM_BAD)
        return fail(p, line, "'%s' must be a number, got %s", path, describe(n).s);
    if (st == NUM_HUGE)
        return fail(p, line, "'%s' is out of range (0, or %g to %g in magnitude), got %s", path, AMSPH_REAL_MIN,
                    AMSPH_REAL_MAX, describe(n).s);
    return 0;
}

static int out_of_bounds(parser *p, const slot *s)
{
    const yaml_node_t *n = s->node;
    return fail(p, value_line(s), "'%s' must be %s, got %s", s->path, range_text(s->spec).s,
                clip(scalar_text(n), n->data.scalar.length, 0).s);
}

static int load_number(parser *p, const slot *s)
{
    double v;
    if (read_number(p, s->node, value_line(s), s->path, &v))
        return CASE_ERROR;
    if (!within_bounds(s->spec, v))
        return out_of_bounds(p, s);
    *(double *)s->dst = v;
    return 0;
}

static int load_int(parser *p, const slot *s)
{
    int v;
    number_status st = parse_int(s->node, &v);
    if (st == NUM_BAD)
        return fail(p, value_line(s), "'%s' must be an integer, got %s", s->path,
                    describe(s->node).s);
    if (st == NUM_HUGE)
        return fail(p, value_line(s), "'%s' is out of range, got %s", s->path, describe(s->node).s);
    if (!within_bounds(s->spec, v))
        return out_of_bounds(p, s);
    *(int *)s->dst = v;
    return 0;
}

/* A list of exactly `dimension` items; `what` names them ("numbers"). */
static int check_dim_list(parser *p, const slot *s, const char *what)
{
    int dim = p->c->dim;
    const yaml_node_t *n = s->node;
    if (n->type != YAML_SEQUENCE_NODE)
        return fail(p, value_line(s), "'%s' must be a list of %d %s, got %s", s->path, dim, what,
                    describe(n).s);
    if (list_length(n) != (size_t)dim)
        return fail(p, value_line(s), "'%s' must have %d %s (dimension %d), got %zu", s->path, dim,
                    what, dim, list_length(n));
    return 0;
}

static int load_vector(parser *p, const slot *s)
{
    if (check_dim_list(p, s, "numbers"))
        return CASE_ERROR;
    double *v = s->dst;
    for (size_t i = 0; i < list_length(s->node); i++) {
        char path[PATH_LEN];
        set_path(path, "%s[%zu]", s->path, i);
        const yaml_node_t *item = list_item(p, s->node, i);
        if (read_number(p, item, line_of(item), path, &v[i]))
            return CASE_ERROR;
    }
    return 0;
}

static int load_bools(parser *p, const slot *s)
{
    if (check_dim_list(p, s, "booleans"))
        return CASE_ERROR;
    int *v = s->dst;
    for (size_t i = 0; i < list_length(s->node); i++) {
        const yaml_node_t *item = list_item(p, s->node, i);
        if (!is_scalar(item, "true") && !is_scalar(item, "false"))
            return fail(p, line_of(item), "'%s[%zu]' must be true or false, got %s", s->path, i,
                        describe(item).s);
        v[i] = is_scalar(item, "true");
    }
    return 0;
}

/* One of `choices`, and one that exists in this dimension. */
static int read_choice(parser *p, const choice *choices, const yaml_node_t *n, size_t line,
                       const char *path, const choice **out)
{
    const choice *c = choices;
    while (c->name && !is_scalar(n, c->name))
        c++;
    if (!c->name)
        return fail(p, line, "'%s' must be one of %s; got %s", path, choice_list(choices).s,
                    describe(n).s);
    if (c->dim && c->dim != p->c->dim)
        return fail(p, line, "'%s': '%s' exists only in %dD, but dimension is %d", path, c->name,
                    c->dim, p->c->dim);
    *out = c;
    return 0;
}

/* Only the keys of the variant c (a value of the selecting key k) apply
 * from here on in the scope. */
static void select_variant(scope *sc, const key_spec *k, const choice *c)
{
    sc->variant = VARIANT_BIT(c->value);
    sc->variant_key = k->key;
    sc->variant_name = c->name;
}

static int load_choice(parser *p, const slot *s)
{
    const choice *c;
    if (read_choice(p, s->spec->choices, s->node, value_line(s), s->path, &c))
        return CASE_ERROR;
    *(int *)s->dst = c->value;
    if (s->spec->flags & F_SELECTS_VARIANT)
        select_variant(s->sc, s->spec, c);
    return 0;
}

static int load_faces(parser *p, const slot *s)
{
    const yaml_node_t *n = s->node;
    if (n->type != YAML_SEQUENCE_NODE)
        return fail(p, value_line(s), "'%s' must be a list of faces (%s), got %s", s->path,
                    choice_list(s->spec->choices).s, describe(n).s);
    unsigned bits = 0;
    for (size_t i = 0; i < list_length(n); i++) {
        const yaml_node_t *item = list_item(p, n, i);
        char path[PATH_LEN];
        const choice *c;
        set_path(path, "%s[%zu]", s->path, i);
        if (read_choice(p, s->spec->choices, item, line_of(item), path, &c))
            return CASE_ERROR;
        if (bits & (unsigned)c->value)
            return fail(p, line_of(item), "'%s': face '%s' is listed twice", path, c->name);
        bits |= (unsigned)c->value;
    }
    *(unsigned *)s->dst = bits;
    return 0;
}

static int load_name(parser *p, const slot *s)
{
    const yaml_node_t *n = s->node;
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.length == 0)
        return fail(p, value_line(s), "'%s' must be a non-empty name, got %s", s->path,
                    describe(n).s);
    size_t len = n->data.scalar.length;
    if (len >= AMSPH_NAME_LEN)
        return fail(p, value_line(s), "'%s' is too long (%zu characters, at most %d): %s", s->path,
                    len, AMSPH_NAME_LEN - 1, describe(n).s);
    for (size_t i = 0; i < len; i++)
        if ((unsigned char)n->data.scalar.value[i] < 0x20 || n->data.scalar.value[i] == 0x7f)
            return fail(p, value_line(s), "'%s' must not contain control characters", s->path);
    memcpy(s->dst, n->data.scalar.value, len);
    ((char *)s->dst)[len] = '\0';
    return 0;
}

/* "water, air": the names of the materials read so far. */
static void material_names(const amsph_case *c, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < c->n_materials && used < size; i++) {
        int n = snprintf(out + used, size - used, "%s%s", i ? ", " : "", c->materials[i].name);
        used += n > 0 ? (size_t)n : 0;
    }
}

static int load_material_ref(parser *p, const slot *s)
{
    const yaml_node_t *n = s->node;
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.length == 0)
        return fail(p, value_line(s), "'%s' must be a material name, got %s", s->path,
                    describe(n).s);
    for (int i = 0; i < p->c->n_materials; i++) {
        if (is_scalar(n, p->c->materials[i].name)) {
            *(int *)s->dst = i;
            return 0;
        }
    }
    char known[AMSPH_MAX_MATERIALS * (AMSPH_NAME_LEN + 2)];
    material_names(p->c, known, sizeof known);
    return fail(p, value_line(s), "unknown material %s in '%s'; known materials: %s", describe(n).s,
                s->path, known);
}

/* A temperature-dependent property: a number, or a list of 2 ..
 * AMSPH_MAX_TABLE pairs [T, value], T >= 0 and increasing, each value
 * within the key's bounds. */
static int load_property(parser *p, const slot *s)
{
    amsph_property *prop = s->dst;
    memset(prop, 0, sizeof *prop);
    const yaml_node_t *n = s->node;
    if (n->type == YAML_SCALAR_NODE) {
        slot number = *s;
        number.dst = &prop->v[0];
        prop->n = 1;
        return load_number(p, &number);
    }
    const size_t count = n->type == YAML_SEQUENCE_NODE ? list_length(n) : 0;
    if (count < 2 || count > AMSPH_MAX_TABLE)
        return fail(p, value_line(s),
                    "'%s' must be a number or a list of 2 to %d [temperature, value] pairs, got %s",
                    s->path, AMSPH_MAX_TABLE, describe(n).s);
    for (size_t i = 0; i < count; i++) {
        const yaml_node_t *pair = list_item(p, n, i);
        char path[PATH_LEN];
        set_path(path, "%s[%zu]", s->path, i);
        if (pair->type != YAML_SEQUENCE_NODE || list_length(pair) != 2)
            return fail(p, line_of(pair), "'%s' must be a pair [temperature, value], got %s", path,
                        describe(pair).s);
        const yaml_node_t *t = list_item(p, pair, 0), *v = list_item(p, pair, 1);
        if (read_number(p, t, line_of(t), path, &prop->T[i]) ||
            read_number(p, v, line_of(v), path, &prop->v[i]))
            return CASE_ERROR;
        if (prop->T[i] < 0 || (i > 0 && !(prop->T[i] > prop->T[i - 1])))
            return fail(p, line_of(t),
                        "'%s': temperatures must be >= 0 K and increasing, got %s after %g", path,
                        describe(t).s, i > 0 ? prop->T[i - 1] : 0.0);
        if (!within_bounds(s->spec, prop->v[i]))
            return fail(p, line_of(v), "'%s' value must be %s, got %s", path,
                        range_text(s->spec).s, describe(v).s);
    }
    prop->n = (int)count;
    return 0;
}

/* A scope for a nested map or list entry, labelled `label`. */
static void init_scope(scope *sc, section_id section, const char *label, void *target,
                       const yaml_node_t *map)
{
    memset(sc, 0, sizeof *sc);
    sc->section = section;
    set_path(sc->label, "%s", label);
    set_path(sc->prefix, "%s.", label);
    sc->target = target;
    sc->map = map;
    sc->variant = ~0u;
}

static int load_map(parser *p, const slot *s)
{
    if (s->node->type != YAML_MAPPING_NODE)
        return fail(p, value_line(s), "'%s' must be a map, got %s", s->path, describe(s->node).s);
    scope sub;
    init_scope(&sub, s->spec->sub, s->path, s->sc->target, s->node);
    return load_scope(p, &sub);
}

/* Entry i of a list section; counts it in the case. */
static void *list_entry(amsph_case *c, section_id section, size_t i)
{
    if (section == SEC_MATERIAL) {
        c->n_materials = (int)i + 1;
        return &c->materials[i];
    }
    if (section == SEC_LASER_PATH) {
        c->laser.n_path = (int)i + 1;
        return &c->laser.path[i];
    }
    c->n_geometry = (int)i + 1;
    return &c->geometry[i];
}

static int load_list(parser *p, const slot *s)
{
    const yaml_node_t *n = s->node;
    if (n->type != YAML_SEQUENCE_NODE)
        return fail(p, value_line(s), "'%s' must be a list of maps, got %s", s->path,
                    describe(n).s);
    size_t count = list_length(n);
    if (count < (size_t)s->spec->lo)
        return fail(p, value_line(s), "'%s' must have at least %g %s", s->path, s->spec->lo,
                    s->spec->lo == 1 ? "entry" : "entries");
    if (count > (size_t)s->spec->hi)
        return fail(p, value_line(s), "'%s' has %zu entries; at most %g are allowed", s->path,
                    count, s->spec->hi);
    for (size_t i = 0; i < count; i++) {
        const yaml_node_t *item = list_item(p, n, i);
        char label[PATH_LEN];
        set_path(label, "%s[%zu]", s->path, i);
        if (item->type != YAML_MAPPING_NODE)
            return fail(p, line_of(item), "'%s' must be a map, got %s", label, describe(item).s);
        scope sub;
        init_scope(&sub, s->spec->sub, label, list_entry(p->c, s->spec->sub, i), item);
        sub.index = i;
        if (load_scope(p, &sub))
            return CASE_ERROR;
    }
    return 0;
}

typedef int (*loader)(parser *p, const slot *s);

static const loader loaders[] = {
    [VT_INT] = load_int,
    [VT_NUMBER] = load_number,
    [VT_VECTOR] = load_vector,
    [VT_BOOLS] = load_bools,
    [VT_CHOICE] = load_choice,
    [VT_NAME] = load_name,
    [VT_MATERIAL] = load_material_ref,
    [VT_FACES] = load_faces,
    [VT_MAP] = load_map,
    [VT_LIST] = load_list,
    [VT_PROPERTY] = load_property,
};

/* ---- maps: collecting keys, defaults, rules across keys ------------------ */

static int find_spec(section_id section, const yaml_node_t *key)
{
    for (size_t i = 0; i < N_SPECS; i++)
        if (specs[i].section == section && is_scalar(key, specs[i].key))
            return (int)i;
    return -1;
}

/* Edit distance between a (any length) and b (short), capped: returns
 * limit + 1 when it is larger than limit. */
static size_t edit_distance(const char *a, size_t la, const char *b, size_t limit)
{
    size_t lb = strlen(b), row[32];
    if (lb >= sizeof row / sizeof row[0] || (la > lb ? la - lb : lb - la) > limit)
        return limit + 1;
    for (size_t j = 0; j <= lb; j++)
        row[j] = j;
    for (size_t i = 1; i <= la; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; j++) {
            size_t up = row[j];
            size_t best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best)
                best = up + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb] > limit ? limit + 1 : row[lb];
}

/* The key of this section closest to `key`, if it is a likely typo. */
static const char *suggest_key(section_id section, const yaml_node_t *key)
{
    const char *best = NULL;
    size_t best_distance = SIZE_MAX;
    for (size_t i = 0; i < N_SPECS; i++) {
        if (specs[i].section != section)
            continue;
        size_t limit = strlen(specs[i].key) < 5 ? 1 : 2;
        size_t d = edit_distance(scalar_text(key), key->data.scalar.length, specs[i].key, limit);
        if (d <= limit && d < best_distance) {
            best = specs[i].key;
            best_distance = d;
        }
    }
    return best;
}

/* The keys of a section, ", " between them, in a string the caller frees
 * (NULL when out of memory). */
static char *section_keys(section_id section)
{
    size_t size = 1;
    for (size_t i = 0; i < N_SPECS; i++)
        if (specs[i].section == section)
            size += strlen(specs[i].key) + 2;
    char *keys = malloc(size);
    if (!keys)
        return NULL;
    keys[0] = '\0';
    size_t used = 0;
    for (size_t i = 0; i < N_SPECS; i++)
        if (specs[i].section == section)
            used += (size_t)snprintf(keys + used, size - used, "%s%s", used ? ", " : "", specs[i].key);
    return keys;
}

static int unknown_key(parser *p, const scope *sc, const yaml_node_t *key)
{
    const char *hint = suggest_key(sc->section, key);
    shown name = clip(scalar_text(key), key->data.scalar.length, 1);
    if (hint)
        return fail(p, line_of(key), "unknown key %s in %s; did you mean '%s'?", name.s, sc->label,
                    hint);
    char *allowed = section_keys(sc->section);
    fail(p, line_of(key), "unknown key %s in %s (allowed: %s)", name.s, sc->label,
         allowed ? allowed : "out of memory listing them");
    free(allowed);
    return CASE_ERROR;
}

/* First pass: the value node of each key, by spec index. */
static int collect_keys(parser *p, scope *sc)
{
    const yaml_node_t *map = sc->map;
    for (const yaml_node_pair_t *pair = map->data.mapping.pairs.start;
         pair < map->data.mapping.pairs.top; pair++) {
        const yaml_node_t *key = yaml_document_get_node(p->doc, pair->key);
        if (key->type != YAML_SCALAR_NODE)
            return fail(p, line_of(key), "keys in %s must be names, got %s", sc->label,
                        describe(key).s);
        int i = find_spec(sc->section, key);
        if (i < 0)
            return unknown_key(p, sc, key);
        if (sc->key[i])
            return fail(p, line_of(key), "duplicate key '%s' in %s (first on line %zu)",
                        specs[i].key, sc->label, line_of(sc->key[i]));
        sc->key[i] = key;
        sc->value[i] = yaml_document_get_node(p->doc, pair->value);
    }
    return 0;
}

/* The spec of a key known to be in the section. */
static int spec_named(section_id section, const char *key)
{
    int i = 0;
    while (specs[i].section != section || strcmp(specs[i].key, key))
        i++;
    return i;
}

/* A plain scalar `text` that reads as if it were written where `at` is. */
static const yaml_node_t *scalar_node(yaml_node_t *node, const char *text, const yaml_node_t *at)
{
    memset(node, 0, sizeof *node);
    node->type = YAML_SCALAR_NODE;
    node->data.scalar.value = (yaml_char_t *)text; /* only read */
    node->data.scalar.length = strlen(text);
    node->data.scalar.style = YAML_PLAIN_SCALAR_STYLE;
    node->start_mark = node->end_mark = at->start_mark;
    return node;
}

/* A material's `preset`: every key of the preset that the material does not
 * give is read as if written with the preset's value on the preset's line. */
static int fill_from_preset(parser *p, scope *sc)
{
    const int at = spec_named(SEC_MATERIAL, "preset");
    if (!sc->value[at])
        return 0;
    char path[PATH_LEN];
    const choice *c;
    set_path(path, "%spreset", sc->prefix);
    if (read_choice(p, preset_choices, sc->value[at], line_of(sc->value[at]), path, &c))
        return CASE_ERROR;
    const preset_key *keys = presets[c->value].keys;
    for (int k = 0; k < MAX_PRESET_KEYS && keys[k].key; k++) {
        const int i = spec_named(SEC_MATERIAL, keys[k].key);
        if (!sc->value[i]) {
            sc->key[i] = scalar_node(&p->preset_key[k], keys[k].key, sc->value[at]);
            sc->value[i] = scalar_node(&p->preset_value[k], keys[k].value, sc->value[at]);
        }
    }
    return 0;
}

static int apply_default(parser *p, scope *sc, const key_spec *k, void *dst)
{
    if (k->flags & F_REQUIRED) {
        if (k->variants)
            return fail(p, line_of(sc->map), "missing required key '%s' in %s (%s '%s')", k->key,
                        sc->label, sc->variant_key, sc->variant_name);
        return fail(p, line_of(sc->map), "missing required key '%s' in %s", k->key, sc->label);
    }
    if (k->flags & F_SELECTS_VARIANT) {
        const choice *c = k->choices;
        while (c->value != (int)k->def)
            c++;
        select_variant(sc, k, c);
    }
    switch (k->type) {
    case VT_NUMBER:
        *(double *)dst = (k->flags & F_NO_DEFAULT) ? 0 : k->def;
        break;
    case VT_INT:
    case VT_CHOICE:
        *(int *)dst = (int)k->def;
        break;
    case VT_VECTOR:
        memset(dst, 0, 3 * sizeof(double));
        break;
    case VT_BOOLS:
        memset(dst, 0, 3 * sizeof(int));
        break;
    case VT_FACES:
        *(unsigned *)dst = 0;
        break;
    case VT_PROPERTY:
        memset(dst, 0, sizeof(amsph_property));
        break;
    case VT_NAME:
    case VT_MATERIAL:
    case VT_MAP:
    case VT_LIST:
        break; /* always required */
    }
    return 0;
}

/* Second pass for one key: its value, or its default. */
static int load_key(parser *p, scope *sc, size_t i)
{
    const key_spec *k = &specs[i];
    slot s = {.sc = sc, .spec = k, .key = sc->key[i], .node = sc->value[i]};
    set_path(s.path, "%s%s", sc->prefix, k->key);
    s.dst = (char *)sc->target + k->offset;
    if (k->variants && !(k->variants & sc->variant)) {
        if (sc->key[i])
            return fail(p, line_of(sc->key[i]), "'%s' does not apply to %s '%s'", s.path,
                        sc->variant_key, sc->variant_name);
        return 0;
    }
    if (!s.node)
        return apply_default(p, sc, k, s.dst);
    return loaders[k->type](p, &s);
}

static const yaml_node_t *found(const scope *sc, const char *key)
{
    for (size_t i = 0; i < N_SPECS; i++)
        if (specs[i].section == sc->section && strcmp(specs[i].key, key) == 0)
            return sc->value[i];
    return NULL;
}

/* max > min in every component (domain, box). */
static int check_corners(parser *p, const scope *sc, const double lo[3], const double hi[3])
{
    const yaml_node_t *min = found(sc, "min"), *max = found(sc, "max");
    for (int d = 0; d < p->c->dim; d++) {
        if (hi[d] > lo[d])
            continue;
        const yaml_node_t *a = list_item(p, max, (size_t)d), *b = list_item(p, min, (size_t)d);
        return fail(p, line_of(a), "'%smax[%d]' (%s) must be > '%smin[%d]' (%s)", sc->prefix, d,
                    clip(scalar_text(a), a->data.scalar.length, 0).s, sc->prefix, d,
                    clip(scalar_text(b), b->data.scalar.length, 0).s);
    }
    return 0;
}

/* Liquid properties default to the solid's; a melting material needs its
 * mushy interval, which must stay above 0 K. */
static int finish_material_thermal(parser *p, const scope *sc)
{
    amsph_material *m = sc->target;
    if (!found(sc, "liquid_specific_heat"))
        m->liquid_specific_heat = m->specific_heat;
    if (!found(sc, "liquid_conductivity"))
        m->liquid_conductivity = m->conductivity;
    if (!found(sc, "mushy_viscosity"))
        m->mushy_viscosity = m->viscosity;
    const yaml_node_t *melting = found(sc, "melting_temperature");
    const yaml_node_t *range = found(sc, "melting_range");
    if (melting && !range)
        return fail(p, line_of(melting), "'%smelting_temperature' needs 'melting_range' (> 0 K)",
                    sc->prefix);
    if (range && !melting)
        return fail(p, line_of(range), "'%smelting_range' needs 'melting_temperature'", sc->prefix);
    if (melting && !(m->melting_range < 2 * m->melting_temperature))
        return fail(p, line_of(range),
                    "'%smelting_range' (%g K) must be below 2 'melting_temperature' (%g K)",
                    sc->prefix, m->melting_range, m->melting_temperature);
    return 0;
}

/* A gas neither melts nor evaporates (Fuchs et al. 2022 Sec. 4.1: the
 * atmosphere around the melt). */
static int finish_material_gas(parser *p, const scope *sc)
{
    const amsph_material *m = sc->target;
    if (m->phase != AMSPH_MATERIAL_GAS)
        return 0;
    static const char *const not_for_gas[] = {"melting_temperature", "recoil_pressure_constant"};
    for (size_t k = 0; k < sizeof not_for_gas / sizeof not_for_gas[0]; k++) {
        const yaml_node_t *given = found(sc, not_for_gas[k]); /* by the material or its preset */
        if (given)
            return fail(p, line_of(given),
                        "material '%s' is a gas ('phase: gas'), which neither melts nor evaporates: "
                        "it must not have '%s%s' (given here or by its preset)",
                        m->name, sc->prefix, not_for_gas[k]);
    }
    return 0;
}

static int finish_material(parser *p, const scope *sc)
{
    const amsph_material *m = sc->target;
    const yaml_node_t *name = found(sc, "name");
    for (size_t i = 0; i < sc->index; i++)
        if (strcmp(p->c->materials[i].name, m->name) == 0)
            return fail(p, line_of(name), "duplicate material name '%s' (first on line %zu)",
                        m->name, p->material_line[i]);
    p->material_line[sc->index] = line_of(name);
    if (finish_material_gas(p, sc))
        return CASE_ERROR;
    return finish_material_thermal(p, sc);
}

/* The recoil force moves fluid; evaporation needs a material that
 * evaporates, and each such material the constants of p_v(T) (and of the
 * vapour mass flux for the heat loss). */
static int check_evaporation(parser *p)
{
    const amsph_case *c = p->c;
    const amsph_thermal_settings *t = &c->thermal;
    if (t->recoil_pressure && !c->fluid.enabled)
        return fail(p, p->thermal_line, "'thermal.recoil_pressure' needs the fluid module (a 'fluid:' section)");
    if (!t->recoil_pressure && !t->evaporative_cooling)
        return 0;
    int evaporating = 0;
    for (int i = 0; i < c->n_materials; i++) {
        const amsph_material *m = &c->materials[i];
        if (!(m->recoil_pressure_constant > 0))
            continue;
        ++evaporating;
        const char *missing = !(m->boiling_temperature > 0)            ? "boiling_temperature"
                              : !(m->recoil_temperature_constant > 0) ? "recoil_temperature_constant"
                              : t->evaporative_cooling && !(m->vapour_mass_constant > 0) ? "vapour_mass_constant"
                                                                                          : NULL;
        if (missing)
            return fail(p, p->material_line[i], "material '%s' evaporates (recoil_pressure_constant > 0) and "
                        "needs '%s' > 0",
                        m->name, missing);
    }
    if (!evaporating)
        return fail(p, p->thermal_line,
                    "'thermal.%s' needs a material that evaporates: give one a "
                    "'recoil_pressure_constant' > 0 (or the preset steel_fuchs)",
                    t->recoil_pressure ? "recoil_pressure" : "evaporative_cooling");
    return 0;
}

/* The thermal module needs heat capacities, conductivities and initial
 * temperatures. */
static int finish_thermal(parser *p)
{
    const amsph_case *c = p->c;
    for (int i = 0; i < c->n_materials; i++) {
        const amsph_material *m = &c->materials[i];
        const char *missing = !m->specific_heat.n ? "specific_heat" : !m->conductivity.n ? "conductivity" : NULL;
        if (missing)
            return fail(p, p->material_line[i], "material '%s' needs '%s' for the thermal module",
                        m->name, missing);
    }
    for (int k = 0; k < c->n_geometry; k++)
        if (!c->geometry[k].has_temperature)
            return fail(p, (size_t)c->geometry[k].line,
                        "geometry[%d] needs 'temperature' for the thermal module", k);
    if (c->thermal.viscous_heating && !c->fluid.enabled)
        return fail(p, p->thermal_line, "'thermal.viscous_heating' needs the fluid module (a 'fluid:' section)");
    return check_evaporation(p);
}

/* Every particle has a temperature: every block gives one, or the history
 * prescribes it. */
static int has_temperatures(const amsph_case *c)
{
    if (c->temperature_history.enabled)
        return 1;
    for (int k = 0; k < c->n_geometry; k++)
        if (!c->geometry[k].has_temperature)
            return 0;
    return 1;
}

/* A material's sigma(T): a surfactant term needs all its constants; a
 * temperature-dependent law needs temperatures. */
static int check_surface_tension(parser *p, int i)
{
    const amsph_case *c = p->c;
    const amsph_material *m = &c->materials[i];
    const int surfactant = m->surfactant_excess > 0;
    if (surfactant && !(m->surfactant_segregation > 0 && m->surfactant_activity > 0))
        return fail(p, p->material_line[i],
                    "material '%s': 'surfactant_excess' needs 'surfactant_segregation' and "
                    "'surfactant_activity' > 0 (and 'surfactant_enthalpy')",
                    m->name);
    if ((surfactant || m->surface_tension_slope != 0) && !has_temperatures(c))
        return fail(p, p->material_line[i],
                    "material '%s': a temperature-dependent surface tension needs temperatures: "
                    "give every geometry block a 'temperature'",
                    m->name);
    return 0;
}

/* The conservative form of the tension takes a constant sigma: a sigma
 * that varies along the surface would add its Marangoni part to the
 * capillary stress's divergence, which is not validated. */
static int check_tension_form(parser *p)
{
    const amsph_case *c = p->c;
    if (c->surface.tension_form != TENSION_FORM_CONSERVATIVE)
        return 0;
    if (c->surface.marangoni)
        return fail(p, p->surface_line,
                    "'surface.tension_form: conservative' has no Marangoni force: use 'tension_form: csf' "
                    "with 'marangoni: true'");
    for (int i = 0; i < c->n_materials; i++) {
        const amsph_material *m = &c->materials[i];
        if (m->surface_tension_slope != 0 || m->surfactant_excess > 0)
            return fail(p, p->material_line[i],
                        "material '%s': 'surface.tension_form: conservative' needs a constant surface tension "
                        "(no 'surface_tension_slope' or 'surfactant_excess'); use 'tension_form: csf'",
                        m->name);
    }
    return 0;
}

/* The surface module works on the fluid module's free surfaces; Marangoni
 * flow needs temperatures; the surface terms' smoothing length is at least
 * the fluid's. */
static int finish_surface(parser *p)
{
    amsph_case *c = p->c;
    amsph_surface_settings *st = &c->surface;
    if (!c->fluid.enabled)
        return fail(p, p->surface_line, "'surface' needs the fluid module (a 'fluid:' section)");
    if (st->marangoni && !has_temperatures(c))
        return fail(p, p->surface_line,
                    "'surface.marangoni' needs temperatures: give every geometry block a "
                    "'temperature' (or add the thermal module)");
    if (st->h_over_dx == 0)
        st->h_over_dx = fmax(c->h_over_dx, (c->kernel == AMSPH_KERNEL_QUINTIC ? 1.2 : 1.8));
    else if (st->h_over_dx < c->h_over_dx)
        return fail(p, p->surface_line, "'surface.h_over_dx' (%g) must be at least 'h_over_dx' (%g)",
                    st->h_over_dx, c->h_over_dx);
    for (int i = 0; i < c->n_materials; i++)
        if (check_surface_tension(p, i))
            return CASE_ERROR;
    return check_tension_form(p);
}

/* The temperature history sets every particle's temperature: no thermal
 * module and no initial temperatures beside it. */
static int finish_history(parser *p)
{
    const amsph_case *c = p->c;
    if (c->thermal.enabled)
        return fail(p, p->history_line,
                    "'temperature_history' prescribes the temperature; it cannot be used with the "
                    "thermal module (the 'thermal:' section on line %zu)",
                    p->thermal_line);
    for (int k = 0; k < c->n_geometry; k++)
        if (c->geometry[k].has_temperature)
            return fail(p, (size_t)c->geometry[k].line,
                        "geometry[%d] has a 'temperature', but 'temperature_history' (line %zu) sets "
                        "every particle's temperature; remove one of them",
                        k, p->history_line);
    return 0;
}

/* A table rho0(T) needs the particles' temperatures. */
static int check_density_tables(parser *p)
{
    const amsph_case *c = p->c;
    int temperatures = c->temperature_history.enabled;
    for (int k = 0; k < c->n_geometry; k++)
        temperatures |= c->geometry[k].has_temperature;
    for (int i = 0; i < c->n_materials && !temperatures; i++)
        if (c->materials[i].density.n >= 2)
            return fail(p, p->material_line[i],
                        "material '%s' has a temperature-dependent 'density', but the particles have "
                        "no temperature: give the geometry blocks a 'temperature' or add a "
                        "'temperature_history'",
                        c->materials[i].name);
    return 0;
}

/* Grains move in the fluid module's flow, and blocks of kind `grain` and
 * the `grains:` section come together. A grain's centre and inertia are
 * sums of particle positions, which a periodic axis would break. */
static int finish_grains(parser *p)
{
    amsph_case *c = p->c;
    int block = -1;
    for (int k = 0; k < c->n_geometry && block < 0; k++)
        if (c->geometry[k].kind == AMSPH_KIND_GRAIN)
            block = k;
    if (!c->grains.enabled)
        return block < 0 ? 0
                         : fail(p, (size_t)c->geometry[block].line,
                                "geometry[%d] is of kind 'grain', which needs a 'grains:' section (with "
                                "'contact_stiffness')",
                                block);
    if (block < 0)
        return fail(p, p->grains_line, "'grains' is set, but no geometry block is of kind 'grain'");
    if (!c->fluid.enabled)
        return fail(p, p->grains_line, "'grains' needs the fluid module (a 'fluid:' section)");
    for (int d = 0; d < c->dim; d++)
        if (c->periodic[d])
            return fail(p, p->grains_line, "'grains' cannot be used with a periodic axis (%c)", "xyz"[d]);
    if (c->grains.distance == 0)
        c->grains.distance = c->dx;
    return 0;
}

/* A gas is a fluid phase: it needs the fluid module with the multiphase
 * pressure force (Fuchs et al. 2022 Eq. 23), whose density-weighted pair
 * pressure and volume weights hold a density ratio of 100. */
static int check_gas(parser *p)
{
    const amsph_case *c = p->c;
    for (int i = 0; i < c->n_materials; i++)
        if (c->materials[i].phase == AMSPH_MATERIAL_GAS &&
            (!c->fluid.enabled || c->fluid.pressure_gradient != PRESSURE_MULTIPHASE))
            return fail(p, p->material_line[i],
                        "material '%s' is a gas: it needs the fluid module with "
                        "'fluid.pressure_gradient: multiphase' (Fuchs et al. 2022 Eq. 23)",
                        c->materials[i].name);
    return 0;
}

/* A contact angle is a property of the surface module's free surfaces. */
static int check_contact_angles(parser *p)
{
    for (int i = 0; i < p->c->n_materials; i++)
        if (p->c->materials[i].contact_angle > 0 && !p->c->surface.enabled)
            return fail(p, p->material_line[i],
                        "material '%s' has a 'contact_angle', which needs the surface module (a "
                        "'surface:' section)",
                        p->c->materials[i].name);
    return 0;
}

/* The two-step Verlet scheme is stable to a smaller step than the
 * leapfrog's: a mode of frequency omega needs omega dt < 1 (the leapfrog
 * omega dt < 2), and the fastest acoustic mode of the particles comes near
 * that limit at the leapfrog's CFL of 0.25 (the 2D dam break at dx = 0.01 m
 * blows up at 0.25 and runs at 0.2, DualSPHysics' default). With verlet the
 * CFL defaults to VERLET_MAX_CFL and may not exceed it. */
#define VERLET_MAX_CFL 0.2

static int finish_verlet_cfl(parser *p, const scope *sc)
{
    amsph_fluid_settings *f = &p->c->fluid;
    if (f->integration != INTEGRATION_VERLET)
        return 0;
    if (!found(sc, "cfl"))
        f->cfl = VERLET_MAX_CFL;
    else if (f->cfl > VERLET_MAX_CFL)
        return fail(p, line_of(found(sc, "cfl")),
                    "'fluid.cfl' is %g; with 'integration: verlet' it must be at most %g (the two-step scheme's "
                    "stability limit, omega dt < 1, is half the leapfrog's)",
                    f->cfl, VERLET_MAX_CFL);
    return 0;
}

/* The Verlet scheme (fluid.integration: verlet) takes the density and the
 * acceleration from one pass at the same state, so nothing may need a
 * neighbour's Gamma of that state (the renormalised pressure form) or a
 * smoothing length from the new density; and it is built for the fluid
 * module alone: the other modules' rates, shifting and the damping follow
 * the leapfrog's half steps. */
static int check_verlet(parser *p)
{
    const amsph_case *c = p->c;
    const amsph_fluid_settings *f = &c->fluid;
    if (f->integration != INTEGRATION_VERLET)
        return 0;
    const char *clash = c->thermal.enabled                       ? "a 'thermal:' section"
                        : c->surface.enabled                     ? "a 'surface:' section"
                        : c->grains.enabled                      ? "a 'grains:' section"
                        : c->temperature_history.enabled         ? "a 'temperature_history:' section"
                        : f->pressure_gradient != PRESSURE_SYMMETRIC ? "a pressure_gradient other than 'symmetric'"
                        : f->smoothing_length != SMOOTHING_FIXED ? "'smoothing_length: volume'"
                        : f->shifting > 0                        ? "'shifting'"
                        : f->transport_pressure > 0              ? "'transport_pressure'"
                        : f->damping_rate > 0                    ? "'damping_rate'"
                                                                 : NULL;
    return clash ? fail(p, p->integration_line,
                        "'fluid.integration: verlet' serves the fluid module alone with "
                        "'pressure_gradient: symmetric', and this case has %s; use 'integration: leapfrog'",
                        clash)
                 : 0;
}

/* At most this many outputs to the end time: more is a mistake of units (a
 * snapshot of every particle at each), and their numbering and the progress
 * estimate would overflow. */
#define MAX_OUTPUTS 1e7

static int check_output_count(parser *p, const scope *sc)
{
    const amsph_case *c = p->c;
    const double outputs = c->end_time / c->output_interval;
    if (!(outputs <= MAX_OUTPUTS))
        return fail(p, line_of(found(sc, "output_interval")),
                    "'output_interval' (%g s) gives %g outputs up to 'end_time' (%g s); at most %g "
                    "are allowed",
                    c->output_interval, outputs, c->end_time, MAX_OUTPUTS);
    return 0;
}

/* Particle positions are amsph_real: at a distance X from the origin a
 * float tells positions apart only X FLT_EPSILON or so. A domain whose far
 * corner leaves them coarser than this fraction of dx is refused (a 1 m
 * domain may go down to dx = 12 um in float). */
#define POSITION_RESOLUTION_MAX 0.01

static int check_position_resolution(parser *p, const scope *sc)
{
    const amsph_case *c = p->c;
    for (int d = 0; d < c->dim; d++) {
        const double far = fmax(fabs(c->domain_min[d]), fabs(c->domain_max[d]));
        const double apart = far * AMSPH_REAL_EPSILON;
        if (apart > POSITION_RESOLUTION_MAX * c->dx)
            return fail(p, line_of(found(sc, "domain")),
                        "the domain reaches %g m from the origin along %c, where the particles' positions "
                        "(%s) are %.2g m = %.2g dx apart (at most %g dx); move the domain next to the "
                        "origin or make dx larger",
                        far, "xyz"[d], sizeof(amsph_real) == sizeof(float) ? "float" : "double", apart,
                        apart / c->dx, POSITION_RESOLUTION_MAX);
    }
    return 0;
}

/* The fluid module's equation of state needs a speed of sound. */
static int finish_top(parser *p, const scope *sc)
{
    if (check_output_count(p, sc) || check_position_resolution(p, sc) || finish_grains(p) || check_gas(p) ||
        check_contact_angles(p) || check_verlet(p))
        return CASE_ERROR;
    if (p->c->thermal.enabled && finish_thermal(p))
        return CASE_ERROR;
    if (p->c->surface.enabled && finish_surface(p))
        return CASE_ERROR;
    if (p->c->temperature_history.enabled && finish_history(p))
        return CASE_ERROR;
    if (check_density_tables(p))
        return CASE_ERROR;
    if (!p->c->fluid.enabled)
        return 0;
    for (int i = 0; i < p->c->n_materials; i++)
        if (p->c->materials[i].sound_speed <= 0)
            return fail(p, p->material_line[i],
                        "material '%s' needs 'sound_speed' > 0 for the fluid module (about 10 "
                        "times the largest expected flow speed)",
                        p->c->materials[i].name);
    return 0;
}

/* Scales the vector of `key` (a cylinder axis, the beam direction) to unit
 * length (without overflow for huge input). */
static int normalise_vector(parser *p, const scope *sc, const char *key, double axis[3])
{
    double largest = fmax(fabs(axis[0]), fmax(fabs(axis[1]), fabs(axis[2])));
    if (largest == 0)
        return fail(p, line_of(found(sc, key)), "'%s%s' must not be zero", sc->prefix, key);
    double norm = 0;
    for (int d = 0; d < 3; d++) {
        axis[d] /= largest;
        norm += axis[d] * axis[d];
    }
    norm = sqrt(norm);
    for (int d = 0; d < 3; d++)
        axis[d] /= norm;
    return 0;
}

/* The keys of each grain distribution of a powder bed (host/powder.h). */
#define DISTRIBUTION_BIT(d) (1u << (d))
static const struct {
    const char *key;
    unsigned distributions; /* DISTRIBUTION_BITs it applies to */
    int required;           /* there */
} powder_keys[] = {
    {"log_sd", DISTRIBUTION_BIT(AMSPH_POWDER_LOGNORMAL), 1},
    {"grain_radius_min", DISTRIBUTION_BIT(AMSPH_POWDER_LOGNORMAL), 1},
    {"grain_radius_max", DISTRIBUTION_BIT(AMSPH_POWDER_LOGNORMAL), 1},
    {"small_radius", DISTRIBUTION_BIT(AMSPH_POWDER_MIXED), 1},
    {"small_fraction", DISTRIBUTION_BIT(AMSPH_POWDER_MIXED), 0},
    {"seed", DISTRIBUTION_BIT(AMSPH_POWDER_LOGNORMAL) | DISTRIBUTION_BIT(AMSPH_POWDER_MIXED), 0},
};

/* A log-normal powder draws radii r0 exp(log_sd z), z standard normal,
 * again until one falls within [grain_radius_min, grain_radius_max]
 * (host/powder.c draw_radius): the fraction of draws it keeps,
 * Phi(ln(max / r0) / log_sd) - Phi(ln(min / r0) / log_sd). Below
 * LOGNORMAL_KEPT_MIN the bed would take a thousand draws a grain or more. */
#define LOGNORMAL_KEPT_MIN 1e-3

static double standard_normal_cdf(double z)
{
    return 0.5 * erfc(-z / sqrt(2.0));
}

static double lognormal_kept(const amsph_geometry *g)
{
    return standard_normal_cdf(log(g->grain_radius_max / g->grain_radius) / g->log_sd) -
           standard_normal_cdf(log(g->grain_radius_min / g->grain_radius) / g->log_sd);
}

/* Each distribution's keys where they apply and nowhere else; radii in
 * order; a region that holds the largest grain. */
static int finish_powder_bed(parser *p, const scope *sc)
{
    amsph_geometry *g = sc->target;
    const char *name = distribution_choices[g->distribution].name;
    for (size_t k = 0; k < sizeof powder_keys / sizeof powder_keys[0]; k++) {
        const int applies = (powder_keys[k].distributions & DISTRIBUTION_BIT(g->distribution)) != 0;
        const yaml_node_t *given = found(sc, powder_keys[k].key);
        if (given && !applies)
            return fail(p, line_of(given), "'%s%s' does not apply to distribution '%s'", sc->prefix,
                        powder_keys[k].key, name);
        if (!given && applies && powder_keys[k].required)
            return fail(p, line_of(sc->map), "missing required key '%s' in %s (distribution '%s')",
                        powder_keys[k].key, sc->label, name);
    }
    double largest = g->grain_radius;
    if (g->distribution == AMSPH_POWDER_LOGNORMAL) {
        if (!(g->grain_radius_min <= g->grain_radius && g->grain_radius <= g->grain_radius_max &&
              g->grain_radius_min < g->grain_radius_max))
            return fail(p, line_of(found(sc, "grain_radius_max")),
                        "'%sgrain_radius_min' (%g m), 'grain_radius' (%g m) and 'grain_radius_max' "
                        "(%g m) must be in increasing order, min below max",
                        sc->prefix, g->grain_radius_min, g->grain_radius, g->grain_radius_max);
        const double kept = lognormal_kept(g);
        if (kept < LOGNORMAL_KEPT_MIN)
            return fail(p, line_of(found(sc, "log_sd")),
                        "'%slog_sd' (%g) leaves a fraction %.3g of the log-normal's draws within "
                        "[grain_radius_min, grain_radius_max] (at least %g: the others are drawn again); "
                        "make log_sd smaller or the range wider",
                        sc->prefix, g->log_sd, kept, LOGNORMAL_KEPT_MIN);
        largest = g->grain_radius_max;
    }
    if (g->distribution == AMSPH_POWDER_MIXED && !(g->small_radius < g->grain_radius))
        return fail(p, line_of(found(sc, "small_radius")),
                    "'%ssmall_radius' (%g m) must be < 'grain_radius' (%g m)", sc->prefix,
                    g->small_radius, g->grain_radius);
    if (check_corners(p, sc, g->min, g->max))
        return CASE_ERROR;
    for (int d = 0; d < p->c->dim; d++)
        if (g->max[d] - g->min[d] < 2 * largest)
            return fail(p, line_of(found(sc, "max")),
                        "the powder bed's region is %g m across along %c, less than the diameter "
                        "%g m of its largest grain",
                        g->max[d] - g->min[d], "xyz"[d], 2 * largest);
    return 0;
}

static int finish_geometry(parser *p, const scope *sc)
{
    amsph_geometry *g = sc->target;
    g->line = (int)line_of(sc->map);
    g->has_temperature = found(sc, "temperature") != NULL;
    if (p->c->materials[g->material].phase == AMSPH_MATERIAL_GAS && g->kind != AMSPH_KIND_FLUID)
        return fail(p, line_of(found(sc, "kind")),
                    "'%skind' must be fluid: material '%s' is a gas (its particles are fluid)",
                    sc->prefix, p->c->materials[g->material].name);
    if (g->fill && sc->index == 0)
        return fail(p, line_of(found(sc, "fill")),
                    "'%sfill' fills around the blocks before it, and this is the first block: "
                    "list it after the shapes it surrounds",
                    sc->prefix);
    if (g->shape == AMSPH_SHAPE_BOX) {
        const yaml_node_t *open = found(sc, "open");
        if (open && g->layers == 0)
            return fail(p, line_of(open), "'%sopen' needs 'layers' > 0 (open faces of a wall)",
                        sc->prefix);
        return check_corners(p, sc, g->min, g->max);
    }
    if (g->shape == AMSPH_SHAPE_CYLINDER)
        return normalise_vector(p, sc, "axis", g->axis);
    if (g->shape == AMSPH_SHAPE_POWDER_BED)
        return finish_powder_bed(p, sc);
    return 0;
}

/* The beam's Gaussian is sampled at the bin columns (volumetric) or at the
 * surface particles (surface), a spacing b apart; the samples sum to the
 * beam's power to within about 2 exp(-pi^2 r_l^2 / (2 b^2)) per axis across
 * the beam (Poisson summation; the sums give +-1.4% at r_l = b, -57% to
 * +60% at b / 2 with the axis on a sample or between two), and a beam
 * much narrower than b falls between the samples or takes many times its
 * power. So the radius must reach the spacing. */
static int check_beam_sampled(parser *p, const scope *sc)
{
    const amsph_laser_settings *l = &p->c->laser;
    const int surface = l->absorption == AMSPH_ABSORPTION_SURFACE;
    const double spacing = surface ? p->c->dx : l->bin_size;
    if (l->radius < spacing)
        return fail(p, line_of(found(sc, "radius")),
                    "'laser.radius' (%g m) is below the spacing at which the beam is sampled, %s (%g m): "
                    "the samples would not hold the beam's power; make the radius at least that, or "
                    "the spacing smaller",
                    l->radius, surface ? "dx" : "laser.bin_size", spacing);
    return 0;
}

/* The beam direction (default: down), perpendicular to periodic directions;
 * off after on, room for both ramps; bins of dx by default; a radius the
 * samples resolve. */
static int finish_laser(parser *p, const scope *sc)
{
    static const char axis_name[3] = {'x', 'y', 'z'};
    amsph_laser_settings *l = &p->c->laser;
    const int dim = p->c->dim;
    l->enabled = 1;
    const yaml_node_t *direction = found(sc, "direction");
    if (!direction)
        l->direction[dim - 1] = -1.0;
    else if (normalise_vector(p, sc, "direction", l->direction))
        return CASE_ERROR;
    for (int d = 0; d < dim; d++)
        if (p->c->periodic[d] && l->direction[d] != 0)
            return fail(p, line_of(direction ? direction : sc->map),
                        "'laser.direction' must be perpendicular to the periodic direction %c (a "
                        "beam along it would wrap around the domain)",
                        axis_name[d]);
    const yaml_node_t *off = found(sc, "off_time");
    if (!off)
        l->off_time = INFINITY;
    else if (!(l->off_time > l->on_time))
        return fail(p, line_of(off), "'laser.off_time' (%g s) must be > 'laser.on_time' (%g s)",
                    l->off_time, l->on_time);
    if (2 * l->ramp_time > l->off_time - l->on_time)
        return fail(p, line_of(found(sc, "ramp_time")),
                    "'laser.ramp_time' (%g s) must be at most half of off_time - on_time (%g s): "
                    "the ramps up and down would overlap",
                    l->ramp_time, l->off_time - l->on_time);
    if (!found(sc, "bin_size"))
        l->bin_size = p->c->dx;
    return check_beam_sampled(p, sc);
}

/* The prescribed temperature stays at or above 0 K. */
static int finish_temperature_history(parser *p, const scope *sc)
{
    amsph_temperature_history *h = &p->c->temperature_history;
    h->enabled = 1;
    p->history_line = line_of(sc->map);
    const double lowest = h->form == AMSPH_HISTORY_SINE ? h->reference - fabs(h->amplitude)
                                                        : h->reference + fmin(h->amplitude, 0.0);
    if (lowest < 0)
        return fail(p, line_of(found(sc, "amplitude")),
                    "'temperature_history.amplitude' (%g K) takes the temperature to %g K, below 0 K",
                    h->amplitude, lowest);
    return 0;
}

/* Fuchs et al. 2022 Eq. 34 asks r_b < h. */
static int finish_barrier(parser *p, const scope *sc)
{
    const amsph_case *c = p->c;
    if (!(c->fluid.barrier_distance < c->h_over_dx * c->dx))
        return fail(p, line_of(found(sc, "distance")),
                    "'fluid.barrier.distance' (%g m) must be below the smoothing length "
                    "h_over_dx dx = %g m",
                    c->fluid.barrier_distance, c->h_over_dx * c->dx);
    return 0;
}

static int finish_scope(parser *p, const scope *sc)
{
    switch (sc->section) {
    case SEC_FLUID:
        p->c->fluid.enabled = 1;
        p->integration_line = line_of(found(sc, "integration") ? found(sc, "integration") : sc->map);
        return finish_verlet_cfl(p, sc);
    case SEC_BARRIER:
        return finish_barrier(p, sc);
    case SEC_THERMAL:
        p->c->thermal.enabled = 1;
        p->thermal_line = line_of(sc->map);
        return 0;
    case SEC_SURFACE:
        p->c->surface.enabled = 1;
        p->surface_line = line_of(sc->map);
        return 0;
    case SEC_LASER:
        return finish_laser(p, sc);
    case SEC_GRAINS:
        p->c->grains.enabled = 1;
        p->grains_line = line_of(sc->map);
        return 0;
    case SEC_LASER_PATH:
        return 0;
    case SEC_HISTORY:
        return finish_temperature_history(p, sc);
    case SEC_DOMAIN:
        return check_corners(p, sc, p->c->domain_min, p->c->domain_max);
    case SEC_MATERIAL:
        return finish_material(p, sc);
    case SEC_GEOMETRY:
        return finish_geometry(p, sc);
    case SEC_TOP:
        return finish_top(p, sc);
    }
    return 0;
}

static int load_scope(parser *p, scope *sc)
{
    if (collect_keys(p, sc) || (sc->section == SEC_MATERIAL && fill_from_preset(p, sc)))
        return CASE_ERROR;
    for (size_t i = 0; i < N_SPECS; i++)
        if (specs[i].section == sc->section && load_key(p, sc, i))
            return CASE_ERROR;
    return finish_scope(p, sc);
}

/* ---- documents ---------------------------------------------------------- */

static size_t line_at_offset(const char *text, size_t len, size_t offset)
{
    size_t line = 1;
    for (size_t i = 0; i < offset && i < len; i++)
        line += text[i] == '\n';
    return line;
}

static int yaml_error(const parser *p, const yaml_parser_t *yp, const char *text, size_t len)
{
    const char *problem = yp->problem ? yp->problem : "unknown problem";
    switch (yp->error) {
    case YAML_MEMORY_ERROR:
        return fail(p, 1, "out of memory while reading YAML");
    case YAML_READER_ERROR:
        return fail(p, line_at_offset(text, len, yp->problem_offset), "unreadable text: %s",
                    problem);
    default:
        break;
    }
    if (yp->context)
        return fail(p, yp->problem_mark.line + 1, "YAML syntax error: %s (%s on line %zu)", problem,
                    yp->context, yp->context_mark.line + 1);
    return fail(p, yp->problem_mark.line + 1, "YAML syntax error: %s", problem);
}

/* A case file holds exactly one document. */
static int check_no_second_document(const parser *p, yaml_parser_t *yp, const char *text,
                                    size_t len)
{
    yaml_document_t next;
    if (!yaml_parser_load(yp, &next))
        return yaml_error(p, yp, text, len);
    int more = yaml_document_get_root_node(&next) != NULL;
    size_t line = next.start_mark.line + 1;
    yaml_document_delete(&next);
    if (more)
        return fail(p, line, "a second YAML document starts here; a case file holds exactly one");
    return 0;
}

static int load_document(parser *p)
{
    const yaml_node_t *root = yaml_document_get_root_node(p->doc);
    if (!root)
        return fail(p, 1, "the case file is empty; expected keys such as 'dimension'");
    if (root->type != YAML_MAPPING_NODE)
        return fail(p, line_of(root), "a case file must be a map of keys, got %s",
                    describe(root).s);
    scope top;
    init_scope(&top, SEC_TOP, "top level", p->c, root);
    top.prefix[0] = '\0';
    return load_scope(p, &top);
}

/* The line where [ and { nest deeper than MAX_FLOW_DEPTH, or 0. Brackets in
 * quotes and comments count too; real case files never pile those up. */
static size_t too_deep_line(const char *text, size_t len)
{
    size_t depth = 0, line = 1;
    for (size_t i = 0; i < len; i++) {
        if (text[i] == '\n')
            line++;
        else if ((text[i] == '[' || text[i] == '{') && ++depth > MAX_FLOW_DEPTH)
            return line;
        else if ((text[i] == ']' || text[i] == '}') && depth > 0)
            depth--;
    }
    return 0;
}

int amsph_case_parse(const char *text, size_t len, const char *name, amsph_case *c, char *err,
                     size_t errlen)
{
    parser p = {.name = name ? name : "<string>", .err = err, .errlen = errlen, .c = c};
    if (err && errlen)
        err[0] = '\0';
    if (!text)
        len = 0;
    memset(c, 0, sizeof *c);
    snprintf(c->path, sizeof c->path, "%s", p.name);
    c->text_hash = text ? amsph_hash(AMSPH_HASH_START, text, len) : AMSPH_HASH_START;
    size_t deep = too_deep_line(text, len);
    if (deep)
        return fail(&p, deep, "lists or maps nested more than %d levels deep", MAX_FLOW_DEPTH);

    yaml_parser_t yp;
    if (!yaml_parser_initialize(&yp))
        return fail(&p, 1, "out of memory while reading YAML");
    yaml_parser_set_input_string(&yp, (const unsigned char *)(text ? text : ""), len);
    yaml_document_t doc;
    int rc;
    if (!yaml_parser_load(&yp, &doc)) {
        rc = yaml_error(&p, &yp, text, len);
    } else {
        p.doc = &doc;
        rc = check_no_second_document(&p, &yp, text, len);
        if (rc == 0)
            rc = load_document(&p);
        yaml_document_delete(&doc);
    }
    yaml_parser_delete(&yp);
    return rc;
}

/* Reads a whole file; on failure returns NULL with errno set (EFBIG: too large). */
static char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = NULL;
    size_t used = 0, size = 0;
    int failed = 0;
    for (;;) {
        if (used == size) {
            size_t grown_size = size ? 2 * size : 4096;
            char *grown = grown_size <= MAX_FILE_BYTES ? realloc(text, grown_size) : NULL;
            if (!grown) {
                errno = grown_size <= MAX_FILE_BYTES ? ENOMEM : EFBIG;
                failed = 1;
                break;
            }
            text = grown;
            size = grown_size;
        }
        size_t got = fread(text + used, 1, size - used, f);
        used += got;
        if (got == 0) {
            failed = ferror(f);
            break;
        }
    }
    int saved = errno;
    fclose(f);
    if (failed) {
        free(text);
        errno = saved;
        return NULL;
    }
    *len = used;
    return text;
}

int amsph_case_load(const char *path, amsph_case *c, char *err, size_t errlen)
{
    size_t len = 0;
    errno = 0;
    char *text = read_file(path, &len);
    if (!text) {
        if (err && errlen)
            snprintf(err, errlen, "%s: cannot read case file: %s", path,
                     errno ? strerror(errno) : "unknown error");
        return CASE_ERROR;
    }
    int rc = amsph_case_parse(text, len, path, c, err, errlen);
    free(text);
    return rc;
}

/* ---- key reference ------------------------------------------------------ */

static const char *type_name(value_type t)
{
    static const char *const names[] = {
        [VT_INT] = "integer",
        [VT_NUMBER] = "number",
        [VT_VECTOR] = "list of *dimension* numbers",
        [VT_BOOLS] = "list of *dimension* booleans",
        [VT_CHOICE] = "string",
        [VT_NAME] = "string",
        [VT_MATERIAL] = "string",
        [VT_FACES] = "list of face names",
        [VT_MAP] = "map",
        [VT_LIST] = "list of maps",
        [VT_PROPERTY] = "number or list of [T, value]",
    };
    return names[t];
}

static const char *choice_name(const choice *choices, int value)
{
    while (choices->name && choices->value != value)
        choices++;
    return choices->name;
}

const char *amsph_kind_name(int kind)
{
    const char *name = choice_name(kind_choices, kind);
    return name ? name : "unknown";
}

static shown default_text(const key_spec *k)
{
    shown out;
    if (k->flags & F_REQUIRED)
        snprintf(out.s, sizeof out.s, "required");
    else if ((k->flags & F_NO_DEFAULT) || k->type == VT_PROPERTY)
        snprintf(out.s, sizeof out.s, "not set");
    else if (k->type == VT_VECTOR)
        snprintf(out.s, sizeof out.s, "0");
    else if (k->type == VT_BOOLS)
        snprintf(out.s, sizeof out.s, "false");
    else if (k->type == VT_FACES)
        snprintf(out.s, sizeof out.s, "none");
    else if (k->type == VT_CHOICE)
        snprintf(out.s, sizeof out.s, "`%s`", choice_name(k->choices, (int)k->def));
    else
        snprintf(out.s, sizeof out.s, "%g", k->def);
    return out;
}

/* `a`, `b (3D)`, ...: the choices whose value is in mask (0: all of them). */
static void print_names(FILE *f, const choice *choices, unsigned mask)
{
    int first = 1;
    for (const choice *c = choices; c->name; c++) {
        if (mask && !(mask & VARIANT_BIT(c->value)))
            continue;
        fprintf(f, "%s`%s`", first ? "" : ", ", c->name);
        if (c->dim)
            fprintf(f, " (%dD)", c->dim);
        first = 0;
    }
}

/* The choices of the key that selects the variants of `section`. */
static const choice *variant_choices(section_id section)
{
    size_t i = 0;
    while (specs[i].section != section || !(specs[i].flags & F_SELECTS_VARIANT))
        i++;
    return specs[i].choices;
}

/* The "allowed" cell: variants, range, choices, counts and rules, with "; ". */
static void print_allowed(FILE *f, const key_spec *k)
{
    const char *sep = "";
    if (k->variants) {
        fprintf(f, "only for ");
        print_names(f, variant_choices(k->section), k->variants);
        sep = "; ";
    }
    shown range = range_text(k);
    if (range.s[0]) {
        fprintf(f, "%s%s", sep, range.s);
        sep = "; ";
    }
    if (k->choices) {
        fprintf(f, "%s", sep);
        print_names(f, k->choices, 0);
        sep = "; ";
    }
    if (k->type == VT_LIST) {
        fprintf(f, "%s%g to %g entries", sep, k->lo, k->hi);
        sep = "; ";
    }
    if (k->rule)
        fprintf(f, "%s%s", sep, k->rule);
}

void amsph_case_set_spacing(amsph_case *c, double dx)
{
    const double factor = dx / c->dx;
    c->dx = dx;
    c->laser.bin_size *= factor;
    c->grains.distance *= factor;
    c->fluid.barrier_distance *= factor;
}

void amsph_case_print_keys(void *file)
{
    FILE *f = file;
    fprintf(f, "| Key | Type | Unit | Default | Allowed | Description |\n");
    fprintf(f, "|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < N_SPECS; i++) {
        const key_spec *k = &specs[i];
        fprintf(f, "| `%s%s` | %s | %s | %s | ", section_prefix[k->section], k->key,
                type_name(k->type), k->unit ? k->unit : "-", default_text(k).s);
        print_allowed(f, k);
        fprintf(f, " | %s |\n", k->doc);
    }
    fprintf(f, "\nMaterial presets (`materials[].preset`); a key the material gives overrides the "
               "preset's:\n\n| Preset | Keys | Source |\n|---|---|---|\n");
    for (const choice *c = preset_choices + 1; c->name; c++) {
        fprintf(f, "| `%s` | ", c->name);
        const preset_key *keys = presets[c->value].keys;
        for (int k = 0; k < MAX_PRESET_KEYS && keys[k].key; k++)
            fprintf(f, "%s`%s: %s`", k ? ", " : "", keys[k].key, keys[k].value);
        fprintf(f, " | %s |\n", presets[c->value].source);
    }
}
