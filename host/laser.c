#include "laser.h"

#include <math.h>
#include <string.h>

#include "error.h"
#include "thermal.h"

#define PI 3.14159265358979323846
#define MAX_BIN_NODES 100000000 /* 100 M nodes: 1.2 GB of bins in float */

double amsph_laser_beam_power(const amsph_case *c, double t)
{
    const amsph_laser_settings *l = &c->laser;
    if (t < l->on_time || t >= l->off_time)
        return 0.0;
    if (l->ramp_time == 0.0)
        return l->power;
    return l->power * fmin(1.0, fmin(t - l->on_time, l->off_time - t) / l->ramp_time);
}

double amsph_laser_beam_energy(const amsph_case *c, double t0, double t1)
{
    const amsph_laser_settings *l = &c->laser;
    const double corners[] = {l->on_time, l->on_time + l->ramp_time, l->off_time - l->ramp_time,
                              l->off_time, t1};
    double energy = 0.0, a = t0;
    for (int k = 0; k < 5 && a < t1; ++k) {
        const double b = fmin(fmax(corners[k], a), t1);
        energy += (b - a) * amsph_laser_beam_power(c, 0.5 * (a + b)); /* linear on [a, b] */
        a = b;
    }
    return energy;
}

void amsph_laser_beam_centre(const amsph_case *c, double t, double x[3])
{
    const amsph_laser_settings *l = &c->laser;
    memcpy(x, l->start, 3 * sizeof *x);
    double left = t; /* travel time still to follow */
    for (int k = 0; k < l->n_path && left > 0.0; ++k) {
        const double *to = l->path[k].to;
        const double length = sqrt((to[0] - x[0]) * (to[0] - x[0]) + (to[1] - x[1]) * (to[1] - x[1]) +
                                   (to[2] - x[2]) * (to[2] - x[2]));
        const double duration = length / l->path[k].speed;
        const double fraction = duration > left ? left / duration : 1.0;
        for (int d = 0; d < 3; ++d)
            x[d] = fraction < 1.0 ? x[d] + fraction * (to[d] - x[d]) : to[d];
        left -= duration;
    }
}

/* The first axis across the beam: the coordinate axis least aligned with
 * the direction d (within the simulated plane in 2D), made normal to d. */
static void beam_across(int dim, const double d[3], double across[3])
{
    int least = 0;
    for (int k = 1; k < dim; ++k)
        if (fabs(d[k]) < fabs(d[least]))
            least = k;
    double norm = 0.0;
    for (int k = 0; k < 3; ++k) {
        across[k] = (k == least ? 1.0 : 0.0) - d[least] * d[k];
        norm += across[k] * across[k];
    }
    for (int k = 0; k < 3; ++k)
        across[k] /= sqrt(norm);
}

int amsph_laser_bins(const amsph_case *c, double support, int *lateral_nodes, int *depth_nodes)
{
    const amsph_laser_settings *l = &c->laser;
    const double reach = sqrt((double)c->dim) * l->bin_size;
    if (reach > support)
        return amsph_bad_input("laser.bin_size %g m is too large: a bin node gathers its particles from "
                               "the grid cells around it, which needs bin_size * sqrt(%d) <= the kernel "
                               "support %g m; use bin_size <= %g m",
                               l->bin_size, c->dim, support, support / sqrt((double)c->dim));
    double extent = 0.0; /* of the domain along the beam */
    for (int k = 0; k < c->dim; ++k)
        extent += fabs(l->direction[k]) * (c->domain_max[k] - c->domain_min[k]);
    const double half = ceil(l->window * l->radius / l->bin_size);
    const double depth = ceil(extent / l->bin_size) + 1.0;
    const double columns = pow(2.0 * half + 1.0, c->dim - 1);
    if (columns * depth > MAX_BIN_NODES)
        return amsph_bad_input("the laser bin grid would have %.3g nodes (at most %g): raise "
                               "laser.bin_size or lower laser.window",
                               columns * depth, (double)MAX_BIN_NODES);
    *lateral_nodes = 2 * (int)half + 1;
    *depth_nodes = (int)depth;
    return 0;
}

