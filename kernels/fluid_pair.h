/* The pressure and viscous acceleration of one fluid particle a by one
 * neighbour b, shared by the fluid forces (kernels/fluid.cl) and the
 * coupling forces on rigid grains (kernels/grains.cl), which take the
 * reaction -m_a a_ab of every fluid neighbour a (Fuchs et al. 2022
 * Sec. 3.4.2), so that the exchange conserves momentum exactly. */
#ifndef AMSPH_FLUID_PAIR_H
#define AMSPH_FLUID_PAIR_H

#include "device.h"
#include "fluid_params.h"
#include "kinds.h"
#include "materials.h"
#include "smoothing.h"
#include "vec3.h"

/* The smoothing length of particle a: with SMOOTHING_VOLUME its own, from
 * its volume (kernels/fluid.cl volume_smoothing_length; walls and solids
 * h0), else h0 (the buffer, then a stand-in, is not read). */
static inline real particle_smoothing_length(GLOBAL const real *smoothing_length, int a, const fluid_params *p)
{
    return p->smoothing_length == SMOOTHING_VOLUME ? smoothing_length[a] : p->h;
}

/* The smoothing length of a pair, the mean h_ab = (h_a + h_b) / 2 (Benz
 * 1990; Monaghan 2005, Rep. Prog. Phys. 68, 1703, on a variable h): one
 * kernel W(r_ab, h_ab) for both particles, so that grad_a W_ab = -grad_b W_ba
 * and every pair force stays equal and opposite (momentum is conserved;
 * tested); h0 exactly where both have h0. */
static inline real pair_smoothing_length(real h_a, real h_b)
{
    return REAL(0.5) * (h_a + h_b);
}

/* The kernel's scale at the pair's h_ab: the one at h0 (taken once per
 * particle) with a fixed h, else one division per pair. */
static inline smoothing_scale pair_smoothing_scale(const smoothing_scale *at_h0, real h_a, real h_b,
                                                   const fluid_params *p)
{
    return p->smoothing_length == SMOOTHING_VOLUME ? smoothing_scale_of(pair_smoothing_length(h_a, h_b)) : *at_h0;
}

/* The volume weight w_ab of one pair in the pressure and laminar viscous
 * forces, as a numerator and a denominator (kept apart so that the
 * single-phase forms round as they always did):
 *   renormalised, symmetric: w_ab = m_b / (rho_a rho_b)        (Russell 2018 Eqs. 3.17, 3.18)
 *   multiphase:              w_ab = (V_a^2 + V_b^2) / (2 m_a)  (Fuchs et al. 2022 Eq. 23,
 *                            after Adami, Hu & Adams 2012; V = m / rho),
 * equal for a pair of equal particles; the multiphase one weighs a light gas
 * particle next to a heavy liquid one by the volumes, not by the masses. */
typedef struct {
    real num, den;
} pair_weight;

static inline pair_weight pair_weight_of(int form, real m_a, real m_b, real rho_a, real rho_b)
{
    pair_weight w;
    if (form == PRESSURE_MULTIPHASE) {
        const real v_a = m_a / rho_a, v_b = m_b / rho_b;
        w.num = v_a * v_a + v_b * v_b;
        w.den = REAL(2.0) * m_a;
    } else {
        w.num = m_b;
        w.den = rho_a * rho_b;
    }
    return w;
}

/* The pair's pressure sum P_ab of the pressure force
 *   a_a = -sum_b w_ab P_ab grad_a W_ab:
 *   renormalised: p_b / Gamma_a + p_a / Gamma_b                   (Russell 2018 Eq. 3.17)
 *   symmetric:    p_a + p_b                (the Gammas are 1 here)
 *   multiphase:   2 (rho_b p_a + rho_a p_b) / (rho_a + rho_b)      (Fuchs et al. 2022 Eq. 23:
 *                 twice the density-weighted inter-particle pressure, continuous across a
 *                 density jump); a wall or solid b enters with rho_b = rho_a, so that it
 *                 holds a gas with its Adami pressure as it holds a liquid (with its own
 *                 density, a wall 100 times denser than a gas would show the gas its own
 *                 pressure back) */
