/* Case files: YAML → validated settings (amsph_case).
 *
 * Every key, its type, unit, range and default lives in one schema table in
 * case.c; `amsph keys` prints that table as the Markdown reference that
 * README.md carries. All lengths in m, times in s, SI everywhere. */
#ifndef AMSPH_CASE_H
#define AMSPH_CASE_H

#include <stddef.h>

#include "fluid_options.h"
#include "surface_options.h"
#include "kinds.h"

#define AMSPH_MAX_MATERIALS 16
#define AMSPH_MAX_GEOMETRY 64
#define AMSPH_MAX_LASER_PATH 64
#define AMSPH_NAME_LEN 64

typedef enum { AMSPH_KERNEL_WENDLAND = 0, AMSPH_KERNEL_QUINTIC = 1 } amsph_kernel_type;

/* Particle kinds as stored in the `kind` field; later kinds get new numbers. */
typedef enum {
    AMSPH_KIND_FLUID = KIND_FLUID,
    AMSPH_KIND_WALL = KIND_WALL,
    AMSPH_KIND_SOLID = KIND_SOLID,
    AMSPH_KIND_GRAIN = KIND_GRAIN
} amsph_kind;

/* The case file's name of a kind (`fluid`, `wall`, ...). */
const char *amsph_kind_name(int kind);

typedef enum {
    AMSPH_SHAPE_BOX = 0,
    AMSPH_SHAPE_CIRCLE = 1, /* 2D only */
    AMSPH_SHAPE_SPHERE = 2, /* 3D only */
    AMSPH_SHAPE_CYLINDER = 3, /* 3D only */
    AMSPH_SHAPE_POWDER_BED = 4 /* grains settled in a box (host/powder.h) */
} amsph_shape;

/* Grain radii of a powder bed (host/powder.h). */
typedef enum {
    AMSPH_POWDER_REGULAR = 0,   /* one radius, touching grains on a square array */
    AMSPH_POWDER_LOGNORMAL = 1, /* truncated log-normal radii */
    AMSPH_POWDER_MIXED = 2      /* two radii */
} amsph_powder_distribution;

typedef enum { AMSPH_BACKEND_OPENMP = 0, AMSPH_BACKEND_OPENCL = 1 } amsph_backend_kind;

/* A material property: a constant, or a piecewise-linear function of
 * temperature given by points (T[i], v[i]) with T increasing, constant
 * beyond the first and last point. */
#define AMSPH_MAX_TABLE 16
typedef struct {
    int n; /* 0: not given; 1: the constant v[0]; >= 2: a table */
    double T[AMSPH_MAX_TABLE]; /* K */
    double v[AMSPH_MAX_TABLE];
} amsph_property;

/* The phase of a material's fluid particles (materials[].phase). A gas is
 * the atmosphere around the liquid (Fuchs et al. 2022 Sec. 4.1): its own
 * fluid phase, outside the liquid for the surface terms, transparent to the
 * laser, and it neither melts nor evaporates. */
typedef enum { AMSPH_MATERIAL_LIQUID = 0, AMSPH_MATERIAL_GAS = 1 } amsph_material_phase;

/* Named materials of PHYSICS.md "Materials" (`preset` in case files). */
typedef enum {
    AMSPH_PRESET_NONE = 0,
    AMSPH_PRESET_STEEL_304 = 1,  /* 304 stainless steel (Russell 2018 Table 4.1) */
    AMSPH_PRESET_STEEL_FUCHS = 2 /* simplified stainless steel (Fuchs et al. 2022 Table 2) */
} amsph_material_preset;

