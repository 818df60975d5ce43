#include "checkpoint.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "h5.h"
#include "hash.h"

#define TRAILER_BYTES 64
#define MAGIC "amsph checkpoint "
#define HDF5_SIGNATURE "\211HDF\r\n\032\n"

/* ---- trailer and checksum ------------------------------------------------ */

/* Writes the trailer after the image's `size` bytes (room for it is there). */
static void append_trailer(unsigned char *image, size_t size)
{
    char trailer[TRAILER_BYTES] = {0};
    snprintf(trailer, sizeof trailer, MAGIC "%d %lld %016" PRIx64 "\n", AMSPH_CHECKPOINT_VERSION,
             (long long)size, amsph_hash(AMSPH_HASH_START, image, size));
    memcpy(image + size, trailer, TRAILER_BYTES);
}

typedef struct {
    long version;
    long long bytes; /* of the HDF5 file before the trailer */
    uint64_t hash;
} trailer_fields;

/* Parses "VERSION BYTES HASH\n" after the magic; 0 on success. */
static int parse_trailer(const char *text, trailer_fields *t)
{
    char *end = NULL;
    errno = 0;
    t->version = strtol(text, &end, 10);
    if (end == text || *end != ' ')
        return 1;
    text = end + 1;
    t->bytes = strtoll(text, &end, 10);
    if (end == text || *end != ' ' || t->bytes < 0)
        return 1;
    text = end + 1;
    t->hash = (uint64_t)strtoull(text, &end, 16);
    return end == text || *end != '\n' || errno == ERANGE;
}

/* Hash of the first `bytes` bytes of f. */
static int hash_prefix(FILE *f, long long bytes, uint64_t *hash)
{
    unsigned char buffer[1 << 16];
    *hash = AMSPH_HASH_START;
    if (fseek(f, 0, SEEK_SET))
        return 1;
    while (bytes > 0) {
        const size_t want = bytes < (long long)sizeof buffer ? (size_t)bytes : sizeof buffer;
        if (fread(buffer, 1, want, f) != want)
            return 1;
        *hash = amsph_hash(*hash, buffer, want);
        bytes -= (long long)want;
    }
    return 0;
}

static int missing_trailer(FILE *f, const char *path)
{
    char start[8] = {0};
    if (fseek(f, 0, SEEK_SET) == 0 && fread(start, 1, sizeof start, f) == sizeof start &&
        !memcmp(start, HDF5_SIGNATURE, sizeof start))
        return amsph_bad_input("%s has no checkpoint trailer: it is truncated, or an HDF5 file that is "
                               "not an amsph checkpoint (a snapshot?)",
                               path);
    return amsph_bad_input("%s is not an amsph checkpoint", path);
}

static int verify_trailer(FILE *f, const char *path)
{
    char text[TRAILER_BYTES + 1] = {0};
    if (fseek(f, 0, SEEK_END))
        return amsph_bad_input("cannot read %s: %s", path, strerror(errno));
    const long long size = (long long)ftell(f);
    if (size < TRAILER_BYTES || fseek(f, -TRAILER_BYTES, SEEK_END) ||
        fread(text, 1, TRAILER_BYTES, f) != TRAILER_BYTES || strncmp(text, MAGIC, strlen(MAGIC)))
        return missing_trailer(f, path);
    trailer_fields t;
    if (parse_trailer(text + strlen(MAGIC), &t))
        return amsph_bad_input("%s: the checkpoint trailer is damaged", path);
    if (t.version != AMSPH_CHECKPOINT_VERSION)
        return amsph_bad_input("%s has checkpoint format version %ld; this amsph reads version %d", path,
                               t.version, AMSPH_CHECKPOINT_VERSION);
    if (t.bytes != size - TRAILER_BYTES)
        return amsph_bad_input("%s is truncated or was altered: %lld bytes before its trailer, %lld written",
                               path, size - TRAILER_BYTES, t.bytes);
    uint64_t hash = 0;
    if (hash_prefix(f, t.bytes, &hash))
        return amsph_bad_input("cannot read %s: %s", path, strerror(errno));
    if (hash != t.hash)
        return amsph_bad_input("%s is corrupt: its checksum does not match its contents", path);
    return 0;
}

static int verify_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return amsph_bad_input("cannot open the restart file %s: %s", path, strerror(errno));
    const int status = verify_trailer(f, path);
    fclose(f);
    return status;
}

