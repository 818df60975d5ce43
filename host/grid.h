/* The sorted particle grid: when and how particles are binned and reordered.
 * The counting sort runs on the device (kernels/grid.cl); the host only
 * reads back how many particles remain. */
#ifndef AMSPH_GRID_H
#define AMSPH_GRID_H

#include "particles.h"
#include "real.h"
#define AMSPH_SHARED_REAL amsph_real
#include "grid_geometry.h"

#define AMSPH_GRID_SCRATCH 8 /* scratch buffers by 32-bit words per particle */

typedef struct {
    grid_geometry geometry;
    int dim;
    int capacity;               /* particles the grid buffers hold */
    amsph_buffer *cell;         /* cell of each particle, in sorted order after a sort */
    amsph_buffer *cell_start;   /* GRID_SETS total_cells + 3 ints: first particle of each bucket
                                   (kernels/grid_geometry.h) */
    amsph_buffer *rank;         /* each particle's slot within its bucket (kernels/grid.cl
                                   grid_bin) */
    amsph_buffer *order;        /* sorted slot -> old index */
    amsph_buffer *chunk_total;  /* prefix-sum chunk totals */
    amsph_buffer *fluid_count;  /* an int per cell: its fluid particles (amsph_grid_count_fluid) */
    amsph_buffer *scratch[AMSPH_GRID_SCRATCH + 1];
    unsigned recomputed;        /* fields (bit per amsph_field_id) that the step recomputes for
                                   every particle after the sort before any kernel reads them:
                                   left unordered */
    int not_finite;             /* particles of the last sort whose position was not finite */
} amsph_grid;

/* Lays cells of side support / GRID_CELLS_PER_SUPPORT (a periodic axis's
 * last cell takes the remainder) over [lo, hi]; a periodic axis needs at
 * least 3 supports. */
int amsph_grid_init(amsph_grid *g, amsph_backend *b, int dim, const double lo[3],
                    const double hi[3], const int periodic[3], double support, int capacity);
/* The cell layout's refusals of amsph_grid_init (a periodic axis shorter
 * than 3 supports, more than 1e9 cells) without allocating anything. */
int amsph_grid_check_layout(int dim, const double lo[3], const double hi[3], const int periodic[3], double support);

/* Bins and sorts the particles, reorders every present field but those of
 * g->recomputed, and drops the particles that left the domain (p->n
 * shrinks, p->removed grows) and those whose position is not finite
 * (g->not_finite of them: evaporation marks the particles it removes so;
 * after a step's move they are a state that blew up, which no guard after
 * the sort could see). */
int amsph_grid_sort(amsph_grid *g, amsph_particles *p);

/* After a sort: g->fluid_count = the fluid particles of p in each cell
 * (kernels/grid.cl grid_fluid_mark), which kernels/neighbours.h
 * grid_fluid_in_box reads. */
int amsph_grid_count_fluid(amsph_grid *g, amsph_backend *b, const amsph_particles *p);

/* out = the exclusive prefix sum of the n ints of in (kernels/grid.cl; in and
 * out may be the same buffer), with chunk_total a scratch of AMSPH_SCAN_CHUNKS ints. */
#define AMSPH_SCAN_CHUNKS 1024
int amsph_exclusive_scan(amsph_backend *b, amsph_buffer *in, amsph_buffer *out, amsph_buffer *chunk_total, int n);
void amsph_grid_free(amsph_grid *g, amsph_backend *b);

#endif
