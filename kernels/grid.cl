/* Sorted particle grid, built on the device by a counting sort:
 *   grid_bin        wrap periodic coordinates, bucket of each particle (its cell
 *                   in the set of its kind, kernels/grid_geometry.h), histogram
 *   scan_*          exclusive prefix sum of the histogram → cell_start
 *   grid_scatter    each particle to a slot of its cell
 *   grid_order_cells  within a cell, slots ordered by global id (deterministic)
 *   gather_words    reorder a field by the permutation
 *   grid_cells_of_buckets  the sorted buckets back to cells
 *   grid_fluid_mark the fluid particles per cell (kernels/neighbours.h grid_fluid_in_box)
 * Cells are numbered x fastest; the two last buckets collect particles that
 * left the domain and those whose position is not finite: they sort to the
 * end and the host drops them, counting each kind. */
#include "device.h"
#include "kinds.h"
#include "neighbours.h"

KERNEL void fill_words(GLOBAL uint *buffer, int n, uint value)
{
    FOR_EACH_ITEM(i, n) { buffer[i] = value; }
}

KERNEL void copy_words(GLOBAL const uint *src, GLOBAL uint *dst, int n)
{
    FOR_EACH_ITEM(i, n) { dst[i] = src[i]; }
}

/* Axis cell of coordinate x, or -1 outside [lo, lo + length] (NaN included). */
static inline int grid_axis_cell(const grid_geometry *g, int d, real x)
{
    const real s = (x - g->lo[d]) / g->cell_size;
    if (!(s >= REAL(0.0)) || !(x <= g->lo[d] + g->length[d]))
        return -1;
    const int c = (int)s;
    return c < g->ncell[d] ? c : g->ncell[d] - 1;
}

/* m h of the fluid and solid particles outside the domain along a closed
 * axis, which the next sort drops, and 0 for the others: the enthalpy that
 * leaves the domain with them, for the thermal module's energy ledger. */
KERNEL void departing_enthalpy(GLOBAL const real *position, GLOBAL const int *kind, GLOBAL const real *mass,
                               GLOBAL const real *enthalpy, int n, grid_geometry g, GLOBAL real *out)
{
    FOR_EACH_ITEM(i, n)
    {
        int outside = 0;
        for (int d = 0; d < AMSPH_DIM; ++d)
            outside |= !g.periodic[d] && grid_axis_cell(&g, d, position[3 * i + d]) < 0;
        out[i] = outside && kind[i] != KIND_WALL ? mass[i] * enthalpy[i] : REAL(0.0);
    }
}

/* The bucket of each particle, the histogram of the buckets (count, zeroed
 * before), and each particle's slot within its bucket, in the order the
 * increments happened to run (grid_order_cells makes the order
 * deterministic). */
KERNEL void grid_bin(GLOBAL real *position, GLOBAL const int *kind, int n, grid_geometry g,
                     GLOBAL int *bucket_of, GLOBAL int *count, GLOBAL int *rank)
{
    FOR_EACH_ITEM(i, n)
    {
        int index = 0;
        int stride = 1;
        int finite = 1;
        for (int d = 0; d < AMSPH_DIM; ++d) {
            real x = position[3 * i + d];
            finite = finite && isfinite(x);
            if (g.periodic[d]) {
                const real hi = g.lo[d] + g.length[d];
                if (x < g.lo[d])
                    x += g.length[d];
                else if (x >= hi)
                    x -= g.length[d];
                position[3 * i + d] = x;
            }
            const int c = grid_axis_cell(&g, d, x);
            index = (c < 0 || index < 0) ? -1 : index + c * stride;
            stride *= g.ncell[d];
        }
        const int set = kind[i] == KIND_WALL ? GRID_SET_WALLS : GRID_SET_BODIES;
        const int bucket = !finite    ? grid_not_finite_bucket(&g)
                           : index < 0 ? grid_departed_bucket(&g)
                                       : grid_bucket(&g, index, set);
        bucket_of[i] = bucket;
        rank[i] = ATOMIC_INC(&count[bucket]);
    }
}

