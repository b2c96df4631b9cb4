/* tests/test_raster.c — the integer rasteriser, pixel-exact.
 *
 * Fill rule (screen-space input through rs_cvert_set, write counting through
 * rs_frame.debug_count, drawn by tests/support/raster_count.c: every frame here goes through
 * that copy, the library's code plus the counting variant): grids and fans of triangles sharing edges cover every pixel
 * exactly once, ties on pixel centres included; degenerate, line, tiny and huge
 * triangles.  World-space input: near-plane crossings, cameras below and inside real
 * terrain (N47E009), vertices far outside the guard band.  Bands of 1, 7, 16 and 240
 * rows give the full frame's bytes; RGB565 is RGB888 reduced; the vertex cache that
 * rs_frame_prepare fills equals a plain per-vertex transcription of the transform
 * (real terrain, random cameras, points on the near/far/screen/guard-band edges); a
 * golden PNG of real terrain is compared byte for byte (on mismatch:
 * tests/out/<name>.actual.png and .diff.png; BITRAIN_UPDATE_GOLDEN=1 rewrites the
 * golden file). */
#include <math.h>
#include "tests/test.h"
#include "core/cam.h"
#include "platform/load.h"
#include "platform/png_io.h"
#include "raster/raster.h"
#include "tests/support/raster_count.h"
#include "raster/ramp.h"
#include "raster/terrain.h"

static uint32_t lcg_state = 12345;
static uint32_t lcg(void) { lcg_state = lcg_state * 1103515245u + 12345u; return lcg_state >> 8; }

/* The chunk table rs_frame_prepare requires, for every frame prepared here (at most
 * 4096 chunks of RS_CHUNK triangles), and what the last render_full drew. */
static int16_t g_chunks[2 * 4096];
static rs_band_stats g_st;

/* Renders f whole (one band) into a fresh buffer (XRGB8888 or RGB565) and returns it. */
static void *render_full(rs_frame *f)
{
    size_t bpp = f->fmt == RS_FMT_RGB565 ? 2 : 4;
    void *c = calloc((size_t)f->w * (size_t)f->h, bpp);
    void *z = calloc((size_t)f->w * (size_t)f->h, 4);
    CHECK(c && z);
    memset(&g_st, 0, sizeof g_st);
    CHECK_EQ(cnt_draw_band(f, 0, f->h, c, (size_t)f->w * bpp, z, &g_st), BR_OK);
    free(z);
    return c;
}

/* ------------------------------------------------------------- screen space */

typedef struct sv { int32_t x, y; } sv;

/* Draws triangles (list of vertex indices) given in sub-pixels with write counting;
 * returns the count image (w*h uint32).  Each triangle is made front-facing first
 * unless keep_order. */
static uint32_t *count_tris(int32_t w, int32_t h, const sv *v, uint32_t nv, const uint32_t *idx,
                            uint32_t nidx, int no_cull)
{
    rs_frame f;
    rs_cvert *cache = malloc(sizeof *cache * nv);
    rs_prim pr;
    uint32_t i, *img;
    memset(&f, 0, sizeof f);
    for (i = 0; i < nv; i++) rs_cvert_set(&cache[i], w, h, v[i].x, v[i].y, 1000, 0x123456u);
    pr.kind = RS_LIST; pr.n = nidx; pr.idx = idx;
    f.w = w; f.h = h; f.fmt = RS_FMT_XRGB8888; f.depth = RS_DEPTH32; f.no_cull = no_cull;
    f.cache = cache; f.nv = nv; f.prims = &pr; f.nprims = 1; f.debug_count = 1;
    img = render_full(&f);
    free(cache);
    return img;
}

/* Orients triangle (a, b, c) counter-clockwise as seen (y down: cross < 0). */
static void front(const sv *v, uint32_t *t)
{
    int64_t cr = (int64_t)(v[t[1]].x - v[t[0]].x) * (v[t[2]].y - v[t[0]].y)
               - (int64_t)(v[t[2]].x - v[t[0]].x) * (v[t[1]].y - v[t[0]].y);
    if (cr > 0) { uint32_t u = t[1]; t[1] = t[2]; t[2] = u; }
}

static int all_equal(const uint32_t *img, int32_t n, uint32_t want, int32_t *bad)
{
    int32_t i, nb = 0;
    for (i = 0; i < n; i++) if (img[i] != want) nb++;
    *bad = nb;
    return nb == 0;
}

/* The (cols + 1) x (rows + 1) vertices of a grid spanning [-20 px, w + 20 px] so the screen
 * is covered; with cols, rows dividing the span the cell corners sit on pixel centres
 * (exact ties); jitter stays below a third of a cell so the mesh stays valid. */
static sv *grid_vertices(int jitter, int32_t w, int32_t h, int32_t cols, int32_t rows)
{
    sv *v = calloc((size_t)(cols + 1) * (size_t)(rows + 1), sizeof *v);
    int32_t i, j, cw = (w + 40) * 16 / cols, ch = (h + 40) * 16 / rows, amp = (cw < ch ? cw : ch) / 3;
    CHECK(v != NULL);
    if (!v) exit(1);
    for (j = 0; j <= rows; j++)
        for (i = 0; i <= cols; i++) {
            sv *p = &v[j * (cols + 1) + i];
            p->x = -20 * 16 + (w + 40) * 16 * i / cols + 8;
            p->y = -20 * 16 + (h + 40) * 16 * j / rows + 8;
            if (jitter && amp > 0 && i > 0 && i < cols && j > 0 && j < rows) {
                p->x += (int32_t)(lcg() % (uint32_t)(2 * amp + 1)) - amp;
                p->y += (int32_t)(lcg() % (uint32_t)(2 * amp + 1)) - amp;
            }
        }
    return v;
}

static void grid_case(int jitter, int32_t w, int32_t h, int32_t cols, int32_t rows)
{
    sv *v = grid_vertices(jitter, w, h, cols, rows);
    uint32_t *idx = calloc((size_t)cols * (size_t)rows * 6, sizeof *idx), n = 0, *img;
    int32_t i, j, bad;
    for (j = 0; j < rows; j++)
        for (i = 0; i < cols; i++) {
            uint32_t a = (uint32_t)(j * (cols + 1) + i), b = a + 1, c = a + (uint32_t)cols + 1, d = c + 1;
            uint32_t *t = idx + n;
            if ((i + j) & 1) { t[0] = a; t[1] = b; t[2] = d; t[3] = a; t[4] = d; t[5] = c; }
            else { t[0] = a; t[1] = b; t[2] = c; t[3] = b; t[4] = d; t[5] = c; }
            front(v, t); front(v, t + 3);
            n += 6;
        }
    img = count_tris(w, h, v, (uint32_t)((cols + 1) * (rows + 1)), idx, n, 0);
    CHECK_MSG(all_equal(img, w * h, 1, &bad), "grid %dx%d jitter %d: %d pixels not covered once", cols, rows, jitter, bad);
    free(img);
    /* reversed: all back faces; culled -> nothing, not culled -> once */
    for (i = 0; i < (int32_t)n; i += 3) { uint32_t u = idx[i + 1]; idx[i + 1] = idx[i + 2]; idx[i + 2] = u; }
    img = count_tris(w, h, v, (uint32_t)((cols + 1) * (rows + 1)), idx, n, 0);
    CHECK_MSG(all_equal(img, w * h, 0, &bad), "back faces drawn: %d pixels", bad);
    free(img);
    img = count_tris(w, h, v, (uint32_t)((cols + 1) * (rows + 1)), idx, n, 1);
    CHECK_MSG(all_equal(img, w * h, 1, &bad), "no-cull grid: %d pixels not covered once", bad);
    free(img);
    free(v); free(idx);
}

