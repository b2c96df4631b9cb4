/* tests/test_water.c — water and atmosphere: the detection rules on real tiles (Lake
 * Constance's seam in N47E009, the Kattegat in N57E011), the clipper's water plane, and
 * `bitrain render` with water, waves and fog giving the same frame in bands of 1, 7, 16
 * and 240 rows, in RGB888 and RGB565; golden images of the lake (from the water), the
 * sea (from high), Monai Valley (its still-water level over its wet points as a --water
 * layer) and N47E009's default view (the far water mesh) in RGB888 and RGB565 at a fixed
 * --time. */
#include "tests/test.h"
#include "core/water.h"
#include "platform/cmd.h"
#include "platform/load.h"
#include "platform/png_io.h"
#include "raster/raster.h"
#include "platform/water_scene.h"
#include "tests/support/waterview.h"

#define RUN(a) run(a, (int)(sizeof a / sizeof a[0]))
static int run(const char *const *args, int n)
{
    char *argv[40];
    int i;
    for (i = 0; i < n; i++) argv[i] = (char *)args[i];
    return cmd_render(n, argv);
}

static void detect(const char *rel, wt_bodies *b)
{
    hf f;
    br_err err;
    wt_params p;
    size_t ws;
    void *work;
    uint8_t *id;
    memset(b, 0, sizeof *b);
    if (dem_load(t_data(rel), NULL, &f, &err) != BR_OK) { CHECK(0); return; }
    memset(&p, 0, sizeof p);
    p.sea_on = 1;
    p.min_area = 170;           /* 1 km^2 of 3" samples at 47 N (as platform/water_scene.c) */
    p.join_dz = 5;
    ws = wt_work_size(f.w, f.h);
    work = malloc(ws);
    id = malloc((size_t)f.w * (size_t)f.h);
    CHECK(work && id);
    if (work && id) CHECK_EQ(wt_detect(&f, &p, id, work, ws, b), BR_OK);
    free(work); free(id);
    dem_free(&f);
}

static void test_detect(void)
{
    wt_bodies b;
    detect("hgt/N47E009.hgt", &b);
    /* Lake Constance: 392 m (52,297 samples) and 396 m (30,650) joined along the seam
     * between columns 599 and 600 (with a third flat region of 197 samples), at the
     * larger region's level; the valley terraces of the Rhine fail the rim rule */
    CHECK(b.n >= 2);
    CHECK_EQ(b.kind[0], WT_LAKE);
    CHECK_EQ(b.level[0], 392);
    CHECK(b.area[0] >= 52297 + 30650);
    CHECK(b.joined[0] >= 2);
    CHECK(b.n <= 6);
    detect("hgt/N57E011.hgt", &b);
    CHECK(b.n >= 1);
    CHECK_EQ(b.kind[0], WT_SEA);
    CHECK_EQ(b.level[0], 0);
    CHECK(b.area[0] > 1000000);
}

/* A wall x = -W .. W, z = -H .. H at y = D seen from the origin along +y: with the clip
 * plane z >= 0 only its upper half is drawn, the clipper's sixth plane. */
static void test_clip_plane(void)
{
    enum { W = 64, H = 48 };
    static rs_vertex v[4];
    static const uint32_t idx[4] = { 0, 1, 2, 3 };
    rs_cvert cache[4];
    rs_prim pr;
    rs_frame f;
    cam c;
    int32_t eye[3] = { 0, 0, 0 }, tgt[3] = { 0, 1000, 0 };
    static uint32_t col[W * H], dep[W * H];
    int k, x, y, above = 0, below = 0;
    rs_band_stats st;
    int16_t *chunks;
    /* strip: (-,-) (+,-) (-,+) (+,+), counter-clockwise seen from the origin */
    for (k = 0; k < 4; k++) {
        v[k].p[0] = (k & 1) ? -400 : 400;
        v[k].p[1] = 1000;
        v[k].p[2] = (k & 2) ? 300 : -300;
        v[k].rgb = 0xff0000u;
    }
    CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, W, H, 10, 100000), BR_OK);
    memset(&f, 0, sizeof f);
    f.w = W; f.h = H; f.no_cull = 1; f.clear_rgb = 0x0000ffu;
    f.v = v; f.nv = 4; f.cache = cache;
    pr.kind = RS_STRIP; pr.n = 4; pr.idx = idx;
    f.prims = &pr; f.nprims = 1;
    chunks = malloc(rs_chunk_mem_size(&pr, 1));
    CHECK(chunks != NULL);
    if (!chunks) return;
    f.chunks = chunks;
    f.clip_z_on = 1; f.clip_z = 0;
    cam_viewproj(&c, &f.vp);
    CHECK_EQ(rs_frame_prepare(&f), BR_OK);
    memset(&st, 0, sizeof st);
    CHECK_EQ(rs_draw_band(&f, 0, H, col, W * 4, dep, &st), BR_OK);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            if ((col[y * W + x] & 0xffffffu) != 0xff0000u) continue;
            if (y < H / 2) above++; else below++;
        }
    /* the wall covers about 33 x 24 pixels; its upper half lies above z = 0 */
    CHECK(above > 300);
    CHECK_EQ(below, 0);         /* nothing under the plane */
    CHECK(st.clipped >= 1);
    f.clip_z_on = 0;            /* without the plane both halves show */
    CHECK_EQ(rs_frame_prepare(&f), BR_OK);
    CHECK_EQ(rs_draw_band(&f, 0, H, col, W * 4, dep, NULL), BR_OK);
    below = 0;
    for (y = H / 2; y < H; y++)
        for (x = 0; x < W; x++) below += (col[y * W + x] & 0xffffffu) == 0xff0000u;
    CHECK(below > 300);
    free(chunks);
}

