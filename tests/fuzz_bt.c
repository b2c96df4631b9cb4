/* tests/fuzz_bt.c — libFuzzer harness: the input as terrain.bt (see tests/fuzz.sh). */
#include "tests/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_one("terrain.bt", data, size, NULL);
    return 0;
}
