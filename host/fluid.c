#include "fluid.h"

#include <math.h>
#include <string.h>

#include "error.h"
#include "material.h"

/* rho0 of every particle at its initial temperature; without temperatures
 * the case's densities are constants (checked by the case parser). */
static void set_reference_density(const amsph_case *c, amsph_host_particles *h)
{
    const amsph_real *temperature = amsph_host_real(h, AMSPH_FIELD_TEMPERATURE);
    const int *material = h->data[AMSPH_FIELD_MATERIAL];
    amsph_real *rho0 = amsph_host_real(h, AMSPH_FIELD_REFERENCE_DENSITY);
    for (int i = 0; i < h->n; ++i)
        rho0[i] = (amsph_real)amsph_material_density(&c->materials[material[i]], temperature ? temperature[i] : 0.0);
}

/* Does rho0 change during the run: a material's rho0 depends on the
 * temperature, and the temperature changes (thermal module or history)? */
static int reference_density_varies(const amsph_case *c)
{
    int varies = 0;
    for (int m = 0; m < c->n_materials; ++m)
        varies |= amsph_material_density_varies(&c->materials[m]);
    return varies && (c->thermal.enabled || c->temperature_history.enabled);
}

/* The smallest mass of a fluid particle of the scene (masses never change),
 * for the barrier's step limit; INFINITY without fluid. */
static double lightest_fluid_mass(const amsph_host_particles *h)
{
    const amsph_real *mass = amsph_host_real(h, AMSPH_FIELD_MASS);
    const int *kind = h->data[AMSPH_FIELD_KIND];
    double lightest = INFINITY;
    for (int i = 0; i < h->n; ++i)
        if (kind[i] == AMSPH_KIND_FLUID)
            lightest = fmin(lightest, mass[i]);
    return lightest;
}

int amsph_fluid_setup(amsph_sim *s, amsph_host_particles *h)
{
    const amsph_fluid_settings *f = &s->config.fluid;
    fluid_params *p = &s->fluid;
    memset(p, 0, sizeof *p);
    p->h = (amsph_real)s->h;
    p->eta2 = (amsph_real)(0.01 * s->h * s->h);
    p->delta = (amsph_real)(f->density_diffusion == DIFFUSION_NONE ? 0.0 : f->delta);
    p->background_pressure = (amsph_real)f->background_pressure;
    p->artificial_alpha = (amsph_real)f->artificial_alpha;
    for (int d = 0; d < 3; ++d)
        p->gravity[d] = (amsph_real)s->config.gravity[d];
    p->density_diffusion = f->density_diffusion;
    p->continuity = f->continuity;
    p->pressure_gradient = f->pressure_gradient;
    p->viscosity = f->viscosity;
    p->wall_slip = f->wall_slip;
    p->clamp_negative_pressure = f->clamp_negative_pressure;
    p->tensile_correction = (amsph_real)f->tensile_correction;
    p->dx = (amsph_real)s->config.dx;
    p->shifting = (amsph_real)f->shifting;
    p->transport_pressure = (amsph_real)f->transport_pressure;
    p->gas_density = f->gas_density;
    p->barrier_stiffness = (amsph_real)f->barrier_stiffness;
    p->barrier_damping = (amsph_real)f->barrier_damping;
    p->barrier_distance = (amsph_real)f->barrier_distance;
    p->smoothing_length = f->smoothing_length;
    p->one_pass = f->integration == INTEGRATION_VERLET;
    p->h_max = (amsph_real)(amsph_fluid_max_smoothing_ratio(&s->config) * s->h);
    s->lightest_fluid_mass = lightest_fluid_mass(h);
    AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_REFERENCE_DENSITY));
    set_reference_density(&s->config, h);
    s->reference_density_varies = reference_density_varies(&s->config);
    p->uniform_material = s->config.n_materials == 1 && !s->reference_density_varies;
    AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_DENSITY_RATE));
    AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_WALL_VELOCITY));
    AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_GAS_WALL_PRESSURE));
    AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_SHEPARD));
    if (p->one_pass) { /* the state a step before, for the Verlet scheme */
        AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_VELOCITY_PREVIOUS));
        AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_DENSITY_PREVIOUS));
    }
    /* liquid until the thermal module says otherwise (it sets the field) */
    AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_LIQUID_FRACTION));
    for (int i = 0; i < h->n; ++i)
        amsph_host_real(h, AMSPH_FIELD_LIQUID_FRACTION)[i] = 1;
    if (f->smoothing_length == SMOOTHING_VOLUME) {
        /* h0: every particle starts with the lattice volume dx^d */
        AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_SMOOTHING_LENGTH));
        for (int i = 0; i < h->n; ++i)
            amsph_host_real(h, AMSPH_FIELD_SMOOTHING_LENGTH)[i] = p->h;
    }
    return 0;
}

