#define _POSIX_C_SOURCE 200809L   /* clock_gettime under -std=c99 */
/* platform/bench_default.c — bitrain bench --scene default: the frame users see, the
 * viewer's terrain frame on the bundled default scene (assets/N47E009.hgt.gz, its
 * default camera or a camera path), nothing else.
 *
 *   bitrain bench --scene default [--path FILE] [--size WxH] [--frames N] [--warmup W]
 *                 [--pixel-error P] [--format rgb888|rgb565] [--depth 32|16]
 *                 [--bands ROWS] [--dem FILE...] [-o last.png]
 *
 * A frame is what `bitrain view` does per frame, with water and fog off: the bitree's
 * view-dependent selection and strip (hysteresis 1/4 of the threshold, geomorph 1/2,
 * as the viewer), the raster vertices, the transform and the rasteriser band by band
 * (64-row bands as the viewer, or --bands).  It runs inside bench_default_frame, so
 *   valgrind --tool=callgrind --toggle-collect=bench_default_frame bitrain bench --scene default ...
 * counts only the timed frames (divide by N); bd_select (selection, strip, vertices)
 * and bd_raster (transform and rasteriser) split it.  With --path, frame i flies line
 * i of the file (wrapping); W untimed warm-up frames fly the path's first W lines
 * (default 0: the first timed frame selects from scratch, as after a jump). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "platform/clock.h"
#include "platform/bench_default.h"
#include "platform/bench_vis.h"
#include "platform/assets.h"
#include "platform/campath.h"
#include "platform/opt.h"
#include "platform/cmd.h"
#include "platform/png_io.h"
#include "platform/scene.h"
#include "platform/sink_frame.h"
#include "platform/water_scene.h"

#define BD_FOV 60
#define BD_MAX_TRI 2000000

struct bd_run {
    scene s;
    int w, h, fmt, depth, bands;
    double pix_err;
    uint8_t *color;
    rs_prim prim;
    rs_frame fr;
    int water;               /* --with-water: water, sky and fog as render and view draw them */
    water_scene ws;
    rs_pipe pipe;            /* the terrain pass alone (no water) */
    void *band_mem;
    size_t band_mem_size;
    uint64_t tris;
    double t_mid;            /* wall clock between selection and rasteriser, ms */
};

/* Selection, strip and raster vertices (scene_frame), as the viewer's frame. */
__attribute__((noinline)) br_status bd_select(bd_run *r, const cam *c)
{
    bt_params bp;
    memset(&bp, 0, sizeof bp);
    memset(&r->fr, 0, sizeof r->fr);
    bp.pixel_err_q8 = (int32_t)(r->pix_err * 256 + 0.5);
    bp.hyst_q8 = 64;
    bp.morph_q8 = 128;
    r->fr.fmt = r->fmt;
    r->fr.depth = r->depth;
    r->fr.clear_rgb = 0x99ccffu;
    return scene_frame(&r->s, c, &bp, &r->fr, &r->prim);
}

/* The frame driver over the prepared frame, band by band: the terrain pass, or with
 * --with-water the water scene's passes and post hook (ws_frame, then its pipe). */
__attribute__((noinline)) br_status bd_raster(bd_run *r, const cam *c);
__attribute__((noinline)) br_status bd_raster(bd_run *r, const cam *c)
{
    const rs_pipe *p = &r->pipe;
    size_t need;
    if (r->water) {
        br_err err;
        if (ws_frame(&r->ws, &r->s, c, &r->fr, &err) != BR_OK) return err.code;
        p = &r->ws.pipe;
    } else {
        rs_pass terrain;
        memset(&r->pipe, 0, sizeof r->pipe);
        r->pipe.w = r->w; r->pipe.h = r->h; r->pipe.fmt = r->fmt; r->pipe.depth = r->depth;
        if (rs_pass_terrain(&terrain, &r->fr) != BR_OK || rs_pipe_add(&r->pipe, &terrain) != BR_OK) return BR_E_ARG;
    }
    need = rs_pipe_mem_size(p, r->bands);
    if (need > r->band_mem_size) {     /* the first frame (the pipe's passes do not change size) */
        free(r->band_mem);
        r->band_mem = malloc(need);
        r->band_mem_size = r->band_mem ? need : 0;
        if (!r->band_mem) return BR_E_NOMEM;
    }
    {
        sink_frame sf;
        sf.px = r->color;
        sf.row_bytes = (size_t)r->w * (r->fmt == RS_FMT_RGB565 ? 2u : 4u);
        return rs_pipe_run(p, r->bands, r->band_mem, r->band_mem_size, sink_frame_band, &sf, NULL);
    }
}

