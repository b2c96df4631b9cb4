#define _POSIX_C_SOURCE 200809L   /* clock_gettime under -std=c99 (builds without SDL flags: the cross suite) */
/* platform/cmd_render.c — bitrain render: one frame of a DEM, headless, to PNG.
 *
 *   bitrain render IN... -o out.png [--size WxH] [--camera EX,EY,EZ,TX,TY,TZ] [--fov DEG]
 *          [--max-error M | --pixel-error P | --full [STEP]] [--bands ROWS]
 *          [--format rgb565|rgb888] [--depth 32|16] [--colors FILE] [--texture PNG] [--no-cull]
 *          [--sun AZ,ALT] [--ambient A] [--zscale F] [--output-format png|rgb565]
 *          [--path FILE -o frame%04d.png]
 * Camera in the heightfield's metres: x east from the west edge, y north from the
 * south edge, z height above 0 m (times --zscale).  Default camera: from the south-west, above the
 * terrain, looking at its centre.  Mesh: the bitree (core/bitree.h), by default
 * view-dependent with a 1 pixel screen-space error; --max-error M selects the
 * fidelity mode (true vertical error <= M metres); --full [STEP] draws the full grid
 * (every STEP-th sample) as row strips instead.  Colours: a gdaldem color-relief file
 * (--colors) or the built-in ramp, lit by a sun (azimuth 315, altitude 45 by default)
 * with 30 % ambient.  --zscale F multiplies heights (default 1; grids without
 * georeference whose relief exceeds half their extent get an automatic scale, since
 * the loader can only assume 1 m spacing for them).  The frame is rendered in bands of ROWS rows (default: whole
 * frame) by the frame driver (raster/frame.h: scene_terrain's terrain pass) and streamed
 * band by band to the PNG sink (platform/sink_png.c) or, with --output-format rgb565, to
 * the raw big-endian RGB565 sink of SPI displays (platform/sink_rgb565.c; -o - is
 * standard output).  --texture PNG stretches a colour map or
 * orthophoto over the whole grid (perspective-correct, nearest texel), lit by the sun.
 * --path FILE flies a camera path (platform/campath.h): frame k (1 for the path's first
 * camera) goes to -o's pattern with k for its %d, each frame exactly `render --camera` with
 * that line: the mesh is selected afresh for every camera (no hysteresis, no geomorph),
 * reusing the tree, and the mesh memory holds the path's largest mesh. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "platform/clock.h"
#include "core/bitree.h"
#include "core/cam.h"
#include "platform/campath.h"
#include "platform/render_spi.h"
#include "platform/cmd.h"
#include "platform/dem_args.h"
#include "platform/geocam.h"
#include "platform/pipe_threads.h"
#include "platform/opt.h"
#include "platform/scene_args.h"
#include "platform/load.h"
#include "platform/scene.h"
#include "platform/sink_png.h"
#include "platform/sink_rgb565.h"
#include "raster/frame.h"
#include "raster/raster.h"
#include "raster/ramp.h"
#include "raster/terrain.h"
#include "platform/water_scene.h"

/* ---------------------------------------------------------------- command */

#define RENDER_SYNOPSIS "IN... -o OUT.png [options]\n" \
    "  camera in metres: x east from the west edge, y north from the south edge, z height (times --zscale)"

/* The frame's sink: the PNG or the raw RGB565 stream. */
typedef struct render_out {
    int raw;
    sink_png png;
    sink_rgb565 rgb565;
} render_out;

static br_status out_open(render_out *o, const char *path, int32_t w, int32_t h, int32_t fmt, br_err *err)
{
    return o->raw ? sink_rgb565_open(&o->rgb565, path, w, fmt, err) : sink_png_open(&o->png, path, w, h, fmt, err);
}

static br_status out_close(render_out *o, br_err *err)
{
    return o->raw ? sink_rgb565_close(&o->rgb565, err) : sink_png_close(&o->png, err);
}

static void out_abort(render_out *o)
{
    if (o->raw) sink_rgb565_close(&o->rgb565, NULL);
    else sink_png_abort(&o->png);
}

