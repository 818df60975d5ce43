/* The sorted grid as seen by a kernel: cell coordinates, and the loop over
 * the particles of the cells around a point that come within a radius of
 * it. Particles are sorted by cell, cells numbered x fastest:
 * cell_start[c] .. cell_start[c+1] are the particles of cell c, and the
 * cells of a row along x are one contiguous range of particles. */
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

/* The widest reach of a neighbour loop, in cells. */
#define GRID_MAX_REACH 4
#define GRID_SPAN_WIDTH (2 * GRID_MAX_REACH + 1)

/* The cells within `reach` of cell cc around the point x, per axis d and
 * offset o (index o + GRID_MAX_REACH): the squared distance from x to the
 * cells at that offset (in cell sizes), and along y and z the offset's
 * wrapped cell coordinate times its stride in the cell index (-1 beyond a
 * closed axis) and its periodic image (the domain length where the offset
 * wraps below the axis's start, minus it above its end). lo .. hi are the
 * offsets that come within the radius; along the axes past the dimension
 * 0 .. 0. Along a periodic axis, whose last cell is wider than cell_size,
 * no cell is passed over (its distances are 0). */
typedef struct {
    int lo[3], hi[3];
    real gap2[3][GRID_SPAN_WIDTH];
    int row_cell[3][GRID_SPAN_WIDTH];
    real image[3][GRID_SPAN_WIDTH];
    real extent2; /* (radius / cell_size)^2, with the slack */
    int cx;       /* cc's x coordinate */
} grid_span;

static inline grid_span grid_near_span(const grid_geometry *g, const real x[3], const int cc[3], int reach,
                                       real radius)
{
    grid_span s;
    const real extent = radius / g->cell_size + GRID_SPAN_SLACK;
    s.extent2 = extent * extent;
    s.cx = cc[0];
    for (int d = 0, stride = 1; d < 3; stride *= g->ncell[d], ++d) {
        const int r = d < AMSPH_DIM ? reach : 0;
        const int trimmed = d < AMSPH_DIM && !g->periodic[d];
        /* cell o spans [o, o + 1) cell sizes from cell cc's lower face */
        const real offset = trimmed ? (x[d] - g->lo[d]) / g->cell_size - (real)cc[d] : REAL(0.0);
        s.lo[d] = -r;
        s.hi[d] = r;
        for (int o = -r; o <= r; ++o) {
            const real gap = !trimmed || o == 0 ? REAL(0.0) : o < 0 ? offset - (real)(o + 1) : (real)o - offset;
            const int k = o + GRID_MAX_REACH;
            s.gap2[d][k] = gap > REAL(0.0) ? gap * gap : REAL(0.0);
            int c = cc[d] + o;
            s.image[d][k] = c < 0 ? -g->length[d] : c >= g->ncell[d] ? g->length[d] : REAL(0.0);
            if (c < 0 || c >= g->ncell[d])
                c = g->periodic[d] ? (c < 0 ? c + g->ncell[d] : c - g->ncell[d]) : -1;
            s.row_cell[d][k] = c < 0 ? -1 : c * stride;
        }
        while (s.lo[d] < 0 && s.gap2[d][s.lo[d] + GRID_MAX_REACH] >= s.extent2)
            ++s.lo[d];
        while (s.hi[d] > 0 && s.gap2[d][s.hi[d] + GRID_MAX_REACH] >= s.extent2)
            --s.hi[d];
    }
    return s;
}

/* A run of a neighbour loop: the particles first .. end - 1 of consecutive
 * cells along x in one row of the span, and the periodic image of the run:
 * the image of each of its particles b next to the point is r_b + image
 * (image[d] = 0, or -/+ the domain length where the row wraps around a
 * periodic axis d). A row comes in up to three parts along x: the cells
 * wrapped from the axis's upper end (part -1), the cells within the axis
 * (0) and those wrapped from its lower end (+1). */
typedef struct {
    int first, end;
    real image[3];
    int part, last_part; /* the part of the row this run holds, and the row's last */
    int row_cell;        /* index of the row's cell at x = 0, -1 beyond a closed axis */
    int x_lo, x_hi;      /* the row's cells along x, unwrapped (x_lo > x_hi: none) */
} grid_run;

/* Part `part` of the row: its cells are the row's cells u = x_lo .. x_hi
 * with part * ncell <= u < (part + 1) * ncell, at u - part * ncell. */