/* The same grid drawn as one triangle strip per row of cells (the strip pairs' quad
 * path, both groups of columns of its 8-column boxes, and the one-triangle-at-a-time
 * code at the screen's edges), counting writes: every pixel exactly once; the strips
 * reversed (all back faces): none with culling, once without. */
static void strip_grid_case(int jitter, int32_t w, int32_t h, int32_t cols, int32_t rows)
{
    sv *v = grid_vertices(jitter, w, h, cols, rows);
    uint32_t *idx = calloc((size_t)rows * (size_t)(cols + 1) * 2, sizeof *idx), *img;
    rs_prim *pr = calloc((size_t)rows, sizeof *pr);
    rs_cvert *cache = malloc(sizeof *cache * (size_t)(cols + 1) * (size_t)(rows + 1));
    const uint32_t nv = (uint32_t)((cols + 1) * (rows + 1));
    int32_t i, j, pass, bad;
    CHECK(idx && pr && cache);
    if (!idx || !pr || !cache) exit(1);
    for (i = 0; i < (int32_t)nv; i++) rs_cvert_set(&cache[i], w, h, v[i].x, v[i].y, 1000, 0x123456u);
    for (pass = 0; pass < 3; pass++) {
        rs_frame f;
        /* pass 0: top row first (front faces: (top-left, bottom-left, top-right) is
         * counter-clockwise as seen); passes 1, 2: bottom row first (back faces) */
        for (j = 0; j < rows; j++) {
            uint32_t *s = idx + (size_t)j * (size_t)(cols + 1) * 2;
            for (i = 0; i <= cols; i++) {
                uint32_t top = (uint32_t)(j * (cols + 1) + i), bot = top + (uint32_t)cols + 1;
                s[2 * i] = pass ? bot : top;
                s[2 * i + 1] = pass ? top : bot;
            }
            pr[j].kind = RS_STRIP; pr[j].n = (uint32_t)(cols + 1) * 2; pr[j].idx = s;
        }
        memset(&f, 0, sizeof f);
        f.w = w; f.h = h; f.fmt = RS_FMT_XRGB8888; f.depth = RS_DEPTH32; f.no_cull = pass == 2;
        f.cache = cache; f.nv = nv; f.prims = pr; f.nprims = rows; f.debug_count = 1;
        img = render_full(&f);
        CHECK_MSG(all_equal(img, w * h, pass == 1 ? 0 : 1, &bad), "strip grid %dx%d jitter %d pass %d: %d pixels wrong",
                  cols, rows, jitter, pass, bad);
        free(img);
    }
    free(v); free(idx); free(pr); free(cache);
}

static void test_fill_grid(void)
{
    grid_case(0, 61, 47, 101, 87);   /* corners on pixel centres: edges through centres */
    grid_case(0, 61, 47, 9, 7);
    grid_case(1, 61, 47, 9, 7);
    grid_case(1, 64, 48, 40, 30);    /* cells of ~2.6 x 2.6 px: the tiny path */
    grid_case(1, 53, 37, 120, 90);   /* sub-pixel cells */
    grid_case(1, 200, 150, 3, 2);    /* large triangles: the general path */
    strip_grid_case(0, 61, 47, 101, 87);  /* corners on centres, sub-pixel cells */
    strip_grid_case(1, 64, 48, 40, 30);   /* ~2.6 px cells: joint boxes of up to 4 x 4 */
    strip_grid_case(1, 61, 47, 15, 40);   /* ~6.7 x 2.2 px cells: boxes of 5 to 8 columns */
    strip_grid_case(0, 61, 47, 15, 40);
    strip_grid_case(1, 67, 45, 12, 20);   /* ~8.9 x 4.3 px: tiny and general triangles */
    strip_grid_case(1, 53, 37, 120, 90);  /* sub-pixel cells */
}

static void test_fill_fan(void)
{
    const int32_t w = 67, h = 45, nrim = 40;
    sv v[41];
    uint32_t idx[120], *img;
    int32_t i, bad, k;
    for (k = 0; k < 3; k++) {
        /* centre on a pixel centre, on a pixel corner, and off-grid */
        v[0].x = 33 * 16 + (k == 0 ? 8 : k == 1 ? 0 : 5);
        v[0].y = 22 * 16 + (k == 0 ? 8 : k == 1 ? 0 : 11);
        for (i = 0; i < nrim; i++) {
            double a = 2 * 3.14159265358979323846 * i / nrim;
            v[1 + i].x = v[0].x + (int32_t)lround(cos(a) * 150 * 16);
            v[1 + i].y = v[0].y + (int32_t)lround(sin(a) * 150 * 16);
        }
        for (i = 0; i < nrim; i++) {
            idx[3 * i] = 0; idx[3 * i + 1] = (uint32_t)(1 + i); idx[3 * i + 2] = (uint32_t)(1 + (i + 1) % nrim);
            front(v, idx + 3 * i);
        }
        img = count_tris(w, h, v, (uint32_t)nrim + 1, idx, (uint32_t)nrim * 3, 0);
        CHECK_MSG(all_equal(img, w * h, 1, &bad), "fan %d: %d pixels not covered once", k, bad);
        free(img);
    }
}

/* The clear (rs_draw_band's first step, 32 bytes a store with an overlapping last
 * one): every pixel the sky, every depth the far plane's, and not a byte more, for
 * widths around the store sizes, both pixel formats and depth sizes, rows packed
 * (stride = row) and padded (stride = row + 8: the padding keeps its bytes). */
