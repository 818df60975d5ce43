/* The melt-pool analysis (host/analyze.c) on synthetic snapshot
 * directories written through the snapshot writer, whose melt regions are
 * lattice boxes with analytic extents, and on a real short run, whose peak
 * temperature and liquid mass must match the run's own series (another
 * code path over the same particles). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analyze.h"
#include "case.h"
#include "output.h"
#include "sim.h"
#include "testing.h"

#define DX 0.1
#define MASS 2.0     /* kg per particle */
#define MAX_ROWS 8

/* A lattice block of material particles at (i + 1/2, j + 1/2, k + 1/2) dx,
 * i < nx, j < ny, k < nz (nz = 1 in 2D), solid at 300 K, at rest. */
static int lattice(int dim, int nx, int ny, int nz, amsph_host_particles *h)
{
    static const amsph_field_id fields[] = {AMSPH_FIELD_POSITION, AMSPH_FIELD_VELOCITY, AMSPH_FIELD_KIND,
                                            AMSPH_FIELD_MASS, AMSPH_FIELD_TEMPERATURE,
                                            AMSPH_FIELD_LIQUID_FRACTION};
    memset(h, 0, sizeof *h);
    h->n = nx * ny * (dim == 3 ? nz : 1);
    for (size_t f = 0; f < sizeof fields / sizeof fields[0]; ++f)
        AMSPH_CHECK(amsph_host_add_field(h, fields[f]));
    amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
    for (int p = 0; p < h->n; ++p) {
        const int i = p % nx, j = (p / nx) % ny, k = p / (nx * ny);
        x[3 * p] = (amsph_real)((i + 0.5) * DX);
        x[3 * p + 1] = (amsph_real)((j + 0.5) * DX);
        x[3 * p + 2] = (amsph_real)(dim == 3 ? (k + 0.5) * DX : 0.0);
        ((int *)h->data[AMSPH_FIELD_KIND])[p] = AMSPH_KIND_SOLID;
        amsph_host_real(h, AMSPH_FIELD_MASS)[p] = (amsph_real)MASS;
        amsph_host_real(h, AMSPH_FIELD_TEMPERATURE)[p] = 300;
    }
    return 0;
}

/* Lattice indices of particle p (as lattice() placed it). */
static void indices(const amsph_host_particles *h, int p, int idx[3])
{
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
    for (int d = 0; d < 3; ++d)
        idx[d] = (int)floor(x[3 * p + d] / DX);
}

/* Melts (liquid fraction 1, fluid, temperature t) the particles with
 * lo[d] <= index < hi[d]. */
static void melt_box(amsph_host_particles *h, const int lo[3], const int hi[3], double t)
{
    for (int p = 0; p < h->n; ++p) {
        int idx[3];
        indices(h, p, idx);
        if (idx[0] >= lo[0] && idx[0] < hi[0] && idx[1] >= lo[1] && idx[1] < hi[1] && idx[2] >= lo[2] &&
            idx[2] < hi[2]) {
            amsph_host_real(h, AMSPH_FIELD_LIQUID_FRACTION)[p] = 1;
            amsph_host_real(h, AMSPH_FIELD_TEMPERATURE)[p] = (amsph_real)t;
            ((int *)h->data[AMSPH_FIELD_KIND])[p] = AMSPH_KIND_FLUID;
        }
    }
}

/* The particle at lattice indices (i, j, k). */
static int at(const amsph_host_particles *h, int i, int j, int k)
{
    for (int p = 0; p < h->n; ++p) {
        int idx[3];
        indices(h, p, idx);
        if (idx[0] == i && idx[1] == j && idx[2] == k)
            return p;
    }
    return -1;
}

/* The analysis CSV: rows x columns of values (NAN for an empty cell). */
typedef struct {
    int rows;
    double value[MAX_ROWS][32];
} table;

static double cell(const table *t, int row, const char *name)
{
    for (int k = 0; k < amsph_analysis_metric_count; ++k)
        if (!strcmp(amsph_analysis_metrics[k].name, name))
            return t->value[row][k];
    CHECK(0, "no metric %s", name);
    return NAN;
}

