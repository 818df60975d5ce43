#include "grains.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "fluid.h"

#define PI 3.14159265358979323846

/* Chunks of the grain-by-grain counting sort (kernels/grains.cl): the sort
 * keeps the grid's order whatever the chunking; more chunks shorten each
 * item's loop, and cost grains x chunks counters. */
#define GRAIN_SORT_CHUNKS 256

static amsph_arg field(amsph_sim *s, amsph_field_id f)
{
    return amsph_arg_buffer(s->particles.field[f]);
}

/* The spin inertia of one particle, I_r = factor m_r (Fuchs et al. 2022
 * Eq. 36): a sphere of the particle's volume dx^3, 0.4 m R^2 with R =
 * (3/(4 pi))^(1/3) dx, or in 2D a disc of area dx^2, 0.5 m R^2 with R =
 * dx / sqrt(pi). (Fuchs print 0.4 m_r (0.75/pi)^(1/3) dx, without the
 * square that the dimensions need.) */
static double particle_inertia_factor(int dim, double dx)
{
    if (dim == 2)
        return 0.5 * dx * dx / PI;
    const double radius = cbrt(0.75 / PI) * dx;
    return 0.4 * radius * radius;
}

int amsph_grains_setup(amsph_sim *s, amsph_host_particles *h)
{
    const amsph_case *c = &s->config;
    amsph_grains_state *gs = &s->grains;
    if (c->grains.distance > s->support)
        return amsph_bad_input("'grains.contact_distance' (%g m) exceeds the kernel support (%g m)",
                               c->grains.distance, s->support);
    const int *grain = h->data[AMSPH_FIELD_GRAIN];
    const int *kind = h->data[AMSPH_FIELD_KIND];
    const amsph_real *mass = amsph_host_real(h, AMSPH_FIELD_MASS);
    gs->count = 0;
    gs->smallest_mass = INFINITY;
    for (int i = 0; i < h->n; ++i)
        if (kind[i] == AMSPH_KIND_GRAIN) {
            gs->count = grain[i] + 1 > gs->count ? grain[i] + 1 : gs->count;
            gs->smallest_mass = fmin(gs->smallest_mass, mass[i]);
        }
    grain_params *p = &gs->params;
    p->stiffness = (amsph_real)c->grains.stiffness;
    p->damping = (amsph_real)c->grains.damping;
    p->distance = (amsph_real)c->grains.distance;
    p->particle_inertia_factor = (amsph_real)particle_inertia_factor(c->dim, c->dx);
    for (int d = 0; d < 3; ++d)
        p->gravity[d] = (amsph_real)c->gravity[d];
    gs->recover_spin = 1;
    return 0;
}

int amsph_grains_allocate(amsph_sim *s)
{
    amsph_grains_state *gs = &s->grains;
    amsph_backend *b = s->backend;
    const size_t counters = (size_t)gs->count * GRAIN_SORT_CHUNKS * sizeof(int);
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)gs->count * GRAIN_RECORD * sizeof(amsph_real), &gs->records));
    AMSPH_CHECK(amsph_buffer_alloc(b, counters, &gs->chunk_count));
    AMSPH_CHECK(amsph_buffer_alloc(b, counters, &gs->chunk_offset));
    AMSPH_CHECK(amsph_buffer_alloc(b, AMSPH_SCAN_CHUNKS * sizeof(int), &gs->chunk_total));
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)s->particles.capacity * sizeof(int), &gs->order));
    /* spins start at 0 until the first sums recover them */
    const size_t bytes = (size_t)gs->count * GRAIN_RECORD * sizeof(amsph_real);
    amsph_real *zero = calloc(1, bytes);
    if (!zero)
        return amsph_fail("out of memory for %d grain records", gs->count);
    const int status = amsph_upload(b, gs->records, 0, bytes, zero);
    free(zero);
    return status;
}

void amsph_grains_free(amsph_sim *s)
{
    amsph_grains_state *gs = &s->grains;
    amsph_buffer_free(s->backend, gs->records);
    amsph_buffer_free(s->backend, gs->chunk_count);
    amsph_buffer_free(s->backend, gs->chunk_offset);
    amsph_buffer_free(s->backend, gs->chunk_total);
    amsph_buffer_free(s->backend, gs->order);
}

