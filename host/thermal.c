#include "thermal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "evaporation.h"
#include "grains.h"
#include "laser.h"
#include "material.h"
#include "thermal_table.h"

#define MUSHY_SUBDIVISIONS 8 /* nodes inside the mushy interval */

static int melts(const amsph_material *m)
{
    return m->melting_temperature > 0.0;
}

/* Liquid fraction at T (Russell 2018 Eq. 3.47, s = 1 liquid). */
static double liquid_fraction(const amsph_material *m, double t)
{
    if (!melts(m))
        return 0.0;
    const double s = (t - (m->melting_temperature - 0.5 * m->melting_range)) / m->melting_range;
    return fmin(fmax(s, 0.0), 1.0);
}

/* Sensible heat capacity and conductivity, solid and liquid blended by s
 * (theta = theta_s + (theta_l - theta_s) s; PHYSICS.md erratum 2). */
static double sensible_heat(const amsph_material *m, double t)
{
    const double cs = amsph_property_value(&m->specific_heat, t);
    const double cl = amsph_property_value(&m->liquid_specific_heat, t);
    return cs + (cl - cs) * liquid_fraction(m, t);
}

static double blended_conductivity(const amsph_material *m, double t)
{
    const double ks = amsph_property_value(&m->conductivity, t);
    const double kl = amsph_property_value(&m->liquid_conductivity, t);
    return ks + (kl - ks) * liquid_fraction(m, t);
}

static int compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void add_breakpoints(const amsph_property *p, double *t, int *count)
{
    for (int i = 0; p->n > 1 && i < p->n; ++i)
        t[(*count)++] = p->T[i];
}

/* Node temperatures: 0 K, every table point, the mushy interval with
 * MUSHY_SUBDIVISIONS nodes inside, and one node above them all, sorted and
 * without repeats. Between neighbouring nodes c_s, c_l and s are linear. */
static int node_temperatures(const amsph_material *m, double *t)
{
    double all[4 * AMSPH_MAX_TABLE + MUSHY_SUBDIVISIONS + 4];
    int count = 0;
    all[count++] = 0.0;
    add_breakpoints(&m->specific_heat, all, &count);
    add_breakpoints(&m->liquid_specific_heat, all, &count);
    add_breakpoints(&m->conductivity, all, &count);
    add_breakpoints(&m->liquid_conductivity, all, &count);
    if (melts(m)) {
        const double solidus = m->melting_temperature - 0.5 * m->melting_range;
        for (int i = 0; i <= MUSHY_SUBDIVISIONS + 1; ++i)
            all[count++] = solidus + m->melting_range * i / (MUSHY_SUBDIVISIONS + 1);
    }
    qsort(all, (size_t)count, sizeof all[0], compare_doubles);
    all[count] = all[count - 1] + 1.0;
    ++count;
    int unique = 0;
    for (int i = 0; i < count; ++i)
        if (unique == 0 || all[i] > t[unique - 1])
            t[unique++] = all[i];
    return unique;
}

/* 0 K, four tables, the mushy interval and its ends, the top node. */
_Static_assert(1 + 4 * AMSPH_MAX_TABLE + MUSHY_SUBDIVISIONS + 2 + 1 <= THERMAL_NODES,
               "the thermal table holds every node");

int amsph_thermal_nodes(const amsph_material *m, double *temperature, double *enthalpy,
                        double *conductivity)
{
    const int count = node_temperatures(m, temperature);
    /* h(T) = int_0^T c_sensible dT' + L s(T). On a segment c_sensible is at
     * most quadratic in T (linear c_s, c_l times linear s), so Simpson's
     * rule integrates it exactly. */
    double sensible = 0.0;
    for (int i = 0; i < count; ++i) {
        const double t = temperature[i];
        if (i > 0) {
            const double a = temperature[i - 1];
            sensible += (t - a) / 6.0 *
                        (sensible_heat(m, a) + 4.0 * sensible_heat(m, 0.5 * (a + t)) + sensible_heat(m, t));
        }
        enthalpy[i] = sensible + m->latent_heat * liquid_fraction(m, t);
        conductivity[i] = blended_conductivity(m, t);
    }
    return count;
}