/* The same frame in bands of 1, 7, 16 and 240 rows, water, waves and fog on. */
static void test_bands(void)
{
    static const char *const fmts[2] = { "rgb888", "rgb565" };
    static const char *const bands[4] = { "1", "7", "16", "240" };
    const char *dem = t_data("hgt/N47E009.hgt");
    int f, k;
    for (f = 0; f < 2; f++) {
        unsigned char *ref = NULL;
        size_t nref = 0;
        for (k = 0; k < 4; k++) {
            char out[256];
            unsigned char *b;
            size_t n = 0;
            const char *a[] = { dem, "-o", out, "--size", "96x240", "--format", fmts[f], "--bands", bands[k],
                                "--camera", "30000,75000,450,45000,60000,600", "--time", "2.5",
                                "--reflection", "half", "--fog" };
            snprintf(out, sizeof out, "%s/water_bands_%s_%s.png", t_outdir(), fmts[f], bands[k]);
            CHECK_EQ(RUN(a), 0);
            b = t_read_file(out, &n);
            CHECK(b && n > 0);
            if (k == 0) { ref = b; nref = n; continue; }
            CHECK_MSG(b && ref && n == nref && !memcmp(b, ref, n), "%s bands of %s rows differ", fmts[f], bands[k]);
            free(b);
        }
        free(ref);
    }
}

/* Monai's water surface: the still-water level (0 m) over the wet points of its
 * bathymetry (depth > 0), nodata elsewhere, as an ESRI ASCII grid of the same size. */
static int monai_water(const char *path)
{
    hf f;
    br_err err;
    dem_opts d;
    FILE *o;
    int32_t x, y;
    memset(&d, 0, sizeof d);
    d.xyz_depth = 1;
    if (dem_load(t_data("xyz/monai_valley_bathymetry.txt"), &d, &f, &err) != BR_OK) return 0;
    o = fopen(path, "w");
    if (!o) { dem_free(&f); return 0; }
    fprintf(o, "ncols %d\nnrows %d\nxllcorner 0\nyllcorner 0\ncellsize 0.014\nNODATA_value -9999\n", f.w, f.h);
    for (y = 0; y < f.h; y++)
        for (x = 0; x < f.w; x++) {
            int32_t z = f.z[(size_t)y * (size_t)f.w + (size_t)x];
            fprintf(o, "%s%c", z != HF_NODATA && z < 0 ? "0" : "-9999", x + 1 < f.w ? ' ' : '\n');
        }
    dem_free(&f);
    return fclose(o) == 0;
}

/* Golden images: lake, sea, Monai, RGB888 and RGB565, --time 1.5; and N47E009's default
 * view, whose water is far enough for the far water mesh (water_scene.h surf). */
static void test_goldens(void)
{
    static const char *const fmts[2] = { "rgb888", "rgb565" };
    char water[256], dem_lake[256], dem_sea[256], dem_monai[256];
    int f, k;
    snprintf(water, sizeof water, "%s/monai_water.asc", t_outdir());
    CHECK(monai_water(water));
    snprintf(dem_lake, sizeof dem_lake, "%s", t_data("hgt/N47E009.hgt"));
    snprintf(dem_sea, sizeof dem_sea, "%s", t_data("hgt/N57E011.hgt"));
    snprintf(dem_monai, sizeof dem_monai, "%s", t_data("xyz/monai_valley_bathymetry.txt"));
    for (f = 0; f < 2; f++)
        for (k = 0; k < 4; k++) {
            static const char *const names[4] = { "lake", "sea", "monai", "far" };
            char out[256], name[64];
            const char *lake[] = { dem_lake, "-o", out, "--size", "160x96", "--format", fmts[f], "--time", "1.5",
                                   "--camera", "40000,66000,420,60000,50000,500" };
            const char *sea[] = { dem_sea, "-o", out, "--size", "160x96", "--format", fmts[f], "--time", "1.5",
                                  "--camera", "10000,20000,3000,40000,60000,0" };
            const char *monai[] = { dem_monai, "--xyz-depth", "--water", water, "-o", out, "--size", "160x96",
                                    "--format", fmts[f], "--time", "1.5" };
            const char *far[] = { dem_lake, "-o", out, "--size", "160x96", "--format", fmts[f], "--time", "1.5" };
            snprintf(name, sizeof name, "water_%s_%s", names[k], fmts[f]);
            snprintf(out, sizeof out, "%s/%s.png", t_outdir(), name);
            CHECK_EQ(k == 0 ? RUN(lake) : k == 1 ? RUN(sea) : k == 2 ? RUN(monai) : RUN(far), 0);
            wv_golden(name, out);
        }
}

