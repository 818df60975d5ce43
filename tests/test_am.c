/* The additive-manufacturing scenes at a small resolution, as tests of the
 * properties a hard case must keep (VALIDATION.md "Stability on hard
 * cases"), not of the papers' figures (BENCHMARKS.md has those):
 *   - the spot weld on 304 steel (cases/am/spot_weld_304_3d.yaml) at
 *     dx = 100 um runs to its end with every guard passing (no NaN, no
 *     pair closer than 0.3 dx, density error in bounds, no particle lost;
 *     at 150 um its 0.5 mm plate is three particles thick and a particle
 *     is still half liquid at 5 ms);
 *   - a melt pool forms (some particle's peak temperature passes the
 *     liquidus, 1773 K) and re-solidifies (at 5 ms no particle is more than
 *     half liquid);
 *   - the energy ledger closes: the enthalpy gained equals the laser energy
 *     absorbed minus radiation plus the wall heat, to 1e-3 of the terms;
 *   - the same for the 2D powder-bed track at 50 W
 *     (cases/am/track_2d_50W.yaml), shortened to 0.3 mm of track (six
 *     grains) on 0.1 mm of substrate at dx = 10 um, with 0.15 ms of cooling
 *     after the 0.15 ms scan;
 *   - DED with mobile grains (cases/am/ded_grains_2d.yaml) at dx = 4 um
 *     (the grains 2 dx in radius) for 12 us: every guard passes, the energy
 *     ledger closes to 1e-4, the grains that reach the pool melt into it
 *     (fewer grain particles, more fluid) and the grains' momentum moves
 *     the melt (the grain particles keep no velocity of their own: each
 *     grain still in flight moves at its initial 10 m/s to 1%).
 * `test_am PART` runs one (spot_weld, track, ded); ctest runs each alone. */
#include <math.h>
#include <string.h>

#include "sim.h"
#include "testing.h"
#include "thermal.h"

/* Runs case c to its end and checks the properties above; `name` for the
 * messages. */
static void run_hard_case(const amsph_case *c, const char *name)
{
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    amsph_host_particles h = {0};
    CHECK_OK(amsph_sim_create(c, b, &s));
    const int start = s.particles.n;
    const int ran = amsph_sim_advance(&s, c->end_time, NULL, NULL) == 0;
    CHECK(ran, "the %s stopped at t = %g s: %s", name, s.time, amsph_last_error());
    double ledger = INFINITY;
    CHECK_OK(amsph_thermal_ledger_error(&s, &ledger));
    if (ran && amsph_particles_download(&s.particles, &h) == 0) {
        const amsph_real *peak = amsph_host_real(&h, AMSPH_FIELD_PEAK_TEMPERATURE);
        const amsph_real *liquid = amsph_host_real(&h, AMSPH_FIELD_LIQUID_FRACTION);
        double hottest = 0.0, most_liquid = 0.0;
        for (int i = 0; i < h.n; ++i) {
            hottest = fmax(hottest, peak[i]);
            most_liquid = fmax(most_liquid, liquid[i]);
        }
        printf("%s, dx %g um: %d particles, %lld steps, peak %.0f K, largest liquid fraction at "
               "%g s %.3f, ledger error %.2e\n",
               name, c->dx * 1e6, h.n, s.step, hottest, s.time, most_liquid, ledger);
        CHECK(h.n == start, "%s: %d of %d particles left", name, h.n, start);
        CHECK(hottest > 1773.0, "%s: no melt pool: the peak temperature %g K stayed below the liquidus",
              name, hottest);
        CHECK(most_liquid < 0.5, "%s: the pool has not solidified: liquid fraction %g at the end", name,
              most_liquid);
        CHECK(ledger < 1e-3, "%s: energy ledger error %g", name, ledger);
    }
    amsph_host_free(&h);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
}

static void test_spot_weld(void)
{
    amsph_case c;
    /* cases/am/, beside the validation cases testing_load_case reads */
    if (testing_load_case("../am/spot_weld_304_3d.yaml", &c))
        return;
    amsph_case_set_spacing(&c, 1.0e-4);
    run_hard_case(&c, "spot weld");
}

/* The track cut to [-half, half] along x, on a substrate `depth` deep with
 * its wall layers below. */
