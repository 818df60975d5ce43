/* Snapshots, the XDMF index, the series and the run loop: a block thrown
 * under gravity (no other forces) runs through amsph_sim_run; every snapshot
 * follows the documented schema (datasets, shapes, units, root attributes),
 * lands on the output times, and the positions follow the ballistic
 * solution x = x0 + u0 t + g t^2 / 2, which kick-drift-kick leap-frog
 * integrates exactly for a constant acceleration (so only round-off
 * remains). The XDMF index lists every field of every snapshot at its time;
 * series.csv has the table's columns and one row per snapshot, with the
 * momentum and kinetic energy of the ballistic solution (and empty energy
 * ledger cells: the block has no thermal module). A heated slab's series
 * carries an energy ledger that closes. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <unistd.h>

#include "case.h"
#include "series.h"
#include "sim.h"
#include "testing.h"

static const char *text =
    "dimension: 3\n"
    "domain: {min: [-1, -1, -1], max: [1, 1, 1]}\n"
    "dx: 0.05\n"
    "end_time: 0.3\n"
    "output_interval: 0.1\n"
    "gravity: [0, 0, -9.81]\n"
    "materials:\n"
    "  - {name: steel, density: 7800, sound_speed: 10}\n"
    "geometry:\n"
    "  - {shape: box, kind: fluid, material: steel, min: [0, 0, 0], max: [0.2, 0.1, 0.1], velocity: [0.5, -0.25, 1.0], temperature: 300}\n";

static double read_double_attribute(hid_t file, const char *name)
{
    double v = NAN;
    hid_t a = H5Aopen(file, name, H5P_DEFAULT);
    if (a >= 0) {
        H5Aread(a, H5T_NATIVE_DOUBLE, &v);
        H5Aclose(a);
    }
    return v;
}

/* Reads dataset `name` as doubles; returns its element count (rows x cols). */
static int read_dataset(hid_t file, const char *name, double **out, int *rows, int *cols, char *unit)
{
    *out = NULL;
    hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
    if (set < 0)
        return 0;
    hid_t space = H5Dget_space(set);
    hsize_t dims[2] = {0, 1};
    const int rank = H5Sget_simple_extent_dims(space, dims, NULL);
    *rows = (int)dims[0];
    *cols = rank == 2 ? (int)dims[1] : 1;
    *out = malloc((size_t)*rows * (size_t)*cols * sizeof **out);
    H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, *out);
    hid_t attr = H5Aopen(set, "unit", H5P_DEFAULT);
    unit[0] = '\0';
    if (attr >= 0) {
        hid_t type = H5Aget_type(attr);
        H5Aread(attr, type, unit);
        H5Tclose(type);
        H5Aclose(attr);
    }
    H5Sclose(space);
    H5Dclose(set);
    return *rows * *cols;
}

static void check_snapshot(const char *dir, int k, const double *x0, const unsigned *id0, int n0)
{
    char path[512];
    snprintf(path, sizeof path, "%s/snap_%06d.h5", dir, k);
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK(file >= 0, "cannot open %s", path);
    if (file < 0)
        return;
    const double t = read_double_attribute(file, "time");
    CHECK(fabs(t - 0.1 * k) < 1e-12, "snapshot %d at t = %.17g, not %g", k, t, 0.1 * k);
    CHECK(read_double_attribute(file, "dx") == 0.05, "dx attribute");
    static const struct {
        const char *name, *unit;
        int cols;
    } schema[] = {{"position", "m", 3}, {"velocity", "m/s", 3}, {"density", "kg/m^3", 1},
                  {"pressure", "Pa", 1}, {"mass", "kg", 1},     {"kind", "1", 1},
                  {"material", "1", 1},  {"id", "1", 1},       {"temperature", "K", 1}};
    double *data[9] = {0};
    for (int s = 0; s < 9; ++s) {
        int rows = 0, cols = 0;
        char unit[64];
        const int count = read_dataset(file, schema[s].name, &data[s], &rows, &cols, unit);
        CHECK(count > 0 && rows == n0 && cols == schema[s].cols && !strcmp(unit, schema[s].unit),
              "snapshot %d: dataset %s is %d x %d [%s]", k, schema[s].name, rows, cols, unit);
    }
    if (data[0] && data[7]) {
        double worst = 0.0;
        for (int i = 0; i < n0; ++i) {
            int j = 0;
            while (j < n0 && id0[j] != (unsigned)data[7][i])
                ++j;
            const double u0[3] = {0.5, -0.25, 1.0}, g[3] = {0, 0, -9.81};
            for (int d = 0; d < 3 && j < n0; ++d)
                worst = fmax(worst, fabs(data[0][3 * i + d] - (x0[3 * j + d] + u0[d] * t + 0.5 * g[d] * t * t)));
        }
        CHECK(worst < (AMSPH_DOUBLE ? 1e-12 : 2e-6), "snapshot %d: ballistic error %g m", k, worst);
    }
    if (data[4])
        CHECK(fabs(data[4][0] - 7800 * 0.05 * 0.05 * 0.05) < 1e-6, "mass %g", data[4][0]);
    for (int s = 0; s < 9; ++s)
        free(data[s]);
    H5Fclose(file);
}

