/* Diagnostics time series: OUTDIR/series.csv, a header line of column names
 * and one row per snapshot (so one per output interval, plus the first and
 * the last state).
 *
 * The columns are one table, amsph_series_columns: each has a name, a unit,
 * a description and a function that computes its value from the state at
 * the row's time. A module adds a column with one entry; `amsph columns`
 * prints the table that README.md carries. A column that does not apply to
 * the case (max_temperature without temperatures, the energy ledger without
 * the thermal module) is an empty cell. */
#ifndef AMSPH_SERIES_H
#define AMSPH_SERIES_H

#include <stdio.h>

#include "sim.h"

/* What a column's value is computed from. */
typedef struct {
    const amsph_sim *sim;
    const amsph_host_particles *particles; /* every field of the sim, downloaded */
    double enthalpy; /* of the material (amsph_thermal_energy), J; NAN without the thermal module */
    double wall_seconds;              /* spent on the simulation so far, restarts included */
    double particle_steps_per_second; /* since the previous row */
} amsph_series_sample;

typedef struct {
    const char *name;
    const char *unit;
    const char *doc;
    double (*value)(const amsph_series_sample *x); /* NAN: not applicable, an empty cell */
} amsph_series_column;

extern const amsph_series_column amsph_series_columns[];
extern const int amsph_series_column_count;

typedef struct {
    FILE *file;
    char path[1100];
} amsph_series;

/* Opens path: a new file with the header when keep < 0; otherwise an
 * existing series (an earlier run of the same simulation) cut to its first
 * keep bytes and continued; a missing one starts anew. */
int amsph_series_open(amsph_series *se, const char *path, long long keep);
/* Appends one row and flushes it. */
int amsph_series_write(amsph_series *se, const amsph_series_sample *x);
/* Bytes written so far (what a checkpoint records as keep). */
long long amsph_series_bytes(const amsph_series *se);
void amsph_series_close(amsph_series *se);

/* The column reference as a Markdown table (README.md carries it). */
void amsph_series_print_columns(FILE *f);

#endif
