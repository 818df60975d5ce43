/* Small HDF5 helpers shared by snapshots and checkpoints: typed attributes,
 * one dataset per particle field (N or N x components, with its unit), and
 * checked readers that say what is missing or of the wrong shape.
 *
 * Writers return a negative value on failure (HDF5's convention); readers
 * return 0 or an amsph status with the message recorded (amsph_fail). */
#ifndef AMSPH_H5_H
#define AMSPH_H5_H

#include <hdf5.h>

#include "particles.h"

/* Files are assembled in memory and then written to disk by amsph, so that
 * a full disk or an unwritable directory is an ordinary write error with a
 * message (HDF5 itself does not recover from failed writes).
 *
 * A new in-memory HDF5 file (named path in messages). */
hid_t amsph_h5_create_in_memory(const char *path);
/* Closes an in-memory file and hands its bytes to the caller (to free()),
 * with `spare` bytes of room after them. */
int amsph_h5_close_to_image(hid_t file, const char *path, size_t spare, unsigned char **image, size_t *size);
/* Writes bytes to path through a temporary name (PATH.tmp), synced to disk
 * and then renamed, so path holds either its old contents or the new. */
int amsph_write_file(const char *path, const void *bytes, size_t size);

/* Turns off HDF5's own printing of error stacks: amsph reports its own. */
void amsph_h5_quiet(void);

/* The native HDF5 type of a field's elements. */
hid_t amsph_h5_field_type(amsph_field_type t);

herr_t amsph_h5_write_attribute(hid_t object, const char *name, hid_t type, const void *value);
herr_t amsph_h5_write_string_attribute(hid_t object, const char *name, const char *value);
/* Dataset `name` of n elements of type (rank 1). */
herr_t amsph_h5_write_array(hid_t location, const char *name, hid_t type, int n, const void *data);
/* Dataset named after field f, from h, with a string attribute `unit`. */
herr_t amsph_h5_write_field(hid_t location, const amsph_host_particles *h, amsph_field_id f);

/* Reads attribute `name` (a scalar of type's class and size) into value;
 * `what` names the file or group in messages. */
int amsph_h5_read_attribute(hid_t object, const char *what, const char *name, hid_t type, void *value);
/* Reads a rank-1 dataset of exactly n elements of type into data. */
int amsph_h5_read_array(hid_t location, const char *what, const char *name, hid_t type, int n, void *data);
/* Number of rows of dataset `name`, checked to be a field of f's shape and
 * element type. */
int amsph_h5_field_rows(hid_t location, const char *what, amsph_field_id f, int *rows);
/* Reads field f into h (which holds h->n particles; the dataset must have
 * h->n rows). */
int amsph_h5_read_field(hid_t location, const char *what, amsph_host_particles *h, amsph_field_id f);

#endif
