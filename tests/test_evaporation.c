/* Evaporation at free surfaces against known answers: on the flat faces of
 * a lattice block at a uniform temperature T the recoil force (Fuchs et al.
 * 2022 Eqs. 10, 30) is p_v(T) times the face area, pointing into the
 * material, and nothing inside it; the evaporative heat loss (Eq. 18) is
 * q_v(T) times the area (both to 1e-5, float rounding; measured 4e-7);
 * both at two temperatures (an error in the exponent changes their ratio),
 * on both backends, which agree particle by particle. A detached particle
 * (alone, or two spacings from its neighbour) radiates and evaporates as a
 * ball of its volume. A laser-heated slab
 * that boils keeps its energy ledger closed
 * with the evaporation term; particles above a cut-off temperature leave,
 * are counted and take their enthalpy into the ledger. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "case.h"
#include "evaporation.h"
#include "sim.h"
#include "testing.h"
#include "thermal.h"

#define C_P 5.4e4       /* Pa (Fuchs Table 2) */
#define C_T 5e4         /* K */
#define T_V 3000.0      /* K */
#define H_V 6.583e6     /* J/kg */
#define C_M 1.1095e-3   /* K s^2/m^2 */
#define T_H0 663.731    /* K */
#define STICKING 0.9    /* not 1, so that a missing c_s shows */
#define HEAT 1000.0     /* J/(kg K): h(T) = HEAT T */
#define DENSITY 1000.0  /* kg/m^3 */
#define DX 0.02         /* m */
#define SIDE 0.4        /* m: the block's width along every periodic axis */

#define MATERIAL                                                                                   \
    "{name: m, density: 1000, sound_speed: 10, specific_heat: 1000, conductivity: 1e-9,\n"        \
    "   recoil_pressure_constant: 5.4e4, recoil_temperature_constant: 5e4, boiling_temperature: 3000,\n" \
    "   evaporation_latent_heat: 6.583e6, vapour_mass_constant: 1.1095e-3, sticking_coefficient: 0.9,\n" \
    "   evaporation_enthalpy_reference: 663.731}"

static double recoil_pressure(double t)
{
    return C_P * exp(-C_T * (1.0 / t - 1.0 / T_V));
}

/* q_v = 0.82 c_s p_v sqrt(C_M / T) (h_v + h(T) - h(T_h,0)), W/m^2. */
static double heat_flux(double t)
{
    return 0.82 * STICKING * recoil_pressure(t) * sqrt(C_M / t) * (H_V + HEAT * (t - T_H0));
}

static int parse(const char *text, amsph_case *c)
{
    char err[1024];
    const int status = amsph_case_parse(text, strlen(text), "test", c, err, sizeof err);
    CHECK(status == 0, "%s", err);
    return status;
}

/* A block SIDE wide along the periodic axes and SIDE / 2 high (the last
 * axis), of kind `kind` at temperature t, with its top and bottom faces
 * free: in 2D 20 x 10 particles, in 3D 20 x 20 x 10. */
static int block_case(int dim, const char *kind, double t, const char *thermal, amsph_case *c)
{
    char text[2048];
    if (dim == 2)
        snprintf(text, sizeof text,
                 "dimension: 2\n"
                 "domain: {min: [0, -0.3], max: [0.4, 0.5], periodic: [true, false]}\n"
                 "dx: 0.02\nend_time: 1\noutput_interval: 1\n%s"
                 "thermal: %s\n"
                 "materials: [" MATERIAL "]\n"
                 "geometry: [{shape: box, kind: %s, material: m, min: [0, 0], max: [0.4, 0.2], temperature: %g}]\n",
                 strcmp(kind, "fluid") == 0 ? "fluid: {}\n" : "", thermal, kind, t);
    else
        snprintf(text, sizeof text,
                 "dimension: 3\n"
                 "domain: {min: [0, 0, -0.3], max: [0.4, 0.4, 0.5], periodic: [true, true, false]}\n"
                 "dx: 0.02\nend_time: 1\noutput_interval: 1\n%s"
                 "thermal: %s\n"
                 "materials: [" MATERIAL "]\n"
                 "geometry: [{shape: box, kind: %s, material: m, min: [0, 0, 0], max: [0.4, 0.4, 0.2], "
                 "temperature: %g}]\n",
                 strcmp(kind, "fluid") == 0 ? "fluid: {}\n" : "", thermal, kind, t);
    return parse(text, c);
}

