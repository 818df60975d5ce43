/* Checkpoints and restarts. A run stopped at step 100 (--max-steps) and
 * restarted to step 200 ends bit for bit where a run straight to step 200
 * ends, field by field in the final snapshot and in every field and scalar
 * of the checkpoint, with the same series rows, on every backend, restarted
 * in the checkpoint's directory and in another: for the dam break, for a
 * melting slab under a laser (thermal, laser and fluid modules) and for the
 * dam break pushing a mobile grain (the grain records are checkpointed; a
 * restart that recovered them from the particles instead differs in the
 * last bits), and for a dam break in a gas whose density is summed. A bad
 * restart file (missing, not a checkpoint, truncated, corrupt, other
 * version, other dimension, other case, other field set, other precision)
 * is refused as bad input with a message saying which. A write that fails
 * for lack of space fails the run with a message and leaves the last
 * checkpoint intact. A stop request writes a checkpoint and a final
 * snapshot; checkpoints also come every checkpoint_interval of wall time. */
#include <hdf5.h>
#include <inttypes.h>
#include <signal.h>
#include <stdio.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "case.h"
#include "checkpoint.h"
#include "hash.h"
#include "series.h"
#include "sim.h"
#include "testing.h"

/* The 2D dam break at a coarse resolution (about 350 particles), with
 * temperatures so that every optional field is there, and `fluid_extra`
 * keys of the fluid module; output times fall between steps 100 and 200. */
#define DAMBREAK_WITH(fluid_extra)                                                                 \
    "domain: {min: [-0.05, -0.05], max: [0.634, 0.45]}\n"                                          \
    "dx: 0.0146\n"                                                                                 \
    "output_interval: 0.005\n"                                                                     \
    "gravity: [0.0, -9.81]\n"                                                                      \
    "fluid: {viscosity: artificial, artificial_alpha: 0.1, tensile_correction: 0.1" fluid_extra "}\n" \
    "materials:\n"                                                                                 \
    "  - {name: water, density: 1000, viscosity: 1.0e-3, sound_speed: 25}\n"                       \
    "geometry:\n"                                                                                  \
    "  - {shape: box, kind: wall, material: water, min: [0, 0], max: [0.584, 0.38], layers: 3, "   \
    "open: [+y], temperature: 300}\n"                                                                              \
    "  - {shape: box, kind: fluid, material: water, min: [0, 0], max: [0.146, 0.292], "            \
    "hydrostatic: true, temperature: 300}\n"

#define DAMBREAK_HEAD DAMBREAK_WITH("")

static const char *dambreak = "dimension: 2\nend_time: 0.4\n" DAMBREAK_HEAD;
/* The same with the smoothing length that follows the volume (its field in the checkpoint). */
static const char *volume_h_dambreak = "dimension: 2\nend_time: 0.4\n" DAMBREAK_WITH(", smoothing_length: volume");
/* The same with the Verlet scheme: the state a step before (its fields) and
 * the last step's length carry over; step 100 falls between Euler steps. */
static const char *verlet_dambreak =
    "dimension: 2\nend_time: 0.4\n" DAMBREAK_WITH(", integration: verlet, pressure_gradient: symmetric");
static const char *dambreak_longer = "dimension: 2\nend_time: 0.5\n" DAMBREAK_HEAD;
/* A 2D steel slab on a cold wall under a 1 kW beam (laser_slab_2d.yaml's
 * geometry), radiating, by implicit midpoint: it melts from step 70 on, and
 * the melt flows (the phase rule turns solids into fluid); output times
 * fall between steps 100 and 200. */
static const char *melting_slab =
    "dimension: 2\n"
    "domain: {min: [-1.0e-4, -2.0e-4], max: [1.1e-3, 8.0e-4]}\n"
    "dx: 2.5e-5\n"
    "end_time: 1.0e-3\n"
    "output_interval: 2.0e-5\n"
    "gravity: [0, -9.81]\n"
    "fluid: {}\n"
    "thermal: {integration: midpoint, radiation: true}\n"
    "materials:\n"
    "  - {name: steel, density: 8000, viscosity: 0.01, mushy_viscosity: 1, sound_speed: 10, specific_heat: 500,\n"
    "     conductivity: 20, melting_temperature: 1700, melting_range: 100, latent_heat: 2.7e5, emissivity: 0.5}\n"
    "geometry:\n"
    "  - {shape: box, kind: solid, material: steel, min: [0, 0], max: [1.0e-3, 5.0e-4], temperature: 400}\n"
    "  - {shape: box, kind: wall, material: steel, min: [0, -7.5e-5], max: [1.0e-3, 0], temperature: 300}\n"
    "laser: {power: 1000, radius: 1.0e-4, absorption_coefficient: 2000, start: [5.0e-4, 5.0e-4], "
    "off_time: 1.0e-3}\n";
