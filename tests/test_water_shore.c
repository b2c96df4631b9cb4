/* tests/test_water_shore.c — the water mesh's tested quads (platform/water_mesh.c,
 * RW_TESTED_RGB in raster/water.h): a block along a low shore is one quad whose pixels
 * the post hook keeps only where the plane's point on the pixel's ray lies in a half cell
 * the exact mesh would cover.  Three views straight down on N47E009 (the pond at 450 m,
 * whose outlet's low land lies inside its tested quads; two low shores of Lake Constance
 * at 392 m), drawn with the terrain and the lowered bottom painted red (water is what is
 * not red) at 0.05 px of screen error: a pixel must be water over a half cell whose three
 * corners are wet, and land over a cell with a low corner and none wet, and over a half
 * cell with a low corner when every corner of its cell is wet or low 2 m under the level
 * (the terrain lies under the plane there, so the hook alone decides).  Cells are judged
 * from the detection's id map and the mesh's low map (itself checked against the DEM),
 * for pixels a quarter of a cell or more from the cell's edges and diagonal.  The fine
 * water mesh's (surf[0]), which views this near draw (platform/water_scene.c far_pays). */
#include <math.h>
#include <stdio.h>
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/load.h"
#include "platform/png_io.h"
#include "platform/scene.h"
#include "platform/water_scene.h"

#define W 320
#define H 192

/* A view straight down (the target a metre north of the point under the eye) on a body's
 * tested quads: eye and target in metres, the body's level in metres. */
typedef struct view {
    double eye[3], target[3];
    int32_t level_m;
} view;

/* The pixel's ray from the eye (look-at basis with the world's z up, 50 degrees of
 * vertical field of view, the default) meets z = level_m at (*gx, *gy) metres. */
static void plane_point(const view *v, int px, int py, double *gx, double *gy)
{
    const double *eye = v->eye, *target = v->target;
    double fwd[3], right[3], up[3], d[3], n, t, f = (H / 2.0) / tan(25.0 * acos(-1.0) / 180.0);
    int k;
    for (k = 0; k < 3; k++) fwd[k] = target[k] - eye[k];
    n = sqrt(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]);
    for (k = 0; k < 3; k++) fwd[k] /= n;
    right[0] = fwd[1]; right[1] = -fwd[0]; right[2] = 0;            /* fwd x z */
    n = sqrt(right[0] * right[0] + right[1] * right[1]);
    right[0] /= n; right[1] /= n;
    up[0] = right[1] * fwd[2] - right[2] * fwd[1];                  /* right x fwd */
    up[1] = right[2] * fwd[0] - right[0] * fwd[2];
    up[2] = right[0] * fwd[1] - right[1] * fwd[0];
    for (k = 0; k < 3; k++) d[k] = fwd[k] + (px + 0.5 - W / 2.0) / f * right[k] - (py + 0.5 - H / 2.0) / f * up[k];
    t = (v->level_m - eye[2]) / d[2];
    *gx = eye[0] + t * d[0];
    *gy = eye[1] + t * d[1];
}

/* The pixels over the half of a shore cell with a low corner: returned (few in a view).
 * fmt: rgb888 or rgb565 (the flag is green's top bit, RGB565's bit 10). */