static void mesh_params(const scene *s, const cam *c, int mode, double max_err, double pix_err, bt_params *bp)
{
    memset(bp, 0, sizeof *bp);
    bp->mode = mode;
    bp->max_err = bt_mm_to_units(&s->f, (int64_t)llround(max_err * 1000));
    bp->c = c;
    bp->fr = s->rt.fr;
    bp->pixel_err_q8 = (int32_t)lround(pix_err * 256);
}

/* The scene's terrain mesh: the bitree's (view-dependent or fidelity) or the full grid.
 * The tree is built and the mesh memory reserved on the first call (at least min_tri
 * triangles: a camera path's largest mesh); later calls reuse them. */
static br_status make_mesh(scene *s, const cam *c, int full_step, int mode, double max_err, double pix_err,
                           uint64_t min_tri, br_err *err)
{
    bt_params bp;
    uint64_t ntri = 0;
    if (full_step > 0) return scene_grid(s, full_step, err);
    mesh_params(s, c, mode, max_err, pix_err, &bp);
    if (!s->tree_mem && scene_tree(s, err) != BR_OK) return err->code;
    if (!s->mesh_mem) {
        if (bt_count(&s->tree, &bp, &ntri) != BR_OK) return br_err_set(err, BR_E_ARG, NULL, "bad mesh parameters");
        if (ntri < min_tri) ntri = min_tri;
        if (scene_reserve(s, (uint32_t)(ntri + 16 > 16000000 ? 16000000 : ntri + 16), err) != BR_OK) return err->code;
    }
    if (scene_mesh(s, c, &bp) != BR_OK) return br_err_set(err, BR_E_ARG, NULL, "cannot extract the mesh");
    return BR_OK;
}

/* The largest mesh along a camera path (builds the tree). */
static br_status path_max_tri(scene *s, const campath *cp, int w, int h, double fov, int mode, double max_err,
                              double pix_err, uint64_t *max_tri, br_err *err)
{
    int k;
    *max_tri = 0;
    if (!s->tree_mem && scene_tree(s, err) != BR_OK) return err->code;
    for (k = 0; k < cp->n; k++) {
        cam c;
        bt_params bp;
        uint64_t n = 0;
        if (scene_camera(s, cp->cam[k], cp->cam[k] + 3, fov, w, h, &c) != BR_OK) continue;   /* said when drawn */
        mesh_params(s, &c, mode, max_err, pix_err, &bp);
        if (bt_count(&s->tree, &bp, &n) != BR_OK) return br_err_set(err, BR_E_ARG, NULL, "bad mesh parameters");
        if (n > *max_tri) *max_tri = n;
    }
    return BR_OK;
}

/* 1 when pattern holds exactly one conversion %d (flags 0, a width) and otherwise only %%. */
static int frame_pattern_ok(const char *p)
{
    int n = 0;
    for (; *p; p++) {
        if (*p != '%') continue;
        if (p[1] == '%') { p++; continue; }
        p++;
        if (*p == '0') p++;
        while (isdigit((unsigned char)*p)) p++;
        if (*p != 'd') return 0;
        n++;
    }
    return n == 1;
}

/* What every frame of a render shares: the scene, its water, the threads, the outputs. */
typedef struct render_job {
    scene s;
    water_scene ws;
    int use_pipe;                   /* water or fog: the water scene's pipe */
    pt_pool *pool;
    render_spi spi;
    render_out ro;
    int w, h, fmt, depth, no_cull, bands, threads, full_step, mode;
    double fov, max_err, pix_err;
    uint64_t min_tri;
} render_job;