static int read_table(const char *path, table *t)
{
    FILE *f = fopen(path, "r");
    char line[4096];
    memset(t, 0, sizeof *t);
    if (!f || !fgets(line, sizeof line, f))
        return -1;
    while (t->rows < MAX_ROWS && fgets(line, sizeof line, f)) {
        char *s = line;
        for (int k = 0; k < amsph_analysis_metric_count; ++k) {
            char *end = s;
            const double v = strtod(s, &end);
            t->value[t->rows][k] = end == s ? NAN : v;
            s = strchr(end, ',');
            s = s ? s + 1 : end;
        }
        ++t->rows;
    }
    fclose(f);
    return 0;
}

static void write_snapshots(const char *dir, int dim, amsph_host_particles *snaps, const double *times, int count)
{
    amsph_output o;
    CHECK_OK(amsph_output_open(&o, dir, dim, DX, 1));
    for (int k = 0; k < count; ++k)
        CHECK_OK(amsph_output_snapshot(&o, &snaps[k], times[k], k));
    amsph_output_close(&o);
}

static int near(double a, double b) { return fabs(a - b) <= 1e-6 * fmax(1.0, fabs(b)); }

/* 2D: a 40 x 10 substrate (top face at 1.0 m). Snapshot 1: a 10 x 4 pool
 * in columns 10-19, rows 6-9, at 2000 K with one particle at 2500 K moving
 * at (3, 4) m/s; the top particle of column 12 (melt) raised 0.05 m, that
 * of column 30 (solid, off the track) 0.3 m. Snapshot 2 (2 s later): a 6 x 2 pool (columns
 * 12-17, rows 8-9) and one particle at liquid fraction 0.4 (not melt); the
 * track is still columns 10-19. */
static void test_synthetic_2d(void)
{
    char dir[256], csv[512];
    if (testing_temp_dir(dir, sizeof dir, "analyze_2d"))
        return;
    amsph_host_particles s[3];
    for (int k = 0; k < 3; ++k)
        CHECK_OK(lattice(2, 40, 10, 1, &s[k]));
    melt_box(&s[1], (int[3]){10, 6, 0}, (int[3]){20, 10, 1}, 2000);
    const int hot = at(&s[1], 15, 7, 0);
    amsph_host_real(&s[1], AMSPH_FIELD_TEMPERATURE)[hot] = 2500;
    amsph_host_real(&s[1], AMSPH_FIELD_VELOCITY)[3 * hot] = 3;
    amsph_host_real(&s[1], AMSPH_FIELD_VELOCITY)[3 * hot + 1] = 4;
    amsph_host_real(&s[1], AMSPH_FIELD_POSITION)[3 * at(&s[1], 12, 9, 0) + 1] += (amsph_real)0.05;
    amsph_host_real(&s[1], AMSPH_FIELD_POSITION)[3 * at(&s[1], 30, 9, 0) + 1] += (amsph_real)0.3;
    melt_box(&s[2], (int[3]){12, 8, 0}, (int[3]){18, 10, 1}, 1900);
    amsph_host_real(&s[2], AMSPH_FIELD_LIQUID_FRACTION)[at(&s[2], 19, 9, 0)] = (amsph_real)0.4;
    amsph_host_real(&s[2], AMSPH_FIELD_POSITION)[3 * at(&s[2], 11, 9, 0) + 1] -= (amsph_real)0.02;
    const double times[3] = {0.0, 1.0, 3.0};
    write_snapshots(dir, 2, s, times, 3);
    snprintf(csv, sizeof csv, "%s/pool.csv", dir);
    const amsph_analysis_axes axes = {.scan = 0, .up = -1, .track_at = NAN, .surface = NAN};
    CHECK_OK(amsph_analyze(dir, &axes, csv));
    table t;
    CHECK(read_table(csv, &t) == 0 && t.rows == 3, "%s: %d rows", csv, t.rows);
    CHECK(cell(&t, 0, "melt_particles") == 0 && isnan(cell(&t, 0, "melt_length")) &&
              isnan(cell(&t, 0, "solidification_rate")) && isnan(cell(&t, 0, "track_height_variation")),
          "snapshot 0: no melt, no rate, no track");
    CHECK(cell(&t, 1, "melt_particles") == 40 && near(cell(&t, 1, "melt_length"), 1.0) &&
              near(cell(&t, 1, "melt_depth"), 0.45) && isnan(cell(&t, 1, "melt_width")),
          "snapshot 1: %g melt particles, length %g m (1), depth %g m (0.45: 4 rows and the raised particle), "
          "width %g (empty in 2D)",
          cell(&t, 1, "melt_particles"), cell(&t, 1, "melt_length"), cell(&t, 1, "melt_depth"),
          cell(&t, 1, "melt_width"));
    CHECK(near(cell(&t, 1, "penetration"), 0.4) && near(cell(&t, 1, "peak_temperature"), 2500) &&
              near(cell(&t, 1, "peak_speed"), 5.0),
          "snapshot 1: penetration %g m (0.4), peak %g K (2500), speed %g m/s (5)", cell(&t, 1, "penetration"),
          cell(&t, 1, "peak_temperature"), cell(&t, 1, "peak_speed"));
    char given_csv[600];
    snprintf(given_csv, sizeof given_csv, "%s/pool_surface.csv", dir);
    table given;
    const amsph_analysis_axes at_surface = {.scan = 0, .up = -1, .track_at = NAN, .surface = 0.8};
    CHECK_OK(amsph_analyze(dir, &at_surface, given_csv));
    CHECK(read_table(given_csv, &given) == 0 && near(cell(&given, 1, "penetration"), 0.2),
          "snapshot 1 with the surface given at 0.8 m: penetration %g m (0.2)", cell(&given, 1, "penetration"));
    CHECK(near(cell(&t, 1, "track_height_variation"), 0.05),
          "snapshot 1: track height variation %g m (0.05; column 30 is off the track)",
          cell(&t, 1, "track_height_variation"));
    CHECK(cell(&t, 2, "melt_particles") == 12 && near(cell(&t, 2, "melt_length"), 0.6) &&
              near(cell(&t, 2, "melt_depth"), 0.2) && near(cell(&t, 2, "penetration"), 0.2),
          "snapshot 2: %g melt particles (12), length %g (0.6), depth %g (0.2), penetration %g (0.2)",
          cell(&t, 2, "melt_particles"), cell(&t, 2, "melt_length"), cell(&t, 2, "melt_depth"),
          cell(&t, 2, "penetration"));
    const double rate = (40.0 - 12.4) * MASS / 2.0;
    CHECK(near(cell(&t, 2, "liquid_mass"), 12.4 * MASS) && near(cell(&t, 2, "solidification_rate"), rate),
          "snapshot 2: liquid mass %g kg (%g), solidification rate %g kg/s (%g)", cell(&t, 2, "liquid_mass"),
          12.4 * MASS, cell(&t, 2, "solidification_rate"), rate);
    CHECK(near(cell(&t, 2, "track_height_variation"), 0.02),
          "snapshot 2: track height variation %g m (0.02: column 11, melted at snapshot 1, sank)",
          cell(&t, 2, "track_height_variation"));
    for (int k = 0; k < 3; ++k)
        amsph_host_free(&s[k]);
}

