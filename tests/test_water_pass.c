/* tests/test_water_pass.c — the water pass (raster/water_pass.c) seeds its depth and
 * clears its body ids only where a water triangle can draw: checked against the water
 * frame drawn alone on N47E009; the post hook's unchecked grid look-ups stay on the
 * grid; its pixel loops at every reflection resolution are pinned by goldens; and the
 * reflection's own selection by parts is the whole extraction's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/scene.h"
#include "platform/water_scene.h"
#include "raster/raster.h"
#include "tests/support/btcheck.h"
#include "tests/support/waterview.h"

/* The hook's grid look-up indexes wet[iy w + ix] with ix = (gx inv_sx) >> 32 for every
 * 0 <= gx < gxmax, unchecked (raster/water_setup.c grid_max): below gxmax ix < wet_w,
 * and from gxmax up to wet_w grid_sx (where it is less) ix >= wet_w, so the bound drops
 * no position the grid holds.  Checked over the 2^17 positions on each side, both axes. */
static void grid_bound_check(const rw_frame *r)
{
    int axis;
    for (axis = 0; axis < 2; axis++) {
        const uint64_t max = axis ? r->gymax : r->gxmax, inv = axis ? r->inv_sy : r->inv_sx;
        const uint64_t n = (uint64_t)(axis ? r->p.wet_h : r->p.wet_w);
        const uint64_t whole = n * (uint64_t)(axis ? r->p.grid_sy : r->p.grid_sx);
        uint64_t g, below = 0, above = 0;
        CHECK(max > 0 && max <= whole);
        for (g = max > (1u << 17) ? max - (1u << 17) : 0; g < max; g++) below += ((g * inv) >> 32) >= n;
        for (g = max; g < whole && g < max + (1u << 17); g++) above += ((g * inv) >> 32) < n;
        CHECK_MSG(below == 0 && above == 0, "axis %d: bound %llu of %llu, %llu below it off the grid, %llu above on it",
                  axis, (unsigned long long)max, (unsigned long long)whole, (unsigned long long)below,
                  (unsigned long long)above);
    }
}

/* The water pass seeds its depth and clears its ids only in the columns water_cols
 * (raster/water_setup.c) gives each group of RW_COL_ROWS rows, and the reflection pass
 * and the post hook read only those: every pixel a water triangle can cover must lie in
 * them.  The water frame is drawn alone over the far depth, so that every pixel of every
 * triangle passes, from the default path's first camera (Lake Constance far off and the
 * Walensee below it: the groups are narrower than the frame, or the test would not see
 * a column left out) and from the water (test_goldens' camera). */
static void test_seed_columns(void)
{
    enum { W = 640, H = 480 };
    static const double cams[2][6] = { { -20683.0, -2764.5, 59448.4, 37671.8, 55590.3, 1662.5 },
                                       { 40000, 66000, 420, 60000, 50000, 500 } };
    static uint32_t col[W * H], dep[W * H];
    static wv_view w;
    int k;
    for (k = 0; k < 2; k++) {
        rs_band_stats st;
        const rw_frame *r;
        int32_t x, y, g;
        uint32_t drawn = 0, outside = 0, narrow = 0, groups = 0;
        wv_view_open(&w, "hgt/N47E009.hgt", cams[k], cams[k] + 3, W, H, NULL);
        CHECK_EQ(ws_frame(&w.ws, &w.s, &w.c, &w.fr, &w.err), BR_OK);
        r = w.ws.rw;
        CHECK(r != NULL && r->water != NULL && r->wlo <= r->whi);
        if (!r || !r->water || r->wlo > r->whi) { wv_view_close(&w); continue; }
        memset(col, 0, sizeof col);
        for (x = 0; x < W * H; x++) dep[x] = r->dfar;
        CHECK_EQ(rs_draw_band(r->water, 0, H, col, (size_t)W * 4, dep, &st), BR_OK);
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++) {
                if (!((col[(size_t)y * W + x] >> 19) & 31u)) continue;     /* no body id */
                drawn++;
                g = y / RW_COL_ROWS;
                outside += y < r->wlo || y > r->whi || x < r->wx0[g] || x > r->wx1[g];
            }
        for (g = r->wlo / RW_COL_ROWS; g <= r->whi / RW_COL_ROWS; g++) {
            groups++;
            narrow += r->wx1[g] - r->wx0[g] + 1 < W;
        }
        printf("seed columns, camera %d: %u water pixels, %u outside their group's columns; %u of %u groups "
               "narrower than the frame\n", k, drawn, outside, narrow, groups);
        CHECK(drawn > 1000);
        CHECK_EQ(outside, 0);
        if (k == 0) CHECK(narrow * 2 > groups);
        grid_bound_check(r);
        wv_view_close(&w);
    }
}

