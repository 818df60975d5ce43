/* Weakly compressible SPH: continuity with delta-SPH and Shepard sums,
 * equation of state, wall states, and the pair forces (pressure, viscosity).
 * Pair loops gather: particle a reads its neighbours b and writes only a.
 * Every pair term takes W(r_ab, h_ab), h_ab = (h_a + h_b) / 2
 * (kernels/fluid_pair.h), over the largest support SUPPORT_OVER_H h_max:
 * h0 for all with `smoothing_length: fixed`; with `volume` each fluid
 * particle's h follows its volume (volume_smoothing_length). */
#include "device.h"
#include "fluid_pair.h"
#include "fluid_params.h"
#include "kinds.h"
#include "materials.h"
#include "neighbours.h"
#include "smoothing.h"
#include "transition.h"
#include "vec3.h"

/* Reference density of every particle at its temperature, rho0(T)
 * (Russell 2018 Eq. 3.52; kernels/materials.h), after the temperature
 * changed. Particles keep their mass: a falling rho0 makes the equation of
 * state push them apart until rho = m / V follows it (isothermal
 * incompressibility, Russell Sec. 3.4.2). */
KERNEL void update_reference_density(GLOBAL const int *material, GLOBAL const real *temperature, int n,
                                     GLOBAL const real *materials, GLOBAL real *reference_density)
{
    FOR_EACH_ITEM(a, n)
    {
        reference_density[a] = reference_density_of_temperature(materials, material[a], temperature[a]);
    }
}

/* Smoothing length that follows the particle volume (Russell 2018 Eq. 3.54),
 * with SMOOTHING_VOLUME, after the density advanced:
 *   h_a = h0 (V_a / V0)^(1/d),  V_a = m_a / rho_a,  V0 = dx^d
 * for fluid particles (V0 the lattice volume every particle starts with: the
 * scene gives each the mass rho dx^d); walls and solids keep h0. */
KERNEL void volume_smoothing_length(GLOBAL const real *mass, GLOBAL const real *density, GLOBAL const int *kind,
                                    int n, fluid_params p, GLOBAL real *smoothing_length)
{
    FOR_EACH_ITEM(a, n)
    {
        real v0 = p.dx;
        for (int d = 1; d < AMSPH_DIM; ++d)
            v0 *= p.dx;
        smoothing_length[a] = kind[a] == KIND_FLUID ? p.h * dimension_root(mass[a] / (density[a] * v0)) : p.h;
    }
}

/* p = c0^2 (rho - rho0(T)) + p_b for fluid particles (Russell 2018
 * Eq. 3.52), rho0(T) from the reference_density field; optionally no lower
 * than p_b, for free-surface flows without tension. */
KERNEL void equation_of_state(GLOBAL const int *kind, GLOBAL const int *material,
                              GLOBAL const real *density, GLOBAL const real *reference_density, int n,
                              GLOBAL const real *materials, fluid_params p, GLOBAL real *pressure)
{
    FOR_EACH_ITEM(a, n)
    {
        if (kind[a] == KIND_FLUID) {
            const real c0 = material_value(materials, material[a], MATERIAL_SOUND_SPEED);
            const real pressure_a = c0 * c0 * (density[a] - reference_density[a]) + p.background_pressure;
            pressure[a] = p.clamp_negative_pressure ? fmax(pressure_a, p.background_pressure) : pressure_a;
        }
    }
}

/* The Adami, Hu & Adams (2012, Eq. 27) wall pressure from the sums over
 * the fluid around a wall particle (a_w = 0: walls move at constant
 * velocity), no lower than floor_w; fallback where no fluid is near. */
static inline real adami_wall_pressure(real sum_w, real sum_p, const real sum_rho_r[3], const fluid_params *p,
                                       real floor_w, real fallback)
{
    return sum_w > REAL(0.0) ? fmax(floor_w, (sum_p + dot3(p->gravity, sum_rho_r)) / sum_w) : fallback;
}

/* The sums of wall_state over the fluid around a wall particle: [0] over
 * the non-gas fluid, [1] over the gas. */
typedef struct {
    real w[2], p[2], rho_r[2][3];
    real u[3], all_w;
} wall_sums;

/* The terms of particle b, seen from the point `point` (the wall's position
 * less b's periodic image), in the wall's sums, if b is fluid and within
 * the support (the wall keeps h0: scale is its kernel's scale). */
PAIR_INLINE void add_wall_pair(wall_sums *s, int b, const real point[3], real support,
                               const smoothing_scale *scale, GLOBAL const real *position,
                               GLOBAL const real *velocity, GLOBAL const int *kind, GLOBAL const int *material,
                               GLOBAL const real *smoothing_length, GLOBAL const real *density,
                               GLOBAL const real *pressure, GLOBAL const real *materials, const fluid_params *p)
{
    if (kind[b] != KIND_FLUID)
        return;
    real r_ab[3];
    for (int d = 0; d < 3; ++d)
        r_ab[d] = point[d] - position[3 * b + d];
    const real r2 = dot3(r_ab, r_ab);
    if (r2 >= support * support)
        return; /* W = 0 */
    const smoothing_scale scale_ab =
        pair_smoothing_scale(scale, p->h, particle_smoothing_length(smoothing_length, b, p), p);
    const real w = smoothing_w_at(&scale_ab, sqrt(r2));
    /* a gas needs the multiphase form (host/case.c) */
    const int phase = p->pressure_gradient == PRESSURE_MULTIPHASE && material_is_gas(materials, material[b]);
    s->w[phase] += w;
    s->p[phase] += pressure[b] * w;
    s->all_w += w;
    for (int d = 0; d < 3; ++d) {
        s->rho_r[phase][d] += density[b] * r_ab[d] * w;
        s->u[d] += velocity[3 * b + d] * w;
    }
}