/* One terrain frame.  Not static and not inlined: callgrind toggles on it. */
__attribute__((noinline)) br_status bench_default_frame(bd_run *r, const cam *c);
__attribute__((noinline)) br_status bench_default_frame(bd_run *r, const cam *c)
{
    br_status st = bd_select(r, c);
    if (st != BR_OK) return st;
    r->tris += r->s.mesh.ntri;
    r->t_mid = br_now_ms();
    return bd_raster(r, c);
}

/* ---------------------------------------------------------------- bench_default.h */

bd_run *bd_open(const char *dem, double pix_err, br_err *err)
{
    scene_opts so;
    bd_run *r = calloc(1, sizeof *r);
    if (!dem) dem = ASSET_DEFAULT_DEM;
    if (!r) { br_err_set(err, BR_E_NOMEM, NULL, "out of memory"); return NULL; }
    r->fmt = RS_FMT_XRGB8888; r->depth = RS_DEPTH32; r->bands = 64; r->pix_err = pix_err;
    memset(&so, 0, sizeof so);
    so.quiet = 1;
    if (scene_open(&r->s, &dem, 1, &so, err) != BR_OK) { free(r); return NULL; }
    if (scene_tree(&r->s, err) != BR_OK || scene_reserve(&r->s, BD_MAX_TRI, err) != BR_OK) {
        scene_close(&r->s);
        free(r);
        return NULL;
    }
    return r;
}

void bd_close(bd_run *r)
{
    if (!r) return;
    scene_close(&r->s);
    free(r);
}

void bd_default_view(const bd_run *r, double eye[3], double tgt[3])
{
    scene_default_view(&r->s, BD_FOV, eye, tgt);
}

br_status bd_camera(const bd_run *r, const double eye[3], const double tgt[3], int32_t w, int32_t h, cam *c)
{
    return scene_camera(&r->s, eye, tgt, BD_FOV, w, h, c);
}

const rs_frame *bd_frame(const bd_run *r)
{
    return &r->fr;
}

uint32_t bd_tris(const bd_run *r)
{
    return r->s.mesh.ntri;
}

void bd_set_pool(bd_run *r, pt_pool *pool)
{
    r->s.pool = pool;
}

