/* tests/test_isa.c — the two copies of the drawing code of an x86-64 build (raster.h
 * rs_isa_set: baseline x86-64 and x86-64-v3, compiled from the same source) give the
 * same bytes: the vertex cache and every pixel of the peer scene (real fuji.png
 * terrain), both cameras, two sizes, every pixel format and depth size, culling off and
 * on, the whole frame and 7-row bands, and a textured frame; and the water frames of
 * `bitrain render` (the post hook's copies, raster/water.c and water_vec.h) on Lake
 * Constance from the water and low over it, the default view, the Kattegat and Monai.
 * On a build or CPU with one copy it says so and checks that rs_isa_set falls back to
 * it. */
#include "raster/raster.h"
#include "core/cam.h"
#include "benchmarks/peer_scene.h"
#include "platform/cmd.h"
#include "tests/test.h"

static peer_scene *g_ps;
static rs_vertex g_v[PEER_NV];
static rs_prim g_prims[PEER_NSTRIP];
static uint32_t g_texels[PEER_N * PEER_N];

static int load_scene(void)
{
    int32_t i;
    if (g_ps) return 1;
    g_ps = (peer_scene *)malloc(sizeof *g_ps);
    if (!g_ps || peer_scene_build(t_data("png/fuji.png"), g_ps) != 0) return 0;
    peer_scene_raster(g_ps, g_v, g_prims);
    /* a texture of the scene's own colours, one texel per grid vertex, mapped onto the
     * grid (u, v in Q8 texels) */
    for (i = 0; i < PEER_NV; i++) {
        g_texels[i] = g_v[i].rgb & 0xffffffu;
        g_v[i].uv[0] = (i % PEER_N) * 256 + 128;
        g_v[i].uv[1] = (i / PEER_N) * 256 + 128;
    }
    return 1;
}

/* One frame with the copy `isa`: its cache and its pixels (whole, or bands of `rows`) */
static int frame(int isa, char camc, int32_t w, int32_t h, int32_t fmt, int32_t depth, int cull,
                 const rs_texture *tex, int32_t rows, rs_cvert *cache, uint8_t *colour, void *zbuf,
                 uint32_t *pixels)
{
    static int16_t chunks[2 * (PEER_NTRI / RS_CHUNK + PEER_NSTRIP)];
    rs_frame f;
    rs_band_stats st = { 0, 0, 0, 0 };
    int32_t y0, bpp = fmt == RS_FMT_RGB565 ? 2 : 4;
    memset(&f, 0, sizeof f);
    if (rs_isa_set(isa) != isa || peer_frame(camc, w, h, g_v, g_prims, &f) != 0) return 0;
    f.fmt = fmt; f.depth = depth; f.no_cull = !cull; f.tex = tex; f.cache = cache; f.chunks = chunks;
    f.one_band = rows >= h;
    if (rs_chunk_mem_size(f.prims, f.nprims) > sizeof chunks || rs_frame_prepare(&f) != BR_OK) return 0;
    for (y0 = 0; y0 < h; y0 += rows) {
        int32_t n = h - y0 < rows ? h - y0 : rows;
        if (rs_draw_band(&f, y0, n, colour + (size_t)y0 * (size_t)w * (size_t)bpp, (size_t)(w * bpp), zbuf, &st) != BR_OK)
            return 0;
    }
    *pixels = st.pixels;
    return 1;
}

static void test_same_bytes(void)
{
    enum { WMAX = 640, HMAX = 480 };
    static uint8_t c0[WMAX * HMAX * 4], c1[WMAX * HMAX * 4];
    static uint32_t zb[WMAX * HMAX];
    static rs_cvert k0[PEER_NV], k1[PEER_NV];
    const int32_t sizes[2][2] = { { 320, 240 }, { 640, 480 } };
    rs_texture tex;
    int ci, si, fmt, dep, cull, bi, frames = 0;
    if (rs_isa_set(RS_ISA_V3) != RS_ISA_V3) {
        printf("test_isa: one copy of the drawing code here (%s): nothing to compare\n", rs_isa_name(rs_isa()));
        CHECK_EQ(rs_isa(), RS_ISA_BASE);
        rs_isa_set(RS_ISA_AUTO);
        return;
    }
    CHECK(load_scene());
    if (!g_ps) return;
    tex.w = tex.h = PEER_N; tex.px = g_texels;
    for (ci = 0; ci < 2; ci++)
        for (si = 0; si < 2; si++)
            for (fmt = 0; fmt < 2; fmt++)
                for (dep = 0; dep < 2; dep++)
                    for (cull = 0; cull < 2; cull++)
                        for (bi = 0; bi < 3; bi++) {
                            const int32_t w = sizes[si][0], h = sizes[si][1];
                            const int32_t rows = bi == 1 ? 7 : h;
                            const rs_texture *tx = bi == 2 ? &tex : NULL;   /* textured, whole frame */
                            const size_t bytes = (size_t)w * (size_t)h * (fmt == RS_FMT_RGB565 ? 2 : 4);
                            uint32_t p0 = 0, p1 = 0;
                            int ok = frame(RS_ISA_BASE, "AB"[ci], w, h, fmt, dep, cull, tx, rows, k0, c0, zb, &p0)
                                     && frame(RS_ISA_V3, "AB"[ci], w, h, fmt, dep, cull, tx, rows, k1, c1, zb, &p1);
                            CHECK_MSG(ok, "camera %c %dx%d", "AB"[ci], w, h);
                            if (!ok) continue;
                            CHECK_MSG(memcmp(k0, k1, sizeof k0) == 0 && memcmp(c0, c1, bytes) == 0 && p0 == p1,
                                      "camera %c %dx%d format %d depth %d cull %d rows %d tex %d: the copies differ",
                                      "AB"[ci], w, h, fmt, dep, cull, rows, tx != NULL);
                            CHECK(p0 > (uint32_t)(w * h / 4));   /* a frame of terrain was drawn */
                            frames++;
                        }
    printf("test_isa: %d frames compared, %s and %s\n", frames, rs_isa_name(RS_ISA_BASE), rs_isa_name(RS_ISA_V3));
    rs_isa_set(RS_ISA_AUTO);
}

