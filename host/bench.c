#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "grid.h"
#include "particles.h"
#include "scene.h"
#include "sim.h"
#include "timers.h"

/* The fields of a fluid scene, at random positions in [0, 1)^3. */
static int random_scene(amsph_host_particles *h, int n)
{
    static const amsph_field_id fields[] = {
        AMSPH_FIELD_POSITION, AMSPH_FIELD_VELOCITY, AMSPH_FIELD_ACCELERATION, AMSPH_FIELD_DENSITY,
        AMSPH_FIELD_PRESSURE, AMSPH_FIELD_MASS,     AMSPH_FIELD_KIND,         AMSPH_FIELD_MATERIAL,
        AMSPH_FIELD_ID};
    h->n = n;
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; ++k)
        AMSPH_CHECK(amsph_host_add_field(h, fields[k]));
    unsigned long long state = 12345;
    amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
    for (int i = 0; i < 3 * n; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        x[i] = (amsph_real)((double)(state >> 11) * 0x1.0p-53);
    }
    for (int i = 0; i < n; ++i)
        ((unsigned *)h->data[AMSPH_FIELD_ID])[i] = (unsigned)i;
    return 0;
}

static int timed_sort(amsph_grid *g, amsph_particles *p, double *seconds)
{
    AMSPH_CHECK(amsph_sync(p->backend));
    const double t0 = amsph_wall_seconds();
    AMSPH_CHECK(amsph_grid_sort(g, p));
    AMSPH_CHECK(amsph_sync(p->backend));
    *seconds = amsph_wall_seconds() - t0;
    return 0;
}

static int compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int amsph_bench_grid(amsph_backend *b, long long n, int repeat, FILE *out)
{
    const amsph_build_options build = {.dim = 3, .kernel = 0};
    AMSPH_CHECK(amsph_build(b, &build));
    amsph_host_particles host = {0};
    amsph_particles p = {0};
    amsph_grid g = {0};
    double *times = calloc((size_t)repeat, sizeof *times);
    const double dx = pow((double)n, -1.0 / 3.0);
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const int periodic[3] = {0, 0, 0};
    int status = times ? random_scene(&host, (int)n) : amsph_fail("out of host memory");
    if (!status)
        status = amsph_particles_upload(b, &host, &p);
    if (!status)
        status = amsph_grid_init(&g, b, 3, lo, hi, periodic, 2.0 * 1.2 * dx, p.capacity);
    double first = 0.0;
    if (!status)
        status = timed_sort(&g, &p, &first);
    for (int r = 0; r < repeat && !status; ++r)
        status = timed_sort(&g, &p, &times[r]);
    if (!status) {
        qsort(times, (size_t)repeat, sizeof *times, compare_doubles);
        const double median = times[repeat / 2];
        fprintf(out, "| %s | %lld | %d | %.3f | %.1f | %.3f | %.1f |\n", b->description, n,
                g.geometry.total_cells, 1e3 * first, 1e9 * first / (double)n, 1e3 * median,
                1e9 * median / (double)n);
    }
    free(times);
    amsph_grid_free(&g, b);
    amsph_particles_free(&p);
    amsph_host_free(&host);
    return status;
}

#if defined(__clang__)
#define COMPILER "clang " __clang_version__
#elif defined(__GNUC__)
#define COMPILER "gcc " __VERSION__
#else
#define COMPILER "unknown compiler"
#endif
#if AMSPH_DOUBLE
#define AMSPH_PRECISION "double"
#else
#define AMSPH_PRECISION "float"
#endif

const char *amsph_bench_build(void)
{
    return COMPILER ", " AMSPH_PRECISION;
}

/* Particles of the case's scene (built on the host and counted). */
static int count_particles(const amsph_case *c, long long *n)
{
    amsph_host_particles h;
    const int status = amsph_scene_build(c, &h);
    *n = h.n;
    amsph_host_free(&h);
    return status;
}

/* The case at a spacing that gives about `target` particles: dx scaled by
 * (n / target)^(1/dim) (amsph_case_set_spacing), repeated while the count is more
 * than 2% off (walls and block edges grow more slowly than the volume). */
