#define _POSIX_C_SOURCE 200809L   /* clock_gettime under -std=c99 (no SDL flags to bring it) */
/* platform/cmd_bench.c — bitrain bench: render the peer benchmark scene of
 * ../shared/bench/PEERS.md with bitrain's integer rasteriser, nothing else, so that
 * one process (or one callgrind run) measures one configuration.
 *
 *   bitrain bench --scene peer --camera A|B --size WxH --frames N [--cull]
 *                 [--format rgb888|rgb565] [--depth 32|16] [--bands ROWS] [-o last.png]
 *                 [--dem fuji.png] [--warmup W]
 * Prints `bitrain camera=A size=640x480 cull=0 frames=N ms/frame=M (median) Mtri/s=T
 * Mpix/s=P drawn_tris=.. clipped=.. span_px=..`.  Mtri/s counts the 131,072 submitted
 * triangles per frame, Mpix/s the w*h pixels of a frame.  Each frame (vertex transform
 * + clear + all strips) runs inside bench_frame(), so
 *   valgrind --tool=callgrind --toggle-collect=bench_frame bitrain bench ... --frames N
 * counts only the N timed frames; divide by N.  W untimed warm-up frames (default 3,
 * as the llvmpipe benchmark gives Mesa) run first, outside bench_frame, so caches and
 * page tables are warm for every timed frame.  Back-face culling is off by default, like the
 * peers' table; --cull turns it on. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "platform/cmd.h"
#include "platform/png_io.h"
#include "raster/raster.h"
#include "benchmarks/peer_scene.h"

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* One frame: transform, clear, draw.  Not static and not inlined: callgrind toggles on it. */
__attribute__((noinline)) br_status bench_frame(rs_frame *f, void *color, void *depth);
__attribute__((noinline)) br_status bench_frame(rs_frame *f, void *color, void *depth)
{
    br_status s = rs_frame_prepare(f);
    if (s != BR_OK) return s;
    f->stat_tris = f->stat_clipped = f->stat_pixels = 0;
    return rs_render_band(f, 0, f->h, color, (size_t)f->w * (f->fmt == RS_FMT_RGB565 ? 2u : 4u), depth);
}

/* A warm-up frame outside bench_frame, so callgrind does not count it (no statistics
 * reset: the body differs from bench_frame's, so the compiler cannot fold the two). */
__attribute__((noinline)) static br_status warm_frame(rs_frame *f, void *color, void *depth)
{
    br_status s = rs_frame_prepare(f);
    if (s != BR_OK) return s;
    return rs_render_band(f, 0, f->h, color, (size_t)f->w * (f->fmt == RS_FMT_RGB565 ? 2u : 4u), depth);
}

static br_status bench_band_sink(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    (void)user; (void)y0; (void)rows; (void)px; (void)stride;
    return BR_OK;
}

