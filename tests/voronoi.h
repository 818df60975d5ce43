/* Voronoi cells of particle positions, the measure of particle volume of
 * Russell (2018) Sec. 4.3.1: m / rho need not be the volume a particle
 * occupies, the volume of its Voronoi cell is.
 *
 * The cell of particle i starts as the square (2D) or cube (3D) of half
 * side `reach` around x_i and is cut by the perpendicular bisector of every
 * particle j within `reach`, keeping the side of x_i (in coordinates
 * relative to x_i). Each cut clips every face, a convex polygon, by the
 * plane (Sutherland-Hodgman); in 3D the points where the plane crossed the
 * faces close the cell with a new face. The result is the exact Voronoi
 * cell when all its vertices lie within reach / 2 of x_i: a particle j
 * beyond reach is then farther from every vertex v than x_i is
 * (|v - x_j| >= |x_j - x_i| - |v - x_i| > reach / 2 >= |v - x_i|), so its
 * bisector cannot cut the cell. Otherwise the cell is open (a free surface,
 * or too few particles within reach) and its volume is reported as -1. */
#ifndef AMSPH_TESTS_VORONOI_H
#define AMSPH_TESTS_VORONOI_H

#include <math.h>
#include <stdlib.h>

#include "real.h"

#define VORONOI_MAX_FACE_VERTICES 48
#define VORONOI_MAX_FACES 64
#define VORONOI_MAX_NEAR 1024

/* A convex polygon in space, vertices in order around it. */
typedef struct {
    int n;
    double v[VORONOI_MAX_FACE_VERTICES][3];
} voronoi_face;

/* A convex cell: one face in 2D (the cell itself, in z = 0), its boundary
 * faces in 3D. */
typedef struct {
    int faces;
    voronoi_face f[VORONOI_MAX_FACES];
} voronoi_cell;

static inline double voronoi_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void voronoi_copy(double to[3], const double from[3])
{
    to[0] = from[0];
    to[1] = from[1];
    to[2] = from[2];
}

/* Clips the face to s(p) = p . d - half <= 0 (|s| below eps counts as on
 * the plane) and adds the points on the plane to cap[] (*caps of them, at
 * most `room`). Returns -1 when a result would not fit. */
static inline int voronoi_clip_face(voronoi_face *face, const double d[3], double half, double eps,
                                    double (*cap)[3], int *caps, int room)
{
    voronoi_face out = {0};
    for (int k = 0; k < face->n; ++k) {
        const double *a = face->v[k], *b = face->v[(k + 1) % face->n];
        const double sa = voronoi_dot(a, d) - half, sb = voronoi_dot(b, d) - half;
        if (out.n + 2 > VORONOI_MAX_FACE_VERTICES || *caps + 2 > room)
            return -1;
        if (sa <= eps)
            voronoi_copy(out.v[out.n++], a);
        if (fabs(sa) <= eps)
            voronoi_copy(cap[(*caps)++], a);
        if ((sa < -eps && sb > eps) || (sa > eps && sb < -eps)) {
            const double f = sa / (sa - sb);
            for (int c = 0; c < 3; ++c)
                out.v[out.n][c] = a[c] + f * (b[c] - a[c]);
            voronoi_copy(cap[(*caps)++], out.v[out.n++]);
        }
    }
    *face = out;
    return 0;
}

/* The face that closes a 3D cell cut by the plane with normal d through
 * the points cap[] (with repeats): the distinct points in order of their
 * angle around their centroid. */
static inline void voronoi_cap_face(double (*cap)[3], int caps, const double d[3], double eps, voronoi_face *face)
{
    face->n = 0;
    for (int k = 0; k < caps && face->n < VORONOI_MAX_FACE_VERTICES; ++k) {
        int repeat = 0;
        for (int j = 0; j < face->n && !repeat; ++j) {
            const double dist[3] = {cap[k][0] - face->v[j][0], cap[k][1] - face->v[j][1], cap[k][2] - face->v[j][2]};
            repeat = voronoi_dot(dist, dist) <= eps * eps;
        }
        if (!repeat)
            voronoi_copy(face->v[face->n++], cap[k]);
    }
    if (face->n < 3)
        return;
    double centre[3] = {0.0, 0.0, 0.0}, e1[3], e2[3], angle[VORONOI_MAX_FACE_VERTICES];
    for (int j = 0; j < face->n; ++j)
        for (int c = 0; c < 3; ++c)
            centre[c] += face->v[j][c] / face->n;
    for (int c = 0; c < 3; ++c)
        e1[c] = face->v[0][c] - centre[c];
    e2[0] = d[1] * e1[2] - d[2] * e1[1];
    e2[1] = d[2] * e1[0] - d[0] * e1[2];
    e2[2] = d[0] * e1[1] - d[1] * e1[0];
    for (int j = 0; j < face->n; ++j) {
        const double r[3] = {face->v[j][0] - centre[0], face->v[j][1] - centre[1], face->v[j][2] - centre[2]};
        angle[j] = atan2(voronoi_dot(r, e2), voronoi_dot(r, e1));
    }
    for (int j = 1; j < face->n; ++j) /* insertion sort by angle */
        for (int k = j; k > 0 && angle[k - 1] > angle[k]; --k) {
            const double t = angle[k];
            angle[k] = angle[k - 1];
            angle[k - 1] = t;
            double v[3];
            voronoi_copy(v, face->v[k]);
            voronoi_copy(face->v[k], face->v[k - 1]);
            voronoi_copy(face->v[k - 1], v);
        }
}