/* The sums of wall_state for wall particle a. Gamma = 0: continuity found
 * no fluid within the support at these positions, and the sums stay 0
 * (with p.one_pass no continuity pass ran: look). Without a periodic axis
 * the loop is the box of cells around the wall (FOR_EACH_IN_BOX), which
 * for a wall is cheaper than trimming it to the support, and gives the
 * same sums. */
PAIR_INLINE wall_sums wall_sums_of(int a, GLOBAL const real *position, GLOBAL const real *velocity,
                                   GLOBAL const int *kind, GLOBAL const int *material, GLOBAL const int *cell,
                                   GLOBAL const real *smoothing_length, GLOBAL const real *gamma,
                                   const grid_geometry *g, GLOBAL const int *cell_start,
                                   GLOBAL const real *density, GLOBAL const real *pressure,
                                   GLOBAL const real *materials, const fluid_params *p)
{
    wall_sums s = {{REAL(0.0), REAL(0.0)}, {REAL(0.0), REAL(0.0)},
                   {{REAL(0.0), REAL(0.0), REAL(0.0)}, {REAL(0.0), REAL(0.0), REAL(0.0)}},
                   {REAL(0.0), REAL(0.0), REAL(0.0)}, REAL(0.0)};
    if (!p->one_pass && !(gamma[a] > REAL(0.0)))
        return s;
    int cc[3];
    grid_cell_coords(g, cell[a], cc);
    real x_a[3];
    grid_point(position, a, x_a);
    const real support = SUPPORT_OVER_H * p->h_max;
    const smoothing_scale scale = smoothing_scale_of(p->h);
    if (!grid_has_periodic_axis(g)) {
        FOR_EACH_IN_BOX(b, g, cc, cell_start, GRID_CELLS_PER_SUPPORT, GRID_SET_BODIES)
        {
            add_wall_pair(&s, b, x_a, support, &scale, position, velocity, kind, material, smoothing_length, density,
                          pressure, materials, p);
        }
    } else {
        FOR_EACH_BODY_NEIGHBOUR(b, run, g, cc, x_a, cell_start, support)
        {
            add_wall_pair(&s, b, run.point, support, &scale, position, velocity, kind, material, smoothing_length,
                          density, pressure, materials, p);
        }
    }
    return s;
}

/* Wall and fixed-solid particles take their state from the fluid around them
 * (Adami, Hu & Adams 2012, Eqs. 22, 27, 28):
 *   p_w   = (sum_f p_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf) / sum_f W_wf
 *   rho_w = rho0_w + (p_w - p_b) / c0^2        (the inverse equation of state)
 *   u~_w  = 2 u_w - sum_f u_f W_wf / sum_f W_wf (no-slip ghost velocity)
 * with r_wf = r_w - r_f and a_w = 0 (walls move at constant velocity).
 * rho0_w and c0 are the wall's own (its material at its temperature), so
 * that its volume m_w / rho_w stays dx^d next to fluids of any rho0. In the
 * multiphase form rho_w = rho0_w: there a wall's density serves only as its
 * volume (the pair pressure takes the fluid's density for it), which keeps
 * the lattice volume; the inverse equation of state would make a wall under
 * 0.5 m of water 1.2% smaller than the fluid's particles beside it (whose
 * hydrostatic mass rho dx^d gives them the lattice volume) and push them off
 * the bottom at 0.2 g.
 * p_w is kept >= p_b: a wall that pulled on the fluid with a negative
 * pressure would glue separating fluid to it and draw particles into it.
 * In the multiphase form (a gas fills the space, nothing separates from a
 * wall) p_w is only kept >= 0: the top of a gas column at rest sits at
 * p_b less its weight, and a wall held at p_b would push it down.
 * Each phase sees the wall's pressure extrapolated from its own particles:
 * `pressure` (and rho_w) sums over the liquid and other non-gas fluid,
 * `gas_wall_pressure` over the gas, each over the other phase where none of
 * its own is near. One sum over both would show the gas beside a
 * liquid-gas interface the liquid's pressure, rho_l g dx above its own: at
 * a density ratio of 100 that pushes the gas along the wall at 100 times
 * its weight. Without a gas both are the sum over all the fluid. */
KERNEL void wall_state(GLOBAL const real *position, GLOBAL const real *velocity,
                       GLOBAL const int *kind, GLOBAL const int *material, GLOBAL const int *cell,
                       GLOBAL const real *smoothing_length, GLOBAL const real *reference_density,
                       GLOBAL const real *gamma, int n, grid_geometry g,
                       GLOBAL const int *cell_start, GLOBAL const real *materials, fluid_params p,
                       GLOBAL real *density, GLOBAL real *pressure, GLOBAL real *gas_wall_pressure,
                       GLOBAL real *wall_velocity)
{
    FOR_EACH_ITEM(a, n)
    {
        if (kind[a] != KIND_FLUID) {
            const wall_sums s = wall_sums_of(a, position, velocity, kind, material, cell, smoothing_length, gamma, &g,
                                             cell_start, density, pressure, materials, &p);
            const real rho0 = reference_density[a];
            const real c0 = material_value(materials, material[a], MATERIAL_SOUND_SPEED);
            const real floor_w = p.pressure_gradient == PRESSURE_MULTIPHASE ? REAL(0.0) : p.background_pressure;
            const real p_gas = adami_wall_pressure(s.w[1], s.p[1], s.rho_r[1], &p, floor_w, p.background_pressure);
            const real p_w = adami_wall_pressure(s.w[0], s.p[0], s.rho_r[0], &p, floor_w, p_gas);
            pressure[a] = p_w;
            gas_wall_pressure[a] = s.w[1] > REAL(0.0) ? p_gas : p_w;
            density[a] = p.pressure_gradient == PRESSURE_MULTIPHASE ? rho0
                                                                    : rho0 + (p_w - p.background_pressure) / (c0 * c0);
            for (int d = 0; d < 3; ++d)
                wall_velocity[3 * a + d] =
                    s.all_w > REAL(0.0) ? REAL(2.0) * velocity[3 * a + d] - s.u[d] / s.all_w : velocity[3 * a + d];
        }
    }
}