/* The cell of each sorted particle from its bucket (grid_bin). */
KERNEL void grid_cells_of_buckets(GLOBAL int *cell, int n, grid_geometry g)
{
    FOR_EACH_ITEM(i, n) { cell[i] = grid_cell_of_bucket(&g, cell[i]); }
}

/* Exclusive prefix sum in three passes over chunks of `chunk` entries:
 * each item scans its chunk, one item scans the chunk totals, each item adds
 * its chunk's offset. count and offset may be the same buffer. */
KERNEL void scan_chunks(GLOBAL const int *count, int n, int chunk, int nchunks, GLOBAL int *offset,
                        GLOBAL int *chunk_total)
{
    FOR_EACH_ITEM(k, nchunks)
    {
        const int begin = k * chunk;
        const int end = begin + chunk < n ? begin + chunk : n;
        int sum = 0;
        for (int j = begin; j < end; ++j) {
            const int c = count[j];
            offset[j] = sum;
            sum += c;
        }
        chunk_total[k] = sum;
    }
}

KERNEL void scan_totals(GLOBAL int *chunk_total, int nchunks)
{
    FOR_EACH_ITEM(k, 1)
    {
        int sum = 0;
        for (int j = 0; j < nchunks; ++j) {
            const int t = chunk_total[j];
            chunk_total[j] = sum;
            sum += t;
        }
    }
}

KERNEL void scan_add(GLOBAL int *offset, int n, int chunk, int nchunks,
                     GLOBAL const int *chunk_total)
{
    FOR_EACH_ITEM(k, nchunks)
    {
        const int begin = k * chunk;
        const int end = begin + chunk < n ? begin + chunk : n;
        for (int j = begin; j < end; ++j)
            offset[j] += chunk_total[k];
    }
}

/* Each particle to its slot in the sorted order: its bucket's start plus
 * its rank within the bucket (grid_bin). */
KERNEL void grid_scatter(GLOBAL const int *cell, GLOBAL const int *rank, int n, GLOBAL const int *cell_start,
                         GLOBAL int *order)
{
    FOR_EACH_ITEM(i, n) { order[cell_start[cell[i]] + rank[i]] = i; }
}

/* The ranks' order within a cell depends on thread timing; sorting each
 * cell's slots by global id makes the result deterministic on every backend. */
KERNEL void grid_order_cells(GLOBAL int *order, GLOBAL const int *cell_start, int nbuckets,
                             GLOBAL const uint *id)
{
    FOR_EACH_ITEM(c, nbuckets)
    {
        const int begin = cell_start[c];
        const int end = cell_start[c + 1];
        for (int j = begin + 1; j < end; ++j) {
            const int moving = order[j];
            const uint key = id[moving];
            int k = j - 1;
            while (k >= begin && id[order[k]] > key) {
                order[k + 1] = order[k];
                --k;
            }
            order[k + 1] = moving;
        }
    }
}

/* dst[i] = src[order[i]] for a field of `words` 32-bit words per particle. */
KERNEL void gather_words(GLOBAL const uint *src, GLOBAL uint *dst, GLOBAL const int *order, int n,
                         int words)
{
    FOR_EACH_ITEM(i, n)
    {
        const int from = order[i];
        for (int w = 0; w < words; ++w)
            dst[words * i + w] = src[words * from + w];
    }
}

/* count[c] = the fluid particles in cell c (count zeroed before). */
KERNEL void grid_fluid_mark(GLOBAL const int *kind, GLOBAL const int *cell, int n, grid_geometry g,
                            GLOBAL int *count)
{
    FOR_EACH_ITEM(a, n)
    {
        if (kind[a] == KIND_FLUID && cell[a] >= 0 && cell[a] < g.total_cells)
            ATOMIC_INC(&count[cell[a]]);
    }
}
