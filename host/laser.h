/* Host side of the laser module: the beam's power schedule and path, the
 * beam-aligned bin grid, and the passes (kernels/laser.cl) that fill every
 * particle's laser_power, the absorbed power per unit volume (W/m^3) that
 * the thermal module adds to the energy rate. */
#ifndef AMSPH_LASER_H
#define AMSPH_LASER_H

#include "sim.h"

/* Adds the laser_power field; for volumetric absorption lays out the bin
 * grid and allocates it (bins must fit the sorted grid: bin_size sqrt(d) at
 * most the kernel support). Needs s->config, s->backend and s->support. */
int amsph_laser_setup(amsph_sim *s, amsph_host_particles *h);

/* The bin grid of volumetric absorption for the case at kernel support
 * `support` (m): nodes across the beam per lateral axis (odd, the middle
 * one on the axis) and along it (from above the domain to below it). Bad
 * input where bin_size sqrt(d) exceeds the support (a node gathers from the
 * grid cells around it) or the nodes would be too many. */
int amsph_laser_bins(const amsph_case *c, double support, int *lateral_nodes, int *depth_nodes);

/* Fills laser_power for the beam at time t (particles sorted, densities
 * current) and sets s->laser.absorbed_power, the total the particles
 * absorbed, W (2D: W per metre of depth). */
int amsph_laser_absorb(amsph_sim *s, double t);

/* laser_power for a step from t0 to t1: the beam where it is at mid-step,
 * with the mean power of the step (so that the energy of the schedule is
 * delivered exactly, switching and ramps included). */
int amsph_laser_absorb_step(amsph_sim *s, double t0, double t1);

/* Energy the beam delivers from t0 to t1, J: the exact integral of the
 * piecewise-linear schedule. */
double amsph_laser_beam_energy(const amsph_case *c, double t0, double t1);

/* Beam power at time t, W: 0 before on_time and from off_time on, ramping
 * linearly over ramp_time after on_time and before off_time. */
double amsph_laser_beam_power(const amsph_case *c, double t);

/* Beam centre at time t, m: start, then along the path segments in order
 * from t = 0, then at rest at the last end point. */
void amsph_laser_beam_centre(const amsph_case *c, double t, double x[3]);

#endif