/* One frame seen from cv (eye, target) to the panel and/or the file name. */
static int render_frame(render_job *j, const double *cv, const char *name, const char *what, double t0, br_err *err)
{
    cam c;
    rs_frame fr;
    rs_pipe pipe, *run = &pipe;
    rs_pass terrain;
    rs_band_stats total;
    size_t memsize;
    double t1, t2;
    if (scene_camera(&j->s, cv, cv + 3, j->fov, j->w, j->h, &c) != BR_OK) {
        fprintf(stderr, "bitrain render: %sunusable camera (eye equals target, or too far from the terrain: "
                "world unit 2^%d m)\n", what, -j->s.rt.shift);
        return 0;
    }
    if (!j->pool && pt_open(&j->pool, j->threads) != BR_OK) {
        fprintf(stderr, "bitrain render: cannot start %d threads\n", j->threads);
        return 0;
    }
    j->s.pool = j->pool;     /* the view extraction's parts too */
    if (make_mesh(&j->s, &c, j->full_step, j->mode, j->max_err, j->pix_err, j->min_tri, err) != BR_OK) {
        fprintf(stderr, "bitrain: %s\n", err->msg);
        return 0;
    }
    t1 = br_now_ms();
    /* the terrain pass, and water and atmosphere's passes and post hook (platform/water_scene.h),
     * in bands through the frame driver to the sinks */
    memset(&fr, 0, sizeof fr);
    memset(&pipe, 0, sizeof pipe);
    fr.fmt = j->fmt; fr.depth = j->depth; fr.no_cull = j->no_cull;
    fr.clear_rgb = 0x99ccffu;
    fr.one_band = j->bands == j->h;
    if (scene_terrain(&j->s, &c, &fr, &terrain) != BR_OK) { fprintf(stderr, "bitrain: bad frame parameters\n"); return 0; }
    pipe.w = j->w; pipe.h = j->h; pipe.fmt = fr.fmt; pipe.depth = fr.depth;
    if (rs_pipe_add(&pipe, &terrain) != BR_OK) return 0;
    if (j->use_pipe) {
        if (ws_frame(&j->ws, &j->s, &c, &fr, err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err->msg); return 0; }
        run = &j->ws.pipe;
    }
    memsize = rs_pipe_mem_size(run, j->bands);
    if (render_spi_on(&j->spi)) {        /* the panel, band by band */
        br_status st;
        if (render_spi_open(&j->spi, j->w, j->h, j->fmt, err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err->msg); return 0; }
        st = pt_run(j->pool, run, j->bands, spi_sink_band, &j->spi.ss, &total);
        if (render_spi_close(&j->spi, st == BR_OK ? err : NULL) != BR_OK || st != BR_OK) {
            fprintf(stderr, "bitrain: %s\n", err->msg[0] ? err->msg : "render failed");
            return 0;
        }
    }
    if (name) {
        render_out *ro = &j->ro;
        if (out_open(ro, name, j->w, j->h, j->fmt, err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err->msg); return 0; }
        if (pt_run(j->pool, run, j->bands, ro->raw ? sink_rgb565_band : sink_png_band,
                   ro->raw ? (void *)&ro->rgb565 : (void *)&ro->png, &total) != BR_OK) {
            out_abort(ro);
            fprintf(stderr, "bitrain: %s\n", err->msg[0] ? err->msg : "render failed");
            return 0;
        }
        if (out_close(ro, err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err->msg); return 0; }
    }
    t2 = br_now_ms();
    fprintf(name && !strcmp(name, "-") ? stderr : stdout,
            "%s: %dx%d, %u vertices, %s, %u triangles drawn (%u clipped), load+mesh %.1f ms, "
            "render+write %.1f ms, world unit 2^%d m, band %d rows (%zu bytes + %zu bytes vertex cache), %d threads\n",
            name ? name : (j->spi.capture ? j->spi.capture : j->spi.dev), j->w, j->h, fr.nv,
            j->full_step ? "full grid" : (j->mode == BT_FIDELITY ? "bitree fidelity" : "bitree view"),
            total.tris, total.clipped, t1 - t0, t2 - t1, -j->s.rt.shift, j->bands, memsize, rs_cache_mem_size(fr.nv),
            j->threads);
    return 1;
}