static void test_clear(void)
{
    static const int32_t ws[] = { 1, 2, 3, 7, 8, 9, 15, 16, 17, 31, 33, 40, 63, 64, 65, 100, 333 };
    enum { ROWS = 3, GUARD = 64 };
    static uint8_t cbuf[(333 * 4 + 8) * ROWS + GUARD], zbuf[333 * 4 * ROWS + GUARD];
    rs_cvert cache[1];
    rs_frame f;
    size_t wi;
    int32_t fmt, dep, pad, bad = 0;
    for (wi = 0; wi < sizeof ws / sizeof ws[0]; wi++)
        for (fmt = 0; fmt < 2; fmt++)
            for (dep = 0; dep < 2; dep++)
                for (pad = 0; pad <= 8; pad += 8) {
                    const int32_t w = ws[wi], cb = fmt == RS_FMT_RGB565 ? 2 : 4, zb = dep == RS_DEPTH16 ? 2 : 4;
                    const size_t row = (size_t)w * (size_t)cb, stride = row + (size_t)pad;
                    const uint32_t sky = fmt == RS_FMT_RGB565 ? 0x9e7fu : 0x99ccffu;
                    uint32_t dfar;
                    size_t i;
                    int32_t x, y;
                    memset(&f, 0, sizeof f);
                    f.w = w; f.h = ROWS; f.fmt = fmt; f.depth = dep; f.clear_rgb = 0x99ccffu; f.cache = cache;
                    f.vp.znear = 3; f.vp.zfar = 1000;
                    dfar = (uint32_t)((int64_t)RS_DEPTH_ONE * 3 / 1000);
                    memset(cbuf, 0xa5, sizeof cbuf); memset(zbuf, 0xa5, sizeof zbuf);
                    CHECK_EQ(cnt_draw_band(&f, 0, ROWS, cbuf, stride, zbuf, NULL), BR_OK);
                    for (y = 0; y < ROWS; y++) {
                        for (x = 0; x < w; x++) {
                            const uint8_t *c = cbuf + (size_t)y * stride + (size_t)x * (size_t)cb;
                            const uint8_t *z = zbuf + ((size_t)y * (size_t)w + (size_t)x) * (size_t)zb;
                            uint16_t h16;
                            uint32_t cv, zv;
                            if (cb == 2) { memcpy(&h16, c, 2); cv = h16; } else memcpy(&cv, c, 4);
                            if (zb == 2) { memcpy(&h16, z, 2); zv = h16; } else memcpy(&zv, z, 4);
                            bad += cv != sky || zv != (dep == RS_DEPTH16 ? dfar >> 14 : dfar);
                        }
                        for (i = 0; i < (size_t)pad; i++) bad += cbuf[(size_t)y * stride + row + i] != 0xa5;
                    }
                    for (i = stride * ROWS; i < sizeof cbuf; i++) bad += cbuf[i] != 0xa5;
                    for (i = (size_t)w * ROWS * (size_t)zb; i < sizeof zbuf; i++) bad += zbuf[i] != 0xa5;
                    CHECK_MSG(bad == 0, "clear w %d format %d depth %d pad %d: %d wrong bytes", w, fmt, dep, pad, bad);
                    if (bad) return;
                }
}

static void test_degenerate_huge_tiny(void)
{
    const int32_t w = 40, h = 30;
    const int32_t G = RS_GUARD_PX * 16 - 64;
    sv v[12];
    uint32_t idx[] = { 0, 1, 2,  3, 3, 4,  5, 6, 7,  8, 9, 10,  0, 0, 0 };
    uint32_t *img;
    int32_t bad;
    /* collinear (line) triangle through many centres */
    v[0].x = 8; v[0].y = 8; v[1].x = 300; v[1].y = 200; v[2].x = 600; v[2].y = 400;
    /* repeated index */
    v[3].x = 100; v[3].y = 100; v[4].x = 400; v[4].y = 50;
    /* tiny triangle between centres */
    v[5].x = 16 * 5 + 9; v[5].y = 16 * 5 + 9; v[6].x = 16 * 5 + 12; v[6].y = 16 * 5 + 9; v[7].x = 16 * 5 + 9; v[7].y = 16 * 5 + 14;
    /* triangle wholly off screen (left) */
    v[8].x = -5000; v[8].y = 10; v[9].x = -100; v[9].y = 300; v[10].x = -2000; v[10].y = 900;
    img = count_tris(w, h, v, 11, idx, 15, 1);
    CHECK_MSG(all_equal(img, w * h, 0, &bad), "degenerate/tiny/off-screen drew %d pixels", bad);
    free(img);
    /* a huge triangle reaching the guard band covers the screen once */
    v[0].x = -G; v[0].y = -G; v[1].x = G; v[1].y = 0; v[2].x = 0; v[2].y = G;
    {
        uint32_t t[3] = { 0, 1, 2 };
        front(v, t);
        img = count_tris(w, h, v, 3, t, 3, 0);
        CHECK_MSG(all_equal(img, w * h, 1, &bad), "huge triangle: %d pixels not covered once", bad);
        free(img);
    }
    /* a tiny triangle around one centre covers exactly that pixel */
    v[0].x = 16 * 7 + 6; v[0].y = 16 * 3 + 6; v[1].x = 16 * 7 + 11; v[1].y = 16 * 3 + 7; v[2].x = 16 * 7 + 8; v[2].y = 16 * 3 + 12;
    {
        uint32_t t[3] = { 0, 1, 2 };
        int32_t i, tot = 0;
        front(v, t);
        img = count_tris(w, h, v, 3, t, 3, 0);
        for (i = 0; i < w * h; i++) tot += (int32_t)img[i];
        CHECK_EQ(tot, 1);
        CHECK_EQ(img[3 * w + 7], 1);
        free(img);
    }
}

/* ------------------------------------------------------------- world space */

/* A 257x257 crop of N47E009 (Alpine, south-east part), shaded with the default ramp. */
typedef struct terrain {
    hf f;
    rs_ramp ramp;
    rt_scene sc;
    rs_vertex *v;
    uint32_t nv, *idx;
    rs_prim prims[256];
    int ok;
} terrain;
static terrain T;

static void terrain_load(void)
{
    hf full;
    br_err err;
    hf_stats st;
    fx_q14 sun[3];
    int32_t x, y, n = 257, ox = 800, oy = 850;
    if (T.ok) return;
    if (dem_load(t_data("hgt/N47E009.hgt"), NULL, &full, &err) != BR_OK) {
        fprintf(stderr, "cannot load N47E009: %s\n", err.msg);
        return;
    }
    T.f = full;
    T.f.w = n; T.f.h = n;
    T.f.z = malloc(sizeof(int32_t) * (size_t)n * (size_t)n);
    for (y = 0; y < n; y++)
        for (x = 0; x < n; x++) T.f.z[y * n + x] = full.z[(size_t)(oy + y) * (size_t)full.w + (size_t)(ox + x)];
    dem_free(&full);
    hf_stats_get(&T.f, &st);
    rs_ramp_default(&T.ramp, hf_z_to_mm(&T.f, st.zmin), hf_z_to_mm(&T.f, st.zmax));
    rs_sun_dir(315000, 45000, sun);
    CHECK_EQ(rt_scene_init(&T.sc, &T.f, &T.ramp, sun, 4915), BR_OK);
    T.nv = (uint32_t)(n * n);
    T.v = malloc(sizeof *T.v * T.nv);
    T.idx = malloc(sizeof *T.idx * (size_t)(n - 1) * (size_t)n * 2);
    for (y = 0; y < n; y++)
        for (x = 0; x < n; x++) rt_vertex(&T.sc, x, y, T.f.z[y * n + x], &T.v[y * n + x]);
    for (y = 0; y + 1 < n; y++) {
        uint32_t *s = T.idx + (size_t)y * (size_t)n * 2;
        for (x = 0; x < n; x++) { s[2 * x] = (uint32_t)(y * n + x); s[2 * x + 1] = (uint32_t)((y + 1) * n + x); }
        T.prims[y].kind = RS_STRIP; T.prims[y].n = (uint32_t)(2 * n); T.prims[y].idx = s;
    }
    T.ok = 1;
}

