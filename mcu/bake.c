/* mcu/bake.c — the host tool that makes a board's flash contents (mcu/bake.h): a
 * square crop of a real DEM, its bitree hierarchy (bt_build, exact metric, saved with
 * bt_tree_save for bt_attach), the shading cache of raster/terrain.h filled for every
 * sample (light levels and the ramp's height table) and a camera path, written as const
 * C arrays.
 *
 *   bake DEM X0 Y0 SIDE PATH.cam OUT.c [PIXEL_ERROR_Q8]
 *
 * The crop is columns X0 .. X0 + SIDE - 1 and rows Y0 .. Y0 + SIDE - 1 of DEM (any
 * format platform/load.h reads).  PATH.cam holds the frames, one `--camera` line each
 * (platform/campath.h) in metres in the CROP's frame (x east from its west edge, y north
 * from its south edge); at most BAKE_MAX_FRAMES are taken.  The scene is set up as
 * platform/scene.c sets up a georeferenced DEM (default ramp over the crop's heights, sun
 * at 315 / 45 degrees, ambient 0.3, vertical scale 1) and the cameras as scene_camera
 * chooses them (60 degrees, near and far planes), at 320 x 240.  Selection as the
 * viewer's: hysteresis 1/4 and geomorph 1/2 of the threshold.  The frames are also drawn
 * here by the product's own path (scene_frame, then the frame driver in 16-row RGB565
 * bands with 16-bit depth) and by the stream path (raster/terrain_stream.h, the same
 * rule without hysteresis), both with the library's own drawing code, and their SPI
 * stream checksums baked beside them: what the mesh and the stream boards must give. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/bitree.h"
#include "mcu/bake.h"
#include "platform/campath.h"
#include "platform/load.h"
#include "platform/board/spi_band.h"
#include "platform/scene.h"
#include "raster/frame.h"
#include "raster/terrain_stream.h"

#define FB_W 320
#define FB_H 240
#define FOVY 60

static int fail(const char *what, const br_err *err)
{
    fprintf(stderr, "bake: %s%s%s\n", what, err ? ": " : "", err ? err->msg : "");
    return 1;
}

/* The crop as a heightfield of its own (georeference moved to its first sample). */
static int crop(const hf *full, int32_t x0, int32_t y0, int32_t side, hf *out)
{
    int32_t y;
    *out = *full;
    out->w = out->h = side;
    out->z = malloc(sizeof *out->z * (size_t)side * (size_t)side);
    if (!out->z) return -1;
    for (y = 0; y < side; y++)
        memcpy(out->z + (size_t)y * side, full->z + (size_t)(y0 + y) * full->w + x0, sizeof *out->z * (size_t)side);
    if (out->geo.kind != HF_GEO_NONE) {
        out->geo.x0 += (int64_t)x0 * out->geo.sx;
        out->geo.y0 -= (int64_t)y0 * out->geo.sy;
    }
    return 0;
}

/* The scene over the crop as scene_open sets up a file (default ramp over its heights,
 * sun 315 / 45 degrees, ambient 0.3, vertical scale 1), and what the board needs of it. */
static int scene_of(scene *s, const hf *f, bake_info *b)
{
    br_err err;
    memset(s, 0, sizeof *s);
    s->f = *f;
    if (scene_setup(s, NULL, "crop", &err) != BR_OK) return -1;
    b->ramp_zmin_mm = hf_z_to_mm(&s->f, s->st.zmin);
    b->ramp_zmax_mm = hf_z_to_mm(&s->f, s->st.zmax);
    b->sun_az_mdeg = 315000;
    b->sun_alt_mdeg = 45000;
    b->ambient_q14 = (int32_t)lround(0.3 * FX_Q14_ONE);
    return 0;
}

typedef struct sum_sink {
    uint32_t sum;
    int dc;
    uint8_t row[2 * FB_W];
} sum_sink;

