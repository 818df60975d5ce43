/* The device interface: buffers, program build, kernel launch by name,
 * reductions. A backend is a table of functions behind an opaque handle
 * (ggml's backend interface, PETSc's registry by name). Kernels are the
 * single-source files in kernels/; each backend runs the same code.
 *
 * Ownership: a buffer belongs to the backend that allocated it and is freed
 * with amsph_buffer_free; the backend must outlive its buffers. */
#ifndef AMSPH_BACKEND_H
#define AMSPH_BACKEND_H

#include <stddef.h>

typedef struct amsph_backend amsph_backend;
typedef struct amsph_buffer amsph_buffer;

/* The largest value argument (a module's parameter struct; host/sim.h
 * checks each at compile time: in a double build fluid_params outgrew an
 * earlier 128 and the copy ran past the end). */
#define AMSPH_ARG_MAX_BYTES 256

/* A kernel argument: a buffer, or a value (scalar or plain struct) copied in. */
typedef struct {
    amsph_buffer *buffer; /* NULL for a value */
    size_t size;          /* bytes of value */
    union {
        double d;
        long long l;
        unsigned char bytes[AMSPH_ARG_MAX_BYTES];
    } value;
} amsph_arg;

amsph_arg amsph_arg_buffer(amsph_buffer *buffer);
amsph_arg amsph_arg_int(int v);
amsph_arg amsph_arg_uint(unsigned v);
amsph_arg amsph_arg_real(double v); /* converted to the build's `real` */
amsph_arg amsph_arg_bytes(const void *v, size_t size);

/* What a program is specialised for: the -D options of the kernel build. */
typedef struct {
    int dim;    /* 2 or 3 */
    int kernel; /* 0 Wendland C2, 1 quintic spline */
} amsph_build_options;

typedef struct {
    const char *name;
    int (*alloc)(amsph_backend *, size_t bytes, amsph_buffer **out);
    void (*free)(amsph_backend *, amsph_buffer *);
    size_t (*size)(amsph_backend *, amsph_buffer *);
    int (*upload)(amsph_backend *, amsph_buffer *, size_t offset, size_t bytes, const void *src);
    int (*download)(amsph_backend *, amsph_buffer *, size_t offset, size_t bytes, void *dst);
    int (*build)(amsph_backend *, const amsph_build_options *);
    int (*launch)(amsph_backend *, const char *kernel, int items, int nargs, const amsph_arg *args);
    int (*sync)(amsph_backend *);
    void (*destroy)(amsph_backend *);
} amsph_backend_iface;

/* Wall time of each kernel by name (`amsph bench throughput --kernels`).
 * With a profile attached, amsph_launch waits for every kernel it starts
 * and charges the time from the start to the end of that wait to the
 * kernel's name: on a GPU the launch's own cost included, on host threads
 * the kernel's run. */
#define AMSPH_PROFILE_KERNELS 128
typedef struct {
    char name[64];
    long long launches;
    double seconds;
} amsph_kernel_time;

typedef struct {
    int count;     /* kernels in the table */
    int untracked; /* launches past a full table, not charged */
    amsph_kernel_time kernel[AMSPH_PROFILE_KERNELS];
} amsph_kernel_profile;

struct amsph_backend {
    const amsph_backend_iface *iface;
    void *impl;
    char description[256]; /* device and platform, for logs and benchmarks */
    amsph_buffer *reduce_partial; /* scratch of the two-stage reductions */
    size_t allocated;             /* bytes in live buffers */
    amsph_kernel_profile *profile; /* non-NULL: each launch waited for and timed */
};

/* Creates the backend named "openmp" or "opencl"; device < 0 picks the
 * first OpenCL device (or AMSPH_DEVICE from the environment). */
int amsph_backend_create(const char *name, int device, amsph_backend **out);
void amsph_backend_destroy(amsph_backend *);
/* Prints the OpenCL platforms and devices and the OpenMP backend. */
void amsph_backend_list(void *file /* FILE * */);

int amsph_buffer_alloc(amsph_backend *, size_t bytes, amsph_buffer **out);
void amsph_buffer_free(amsph_backend *, amsph_buffer *);
int amsph_upload(amsph_backend *, amsph_buffer *, size_t offset, size_t bytes, const void *src);
int amsph_download(amsph_backend *, amsph_buffer *, size_t offset, size_t bytes, void *dst);
int amsph_build(amsph_backend *, const amsph_build_options *);
int amsph_launch(amsph_backend *, const char *kernel, int items, int nargs, const amsph_arg *args);
int amsph_sync(amsph_backend *);

/* Sum, maximum and minimum of n `real` values of a buffer (host result in double). */
int amsph_reduce_sum(amsph_backend *, amsph_buffer *, int n, double *out);
int amsph_reduce_max(amsph_backend *, amsph_buffer *, int n, double *out);
int amsph_reduce_min(amsph_backend *, amsph_buffer *, int n, double *out);

/* Launch with the arguments written inline: AMSPH_LAUNCH(b, "name", n, arg...). */
#define AMSPH_LAUNCH(backend, kernel, items, ...)                                                  \
    amsph_launch((backend), (kernel), (items),                                                     \
                 (int)(sizeof((amsph_arg[]){__VA_ARGS__}) / sizeof(amsph_arg)),                    \
                 (amsph_arg[]){__VA_ARGS__})

#endif
