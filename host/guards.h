/* Run guards: non-finite values (every run), and with the fluid module
 * particle pairs closer than a fraction of dx, density error out of
 * bounds, a smoothing length past the grid's h_max (host/fluid.c). */
#ifndef AMSPH_GUARDS_H
#define AMSPH_GUARDS_H

#include "sim.h"

/* Returns 0, or fails with a message naming the check, the step and time,
 * and the first offending particle's id and position. */
int amsph_guards_check(amsph_sim *s);

#endif
