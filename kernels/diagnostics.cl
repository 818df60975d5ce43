/* Kernels that measure the discretisation itself: kernel moments and explicit
 * neighbour lists. The tests use them to check the smoothing kernels and the
 * grid against exact answers (VALIDATION.md K1, K2). */
#include "device.h"
#include "neighbours.h"
#include "smoothing.h"

/* Kernel moments with V_b = m_b / rho_b, per particle a:
 *   zeroth[a]  = sum_b V_b W_ab                       (= 1 in the interior)
 *   first[a]   = sum_b V_b (r_b - r_a) W_ab           (= 0)
 *   gradient[a]= sum_b V_b (r_b - r_a) (x) grad_a W_ab  (= I), row-major 3x3
 * (the last is the SPH gradient of f = r, with grad_a W_ab = F r_ab). */
KERNEL void kernel_moments(GLOBAL const real *position, GLOBAL const real *mass,
                           GLOBAL const real *density, GLOBAL const int *cell, int n,
                           grid_geometry g, GLOBAL const int *cell_start, real h,
                           GLOBAL real *zeroth, GLOBAL real *first, GLOBAL real *gradient)
{
    FOR_EACH_ITEM(a, n)
    {
        int cc[3];
        grid_cell_coords(&g, cell[a], cc);
        real m0 = REAL(0.0);
        real m1[3] = {REAL(0.0), REAL(0.0), REAL(0.0)};
        real m2[9] = {REAL(0.0)};
        real x_a[3];
        grid_point(position, a, x_a);
        FOR_EACH_NEIGHBOUR(b, run, &g, cc, x_a, cell_start, SUPPORT_OVER_H * h)
        {
            real r_ab[3];
            grid_displacement(&run, position, b, r_ab);
            const real r = sqrt(r_ab[0] * r_ab[0] + r_ab[1] * r_ab[1] + r_ab[2] * r_ab[2]);
            const real v_b = mass[b] / density[b];
            const real w = smoothing_w(r, h);
            const real f = smoothing_grad_factor(r, h);
            m0 += v_b * w;
            for (int i = 0; i < 3; ++i) {
                m1[i] -= v_b * r_ab[i] * w;
                for (int j = 0; j < 3; ++j)
                    m2[3 * i + j] -= v_b * r_ab[i] * f * r_ab[j];
            }
        }
        zeroth[a] = m0;
        for (int i = 0; i < 3; ++i)
            first[3 * a + i] = m1[i];
        for (int i = 0; i < 9; ++i)
            gradient[9 * a + i] = m2[i];
    }
}

/* The ids of the particles b != a within the radius of a in the set `set`
 * that a loop visits, folded in the order it visits them (h = 31 h + id):
 * two loops with the same fold visit them in the same order. */
static inline uint visit_fold(uint fold, int a, int b, real r2, real radius, GLOBAL const uint *id)
{
    return b != a && r2 < radius * radius ? 31u * fold + id[b] : fold;
}

/* Global ids of every b != a with |r_ab| < radius in the sets first_set
 * .. last_set (GRID_SET_*), up to max_neighbours; count[a] is the true
 * number even when the list is cut. On a grid without a
 * periodic axis, box_count[a] is the number of those of set last_set that
 * FOR_EACH_IN_BOX finds, and box_order[a] 1 where it visits them in
 * the order of FOR_EACH_NEIGHBOUR_IN over that set (visit_fold); -1 and 0
 * with a periodic axis. within_order[a] is 1 where FOR_EACH_NEIGHBOUR_WITHIN
 * visits the particles of both sets within the radius in the order of
 * FOR_EACH_NEIGHBOUR (and no other particle). */
KERNEL void neighbour_list(GLOBAL const real *position, GLOBAL const uint *id,
                           GLOBAL const int *cell, int n, grid_geometry g,
                           GLOBAL const int *cell_start, real radius, int first_set, int last_set,
                           int max_neighbours, GLOBAL int *count, GLOBAL uint *neighbours,
                           GLOBAL int *box_count, GLOBAL int *box_order, GLOBAL int *within_order)
{
    FOR_EACH_ITEM(a, n)
    {
        int cc[3];
        grid_cell_coords(&g, cell[a], cc);
        int found = 0;
        real x_a[3];
        grid_point(position, a, x_a);
        FOR_EACH_NEIGHBOUR_IN(b, run, &g, cc, x_a, cell_start, GRID_CELLS_PER_SUPPORT, radius, first_set, last_set)
        {
            real r_ab[3];
            grid_displacement(&run, position, b, r_ab);
            const real r2 = r_ab[0] * r_ab[0] + r_ab[1] * r_ab[1] + r_ab[2] * r_ab[2];
            if (b != a && r2 < radius * radius) {
                if (found < max_neighbours)
                    neighbours[max_neighbours * a + found] = id[b];
                ++found;
            }
        }
        count[a] = found;
        box_count[a] = -1;
        box_order[a] = 0;
        if (!grid_has_periodic_axis(&g)) {
            uint trimmed = 0u, boxed = 0u;
            int in_box = 0;
            FOR_EACH_NEIGHBOUR_IN(b, run, &g, cc, x_a, cell_start, GRID_CELLS_PER_SUPPORT, radius, last_set, last_set)
            {
                real r_ab[3];
                grid_displacement(&run, position, b, r_ab);
                trimmed = visit_fold(trimmed, a, b, r_ab[0] * r_ab[0] + r_ab[1] * r_ab[1] + r_ab[2] * r_ab[2], radius, id);
            }
            FOR_EACH_IN_BOX(b, &g, cc, cell_start, GRID_CELLS_PER_SUPPORT, last_set)
            {
                real r2 = REAL(0.0);
                for (int d = 0; d < 3; ++d)
                    r2 += (x_a[d] - position[3 * b + d]) * (x_a[d] - position[3 * b + d]);
                in_box += b != a && r2 < radius * radius;
                boxed = visit_fold(boxed, a, b, r2, radius, id);
            }
            box_count[a] = in_box;
            box_order[a] = boxed == trimmed;
        }
        uint trimmed = 0u, listed = 0u;
        FOR_EACH_NEIGHBOUR(b, run, &g, cc, x_a, cell_start, radius)
        {
            real r_ab[3];
            grid_displacement(&run, position, b, r_ab);
            trimmed = visit_fold(trimmed, a, b, r_ab[0] * r_ab[0] + r_ab[1] * r_ab[1] + r_ab[2] * r_ab[2], radius, id);
        }
        FOR_EACH_NEIGHBOUR_WITHIN(b, run, &g, cc, x_a, cell_start, position, a, radius)
        {
            listed = 31u * listed + id[b];
        }
        within_order[a] = listed == trimmed;
    }
}

/* near[a] = grid_fluid_in_box of particle a's cell over the support's box
 * (kernels/neighbours.h), from count (host/grid.c amsph_grid_count_fluid). */
KERNEL void fluid_in_box(GLOBAL const int *cell, int n, grid_geometry g, GLOBAL const int *cell_start,
                         GLOBAL const int *count, GLOBAL int *near)
{
    FOR_EACH_ITEM(a, n)
    {
        int cc[3];
        grid_cell_coords(&g, cell[a], cc);
        near[a] = grid_fluid_in_box(&g, cell_start, count, cc, GRID_CELLS_PER_SUPPORT);
    }
}