/* The dam break's wave meets a grain (of water's density) resting on the floor, which it
 * pushes and turns (the grains module: grain records beside the particles). */
static const char *grain_dambreak =
    "dimension: 2\nend_time: 0.4\n" DAMBREAK_HEAD
    "  - {shape: box, kind: grain, material: water, min: [0.3066, 0], max: [0.365, 0.0438], temperature: 300}\n"
    "grains: {contact_stiffness: 1.0e4, contact_damping: 1.0}\n";
/* A dam break in a closed tank of gas (density ratio 100) whose density is
 * summed over its neighbours: the lattice's kernel sum that the summation
 * divides by is worked out at the start (amsph_fluid_start), in a restart too
 * (before 2026-12-05 it was 0 there, and the gas's density went to NaN at the
 * restart's first step). */
static const char *gas_dambreak =
    "dimension: 2\nend_time: 0.4\n"
    "domain: {min: [-0.05, -0.05], max: [0.634, 0.45]}\n"
    "dx: 0.0146\n"
    "output_interval: 0.005\n"
    "gravity: [0.0, -9.81]\n"
    "fluid: {viscosity: artificial, artificial_alpha: 0.1, pressure_gradient: multiphase, gas_density: summation}\n"
    "materials:\n"
    "  - {name: water, density: 1000, viscosity: 1.0e-3, sound_speed: 25}\n"
    "  - {name: air, phase: gas, density: 10, viscosity: 1.0e-4, sound_speed: 50}\n"
    "geometry:\n"
    "  - {shape: box, kind: wall, material: water, min: [0, 0], max: [0.584, 0.38], layers: 3}\n"
    "  - {shape: box, kind: fluid, material: water, min: [0, 0], max: [0.146, 0.292], hydrostatic: true}\n"
    "  - {shape: box, kind: fluid, material: air, min: [0, 0], max: [0.584, 0.38], fill: true}\n";
static const char *cube_3d =
    "dimension: 3\n"
    "domain: {min: [0, 0, 0], max: [1, 1, 1]}\n"
    "dx: 0.1\n"
    "end_time: 1\n"
    "output_interval: 0.5\n"
    "materials:\n"
    "  - {name: water, density: 1000}\n"
    "geometry:\n"
    "  - {shape: box, kind: fluid, material: water, min: [0.2, 0.2, 0.2], max: [0.5, 0.5, 0.5]}\n";

static void parse(const char *text, amsph_case *c)
{
    char err[512];
    CHECK(amsph_case_parse(text, strlen(text), "restart.yaml", c, err, sizeof err) == 0, "%s", err);
}

static void join(char *out, size_t size, const char *dir, const char *name)
{
    snprintf(out, size, "%s/%s", dir, name);
}

/* Runs the case into dir up to max_steps, from the start or from the
 * checkpoint `restart`. */
static int run_case(amsph_backend *b, const amsph_case *c, const char *dir, long long max_steps,
                    const char *restart, const volatile sig_atomic_t *stop)
{
    amsph_checkpoint ck = {0};
    amsph_sim s = {0};
    int status = 0;
    if (restart) {
        status = amsph_checkpoint_read(restart, &ck);
        if (!status)
            status = amsph_checkpoint_check_case(&ck, restart, c);
        if (!status)
            status = amsph_sim_restore(c, b, &ck.state, &s);
    } else {
        status = amsph_sim_create(c, b, &s);
    }
    const amsph_run_options options = {.outdir = dir,
                                       .quiet = 1,
                                       .max_steps = max_steps,
                                       .stop = stop,
                                       .resume = restart ? &ck.run : NULL,
                                       .resume_path = restart};
    if (!status)
        status = amsph_sim_run(&s, &options);
    amsph_sim_free(&s);
    amsph_checkpoint_free(&ck);
    return status;
}

