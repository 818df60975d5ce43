/* Per-material constants as the kernels see them: a table of
 * MATERIAL_STRIDE reals per material, indexed by the particle's material id.
 * The host fills it from the case (host/sim.c, material_table). */
#ifndef AMSPH_MATERIALS_H
#define AMSPH_MATERIALS_H

#define MATERIAL_DENSITY 0     /* reference density rho0, kg/m^3 */
#define MATERIAL_SOUND_SPEED 1 /* artificial speed of sound c0, m/s */
#define MATERIAL_VISCOSITY 2   /* dynamic viscosity mu of the liquid, Pa s */
#define MATERIAL_MUSHY_VISCOSITY 3 /* mu at liquid fraction 0, Pa s */
/* surface tension sigma(T) = sigma0 + slope (T - T_ref)
 *   - R T Gamma_s ln(1 + k_l a_s exp(-dH0 / (R T))), at least sigma_min
 * (Sahoo, DebRoy & McNallan 1988; Russell 2018 Eq. 4.2), kernels/surface.cl */
#define MATERIAL_SURFACE_TENSION 4       /* sigma0, N/m */
#define MATERIAL_SURFACE_TENSION_SLOPE 5 /* d sigma/dT of the clean surface (-A), N/(m K) */
#define MATERIAL_SURFACE_TENSION_TREF 6  /* T_ref, K */
#define MATERIAL_SURFACE_TENSION_MIN 7   /* sigma_min, N/m */
#define MATERIAL_SURFACTANT_EXCESS 8     /* Gamma_s, mol/m^2; 0: no surfactant term */
#define MATERIAL_SURFACTANT_LOG_K 9      /* ln(k_l a_s) */
#define MATERIAL_SURFACTANT_ENTHALPY 10  /* dH0, J/mol */
#define MATERIAL_STRIDE 11

#ifdef AMSPH_DEVICE_H
static inline real material_value(GLOBAL const real *table, int material, int property)
{
    return table[MATERIAL_STRIDE * material + property];
}

/* Reference density rho0 of a particle: the hook where rho0(T) of the
 * isothermally incompressible fluid (Russell 2018 Eq. 3.52) enters. */
static inline real reference_density(GLOBAL const real *table, int material)
{
    return material_value(table, material, MATERIAL_DENSITY);
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
