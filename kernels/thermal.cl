/* Heat transfer with the specific enthalpy h as the state variable:
 *   dh_a/dt = conduction + viscous heating + (laser - radiation) / rho_a,
 * and the temperature from h through the material's enthalpy table
 * (kernels/thermal_table.h: apparent heat capacity with the latent heat
 * over the mushy interval). Conduction moves m_a dh_a = -m_b dh_b between
 * every pair, so the enthalpy ledger closes to round-off.
 *
 * Walls hold their temperature (Dirichlet); fluid and fixed solid
 * particles conduct, melt and solidify. A free surface is adiabatic unless
 * it radiates. */
#include "device.h"
#include "kinds.h"
#include "materials.h"
#include "neighbours.h"
#include "smoothing.h"
#include "thermal_params.h"
#include "thermal_table.h"
#include "vapour.h"

#define STEFAN_BOLTZMANN REAL(5.670374419e-8) /* W/(m^2 K^4) */

static inline real thermal_dot3(const real a[3], const real b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

KERNEL void enthalpy_from_temperature(GLOBAL const int *material, GLOBAL const real *temperature,
                                      int n, GLOBAL const real *table, GLOBAL real *enthalpy)
{
    FOR_EACH_ITEM(a, n)
    {
        enthalpy[a] = enthalpy_of_temperature(table, material[a], temperature[a]);
    }
}

/* Temperature (walls keep theirs), liquid fraction and conductivity from
 * the enthalpy. A material that does not melt is liquid as fluid and solid
 * otherwise. */
KERNEL void thermal_state(GLOBAL const int *kind, GLOBAL const int *material,
                          GLOBAL const real *enthalpy, int n, GLOBAL const real *table,
                          GLOBAL real *temperature, GLOBAL real *liquid_fraction,
                          GLOBAL real *conductivity)
{
    FOR_EACH_ITEM(a, n)
    {
        const int mat = material[a];
        if (kind[a] != KIND_WALL)
            temperature[a] = temperature_of_enthalpy(table, mat, enthalpy[a]);
        const real temp = temperature[a];
        liquid_fraction[a] = material_melts(table, mat) ? liquid_fraction_of_temperature(table, mat, temp)
                                                        : (kind[a] == KIND_FLUID ? REAL(1.0) : REAL(0.0));
        conductivity[a] = conductivity_of_temperature(table, mat, temp);
    }
}

/* Walls hold their temperature T_w = T(h_w) (Dirichlet). For conduction a
 * wall shows the fluid and solid next to it the mirrored temperature
 *   T~_w = 2 T_w - sum_f T_f W_wf / sum_f W_wf,
 * the temperature analogue of Adami et al.'s (2012) no-slip ghost velocity:
 * the profile continues through the boundary with T = T_w on it. A wall
 * held at T_w alone puts a kink in the profile there, and the Laplacian
 * across it makes the error first order in dx. */
KERNEL void wall_temperature(GLOBAL const real *position, GLOBAL const real *temperature,
                             GLOBAL const real *enthalpy, GLOBAL const int *kind,
                             GLOBAL const int *material, GLOBAL const int *cell, int n, grid_geometry g,
                             GLOBAL const int *cell_start, GLOBAL const real *table, thermal_params p,
                             GLOBAL real *ghost_temperature)
{
    FOR_EACH_ITEM(a, n)
    {
        real ghost = temperature[a];
        if (kind[a] == KIND_WALL) {
            int cc[3];
            grid_cell_coords(&g, cell[a], cc);
            real x_a[3];
            grid_point(position, a, x_a);
            real sum_w = REAL(0.0), sum_t = REAL(0.0);
            FOR_EACH_BODY_NEIGHBOUR(b, run, &g, cc, x_a, cell_start, SUPPORT_OVER_H * p.h)
            {
                real r_ab[3];
                grid_displacement(&run, position, b, r_ab);
                const real w = smoothing_w(sqrt(thermal_dot3(r_ab, r_ab)), p.h);
                sum_w += w;
                sum_t += w * temperature[b];
            }
            const real wall = temperature_of_enthalpy(table, material[a], enthalpy[a]);
            ghost = sum_w > REAL(0.0) ? REAL(2.0) * wall - sum_t / sum_w : wall;
        }
        ghost_temperature[a] = ghost;
    }
}

/* Conduction of one pair (Cleary & Monaghan 1999; Russell 2018 Eq. 3.45):
 *   dh_a/dt = sum_b 4 m_b / (rho_a rho_b) k_a k_b / (k_a + k_b) (T_a - T_b)
 *             (r_ab . grad_a W_ab) / (r_ab^2 + eta^2),
 * here with V_b = m_b / rho_b and without the 1 / rho_a, which the caller
 * applies. r_ab . grad_a W_ab < 0, so heat flows from hot to cold (tested:
 * a perturbation decays). */
static inline real conduction_pair(real k_a, real k_b, real t_a, real t_b, real v_b,
                                   real r_dot_grad, real r2, const thermal_params *p)
{
    const real k_sum = k_a + k_b;
    const real k_ab = k_sum > REAL(0.0) ? REAL(4.0) * k_a * k_b / k_sum : REAL(0.0);
    return v_b * k_ab * (t_a - t_b) * r_dot_grad / (r2 + p->eta2);
}

/* Viscous dissipation of a Newtonian fluid, per unit volume (the
 * tau : grad u of Russell 2018 Eqs. 3.37 and 3.43, Stokes' hypothesis):
 *   Phi = 2 mu (D : D - (tr D)^2 / d),  D = (G + G^T) / 2,
 * with the velocity gradient G = G_raw M^-1 renormalised by the moment
 * matrix (Bonet & Lok 1999),
 *   G_raw = sum_b V_b (u_b - u_a) (x) grad_a W_ab,  M = sum_b V_b (r_b - r_a) (x) grad_a W_ab,
 * exact for a linear velocity field. Russell's pairwise Eq. 3.44 gives
 * only 0.83 mu gamma^2 for a simple shear on a lattice (quintic, h = dx;
 * 0.75 for Wendland C2 at h = 1.2 dx), because the lattice neighbours along
 * the axes carry no x^2 y^2 moment. */
static inline real viscous_dissipation(const real g_raw[3][3], const real m[3][3], real mu)
{
    real inverse[3][3] = {{REAL(0.0)}};
#if AMSPH_DIM == 2
    const real det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    inverse[0][0] = m[1][1] / det;
    inverse[0][1] = -m[0][1] / det;
    inverse[1][0] = -m[1][0] / det;
    inverse[1][1] = m[0][0] / det;
#else
    const real det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            inverse[j][i] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
        }
#endif
    if (!isfinite(det) || fabs(det) < REAL(1e-6))
        return REAL(0.0); /* too few neighbours to know the gradient */
    real d[3][3], trace = REAL(0.0), dd = REAL(0.0);
    real g[3][3];
    for (int i = 0; i < AMSPH_DIM; ++i)
        for (int j = 0; j < AMSPH_DIM; ++j) {
            g[i][j] = REAL(0.0);
            for (int k = 0; k < AMSPH_DIM; ++k)
                g[i][j] += g_raw[i][k] * inverse[k][j];
        }
    for (int i = 0; i < AMSPH_DIM; ++i)
        for (int j = 0; j < AMSPH_DIM; ++j) {
            d[i][j] = REAL(0.5) * (g[i][j] + g[j][i]);
            dd += d[i][j] * d[i][j];
        }
    for (int i = 0; i < AMSPH_DIM; ++i)
        trace += d[i][i];
    return REAL(2.0) * mu * (dd - trace * trace / AMSPH_DIM);
}

