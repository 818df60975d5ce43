#include "powder.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"

#define PI 3.14159265358979323846
#define MISSES 200       /* failed drops in a row that end the deposition */
#define MAX_EVENTS 1000  /* contacts one drop may go through before it is given up */
#define CONTACT_TOL 1e-9 /* relative slack of a contact */

/* ---- random numbers: splitmix64 (Steele, Lea & Flood 2014) ---------------- */

typedef struct {
    uint64_t state;
} random_stream;

static uint64_t next_bits(random_stream *r)
{
    uint64_t z = (r->state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1), 53 random bits. */
static double uniform(random_stream *r)
{
    return (double)(next_bits(r) >> 11) * 0x1.0p-53;
}

/* Standard normal (Box-Muller). */
static double normal(random_stream *r)
{
    const double u = 1.0 - uniform(r), v = uniform(r);
    return sqrt(-2.0 * log(u)) * cos(2.0 * PI * v);
}

/* ---- radii ---------------------------------------------------------------- */

double amsph_powder_smallest_radius(const amsph_geometry *g)
{
    switch (g->distribution) {
    case AMSPH_POWDER_LOGNORMAL:
        return g->grain_radius_min;
    case AMSPH_POWDER_MIXED:
        return g->small_fraction > 0.0 ? g->small_radius : g->grain_radius;
    case AMSPH_POWDER_REGULAR:
        break;
    }
    return g->grain_radius;
}

/* A radius of the distribution: log-normal by rejection of the draws
 * outside [grain_radius_min, grain_radius_max]. */
static double draw_radius(const amsph_geometry *g, random_stream *r)
{
    if (g->distribution == AMSPH_POWDER_MIXED)
        return uniform(r) < g->small_fraction ? g->small_radius : g->grain_radius;
    for (;;) {
        const double radius = g->grain_radius * exp(g->log_sd * normal(r));
        if (radius >= g->grain_radius_min && radius <= g->grain_radius_max)
            return radius;
    }
}

/* ---- geometry ------------------------------------------------------------- */

/* What a settling grain meets, other than a grain (>= 0: its index). */
enum { NO_CONTACT = -1, SUBSTRATE = -2, SIDE_WALL = -3 };

/* The bed settles along -up, up = y (2D) or z (3D). */
typedef struct {
    int dim, up;
    double floor;           /* height of the substrate, m */
    const double *lo, *hi;  /* the region's corners: its sides are walls */
    const amsph_grain *grain;
    int n;
} settling;

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Squared distance of a and b across `up`. */
static double lateral_distance2(const settling *s, const double a[3], const double b[3])
{
    double d2 = 0.0;
    for (int k = 0; k < s->dim; ++k)
        if (k != s->up)
            d2 += (a[k] - b[k]) * (a[k] - b[k]);
    return d2;
}

/* A grain of radius r falling straight down from p: the height of its
 * centre at the first contact (the substrate, or grain *hit). Grain
 * `skip` (the one it just rolled off, level with it) is passed over. */
static double fall(const settling *s, const double p[3], double r, int skip, int *hit)
{
    double height = s->floor + r;
    *hit = SUBSTRATE;
    for (int j = 0; j < s->n; ++j) {
        const amsph_grain *g = &s->grain[j];
        const double reach = r + g->radius, d2 = lateral_distance2(s, p, g->centre);
        if (j == skip || d2 >= reach * reach)
            continue;
        const double touch = g->centre[s->up] + sqrt(reach * reach - d2);
        if (touch > height && touch <= p[s->up] + CONTACT_TOL * reach) {
            height = touch;
            *hit = j;
        }
    }
    return height;
}

/* Rolling on grain j: the centre moves on the circle p(theta) = c_j +
 * R (sin theta u + cos theta e_up), R = r + r_j, theta from the vertical,
 * u the unit vector across `up` towards the grain. */
typedef struct {
    int on;          /* the grain rolled on */
    double u[3];     /* lateral unit vector */
    double reach;    /* R */
    double theta;    /* current angle */
} roll;

static void roll_position(const settling *s, const roll *w, double theta, double p[3])
{
    const double *c = s->grain[w->on].centre;
    for (int k = 0; k < 3; ++k)
        p[k] = c[k] + w->reach * sin(theta) * w->u[k];
    p[s->up] += w->reach * cos(theta);
}

/* The roll on grain j of the grain at p; false when p sits on top of j's
 * axis (no downhill direction). */
static int start_roll(const settling *s, int j, const double p[3], double r, roll *w)
{
    const double *c = s->grain[j].centre;
    const double lateral = sqrt(lateral_distance2(s, p, c));
    w->on = j;
    w->reach = r + s->grain[j].radius;
    memset(w->u, 0, sizeof w->u);
    if (lateral <= CONTACT_TOL * w->reach)
        return 0;
    for (int k = 0; k < s->dim; ++k)
        if (k != s->up)
            w->u[k] = (p[k] - c[k]) / lateral;
    w->theta = atan2(lateral, p[s->up] - c[s->up]);
    return 1;
}

/* First angle in (from, to] at which A sin theta + B cos theta = C, or
 * INFINITY; `leaving`: the root nearest `from` is the contact the grain is
 * leaving there, and only the other one counts. */
static double first_root(double A, double B, double C, double from, double to, int leaving)
{
    const double rho = sqrt(A * A + B * B);
    if (rho == 0.0 || fabs(C) > rho)
        return INFINITY;
    const double phi = atan2(A, B), half = acos(C / rho);
    double roots[6];
    int nearest = 0;
    for (int i = 0; i < 6; ++i) {
        roots[i] = phi + (i % 2 ? half : -half) + 2.0 * PI * (i / 2 - 1);
        if (fabs(roots[i] - from) < fabs(roots[nearest] - from))
            nearest = i;
    }
    double best = INFINITY;
    for (int i = 0; i < 6; ++i)
        if (!(leaving && i == nearest) && roots[i] > from + 1e-12 && roots[i] <= to && roots[i] < best)
            best = roots[i];
    return best;
}

/* Whether the rolling grain (radius r) touches grain k now (the support it
 * has just left, or one it has just fallen off). */
static int in_contact(const settling *s, const roll *w, int k, double r)
{
    double p[3];
    roll_position(s, w, w->theta, p);
    const amsph_grain *g = &s->grain[k];
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a)
        d2 += (p[a] - g->centre[a]) * (p[a] - g->centre[a]);
    return fabs(sqrt(d2) - (r + g->radius)) <= 1e3 * CONTACT_TOL * (r + g->radius);
}

