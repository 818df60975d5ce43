/* Time integration: kick-drift-kick leap-frog (Russell 2018 Eq. 3.55 in
 * its velocity-Verlet form, one force evaluation per step), in which the
 * density advances with the positions:
 *   u^{n+1/2} = u^n + a^n dt/2
 *   r^{n+1}   = r^n + u^{n+1/2} dt
 *   rho^{n+1} = rho^n + dt drho/dt(r^{n+1}, u^{n+1/2})
 *   u^{n+1}   = u^{n+1/2} + a^{n+1} dt/2,  a^{n+1} from r^{n+1}, rho^{n+1}, u^{n+1/2}.
 * Kicking the density with the velocity instead (rho^{n+1/2} = rho^n +
 * dt/2 drho/dt^n, ...) is unconditionally unstable for the acoustic
 * oscillator u' = -a rho, rho' = b u: its amplification matrix has
 * determinant 1 + (omega dt)^2 / 2 + (omega dt)^4 / 16 > 1.
 * Fluid particles are kicked; walls and fixed solids keep their velocity
 * (a moving wall drifts at it) and take their density from the fluid. */
#include "device.h"
#include "fluid_options.h"
#include "kinds.h"

/* a = g for fluid, 0 elsewhere: the rates of a scene without fluid forces. */
KERNEL void body_force(GLOBAL const int *kind, int n, real gx, real gy, real gz,
                       GLOBAL real *acceleration)
{
    FOR_EACH_ITEM(i, n)
    {
        const real on = kind[i] == KIND_FLUID ? REAL(1.0) : REAL(0.0);
        acceleration[3 * i + 0] = on * gx;
        acceleration[3 * i + 1] = on * gy;
        acceleration[3 * i + 2] = on * gz;
    }
}

KERNEL void kick(GLOBAL const int *kind, GLOBAL const real *acceleration, int n, real half_dt,
                 GLOBAL real *velocity)
{
    FOR_EACH_ITEM(i, n)
    {
        if (kind[i] == KIND_FLUID) {
            for (int d = 0; d < AMSPH_DIM; ++d)
                velocity[3 * i + d] += half_dt * acceleration[3 * i + d];
        }
    }
}

/* Relaxation towards rest: u *= factor (= exp(-rate dt)) for fluid
 * particles. Friction removes kinetic energy and leaves every equilibrium
 * of the forces in place, so a scene damped to rest shows the balance of
 * its forces (a droplet's Young-Laplace pressure) without waiting for
 * weakly damped acoustic modes to die out. */
KERNEL void damp_velocity(GLOBAL const int *kind, int n, real factor, GLOBAL real *velocity)
{
    FOR_EACH_ITEM(i, n)
    {
        if (kind[i] == KIND_FLUID) {
            for (int d = 0; d < AMSPH_DIM; ++d)
                velocity[3 * i + d] *= factor;
        }
    }
}

/* The density a fluid particle takes at the step's end from `advanced`,
 * the scheme's update, where fewer than d other particles lie within its
 * support (`others`, counted by continuity): spray.
 *  - Alone: rho0(T). Continuity has nothing to expand or compress it
 *    against, and a drop that small stands at the ambient pressure, p = p_b.
 *    Without this a spray particle heated in a beam keeps the density it
 *    left the melt with while rho0(T) falls (in the 200 W track, 35% apart:
 *    the density guard), and meets the melt again compressed.
 *  - With 1 to d - 1 others (a pair; in 3D also three): at least rho0(T).
 *    Its neighbours span fewer than d directions (the moment matrix
 *    B = -sum_b V_b r_ab (grad_a W_ab)^T has rank below d), so continuity
 *    sees its volume change along those directions only: it measures the
 *    pair closing, whose pressure pushes the two apart, but not the
 *    particle's volume, and a pair torn off below rho0 would pull itself
 *    together by its tension (the PBF point case: 2% below rho0, -55 MPa,
 *    0.3 dx apart). Spray holds no tension.
 * From d others on, `advanced`. */
static inline real density_at_step_end(int others, real reference_density, real advanced)
{
    if (others >= AMSPH_DIM)
        return advanced;
    return others == 0 ? reference_density : fmax(advanced, reference_density);
}

