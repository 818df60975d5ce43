/* The amsph command line. Exit status: 0 success, 1 a run failed, 2 bad
 * input (command line, case file or restart file), 128 + the signal number
 * for a run stopped by SIGINT or SIGTERM (after its checkpoint). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "analyze.h"
#include "backend.h"
#include "bench.h"
#include "case.h"
#include "checkpoint.h"
#include "error.h"
#include "output.h"
#include "powder.h"
#include "scene.h"
#include "series.h"
#include "sim.h"

#define EXIT_BAD_INPUT AMSPH_BAD_INPUT
#define DEFAULT_CHECKPOINT_INTERVAL 1800.0 /* wall seconds */
#define AMSPH_MAX_PLOTTED 16                /* metrics `analyze --plot` draws, at most */

static const char usage[] =
    "usage: amsph <command> [options]\n"
    "\n"
    "commands:\n"
    "  run CASE.yaml -o OUTDIR [--backend openmp|opencl] [--device N] [--quiet] [--force]\n"
    "      [--max-steps N] [--checkpoint-interval SECONDS] [--restart CHECKPOINT]\n"
    "                      run a case; snapshots OUTDIR/snap_NNNNNN.h5 and OUTDIR/snapshots.xmf,\n"
    "                      diagnostics OUTDIR/series.csv, checkpoints OUTDIR/checkpoint.h5\n"
    "  check CASE.yaml     validate a case file and build its scene without running it\n"
    "  devices             list the OpenCL devices and the OpenMP backend\n"
    "  keys                print the case-file key reference (Markdown)\n"
    "  columns             print the series.csv column reference (Markdown)\n"
    "  analyze OUTDIR [--csv FILE] [--plot FILE.png] [--scan x|y|z] [--up x|y|z] [--track-at M]\n"
    "          [--surface M]\n"
    "                      melt-pool metrics of every snapshot (default OUTDIR/melt_pool.csv),\n"
    "                      plotted over time with --plot; scan axis default x, up the last axis\n"
    "  analyze --metrics   print the metric reference (Markdown)\n"
    "  bench grid [--particles N]... [--repeat R] [--backend B] [--device N]\n"
    "                      time the sorted-grid build (3D, random particles)\n"
    "  bench throughput CASE.yaml [--particles N]... [--steps S] [--warmup W] [--quick]\n"
    "      [--kernels] [--csv FILE] [--backend B] [--device N]\n"
    "                      time the case's step scaled to N particles (default: as it is):\n"
    "                      particle-steps/s, ms per module, device bytes per particle and\n"
    "                      the growth of the step's time with N; --quick: 2 + 3 steps;\n"
    "                      --kernels: S more steps with each launch waited for, ms per kernel\n"
    "  --help              this text\n"
    "\n"
    "The backend and device default to the case file's, then openmp and the first\n"
    "OpenCL device; AMSPH_DEVICE in the environment picks the OpenCL device too.\n";

typedef struct {
    const char *case_path;
    const char *outdir;
    const char *backend; /* NULL: the case's */
    int device;          /* -1: the case's */
    int quiet;
    int force;
    long long max_steps;        /* 0: no limit */
    double checkpoint_interval; /* wall seconds; 0: none */
    const char *restart;        /* checkpoint to continue from */
    long long particles[AMSPH_BENCH_MAX_COUNTS]; /* bench: --particles, in order */
    int n_particles;
    int repeat;
    int steps;  /* 0: the default */
    int warmup; /* -1: the default */
    int quick;
    int kernels; /* bench throughput: time each kernel too */
    const char *csv;
    const char *plot;            /* analyze: PNG of the metrics over time */
    amsph_analysis_axes axes;    /* analyze */
    int metrics;                 /* analyze --metrics */
} cli_options;

static int bad_usage(const char *message, const char *value)
{
    fprintf(stderr, "amsph: %s%s%s\n(amsph --help for usage)\n", message, value ? ": " : "",
            value ? value : "");
    return EXIT_BAD_INPUT;
}

