/* tests/test_raster_variants.c — the build-time variant choice of raster/raster.c
 * (RS_WITH_*), as a board with little flash would use it.
 *
 * This file compiles a second copy of raster.c and xform.c (the vertex transform)
 * keeping only RGB565 with 16-bit depth, their functions renamed (min_*) so that it
 * links beside the full library, and with BR_DIV64_NATIVE = 0: the quotients of the
 * vertex transform and the triangles' reciprocals come from core/fx.h's fx_recip, as on
 * 32-bit ARM, instead of `/`.  On the peer
 * scene (real fuji.png terrain, both cameras, whole frame and 7-row bands) the reduced
 * copy must give exactly the full library's bytes, and refuse every variant it left out
 * with BR_E_UNSUPPORTED instead of drawing. */
/* dividing without the 64-bit divide, as a 32-bit board does (core/config.h
 * BR_DIV64_NATIVE, read by core/fx.h's fx_divisor): set before any header; the full
 * library it is compared with is built separately, with the native default */
#define BR_DIV64_NATIVE 0
/* the reduced copy's variants: core/config.h reads these at the first include */
#define RS_WITH_888 0
#define RS_WITH_Z32 0
#define RS_WITH_TEX 0
#define RS_WITH_COUNT 0
#include "raster/raster.h"
#include "core/cam.h"
#include "benchmarks/peer_scene.h"
#include "tests/test.h"

#define rs_cache_mem_size min_cache_mem_size
#define rs_band_mem_size min_band_mem_size
#define rs_chunk_mem_size min_chunk_mem_size
#define rs_clip_mem_size min_clip_mem_size
#define rs_cvert_set min_cvert_set
#define rs_cvert_recolour min_cvert_recolour
#define rs_frame_prepare min_frame_prepare
#define rs_draw_band min_draw_band
#define rs_variant_built min_variant_built
#define rs_to_rgb888 min_to_rgb888
/* raster.h is already included under the real names, so the renamed copy has no
 * prototypes of its own: its definitions come first, which is all the calls below need */
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#endif
#include "raster/raster.c"
#include "raster/xform.c"
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
#undef rs_cache_mem_size
#undef rs_band_mem_size
#undef rs_chunk_mem_size
#undef rs_cvert_set
#undef rs_frame_prepare
#undef rs_draw_band
#undef rs_variant_built
#undef rs_to_rgb888

#define W 320
#define H 240

static peer_scene *g_ps;
static rs_vertex g_v[PEER_NV];
static rs_prim g_prims[PEER_NSTRIP];
static int16_t g_chunks[2][2 * (PEER_NTRI / RS_CHUNK + PEER_NSTRIP)];   /* the two frames' chunk tables */

static int load_scene(void)
{
    if (g_ps) return 1;
    g_ps = (peer_scene *)malloc(sizeof *g_ps);
    if (!g_ps || peer_scene_build(t_data("png/fuji.png"), g_ps) != 0) return 0;
    peer_scene_raster(g_ps, g_v, g_prims);
    return 1;
}

/* Frame of peer camera `which` at W x H in RGB565 + 16-bit depth, cache and chunk
 * table (g_chunks[table]) from `prepare`. */
static int setup(rs_frame *f, char which, br_status (*prepare)(rs_frame *), int table)
{
    memset(f, 0, sizeof *f);
    if (!load_scene() || peer_frame(which, W, H, g_v, g_prims, f) != 0) return 0;
    f->fmt = RS_FMT_RGB565; f->depth = RS_DEPTH16;
    f->cache = (rs_cvert *)malloc(rs_cache_mem_size(PEER_NV));
    f->chunks = g_chunks[table];
    if (rs_chunk_mem_size(f->prims, f->nprims) > sizeof g_chunks[table]) return 0;
    return f->cache && prepare(f) == BR_OK;
}

/* The whole frame drawn in bands of `rows` by `band_fn` into colour (W x H RGB565). */
static br_status draw(const rs_frame *f,
                      br_status (*band_fn)(const rs_frame *, int32_t, int32_t, void *, size_t, void *, rs_band_stats *),
                      int32_t rows, uint16_t *colour, uint16_t *zbuf, rs_band_stats *st)
{
    int32_t y0;
    for (y0 = 0; y0 < H; y0 += rows) {
        int32_t n = H - y0 < rows ? H - y0 : rows;
        br_status s = band_fn(f, y0, n, colour + (size_t)y0 * W, W * 2, zbuf, st);
        if (s != BR_OK) return s;
    }
    return BR_OK;
}