/* rho += dt drho/dt for fluid particles (continuity, kernels/fluid.cl),
 * density_at_step_end; with gas_summed (fluid.gas_density: summation) plus
 * the summed density's pull summed_pull (kernels/fluid.cl
 * summed_density_pull; there drho/dt is the continuity's share of it). */
KERNEL void advance_density(GLOBAL const int *kind, GLOBAL const real *density_rate, GLOBAL const int *others,
                            GLOBAL const real *reference_density, GLOBAL const real *summed_pull, int gas_summed,
                            int n, real dt, GLOBAL real *density)
{
    FOR_EACH_ITEM(i, n)
    {
        if (kind[i] == KIND_FLUID) {
            const real pull = gas_summed ? summed_pull[i] : REAL(0.0);
            density[i] = density_at_step_end(others[i], reference_density[i], density[i] + dt * density_rate[i] + pull);
        }
    }
}

/* One step of the Verlet scheme (Verlet 1967; as DualSPHysics has it,
 * Crespo et al. 2015 Sec. 2.7.1), from the rates a^n and drho^n/dt of one
 * neighbour pass at the state n (fluid_forces with p.one_pass):
 *   r^(n+1)   = r^n + dt v^n + dt^2 a^n / 2
 *   v^(n+1)   = v^(n-1) + span a^n,      rho^(n+1) = rho^(n-1) + span drho^n/dt
 * span = t^(n+1) - t^(n-1), the two steps the difference spans (2 dt where
 * the step does not change); with `euler` (one step in fluid.verlet_steps)
 *   v^(n+1)   = v^n + dt a^n,            rho^(n+1) = rho^n + dt drho^n/dt,
 * which joins the two interleaved sequences of the scheme again. The state
 * n becomes the previous one; the density goes through density_at_step_end.
 * Walls and fixed solids move with their velocity; grains are not in such
 * a case (case.c). */
KERNEL void verlet_update(GLOBAL const int *kind, GLOBAL const real *acceleration, GLOBAL const real *density_rate,
                          GLOBAL const int *others, GLOBAL const real *reference_density, int n, real dt,
                          real span, int euler, GLOBAL real *position, GLOBAL real *velocity,
                          GLOBAL real *velocity_previous, GLOBAL real *density, GLOBAL real *density_previous)
{
    FOR_EACH_ITEM(i, n)
    {
        if (kind[i] == KIND_FLUID) {
            for (int d = 0; d < AMSPH_DIM; ++d) {
                const real u = velocity[3 * i + d], a = acceleration[3 * i + d];
                position[3 * i + d] += dt * u + REAL(0.5) * dt * dt * a;
                velocity[3 * i + d] = euler ? u + dt * a : velocity_previous[3 * i + d] + span * a;
                velocity_previous[3 * i + d] = u;
            }
            const real rho = density[i];
            density[i] = density_at_step_end(others[i], reference_density[i],
                                             euler ? rho + dt * density_rate[i]
                                                   : density_previous[i] + span * density_rate[i]);
            density_previous[i] = rho;
        } else {
            for (int d = 0; d < AMSPH_DIM; ++d)
                position[3 * i + d] += dt * velocity[3 * i + d];
        }
    }
}

/* r += dt v, except for grain particles, which move with their grain
 * (grain_drift, kernels/grains.cl). */
KERNEL void drift(GLOBAL const int *kind, GLOBAL const real *velocity, int n, real dt, GLOBAL real *position)
{
    FOR_EACH_ITEM(i, n)
    {
        if (kind[i] != KIND_GRAIN)
            for (int d = 0; d < AMSPH_DIM; ++d)
                position[3 * i + d] += dt * velocity[3 * i + d];
    }
}

/* |v| per particle of a 3-vector field (speed, acceleration magnitude). */
KERNEL void vector_norm(GLOBAL const real *v, int n, GLOBAL real *out)
{
    FOR_EACH_ITEM(i, n)
    {
        const real x = v[3 * i], y = v[3 * i + 1], z = v[3 * i + 2];
        out[i] = sqrt(x * x + y * y + z * z);
    }
}