static int check_view(const view *v, const char *fmt)
{
    const char *in[1];
    char out[256], camera[128], colors[256];
    scene s;
    scene_opts so;
    ws_opts wo;
    water_scene ws;
    br_err err;
    uint8_t *px = NULL, body = 0;
    int pw = 0, ph = 0, x, y, k, tested = 0, bad_low = 0;
    int must_water = 0, bad_water = 0, must_land = 0, bad_land = 0, must_half = 0, bad_half = 0;
    uint32_t i;
    memset(&s, 0, sizeof s); memset(&so, 0, sizeof so); memset(&wo, 0, sizeof wo); memset(&ws, 0, sizeof ws);
    in[0] = t_data("hgt/N47E009.hgt");
    so.quiet = 1;
    wo.quiet = 1;
    CHECK_EQ(scene_open(&s, in, 1, &so, &err), BR_OK);
    CHECK_EQ(ws_open(&ws, &s, &wo, &err), BR_OK);
    for (k = 0; k < ws.nbodies; k++) if (!body && ws.bodies.level[k] == v->level_m) body = (uint8_t)(k + 1);
    CHECK_MSG(body != 0, "no body at %d m", v->level_m);
    for (i = 0; i + 2 < ws.surf[0].mesh.nidx; i += 3) {
        const wm_vert *a = &ws.surf[0].mesh.v[ws.surf[0].mesh.idx[i]];
        tested += a->tested && a->id == body;
    }
    CHECK_MSG(tested > 0, "the body at %d m has no tested triangles", v->level_m);
    snprintf(out, sizeof out, "%s/water_tested_%d_%s.png", t_outdir(), v->level_m, fmt);
    snprintf(colors, sizeof colors, "%s/water_tested_red.txt", t_outdir());
    {
        FILE *o = fopen(colors, "w");
        CHECK(o != NULL);
        if (!o) goto done;
        fputs("-500 255 0 0\n9000 255 0 0\n", o);    /* the land and the lowered bottom: red */
        CHECK_EQ(fclose(o), 0);
    }
    snprintf(camera, sizeof camera, "%.0f,%.0f,%.0f,%.0f,%.0f,%.0f", v->eye[0], v->eye[1], v->eye[2], v->target[0],
             v->target[1], v->target[2]);
    {
        const char *a[] = { "render", in[0], "-o", out, "--size", "320x192", "--time", "1.5", "--no-fog",
                            "--camera", camera, "--colors", colors, "--pixel-error", "0.05", "--format", fmt };
        CHECK_EQ(cmd_render((int)(sizeof a / sizeof a[0]) - 1, (char **)(void *)(a + 1)), 0);
        CHECK_EQ(png_read_rgb(out, &pw, &ph, &px, &err), BR_OK);
    }
    if (!px || pw != W || ph != H || !body) goto done;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            const uint8_t *p = px + 3 * ((size_t)y * W + (size_t)x);
            const int water = p[1] > 8 || p[2] > 8;     /* the water's tint and the sky's reflection */
            double gx, gy, fc, fr;
            long col, row;
            int corner[4], k2, wet = 0, low = 0, tri[3], twet = 0, tlow = 0, tdeep = 1;
            plane_point(v, x, y, &gx, &gy);
            /* the cell (col, row) .. (col + 1, row + 1) under the point and the offsets in it
             * (fc east, fr south), a quarter of a cell or more from its edges and diagonal
             * (the projection's rounding moves a point less) */
            fc = gx * 1e6 / (double)s.f.dx_um;
            fr = (double)s.f.h - 1.0 - gy * 1e6 / (double)s.f.dy_um;
            col = (long)floor(fc);
            row = (long)floor(fr);
            fc -= floor(fc);
            fr -= floor(fr);
            if (fc < 0.25 || fc > 0.75 || fr < 0.25 || fr > 0.75 || fabs(fc + fr - 1) < 0.25) continue;
            if (col < 0 || row < 0 || col + 1 >= s.f.w || row + 1 >= s.f.h) continue;
            /* corners nw ne sw se; 1 wet with the body, 2 low (checked against the DEM), 0 */
            for (k2 = 0; k2 < 4; k2++) {
                const size_t j = (size_t)(row + (k2 >> 1)) * (size_t)s.f.w + (size_t)(col + (k2 & 1));
                corner[k2] = ws.id[j] == body ? 1 : ws.surf[0].mesh.low && ws.surf[0].mesh.low[j] ? 2 : 0;
                if (corner[k2] == 2)
                    bad_low += ws.id[j] || hf_z_to_mm(&s.f, s.f.z[j]) >= (int64_t)v->level_m * 1000;
                wet += corner[k2] == 1;
                low += corner[k2] == 2;
            }
            /* the point's half of the cell: sw se ne, or sw ne nw */
            tri[0] = 2; tri[1] = fc + fr > 1 ? 3 : 1; tri[2] = fc + fr > 1 ? 1 : 0;
            for (k2 = 0; k2 < 3; k2++) {
                twet += corner[tri[k2]] == 1;
                tlow += corner[tri[k2]] == 2;
            }
            /* every corner wet or low 2 m under the level: the terrain (its LOD at 0.05 px
             * under 2 m here, either diagonal) lies under the plane in the whole cell */
            for (k2 = 0; k2 < 4; k2++) {
                const size_t j = (size_t)(row + (k2 >> 1)) * (size_t)s.f.w + (size_t)(col + (k2 & 1));
                const int64_t under_mm = (int64_t)v->level_m * 1000 - hf_z_to_mm(&s.f, s.f.z[j]);
                if (corner[k2] == 0 || (corner[k2] == 2 && under_mm < 2000)) tdeep = 0;
            }
            /* water: the half's corners are wet (the bottom lowered under the plane); land:
             * the cell has a low corner and none wet (no triangle of the exact mesh), or the
             * half has a low corner and lies under the plane */
            if (twet == 3) { must_water++; bad_water += !water; }
            if (low > 0 && wet == 0) { must_land++; bad_land += water; }
            if (wet > 0 && tlow > 0 && tdeep) { must_half++; bad_half += water; }
        }
    printf("%s, tested quads at %d m: %d triangles; %d pixels over water (%d not water), %d over low land (%d water), "
           "%d over a low half of a shore cell (%d water)\n",
           fmt, v->level_m, tested, must_water, bad_water, must_land, bad_land, must_half, bad_half);
    CHECK(ws.surf[0].mesh.low != NULL);
    CHECK_MSG(must_water >= 100, "%d pixels over the body", must_water);
    CHECK_MSG(must_land >= 10, "%d pixels over low land", must_land);
    CHECK_EQ(bad_low, 0);
    CHECK_EQ(bad_water, 0);
    CHECK_EQ(bad_land, 0);
    CHECK_EQ(bad_half, 0);