typedef struct {
    char name[AMSPH_NAME_LEN];
    int preset;       /* amsph_material_preset whose values fill the keys not given */
    amsph_property density; /* reference density rho0(T), kg/m^3, > 0 (host/material.h) */
    double viscosity; /* dynamic viscosity (of the liquid), Pa s, >= 0 (default 0) */
    double sound_speed; /* artificial speed of sound c0, m/s, >= 0 (default 0: not set) */
    /* thermal module; the liquid_* ones default to the solid's */
    amsph_property specific_heat;        /* J/(kg K), > 0 */
    amsph_property liquid_specific_heat;
    amsph_property conductivity;         /* W/(m K), >= 0 */
    amsph_property liquid_conductivity;
    double melting_temperature; /* T_m, K; 0: the material does not melt */
    double melting_range;       /* width dT of the mushy interval [T_m - dT/2, T_m + dT/2], K */
    double latent_heat;         /* J/kg, >= 0 */
    double mushy_viscosity;     /* viscosity at the solidus (liquid fraction 0), Pa s */
    double emissivity;          /* in [0, 1], default 0 */
    /* surface module: sigma(T) = sigma0 + slope (T - T_ref) - R T Gamma_s ln(1 + k_l a_s
     * exp(-dH0/(R T))), at least sigma_min (kernels/surface.cl); all default 0 */
    double surface_tension;                       /* sigma0, N/m */
    double surface_tension_slope;                 /* d sigma/dT of the clean surface, N/(m K) */
    double surface_tension_reference_temperature; /* T_ref, K */
    double surface_tension_minimum;               /* sigma_min, N/m */
    double surfactant_excess;                     /* Gamma_s, mol/m^2 */
    double surfactant_segregation;                /* k_l */
    double surfactant_activity;                   /* a_s */
    double surfactant_enthalpy;                   /* dH0, J/mol */
    /* evaporation (Fuchs et al. 2022 Eqs. 10, 18; kernels/vapour.h); a material
     * with recoil_pressure_constant 0 (the default) does not evaporate */
    double boiling_temperature;            /* T_v, K */
    double recoil_pressure_constant;       /* C_P of p_v(T) = C_P exp(-C_T (1/T - 1/T_v)), Pa */
    double recoil_temperature_constant;    /* C_T = molar latent heat / R, K */
    double evaporation_latent_heat;        /* h_v, J/kg */
    double vapour_mass_constant;           /* C_M = M / (2 pi R), K s^2/m^2 */
    double sticking_coefficient;           /* c_s, default 1 */
    double evaporation_enthalpy_reference; /* T_h,0 of h(T) in Eq. 18, K, default 0 */
    int phase; /* AMSPH_MATERIAL_LIQUID or _GAS: a gas is a fluid phase of its own (Fuchs et al. 2022 Sec. 4.1) */
    /* wetting (Fuchs et al. 2022 Sec. 3.3.3; kernels/surface.cl) */
    double contact_angle;            /* theta0 of this liquid on solids and walls, degrees;
                                        0: not set (the liquid wets completely) */
    double wetting_transition_range; /* dT_s: a solid of this material fades out of the solid
                                        colour over [T_sol - dT_s, T_sol], K, default 5 */
} amsph_material;

/* Faces of a box, as bits of amsph_geometry.open_faces: bit 2d is the face at
 * min along axis d ("-x", "-y", "-z"), bit 2d+1 the face at max ("+x", ...). */
#define AMSPH_FACE_BIT(axis, upper) (1u << (2 * (axis) + ((upper) ? 1 : 0)))

typedef struct {
    amsph_shape shape;
    amsph_kind kind;
    int material;          /* index into amsph_case.materials */
    double min[3], max[3]; /* box or powder-bed region corners, m (unused components 0) */
    double center[3];      /* circle/sphere centre; cylinder: centre of the base, m */
    double radius;         /* circle/sphere/cylinder radius, m */
    double axis[3];        /* cylinder axis, unit vector (normalised by the parser) */
    double length;         /* cylinder length along axis, m */
    int layers;            /* box only: 0 = filled box; n > 0 = n particle layers of wall
                              outside the box faces (a tank or channel around the box) */
    unsigned open_faces;   /* box with layers > 0: faces without wall (AMSPH_FACE_BIT) */
    double velocity[3];    /* initial velocity, m/s (default 0) */
    double temperature;    /* initial temperature, K */
    int has_temperature;   /* 1 if `temperature` was given */
    int hydrostatic;       /* 1: initial density in hydrostatic balance (fluid module) */
    int fill;              /* 1: only the lattice points away from the particles of the blocks
                              before it (a gas around the other shapes) */
    /* powder bed only (host/powder.h) */
    amsph_powder_distribution distribution; /* default regular */
    double grain_radius;     /* regular: every grain; lognormal: exp(mean of ln r); mixed: the
                                large grains, m */
    double log_sd;           /* lognormal: standard deviation of ln r */
    double grain_radius_min; /* lognormal: truncation of the radii, m */
    double grain_radius_max;
    double small_radius;     /* mixed: radius of the small grains, m */
    double small_fraction;   /* mixed: number fraction of small grains, default 0.5 */
    int seed;                /* lognormal, mixed: seed of the deposition, default 1 */
    int line;              /* line of the block in the case file, for messages */
} amsph_geometry;

/* The fluid module (weakly compressible SPH); on when the case has a
 * `fluid:` section. Choices take the values of kernels/fluid_options.h. */
