/* A simulation: the case, its particles on a backend, the sorted grid and
 * the time loop assembled from the case's modules. */
#ifndef AMSPH_SIM_H
#define AMSPH_SIM_H

#include "backend.h"
#include "case.h"
#include "grid.h"
#include "particles.h"

typedef struct {
    amsph_case config;
    amsph_backend *backend; /* not owned */
    amsph_particles particles;
    amsph_grid grid;
    amsph_buffer *work; /* one real per particle, for reductions */
    double h;           /* smoothing length, m */
    double support;     /* kernel support radius, m */
    double time;        /* s */
    double dt;          /* last step, s */
    long long step;
} amsph_sim;

/* Kernel support radius / h: 2 (Wendland C2) or 3 (quintic spline). */
double amsph_support_over_h(amsph_kernel_type kernel);

/* Builds the scene of the case on backend b (kernels built for the case's
 * dimension and smoothing kernel), sorts it and evaluates the initial forces. */
int amsph_sim_create(const amsph_case *c, amsph_backend *b, amsph_sim *s);
void amsph_sim_free(amsph_sim *s);

/* The step the stability limits allow now, s. */
int amsph_sim_stable_dt(amsph_sim *s, double *dt);
/* Advances by dt (kick-drift-kick). */
int amsph_sim_step(amsph_sim *s, double dt);

typedef struct {
    const char *outdir;
    int quiet;
} amsph_run_options;

/* Runs to the case's end time, writing snapshots at t = 0, every output
 * interval and at the end, and reporting progress on stderr. */
int amsph_sim_run(amsph_sim *s, const amsph_run_options *options);

#endif
