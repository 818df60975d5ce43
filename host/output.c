#include "output.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "error.h"
#include "h5.h"

int amsph_snapshot_list_add(amsph_snapshot_list *l, double time, int particles)
{
    if (l->count == l->capacity) {
        const int capacity = l->capacity ? 2 * l->capacity : 64;
        double *times = realloc(l->time, (size_t)capacity * sizeof *times);
        if (times)
            l->time = times;
        int *counts = realloc(l->particles, (size_t)capacity * sizeof *counts);
        if (counts)
            l->particles = counts;
        if (!times || !counts)
            return amsph_fail("out of host memory for the snapshot index");
        l->capacity = capacity;
    }
    l->time[l->count] = time;
    l->particles[l->count] = particles;
    ++l->count;
    return 0;
}

int amsph_snapshot_list_copy(amsph_snapshot_list *dst, const amsph_snapshot_list *src)
{
    for (int k = 0; k < src->count; ++k)
        AMSPH_CHECK(amsph_snapshot_list_add(dst, src->time[k], src->particles[k]));
    return 0;
}

void amsph_snapshot_list_free(amsph_snapshot_list *l)
{
    free(l->time);
    free(l->particles);
    memset(l, 0, sizeof *l);
}

int amsph_output_check_dir(const char *dir, int force)
{
    struct stat st;
    if (stat(dir, &st))
        return 0; /* missing, or unreachable: creating it says why */
    if (!S_ISDIR(st.st_mode))
        return amsph_bad_input("output directory %s exists and is not a directory", dir);
    DIR *d = opendir(dir);
    if (!d)
        return amsph_fail("cannot read the output directory %s: %s", dir, strerror(errno));
    const struct dirent *e;
    while ((e = readdir(d)) && (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")))
        ;
    char example[256];
    snprintf(example, sizeof example, "%s", e ? e->d_name : "");
    closedir(d);
    if (example[0] && !force)
        return amsph_bad_input("output directory %s already holds files (%s, ...); choose another "
                               "or pass --force to replace the run in it",
                               dir, example);
    return 0;
}

/* The directory part of a path ("." when it has none). */
static void directory_of(const char *file, char *dir, size_t size)
{
    snprintf(dir, size, "%s", file);
    char *slash = strrchr(dir, '/');
    if (!slash)
        snprintf(dir, size, ".");
    else
        slash[slash == dir ? 1 : 0] = '\0';
}

int amsph_output_holds(const char *dir, const char *file)
{
    char parent[1024];
    directory_of(file, parent, sizeof parent);
    struct stat a, b;
    return !stat(dir, &a) && !stat(parent, &b) && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

static int make_dirs(const char *dir)
{
    char path[1024];
    if (snprintf(path, sizeof path, "%s", dir) >= (int)sizeof path)
        return amsph_fail("output directory name too long: %s", dir);
    for (char *p = path + 1; *p; ++p) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(path, 0777) && errno != EEXIST)
            return amsph_fail("cannot create directory %s: %s", path, strerror(errno));
        *p = '/';
    }
    if (mkdir(path, 0777) && errno != EEXIST)
        return amsph_fail("cannot create directory %s: %s", path, strerror(errno));
    return 0;
}

int amsph_output_open(amsph_output *o, const char *dir, int dim, double dx, int force)
{
    memset(o, 0, sizeof *o);
    if (snprintf(o->dir, sizeof o->dir, "%s", dir) >= (int)sizeof o->dir)
        return amsph_bad_input("output directory name too long: %s", dir);
    o->dim = dim;
    o->dx = dx;
    amsph_h5_quiet();
    AMSPH_CHECK(amsph_output_check_dir(dir, force));
    return make_dirs(dir);
}

int amsph_output_continue(amsph_output *o, const amsph_snapshot_list *earlier, int in_place)
{
    AMSPH_CHECK(amsph_snapshot_list_copy(&o->list, earlier));
    o->first = in_place ? 0 : earlier->count;
    return 0;
}

/* The number of a snapshot file named snap_N.h5 (N in digits); -1 for any
 * other name. */
static long snapshot_number(const char *name)
{
    if (strncmp(name, "snap_", 5) || !isdigit((unsigned char)name[5]))
        return -1;
    char *end = NULL;
    const long k = strtol(name + 5, &end, 10);
    return strcmp(end, ".h5") ? -1 : k;
}

static int remove_file(const amsph_output *o, const char *name)
{
    char path[1100];
    AMSPH_CHECK(amsph_output_path(o, name, path, sizeof path));
    if (unlink(path) && errno != ENOENT)
        return amsph_fail("cannot remove %s: %s", path, strerror(errno));
    return 0;
}

int amsph_output_clear(const amsph_output *o, int in_place)
{
    static const char *const run_files[] = {AMSPH_OUTPUT_INDEX, AMSPH_OUTPUT_SERIES, AMSPH_OUTPUT_CHECKPOINT,
                                            AMSPH_OUTPUT_ANALYSIS};
    for (size_t k = 0; k < sizeof run_files / sizeof run_files[0] && !in_place; ++k)
        AMSPH_CHECK(remove_file(o, run_files[k]));
    DIR *d = opendir(o->dir);
    if (!d)
        return amsph_fail("cannot read the output directory %s: %s", o->dir, strerror(errno));
    const long from = in_place ? o->list.count : 0;
    int status = 0;
    for (const struct dirent *e; !status && (e = readdir(d));)
        if (snapshot_number(e->d_name) >= from)
            status = remove_file(o, e->d_name);
    closedir(d);
    return status;
}

void amsph_output_close(amsph_output *o)
{
    amsph_snapshot_list_free(&o->list);
    memset(o, 0, sizeof *o);
}

int amsph_output_path(const amsph_output *o, const char *name, char *path, size_t size)
{
    if (snprintf(path, size, "%s/%s", o->dir, name) >= (int)size)
        return amsph_fail("path too long: %s/%s", o->dir, name);
    return 0;
}

static herr_t write_snapshot_contents(hid_t file, const amsph_output *o, const amsph_host_particles *h,
                                      double time, long long step)
{
    herr_t status = 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT && status >= 0; ++f)
        if (h->data[f] && (amsph_fields[f].flags & AMSPH_FIELD_OUTPUT))
            status = amsph_h5_write_field(file, h, (amsph_field_id)f);
    if (status >= 0)
        status = amsph_h5_write_attribute(file, "time", H5T_NATIVE_DOUBLE, &time);
    if (status >= 0)
        status = amsph_h5_write_attribute(file, "step", H5T_NATIVE_LLONG, &step);
    if (status >= 0)
        status = amsph_h5_write_attribute(file, "dim", H5T_NATIVE_INT, &o->dim);
    if (status >= 0)
        status = amsph_h5_write_attribute(file, "dx", H5T_NATIVE_DOUBLE, &o->dx);
    return status;
}

