#include "sim.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "error.h"
#include "output.h"
#include "scene.h"

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

double amsph_support_over_h(amsph_kernel_type kernel)
{
    return kernel == AMSPH_KERNEL_QUINTIC ? 3.0 : 2.0; /* SUPPORT_OVER_H of kernels/smoothing.h */
}

static int compute_acceleration(amsph_sim *s)
{
    amsph_particles *p = &s->particles;
    const double *g = s->config.gravity;
    return AMSPH_LAUNCH(s->backend, "body_force", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                        amsph_arg_int(p->n), amsph_arg_real(g[0]), amsph_arg_real(g[1]),
                        amsph_arg_real(g[2]), amsph_arg_buffer(p->field[AMSPH_FIELD_ACCELERATION]));
}

int amsph_sim_create(const amsph_case *c, amsph_backend *b, amsph_sim *s)
{
    memset(s, 0, sizeof *s);
    s->config = *c;
    s->backend = b;
    s->h = c->h_over_dx * c->dx;
    s->support = amsph_support_over_h(c->kernel) * s->h;
    amsph_build_options build = {.dim = c->dim, .kernel = (int)c->kernel};
    AMSPH_CHECK(amsph_build(b, &build));

    amsph_host_particles host;
    int status = amsph_scene_build(c, &host);
    if (!status)
        status = amsph_host_add_field(&host, AMSPH_FIELD_ACCELERATION);
    if (!status)
        status = amsph_particles_upload(b, &host, &s->particles);
    amsph_host_free(&host);
    AMSPH_CHECK(status);
    const int capacity = s->particles.capacity;
    AMSPH_CHECK(amsph_grid_init(&s->grid, b, c->dim, c->domain_min, c->domain_max, c->periodic,
                                s->support, capacity));
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * sizeof(amsph_real), &s->work));
    AMSPH_CHECK(amsph_grid_sort(&s->grid, &s->particles));
    return compute_acceleration(s);
}

void amsph_sim_free(amsph_sim *s)
{
    if (!s->backend)
        return;
    amsph_grid_free(&s->grid, s->backend);
    amsph_particles_free(&s->particles);
    amsph_buffer_free(s->backend, s->work);
    memset(s, 0, sizeof *s);
}

/* Time-step limits (Fuchs et al. 2022 Eq. 42):
 *   acoustic  dt <= 0.25 h / (c0 + |u|max)
 *   body force dt <= 0.25 sqrt(h / |g|)
 * Later modules add viscous, capillary and diffusion limits here. */
int amsph_sim_stable_dt(amsph_sim *s, double *dt)
{
    amsph_particles *p = &s->particles;
    double umax = 0.0;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "vector_norm", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY]),
                             amsph_arg_int(p->n), amsph_arg_buffer(s->work)));
    AMSPH_CHECK(amsph_reduce_max(s->backend, s->work, p->n, &umax));
    double c0 = 0.0;
    for (int m = 0; m < s->config.n_materials; ++m)
        c0 = fmax(c0, s->config.materials[m].sound_speed);
    const double *g = s->config.gravity;
    const double gnorm = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    double limit = INFINITY;
    if (c0 + umax > 0.0)
        limit = fmin(limit, 0.25 * s->h / (c0 + umax));
    if (gnorm > 0.0)
        limit = fmin(limit, 0.25 * sqrt(s->h / gnorm));
    if (!isfinite(umax))
        return amsph_fail("step %lld, t = %g s: a particle speed is not finite", s->step, s->time);
    *dt = limit;
    return 0;
}

int amsph_sim_step(amsph_sim *s, double dt)
{
    amsph_backend *b = s->backend;
    amsph_particles *p = &s->particles;
    AMSPH_CHECK(AMSPH_LAUNCH(b, "kick", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_ACCELERATION]), amsph_arg_int(p->n),
                             amsph_arg_real(0.5 * dt), amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY])));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "drift", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY]), amsph_arg_int(p->n),
                             amsph_arg_real(dt), amsph_arg_buffer(p->field[AMSPH_FIELD_POSITION])));
    AMSPH_CHECK(amsph_grid_sort(&s->grid, p));
    AMSPH_CHECK(compute_acceleration(s));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "kick", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_ACCELERATION]), amsph_arg_int(p->n),
                             amsph_arg_real(0.5 * dt), amsph_arg_buffer(p->field[AMSPH_FIELD_VELOCITY])));
    s->time += dt;
    s->dt = dt;
    ++s->step;
    return 0;
}

static int write_snapshot(amsph_sim *s, amsph_output *out)
{
    amsph_host_particles host;
    int status = amsph_particles_download(&s->particles, &host);
    if (!status)
        status = amsph_output_snapshot(out, &host, s->time, s->step);
    amsph_host_free(&host);
    return status;
}

typedef struct {
    int quiet, terminal;
    double start, last_print;
    long long first_step;
    double particle_steps;
} progress;

static void report_progress(progress *pr, const amsph_sim *s, int final)
{
    const double now = wall_seconds();
    const double interval = pr->terminal ? 0.5 : 10.0;
    if (pr->quiet || (!final && now - pr->last_print < interval))
        return;
    pr->last_print = now;
    const double elapsed = now - pr->start;
    const double fraction = s->time / s->config.end_time;
    const double steps = (double)(s->step - pr->first_step);
    const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    fprintf(stderr, "%st = %.4e s  %5.1f%%  step %lld  %.1f steps/s  %.3e particle-steps/s  ETA %.0f s%s",
            pr->terminal ? "\r" : "", s->time, 100.0 * fraction, s->step,
            elapsed > 0 ? steps / elapsed : 0.0, elapsed > 0 ? pr->particle_steps / elapsed : 0.0,
            eta, pr->terminal && !final ? "  " : "\n");
    fflush(stderr);
}

int amsph_sim_run(amsph_sim *s, const amsph_run_options *options)
{
    amsph_output out;
    AMSPH_CHECK(amsph_output_open(&out, options->outdir, s->config.dim, s->config.dx));
    progress pr = {.quiet = options->quiet, .terminal = isatty(2), .start = wall_seconds(),
                   .first_step = s->step};
    const double end = s->config.end_time;
    const double interval = s->config.output_interval;
    int status = write_snapshot(s, &out);
    long long next_output = 1;
    while (!status && s->time < end * (1.0 - 1e-12)) {
        const double target = fmin(end, (double)next_output * interval);
        double dt = 0.0;
        status = amsph_sim_stable_dt(s, &dt);
        if (status)
            break;
        dt = fmin(dt, target - s->time);
        status = amsph_sim_step(s, dt);
        pr.particle_steps += s->particles.n;
        if (!status && s->time >= target * (1.0 - 1e-12)) {
            s->time = target; /* land exactly on output times */
            status = write_snapshot(s, &out);
            ++next_output;
        }
        report_progress(&pr, s, 0);
    }
    if (!status)
        report_progress(&pr, s, 1);
    amsph_output_close(&out);
    return status;
}
