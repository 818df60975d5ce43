#include "scene.h"

#include <math.h>
#include <string.h>

#include "error.h"

/* Lattice of spacing dx over [lo, hi) per axis, points at cell centres. */
typedef struct {
    int dim;
    double lo[3], dx;
    int count[3];
} lattice;

static lattice lattice_over(int dim, const double lo[3], const double hi[3], double dx)
{
    lattice l = {.dim = dim, .dx = dx, .count = {1, 1, 1}};
    for (int d = 0; d < dim; ++d) {
        l.lo[d] = lo[d];
        const int n = (int)floor((hi[d] - lo[d]) / dx + 0.5);
        l.count[d] = n > 0 ? n : 0;
    }
    return l;
}

static void lattice_point(const lattice *l, long long k, double x[3])
{
    memset(x, 0, 3 * sizeof *x);
    for (int d = 0; d < l->dim; ++d) {
        x[d] = l->lo[d] + ((double)(k % l->count[d]) + 0.5) * l->dx;
        k /= l->count[d];
    }
}

static int inside_box(const double x[3], const double min[3], const double max[3], int dim)
{
    for (int d = 0; d < dim; ++d)
        if (x[d] < min[d] || x[d] > max[d])
            return 0;
    return 1;
}

/* Does x belong to geometry block g? For a box with wall layers the block is
 * the shell outside the box, on the faces that are not open. */
static int block_contains(const amsph_geometry *g, const double x[3], int dim)
{
    double r[3], r2 = 0.0;
    for (int d = 0; d < 3; ++d) {
        r[d] = x[d] - g->center[d];
        r2 += r[d] * r[d];
    }
    switch (g->shape) {
    case AMSPH_SHAPE_BOX:
        return g->layers == 0 ? inside_box(x, g->min, g->max, dim) : !inside_box(x, g->min, g->max, dim);
    case AMSPH_SHAPE_CIRCLE:
    case AMSPH_SHAPE_SPHERE:
        return r2 < g->radius * g->radius;
    case AMSPH_SHAPE_CYLINDER: {
        const double along = r[0] * g->axis[0] + r[1] * g->axis[1] + r[2] * g->axis[2];
        return along >= 0.0 && along < g->length && r2 - along * along < g->radius * g->radius;
    }
    }
    return 0;
}

/* The lattice that covers block g. Boxes are aligned to their corner, round
 * shapes to their centre, so a symmetric shape gets a symmetric lattice. */
static lattice block_lattice(const amsph_geometry *g, int dim, double dx)
{
    double lo[3] = {0}, hi[3] = {0};
    for (int d = 0; d < dim; ++d) {
        if (g->shape == AMSPH_SHAPE_BOX) {
            const double pad = g->layers * dx;
            lo[d] = g->min[d] - (g->open_faces & AMSPH_FACE_BIT(d, 0) ? 0.0 : pad);
            hi[d] = g->max[d] + (g->open_faces & AMSPH_FACE_BIT(d, 1) ? 0.0 : pad);
        } else {
            const double reach = g->shape == AMSPH_SHAPE_CYLINDER ? g->radius + g->length : g->radius;
            const double cells = ceil(reach / dx);
            lo[d] = g->center[d] - cells * dx;
            hi[d] = g->center[d] + cells * dx;
        }
    }
    return lattice_over(dim, lo, hi, dx);
}

static int check_inside_domain(const amsph_case *c, const amsph_geometry *g, const double x[3])
{
    for (int d = 0; d < c->dim; ++d)
        if (x[d] < c->domain_min[d] || x[d] > c->domain_max[d])
            return amsph_fail("%s:%d: geometry block places a particle at %c = %g m, outside the "
                              "domain [%g, %g]; enlarge the domain or move the block",
                              c->path, g->line, "xyz"[d], x[d], c->domain_min[d], c->domain_max[d]);
    return 0;
}

static void set_particle(const amsph_case *c, const amsph_geometry *g, const double x[3],
                         amsph_host_particles *h, int i)
{
    const amsph_material *m = &c->materials[g->material];
    amsph_real *pos = amsph_host_real(h, AMSPH_FIELD_POSITION);
    amsph_real *vel = amsph_host_real(h, AMSPH_FIELD_VELOCITY);
    for (int d = 0; d < 3; ++d) {
        pos[3 * i + d] = (amsph_real)x[d];
        vel[3 * i + d] = (amsph_real)g->velocity[d];
    }
    amsph_host_real(h, AMSPH_FIELD_DENSITY)[i] = (amsph_real)m->density;
    amsph_host_real(h, AMSPH_FIELD_MASS)[i] = (amsph_real)(m->density * pow(c->dx, c->dim));
    ((int *)h->data[AMSPH_FIELD_KIND])[i] = (int)g->kind;
    ((int *)h->data[AMSPH_FIELD_MATERIAL])[i] = g->material;
    ((unsigned *)h->data[AMSPH_FIELD_ID])[i] = (unsigned)i;
    if (h->data[AMSPH_FIELD_TEMPERATURE])
        amsph_host_real(h, AMSPH_FIELD_TEMPERATURE)[i] = (amsph_real)g->temperature;
}

