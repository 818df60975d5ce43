#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <time.h>

#include "error.h"
#include "grid.h"
#include "particles.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

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
    const double t0 = now();
    AMSPH_CHECK(amsph_grid_sort(g, p));
    AMSPH_CHECK(amsph_sync(p->backend));
    *seconds = now() - t0;
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
