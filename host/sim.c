#include "sim.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "evaporation.h"
#include "fluid.h"
#include "grains.h"
#include "guards.h"
#include "laser.h"
#include "materials.h"
#include "scene.h"
#include "surface.h"
#include "thermal.h"

/* Steps between copies of the state that passed the guards. */
#define LAST_GOOD_INTERVAL 20

double amsph_support_over_h(amsph_kernel_type kernel)
{
    return kernel == AMSPH_KERNEL_QUINTIC ? 3.0 : 2.0; /* SUPPORT_OVER_H of kernels/smoothing.h */
}

/* The constants of sigma(T) (kernels/surface.cl) of one material. */
static void surface_tension_row(const amsph_material *m, amsph_real *row)
{
    const int surfactant = m->surfactant_excess > 0;
    row[MATERIAL_SURFACE_TENSION] = (amsph_real)m->surface_tension;
    row[MATERIAL_SURFACE_TENSION_SLOPE] = (amsph_real)m->surface_tension_slope;
    row[MATERIAL_SURFACE_TENSION_TREF] = (amsph_real)m->surface_tension_reference_temperature;
    row[MATERIAL_SURFACE_TENSION_MIN] = (amsph_real)m->surface_tension_minimum;
    row[MATERIAL_SURFACTANT_EXCESS] = (amsph_real)m->surfactant_excess;
    row[MATERIAL_SURFACTANT_LOG_K] =
        (amsph_real)(surfactant ? log(m->surfactant_segregation * m->surfactant_activity) : 0.0);
    row[MATERIAL_SURFACTANT_ENTHALPY] = (amsph_real)m->surfactant_enthalpy;
}

/* The constants of evaporation (kernels/vapour.h) of one material;
 * h(T_h,0) needs the thermal tables (the recoil force alone does not). */
static void evaporation_row(const amsph_material *m, amsph_real *row)
{
    const double reference = m->specific_heat.n ? amsph_thermal_enthalpy(m, m->evaporation_enthalpy_reference) : 0.0;
    row[MATERIAL_RECOIL_PRESSURE] = (amsph_real)m->recoil_pressure_constant;
    row[MATERIAL_RECOIL_TEMPERATURE] = (amsph_real)m->recoil_temperature_constant;
    row[MATERIAL_BOILING_TEMPERATURE] = (amsph_real)m->boiling_temperature;
    row[MATERIAL_VAPOUR_HEAT] = (amsph_real)(m->evaporation_latent_heat - reference);
    row[MATERIAL_VAPOUR_FLUX] = (amsph_real)(0.82 * m->sticking_coefficient * sqrt(m->vapour_mass_constant));
}

/* The constants of the contact angle (kernels/surface.cl) of one material:
 * theta0 in radians, and the temperatures between which a fixed solid of
 * a melting material fades from solid colour 1 to 0 (Fuchs et al. 2022
 * Sec. 3.3.3: chi = f-bar[T, T_sol - dT_s, T_sol]; amsph's solid melts at
 * the solidus, host/thermal.c). */
static void wetting_row(const amsph_material *m, amsph_real *row)
{
    row[MATERIAL_CONTACT_ANGLE] = (amsph_real)(m->contact_angle * 3.14159265358979323846 / 180.0);
    if (m->melting_temperature > 0) {
        const double solidus = m->melting_temperature - 0.5 * m->melting_range;
        row[MATERIAL_SOLID_COLOUR_LOW] = (amsph_real)(solidus - m->wetting_transition_range);
        row[MATERIAL_SOLID_COLOUR_HIGH] = (amsph_real)solidus;
    }
}