static int set_particle_velocities(amsph_sim *s)
{
    const int n = s->particles.n;
    return AMSPH_LAUNCH(s->backend, "grain_particle_velocity", n, field(s, AMSPH_FIELD_KIND),
                        field(s, AMSPH_FIELD_GRAIN), field(s, AMSPH_FIELD_POSITION), amsph_arg_int(n),
                        amsph_arg_buffer(s->grains.records), field(s, AMSPH_FIELD_VELOCITY));
}

/* One stage of the module's step, given the step's time (or half of it). */
typedef int (*grain_stage)(amsph_sim *s, double dt);

/* Runs `stage` timed as the grains' phase of the step (host/timers.h), then
 * returns to the phase that was current: the module's calls sit inside the
 * integration, forces and thermal phases. */
static int in_grains_phase(amsph_sim *s, grain_stage stage, double dt)
{
    amsph_phase outer;
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_GRAINS, &outer));
    AMSPH_CHECK(stage(s, dt));
    return amsph_sim_phase(s, outer, NULL);
}

static int kick(amsph_sim *s, double half_dt)
{
    const int count = s->grains.count;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "grain_kick", count, amsph_arg_int(count), amsph_arg_real(half_dt),
                             amsph_arg_buffer(s->grains.records)));
    return set_particle_velocities(s);
}

int amsph_grains_kick(amsph_sim *s, double half_dt)
{
    return in_grains_phase(s, kick, half_dt);
}

static int drift(amsph_sim *s, double dt)
{
    const int n = s->particles.n, count = s->grains.count;
    /* in 2D omega lies along z and the half turn keeps it (kernels/grains.cl) */
    if (s->config.dim == 3)
        AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "grain_midpoint_spin", count, amsph_arg_int(count), amsph_arg_real(dt),
                                 amsph_arg_buffer(s->grains.records)));
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "grain_drift", n, field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_GRAIN),
                             amsph_arg_int(n), amsph_arg_buffer(s->grains.records), amsph_arg_real(dt),
                             field(s, AMSPH_FIELD_POSITION)));
    return AMSPH_LAUNCH(s->backend, "grain_drift_centres", count, amsph_arg_int(count), amsph_arg_real(dt),
                        amsph_arg_buffer(s->grains.records));
}

int amsph_grains_drift(amsph_sim *s, double dt)
{
    return in_grains_phase(s, drift, dt);
}

/* The grain particles listed grain by grain (order), then the sums. */
static int grain_sums(amsph_sim *s, int recover_spin)
{
    amsph_grains_state *gs = &s->grains;
    amsph_backend *b = s->backend;
    const int n = s->particles.n;
    const int chunk = n > GRAIN_SORT_CHUNKS ? (n + GRAIN_SORT_CHUNKS - 1) / GRAIN_SORT_CHUNKS : 1;
    const int nchunks = n > 0 ? (n + chunk - 1) / chunk : 1;
    AMSPH_CHECK(AMSPH_LAUNCH(b, "grain_chunk_count", nchunks, field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_GRAIN),
                             amsph_arg_int(n), amsph_arg_int(chunk), amsph_arg_int(nchunks),
                             amsph_arg_int(gs->count), amsph_arg_buffer(gs->chunk_count)));
    AMSPH_CHECK(amsph_exclusive_scan(b, gs->chunk_count, gs->chunk_offset, gs->chunk_total, gs->count * nchunks));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "grain_chunk_scatter", nchunks, field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_GRAIN), amsph_arg_int(n), amsph_arg_int(chunk),
                             amsph_arg_int(nchunks), amsph_arg_buffer(gs->chunk_offset), amsph_arg_buffer(gs->order)));
    return AMSPH_LAUNCH(b, "grain_sums", gs->count, amsph_arg_buffer(gs->order), amsph_arg_buffer(gs->chunk_offset),
                        amsph_arg_int(nchunks), amsph_arg_int(gs->count), field(s, AMSPH_FIELD_POSITION),
                        field(s, AMSPH_FIELD_VELOCITY), field(s, AMSPH_FIELD_MASS),
                        field(s, AMSPH_FIELD_ACCELERATION), amsph_arg_bytes(&gs->params, sizeof gs->params),
                        amsph_arg_int(recover_spin), amsph_arg_buffer(gs->records));
}

