/* The run: the time loop to the end time or a requested stop, snapshots and
 * series rows at the output times, checkpoints, progress on stderr, and the
 * last good state written when a guard fails. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "checkpoint.h"
#include "error.h"
#include "output.h"
#include "series.h"
#include "sim.h"
#include "thermal.h"

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct {
    int quiet, terminal;
    int line_open;         /* a terminal line waits for its newline */
    double start;          /* wall clock at the start of this run */
    double last_print;
    double start_fraction; /* progress at the start of this run */
    long long first_step;
    double particle_steps; /* since the start of this run */
} progress;

typedef struct {
    amsph_sim *s;
    const amsph_run_options *options;
    amsph_output out;
    amsph_series series;
    progress pr;
    long long next_output;      /* index k of the next output time k * output_interval */
    long long snapshot_step;    /* step of the last snapshot written (-1: none in this run) */
    double wall_before;         /* wall seconds of the simulation before this run */
    double last_checkpoint;     /* wall clock of the last checkpoint */
    double row_wall;            /* wall clock at the previous series row */
    double row_particle_steps;  /* progress.particle_steps at the previous series row */
    int status;                 /* a failure inside the step callback */
} run;

/* Share of the run done: of the end time, or of max_steps if that is nearer. */
static double fraction_done(const run *r)
{
    const amsph_sim *s = r->s;
    double f = s->time / s->config.end_time;
    if (r->options->max_steps > 0)
        f = fmax(f, (double)s->step / (double)r->options->max_steps);
    return fmin(f, 1.0);
}

/* The longest duration format_duration writes as h:mm:ss. */
#define LONGEST_DAYS 99

/* h:mm:ss; "?" when unknown, ">99 days" beyond LONGEST_DAYS (also an
 * estimate that overflowed to infinity). */
static void format_duration(double seconds, char *out, size_t size)
{
    if (isnan(seconds) || seconds < 0.0) {
        snprintf(out, size, "?");
        return;
    }
    if (seconds > LONGEST_DAYS * 86400.0) { /* also keeps the conversion below in range */
        snprintf(out, size, ">%d days", LONGEST_DAYS);
        return;
    }
    const long long whole = (long long)(seconds + 0.5);
    snprintf(out, size, "%lld:%02lld:%02lld", whole / 3600, whole / 60 % 60, whole % 60);
}

/* One progress line: in place on a terminal (every 0.5 s), a plain line
 * every 10 s otherwise, and always at the end (final). */
static void report_progress(run *r, int final)
{
    progress *pr = &r->pr;
    const double now = wall_seconds();
    if (pr->quiet || (!final && now - pr->last_print < (pr->terminal ? 0.5 : 10.0)))
        return;
    pr->last_print = now;
    const amsph_sim *s = r->s;
    const double elapsed = now - pr->start;
    const double fraction = fraction_done(r);
    const double done = fraction - pr->start_fraction;
    char eta[32];
    format_duration(done > 0.0 ? elapsed * (1.0 - fraction) / done : NAN, eta, sizeof eta);
    fprintf(stderr,
            "%st = %.4e s  %5.1f%%  step %lld  dt %.2e (%s)  %.1f steps/s  %.3e particle-steps/s  ETA %s%s",
            pr->terminal ? "\r" : "", s->time, 100.0 * fraction, s->step, s->dt, s->dt_limit,
            elapsed > 0 ? (double)(s->step - pr->first_step) / elapsed : 0.0,
            elapsed > 0 ? pr->particle_steps / elapsed : 0.0, eta, pr->terminal ? "\033[K" : "\n");
    if (final && pr->terminal)
        fputc('\n', stderr);
    pr->line_open = pr->terminal && !final;
    fflush(stderr);
}

/* Ends a terminal progress line before other messages follow. */
static void close_progress_line(progress *pr)
{
    if (pr->line_open)
        fputc('\n', stderr);
    pr->line_open = 0;
}

static int stop_requested(const run *r)
{
    const amsph_run_options *o = r->options;
    return (o->stop && *o->stop) || (o->max_steps > 0 && r->s->step >= o->max_steps);
}

static int finished(const run *r) { return r->s->time >= r->s->config.end_time * (1.0 - 1e-12); }

static int write_checkpoint(run *r)
{
    amsph_sim *s = r->s;
    char path[1100];
    AMSPH_CHECK(amsph_output_path(&r->out, AMSPH_OUTPUT_CHECKPOINT, path, sizeof path));
    amsph_checkpoint ck = {.dim = s->config.dim, .case_hash = s->config.text_hash};
    snprintf(ck.case_path, sizeof ck.case_path, "%s", s->config.path);
    ck.run.next_output = r->next_output;
    ck.run.wall_seconds = r->wall_before + wall_seconds() - r->pr.start;
    ck.run.series_bytes = amsph_series_bytes(&r->series);
    ck.run.snapshots = r->out.list; /* borrowed: only the state is freed below */
    int status = amsph_sim_save(s, &ck.state);
    if (!status)
        status = amsph_checkpoint_write(path, &ck);
    amsph_sim_state_free(&ck.state);
    r->last_checkpoint = wall_seconds();
    return status;
}