double amsph_fluid_max_smoothing_ratio(const amsph_case *c)
{
    return c->fluid.enabled && c->fluid.smoothing_length == SMOOTHING_VOLUME ? c->fluid.max_smoothing_ratio : 1.0;
}

static amsph_arg field(amsph_sim *s, amsph_field_id f)
{
    return amsph_arg_buffer(s->particles.field[f]);
}

amsph_arg amsph_fluid_smoothing_length(amsph_sim *s)
{
    return field(s, s->fluid.smoothing_length == SMOOTHING_VOLUME ? AMSPH_FIELD_SMOOTHING_LENGTH : AMSPH_FIELD_DENSITY);
}

/* h of every particle from its volume after the density changed
 * (kernels/fluid.cl volume_smoothing_length). */
static int update_smoothing_length(amsph_sim *s)
{
    const int n = s->particles.n;
    return AMSPH_LAUNCH(s->backend, "volume_smoothing_length", n, field(s, AMSPH_FIELD_MASS),
                        field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_KIND), amsph_arg_int(n),
                        amsph_arg_bytes(&s->fluid, sizeof s->fluid), field(s, AMSPH_FIELD_SMOOTHING_LENGTH));
}

int amsph_fluid_check_smoothing_length(amsph_sim *s)
{
    const int n = s->particles.n;
    double largest = 0.0;
    if (s->fluid.smoothing_length != SMOOTHING_VOLUME)
        return 0;
    AMSPH_CHECK(amsph_reduce_max(s->backend, s->particles.field[AMSPH_FIELD_SMOOTHING_LENGTH], n, &largest));
    if (!(largest > s->fluid.h_max))
        return 0;
    amsph_host_particles h;
    int status = amsph_particles_download(&s->particles, &h);
    int i = 0;
    while (!status && i < n - 1 && amsph_host_real(&h, AMSPH_FIELD_SMOOTHING_LENGTH)[i] != (amsph_real)largest)
        ++i;
    if (!status) {
        const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION) + 3 * i;
        status = amsph_fail("guard 'smoothing length' failed: step %lld, t = %.6g s: particle id %u at (%.6g, "
                            "%.6g, %.6g) m has the smoothing length %.4g h0 (its volume %.4g dx^d), above "
                            "fluid.max_smoothing_ratio = %g, for which the neighbour grid is laid out; raise it",
                            s->step, s->time, ((unsigned *)h.data[AMSPH_FIELD_ID])[i], (double)x[0],
                            (double)x[1], (double)x[2], largest / s->h, pow(largest / s->h, s->config.dim),
                            s->config.fluid.max_smoothing_ratio);
    }
    amsph_host_free(&h);
    return status;
}

int amsph_fluid_reference_density(amsph_sim *s)
{
    const int n = s->particles.n;
    return AMSPH_LAUNCH(s->backend, "update_reference_density", n, field(s, AMSPH_FIELD_MATERIAL),
                        field(s, AMSPH_FIELD_TEMPERATURE), amsph_arg_int(n), amsph_arg_buffer(s->materials),
                        field(s, AMSPH_FIELD_REFERENCE_DENSITY));
}

/* Gamma_lattice of kernels/fluid.cl lattice_shepard_sum (into the first
 * element of s->work), into the fluid's parameters, for the gas's summed
 * density (fluid.gas_density: summation). */
int amsph_fluid_start(amsph_sim *s)
{
    if (s->fluid.gas_density != GAS_DENSITY_SUMMATION)
        return 0;
    amsph_real value = 0;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "lattice_shepard_sum", 1, amsph_arg_int(1),
                             amsph_arg_bytes(&s->fluid, sizeof s->fluid), amsph_arg_buffer(s->work)));
    AMSPH_CHECK(amsph_download(s->backend, s->work, 0, sizeof value, &value));
    s->fluid.lattice_shepard = value;
    return 0;
}