static void sum_put(void *user, int dc, const uint8_t *p, size_t n)
{
    sum_sink *k = (sum_sink *)user;
    k->sum = spib_sum(k->sum, &k->dc, dc, p, n);
}

static br_status sum_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    spib_band(sum_put, user, FB_W, y0, rows, px, stride, ((sum_sink *)user)->row);
    return BR_OK;
}

/* The frames through scene_frame (its own tree and meshes: the hysteresis state runs
 * through the path as on the board), their stream checksums into b->scene_sum. */
static int scene_sums(scene *s, const cam *cams, bake_info *b, br_err *err)
{
    static uint8_t band[FB_W * 16 * 4 + 64];
    int i;
    if (scene_tree(s, err) != BR_OK || scene_reserve(s, 65536, err) != BR_OK) return -1;
    for (i = 0; i < b->nframes; i++) {
        bt_params bp;
        rs_frame fr;
        rs_prim prim;
        rs_pipe pipe;
        rs_pass terrain;
        sum_sink k;
        memset(&bp, 0, sizeof bp);
        bp.pixel_err_q8 = b->pixel_err_q8; bp.hyst_q8 = b->hyst_q8; bp.morph_q8 = b->morph_q8;
        memset(&fr, 0, sizeof fr);
        fr.fmt = RS_FMT_RGB565; fr.depth = RS_DEPTH16; fr.clear_rgb = b->clear_rgb;
        memset(&pipe, 0, sizeof pipe);
        pipe.w = FB_W; pipe.h = FB_H; pipe.fmt = RS_FMT_RGB565; pipe.depth = RS_DEPTH16;
        k.sum = SPIB_SUM_INIT; k.dc = -1;
        if (scene_frame(s, &cams[i], &bp, &fr, &prim) != BR_OK || rs_pass_terrain(&terrain, &fr) != BR_OK
            || rs_pipe_add(&pipe, &terrain) != BR_OK || rs_pipe_mem_size(&pipe, 16) > sizeof band
            || rs_pipe_run(&pipe, 16, band, sizeof band, sum_band, &k, NULL) != BR_OK) {
            br_err_set(err, BR_E_VALUE, NULL, "frame %d: the scene's frame path failed", i);
            return -1;
        }
        b->scene_sum[i] = k.sum;
    }
    return 0;
}

/* The frames through the stream path (the baked tree t, the scene's shading), their
 * stream checksums into b->stream_sum. */
static int stream_sums(scene *s, bt_tree *t, const cam *cams, bake_info *b, br_err *err)
{
    static uint8_t band[FB_W * BAKE_STREAM_ROWS * 4 + 64];
    static uint64_t wmem[16384], bmem[8192];
    bt_stream *walk;
    rt_stream rs;
    int i;
    memset(&rs, 0, sizeof rs);
    if (bt_stream_mem_size(512, t->nslot) > sizeof wmem || bt_stream_init(&walk, 512, t->nslot, wmem, sizeof wmem) != BR_OK
        || bt_stream_order(walk, BT_STREAM_BACK_TO_FRONT) != BR_OK
        || rt_stream_mem_size(64, 96) > sizeof bmem || rt_stream_init(&rs, 64, 96, bmem, sizeof bmem) != BR_OK) {
        br_err_set(err, BR_E_VALUE, NULL, "the stream path's memory");
        return -1;
    }
    rs.scene = &s->rt;
    rs.walk = walk;
    for (i = 0; i < b->nframes; i++) {
        bt_params bp;
        rs_pipe pipe;
        sum_sink k;
        memset(&bp, 0, sizeof bp);
        bp.mode = BT_VIEW; bp.c = &cams[i]; bp.fr = s->rt.fr;
        bp.pixel_err_q8 = b->pixel_err_q8; bp.morph_q8 = b->morph_q8;
        k.sum = SPIB_SUM_INIT; k.dc = -1;
        if (bt_stream_frame(walk, t, &bp) != BR_OK
            || rt_stream_pipe(&rs, &cams[i], RS_FMT_RGB565, RS_DEPTH_NONE, b->clear_rgb, &pipe) != BR_OK
            || rs_pipe_mem_size(&pipe, BAKE_STREAM_ROWS) > sizeof band
            || rs_pipe_run(&pipe, BAKE_STREAM_ROWS, band, sizeof band, sum_band, &k, NULL) != BR_OK) {
            br_err_set(err, BR_E_VALUE, NULL, "frame %d: the stream path failed", i);
            return -1;
        }
        b->stream_sum[i] = k.sum;
    }
    return 0;
}

