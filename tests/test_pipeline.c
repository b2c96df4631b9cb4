#define _POSIX_C_SOURCE 200809L   /* setenv (the SDL test picks the dummy video driver) */
/* tests/test_pipeline.c — the one frame driver (raster/frame.h) and the sinks.
 *
 * On the peer scene (real fuji.png terrain, ../shared/bench/PEERS.md): a frame through
 * rs_pipe_run gives rs_draw_band's whole frame byte for byte for bands of 1, 7, 16, 64
 * rows and the full height, and the statistics of its bands sum to the whole frame's;
 * the post hook sees the band's colour and depth; the chunk table cannot be left out.
 * With synthetic passes: a pass with a margin and a scratch band sees exactly the rows
 * [y0 - margin, y0 + rows + margin) clipped to the frame, a later pass reads them, and
 * rows_touched skips a pass for the bands it cannot touch.  The raw RGB565 sink writes
 * big-endian RGB565, the same bytes from an XRGB8888 frame as from an RGB565 one, and
 * `bitrain render --output-format rgb565` writes the frame its PNG shows, and `-o -`
 * puts the image alone on standard output; the SDL sink fills a streaming texture with
 * the frame. */
#include <fcntl.h>
#include <unistd.h>
#include "raster/frame.h"
#include "raster/raster.h"
#include "platform/cmd.h"
#include "benchmarks/peer_scene.h"
#include "platform/png_io.h"
#include "platform/sink_rgb565.h"
#include "platform/sink_sdl.h"
#include "tests/test.h"

#define W 320
#define H 240
#define NCHUNK (PEER_NTRI / RS_CHUNK + PEER_NSTRIP)   /* >= the chunks of the peer strips */

static peer_scene *g_ps;
static rs_vertex g_v[PEER_NV];
static rs_prim g_prims[PEER_NSTRIP];
static rs_cvert g_cache[PEER_NV];
static int16_t g_chunks[2 * NCHUNK];

/* Peer camera `which` at W x H in format fmt / depth dep, prepared. */
static int peer(rs_frame *f, char which, int32_t fmt, int32_t dep, int one_band)
{
    memset(f, 0, sizeof *f);
    if (!g_ps) {
        g_ps = (peer_scene *)malloc(sizeof *g_ps);
        if (!g_ps || peer_scene_build(t_data("png/fuji.png"), g_ps) != 0) return 0;
        peer_scene_raster(g_ps, g_v, g_prims);
    }
    if (peer_frame(which, W, H, g_v, g_prims, f) != 0) return 0;
    f->fmt = fmt; f->depth = dep; f->cache = g_cache; f->chunks = g_chunks; f->one_band = one_band;
    if (rs_chunk_mem_size(f->prims, f->nprims) > sizeof g_chunks) return 0;
    return rs_frame_prepare(f) == BR_OK;
}

/* A sink that assembles the frame (colour rows packed) and checks the band order. */
typedef struct capture {
    uint8_t *px;
    size_t row;
    int32_t next_y, bands, bad;
} capture;

static br_status capture_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    capture *c = (capture *)user;
    int32_t y;
    if (y0 != c->next_y) c->bad++;
    for (y = 0; y < rows; y++) memcpy(c->px + (size_t)(y0 + y) * c->row, (const uint8_t *)px + (size_t)y * stride, c->row);
    c->next_y = y0 + rows;
    c->bands++;
    return BR_OK;
}

static void pipe_init(rs_pipe *p, int32_t fmt, int32_t dep)
{
    memset(p, 0, sizeof *p);
    p->w = W; p->h = H; p->fmt = fmt; p->depth = dep;
}

