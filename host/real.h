/* The host's name for the kernels' `real` (float unless built with AMSPH_DOUBLE). */
#ifndef AMSPH_REAL_H
#define AMSPH_REAL_H
#if AMSPH_DOUBLE
typedef double amsph_real;
#else
typedef float amsph_real;
#endif
#endif
