/* The surface module (kernels/surface.cl): surface tension after Russell's
 * modified Morris CSF and the Marangoni force, each against a known answer.
 *   - a flat free surface: the colour gradient integrates to 1 across it,
 *     its curvature is 0 (and the surface loop wraps a periodic axis);
 *   - sigma(T) of 304 steel (Sahoo et al. 1988) against the formula;
 *   - the capillary time step (PHYSICS.md erratum 3);
 *   - Young-Laplace: a droplet at rest holds (d - 1) sigma/R inside
 *     (erratum 1), in 2D and 3D;
 *   - thermocapillary return flow in a closed layer: the profile
 *     u(y) = tau d / (4 mu) (3 (y/d)^2 - 2 y/d), tau = d sigma/dT dT/dx;
 *   - a square patch relaxes to the circle of its area, at rest;
 *   - the curvature of a lattice sphere, rough or not, and on normals put in
 *     exactly, that of a circle, a sphere, a bubble and a cap on a wall,
 *     row by row;
 *   - wetting (Fuchs et al. 2022 Eqs. 27-29): at the contact line the normals
 *     take the prescribed angle, and a patch on a wall with theta0 = 90
 *     degrees keeps its 90-degree contact angle where a completely wetting
 *     one spreads, and a half disc with theta0 = 60 or 120 degrees comes to
 *     rest at that angle (with the interface viscosity, Fuchs Eqs. 31-32,
 *     which leaves rigid motion alone and damps a strain at the surface), as
 *     does a half sphere at 60 degrees;
 *   - both backends give the same surface forces. */
#include <math.h>

#include "sim.h"
#include "surface.h"
#include "testing.h"
#include "testing_run.h"

static int parse(const char *text, amsph_case *c)
{
    char err[512];
    const int status = amsph_case_parse(text, strlen(text), "surface.yaml", c, err, sizeof err);
    CHECK(status == 0, "%s", err);
    return status;
}

static int download(amsph_sim *s, amsph_host_particles *h)
{
    const int status = amsph_particles_download(&s->particles, h);
    CHECK(status == 0, "%s", amsph_last_error());
    return status;
}

/* A 2D liquid of sigma = 10 N/m on a 0.05 m lattice (quintic kernel), no
 * gravity, at rest: the domain's line and the geometry's blocks. */
#define STILL_LIQUID_CASE(domain, blocks)                                                         \
    "dimension: 2\n" domain "dx: 0.05\n"                                                          \
    "kernel: quintic\n"                                                                          \
    "end_time: 1\n"                                                                              \
    "output_interval: 1\n"                                                                       \
    "fluid: {}\n"                                                                                \
    "surface: {}\n"                                                                              \
    "materials:\n"                                                                               \
    "  - {name: liquid, density: 1000, sound_speed: 2, surface_tension: 10}\n"                   \
    "geometry:\n" blocks

/* A slab 0.5 m thick, periodic in x (1 m: 8 cells, the surface loop reaches
 * 2 cells each way), free on both faces. */
static const char *slab_case =
    STILL_LIQUID_CASE("domain: {min: [0, -0.5], max: [1, 1.0], periodic: [true, false]}\n",
                      "  - {shape: box, kind: fluid, material: liquid, min: [0, 0], max: [1, 0.5]}\n");

/* Across a flat surface the colour gradient n (Russell Eq. 3.26) must
 * integrate to the jump of the colour, 1 (sum of V n_y over the upper half
 * per metre of surface, pointing down into the liquid), and the curvature
 * and the surface force must vanish. */
static void test_flat_surface(void)
{
    amsph_case c;
    amsph_host_particles h = {0};
    if (!parse(slab_case, &c) && !testing_run_case(&c, 0, 0.0, &h)) {
        const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
        const amsph_real *n = amsph_host_real(&h, AMSPH_FIELD_NORMAL);
        const amsph_real *kappa = amsph_host_real(&h, AMSPH_FIELD_CURVATURE);
        const amsph_real *acc = amsph_host_real(&h, AMSPH_FIELD_ACCELERATION);
        double upper = 0.0, lower = 0.0, kappa_max = 0.0, acc_max = 0.0;
        for (int i = 0; i < h.n; ++i) {
            const double v = c.dx * c.dx;
            if (x[3 * i + 1] > 0.25)
                upper += v * n[3 * i + 1];
            else
                lower += v * n[3 * i + 1];
            kappa_max = fmax(kappa_max, fabs(kappa[i]));
            acc_max = fmax(acc_max, hypot(acc[3 * i], acc[3 * i + 1]));
        }
        CHECK(fabs(upper + 1.0) < 0.05, "integral of n across the upper surface %g, expected -1", upper);
        CHECK(fabs(lower - 1.0) < 0.05, "integral of n across the lower surface %g, expected 1", lower);
        /* a tenth of 1/R for R = 100 m */
        CHECK(kappa_max < 1e-3, "largest curvature on a flat slab %g 1/m", kappa_max);
        CHECK(acc_max < 1e-3, "largest acceleration on a flat slab at rest %g m/s^2", acc_max);
    }
    amsph_host_free(&h);
}

/* Sahoo et al. (1988), Russell 2018 Eq. 4.2, evaluated directly in double
 * precision: sigma0 - A (T - T_m) - R T Gamma_s ln(1 + k_l a_s exp(-dH0/(R T))),
 * held at sigma_min. Gamma_s = 1.3e-8 kmol/m^2 = 1.3e-5 mol/m^2: Russell
 * quotes 1.3e-8 beside R = 8.3145 J/(mol K) and dH0 in J/mol, which makes
 * the adsorption term a thousand times too small to turn dsigma/dT positive
 * as the thesis says it does. */
static double sahoo(double t)
{
    const double r = 8.314462618, gamma_s = 1.3e-5, k_l = 0.0032, a_s = 0.0022, dh0 = -166e3;
    const double sigma = 1.943 - 0.5e-3 * (t - 1723.0) - r * t * gamma_s * log(1.0 + k_l * a_s * exp(-dh0 / (r * t)));
    return fmax(sigma, 0.2);
}

static void test_surface_tension_law(void)
{
    static const double temperature[] = {300, 1500, 1700, 1723, 2000, 3000, 6000};
    enum { BLOCKS = sizeof temperature / sizeof temperature[0] };
    char text[4096];
    int used = snprintf(text, sizeof text,
                        "dimension: 2\n"
                        "domain: {min: [0, 0], max: [%d, 1]}\n"
                        "dx: 0.1\n"
                        "end_time: 1\n"
                        "output_interval: 1\n"
                        "fluid: {}\n"
                        "surface: {}\n"
                        "materials:\n"
                        "  - {name: steel, density: 7000, sound_speed: 10, surface_tension: 1.943,\n"
                        "     surface_tension_slope: -0.5e-3, surface_tension_reference_temperature: 1723,\n"
                        "     surface_tension_minimum: 0.2, surfactant_excess: 1.3e-5,\n"
                        "     surfactant_segregation: 0.0032, surfactant_activity: 0.0022,\n"
                        "     surfactant_enthalpy: -166e3}\n"
                        "geometry:\n",
                        BLOCKS);
    for (int k = 0; k < BLOCKS; ++k)
        used += snprintf(text + used, sizeof text - (size_t)used,
                         "  - {shape: box, kind: fluid, material: steel, min: [%d, 0], max: [%d.5, 0.5], "
                         "temperature: %g}\n",
                         k, k, temperature[k]);
    amsph_case c;
    amsph_host_particles h = {0};
    if (!parse(text, &c) && !testing_run_case(&c, 0, 0.0, &h)) {
        const amsph_real *t = amsph_host_real(&h, AMSPH_FIELD_TEMPERATURE);
        const amsph_real *sigma = amsph_host_real(&h, AMSPH_FIELD_SURFACE_TENSION);
        double worst = 0.0;
        for (int i = 0; i < h.n; ++i)
            worst = fmax(worst, fabs(sigma[i] - sahoo(t[i])) / sahoo(t[i]));
        CHECK(worst < 1e-5, "sigma(T) differs from Sahoo's law by %g (relative)", worst);
        /* the law turns over near the melting point: d sigma/dT > 0 below */
        CHECK(sahoo(1650) > sahoo(1600) && sahoo(1900) < sahoo(1800), "Sahoo's law does not turn over");
    }
    amsph_host_free(&h);
}

