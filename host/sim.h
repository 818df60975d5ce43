/* A simulation: the case, its particles on a backend, the sorted grid and
 * the time step assembled from the case's modules:
 *   no module:   fluid particles fall under gravity (ballistic)
 *   fluid:       weakly compressible SPH (kernels/fluid.cl) with walls,
 *                adaptive dt and run guards;
 *   thermal:     enthalpy, conduction, phase change, radiation (kernels/thermal.cl),
 *                or instead a prescribed temperature history;
 *   laser:       the absorbed laser power of every particle (kernels/laser.cl),
 *                evaluated with the enthalpy update (thermal) or after every drift. */
#ifndef AMSPH_SIM_H
#define AMSPH_SIM_H

#include <signal.h>

#include "backend.h"
#include "case.h"
#include "grid.h"
#include "particles.h"
#include "timers.h"
#define AMSPH_SHARED_REAL amsph_real
#include "fluid_params.h"
#include "surface_params.h"
#include "thermal_params.h"

/* Terms of the energy ledger, as the thermal module books them. */
enum {
    AMSPH_LEDGER_LASER,
    AMSPH_LEDGER_RADIATION,
    AMSPH_LEDGER_EVAPORATION,
    AMSPH_LEDGER_WALLS,
    AMSPH_LEDGER_VISCOUS,
    AMSPH_LEDGER_TERMS
};

/* Time integrals of the heat exchanged by the material (fluid and solid),
 * J (J/m in 2D): enthalpy now - initial
 *   = laser - radiation - evaporation - evaporated - departed + walls + viscous. */
typedef struct {
    double initial;     /* sum of m h at the start */
    double laser;       /* absorbed laser energy */
    double radiation;   /* radiated from free surfaces */
    double evaporation; /* carried off by the vapour of free surfaces (Fuchs Eq. 18) */
    double evaporated;  /* m h of the particles removed above thermal.evaporation_temperature */
    double departed;    /* m h of the particles that left the domain */
    double walls;     /* given by the Dirichlet walls (negative: taken) */
    double viscous;   /* viscous dissipation turned into heat */
} amsph_energy_ledger;

/* Device scratch of the thermal step, one real per particle each. */
typedef struct {
    amsph_buffer *enthalpy_start, *rate_start, *temperature_previous;
    amsph_buffer *wall_temperature; /* mirrored temperature of walls (kernels/thermal.cl) */
    amsph_buffer *power[AMSPH_LEDGER_TERMS];
    amsph_buffer *evaporated; /* 1 for a particle that evaporates now, else 0 (evaporate_hot) */
} amsph_thermal_work;
#include "laser_params.h"
#include "grain_params.h"

/* Every parameter struct passed by value fits a kernel argument. */
_Static_assert(sizeof(fluid_params) <= AMSPH_ARG_MAX_BYTES, "fluid_params too large for amsph_arg");
_Static_assert(sizeof(thermal_params) <= AMSPH_ARG_MAX_BYTES, "thermal_params too large for amsph_arg");
_Static_assert(sizeof(surface_params) <= AMSPH_ARG_MAX_BYTES, "surface_params too large for amsph_arg");
_Static_assert(sizeof(laser_params) <= AMSPH_ARG_MAX_BYTES, "laser_params too large for amsph_arg");
_Static_assert(sizeof(grain_params) <= AMSPH_ARG_MAX_BYTES, "grain_params too large for amsph_arg");
_Static_assert(sizeof(grid_geometry) <= AMSPH_ARG_MAX_BYTES, "grid_geometry too large for amsph_arg");

/* The grains module's state (host/grains.h). */
typedef struct {
    int count;              /* grains (indices 0 .. count - 1 in the `grain` field) */
    grain_params params;
    double smallest_mass;   /* of a grain particle, kg (2D: kg/m), for the contact time step */
    int recover_spin;       /* the next sums take the angular velocities from the particles */
    amsph_buffer *records;  /* count x GRAIN_RECORD reals (kernels/grain_params.h) */
    amsph_buffer *chunk_count, *chunk_offset, *chunk_total; /* the grain-by-grain sort's counters */
    amsph_buffer *order;    /* the grain particles, grain by grain */
} amsph_grains_state;