/* `bitrain render` ARGS (-o OUT appended) with the copy `isa`; the PNG's bytes */
static unsigned char *render_with(int isa, const char *const *args, int n, const char *out, size_t *len)
{
    char *argv[32];
    int i;
    for (i = 0; i < n; i++) argv[i] = (char *)args[i];
    argv[n] = (char *)"-o";
    argv[n + 1] = (char *)out;
    if (rs_isa_set(isa) != isa || cmd_render(n + 2, argv) != 0) return NULL;
    return t_read_file(out, len);
}

/* Water, sky and fog: the lake from the water (the golden camera) and low over it (the
 * lake path's frame 250, where the water fills the frame's last rows), the default view
 * (its lake seen from afar: shore tests), with waves at --time, in RGB888 at three sizes,
 * two band heights and three reflection resolutions and in RGB565; the Kattegat from
 * high and Monai Valley's water. */
static void test_water_same_bytes(void)
{
    enum { N = 10 };
    char lake[256], sea[256], out[256];
    const char *const lo = "40000,66000,420,60000,50000,500", *const low = "25243.8,73994.4,450.0,27752.4,72349.2,150.0";
    const char *const scenes[N][12] = {
        { lake, "--size", "320x240", "--time", "1.5", "--camera", lo, NULL },
        { lake, "--size", "640x480", "--time", "2.25", "--camera", low, NULL },
        { lake, "--size", "640x480", "--time", "7", "--camera", low, "--bands", "7", NULL },
        { lake, "--size", "320x240", "--time", "0.5", "--camera", low, "--format", "rgb565", NULL },
        { lake, "--size", "320x240", "--time", "4", "--camera", low, "--reflection", "full", NULL },
        { lake, "--size", "640x480", "--time", "5", "--camera", lo, "--reflection", "quarter", NULL },
        { lake, "--size", "320x240", "--time", "3", NULL },
        { lake, "--size", "1280x720", "--time", "3", "--bands", "16", NULL },
        { sea, "--size", "320x240", "--time", "1.5", "--camera", "10000,20000,3000,40000,60000,0", NULL },
        { t_data("xyz/monai_valley_bathymetry.txt"), "--xyz-depth", "--size", "320x240", "--time", "1.5", NULL },
    };
    int i;
    if (rs_isa_set(RS_ISA_V3) != RS_ISA_V3) { rs_isa_set(RS_ISA_AUTO); return; }
    snprintf(lake, sizeof lake, "%s", t_data("hgt/N47E009.hgt"));
    snprintf(sea, sizeof sea, "%s", t_data("hgt/N57E011.hgt"));
    snprintf(out, sizeof out, "%s/isa_water.png", t_outdir());
    for (i = 0; i < N; i++) {
        int n = 0;
        size_t l0 = 0, l1 = 0;
        unsigned char *b0, *b1;
        while (scenes[i][n]) n++;
        b0 = render_with(RS_ISA_BASE, scenes[i], n, out, &l0);
        b1 = render_with(RS_ISA_V3, scenes[i], n, out, &l1);
        CHECK_MSG(b0 && b1 && l0 == l1 && !memcmp(b0, b1, l0), "water scene %d: the copies differ", i);
        free(b0);
        free(b1);
    }
    printf("test_isa: %d water frames compared\n", N);
    rs_isa_set(RS_ISA_AUTO);
}

int main(void)
{
    T_RUN(test_same_bytes);
    T_RUN(test_water_same_bytes);
    free(g_ps);
    return t_finish();
}