/* Visits the lattice points of block g: counts them, or (h != NULL) checks
 * and stores them from particle index h->n - count onwards. */
static int visit_block(const amsph_case *c, const amsph_geometry *g, amsph_host_particles *h,
                       long long *count)
{
    const lattice l = block_lattice(g, c->dim, c->dx);
    const long long points = (long long)l.count[0] * l.count[1] * l.count[2];
    const long long first = h ? h->n - *count : 0;
    long long found = 0;
    for (long long k = 0; k < points; ++k) {
        double x[3];
        lattice_point(&l, k, x);
        if (!block_contains(g, x, c->dim))
            continue;
        if (h) {
            AMSPH_CHECK(check_inside_domain(c, g, x));
            set_particle(c, g, x, h, (int)(first + found));
        }
        ++found;
    }
    *count = found;
    return 0;
}

/* Hydrostatic initial density of the block's particles [first, h->n): with
 * depth d below the block's highest particle (along -g) plus dx/2,
 *   p = rho0 |g| d,  rho = rho0 + p / c0^2 (the equation of state),
 * and mass rho dx^d, so that the particle volume m / rho stays dx^d. */
static void set_hydrostatic(const amsph_case *c, const amsph_geometry *g, amsph_host_particles *h,
                            int first)
{
    const double gnorm = sqrt(c->gravity[0] * c->gravity[0] + c->gravity[1] * c->gravity[1] +
                              c->gravity[2] * c->gravity[2]);
    const amsph_material *m = &c->materials[g->material];
    if (gnorm == 0.0 || m->sound_speed <= 0.0)
        return;
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
    double top = -INFINITY;
    for (int i = first; i < h->n; ++i) {
        double height = 0.0; /* along -g */
        for (int d = 0; d < 3; ++d)
            height -= x[3 * i + d] * c->gravity[d] / gnorm;
        top = fmax(top, height);
    }
    for (int i = first; i < h->n; ++i) {
        double height = 0.0;
        for (int d = 0; d < 3; ++d)
            height -= x[3 * i + d] * c->gravity[d] / gnorm;
        const double depth = top + 0.5 * c->dx - height;
        const double rho = m->density + m->density * gnorm * depth / (m->sound_speed * m->sound_speed);
        amsph_host_real(h, AMSPH_FIELD_DENSITY)[i] = (amsph_real)rho;
        /* the lattice volume dx^d holds the compressed fluid: m = rho dx^d */
        amsph_host_real(h, AMSPH_FIELD_MASS)[i] = (amsph_real)(rho * pow(c->dx, c->dim));
    }
}

static int add_block(const amsph_case *c, const amsph_geometry *g, amsph_host_particles *h)
{
    long long count = 0;
    AMSPH_CHECK(visit_block(c, g, NULL, &count));
    if (count == 0)
        return amsph_fail("%s:%d: geometry block holds no particle at dx = %g m; make it larger "
                          "than dx",
                          c->path, g->line, c->dx);
    if (h->n + count > 2147483647LL)
        return amsph_fail("%s:%d: the scene would exceed 2^31 particles", c->path, g->line);
    const int first = h->n;
    AMSPH_CHECK(amsph_host_resize(h, h->n + (int)count));
    AMSPH_CHECK(visit_block(c, g, h, &count));
    if (g->hydrostatic)
        set_hydrostatic(c, g, h, first);
    return 0;
}

static int temperature_given(const amsph_case *c)
{
    int given = 0;
    for (int k = 0; k < c->n_geometry; ++k)
        given += c->geometry[k].has_temperature;
    return given;
}

int amsph_scene_build(const amsph_case *c, amsph_host_particles *h)
{
    static const amsph_field_id always[] = {
        AMSPH_FIELD_POSITION, AMSPH_FIELD_VELOCITY, AMSPH_FIELD_DENSITY, AMSPH_FIELD_PRESSURE,
        AMSPH_FIELD_MASS,     AMSPH_FIELD_KIND,     AMSPH_FIELD_MATERIAL, AMSPH_FIELD_ID};
    memset(h, 0, sizeof *h);
    for (size_t k = 0; k < sizeof always / sizeof always[0]; ++k)
        AMSPH_CHECK(amsph_host_add_field(h, always[k]));
    const int with_temperature = temperature_given(c);
    if (with_temperature) {
        if (with_temperature != c->n_geometry)
            for (int k = 0; k < c->n_geometry; ++k)
                if (!c->geometry[k].has_temperature)
                    return amsph_fail("%s:%d: this geometry block has no 'temperature' while others "
                                      "do; give every block an initial temperature",
                                      c->path, c->geometry[k].line);
        AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_TEMPERATURE));
    }
    for (int k = 0; k < c->n_geometry; ++k)
        AMSPH_CHECK(add_block(c, &c->geometry[k], h));
    return 0;
}
