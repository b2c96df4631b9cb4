/* tests/fuzz_png.c — libFuzzer harness: the input as a PNG, under each of
 * the height encodings in turn (chosen by the input length; tests/fuzz.sh). */
#include "tests/fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    dem_opts o = { 0, 0, 0, 0 };
    o.png_encoding = (int)(size % 4);
    if (size % 8 >= 4) { o.png_scale = 0.25; o.png_offset = -10.5; }
    fuzz_one("terrain.png", data, size, &o);
    return 0;
}
