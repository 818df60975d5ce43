/* Per-material constants as the kernels see them: a table of
 * MATERIAL_STRIDE reals per material, indexed by the particle's material id.
 * The host fills it from the case (host/sim.c, material_table). */
#ifndef AMSPH_MATERIALS_H
#define AMSPH_MATERIALS_H

#define MATERIAL_DENSITY 0     /* reference density rho0, kg/m^3 */
#define MATERIAL_SOUND_SPEED 1 /* artificial speed of sound c0, m/s */
#define MATERIAL_VISCOSITY 2   /* dynamic viscosity mu of the liquid, Pa s */
#define MATERIAL_MUSHY_VISCOSITY 3 /* mu at liquid fraction 0, Pa s */
#define MATERIAL_STRIDE 4

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