static int lay_out_bins(amsph_sim *s)
{
    laser_params *p = &s->laser.params;
    AMSPH_CHECK(amsph_laser_bins(&s->config, s->support, &p->lateral_nodes, &p->depth_nodes));
    size_t nodes = (size_t)p->depth_nodes;
    for (int k = 0; k < 2; ++k) { /* the whole grid; each pass takes part of it (pass_grid) */
        p->lateral_first[k] = 0;
        p->lateral_count[k] = k < s->config.dim - 1 ? p->lateral_nodes : 1;
        nodes *= (size_t)p->lateral_count[k];
    }
    const size_t bytes = nodes * sizeof(amsph_real);
    AMSPH_CHECK(amsph_buffer_alloc(s->backend, bytes, &s->laser.bin_weight));
    return amsph_buffer_alloc(s->backend, bytes, &s->laser.bin_power);
}

int amsph_laser_setup(amsph_sim *s, amsph_host_particles *h)
{
    const amsph_case *c = &s->config;
    const amsph_laser_settings *l = &c->laser;
    laser_params *p = &s->laser.params;
    memset(&s->laser, 0, sizeof s->laser);
    double across[3];
    beam_across(c->dim, l->direction, across);
    for (int k = 0; k < 3; ++k) {
        p->direction[k] = (amsph_real)l->direction[k];
        p->across[k] = (amsph_real)across[k];
    }
    p->radius = (amsph_real)l->radius;
    p->bin_size = (amsph_real)l->bin_size;
    const int volumetric = l->absorption == AMSPH_ABSORPTION_VOLUMETRIC;
    p->absorption = (amsph_real)(volumetric ? l->absorption_coefficient : l->absorptivity);
    if (!volumetric)
        AMSPH_CHECK(amsph_surface_delta(s, 0.0, &p->surface_delta));
    AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_LASER_POWER));
    return volumetric ? lay_out_bins(s) : 0;
}

/* Beam state at time t: centre (wrapped into the domain on periodic axes,
 * so that every particle is less than a domain length from it), peak
 * irradiance 2P/(pi r_l^2) (Russell 2018 Eq. 3.42; for the Beer-Lambert
 * columns its non-reflected fraction zeta, the surface kernel applies zeta
 * itself) and the depth of the first bin node, the least depth of the
 * domain's corners. */
static void aim_beam(amsph_sim *s, double t, double power)
{
    const amsph_case *c = &s->config;
    const amsph_laser_settings *l = &c->laser;
    laser_params *p = &s->laser.params;
    double centre[3];
    amsph_laser_beam_centre(c, t, centre);
    for (int k = 0; k < c->dim; ++k) {
        const double length = c->domain_max[k] - c->domain_min[k];
        if (c->periodic[k])
            centre[k] -= length * floor((centre[k] - c->domain_min[k]) / length);
    }
    double depth_lo = 0.0;
    for (int k = 0; k < c->dim; ++k)
        depth_lo += fmin(l->direction[k] * (c->domain_min[k] - centre[k]),
                         l->direction[k] * (c->domain_max[k] - centre[k]));
    for (int k = 0; k < 3; ++k)
        p->centre[k] = (amsph_real)centre[k];
    p->depth_lo = (amsph_real)depth_lo;
    const double entering = l->absorption == AMSPH_ABSORPTION_VOLUMETRIC ? l->absorptivity : 1.0;
    p->peak_intensity = (amsph_real)(entering * 2.0 * power / (PI * l->radius * l->radius));
}

static amsph_arg field(amsph_sim *s, amsph_field_id f)
{
    return amsph_arg_buffer(s->particles.field[f]);
}

/* The extreme of sign q_d over the particles under the bin columns
 * (kernels/laser.cl laser_depth_extent). */