static void test_bands_equal_whole_frame(void)
{
    static uint8_t whole[W * H * 4], got[W * H * 4], zb[W * H * 4];
    const int32_t band_rows[5] = { 1, 7, 16, 64, H };
    int32_t fi, k;
    for (fi = 0; fi < 2; fi++) {
        const int32_t fmt = fi ? RS_FMT_RGB565 : RS_FMT_XRGB8888, dep = fi ? RS_DEPTH16 : RS_DEPTH32;
        const size_t bpp = fi ? 2 : 4;
        rs_frame f;
        rs_band_stats ws = { 0, 0, 0, 0 };
        CHECK(peer(&f, 'B', fmt, dep, 0));
        CHECK_EQ(rs_draw_band(&f, 0, H, whole, W * bpp, zb, &ws), BR_OK);
        for (k = 0; k < 5; k++) {
            rs_pipe p;
            rs_pass terrain;
            rs_band_stats total, sum = { 0, 0, 0, 0 };
            capture c = { got, W * bpp, 0, 0, 0 };
            size_t size;
            void *mem;
            int32_t y0;
            pipe_init(&p, fmt, dep);
            CHECK_EQ(rs_pass_terrain(&terrain, &f), BR_OK);
            CHECK_EQ(rs_pipe_add(&p, &terrain), BR_OK);
            size = rs_pipe_mem_size(&p, band_rows[k]);
            mem = malloc(size);
            if (!mem) { CHECK(mem); return; }
            memset(got, 0, sizeof got);
            CHECK_EQ(rs_pipe_run(&p, band_rows[k], mem, size, capture_band, &c, &total), BR_OK);
            CHECK_EQ(c.bad, 0);
            CHECK_EQ(c.bands, (H + band_rows[k] - 1) / band_rows[k]);
            CHECK_MSG(!memcmp(got, whole, (size_t)W * H * bpp), "fmt %d: bands of %d rows differ from the whole frame",
                      fmt, band_rows[k]);
            /* the statistics: each band's alone, summed here, equal rs_pipe_run's total; a
             * pixel is written in one band only, so they sum to the whole frame's pixels;
             * a triangle across bands is set up in each */
            for (y0 = 0; y0 < H; y0 += band_rows[k]) {
                rs_band b;
                rs_band_stats st;
                int32_t rows = H - y0 < band_rows[k] ? H - y0 : band_rows[k];
                CHECK_EQ(rs_pipe_band(&p, y0, rows, mem, size, &b, &st), BR_OK);
                CHECK_EQ(st.passes_run, 1u);
                sum.tris += st.tris; sum.clipped += st.clipped; sum.pixels += st.pixels;
            }
            CHECK_EQ(total.tris, sum.tris);
            CHECK_EQ(total.clipped, sum.clipped);
            CHECK_EQ(total.pixels, sum.pixels);
            CHECK_EQ(total.pixels, ws.pixels);
            CHECK(total.tris >= ws.tris && total.clipped >= ws.clipped);
            if (band_rows[k] == H) CHECK(total.tris == ws.tris && total.clipped == ws.clipped);
            CHECK_EQ(rs_pipe_band(&p, 0, band_rows[k], mem, size - 1, &(rs_band){ 0 }, &sum), BR_E_ARG);
            free(mem);
        }
        CHECK(ws.pixels > W * H / 3 && ws.tris > 1000);
    }
}

/* ------------------------------------------------------------- the post hook */

typedef struct post_check {
    const uint32_t *colour, *depth;     /* the whole frame drawn by rs_draw_band */
    int32_t bad, calls;
} post_check;

static br_status post_sees(const void *user, rs_band *b, rs_band_stats *st)
{
    post_check *pc = (post_check *)(uintptr_t)user;
    int32_t y, x;
    (void)st;
    pc->calls++;
    for (y = 0; y < b->rows; y++)
        for (x = 0; x < b->w; x++) {
            uint32_t *c = (uint32_t *)(void *)((uint8_t *)b->color + (size_t)y * b->stride) + x;
            const uint32_t d = ((const uint32_t *)b->depth)[(size_t)y * (size_t)b->w + (size_t)x];
            const size_t i = (size_t)(b->y0 + y) * W + (size_t)x;
            pc->bad += *c != pc->colour[i] || d != pc->depth[i];
            *c ^= 0xffffffu;   /* a post hook may change the band: the sink sees it */
        }
    return BR_OK;
}