/* 3D: a 20 x 10 x 6 substrate; a pool of 8 x 4 x 3 (x from 5, y from 3,
 * the top 3 layers): length 0.8, width 0.4, depth 0.3, penetration 0.3. With
 * --scan y the length and width swap. */
static void test_synthetic_3d(void)
{
    char dir[256], csv[512];
    if (testing_temp_dir(dir, sizeof dir, "analyze_3d"))
        return;
    amsph_host_particles s[2];
    for (int k = 0; k < 2; ++k)
        CHECK_OK(lattice(3, 20, 10, 6, &s[k]));
    melt_box(&s[1], (int[3]){5, 3, 3}, (int[3]){13, 7, 6}, 2000);
    const double times[2] = {0.0, 1.0};
    write_snapshots(dir, 3, s, times, 2);
    snprintf(csv, sizeof csv, "%s/pool.csv", dir);
    for (int scan = 0; scan < 2; ++scan) {
        const amsph_analysis_axes axes = {.scan = scan, .up = -1, .track_at = NAN, .surface = NAN};
        table t;
        CHECK_OK(amsph_analyze(dir, &axes, csv));
        CHECK(read_table(csv, &t) == 0 && t.rows == 2, "%s: %d rows", csv, t.rows);
        const double length = scan ? 0.4 : 0.8, width = scan ? 0.8 : 0.4;
        CHECK(cell(&t, 1, "melt_particles") == 96 && near(cell(&t, 1, "melt_length"), length) &&
                  near(cell(&t, 1, "melt_width"), width) && near(cell(&t, 1, "melt_depth"), 0.3) &&
                  near(cell(&t, 1, "penetration"), 0.3) && near(cell(&t, 1, "track_height_variation"), 0.0),
              "3D, scan %c: %g melt particles (96), length %g (%g), width %g (%g), depth %g (0.3), penetration "
              "%g (0.3), height variation %g (0)",
              "xy"[scan], cell(&t, 1, "melt_particles"), cell(&t, 1, "melt_length"), length,
              cell(&t, 1, "melt_width"), width, cell(&t, 1, "melt_depth"), cell(&t, 1, "penetration"),
              cell(&t, 1, "track_height_variation"));
    }
    const amsph_analysis_axes same = {.scan = 2, .up = 2, .track_at = NAN, .surface = NAN};
    CHECK(amsph_analyze(dir, &same, csv) == AMSPH_BAD_INPUT, "scan and up on one axis are refused");
    for (int k = 0; k < 2; ++k)
        amsph_host_free(&s[k]);
}