/* delta-SPH density diffusion of one pair, as a Laplacian of the diffused
 * quantity q (rho; rho - rho0 after Russell 2018 Eq. 3.53, each particle
 * with its own rho0(T), so that neighbours of different reference density
 * exchange only their departures from it; or rho - rho0 less the
 * hydrostatic density after Fourtakas et al. 2019, which leaves a fluid at
 * rest under gravity untouched):
 *   D_a = delta h_a c0 sum_b 2 (q_a - q_b) (r_ab . grad_a W_ab) / (r_ab^2 + eta^2) V_b,
 * the Molteni & Colagrossi (2009) form without Antuono's correction term;
 * it decays a perturbation of q (tested). */
static inline real density_diffusion_pair(real q_a, real q_b, real r_dot_grad, real r2, real v_b,
                                          const fluid_params *p)
{
    return REAL(2.0) * (q_a - q_b) * r_dot_grad / (r2 + p->eta2) * v_b;
}

/* Are two materials of the same phase (both gas, or both not)? Density
 * diffusion acts within a phase: across a liquid-gas interface the
 * departures rho - rho0 of equal pressures differ by the ratio of the
 * phases' c0^2, and diffusing them would carry mass across it. A gas needs
 * the multiphase pressure form (case.c), so without it every pair is. */
static inline int same_phase(GLOBAL const real *materials, const fluid_params *p, int mat_a, int mat_b)
{
    return p->pressure_gradient != PRESSURE_MULTIPHASE ||
           material_is_gas(materials, mat_a) == material_is_gas(materials, mat_b);
}

/* Does the continuity of a particle of material mat_a take the velocity of
 * a fluid neighbour of mat_b? A gas takes every fluid, so a liquid coming
 * at it compresses it; a liquid takes its own phase only: its surface is a
 * free surface to continuity, as without a gas. With the gas's velocity in
 * its sum, gas squeezed out of the closing gap between a binder drop and a
 * grain at 60 to 90 m/s pressed the binder particles it passed by 35% (the
 * density guard) in cases/am/binder_jetting_10ms_gas_2d.yaml. Tested in
 * test_gas (a liquid disc in streaming gas). */
static inline int continuity_takes(GLOBAL const real *materials, const fluid_params *p, int mat_a, int mat_b)
{
    return same_phase(materials, p, mat_a, mat_b) || material_is_gas(materials, mat_a);
}

/* Does the delta-SPH term diffuse rho - rho0 (Russell, Fourtakas) rather than rho? */
static inline int diffuses_departure(const fluid_params *p)
{
    return p->density_diffusion == DIFFUSION_RUSSELL || p->density_diffusion == DIFFUSION_FOURTAKAS;
}

/* The sums of continuity over the neighbours of a particle. */
typedef struct {
    real shepard, drho, diffusion, nearest;
    real kernel_sum; /* sum_b W(r_ab, h0), a gas particle with GAS_DENSITY_SUMMATION (summed_density_pull) */
    int fluid_near; /* a fluid particle other than a lies within the support */
    int others;     /* fluid a: the particles other than a within its support */
    /* CONTINUITY_CORRECTED: moment[3 i + j] = B_ij and rate[3 i + j] = D_ij
     * of corrected_density_rate */
    real moment[9], rate[9];
} continuity_sums;

/* Sums over no neighbour yet. */
static inline continuity_sums continuity_sums_none(void)
{
    const continuity_sums none = {REAL(0.0), REAL(0.0), REAL(0.0), NO_NEIGHBOUR, REAL(0.0), 0, 0, {REAL(0.0)}, {REAL(0.0)}};
    return none;
}

/* Smallest det B_a at which continuity takes the corrected kernel gradient:
 * 1 in the interior, 0.25 on a flat 2D surface (B_nn = 0.5), about 0.125
 * in a 3D corner; a particle with a few neighbours on one side (spray, a
 * film one particle thick) has B near singular and keeps the plain sum. */
#define CORRECTION_MIN_DETERMINANT REAL(0.05)

/* drho_a/dt with the corrected kernel gradient L_a grad_a W_ab (Bonet & Lok
 * 1999, Comput. Methods Appl. Mech. Engrg. 180, 97-115, their gradient
 * correction; Randles & Libersky 1996) in Russell's continuity (Eq. 3.14):
 *   drho_a/dt = rho_a sum_b V_b u_ab . L_a grad_a W_ab = rho_a sum_ij (L_a)_ij D_ij,
 *   L_a = B_a^-1,  B_ij = -sum_b V_b r_ab,i (grad_a W_ab)_j,  D_ij = sum_b V_b u_ab,i (grad_a W_ab)_j,
 * which is exact for every linear velocity field, u = A x gives -rho_a tr A,
 * also where a free surface truncates the support (B = I in the interior
 * of a lattice, B_nn = 0.5 at a surface). The plain sum rho_a tr D takes
 * tr B for d there: at a free surface continuity then sees about half of
 * the compression or expansion normal to it, and the particles near the
 * surface move further than their volume m / rho says until their rho
 * follows rho0 (in the expansion cycle the band below the surface drifts
 * from m / rho0 cycle by cycle, BENCHMARKS.md). Returns the plain sum
 * where det B is below CORRECTION_MIN_DETERMINANT. */
static inline real corrected_density_rate(const continuity_sums *s, real rho_a)
{
    real b[9];
    for (int k = 0; k < 9; ++k)
        b[k] = s->moment[k];
#if AMSPH_DIM == 2
    b[8] = REAL(1.0); /* the z row and column: the identity */
#endif
    const real c00 = b[4] * b[8] - b[5] * b[7], c01 = b[5] * b[6] - b[3] * b[8], c02 = b[3] * b[7] - b[4] * b[6];
    const real det = b[0] * c00 + b[1] * c01 + b[2] * c02;
    if (!(det >= CORRECTION_MIN_DETERMINANT))
        return s->drho;
    /* L = B^-1 = adj(B) / det B */
    const real l[9] = {c00, b[2] * b[7] - b[1] * b[8], b[1] * b[5] - b[2] * b[4],
                       c01, b[0] * b[8] - b[2] * b[6], b[2] * b[3] - b[0] * b[5],
                       c02, b[1] * b[6] - b[0] * b[7], b[0] * b[4] - b[1] * b[3]};
    real sum = REAL(0.0);
    for (int k = 0; k < 9; ++k)
        sum += l[k] * s->rate[k];
    return rho_a * sum / det;
}

