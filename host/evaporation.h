/* Host side of evaporation at free surfaces (kernels/evaporation.cl): the
 * recoil force of Fuchs et al. 2022 Eqs. 10 and 30 (the heat loss of their
 * Eq. 18 is a term of the thermal module's heat rate), and the simpler
 * option of removing particles above a cut-off temperature. Settings come
 * from the case's `thermal:` keys (thermal_params). */
#ifndef AMSPH_EVAPORATION_H
#define AMSPH_EVAPORATION_H

#include "sim.h"

/* Adds the recoil force per mass of the free surfaces' fluid particles to
 * their acceleration (after the fluid forces, on the sorted grid). */
int amsph_evaporation_recoil(amsph_sim *s);

/* Removes the fluid and solid particles above thermal.evaporation_temperature
 * (after the thermal update): counts them in s->evaporated_particles, books
 * their enthalpy in s->ledger.evaporated and sorts the grid without them. */
int amsph_evaporation_remove_hot(amsph_sim *s);

#endif