/* The value text of option `name` (NULL: missing) as an integer in [min,
 * max] into out; else bad usage that says what it takes (what: "a count"). */
static int parse_int_option(const char *name, const char *text, const char *what, long long min, long long max,
                            long long *out)
{
    char *end = NULL;
    errno = 0;
    const long long v = text ? strtoll(text, &end, 10) : 0;
    if (!text || *end || end == text || errno == ERANGE || v < min || v > max) {
        char message[160];
        snprintf(message, sizeof message, "%s takes %s from %lld to %lld", name, what, min, max);
        return bad_usage(message, text);
    }
    *out = v;
    return 0;
}

/* A particle count: an integer, also written as 1e6. */
static int parse_count_option(const char *text, long long *out)
{
    char *end = NULL;
    const double v = strtod(text, &end);
    if (!end || *end || end == text || !(v >= 1.0 && v <= 2e9) || v != floor(v))
        return 1;
    *out = (long long)v;
    return 0;
}

static int parse_seconds_option(const char *text, double *out)
{
    char *end = NULL;
    const double v = strtod(text, &end);
    if (!end || *end || end == text || !isfinite(v) || v < 0.0)
        return 1;
    *out = v;
    return 0;
}

/* An axis name x, y or z; -1 otherwise. */
static int parse_axis(const char *text)
{
    return !strcmp(text, "x") ? 0 : !strcmp(text, "y") ? 1 : !strcmp(text, "z") ? 2 : -1;
}

/* Parses the options after the command word; positional arguments go to
 * case_path (analyze: the output directory). Returns 0 or an exit status. */
static int parse_options(int argc, char **argv, cli_options *o)
{
    for (int i = 0; i < argc; ++i) {
        const char *a = argv[i];
        const int has_value = i + 1 < argc;
        const char *value = has_value ? argv[i + 1] : NULL;
        long long v = 0;
        if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!has_value || !*value)
                return bad_usage("-o needs a directory", NULL);
            o->outdir = argv[++i];
        } else if (!strcmp(a, "--backend")) {
            if (!has_value || (strcmp(value, "openmp") && strcmp(value, "opencl")))
                return bad_usage("--backend takes openmp or opencl", value);
            o->backend = argv[++i];
        } else if (!strcmp(a, "--device")) {
            if (parse_int_option(a, value, "a device index", 0, INT_MAX, &v))
                return EXIT_BAD_INPUT;
            o->device = (int)v;
            ++i;
        } else if (!strcmp(a, "--particles")) {
            if (!has_value || parse_count_option(value, &v))
                return bad_usage("--particles takes a count from 1 to 2e9", value);
            if (o->n_particles == AMSPH_BENCH_MAX_COUNTS)
                return bad_usage("--particles is given more than 32 times", NULL);
            o->particles[o->n_particles++] = v;
            ++i;
        } else if (!strcmp(a, "--steps") || !strcmp(a, "--warmup")) {
            const int steps = !strcmp(a, "--steps");
            if (parse_int_option(a, value, "a count", steps ? 1 : 0, 1000000, &v))
                return EXIT_BAD_INPUT;
            *(steps ? &o->steps : &o->warmup) = (int)v;
            ++i;
        } else if (!strcmp(a, "--csv")) {
            if (!has_value)
                return bad_usage("--csv needs a file", NULL);
            o->csv = argv[++i];
        } else if (!strcmp(a, "--plot")) {
            if (!has_value)
                return bad_usage("--plot needs a PNG file", NULL);
            o->plot = argv[++i];
        } else if (!strcmp(a, "--scan") || !strcmp(a, "--up")) {
            const int axis = has_value ? parse_axis(value) : -1;
            if (axis < 0)
                return bad_usage(!strcmp(a, "--scan") ? "--scan takes x, y or z" : "--up takes x, y or z",
                                 value);
            *(!strcmp(a, "--scan") ? &o->axes.scan : &o->axes.up) = axis;
            ++i;
        } else if (!strcmp(a, "--track-at") || !strcmp(a, "--surface")) {
            double *coordinate = !strcmp(a, "--track-at") ? &o->axes.track_at : &o->axes.surface;
            char *end = NULL;
            *coordinate = has_value ? strtod(value, &end) : NAN;
            if (!has_value || !end || *end || end == value || !isfinite(*coordinate))
                return bad_usage(!strcmp(a, "--track-at") ? "--track-at takes a coordinate in m"
                                                          : "--surface takes a coordinate in m",
                                 value);
            ++i;
        } else if (!strcmp(a, "--metrics")) {
            o->metrics = 1;
        } else if (!strcmp(a, "--quick")) {
            o->quick = 1;
        } else if (!strcmp(a, "--kernels")) {
            o->kernels = 1;
        } else if (!strcmp(a, "--repeat")) {
            if (parse_int_option(a, value, "a count", 1, 100000, &v))
                return EXIT_BAD_INPUT;
            o->repeat = (int)v;
            ++i;
        } else if (!strcmp(a, "--max-steps")) {
            if (parse_int_option(a, value, "a step count", 1, LLONG_MAX, &v))
                return EXIT_BAD_INPUT;
            o->max_steps = v;
            ++i;
        } else if (!strcmp(a, "--checkpoint-interval")) {
            if (!has_value || parse_seconds_option(value, &o->checkpoint_interval))
                return bad_usage("--checkpoint-interval takes wall seconds >= 0 (0: none)", value);
            ++i;
        } else if (!strcmp(a, "--restart")) {
            if (!has_value)
                return bad_usage("--restart needs a checkpoint file", NULL);
            o->restart = argv[++i];
        } else if (!strcmp(a, "--force")) {
            o->force = 1;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            o->quiet = 1;
        } else if (a[0] == '-') {
            return bad_usage("unknown option", a);
        } else if (!o->case_path) {
            o->case_path = a;
        } else {
            return bad_usage("unexpected argument", a);
        }
    }
    return 0;
}

