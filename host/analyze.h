/* Melt-pool analysis of a run's snapshots (`amsph analyze OUTDIR`): one CSV
 * row per snapshot, in time order, of the metrics in amsph_analysis_metrics.
 *
 * The metrics are one table, like the series columns (host/series.h): each
 * has a name, a unit, its definition and the function that computes it
 * from one snapshot and what the earlier snapshots left (the initial
 * substrate surface, the track's columns, the previous liquid mass).
 * `amsph analyze --metrics` prints the table that README.md carries. A
 * metric that does not apply (no melt, no earlier snapshot, a width in 2D)
 * is an empty cell. */
#ifndef AMSPH_ANALYZE_H
#define AMSPH_ANALYZE_H

#include <stdio.h>

#include "particles.h"

/* Which axes the geometry is measured along (0 x, 1 y, 2 z). */
typedef struct {
    int scan;           /* along the track (length); default x */
    int up;             /* up (depth, heights); default the last axis */
    double track_at;    /* 3D: the track's coordinate on the third axis; NAN: the
                           middle of the non-wall particles of the first snapshot */
    double surface;     /* up coordinate of the initial substrate surface; NAN: the top of
                           the highest solid particle of the first snapshot */
} amsph_analysis_axes;

#define AMSPH_ANALYSIS_MAX_COLUMNS 65536

/* What the metrics of one snapshot read. */
typedef struct {
    const amsph_host_particles *particles; /* position, velocity, kind, mass; temperature and
                                              liquid_fraction where the run had them */
    int dim;
    double dx, time;
    amsph_analysis_axes axes;
    int width_axis;                /* the third axis in 3D, -1 in 2D */
    double surface;                /* initial top of the solid (first snapshot), m */
    double column_origin;          /* scan coordinate of column 0, m */
    int n_columns;                 /* columns dx wide along the scan axis */
    unsigned char *track;          /* per column: 1 once a particle in it was over half liquid */
    double previous_time, previous_liquid_mass; /* NAN at the first snapshot */
} amsph_analysis_state;

typedef struct {
    const char *name;
    const char *unit;
    const char *doc;
    double (*value)(const amsph_analysis_state *a); /* NAN: an empty cell */
} amsph_analysis_metric;

extern const amsph_analysis_metric amsph_analysis_metrics[];
extern const int amsph_analysis_metric_count;

/* Reads OUTDIR/snap_*.h5 in order and writes the CSV to csv_path.
 * Returns 0 or an amsph status (bad input: no snapshots, a field missing). */
int amsph_analyze(const char *outdir, const amsph_analysis_axes *axes, const char *csv_path);

/* The metric reference as a Markdown table (README.md carries it). */
void amsph_analysis_print_metrics(FILE *f);

#endif