static long long saved_scalar(const amsph_checkpoint *ck, const char *name)
{
    for (int k = 0; k < AMSPH_SIM_SCALAR_COUNT; ++k)
        if (!strcmp(amsph_sim_scalars[k].name, name))
            return ck->state.scalar[k].integer;
    CHECK(0, "no sim scalar named %s", name);
    return -1;
}

/* The checkpoint in dir; ck is freed by the caller. */
static int read_checkpoint(const char *dir, amsph_checkpoint *ck)
{
    char path[600];
    join(path, sizeof path, dir, "checkpoint.h5");
    const int status = amsph_checkpoint_read(path, ck);
    CHECK(status == 0, "%s", amsph_last_error());
    return status;
}

static int same_fields(const amsph_host_particles *a, const amsph_host_particles *b, const char *what)
{
    int same = a->n == b->n;
    for (int f = 0; f < AMSPH_FIELD_COUNT && same; ++f) {
        const size_t bytes = (size_t)a->n * amsph_field_bytes((amsph_field_id)f);
        same = !a->data[f] == !b->data[f] && (!a->data[f] || !memcmp(a->data[f], b->data[f], bytes));
        CHECK(same, "%s: field %s differs", what, amsph_fields[f].name);
    }
    return same;
}

/* The checkpoints in the two directories hold the same bits. */
static void check_same_checkpoint(const char *dir_a, const char *dir_b)
{
    amsph_checkpoint a = {0}, b = {0};
    if (!read_checkpoint(dir_a, &a) && !read_checkpoint(dir_b, &b)) {
        CHECK(same_fields(&a.state.particles, &b.state.particles, dir_b), "particles differ from %s", dir_a);
        CHECK(same_fields(&a.state.last_good, &b.state.last_good, dir_b), "last good differs from %s", dir_a);
        CHECK(!memcmp(a.state.scalar, b.state.scalar, sizeof a.state.scalar), "%s: scalars differ", dir_b);
        CHECK(saved_scalar(&b, "step") == 200, "%s: checkpoint at step %lld", dir_b, saved_scalar(&b, "step"));
    }
    amsph_checkpoint_free(&a);
    amsph_checkpoint_free(&b);
}

/* The bytes of dataset `name` of an HDF5 file, in its stored type. */
static char *dataset_bytes(hid_t file, const char *name, size_t *size)
{
    hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
    if (set < 0)
        return NULL;
    hid_t type = H5Dget_type(set), space = H5Dget_space(set);
    *size = (size_t)H5Sget_simple_extent_npoints(space) * H5Tget_size(type);
    char *data = malloc(*size ? *size : 1);
    H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Sclose(space);
    H5Tclose(type);
    H5Dclose(set);
    return data;
}

