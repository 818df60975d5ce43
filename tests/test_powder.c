/* Powder beds (host/powder.h), checked against geometry and statistics
 * computed here, not against the program's own figures:
 *   - a seed gives the same bed every time, another seed another bed;
 *   - no two grains overlap, every grain lies in the region;
 *   - every grain rests: on the substrate, or (2D) on two supports (grains
 *     or a side wall) one on each side of its centre, or (3D) on three
 *     grains, or on a side wall and one or two grains;
 *   - radii lie within the distribution's bounds, and the sample of a
 *     log-normal bed has the mean and standard deviation of ln r of the
 *     truncated normal law within 4 standard errors; a mixed bed has the
 *     requested share of small grains within 4 standard errors;
 *   - the area fraction of a monodisperse 2D bed, measured by counting
 *     points of a fine lattice inside grains in a window away from the
 *     walls, the substrate and the top, lies between 0.78 (random
 *     deposition with rolling gives about 0.82) and the densest packing
 *     of discs, pi / (2 sqrt 3) = 0.9069; in 3D below the densest packing
 *     of spheres, pi / (3 sqrt 2) = 0.7405, and above 0.55 (Visscher &
 *     Bolsterli 1972 found 0.58 for this deposition);
 *   - the regular bed is Russell's row of touching grains;
 *   - the scene fills the grains, and only them, with lattice particles. */
#include <math.h>

#include "powder.h"
#include "scene.h"
#include "testing.h"

#define TOL 1e-6 /* relative slack of a contact */

/* A bed of 40 x 40 radii (2D; 3D: 16 x 16 x 16) of grains of radius about 1. */
static amsph_geometry bed_geometry(int dim, amsph_powder_distribution distribution, int seed)
{
    amsph_geometry g = {.shape = AMSPH_SHAPE_POWDER_BED, .distribution = distribution, .seed = seed};
    g.grain_radius = 1.0;
    g.log_sd = 0.2;
    g.grain_radius_min = 0.7;
    g.grain_radius_max = 1.4;
    g.small_radius = 0.5;
    g.small_fraction = 0.3;
    for (int k = 0; k < dim; ++k)
        g.max[k] = dim == 2 ? 40.0 : 16.0;
    return g;
}

static double distance(const amsph_grain *a, const amsph_grain *b)
{
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
        d2 += (a->centre[k] - b->centre[k]) * (a->centre[k] - b->centre[k]);
    return sqrt(d2);
}

static void test_reproducible(void)
{
    amsph_geometry g = bed_geometry(2, AMSPH_POWDER_LOGNORMAL, 7);
    amsph_powder a, b, other;
    CHECK_OK(amsph_powder_deposit(&g, 2, &a));
    CHECK_OK(amsph_powder_deposit(&g, 2, &b));
    g.seed = 8;
    CHECK_OK(amsph_powder_deposit(&g, 2, &other));
    CHECK(a.n == b.n && memcmp(a.grain, b.grain, (size_t)a.n * sizeof *a.grain) == 0,
          "seed 7 gave two different beds (%d and %d grains)", a.n, b.n);
    int same = other.n == a.n;
    for (int i = 0; same && i < a.n; ++i)
        same = distance(&a.grain[i], &other.grain[i]) == 0.0;
    CHECK(!same, "seeds 7 and 8 gave the same bed");
    amsph_powder_free(&a);
    amsph_powder_free(&b);
    amsph_powder_free(&other);
}

/* Supports of grain i: the substrate, side walls and the touching grains
 * laid before it; in 2D those on its left and right. */
typedef struct {
    int substrate, walls, count, left, right;
} supports;

static supports supports_of(const amsph_powder *bed, const amsph_geometry *g, int i)
{
    const amsph_grain *a = &bed->grain[i];
    const int dim = bed->dim, up = dim - 1;
    supports s = {0};
    s.substrate = fabs(a->centre[up] - a->radius - g->min[up]) <= TOL * a->radius;
    for (int k = 0; k < up; ++k) {
        const int low = fabs(a->centre[k] - a->radius - g->min[k]) <= TOL * a->radius;
        const int high = fabs(a->centre[k] + a->radius - g->max[k]) <= TOL * a->radius;
        s.walls += low + high;
        s.count += low + high;
        s.left += low;
        s.right += high;
    }
    for (int j = 0; j < i; ++j) {
        const amsph_grain *b = &bed->grain[j];
        const double reach = a->radius + b->radius;
        if (fabs(distance(a, b) - reach) > TOL * reach)
            continue;
        ++s.count;
        s.left += b->centre[0] <= a->centre[0];
        s.right += b->centre[0] >= a->centre[0];
    }
    return s;
}