/* The reflection shows the terrain: a grazing view across Lake Constance with a colour
 * file that paints the land above the water (398 m and up) one pure colour and the lake
 * (392/396 m) black.  The water pixels are those the same view draws black with
 * --no-water; in the rows under the far shore they take the land's colour (red, then
 * green with the green file: 421 of 7529 each), not without the reflection (20, the
 * shore's edge pixels).  Fog off, --time fixed. */
static void test_reflection_colour(void)
{
    static const char *const ramps[2] = { "0 0 0 0\n397 0 0 0\n398 255 0 0\n9000 255 0 0\n",
                                          "0 0 0 0\n397 0 0 0\n398 0 255 0\n9000 0 255 0\n" };
    char col[2][256], out[4][256], dem[256];
    uint8_t *px[4] = { NULL, NULL, NULL, NULL };
    int k, i, w = 0, h = 0, wet = 0, tint[3] = { 0, 0, 0 };
    snprintf(dem, sizeof dem, "%s", t_data("hgt/N47E009.hgt"));
    for (k = 0; k < 2; k++) {
        FILE *f;
        snprintf(col[k], sizeof col[k], "%s/water_ramp%d.txt", t_outdir(), k);
        f = fopen(col[k], "w");
        CHECK(f != NULL);
        if (!f) return;
        fputs(ramps[k], f);
        CHECK_EQ(fclose(f), 0);
    }
    for (k = 0; k < 4; k++) {
        /* 0: red, 1: green, 2: red without reflection, 3: red without water */
        const char *args[] = { dem, "-o", out[k], "--size", "160x96", "--time", "1.5", "--no-fog", "--camera",
                               "40000,66000,420,60000,50000,500", "--colors", col[k == 1],
                               k == 3 ? "--no-water" : "--reflection", k == 2 ? "none" : "full" };
        br_err err;
        int aw, ah;
        snprintf(out[k], sizeof out[k], "%s/water_refl_colour%d.png", t_outdir(), k);
        CHECK_EQ(run(args, k == 3 ? 13 : 14), 0);     /* k == 3: no --reflection value */
        CHECK_EQ(png_read_rgb(out[k], &aw, &ah, &px[k], &err), BR_OK);
        if (!px[k]) goto done;
        w = aw; h = ah;
    }
    for (i = 0; i < w * h; i++) {
        const uint8_t *d = px[3] + 3 * i;
        if (d[0] >= 16 || d[1] >= 16 || d[2] >= 16) continue;     /* not water */
        wet++;
        for (k = 0; k < 3; k++) {
            const uint8_t *p = px[k] + 3 * i;
            int c = k == 1 ? 1 : 0;     /* the painted channel */
            tint[k] += p[c] > p[1 - c] + 32 && p[c] > p[2] + 32;
        }
    }
    CHECK_MSG(wet > w * h / 3, "%d water pixels", wet);
    CHECK_MSG(tint[0] > 200, "%d water pixels red", tint[0]);
    CHECK_MSG(tint[1] > 200, "%d water pixels green", tint[1]);
    CHECK_MSG(tint[2] * 8 < tint[0], "%d water pixels red without the reflection, %d with", tint[2], tint[0]);
done:
    for (k = 0; k < 4; k++) free(px[k]);
}

typedef struct img_sink {
    uint32_t *px;
    int32_t w;
} img_sink;

static br_status to_img(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    img_sink *o = (img_sink *)user;
    int32_t y;
    for (y = 0; y < rows; y++)
        memcpy(o->px + (size_t)(y0 + y) * (size_t)o->w, (const uint8_t *)px + (size_t)y * stride, (size_t)o->w * 4);
    return BR_OK;
}

/* The reflection's own LOD: the lake from the water at 320x192, 1 px.  At
 * --reflection-error 4 the mirrored camera's selection has fewer triangles than at 1 and
 * the reflection frame sets up fewer (drawn whole, full resolution); at 0 (the zeroed
 * options here; the commands' default is WS_REFL_ERR, 4) it draws the terrain's mesh; the
 * terrain's mesh
 * and its hysteresis state are untouched by it (the same strip before and after).
 * Nothing under the plane leaks: the reflection's own mesh moved under the plane draws
 * no pixel through the clipper's plane (without the plane, it does). */
/* The mirror's vertices (ws.rbed) are the mesh's (src, from m), with the lowered bed of
 * the mirror's body raised to the water plane and nothing else changed; the lake camera
 * has such vertices. */
static void bed_level_check(const water_scene *ws, const scene *s, const rs_vertex *src, const bt_mesh *m)
{
    uint32_t i, raised = 0, bad = 0, below = 0;
    const int32_t plane = ws->rfr.clip_z, body = ws->rw->p.refl_body;
    for (i = 0; i < m->nv; i++) {
        const rs_vertex *a = &src[i], *b = &ws->rbed[i];
        const int wet = ws->id[(size_t)m->v[i].y * (size_t)s->f.w + (size_t)m->v[i].x] == body;
        const int32_t z = wet && a->p[2] < plane ? plane : a->p[2];
        bad += b->p[0] != a->p[0] || b->p[1] != a->p[1] || b->p[2] != z || b->rgb != a->rgb;
        raised += b->p[2] != a->p[2];
        below += b->p[2] < plane;
    }
    printf("mirror vertices: %u of %u raised to the plane, %u left under it\n", raised, m->nv, below);
    CHECK_EQ(bad, 0);
    CHECK_EQ(ws->rfr.clip_z_on, below > 0);     /* the clip plane only where it can cut */
    CHECK(raised > 10);
}