static inline real pair_pressure_sum(int form, real p_a, real p_b, real rho_a, real rho_b, real gamma_a,
                                     real gamma_b)
{
    if (form == PRESSURE_MULTIPHASE)
        return REAL(2.0) * (rho_b * p_a + rho_a * p_b) / (rho_a + rho_b);
    return p_b / gamma_a + p_a / gamma_b;
}

/* Laminar viscosity (Morris, Fox & Zhu 1997 Eq. 8) with the harmonic mean
 * 2 mu_a mu_b / (mu_a + mu_b) in place of (mu_a + mu_b) / 2 (Russell 2018
 * Eq. 3.18) for unequal viscosities:
 *   a_a += sum_b w_ab 4 mu_a mu_b / (mu_a + mu_b)
 *          (r_ab . grad_a W_ab) / (r_ab^2 + eta^2) u_ab,
 * w_ab = m_b / (rho_a rho_b), or in the multiphase form (V_a^2 + V_b^2) / (2 m_a),
 * which makes it the viscous term of Fuchs et al. 2022 Eq. 23 (pair_weight_of). */
static inline real laminar_viscosity_factor(real mu_a, real mu_b, pair_weight w, real r_dot_grad,
                                            real r2, const fluid_params *p)
{
    const real mu_sum = mu_a + mu_b;
    const real mu_ab = mu_sum > REAL(0.0) ? REAL(4.0) * mu_a * mu_b / mu_sum : REAL(0.0);
    return w.num * mu_ab / w.den * r_dot_grad / (r2 + p->eta2);
}

/* Barrier force of a pair closer than r_b (Fuchs et al. 2022 Eq. 34):
 *   F_a = sum_b (k_b g + d_b |g| dg/dt) e_ab,  g = r_b - r,  dg/dt = -e_ab . u_ab,
 * e_ab = r_ab / r, for r < r_b (else 0); a_a = F_a / m_a. Returned as the
 * factor of r_ab; off (0) without a barrier (k_b = 0). */
static inline real barrier_factor(real r, real u_dot_r, real m_a, const fluid_params *p)
{
    if (!(r < p->barrier_distance) || r <= REAL(0.0))
        return REAL(0.0);
    const real g = p->barrier_distance - r;
    const real g_rate = -u_dot_r / r;
    return (p->barrier_stiffness * g + p->barrier_damping * g * g_rate) / (m_a * r);
}

/* Monaghan (1992) artificial viscosity, for approaching pairs:
 *   Pi_ab = -alpha c h_ab min(u_ab . r_ab, 0) / (rho_mean (r_ab^2 + eta^2)),  a_a -= m_b Pi_ab grad_a W_ab
 * evaluated for every pair, as a select rather than a branch: half the
 * pairs of a flow approach, in no order a branch predictor can follow. */
static inline real artificial_viscosity(real u_dot_r, real r2, real c_mean, real rho_mean, real h_ab,
                                        const fluid_params *p)
{
    const real approach = REAL(0.5) * (u_dot_r - fabs(u_dot_r)); /* min(u . r, 0), exactly */
    return -p->artificial_alpha * c_mean * h_ab * approach / (rho_mean * (r2 + p->eta2));
}

/* Monaghan (2000) artificial pressure against the tensile instability.
 * Particles under tension (p below the background pressure p_bg) attract
 * each other, and the continuity density does not stop two of them closing
 * up: in the 2D dam break, thin films along the walls pair up to 0.3 dx at
 * negative pressures of a few hundred Pa. A short-range repulsion for the
 * tensile part of the pair's pressures,
 *   a_a -= m_b R (W_ab / W(dx))^4 grad_a W_ab   (both W at the pair's h_ab),
 *   R = eps (max(p_bg - p_a, 0) / rho_a^2 + max(p_bg - p_b, 0) / rho_b^2),
 * returned as the factor of r_ab. Between fluid particles only (against a
 * wall it pushes a film under tension off the wall, lowering its density).
 * Keep eps small: at 0.15 and above the dam break's film along the left wall
 * runs away in tension (density guard); 0.05 to 0.1 runs. */