static int scale_to_count(const amsph_case *c, long long target, amsph_case *scaled)
{
    *scaled = *c;
    long long n = 0;
    AMSPH_CHECK(count_particles(scaled, &n));
    for (int k = 0; k < 4 && fabs((double)n / (double)target - 1.0) > 0.02; ++k) {
        const double factor = pow((double)n / (double)target, 1.0 / scaled->dim);
        amsph_case_set_spacing(scaled, scaled->dx * factor);
        if (count_particles(scaled, &n)) {
            char message[1024];
            snprintf(message, sizeof message, "%s", amsph_last_error());
            return amsph_fail("%s (the case scaled to dx = %g m for %lld particles)", message, scaled->dx,
                              target);
        }
    }
    return 0;
}

/* `count` steps of the stable size, as amsph_sim_advance takes them. */
static int take_steps(amsph_sim *s, int count)
{
    for (int k = 0; k < count; ++k) {
        double dt = 0.0;
        AMSPH_CHECK(amsph_sim_stable_dt(s, &dt));
        AMSPH_CHECK(amsph_sim_step(s, dt));
    }
    return amsph_sync(s->backend);
}

/* One particle count's measurements. */
typedef struct {
    long long particles;
    double dx;
    double seconds;          /* the steps with the timers off */
    double timed_seconds;    /* the same number of steps with the timers on */
    double device_bytes;     /* every live buffer of the backend */
    amsph_timers timers;     /* of the timed steps */
    amsph_kernel_profile profile; /* o->kernels: of `steps` more, each launch waited for */
    double profiled_seconds;      /* those steps' wall time */
} measurement;

/* `steps` steps with each kernel timed (amsph_kernel_profile) into m. */
static int profile_kernels(amsph_sim *s, int steps, measurement *m)
{
    s->backend->profile = &m->profile;
    const double start = amsph_wall_seconds();
    const int status = take_steps(s, steps);
    m->profiled_seconds = amsph_wall_seconds() - start;
    s->backend->profile = NULL;
    return status;
}

static int measure(amsph_backend *b, const amsph_case *c, const amsph_bench_options *o, measurement *m)
{
    amsph_sim s;
    AMSPH_CHECK(amsph_sim_create(c, b, &s));
    m->particles = s.particles.n;
    m->dx = c->dx;
    m->device_bytes = (double)b->allocated;
    int status = take_steps(&s, o->warmup);
    double start = amsph_wall_seconds();
    if (!status)
        status = take_steps(&s, o->steps);
    m->seconds = amsph_wall_seconds() - start;
    amsph_timers_reset(&s.timers, 1);
    start = amsph_wall_seconds();
    if (!status)
        status = take_steps(&s, o->steps);
    m->timed_seconds = amsph_wall_seconds() - start;
    m->timers = s.timers;
    amsph_timers_reset(&s.timers, 0);
    if (!status && o->kernels)
        status = profile_kernels(&s, o->steps, m);
    amsph_sim_free(&s);
    return status;
}

static void print_header(const amsph_case *c, amsph_backend *b, const amsph_bench_options *o, FILE *out)
{
    fprintf(out, "%s, %dD: %s; %s; %d warm-up and %d timed steps (twice: timers off, then on)\n\n", c->path,
            c->dim, b->description, amsph_bench_build(), o->warmup, o->steps);
    fprintf(out, "| particles | ms/step | particle-steps/s | device bytes/particle |");
    for (int k = 1; k < AMSPH_PHASE_COUNT; ++k)
        fprintf(out, " %s |", amsph_phase_names[k]);
    fprintf(out, " other |\n|---|---|---|---|");
    for (int k = 1; k <= AMSPH_PHASE_COUNT; ++k)
        fprintf(out, "---|");
    fputc('\n', out);
}

/* A Markdown row: the step's time, then each phase's ms per step from the
 * timed steps ("-": not in this case) and the rest of the timed step. */
static void print_row(const measurement *m, int steps, FILE *out)
{
    const double ms = 1e3 * m->seconds / steps;
    fprintf(out, "| %lld | %.3g | %.3g | %.0f |", m->particles, ms, (double)m->particles / (1e-3 * ms),
            m->device_bytes / (double)m->particles);
    double phases = 0.0;
    for (int k = 1; k < AMSPH_PHASE_COUNT; ++k) {
        phases += m->timers.seconds[k];
        if (m->timers.used[k])
            fprintf(out, " %.3g |", 1e3 * m->timers.seconds[k] / steps);
        else
            fprintf(out, " - |");
    }
    fprintf(out, " %.3g |\n", 1e3 * (m->timed_seconds - phases) / steps);
    fflush(out);
}

