/* The Voronoi cell areas of tests/voronoi.h, the volume measure of the
 * isothermal-incompressibility cases, on point sets with known cells:
 *   - a square lattice of spacing a: every closed cell is a^2;
 *   - a hexagonal lattice of spacing a: every closed cell is sqrt(3)/2 a^2;
 *   - a jittered lattice in the unit square with its mirror images across
 *     the four sides: the cells of the original points tile the square, so
 *     their areas sum to 1; no two agree, unlike on a lattice;
 *   - the outermost points of a finite set have open cells (-1), and a
 *     reach too short to be sure of a cell reports it open, never wrong. */
#include <math.h>

#include "testing.h"
#include "voronoi.h"

enum { MAX_POINTS = 4096 };
static amsph_real position[3 * MAX_POINTS];
static double area[MAX_POINTS];

static void place(int i, double x, double y)
{
    position[3 * i] = (amsph_real)x;
    position[3 * i + 1] = (amsph_real)y;
    position[3 * i + 2] = 0;
}

/* Cells of an n x n lattice with rows offset by `shift` of a spacing and
 * `rise` apart (square: 0, 1; hexagonal: 1/2, sqrt(3)/2): the interior ones
 * are `expected`, those of the bottom and top rows open. */
static void check_lattice(const char *name, double shift, double rise, double expected)
{
    const int n = 20;
    const double a = 0.05;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            place(i + n * j, a * (i + shift * (j % 2)), a * rise * j);
    CHECK_OK(voronoi_areas(position, n * n, 3.0 * a, area));
    double worst = 0.0;
    int closed = 0, open_edges = 1;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double cell = area[i + n * j];
            if (j == 0 || j == n - 1) {
                open_edges &= cell < 0.0;
            } else if (i > 0 && i < n - 1) {
                worst = fmax(worst, fabs(cell - expected * a * a));
                ++closed;
            }
        }
    CHECK(closed == (n - 2) * (n - 2), "%s: %d closed interior cells of %d", name, closed, (n - 2) * (n - 2));
    CHECK(worst < (AMSPH_DOUBLE ? 1e-12 : 1e-6) * a * a, "%s: a cell differs from %g a^2 by %g a^2", name, expected,
          worst / (a * a));
    CHECK(open_edges, "%s: a cell of the bottom or top row is closed", name);
}

/* A jittered m x m lattice in [0, 1]^2 and its mirror images across x = 0,
 * x = 1, y = 0, y = 1: the originals' cells tile the unit square. */
static void check_tiling(void)
{
    const int m = 25, n = m * m;
    const double a = 1.0 / m;
    unsigned long long state = 2024;
    for (int k = 0; k < n; ++k) {
        double jitter[2];
        for (int d = 0; d < 2; ++d) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            jitter[d] = 0.6 * ((double)(state >> 11) * 0x1.0p-53 - 0.5);
        }
        const double x = a * (k % m + 0.5 + jitter[0]), y = a * (k / m + 0.5 + jitter[1]);
        place(k, x, y);
        place(n + k, -x, y);
        place(2 * n + k, 2.0 - x, y);
        place(3 * n + k, x, -y);
        place(4 * n + k, x, 2.0 - y);
    }
    CHECK_OK(voronoi_areas(position, 5 * n, 4.0 * a, area));
    double sum = 0.0, smallest = INFINITY, largest = 0.0;
    int open = 0;
    for (int k = 0; k < n; ++k) {
        open += area[k] < 0.0;
        sum += area[k];
        smallest = fmin(smallest, area[k]);
        largest = fmax(largest, area[k]);
    }
    CHECK(open == 0, "%d cells of the mirrored set are open", open);
    CHECK(fabs(sum - 1.0) < (AMSPH_DOUBLE ? 1e-12 : 1e-5), "cells sum to %.9g, not the square's area 1", sum);
    CHECK(largest - smallest > 0.2 * a * a, "jittered cells all alike (%g to %g)", smallest, largest);
    /* a reach of one spacing closes few cells, and those right */
    static double short_reach[MAX_POINTS];
    CHECK_OK(voronoi_areas(position, 5 * n, a, short_reach));
    double worst = 0.0;
    open = 0;
    for (int k = 0; k < n; ++k) {
        open += short_reach[k] < 0.0;
        if (short_reach[k] >= 0.0)
            worst = fmax(worst, fabs(short_reach[k] - area[k]));
    }
    CHECK(open > n / 2, "with reach = spacing, %d of %d cells closed", n - open, n);
    CHECK(worst < (AMSPH_DOUBLE ? 1e-12 : 1e-6) * a * a, "a cell closed at a short reach is off by %g a^2",
          worst / (a * a));
}

int main(void)
{
    check_lattice("square", 0.0, 1.0, 1.0);
    check_lattice("hexagonal", 0.5, sqrt(3.0) / 2.0, sqrt(3.0) / 2.0);
    check_tiling();
    return testing_finish();
}