double amsph_thermal_enthalpy(const amsph_material *m, double t)
{
    double nodes[THERMAL_NODES], h[THERMAL_NODES], k[THERMAL_NODES];
    const int count = amsph_thermal_nodes(m, nodes, h, k);
    int i = 0; /* the segment that holds t, the last one beyond it (as table_interpolate) */
    while (i < count - 2 && t >= nodes[i + 1])
        ++i;
    return h[i] + (t - nodes[i]) * (h[i + 1] - h[i]) / (nodes[i + 1] - nodes[i]);
}

int amsph_surface_delta(amsph_sim *s, double cutoff, amsph_real *delta)
{
    amsph_buffer *out = NULL;
    amsph_real integral = 0;
    AMSPH_CHECK(amsph_buffer_alloc(s->backend, sizeof integral, &out));
    int status = AMSPH_LAUNCH(s->backend, "flat_face_delta", 1, amsph_arg_real(s->h), amsph_arg_real(s->config.dx),
                              amsph_arg_real(cutoff), amsph_arg_buffer(out));
    if (!status)
        status = amsph_download(s->backend, out, 0, sizeof integral, &integral);
    amsph_buffer_free(s->backend, out);
    if (!status && !(integral > 0))
        status = amsph_fail("no row of a flat lattice face reaches the surface cut-off %g", cutoff);
    *delta = status ? 0 : 1 / integral;
    return status;
}

int amsph_thermal_setup(amsph_sim *s, amsph_host_particles *h)
{
    static const amsph_field_id fields[] = {AMSPH_FIELD_ENTHALPY, AMSPH_FIELD_ENTHALPY_RATE,
                                            AMSPH_FIELD_CONDUCTIVITY, AMSPH_FIELD_LIQUID_FRACTION,
                                            AMSPH_FIELD_PEAK_TEMPERATURE, AMSPH_FIELD_LASER_POWER};
    const amsph_thermal_settings *t = &s->config.thermal;
    thermal_params *p = &s->thermal;
    memset(p, 0, sizeof *p);
    p->h = (amsph_real)s->h;
    p->eta2 = (amsph_real)(0.01 * s->h * s->h);
    p->ambient_temperature = (amsph_real)t->ambient_temperature;
    p->surface_cutoff = (amsph_real)0.1; /* PHYSICS.md erratum 5: |n| h against ~0.1 */
    p->radiation = t->radiation;
    p->evaporative_cooling = t->evaporative_cooling;
    p->recoil_pressure = t->recoil_pressure;
    p->evaporation_temperature = (amsph_real)t->evaporation_temperature;
    if (p->radiation || p->evaporative_cooling || p->recoil_pressure)
        AMSPH_CHECK(amsph_surface_delta(s, p->surface_cutoff, &p->surface_delta));
    p->viscous_heating = t->viscous_heating;
    p->phase_change_kinds = s->config.fluid.enabled;
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; ++k)
        AMSPH_CHECK(amsph_host_add_field(h, fields[k]));
    return 0;
}

static int upload_tables(amsph_sim *s)
{
    const amsph_case *c = &s->config;
    const size_t bytes = (size_t)c->n_materials * THERMAL_STRIDE * sizeof(amsph_real);
    amsph_real *table = calloc(1, bytes);
    if (!table)
        return amsph_fail("out of host memory for the thermal tables");
    for (int m = 0; m < c->n_materials; ++m) {
        double t[THERMAL_NODES], h[THERMAL_NODES], k[THERMAL_NODES];
        const amsph_material *mat = &c->materials[m];
        const int count = amsph_thermal_nodes(mat, t, h, k);
        amsph_real *row = table + (size_t)m * THERMAL_STRIDE;
        for (int i = 0; i < count; ++i) {
            row[THERMAL_TEMPERATURE + i] = (amsph_real)t[i];
            row[THERMAL_ENTHALPY + i] = (amsph_real)h[i];
            row[THERMAL_CONDUCTIVITY + i] = (amsph_real)k[i];
        }
        row[THERMAL_COUNT] = (amsph_real)count;
        row[THERMAL_SOLIDUS] = (amsph_real)(melts(mat) ? mat->melting_temperature - 0.5 * mat->melting_range : 0.0);
        row[THERMAL_LIQUIDUS] = (amsph_real)(melts(mat) ? mat->melting_temperature + 0.5 * mat->melting_range : 0.0);
        row[THERMAL_EMISSIVITY] = (amsph_real)mat->emissivity;
    }
    int status = amsph_buffer_alloc(s->backend, bytes, &s->thermal_table);
    if (!status)
        status = amsph_upload(s->backend, s->thermal_table, 0, bytes, table);
    free(table);
    return status;
}