/* ---- writing ------------------------------------------------------------- */

static herr_t write_particles(hid_t file, const char *name, const amsph_host_particles *h)
{
    hid_t group = H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    herr_t status = group < 0 ? -1 : 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT && status >= 0; ++f)
        if (h->data[f])
            status = amsph_h5_write_field(group, h, (amsph_field_id)f);
    if (group >= 0)
        H5Gclose(group);
    return status;
}

/* A sim scalar's HDF5 type (the union's members share its address). */
static hid_t scalar_type(const amsph_sim_scalar *info)
{
    return info->integer ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE;
}

static herr_t write_scalars(hid_t file, const amsph_scalar_value *v)
{
    hid_t group = H5Gcreate2(file, "sim", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    herr_t status = group < 0 ? -1 : 0;
    for (int k = 0; k < AMSPH_SIM_SCALAR_COUNT && status >= 0; ++k)
        status = amsph_h5_write_attribute(group, amsph_sim_scalars[k].name, scalar_type(&amsph_sim_scalars[k]),
                                          &v[k]);
    if (group >= 0)
        H5Gclose(group);
    return status;
}

static herr_t write_run(hid_t file, const amsph_run_record *r)
{
    hid_t group = H5Gcreate2(file, "run", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    herr_t status = group < 0 ? -1 : 0;
    const amsph_snapshot_list *l = &r->snapshots;
    if (status >= 0)
        status = amsph_h5_write_attribute(group, "next_output", H5T_NATIVE_LLONG, &r->next_output);
    if (status >= 0)
        status = amsph_h5_write_attribute(group, "wall_seconds", H5T_NATIVE_DOUBLE, &r->wall_seconds);
    if (status >= 0)
        status = amsph_h5_write_attribute(group, "series_bytes", H5T_NATIVE_LLONG, &r->series_bytes);
    if (status >= 0)
        status = amsph_h5_write_attribute(group, "snapshots", H5T_NATIVE_INT, &l->count);
    if (status >= 0)
        status = amsph_h5_write_array(group, "snapshot_time", H5T_NATIVE_DOUBLE, l->count, l->time);
    if (status >= 0)
        status = amsph_h5_write_array(group, "snapshot_particles", H5T_NATIVE_INT, l->count, l->particles);
    if (group >= 0)
        H5Gclose(group);
    return status;
}

static herr_t write_contents(hid_t file, const amsph_checkpoint *ck)
{
    const int real_bytes = (int)sizeof(amsph_real);
    herr_t status = amsph_h5_write_attribute(file, "dim", H5T_NATIVE_INT, &ck->dim);
    if (status >= 0)
        status = amsph_h5_write_attribute(file, "real_bytes", H5T_NATIVE_INT, &real_bytes);
    if (status >= 0)
        status = amsph_h5_write_attribute(file, "case_hash", H5T_NATIVE_ULLONG, &ck->case_hash);
    if (status >= 0)
        status = amsph_h5_write_string_attribute(file, "case_path", ck->case_path);
    if (status >= 0)
        status = write_particles(file, "particles", &ck->state.particles);
    if (status >= 0)
        status = write_particles(file, "last_good", &ck->state.last_good);
    if (status >= 0)
        status = write_scalars(file, ck->state.scalar);
    if (status >= 0)
        status = write_run(file, &ck->run);
    if (status >= 0)
        status = amsph_h5_write_attribute(file, "grain_values", H5T_NATIVE_INT, &ck->state.grain_values);
    if (status >= 0 && ck->state.grain_values > 0)
        status = amsph_h5_write_array(file, "grains", amsph_h5_field_type(AMSPH_TYPE_REAL), ck->state.grain_values,
                                      ck->state.grains);
    return status;
}

int amsph_checkpoint_write(const char *path, const amsph_checkpoint *ck)
{
    amsph_h5_quiet();
    hid_t file = amsph_h5_create_in_memory(path);
    if (file < 0)
        return amsph_fail("cannot create %s in memory", path);
    if (write_contents(file, ck) < 0) {
        H5Fclose(file);
        return amsph_fail("cannot assemble %s in memory (out of memory?)", path);
    }
    unsigned char *image = NULL;
    size_t size = 0;
    AMSPH_CHECK(amsph_h5_close_to_image(file, path, TRAILER_BYTES, &image, &size));
    append_trailer(image, size);
    const int status = amsph_write_file(path, image, size + TRAILER_BYTES);
    free(image);
    return status;
}

/* ---- reading ------------------------------------------------------------- */

static int read_string_attribute(hid_t object, const char *what, const char *name, char *out, size_t size)
{
    hid_t attr = H5Aexists(object, name) > 0 ? H5Aopen(object, name, H5P_DEFAULT) : -1;
    hid_t type = attr < 0 ? -1 : H5Aget_type(attr);
    int status = 0;
    if (type < 0 || H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) ||
        H5Tget_size(type) >= size)
        status = amsph_bad_input("%s: attribute '%s' is missing or not a short string", what, name);
    else if (H5Aread(attr, type, out) < 0)
        status = amsph_bad_input("%s: attribute '%s' cannot be read", what, name);
    else
        out[H5Tget_size(type)] = '\0';
    if (type >= 0)
        H5Tclose(type);
    if (attr >= 0)
        H5Aclose(attr);
    return status;
}

static int read_root(hid_t file, const char *path, amsph_checkpoint *ck)
{
    int real_bytes = 0;
    AMSPH_CHECK(amsph_h5_read_attribute(file, path, "dim", H5T_NATIVE_INT, &ck->dim));
    AMSPH_CHECK(amsph_h5_read_attribute(file, path, "real_bytes", H5T_NATIVE_INT, &real_bytes));
    AMSPH_CHECK(amsph_h5_read_attribute(file, path, "case_hash", H5T_NATIVE_ULLONG, &ck->case_hash));
    AMSPH_CHECK(read_string_attribute(file, path, "case_path", ck->case_path, sizeof ck->case_path));
    if (ck->dim != 2 && ck->dim != 3)
        return amsph_bad_input("%s: dimension %d is not 2 or 3", path, ck->dim);
    if (real_bytes != (int)sizeof(amsph_real))
        return amsph_bad_input("%s was written by a build with %d-byte reals; this build has %d-byte "
                               "reals (AMSPH_DOUBLE=%s)",
                               path, real_bytes, (int)sizeof(amsph_real), AMSPH_DOUBLE ? "ON" : "OFF");
    return 0;
}

/* Bad input naming a dataset of the group that is not a field of this build. */
static int check_no_unknown(hid_t group, const char *what, int known)
{
    H5G_info_t info;
    if (H5Gget_info(group, &info) < 0)
        return amsph_bad_input("%s cannot be listed", what);
    for (hsize_t k = 0; k < info.nlinks && (int)info.nlinks != known; ++k) {
        char name[64] = "";
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT);
        int f = 0;
        while (f < AMSPH_FIELD_COUNT && strcmp(name, amsph_fields[f].name))
            ++f;
        if (f == AMSPH_FIELD_COUNT)
            return amsph_bad_input("%s: its field set differs from this build's: '%s' is not a field "
                                   "amsph knows",
                                   what, name);
    }
    return 0;
}

