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
#include "platform/clock.h"
#include "platform/cmd.h"
#include "platform/opt.h"
#include "platform/png_io.h"
#include "platform/sink_frame.h"
#include "raster/frame.h"
#include "raster/raster.h"
#include "benchmarks/peer_scene.h"

/* One frame: transform, clear, draw, as one whole-frame band of the frame driver.  Not
 * static and not inlined: callgrind toggles on it. */
__attribute__((noinline)) br_status bench_frame(rs_frame *f, const rs_pipe *p, void *mem, size_t size,
                                                rs_band *b, rs_band_stats *st);
__attribute__((noinline)) br_status bench_frame(rs_frame *f, const rs_pipe *p, void *mem, size_t size,
                                                rs_band *b, rs_band_stats *st)
{
    br_status s = rs_frame_prepare(f);
    if (s != BR_OK) return s;
    return rs_pipe_band(p, 0, f->h, mem, size, b, st);
}

/* A warm-up frame outside bench_frame, so callgrind does not count it (the bodies must
 * differ, or the compiler may fold the two: this one checks the band it drew). */
__attribute__((noinline)) static br_status warm_frame(rs_frame *f, const rs_pipe *p, void *mem, size_t size,
                                                      rs_band *b, rs_band_stats *st)
{
    br_status s = rs_frame_prepare(f);
    if (s != BR_OK) return s;
    s = rs_pipe_band(p, 0, f->h, mem, size, b, st);
    return s == BR_OK && b->rows != f->h ? BR_E_ARG : s;
}

#define BENCH_SYNOPSIS "--scene peer [options]\n" \
    "  the peer benchmark scene of ../shared/bench/PEERS.md, drawn by the rasteriser alone"

