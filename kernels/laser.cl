/* Laser absorption: the absorbed power per unit volume of each particle,
 * laser_power (W/m^3), and its power absorbed[a] = laser_power V_a (W; 2D:
 * W per metre of depth) for the host's total.
 *
 * Volumetric (Russell 2018 §3.2.2), two gather passes, no atomics, so the
 * result does not depend on thread timing:
 *   laser_absorb_columns   each column of bins walks down the beam, each
 *                          node gathering the PIC weights and volumes of
 *                          the particles around it and absorbing Beer-Lambert
 *                          style (Eqs. 3.40-3.41), until its light is spent;
 *   laser_gather_power     each particle gathers the power of its 2^d nodes.
 * Surface (Fuchs et al. 2022 Eq. 17): laser_surface_absorb, one pass.
 * The beam frame and bin grid are described in laser_params.h. */
#include "colour.h"
#include "device.h"
#include "laser_params.h"
#include "neighbours.h"
#include "smoothing.h"
#include "vec3.h"

/* Gaussian irradiance at squared distance r2 from the axis (Russell 2018
 * Eq. 3.42, Fuchs et al. 2022 Eq. 17): I0(r) = 2P/(pi r_l^2) exp(-2 r^2/r_l^2),
 * W/m^2. In 2D the plane is a slice through the axis, so the same formula
 * gives powers per metre of depth. */
static inline real laser_irradiance(const laser_params *p, real r2)
{
    return p->peak_intensity * exp(REAL(-2.0) * r2 / (p->radius * p->radius));
}

/* The beam frame: axis[k] across the beam for k < dim - 1, axis[dim - 1] = d. */
static inline void laser_frame(const laser_params *p, real axis[AMSPH_DIM][3])
{
    for (int c = 0; c < 3; ++c) {
        axis[0][c] = p->across[c];
        axis[AMSPH_DIM - 1][c] = p->direction[c];
    }
#if AMSPH_DIM == 3
    cross3(p->direction, p->across, axis[1]);
#endif
}

/* Beam coordinates q of particle a (laser_params.h). */
static inline void laser_beam_coords(const grid_geometry *g, const laser_params *p,
                                     real axis[AMSPH_DIM][3], GLOBAL const real *position,
                                     int a, real q[AMSPH_DIM])
{
    real r[3];
    for (int d = 0; d < 3; ++d)
        r[d] = grid_nearest_image(g, d, position[3 * a + d] - p->centre[d]);
    for (int k = 0; k < AMSPH_DIM; ++k)
        q[k] = dot3(r, axis[k]);
}

/* Half the lateral node count: the column index of the axis. */
static inline real laser_axis_index(const laser_params *p)
{
    return REAL(0.5) * (real)(p->lateral_nodes - 1);
}

/* Beam coordinates in bin units, u_k = node index where a node sits. */
static inline void laser_bin_coords(const laser_params *p, const real q[AMSPH_DIM],
                                    real u[AMSPH_DIM])
{
    for (int k = 0; k < AMSPH_DIM - 1; ++k)
        u[k] = q[k] / p->bin_size + laser_axis_index(p);
    u[AMSPH_DIM - 1] = (q[AMSPH_DIM - 1] - p->depth_lo) / p->bin_size;
}

/* Node indices i of the pass's node number `node` (depth index last). */
static inline void laser_node_indices(const laser_params *p, int node, int i[AMSPH_DIM])
{
    i[AMSPH_DIM - 1] = node % p->depth_nodes;
    int column = node / p->depth_nodes;
    for (int k = 0; k < AMSPH_DIM - 1; ++k) {
        i[k] = p->lateral_first[k] + column % p->lateral_count[k];
        column /= p->lateral_count[k];
    }
}

/* The pass's node number of indices i, or -1 outside its nodes. */
static inline int laser_node_number(const laser_params *p, const int i[AMSPH_DIM])
{
    if (i[AMSPH_DIM - 1] < 0 || i[AMSPH_DIM - 1] >= p->depth_nodes)
        return -1;
    int column = 0;
    for (int k = AMSPH_DIM - 2; k >= 0; --k) {
        const int j = i[k] - p->lateral_first[k];
        if (j < 0 || j >= p->lateral_count[k])
            return -1;
        column = column * p->lateral_count[k] + j;
    }
    return i[AMSPH_DIM - 1] + p->depth_nodes * column;
}

