#include "analyze.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "case.h"
#include "error.h"
#include "h5.h"

static int count(const amsph_analysis_state *a) { return a->particles->n; }

static const amsph_real *real_field(const amsph_analysis_state *a, amsph_field_id f)
{
    return amsph_host_real(a->particles, f);
}

static double coordinate(const amsph_analysis_state *a, int i, int axis)
{
    return real_field(a, AMSPH_FIELD_POSITION)[3 * i + axis];
}

static int is_material(const amsph_analysis_state *a, int i)
{
    return ((const int *)a->particles->data[AMSPH_FIELD_KIND])[i] != AMSPH_KIND_WALL;
}

/* Over half liquid: the melt pool. */
static int is_melt(const amsph_analysis_state *a, int i)
{
    const amsph_real *phi = real_field(a, AMSPH_FIELD_LIQUID_FRACTION);
    return phi && is_material(a, i) && phi[i] > 0.5;
}

/* The melt's lowest and highest coordinate along an axis; 0 without melt. */
static int melt_range(const amsph_analysis_state *a, int axis, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    int melted = 0;
    for (int i = 0; i < count(a); ++i)
        if (is_melt(a, i)) {
            const double x = coordinate(a, i, axis);
            *lo = fmin(*lo, x);
            *hi = fmax(*hi, x);
            melted = 1;
        }
    return melted;
}

/* Extent of the melt along an axis: its particles' span plus one spacing
 * (each stands for a cell dx wide), NAN without melt. */
static double melt_extent(const amsph_analysis_state *a, int axis)
{
    double lo, hi;
    return axis >= 0 && melt_range(a, axis, &lo, &hi) ? hi - lo + a->dx : NAN;
}

static double time_of(const amsph_analysis_state *a) { return a->time; }

static double melt_particles(const amsph_analysis_state *a)
{
    if (!real_field(a, AMSPH_FIELD_LIQUID_FRACTION))
        return NAN;
    int melted = 0;
    for (int i = 0; i < count(a); ++i)
        melted += is_melt(a, i);
    return melted;
}

static double melt_length(const amsph_analysis_state *a) { return melt_extent(a, a->axes.scan); }
static double melt_width(const amsph_analysis_state *a) { return melt_extent(a, a->width_axis); }
static double melt_depth(const amsph_analysis_state *a) { return melt_extent(a, a->axes.up); }

static double penetration(const amsph_analysis_state *a)
{
    double lo, hi;
    return melt_range(a, a->axes.up, &lo, &hi) ? a->surface - (lo - 0.5 * a->dx) : NAN;
}

static double peak_temperature(const amsph_analysis_state *a)
{
    const amsph_real *t = real_field(a, AMSPH_FIELD_TEMPERATURE);
    if (!t)
        return NAN;
    double peak = -INFINITY;
    for (int i = 0; i < count(a); ++i)
        if (is_material(a, i))
            peak = fmax(peak, t[i]);
    return peak;
}

static double peak_speed(const amsph_analysis_state *a)
{
    const amsph_real *v = real_field(a, AMSPH_FIELD_VELOCITY);
    double peak = 0.0;
    for (int i = 0; i < count(a); ++i)
        if (is_material(a, i))
            peak = fmax(peak, sqrt((double)v[3 * i] * v[3 * i] + (double)v[3 * i + 1] * v[3 * i + 1] +
                                   (double)v[3 * i + 2] * v[3 * i + 2]));
    return peak;
}

static double liquid_mass(const amsph_analysis_state *a)
{
    const amsph_real *phi = real_field(a, AMSPH_FIELD_LIQUID_FRACTION), *m = real_field(a, AMSPH_FIELD_MASS);
    if (!phi)
        return NAN;
    double sum = 0.0;
    for (int i = 0; i < count(a); ++i)
        if (is_material(a, i))
            sum += (double)m[i] * phi[i];
    return sum;
}