static const char *output_fields[] = {"velocity", "density", "pressure", "mass", "kind",
                                      "material", "id", "temperature"};
#define OUTPUT_FIELDS (int)(sizeof output_fields / sizeof output_fields[0])

static void check_xdmf(const char *dir, int snapshots, int n)
{
    char path[512], *xdmf = calloc(1, 1 << 20), item[128];
    snprintf(path, sizeof path, "%s/snapshots.xmf", dir);
    FILE *f = fopen(path, "r");
    CHECK(f != NULL, "no XDMF index");
    if (f) {
        xdmf[fread(xdmf, 1, (1 << 20) - 1, f)] = 0;
        fclose(f);
    }
    CHECK(strstr(xdmf, "CollectionType=\"Temporal\""), "not a temporal collection");
    for (int k = 0; k < snapshots; ++k) {
        snprintf(item, sizeof item, "<Time Value=\"%.17g\"/>", fmin(0.3, 0.1 * k)); /* the end time lands exactly */
        CHECK(strstr(xdmf, item), "XDMF: no %s", item);
        snprintf(item, sizeof item, "Dimensions=\"%d 3\" NumberType=\"Float\" Precision=\"%zu\" "
                                    "Format=\"HDF\">snap_%06d.h5:/position<", n, sizeof(amsph_real), k);
        CHECK(strstr(xdmf, item), "XDMF: no geometry %s", item);
        for (int d = 0; d < OUTPUT_FIELDS; ++d) {
            snprintf(item, sizeof item, "snap_%06d.h5:/%s<", k, output_fields[d]);
            CHECK(strstr(xdmf, item), "XDMF: snapshot %d lacks %s", k, output_fields[d]);
        }
    }
    free(xdmf);
}

/* Splits a CSV line in place; returns the number of cells. */
static int split(char *line, char **cells, int max)
{
    int count = 0;
    line[strcspn(line, "\n")] = '\0';
    for (char *p = line; count < max; ++p) {
        cells[count++] = p;
        p = strchr(p, ',');
        if (!p)
            break;
        *p = '\0';
    }
    return count;
}

static int column(const char *name)
{
    for (int c = 0; c < amsph_series_column_count; ++c)
        if (!strcmp(amsph_series_columns[c].name, name))
            return c;
    CHECK(0, "no series column %s", name);
    return 0;
}

static int close_to(const char *cell, double expected)
{
    return fabs(atof(cell) - expected) <= 1e-5 * fmax(1.0, fabs(expected));
}