static int upload_materials(amsph_sim *s)
{
    const amsph_case *c = &s->config;
    amsph_real table[AMSPH_MAX_MATERIALS * MATERIAL_STRIDE] = {0};
    for (int m = 0; m < c->n_materials; ++m) {
        const amsph_material *mat = &c->materials[m];
        amsph_real *row = table + MATERIAL_STRIDE * m;
        row[MATERIAL_SOUND_SPEED] = (amsph_real)mat->sound_speed;
        row[MATERIAL_VISCOSITY] = (amsph_real)mat->viscosity;
        row[MATERIAL_MUSHY_VISCOSITY] = (amsph_real)mat->mushy_viscosity;
        row[MATERIAL_GAS] = mat->phase == AMSPH_MATERIAL_GAS;
        surface_tension_row(mat, row);
        evaporation_row(mat, row);
        wetting_row(mat, row);
        row[MATERIAL_DENSITY_POINTS] = (amsph_real)mat->density.n;
        for (int i = 0; i < mat->density.n; ++i) {
            row[MATERIAL_DENSITY_TEMPERATURE + i] = (amsph_real)mat->density.T[i];
            row[MATERIAL_DENSITY_VALUE + i] = (amsph_real)mat->density.v[i];
        }
    }
    const size_t bytes = sizeof table;
    AMSPH_CHECK(amsph_buffer_alloc(s->backend, bytes, &s->materials));
    return amsph_upload(s->backend, s->materials, 0, bytes, table);
}

/* Density over the step dt (fluid module), the absorbed laser power at the
 * step's end time (laser module without the thermal module, which absorbs
 * at the middle of its enthalpy step), then the acceleration of every
 * particle, from the state after the drift. */
static int compute_rates(amsph_sim *s, double dt)
{
    if (s->config.fluid.enabled && !s->fluid.one_pass) {
        AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_DENSITY, NULL));
        AMSPH_CHECK(amsph_fluid_density(s, dt));
    }
    if (s->config.laser.enabled && !s->config.thermal.enabled)
        AMSPH_CHECK(amsph_laser_absorb(s, s->time + dt));
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_FORCES, NULL));
    if (s->config.fluid.enabled) {
        AMSPH_CHECK(amsph_fluid_forces(s));
        if (s->config.grains.enabled)
            AMSPH_CHECK(amsph_grains_forces(s));
        if (s->config.thermal.enabled && s->config.thermal.recoil_pressure) {
            AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_SURFACE, NULL));
            AMSPH_CHECK(amsph_evaporation_recoil(s));
        }
        if (s->config.surface.enabled) {
            AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_SURFACE, NULL));
            AMSPH_CHECK(amsph_surface_forces(s));
        }
        return s->config.grains.enabled ? amsph_grains_sum_forces(s) : 0;
    }
    amsph_particles *p = &s->particles;
    const double *g = s->config.gravity;
    return AMSPH_LAUNCH(s->backend, "body_force", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                        amsph_arg_int(p->n), amsph_arg_real(g[0]), amsph_arg_real(g[1]),
                        amsph_arg_real(g[2]), amsph_arg_buffer(p->field[AMSPH_FIELD_ACCELERATION]));
}

/* The temperature at the step's end, from the thermal module or the
 * prescribed history, and the reference densities that follow it. */
static int update_temperature(amsph_sim *s, double dt)
{
    if (s->config.thermal.enabled || s->config.temperature_history.enabled)
        AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_THERMAL, NULL));
    if (s->config.thermal.enabled)
        AMSPH_CHECK(amsph_thermal_advance(s, dt));
    else if (s->config.temperature_history.enabled)
        AMSPH_CHECK(amsph_thermal_prescribe(s, s->time + dt));
    if (s->reference_density_varies)
        AMSPH_CHECK(amsph_fluid_reference_density(s));
    return 0;
}

/* The sort after a step's move: a position that is not finite there is a
 * state that blew up, a failed guard (the run writes the last good state). */
static int sort_moved(amsph_sim *s)
{
    AMSPH_CHECK(amsph_grid_sort(&s->grid, &s->particles));
    s->guard_failed = s->grid.not_finite > 0;
    if (s->guard_failed)
        return amsph_fail("guard 'finite values' failed: step %lld, t = %.6g s: %d particles have a position "
                          "that is not finite (NaN or inf); reduce cfl or check the case's forces and "
                          "material values",
                          s->step + 1, s->time, s->grid.not_finite);
    return 0;
}

static int keep_last_good(amsph_sim *s)
{
    s->last_good_time = s->time;
    s->last_good_step = s->step;
    return amsph_particles_copy_output(&s->last_good, &s->particles);
}

