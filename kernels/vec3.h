/* Small helpers on 3-vectors stored as real[3] (kernels use scalar
 * components, not OpenCL vector types; see device.h). */
#ifndef AMSPH_VEC3_H
#define AMSPH_VEC3_H

#include "device.h"

static inline real dot3(const real a[3], const real b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* out = a x b */
static inline void cross3(const real a[3], const real b[3], real out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The d-th root of x, d the dimension (of a volume: the particle spacing). */
static inline real dimension_root(real x)
{
#if AMSPH_DIM == 2
    return sqrt(x);
#else
    return cbrt(x);
#endif
}

#endif
