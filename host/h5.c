#include "h5.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "error.h"

hid_t amsph_h5_create_in_memory(const char *name)
{
    hid_t access = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_fapl_core(access, 1 << 20, 0);
    hid_t file = H5Fcreate(name, H5F_ACC_TRUNC, H5P_DEFAULT, access);
    H5Pclose(access);
    return file;
}

int amsph_h5_close_to_image(hid_t file, const char *path, size_t spare, unsigned char **image, size_t *size)
{
    const ssize_t bytes = H5Fflush(file, H5F_SCOPE_GLOBAL) < 0 ? -1 : H5Fget_file_image(file, NULL, 0);
    *image = bytes > 0 ? malloc((size_t)bytes + spare) : NULL;
    int ok = *image && H5Fget_file_image(file, *image, (size_t)bytes) == bytes;
    ok = H5Fclose(file) >= 0 && ok;
    if (!ok) {
        free(*image);
        *image = NULL;
        return amsph_fail("cannot assemble %s in memory (out of memory?)", path);
    }
    *size = (size_t)bytes;
    return 0;
}

int amsph_write_file(const char *path, const void *bytes, size_t size)
{
    char tmp[1100];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
        return amsph_fail("path too long: %s", path);
    FILE *f = fopen(tmp, "wb");
    if (!f)
        return amsph_fail("cannot create %s: %s", tmp, strerror(errno));
    int failed = fwrite(bytes, 1, size, f) != size || fflush(f) || fsync(fileno(f));
    const int error = errno;
    failed = fclose(f) || failed;
    if (failed || rename(tmp, path)) {
        const int reason = failed ? error : errno;
        remove(tmp);
        return amsph_fail("cannot write %s: %s", path, strerror(reason));
    }
    return 0;
}

void amsph_h5_quiet(void) { H5Eset_auto2(H5E_DEFAULT, NULL, NULL); }

hid_t amsph_h5_field_type(amsph_field_type t)
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

herr_t amsph_h5_write_attribute(hid_t object, const char *name, hid_t type, const void *value)
{
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t attr = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    herr_t status = attr < 0 ? -1 : H5Awrite(attr, type, value);
    if (attr >= 0)
        H5Aclose(attr);
    H5Sclose(space);
    return status;
}

herr_t amsph_h5_write_string_attribute(hid_t object, const char *name, const char *value)
{
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, strlen(value) + 1);
    herr_t status = amsph_h5_write_attribute(object, name, type, value);
    H5Tclose(type);
    return status;
}

