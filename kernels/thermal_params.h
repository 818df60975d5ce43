/* Settings of the thermal module as the kernels see them, passed by value;
 * the host includes it with AMSPH_SHARED_REAL = amsph_real. */
#ifndef AMSPH_THERMAL_PARAMS_H
#define AMSPH_THERMAL_PARAMS_H

#ifndef AMSPH_SHARED_REAL
#define AMSPH_SHARED_REAL real
#endif

typedef struct {
    AMSPH_SHARED_REAL h;                   /* smoothing length, m */
    AMSPH_SHARED_REAL eta2;                /* 0.01 h^2, keeps 1/r^2 finite, m^2 */
    AMSPH_SHARED_REAL ambient_temperature; /* T_inf of the radiation, K */
    AMSPH_SHARED_REAL surface_cutoff;      /* |grad Gamma| h below this: not a surface */
    AMSPH_SHARED_REAL surface_delta;       /* delta = this |grad Gamma| (flat_face_delta) */
    AMSPH_SHARED_REAL evaporation_temperature; /* hotter particles are removed, K; 0: none */
    int radiation;                         /* 1: free surfaces radiate */
    int evaporative_cooling;               /* 1: free surfaces lose the heat of evaporation */
    int recoil_pressure;                   /* 1: the recoil force on free surfaces of fluid */
    int viscous_heating;                   /* 1: viscous dissipation heats the fluid */
    int phase_change_kinds;                /* 1: melted solid becomes fluid and back */
} thermal_params;

#ifdef AMSPH_DEVICE_H
/* The surface delta of a particle with colour gradient size |grad Gamma|
 * (grad Gamma = sum_b V_b grad_a W_ab over every particle, pointing into
 * the material): c |grad Gamma|, with c = p->surface_delta from
 * flat_face_delta (kernels/thermal.cl) so that it integrates to 1 across a
 * flat lattice face; 0 below the cut-off |grad Gamma| h (the interior). */
static inline real surface_delta(real grad_gamma, const thermal_params *p)
{
    return grad_gamma * p->h < p->surface_cutoff ? REAL(0.0) : p->surface_delta * grad_gamma;
}
#endif

#endif