static void shorten_track(amsph_case *c, double half, double depth)
{
    const double wall = 3.0 * c->dx;
    for (int k = 0; k < c->n_geometry; ++k) {
        amsph_geometry *g = &c->geometry[k];
        g->min[0] = -half;
        g->max[0] = half;
        if (g->kind == AMSPH_KIND_SOLID && g->shape == AMSPH_SHAPE_BOX)
            g->min[1] = -depth;
        if (g->kind == AMSPH_KIND_WALL) {
            g->min[1] = -depth - wall;
            g->max[1] = -depth;
        }
    }
    c->domain_min[0] = -half - 0.05e-3;
    c->domain_max[0] = half + 0.05e-3;
    c->domain_min[1] = -depth - 2.0 * wall;
    const double speed = c->laser.path[0].speed;
    c->laser.start[0] = -half;
    c->laser.path[0].to[0] = half;
    c->laser.off_time = 2.0 * half / speed;
    c->end_time = c->laser.off_time + 0.15e-3;
}

/* The 50 W track within the default density bound, 10%. At 100 and 150 W
 * and this spacing the melted grains throw off lone particles that stay
 * in the beam, heat past 8000 K and leave the domain (BENCHMARKS.md). */
static void test_track(void)
{
    amsph_case c;
    if (testing_load_case("../am/track_2d_50W.yaml", &c))
        return;
    amsph_case_set_spacing(&c, 1.0e-5);
    c.fluid.max_density_error = 0.1;
    shorten_track(&c, 0.15e-3, 0.1e-3);
    run_hard_case(&c, "2D track, 50 W");
}

/* Counts of grain and fluid particles, and the speed of the fastest and
 * slowest grain particle. */
static void grain_census(const amsph_host_particles *h, int *grain, int *fluid, double *fastest, double *slowest)
{
    const int *kind = h->data[AMSPH_FIELD_KIND];
    const amsph_real *v = amsph_host_real(h, AMSPH_FIELD_VELOCITY);
    *grain = *fluid = 0;
    *fastest = 0.0;
    *slowest = INFINITY;
    for (int i = 0; i < h->n; ++i) {
        *fluid += kind[i] == AMSPH_KIND_FLUID;
        if (kind[i] == AMSPH_KIND_GRAIN) {
            ++*grain;
            const double speed = sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1]);
            *fastest = fmax(*fastest, speed);
            *slowest = fmin(*slowest, speed);
        }
    }
}

static void test_ded(void)
{
    amsph_case c;
    if (testing_load_case("../am/ded_grains_2d.yaml", &c))
        return;
    amsph_case_set_spacing(&c, 4.0e-6);
    c.end_time = 1.2e-5;
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    amsph_host_particles start = {0}, end = {0};
    CHECK_OK(amsph_sim_create(&c, b, &s));
    CHECK_OK(amsph_particles_download(&s.particles, &start));
    const int ran = amsph_sim_advance(&s, c.end_time, NULL, NULL) == 0;
    CHECK(ran, "DED stopped at t = %g s: %s", s.time, amsph_last_error());
    double ledger = INFINITY;
    CHECK_OK(amsph_thermal_ledger_error(&s, &ledger));
    if (ran && amsph_particles_download(&s.particles, &end) == 0) {
        int grain0, fluid0, grain1, fluid1;
        double fast0, slow0, fast1, slow1;
        grain_census(&start, &grain0, &fluid0, &fast0, &slow0);
        grain_census(&end, &grain1, &fluid1, &fast1, &slow1);
        printf("DED, dx %g um: %d particles, %lld steps; grain particles %d -> %d, fluid %d -> %d, grain "
               "speeds %.3g to %.3g m/s at the end, ledger error %.2e\n",
               c.dx * 1e6, end.n, s.step, grain0, grain1, fluid0, fluid1, slow1, fast1, ledger);
        CHECK(grain1 < grain0 && fluid1 > fluid0 + (grain0 - grain1) / 2,
              "the grains did not melt into the pool: grain particles %d -> %d, fluid %d -> %d", grain0, grain1,
              fluid0, fluid1);
        CHECK(fabs(fast1 - 10.0) < 0.1, "the fastest grain moves at %g m/s, not its initial 10", fast1);
        CHECK(ledger < 1e-4, "DED: energy ledger error %g", ledger);
    }
    amsph_host_free(&start);
    amsph_host_free(&end);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        void (*run)(void);
    } parts[] = {{"spot_weld", test_spot_weld}, {"track", test_track}, {"ded", test_ded}};
    int ran = 0;
    for (size_t k = 0; k < sizeof parts / sizeof parts[0]; ++k)
        if (argc < 2 || strcmp(argv[1], parts[k].name) == 0) {
            parts[k].run();
            ++ran;
        }
    CHECK(ran > 0, "unknown part '%s' (spot_weld, track, ded)", argv[1]);
    return testing_finish();
}
