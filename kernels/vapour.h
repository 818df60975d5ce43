/* Evaporation at free surfaces (Fuchs et al. 2022 §2.1.2 and §2.3), from a
 * material's constants (kernels/materials.h):
 *   recoil pressure  p_v(T) = C_P exp(-C_T (1/T - 1/T_v))            (Eq. 10)
 *   vapour mass flux m_v(T) = 0.82 c_s p_v(T) sqrt(C_M / T)          (Eq. 18)
 *   heat flux        q_v(T) = m_v(T) (h_v + h(T) - h(T_h,0))         (Eq. 18)
 * per unit area of the surface; the kernels spread them with the surface
 * delta of thermal_params.h. A material with C_P = 0 does not evaporate. */
#ifndef AMSPH_VAPOUR_H
#define AMSPH_VAPOUR_H

#include "materials.h"

/* p_v(T), Pa; 0 at T = 0 K (the limit) and for a material that does not
 * evaporate. Below about T_v / 4 it underflows to 0 in float. */
static inline real recoil_pressure(GLOBAL const real *materials, int material, real t)
{
    const real c_p = material_value(materials, material, MATERIAL_RECOIL_PRESSURE);
    if (!(c_p > REAL(0.0)) || !(t > REAL(0.0)))
        return REAL(0.0);
    const real c_t = material_value(materials, material, MATERIAL_RECOIL_TEMPERATURE);
    const real t_v = material_value(materials, material, MATERIAL_BOILING_TEMPERATURE);
    return c_p * exp(-c_t * (REAL(1.0) / t - REAL(1.0) / t_v));
}

/* q_v(T) = m_v(T) (h_v + h(T) - h(T_h,0)), W/m^2, with h the particle's
 * specific enthalpy from 0 K (the thermal tables' reference). */
static inline real evaporation_heat_flux(GLOBAL const real *materials, int material, real t, real h)
{
    const real p_v = recoil_pressure(materials, material, t);
    if (!(p_v > REAL(0.0)))
        return REAL(0.0);
    const real mass_flux = material_value(materials, material, MATERIAL_VAPOUR_FLUX) * p_v / sqrt(t);
    return mass_flux * (material_value(materials, material, MATERIAL_VAPOUR_HEAT) + h);
}

#endif
