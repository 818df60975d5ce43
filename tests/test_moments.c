/* Kernel moments on lattices (VALIDATION.md K1), through the device kernel
 * kernel_moments on every backend, 2D and 3D, both smoothing kernels:
 *   zeroth  sum_b V_b W_ab = 1
 *   first   sum_b V_b (r_b - r_a) W_ab = 0
 *   gradient sum_b V_b (r_b - r_a) (x) grad_a W_ab = I
 * at interior particles (more than a support from the boundary).
 *
 * 1. Where the lattice resolves the kernel (quintic at h = 1.5 dx, Wendland
 *    C2 at h = 2.5 dx) the interior errors are < 1e-3.
 * 2. At the settings of the sources a lattice resolves the kernel less well:
 *    Wendland C2 at h = 1.2 dx (Russell) gives sum V W = 1.018 (2D) and
 *    1.017 (3D), which is why his pressure gradient divides by Gamma_a
 *    (Eq. 3.17); the quintic at h = dx (Fuchs et al.) misses I by 1.0e-3 in
 *    3D. There, and on jittered lattices, the device sums must equal an
 *    independent double-precision brute-force sum written here from the
 *    published formulas. */
#include <math.h>

#include "grid_fixture.h"

#define PI 3.14159265358979323846

/* Independent reference kernels (Wendland 1995; Morris et al. 1997). */
static double reference_w(int kernel, int dim, double r, double h, double *f)
{
    const double q = r / h;
    if (kernel == 0) {
        const double a = dim == 2 ? 7.0 / (4.0 * PI * h * h) : 21.0 / (16.0 * PI * h * h * h);
        const double t = q < 2.0 ? 1.0 - 0.5 * q : 0.0;
        *f = -5.0 * a * t * t * t / (h * h);
        return a * t * t * t * t * (2.0 * q + 1.0);
    }
    const double a = dim == 2 ? 7.0 / (478.0 * PI * h * h) : 1.0 / (120.0 * PI * h * h * h);
    double w = 0.0, dw = 0.0;
    const double weight[3] = {1.0, -6.0, 15.0};
    for (int k = 0; k < 3; ++k) {
        const double t = (3.0 - k) - q;
        if (t > 0.0) {
            w += weight[k] * t * t * t * t * t;
            dw += weight[k] * t * t * t * t;
        }
    }
    *f = r > 0.0 ? -5.0 * a * dw / (h * r) : -120.0 * a / (h * h);
    return a * w;
}

typedef struct {
    int kernel;
    double h_over_dx;
    double jitter; /* fraction of dx */
    int against_one; /* 1: compare with the exact moments, 0: with the brute-force sums */
} moment_case;

typedef struct {
    double zeroth, first, gradient; /* worst interior errors */
} moment_errors;

static void lattice(int dim, int per_axis, double dx, double jitter, double *x, double lo[3], double hi[3])
{
    unsigned long long state = 99;
    const int n = dim == 2 ? per_axis * per_axis : per_axis * per_axis * per_axis;
    for (int i = 0; i < n; ++i) {
        int k = i;
        for (int d = 0; d < 3; ++d) {
            const double jit = jitter * dx * (2.0 * testing_random(&state) - 1.0);
            x[3 * i + d] = d < dim ? (k % per_axis + 0.5) * dx + jit : 0.0;
            k /= per_axis;
        }
    }
    for (int d = 0; d < 3; ++d) {
        lo[d] = d < dim ? -dx : 0.0;
        hi[d] = d < dim ? (per_axis + 1) * dx : 0.0;
    }
}

