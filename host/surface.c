#include "surface.h"

#include <math.h>
#include <string.h>

#include "error.h"
#include "material.h"

#define PI 3.14159265358979323846

int amsph_surface_setup(amsph_sim *s, amsph_host_particles *h)
{
    static const amsph_field_id fields[] = {AMSPH_FIELD_SURFACE_SHEPARD, AMSPH_FIELD_NORMAL,
                                            AMSPH_FIELD_UNIT_NORMAL, AMSPH_FIELD_NORMAL_WEIGHT,
                                            AMSPH_FIELD_RAW_CURVATURE, AMSPH_FIELD_CURVATURE,
                                            AMSPH_FIELD_SURFACE_TENSION};
    static const amsph_field_id wetting_fields[] = {AMSPH_FIELD_WET_FRACTION, AMSPH_FIELD_WET_COLOUR,
                                                    AMSPH_FIELD_WET_NORMAL};
    const amsph_surface_settings *st = &s->config.surface;
    surface_params *p = &s->surface;
    memset(p, 0, sizeof *p);
    const double h_st = st->h_over_dx * s->config.dx;
    p->h = (amsph_real)h_st;
    p->normal_cutoff = (amsph_real)st->normal_cutoff;
    p->max_curvature = (amsph_real)(0.5 / h_st);
    p->min_shepard = (amsph_real)st->min_shepard;
    p->interface_viscosity = (amsph_real)st->interface_viscosity;
    /* cells are s->support / GRID_CELLS_PER_SUPPORT wide (wider with fluid.smoothing_length: volume,
     * host/sim.c); the surface support needs at most this many */
    p->reach = (int)ceil(amsph_support_over_h(s->config.kernel) * h_st / s->support * GRID_CELLS_PER_SUPPORT - 1e-9);
    p->tension = st->tension;
    p->reaction = st->tension && s->config.grains.enabled;
    p->marangoni = st->marangoni;
    p->form = st->tension ? st->tension_form : TENSION_FORM_CSF;
    for (int m = 0; m < s->config.n_materials; ++m) {
        const amsph_material *mat = &s->config.materials[m];
        p->temperature |= mat->surface_tension_slope != 0 || mat->surfactant_excess > 0;
        p->wetting |= mat->contact_angle > 0;
    }
    p->temperature |= p->marangoni;
    for (int m = 0; m < s->config.n_materials; ++m)
        p->gas |= s->config.materials[m].phase == AMSPH_MATERIAL_GAS;
    /* the solid colour of a melting solid follows its temperature, where there is one */
    p->temperature |= p->wetting && h->data[AMSPH_FIELD_TEMPERATURE] != NULL;
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; ++k)
        AMSPH_CHECK(amsph_host_add_field(h, fields[k]));
    for (size_t k = 0; k < sizeof wetting_fields / sizeof wetting_fields[0] && p->wetting; ++k)
        AMSPH_CHECK(amsph_host_add_field(h, wetting_fields[k]));
    return 0;
}

static int check_grid(const amsph_sim *s)
{
    const grid_geometry *g = &s->grid.geometry;
    const int span = 2 * s->surface.reach + 1;
    for (int d = 0; d < s->config.dim; ++d)
        if (g->periodic[d] && g->ncell[d] < span)
            return amsph_bad_input("the surface terms' support (%g m) needs a periodic direction "
                                   "of at least %d cells of %g m; direction %d has %d: widen the "
                                   "domain or lower surface.h_over_dx",
                                   amsph_support_over_h(s->config.kernel) * s->surface.h, span,
                                   (double)g->cell_size, d, g->ncell[d]);
    return 0;
}