static void check_series(const char *dir, int snapshots, int n)
{
    char path[512], line[4096], *cells[64];
    snprintf(path, sizeof path, "%s/series.csv", dir);
    FILE *f = fopen(path, "r");
    CHECK(f && fgets(line, sizeof line, f), "no series.csv");
    const int columns = f ? split(line, cells, 64) : 0;
    CHECK(columns == amsph_series_column_count, "%d columns in the header", columns);
    for (int c = 0; c < columns && c < amsph_series_column_count; ++c)
        CHECK(!strcmp(cells[c], amsph_series_columns[c].name), "column %d is %s", c, cells[c]);
    const double M = n * 7800 * 0.05 * 0.05 * 0.05;
    int rows = 0;
    while (f && fgets(line, sizeof line, f)) {
        CHECK(split(line, cells, 64) == amsph_series_column_count, "row %d: cells", rows);
        const double t = 0.1 * rows, w = 1.0 - 9.81 * t;
        CHECK(close_to(cells[column("time")], t) && close_to(cells[column("fluid_particles")], n) &&
                  close_to(cells[column("total_mass")], M) && close_to(cells[column("max_temperature")], 300),
              "row %d: time, particles, mass or temperature", rows);
        CHECK(close_to(cells[column("momentum_x")], 0.5 * M) && close_to(cells[column("momentum_y")], -0.25 * M) &&
                  close_to(cells[column("momentum_z")], w * M) &&
                  close_to(cells[column("kinetic_energy")], 0.5 * M * (0.25 + 0.0625 + w * w)),
              "row %d: momentum or kinetic energy off the ballistic solution", rows);
        CHECK(cells[column("liquid_mass")][0] == '\0', "row %d: liquid_mass without phase change", rows);
        CHECK(cells[column("enthalpy")][0] == '\0' && cells[column("ledger_error")][0] == '\0' &&
                  cells[column("thermal_iterations")][0] == '\0',
              "row %d: energy ledger cells without the thermal module", rows);
        ++rows;
    }
    CHECK(rows == snapshots, "%d rows for %d snapshots", rows, snapshots);
    if (f)
        fclose(f);
}

/* A 2D steel slab at 400 K on a wall held at 300 K, under the beam of
 * laser_slab_2d.yaml for 1 ms, radiating (emissivity 0.5) and melting
 * under the beam, cooling to 1.5 ms; enthalpy by implicit midpoint. */
static const char *heated_slab =
    "dimension: 2\n"
    "domain: {min: [-1.0e-4, -2.0e-4], max: [1.1e-3, 6.0e-4]}\n"
    "dx: 2.5e-5\n"
    "end_time: 1.5e-3\n"
    "output_interval: 2.5e-4\n"
    "thermal: {integration: midpoint, radiation: true, ambient_temperature: 300}\n"
    "materials:\n"
    "  - {name: steel, density: 8000, specific_heat: 500, conductivity: 20, melting_temperature: 1700,\n"
    "     melting_range: 100, latent_heat: 2.7e5, emissivity: 0.5}\n"
    "geometry:\n"
    "  - {shape: box, kind: solid, material: steel, min: [0, 0], max: [1.0e-3, 5.0e-4], temperature: 400}\n"
    "  - {shape: box, kind: wall, material: steel, min: [0, -7.5e-5], max: [1.0e-3, 0], temperature: 300}\n"
    "laser: {power: 100, radius: 1.0e-4, absorption_coefficient: 2000, start: [5.0e-4, 5.0e-4], "
    "off_time: 1.0e-3}\n";

/* The series' columns by name, one row in cells (parsed as numbers). */
static double cell(char **cells, const char *name)
{
    return atof(cells[column(name)]);
}

/* Every row of the heated slab's series: the enthalpy change since the
 * first row equals laser - radiated + wall + viscous to 1e-5 of the gross
 * exchange, and ledger_error says so. The exchanges are booked as the
 * update applies them, so only the rounding of the float enthalpies
 * remains: about 1e-7 of the slab's 800 J/m, 2e-7 of the exchange (issue
 * 4 asks for 0.5%; radiation booked with the wrong sign would miss by
 * 7e-5). The laser energy is the absorbed power of the slice, P sqrt(2/pi)
 * / r_l (1 - exp(-alpha L)) (laser_slab_2d.yaml), times the time the beam
 * was on (to 0.1%); the slab radiates, the colder wall takes heat, and by
 * 1 ms part of it has melted (so latent heat is in the ledger). */