static void test_same_bytes(void)
{
    static uint16_t full[W * H], part[W * H], zb[W * H];
    const char cams[2] = { 'A', 'B' };
    const int32_t bands[2] = { H, 7 };
    int ci, bi;
    for (ci = 0; ci < 2; ci++) {
        rs_frame ff, fm;
        long terrain = 0, i;
        rs_band_stats sf = { 0, 0, 0, 0 }, sm = { 0, 0, 0, 0 };
        CHECK(setup(&ff, cams[ci], rs_frame_prepare, 0));
        CHECK(setup(&fm, cams[ci], min_frame_prepare, 1));
        if (!ff.cache || !fm.cache) return;
        for (i = 0; i < PEER_NV; i++) {   /* u, v are written for textured frames only */
            const rs_cvert *a = &ff.cache[i], *b = &fm.cache[i];
            if (a->x != b->x || a->y != b->y || a->d != b->d || a->c != b->c || a->cp != b->cp) break;
        }
        CHECK_EQ(i, PEER_NV);
        for (bi = 0; bi < 2; bi++) {
            CHECK_EQ(draw(&ff, rs_draw_band, bands[bi], full, zb, &sf), BR_OK);
            CHECK_EQ(draw(&fm, min_draw_band, bands[bi], part, zb, &sm), BR_OK);
            CHECK_MSG(memcmp(full, part, sizeof full) == 0, "camera %c, bands of %d rows", cams[ci], bands[bi]);
        }
        for (i = 0; i < W * H; i++) terrain += full[i] != 0x9e7f;   /* not sky */
        CHECK_MSG(terrain > W * H / 3, "camera %c: %ld terrain pixels", cams[ci], terrain);
        CHECK_EQ(sf.pixels, sm.pixels);
        free(ff.cache); free(fm.cache);
    }
}

static void test_refused(void)
{
    static uint32_t colour[W * H], zb[W * H];
    static const uint32_t texel = 0xffffff;
    rs_texture tex;
    rs_frame f;
    int32_t fmt, dep;
    for (fmt = 0; fmt < 2; fmt++)
        for (dep = 0; dep < 2; dep++) {
            CHECK_EQ(rs_variant_built(fmt, dep, 0), 1);
            CHECK_EQ(rs_variant_built(fmt, dep, 1), 1);
            CHECK_EQ(min_variant_built(fmt, dep, 0), fmt == RS_FMT_RGB565 && dep == RS_DEPTH16);
            CHECK_EQ(min_variant_built(fmt, dep, 1), 0);
        }
    /* without depth (RS_DEPTH_NONE): both formats, no textures; the reduced copy RGB565 */
    for (fmt = 0; fmt < 2; fmt++) {
        CHECK_EQ(rs_variant_built(fmt, RS_DEPTH_NONE, 0), 1);
        CHECK_EQ(rs_variant_built(fmt, RS_DEPTH_NONE, 1), 0);
        CHECK_EQ(min_variant_built(fmt, RS_DEPTH_NONE, 0), fmt == RS_FMT_RGB565);
    }
    CHECK(setup(&f, 'A', min_frame_prepare, 0));
    if (!f.cache) return;
    f.fmt = RS_FMT_XRGB8888;
    memset(colour, 0x5a, sizeof colour);
    CHECK_EQ(min_draw_band(&f, 0, H, colour, W * 4, zb, NULL), BR_E_UNSUPPORTED);
    CHECK(colour[0] == 0x5a5a5a5au && colour[W * H - 1] == 0x5a5a5a5au);   /* nothing drawn or cleared */
    f.fmt = RS_FMT_RGB565; f.depth = RS_DEPTH32;
    CHECK_EQ(min_draw_band(&f, 0, H, colour, W * 2, zb, NULL), BR_E_UNSUPPORTED);
    f.depth = RS_DEPTH16;
    tex.w = tex.h = 1; tex.px = &texel;
    f.tex = &tex;
    CHECK_EQ(min_draw_band(&f, 0, H, colour, W * 2, zb, NULL), BR_E_UNSUPPORTED);
    f.tex = NULL;
    f.debug_count = 1;
    CHECK_EQ(min_draw_band(&f, 0, H, colour, W * 2, zb, NULL), BR_E_UNSUPPORTED);
    /* the shipped library has no counting variant (tests/support/raster_count.c has) */
    CHECK_EQ(rs_draw_band(&f, 0, H, colour, W * 2, zb, NULL), BR_E_UNSUPPORTED);
    f.debug_count = 0;
    /* without depth a frame's order is its picture's: strips (the peer scene's) refused,
     * nothing drawn or cleared */
    f.depth = RS_DEPTH_NONE;
    memset(colour, 0x5a, sizeof colour);
    CHECK_EQ(rs_draw_band(&f, 0, H, colour, W * 2, NULL, NULL), BR_E_ARG);
    CHECK_EQ(min_draw_band(&f, 0, H, colour, W * 2, NULL, NULL), BR_E_ARG);
    CHECK(colour[0] == 0x5a5a5a5au && colour[W * H - 1] == 0x5a5a5a5au);
    f.depth = RS_DEPTH16;
    CHECK_EQ(min_draw_band(&f, 0, H, colour, W * 2, NULL, NULL), BR_E_ARG);     /* depth needed */
    CHECK_EQ(min_draw_band(&f, 0, H, colour, W * 2, zb, NULL), BR_OK);
    free(f.cache);
}

int main(void)
{
    T_RUN(test_same_bytes);
    T_RUN(test_refused);
    free(g_ps);
    return t_finish();
}
