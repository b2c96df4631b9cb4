/* tests/cross/xdet_stages.c — probe stages for the bitree and the rasteriser. */
#include <stdio.h>
#include "tests/cross/xdet_stages.h"

void xdet_stages(const hf *f)
{
    (void)f;
}