static double solidification_rate(const amsph_analysis_state *a)
{
    return -(liquid_mass(a) - a->previous_liquid_mass) / (a->time - a->previous_time);
}

/* Column (dx wide along the scan axis) of particle i on the track's line
 * (3D: within dx/2 of it across, with 0.1% for the rounding of float
 * positions: a line halfway between two lattice rows takes both), or -1
 * (off the line, outside the columns). */
static int track_column(const amsph_analysis_state *a, int i)
{
    if (a->width_axis >= 0 && fabs(coordinate(a, i, a->width_axis) - a->axes.track_at) > 0.501 * a->dx)
        return -1;
    const double c = floor((coordinate(a, i, a->axes.scan) - a->column_origin) / a->dx);
    return c >= 0 && c < a->n_columns ? (int)c : -1;
}

static double track_height_variation(const amsph_analysis_state *a)
{
    double *top = malloc((size_t)a->n_columns * sizeof *top);
    if (!top)
        return NAN;
    for (int k = 0; k < a->n_columns; ++k)
        top[k] = -INFINITY;
    for (int i = 0; i < count(a); ++i) {
        const int k = is_material(a, i) ? track_column(a, i) : -1;
        if (k >= 0)
            top[k] = fmax(top[k], coordinate(a, i, a->axes.up) + 0.5 * a->dx);
    }
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < a->n_columns; ++k)
        if (a->track[k] && isfinite(top[k])) {
            lo = fmin(lo, top[k]);
            hi = fmax(hi, top[k]);
        }
    free(top);
    return hi >= lo ? hi - lo : NAN;
}

/* "Melt": fluid and solid particles with liquid fraction > 0.5 (walls never
 * count); extents count each particle as a cell dx wide. */
const amsph_analysis_metric amsph_analysis_metrics[] = {
    {"time", "s", "Simulated time of the snapshot", time_of},
    {"melt_particles", "1", "Particles of the melt pool: fluid and solid with liquid fraction > 0.5", melt_particles},
    {"melt_length", "m", "Extent of the melt along the scan axis: max - min of its particles' coordinates + dx",
     melt_length},
    {"melt_width", "m", "Extent of the melt along the third axis (3D; empty in 2D), as the length", melt_width},
    {"melt_depth", "m", "Extent of the melt along the up axis (top to bottom of the pool), as the length",
     melt_depth},
    {"penetration", "m",
     "Initial substrate surface minus the melt's bottom (its lowest particle's up coordinate - dx/2); the "
     "surface is --surface, else the highest solid particle of the first snapshot + dx/2 (of any non-wall particle if it has "
     "no solid); negative: the melt stays above it",
     penetration},
    {"peak_temperature", "K", "Largest temperature of a fluid or solid particle", peak_temperature},
    {"peak_speed", "m/s", "Largest speed of a fluid or solid particle", peak_speed},
    {"liquid_mass", "kg", "Sum of mass times liquid fraction over fluid and solid (per metre in 2D)", liquid_mass},
    {"solidification_rate", "kg/s",
     "-(liquid_mass - its value at the previous snapshot) / (time between them): positive while the pool "
     "solidifies; empty at the first snapshot",
     solidification_rate},
    {"track_height_variation", "m",
     "Max - min of the top surface height along the track: the scan axis in columns dx wide (3D: of the "
     "particles within dx/2 of the track's line, --track-at), each column's height its highest fluid or solid "
     "particle + dx/2, over the columns where a particle has been melt in this or an earlier snapshot",
     track_height_variation},
};
const int amsph_analysis_metric_count = (int)(sizeof amsph_analysis_metrics / sizeof amsph_analysis_metrics[0]);

void amsph_analysis_print_metrics(FILE *f)
{
    fprintf(f, "| Metric | Unit | Definition |\n|---|---|---|\n");
    for (int k = 0; k < amsph_analysis_metric_count; ++k)
        fprintf(f, "| `%s` | %s | %s |\n", amsph_analysis_metrics[k].name, amsph_analysis_metrics[k].unit,
                amsph_analysis_metrics[k].doc);
}

