/* The isothermally incompressible fluid (Russell 2018 Sec. 3.4 and 4.3.1;
 * VALIDATION.md I1, I3, I4): the reference density follows the temperature,
 * rho0(T), and the particle volumes must follow m / rho0(T).
 *
 *   - rho0(T) tables: the 304 steel law of PHYSICS.md, continuous across the
 *     mushy interval, on the host and in the kernels of both backends; rho0
 *     following the thermal module's temperature;
 *   - I1, expansion cycle: a droplet whose rho0 swings +-5% ten times; the
 *     Voronoi cell areas of its interior (r < R/2) and of a band below the
 *     surface (0.8 R < r < 0.9 R) against m / rho0(T), in 2D and 3D;
 *   - I3, expanding column: the lower of two stacked fluids loses 10% of
 *     rho0 under gravity; the Voronoi volumes of both against m / rho0(T);
 *   - I4, sinking fluid: a heavy fluid sinks into a light one; the
 *     particle-scale pressure noise with the delta-SPH of rho - rho0 and
 *     without it;
 *   - the smoothing length that follows the particle volume (Russell Eq.
 *     3.54, fluid.smoothing_length: volume): a droplet whose rho0 falls 10%
 *     ends with h = h0 (V / V0)^(1/2), and the run stops naming a particle
 *     whose h outgrows the grid; pair forces with unequal h conserve
 *     momentum; both backends agree.
 * The ctest runs the shipped cases at a coarser spacing and a shorter end
 * time on the OpenMP backend (tests/test_backends.c compares the backends).
 *
 * `test_isothermal sweep CASE DX...` (CASE: cycle, cycle_volume_h,
 * cycle_3d, column, sinking; cycle_volume_h is cycle with
 * fluid.smoothing_length: volume) runs a whole shipped case at each spacing and prints a Markdown
 * row per run for BENCHMARKS.md: measurements, no assertions. */
#include <math.h>
#include <stdio.h>
#include <time.h>

#include "case.h"
#include "fluid.h"
#include "material.h"
#include "sim.h"
#include "testing.h"
#include "testing_run.h"
#include "voronoi.h"

#define VORONOI_REACH 3.0 /* spacings: closes every cell of a fluid lattice */

static int is_fluid(const amsph_host_particles *h, int i)
{
    return ((const int *)h->data[AMSPH_FIELD_KIND])[i] == AMSPH_KIND_FLUID;
}

static int material_of(const amsph_host_particles *h, int i)
{
    return ((const int *)h->data[AMSPH_FIELD_MATERIAL])[i];
}

static const amsph_real *position_of(const amsph_host_particles *h, int i)
{
    return amsph_host_real(h, AMSPH_FIELD_POSITION) + 3 * i;
}

/* Volume m / rho0(T) the isothermally incompressible fluid should fill. */
static double expected_volume(const amsph_host_particles *h, int i)
{
    return amsph_host_real(h, AMSPH_FIELD_MASS)[i] / amsph_host_real(h, AMSPH_FIELD_REFERENCE_DENSITY)[i];
}

/* ---- the measured quantities of each case, at one output time ----------- */

/* The errors a case measures, each the largest magnitude over the output
 * times. */
enum { MAX_ERRORS = 2 };
typedef struct {
    double worst[MAX_ERRORS];
    int open;     /* selected particles with open Voronoi cells, summed */
    int measured; /* output times measured so far */
} errors;

static void keep(errors *e, int k, double value)
{
    e->worst[k] = fmax(e->worst[k], fabs(value));
}

typedef int (*measure)(const amsph_case *c, const amsph_host_particles *h, errors *e);

/* Which region (0 or 1) particle i belongs to, or -1. */
typedef int (*region_of)(const amsph_case *c, const amsph_host_particles *h, int i, const double *shape);

/* Voronoi volume of each region over its expected volume, minus 1, into
 * e->worst[0] and [1]; particles with open cells are left out and counted
 * in e->open. `shape` holds what region_of needs. */
static int voronoi_errors(const amsph_case *c, const amsph_host_particles *h, region_of region,
                          const double *shape, errors *e)
{
    double *volume = malloc((size_t)h->n * sizeof *volume);
    if (!volume || voronoi_volumes(amsph_host_real(h, AMSPH_FIELD_POSITION), h->n, c->dim,
                                   VORONOI_REACH * c->dx, volume)) {
        free(volume);
        return amsph_fail("out of memory for the Voronoi cells");
    }
    double measured[MAX_ERRORS] = {0.0, 0.0}, expected[MAX_ERRORS] = {0.0, 0.0};
    for (int i = 0; i < h->n; ++i) {
        const int k = region(c, h, i, shape);
        if (k < 0)
            continue;
        if (volume[i] < 0.0) {
            ++e->open;
            continue;
        }
        measured[k] += volume[i];
        expected[k] += expected_volume(h, i);
    }
    for (int k = 0; k < MAX_ERRORS; ++k)
        if (expected[k] > 0.0)
            keep(e, k, measured[k] / expected[k] - 1.0);
    free(volume);
    return 0;
}

/* Centre of the fluid and the radius of the disc (2D) or ball (3D) of the
 * expected volume: shape[0..2], shape[3]. */
static void droplet_shape(const amsph_host_particles *h, int dim, double shape[4])
{
    double volume = 0.0, count = 0.0;
    shape[0] = shape[1] = shape[2] = 0.0;
    for (int i = 0; i < h->n; ++i) {
        if (!is_fluid(h, i))
            continue;
        volume += expected_volume(h, i);
        for (int d = 0; d < 3; ++d)
            shape[d] += position_of(h, i)[d];
        ++count;
    }
    for (int d = 0; d < 3; ++d)
        shape[d] /= count;
    shape[3] = dim == 2 ? sqrt(volume / PI) : cbrt(3.0 * volume / (4.0 * PI));
}

/* I1: the interior r < R/2 (0) and the band 0.8 R < r < 0.9 R (1) (Russell
 * 2018 Fig. 4.4), R the radius of the disc (ball) of the expected volume. */