static int depth_extreme(amsph_sim *s, double sign, double *extreme)
{
    const int n = s->particles.n;
    AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "laser_depth_extent", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_MATERIAL), amsph_arg_int(n),
                             amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry),
                             amsph_arg_buffer(s->materials), amsph_arg_bytes(&s->laser.params, sizeof s->laser.params),
                             amsph_arg_real(sign), amsph_arg_buffer(s->work)));
    return amsph_reduce_max(s->backend, s->work, n, extreme);
}

/* The nodes first .. last (of count along an axis, node i at lo + i size)
 * that reach the points between q_lo and q_hi, and one more on either side
 * (a particle reaches the two nodes around it). */
static void nodes_over(double q_lo, double q_hi, double lo, double size, int count, int *first, int *last)
{
    *first = (int)fmax(0.0, floor((q_lo - lo) / size) - 1.0);
    *last = (int)fmin(count - 1.0, ceil((q_hi - lo) / size) + 1.0);
}

/* The pass's columns: along each axis across the beam, those over the
 * domain (the range of q_k over its corners), or all of them where the
 * axis has a part along a periodic direction. A plate narrower than the
 * beam's window leaves the columns beside it empty. Returns the count. */
static int lateral_columns(const amsph_case *c, laser_params *pass)
{
    double axis[2][3];
    for (int d = 0; d < 3; ++d)
        axis[0][d] = pass->across[d];
    for (int d = 0; d < 3; ++d) /* e2 = d x e1 */
        axis[1][d] = (double)pass->direction[(d + 1) % 3] * pass->across[(d + 2) % 3] -
                     (double)pass->direction[(d + 2) % 3] * pass->across[(d + 1) % 3];
    int columns = 1;
    for (int k = 0; k < c->dim - 1; ++k) {
        double q_lo = 0.0, q_hi = 0.0;
        int wraps = 0;
        for (int d = 0; d < c->dim; ++d) {
            const double a = axis[k][d] * (c->domain_min[d] - pass->centre[d]);
            const double b = axis[k][d] * (c->domain_max[d] - pass->centre[d]);
            q_lo += fmin(a, b);
            q_hi += fmax(a, b);
            wraps |= c->periodic[d] && axis[k][d] != 0.0;
        }
        const double size = pass->bin_size, lo = -0.5 * (pass->lateral_nodes - 1) * size; /* q_k of column 0 */
        int first = 0, last = pass->lateral_nodes - 1;
        if (!wraps)
            nodes_over(q_lo, q_hi, lo, size, pass->lateral_nodes, &first, &last);
        pass->lateral_first[k] = first;
        pass->lateral_count[k] = last - first + 1;
        columns *= pass->lateral_count[k];
    }
    return columns;
}

/* The bin grid of this pass: the nodes of the whole grid (aim_beam) over
 * the domain (lateral_columns) and from one above the shallowest particle
 * under the columns to one below the deepest, the same lattice, so the
 * result is the whole grid's (rounding aside) at a fraction of its nodes:
 * the columns beside the domain and the nodes above and below the material
 * would pass the irradiance on unchanged. */
static int pass_grid(amsph_sim *s, laser_params *pass, int *columns)
{
    *pass = s->laser.params;
    double deepest, minus_shallowest;
    AMSPH_CHECK(depth_extreme(s, 1.0, &deepest));
    AMSPH_CHECK(depth_extreme(s, -1.0, &minus_shallowest));
    int first = 0, last = 0; /* no particle under the columns: one layer above the domain */
    if (deepest > 0.5 * LASER_NOT_UNDER)
        nodes_over(-minus_shallowest, deepest, pass->depth_lo, pass->bin_size, pass->depth_nodes, &first, &last);
    pass->depth_lo = (amsph_real)(pass->depth_lo + first * (double)pass->bin_size);
    pass->depth_nodes = last - first + 1;
    *columns = lateral_columns(&s->config, pass);
    return 0;
}

/* Russell 2018 §3.2.2: volumes onto the bins and Beer-Lambert down the
 * columns in one walk, power back to the particles (kernels/laser.cl). */
