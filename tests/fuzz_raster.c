/* tests/fuzz_raster.c — libFuzzer harness for raster/ (see tests/fuzz.sh): the input
 * chooses a small frame (size, pixel format, depth size or none, culling, texture, chunk table,
 * band height), a camera and a few vertices with strip or list indices, anywhere within
 * the documented limits (|coord| <= CAM_COORD_MAX, texture coordinates 0 .. w * 256).
 * Findings: any sanitizer report, and a banded frame whose bytes differ from the whole
 * frame's (abort). */
#include <stdlib.h>
#include <string.h>
#include "raster/raster.h"
#include "core/cam.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct rd {
    const uint8_t *p;
    size_t n;
} rd;

static uint32_t u8(rd *r)
{
    if (!r->n) return 0;
    r->n--;
    return *r->p++;
}

static uint32_t u32(rd *r)
{
    uint32_t v = u8(r);
    v |= u8(r) << 8;
    v |= u8(r) << 16;
    return v | u8(r) << 24;
}

/* A coordinate at the terrain's scale, at a larger one, anywhere, or at the limit. */
static int32_t coord(rd *r)
{
    uint32_t sel = u8(r), v = u32(r);
    switch (sel & 3) {
    case 0: return (int32_t)(v % 2001u) - 1000;
    case 1: return (int32_t)(v % 2000001u) - 1000000;
    case 2: return (int32_t)(v % (2u * (uint32_t)CAM_COORD_MAX + 1u)) - CAM_COORD_MAX;
    default: return sel & 4 ? CAM_COORD_MAX : -CAM_COORD_MAX;
    }
}

#define MAXV 40
#define MAXI 64

static const uint32_t texels[12] = { 0xff0000, 0x00ff00, 0x0000ff, 0xffffff, 0x808080, 0x102030,
                                     0xffff00, 0x00ffff, 0xff00ff, 0x000000, 0x7f7f7f, 0x123456 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    rd r;
    rs_frame f;
    rs_vertex v[MAXV];
    uint32_t idx[2][MAXI];
    rs_prim pr[2];
    rs_texture tex;
    cam c;
    int32_t eye[3], tgt[3], fovy, zn, zf, rows, k, i;
    size_t bpp, px, cb;
    uint8_t *full = NULL, *band = NULL, *zb = NULL, *mem = NULL;
    uint32_t nv;

    r.p = data; r.n = size;
    memset(&f, 0, sizeof f);
    f.w = 1 + (int32_t)(u8(&r) % 96u);
    f.h = 1 + (int32_t)(u8(&r) % 96u);
    k = (int32_t)u8(&r);
    f.fmt = k & 1 ? RS_FMT_RGB565 : RS_FMT_XRGB8888;
    f.depth = k & 2 ? RS_DEPTH16 : RS_DEPTH32;
    f.no_cull = (k >> 2) & 1;
    tex.w = 4; tex.h = 3; tex.px = texels;
    if (k & 8) f.tex = &tex;
    else if (k & 16) f.depth = RS_DEPTH_NONE;   /* no depth: lists only, drawn in order */
    rows = 1 + (int32_t)(u8(&r) % (uint32_t)f.h);
    f.clear_rgb = u32(&r) & 0xffffffu;
    for (i = 0; i < 3; i++) eye[i] = coord(&r);
    for (i = 0; i < 3; i++) tgt[i] = coord(&r);
    fovy = 1000 + (int32_t)(u32(&r) % 169001u);
    zn = 1 + (int32_t)(u32(&r) % (u8(&r) & 1 ? 1000u : 1000000u));
    zf = zn + 1 + (int32_t)(u32(&r) % (uint32_t)(INT32_MAX - zn));
    if (cam_look_at(&c, eye, tgt, fovy, f.w, f.h, zn, zf) != BR_OK) return 0;
    cam_viewproj(&c, &f.vp);

    nv = 1 + u8(&r) % MAXV;
    for (i = 0; i < (int32_t)nv; i++) {
        v[i].p[0] = coord(&r); v[i].p[1] = coord(&r); v[i].p[2] = coord(&r);
        v[i].rgb = u32(&r) & 0xffffffu;
        v[i].uv[0] = (int32_t)(u32(&r) % (uint32_t)(tex.w * 256 + 1));
        v[i].uv[1] = (int32_t)(u32(&r) % (uint32_t)(tex.h * 256 + 1));
    }
    f.nprims = 1 + (int32_t)(u8(&r) & 1);
    for (k = 0; k < f.nprims; k++) {
        pr[k].kind = (u8(&r) & 1) || f.depth == RS_DEPTH_NONE ? RS_LIST : RS_STRIP;
        pr[k].n = u8(&r) % (MAXI + 1);
        for (i = 0; i < (int32_t)pr[k].n; i++) idx[k][i] = u8(&r) % nv;
        pr[k].idx = idx[k];
    }
    f.v = v; f.nv = nv; f.prims = pr;
    f.cache = malloc(rs_cache_mem_size(nv));
    f.chunks = malloc(rs_chunk_mem_size(pr, f.nprims));
    f.one_band = u8(&r) & 1;    /* its chunk table "every row": bands still exact */
    bpp = f.fmt == RS_FMT_RGB565 ? 2 : 4;
    px = (size_t)f.w * (size_t)f.h;
    cb = px * bpp;
    full = malloc(cb);
    band = malloc(cb);
    zb = malloc(px * 4);
    mem = malloc(rs_band_mem_size(f.w, rows, f.fmt, f.depth));
    if (!f.cache || !f.chunks || !full || !band || !zb || !mem) abort();
    if (rs_frame_prepare(&f) != BR_OK) abort();        /* every input here is within the contract */
    if (rs_draw_band(&f, 0, f.h, full, (size_t)f.w * bpp, f.depth == RS_DEPTH_NONE ? NULL : zb, NULL) != BR_OK) abort();
    for (k = 0; k < f.h; k += rows) {
        int32_t n = f.h - k < rows ? f.h - k : rows;
        if (rs_draw_band(&f, k, n, band + (size_t)k * (size_t)f.w * bpp, (size_t)f.w * bpp, mem, NULL) != BR_OK) abort();
    }
    if (memcmp(full, band, cb) != 0) abort();           /* bands must give the whole frame's bytes */
    free(f.cache); free(f.chunks); free(full); free(band); free(zb); free(mem);
    return 0;
}