static moment_errors measure(amsph_backend *b, int dim, const moment_case *mc)
{
    const double dx = 1e-3, h = mc->h_over_dx * dx;
    const double support = (mc->kernel ? 3.0 : 2.0) * h;
    const int per_axis = (int)ceil(2.0 * support / dx) + (dim == 2 ? 12 : 4);
    const int n = dim == 2 ? per_axis * per_axis : per_axis * per_axis * per_axis;
    const double volume = pow(dx, dim);
    double *x = malloc((size_t)n * 3 * sizeof *x), lo[3], hi[3];
    lattice(dim, per_axis, dx, mc->jitter, x, lo, hi);
    moment_errors e = {0, 0, 0};
    grid_fixture f;
    const int periodic[3] = {0, 0, 0};
    CHECK_OK(fixture_create(&f, b, dim, mc->kernel, x, n, lo, hi, periodic, support, volume));
    amsph_buffer *m0b = NULL, *m1b = NULL, *m2b = NULL;
    CHECK_OK(amsph_buffer_alloc(b, (size_t)n * sizeof(amsph_real), &m0b));
    CHECK_OK(amsph_buffer_alloc(b, (size_t)n * 3 * sizeof(amsph_real), &m1b));
    CHECK_OK(amsph_buffer_alloc(b, (size_t)n * 9 * sizeof(amsph_real), &m2b));
    CHECK_OK(AMSPH_LAUNCH(b, "kernel_moments", n, amsph_arg_buffer(f.p.field[AMSPH_FIELD_POSITION]),
                          amsph_arg_buffer(f.p.field[AMSPH_FIELD_MASS]),
                          amsph_arg_buffer(f.p.field[AMSPH_FIELD_DENSITY]), amsph_arg_buffer(f.g.cell),
                          amsph_arg_int(n), fixture_geometry(&f), amsph_arg_buffer(f.g.cell_start),
                          amsph_arg_real(h), amsph_arg_buffer(m0b), amsph_arg_buffer(m1b),
                          amsph_arg_buffer(m2b)));
    amsph_real *m0 = malloc((size_t)n * sizeof *m0), *m1 = malloc((size_t)n * 3 * sizeof *m1),
               *m2 = malloc((size_t)n * 9 * sizeof *m2);
    amsph_host_particles s;
    CHECK_OK(amsph_particles_download(&f.p, &s));
    CHECK_OK(amsph_download(b, m0b, 0, (size_t)n * sizeof *m0, m0));
    CHECK_OK(amsph_download(b, m1b, 0, (size_t)n * 3 * sizeof *m1, m1));
    CHECK_OK(amsph_download(b, m2b, 0, (size_t)n * 9 * sizeof *m2, m2));
    const amsph_real *p = amsph_host_real(&s, AMSPH_FIELD_POSITION);
    for (int a = 0; a < n; ++a) {
        int interior = 1;
        for (int d = 0; d < dim; ++d)
            interior &= p[3 * a + d] > support + 0.5 * dx && p[3 * a + d] < per_axis * dx - support - 0.5 * dx;
        if (!interior)
            continue;
        /* expected moments: exact, or brute force over all particles */
        double z = 1.0, m1r[3] = {0, 0, 0}, m2r[9] = {1, 0, 0, 0, 1, 0, 0, 0, dim == 3 ? 1 : 0};
        if (!mc->against_one) {
            z = 0.0;
            memset(m1r, 0, sizeof m1r);
            memset(m2r, 0, sizeof m2r);
            for (int b2 = 0; b2 < n; ++b2) {
                double r[3], r2 = 0.0, fac;
                for (int d = 0; d < 3; ++d) {
                    r[d] = (double)p[3 * b2 + d] - (double)p[3 * a + d]; /* r_b - r_a */
                    r2 += r[d] * r[d];
                }
                const double w = reference_w(mc->kernel, dim, sqrt(r2), h, &fac);
                if (sqrt(r2) >= support)
                    continue;
                z += volume * w;
                for (int i = 0; i < 3; ++i) {
                    m1r[i] += volume * r[i] * w;
                    for (int j = 0; j < 3; ++j)
                        m2r[3 * i + j] -= volume * r[i] * fac * r[j]; /* grad_a W = -F (r_b - r_a) */
                }
            }
        }
        e.zeroth = fmax(e.zeroth, fabs(m0[a] - z));
        for (int i = 0; i < 3; ++i) {
            e.first = fmax(e.first, fabs(m1[3 * a + i] - m1r[i]) / h);
            for (int j = 0; j < 3; ++j)
                e.gradient = fmax(e.gradient, fabs(m2[9 * a + 3 * i + j] - m2r[3 * i + j]));
        }
    }
    free(m0), free(m1), free(m2), free(x);
    amsph_host_free(&s);
    amsph_buffer_free(b, m0b), amsph_buffer_free(b, m1b), amsph_buffer_free(b, m2b);
    fixture_free(&f);
    return e;
}

int main(void)
{
    static const moment_case cases[] = {
        {1, 1.5, 0.0, 1}, {0, 2.5, 0.0, 1}, /* resolved: exact moments */
        {0, 1.2, 0.0, 0}, {0, 1.2, 0.1, 0}, /* Russell's setting, lattice and jittered */
        {1, 1.0, 0.0, 0}, {1, 1.0, 0.1, 0}, /* Fuchs's setting, lattice and jittered */
    };
    /* brute-force agreement: float sums of ~100 terms of size up to ~0.1 */
    const double agree = AMSPH_DOUBLE ? 1e-10 : 2e-5;
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_backend *b = testing_backend(k);
        if (!b)
            continue;
        for (int dim = 2; dim <= 3; ++dim)
            for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
                const moment_case *mc = &cases[c];
                const moment_errors e = measure(b, dim, mc);
                const double tol = mc->against_one ? 1e-3 : agree;
                fprintf(stderr, "%s %dD %s h/dx=%.1f jitter=%.2f: errors %.2e %.2e %.2e\n",
                        b->iface->name, dim, mc->kernel ? "quintic" : "wendland", mc->h_over_dx,
                        mc->jitter, e.zeroth, e.first, e.gradient);
                CHECK(e.zeroth < tol && e.first < tol && e.gradient < tol,
                      "%s %dD kernel %d h/dx %.1f jitter %.2f: errors %g %g %g exceed %g",
                      b->iface->name, dim, mc->kernel, mc->h_over_dx, mc->jitter, e.zeroth, e.first,
                      e.gradient, tol);
            }
        amsph_backend_destroy(b);
    }
    return testing_finish();
}
