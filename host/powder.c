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

/* A rolling grain's centre moves on the circle
 *   p(phi) = m + rho (cos phi e1 + sin phi e2),  phi from `from` to `to`:
 * on one grain j, m = c_j, rho = r + r_j, e1 = e_up, e2 the lateral unit
 * vector towards the grain, phi its angle from the vertical, up to the
 * side of j (pi/2, where it falls off); on two grains (3D), the circle of
 * the points that touch both, from the grain's place (phi = 0) down to its
 * lowest point. */
typedef struct {
    double m[3], e1[3], e2[3];
    double rho, from, to;
} circle;

static void circle_point(const circle *w, double phi, double p[3])
{
    for (int k = 0; k < 3; ++k)
        p[k] = w->m[k] + w->rho * (cos(phi) * w->e1[k] + sin(phi) * w->e2[k]);
}

static double distance(const double a[3], const double b[3])
{
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
        d2 += (a[k] - b[k]) * (a[k] - b[k]);
    return sqrt(d2);
}

/* Unit vector (p - c) / |p - c|. */
static void unit_from(const double c[3], const double p[3], double n[3])
{
    const double d = distance(p, c);
    for (int k = 0; k < 3; ++k)
        n[k] = (p[k] - c[k]) / d;
}

/* The roll of the grain at p on grain j alone; false when there is none:
 * p right above j (balanced on top) or at or below its side. */
static int roll_on_one(const settling *s, int j, const double p[3], double r, circle *w)
{
    const double *c = s->grain[j].centre;
    const double lateral = sqrt(lateral_distance2(s, p, c));
    memset(w, 0, sizeof *w);
    memcpy(w->m, c, sizeof w->m);
    w->rho = r + s->grain[j].radius;
    w->e1[s->up] = 1.0;
    for (int k = 0; k < s->dim; ++k)
        if (k != s->up && lateral > 0.0)
            w->e2[k] = (p[k] - c[k]) / lateral;
    w->from = atan2(lateral, p[s->up] - c[s->up]);
    w->to = 0.5 * PI;
    return lateral > CONTACT_TOL * w->rho && w->from < w->to;
}

/* The roll of the grain at p on grains j and k together (3D), downhill
 * along their circle; false at its lowest point. */
static int roll_on_two(const settling *s, int j, int k, const double p[3], double r, circle *w)
{
    const double *cj = s->grain[j].centre, *ck = s->grain[k].centre;
    const double d = distance(cj, ck), rj = r + s->grain[j].radius, rk = r + s->grain[k].radius;
    const double along = (d * d + rj * rj - rk * rk) / (2.0 * d);
    double a[3];
    for (int q = 0; q < 3; ++q) {
        a[q] = (ck[q] - cj[q]) / d;
        w->m[q] = cj[q] + along * a[q];
    }
    w->rho = sqrt(fmax(rj * rj - along * along, 0.0));
    unit_from(w->m, p, w->e1);
    /* e2 = a x e1, turned downhill */
    w->e2[0] = a[1] * w->e1[2] - a[2] * w->e1[1];
    w->e2[1] = a[2] * w->e1[0] - a[0] * w->e1[2];
    w->e2[2] = a[0] * w->e1[1] - a[1] * w->e1[0];
    const double sign = w->e2[s->up] > 0.0 ? -1.0 : 1.0;
    for (int q = 0; q < 3; ++q)
        w->e2[q] *= sign;
    w->from = 0.0;
    w->to = atan2(-w->e2[s->up], -w->e1[s->up]); /* where the height m + rho (cos e1 + sin e2) . e_up is least */
    return w->e2[s->up] < -CONTACT_TOL && w->to > CONTACT_TOL;
}

/* First angle in (from, to] at which A sin phi + B cos phi = C, or
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

/* The first contact of a grain of radius r rolling on circle w (supports
 * `on`, `count` of them): the substrate, a side wall of the region, a grain
 * (*hit = its index) or none before the circle's end (*hit = NO_CONTACT,
 * returns `to`). A grain it touches at the start counts at once when the
 * roll goes into it, and only where it meets it again when the roll takes
 * it away. Each contact reads A sin phi + B cos phi = C: for the plane
 * x_k = b, rho (e2_k sin + e1_k cos) = b - m_k; for grain q, with
 * D = m - c_q, 2 rho (D.e2 sin + D.e1 cos) = (r + r_q)^2 - |D|^2 - rho^2. */