static int droplet_region(const amsph_case *c, const amsph_host_particles *h, int i, const double *shape)
{
    (void)c;
    double r2 = 0.0;
    for (int d = 0; d < 3; ++d)
        r2 += ((double)position_of(h, i)[d] - shape[d]) * ((double)position_of(h, i)[d] - shape[d]);
    const double r = sqrt(r2) / shape[3];
    return r < 0.5 ? 0 : r > 0.8 && r < 0.9 ? 1 : -1;
}

static int measure_cycle(const amsph_case *c, const amsph_host_particles *h, errors *e)
{
    double shape[4];
    droplet_shape(h, c->dim, shape);
    return voronoi_errors(c, h, droplet_region, shape, e);
}

/* I3: the lower fluid (material 0, region 0) whole, bounded by walls and
 * the upper fluid; the upper fluid (material 1, region 1) more than 3
 * spacings below its top (shape[0]). */
static int column_region(const amsph_case *c, const amsph_host_particles *h, int i, const double *shape)
{
    if (!is_fluid(h, i))
        return -1;
    if (material_of(h, i) == 0)
        return 0;
    return position_of(h, i)[1] < shape[0] - 3.0 * c->dx ? 1 : -1;
}

static int measure_column(const amsph_case *c, const amsph_host_particles *h, errors *e)
{
    double top = -INFINITY;
    for (int i = 0; i < h->n; ++i)
        if (is_fluid(h, i) && material_of(h, i) == 1)
            top = fmax(top, position_of(h, i)[1]);
    return voronoi_errors(c, h, column_region, &top, e);
}

/* I4: the particle-scale pressure noise, the RMS over the fluid particles
 * inside one fluid of p_a - <p>_a, <p>_a the mean pressure of the particles
 * within 1.5 spacings (on a lattice the particle and its 8 neighbours),
 * relative to rho g H of the light fluid (material 0, H = 1 m, g = 9.81
 * m/s^2). A smooth pressure (hydrostatic: linear) leaves nothing, a
 * checkerboard its amplitude. Inside one fluid: the kernel sum Gamma_a
 * above 0.99 (away from the free surface) and every particle within 1.5
 * spacings, at least 5, fluid of the particle's material (away from the
 * walls and from the interface between the fluids, where the pressure
 * gradient jumps). Not at t = 0: the blocks start in hydrostatic balance
 * column by column, which puts a jump in the light fluid's pressure beside
 * the heavy block's column until it adjusts. */
static int measure_sinking(const amsph_case *c, const amsph_host_particles *h, errors *e)
{
    if (e->measured == 0)
        return 0;
    const double reach = 1.5 * c->dx;
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION), *p = amsph_host_real(h, AMSPH_FIELD_PRESSURE);
    const amsph_real *gamma = amsph_host_real(h, AMSPH_FIELD_SHEPARD);
    voronoi_buckets b = {0};
    int status = voronoi_buckets_build(&b, x, h->n, reach) ? amsph_fail("out of memory") : 0;
    double sum = 0.0, count = 0.0;
    for (int a = 0; !status && a < h->n; ++a) {
        if (!is_fluid(h, a) || gamma[a] < 0.99)
            continue;
        const double at[3] = {x[3 * a], x[3 * a + 1], x[3 * a + 2]};
        int near[VORONOI_MAX_NEAR], mixed = 0;
        const int n_near = voronoi_near(&b, x, at, reach, near);
        double mean = 0.0;
        for (int k = 0; k < n_near; ++k) {
            mixed |= !is_fluid(h, near[k]) || material_of(h, near[k]) != material_of(h, a);
            mean += (double)p[near[k]] / n_near;
        }
        if (mixed || n_near < 5)
            continue;
        sum += (p[a] - mean) * (p[a] - mean);
        count += 1.0;
    }
    voronoi_buckets_free(&b);
    const double scale = amsph_material_density(&c->materials[0], 0.0) * 9.81 * 1.0;
    if (!status && count > 0.0)
        keep(e, 0, sqrt(sum / count) / scale);
    return status;
}

/* ---- runs -------------------------------------------------------------- */

typedef struct {
    int particles;
    long long steps;
    double wall;    /* s */
    double reached; /* simulated time, s */
    int stopped;    /* a guard stopped the run */
} run_record;

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Runs the case on the OpenMP backend and measures at every output time,
 * t = 0 included. */
static int run_measured(const amsph_case *c, measure m, errors *e, run_record *record)
{
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    const double start = seconds();
    int status = amsph_sim_create(c, b, &s);
    for (int k = 0; !status && k * c->output_interval <= c->end_time * (1 + 1e-9); ++k) {
        status = amsph_sim_advance(&s, k * c->output_interval, NULL, NULL);
        amsph_host_particles h = {0};
        if (!status)
            status = amsph_particles_download(&s.particles, &h);
        if (!status)
            status = m(c, &h, e);
        ++e->measured;
        amsph_host_free(&h);
    }
    record->particles = s.particles.n;
    record->steps = s.step;
    record->wall = seconds() - start;
    record->reached = s.time;
    record->stopped = s.guard_failed;
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
    return status;
}

/* The shipped case at spacing dx (0: its own) and end time (0: its own). */
static int load_case(const char *file, double dx, double end_time, amsph_case *c)
{
    AMSPH_CHECK(testing_load_case(file, c));
    if (dx > 0.0)
        c->dx = dx;
    if (end_time > 0.0)
        c->end_time = end_time;
    return 0;
}

/* ---- tests ------------------------------------------------------------- */

/* The 304 steel density law of PHYSICS.md (Russell 2018 Table 4.1) as a
 * table: each phase's line at its own temperatures, and across the mushy
 * interval [1673, 1773] K the straight line from the solid's value at the
 * solidus to the liquid's at the liquidus. The law as written jumps there
 * (the mushy line 7443 - 6.03 (T - 1673) starts 112 kg/m^3 above the solid
 * at 1673 K and meets the liquid at 1773 K); a jump in rho0 would be a jump
 * of c0^2 rho0 / 70 in pressure at one temperature. Checked: the table
 * holds the solid and liquid laws at their temperatures, is continuous,
 * and the kernels of both backends evaluate it as the host does. */
