/* The sorted grid (VALIDATION.md K2): neighbour pairs from the cell loop
 * against brute force on random, clustered, single-cell, cell-face and
 * periodic inputs; the sort as a permutation that keeps every field with
 * its particle; removal of particles that leave the domain. Every backend,
 * 2D and 3D. */
#include <math.h>

#include "grid_fixture.h"

#define MAX_NEIGHBOURS 512

typedef struct {
    const char *name;
    int n;
    void (*place)(double *x, int n, int dim, unsigned long long *state);
    int periodic;
} input_case;

static const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {1.0, 0.8, 0.6};
static const double support = 0.1;

static void place_random(double *x, int n, int dim, unsigned long long *s)
{
    for (int i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d)
            x[3 * i + d] = d < dim ? lo[d] + (hi[d] - lo[d]) * testing_random(s) : 0.0;
}

/* Three tight clusters and a sparse background. */
static void place_clustered(double *x, int n, int dim, unsigned long long *s)
{
    static const double centres[3][3] = {{0.2, 0.2, 0.2}, {0.5, 0.41, 0.3}, {0.95, 0.75, 0.55}};
    for (int i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d) {
            const double c = centres[i % 3][d];
            double v = i % 7 == 0 ? lo[d] + (hi[d] - lo[d]) * testing_random(s)
                                  : c + 0.06 * (testing_random(s) - 0.5);
            v = fmin(fmax(v, lo[d]), hi[d]);
            x[3 * i + d] = d < dim ? v : 0.0;
        }
}

/* Every particle in one cell. */
static void place_one_cell(double *x, int n, int dim, unsigned long long *s)
{
    for (int i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d)
            x[3 * i + d] = d < dim ? 0.3 + 0.099 * testing_random(s) : 0.0;
}

/* Coordinates on cell faces (multiples of the cell size) and domain faces. */
static void place_on_faces(double *x, int n, int dim, unsigned long long *s)
{
    for (int i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d) {
            const int faces = (int)floor((hi[d] - lo[d]) / support);
            const double on_face = support * floor(testing_random(s) * (faces + 1));
            const double v = i % 2 ? fmin(on_face, hi[d]) : lo[d] + (hi[d] - lo[d]) * testing_random(s);
            x[3 * i + d] = d < dim ? v : 0.0;
        }
}

/* The walls (fixture_is_wall) anywhere, the fluid in a slab around x = 0.3
 * on a closed or a periodic axis: walls far from and near to it. */
static void place_fluid_slab(double *x, int n, int dim, unsigned long long *s)
{
    place_random(x, n, dim, s);
    for (int i = 0; i < n; ++i)
        if (!fixture_is_wall(i))
            x[3 * i] = 0.25 + 0.1 * testing_random(s);
}

static const input_case inputs[] = {
    {"random", 1500, place_random, 0},       {"clustered", 1200, place_clustered, 0},
    {"one cell", 300, place_one_cell, 0},     {"cell faces", 1000, place_on_faces, 0},
    {"periodic", 1500, place_random, 1},      {"periodic faces", 800, place_on_faces, 1},
    {"fluid slab", 1200, place_fluid_slab, 0}, {"periodic fluid slab", 1200, place_fluid_slab, 1},
};

/* r^2 of the nearest image, in double. */
static double distance2(const amsph_real *x, int a, int b, const int periodic[3])
{
    double r2 = 0.0;
    for (int d = 0; d < 3; ++d) {
        double r = (double)x[3 * a + d] - (double)x[3 * b + d];
        if (periodic[d]) {
            const double length = hi[d] - lo[d];
            r -= length * round(r / length);
        }
        r2 += r * r;
    }
    return r2;
}

static int contains(const unsigned *list, int count, unsigned id)
{
    for (int k = 0; k < count; ++k)
        if (list[k] == id)
            return 1;
    return 0;
}

/* Kernel neighbour lists against all pairs, over both sets of cells and
 * over the non-wall set alone (fixture_is_wall); pairs within 1e-5 of the
 * radius are ambiguous in float and not counted either way. */
/* The loop over sets 0 .. last_set against brute force; without a periodic
 * axis the box loop over set last_set too, and its order against the
 * trimmed loop's; the listing loop over both sets against the trimmed
 * loop's visits. */