/* The recoil accelerations alone of the fluid block at t on backend k, by
 * particle id, 3 per particle (NULL where the backend is missing); the
 * mass of a particle into *mass, the count into *n. */
static double *recoil_by_id(int dim, double t, int k, int *n)
{
    amsph_case c;
    amsph_backend *b = testing_backend(k);
    if (!b || block_case(dim, "fluid", t, "{recoil_pressure: true}", &c)) {
        amsph_backend_destroy(b);
        return NULL;
    }
    amsph_sim s;
    amsph_host_particles h = {0};
    double *a = NULL;
    CHECK_OK(amsph_sim_create(&c, b, &s));
    const int words = 3 * s.particles.n * (int)(sizeof(amsph_real) / 4);
    CHECK_OK(AMSPH_LAUNCH(b, "fill_words", words, amsph_arg_buffer(s.particles.field[AMSPH_FIELD_ACCELERATION]),
                          amsph_arg_int(words), amsph_arg_uint(0)));
    CHECK_OK(amsph_evaporation_recoil(&s));
    CHECK_OK(amsph_particles_download(&s.particles, &h));
    a = calloc(3 * (size_t)h.n, sizeof *a);
    const amsph_real *acc = amsph_host_real(&h, AMSPH_FIELD_ACCELERATION);
    for (int i = 0; a && i < h.n; ++i) {
        const unsigned id = ((unsigned *)h.data[AMSPH_FIELD_ID])[i];
        for (int d = 0; d < 3 && id < (unsigned)h.n; ++d)
            a[3 * id + d] = acc[3 * i + d];
    }
    *n = h.n;
    amsph_host_free(&h);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
    return a;
}

/* Particle id i of the block's lattice: its height above the bottom face
 * in spacings (the scene fills boxes x fastest, the last axis slowest). */
static int row_of(int dim, int id)
{
    const int per_row = dim == 2 ? 20 : 400;
    return id / per_row;
}

/* Sums of m a over the upper and lower half (last axis) and of |m a| across
 * the faces and in the interior (rows farther than the support from both
 * faces), against -p_v A and +p_v A. */
static void check_recoil(int dim, double t, const double *a, int n, const char *backend)
{
    const double mass = DENSITY * pow(DX, dim), area = dim == 2 ? SIDE : SIDE * SIDE;
    const int rows = 10, reach = 3; /* support 2.4 dx */
    double upper = 0.0, lower = 0.0, across = 0.0, inside = 0.0;
    for (int i = 0; i < n; ++i) {
        const int row = row_of(dim, i);
        const double up = mass * a[3 * i + dim - 1];
        if (row >= rows / 2)
            upper += up;
        else
            lower += up;
        for (int d = 0; d < dim - 1; ++d)
            across += fabs(mass * a[3 * i + d]);
        if (row >= reach && row < rows - reach)
            inside += fabs(up);
    }
    const double exact = recoil_pressure(t) * area;
    fprintf(stderr, "recoil %dD at %g K (%s): top %.6g, bottom %.6g, p_v A = %.6g (%.1e, %.1e off); across %.2g, "
            "interior %.2g\n", dim, t, backend, upper, lower, exact, -upper / exact - 1.0, lower / exact - 1.0, across,
            inside);
    CHECK(fabs(-upper / exact - 1.0) < 1e-5 && fabs(lower / exact - 1.0) < 1e-5,
          "%dD, %g K, %s: recoil force on the top face %.6g, bottom %.6g, p_v A = %.6g", dim, t, backend, upper,
          lower, exact);
    CHECK(across < 2e-5 * exact && inside < 1e-6 * exact,
          "%dD, %g K, %s: recoil force along the faces %.3g, in the interior %.3g (p_v A = %.3g)", dim, t, backend,
          across, inside, exact);
}

