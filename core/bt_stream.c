/* core/bt_stream.c — the view selection streamed to a callback, one window of the
 * screen at a time, without a mesh (contract: core/bitree.h "streamed walk").
 *
 * The walk is core/bt_mesh.c's rec with the view rule (decide, memoised): the same
 * diamonds split, the same geomorph heights (bti_mid_z), the same leaves in the same
 * order.  What it leaves out is the output: no vertex array, no strip, no vertex hash,
 * no split list.  Each leaf goes to the caller as its three grid points.
 *
 * Why no hysteresis.  A split's answer depends on ST_PREV only through tau_lo; with
 * hyst_q8 = 0 (tau_lo = tau) the rule reads the diamond and the camera alone, so every
 * walk of a frame, whatever its window, gives every diamond the same answer, and the
 * union of the walks' leaves is one conforming mesh (the rule splits a set closed under
 * "parent of": monotone errors and nested volumes, bt_mesh.c).  With hysteresis a walk
 * would have to record this frame's splits for the next one, and a diamond that no
 * window visits (its volume passes each frustum plane of the frame but lies outside
 * every window's) would record nothing: the next frame's mesh, and so its pixels, would
 * depend on how the screen was cut.  The geomorph already hides a split's change of
 * answer at the threshold (a vertex there sits at its fictitious height), which is what
 * hysteresis is for.
 *
 * The window.  A walk for rows [y0, y1) of the screen tests each diamond's nested
 * volume (the box view_err tests against the frustum) against the two planes through
 * the window's top and bottom edges (cam_frustum_window) and skips the subtree of one
 * that lies wholly outside either: none of its triangles can cover a pixel centre of
 * those rows.  The plane test only prunes; the decision is the whole frustum's, so the
 * same diamond splits in every window that reaches it. */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/config.h"
#include "core/bt_em.h"

struct bt_stream {
    bti_extract e;
    bt_mesh memo;           /* only memo, memo_mask and memo_gen: decide_memo's cache */
    bt_params p;            /* the frame's parameters and camera, copied (e.p points here) */
    cam c;
    cam_plane win[2];       /* the walk's window: its bottom and top planes */
    bt_stream_leaf fn;
    void *user;
    uint32_t count;
};

static size_t head_size(void)
{
    return (sizeof(bt_stream) + 7) & ~(size_t)7;
}

size_t bt_stream_mem_size(uint32_t memo_entries)
{
    if (memo_entries < 16 || (memo_entries & (memo_entries - 1)) || memo_entries > (1u << 24)) return 0;
    return head_size() + (size_t)memo_entries * 8u * BTI_MEMO_W;
}

br_status bt_stream_init(bt_stream **out, uint32_t memo_entries, void *mem, size_t mem_bytes)
{
    bt_stream *s = (bt_stream *)mem;
    const size_t need = bt_stream_mem_size(memo_entries);
    if (!out || !mem || !need || mem_bytes < need || ((uintptr_t)mem & 7)) return BR_E_ARG;
    memset(s, 0, sizeof *s);
    s->memo.memo = (uint64_t *)(void *)((uint8_t *)mem + head_size());
    s->memo.memo_mask = memo_entries - 1;
    bti_memo_clear(s->memo.memo, memo_entries);
    *out = s;
    return BR_OK;
}

br_status bt_stream_frame(bt_stream *s, bt_tree *t, const bt_params *p)
{
    br_status st;
    int i;
    if (!s || !t || !p || !p->c || p->mode != BT_VIEW || p->hyst_q8 != 0 || p->window) return BR_E_ARG;
    s->p = *p;
    s->c = *p->c;
    s->p.c = &s->c;
    if ((st = bti_setup(&s->e, t, &s->p)) != BR_OK) return st;
    /* the memo: this frame's answers only (an entry of another generation is a miss;
     * with frame coherence compiled in, no accumulator proves an older one) */
    s->e.m = &s->memo;
    s->e.coh = NULL;
    s->e.coh_acc = UINT64_MAX;
    for (i = 0; i < BT_COH_NCTR; i++) s->e.coh_ctr[i] = UINT64_MAX;
    if (++s->memo.memo_gen > 0xFFFFu) {
        bti_memo_clear(s->memo.memo, s->memo.memo_mask + 1);
        s->memo.memo_gen = 1;
    }
    return BR_OK;
}

/* 1 when diamond (x, y)'s volume lies wholly outside one of the window's planes in
 * *wmask; planes it lies wholly inside leave *wmask (its descendants' volumes nest) */
