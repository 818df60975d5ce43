/* Powder beds: grains (discs in 2D, spheres in 3D) settled on a substrate,
 * for the `powder_bed` geometry blocks (host/scene.c fills them with
 * particles on the dx lattice).
 *
 * The bed lies in the block's region [min, max]; grains settle towards
 * its bottom face (-y in 2D, -z in 3D), which is the substrate's top.
 *   regular:   touching grains of one radius on a square array from the
 *              region's lower corner (Russell 2018 §5.1.1, "a regular
 *              distribution of powder particles");
 *   lognormal: ln r normal with mean ln(grain_radius) and standard
 *              deviation log_sd, truncated to [grain_radius_min,
 *              grain_radius_max] (Fuchs et al. 2022 §4: diameters from 16
 *              to 32 um);
 *   mixed:     radius small_radius with probability small_fraction, else
 *              grain_radius (Russell §5.1.1.1, 15 and 30 um).
 * The random beds are built by sequential deposition (Visscher & Bolsterli
 * 1972): each grain, of a seeded random radius, is dropped at a seeded
 * random lateral position and falls until it meets the substrate or a
 * grain; on one grain it rolls down the vertical plane through the two
 * centres, on two (3D) down the circle of the points that touch both,
 * until it meets another grain, the substrate or a side of the region
 * (the sides are walls); it leaves a support that would have to pull to
 * hold it (the supports' normal forces, least squares) and falls again
 * when it rolls past the side of its only one. It rests on the substrate,
 * on a wall, on dim grains that all push (in 2D one each side of its
 * centre), or at the bottom of the circle of two. A grain that would rest
 * above the region's top face (the spreader's height) is not laid; the
 * bed is full after MISSES drops in a row fail.
 * Everything follows from the seed (a splitmix64 generator), so a seed
 * gives the same bed wherever the C library's sin, cos and log agree. */
#ifndef AMSPH_POWDER_H
#define AMSPH_POWDER_H

#include "case.h"

typedef struct {
    double centre[3]; /* m */
    double radius;    /* m */
} amsph_grain;

typedef struct {
    int dim;
    int n;              /* grains */
    amsph_grain *grain; /* n grains, in the order of deposition */
} amsph_powder;

/* Settles the bed of powder-bed block g in `dim` dimensions. */
int amsph_powder_deposit(const amsph_geometry *g, int dim, amsph_powder *bed);
void amsph_powder_free(amsph_powder *bed);

/* Grain volume (area in 2D) over the volume of the block's region. */
double amsph_powder_packing_fraction(const amsph_powder *bed, const amsph_geometry *g);

/* Whether x lies inside a grain. */
int amsph_powder_contains(const amsph_powder *bed, const double x[3]);
/* The index of the grain x lies in, or -1. */
int amsph_powder_grain_at(const amsph_powder *bed, const double x[3]);

/* Smallest grain radius the distribution of block g can draw, m. */
double amsph_powder_smallest_radius(const amsph_geometry *g);

#endif