static int load_case(const char *path, amsph_case *c)
{
    if (!path)
        return bad_usage("a case file is needed", NULL);
    char error[4096]; /* room for the longest list of allowed keys */
    if (amsph_case_load(path, c, error, sizeof error)) {
        fprintf(stderr, "%s\n", error);
        return EXIT_BAD_INPUT;
    }
    return 0;
}

static int open_backend(const char *name, int device, amsph_backend **b)
{
    if (amsph_backend_create(name, device, b)) {
        fprintf(stderr, "amsph: %s\n", amsph_last_error());
        return 1;
    }
    return 0;
}

/* The signal that asked a run to stop (0: none). The handler only sets it;
 * the run checks it after every step. A second signal ends the process. */
static volatile sig_atomic_t stop_signal;

static void on_stop_signal(int signo) { stop_signal = signo; }

static void catch_stop_signals(void)
{
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = on_stop_signal;
    action.sa_flags = SA_RESTART | SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, NULL);
    sigaction(SIGTERM, &action, NULL);
}

/* Reports a failed step of command_run; returns its exit status. */
static int failed(int status)
{
    fprintf(stderr, "amsph: %s\n", amsph_last_error());
    return status == AMSPH_BAD_INPUT ? EXIT_BAD_INPUT : 1;
}

/* The sim, created from the case or restored from the checkpoint. */
static int start_sim(const cli_options *o, const amsph_case *c, amsph_backend *b, amsph_checkpoint *ck,
                     amsph_sim *sim)
{
    if (!o->restart)
        return amsph_sim_create(c, b, sim);
    AMSPH_CHECK(amsph_sim_restore(c, b, &ck->state, sim));
    if (o->max_steps > 0 && sim->step >= o->max_steps)
        return amsph_bad_input("--max-steps %lld: the checkpoint %s is at step %lld already", o->max_steps,
                               o->restart, sim->step);
    return 0;
}

