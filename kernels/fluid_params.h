/* Settings of the fluid module as the kernels see them, passed by value;
 * the host includes it with AMSPH_SHARED_REAL = amsph_real. */
#ifndef AMSPH_FLUID_PARAMS_H
#define AMSPH_FLUID_PARAMS_H

#ifndef AMSPH_SHARED_REAL
#define AMSPH_SHARED_REAL real
#endif

#include "fluid_options.h"

typedef struct {
    AMSPH_SHARED_REAL h;                   /* smoothing length h0 (walls, and every particle with SMOOTHING_FIXED), m */
    AMSPH_SHARED_REAL h_max;               /* largest smoothing length a pair loop reaches: h, or with
                                              SMOOTHING_VOLUME max_smoothing_ratio h, m */
    int smoothing_length;                  /* SMOOTHING_* */
    AMSPH_SHARED_REAL eta2;                /* 0.01 h0^2 (with SMOOTHING_VOLUME too), keeps 1/r^2 finite, m^2 */
    AMSPH_SHARED_REAL delta;               /* delta-SPH coefficient (typically 0.1) */
    AMSPH_SHARED_REAL background_pressure; /* added to every fluid pressure, Pa */
    AMSPH_SHARED_REAL artificial_alpha;    /* Monaghan's alpha */
    AMSPH_SHARED_REAL gravity[3];          /* m/s^2 */
    int density_diffusion;                 /* DIFFUSION_* */
    int continuity;                        /* CONTINUITY_* */
    int pressure_gradient;                 /* PRESSURE_* */
    int viscosity;                         /* VISCOSITY_* */
    int wall_slip;                         /* WALL_* */
    int clamp_negative_pressure;           /* 1: p >= background pressure */
    AMSPH_SHARED_REAL tensile_correction;  /* Monaghan (2000) epsilon; 0: off */
    AMSPH_SHARED_REAL dx;                  /* initial particle spacing, m */
    AMSPH_SHARED_REAL shifting;            /* particle shifting coefficient A; 0: off */
    int gas_density;                       /* GAS_DENSITY_* */
    AMSPH_SHARED_REAL lattice_shepard;     /* Gamma inside the initial lattice (lattice_shepard_sum), with
                                              GAS_DENSITY_SUMMATION; else 0 */
    AMSPH_SHARED_REAL transport_pressure;  /* p_tv of the transport velocity (Adami et al. 2013 Eq. 13), Pa; 0: off */
    AMSPH_SHARED_REAL barrier_stiffness;   /* k_b of Fuchs et al. 2022 Eq. 34; 0: off */
    AMSPH_SHARED_REAL barrier_damping;     /* d_b */
    AMSPH_SHARED_REAL barrier_distance;    /* r_b, m */
    int one_pass;                          /* 1: fluid_forces evaluates the continuity sums too
                                              (fluid.integration: verlet) */
    int uniform_material;                  /* 1: every particle has the one material of the case,
                                              whose rho0 does not vary: a pair term reads no
                                              neighbour's material or rho0 */
} fluid_params;

#endif