static void test_post_hook(void)
{
    static uint32_t whole[W * H], zb[W * H], got[W * H];
    rs_frame f;
    rs_pipe p;
    rs_pass terrain;
    post_check pc = { whole, zb, 0, 0 };
    capture c = { (uint8_t *)got, W * 4, 0, 0, 0 };
    size_t size, i;
    void *mem;
    int32_t bad = 0;
    CHECK(peer(&f, 'A', RS_FMT_XRGB8888, RS_DEPTH32, 0));
    CHECK_EQ(rs_draw_band(&f, 0, H, whole, W * 4, zb, NULL), BR_OK);
    pipe_init(&p, RS_FMT_XRGB8888, RS_DEPTH32);
    CHECK_EQ(rs_pass_terrain(&terrain, &f), BR_OK);
    CHECK_EQ(rs_pipe_add(&p, &terrain), BR_OK);
    p.post = post_sees;
    p.post_user = &pc;
    size = rs_pipe_mem_size(&p, 16);
    mem = malloc(size);
    if (!mem) { CHECK(mem); return; }
    CHECK_EQ(rs_pipe_run(&p, 16, mem, size, capture_band, &c, NULL), BR_OK);
    CHECK_EQ(pc.calls, H / 16);
    CHECK_EQ(pc.bad, 0);
    for (i = 0; i < (size_t)W * H; i++) bad += got[i] != (whole[i] ^ 0xffffffu);
    CHECK_EQ(bad, 0);
    free(mem);
}

/* ------------------------------------------------------------- margins, scratch, skipping */

#define MARGIN 5
#define SW 24
#define SH 50

/* Pass 0 (scratch, margin MARGIN): writes each scratch row's frame row number into its
 * colour and depth.  Pass 1 (rows_touched: only rows 20..29): marks its rows.  Pass 2
 * (into the band): copies from pass 0's scratch the row 2 rows below, checking every
 * scratch row it can see, and whether pass 1 ran. */
typedef struct synth {
    int32_t bad, runs[3];
} synth;

static br_status rows_to_scratch(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    synth *s = (synth *)(uintptr_t)user;
    int32_t y, x, top = b->y0 - MARGIN < 0 ? 0 : b->y0 - MARGIN;
    int32_t bottom = b->y0 + b->rows + MARGIN > SH ? SH : b->y0 + b->rows + MARGIN;
    (void)st;
    s->runs[0]++;
    if (!b->scratch[self] || b->scratch_y0[self] != top || b->scratch_rows[self] != bottom - top
        || b->scratch_stride[self] < (size_t)SW * 4 || !b->scratch_depth[self]) { s->bad++; return BR_OK; }
    for (y = 0; y < b->scratch_rows[self]; y++)
        for (x = 0; x < SW; x++) {
            ((uint32_t *)(void *)((uint8_t *)b->scratch[self] + (size_t)y * b->scratch_stride[self]))[x] =
                (uint32_t)(b->scratch_y0[self] + y);
            ((uint32_t *)b->scratch_depth[self])[(size_t)y * SW + (size_t)x] = (uint32_t)(b->scratch_y0[self] + y) + 1000u;
        }
    return BR_OK;
}

static int rows_20_29(const void *user, int32_t y0, int32_t rows)
{
    (void)user;
    return y0 < 30 && y0 + rows > 20;
}

static br_status mark_rows(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    synth *s = (synth *)(uintptr_t)user;
    (void)self; (void)st;
    s->runs[1]++;
    if (!(b->y0 < 30 && b->y0 + b->rows > 20)) s->bad++;   /* skipping failed */
    return BR_OK;
}