/* No overlap, inside the region, at rest, radii in bounds. */
static void check_bed(const amsph_powder *bed, const amsph_geometry *g, const char *name)
{
    const int dim = bed->dim;
    int overlaps = 0, outside = 0, unsupported = 0, out_of_bounds = 0;
    const double lo = g->distribution == AMSPH_POWDER_LOGNORMAL ? g->grain_radius_min
                      : g->distribution == AMSPH_POWDER_MIXED ? g->small_radius
                                                              : g->grain_radius;
    const double hi = g->distribution == AMSPH_POWDER_LOGNORMAL ? g->grain_radius_max : g->grain_radius;
    for (int i = 0; i < bed->n; ++i) {
        const amsph_grain *a = &bed->grain[i];
        for (int j = 0; j < i; ++j) {
            const int overlap = distance(a, &bed->grain[j]) < (a->radius + bed->grain[j].radius) * (1.0 - TOL);
            overlaps += overlap;
            if (overlap)
                fprintf(stderr, "%s: grains %d and %d overlap by %g\n", name, i, j,
                        a->radius + bed->grain[j].radius - distance(a, &bed->grain[j]));
        }
        for (int k = 0; k < dim; ++k)
            outside += a->centre[k] - a->radius < g->min[k] - TOL || a->centre[k] + a->radius > g->max[k] + TOL;
        const supports s = supports_of(bed, g, i);
        const int rests = s.substrate || (dim == 2 ? s.left >= 1 && s.right >= 1
                                                   : s.count >= 3 || (s.walls >= 1 && s.count >= 2));
        unsupported += !rests;
        if (!rests && unsupported <= 3)
            fprintf(stderr, "%s: grain %d at (%g, %g, %g), radius %g, has %d supports (%d left, %d right)\n",
                    name, i, a->centre[0], a->centre[1], a->centre[2], a->radius, s.count, s.left, s.right);
        if (g->distribution == AMSPH_POWDER_MIXED)
            out_of_bounds += a->radius != g->small_radius && a->radius != g->grain_radius;
        else
            out_of_bounds += a->radius < lo || a->radius > hi;
    }
    CHECK(bed->n > 100, "%s: only %d grains", name, bed->n);
    CHECK(overlaps == 0, "%s: %d overlapping pairs", name, overlaps);
    CHECK(outside == 0, "%s: %d grains reach outside the region", name, outside);
    CHECK(unsupported == 0, "%s: %d of %d grains do not rest on support", name, unsupported, bed->n);
    CHECK(out_of_bounds == 0, "%s: %d radii outside the distribution", name, out_of_bounds);
}

static void test_invariants(void)
{
    static const struct {
        int dim;
        amsph_powder_distribution distribution;
        const char *name;
    } beds[] = {{2, AMSPH_POWDER_LOGNORMAL, "2D log-normal"},
                {2, AMSPH_POWDER_MIXED, "2D mixed"},
                {3, AMSPH_POWDER_LOGNORMAL, "3D log-normal"},
                {3, AMSPH_POWDER_MIXED, "3D mixed"}};
    for (size_t k = 0; k < sizeof beds / sizeof beds[0]; ++k) {
        const amsph_geometry g = bed_geometry(beds[k].dim, beds[k].distribution, 3);
        amsph_powder bed;
        CHECK_OK(amsph_powder_deposit(&g, beds[k].dim, &bed));
        check_bed(&bed, &g, beds[k].name);
        amsph_powder_free(&bed);
    }
}

static double phi(double x)
{
    return exp(-0.5 * x * x) / sqrt(2.0 * PI);
}

static double Phi(double x)
{
    return 0.5 * erfc(-x / sqrt(2.0));
}

/* Whether a grain lies in the lower 90% of the region: the draws laid
 * there are a sample of the law; at the top, where the bed fills up from
 * many failed drops, small grains fit where large ones do not. */
static int below_top(const amsph_grain *a, const amsph_geometry *g)
{
    return a->centre[1] < g->min[1] + 0.9 * (g->max[1] - g->min[1]);
}