static void print_csv_header(FILE *csv)
{
    fprintf(csv, "case,dim,backend,build,particles,dx,steps,ms_per_step,particle_steps_per_s,"
                 "device_bytes_per_particle,timed_ms_per_step");
    for (int k = 1; k < AMSPH_PHASE_COUNT; ++k)
        fprintf(csv, ",ms_%s", amsph_phase_names[k]);
    fputc('\n', csv);
}

/* A CSV row; a phase not in the case is an empty field. */
static void print_csv_row(const amsph_case *c, amsph_backend *b, const measurement *m, int steps, FILE *csv)
{
    const double ms = 1e3 * m->seconds / steps;
    fprintf(csv, "%s,%d,\"%s\",\"%s\",%lld,%.6g,%d,%.6g,%.6g,%.6g,%.6g", c->path, c->dim, b->description,
            amsph_bench_build(), m->particles, m->dx, steps, ms, (double)m->particles / (1e-3 * ms),
            m->device_bytes / (double)m->particles, 1e3 * m->timed_seconds / steps);
    for (int k = 1; k < AMSPH_PHASE_COUNT; ++k) {
        if (m->timers.used[k])
            fprintf(csv, ",%.6g", 1e3 * m->timers.seconds[k] / steps);
        else
            fputc(',', csv);
    }
    fputc('\n', csv);
    fflush(csv);
}

static int by_kernel_seconds(const void *pa, const void *pb)
{
    const double a = ((const amsph_kernel_time *)pa)->seconds, b = ((const amsph_kernel_time *)pb)->seconds;
    return (a < b) - (a > b);
}

/* The kernels of one count's profiled steps, the slowest first. */
static void print_kernels(const measurement *m, int steps, FILE *out)
{
    amsph_kernel_profile p = m->profile;
    qsort(p.kernel, (size_t)p.count, sizeof p.kernel[0], by_kernel_seconds);
    double total = 0.0;
    for (int k = 0; k < p.count; ++k)
        total += p.kernel[k].seconds;
    fprintf(out, "\nkernels at %lld particles, each launch waited for: the steps took %.3g ms each, "
                 "the kernels %.3g ms of it\n\n| kernel | launches/step | ms/step | share of the kernels |\n"
                 "|---|---|---|---|\n",
            m->particles, 1e3 * m->profiled_seconds / steps, 1e3 * total / steps);
    for (int k = 0; k < p.count; ++k)
        fprintf(out, "| %s | %.3g | %.3g | %.1f%% |\n", p.kernel[k].name, (double)p.kernel[k].launches / steps,
                1e3 * p.kernel[k].seconds / steps, total > 0.0 ? 100.0 * p.kernel[k].seconds / total : 0.0);
    if (p.untracked)
        fprintf(out, "(%d launches past the table's %d kernels not charged)\n", p.untracked, AMSPH_PROFILE_KERNELS);
}

/* Least-squares slope of log(time per step) against log(particles). */
static double growth_exponent(const measurement *m, int count)
{
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (int k = 0; k < count; ++k) {
        const double x = log((double)m[k].particles), y = log(m[k].seconds);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

int amsph_bench_throughput(amsph_backend *b, const amsph_case *c, const amsph_bench_options *o, FILE *out)
{
    const int counts = o->n_particles > 0 ? o->n_particles : 1;
    measurement *m = calloc((size_t)counts, sizeof *m);
    if (!m)
        return amsph_fail("out of host memory");
    print_header(c, b, o, out);
    if (o->csv)
        print_csv_header(o->csv);
    int status = 0;
    for (int k = 0; k < counts && !status; ++k) {
        amsph_case scaled = *c;
        if (o->n_particles > 0)
            status = scale_to_count(c, o->particles[k], &scaled);
        if (!status)
            status = measure(b, &scaled, o, &m[k]);
        if (!status)
            print_row(&m[k], o->steps, out);
        if (!status && o->csv)
            print_csv_row(&scaled, b, &m[k], o->steps, o->csv);
    }
    if (!status && counts > 1 && m[counts - 1].particles != m[0].particles)
        fprintf(out, "\ncost growth: time per step ~ particles^%.2f (least squares over %d counts)\n",
                growth_exponent(m, counts), counts);
    for (int k = 0; k < counts && !status && o->kernels; ++k)
        print_kernels(&m[k], o->steps, out);
    free(m);
    return status;
}