/* Camera from metres (x east from the crop's west edge, y north from its south edge). */
static void terrain_frame(rs_frame *f, rs_cvert *cache, int32_t w, int32_t h, const double e[3],
                          const double t[3], double fov, double znear_m)
{
    cam c;
    int32_t ei[3], ti[3], i;
    double s = ldexp(1.0, T.sc.shift);
    for (i = 0; i < 3; i++) { ei[i] = (int32_t)lround(e[i] * s); ti[i] = (int32_t)lround(t[i] * s); }
    CHECK_EQ(cam_look_at(&c, ei, ti, (int32_t)lround(fov * 1000), w, h, (int32_t)lround(znear_m * s),
                         (int32_t)lround(60000 * s)), BR_OK);
    memset(f, 0, sizeof *f);
    f->w = w; f->h = h; f->fmt = RS_FMT_XRGB8888; f->depth = RS_DEPTH32; f->clear_rgb = 0x99ccffu;
    f->v = T.v; f->nv = T.nv; f->cache = cache; f->prims = T.prims; f->nprims = 256;
    f->chunks = g_chunks;
    CHECK(rs_chunk_mem_size(f->prims, f->nprims) <= sizeof g_chunks);
    cam_viewproj(&c, &f->vp);
    CHECK_EQ(cnt_frame_prepare(f), BR_OK);
}

/* Terrain crop: ~14.6 km (east) x 23.7 km (north) at 57 x 92 m spacing. */
static const double CAM_OBLIQUE_E[3] = { -3000, -4000, 5000 }, CAM_OBLIQUE_T[3] = { 7000, 11000, 1200 };

static void test_bands_and_formats(void)
{
    const int32_t w = 320, h = 240;
    rs_cvert *cache;
    rs_frame f;
    uint32_t *full;
    int32_t bands[4] = { 1, 7, 16, 240 }, k, fmt, dep;
    terrain_load();
    if (!T.ok) { CHECK(T.ok); return; }
    cache = malloc(rs_cache_mem_size(T.nv));
    for (dep = 0; dep < 2; dep++)
        for (fmt = 0; fmt < 2; fmt++) {
            size_t bpp = fmt == RS_FMT_RGB565 ? 2 : 4;
            terrain_frame(&f, cache, w, h, CAM_OBLIQUE_E, CAM_OBLIQUE_T, 50, 1);
            f.fmt = fmt; f.depth = dep;
            full = render_full(&f);
            /* bands with the chunk table (skipping chunks that miss a band); last, bands of
             * 7 rows of a frame prepared as one band (its table says "every row") */
            for (k = 0; k < 5; k++) {
                int32_t y0, rows = bands[k < 4 ? k : 1];
                uint8_t *img = malloc((size_t)w * h * bpp);
                void *mem = malloc(rs_band_mem_size(w, rows, fmt, dep));
                f.one_band = k == 4;
                CHECK_EQ(cnt_frame_prepare(&f), BR_OK);
                for (y0 = 0; y0 < h; y0 += rows) {
                    int32_t r = h - y0 < rows ? h - y0 : rows;
                    CHECK_EQ(cnt_draw_band(&f, y0, r, img + (size_t)y0 * w * bpp, (size_t)w * bpp, mem, NULL), BR_OK);
                }
                CHECK_MSG(!memcmp(img, full, (size_t)w * h * bpp), "bands of %d rows differ (fmt %d depth %d one_band %d)",
                          rows, fmt, dep, f.one_band);
                free(img); free(mem);
            }
            free(full);
        }
    /* RGB565 is RGB888 reduced */
    {
        uint32_t *c888;
        uint16_t *c565;
        int32_t i, bad = 0;
        terrain_frame(&f, cache, w, h, CAM_OBLIQUE_E, CAM_OBLIQUE_T, 50, 1);
        c888 = render_full(&f);
        f.fmt = RS_FMT_RGB565;
        c565 = render_full(&f);
        for (i = 0; i < w * h; i++) {
            uint32_t p = c888[i];
            uint16_t r = (uint16_t)(((p >> 8) & 0xf800u) | ((p >> 5) & 0x07e0u) | ((p >> 3) & 0x1fu));
            if (r != c565[i]) bad++;
        }
        CHECK_MSG(bad == 0, "%d RGB565 pixels differ from RGB888 reduced", bad);
        free(c888); free(c565);
    }
    free(cache);
}

static int32_t count_not(const uint32_t *img, int32_t n, uint32_t v)
{
    int32_t i, k = 0;
    for (i = 0; i < n; i++) if (img[i] != v) k++;
    return k;
}

static void test_near_plane_and_inside(void)
{
    const int32_t w = 160, h = 120;
    rs_cvert *cache;
    rs_frame f;
    uint32_t *img, *cnt;
    int32_t i, bad;
    hf_stats st;
    double zmin, zc;
    terrain_load();
    if (!T.ok) { CHECK(T.ok); return; }
    hf_stats_get(&T.f, &st);
    zmin = (double)hf_z_to_mm(&T.f, st.zmin) / 1000;
    cache = malloc(rs_cache_mem_size(T.nv));
    {   /* camera 1.5 m above the ground, looking along a valley: near-plane crossings */
        int32_t gx = 128, gy = 128;
        double e[3], t[3];
        zc = (double)hf_z_to_mm(&T.f, T.f.z[gy * 257 + gx]) / 1000;
        e[0] = gx * 57.0; e[1] = (256 - gy) * 92.6; e[2] = zc + 1.5;
        t[0] = e[0] + 3000; t[1] = e[1] + 2000; t[2] = zc;
        terrain_frame(&f, cache, w, h, e, t, 75, 0.25);
        f.debug_count = 1;
        cnt = render_full(&f);
        /* the bottom row is ground (written), the terrain is in front of the camera */
        for (i = 0; i < w; i++) CHECK(cnt[(h - 1) * w + i] >= 1);
        bad = 0;
        for (i = 0; i < w * h; i++) if (cnt[i] > 12) bad++;   /* nothing absurd */
        CHECK_EQ(bad, 0);
        CHECK(g_st.clipped > 0);
        free(cnt);
    }
    {   /* camera below the whole terrain looking up: only back faces -> all sky */
        double e[3] = { 7000, 11000, zmin - 500 }, t[3] = { 7100, 12000, zmin + 2000 };
        terrain_frame(&f, cache, w, h, e, t, 60, 1);
        img = render_full(&f);
        CHECK_MSG(count_not(img, w * h, 0x99ccffu) == 0, "%d non-sky pixels seen from below", count_not(img, w * h, 0x99ccffu));
        free(img);
        f.no_cull = 1;
        img = render_full(&f);
        CHECK(count_not(img, w * h, 0x99ccffu) > w * h / 4);  /* the underside is there */
        free(img);
    }
    {   /* camera inside a mountain (below the surface): no crash, band-exact */
        double e[3] = { 7300, 11800, zmin + 50 }, t[3] = { 9000, 13000, zmin + 400 };
        uint8_t *band;
        void *mem = malloc(rs_band_mem_size(w, 7, RS_FMT_XRGB8888, RS_DEPTH32));
        int32_t y0;
        terrain_frame(&f, cache, w, h, e, t, 90, 0.1);
        img = render_full(&f);
        band = malloc((size_t)w * h * 4);
        for (y0 = 0; y0 < h; y0 += 7)
            cnt_draw_band(&f, y0, h - y0 < 7 ? h - y0 : 7, band + (size_t)y0 * w * 4, (size_t)w * 4, mem, NULL);
        CHECK(!memcmp(band, img, (size_t)w * h * 4));
        free(img); free(band); free(mem);
    }
    free(cache);
}