/* ---- reading snapshots ------------------------------------------------- */

static const amsph_field_id needed_fields[] = {AMSPH_FIELD_POSITION, AMSPH_FIELD_VELOCITY, AMSPH_FIELD_KIND,
                                               AMSPH_FIELD_MASS};
static const amsph_field_id optional_fields[] = {AMSPH_FIELD_TEMPERATURE, AMSPH_FIELD_LIQUID_FRACTION};

static int read_field(hid_t file, const char *path, amsph_host_particles *h, amsph_field_id f)
{
    AMSPH_CHECK(amsph_host_add_field(h, f));
    return amsph_h5_read_field(file, path, h, f);
}

static int read_snapshot_file(hid_t file, const char *path, amsph_host_particles *h, int *dim, double *dx,
                              double *time)
{
    AMSPH_CHECK(amsph_h5_read_attribute(file, path, "time", H5T_NATIVE_DOUBLE, time));
    AMSPH_CHECK(amsph_h5_read_attribute(file, path, "dim", H5T_NATIVE_INT, dim));
    AMSPH_CHECK(amsph_h5_read_attribute(file, path, "dx", H5T_NATIVE_DOUBLE, dx));
    AMSPH_CHECK(amsph_h5_field_rows(file, path, AMSPH_FIELD_POSITION, &h->n));
    for (size_t k = 0; k < sizeof needed_fields / sizeof needed_fields[0]; ++k)
        AMSPH_CHECK(read_field(file, path, h, needed_fields[k]));
    for (size_t k = 0; k < sizeof optional_fields / sizeof optional_fields[0]; ++k)
        if (H5Lexists(file, amsph_fields[optional_fields[k]].name, H5P_DEFAULT) > 0)
            AMSPH_CHECK(read_field(file, path, h, optional_fields[k]));
    return 0;
}

/* The path of snapshot k of outdir. */
static int snapshot_path(const char *outdir, int k, char *path, size_t size)
{
    if (snprintf(path, size, "%s/snap_%06d.h5", outdir, k) >= (int)size)
        return amsph_bad_input("path too long: %s", outdir);
    return 0;
}

/* The snapshot at path into h, which the caller frees whatever the status. */
static int read_snapshot(const char *path, amsph_host_particles *h, int *dim, double *dx, double *time)
{
    memset(h, 0, sizeof *h);
    amsph_h5_quiet();
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file < 0)
        return amsph_bad_input("%s is not a readable HDF5 snapshot", path);
    const int status = read_snapshot_file(file, path, h, dim, dx, time);
    H5Fclose(file);
    return status;
}

/* ---- the analysis ------------------------------------------------------ */

/* From the first snapshot: the substrate surface, the columns along the
 * scan axis and the track's line. */
static int start_state(amsph_analysis_state *a)
{
    const int *kind = a->particles->data[AMSPH_FIELD_KIND];
    double top_solid = -INFINITY, top = -INFINITY, lo = INFINITY, hi = -INFINITY;
    double width_lo = INFINITY, width_hi = -INFINITY;
    for (int i = 0; i < count(a); ++i) {
        if (!is_material(a, i))
            continue;
        const double z = coordinate(a, i, a->axes.up), x = coordinate(a, i, a->axes.scan);
        top = fmax(top, z);
        if (kind[i] == AMSPH_KIND_SOLID)
            top_solid = fmax(top_solid, z);
        lo = fmin(lo, x);
        hi = fmax(hi, x);
        if (a->width_axis >= 0) {
            width_lo = fmin(width_lo, coordinate(a, i, a->width_axis));
            width_hi = fmax(width_hi, coordinate(a, i, a->width_axis));
        }
    }
    if (!isfinite(top))
        return amsph_bad_input("the first snapshot has no fluid or solid particles to analyse");
    a->surface = isfinite(a->axes.surface) ? a->axes.surface : (isfinite(top_solid) ? top_solid : top) + 0.5 * a->dx;
    a->column_origin = lo - 0.5 * a->dx;
    const double columns = ceil((hi - lo) / a->dx - 1e-6) + 1.0;
    if (columns > AMSPH_ANALYSIS_MAX_COLUMNS)
        return amsph_bad_input("the material spans %g spacings along the scan axis (at most %d)", columns,
                               AMSPH_ANALYSIS_MAX_COLUMNS);
    a->n_columns = (int)columns;
    a->track = calloc((size_t)a->n_columns, 1);
    if (!a->track)
        return amsph_fail("out of host memory for %d track columns", a->n_columns);
    if (a->width_axis >= 0 && isnan(a->axes.track_at))
        a->axes.track_at = 0.5 * (width_lo + width_hi);
    return 0;
}