static int write_snapshot_file(const char *path, const amsph_output *o, const amsph_host_particles *h,
                               double time, long long step)
{
    hid_t file = amsph_h5_create_in_memory(path);
    if (file < 0)
        return amsph_fail("cannot create %s in memory", path);
    if (write_snapshot_contents(file, o, h, time, step) < 0) {
        H5Fclose(file);
        return amsph_fail("cannot assemble %s in memory (out of memory?)", path);
    }
    unsigned char *image = NULL;
    size_t size = 0;
    AMSPH_CHECK(amsph_h5_close_to_image(file, path, 0, &image, &size));
    const int status = amsph_write_file(path, image, size);
    free(image);
    return status;
}

static const char *xdmf_number_type(amsph_field_type t)
{
    return t == AMSPH_TYPE_REAL ? "Float" : t == AMSPH_TYPE_INT ? "Int" : "UInt";
}

static void write_xdmf_grid(FILE *f, const amsph_output *o, int k)
{
    const int n = o->list.particles[k];
    fprintf(f, "      <Grid Name=\"snap_%06d\" GridType=\"Uniform\">\n", k);
    fprintf(f, "        <Time Value=\"%.17g\"/>\n", o->list.time[k]);
    fprintf(f, "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\"/>\n", n);
    fprintf(f, "        <Geometry GeometryType=\"XYZ\">\n");
    fprintf(f, "          <DataItem Dimensions=\"%d 3\" NumberType=\"Float\" Precision=\"%zu\" "
               "Format=\"HDF\">snap_%06d.h5:/position</DataItem>\n",
            n, sizeof(amsph_real), k);
    fprintf(f, "        </Geometry>\n");
    for (int id = 0; id < AMSPH_FIELD_COUNT; ++id) {
        const amsph_field_info *info = &amsph_fields[id];
        if (!(o->present & (1u << id)) || id == AMSPH_FIELD_POSITION)
            continue;
        const int vector = info->components == 3;
        fprintf(f, "        <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n",
                info->name, vector ? "Vector" : "Scalar");
        fprintf(f, "          <DataItem Dimensions=\"%d%s\" NumberType=\"%s\" Precision=\"%zu\" "
                   "Format=\"HDF\">snap_%06d.h5:/%s</DataItem>\n",
                n, vector ? " 3" : "", xdmf_number_type(info->type),
                info->type == AMSPH_TYPE_REAL ? sizeof(amsph_real) : (size_t)4, k, info->name);
        fprintf(f, "        </Attribute>\n");
    }
    fprintf(f, "      </Grid>\n");
}

static int write_xdmf(const amsph_output *o)
{
    char path[1100], *text = NULL;
    size_t size = 0;
    AMSPH_CHECK(amsph_output_path(o, AMSPH_OUTPUT_INDEX, path, sizeof path));
    FILE *f = open_memstream(&text, &size);
    if (!f)
        return amsph_fail("out of host memory for %s", path);
    fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n");
    fprintf(f, "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
    for (int k = o->first; k < o->list.count; ++k)
        write_xdmf_grid(f, o, k);
    fprintf(f, "    </Grid>\n  </Domain>\n</Xdmf>\n");
    const int status =
        fclose(f) ? amsph_fail("out of host memory for %s", path) : amsph_write_file(path, text, size);
    free(text);
    return status;
}

int amsph_output_snapshot(amsph_output *o, const amsph_host_particles *h, double time, long long step)
{
    char name[32], path[1100];
    snprintf(name, sizeof name, "snap_%06d.h5", o->list.count);
    AMSPH_CHECK(amsph_output_path(o, name, path, sizeof path));
    AMSPH_CHECK(write_snapshot_file(path, o, h, time, step));
    AMSPH_CHECK(amsph_snapshot_list_add(&o->list, time, h->n));
    o->present = 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f)
        if (h->data[f] && (amsph_fields[f].flags & AMSPH_FIELD_OUTPUT))
            o->present |= 1u << f;
    return write_xdmf(o);
}
