/* Surface tension on free surfaces: Russell's modification of Morris's CSF
 * scheme (Russell 2018 Sec. 3.1.2, Eqs. 3.26-3.31), and the Marangoni force
 * (Russell Eqs. 3.32-3.35 with PHYSICS.md erratum 4).
 *
 * Every particle (fluid, fixed solid, wall) has colour c = 1 and the outside
 * has c = 0, so the colour gradient lives on free surfaces only: where liquid
 * meets the solid of the same material, or a wall, there is no surface and
 * no tension (Russell: "solid and fluid particles were considered to be of
 * the same color function"). A gas (materials[].phase) is outside: its
 * particles have c = 0 and no normal, so the liquid sees a gas as it sees
 * the void, and the CSF force acts on the liquid side of a liquid-gas
 * interface (the denser phase, as Fuchs et al. 2022 Remark 3 has it). The terms use their own smoothing length h_st
 * (surface_params.h; Russell: 1.5 times the fluid's), so their pair loops
 * reach p.reach cells around a particle's cell.
 *
 * A liquid whose material has a contact angle theta0 (p.wetting) meets
 * solids and walls at that angle (Fuchs et al. 2022 Sec. 3.3.3): near them
 * its normals are turned to the angle (Eqs. 27-29, surface_normal), and its
 * curvature and the curvature's smoothing sum over liquid particles only,
 * so the free face of a solid or wall beside the drop (a solid-void surface,
 * not the liquid's) does not bend the liquid's normal field. Its colour
 * gradient still counts solids and walls as material: in this single-phase
 * model the gas is the void, and the wetted base, where the liquid touches
 * the solid, is no liquid-gas surface. The gathers, over the particles near
 * the liquid (blocks_from_liquid):
 *   surface_blocks_*   each block of cells' distance from the nearest liquid
 *   surface_shepard    Gamma_a = sum_b V_b W_ab
 *   surface_normal     n_a (Eq. 3.26)
 *   surface_wetting    n^_a turned to the contact angle (Fuchs Eqs. 27-29; only
 *                      with p.wetting)
 *   surface_curvature  kappa_a of the particles with a normal (Eqs. 3.27, 3.28,
 *                      taken to the surface; cap)
 *   surface_force      smoothed kappa (Eq. 3.30), the CSF force (Eq. 3.31) and
 *                      the Marangoni force (Eq. 3.35) on fluid particles; in
 *                      the conservative form also the capillary stress's
 *                      divergence, and its difference to the CSF force
 *   surface_share      (conservative form) that difference shared out over
 *                      the liquid, so that the tension's sum is the stress's.
 * W is the case's smoothing kernel at h_st (kernels/smoothing.h). */
#include "device.h"
#include "kinds.h"
#include "materials.h"
#include "neighbours.h"
#include "smoothing.h"
#include "surface_params.h"
#include "transition.h"
#include "vec3.h"

#define GAS_CONSTANT REAL(8.314462618) /* J/(mol K) */

/* ln(1 + e^y), without overflow for large y. */
static inline real softplus(real y)
{
    return y > REAL(0.0) ? y + log1p(exp(-y)) : log1p(exp(y));
}

/* Surface tension sigma(T) of a material and its slope d sigma/dT
 * (Sahoo, DebRoy & McNallan 1988; Russell 2018 Eq. 4.2):
 *   sigma = sigma0 + slope (T - T_ref) - R T Gamma_s ln(1 + k_l a_s e^(-dH0/(R T)))
 *   d sigma/dT = slope - R Gamma_s ln(1 + K a_s) - Gamma_s dH0 K a_s / (T (1 + K a_s)),
 * K = k_l e^(-dH0/(R T)); with Gamma_s = 0 a linear law, with slope = 0 too
 * a constant; never below sigma_min (where it is held, the slope is 0).
 * ln(1 + K a_s) = softplus(y), y = ln(k_l a_s) - dH0/(R T), stays finite
 * where K would overflow a float (cold solid, dH0 < 0). */
static inline real surface_tension(GLOBAL const real *materials, int material, real t, real *slope)
{
    real sigma = material_value(materials, material, MATERIAL_SURFACE_TENSION) +
                 material_value(materials, material, MATERIAL_SURFACE_TENSION_SLOPE) *
                     (t - material_value(materials, material, MATERIAL_SURFACE_TENSION_TREF));
    real d_sigma = material_value(materials, material, MATERIAL_SURFACE_TENSION_SLOPE);
    const real excess = material_value(materials, material, MATERIAL_SURFACTANT_EXCESS);
    if (excess > REAL(0.0)) {
        const real t_abs = fmax(t, REAL(1.0));
        const real enthalpy = material_value(materials, material, MATERIAL_SURFACTANT_ENTHALPY);
        const real y = material_value(materials, material, MATERIAL_SURFACTANT_LOG_K) -
                       enthalpy / (GAS_CONSTANT * t_abs);
        const real coverage = REAL(1.0) / (REAL(1.0) + exp(-y)); /* K a_s / (1 + K a_s) */
        sigma -= GAS_CONSTANT * t_abs * excess * softplus(y);
        d_sigma -= GAS_CONSTANT * excess * softplus(y) + excess * enthalpy * coverage / t_abs;
    }
    const real sigma_min = material_value(materials, material, MATERIAL_SURFACE_TENSION_MIN);
    if (sigma < sigma_min) {
        sigma = sigma_min;
        d_sigma = REAL(0.0);
    }
    *slope = d_sigma;
    return sigma;
}

/* Squared support radius of the surface terms: farther pairs add nothing,
 * and most of the (2 reach + 1)^d cells' particles are farther. */
static inline real surface_support2(const surface_params *p)
{
    return SUPPORT_OVER_H * SUPPORT_OVER_H * p->h * p->h;
}

/* The centre of particle a's loop over its surface support: its cell's
 * coordinates cc and its position x; returns the squared support radius. */
static inline real surface_loop_centre(const grid_geometry *g, const surface_params *p, GLOBAL const int *cell,
                                       GLOBAL const real *position, int a, int cc[3], real x[3])
{
    grid_cell_coords(g, cell[a], cc);
    grid_point(position, a, x);
    return surface_support2(p);
}

/* The correction of the normals reaches from c_sf = WETTING_C1 (f = 0) to
 * full at c_sf = WETTING_C2 (Fuchs et al. 2022 Eq. 29: c1 = 0, c2 = 0.2);
 * vectors of a dimensionless size below WETTING_EPSILON have no direction
 * (Fuchs's epsilon of Eqs. 20, 28, 29). */
#define WETTING_C1 REAL(0.0)
#define WETTING_C2 REAL(0.2)
#define WETTING_EPSILON REAL(1e-6)

/* theta0 of particle a (rad) where a is a liquid whose material has a
 * contact angle; 0 elsewhere (and always without p.wetting). */
static inline real contact_angle(GLOBAL const int *kind, GLOBAL const int *material,
                                 GLOBAL const real *materials, const surface_params *p, int a)
{
    return p->wetting && kind[a] == KIND_FLUID ? material_value(materials, material[a], MATERIAL_CONTACT_ANGLE)
                                               : REAL(0.0);
}

/* Whether neighbour b enters the curvature of a liquid with a contact
 * angle (theta0 > 0): liquid only; every particle otherwise. */
static inline int shapes_curvature(real theta0, int kind_b)
{
    return theta0 <= REAL(0.0) || kind_b == KIND_FLUID;
}

/* The solid colour chi_b of particle b (Fuchs et al. 2022 Sec. 3.3.3):
 * 1 on walls, 0 on fluid; on a fixed solid of a melting material
 * f-bar[T_b, T_sol - dT_s, T_sol] (Eq. 21), so that the colour fades out
 * before the solid melts (at the solidus it turns fluid, host/thermal.c)
 * instead of jumping; 1 where the material does not melt or the case has
 * no temperatures. */
static inline real solid_colour(int kind_b, int material_b, real t_b, GLOBAL const real *materials,
                                int temperature)
{
    if (kind_b == KIND_FLUID)
        return REAL(0.0);
    const real low = material_value(materials, material_b, MATERIAL_SOLID_COLOUR_LOW);
    const real high = material_value(materials, material_b, MATERIAL_SOLID_COLOUR_HIGH);
    if (kind_b == KIND_WALL || !temperature || !(high > low))
        return REAL(1.0);
    return REAL(1.0) - transition(t_b, low, high);
}

/* Unit vector of v into u; 0 where |v| scale <= WETTING_EPSILON. */
static inline void wetting_unit(const real v[3], real scale, real u[3])
{
    const real size = sqrt(dot3(v, v));
    for (int d = 0; d < 3; ++d)
        u[d] = size * scale > WETTING_EPSILON ? v[d] / size : REAL(0.0);
}