static const char *steel_case =
    "dimension: 2\n"
    "domain: {min: [0, 0], max: [1, 0.1]}\n"
    "dx: 0.01\n"
    "end_time: 1\n"
    "output_interval: 1\n"
    "fluid: {}\n"
    "materials:\n"
    "  - name: steel_304\n"
    "    density: [[298, 8020], [1673, 7331.125], [1773, 6840], [3000, 5981.1]]\n"
    "    sound_speed: 10\n"
    "geometry:\n"
    "  - {shape: box, kind: fluid, material: steel_304, min: [0, 0], max: [1, 0.1], temperature: 300}\n";

static double steel_solid(double t) { return 8020.0 - 0.501 * (t - 298.0); }
static double steel_liquid(double t) { return 6840.0 - 0.70 * (t - 1773.0); }

static void test_steel_density(void)
{
    amsph_case c;
    char err[512];
    CHECK(amsph_case_parse(steel_case, strlen(steel_case), "steel.yaml", &c, err, sizeof err) == 0, "%s", err);
    const amsph_material *m = &c.materials[0];
    double worst = 0.0;
    for (double t = 298.0; t <= 1673.0; t += 25.0)
        worst = fmax(worst, fabs(amsph_material_density(m, t) - steel_solid(t)));
    for (double t = 1773.0; t <= 3000.0; t += 25.0)
        worst = fmax(worst, fabs(amsph_material_density(m, t) - steel_liquid(t)));
    CHECK(worst < 1e-9, "the table departs from the solid or liquid law by %g kg/m^3", worst);
    const double bounds[2] = {1673.0, 1773.0};
    for (int k = 0; k < 2; ++k) {
        const double jump = amsph_material_density(m, bounds[k] + 1e-6) - amsph_material_density(m, bounds[k] - 1e-6);
        CHECK(fabs(jump) < 1e-3, "rho0 jumps by %g kg/m^3 at %g K", jump, bounds[k]);
    }
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_backend *b = testing_backend(k);
        if (!b)
            continue;
        amsph_sim s;
        amsph_host_particles h;
        CHECK_OK(amsph_sim_create(&c, b, &s));
        CHECK_OK(amsph_particles_download(&s.particles, &h));
        for (int i = 0; i < h.n; ++i) /* 200 K to 3200 K across the particles */
            amsph_host_real(&h, AMSPH_FIELD_TEMPERATURE)[i] = (amsph_real)(200.0 + 3000.0 * i / (h.n - 1));
        amsph_particles_free(&s.particles);
        CHECK_OK(amsph_particles_upload(b, &h, &s.particles));
        CHECK_OK(amsph_fluid_reference_density(&s));
        amsph_host_free(&h);
        CHECK_OK(amsph_particles_download(&s.particles, &h));
        double differs = 0.0;
        for (int i = 0; i < h.n; ++i) {
            const double t = amsph_host_real(&h, AMSPH_FIELD_TEMPERATURE)[i];
            differs = fmax(differs, fabs(amsph_host_real(&h, AMSPH_FIELD_REFERENCE_DENSITY)[i] -
                                         amsph_material_density(m, t)));
        }
        CHECK(differs < (AMSPH_DOUBLE ? 1e-9 : 2e-3), "backend %d: kernel rho0(T) differs from the host's by %g",
              k, differs);
        amsph_host_free(&h);
        amsph_sim_free(&s);
        amsph_backend_destroy(b);
    }
}

/* With the thermal module, rho0 follows the temperature the enthalpy step
 * gives: a fluid column between a hot and a cold wall, after some steps
 * of conduction, has every particle's rho0 at the table's value for its
 * temperature, and the temperatures spread. */
static const char *heated_case =
    "dimension: 2\n"
    "domain: {min: [-0.2, -0.2], max: [1.2, 0.6]}\n"
    "dx: 0.05\n"
    "end_time: 1\n"
    "output_interval: 1\n"
    "thermal: {}\n"
    "fluid: {}\n"
    "materials:\n"
    "  - {name: liquid, density: [[300, 1000], [400, 900]], sound_speed: 20, specific_heat: 1000, conductivity: 500}\n"
    "  - {name: hot, density: 1000, sound_speed: 20, specific_heat: 1000, conductivity: 500}\n"
    "geometry:\n"
    "  - {shape: box, kind: fluid, material: liquid, min: [0, 0], max: [1, 0.4], temperature: 300}\n"
    "  - {shape: box, kind: wall, material: hot, min: [0, 0], max: [1, 0.4], layers: 3, open: [+y], temperature: 400}\n";

static void test_thermal_drives_rho0(void)
{
    amsph_case c;
    char err[512];
    CHECK(amsph_case_parse(heated_case, strlen(heated_case), "heated.yaml", &c, err, sizeof err) == 0, "%s", err);
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    amsph_host_particles h;
    CHECK_OK(amsph_sim_create(&c, b, &s));
    for (int k = 0; k < 50; ++k) {
        double dt;
        CHECK_OK(amsph_sim_stable_dt(&s, &dt));
        CHECK_OK(amsph_sim_step(&s, dt));
    }
    CHECK_OK(amsph_particles_download(&s.particles, &h));
    double differs = 0.0, coolest = INFINITY, hottest = 0.0;
    for (int i = 0; i < h.n; ++i) {
        if (!is_fluid(&h, i))
            continue;
        const double t = amsph_host_real(&h, AMSPH_FIELD_TEMPERATURE)[i];
        coolest = fmin(coolest, t);
        hottest = fmax(hottest, t);
        differs = fmax(differs, fabs(amsph_host_real(&h, AMSPH_FIELD_REFERENCE_DENSITY)[i] -
                                     amsph_material_density(&c.materials[0], t)));
    }
    CHECK(hottest - coolest > 1.0, "the walls did not heat the fluid (T from %g to %g K)", coolest, hottest);
    CHECK(differs < (AMSPH_DOUBLE ? 1e-9 : 2e-3), "rho0 lags the temperature by up to %g kg/m^3", differs);
    amsph_host_free(&h);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
}