#define SCALAR_INFO(member)                                                                        \
    {#member, _Generic(((amsph_sim *)0)->member, long long: 1, double: 0), offsetof(amsph_sim, member)},
const amsph_sim_scalar amsph_sim_scalars[AMSPH_SIM_SCALAR_COUNT] = {AMSPH_SIM_SCALARS(SCALAR_INFO)};
#undef SCALAR_INFO

/* The case's particles on the host: the scene, with the fields of the
 * enabled modules (which also fill their settings in s). */
static int build_host_particles(amsph_sim *s, amsph_host_particles *host)
{
    int status = amsph_scene_build(&s->config, host);
    if (!status)
        status = amsph_host_add_field(host, AMSPH_FIELD_ACCELERATION);
    if (!status && s->config.fluid.enabled)
        status = amsph_fluid_setup(s, host);
    if (!status && s->config.thermal.enabled)
        status = amsph_thermal_setup(s, host);
    if (!status && s->config.surface.enabled)
        status = amsph_surface_setup(s, host);
    if (!status && s->config.laser.enabled)
        status = amsph_laser_setup(s, host);
    if (!status && s->config.grains.enabled)
        status = amsph_grains_setup(s, host);
    return status;
}

static int build_particles(amsph_sim *s)
{
    amsph_host_particles host;
    int status = build_host_particles(s, &host);
    if (!status)
        status = amsph_particles_upload(s->backend, &host, &s->particles);
    amsph_host_free(&host);
    return status;
}

/* The kernel's support at the case's initial smoothing length, m. */
static double kernel_support(const amsph_case *c)
{
    return amsph_support_over_h(c->kernel) * c->h_over_dx * c->dx;
}

/* The grid's cells hold the largest support of the fluid's pair loops
 * (kernels/fluid.cl). */
static double grid_support(const amsph_case *c)
{
    return amsph_fluid_max_smoothing_ratio(c) * kernel_support(c);
}

int amsph_sim_check_layout(const amsph_case *c)
{
    AMSPH_CHECK(amsph_grid_check_layout(c->dim, c->domain_min, c->domain_max, c->periodic, grid_support(c)));
    int lateral_nodes, depth_nodes;
    if (c->laser.enabled && c->laser.absorption == AMSPH_ABSORPTION_VOLUMETRIC)
        AMSPH_CHECK(amsph_laser_bins(c, kernel_support(c), &lateral_nodes, &depth_nodes));
    return 0;
}

/* What every sim has before its particles: settings, a layout the case
 * allows, and built kernels. */
static int prepare(const amsph_case *c, amsph_backend *b, amsph_sim *s)
{
    memset(s, 0, sizeof *s);
    s->config = *c;
    s->backend = b;
    AMSPH_CHECK(amsph_sim_check_layout(c)); /* before the scene is built */
    s->h = c->h_over_dx * c->dx;
    s->support = kernel_support(c);
    s->dt_limit = "none";
    amsph_build_options build = {.dim = c->dim, .kernel = (int)c->kernel};
    return amsph_build(b, &build);
}

/* The grid and work buffers, once the particles are on the device, and
 * the fluid's constants worked out on the device with them (the lattice's
 * kernel sum of a summed gas density: amsph_fluid_start), for a new run and
 * a restart alike. */
static int allocate_device_state(amsph_sim *s)
{
    const amsph_case *c = &s->config;
    amsph_backend *b = s->backend;
    const int capacity = s->particles.capacity;
    AMSPH_CHECK(amsph_grid_init(&s->grid, b, c->dim, c->domain_min, c->domain_max, c->periodic, grid_support(c),
                                capacity));
    s->grid.recomputed = amsph_fluid_recomputed_fields(s);
    if (c->surface.enabled)
        AMSPH_CHECK(amsph_surface_allocate(s));
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * sizeof(amsph_real), &s->work));
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * sizeof(amsph_real), &s->closest));
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * sizeof(int), &s->others));
    if (amsph_fluid_shifts(&c->fluid))
        AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * 3 * sizeof(amsph_real), &s->shift));
    if (c->grains.enabled)
        AMSPH_CHECK(amsph_grains_allocate(s));
    if (c->grains.enabled && c->surface.enabled)
        AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * 4 * sizeof(amsph_real), &s->contact_pull));
    AMSPH_CHECK(upload_materials(s));
    return c->fluid.enabled ? amsph_fluid_start(s) : 0;
}

int amsph_sim_create(const amsph_case *c, amsph_backend *b, amsph_sim *s)
{
    AMSPH_CHECK(prepare(c, b, s));
    AMSPH_CHECK(build_particles(s));
    AMSPH_CHECK(allocate_device_state(s));
    AMSPH_CHECK(amsph_grid_sort(&s->grid, &s->particles));
    if (c->thermal.enabled)
        AMSPH_CHECK(amsph_thermal_start(s));
    AMSPH_CHECK(compute_rates(s, 0.0));
    return keep_last_good(s);
}