/* Is particle a a gas whose density is summed (fluid.gas_density: summation)? */
static inline int gas_density_summed(int a, GLOBAL const int *kind, GLOBAL const int *material,
                                     GLOBAL const real *materials, const fluid_params *p)
{
    return p->gas_density == GAS_DENSITY_SUMMATION && kind[a] == KIND_FLUID &&
           material_is_gas(materials, material[a]);
}

/* What the continuity sums need of particle a. */
typedef struct {
    int fluid, material;
    int summed;            /* gas_density_summed */
    real rho, rho0, q;     /* q: the diffused quantity (density_diffusion_pair) */
    real h;                /* particle_smoothing_length */
    real u[3];
    smoothing_scale scale; /* of W at h0 */
} continuity_side;

static inline continuity_side continuity_side_of(int a, GLOBAL const real *velocity, GLOBAL const real *density,
                                                 GLOBAL const real *reference_density,
                                                 GLOBAL const real *smoothing_length, GLOBAL const int *kind,
                                                 GLOBAL const int *material, GLOBAL const real *materials,
                                                 const fluid_params *p)
{
    continuity_side s;
    s.fluid = kind[a] == KIND_FLUID;
    s.material = material[a];
    s.summed = gas_density_summed(a, kind, material, materials, p);
    s.rho = density[a];
    s.rho0 = reference_density[a];
    s.q = s.rho - (diffuses_departure(p) ? s.rho0 : REAL(0.0));
    s.h = particle_smoothing_length(smoothing_length, a, p);
    s.scale = smoothing_scale_of(p->h);
    for (int d = 0; d < 3; ++d)
        s.u[d] = velocity[3 * a + d];
    return s;
}

/* The terms of neighbour b (b = a too) at r_ab = r_a - r_b, |r_ab|^2 = r2
 * within the support, in the continuity sums of particle a (its side s_a). */
PAIR_INLINE void add_continuity_pair(const continuity_side *s_a, int a, int b, const real r_ab[3], real r2,
                                     GLOBAL const real *velocity, GLOBAL const real *density,
                                     GLOBAL const real *reference_density, GLOBAL const real *smoothing_length,
                                     GLOBAL const real *mass, GLOBAL const int *kind, GLOBAL const int *material,
                                     GLOBAL const real *materials, const fluid_params *p, continuity_sums *sums)
{
    const real r = sqrt(r2);
    const real v_b = mass[b] / density[b];
    const smoothing_scale scale_ab =
        pair_smoothing_scale(&s_a->scale, s_a->h, particle_smoothing_length(smoothing_length, b, p), p);
    if (!p->one_pass) /* no force reads it there (fluid_forces) */
        sums->shepard += smoothing_w_at(&scale_ab, r) * v_b;
    if (s_a->summed)
        sums->kernel_sum += smoothing_w_at(&s_a->scale, r);
    sums->fluid_near |= b != a && kind[b] == KIND_FLUID;
    if (!s_a->fluid || b == a)
        return;
    sums->nearest = r < sums->nearest ? r : sums->nearest; /* fmin, without a call to libm in C */
    sums->others += 1;
    if (kind[b] == KIND_FLUID && !continuity_takes(materials, p, s_a->material, material[b]))
        return;
    const real f = smoothing_grad_factor_at(&scale_ab, r); /* grad_a W_ab = f r_ab */
    real u_ab[3];
    for (int d = 0; d < 3; ++d)
        u_ab[d] = s_a->u[d] - velocity[3 * b + d];
    sums->drho += s_a->rho * f * dot3(u_ab, r_ab) * v_b;
    if (p->continuity == CONTINUITY_CORRECTED)
        for (int i = 0; i < AMSPH_DIM; ++i)
            for (int j = 0; j < AMSPH_DIM; ++j) {
                sums->moment[3 * i + j] -= v_b * r_ab[i] * f * r_ab[j];
                sums->rate[3 * i + j] += v_b * u_ab[i] * f * r_ab[j];
            }
    /* between fluid particles only: the term of a wall neighbour (its state
     * is valid) is computed and dropped by a select, not a branch */
    if (p->density_diffusion != DIFFUSION_NONE && same_phase(materials, p, s_a->material, material[b])) {
        /* b's rho0: a's where every particle has the one material (p->uniform_material) */
        const real rho0_b = p->uniform_material ? s_a->rho0 : reference_density[b];
        const real q_b = density[b] - (diffuses_departure(p) ? rho0_b : REAL(0.0));
        real dq = s_a->q - q_b;
        if (p->density_diffusion == DIFFUSION_FOURTAKAS) {
            /* minus the hydrostatic density difference of the pair,
             * rho0_b (g . r_ab) / c0_b^2 (linear equation of state) */
            const real c0_b = material_value(materials, material[b], MATERIAL_SOUND_SPEED);
            dq -= rho0_b * dot3(p->gravity, r_ab) / (c0_b * c0_b);
        }
        const real term = density_diffusion_pair(dq, REAL(0.0), f * r2, r2, v_b, p);
        sums->diffusion += kind[b] == KIND_FLUID ? term : REAL(0.0);
    }
}

/* The sums of continuity over the neighbours of particle a in the sets
 * first_set .. last_set (GRID_SET_*), added to sums. */
