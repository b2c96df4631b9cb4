/* raster/terrain_stream.c — see terrain_stream.h. */
#include "raster/terrain_stream.h"
#include <string.h>

static size_t up8(size_t n) { return (n + 7) & ~(size_t)7; }

/* Hash slots: the least power of two >= 2 cap_v (at most half full) */
static uint32_t slots_for(uint32_t cap_v)
{
    uint32_t n = 1;
    while (n < 2 * cap_v) n <<= 1;
    return n;
}

static size_t list_bytes(uint32_t cap_t, rs_prim *pr)
{
    pr->kind = RS_LIST; pr->n = 3 * cap_t; pr->idx = NULL;
    return up8(rs_chunk_mem_size(pr, 1));
}

size_t rt_stream_mem_size(uint32_t cap_v, uint32_t cap_t)
{
    rs_prim pr;
    uint32_t ns;
    if (cap_v < 3 || cap_v > 4096 || cap_t < 1 || cap_t > (1u << 20)) return 0;
    ns = slots_for(cap_v);
    return up8(sizeof(rs_vertex) * cap_v) + up8(rs_cache_mem_size(cap_v)) + up8((size_t)3 * cap_t * sizeof(br_index))
         + list_bytes(cap_t, &pr) + up8((size_t)ns * 4) + up8((size_t)ns * 2);
}

br_status rt_stream_init(rt_stream *s, uint32_t cap_v, uint32_t cap_t, void *mem, size_t mem_bytes)
{
    uint8_t *p = (uint8_t *)mem;
    const size_t need = rt_stream_mem_size(cap_v, cap_t);
    uint32_t ns;
    if (!s || !mem || !need || mem_bytes < need || ((uintptr_t)mem & 7)) return BR_E_ARG;
    ns = slots_for(cap_v);
    s->cap_v = cap_v; s->cap_t = cap_t; s->hmask = ns - 1;
    s->v = (rs_vertex *)(void *)p; p += up8(sizeof(rs_vertex) * cap_v);
    s->cache = (rs_cvert *)(void *)p; p += up8(rs_cache_mem_size(cap_v));
    s->idx = (br_index *)(void *)p; p += up8((size_t)3 * cap_t * sizeof(br_index));
    s->chunks = (int16_t *)(void *)p; p += list_bytes(cap_t, &s->prim);
    s->hkey = (uint32_t *)(void *)p; p += up8((size_t)ns * 4);
    s->hval = (uint16_t *)(void *)p;
    s->nv = s->nt = 0;
    s->leaves = s->batches = 0;
    return BR_OK;
}

/* Draws the batch into the band (the first of a band clears it), then empties it.  After
 * an error the band draws nothing more (its batches are emptied, s->err kept). */
static void flush(rt_stream *s)
{
    rs_frame *f = &s->fr;
    br_status st;
    if (s->err != BR_OK) {
        s->nv = s->nt = 0;
        return;
    }
    if (s->nt == 0 && s->cleared) return;
    s->prim.kind = RS_LIST; s->prim.n = 3 * s->nt; s->prim.idx = s->idx;
    f->v = s->v; f->nv = s->nv; f->cache = s->cache;
    f->prims = &s->prim; f->nprims = 1; f->chunks = s->chunks;
    f->one_band = 1;            /* drawn in this band only: no rows per chunk */
    f->no_clear = s->cleared;
    st = rs_frame_prepare(f);
    if (st == BR_OK) st = rs_draw_band(f, s->band->y0, s->band->rows, s->band->color, s->band->stride,
                                       s->band->depth, s->st);
    s->err = st;
    s->cleared = 1;
    s->batches++;
    s->nv = s->nt = 0;
    if (++s->gen >= (1u << 20)) s->err = BR_E_NOMEM;     /* tags hold 20 bits of it */
    memset(s->hkey, 0, ((size_t)s->hmask + 1) * 4);
}

/* The batch index of point q: its tag when this batch gave it one, else the hash's,
 * else a new vertex, shaded (bt_svert.tag: gen << 12 | index, gen >= 1, index < 4096) */
static uint32_t vertex(rt_stream *s, bt_svert *q)
{
    uint32_t key, h, i;
    if ((q->tag >> 12) == s->gen) return q->tag & 0xfffu;
    key = (uint32_t)q->y * s->n_key + (uint32_t)q->x + 1u;
    h = (key * 2654435761u) >> 16 & s->hmask;
    while (s->hkey[h]) {
        if (s->hkey[h] == key) {
            i = s->hval[h];
            q->tag = s->gen << 12 | i;
            return i;
        }
        h = (h + 1) & s->hmask;
    }
    i = s->nv++;
    s->hkey[h] = key;
    s->hval[h] = (uint16_t)i;
    rt_vertex(s->scene, q->x, q->y, q->z, &s->v[i]);
    q->tag = s->gen << 12 | i;
    return i;
}

static void on_leaf(void *user, bt_svert *a, bt_svert *b, bt_svert *c)
{
    rt_stream *s = (rt_stream *)user;
    br_index *t;
    if (s->nt == s->cap_t || s->nv + 3 > s->cap_v) flush(s);
    t = &s->idx[3 * s->nt++];
    t[0] = (br_index)vertex(s, a);
    t[1] = (br_index)vertex(s, b);
    t[2] = (br_index)vertex(s, c);
    s->leaves++;
}

static br_status stream_run(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    rt_stream *s = (rt_stream *)(uintptr_t)user;     /* its batch: one band at a time */
    int32_t win[4];
    (void)self;
    if (b->fmt != s->fr.fmt || b->depth_fmt != s->fr.depth || b->w != s->fr.w) return BR_E_ARG;
    win[0] = 0; win[1] = b->y0; win[2] = b->w; win[3] = b->y0 + b->rows;
    s->band = b; s->st = st;
    s->cleared = 0; s->err = BR_OK;
    s->nv = s->nt = 0;
    s->gen = 1;                 /* the walk's points start with tag 0 */
    s->n_key = (uint32_t)s->scene->f->w;
    memset(s->hkey, 0, ((size_t)s->hmask + 1) * 4);
    (void)bt_stream_walk(s->walk, win, on_leaf, s);
    flush(s);
    return s->err;
}

br_status rt_stream_pipe(rt_stream *s, const cam *c, int32_t fmt, int32_t depth, uint32_t clear_rgb, rs_pipe *pipe)
{
    rs_pass pass;
    br_status st;
    if (!s || !c || !pipe) return BR_E_ARG;
    memset(&s->fr, 0, sizeof s->fr);
    s->fr.w = c->w; s->fr.h = c->h; s->fr.fmt = fmt; s->fr.depth = depth;
    s->fr.clear_rgb = clear_rgb;
    cam_viewproj(c, &s->fr.vp);
    memset(pipe, 0, sizeof *pipe);
    pipe->w = c->w; pipe->h = c->h; pipe->fmt = fmt; pipe->depth = depth;
    if ((st = rs_pass_stream(&pass, s)) != BR_OK) return st;
    return rs_pipe_add(pipe, &pass);
}

br_status rs_pass_stream(rs_pass *pass, rt_stream *s)
{
    if (!pass || !s || !s->scene || !s->walk || !s->v) return BR_E_ARG;
    memset(pass, 0, sizeof *pass);
    pass->name = "terrain";
    pass->run = stream_run;
    pass->user = s;
    return BR_OK;
}