/* Cuts the cell by the bisector of the origin and d (keeping the origin's
 * side). Returns -1 when the result would not fit. */
static inline int voronoi_cut(voronoi_cell *cell, const double d[3], int dim)
{
    const double half = 0.5 * voronoi_dot(d, d), eps = 1e-12 * half;
    double cap[4 * VORONOI_MAX_FACES][3];
    int caps = 0, kept = 0;
    for (int k = 0; k < cell->faces; ++k) {
        if (voronoi_clip_face(&cell->f[k], d, half, eps, cap, &caps, 4 * VORONOI_MAX_FACES))
            return -1;
        if (cell->f[k].n >= 3)
            cell->f[kept++] = cell->f[k];
    }
    cell->faces = kept;
    if (dim == 3) {
        voronoi_face closing;
        voronoi_cap_face(cap, caps, d, sqrt(eps), &closing);
        if (closing.n >= 3) {
            if (cell->faces == VORONOI_MAX_FACES)
                return -1;
            cell->f[cell->faces++] = closing;
        }
    }
    return 0;
}

/* Volume (area in 2D) of the cell, which holds the origin, and the largest
 * distance of a vertex from the origin. */
static inline double voronoi_measure(const voronoi_cell *cell, int dim, double *farthest)
{
    double volume = 0.0;
    *farthest = 0.0;
    for (int k = 0; k < cell->faces; ++k) {
        const voronoi_face *f = &cell->f[k];
        double face = 0.0;
        for (int j = 0; j < f->n; ++j) {
            const double *a = f->v[j], *b = f->v[(j + 1) % f->n];
            *farthest = fmax(*farthest, sqrt(voronoi_dot(a, a)));
            if (dim == 2) {
                face += a[0] * b[1] - b[0] * a[1]; /* shoelace */
            } else if (j > 0 && j + 1 < f->n) { /* the tetrahedron (origin, v0, a, b) */
                const double *o = f->v[0];
                face += o[0] * (a[1] * b[2] - a[2] * b[1]) - o[1] * (a[0] * b[2] - a[2] * b[0]) +
                        o[2] * (a[0] * b[1] - a[1] * b[0]);
            }
        }
        volume += fabs(face) / (dim == 2 ? 2.0 : 6.0);
    }
    return volume;
}

/* The square (2D) or cube (3D) of half side r around the origin. */
static inline void voronoi_box(voronoi_cell *cell, int dim, double r)
{
    static const int corner[6][4][3] = {{{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}},
                                        {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
                                        {{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1}},
                                        {{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}},
                                        {{-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}, {-1, -1, 1}},
                                        {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}}};
    cell->faces = dim == 2 ? 1 : 6;
    for (int k = 0; k < cell->faces; ++k) {
        cell->f[k].n = 4;
        for (int j = 0; j < 4; ++j)
            for (int c = 0; c < 3; ++c)
                cell->f[k].v[j][c] = dim == 2 && c == 2 ? 0.0 : r * corner[k][j][c];
    }
}

/* A grid of cubic buckets of side `reach` over the points (a position
 * field, 3 components per point; z = 0 in 2D gives one layer). */
typedef struct {
    double lo[3], side;
    int cells[3];
    int *start; /* cells[0] cells[1] cells[2] + 1 offsets into order */
    int *order; /* point indices by bucket */
} voronoi_buckets;

static inline int voronoi_bucket_of(const voronoi_buckets *b, const double *p, int axis)
{
    const int c = (int)floor((p[axis] - b->lo[axis]) / b->side);
    return c < 0 ? 0 : c >= b->cells[axis] ? b->cells[axis] - 1 : c;
}

static inline int voronoi_bucket_index(const voronoi_buckets *b, const amsph_real *x)
{
    const double p[3] = {x[0], x[1], x[2]};
    return voronoi_bucket_of(b, p, 0) +
           b->cells[0] * (voronoi_bucket_of(b, p, 1) + b->cells[1] * voronoi_bucket_of(b, p, 2));
}