/* ln r of a log-normal bed against the normal law N(mu, sigma) truncated to
 * [ln r_min, ln r_max]: with a, b the bounds in units of sigma from mu and
 * Z = Phi(b) - Phi(a),
 *   mean = mu + sigma (phi(a) - phi(b)) / Z,
 *   var  = sigma^2 (1 + (a phi(a) - b phi(b)) / Z - ((phi(a) - phi(b)) / Z)^2). */
static void test_lognormal_statistics(void)
{
    amsph_geometry g = bed_geometry(2, AMSPH_POWDER_LOGNORMAL, 11);
    g.max[1] = 200.0;
    amsph_powder bed;
    CHECK_OK(amsph_powder_deposit(&g, 2, &bed));
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (int i = 0; i < bed.n; ++i)
        if (below_top(&bed.grain[i], &g)) {
            const double l = log(bed.grain[i].radius);
            sum += l;
            sum2 += l * l;
            ++n;
        }
    const double mean = sum / n, sd = sqrt(sum2 / n - mean * mean);
    const double mu = log(g.grain_radius), sigma = g.log_sd;
    const double a = (log(g.grain_radius_min) - mu) / sigma, b = (log(g.grain_radius_max) - mu) / sigma;
    const double z = Phi(b) - Phi(a), shift = (phi(a) - phi(b)) / z;
    const double law_mean = mu + sigma * shift;
    const double law_sd = sigma * sqrt(1.0 + (a * phi(a) - b * phi(b)) / z - shift * shift);
    printf("log-normal bed: %d grains below the top, ln r mean %.4f (law %.4f), sd %.4f (law %.4f)\n", n,
           mean, law_mean, sd, law_sd);
    CHECK(fabs(mean - law_mean) < 4.0 * law_sd / sqrt(n), "mean of ln r %g, law %g", mean, law_mean);
    CHECK(fabs(sd - law_sd) < 4.0 * law_sd / sqrt(2.0 * n), "sd of ln r %g, law %g", sd, law_sd);
    amsph_powder_free(&bed);

    g = bed_geometry(2, AMSPH_POWDER_MIXED, 11);
    g.max[1] = 200.0;
    CHECK_OK(amsph_powder_deposit(&g, 2, &bed));
    int small = 0;
    n = 0;
    for (int i = 0; i < bed.n; ++i)
        if (below_top(&bed.grain[i], &g)) {
            small += bed.grain[i].radius == g.small_radius;
            ++n;
        }
    const double share = (double)small / n, p = g.small_fraction;
    printf("mixed bed: %d grains below the top, share of small grains %.4f (asked %.4f)\n", n, share, p);
    CHECK(fabs(share - p) < 4.0 * sqrt(p * (1.0 - p) / n), "share of small grains %g, asked %g", share, p);
    amsph_powder_free(&bed);
}

/* Fraction of the points of a lattice of spacing `step` over the window
 * [lo, hi] that lie inside a grain. */
static double window_fraction(const amsph_powder *bed, const double lo[3], const double hi[3], double step)
{
    long long inside = 0, points = 0;
    const int dim = bed->dim;
    int count[3] = {1, 1, 1};
    for (int k = 0; k < dim; ++k)
        count[k] = (int)((hi[k] - lo[k]) / step);
    for (int i = 0; i < count[0] * count[1] * count[2]; ++i) {
        double x[3] = {0.0, 0.0, 0.0};
        for (int k = 0, rest = i; k < dim; rest /= count[k], ++k)
            x[k] = lo[k] + (rest % count[k] + 0.5) * step;
        inside += amsph_powder_contains(bed, x);
        ++points;
    }
    return (double)inside / (double)points;
}

static void test_packing(void)
{
    for (int dim = 2; dim <= 3; ++dim) {
        amsph_geometry g = bed_geometry(dim, AMSPH_POWDER_MIXED, 5);
        g.small_fraction = 0.0; /* every grain of radius 1 */
        amsph_powder bed;
        CHECK_OK(amsph_powder_deposit(&g, dim, &bed));
        double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < dim; ++k) {
            lo[k] = g.min[k] + 4.0;
            hi[k] = g.max[k] - 4.0;
        }
        const double fraction = window_fraction(&bed, lo, hi, dim == 2 ? 0.05 : 0.1);
        const double densest = dim == 2 ? PI / (2.0 * sqrt(3.0)) : PI / (3.0 * sqrt(2.0));
        const double least = dim == 2 ? 0.78 : 0.55;
        printf("monodisperse %dD bed: %d grains, packing fraction %.4f of the window, %.4f of the region\n",
               dim, bed.n, fraction, amsph_powder_packing_fraction(&bed, &g));
        CHECK(fraction > least && fraction < densest, "%dD packing fraction %g outside (%g, %g)", dim,
              fraction, least, densest);
        amsph_powder_free(&bed);
    }
}