/* Spray: fluid particles with fewer than d others within their support
 * (kernels/integrate.cl density_at_step_end), cooled by the prescribed
 * history by 50 K over a quarter period while rho0(T) rises from 1000 to
 * 1050 kg/m^3.
 *  - A lone particle, a pair and (3D) a row of three at rest, 1 dx apart in
 *    a support of 2.4 dx: each ends at rho0(T), so at p = p_b = 0, and the
 *    pair and the row keep their spacing. With continuity alone a particle
 *    keeps the 1000 it started with, and a pair's 2e4 Pa of tension pulls it
 *    onto itself, as the spray pairs torn off the PBF melt were.
 *  - A pair 2 dx apart closing at 2 m/s (0.1 c0): continuity compresses it
 *    above rho0 and its pressure turns it round; it ends moving apart, each
 *    alone at rho0(T). With rho0 taken whatever the pair does, nothing but
 *    the weak artificial viscosity resists the closing, and the two pass
 *    through each other (the 150 W track's spray pair met at 0.3 dx).
 * And a lone particle heated by 50 K, rho0(T) falling to 950: it takes
 * rho0(T) too, where a floor at rho0 (the pair's rule) would leave it at the
 * 1000 it started with, to meet the melt again compressed. */
#define SPRAY_GEOMETRY_2D \
    "geometry:\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [-0.6, 0], max: [-0.5, 0.1]}\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [0.5, 0], max: [0.7, 0.1]}\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [-0.15, -0.5], max: [-0.05, -0.4], velocity: [1, 0]}\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [0.05, -0.5], max: [0.15, -0.4], velocity: [-1, 0]}\n"

#define SPRAY_GEOMETRY_3D \
    "geometry:\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [-0.6, 0, 0], max: [-0.5, 0.1, 0.1]}\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [0.5, 0, 0], max: [0.7, 0.1, 0.1]}\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [0, 0.5, 0], max: [0.1, 0.8, 0.1]}\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [-0.15, -0.5, 0], max: [-0.05, -0.4, 0.1], velocity: [1, 0, 0]}\n" \
    "  - {shape: box, kind: fluid, material: liquid, min: [0.05, -0.5, 0], max: [0.15, -0.4, 0.1], velocity: [-1, 0, 0]}\n"

#define SPRAY_SETTINGS(amplitude) \
    "dx: 0.1\n" \
    "end_time: 0.25\n" \
    "output_interval: 0.25\n" \
    "temperature_history: {reference: 300, amplitude: " amplitude ", frequency: 1}\n" \
    "fluid: {viscosity: artificial, artificial_alpha: 0.1}\n" \
    "materials:\n" \
    "  - {name: liquid, density: [[250, 1050], [350, 950]], sound_speed: 20}\n"

static const char *spray_case_2d =
    "dimension: 2\ndomain: {min: [-1, -1], max: [1, 1]}\n" SPRAY_SETTINGS("-50") SPRAY_GEOMETRY_2D;
static const char *spray_case_3d =
    "dimension: 3\ndomain: {min: [-1, -1, -1], max: [1, 1, 1]}\n" SPRAY_SETTINGS("-50") SPRAY_GEOMETRY_3D;
static const char *lone_heated_case =
    "dimension: 2\ndomain: {min: [-1, -1], max: [1, 1]}\n" SPRAY_SETTINGS("50")
    "geometry:\n"
    "  - {shape: box, kind: fluid, material: liquid, min: [-0.6, 0], max: [-0.5, 0.1]}\n";

/* Does particle i of h have another particle dx away, to 1e-3 dx? */
static int has_partner(const amsph_host_particles *h, int i, double dx)
{
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
    for (int j = 0; j < h->n; ++j) {
        double r2 = 0.0;
        for (int d = 0; d < 3; ++d)
            r2 += (x[3 * i + d] - x[3 * j + d]) * (x[3 * i + d] - x[3 * j + d]);
        if (j != i && fabs(sqrt(r2) - dx) < 1e-3 * dx)
            return 1;
    }
    return 0;
}

/* The closing pair (the last two particles created, y < -0.3): the one
 * that started on the left must still be on the left, moving left. */
static void check_closing_pair(const amsph_host_particles *h, int dim)
{
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION), *v = amsph_host_real(h, AMSPH_FIELD_VELOCITY);
    const unsigned *id = (const unsigned *)h->data[AMSPH_FIELD_ID];
    int left = -1, right = -1;
    for (int i = 0; i < h->n; ++i)
        if (x[3 * i + 1] < -0.3) {
            if (left < 0 || id[i] < id[left]) {
                right = left;
                left = i;
            } else {
                right = i;
            }
        }
    CHECK(left >= 0 && right >= 0, "%dD: the closing pair is not in the domain", dim);
    if (left < 0 || right < 0)
        return;
    CHECK(x[3 * left] < x[3 * right], "%dD: the closing pair passed through each other (x %g and %g)", dim,
          x[3 * left], x[3 * right]);
    CHECK(v[3 * left] < -0.1 && v[3 * right] > 0.1, "%dD: the closing pair did not turn round (u %g and %g m/s)", dim,
          v[3 * left], v[3 * right]);
}

/* Runs `text` on backend k into h, checks its particle count and that every
 * particle was moved 50 K by the history (to 250 or 350 K, `end_temperature`)
 * and ends at rho0(T). Returns 0, or 1 where the backend is not there. */