static int cameras(const scene *s, const char *path, bake_info *b, cam *cams, br_err *err)
{
    campath cp = { NULL, 0 };
    int i, j;
    double scale = ldexp(1.0, s->rt.shift);
    if (campath_read(path, &cp, err) != BR_OK) return -1;
    b->nframes = cp.n < BAKE_MAX_FRAMES ? cp.n : BAKE_MAX_FRAMES;
    for (i = 0; i < b->nframes; i++) {
        cam c;
        if (scene_camera(s, cp.cam[i], cp.cam[i] + 3, FOVY, FB_W, FB_H, &c) != BR_OK) {
            br_err_set(err, BR_E_VALUE, path, "line %d: the camera does not fit the scene", i + 1);
            campath_free(&cp);
            return -1;
        }
        for (j = 0; j < 3; j++) {   /* scene_camera's own rounding of eye and target */
            b->cam[i].eye[j] = c.eye[j];
            b->cam[i].tgt[j] = (int32_t)lround(cp.cam[i][3 + j] * scale);
        }
        b->cam[i].znear = c.znear;
        b->cam[i].zfar = c.zfar;
        cams[i] = c;
    }
    campath_free(&cp);
    return 0;
}

static void put_i32(FILE *o, const char *decl, const int32_t *v, size_t n)
{
    size_t i;
    fprintf(o, "%s[%zu] = {\n", decl, n);
    for (i = 0; i < n; i++) fprintf(o, "%ld,%s", (long)v[i], i % 16 == 15 ? "\n" : "");
    fprintf(o, "\n};\n");
}

static void put_u32(FILE *o, const char *decl, const uint32_t *v, size_t n)
{
    size_t i;
    fprintf(o, "%s[%zu] = {\n", decl, n);
    for (i = 0; i < n; i++) fprintf(o, "0x%lxu,%s", (unsigned long)v[i], i % 12 == 11 ? "\n" : "");
    fprintf(o, "\n};\n");
}

static void put_u16(FILE *o, const char *decl, const uint16_t *v, size_t n)
{
    size_t i;
    fprintf(o, "%s[%zu] = {\n", decl, n);
    for (i = 0; i < n; i++) fprintf(o, "0x%xu,%s", (unsigned)v[i], i % 16 == 15 ? "\n" : "");
    fprintf(o, "\n};\n");
}