static void test_far_outside_guard(void)
{
    /* a ground plane made of huge triangles reaching CAM_COORD_MAX, seen from 2 units up:
     * near-plane and guard-band clipping; every pixel below the horizon exactly once */
    const int32_t w = 96, h = 64, M = CAM_COORD_MAX;
    rs_vertex v[5] = { { { -M, -M, 0 }, 0x00ff00u, { 0, 0 } }, { { M, -M, 0 }, 0x00ff00u, { 0, 0 } }, { { M, M, 0 }, 0x00ff00u, { 0, 0 } },
                       { { -M, M, 0 }, 0x00ff00u, { 0, 0 } }, { { 0, 0, 0 }, 0xff0000u, { 0, 0 } } };
    uint32_t idx[12] = { 0, 1, 4,  1, 2, 4,  2, 3, 4,  3, 0, 4 };
    rs_prim pr = { RS_LIST, 12, idx };
    rs_cvert cache[5];
    rs_frame f;
    cam c;
    int32_t eye[3] = { 100, -50, 2 }, tg[3] = { 300, 1000, 2 }, y, x, bad = 0, rows_sky = 0;
    uint32_t *cnt;
    CHECK_EQ(cam_look_at(&c, eye, tg, 60000, w, h, 1, M), BR_OK);
    memset(&f, 0, sizeof f);
    f.w = w; f.h = h; f.v = v; f.nv = 5; f.cache = cache; f.prims = &pr; f.nprims = 1; f.debug_count = 1;
    f.chunks = g_chunks;
    cam_viewproj(&c, &f.vp);
    CHECK_EQ(cnt_frame_prepare(&f), BR_OK);
    cnt = render_full(&f);
    /* looking horizontally: the lower half is ground, the upper half sky */
    for (y = 0; y < h; y++) {
        int32_t s = 0;
        for (x = 0; x < w; x++) {
            if (cnt[y * w + x] > 1) bad++;
            s += (int32_t)cnt[y * w + x];
        }
        if (y >= h / 2 + 1) CHECK_MSG(s == w, "row %d: %d of %d pixels", y, s, w);
        if (y < h / 2 - 1 && s == 0) rows_sky++;
    }
    CHECK_EQ(bad, 0);
    CHECK_EQ(rows_sky, h / 2 - 1);
    free(cnt);
}

static void test_near_plane_grid(void)
{
    /* a flat 64 x 64 grid around a camera 2 units above it, looking level: triangles
     * around the camera cross the near plane; every ground pixel is written once */
    const int32_t w = 96, h = 64, n = 65;
    rs_vertex *v = malloc(sizeof *v * n * n);
    uint32_t *idx = malloc(sizeof *idx * 6 * 64 * 64), k = 0, *cnt;
    rs_prim pr;
    rs_cvert *cache = malloc(sizeof *cache * n * n);
    rs_frame f;
    cam c;
    int32_t eye[3] = { 3, 5, 2 }, tg[3] = { 40, 300, 2 }, x, y, bad = 0;
    for (y = 0; y < n; y++)
        for (x = 0; x < n; x++) {
            v[y * n + x].p[0] = -512 + 16 * x; v[y * n + x].p[1] = -512 + 16 * y; v[y * n + x].p[2] = 0;
            v[y * n + x].rgb = 0x808080u;
        }
    for (y = 0; y + 1 < n; y++)     /* CCW seen from +z: (a, b, d), (a, d, c) with y north */
        for (x = 0; x + 1 < n; x++) {
            uint32_t a = (uint32_t)(y * n + x), b = a + 1, cc = a + (uint32_t)n, d = cc + 1;
            idx[k++] = a; idx[k++] = b; idx[k++] = d; idx[k++] = a; idx[k++] = d; idx[k++] = cc;
        }
    pr.kind = RS_LIST; pr.n = k; pr.idx = idx;
    CHECK_EQ(cam_look_at(&c, eye, tg, 70000, w, h, 1, 100000), BR_OK);
    memset(&f, 0, sizeof f);
    f.w = w; f.h = h; f.v = v; f.nv = (uint32_t)(n * n); f.cache = cache; f.prims = &pr; f.nprims = 1;
    f.debug_count = 1; f.chunks = g_chunks;
    cam_viewproj(&c, &f.vp);
    CHECK_EQ(cnt_frame_prepare(&f), BR_OK);
    cnt = render_full(&f);
    CHECK(g_st.clipped > 0);
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            uint32_t want = y >= h / 2 + 2 ? 1 : (y < h / 2 ? 0 : cnt[y * w + x]);
            /* rows at the horizon are excluded: there, grid rows hundreds of units apart
             * snap to the same 1/16-pixel row, so the snapped mesh folds (any finite
             * sub-pixel precision does this; the depth test resolves it) */
            if (cnt[y * w + x] != want) {
                if (bad < 5) fprintf(stderr, "  pixel (%d, %d): %u\n", x, y, cnt[y * w + x]);
                bad++;
            }
        }
    CHECK_MSG(bad == 0, "%d pixels not covered as expected around the near plane", bad);
    free(cnt); free(v); free(idx); free(cache);
}

/* A ground plane textured with a 64x64 map whose texel (tx, ty) has colour
 * (4 tx, 4 ty, 0x55), seen obliquely; every pixel's texel is compared with the exact
 * perspective mapping (ray / plane intersection in double precision): within one
 * texel.  n = 1: two large triangles (general path); n = 48: a grid (tiny path). */
