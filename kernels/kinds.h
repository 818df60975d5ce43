/* Particle kinds as stored in the `kind` field, shared by kernels and host.
 * Later kinds get new numbers; these never change (snapshots store them). */
#ifndef AMSPH_KINDS_H
#define AMSPH_KINDS_H
#define KIND_FLUID 0
#define KIND_WALL 1
#define KIND_SOLID 2
#define KIND_GRAIN 3 /* a particle of a mobile rigid grain (kernels/grains.cl) */
#endif
