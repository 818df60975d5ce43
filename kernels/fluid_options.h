/* Choices of the fluid module, shared by the case parser and the kernels. */
#ifndef AMSPH_FLUID_OPTIONS_H
#define AMSPH_FLUID_OPTIONS_H

#define DIFFUSION_NONE 0
#define DIFFUSION_MOLTENI 1 /* diffuses rho (Molteni & Colagrossi 2009) */
#define DIFFUSION_RUSSELL 2 /* diffuses rho - rho0 (Russell 2018 Eq. 3.53) */
#define DIFFUSION_FOURTAKAS 3 /* diffuses rho - rho_hydrostatic (Fourtakas et al. 2019) */

#define PRESSURE_RENORMALISED 0 /* Russell 2018 Eq. 3.17 */
#define PRESSURE_SYMMETRIC 1
#define PRESSURE_MULTIPHASE 2 /* Fuchs et al. 2022 Eq. 23 (Adami, Hu & Adams 2012, 2013) */

#define VISCOSITY_LAMINAR 0    /* Morris et al. 1997, harmonic-mean viscosity */
#define VISCOSITY_ARTIFICIAL 1 /* Monaghan 1992 */

#define WALL_NO_SLIP 0
#define WALL_FREE_SLIP 1

#define CONTINUITY_PLAIN 0     /* rho_a sum_b u_ab . grad_a W_ab V_b (Russell 2018 Eq. 3.14) */
#define CONTINUITY_CORRECTED 1 /* the same with the kernel gradient corrected (Bonet & Lok 1999) */

#define GAS_DENSITY_CONTINUITY 0 /* the gas's density from the continuity equation, as the liquid's */
#define GAS_DENSITY_SUMMATION 1  /* rho_a = m_a sum_b W_ab (Adami, Hu & Adams 2013), over the lattice's sum */

#define SMOOTHING_FIXED 0  /* h = h_over_dx dx for every particle */
#define SMOOTHING_VOLUME 1 /* fluid particles: h_a = h0 (V_a / V0)^(1/d) (Russell 2018 Eq. 3.54) */

#define INTEGRATION_LEAPFROG 0 /* kick-drift-kick, density after the drift (Russell 2018 Eq. 3.55) */
#define INTEGRATION_VERLET 1   /* Verlet (1967) as DualSPHysics has it: one neighbour pass per step */

/* The nearest-neighbour distance (the `closest` buffer) of a fluid particle
 * with no other particle within its support: a lone particle. */
#define NO_NEIGHBOUR REAL(1e30)

#endif