/* With a slow sound speed out of the way, the capillary limit
 * 0.25 sqrt(rho h^3 / (2 pi sigma)) (Fuchs et al. 2022 Eq. 42; not its
 * square, PHYSICS.md erratum 3) sets the step. */
static void test_capillary_step(void)
{
    amsph_case c;
    if (parse(slab_case, &c))
        return;
    c.materials[0].surface_tension = 1e4;
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    double dt = 0.0;
    CHECK_OK(amsph_sim_create(&c, b, &s));
    CHECK_OK(amsph_sim_stable_dt(&s, &dt));
    const double h = s.h;
    const double expected = 0.25 * sqrt(1000.0 * h * h * h / (2.0 * PI * 1e4));
    CHECK(strcmp(s.dt_limit, "capillary") == 0, "the step is set by the %s limit", s.dt_limit);
    CHECK(fabs(dt - expected) < 1e-6 * expected, "capillary step %g s, expected %g s", dt, expected);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
}

/* Mean pressure inside r < R/2 and the largest speed of a droplet about the
 * origin. */
static void droplet_state(const amsph_host_particles *h, double radius, double *pressure, double *speed)
{
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
    const amsph_real *p = amsph_host_real(h, AMSPH_FIELD_PRESSURE);
    const amsph_real *v = amsph_host_real(h, AMSPH_FIELD_VELOCITY);
    double sum = 0.0;
    int count = 0;
    *speed = 0.0;
    for (int i = 0; i < h->n; ++i) {
        const amsph_real *xi = x + 3 * i, *vi = v + 3 * i;
        if (sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]) < 0.5 * radius) {
            sum += p[i];
            ++count;
        }
        *speed = fmax(*speed, sqrt(vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]));
    }
    *pressure = count ? sum / count : NAN;
}

/* The mean curvature of the particles with a normal, weighted as the CSF
 * force weights it (by V_a |n_a|: the Laplace pressure is sigma times its
 * integral across the band), over 2/R for the sphere of R = 1 m (kappa < 0 on
 * a convex surface). */
static double band_curvature(const amsph_host_particles *h)
{
    const amsph_real *n = amsph_host_real(h, AMSPH_FIELD_NORMAL);
    const amsph_real *kappa = amsph_host_real(h, AMSPH_FIELD_CURVATURE);
    const amsph_real *m = amsph_host_real(h, AMSPH_FIELD_MASS), *rho = amsph_host_real(h, AMSPH_FIELD_DENSITY);
    double weight = 0.0, sum = 0.0;
    for (int i = 0; i < h->n; ++i) {
        const double w = m[i] / rho[i] *
                         sqrt(n[3 * i] * n[3 * i] + n[3 * i + 1] * n[3 * i + 1] + n[3 * i + 2] * n[3 * i + 2]);
        weight += w;
        sum += w * kappa[i];
    }
    return -sum / weight / 2.0;
}

/* The lattice sphere of young_laplace_3d.yaml (R = 1 m = 10 dx) as built:
 * its band's curvature within 5% of 2/R, with the case's quintic kernel and
 * with Wendland C2 at a surface smoothing length of 1.8 dx. The band's rows 1
 * to 3 dx inside lie on level sets of radius R - delta; read as they are,
 * without taking them to the surface (kernels/surface.cl,
 * curvature_at_surface), the mean was 1.120 and 1.109 of 2/R (BENCHMARKS.md,
 * "The curvature at the surface"). */
static void check_sphere_curvature(amsph_kernel_type kernel, double surface_h_over_dx)
{
    amsph_case c;
    amsph_host_particles h = {0};
    if (testing_load_case("young_laplace_3d.yaml", &c))
        return;
    c.kernel = kernel;
    c.surface.h_over_dx = surface_h_over_dx;
    if (!testing_run_case(&c, 0, 0.0, &h)) {
        const double ratio = band_curvature(&h);
        printf("sphere at rest (%s, surface h %.1f dx): curvature %.4f of 2/R\n",
               kernel == AMSPH_KERNEL_QUINTIC ? "quintic" : "wendland", surface_h_over_dx, ratio);
        CHECK(fabs(ratio - 1.0) < 0.05, "mean curvature of a sphere of R = 10 dx: %g of 2/R", ratio);
    }
    amsph_host_free(&h);
}

/* The same sphere with every particle moved by up to 0.1 dx along each axis
 * (uniform, seeded), its curvature read in a first step of 1e-9 s: within 5%
 * of 2/R. The scatter of the normals must not read as curvature. Russell's
 * (n^_b - n^_a) . r_ab turned it into curvature through (n^_b . n^_a - 1)
 * (r_ab . n^_a), and read 1.127 of 2/R here (1.039 without the jitter); the
 * divergence along the surface reads 1.009 (kernels/surface.cl,
 * surface_curvature; BENCHMARKS.md, "The curvature along the surface"). */
static void check_rough_sphere_curvature(void)
{
    amsph_case c;
    if (testing_load_case("young_laplace_3d.yaml", &c))
        return;
    amsph_backend *b = testing_backend(0);
    if (!b)
        return;
    const double jitter = 0.1;
    amsph_sim s;
    amsph_host_particles h = {0};
    int status = amsph_sim_create(&c, b, &s);
    if (!status)
        status = amsph_particles_download(&s.particles, &h);
    if (!status) {
        amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
        unsigned long long state = 20261206;
        for (int i = 0; i < 3 * h.n; ++i)
            x[i] += (amsph_real)(jitter * c.dx * (2.0 * testing_random(&state) - 1.0));
        status = testing_replace_particles(&s, &h);
        if (!status)
            status = amsph_sim_step(&s, 1e-9);
        if (!status)
            status = amsph_particles_download(&s.particles, &h);
    }
    amsph_sim_free(&s);
    CHECK(status == 0, "%s", amsph_last_error());
    if (!status) {
        const double ratio = band_curvature(&h);
        printf("sphere jittered by %.1f dx: curvature %.4f of 2/R\n", jitter, ratio);
        CHECK(fabs(ratio - 1.0) < 0.05, "mean curvature of a rough sphere of R = 10 dx: %g of 2/R", ratio);
    }
    amsph_host_free(&h);
    amsph_backend_destroy(b);
}

/* A sphere (a circle in 2D) of centre `centre` and radius R with the liquid
 * inside it (side +1: a droplet, kappa = -(d - 1)/R) or outside (side -1: a
 * bubble, kappa = +(d - 1)/R); `wall` is the height of a wall's face under
 * it (a cap), or -INFINITY. */
typedef struct {
    double centre[3], radius, side, wall;
} exact_sphere;

enum { CURVATURE_ROWS = 4 }; /* rows 0 to 3 dx below the surface, then the wall row */

/* Case c after a first step of 1e-9 s (which gives the particles their
 * weights psi_a), with the unit normal of every particle with a normal set
 * to the sphere's, -side (x - c)/|x - c|, and the curvature pass run again
 * on them alone (amsph_surface_curvature); its particles in h. */
