/* tests/fuzz_zip.c — libFuzzer harness: the input as a compressed tile
 * (.zip, or .gz when it starts with the gzip magic; tests/fuzz.sh). */
#include "tests/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_one("N47E009.hgt.zip", data, size, NULL);
    return 0;
}
