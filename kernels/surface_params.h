/* Settings of the surface module (surface tension and Marangoni force) as
 * the kernels see them, passed by value; the host includes it with
 * AMSPH_SHARED_REAL = amsph_real. */
#ifndef AMSPH_SURFACE_PARAMS_H
#define AMSPH_SURFACE_PARAMS_H

#include "surface_options.h"

#ifndef AMSPH_SHARED_REAL
#define AMSPH_SHARED_REAL real
#endif

typedef struct {
    AMSPH_SHARED_REAL h;             /* smoothing length of the surface terms, m (1.5 h by default) */
    AMSPH_SHARED_REAL normal_cutoff; /* a normal counts where |n| h >= this (Russell Eq. 3.27, erratum 5) */
    AMSPH_SHARED_REAL max_curvature; /* |kappa| <= 1 / (2 h) (Russell Sec. 3.1.2, flaw 4), 1/m */
    AMSPH_SHARED_REAL min_shepard;   /* particles with Gamma below this carry no surface force */
    AMSPH_SHARED_REAL interface_viscosity; /* alpha0 of Fuchs et al. 2022 Eq. 32; 0: off */
    int reach;                       /* cells the surface support spans from a particle's cell */
    int tension;                     /* 1: the normal (curvature) force */
    int reaction;                    /* 1: surface_force records the liquid's CSF force for the
                                        grains' reaction (surface_contact_pull) */
    int marangoni;                   /* 1: the tangential force d sigma/dT grad_s T |n| */
    int temperature;                 /* 1: sigma or the solid colour depends on T (the temperature
                                        buffer is read) */
    int gas;                         /* 1: the case has a gas (the CSF force of Fuchs et al. 2022 Eq. 24) */
    int form;                        /* TENSION_FORM_* with the tension; TENSION_FORM_CSF without */
    int wetting;                     /* 1: a material has a contact angle (Fuchs et al. 2022
                                        Eqs. 27-29); 0: every particle is one colour */
    int blocks[3];                   /* blocks of `reach` cells per axis (1 on unused axes; the
                                        last block of an axis takes the remaining cells) */
    int near_blocks;                 /* particles more blocks than this from the nearest liquid
                                        take no part in the surface terms (SURFACE_NEAR_BLOCKS;
                                        more: every particle takes part, and takes a normal) */
} surface_params;

/* A particle's Shepard sum reaches the liquid's forces through three
 * gathers of the surface support (normal, curvature, force), and a block is
 * at least one support wide, so three blocks suffice. */
#define SURFACE_NEAR_BLOCKS 3

/* The number of blocks, on the host and in the kernels. */
static inline int surface_block_count(const surface_params *p)
{
    return p->blocks[0] * p->blocks[1] * p->blocks[2];
}

#endif
