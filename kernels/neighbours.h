/* The sorted grid as seen by a kernel: cell coordinates, and the loop over
 * the particles of the cells around a point that come within a radius of
 * it. Particles are sorted by row of cells along x, set (walls last) and
 * cell (kernels/grid_geometry.h): cell_start[k] .. cell_start[k + 1] are
 * the particles of bucket k (grid_bucket), and the cells of a row along x
 * are one contiguous range of particles in each set. */
#ifndef AMSPH_NEIGHBOURS_H
#define AMSPH_NEIGHBOURS_H

#include "device.h"

/* Cell coordinates of cell index c (x fastest). */
static inline void grid_cell_coords(const grid_geometry *g, int c, int cc[3])
{
    cc[0] = c % g->ncell[0];
    cc[1] = (c / g->ncell[0]) % g->ncell[1];
    cc[2] = c / (g->ncell[0] * g->ncell[1]);
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

/* The position of particle a as a private point (the centre of a neighbour loop). */
static inline void grid_point(GLOBAL const real *position, int a, real x[3])
{
    for (int d = 0; d < 3; ++d)
        x[d] = position[3 * a + d];
}

/* Positions and cell faces are rounded to about 1e-6 cell sizes: a cell is
 * passed over only when it lies this many cell sizes beyond the radius, so
 * that no particle within the radius is lost to rounding. */
#define GRID_SPAN_SLACK REAL(1e-4)

/* The widest reach of a neighbour loop, in cells: the surface terms' support
 * is at most 4 kernel supports (surface.h_over_dx <= 4 h_over_dx, host/case.c). */
#define GRID_MAX_REACH (4 * GRID_CELLS_PER_SUPPORT)
#define GRID_SPAN_WIDTH (2 * GRID_MAX_REACH + 1)

/* The cells within `reach` of cell cc that come within the radius of the
 * point x. Per axis, the squared distances from x to the m-th cell below
 * and above cc (cell sizes, m = 0 .. reach - 1; GRID_BEYOND past a closed
 * axis's end and along the axes past the dimension); along a periodic axis,
 * whose last cell is wider than cell_size, no cell is passed over (its
 * distances are 0). Per offset o along y and z (index o + GRID_MAX_REACH):
 * the squared distance from x to the cells at o, their coordinate wrapped
 * around a periodic axis times its stride in the cell index, and the
 * point's coordinate as the particles there see it: x less the periodic
 * image (a particle's image next to x is r_b + image, image the domain
 * length where o wraps below the axis's start, minus it above its end). */
typedef struct {
    real below2[3][GRID_MAX_REACH], above2[3][GRID_MAX_REACH];
    real gap2[2][GRID_SPAN_WIDTH];
    int row_cell[2][GRID_SPAN_WIDTH];
    real point[2][GRID_SPAN_WIDTH];
    real extent2; /* (radius / cell_size + the slack)^2 */
    int lo_z, hi_z; /* the offsets along z within the radius */
    int cx;         /* cc's x coordinate */
    real x;         /* the point's x */
} grid_span;

#define GRID_BEYOND REAL(1e30)

/* The number of cells on one side of cc along an axis, given the squared
 * distances to them (increasing), that come closer than sqrt(room). */
static inline int grid_cells_within(const real gap2[GRID_MAX_REACH], int reach, real room)
{
    int cells = 0;
    for (int m = 0; m < reach; ++m)
        cells += gap2[m] < room;
    return cells;
}

static inline grid_span *grid_near_span(grid_span *s, const grid_geometry *g, const real x[3], const int cc[3],
                                        int reach, real radius)
{
    const real extent = radius / g->cell_size + GRID_SPAN_SLACK;
    s->extent2 = extent * extent;
    s->cx = cc[0];
    s->x = x[0];
    for (int d = 0, stride = 1; d < 3; stride *= g->ncell[d], ++d) {
        const int trimmed = d < AMSPH_DIM && !g->periodic[d];
        /* cell o spans [o, o + 1) cell sizes from cell cc's lower face */
        const real offset = trimmed ? (x[d] - g->lo[d]) / g->cell_size - (real)cc[d] : REAL(0.0);
        for (int m = 0; m < reach; ++m) {
            const real below = offset + (real)m, above = REAL(1.0) - offset + (real)m;
            s->below2[d][m] = !trimmed ? REAL(0.0) : below > REAL(0.0) ? below * below : REAL(0.0);
            s->above2[d][m] = !trimmed ? REAL(0.0) : above > REAL(0.0) ? above * above : REAL(0.0);
            if (d >= AMSPH_DIM || (trimmed && cc[d] - m - 1 < 0))
                s->below2[d][m] = GRID_BEYOND;
            if (d >= AMSPH_DIM || (trimmed && cc[d] + m + 1 >= g->ncell[d]))
                s->above2[d][m] = GRID_BEYOND;
        }
        const int lo = -grid_cells_within(s->below2[d], reach, s->extent2);
        const int hi = grid_cells_within(s->above2[d], reach, s->extent2);
        for (int o = lo; d > 0 && o <= hi; ++o) {
            const int k = o + GRID_MAX_REACH, c = cc[d] + o;
            s->gap2[d - 1][k] = o < 0 ? s->below2[d][-o - 1] : o > 0 ? s->above2[d][o - 1] : REAL(0.0);
            s->point[d - 1][k] = x[d] - (c < 0 ? -g->length[d] : c >= g->ncell[d] ? g->length[d] : REAL(0.0));
            s->row_cell[d - 1][k] = (c < 0 ? c + g->ncell[d] : c >= g->ncell[d] ? c - g->ncell[d] : c) * stride;
        }
        s->lo_z = lo;
        s->hi_z = hi;
    }
    return s;
}

/* The room left along x and y in the slab of cells at offset oz along z:
 * extent^2 less the slab's squared distance. */
static inline real grid_slab_room(const grid_span *s, int oz)
{
    return s->extent2 - s->gap2[1][oz + GRID_MAX_REACH];
}

/* A run of a neighbour loop: the particles first .. end - 1 of one set of
 * cells (GRID_SET_*) in consecutive cells along x in one row of the span,
 * and the point as they see it: the point less the periodic image of the
 * run (grid_span), so that r_ab = point - r_b for the point as r_a. On a
 * periodic x axis a row comes in three parts: the cells wrapped from the
 * axis's upper end (part -1), the cells within the axis (0) and those
 * wrapped from its lower end (+1), each possibly empty. A row's runs go
 * part by part within each set, the sets first_set .. last_set in turn. */
typedef struct {
    int first, end;
    real point[3];
    int part, first_part, last_part; /* the part of the row this run holds, and the row's parts */
    int set, last_set;               /* the set of this run, and the loop's last */
    int row_cell;                    /* index of the row's cell at x = 0 */
    int x_lo, x_hi;                  /* the row's cells along x, unwrapped */
} grid_run;

/* first and end of the run's set and part: the row's cells u = x_lo ..
 * x_hi with part * ncell <= u < (part + 1) * ncell, at u - part * ncell (on
 * a closed x axis, part 0: all of them). */
static inline void grid_run_locate(const grid_geometry *g, GLOBAL const int *cell_start, real x, grid_run *run)
{
    const int n = g->ncell[0], part = run->part;
    const int row = grid_row_bucket(g, run->row_cell, run->set) - part * n;
    if (!g->periodic[0]) {
        run->first = cell_start[row + run->x_lo];
        run->end = cell_start[row + run->x_hi + 1];
        return;
    }
    const int u_lo = run->x_lo > part * n ? run->x_lo : part * n;
    const int u_hi = run->x_hi < part * n + n - 1 ? run->x_hi : part * n + n - 1;
    run->point[0] = x - (real)part * g->length[0];
    run->first = u_lo <= u_hi ? cell_start[row + u_lo] : 0;
    run->end = u_lo <= u_hi ? cell_start[row + u_hi + 1] : 0;
}

/* The first run of the span's row (oy, oz) in the sets first_set ..
 * last_set, `reach` cells to either side of the span's centre (the
 * span's; a constant where the loop's is, which unrolls the counts), whose y offset is within the radius in its slab (room > its
 * squared distance): its cells along x trimmed to those within the radius
 * of the point (gap_x^2 + gap_y^2 + gap_z^2 < extent^2). */
static inline grid_run grid_row(const grid_geometry *g, GLOBAL const int *cell_start, const grid_span *s,
                                int reach, real slab_room, int oy, int oz, int first_set, int last_set)
{
    grid_run run;
    const int ky = oy + GRID_MAX_REACH, kz = oz + GRID_MAX_REACH;
    const real room = slab_room - s->gap2[0][ky];
    run.row_cell = s->row_cell[0][ky] + s->row_cell[1][kz];
    run.point[0] = s->x;
    run.point[1] = s->point[0][ky];
    run.point[2] = s->point[1][kz];
    run.x_lo = s->cx - grid_cells_within(s->below2[0], reach, room);
    run.x_hi = s->cx + grid_cells_within(s->above2[0], reach, room);
    run.first_part = run.part = g->periodic[0] ? -1 : 0;
    run.last_part = g->periodic[0] ? 1 : 0;
    run.set = first_set;
    run.last_set = last_set;
    grid_run_locate(g, cell_start, s->x, &run);
    return run;
}

/* The next run of the row, if any (run->set > run->last_set: none). */
static inline void grid_run_next(const grid_geometry *g, GLOBAL const int *cell_start, const grid_span *s,
                                 grid_run *run)
{
    if (++run->part > run->last_part) {
        run->part = run->first_part;
        if (++run->set > run->last_set)
            return;
    }
    grid_run_locate(g, cell_start, s->x, run);
}

/* Loop over the runs (grid_run, named `run`) of the sets first_set ..
 * last_set (GRID_SET_*) in the cells within `reach` (<= GRID_MAX_REACH) of
 * cell cc that come within `radius` of the point x (a private real[3];
 * grid_point): one run of contiguous particles per row of cells, set and
 * periodic image, the rows and their cells trimmed to the sphere. */
#define FOR_EACH_RUN_IN(run, g, cc, x, cell_start, reach, radius, from_set, to_set)                \
    for (grid_span nb_s_, *nb_once_ = grid_near_span(&nb_s_, (g), (x), (cc), (reach), (radius));   \
         nb_once_; nb_once_ = 0)                                                                   \
        for (int nb_z_ = nb_s_.lo_z; nb_z_ <= nb_s_.hi_z; ++nb_z_)                                 \
            for (real nb_room_ = grid_slab_room(&nb_s_, nb_z_), *nb_slab_ = &nb_room_; nb_slab_;    \
                 nb_slab_ = 0)                                                                     \
                for (int nb_y_ = -grid_cells_within(nb_s_.below2[1], (reach), nb_room_),          \
                         nb_y_hi_ = grid_cells_within(nb_s_.above2[1], (reach), nb_room_);         \
                     nb_y_ <= nb_y_hi_; ++nb_y_)                                                   \
                    for (grid_run run = grid_row((g), (cell_start), &nb_s_, (reach), nb_room_, nb_y_, nb_z_, \
                                                 (from_set), (to_set));                           \
                         run.set <= run.last_set; grid_run_next((g), (cell_start), &nb_s_, &run))

/* Loop b over the particles of the runs of FOR_EACH_RUN_IN: with cells of
 * half the kernel support, 3D, 2.5 candidates per particle within the
 * support.
 *   FOR_EACH_NEIGHBOUR_IN(b, run, &g, cc, x, cell_start, reach, radius, first_set, last_set) { ... } */
#define FOR_EACH_NEIGHBOUR_IN(b, run, g, cc, x, cell_start, reach, radius, from_set, to_set)      \
    FOR_EACH_RUN_IN(run, g, cc, x, cell_start, reach, radius, from_set, to_set)                    \
    for (int b = run.first; b < run.end; ++b)

/* The loop over every particle (both sets) within `reach` cells. */
#define FOR_EACH_NEIGHBOUR_NEAR(b, run, g, cc, x, cell_start, reach, radius)                       \
    FOR_EACH_NEIGHBOUR_IN(b, run, g, cc, x, cell_start, reach, radius, GRID_SET_BODIES, GRID_SET_WALLS)

/* The neighbour loop of a radius up to the kernel support. */
#define FOR_EACH_NEIGHBOUR(b, run, g, cc, x, cell_start, radius)                                   \
    FOR_EACH_NEIGHBOUR_NEAR(b, run, g, cc, x, cell_start, GRID_CELLS_PER_SUPPORT, radius)

/* The same loop over the particles that are not walls (GRID_SET_BODIES). */
#define FOR_EACH_BODY_NEIGHBOUR(b, run, g, cc, x, cell_start, radius)                              \
    FOR_EACH_NEIGHBOUR_IN(b, run, g, cc, x, cell_start, GRID_CELLS_PER_SUPPORT, radius, GRID_SET_BODIES, \
                          GRID_SET_BODIES)

/* r_ab = r_a - r_b for the loop's point as r_a and the image of b next to it. */
static inline void grid_displacement(const grid_run *run, GLOBAL const real *position, int b, real r_ab[3])
{
    for (int d = 0; d < 3; ++d)
        r_ab[d] = run->point[d] - position[3 * b + d];
}

/* r_ab (grid_displacement) and r2 = |r_ab|^2; 1 when r2 < radius2. */
static inline int grid_pair_within(const grid_run *run, GLOBAL const real *position, int b, real radius2,
                                   real r_ab[3], real *r2)
{
    grid_displacement(run, position, b, r_ab);
    *r2 = r_ab[0] * r_ab[0] + r_ab[1] * r_ab[1] + r_ab[2] * r_ab[2];
    return *r2 < radius2;
}

/* Candidates a pair loop tests at a time (FOR_EACH_NEIGHBOUR_WITHIN). */
#define GRID_CANDIDATES 16

/* The particles of a stretch of a run that lie within the radius. */
typedef struct {
    int count;
    int index[GRID_CANDIDATES];
} grid_within;

/* The particles first .. end - 1 of a run (at most GRID_CANDIDATES), but
 * `self`, closer than sqrt(radius2) to the run's point, listed without a
 * branch on the distance. Returns w, for the loop's test. */
static inline grid_within *grid_gather_within(const real point[3], GLOBAL const real *position, int first, int end,
                                              int self, real radius2, grid_within *w)
{
    int count = 0;
    for (int b = first; b < end; ++b) {
        real r2 = REAL(0.0);
        for (int d = 0; d < 3; ++d) {
            const real r = point[d] - position[3 * b + d];
            r2 += r * r;
        }
        w->index[count] = b;
        count += (r2 < radius2) & (b != self);
    }
    w->count = count;
    return w;
}

/* The first index past the stretch of GRID_CANDIDATES from first, within end. */
static inline int grid_stretch_end(int first, int end)
{
    return end - first < GRID_CANDIDATES ? end : first + GRID_CANDIDATES;
}

/* Loop b over the list w of grid_gather_within (a loop's body may
 * `continue`, not `break`). */
#define FOR_EACH_LISTED(b, w)                                                                      \
    for (int nb_k_ = 0; nb_k_ < (w).count; ++nb_k_)                                                \
        for (int b = (w).index[nb_k_], nb_one_ = 1; nb_one_; nb_one_ = 0)

/* Loop b over the particles of both sets within `radius` (up to the kernel
 * support) of particle `self` at the point x, but self: FOR_EACH_NEIGHBOUR
 * with the distance test taken out of the pair loop. Each run's candidates
 * are listed a stretch of GRID_CANDIDATES at a time (grid_gather_within),
 * then the pair loop visits the list, in the run's order: in 3D 2 in 5
 * candidates lie within, in no order a branch predictor can follow, and a
 * branch on each would be mispredicted about every third time. The body
 * computes r_ab itself (grid_displacement) and may `continue`, not `break`.
 *   FOR_EACH_NEIGHBOUR_WITHIN(b, run, &g, cc, x, cell_start, position, self, radius) { ... } */
#define FOR_EACH_NEIGHBOUR_WITHIN(b, run, g, cc, x, cell_start, position, self, radius)           \
    FOR_EACH_RUN_IN(run, g, cc, x, cell_start, GRID_CELLS_PER_SUPPORT, radius, GRID_SET_BODIES,     \
                    GRID_SET_WALLS)                                                                \
    for (int nb_first_ = run.first; nb_first_ < run.end; nb_first_ += GRID_CANDIDATES)            \
        for (grid_within nb_w_, *nb_list_ = grid_gather_within(run.point, (position), nb_first_,    \
                                                               grid_stretch_end(nb_first_, run.end), \
                                                               (self), (radius) * (radius), &nb_w_); \
             nb_list_; nb_list_ = 0)                                                               \
            FOR_EACH_LISTED(b, nb_w_)

/* Does the grid wrap around along any axis? The box loops below serve only
 * a grid that does not. */
static inline int grid_has_periodic_axis(const grid_geometry *g)
{
    return g->periodic[0] || g->periodic[1] || g->periodic[2];
}

/* The cells within `reach` of cell cc, a box of (2 reach + 1)^d cells cut
 * at the grid's faces: its lowest and highest cell along each axis.
 * Returns 1, for the loop's test. */
static inline int grid_box(const grid_geometry *g, const int cc[3], int reach, int lo[3], int hi[3])
{
    for (int d = 0; d < 3; ++d) {
        lo[d] = d < AMSPH_DIM && cc[d] > reach ? cc[d] - reach : 0;
        hi[d] = d >= AMSPH_DIM ? 0 : cc[d] + reach < g->ncell[d] ? cc[d] + reach : g->ncell[d] - 1;
    }
    return 1;
}

/* The bucket of the cell at x = 0 of row (y, z) in set `set`. */
static inline int grid_box_row(const grid_geometry *g, int y, int z, int set)
{
    return grid_row_bucket(g, (z * g->ncell[1] + y) * g->ncell[0], set);
}

/* Whether a fluid particle lies in the box of cells within `reach` of cell
 * cc (grid_box): count holds the fluid particles per cell (kernels/grid.cl
 * grid_fluid_mark), and a row of cells with no non-wall particle at all
 * (GRID_SET_BODIES) is passed over after one comparison, so that the walls
 * far from anything that moves, most of a tank's, cost a test per row. A
 * pair loop of that reach from cc finds no fluid where it is 0. 1 with a
 * periodic axis (not tested). */
static inline int grid_fluid_in_box(const grid_geometry *g, GLOBAL const int *cell_start, GLOBAL const int *count,
                                    const int cc[3], int reach)
{
    if (grid_has_periodic_axis(g))
        return 1;
    int lo[3], hi[3];
    grid_box(g, cc, reach, lo, hi);
    for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y) {
            const int bodies = grid_box_row(g, y, z, GRID_SET_BODIES);
            if (cell_start[bodies + lo[0]] == cell_start[bodies + hi[0] + 1])
                continue;
            const int row = (z * g->ncell[1] + y) * g->ncell[0];
            for (int x = lo[0]; x <= hi[0]; ++x)
                if (count[row + x] > 0)
                    return 1;
        }
    return 0;
}

