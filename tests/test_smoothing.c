/* The smoothing kernel of this build (AMSPH_DIM, AMSPH_KERNEL) against its
 * defining properties: unit integral, compact support, and a gradient factor
 * consistent with dW/dr. Compiled once per dimension and kernel. */
#include "smoothing.h"
#include "testing.h"

/* Integral of W over its support by the midpoint rule in r. */
static double integral_of_w(double h)
{
    const int steps = 200000;
    const double support = SUPPORT_OVER_H * h;
    const double dr = support / steps;
    double sum = 0.0;
    for (int k = 0; k < steps; ++k) {
        const double r = (k + 0.5) * dr;
        const double shell = AMSPH_DIM == 2 ? 2.0 * PI * r : 4.0 * PI * r * r;
        sum += smoothing_w((real)r, (real)h) * shell * dr;
    }
    return sum;
}

int main(void)
{
    const double h = 1.3e-3;
    const double support = SUPPORT_OVER_H * h;
    const double integral = integral_of_w(h);
    CHECK(fabs(integral - 1.0) < 1e-5, "integral of W = %.8f, not 1", integral);
    CHECK(smoothing_w((real)support, (real)h) == 0.0, "W at the support radius is not 0");
    CHECK(smoothing_w((real)(1.01 * support), (real)h) == 0.0, "W beyond the support is not 0");
    CHECK(smoothing_grad_factor((real)support, (real)h) == 0.0, "gradient at the support is not 0");
    CHECK(smoothing_w((real)(0.99 * support), (real)h) > 0.0, "W just inside the support is 0");

    /* F = (dW/dr)/r against a central difference of W, across the support */
    double worst = 0.0;
    for (int k = 1; k < 100; ++k) {
        const double r = support * k / 100.0;
        const double e = (AMSPH_DOUBLE ? 1e-5 : 1e-2) * h; /* balances truncation and round-off */
        const double dwdr = ((double)smoothing_w((real)(r + e), (real)h) -
                             (double)smoothing_w((real)(r - e), (real)h)) / (2.0 * e);
        const double scale = fabs((double)smoothing_grad_factor((real)(0.5 * h), (real)h) * 0.5 * h);
        const double err = fabs((double)smoothing_grad_factor((real)r, (real)h) * r - dwdr) / scale;
        worst = fmax(worst, err);
        CHECK(smoothing_w((real)r, (real)h) >= 0.0, "W < 0 at r = %g", r);
    }
    /* truncation ~(e/h)^2 and round-off ~eps h/e: ~1e-4 in float, ~1e-9 in double */
    CHECK(worst < (AMSPH_DOUBLE ? 1e-6 : 1e-3), "gradient factor differs from dW/dr by %g", worst);
    /* the gradient factor is finite, negative and continuous at r -> 0
     * (F(q) - F(0) = O(q) for Wendland, O(q^2) for the quintic) */
    const double f0 = smoothing_grad_factor((real)0.0, (real)h);
    const double f_small = smoothing_grad_factor((real)(1e-4 * h), (real)h);
    CHECK(f0 < 0.0 && fabs(f0 - f_small) < 1e-3 * fabs(f0), "F(0) = %g, F(1e-4 h) = %g", f0, f_small);
    return testing_finish();
}