static br_status copy_from_scratch(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    synth *s = (synth *)(uintptr_t)user;
    int32_t y, x;
    (void)self; (void)st;
    s->runs[2]++;
    if (!b->scratch[0] || b->scratch[1] || b->scratch[2]) { s->bad++; return BR_OK; }
    for (y = 0; y < b->scratch_rows[0]; y++) {   /* every row of the scratch band as written */
        const uint32_t *c = (const uint32_t *)(void *)((uint8_t *)b->scratch[0] + (size_t)y * b->scratch_stride[0]);
        const uint32_t *d = (const uint32_t *)b->scratch_depth[0] + (size_t)y * SW;
        for (x = 0; x < SW; x++)
            s->bad += c[x] != (uint32_t)(b->scratch_y0[0] + y) || d[x] != (uint32_t)(b->scratch_y0[0] + y) + 1000u;
    }
    for (y = 0; y < b->rows; y++) {
        int32_t src = b->y0 + y + 2 < SH ? b->y0 + y + 2 : SH - 1;   /* inside the margin */
        const uint32_t *c = (const uint32_t *)(void *)((uint8_t *)b->scratch[0]
                                                         + (size_t)(src - b->scratch_y0[0]) * b->scratch_stride[0]);
        uint32_t *o = (uint32_t *)(void *)((uint8_t *)b->color + (size_t)y * b->stride);
        uint32_t ran1 = (st->passes_run >> 1) & 1u;
        for (x = 0; x < SW; x++) o[x] = c[x] | ran1 << 16;
    }
    return BR_OK;
}

static void test_margin_scratch_skip(void)
{
    static uint32_t got[SW * SH];
    const int32_t band_rows[4] = { 1, 7, 16, SH };
    int32_t k, y, x;
    for (k = 0; k < 4; k++) {
        synth s;
        rs_pipe p;
        rs_pass a, m, cp;
        capture c = { (uint8_t *)got, SW * 4, 0, 0, 0 };
        size_t size;
        void *mem;
        int32_t nb = (SH + band_rows[k] - 1) / band_rows[k], bad = 0, touched = 0;
        memset(&s, 0, sizeof s);
        memset(&p, 0, sizeof p);
        memset(&a, 0, sizeof a); memset(&m, 0, sizeof m); memset(&cp, 0, sizeof cp);
        p.w = SW; p.h = SH; p.fmt = RS_FMT_XRGB8888; p.depth = RS_DEPTH32;
        a.name = "rows"; a.margin = MARGIN; a.scratch = 1; a.run = rows_to_scratch; a.user = &s;
        m.name = "mark"; m.rows_touched = rows_20_29; m.run = mark_rows; m.user = &s;
        cp.name = "copy"; cp.run = copy_from_scratch; cp.user = &s;
        CHECK_EQ(rs_pipe_add(&p, &a), BR_OK);
        CHECK_EQ(rs_pipe_add(&p, &m), BR_OK);
        CHECK_EQ(rs_pipe_add(&p, &cp), BR_OK);
        size = rs_pipe_mem_size(&p, band_rows[k]);
        CHECK(size >= (size_t)SW * (size_t)band_rows[k] * 8 + (size_t)SW * (size_t)(band_rows[k] + 2 * MARGIN < SH ? band_rows[k] + 2 * MARGIN : SH) * 8);
        mem = malloc(size);
        if (!mem) { CHECK(mem); return; }
        CHECK_EQ(rs_pipe_run(&p, band_rows[k], mem, size, capture_band, &c, NULL), BR_OK);
        CHECK_MSG(s.bad == 0, "bands of %d rows: %d wrong", band_rows[k], s.bad);
        CHECK_EQ(s.runs[0], nb);
        CHECK_EQ(s.runs[2], nb);
        for (y = 0; y < SH; y += band_rows[k]) touched += y < 30 && y + band_rows[k] > 20;
        CHECK_EQ(s.runs[1], touched);
        for (y = 0; y < SH; y++) {
            int32_t b0 = y / band_rows[k] * band_rows[k];
            uint32_t ran1 = b0 < 30 && b0 + band_rows[k] > 20;
            uint32_t want = (uint32_t)(y + 2 < SH ? y + 2 : SH - 1) | ran1 << 16;
            for (x = 0; x < SW; x++) bad += got[y * SW + x] != want;
        }
        CHECK_MSG(bad == 0, "bands of %d rows: %d pixels wrong", band_rows[k], bad);
        free(mem);
    }
    {   /* malformed passes are refused */
        rs_pipe p;
        rs_pass q;
        int32_t i;
        memset(&p, 0, sizeof p);
        memset(&q, 0, sizeof q);
        CHECK_EQ(rs_pipe_add(&p, &q), BR_E_ARG);            /* no run */
        q.run = mark_rows; q.margin = -1;
        CHECK_EQ(rs_pipe_add(&p, &q), BR_E_ARG);
        q.margin = 0; q.scratch = 2;
        CHECK_EQ(rs_pipe_add(&p, &q), BR_E_ARG);
        q.scratch = 1; p.depth = RS_DEPTH_NONE;
        CHECK_EQ(rs_pipe_add(&p, &q), BR_E_ARG);            /* scratch without depth */
        p.depth = RS_DEPTH32;
        q.scratch = 0;
        for (i = 0; i < RS_PIPE_MAX_PASSES; i++) CHECK_EQ(rs_pipe_add(&p, &q), BR_OK);
        CHECK_EQ(rs_pipe_add(&p, &q), BR_E_ARG);            /* full */
    }
}

