/* Mobile powder grains (Fuchs et al. 2022 Sec. 2.2 and 3.4): each grain is
 * a rigid body made of particles of kind KIND_GRAIN, its index in the
 * `grain` field. The particles do not move on their own; every step
 *   grain_kick            u_k, omega_k from f_k, m_k (Fuchs Eqs. 11, 12)
 *   grain_particle_velocity  u_r = u_k + omega_k x (r_r - r_k)
 *   grain_drift           r_r moves with the rigid motion over dt
 *   grain_particle_forces f_r of each grain particle: the reaction of the
 *                         fluid (Sec. 3.4.2) and the contact (Eqs. 39, 40)
 *   grain_chunk_count, grain_chunk_scatter  list the particles grain by grain
 *   grain_sums            m_k, r_k, I_k, f_k, torque (Fuchs Eqs. 35, 36, 38)
 *                         and the velocity after a change of particles (Eq. 37)
 * and, with the thermal module, grain_capture and grain_change_phase move
 * particles between grains and the fluid as they melt and solidify. */
#include "device.h"
#include "fluid_pair.h"
#include "grain_params.h"
#include "kinds.h"
#include "neighbours.h"
#include "thermal_table.h"
#include "vec3.h"

static inline void grain_vector(GLOBAL const real *grains, int k, int field, real v[3])
{
    for (int d = 0; d < 3; ++d)
        v[d] = grains[GRAIN_RECORD * k + field + d];
}

/* The motion of particle r's grain: its centre, velocity and angular
 * velocity, and r's arm r_r - r_k. */
static inline void grain_motion(GLOBAL const real *grains, GLOBAL const int *grain, GLOBAL const real *position,
                                int r, real centre[3], real u[3], real w[3], real arm[3])
{
    const int k = grain[r];
    grain_vector(grains, k, GRAIN_CENTRE, centre);
    grain_vector(grains, k, GRAIN_VELOCITY, u);
    grain_vector(grains, k, GRAIN_SPIN, w);
    for (int d = 0; d < 3; ++d)
        arm[d] = position[3 * r + d] - centre[d];
}

/* x = I^-1 y for the symmetric inertia I (xx, yy, zz, xy, xz, yz), by
 * Cramer's rule; in 2D only the z components take part. */
static inline void inertia_solve(const real i6[6], const real y[3], real x[3])
{
#if AMSPH_DIM == 2
    x[0] = REAL(0.0);
    x[1] = REAL(0.0);
    x[2] = i6[2] > REAL(0.0) ? y[2] / i6[2] : REAL(0.0);
#else
    const real a = i6[0], b = i6[1], c = i6[2], d = i6[3], e = i6[4], f = i6[5];
    /* [[a d e] [d b f] [e f c]] */
    const real c00 = b * c - f * f, c01 = e * f - d * c, c02 = d * f - b * e;
    const real c11 = a * c - e * e, c12 = d * e - a * f, c22 = a * b - d * d;
    const real det = a * c00 + d * c01 + e * c02;
    const real inv = det > REAL(0.0) ? REAL(1.0) / det : REAL(0.0);
    x[0] = inv * (c00 * y[0] + c01 * y[1] + c02 * y[2]);
    x[1] = inv * (c01 * y[0] + c11 * y[1] + c12 * y[2]);
    x[2] = inv * (c02 * y[0] + c12 * y[1] + c22 * y[2]);
#endif
}

/* Entry (a, b) of the symmetric inertia stored as xx, yy, zz, xy, xz, yz. */
static inline real inertia_entry(const real i6[6], int a, int b)
{
    return a == b ? i6[a] : i6[a + b + 2]; /* xy: 0 + 1 + 2 = 3, xz: 4, yz: 5 */
}

/* I omega for the symmetric inertia (xx, yy, zz, xy, xz, yz). */
static inline void inertia_apply(const real i6[6], const real w[3], real out[3])
{
    out[0] = i6[0] * w[0] + i6[3] * w[1] + i6[4] * w[2];
    out[1] = i6[3] * w[0] + i6[1] * w[1] + i6[5] * w[2];
    out[2] = i6[4] * w[0] + i6[5] * w[1] + i6[2] * w[2];
}

