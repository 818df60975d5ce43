/* Voronoi cells of 2D particle positions, the measure of particle volume of
 * Russell (2018) Sec. 4.3.1: m / rho need not be the volume a particle
 * occupies, the area of its Voronoi cell is.
 *
 * The cell of particle i is the square of half side `reach` around x_i cut
 * by the perpendicular bisector of every particle j within `reach`, keeping
 * the side of x_i (Sutherland-Hodgman clipping of a convex polygon by one
 * half-plane at a time, in coordinates relative to x_i). The result is the
 * exact Voronoi cell when all its vertices lie within reach / 2 of x_i: a
 * particle j beyond reach is then farther from every vertex v than x_i is
 * (|v - x_j| >= |x_j - x_i| - |v - x_i| > reach / 2 >= |v - x_i|), so its
 * bisector cannot cut the cell. Otherwise the cell is open (a free surface,
 * or too few particles within reach) and its area is reported as -1. */
#ifndef AMSPH_TESTS_VORONOI_H
#define AMSPH_TESTS_VORONOI_H

#include <math.h>
#include <stdlib.h>

#include "real.h"

#define VORONOI_MAX_VERTICES 128

typedef struct {
    int n;
    double x[VORONOI_MAX_VERTICES], y[VORONOI_MAX_VERTICES];
} voronoi_polygon;

/* Keeps the part of the polygon where (p - m) . d <= 0, the side of the
 * origin of the bisector of the origin and (dx, dy), m = d / 2. Returns -1
 * when the result would not fit. */
static inline int voronoi_clip(voronoi_polygon *poly, double dx, double dy)
{
    const double half = 0.5 * (dx * dx + dy * dy); /* m . d */
    voronoi_polygon out = {0};
    for (int k = 0; k < poly->n; ++k) {
        const int next = (k + 1) % poly->n;
        const double sa = poly->x[k] * dx + poly->y[k] * dy - half;
        const double sb = poly->x[next] * dx + poly->y[next] * dy - half;
        if (sa <= 0.0) {
            if (out.n == VORONOI_MAX_VERTICES)
                return -1;
            out.x[out.n] = poly->x[k];
            out.y[out.n++] = poly->y[k];
        }
        if ((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0)) {
            if (out.n == VORONOI_MAX_VERTICES)
                return -1;
            const double f = sa / (sa - sb);
            out.x[out.n] = poly->x[k] + f * (poly->x[next] - poly->x[k]);
            out.y[out.n++] = poly->y[k] + f * (poly->y[next] - poly->y[k]);
        }
    }
    *poly = out;
    return 0;
}

/* Shoelace area and the largest vertex distance from the origin. */
static inline double voronoi_area(const voronoi_polygon *poly, double *farthest)
{
    double twice = 0.0;
    *farthest = 0.0;
    for (int k = 0; k < poly->n; ++k) {
        const int next = (k + 1) % poly->n;
        twice += poly->x[k] * poly->y[next] - poly->x[next] * poly->y[k];
        *farthest = fmax(*farthest, sqrt(poly->x[k] * poly->x[k] + poly->y[k] * poly->y[k]));
    }
    return 0.5 * twice;
}

/* A square bucket grid of side `reach` over the points (x, y of a position
 * field with 3 components per point). */
typedef struct {
    double lo[2], side;
    int cells[2];
    int *start; /* cells[0] cells[1] + 1 offsets into order */
    int *order; /* point indices by bucket */
} voronoi_buckets;

static inline int voronoi_bucket_of(const voronoi_buckets *b, const amsph_real *p, int axis)
{
    const int c = (int)floor((p[axis] - b->lo[axis]) / b->side);
    return c < 0 ? 0 : c >= b->cells[axis] ? b->cells[axis] - 1 : c;
}

static inline int voronoi_bucket_index(const voronoi_buckets *b, const amsph_real *p)
{
    return voronoi_bucket_of(b, p, 0) + b->cells[0] * voronoi_bucket_of(b, p, 1);
}

static inline int voronoi_buckets_build(voronoi_buckets *b, const amsph_real *position, int n, double reach)
{
    double hi[2] = {-INFINITY, -INFINITY};
    b->lo[0] = b->lo[1] = INFINITY;
    for (int i = 0; i < n; ++i)
        for (int d = 0; d < 2; ++d) {
            b->lo[d] = fmin(b->lo[d], position[3 * i + d]);
            hi[d] = fmax(hi[d], position[3 * i + d]);
        }
    b->side = reach;
    for (int d = 0; d < 2; ++d)
        b->cells[d] = (int)((hi[d] - b->lo[d]) / reach) + 1;
    const int buckets = b->cells[0] * b->cells[1];
    b->start = calloc((size_t)buckets + 1, sizeof *b->start);
    b->order = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->order);
    if (!b->start || !b->order)
        return -1;
    for (int i = 0; i < n; ++i)
        ++b->start[voronoi_bucket_index(b, position + 3 * i) + 1];
    for (int k = 0; k < buckets; ++k)
        b->start[k + 1] += b->start[k];
    int *fill = malloc((size_t)buckets * sizeof *fill);
    if (!fill)
        return -1;
    for (int k = 0; k < buckets; ++k)
        fill[k] = b->start[k];
    for (int i = 0; i < n; ++i)
        b->order[fill[voronoi_bucket_index(b, position + 3 * i)]++] = i;
    free(fill);
    return 0;
}

/* Area of the Voronoi cell of point i, or -1 when it is open. */
static inline double voronoi_cell(const voronoi_buckets *b, const amsph_real *position, int i, double reach)
{
    const amsph_real *p = position + 3 * i;
    voronoi_polygon poly = {4, {-reach, reach, reach, -reach}, {-reach, -reach, reach, reach}};
    const int cx = voronoi_bucket_of(b, p, 0), cy = voronoi_bucket_of(b, p, 1);
    for (int by = cy - 1; by <= cy + 1; ++by)
        for (int bx = cx - 1; bx <= cx + 1; ++bx) {
            if (bx < 0 || by < 0 || bx >= b->cells[0] || by >= b->cells[1])
                continue;
            const int bucket = bx + b->cells[0] * by;
            for (int k = b->start[bucket]; k < b->start[bucket + 1]; ++k) {
                const int j = b->order[k];
                const double dx = (double)position[3 * j] - p[0], dy = (double)position[3 * j + 1] - p[1];
                if (j == i || dx * dx + dy * dy > reach * reach)
                    continue;
                if (voronoi_clip(&poly, dx, dy))
                    return -1.0;
            }
        }
    double farthest;
    const double area = voronoi_area(&poly, &farthest);
    return 2.0 * farthest <= reach ? area : -1.0;
}

/* Cell areas of n points (x, y of a position field with 3 components per
 * point); -1 for open cells. Returns 0, or -1 when out of memory. */
static inline int voronoi_areas(const amsph_real *position, int n, double reach, double *area)
{
    voronoi_buckets b = {0};
    const int status = voronoi_buckets_build(&b, position, n, reach);
    for (int i = 0; !status && i < n; ++i)
        area[i] = voronoi_cell(&b, position, i, reach);
    free(b.start);
    free(b.order);
    return status;
}

#endif
