/* Output: one HDF5 file per snapshot (OUTDIR/snap_NNNNNN.h5) and an XDMF
 * index (OUTDIR/snapshots.xmf) that ParaView opens as one time series.
 *
 * Snapshot schema (stable): root datasets named after the registry fields
 * flagged for output (position N x 3, velocity N x 3, density, pressure,
 * mass, kind, material, id, and temperature, liquid_fraction when present),
 * each with a string attribute `unit`; root attributes time (s), step, dim,
 * dx (m). Files are written under a temporary name and renamed, so a crash
 * never leaves a half-written snapshot under the final name. */
#ifndef AMSPH_OUTPUT_H
#define AMSPH_OUTPUT_H

#include "particles.h"

typedef struct {
    char dir[1024];
    int dim;
    double dx;
    int count;        /* snapshots written */
    int capacity;
    double *times;    /* time of each snapshot */
    int *particles;   /* particle count of each snapshot */
    unsigned present; /* bit f: field f is in the snapshots */
} amsph_output;

/* Creates OUTDIR (and parents) if needed. */
int amsph_output_open(amsph_output *o, const char *dir, int dim, double dx);
/* Writes the next snapshot and rewrites the XDMF index. */
int amsph_output_snapshot(amsph_output *o, const amsph_host_particles *h, double time, long long step);
void amsph_output_close(amsph_output *o);

#endif
