/* Running a whole case in a test (with the harness of testing.h). */
#ifndef AMSPH_TESTING_RUN_H
#define AMSPH_TESTING_RUN_H

#include <math.h>

#include "sim.h"
#include "testing.h"

/* Runs case c on backend k (0: OpenMP, 1: OpenCL) from its start to time
 * `until` (0: the initial state) and downloads the particles into h;
 * non-zero where the backend is missing or the run failed (a failed check). */
static inline int testing_run_case(const amsph_case *c, int k, double until, amsph_host_particles *h)
{
    amsph_backend *b = testing_backend(k);
    if (!b)
        return 1;
    amsph_sim s;
    int status = amsph_sim_create(c, b, &s);
    if (status == 0 && until > 0.0)
        status = amsph_sim_advance(&s, until, NULL, NULL);
    CHECK(status == 0, "%s", amsph_last_error());
    if (status == 0) {
        status = amsph_particles_download(&s.particles, h);
        CHECK(status == 0, "%s", amsph_last_error());
    }
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
    return status;
}

/* Replaces the sim's particles with h (freed here) and sorts the grid again,
 * for a test that moves or changes particles between steps. */
static inline int testing_replace_particles(amsph_sim *s, amsph_host_particles *h)
{
    amsph_particles_free(&s->particles);
    const int status = amsph_particles_upload(s->backend, h, &s->particles);
    amsph_host_free(h);
    AMSPH_CHECK(status);
    return amsph_grid_sort(&s->grid, &s->particles);
}

/* The largest magnitude of field f over set a, and the largest difference
 * between a and b (the same particles in the same order: two backends' runs
 * of one case), over every component. */
static inline void testing_field_difference(const amsph_host_particles *a, const amsph_host_particles *b,
                                            amsph_field_id f, double *largest, double *diff)
{
    const int comps = amsph_fields[f].components;
    const amsph_real *x = amsph_host_real(a, f), *y = amsph_host_real(b, f);
    *largest = *diff = 0.0;
    for (int i = 0; i < comps * a->n; ++i) {
        *largest = fmax(*largest, fabs(x[i]));
        *diff = fmax(*diff, fabs(x[i] - y[i]));
    }
}

#endif