/* ------------------------------------------------------------- the chunk table */

static void test_chunk_table_required(void)
{
    static uint32_t colour[W * H], zb[W * H];
    rs_frame f;
    rs_pass terrain;
    rs_pipe p;
    rs_band b;
    rs_band_stats st;
    size_t size;
    void *mem;
    CHECK(peer(&f, 'B', RS_FMT_XRGB8888, RS_DEPTH32, 0));
    f.chunks = NULL;
    CHECK_EQ(rs_frame_prepare(&f), BR_E_ARG);
    CHECK_EQ(rs_pass_terrain(&terrain, &f), BR_E_ARG);
    /* a frame prepared as one band: whole-frame bands only through the driver */
    CHECK(peer(&f, 'B', RS_FMT_XRGB8888, RS_DEPTH32, 1));
    pipe_init(&p, RS_FMT_XRGB8888, RS_DEPTH32);
    CHECK_EQ(rs_pass_terrain(&terrain, &f), BR_OK);
    CHECK_EQ(rs_pipe_add(&p, &terrain), BR_OK);
    size = rs_pipe_mem_size(&p, H);
    mem = malloc(size);
    if (!mem) { CHECK(mem); return; }
    CHECK_EQ(rs_pipe_band(&p, 0, 64, mem, size, &b, &st), BR_E_ARG);
    CHECK_EQ(rs_pipe_band(&p, 0, H, mem, size, &b, &st), BR_OK);
    CHECK_EQ(rs_draw_band(&f, 0, H, colour, W * 4, zb, NULL), BR_OK);
    CHECK(!memcmp(b.color, colour, sizeof colour));
    free(mem);
}

/* ------------------------------------------------------------- the raw RGB565 sink */

