/* tests/fuzz_hgt.c — libFuzzer harness: the input as N47E009.hgt (see tests/fuzz.sh). */
#include "tests/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_one("N47E009.hgt", data, size, NULL);
    return 0;
}
