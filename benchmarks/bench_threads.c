#define _POSIX_C_SOURCE 200809L   /* clock_gettime */
/* benchmarks/bench_threads.c — what N drawing threads (platform/pipe_threads.h) buy on
 * the default scene (assets/N47E009.hgt.gz) at 640x480 in 64-row bands, along a flight
 * around the tile (24 cameras on a circle 45 km out and 25 km up, looking at its centre).
 *
 * Per camera the frame is prepared once (selection and vertices: serial), then its
 * raster (the driver: terrain pass, sink copying into a frame buffer) is timed with 1
 * and N threads interleaved, R times each, taking the median of each, so that the
 * load of a shared machine falls on both alike.  Prints the ratios: raster only, and
 * the whole frame (serial selection + vertices + raster), and what limits them: the
 * serial share, bands without triangles, and the time threads wait for their turn at
 * the sink.
 *   bench_threads [N [R]]     (default: online cores, 5) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "platform/clock.h"
#include "platform/pipe_threads.h"
#include "platform/scene.h"

#define W 640
#define H 480
#define BAND 64
#define NCAM 24

static uint32_t *frame_px;

static br_status sink(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    int32_t y;
    (void)user;
    for (y = 0; y < rows; y++) memcpy(frame_px + (size_t)(y0 + y) * W, (const uint8_t *)px + (size_t)y * stride, W * 4);
    return BR_OK;
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : pt_online_cores(), reps = argc > 2 ? atoi(argv[2]) : 5, ci, r, t;
    const char *in[1] = { "assets/N47E009.hgt.gz" };
    scene s;
    scene_opts o;
    br_err err;
    pt_pool *p1, *pn;
    rs_prim cap;
    int16_t *chunks;
    double sum1 = 0, sumn = 0, sum_serial = 0, wait = 0, draw = 0;
    long bands_all = 0, bands_empty = 0;
    void *bm;
    size_t bms;
    if (n < 2) n = 2;
    if (reps < 1) reps = 1;
    memset(&o, 0, sizeof o);
    o.quiet = 1;
    if (scene_open(&s, in, 1, &o, &err) != BR_OK || scene_tree(&s, &err) != BR_OK || scene_reserve(&s, 2000000, &err) != BR_OK) {
        fprintf(stderr, "bench_threads: %s\n", err.msg);
        return 1;
    }
    cap.kind = RS_STRIP; cap.n = s.mesh.cap_s; cap.idx = NULL;
    chunks = malloc(rs_chunk_mem_size(&cap, 1) + 4);
    frame_px = malloc((size_t)W * H * 4);
    if (!chunks || !frame_px || pt_open(&p1, 1) != BR_OK || pt_open(&pn, n) != BR_OK) return 1;
    bms = rs_band_mem_size(W, BAND, RS_FMT_XRGB8888, RS_DEPTH32) + 1024;
    bm = malloc(bms);
    for (ci = 0; ci < NCAM; ci++) {
        double a = 6.283185307179586 * ci / NCAM, eye[3], tgt[3], t1[16], tn[16], t0;
        cam c;
        bt_params bp;
        rs_frame fr;
        rs_prim prim;
        rs_pass terrain;
        rs_pipe pp;
        int32_t y0;
        tgt[0] = 0.5 * s.width_m; tgt[1] = 0.5 * s.depth_m; tgt[2] = 0.5 * (s.zmin_m + s.zmax_m);
        eye[0] = tgt[0] + 45000 * sin(a); eye[1] = tgt[1] + 45000 * cos(a); eye[2] = tgt[2] + 25000;
        memset(&bp, 0, sizeof bp);
        memset(&fr, 0, sizeof fr);
        memset(&pp, 0, sizeof pp);
        if (scene_camera(&s, eye, tgt, 60, W, H, &c) != BR_OK) return 1;
        fr.fmt = RS_FMT_XRGB8888; fr.depth = RS_DEPTH32; fr.clear_rgb = 0x99ccffu; fr.chunks = chunks;
        t0 = br_now_ms();
        if (scene_frame(&s, &c, &bp, &fr, &prim) != BR_OK) return 1;
        sum_serial += br_now_ms() - t0;
        rs_pass_terrain(&terrain, &fr);
        pp.w = W; pp.h = H; pp.fmt = RS_FMT_XRGB8888; pp.depth = RS_DEPTH32;
        rs_pipe_add(&pp, &terrain);
        for (y0 = 0; y0 < H; y0 += BAND) {
            rs_band b;
            rs_band_stats st;
            rs_pipe_band(&pp, y0, H - y0 < BAND ? H - y0 : BAND, bm, bms, &b, &st);
            bands_all++;
            bands_empty += st.tris == 0;
        }
        if (reps > 16) reps = 16;
        for (r = 0; r < reps; r++) {       /* interleaved: 1, N, 1, N, ... */
            const pt_thread_time *tt;
            t0 = br_now_ms(); pt_run(p1, &pp, BAND, sink, NULL, NULL); t1[r] = br_now_ms() - t0;
            t0 = br_now_ms(); pt_run(pn, &pp, BAND, sink, NULL, NULL); tn[r] = br_now_ms() - t0;
            tt = pt_last_times(pn);
            for (t = 0; t < n; t++) { wait += tt[t].wait_ms / reps; draw += tt[t].draw_ms / reps; }
        }
        qsort(t1, (size_t)reps, sizeof t1[0], br_cmp_double);
        qsort(tn, (size_t)reps, sizeof tn[0], br_cmp_double);
        sum1 += t1[reps / 2];
        sumn += tn[reps / 2];
    }
    printf("bench_threads: N47E009 640x480, bands of %d rows, %d cameras, %d runs each (medians), %d online cores\n",
           BAND, NCAM, reps, pt_online_cores());
    printf("  raster: 1 thread %.2f ms/frame, %d threads %.2f ms/frame: speed-up %.2fx\n", sum1 / NCAM, n, sumn / NCAM, sum1 / sumn);
    printf("  whole frame with serial selection + vertices (%.2f ms/frame): speed-up %.2fx\n", sum_serial / NCAM,
           (sum_serial + sum1) / (sum_serial + sumn));
    printf("  bands without triangles: %ld of %ld; %d threads: %.1f%% of thread time waiting for the sink's turn\n",
           bands_empty, bands_all, n, 100 * wait / (wait + draw + 1e-9));
    pt_close(p1);
    pt_close(pn);
    free(chunks); free(frame_px); free(bm);
    scene_close(&s);
    return 0;
}