static inline void voronoi_buckets_free(voronoi_buckets *b)
{
    free(b->start);
    free(b->order);
}

/* Returns 0, or -1 when out of memory (free with voronoi_buckets_free). */
static inline int voronoi_buckets_build(voronoi_buckets *b, const amsph_real *position, int n, double reach)
{
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    b->lo[0] = b->lo[1] = b->lo[2] = INFINITY;
    for (int i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d) {
            b->lo[d] = fmin(b->lo[d], position[3 * i + d]);
            hi[d] = fmax(hi[d], position[3 * i + d]);
        }
    b->side = reach;
    for (int d = 0; d < 3; ++d)
        b->cells[d] = (int)((hi[d] - b->lo[d]) / reach) + 1;
    const int buckets = b->cells[0] * b->cells[1] * b->cells[2];
    b->start = calloc((size_t)buckets + 1, sizeof *b->start);
    b->order = malloc((size_t)(n > 0 ? n : 1) * sizeof *b->order);
    int *fill = malloc((size_t)buckets * sizeof *fill);
    if (!b->start || !b->order || !fill) {
        free(fill);
        return -1;
    }
    for (int i = 0; i < n; ++i)
        ++b->start[voronoi_bucket_index(b, position + 3 * i) + 1];
    for (int k = 0; k < buckets; ++k) {
        b->start[k + 1] += b->start[k];
        fill[k] = b->start[k];
    }
    for (int i = 0; i < n; ++i)
        b->order[fill[voronoi_bucket_index(b, position + 3 * i)]++] = i;
    free(fill);
    return 0;
}

/* The points within `reach` (at most the buckets' side) of p, at most
 * VORONOI_MAX_NEAR; returns their count, or -1 when there are more. */
static inline int voronoi_near(const voronoi_buckets *b, const amsph_real *position, const double p[3],
                               double reach, int *near)
{
    int count = 0, c[3];
    for (int d = 0; d < 3; ++d)
        c[d] = voronoi_bucket_of(b, p, d);
    for (int bz = c[2] - 1; bz <= c[2] + 1; ++bz)
        for (int by = c[1] - 1; by <= c[1] + 1; ++by)
            for (int bx = c[0] - 1; bx <= c[0] + 1; ++bx) {
                if (bx < 0 || by < 0 || bz < 0 || bx >= b->cells[0] || by >= b->cells[1] || bz >= b->cells[2])
                    continue;
                const int bucket = bx + b->cells[0] * (by + b->cells[1] * bz);
                for (int k = b->start[bucket]; k < b->start[bucket + 1]; ++k) {
                    const int j = b->order[k];
                    const double r[3] = {position[3 * j] - p[0], position[3 * j + 1] - p[1],
                                         position[3 * j + 2] - p[2]};
                    if (voronoi_dot(r, r) > reach * reach)
                        continue;
                    if (count == VORONOI_MAX_NEAR)
                        return -1;
                    near[count++] = j;
                }
            }
    return count;
}

/* Volume (area in 2D) of the Voronoi cell of point i, or -1 when it is open. */
static inline double voronoi_cell_volume(const voronoi_buckets *b, const amsph_real *position, int i, int dim,
                                         double reach)
{
    voronoi_cell cell;
    const double p[3] = {position[3 * i], position[3 * i + 1], position[3 * i + 2]};
    int near[VORONOI_MAX_NEAR];
    const int count = voronoi_near(b, position, p, reach, near);
    if (count < 0)
        return -1.0;
    voronoi_box(&cell, dim, reach);
    for (int k = 0; k < count; ++k) {
        const int j = near[k];
        const double d[3] = {position[3 * j] - p[0], position[3 * j + 1] - p[1], position[3 * j + 2] - p[2]};
        if (j != i && voronoi_cut(&cell, d, dim))
            return -1.0;
    }
    double farthest;
    const double volume = voronoi_measure(&cell, dim, &farthest);
    return 2.0 * farthest <= reach ? volume : -1.0;
}

/* Cell volumes (areas in 2D) of n points (a position field, 3 components
 * per point); -1 for open cells. Returns 0, or -1 when out of memory. */
static inline int voronoi_volumes(const amsph_real *position, int n, int dim, double reach, double *volume)
{
    voronoi_buckets b = {0};
    const int status = voronoi_buckets_build(&b, position, n, reach);
    for (int i = 0; !status && i < n; ++i)
        volume[i] = voronoi_cell_volume(&b, position, i, dim, reach);
    voronoi_buckets_free(&b);
    return status;
}

#endif
