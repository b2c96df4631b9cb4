/* benchmarks/arm/peer_run.c — renders FRAMES frames of the peer scene from peer_dump's
 * raw file (peer_file.h) with core/ + raster/ only (no libpng, so it links statically
 * for qemu-user targets), set up exactly like peer_frame() + bitrain bench's
 * bench_frame(): XRGB8888, 32-bit depth, culling off, sky 0x99ccff, the whole frame as
 * one band of the frame driver.  Prints the checksum line of the last frame (same format as peer_dump).
 * For instruction counts run it with 1 and with 11 frames: (count(11) - count(1)) / 10
 * is one frame, everything else (file reading, set-up, checksum) cancels.
 * With "board": the configuration of a board without a framebuffer (RGB565, 16-bit
 * depth, the frame driver's bands of 16 rows in one band's memory); the checksum,
 * FNV-1a over the bytes of every band's pixels (low byte first), is taken in the
 * last frame only, where a board would send the band to its display.
 *
 *   peer_run SCENE.bin A|B WxH FRAMES [board]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "raster/frame.h"
#include "raster/raster.h"
#include "benchmarks/arm/peer_file.h"

static const unsigned char *rd_p, *rd_end;

static uint32_t get(void)
{
    uint32_t v;
    if (rd_end - rd_p < 4) { fprintf(stderr, "peer_run: file too short\n"); exit(1); }
    v = (uint32_t)rd_p[0] | (uint32_t)rd_p[1] << 8 | (uint32_t)rd_p[2] << 16 | (uint32_t)rd_p[3] << 24;
    rd_p += 4;
    return v;
}

#define BOARD_ROWS 16
static int g_board, g_sum_now;
static uint64_t g_sum = 0xcbf29ce484222325u;

/* A board's sink: where it would send the band to its display, the checksum (last frame). */
static br_status board_sink(void *user, int32_t y0, int32_t rows, const void *pixels, size_t stride)
{
    const int32_t w = *(const int32_t *)user;
    int32_t y, x;
    (void)y0;
    if (!g_sum_now) return BR_OK;
    for (y = 0; y < rows; y++) {
        const uint16_t *px = (const uint16_t *)(const void *)((const uint8_t *)pixels + (size_t)y * stride);
        for (x = 0; x < w; x++) {
            g_sum = (g_sum ^ (px[x] & 255u)) * 0x100000001b3u;
            g_sum = (g_sum ^ (px[x] >> 8)) * 0x100000001b3u;
        }
    }
    return BR_OK;
}

/* One frame through the frame driver (raster/frame.h), as platform/cmd_bench.c's
 * bench_frame (same name, so callgrind's --toggle-collect=bench_frame works here too):
 * the whole frame as one band into *b, or on a board bands of BOARD_ROWS to board_sink. */
__attribute__((noinline)) br_status bench_frame(rs_frame *f, const rs_pipe *p, void *mem, size_t size, rs_band *b,
                                                rs_band_stats *st);
__attribute__((noinline)) br_status bench_frame(rs_frame *f, const rs_pipe *p, void *mem, size_t size, rs_band *b,
                                                rs_band_stats *st)
{
    br_status s = rs_frame_prepare(f);
    if (s != BR_OK) return s;
    if (!g_board) return rs_pipe_band(p, 0, f->h, mem, size, b, st);
    return rs_pipe_run(p, BOARD_ROWS, mem, size, board_sink, &f->w, st);
}

