/* Particle store: structure of arrays on the device, one buffer per field.
 *
 * The field registry below is the one list of fields: kernels get their
 * buffers by field id, the grid reorders every present field, and snapshots
 * write every present field flagged for output, with its unit. Vectors are
 * stored as N x 3 (z = 0 in 2D). */
#ifndef AMSPH_PARTICLES_H
#define AMSPH_PARTICLES_H

#include "backend.h"
#include "real.h"

typedef enum { AMSPH_TYPE_REAL, AMSPH_TYPE_INT, AMSPH_TYPE_UINT } amsph_field_type;

#define AMSPH_FIELD_OUTPUT 1u /* written to snapshots */

/* X(ID, name, type, components, unit, flags) */
#define AMSPH_FIELDS(X)                                                                            \
    X(POSITION, "position", AMSPH_TYPE_REAL, 3, "m", AMSPH_FIELD_OUTPUT)                           \
    X(VELOCITY, "velocity", AMSPH_TYPE_REAL, 3, "m/s", AMSPH_FIELD_OUTPUT)                         \
    X(ACCELERATION, "acceleration", AMSPH_TYPE_REAL, 3, "m/s^2", 0)                                \
    X(DENSITY, "density", AMSPH_TYPE_REAL, 1, "kg/m^3", AMSPH_FIELD_OUTPUT)                        \
    X(PRESSURE, "pressure", AMSPH_TYPE_REAL, 1, "Pa", AMSPH_FIELD_OUTPUT)                          \
    X(REFERENCE_DENSITY, "reference_density", AMSPH_TYPE_REAL, 1, "kg/m^3", AMSPH_FIELD_OUTPUT)    \
    X(MASS, "mass", AMSPH_TYPE_REAL, 1, "kg", AMSPH_FIELD_OUTPUT)                                  \
    X(KIND, "kind", AMSPH_TYPE_INT, 1, "1", AMSPH_FIELD_OUTPUT)                                    \
    X(MATERIAL, "material", AMSPH_TYPE_INT, 1, "1", AMSPH_FIELD_OUTPUT)                            \
    X(ID, "id", AMSPH_TYPE_UINT, 1, "1", AMSPH_FIELD_OUTPUT)                                       \
    X(TEMPERATURE, "temperature", AMSPH_TYPE_REAL, 1, "K", AMSPH_FIELD_OUTPUT)                     \
    X(LIQUID_FRACTION, "liquid_fraction", AMSPH_TYPE_REAL, 1, "1", AMSPH_FIELD_OUTPUT)             \
    X(DENSITY_RATE, "density_rate", AMSPH_TYPE_REAL, 1, "kg/(m^3 s)", 0)                           \
    X(SHEPARD, "shepard", AMSPH_TYPE_REAL, 1, "1", 0)                                              \
    X(VELOCITY_PREVIOUS, "velocity_previous", AMSPH_TYPE_REAL, 3, "m/s", 0)                      \
    X(DENSITY_PREVIOUS, "density_previous", AMSPH_TYPE_REAL, 1, "kg/m^3", 0)                       \
    X(SMOOTHING_LENGTH, "smoothing_length", AMSPH_TYPE_REAL, 1, "m", AMSPH_FIELD_OUTPUT)           \
    X(WALL_VELOCITY, "wall_velocity", AMSPH_TYPE_REAL, 3, "m/s", 0)                               \
    X(GAS_WALL_PRESSURE, "gas_wall_pressure", AMSPH_TYPE_REAL, 1, "Pa", 0)                         \
    X(ENTHALPY, "enthalpy", AMSPH_TYPE_REAL, 1, "J/kg", AMSPH_FIELD_OUTPUT)                        \
    X(ENTHALPY_RATE, "enthalpy_rate", AMSPH_TYPE_REAL, 1, "W/kg", 0)                               \
    X(CONDUCTIVITY, "conductivity", AMSPH_TYPE_REAL, 1, "W/(m K)", 0)                              \
    X(PEAK_TEMPERATURE, "peak_temperature", AMSPH_TYPE_REAL, 1, "K", AMSPH_FIELD_OUTPUT)           \
    X(LASER_POWER, "laser_power", AMSPH_TYPE_REAL, 1, "W/m^3", AMSPH_FIELD_OUTPUT)                \
    X(SURFACE_SHEPARD, "surface_shepard", AMSPH_TYPE_REAL, 1, "1", 0)                              \
    X(NORMAL, "normal", AMSPH_TYPE_REAL, 3, "1/m", AMSPH_FIELD_OUTPUT)                             \
    X(UNIT_NORMAL, "unit_normal", AMSPH_TYPE_REAL, 3, "1", 0)                                      \
    X(NORMAL_WEIGHT, "normal_weight", AMSPH_TYPE_REAL, 1, "1", 0)                                  \
    X(WET_FRACTION, "wet_fraction", AMSPH_TYPE_REAL, 2, "1", 0)                                    \
    X(WET_COLOUR, "wet_colour", AMSPH_TYPE_REAL, 1, "1", 0)                                        \
    X(WET_NORMAL, "wet_normal", AMSPH_TYPE_REAL, 3, "1/m", 0)                                      \
    X(RAW_CURVATURE, "raw_curvature", AMSPH_TYPE_REAL, 1, "1/m", 0)                                \
    X(CURVATURE, "curvature", AMSPH_TYPE_REAL, 1, "1/m", AMSPH_FIELD_OUTPUT)                       \
    X(SURFACE_TENSION, "surface_tension", AMSPH_TYPE_REAL, 1, "N/m", AMSPH_FIELD_OUTPUT)            \
    X(GRAIN, "grain", AMSPH_TYPE_INT, 1, "1", AMSPH_FIELD_OUTPUT)