static amsph_arg field(amsph_sim *s, amsph_field_id f)
{
    return amsph_arg_buffer(s->particles.field[f]);
}

static int update_state(amsph_sim *s)
{
    return AMSPH_LAUNCH(s->backend, "thermal_state", s->particles.n, field(s, AMSPH_FIELD_KIND),
                        field(s, AMSPH_FIELD_MATERIAL), field(s, AMSPH_FIELD_ENTHALPY),
                        amsph_arg_int(s->particles.n), amsph_arg_buffer(s->thermal_table),
                        field(s, AMSPH_FIELD_TEMPERATURE), field(s, AMSPH_FIELD_LIQUID_FRACTION),
                        field(s, AMSPH_FIELD_CONDUCTIVITY));
}

static int finish_step(amsph_sim *s)
{
    if (s->config.grains.enabled && s->thermal.phase_change_kinds)
        AMSPH_CHECK(amsph_grains_change_phase(s));
    return AMSPH_LAUNCH(s->backend, "finish_thermal_step", s->particles.n,
                        field(s, AMSPH_FIELD_MATERIAL), field(s, AMSPH_FIELD_TEMPERATURE),
                        field(s, AMSPH_FIELD_LIQUID_FRACTION), amsph_arg_int(s->particles.n),
                        amsph_arg_buffer(s->thermal_table),
                        amsph_arg_bytes(&s->thermal, sizeof s->thermal), field(s, AMSPH_FIELD_KIND),
                        field(s, AMSPH_FIELD_VELOCITY), field(s, AMSPH_FIELD_PEAK_TEMPERATURE));
}

static int alloc_work(amsph_sim *s, amsph_buffer **buffer)
{
    return amsph_buffer_alloc(s->backend, (size_t)s->particles.capacity * sizeof(amsph_real), buffer);
}

/* The diffusion limit diffusion_number rho c h^2 / k over the materials,
 * with the smallest reference density, apparent heat capacity and the
 * largest conductivity of each material's tables (fixed for the run). */
static double diffusion_limit(const amsph_sim *s)
{
    const amsph_case *c = &s->config;
    double limit = INFINITY;
    for (int m = 0; m < c->n_materials; ++m) {
        double t[THERMAL_NODES], h[THERMAL_NODES], k[THERMAL_NODES];
        const int count = amsph_thermal_nodes(&c->materials[m], t, h, k);
        double c_min = INFINITY, k_max = 0.0;
        for (int i = 0; i < count; ++i) {
            k_max = fmax(k_max, k[i]);
            if (i > 0)
                c_min = fmin(c_min, (h[i] - h[i - 1]) / (t[i] - t[i - 1]));
        }
        double rho_min, rho_max;
        amsph_material_density_bounds(&c->materials[m], &rho_min, &rho_max);
        if (k_max > 0.0)
            limit = fmin(limit, c->thermal.diffusion_number * rho_min * c_min * s->h * s->h / k_max);
    }
    return limit;
}

int amsph_thermal_allocate(amsph_sim *s)
{
    amsph_thermal_work *w = &s->thermal_work;
    AMSPH_CHECK(upload_tables(s));
    s->thermal_dt = diffusion_limit(s);
    AMSPH_CHECK(alloc_work(s, &w->enthalpy_start));
    AMSPH_CHECK(alloc_work(s, &w->rate_start));
    AMSPH_CHECK(alloc_work(s, &w->temperature_previous));
    AMSPH_CHECK(alloc_work(s, &w->wall_temperature));
    for (int k = 0; k < AMSPH_LEDGER_TERMS; ++k)
        AMSPH_CHECK(alloc_work(s, &w->power[k]));
    if (s->thermal.evaporation_temperature > 0)
        AMSPH_CHECK(alloc_work(s, &w->evaporated));
    return 0;
}