static void refl_lod_opts(wv_view *v)
{
    v->so.ramp_abs = 1;
    v->wo.reflection = 1; v->wo.no_fog = 1;
    v->bp.hyst_q8 = 64;
}

static void test_refl_lod(void)
{
    enum { W = 320, H = 192 };
    static uint32_t col[W * H], dep[W * H];
    double eye[3] = { 40000, 66000, 420 }, tgt[3] = { 60000, 50000, 500 };
    static wv_view w;
    rs_band_stats st;
    uint32_t ntri[2] = { 0, 0 }, tris[2] = { 0, 0 }, tns, i;
    uint32_t *tstrip = NULL;
    int k;
    wv_view_open(&w, "hgt/N47E009.hgt", eye, tgt, W, H, refl_lod_opts);
    tns = w.s.mesh.ns;
    tstrip = malloc(sizeof *tstrip * (tns ? tns : 1));
    CHECK(tstrip != NULL);
    if (!tstrip) goto done;
    memcpy(tstrip, w.s.mesh.strip, sizeof *tstrip * tns);
    CHECK_EQ(ws_frame(&w.ws, &w.s, &w.c, &w.fr, &w.err), BR_OK);     /* refl_err 0: the terrain's mesh */
    CHECK(w.ws.rown == 0 && w.ws.rfr.v == w.ws.rbed && w.ws.rfr.nv == w.s.mesh.nv);
    bed_level_check(&w.ws, &w.s, w.s.verts, &w.s.mesh);
    for (k = 0; k < 2; k++) {
        w.ws.o.refl_err = k ? 4 : 1;
        CHECK_EQ(ws_frame(&w.ws, &w.s, &w.c, &w.fr, &w.err), BR_OK);
        CHECK_EQ(w.ws.rown, 1);
        if (!w.ws.rown) goto done;
        CHECK(w.ws.rfr.v == w.ws.rbed && w.ws.rfr.nv == w.ws.rmesh.nv);
        bed_level_check(&w.ws, &w.s, w.ws.rverts, &w.ws.rmesh);
        ntri[k] = w.ws.rmesh.ntri;
        memset(&st, 0, sizeof st);
        CHECK_EQ(rs_draw_band(&w.ws.rfr, 0, H, col, W * 4, dep, &st), BR_OK);
        tris[k] = st.tris;
    }
    printf("reflection LOD: %u triangles selected, %u set up at the terrain's error; %u, %u at 4x; terrain %u\n",
           ntri[0], tris[0], ntri[1], tris[1], w.s.mesh.ntri);
    CHECK_MSG(ntri[1] * 2 < ntri[0], "%u triangles at 4x, %u at 1x", ntri[1], ntri[0]);
    CHECK_MSG(tris[1] * 2 < tris[0], "%u triangles set up at 4x, %u at 1x", tris[1], tris[0]);
    /* the terrain's mesh is the one its selection made: the reflection's does not touch
     * its hysteresis state (the next frame's terrain selection reads it) */
    CHECK(w.s.mesh.ns == tns && !memcmp(tstrip, w.s.mesh.strip, sizeof *tstrip * tns));
    bt_parts_reset(w.s.parts);    /* the first frame's cut of the parts, so its numbering */
    CHECK_EQ(scene_mesh(&w.s, &w.c, &w.bp), BR_OK);
    CHECK(w.s.mesh.ns == tns && !memcmp(tstrip, w.s.mesh.strip, sizeof *tstrip * tns));
    /* the reflection's mesh moved down until its highest vertex is one unit under the
     * plane: nothing through the clipper's plane; without the plane it shows */
    {
        int32_t zmax = INT32_MIN;
        for (i = 0; i < w.ws.rfr.nv; i++) if (w.ws.rverts[i].p[2] > zmax) zmax = w.ws.rverts[i].p[2];
        for (i = 0; i < w.ws.rfr.nv; i++) w.ws.rverts[i].p[2] -= zmax - w.ws.rfr.clip_z + 1;
        w.ws.rfr.v = w.ws.rverts;   /* as they are, no bed raised to the plane */
    }
    for (k = 0; k < 2; k++) {
        w.ws.rfr.clip_z_on = !k;
        CHECK_EQ(rs_frame_prepare(&w.ws.rfr), BR_OK);
        memset(&st, 0, sizeof st);
        CHECK_EQ(rs_draw_band(&w.ws.rfr, 0, H, col, W * 4, dep, &st), BR_OK);
        if (k == 0) CHECK_MSG(st.pixels == 0, "%u pixels under the plane", st.pixels);
        else CHECK_MSG(st.pixels > 1000, "%u pixels without the plane", st.pixels);
    }
done:
    free(tstrip);
    wv_view_close(&w);
}