void amsph_sim_free(amsph_sim *s)
{
    if (!s->backend)
        return;
    amsph_grid_free(&s->grid, s->backend);
    amsph_particles_free(&s->particles);
    amsph_particles_free(&s->last_good);
    amsph_buffer_free(s->backend, s->work);
    amsph_buffer_free(s->backend, s->closest);
    amsph_buffer_free(s->backend, s->others);
    amsph_buffer_free(s->backend, s->shift);
    amsph_buffer_free(s->backend, s->contact_pull);
    for (int k = 0; k < 2; ++k) {
        amsph_buffer_free(s->backend, s->surface_blocks[k]);
        amsph_buffer_free(s->backend, s->tension_share[k]);
    }
    amsph_buffer_free(s->backend, s->plain_liquid);
    amsph_buffer_free(s->backend, s->materials);
    if (s->config.thermal.enabled)
        amsph_thermal_free(s);
    if (s->config.grains.enabled)
        amsph_grains_free(s);
    amsph_buffer_free(s->backend, s->laser.bin_weight);
    amsph_buffer_free(s->backend, s->laser.bin_power);
    memset(s, 0, sizeof *s);
}

static unsigned field_set(const amsph_host_particles *h)
{
    unsigned set = 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f)
        set |= h->data[f] ? 1u << f : 0u;
    return set;
}

/* Bad input naming the first field that one set has and the other lacks. */
static int compare_field_sets(unsigned saved, unsigned needed)
{
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f) {
        const unsigned bit = 1u << f;
        if ((saved ^ needed) & bit)
            return amsph_bad_input("the saved state's field set differs from the case's: it %s field "
                                   "'%s', which this case %s in this build",
                                   saved & bit ? "has" : "lacks", amsph_fields[f].name,
                                   saved & bit ? "does not use" : "needs");
    }
    return 0;
}

/* Checks st's fields against the case's (building the scene once on the
 * host, which also fills the modules' settings in s). */
static int check_saved_fields(amsph_sim *s, const amsph_sim_state *st)
{
    amsph_host_particles scene;
    int status = build_host_particles(s, &scene);
    if (!status)
        status = compare_field_sets(field_set(&st->particles), field_set(&scene));
    amsph_host_free(&scene);
    return status;
}

/* Uploads h into buffers that hold `capacity` particles (at least h->n), as
 * the last good copy must hold every particle the sim may have. */
static int upload_with_capacity(amsph_backend *b, const amsph_host_particles *h, int capacity,
                                amsph_particles *p)
{
    amsph_host_particles padded = {.n = h->n};
    int status = 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT && !status; ++f)
        if (h->data[f])
            status = amsph_host_add_field(&padded, (amsph_field_id)f);
    for (int f = 0; f < AMSPH_FIELD_COUNT && !status; ++f)
        if (h->data[f])
            memcpy(padded.data[f], h->data[f], (size_t)h->n * amsph_field_bytes((amsph_field_id)f));
    if (!status)
        status = amsph_host_resize(&padded, capacity > h->n ? capacity : h->n);
    if (!status)
        status = amsph_particles_upload(b, &padded, p);
    p->n = h->n;
    amsph_host_free(&padded);
    return status;
}

static void copy_scalars(amsph_sim *s, amsph_scalar_value *v, int to_sim)
{
    for (int k = 0; k < AMSPH_SIM_SCALAR_COUNT; ++k) {
        char *member = (char *)s + amsph_sim_scalars[k].offset;
        void *value = amsph_sim_scalars[k].integer ? (void *)&v[k].integer : (void *)&v[k].real;
        const size_t bytes = amsph_sim_scalars[k].integer ? sizeof v[k].integer : sizeof v[k].real;
        memcpy(to_sim ? member : value, to_sim ? value : member, bytes);
    }
}

