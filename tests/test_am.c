/* The additive-manufacturing scenes at a small resolution, as tests of the
 * properties a hard case must keep (VALIDATION.md "Stability on hard
 * cases"), not of the papers' figures (BENCHMARKS.md has those):
 *   - the spot weld on 304 steel (cases/am/spot_weld_304_3d.yaml) at
 *     dx = 150 um runs to its end with every guard passing (no NaN, no pair
 *     closer than 0.3 dx, density error in bounds, no particle lost);
 *   - a melt pool forms (some particle's peak temperature passes the
 *     liquidus, 1773 K) and re-solidifies (at 5 ms no particle is more than
 *     half liquid);
 *   - the energy ledger closes: the enthalpy gained equals the laser energy
 *     absorbed minus radiation plus the wall heat, to 1e-3 of the terms. */
#include <math.h>

#include "sim.h"
#include "testing.h"
#include "thermal.h"

static void test_spot_weld(void)
{
    amsph_case c;
    /* cases/am/, beside the validation cases testing_load_case reads */
    if (testing_load_case("../am/spot_weld_304_3d.yaml", &c))
        return;
    c.dx = 1.5e-4;
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    amsph_host_particles h = {0};
    CHECK_OK(amsph_sim_create(&c, b, &s));
    const int start = s.particles.n;
    const int ran = amsph_sim_advance(&s, c.end_time, NULL, NULL) == 0;
    CHECK(ran, "the spot weld stopped at t = %g s: %s", s.time, amsph_last_error());
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
        printf("spot weld, dx 150 um: %d particles, %lld steps, peak %.0f K, largest liquid fraction at "
               "%g s %.3f, ledger error %.2e\n",
               h.n, s.step, hottest, s.time, most_liquid, ledger);
        CHECK(h.n == start, "%d of %d particles left", h.n, start);
        CHECK(hottest > 1773.0, "no melt pool: the peak temperature %g K stayed below the liquidus", hottest);
        CHECK(most_liquid < 0.5, "the pool has not solidified: liquid fraction %g at the end", most_liquid);
        CHECK(ledger < 1e-3, "energy ledger error %g", ledger);
    }
    amsph_host_free(&h);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
}

int main(void)
{
    test_spot_weld();
    return testing_finish();
}
