/* OpenMP backend: buffers are host memory, kernels are the C11 build of
 * kernels/ (generated table, one per dimension and smoothing kernel), each
 * work-item loop an OpenMP `parallel for`.
 *
 * An offload build (AMSPH_OMP_OFFLOAD) makes each loop a target region
 * instead (kernels/device.h). When the default device is an accelerator,
 * each buffer gets a copy on it, associated with the buffer's host
 * allocation (omp_target_associate_ptr): a kernel receives the host
 * pointers, and the target region translates them to the device copies.
 * Uploads and downloads copy between the caller's memory and the device
 * copy, so the host allocation only lends its addresses. Without a device
 * (or with OMP_TARGET_OFFLOAD=DISABLED) the target regions run on host
 * threads and buffers are host memory, as in the plain build. */
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
    void *data;   /* host memory (with an offload device: the key of the device copy) */
    void *device; /* the copy on the offload device, NULL where kernels run on the host */
    size_t bytes;
};

typedef struct {
    const amsph_omp_kernel *table; /* the built program, NULL before build */
    int device;                    /* offload device, -1 where kernels run on the host */
} openmp_state;

/* The device the kernels' target regions run on, or -1 where they run on host threads. */
static int offload_device(void)
{
#if AMSPH_OMP_OFFLOAD
    const int device = omp_get_default_device();
    return omp_get_num_devices() > 0 && device != omp_get_initial_device() ? device : -1;
#else
    return -1;
#endif
}

#if AMSPH_OMP_OFFLOAD
/* Gives buf a copy on the device, associated with its host addresses. */
static int attach_device_copy(int device, amsph_buffer *buf)
{
    buf->device = omp_target_alloc(buf->bytes, device);
    if (!buf->device)
        return amsph_fail("openmp: out of memory on offload device %d allocating %zu bytes", device,
                          buf->bytes);
    if (omp_target_associate_ptr(buf->data, buf->device, buf->bytes, 0, device)) {
        omp_target_free(buf->device, device);
        buf->device = NULL;
        return amsph_fail("openmp: cannot map %zu bytes on offload device %d", buf->bytes, device);
    }
    return 0;
}

static void detach_device_copy(int device, amsph_buffer *buf)
{
    omp_target_disassociate_ptr(buf->data, device);
    omp_target_free(buf->device, device);
}

static int copy_status(int status, size_t bytes, const char *direction, int device)
{
    if (status)
        return amsph_fail("openmp: copy of %zu bytes %s offload device %d failed", bytes, direction,
                          device);
    return 0;
}
#endif

static int openmp_alloc(amsph_backend *b, size_t bytes, amsph_buffer **out)
{
    const int device = ((openmp_state *)b->impl)->device;
    amsph_buffer *buf = malloc(sizeof *buf);
    void *data = NULL;
    if (!buf || posix_memalign(&data, 64, bytes)) {
        free(buf);
        return amsph_fail("openmp: out of host memory allocating %zu bytes", bytes);
    }
    buf->data = data;
    buf->device = NULL;
    buf->bytes = bytes;
#if AMSPH_OMP_OFFLOAD
    const int status = device >= 0 ? attach_device_copy(device, buf) : 0;
    if (status) {
        free(data);
        free(buf);
        return status;
    }
#else
    (void)device;
#endif
    *out = buf;
    return 0;
}

static void openmp_free(amsph_backend *b, amsph_buffer *buf)
{
#if AMSPH_OMP_OFFLOAD
    if (buf->device)
        detach_device_copy(((openmp_state *)b->impl)->device, buf);
#else
    (void)b;
#endif
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
    AMSPH_CHECK(check_range(buf, offset, bytes));
#if AMSPH_OMP_OFFLOAD
    const int device = ((openmp_state *)b->impl)->device;
    if (buf->device)
        return copy_status(omp_target_memcpy(buf->device, src, bytes, offset, 0, device,
                                             omp_get_initial_device()),
                           bytes, "to", device);
#else
    (void)b;
#endif
    memcpy((char *)buf->data + offset, src, bytes);
    return 0;
}

static int openmp_download(amsph_backend *b, amsph_buffer *buf, size_t offset, size_t bytes,
                           void *dst)
{
    AMSPH_CHECK(check_range(buf, offset, bytes));
#if AMSPH_OMP_OFFLOAD
    const int device = ((openmp_state *)b->impl)->device;
    if (buf->device)
        return copy_status(omp_target_memcpy(dst, buf->device, bytes, 0, offset,
                                             omp_get_initial_device(), device),
                           bytes, "from", device);
#else
    (void)b;
#endif
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
    s->device = offload_device();
#if AMSPH_OMP_OFFLOAD
    if (s->device >= 0)
        snprintf(b->description, sizeof b->description, "OpenMP target offload, device %d of %d",
                 s->device, omp_get_num_devices());
    else
        snprintf(b->description, sizeof b->description,
                 "OpenMP target offload build without a device: %d host threads",
                 omp_get_max_threads());
#elif defined(_OPENMP)
    snprintf(b->description, sizeof b->description, "OpenMP, %d host threads",
             omp_get_max_threads());
#else
    snprintf(b->description, sizeof b->description, "serial host (built without OpenMP)");
#endif
    *out = b;
    return 0;
}
