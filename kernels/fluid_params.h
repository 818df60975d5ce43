/* Settings of the fluid module as the kernels see them, passed by value;
 * the host includes it with AMSPH_SHARED_REAL = amsph_real. */
#ifndef AMSPH_FLUID_PARAMS_H
#define AMSPH_FLUID_PARAMS_H

#ifndef AMSPH_SHARED_REAL
#define AMSPH_SHARED_REAL real
#endif

#define DIFFUSION_NONE 0
#define DIFFUSION_MOLTENI 1 /* diffuses rho (Molteni & Colagrossi 2009) */
#define DIFFUSION_RUSSELL 2 /* diffuses rho - rho0 (Russell 2018 Eq. 3.53) */

#define PRESSURE_RENORMALISED 0 /* Russell 2018 Eq. 3.17 */
#define PRESSURE_SYMMETRIC 1

#define VISCOSITY_LAMINAR 0    /* Morris et al. 1997, harmonic-mean viscosity */
#define VISCOSITY_ARTIFICIAL 1 /* Monaghan 1992 */

#define WALL_NO_SLIP 0
#define WALL_FREE_SLIP 1

typedef struct {
    AMSPH_SHARED_REAL h;                   /* smoothing length, m */
    AMSPH_SHARED_REAL eta2;                /* 0.01 h^2, keeps 1/r^2 finite, m^2 */
    AMSPH_SHARED_REAL delta;               /* delta-SPH coefficient (typically 0.1) */
    AMSPH_SHARED_REAL background_pressure; /* added to every fluid pressure, Pa */
    AMSPH_SHARED_REAL artificial_alpha;    /* Monaghan's alpha */
    AMSPH_SHARED_REAL gravity[3];          /* m/s^2 */
    int density_diffusion;                 /* DIFFUSION_* */
    int pressure_gradient;                 /* PRESSURE_* */
    int viscosity;                         /* VISCOSITY_* */
    int wall_slip;                         /* WALL_* */
} fluid_params;

#endif