/* Half a kick of the balance of linear and angular momentum of each grain
 * (Fuchs et al. 2022 Eqs. 11, 12), the latter for the angular momentum
 * L = I omega in the world frame, whose rate is the torque alone (the
 * gyroscopic term omega x I omega of Eq. 12 for omega is then implicit):
 *   u_k += dt/2 f_k / m_k,   L_k += dt/2 m_k,   omega_k = I_k^-1 L_k
 * (gravity is part of f_k, grain_particle_forces). A free body keeps its L
 * to rounding, where integrating omega with the gyroscopic term drifts at
 * first order in dt (7e-4 over a turn of test_grains' tumbling brick). */
KERNEL void grain_kick(int ngrains, real half_dt, GLOBAL real *grains)
{
    FOR_EACH_ITEM(k, ngrains)
    {
        GLOBAL real *rec = grains + GRAIN_RECORD * k;
        const real m = rec[GRAIN_MASS];
        if (m > REAL(0.0)) {
            real l[3], w[3], i6[6];
            for (int d = 0; d < 3; ++d) {
                rec[GRAIN_VELOCITY + d] += half_dt * rec[GRAIN_FORCE + d] / m;
                rec[GRAIN_ANGULAR_MOMENTUM + d] += half_dt * rec[GRAIN_TORQUE + d];
                l[d] = rec[GRAIN_ANGULAR_MOMENTUM + d];
            }
            for (int e = 0; e < 6; ++e)
                i6[e] = rec[GRAIN_INERTIA + e];
            inertia_solve(i6, l, w);
            for (int d = 0; d < 3; ++d)
                rec[GRAIN_SPIN + d] = w[d];
        }
    }
}

/* The rigid-body velocity of the grain particles, u_r = u_k + omega_k x
 * (r_r - r_k): what the fluid sees (continuity, no-slip ghost velocity) and
 * what a particle keeps when it melts. */
KERNEL void grain_particle_velocity(GLOBAL const int *kind, GLOBAL const int *grain,
                                    GLOBAL const real *position, int n, GLOBAL const real *grains,
                                    GLOBAL real *velocity)
{
    FOR_EACH_ITEM(r, n)
    {
        if (kind[r] == KIND_GRAIN) {
            real centre[3], u[3], w[3], arm[3], spin_part[3];
            grain_motion(grains, grain, position, r, centre, u, w, arm);
            cross3(w, arm, spin_part);
            for (int d = 0; d < 3; ++d)
                velocity[3 * r + d] = u[d] + spin_part[d];
        }
    }
}

/* v rotated by the angle vector theta (Rodrigues' formula):
 *   R v = v cos t + (e x v) sin t + e (e . v)(1 - cos t),  t = |theta|, e = theta / t. */
static inline void rotate(const real theta[3], const real v[3], real out[3])
{
    const real t = sqrt(dot3(theta, theta));
    if (!(t > REAL(0.0))) {
        for (int d = 0; d < 3; ++d)
            out[d] = v[d];
        return;
    }
    real e[3], exv[3];
    for (int d = 0; d < 3; ++d)
        e[d] = theta[d] / t;
    cross3(e, v, exv);
    const real c = cos(t), s = sin(t), ev = dot3(e, v);
    for (int d = 0; d < 3; ++d)
        out[d] = v[d] * c + exv[d] * s + e[d] * ev * (REAL(1.0) - c);
}

/* The drift of the grain particles: the grain translates by u_k dt and turns
 * by omega_k dt about its centre, so the particles keep their distances
 * (a drift along u_r would stretch a spinning grain at second order):
 *   r_r <- r_k + u_k dt + R(omega_k dt) (r_r - r_k).
 * Runs before grain_drift_centres. */
KERNEL void grain_drift(GLOBAL const int *kind, GLOBAL const int *grain, int n,
                        GLOBAL const real *grains, real dt, GLOBAL real *position)
{
    FOR_EACH_ITEM(r, n)
    {
        if (kind[r] == KIND_GRAIN) {
            real centre[3], u[3], theta[3], arm[3], turned[3];
            grain_motion(grains, grain, position, r, centre, u, theta, arm);
            for (int d = 0; d < 3; ++d)
                theta[d] *= dt;
            rotate(theta, arm, turned);
            for (int d = 0; d < AMSPH_DIM; ++d)
                position[3 * r + d] = centre[d] + u[d] * dt + turned[d];
        }
    }
}