int amsph_thermal_start(amsph_sim *s)
{
    AMSPH_CHECK(amsph_thermal_allocate(s));
    const int n = s->particles.n;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "enthalpy_from_temperature", n, field(s, AMSPH_FIELD_MATERIAL),
                             field(s, AMSPH_FIELD_TEMPERATURE), amsph_arg_int(n),
                             amsph_arg_buffer(s->thermal_table), field(s, AMSPH_FIELD_ENTHALPY)));
    AMSPH_CHECK(update_state(s));
    AMSPH_CHECK(finish_step(s));
    if (s->config.laser.enabled)
        AMSPH_CHECK(amsph_laser_absorb(s, s->time));
    memset(&s->ledger, 0, sizeof s->ledger);
    return amsph_thermal_energy(s, &s->ledger.initial);
}

void amsph_thermal_free(amsph_sim *s)
{
    amsph_thermal_work *w = &s->thermal_work;
    amsph_buffer_free(s->backend, s->thermal_table);
    amsph_buffer_free(s->backend, w->enthalpy_start);
    amsph_buffer_free(s->backend, w->rate_start);
    amsph_buffer_free(s->backend, w->temperature_previous);
    amsph_buffer_free(s->backend, w->wall_temperature);
    for (int k = 0; k < AMSPH_LEDGER_TERMS; ++k)
        amsph_buffer_free(s->backend, w->power[k]);
    amsph_buffer_free(s->backend, w->evaporated);
}

/* Enthalpy rates into `rate` and the ledger powers (W) into power[]. */
static int heat_rate(amsph_sim *s, amsph_buffer *rate, double power[AMSPH_LEDGER_TERMS])
{
    amsph_thermal_work *w = &s->thermal_work;
    amsph_particles *p = &s->particles;
    const amsph_field_id ghost = p->field[AMSPH_FIELD_WALL_VELOCITY] ? AMSPH_FIELD_WALL_VELOCITY : AMSPH_FIELD_VELOCITY;
    const amsph_arg grid = amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry);
    const amsph_arg params = amsph_arg_bytes(&s->thermal, sizeof s->thermal);
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "wall_temperature", p->n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_TEMPERATURE), field(s, AMSPH_FIELD_ENTHALPY),
                             field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MATERIAL),
                             amsph_arg_buffer(s->grid.cell), amsph_arg_int(p->n), grid,
                             amsph_arg_buffer(s->grid.cell_start), amsph_arg_buffer(s->thermal_table),
                             params, amsph_arg_buffer(w->wall_temperature)));
    AMSPH_CHECK(AMSPH_LAUNCH(
        s->backend, "heat_rate", p->n, field(s, AMSPH_FIELD_POSITION), field(s, AMSPH_FIELD_VELOCITY),
        field(s, ghost), field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_MASS),
        field(s, AMSPH_FIELD_TEMPERATURE), amsph_arg_buffer(w->wall_temperature),
        field(s, AMSPH_FIELD_CONDUCTIVITY), field(s, AMSPH_FIELD_LIQUID_FRACTION),
        field(s, AMSPH_FIELD_LASER_POWER), field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MATERIAL),
        amsph_arg_buffer(s->grid.cell), amsph_arg_int(p->n), grid, amsph_arg_buffer(s->grid.cell_start),
        amsph_arg_buffer(s->materials), amsph_arg_buffer(s->thermal_table), params, amsph_arg_buffer(rate),
        amsph_arg_buffer(w->power[AMSPH_LEDGER_LASER]), amsph_arg_buffer(w->power[AMSPH_LEDGER_RADIATION]),
        amsph_arg_buffer(w->power[AMSPH_LEDGER_EVAPORATION]), amsph_arg_buffer(w->power[AMSPH_LEDGER_WALLS]),
        amsph_arg_buffer(w->power[AMSPH_LEDGER_VISCOUS])));
    const int present[AMSPH_LEDGER_TERMS] = {
        [AMSPH_LEDGER_LASER] = s->config.laser.enabled, [AMSPH_LEDGER_RADIATION] = s->thermal.radiation,
        [AMSPH_LEDGER_EVAPORATION] = s->thermal.evaporative_cooling, [AMSPH_LEDGER_WALLS] = 1,
        [AMSPH_LEDGER_VISCOUS] = s->thermal.viscous_heating};
    for (int k = 0; k < AMSPH_LEDGER_TERMS; ++k) {
        power[k] = 0.0;
        if (present[k])
            AMSPH_CHECK(amsph_reduce_sum(s->backend, w->power[k], p->n, &power[k]));
    }
    return 0;
}

