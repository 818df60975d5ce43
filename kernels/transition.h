/* The linear ramp shared by the kernels' blends, so that none switches at
 * one value. */
#ifndef AMSPH_TRANSITION_H
#define AMSPH_TRANSITION_H

#include "device.h"

/* The linear transition function f[x, x1, x2] of Fuchs et al. 2022 Eq. 21:
 * 0 at x1, 1 at x2, linear between and held beyond; with x1 > x2 the ramp
 * falls (1 up to x2, 0 from x1). */
static inline real transition(real x, real x1, real x2)
{
    return fmin(fmax((x - x1) / (x2 - x1), REAL(0.0)), REAL(1.0));
}

#endif