static int write_c(const char *out, const char *src, const hf *f, const uint32_t *blob, size_t blob_bytes,
                   const uint16_t *lvl, const uint32_t *ztab,
                   const bake_info *b)
{
    FILE *o = fopen(out, "w");
    int i;
    if (!o) return -1;
    fprintf(o, "/* generated by mcu/bake.c from %s: do not edit */\n#include \"mcu/bake.h\"\n\n", src);
    put_i32(o, "const int32_t bake_z", f->z, (size_t)f->w * f->h);
    put_u32(o, "const uint32_t bake_tree", blob, blob_bytes / 4);
    fprintf(o, "const uint32_t bake_tree_bytes = %luu;\n", (unsigned long)blob_bytes);
    put_u16(o, "const uint16_t bake_lvl", lvl, (size_t)f->w * f->h);
    put_u32(o, "const uint32_t bake_ztab", ztab, (size_t)b->nz);
    fprintf(o, "const bake_info bake = {\n  %ld, %ld, %ld, %ld, %lldLL, %lldLL,\n  %ld, %lldLL, %lldLL, %lldLL, %lldLL,\n",
            (long)b->w, (long)b->h, (long)b->z_num, (long)b->z_den, (long long)b->dx_um, (long long)b->dy_um,
            (long)b->geo_kind, (long long)b->geo_x0, (long long)b->geo_y0, (long long)b->geo_sx, (long long)b->geo_sy);
    fprintf(o, "  %ld, %ld, %ld, %ld, %ld, %lldLL, %luu, %ld,\n  %lldLL, %lldLL, %ld, %ld, %ld,\n",
            (long)b->n, (long)b->k, (long)b->metric, (long)b->zmin, (long)b->zmax, (long long)b->nvalid,
            (unsigned long)b->nslot, (long)b->nz,
            (long long)b->ramp_zmin_mm, (long long)b->ramp_zmax_mm, (long)b->sun_az_mdeg, (long)b->sun_alt_mdeg,
            (long)b->ambient_q14);
    fprintf(o, "  %ld, %ld, %ld, %ld, %ld, %ld, 0x%lxu, %ld,\n  {\n", (long)b->fb_w, (long)b->fb_h,
            (long)b->fovy_mdeg, (long)b->pixel_err_q8, (long)b->hyst_q8, (long)b->morph_q8,
            (unsigned long)b->clear_rgb, (long)b->nframes);
    for (i = 0; i < b->nframes; i++)
        fprintf(o, "    { { %ld, %ld, %ld }, { %ld, %ld, %ld }, %ld, %ld },\n", (long)b->cam[i].eye[0],
                (long)b->cam[i].eye[1], (long)b->cam[i].eye[2], (long)b->cam[i].tgt[0], (long)b->cam[i].tgt[1],
                (long)b->cam[i].tgt[2], (long)b->cam[i].znear, (long)b->cam[i].zfar);
    fprintf(o, "  },\n  {");
    for (i = 0; i < b->nframes; i++) fprintf(o, " 0x%08lxu,", (unsigned long)b->scene_sum[i]);
    fprintf(o, " },\n  {");
    for (i = 0; i < b->nframes; i++) fprintf(o, " 0x%08lxu,", (unsigned long)b->stream_sum[i]);
    fprintf(o, " }\n};\n");
    return fclose(o) == 0 ? 0 : -1;
}

