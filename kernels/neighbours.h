/* The sorted grid as seen by a kernel: cell coordinates, the minimum-image
 * displacement for periodic axes, and the loop over the 3^d cells around a
 * particle. Particles are sorted by cell; cell_start[c] .. cell_start[c+1]
 * are the particles of cell c. */
#ifndef AMSPH_NEIGHBOURS_H
#define AMSPH_NEIGHBOURS_H

#include "device.h"

/* Cells around a particle's cell within `reach` cells along each axis:
 * (2 reach + 1)^d. Pair loops of the kernel support reach 1 cell (cells are
 * at least the support radius wide); wider supports, such as the surface
 * terms' (kernels/surface.cl), reach further. */
#if AMSPH_DIM == 2
#define NEIGHBOUR_CELLS(reach) ((2 * (reach) + 1) * (2 * (reach) + 1))
#else
#define NEIGHBOUR_CELLS(reach) ((2 * (reach) + 1) * (2 * (reach) + 1) * (2 * (reach) + 1))
#endif

/* Cell coordinates of cell index c (x fastest). */
static inline void grid_cell_coords(const grid_geometry *g, int c, int cc[3])
{
    cc[0] = c % g->ncell[0];
    cc[1] = (c / g->ncell[0]) % g->ncell[1];
    cc[2] = c / (g->ncell[0] * g->ncell[1]);
}

/* Index of the cell at offset o from cell cc, wrapped on periodic axes; -1
 * outside a closed axis. */
static inline int grid_cell_at(const grid_geometry *g, const int cc[3], int ox, int oy, int oz)
{
    const int o[3] = {ox, oy, oz};
    int index = 0, stride = 1;
    for (int d = 0; d < AMSPH_DIM; ++d) {
        int c = cc[d] + o[d];
        if (c < 0 || c >= g->ncell[d]) {
            if (!g->periodic[d])
                return -1;
            c = c < 0 ? c + g->ncell[d] : c - g->ncell[d];
        }
        index += c * stride;
        stride *= g->ncell[d];
    }
    return index;
}

/* Index of the k-th of the cells within `reach` of cc (k = 0 ..
 * NEIGHBOUR_CELLS(reach) - 1, x fastest), wrapped on periodic axes (which
 * must have at least 2 reach + 1 cells); -1 where it falls outside a closed
 * axis. */
static inline int grid_neighbour_cell(const grid_geometry *g, const int cc[3], int k, int reach)
{
    const int span = 2 * reach + 1;
    int o[3] = {0, 0, 0};
    for (int d = 0; d < AMSPH_DIM; ++d, k /= span)
        o[d] = k % span - reach;
    return grid_cell_at(g, cc, o[0], o[1], o[2]);
}

/* A displacement r along axis d, replaced by its nearest periodic image on a
 * periodic axis (|r| below one domain length). */
static inline real grid_nearest_image(const grid_geometry *g, int d, real r)
{
    if (g->periodic[d]) {
        const real half_length = REAL(0.5) * g->length[d];
        if (r > half_length)
            r -= g->length[d];
        else if (r < -half_length)
            r += g->length[d];
    }
    return r;
}

/* r_ab = r_a - r_b, the nearest periodic image on periodic axes. */
static inline void grid_displacement(const grid_geometry *g, GLOBAL const real *position, int a,
                                     int b, real r_ab[3])
{
    for (int d = 0; d < 3; ++d)
        r_ab[d] = grid_nearest_image(g, d, position[3 * a + d] - position[3 * b + d]);
}

/* Loop b over every particle in the cells within `reach` of cell
 * coordinates cc (particle a itself included: callers skip b == a where it
 * matters).
 *   FOR_EACH_NEIGHBOUR_WITHIN(b, &g, cc, cell_start, reach) { ... } */
#define FOR_EACH_NEIGHBOUR_WITHIN(b, g, cc, cell_start, reach)                                     \
    for (int nb_k_ = 0; nb_k_ < NEIGHBOUR_CELLS(reach); ++nb_k_)                                   \
        for (int nb_c_ = grid_neighbour_cell((g), (cc), nb_k_, (reach)),                           \
                 b = nb_c_ < 0 ? 0 : (cell_start)[nb_c_],                                          \
                 nb_end_ = nb_c_ < 0 ? 0 : (cell_start)[nb_c_ + 1];                                \
             b < nb_end_; ++b)

