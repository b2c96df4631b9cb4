/* tests/fuzz_tif.c — libFuzzer harness: the input as terrain.tif (see tests/fuzz.sh). */
#include "tests/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_one("terrain.tif", data, size, NULL);
    return 0;
}