int main(int argc, char **argv)
{
    hf full, f;
    scene s;
    bt_tree t;
    bake_info b;
    cam cams[BAKE_MAX_FRAMES];
    br_err err;
    void *tmem, *scratch;
    void *cache, *blob;
    const uint16_t *lvl;
    const uint32_t *ztab;
    size_t cache_bytes, blob_bytes;
    long x0, y0, side, perr = 256;
    int32_t x, y;
    if (argc < 7 || argc > 8) {
        fprintf(stderr, "usage: bake DEM X0 Y0 SIDE PATH.cam OUT.c [PIXEL_ERROR_Q8]\n");
        return 2;
    }
    x0 = strtol(argv[2], NULL, 10); y0 = strtol(argv[3], NULL, 10); side = strtol(argv[4], NULL, 10);
    if (argc == 8) perr = strtol(argv[7], NULL, 10);
    if (perr < 1 || perr > 65536) return fail("PIXEL_ERROR_Q8 must be 1 .. 65536", NULL);
    if (dem_load(argv[1], NULL, &full, &err) != BR_OK) return fail("cannot load the DEM", &err);
    if (side < 3 || x0 < 0 || y0 < 0 || x0 + side > full.w || y0 + side > full.h) {
        fprintf(stderr, "bake: %s: crop %ld,%ld side %ld is outside the %dx%d grid\n", argv[1], x0, y0, side,
                (int)full.w, (int)full.h);
        return 1;
    }
    if (crop(&full, (int32_t)x0, (int32_t)y0, (int32_t)side, &f) != 0) return fail("out of memory", NULL);
    dem_free(&full);
    memset(&b, 0, sizeof b);
    if (scene_of(&s, &f, &b) != 0) return fail("the crop is not a valid heightfield", NULL);
    tmem = malloc(bt_mem_size(f.w, f.h));
    scratch = malloc(bt_scratch_size(f.w, f.h));
    cache_bytes = rt_cache_mem_size(&s.rt);
    cache = cache_bytes ? malloc(cache_bytes) : NULL;
    if (!tmem || !scratch || !cache) return fail("out of memory", NULL);
    if (bt_build(&t, &s.f, BT_METRIC_EXACT, tmem, bt_mem_size(f.w, f.h), scratch, bt_scratch_size(f.w, f.h)) != BR_OK)
        return fail("cannot build the bitree", NULL);
    free(scratch);
    blob_bytes = bt_tree_blob_size(&t);
    blob = malloc(blob_bytes);
    if (!blob || bt_tree_save(&t, blob, blob_bytes) != BR_OK || blob_bytes % 4 != 0)
        return fail("cannot save the bitree", NULL);
    /* the shading cache filled for every valid sample, so the board only reads it */
    if (rt_scene_cache(&s.rt, cache, cache_bytes) != BR_OK || s.rt.nz == 0) return fail("shading cache", NULL);
    for (y = 0; y < f.h; y++)
        for (x = 0; x < f.w; x++) {
            int32_t z = f.z[(size_t)y * f.w + x];
            rs_vertex v;
            if (z != HF_NODATA) rt_vertex(&s.rt, x, y, z, &v);
        }
    lvl = s.rt.lvl;         /* kept: scene_sums attaches the scene's own cache */
    ztab = s.rt.ztab;
    b.w = f.w; b.h = f.h; b.z_num = f.z_num; b.z_den = f.z_den; b.dx_um = f.dx_um; b.dy_um = f.dy_um;
    b.geo_kind = f.geo.kind; b.geo_x0 = f.geo.x0; b.geo_y0 = f.geo.y0; b.geo_sx = f.geo.sx; b.geo_sy = f.geo.sy;
    b.n = t.n; b.k = t.k; b.metric = t.metric; b.zmin = t.zmin; b.zmax = t.zmax; b.nvalid = t.nvalid;
    b.nslot = t.nslot; b.nz = s.rt.nz;
    b.fb_w = FB_W; b.fb_h = FB_H; b.fovy_mdeg = FOVY * 1000;
    b.pixel_err_q8 = (int32_t)perr; b.hyst_q8 = 64; b.morph_q8 = 128;
    b.clear_rgb = 0x99ccffu;
    if (cameras(&s, argv[5], &b, cams, &err) != 0) return fail("camera path", &err);
    if (stream_sums(&s, &t, cams, &b, &err) != 0) return fail("the stream path's frames", &err);
    if (scene_sums(&s, cams, &b, &err) != 0) return fail("the scene's frames", &err);
    if (write_c(argv[6], argv[1], &f, (const uint32_t *)blob, blob_bytes, lvl, ztab, &b) != 0) {
        fprintf(stderr, "bake: %s: cannot write\n", argv[6]);
        return 1;
    }
    printf("bake: %s crop %ld,%ld %ldx%ld (%ld..%ld m), hierarchy %dx%d, %d frames -> %s\n", argv[1], x0, y0, side,
           side, (long)(b.ramp_zmin_mm / 1000), (long)(b.ramp_zmax_mm / 1000), (int)t.n, (int)t.n, (int)b.nframes,
           argv[6]);
    free(tmem); free(blob);
    scene_close(&s);        /* frees the crop's heights too (s.f holds them) */
    free(cache);
    return 0;
}