static int curvature_on_exact_normals(const amsph_case *c, exact_sphere e, amsph_host_particles *h)
{
    amsph_backend *b = testing_backend(0);
    if (!b)
        return 1;
    amsph_sim s;
    int status = amsph_sim_create(c, b, &s);
    if (!status)
        status = amsph_sim_step(&s, 1e-9);
    if (!status)
        status = amsph_particles_download(&s.particles, h);
    if (!status) {
        const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
        const amsph_real *psi = amsph_host_real(h, AMSPH_FIELD_NORMAL_WEIGHT);
        amsph_real *n_hat = amsph_host_real(h, AMSPH_FIELD_UNIT_NORMAL);
        for (int i = 0; i < h->n; ++i) {
            double r[3], size = 0.0;
            for (int d = 0; d < 3; ++d) {
                r[d] = x[3 * i + d] - e.centre[d];
                size += r[d] * r[d];
            }
            size = sqrt(size);
            for (int d = 0; d < 3; ++d)
                n_hat[3 * i + d] = psi[i] > 0.0 ? (amsph_real)(-e.side * r[d] / size) : (amsph_real)0.0;
        }
        status = testing_replace_particles(&s, h);
        if (!status)
            status = amsph_surface_curvature(&s);
        if (!status)
            status = amsph_particles_download(&s.particles, h);
    }
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
    CHECK(status == 0, "%s", amsph_last_error());
    return status;
}

/* The curvature pass on exact normals (curvature_on_exact_normals): the
 * mean raw curvature of each row of the band (by depth below the sphere, in
 * steps of dx), and of the row within dx of a wall, must be (d - 1)/R to
 * within 4%. With exact normals each pair reads the curvature of its level
 * set, and the reading, taken to the surface from the neighbours' mean
 * depth u_a and the particle's own depth delta_a (kernels/surface.cl,
 * surface_curvature), is the surface's on every row. The scatter of a
 * model's normals is left out, so this holds the terms that map the
 * reading to the surface, which the band's mean does not. */
static void check_exact_normal_curvature(const char *label, const amsph_case *c, exact_sphere e)
{
    const double tolerance = 0.04; /* see test_exact_normal_curvature */
    amsph_host_particles h = {0};
    if (curvature_on_exact_normals(c, e, &h)) {
        amsph_host_free(&h);
        return;
    }
    const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
    const amsph_real *psi = amsph_host_real(&h, AMSPH_FIELD_NORMAL_WEIGHT);
    const amsph_real *kappa = amsph_host_real(&h, AMSPH_FIELD_RAW_CURVATURE);
    const double expected = -e.side * (c->dim - 1) / e.radius;
    double sum[CURVATURE_ROWS + 1] = {0.0}, low[CURVATURE_ROWS + 1], high[CURVATURE_ROWS + 1];
    int count[CURVATURE_ROWS + 1] = {0};
    for (int k = 0; k <= CURVATURE_ROWS; ++k)
        low[k] = INFINITY, high[k] = -INFINITY;
    for (int i = 0; i < h.n; ++i) {
        if (!(psi[i] > 0.0))
            continue;
        double r2 = 0.0;
        for (int d = 0; d < 3; ++d)
            r2 += (x[3 * i + d] - e.centre[d]) * (x[3 * i + d] - e.centre[d]);
        int k = (int)floor(e.side * (e.radius - sqrt(r2)) / c->dx);
        if (x[3 * i + c->dim - 1] < e.wall + c->dx)
            k = CURVATURE_ROWS;
        else if (k < 0 || k >= CURVATURE_ROWS)
            continue;
        const double ratio = kappa[i] / expected;
        sum[k] += ratio;
        low[k] = fmin(low[k], ratio);
        high[k] = fmax(high[k], ratio);
        ++count[k];
    }
    for (int k = 0; k <= CURVATURE_ROWS; ++k) {
        if (!count[k])
            continue;
        const double mean = sum[k] / count[k];
        char row[32] = "wall row";
        if (k < CURVATURE_ROWS)
            snprintf(row, sizeof row, "row %d-%d dx down", k, k + 1);
        printf("%s, exact normals, %s: curvature %.4f of (d - 1)/R (%d particles, %.3f to %.3f)\n", label, row,
               mean, count[k], low[k], high[k]);
        CHECK(fabs(mean - 1.0) < tolerance, "%s, exact normals, %s: curvature %g of (d - 1)/R", label, row, mean);
    }
    amsph_host_free(&h);
}

/* The liquid around a bubble of R = 1 m = 10 dx (quintic kernel, gas at a
 * hundredth of the liquid's density), periodic. */
static const char *bubble_case = "dimension: 3\n"
                                 "domain: {min: [-1.5, -1.5, -1.5], max: [1.5, 1.5, 1.5], "
                                 "periodic: [true, true, true]}\n"
                                 "dx: 0.1\n"
                                 "kernel: quintic\n"
                                 "end_time: 1\n"
                                 "output_interval: 1\n"
                                 "fluid: {pressure_gradient: multiphase}\n"
                                 "surface: {}\n"
                                 "materials:\n"
                                 "  - {name: liquid, density: 1000, viscosity: 40, sound_speed: 3, "
                                 "surface_tension: 10}\n"
                                 "  - {name: air, phase: gas, density: 10, viscosity: 4, sound_speed: 3}\n"
                                 "geometry:\n"
                                 "  - {shape: sphere, kind: fluid, material: air, center: [0, 0, 0], radius: 1.0}\n"
                                 "  - {shape: box, kind: fluid, material: liquid, min: [-1.5, -1.5, -1.5], "
                                 "max: [1.5, 1.5, 1.5], fill: true}\n";

/* The operator on exact normals: the lattice circle and sphere of the
 * Young-Laplace cases (R = 20 and 10 dx), the liquid around a bubble of R =
 * 10 dx, and the cap of sessile_cap_3d.yaml at 120 degrees made exact
 * (R = 10 dx, its centre R/2 above the wall's face, on the wall's lattice:
 * the liquid's lowest layer dx/2 above the face), whose rows a wall cuts.
 * Every row reads within 4%: measured 0.973 to 1.032 (the band's inner row
 * of the sphere and the cap low, of the bubble high). Each term that takes
 * the reading to the surface moves a row past 4% when left out (BENCHMARKS.md,
 * "The curvature operator on exact normals"): the level set's reading as it
 * is, 1.06 to 1.10 (0.93 on the bubble); without u_a, 0.930 on the sphere's
 * inner row and 1.082 on the bubble's; without its sag term, 0.951 on the
 * cap's; without the 45-degree cone in delta_a, 1.098 on the bubble, whose
 * own row lies above the particle; without the half spacing in delta_a,
 * 1.043 on the sphere's outer row. Russell's (n^_b - n^_a) . r_ab in place
 * of n^_b . t_ab reads 0.960 and 1.064 on the inner rows. */
static void test_exact_normal_curvature(void)
{
    amsph_case c;
    if (!testing_load_case("young_laplace_2d.yaml", &c))
        check_exact_normal_curvature("circle", &c, (exact_sphere){{0, 0, 0}, 1.0, 1.0, -INFINITY});
    if (!testing_load_case("young_laplace_3d.yaml", &c))
        check_exact_normal_curvature("sphere", &c, (exact_sphere){{0, 0, 0}, 1.0, 1.0, -INFINITY});
    if (!parse(bubble_case, &c))
        check_exact_normal_curvature("bubble", &c, (exact_sphere){{0, 0, 0}, 1.0, -1.0, -INFINITY});
    if (!testing_load_case("sessile_cap_3d.yaml", &c)) {
        const double radius = 10.0 * c.dx;
        c.geometry[2].radius = radius;
        c.geometry[2].center[2] = 0.5 * radius;
        const exact_sphere cap = {{0, 0, 0.5 * radius}, radius, 1.0, 0.0};
        check_exact_normal_curvature("cap at 120 degrees", &c, cap);
    }
}