/* The unit normal n (inward, this module's convention) of a liquid particle
 * near solids, turned towards the contact angle theta0 after Fuchs et al.
 * 2022 Eqs. 27-29 in their outward convention (n_lg = -n):
 *   n_sf = grad c_sf / |grad c_sf|        (Eqs. 19-20: from the liquid into the solid)
 *   t_sf = n_lg - (n_lg . n_sf) n_sf, normalised            (Eq. 28)
 *   n^_lg = t_sf sin theta0 - n_sf cos theta0               (Eq. 27)
 *   n <- -(f[c_sf, c1, c2] n^_lg + f-bar[c_sf, c1, c2] n_lg), normalised (Eq. 29)
 * with n_lg = g / |g|, g the smoothed outward colour gradient of
 * surface_wetting (in place of the particle's own normal: see there); h
 * makes |grad c_sf| and |g| (1/m) dimensionless for the epsilon tests. */
static inline void wetted_normal(real theta0, real c_sf, const real grad_sf[3], const real g[3],
                                 real h, real n[3])
{
    real n_sf[3], n_lg[3], t_tilde[3], t_sf[3], blend[3];
    wetting_unit(grad_sf, h, n_sf);
    wetting_unit(g, h, n_lg);
    const real along = dot3(n_lg, n_sf);
    for (int d = 0; d < 3; ++d)
        t_tilde[d] = n_lg[d] - along * n_sf[d];
    wetting_unit(t_tilde, REAL(1.0), t_sf);
    const real f = transition(c_sf, WETTING_C1, WETTING_C2);
    for (int d = 0; d < 3; ++d)
        blend[d] = f * (t_sf[d] * sin(theta0) - n_sf[d] * cos(theta0)) + (REAL(1.0) - f) * n_lg[d];
    wetting_unit(blend, REAL(1.0), n_lg);
    for (int d = 0; d < 3; ++d)
        n[d] = -n_lg[d];
}

static inline real normal_size(GLOBAL const real *normal, int a)
{
    return sqrt(normal[3 * a] * normal[3 * a] + normal[3 * a + 1] * normal[3 * a + 1] +
                normal[3 * a + 2] * normal[3 * a + 2]);
}

/* Does particle b have colour 1: liquid, solid or wall, not gas? */
static inline int colour_material(GLOBAL const real *materials, GLOBAL const int *material, int b)
{
    return !material_is_gas(materials, material[b]);
}

/* Whether particle a is a liquid: fluid, not gas. */
static inline int is_liquid(GLOBAL const int *kind, GLOBAL const int *material, GLOBAL const real *materials, int a)
{
    return kind[a] == KIND_FLUID && colour_material(materials, material, a);
}

/* Whether particle a takes the CSF force of surface_force: a liquid with
 * Gamma_a >= min_shepard. */
static inline int takes_surface_force(GLOBAL const int *kind, GLOBAL const int *material,
                                      GLOBAL const real *materials, GLOBAL const real *shepard,
                                      const surface_params *p, int a)
{
    return is_liquid(kind, material, materials, a) && shepard[a] >= p->min_shepard;
}

/* Whether surface_force writes the surface force of particle a (and
 * surface_contact_pull leaves it): the particles that take the CSF force;
 * in the conservative form every liquid particle, as each takes its
 * pairs' share of the capillary stress, of its neighbours' stress too. */
static inline int records_surface_force(GLOBAL const int *kind, GLOBAL const int *material,
                                        GLOBAL const real *materials, GLOBAL const real *shepard,
                                        const surface_params *p, int a)
{
    return p->form == TENSION_FORM_CONSERVATIVE ? is_liquid(kind, material, materials, a)
                                                : takes_surface_force(kind, material, materials, shepard, p, a);
}

/* The unit normal that the surface stress of particle a takes: the (turned)
 * unit normal n^_a where it has one (psi_a > 0), else n_a / |n_a| (the CSF
 * force acts on every liquid particle with a colour gradient); 0 without. */
static inline void stress_normal(GLOBAL const real *normal, GLOBAL const real *unit_normal,
                                 GLOBAL const real *normal_weight, int a, real n_hat[3])
{
    const real size = normal_size(normal, a);
    for (int d = 0; d < 3; ++d)
        n_hat[d] = normal_weight[a] > REAL(0.0) ? unit_normal[3 * a + d]
                   : size > REAL(0.0)           ? normal[3 * a + d] / size
                                                : REAL(0.0);
}

/* T . r for the capillary stress of the interface (Lafaurie et al. 1994,
 * J. Comput. Phys. 113, Eq. 6; in SPH Hu & Adams 2006, J. Comput. Phys.
 * 213, Eq. 18)
 *   T = sigma |n| (1 - n^ n^),
 * its size sigma |n| given, n^ the unit normal of stress_normal. */
static inline void capillary_stress_dot(real size, const real n_hat[3], const real r[3], real out[3])
{
    const real along = dot3(n_hat, r);
    for (int d = 0; d < 3; ++d)
        out[d] = size * (r[d] - along * n_hat[d]);
}

/* The size sigma_a |n_a| of the capillary stress of particle a, and its
 * unit normal into n_hat: a liquid that takes the surface force carries
 * it (sigma at temperature t_a); 0 elsewhere. */
static inline real capillary_stress_size(GLOBAL const int *kind, GLOBAL const int *material,
                                         GLOBAL const real *materials, GLOBAL const real *shepard,
                                         GLOBAL const real *normal, GLOBAL const real *unit_normal,
                                         GLOBAL const real *normal_weight, const surface_params *p, int a,
                                         real t_a, real n_hat[3])
{
    real slope;
    stress_normal(normal, unit_normal, normal_weight, a, n_hat);
    return takes_surface_force(kind, material, materials, shepard, p, a)
               ? surface_tension(materials, material[a], t_a, &slope) * normal_size(normal, a)
               : REAL(0.0);
}

/* The weight 1/Gamma_b of particle b's side of a stress pair (0 where no
 * Shepard sum was taken). */
static inline real stress_weight(GLOBAL const real *shepard, int b)
{
    return shepard[b] > REAL(0.0) ? REAL(1.0) / shepard[b] : REAL(0.0);
}

/* The weight of the pair of liquid a and solid r in the flux of the
 * capillary stress into the solid (capillary_stress_pair,
 * surface_contact_pull): the solid takes a's stress T_a as its own, the
 * interface continued into the wall, so the pair's term is
 * T_a (1/Gamma_r + 1/Gamma_a) . grad W. With T_r = 0 the pairs hold only
 * the liquid's side of the smoothed jump of T at the wall,
 * int_liquid T . grad phi_s dV = T phi_s(wall) = T / 2 (phi_s the solid's
 * kernel-smoothed indicator), about half the pull: a 2D liquid bridge at
 * 90 degrees pulled each plate with 0.50 (CSF form, weight 1) and 0.58
 * (conservative, 1/Gamma_r) of 2 sigma, and with this weight 1.05 and 1.06
 * (test_grains bridge). */
static inline real solid_pair_weight(GLOBAL const real *shepard, int a, int r)
{
    return stress_weight(shepard, r) + stress_weight(shepard, a);
}

/* Pair b's term of the divergence of the capillary stress at liquid
 * particle a, free-surface consistent as the colour gradient is (Russell
 * 2018 Eq. 3.26: the weights 1/Gamma),
 *   f_a = sum_b V_b (T_a / Gamma_b + T_b / Gamma_a) . grad_a W_ab,
 * added to stress (per volume); stress_a and n_a are a's stress size and
 * normal (capillary_stress_size), f_v_b = V_b f with grad_a W_ab = f r_ab.
 * A pair's terms on a and b are equal and opposite (grad_b W_ba =
 * -grad_a W_ab), so their sum over a body of liquid is zero; its pairs with
 * solids (T_b = T_a there, solid_pair_weight) leave the contact-line pull,
 * whose reaction surface_contact_pull gives the solids. */