/* sign q_d of the particles that reach a node of the bin columns (within
 * one bin of the outermost column across the beam), LASER_NOT_UNDER for the others:
 * with sign +1 its maximum is the deepest of them, with -1 the maximum is
 * minus the shallowest. The host lays each pass's nodes over that range
 * only: above the material a column carries its irradiance unchanged, and
 * below it there is nothing to absorb. */
KERNEL void laser_depth_extent(GLOBAL const real *position, GLOBAL const int *material, int n, grid_geometry g,
                               GLOBAL const real *materials, laser_params p, real sign, GLOBAL real *out)
{
    FOR_EACH_ITEM(a, n)
    {
        real axis[AMSPH_DIM][3];
        laser_frame(&p, axis);
        real q[AMSPH_DIM];
        laser_beam_coords(&g, &p, axis, position, a, q);
        const real reach = (laser_axis_index(&p) + REAL(1.0)) * p.bin_size;
        int under = !material_is_gas(materials, material[a]); /* a gas is transparent */
        for (int k = 0; k < AMSPH_DIM - 1; ++k)
            under &= fabs(q[k]) < reach;
        out[a] = under ? sign * q[AMSPH_DIM - 1] : (real)LASER_NOT_UNDER;
    }
}

/* Particle-in-cell (cloud-in-cell) weight of a particle at `offset` (beam
 * frame, bin units) from a node: Russell 2018 §3.2.2,
 * w = (1 - |C_x - P_x|)(1 - |C_y - P_y|), multilinear in d dimensions; the
 * weights of a particle over its 2^d nodes sum to 1. */
static inline real laser_pic_weight(const real offset[AMSPH_DIM])
{
    real w = REAL(1.0);
    for (int k = 0; k < AMSPH_DIM; ++k)
        w *= fmax(REAL(0.0), REAL(1.0) - fabs(offset[k]));
    return w;
}

/* The cell nearest to point x: x wrapped on periodic axes, the cell clamped
 * to the grid on closed ones (a node just outside the domain still reaches
 * the particles near it through the cells around). */
static inline void laser_cell_near(const grid_geometry *g, real x[3], int cc[3])
{
    for (int d = 0; d < 3; ++d) {
        cc[d] = 0;
        if (d >= AMSPH_DIM)
            continue;
        if (g->periodic[d])
            x[d] -= g->length[d] * floor((x[d] - g->lo[d]) / g->length[d]);
        const real c = floor((x[d] - g->lo[d]) / g->cell_size);
        cc[d] = c < REAL(0.0) ? 0 : c >= (real)g->ncell[d] ? g->ncell[d] - 1 : (int)c;
    }
}

/* The light left in a column below this fraction of the irradiance that
 * enters it is spent: the nodes beneath gather nothing and take no power.
 * It is the unit roundoff of `real`, so what the column no longer absorbs
 * lies below the rounding of the power it has absorbed (a column of metal
 * at alpha bin_size = 5 spends its light in four bins, where the walk went
 * on through the whole plate and the wall under it). */
#if AMSPH_DOUBLE
#define LASER_SPENT REAL(1.1102230246251565e-16)
#else
#define LASER_SPENT REAL(5.9604645e-8)
#endif

/* Step 1 (Russell 2018 §3.2.2, "sum all particle contributions to a given
 * bin"): node i gathers, over the particles p around it,
 *   weight = sum_p w_pn,   returned: the bin volume sum_p w_pn V_p,   V_p = m_p / rho_p.
 * A particle with w_pn > 0 lies within bin_size sqrt(d) of the node, which
 * the host keeps within the kernel support: the cells around the node that
 * the ball of that radius touches hold them all (FOR_EACH_NEIGHBOUR); the
 * others in those cells are passed over by their offsets, before the
 * weight is formed. */