static void test_rgb565_sink(void)
{
    static uint8_t a[W * H * 2], bb[W * H * 2];
    const uint32_t px888[3] = { 0xff0000u, 0x00ff00u, 0x123456u };
    const uint16_t px565[2] = { 0xf800u, 0x1234u };
    uint8_t out[6];
    char path[512];
    sink_rgb565 s;
    br_err err;
    rs_frame f;
    int32_t fi;
    sink_rgb565_row(RS_FMT_XRGB8888, px888, 3, out);
    CHECK(out[0] == 0xf8 && out[1] == 0x00 && out[2] == 0x07 && out[3] == 0xe0);
    CHECK(out[4] == (0x10 | 0x01) && out[5] == (0xa0 | 0x0a));   /* 0x12>>3=2, 0x34>>2=13, 0x56>>3=10 */
    sink_rgb565_row(RS_FMT_RGB565, px565, 2, out);
    CHECK(out[0] == 0xf8 && out[1] == 0x00 && out[2] == 0x12 && out[3] == 0x34);
    /* the same peer frame in both formats through the file sink: the same bytes */
    snprintf(path, sizeof path, "%s/pipeline.rgb565", t_outdir());
    for (fi = 0; fi < 2; fi++) {
        const int32_t fmt = fi ? RS_FMT_RGB565 : RS_FMT_XRGB8888;
        rs_pipe p;
        rs_pass terrain;
        size_t size, len = 0;
        void *mem;
        unsigned char *file;
        CHECK(peer(&f, 'A', fmt, RS_DEPTH32, 0));
        pipe_init(&p, fmt, RS_DEPTH32);
        CHECK_EQ(rs_pass_terrain(&terrain, &f), BR_OK);
        CHECK_EQ(rs_pipe_add(&p, &terrain), BR_OK);
        size = rs_pipe_mem_size(&p, 7);
        mem = malloc(size);
        if (!mem) { CHECK(mem); return; }
        CHECK_EQ(sink_rgb565_open(&s, path, W, fmt, &err), BR_OK);
        CHECK_EQ(rs_pipe_run(&p, 7, mem, size, sink_rgb565_band, &s, NULL), BR_OK);
        CHECK_EQ(sink_rgb565_close(&s, &err), BR_OK);
        file = t_read_file(path, &len);
        CHECK(file && len == sizeof a);
        if (file && len == sizeof a) memcpy(fi ? bb : a, file, len);
        free(file);
        free(mem);
    }
    CHECK(!memcmp(a, bb, sizeof a));
    CHECK_EQ(sink_rgb565_open(&s, "tests/out/no/such/dir/x.rgb565", W, RS_FMT_RGB565, &err), BR_E_IO);
    CHECK(strstr(err.msg, "x.rgb565") != NULL);
}

/* `bitrain render --output-format rgb565` on real terrain (N47E009) in 5-row bands: the
 * PNG of the same frame, pixel for pixel (RGB565 expanded by bit replication), and the
 * same bytes from an XRGB8888 frame.  Without water and fog: an RGB565 frame dithers
 * their gradients, which an XRGB8888 frame converted by the sink does not. */
static void test_render_raw(void)
{
    char raw[512], raw888[512], png[512];
    const char *dem = t_data("hgt/N47E009.hgt");
    const char *a1[] = { dem, "-o", raw, "--size", "40x30", "--bands", "5", "--format", "rgb565",
                         "--output-format", "rgb565", "--no-water", "--no-fog" };
    const char *a2[] = { dem, "-o", raw888, "--size", "40x30", "--output-format", "rgb565", "--no-water", "--no-fog" };
    const char *a3[] = { dem, "-o", png, "--size", "40x30", "--format", "rgb565", "--no-water", "--no-fog" };
    unsigned char *r1, *r2;
    uint8_t *rgb = NULL;
    size_t n1 = 0, n2 = 0;
    int w = 0, h = 0, i, bad = 0;
    br_err err;
    snprintf(raw, sizeof raw, "%s/render.rgb565", t_outdir());
    snprintf(raw888, sizeof raw888, "%s/render888.rgb565", t_outdir());
    snprintf(png, sizeof png, "%s/render565.png", t_outdir());
    CHECK_EQ(cmd_render(13, (char **)(uintptr_t)a1), 0);
    CHECK_EQ(cmd_render(9, (char **)(uintptr_t)a2), 0);
    CHECK_EQ(cmd_render(9, (char **)(uintptr_t)a3), 0);
    r1 = t_read_file(raw, &n1);
    r2 = t_read_file(raw888, &n2);
    CHECK(r1 && r2 && n1 == 40 * 30 * 2 && n2 == n1 && !memcmp(r1, r2, n1));
    CHECK_EQ(png_read_rgb(png, &w, &h, &rgb, &err), BR_OK);
    if (r1 && rgb && n1 == 40 * 30 * 2 && w == 40 && h == 30)
        for (i = 0; i < 40 * 30; i++) {
            uint32_t v = (uint32_t)r1[2 * i] << 8 | r1[2 * i + 1], r = v >> 11, g = (v >> 5) & 63, b = v & 31;
            bad += rgb[3 * i] != ((r << 3) | (r >> 2)) || rgb[3 * i + 1] != ((g << 2) | (g >> 4))
                   || rgb[3 * i + 2] != ((b << 3) | (b >> 2));
        }
    else CHECK(0);
    CHECK_EQ(bad, 0);
    free(r1); free(r2); free(rgb);
}

