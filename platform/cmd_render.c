/* platform/cmd_render.c — bitrain render: one frame of a DEM, headless, to PNG.
 *
 *   bitrain render IN... -o out.png [--size WxH] [--camera EX,EY,EZ,TX,TY,TZ] [--fov DEG]
 *          [--max-error M | --pixel-error P | --full [STEP]] [--bands ROWS]
 *          [--format rgb565|rgb888] [--depth 32|16] [--colors FILE] [--texture PNG] [--no-cull]
 *          [--sun AZ,ALT] [--ambient A] [--zscale F]
 * Camera in the heightfield's metres: x east from the west edge, y north from the
 * south edge, z height above 0 m (times --zscale).  Default camera: from the south-west, above the
 * terrain, looking at its centre.  Mesh: the bitree (core/bitree.h), by default
 * view-dependent with a 1 pixel screen-space error; --max-error M selects the
 * fidelity mode (true vertical error <= M metres); --full [STEP] draws the full grid
 * (every STEP-th sample) as row strips instead.  Colours: a gdaldem color-relief file
 * (--colors) or the built-in ramp, lit by a sun (azimuth 315, altitude 45 by default)
 * with 30 % ambient.  --zscale F multiplies heights (default 1; grids without
 * georeference get an automatic scale that brings their steep slopes to 0.75, since
 * the loader can only assume 1 m spacing for them: platform/scene.c).  The frame is rendered in bands of ROWS rows (default: whole
 * frame) and streamed to the PNG band by band.  --texture PNG stretches a colour map or
 * orthophoto over the whole grid (perspective-correct, nearest texel), lit by the sun. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "core/bitree.h"
#include "core/cam.h"
#include "platform/cmd.h"
#include "platform/dem_args.h"
#include "platform/opt.h"
#include "platform/scene_args.h"
#include "platform/load.h"
#include "platform/scene.h"
#include "platform/water_scene.h"
#include "platform/png_io.h"
#include "raster/raster.h"
#include "raster/ramp.h"
#include "raster/terrain.h"

/* ---------------------------------------------------------------- PNG sink */

typedef struct png_sink {
    png_out *po;
    int32_t w, fmt;
    uint8_t *rgb;
    br_err *err;
} png_sink;

static br_status sink_png(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    png_sink *s = (png_sink *)user;
    int32_t y;
    (void)y0;
    for (y = 0; y < rows; y++) {
        br_status st;
        rs_to_rgb888(s->fmt, (const uint8_t *)px + (size_t)y * stride, s->w, s->rgb);
        st = png_out_rows(s->po, s->rgb, 1, (size_t)s->w * 3, s->err);
        if (st != BR_OK) return st;
    }
    return BR_OK;
}

/* ---------------------------------------------------------------- command */

static double ms_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

#define RENDER_SYNOPSIS "IN... -o OUT.png [options]\n" \
    "  camera in metres: x east from the west edge, y north from the south edge, z height (times --zscale)"

