/* platform/board/board_scene.h — what the board's two frame paths (board.c: the mesh,
 * board_stream.c: the stream; board.h) share: the baked scene set up from flash, and the
 * band sink that streams each finished band as platform/board/spi_band.h's bytes into
 * the frame's checksum.  Freestanding. */
#ifndef BR_BOARD_SCENE_H
#define BR_BOARD_SCENE_H
#include <stddef.h>
#include <stdint.h>
#include "core/hf.h"
#include "raster/ramp.h"
#include "raster/raster.h"
#include "raster/terrain.h"

/* The heightfield over the baked heights (read only), the default ramp over the crop's
 * heights, and the scene with the baked shading cache attached (rt_vertex only reads
 * it).  BR_E_ARG when the bake is inconsistent. */
br_status board_scene(hf *f, rs_ramp *ramp, rt_scene *rt);

/* A frame's SPI stream being summed (spib_sum), then handed to tap (NULL: none). */
typedef struct board_sum {
    uint32_t sum;
    int dc;
    uint8_t *row;               /* 2 w bytes: one row of the band as the panel takes it */
    rs_sink tap;
    void *tap_user;
} board_sum;

void board_sum_start(board_sum *s, uint8_t *row, rs_sink tap, void *tap_user);
/* rs_sink for rs_pipe_run: user is a board_sum */
br_status board_sum_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride);

static inline size_t board_up8(size_t n) { return (n + 7) & ~(size_t)7; }

#endif