static void check_pairs(grid_fixture *f, const input_case *in, const int periodic[3], int last_set)
{
    const int n = f->p.n;
    amsph_buffer *count_buf = NULL, *list_buf = NULL, *box_count_buf = NULL, *box_order_buf = NULL,
                 *within_buf = NULL;
    CHECK_OK(amsph_buffer_alloc(f->b, (size_t)n * sizeof(int), &count_buf));
    CHECK_OK(amsph_buffer_alloc(f->b, (size_t)n * sizeof(int), &box_count_buf));
    CHECK_OK(amsph_buffer_alloc(f->b, (size_t)n * sizeof(int), &box_order_buf));
    CHECK_OK(amsph_buffer_alloc(f->b, (size_t)n * sizeof(int), &within_buf));
    CHECK_OK(amsph_buffer_alloc(f->b, (size_t)n * MAX_NEIGHBOURS * sizeof(unsigned), &list_buf));
    CHECK_OK(AMSPH_LAUNCH(f->b, "neighbour_list", n, amsph_arg_buffer(f->p.field[AMSPH_FIELD_POSITION]),
                          amsph_arg_buffer(f->p.field[AMSPH_FIELD_ID]), amsph_arg_buffer(f->g.cell),
                          amsph_arg_int(n), fixture_geometry(f), amsph_arg_buffer(f->g.cell_start),
                          amsph_arg_real(support), amsph_arg_int(GRID_SET_BODIES), amsph_arg_int(last_set),
                          amsph_arg_int(MAX_NEIGHBOURS),
                          amsph_arg_buffer(count_buf), amsph_arg_buffer(list_buf),
                          amsph_arg_buffer(box_count_buf), amsph_arg_buffer(box_order_buf),
                          amsph_arg_buffer(within_buf)));
    amsph_host_particles h;
    CHECK_OK(amsph_particles_download(&f->p, &h));
    int *count = malloc((size_t)n * sizeof *count);
    unsigned *list = malloc((size_t)n * MAX_NEIGHBOURS * sizeof *list);
    CHECK_OK(amsph_download(f->b, count_buf, 0, (size_t)n * sizeof *count, count));
    CHECK_OK(amsph_download(f->b, list_buf, 0, (size_t)n * MAX_NEIGHBOURS * sizeof *list, list));
    int *box_count = malloc((size_t)n * sizeof *box_count), *box_order = malloc((size_t)n * sizeof *box_order);
    CHECK_OK(amsph_download(f->b, box_count_buf, 0, (size_t)n * sizeof *box_count, box_count));
    CHECK_OK(amsph_download(f->b, box_order_buf, 0, (size_t)n * sizeof *box_order, box_order));
    int *within_order = malloc((size_t)n * sizeof *within_order);
    CHECK_OK(amsph_download(f->b, within_buf, 0, (size_t)n * sizeof *within_order, within_order));
    const int any_periodic = periodic[0] || periodic[1] || periodic[2];
    const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
    const unsigned *id = h.data[AMSPH_FIELD_ID];
    long long missing = 0, extra = 0, pairs = 0;
    long long box_wrong = 0, box_pairs = 0, box_out_of_order = 0, within_out_of_order = 0;
    for (int a = 0; a < n; ++a) {
        CHECK(count[a] <= MAX_NEIGHBOURS, "%s: particle %u has %d neighbours", in->name, id[a], count[a]);
        const unsigned *mine = list + (size_t)a * MAX_NEIGHBOURS;
        int expected = 0, ambiguous = 0, in_set = 0, in_set_ambiguous = 0;
        for (int b = 0; b < n; ++b) {
            const int of_last_set = b != a && fixture_is_wall((int)id[b]) == (last_set == GRID_SET_WALLS);
            const double r_set = of_last_set ? sqrt(distance2(x, a, b, periodic)) : INFINITY;
            in_set_ambiguous += fabs(r_set - support) < 1e-5 * support;
            in_set += r_set < support && !(fabs(r_set - support) < 1e-5 * support);
            if (b == a || (last_set == GRID_SET_BODIES && fixture_is_wall((int)id[b])))
                continue;
            const double r = sqrt(distance2(x, a, b, periodic));
            const int listed = contains(mine, count[a], id[b]);
            if (fabs(r - support) < 1e-5 * support) {
                ambiguous += listed;
                continue;
            }
            if (r < support) {
                ++expected;
                missing += !listed;
            }
        }
        extra += count[a] - ambiguous - expected;
        pairs += expected;
        within_out_of_order += !within_order[a];
        /* the box loop over set last_set: no pair missed or extra, the trimmed loop's order */
        if (any_periodic) {
            box_wrong += box_count[a] != -1;
        } else {
            box_wrong += box_count[a] < in_set || box_count[a] > in_set + in_set_ambiguous;
            box_out_of_order += !box_order[a];
            box_pairs += in_set;
        }
    }
    CHECK(box_wrong == 0 && box_out_of_order == 0,
          "%s, %dD, set %d: the box loop miscounts %lld particles' neighbours (of %lld pairs), visits %lld out of "
          "the trimmed loop's order",
          in->name, f->dim, last_set, box_wrong, box_pairs, box_out_of_order);
    CHECK(within_out_of_order == 0, "%s, %dD: the listing loop visits %lld particles' neighbours out of the "
          "trimmed loop's order", in->name, f->dim, within_out_of_order);
    CHECK(any_periodic || box_pairs > n, "%s, %dD: the box loop found only %lld pairs", in->name, f->dim, box_pairs);
    CHECK(missing == 0 && extra == 0, "%s, %dD, sets 0-%d: %lld pairs missed, %lld extra, of %lld", in->name,
          f->dim, last_set, missing, extra, pairs);
    CHECK(pairs > n, "%s, %dD: only %lld pairs; the input does not test much", in->name, f->dim, pairs);
    free(box_count);
    free(box_order);
    free(within_order);
    free(count);
    free(list);
    amsph_host_free(&h);
    amsph_buffer_free(f->b, count_buf);
    amsph_buffer_free(f->b, list_buf);
    amsph_buffer_free(f->b, box_count_buf);
    amsph_buffer_free(f->b, box_order_buf);
    amsph_buffer_free(f->b, within_buf);
}