static inline void grid_run_part(const grid_geometry *g, GLOBAL const int *cell_start, grid_run *run,
                                 int part)
{
    const int n = g->ncell[0];
    const int u_lo = run->x_lo > part * n ? run->x_lo : part * n;
    const int u_hi = run->x_hi < part * n + n - 1 ? run->x_hi : part * n + n - 1;
    run->part = part;
    run->image[0] = (real)part * g->length[0];
    run->first = run->end = 0;
    if (u_lo <= u_hi && run->row_cell >= 0) {
        run->first = cell_start[run->row_cell + u_lo - part * n];
        run->end = cell_start[run->row_cell + u_hi - part * n + 1];
    }
}

/* The first run of the span's row (oy, oz): its cells along x trimmed to
 * those within the radius of the point (gap_x^2 + gap_y^2 + gap_z^2 <
 * extent^2), none where the row lies beyond the radius or beyond a closed
 * axis's end. */
static inline grid_run grid_row(const grid_geometry *g, GLOBAL const int *cell_start, const grid_span *s,
                                int oy, int oz)
{
    grid_run run;
    const int ky = oy + GRID_MAX_REACH, kz = oz + GRID_MAX_REACH;
    const int cy = s->row_cell[1][ky], cz = s->row_cell[2][kz];
    run.row_cell = cy < 0 || cz < 0 ? -1 : cy + cz;
    run.image[1] = s->image[1][ky];
    run.image[2] = s->image[2][kz];
    const real room = s->extent2 - s->gap2[1][ky] - s->gap2[2][kz];
    run.x_lo = s->lo[0];
    run.x_hi = s->hi[0];
    while (run.x_lo <= run.x_hi && s->gap2[0][run.x_lo + GRID_MAX_REACH] >= room)
        ++run.x_lo;
    while (run.x_lo <= run.x_hi && s->gap2[0][run.x_hi + GRID_MAX_REACH] >= room)
        --run.x_hi;
    run.x_lo += s->cx;
    run.x_hi += s->cx;
    run.last_part = g->periodic[0] ? 1 : 0;
    grid_run_part(g, cell_start, &run, -run.last_part);
    return run;
}

/* Loop b over the particles of the cells within `reach` (<= GRID_MAX_REACH)
 * of cell cc that come within `radius` of the point x (a private real[3];
 * grid_point), one run (grid_run, named `run`) of contiguous particles per
 * row of cells and periodic image: with cells of the kernel support, 3D,
 * 4.9 candidates per particle within the support (6.4 in the 27 cells).
 *   FOR_EACH_NEIGHBOUR_NEAR(b, run, &g, cc, x, cell_start, reach, radius) { ... } */
#define FOR_EACH_NEIGHBOUR_NEAR(b, run, g, cc, x, cell_start, reach, radius)                       \
    for (grid_span nb_s_ = grid_near_span((g), (x), (cc), (reach), (radius));                      \
         nb_s_.lo[2] <= nb_s_.hi[2]; ++nb_s_.lo[2])                                                \
        for (int nb_y_ = nb_s_.lo[1]; nb_y_ <= nb_s_.hi[1]; ++nb_y_)                               \
            for (grid_run run = grid_row((g), (cell_start), &nb_s_, nb_y_, nb_s_.lo[2]);           \
                 run.part <= run.last_part; grid_run_part((g), (cell_start), &run, run.part + 1))   \
                for (int b = run.first; b < run.end; ++b)

/* The neighbour loop of the kernel support: the cells around the particle
 * reach 1 cell (cells are at least the support wide). */
#define FOR_EACH_NEIGHBOUR(b, run, g, cc, x, cell_start, radius)                                   \
    FOR_EACH_NEIGHBOUR_NEAR(b, run, g, cc, x, cell_start, 1, radius)

/* r_ab = r_a - r_b for the point x_a = r_a and the image of b in run. */
static inline void grid_displacement(const real x_a[3], GLOBAL const real *position, int b,
                                     const grid_run *run, real r_ab[3])
{
    for (int d = 0; d < 3; ++d)
        r_ab[d] = (x_a[d] - position[3 * b + d]) - run->image[d];
}

/* r_ab (grid_displacement) and r2 = |r_ab|^2; 1 when r2 < radius2. */
static inline int grid_pair_within(const real x_a[3], GLOBAL const real *position, int b,
                                   const grid_run *run, real radius2, real r_ab[3], real *r2)
{
    grid_displacement(x_a, position, b, run, r_ab);
    *r2 = r_ab[0] * r_ab[0] + r_ab[1] * r_ab[1] + r_ab[2] * r_ab[2];
    return *r2 < radius2;
}

#endif