static void report_end(const cli_options *o, const amsph_sim *sim)
{
    if (stop_signal)
        fprintf(stderr, "amsph: stopped by signal %d at step %lld (t = %.6g s); restart from %s/checkpoint.h5\n",
                (int)stop_signal, sim->step, sim->time, o->outdir);
    else if (o->quiet)
        return;
    else if (sim->time < sim->config.end_time * (1.0 - 1e-12))
        fprintf(stderr, "amsph: stopped at step %lld (t = %.6g s), --max-steps; restart from %s/checkpoint.h5\n",
                sim->step, sim->time, o->outdir);
    else
        fprintf(stderr, "amsph: done, %lld steps, %lld particles left the domain, %lld evaporated; output in %s\n",
                sim->step, sim->particles.removed, sim->evaporated_particles, o->outdir);
}

/* Loads what a run needs before any work: the case, the checkpoint to
 * restart from, and an output directory it may write into. */
static int prepare_run(const cli_options *o, amsph_case *c, amsph_checkpoint *ck)
{
    int status = load_case(o->case_path, c);
    if (status)
        return status;
    if (!o->outdir)
        return bad_usage("run needs an output directory: -o OUTDIR", NULL);
    if (o->restart && ((status = amsph_checkpoint_read(o->restart, ck)) ||
                       (status = amsph_checkpoint_check_case(ck, o->restart, c))))
        return failed(status);
    const int in_place = o->restart && amsph_output_holds(o->outdir, o->restart);
    status = amsph_output_check_dir(o->outdir, o->force || in_place);
    return status ? failed(status) : 0;
}

/* One line per powder-bed block: its grains and packing fraction. */
static int report_powder_beds(const amsph_case *c, FILE *f)
{
    for (int k = 0; k < c->n_geometry; ++k) {
        const amsph_geometry *g = &c->geometry[k];
        if (g->shape != AMSPH_SHAPE_POWDER_BED)
            continue;
        amsph_powder bed;
        AMSPH_CHECK(amsph_powder_deposit(g, c->dim, &bed));
        double smallest = INFINITY, largest = 0.0;
        for (int i = 0; i < bed.n; ++i) {
            smallest = fmin(smallest, bed.grain[i].radius);
            largest = fmax(largest, bed.grain[i].radius);
        }
        fprintf(f, "amsph: %s:%d: powder bed of %d grains, radii %.4g to %.4g m, packing fraction %.4f\n",
                c->path, g->line, bed.n, smallest, largest, amsph_powder_packing_fraction(&bed, g));
        amsph_powder_free(&bed);
    }
    return 0;
}

/* --checkpoint-interval counts wall seconds. Below a second it is most
 * likely meant as simulated time, and rewrites the checkpoint (every field of
 * every particle) after nearly every step: a 414176-particle scene took 204 s
 * for 204 steps with 1e-6, 124 s without (BENCHMARKS.md, "The gas in 3D").
 * Said even with --quiet, and the run goes on: frequent checkpoints can be
 * wanted when debugging. */
static void warn_short_checkpoint_interval(double interval)
{
    if (interval > 0.0 && interval < 1.0)
        fprintf(stderr,
                "amsph: warning: --checkpoint-interval %g is in seconds of wall time, not simulated time: "
                "the checkpoint is rewritten after every step that takes longer\n",
                interval);
}