/* fn(argc, argv) (a command) with stdout sent to file `path`; its exit code. */
static int cmd_to_file(int (*fn)(int, char **), int argc, const char **argv, const char *path)
{
    int saved, fd, rc;
    fflush(stdout);
    saved = dup(1);
    fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (saved < 0 || fd < 0) return -100;
    dup2(fd, 1);
    close(fd);
    rc = fn(argc, (char **)(uintptr_t)argv);
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    return rc;
}

/* `render -o -`, with water (whose lake lines the command prints otherwise): standard
 * output carries the image and nothing else, the same bytes as `-o FILE`, in both
 * output formats; `hillshade -o -` the same. */
static void test_render_stdout(void)
{
    static const char *const fmts[2] = { "png", "rgb565" };
    const char *dem = t_data("hgt/N47E009.hgt");
    int k;
    for (k = 0; k < 2; k++) {
        char file[512], piped[512];
        const char *to_file[] = { dem, "-o", file, "--size", "40x30", "--output-format", fmts[k] };
        const char *to_out[] = { dem, "-o", "-", "--size", "40x30", "--output-format", fmts[k] };
        unsigned char *a, *b;
        size_t na = 0, nb = 0;
        snprintf(file, sizeof file, "%s/render_file.%s", t_outdir(), fmts[k]);
        snprintf(piped, sizeof piped, "%s/render_stdout.%s", t_outdir(), fmts[k]);
        CHECK_EQ(cmd_render(7, (char **)(uintptr_t)to_file), 0);
        CHECK_EQ(cmd_to_file(cmd_render, 7, to_out, piped), 0);
        a = t_read_file(file, &na);
        b = t_read_file(piped, &nb);
        CHECK_MSG(a && b && na == nb && !memcmp(a, b, na), "-o - with %s: %zu bytes on stdout, %zu in the file",
                  fmts[k], nb, na);
        if (k == 1) CHECK_EQ(nb, (size_t)40 * 30 * 2);
        else CHECK(nb > 8 && b && !memcmp(b, "\x89PNG", 4));
        free(a); free(b);
    }
    {   /* hillshade -o -: the PNG alone too (it names the file it wrote otherwise) */
        char file[512], piped[512];
        const char *to_file[] = { dem, "-o", file }, *to_out[] = { dem, "-o", "-" };
        unsigned char *a, *b;
        size_t na = 0, nb = 0;
        snprintf(file, sizeof file, "%s/hillshade_file.png", t_outdir());
        snprintf(piped, sizeof piped, "%s/hillshade_stdout.png", t_outdir());
        CHECK_EQ(cmd_hillshade(3, (char **)(uintptr_t)to_file), 0);
        CHECK_EQ(cmd_to_file(cmd_hillshade, 3, to_out, piped), 0);
        a = t_read_file(file, &na);
        b = t_read_file(piped, &nb);
        CHECK_MSG(a && b && na == nb && !memcmp(a, b, na), "hillshade -o -: %zu bytes on stdout, %zu in the file", nb, na);
        free(a); free(b);
    }
}