static int run_spray(const char *text, int k, int particles, double end_temperature, amsph_case *c,
                     amsph_host_particles *h)
{
    char err[512];
    CHECK(amsph_case_parse(text, strlen(text), "spray.yaml", c, err, sizeof err) == 0, "%s", err);
    if (testing_run_case(c, k, c->end_time, h))
        return 1;
    CHECK(h->n == particles, "%dD: %d particles, not %d", c->dim, h->n, particles);
    for (int i = 0; i < h->n; ++i) {
        const double t = amsph_host_real(h, AMSPH_FIELD_TEMPERATURE)[i];
        const double rho0 = amsph_material_density(&c->materials[0], t);
        const double rho = amsph_host_real(h, AMSPH_FIELD_DENSITY)[i];
        CHECK(fabs(t - end_temperature) < 1.0, "%dD particle %d at %g K, not %g", c->dim, i, t, end_temperature);
        CHECK(fabs(rho - rho0) < 1e-5 * rho0, "%dD particle %d: rho %g against rho0(T) %g", c->dim, i, rho, rho0);
    }
    return 0;
}

static void check_spray(const char *text, int particles)
{
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_case c;
        amsph_host_particles h;
        if (run_spray(text, k, particles, 250.0, &c, &h))
            continue;
        /* every particle at rest but the lone one still has a partner 1 dx
         * away: no tension drew them in */
        int paired = 0;
        for (int i = 0; i < h.n; ++i)
            paired += has_partner(&h, i, c.dx);
        CHECK(paired == particles - 3, "%dD: %d particles keep a partner 1 dx away, not %d", c.dim, paired,
              particles - 3);
        check_closing_pair(&h, c.dim);
        amsph_host_free(&h);
    }
}

static void test_spray(void)
{
    check_spray(spray_case_2d, 5);
    check_spray(spray_case_3d, 8);
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_case c;
        amsph_host_particles h;
        if (!run_spray(lone_heated_case, k, 1, 350.0, &c, &h))
            amsph_host_free(&h);
    }
}

/* ---- the cases ---------------------------------------------------------- */

typedef struct {
    const char *name;            /* as the command line gives it */
    const char *file;            /* in cases/validation/ */
    measure measure;
    const char *what[MAX_ERRORS]; /* the errors, for the sweep's table; NULL: none */
    int smoothing_length;        /* fluid.smoothing_length; -1: the file's */
} case_spec;

static const case_spec cases[] = {
    {"cycle", "expansion_cycle_2d.yaml", measure_cycle, {"interior", "0.8-0.9 R"}, -1},
    {"cycle_3d", "expansion_cycle_3d.yaml", measure_cycle, {"interior", "0.8-0.9 R"}, -1},
    {"column", "expansion_column_2d.yaml", measure_column, {"lower fluid", "upper fluid"}, -1},
    {"sinking", "sinking_2d.yaml", measure_sinking, {"pressure noise", NULL}, -1},
    {"cycle_volume_h", "expansion_cycle_2d.yaml", measure_cycle, {"interior", "0.8-0.9 R"}, SMOOTHING_VOLUME},
};
#define N_CASES (int)(sizeof cases / sizeof cases[0])

/* Runs case k at spacing dx and end time (0: the file's), with the delta-SPH
 * form `diffusion` (< 0: the file's). */
static int run_case(int k, double dx, double end_time, int diffusion, errors *e, run_record *record)
{
    amsph_case c;
    AMSPH_CHECK(load_case(cases[k].file, dx, end_time, &c));
    if (diffusion >= 0)
        c.fluid.density_diffusion = diffusion;
    if (cases[k].smoothing_length >= 0)
        c.fluid.smoothing_length = cases[k].smoothing_length;
    memset(e, 0, sizeof *e);
    return run_measured(&c, cases[k].measure, e, record);
}

/* I1, 2D, at the thesis's spacing for two cycles: interior and band within
 * the goal (half the thesis's 0.4% and 0.8%), every cell closed. With the
 * plain continuity sum the band drifted from cycle to cycle (0.15% after
 * one, 0.24% after two, 0.40% after ten); the case's corrected continuity
 * holds it (BENCHMARKS.md), and two cycles are what fits a ctest. */
static void test_cycle(void)
{
    errors e;
    run_record r;
    CHECK_OK(run_case(0, 0.05, 2.0, -1, &e, &r));
    fprintf(stderr, "expansion cycle 2D: interior %.4f%%, band %.4f%% (%d particles)\n", 100 * e.worst[0],
            100 * e.worst[1], r.particles);
    CHECK(e.worst[0] < 0.002, "interior volume error %.4f%% (goal < 0.2%%)", 100 * e.worst[0]);
    CHECK(e.worst[1] < 0.004, "volume error in 0.8-0.9 R %.4f%% (goal < 0.4%%)", 100 * e.worst[1]);
    CHECK(e.open == 0, "%d measured particles have open Voronoi cells", e.open);
}

/* I1, 3D, one cycle of a ball of only 5 spacings' radius: its interior
 * follows the +-5% swing of m / rho0 to a tenth of it (the goals are
 * measured at finer spacing, BENCHMARKS.md; the band 0.8-0.9 R is the
 * second layer from the surface here and is not checked). */
static void test_cycle_3d(void)
{
    errors e;
    run_record r;
    CHECK_OK(run_case(1, 0.2, 1.0, -1, &e, &r));
    fprintf(stderr, "expansion cycle 3D: interior %.4f%%, band %.4f%% (%d particles)\n", 100 * e.worst[0],
            100 * e.worst[1], r.particles);
    CHECK(e.worst[0] < 0.005, "interior volume error %.4f%% (a tenth of the swing: 0.5%%)", 100 * e.worst[0]);
}

/* I3, coarse: both fluids' volumes within 1% of m / rho0(T). */
static void test_column(void)
{
    errors e;
    run_record r;
    CHECK_OK(run_case(2, 0.1, 0.0, -1, &e, &r));
    fprintf(stderr, "expansion column: lower %.4f%%, upper %.4f%% (%d particles)\n", 100 * e.worst[0],
            100 * e.worst[1], r.particles);
    CHECK(e.worst[0] < 0.01, "lower fluid volume error %.4f%% (goal < 1%%)", 100 * e.worst[0]);
    CHECK(e.worst[1] < 0.01, "upper fluid volume error %.4f%% (goal < 1%%)", 100 * e.worst[1]);
    CHECK(e.open == 0, "%d measured particles have open Voronoi cells", e.open);
}