/* The last snapshots of two directories agree field by field. */
static void check_same_final_snapshot(const char *dir_a, int last_a, const char *dir_b, int last_b)
{
    char path_a[600], path_b[600], name[32];
    snprintf(name, sizeof name, "snap_%06d.h5", last_a);
    join(path_a, sizeof path_a, dir_a, name);
    snprintf(name, sizeof name, "snap_%06d.h5", last_b);
    join(path_b, sizeof path_b, dir_b, name);
    hid_t a = H5Fopen(path_a, H5F_ACC_RDONLY, H5P_DEFAULT), b = H5Fopen(path_b, H5F_ACC_RDONLY, H5P_DEFAULT);
    CHECK(a >= 0 && b >= 0, "cannot open %s or %s", path_a, path_b);
    for (int f = 0; f < AMSPH_FIELD_COUNT && a >= 0 && b >= 0; ++f) {
        if (!(amsph_fields[f].flags & AMSPH_FIELD_OUTPUT))
            continue;
        size_t size_a = 0, size_b = 0;
        char *x = dataset_bytes(a, amsph_fields[f].name, &size_a);
        char *y = dataset_bytes(b, amsph_fields[f].name, &size_b);
        CHECK(!x == !y && (!x || (size_a == size_b && !memcmp(x, y, size_a))), "%s: field %s differs from %s",
              path_b, amsph_fields[f].name, path_a);
        free(x);
        free(y);
    }
    if (a >= 0)
        H5Fclose(a);
    if (b >= 0)
        H5Fclose(b);
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

/* Whether column c of series.csv depends on the wall clock. */
static int wall_clock_column(int c)
{
    return !strcmp(amsph_series_columns[c].name, "wall_seconds") ||
           !strcmp(amsph_series_columns[c].name, "particle_steps_per_second");
}

/* Every row of dir_a's series.csv is in dir_b's, cell for cell but the wall
 * clock's; dir_b has `extra` more rows. */
static void check_same_series(const char *dir_a, const char *dir_b, int extra)
{
    char path_a[600], path_b[600], row_a[4096], row_b[4096], *a[64], *b[64];
    join(path_a, sizeof path_a, dir_a, "series.csv");
    join(path_b, sizeof path_b, dir_b, "series.csv");
    FILE *fa = fopen(path_a, "r"), *fb = fopen(path_b, "r");
    CHECK(fa && fb, "cannot open %s or %s", path_a, path_b);
    int rows_a = 0, rows_b = 0;
    while (fa && fb && fgets(row_a, sizeof row_a, fa)) {
        const int cells = split(row_a, a, 64);
        int same = 0;
        while (!same && fgets(row_b, sizeof row_b, fb)) {
            ++rows_b;
            same = split(row_b, b, 64) == cells && !strcmp(a[0], b[0]);
        }
        for (int c = 0; same && c < cells; ++c)
            CHECK(wall_clock_column(c) || !strcmp(a[c], b[c]), "%s, step %s: %s is %s, straight %s", path_b, a[0],
                  c < amsph_series_column_count ? amsph_series_columns[c].name : "?", b[c], a[c]);
        CHECK(same, "%s lacks the row of step %s", path_b, a[0]);
        ++rows_a;
    }
    while (fb && fgets(row_b, sizeof row_b, fb))
        ++rows_b;
    CHECK(rows_b == rows_a + extra, "%s has %d lines, %s %d (expected %d more)", path_b, rows_b, path_a, rows_a,
          extra);
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
}

static int count_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "r");
    int count = 0;
    char line[4096];
    while (f && fgets(line, sizeof line, f))
        count += strstr(line, text) != NULL;
    if (f)
        fclose(f);
    return count;
}

/* The case `text` run straight to step 200, and stopped at step 100 and
 * restarted to 200 in the checkpoint's directory and in another, on
 * backend k. */
