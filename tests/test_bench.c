/* `amsph bench throughput` and the step's phase timers: the timers leave the
 * simulation's bits alone and charge each module's time to its phase, the
 * phases of a step add up to no more than the step, and the benchmark
 * scales the case to the particle counts asked for and writes a table of
 * that structure. Times are never compared with any speed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "sim.h"
#include "testing.h"
#include "timers.h"

/* cases/bench/am_grains_2d.yaml: every module the step has, mobile grains
 * included, 2023 particles (the grains need at least about 1200). */
static int load_am_case(amsph_case *c)
{
    char path[1024], err[1024];
    snprintf(path, sizeof path, "%s/cases/bench/am_grains_2d.yaml", AMSPH_SOURCE_DIR);
    const int status = amsph_case_load(path, c, err, sizeof err);
    CHECK(status == 0, "%s", err);
    return status;
}

static int take_steps(amsph_sim *s, int count)
{
    for (int k = 0; k < count; ++k) {
        double dt = 0.0;
        AMSPH_CHECK(amsph_sim_stable_dt(s, &dt));
        AMSPH_CHECK(amsph_sim_step(s, dt));
    }
    return amsph_sync(s->backend);
}

/* Fields of the two sims that differ in any bit (-1 if a download fails). */
static int differing_fields(amsph_sim *a, amsph_sim *b)
{
    amsph_host_particles ha, hb;
    int status = amsph_particles_download(&a->particles, &ha);
    if (!status)
        status = amsph_particles_download(&b->particles, &hb);
    int differ = status ? -1 : 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT && !status; ++f)
        if (ha.data[f])
            differ += ha.n != hb.n || !hb.data[f] ||
                      memcmp(ha.data[f], hb.data[f], (size_t)ha.n * amsph_field_bytes((amsph_field_id)f));
    amsph_host_free(&ha);
    amsph_host_free(&hb);
    return differ;
}

/* The AM case twice on one backend: `plain` runs without instruments,
 * `measured` with one (the phase timers, the kernel profile). */
typedef struct {
    amsph_backend *b;
    amsph_sim plain, measured;
} sim_pair;

#define PAIR_STEPS 5

/* The pair after PAIR_STEPS steps of `plain`; nonzero: nothing to test. */
static int sim_pair_open(int backend, sim_pair *p)
{
    amsph_case c;
    p->b = testing_backend(backend);
    if (!p->b || load_am_case(&c)) {
        amsph_backend_destroy(p->b);
        return 1;
    }
    CHECK_OK(amsph_sim_create(&c, p->b, &p->plain));
    CHECK_OK(amsph_sim_create(&c, p->b, &p->measured));
    CHECK_OK(take_steps(&p->plain, PAIR_STEPS));
    return 0;
}

/* PAIR_STEPS steps of `measured`, which must end in the bits of `plain`;
 * their wall time, s. */
static double sim_pair_measure(sim_pair *p, const char *instrument)
{
    const double start = amsph_wall_seconds();
    CHECK_OK(take_steps(&p->measured, PAIR_STEPS));
    const double wall = amsph_wall_seconds() - start;
    CHECK(differing_fields(&p->plain, &p->measured) == 0, "%s: the %s changed the state", p->b->description,
          instrument);
    return wall;
}

static void sim_pair_close(sim_pair *p)
{
    amsph_sim_free(&p->plain);
    amsph_sim_free(&p->measured);
    amsph_backend_destroy(p->b);
}

/* Five steps with the timers on end in the same bits as five without; the
 * phases of the modules the case has are charged and no other, and they add
 * up to no more than the wall time of the steps. */