static int read_fields(hid_t group, const char *what, amsph_host_particles *h)
{
    AMSPH_CHECK(amsph_h5_field_rows(group, what, AMSPH_FIELD_POSITION, &h->n));
    int known = 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f) {
        if (H5Lexists(group, amsph_fields[f].name, H5P_DEFAULT) <= 0)
            continue;
        AMSPH_CHECK(amsph_h5_read_field(group, what, h, (amsph_field_id)f));
        ++known;
    }
    return check_no_unknown(group, what, known);
}

typedef int (*group_reader)(hid_t group, const char *what, void *target);

/* Opens group `name` of the file and hands it to read. */
static int read_group(hid_t file, const char *path, const char *name, group_reader read, void *target)
{
    char what[1100];
    snprintf(what, sizeof what, "%s /%s", path, name);
    if (H5Lexists(file, name, H5P_DEFAULT) <= 0)
        return amsph_bad_input("%s: the group is missing", what);
    hid_t group = H5Gopen2(file, name, H5P_DEFAULT);
    if (group < 0)
        return amsph_bad_input("%s is not a readable group", what);
    const int status = read(group, what, target);
    H5Gclose(group);
    return status;
}

static int read_particles(hid_t group, const char *what, void *target)
{
    return read_fields(group, what, target);
}

static int read_scalars(hid_t group, const char *what, void *target)
{
    amsph_scalar_value *v = target;
    for (int k = 0; k < AMSPH_SIM_SCALAR_COUNT; ++k)
        AMSPH_CHECK(amsph_h5_read_attribute(group, what, amsph_sim_scalars[k].name,
                                            scalar_type(&amsph_sim_scalars[k]), &v[k]));
    return 0;
}