int amsph_surface_allocate(amsph_sim *s)
{
    AMSPH_CHECK(check_grid(s));
    const grid_geometry *g = &s->grid.geometry;
    surface_params *p = &s->surface;
    /* whole blocks of `reach` cells; the last takes the remainder (kernels/surface.cl) */
    for (int d = 0; d < 3; ++d)
        p->blocks[d] = g->ncell[d] / p->reach > 1 ? g->ncell[d] / p->reach : 1;
    p->near_blocks = SURFACE_NEAR_BLOCKS;
    for (int k = 0; k < 2; ++k)
        AMSPH_CHECK(amsph_buffer_alloc(s->backend, (size_t)surface_block_count(p) * sizeof(int),
                                       &s->surface_blocks[k]));
    for (int k = 0; k < 2 && p->form == TENSION_FORM_CONSERVATIVE; ++k)
        AMSPH_CHECK(amsph_buffer_alloc(s->backend, (size_t)s->particles.capacity * 4 * sizeof(amsph_real),
                                       &s->tension_share[k]));
    return amsph_buffer_alloc(s->backend, sizeof(int), &s->plain_liquid);
}

static amsph_arg field(amsph_sim *s, amsph_field_id f)
{
    return amsph_arg_buffer(s->particles.field[f]);
}

/* The temperature buffer where sigma(T) or the Marangoni force reads it;
 * otherwise any buffer stands in, unread (surface_params.temperature = 0). */
static amsph_arg temperature(amsph_sim *s)
{
    return field(s, s->surface.temperature ? AMSPH_FIELD_TEMPERATURE : AMSPH_FIELD_CURVATURE);
}

/* The reaction of the surface tension on the grains (kernels/surface.cl,
 * surface_grain_reaction): the pull of the liquid on every solid particle,
 * the sums of the pulls and of their weights, and the grains' share. */
static int grain_reaction(amsph_sim *s, amsph_arg cells, amsph_arg grid, amsph_arg cell_start, amsph_arg away,
                          amsph_arg params)
{
    amsph_backend *b = s->backend;
    const int n = s->particles.n;
    AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_contact_pull", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_MATERIAL), field(s, AMSPH_FIELD_SURFACE_SHEPARD),
                             field(s, AMSPH_FIELD_NORMAL), field(s, AMSPH_FIELD_UNIT_NORMAL),
                             field(s, AMSPH_FIELD_NORMAL_WEIGHT), field(s, AMSPH_FIELD_SURFACE_TENSION), cells,
                             amsph_arg_int(n), grid, cell_start,
                             amsph_arg_buffer(s->grid.fluid_count), amsph_arg_buffer(s->materials), away, params,
                             amsph_arg_buffer(s->contact_pull)));
    double sum[4] = {0.0, 0.0, 0.0, 0.0}; /* the net pull (3) and the solids' weight */
    for (int c = 0; c < 4; ++c) {
        if (c >= s->config.dim && c < 3)
            continue;
        AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_pull_component", n, amsph_arg_buffer(s->contact_pull), amsph_arg_int(n),
                                 amsph_arg_int(c), amsph_arg_buffer(s->work)));
        AMSPH_CHECK(amsph_reduce_sum(b, s->work, n, &sum[c]));
    }
    const double per_weight = sum[3] > 0.0 ? -1.0 / sum[3] : 0.0;
    return AMSPH_LAUNCH(b, "surface_grain_reaction", n, field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MASS),
                        amsph_arg_buffer(s->contact_pull), amsph_arg_int(n), amsph_arg_real(sum[0] * per_weight),
                        amsph_arg_real(sum[1] * per_weight), amsph_arg_real(sum[2] * per_weight),
                        field(s, AMSPH_FIELD_ACCELERATION));
}

/* The passes of the conservative form's share (kernels/surface.cl
 * surface_share). On young_laplace_gas_2d (quintic, h_st = 1.2 dx) the
 * droplet's surface clumped with one pass (closest pair 0.72 dx at 10 s,
 * largest speed 5.4e-3 m/s) and came to rest with three (0.83 dx and
 * 8.8e-4 m/s, as the CSF force alone: 0.82 dx, 6.5e-4 m/s); BENCHMARKS.md. */
#define TENSION_SHARE_PASSES 3