/* The mirror goes to the body whose water covers the screen.  At the lake path's first
 * camera body 2 has triangles beside and behind the camera that need the clipper, while
 * body 1 fills the view; counted as the whole screen, those gave body 2 the mirror and
 * the lake in view reflected only sky (the frame had the bytes and the drawn triangles
 * of the frame without a reflection).  Their area cut at the near plane and the screen
 * gives it to body 1, and the half-resolution reflection shows: more triangles drawn,
 * other bytes (64-row bands, 320x240, fog on). */
static void test_refl_body_rows(void)
{
    enum { W = 320, H = 240, BR = 64 };
    double eye[3] = { 21096.2, 76714.6, 464.0 }, tgt[3] = { 23604.8, 75069.3, 164.0 };
    uint8_t *px[2] = { NULL, NULL };
    uint32_t tris[2] = { 0, 0 };
    static wv_view w;
    int k;
    for (k = 0; k < 2; k++) {
        size_t mb;
        void *mem = NULL;
        int32_t y0;
        wv_view_open(&w, "hgt/N47E009.hgt", eye, tgt, W, H, NULL);
        w.ws.o.reflection = k ? 4 : 0;      /* none; the default, half (read by each ws_frame) */
        CHECK_EQ(ws_frame(&w.ws, &w.s, &w.c, &w.fr, &w.err), BR_OK);
        if (k == 0)
            CHECK_MSG(w.ws.rw->refl != NULL && w.ws.rw->p.refl_body == 1, "mirror on body %d", (int)w.ws.rw->p.refl_body);
        mb = rs_pipe_mem_size(&w.ws.pipe, BR);
        mem = malloc(mb);
        px[k] = malloc((size_t)W * H * 4);
        CHECK(mem && px[k]);
        for (y0 = 0; mem && px[k] && y0 < H; y0 += BR) {
            rs_band b;
            rs_band_stats st;
            const int32_t rows = H - y0 < BR ? H - y0 : BR;
            int32_t y;
            CHECK_EQ(rs_pipe_band(&w.ws.pipe, y0, rows, mem, mb, &b, &st), BR_OK);
            tris[k] += st.tris;
            for (y = 0; y < rows; y++)
                memcpy(px[k] + (size_t)(y0 + y) * W * 4, (const uint8_t *)b.color + (size_t)y * b.stride, (size_t)W * 4);
        }
        free(mem);
        wv_view_close(&w);
    }
    CHECK_MSG(tris[0] > tris[1] + 1000, "%u triangles with the reflection, %u without", tris[0], tris[1]);
    CHECK(px[0] && px[1] && memcmp(px[0], px[1], (size_t)W * H * 4) != 0);
    free(px[0]); free(px[1]);
}

/* A still flat mirror: waves off, the Fresnel term forced to 1, full-resolution
 * reflection, fog off, the lake from the water (test_goldens' camera).  The mirrored
 * camera C2 = (M right, -M up, M fwd) at M eye (M: z -> 2 H - z; a proper rotation, so
 * the terrain's own winding) sees the terrain above the plane at camera coordinates
 * (x, -y, z) of what the camera sees mirrored: its row h-1-j, drawn directly with the
 * same clip plane, is the reflection's row j.  Every water pixel whose mirrored pixel
 * shows terrain is compared.  The projection rounds -y and y to subpixels differently,
 * so edge functions and Gouraud gradients differ by a rounding: tolerance, at least 3/4
 * of the pixels exact, at most 3 % more than 2 per channel off (triangle edges, where
 * the neighbouring triangle wins).  The reflection draws its own LOD at the terrain's
 * error (--reflection-error 1): the mirrored camera's own mesh, which C2 draws here;
 * measured 287 exact, 68 within 2, 6 beyond, of 361. */
