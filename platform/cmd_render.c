#define _POSIX_C_SOURCE 200809L   /* clock_gettime under -std=c99 (no SDL flags to bring it) */
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
 * georeference whose relief exceeds half their extent get an automatic scale, since
 * the loader can only assume 1 m spacing for them).  The frame is rendered in bands of ROWS rows (default: whole
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
#include "platform/load.h"
#include "platform/scene.h"
#include "platform/png_io.h"
#include "platform/sink_spi.h"
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

/* ---------------------------------------------------------------- SPI panel sink */

typedef struct spi_opts {
    const char *dev, *capture, *dc, *rst;
    int panel, mode, madctl;
    long hz;
} spi_opts;

/* One SPI option at argv a (value n): 1 taken with its value, 0 not an SPI option,
 * -1 a bad value (the message printed). */
static int spi_arg(spi_opts *o, const char *a, const char *n)
{
    char *end = NULL;
    if (!n) return 0;
    if (!strcmp(a, "--spi")) o->dev = n;
    else if (!strcmp(a, "--spi-capture")) o->capture = n;
    else if (!strcmp(a, "--dc")) o->dc = n;
    else if (!strcmp(a, "--reset")) o->rst = n;
    else if (!strcmp(a, "--panel")) {
        if (!(o->panel = spi_panel_parse(n))) { fprintf(stderr, "bitrain render: --panel '%s': st7789 or ili9341\n", n); return -1; }
    } else if (!strcmp(a, "--spi-hz")) {
        o->hz = strtol(n, &end, 10);
        if (*end || o->hz < 1000 || o->hz > 100000000) { fprintf(stderr, "bitrain render: --spi-hz '%s': 1000 .. 100000000\n", n); return -1; }
    } else if (!strcmp(a, "--spi-mode")) {
        o->mode = (int)strtol(n, &end, 10);
        if (*end || o->mode < 0 || o->mode > 3) { fprintf(stderr, "bitrain render: --spi-mode '%s': 0 .. 3\n", n); return -1; }
    } else if (!strcmp(a, "--madctl")) {
        o->madctl = (int)strtol(n, &end, 0);
        if (*end || o->madctl < 0 || o->madctl > 255) { fprintf(stderr, "bitrain render: --madctl '%s': 0 .. 0xff\n", n); return -1; }
    } else return 0;
    return 1;
}

/* The panel's writer (spidev, or the capture file) and sink, started up */
static br_status spi_open(const spi_opts *o, int w, int h, int fmt, spi_writer *wr, spi_sink *ss, br_err *err)
{
    br_status st = o->capture ? spi_capture_open(wr, o->capture, err)
                              : spi_linux_open(wr, o->dev, (uint32_t)o->hz, o->mode, o->dc, o->rst, err);
    if (st != BR_OK) return st;
    st = spi_sink_open(ss, wr, o->panel, w, h, fmt, o->madctl, err);
    if (st != BR_OK) {
        if (o->capture) spi_capture_close(wr, NULL);
        else spi_linux_close(wr);
    }
    return st;
}

static br_status spi_close(const spi_opts *o, spi_writer *wr, spi_sink *ss, br_err *err)
{
    spi_sink_close(ss);
    if (o->capture) return spi_capture_close(wr, err);
    spi_linux_close(wr);
    return BR_OK;
}

/* ---------------------------------------------------------------- command */

static double ms_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static int usage(void)
{
    fprintf(stderr,
            "usage: bitrain render IN... -o out.png [--size WxH] [--camera EX,EY,EZ,TX,TY,TZ] [--fov DEG]\n"
            "         [--max-error M | --pixel-error P | --full [STEP]] [--bands ROWS]\n"
            "         [--format rgb565|rgb888] [--depth 32|16] [--colors FILE] [--texture PNG] [--no-cull]\n"
            "         [--sun AZ,ALT] [--ambient A] [--zscale F]\n"
            "         [--spi /dev/spidevB.C | --spi-capture FILE] [--panel st7789|ili9341] [--dc CHIP:LINE]\n"
            "         [--reset CHIP:LINE] [--spi-hz HZ] [--spi-mode 0-3] [--madctl M]\n"
            "  camera in metres: x east from the west edge, y north from the south edge, z height\n"
            "  --spi: each band to an SPI panel (-o optional; RGB565 unless --format says otherwise,\n"
            "         bands of 16 rows unless --bands says otherwise);\n"
            "         D/C line --dc (default /dev/gpiochip0:25), 16 MHz, mode 0, panel st7789\n");
    return 2;
}

int cmd_render(int argc, char **argv)
{
    const char *in[64], *out = NULL;
    int nin = 0, i, w = 800, h = 600, have_cam = 0, mode = BT_VIEW, full_step = 0, bands = 0, r;
    int fmt = RS_FMT_XRGB8888, depth = RS_DEPTH32, no_cull = 0;
    double camv[6], fov = 50, max_err = 0, pix_err = 1;
    scene_opts so;
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
    spi_opts so_spi;
    spi_writer spw;
    spi_sink ss;
    int have_fmt = 0;
    double t0, t1, t2;
    int rc = 1;

    memset(&so, 0, sizeof so);
    memset(&s, 0, sizeof s);
    memset(&fr, 0, sizeof fr);
    memset(&ps, 0, sizeof ps);
    memset(&so_spi, 0, sizeof so_spi);
    so_spi.panel = SPI_PANEL_ST7789; so_spi.madctl = -1; so_spi.hz = 16000000; so_spi.dc = "/dev/gpiochip0:25";
    for (i = 0; i < argc; i++) {
        const char *a = argv[i], *n = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-o") && n) { out = n; i++; }
        else if (!strcmp(a, "--size") && n) { if (sscanf(n, "%dx%d", &w, &h) != 2) return usage(); i++; }
        else if (!strcmp(a, "--camera") && n) {
            if (sscanf(n, "%lf,%lf,%lf,%lf,%lf,%lf", &camv[0], &camv[1], &camv[2], &camv[3], &camv[4], &camv[5]) != 6)
                return usage();
            have_cam = 1; i++;
        } else if (!strcmp(a, "--fov") && n) { fov = atof(n); i++; }
        else if (!strcmp(a, "--max-error") && n) { max_err = atof(n); mode = BT_FIDELITY; i++; }
        else if (!strcmp(a, "--pixel-error") && n) { pix_err = atof(n); mode = BT_VIEW; i++; }
        else if (!strcmp(a, "--full")) {
            full_step = 1;
            if (n && isdigit((unsigned char)n[0])) { full_step = atoi(n); i++; }
        } else if (!strcmp(a, "--bands") && n) { bands = atoi(n); i++; }
        else if (!strcmp(a, "--format") && n) {
            if (!strcmp(n, "rgb565")) fmt = RS_FMT_RGB565;
            else if (!strcmp(n, "rgb888")) fmt = RS_FMT_XRGB8888;
            else return usage();
            have_fmt = 1; i++;
        } else if ((r = spi_arg(&so_spi, a, n)) != 0) { if (r < 0) return 2; i++; }
        else if (!strcmp(a, "--depth") && n) { depth = atoi(n) == 16 ? RS_DEPTH16 : RS_DEPTH32; i++; }
        else if (!strcmp(a, "--colors") && n) { so.colors = n; i++; }
        else if (!strcmp(a, "--texture") && n) { so.texture = n; i++; }
        else if (!strcmp(a, "--no-cull")) no_cull = 1;
        else if (!strcmp(a, "--sun") && n) { if (sscanf(n, "%lf,%lf", &so.sun_az, &so.sun_alt) != 2) return usage(); i++; }
        else if (!strcmp(a, "--ambient") && n) { so.ambient = atof(n); i++; }
        else if (!strcmp(a, "--zscale") && n) { so.zscale = atof(n); i++; }
        else if ((r = dem_args_parse(&so.dem, argc, argv, &i, "render")) != 0) { if (r < 0) return 2; }
        else if (!strcmp(a, "-h") || !strcmp(a, "--help")) { usage(); return 0; }
        else if (a[0] == '-' && a[1]) { fprintf(stderr, "bitrain render: unknown option '%s'\n", a); return usage(); }
        else if (nin < 64) in[nin++] = a;
    }
    if (so_spi.dev || so_spi.capture) {         /* the panel's format, a small band in RAM */
        if (!have_fmt) fmt = RS_FMT_RGB565;
        if (!bands) bands = 16;
    }
    if (!nin || !(out || so_spi.dev || so_spi.capture) || w < 1 || h < 1 || w > RS_MAX_DIM || h > RS_MAX_DIM || !(fov >= 1 && fov <= 170)
        || full_step < 0 || bands < 0 || !(so.ambient >= 0 && so.ambient <= 1) || !(pix_err > 0) || max_err < 0
        || !(so.zscale >= 0 && so.zscale <= 1000))
        return usage();
    if (bands == 0 || bands > h) bands = h;

    t0 = ms_now();
    if (scene_open(&s, in, nin, &so, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); return 1; }
    if (!have_cam) scene_default_view(&s, fov, camv, camv + 3);
    if (scene_camera(&s, camv, camv + 3, fov, w, h, &c) != BR_OK) {
        fprintf(stderr, "bitrain render: unusable camera (eye equals target, or too far from the terrain: "
                "world unit 2^%d m)\n", -s.rt.shift);
        goto done;
    }

    /* mesh */
    if (full_step > 0) {
        int32_t gw = (s.f.w - 1) / full_step + 1, gh = (s.f.h - 1) / full_step + 1, x, y;
        nv = (uint32_t)gw * (uint32_t)gh;
        verts = malloc(sizeof *verts * nv);
        idx = malloc(sizeof *idx * (size_t)2 * (size_t)gw * (size_t)(gh - 1 > 0 ? gh - 1 : 1));
        prims = malloc(sizeof *prims * (size_t)(gh > 1 ? gh - 1 : 1));
        if (!verts || !idx || !prims) { fprintf(stderr, "bitrain: out of memory\n"); goto done; }
        for (y = 0; y < gh; y++)
            for (x = 0; x < gw; x++) {
                int32_t z = s.f.z[(size_t)y * full_step * (size_t)s.f.w + (size_t)x * full_step];
                rt_vertex(&s.rt, x * full_step, y * full_step, z == HF_NODATA ? 0 : z, &verts[y * gw + x]);
            }
        /* row strips, south-west first vertex: CCW seen from +z (row y is north of y+1) */
        for (y = 0; y + 1 < gh; y++) {
            uint32_t *sp = idx + nidx;
            for (x = 0; x < gw; x++) {
                sp[2 * x] = (uint32_t)(y * gw + x);
                sp[2 * x + 1] = (uint32_t)((y + 1) * gw + x);
            }
            prims[nprims].kind = RS_STRIP; prims[nprims].n = (uint32_t)(2 * gw); prims[nprims].idx = sp;
            nprims++; nidx += (uint32_t)(2 * gw);
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
    fr.chunks = bands < h ? malloc(rs_chunk_mem_size(prims, nprims) + 4) : NULL;
    bandmem = malloc(rs_band_mem_size(w, bands, fmt, depth));
    ps.rgb = malloc((size_t)w * 3);
    if (!fr.cache || !bandmem || !ps.rgb) { fprintf(stderr, "bitrain: out of memory\n"); goto done; }
    cam_viewproj(&c, &fr.vp);
    if (rs_frame_prepare(&fr) != BR_OK) { fprintf(stderr, "bitrain: bad frame parameters\n"); goto done; }
    err.msg[0] = 0;
    if (so_spi.dev || so_spi.capture) {        /* the panel, band by band */
        br_status st;
        if (spi_open(&so_spi, w, h, fmt, &spw, &ss, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
        st = rs_render(&fr, bands, bandmem, spi_sink_band, &ss);
        if (spi_close(&so_spi, &spw, &ss, st == BR_OK ? &err : NULL) != BR_OK || st != BR_OK) {
            fprintf(stderr, "bitrain: %s\n", err.msg[0] ? err.msg : "render failed");
            goto done;
        }
        if (out) rs_frame_prepare(&fr);         /* the statistics again for the PNG below */
    }
    if (out) {
        if (png_out_open(&ps.po, out, w, h, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
        ps.w = w; ps.fmt = fmt; ps.err = &err;
        if (rs_render(&fr, bands, bandmem, sink_png, &ps) != BR_OK) {
            png_out_abort(ps.po);
            fprintf(stderr, "bitrain: %s\n", err.msg[0] ? err.msg : "render failed");
            goto done;
        }
        if (png_out_close(ps.po, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
    }
    t2 = ms_now();
    printf("%s: %dx%d, %u vertices, %s, %u triangles drawn (%u clipped), load+mesh %.1f ms, "
           "render+write %.1f ms, world unit 2^%d m, band %d rows (%zu bytes + %zu bytes vertex cache)\n",
           out ? out : (so_spi.capture ? so_spi.capture : so_spi.dev), w, h, nv, full_step ? "full grid" : (mode == BT_FIDELITY ? "bitree fidelity" : "bitree view"),
           fr.stat_tris, fr.stat_clipped, t1 - t0, t2 - t1, -s.rt.shift, bands,
           rs_band_mem_size(w, bands, fmt, depth), rs_cache_mem_size(nv));
    rc = 0;
done:
    if (full_step) free(fr.cache);
    free(verts); free(idx); free(prims); free(fr.chunks); free(bandmem); free(ps.rgb);
    scene_close(&s);
    return rc;
}