static inline real tensile_correction(real p_a, real p_b, real rho_a, real rho_b, real m_b, real r,
                                      real f, real h_ab, const fluid_params *p)
{
    const real tension_a = fmax(p->background_pressure - p_a, REAL(0.0));
    const real tension_b = fmax(p->background_pressure - p_b, REAL(0.0));
    const real big_r = p->tensile_correction * (tension_a / (rho_a * rho_a) + tension_b / (rho_b * rho_b));
    const real fw = smoothing_w(r, h_ab) / smoothing_w(p->dx, h_ab);
    const real fw2 = fw * fw;
    return -m_b * big_r * fw2 * fw2 * f;
}

/* What the pair force needs of particle a, the fluid particle it acts on. */
typedef struct {
    real m, rho, p, mu, c, gamma;
    real h; /* particle_smoothing_length */
    real u[3];
    smoothing_scale scale; /* of W at h0 */
    int gas; /* of a gas material: walls show it their gas_wall_pressure */
} fluid_pair_side;

static inline fluid_pair_side fluid_pair_side_of(int a, GLOBAL const real *velocity, GLOBAL const real *mass,
                                                 GLOBAL const real *density, GLOBAL const real *pressure,
                                                 GLOBAL const real *gamma, GLOBAL const real *liquid_fraction,
                                                 GLOBAL const real *smoothing_length, GLOBAL const int *material,
                                                 GLOBAL const real *materials, const fluid_params *p)
{
    fluid_pair_side s;
    s.m = mass[a];
    s.rho = density[a];
    s.p = pressure[a];
    s.mu = particle_viscosity(materials, material[a], liquid_fraction[a]);
    s.c = material_value(materials, material[a], MATERIAL_SOUND_SPEED);
    s.gamma = p->pressure_gradient == PRESSURE_RENORMALISED ? gamma[a] : REAL(1.0);
    /* a gas needs the multiphase form (host/case.c) */
    s.gas = p->pressure_gradient == PRESSURE_MULTIPHASE && material_is_gas(materials, material[a]);
    s.h = particle_smoothing_length(smoothing_length, a, p);
    s.scale = smoothing_scale_of(p->h);
    for (int d = 0; d < 3; ++d)
        s.u[d] = velocity[3 * a + d];
    return s;
}

/* Acceleration of fluid particle a (its side s_a) by neighbour b at r_ab =
 * r_a - r_b, 0 < |r_ab| below the largest support SUPPORT_OVER_H h_max, added to acc
 * (0 beyond the pair's support SUPPORT_OVER_H h_ab, but for the barrier): pressure gradient +
 * viscosity + barrier. Pressure gradient a_a = -sum_b w_ab P_ab grad_a W_ab
 * (pair_weight_of, pair_pressure_sum):
 *   renormalised: a_a = -sum_b m_b / (rho_a rho_b) (p_b / Gamma_a + p_a / Gamma_b) grad_a W_ab
 *                 (Russell 2018 Eq. 3.17)
 *   symmetric:    a_a = -sum_b m_b / (rho_a rho_b) (p_a + p_b) grad_a W_ab
 *   multiphase:   a_a = -(1/m_a) sum_b (V_a^2 + V_b^2) (rho_b p_a + rho_a p_b) / (rho_a + rho_b)
 *                 grad_a W_ab, with the laminar viscosity in the same weights
 *                 (Fuchs et al. 2022 Eq. 23)
 * plus, if set, the tensile correction (above) and the barrier force. The
 * viscosity follows the liquid fraction through the mushy zone
 * (materials.h). Walls, solids and grains enter with their Adami state
 * (a gas particle with the pressure extrapolated from the gas,
 * gas_wall_pressure; kernels/fluid.cl wall_state); viscosity sees their
 * ghost velocity (no-slip) or nothing (free-slip). */