static void test_still_mirror(void)
{
    enum { W = 160, H = 96 };
    static uint32_t wet[W * H], dry[W * H], dir[W * H], dep[W * H];
    double eye[3] = { 40000, 66000, 420 }, tgt[3] = { 60000, 50000, 500 };
    scene s;
    scene_opts so;
    ws_opts wo;
    water_scene ws;
    br_err err;
    cam c, c2;
    bt_params bp;
    rs_frame fr, dfr;
    img_sink is;
    rs_cvert *dcache = NULL;
    int16_t *dchunks = NULL;
    void *mem = NULL;
    size_t ms;
    int32_t x, y, k, n = 0, same = 0, near = 0;
    wv_defaults(&so, &wo, &bp, &fr, &err);
    so.ramp_abs = 1;
    wo.reflection = 1; wo.no_waves = 1; wo.fresnel_one = 1; wo.no_fog = 1;
    wo.refl_err = 1;                    /* the reflection's own selection at the terrain's error */
    fr.clear_rgb = 0x99ccffu;
    wv_lake_frame(&s, &so, &ws, &wo, eye, tgt, W, H, &c, &bp, &fr);
    CHECK_EQ(rs_draw_band(&fr, 0, H, dry, W * 4, dep, NULL), BR_OK);      /* the terrain alone */
    CHECK_EQ(ws_frame(&ws, &s, &c, &fr, &err), BR_OK);
    CHECK(ws.rfr.nv > 0 && ws.rfr.w == W && ws.rown == 1);
    ms = rs_pipe_mem_size(&ws.pipe, H);
    mem = malloc(ms);
    is.px = wet; is.w = W;
    CHECK(mem != NULL);
    if (!mem || ws.rfr.nv == 0) goto done;
    CHECK_EQ(rs_pipe_run(&ws.pipe, H, mem, ms, to_img, &is, NULL), BR_OK);
    /* the mirrored camera, drawn directly */
    c2 = c;
    c2.eye[2] = 2 * ws.rfr.clip_z - c.eye[2];
    for (k = 0; k < 3; k++) {
        c2.right[k] = k == 2 ? -c.right[k] : c.right[k];
        c2.up[k] = k == 2 ? c.up[k] : -c.up[k];
        c2.fwd[k] = k == 2 ? -c.fwd[k] : c.fwd[k];
    }
    CHECK(!memcmp(&c2, &ws.rcam, sizeof c2));
    dfr = ws.rfr;
    dfr.prims = &ws.rmprim;     /* C2 is a proper rotation: the mesh's own winding */
    dfr.nprims = 1;
    dcache = malloc(rs_cache_mem_size(dfr.nv));
    dchunks = malloc(rs_chunk_mem_size(dfr.prims, 1) + 4);
    CHECK(dcache && dchunks);
    if (!dcache || !dchunks) goto done;
    dfr.cache = dcache; dfr.chunks = dchunks; dfr.clear_rgb = 0xff00ffu;
    cam_viewproj(&c2, &dfr.vp);
    CHECK_EQ(rs_frame_prepare(&dfr), BR_OK);
    CHECK_EQ(rs_draw_band(&dfr, 0, H, dir, W * 4, dep, NULL), BR_OK);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            const uint32_t a = wet[y * W + x] & 0xffffffu, m = dir[(H - 1 - y) * W + x] & 0xffffffu;
            if (a == (dry[y * W + x] & 0xffffffu) || m == 0xff00ffu) continue;   /* not water; sky */
            n++;
            same += a == m;
            if (a != m) {
                int cmax = 0;
                for (k = 0; k < 24; k += 8) {
                    int dc = (int)((a >> k) & 255u) - (int)((m >> k) & 255u);
                    if (dc < 0) dc = -dc;
                    if (dc > cmax) cmax = dc;
                }
                near += cmax <= 2;
            }
        }
    printf("still mirror: %d of %d reflected pixels exact, %d within 2 per channel\n", same, n, near);
    CHECK_MSG(n > 300, "%d reflected pixels", n);
    CHECK_MSG(same * 4 >= n * 3, "%d of %d reflected pixels exact", same, n);
    CHECK_MSG((n - same - near) * 100 <= n * 3, "%d of %d reflected pixels more than 2 off", n - same - near, n);
done:
    free(mem); free(dcache); free(dchunks);
    ws_close(&ws);
    scene_close(&s);
}

/* Which bodies' triangles of the water mesh cover point (cx + 0.3, cy + 0.6) of each cell
 * (a bit per body id), inclusive of edges: the point is inside a cell, never on a cell's
 * border, where triangles of different bodies meet. */
static void cover_cells(const wm_mesh *m, int32_t w, int32_t h, uint32_t *cov)
{
    uint32_t k;
    memset(cov, 0, sizeof *cov * (size_t)w * (size_t)h);
    for (k = 0; k + 2 < m->nidx; k += 3) {
        const wm_vert *t[3] = { &m->v[m->idx[k]], &m->v[m->idx[k + 1]], &m->v[m->idx[k + 2]] };
        int32_t x0 = t[0]->x, x1 = t[0]->x, y0 = t[0]->y, y1 = t[0]->y, x, y, j;
        for (j = 1; j < 3; j++) {
            x0 = t[j]->x < x0 ? t[j]->x : x0; x1 = t[j]->x > x1 ? t[j]->x : x1;
            y0 = t[j]->y < y0 ? t[j]->y : y0; y1 = t[j]->y > y1 ? t[j]->y : y1;
        }
        for (y = y0; y < y1 && y < h; y++)
            for (x = x0; x < x1 && x < w; x++) {
                const int64_t px = 10 * (int64_t)x + 3, py = 10 * (int64_t)y + 6;
                int pos = 0, neg = 0;
                for (j = 0; j < 3; j++) {
                    const wm_vert *a = t[j], *b = t[(j + 1) % 3];
                    const int64_t e = (int64_t)(b->x - a->x) * (py - 10 * a->y) - (int64_t)(b->y - a->y) * (px - 10 * a->x);
                    pos += e >= 0; neg += e <= 0;
                }
                if (pos == 3 || neg == 3) cov[(size_t)y * (size_t)w + (size_t)x] |= 1u << t[0]->id;
            }
    }
}

/* Two bodies at different levels that meet: the Rhine in N50E008 (the Rheingau, at the
 * tile's south edge), which SRTM flattened at 80 m (468 samples) and 79 m (364) on either
 * side of a step between columns 101 and 104, rows 1189 to 1192.  Every cell whose four
 * corners are wet is covered by the water mesh, and a cell with corners of both bodies by
 * the lower body (79 m) alone, sloping to the 80 m samples (docs/water.md's table);
 * before, such cells were nobody's and the lowered bottom showed through a hole in the
 * river. */
