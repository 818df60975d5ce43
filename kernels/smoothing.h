/* Smoothing kernels W(r, h) and their radial derivatives, 2D and 3D.
 *
 * Selected at build time by AMSPH_KERNEL (0 Wendland C2, 1 quintic spline).
 * smoothing_w(r, h) is W; smoothing_grad_factor(r, h) is F with
 * grad_a W_ab = F * r_ab (r_ab = r_a - r_b), i.e. F = (dW/dr) / r.
 * A pair loop takes the kernel's scale factors once (smoothing_scale_of) and
 * calls smoothing_w_at / smoothing_grad_factor_at, which then divide by
 * nothing: per pair, 1/h, the normalisation alpha and alpha/h^2 cost three
 * divisions, a fifth of the continuity loop's instructions. */
#ifndef AMSPH_SMOOTHING_H
#define AMSPH_SMOOTHING_H

#include "device.h"

#ifndef AMSPH_KERNEL
#error "AMSPH_KERNEL must be defined (0 Wendland C2, 1 quintic spline)"
#endif

/* The scale factors of the kernel at smoothing length h (smoothing_scale_of). */
typedef struct {
    real inv_h;      /* 1 / h */
    real alpha;      /* the normalisation */
    real grad_alpha; /* alpha / h^2, of the gradient factor */
} smoothing_scale;

#if AMSPH_KERNEL == 0
/* Wendland C2, support 2h (Wendland 1995; Russell 2018 Eq. 2.5, whose
 * printed "((1-q)/2)^4" is a typo for (1 - q/2)^4, as its normalisation and
 * its printed derivative show):
 *   W = alpha (1 - q/2)^4 (2q + 1),  q = r/h <= 2,
 *   alpha = 7/(4 pi h^2) in 2D, 21/(16 pi h^3) in 3D,
 *   dW/dr = -5 alpha q (1 - q/2)^3 / h. */
#define SUPPORT_OVER_H REAL(2.0)

/* alpha h^d */
#if AMSPH_DIM == 2
#define SMOOTHING_NORM (REAL(7.0) / (REAL(4.0) * PI_REAL))
#else
#define SMOOTHING_NORM (REAL(21.0) / (REAL(16.0) * PI_REAL))
#endif

static inline real smoothing_w_at(const smoothing_scale *k, real r)
{
    const real q = r * k->inv_h;
    if (q >= REAL(2.0))
        return REAL(0.0);
    const real t = REAL(1.0) - REAL(0.5) * q;
    const real t2 = t * t;
    return k->alpha * t2 * t2 * (REAL(2.0) * q + REAL(1.0));
}

static inline real smoothing_grad_factor_at(const smoothing_scale *k, real r)
{
    const real q = r * k->inv_h;
    if (q >= REAL(2.0))
        return REAL(0.0);
    const real t = REAL(1.0) - REAL(0.5) * q;
    return REAL(-5.0) * k->grad_alpha * t * t * t;
}

#elif AMSPH_KERNEL == 1
/* Quintic spline, support 3h (Morris, Fox & Zhu 1997; Fuchs et al. 2022 §3):
 *   W = alpha [(3-q)^5 - 6 (2-q)^5 + 15 (1-q)^5], each term only where positive,
 *   alpha = 7/(478 pi h^2) in 2D, 1/(120 pi h^3) in 3D,
 *   dW/dr = -5 alpha [(3-q)^4 - 6 (2-q)^4 + 15 (1-q)^4] / h. */
#define SUPPORT_OVER_H REAL(3.0)

/* alpha h^d */
#if AMSPH_DIM == 2
#define SMOOTHING_NORM (REAL(7.0) / (REAL(478.0) * PI_REAL))
#else
#define SMOOTHING_NORM (REAL(1.0) / (REAL(120.0) * PI_REAL))
#endif

/* For q < 1 all three pieces are active and their sum cancels heavily in
 * float; expanded, it is exact and cheap (Horner):
 *   W/alpha = 66 - 60 q^2 + 30 q^4 - 10 q^5,
 *   (dW/dq)/alpha = -5 q (24 - 24 q^2 + 10 q^3). */
static inline real smoothing_w_at(const smoothing_scale *k, real r)
{
    const real q = r * k->inv_h;
    real w;
    if (q < REAL(1.0)) {
        const real q2 = q * q;
        w = REAL(66.0) + q2 * (REAL(-60.0) + q2 * (REAL(30.0) - REAL(10.0) * q));
    } else if (q < REAL(3.0)) {
        const real t3 = REAL(3.0) - q, t2 = REAL(2.0) - q;
        w = t3 * t3 * t3 * t3 * t3;
        if (q < REAL(2.0))
            w -= REAL(6.0) * t2 * t2 * t2 * t2 * t2;
    } else {
        w = REAL(0.0);
    }
    return k->alpha * w;
}

static inline real smoothing_grad_factor_at(const smoothing_scale *k, real r)
{
    const real q = r * k->inv_h;
    real f; /* (dW/dq) / (-5 alpha q) */
    if (q < REAL(1.0)) {
        f = REAL(24.0) + q * q * (REAL(-24.0) + REAL(10.0) * q);
    } else if (q < REAL(3.0)) {
        const real t3 = REAL(3.0) - q, t2 = REAL(2.0) - q;
        f = t3 * t3 * t3 * t3;
        if (q < REAL(2.0))
            f -= REAL(6.0) * t2 * t2 * t2 * t2;
        f /= q;
    } else {
        f = REAL(0.0);
    }
    return REAL(-5.0) * k->grad_alpha * f;
}
#else
#error "unknown AMSPH_KERNEL"
#endif

/* The scale at h from 1/h: one division, whose rounding OpenCL leaves to the
 * device (2.5 ulp), so that the backends differ by at most that. */
static inline smoothing_scale smoothing_scale_of(real h)
{
    smoothing_scale k;
    k.inv_h = REAL(1.0) / h;
    k.alpha = SMOOTHING_NORM * k.inv_h * k.inv_h;
#if AMSPH_DIM == 3
    k.alpha *= k.inv_h;
#endif
    k.grad_alpha = k.alpha * k.inv_h * k.inv_h;
    return k;
}

/* W(r, h) and F(r, h) at one h, for loops that do not keep the scale. */
static inline real smoothing_w(real r, real h)
{
    const smoothing_scale k = smoothing_scale_of(h);
    return smoothing_w_at(&k, r);
}

static inline real smoothing_grad_factor(real r, real h)
{
    const smoothing_scale k = smoothing_scale_of(h);
    return smoothing_grad_factor_at(&k, r);
}

#endif