static void texture_case(int32_t n, int fmt, int low)
{
    const int32_t w = low ? 400 : 160, h = low ? 300 : 120, TS = 64;
    const double X0 = -4000, X1 = 4000, Y0 = 200, Y1 = 12000;
    uint32_t texel[64 * 64], *idx, k = 0;
    rs_texture tex;
    rs_vertex *v = calloc((size_t)(n + 1) * (size_t)(n + 1), sizeof *v);
    rs_cvert *cache = calloc((size_t)(n + 1) * (size_t)(n + 1), sizeof *cache);
    rs_prim pr;
    rs_frame f;
    cam c;
    int32_t eye[3] = { 0, -500, low ? 120 : 700 }, tg[3] = { 0, 4000, 0 }, x, y, bad = 0, checked = 0;
    void *img;
    idx = calloc((size_t)n * (size_t)n * 6, sizeof *idx);
    for (y = 0; y < TS; y++) for (x = 0; x < TS; x++) texel[y * TS + x] = (uint32_t)(4 * x) << 16 | (uint32_t)(4 * y) << 8 | 0x55u;
    tex.w = TS; tex.h = TS; tex.px = texel;
    for (y = 0; y <= n; y++)
        for (x = 0; x <= n; x++) {
            rs_vertex *p = &v[y * (n + 1) + x];
            p->p[0] = (int32_t)(X0 + (X1 - X0) * x / n); p->p[1] = (int32_t)(Y1 - (Y1 - Y0) * y / n); p->p[2] = 0;
            p->rgb = 0xffffffu;
            p->uv[0] = x * TS * 256 / n; p->uv[1] = y * TS * 256 / n;   /* row 0 = far (north) edge */
        }
    for (y = 0; y < n; y++)     /* CCW seen from +z (y row goes south) */
        for (x = 0; x < n; x++) {
            uint32_t a = (uint32_t)(y * (n + 1) + x), b = a + 1, cc = a + (uint32_t)n + 1, d = cc + 1;
            idx[k++] = a; idx[k++] = cc; idx[k++] = b; idx[k++] = b; idx[k++] = cc; idx[k++] = d;
        }
    pr.kind = RS_LIST; pr.n = k; pr.idx = idx;
    CHECK_EQ(cam_look_at(&c, eye, tg, 60000, w, h, 16, 100000), BR_OK);
    memset(&f, 0, sizeof f);
    f.w = w; f.h = h; f.fmt = fmt; f.v = v; f.nv = (uint32_t)((n + 1) * (n + 1)); f.cache = cache;
    f.prims = &pr; f.nprims = 1; f.tex = &tex; f.clear_rgb = 0x000000u; f.chunks = g_chunks;
    cam_viewproj(&c, &f.vp);
    CHECK_EQ(cnt_frame_prepare(&f), BR_OK);
    img = render_full(&f);
    {
        double R[3][3], fo = (double)c.f_q16 / 65536.0;
        int i;
        for (i = 0; i < 3; i++) {
            R[0][i] = c.right[i] / 1073741824.0; R[1][i] = c.up[i] / 1073741824.0; R[2][i] = c.fwd[i] / 1073741824.0;
        }
        for (y = h / 3; y < h; y++)
            for (x = 0; x < w; x++) {
                double dc[3] = { (x + 0.5 - w / 2.0) / fo, -(y + 0.5 - h / 2.0) / fo, 1 }, dw[3], t, wx, wy, u, vv, t2;
                uint32_t p;
                int32_t tx, ty;
                for (i = 0; i < 3; i++) dw[i] = R[0][i] * dc[0] + R[1][i] * dc[1] + R[2][i] * dc[2];
                if (dw[2] >= 0) continue;
                t = -eye[2] / dw[2]; wx = eye[0] + t * dw[0]; wy = eye[1] + t * dw[1];
                if (wx < X0 + 300 || wx > X1 - 300 || wy < Y0 + 300 || wy > Y1 - 300) continue;
                u = (wx - X0) / (X1 - X0) * TS; vv = (Y1 - wy) / (Y1 - Y0) * TS;
                /* only where a pixel covers less than half a texel (magnification): the
                 * 1/16-pixel vertex snapping moves minified texels by more than one */
                for (i = 0; i < 3; i++) dw[i] = R[0][i] * dc[0] + R[1][i] * (dc[1] - 1 / fo) + R[2][i] * dc[2];
                if (dw[2] >= 0) continue;
                t2 = -eye[2] / dw[2];
                if (fabs((Y1 - (eye[1] + t2 * dw[1])) / (Y1 - Y0) * TS - vv) > 0.5) continue;
                if (fmt == RS_FMT_RGB565) {
                    uint16_t q = ((uint16_t *)img)[y * w + x];
                    tx = (q >> 11) * 8 / 4; ty = ((q >> 5) & 63) * 4 / 4;
                } else {
                    p = ((uint32_t *)img)[y * w + x];
                    tx = (int32_t)((p >> 16) & 255) / 4; ty = (int32_t)((p >> 8) & 255) / 4;
                }
                checked++;
                if (fabs(tx + 0.5 - u) > (fmt == RS_FMT_RGB565 ? 2.5 : 1.5) || fabs(ty + 0.5 - vv) > 1.5) {
                    if (bad < 3) fprintf(stderr, "  n=%d pixel (%d,%d): texel (%d,%d), expected (%.2f,%.2f)\n", n, x, y, tx, ty, u, vv);
                    bad++;
                }
            }
    }
    if (getenv("BITRAIN_VERBOSE")) fprintf(stderr, "  texture n=%d fmt %d: %d pixels checked, %d off\n", n, fmt, checked, bad);
    CHECK(checked > 1000);
    CHECK_MSG(bad == 0, "n=%d: %d of %d pixels off by more than a texel", n, bad, checked);
    free(img); free(v); free(cache); free(idx);
}

static void test_texture(void)
{
    texture_case(1, RS_FMT_XRGB8888, 0);
    texture_case(48, RS_FMT_XRGB8888, 0);
    texture_case(1, RS_FMT_RGB565, 0);
    texture_case(1, RS_FMT_XRGB8888, 1);     /* low camera: long spans, depth ratio > 50 */
    texture_case(16, RS_FMT_XRGB8888, 1);
}

/* ------------------------------------------------------------- vertex transform */

/* One cache entry as raster.h states it, with the plainest arithmetic: camera space
 * c = (r p + t) >> 30; behind the near plane only the colour; beyond the guard band
 * (|f c0| or |f c1| > 2^14 px * c2, f in Q8 pixels) the sides; else x, y rounded to
 * 1/16 px around the centre, d = RS_DEPTH_ONE znear / c2 and the screen sides.
 * rs_frame_prepare takes shorter roads for common vertices: they must all end here. */
