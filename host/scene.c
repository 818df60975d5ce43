#include "scene.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "material.h"
#include "powder.h"
#define AMSPH_SHARED_REAL amsph_real
#include "grain_params.h"

/* Lattice of spacing dx over [lo, hi) per axis, points at cell centres. */
typedef struct {
    int dim;
    double lo[3], dx;
    int count[3];
    double points; /* count[0] count[1] count[2]; infinite where an axis would pass INT_MAX */
} lattice;

/* A block whose lattice has more points than this is refused before it is
 * walked: 2^34, eight times the particles a scene may hold (a shell of
 * wall layers or a long cylinder walks more points than it places). */
#define LATTICE_POINTS_MAX 17179869184.0

static lattice lattice_over(int dim, const double lo[3], const double hi[3], double dx)
{
    lattice l = {.dim = dim, .dx = dx, .count = {1, 1, 1}, .points = 1.0};
    for (int d = 0; d < dim; ++d) {
        l.lo[d] = lo[d];
        const double n = fmax(floor((hi[d] - lo[d]) / dx + 0.5), 0.0);
        l.count[d] = n <= INT_MAX ? (int)n : INT_MAX;
        l.points *= n <= INT_MAX ? n : INFINITY;
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

/* Does x belong to geometry block g (bed: its grains, for a powder bed)?
 * For a box with wall layers the block is the shell outside the box, on
 * the faces that are not open. */
static int block_contains(const amsph_geometry *g, const amsph_powder *bed, const double x[3],
                          int dim)
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
    case AMSPH_SHAPE_POWDER_BED:
        return amsph_powder_contains(bed, x);
    }
    return 0;
}

/* The lattice that covers block g. Boxes and powder beds are aligned to
 * their corner (a bed on a box's lattice when its region starts on the
 * box's face), round shapes to their centre, so a symmetric shape gets a
 * symmetric lattice. */