#define AMSPH_FIELD_ENUM(id, name, type, comps, unit, flags) AMSPH_FIELD_##id,
typedef enum { AMSPH_FIELDS(AMSPH_FIELD_ENUM) AMSPH_FIELD_COUNT } amsph_field_id;
#undef AMSPH_FIELD_ENUM

typedef struct {
    const char *name;
    amsph_field_type type;
    int components;
    const char *unit;
    unsigned flags;
} amsph_field_info;

extern const amsph_field_info amsph_fields[AMSPH_FIELD_COUNT];

/* Bytes of one particle's value of the field (every element is 4 bytes, or
 * 8 for `real` in a double build). */
size_t amsph_field_bytes(amsph_field_id f);

/* Host copy of the particles: one array per present field, NULL otherwise. */
typedef struct {
    int n;
    void *data[AMSPH_FIELD_COUNT];
} amsph_host_particles;

/* Adds field f to the host set (zero-filled, n entries). */
int amsph_host_add_field(amsph_host_particles *h, amsph_field_id f);
/* Grows every present field to hold n particles (new entries zero). */
int amsph_host_resize(amsph_host_particles *h, int n);
void amsph_host_free(amsph_host_particles *h);
static inline amsph_real *amsph_host_real(const amsph_host_particles *h, amsph_field_id f)
{
    return (amsph_real *)h->data[f];
}

typedef struct {
    amsph_backend *backend;
    int n;             /* particles in the simulation */
    int capacity;      /* particles the buffers hold */
    long long removed; /* particles removed for leaving the domain, since the start */
    amsph_buffer *field[AMSPH_FIELD_COUNT]; /* NULL where the field is absent */
} amsph_particles;

/* Uploads a host set (its fields become the present fields). */
int amsph_particles_upload(amsph_backend *b, const amsph_host_particles *h, amsph_particles *p);
/* Makes dst a device copy of the output fields of src (same backend);
 * allocates dst's buffers on first use. */
int amsph_particles_copy_output(amsph_particles *dst, const amsph_particles *src);
/* Downloads the present fields into a fresh host set (freed by the caller
 * with amsph_host_free, also on failure). */
int amsph_particles_download(amsph_particles *p, amsph_host_particles *h);
void amsph_particles_free(amsph_particles *p);

#endif