static void ref_cvert(const rs_frame *f, const rs_vertex *v, rs_cvert *o)
{
    const cam_vp *vp = &f->vp;
    const int64_t f8 = (vp->f_q16 + 128) >> 8, g8 = (int64_t)RS_GUARD_PX << 8;
    const uint32_t rgb = v->rgb & 0xffffffu;
    uint32_t oc = 0;
    int64_t c[3];
    int i;
    for (i = 0; i < 3; i++)
        c[i] = ((int64_t)vp->r[i][0] * v->p[0] + (int64_t)vp->r[i][1] * v->p[1]
                + (int64_t)vp->r[i][2] * v->p[2] + vp->t[i]) >> 30;
    o->x = o->y = 0;
    o->d = 0;
    if (c[2] < vp->znear) oc = RS_OUT_NEAR;
    else {
        const int64_t ax = f8 * c[0], ay = f8 * c[1], lim = g8 * c[2];
        if (c[2] > vp->zfar) oc |= RS_OUT_FAR;
        if (ax > lim || -ax > lim || ay > lim || -ay > lim) {
            oc |= RS_OUT_GUARD;
            if (ax > lim) oc |= RS_OUT_RIGHT;
            if (-ax > lim) oc |= RS_OUT_LEFT;
            if (ay > lim) oc |= RS_OUT_TOP;
            if (-ay > lim) oc |= RS_OUT_BOTTOM;
        } else {
            o->x = f->w * 8 + (int32_t)((ax / c[2] + 8) >> 4);
            o->y = f->h * 8 - (int32_t)((ay / c[2] + 8) >> 4);
            o->d = (uint32_t)((int64_t)RS_DEPTH_ONE * vp->znear / c[2]);
            if (o->x < 8) oc |= RS_OUT_LEFT;
            if (o->x > f->w * 16 - 8) oc |= RS_OUT_RIGHT;
            if (o->y < 8) oc |= RS_OUT_TOP;
            if (o->y > f->h * 16 - 8) oc |= RS_OUT_BOTTOM;
        }
    }
    o->c = rgb | (oc << 24);
    o->cp = ((uint64_t)(rgb >> 16) << 42) | ((uint64_t)((rgb >> 8) & 255u) << 21) | (rgb & 255u);
    o->u = v->uv[0];
    o->v = v->uv[1];
}

/* Compares f's cache (after rs_frame_prepare) with ref_cvert; u, v only when textured.
 * Counts the entries by outcode class in cls (on screen, off screen, near, far, guard). */
static int32_t cache_mismatches(const rs_frame *f, long cls[5])
{
    int32_t bad = 0;
    uint32_t i;
    for (i = 0; i < f->nv; i++) {
        const rs_cvert *a = &f->cache[i];
        rs_cvert r;
        uint32_t oc;
        ref_cvert(f, &f->v[i], &r);
        oc = r.c >> 24;
        cls[oc & RS_OUT_NEAR ? 2 : oc & RS_OUT_GUARD ? 4 : oc & RS_OUT_FAR ? 3 : oc ? 1 : 0]++;
        if (a->x != r.x || a->y != r.y || a->d != r.d || a->c != r.c || a->cp != r.cp
            || (f->tex && (a->u != r.u || a->v != r.v))) {
            if (bad < 3)
                fprintf(stderr, "  vertex %u (%d, %d, %d): got %d %d %u %08x %llx, want %d %d %u %08x %llx\n", i,
                        f->v[i].p[0], f->v[i].p[1], f->v[i].p[2], a->x, a->y, a->d, a->c, (unsigned long long)a->cp,
                        r.x, r.y, r.d, r.c, (unsigned long long)r.cp);
            bad++;
        }
    }
    return bad;
}

static int64_t clamp_coord(int64_t p) { return p > CAM_COORD_MAX ? CAM_COORD_MAX : p < -CAM_COORD_MAX ? -CAM_COORD_MAX : p; }
static int64_t rnd_range(int64_t lo, int64_t hi)
{
    uint64_t r = ((uint64_t)lcg() << 40) ^ ((uint64_t)lcg() << 20) ^ lcg();
    return lo + (int64_t)(r % (uint64_t)(hi - lo + 1));
}