/* Radiation from a free surface (Russell 2018 Eq. 3.39), per unit volume:
 *   s_rad = sigma_B eps (T^4 - T_inf^4) delta,
 * with the surface delta delta = c |grad Gamma| in place of 1 / dz: the
 * Shepard sum Gamma = sum_b V_b W_ab falls from 1 to about 1/2 across the
 * outermost particles (there is nothing outside to sum), so c = 2 would
 * make it integrate to the surface area; c = p->surface_delta makes it do so
 * exactly on a flat lattice face, the cut-off included (flat_face_delta;
 * surface_delta in thermal_params.h). */
static inline real radiation_loss(real temp, real emissivity, real delta, const thermal_params *p)
{
    const real t2 = temp * temp, ambient2 = p->ambient_temperature * p->ambient_temperature;
    return STEFAN_BOLTZMANN * emissivity * (t2 * t2 - ambient2 * ambient2) * delta;
}

/* The surface delta of a detached particle, one with no material neighbour
 * nearer than DETACHED_SPACINGS times its own spacing V^(1/d) (spray): its
 * colour gradient sums little or nothing (exactly nothing alone, below the
 * cut-off with one neighbour two spacings off), yet all of it is free
 * surface. It radiates and evaporates as a ball of its own volume V (a
 * disc per unit depth in 2D): surface over volume
 *   delta = d / r,   r = sqrt(V / pi) in 2D,   r = cbrt(3 V / (4 pi)) in 3D.
 * Lattice neighbours (1 spacing, sqrt(2) diagonally) are nearer, so faces
 * and corners keep the colour gradient's delta. */