/* The conservative form's share, smoothed TENSION_SHARE_PASSES times
 * between the two tension_share buffers and added to the acceleration. */
static int share_tension(amsph_sim *s, amsph_arg cells, amsph_arg grid, amsph_arg cell_start, amsph_arg params)
{
    for (int k = 0; k < TENSION_SHARE_PASSES; ++k)
        AMSPH_CHECK(AMSPH_LAUNCH(s->backend, "surface_share", s->particles.n, field(s, AMSPH_FIELD_POSITION),
                                 field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_MASS), field(s, AMSPH_FIELD_KIND),
                                 field(s, AMSPH_FIELD_MATERIAL), amsph_arg_buffer(s->materials), cells,
                                 amsph_arg_int(s->particles.n), grid, cell_start, params,
                                 amsph_arg_buffer(s->tension_share[k % 2]),
                                 amsph_arg_int(k == TENSION_SHARE_PASSES - 1),
                                 amsph_arg_buffer(s->tension_share[(k + 1) % 2]), field(s, AMSPH_FIELD_ACCELERATION)));
    return 0;
}

/* Each block's distance from the nearest liquid, in blocks (kernels/surface.cl,
 * surface_blocks_*): the liquid counted per block, then spread along each
 * axis in turn between the two block buffers; *away is the one that ends
 * with the distances. s->plain_liquid counts the liquid particles without
 * a contact angle; near_blocks past its default (a test's pass over every
 * particle) starts it at 1, so that every particle takes a normal. */
static int find_liquid_blocks(amsph_sim *s, amsph_arg grid, amsph_arg params, amsph_buffer **away)
{
    amsph_backend *b = s->backend;
    const int n = s->particles.n;
    const int blocks = surface_block_count(&s->surface);
    amsph_buffer *from = s->surface_blocks[0], *to = s->surface_blocks[1];
    AMSPH_CHECK(AMSPH_LAUNCH(b, "fill_words", blocks, amsph_arg_buffer(from), amsph_arg_int(blocks), amsph_arg_uint(0)));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "fill_words", 1, amsph_arg_buffer(s->plain_liquid), amsph_arg_int(1),
                             amsph_arg_uint(s->surface.near_blocks > SURFACE_NEAR_BLOCKS)));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_blocks_mark", n, field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MATERIAL),
                             amsph_arg_buffer(s->materials), amsph_arg_buffer(s->grid.cell), amsph_arg_int(n), grid,
                             params, amsph_arg_buffer(from), amsph_arg_buffer(s->plain_liquid)));
    for (int axis = 0; axis < s->config.dim; ++axis) {
        AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_blocks_spread", blocks, amsph_arg_buffer(from), amsph_arg_int(axis),
                                 amsph_arg_int(axis == 0), grid, params, amsph_arg_buffer(to)));
        amsph_buffer *swap = from;
        from = to;
        to = swap;
    }
    *away = from;
    return 0;
}

/* A wetting field's buffer; the work buffer, which the kernels do not
 * touch then, where no material has a contact angle. */
static amsph_arg wetting_field(amsph_sim *s, amsph_field_id f)
{
    return s->surface.wetting ? field(s, f) : amsph_arg_buffer(s->work);
}

/* The curvature pass (kernels/surface.cl, surface_curvature) from the unit
 * normals and normal weights the particles hold, into raw_curvature; grid,
 * params and away as amsph_surface_forces builds them. */
static int curvature_pass(amsph_sim *s, amsph_arg grid, amsph_arg params, amsph_arg away)
{
    const int n = s->particles.n;
    return AMSPH_LAUNCH(s->backend, "surface_curvature", n, field(s, AMSPH_FIELD_POSITION),
                        field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_MASS),
                        field(s, AMSPH_FIELD_UNIT_NORMAL), field(s, AMSPH_FIELD_NORMAL_WEIGHT),
                        field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MATERIAL), amsph_arg_buffer(s->materials),
                        amsph_arg_buffer(s->grid.cell), amsph_arg_int(n), grid, amsph_arg_buffer(s->grid.cell_start),
                        away, params, field(s, AMSPH_FIELD_RAW_CURVATURE));
}

