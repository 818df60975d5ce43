/* `amsph bench`: measurements, never assertions. */
#ifndef AMSPH_BENCH_H
#define AMSPH_BENCH_H

#include <stdio.h>

#include "backend.h"

/* Times the sorted-grid build (bin, counting sort, reorder of the fields of a
 * fluid scene) for n particles at random in a unit cube, 3D, Wendland C2,
 * h = 1.2 dx: once from random order, then `repeat` times on sorted input
 * (the steady state of a simulation). Prints a Markdown table row. */
int amsph_bench_grid(amsph_backend *b, long long n, int repeat, FILE *out);

#endif