/* Russell 2018 §4.2 with the right law (erratum 1): a droplet of radius
 * R = 1 m with sigma = 10 N/m holds (d - 1) sigma / R inside, within
 * `tolerance`, and after the relaxation damping ends its largest speed
 * stays below `speed_limit`. */
static void check_young_laplace(const char *file, int form, double tolerance, double speed_limit)
{
    amsph_case c;
    amsph_host_particles h = {0};
    if (testing_load_case(file, &c))
        return;
    c.surface.tension_form = form;
    if (!testing_run_case(&c, 0, c.end_time, &h)) {
        const double expected = (c.dim - 1) * 10.0;
        double pressure, speed;
        droplet_state(&h, 1.0, &pressure, &speed);
        printf("young-laplace %dD (%s): pressure inside %.4f Pa ((d - 1) sigma/R = %g), largest speed %.2e m/s\n",
               c.dim, form == TENSION_FORM_CSF ? "csf" : "conservative", pressure, expected, speed);
        CHECK(fabs(pressure / expected - 1.0) < tolerance, "pressure inside the %dD droplet %g Pa, expected %g Pa",
              c.dim, pressure, expected);
        CHECK(speed < speed_limit, "the droplet is not at rest: largest speed %g m/s", speed);
    }
    amsph_host_free(&h);
}

/* 2D at R = 20 dx: within 5% (the thesis's scheme was 40% off), at rest to
 * 1% of the capillary speed sqrt(sigma/(rho R)) = 0.1 m/s. 3D at R = 10 dx
 * (young_laplace_3d.yaml, 4224 particles): the law 2 sigma/R within 5% (a
 * 2D law sigma/R would read 50% low). Before the band's curvature was taken
 * to the surface and normalised by its tangential moment it read +7.5% here
 * (+4.7% at R = 20 dx) and +3.1% in 2D; BENCHMARKS.md, "The curvature at the
 * surface". The 3D droplet's parasitic speed at R = 10 dx is 3.5% of the
 * capillary speed, so rest is not checked there. */
static void test_young_laplace(void)
{
    check_young_laplace("young_laplace_2d.yaml", TENSION_FORM_CSF, 0.05, 1e-3);
    check_young_laplace("young_laplace_3d.yaml", TENSION_FORM_CSF, 0.05, INFINITY);
}

/* The conservative form holds the 2D law as the CSF force does, to the
 * same goals (measured +0.04% and 4.7e-4 m/s; the CSF force -0.32% and
 * 6.3e-4 m/s). */
static void test_young_laplace_conservative(void)
{
    check_young_laplace("young_laplace_2d.yaml", TENSION_FORM_CONSERVATIVE, 0.05, 1e-3);
}

/* A 1 m x 1 m square patch (sigma = 10 N/m, no gravity, no damping)
 * relaxes to a circle of radius 1/sqrt(pi): the outer radius, in 36
 * sectors about the centre of mass (outermost particle + dx/2), within 1%
 * of it with a spread below 0.2 dx, and the parasitic speed below 1e-3 of
 * the capillary speed sqrt(sigma/(rho R)) = 0.133 m/s. */
static void test_square_droplet(void)
{
    amsph_case c;
    amsph_host_particles h = {0};
    if (!testing_load_case("square_droplet_2d.yaml", &c) && !testing_run_case(&c, 0, c.end_time, &h)) {
        enum { SECTORS = 36 };
        const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
        const amsph_real *v = amsph_host_real(&h, AMSPH_FIELD_VELOCITY);
        double centre[2] = {0.0, 0.0}, outer[SECTORS] = {0}, speed = 0.0;
        for (int i = 0; i < h.n; ++i)
            for (int d = 0; d < 2; ++d)
                centre[d] += x[3 * i + d] / h.n;
        for (int i = 0; i < h.n; ++i) {
            const double dx = x[3 * i] - centre[0], dy = x[3 * i + 1] - centre[1];
            int sector = (int)floor((atan2(dy, dx) + PI) / (2 * PI) * SECTORS);
            sector = sector < 0 ? 0 : sector >= SECTORS ? SECTORS - 1 : sector;
            outer[sector] = fmax(outer[sector], hypot(dx, dy) + 0.5 * c.dx);
            speed = fmax(speed, hypot(v[3 * i], v[3 * i + 1]));
        }
        double mean = 0.0, spread = 0.0;
        for (int k = 0; k < SECTORS; ++k)
            mean += outer[k] / SECTORS;
        for (int k = 0; k < SECTORS; ++k)
            spread += (outer[k] - mean) * (outer[k] - mean) / SECTORS;
        spread = sqrt(spread);
        const double radius = 1.0 / sqrt(PI);
        printf("square droplet: outer radius %.4f m (circle %.4f), spread %.4f m, speed %.2e m/s\n",
               mean, radius, spread, speed);
        CHECK(fabs(mean - radius) < 0.01 * radius, "outer radius %g m, circle %g m", mean, radius);
        CHECK(spread < 0.2 * c.dx, "the shape is not round: radius spread %g m", spread);
        CHECK(speed < 1.33e-4, "parasitic speed %g m/s", speed);
    }
    amsph_host_free(&h);
}

/* A liquid layer of depth d = 0.5 m in a closed box 2 m long under gravity,
 * with the temperature held at T = G x: the Marangoni stress
 * tau = d sigma/dT G drives the surface towards the cold end and the
 * pressure of the tilted surface drives the return flow below it. Away from
 * the ends (lubrication theory, zero net flux, no slip at y = 0):
 *   u(y) = tau d / (4 mu) (3 (y/d)^2 - 2 y/d).
 * mu sets the viscous spin-up d^2/nu and the surface's settling time
 * 3 L^2 mu / (rho g d^3) both to ~1.5 s; the profile is taken at 6 s in the
 * middle quarter. The CSF force spreads the stress over the two top rows
 * (0.1 d at d = 10 dx), which shifts the profile by O(dx/d): here the
 * profile must be within 10% of tau d / (4 mu) everywhere (measured 6.6%;
 * 4.3% at d = 20 dx, BENCHMARKS.md). */
static const double marangoni_gradient = 1.0;   /* G, K/m */
static const double marangoni_slope = -0.01;    /* d sigma/dT, N/(m K) */
static const double marangoni_viscosity = 0.16; /* mu, Pa s */
static const double marangoni_depth = 0.5;      /* d, m */

static const char *marangoni_case =
    "dimension: 2\n"
    "domain: {min: [-0.3, -0.3], max: [2.3, 1.0]}\n"
    "dx: 0.05\n"
    "kernel: quintic\n"
    "end_time: 6\n"
    "output_interval: 6\n"
    "gravity: [0, -10]\n"
    "fluid: {density_diffusion: fourtakas}\n"
    "surface: {tension: false, marangoni: true}\n"
    "materials:\n"
    "  - {name: liquid, density: 1, viscosity: 0.16, sound_speed: 15, surface_tension: 1,\n"
    "     surface_tension_slope: -0.01}\n"
    "geometry:\n"
    "  - {shape: box, kind: wall, material: liquid, min: [0, 0], max: [2, 0.8], layers: 3,\n"
    "     open: [+y], temperature: 0}\n"
    "  - {shape: box, kind: fluid, material: liquid, min: [0, 0], max: [2, 0.5], hydrostatic: true,\n"
    "     temperature: 0}\n";

/* After every step: T = G x on every particle. */
static int hold_temperature(void *context, const amsph_sim *s)
{
    amsph_real *buffer = context;
    const int n = s->particles.n;
    const size_t vec = (size_t)n * 3 * sizeof(amsph_real), scalar = (size_t)n * sizeof(amsph_real);
    if (amsph_download(s->backend, s->particles.field[AMSPH_FIELD_POSITION], 0, vec, buffer))
        return 1;
    for (int i = 0; i < n; ++i)
        buffer[i] = (amsph_real)(marangoni_gradient * buffer[3 * i]);
    return amsph_upload(s->backend, s->particles.field[AMSPH_FIELD_TEMPERATURE], 0, scalar, buffer);
}

