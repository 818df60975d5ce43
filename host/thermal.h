/* Host side of the thermal module: the materials' enthalpy tables, the
 * enthalpy update of a step (explicit, or implicit midpoint by fixed-point
 * iteration), the diffusion time-step limit and the energy ledger; and,
 * for cases without the module, the prescribed temperature history. */
#ifndef AMSPH_THERMAL_H
#define AMSPH_THERMAL_H

#include "sim.h"
#include "thermal_table.h"

/* The factor c of the surface delta c |grad Gamma| that integrates to 1
 * across a flat lattice face, counting the particles with |grad Gamma| h at
 * or above `cutoff` (kernels/thermal.cl flat_face_delta, computed on the
 * sim's backend for its kernel, h and dx). */
int amsph_surface_delta(amsph_sim *s, double cutoff, amsph_real *delta);

/* Adds the module's fields to the host particles. */
int amsph_thermal_setup(amsph_sim *s, amsph_host_particles *h);
/* The device tables and scratch buffers (also for a restart, whose state
 * comes from the checkpoint). */
int amsph_thermal_allocate(amsph_sim *s);
/* On the device, after the first sort: amsph_thermal_allocate, enthalpy from
 * the initial temperature, the initial state and the ledger's starting energy. */
int amsph_thermal_start(amsph_sim *s);
void amsph_thermal_free(amsph_sim *s);
/* Advances the enthalpy over dt (after the drift and sort) and updates
 * temperature, liquid fraction, peak temperature, kinds and the ledger. */
int amsph_thermal_advance(amsph_sim *s, double dt);
/* Lowers *dt to the diffusion limit diffusion_number rho c h^2 / k (Fuchs et
 * al. 2022 Eq. 42) over the materials. */
void amsph_thermal_dt(const amsph_sim *s, double *dt, const char **limit);
/* Sum of m h over fluid and solid particles, J (per metre in 2D). */
int amsph_thermal_energy(amsph_sim *s, double *energy);
/* Books in the ledger the enthalpy of the particles outside the domain,
 * which the next sort drops (after the drift, before the sort). */
int amsph_thermal_book_departures(amsph_sim *s);
/* |energy change - booked exchanges| over the gross exchange (0 when
 * nothing was exchanged and nothing changed), with the material's enthalpy
 * now `energy` (amsph_thermal_energy). */
double amsph_energy_ledger_error(const amsph_energy_ledger *l, double energy);
/* The same for the sim's state now. */
int amsph_thermal_ledger_error(amsph_sim *s, double *error);

/* Sets every particle's temperature to the case's temperature history at
 * time t (cases without the thermal module). */
int amsph_thermal_prescribe(amsph_sim *s, double t);

/* h(T) of a material's node table, J/kg (as the kernels interpolate it). */
double amsph_thermal_enthalpy(const amsph_material *m, double t);

/* Node table of one material (exposed for tests): temperatures, enthalpies
 * and conductivities of THERMAL_NODES nodes at most; returns the count. */
int amsph_thermal_nodes(const amsph_material *m, double *temperature, double *enthalpy,
                        double *conductivity);

#endif