static inline void add_continuity_sums(int a, int first_set, int last_set, GLOBAL const real *position,
                                       GLOBAL const real *velocity, GLOBAL const real *density,
                                       GLOBAL const real *reference_density, GLOBAL const real *smoothing_length,
                                       GLOBAL const real *mass,
                                       GLOBAL const int *kind, GLOBAL const int *material,
                                       GLOBAL const int *cell, const grid_geometry *g,
                                       GLOBAL const int *cell_start, GLOBAL const real *materials,
                                       const fluid_params *p, continuity_sums *sums_io)
{
    continuity_sums sums = *sums_io; /* private: kept in registers, not stored per pair */
    int cc[3];
    grid_cell_coords(g, cell[a], cc);
    real x_a[3];
    grid_point(position, a, x_a);
    const real support = SUPPORT_OVER_H * p->h_max;
    const continuity_side s_a =
        continuity_side_of(a, velocity, density, reference_density, smoothing_length, kind, material, materials, p);
    FOR_EACH_NEIGHBOUR_IN(b, run, g, cc, x_a, cell_start, GRID_CELLS_PER_SUPPORT, support, first_set, last_set)
    {
        real r_ab[3];
        grid_displacement(&run, position, b, r_ab);
        const real r2 = dot3(r_ab, r_ab);
        if (r2 >= support * support)
            continue; /* W = 0: 3 candidates in 5 in 3D, 2 in 5 in 2D */
        add_continuity_pair(&s_a, a, b, r_ab, r2, velocity, density, reference_density, smoothing_length, mass,
                            kind, material, materials, p, &sums);
    }
    *sums_io = sums;
}

/* drho_a/dt of continuity_sums (continuity, below): the plain or the
 * corrected sum (fluid.continuity), plus the delta-SPH term. */
static inline real continuity_rate(const continuity_sums *sums, int a, GLOBAL const real *density,
                                   GLOBAL const real *smoothing_length, GLOBAL const int *material,
                                   GLOBAL const real *materials, const fluid_params *p)
{
    const real drho = p->continuity == CONTINUITY_CORRECTED ? corrected_density_rate(sums, density[a]) : sums->drho;
    return drho + p->delta * particle_smoothing_length(smoothing_length, a, p) *
                      material_value(materials, material[a], MATERIAL_SOUND_SPEED) * sums->diffusion;
}

/* Shepard sum Gamma below which a fluid particle counts as lying on a free
 * surface (particle shifting): on a lattice with
 * Wendland C2 at h = 1.2 dx, 0.823 on a flat face, 1.017 one layer below it
 * and 1.018 in the interior (wider kernels reach further in: shifting
 * spreads the flag to every fluid neighbour within the support). */
#define FREE_SURFACE_SHEPARD REAL(0.95)

/* The Shepard sum of a particle inside a block of the initial lattice,
 * Gamma_lattice = dx^d sum_n W(|n| dx, h0) over the lattice points n dx
 * within the support, the point itself included. One item. */
KERNEL void lattice_shepard_sum(int n, fluid_params p, GLOBAL real *shepard)
{
    FOR_EACH_ITEM(i, n)
    {
        const smoothing_scale scale = smoothing_scale_of(p.h);
        const int reach = (int)(SUPPORT_OVER_H * p.h / p.dx);
        const int reach_z = AMSPH_DIM == 3 ? reach : 0;
        real sum = REAL(0.0);
        for (int x = -reach; x <= reach; ++x)
            for (int y = -reach; y <= reach; ++y)
                for (int z = -reach_z; z <= reach_z; ++z)
                    sum += smoothing_w_at(&scale, p.dx * sqrt((real)(x * x + y * y + z * z)));
        for (int d = 0; d < AMSPH_DIM; ++d)
            sum *= p.dx;
        shepard[i] = sum;
    }
}

/* The density of a gas particle summed over its neighbours (fluid.gas_density:
 * summation; Adami, Hu & Adams 2013), in place of the continuity's:
 *   rho_sum,a = m_a sum_b W_ab / Gamma_lattice
 * every particle within the support at h0 counted (a itself, fluid of every
 * phase, walls, solids and grains; continuity_sums.kernel_sum), Gamma_lattice
 * = lattice_shepard_sum, so that a particle of mass rho0 dx^d inside the
 * initial lattice has rho0. It follows the positions, whatever moved them:
 * on an evenly spaced gas it is rho0, whatever the flow did before. Where
 * the support is cut (a void beside the particle, such as a gap a moving
 * grain opens) the sum falls with the missing neighbours, by a third at a
 * corner and by 7% where Gamma_a is 0.95; there the continuity's density
 * stands. Between the two the density is blended,
 *   rho_a^(n+1) = s rho_sum,a + (1 - s) (rho_a^n + dt drho_a/dt),
 *   s = transition(Gamma_a / Gamma_lattice, SUMMED_FROM, SUMMED_FULL),
 * so that the density of a particle whose support fills up moves to the
 * summed one smoothly: switched at one Gamma, it jumped by the 7%, a
 * pressure step of 0.07 rho0 c0^2 (4.8e5 Pa in the 1 m/s binder scene with
 * gas, which set a pocket of gas beside the particle oscillating at up to
 * 400 m/s; RESULTS.md). Returned as the step's two parts: *continuity_share
 * = 1 - s, the factor of the continuity's rate, and the summed density's
 * pull s (rho_sum,a - rho_a^n); 0 and 1 for every particle that is not a
 * summed gas. */
#define SUMMED_FROM REAL(0.93) /* Gamma / Gamma_lattice: 0.81 on a flat face (2D and 3D), 1 inside */
#define SUMMED_FULL REAL(0.98) /* the row under a flat face: 0.999 (Wendland C2, 2D and 3D), 0.973 / 0.976 (quintic, 2D / 3D), at h = 1.2 dx */

static inline real summed_density_pull(const continuity_sums *sums, int a, GLOBAL const real *mass,
                                       GLOBAL const real *density, GLOBAL const int *kind,
                                       GLOBAL const int *material, GLOBAL const real *materials,
                                       const fluid_params *p, real *continuity_share)
{
    *continuity_share = REAL(1.0);
    if (!gas_density_summed(a, kind, material, materials, p))
        return REAL(0.0);
    const real fill = sums->shepard / p->lattice_shepard;
    const real s = transition(fill, SUMMED_FROM, SUMMED_FULL);
    *continuity_share = REAL(1.0) - s;
    return s * (mass[a] * sums->kernel_sum / p->lattice_shepard - density[a]);
}

