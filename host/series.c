#include "series.h"

#include <errno.h>
#include <math.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "error.h"
#include "thermal.h"

static const amsph_real *field(const amsph_series_sample *x, amsph_field_id f)
{
    return amsph_host_real(x->particles, f);
}

static int count(const amsph_series_sample *x) { return x->particles->n; }

static double count_kind(const amsph_series_sample *x, amsph_kind kind)
{
    const int *k = x->particles->data[AMSPH_FIELD_KIND];
    int total = 0;
    for (int i = 0; i < count(x); ++i)
        total += k[i] == (int)kind;
    return total;
}

static double squared_speed(const amsph_real *v, int i)
{
    return (double)v[3 * i] * v[3 * i] + (double)v[3 * i + 1] * v[3 * i + 1] + (double)v[3 * i + 2] * v[3 * i + 2];
}

/* Largest value of a scalar field, NAN where the case lacks it. */
static double max_of(const amsph_series_sample *x, amsph_field_id f)
{
    const amsph_real *a = field(x, f);
    if (!a)
        return NAN;
    double largest = -INFINITY;
    for (int i = 0; i < count(x); ++i)
        largest = fmax(largest, a[i]);
    return largest;
}

static double momentum(const amsph_series_sample *x, int axis)
{
    const amsph_real *m = field(x, AMSPH_FIELD_MASS), *v = field(x, AMSPH_FIELD_VELOCITY);
    double sum = 0.0;
    for (int i = 0; i < count(x); ++i)
        sum += (double)m[i] * v[3 * i + axis];
    return sum;
}

static double sim_step(const amsph_series_sample *x) { return (double)x->sim->step; }
static double sim_time(const amsph_series_sample *x) { return x->sim->time; }
static double sim_dt(const amsph_series_sample *x) { return x->sim->dt; }
static double fluid_particles(const amsph_series_sample *x) { return count_kind(x, AMSPH_KIND_FLUID); }
static double wall_particles(const amsph_series_sample *x) { return count_kind(x, AMSPH_KIND_WALL); }
static double solid_particles(const amsph_series_sample *x) { return count_kind(x, AMSPH_KIND_SOLID); }
static double grain_particles(const amsph_series_sample *x) { return count_kind(x, AMSPH_KIND_GRAIN); }
static double removed(const amsph_series_sample *x) { return (double)x->sim->particles.removed; }
static double max_temperature(const amsph_series_sample *x) { return max_of(x, AMSPH_FIELD_TEMPERATURE); }
static double momentum_x(const amsph_series_sample *x) { return momentum(x, 0); }
static double momentum_y(const amsph_series_sample *x) { return momentum(x, 1); }
static double momentum_z(const amsph_series_sample *x) { return momentum(x, 2); }
static double wall_seconds(const amsph_series_sample *x) { return x->wall_seconds; }
static double throughput(const amsph_series_sample *x) { return x->particle_steps_per_second; }

static double max_speed(const amsph_series_sample *x)
{
    double largest = 0.0;
    for (int i = 0; i < count(x); ++i)
        largest = fmax(largest, squared_speed(field(x, AMSPH_FIELD_VELOCITY), i));
    return sqrt(largest);
}

static double total_mass(const amsph_series_sample *x)
{
    const amsph_real *m = field(x, AMSPH_FIELD_MASS);
    double sum = 0.0;
    for (int i = 0; i < count(x); ++i)
        sum += m[i];
    return sum;
}

static double liquid_mass(const amsph_series_sample *x)
{
    const amsph_real *m = field(x, AMSPH_FIELD_MASS), *phi = field(x, AMSPH_FIELD_LIQUID_FRACTION);
    if (!phi)
        return NAN;
    double sum = 0.0;
    for (int i = 0; i < count(x); ++i)
        sum += (double)m[i] * phi[i];
    return sum;
}

