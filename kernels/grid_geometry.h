/* The grid a pair loop walks, passed to kernels by value; the host includes
 * it with AMSPH_SHARED_REAL defined as its amsph_real, so both sides share one
 * layout. Lengths in m. Cells are numbered x fastest; cell sizes are
 * cell_size except the last cell of an axis, which takes the remainder.
 *
 * The particles of each row of cells along x are sorted into two sets:
 * first everything that is not a wall (fluid, solids, grains: the particles
 * that move or change kind), then the walls, which never change kind. The
 * buckets go row by row, and within a row set by set, cell by cell along
 * x: bucket (2 row + set) ncell[0] + x. Bucket 2 total_cells collects the
 * particles that left the domain, the last bucket after it those whose
 * position is not finite (host/grid.h amsph_grid_sort). A loop that needs only non-wall
 * neighbours (the walls' state from the fluid) then reads no wall at all,
 * and a wall far from any fluid costs nothing there; the rows keep both
 * sets of a neighbourhood close in memory, and a contiguous range of
 * particles a compact region of space (for the threads' shares). */
#ifndef AMSPH_GRID_GEOMETRY_H
#define AMSPH_GRID_GEOMETRY_H

#ifndef AMSPH_SHARED_REAL
#define AMSPH_SHARED_REAL real
#endif

/* Cells per kernel support: cells are support / GRID_CELLS_PER_SUPPORT wide,
 * and a pair loop of the support reaches this many cells around a
 * particle's cell (kernels/neighbours.h). With the loop trimmed to the
 * support sphere, cells of half the support hold 2.5 candidates per
 * neighbour in 3D, cells of the whole support 4.9. */
#define GRID_CELLS_PER_SUPPORT 2

typedef struct {
    AMSPH_SHARED_REAL lo[3];     /* domain minimum corner */
    AMSPH_SHARED_REAL length[3]; /* domain extent per axis */
    AMSPH_SHARED_REAL cell_size; /* side of a cell, the kernel support / GRID_CELLS_PER_SUPPORT */
    int ncell[3];              /* cells per axis (1 for unused axes) */
    int periodic[3];           /* 1 where the axis wraps around */
    int total_cells;           /* ncell[0] * ncell[1] * ncell[2], the cells of one set */
} grid_geometry;

/* The sets of cells (see above), in sorted order. */
#define GRID_SET_BODIES 0 /* fluid, solid and grain particles */
#define GRID_SET_WALLS 1  /* wall particles */
#define GRID_SETS 2

/* The bucket of cell `cell`'s particles of set `set` (its row's in that
 * set from `row_bucket`), the cell of a bucket, the bucket of the
 * particles that left the domain and of those whose position is not finite. */
static inline int grid_row_bucket(const grid_geometry *g, int row_cell, int set)
{
    return GRID_SETS * row_cell + set * g->ncell[0]; /* row_cell: the row's cell at x = 0 */
}
static inline int grid_bucket(const grid_geometry *g, int cell, int set)
{
    const int x = cell % g->ncell[0];
    return grid_row_bucket(g, cell - x, set) + x;
}
static inline int grid_cell_of_bucket(const grid_geometry *g, int bucket)
{
    const int n = g->ncell[0];
    return bucket / (GRID_SETS * n) * n + bucket % n;
}
static inline int grid_departed_bucket(const grid_geometry *g)
{
    return GRID_SETS * g->total_cells;
}
static inline int grid_not_finite_bucket(const grid_geometry *g)
{
    return grid_departed_bucket(g) + 1;
}

#endif
