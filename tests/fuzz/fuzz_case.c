/* libFuzzer target: the YAML case parser on arbitrary bytes. Every input
 * must give a case or an error message, never a crash, hang or leak. */
#include <stddef.h>
#include <stdint.h>

#include "case.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static amsph_case c;
    char err[1024];
    amsph_case_parse((const char *)data, size, "fuzz.yaml", &c, err, sizeof err);
    return 0;
}
