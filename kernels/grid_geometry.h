/* The grid a pair loop walks, passed to kernels by value; the host includes
 * it with AMSPH_SHARED_REAL defined as its amsph_real, so both sides share one
 * layout. Lengths in m. Cells are numbered x fastest; cell sizes are
 * cell_size except the last cell of an axis, which takes the remainder. */
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
    int total_cells;           /* ncell[0] * ncell[1] * ncell[2]; bucket total_cells collects
                                  particles that left the domain */
} grid_geometry;

#endif