KERNEL void grain_drift_centres(int ngrains, real dt, GLOBAL real *grains)
{
    FOR_EACH_ITEM(k, ngrains)
    {
        for (int d = 0; d < AMSPH_DIM; ++d)
            grains[GRAIN_RECORD * k + GRAIN_CENTRE + d] += dt * grains[GRAIN_RECORD * k + GRAIN_VELOCITY + d];
    }
}

/* The angular velocity over a drift of dt, at the middle of the turn
 * (implicit midpoint for the orientation): the grain turned by half of
 * omega dt has the inertia I' = R I R^T (R the half turn), and omega' =
 * I'^-1 L. Turning by the omega of the step's start instead gets the
 * orientation wrong at first order in dt for a grain whose omega wanders
 * (test_grains' tumbling brick lost 2.5e-3 of its energy in a turn). In 2D
 * omega and L lie along z, whose moment a turn about z keeps: omega stays,
 * and the host does not launch it. */
KERNEL void grain_midpoint_spin(int ngrains, real dt, GLOBAL real *grains)
{
    FOR_EACH_ITEM(k, ngrains)
    {
        GLOBAL real *rec = grains + GRAIN_RECORD * k;
        if (rec[GRAIN_MASS] > REAL(0.0)) {
            real half_turn[3], l[3], w[3], rot[3][3], i6[6], turned[6];
            grain_vector(grains, k, GRAIN_SPIN, half_turn);
            grain_vector(grains, k, GRAIN_ANGULAR_MOMENTUM, l);
            for (int d = 0; d < 3; ++d)
                half_turn[d] *= REAL(0.5) * dt;
            for (int c = 0; c < 3; ++c) { /* column c of R: the turned unit vector */
                real e[3] = {REAL(0.0), REAL(0.0), REAL(0.0)}, col[3];
                e[c] = REAL(1.0);
                rotate(half_turn, e, col);
                for (int d = 0; d < 3; ++d)
                    rot[d][c] = col[d];
            }
            for (int e = 0; e < 6; ++e)
                i6[e] = rec[GRAIN_INERTIA + e];
            const int row[6] = {0, 1, 2, 0, 0, 1}, col[6] = {0, 1, 2, 1, 2, 2};
            for (int e = 0; e < 6; ++e) { /* (R I R^T)_ij = sum_ab R_ia I_ab R_jb */
                real sum = REAL(0.0);
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b)
                        sum += rot[row[e]][a] * inertia_entry(i6, a, b) * rot[col[e]][b];
                turned[e] = sum;
            }
            inertia_solve(turned, l, w);
            for (int d = 0; d < 3; ++d)
                rec[GRAIN_SPIN + d] = w[d];
        }
    }
}

/* The contact force on grain particle r from particle b of another grain,
 * a wall or a fixed solid (Fuchs et al. 2022 Eqs. 39, 40): a spring and
 * dashpot along e = r_rb / |r_rb| on the overlap g = d - |r_rb| (d the
 * contact distance, dx), and only while it pushes:
 *   f_rb = (k_c g + d_c g') e  if k_c g + d_c g' > 0,   g' = -e . u_rb. */
static inline void contact_force(const real r_rb[3], real r, const real u_rb[3], const grain_params *p,
                                 real f[3])
{
    const real gap = p->distance - r;
    const real closing = -dot3(r_rb, u_rb) / r;
    const real push = p->stiffness * gap + p->damping * closing;
    if (push > REAL(0.0))
        for (int d = 0; d < 3; ++d)
            f[d] += push * r_rb[d] / r;
}

/* Acceleration f_r / m_r + g of each grain particle r. f_r sums
 *   the fluid's reaction  -m_i a_ir over the fluid neighbours i, with a_ir
 *                         the pair acceleration of kernels/fluid_pair.h that
 *                         fluid_forces gives i (Fuchs Sec. 3.4.2), and
 *   the contact forces    of the particles of other grains, walls and fixed
 *                         solids closer than the contact distance.
 * The grain sums f_k = sum_r m_r a_r (Fuchs Eq. 38). A particle whose box
 * of cells holds no fluid (grid_fluid_in_box, fluid_count as continuity
 * left it: most of a powder bed beside a droplet) has only contacts, and
 * its loop reaches the contact distance only: the same cells in the same
 * order, so the same sum bit for bit. */
