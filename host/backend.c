/* Backend registry and the parts every backend shares: argument packing and
 * the two-stage reductions (kernels/reduce.cl). */
#include "backend.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "real.h"
#include "timers.h"

int amsph_backend_openmp_create(amsph_backend **out);
#if AMSPH_HAVE_OPENCL
int amsph_backend_opencl_create(int device, amsph_backend **out);
void amsph_backend_opencl_list(FILE *file);
#endif

/* Reduction chunks: enough items to occupy a device, few partials to read. */
#define REDUCE_CHUNKS 1024
#define REDUCE_SUM 0
#define REDUCE_MAX 1
#define REDUCE_MIN 2

int amsph_backend_create(const char *name, int device, amsph_backend **out)
{
    *out = NULL;
    int status;
    if (strcmp(name, "openmp") == 0) {
        status = amsph_backend_openmp_create(out);
    } else if (strcmp(name, "opencl") == 0) {
#if AMSPH_HAVE_OPENCL
        if (device < 0 && getenv("AMSPH_DEVICE"))
            device = atoi(getenv("AMSPH_DEVICE"));
        status = amsph_backend_opencl_create(device < 0 ? 0 : device, out);
#else
        (void)device;
        return amsph_fail("this amsph was built without OpenCL (AMSPH_OPENCL=OFF); use "
                          "--backend openmp or rebuild with -DAMSPH_OPENCL=ON");
#endif
    } else {
        return amsph_fail("unknown backend '%s' (allowed: openmp, opencl)", name);
    }
    if (status)
        return status;
    status = amsph_buffer_alloc(*out, REDUCE_CHUNKS * sizeof(amsph_real), &(*out)->reduce_partial);
    if (status) {
        amsph_backend_destroy(*out);
        *out = NULL;
    }
    return status;
}

void amsph_backend_destroy(amsph_backend *b)
{
    if (!b)
        return;
    amsph_buffer_free(b, b->reduce_partial);
    b->iface->destroy(b);
}

void amsph_backend_list(void *file)
{
    FILE *f = file;
    amsph_backend *openmp = NULL;
    if (amsph_backend_openmp_create(&openmp) == 0) {
        fprintf(f, "openmp: %s\n", openmp->description);
        openmp->iface->destroy(openmp);
    } else {
        fprintf(f, "openmp: unavailable: %s\n", amsph_last_error());
    }
#if AMSPH_HAVE_OPENCL
    amsph_backend_opencl_list(f);
#else
    fprintf(f, "opencl: not built (AMSPH_OPENCL=OFF)\n");
#endif
}

amsph_arg amsph_arg_buffer(amsph_buffer *buffer)
{
    amsph_arg a = {.buffer = buffer, .size = 0};
    return a;
}

/* A value larger than AMSPH_ARG_MAX_BYTES (host/sim.h rules that out at
 * compile time for the parameter structs) becomes a 0-byte argument, which
 * the launch refuses as the wrong size. */
amsph_arg amsph_arg_bytes(const void *v, size_t size)
{
    amsph_arg a = {.buffer = NULL, .size = size <= AMSPH_ARG_MAX_BYTES ? size : 0};
    memcpy(a.value.bytes, v, a.size);
    return a;
}

amsph_arg amsph_arg_int(int v) { return amsph_arg_bytes(&v, sizeof v); }
amsph_arg amsph_arg_uint(unsigned v) { return amsph_arg_bytes(&v, sizeof v); }

amsph_arg amsph_arg_real(double v)
{
    const amsph_real r = (amsph_real)v;
    return amsph_arg_bytes(&r, sizeof r);
}

int amsph_buffer_alloc(amsph_backend *b, size_t bytes, amsph_buffer **out)
{
    AMSPH_CHECK(b->iface->alloc(b, bytes ? bytes : 1, out));
    b->allocated += b->iface->size(b, *out);
    return 0;
}

void amsph_buffer_free(amsph_backend *b, amsph_buffer *buffer)
{
    if (!buffer)
        return;
    b->allocated -= b->iface->size(b, buffer);
    b->iface->free(b, buffer);
}

