/* Checkpoints: everything a restart needs to continue a simulation bit for
 * bit (on the same backend and device): every particle field, the last good
 * copy, the sim's scalars (amsph_sim_scalars), the grain records, and where the run's output
 * stands.
 *
 * File layout, format version AMSPH_CHECKPOINT_VERSION: an HDF5 file with
 *     root attributes dim, real_bytes, case_hash, case_path, grain_values
 *     /particles   one dataset per field (as in snapshots)
 *     /last_good   the output fields of the last state that passed the guards
 *     /sim         one attribute per sim scalar (float64 or int64)
 *     /run         attributes next_output, wall_seconds, series_bytes,
 *                  snapshots; datasets snapshot_time, snapshot_particles
 *     /grains      the grain records, grain_values reals (only with grains)
 * followed by a 64-byte text trailer (HDF5 ignores bytes past its end)
 *     amsph checkpoint VERSION HDF5_BYTES FNV1A64_OF_THEM_IN_HEX
 * The trailer and checksum are verified before HDF5 reads anything, so a
 * truncated or corrupt file is refused with a message instead of reaching
 * the HDF5 parser. The file is assembled in memory and written under a
 * temporary name, synced and renamed: the previous checkpoint stays intact
 * until the new one is complete. */
#ifndef AMSPH_CHECKPOINT_H
#define AMSPH_CHECKPOINT_H

#include "output.h"
#include "sim.h"

#define AMSPH_CHECKPOINT_VERSION 2 /* 2: grain records */

/* Where the run's output stands. */
struct amsph_run_record {
    long long next_output;         /* index k of the next output time k * output_interval */
    double wall_seconds;           /* wall time spent on the simulation so far */
    long long series_bytes;        /* length of series.csv at the checkpoint */
    amsph_snapshot_list snapshots; /* the snapshots written so far */
};

typedef struct {
    int dim;
    unsigned long long case_hash; /* amsph_case.text_hash of the case it ran */
    char case_path[512];          /* that case's file, for messages */
    amsph_sim_state state;
    amsph_run_record run;
} amsph_checkpoint;

int amsph_checkpoint_write(const char *path, const amsph_checkpoint *ck);
/* Reads and verifies a checkpoint: header, version, length, checksum and
 * structure. Anything wrong is bad input (AMSPH_BAD_INPUT) with a message
 * that says what; ck is freed by the caller, also on failure. */
int amsph_checkpoint_read(const char *path, amsph_checkpoint *ck);
/* Bad input unless the checkpoint comes from case c (dimension, case text). */
int amsph_checkpoint_check_case(const amsph_checkpoint *ck, const char *path, const amsph_case *c);
void amsph_checkpoint_free(amsph_checkpoint *ck);

#endif