int cmd_bench(int argc, char **argv)
{
    const char *out = NULL, *dem = "../shared/data/dem/png/fuji.png", *pos[1];
    char camc;
    int size[2] = { 640, 480 }, w, h, frames = 10, warm = 3, cull = 0, fmt = RS_FMT_XRGB8888, depth_choice = 0;
    int depth, bands = 0, band_rows, scene_choice = -1, cam_choice = 0, isa_choice = 0, npos, r, i;
    const opt_spec own[] = {
        { "--scene", OPT_CHOICE, &scene_choice, 0, 0, 0, "peer|default|all", "S", "the scene (peer: ../shared/bench/PEERS.md; default: `bitrain bench --scene default --help`; all or none: the board table, `bitrain bench --help`)", NULL },
        { "--camera", OPT_CHOICE, &cam_choice, 0, 0, 0, "A|B|a|b", "C", "the peer camera", NULL },
        { "--size", OPT_SIZE, size, 1, RS_MAX_DIM, 0, NULL, "WxH", "frame size (default 640x480)", NULL },
        { "--frames", OPT_INT, &frames, 1, 1000000, 0, NULL, "N", "timed frames (default 10)", NULL },
        { "--warmup", OPT_INT, &warm, 0, 1000000, 0, NULL, "W", "untimed frames first (default 3)", NULL },
        { "--cull", OPT_FLAG, &cull, 0, 0, 0, NULL, NULL, "cull back faces", NULL },
        { "--format", OPT_CHOICE, &fmt, 0, 0, 0, "rgb888|rgb565", "F", "pixel format", NULL },
        { "--depth", OPT_CHOICE, &depth_choice, 0, 0, 0, "32|16", "BITS", "depth buffer bits", NULL },
        { "--bands", OPT_INT, &bands, 0, RS_MAX_DIM, 0, NULL, "ROWS", "band mode with bands of ROWS rows (0: whole frame)", NULL },
        { "-o", OPT_STR, &out, 0, 0, 0, NULL, "OUT.png", "write the last frame", NULL },
        { "--dem", OPT_STR, &dem, 0, 0, 0, NULL, "FILE", "the peer scene's terrain (default ../shared/data/dem/png/fuji.png)", NULL },
        { "--isa", OPT_CHOICE, &isa_choice, 0, 0, 0, "auto|x86-64|x86-64-v3", "ISA", "the copy of the drawing code (default auto)", NULL },
        OPT_END
    };
    const opt_spec *const tables[] = { own, NULL };
    peer_scene *ps;
    rs_vertex *v;
    rs_prim prims[PEER_NSTRIP];
    rs_frame f;
    rs_pipe pipe;
    rs_pass terrain;
    rs_band band = { 0 };
    rs_band_stats st;
    sink_frame fc;
    size_t bpp, memsize;
    void *mem;
    double *ms;
    for (i = 0; i < argc && strcmp(argv[i], "--scene"); i++) {}
    if (i == argc || (i + 1 < argc && !strcmp(argv[i + 1], "all")))   /* the board table: bench_board.c */
        return cmd_bench_board(argc, argv);
    if (i + 1 < argc && !strcmp(argv[i + 1], "default")) return cmd_bench_default(argc, argv);   /* bench_default.c */
    r = opt_parse("bench", BENCH_SYNOPSIS, tables, argc, argv, pos, 0, &npos);
    if (r != OPT_OK) return r == OPT_HELP ? 0 : 2;
    camc = "ABab"[cam_choice];
    w = size[0];
    h = size[1];
    depth = depth_choice ? RS_DEPTH16 : RS_DEPTH32;
    bpp = fmt == RS_FMT_RGB565 ? 2u : 4u;
    band_rows = bands == 0 || bands > h ? h : bands;
    if (isa_choice) {
        int want = isa_choice == 1 ? RS_ISA_BASE : RS_ISA_V3;
        if (rs_isa_set(want) != want) {
            fprintf(stderr, "bitrain bench: --isa %s: this build or CPU has no such copy\n", isa_choice == 1 ? "x86-64" : "x86-64-v3");
            return 1;
        }
    }
    ps = (peer_scene *)malloc(sizeof *ps);
    v = (rs_vertex *)malloc(sizeof(rs_vertex) * PEER_NV);
    ms = (double *)malloc(sizeof(double) * (size_t)frames);
    if (!ps || !v || !ms) { fprintf(stderr, "bitrain bench: out of memory\n"); return 1; }
    if (peer_scene_build(dem, ps) != 0) return 1;
    peer_scene_raster(ps, v, prims);
    if (peer_frame(camc, w, h, v, prims, &f) != 0) { fprintf(stderr, "bitrain bench: bad camera\n"); return 1; }
    f.cache = (rs_cvert *)malloc(rs_cache_mem_size(PEER_NV));
    f.chunks = (int16_t *)malloc(rs_chunk_mem_size(prims, PEER_NSTRIP));
    f.fmt = fmt; f.depth = depth; f.no_cull = !cull;
    f.one_band = bands == 0;
    memset(&pipe, 0, sizeof pipe);
    pipe.w = w; pipe.h = h; pipe.fmt = fmt; pipe.depth = depth;
    if (rs_pass_terrain(&terrain, &f) != BR_OK || rs_pipe_add(&pipe, &terrain) != BR_OK) return 1;
    memsize = rs_pipe_mem_size(&pipe, band_rows);
    mem = malloc(memsize);
    fc.row_bytes = (size_t)w * bpp;
    fc.px = malloc(fc.row_bytes * (size_t)h);
    if (!f.cache || !f.chunks || !mem || !fc.px) { fprintf(stderr, "bitrain bench: out of memory\n"); return 1; }
    memset(&st, 0, sizeof st);
    for (i = -warm; i < frames; i++) {   /* i < 0: untimed warm-up, outside bench_frame */
        double t0 = br_now_ms();
        br_status s;
        if (bands > 0) {   /* band mode: the driver's band loop into fc */
            s = rs_frame_prepare(&f);
            if (s == BR_OK) s = rs_pipe_run(&pipe, band_rows, mem, memsize, sink_frame_band, &fc, &st);
        } else s = i < 0 ? warm_frame(&f, &pipe, mem, memsize, &band, &st)
                         : bench_frame(&f, &pipe, mem, memsize, &band, &st);
        if (s != BR_OK) { fprintf(stderr, "bitrain bench: render failed (%d)\n", (int)s); return 1; }
        if (i >= 0) ms[i] = br_now_ms() - t0;
    }
    qsort(ms, (size_t)frames, sizeof *ms, br_cmp_double);
    {
        double med = frames & 1 ? ms[frames / 2] : 0.5 * (ms[frames / 2 - 1] + ms[frames / 2]);
        printf("bitrain camera=%c size=%dx%d cull=%d format=%s depth=%d bands=%d frames=%d ms/frame=%.3f "
               "Mtri/s=%.1f Mpix/s=%.1f drawn_tris=%u clipped=%u span_px=%u isa=%s\n",
               camc, w, h, cull, fmt == RS_FMT_RGB565 ? "rgb565" : "rgb888", depth == RS_DEPTH16 ? 16 : 32,
               bands, frames, med, PEER_NTRI / med / 1e3, (double)w * h / med / 1e3,
               st.tris, st.clipped, st.pixels, rs_isa_name(rs_isa()));
    }
    if (out) {
        br_err err;
        uint8_t *rgb = (uint8_t *)malloc((size_t)w * (size_t)h * 3);
        if (!rgb) return 1;
        if (bands == 0) sink_frame_band(&fc, 0, h, band.color, band.stride);
        for (i = 0; i < h; i++) rs_to_rgb888(fmt, (const uint8_t *)fc.px + (size_t)i * fc.row_bytes, w, rgb + (size_t)i * (size_t)w * 3);
        if (png_write_rgb(out, w, h, rgb, (size_t)w * 3, &err) != BR_OK) {
            fprintf(stderr, "bitrain bench: %s\n", err.msg);
            return 1;
        }
        free(rgb);
    }
    free(ps); free(v); free(f.cache); free(f.chunks); free(mem); free(fc.px); free(ms);
    return 0;
}
