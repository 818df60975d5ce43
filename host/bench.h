/* `amsph bench`: measurements, never assertions. */
#ifndef AMSPH_BENCH_H
#define AMSPH_BENCH_H

#include <stdio.h>

#include "backend.h"
#include "case.h"

/* Times the sorted-grid build (bin, counting sort, reorder of the fields of a
 * fluid scene) for n particles at random in a unit cube, 3D, Wendland C2,
 * h = 1.2 dx: once from random order, then `repeat` times on sorted input
 * (the steady state of a simulation). Prints a Markdown table row. */
int amsph_bench_grid(amsph_backend *b, long long n, int repeat, FILE *out);

#define AMSPH_BENCH_MAX_COUNTS 32

typedef struct {
    long long particles[AMSPH_BENCH_MAX_COUNTS]; /* particle counts to scale the case to */
    int n_particles;                             /* 0: the case as it is */
    int warmup;                                  /* steps before the timing */
    int steps;                                   /* timed steps */
    FILE *csv;                                   /* non-NULL: a CSV table too */
    int kernels;                                 /* 1: `steps` more with each kernel timed */
} amsph_bench_options;

/* Throughput of the case's time step: for each particle count, the case at
 * the spacing that gives about that many particles, `warmup` steps, then
 * `steps` steps timed as a whole (particle-steps per second) and `steps`
 * more with the per-phase timers on (host/timers.h: ms per step of each
 * module). Prints a Markdown table with the device bytes per particle, and
 * the least-squares exponent of time per step against the particle count.
 * With o->kernels, `steps` more with every launch waited for and timed
 * (amsph_kernel_profile), and a table of the kernels for each count. */
int amsph_bench_throughput(amsph_backend *b, const amsph_case *c, const amsph_bench_options *o, FILE *out);

/* The compiler and precision of this build, for benchmark tables. */
const char *amsph_bench_build(void);

#endif