#define DETACHED_SPACINGS REAL(1.5)

static inline real droplet_delta(real volume)
{
#if AMSPH_DIM == 2
    const real radius = sqrt(volume / PI_REAL);
#else
    const real radius = cbrt(REAL(3.0) * volume / (REAL(4.0) * PI_REAL));
#endif
    return (real)AMSPH_DIM / radius;
}

/* (DETACHED_SPACINGS V^(1/d))^2: nearer material neighbours attach. */
static inline real attached_distance2(real volume)
{
#if AMSPH_DIM == 2
    const real spacing2 = volume;
#else
    const real spacing = cbrt(volume);
    const real spacing2 = spacing * spacing;
#endif
    return DETACHED_SPACINGS * DETACHED_SPACINGS * spacing2;
}

/* The integral across a flat face of a square (cubic) lattice of spacing dx
 * of |grad Gamma| = |sum_b V_b grad_a W_ab| over the particles whose
 * |grad Gamma| h reaches `cutoff`: sum over the rows j under the face of
 * dx |grad Gamma_j|, row j at depth (j + 1/2) dx, its neighbours every
 * lattice point at or below the face. Continuous: 1/2 (Gamma falls from 1
 * to 1/2); the sampled rows, the kernel's lattice moments and the cut-off
 * make it a few percent less. The surface deltas of the radiation and of
 * the laser's surface absorption divide by it. One work item. */
KERNEL void flat_face_delta(real h, real dx, real cutoff, GLOBAL real *integral)
{
    FOR_EACH_ITEM(item, 1)
    {
        const real support2 = SUPPORT_OVER_H * SUPPORT_OVER_H * h * h;
        const int reach = (int)ceil(SUPPORT_OVER_H * h / dx);
        const int lateral3 = AMSPH_DIM == 3 ? reach : 0;
        real volume = dx;
        for (int d = 1; d < AMSPH_DIM; ++d)
            volume *= dx;
        real sum = REAL(0.0);
        for (int j = 0; j <= reach; ++j) {
            real grad = REAL(0.0); /* along the outward normal; across it the sum cancels */
            for (int k = 0; k <= j + reach; ++k)
                for (int i = -reach; i <= reach; ++i)
                    for (int l = -lateral3; l <= lateral3; ++l) {
                        const real z = (real)(k - j) * dx; /* z_a - z_b, up the normal */
                        const real r2 = (real)(i * i + l * l) * dx * dx + z * z;
                        if (r2 > REAL(0.0) && r2 < support2)
                            grad += volume * smoothing_grad_factor(sqrt(r2), h) * z;
                    }
            if (fabs(grad) * h >= cutoff)
                sum += dx * fabs(grad);
        }
        integral[item] = sum;
    }
}

