/* Wall-clock time per phase of the time step, for `amsph bench`. Off by
 * default: a sim switches phases at no cost. On, every switch waits for the
 * backend to finish (amsph_sync) and charges the time since the previous
 * switch to the phase that was current, so each phase gets the time of its
 * own kernels only and the phases of a step add up to no more than it. */
#ifndef AMSPH_TIMERS_H
#define AMSPH_TIMERS_H

#include "backend.h"

/* The phases of a step, one per module. A module added to the step gets a
 * row here and a switch to its phase before its calls. */
#define AMSPH_PHASES(X)                                                                            \
    X(SORT, "sort")               /* drift's grid sort and reorder */                              \
    X(DENSITY, "density")         /* continuity, Shepard sums, density update */                   \
    X(FORCES, "forces")           /* equation of state, wall states, pressure and viscous forces */ \
    X(SURFACE, "surface")         /* surface tension, Marangoni */                                 \
    X(THERMAL, "thermal")         /* enthalpy step: conduction, radiation, phase change */         \
    X(LASER, "laser")             /* absorbed laser power */                                       \
    X(GRAINS, "grains")           /* grain forces, sums, kicks, drift, melting and capture */      \
    X(INTEGRATION, "integration") /* kicks, drift, stable time step */                             \
    X(GUARDS, "guards")           /* run guards and the last good copy */

#define AMSPH_PHASE_ENUM(id, name) AMSPH_PHASE_##id,
/* NONE: outside the step, charged to nothing (a zeroed amsph_timers is off
 * and in no phase). */
typedef enum { AMSPH_PHASE_NONE, AMSPH_PHASES(AMSPH_PHASE_ENUM) AMSPH_PHASE_COUNT } amsph_phase;
#undef AMSPH_PHASE_ENUM

extern const char *const amsph_phase_names[AMSPH_PHASE_COUNT]; /* "none", "sort", ... */

typedef struct {
    int enabled;
    amsph_phase current;
    double since;                      /* wall clock of the last switch, s */
    double seconds[AMSPH_PHASE_COUNT]; /* charged to each phase since the last reset */
    int used[AMSPH_PHASE_COUNT];       /* the phase was current since the last reset */
} amsph_timers;

/* Monotonic wall clock, s. */
double amsph_wall_seconds(void);

/* Zeroes the totals and turns the timers on or off. */
void amsph_timers_reset(amsph_timers *t, int enabled);

/* Makes `next` the current phase; with the timers on, first waits for b and
 * charges the time since the last switch to the phase that was current.
 * *previous (may be NULL) receives that phase, for a nested phase to
 * switch back to it. */
int amsph_timers_switch(amsph_timers *t, amsph_backend *b, amsph_phase next, amsph_phase *previous);

#endif
