/* tests/fuzz_xyz.c — libFuzzer harness: the input as XYZ text, as heights
 * or as depths (by the input length; tests/fuzz.sh). */
#include "tests/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    dem_opts o = { 0, 0, 0, 0 };
    o.xyz_depth = (int)(size & 1);
    fuzz_one("points.xyz", data, size, &o);
    return 0;
}
