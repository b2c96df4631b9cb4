/* tests/fuzz_asc.c — libFuzzer harness: the input as grid.asc (see tests/fuzz.sh). */
#include "tests/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_one("grid.asc", data, size, NULL);
    return 0;
}