int cmd_bench(int argc, char **argv)
{
    const char *scene = NULL, *out = NULL, *dem = "../shared/data/dem/png/fuji.png";
    char camc = 'A';
    int w = 640, h = 480, frames = 10, warm = 3, cull = 0, fmt = RS_FMT_XRGB8888, depth = RS_DEPTH32, bands = 0;
    int i;
    peer_scene *ps;
    rs_vertex *v;
    rs_prim prims[PEER_NSTRIP];
    rs_frame f;
    rs_cvert *cache;
    void *color, *zbuf, *mem = NULL;
    double *ms;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i], *n = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--scene") && n) { scene = n; i++; }
        else if (!strcmp(a, "--camera") && n) { camc = n[0]; i++; }
        else if (!strcmp(a, "--size") && n) { if (sscanf(n, "%dx%d", &w, &h) != 2) goto usage; i++; }
        else if (!strcmp(a, "--frames") && n) { frames = atoi(n); i++; }
        else if (!strcmp(a, "--warmup") && n) { warm = atoi(n); i++; }
        else if (!strcmp(a, "--cull")) cull = 1;
        else if (!strcmp(a, "--format") && n) {
            if (!strcmp(n, "rgb565")) fmt = RS_FMT_RGB565;
            else if (!strcmp(n, "rgb888")) fmt = RS_FMT_XRGB8888;
            else goto usage;
            i++;
        } else if (!strcmp(a, "--depth") && n) { depth = atoi(n) == 16 ? RS_DEPTH16 : RS_DEPTH32; i++; }
        else if (!strcmp(a, "--bands") && n) { bands = atoi(n); i++; }
        else if (!strcmp(a, "-o") && n) { out = n; i++; }
        else if (!strcmp(a, "--dem") && n) { dem = n; i++; }
        else if (!strcmp(a, "--isa") && n) {
            /* the copy of the drawing code (raster.h rs_isa_set): auto, x86-64, x86-64-v3 */
            int want = !strcmp(n, "auto") ? RS_ISA_AUTO : !strcmp(n, "x86-64-v3") ? RS_ISA_V3
                       : !strcmp(n, rs_isa_name(RS_ISA_BASE)) ? RS_ISA_BASE : -1;
            if (want < 0) goto usage;
            if (rs_isa_set(want) != want && want != RS_ISA_AUTO) {
                fprintf(stderr, "bitrain bench: --isa %s: this build or CPU has no such copy\n", n);
                return 1;
            }
            i++;
        }
        else if (!strcmp(a, "-h") || !strcmp(a, "--help")) goto usage;
        else { fprintf(stderr, "bitrain bench: unknown option '%s'\n", a); goto usage; }
    }
    if (!scene || strcmp(scene, "peer") || frames < 1 || warm < 0 || w < 1 || h < 1 || w > RS_MAX_DIM || h > RS_MAX_DIM)
        goto usage;
    if (camc != 'A' && camc != 'a' && camc != 'B' && camc != 'b') goto usage;
    ps = (peer_scene *)malloc(sizeof *ps);
    v = (rs_vertex *)malloc(sizeof(rs_vertex) * PEER_NV);
    cache = (rs_cvert *)malloc(rs_cache_mem_size(PEER_NV));
    color = malloc((size_t)w * (size_t)h * 4);
    zbuf = malloc((size_t)w * (size_t)h * 4);
    ms = (double *)malloc(sizeof(double) * (size_t)frames);
    if (!ps || !v || !cache || !color || !zbuf || !ms) { fprintf(stderr, "bitrain bench: out of memory\n"); return 1; }
    if (peer_scene_build(dem, ps) != 0) return 1;
    peer_scene_raster(ps, v, prims);
    if (peer_frame(camc, w, h, v, prims, &f) != 0) { fprintf(stderr, "bitrain bench: bad camera\n"); return 1; }
    f.cache = cache; f.fmt = fmt; f.depth = depth; f.no_cull = !cull;
    if (bands > 0) {   /* band mode: with the chunk table, bands skip what misses them */
        mem = malloc(rs_band_mem_size(w, bands, fmt, depth));
        f.chunks = malloc(rs_chunk_mem_size(prims, PEER_NSTRIP));
        if (!mem || !f.chunks) return 1;
    }
    for (i = -warm; i < frames; i++) {   /* i < 0: untimed warm-up, outside bench_frame */
        double t0 = now_ms();
        br_status s;
        if (bands > 0) {
            s = rs_frame_prepare(&f);
            if (s == BR_OK) s = rs_render(&f, bands, mem, bench_band_sink, NULL);
        } else s = i < 0 ? warm_frame(&f, color, zbuf) : bench_frame(&f, color, zbuf);
        if (s != BR_OK) { fprintf(stderr, "bitrain bench: render failed (%d)\n", (int)s); return 1; }
        if (i >= 0) ms[i] = now_ms() - t0;
    }
    qsort(ms, (size_t)frames, sizeof *ms, cmp_d);
    {
        double med = frames & 1 ? ms[frames / 2] : 0.5 * (ms[frames / 2 - 1] + ms[frames / 2]);
        printf("bitrain camera=%c size=%dx%d cull=%d format=%s depth=%d bands=%d frames=%d ms/frame=%.3f "
               "Mtri/s=%.1f Mpix/s=%.1f drawn_tris=%u clipped=%u span_px=%u isa=%s\n",
               camc, w, h, cull, fmt == RS_FMT_RGB565 ? "rgb565" : "rgb888", depth == RS_DEPTH16 ? 16 : 32,
               bands, frames, med, PEER_NTRI / med / 1e3, (double)w * h / med / 1e3,
               f.stat_tris, f.stat_clipped, f.stat_pixels, rs_isa_name(rs_isa()));
    }
    if (out) {
        br_err err;
        uint8_t *rgb = (uint8_t *)malloc((size_t)w * (size_t)h * 3);
        if (!rgb) return 1;
        if (bands > 0) bench_frame(&f, color, zbuf);
        for (i = 0; i < h; i++)
            rs_to_rgb888(fmt, (uint8_t *)color + (size_t)i * (size_t)w * (fmt == RS_FMT_RGB565 ? 2 : 4), w,
                         rgb + (size_t)i * (size_t)w * 3);
        if (png_write_rgb(out, w, h, rgb, (size_t)w * 3, &err) != BR_OK) {
            fprintf(stderr, "bitrain bench: %s\n", err.msg);
            return 1;
        }
        free(rgb);
    }
    free(ps); free(v); free(f.cache); free(color); free(zbuf); free(ms); free(mem); free(f.chunks);
    return 0;
usage:
    fprintf(stderr, "usage: bitrain bench --scene peer --camera A|B --size WxH --frames N [--cull]\n"
                    "       [--format rgb888|rgb565] [--depth 32|16] [--bands ROWS] [-o last.png] [--dem fuji.png]\n"
                    "       [--warmup W]   (W untimed frames first, default 3)\n"
                    "       [--isa auto|x86-64|x86-64-v3]   (the copy of the drawing code, default auto)\n");
    return 2;
}
