/* The beam and its bin grid as the laser kernels see them, passed by value;
 * the host includes it with AMSPH_SHARED_REAL = amsph_real.
 *
 * The beam frame: `direction` d (unit, the way the light travels) and
 * `across` e1 (unit, d . e1 = 0); in 3D the second lateral axis is
 * e2 = d x e1. A point x has beam coordinates
 *   q_k = (x - centre) . e_k   across the beam (k < dim - 1),
 *   q_d = (x - centre) . d     along it,
 * with the nearest periodic image of x - centre. Bin nodes sit at
 *   q_k = (i_k - (lateral_nodes - 1) / 2) bin_size,  i_k = 0 .. lateral_nodes - 1,
 *   q_d = depth_lo + i_d bin_size,                    i_d = 0 .. depth_nodes - 1,
 * so the middle column lies on the axis and node i_d = 0 is above the
 * whole domain. A pass of the absorption lays its nodes over part of that
 * grid: the columns i_k = lateral_first[k] .. lateral_first[k] +
 * lateral_count[k] - 1 and depth_nodes from depth_lo (the host's laser
 * state keeps the whole grid: 0 and lateral_nodes). Node index: i_d +
 * depth_nodes * column, column = i_0 - lateral_first[0] (+ lateral_count[0]
 * (i_1 - lateral_first[1]) in 3D): a column's nodes are contiguous. */
#ifndef AMSPH_LASER_PARAMS_H
#define AMSPH_LASER_PARAMS_H

#ifndef AMSPH_SHARED_REAL
#define AMSPH_SHARED_REAL real
#endif

/* laser_depth_extent's value for a particle under no bin column. */
#define LASER_NOT_UNDER (-1e30)

typedef struct {
    AMSPH_SHARED_REAL centre[3];      /* a point on the beam axis, m */
    AMSPH_SHARED_REAL direction[3];   /* d, unit */
    AMSPH_SHARED_REAL across[3];      /* e1, unit, normal to d */
    AMSPH_SHARED_REAL depth_lo;       /* q_d of the first node of every column, m */
    AMSPH_SHARED_REAL bin_size;       /* node spacing, m */
    AMSPH_SHARED_REAL peak_intensity; /* 2 P / (pi r_l^2) at the current power (volumetric:
                                         times the absorptivity zeta), W/m^2 */
    AMSPH_SHARED_REAL radius;         /* 1/e^2 radius r_l, m */
    AMSPH_SHARED_REAL absorption;     /* volumetric: alpha, 1/m; surface: zeta */
    AMSPH_SHARED_REAL surface_delta;  /* surface: delta = this |grad Gamma| (flat_face_delta) */
    int lateral_nodes;                /* nodes across the beam per lateral axis (odd) */
    int lateral_first[2];             /* the pass's first column index per lateral axis */
    int lateral_count[2];             /* the pass's columns per lateral axis */
    int depth_nodes;                  /* nodes along the beam */
} laser_params;

#endif
