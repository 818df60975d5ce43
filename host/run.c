/* The run: time loop to the end time, snapshots at the output times,
 * progress on stderr, and the last good state written when a guard fails. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "error.h"
#include "output.h"
#include "sim.h"

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int write_snapshot(amsph_particles *p, amsph_output *out, double time, long long step)
{
    amsph_host_particles host;
    int status = amsph_particles_download(p, &host);
    if (!status)
        status = amsph_output_snapshot(out, &host, time, step);
    amsph_host_free(&host);
    return status;
}

/* After a failed guard: the last state that passed, as the next snapshot. */
static int write_last_good(amsph_sim *s, amsph_output *out)
{
    char message[1024];
    snprintf(message, sizeof message, "%s", amsph_last_error());
    if (write_snapshot(&s->last_good, out, s->last_good_time, s->last_good_step))
        return amsph_fail("%s; writing the last good state failed too: %s", message, amsph_last_error());
    return amsph_fail("%s\nthe last good state (step %lld, t = %.6g s) is %s/snap_%06d.h5", message,
                      s->last_good_step, s->last_good_time, out->dir, out->count - 1);
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
    fprintf(stderr,
            "%st = %.4e s  %5.1f%%  step %lld  dt %.2e (%s)  %.1f steps/s  %.3e particle-steps/s  "
            "ETA %.0f s%s",
            pr->terminal ? "\r" : "", s->time, 100.0 * fraction, s->step, s->dt, s->dt_limit,
            elapsed > 0 ? steps / elapsed : 0.0, elapsed > 0 ? pr->particle_steps / elapsed : 0.0, eta,
            pr->terminal && !final ? "  " : "\n");
    fflush(stderr);
}

static void after_step(void *context, const amsph_sim *s)
{
    progress *pr = context;
    pr->particle_steps += s->particles.n;
    report_progress(pr, s, 0);
}

int amsph_sim_advance(amsph_sim *s, double target, void (*each_step)(void *, const amsph_sim *),
                      void *context)
{
    while (s->time < target * (1.0 - 1e-12)) {
        double dt = 0.0;
        AMSPH_CHECK(amsph_sim_stable_dt(s, &dt));
        AMSPH_CHECK(amsph_sim_step(s, fmin(dt, target - s->time)));
        if (each_step)
            each_step(context, s);
    }
    s->time = target; /* land exactly on output times */
    return 0;
}

int amsph_sim_run(amsph_sim *s, const amsph_run_options *options)
{
    amsph_output out;
    AMSPH_CHECK(amsph_output_open(&out, options->outdir, s->config.dim, s->config.dx));
    progress pr = {.quiet = options->quiet, .terminal = isatty(2), .start = wall_seconds(),
                   .first_step = s->step};
    const double end = s->config.end_time;
    const double interval = s->config.output_interval;
    int status = write_snapshot(&s->particles, &out, s->time, s->step);
    for (long long k = 1; !status && s->time < end * (1.0 - 1e-12); ++k) {
        status = amsph_sim_advance(s, fmin(end, (double)k * interval), after_step, &pr);
        if (!status)
            status = write_snapshot(&s->particles, &out, s->time, s->step);
    }
    if (status && s->guard_failed)
        status = write_last_good(s, &out);
    if (!status)
        report_progress(&pr, s, 1);
    amsph_output_close(&out);
    return status;
}
