/* The colour gradient of the material at particle a,
 *   grad Gamma_a = sum_b V_b grad_a W_ab,   V_b = m_b / rho_b,
 * over every particle but gas (fluid, solid and wall are all material, a
 * gas is outside like the void, so it is nonzero only within a support of a
 * free surface or a liquid-gas interface, where it points into the
 * material), at smoothing length h; b = a adds nothing (grad W vanishes at
 * r = 0). The surface laser (Fuchs et al. 2022 Eq. 17, kernels/laser.cl) and
 * the recoil force (Fuchs Eq. 30, kernels/evaporation.cl) take their
 * normals and surface delta from it. */
#ifndef AMSPH_COLOUR_H
#define AMSPH_COLOUR_H

#include "device.h"
#include "materials.h"
#include "neighbours.h"
#include "smoothing.h"

static inline void colour_gradient(GLOBAL const real *position, GLOBAL const real *mass,
                                   GLOBAL const real *density, GLOBAL const int *material,
                                   GLOBAL const real *materials, const grid_geometry *g,
                                   GLOBAL const int *cell_start, int cell_a, int a, real h, real grad[3])
{
    int cc[3];
    grid_cell_coords(g, cell_a, cc);
    const real support = SUPPORT_OVER_H * h, support2 = support * support;
    real x_a[3];
    grid_point(position, a, x_a);
    for (int d = 0; d < 3; ++d)
        grad[d] = REAL(0.0);
    FOR_EACH_NEIGHBOUR(b, run, g, cc, x_a, cell_start, support)
    {
        real r_ab[3], r2;
        if (!material_is_gas(materials, material[b]) && grid_pair_within(&run, position, b, support2, r_ab, &r2)) {
            const real f = smoothing_grad_factor(sqrt(r2), h) * mass[b] / density[b];
            for (int d = 0; d < 3; ++d)
                grad[d] += f * r_ab[d];
        }
    }
}

#endif