static int advance(amsph_sim *s, amsph_buffer *start, amsph_buffer *rate_start, amsph_buffer *rate,
                   double dt_start, double dt_now)
{
    const int n = s->particles.n;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "advance_enthalpy", n, field(s, AMSPH_FIELD_KIND),
                             amsph_arg_buffer(start), amsph_arg_buffer(rate_start), amsph_arg_buffer(rate),
                             amsph_arg_int(n), amsph_arg_real(dt_start), amsph_arg_real(dt_now),
                             field(s, AMSPH_FIELD_ENTHALPY)));
    return update_state(s);
}

static int copy_reals(amsph_sim *s, amsph_buffer *src, amsph_buffer *dst)
{
    const int words = s->particles.n * (int)(sizeof(amsph_real) / 4);
    return AMSPH_LAUNCH(s->backend, "copy_words", words, amsph_arg_buffer(src), amsph_arg_buffer(dst),
                        amsph_arg_int(words));
}

static void book(amsph_sim *s, const double *power_a, const double *power_b, double dt)
{
    s->ledger.laser += 0.5 * dt * (power_a[AMSPH_LEDGER_LASER] + power_b[AMSPH_LEDGER_LASER]);
    s->ledger.radiation += 0.5 * dt * (power_a[AMSPH_LEDGER_RADIATION] + power_b[AMSPH_LEDGER_RADIATION]);
    s->ledger.evaporation += 0.5 * dt * (power_a[AMSPH_LEDGER_EVAPORATION] + power_b[AMSPH_LEDGER_EVAPORATION]);
    s->ledger.walls += 0.5 * dt * (power_a[AMSPH_LEDGER_WALLS] + power_b[AMSPH_LEDGER_WALLS]);
    s->ledger.viscous += 0.5 * dt * (power_a[AMSPH_LEDGER_VISCOUS] + power_b[AMSPH_LEDGER_VISCOUS]);
}

/* Explicit Euler: h^{n+1} = h^n + dt G(T^n). */
static int advance_explicit(amsph_sim *s, double dt)
{
    double power[AMSPH_LEDGER_TERMS];
    amsph_buffer *rate = s->particles.field[AMSPH_FIELD_ENTHALPY_RATE];
    AMSPH_CHECK(heat_rate(s, rate, power));
    AMSPH_CHECK(advance(s, s->particles.field[AMSPH_FIELD_ENTHALPY], rate, rate, 0.0, dt));
    book(s, power, power, dt);
    s->thermal_iterations = 1;
    return 0;
}

/* Implicit midpoint by fixed-point iteration (Russell 2018 Alg. 3.1):
 *   h^{i+1} = h^n + dt/2 (G(T^n) + G(T^i)),  from h^0 = h^n + dt G(T^n),
 * until max |T^{i+1} - T^i| < tolerance max T^n (Alg. 3.1 divides by T^n
 * per particle, which fails for a material at 0 K). */