static void mark_track(amsph_analysis_state *a)
{
    for (int i = 0; i < count(a); ++i) {
        const int k = is_melt(a, i) ? track_column(a, i) : -1;
        if (k >= 0)
            a->track[k] = 1;
    }
}

static int write_row(FILE *f, const amsph_analysis_state *a)
{
    for (int k = 0; k < amsph_analysis_metric_count; ++k) {
        const double v = amsph_analysis_metrics[k].value(a);
        fputs(k ? "," : "", f);
        if (!isnan(v))
            fprintf(f, "%.9g", v);
    }
    return fputc('\n', f) == EOF;
}

static int check_axes(const amsph_analysis_axes *axes, int dim)
{
    if (axes->scan >= dim || axes->up >= dim || axes->scan == axes->up)
        return amsph_bad_input("the scan axis (%c) and the up axis (%c) must be two different axes of the %dD run",
                               "xyz"[axes->scan], "xyz"[axes->up], dim);
    return 0;
}

static int analyze_snapshots(const char *outdir, const amsph_analysis_axes *axes, FILE *out)
{
    amsph_analysis_state a = {.axes = *axes, .previous_time = NAN, .previous_liquid_mass = NAN};
    int status = 0;
    for (int k = 0;; ++k) {
        char path[1100];
        status = snapshot_path(outdir, k, path, sizeof path);
        if (status || access(path, F_OK) != 0) /* no snapshot k: the end */
            break;
        amsph_host_particles h;
        status = read_snapshot(path, &h, &a.dim, &a.dx, &a.time);
        a.particles = &h;
        if (!status && k == 0) {
            if (a.axes.up < 0)
                a.axes.up = a.dim - 1;
            a.width_axis = a.dim == 3 ? 3 - a.axes.scan - a.axes.up : -1;
            status = check_axes(&a.axes, a.dim);
            if (!status)
                status = start_state(&a);
        }
        if (!status) {
            mark_track(&a);
            if (write_row(out, &a))
                status = amsph_fail("cannot write the analysis: %s", strerror(errno));
            a.previous_time = a.time;
            a.previous_liquid_mass = liquid_mass(&a);
        }
        amsph_host_free(&h);
        if (status)
            break;
    }
    free(a.track);
    return status;
}

int amsph_analyze(const char *outdir, const amsph_analysis_axes *axes, const char *csv_path)
{
    char first[1100];
    AMSPH_CHECK(snapshot_path(outdir, 0, first, sizeof first));
    if (access(first, F_OK) != 0)
        return amsph_bad_input("%s holds no snapshot (snap_000000.h5)", outdir);
    FILE *out = fopen(csv_path, "w");
    if (!out)
        return amsph_bad_input("cannot create %s: %s", csv_path, strerror(errno));
    for (int k = 0; k < amsph_analysis_metric_count; ++k)
        fprintf(out, "%s%s", k ? "," : "", amsph_analysis_metrics[k].name);
    fputc('\n', out);
    int status = analyze_snapshots(outdir, axes, out);
    if (fclose(out) && !status)
        status = amsph_fail("cannot write %s: %s", csv_path, strerror(errno));
    return status;
}