/* I4, coarse: the delta-SPH of rho - rho0 smooths the pressure: at most
 * half the noise of the run without it, which may stop on a guard (its
 * noise is the largest until then). */
static void test_sinking(void)
{
    errors with, without;
    run_record r_with, r_without;
    CHECK_OK(run_case(3, 0.05, 0.0, DIFFUSION_RUSSELL, &with, &r_with));
    const int status = run_case(3, 0.05, 0.0, DIFFUSION_NONE, &without, &r_without);
    CHECK(status == 0 || r_without.stopped, "without delta-SPH: %s", amsph_last_error());
    fprintf(stderr, "sinking: pressure noise %.3e rho g H with delta-SPH, %.3e without (to t = %.3g s)\n",
            with.worst[0], without.worst[0], r_without.reached);
    CHECK(with.worst[0] < 0.5 * without.worst[0], "pressure noise %.3e with delta-SPH, %.3e without",
          with.worst[0], without.worst[0]);
}

/* ---- the smoothing length that follows the volume (Russell Eq. 3.54) ---- */

/* A droplet of radius 0.5 m (314 particles) whose rho0 falls 10% over the
 * first 0.5 s (a linear rho0(T) and a temperature ramp), then stays. */
static const char *expanding_case =
    "dimension: 2\n"
    "domain: {min: [-1, -1], max: [1, 1]}\n"
    "dx: 0.05\n"
    "kernel: quintic\n"
    "h_over_dx: 1.2\n"
    "end_time: 1.5\n"
    "output_interval: 0.5\n"
    "temperature_history: {form: ramp, reference: 300, amplitude: 100, duration: 0.5}\n"
    "fluid: {smoothing_length: volume, max_smoothing_ratio: %g, viscosity: artificial, artificial_alpha: 0.1}\n"
    "materials:\n"
    "  - {name: liquid, density: [[300, 1000], [400, 900]], sound_speed: 50}\n"
    "geometry:\n"
    "  - {shape: circle, kind: fluid, material: liquid, center: [0, 0], radius: 0.5}\n";

static int parse_text(const char *text, amsph_case *c)
{
    char err[512];
    return amsph_case_parse(text, strlen(text), "smoothing.yaml", c, err, sizeof err) ? amsph_fail("%s", err) : 0;
}

/* The droplet run to its end on backend b with the grid laid out for
 * max_ratio h0; its particles at the end into h (freed by the caller). */
static int run_expanding(amsph_backend *b, double max_ratio, amsph_host_particles *h, int *guard_failed)
{
    char text[2048];
    snprintf(text, sizeof text, expanding_case, max_ratio);
    amsph_case c;
    AMSPH_CHECK(parse_text(text, &c));
    amsph_sim s;
    int status = amsph_sim_create(&c, b, &s);
    if (!status)
        status = amsph_sim_advance(&s, c.end_time, NULL, NULL);
    *guard_failed = s.guard_failed;
    if (!status)
        status = amsph_particles_download(&s.particles, h);
    amsph_sim_free(&s);
    return status;
}

/* Mean h / h0 and Voronoi volume / dx^2 of the particles within R/2 of
 * the centre, R from the expected volume (droplet_shape). */
static int interior_means(const amsph_host_particles *h, double h0, double dx, double *h_ratio, double *v_ratio)
{
    double shape[4], *volume = malloc((size_t)h->n * sizeof *volume);
    droplet_shape(h, 2, shape);
    if (!volume || voronoi_volumes(amsph_host_real(h, AMSPH_FIELD_POSITION), h->n, 2, VORONOI_REACH * dx, volume)) {
        free(volume);
        return amsph_fail("out of memory for the Voronoi cells");
    }
    double sum_h = 0.0, sum_v = 0.0, count = 0.0;
    for (int i = 0; i < h->n; ++i)
        if (droplet_region(NULL, h, i, shape) == 0 && volume[i] > 0.0) {
            sum_h += amsph_host_real(h, AMSPH_FIELD_SMOOTHING_LENGTH)[i] / h0;
            sum_v += volume[i] / (dx * dx);
            count += 1.0;
        }
    free(volume);
    *h_ratio = sum_h / count;
    *v_ratio = sum_v / count;
    return count > 0.0 ? 0 : amsph_fail("no interior particles");
}

/* The droplet's rho0 falls 10%, so its particles' volumes grow by 1/0.9
 * and, after Eq. 3.54, their h by sqrt(1/0.9) = 1.0541 in 2D: the interior's
 * mean h within 0.2% of that (the volumes follow m / rho0 to about 0.15%,
 * BENCHMARKS.md, h to half of it) and of h0 sqrt(V / dx^2) of its measured
 * Voronoi cells; both backends within 1e-4 of each other. With the grid
 * laid out for 1.03 h0 the run stops on the smoothing-length guard, which
 * names the particle. */
static void test_volume_smoothing(void)
{
    const double h0 = 1.2 * 0.05, expected = sqrt(1.0 / 0.9);
    double backend_ratio[TESTING_BACKENDS] = {0.0, 0.0};
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        amsph_backend *b = testing_backend(k);
        if (!b)
            continue;
        amsph_host_particles h = {0};
        int stopped = 0;
        CHECK_OK(run_expanding(b, 1.1, &h, &stopped));
        amsph_backend_destroy(b);
        double h_ratio = 0.0, v_ratio = 0.0;
        CHECK_OK(interior_means(&h, h0, 0.05, &h_ratio, &v_ratio));
        fprintf(stderr, "backend %d: interior h / h0 %.5f (sqrt(1/0.9) = %.5f), Voronoi V / dx^2 %.5f\n", k,
                h_ratio, expected, v_ratio);
        CHECK(fabs(h_ratio / expected - 1.0) < 0.002, "backend %d: interior h / h0 = %.5f, expected %.5f", k, h_ratio,
              expected);
        CHECK(fabs(h_ratio / sqrt(v_ratio) - 1.0) < 0.002, "backend %d: h / h0 = %.5f, sqrt(V / V0) = %.5f", k,
              h_ratio, sqrt(v_ratio));
        backend_ratio[k] = h_ratio;
        amsph_host_free(&h);
    }
    if (backend_ratio[1] > 0.0)
        CHECK(fabs(backend_ratio[1] / backend_ratio[0] - 1.0) < 1e-4, "backends differ: h / h0 %.6f and %.6f",
              backend_ratio[0], backend_ratio[1]);
    amsph_host_particles h = {0};
    int stopped = 0;
    amsph_backend *b = testing_backend(0);
    CHECK(run_expanding(b, 1.03, &h, &stopped) != 0 && stopped, "h outgrew 1.03 h0 and the run went on");
    amsph_backend_destroy(b);
    CHECK(strstr(amsph_last_error(), "guard 'smoothing length' failed") &&
              strstr(amsph_last_error(), "particle id") && strstr(amsph_last_error(), "max_smoothing_ratio = 1.03"),
          "the guard's message: %s", amsph_last_error());
    amsph_host_free(&h);
}

