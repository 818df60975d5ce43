/* The OpenMP backend's view of the kernels: the generated table (see
 * cmake/embed_kernels.c) maps each kernel name to a trampoline that unpacks
 * amsph_omp_arg values into the C function compiled from kernels/. */
#ifndef AMSPH_BACKEND_OPENMP_TABLE_H
#define AMSPH_BACKEND_OPENMP_TABLE_H

#include <stddef.h>

typedef struct {
    void *pointer;     /* buffer data, or NULL for a value */
    const void *value; /* the value's bytes */
    size_t size;
} amsph_omp_arg;

/* Returns 0, or k+1 when argument k has the wrong size. */
typedef int (*amsph_omp_trampoline)(const amsph_omp_arg *args);

typedef struct {
    const char *name;
    int nargs;
    amsph_omp_trampoline run;
} amsph_omp_kernel;

/* One table per (dimension, smoothing kernel); ends with a NULL name. */
extern const amsph_omp_kernel amsph_omp_kernels_2_0[], amsph_omp_kernels_2_1[],
    amsph_omp_kernels_3_0[], amsph_omp_kernels_3_1[];

#endif