static void test_recoil(void)
{
    static const double temperatures[] = {3000.0, 3500.0};
    for (int dim = 2; dim <= 3; ++dim)
        for (int j = 0; j < 2; ++j) {
            double *a[TESTING_BACKENDS];
            int n[TESTING_BACKENDS] = {0};
            for (int k = 0; k < TESTING_BACKENDS; ++k) {
                a[k] = recoil_by_id(dim, temperatures[j], k, &n[k]);
                if (a[k])
                    check_recoil(dim, temperatures[j], a[k], n[k], k ? "opencl" : "openmp");
            }
            if (a[0] && a[1]) {
                double worst = 0.0, scale = 0.0;
                for (int i = 0; i < 3 * n[0] && n[0] == n[1]; ++i) {
                    worst = fmax(worst, fabs(a[0][i] - a[1][i]));
                    scale = fmax(scale, fabs(a[0][i]));
                }
                fprintf(stderr, "recoil %dD at %g K: the backends differ by %.2e of the largest\n", dim,
                        temperatures[j], worst / scale);
                CHECK(n[0] == n[1] && worst <= 1e-5 * scale, "%dD recoil: backends differ by %.3g of the largest",
                      dim, worst / scale);
            }
            free(a[0]);
            free(a[1]);
        }
}

/* One explicit step of dt of the solid block at t on backend k: the
 * evaporative heat booked, against q_v(t) times the two faces and dt (the
 * ledger books the power at the step's start), and the ledger error. */
static void check_cooling(int dim, double t, int k)
{
    amsph_case c;
    amsph_backend *b = testing_backend(k);
    if (!b || block_case(dim, "solid", t, "{evaporative_cooling: true}", &c)) {
        amsph_backend_destroy(b);
        return;
    }
    amsph_sim s;
    const double dt = 1e-3, area = 2.0 * (dim == 2 ? SIDE : SIDE * SIDE);
    double ledger = INFINITY;
    CHECK_OK(amsph_sim_create(&c, b, &s));
    CHECK_OK(amsph_sim_step(&s, dt));
    CHECK_OK(amsph_thermal_ledger_error(&s, &ledger));
    const double exact = heat_flux(t) * area * dt;
    fprintf(stderr, "evaporative cooling %dD at %g K (%s): %.6g J, q_v A dt = %.6g J (%.1e off); ledger error %.2e\n",
            dim, t, k ? "opencl" : "openmp", s.ledger.evaporation, exact, s.ledger.evaporation / exact - 1.0, ledger);
    CHECK(fabs(s.ledger.evaporation / exact - 1.0) < 1e-5, "%dD, %g K: evaporation heat %.6g J, q_v A dt = %.6g J",
          dim, t, s.ledger.evaporation, exact);
    CHECK(ledger < 5e-5, "%dD, %g K: ledger error %.3g with evaporative cooling", dim, t, ledger);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
}

static void test_cooling(void)
{
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        check_cooling(2, 3000.0, k);
        check_cooling(2, 3500.0, k);
        check_cooling(3, 3500.0, k);
    }
}

/* Detached particles radiate and evaporate as balls of their volume dx^d:
 * a disc of perimeter 2 sqrt(pi) dx per unit depth in 2D, a sphere of area
 * 4 pi (3 / (4 pi))^(2/3) dx^2 in 3D. `count` one-spacing cubes 2 dx apart
 * along x (1: a lone particle, whose colour gradient is zero; 2: a pair
 * within each other's support, whose colour gradient is below the surface
 * cut-off), one explicit step of dt at 3500 K, emissivity 0.5 into 0 K: the
 * heat booked is count q_v A dt and count sigma eps T^4 A dt. Without the
 * balls neither would lose anything. */