/* The post hook compiles its pixel loop once more for the common case (raster/water.c
 * rw_post: waves, the fixed tint, Schlick's Fresnel term and the default half-resolution
 * reflection) in the two layouts of the benchmarks and boards; the goldens of
 * tests/test_water.c pin it at half resolution.  Here the same lake view at full and
 * quarter resolution in those layouts (XRGB8888 with 32-bit depth, RGB565 with 16-bit
 * depth), which take the general loop: goldens made before the common loop fixed its
 * resolution, so a loop that read the wrong resolution fails.  The reflection draws the
 * terrain's mesh (--reflection-error 0), as it did by default when they were made. */
static void test_reflection_res(void)
{
    static const char *const res[2] = { "full", "quarter" };
    static const char *const fmt[2][3] = { { "rgb888", "32", "rgb888" }, { "rgb565", "16", "rgb565_z16" } };
    int i, f;
    for (i = 0; i < 2; i++)
        for (f = 0; f < 2; f++) {
            char out[256], name[64];
            const char *a[] = { t_data("hgt/N47E009.hgt"), "-o", out, "--size", "160x96", "--format", fmt[f][0],
                                "--depth", fmt[f][1], "--time", "1.5", "--reflection", res[i],
                                "--reflection-error", "0", "--camera", "40000,66000,420,60000,50000,500" };
            char *argv[sizeof a / sizeof a[0]];
            int k;
            for (k = 0; k < (int)(sizeof a / sizeof a[0]); k++) argv[k] = (char *)a[k];
            snprintf(name, sizeof name, "water_refl_%s_%s", res[i], fmt[f][2]);
            snprintf(out, sizeof out, "%s/%s.png", t_outdir(), name);
            CHECK_EQ(cmd_render((int)(sizeof a / sizeof a[0]), argv), 0);
            wv_golden(name, out);
        }
}

/* The reflection's own LOD at 4x with the land's absolute colours (the views below) */
static void refl_opts(wv_view *v)
{
    v->so.ramp_abs = 1;
    v->wo.refl_err = 4;
    v->wo.time_s = 1.5;
}

/* The reflection's own selection by parts on three threads (platform/water_scene.c
 * refl_select: the parts whose decisions still hold replayed, the vertices of the parts
 * that moved set up again) draws what a whole extraction draws: along six steps of 20 m
 * over the lake, its proper triangles (the strip decoded) are those of a fresh bt_extract
 * for the mirrored camera, in order, corner by corner, and each corner's raster vertex is
 * rt_from_mesh's. */