/* The first contact of roll w before the grain (radius r) passes its
 * support's side (theta = pi/2): the substrate, a side wall of the region,
 * a grain (*hit = its index) or none (returns pi/2). For grain k, with
 * d = c_j - c_k, |p(theta) - c_k| = r + r_k reads
 *   2 R (d.u sin theta + d.e cos theta) = (r + r_k)^2 - |d|^2 - R^2. */
static double roll_contact(const settling *s, const roll *w, double r, int *hit)
{
    const double *c = s->grain[w->on].centre;
    double first = 0.5 * PI;
    *hit = NO_CONTACT;
    const double level = (s->floor + r - c[s->up]) / w->reach;
    if (level >= -1.0 && level <= 1.0 && acos(level) > w->theta && acos(level) <= first) {
        first = acos(level);
        *hit = SUBSTRATE;
    }
    for (int k = 0; k < s->dim; ++k) {
        if (w->u[k] == 0.0)
            continue;
        const double wall = w->u[k] > 0.0 ? s->hi[k] - r : s->lo[k] + r;
        const double along = (wall - c[k]) / (w->reach * w->u[k]);
        if (along >= 0.0 && along <= 1.0 && asin(along) > w->theta && asin(along) < first) {
            first = asin(along);
            *hit = SIDE_WALL;
        }
    }
    double e[3] = {0.0, 0.0, 0.0};
    e[s->up] = 1.0;
    for (int k = 0; k < s->n; ++k) {
        const amsph_grain *g = &s->grain[k];
        double d[3];
        for (int a = 0; a < 3; ++a)
            d[a] = c[a] - g->centre[a];
        const double touch = r + g->radius;
        if (k == w->on || dot(d, d) >= (w->reach + touch) * (w->reach + touch))
            continue;
        const double A = dot(d, w->u), B = dot(d, e);
        const int touching = in_contact(s, w, k, r);
        if (touching && A * cos(w->theta) - B * sin(w->theta) <= 0.0) {
            first = w->theta; /* touching and rolling into it: stopped here */
            *hit = k;
            continue;
        }
        const double theta = first_root(A, B, (touch * touch - dot(d, d) - w->reach * w->reach) / (2.0 * w->reach),
                                        w->theta, first, touching);
        if (theta < first) {
            first = theta;
            *hit = k;
        }
    }
    return first;
}

/* Drops a grain of radius r at lateral position p and lets it settle;
 * p becomes its resting centre. False when it does not come to rest. */
static int settle(const settling *s, double p[3], double r)
{
    int skip = -1;
    for (int event = 0; event < MAX_EVENTS; ++event) {
        int hit;
        p[s->up] = fall(s, p, r, skip, &hit);
        if (hit == SUBSTRATE)
            return 1;
        roll w;
        if (!start_roll(s, hit, p, r, &w))
            return 1; /* balanced on top of a grain */
        for (; event < MAX_EVENTS; ++event) {
            int next;
            const double theta = roll_contact(s, &w, r, &next);
            roll_position(s, &w, theta, p);
            if (next == SUBSTRATE || next == SIDE_WALL)
                return 1; /* rolled down onto the substrate, or against a side */
            if (next == NO_CONTACT) {
                skip = w.on; /* past the side of its support: falls again */
                break;
            }
            /* On two grains: it goes on rolling on the second only if
             * that takes it away from the first. */
            roll v;
            if (!start_roll(s, next, p, r, &v) || v.theta >= 0.5 * PI)
                return 1; /* on top of it, or wedged against its side */
            double ahead[3], away[3];
            roll_position(s, &v, v.theta + 1e-6, ahead);
            for (int k = 0; k < 3; ++k) {
                away[k] = p[k] - s->grain[w.on].centre[k];
                ahead[k] -= p[k];
            }
            if (dot(ahead, away) <= 0.0)
                return 1;
            w = v;
        }
    }
    return 0;
}