int cmd_bench_default(int argc, char **argv)
{
    const char *dems[16], *path = NULL, *out = NULL, *tree = NULL;
    int ndem = 0, frames = 10, warm = 0, fill_voids = 0, vis = 0, i, rc = 1;
    bd_vis vc;
    bd_run *r = calloc(1, sizeof *r);
    campath cp = {NULL, 0};
    scene_opts so;
    ws_opts wo;
    ws_args wa;
    opt_spec water_t[WS_ARGS_N];
    br_err err;
    double *ms = NULL, *sel_ms = NULL, eye[3], tgt[3];
    if (!r) return 1;
    memset(&vc, 0, sizeof vc);
    r->w = 320; r->h = 240; r->fmt = RS_FMT_XRGB8888; r->depth = RS_DEPTH32; r->bands = 64; r->pix_err = 1;
    memset(&wo, 0, sizeof wo);
    wo.quiet = 1;
    ws_args_table(&wa, &wo, water_t);
    {
        int size[2] = { 320, 240 }, fmt = 0, depth = 0, scene_choice = 0, npos = 0, pr;
        const char *pos[1];
        opt_strs dem_list = { dems, 0, (int)(sizeof dems / sizeof dems[0]) };
        const opt_spec own[] = {
            { "--scene", OPT_CHOICE, &scene_choice, 0, 0, 0, "default", "S", "the users' scene (assets/N47E009.hgt.gz)", NULL },
            { "--path", OPT_STR, &path, 0, 0, 0, NULL, "FILE", "camera path: one --camera line a frame (assets/*.cam)", NULL },
            { "--size", OPT_SIZE, size, 16, RS_MAX_DIM, 0, NULL, "WxH", "frame size (default 320x240)", NULL },
            { "--frames", OPT_INT, &frames, 1, 1000000, 0, NULL, "N", "timed frames (default 10)", NULL },
            { "--warmup", OPT_INT, &warm, 0, 1000000, 0, NULL, "W", "untimed frames first (default 0)", NULL },
            { "--pixel-error", OPT_NUM, &r->pix_err, 0.01, 1000, 0, NULL, "P", "screen-space error, pixels (default 1)", NULL },
            { "--format", OPT_CHOICE, &fmt, 0, 0, 0, "rgb888|rgb565", "F", "pixel format", NULL },
            { "--depth", OPT_CHOICE, &depth, 0, 0, 0, "32|16", "BITS", "depth buffer bits", NULL },
            { "--bands", OPT_INT, &r->bands, 1, RS_MAX_DIM, 0, NULL, "ROWS", "band height (default 64, the viewer's)", NULL },
            { "--dem", OPT_STRS, &dem_list, 0, 0, 0, NULL, "FILE",
              "another terrain instead of the default; given again, tiles merged as render merges its inputs", NULL },
            { "--tree", OPT_STR, &tree, 0, 0, 0, NULL, "FILE", "attach the bitree saved by `bitrain mesh --save-tree` instead of building it", NULL },
            { "--fill-voids", OPT_FLAG, &fill_voids, 0, 0, 0, NULL, NULL,
              "fill the terrain's voids from their borders first, as render and view do with it", NULL },
            { "-o", OPT_STR, &out, 0, 0, 0, NULL, "OUT.png", "write the last frame", NULL },
            { "--visibility", OPT_FLAG, &vis, 0, 0, 0, NULL, NULL,
              "also count, outside the timed frames, the terrain triangles that own a pixel of the "
              "frame and why the others own none (the frame drawn again)", NULL },
            { "--with-water", OPT_FLAG, &r->water, 0, 0, 0, NULL, NULL,
              "draw water, sky and fog as render and view do (default: the terrain frame alone); "
              "the water options below apply", NULL },
            OPT_END
        };
        const opt_spec *const tables[] = { own, water_t, NULL };
        pr = opt_parse("bench", "--scene default [options]\n"
                       "  the default scene's terrain frame: selection + strip + vertices + transform + raster",
                       tables, argc, argv, pos, 0, &npos);
        if (pr == OPT_OK) pr = ws_args_finish(&wa, "bench");
        if (pr == OPT_OK && !r->water && (wo.no_water || wo.have_level || wo.water_file || wo.no_fog || wa.fog
                                          || wa.time_seen || wa.refl_seen || wa.refl_err_seen))
            pr = opt_fail("bench", "--no-water", "water options need --with-water");
        if (pr != OPT_OK) { free(r); return pr == OPT_HELP ? 0 : 2; }
        r->w = size[0];
        r->h = size[1];
        r->fmt = fmt ? RS_FMT_RGB565 : RS_FMT_XRGB8888;
        r->depth = depth ? RS_DEPTH16 : RS_DEPTH32;
        ndem = dem_list.n;
    }
    if (!ndem) dems[ndem++] = ASSET_DEFAULT_DEM;
    if (path && campath_read(path, &cp, &err) != BR_OK) { fprintf(stderr, "bitrain bench: %s\n", err.msg); goto done; }
    memset(&so, 0, sizeof so);
    so.quiet = 1;
    so.ramp_abs = r->water;     /* render and view colour by absolute elevation with water */
    so.tree = tree;
    so.dem.fill_voids = fill_voids;
    if (scene_open(&r->s, dems, ndem, &so, &err) != BR_OK) { fprintf(stderr, "bitrain bench: %s\n", err.msg); goto done; }
    wo.shore_bound = 1;
    wo.shore_px = r->pix_err;
    wo.view_px = r->pix_err;
    if (r->water && ws_open(&r->ws, &r->s, &wo, &err) != BR_OK) {
        r->water = 0;
        fprintf(stderr, "bitrain bench: %s\n", err.msg);
        goto done;
    }
    if (scene_tree(&r->s, &err) != BR_OK || scene_reserve(&r->s, BD_MAX_TRI, &err) != BR_OK
        || (r->water && ws_reserve(&r->ws, &r->s) != BR_OK)) {
        fprintf(stderr, "bitrain bench: %s: %s\n", dems[0], r->water && r->s.mesh_mem ? "out of memory" : err.msg);
        goto done;
    }
    r->color = malloc((size_t)r->w * (size_t)r->h * 4);
    ms = malloc(sizeof *ms * (size_t)frames);
    sel_ms = malloc(sizeof *sel_ms * (size_t)frames);
    if (!r->color || !ms || !sel_ms) { fprintf(stderr, "bitrain bench: out of memory\n"); goto done; }
    scene_default_view(&r->s, BD_FOV, eye, tgt);
    for (i = -warm; i < frames; i++) {
        cam c;
        double t0, t1;
        int k = i < 0 ? i + warm : i;
        const double *e = eye, *t = tgt;
        br_status st;
        if (cp.n) { e = cp.cam[k % cp.n]; t = cp.cam[k % cp.n] + 3; }
        if (scene_camera(&r->s, e, t, BD_FOV, r->w, r->h, &c) != BR_OK) {
            fprintf(stderr, "bitrain bench: %s: frame %d: unusable camera\n", path ? path : "default view", k + 1);
            goto done;
        }
        t0 = br_now_ms();
        if (i < 0) { st = bd_select(r, &c); if (st == BR_OK) st = bd_raster(r, &c); }
        else {
            st = bench_default_frame(r, &c);
            t1 = br_now_ms();
            ms[i] = t1 - t0;
            sel_ms[i] = r->t_mid - t0;
        }
        if (st != BR_OK) { fprintf(stderr, "bitrain bench: frame %d failed (%d)\n", k + 1, (int)st); goto done; }
        if (vis && i >= 0 && bd_visibility(&r->fr, &vc, &err) != BR_OK) {
            fprintf(stderr, "bitrain bench: frame %d: %s\n", k + 1, err.msg);
            goto done;
        }
    }
    {
        double med, smed, tri = (double)r->tris / frames;
        qsort(ms, (size_t)frames, sizeof *ms, br_cmp_double);
        qsort(sel_ms, (size_t)frames, sizeof *sel_ms, br_cmp_double);
        med = frames & 1 ? ms[frames / 2] : 0.5 * (ms[frames / 2 - 1] + ms[frames / 2]);
        smed = frames & 1 ? sel_ms[frames / 2] : 0.5 * (sel_ms[frames / 2 - 1] + sel_ms[frames / 2]);
        printf("bitrain scene=default path=%s size=%dx%d pixel_error=%g format=%s depth=%d bands=%d frames=%d "
               "ms/frame=%.3f select_ms=%.3f tris/frame=%.0f Mtri/s(frame)=%.2f Mtri/s(raster)=%.2f\n",
               path ? path : "-", r->w, r->h, r->pix_err, r->fmt == RS_FMT_RGB565 ? "rgb565" : "rgb888",
               r->depth == RS_DEPTH16 ? 16 : 32, r->bands, frames, med, smed, tri,
               tri / med / 1e3, med > smed ? tri / (med - smed) / 1e3 : 0.0);
    }
    if (vis && vc.tris) {
        const double n = (double)vc.frames, pc = 100.0 / (double)vc.tris;
        printf("visibility: triangles/frame=%.0f seen=%.0f (%.1f%%) tiny=%.0f (%.1f%%) edge=%.0f (%.1f%%) "
               "back=%.0f (%.1f%%) hidden=%.0f (%.1f%%)\n", (double)vc.tris / n, (double)vc.seen / n,
               (double)vc.seen * pc, (double)vc.tiny / n, (double)vc.tiny * pc, (double)vc.edge / n,
               (double)vc.edge * pc, (double)vc.back / n, (double)vc.back * pc, (double)vc.hidden / n,
               (double)vc.hidden * pc);
    }
    rc = 0;
    if (out) {
        uint8_t *rgb = malloc((size_t)r->w * (size_t)r->h * 3);
        size_t bpp = r->fmt == RS_FMT_RGB565 ? 2u : 4u;
        if (!rgb) { rc = 1; goto done; }
        for (i = 0; i < r->h; i++)
            rs_to_rgb888(r->fmt, r->color + (size_t)i * (size_t)r->w * bpp, r->w, rgb + (size_t)i * (size_t)r->w * 3);
        if (png_write_rgb(out, r->w, r->h, rgb, (size_t)r->w * 3, &err) != BR_OK) {
            fprintf(stderr, "bitrain bench: %s\n", err.msg);
            rc = 1;
        }
        free(rgb);
    }
done:
    free(ms); free(sel_ms);
    if (r->color) free(r->color);
    free(r->band_mem);
    if (r->water) ws_close(&r->ws);
    scene_close(&r->s);
    campath_free(&cp);
    free(r);
    return rc;
}