static void test_series_ledger(void)
{
    char dir[256], path[600], line[4096], *cells[64];
    testing_temp_dir(dir, sizeof dir, "output_ledger");
    amsph_case c;
    char err[512];
    CHECK(amsph_case_parse(heated_slab, strlen(heated_slab), "slab.yaml", &c, err, sizeof err) == 0, "%s", err);
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    const amsph_run_options run = {.outdir = dir, .quiet = 1};
    CHECK_OK(amsph_sim_create(&c, b, &s));
    CHECK_OK(amsph_sim_run(&s, &run));
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
    const double absorbed = 100.0 * sqrt(2.0 / PI) / 1e-4 * (1.0 - exp(-2000.0 * 5e-4)); /* W/m */
    snprintf(path, sizeof path, "%s/series.csv", dir);
    FILE *f = fopen(path, "r");
    CHECK(f && fgets(line, sizeof line, f), "no series.csv in %s", dir);
    double initial = NAN;
    int rows = 0;
    while (f && fgets(line, sizeof line, f) && split(line, cells, 64) == amsph_series_column_count) {
        const double t = cell(cells, "time"), change = cell(cells, "enthalpy") - initial;
        const double laser = cell(cells, "laser_energy"), radiated = cell(cells, "radiated_energy");
        const double wall = cell(cells, "wall_heat"), viscous = cell(cells, "viscous_heat");
        const double gross = fabs(laser) + fabs(radiated) + fabs(wall) + fabs(viscous);
        const double error = fabs(change - (laser - radiated + wall + viscous)) / fmax(gross, fabs(change));
        const int iterations = (int)cell(cells, "thermal_iterations");
        if (rows++ == 0) {
            initial = cell(cells, "enthalpy");
            CHECK(initial > 0.0 && gross == 0.0 && iterations == 0,
                  "first row: enthalpy %g J/m, exchanges %g J/m, %d iterations", initial, gross, iterations);
            continue;
        }
        fprintf(stderr, "t = %.2e s: enthalpy %+.6g J/m, laser %.6g, radiated %.4g, wall %.4g; error %.2e\n", t,
                change, laser, radiated, wall, error);
        CHECK(error < 1e-5 && fabs(cell(cells, "ledger_error") - error) < 1e-6,
              "t = %g s: enthalpy change %.8g J/m, exchanges %.8g J/m (error %.3g, ledger_error %s)", t, change,
              laser - radiated + wall + viscous, error, cells[column("ledger_error")]);
        CHECK(fabs(laser - absorbed * fmin(t, 1e-3)) < 1e-3 * absorbed * fmin(t, 1e-3),
              "t = %g s: laser energy %.6g J/m, absorbed power x time on %.6g J/m", t, laser,
              absorbed * fmin(t, 1e-3));
        CHECK(radiated > 0.0 && wall < 0.0 && viscous == 0.0,
              "t = %g s: radiated %g J/m (> 0), wall %g J/m (< 0: the 300 K wall cools the slab), viscous %g",
              t, radiated, wall, viscous);
        CHECK(iterations >= 2 && iterations < c.thermal.max_iterations, "t = %g s: %d midpoint iterations", t,
              iterations);
        CHECK(t < 1e-3 || cell(cells, "liquid_mass") > 0.0, "t = %g s: nothing melted", t);
    }
    CHECK(rows == 7, "%d rows in %s, expected 7 (0 to 1.5 ms every 0.25 ms)", rows, path);
    if (f)
        fclose(f);
}

int main(void)
{
    char dir[256];
    testing_temp_dir(dir, sizeof dir, "output");
    amsph_case c;
    char err[512];
    CHECK(amsph_case_parse(text, strlen(text), "output.yaml", &c, err, sizeof err) == 0, "%s", err);
    amsph_backend *b = testing_backend(0);
    amsph_sim s;
    CHECK_OK(amsph_sim_create(&c, b, &s));
    amsph_host_particles initial;
    CHECK_OK(amsph_particles_download(&s.particles, &initial));
    const int n0 = initial.n;
    double *x0 = malloc((size_t)n0 * 3 * sizeof *x0);
    for (int i = 0; i < 3 * n0; ++i)
        x0[i] = amsph_host_real(&initial, AMSPH_FIELD_POSITION)[i];
    const amsph_run_options run = {.outdir = dir, .quiet = 1};
    CHECK_OK(amsph_sim_run(&s, &run));
    CHECK(n0 == 4 * 2 * 2, "%d particles in a 0.2 x 0.1 x 0.1 box at dx 0.05", n0);
    for (int k = 0; k <= 3; ++k)
        check_snapshot(dir, k, x0, initial.data[AMSPH_FIELD_ID], n0);
    char path[512];
    snprintf(path, sizeof path, "%s/snap_000004.h5", dir);
    CHECK(access(path, F_OK) != 0, "a fifth snapshot exists: output past the end time");
    check_xdmf(dir, 4, n0);
    check_series(dir, 4, n0);
    test_series_ledger();
    free(x0);
    amsph_host_free(&initial);
    amsph_sim_free(&s);
    amsph_backend_destroy(b);
    return testing_finish();
}