/* Continuity and Shepard sums, evaluated after the drift with the half-step
 * velocity, so that the density advances like a position (see
 * kernels/integrate.cl):
 *   drho_a/dt = rho_a sum_b u_ab . grad_a W_ab V_b + D_a   (Russell 2018 Eq. 3.14)
 *   Gamma_a   = sum_b W_ab V_b                            (below Russell Eq. 3.17)
 * Walls enter with their own (prescribed) velocity; the delta-SPH term acts
 * between fluid particles of the same phase only. closest[a] is the distance
 * to the nearest other particle, for the guards, and others[a] the number of
 * other particles within the support, for the density update
 * (kernels/integrate.cl density_at_step_end); with GAS_DENSITY_SUMMATION
 * summed_pull[a] the summed density's pull (summed_density_pull), and the
 * rate of a summed gas particle is the continuity's share of it (untouched
 * otherwise). The rates are computed for fluid
 * particles. Gamma is computed for every fluid particle, and for the others
 * where a fluid particle lies within the support: only a fluid neighbour's
 * renormalised pressure force reads it (fluid_pair.h). Elsewhere it is 0,
 * and such a particle loops over no neighbour: the walls, solids and grains
 * whose box of cells holds no fluid (grid_fluid_in_box: a tank's walls far
 * from the water, a substrate under a small melt pool, a powder bed beside
 * a droplet) cost that test only. With the symmetric and
 * multiphase pressure forms no force reads a non-fluid particle's Gamma,
 * and it is the sum over its non-wall neighbours only: positive where a
 * fluid particle is within the support, which is what wall_state asks of it. */
KERNEL void continuity(GLOBAL const real *position, GLOBAL const real *velocity,
                       GLOBAL const real *density, GLOBAL const real *reference_density,
                       GLOBAL const real *smoothing_length,
                       GLOBAL const real *mass, GLOBAL const int *kind, GLOBAL const int *material,
                       GLOBAL const int *cell, int n, grid_geometry g, GLOBAL const int *cell_start,
                       GLOBAL const int *fluid_count, GLOBAL const real *materials, fluid_params p,
                       GLOBAL real *density_rate, GLOBAL real *gamma, GLOBAL real *closest, GLOBAL int *others,
                       GLOBAL real *summed_pull)
{
    FOR_EACH_ITEM(a, n)
    {
        const int fluid_a = kind[a] == KIND_FLUID;
        continuity_sums sums = continuity_sums_none();
        int cc[3];
        grid_cell_coords(&g, cell[a], cc);
        if (fluid_a || grid_fluid_in_box(&g, cell_start, fluid_count, cc, GRID_CELLS_PER_SUPPORT))
            add_continuity_sums(a, GRID_SET_BODIES, fluid_a ? GRID_SET_WALLS : GRID_SET_BODIES, position, velocity,
                                density, reference_density, smoothing_length, mass, kind, material, cell, &g,
                                cell_start, materials, &p, &sums);
        if (!fluid_a && sums.fluid_near && p.pressure_gradient == PRESSURE_RENORMALISED)
            add_continuity_sums(a, GRID_SET_WALLS, GRID_SET_WALLS, position, velocity, density, reference_density,
                                smoothing_length, mass, kind, material, cell, &g, cell_start, materials, &p, &sums);
        gamma[a] = fluid_a || sums.fluid_near ? sums.shepard : REAL(0.0);
        real continuity_share = REAL(1.0);
        if (p.gas_density == GAS_DENSITY_SUMMATION)
            summed_pull[a] =
                summed_density_pull(&sums, a, mass, density, kind, material, materials, &p, &continuity_share);
        density_rate[a] = fluid_a ? continuity_share * continuity_rate(&sums, a, density, smoothing_length, material,
                                                                       materials, &p)
                                  : REAL(0.0);
        closest[a] = sums.nearest;
        others[a] = sums.others;
    }
}

/* The options of the fluid-only scenes (dam breaks, tanks; DualSPHysics's
 * scheme): fixed h, the symmetric pressure force, artificial viscosity,
 * the plain continuity sum, neither the tensile correction nor a barrier,
 * one material of constant rho0.
 * Where a case has them, fluid_forces hands its pair loop
 * fluid_params_plain, a copy of the parameters with these options as
 * constants, and the compiler folds the other options' branches out of the
 * pair terms: one source compiled twice, as a C++ template would be. */
static inline int fluid_options_plain(const fluid_params *p)
{
    return p->smoothing_length == SMOOTHING_FIXED && p->pressure_gradient == PRESSURE_SYMMETRIC &&
           p->viscosity == VISCOSITY_ARTIFICIAL && p->continuity == CONTINUITY_PLAIN &&
           p->tensile_correction == REAL(0.0) && p->barrier_stiffness == REAL(0.0) && p->uniform_material;
}

static inline fluid_params fluid_params_plain(fluid_params p)
{
    p.smoothing_length = SMOOTHING_FIXED;
    p.pressure_gradient = PRESSURE_SYMMETRIC;
    p.viscosity = VISCOSITY_ARTIFICIAL;
    p.continuity = CONTINUITY_PLAIN;
    p.tensile_correction = REAL(0.0);
    p.barrier_stiffness = REAL(0.0);
    p.uniform_material = 1;
    return p;
}

/* Acceleration of fluid particle a (fluid_forces, below), and with
 * p->one_pass its continuity sums. */