/* Loop b over the particles of set `set` (GRID_SET_*) in the box of cells
 * within `reach` of cell cc (grid_box), one run of contiguous particles per
 * row of cells, on a grid without a periodic axis (grid_has_periodic_axis):
 * the displacement is position[a] - position[b]. Unlike FOR_EACH_NEIGHBOUR_IN
 * it does not trim the box to a sphere around a point, so it costs no
 * set-up but the box's faces and a few instructions per row, and visits
 * about 1.5 times the candidates in 3D: the loop for a point with few
 * candidates, such as a wall over the fluid near it (an empty row costs two
 * loads). It visits the cells in the order FOR_EACH_NEIGHBOUR_IN does (which
 * visits a subset of them), so a sum over the particles within a radius
 * comes out bit for bit the same.
 *   FOR_EACH_IN_BOX(b, &g, cc, cell_start, reach, set) { ... } */
#define FOR_EACH_IN_BOX(b, g, cc, cell_start, reach, set)                                         \
    for (int nb_lo_[3], nb_hi_[3], nb_once_ = grid_box((g), (cc), (reach), nb_lo_, nb_hi_); nb_once_;  \
         nb_once_ = 0)                                                                             \
        for (int nb_z_ = nb_lo_[2]; nb_z_ <= nb_hi_[2]; ++nb_z_)                                   \
            for (int nb_y_ = nb_lo_[1]; nb_y_ <= nb_hi_[1]; ++nb_y_)                               \
                for (int nb_row_ = grid_box_row((g), nb_y_, nb_z_, (set)), b = (cell_start)[nb_row_ + nb_lo_[0]], \
                         nb_end_ = (cell_start)[nb_row_ + nb_hi_[0] + 1];                          \
                     b < nb_end_; ++b)

#endif