/* The laser module's state (host/laser.h). */
typedef struct {
    laser_params params;      /* the beam at the last absorption */
    amsph_buffer *bin_weight; /* per node: sum of PIC weights (0 where the light is spent) */
    amsph_buffer *bin_power;  /* per node: absorbed power, W (2D: W/m) */
    double absorbed_power;    /* absorbed by all particles at the last absorption, W (2D: W/m) */
} amsph_laser_state;

typedef struct {
    amsph_case config;
    amsph_backend *backend; /* not owned */
    amsph_particles particles;
    amsph_grid grid;
    amsph_buffer *work;      /* one real per particle, from one launch to the next: reductions,
                                the summed gas density (amsph_fluid_density) */
    amsph_buffer *closest;   /* nearest-neighbour distance per particle (fluid) */
    amsph_buffer *others;    /* an int per particle: the other particles within its support (fluid) */
    amsph_buffer *shift;     /* shifting displacements, three reals per particle (amsph_fluid_shifts) */
    amsph_buffer *contact_pull; /* four reals per particle: the surface tension's pull and its weight
                                   (surface with grains; kernels/surface.cl surface_contact_pull) */
    amsph_buffer *tension_share[2]; /* four reals per particle each, the conservative form's share
                                       of the tension and its smoothing (kernels/surface.cl
                                       surface_share; surface.tension_form: conservative) */
    amsph_buffer *surface_blocks[2]; /* an int per block of cells: the blocks' distance from the
                                        liquid (surface; kernels/surface.cl surface_blocks_*) */
    amsph_buffer *plain_liquid;      /* one int: the liquid particles without a contact angle
                                        (surface; kernels/surface.cl surface_blocks_mark) */
    amsph_buffer *materials; /* per-material constants (kernels/materials.h) */
    fluid_params fluid;
    int reference_density_varies; /* rho0(T) is re-evaluated after every temperature change */
    double lightest_fluid_mass;   /* of the scene's fluid particles, kg (2D: kg/m); the barrier's step limit */
    thermal_params thermal;
    amsph_buffer *thermal_table; /* kernels/thermal_table.h */
    amsph_thermal_work thermal_work;
    amsph_energy_ledger ledger;
    int thermal_iterations; /* of the last step (midpoint: fixed-point iterations) */
    long long evaporated_particles; /* removed above thermal.evaporation_temperature, since the start */
    double thermal_dt;      /* the diffusion limit, s (fixed for the run) */
    amsph_laser_state laser;
    amsph_grains_state grains;
    surface_params surface;
    double h;       /* smoothing length, m */
    double support; /* kernel support radius, m */
    double time;    /* s */
    double dt;      /* last step, s */
    double dt_min;  /* a step below this stops the run, s */
    const char *dt_limit; /* which limit set the last step */
    long long step;
    /* the last state that passed the guards, kept on the device */
    amsph_particles last_good;
    double last_good_time;
    long long last_good_step;
    int guard_failed; /* the last step failed a guard (the error says which) */
    amsph_timers timers; /* off unless a benchmark turns them on */
} amsph_sim;

/* The sim's scalar state, which a checkpoint saves and a restart restores:
 * X(member) for each member of amsph_sim (a double or a long long; nested
 * members as `a.b`). A module that keeps state outside the particle fields
 * (an energy ledger, the absorbed laser energy) adds its member here. The
 * label dt_limit and guard_failed need not be kept: the next step sets the
 * one, and no checkpoint is written after a guard failed. */
#define AMSPH_SIM_SCALARS(X)                                                                       \
    X(time)                                                                                        \
    X(dt)                                                                                          \
    X(dt_min)                                                                                      \
    X(step)                                                                                        \
    X(last_good_time)                                                                              \
    X(last_good_step)                                                                              \
    X(particles.removed)                                                                           \
    X(last_good.removed)                                                                           \
    X(ledger.initial)                                                                              \
    X(ledger.laser)                                                                                \
    X(ledger.radiation)                                                                            \
    X(ledger.evaporation)                                                                          \
    X(ledger.evaporated)                                                                           \
    X(ledger.departed)                                                                             \
    X(evaporated_particles)                                                                        \
    X(ledger.walls)                                                                                \
    X(ledger.viscous)

#define AMSPH_SIM_SCALAR_ONE(member) +1
enum { AMSPH_SIM_SCALAR_COUNT = 0 AMSPH_SIM_SCALARS(AMSPH_SIM_SCALAR_ONE) };
#undef AMSPH_SIM_SCALAR_ONE

typedef struct {
    const char *name; /* the member, as written above */
    int integer;      /* 1: long long, 0: double */
    size_t offset;    /* in amsph_sim */
} amsph_sim_scalar;

