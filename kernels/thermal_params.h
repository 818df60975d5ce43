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
    int radiation;                         /* 1: free surfaces radiate */
    int viscous_heating;                   /* 1: viscous dissipation heats the fluid */
    int phase_change_kinds;                /* 1: melted solid becomes fluid and back */
} thermal_params;

#endif
