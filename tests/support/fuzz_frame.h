/* tests/support/fuzz_frame.h — the fuzz harnesses' frame: scene s seen from eye towards
 * tgt at 64 x 48 (60 degrees), selected with p, rows y0 .. y0 + rows - 1 drawn in
 * XRGB8888 into px (64 pixels a row).  A camera the scene cannot place is a refusal
 * (said, not a finding: 0 returned); a frame call that fails after it is a finding
 * (abort).  Header-only, as the harnesses link no test support objects. */
#ifndef BR_TEST_FUZZ_FRAME_H
#define BR_TEST_FUZZ_FRAME_H
#include <stdlib.h>
#include <string.h>
#include "platform/scene.h"

static int fuzz_frame(scene *s, const double eye[3], const double tgt[3], bt_params *p, int32_t y0, int32_t rows,
                      uint32_t *px)
{
    cam c;
    rs_frame fr;
    rs_prim prim;
    void *mem;
    if (scene_camera(s, eye, tgt, 60, 64, 48, &c) != BR_OK) return 0;
    memset(&fr, 0, sizeof fr);
    fr.fmt = RS_FMT_XRGB8888;
    fr.depth = RS_DEPTH32;
    fr.clear_rgb = 0x99ccffu;
    if (scene_frame(s, &c, p, &fr, &prim) != BR_OK) abort();
    mem = malloc(rs_band_mem_size(64, rows, fr.fmt, fr.depth));
    if (!mem) abort();
    if (rs_draw_band(&fr, y0, rows, px, 64 * 4, mem, NULL) != BR_OK) abort();
    free(mem);
    return 1;
}

#endif
