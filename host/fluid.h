/* Host side of the fluid module: settings for the kernels, the pass
 * sequence that evaluates the rates, and the module's time-step limits. */
#ifndef AMSPH_FLUID_H
#define AMSPH_FLUID_H

#include "sim.h"

/* Fills s->fluid from the case and adds the module's fields, among them
 * every particle's reference density rho0(T) at its initial temperature. */
int amsph_fluid_setup(amsph_sim *s, amsph_host_particles *h);
/* Once the device is ready: the constants computed there (the lattice's
 * Shepard sum of the summed gas density). */
int amsph_fluid_start(amsph_sim *s);
/* rho0(T) of every particle from its temperature (after the temperature
 * changed; only where s->reference_density_varies). */
int amsph_fluid_reference_density(amsph_sim *s);
/* After the drift: continuity (with the half-step velocity) and Shepard
 * sums, then rho += dt drho/dt for fluid particles (dt = 0 at the start),
 * or the summed density of a gas (fluid.gas_density: summation). */
int amsph_fluid_density(amsph_sim *s, double dt);
/* Equation of state, wall states, then the acceleration of every fluid
 * particle. */
int amsph_fluid_forces(amsph_sim *s);
/* The fields the sort may leave unordered (amsph_grid.recomputed): under
 * the Verlet scheme, which serves the fluid module alone, a step sorts
 * and then computes the rates and the wall states of every particle
 * (equation of state, wall_state, fluid_forces) before any kernel reads
 * them; none otherwise. */
unsigned amsph_fluid_recomputed_fields(const amsph_sim *s);
/* Whether a step ends with a shifting pass: particle shifting
 * (fluid.shifting) or the transport velocity (fluid.transport_pressure). */
int amsph_fluid_shifts(const amsph_fluid_settings *f);
/* Particle shifting and the transport velocity's displacement at the end of
 * a step of dt: kernels/fluid.cl shifting_displacement, added to the
 * positions. */
int amsph_fluid_shift(amsph_sim *s, double dt);
/* The buffer of the fluid particles' own smoothing lengths as a kernel
 * argument (fluid.smoothing_length: volume); otherwise a stand-in the
 * kernels do not read (kernels/fluid_pair.h particle_smoothing_length). */
amsph_arg amsph_fluid_smoothing_length(amsph_sim *s);
/* The largest smoothing length over h0 that the neighbour grid serves:
 * fluid.max_smoothing_ratio with `smoothing_length: volume`, else 1. */
double amsph_fluid_max_smoothing_ratio(const amsph_case *c);
/* Stops the run (bad input, naming the particle) when a fluid particle's
 * smoothing length exceeds the grid's h_max (`smoothing_length: volume`). */
int amsph_fluid_check_smoothing_length(amsph_sim *s);
/* Lowers *dt to the acoustic, viscous and force limits (Fuchs et al. 2022
 * Eq. 42), naming the one that binds in *limit. */
int amsph_fluid_dt(amsph_sim *s, double *dt, const char **limit);

#endif