/* grid_fluid_in_box (kernels/neighbours.h) from amsph_grid_count_fluid: a
 * particle told no fluid is in its box has no fluid particle (not
 * fixture_is_wall) within the support, so a loop may skip it
 * (kernels/fluid.cl continuity); *told_none counts those. */
static void check_fluid_near(grid_fixture *f, const input_case *in, const int periodic[3], long long *told_none)
{
    const int n = f->p.n;
    amsph_buffer *near_buf = NULL;
    CHECK_OK(amsph_grid_count_fluid(&f->g, f->b, &f->p));
    CHECK_OK(amsph_buffer_alloc(f->b, (size_t)n * sizeof(int), &near_buf));
    CHECK_OK(AMSPH_LAUNCH(f->b, "fluid_in_box", n, amsph_arg_buffer(f->g.cell), amsph_arg_int(n),
                          fixture_geometry(f), amsph_arg_buffer(f->g.cell_start), amsph_arg_buffer(f->g.fluid_count),
                          amsph_arg_buffer(near_buf)));
    int *near = malloc((size_t)n * sizeof *near);
    CHECK_OK(amsph_download(f->b, near_buf, 0, (size_t)n * sizeof *near, near));
    amsph_host_particles h;
    CHECK_OK(amsph_particles_download(&f->p, &h));
    const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
    const unsigned *id = h.data[AMSPH_FIELD_ID];
    long long none = 0, wrong = 0;
    for (int a = 0; a < n; ++a) {
        if (near[a])
            continue;
        ++none;
        for (int b = 0; b < n; ++b)
            if (b != a && !fixture_is_wall((int)id[b]) && distance2(x, a, b, periodic) < support * support) {
                ++wrong;
                break;
            }
    }
    CHECK(wrong == 0, "%s, %dD: %lld particles told no fluid is near, of %lld told so, have fluid within the support",
          in->name, f->dim, wrong, none);
    *told_none += none;
    amsph_host_free(&h);
    amsph_buffer_free(f->b, near_buf);
    free(near);
}

