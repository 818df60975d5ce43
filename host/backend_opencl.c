/* OpenCL backend (pocl on the CPU, any GPU driver): the program is the
 * embedded kernels/ source, built at run time with -D options; kernel
 * objects are created on first launch and cached by name. Devices are
 * numbered across all platforms in the order the ICD loader lists them. */
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "error.h"

extern const char amsph_opencl_source[];

#define MAX_DEVICES 64
#define MAX_KERNELS 128

struct amsph_buffer {
    cl_mem mem;
};

typedef struct {
    char name[64];
    cl_kernel kernel;
} cached_kernel;

typedef struct {
    cl_context context;
    cl_command_queue queue;
    cl_device_id device;
    cl_program program;
    int n_kernels;
    cached_kernel kernels[MAX_KERNELS];
} opencl_state;

static int cl_fail(const char *what, cl_int err)
{
    return amsph_fail("opencl: %s failed (error %d)", what, (int)err);
}

/* All devices of all platforms, in loader order. */
static int enumerate_devices(cl_device_id *devices, cl_platform_id *platforms, int *count)
{
    cl_platform_id ids[16];
    cl_uint n_platforms = 0;
    cl_int err = clGetPlatformIDs(16, ids, &n_platforms);
    if (err != CL_SUCCESS || n_platforms == 0)
        return amsph_fail("opencl: no OpenCL platform found (is an ICD such as pocl-opencl-icd "
                          "installed? see /etc/OpenCL/vendors); --backend openmp still works");
    *count = 0;
    for (cl_uint p = 0; p < n_platforms && *count < MAX_DEVICES; ++p) {
        cl_uint n = 0;
        if (clGetDeviceIDs(ids[p], CL_DEVICE_TYPE_ALL, (cl_uint)(MAX_DEVICES - *count),
                           devices + *count, &n) != CL_SUCCESS)
            continue;
        for (cl_uint d = 0; d < n; ++d)
            platforms[*count + (int)d] = ids[p];
        *count += (int)n;
    }
    if (*count == 0)
        return amsph_fail("opencl: platforms found but no devices; --backend openmp still works");
    return 0;
}

static void describe(cl_platform_id platform, cl_device_id device, char *out, size_t len)
{
    char pname[128] = "", dname[128] = "", version[128] = "";
    clGetPlatformInfo(platform, CL_PLATFORM_NAME, sizeof pname, pname, NULL);
    clGetDeviceInfo(device, CL_DEVICE_NAME, sizeof dname, dname, NULL);
    clGetDeviceInfo(device, CL_DRIVER_VERSION, sizeof version, version, NULL);
    snprintf(out, len, "OpenCL %s / %s (driver %s)", pname, dname, version);
}

void amsph_backend_opencl_list(FILE *file)
{
    cl_device_id devices[MAX_DEVICES];
    cl_platform_id platforms[MAX_DEVICES];
    int n = 0;
    if (enumerate_devices(devices, platforms, &n)) {
        fprintf(file, "%s\n", amsph_last_error());
        return;
    }
    for (int i = 0; i < n; ++i) {
        char text[256];
        describe(platforms[i], devices[i], text, sizeof text);
        fprintf(file, "opencl --device %d: %s\n", i, text);
    }
}

static int opencl_alloc(amsph_backend *b, size_t bytes, amsph_buffer **out)
{
    opencl_state *s = b->impl;
    cl_int err;
    amsph_buffer *buf = malloc(sizeof *buf);
    if (!buf)
        return amsph_fail("opencl: out of host memory");
    buf->mem = clCreateBuffer(s->context, CL_MEM_READ_WRITE, bytes, NULL, &err);
    if (err != CL_SUCCESS) {
        free(buf);
        return amsph_fail("opencl: cannot allocate %zu bytes on the device (error %d)", bytes,
                          (int)err);
    }
    *out = buf;
    return 0;
}

static void opencl_free(amsph_backend *b, amsph_buffer *buf)
{
    (void)b;
    clReleaseMemObject(buf->mem);
    free(buf);
}

static size_t opencl_size(amsph_backend *b, amsph_buffer *buf)
{
    (void)b;
    size_t bytes = 0;
    clGetMemObjectInfo(buf->mem, CL_MEM_SIZE, sizeof bytes, &bytes, NULL);
    return bytes;
}

static int opencl_upload(amsph_backend *b, amsph_buffer *buf, size_t offset, size_t bytes,
                         const void *src)
{
    opencl_state *s = b->impl;
    cl_int err = clEnqueueWriteBuffer(s->queue, buf->mem, CL_TRUE, offset, bytes, src, 0, NULL, NULL);
    return err == CL_SUCCESS ? 0 : cl_fail("upload", err);
}

static int opencl_download(amsph_backend *b, amsph_buffer *buf, size_t offset, size_t bytes,
                           void *dst)
{
    opencl_state *s = b->impl;
    cl_int err = clEnqueueReadBuffer(s->queue, buf->mem, CL_TRUE, offset, bytes, dst, 0, NULL, NULL);
    return err == CL_SUCCESS ? 0 : cl_fail("download", err);
}

static void release_program(opencl_state *s)
{
    for (int k = 0; k < s->n_kernels; ++k)
        clReleaseKernel(s->kernels[k].kernel);
    s->n_kernels = 0;
    if (s->program)
        clReleaseProgram(s->program);
    s->program = NULL;
}