int main(int argc, char **argv)
{
    FILE *fp;
    unsigned char *buf;
    long len;
    uint32_t nv, nstrip, slen, ncam, i, k;
    rs_vertex *v;
    rs_prim *prims;
    uint32_t *idx;
    int32_t eye[3], tg[3], fovy = 0, zn = 0, zf = 0, w, h;
    int frames, found = 0, n;
    cam c;
    rs_frame f;
    rs_pipe pipe;
    rs_pass terrain;
    rs_band band;
    rs_band_stats st;
    size_t size;
    void *mem;
    if (argc < 5 || argc > 6 || sscanf(argv[3], "%dx%d", &w, &h) != 2 || (frames = atoi(argv[4])) < 1 || w < 1 ||
        h < 1 || w > RS_MAX_DIM || h > RS_MAX_DIM || (argc == 6 && strcmp(argv[5], "board") != 0)) {
        fprintf(stderr, "usage: peer_run SCENE.bin A|B WxH FRAMES [board]\n");
        return 2;
    }
    g_board = argc == 6;
    fp = fopen(argv[1], "rb");
    if (!fp || fseek(fp, 0, SEEK_END) != 0 || (len = ftell(fp)) < 0 || fseek(fp, 0, SEEK_SET) != 0) {
        fprintf(stderr, "peer_run: %s: cannot read\n", argv[1]);
        return 1;
    }
    buf = (unsigned char *)malloc((size_t)len + 1);
    if (!buf || fread(buf, 1, (size_t)len, fp) != (size_t)len) { fprintf(stderr, "peer_run: %s: cannot read\n", argv[1]); return 1; }
    fclose(fp);
    rd_p = buf; rd_end = buf + len;
    if (get() != PF_MAGIC || get() != PF_VERSION) { fprintf(stderr, "peer_run: %s: not a peer scene file\n", argv[1]); return 1; }
    nv = get();
    if (nv == 0 || nv > (uint32_t)(len / 16)) { fprintf(stderr, "peer_run: bad vertex count\n"); return 1; }
    v = (rs_vertex *)calloc(nv, sizeof *v);
    if (!v) return 1;
    for (i = 0; i < nv; i++) {
        for (k = 0; k < 3; k++) v[i].p[k] = (int32_t)get();
        v[i].rgb = get();
    }
    nstrip = get(); slen = get();
    if (nstrip == 0 || slen < 3 || (uint64_t)nstrip * slen > (uint64_t)(rd_end - rd_p) / 4) {
        fprintf(stderr, "peer_run: bad strip table\n");
        return 1;
    }
    idx = (uint32_t *)malloc(sizeof *idx * nstrip * slen);
    prims = (rs_prim *)calloc(nstrip, sizeof *prims);
    if (!idx || !prims) return 1;
    for (i = 0; i < nstrip * slen; i++)
        if ((idx[i] = get()) >= nv) { fprintf(stderr, "peer_run: index out of range\n"); return 1; }
    for (i = 0; i < nstrip; i++) { prims[i].kind = RS_STRIP; prims[i].n = slen; prims[i].idx = idx + i * slen; }
    ncam = get();
    for (i = 0; i < ncam; i++) {
        int32_t e[3], t[3], fv, n0, f0;
        char code = (char)get();
        for (k = 0; k < 3; k++) e[k] = (int32_t)get();
        for (k = 0; k < 3; k++) t[k] = (int32_t)get();
        fv = (int32_t)get(); n0 = (int32_t)get(); f0 = (int32_t)get();
        if (code == argv[2][0] || code == argv[2][0] - 'a' + 'A') {
            memcpy(eye, e, sizeof eye); memcpy(tg, t, sizeof tg);
            fovy = fv; zn = n0; zf = f0; found = 1;
        }
    }
    if (!found) { fprintf(stderr, "peer_run: no camera '%s' in the file\n", argv[2]); return 2; }
    /* peer_frame() of benchmarks/peer_scene.c, from the integer camera */
    if (cam_look_at(&c, eye, tg, fovy, w, h, zn, zf) != BR_OK) { fprintf(stderr, "peer_run: camera refused\n"); return 1; }
    memset(&f, 0, sizeof f);
    f.w = w; f.h = h; f.no_cull = 1;
    f.fmt = g_board ? RS_FMT_RGB565 : RS_FMT_XRGB8888;
    f.depth = g_board ? RS_DEPTH16 : RS_DEPTH32;
    f.clear_rgb = 0x99ccffu;
    f.v = v; f.nv = nv; f.prims = prims; f.nprims = (int32_t)nstrip;
    cam_viewproj(&c, &f.vp);
    f.cache = (rs_cvert *)malloc(rs_cache_mem_size(nv));
    f.chunks = (int16_t *)malloc(rs_chunk_mem_size(prims, f.nprims));
    f.one_band = !g_board;
    memset(&pipe, 0, sizeof pipe);
    pipe.w = w; pipe.h = h; pipe.fmt = f.fmt; pipe.depth = f.depth;
    if (rs_pass_terrain(&terrain, &f) != BR_OK || rs_pipe_add(&pipe, &terrain) != BR_OK) return 1;
    size = rs_pipe_mem_size(&pipe, g_board ? BOARD_ROWS : h);   /* a board holds one band */
    mem = malloc(size);
    if (!f.cache || !mem || !f.chunks) { fprintf(stderr, "peer_run: out of memory\n"); return 1; }
    for (n = 0; n < frames; n++) {
        g_sum_now = n == frames - 1;
        if (bench_frame(&f, &pipe, mem, size, &band, &st) != BR_OK) { fprintf(stderr, "peer_run: render failed\n"); return 1; }
    }
    printf("camera=%c size=%dx%d checksum=%016llx drawn_tris=%u clipped=%u span_px=%u\n", argv[2][0], w, h,
           (unsigned long long)(g_board ? g_sum : pf_checksum((const uint32_t *)band.color, w, h, (size_t)w)), st.tris, st.clipped,
           st.pixels);
    free(f.chunks);
    free(buf); free(v); free(idx); free(prims); free(f.cache); free(mem);
    return 0;
}
