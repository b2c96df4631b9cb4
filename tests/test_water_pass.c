/* tests/test_water_pass.c — the water pass (raster/water_pass.c) seeds its depth and
 * clears its body ids only where a water triangle can draw: checked against the water
 * frame drawn alone on N47E009; the post hook's unchecked grid look-ups stay on the
 * grid; and its pixel loops at every reflection resolution are pinned by goldens. */
#include <stdio.h>
#include <string.h>
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/scene.h"
#include "platform/water_scene.h"
#include "raster/raster.h"
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
    int k;
    for (k = 0; k < 2; k++) {
        scene s;
        scene_opts so;
        ws_opts wo;
        water_scene ws;
        br_err err;
        cam c;
        bt_params bp;
        rs_frame fr;
        rs_band_stats st;
        const rw_frame *r;
        int32_t x, y, g;
        uint32_t drawn = 0, outside = 0, narrow = 0, groups = 0;
        wv_defaults(&so, &wo, &bp, &fr, &err);
        wv_lake_frame(&s, &so, &ws, &wo, cams[k], cams[k] + 3, W, H, &c, &bp, &fr);
        CHECK_EQ(ws_frame(&ws, &s, &c, &fr, &err), BR_OK);
        r = ws.rw;
        CHECK(r != NULL && r->water != NULL && r->wlo <= r->whi);
        if (!r || !r->water || r->wlo > r->whi) { ws_close(&ws); scene_close(&s); continue; }
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
        ws_close(&ws);
        scene_close(&s);
    }
}

/* The post hook compiles its pixel loop once more for the common case (raster/water.c
 * rw_post: waves, the fixed tint, Schlick's Fresnel term and the default half-resolution
 * reflection) in the two layouts of the benchmarks and boards; the goldens of
 * tests/test_water.c pin it at half resolution.  Here the same lake view at full and
 * quarter resolution in those layouts (XRGB8888 with 32-bit depth, RGB565 with 16-bit
 * depth), which take the general loop: goldens made before the common loop fixed its
 * resolution, so a loop that read the wrong resolution fails. */
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
                                "--camera", "40000,66000,420,60000,50000,500" };
            char *argv[sizeof a / sizeof a[0]];
            int k;
            for (k = 0; k < (int)(sizeof a / sizeof a[0]); k++) argv[k] = (char *)a[k];
            snprintf(name, sizeof name, "water_refl_%s_%s", res[i], fmt[f][2]);
            snprintf(out, sizeof out, "%s/%s.png", t_outdir(), name);
            CHECK_EQ(cmd_render((int)(sizeof a / sizeof a[0]), argv), 0);
            wv_golden(name, out);
        }
}

int main(void)
{
    T_RUN(test_seed_columns);
    T_RUN(test_reflection_res);
    return t_finish();
}