static inline real laser_gather_node(GLOBAL const real *position, GLOBAL const real *mass,
                                     GLOBAL const real *density, GLOBAL const int *material,
                                     const grid_geometry *g, GLOBAL const int *cell_start,
                                     GLOBAL const real *materials, const laser_params *p,
                                     real axis[AMSPH_DIM][3], const int i[AMSPH_DIM], real *weight)
{
    real q_node[AMSPH_DIM];
    for (int k = 0; k < AMSPH_DIM - 1; ++k)
        q_node[k] = ((real)i[k] - laser_axis_index(p)) * p->bin_size;
    q_node[AMSPH_DIM - 1] = p->depth_lo + (real)i[AMSPH_DIM - 1] * p->bin_size;
    real x[3];
    for (int d = 0; d < 3; ++d) {
        x[d] = p->centre[d];
        for (int k = 0; k < AMSPH_DIM; ++k)
            x[d] += q_node[k] * axis[k][d];
    }
    int cc[3];
    laser_cell_near(g, x, cc);
    const real reach2 = (real)AMSPH_DIM * p->bin_size * p->bin_size;
    real sum_w = REAL(0.0), sum_wv = REAL(0.0);
    FOR_EACH_NEIGHBOUR(b, run, g, cc, x, cell_start, sqrt(reach2))
    {
        real r[3], offset[AMSPH_DIM]; /* r_b - x for the image of b next to the node */
        for (int d = 0; d < 3; ++d)
            r[d] = position[3 * b + d] - run.point[d];
        int in_stencil = 1;
        for (int k = 0; k < AMSPH_DIM; ++k) {
            offset[k] = dot3(r, axis[k]) / p->bin_size;
            in_stencil &= fabs(offset[k]) < REAL(1.0);
        }
        if (in_stencil && !material_is_gas(materials, material[b])) { /* a gas is transparent */
            const real w = laser_pic_weight(offset);
            sum_w += w;
            sum_wv += w * mass[b] / density[b];
        }
    }
    *weight = sum_w;
    return sum_wv;
}

/* Step 2 (Russell 2018 Eqs. 3.40-3.41 through the bins): each column walks
 * down the beam from the irradiance I0(r) of its axis distance r (Eq. 3.42)
 * at the top, gathering each node (step 1) on its way. Bin k, of
 * cross-section A (2D: bin_size x 1 m) and volume fraction
 * V_f = volume / (A bin_size), has the optical thickness
 *   tau_k = alpha bin_size V_f = alpha volume / A,
 * absorbs P_k = I_k A (1 - exp(-tau_k)) and passes I_{k+1} = I_k exp(-tau_k)
 * on. The sum telescopes: a column absorbs exactly I0 A (1 - exp(-sum tau_k)),
 * the Beer-Lambert total of its material, whatever the bin size, less the
 * light it holds when spent (below LASER_SPENT I0). Russell's linearised
 * P_k = alpha I_k sum w V is the first-order expansion of the same bin in
 * alpha bin_size: it overshoots by about tau_k / 2 per bin (5% at
 * alpha bin_size = 0.1) and cannot meet a 0.1% energy goal. */
KERNEL void laser_absorb_columns(GLOBAL const real *position, GLOBAL const real *mass,
                                 GLOBAL const real *density, GLOBAL const int *material, grid_geometry g,
                                 GLOBAL const int *cell_start, GLOBAL const real *materials, laser_params p,
                                 int columns, GLOBAL real *bin_weight, GLOBAL real *bin_power)
{
    FOR_EACH_ITEM(column, columns)
    {
        real axis[AMSPH_DIM][3];
        laser_frame(&p, axis);
        int i[AMSPH_DIM];
        laser_node_indices(&p, p.depth_nodes * column, i);
        real r2 = REAL(0.0);
        for (int k = 0; k < AMSPH_DIM - 1; ++k) {
            const real q = ((real)i[k] - laser_axis_index(&p)) * p.bin_size;
            r2 += q * q;
        }
#if AMSPH_DIM == 3
        const real area = p.bin_size * p.bin_size;
#else
        const real area = p.bin_size;
#endif
        real intensity = laser_irradiance(&p, r2);
        const real spent = LASER_SPENT * intensity;
        for (int k = 0; k < p.depth_nodes; ++k) {
            const int node = k + p.depth_nodes * column;
            real weight = REAL(0.0), power = REAL(0.0);
            if (intensity > spent) {
                i[AMSPH_DIM - 1] = k;
                const real volume = laser_gather_node(position, mass, density, material, &g, cell_start, materials,
                                                      &p, axis, i, &weight);
                const real tau = p.absorption * volume / area;
                power = -intensity * area * expm1(-tau);
                intensity *= exp(-tau);
            }
            bin_weight[node] = weight;
            bin_power[node] = power;
        }
    }
}

