/* Particles at given positions on a backend, sorted on a grid: the fixture
 * of the grid and neighbour tests. */
#ifndef AMSPH_GRID_FIXTURE_H
#define AMSPH_GRID_FIXTURE_H

#include "grid.h"
#include "particles.h"
#include "kinds.h"
#include "testing.h"

typedef struct {
    amsph_backend *b;
    amsph_particles p;
    amsph_grid g;
    int dim;
} grid_fixture;

/* Is the particle of fixture index (and id) i a wall? */
static inline int fixture_is_wall(int i)
{
    return i % 3 == 1;
}

/* n positions (x, y, z each), unit mass and density 1/dx^dim so V = dx^dim;
 * every third particle (i % 3 == 1) a wall, so that the loops cross both
 * sets of cells (kernels/grid_geometry.h), the others fluid. */
static inline int fixture_create(grid_fixture *f, amsph_backend *b, int dim, int kernel,
                                 const double *x, int n, const double lo[3], const double hi[3],
                                 const int periodic[3], double support, double volume)
{
    memset(f, 0, sizeof *f);
    f->b = b;
    f->dim = dim;
    const amsph_build_options build = {.dim = dim, .kernel = kernel};
    AMSPH_CHECK(amsph_build(b, &build));
    amsph_host_particles h = {.n = n};
    static const amsph_field_id fields[] = {AMSPH_FIELD_POSITION, AMSPH_FIELD_MASS, AMSPH_FIELD_DENSITY,
                                            AMSPH_FIELD_KIND, AMSPH_FIELD_ID};
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; ++k)
        AMSPH_CHECK(amsph_host_add_field(&h, fields[k]));
    for (int i = 0; i < n; ++i) {
        for (int d = 0; d < 3; ++d)
            amsph_host_real(&h, AMSPH_FIELD_POSITION)[3 * i + d] = (amsph_real)x[3 * i + d];
        amsph_host_real(&h, AMSPH_FIELD_MASS)[i] = (amsph_real)1.0;
        amsph_host_real(&h, AMSPH_FIELD_DENSITY)[i] = (amsph_real)(1.0 / volume);
        ((int *)h.data[AMSPH_FIELD_KIND])[i] = fixture_is_wall(i) ? KIND_WALL : KIND_FLUID;
        ((unsigned *)h.data[AMSPH_FIELD_ID])[i] = (unsigned)i;
    }
    int status = amsph_particles_upload(b, &h, &f->p);
    amsph_host_free(&h);
    AMSPH_CHECK(status);
    AMSPH_CHECK(amsph_grid_init(&f->g, b, dim, lo, hi, periodic, support, n));
    return amsph_grid_sort(&f->g, &f->p);
}

static inline void fixture_free(grid_fixture *f)
{
    amsph_grid_free(&f->g, f->b);
    amsph_particles_free(&f->p);
}

static inline amsph_arg fixture_geometry(const grid_fixture *f)
{
    return amsph_arg_bytes(&f->g.geometry, sizeof f->g.geometry);
}

#endif
