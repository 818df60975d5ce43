#include "particles.h"

#include <stdlib.h>
#include <string.h>

#include "error.h"

#define AMSPH_FIELD_INFO(id, name, type, comps, unit, flags) {name, type, comps, unit, flags},
const amsph_field_info amsph_fields[AMSPH_FIELD_COUNT] = {AMSPH_FIELDS(AMSPH_FIELD_INFO)};
#undef AMSPH_FIELD_INFO

size_t amsph_field_bytes(amsph_field_id f)
{
    const size_t element = amsph_fields[f].type == AMSPH_TYPE_REAL ? sizeof(amsph_real) : 4;
    return element * (size_t)amsph_fields[f].components;
}

int amsph_host_add_field(amsph_host_particles *h, amsph_field_id f)
{
    if (h->data[f])
        return 0;
    h->data[f] = calloc(h->n > 0 ? (size_t)h->n : 1, amsph_field_bytes(f));
    return h->data[f] ? 0 : amsph_fail("out of host memory for field '%s'", amsph_fields[f].name);
}

int amsph_host_resize(amsph_host_particles *h, int n)
{
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f) {
        if (!h->data[f])
            continue;
        const size_t bytes = amsph_field_bytes((amsph_field_id)f);
        void *grown = realloc(h->data[f], (n > 0 ? (size_t)n : 1) * bytes);
        if (!grown)
            return amsph_fail("out of host memory for %d particles", n);
        if (n > h->n)
            memset((char *)grown + (size_t)h->n * bytes, 0, (size_t)(n - h->n) * bytes);
        h->data[f] = grown;
    }
    h->n = n;
    return 0;
}

void amsph_host_free(amsph_host_particles *h)
{
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f)
        free(h->data[f]);
    memset(h, 0, sizeof *h);
}

int amsph_particles_upload(amsph_backend *b, const amsph_host_particles *h, amsph_particles *p)
{
    memset(p, 0, sizeof *p);
    p->backend = b;
    p->n = h->n;
    p->capacity = h->n;
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f) {
        if (!h->data[f])
            continue;
        const size_t bytes = (size_t)h->n * amsph_field_bytes((amsph_field_id)f);
        AMSPH_CHECK(amsph_buffer_alloc(b, bytes, &p->field[f]));
        AMSPH_CHECK(amsph_upload(b, p->field[f], 0, bytes, h->data[f]));
    }
    return 0;
}

int amsph_particles_download(amsph_particles *p, amsph_host_particles *h)
{
    memset(h, 0, sizeof *h);
    h->n = p->n;
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f) {
        if (!p->field[f])
            continue;
        AMSPH_CHECK(amsph_host_add_field(h, (amsph_field_id)f));
        AMSPH_CHECK(amsph_download(p->backend, p->field[f], 0,
                                   (size_t)p->n * amsph_field_bytes((amsph_field_id)f), h->data[f]));
    }
    return 0;
}

int amsph_particles_copy_output(amsph_particles *dst, const amsph_particles *src)
{
    amsph_backend *b = src->backend;
    dst->backend = b;
    dst->n = src->n;
    dst->capacity = src->capacity;
    dst->removed = src->removed;
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f) {
        if (!src->field[f] || !(amsph_fields[f].flags & AMSPH_FIELD_OUTPUT))
            continue;
        const int words = (int)(amsph_field_bytes((amsph_field_id)f) / 4);
        if (!dst->field[f])
            AMSPH_CHECK(amsph_buffer_alloc(b, (size_t)src->capacity * (size_t)words * 4, &dst->field[f]));
        AMSPH_CHECK(AMSPH_LAUNCH(b, "copy_words", src->n * words, amsph_arg_buffer(src->field[f]),
                                 amsph_arg_buffer(dst->field[f]), amsph_arg_int(src->n * words)));
    }
    return 0;
}

void amsph_particles_free(amsph_particles *p)
{
    for (int f = 0; f < AMSPH_FIELD_COUNT; ++f)
        amsph_buffer_free(p->backend, p->field[f]);
    memset(p, 0, sizeof *p);
}