typedef struct {
    int enabled;
    int density_diffusion;      /* DIFFUSION_*, default DIFFUSION_RUSSELL */
    double delta;               /* delta-SPH coefficient, default 0.1 */
    int continuity;             /* CONTINUITY_*, default CONTINUITY_PLAIN */
    int pressure_gradient;      /* PRESSURE_*, default PRESSURE_RENORMALISED */
    int viscosity;              /* VISCOSITY_*, default VISCOSITY_LAMINAR */
    double artificial_alpha;    /* Monaghan alpha, default 0.02 */
    double background_pressure; /* Pa, default 0 */
    int clamp_negative_pressure; /* 1: p = max(p, background_pressure), default 0 */
    double tensile_correction;  /* Monaghan (2000) artificial-pressure epsilon under tension, default 0 */
    int wall_slip;              /* WALL_*, default WALL_NO_SLIP */
    double cfl;                 /* acoustic CFL number, default 0.25 */
    double dt_min;              /* s: a step below it stops the run; default 0: 1e-6 of the first step */
    double min_pair_distance;   /* guard: nearest pair below this fraction of dx stops the run, default 0.3 */
    double max_density_error;   /* guard: |rho - rho0| / rho0 above this stops the run, default 0.1 */
    double damping_rate;        /* relaxation: u *= exp(-rate dt) each step, 1/s, default 0 */
    double damping_end;         /* ... while t < damping_end, s, default 0 */
    double shifting;            /* particle shifting coefficient A (D = A h |u| dt), default 0: off */
    int gas_density;            /* GAS_DENSITY_*, default continuity */
    double transport_pressure;  /* background pressure of the transport velocity, Pa, default 0: off */
    int smoothing_length;       /* SMOOTHING_*, default SMOOTHING_FIXED */
    double max_smoothing_ratio; /* SMOOTHING_VOLUME: the largest h / h0 the grid serves, default 1.1 */
    int integration;            /* INTEGRATION_*, default INTEGRATION_LEAPFROG */
    int verlet_steps;           /* INTEGRATION_VERLET: every this many steps one is an Euler step, default 40 */
    /* barrier forces of too-close pairs (Fuchs et al. 2022 Eq. 34), on with a
     * `barrier:` section; 2D: per metre of depth */
    double barrier_stiffness;   /* k_b, kg/s^2 (2D: kg/(m s^2)); 0: off */
    double barrier_damping;     /* d_b, kg/(m s) (2D: kg/(m^2 s)), default 0 */
    double barrier_distance;    /* r_b, m, below the smoothing length */
} amsph_fluid_settings;

/* The thermal module (enthalpy, conduction, phase change, radiation); on
 * when the case has a `thermal:` section. */
typedef enum { AMSPH_THERMAL_EXPLICIT = 0, AMSPH_THERMAL_MIDPOINT = 1 } amsph_thermal_integration;

typedef struct {
    int enabled;
    int integration;            /* amsph_thermal_integration, default explicit */
    double tolerance;           /* midpoint: max |T^{i+1} - T^i| / T^n to stop, default 1e-6 */
    int max_iterations;         /* midpoint: iteration cap, default 20 */
    double diffusion_number;    /* dt <= diffusion_number rho c h^2 / k, default 0.1 */
    int radiation;              /* 1: free surfaces radiate (Russell Eq. 3.39), default 0 */
    double ambient_temperature; /* T_inf of the radiation, K, default 300 */
    int viscous_heating;        /* 1: tau : grad u heats the fluid (kernels/thermal.cl), default 0 */
    int evaporative_cooling;    /* 1: free surfaces lose the heat of Fuchs Eq. 18, default 0 */
    int recoil_pressure;        /* 1: the recoil force of Fuchs Eqs. 10, 30 on fluid, default 0 */
    double evaporation_temperature; /* particles above it are removed, K; 0: never (default) */
} amsph_thermal_settings;
/* The surface module (surface tension and Marangoni force on free
 * surfaces, kernels/surface.cl); on when the case has a `surface:` section. */
typedef struct {
    int enabled;
    int tension;          /* 1: the normal (curvature) force, default 1 */
    int marangoni;        /* 1: the Marangoni force, default 0 */
    int tension_form;     /* TENSION_FORM_* (kernels/surface_options.h), default csf */
    double h_over_dx;     /* smoothing length of the surface terms / dx, default: support 3.6 dx */
    double normal_cutoff; /* a normal counts where |n| h >= this, default 0.1 */
    double min_shepard;   /* particles with a Shepard sum below this carry no surface force */
    double interface_viscosity; /* alpha0 of Fuchs et al. 2022 Eq. 32; 0: off */
} amsph_surface_settings;

/* Mobile powder grains (rigid bodies of particles, host/grains.h); on when
 * the case has a `grains:` section, which the blocks of kind `grain` need. */
typedef struct {
    int enabled;
    double stiffness; /* contact stiffness k_c (Fuchs et al. 2022 Eq. 39), kg/s^2, > 0 */
    double damping;   /* contact damping d_c, kg/s, >= 0 (default 0) */
    double distance;  /* contact distance, m (default dx) */
} amsph_grains_settings;