/* A snapshot of the current state and its row of the series. */
static int write_output(run *r)
{
    amsph_sim *s = r->s;
    amsph_host_particles host = {0};
    const double now = wall_seconds();
    const double interval = now - r->row_wall;
    const double particle_steps = r->pr.particle_steps - r->row_particle_steps;
    amsph_series_sample sample = {
        .sim = s,
        .particles = &host,
        .enthalpy = NAN,
        .wall_seconds = r->wall_before + now - r->pr.start,
        .particle_steps_per_second = interval > 0.0 ? particle_steps / interval : 0.0,
    };
    int status = s->config.thermal.enabled ? amsph_thermal_energy(s, &sample.enthalpy) : 0;
    if (!status)
        status = amsph_particles_download(&s->particles, &host);
    if (!status)
        status = amsph_output_snapshot(&r->out, &host, s->time, s->step);
    if (!status)
        status = amsph_series_write(&r->series, &sample);
    amsph_host_free(&host);
    r->snapshot_step = s->step;
    r->row_wall = now;
    r->row_particle_steps = r->pr.particle_steps;
    return status;
}

static int after_step(void *context, const amsph_sim *s)
{
    run *r = context;
    r->pr.particle_steps += s->particles.n;
    report_progress(r, 0);
    const double interval = r->options->checkpoint_interval;
    if (interval > 0.0 && wall_seconds() - r->last_checkpoint >= interval)
        r->status = write_checkpoint(r);
    return r->status || stop_requested(r);
}

int amsph_sim_advance(amsph_sim *s, double target, int (*each_step)(void *, const amsph_sim *), void *context)
{
    while (s->time < target * (1.0 - 1e-12)) {
        double dt = 0.0;
        AMSPH_CHECK(amsph_sim_stable_dt(s, &dt));
        AMSPH_CHECK(amsph_sim_step(s, fmin(dt, target - s->time)));
        if (each_step && each_step(context, s) && s->time < target * (1.0 - 1e-12))
            return 0;
    }
    s->time = target; /* land exactly on output times */
    return 0;
}

/* Advances to the next output time and writes its output, unless a stop or
 * a failure comes first. */
static int advance_to_next_output(run *r)
{
    amsph_sim *s = r->s;
    const double target = fmin(s->config.end_time, (double)r->next_output * s->config.output_interval);
    AMSPH_CHECK(amsph_sim_advance(s, target, after_step, r));
    AMSPH_CHECK(r->status);
    if (s->time != target)
        return 0;
    ++r->next_output;
    return write_output(r);
}

/* A requested stop: the final state as a snapshot, unless it just was one,
 * and a checkpoint to restart from. */
static int stop_with_checkpoint(run *r)
{
    if (r->snapshot_step != r->s->step)
        AMSPH_CHECK(write_output(r));
    return write_checkpoint(r);
}

/* After a failed guard: the last state that passed, as the next snapshot. */
static int write_last_good(amsph_sim *s, amsph_output *out)
{
    char message[1024];
    snprintf(message, sizeof message, "%s", amsph_last_error());
    amsph_host_particles host;
    int status = amsph_particles_download(&s->last_good, &host);
    if (!status)
        status = amsph_output_snapshot(out, &host, s->last_good_time, s->last_good_step);
    amsph_host_free(&host);
    if (status)
        return amsph_fail("%s; writing the last good state failed too: %s", message, amsph_last_error());
    return amsph_fail("%s\nthe last good state (step %lld, t = %.6g s) is %s/snap_%06d.h5", message,
                      s->last_good_step, s->last_good_time, out->dir, out->list.count - 1);
}

/* Opens the output (continuing a restarted simulation's, in place when the
 * output directory is the checkpoint's) and starts the clocks. */
static int start(run *r, amsph_sim *s, const amsph_run_options *options)
{
    memset(r, 0, sizeof *r);
    r->s = s;
    r->options = options;
    r->next_output = 1;
    r->snapshot_step = -1;
    const amsph_run_record *resume = options->resume;
    const int in_place = resume && amsph_output_holds(options->outdir, options->resume_path);
    const int force = options->force || in_place;
    AMSPH_CHECK(amsph_output_open(&r->out, options->outdir, s->config.dim, s->config.dx, force));
    if (resume) {
        AMSPH_CHECK(amsph_output_continue(&r->out, &resume->snapshots, in_place));
        r->next_output = resume->next_output;
        r->wall_before = resume->wall_seconds;
    }
    AMSPH_CHECK(amsph_output_clear(&r->out, in_place));
    char path[1100];
    AMSPH_CHECK(amsph_output_path(&r->out, AMSPH_OUTPUT_SERIES, path, sizeof path));
    AMSPH_CHECK(amsph_series_open(&r->series, path, in_place ? resume->series_bytes : -1));
    const double now = wall_seconds();
    r->pr = (progress){.quiet = options->quiet, .terminal = isatty(2), .start = now, .last_print = now,
                       .first_step = s->step};
    r->pr.start_fraction = fraction_done(r);
    r->last_checkpoint = r->row_wall = now;
    return 0;
}

int amsph_sim_run(amsph_sim *s, const amsph_run_options *options)
{
    run r;
    int status = start(&r, s, options);
    if (!status && !options->resume)
        status = write_output(&r);
    while (!status && !finished(&r) && !stop_requested(&r))
        status = advance_to_next_output(&r);
    if (!status && !finished(&r))
        status = stop_with_checkpoint(&r);
    if (status)
        close_progress_line(&r.pr);
    if (status && s->guard_failed)
        status = write_last_good(s, &r.out);
    if (!status)
        report_progress(&r, 1);
    amsph_series_close(&r.series);
    amsph_output_close(&r.out);
    return status;
}