static void test_bit_identical(int k, const char *text, const char *tag)
{
    amsph_backend *b = testing_backend(k);
    if (!b)
        return;
    amsph_case c;
    parse(text, &c);
    char straight[128], stopped[128], elsewhere[128], from[600], label[64];
    snprintf(label, sizeof label, "restart_%s_straight", tag);
    testing_temp_dir(straight, sizeof straight, label);
    snprintf(label, sizeof label, "restart_%s_stopped", tag);
    testing_temp_dir(stopped, sizeof stopped, label);
    snprintf(label, sizeof label, "restart_%s_elsewhere", tag);
    testing_temp_dir(elsewhere, sizeof elsewhere, label);
    join(from, sizeof from, stopped, "checkpoint.h5");
    CHECK_OK(run_case(b, &c, straight, 200, NULL, NULL));
    CHECK_OK(run_case(b, &c, stopped, 100, NULL, NULL));
    amsph_checkpoint half = {0};
    if (!read_checkpoint(stopped, &half)) {
        const amsph_host_particles *h = &half.state.particles;
        int fluid = 0;
        for (int i = 0; i < h->n; ++i)
            fluid += ((const int *)h->data[AMSPH_FIELD_KIND])[i] == AMSPH_KIND_FLUID;
        CHECK(saved_scalar(&half, "step") == 100 && fluid > 0, "%s: stopped at step %lld with %d fluid particles",
              tag, saved_scalar(&half, "step"), fluid);
    }
    const int before = half.run.snapshots.count;
    amsph_checkpoint_free(&half);
    CHECK_OK(run_case(b, &c, elsewhere, 200, from, NULL));
    CHECK_OK(run_case(b, &c, stopped, 200, from, NULL));
    check_same_checkpoint(straight, elsewhere);
    check_same_checkpoint(straight, stopped);
    check_same_series(straight, stopped, 1); /* the stop's row */

    amsph_checkpoint a = {0}, d = {0};
    if (!read_checkpoint(straight, &a) && !read_checkpoint(stopped, &d)) {
        const int last_a = a.run.snapshots.count - 1, last_d = d.run.snapshots.count - 1;
        check_same_final_snapshot(straight, last_a, elsewhere, last_d);
        check_same_final_snapshot(straight, last_a, stopped, last_d);
        CHECK(last_d == last_a + 1, "%d snapshots after the restart, %d straight (one more: the stop)",
              last_d + 1, last_a + 1);
        char path[600];
        join(path, sizeof path, stopped, "snapshots.xmf");
        CHECK(count_text(path, "<Grid Name=\"snap_") == last_d + 1, "in place: the index lists %d of %d",
              count_text(path, "<Grid Name=\"snap_"), last_d + 1);
        join(path, sizeof path, elsewhere, "snapshots.xmf");
        CHECK(count_text(path, "<Grid Name=\"snap_") == last_d + 1 - before,
              "elsewhere: the index lists %d snapshots, not the %d written there",
              count_text(path, "<Grid Name=\"snap_"), last_d + 1 - before);
        join(path, sizeof path, stopped, "series.csv");
        CHECK(count_text(path, ",") == last_d + 2, "in place: series.csv has %d lines for %d snapshots",
              count_text(path, ","), last_d + 1);
    }
    amsph_checkpoint_free(&a);
    amsph_checkpoint_free(&d);
    amsph_backend_destroy(b);
}

/* Writes src to dst, cut to `keep` bytes (< 0: all) and with the byte at
 * `flip` (< 0: none) inverted, or `patch` written at offset `at`. */
static void copy_altered(const char *src, const char *dst, long keep, long flip, long at, const char *patch)
{
    FILE *in = fopen(src, "rb");
    static char bytes[1 << 22];
    const size_t n = in ? fread(bytes, 1, sizeof bytes, in) : 0;
    if (in)
        fclose(in);
    CHECK(n > 0 && n < sizeof bytes, "cannot read %s", src);
    if (flip >= 0)
        bytes[flip] = (char)~bytes[flip];
    if (patch)
        memcpy(bytes + at, patch, strlen(patch));
    FILE *out = fopen(dst, "wb");
    CHECK(out != NULL, "cannot write %s", dst);
    if (out) {
        fwrite(bytes, 1, keep >= 0 ? (size_t)keep : n, out);
        fclose(out);
    }
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) ? -1 : (long)st.st_size;
}

/* What restoring the case's sim from the checkpoint at path returns. */
static int restore_status(amsph_backend *b, const char *path, const char *text)
{
    amsph_case c;
    parse(text, &c);
    amsph_checkpoint ck = {0};
    amsph_sim s = {0};
    int status = amsph_checkpoint_read(path, &ck);
    if (!status)
        status = amsph_checkpoint_check_case(&ck, path, &c);
    if (!status)
        status = amsph_sim_restore(&c, b, &ck.state, &s);
    amsph_sim_free(&s);
    amsph_checkpoint_free(&ck);
    return status;
}

static void expect_refusal(amsph_backend *b, const char *path, const char *text, const char *words)
{
    const int status = restore_status(b, path, text);
    CHECK(status == AMSPH_BAD_INPUT && strstr(amsph_last_error(), words),
          "expected a refusal saying '%s', got status %d: %s", words, status, amsph_last_error());
}

/* The checkpoint of `good` without the field `shepard`, written to path. */
static void write_without_shepard(const char *good, const char *path)
{
    amsph_checkpoint ck = {0};
    CHECK_OK(amsph_checkpoint_read(good, &ck));
    free(ck.state.particles.data[AMSPH_FIELD_SHEPARD]);
    ck.state.particles.data[AMSPH_FIELD_SHEPARD] = NULL;
    CHECK_OK(amsph_checkpoint_write(path, &ck));
    amsph_checkpoint_free(&ck);
}