int amsph_sim_restore(const amsph_case *c, amsph_backend *b, const amsph_sim_state *st, amsph_sim *s)
{
    AMSPH_CHECK(prepare(c, b, s));
    AMSPH_CHECK(check_saved_fields(s, st));
    AMSPH_CHECK(amsph_particles_upload(b, &st->particles, &s->particles));
    AMSPH_CHECK(allocate_device_state(s));
    AMSPH_CHECK(upload_with_capacity(b, &st->last_good, s->particles.capacity, &s->last_good));
    if (c->thermal.enabled)
        AMSPH_CHECK(amsph_thermal_allocate(s));
    amsph_scalar_value scalar[AMSPH_SIM_SCALAR_COUNT];
    memcpy(scalar, st->scalar, sizeof scalar);
    copy_scalars(s, scalar, 1);
    if (c->fluid.enabled && s->fluid.one_pass) {
        /* The Verlet update reads the neighbour counts of the last pass
         * (density_at_step_end, kernels/integrate.cl), which a checkpoint
         * does not hold. The state was saved sorted, so the pass again gives
         * them and the saved rates bit for bit. */
        AMSPH_CHECK(amsph_grid_sort(&s->grid, &s->particles));
        AMSPH_CHECK(amsph_fluid_forces(s));
    }
    return c->grains.enabled ? amsph_grains_restore(s, st->grains, st->grain_values) : 0;
}

int amsph_sim_save(amsph_sim *s, amsph_sim_state *st)
{
    memset(st, 0, sizeof *st);
    copy_scalars(s, st->scalar, 0);
    AMSPH_CHECK(amsph_particles_download(&s->particles, &st->particles));
    AMSPH_CHECK(amsph_particles_download(&s->last_good, &st->last_good));
    return s->config.grains.enabled ? amsph_grains_save(s, &st->grains, &st->grain_values) : 0;
}

void amsph_sim_state_free(amsph_sim_state *st)
{
    free(st->grains);
    st->grains = NULL;
    amsph_host_free(&st->particles);
    amsph_host_free(&st->last_good);
}

int amsph_sim_phase(amsph_sim *s, amsph_phase next, amsph_phase *previous)
{
    return amsph_timers_switch(&s->timers, s->backend, next, previous);
}

int amsph_sim_max_norm(amsph_sim *s, amsph_field_id f, double *out)
{
    amsph_particles *p = &s->particles;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "vector_norm", p->n, amsph_arg_buffer(p->field[f]),
                             amsph_arg_int(p->n), amsph_arg_buffer(s->work)));
    return amsph_reduce_max(s->backend, s->work, p->n, out);
}

/* A first step that the run could not finish with: the case's values set
 * it (a sound speed of 1e19 m/s, a conductivity of 1e30 W/(m K)), so it
 * is bad input naming its limit, not a flow that blows up later. */
#define MAX_STEPS_TO_END 1e12

static int check_first_dt(const amsph_sim *s, double dt)
{
    const double steps = (s->config.end_time - s->time) / dt;
    if (!(dt > 0.0) || steps > MAX_STEPS_TO_END)
        return amsph_bad_input("the first time step is %.3g s (%s limit), %.3g steps to end_time = %g s (at "
                               "most %g); check the case's values that set the %s limit",
                               dt, s->dt_limit, steps, s->config.end_time, MAX_STEPS_TO_END, s->dt_limit);
    return 0;
}

/* Without the fluid module the limits are the kinematic CFL and the body
 * force (Fuchs et al. 2022 Eq. 42); the fluid module adds its own. */
static int stable_dt(amsph_sim *s, double *dt)
{
    *dt = INFINITY;
    s->dt_limit = "none";
    if (s->config.fluid.enabled) {
        AMSPH_CHECK(amsph_fluid_dt(s, dt, &s->dt_limit));
    } else {
        double umax = 0.0;
        AMSPH_CHECK(amsph_sim_max_norm(s, AMSPH_FIELD_VELOCITY, &umax));
        const double *g = s->config.gravity;
        const double gnorm = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        if (umax > 0.0)
            amsph_lower_dt(dt, &s->dt_limit, 0.25 * s->h / umax, "kinematic");
        if (gnorm > 0.0)
            amsph_lower_dt(dt, &s->dt_limit, 0.25 * sqrt(s->h / gnorm), "body force");
    }
    if (s->config.surface.enabled)
        AMSPH_CHECK(amsph_surface_dt(s, dt, &s->dt_limit));
    if (s->config.thermal.enabled)
        amsph_thermal_dt(s, dt, &s->dt_limit);
    if (s->config.grains.enabled)
        amsph_grains_dt(s, dt, &s->dt_limit);
    if (s->dt_min == 0.0 && !(*dt > 0.0 && isinf(*dt)))
        AMSPH_CHECK(check_first_dt(s, *dt));
    if (s->dt_min == 0.0 && isfinite(*dt))
        s->dt_min = s->config.fluid.dt_min > 0.0 ? s->config.fluid.dt_min : 1e-6 * *dt;
    if (*dt < s->dt_min || !(*dt > 0.0))
        return amsph_fail("step %lld, t = %.6g s: the time step %.3g s (%s limit) fell below "
                          "dt_min = %.3g s; the flow is blowing up or dt_min is too large",
                          s->step, s->time, *dt, s->dt_limit, s->dt_min);
    return 0;
}

