/* libFuzzer target: the restart reader on arbitrary files. Every input must
 * be read or refused with a message, never a crash, hang or leak. The bytes
 * go to a file (the reader takes a path) in a private temporary directory.
 *
 * With FUZZ_RESIGN defined the target first gives the input a valid trailer
 * (version, length and checksum of the bytes), so that the mutations reach
 * HDF5 and the reader's checks of the file's structure instead of stopping
 * at the checksum. */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "checkpoint.h"
#include "hash.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char *scratch_path(void)
{
    static char path[64];
    if (!path[0]) {
        char dir[] = "/tmp/amsph_fuzz_XXXXXX";
        if (!mkdtemp(dir))
            abort();
        snprintf(path, sizeof path, "%s/checkpoint.h5", dir);
    }
    return path;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = scratch_path();
    FILE *f = fopen(path, "wb");
    if (!f)
        abort();
    fwrite(data, 1, size, f);
#ifdef FUZZ_RESIGN
    char trailer[64] = {0};
    snprintf(trailer, sizeof trailer, "amsph checkpoint %d %zu %016" PRIx64 "\n", AMSPH_CHECKPOINT_VERSION, size,
             amsph_hash(AMSPH_HASH_START, data, size));
    fwrite(trailer, 1, sizeof trailer, f);
#endif
    fclose(f);
    amsph_checkpoint ck;
    amsph_checkpoint_read(path, &ck);
    amsph_checkpoint_free(&ck);
    return 0;
}