int amsph_surface_curvature(amsph_sim *s)
{
    const amsph_arg grid = amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry);
    const amsph_arg params = amsph_arg_bytes(&s->surface, sizeof s->surface);
    amsph_buffer *away;
    AMSPH_CHECK(find_liquid_blocks(s, grid, params, &away));
    return curvature_pass(s, grid, params, amsph_arg_buffer(away));
}

int amsph_surface_forces(amsph_sim *s)
{
    amsph_backend *b = s->backend;
    const int n = s->particles.n;
    const amsph_arg grid = amsph_arg_bytes(&s->grid.geometry, sizeof s->grid.geometry);
    const amsph_arg cells = amsph_arg_buffer(s->grid.cell);
    const amsph_arg cell_start = amsph_arg_buffer(s->grid.cell_start);
    const amsph_arg materials = amsph_arg_buffer(s->materials);
    const amsph_arg params = amsph_arg_bytes(&s->surface, sizeof s->surface);
    const amsph_arg plain = amsph_arg_buffer(s->plain_liquid);
    amsph_buffer *away_buffer;
    AMSPH_CHECK(find_liquid_blocks(s, grid, params, &away_buffer));
    const amsph_arg away = amsph_arg_buffer(away_buffer);
    AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_shepard", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_MASS),
                             field(s, AMSPH_FIELD_MATERIAL), cells, amsph_arg_int(n), grid, cell_start,
                             amsph_arg_buffer(s->grid.fluid_count), field(s, AMSPH_FIELD_KIND), materials, away,
                             plain, params, field(s, AMSPH_FIELD_SURFACE_SHEPARD),
                             wetting_field(s, AMSPH_FIELD_WET_FRACTION)));
    if (s->surface.wetting) /* the solids' wet colour (kernels/surface.cl) */
        AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_wet_colour", n, field(s, AMSPH_FIELD_POSITION),
                                 field(s, AMSPH_FIELD_KIND), cells, amsph_arg_int(n), grid, cell_start, params,
                                 field(s, AMSPH_FIELD_WET_FRACTION), field(s, AMSPH_FIELD_WET_COLOUR)));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_normal", n, field(s, AMSPH_FIELD_POSITION),
                             field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_MASS),
                             field(s, AMSPH_FIELD_SURFACE_SHEPARD), field(s, AMSPH_FIELD_KIND),
                             field(s, AMSPH_FIELD_MATERIAL), cells, amsph_arg_int(n), grid, cell_start, materials,
                             away, plain, wetting_field(s, AMSPH_FIELD_WET_COLOUR), params,
                             field(s, AMSPH_FIELD_NORMAL), field(s, AMSPH_FIELD_UNIT_NORMAL),
                             field(s, AMSPH_FIELD_NORMAL_WEIGHT), wetting_field(s, AMSPH_FIELD_WET_NORMAL)));
    if (s->surface.wetting)
        AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_wetting", n, field(s, AMSPH_FIELD_POSITION),
                                 field(s, AMSPH_FIELD_DENSITY), field(s, AMSPH_FIELD_MASS),
                                 field(s, AMSPH_FIELD_WET_NORMAL), field(s, AMSPH_FIELD_NORMAL_WEIGHT),
                                 field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MATERIAL),
                                 temperature(s), amsph_arg_buffer(s->materials), cells,
                                 amsph_arg_int(n), grid, cell_start, params,
                                 field(s, AMSPH_FIELD_UNIT_NORMAL)));
    AMSPH_CHECK(curvature_pass(s, grid, params, away));
    AMSPH_CHECK(AMSPH_LAUNCH(b, "surface_force", n, field(s, AMSPH_FIELD_POSITION),
                        field(s, AMSPH_FIELD_VELOCITY), field(s, AMSPH_FIELD_DENSITY),
                        field(s, AMSPH_FIELD_MASS), temperature(s),
                        field(s, AMSPH_FIELD_KIND), field(s, AMSPH_FIELD_MATERIAL),
                        field(s, AMSPH_FIELD_SURFACE_SHEPARD), field(s, AMSPH_FIELD_NORMAL),
                        field(s, AMSPH_FIELD_UNIT_NORMAL), field(s, AMSPH_FIELD_NORMAL_WEIGHT),
                        field(s, AMSPH_FIELD_RAW_CURVATURE), cells, amsph_arg_int(n), grid,
                        cell_start, amsph_arg_buffer(s->materials), params,
                        field(s, AMSPH_FIELD_ACCELERATION), field(s, AMSPH_FIELD_CURVATURE),
                        field(s, AMSPH_FIELD_SURFACE_TENSION),
                        amsph_arg_buffer(s->surface.reaction ? s->contact_pull : s->work),
                        amsph_arg_buffer(s->surface.form == TENSION_FORM_CONSERVATIVE ? s->tension_share[0] : s->work)));
    if (s->surface.form == TENSION_FORM_CONSERVATIVE)
        AMSPH_CHECK(share_tension(s, cells, grid, cell_start, params));
    return s->surface.reaction ? grain_reaction(s, cells, grid, cell_start, away, params) : 0;
}

