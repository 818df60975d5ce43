/* Host side of the surface module: surface tension and the Marangoni force
 * on free surfaces (kernels/surface.cl), and the capillary time-step limit. */
#ifndef AMSPH_SURFACE_H
#define AMSPH_SURFACE_H

#include "sim.h"

/* Fills s->surface from the case and adds the module's fields. */
int amsph_surface_setup(amsph_sim *s, amsph_host_particles *h);
/* Checks that the grid's cells serve the surface support and allocates the
 * blocks of cells that find the particles near the liquid (after the grid
 * is laid out). */
int amsph_surface_allocate(amsph_sim *s);
/* Adds the surface forces to the acceleration of fluid particles, and
 * their reaction to that of grain particles (after the fluid forces and
 * the grain particles' forces, before the grains' sums; after the step's
 * amsph_fluid_density, whose fluid counts per cell it reads). */
int amsph_surface_forces(amsph_sim *s);
/* The curvature alone (raw_curvature), from the unit normals and normal
 * weights the particles hold: the pass of amsph_surface_forces after the
 * normals, for a test that prescribes them. */
int amsph_surface_curvature(amsph_sim *s);
/* Lowers *dt to the capillary limit 0.25 sqrt(rho h^3 / (2 pi sigma))
 * (Fuchs et al. 2022 Eq. 42; PHYSICS.md erratum 3) with the smallest
 * reference density and the largest sigma(T) of the particles, and, with
 * an interface viscosity, to its viscous limit (host/surface.c). */
int amsph_surface_dt(amsph_sim *s, double *dt, const char **limit);

#endif