/* A temperature prescribed uniformly on every particle, for cases without
 * the thermal module (host/thermal.h); on when the case has a
 * `temperature_history:` section:
 *   sine: T(t) = T_ref + A sin(2 pi f t)
 *   ramp: T(t) = T_ref + A min(t / duration, 1) */
typedef enum { AMSPH_HISTORY_SINE = 0, AMSPH_HISTORY_RAMP = 1 } amsph_history_form;

typedef struct {
    int enabled;
    amsph_history_form form; /* default sine */
    double reference;        /* T_ref, K, >= 0 */
    double amplitude;        /* A, K */
    double frequency;        /* f, Hz, > 0 (sine) */
    double duration;         /* s, > 0 (ramp) */
} amsph_temperature_history;

typedef enum { AMSPH_ABSORPTION_VOLUMETRIC = 0, AMSPH_ABSORPTION_SURFACE = 1 } amsph_absorption;

/* One leg of the beam's path: from the previous point straight to `to`. */
typedef struct {
    double to[3]; /* end point, m (unused components 0) */
    double speed; /* m/s, > 0 */
} amsph_laser_segment;

/* The laser module (a Gaussian beam, host/laser.h); on when the case has a
 * `laser:` section. In 2D the simulated plane is a slice through the beam
 * axis, so absorbed powers are per metre of depth. */
typedef struct {
    int enabled;
    double power;                  /* beam power P, W, > 0 */
    double radius;                 /* 1/e^2 radius r_l, m, > 0 */
    amsph_absorption absorption;   /* default volumetric */
    double absorption_coefficient; /* Beer-Lambert alpha, 1/m (volumetric) */
    double absorptivity;           /* non-reflected fraction zeta, in (0, 1], default 1 */
    double direction[3];           /* unit vector; default -y (2D), -z (3D) */
    double start[3];               /* beam centre at t = 0, m */
    int n_path;                    /* segments followed after start */
    amsph_laser_segment path[AMSPH_MAX_LASER_PATH];
    double on_time;                /* s, default 0 */
    double off_time;               /* s, > on_time; default INFINITY (never off) */
    double ramp_time;              /* linear ramp after on and before off, s, default 0 */
    double bin_size;               /* side of a bin, m; default dx */
    double window;                 /* columns reach this many radii from the axis, default 3 */
} amsph_laser_settings;

typedef struct {
    char path[512];       /* the file it came from (or the name given to the string parser) */
    unsigned long long text_hash; /* amsph_hash of the case text: a restart must match it */
    int dim;              /* 2 or 3 */
    double domain_min[3]; /* m; components >= dim are 0 */
    double domain_max[3];
    int periodic[3];      /* 1 where the direction is periodic */
    double dx;            /* initial particle spacing, m, > 0 */
    double h_over_dx;     /* smoothing length / dx, default 1.2, in [1, 3] */
    amsph_kernel_type kernel; /* default Wendland C2 */
    double end_time;      /* s, > 0 */
    double output_interval; /* s, > 0 */
    amsph_backend_kind backend; /* default openmp; the CLI's --backend overrides */
    int device;           /* OpenCL device index, default -1 (first); --device overrides */
    double gravity[3];    /* m/s^2, default 0 */
    amsph_fluid_settings fluid;
    amsph_thermal_settings thermal;
    amsph_surface_settings surface;
    amsph_laser_settings laser;
    amsph_grains_settings grains;
    amsph_temperature_history temperature_history;
    int n_materials;
    amsph_material materials[AMSPH_MAX_MATERIALS];
    int n_geometry;
    amsph_geometry geometry[AMSPH_MAX_GEOMETRY];
} amsph_case;

/* Parses and validates. Returns 0 on success; otherwise a non-zero status and
 * writes one line "file:line: message" (no trailing newline) into err. */
int amsph_case_load(const char *path, amsph_case *c, char *err, size_t errlen);
int amsph_case_parse(const char *text, size_t len, const char *name, amsph_case *c, char *err,
                     size_t errlen);

/* Sets the spacing to dx and scales the lengths that the case sizes in dx
 * along (host/case.c gives them dx by default, and they are numerical, not
 * the scene's): the laser bins, the grains' contact distance (Fuchs et al.
 * 2022 Eq. 40: dx) and the barrier forces' reach (Fuchs Eq. 34: dx / 2).
 * The bodies, powder-bed grains included, keep their sizes: the scene is
 * the same at a finer or coarser resolution. */
void amsph_case_set_spacing(amsph_case *c, double dx);

/* Writes the Markdown key reference (one table row per key, with unit and
 * default) to the stream; README.md carries its output. */
void amsph_case_print_keys(void *file /* FILE * */);

#endif
