#include "output.h"

#include <errno.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "error.h"

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

int amsph_output_open(amsph_output *o, const char *dir, int dim, double dx)
{
    memset(o, 0, sizeof *o);
    if (snprintf(o->dir, sizeof o->dir, "%s", dir) >= (int)sizeof o->dir)
        return amsph_fail("output directory name too long: %s", dir);
    o->dim = dim;
    o->dx = dx;
    return make_dirs(dir);
}

void amsph_output_close(amsph_output *o)
{
    free(o->times);
    free(o->particles);
    memset(o, 0, sizeof *o);
}

static hid_t native_type(amsph_field_type t)
{
    switch (t) {
    case AMSPH_TYPE_INT:
        return H5T_NATIVE_INT;
    case AMSPH_TYPE_UINT:
        return H5T_NATIVE_UINT;
    case AMSPH_TYPE_REAL:
        break;
    }
    return sizeof(amsph_real) == 8 ? H5T_NATIVE_DOUBLE : H5T_NATIVE_FLOAT;
}

static herr_t write_scalar_attribute(hid_t object, const char *name, hid_t type, const void *value)
{
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t attr = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    herr_t status = attr < 0 ? -1 : H5Awrite(attr, type, value);
    if (attr >= 0)
        H5Aclose(attr);
    H5Sclose(space);
    return status;
}

static herr_t write_string_attribute(hid_t object, const char *name, const char *value)
{
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, strlen(value) + 1);
    herr_t status = write_scalar_attribute(object, name, type, value);
    H5Tclose(type);
    return status;
}

static herr_t write_field(hid_t file, const amsph_host_particles *h, amsph_field_id f)
{
    const amsph_field_info *info = &amsph_fields[f];
    hsize_t dims[2] = {(hsize_t)h->n, (hsize_t)info->components};
    hid_t space = H5Screate_simple(info->components > 1 ? 2 : 1, dims, NULL);
    hid_t type = native_type(info->type);
    hid_t set = H5Dcreate2(file, info->name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    herr_t status = set < 0 ? -1 : H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, h->data[f]);
    if (status >= 0)
        status = write_string_attribute(set, "unit", info->unit);
    if (set >= 0)
        H5Dclose(set);
    H5Sclose(space);
    return status;
}

static int write_snapshot_file(const char *path, const amsph_output *o,
                               const amsph_host_particles *h, double time, long long step)
{
    hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file < 0)
        return amsph_fail("cannot create %s (is the directory writable, the disk full?)", path);
    herr_t status = 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT && status >= 0; ++f)
        if (h->data[f] && (amsph_fields[f].flags & AMSPH_FIELD_OUTPUT))
            status = write_field(file, h, (amsph_field_id)f);
    const int dim = o->dim;
    if (status >= 0)
        status = write_scalar_attribute(file, "time", H5T_NATIVE_DOUBLE, &time);
    if (status >= 0)
        status = write_scalar_attribute(file, "step", H5T_NATIVE_LLONG, &step);
    if (status >= 0)
        status = write_scalar_attribute(file, "dim", H5T_NATIVE_INT, &dim);
    if (status >= 0)
        status = write_scalar_attribute(file, "dx", H5T_NATIVE_DOUBLE, &o->dx);
    if (H5Fclose(file) < 0 || status < 0) {
        remove(path);
        return amsph_fail("writing %s failed (disk full?)", path);
    }
    return 0;
}

static const char *xdmf_number_type(amsph_field_type t)
{
    return t == AMSPH_TYPE_REAL ? "Float" : t == AMSPH_TYPE_INT ? "Int" : "UInt";
}

static void write_xdmf_grid(FILE *f, const amsph_output *o, int k)
{
    const int n = o->particles[k];
    fprintf(f, "      <Grid Name=\"snap_%06d\" GridType=\"Uniform\">\n", k);
    fprintf(f, "        <Time Value=\"%.17g\"/>\n", o->times[k]);
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
    char path[1100], tmp[1110];
    snprintf(path, sizeof path, "%s/snapshots.xmf", o->dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return amsph_fail("cannot write %s: %s", tmp, strerror(errno));
    fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n");
    fprintf(f, "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
    for (int k = 0; k < o->count; ++k)
        write_xdmf_grid(f, o, k);
    fprintf(f, "    </Grid>\n  </Domain>\n</Xdmf>\n");
    if (fclose(f) || rename(tmp, path))
        return amsph_fail("cannot write %s: %s", path, strerror(errno));
    return 0;
}

int amsph_output_snapshot(amsph_output *o, const amsph_host_particles *h, double time, long long step)
{
    char path[1100], tmp[1110];
    snprintf(path, sizeof path, "%s/snap_%06d.h5", o->dir, o->count);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    AMSPH_CHECK(write_snapshot_file(tmp, o, h, time, step));
    if (rename(tmp, path))
        return amsph_fail("cannot rename %s to %s: %s", tmp, path, strerror(errno));
    if (o->count == o->capacity) {
        const int capacity = o->capacity ? 2 * o->capacity : 64;
        double *times = realloc(o->times, (size_t)capacity * sizeof *times);
        if (times)
            o->times = times;
        int *particles = realloc(o->particles, (size_t)capacity * sizeof *particles);
        if (particles)
            o->particles = particles;
        if (!times || !particles)
            return amsph_fail("out of host memory for the snapshot index");
        o->capacity = capacity;
    }
    o->times[o->count] = time;
    o->particles[o->count] = h->n;
    o->present = 0;
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f)
        if (h->data[f] && (amsph_fields[f].flags & AMSPH_FIELD_OUTPUT))
            o->present |= 1u << f;
    ++o->count;
    return write_xdmf(o);
}