/* Column `name` of OUTDIR/series.csv at row `row` (1 = the first data row). */
static double series_value(const char *dir, const char *name, int row)
{
    char path[512], line[8192];
    snprintf(path, sizeof path, "%s/series.csv", dir);
    FILE *f = fopen(path, "r");
    double v = NAN;
    if (!f || !fgets(line, sizeof line, f)) {
        if (f)
            fclose(f);
        return v;
    }
    int column = -1, k = 0;
    for (char *s = strtok(line, ",\n"); s; s = strtok(NULL, ",\n"), ++k)
        if (!strcmp(s, name))
            column = k;
    for (int r = 1; r <= row && fgets(line, sizeof line, f); ++r)
        if (r == row) {
            char *s = line;
            for (int c = 0; c < column && s; ++c)
                s = strchr(s, ',') ? strchr(s, ',') + 1 : NULL;
            v = s ? strtod(s, NULL) : NAN;
        }
    fclose(f);
    return v;
}

/* The recoil pool (cases/am/recoil_pool_2d.yaml) to 30 us: the analysis's
 * peak temperature and liquid mass at every snapshot are the series' (its
 * walls stay at 1500 K, below the solidus, so the sums agree); the pool has
 * formed and reaches below the substrate's surface, at most its thickness. */
static void test_real_run(void)
{
    amsph_case c;
    char dir[256], csv[512];
    if (testing_load_case("../am/recoil_pool_2d.yaml", &c) || testing_temp_dir(dir, sizeof dir, "analyze_run"))
        return;
    c.end_time = 3e-5;
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    const amsph_run_options run = {.outdir = dir, .quiet = 1, .force = 1};
    CHECK_OK(amsph_sim_create(&c, b, &s));
    CHECK_OK(amsph_sim_run(&s, &run));
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
    snprintf(csv, sizeof csv, "%s/melt_pool.csv", dir);
    const amsph_analysis_axes axes = {.scan = 0, .up = -1, .track_at = NAN, .surface = NAN};
    CHECK_OK(amsph_analyze(dir, &axes, csv));
    table t;
    CHECK(read_table(csv, &t) == 0 && t.rows == 7, "%s: %d rows (7 snapshots)", csv, t.rows);
    for (int r = 0; r < t.rows; ++r) {
        const double peak = series_value(dir, "max_temperature", r + 1), mass = series_value(dir, "liquid_mass", r + 1);
        CHECK(fabs(cell(&t, r, "peak_temperature") - peak) <= 1e-6 * peak &&
                  fabs(cell(&t, r, "liquid_mass") - mass) <= 1e-6 * fmax(mass, 1e-12),
              "snapshot %d: peak %.9g K, series %.9g; liquid mass %.9g, series %.9g", r,
              cell(&t, r, "peak_temperature"), peak, cell(&t, r, "liquid_mass"), mass);
    }
    const double depth = cell(&t, t.rows - 1, "penetration");
    fprintf(stderr, "recoil pool at 30 us: %g melt particles, length %.3g m, penetration %.3g m\n",
            cell(&t, t.rows - 1, "melt_particles"), cell(&t, t.rows - 1, "melt_length"), depth);
    CHECK(cell(&t, t.rows - 1, "melt_particles") > 0 && depth > 0 && depth <= 1e-4,
          "recoil pool: penetration %g m, within the 100 um slab", depth);
}

int main(void)
{
    test_synthetic_2d();
    test_synthetic_3d();
    test_real_run();
    return testing_finish();
}