static void test_timers(int backend)
{
    sim_pair p;
    if (sim_pair_open(backend, &p))
        return;
    amsph_timers_reset(&p.measured.timers, 1);
    const double wall = sim_pair_measure(&p, "timers");
    const amsph_timers *t = &p.measured.timers;
    CHECK(t->current == AMSPH_PHASE_NONE, "%s: the step ended in phase %s", p.b->description,
          amsph_phase_names[t->current]);
    double sum = 0.0;
    for (int k = 1; k < AMSPH_PHASE_COUNT; ++k) {
        CHECK(t->used[k], "%s: phase %s unused in a scene with every module", p.b->description,
              amsph_phase_names[k]);
        CHECK(t->seconds[k] > 0.0, "%s: phase %s charged %g s", p.b->description, amsph_phase_names[k],
              t->seconds[k]);
        sum += t->seconds[k];
    }
    CHECK(sum <= wall, "%s: the phases took %g s of %g s", p.b->description, sum, wall);
    sim_pair_close(&p);
}

/* The kernel profile: five steps with every launch waited for and timed
 * end in the same bits as five without; the kick, launched at the start
 * and the end of each leapfrog step (host/sim.c), is counted twice a step;
 * no launch goes uncounted, and the kernels' times add up to no more than
 * the wall time of the steps. */
static void test_kernel_profile(int backend)
{
    sim_pair p;
    if (sim_pair_open(backend, &p))
        return;
    amsph_kernel_profile profile = {0};
    p.b->profile = &profile;
    const double wall = sim_pair_measure(&p, "kernel profile");
    p.b->profile = NULL;
    CHECK(profile.untracked == 0 && profile.count > 20, "%s: %d kernels timed, %d launches untracked",
          p.b->description, profile.count, profile.untracked);
    double sum = 0.0;
    long long kicks = -1;
    for (int k = 0; k < profile.count; ++k) {
        const amsph_kernel_time *kt = &profile.kernel[k];
        CHECK(kt->launches > 0 && kt->seconds >= 0.0, "%s: %s: %lld launches, %g s", p.b->description, kt->name,
              kt->launches, kt->seconds);
        sum += kt->seconds;
        if (!strcmp(kt->name, "kick"))
            kicks = kt->launches;
    }
    CHECK(kicks == 2 * PAIR_STEPS, "%s: kick launched %lld times in %d steps", p.b->description, kicks,
          PAIR_STEPS);
    CHECK(sum <= wall, "%s: the kernels took %g s of %g s", p.b->description, sum, wall);
    sim_pair_close(&p);
}

/* Splits a CSV line in place into at most `max` fields (quoted fields may
 * hold commas); returns the count. */
static int split_csv(char *line, char **field, int max)
{
    int count = 0;
    for (char *p = line; count < max;) {
        const int quoted = *p == '"';
        field[count++] = p + quoted;
        p = quoted ? strchr(p + 1, '"') : p;
        if (!p)
            break;
        p = strpbrk(p, ",\n");
        if (quoted)
            p[-1] = '\0';
        if (!p || *p == '\n') {
            if (p)
                *p = '\0';
            break;
        }
        *p++ = '\0';
    }
    return count;
}

#define COLUMNS (11 + AMSPH_PHASE_COUNT - 1)

/* Checks one CSV row of the table: the particle count near the one asked
 * for, positive step times, each phase's time given and >= 0 (the scene
 * has every module) and all of them no more than the timed step. */