int amsph_upload(amsph_backend *b, amsph_buffer *buf, size_t offset, size_t bytes, const void *src)
{
    return bytes ? b->iface->upload(b, buf, offset, bytes, src) : 0;
}

int amsph_download(amsph_backend *b, amsph_buffer *buf, size_t offset, size_t bytes, void *dst)
{
    return bytes ? b->iface->download(b, buf, offset, bytes, dst) : 0;
}

int amsph_build(amsph_backend *b, const amsph_build_options *options)
{
    if (options->dim != 2 && options->dim != 3)
        return amsph_fail("kernel build: dimension must be 2 or 3, got %d", options->dim);
    if (options->kernel != 0 && options->kernel != 1)
        return amsph_fail("kernel build: unknown smoothing kernel %d", options->kernel);
    return b->iface->build(b, options);
}

/* Row of `kernel` in the profile (added if new), or NULL when the table is full. */
static double *kernel_seconds(amsph_kernel_profile *p, const char *kernel)
{
    int k = 0;
    while (k < p->count && strcmp(p->kernel[k].name, kernel) != 0)
        ++k;
    if (k == AMSPH_PROFILE_KERNELS) {
        ++p->untracked;
        return NULL;
    }
    if (k == p->count) {
        snprintf(p->kernel[k].name, sizeof p->kernel[k].name, "%s", kernel);
        ++p->count;
    }
    ++p->kernel[k].launches;
    return &p->kernel[k].seconds;
}

/* A launch waited for and charged to the kernel's name (b->profile). */
static int profiled_launch(amsph_backend *b, const char *kernel, int items, int nargs, const amsph_arg *args)
{
    const double start = amsph_wall_seconds();
    AMSPH_CHECK(b->iface->launch(b, kernel, items, nargs, args));
    AMSPH_CHECK(b->iface->sync(b));
    double *seconds = kernel_seconds(b->profile, kernel);
    if (seconds)
        *seconds += amsph_wall_seconds() - start;
    return 0;
}

int amsph_launch(amsph_backend *b, const char *kernel, int items, int nargs, const amsph_arg *args)
{
    if (items <= 0)
        return 0;
    if (b->profile)
        return profiled_launch(b, kernel, items, nargs, args);
    return b->iface->launch(b, kernel, items, nargs, args);
}

int amsph_sync(amsph_backend *b) { return b->iface->sync(b); }

static int reduce(amsph_backend *b, amsph_buffer *x, int n, int op, double *out)
{
    *out = op == REDUCE_MAX ? -INFINITY : op == REDUCE_MIN ? INFINITY : 0.0;
    if (n <= 0)
        return 0;
    const int chunk = (n + REDUCE_CHUNKS - 1) / REDUCE_CHUNKS;
    const int nchunks = (n + chunk - 1) / chunk;
    AMSPH_CHECK(AMSPH_LAUNCH(b, "reduce_chunks", nchunks, amsph_arg_buffer(x), amsph_arg_int(n),
                             amsph_arg_int(chunk), amsph_arg_int(nchunks), amsph_arg_int(op),
                             amsph_arg_buffer(b->reduce_partial)));
    amsph_real partial[REDUCE_CHUNKS];
    AMSPH_CHECK(amsph_download(b, b->reduce_partial, 0, (size_t)nchunks * sizeof(amsph_real),
                               partial));
    for (int k = 0; k < nchunks; ++k)
        *out = op == REDUCE_MAX ? fmax(*out, partial[k]) : op == REDUCE_MIN ? fmin(*out, partial[k]) : *out + partial[k];
    return 0;
}

int amsph_reduce_sum(amsph_backend *b, amsph_buffer *x, int n, double *out)
{
    return reduce(b, x, n, REDUCE_SUM, out);
}

int amsph_reduce_max(amsph_backend *b, amsph_buffer *x, int n, double *out)
{
    return reduce(b, x, n, REDUCE_MAX, out);
}

int amsph_reduce_min(amsph_backend *b, amsph_buffer *x, int n, double *out)
{
    return reduce(b, x, n, REDUCE_MIN, out);
}