/* An isolated cloud of fluid particles, 12 x 12 in 2D, 6 x 6 x 6 in 3D,
 * positions jittered by up to 0.15 dx, densities 0.9 to 1.1 rho0 (so h
 * spreads over +-5% in 2D, +-3.4% in 3D), random velocities: one pass of
 * the pair forces, with each viscosity form. */
static const char *cloud_case =
    "dimension: %d\n"
    "domain: {min: %s, max: %s}\n"
    "dx: 0.05\n"
    "end_time: 1\n"
    "output_interval: 1\n"
    "fluid: {smoothing_length: volume, max_smoothing_ratio: 1.2, viscosity: %s, artificial_alpha: 0.5,\n"
    "        tensile_correction: 0.1}\n"
    "materials:\n"
    "  - {name: liquid, density: 1000, sound_speed: 10, viscosity: 0.5}\n"
    "geometry:\n"
    "  - {shape: box, kind: fluid, material: liquid, min: %s, max: %s}\n";

enum { CLOUD_MAX = 216 };

typedef struct {
    int n;
    double ma[CLOUD_MAX][3]; /* m a by particle id */
    double h[CLOUD_MAX];     /* smoothing length by particle id */
    double spread;           /* max h / min h */
} cloud_result;

/* The same draws for a particle id on every backend: jitter, velocity, density. */
static void perturb_cloud(amsph_host_particles *h, int dim, double dx)
{
    for (int i = 0; i < h->n; ++i) {
        unsigned long long state = 12345 + 7919ULL * ((unsigned *)h->data[AMSPH_FIELD_ID])[i];
        for (int d = 0; d < dim; ++d) {
            amsph_host_real(h, AMSPH_FIELD_POSITION)[3 * i + d] += (amsph_real)(0.3 * dx * (testing_random(&state) - 0.5));
            amsph_host_real(h, AMSPH_FIELD_VELOCITY)[3 * i + d] = (amsph_real)(0.2 * (testing_random(&state) - 0.5));
        }
        amsph_host_real(h, AMSPH_FIELD_DENSITY)[i] = (amsph_real)(1000.0 * (0.9 + 0.2 * testing_random(&state)));
    }
}

static void keep_cloud(const amsph_host_particles *h, cloud_result *r)
{
    double lo = INFINITY, hi = 0.0;
    r->n = h->n;
    for (int i = 0; i < h->n && i < CLOUD_MAX; ++i) {
        const unsigned id = ((unsigned *)h->data[AMSPH_FIELD_ID])[i];
        const double m = amsph_host_real(h, AMSPH_FIELD_MASS)[i];
        for (int d = 0; d < 3; ++d)
            r->ma[id][d] = m * amsph_host_real(h, AMSPH_FIELD_ACCELERATION)[3 * i + d];
        r->h[id] = amsph_host_real(h, AMSPH_FIELD_SMOOTHING_LENGTH)[i];
        lo = fmin(lo, r->h[id]);
        hi = fmax(hi, r->h[id]);
    }
    r->spread = hi / lo;
}

/* The perturbed cloud's pair forces on backend b. */
static int cloud_forces(amsph_backend *b, int dim, const char *viscosity, cloud_result *r)
{
    char text[2048];
    const char *corner = dim == 2 ? "[-1, -1]" : "[-1, -1, -1]", *far = dim == 2 ? "[1, 1]" : "[1, 1, 1]";
    const char *lo = dim == 2 ? "[-0.3, -0.3]" : "[-0.15, -0.15, -0.15]", *hi = dim == 2 ? "[0.3, 0.3]" : "[0.15, 0.15, 0.15]";
    snprintf(text, sizeof text, cloud_case, dim, corner, far, viscosity, lo, hi);
    amsph_case c;
    AMSPH_CHECK(parse_text(text, &c));
    amsph_sim s;
    amsph_host_particles h;
    int status = amsph_sim_create(&c, b, &s);
    if (!status)
        status = amsph_particles_download(&s.particles, &h);
    if (!status) {
        perturb_cloud(&h, dim, c.dx);
        amsph_particles_free(&s.particles);
        status = amsph_particles_upload(b, &h, &s.particles);
        amsph_host_free(&h);
    }
    if (!status)
        status = amsph_grid_sort(&s.grid, &s.particles);
    if (!status)
        status = amsph_fluid_density(&s, 0.0); /* the Shepard sums and h at these densities */
    if (!status)
        status = amsph_fluid_forces(&s);
    if (!status)
        status = amsph_particles_download(&s.particles, &h);
    if (!status) {
        keep_cloud(&h, r);
        status = h.n <= CLOUD_MAX ? 0 : amsph_fail("the cloud has %d particles, more than %d", h.n, CLOUD_MAX);
        amsph_host_free(&h);
    }
    amsph_sim_free(&s);
    return status;
}

/* Each h follows its particle's volume, in 2D and 3D: the cloud's h spans
 * (1.1 / 0.9)^(1/d). With h_ab = (h_a + h_b) / 2 every pair's forces are equal and opposite:
 * the cloud's sum of m a is round-off (below 1e-5 of sum |m a|; a pair
 * kernel at h_a alone leaves 8e-3 here in 2D), for laminar and artificial
 * viscosity with the tensile correction, in 2D and 3D; both backends agree
 * to 1e-4. */