static double roll_contact(const settling *s, const circle *w, const int *on, int count, double r, int *hit)
{
    double first = w->to;
    *hit = NO_CONTACT;
    const double floor_phi = first_root(w->rho * w->e2[s->up], w->rho * w->e1[s->up],
                                        s->floor + r - w->m[s->up], w->from, first, 0);
    if (floor_phi <= first) {
        first = floor_phi;
        *hit = SUBSTRATE;
    }
    for (int k = 0; k < s->dim; ++k) {
        if (k == s->up)
            continue;
        for (int side = 0; side < 2; ++side) {
            const double wall = side ? s->hi[k] - r : s->lo[k] + r;
            const double phi = first_root(w->rho * w->e2[k], w->rho * w->e1[k], wall - w->m[k], w->from, first, 0);
            if (phi < first) {
                first = phi;
                *hit = SIDE_WALL;
            }
        }
    }
    double p[3];
    circle_point(w, w->from, p);
    for (int q = 0; q < s->n; ++q) {
        const amsph_grain *g = &s->grain[q];
        const double touch = r + g->radius;
        int support = 0;
        for (int i = 0; i < count; ++i)
            support |= on[i] == q;
        double D[3];
        for (int k = 0; k < 3; ++k)
            D[k] = w->m[k] - g->centre[k];
        if (support || dot(D, D) >= (w->rho + touch) * (w->rho + touch))
            continue;
        const double A = dot(D, w->e2), B = dot(D, w->e1);
        const int touching = fabs(distance(p, g->centre) - touch) <= 1e3 * CONTACT_TOL * touch;
        if (touching && A * cos(w->from) - B * sin(w->from) <= 0.0) {
            first = w->from; /* touching and rolling into it: stopped here */
            *hit = q;
            continue;
        }
        const double phi = first_root(A, B, (touch * touch - dot(D, D) - w->rho * w->rho) / (2.0 * w->rho),
                                      w->from, first, touching);
        if (phi < first) {
            first = phi;
            *hit = q;
        }
    }
    return first;
}

/* The forces of supports `on` (count of them, each pushing along its
 * normal n_i from its centre to p) that hold up a grain at p: lambda with
 * sum lambda_i n_i the part of e_up the normals span (least squares,
 * G lambda = b with G_ij = n_i . n_j, b_i = n_i . e_up, by Cramer's rule).
 * Returns the support with the most negative force, or -1 when all push. */
static int pulling_support(const settling *s, const int *on, int count, const double p[3])
{
    double n[3][3], G[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, b[3] = {0, 0, 0};
    for (int i = 0; i < count; ++i) {
        unit_from(s->grain[on[i]].centre, p, n[i]);
        b[i] = n[i][s->up];
    }
    for (int i = 0; i < count; ++i)
        for (int j = 0; j < count; ++j)
            G[i][j] = dot(n[i], n[j]);
    const double det = G[0][0] * (G[1][1] * G[2][2] - G[1][2] * G[2][1]) -
                       G[0][1] * (G[1][0] * G[2][2] - G[1][2] * G[2][0]) +
                       G[0][2] * (G[1][0] * G[2][1] - G[1][1] * G[2][0]);
    int worst = -1;
    double least = 0.0;
    for (int i = 0; i < count; ++i) {
        double M[3][3];
        memcpy(M, G, sizeof M);
        for (int j = 0; j < 3; ++j)
            M[j][i] = b[j];
        const double lambda = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                               M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                               M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) / det;
        if (lambda < least) {
            least = lambda;
            worst = i;
        }
    }
    return worst;
}

/* Drops a grain of radius r at lateral position p and lets it settle
 * (header); p becomes its resting centre. False when it does not come to
 * rest within MAX_EVENTS contacts. The grains it rests on are `on`: none
 * (falling), one (rolling on it), two (2D: resting; 3D: rolling on both
 * unless at the bottom of their circle), three (3D: resting when all push). */
static int settle(const settling *s, double p[3], double r)
{
    int on[3], count = 0, skip = -1;
    for (int event = 0; event < MAX_EVENTS; ++event) {
        if (count == 0) {
            int hit;
            p[s->up] = fall(s, p, r, skip, &hit);
            if (hit == SUBSTRATE)
                return 1;
            on[count++] = hit;
            continue;
        }
        const int pulling = count > 1 ? pulling_support(s, on, count, p) : -1;
        if (pulling >= 0) { /* it leaves that support */
            on[pulling] = on[--count];
            continue;
        }
        if (count == s->dim)
            return 1; /* held by dim supports that all push */
        circle w;
        const int rolls = count == 1 ? roll_on_one(s, on[0], p, r, &w) : roll_on_two(s, on[0], on[1], p, r, &w);
        if (!rolls) {
            if (count == 2 || w.from < 0.5 * PI)
                return 1; /* at the bottom of the circle of two, or on top of one */
            skip = on[0]; /* at or below its support's side: falls */
            count = 0;
            continue;
        }
        int next;
        const double phi = roll_contact(s, &w, on, count, r, &next);
        circle_point(&w, phi, p);
        if (next == SUBSTRATE || next == SIDE_WALL)
            return 1;
        if (next >= 0)
            on[count++] = next;
        else if (count == 1) { /* past the side of its support: falls again */
            skip = on[0];
            count = 0;
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

int amsph_powder_grain_at(const amsph_powder *bed, const double x[3])
{
    for (int i = 0; i < bed->n; ++i) {
        const amsph_grain *g = &bed->grain[i];
        double d2 = 0.0;
        for (int k = 0; k < bed->dim; ++k)
            d2 += (x[k] - g->centre[k]) * (x[k] - g->centre[k]);
        if (d2 < g->radius * g->radius)
            return i;
    }
    return -1;
}

int amsph_powder_contains(const amsph_powder *bed, const double x[3])
{
    return amsph_powder_grain_at(bed, x) >= 0;
}