static void test_marangoni_return_flow(void)
{
    amsph_case c;
    if (parse(marangoni_case, &c))
        return;
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    amsph_host_particles h = {0};
    CHECK_OK(amsph_sim_create(&c, b, &s));
    amsph_real *buffer = malloc((size_t)s.particles.capacity * 3 * sizeof(amsph_real));
    CHECK_OK(hold_temperature(buffer, &s));
    CHECK_OK(amsph_sim_advance(&s, c.end_time, hold_temperature, buffer));
    if (!download(&s, &h)) {
        const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
        const amsph_real *v = amsph_host_real(&h, AMSPH_FIELD_VELOCITY);
        const int *k = (const int *)h.data[AMSPH_FIELD_KIND];
        enum { ROWS = 10 };
        double sum[ROWS] = {0}, count[ROWS] = {0};
        for (int i = 0; i < h.n; ++i) {
            const int row = (int)floor(x[3 * i + 1] / c.dx);
            if (k[i] == AMSPH_KIND_FLUID && x[3 * i] > 0.75 && x[3 * i] < 1.25 && row >= 0 && row < ROWS) {
                sum[row] += v[3 * i];
                count[row] += 1;
            }
        }
        const double d = marangoni_depth;
        const double surface_speed = marangoni_slope * marangoni_gradient * d / (4.0 * marangoni_viscosity);
        double worst = 0.0;
        for (int row = 0; row < ROWS; ++row) {
            const double eta = (row + 0.5) * c.dx / d;
            const double exact = surface_speed * (3.0 * eta * eta - 2.0 * eta);
            const double u = count[row] ? sum[row] / count[row] : NAN;
            worst = fmax(worst, fabs(u - exact) / fabs(surface_speed));
            printf("marangoni: y/d %.3f  u %+.4e  exact %+.4e\n", eta, u, exact);
        }
        CHECK(worst < 0.10, "return-flow profile off by %g of tau d / (4 mu)", worst);
    }
    free(buffer);
    amsph_host_free(&h);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
}

/* The sessile patch of sessile_droplet_2d.yaml with contact angle theta0
 * (degrees; 0: none, complete wetting). */
static int sessile_case(double theta0, double end_time, amsph_case *c)
{
    if (testing_load_case("sessile_droplet_2d.yaml", c))
        return 1;
    c->materials[0].contact_angle = theta0;
    c->end_time = end_time;
    return 0;
}

/* At t = 0, on the square patch of sessile_droplet_2d.yaml: the unit normal
 * of the liquid particle at each lower corner (the contact line, solid
 * colour c_sf above c2 = 0.2, so Eq. 29 takes the prescribed normal whole)
 * is Fuchs's Eq. 27 n^ = t sin theta0 - n_sf cos theta0, with n_sf = -y
 * (into the wall) and t = +-x (away from the liquid), in this module's
 * inward sign: -(+-sin theta0, cos theta0). */
static void test_contact_line_normal(double theta0)
{
    amsph_case c;
    amsph_host_particles h = {0};
    if (!sessile_case(theta0, 1.0, &c) && !testing_run_case(&c, 0, 0.0, &h)) {
        const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
        const amsph_real *n = amsph_host_real(&h, AMSPH_FIELD_UNIT_NORMAL);
        const int *kind = (const int *)h.data[AMSPH_FIELD_KIND];
        const double angle = theta0 * PI / 180.0;
        int corners = 0;
        for (int i = 0; i < h.n; ++i) {
            if (kind[i] != AMSPH_KIND_FLUID || x[3 * i + 1] > c.dx || fabs(x[3 * i]) < 0.75 - c.dx)
                continue;
            const double side = x[3 * i] > 0 ? 1.0 : -1.0;
            const double expected[2] = {-side * sin(angle), -cos(angle)};
            const double error = hypot(n[3 * i] - expected[0], n[3 * i + 1] - expected[1]);
            CHECK(error < 1e-5, "theta0 %g: contact-line normal (%g, %g), expected (%g, %g)", theta0, n[3 * i],
                  n[3 * i + 1], expected[0], expected[1]);
            ++corners;
        }
        CHECK(corners == 2, "found %d contact-line particles, expected 2", corners);
    }
    amsph_host_free(&h);
}

/* The surface passes leave out the particles more than SURFACE_NEAR_BLOCKS
 * blocks from the liquid (kernels/surface.cl, blocks_from_liquid), and
 * where every liquid has a contact angle the normals of solids and walls
 * and the Shepard sums beyond one block; the liquid must move as it does
 * when every particle takes part (near_blocks beyond the grid, which also
 * gives every particle a normal). The sessile droplet's wall reaches 4 to 5
 * blocks past the drop on each side; at theta0 = 0 the liquid's curvature
 * sums over the wall's surface normals beside it too. Fails with one block
 * too few. */
static void test_passes_near_liquid(double theta0)
{
    static const amsph_field_id fields[] = {AMSPH_FIELD_POSITION, AMSPH_FIELD_VELOCITY, AMSPH_FIELD_DENSITY,
                                            AMSPH_FIELD_CURVATURE};
    amsph_case c;
    if (sessile_case(theta0, 0.1, &c))
        return;
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_backend *b = testing_backend(k);
        amsph_host_particles h[2] = {{0}};
        int have = 0;
        for (int every = 0; every < 2 && b; ++every) {
            amsph_sim s;
            if (amsph_sim_create(&c, b, &s) == 0) {
                if (every)
                    s.surface.near_blocks = 1000;
                have += amsph_sim_advance(&s, c.end_time, NULL, NULL) == 0 && download(&s, &h[every]) == 0;
            }
            CHECK(have == every + 1, "theta0 %g: %s", theta0, amsph_last_error());
            amsph_sim_free(&s);
        }
        for (size_t f = 0; f < sizeof fields / sizeof fields[0] && have == 2; ++f) {
            double largest, diff;
            testing_field_difference(&h[0], &h[1], fields[f], &largest, &diff);
            CHECK(diff == 0.0, "theta0 %g, backend %d: %s differs by %g (largest %g) when every particle "
                  "takes part", theta0, k, amsph_fields[fields[f]].name, diff, largest);
        }
        for (int every = 0; every < 2; ++every)
            amsph_host_free(&h[every]);
        amsph_backend_destroy(b);
    }
}

/* Contact angle of a sessile drop from its particles: a circle (2D) or
 * sphere (3D) by Kasa's algebraic least-squares fit through the free-surface
 * fluid particles (fewer particles of any kind within 2.1 dx than a lattice's
 * interior: below 11 of 12 in 2D, 29 of 32 in 3D) more than 2 dx above the
 * wall face (the last axis at 0), its radius taken dx/2 out (the surface lies
 * half a spacing beyond the outer particles); cos theta = (0 - centre) /
 * radius on the last axis (theta in the liquid, degrees). tools/contact_angle.py
 * reads snapshots the same way. */