int amsph_fluid_density(amsph_sim *s, double dt)
{
    amsph_backend *b = s->backend;
    const int n = s->particles.n;
    AMSPH_CHECK(amsph_grid_count_fluid(&s->grid, b, &s->particles));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "continuity", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_VELOCITY), field(s, AMSPH_FIELD_DENSITY),
                             field(s, AMSPH_FIELD_REFERENCE_DENSITY),
                             amsph_fluid_smoothing_length(s),
                             field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_MATERIAL), amsph_arg_buffer(s->grid.cell),
                             amsph_arg_int(n), amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry),
                             amsph_arg_buffer(s->grid.cell_start), amsph_arg_buffer(s->grid.fluid_count),
                             amsph_arg_buffer(s->materials), amsph_arg_bytes(&s->fluid, sizeof s->fluid),
                             field(s, AMSPH_FIELD_DENSITY_RATE), field(s, AMSPH_FIELD_SHEPARD),
                             amsph_arg_buffer(s->closest), amsph_arg_buffer(s->others), amsph_arg_buffer(s->work)));
    /* s->work: the summed gas density's pull, from continuity to
     * advance_density (written and read only with fluid.gas_density: summation) */
    AMSPH_CHECK(AMSPH_LAUNCH(b, "advance_density", n, field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_DENSITY_RATE), amsph_arg_buffer(s->others),
                             field(s, AMSPH_FIELD_REFERENCE_DENSITY), amsph_arg_buffer(s->work),
                             amsph_arg_int(s->fluid.gas_density == GAS_DENSITY_SUMMATION), amsph_arg_int(n),
                             amsph_arg_real(dt), field(s, AMSPH_FIELD_DENSITY)));
    return s->fluid.smoothing_length == SMOOTHING_VOLUME ? update_smoothing_length(s) : 0;
}

int amsph_fluid_forces(amsph_sim *s)
{
    amsph_backend *b = s->backend;
    const int n = s->particles.n;
    const amsph_arg grid = amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry);
    const amsph_arg params = amsph_arg_bytes(&s->fluid, sizeof s->fluid);
    AMSPH_CHECK(AMSPH_LAUNCH(b, "equation_of_state", n, field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_MATERIAL), field(s, AMSPH_FIELD_DENSITY),
                             field(s, AMSPH_FIELD_REFERENCE_DENSITY), amsph_arg_int(n), amsph_arg_buffer(s->materials), params,
                             field(s, AMSPH_FIELD_PRESSURE)));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "wall_state", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_VELOCITY), field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_MATERIAL), amsph_arg_buffer(s->grid.cell),
                             amsph_fluid_smoothing_length(s), field(s, AMSPH_FIELD_REFERENCE_DENSITY),
                             field(s, AMSPH_FIELD_SHEPARD), amsph_arg_int(n), grid,
                             amsph_arg_buffer(s->grid.cell_start), amsph_arg_buffer(s->materials), params,
                             field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_PRESSURE),
                             field(s, AMSPH_FIELD_GAS_WALL_PRESSURE), field(s, AMSPH_FIELD_WALL_VELOCITY)));
    return AMSPH_LAUNCH(b, "fluid_forces", n, field(s, AMSPH_FIELD_POSITION),
                        field(s, AMSPH_FIELD_VELOCITY), field(s, AMSPH_FIELD_WALL_VELOCITY),
                        field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_REFERENCE_DENSITY),
                        field(s, AMSPH_FIELD_PRESSURE),
                        field(s, AMSPH_FIELD_GAS_WALL_PRESSURE), field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_SHEPARD),
                        field(s, AMSPH_FIELD_LIQUID_FRACTION), amsph_fluid_smoothing_length(s),
                        field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MATERIAL),
                        amsph_arg_buffer(s->grid.cell), amsph_arg_int(n), grid,
                        amsph_arg_buffer(s->grid.cell_start), amsph_arg_buffer(s->materials), params,
                        field(s, AMSPH_FIELD_ACCELERATION), field(s, AMSPH_FIELD_DENSITY_RATE),
                        amsph_arg_buffer(s->closest), amsph_arg_buffer(s->others));
}

