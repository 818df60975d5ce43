/* Run guards: per particle, the first check it fails, as a code the host
 * reduces with a maximum:
 *   GUARD_DENSITY   |rho - rho0(T)| / rho0(T) above the bound (fluid); with
 *                   negative pressures clamped, (rho - rho0) / rho0 only: an
 *                   expanded particle then has no pressure and pushes nothing
 *                   (spray torn off a droplet keeps the density it left with)
 *   GUARD_CLOSE     nearest neighbour closer than the bound (fluid)
 *   GUARD_NOT_FINITE position, velocity, density or (with_temperature)
 *                   temperature not finite (any kind)
 * Without the fluid module (fluid = 0) only the last is checked, and
 * reference_density and closest are not read. */
#include "device.h"
#include "kinds.h"

#define GUARD_OK 0
#define GUARD_DENSITY 1
#define GUARD_CLOSE 2
#define GUARD_NOT_FINITE 3

KERNEL void guard_check(GLOBAL const real *position, GLOBAL const real *velocity,
                        GLOBAL const real *density, GLOBAL const real *reference_density,
                        GLOBAL const real *temperature, int with_temperature, GLOBAL const int *kind,
                        GLOBAL const real *closest, int n, int fluid, real min_distance,
                        real max_density_error, int clamped, GLOBAL real *code)
{
    FOR_EACH_ITEM(a, n)
    {
        int finite = isfinite(density[a]) && (!with_temperature || isfinite(temperature[a]));
        for (int d = 0; d < 3; ++d)
            finite = finite && isfinite(position[3 * a + d]) && isfinite(velocity[3 * a + d]);
        int result = GUARD_OK;
        if (!finite) {
            result = GUARD_NOT_FINITE;
        } else if (fluid && kind[a] == KIND_FLUID) {
            const real rho0 = reference_density[a];
            if (closest[a] < min_distance)
                result = GUARD_CLOSE;
            else if ((clamped ? density[a] - rho0 : fabs(density[a] - rho0)) > max_density_error * rho0)
                result = GUARD_DENSITY;
        }
        code[a] = (real)result;
    }
}