/* The checkpoint of `good` as a build of the other precision (AMSPH_DOUBLE)
 * would label it, written to path: its HDF5 part with the root attribute
 * real_bytes changed to the other size, sealed with a fresh trailer (the
 * layout of checkpoint.h), so that only the precision is wrong. */
static void write_other_precision(const char *good, const char *path)
{
    const long hdf5_bytes = file_size(good) - 64;
    copy_altered(good, path, hdf5_bytes, -1, 0, NULL);
    const int other = sizeof(amsph_real) == 4 ? 8 : 4;
    hid_t file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t attr = file < 0 ? -1 : H5Aopen(file, "real_bytes", H5P_DEFAULT);
    CHECK(attr >= 0 && H5Awrite(attr, H5T_NATIVE_INT, &other) >= 0, "cannot relabel %s", path);
    if (attr >= 0)
        H5Aclose(attr);
    if (file >= 0)
        H5Fclose(file);
    static unsigned char bytes[1 << 22];
    FILE *f = fopen(path, "r+b");
    const size_t n = f ? fread(bytes, 1, sizeof bytes, f) : 0;
    char trailer[64] = {0};
    snprintf(trailer, sizeof trailer, "amsph checkpoint %d %zu %016" PRIx64 "\n", AMSPH_CHECKPOINT_VERSION, n,
             amsph_hash(AMSPH_HASH_START, bytes, n));
    CHECK(f && n > 0 && fwrite(trailer, 1, sizeof trailer, f) == sizeof trailer, "cannot seal %s", path);
    if (f)
        fclose(f);
}

static void test_refusals(amsph_backend *b, const char *dir)
{
    char good[600], bad[600], snapshot[600];
    join(good, sizeof good, dir, "checkpoint.h5");
    join(bad, sizeof bad, dir, "bad.h5");
    join(snapshot, sizeof snapshot, dir, "snap_000000.h5");
    const long size = file_size(good);
    CHECK(restore_status(b, good, dambreak) == 0, "the good checkpoint was refused: %s", amsph_last_error());
    expect_refusal(b, "/nonexistent/checkpoint.h5", dambreak, "cannot open");
    expect_refusal(b, snapshot, dambreak, "not an amsph checkpoint");
    copy_altered(good, bad, size - 1000, -1, 0, NULL);
    expect_refusal(b, bad, dambreak, "truncated");
    copy_altered(good, bad, -1, size / 2, 0, NULL);
    expect_refusal(b, bad, dambreak, "corrupt");
    copy_altered(good, bad, -1, -1, size - 64 + (long)strlen("amsph checkpoint "), "7");
    expect_refusal(b, bad, dambreak, "format version 7");
    expect_refusal(b, good, cube_3d, "is a 2D checkpoint; the case restart.yaml is 3D");
    expect_refusal(b, good, dambreak_longer, "written for another case");
    write_without_shepard(good, bad);
    expect_refusal(b, bad, dambreak, "lacks field 'shepard'");
    write_other_precision(good, bad);
    expect_refusal(b, bad, dambreak, sizeof(amsph_real) == 4 ? "written by a build with 8-byte reals; this build "
                                                               "has 4-byte reals (AMSPH_DOUBLE=OFF)"
                                                             : "written by a build with 4-byte reals; this build "
                                                               "has 8-byte reals (AMSPH_DOUBLE=ON)");
}

/* Sets the soft limit on the size of files this process writes. */
static void limit_file_size(rlim_t bytes)
{
    struct rlimit limit;
    getrlimit(RLIMIT_FSIZE, &limit);
    limit.rlim_cur = bytes;
    CHECK(setrlimit(RLIMIT_FSIZE, &limit) == 0, "setrlimit");
}

static int same_file(const char *a, const char *b)
{
    FILE *x = fopen(a, "rb"), *y = fopen(b, "rb");
    int same = x && y;
    while (same) {
        const int cx = fgetc(x), cy = fgetc(y);
        same = cx == cy;
        if (cx == EOF)
            break;
    }
    if (x)
        fclose(x);
    if (y)
        fclose(y);
    return same;
}

/* A full disk (a file size limit here): the write fails with a message, the
 * run stops, and the last checkpoint is the one that was there. */