static inline void capillary_stress_pair(GLOBAL const int *kind, GLOBAL const int *material,
                                         GLOBAL const real *materials, GLOBAL const real *shepard,
                                         GLOBAL const real *normal, GLOBAL const real *unit_normal,
                                         GLOBAL const real *normal_weight, GLOBAL const real *temperature,
                                         const surface_params *p, real stress_a, const real n_a[3], int a, int b,
                                         const real r_ab[3], real f_v_b, real stress[3])
{
    real n_b[3], t_a[3], t_b[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
    if (kind[b] != KIND_FLUID) {
        capillary_stress_dot(stress_a * solid_pair_weight(shepard, a, b), n_a, r_ab, t_a);
    } else {
        const real stress_b = capillary_stress_size(kind, material, materials, shepard, normal, unit_normal,
                                                    normal_weight, p, b, p->temperature ? temperature[b] : REAL(0.0),
                                                    n_b);
        capillary_stress_dot(stress_a * stress_weight(shepard, b), n_a, r_ab, t_a);
        capillary_stress_dot(stress_b * stress_weight(shepard, a), n_b, r_ab, t_b);
    }
    for (int d = 0; d < 3; ++d)
        stress[d] += f_v_b * (t_a[d] + t_b[d]);
}

/* The particles near the liquid. The liquid's forces (surface_force) read
 * the curvature of the particles within one surface support of it, which
 * reads the normals within two supports, which read the Shepard sums
 * within three; what lies farther reaches no liquid. The grid's cells are
 * grouped into blocks of p.reach cells per axis, each at least one support
 * wide, so a neighbour is at most one block away. surface_blocks_mark and
 * surface_blocks_spread give every block its distance from the nearest
 * block with a liquid particle, in blocks (Chebyshev: the largest of the
 * axes' distances; larger than p.near_blocks + 1 counts as far). A particle
 * k blocks away takes part in
 *   the Shepard sums                  where k <= near_blocks,
 *   the normals                       where k <= near_blocks - 1,
 *   the curvature and the contact pull where k <= near_blocks - 2,
 * and its terms are 0 elsewhere. The surface force's loop runs on liquid
 * particles only. With near_blocks = SURFACE_NEAR_BLOCKS (3) the liquid's
 * terms are those of passes over every particle, and in a scene that is
 * mostly solid (a substrate under a melt pool, a powder bed) the passes
 * cost in proportion to the melt. Where every liquid has a contact angle
 * (*plain = 0, surface_blocks_mark), the curvature and its smoothing read liquid
 * normals only (shapes_curvature), so only liquid particles take a normal
 * and the Shepard sums that those normals read lie within one support of
 * the liquid, k <= near_blocks - 2; the liquid's terms are the same. Those
 * Shepard sums and the contact pull's loop on a solid also need a liquid
 * particle within the particle's own support, which the grid's fluid
 * counts tell cell by cell (fluid_within_support): the blocks bound the
 * liquid's reach only to within a block. */
#define SURFACE_FAR 0x40000000

/* The block of a cell (-1 for the cell of the particles that left the domain). */
static inline int surface_block(const grid_geometry *g, const surface_params *p, int cell)
{
    if (cell < 0 || cell >= g->total_cells)
        return -1;
    int cc[3];
    grid_cell_coords(g, cell, cc);
    int k = 0;
    for (int d = 2; d >= 0; --d) {
        const int b = cc[d] / p->reach;
        k = k * p->blocks[d] + (b < p->blocks[d] ? b : p->blocks[d] - 1);
    }
    return k;
}

/* The distance from the liquid, in blocks, of the particle in cell `cell`. */
static inline int blocks_from_liquid(GLOBAL const int *blocks_away, const grid_geometry *g,
                                     const surface_params *p, int cell)
{
    const int k = surface_block(g, p, cell);
    return k < 0 ? SURFACE_FAR : blocks_away[k];
}

/* count[k] = the liquid particles in block k (count zeroed before); *plain
 * += those of them without a contact angle. */
KERNEL void surface_blocks_mark(GLOBAL const int *kind, GLOBAL const int *material, GLOBAL const real *materials,
                                GLOBAL const int *cell, int n, grid_geometry g, surface_params p,
                                GLOBAL int *count, GLOBAL int *plain)
{
    FOR_EACH_ITEM(a, n)
    {
        const int k = surface_block(&g, &p, cell[a]);
        if (k >= 0 && is_liquid(kind, material, materials, a)) {
            ATOMIC_INC(&count[k]);
            if (contact_angle(kind, material, materials, &p, a) <= REAL(0.0))
                ATOMIC_INC(plain);
        }
    }
}

/* One axis of the blocks' distance from the liquid, which separates axis by
 * axis as the largest of the axes' distances does:
 *   out[k] = min over |s| <= near_blocks + 1 of max(|s|, in[k + s e_axis]),
 * k + s wrapped around a periodic axis and dropped past a closed one's
 * ends; with from_count, in holds surface_blocks_mark's counts (a block
 * with liquid is 0 blocks away, one without far). */
KERNEL void surface_blocks_spread(GLOBAL const int *in, int axis, int from_count, grid_geometry g,
                                  surface_params p, GLOBAL int *out)
{
    FOR_EACH_ITEM(k, surface_block_count(&p))
    {
        int stride = 1;
        for (int d = 0; d < axis; ++d)
            stride *= p.blocks[d];
        const int blocks = p.blocks[axis], at = k / stride % blocks;
        int nearest = SURFACE_FAR;
        for (int s = -p.near_blocks - 1; s <= p.near_blocks + 1; ++s) {
            int j = at + s;
            if (g.periodic[axis])
                j = (j % blocks + blocks) % blocks;
            else if (j < 0 || j >= blocks)
                continue;
            const int value = in[k + (j - at) * stride];
            const int away = from_count ? (value > 0 ? 0 : SURFACE_FAR) : value;
            const int shift = s < 0 ? -s : s;
            const int here = away > shift ? away : shift;
            nearest = here < nearest ? here : nearest;
        }
        out[k] = nearest;
    }
}

/* How far from the liquid, in blocks, the Shepard sums are read (see above). */
static inline int shepard_blocks(const surface_params *p, GLOBAL const int *plain)
{
    return *plain > 0 ? p->near_blocks : p->near_blocks - 2;
}

/* Whether particle a takes a normal: colour 1, within near_blocks - 1 of
 * the liquid, and a liquid itself where every liquid has a contact angle. */
static inline int takes_normal(GLOBAL const int *kind, GLOBAL const int *material, GLOBAL const real *materials,
                               GLOBAL const int *blocks_away, GLOBAL const int *plain, const grid_geometry *g,
                               const surface_params *p, GLOBAL const int *cell, int a)
{
    return (*plain > 0 ? colour_material(materials, material, a) : is_liquid(kind, material, materials, a)) &&
           blocks_from_liquid(blocks_away, g, p, cell[a]) <= p->near_blocks - 1;
}

/* Whether a fluid particle lies in the box of cells of the surface
 * support around cell `cell`: the grid's fluid counts, which the step's
 * continuity pass has made (kernels/neighbours.h grid_fluid_in_box). The
 * fluid holds the liquid, so where this is 0 no liquid is within the
 * support of a particle in that cell. */
static inline int fluid_within_support(const grid_geometry *g, GLOBAL const int *cell_start,
                                       GLOBAL const int *fluid_count, const surface_params *p, int cell)
{
    int cc[3];
    grid_cell_coords(g, cell, cc);
    return grid_fluid_in_box(g, cell_start, fluid_count, cc, p->reach);
}

/* Gamma_a = sum_b V_b W_ab at h_st, over every particle of colour 1, where
 * a normal reads it: within shepard_blocks of the liquid and, where only
 * the liquid takes a normal (*plain = 0), with a liquid within a's support;
 * 0 elsewhere. With wetting, a solid's f and L of surface_wet_colour from
 * the same sum (0 on the fluid and where it is not taken). */
KERNEL void surface_shepard(GLOBAL const real *position, GLOBAL const real *density,
                            GLOBAL const real *mass, GLOBAL const int *material, GLOBAL const int *cell,
                            int n, grid_geometry g, GLOBAL const int *cell_start, GLOBAL const int *fluid_count,
                            GLOBAL const int *kind, GLOBAL const real *materials, GLOBAL const int *blocks_away,
                            GLOBAL const int *plain, surface_params p, GLOBAL real *shepard,
                            GLOBAL real *wet_fraction)
{
    FOR_EACH_ITEM(a, n)
    {
        real sum = REAL(0.0), liquid = REAL(0.0);
        if (blocks_from_liquid(blocks_away, &g, &p, cell[a]) <= shepard_blocks(&p, plain) &&
            (*plain > 0 || fluid_within_support(&g, cell_start, fluid_count, &p, cell[a]))) {
            int cc[3];
            real x_a[3];
            const real support2 = surface_loop_centre(&g, &p, cell, position, a, cc, x_a), support = sqrt(support2);
            FOR_EACH_NEIGHBOUR_NEAR(b, run, &g, cc, x_a, cell_start, p.reach, support)
            {
                real r_ab[3], r2;
                if (colour_material(materials, material, b) &&
                    grid_pair_within(&run, position, b, support2, r_ab, &r2)) {
                    const real w = smoothing_w(sqrt(r2), p.h) * mass[b] / density[b];
                    sum += w;
                    liquid += kind[b] == KIND_FLUID ? w : REAL(0.0);
                }
            }
        }
        shepard[a] = sum;
        if (p.wetting) {
            const int solid = kind[a] != KIND_FLUID && liquid > REAL(0.0);
            wet_fraction[2 * a] = solid ? liquid / fmax(REAL(1.0) - (sum - liquid), liquid) : REAL(0.0);
            wet_fraction[2 * a + 1] = solid ? liquid : REAL(0.0);
        }
    }
}

/* The wet colour of the solids, with which they enter the liquid-gas
 * normal of the wetting model (the wet normal of surface_normal, read by
 * surface_wetting for n_lg in Fuchs et al. 2022 Eqs. 28-29): 1 where the
 * liquid covers the solid's face, 0 on its dry face. With colour 1 on
 * every solid, the dry face above a contact line is part of the liquid's
 * body to the normals of the rows above those that Eq. 29 turns fully;
 * they lean towards the wall, and a 2D liquid bridge at 90 degrees
 * (test_grains bridge) bulged from about 2.5 s (6 s: 0.524 m high at the
 * plates, 0.630 m in the middle, +11.9 Pa where a flat bridge has 0; with
 * the wet colour 0.583 and 0.568 m, +0.88 Pa). Only that normal takes it:
 * with the dry face at 0 in the colour gradient that carries the CSF
 * force, a drop at 120 degrees climbed off its wall (BENCHMARKS.md).
 * Each solid r that takes a Shepard sum takes, in surface_shepard,
 *   L_r = sum_b V_b W_rb over the liquid b,  S_r = sum_b V_b W_rb over the solids b,
 *   f_r = L_r / max(1 - S_r, L_r):
 * the liquid's share of the space around r that the solids leave open
 * (1 - S_r; the sum of V W over a full support is 1). f is the wet colour
 * on the solid's face; deeper in a solid thinner than two supports,
 * 1 - S_r also holds the empty space behind it (f = 0.07 on the third row
 * of a plate four rows thick, under the liquid). surface_wet_colour
 * carries the face's value into the solid as the mean
 *   c_r = sum_b W_rb L_b^3 f_b / sum_b W_rb L_b^3
 * over the solids b (b = r too), in which the face's rows, with the
 * largest L, outweigh the rest; 1 on the fluid, which surface_normal does
 * not read. */
KERNEL void surface_wet_colour(GLOBAL const real *position, GLOBAL const int *kind, GLOBAL const int *cell,
                               int n, grid_geometry g, GLOBAL const int *cell_start, surface_params p,
                               GLOBAL const real *wet_fraction, GLOBAL real *wet_colour)
{
    FOR_EACH_ITEM(a, n)
    {
        real sum = REAL(0.0), weight = REAL(0.0);
        if (kind[a] != KIND_FLUID && wet_fraction[2 * a + 1] > REAL(0.0)) {
            int cc[3];
            real x_a[3];
            const real support2 = surface_loop_centre(&g, &p, cell, position, a, cc, x_a), support = sqrt(support2);
            FOR_EACH_NEIGHBOUR_NEAR(b, run, &g, cc, x_a, cell_start, p.reach, support)
            {
                real r_ab[3], r2;
                const real liquid_b = kind[b] == KIND_FLUID ? REAL(0.0) : wet_fraction[2 * b + 1];
                if (liquid_b <= REAL(0.0) || !grid_pair_within(&run, position, b, support2, r_ab, &r2))
                    continue; /* the fluid, and solids out of the liquid's reach (L_b = 0) */
                const real w = smoothing_w(sqrt(r2), p.h) * liquid_b * liquid_b * liquid_b;
                sum += w * wet_fraction[2 * b];
                weight += w;
            }
        }
        wet_colour[a] = kind[a] == KIND_FLUID ? REAL(1.0) : weight > REAL(0.0) ? sum / weight : REAL(0.0);
    }
}

/* The free-surface-consistent colour gradient (Russell 2018 Eq. 3.26) with
 * c = 1 on every particle but gas (c = 0, no normal):
 *   n_a = sum_b V_b (c_b / Gamma_a + c_a / Gamma_b) grad_a W_ab,
 * which points into the material, of size ~ 1 / (interface width); across
 * a surface it integrates to 1 (the jump of c). The unit normal n^_a enters
 * the curvature with the weight psi_a (Russell's ceil(n^_a), Eq. 3.28):
 *   psi_a = clamp(|n_a| h_st / cut-off - 1, 0, 1)   (cut-off: Russell Eq. 3.27, erratum 5)
 * where n_a . grad Gamma_a > 0 (grad Gamma_a = sum_b V_b grad_a W_ab) and
 * Gamma_a >= min_shepard, psi_a = 0 elsewhere. Two changes to the thesis:
 *  - psi ramps from 0 at the cut-off to 1 at twice the cut-off instead of
 *    jumping: the third row below a surface sits at |n| h ~ 0.1, and its
 *    normals switching on and off (Russell's flaw 3, which his curvature
 *    smoothing only softens) drove a 2D droplet unstable after a few seconds;
 *  - two to three rows below a surface, Eq. 3.26 has a lobe that points out
 *    of the material (the 1/Gamma_b of the surface particles outweighs the
 *    missing outer neighbours); on a circle cut from a square lattice those
 *    normals passed the cut-off at the steps and made the mean curvature
 *    2.6 times too large. They are not surface normals.
 * With wetting, every liquid particle also gets its wet normal: the same
 * sum with c_b the wet colour of surface_wet_colour on the solids, which
 * surface_wetting reads. It is taken as n_a less the solids' dry share
 * (1 - c_b), a sum over the solid neighbours only (5% off this kernel on
 * the 3D sessile cap and on a free 3D droplet, against a second full sum). */
KERNEL void surface_normal(GLOBAL const real *position, GLOBAL const real *density,
                           GLOBAL const real *mass, GLOBAL const real *shepard, GLOBAL const int *kind,
                           GLOBAL const int *material, GLOBAL const int *cell, int n, grid_geometry g,
                           GLOBAL const int *cell_start, GLOBAL const real *materials,
                           GLOBAL const int *blocks_away, GLOBAL const int *plain,
                           GLOBAL const real *wet_colour, surface_params p, GLOBAL real *normal,
                           GLOBAL real *unit_normal, GLOBAL real *normal_weight, GLOBAL real *wet_normal)
{
    FOR_EACH_ITEM(a, n)
    {
        real sum[3] = {REAL(0.0), REAL(0.0), REAL(0.0)}, dry[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        const int wets = p.wetting && kind[a] == KIND_FLUID;
        real grad_gamma[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        /* no normal on gas, nor far from the liquid (n_a = 0, psi_a = 0) */
        const int has_normal = takes_normal(kind, material, materials, blocks_away, plain, &g, &p, cell, a);
        if (has_normal) {
            int cc[3];
            real x_a[3];
            const real support2 = surface_loop_centre(&g, &p, cell, position, a, cc, x_a), support = sqrt(support2);
            const real inv_gamma_a = REAL(1.0) / shepard[a];
            FOR_EACH_NEIGHBOUR_NEAR(b, run, &g, cc, x_a, cell_start, p.reach, support)
            {
                real r_ab[3], r2;
                if (!colour_material(materials, material, b) ||
                    !grid_pair_within(&run, position, b, support2, r_ab, &r2))
                    continue;
                const real f = smoothing_grad_factor(sqrt(r2), p.h); /* grad_a W_ab = f r_ab */
                const real v_b = mass[b] / density[b];
                const real weight = v_b * (inv_gamma_a + REAL(1.0) / shepard[b]) * f;
                for (int d = 0; d < 3; ++d) {
                    sum[d] += weight * r_ab[d];
                    grad_gamma[d] += v_b * f * r_ab[d];
                }
                if (wets && kind[b] != KIND_FLUID) /* a solid: its dry share 1 - c_b */
                    for (int d = 0; d < 3; ++d)
                        dry[d] += (REAL(1.0) - wet_colour[b]) * weight * r_ab[d];
            }
        }
        const real size = sqrt(dot3(sum, sum));
        const int inward = has_normal && dot3(sum, grad_gamma) > REAL(0.0) && shepard[a] >= p.min_shepard;
        const real psi = inward ? fmin(fmax(size * p.h / p.normal_cutoff - REAL(1.0), REAL(0.0)), REAL(1.0))
                                : REAL(0.0);
        normal_weight[a] = psi;
        if (p.wetting)
            for (int d = 0; d < 3; ++d)
                wet_normal[3 * a + d] = wets ? sum[d] - dry[d] : REAL(0.0);
        for (int d = 0; d < 3; ++d) {
            normal[3 * a + d] = sum[d];
            unit_normal[3 * a + d] = psi > REAL(0.0) ? sum[d] / size : REAL(0.0);
        }
    }
}

/* Wetting (Fuchs et al. 2022 Sec. 3.3.3), on each liquid particle with a
 * contact angle theta0 and a normal (psi_a > 0), after surface_normal:
 *   c_sf = (1/V_a) sum_b chi_b (V_a^2 + V_b^2) rho_a / (rho_a + rho_b) W_ab
 * over the solids and walls b (Eq. 19 with chi_b = solid_colour; grad c_sf
 * with grad_a W_ab in place of W_ab), and
 *   g_a = -sum_b V_b W_ab n^wet_b
 * over the liquid b (b = a too): the outward colour gradients around a,
 * smoothed, which stand for the liquid-gas normal n_lg in the tangent t_sf
 * (Eq. 28) and the blend (Eq. 29); n^wet_b is the wet normal of
 * surface_normal, whose solids count with their wet colour
 * (surface_wet_colour), as a solid's dry face is no part of the liquid's
 * body. Fuchs takes the particle's own normal;
 * on a wetted base within a support of the contact line that normal is
 * short and points mostly away from the wall, so the sign of its part along
 * the wall is noise and neighbours got opposite tangents (capped curvature,
 * a drop that tore off its wall), and a row above it the lobe of Eq. 3.26
 * (surface_normal) points out of the liquid; the surface particles at the
 * contact line, whose colour gradients are largest, decide g_a. The unit
 * normal n^_a turns towards theta0 (wetted_normal); n_a, the colour gradient
 * that carries the CSF force (Fuchs Eq. 24: grad c, not the corrected
 * normal), stays. */
KERNEL void surface_wetting(GLOBAL const real *position, GLOBAL const real *density,
                            GLOBAL const real *mass, GLOBAL const real *wet_normal,
                            GLOBAL const real *normal_weight, GLOBAL const int *kind,
                            GLOBAL const int *material, GLOBAL const real *temperature,
                            GLOBAL const real *materials, GLOBAL const int *cell, int n,
                            grid_geometry g, GLOBAL const int *cell_start, surface_params p,
                            GLOBAL real *unit_normal)
{
    FOR_EACH_ITEM(a, n)
    {
        const real theta0 = contact_angle(kind, material, materials, &p, a);
        if (theta0 > REAL(0.0) && normal_weight[a] > REAL(0.0)) {
            int cc[3];
            real x_a[3];
            const real support2 = surface_loop_centre(&g, &p, cell, position, a, cc, x_a), support = sqrt(support2);
            const real v_a = mass[a] / density[a];
            real c_sf = REAL(0.0);
            real grad_sf[3] = {REAL(0.0), REAL(0.0), REAL(0.0)}, outward[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
            FOR_EACH_NEIGHBOUR_NEAR(b, run, &g, cc, x_a, cell_start, p.reach, support)
            {
                real r_ab[3], r2;
                if (!grid_pair_within(&run, position, b, support2, r_ab, &r2))
                    continue;
                const real r = sqrt(r2), v_b = mass[b] / density[b];
                if (kind[b] == KIND_FLUID) {
                    for (int d = 0; d < 3; ++d)
                        outward[d] -= v_b * smoothing_w(r, p.h) * wet_normal[3 * b + d];
                    continue;
                }
                const real t_b = p.temperature ? temperature[b] : REAL(0.0);
                const real chi = solid_colour(kind[b], material[b], t_b, materials, p.temperature) *
                                 (v_a * v_a + v_b * v_b) / v_a * density[a] / (density[a] + density[b]);
                c_sf += chi * smoothing_w(r, p.h);
                for (int d = 0; d < 3; ++d)
                    grad_sf[d] += chi * smoothing_grad_factor(r, p.h) * r_ab[d];
            }
            if (c_sf > WETTING_C1) {
                real n_hat[3];
                for (int d = 0; d < 3; ++d)
                    n_hat[d] = unit_normal[3 * a + d];
                wetted_normal(theta0, c_sf, grad_sf, outward, p.h, n_hat);
                for (int d = 0; d < 3; ++d)
                    unit_normal[3 * a + d] = n_hat[d];
            }
        }
    }
}

/* The curvature of the surface above a particle, from the curvature kappa
 * of the level set it lies on and its depth delta below the surface. The
 * particles of a surface band lie on level sets parallel to the surface;
 * below a sphere of radius R (a circle in 2D) the one at depth delta has
 * radius R - delta, so that with kappa = -(d - 1)/(R - delta)
 *   kappa_s = kappa / (1 - delta kappa / (d - 1))
 * (the mean curvature of a parallel surface; do Carmo 1976, Differential
 * Geometry of Curves and Surfaces, Sec. 3-5). Exact where the principal
 * curvatures are equal; on a 3D cylinder it takes out half the level set's
 * excess. Without it the band's rows 1 to 3 dx inside read their level
 * set's (d - 1)/(R - delta), and a droplet's Laplace pressure followed them
 * (+7.5% at R = 10 dx in 3D; BENCHMARKS.md, "The curvature at the
 * surface"). A concave surface (kappa > 0) is at most doubled (delta kappa
 * / (d - 1) <= 1/2), where the level set's centre would come within delta
 * of the particle; the liquid around a bubble of R = 10 dx reads 0.94 of
 * 2/R (0.87 uncorrected). */
static inline real curvature_at_surface(real kappa, real depth)
{
    return kappa / (REAL(1.0) - fmin(depth * kappa / (real)(AMSPH_DIM - 1), REAL(0.5)));
}

/* Curvature of the particles with a normal (psi_a > 0), over the neighbours
 * with one (Russell 2018 Eq. 3.28; Morris 2000 sums over those only), the
 * divergence of the unit normals taken along the surface:
 *   kappa_a = ((d - 1)/M_a) sum_b psi_b V_b F_ab n^_b . t_ab,
 *   M_a     = -sum_b psi_b V_b F_ab |t_ab|^2,   t_ab = r_ab - (r_ab . n^_a) n^_a,
 * grad_a W_ab = F_ab r_ab. A level set's unit normal varies along the
 * surface only, so for a normal field linear in x the sum reads the
 * tangential trace of its gradient against the tangential moment M_a, and
 * (d - 1)/M_a reads the divergence; on a full support M_a / (d - 1) = 1 and
 * Russell's Gamma*_a (Eq. 3.29) = 1 too, but on the band of particles with a
 * normal, and where a wall cuts it (the rows at a contact line), only M_a
 * stays consistent. Russell's (n^_b - n^_a) . r_ab differs from n^_b . t_ab
 * by (n^_b . n^_a - 1)(r_ab . n^_a), whose first factor any scatter of the
 * normals makes negative, never positive: on the outer row, whose
 * neighbours lie below it, the scatter read as convex curvature (a lattice
 * sphere of R = 10 dx with its particles moved by up to 0.1 dx read 1.13 of
 * 2/R; the body of a 3D cap at 120 degrees crept from 1.02 to 1.25 of 2/R
 * while its shape held, until its contact line gave way; BENCHMARKS.md, "The
 * curvature along the surface").
 * On a sphere each pair reads the curvature of b's level set, so kappa_a is
 * that of the level set at the neighbours' mean depth below a,
 *   u_a = sum_b w_b (kappa_a |t_ab|^2 / (2 (d - 1)) - r_ab . n^_a) / sum_b w_b,
 * w_b = -psi_b V_b F_ab |t_ab|^2, the first term the sag of the level set
 * over |t_ab| (Taylor; kappa_a < 0 on a convex surface). It is taken to the
 * surface (curvature_at_surface) from the depth u_a + delta_a, a's own depth
 *   delta_a = max(0, max_b r_ab . n^_a) + V_a^(1/d) / 2,
 * the height of its outermost neighbour along the outward normal -n^_a,
 * over the b within 45 degrees of it (a normal tilted by epsilon raises a
 * neighbour at t_ab by epsilon |t_ab|, which the max would keep), and half
 * a spacing from the outer row's centres to the surface. Capped at
 * |kappa| <= 1/(2 h_st) (Russell Sec. 3.1.2, flaw 4), within near_blocks - 2
 * blocks of the liquid (blocks_from_liquid); 0 elsewhere and where M_a = 0
 * (no neighbour along the surface). With the inward normal, a convex surface
 * has kappa < 0 (a circle: -1/R). A liquid with a contact angle sums over
 * liquid b only (shapes_curvature). */
KERNEL void surface_curvature(GLOBAL const real *position, GLOBAL const real *density,
                              GLOBAL const real *mass, GLOBAL const real *unit_normal,
                              GLOBAL const real *normal_weight, GLOBAL const int *kind,
                              GLOBAL const int *material, GLOBAL const real *materials,
                              GLOBAL const int *cell, int n, grid_geometry g,
                              GLOBAL const int *cell_start, GLOBAL const int *blocks_away,
                              surface_params p, GLOBAL real *curvature)
{
    FOR_EACH_ITEM(a, n)
    {
        real kappa = REAL(0.0);
        const real theta0 = contact_angle(kind, material, materials, &p, a);
        if (normal_weight[a] > REAL(0.0) && blocks_from_liquid(blocks_away, &g, &p, cell[a]) <= p.near_blocks - 2) {
            int cc[3];
            real x_a[3], n_a[3];
            const real support2 = surface_loop_centre(&g, &p, cell, position, a, cc, x_a), support = sqrt(support2);
            real divergence = REAL(0.0), moment = REAL(0.0), rise = REAL(0.0), lift = REAL(0.0), spread = REAL(0.0);
            for (int d = 0; d < 3; ++d)
                n_a[d] = unit_normal[3 * a + d];
            FOR_EACH_NEIGHBOUR_NEAR(b, run, &g, cc, x_a, cell_start, p.reach, support)
            {
                if (normal_weight[b] <= REAL(0.0) || !shapes_curvature(theta0, kind[b]))
                    continue;
                real r_ab[3], r2;
                if (!grid_pair_within(&run, position, b, support2, r_ab, &r2))
                    continue;
                const real v_b = normal_weight[b] * mass[b] / density[b];
                const real f = v_b * smoothing_grad_factor(sqrt(r2), p.h);
                const real across = dot3(r_ab, n_a);
                real n_b[3];
                for (int d = 0; d < 3; ++d)
                    n_b[d] = unit_normal[3 * b + d];
                const real tangential2 = r2 - across * across;
                divergence += f * (dot3(n_b, r_ab) - across * dot3(n_b, n_a)); /* f n^_b . t_ab */
                moment -= f * tangential2;
                lift -= f * tangential2 * across;
                spread -= f * tangential2 * tangential2;
                if (across * across >= tangential2)
                    rise = fmax(rise, across);
            }
            if (moment > REAL(0.0)) {
                const real level = (real)(AMSPH_DIM - 1) * divergence / moment;
                const real below = (level * spread / (REAL(2.0) * (real)(AMSPH_DIM - 1)) - lift) / moment; /* u_a */
                const real depth = below + rise + REAL(0.5) * dimension_root(mass[a] / density[a]);
                kappa = curvature_at_surface(level, depth);
                kappa = fmin(fmax(kappa, -p.max_curvature), p.max_curvature);
            }
        }
        curvature[a] = kappa;
    }
}

/* The term of gas particle b in the liquid-gas colour gradient of liquid
 * particle a (Fuchs et al. 2022 Eq. 19, chi = 1, b over the gas):
 *   grad c_a = (1/V_a) sum_b (V_a^2 + V_b^2) rho_a / (rho_a + rho_b) grad_a W_ab,
 * which points out of the liquid. It is the colour gradient that the
 * multiphase pressure force (Fuchs Eq. 23, kernels/fluid.cl) balances: a
 * pressure P inside the liquid and none in the gas push liquid particle a
 * with P V_a grad c_a (as sum_b (V_a^2 + V_b^2) grad_a W_ab vanishes over a
 * full support), so a CSF force along it holds the Young-Laplace jump
 * without the mismatch of two different discrete gradients. Returned as
 * the factor of r_ab, f the kernel's grad_a W_ab = f r_ab. */
static inline real interface_colour_factor(real m_a, real rho_a, real m_b, real rho_b, real f)
{
    const real v_a = m_a / rho_a, v_b = m_b / rho_b;
    return (v_a * v_a + v_b * v_b) * rho_a / (rho_a + rho_b) * f / v_a;
}

/* Interface viscosity (Fuchs et al. 2022 Sec. 3.3.5, Eqs. 31-32): an
 * artificial viscosity (Monaghan 1992) on the liquid at its free surface,
 * of factor alpha_a = alpha0 h |n_a| (Eq. 32, delta_a = |n_a|), so that it
 * acts where the colour gradient is and fades into the bulk:
 *   a_a += alpha_ab sum_b m_b h c_ab (u_ab . r_ab) / (rho_ab (r_ab^2 + eps h^2)) grad_a W_ab
 * over the liquid b, c_ab and rho_ab the pair's mean sound speed and
 * density, eps = INTERFACE_VISCOSITY_EPSILON; it damps the spurious flows of
 * the CSF force along the surface. Unlike Monaghan's, Eq. 31 acts on
 * receding pairs too; its sign here is the dissipative one (a closing pair
 * repels). Fuchs weighs each particle's sum with its own alpha_a, so that
 * the two forces of a pair differ where |n| does (a surface particle and
 * one below it) and the liquid's momentum is not kept ("a non-conservative
 * surface tension formulation with interface viscosity"): a drop wetting a
 * free grain swung to 22 kg m/s per m in 7 s. Here the pair takes the
 * larger of its two factors, alpha_ab = max(alpha_a, alpha_b): the pair's
 * forces are equal and opposite and along r_ab, so linear and angular
 * momentum are kept, and no surface particle is damped less than by Eq. 31
 * (the pair's mean would keep momentum too, but damps less). The force
 * reaches two supports into the liquid, and without Fuchs's drag of the
 * surface against the interior a sessile cap takes longer to rest (at 60
 * degrees it overshoots to 54 and is at rest by 40 s, not 20; BENCHMARKS.md).
 * Gas neighbours (100 times lighter) take no part, so that the sum runs over
 * the liquid's own pairs only. Returned as the factor of m_b r_ab, f the
 * kernel's grad_a W_ab = f r_ab. */
#define INTERFACE_VISCOSITY_EPSILON REAL(0.01)

static inline real interface_viscosity_factor(real alpha_ab, real h, real c_mean, real rho_mean, real u_dot_r,
                                              real r2, real f)
{
    return alpha_ab * h * c_mean * u_dot_r / (rho_mean * (r2 + INTERFACE_VISCOSITY_EPSILON * h * h)) * f;
}

/* alpha_a of the interface viscosity (Fuchs et al. 2022 Eq. 32) on a liquid
 * particle a (fluid, not gas): alpha0 h |n_a|; 0 elsewhere and when off. */
static inline real interface_viscosity_alpha(GLOBAL const int *kind, GLOBAL const int *material,
                                             GLOBAL const real *materials, GLOBAL const real *normal,
                                             const surface_params *p, int a)
{
    return p->interface_viscosity > REAL(0.0) && kind[a] == KIND_FLUID && colour_material(materials, material, a)
               ? p->interface_viscosity * p->h * normal_size(normal, a)
               : REAL(0.0);
}

/* alpha_ab of the interface viscosity on the pair of liquid a (its alpha_a)
 * and b: the larger of the two factors on a liquid pair, 0 otherwise. */
static inline real interface_viscosity_pair_alpha(GLOBAL const int *kind, GLOBAL const int *material,
                                                  GLOBAL const real *materials, GLOBAL const real *normal,
                                                  const surface_params *p, real alpha_a, int a, int b)
{
    if (p->interface_viscosity <= REAL(0.0) || b == a || !is_liquid(kind, material, materials, b))
        return REAL(0.0);
    return fmax(alpha_a, interface_viscosity_alpha(kind, material, materials, normal, p, b));
}

/* Component d of the CSF force per volume on liquid particle a (see surface_force). */
static inline real csf_force(int gas, real sigma, real kappa, const real grad_c[3], GLOBAL const real *normal, int a,
                             int d)
{
    return gas ? sigma * kappa * grad_c[d] : -sigma * kappa * normal[3 * a + d];
}

/* On fluid particles, with the curvature smoothed over the particles with a
 * normal (Russell 2018 Eq. 3.30),
 *   kappa~_a = (1/Gamma*_a) sum_b psi_b V_b kappa_b W_ab,
 * the CSF force per volume (Russell Eq. 3.31)
 *   f_a = -sigma(T_a) kappa~_a n_a,
 * with a gas in the case on the liquid side of the liquid-gas interface
 * (Fuchs et al. 2022 Eq. 24, Remark 3: the denser phase takes the force)
 *   f_a = sigma(T_a) kappa~_a grad c_a       (interface_colour_factor),
 * and the Marangoni force per volume (Russell Eqs. 3.33, 3.35) with the
 * free-surface-consistent temperature gradient (PHYSICS.md erratum 4)
 *   grad T_a = (1/Gamma_a) sum_b V_b (T_b - T_a) grad_a W_ab,
 *   f_a += d sigma/dT (grad T_a - (grad T_a . n^_a) n^_a) |n_a|,
 * add f_a / rho_a to the acceleration (not of gas, which has colour 0 and
 * adds nothing to these sums). Every liquid particle gets its smoothed
 * curvature (0 elsewhere) and every particle sigma(T) (outputs; the
 * capillary time step reads sigma).
 * A liquid with a contact angle smooths over liquid b only (shapes_curvature);
 * its n_a is the turned normal of surface_normal. With
 * p.interface_viscosity, the interface viscosity (interface_viscosity_factor)
 * joins the acceleration. With p.reaction, pull[4 a .. 4 a + 2] records the
 * CSF force f_a V_a of each particle that takes it (the Marangoni force
 * not), and pull[4 a + 3] 0, for surface_contact_pull. In the conservative
 * form (p.form) it also sums the capillary stress's divergence f^stress_a
 * (capillary_stress_pair), records that in pull in place of the CSF force,
 * and leaves share[4 a .. 4 a + 3] = ((f^stress_a - f^csf_a) V_a, Gamma'_a)
 * for surface_share, on every particle (0 off the liquid). */
KERNEL void surface_force(GLOBAL const real *position, GLOBAL const real *velocity, GLOBAL const real *density,
                          GLOBAL const real *mass, GLOBAL const real *temperature,
                          GLOBAL const int *kind, GLOBAL const int *material,
                          GLOBAL const real *shepard, GLOBAL const real *normal, GLOBAL const real *unit_normal,
                          GLOBAL const real *normal_weight, GLOBAL const real *raw_curvature, GLOBAL const int *cell, int n,
                          grid_geometry g, GLOBAL const int *cell_start,
                          GLOBAL const real *materials, surface_params p,
                          GLOBAL real *acceleration, GLOBAL real *curvature,
                          GLOBAL real *tension, GLOBAL real *pull, GLOBAL real *share)
{
    FOR_EACH_ITEM(a, n)
    {
        const real t_a = p.temperature ? temperature[a] : REAL(0.0);
        real liquid_shepard = REAL(0.0); /* Gamma'_a over the liquid (conservative form) */
        const real theta0 = contact_angle(kind, material, materials, &p, a);
        real gamma_star = REAL(0.0), kappa_sum = REAL(0.0);
        real grad_t[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        real grad_c[3] = {REAL(0.0), REAL(0.0), REAL(0.0)}; /* Fuchs Eq. 19 (with a gas) */
        real damping[3] = {REAL(0.0), REAL(0.0), REAL(0.0)}; /* Fuchs Eq. 31 */
        real stress[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};  /* the capillary stress's divergence */
        const real alpha_a = interface_viscosity_alpha(kind, material, materials, normal, &p, a);
        real n_a[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        const real stress_a = p.form == TENSION_FORM_CONSERVATIVE
                                  ? capillary_stress_size(kind, material, materials, shepard, normal, unit_normal,
                                                          normal_weight, &p, a, t_a, n_a)
                                  : REAL(0.0);
        if (is_liquid(kind, material, materials, a)) {
            int cc[3];
            real x_a[3];
            const real support2 = surface_loop_centre(&g, &p, cell, position, a, cc, x_a), support = sqrt(support2);
            FOR_EACH_NEIGHBOUR_NEAR(b, run, &g, cc, x_a, cell_start, p.reach, support)
            {
                real r_ab[3], r2;
                if (!grid_pair_within(&run, position, b, support2, r_ab, &r2))
                    continue;
                const real r = sqrt(r2);
                const real alpha_ab =
                    interface_viscosity_pair_alpha(kind, material, materials, normal, &p, alpha_a, a, b);
                if (alpha_ab > REAL(0.0)) {
                    real u_ab[3];
                    for (int d = 0; d < 3; ++d)
                        u_ab[d] = velocity[3 * a + d] - velocity[3 * b + d];
                    const real c_mean = REAL(0.5) * (material_value(materials, material[a], MATERIAL_SOUND_SPEED) +
                                                     material_value(materials, material[b], MATERIAL_SOUND_SPEED));
                    const real v = mass[b] * interface_viscosity_factor(alpha_ab, p.h, c_mean,
                                                                        REAL(0.5) * (density[a] + density[b]),
                                                                        dot3(u_ab, r_ab), r2,
                                                                        smoothing_grad_factor(r, p.h));
                    for (int d = 0; d < 3; ++d)
                        damping[d] += v * r_ab[d];
                }
                if (!colour_material(materials, material, b)) {
                    const real c = interface_colour_factor(mass[a], density[a], mass[b], density[b],
                                                           smoothing_grad_factor(r, p.h));
                    for (int d = 0; d < 3; ++d)
                        grad_c[d] += c * r_ab[d];
                    continue;
                }
                const real v_b = mass[b] / density[b];
                if (p.form == TENSION_FORM_CONSERVATIVE) {
                    capillary_stress_pair(kind, material, materials, shepard, normal, unit_normal, normal_weight,
                                          temperature, &p, stress_a, n_a, a, b, r_ab,
                                          v_b * smoothing_grad_factor(r, p.h), stress);
                    if (is_liquid(kind, material, materials, b))
                        liquid_shepard += v_b * smoothing_w(r, p.h);
                }
                if (normal_weight[b] > REAL(0.0) && shapes_curvature(theta0, kind[b])) {
                    const real w = normal_weight[b] * v_b * smoothing_w(r, p.h);
                    gamma_star += w;
                    kappa_sum += w * raw_curvature[b];
                }
                if (p.marangoni) {
                    const real weight = v_b * (temperature[b] - t_a) * smoothing_grad_factor(r, p.h);
                    for (int d = 0; d < 3; ++d)
                        grad_t[d] += weight * r_ab[d];
                }
            }
        }
        const real kappa = gamma_star > REAL(0.0) ? kappa_sum / gamma_star : REAL(0.0);
        real d_sigma;
        const real sigma = surface_tension(materials, material[a], t_a, &d_sigma);
        curvature[a] = kappa;
        tension[a] = sigma;
        const int csf = p.tension && takes_surface_force(kind, material, materials, shepard, &p, a);
        if (p.form == TENSION_FORM_CONSERVATIVE) {
            for (int d = 0; d < 3; ++d) {
                const real f_csf = csf ? csf_force(p.gas, sigma, kappa, grad_c, normal, a, d) : REAL(0.0);
                share[4 * a + d] = (stress[d] - f_csf) * mass[a] / density[a];
            }
            share[4 * a + 3] = liquid_shepard;
        }
        if (records_surface_force(kind, material, materials, shepard, &p, a)) {
            real force[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
            if (csf)
                for (int d = 0; d < 3; ++d)
                    force[d] = csf_force(p.gas, sigma, kappa, grad_c, normal, a, d);
            if (p.reaction) {
                for (int d = 0; d < 3; ++d)
                    pull[4 * a + d] =
                        (p.form == TENSION_FORM_CONSERVATIVE ? stress[d] : force[d]) * mass[a] / density[a];
                pull[4 * a + 3] = REAL(0.0);
            }
            if (p.marangoni) {
                const real norm = normal_size(normal, a);
                real n_hat[3];
                for (int d = 0; d < 3; ++d)
                    n_hat[d] = norm > REAL(0.0) ? normal[3 * a + d] / norm : REAL(0.0);
                for (int d = 0; d < 3; ++d)
                    grad_t[d] /= shepard[a];
                const real normal_part = dot3(grad_t, n_hat);
                for (int d = 0; d < 3; ++d)
                    force[d] += d_sigma * (grad_t[d] - normal_part * n_hat[d]) * norm;
            }
            for (int d = 0; d < 3; ++d)
                acceleration[3 * a + d] += force[d] / density[a];
        }
        if (p.interface_viscosity > REAL(0.0))
            for (int d = 0; d < 3; ++d)
                acceleration[3 * a + d] += damping[d];
    }
}

/* One pass of the conservative form's share (tension_form: conservative).
 * The CSF force holds the Young-Laplace jump and keeps a surface's
 * particles apart, but its sum over a closed body of liquid is not zero
 * (the curvature's error along the surface; BENCHMARKS.md, "Where the push
 * comes from"). The capillary stress's divergence (capillary_stress_pair)
 * sums to zero over any body, but its pull along the surface clumps the
 * surface particles (the tensile instability: 0.3 dx apart within 6 s on
 * young_laplace_gas_2d). surface_force applies the CSF force F^csf_a and
 * leaves in share the difference D_a = (f^stress_a - f^csf_a) V_a and
 * Gamma'_a = sum_b V_b W_ab over the liquid b; each pass smooths it over
 * the liquid, conservatively (the weights V_a W_ab / Gamma'_b of each b's
 * share sum to 1 over the a):
 *   D'_a = V_a sum_b W_ab D_b / Gamma'_b,
 * and the last adds D'_a / m_a to the acceleration instead. So every
 * liquid particle takes
 *   F_a = F^csf_a + (S^k D)_a,   sum_a F_a = sum_a F^stress_a,
 * the stress's net (zero on a closed body, the contact-line pull where
 * the liquid wets a solid) with the CSF force's distribution at the
 * scale of a particle: S^k damps the differences between neighbours that
 * drive the clumping. k = TENSION_SHARE_PASSES (host/surface.c). smoothed
 * takes D' (and Gamma') where the pass is not the last. */
KERNEL void surface_share(GLOBAL const real *position, GLOBAL const real *density, GLOBAL const real *mass,
                          GLOBAL const int *kind, GLOBAL const int *material, GLOBAL const real *materials,
                          GLOBAL const int *cell, int n, grid_geometry g, GLOBAL const int *cell_start,
                          surface_params p, GLOBAL const real *share, int last, GLOBAL real *smoothed,
                          GLOBAL real *acceleration)
{
    FOR_EACH_ITEM(a, n)
    {
        real sum[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        const int liquid = is_liquid(kind, material, materials, a);
        if (liquid) {
            int cc[3];
            real x_a[3];
            const real support2 = surface_loop_centre(&g, &p, cell, position, a, cc, x_a), support = sqrt(support2);
            FOR_EACH_NEIGHBOUR_NEAR(b, run, &g, cc, x_a, cell_start, p.reach, support)
            {
                real r_ab[3], r2;
                if (!is_liquid(kind, material, materials, b) || !(share[4 * b + 3] > REAL(0.0)) ||
                    !grid_pair_within(&run, position, b, support2, r_ab, &r2))
                    continue;
                const real w = smoothing_w(sqrt(r2), p.h) / share[4 * b + 3];
                for (int d = 0; d < 3; ++d)
                    sum[d] += w * share[4 * b + d];
            }
        }
        if (last && liquid) {
            for (int d = 0; d < 3; ++d)
                acceleration[3 * a + d] += sum[d] / density[a];
        } else if (!last) {
            for (int d = 0; d < 3; ++d)
                smoothed[4 * a + d] = sum[d] * mass[a] / density[a];
            smoothed[4 * a + 3] = share[4 * a + 3];
        }
    }
}

/* The surface tension's pull between the liquid and the solids it wets
 * (after surface_force, which leaves sigma_a in tension and, on a liquid a,
 * its CSF force F_a = f_a V_a in pull: -sigma_a kappa~_a V_a n_a, Russell
 * 2018 Eq. 3.31, or with a gas Fuchs et al. 2022 Eq. 24; in the
 * conservative form the capillary stress's divergence f^stress_a V_a, which
 * its share gives the liquid in sum): pull[4 i .. 4 i + 2] gets
 *   on a solid r    the contact-line force of the liquid on it
 *                   F_r = -sum_a V_a V_r w_ar T_a . grad_a W_ar,  T_a = sigma_a |n_a| (1 - n^_a n^_a),
 * (w_ar of solid_pair_weight, which capillary_stress_pair gives the pair
 * too) and pull[4 i + 3] its weight |F_r| (0 elsewhere). T is the capillary
 * stress of the interface (Lafaurie et al. 1994, J. Comput. Phys. 113,
 * Eq. 6; in SPH Hu & Adams 2006, J. Comput. Phys. 213, Eq. 18), whose
 * divergence is the CSF force: the net CSF force on a body of liquid is the
 * flux of T through its faces, and T vanishes off the interface band and
 * has no flux through the free surface itself (T . n^ = 0), so what the CSF
 * force leaves on a liquid that wets a solid is the flux of T into the
 * solid where the surface meets it, the contact-line pull: sigma times the
 * surface's unit conormals along its contact lines (2 sigma sin theta0 on a
 * 2D sessile drop, which its pressure on the wetted face balances). The
 * symmetric SPH divergence sum_b V_a V_b (T_a + T_b) . grad_a W_ab cancels
 * pair by pair inside the liquid; its part over solid neighbours (T_r =
 * T_a, solid_pair_weight) is that flux, and F_r its reaction on the solid
 * at the contact line (Newton's third law). n^_a is the turned normal of surface_wetting, so
 * F_r pulls at the contact angle. Solids are every particle of colour 1
 * but fluid: grains, fixed solids and walls (the last two are held). The
 * Marangoni force is not in the pull: its net on an open surface (the
 * surface gradient of sigma, integrated) is left on the liquid. */
KERNEL void surface_contact_pull(GLOBAL const real *position, GLOBAL const real *density,
                                 GLOBAL const real *mass, GLOBAL const int *kind,
                                 GLOBAL const int *material, GLOBAL const real *shepard,
                                 GLOBAL const real *normal, GLOBAL const real *unit_normal,
                                 GLOBAL const real *normal_weight,
                                 GLOBAL const real *tension, GLOBAL const int *cell, int n,
                                 grid_geometry g, GLOBAL const int *cell_start, GLOBAL const int *fluid_count,
                                 GLOBAL const real *materials, GLOBAL const int *blocks_away,
                                 surface_params p, GLOBAL real *pull)
{
    FOR_EACH_ITEM(i, n)
    {
        real force[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        const real v_i = mass[i] / density[i];
        const int solid = kind[i] != KIND_FLUID && colour_material(materials, material, i);
        if (solid && blocks_from_liquid(blocks_away, &g, &p, cell[i]) <= p.near_blocks - 2 &&
            fluid_within_support(&g, cell_start, fluid_count, &p, cell[i])) {
            int cc[3];
            real x_r[3];
            const real support2 = surface_loop_centre(&g, &p, cell, position, i, cc, x_r), support = sqrt(support2);
            FOR_EACH_NEIGHBOUR_NEAR(a, run, &g, cc, x_r, cell_start, p.reach, support)
            {
                real r_ra[3], r2, n_hat[3];
                if (!takes_surface_force(kind, material, materials, shepard, &p, a) ||
                    !grid_pair_within(&run, position, a, support2, r_ra, &r2))
                    continue;
                stress_normal(normal, unit_normal, normal_weight, a, n_hat);
                /* -V_a V_r T_a . grad_a W_ar with grad_a W_ar = -f r_ra */
                real t_dot_r[3];
                capillary_stress_dot(tension[a] * normal_size(normal, a), n_hat, r_ra, t_dot_r);
                const real share = mass[a] / density[a] * v_i * smoothing_grad_factor(sqrt(r2), p.h) *
                                   solid_pair_weight(shepard, a, i);
                for (int d = 0; d < 3; ++d)
                    force[d] += share * t_dot_r[d];
            }
        }
        if (!records_surface_force(kind, material, materials, shepard, &p, i)) {
            for (int d = 0; d < 3; ++d)
                pull[4 * i + d] = force[d];
            pull[4 * i + 3] = solid ? sqrt(dot3(force, force)) : REAL(0.0);
        }
    }
}

/* work_i = pull[4 i + c], for a reduction. */
KERNEL void surface_pull_component(GLOBAL const real *pull, int n, int c, GLOBAL real *work)
{
    FOR_EACH_ITEM(i, n)
    {
        work[i] = pull[4 * i + c];
    }
}

/* The reaction of the surface tension on the grains, added to the
 * acceleration of each grain particle r after surface_contact_pull:
 *   a_r += (F_r + |F_r| c) / m_r,   c = -(sum_i pull_i) / (sum_r |F_r|),
 * the sums over every particle (host/surface.c). The CSF force and its
 * stress flux F_r (surface_contact_pull) are two discretisations of the
 * same pull and agree to the discretisation error only: on the drop
 * beside a grain of test_grains wet the flux is 19.8 N/m at the start, the
 * CSF force's net 21.6, and the contact lines at theta0 pull with 18.0
 * (before the solid took the liquid's stress, solid_pair_weight, the flux
 * came to 0.3 to 0.4 of the CSF force's net there and on a sessile half
 * disc). c hands the
 * rest of the liquid's net CSF force to the solids in proportion to their
 * contact-line force, so that the surface tension's forces sum to zero
 * over liquid and solids (walls and fixed solids take their share, held),
 * while each contact line keeps the direction of its own pull. In the
 * conservative form the liquid's net is the stress's, whose pairs with the
 * solids F_r answers pair by pair: c is 0 to round-off. */
KERNEL void surface_grain_reaction(GLOBAL const int *kind, GLOBAL const real *mass, GLOBAL const real *pull,
                                   int n, real cx, real cy, real cz, GLOBAL real *acceleration)
{
    FOR_EACH_ITEM(r, n)
    {
        if (kind[r] == KIND_GRAIN) {
            const real c[3] = {cx, cy, cz};
            for (int d = 0; d < 3; ++d)
                acceleration[3 * r + d] += (pull[4 * r + d] + pull[4 * r + 3] * c[d]) / mass[r];
        }
    }
}