static double sessile_angle(const amsph_host_particles *h, int dim, double dx)
{
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
    const int *kind = (const int *)h->data[AMSPH_FIELD_KIND];
    const int up = dim - 1, unknowns = dim + 1, interior = dim == 2 ? 11 : 29;
    double m[4][5] = {{0}};
    for (int i = 0; i < h->n; ++i) {
        if (kind[i] != AMSPH_KIND_FLUID || x[3 * i + up] < 2.0 * dx)
            continue;
        int near = 0;
        for (int j = 0; j < h->n; ++j) {
            double r2 = 0.0;
            for (int d = 0; d < dim; ++d)
                r2 += (x[3 * j + d] - x[3 * i + d]) * (x[3 * j + d] - x[3 * i + d]);
            near += j != i && r2 < 2.1 * dx * 2.1 * dx;
        }
        if (near >= interior)
            continue;
        /* x.x + D.x + F = 0: normal equations of (x, 1) (D, F) = -x.x */
        double row[4], rhs = 0.0;
        for (int d = 0; d < dim; ++d) {
            row[d] = x[3 * i + d];
            rhs -= row[d] * row[d];
        }
        row[dim] = 1.0;
        for (int r = 0; r < unknowns; ++r) {
            for (int k = 0; k < unknowns; ++k)
                m[r][k] += row[r] * row[k];
            m[r][unknowns] += row[r] * rhs;
        }
    }
    for (int p = 0; p < unknowns; ++p) /* Gauss-Jordan; the matrix is symmetric positive definite */
        for (int r = 0; r < unknowns; ++r) {
            if (r == p)
                continue;
            const double f = m[r][p] / m[p][p];
            for (int k = 0; k <= unknowns; ++k)
                m[r][k] -= f * m[p][k];
        }
    double centre[3], radius2 = -m[dim][unknowns] / m[dim][dim];
    for (int d = 0; d < dim; ++d) {
        centre[d] = -0.5 * m[d][unknowns] / m[d][d];
        radius2 += centre[d] * centre[d];
    }
    const double radius = sqrt(radius2) + 0.5 * dx;
    return acos(fmax(-1.0, fmin(1.0, -centre[up] / radius))) * 180.0 / PI;
}

/* theta0 = 90 degrees holds the square patch at its 90-degree contact
 * angle to 5 degrees (measured 91.2 at 10 s; no damping), while the
 * completely wetting patch (no contact angle) spreads past 80 degrees by
 * 5 s (76 at 4 s, 49 at 8 s). */
static void test_sessile_droplet(void)
{
    static const struct {
        double theta0, end_time, lowest, highest;
    } runs[] = {{90.0, 10.0, 85.0, 95.0}, {0.0, 5.0, 0.0, 80.0}};
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; ++k) {
        amsph_case c;
        amsph_host_particles h = {0};
        if (!sessile_case(runs[k].theta0, runs[k].end_time, &c) && !testing_run_case(&c, 0, c.end_time, &h)) {
            const double angle = sessile_angle(&h, c.dim, c.dx);
            printf("sessile droplet: theta0 %g, contact angle %.2f degrees at %g s\n", runs[k].theta0, angle,
                   c.end_time);
            CHECK(angle > runs[k].lowest && angle < runs[k].highest,
                  "theta0 %g: contact angle %g degrees at %g s, expected in (%g, %g)", runs[k].theta0, angle,
                  c.end_time, runs[k].lowest, runs[k].highest);
        }
        amsph_host_free(&h);
    }
}

/* Moves the faces of the case's boxes to the nearest multiples of its dx, so
 * that at a spacing other than the case's a wall's top layer still lies dx/2
 * below its face, as the centred lattice of the drop's lowest layer lies
 * dx/2 above it (sessile_cap_3d.yaml's 3.22 m wall, 46 layers at its 0.07 m,
 * is 32 layers of 0.1 m over 3.2 m). */
static void boxes_on_lattice(amsph_case *c)
{
    for (int g = 0; g < c->n_geometry; ++g)
        if (c->geometry[g].shape == AMSPH_SHAPE_BOX)
            for (int d = 0; d < c->dim; ++d) {
                c->geometry[g].min[d] = c->dx * round(c->geometry[g].min[d] / c->dx);
                c->geometry[g].max[d] = c->dx * round(c->geometry[g].max[d] / c->dx);
            }
}

/* A sessile cap of `file` at contact angle theta0, run to end_time (s; 0:
 * the case's) at spacing dx (0: the case's), comes to rest at theta0: its
 * contact angle within 5 degrees, no particle faster than 2% of the capillary
 * speed sigma / mu (0.25 m/s). */
static void check_sessile_cap(const char *file, double theta0, double dx, double end_time)
{
    amsph_case c;
    amsph_host_particles h = {0};
    if (testing_load_case(file, &c))
        return;
    c.materials[0].contact_angle = theta0;
    if (dx > 0.0) {
        amsph_case_set_spacing(&c, dx);
        boxes_on_lattice(&c);
    }
    c.end_time = end_time > 0.0 ? end_time : c.end_time;
    if (!testing_run_case(&c, 0, c.end_time, &h)) {
        const double angle = sessile_angle(&h, c.dim, c.dx);
        const amsph_real *u = amsph_host_real(&h, AMSPH_FIELD_VELOCITY);
        const int *kind = (const int *)h.data[AMSPH_FIELD_KIND];
        double fastest = 0.0;
        for (int i = 0; i < h.n; ++i)
            if (kind[i] == AMSPH_KIND_FLUID)
                fastest = fmax(fastest, sqrt(u[3 * i] * u[3 * i] + u[3 * i + 1] * u[3 * i + 1] +
                                             u[3 * i + 2] * u[3 * i + 2]));
        const double capillary_speed = c.materials[0].surface_tension / c.materials[0].viscosity;
        printf("sessile cap %s: theta0 %g, contact angle %.2f degrees, fastest %.2e m/s at %g s\n", file, theta0,
               angle, fastest, c.end_time);
        CHECK(fabs(angle - theta0) < 5.0, "%s, theta0 %g: contact angle %g degrees at %g s", file, theta0, angle,
              c.end_time);
        CHECK(fastest < 0.02 * capillary_speed, "%s, theta0 %g: not at rest, a particle at %g m/s", file, theta0,
              fastest);
    }
    amsph_host_free(&h);
}

/* The half disc of sessile_cap_2d.yaml (radius 0.85 m on a free-slip wall,
 * a 90-degree contact angle as built) relaxes to a cap at the contact angle
 * theta0 = 60 and 120 degrees and comes to rest there by 40 s (issue 10,
 * item 5; measured 61.25 and 120.25 degrees, fastest 0.24% and 0.40% of the
 * capillary speed; 58.9 and 116.5 before the curvature was taken to the
 * surface). The interface viscosity keeps the momentum, so the
 * 60-degree cap overshoots to 54 degrees at 12 s and is still moving at 20 s
 * (2.6%; BENCHMARKS.md). The half sphere of sessile_cap_3d.yaml at 60
 * degrees, at dx = 0.1 m (radius 8.5 dx) to 20 s: measured 64.74 degrees
 * (64.25 with Russell's divergence sum, 62.1 before the curvature was taken
 * to the surface). In 3D the caps rest off theta0 toward 90 degrees, as the
 * push on the rows at the wall sets it (BENCHMARKS.md, "The solids coloured
 * as the surface extended into them"): at 120 degrees this spacing rests at
 * 112.1 to 112.7 from 40 to 60 s, the case's 12 dx at 115.5 to 116.6 from
 * 14 to 40 s, and 16 dx overshoots to 123.4 and slides back to 116.9 at 36 s
 * (BENCHMARKS.md, "The curvature along the surface" and "The 3D cap at 120
 * degrees by resolution"). */
static void test_sessile_cap(void)
{
    check_sessile_cap("sessile_cap_2d.yaml", 60.0, 0.0, 0.0);
    check_sessile_cap("sessile_cap_2d.yaml", 120.0, 0.0, 0.0);
    check_sessile_cap("sessile_cap_3d.yaml", 60.0, 0.1, 20.0);
}

/* A velocity field on the disc of young_laplace_2d.yaml (R = 1 m, centre 0):
 * u = (u0 - w y + e x + q y^2, v0 + w x - e y), a translation, a rigid
 * rotation w, a plane strain e and a shear q y^2 (whose viscous force does
 * not vanish by the disc's symmetry). */