done:
    free(px);
    ws_close(&ws);
    scene_close(&s);
    return must_half;
}

/* The body, and Lake Constance's low shore at columns 256 to 288, rows 320 to 352. */
static void test_tested_quads(void)
{
    static const view views[3] = { { { 49500, 65000, 1450 }, { 49500, 65001, 450 }, 450 },
                                   { { 17078, 80050, 1392 }, { 17078, 80051, 392 }, 392 },
                                   { { 27594, 73611, 1392 }, { 27594, 73612, 392 }, 392 } };
    static const char *const fmts[2] = { "rgb888", "rgb565" };
    int f;
    for (f = 0; f < 2; f++) {
        int half = 0, k;
        for (k = 0; k < 3; k++) half += check_view(&views[k], fmts[f]);
        CHECK_MSG(half >= 10, "%s: %d pixels over low halves of shore cells", fmts[f], half);
    }
}

/* A texture of N57E011 from its own heights, one texel a grid cell (texel (x, y) covers
 * samples x .. x + 1, y .. y + 1, as rt_scene maps sample (w - 1, h - 1) to texel (tex_w,
 * tex_h)): red where sample (x, y) lies above the sea, blue elsewhere, so a land pixel
 * whose texel came from the wrong place is not red.  Written to path; 0 on success. */
static int sea_texture(const char *dem, const char *path)
{
    hf f;
    br_err err;
    uint8_t *rgb;
    int x, y, tw, th, rc = -1;
    memset(&f, 0, sizeof f);
    CHECK_EQ(dem_load(dem, NULL, &f, &err), BR_OK);
    if (!f.z) return -1;
    tw = f.w - 1; th = f.h - 1;
    rgb = malloc(3 * (size_t)tw * (size_t)th);
    CHECK(rgb != NULL);
    if (rgb) {
        for (y = 0; y < th; y++)
            for (x = 0; x < tw; x++) {
                const int32_t z = f.z[(size_t)y * (size_t)f.w + (size_t)x];
                uint8_t *p = rgb + 3 * ((size_t)y * (size_t)tw + (size_t)x);
                const int land = z != HF_NODATA && hf_z_to_mm(&f, z) > 0;
                p[0] = land ? 255 : 0; p[1] = 0; p[2] = land ? 0 : 255;
            }
        CHECK_EQ(png_write_rgb(path, tw, th, rgb, 3 * (size_t)tw, &err), BR_OK);
        rc = 0;
        free(rgb);
    }
    dem_free(&f);
    return rc;
}