static void check_detached(int dim, int count, int k)
{
    const char *lo = dim == 2 ? "[-0.1, -0.1]" : "[-0.1, -0.1, -0.1]";
    const char *hi = dim == 2 ? "[0.16, 0.12]" : "[0.16, 0.12, 0.12]";
    char text[2048], cubes[512] = "";
    for (int i = 0; i < count; ++i) {
        const double x = 2.0 * DX * i;
        const size_t used = strlen(cubes);
        snprintf(cubes + used, sizeof cubes - used,
                 dim == 2 ? "%s{shape: box, kind: solid, material: m, min: [%g, 0], max: [%g, 0.02], temperature: 3500}"
                          : "%s{shape: box, kind: solid, material: m, min: [%g, 0, 0], max: [%g, 0.02, 0.02], "
                            "temperature: 3500}",
                 i ? ", " : "", x, x + DX);
    }
    snprintf(text, sizeof text,
             "dimension: %d\ndomain: {min: %s, max: %s}\n"
             "dx: 0.02\nend_time: 1\noutput_interval: 1\n"
             "thermal: {evaporative_cooling: true, radiation: true, ambient_temperature: 0}\n"
             "materials: [" MATERIAL "]\n"
             "geometry: [%s]\n",
             dim, lo, hi, cubes);
    amsph_case c;
    amsph_backend *b = testing_backend(k);
    if (!b || parse(text, &c)) {
        amsph_backend_destroy(b);
        return;
    }
    c.materials[0].emissivity = 0.5;
    amsph_sim s;
    const double dt = 1e-3, t = 3500.0;
    const double area = count * (dim == 2 ? 2.0 * sqrt(PI) * DX : 4.0 * PI * pow(3.0 / (4.0 * PI), 2.0 / 3.0) * DX * DX);
    CHECK_OK(amsph_sim_create(&c, b, &s));
    CHECK_OK(amsph_sim_step(&s, dt));
    const double evaporation = heat_flux(t) * area * dt, radiation = STEFAN_BOLTZMANN * 0.5 * pow(t, 4) * area * dt;
    fprintf(stderr, "%d detached %dD at %g K (%s, %d particles): evaporation %.6g J, q_v A dt = %.6g J (%.1e off); "
            "radiation %.6g J, sigma eps T^4 A dt = %.6g J (%.1e off)\n", count, dim, t, k ? "opencl" : "openmp",
            s.particles.n, s.ledger.evaporation, evaporation, s.ledger.evaporation / evaporation - 1.0,
            s.ledger.radiation, radiation, s.ledger.radiation / radiation - 1.0);
    CHECK(s.particles.n == count, "%dD: the detached scene has %d particles, not %d", dim, s.particles.n, count);
    CHECK(fabs(s.ledger.evaporation / evaporation - 1.0) < 1e-5 && fabs(s.ledger.radiation / radiation - 1.0) < 1e-5,
          "%dD, %d detached: evaporation %.6g J (q_v A dt = %.6g), radiation %.6g J (sigma eps T^4 A dt = %.6g)", dim,
          count, s.ledger.evaporation, evaporation, s.ledger.radiation, radiation);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
}

static void test_detached(void)
{
    for (int k = 0; k < TESTING_BACKENDS; ++k)
        for (int dim = 2; dim <= 3; ++dim)
            for (int count = 1; count <= 2; ++count)
                check_detached(dim, count, k);
}

/* A solid block of 20 x 15 particles at 1000 K under 20 x 5 at 3500 K,
 * cut-off 3000 K, conduction negligible: one step removes exactly the 100
 * hot ones, counts them and books their enthalpy 100 m c 3500; what is
 * left is the cold block, and the ledger closes. */