static void test_volume_smoothing_momentum(void)
{
    static const char *forms[] = {"laminar", "artificial"};
    static cloud_result r[TESTING_BACKENDS];
    for (int dim = 2; dim <= 3; ++dim)
        for (int f = 0; f < 2; ++f) {
            int ran[TESTING_BACKENDS] = {0, 0};
            for (int k = 0; k < TESTING_BACKENDS; ++k) {
                amsph_backend *b = testing_backend(k);
                if (!b)
                    continue;
                const int status = cloud_forces(b, dim, forms[f], &r[k]);
                amsph_backend_destroy(b);
                CHECK_OK(status);
                ran[k] = !status;
                double net[3] = {0.0, 0.0, 0.0}, scale = 0.0;
                for (int id = 0; id < r[k].n; ++id) {
                    const double *ma = r[k].ma[id];
                    for (int d = 0; d < 3; ++d)
                        net[d] += ma[d];
                    scale += sqrt(ma[0] * ma[0] + ma[1] * ma[1] + ma[2] * ma[2]);
                }
                const double momentum = sqrt(net[0] * net[0] + net[1] * net[1] + net[2] * net[2]);
                fprintf(stderr, "%dD %s, backend %d: |sum m a| / sum |m a| = %.3e, h spread %.4f\n", dim, forms[f],
                        k, momentum / scale, r[k].spread);
                /* the densities span nearly 0.9 to 1.1 rho0, so h spans (1.1 / 0.9)^(1/d) to within 1% */
                const double span = pow(1.1 / 0.9, 1.0 / dim);
                CHECK(fabs(r[k].spread / span - 1.0) < 0.01, "%dD: h spreads by %.4f, not (1.1 / 0.9)^(1/%d) = %.4f",
                      dim, r[k].spread, dim, span);
                CHECK(momentum < 1e-5 * scale, "%dD %s, backend %d: momentum %.3e of %.3e", dim, forms[f], k,
                      momentum, scale);
            }
            if (ran[0] && ran[1]) {
                double worst = 0.0, largest = 0.0, h_diff = 0.0;
                for (int id = 0; id < r[0].n; ++id)
                    for (int d = 0; d < 3; ++d) {
                        worst = fmax(worst, fabs(r[0].ma[id][d] - r[1].ma[id][d]));
                        largest = fmax(largest, fabs(r[0].ma[id][d]));
                        h_diff = fmax(h_diff, fabs(r[0].h[id] / r[1].h[id] - 1.0));
                    }
                CHECK(worst < 1e-4 * largest && h_diff < 1e-5, "%dD %s: the backends differ by %.3e of m a, %.3e of h",
                      dim, forms[f], worst / largest, h_diff);
            }
        }
}

/* ---- the sweep ---------------------------------------------------------- */

static void print_row(int k, const char *variant, double dx, const errors *e, const run_record *r)
{
    printf("| %s%s | %g | %d | %lld | %.1f | %.3g | %.3g%s |", cases[k].name, variant, dx, r->particles, r->steps,
           r->wall, (double)r->particles * (double)r->steps / r->wall, r->reached, r->stopped ? " (guard)" : "");
    for (int j = 0; j < MAX_ERRORS; ++j)
        if (cases[k].what[j])
            printf(" %.3e |", e->worst[j]);
    printf(" %d |\n", e->open);
    fflush(stdout);
}

/* The whole case at each spacing (the sinking case with and without
 * delta-SPH), one Markdown row each; a run a guard stopped reports its
 * errors until then. */
static int sweep(int argc, char **argv)
{
    int k = 0;
    while (k < N_CASES && strcmp(argv[2], cases[k].name) != 0)
        ++k;
    if (k == N_CASES) {
        fprintf(stderr, "test_isothermal sweep: unknown case '%s' (cycle, cycle_volume_h, cycle_3d, column, sinking)\n",
                argv[2]);
        return 2;
    }
    printf("| case | dx (m) | particles | steps | wall (s) | particle-steps/s | reached (s) |");
    for (int j = 0; j < MAX_ERRORS; ++j)
        if (cases[k].what[j])
            printf(" %s |", cases[k].what[j]);
    printf(" open cells |\n|---|---|---|---|---|---|---|%s%s---|\n", cases[k].what[0] ? "---|" : "",
           cases[k].what[1] ? "---|" : "");
    const int sinking = strcmp(cases[k].name, "sinking") == 0;
    for (int a = 3; a < argc; ++a) {
        const double dx = atof(argv[a]);
        for (int v = 0; v <= sinking; ++v) {
            errors e;
            run_record r;
            if (run_case(k, dx, 0.0, v ? DIFFUSION_NONE : -1, &e, &r)) {
                fprintf(stderr, "%s%s, dx %g: %s\n", cases[k].name, v ? " (no delta-SPH)" : "", dx,
                        amsph_last_error());
                if (!r.stopped)
                    return 1;
            }
            print_row(k, v ? " (no delta-SPH)" : "", dx, &e, &r);
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 4 && strcmp(argv[1], "sweep") == 0)
        return sweep(argc, argv);
    static const struct {
        const char *name;
        void (*run)(void);
    } parts[] = {{"law", test_steel_density}, {"law", test_thermal_drives_rho0}, {"cycle", test_cycle},
                 {"cycle_3d", test_cycle_3d},   {"column", test_column},                {"sinking", test_sinking},
                 {"smoothing", test_volume_smoothing}, {"smoothing", test_volume_smoothing_momentum},
                 {"spray", test_spray}};
    int ran = 0;
    for (size_t k = 0; k < sizeof parts / sizeof parts[0]; ++k)
        if (argc < 2 || strcmp(argv[1], parts[k].name) == 0) {
            parts[k].run();
            ++ran;
        }
    CHECK(ran > 0, "unknown part '%s' (law, cycle, cycle_3d, column, sinking, smoothing, spray; or sweep CASE DX...)",
          argv[1]);
    return testing_finish();
}
