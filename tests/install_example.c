/* tests/install_example.c — the smallest program against an installed bitrain
 * (mk/check-install.sh builds it with `pkg-config --cflags --static --libs bitrain`
 * after `make install DESTDIR=...`): the public headers are found under their
 * installed names and libbitrain.a links.  It sizes a bitree for a 1201 x 1201 SRTM3
 * tile and one 16-row band of a 320 x 240 RGB565 frame, and prints both. */
#include <stdio.h>
#include "core/bitree.h"
#include "raster/raster.h"
#include "platform/load.h"

int main(void)
{
    const size_t tree = bt_mem_size(1201, 1201);
    const size_t band = rs_band_mem_size(320, 16, RS_FMT_RGB565, RS_DEPTH16);
    printf("bitree 1201x1201: %zu bytes; band 320x16 RGB565 + 16-bit depth: %zu bytes\n", tree, band);
    return tree == 0 || band != 320u * 16u * 4u;
}
