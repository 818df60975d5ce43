/* Mobile powder grains as rigid bodies (Fuchs et al. 2022 Sec. 2.2, 3.4):
 * the record of one grain in the grain buffer, GRAIN_RECORD reals each, and
 * the settings the kernels see. The host includes it with
 * AMSPH_SHARED_REAL = amsph_real. */
#ifndef AMSPH_GRAIN_PARAMS_H
#define AMSPH_GRAIN_PARAMS_H

#ifndef AMSPH_SHARED_REAL
#define AMSPH_SHARED_REAL real
#endif

#define GRAIN_MASS 0              /* m_k, kg (2D: kg/m); 0 once the grain has melted */
#define GRAIN_CENTRE 1            /* r_k, centre of mass, m (3) */
#define GRAIN_VELOCITY 4          /* u_k, m/s (3) */
#define GRAIN_SPIN 7              /* omega_k, rad/s (3; 2D: z only) */
#define GRAIN_FORCE 10            /* f_k, N (3) */
#define GRAIN_TORQUE 13           /* m_k about r_k, N m (3) */
#define GRAIN_INERTIA 16          /* I_k about r_k: xx, yy, zz, xy, xz, yz (6), kg m^2 */
#define GRAIN_ANGULAR_MOMENTUM 22 /* L_k = I_k omega_k about r_k, kg m^2/s (3), what the kicks integrate */
#define GRAIN_PARTICLES 25        /* particles of the grain */
#define GRAIN_RECORD 26

/* Particles of no grain carry this in the `grain` field. */
#define GRAIN_NONE (-1)

typedef struct {
    AMSPH_SHARED_REAL stiffness;   /* k_c of Fuchs Eq. 39, kg/s^2 */
    AMSPH_SHARED_REAL damping;     /* d_c of Fuchs Eq. 39, kg/s */
    AMSPH_SHARED_REAL distance;    /* contact distance (Fuchs: dx), m */
    AMSPH_SHARED_REAL particle_inertia_factor; /* I_r = factor m_r (Fuchs Eq. 36), m^2 */
    AMSPH_SHARED_REAL gravity[3];  /* m/s^2 */
} grain_params;

#endif