KERNEL void grain_particle_forces(GLOBAL const real *position, GLOBAL const real *velocity,
                                  GLOBAL const real *wall_velocity, GLOBAL const real *density,
                                  GLOBAL const real *pressure, GLOBAL const real *gas_wall_pressure,
                                  GLOBAL const real *mass, GLOBAL const real *gamma,
                                  GLOBAL const real *liquid_fraction, GLOBAL const real *smoothing_length,
                                  GLOBAL const int *kind, GLOBAL const int *material, GLOBAL const int *grain,
                                  GLOBAL const int *cell, int n, grid_geometry g, GLOBAL const int *cell_start,
                                  GLOBAL const int *fluid_count, GLOBAL const real *materials, fluid_params fp,
                                  grain_params p, GLOBAL real *acceleration)
{
    FOR_EACH_ITEM(r, n)
    {
        if (kind[r] == KIND_GRAIN) {
            int cc[3];
            grid_cell_coords(&g, cell[r], cc);
            real x_r[3];
            grid_point(position, r, x_r);
            const real support = SUPPORT_OVER_H * fp.h_max;
            const int fluid_near = grid_fluid_in_box(&g, cell_start, fluid_count, cc, GRID_CELLS_PER_SUPPORT);
            const real reach = fluid_near ? fmax(support, p.distance) : p.distance;
            real f[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
            FOR_EACH_NEIGHBOUR(b, run, &g, cc, x_r, cell_start, reach)
            {
                real r_rb[3], r2;
                if (b == r || !grid_pair_within(&run, position, b, reach * reach, r_rb, &r2))
                    continue;
                if (kind[b] == KIND_FLUID) {
                    if (r2 < support * support) {
                        const fluid_pair_side s_b = fluid_pair_side_of(b, velocity, mass, density, pressure, gamma,
                                                                       liquid_fraction, smoothing_length, material,
                                                                       materials, &fp);
                        real r_br[3] = {-r_rb[0], -r_rb[1], -r_rb[2]};
                        real a_br[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
                        fluid_pair_acceleration(&s_b, r, r_br, r2, velocity, wall_velocity, density, pressure,
                                                gas_wall_pressure, mass, gamma, liquid_fraction, smoothing_length, kind,
                                                material, materials, &fp, a_br);
                        for (int d = 0; d < 3; ++d)
                            f[d] -= mass[b] * a_br[d];
                    }
                } else if ((kind[b] != KIND_GRAIN || grain[b] != grain[r]) && r2 < p.distance * p.distance) {
                    real u_rb[3];
                    for (int d = 0; d < 3; ++d)
                        u_rb[d] = velocity[3 * r + d] - velocity[3 * b + d];
                    contact_force(r_rb, sqrt(r2), u_rb, &p, f);
                }
            }
            for (int d = 0; d < 3; ++d)
                acceleration[3 * r + d] = f[d] / mass[r] + p.gravity[d];
        }
    }
}

/* The particles grain by grain, by a counting sort that keeps the grid's
 * order within a grain (so the sums below are the same on every backend
 * and thread count): the particles are cut into nchunks chunks; count[k
 * nchunks + c] counts grain k's particles in chunk c; its exclusive prefix
 * sum is where they go. */
KERNEL void grain_chunk_count(GLOBAL const int *kind, GLOBAL const int *grain, int n, int chunk, int nchunks,
                              int ngrains, GLOBAL int *count)
{
    FOR_EACH_ITEM(c, nchunks)
    {
        for (int k = 0; k < ngrains; ++k)
            count[k * nchunks + c] = 0;
        const int end = (c + 1) * chunk < n ? (c + 1) * chunk : n;
        for (int r = c * chunk; r < end; ++r)
            if (kind[r] == KIND_GRAIN)
                ++count[grain[r] * nchunks + c];
    }
}

/* order lists the grain particles grain by grain; afterwards offset[k
 * nchunks + nchunks - 1] is the end of grain k's list. */
KERNEL void grain_chunk_scatter(GLOBAL const int *kind, GLOBAL const int *grain, int n, int chunk, int nchunks,
                                GLOBAL int *offset, GLOBAL int *order)
{
    FOR_EACH_ITEM(c, nchunks)
    {
        const int end = (c + 1) * chunk < n ? (c + 1) * chunk : n;
        for (int r = c * chunk; r < end; ++r)
            if (kind[r] == KIND_GRAIN)
                order[offset[grain[r] * nchunks + c]++] = r;
    }
}

/* Mass quantities and resultants of each grain from its particles r:
 *   m_k = sum m_r,  r_k = sum m_r r_r / m_k                   (Fuchs Eq. 35)
 *   I_k = sum [I_r 1 + m_r (|r_rk|^2 1 - r_rk r_rk)]          (Fuchs Eq. 36)
 *   f_k = sum m_r a_r,  torque = sum r_rk x m_r a_r           (Fuchs Eq. 38)
 *   u_k = sum m_r u_r / m_k                                   (Fuchs Eq. 37)
 * with r_rk = r_r - r_k. The particles move rigidly, u_r = u_k' + omega_k x
 * (r_r - r_k'), so the last is u_k' + omega_k x (r_k - r_k'): Eq. 37 after
 * the grain lost or gained particles, and u_k itself otherwise. With
 * recover_spin (at the start) omega_k solves the angular momentum of the
 * particles, sum r_rk x m_r u_r = I omega_k with I of the points alone,
 * which is exact for a rigid rotation. */
KERNEL void grain_sums(GLOBAL const int *order, GLOBAL const int *offset, int nchunks, int ngrains,
                       GLOBAL const real *position, GLOBAL const real *velocity, GLOBAL const real *mass,
                       GLOBAL const real *acceleration, grain_params p, int recover_spin, GLOBAL real *grains)
{
    FOR_EACH_ITEM(k, ngrains)
    {
        GLOBAL real *rec = grains + GRAIN_RECORD * k;
        const int begin = k == 0 ? 0 : offset[k * nchunks - 1];
        const int end = offset[(k + 1) * nchunks - 1];
        /* sums of departures from the grain's last centre and velocity,
         * which are small and of either sign, so that rounding does not
         * build up into a drift of the centre or the momentum */
        real centre_before[3], velocity_before[3];
        grain_vector(grains, k, GRAIN_CENTRE, centre_before);
        grain_vector(grains, k, GRAIN_VELOCITY, velocity_before);
        real m = REAL(0.0), moment[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        real momentum[3] = {REAL(0.0), REAL(0.0), REAL(0.0)}, force[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        for (int j = begin; j < end; ++j) {
            const int r = order[j];
            m += mass[r];
            for (int d = 0; d < 3; ++d) {
                moment[d] += mass[r] * (position[3 * r + d] - centre_before[d]);
                momentum[d] += mass[r] * (velocity[3 * r + d] - velocity_before[d]);
                force[d] += mass[r] * acceleration[3 * r + d];
            }
        }
        real spin[3], angular_momentum[3];
        grain_vector(grains, k, GRAIN_SPIN, spin);
        grain_vector(grains, k, GRAIN_ANGULAR_MOMENTUM, angular_momentum);
        const real particles_before = rec[GRAIN_PARTICLES];
        for (int f = 0; f < GRAIN_RECORD; ++f)
            rec[f] = REAL(0.0);
        if (m > REAL(0.0)) {
            real centre[3];
            for (int d = 0; d < 3; ++d)
                centre[d] = centre_before[d] + moment[d] / m;
            real i6[6];
            real torque[3] = {REAL(0.0), REAL(0.0), REAL(0.0)}, orbital[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
            real point_i6[6] = {REAL(0.0), REAL(0.0), REAL(0.0), REAL(0.0), REAL(0.0), REAL(0.0)};
            for (int j = begin; j < end; ++j) {
                const int r = order[j];
                real arm[3], ma[3], mu[3], t[3], l[3];
                for (int d = 0; d < 3; ++d) {
                    arm[d] = position[3 * r + d] - centre[d];
                    ma[d] = mass[r] * acceleration[3 * r + d];
                    mu[d] = mass[r] * velocity[3 * r + d];
                }
                const real a2 = dot3(arm, arm);
                point_i6[0] += mass[r] * (a2 - arm[0] * arm[0]);
                point_i6[1] += mass[r] * (a2 - arm[1] * arm[1]);
                point_i6[2] += mass[r] * (a2 - arm[2] * arm[2]);
                point_i6[3] -= mass[r] * arm[0] * arm[1];
                point_i6[4] -= mass[r] * arm[0] * arm[2];
                point_i6[5] -= mass[r] * arm[1] * arm[2];
                cross3(arm, ma, t);
                cross3(arm, mu, l);
                for (int d = 0; d < 3; ++d) {
                    torque[d] += t[d];
                    orbital[d] += l[d];
                }
            }
            for (int e = 0; e < 6; ++e)
                i6[e] = point_i6[e] + (e < 3 ? p.particle_inertia_factor * m : REAL(0.0));
            /* the angular velocity: from the particles' orbital angular
             * momentum (recover_spin); unchanged where the grain lost or
             * gained particles (Eq. 37), its L following the new inertia;
             * else from the L the kicks integrate, through the inertia of the
             * turned grain */
            if (recover_spin)
                inertia_solve(point_i6, orbital, spin);
            if (recover_spin || (real)(end - begin) != particles_before)
                inertia_apply(i6, spin, angular_momentum);
            else
                inertia_solve(i6, angular_momentum, spin);
            rec[GRAIN_MASS] = m;
            for (int d = 0; d < 3; ++d) {
                rec[GRAIN_CENTRE + d] = centre[d];
                rec[GRAIN_VELOCITY + d] = velocity_before[d] + momentum[d] / m;
                rec[GRAIN_SPIN + d] = spin[d];
                rec[GRAIN_FORCE + d] = force[d];
                rec[GRAIN_TORQUE + d] = torque[d];
                rec[GRAIN_ANGULAR_MOMENTUM + d] = angular_momentum[d];
            }
            for (int e = 0; e < 6; ++e)
                rec[GRAIN_INERTIA + e] = i6[e];
            rec[GRAIN_PARTICLES] = (real)(end - begin);
        }
    }
}

/* Which grain a fluid particle that solidifies now joins (Fuchs et al.
 * 2022 Sec. 3.4.1: grains gain particles): the grain of its nearest
 * non-fluid neighbour within the support, if that is a grain particle;
 * GRAIN_NONE (it becomes a fixed solid) if that is a wall or a fixed solid
 * or there is none. Writes `grain` of solidifying fluid particles only and
 * reads it of grain particles only, so the gather has no race. */
KERNEL void grain_capture(GLOBAL const real *position, GLOBAL const int *kind, GLOBAL const int *material,
                          GLOBAL const real *liquid_fraction, GLOBAL const int *cell, int n, grid_geometry g,
                          GLOBAL const int *cell_start, GLOBAL const real *table, real support,
                          GLOBAL int *grain)
{
    FOR_EACH_ITEM(a, n)
    {
        if (kind[a] == KIND_FLUID && liquid_fraction[a] <= REAL(0.0) && material_melts(table, material[a])) {
            int cc[3];
            grid_cell_coords(&g, cell[a], cc);
            real x_a[3];
            grid_point(position, a, x_a);
            real nearest = support * support;
            int joins = GRAIN_NONE;
            FOR_EACH_NEIGHBOUR(b, run, &g, cc, x_a, cell_start, support)
            {
                real r_ab[3], r2;
                if (kind[b] != KIND_FLUID && grid_pair_within(&run, position, b, nearest, r_ab, &r2)) {
                    nearest = r2;
                    joins = kind[b] == KIND_GRAIN ? grain[b] : GRAIN_NONE;
                }
            }
            grain[a] = joins;
        }
    }
}

/* Grain particles that melt (liquid fraction above 0) leave their grain as
 * fluid at the velocity they had (Fuchs Sec. 3.4.1); solidifying fluid
 * particles that grain_capture gave a grain join it. The rest of the phase
 * change (a fluid becomes a fixed solid, and back) is finish_thermal_step's. */
KERNEL void grain_change_phase(GLOBAL const real *liquid_fraction, GLOBAL const int *material, int n,
                               GLOBAL const real *table, GLOBAL int *kind, GLOBAL int *grain)
{
    FOR_EACH_ITEM(a, n)
    {
        if (kind[a] == KIND_GRAIN && liquid_fraction[a] > REAL(0.0)) {
            kind[a] = KIND_FLUID;
            grain[a] = GRAIN_NONE;
        } else if (kind[a] == KIND_FLUID && liquid_fraction[a] <= REAL(0.0) && material_melts(table, material[a]) &&
                   grain[a] != GRAIN_NONE) {
            kind[a] = KIND_GRAIN;
        }
    }
}
