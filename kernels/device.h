/* Portability layer: every file in kernels/ is OpenCL C 1.2 and, through this
 * header, C11 that the OpenMP backend compiles.
 *
 * Build-time constants (the OpenCL build passes them as -D options, the C
 * build as compiler flags):
 *   AMSPH_DIM     2 or 3
 *   AMSPH_DOUBLE  1 for double precision, 0 for float
 *   AMSPH_OMP_OFFLOAD  1 where the C build's loops run on an OpenMP target
 *                 device (CMake AMSPH_OPENMP_OFFLOAD), 0 or undefined otherwise
 *
 * Rules for kernel code, so that both worlds accept it:
 *   - a kernel is `KERNEL void name(args)` on one declaration; buffer
 *     arguments are `GLOBAL T *`, others are passed by value;
 *   - the work-item loop is `FOR_EACH_ITEM(i, n) { ... }`, with no `return`
 *     or `continue` at its top level (the C form is an OpenMP `for`);
 *   - helpers are `static inline` (PAIR_INLINE for the body of a pair loop,
 *     which the C compiler would otherwise call); no vector-type arithmetic (float4 + float4),
 *     use scalar components; no file-scope variables (an offloaded loop
 *     reaches only the kernel's arguments and locals);
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
#if defined(_OPENMP) && AMSPH_OMP_OFFLOAD
/* Each loop is a target region on the default device. Every buffer has a
 * device copy associated with its host addresses (host/backend_openmp.c), and
 * a pointer used in a target region without a map clause is translated to the
 * device address of the storage it points to (OpenMP 5.0 §2.19.7: a
 * zero-length array section); values and structs are copied in. Helpers
 * called from the loop are compiled for the device as implicitly
 * `declare target` (OpenMP 5.0 §2.12.7). */
#define FOR_EACH_ITEM(i, n)                                                                        \
    _Pragma("omp target teams distribute parallel for defaultmap(firstprivate: aggregate)")        \
    for (int i = 0; i < (n); ++i)
#elif defined(_OPENMP)
/* Host threads take the items in guided chunks: the work per item is
 * uneven where a pass skips the particles far from the liquid (the surface
 * terms) or from the beam, and in grid order those sit together, so equal
 * static halves left one thread waiting (21% of the spot weld's samples in
 * libgomp; guided: 10% less wall time, uniform scenes unchanged;
 * BENCHMARKS.md). Each item writes only its own outputs, so the result does
 * not depend on which thread takes it. */
#define FOR_EACH_ITEM(i, n)                                                                        \
    _Pragma("omp parallel for schedule(guided)") for (int i = 0; i < (n); ++i)
#else
#define FOR_EACH_ITEM(i, n) for (int i = 0; i < (n); ++i)
#endif
#define ATOMIC_INC(p) __atomic_fetch_add((p), 1, __ATOMIC_RELAXED)
typedef unsigned int uint;

#endif

/* A pair loop's body, inlined: the call and its dozen arguments per pair
 * cost more than the force's arithmetic. Both compilers need telling: gcc
 * and pocl's LLVM each left pair functions as calls (pocl: the continuity
 * terms and the fluid pass, 25% of the 3D dam break's step). */
#define PAIR_INLINE static inline __attribute__((always_inline))

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