static void test_step(void)
{
    const char *in[1];
    scene s;
    scene_opts so;
    ws_opts wo;
    water_scene ws;
    br_err err;
    uint32_t *cov = NULL;
    int32_t x, y, w, h, lo = 0, k, wet = 0, mixed = 0, bad = 0, miss = 0;
    memset(&s, 0, sizeof s); memset(&so, 0, sizeof so); memset(&wo, 0, sizeof wo); memset(&ws, 0, sizeof ws);
    in[0] = t_data("hgt/N50E008.hgt");
    so.quiet = 1;
    wo.quiet = 1;
    CHECK_EQ(scene_open(&s, in, 1, &so, &err), BR_OK);
    CHECK_EQ(ws_open(&ws, &s, &wo, &err), BR_OK);
    CHECK_EQ(ws.nbodies, 2);
    if (ws.nbodies != 2) goto done;
    CHECK_EQ(ws.bodies.level[0], 80);
    CHECK_EQ(ws.bodies.level[1], 79);
    for (k = 0; k < 2; k++) if (ws.bodies.level[k] < ws.bodies.level[lo]) lo = k;
    w = s.f.w; h = s.f.h;
    cov = malloc(sizeof *cov * (size_t)w * (size_t)h);
    CHECK(cov != NULL);
    if (!cov) goto done;
    for (k = 0; k < 2; k++) {   /* both meshes: the fine one and the far one */
        cover_cells(&ws.surf[k].mesh, w, h, cov);
        for (y = 0; y + 1 < h; y++)
            for (x = 0; x + 1 < w; x++) {
                const uint8_t *i0 = ws.id + (size_t)y * (size_t)w + (size_t)x, *i1 = i0 + w;
                const uint32_t c = cov[(size_t)y * (size_t)w + (size_t)x];
                const uint32_t set = (1u << i0[0]) | (1u << i0[1]) | (1u << i1[0]) | (1u << i1[1]);
                if (!i0[0] || !i0[1] || !i1[0] || !i1[1]) continue;
                wet++;
                miss += c == 0;
                if ((set & (set - 1)) == 0) continue;       /* one body */
                mixed++;
                bad += c != 1u << (lo + 1);
            }
    }
    printf("step, both meshes: %d all-wet cells, %d of them uncovered; %d with both bodies, %d not the lower body's alone\n",
           wet, miss, mixed, bad);
    CHECK_MSG(mixed >= 1, "%d cells with both bodies", mixed);
    CHECK_EQ(bad, 0);
    CHECK_EQ(miss, 0);
done:
    free(cov);
    ws_close(&ws);
    scene_close(&s);
}

/* Dry land below the sea level inside an island: Laesoe (N57E011, columns 0 to 240, rows
 * 806 to 934, 1 to 22 m) holds 24 samples at -1 and -2 m in its southern marshes, enclosed
 * by land at or above 0 m.  The water mesh covers the cells around them as it covers the
 * island (docs/water.md's table), and the default view from high (docs/img/
 * water_sea_high.png: the terrain's LOD sinks the island into the lowered sea bottom)
 * shows no light patch at pixel (160, 190): before, those cells were a hole in the water
 * through which the bottom (the ramp at -21 m, 0x437199 after fog) showed, 41 pixels. */
static void test_pocket(void)
{
    const char *in[1];
    scene s;
    scene_opts so;
    ws_opts wo;
    water_scene ws;
    br_err err;
    uint32_t *cov = NULL;
    uint8_t *px = NULL;
    char out[256];
    int32_t x, y, w, h, m, pockets = 0, open = 0, light = 0, pw = 0, ph = 0;
    memset(&s, 0, sizeof s); memset(&so, 0, sizeof so); memset(&wo, 0, sizeof wo); memset(&ws, 0, sizeof ws);
    in[0] = t_data("hgt/N57E011.hgt");
    so.quiet = 1;
    wo.quiet = 1;
    CHECK_EQ(scene_open(&s, in, 1, &so, &err), BR_OK);
    CHECK_EQ(ws_open(&ws, &s, &wo, &err), BR_OK);
    CHECK_EQ(ws.nbodies, 1);
    w = s.f.w; h = s.f.h;
    cov = malloc(sizeof *cov * (size_t)w * (size_t)h);
    CHECK(cov != NULL);
    if (!cov || ws.nbodies != 1) goto done;
    for (m = 0; m < 2; m++) {   /* both meshes: the fine one and the far one */
        cover_cells(&ws.surf[m].mesh, w, h, cov);
        for (y = 806; y <= 934; y++)
            for (x = 0; x <= 240; x++) {
                const size_t i = (size_t)y * (size_t)w + (size_t)x;
                int k;
                if (ws.id[i] || s.f.z[i] >= 0) continue;
                pockets += m == 0;
                for (k = 0; k < 4; k++) {   /* the four cells around the sample */
                    const int32_t cx = x - (k & 1), cy = y - (k >> 1);
                    if (cx < 0 || cy < 0 || cx + 1 >= w || cy + 1 >= h) continue;
                    open += cov[(size_t)cy * (size_t)w + (size_t)cx] != 1u << 1;
                }
            }
    }
    CHECK_EQ(pockets, 24);
    CHECK_MSG(open == 0, "%d cells around Laesoe's pockets not covered by the sea", open);
    {
        const char *a[] = { in[0], "-o", out, "--size", "320x240" };
        snprintf(out, sizeof out, "%s/water_sea_high.png", t_outdir());
        CHECK_EQ(RUN(a), 0);
        CHECK_EQ(png_read_rgb(out, &pw, &ph, &px, &err), BR_OK);
    }
    if (!px || pw != 320 || ph != 240) goto done;
    /* lighter than the sea (0x1d4762 there), not the sky (blue >= 200) and not next to it
     * (the bottom's edge shows in a pixel along the tile's near edges) */
    for (y = 170; y < 210; y++)
        for (x = 130; x < 190; x++) {
            const uint8_t *p = px + 3 * ((size_t)y * 320 + (size_t)x);
            const int edge = p[3 + 2] >= 200 || p[-3 + 2] >= 200 || p[3 * 320 + 2] >= 200 || p[-3 * 320 + 2] >= 200;
            light += p[0] >= 50 && p[2] >= 130 && p[2] < 200 && !edge;
        }
    printf("pocket: %d pocket samples, %d open cells, %d light pixels around (160, 190)\n", pockets, open, light);
    CHECK_MSG(light == 0, "%d light pixels in the sea around (160, 190)", light);
done:
    free(cov); free(px);
    ws_close(&ws);
    scene_close(&s);
}