/* The interface viscosity (Fuchs et al. 2022 Eqs. 31-32) is Monaghan's
 * artificial viscosity of factor alpha_a = alpha0 h_st |n_a|, explicit in
 * time. As a kinematic viscosity nu = alpha h_st c / (2 (d + 2)) (Monaghan
 * 2005, Rep. Prog. Phys. 68: alpha h c / 8 in 2D, / 10 in 3D) it takes
 * the fluid's viscous limit dt <= 0.125 h_st^2 / nu (Morris et al. 1997),
 * with the largest colour gradient |n| of any particle (the liquid's where
 * every liquid has a contact angle, as only liquids then take a normal;
 * beside a liquid without one, a wall's free face may reach more) and the
 * fastest sound speed c0 of the materials that carry tension. Without it
 * a sessile cap at alpha0 = 14.4 and 8.5 dx ran at four times this dt and
 * its surface jittered at 0.05 m/s (BENCHMARKS.md). */
static int interface_viscosity_dt(amsph_sim *s, double c0, double *dt, const char **limit)
{
    const surface_params *p = &s->surface;
    if (p->interface_viscosity <= 0)
        return 0;
    double largest_normal = 0.0;
    AMSPH_CHECK(amsph_sim_max_norm(s, AMSPH_FIELD_NORMAL, &largest_normal));
    const double h = p->h, alpha = p->interface_viscosity * h * largest_normal;
    const double nu = alpha * h * c0 / (2.0 * (s->config.dim + 2));
    if (nu > 0.0)
        amsph_lower_dt(dt, limit, 0.125 * h * h / nu, "interface viscosity");
    return 0;
}

int amsph_surface_dt(amsph_sim *s, double *dt, const char **limit)
{
    double sigma = 0.0, rho = INFINITY, c0 = 0.0;
    AMSPH_CHECK(amsph_reduce_max(s->backend, s->particles.field[AMSPH_FIELD_SURFACE_TENSION],
                                 s->particles.n, &sigma));
    for (int m = 0; m < s->config.n_materials; ++m) {
        const amsph_material *mat = &s->config.materials[m];
        double lowest, highest;
        amsph_material_density_bounds(mat, &lowest, &highest);
        if (mat->phase != AMSPH_MATERIAL_GAS) { /* a gas carries no tension */
            rho = fmin(rho, lowest);
            c0 = fmax(c0, mat->sound_speed);
        }
    }
    AMSPH_CHECK(interface_viscosity_dt(s, c0, dt, limit));
    const double h = s->h;
    if (sigma > 0.0)
        amsph_lower_dt(dt, limit, 0.25 * sqrt(rho * h * h * h / (2.0 * PI * sigma)), "capillary");
    return 0;
}