int cmd_render(int argc, char **argv)
{
    const char *in[64], *out = NULL, *path = NULL;
    int nin = 0, size[2] = { 800, 600 }, have_cam = 0, have_max = 0, have_pix = 0, have_fmt = 0, have_bands = 0;
    int depth_choice = 0, r, k, nframes = 1, rc = 1;
    campath cp = { NULL, 0 };
    geocam_args ga;
    dem_args da;
    scene_args sa;
    ws_args wa;
    ws_opts wo;
    scene_opts so;
    double camv[6], t0;
    br_err err;
    opt_spec dem_t[DEM_ARGS_N], look_t[SCENE_ARGS_N], geo_t[GEOCAM_ARGS_N], water_t[WS_ARGS_N], spi_t[RENDER_SPI_N];
    static render_job job;          /* the scene and its buffers: large, one per process */
    render_job *j = &job;
    const opt_spec own[] = {
        { "-o", OPT_STR, &out, 0, 0, 0, NULL, "OUT.png", "the image to write (-: standard output)", NULL },
        { "--size", OPT_SIZE, size, 1, RS_MAX_DIM, 0, NULL, "WxH", "image size (default 800x600)", NULL },
        { "--camera", OPT_NUMS, camv, -CAMPATH_COORD_MAX, CAMPATH_COORD_MAX, 6, NULL, "EX,EY,EZ,TX,TY,TZ",
          "eye and target, metres", &have_cam },
        { "--fov", OPT_NUM, &j->fov, 1, 170, 0, NULL, "DEG", "vertical field of view (default 50)", NULL },
        { "--max-error", OPT_NUM, &j->max_err, 0, 100000, 0, NULL, "M",
          "fidelity mesh: true vertical error at most M metres", &have_max },
        { "--pixel-error", OPT_NUM, &j->pix_err, 0.01, 1000, 0, NULL, "P",
          "view-dependent mesh: screen error at most P pixels (default 1)", &have_pix },
        { "--full", OPT_INT_OPT, &j->full_step, 1, 4096, 0, NULL, "[STEP]", "the full grid (every STEP-th sample)", NULL },
        { "--bands", OPT_INT, &j->bands, 0, RS_MAX_DIM, 0, NULL, "ROWS", "render in bands of ROWS rows (0: whole frame)",
          &have_bands },
        { "--format", OPT_CHOICE, &j->fmt, 0, 0, 0, "rgb888|rgb565", "F", "pixel format of the frame", &have_fmt },
        { "--depth", OPT_CHOICE, &depth_choice, 0, 0, 0, "32|16", "BITS", "depth buffer bits", NULL },
        { "--no-cull", OPT_FLAG, &j->no_cull, 0, 0, 0, NULL, NULL, "draw back faces too", NULL },
        { "--output-format", OPT_CHOICE, &j->ro.raw, 0, 0, 0, "png|rgb565", "F",
          "png, or rgb565: raw big-endian RGB565 rows as an SPI display takes them", NULL },
        { "--path", OPT_STR, &path, 0, 0, 0, NULL, "FILE",
          "a camera path (one --camera line a frame, assets/*.cam): one image a line, -o a pattern such as frame%04d.png "
          "(%d: 1 for the first line)", NULL },
        { "--threads", OPT_INT, &j->threads, 1, PT_MAX_THREADS, 0, NULL, "N",
          "drawing threads (default: online cores; bands of 64 rows unless --bands)", NULL },
        OPT_END
    };
    const opt_spec *const tables[] = { own, look_t, water_t, spi_t, geo_t, dem_t, NULL };

    memset(j, 0, sizeof *j);
    memset(&so, 0, sizeof so);
    memset(&wo, 0, sizeof wo);
    memset(&err, 0, sizeof err);
    j->fov = 50; j->pix_err = 1; j->threads = pt_online_cores();
    dem_args_table(&da, &so.dem, dem_t);
    scene_args_table(&sa, &so, look_t);
    geocam_args_table(&ga, geo_t);
    ws_args_table(&wa, &wo, water_t);
    render_spi_table(&j->spi, spi_t);
    r = opt_parse("render", RENDER_SYNOPSIS, tables, argc, argv, in, 64, &nin);
    if (r != OPT_OK) return r == OPT_HELP ? 0 : 2;
    if (dem_args_finish(&da, "render") != OPT_OK || scene_args_finish(&sa, "render") != OPT_OK
        || ws_args_finish(&wa, "render") != OPT_OK) return 2;
    if (!nin) { fprintf(stderr, "bitrain render: no input file (`bitrain render --help`)\n"); return 2; }
    if (!out && !render_spi_on(&j->spi)) { fprintf(stderr, "bitrain render: no output: -o OUT.png or --spi DEV\n"); return 2; }
    if (have_max && have_pix) return opt_fail("render", "--max-error", "cannot be used with --pixel-error");
    if (j->full_step && (have_max || have_pix))
        return opt_fail("render", "--full", "cannot be used with --max-error or --pixel-error");
    if (have_cam && (ga.from_seen || ga.at_seen)) return opt_fail("render", "--camera", "cannot be used with --look-from/--look-at");
    if (path && (have_cam || ga.from_seen || ga.at_seen))
        return opt_fail("render", "--path", "cannot be used with --camera or --look-from/--look-at");
    if (path && (!out || !frame_pattern_ok(out)))
        return opt_fail("render", "-o", "with --path, the name needs one %%d for the frame number (frame%%04d.png)");
    j->mode = have_max ? BT_FIDELITY : BT_VIEW;
    j->w = size[0];
    j->h = size[1];
    j->depth = depth_choice ? RS_DEPTH16 : RS_DEPTH32;
    if (render_spi_on(&j->spi)) {        /* a panel: its format, and a small band in RAM */
        if (!have_fmt) j->fmt = RS_FMT_RGB565;
        if (!have_bands) j->bands = 16;
    }
    if (j->bands == 0) j->bands = j->threads > 1 ? 64 : j->h;
    if (j->bands > j->h) j->bands = j->h;
    if (out && !strcmp(out, "-")) so.quiet = wo.quiet = 1;   /* stdout carries the image only */

    if (path && campath_read(path, &cp, &err) != BR_OK) { fprintf(stderr, "bitrain render: %s\n", err.msg); return 1; }
    if (cp.n) nframes = cp.n;
    t0 = br_now_ms();
    j->use_pipe = !(wo.no_water && wo.no_fog);
    so.ramp_abs = j->use_pipe;
    if (scene_open(&j->s, in, nin, &so, &err) != BR_OK) {
        fprintf(stderr, "bitrain: %s\n", err.msg);
        campath_free(&cp);
        return 1;
    }
    wo.shore_bound = 1;       /* the mesh's error bound spares the shore test on land */
    wo.shore_px = j->full_step > 0 || j->mode == BT_FIDELITY ? 0 : j->pix_err;
    wo.shore_m = j->full_step > 0 || j->mode != BT_FIDELITY ? 0 : j->max_err;
    wo.view_px = wo.shore_px;  /* the reflection's own selection: view meshes only */
    if (j->use_pipe && ws_open(&j->ws, &j->s, &wo, &err) != BR_OK) {
        fprintf(stderr, "bitrain: %s\n", err.msg);
        j->use_pipe = 0;
        goto done;
    }
    r = geocam_resolve(&ga, &j->s, "render", camv);
    if (r < 0) { rc = 2; goto done; }
    if (r) have_cam = 1;
    if (!have_cam) scene_default_view(&j->s, j->fov, camv, camv + 3);
    if (cp.n && !j->full_step
        && path_max_tri(&j->s, &cp, j->w, j->h, j->fov, j->mode, j->max_err, j->pix_err, &j->min_tri, &err) != BR_OK) {
        fprintf(stderr, "bitrain: %s: %s\n", in[0], err.msg);
        goto done;
    }
    for (k = 0; k < nframes; k++) {   /* one frame, or one a line of the path */
        char name[4096], what[64] = "";
        if (cp.n) {
            snprintf(name, sizeof name, out, k + 1);
            snprintf(what, sizeof what, "camera %d of the path: ", k + 1);
        } else if (out) snprintf(name, sizeof name, "%s", out);
        if (k) t0 = br_now_ms();
        if (!render_frame(j, cp.n ? cp.cam[k] : camv, out ? name : NULL, what, t0, &err)) goto done;
    }
    rc = 0;
done:
    j->s.pool = NULL;
    pt_close(j->pool);
    if (j->use_pipe) ws_close(&j->ws);
    scene_close(&j->s);
    campath_free(&cp);
    return rc;
}