/* Mean absolute difference per channel of two PNGs of one size (-1: unreadable). */
static int mean_diff(const char *pa, const char *pb)
{
    int aw, ah, bw, bh;
    uint8_t *a = NULL, *b = NULL;
    br_err err;
    long sum = 0, i, n;
    if (png_read_rgb(pa, &aw, &ah, &a, &err) != BR_OK || png_read_rgb(pb, &bw, &bh, &b, &err) != BR_OK
        || aw != bw || ah != bh) { free(a); free(b); return -1; }
    n = 3L * aw * ah;
    for (i = 0; i < n; i++) sum += a[i] > b[i] ? a[i] - b[i] : b[i] - a[i];
    free(a); free(b);
    return (int)(sum / n);
}

/* Looking straight down on Lake Constance from 3 km, the fog (which hides the tile's far
 * edge) must leave the ground under the camera alone: it runs from 55 % of the farthest
 * grid corner's distance from the eye, not of its depth along the view axis (tens of
 * kilometres, not the 3 km under the camera). */
static void test_fog_from_high(void)
{
    char a[256], b[256];
    const char *dem = "assets/N47E009.hgt.gz";
    const char *fog[] = { dem, "--camera", "22500,75900,3000,22501,75901,164", "--size", "64x64",
                          "--time", "1", "-o", a };
    const char *nofog[] = { dem, "--camera", "22500,75900,3000,22501,75901,164", "--size", "64x64",
                            "--time", "1", "--no-fog", "-o", b };
    snprintf(a, sizeof a, "%s/water_high_fog.png", t_outdir());
    snprintf(b, sizeof b, "%s/water_high_nofog.png", t_outdir());
    CHECK_EQ(RUN(fog), 0);
    CHECK_EQ(RUN(nofog), 0);
    CHECK_MSG(mean_diff(a, b) >= 0 && mean_diff(a, b) <= 2, "fog changed the ground under the camera by %d a channel",
              mean_diff(a, b));
}

/* bitrain bench --scene default --with-water draws the water frame users see (and the
 * water options need it). */
static void test_bench_water(void)
{
    char out[256];
    const char *wet[] = { "--scene", "default", "--with-water", "--frames", "2", "--size", "96x64",
                          "--path", "assets/lake-path.cam", "-o", out };
    const char *bad[] = { "--scene", "default", "--no-water", "--frames", "1" };
    int w, h, x, y, n = 0;
    uint8_t *rgb;
    br_err err;
    snprintf(out, sizeof out, "%s/bench_water.png", t_outdir());
    CHECK_EQ(cmd_bench_default((int)(sizeof wet / sizeof wet[0]), (char **)(void *)wet), 0);
    CHECK_EQ(cmd_bench_default((int)(sizeof bad / sizeof bad[0]), (char **)(void *)bad), 2);
    if (png_read_rgb(out, &w, &h, &rgb, &err) != BR_OK) { CHECK_MSG(0, "cannot read %s", out); return; }
    for (y = h / 2; y < h; y++)
        for (x = 0; x < w; x++) {
            const uint8_t *p = rgb + 3 * ((size_t)y * (size_t)w + (size_t)x);
            n += p[2] > p[0] + 16 && p[2] > p[1];
        }
    free(rgb);
    CHECK_MSG(n > 100, "%d water pixels in the lower half of the lake path's second frame", n);
}

int main(void)
{
    T_RUN(test_detect);
    T_RUN(test_step);
    T_RUN(test_pocket);
    T_RUN(test_clip_plane);
    T_RUN(test_bands);
    T_RUN(test_goldens);
    T_RUN(test_reflection_colour);
    T_RUN(test_still_mirror);
    T_RUN(test_refl_lod);
    T_RUN(test_refl_body_rows);
    T_RUN(test_fog_from_high);
    T_RUN(test_bench_water);
    return t_finish();
}