typedef struct {
    double spin, strain, shear;
} disc_flow;

enum { DISC_PARTICLES = 2000 }; /* room for the disc's particles (pi R^2 / dx^2, about 1260) */

/* The surface force's acceleration on the disc of case c (young_laplace_2d.yaml
 * or a variant) moving with the flow f: accel[3 n], x[3 n] and the
 * velocities u[3 n] of the n particles are written. */
static int disc_acceleration(const amsph_case *c, disc_flow f, double *accel, double *x, double *u, int *n)
{
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    amsph_host_particles h = {0};
    int status = !b || amsph_sim_create(c, b, &s);
    if (b && !status) {
        status = download(&s, &h);
        CHECK(h.n <= DISC_PARTICLES, "the disc has %d particles, room for %d", h.n, DISC_PARTICLES);
        status = status || h.n > DISC_PARTICLES;
        amsph_real *xh = amsph_host_real(&h, AMSPH_FIELD_POSITION), *uh = amsph_host_real(&h, AMSPH_FIELD_VELOCITY);
        amsph_real *ah = amsph_host_real(&h, AMSPH_FIELD_ACCELERATION);
        for (int i = 0; i < h.n && !status; ++i) {
            const double xi = xh[3 * i + 0], yi = xh[3 * i + 1];
            uh[3 * i + 0] = (amsph_real)(0.1 - f.spin * yi + f.strain * xi + f.shear * yi * yi);
            uh[3 * i + 1] = (amsph_real)(0.05 + f.spin * xi - f.strain * yi);
            ah[3 * i + 0] = ah[3 * i + 1] = ah[3 * i + 2] = 0;
        }
        const size_t bytes = (size_t)h.n * 3 * sizeof(amsph_real);
        status = status || amsph_upload(b, s.particles.field[AMSPH_FIELD_VELOCITY], 0, bytes, uh) ||
                 amsph_upload(b, s.particles.field[AMSPH_FIELD_ACCELERATION], 0, bytes, ah) ||
                 amsph_surface_forces(&s) || download(&s, &h);
        CHECK(status == 0, "%s", amsph_last_error());
        for (int i = 0; i < h.n && !status; ++i) {
            for (int d = 0; d < 3; ++d) {
                accel[3 * i + d] = amsph_host_real(&h, AMSPH_FIELD_ACCELERATION)[3 * i + d];
                x[3 * i + d] = amsph_host_real(&h, AMSPH_FIELD_POSITION)[3 * i + d];
                u[3 * i + d] = amsph_host_real(&h, AMSPH_FIELD_VELOCITY)[3 * i + d];
            }
        }
        *n = h.n;
        amsph_host_free(&h);
        amsph_sim_free(&s);
    }
    amsph_backend_destroy(b);
    return status;
}

/* The surface force's acceleration on the disc of young_laplace_2d.yaml
 * moving with the flow f, with the interface viscosity alpha0 (Fuchs et
 * al. 2022 Eqs. 31-32) or without it (alpha0 = 0): the state is the same,
 * so the difference of the two is the interface viscosity's. */
static int interface_viscosity_acceleration(double alpha0, disc_flow f, double *accel, double *x, double *u, int *n)
{
    amsph_case c;
    if (testing_load_case("young_laplace_2d.yaml", &c))
        return 1;
    c.surface.interface_viscosity = alpha0;
    return disc_acceleration(&c, f, accel, x, u, n);
}

/* An L of liquid (0.75 m^2, sigma = 10 N/m, no gravity): two boxes on one
 * lattice, with convex corners and a concave one. Mirror symmetric about
 * y = x only, so the tension's errors need not cancel along (1, 1). */
static const char *l_drop_case =
    STILL_LIQUID_CASE("domain: {min: [-1.5, -1.5], max: [1.5, 1.5]}\n",
                      "  - {shape: box, kind: fluid, material: liquid, min: [-0.5, -0.5], max: [0, 0.5]}\n"
                      "  - {shape: box, kind: fluid, material: liquid, min: [0, -0.5], max: [0.5, 0]}\n");

/* The net of the tension on the L at rest in the tension form `form`:
 * |sum_a m_a a_a| and sum_a |m_a a_a| (equal masses, so in units of m). */
static int l_drop_net_tension(int form, double *net, double *scale)
{
    static double a[3 * DISC_PARTICLES], x[3 * DISC_PARTICLES], u[3 * DISC_PARTICLES];
    amsph_case c;
    int n = 0;
    if (parse(l_drop_case, &c))
        return 1;
    c.surface.tension_form = form;
    if (disc_acceleration(&c, (disc_flow){0}, a, x, u, &n))
        return 1;
    double sum[2] = {0.0, 0.0};
    *scale = 0.0;
    for (int i = 0; i < n; ++i) {
        sum[0] += a[3 * i];
        sum[1] += a[3 * i + 1];
        *scale += hypot(a[3 * i], a[3 * i + 1]);
    }
    *net = hypot(sum[0], sum[1]);
    return 0;
}

/* The tension's net force on a closed drop is zero in the continuum (the
 * closed integral of kappa n vanishes). The CSF force's sum over the
 * particles is the error of the curvature along the surface, which the
 * corners of an L show (a disc at rest shows almost none: 2e-7 of the
 * sum of sizes, off the lattice's symmetry); the conservative form
 * (surface_share) sums to the capillary stress's divergence, whose pair
 * terms cancel: zero to float round-off (1e-5 of the sum of sizes). */
static void test_conservative_net_force(void)
{
    double csf_net, csf_scale, net, scale;
    if (l_drop_net_tension(TENSION_FORM_CSF, &csf_net, &csf_scale) ||
        l_drop_net_tension(TENSION_FORM_CONSERVATIVE, &net, &scale))
        return;
    printf("tension on an L: net %.3g of %.3g (CSF), %.3g of %.3g (conservative)\n", csf_net, csf_scale, net,
           scale);
    CHECK(csf_net > 1e-3 * csf_scale, "the CSF force's net on the L, %g of %g, leaves nothing to test", csf_net,
          csf_scale);
    CHECK(scale > 0.0 && net < 1e-5 * scale, "the conservative tension's net on the L: %g of %g", net, scale);
}

/* The interface viscosity's acceleration da[3 n] on the disc in the flow
 * f (alpha0 = 7.2 as Fuchs et al. 2022 Table 1), with x, u and n as
 * interface_viscosity_acceleration writes them. */
static int interface_viscosity_part(disc_flow f, double *da, double *x, double *u, int *n)
{
    static double a0[3 * DISC_PARTICLES];
    if (interface_viscosity_acceleration(0.0, f, a0, x, u, n) ||
        interface_viscosity_acceleration(7.2, f, da, x, u, n))
        return 1;
    for (int i = 0; i < 3 * *n; ++i)
        da[i] -= a0[i];
    return 0;
}

/* The interface viscosity is a viscosity of the interface: it leaves a
 * rigid motion (translation and rotation: u_ab . r_ab = 0) alone, it
 * dissipates a strain (sum m u . a < 0: the power of a viscous force),
 * and it acts near the surface only (alpha = alpha0 h |n|, and |n|
 * vanishes a support below the surface; a pair takes the larger alpha of
 * its two, so the force reaches two supports deep), while the strain rate
 * is the same everywhere. */