static void test_neighbours(amsph_backend *b, int dim)
{
    long long told_none = 0;
    for (size_t k = 0; k < sizeof inputs / sizeof inputs[0]; ++k) {
        const input_case *in = &inputs[k];
        const int periodic[3] = {in->periodic, in->periodic && dim > 1, in->periodic && dim > 2};
        unsigned long long state = 1000 + k;
        double *x = malloc((size_t)in->n * 3 * sizeof *x);
        in->place(x, in->n, dim, &state);
        grid_fixture f;
        const int status = fixture_create(&f, b, dim, 0, x, in->n, lo, hi, periodic, support, 1.0);
        CHECK(status == 0, "%s: %s", in->name, amsph_last_error());
        if (status == 0) {
            CHECK(f.p.n == in->n, "%s: %d of %d particles kept", in->name, f.p.n, in->n);
            check_pairs(&f, in, periodic, GRID_SET_WALLS);
            check_pairs(&f, in, periodic, GRID_SET_BODIES);
            check_fluid_near(&f, in, periodic, &told_none);
        }
        fixture_free(&f);
        free(x);
    }
    fprintf(stderr, "%dD: grid_fluid_in_box found %lld particles with no fluid near\n", dim, told_none);
    CHECK(told_none > 0, "%dD: grid_fluid_in_box found no particle without fluid near: the inputs do not test it",
          dim);
}

