/* OpenMP backend: buffers are host memory, kernels are the C11 build of
 * kernels/ (generated table, one per dimension and smoothing kernel), each
 * work-item loop an OpenMP `parallel for`. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "backend.h"
#include "backend_openmp_table.h"
#include "error.h"

struct amsph_buffer {
    void *data;
    size_t bytes;
};

typedef struct {
    const amsph_omp_kernel *table; /* the built program, NULL before build */
} openmp_state;

static int openmp_alloc(amsph_backend *b, size_t bytes, amsph_buffer **out)
{
    (void)b;
    amsph_buffer *buf = malloc(sizeof *buf);
    void *data = NULL;
    if (!buf || posix_memalign(&data, 64, bytes)) {
        free(buf);
        return amsph_fail("openmp: out of host memory allocating %zu bytes", bytes);
    }
    buf->data = data;
    buf->bytes = bytes;
    *out = buf;
    return 0;
}

static void openmp_free(amsph_backend *b, amsph_buffer *buf)
{
    (void)b;
    free(buf->data);
    free(buf);
}

static size_t openmp_size(amsph_backend *b, amsph_buffer *buf)
{
    (void)b;
    return buf->bytes;
}

static int check_range(const amsph_buffer *buf, size_t offset, size_t bytes)
{
    if (offset > buf->bytes || bytes > buf->bytes - offset)
        return amsph_fail("openmp: transfer of %zu bytes at %zu outside a buffer of %zu bytes", bytes,
                          offset, buf->bytes);
    return 0;
}

static int openmp_upload(amsph_backend *b, amsph_buffer *buf, size_t offset, size_t bytes,
                         const void *src)
{
    (void)b;
    AMSPH_CHECK(check_range(buf, offset, bytes));
    memcpy((char *)buf->data + offset, src, bytes);
    return 0;
}

static int openmp_download(amsph_backend *b, amsph_buffer *buf, size_t offset, size_t bytes,
                           void *dst)
{
    (void)b;
    AMSPH_CHECK(check_range(buf, offset, bytes));
    memcpy(dst, (const char *)buf->data + offset, bytes);
    return 0;
}

static int openmp_build(amsph_backend *b, const amsph_build_options *o)
{
    static const amsph_omp_kernel *const tables[2][2] = {
        {amsph_omp_kernels_2_0, amsph_omp_kernels_2_1},
        {amsph_omp_kernels_3_0, amsph_omp_kernels_3_1}};
    ((openmp_state *)b->impl)->table = tables[o->dim - 2][o->kernel];
    return 0;
}

static int openmp_launch(amsph_backend *b, const char *kernel, int items, int nargs,
                         const amsph_arg *args)
{
    (void)items; /* the kernels loop over their own item count */
    const amsph_omp_kernel *k = ((openmp_state *)b->impl)->table;
    if (!k)
        return amsph_fail("openmp: kernel '%s' launched before the program was built", kernel);
    while (k->name && strcmp(k->name, kernel) != 0)
        ++k;
    if (!k->name)
        return amsph_fail("openmp: no kernel named '%s'", kernel);
    if (k->nargs != nargs)
        return amsph_fail("openmp: kernel '%s' takes %d arguments, got %d", kernel, k->nargs, nargs);
    amsph_omp_arg unpacked[32];
    for (int i = 0; i < nargs; ++i) {
        unpacked[i].pointer = args[i].buffer ? args[i].buffer->data : NULL;
        unpacked[i].value = args[i].value.bytes;
        unpacked[i].size = args[i].buffer ? 0 : args[i].size;
    }
    const int bad = k->run(unpacked);
    if (bad)
        return amsph_fail("openmp: kernel '%s' argument %d has the wrong size (%zu bytes)", kernel,
                          bad - 1, args[bad - 1].size);
    return 0;
}

static int openmp_sync(amsph_backend *b)
{
    (void)b;
    return 0;
}

static void openmp_destroy(amsph_backend *b)
{
    free(b->impl);
    free(b);
}

static const amsph_backend_iface openmp_iface = {
    "openmp",     openmp_alloc, openmp_free,   openmp_size, openmp_upload, openmp_download,
    openmp_build, openmp_launch, openmp_sync, openmp_destroy};

int amsph_backend_openmp_create(amsph_backend **out)
{
    amsph_backend *b = calloc(1, sizeof *b);
    openmp_state *s = calloc(1, sizeof *s);
    if (!b || !s) {
        free(b);
        free(s);
        return amsph_fail("openmp: out of host memory");
    }
    b->iface = &openmp_iface;
    b->impl = s;
#ifdef _OPENMP
    snprintf(b->description, sizeof b->description, "OpenMP, %d host threads",
             omp_get_max_threads());
#else
    snprintf(b->description, sizeof b->description, "serial host (built without OpenMP)");
#endif
    *out = b;
    return 0;
}