static int advance_midpoint(amsph_sim *s, double dt)
{
    amsph_thermal_work *w = &s->thermal_work;
    const amsph_thermal_settings *t = &s->config.thermal;
    const int n = s->particles.n;
    amsph_buffer *temperature = s->particles.field[AMSPH_FIELD_TEMPERATURE];
    amsph_buffer *rate = s->particles.field[AMSPH_FIELD_ENTHALPY_RATE];
    double power_start[AMSPH_LEDGER_TERMS], power[AMSPH_LEDGER_TERMS], scale;
    AMSPH_CHECK(amsph_reduce_max(s->backend, temperature, n, &scale));
    AMSPH_CHECK(copy_reals(s, s->particles.field[AMSPH_FIELD_ENTHALPY], w->enthalpy_start));
    AMSPH_CHECK(heat_rate(s, w->rate_start, power_start));
    AMSPH_CHECK(advance(s, w->enthalpy_start, w->rate_start, w->rate_start, 0.0, dt));
    double change = INFINITY;
    int i = 0;
    while (!(change < t->tolerance * scale) && i < t->max_iterations) {
        AMSPH_CHECK(copy_reals(s, temperature, w->temperature_previous));
        AMSPH_CHECK(heat_rate(s, rate, power));
        AMSPH_CHECK(advance(s, w->enthalpy_start, w->rate_start, rate, 0.5 * dt, 0.5 * dt));
        AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "temperature_change", n, amsph_arg_buffer(temperature),
                                 amsph_arg_buffer(w->temperature_previous), amsph_arg_int(n),
                                 amsph_arg_buffer(s->work)));
        AMSPH_CHECK(amsph_reduce_max(s->backend, s->work, n, &change));
        ++i;
    }
    if (!(change < t->tolerance * scale))
        return amsph_fail("step %lld, t = %.6g s: the midpoint temperature iteration did not converge in "
                          "%d iterations (change %.3g K > tolerance x max T = %.3g K); lower "
                          "thermal.diffusion_number or raise thermal.max_iterations",
                          s->step, s->time, i, change, t->tolerance * scale);
    book(s, power_start, power, dt);
    s->thermal_iterations = i;
    return 0;
}

int amsph_thermal_advance(amsph_sim *s, double dt)
{
    if (s->config.laser.enabled)
        AMSPH_CHECK(amsph_laser_absorb_step(s, s->time, s->time + dt));
    if (s->config.thermal.integration == AMSPH_THERMAL_MIDPOINT)
        AMSPH_CHECK(advance_midpoint(s, dt));
    else
        AMSPH_CHECK(advance_explicit(s, dt));
    AMSPH_CHECK(finish_step(s));
    return s->thermal.evaporation_temperature > 0 ? amsph_evaporation_remove_hot(s) : 0;
}

void amsph_thermal_dt(const amsph_sim *s, double *dt, const char **limit)
{
    if (s->thermal_dt < *dt) {
        *dt = s->thermal_dt;
        *limit = "diffusion";
    }
}

int amsph_thermal_book_departures(amsph_sim *s)
{
    const int n = s->particles.n;
    double leaving = 0.0;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "departing_enthalpy", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MASS),
                             field(s, AMSPH_FIELD_ENTHALPY), amsph_arg_int(n),
                             amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry),
                             amsph_arg_buffer(s->work)));
    AMSPH_CHECK(amsph_reduce_sum(s->backend, s->work, n, &leaving));
    s->ledger.departed += leaving;
    return 0;
}

int amsph_thermal_energy(amsph_sim *s, double *energy)
{
    const int n = s->particles.n;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "material_enthalpy", n, field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_ENTHALPY), amsph_arg_int(n),
                             amsph_arg_buffer(s->work)));
    return amsph_reduce_sum(s->backend, s->work, n, energy);
}

double amsph_energy_ledger_error(const amsph_energy_ledger *l, double energy)
{
    const double change = energy - l->initial;
    const double booked =
        l->laser - l->radiation - l->evaporation - l->evaporated - l->departed + l->walls + l->viscous;
    const double gross = fabs(l->laser) + fabs(l->radiation) + fabs(l->evaporation) + fabs(l->evaporated) +
                         fabs(l->departed) + fabs(l->walls) + fabs(l->viscous);
    const double scale = fmax(gross, fabs(change));
    return scale > 0.0 ? fabs(change - booked) / scale : 0.0;
}

int amsph_thermal_ledger_error(amsph_sim *s, double *error)
{
    double energy;
    AMSPH_CHECK(amsph_thermal_energy(s, &energy));
    *error = amsph_energy_ledger_error(&s->ledger, energy);
    return 0;
}

int amsph_thermal_prescribe(amsph_sim *s, double t)
{
    const double value = amsph_temperature_history_at(&s->config.temperature_history, t);
    return AMSPH_LAUNCH(s->backend, "uniform_temperature", s->particles.n, amsph_arg_int(s->particles.n),
                        amsph_arg_real(value), field(s, AMSPH_FIELD_TEMPERATURE));
}