/* The SDL sink into a streaming texture (SDL's dummy video driver, software renderer):
 * the texture, read back, and the keep buffer hold the whole frame, in bands of 64 rows. */
static void test_sdl_sink(void)
{
    static uint32_t whole[W * H], zb[W * H], keep[W * H], back[W * H];
    SDL_Window *win = NULL;
    SDL_Renderer *ren = NULL;
    SDL_Texture *tex = NULL;
    sink_sdl ss;
    rs_frame f;
    rs_pipe p;
    rs_pass terrain;
    size_t size;
    void *mem;
    setenv("SDL_VIDEODRIVER", "dummy", 1);
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        printf("  test_sdl_sink: skipped (no SDL video driver: %s)\n", SDL_GetError());
        return;
    }
    win = SDL_CreateWindow("test", 0, 0, W, H, SDL_WINDOW_HIDDEN);
    ren = win ? SDL_CreateRenderer(win, -1, SDL_RENDERER_SOFTWARE) : NULL;
    tex = ren ? SDL_CreateTexture(ren, sink_sdl_format(RS_FMT_XRGB8888), SDL_TEXTUREACCESS_STREAMING, W, H) : NULL;
    CHECK_MSG(tex != NULL, "SDL: %s", SDL_GetError());
    CHECK(peer(&f, 'B', RS_FMT_XRGB8888, RS_DEPTH32, 0));
    CHECK_EQ(rs_draw_band(&f, 0, H, whole, W * 4, zb, NULL), BR_OK);
    pipe_init(&p, RS_FMT_XRGB8888, RS_DEPTH32);
    CHECK_EQ(rs_pass_terrain(&terrain, &f), BR_OK);
    CHECK_EQ(rs_pipe_add(&p, &terrain), BR_OK);
    size = rs_pipe_mem_size(&p, 64);
    mem = malloc(size);
    if (tex && mem) {
        sink_sdl_init(&ss, tex, W, H, RS_FMT_XRGB8888, keep);
        CHECK_EQ(sink_sdl_band(&ss, 0, 1, whole, W * 4), BR_E_ARG);    /* not locked */
        CHECK_EQ(sink_sdl_lock(&ss), BR_OK);
        CHECK_EQ(rs_pipe_run(&p, 64, mem, size, sink_sdl_band, &ss, NULL), BR_OK);
        CHECK_EQ(sink_sdl_band(&ss, H - 1, 2, whole, W * 4), BR_E_ARG);   /* beyond the texture */
        sink_sdl_unlock(&ss);
        CHECK(!memcmp(keep, whole, sizeof whole));
        CHECK_EQ(SDL_RenderCopy(ren, tex, NULL, NULL), 0);
        CHECK_EQ(SDL_RenderReadPixels(ren, NULL, SDL_PIXELFORMAT_RGB888, back, W * 4), 0);
        {
            int32_t i, bad = 0;
            for (i = 0; i < W * H; i++) bad += (back[i] & 0xffffffu) != whole[i];
            CHECK_EQ(bad, 0);
        }
    }
    free(mem);
    if (tex) SDL_DestroyTexture(tex);
    if (ren) SDL_DestroyRenderer(ren);
    if (win) SDL_DestroyWindow(win);
    SDL_Quit();
}

int main(void)
{
    T_RUN(test_bands_equal_whole_frame);
    T_RUN(test_post_hook);
    T_RUN(test_margin_scratch_skip);
    T_RUN(test_chunk_table_required);
    T_RUN(test_rgb565_sink);
    T_RUN(test_render_raw);
    T_RUN(test_render_stdout);
    T_RUN(test_sdl_sink);
    free(g_ps);
    return t_finish();
}
