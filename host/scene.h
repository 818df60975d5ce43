/* Scene geometry: particles on a lattice of spacing dx filling the case's
 * geometry blocks (boxes, circles, spheres, cylinders, wall shells). */
#ifndef AMSPH_SCENE_H
#define AMSPH_SCENE_H

#include "case.h"
#include "particles.h"

/* Fills h (fields position, velocity, density, pressure, mass, kind,
 * material, id, and temperature when the case gives one) from the case.
 * Fails with a message naming the block's line when a block is empty or
 * reaches outside the domain. */
int amsph_scene_build(const amsph_case *c, amsph_host_particles *h);

#endif