static void test_removal(void)
{
    const char *text = "dimension: 2\n"
                       "domain: {min: [-0.1, -0.1], max: [0.5, 0.5]}\n"
                       "dx: 0.02\nend_time: 1\noutput_interval: 1\n"
                       "thermal: {evaporation_temperature: 3000}\n"
                       "materials: [" MATERIAL "]\n"
                       "geometry:\n"
                       "  - {shape: box, kind: solid, material: m, min: [0, 0], max: [0.4, 0.3], temperature: 1000}\n"
                       "  - {shape: box, kind: solid, material: m, min: [0, 0.3], max: [0.4, 0.4], temperature: 3500}\n";
    amsph_case c;
    if (parse(text, &c))
        return;
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_backend *b = testing_backend(k);
        if (!b)
            continue;
        amsph_sim s;
        amsph_host_particles h = {0};
        double ledger = INFINITY;
        CHECK_OK(amsph_sim_create(&c, b, &s));
        CHECK_OK(amsph_sim_step(&s, 1e-3));
        CHECK_OK(amsph_thermal_ledger_error(&s, &ledger));
        CHECK_OK(amsph_particles_download(&s.particles, &h));
        double hottest = 0.0;
        for (int i = 0; i < h.n; ++i)
            hottest = fmax(hottest, amsph_host_real(&h, AMSPH_FIELD_TEMPERATURE)[i]);
        const double exact = 100 * DENSITY * DX * DX * HEAT * 3500.0;
        fprintf(stderr, "removal (%s): %d left (hottest %.6g K), %lld evaporated with %.6g J/m (100 m c T = %.6g); "
                "%lld left the domain; ledger error %.2e\n",
                k ? "opencl" : "openmp", h.n, hottest, s.evaporated_particles, s.ledger.evaporated, exact,
                s.particles.removed, ledger);
        CHECK(h.n == 300 && s.evaporated_particles == 100 && s.particles.removed == 0 && hottest < 1001.0,
              "%d particles left (hottest %g K), %lld evaporated, %lld left the domain", h.n, hottest,
              s.evaporated_particles, s.particles.removed);
        CHECK(fabs(s.ledger.evaporated / exact - 1.0) < 1e-5 && ledger < 1e-5,
              "evaporated enthalpy %.7g J/m, 100 m c T = %.7g; ledger error %.3g", s.ledger.evaporated, exact, ledger);
        amsph_host_free(&h);
        amsph_sim_free(&s);
        amsph_backend_destroy(b);
    }
}

/* Particles that leave the domain take their enthalpy out of the ledger
 * (departed_energy): a block at 1000 K drifting at 1 m/s (no fluid module:
 * ballistic) through the closed +x face loses ten columns of ten particles
 * in 15 steps of one spacing; the departed enthalpy is their m h and the
 * ledger closes. */
static void test_departure(void)
{
    const char *text = "dimension: 2\n"
                       "domain: {min: [0, 0], max: [1, 0.4]}\n"
                       "dx: 0.02\nend_time: 1\noutput_interval: 1\n"
                       "thermal: {}\n"
                       "materials: [" MATERIAL "]\n"
                       "geometry:\n"
                       "  - {shape: box, kind: fluid, material: m, min: [0.5, 0.1], max: [0.9, 0.3], velocity: [1, 0],\n"
                       "     temperature: 1000}\n";
    amsph_case c;
    if (parse(text, &c))
        return;
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_backend *b = testing_backend(k);
        if (!b)
            continue;
        amsph_sim s;
        double ledger = INFINITY;
        CHECK_OK(amsph_sim_create(&c, b, &s));
        for (int step = 0; step < 15; ++step)
            CHECK_OK(amsph_sim_step(&s, DX));
        CHECK_OK(amsph_thermal_ledger_error(&s, &ledger));
        const double exact = (double)s.particles.removed * DENSITY * DX * DX * HEAT * 1000.0;
        fprintf(stderr, "departure (%s): %lld left the domain with %.6g J/m (m h each: %.6g); ledger error %.2e\n",
                k ? "opencl" : "openmp", s.particles.removed, s.ledger.departed, exact, ledger);
        CHECK(s.particles.removed == 100, "%lld particles left the domain, not 100", s.particles.removed);
        CHECK(fabs(s.ledger.departed / exact - 1.0) < 1e-5 && ledger < 1e-5,
              "departed enthalpy %.7g J/m, their m h %.7g; ledger error %.3g", s.ledger.departed, exact, ledger);
        amsph_sim_free(&s);
        amsph_backend_destroy(b);
    }
}

/* Runs the case (its end time `end` when > 0) and returns the peak
 * temperature; the sim is left for the caller to read and free. */
