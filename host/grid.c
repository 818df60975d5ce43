#include "grid.h"

#include <math.h>
#include <string.h>

#include "error.h"

static const char axis_name[3] = {'x', 'y', 'z'};

static int layout_cells(amsph_grid *g, int dim, const double lo[3], const double hi[3],
                        const int periodic[3], double support)
{
    grid_geometry *geo = &g->geometry;
    memset(geo, 0, sizeof *geo);
    const double cell_size = support / GRID_CELLS_PER_SUPPORT;
    geo->cell_size = (amsph_real)cell_size;
    geo->total_cells = 1;
    for (int d = 0; d < 3; ++d) {
        geo->ncell[d] = 1;
        if (d >= dim)
            continue;
        const double length = hi[d] - lo[d];
        geo->lo[d] = (amsph_real)lo[d];
        geo->length[d] = (amsph_real)length;
        geo->periodic[d] = periodic[d];
        const double cells = length / cell_size;
        if (periodic[d]) {
            if (length < 3.0 * support)
                return amsph_bad_input("periodic axis %c: the domain length %g m is shorter than 3 "
                                  "kernel supports (%g m); enlarge the domain or refine dx",
                                  axis_name[d], length, 3.0 * support);
            geo->ncell[d] = (int)floor(cells);
        } else {
            geo->ncell[d] = cells < 1.0 ? 1 : (int)ceil(cells);
        }
        if ((double)GRID_SETS * geo->total_cells * geo->ncell[d] > 2.0e9)
            return amsph_bad_input("the grid would need more than 1e9 cells; shrink the domain");
        geo->total_cells *= geo->ncell[d];
    }
    return 0;
}

int amsph_grid_check_layout(int dim, const double lo[3], const double hi[3], const int periodic[3], double support)
{
    amsph_grid g;
    memset(&g, 0, sizeof g);
    return layout_cells(&g, dim, lo, hi, periodic, support);
}

int amsph_grid_init(amsph_grid *g, amsph_backend *b, int dim, const double lo[3],
                    const double hi[3], const int periodic[3], double support, int capacity)
{
    memset(g, 0, sizeof *g);
    g->dim = dim;
    g->capacity = capacity;
    AMSPH_CHECK(layout_cells(g, dim, lo, hi, periodic, support));
    const size_t buckets = (size_t)grid_not_finite_bucket(&g->geometry) + 1;
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * sizeof(int), &g->cell));
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * sizeof(int), &g->order));
    AMSPH_CHECK(amsph_buffer_alloc(b, (buckets + 1) * sizeof(int), &g->cell_start));
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)capacity * sizeof(int), &g->rank));
    AMSPH_CHECK(amsph_buffer_alloc(b, AMSPH_SCAN_CHUNKS * sizeof(int), &g->chunk_total));
    AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)g->geometry.total_cells * sizeof(int), &g->fluid_count));
    return 0;
}

void amsph_grid_free(amsph_grid *g, amsph_backend *b)
{
    amsph_buffer_free(b, g->cell);
    amsph_buffer_free(b, g->order);
    amsph_buffer_free(b, g->cell_start);
    amsph_buffer_free(b, g->rank);
    amsph_buffer_free(b, g->chunk_total);
    amsph_buffer_free(b, g->fluid_count);
    for (int w = 0; w <= AMSPH_GRID_SCRATCH; ++w)
        amsph_buffer_free(b, g->scratch[w]);
    memset(g, 0, sizeof *g);
}

static int fill_zero(amsph_backend *b, amsph_buffer *buf, int n)
{
    return AMSPH_LAUNCH(b, "fill_words", n, amsph_arg_buffer(buf), amsph_arg_int(n),
                        amsph_arg_uint(0));
}

int amsph_exclusive_scan(amsph_backend *b, amsph_buffer *in, amsph_buffer *out, amsph_buffer *chunk_total, int n)
{
    const int chunk = (n + AMSPH_SCAN_CHUNKS - 1) / AMSPH_SCAN_CHUNKS;
    const int nchunks = (n + chunk - 1) / chunk;
    AMSPH_CHECK(AMSPH_LAUNCH(b, "scan_chunks", nchunks, amsph_arg_buffer(in), amsph_arg_int(n),
                             amsph_arg_int(chunk), amsph_arg_int(nchunks), amsph_arg_buffer(out),
                             amsph_arg_buffer(chunk_total)));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "scan_totals", 1, amsph_arg_buffer(chunk_total), amsph_arg_int(nchunks)));
    return AMSPH_LAUNCH(b, "scan_add", nchunks, amsph_arg_buffer(out), amsph_arg_int(n), amsph_arg_int(chunk),
                        amsph_arg_int(nchunks), amsph_arg_buffer(chunk_total));
}