int cmd_render(int argc, char **argv)
{
    const char *in[64], *out = NULL;
    int nin = 0, size[2] = { 800, 600 }, w, h, have_cam = 0, have_max = 0, have_pix = 0, mode = BT_VIEW;
    int full_step = 0, bands = 0, fmt = RS_FMT_XRGB8888, depth_choice = 0, depth, no_cull = 0, r;
    double camv[6], fov = 50, max_err = 0, pix_err = 1;
    scene_opts so;
    scene_args sa;
    dem_args da;
    opt_spec dem_t[DEM_ARGS_N], look_t[SCENE_ARGS_N], water_t[WS_ARGS_N];
    ws_args wa;
    const opt_spec own[] = {
        { "-o", OPT_STR, &out, 0, 0, 0, NULL, "OUT.png", "the image to write", NULL },
        { "--size", OPT_SIZE, size, 1, RS_MAX_DIM, 0, NULL, "WxH", "image size (default 800x600)", NULL },
        { "--camera", OPT_NUMS, camv, -1e7, 1e7, 6, NULL, "EX,EY,EZ,TX,TY,TZ", "eye and target, metres",
          &have_cam },
        { "--fov", OPT_NUM, &fov, 1, 170, 0, NULL, "DEG", "vertical field of view (default 50)", NULL },
        { "--max-error", OPT_NUM, &max_err, 0, 100000, 0, NULL, "M",
          "fidelity mesh: true vertical error at most M metres", &have_max },
        { "--pixel-error", OPT_NUM, &pix_err, 0.01, 1000, 0, NULL, "P",
          "view-dependent mesh: screen error at most P pixels (default 1)", &have_pix },
        { "--full", OPT_INT_OPT, &full_step, 1, 4096, 0, NULL, "[STEP]", "the full grid (every STEP-th sample)", NULL },
        { "--bands", OPT_INT, &bands, 0, RS_MAX_DIM, 0, NULL, "ROWS", "render in bands of ROWS rows (0: whole frame)", NULL },
        { "--format", OPT_CHOICE, &fmt, 0, 0, 0, "rgb888|rgb565", "F", "pixel format of the frame", NULL },
        { "--depth", OPT_CHOICE, &depth_choice, 0, 0, 0, "32|16", "BITS", "depth buffer bits", NULL },
        { "--no-cull", OPT_FLAG, &no_cull, 0, 0, 0, NULL, NULL, "draw back faces too", NULL },
        OPT_END
    };
    const opt_spec *const tables[] = { own, look_t, water_t, dem_t, NULL };
    scene s;
    br_err err;
    cam c;
    rs_vertex *verts = NULL;
    uint32_t nv = 0, *idx = NULL, nidx = 0;
    rs_prim *prims = NULL;
    int32_t nprims = 0;
    rs_frame fr;
    void *bandmem = NULL;
    png_sink ps;
    double t0, t1, t2;
    int rc = 1;
    ws_opts wo;
    water_scene ws;
    int use_pipe;

    memset(&so, 0, sizeof so);
    memset(&s, 0, sizeof s);
    memset(&fr, 0, sizeof fr);
    memset(&ps, 0, sizeof ps);
    memset(&wo, 0, sizeof wo);
    memset(&ws, 0, sizeof ws);
    dem_args_table(&da, &so.dem, dem_t);
    scene_args_table(&sa, &so, look_t);
    ws_args_table(&wa, &wo, water_t);
    r = opt_parse("render", RENDER_SYNOPSIS, tables, argc, argv, in, 64, &nin);
    if (r != OPT_OK) return r == OPT_HELP ? 0 : 2;
    if (dem_args_finish(&da, "render") != OPT_OK) return 2;
    if (scene_args_finish(&sa, "render") != OPT_OK) return 2;
    if (ws_args_finish(&wa, "render") != OPT_OK) return 2;
    if (!nin) { fprintf(stderr, "bitrain render: no input file (`bitrain render --help`)\n"); return 2; }
    if (!out) { fprintf(stderr, "bitrain render: no output file: -o OUT.png\n"); return 2; }
    if (have_max && have_pix) return opt_fail("render", "--max-error", "cannot be used with --pixel-error");
    if (full_step && (have_max || have_pix))
        return opt_fail("render", "--full", "cannot be used with --max-error or --pixel-error");
    mode = have_max ? BT_FIDELITY : BT_VIEW;
    w = size[0];
    h = size[1];
    depth = depth_choice ? RS_DEPTH16 : RS_DEPTH32;
    if (bands == 0 || bands > h) bands = h;

    t0 = ms_now();
    use_pipe = !(wo.no_water && wo.no_fog);
    so.ramp_abs = use_pipe;
    if (scene_open(&s, in, nin, &so, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); return 1; }
    if (use_pipe && ws_open(&ws, &s, &wo, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
    if (!have_cam) scene_default_view(&s, fov, camv, camv + 3);
    if (scene_camera(&s, camv, camv + 3, fov, w, h, &c) != BR_OK) {
        fprintf(stderr, "bitrain render: unusable camera (eye equals target, or too far from the terrain: "
                "world unit 2^%d m)\n", -s.rt.shift);
        goto done;
    }

    /* mesh */
    if (full_step > 0) {
        int32_t gw = (s.f.w - 1) / full_step + 1, gh = (s.f.h - 1) / full_step + 1, x, y, pass;
        size_t nruns = 0;
        nv = (uint32_t)gw * (uint32_t)gh;
        verts = malloc(sizeof *verts * nv);
        idx = malloc(sizeof *idx * (size_t)2 * (size_t)gw * (size_t)(gh - 1 > 0 ? gh - 1 : 1));
        if (!verts || !idx) { fprintf(stderr, "bitrain: out of memory\n"); goto done; }
        for (y = 0; y < gh; y++)
            for (x = 0; x < gw; x++) {
                int32_t z = s.f.z[(size_t)y * full_step * (size_t)s.f.w + (size_t)x * full_step];
                rt_vertex(&s.rt, x * full_step, y * full_step, z == HF_NODATA ? 0 : z, &verts[y * gw + x]);
            }
        /* row strips, south-west first vertex: CCW seen from +z (row y is north of y+1),
         * one per run of columns whose two samples are valid: a void is a hole, as in
         * the bitree's meshes (no triangle touches a void sample) */
        for (pass = 0; pass < 2; pass++) {
            if (pass == 1 && !(prims = malloc(sizeof *prims * (nruns ? nruns : 1)))) {
                fprintf(stderr, "bitrain: out of memory\n");
                goto done;
            }
            for (y = 0; y + 1 < gh; y++) {
                int32_t a = 0, b;
                while (a < gw) {
                    const int32_t *zr = s.f.z + (size_t)y * full_step * (size_t)s.f.w;
                    const int32_t *zn = s.f.z + (size_t)(y + 1) * full_step * (size_t)s.f.w;
                    for (b = a; b < gw && zr[(size_t)b * full_step] != HF_NODATA && zn[(size_t)b * full_step] != HF_NODATA; b++) {}
                    if (b - a >= 2 && pass == 0) nruns++;
                    else if (b - a >= 2) {
                        uint32_t *sp = idx + nidx;
                        for (x = a; x < b; x++) {
                            sp[2 * (x - a)] = (uint32_t)(y * gw + x);
                            sp[2 * (x - a) + 1] = (uint32_t)((y + 1) * gw + x);
                        }
                        prims[nprims].kind = RS_STRIP; prims[nprims].n = (uint32_t)(2 * (b - a)); prims[nprims].idx = sp;
                        nprims++; nidx += (uint32_t)(2 * (b - a));
                    }
                    a = b + 1;
                }
            }
        }
    } else {
        bt_params bp;
        uint64_t ntri = 0;
        memset(&bp, 0, sizeof bp);
        bp.mode = mode;
        bp.max_err = bt_mm_to_units(&s.f, (int64_t)llround(max_err * 1000));
        bp.c = &c;
        bp.fr = s.rt.fr;
        bp.pixel_err_q8 = (int32_t)lround(pix_err * 256);
        if (scene_tree(&s, &err) != BR_OK) { fprintf(stderr, "bitrain: %s: %s\n", in[0], err.msg); goto done; }
        if (bt_count(&s.tree, &bp, &ntri) != BR_OK) { fprintf(stderr, "bitrain: bad mesh parameters\n"); goto done; }
        if (scene_reserve(&s, (uint32_t)(ntri + 16 > 16000000 ? 16000000 : ntri + 16), &err) != BR_OK) {
            fprintf(stderr, "bitrain: %s: %s\n", in[0], err.msg);
            goto done;
        }
        if (bt_extract(&s.tree, &bp, &s.mesh) != BR_OK) { fprintf(stderr, "bitrain: cannot extract the mesh\n"); goto done; }
        nv = s.mesh.nv;
        rt_from_mesh(&s.rt, &s.mesh, s.verts);
        prims = malloc(sizeof *prims);
        if (!prims) { fprintf(stderr, "bitrain: out of memory\n"); goto done; }
        prims[0].kind = RS_STRIP; prims[0].n = s.mesh.ns; prims[0].idx = s.mesh.strip;
        nprims = 1;
    }
    t1 = ms_now();

    /* render in bands, streaming to the PNG */
    fr.w = w; fr.h = h; fr.fmt = fmt; fr.depth = depth; fr.no_cull = no_cull;
    fr.clear_rgb = 0x99ccffu;
    fr.tex = s.rt.tex_w > 0 ? &s.tex : NULL;
    fr.v = full_step ? verts : s.verts; fr.nv = nv; fr.prims = prims; fr.nprims = nprims;
    fr.cache = full_step ? malloc(rs_cache_mem_size(nv ? nv : 1)) : s.cache;
    fr.chunks = bands < h || use_pipe ? malloc(rs_chunk_mem_size(prims, nprims) + 4) : NULL;
    bandmem = use_pipe ? NULL : malloc(rs_band_mem_size(w, bands, fmt, depth));
    ps.rgb = malloc((size_t)w * 3);
    if (!fr.cache || (!bandmem && !use_pipe) || !ps.rgb) { fprintf(stderr, "bitrain: out of memory\n"); goto done; }
    cam_viewproj(&c, &fr.vp);
    if (rs_frame_prepare(&fr) != BR_OK) { fprintf(stderr, "bitrain: bad frame parameters\n"); goto done; }
    if (png_out_open(&ps.po, out, w, h, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
    ps.w = w; ps.fmt = fmt; ps.err = &err;
    if (use_pipe) {     /* water and atmosphere: the frame pipe (platform/water_scene.h) */
        size_t mb;
        rs_band_stats tot;
        if (ws_frame(&ws, &s, &c, &fr, &err) != BR_OK) {
            png_out_abort(ps.po);
            fprintf(stderr, "bitrain: %s\n", err.msg);
            goto done;
        }
        mb = rs_pipe_mem_size(&ws.pipe, bands);
        bandmem = malloc(mb);
        if (!bandmem || rs_pipe_run(&ws.pipe, bands, bandmem, mb, sink_png, &ps, &tot) != BR_OK) {
            png_out_abort(ps.po);
            fprintf(stderr, "bitrain: %s\n", err.msg[0] ? err.msg : "render failed");
            goto done;
        }
        fr.stat_tris = tot.tris; fr.stat_clipped = tot.clipped;
    } else if (rs_render(&fr, bands, bandmem, sink_png, &ps) != BR_OK) {
        png_out_abort(ps.po);
        fprintf(stderr, "bitrain: %s\n", err.msg[0] ? err.msg : "render failed");
        goto done;
    }
    if (png_out_close(ps.po, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
    t2 = ms_now();
    printf("%s: %dx%d, %u vertices, %s, %u triangles drawn (%u clipped), load+mesh %.1f ms, "
           "render+write %.1f ms, world unit 2^%d m, band %d rows (%zu bytes + %zu bytes vertex cache)\n",
           out, w, h, nv, full_step ? "full grid" : (mode == BT_FIDELITY ? "bitree fidelity" : "bitree view"),
           fr.stat_tris, fr.stat_clipped, t1 - t0, t2 - t1, -s.rt.shift, bands,
           rs_band_mem_size(w, bands, fmt, depth), rs_cache_mem_size(nv));
    rc = 0;
done:
    if (full_step) free(fr.cache);
    free(verts); free(idx); free(prims); free(fr.chunks); free(bandmem); free(ps.rgb);
    if (use_pipe) ws_close(&ws);
    scene_close(&s);
    return rc;
}