static double run(amsph_case *c, double end, amsph_backend *b, amsph_sim *s)
{
    double peak = NAN;
    CHECK_OK(amsph_sim_create(c, b, s));
    CHECK_OK(amsph_sim_advance(s, end > 0 ? end : c->end_time, NULL, NULL));
    CHECK_OK(amsph_reduce_max(b, s->particles.field[AMSPH_FIELD_TEMPERATURE], s->particles.n, &peak));
    return peak;
}

/* The laser-heated slab that boils (cases/validation/evaporating_slab_2d.yaml):
 * the ledger closes with the evaporation term (measured 1.1e-6) while the
 * vapour carries off more than 5% of the absorbed energy, and the peak
 * temperature stays below the one without evaporative cooling. */
static void test_boiling_slab(void)
{
    amsph_case c;
    amsph_backend *b = testing_backend(0);
    if (testing_load_case("evaporating_slab_2d.yaml", &c))
        return;
    amsph_sim s;
    double ledger = INFINITY;
    const double peak = run(&c, 0, b, &s);
    CHECK_OK(amsph_thermal_ledger_error(&s, &ledger));
    const double share = s.ledger.evaporation / s.ledger.laser;
    amsph_sim_free(&s);
    c.thermal.evaporative_cooling = 0;
    const double uncooled = run(&c, 0, b, &s);
    amsph_sim_free(&s);
    fprintf(stderr, "boiling slab: ledger error %.2e, evaporation %.3f of the laser energy, peak %.5g K (%.5g K "
            "without evaporative cooling)\n", ledger, share, peak, uncooled);
    CHECK(ledger < 1e-4 && share > 0.05, "boiling slab: ledger error %.3g, evaporation %.3g of the laser energy",
          ledger, share);
    CHECK(peak > T_V && peak < uncooled - 100.0, "boiling slab: peak %.5g K, without evaporative cooling %.5g K", peak,
          uncooled);
    amsph_backend_destroy(b);
}

/* Mean height of the fluid within x0 +- r of the beam axis, m. */
static double pool_height(amsph_sim *s, double x0, double r)
{
    amsph_host_particles h = {0};
    double sum = 0.0;
    int count = 0;
    CHECK_OK(amsph_particles_download(&s->particles, &h));
    const amsph_real *x = amsph_host_real(&h, AMSPH_FIELD_POSITION);
    const int *kind = h.data[AMSPH_FIELD_KIND];
    for (int i = 0; i < h.n; ++i)
        if (kind[i] == AMSPH_KIND_FLUID && fabs(x[3 * i] - x0) < r) {
            sum += x[3 * i + 1];
            ++count;
        }
    amsph_host_free(&h);
    return count ? sum / count : NAN;
}

/* The recoil pool (cases/am/recoil_pool_2d.yaml) to 40 us: with the recoil
 * pressure the melt under the beam sits lower than without, and the
 * ledger closes. */
static void test_recoil_pool(void)
{
    amsph_case c;
    if (testing_load_case("../am/recoil_pool_2d.yaml", &c))
        return;
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    double ledger = INFINITY;
    run(&c, 4e-5, b, &s);
    CHECK_OK(amsph_thermal_ledger_error(&s, &ledger));
    const double pushed = pool_height(&s, c.laser.start[0], c.laser.radius);
    amsph_sim_free(&s);
    c.thermal.recoil_pressure = 0;
    run(&c, 4e-5, b, &s);
    const double free_pool = pool_height(&s, c.laser.start[0], c.laser.radius);
    amsph_sim_free(&s);
    fprintf(stderr, "recoil pool at 40 us: mean melt height under the beam %.4g um with recoil, %.4g um without; "
            "ledger error %.2e\n", 1e6 * pushed, 1e6 * free_pool, ledger);
    CHECK(pushed < free_pool && ledger < 1e-4, "recoil pool: melt height %.4g um with recoil, %.4g um without; "
          "ledger error %.3g", 1e6 * pushed, 1e6 * free_pool, ledger);
    amsph_backend_destroy(b);
}

int main(void)
{
    test_recoil();
    test_cooling();
    test_detached();
    test_removal();
    test_departure();
    test_boiling_slab();
    test_recoil_pool();
    return testing_finish();
}
