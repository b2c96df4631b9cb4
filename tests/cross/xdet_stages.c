/* tests/cross/xdet_stages.c — probe stages for the bitree and the rasteriser:
 * a fidelity mesh (which reads the whole error hierarchy), a view-dependent mesh, and frames drawn
 * from it in both pixel formats and both depth sizes, each hashed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/bitree.h"
#include "raster/raster.h"
#include "raster/terrain.h"
#include "tests/cross/xdet_stages.h"

static uint32_t hash_mesh(const bt_mesh *m)
{
    uint32_t h = 2166136261u, i;
    for (i = 0; i < m->nv; i++) {
        h = xdet_fnv_i32(h, m->v[i].x); h = xdet_fnv_i32(h, m->v[i].y);
        h = xdet_fnv_i32(h, m->v[i].z); h = xdet_fnv_i32(h, m->v[i].morph);
        h = xdet_fnv_i32(h, m->v[i].state);
    }
    for (i = 0; i < m->ns; i++) h = xdet_fnv_i32(h, (int32_t)m->strip[i]);
    return h;
}

static uint32_t frame_hash(rs_frame *fr, int32_t fmt, int32_t depth, int32_t band_rows, long *terrain)
{
    size_t bpp = fmt == RS_FMT_RGB565 ? 2 : 4, dbytes = depth == RS_DEPTH16 ? 2 : 4;
    uint8_t *col = malloc((size_t)fr->w * (size_t)band_rows * bpp);
    void *zb = malloc((size_t)fr->w * (size_t)band_rows * dbytes);
    uint32_t h = 2166136261u;
    int32_t y0;
    fr->fmt = fmt;
    fr->depth = depth;
    for (y0 = 0; y0 < fr->h; y0 += band_rows) {
        int32_t rows = fr->h - y0 < band_rows ? fr->h - y0 : band_rows, y, x;
        rs_draw_band(fr, y0, rows, col, (size_t)fr->w * bpp, zb, NULL);
        /* hash pixel values, not bytes, so the hash is endian-neutral */
        for (y = 0; y < rows; y++)
            for (x = 0; x < fr->w; x++) {
                const uint8_t *p = col + ((size_t)y * (size_t)fr->w + (size_t)x) * bpp;
                uint32_t v = bpp == 2 ? *(const uint16_t *)(const void *)p : *(const uint32_t *)(const void *)p;
                h = xdet_fnv_i32(h, (int32_t)v);
                if (v != (bpp == 2 ? 0x9e7fu : 0x99ccffu)) (*terrain)++;
            }
    }
    free(col);
    free(zb);
    return h;
}

void xdet_stages(const hf *f)
{
    bt_tree t;
    bt_mesh m;
    bt_params p;
    size_t tb = bt_mem_size(f->w, f->h), sb = bt_scratch_size(f->w, f->h), mb = bt_mesh_mem_size(400000);
    void *tm = malloc(tb), *sm = malloc(sb), *mm = malloc(mb);
    rt_scene sc;
    rs_ramp ramp;
    fx_q14 sun[3];
    cam c;
    int32_t eye[3], tgt[3];
    rs_vertex *verts;
    rs_frame fr;
    rs_prim prim;
    hf_stats st;

    if (!tm || !sm || !mm) { printf("bitree out-of-memory\n"); return; }
    if (bt_build(&t, f, BT_METRIC_EXACT, tm, tb, sm, sb) != BR_OK) { printf("bitree build-failed\n"); return; }
    bt_mesh_init(&m, 400000, mm, mb);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = 5; /* 5 m: HGT units are metres */
    bt_extract(&t, &p, &m);
    printf("bitree-fidelity-5m %08lx tris %u\n", (unsigned long)hash_mesh(&m), m.ntri);

    hf_stats_get(f, &st);
    rs_ramp_default(&ramp, hf_z_to_mm(f, st.zmin), hf_z_to_mm(f, st.zmax));
    rs_sun_dir(315000, 45000, sun);
    rt_scene_init(&sc, f, &ramp, sun, FX_Q14_ONE * 3 / 10);
    /* low camera on the south-west corner looking north-east across the window */
    eye[0] = (int32_t)rt_mm_to_world(&sc, -2000000); eye[1] = (int32_t)rt_mm_to_world(&sc, -3000000);
    eye[2] = (int32_t)rt_mm_to_world(&sc, 3200000);
    tgt[0] = (int32_t)rt_mm_to_world(&sc, 16000000); tgt[1] = (int32_t)rt_mm_to_world(&sc, 24000000);
    tgt[2] = (int32_t)rt_mm_to_world(&sc, 800000);
    cam_look_at(&c, eye, tgt, 55000, 160, 120, (int32_t)rt_mm_to_world(&sc, 8000),
                (int32_t)rt_mm_to_world(&sc, 200000000));
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW;
    p.c = &c;
    p.fr = sc.fr;
    p.pixel_err_q8 = 256;
    p.morph_q8 = 128;
    bt_extract(&t, &p, &m);
    printf("bitree-view %08lx tris %u\n", (unsigned long)hash_mesh(&m), m.ntri);

    verts = malloc(sizeof *verts * (m.nv ? m.nv : 1));
    memset(&fr, 0, sizeof fr);
    rt_from_mesh(&sc, &m, verts);
    prim.kind = RS_STRIP; prim.n = m.ns; prim.idx = m.strip;
    fr.w = 160; fr.h = 120; fr.clear_rgb = 0x99ccffu;
    fr.v = verts; fr.nv = m.nv; fr.prims = &prim; fr.nprims = 1;
    fr.cache = malloc(rs_cache_mem_size(m.nv ? m.nv : 1));
    fr.chunks = malloc(rs_chunk_mem_size(&prim, 1));
    cam_viewproj(&c, &fr.vp);
    if (rs_frame_prepare(&fr) != BR_OK) { printf("raster prepare-failed\n"); return; }
    {
        long t1 = 0, t2 = 0, t3 = 0;
        uint32_t a = frame_hash(&fr, RS_FMT_XRGB8888, RS_DEPTH32, 120, &t1);
        uint32_t b = frame_hash(&fr, RS_FMT_XRGB8888, RS_DEPTH32, 7, &t2);
        uint32_t d = frame_hash(&fr, RS_FMT_RGB565, RS_DEPTH16, 16, &t3);
        printf("raster-888-z32 %08lx terrain-pixels %ld\n", (unsigned long)a, t1);
        printf("raster-888-z32-bands7 %08lx terrain-pixels %ld\n", (unsigned long)b, t2);
        printf("raster-565-z16 %08lx terrain-pixels %ld\n", (unsigned long)d, t3);
    }
    free(fr.cache);
    free(fr.chunks);
    free(verts);
    free(tm); free(sm); free(mm);
}