static void check_row(char *line, long long asked)
{
    char *f[COLUMNS + 1];
    const int count = split_csv(line, f, COLUMNS + 1);
    CHECK(count == COLUMNS, "a row has %d fields, expected %d", count, COLUMNS);
    if (count != COLUMNS)
        return;
    const long long particles = atoll(f[4]);
    CHECK(fabs((double)particles / (double)asked - 1.0) < 0.05, "%lld particles for %lld asked", particles,
          asked);
    CHECK(atof(f[7]) > 0.0 && atof(f[8]) > 0.0 && atof(f[10]) > 0.0,
          "ms/step %s, particle-steps/s %s, timed ms/step %s", f[7], f[8], f[10]);
    CHECK(fabs(atof(f[8]) - (double)particles / (1e-3 * atof(f[7]))) <= 1e-4 * atof(f[8]),
          "particle-steps/s %s is not particles / time per step", f[8]);
    CHECK(atof(f[9]) > 100.0, "%s device bytes per particle (the fields alone take more)", f[9]);
    double sum = 0.0;
    for (int k = 1; k < AMSPH_PHASE_COUNT; ++k) {
        const char *ms = f[10 + k];
        CHECK(*ms != '\0', "phase %s: no time", amsph_phase_names[k]);
        CHECK(atof(ms) >= 0.0, "phase %s: %s ms", amsph_phase_names[k], ms);
        sum += atof(ms);
    }
    CHECK(sum <= atof(f[10]) * (1.0 + 1e-5), "the phases took %g ms of a %s ms step", sum, f[10]);
}

/* The table for two particle counts on the OpenMP backend. */
static void test_throughput_table(void)
{
    amsph_case c;
    amsph_backend *b = testing_backend(0);
    if (!b || load_am_case(&c)) {
        amsph_backend_destroy(b);
        return;
    }
    char *text = NULL, *csv_text = NULL;
    size_t text_size = 0, csv_size = 0;
    FILE *out = open_memstream(&text, &text_size);
    amsph_bench_options o = {.particles = {1500, 3000}, .n_particles = 2, .warmup = 1, .steps = 2, .kernels = 1};
    o.csv = open_memstream(&csv_text, &csv_size);
    CHECK_OK(amsph_bench_throughput(b, &c, &o, out));
    fclose(out);
    fclose(o.csv);
    CHECK(strstr(text, "| particles | ms/step | particle-steps/s |") != NULL, "no table header in:\n%s", text);
    CHECK(strstr(text, "cost growth: time per step ~ particles^") != NULL, "no growth exponent in:\n%s", text);
    const char *kernels = strstr(text, "\nkernels at 1");
    CHECK(kernels && strstr(kernels + 1, "\nkernels at 3"), "no kernel table for each count in:\n%s", text);
    CHECK(kernels && strstr(kernels, "| kick | 2 | "), "no kick launched twice a step in:\n%s", text);
    char *line[3] = {csv_text};
    for (int k = 1; k < 3; ++k)
        line[k] = line[k - 1] && strchr(line[k - 1], '\n') ? strchr(line[k - 1], '\n') + 1 : NULL;
    CHECK(!strncmp(csv_text, "case,dim,backend,build,particles,", 33), "CSV header: %.60s", csv_text);
    CHECK(line[2] && *line[2], "the CSV has fewer than two rows:\n%s", csv_text);
    if (line[2] && *line[2]) {
        check_row(line[1], 1500);
        check_row(line[2], 3000);
    }
    free(text);
    free(csv_text);
    amsph_backend_destroy(b);
}

/* The scene scaled to 15000 particles (dx 0.0027 m) steps: the grains'
 * contact distance follows dx (Fuchs et al. 2022 Eq. 40); left at the
 * case's dx, 0.0073 m, it would exceed the kernel support, 2.4 dx = 0.0064
 * m, and the sim would refuse the case. */
static void test_scaled_contact_distance(void)
{
    amsph_case c;
    amsph_backend *b = testing_backend(0);
    if (!b || load_am_case(&c)) {
        amsph_backend_destroy(b);
        return;
    }
    char *text = NULL;
    size_t text_size = 0;
    FILE *out = open_memstream(&text, &text_size);
    amsph_bench_options o = {.particles = {15000}, .n_particles = 1, .warmup = 0, .steps = 1};
    CHECK_OK(amsph_bench_throughput(b, &c, &o, out));
    fclose(out);
    free(text);
    amsph_backend_destroy(b);
}

int main(void)
{
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        test_timers(k);
        test_kernel_profile(k);
    }
    test_throughput_table();
    test_scaled_contact_distance();
    return testing_finish();
}
