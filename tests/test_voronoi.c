/* The Voronoi cell volumes of tests/voronoi.h, the volume measure of the
 * isothermal-incompressibility cases, on point sets with known cells:
 *   - square and cubic lattices of spacing a: every closed cell is a^d;
 *   - a hexagonal lattice of spacing a: sqrt(3)/2 a^2; a body-centred
 *     cubic lattice of cube side a (truncated octahedra): a^3 / 2;
 *   - a jittered lattice in the unit square (cube) with its mirror images
 *     across every side (face): the cells of the original points tile it,
 *     so their volumes sum to 1, though no two agree;
 *   - the outermost points of a finite set have open cells (-1), and a
 *     reach too short to be sure of a cell reports it open, never wrong. */
#include <math.h>

#include "testing.h"
#include "voronoi.h"

enum { MAX_POINTS = 16384 };
static amsph_real position[3 * MAX_POINTS];
static double volume[MAX_POINTS], short_reach[MAX_POINTS];

static void place(int i, double x, double y, double z)
{
    position[3 * i] = (amsph_real)x;
    position[3 * i + 1] = (amsph_real)y;
    position[3 * i + 2] = (amsph_real)z;
}

static const double tolerance = AMSPH_DOUBLE ? 1e-12 : 1e-5;

/* Cells of a 2D lattice of n x n points with rows offset by `shift` of a
 * spacing and `rise` apart (square: 0, 1; hexagonal: 1/2, sqrt(3)/2): the
 * interior ones are `expected` a^2, those of the bottom and top rows open. */
static void check_lattice_2d(const char *name, double shift, double rise, double expected)
{
    const int n = 20;
    const double a = 0.05;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            place(i + n * j, a * (i + shift * (j % 2)), a * rise * j, 0.0);
    CHECK_OK(voronoi_volumes(position, n * n, 2, 3.0 * a, volume));
    double worst = 0.0;
    int closed = 0, open_edges = 1;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double cell = volume[i + n * j];
            if (j == 0 || j == n - 1) {
                open_edges &= cell < 0.0;
            } else if (i > 0 && i < n - 1) {
                worst = fmax(worst, fabs(cell - expected * a * a));
                ++closed;
            }
        }
    CHECK(closed == (n - 2) * (n - 2), "%s: %d closed interior cells of %d", name, closed, (n - 2) * (n - 2));
    CHECK(worst < tolerance * a * a, "%s: a cell differs from %g a^2 by %g a^2", name, expected, worst / (a * a));
    CHECK(open_edges, "%s: a cell of the bottom or top row is closed", name);
}

/* Cells of a cubic lattice of n^3 points, with the cube centres too when
 * body_centred: the cells of points two layers inside are a^3 (cubic) or
 * a^3 / 2 (body-centred cubic: truncated octahedra), the outermost open. */
static void check_lattice_3d(const char *name, int body_centred, double expected)
{
    const int n = 8;
    const double a = 0.1;
    int count = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                place(count++, a * i, a * j, a * k);
                if (body_centred)
                    place(count++, a * (i + 0.5), a * (j + 0.5), a * (k + 0.5));
            }
    CHECK_OK(voronoi_volumes(position, count, 3, 3.0 * a, volume));
    const double last = body_centred ? n - 0.5 : n - 1.0; /* the largest coordinate / a */
    double worst = 0.0;
    int closed = 0, open_outer = 1;
    for (int p = 0; p < count; ++p) {
        int inside = 1, outer = 0;
        for (int d = 0; d < 3; ++d) {
            const double x = position[3 * p + d] / a;
            inside &= x >= 2.0 && x <= n - 3.0;
            outer |= x < 0.25 || x > last - 0.25;
        }
        if (inside) {
            worst = fmax(worst, fabs(volume[p] - expected * a * a * a));
            ++closed;
        }
        if (outer)
            open_outer &= volume[p] < 0.0;
    }
    CHECK(closed > 0 && worst < tolerance * a * a * a, "%s: a cell of %d differs from %g a^3 by %g a^3", name,
          closed, expected, worst / (a * a * a));
    CHECK(open_outer, "%s: a cell on the lattice's outside is closed", name);
}

/* A jittered m^d lattice in [0, 1]^d and its mirror images across every
 * side (face): the originals' cells tile the unit square (cube). */
static void check_tiling(int dim, int m)
{
    const double a = 1.0 / m;
    int n = 1;
    for (int d = 0; d < dim; ++d)
        n *= m;
    unsigned long long state = 2024;
    for (int k = 0; k < n; ++k) {
        double x[3] = {0.0, 0.0, 0.0};
        for (int d = 0, rest = k; d < dim; ++d, rest /= m) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            x[d] = a * (rest % m + 0.5 + 0.6 * ((double)(state >> 11) * 0x1.0p-53 - 0.5));
        }
        place(k, x[0], x[1], x[2]);
        for (int d = 0; d < dim; ++d)
            for (int side = 0; side < 2; ++side) {
                double mirror[3] = {x[0], x[1], x[2]};
                mirror[d] = side ? 2.0 - x[d] : -x[d];
                place(n * (1 + 2 * d + side) + k, mirror[0], mirror[1], mirror[2]);
            }
    }
    const int total = n * (1 + 2 * dim);
    CHECK_OK(voronoi_volumes(position, total, dim, 4.0 * a, volume));
    double sum = 0.0, smallest = INFINITY, largest = 0.0;
    int open = 0;
    for (int k = 0; k < n; ++k) {
        open += volume[k] < 0.0;
        sum += volume[k];
        smallest = fmin(smallest, volume[k]);
        largest = fmax(largest, volume[k]);
    }
    const double cell = pow(a, dim);
    CHECK(open == 0, "%dD: %d cells of the mirrored set are open", dim, open);
    CHECK(fabs(sum - 1.0) < 10 * tolerance, "%dD: cells sum to %.9g, not the unit volume", dim, sum);
    CHECK(largest - smallest > 0.2 * cell, "%dD: jittered cells all alike (%g to %g)", dim, smallest, largest);
    /* a reach of one spacing closes few cells, and those right */
    CHECK_OK(voronoi_volumes(position, total, dim, a, short_reach));
    double worst = 0.0;
    open = 0;
    for (int k = 0; k < n; ++k) {
        open += short_reach[k] < 0.0;
        if (short_reach[k] >= 0.0)
            worst = fmax(worst, fabs(short_reach[k] - volume[k]));
    }
    CHECK(open > n / 2, "%dD: with reach = spacing, %d of %d cells closed", dim, n - open, n);
    CHECK(worst < tolerance * cell, "%dD: a cell closed at a short reach is off by %g of a^d", dim, worst / cell);
}

int main(void)
{
    check_lattice_2d("square", 0.0, 1.0, 1.0);
    check_lattice_2d("hexagonal", 0.5, sqrt(3.0) / 2.0, sqrt(3.0) / 2.0);
    check_lattice_3d("cubic", 0, 1.0);
    check_lattice_3d("body-centred cubic", 1, 0.5);
    check_tiling(2, 25);
    check_tiling(3, 10);
    return testing_finish();
}