static herr_t write_dataset(hid_t location, const char *name, hid_t type, int rank, const hsize_t *dims,
                            const void *data)
{
    hid_t space = H5Screate_simple(rank, dims, NULL);
    hid_t set = H5Dcreate2(location, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    herr_t status = set < 0 ? -1 : H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    if (set >= 0)
        H5Dclose(set);
    H5Sclose(space);
    return status;
}

herr_t amsph_h5_write_array(hid_t location, const char *name, hid_t type, int n, const void *data)
{
    const hsize_t dims[1] = {(hsize_t)n};
    return write_dataset(location, name, type, 1, dims, data);
}

herr_t amsph_h5_write_field(hid_t location, const amsph_host_particles *h, amsph_field_id f)
{
    const amsph_field_info *info = &amsph_fields[f];
    const hsize_t dims[2] = {(hsize_t)h->n, (hsize_t)info->components};
    herr_t status = write_dataset(location, info->name, amsph_h5_field_type(info->type),
                                  info->components > 1 ? 2 : 1, dims, h->data[f]);
    if (status < 0)
        return status;
    hid_t set = H5Dopen2(location, info->name, H5P_DEFAULT);
    status = set < 0 ? -1 : amsph_h5_write_string_attribute(set, "unit", info->unit);
    if (set >= 0)
        H5Dclose(set);
    return status;
}

/* 0 if the stored type has the class, size and sign of the wanted one. */
static int same_type(hid_t stored, hid_t wanted)
{
    const H5T_class_t c = H5Tget_class(stored);
    if (c != H5Tget_class(wanted) || H5Tget_size(stored) != H5Tget_size(wanted))
        return 1;
    return c == H5T_INTEGER && H5Tget_sign(stored) != H5Tget_sign(wanted);
}

static const char *type_text(hid_t t)
{
    const H5T_class_t c = H5Tget_class(t);
    if (c == H5T_FLOAT)
        return H5Tget_size(t) == 8 ? "float64" : H5Tget_size(t) == 4 ? "float32" : "a float";
    if (c == H5T_INTEGER)
        return H5Tget_size(t) == 8 ? "int64" : H5Tget_size(t) == 4 ? "int32" : "an integer";
    return c == H5T_STRING ? "a string" : "an unknown type";
}

int amsph_h5_read_attribute(hid_t object, const char *what, const char *name, hid_t type, void *value)
{
    if (H5Aexists(object, name) <= 0)
        return amsph_bad_input("%s: attribute '%s' is missing", what, name);
    hid_t attr = H5Aopen(object, name, H5P_DEFAULT);
    hid_t stored = attr < 0 ? -1 : H5Aget_type(attr);
    hid_t space = attr < 0 ? -1 : H5Aget_space(attr);
    int status = 0;
    if (stored < 0 || space < 0 || H5Sget_simple_extent_npoints(space) != 1)
        status = amsph_bad_input("%s: attribute '%s' is unreadable or not a single value", what, name);
    else if (same_type(stored, type))
        status = amsph_bad_input("%s: attribute '%s' is %s, expected %s", what, name, type_text(stored),
                                 type_text(type));
    else if (H5Aread(attr, type, value) < 0)
        status = amsph_bad_input("%s: attribute '%s' cannot be read", what, name);
    if (space >= 0)
        H5Sclose(space);
    if (stored >= 0)
        H5Tclose(stored);
    if (attr >= 0)
        H5Aclose(attr);
    return status;
}

/* Opens dataset `name`, checks its element type and shape (rank 1 when
 * columns is 1, else rows x columns) and returns its rows. */
static int open_checked(hid_t location, const char *what, const char *name, hid_t type, int columns,
                        hid_t *set, int *rows)
{
    if (H5Lexists(location, name, H5P_DEFAULT) <= 0)
        return amsph_bad_input("%s: dataset '%s' is missing", what, name);
    *set = H5Dopen2(location, name, H5P_DEFAULT);
    if (*set < 0)
        return amsph_bad_input("%s: '%s' is not a readable dataset", what, name);
    hid_t stored = H5Dget_type(*set);
    hid_t space = H5Dget_space(*set);
    hsize_t dims[2] = {0, 0};
    const int rank = space < 0 ? -1 : H5Sget_simple_extent_ndims(space);
    if (rank >= 1 && rank <= 2)
        H5Sget_simple_extent_dims(space, dims, NULL);
    int status = 0;
    if (stored < 0 || same_type(stored, type))
        status = amsph_bad_input("%s: dataset '%s' is %s, expected %s", what, name,
                                 stored < 0 ? "unreadable" : type_text(stored), type_text(type));
    else if (rank != (columns > 1 ? 2 : 1) || (rank == 2 && dims[1] != (hsize_t)columns) ||
             dims[0] > INT_MAX)
        status = amsph_bad_input("%s: dataset '%s' should be N x %d", what, name, columns);
    *rows = (int)dims[0];
    if (space >= 0)
        H5Sclose(space);
    if (stored >= 0)
        H5Tclose(stored);
    if (status) {
        H5Dclose(*set);
        *set = -1;
    }
    return status;
}

static int read_checked(hid_t location, const char *what, const char *name, hid_t type, int columns,
                        int n, void *data)
{
    hid_t set = -1;
    int rows = 0;
    AMSPH_CHECK(open_checked(location, what, name, type, columns, &set, &rows));
    int status = 0;
    if (rows != n)
        status = amsph_bad_input("%s: dataset '%s' has %d rows, expected %d", what, name, rows, n);
    else if (n > 0 && H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
        status = amsph_bad_input("%s: dataset '%s' cannot be read", what, name);
    H5Dclose(set);
    return status;
}

int amsph_h5_read_array(hid_t location, const char *what, const char *name, hid_t type, int n, void *data)
{
    return read_checked(location, what, name, type, 1, n, data);
}

int amsph_h5_field_rows(hid_t location, const char *what, amsph_field_id f, int *rows)
{
    const amsph_field_info *info = &amsph_fields[f];
    hid_t set = -1;
    AMSPH_CHECK(open_checked(location, what, info->name, amsph_h5_field_type(info->type), info->components,
                             &set, rows));
    H5Dclose(set);
    return 0;
}

int amsph_h5_read_field(hid_t location, const char *what, amsph_host_particles *h, amsph_field_id f)
{
    const amsph_field_info *info = &amsph_fields[f];
    AMSPH_CHECK(amsph_host_add_field(h, f));
    return read_checked(location, what, info->name, amsph_h5_field_type(info->type), info->components,
                        h->n, h->data[f]);
}