int amsph_sim_stable_dt(amsph_sim *s, double *dt)
{
    amsph_phase outside;
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_INTEGRATION, &outside));
    AMSPH_CHECK(stable_dt(s, dt));
    return amsph_sim_phase(s, outside, NULL);
}

static int kick(amsph_sim *s, double half_dt)
{
    amsph_particles *p = &s->particles;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "kick", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_ACCELERATION]), amsph_arg_int(p->n),
                             amsph_arg_real(half_dt), amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY])));
    return s->config.grains.enabled ? amsph_grains_kick(s, half_dt) : 0;
}

/* Kick-drift-kick (Russell 2018 Eq. 3.55): the rates after the drift, the
 * density advanced with them (fluid.integration: leapfrog). */
static int leapfrog_advance(amsph_sim *s, double dt)
{
    amsph_particles *p = &s->particles;
    AMSPH_CHECK(kick(s, 0.5 * dt));
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "drift", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY]),
                             amsph_arg_int(p->n), amsph_arg_real(dt),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_POSITION])));
    if (s->config.grains.enabled)
        AMSPH_CHECK(amsph_grains_drift(s, dt));
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_SORT, NULL));
    if (s->config.thermal.enabled)
        AMSPH_CHECK(amsph_thermal_book_departures(s));
    AMSPH_CHECK(sort_moved(s));
    AMSPH_CHECK(update_temperature(s, dt));
    AMSPH_CHECK(compute_rates(s, dt));
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_INTEGRATION, NULL));
    AMSPH_CHECK(kick(s, 0.5 * dt));
    if (s->config.fluid.damping_rate > 0.0 && s->time < s->config.fluid.damping_end)
        AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "damp_velocity", p->n,
                                 amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]), amsph_arg_int(p->n),
                                 amsph_arg_real(exp(-s->config.fluid.damping_rate * dt)),
                                 amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY])));
    return amsph_fluid_shifts(&s->config.fluid) ? amsph_fluid_shift(s, dt) : 0;
}

/* The Verlet scheme (fluid.integration: verlet; kernels/integrate.cl
 * verlet_update) from the rates of the state it starts from, then the
 * rates of the new state in one neighbour pass. The difference spans this
 * step and the one before (s->dt). */
static int verlet_advance(amsph_sim *s, double dt)
{
    amsph_particles *p = &s->particles;
    const int euler = s->step % s->config.fluid.verlet_steps == 0;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "verlet_update", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_ACCELERATION]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_DENSITY_RATE]), amsph_arg_buffer(s->others),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_REFERENCE_DENSITY]), amsph_arg_int(p->n),
                             amsph_arg_real(dt), amsph_arg_real(dt + s->dt), amsph_arg_int(euler),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_POSITION]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY_PREVIOUS]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_DENSITY]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_DENSITY_PREVIOUS])));
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_SORT, NULL));
    AMSPH_CHECK(sort_moved(s));
    return compute_rates(s, dt);
}

int amsph_sim_step(amsph_sim *s, double dt)
{
    amsph_phase outside;
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_INTEGRATION, &outside));
    AMSPH_CHECK(s->fluid.one_pass ? verlet_advance(s, dt) : leapfrog_advance(s, dt));
    s->time += dt;
    s->dt = dt;
    ++s->step;
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_GUARDS, NULL));
    if (amsph_guards_check(s)) {
        s->guard_failed = 1;
        return 1;
    }
    if (s->step % LAST_GOOD_INTERVAL == 0)
        AMSPH_CHECK(keep_last_good(s));
    return amsph_sim_phase(s, outside, NULL);
}