static int absorb_volumetric(amsph_sim *s)
{
    amsph_backend *b = s->backend;
    amsph_laser_state *l = &s->laser;
    const int n = s->particles.n;
    laser_params pass;
    int columns;
    AMSPH_CHECK(pass_grid(s, &pass, &columns));
    const amsph_arg grid = amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry);
    const amsph_arg params = amsph_arg_bytes(&pass, sizeof pass);
    AMSPH_CHECK(AMSPH_LAUNCH(b, "laser_absorb_columns", columns, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_DENSITY),
                             field(s, AMSPH_FIELD_MATERIAL), grid, amsph_arg_buffer(s->grid.cell_start),
                             amsph_arg_buffer(s->materials), params, amsph_arg_int(columns),
                             amsph_arg_buffer(l->bin_weight), amsph_arg_buffer(l->bin_power)));
    return AMSPH_LAUNCH(b, "laser_gather_power", n, field(s, AMSPH_FIELD_POSITION),
                        field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_DENSITY),
                        field(s, AMSPH_FIELD_MATERIAL), amsph_arg_int(n), grid,
                        amsph_arg_buffer(s->materials), params, amsph_arg_buffer(l->bin_weight), amsph_arg_buffer(l->bin_power),
                        field(s, AMSPH_FIELD_LASER_POWER), amsph_arg_buffer(s->work));
}

/* Fuchs et al. 2022 Eq. 17 on the faces turned to the beam. */
static int absorb_surface(amsph_sim *s)
{
    const int n = s->particles.n;
    return AMSPH_LAUNCH(s->backend, "laser_surface_absorb", n, field(s, AMSPH_FIELD_POSITION),
                        field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_DENSITY),
                        field(s, AMSPH_FIELD_MATERIAL), amsph_arg_buffer(s->grid.cell), amsph_arg_int(n),
                        amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry),
                        amsph_arg_buffer(s->grid.cell_start), amsph_arg_buffer(s->materials),
                        amsph_arg_bytes(&s->laser.params, sizeof s->laser.params), amsph_arg_real(s->h),
                        field(s, AMSPH_FIELD_LASER_POWER), amsph_arg_buffer(s->work));
}

/* laser_power for the beam at time t with the given power. */
static int absorb_beam(amsph_sim *s, double t, double power)
{
    _Static_assert(sizeof(laser_params) <= sizeof(((amsph_arg *)0)->value.bytes),
                   "laser_params must fit a kernel argument");
    aim_beam(s, t, power);
    const int n = s->particles.n;
    if (s->laser.params.peak_intensity == 0) { /* off: no light anywhere */
        s->laser.absorbed_power = 0.0;
        const int words = n * (int)(amsph_field_bytes(AMSPH_FIELD_LASER_POWER) / 4);
        return AMSPH_LAUNCH(s->backend, "fill_words", words, field(s, AMSPH_FIELD_LASER_POWER),
                            amsph_arg_int(words), amsph_arg_uint(0));
    }
    if (s->config.laser.absorption == AMSPH_ABSORPTION_VOLUMETRIC)
        AMSPH_CHECK(absorb_volumetric(s));
    else
        AMSPH_CHECK(absorb_surface(s));
    return amsph_reduce_sum(s->backend, s->work, n, &s->laser.absorbed_power);
}

/* absorb_beam, timed as the laser's phase of the step. */
static int absorb(amsph_sim *s, double t, double power)
{
    amsph_phase outer;
    AMSPH_CHECK(amsph_sim_phase(s, AMSPH_PHASE_LASER, &outer));
    AMSPH_CHECK(absorb_beam(s, t, power));
    return amsph_sim_phase(s, outer, NULL);
}

int amsph_laser_absorb(amsph_sim *s, double t)
{
    return absorb(s, t, amsph_laser_beam_power(&s->config, t));
}

int amsph_laser_absorb_step(amsph_sim *s, double t0, double t1)
{
    return absorb(s, 0.5 * (t0 + t1), amsph_laser_beam_energy(&s->config, t0, t1) / (t1 - t0));
}