static void test_transform(void)
{
    /* real terrain from an oblique camera, a camera 3 m above the ground (vertices behind
     * the near plane) and a 2-degree telephoto (most vertices beyond the guard band) */
    static const double lo_e[3] = { 6000, 9000, 700 }, lo_t[3] = { 9000, 14000, 500 };
    enum { NV = 1024, NCAM = 300 };
    rs_vertex *v = malloc(sizeof *v * NV);
    rs_cvert *cache;
    rs_frame f;
    long cls[5] = { 0, 0, 0, 0, 0 };
    uint32_t texel = 0xffffffu;
    rs_texture tex;
    int32_t bad = 0, k, i;
    tex.w = tex.h = 1; tex.px = &texel;
    terrain_load();
    if (!T.ok) { CHECK(T.ok); free(v); return; }
    cache = malloc(rs_cache_mem_size(T.nv > NV ? T.nv : NV));
    terrain_frame(&f, cache, 161, 121, CAM_OBLIQUE_E, CAM_OBLIQUE_T, 50, 1);
    bad += cache_mismatches(&f, cls);
    terrain_frame(&f, cache, 320, 240, lo_e, lo_t, 70, 1);
    bad += cache_mismatches(&f, cls);
    terrain_frame(&f, cache, 640, 480, CAM_OBLIQUE_E, CAM_OBLIQUE_T, 2, 1);
    bad += cache_mismatches(&f, cls);
    /* random cameras (every scale up to CAM_COORD_MAX, viewports 1 .. 4096) and points:
     * anywhere, or aimed at camera-space spots on the edges of the decisions: the near
     * and far planes, the screen edge and the guard band edge, a few units either side */
    for (k = 0; k < NCAM; k++) {
        const int64_t big = k % 4 == 0 ? 1000 : k % 4 == 1 ? 100000 : k % 4 == 2 ? 10000000 : CAM_COORD_MAX;
        int32_t eye[3], tg[3], w, h, zn, zf;
        cam c;
        for (i = 0; i < 3; i++) { eye[i] = (int32_t)rnd_range(-big, big); tg[i] = (int32_t)rnd_range(-big, big); }
        w = (int32_t)(k & 1 ? rnd_range(1, 64) : rnd_range(1, 4096));
        h = (int32_t)(k & 2 ? rnd_range(1, 64) : rnd_range(1, 4096));
        zn = (int32_t)rnd_range(1, big / 64 + 1);
        zf = (int32_t)(zn + rnd_range(1, big));
        if (cam_look_at(&c, eye, tg, (int32_t)rnd_range(1000, 170000), w, h, zn, zf) != BR_OK) continue;
        memset(&f, 0, sizeof f);
        f.w = w; f.h = h; f.v = v; f.nv = NV; f.cache = cache; f.chunks = g_chunks;
        f.tex = k & 4 ? &tex : NULL;
        cam_viewproj(&c, &f.vp);
        for (i = 0; i < NV; i++) {
            int32_t j, mode = (int32_t)(lcg() % 4);
            int64_t cz = 0, c0 = 0, c1 = 0;
            if (mode) {
                cz = mode == 1 ? zn + rnd_range(-2, 2) : mode == 2 ? zf + rnd_range(-2, 2) : rnd_range(zn, zf);
                c0 = cz * (lcg() & 1 ? RS_GUARD_PX : w / 2) * 65536 / c.f_q16 * (lcg() & 1 ? 1 : -1) + rnd_range(-3, 3);
                c1 = cz * (lcg() & 1 ? RS_GUARD_PX : h / 2) * 65536 / c.f_q16 * (lcg() & 1 ? 1 : -1) + rnd_range(-3, 3);
                if (lcg() & 1) c1 = rnd_range(-(c1 < 0 ? -c1 : c1), c1 < 0 ? -c1 : c1);
                else if (lcg() & 1) c0 = rnd_range(-(c0 < 0 ? -c0 : c0), c0 < 0 ? -c0 : c0);
                if (c0 > INT32_MAX || -c0 > INT32_MAX || c1 > INT32_MAX || -c1 > INT32_MAX) mode = 0;
            }
            for (j = 0; j < 3; j++)
                v[i].p[j] = (int32_t)clamp_coord(mode ? eye[j] + (((int64_t)c.right[j] * c0 + (int64_t)c.up[j] * c1
                                                                   + (int64_t)c.fwd[j] * cz) >> 30) + rnd_range(-1, 1)
                                                      : rnd_range(-big, big));
            v[i].rgb = ((uint32_t)lcg() << 8) ^ lcg();   /* junk in the top byte too */
            v[i].uv[0] = (int32_t)(((uint32_t)lcg() << 8) ^ lcg());
            v[i].uv[1] = (int32_t)lcg();
        }
        if (k & 8) {
            /* rows for the fast loop's row stepping: runs of one y with x stepping by a
             * constant dx (small, large, or beyond 2^30 where the loop does not step),
             * across x = 0 and into the CAM_COORD_MAX clamp; z as drawn above */
            int64_t dx = 0;
            int32_t run = 0;
            for (i = 1; i < NV; i++) {
                if (run-- <= 0) {
                    uint32_t r = lcg() % 4;
                    run = (int32_t)rnd_range(0, 40);
                    dx = r == 0 ? rnd_range(-3, 3) : r == 1 ? rnd_range(-big / 16, big / 16)
                       : r == 2 ? rnd_range(-((int64_t)1 << 31), (int64_t)1 << 31) : big / 64 + 1;
                    continue;
                }
                v[i].p[1] = v[i - 1].p[1];
                v[i].p[0] = (int32_t)clamp_coord(v[i - 1].p[0] + dx);
            }
        }
        f.nv = NV - (uint32_t)(k % 5);    /* every remainder of the loop's unrolling */
        CHECK_EQ(cnt_frame_prepare(&f), BR_OK);
        bad += cache_mismatches(&f, cls);
    }
    if (getenv("BITRAIN_VERBOSE"))
        fprintf(stderr, "  transform: %ld on screen, %ld off, %ld near, %ld far, %ld beyond the guard band\n",
                cls[0], cls[1], cls[2], cls[3], cls[4]);
    for (i = 0; i < 5; i++) CHECK(cls[i] > 1000);
    CHECK_MSG(bad == 0, "%d cache entries differ from the reference transform", bad);
    free(cache); free(v);
}

/* ------------------------------------------------------------- golden image */

static void golden_compare(const char *name, const uint32_t *img, int32_t w, int32_t h)
{
    char gpath[256], apath[256], dpath[256];
    uint8_t *rgb = malloc((size_t)w * h * 3), *gold = NULL;
    int32_t gw = 0, gh = 0, i, diff = 0;
    br_err err;
    snprintf(gpath, sizeof gpath, "tests/golden/%s.png", name);
    rs_to_rgb888(RS_FMT_XRGB8888, img, w * h, rgb);
    if (getenv("BITRAIN_UPDATE_GOLDEN")) {
        CHECK_EQ(png_write_rgb(gpath, w, h, rgb, (size_t)w * 3, &err), BR_OK);
        fprintf(stderr, "wrote %s\n", gpath);
    }
    if (png_read_rgb(gpath, &gw, &gh, &gold, &err) != BR_OK) {
        CHECK_MSG(0, "cannot read %s (BITRAIN_UPDATE_GOLDEN=1 writes it)", gpath);
        free(rgb);
        return;
    }
    if (gw == w && gh == h)
        for (i = 0; i < w * h * 3; i++) if (rgb[i] != gold[i]) diff++;
    if (gw != w || gh != h || diff) {
        uint8_t *d = malloc((size_t)w * h * 3);
        snprintf(apath, sizeof apath, "%s/%s.actual.png", t_outdir(), name);
        snprintf(dpath, sizeof dpath, "%s/%s.diff.png", t_outdir(), name);
        png_write_rgb(apath, w, h, rgb, (size_t)w * 3, &err);
        for (i = 0; i < w * h; i++) {   /* differing pixels red on a dimmed copy */
            int same = gw == w && gh == h && !memcmp(rgb + 3 * i, gold + 3 * i, 3);
            d[3 * i] = same ? (uint8_t)(rgb[3 * i] / 4) : 255;
            d[3 * i + 1] = same ? (uint8_t)(rgb[3 * i + 1] / 4) : 0;
            d[3 * i + 2] = same ? (uint8_t)(rgb[3 * i + 2] / 4) : 0;
        }
        png_write_rgb(dpath, w, h, d, (size_t)w * 3, &err);
        CHECK_MSG(0, "%s: %d bytes differ (size %dx%d vs %dx%d); actual %s, diff %s", gpath, diff, w, h, gw, gh, apath, dpath);
        free(d);
    }
    free(rgb); free(gold);
}

static void test_golden(void)
{
    const int32_t w = 161, h = 121;   /* odd, asymmetric */
    rs_cvert *cache;
    rs_frame f;
    uint32_t *img;
    terrain_load();
    if (!T.ok) { CHECK(T.ok); return; }
    cache = malloc(rs_cache_mem_size(T.nv));
    terrain_frame(&f, cache, w, h, CAM_OBLIQUE_E, CAM_OBLIQUE_T, 50, 1);
    img = render_full(&f);
    golden_compare("raster_n47e009_161x121", img, w, h);
    free(img);
    free(cache);
}

int main(void)
{
    T_RUN(test_fill_grid);
    T_RUN(test_fill_fan);
    T_RUN(test_clear);
    T_RUN(test_degenerate_huge_tiny);
    T_RUN(test_bands_and_formats);
    T_RUN(test_near_plane_and_inside);
    T_RUN(test_far_outside_guard);
    T_RUN(test_near_plane_grid);
    T_RUN(test_texture);
    T_RUN(test_transform);
    T_RUN(test_golden);
    if (T.ok) { free(T.f.z); free(T.v); free(T.idx); }
    return t_finish();
}