/* The enthalpy rate of every particle (walls too: their rate is the heat
 * they give the material, booked in the ledger, never applied) and the
 * powers the energy ledger integrates, per particle, in W:
 *   power_laser     m_a s_laser / rho_a          absorbed by fluid and solid
 *   power_radiation m_a s_rad / rho_a            lost by fluid and solid
 *   power_evaporation m_a q_v delta / rho_a      lost by fluid and solid (Fuchs
 *                                                Eq. 18, kernels/vapour.h)
 *   power_wall      -m_w dh_w/dt of a wall       given by the wall (Dirichlet)
 *   power_viscous   m_a Phi / rho_a              heating of the fluid
 * The losses take the surface delta of the colour gradient (surface_delta),
 * of a ball for a detached particle (droplet_delta).
 * Conduction uses the walls' mirrored temperature (wall_temperature) on
 * both sides of a pair. laser_power is the absorbed laser power per volume
 * (laser module; zeros without a laser). wall_velocity is the no-slip ghost velocity of walls
 * (read only with viscous heating). */
KERNEL void heat_rate(GLOBAL const real *position, GLOBAL const real *velocity,
                      GLOBAL const real *wall_velocity, GLOBAL const real *density,
                      GLOBAL const real *mass, GLOBAL const real *temperature,
                      GLOBAL const real *ghost_temperature,
                      GLOBAL const real *conductivity, GLOBAL const real *liquid_fraction,
                      GLOBAL const real *laser_power, GLOBAL const int *kind,
                      GLOBAL const int *material, GLOBAL const int *cell, int n, grid_geometry g,
                      GLOBAL const int *cell_start, GLOBAL const real *materials,
                      GLOBAL const real *table, thermal_params p, GLOBAL real *enthalpy_rate,
                      GLOBAL real *power_laser, GLOBAL real *power_radiation,
                      GLOBAL real *power_evaporation, GLOBAL real *power_wall,
                      GLOBAL real *power_viscous)
{
    FOR_EACH_ITEM(a, n)
    {
        int cc[3];
        grid_cell_coords(&g, cell[a], cc);
        const int wall_a = kind[a] == KIND_WALL;
        const int heats = p.viscous_heating && kind[a] == KIND_FLUID;
        const real rho_a = density[a], t_a = ghost_temperature[a], k_a = conductivity[a];
        real conduction = REAL(0.0);
        real grad_gamma[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        const real attached2 = attached_distance2(mass[a] / rho_a);
        int attached = 0; /* material neighbours nearer than attached_distance2 */
        real grad_u[3][3] = {{REAL(0.0)}}, moment[3][3] = {{REAL(0.0)}};
        real x_a[3];
        grid_point(position, a, x_a);
        const real support = SUPPORT_OVER_H * p.h;
        FOR_EACH_NEIGHBOUR(b, run, &g, cc, x_a, cell_start, support)
        {
            real r_ab[3];
            grid_displacement(&run, position, b, r_ab);
            const real r2 = thermal_dot3(r_ab, r_ab);
            if (b != a && r2 < support * support) {
                const real f = smoothing_grad_factor(sqrt(r2), p.h); /* grad_a W_ab = f r_ab */
                const real v_b = mass[b] / density[b];
                conduction += conduction_pair(k_a, conductivity[b], t_a, ghost_temperature[b], v_b, f * r2, r2, &p);
                if (!material_is_gas(materials, material[b])) { /* the colour of kernels/colour.h */
                    attached += r2 < attached2;
                    for (int d = 0; d < 3; ++d)
                        grad_gamma[d] += v_b * f * r_ab[d];
                }
                if (heats) {
                    const int fluid_b = kind[b] == KIND_FLUID;
                    for (int i = 0; i < 3; ++i) {
                        const real u_ba = (fluid_b ? velocity[3 * b + i] : wall_velocity[3 * b + i]) - velocity[3 * a + i];
                        for (int j = 0; j < 3; ++j) {
                            grad_u[i][j] += v_b * u_ba * f * r_ab[j];
                            moment[i][j] -= v_b * r_ab[i] * f * r_ab[j];
                        }
                    }
                }
            }
        }
        conduction /= rho_a;
        const real viscous =
            heats ? viscous_dissipation(grad_u, moment, particle_viscosity(materials, material[a], liquid_fraction[a])) / rho_a
                  : REAL(0.0);
        const real m_a = mass[a], temp_a = temperature[a];
        const int mat = material[a];
        const real delta = wall_a || material_is_gas(materials, mat) ? REAL(0.0)
                           : attached == 0 ? droplet_delta(m_a / rho_a)
                                                      : surface_delta(sqrt(thermal_dot3(grad_gamma, grad_gamma)), &p);
        const real emissivity = thermal_material(table, mat)[THERMAL_EMISSIVITY];
        const real radiation = p.radiation ? radiation_loss(temp_a, emissivity, delta, &p) / rho_a : REAL(0.0);
        const real evaporation =
            p.evaporative_cooling && delta > REAL(0.0)
                ? evaporation_heat_flux(materials, mat, temp_a, enthalpy_of_temperature(table, mat, temp_a)) * delta / rho_a
                : REAL(0.0);
        const real laser = wall_a ? REAL(0.0) : laser_power[a] / rho_a;
        enthalpy_rate[a] = conduction + viscous + laser - radiation - evaporation;
        power_laser[a] = m_a * laser;
        power_radiation[a] = m_a * radiation;
        power_evaporation[a] = m_a * evaporation;
        power_wall[a] = wall_a ? -m_a * conduction : REAL(0.0);
        power_viscous[a] = m_a * viscous;
    }
}

/* h = h_start + dt_start rate_start + dt_now rate for fluid and solid:
 * explicit Euler (dt_start = 0) or one trapezoidal midpoint iterate
 * (dt_start = dt_now = dt / 2; Russell 2018 Alg. 3.1). */
KERNEL void advance_enthalpy(GLOBAL const int *kind, GLOBAL const real *enthalpy_start,
                             GLOBAL const real *rate_start, GLOBAL const real *rate, int n,
                             real dt_start, real dt_now, GLOBAL real *enthalpy)
{
    FOR_EACH_ITEM(a, n)
    {
        if (kind[a] != KIND_WALL)
            enthalpy[a] = enthalpy_start[a] + dt_start * rate_start[a] + dt_now * rate[a];
    }
}

/* |T - T_previous| per particle, for the convergence test of the midpoint
 * iteration. */
KERNEL void temperature_change(GLOBAL const real *temperature, GLOBAL const real *previous, int n,
                               GLOBAL real *change)
{
    FOR_EACH_ITEM(a, n)
    {
        change[a] = fabs(temperature[a] - previous[a]);
    }
}

/* m h for fluid and solid, 0 for walls: the enthalpy of the material. */
KERNEL void material_enthalpy(GLOBAL const int *kind, GLOBAL const real *mass,
                              GLOBAL const real *enthalpy, int n, GLOBAL real *out)
{
    FOR_EACH_ITEM(a, n)
    {
        out[a] = kind[a] == KIND_WALL ? REAL(0.0) : mass[a] * enthalpy[a];
    }
}

/* After a step: the peak temperature so far, and, with the fluid module,
 * the phase rule: a fixed solid of a melting material whose liquid fraction
 * rises above 0 becomes fluid (at rest); a fluid particle of a melting
 * material back at liquid fraction 0 becomes a fixed solid and stops. The
 * mushy zone is fluid, its viscosity ramped by the liquid fraction. */
KERNEL void finish_thermal_step(GLOBAL const int *material, GLOBAL const real *temperature,
                                GLOBAL const real *liquid_fraction, int n, GLOBAL const real *table,
                                thermal_params p, GLOBAL int *kind, GLOBAL real *velocity,
                                GLOBAL real *peak_temperature)
{
    FOR_EACH_ITEM(a, n)
    {
        peak_temperature[a] = fmax(peak_temperature[a], temperature[a]);
        if (p.phase_change_kinds && material_melts(table, material[a])) {
            const real s = liquid_fraction[a];
            if (kind[a] == KIND_SOLID && s > REAL(0.0)) {
                kind[a] = KIND_FLUID;
            } else if (kind[a] == KIND_FLUID && s <= REAL(0.0)) {
                kind[a] = KIND_SOLID;
                for (int d = 0; d < 3; ++d)
                    velocity[3 * a + d] = REAL(0.0);
            }
        }
    }
}

/* A prescribed temperature, the same on every particle (the temperature
 * history of cases without the thermal module, host/material.h). */
KERNEL void uniform_temperature(int n, real value, GLOBAL real *temperature)
{
    FOR_EACH_ITEM(a, n)
    {
        temperature[a] = value;
    }
}