/* r_ab = r_a - r_b (nearest image) and r2 = |r_ab|^2; 1 when r2 < radius2. */
static inline int grid_pair_within(const grid_geometry *g, GLOBAL const real *position, int a, int b, real radius2,
                                   real r_ab[3], real *r2)
{
    grid_displacement(g, position, a, b, r_ab);
    *r2 = r_ab[0] * r_ab[0] + r_ab[1] * r_ab[1] + r_ab[2] * r_ab[2];
    return *r2 < radius2;
}

/* The position of particle a as a private point (for FOR_EACH_NEIGHBOUR_NEAR). */
static inline void grid_point(GLOBAL const real *position, int a, real x[3])
{
    for (int d = 0; d < 3; ++d)
        x[d] = position[3 * a + d];
}

/* Offsets, along each axis, of the cells within `reach` of cell cc that
 * come within extent[d] of the point x along axis d: the whole -reach ..
 * reach along a periodic axis (its last cell is wider than cell_size), 0 .. 0
 * along the axes past the dimension. */
typedef struct {
    int lo[3], hi[3];
} grid_span;

static inline grid_span grid_box_span(const grid_geometry *g, const real x[3], const int cc[3], int reach,
                                      const real extent[3])
{
    grid_span s;
    for (int d = 0; d < 3; ++d) {
        s.lo[d] = d < AMSPH_DIM ? -reach : 0;
        s.hi[d] = d < AMSPH_DIM ? reach : 0;
        if (d >= AMSPH_DIM || g->periodic[d])
            continue;
        /* cell o spans [o, o + 1) cell sizes from cell cc's lower face */
        const real offset = (x[d] - g->lo[d]) / g->cell_size - (real)cc[d], cells = extent[d] / g->cell_size;
        while (s.lo[d] < 0 && (real)(s.lo[d] + 1) <= offset - cells)
            ++s.lo[d];
        while (s.hi[d] > 0 && (real)s.hi[d] >= offset + cells)
            --s.hi[d];
    }
    return s;
}

/* The span of the cells that come within `radius` of x (a ball). */
static inline grid_span grid_near_span(const grid_geometry *g, const real x[3], const int cc[3], int reach,
                                       real radius)
{
    const real extent[3] = {radius, radius, radius};
    return grid_box_span(g, x, cc, reach, extent);
}

/* Loop b over the particles of the cells of span s around cell cc (a
 * grid_span, consumed by the loop):
 *   FOR_EACH_NEIGHBOUR_IN_SPAN(b, &g, cc, s, cell_start) { ... } */
#define FOR_EACH_NEIGHBOUR_IN_SPAN(b, g, cc, s, cell_start)                                        \
    for (grid_span nb_s_ = (s); nb_s_.lo[2] <= nb_s_.hi[2]; ++nb_s_.lo[2])                          \
        for (int nb_y_ = nb_s_.lo[1]; nb_y_ <= nb_s_.hi[1]; ++nb_y_)                               \
            for (int nb_x_ = nb_s_.lo[0]; nb_x_ <= nb_s_.hi[0]; ++nb_x_)                           \
                for (int nb_c_ = grid_cell_at((g), (cc), nb_x_, nb_y_, nb_s_.lo[2]),               \
                         b = nb_c_ < 0 ? 0 : (cell_start)[nb_c_],                                  \
                         nb_end_ = nb_c_ < 0 ? 0 : (cell_start)[nb_c_ + 1];                        \
                     b < nb_end_; ++b)

/* Loop b over the particles of the cells within `reach` of cell cc that
 * come within `radius` of the point x (a private real[3]; grid_point):
 * with a support of 1.5 cells (reach 2), about 45 of the 125 cells in 3D.
 *   FOR_EACH_NEIGHBOUR_NEAR(b, &g, cc, x, cell_start, reach, radius) { ... } */
#define FOR_EACH_NEIGHBOUR_NEAR(b, g, cc, x, cell_start, reach, radius)                            \
    FOR_EACH_NEIGHBOUR_IN_SPAN(b, g, cc, grid_near_span((g), (x), (cc), (reach), (radius)), cell_start)

/* The 3^d cells of the kernel support. */
#define FOR_EACH_NEIGHBOUR(b, g, cc, cell_start) FOR_EACH_NEIGHBOUR_WITHIN(b, g, cc, cell_start, 1)

#endif
