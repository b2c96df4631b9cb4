/* platform/board/board_stream.c — the board's frames drawn band by band straight from
 * the tree (board.h; MCU_PATH=stream, build/mcu/bitrain-CORE.elf): no mesh is kept.
 * Each band of BAKE_STREAM_ROWS rows walks the baked hierarchy for its rows (core/
 * bitree.h bt_stream_walk: the view rule without hysteresis) and draws the leaves it
 * meets in small batches (raster/terrain_stream.h), back to front and without a depth
 * buffer (RS_DEPTH_NONE: twice the rows in the band's bytes), then goes to the SPI
 * stream.  What a frame writes is the band, one batch, the walk's state, its answer
 * planes and its weight cache: RAM that does not grow with the frame's triangles
 * (docs/mcu.md).  platform/board/board.c is the other path (MCU_PATH=mesh): the
 * product's whole-frame mesh and strip, its pixels, 201 KB.
 * Freestanding: core/, raster/, the baked arrays and memset/memcpy, nothing else. */
#include "platform/board/board.h"
#include <string.h>
#include "core/bitree.h"
#include "mcu/bake.h"
#include "platform/board/board_scene.h"
#include "raster/frame.h"
#include "raster/ramp.h"
#include "raster/terrain_stream.h"

/* Sizes (RAM against instructions, docs/mcu.md: a band row is 1,280 bytes and saves more
 * than the bytes of a larger batch or cache would) */
#ifndef BOARD_WCACHE
#define BOARD_WCACHE 512        /* the walk's cache of split weights and masks */
#endif
#ifndef BOARD_BATCH_V
#define BOARD_BATCH_V 64        /* vertices of a batch */
#endif
#ifndef BOARD_BATCH_T
#define BOARD_BATCH_T 96        /* triangles of a batch */
#endif

struct board_state {
    hf f;
    rs_ramp ramp;
    rt_scene rt;
    bt_tree tree;               /* the baked hierarchy, no frame state */
    bt_stream *walk;
    rt_stream batch;
    cam c;                      /* the last frame's camera */
    void *band;
    size_t band_bytes;
    uint8_t *row;               /* the SPI row buffer, 2 w bytes */
};

static struct board_state B;

static const char *const part_name[BP_N] = {
    "walk (bt_stream, answers)", "", "batch (raster/terrain_stream.h)", "", "", "band colour (no depth: leaves back to front)", "SPI row buffer"
};

const char *board_part_name(int part)
{
    return part >= 0 && part < BP_N ? part_name[part] : "?";
}

size_t board_part_borrowed(int part, const char **from)
{
    (void)part;
    if (from) *from = "";
    return 0;
}

size_t board_state_size(void)
{
    return sizeof B;
}

static void pipe_of(rs_pipe *pipe)
{
    memset(pipe, 0, sizeof *pipe);
    pipe->w = bake.fb_w; pipe->h = bake.fb_h; pipe->fmt = RS_FMT_RGB565; pipe->depth = RS_DEPTH_NONE;
}

br_status board_init(void *arena, size_t arena_bytes, size_t size[BP_N])
{
    size_t sz[BP_N], total = 0;
    uint8_t *p = (uint8_t *)arena;
    rs_pipe pipe;
    int i;
    memset(&B, 0, sizeof B);
    if (board_scene(&B.f, &B.ramp, &B.rt) != BR_OK) return BR_E_ARG;
    pipe_of(&pipe);
    for (i = 0; i < BP_N; i++) sz[i] = 0;
    sz[BP_STATE] = board_up8(bt_stream_mem_size(BOARD_WCACHE, bake.nslot));
    sz[BP_VERTS] = board_up8(rt_stream_mem_size(BOARD_BATCH_V, BOARD_BATCH_T));
    sz[BP_BAND] = board_up8(rs_pipe_mem_size(&pipe, BAKE_STREAM_ROWS));
    sz[BP_ROW] = board_up8((size_t)bake.fb_w * 2);
    for (i = 0; i < BP_N; i++) {
        if (size) size[i] = sz[i];
        total += sz[i];
    }
    if (!arena || ((uintptr_t)arena & 7) != 0 || total > arena_bytes) return BR_E_NOMEM;
    /* no frame state: the stream's view rule has no hysteresis */
    if (bt_attach(&B.tree, &B.f, bake_tree, bake_tree_bytes, NULL, 0) != BR_OK) return BR_E_ARG;
    if (bt_stream_init(&B.walk, BOARD_WCACHE, bake.nslot, p, sz[BP_STATE]) != BR_OK
        || bt_stream_order(B.walk, BT_STREAM_BACK_TO_FRONT) != BR_OK)
        return BR_E_ARG;
    p += sz[BP_STATE];
    if (rt_stream_init(&B.batch, BOARD_BATCH_V, BOARD_BATCH_T, p, sz[BP_VERTS]) != BR_OK) return BR_E_ARG;
    p += sz[BP_VERTS];
    B.band = p; B.band_bytes = sz[BP_BAND];
    p += sz[BP_BAND];
    B.row = p;
    B.batch.scene = &B.rt;
    B.batch.walk = B.walk;
    return BR_OK;
}

br_status board_frame(int32_t i, rs_sink tap, void *tap_user, board_frame_info *out)
{
    const bake_cam *bc;
    bt_params bp;
    rs_pipe pipe;
    rs_band_stats total;
    board_sum s;
    br_status st;
    uint32_t leaves0 = B.batch.leaves;
    if (i < 0 || i >= bake.nframes || !B.row) return BR_E_ARG;
    bc = &bake.cam[i];
    st = cam_look_at(&B.c, bc->eye, bc->tgt, bake.fovy_mdeg, bake.fb_w, bake.fb_h, bc->znear, bc->zfar);
    if (st != BR_OK) return st;
    memset(&bp, 0, sizeof bp);
    bp.mode = BT_VIEW;
    bp.c = &B.c;
    bp.fr = B.rt.fr;
    bp.pixel_err_q8 = bake.pixel_err_q8;
    bp.morph_q8 = bake.morph_q8;
    if ((st = bt_stream_frame(B.walk, &B.tree, &bp)) != BR_OK
        || (st = rt_stream_pipe(&B.batch, &B.c, RS_FMT_RGB565, RS_DEPTH_NONE, bake.clear_rgb, &pipe)) != BR_OK)
        return st;
    board_sum_start(&s, B.row, tap, tap_user);
    st = rs_pipe_run(&pipe, BAKE_STREAM_ROWS, B.band, B.band_bytes, board_sum_band, &s, &total);
    if (st != BR_OK) return st;
    out->sum = s.sum;
    out->expect = bake.stream_sum[i];
    out->ntri = B.batch.leaves - leaves0;     /* set-ups: a triangle once per band it reaches */
    out->nv = 0; out->ns = 0;
    out->overflow = 0;
    out->pixels = total.pixels;
    return BR_OK;
}

static void count_leaf(void *user, bt_svert *a, bt_svert *b, bt_svert *c)
{
    (void)user; (void)a; (void)b; (void)c;
}

uint32_t board_last_triangles(void)
{
    return B.walk ? bt_stream_walk(B.walk, NULL, count_leaf, NULL) : 0;
}

void board_last_frame(const rs_cvert **cache, uint32_t *nv, const br_index **strip, uint32_t *ns)
{
    *cache = NULL; *nv = 0; *strip = NULL; *ns = 0;
}