static double kinetic_energy(const amsph_series_sample *x)
{
    const amsph_real *m = field(x, AMSPH_FIELD_MASS), *v = field(x, AMSPH_FIELD_VELOCITY);
    double sum = 0.0;
    for (int i = 0; i < count(x); ++i)
        sum += 0.5 * m[i] * squared_speed(v, i);
    return sum;
}

/* The thermal module's quantities: the energy ledger (sim.h), the
 * material's enthalpy and the iterations of the last enthalpy update;
 * NAN without the module. */
static double thermal_value(const amsph_series_sample *x, double value)
{
    return x->sim->config.thermal.enabled ? value : NAN;
}

static double enthalpy(const amsph_series_sample *x) { return thermal_value(x, x->enthalpy); }
static double laser_energy(const amsph_series_sample *x) { return thermal_value(x, x->sim->ledger.laser); }
static double radiated_energy(const amsph_series_sample *x) { return thermal_value(x, x->sim->ledger.radiation); }
static double evaporation_heat(const amsph_series_sample *x) { return thermal_value(x, x->sim->ledger.evaporation); }
static double evaporated_energy(const amsph_series_sample *x) { return thermal_value(x, x->sim->ledger.evaporated); }
static double evaporated_particles(const amsph_series_sample *x)
{
    return thermal_value(x, (double)x->sim->evaporated_particles);
}
static double departed_energy(const amsph_series_sample *x) { return thermal_value(x, x->sim->ledger.departed); }
static double wall_heat(const amsph_series_sample *x) { return thermal_value(x, x->sim->ledger.walls); }
static double viscous_heat(const amsph_series_sample *x) { return thermal_value(x, x->sim->ledger.viscous); }
static double thermal_iterations(const amsph_series_sample *x)
{
    return thermal_value(x, x->sim->thermal_iterations);
}

static double ledger_error(const amsph_series_sample *x)
{
    return thermal_value(x, amsph_energy_ledger_error(&x->sim->ledger, x->enthalpy));
}

/* Sums run over every particle (walls and solids included); masses, and so
 * momenta and energies, are per unit depth in 2D. */
const amsph_series_column amsph_series_columns[] = {
    {"step", "1", "Steps since the start of the simulation (restarts included)", sim_step},
    {"time", "s", "Simulated time", sim_time},
    {"dt", "s", "Last time step", sim_dt},
    {"fluid_particles", "1", "Fluid particles", fluid_particles},
    {"wall_particles", "1", "Wall particles", wall_particles},
    {"solid_particles", "1", "Fixed-solid particles", solid_particles},
    {"grain_particles", "1", "Particles of mobile grains (the grains module)", grain_particles},
    {"removed_particles", "1", "Particles removed for leaving the domain, since the start", removed},
    {"max_speed", "m/s", "Largest particle speed", max_speed},
    {"max_temperature", "K", "Largest temperature; empty when the case has no temperatures", max_temperature},
    {"liquid_mass", "kg", "Sum of mass times liquid fraction; empty without phase change", liquid_mass},
    {"total_mass", "kg", "Mass of all particles", total_mass},
    {"momentum_x", "kg m/s", "Total momentum, x component", momentum_x},
    {"momentum_y", "kg m/s", "Total momentum, y component", momentum_y},
    {"momentum_z", "kg m/s", "Total momentum, z component", momentum_z},
    {"kinetic_energy", "J", "Total kinetic energy, sum of m u^2 / 2", kinetic_energy},
    {"enthalpy", "J",
     "Sum of m h over fluid and solid particles (sensible heat from 0 K plus latent heat); this and "
     "the next nine are empty without the thermal module",
     enthalpy},
    {"laser_energy", "J", "Laser energy absorbed by the material since the start", laser_energy},
    {"radiated_energy", "J", "Energy radiated from free surfaces since the start", radiated_energy},
    {"evaporation_heat", "J",
     "Heat carried off by the vapour of free surfaces since the start (thermal.evaporative_cooling, Fuchs "
     "Eq. 18)",
     evaporation_heat},
    {"evaporated_particles", "1", "Particles removed above thermal.evaporation_temperature since the start",
     evaporated_particles},
    {"evaporated_energy", "J", "Enthalpy m h of the particles removed above thermal.evaporation_temperature",
     evaporated_energy},
    {"departed_energy", "J", "Enthalpy m h of the particles that left the domain since the start",
     departed_energy},
    {"wall_heat", "J", "Heat given to the material by the Dirichlet walls since the start (negative: taken)",
     wall_heat},
    {"viscous_heat", "J", "Viscous dissipation turned into heat since the start", viscous_heat},
    {"ledger_error", "1",
     "Energy ledger: abs(enthalpy change - (laser - radiated - evaporation_heat - evaporated_energy - "
     "departed_energy + wall + viscous)) over the larger of the change and the sum of the seven terms' "
     "magnitudes",
     ledger_error},
    {"thermal_iterations", "1",
     "Fixed-point iterations of the last enthalpy update (1 explicit; 0 before the first step)",
     thermal_iterations},
    {"wall_seconds", "s", "Wall time spent on the simulation so far, restarts included", wall_seconds},
    {"particle_steps_per_second", "1/s", "Particles times steps per wall second since the previous row",
     throughput},
};
const int amsph_series_column_count = (int)(sizeof amsph_series_columns / sizeof amsph_series_columns[0]);