static int out_of_window(const bt_stream *s, int32_t x, int32_t y, uint32_t id, unsigned *wmask)
{
    int32_t lo[3], hi[3];
    int i, k;
    bti_dvolume(&s->e, x, y, id, lo, hi);
    for (i = 0; i < 2; i++) {
        int64_t sp, sn;
        if (!(*wmask & (1u << i))) continue;
        sp = sn = s->win[i].d;
        for (k = 0; k < 3; k++) {
            const int32_t nk = s->win[i].n[k];
            sp += (int64_t)nk * (nk >= 0 ? hi[k] : lo[k]);
            sn += (int64_t)nk * (nk >= 0 ? lo[k] : hi[k]);
        }
        if (sp < 0) return 1;
        if (sn >= 0) *wmask &= ~(1u << i);
    }
    return 0;
}

/* Leaf (a, c, b), apex c: to the caller apex first, then counter-clockwise seen from
 * +z (core/bitree.h: cross < 0 in grid (x, row)).  |dx|, |dy| <= 2^14 (BR_MAX_SIDE):
 * the cross product stays below 2^29. */
static void leaf(bt_stream *s, bt_svert *a, bt_svert *c, bt_svert *b)
{
    const int32_t cr = (a->x - c->x) * (b->y - c->y) - (a->y - c->y) * (b->x - c->x);
    s->count++;
    if (cr < 0) s->fn(s->user, c, a, b);
    else s->fn(s->user, c, b, a);
}

static void walk(bt_stream *s, bt_svert *a, bt_svert *c, bt_svert *b, unsigned mask, unsigned wmask)
{
    bti_extract *e = &s->e;
    bt_svert mm;
    uint32_t id;
    int sp;
    if ((a->x + b->x) & 1) {     /* unit legs: the hypotenuse midpoint is no sample */
        if (bti_tri_valid6(e, a->x, a->y, c->x, c->y, b->x, b->y)) leaf(s, a, c, b);
        return;
    }
    mm.x = a->x + ((b->x - a->x) >> 1);
    mm.y = a->y + ((b->y - a->y) >> 1);
    id = bti_slot(e->t, mm.x, mm.y);
    sp = bti_decide_memo(e, mm.x, mm.y, id, &mask, &mm.morph);
    if (sp < 0 || (wmask && out_of_window(s, mm.x, mm.y, id, &wmask))) return;
    if (!sp) {
        /* as rec: a leaf over padding voids is dropped */
        if (!e->nonvoid && BT_NODE_ERR(e->t->node[id]) == BT_CODE_SPLIT) return;
        if (bti_tri_valid6(e, a->x, a->y, c->x, c->y, b->x, b->y)) leaf(s, a, c, b);
        return;
    }
    mm.tag = 0;
    mm.z = bti_mid_z(e, a->z, b->z, mm.x, mm.y, &mm.morph);
    walk(s, a, &mm, c, mask, wmask);
    walk(s, c, &mm, b, mask, wmask);
}

static void corner(const bt_tree *t, int32_t x, int32_t y, bt_svert *q)
{
    q->x = x; q->y = y; q->z = bti_zreal(t, x, y); q->morph = BT_MORPH_ONE; q->tag = 0;
}

uint32_t bt_stream_walk(bt_stream *s, const int32_t window[4], bt_stream_leaf fn, void *user)
{
    bt_svert q[4];
    unsigned wmask = 0;
    const int32_t S = s->e.S;
    if (window) {
        cam_plane pl[CAM_NPLANES];
        if (window[0] < 0 || window[0] >= window[2] || window[2] > s->c.w || window[1] < 0 || window[1] >= window[3]
            || window[3] > s->c.h)
            return 0;
        cam_frustum_window(&s->c, window, pl);
        s->win[0] = pl[CAM_BOTTOM];
        s->win[1] = pl[CAM_TOP];
        wmask = 3;
    }
    s->fn = fn;
    s->user = user;
    s->count = 0;
    corner(s->e.t, 0, 0, &q[0]); corner(s->e.t, S, 0, &q[1]);
    corner(s->e.t, S, S, &q[2]); corner(s->e.t, 0, S, &q[3]);
    walk(s, &q[0], &q[1], &q[2], 0x3f, wmask);
    walk(s, &q[2], &q[3], &q[0], 0x3f, wmask);
    return s->count;
}