/* Whether a grain at p of radius r lies inside the region of g. */
static int inside_region(const amsph_geometry *g, int dim, const double p[3], double r)
{
    for (int k = 0; k < dim; ++k)
        if (p[k] - r < g->min[k] - CONTACT_TOL * r || p[k] + r > g->max[k] + CONTACT_TOL * r)
            return 0;
    return 1;
}

static int add_grain(amsph_powder *bed, int *capacity, const double p[3], double r)
{
    if (bed->n == *capacity) {
        const int grown = *capacity ? 2 * *capacity : 64;
        amsph_grain *more = realloc(bed->grain, (size_t)grown * sizeof *more);
        if (!more)
            return amsph_fail("out of host memory for %d powder grains", grown);
        bed->grain = more;
        *capacity = grown;
    }
    amsph_grain *g = &bed->grain[bed->n++];
    memcpy(g->centre, p, sizeof g->centre);
    g->radius = r;
    return 0;
}

/* Touching grains of grain_radius on a square array from the lower corner. */
static int deposit_regular(const amsph_geometry *g, int dim, amsph_powder *bed)
{
    const double r = g->grain_radius;
    int count[3] = {1, 1, 1}, capacity = 0;
    for (int k = 0; k < dim; ++k)
        count[k] = (int)floor((g->max[k] - g->min[k]) / (2.0 * r) * (1.0 + CONTACT_TOL));
    for (int i = 0; i < count[0] * count[1] * count[2]; ++i) {
        double p[3] = {0.0, 0.0, 0.0};
        for (int k = 0, rest = i; k < dim; rest /= count[k], ++k)
            p[k] = g->min[k] + r * (2 * (rest % count[k]) + 1);
        AMSPH_CHECK(add_grain(bed, &capacity, p, r));
    }
    return 0;
}

/* Sequential deposition until MISSES drops in a row fail (header). */
static int deposit_random(const amsph_geometry *g, int dim, amsph_powder *bed)
{
    random_stream stream = {(uint64_t)g->seed};
    settling s = {.dim = dim, .up = dim - 1, .floor = g->min[dim - 1], .lo = g->min, .hi = g->max};
    int capacity = 0;
    for (int misses = 0; misses < MISSES;) {
        const double r = draw_radius(g, &stream);
        double p[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < dim - 1; ++k)
            p[k] = g->min[k] + r + (g->max[k] - g->min[k] - 2.0 * r) * uniform(&stream);
        p[s.up] = INFINITY;
        s.grain = bed->grain;
        s.n = bed->n;
        if (settle(&s, p, r) && inside_region(g, dim, p, r)) {
            AMSPH_CHECK(add_grain(bed, &capacity, p, r));
            misses = 0;
        } else {
            ++misses;
        }
    }
    return 0;
}

int amsph_powder_deposit(const amsph_geometry *g, int dim, amsph_powder *bed)
{
    memset(bed, 0, sizeof *bed);
    bed->dim = dim;
    const int status = g->distribution == AMSPH_POWDER_REGULAR ? deposit_regular(g, dim, bed)
                                                               : deposit_random(g, dim, bed);
    if (status)
        amsph_powder_free(bed);
    return status;
}

void amsph_powder_free(amsph_powder *bed)
{
    free(bed->grain);
    memset(bed, 0, sizeof *bed);
}

double amsph_powder_packing_fraction(const amsph_powder *bed, const amsph_geometry *g)
{
    double grains = 0.0, region = 1.0;
    for (int i = 0; i < bed->n; ++i)
        grains += bed->dim == 2 ? PI * pow(bed->grain[i].radius, 2)
                                : 4.0 / 3.0 * PI * pow(bed->grain[i].radius, 3);
    for (int k = 0; k < bed->dim; ++k)
        region *= g->max[k] - g->min[k];
    return grains / region;
}

int amsph_powder_contains(const amsph_powder *bed, const double x[3])
{
    for (int i = 0; i < bed->n; ++i) {
        const amsph_grain *g = &bed->grain[i];
        double d2 = 0.0;
        for (int k = 0; k < bed->dim; ++k)
            d2 += (x[k] - g->centre[k]) * (x[k] - g->centre[k]);
        if (d2 < g->radius * g->radius)
            return 1;
    }
    return 0;
}