PAIR_INLINE void fluid_pair_acceleration(const fluid_pair_side *s_a, int b, const real r_ab[3], real r2,
                                           GLOBAL const real *velocity, GLOBAL const real *wall_velocity,
                                           GLOBAL const real *density, GLOBAL const real *pressure,
                                           GLOBAL const real *gas_wall_pressure,
                                           GLOBAL const real *mass, GLOBAL const real *gamma,
                                           GLOBAL const real *liquid_fraction, GLOBAL const real *smoothing_length,
                                           GLOBAL const int *kind, GLOBAL const int *material,
                                           GLOBAL const real *materials, const fluid_params *p, real acc[3])
{
    const real h_b = particle_smoothing_length(smoothing_length, b, p);
    const real h_ab = pair_smoothing_length(s_a->h, h_b);
    const smoothing_scale scale_ab = pair_smoothing_scale(&s_a->scale, s_a->h, h_b, p);
    const real f = smoothing_grad_factor_at(&scale_ab, sqrt(r2)); /* grad_a W_ab = f r_ab */
    const int fluid_b = kind[b] == KIND_FLUID;
    const int mat_b = material[b];
    const real rho_b = density[b], m_b = mass[b];
    const real gamma_b = p->pressure_gradient == PRESSURE_RENORMALISED ? gamma[b] : REAL(1.0);
    const real pressure_b = fluid_b || !s_a->gas ? pressure[b] : gas_wall_pressure[b];
    const pair_weight w = pair_weight_of(p->pressure_gradient, s_a->m, m_b, s_a->rho, rho_b);
    real pressure_term = -w.num / w.den *
                         pair_pressure_sum(p->pressure_gradient, s_a->p, pressure_b, s_a->rho, fluid_b ? rho_b : s_a->rho,
                                           s_a->gamma, gamma_b) *
                         f;
    if (fluid_b && p->tensile_correction > REAL(0.0))
        pressure_term += tensile_correction(s_a->p, pressure_b, s_a->rho, rho_b, m_b, sqrt(r2), f, h_ab, p);
    /* viscosity sees a wall's ghost velocity: the array is selected, not the
     * load branched, as fluid and wall neighbours alternate near a wall */
    GLOBAL const real *u_b = fluid_b ? velocity : wall_velocity;
    real u_visc[3];
    for (int d = 0; d < 3; ++d)
        u_visc[d] = s_a->u[d] - u_b[3 * b + d];
    const int viscous = fluid_b || p->wall_slip == WALL_NO_SLIP;
    real radial = pressure_term; /* multiplies r_ab */
    if (viscous && p->viscosity == VISCOSITY_ARTIFICIAL) {
        const real c_b = p->uniform_material ? s_a->c : material_value(materials, mat_b, MATERIAL_SOUND_SPEED);
        radial += -m_b * f *
                  artificial_viscosity(dot3(u_visc, r_ab), r2, REAL(0.5) * (s_a->c + c_b),
                                       REAL(0.5) * (s_a->rho + rho_b), h_ab, p);
    }
    if (p->barrier_stiffness > REAL(0.0)) {
        real u_ab[3];
        for (int d = 0; d < 3; ++d)
            u_ab[d] = s_a->u[d] - velocity[3 * b + d];
        radial += barrier_factor(sqrt(r2), dot3(u_ab, r_ab), s_a->m, p);
    }
    /* the laminar term is along u_ab, the others along r_ab; a term that is
     * off is left out, not added as 0 (which the compiler must keep) */
    if (viscous && p->viscosity == VISCOSITY_LAMINAR) {
        const real mu_b = particle_viscosity(materials, mat_b, liquid_fraction[b]);
        const real visc_scalar = laminar_viscosity_factor(s_a->mu, mu_b, w, f * r2, r2, p);
        for (int d = 0; d < 3; ++d)
            acc[d] += radial * r_ab[d] + visc_scalar * u_visc[d];
    } else {
        for (int d = 0; d < 3; ++d)
            acc[d] += radial * r_ab[d];
    }
}

#endif