/* The land pixels (red: the colour file paints every height red, and the water's tint
 * turns the lowered bottom blue; or, textured, sea_texture's red) of N57E011 seen
 * straight down from 40 km over Laesoe (columns 0 to 240, rows 806 to 934, 1 to 22 m
 * over the sea), fog off, into land[] (W x H); returns how many.  pixel_error NULL: the
 * full grid. */
static int sea_land(const char *fmt, const char *pixel_error, int textured, uint8_t *land)
{
    const char *dem = t_data("hgt/N57E011.hgt");
    char out[256], colors[256], tex[256];
    uint8_t *px = NULL;
    int pw = 0, ph = 0, n = 0, i;
    br_err err;
    snprintf(out, sizeof out, "%s/water_land_%s_%s%s.png", t_outdir(), fmt, pixel_error ? pixel_error : "full",
             textured ? "_tex" : "");
    snprintf(colors, sizeof colors, "%s/water_land_red.txt", t_outdir());
    snprintf(tex, sizeof tex, "%s/water_land_tex.png", t_outdir());
    {
        FILE *o = fopen(colors, "w");
        CHECK(o != NULL);
        if (!o) return -1;
        fputs("-500 255 0 0\n9000 255 0 0\n", o);
        CHECK_EQ(fclose(o), 0);
    }
    if (textured && sea_texture(dem, tex) != 0) return -1;
    {
        const char *a[] = { "render", dem, "-o", out, "--size", "320x192", "--no-fog", "--format", fmt,
                            "--camera", "10000,20000,40000,10000,20001,0", textured ? "--texture" : "--colors",
                            textured ? tex : colors, pixel_error ? "--pixel-error" : "--full",
                            pixel_error ? pixel_error : "1" };
        CHECK_EQ(cmd_render((int)(sizeof a / sizeof a[0]) - 1, (char **)(void *)(a + 1)), 0);
        CHECK_EQ(png_read_rgb(out, &pw, &ph, &px, &err), BR_OK);
    }
    if (!px || pw != W || ph != H) { free(px); return -1; }
    for (i = 0; i < W * H; i++) {
        const uint8_t *p = px + 3 * (size_t)i;
        land[i] = p[0] > 16 && p[1] <= 8 && p[2] <= 8;
        n += land[i];
    }
    free(px);
    return n;
}

/* The land test (rw_params.land): from 40 km up a pixel of screen error lets the terrain's
 * LOD sink Laesoe (22 m at most) into the lowered sea bottom, and without the test the
 * island was not drawn at all.  Its land pixels must be the full grid's, where the LOD
 * sinks nothing, within 8 % (the cells' edges: the full grid draws the shore where the
 * terrain crosses the plane, the test where a cell's four corners are dry), in both the
 * lanes (XRGB8888) and the scalar loop (RGB565), coloured by height and under a texture
 * (the texel at the plane's point times the sample's lighting). */
static void test_sunk_island(void)
{
    static const char *const fmts[2] = { "rgb888", "rgb565" };
    static uint8_t lod[W * H], full[W * H];
    int f, i, tx;
    for (tx = 0; tx < 2; tx++)
        for (f = 0; f < 2; f++) {
            const int nl = sea_land(fmts[f], "1", tx, lod), nf = sea_land(fmts[f], NULL, tx, full);
            int differ = 0;
            for (i = 0; i < W * H; i++) differ += lod[i] != full[i];
            printf("%s%s, Laesoe from 40 km: %d land pixels at 1 px, %d with the full grid, %d differ\n", fmts[f],
                   tx ? " textured" : "", nl, nf, differ);
            CHECK_MSG(nf > 1000, "%s: %d land pixels with the full grid", fmts[f], nf);
            CHECK_MSG(differ * 100 <= 8 * nf, "%s: %d of %d land pixels differ", fmts[f], differ, nf);
        }
}

int main(void)
{
    T_RUN(test_tested_quads);
    T_RUN(test_sunk_island);
    return t_finish();
}