extern const amsph_sim_scalar amsph_sim_scalars[AMSPH_SIM_SCALAR_COUNT];

typedef union {
    double real;
    long long integer;
} amsph_scalar_value;

/* The sim's state on the host: everything a restart needs besides the case. */
typedef struct {
    amsph_host_particles particles; /* every field */
    amsph_host_particles last_good; /* output fields of the last state that passed the guards */
    amsph_scalar_value scalar[AMSPH_SIM_SCALAR_COUNT]; /* in amsph_sim_scalars order */
    int grain_values;   /* grains x GRAIN_RECORD (the grains module), else 0 */
    amsph_real *grains; /* the grain records (kernels/grain_params.h) */
} amsph_sim_state;

/* Kernel support radius / h: 2 (Wendland C2) or 3 (quintic spline). */
double amsph_support_over_h(amsph_kernel_type kernel);

/* Builds the scene of the case on backend b (kernels built for the case's
 * dimension and smoothing kernel), sorts it and evaluates the initial rates. */
int amsph_sim_create(const amsph_case *c, amsph_backend *b, amsph_sim *s);
void amsph_sim_free(amsph_sim *s);

/* Downloads the state (st is freed by the caller with amsph_sim_state_free,
 * also on failure). */
int amsph_sim_save(amsph_sim *s, amsph_sim_state *st);
/* As amsph_sim_create, but the particles and scalars come from a saved
 * state of a sim of the same case, which continues exactly where it was:
 * nothing is re-evaluated. A state whose field set is not the one this case
 * has in this build is refused as bad input. */
int amsph_sim_restore(const amsph_case *c, amsph_backend *b, const amsph_sim_state *st, amsph_sim *s);
void amsph_sim_state_free(amsph_sim_state *st);

/* Switches the sim's timers to phase `next` (host/timers.h): a module calls
 * it before its kernels, and a nested one switches back to *previous. */
int amsph_sim_phase(amsph_sim *s, amsph_phase next, amsph_phase *previous);

/* Lowers the step *dt to candidate where that is smaller, and names the
 * limit that set it (*limit, shown in the progress line and series.csv). */
static inline void amsph_lower_dt(double *dt, const char **limit, double candidate, const char *name)
{
    if (candidate < *dt) {
        *dt = candidate;
        *limit = name;
    }
}

/* Largest |v| over the particles of a 3-vector field (velocity, acceleration). */
int amsph_sim_max_norm(amsph_sim *s, amsph_field_id f, double *out);

/* The step the stability limits allow now, s (sets s->dt_limit). */
int amsph_sim_stable_dt(amsph_sim *s, double *dt);

/* What amsph_sim_create would refuse of the case's grid and laser bins
 * (bad input), checked without a backend: for `amsph check`. */
int amsph_sim_check_layout(const amsph_case *c);
/* Advances by dt (kick-drift-kick), then checks the guards. */
int amsph_sim_step(amsph_sim *s, double dt);

/* Steps with the stable dt until exactly `target` (s). each_step (may be
 * NULL) is called after every step; when it returns non-zero the advance
 * stops early, with s->time short of target. */
int amsph_sim_advance(amsph_sim *s, double target, int (*each_step)(void *context, const amsph_sim *s),
                      void *context);

/* Where a restarted run takes up its output (amsph_checkpoint.run). */
typedef struct amsph_run_record amsph_run_record;

typedef struct {
    const char *outdir;
    int quiet;
    int force;                  /* write into a directory that holds files */
    long long max_steps;        /* > 0: stop when s->step reaches it */
    double checkpoint_interval; /* > 0: a checkpoint every this many wall seconds */
    const volatile sig_atomic_t *stop; /* non-NULL: stop when *stop becomes non-zero (a signal) */
    const amsph_run_record *resume; /* non-NULL: the sim was restored from this checkpoint */
    const char *resume_path;        /* ... read from this file */
} amsph_run_options;

/* Runs to the case's end time, writing snapshots at t = 0, every output
 * interval and at the end, a row of OUTDIR/series.csv with each, and
 * reporting progress on stderr. Stopped early (max_steps, *stop), it writes
 * a final snapshot and OUTDIR/checkpoint.h5. A failed guard writes the last
 * good state as a snapshot before returning the error. */
int amsph_sim_run(amsph_sim *s, const amsph_run_options *options);

#endif