/* Step 3 (Russell 2018 §3.2.2, last two steps): particle a takes from each
 * of its 2^d nodes n the share of the node's power its weight gave it,
 *   P_a = sum_n P_n w_an / bin_weight[n],   laser_power_a = P_a / V_a,
 * so the particles absorb what the bins did (to rounding: w_an here comes
 * from the beam coordinates, in step 1 from the offset to the node). */
KERNEL void laser_gather_power(GLOBAL const real *position, GLOBAL const real *mass,
                               GLOBAL const real *density, GLOBAL const int *material, int n,
                               grid_geometry g, GLOBAL const real *materials, laser_params p,
                               GLOBAL const real *bin_weight, GLOBAL const real *bin_power,
                               GLOBAL real *laser_power, GLOBAL real *absorbed)
{
    FOR_EACH_ITEM(a, n)
    {
        real axis[AMSPH_DIM][3];
        laser_frame(&p, axis);
        real q[AMSPH_DIM], u[AMSPH_DIM];
        laser_beam_coords(&g, &p, axis, position, a, q);
        laser_bin_coords(&p, q, u);
        int base[AMSPH_DIM];
        for (int k = 0; k < AMSPH_DIM; ++k)
            base[k] = (int)floor(u[k]);
        real power = REAL(0.0);
        for (int corner = 0; corner < (1 << AMSPH_DIM); ++corner) {
            int i[AMSPH_DIM];
            real offset[AMSPH_DIM];
            for (int k = 0; k < AMSPH_DIM; ++k) {
                i[k] = base[k] + ((corner >> k) & 1);
                offset[k] = u[k] - (real)i[k];
            }
            const int node = laser_node_number(&p, i);
            if (node >= 0 && bin_weight[node] > REAL(0.0) && !material_is_gas(materials, material[a]))
                power += bin_power[node] * laser_pic_weight(offset) / bin_weight[node];
        }
        laser_power[a] = power * density[a] / mass[a];
        absorbed[a] = power;
    }
}

/* Surface absorption (Fuchs et al. 2022 Eq. 17):
 *   s_a = zeta <-n_a . e_l> I0(r_a) delta_a,
 * with the colour gradient grad Gamma_a = sum_b V_b grad_a W_ab over every
 * particle (fluid, wall and solid are all material), the outward normal
 * n_a = -grad Gamma_a / |grad Gamma_a| and the surface delta
 * delta_a = c |grad Gamma_a|. Then <-n . e_l> delta = c <grad Gamma . e_l>,
 * which needs no cut-off where |grad Gamma| vanishes. With no particles
 * outside, the sum over the material sees only the inner half of the jump
 * of Gamma (Gamma = 1/2 on the surface), so c = 2 would make a flat face
 * absorb zeta times the power that falls on it to the accuracy of the
 * kernel's lattice gradient (the quintic within 0.1%, Wendland C2 at
 * h = 1.2 dx 1.5% low in 3D, 3.6% in 2D); c = p.surface_delta, the inverse
 * of flat_face_delta (kernels/thermal.cl) without a cut-off, makes it exact
 * on a lattice face. No shadowing: every face turned to the beam is lit. */
KERNEL void laser_surface_absorb(GLOBAL const real *position, GLOBAL const real *mass,
                                 GLOBAL const real *density, GLOBAL const int *material,
                                 GLOBAL const int *cell, int n, grid_geometry g,
                                 GLOBAL const int *cell_start, GLOBAL const real *materials, laser_params p,
                                 real h, GLOBAL real *laser_power, GLOBAL real *absorbed)
{
    FOR_EACH_ITEM(a, n)
    {
        real grad[3];
        colour_gradient(position, mass, density, material, materials, &g, cell_start, cell[a], a, h, grad);
        real axis[AMSPH_DIM][3];
        laser_frame(&p, axis);
        real q[AMSPH_DIM];
        laser_beam_coords(&g, &p, axis, position, a, q);
        real r2 = REAL(0.0);
        for (int k = 0; k < AMSPH_DIM - 1; ++k)
            r2 += q[k] * q[k];
        const real facing = material_is_gas(materials, material[a]) ? REAL(0.0) : fmax(REAL(0.0), dot3(grad, p.direction));
        laser_power[a] = p.absorption * laser_irradiance(&p, r2) * p.surface_delta * facing;
        absorbed[a] = laser_power[a] * mass[a] / density[a];
    }
}