static void test_refl_parts(void)
{
    enum { W = 320, H = 192 };
    static wv_view w;
    double eye[3] = { 40000, 66000, 420 }, tgt[3] = { 60000, 50000, 500 };
    pt_pool *pool = NULL;
    int step;
    wv_view_open(&w, "hgt/N47E009.hgt", eye, tgt, W, H, refl_opts);
    CHECK_EQ(pt_open(&pool, 3), BR_OK);
    w.s.pool = pool;                    /* the parts on three threads */
    for (step = 0; step < 6; step++) {
        bt_tree t = w.s.tree;
        bt_params rp;
        bt_mesh m;
        void *mem = NULL;
        rs_vertex *v = NULL;
        mc_vert *av = NULL, *bv = NULL;
        int32_t *as = NULL, *bs = NULL, *at = NULL, *bt = NULL;
        int64_t ant = 0, anl = 0, bnt = 0, bnl = 0, i, bad = 0;
        if (step) {
            eye[0] += 14; eye[1] -= 14; tgt[0] += 14; tgt[1] -= 14;
            CHECK_EQ(scene_camera(&w.s, eye, tgt, 50, W, H, &w.c), BR_OK);
            CHECK_EQ(scene_mesh(&w.s, &w.c, &w.bp), BR_OK);
            CHECK_EQ(scene_terrain(&w.s, &w.c, &w.fr, NULL), BR_OK);
        }
        CHECK_EQ(ws_frame(&w.ws, &w.s, &w.c, &w.fr, &w.err), BR_OK);
        CHECK_EQ(w.ws.rown, 1);
        CHECK(w.ws.rparts != NULL);
        t.st = calloc(bt_state_size(w.s.tree.nslot) + 1, 1);
        memset(&rp, 0, sizeof rp);
        rp.mode = BT_VIEW; rp.c = &w.ws.rcam; rp.fr = w.s.rt.fr; rp.pixel_err_q8 = 4 * 256;
        CHECK(t.st != NULL && btc_extract(&t, &rp, 0, &m, &mem) == 0);
        v = malloc(sizeof *v * (m.nv ? m.nv : 1));
        CHECK(v != NULL);
        if (!t.st || !mem || !v) { free(t.st); free(mem); free(v); break; }
        rt_from_mesh(&w.s.rt, &m, v);
        CHECK_EQ(btc_decode(&w.ws.rmesh, &av, &as, &at, &ant, &anl), 0);
        CHECK_EQ(btc_decode(&m, &bv, &bs, &bt, &bnt, &bnl), 0);
        CHECK_EQ(ant, bnt);
        for (i = 0; at && bt && i < 3 * ant && i < 3 * bnt; i++) {
            const mc_vert *a = &av[at[i]], *b = &bv[bt[i]];
            const rs_vertex *ra = &w.ws.rverts[at[i]], *rb = &v[bt[i]];
            bad += a->x != b->x || a->y != b->y || a->zq != b->zq || memcmp(ra->p, rb->p, sizeof ra->p)
                   || ra->rgb != rb->rgb;
        }
        if (step == 5)
            printf("reflection by parts: %lld triangles, %u parts replayed, as a whole extraction\n",
                   (long long)ant, bt_parts_reused(w.ws.rparts));
        CHECK_MSG(bad == 0 && ant > 100, "step %d: %lld of %lld corners differ", step, (long long)bad,
                  (long long)ant * 3);
        free(av); free(as); free(at); free(bv); free(bs); free(bt); free(v); free(mem); free(t.st);
    }
    w.s.pool = NULL;
    pt_close(pool);
    wv_view_close(&w);
}

static br_status to_rows(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    uint32_t *img = (uint32_t *)user;
    int32_t y;
    for (y = 0; y < rows; y++) memcpy(img + (size_t)(y0 + y) * 320, (const uint8_t *)px + (size_t)y * stride, 320 * 4);
    return BR_OK;
}

/* The reflection's own selection culled to the screen rectangle around its water
 * (platform/water_scene.c refl_window: the box of the body's water vertices, grown by the
 * waves' reach and a reduced row, upside down for the mirrored camera) draws the same
 * frame as that selection over the whole screen, waves, fog and the half-resolution
 * reflection on, 320x192: the default view (the lake a small part of the screen, the
 * window leaves most triangles out, the mirror shows sky only), Crater Lake from its
 * southern slope (crater_0513.bt: the lake at the screen's right, its cliffs mirrored; the
 * window leaves the left half and the sky's rows out), and Lake Constance from the water
 * (the lake reaches behind the camera: no window).  The frames, and the mirror itself
 * under the box of the water's vertices, where the hook reads it. */
