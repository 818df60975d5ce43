/* Per-material thermal properties as the kernels see them: for each material
 * THERMAL_STRIDE reals holding node temperatures T_i (increasing, from 0 K),
 * the specific enthalpy h(T_i) and the conductivity k(T_i), both linear
 * between nodes, followed by the node count and the mushy interval.
 *
 * The host (host/thermal.c) builds the nodes from the material's properties:
 * h(T) = integral of the sensible heat capacity from 0 K, plus L s(T). With
 * the latent heat spread over the mushy interval this is the apparent heat
 * capacity method (Russell 2018 Eqs. 3.46-3.47), carried by the enthalpy so
 * that the latent heat is exactly L (Eq. 3.46's L / (2 dT) with dT the full
 * interval width would give L / 2). */
#ifndef AMSPH_THERMAL_TABLE_H
#define AMSPH_THERMAL_TABLE_H

#define THERMAL_NODES 96
#define THERMAL_TEMPERATURE 0                    /* T_i, K */
#define THERMAL_ENTHALPY THERMAL_NODES           /* h(T_i), J/kg */
#define THERMAL_CONDUCTIVITY (2 * THERMAL_NODES) /* k(T_i), W/(m K) */
#define THERMAL_COUNT (3 * THERMAL_NODES)        /* nodes in use (>= 2) */
#define THERMAL_SOLIDUS (THERMAL_COUNT + 1)      /* T_m - dT/2, K; melts only if < liquidus */
#define THERMAL_LIQUIDUS (THERMAL_COUNT + 2)     /* T_m + dT/2, K */
#define THERMAL_EMISSIVITY (THERMAL_COUNT + 3)
#define THERMAL_STRIDE (THERMAL_COUNT + 4)

#ifdef AMSPH_DEVICE_H
/* Index i in [0, count - 2] of the segment [x_i, x_i+1] that holds v (the
 * first or last one beyond the ends); x increasing. */
static inline int thermal_segment(GLOBAL const real *x, int count, real v)
{
    int lo = 0, hi = count - 1;
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (v < x[mid])
            hi = mid;
        else
            lo = mid;
    }
    return lo;
}

static inline GLOBAL const real *thermal_material(GLOBAL const real *table, int material)
{
    return table + THERMAL_STRIDE * material;
}

static inline int thermal_count(GLOBAL const real *t)
{
    return (int)t[THERMAL_COUNT];
}

/* y(v) on the nodes (x_i, y_i), x increasing: linear between nodes and
 * extended linearly beyond the ends. */
static inline real table_interpolate(GLOBAL const real *x, GLOBAL const real *y, int count, real v)
{
    const int i = thermal_segment(x, count, v);
    return y[i] + (v - x[i]) * (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
}

/* T(h): the inverse of the enthalpy table. */
static inline real temperature_of_enthalpy(GLOBAL const real *table, int material, real h)
{
    GLOBAL const real *t = thermal_material(table, material);
    return table_interpolate(t + THERMAL_ENTHALPY, t + THERMAL_TEMPERATURE, thermal_count(t), h);
}

static inline real enthalpy_of_temperature(GLOBAL const real *table, int material, real temp)
{
    GLOBAL const real *t = thermal_material(table, material);
    return table_interpolate(t + THERMAL_TEMPERATURE, t + THERMAL_ENTHALPY, thermal_count(t), temp);
}

/* k(T), constant beyond the last node. */
static inline real conductivity_of_temperature(GLOBAL const real *table, int material, real temp)
{
    GLOBAL const real *t = thermal_material(table, material);
    GLOBAL const real *temperature = t + THERMAL_TEMPERATURE;
    const int count = thermal_count(t);
    return table_interpolate(temperature, t + THERMAL_CONDUCTIVITY, count, fmin(temp, temperature[count - 1]));
}

static inline int material_melts(GLOBAL const real *table, int material)
{
    GLOBAL const real *t = thermal_material(table, material);
    return t[THERMAL_SOLIDUS] < t[THERMAL_LIQUIDUS];
}

/* Liquid fraction s (0 solid, 1 liquid; Russell 2018 Eq. 3.47 with
 * erratum 2 of PHYSICS.md), linear over the mushy interval. */
static inline real liquid_fraction_of_temperature(GLOBAL const real *table, int material, real temp)
{
    GLOBAL const real *t = thermal_material(table, material);
    const real s = (temp - t[THERMAL_SOLIDUS]) / (t[THERMAL_LIQUIDUS] - t[THERMAL_SOLIDUS]);
    return fmin(fmax(s, REAL(0.0)), REAL(1.0));
}
#endif

#endif