unsigned amsph_fluid_recomputed_fields(const amsph_sim *s)
{
    /* the Shepard sum: no kernel of the scheme reads it (kernels/fluid.cl fluid_forces) */
    static const amsph_field_id recomputed[] = {AMSPH_FIELD_ACCELERATION, AMSPH_FIELD_DENSITY_RATE,
                                                AMSPH_FIELD_PRESSURE, AMSPH_FIELD_GAS_WALL_PRESSURE,
                                                AMSPH_FIELD_WALL_VELOCITY, AMSPH_FIELD_SHEPARD};
    unsigned fields = 0;
    for (size_t k = 0; s->fluid.one_pass && k < sizeof recomputed / sizeof recomputed[0]; ++k)
        fields |= 1u << recomputed[k];
    return fields;
}

int amsph_fluid_shifts(const amsph_fluid_settings *f)
{
    return f->shifting > 0.0 || f->transport_pressure > 0.0;
}

int amsph_fluid_shift(amsph_sim *s, double dt)
{
    amsph_backend *b = s->backend;
    const int n = s->particles.n;
    AMSPH_CHECK(AMSPH_LAUNCH(b, "shifting_displacement", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_VELOCITY), field(s, AMSPH_FIELD_DENSITY),
                             field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_SHEPARD),
                             amsph_fluid_smoothing_length(s), field(s, AMSPH_FIELD_KIND),
                             amsph_arg_buffer(s->grid.cell), amsph_arg_int(n),
                             amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry),
                             amsph_arg_buffer(s->grid.cell_start), amsph_arg_bytes(&s->fluid, sizeof s->fluid),
                             amsph_arg_real(dt), amsph_arg_buffer(s->shift)));
    /* position += 1 * shift */
    return AMSPH_LAUNCH(b, "drift", n, field(s, AMSPH_FIELD_KIND), amsph_arg_buffer(s->shift), amsph_arg_int(n), amsph_arg_real(1.0),
                        field(s, AMSPH_FIELD_POSITION));
}

/* Largest speed of sound and kinematic viscosity (with the smallest rho0)
 * over the materials. */
static void material_extremes(const amsph_case *c, double *c0, double *nu)
{
    *c0 = 0.0;
    *nu = 0.0;
    for (int m = 0; m < c->n_materials; ++m) {
        double rho_min, rho_max;
        amsph_material_density_bounds(&c->materials[m], &rho_min, &rho_max);
        *c0 = fmax(*c0, c->materials[m].sound_speed);
        *nu = fmax(*nu, c->materials[m].viscosity / rho_min);
    }
}

int amsph_fluid_dt(amsph_sim *s, double *dt, const char **limit)
{
    double umax = 0.0, amax = 0.0, c0, nu;
    AMSPH_CHECK(amsph_sim_max_norm(s, AMSPH_FIELD_VELOCITY, &umax));
    AMSPH_CHECK(amsph_sim_max_norm(s, AMSPH_FIELD_ACCELERATION, &amax));
    material_extremes(&s->config, &c0, &nu);
    /* the smallest smoothing length (Russell Eq. 3.54 shrinks a compressed particle's) for every limit */
    double h = s->h;
    if (s->fluid.smoothing_length == SMOOTHING_VOLUME)
        AMSPH_CHECK(amsph_reduce_min(s->backend, s->particles.field[AMSPH_FIELD_SMOOTHING_LENGTH], s->particles.n, &h));
    amsph_lower_dt(dt, limit, s->config.fluid.cfl * h / (c0 + umax), "acoustic");
    if (nu > 0.0)
        amsph_lower_dt(dt, limit, 0.125 * h * h / nu, "viscous");
    if (amax > 0.0)
        amsph_lower_dt(dt, limit, 0.25 * sqrt(h / amax), "force");
    /* the contact condition of Fuchs et al. 2022 Eq. 42 for the barrier forces */
    if (s->config.fluid.barrier_stiffness > 0.0)
        amsph_lower_dt(dt, limit, 0.22 * sqrt(s->lightest_fluid_mass / s->config.fluid.barrier_stiffness), "barrier");
    return 0;
}
