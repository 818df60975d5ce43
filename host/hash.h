/* FNV-1a, 64 bit: a fingerprint of bytes (the case text that a checkpoint
 * must match, the checksum that guards a checkpoint against corruption).
 * Feed pieces in order: h = amsph_hash(h, piece, n), starting from
 * AMSPH_HASH_START. */
#ifndef AMSPH_HASH_H
#define AMSPH_HASH_H

#include <stddef.h>
#include <stdint.h>

#define AMSPH_HASH_START 14695981039346656037ull

static inline uint64_t amsph_hash(uint64_t h, const void *bytes, size_t n)
{
    const unsigned char *p = bytes;
    for (size_t i = 0; i < n; ++i)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

#endif
