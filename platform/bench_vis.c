/* platform/bench_vis.c — where a frame's triangles go (see bench_vis.h). */
#include "platform/bench_vis.h"
#include <stdlib.h>
#include <string.h>
#include "platform/sink_frame.h"
#include "raster/frame.h"

#define VIS_MAX_ID 0xffffffu

/* The frame's triangles as a list in draw order (rs_prim_tri), each with its own three
 * vertices, coloured with their number 1, 2, ...; *nt of them. */
static br_status id_list(const rs_frame *f, rs_vertex **v, br_index **idx, uint32_t *nt)
{
    uint64_t cap = 0;
    uint32_t n = 0, t;
    int32_t p;
    for (p = 0; p < f->nprims; p++) cap += rs_prim_tris(&f->prims[p]);
    if (cap > VIS_MAX_ID) return BR_E_ARG;
    *v = malloc(sizeof **v * 3 * (size_t)(cap + 1));
    *idx = malloc(sizeof **idx * 3 * (size_t)(cap + 1));
    if (!*v || !*idx) return BR_E_NOMEM;
    for (p = 0; p < f->nprims; p++) {
        const rs_prim *pr = &f->prims[p];
        for (t = 0; t < rs_prim_tris(pr); t++) {
            uint32_t a, b, c, k;
            rs_prim_tri(pr, t, &a, &b, &c);
            if (a == b || b == c || a == c) continue;     /* a strip's line triangle */
            (*v)[3 * n] = f->v[a]; (*v)[3 * n + 1] = f->v[b]; (*v)[3 * n + 2] = f->v[c];
            for (k = 0; k < 3; k++) {
                (*v)[3 * n + k].rgb = n + 1;
                (*idx)[3 * n + k] = (br_index)(3 * n + k);
            }
            n++;
        }
    }
    *nt = n;
    return BR_OK;
}

/* 1 when triangle (a, b, c), screen positions in sub-pixels, covers a pixel centre (of
 * the pixels of its bounding box), edges included. */
static int covers_centre(const rs_cvert *a, const rs_cvert *b, const rs_cvert *c)
{
    const int64_t x0 = a->x, y0 = a->y, x1 = b->x, y1 = b->y, x2 = c->x, y2 = c->y;
    const int64_t h = (int64_t)1 << (RS_SUBPIX_BITS - 1);
    int64_t mnx = x0 < x1 ? x0 : x1, mxx = x0 > x1 ? x0 : x1, mny = y0 < y1 ? y0 : y1, mxy = y0 > y1 ? y0 : y1, px, py;
    mnx = mnx < x2 ? mnx : x2; mxx = mxx > x2 ? mxx : x2;
    mny = mny < y2 ? mny : y2; mxy = mxy > y2 ? mxy : y2;
    for (py = mny >> RS_SUBPIX_BITS; py <= mxy >> RS_SUBPIX_BITS; py++)
        for (px = mnx >> RS_SUBPIX_BITS; px <= mxx >> RS_SUBPIX_BITS; px++) {
            const int64_t cx = px * 2 * h + h, cy = py * 2 * h + h;
            const int64_t e0 = (x1 - x0) * (cy - y0) - (cx - x0) * (y1 - y0);
            const int64_t e1 = (x2 - x1) * (cy - y1) - (cx - x1) * (y2 - y1);
            const int64_t e2 = (x0 - x2) * (cy - y2) - (cx - x2) * (y0 - y2);
            if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0)) return 1;
        }
    return 0;
}

br_status bd_visibility(const rs_frame *f, bd_vis *acc, br_err *err)
{
    rs_frame g = *f;
    rs_prim list;
    rs_pipe pipe;
    rs_pass pass;
    sink_frame sink;
    uint32_t *px = NULL;
    rs_vertex *v = NULL;
    br_index *idx = NULL;
    uint8_t *seen = NULL;
    void *band = NULL;
    size_t need, i;
    uint32_t nt = 0, t;
    br_status st;
    memset(&sink, 0, sizeof sink);
    g.cache = NULL; g.chunks = NULL;        /* f's own: never freed here */
    if ((st = id_list(f, &v, &idx, &nt)) != BR_OK) goto out;
    list.kind = RS_LIST; list.n = 3 * nt; list.idx = idx;
    g.v = v; g.nv = 3 * nt; g.prims = &list; g.nprims = 1;
    g.fmt = RS_FMT_XRGB8888; g.tex = NULL; g.clear_rgb = 0; g.clear_rows = NULL; g.no_clear = 0;
    g.clips = NULL; g.clip_cap = 0; g.one_band = 1;
    g.cache = malloc(rs_cache_mem_size(g.nv ? g.nv : 1));
    g.chunks = malloc(rs_chunk_mem_size(&list, 1));
    seen = calloc((size_t)nt + 1, 1);
    px = malloc(sizeof *px * (size_t)g.w * (size_t)g.h);
    sink.px = px;
    sink.row_bytes = (size_t)g.w * 4;
    st = BR_E_NOMEM;
    if (!g.cache || !g.chunks || !seen || !px) goto out;
    if ((st = rs_frame_prepare(&g)) != BR_OK) goto out;
    memset(&pipe, 0, sizeof pipe);
    pipe.w = g.w; pipe.h = g.h; pipe.fmt = g.fmt; pipe.depth = g.depth;
    if ((st = rs_pass_terrain(&pass, &g)) != BR_OK || (st = rs_pipe_add(&pipe, &pass)) != BR_OK) goto out;
    need = rs_pipe_mem_size(&pipe, g.h);
    st = BR_E_NOMEM;
    if (!(band = malloc(need))) goto out;
    if ((st = rs_pipe_run(&pipe, g.h, band, need, sink_frame_band, &sink, NULL)) != BR_OK) goto out;
    for (i = 0; i < (size_t)g.w * (size_t)g.h; i++) {
        const uint32_t id = px[i] & VIS_MAX_ID;
        if (id && id <= nt) seen[id] = 1;
    }
    for (t = 0; t < nt; t++) {
        const rs_cvert *a = &g.cache[3 * t], *b = &g.cache[3 * t + 1], *c = &g.cache[3 * t + 2];
        const int64_t area = (int64_t)(b->x - a->x) * (c->y - a->y) - (int64_t)(c->x - a->x) * (b->y - a->y);
        if (seen[t + 1]) acc->seen++;
        else if (((a->c | b->c | c->c) >> 24) != 0) acc->edge++;     /* an outcode set */
        else if (!covers_centre(a, b, c)) acc->tiny++;
        else if (area >= 0) acc->back++;         /* the rasteriser's front faces: area < 0 */
        else acc->hidden++;
    }
    acc->tris += nt;
    acc->frames++;
out:
    if (st != BR_OK) br_err_set(err, st, NULL, st == BR_E_NOMEM ? "visibility: out of memory"
                                                                 : "visibility: frame not drawn again");
    free(v); free(idx); free(seen); free(g.cache); free(g.chunks); free(px); free(band);
    return st;
}