/* Russell's bed: a row of touching grains of radius 25 um on a 1.2 mm track. */
static void test_regular(void)
{
    amsph_geometry g = {.shape = AMSPH_SHAPE_POWDER_BED, .distribution = AMSPH_POWDER_REGULAR};
    g.grain_radius = 25e-6;
    g.min[0] = -0.6e-3;
    g.max[0] = 0.6e-3;
    g.max[1] = 50e-6;
    amsph_powder bed;
    CHECK_OK(amsph_powder_deposit(&g, 2, &bed));
    CHECK(bed.n == 24, "%d grains in the row, expected 24", bed.n);
    for (int i = 0; i < bed.n; ++i)
        CHECK(fabs(bed.grain[i].centre[0] - (-0.6e-3 + 25e-6 * (2 * i + 1))) < 1e-12 &&
                  fabs(bed.grain[i].centre[1] - 25e-6) < 1e-12,
              "grain %d at (%g, %g)", i, bed.grain[i].centre[0], bed.grain[i].centre[1]);
    CHECK(fabs(amsph_powder_packing_fraction(&bed, &g) - PI / 4.0) < 1e-12,
          "a row of touching discs fills pi/4 of its strip, got %g", amsph_powder_packing_fraction(&bed, &g));
    amsph_powder_free(&bed);
}

/* The scene's particles of a bed: lattice points inside grains, as many as
 * the points of the lattice that lie inside grains (counted here), none
 * outside a grain; grains under 2 dx in radius refused. */
static void test_scene(void)
{
    static const char text[] =
        "dimension: 2\n"
        "domain: {min: [0, -1.0e-4], max: [6.0e-4, 2.0e-4]}\n"
        "dx: 4.0e-6\n"
        "end_time: 1.0e-6\n"
        "output_interval: 1.0e-6\n"
        "materials:\n"
        "  - {name: steel, density: 8000}\n"
        "geometry:\n"
        "  - {shape: box, kind: solid, material: steel, min: [0, -1.0e-4], max: [6.0e-4, 0]}\n"
        "  - {shape: powder_bed, kind: solid, material: steel, min: [0, 0], max: [6.0e-4, 1.0e-4],\n"
        "     distribution: lognormal, grain_radius: 12e-6, log_sd: 0.17, grain_radius_min: 8e-6,\n"
        "     grain_radius_max: 16e-6, seed: 2}\n";
    amsph_case c;
    char err[512];
    CHECK(amsph_case_parse(text, sizeof text - 1, "bed", &c, err, sizeof err) == 0, "%s", err);
    amsph_host_particles h;
    CHECK_OK(amsph_scene_build(&c, &h));
    amsph_powder bed;
    CHECK_OK(amsph_powder_deposit(&c.geometry[1], 2, &bed));
    const int nx = 150, ny = 25; /* the bed's lattice, 6e-4 x 1e-4 at dx 4e-6 */
    int expected = nx * 25;       /* the substrate */
    for (int i = 0; i < nx * ny; ++i) {
        const double x[3] = {(i % nx + 0.5) * 4.0e-6, (i / nx + 0.5) * 4.0e-6, 0.0};
        expected += amsph_powder_contains(&bed, x);
    }
    const amsph_real *pos = amsph_host_real(&h, AMSPH_FIELD_POSITION);
    int strays = 0;
    for (int i = 0; i < h.n; ++i) {
        const double x[3] = {pos[3 * i], pos[3 * i + 1], 0.0};
        strays += x[1] > 0.0 && !amsph_powder_contains(&bed, x);
    }
    CHECK(h.n == expected, "%d particles, expected %d", h.n, expected);
    CHECK(strays == 0, "%d bed particles outside every grain", strays);
    amsph_powder_free(&bed);
    amsph_host_free(&h);

    c.dx = 5.0e-6; /* grains of 8 um at 5 um: not resolved */
    CHECK(amsph_scene_build(&c, &h) != 0 && strstr(amsph_last_error(), "not resolved"),
          "a bed of grains under 2 dx was accepted: %s", amsph_last_error());
    amsph_host_free(&h);
}

int main(void)
{
    test_reproducible();
    test_invariants();
    test_lognormal_statistics();
    test_packing();
    test_regular();
    test_scene();
    return testing_finish();
}
