#include "guards.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "error.h"
#include "fluid.h"

/* Codes of kernels/guards.cl */
enum { GUARD_OK, GUARD_DENSITY, GUARD_CLOSE, GUARD_NOT_FINITE };

/* One particle's value of a field, downloaded. */
static int fetch(amsph_sim *s, amsph_field_id f, int i, void *out)
{
    const size_t bytes = amsph_field_bytes(f);
    return amsph_download(s->backend, s->particles.field[f], (size_t)i * bytes, bytes, out);
}

static int first_with_code(amsph_sim *s, int code, int *index)
{
    const int n = s->particles.n;
    amsph_real *codes = malloc((size_t)n * sizeof *codes);
    if (!codes)
        return amsph_fail("out of host memory reading the guard codes");
    int status = amsph_download(s->backend, s->work, 0, (size_t)n * sizeof *codes, codes);
    *index = 0;
    while (!status && *index < n && (int)codes[*index] != code)
        ++*index;
    free(codes);
    return status;
}

/* One field of every particle, downloaded into a new array. */
static int fetch_all(amsph_sim *s, amsph_field_id f, void **out)
{
    const size_t bytes = (size_t)s->particles.n * amsph_field_bytes(f);
    *out = malloc(bytes ? bytes : 1);
    if (!*out)
        return amsph_fail("out of host memory reading a field for the guard's report");
    return amsph_download(s->backend, s->particles.field[f], 0, bytes, *out);
}

/* The particle nearest to particle i, which the spacing guard stopped: a scan
 * of every position, with the nearest periodic image on periodic axes. */
typedef struct {
    int index;
    double closing_speed; /* -(u_i - u_j) . e_ij: positive while the pair closes */
} nearest_pair;

static int nearest_neighbour(amsph_sim *s, int i, nearest_pair *pair)
{
    amsph_real *x = NULL, *u = NULL;
    int status = fetch_all(s, AMSPH_FIELD_POSITION, (void **)&x);
    if (!status)
        status = fetch_all(s, AMSPH_FIELD_VELOCITY, (void **)&u);
    const grid_geometry *g = &s->grid.geometry;
    double best = INFINITY, r_pair[3] = {0.0, 0.0, 0.0};
    pair->index = -1;
    for (int j = 0; !status && j < s->particles.n; ++j) {
        double r[3], r2 = 0.0;
        for (int d = 0; d < 3; ++d) {
            r[d] = (double)x[3 * i + d] - x[3 * j + d];
            if (g->periodic[d])
                r[d] = remainder(r[d], g->length[d]);
            r2 += r[d] * r[d];
        }
        if (j != i && r2 < best) {
            best = r2;
            pair->index = j;
            for (int d = 0; d < 3; ++d)
                r_pair[d] = r[d];
        }
    }
    pair->closing_speed = 0.0;
    for (int d = 0; !status && pair->index >= 0 && d < 3; ++d)
        pair->closing_speed -= ((double)u[3 * i + d] - u[3 * pair->index + d]) * r_pair[d] / sqrt(best);
    free(x);
    free(u);
    return status ? status : pair->index < 0 ? amsph_fail("the spacing guard found no second particle") : 0;
}

/* The spacing guard's message: the distance it tested, the pair, how fast it
 * closes, and the setting that keeps such pairs apart (Fuchs et al. 2022
 * Eq. 34). */
static int report_close_pair(amsph_sim *s, int i, const char *where, double limit)
{
    amsph_real closest;
    AMSPH_CHECK(amsph_download(s->backend, s->closest, (size_t)i * sizeof closest, sizeof closest, &closest));
    nearest_pair pair;
    AMSPH_CHECK(nearest_neighbour(s, i, &pair));
    unsigned id;
    int kind;
    AMSPH_CHECK(fetch(s, AMSPH_FIELD_ID, pair.index, &id));
    AMSPH_CHECK(fetch(s, AMSPH_FIELD_KIND, pair.index, &kind));
    const amsph_fluid_settings *f = &s->config.fluid;
    const double dx = s->config.dx;
    const char *remedy = f->barrier_stiffness > 0.0
                             ? "a stiffer fluid.barrier or a larger barrier distance keeps such pairs apart"
                             : "a barrier (fluid.barrier, Fuchs et al. 2022 Eq. 34) keeps such pairs apart";
    return amsph_fail("guard 'particle spacing' failed: %s is %.3g dx from its nearest neighbour, %s "
                      "particle id %u, closing at %.3g m/s (limit %.3g dx); %s",
                      where, (double)closest / dx, amsph_kind_name(kind), id, pair.closing_speed, limit,
                      remedy);
}

static int report(amsph_sim *s, int code, int i)
{
    amsph_real x[3];
    unsigned id;
    AMSPH_CHECK(fetch(s, AMSPH_FIELD_POSITION, i, x));
    AMSPH_CHECK(fetch(s, AMSPH_FIELD_ID, i, &id));
    char where[160];
    snprintf(where, sizeof where, "step %lld, t = %.6g s: particle id %u at (%.6g, %.6g, %.6g) m", s->step,
             s->time, id, (double)x[0], (double)x[1], (double)x[2]);
    if (code == GUARD_NOT_FINITE)
        return amsph_fail("guard 'finite values' failed: %s has a non-finite position, velocity, density "
                          "or temperature; reduce cfl or check the case's forces and material values",
                          where);
    const amsph_fluid_settings *f = &s->config.fluid;
    if (code == GUARD_CLOSE)
        return report_close_pair(s, i, where, f->min_pair_distance);
    amsph_real rho, rho0;
    AMSPH_CHECK(fetch(s, AMSPH_FIELD_DENSITY, i, &rho));
    AMSPH_CHECK(fetch(s, AMSPH_FIELD_REFERENCE_DENSITY, i, &rho0));
    return amsph_fail("guard 'density error' failed: %s has density %.6g kg/m^3, %.3g%% from "
                      "rho0 = %.6g (limit %.3g%%); raise sound_speed or max_density_error",
                      where, (double)rho, 100.0 * ((double)rho - rho0) / rho0, (double)rho0,
                      100.0 * f->max_density_error);
}

int amsph_guards_check(amsph_sim *s)
{
    amsph_particles *p = &s->particles;
    const amsph_fluid_settings *f = &s->config.fluid;
    amsph_buffer *density = p->field[AMSPH_FIELD_DENSITY], *temperature = p->field[AMSPH_FIELD_TEMPERATURE];
    /* fields a kernel does not read stand in for those that are absent */
    amsph_buffer *reference = f->enabled ? p->field[AMSPH_FIELD_REFERENCE_DENSITY] : density;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "guard_check", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_POSITION]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY]), amsph_arg_buffer(density),
                             amsph_arg_buffer(reference), amsph_arg_buffer(temperature ? temperature : density),
                             amsph_arg_int(temperature != NULL), amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                             amsph_arg_buffer(s->closest), amsph_arg_int(p->n), amsph_arg_int(f->enabled),
                             amsph_arg_real(f->min_pair_distance * s->config.dx),
                             amsph_arg_real(f->max_density_error), amsph_arg_int(f->clamp_negative_pressure),
                             amsph_arg_buffer(s->work)));
    double worst = 0.0;
    AMSPH_CHECK(amsph_reduce_max(s->backend, s->work, p->n, &worst));
    if (worst == GUARD_OK)
        return f->enabled ? amsph_fluid_check_smoothing_length(s) : 0;
    int i = 0;
    AMSPH_CHECK(first_with_code(s, (int)worst, &i));
    return report(s, (int)worst, i);
}