static int command_run(const cli_options *o)
{
    catch_stop_signals();
    amsph_case c;
    amsph_checkpoint ck = {0};
    amsph_backend *b = NULL;
    int status = prepare_run(o, &c, &ck);
    if (!status) {
        const char *backend = c.backend == AMSPH_BACKEND_OPENCL ? "opencl" : "openmp";
        status = open_backend(o->backend ? o->backend : backend, o->device >= 0 ? o->device : c.device, &b);
    }
    if (!status && !o->quiet) {
        fprintf(stderr, "amsph: %s on %s\n", c.path, b->description);
        status = report_powder_beds(&c, stderr);
    }
    if (!status)
        warn_short_checkpoint_interval(o->checkpoint_interval);
    if (status) {
        amsph_checkpoint_free(&ck);
        amsph_backend_destroy(b);
        return status;
    }
    amsph_sim sim;
    const amsph_run_options run = {.outdir = o->outdir,
                                   .quiet = o->quiet,
                                   .force = o->force,
                                   .max_steps = o->max_steps,
                                   .checkpoint_interval = o->checkpoint_interval,
                                   .stop = &stop_signal,
                                   .resume = o->restart ? &ck.run : NULL,
                                   .resume_path = o->restart};
    status = start_sim(o, &c, b, &ck, &sim);
    if (!status) {
        if (!o->quiet)
            fprintf(stderr, "amsph: %d particles, h = %g m, %.0f device bytes per particle\n",
                    sim.particles.n, sim.h, (double)b->allocated / sim.particles.n);
        status = amsph_sim_run(&sim, &run);
    }
    if (status)
        status = failed(status);
    else
        report_end(o, &sim);
    amsph_sim_free(&sim);
    amsph_checkpoint_free(&ck);
    amsph_backend_destroy(b);
    return status ? status : stop_signal ? 128 + (int)stop_signal : 0;
}

/* Parses the case, lays out its grid and laser bins and builds its scene
 * (the errors of placing the blocks: overlaps, empty blocks, particles
 * outside the domain), as `run` would. */
static int command_check(const cli_options *o)
{
    amsph_case c;
    int status = load_case(o->case_path, &c);
    if (status)
        return status;
    amsph_host_particles h = {0};
    status = amsph_sim_check_layout(&c);
    if (!status)
        status = amsph_scene_build(&c, &h);
    if (!status)
        printf("%s: ok (dimension %d, %d materials, %d geometry blocks, %d particles)\n", c.path, c.dim,
               c.n_materials, c.n_geometry, h.n);
    amsph_host_free(&h);
    if (status)
        return failed(status);
    return report_powder_beds(&c, stdout);
}

static int bench_grid(const cli_options *o, amsph_backend *b)
{
    int status = 0;
    for (int k = 0; k < (o->n_particles ? o->n_particles : 1) && !status; ++k)
        status = amsph_bench_grid(b, o->n_particles ? o->particles[k] : 100000, o->repeat ? o->repeat : 10,
                                  stdout);
    return status;
}

static int bench_throughput(const cli_options *o, const amsph_case *c, amsph_backend *b)
{
    amsph_bench_options bench = {.n_particles = o->n_particles,
                                 .warmup = o->warmup >= 0 ? o->warmup : o->quick ? 2 : 5,
                                 .steps = o->steps ? o->steps : o->quick ? 3 : 20,
                                 .kernels = o->kernels};
    memcpy(bench.particles, o->particles, sizeof bench.particles);
    if (o->csv && !(bench.csv = fopen(o->csv, "w")))
        return amsph_bad_input("cannot write %s: %s", o->csv, strerror(errno));
    const int status = amsph_bench_throughput(b, c, &bench, stdout);
    if (bench.csv && fclose(bench.csv) && !status)
        return amsph_fail("cannot write %s: %s", o->csv, strerror(errno));
    return status;
}

/* `bench grid` or `bench throughput CASE` (what: the word after bench). */
static int command_bench(const cli_options *o, const char *what)
{
    const char *case_path = o->case_path;
    const int grid = what && !strcmp(what, "grid");
    if (!grid && !(what && !strcmp(what, "throughput")))
        return bad_usage("bench knows: grid, throughput", what);
    amsph_case c;
    if (grid && case_path)
        return bad_usage("bench grid takes no case file", case_path);
    if (!grid && load_case(case_path, &c))
        return EXIT_BAD_INPUT;
    amsph_backend *b = NULL;
    const char *backend = grid || c.backend == AMSPH_BACKEND_OPENMP ? "openmp" : "opencl";
    if (open_backend(o->backend ? o->backend : backend, o->device >= 0 ? o->device : grid ? -1 : c.device, &b))
        return 1;
    const int status = grid ? bench_grid(o, b) : bench_throughput(o, &c, b);
    if (status)
        fprintf(stderr, "amsph: %s\n", amsph_last_error());
    amsph_backend_destroy(b);
    return status == AMSPH_BAD_INPUT ? EXIT_BAD_INPUT : status ? 1 : 0;
}

