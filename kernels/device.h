/* Portability layer: every file in kernels/ is OpenCL C 1.2 and, through this
 * header, C11 that the OpenMP backend compiles.
 *
 * Build-time constants (the OpenCL build passes them as -D options, the C
 * build as compiler flags):
 *   AMSPH_DIM     2 or 3
 *   AMSPH_DOUBLE  1 for double precision, 0 for float
 *
 * Rules for kernel code, so that both worlds accept it:
 *   - a kernel is `KERNEL void name(args)` on one declaration; buffer
 *     arguments are `GLOBAL T *`, others are passed by value;
 *   - the work-item loop is `FOR_EACH_ITEM(i, n) { ... }`, with no `return`
 *     or `continue` at its top level (the C form is an OpenMP `for`);
 *   - helpers are `static inline`; no vector-type arithmetic (float4 + float4),
 *     use scalar components;
 *   - a pair loop gathers: item a reads b and writes only a, so no atomics
 *     are needed except in the grid's histogram and scatter. */
#ifndef AMSPH_DEVICE_H
#define AMSPH_DEVICE_H

#ifndef AMSPH_DIM
#error "AMSPH_DIM must be defined (2 or 3)"
#endif

#ifdef __OPENCL_VERSION__

#if AMSPH_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif
#define KERNEL __kernel
#define GLOBAL __global
#define FOR_EACH_ITEM(i, n)                                                                        \
    const int i = (int)get_global_id(0);                                                           \
    if (i < (n))
#define ATOMIC_INC(p) atomic_inc(p)

#else /* C11 for the OpenMP backend */

#include <tgmath.h> /* sqrt, fmax, ... on `real` as in OpenCL */
#define KERNEL static
#define GLOBAL
#ifdef _OPENMP
#define FOR_EACH_ITEM(i, n)                                                                        \
    _Pragma("omp parallel for schedule(static)") for (int i = 0; i < (n); ++i)
#else
#define FOR_EACH_ITEM(i, n) for (int i = 0; i < (n); ++i)
#endif
#define ATOMIC_INC(p) __atomic_fetch_add((p), 1, __ATOMIC_RELAXED)
typedef unsigned int uint;

#endif

#if AMSPH_DOUBLE
typedef double real;
#define REAL(x) (x)
#else
typedef float real;
#define REAL(x) (x##f)
#endif

#define PI_REAL REAL(3.14159265358979323846)

#include "grid_geometry.h"

#endif
