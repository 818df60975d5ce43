/* Evaporation at free surfaces (kernels/vapour.h for the model):
 *   recoil_force     the recoil pressure's force on fluid (Fuchs et al. 2022
 *                    Eqs. 10, 30); the heat loss of Eq. 18 is a term of
 *                    heat_rate (kernels/thermal.cl)
 *   evaporate_hot    the simpler option: particles above a cut-off
 *                    temperature leave (the damage parameter Russell 2018
 *                    proposes at the opening of ch. 3) */
#include "colour.h"
#include "device.h"
#include "kinds.h"
#include "neighbours.h"
#include "smoothing.h"
#include "thermal_params.h"
#include "thermal_table.h"
#include "vapour.h"
#include "vec3.h"

/* The recoil force per volume (Fuchs Eq. 10; Eq. 30 is its discrete form
 * F_a = -V_a p_v(T_a) n_a delta_a):
 *   f_a = -p_v(T_a) n_a delta_a = p_v(T_a) c grad Gamma_a,
 * with the outward unit normal n_a = -grad Gamma_a / |grad Gamma_a|, the
 * colour gradient grad Gamma_a = sum_b V_b grad_a W_ab over every particle
 * but gas (fluid, solid and wall are all material, so it lives on free
 * surfaces and liquid-gas interfaces only) and the surface delta c |grad Gamma_a| of the radiation
 * (surface_delta, thermal_params.h): on a flat lattice face the force per
 * area is p_v exactly, pointing into the material. Adds f_a / rho_a to the
 * acceleration of fluid particles (not of gas, which does not evaporate). */
KERNEL void recoil_force(GLOBAL const real *position, GLOBAL const real *density,
                         GLOBAL const real *mass, GLOBAL const real *temperature,
                         GLOBAL const int *kind, GLOBAL const int *material,
                         GLOBAL const int *cell, int n, grid_geometry g,
                         GLOBAL const int *cell_start, GLOBAL const real *materials,
                         thermal_params p, GLOBAL real *acceleration)
{
    FOR_EACH_ITEM(a, n)
    {
        if (kind[a] == KIND_FLUID && !material_is_gas(materials, material[a])) {
            real grad_gamma[3];
            colour_gradient(position, mass, density, material, materials, &g, cell_start, cell[a], a, p.h, grad_gamma);
            const real size = sqrt(dot3(grad_gamma, grad_gamma));
            const real delta = surface_delta(size, &p);
            if (delta > REAL(0.0)) {
                const real scale = recoil_pressure(materials, material[a], temperature[a]) * delta / size / density[a];
                for (int d = 0; d < 3; ++d)
                    acceleration[3 * a + d] += scale * grad_gamma[d];
            }
        }
    }
}

/* Fluid and solid particles hotter than p.evaporation_temperature leave:
 * their position becomes NaN, so the next sort drops them (grid_bin), and
 * removed_enthalpy gets their m h (0 for the others) and removed 1 (else 0)
 * for the energy ledger and the count. */
KERNEL void evaporate_hot(GLOBAL const int *kind, GLOBAL const real *temperature,
                          GLOBAL const real *mass, GLOBAL const real *enthalpy, int n,
                          thermal_params p, GLOBAL real *position,
                          GLOBAL real *removed_enthalpy, GLOBAL real *removed)
{
    FOR_EACH_ITEM(a, n)
    {
        const int leaves = kind[a] != KIND_WALL && temperature[a] > p.evaporation_temperature;
        removed_enthalpy[a] = leaves ? mass[a] * enthalpy[a] : REAL(0.0);
        removed[a] = leaves ? REAL(1.0) : REAL(0.0);
        if (leaves)
            for (int d = 0; d < 3; ++d)
                position[3 * a + d] = NAN;
    }
}
