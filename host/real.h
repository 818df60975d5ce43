/* The host's name for the kernels' `real` (float unless built with AMSPH_DOUBLE). */
#ifndef AMSPH_REAL_H
#define AMSPH_REAL_H
#include <float.h>
/* AMSPH_REAL_MAX and AMSPH_REAL_MIN: the largest finite and the smallest
 * normal magnitude it holds; AMSPH_REAL_EPSILON: its spacing at 1. */
#if AMSPH_DOUBLE
typedef double amsph_real;
#define AMSPH_REAL_MAX DBL_MAX
#define AMSPH_REAL_MIN DBL_MIN
#define AMSPH_REAL_EPSILON DBL_EPSILON
#else
typedef float amsph_real;
#define AMSPH_REAL_MAX FLT_MAX
#define AMSPH_REAL_MIN FLT_MIN
#define AMSPH_REAL_EPSILON FLT_EPSILON
#endif
#endif
