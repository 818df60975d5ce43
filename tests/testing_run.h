/* Running a whole case in a test (with the harness of testing.h). */
#ifndef AMSPH_TESTING_RUN_H
#define AMSPH_TESTING_RUN_H

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

#endif
