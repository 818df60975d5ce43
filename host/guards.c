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

/* The particle nearest to particle a, which the spacing guard stopped (a scan
 * of the downloaded state, with the nearest periodic image on periodic
 * axes), and the speed -(u_a - u_b) . e_ab at which the pair closes. */
static int nearest_neighbour(const amsph_host_particles *h, const grid_geometry *g, int a, double *closing_speed)
{
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION), *u = amsph_host_real(h, AMSPH_FIELD_VELOCITY);
    double best = INFINITY, r_ab[3] = {0.0, 0.0, 0.0};
    int nearest = -1;
    for (int b = 0; b < h->n; ++b) {
        double r[3], r2 = 0.0;
        for (int d = 0; d < 3; ++d) {
            r[d] = (double)x[3 * a + d] - x[3 * b + d];
            if (g->periodic[d])
                r[d] = remainder(r[d], g->length[d]);
            r2 += r[d] * r[d];
        }
        if (b != a && r2 < best) {
            best = r2;
            nearest = b;
            for (int d = 0; d < 3; ++d)
                r_ab[d] = r[d];
        }
    }
    *closing_speed = 0.0;
    for (int d = 0; nearest >= 0 && d < 3; ++d)
        *closing_speed -= ((double)u[3 * a + d] - u[3 * nearest + d]) * r_ab[d] / sqrt(best);
    return nearest;
}

/* The spacing guard's message: the distance it tested, the pair, how fast it
 * closes, and the setting that keeps such pairs apart (Fuchs et al. 2022
 * Eq. 34). */
static int report_close_pair(amsph_sim *s, int i, const char *where, double limit)
{
    amsph_real closest;
    AMSPH_CHECK(amsph_download(s->backend, s->closest, (size_t)i * sizeof closest, sizeof closest, &closest));
    amsph_host_particles h;
    const int status = amsph_particles_download(&s->particles, &h);
    if (status) {
        amsph_host_free(&h);
        return status;
    }
    double closing_speed;
    const int j = nearest_neighbour(&h, &s->grid.geometry, i, &closing_speed);
    const unsigned id = j >= 0 ? ((const unsigned *)h.data[AMSPH_FIELD_ID])[j] : 0;
    const int kind = j >= 0 ? ((const int *)h.data[AMSPH_FIELD_KIND])[j] : -1;
    amsph_host_free(&h);
    if (j < 0)
        return amsph_fail("the spacing guard found no second particle");
    const amsph_fluid_settings *f = &s->config.fluid;
    const char *remedy = f->barrier_stiffness > 0.0
                             ? "a stiffer fluid.barrier or a larger barrier distance keeps such pairs apart"
                             : "a barrier (fluid.barrier, Fuchs et al. 2022 Eq. 34) keeps such pairs apart";
    return amsph_fail("guard 'particle spacing' failed: %s is %.3g dx from its nearest neighbour, %s "
                      "particle id %u, closing at %.3g m/s (limit %.3g dx); %s",
                      where, (double)closest / s->config.dx, amsph_kind_name(kind), id, closing_speed, limit,
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