/* Runs argv (argv[0] looked up on PATH) and waits; its exit status, or 1. */
static int run_program(char *const argv[])
{
    fflush(NULL);
    const pid_t child = fork();
    if (child == 0) {
        execvp(argv[0], argv);
        fprintf(stderr, "amsph: cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) < 0)
        return 1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

/* Plots the analysis CSV with tools/plot_series.py: the Python of
 * AMSPH_PYTHON (environment, else the one CMake found), the tools of
 * AMSPH_SOURCE_DIR (environment, else the source tree of the build). */
static int plot_analysis(const char *self, const char *csv, const char *png)
{
    const char *python = getenv("AMSPH_PYTHON") ? getenv("AMSPH_PYTHON") : AMSPH_PYTHON;
    const char *source = getenv("AMSPH_SOURCE_DIR") ? getenv("AMSPH_SOURCE_DIR") : AMSPH_SOURCE_DIR;
    char script[1100];
    snprintf(script, sizeof script, "%s/tools/plot_series.py", source);
    char *argv[8 + AMSPH_MAX_PLOTTED] = {(char *)python, script, (char *)csv, "-o", (char *)png,
                                         "--amsph", (char *)self, "--units-from", "metrics", "--columns"};
    int argc = 10;
    for (int k = 1; k < amsph_analysis_metric_count && argc < 8 + AMSPH_MAX_PLOTTED - 1; ++k)
        argv[argc++] = (char *)amsph_analysis_metrics[k].name;
    argv[argc] = NULL;
    const int status = run_program(argv);
    if (status)
        fprintf(stderr, "amsph: plotting %s with %s %s failed (status %d); the CSV is written\n", png, python, script,
                status);
    return status ? 1 : 0;
}

static int command_analyze(const cli_options *o, const char *self)
{
    if (o->metrics) {
        amsph_analysis_print_metrics(stdout);
        return 0;
    }
    if (!o->case_path)
        return bad_usage("analyze needs an output directory", NULL);
    char csv[1100];
    if (!o->csv && snprintf(csv, sizeof csv, "%s/" AMSPH_OUTPUT_ANALYSIS, o->case_path) >= (int)sizeof csv)
        return bad_usage("output directory path too long", o->case_path);
    const char *path = o->csv ? o->csv : csv;
    const int status = amsph_analyze(o->case_path, &o->axes, path);
    if (status)
        return failed(status);
    return o->plot ? plot_analysis(self, path, o->plot) : 0;
}

int main(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        fputs(usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? EXIT_BAD_INPUT : 0;
    }
    const char *command = argv[1];
    cli_options o = {.device = -1,
                     .checkpoint_interval = DEFAULT_CHECKPOINT_INTERVAL,
                     .warmup = -1,
                     .axes = {.scan = 0, .up = -1, .track_at = NAN, .surface = NAN}};
    const int options_from = !strcmp(command, "bench") && argc > 2 ? 3 : 2; /* after `bench WHAT` */
    int status = parse_options(argc - options_from, argv + options_from, &o);
    if (status)
        return status;
    if (!strcmp(command, "run"))
        return command_run(&o);
    if (!strcmp(command, "check"))
        return command_check(&o);
    if (!strcmp(command, "devices")) {
        amsph_backend_list(stdout);
        return 0;
    }
    if (!strcmp(command, "keys")) {
        amsph_case_print_keys(stdout);
        return 0;
    }
    if (!strcmp(command, "columns")) {
        amsph_series_print_columns(stdout);
        return 0;
    }
    if (!strcmp(command, "bench"))
        return command_bench(&o, argc > 2 ? argv[2] : NULL);
    if (!strcmp(command, "analyze"))
        return command_analyze(&o, argv[0]);
    return bad_usage("unknown command", command);
}