static int read_snapshot_list(hid_t group, const char *what, amsph_snapshot_list *l)
{
    int count = 0;
    AMSPH_CHECK(amsph_h5_read_attribute(group, what, "snapshots", H5T_NATIVE_INT, &count));
    if (count < 0)
        return amsph_bad_input("%s: %d snapshots", what, count);
    const size_t slots = count > 0 ? (size_t)count : 1;
    l->time = malloc(slots * sizeof *l->time);
    l->particles = malloc(slots * sizeof *l->particles);
    if (!l->time || !l->particles)
        return amsph_fail("out of host memory for an index of %d snapshots", count);
    l->capacity = l->count = count;
    AMSPH_CHECK(amsph_h5_read_array(group, what, "snapshot_time", H5T_NATIVE_DOUBLE, count, l->time));
    return amsph_h5_read_array(group, what, "snapshot_particles", H5T_NATIVE_INT, count, l->particles);
}

static int read_run(hid_t group, const char *what, void *target)
{
    amsph_run_record *r = target;
    AMSPH_CHECK(amsph_h5_read_attribute(group, what, "next_output", H5T_NATIVE_LLONG, &r->next_output));
    AMSPH_CHECK(amsph_h5_read_attribute(group, what, "wall_seconds", H5T_NATIVE_DOUBLE, &r->wall_seconds));
    AMSPH_CHECK(amsph_h5_read_attribute(group, what, "series_bytes", H5T_NATIVE_LLONG, &r->series_bytes));
    if (r->next_output < 0 || r->series_bytes < 0)
        return amsph_bad_input("%s: negative next_output or series_bytes", what);
    return read_snapshot_list(group, what, &r->snapshots);
}

/* The grain records (the grains module), after the other groups. */
static int read_grains(hid_t file, const char *path, amsph_sim_state *st)
{
    AMSPH_CHECK(amsph_h5_read_attribute(file, path, "grain_values", H5T_NATIVE_INT, &st->grain_values));
    if (st->grain_values < 0)
        return amsph_bad_input("%s: %d grain values", path, st->grain_values);
    if (st->grain_values == 0)
        return 0;
    st->grains = malloc((size_t)st->grain_values * sizeof *st->grains);
    if (!st->grains)
        return amsph_fail("out of host memory for %d grain values", st->grain_values);
    return amsph_h5_read_array(file, path, "grains", amsph_h5_field_type(AMSPH_TYPE_REAL), st->grain_values,
                               st->grains);
}

static int read_contents(hid_t file, const char *path, amsph_checkpoint *ck)
{
    AMSPH_CHECK(read_root(file, path, ck));
    AMSPH_CHECK(read_group(file, path, "particles", read_particles, &ck->state.particles));
    AMSPH_CHECK(read_group(file, path, "last_good", read_particles, &ck->state.last_good));
    AMSPH_CHECK(read_group(file, path, "sim", read_scalars, ck->state.scalar));
    AMSPH_CHECK(read_group(file, path, "run", read_run, &ck->run));
    return read_grains(file, path, &ck->state);
}

int amsph_checkpoint_read(const char *path, amsph_checkpoint *ck)
{
    memset(ck, 0, sizeof *ck);
    AMSPH_CHECK(verify_file(path));
    amsph_h5_quiet();
    hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file < 0)
        return amsph_bad_input("%s: its checksum is right but HDF5 cannot open it", path);
    const int status = read_contents(file, path, ck);
    H5Fclose(file);
    return status;
}

int amsph_checkpoint_check_case(const amsph_checkpoint *ck, const char *path, const amsph_case *c)
{
    if (ck->dim != c->dim)
        return amsph_bad_input("%s is a %dD checkpoint; the case %s is %dD", path, ck->dim, c->path, c->dim);
    if (ck->case_hash != c->text_hash)
        return amsph_bad_input("%s was written for another case (%s): the text of %s differs from it; "
                               "restart with the case file the run began with",
                               path, ck->case_path, c->path);
    return 0;
}

void amsph_checkpoint_free(amsph_checkpoint *ck)
{
    amsph_sim_state_free(&ck->state);
    amsph_snapshot_list_free(&ck->run.snapshots);
    memset(ck, 0, sizeof *ck);
}