/* The grain particles' forces (the step's time is not needed); after
 * amsph_fluid_density, whose fluid counts per cell the kernel reads. */
static int forces(amsph_sim *s, double unused_dt)
{
    (void)unused_dt;
    const amsph_grains_state *gs = &s->grains;
    const int n = s->particles.n;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "grain_particle_forces", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_VELOCITY), field(s, AMSPH_FIELD_WALL_VELOCITY),
                             field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_PRESSURE),
                             field(s, AMSPH_FIELD_GAS_WALL_PRESSURE), field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_SHEPARD), field(s, AMSPH_FIELD_LIQUID_FRACTION),
                             amsph_fluid_smoothing_length(s), field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MATERIAL), field(s, AMSPH_FIELD_GRAIN),
                             amsph_arg_buffer(s->grid.cell), amsph_arg_int(n),
                             amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry),
                             amsph_arg_buffer(s->grid.cell_start), amsph_arg_buffer(s->grid.fluid_count),
                             amsph_arg_buffer(s->materials), amsph_arg_bytes(&s->fluid, sizeof s->fluid),
                             amsph_arg_bytes(&gs->params, sizeof gs->params), field(s, AMSPH_FIELD_ACCELERATION)));
    return 0;
}

int amsph_grains_forces(amsph_sim *s)
{
    return in_grains_phase(s, forces, 0.0);
}

/* The grains' sums of the forces (the step's time is not needed). */
static int sum_forces(amsph_sim *s, double unused_dt)
{
    (void)unused_dt;
    AMSPH_CHECK(grain_sums(s, s->grains.recover_spin));
    s->grains.recover_spin = 0;
    return 0;
}

int amsph_grains_sum_forces(amsph_sim *s)
{
    return in_grains_phase(s, sum_forces, 0.0);
}

int amsph_grains_recover(amsph_sim *s)
{
    return grain_sums(s, 1);
}

/* Melting and capture (the step's time is not needed). */
static int change_phase(amsph_sim *s, double unused_dt)
{
    (void)unused_dt;
    const int n = s->particles.n;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "grain_capture", n, field(s, AMSPH_FIELD_POSITION), field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_MATERIAL), field(s, AMSPH_FIELD_LIQUID_FRACTION),
                             amsph_arg_buffer(s->grid.cell), amsph_arg_int(n),
                             amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry),
                             amsph_arg_buffer(s->grid.cell_start), amsph_arg_buffer(s->thermal_table),
                             amsph_arg_real(s->support), field(s, AMSPH_FIELD_GRAIN)));
    return AMSPH_LAUNCH(s->backend, "grain_change_phase", n, field(s, AMSPH_FIELD_LIQUID_FRACTION),
                        field(s, AMSPH_FIELD_MATERIAL), amsph_arg_int(n), amsph_arg_buffer(s->thermal_table),
                        field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_GRAIN));
}

int amsph_grains_change_phase(amsph_sim *s)
{
    return in_grains_phase(s, change_phase, 0.0);
}

void amsph_grains_dt(const amsph_sim *s, double *dt, const char **limit)
{
    amsph_lower_dt(dt, limit, 0.22 * sqrt(s->grains.smallest_mass / s->config.grains.stiffness), "contact");
}

int amsph_grains_save(amsph_sim *s, amsph_real **records, int *values)
{
    *values = s->grains.count * GRAIN_RECORD;
    *records = malloc((size_t)(*values > 0 ? *values : 1) * sizeof **records);
    if (!*records)
        return amsph_fail("out of host memory for %d grain records", s->grains.count);
    return amsph_grains_download(s, *records);
}

int amsph_grains_restore(amsph_sim *s, const amsph_real *records, int values)
{
    if (values != s->grains.count * GRAIN_RECORD)
        return amsph_bad_input("the saved state holds %d grain values; this case has %d grains of %d",
                               values, s->grains.count, GRAIN_RECORD);
    s->grains.recover_spin = 0;
    return amsph_upload(s->backend, s->grains.records, 0, (size_t)values * sizeof(amsph_real), records);
}

int amsph_grains_download(amsph_sim *s, amsph_real *records)
{
    return amsph_download(s->backend, s->grains.records, 0,
                          (size_t)s->grains.count * GRAIN_RECORD * sizeof(amsph_real), records);
}