static int write_header(amsph_series *se)
{
    for (int c = 0; c < amsph_series_column_count; ++c)
        fprintf(se->file, "%s%s", c ? "," : "", amsph_series_columns[c].name);
    fputc('\n', se->file);
    return fflush(se->file) ? amsph_fail("cannot write %s: %s", se->path, strerror(errno)) : 0;
}

/* Opens an existing series for appending after its first keep bytes. */
static int continue_file(amsph_series *se, long long keep)
{
    struct stat st;
    if (stat(se->path, &st) || st.st_size < keep)
        return amsph_fail("%s is shorter than when the checkpoint was written (%lld bytes); "
                          "restart into another directory",
                          se->path, keep);
    if (truncate(se->path, (off_t)keep))
        return amsph_fail("cannot cut %s back to the checkpoint: %s", se->path, strerror(errno));
    se->file = fopen(se->path, "a");
    if (!se->file || fseek(se->file, 0, SEEK_END))
        return amsph_fail("cannot open %s: %s", se->path, strerror(errno));
    return 0;
}

int amsph_series_open(amsph_series *se, const char *path, long long keep)
{
    memset(se, 0, sizeof *se);
    if (snprintf(se->path, sizeof se->path, "%s", path) >= (int)sizeof se->path)
        return amsph_fail("path too long: %s", path);
    if (keep >= 0 && access(path, F_OK) == 0)
        return continue_file(se, keep);
    se->file = fopen(path, "w");
    if (!se->file)
        return amsph_fail("cannot create %s: %s", path, strerror(errno));
    return write_header(se);
}

int amsph_series_write(amsph_series *se, const amsph_series_sample *x)
{
    for (int c = 0; c < amsph_series_column_count; ++c) {
        const double v = amsph_series_columns[c].value(x);
        fputs(c ? "," : "", se->file);
        if (!isnan(v))
            fprintf(se->file, "%.15g", v);
    }
    fputc('\n', se->file);
    if (fflush(se->file) || ferror(se->file))
        return amsph_fail("cannot write %s: %s (disk full?)", se->path, strerror(errno));
    return 0;
}

long long amsph_series_bytes(const amsph_series *se) { return se->file ? (long long)ftell(se->file) : 0; }

void amsph_series_close(amsph_series *se)
{
    if (se->file)
        fclose(se->file);
    memset(se, 0, sizeof *se);
}

void amsph_series_print_columns(FILE *f)
{
    fprintf(f, "| Column | Unit | Meaning |\n|---|---|---|\n");
    for (int c = 0; c < amsph_series_column_count; ++c)
        fprintf(f, "| `%s` | %s | %s |\n", amsph_series_columns[c].name, amsph_series_columns[c].unit,
                amsph_series_columns[c].doc);
}
