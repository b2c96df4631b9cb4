/* benchmarks/bench_raster.c — bitrain's integer rasteriser on the peer scene of
 * ../shared/bench/PEERS.md (fuji.png, 257x257 grid, 131,072 triangles as 256 strips):
 * cameras A and B at 320x240 and 640x480, back-face culling off (as the peers' table)
 * and on, XRGB8888 + 32-bit depth, single thread.  Prints per configuration the median
 * ms per frame over FRAMES frames (default 30; env BENCH_FRAMES), triangles/s
 * (submitted) and pixels/s (w*h per frame), plus the band-mode memory of 320x240
 * RGB565.  With both copies of the drawing code (x86-64 builds on an AVX2 CPU:
 * raster.h rs_isa_set) each configuration runs with each, the automatic choice last.  Instructions per frame: one configuration per process with callgrind,
 *   valgrind --tool=callgrind --toggle-collect=bench_frame \
 *       ./bitrain bench --scene peer --camera A --size 640x480 --frames 10
 * (total Ir / 10), see docs/raster.md.  Figures only; never fails on time. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "benchmarks/peer_scene.h"
#include "tests/support/timing.h"
#include "core/cam.h"
#include "raster/raster.h"

int main(void)
{
    static const struct { char cam; int w, h; } cfg[] = {
        { 'A', 320, 240 }, { 'B', 320, 240 }, { 'A', 640, 480 }, { 'B', 640, 480 } };
    const char *e = getenv("BENCH_FRAMES");
    int frames = e ? atoi(e) : 30, i, k, cull, isa, nisa;
    peer_scene *ps = malloc(sizeof *ps);
    rs_vertex *v = malloc(sizeof *v * PEER_NV);
    rs_cvert *cache = malloc(rs_cache_mem_size(PEER_NV));
    int16_t *chunks = malloc(2 * sizeof(int16_t) * (PEER_NTRI / RS_CHUNK + PEER_NSTRIP));   /* >= rs_chunk_mem_size */
    void *color = malloc(640 * 480 * 4), *zbuf = malloc(640 * 480 * 4);
    double *ms = malloc(sizeof(double) * (size_t)(frames > 0 ? frames : 1));
    rs_prim prims[PEER_NSTRIP];
    if (frames < 1) frames = 1;
    if (!ps || !v || !cache || !chunks || !color || !zbuf || !ms) { printf("bench_raster: out of memory\n"); return 0; }
    if (peer_scene_build("../shared/data/dem/png/fuji.png", ps) != 0) {
        printf("bench_raster: skipped (fuji.png not found; run from the repo root)\n");
        return 0;
    }
    peer_scene_raster(ps, v, prims);
    nisa = rs_isa_set(RS_ISA_V3) == RS_ISA_V3 ? 2 : 1;
    for (isa = nisa == 2 ? RS_ISA_BASE : nisa; isa <= nisa; isa++) {     /* nisa: the automatic choice */
        if (isa == nisa) rs_isa_set(RS_ISA_AUTO);
        else rs_isa_set(isa);
        printf("bitrain raster (%s copy%s), peer scene, %d frames per configuration (median), XRGB8888 + depth32:\n",
               rs_isa_name(rs_isa()), isa == nisa ? ", the automatic choice" : "", frames);
        for (cull = 0; cull < 2; cull++)
            for (k = 0; k < 4; k++) {
                rs_frame f;
                rs_band_stats st;
                double med;
                peer_frame(cfg[k].cam, cfg[k].w, cfg[k].h, v, prims, &f);
                f.cache = cache; f.chunks = chunks; f.no_cull = !cull; f.one_band = 1;
                for (i = 0; i < frames; i++) {
                    double t0 = tm_now_ms();
                    memset(&st, 0, sizeof st);
                    rs_frame_prepare(&f);
                    rs_draw_band(&f, 0, f.h, color, (size_t)f.w * 4, zbuf, &st);
                    ms[i] = tm_now_ms() - t0;
                }
                med = tm_median(ms, frames);
                printf("  camera %c %dx%d cull=%d: %.2f ms/frame, %.1f Mtri/s, %.1f Mpix/s (%u triangles set up, %u clipped)\n",
                       cfg[k].cam, cfg[k].w, cfg[k].h, cull, med, PEER_NTRI / med / 1e3,
                       (double)cfg[k].w * cfg[k].h / med / 1e3, st.tris, st.clipped);
            }
    }
    printf("band mode 320x240 RGB565: 16-row band %zu bytes (16-bit depth) / %zu bytes (32-bit depth) + vertex cache %zu bytes\n",
           rs_band_mem_size(320, 16, RS_FMT_RGB565, RS_DEPTH16), rs_band_mem_size(320, 16, RS_FMT_RGB565, RS_DEPTH32),
           rs_cache_mem_size(PEER_NV));
    free(ps); free(v); free(cache); free(chunks); free(color); free(zbuf); free(ms);
    return 0;
}