static void test_full_disk(amsph_backend *b, const char *dir)
{
    amsph_case c;
    parse(dambreak, &c);
    char path[600], copy[600], tmp[610];
    join(path, sizeof path, dir, "checkpoint.h5");
    join(copy, sizeof copy, dir, "copy.h5");
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    copy_altered(path, copy, -1, -1, 0, NULL);
    amsph_checkpoint ck = {0};
    CHECK_OK(amsph_checkpoint_read(path, &ck));
    signal(SIGXFSZ, SIG_IGN);
    limit_file_size(4096);
    const int status = amsph_checkpoint_write(path, &ck);
    char message[1024];
    snprintf(message, sizeof message, "%s", amsph_last_error());
    const int run_status = run_case(b, &c, dir, 200, path, NULL);
    limit_file_size(RLIM_INFINITY);
    CHECK(status == AMSPH_FAILED && strstr(message, "cannot write") && strstr(message, "checkpoint.h5") &&
              strstr(message, "File too large"),
          "a checkpoint write past the limit: status %d, message '%s'", status, message);
    CHECK(run_status == AMSPH_FAILED && strstr(amsph_last_error(), "cannot write") && strstr(amsph_last_error(), dir),
          "a run that cannot write: status %d, message '%s'", run_status, amsph_last_error());
    CHECK(same_file(path, copy), "the last checkpoint changed");
    CHECK(access(tmp, F_OK) != 0, "%s left behind", tmp);
    amsph_checkpoint_free(&ck);
}

/* A stop request (what SIGINT and SIGTERM set) before the first step: a
 * final snapshot and a checkpoint at step 0. */
static void test_stop_request(amsph_backend *b)
{
    amsph_case c;
    parse(dambreak, &c);
    char dir[128];
    testing_temp_dir(dir, sizeof dir, "restart_stop");
    static volatile sig_atomic_t stop = SIGTERM;
    CHECK_OK(run_case(b, &c, dir, 0, NULL, &stop));
    amsph_checkpoint ck = {0};
    if (!read_checkpoint(dir, &ck))
        CHECK(saved_scalar(&ck, "step") == 0 && ck.run.snapshots.count == 1,
              "stopped at step %lld with %d snapshots", saved_scalar(&ck, "step"), ck.run.snapshots.count);
    amsph_checkpoint_free(&ck);
}

/* A checkpoint every (tiny) interval of wall time, without a stop. */
static void test_periodic_checkpoint(amsph_backend *b)
{
    amsph_case c;
    parse(cube_3d, &c);
    char dir[128];
    testing_temp_dir(dir, sizeof dir, "restart_periodic");
    amsph_sim s;
    const amsph_run_options options = {.outdir = dir, .quiet = 1, .checkpoint_interval = 1e-9};
    CHECK_OK(amsph_sim_create(&c, b, &s));
    CHECK_OK(amsph_sim_run(&s, &options));
    amsph_checkpoint ck = {0};
    if (!read_checkpoint(dir, &ck))
        CHECK(saved_scalar(&ck, "step") == s.step, "the last checkpoint is at step %lld, the run ended at %lld",
              saved_scalar(&ck, "step"), s.step);
    amsph_checkpoint_free(&ck);
    amsph_sim_free(&s);
}

int main(void)
{
    for (int k = 0; k < TESTING_BACKENDS; ++k) {
        test_bit_identical(k, dambreak, "dambreak");
        test_bit_identical(k, melting_slab, "slab");
        test_bit_identical(k, grain_dambreak, "grains");
        test_bit_identical(k, volume_h_dambreak, "volume_h");
        test_bit_identical(k, verlet_dambreak, "verlet");
        test_bit_identical(k, gas_dambreak, "gas");
    }
    amsph_backend *b = testing_backend(0);
    amsph_case c;
    parse(dambreak, &c);
    char dir[128];
    testing_temp_dir(dir, sizeof dir, "restart_refusals");
    CHECK_OK(run_case(b, &c, dir, 20, NULL, NULL));
    test_refusals(b, dir);
    test_full_disk(b, dir);
    test_stop_request(b);
    test_periodic_checkpoint(b);
    amsph_backend_destroy(b);
    return testing_finish();
}