/* Fields tagged by id before the sort must still match their id after it. */
static void test_sort_keeps_fields(amsph_backend *b, int dim)
{
    const int n = 2000;
    const int periodic[3] = {0, 0, 0};
    unsigned long long state = 7;
    double *x = malloc((size_t)n * 3 * sizeof *x);
    place_random(x, n, dim, &state);
    /* five particles leave the domain */
    for (int k = 0; k < 5; ++k)
        x[3 * (100 * k + 3) + k % dim] = k % 2 ? -0.25 : 5.0;
    amsph_host_particles h = {.n = n};
    static const amsph_field_id fields[] = {AMSPH_FIELD_POSITION, AMSPH_FIELD_VELOCITY,
                                            AMSPH_FIELD_DENSITY,  AMSPH_FIELD_KIND,
                                            AMSPH_FIELD_MATERIAL, AMSPH_FIELD_ID};
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; ++k)
        CHECK_OK(amsph_host_add_field(&h, fields[k]));
    for (int i = 0; i < n; ++i) {
        for (int d = 0; d < 3; ++d) {
            amsph_host_real(&h, AMSPH_FIELD_POSITION)[3 * i + d] = (amsph_real)x[3 * i + d];
            amsph_host_real(&h, AMSPH_FIELD_VELOCITY)[3 * i + d] = (amsph_real)(i * (d + 1));
        }
        amsph_host_real(&h, AMSPH_FIELD_DENSITY)[i] = (amsph_real)(1000 + i);
        ((int *)h.data[AMSPH_FIELD_KIND])[i] = i % 3;
        ((int *)h.data[AMSPH_FIELD_MATERIAL])[i] = i % 5;
        ((unsigned *)h.data[AMSPH_FIELD_ID])[i] = (unsigned)(n - 1 - i); /* ids not in index order */
    }
    amsph_particles p;
    amsph_grid g;
    CHECK_OK(amsph_particles_upload(b, &h, &p));
    CHECK_OK(amsph_grid_init(&g, b, dim, lo, hi, periodic, support, n));
    CHECK_OK(amsph_grid_sort(&g, &p));
    CHECK_OK(amsph_grid_sort(&g, &p)); /* a second sort of sorted input changes nothing */
    CHECK(p.n == n - 5 && p.removed == 5, "kept %d, removed %lld; expected %d and 5", p.n, p.removed, n - 5);

    amsph_host_particles s;
    CHECK_OK(amsph_particles_download(&p, &s));
    int *cell = malloc((size_t)p.n * sizeof *cell), *bucket = malloc((size_t)p.n * sizeof *bucket);
    const int departed = grid_departed_bucket(&g.geometry);
    int *start = malloc(((size_t)departed + 2) * sizeof *start);
    CHECK_OK(amsph_download(b, g.cell, 0, (size_t)p.n * sizeof *cell, cell));
    CHECK_OK(amsph_download(b, g.cell_start, 0, ((size_t)departed + 2) * sizeof *start, start));
    char *seen = calloc((size_t)n, 1);
    int bad_fields = 0, bad_order = 0, bad_cells = 0;
    const unsigned *id = s.data[AMSPH_FIELD_ID];
    for (int k = 0; k < p.n; ++k) {
        const int i = n - 1 - (int)id[k]; /* original index */
        seen[i]++;
        for (int d = 0; d < 3; ++d) {
            bad_fields += amsph_host_real(&s, AMSPH_FIELD_POSITION)[3 * k + d] != (amsph_real)x[3 * i + d];
            bad_fields += amsph_host_real(&s, AMSPH_FIELD_VELOCITY)[3 * k + d] != (amsph_real)(i * (d + 1));
        }
        bad_fields += amsph_host_real(&s, AMSPH_FIELD_DENSITY)[k] != (amsph_real)(1000 + i);
        bad_fields += ((int *)s.data[AMSPH_FIELD_KIND])[k] != i % 3;
        bad_fields += ((int *)s.data[AMSPH_FIELD_MATERIAL])[k] != i % 5;
        bad_cells += !(cell[k] >= 0 && cell[k] < g.geometry.total_cells);
        bucket[k] = grid_bucket(&g.geometry, cell[k], i % 3 == KIND_WALL ? GRID_SET_WALLS : GRID_SET_BODIES);
        bad_cells += grid_cell_of_bucket(&g.geometry, bucket[k]) != cell[k];
        bad_cells += !(start[bucket[k]] <= k && k < start[bucket[k] + 1]);
        if (k > 0)
            bad_order += bucket[k] < bucket[k - 1] || (bucket[k] == bucket[k - 1] && id[k] <= id[k - 1]);
    }
    int duplicates = 0;
    for (int i = 0; i < n; ++i)
        duplicates += seen[i] > 1;
    CHECK(bad_fields == 0, "%dD: %d field values separated from their particle", dim, bad_fields);
    CHECK(duplicates == 0, "%dD: %d particles appear twice", dim, duplicates);
    CHECK(bad_cells == 0, "%dD: %d particles outside their cell range", dim, bad_cells);
    CHECK(bad_order == 0, "%dD: %d particles out of (row, set, cell, id) order", dim, bad_order);
    CHECK(start[departed] == p.n, "%dD: cell ranges end at %d, not %d", dim, start[departed], p.n);
    free(seen);
    free(bucket);
    free(cell);
    free(start);
    /* a position that is not finite is dropped and counted apart from the
     * departures (evaporation marks its particles so; a step refuses it) */
    amsph_host_real(&h, AMSPH_FIELD_POSITION)[3 * 777] = (amsph_real)NAN;
    amsph_particles_free(&p);
    CHECK_OK(amsph_particles_upload(b, &h, &p));
    CHECK_OK(amsph_grid_sort(&g, &p));
    CHECK(p.n == n - 6 && p.removed == 5 && g.not_finite == 1,
          "%dD: with a NaN position kept %d, removed %lld, %d not finite; expected %d, 5 and 1", dim, p.n,
          p.removed, g.not_finite, n - 6);
    free(x);
    amsph_host_free(&h);
    amsph_host_free(&s);
    amsph_grid_free(&g, b);
    amsph_particles_free(&p);
}

/* A periodic axis shorter than three supports is refused with a message. */
static void test_periodic_too_short(amsph_backend *b)
{
    amsph_grid g;
    const int periodic[3] = {1, 0, 0};
    const double short_hi[3] = {0.25, 1.0, 0.0};
    CHECK(amsph_grid_init(&g, b, 2, lo, short_hi, periodic, support, 10) != 0, "accepted");
    CHECK(strstr(amsph_last_error(), "periodic axis x") != NULL, "message: %s", amsph_last_error());
    amsph_grid_free(&g, b);
}

int main(void)
{
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_backend *b = testing_backend(k);
        if (!b)
            continue;
        fprintf(stderr, "backend: %s\n", b->description);
        for (int dim = 2; dim <= 3; ++dim) {
            test_neighbours(b, dim);
            test_sort_keeps_fields(b, dim);
        }
        test_periodic_too_short(b);
        amsph_backend_destroy(b);
    }
    return testing_finish();
}