static lattice block_lattice(const amsph_geometry *g, int dim, double dx)
{
    double lo[3] = {0}, hi[3] = {0};
    for (int d = 0; d < dim; ++d) {
        if (g->shape == AMSPH_SHAPE_BOX || g->shape == AMSPH_SHAPE_POWDER_BED) {
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
            return amsph_bad_input("%s:%d: geometry block places a particle at %c = %g m, outside the "
                                   "domain [%g, %g]; enlarge the domain or move the block",
                                   c->path, g->line, "xyz"[d], x[d], c->domain_min[d], c->domain_max[d]);
    return 0;
}

/* A particle's temperature at t = 0: its block's, or the prescribed history's. */
static double initial_temperature(const amsph_case *c, const amsph_geometry *g)
{
    return c->temperature_history.enabled ? amsph_temperature_history_at(&c->temperature_history, 0.0)
                                          : g->temperature;
}

/* Density rho0(T) at the initial temperature and mass rho0 dx^d: each
 * particle fills the lattice volume dx^d. `grain` is the grain index of a
 * grain particle (the `grain` field, present when the scene has grains). */
static void set_particle(const amsph_case *c, const amsph_geometry *g, const double x[3], int grain,
                         amsph_host_particles *h, int i)
{
    const double temperature = initial_temperature(c, g);
    const double rho0 = amsph_material_density(&c->materials[g->material], temperature);
    amsph_real *pos = amsph_host_real(h, AMSPH_FIELD_POSITION);
    amsph_real *vel = amsph_host_real(h, AMSPH_FIELD_VELOCITY);
    for (int d = 0; d < 3; ++d) {
        pos[3 * i + d] = (amsph_real)x[d];
        vel[3 * i + d] = (amsph_real)g->velocity[d];
    }
    amsph_host_real(h, AMSPH_FIELD_DENSITY)[i] = (amsph_real)rho0;
    amsph_host_real(h, AMSPH_FIELD_MASS)[i] = (amsph_real)(rho0 * pow(c->dx, c->dim));
    ((int *)h->data[AMSPH_FIELD_KIND])[i] = (int)g->kind;
    ((int *)h->data[AMSPH_FIELD_MATERIAL])[i] = g->material;
    ((unsigned *)h->data[AMSPH_FIELD_ID])[i] = (unsigned)i;
    if (h->data[AMSPH_FIELD_TEMPERATURE])
        amsph_host_real(h, AMSPH_FIELD_TEMPERATURE)[i] = (amsph_real)temperature;
    if (h->data[AMSPH_FIELD_GRAIN])
        ((int *)h->data[AMSPH_FIELD_GRAIN])[i] = g->kind == AMSPH_KIND_GRAIN ? grain : GRAIN_NONE;
}

/* A `fill` block leaves out its lattice points closer than this many dx to
 * a particle placed before it: on a common lattice it skips exactly the
 * occupied points, on an offset one those nearer than three quarters of a
 * spacing. */
#define FILL_CLEARANCE 0.75

/* A point a `fill` block leaves out must lie within this many dx of the
 * particle it makes way for: a lattice offset by a fraction f < 0.75 of a
 * spacing from the one before it skips a whole layer along a flat face and
 * leaves a gap of (1 + f) dx there (the 3D sessile cap's wall, 0.71 dx
 * off, started its liquid 1.7 dx above the wall and 12% short). */
#define FILL_LATTICE_MISMATCH 0.1

/* Any other block may not place a particle closer than this many dx to one
 * placed before it: blocks that overlap would put particles on top of each
 * other (twice the mass there, and no force between a coincident pair), and
 * the run's spacing guard stops below 0.3 dx by default. Blocks that meet
 * on lattices offset by half a spacing (0.5 dx) pass. */
#define OVERLAP_CLEARANCE 0.3

/* The particles placed so far, for the `fill`, overlap and contact tests:
 * bucketed by a hash of their cell of dx (cells are not bounded by the
 * domain's size at dx: two small blocks far apart in a large domain take
 * memory for their particles only). Cells that share a bucket are told
 * apart by the distance test of occupied_find. */
typedef struct {
    int dim;
    double lo[3], size;
    unsigned long long buckets; /* a power of two */
    int *start;    /* buckets + 1 offsets into x and index */
    amsph_real *x; /* their positions, by bucket (a copy: placing the block resizes h) */
    int *index;    /* their indices in h, by bucket */
} occupied;

/* Cell coordinates of x, in cells of o->size from o->lo. */
static void occupied_cell(const occupied *o, const double x[3], long long cc[3])
{
    for (int d = 0; d < 3; ++d)
        cc[d] = d < o->dim ? (long long)floor((x[d] - o->lo[d]) / o->size) : 0;
}

/* The bucket of cell cc (a 64-bit mix of its coordinates). */
static unsigned long long occupied_bucket(const occupied *o, const long long cc[3])
{
    unsigned long long key = 0x9e3779b97f4a7c15ULL;
    for (int d = 0; d < 3; ++d) {
        key ^= (unsigned long long)cc[d] + 0x9e3779b97f4a7c15ULL + (key << 6) + (key >> 2);
        key ^= key >> 31;
        key *= 0xbf58476d1ce4e5b9ULL;
    }
    return (key ^ (key >> 29)) & (o->buckets - 1);
}

static unsigned long long bucket_of_point(const occupied *o, const double x[3])
{
    long long cc[3];
    occupied_cell(o, x, cc);
    return occupied_bucket(o, cc);
}

static void occupied_free(occupied *o)
{
    free(o->start);
    free(o->x);
    free(o->index);
}

/* Buckets the first n particles of h (a counting sort by bucket; twice as
 * many buckets as particles). */
static int occupied_build(const amsph_case *c, const amsph_host_particles *h, int n, occupied *o)
{
    memset(o, 0, sizeof *o);
    o->dim = c->dim;
    o->size = c->dx;
    for (int d = 0; d < 3; ++d)
        o->lo[d] = c->domain_min[d];
    o->buckets = 1;
    while (o->buckets < 2ULL * (unsigned long long)n)
        o->buckets *= 2;
    const amsph_real *x_h = amsph_host_real(h, AMSPH_FIELD_POSITION);
    o->start = calloc((size_t)o->buckets + 1, sizeof *o->start);
    o->x = malloc((size_t)(n > 0 ? n : 1) * 3 * sizeof *o->x);
    o->index = malloc((size_t)(n > 0 ? n : 1) * sizeof *o->index);
    int *next = malloc((size_t)o->buckets * sizeof *next);
    if (!o->start || !o->x || !o->index || !next) {
        free(next);
        occupied_free(o);
        return amsph_fail("out of host memory bucketing the %d particles placed", n);
    }
    for (int i = 0; i < n; ++i) {
        const double x[3] = {x_h[3 * i], x_h[3 * i + 1], x_h[3 * i + 2]};
        ++o->start[bucket_of_point(o, x) + 1];
    }
    for (unsigned long long k = 0; k < o->buckets; ++k)
        o->start[k + 1] += o->start[k];
    memcpy(next, o->start, (size_t)o->buckets * sizeof *next);
    for (int i = 0; i < n; ++i) {
        const double x[3] = {x_h[3 * i], x_h[3 * i + 1], x_h[3 * i + 2]};
        const int slot = next[bucket_of_point(o, x)]++;
        for (int d = 0; d < 3; ++d)
            o->x[3 * slot + d] = x_h[3 * i + d];
        o->index[slot] = i;
    }
    free(next);
    return 0;
}

/* Which particles count in occupied_find: partner(ctx, j) for particle j of h. */
typedef int (*occupied_partner)(const void *ctx, int j);

/* The cells that a ball of radius `reach` about x touches, first[d] to
 * last[d] along each axis (widened by 1e-9 of a cell against rounding):
 * one or two along an axis for a reach under half a cell, so a point on
 * the lattice of the particles before it looks into one bucket, not 27. */
static void occupied_reach(const occupied *o, const double x[3], double reach, long long first[3],
                           long long last[3])
{
    const double margin = reach + 1e-9 * o->size;
    for (int d = 0; d < 3; ++d) {
        first[d] = d < o->dim ? (long long)floor((x[d] - margin - o->lo[d]) / o->size) : 0;
        last[d] = d < o->dim ? (long long)floor((x[d] + margin - o->lo[d]) / o->size) : 0;
    }
}

/* The slot in o of the nearest particle within `clearance` dx of x that
 * `partner` accepts (any, without one), or -1. */
static int occupied_nearest(const occupied *o, const double x[3], double clearance, occupied_partner partner,
                            const void *ctx)
{
    double nearest2 = clearance * clearance * o->size * o->size;
    int nearest = -1;
    long long first[3], last[3];
    occupied_reach(o, x, clearance * o->size, first, last);
    long long k[3];
    for (k[2] = first[2]; k[2] <= last[2]; ++k[2])
        for (k[1] = first[1]; k[1] <= last[1]; ++k[1])
            for (k[0] = first[0]; k[0] <= last[0]; ++k[0]) {
                const unsigned long long bucket = occupied_bucket(o, k);
                for (int j = o->start[bucket]; j < o->start[bucket + 1]; ++j) {
                    const amsph_real *y = o->x + 3 * j;
                    double r2 = 0.0;
                    for (int d = 0; d < o->dim; ++d)
                        r2 += (x[d] - y[d]) * (x[d] - y[d]);
                    if (r2 < nearest2 && (!partner || partner(ctx, o->index[j]))) {
                        nearest2 = r2;
                        nearest = j;
                    }
                }
            }
    return nearest;
}

/* The index in h of the nearest particle within `clearance` dx of x that
 * `partner` accepts, or -1. */
static int occupied_find(const occupied *o, const double x[3], double clearance, occupied_partner partner,
                         const void *ctx)
{
    const int slot = occupied_nearest(o, x, clearance, partner, ctx);
    return slot >= 0 ? o->index[slot] : -1;
}

/* A lattice point of block g that lies on a particle of the blocks before it. */
static int overlap_error(const amsph_case *c, const amsph_geometry *g, const double x[3])
{
    return amsph_bad_input("%s:%d: geometry block places a particle at (%g, %g, %g) m within %g dx of a "
                           "particle of a block before it: the blocks overlap; move or shrink one, or "
                           "give this one 'fill: true' to fill only the space the others leave",
                           c->path, g->line, x[0], x[1], x[2], OVERLAP_CLEARANCE);
}

/* The shift y - x that takes lattice point x onto particle y, to a
 * thousandth of dx (clear of y's rounding); returns its length in dx. */
static double shift_onto(const amsph_case *c, const double x[3], const amsph_real y[3], double shift[3])
{
    double r2 = 0.0;
    for (int d = 0; d < 3; ++d) {
        shift[d] = d < c->dim ? round((y[d] - x[d]) / c->dx * 1e3) * 1e-3 * c->dx + 0.0 : 0.0;
        r2 += shift[d] * shift[d];
    }
    return sqrt(r2) / c->dx;
}

/* A `fill` block's lattice point x that a particle placed before it makes
 * way for without lying on it: `shift` (offset dx long) away. */
static int fill_offset_error(const amsph_case *c, const amsph_geometry *g, const double x[3],
                             const double shift[3], double offset)
{
    return amsph_bad_input("%s:%d: this fill block's lattice is offset from that of a block before it: "
                           "its point (%g, %g, %g) m lies %.2f dx from a particle there, so the fill "
                           "would leave a gap of up to %.2f dx along their common faces; move this block "
                           "by (%.3g, %.3g, %.3g) m (or the other the opposite way) so the lattices coincide",
                           c->path, g->line, x[0], x[1], x[2], offset, 1.0 + offset, shift[0], shift[1], shift[2]);
}

/* Visits the lattice points of block g (a `fill` block: those away from the
 * particles in `before`, on their lattice; any other block: an error where
 * one lies on them):
 * counts them, or (h != NULL) checks and stores them from particle index
 * h->n - count onwards. A block of kind grain is grain first_grain; a powder
 * bed's grain i is first_grain + i. */
static int visit_block(const amsph_case *c, const amsph_geometry *g, const amsph_powder *bed,
                       const occupied *before, int first_grain, amsph_host_particles *h, long long *count)
{
    const lattice l = block_lattice(g, c->dim, c->dx);
    if (l.points > LATTICE_POINTS_MAX)
        return amsph_bad_input("%s:%d: geometry block spans %.3g lattice points at dx = %g m (at most %.3g); "
                               "make dx larger or the block smaller",
                               c->path, g->line, l.points, c->dx, LATTICE_POINTS_MAX);
    const long long points = (long long)l.points;
    const long long first = h ? h->n - *count : 0;
    long long found = 0;
    for (long long k = 0; k < points; ++k) {
        double x[3];
        lattice_point(&l, k, x);
        if (!block_contains(g, bed, x, c->dim))
            continue;
        const int taken = before ? occupied_nearest(before, x, g->fill ? FILL_CLEARANCE : OVERLAP_CLEARANCE,
                                                    NULL, NULL)
                                 : -1;
        if (taken >= 0) {
            if (!g->fill)
                return overlap_error(c, g, x);
            double shift[3];
            const double offset = shift_onto(c, x, before->x + 3 * taken, shift);
            if (offset > FILL_LATTICE_MISMATCH)
                return fill_offset_error(c, g, x, shift, offset);
            continue;
        }
        AMSPH_CHECK(check_inside_domain(c, g, x));
        if (h) {
            set_particle(c, g, x, first_grain + (bed ? amsph_powder_grain_at(bed, x) : 0), h,
                         (int)(first + found));
        }
        ++found;
    }
    *count = found;
    return 0;
}

/* A particle of a hydrostatic block, for the column pass below. */
typedef struct {
    double across[2]; /* coordinates across g, m */
    double height;    /* along -g, m */
    long long group;  /* band of equal across[0], then column of equal across[0..1] */
    int index;
} column_entry;

static int compare_doubles(double a, double b)
{
    return (a > b) - (a < b);
}

static int by_across0(const void *pa, const void *pb)
{
    const column_entry *a = pa, *b = pb;
    return compare_doubles(a->across[0], b->across[0]);
}

static int by_band_across1(const void *pa, const void *pb)
{
    const column_entry *a = pa, *b = pb;
    return a->group != b->group ? (a->group > b->group) - (a->group < b->group)
                                : compare_doubles(a->across[1], b->across[1]);
}

/* By column, and from the top down within a column. */
static int by_column_top_down(const void *pa, const void *pb)
{
    const column_entry *a = pa, *b = pb;
    return a->group != b->group ? (a->group > b->group) - (a->group < b->group)
                                : compare_doubles(b->height, a->height);
}

/* Numbers the groups of sorted entries: a new one where the group before
 * changes or across[axis] moves on by more than half a spacing from the
 * group's first entry (points of a lattice column share their coordinates
 * across g; neighbouring columns are a spacing apart). */
static void number_groups(column_entry *e, int count, int axis, double dx)
{
    long long group = -1, previous = -1;
    double start = 0.0;
    for (int k = 0; k < count; ++k) {
        if (k == 0 || e[k].group != previous || e[k].across[axis] - start > 0.5 * dx) {
            ++group;
            start = e[k].across[axis];
        }
        previous = e[k].group;
        e[k].group = group;
    }
}

/* Unit vectors u, v across the unit vector e (v = e x u). */
static void across(const double e[3], double u[3], double v[3])
{
    int axis = 0; /* the axis least aligned with e */
    for (int d = 1; d < 3; ++d)
        if (fabs(e[d]) < fabs(e[axis]))
            axis = d;
    double norm = 0.0;
    for (int d = 0; d < 3; ++d) {
        u[d] = (d == axis) - e[axis] * e[d];
        norm += u[d] * u[d];
    }
    for (int d = 0; d < 3; ++d)
        u[d] /= sqrt(norm);
    v[0] = e[1] * u[2] - e[2] * u[1];
    v[1] = e[2] * u[0] - e[0] * u[2];
    v[2] = e[0] * u[1] - e[1] * u[0];
}

/* The entry of the particle at x: its coordinates across and along `up`. */
static column_entry column_entry_of(const amsph_real *x, const double up[3], int index)
{
    double u[3], v[3];
    across(up, u, v);
    column_entry entry = {{0.0, 0.0}, 0.0, 0, index};
    for (int d = 0; d < 3; ++d) {
        entry.across[0] += x[d] * u[d];
        entry.across[1] += x[d] * v[d];
        entry.height += x[d] * up[d];
    }
    return entry;
}

/* Sorts the entries into lattice columns (numbered in `group`), each from
 * the top down. */
static void sort_columns(column_entry *e, int count, double dx)
{
    qsort(e, (size_t)count, sizeof *e, by_across0);
    number_groups(e, count, 0, dx);
    qsort(e, (size_t)count, sizeof *e, by_band_across1);
    number_groups(e, count, 1, dx);
    qsort(e, (size_t)count, sizeof *e, by_column_top_down);
}

/* Hydrostatic initial state of the particles of the blocks marked
 * `hydrostatic` (block k holds particles [first[k], first[k + 1])): in each
 * lattice column along g, from the top down, the weight of the hydrostatic
 * fluid above,
 *   p_i = |g| dx (sum_{j above i} rho0_j + rho0_i / 2),
 *   rho_i = rho0_i + p_i / c0_i^2 (the equation of state),
 * with rho0 the particles' initial density, and mass rho_i dx^d, so that
 * each particle keeps the lattice volume. Blocks stacked on a common
 * lattice start in balance with each other, whatever their rho0. A
 * non-fluid particle (a grain or solid in a hydrostatic block) keeps its
 * state and counts in the column with the rho0 of the fluid above it. */
static int set_hydrostatic(const amsph_case *c, const int *first, amsph_host_particles *h)
{
    const double gnorm = sqrt(c->gravity[0] * c->gravity[0] + c->gravity[1] * c->gravity[1] +
                              c->gravity[2] * c->gravity[2]);
    if (gnorm == 0.0)
        return 0;
    const double up[3] = {-c->gravity[0] / gnorm, -c->gravity[1] / gnorm, -c->gravity[2] / gnorm};
    column_entry *entries = malloc((size_t)(h->n > 0 ? h->n : 1) * sizeof *entries);
    if (!entries)
        return amsph_fail("out of host memory for the hydrostatic initial state");
    const amsph_real *x = amsph_host_real(h, AMSPH_FIELD_POSITION);
    int count = 0;
    for (int k = 0; k < c->n_geometry; ++k)
        if (c->geometry[k].hydrostatic && c->materials[c->geometry[k].material].sound_speed > 0.0)
            for (int i = first[k]; i < first[k + 1]; ++i)
                entries[count++] = column_entry_of(x + 3 * i, up, i);
    sort_columns(entries, count, c->dx);
    amsph_real *rho = amsph_host_real(h, AMSPH_FIELD_DENSITY);
    const int *material = h->data[AMSPH_FIELD_MATERIAL];
    const int *kind = h->data[AMSPH_FIELD_KIND];
    double above = 0.0;      /* sum of rho0 over the column above */
    double fluid_rho0 = 0.0; /* of the last fluid particle above, 0 for none */
    for (int k = 0; k < count; ++k) {
        if (k > 0 && entries[k].group != entries[k - 1].group)
            above = fluid_rho0 = 0.0;
        const int i = entries[k].index;
        const double rho0 = rho[i], c0 = c->materials[material[i]].sound_speed;
        if (kind[i] != AMSPH_KIND_FLUID) {
            /* a body held in the fluid: below it the fluid has the pressure
             * of its depth, as if the fluid above filled the body */
            above += fluid_rho0 > 0.0 ? fluid_rho0 : rho0;
            continue;
        }
        fluid_rho0 = rho0;
        const double p = gnorm * c->dx * (above + 0.5 * rho0);
        above += rho0;
        rho[i] = (amsph_real)(rho0 + p / (c0 * c0));
        amsph_host_real(h, AMSPH_FIELD_MASS)[i] = (amsph_real)(rho[i] * pow(c->dx, c->dim));
    }
    free(entries);
    return 0;
}

static int place_block(const amsph_case *c, const amsph_geometry *g, const amsph_powder *bed,
                       const occupied *before, int first_grain, amsph_host_particles *h)
{
    long long count = 0;
    AMSPH_CHECK(visit_block(c, g, bed, before, first_grain, NULL, &count));
    if (count == 0)
        return amsph_bad_input("%s:%d: geometry block holds no particle at dx = %g m; make it larger "
                               "than dx%s",
                               c->path, g->line, c->dx, g->fill ? " (or the blocks before it fill it)" : "");
    if (h->n + count > 2147483647LL)
        return amsph_fail("%s:%d: the scene would exceed 2^31 particles", c->path, g->line);
    AMSPH_CHECK(amsph_host_resize(h, h->n + (int)count));
    return visit_block(c, g, bed, before, first_grain, h, &count);
}

/* Block g's particles; a `fill` block's only away from those placed so far,
 * any other's nowhere near them. */
static int fill_block(const amsph_case *c, const amsph_geometry *g, const amsph_powder *bed,
                      int first_grain, amsph_host_particles *h)
{
    if (h->n == 0)
        return place_block(c, g, bed, NULL, first_grain, h);
    occupied before;
    AMSPH_CHECK(occupied_build(c, h, h->n, &before));
    const int status = place_block(c, g, bed, &before, first_grain, h);
    occupied_free(&before);
    return status;
}

/* Grains resolved by at least this many dx in radius. */
#define GRAIN_RADIUS_MIN_DX 2.0

/* Adds block g's particles; a block of kind grain takes the next grain
 * indices from *next_grain (one, or one per grain of a powder bed). */
static int add_block(const amsph_case *c, const amsph_geometry *g, amsph_host_particles *h, int *next_grain)
{
    const int first_grain = *next_grain;
    if (g->shape != AMSPH_SHAPE_POWDER_BED) {
        *next_grain += g->kind == AMSPH_KIND_GRAIN;
        return fill_block(c, g, NULL, first_grain, h);
    }
    const double smallest = amsph_powder_smallest_radius(g);
    if (smallest < GRAIN_RADIUS_MIN_DX * c->dx)
        return amsph_bad_input("%s:%d: powder grains of radius %g m are not resolved at dx = %g m; "
                               "make dx at most %g m (a radius of %g dx)",
                               c->path, g->line, smallest, c->dx, smallest / GRAIN_RADIUS_MIN_DX,
                               GRAIN_RADIUS_MIN_DX);
    amsph_powder bed;
    AMSPH_CHECK(amsph_powder_deposit(g, c->dim, &bed));
    *next_grain += g->kind == AMSPH_KIND_GRAIN ? bed.n : 0;
    const int status = fill_block(c, g, &bed, first_grain, h);
    amsph_powder_free(&bed);
    return status;
}

/* Grain particles closer than this fraction of the contact distance to a
 * contact partner start pressed: the contact spring (Fuchs et al. 2022 Eq.
 * 39) throws them apart at the first step. A powder bed samples all its
 * grains on one lattice (pairs of touching grains dx apart), so do blocks
 * on lattices that line up; `circle` blocks about other centres do not
 * (0.36 dx apart on a bed of touching discs: its grains flew apart at up to
 * 9 m/s before anything touched them). */
#define PRESSED_FRACTION 0.9

typedef struct {
    const int *kind, *grain;
    int of; /* the grain particle whose partners are sought */
} contact_partners;

/* Particle j of another grain, a wall or a fixed solid: what grain particle
 * `of` has contact forces with (kernels/grains.cl grain_particle_forces). */
static int is_contact_partner(const void *ctx, int j)
{
    const contact_partners *p = ctx;
    return p->kind[j] != AMSPH_KIND_FLUID && (p->kind[j] != AMSPH_KIND_GRAIN || p->grain[j] != p->grain[p->of]);
}

/* Refuses grains that start pressed against other grains, walls or solids. */
static int check_grain_contacts(const amsph_case *c, const int first[], const amsph_host_particles *h)
{
    occupied all;
    AMSPH_CHECK(occupied_build(c, h, h->n, &all));
    contact_partners p = {.kind = h->data[AMSPH_FIELD_KIND], .grain = h->data[AMSPH_FIELD_GRAIN]};
    const amsph_real *x_h = amsph_host_real(h, AMSPH_FIELD_POSITION);
    const double clearance = PRESSED_FRACTION * c->grains.distance / c->dx;
    int i, partner = -1;
    for (i = 0; i < h->n; ++i) {
        if (p.kind[i] != AMSPH_KIND_GRAIN)
            continue;
        const double x[3] = {x_h[3 * i], x_h[3 * i + 1], x_h[3 * i + 2]};
        p.of = i;
        partner = occupied_find(&all, x, clearance, is_contact_partner, &p);
        if (partner >= 0)
            break;
    }
    occupied_free(&all);
    if (partner < 0)
        return 0;
    int k = 0; /* the block of particle i */
    while (first[k + 1] <= i)
        ++k;
    double r2 = 0.0;
    for (int d = 0; d < 3; ++d)
        r2 += (x_h[3 * i + d] - x_h[3 * partner + d]) * (x_h[3 * i + d] - x_h[3 * partner + d]);
    const int kind = p.kind[partner];
    return amsph_bad_input("%s:%d: a grain particle at (%g, %g, %g) m starts %.3g dx from a particle of %s, "
                           "inside the contact distance (%.3g dx): the contact springs would throw them "
                           "apart; leave a contact distance between them (a powder_bed block samples its "
                           "grains on one lattice)",
                           c->path, c->geometry[k].line, x_h[3 * i], x_h[3 * i + 1], x_h[3 * i + 2],
                           sqrt(r2) / c->dx,
                           kind == AMSPH_KIND_GRAIN  ? "another grain"
                           : kind == AMSPH_KIND_WALL ? "a wall"
                                                     : "a fixed solid",
                           c->grains.distance / c->dx);
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
    if (c->temperature_history.enabled) {
        AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_TEMPERATURE));
    } else if (with_temperature) {
        if (with_temperature != c->n_geometry)
            for (int k = 0; k < c->n_geometry; ++k)
                if (!c->geometry[k].has_temperature)
                    return amsph_bad_input("%s:%d: this geometry block has no 'temperature' while others "
                                           "do; give every block an initial temperature",
                                           c->path, c->geometry[k].line);
        AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_TEMPERATURE));
    }
    if (c->grains.enabled)
        AMSPH_CHECK(amsph_host_add_field(h, AMSPH_FIELD_GRAIN));
    int first[AMSPH_MAX_GEOMETRY + 1], next_grain = 0;
    for (int k = 0; k < c->n_geometry; ++k) {
        first[k] = h->n;
        AMSPH_CHECK(add_block(c, &c->geometry[k], h, &next_grain));
    }
    first[c->n_geometry] = h->n;
    if (c->grains.enabled)
        AMSPH_CHECK(check_grain_contacts(c, first, h));
    return set_hydrostatic(c, first, h);
}