static void test_interface_viscosity(void)
{
    static double da[3 * DISC_PARTICLES], x[3 * DISC_PARTICLES], u[3 * DISC_PARTICLES];
    const double radius = 1.0, support = 3.6 * 0.05;
    int n = 0;
    double rigid = 0.0, surface = 0.0, bulk = 0.0, power = 0.0;
    if (interface_viscosity_part((disc_flow){.spin = 0.3}, da, x, u, &n))
        return;
    for (int i = 0; i < 3 * n; ++i)
        rigid = fmax(rigid, fabs(da[i]));
    if (interface_viscosity_part((disc_flow){.spin = 0.3, .strain = 0.1}, da, x, u, &n))
        return;
    for (int i = 0; i < n; ++i) {
        const double r = hypot(x[3 * i], x[3 * i + 1]), magnitude = hypot(da[3 * i], da[3 * i + 1]);
        power += u[3 * i] * da[3 * i] + u[3 * i + 1] * da[3 * i + 1]; /* equal masses */
        if (r < radius - 2.0 * support - 0.05)
            bulk = fmax(bulk, magnitude);
        else
            surface = fmax(surface, magnitude);
    }
    printf("interface viscosity: rigid motion %g, strain: surface %g, bulk %g m/s^2, power %g\n", rigid, surface,
           bulk, power);
    CHECK(surface > 0.0 && rigid < 1e-4 * surface, "rigid motion: %g m/s^2 (strain at the surface: %g)", rigid,
          surface);
    CHECK(bulk < 1e-3 * surface, "strain: %g m/s^2 in the bulk, %g at the surface", bulk, surface);
    CHECK(power < 0.0, "strain: power %g, not dissipated", power);
}

/* The interface viscosity keeps the liquid's momentum: its pair forces are
 * equal and opposite and along r_ab, so over the disc (equal masses) in a
 * flow with a shear, its accelerations sum to 0 and so do their moments
 * about the centre, to float round-off (1e-5 of the sums of their sizes).
 * Fuchs's Eq. 31 as printed, each particle's sum weighed with its own
 * alpha, does not: a surface particle and the one below it pull each other
 * unequally. */
static void test_interface_viscosity_momentum(void)
{
    static double da[3 * DISC_PARTICLES], x[3 * DISC_PARTICLES], u[3 * DISC_PARTICLES];
    int n = 0;
    if (interface_viscosity_part((disc_flow){.spin = 0.3, .strain = 0.1, .shear = 0.5}, da, x, u, &n))
        return;
    double net[2] = {0.0, 0.0}, moment = 0.0, scale = 0.0, moment_scale = 0.0;
    for (int i = 0; i < n; ++i) {
        const double magnitude = hypot(da[3 * i], da[3 * i + 1]);
        net[0] += da[3 * i];
        net[1] += da[3 * i + 1];
        moment += x[3 * i] * da[3 * i + 1] - x[3 * i + 1] * da[3 * i];
        scale += magnitude;
        moment_scale += hypot(x[3 * i], x[3 * i + 1]) * magnitude;
    }
    printf("interface viscosity: net force (%g, %g) of %g, moment %g of %g\n", net[0], net[1], scale, moment,
           moment_scale);
    CHECK(scale > 0.0 && hypot(net[0], net[1]) < 1e-5 * scale, "net force (%g, %g), sum of sizes %g", net[0],
          net[1], scale);
    CHECK(fabs(moment) < 1e-5 * moment_scale, "net moment %g, sum of sizes %g", moment, moment_scale);
}

/* The largest speed of the undamped disc of young_laplace_2d.yaml, from
 * rest, with the interface viscosity alpha0, over its states at 0.25, 0.5,
 * 0.75 and 1 s; NAN if the run failed. */
static double undamped_disc_speed(double alpha0)
{
    amsph_case c;
    if (testing_load_case("young_laplace_2d.yaml", &c))
        return NAN;
    c.fluid.damping_rate = 0.0;
    c.surface.interface_viscosity = alpha0;
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    amsph_host_particles h = {0};
    double largest = NAN;
    if (b && amsph_sim_create(&c, b, &s) == 0) {
        largest = 0.0;
        for (int k = 1; k <= 4; ++k) {
            double pressure, speed;
            if (amsph_sim_advance(&s, 0.25 * k, NULL, NULL) || amsph_particles_download(&s.particles, &h)) {
                largest = NAN;
                break;
            }
            droplet_state(&h, 1.0, &pressure, &speed);
            largest = fmax(largest, speed);
        }
        amsph_sim_free(&s);
    }
    CHECK(!isnan(largest), "the undamped disc, alpha0 %g: %s", alpha0, amsph_last_error());
    amsph_host_free(&h);
    amsph_backend_destroy(b);
    return largest;
}

/* The interface viscosity is explicit in time, and its step limit
 * (host/surface.c) keeps it dissipative however large alpha0: the disc
 * with alpha0 = 15 (twice Fuchs's 7.2) moves no faster than without it
 * (measured 1.18e-2 against 1.70e-2 m/s in 758 and 136 steps). Without the
 * limit (285 steps: a step 2.7 times longer on average) its surface
 * jittered at up to 8.8e-2 m/s. */
static void test_interface_viscosity_step(void)
{
    const double without = undamped_disc_speed(0.0), with = undamped_disc_speed(15.0);
    printf("undamped disc: largest speed %.3e m/s without the interface viscosity, %.3e with alpha0 = 15\n",
           without, with);
    CHECK(with <= without, "the interface viscosity (alpha0 = 15) sped the disc up: %g m/s, %g without it", with,
          without);
}

/* Both backends: the same normals, curvatures and accelerations after the
 * first 0.05 s of a droplet in the tension form `form` (float: within 1e-4
 * of the largest). */
static void check_backends_agree(const char *file, int form)
{
    static const amsph_field_id fields[] = {AMSPH_FIELD_NORMAL, AMSPH_FIELD_UNIT_NORMAL,
                                            AMSPH_FIELD_CURVATURE, AMSPH_FIELD_ACCELERATION};
    amsph_case c;
    amsph_host_particles h[TESTING_BACKENDS] = {{0}};
    int have = 0;
    if (testing_load_case(file, &c))
        return;
    c.surface.tension_form = form;
    for (int k = 0; k < TESTING_BACKENDS; ++k)
        have += !testing_run_case(&c, k, 0.05, &h[k]);
    for (size_t f = 0; f < sizeof fields / sizeof fields[0] && have == TESTING_BACKENDS; ++f) {
        double largest, diff;
        testing_field_difference(&h[0], &h[1], fields[f], &largest, &diff);
        CHECK(diff <= 1e-4 * largest, "%s: backends differ by %g (largest %g) in %s", amsph_fields[fields[f]].name,
              diff, largest, file);
    }
    for (int k = 0; k < TESTING_BACKENDS; ++k)
        amsph_host_free(&h[k]);
}

int main(void)
{
    test_flat_surface();
    check_sphere_curvature(AMSPH_KERNEL_QUINTIC, 1.2);
    check_sphere_curvature(AMSPH_KERNEL_WENDLAND, 1.8);
    check_rough_sphere_curvature();
    test_exact_normal_curvature();
    test_surface_tension_law();
    test_capillary_step();
    check_backends_agree("young_laplace_2d.yaml", TENSION_FORM_CSF);
    check_backends_agree("young_laplace_2d.yaml", TENSION_FORM_CONSERVATIVE);
    check_backends_agree("young_laplace_3d.yaml", TENSION_FORM_CSF);
    check_backends_agree("sessile_droplet_2d.yaml", TENSION_FORM_CSF);
    check_backends_agree("sessile_cap_2d.yaml", TENSION_FORM_CSF);
    check_backends_agree("sessile_cap_2d.yaml", TENSION_FORM_CONSERVATIVE);
    test_conservative_net_force();
    test_contact_line_normal(60.0);
    test_contact_line_normal(120.0);
    test_passes_near_liquid(0.0);
    test_passes_near_liquid(60.0);
    test_interface_viscosity();
    test_interface_viscosity_momentum();
    test_interface_viscosity_step();
    test_sessile_droplet();
    test_sessile_cap();
    test_marangoni_return_flow();
    test_young_laplace();
    test_young_laplace_conservative();
    test_square_droplet();
    return testing_finish();
}