static void test_refl_window(void)
{
    enum { W = 320, H = 192 };
    static uint32_t img[2][W * H], refl[2][W * H], rdep[W * H];
    static const double views[3][6] = { { -20683.0, -2764.5, 59448.4, 37671.8, 55590.3, 1662.5 },
                                        { 5200, 800, 3200, 5200, 8000, 1883 },
                                        { 40000, 66000, 420, 60000, 50000, 500 } };
    static wv_view w;
    int v, k;
    for (v = 0; v < 3; v++) {
        uint32_t ntri[2] = { 0, 0 }, i, inside = 0, terrain = 0, differ = 0;
        int32_t box[4] = { INT32_MAX, INT32_MAX, INT32_MIN, INT32_MIN }, x, y;
        wv_view_open(&w, v == 1 ? "bt/crater_0513.bt" : "hgt/N47E009.hgt", views[v], views[v] + 3, W, H, refl_opts);
        for (k = 0; k < 2; k++) {
            void *mem;
            size_t ms;
            w.ws.o.refl_no_window = k;
            memset(img[k], 0, sizeof img[k]);
            if (k) CHECK_EQ(scene_terrain(&w.s, &w.c, &w.fr, NULL), BR_OK);    /* (ws_frame fogs its vertices) */
            CHECK_EQ(ws_frame(&w.ws, &w.s, &w.c, &w.fr, &w.err), BR_OK);
            CHECK_EQ(w.ws.rown, 1);
            ntri[k] = w.ws.rmesh.ntri;
            CHECK_EQ(rs_draw_band(&w.ws.rfr, 0, w.ws.rfr.h, refl[k], (size_t)w.ws.rfr.w * 4, rdep, NULL), BR_OK);
            ms = rs_pipe_mem_size(&w.ws.pipe, H);
            mem = malloc(ms);
            CHECK(mem != NULL);
            if (mem) CHECK_EQ(rs_pipe_run(&w.ws.pipe, H, mem, ms, to_rows, img[k], NULL), BR_OK);
            free(mem);
        }
        /* the reflection itself, drawn whole, in the box of the body's water vertices (reduced
         * pixels): where the hook reads it, the same with and without the window */
        for (i = 0; i < w.ws.wfr.nv; i++) {
            const rs_cvert *wv = &w.ws.wfr.cache[i];
            if ((wv->c & RW_ID_MASK) != RW_ID_RGB(w.ws.rw->p.refl_body)) continue;
            box[0] = wv->x < box[0] ? wv->x : box[0]; box[2] = wv->x > box[2] ? wv->x : box[2];
            box[1] = wv->y < box[1] ? wv->y : box[1]; box[3] = wv->y > box[3] ? wv->y : box[3];
        }
        for (y = 0; y < w.ws.rfr.h; y++)
            for (x = 0; x < w.ws.rfr.w; x++) {
                const size_t j = (size_t)y * (size_t)w.ws.rfr.w + (size_t)x;
                if ((x << 1 << RS_SUBPIX_BITS) < box[0] || (x << 1 << RS_SUBPIX_BITS) > box[2]
                    || (y << 1 << RS_SUBPIX_BITS) < box[1] || (y << 1 << RS_SUBPIX_BITS) > box[3])
                    continue;
                inside++;
                terrain += (refl[1][j] & 0xffffffu) != (w.ws.rfr.clear_rgb & 0xffffffu);
                differ += refl[0][j] != refl[1][j];
            }
        printf("reflection window, view %d: %u triangles selected, %u over the whole screen; %u of %u mirror pixels "
               "under the water's box drawn\n", v, ntri[0], ntri[1], terrain, inside);
        CHECK_MSG(differ == 0, "view %d: %u of the mirror's pixels under the water's box differ", v, differ);
        if (v == 1) CHECK_MSG(terrain > 50, "%u mirror pixels drawn", terrain);
        CHECK_MSG(!memcmp(img[0], img[1], sizeof img[0]), "view %d: the window changes the frame", v);
        if (v < 2) CHECK_MSG(ntri[0] < ntri[1], "%u triangles in the window, %u without", ntri[0], ntri[1]);
        wv_view_close(&w);
    }
}

int main(void)
{
    T_RUN(test_seed_columns);
    T_RUN(test_reflection_res);
    T_RUN(test_refl_parts);
    T_RUN(test_refl_window);
    return t_finish();
}
