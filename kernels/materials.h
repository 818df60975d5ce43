/* Per-material constants as the kernels see them: a table of
 * MATERIAL_STRIDE reals per material, indexed by the particle's material id.
 * The host fills it from the case (host/sim.c, upload_materials). */
#ifndef AMSPH_MATERIALS_H
#define AMSPH_MATERIALS_H

#define MATERIAL_SOUND_SPEED 0 /* artificial speed of sound c0, m/s */
#define MATERIAL_VISCOSITY 1   /* dynamic viscosity mu of the liquid, Pa s */
#define MATERIAL_MUSHY_VISCOSITY 2 /* mu at liquid fraction 0, Pa s */
/* surface tension sigma(T) = sigma0 + slope (T - T_ref)
 *   - R T Gamma_s ln(1 + k_l a_s exp(-dH0 / (R T))), at least sigma_min
 * (Sahoo, DebRoy & McNallan 1988; Russell 2018 Eq. 4.2), kernels/surface.cl */
#define MATERIAL_SURFACE_TENSION 3       /* sigma0, N/m */
#define MATERIAL_SURFACE_TENSION_SLOPE 4 /* d sigma/dT of the clean surface (-A), N/(m K) */
#define MATERIAL_SURFACE_TENSION_TREF 5  /* T_ref, K */
#define MATERIAL_SURFACE_TENSION_MIN 6   /* sigma_min, N/m */
#define MATERIAL_SURFACTANT_EXCESS 7     /* Gamma_s, mol/m^2; 0: no surfactant term */
#define MATERIAL_SURFACTANT_LOG_K 8      /* ln(k_l a_s) */
#define MATERIAL_SURFACTANT_ENTHALPY 9   /* dH0, J/mol */
/* evaporation (Fuchs et al. 2022 Eqs. 10, 18), kernels/vapour.h */
#define MATERIAL_RECOIL_PRESSURE 10    /* C_P, Pa; 0: the material does not evaporate */
#define MATERIAL_RECOIL_TEMPERATURE 11 /* C_T, K */
#define MATERIAL_BOILING_TEMPERATURE 12 /* T_v, K */
#define MATERIAL_VAPOUR_HEAT 13        /* h_v - h(T_h,0) with h from 0 K (thermal_table.h), J/kg */
#define MATERIAL_VAPOUR_FLUX 14        /* 0.82 c_s sqrt(C_M), sqrt(K) s/m */
/* 1: a gas (materials[].phase; Fuchs et al. 2022 Sec. 4.1), 0: liquid or solid */
#define MATERIAL_GAS 15
/* wetting (Fuchs et al. 2022 Sec. 3.3.3, Eqs. 27-29), kernels/surface.cl */
#define MATERIAL_CONTACT_ANGLE 16   /* theta0 of the liquid on solids and walls, rad; 0: not set */
#define MATERIAL_SOLID_COLOUR_LOW 17  /* a solid of the material is solid colour 1 below this, K */
#define MATERIAL_SOLID_COLOUR_HIGH 18 /* ... and 0 at this (the solidus); <= LOW: always 1 */
/* Reference density rho0(T): n points (T_i, rho0_i), T increasing, linear
 * between them and constant beyond the ends; n = 1: the constant rho0_0. */
#define MATERIAL_TABLE_POINTS 16        /* AMSPH_MAX_TABLE of host/case.h */
#define MATERIAL_DENSITY_POINTS 19      /* n, at most MATERIAL_TABLE_POINTS */
#define MATERIAL_DENSITY_TEMPERATURE 20 /* T_i, K */
#define MATERIAL_DENSITY_VALUE (MATERIAL_DENSITY_TEMPERATURE + MATERIAL_TABLE_POINTS) /* rho0_i, kg/m^3 */
#define MATERIAL_STRIDE (MATERIAL_DENSITY_VALUE + MATERIAL_TABLE_POINTS)

#ifdef AMSPH_DEVICE_H
static inline real material_value(GLOBAL const real *table, int material, int property)
{
    return table[MATERIAL_STRIDE * material + property];
}

/* Reference density rho0(T) of the isothermally incompressible fluid
 * (Russell 2018 Eq. 3.52, generalised to a table; the host's
 * amsph_material_density evaluates the same rule). Fluid kernels read it
 * per particle from the reference_density field, which this fills. */
static inline real reference_density_of_temperature(GLOBAL const real *table, int material, real temperature)
{
    GLOBAL const real *m = table + MATERIAL_STRIDE * material;
    GLOBAL const real *t = m + MATERIAL_DENSITY_TEMPERATURE;
    GLOBAL const real *rho0 = m + MATERIAL_DENSITY_VALUE;
    const int n = (int)m[MATERIAL_DENSITY_POINTS];
    if (n == 1 || temperature <= t[0])
        return rho0[0];
    for (int i = 1; i < n; ++i)
        if (temperature < t[i])
            return rho0[i - 1] + (temperature - t[i - 1]) * (rho0[i] - rho0[i - 1]) / (t[i] - t[i - 1]);
    return rho0[n - 1];
}

/* Is the material a gas: the atmosphere around the liquid, which is
 * outside it for the surface terms (kernels/colour.h, surface.cl), the
 * laser and evaporation? */
static inline int material_is_gas(GLOBAL const real *table, int material)
{
    return material_value(table, material, MATERIAL_GAS) != REAL(0.0);
}

/* Viscosity ramped through the mushy zone by the liquid fraction s (Russell
 * 2018 Sec. 3.3): mu = mu_mushy + (mu - mu_mushy) s. */
static inline real particle_viscosity(GLOBAL const real *table, int material, real s)
{
    const real mushy = material_value(table, material, MATERIAL_MUSHY_VISCOSITY);
    return mushy + (material_value(table, material, MATERIAL_VISCOSITY) - mushy) * s;
}
#endif

#endif