/* Reorders one buffer of `words` 32-bit words per particle by g->order,
 * through a scratch buffer of the same size that it then swaps with. */
static int reorder(amsph_grid *g, amsph_backend *b, amsph_buffer **field, int words, int n)
{
    if (words > AMSPH_GRID_SCRATCH)
        return amsph_fail("grid: a field of %d words per particle is too wide to reorder", words);
    amsph_buffer **scratch = &g->scratch[words];
    if (!*scratch)
        AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)g->capacity * (size_t)words * 4, scratch));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "gather_words", n, amsph_arg_buffer(*field),
                             amsph_arg_buffer(*scratch), amsph_arg_buffer(g->order),
                             amsph_arg_int(n), amsph_arg_int(words)));
    amsph_buffer *sorted = *scratch;
    *scratch = *field;
    *field = sorted;
    return 0;
}

int amsph_grid_sort(amsph_grid *g, amsph_particles *p)
{
    amsph_backend *b = p->backend;
    const int n = p->n;
    if (n > g->capacity)
        return amsph_fail("grid: %d particles exceed the grid's capacity of %d", n, g->capacity);
    const int departed = grid_departed_bucket(&g->geometry), buckets = grid_not_finite_bucket(&g->geometry) + 1;
    const amsph_arg geometry = amsph_arg_bytes(&g->geometry, sizeof g->geometry);
    /* the histogram in cell_start, scanned in place: no array of the buckets' size but
     * cell_start (at 1e6 particles of the 3D dam break, 8 million buckets, 36 bytes per
     * particle each) */
    AMSPH_CHECK(fill_zero(b, g->cell_start, buckets + 1));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "grid_bin", n, amsph_arg_buffer(p->field[AMSPH_FIELD_POSITION]),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]), amsph_arg_int(n), geometry,
                             amsph_arg_buffer(g->cell), amsph_arg_buffer(g->cell_start),
                             amsph_arg_buffer(g->rank)));
    AMSPH_CHECK(amsph_exclusive_scan(b, g->cell_start, g->cell_start, g->chunk_total, buckets + 1));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "grid_scatter", n, amsph_arg_buffer(g->cell), amsph_arg_buffer(g->rank),
                             amsph_arg_int(n), amsph_arg_buffer(g->cell_start), amsph_arg_buffer(g->order)));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "grid_order_cells", buckets, amsph_arg_buffer(g->order),
                             amsph_arg_buffer(g->cell_start), amsph_arg_int(buckets),
                             amsph_arg_buffer(p->field[AMSPH_FIELD_ID])));
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f)
        if (p->field[f] && !(g->recomputed & (1u << f)))
            AMSPH_CHECK(reorder(g, b, &p->field[f], (int)(amsph_field_bytes((amsph_field_id)f) / 4), n));
    AMSPH_CHECK(reorder(g, b, &g->cell, 1, n));

    int ends[2]; /* of the particles kept and of those that left the domain */
    AMSPH_CHECK(amsph_download(b, g->cell_start, (size_t)departed * sizeof(int), sizeof ends, ends));
    const int kept = ends[0];
    g->not_finite = n - ends[1];
    AMSPH_CHECK(AMSPH_LAUNCH(b, "grid_cells_of_buckets", kept, amsph_arg_buffer(g->cell), amsph_arg_int(kept),
                             geometry));
    p->removed += ends[1] - kept;
    p->n = kept;
    return 0;
}

int amsph_grid_count_fluid(amsph_grid *g, amsph_backend *b, const amsph_particles *p)
{
    const int cells = g->geometry.total_cells;
    AMSPH_CHECK(AMSPH_LAUNCH(b, "fill_words", cells, amsph_arg_buffer(g->fluid_count), amsph_arg_int(cells),
                             amsph_arg_uint(0)));
    return AMSPH_LAUNCH(b, "grid_fluid_mark", p->n, amsph_arg_buffer(p->field[AMSPH_FIELD_KIND]),
                        amsph_arg_buffer(g->cell), amsph_arg_int(p->n),
                        amsph_arg_bytes(&g->geometry, sizeof g->geometry), amsph_arg_buffer(g->fluid_count));
}