static int opencl_build(amsph_backend *b, const amsph_build_options *o)
{
    opencl_state *s = b->impl;
    release_program(s);
    const char *source = amsph_opencl_source;
    cl_int err;
    s->program = clCreateProgramWithSource(s->context, 1, &source, NULL, &err);
    if (err != CL_SUCCESS)
        return cl_fail("clCreateProgramWithSource", err);
    char options[256];
    snprintf(options, sizeof options, "-cl-std=CL1.2 -DAMSPH_DIM=%d -DAMSPH_KERNEL=%d -DAMSPH_DOUBLE=%d",
             o->dim, o->kernel, AMSPH_DOUBLE);
    err = clBuildProgram(s->program, 1, &s->device, options, NULL, NULL);
    if (err != CL_SUCCESS) {
        size_t len = 0;
        clGetProgramBuildInfo(s->program, s->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &len);
        char *log = calloc(len + 1, 1);
        if (log)
            clGetProgramBuildInfo(s->program, s->device, CL_PROGRAM_BUILD_LOG, len, log, NULL);
        fprintf(stderr, "amsph: OpenCL build log (%s):\n%s\n", options, log ? log : "");
        free(log);
        release_program(s);
        return amsph_fail("opencl: building the kernels failed (error %d, log above)", (int)err);
    }
    return 0;
}

static int find_kernel(opencl_state *s, const char *name, cl_kernel *out)
{
    for (int k = 0; k < s->n_kernels; ++k)
        if (strcmp(s->kernels[k].name, name) == 0) {
            *out = s->kernels[k].kernel;
            return 0;
        }
    if (!s->program)
        return amsph_fail("opencl: kernel '%s' launched before the program was built", name);
    if (s->n_kernels == MAX_KERNELS || strlen(name) >= sizeof s->kernels[0].name)
        return amsph_fail("opencl: kernel cache full at '%s'", name);
    cl_int err;
    cl_kernel k = clCreateKernel(s->program, name, &err);
    if (err != CL_SUCCESS)
        return amsph_fail("opencl: no kernel named '%s' (error %d)", name, (int)err);
    strcpy(s->kernels[s->n_kernels].name, name);
    s->kernels[s->n_kernels++].kernel = k;
    *out = k;
    return 0;
}

static int opencl_launch(amsph_backend *b, const char *name, int items, int nargs,
                         const amsph_arg *args)
{
    opencl_state *s = b->impl;
    cl_kernel k = NULL;
    AMSPH_CHECK(find_kernel(s, name, &k));
    cl_uint expected = 0;
    clGetKernelInfo(k, CL_KERNEL_NUM_ARGS, sizeof expected, &expected, NULL);
    if ((int)expected != nargs)
        return amsph_fail("opencl: kernel '%s' takes %u arguments, got %d", name, expected, nargs);
    for (int i = 0; i < nargs; ++i) {
        cl_int err = args[i].buffer
                         ? clSetKernelArg(k, (cl_uint)i, sizeof(cl_mem), &args[i].buffer->mem)
                         : clSetKernelArg(k, (cl_uint)i, args[i].size, args[i].value.bytes);
        if (err != CL_SUCCESS)
            return amsph_fail("opencl: kernel '%s' argument %d rejected (error %d)", name, i,
                              (int)err);
    }
    const size_t global = (size_t)items;
    cl_int err = clEnqueueNDRangeKernel(s->queue, k, 1, NULL, &global, NULL, 0, NULL, NULL);
    if (err != CL_SUCCESS)
        return amsph_fail("opencl: launching '%s' on %d items failed (error %d)", name, items,
                          (int)err);
    return 0;
}

static int opencl_sync(amsph_backend *b)
{
    opencl_state *s = b->impl;
    cl_int err = clFinish(s->queue);
    return err == CL_SUCCESS ? 0 : cl_fail("clFinish", err);
}

static void opencl_destroy(amsph_backend *b)
{
    opencl_state *s = b->impl;
    if (s->queue)
        clFinish(s->queue); /* nothing queued may outlive the context (pocl compiles at enqueue) */
    release_program(s);
    if (s->queue)
        clReleaseCommandQueue(s->queue);
    if (s->context)
        clReleaseContext(s->context);
    free(s);
    free(b);
}

static const amsph_backend_iface opencl_iface = {
    "opencl",     opencl_alloc, opencl_free,   opencl_size, opencl_upload, opencl_download,
    opencl_build, opencl_launch, opencl_sync, opencl_destroy};

int amsph_backend_opencl_create(int device, amsph_backend **out)
{
    cl_device_id devices[MAX_DEVICES];
    cl_platform_id platforms[MAX_DEVICES];
    int n = 0;
    AMSPH_CHECK(enumerate_devices(devices, platforms, &n));
    if (device >= n)
        return amsph_fail("opencl: no device %d (found %d; `amsph devices` lists them)", device, n);
    amsph_backend *b = calloc(1, sizeof *b);
    opencl_state *s = calloc(1, sizeof *s);
    if (!b || !s) {
        free(b);
        free(s);
        return amsph_fail("opencl: out of host memory");
    }
    b->iface = &opencl_iface;
    b->impl = s;
    s->device = devices[device];
    cl_int err;
    s->context = clCreateContext(NULL, 1, &s->device, NULL, NULL, &err);
    if (err == CL_SUCCESS)
        s->queue = clCreateCommandQueue(s->context, s->device, 0, &err);
    if (err != CL_SUCCESS) {
        opencl_destroy(b);
        return cl_fail("creating a context and queue", err);
    }
    describe(platforms[device], s->device, b->description, sizeof b->description);
    *out = b;
    return 0;
}
