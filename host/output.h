/* Output: one HDF5 file per snapshot (OUTDIR/snap_NNNNNN.h5) and an XDMF
 * index (OUTDIR/snapshots.xmf) that ParaView opens as one time series.
 *
 * Snapshot schema (stable): root datasets named after the registry fields
 * flagged for output (position N x 3, velocity N x 3, density, pressure,
 * mass, kind, material, id, and temperature, liquid_fraction when present),
 * each with a string attribute `unit`; root attributes time (s), step, dim,
 * dx (m). Files are written under a temporary name and renamed, so a crash
 * never leaves a half-written snapshot under the final name.
 *
 * Snapshots are numbered over the whole simulation, restarts included: a run
 * restarted in the directory of its checkpoint continues that directory's
 * numbering and index (the snapshots written after the checkpoint are
 * removed); one restarted elsewhere continues the numbering and indexes its
 * own snapshots only. */
#ifndef AMSPH_OUTPUT_H
#define AMSPH_OUTPUT_H

#include "particles.h"

/* The files of a run in OUTDIR besides its snapshots, and the analysis that
 * `amsph analyze OUTDIR` writes there by default. */
#define AMSPH_OUTPUT_INDEX "snapshots.xmf"
#define AMSPH_OUTPUT_SERIES "series.csv"
#define AMSPH_OUTPUT_CHECKPOINT "checkpoint.h5"
#define AMSPH_OUTPUT_ANALYSIS "melt_pool.csv"

/* The snapshots of a simulation so far. */
typedef struct {
    int count;
    int capacity;
    double *time;   /* time of each snapshot, s */
    int *particles; /* particle count of each snapshot */
} amsph_snapshot_list;

int amsph_snapshot_list_add(amsph_snapshot_list *l, double time, int particles);
int amsph_snapshot_list_copy(amsph_snapshot_list *dst, const amsph_snapshot_list *src);
void amsph_snapshot_list_free(amsph_snapshot_list *l);

typedef struct {
    char dir[1024];
    int dim;
    double dx;
    amsph_snapshot_list list; /* every snapshot of the simulation */
    int first;                /* the first of them in this directory */
    unsigned present;         /* bit f: field f is in the snapshots */
} amsph_output;

/* Bad input unless dir can take a new run: it does not exist, is an empty
 * directory, or force is set (amsph_output_clear then removes the earlier
 * run's files). */
int amsph_output_check_dir(const char *dir, int force);
/* 1 if dir is the directory that holds file (both exist), else 0. */
int amsph_output_holds(const char *dir, const char *file);

/* Creates OUTDIR (and parents) after amsph_output_check_dir(dir, force). */
int amsph_output_open(amsph_output *o, const char *dir, int dim, double dx, int force);
/* Continues after the snapshots of an earlier run of the same simulation:
 * the next snapshot is number earlier->count; the index lists the earlier
 * ones too when in_place (this is their directory). */
int amsph_output_continue(amsph_output *o, const amsph_snapshot_list *earlier, int in_place);
/* Removes what an earlier run left in the open directory, so that it holds
 * one run only: its snapshots from number o->list.count on, and unless
 * in_place (a restart in the checkpoint's directory, which keeps the earlier
 * snapshots, index and series) all its snapshots and the four files above.
 * Other files stay. */
int amsph_output_clear(const amsph_output *o, int in_place);
/* Writes the next snapshot and rewrites the XDMF index. */
int amsph_output_snapshot(amsph_output *o, const amsph_host_particles *h, double time, long long step);
void amsph_output_close(amsph_output *o);

/* OUTDIR/name into path (fails if too long). */
int amsph_output_path(const amsph_output *o, const char *name, char *path, size_t size);

#endif