PAIR_INLINE void fluid_forces_of(int a, GLOBAL const real *position, GLOBAL const real *velocity,
                                 GLOBAL const real *wall_velocity, GLOBAL const real *density,
                                 GLOBAL const real *reference_density, GLOBAL const real *pressure,
                                 GLOBAL const real *gas_wall_pressure, GLOBAL const real *mass,
                                 GLOBAL const real *gamma, GLOBAL const real *liquid_fraction,
                                 GLOBAL const real *smoothing_length, GLOBAL const int *kind,
                                 GLOBAL const int *material, GLOBAL const int *cell, const grid_geometry *g,
                                 GLOBAL const int *cell_start, GLOBAL const real *materials, const fluid_params *p,
                                 real acc[3], continuity_sums *sums)
{
    int cc[3];
    grid_cell_coords(g, cell[a], cc);
    real x_a[3];
    grid_point(position, a, x_a);
    const real support = SUPPORT_OVER_H * p->h_max;
    const fluid_pair_side s_a = fluid_pair_side_of(a, velocity, mass, density, pressure, gamma, liquid_fraction,
                                                   smoothing_length, material, materials, p);
    const continuity_side c_a =
        continuity_side_of(a, velocity, density, reference_density, smoothing_length, kind, material, materials, p);
    if (p->one_pass) {
        const real self[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        add_continuity_pair(&c_a, a, a, self, REAL(0.0), velocity, density, reference_density, smoothing_length,
                            mass, kind, material, materials, p, sums);
    }
    FOR_EACH_NEIGHBOUR_WITHIN(b, run, g, cc, x_a, cell_start, position, a, support)
    {
        real r_ab[3];
        grid_displacement(&run, position, b, r_ab);
        const real r2 = dot3(r_ab, r_ab);
        fluid_pair_acceleration(&s_a, b, r_ab, r2, velocity, wall_velocity, density, pressure, gas_wall_pressure,
                                mass, gamma, liquid_fraction, smoothing_length, kind, material, materials, p, acc);
        if (p->one_pass)
            add_continuity_pair(&c_a, a, b, r_ab, r2, velocity, density, reference_density, smoothing_length,
                                mass, kind, material, materials, p, sums);
    }
}

/* Acceleration of the fluid particles: gravity + the pair forces of
 * kernels/fluid_pair.h. With p.one_pass (fluid.integration: verlet) the same
 * pass over the neighbours also evaluates the continuity sums of the fluid
 * particles at this state (continuity, above; the velocity of the state,
 * not of a half step) into density_rate, closest and others, and writes 0,
 * NO_NEIGHBOUR and 0 for the other particles. It takes no Shepard sum: no
 * force reads Gamma under the symmetric pressure form, and wall_state finds the
 * fluid near a wall itself. Without p.one_pass those three are not touched. */
KERNEL void fluid_forces(GLOBAL const real *position, GLOBAL const real *velocity,
                         GLOBAL const real *wall_velocity, GLOBAL const real *density,
                         GLOBAL const real *reference_density,
                         GLOBAL const real *pressure, GLOBAL const real *gas_wall_pressure, GLOBAL const real *mass,
                         GLOBAL const real *gamma, GLOBAL const real *liquid_fraction,
                         GLOBAL const real *smoothing_length,
                         GLOBAL const int *kind, GLOBAL const int *material,
                         GLOBAL const int *cell, int n, grid_geometry g,
                         GLOBAL const int *cell_start, GLOBAL const real *materials, fluid_params p,
                         GLOBAL real *acceleration, GLOBAL real *density_rate, GLOBAL real *closest,
                         GLOBAL int *others)
{
    FOR_EACH_ITEM(a, n)
    {
        real acc[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        continuity_sums sums = continuity_sums_none();
        const int fluid_a = kind[a] == KIND_FLUID;
        if (fluid_a && fluid_options_plain(&p)) {
            const fluid_params plain = fluid_params_plain(p);
            fluid_forces_of(a, position, velocity, wall_velocity, density, reference_density, pressure,
                            gas_wall_pressure, mass, gamma, liquid_fraction, smoothing_length, kind, material, cell,
                            &g, cell_start, materials, &plain, acc, &sums);
        } else if (fluid_a) {
            fluid_forces_of(a, position, velocity, wall_velocity, density, reference_density, pressure,
                            gas_wall_pressure, mass, gamma, liquid_fraction, smoothing_length, kind, material, cell,
                            &g, cell_start, materials, &p, acc, &sums);
        }
        for (int d = 0; d < 3; ++d)
            acceleration[3 * a + d] = acc[d] + (fluid_a ? p.gravity[d] : REAL(0.0));
        if (p.one_pass) {
            density_rate[a] = fluid_a ? continuity_rate(&sums, a, density, smoothing_length, material, materials, &p) : REAL(0.0);
            closest[a] = sums.nearest;
            others[a] = sums.others;
        }
    }
}

/* The share of the transport velocity's displacement that particle a takes,
 * from its colour gradient |sum_b V_b grad_a W_ab| h_a (`cut`): 1 up to
 * TRANSPORT_FULL_CUT, falling linearly to 0 at TRANSPORT_NO_CUT. With
 * Wendland C2 at h = 1.2 dx, `cut` is 0 inside the lattice, 0.19 for a
 * particle moved 0.2 dx off its site (0.10 in 3D), up to 0.06 in the gas of
 * the binder scenes, 0.56 on a flat face (0.58 in 3D, on the cubic lattice,
 * whose Gamma there is 0.81 of the lattice's too, as in 2D: the bounds of
 * the share and of the summed density carry over to 3D) and 0.7 to 0.9 on
 * the edge of a pocket of gas
 * squeezed to 0.6 dx beside a void between grains. There the displacement,
 * a push into the void as strong as the gas's own pressure (p_tv =
 * rho0 c0^2), is a step in the positions with no momentum behind it, while
 * the summed density's tension pulls the particles back by their velocity:
 * with the whole push, that pocket went from rest to 400 m/s in 40 steps
 * (RESULTS.md). The free-surface projection of shifting_displacement
 * removes the push only where a Gamma flags the surface, and Gamma is the
 * lattice's in a squeezed pocket; the share fades the push out with the
 * cut itself, continuously (test_fluid). */
#define TRANSPORT_FULL_CUT REAL(0.25)
#define TRANSPORT_NO_CUT REAL(0.5)

static inline real transport_share(real cut)
{
    return transition(cut, TRANSPORT_NO_CUT, TRANSPORT_FULL_CUT);
}

/* Particle shifting (Lind et al. 2012; Skillen et al. 2013): after a step,
 * each fluid particle moves down the gradient of the particle concentration,
 *   delta r_a = -D grad C_a,   D = A h_a |u_a| dt              (Skillen et al.)
 *   grad C_a = sum_b V_b (1 + R (W_ab / W(dx))^n) grad_a W_ab  (Lind et al.,
 *              with Monaghan's (2000) anti-clumping term, R = 0.2, n = 4),
 * which evens out the particle distribution: particles crowded on one side
 * move to the other, and a pair closing up repels more strongly the
 * closer it gets. Walls and solids count as material in C, so a particle
 * next to a wall is not pushed into it. Near a free surface (the particle or
 * a fluid neighbour within the support has Gamma below
 * FREE_SURFACE_SHEPARD) C is truncated and grad C points into the fluid,
 * which would push the surface outwards; there only the part tangential to
 * the surface is kept (Lind et al.), the normal taken along the plain
 * colour gradient sum_b V_b grad_a W_ab. The fields are not corrected for
 * the displacement (it is a small fraction of dx per step: |u| dt is below
 * 0.25 h times the Mach number).
 * With a transport pressure p_tv, the displacement adds that of Adami, Hu &
 * Adams's (2013) transport velocity u~ = u + (dt / 2) a~ over the step,
 *   a~_a = -(p_tv / m_a) sum_b (V_a^2 + V_b^2) grad_a W_ab   (their Eq. 13),
 *   delta r_a += (dt^2 / 2) a~_a  times transport_share (above),
 * the pair pressure term of the multiphase form (Fuchs et al. 2022 Eq. 23)
 * at a uniform p_tv: what `background_pressure` adds to the force, moved
 * from the momentum to the positions. It too pushes particles from crowded
 * to sparse places, with no force on a body the particles pass; their
 * extra stress (Adami's A = rho u (u~ - u)) is left out. shift[a] is the
 * displacement (0 for walls and solids), added to the positions by the
 * drift kernel. */
KERNEL void shifting_displacement(GLOBAL const real *position, GLOBAL const real *velocity,
                                  GLOBAL const real *density, GLOBAL const real *mass,
                                  GLOBAL const real *gamma, GLOBAL const real *smoothing_length, GLOBAL const int *kind,
                                  GLOBAL const int *cell, int n, grid_geometry g,
                                  GLOBAL const int *cell_start, fluid_params p, real dt,
                                  GLOBAL real *shift)
{
    FOR_EACH_ITEM(a, n)
    {
        real delta_r[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        if (kind[a] == KIND_FLUID) {
            int cc[3];
            grid_cell_coords(&g, cell[a], cc);
            const smoothing_scale scale = smoothing_scale_of(p.h);
            const real w_dx = smoothing_w_at(&scale, p.dx);
            real grad_c[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
            real colour[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
            real transport[3] = {REAL(0.0), REAL(0.0), REAL(0.0)}; /* sum_b (V_a^2 + V_b^2) grad_a W_ab */
            const real volume_a = mass[a] / density[a];
            int near_surface = gamma[a] < FREE_SURFACE_SHEPARD;
            const real support = SUPPORT_OVER_H * p.h_max;
            const real h_a = particle_smoothing_length(smoothing_length, a, &p);
            real x_a[3];
            grid_point(position, a, x_a);
            FOR_EACH_NEIGHBOUR(b, run, &g, cc, x_a, cell_start, support)
            {
                real r_ab[3], r2;
                if (b == a || !grid_pair_within(&run, position, b, support * support, r_ab, &r2))
                    continue;
                const real r = sqrt(r2);
                const smoothing_scale scale_ab =
                    pair_smoothing_scale(&scale, h_a, particle_smoothing_length(smoothing_length, b, &p), &p);
                const real f = smoothing_grad_factor_at(&scale_ab, r); /* grad_a W_ab = f r_ab */
                const real volume_b = mass[b] / density[b];
                const real fv = f * volume_b;
                const real w_dx_ab = p.smoothing_length == SMOOTHING_VOLUME ? smoothing_w_at(&scale_ab, p.dx) : w_dx;
                const real w = smoothing_w_at(&scale_ab, r) / w_dx_ab;
                const real clumping = REAL(1.0) + REAL(0.2) * (w * w) * (w * w);
                for (int d = 0; d < 3; ++d) {
                    grad_c[d] += clumping * fv * r_ab[d];
                    colour[d] += fv * r_ab[d];
                    transport[d] += (volume_a * volume_a + volume_b * volume_b) * f * r_ab[d];
                }
                near_surface |= kind[b] == KIND_FLUID && gamma[b] < FREE_SURFACE_SHEPARD;
            }
            real u_a[3];
            for (int d = 0; d < 3; ++d)
                u_a[d] = velocity[3 * a + d];
            const real speed = sqrt(dot3(u_a, u_a));
            const real diffusivity = p.shifting * h_a * speed * dt;
            const real colour_norm = sqrt(dot3(colour, colour));
            const real transport_step =
                REAL(0.5) * dt * dt * p.transport_pressure / mass[a] * transport_share(colour_norm * h_a);
            for (int d = 0; d < 3; ++d)
                delta_r[d] = -diffusivity * grad_c[d] - transport_step * transport[d];
            if (near_surface && colour_norm > REAL(0.0)) {
                const real normal_part = dot3(delta_r, colour) / (colour_norm * colour_norm);
                for (int d = 0; d < 3; ++d)
                    delta_r[d] -= normal_part * colour[d];
            }
        }
        for (int d = 0; d < 3; ++d)
            shift[3 * a + d] = delta_r[d];
    }
}
