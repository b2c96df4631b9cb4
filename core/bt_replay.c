/* core/bt_replay.c — a part's mesh of the last frame made this frame's without its
 * walk (bti_part_replay; the proof is docs/bitree.md "Part replay"): its recorded
 * decisions made again, its split vertices' heights and weights updated. */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/bt_em.h"

/* Vertex i of part mesh pm gets height z and weight morph (its state as vid_find sets it);
 * its bit in moved (NULL: none) is set. */
static void set_height(bt_mesh *pm, uint8_t *moved, uint32_t i, int32_t z, uint16_t morph)
{
    bt_vert *v = &pm->v[i];
    const uint8_t st = morph == BT_MORPH_ONE ? BT_S : BT_F;
    if (moved) moved[i >> 3] |= (uint8_t)(1u << (i & 7));
    v->z = z;
    v->morph = morph;
    if (st != v->state) {
        if (st == BT_F) pm->nfict++;
        else pm->nfict--;
        v->state = st;
    }
}

/* Vertex i's bit in a replay's moved bits (set_height) */
static inline unsigned moved_bit(const uint8_t *moved, uint32_t i) { return (moved[i >> 3] >> (i & 7)) & 1u; }

/* Record r's decision made again under plane mask *mask (then the mask handed on): its
 * answer when the entry it holds proves it, as decide_memo's frame coherence would from
 * the memo (an entry is a proof however it is kept), else through the memo.  *same is
 * set when the weight is the record's own, unchanged. */
static inline int replay_decide(bti_extract *e, const bti_wtab *wt, bti_rec *r, unsigned *mask, uint16_t *morph,
                                int *same)
{
    int sp;
    *same = 0;
    (void)wt;               /* (BR_COHERENCE 0: no weight is kept) */
#if BR_COHERENCE
    if (bti_coh_proves(e, r->w, r->sp, r->idx, r->pbit, mask)) {
        /* a split whose weight moves with the distance: the weight again when the
         * distance has left the run that gives the last one (bti_coh_weight_run) */
        *same = 1;
        if ((r->w & BTI_COH_MOVING) && e->coh_acc > r->wexp) {
            int64_t d;
            if (!r->terms) { bti_morph_terms(e, r->x, r->y, r->idx, r->lo, r->hi, &r->lhs); r->terms = 1; }
            d = bti_box_dist(e->p->c->eye, r->lo, r->hi);
            if (d < r->wdlo || d > r->wdhi) {
                const uint16_t w = bti_morph_at(e, r->lhs, d);
                bti_coh_weight_run(wt, r->lhs, w, &r->wdlo, &r->wdhi);
                *same = w == r->morph0;
                r->morph0 = w;
            }
            /* the distance moves by at most the eye's L1 travel (core/bt_coh.c (1)); an
             * empty run (d outside it) holds for this frame only */
            r->wexp = d < r->wdlo || d > r->wdhi ? 0
                    : e->coh_acc + (uint64_t)(d - r->wdlo < r->wdhi - d ? d - r->wdlo : r->wdhi - d);
        }
        *morph = r->morph0;
        return r->sp;
    }
#endif
    sp = bti_decide_memo(e, r->x, r->y, r->idx, mask, morph);
    r->w = bti_memo_w(e->m, r->idx);
    r->morph0 = *morph;
    r->wdlo = 1;
    r->wdhi = 0;
    r->wexp = 0;
    return sp;
}

/* Corner j of root r in record order: 0 a, 1 c, 2 b (BTI_REF_A + j) */
static inline const bti_pt *root_corner(const bti_root *r, uint32_t j)
{
    return j == 0 ? &r->a : j == 1 ? &r->c : &r->b;
}

/* The height of a split's hypotenuse end: a root corner (BTI_REF_*) or an earlier record */
static inline int32_t ref_z(const bti_root *rt, const bti_rec *R, uint32_t ref)
{
    return ref >= BTI_REF_A ? root_corner(rt, ref - BTI_REF_A)->z : R[ref].z;
}

/* Whether that end's height moved in this replay (moved[]: root corners a, c, b) */
static inline int ref_moved(const int moved[3], const bti_rec *R, uint32_t ref)
{
    return ref >= BTI_REF_A ? moved[ref - BTI_REF_A] : R[ref].moved;
}

/* Part k's mesh of the last frame with its split vertices' heights and weights
 * updated, when that is this frame's: 1 then, else 0 (walk it).  The walk's decisions
 * are a function of the diamond, the plane mask it is decided under, the camera and
 * ST_PREV (decide_memo), and its course a function of their answers: from the same
 * root, the same answers and masks at every decision in the same order mean the same
 * leaves, vertices, strip, split list and snapshots; only the heights of split
 * vertices (their weights and their hypotenuse ends') move.  So the recorded
 * decisions are made again in order, through the memo as the walk would (the same
 * entries result), and the first that differs sends the part to its walk (0, as
 * when it cannot be tried). */
int bti_part_replay(bt_parts *ps, uint32_t k)
{
    bt_mesh *pm = &ps->slot[k].m;
    bti_rec *R = ps->slot[k].rec;
    const bti_root *rt = &ps->root[k], *lr = &ps->slot[k].last_root;
    bti_extract e;
    uint32_t i, n = ps->slot[k].nrec, j, nmoved = 0;
    uint8_t *vm = ps->slot[k].vmoved;
    int moved[3];
    if (!ps->slot[k].reuse || !ps->e0.coh || ps->coh.fresh || ps->e0.coh_acc == UINT64_MAX
        || !bti_same_root(rt, lr) || pm->memo_gen >= 0xFFFFu)
        return 0;
    ps->slot[k].reuse = 0;       /* until the replay succeeds */
    pm->memo_gen++;
    e = ps->e0;
    e.m = pm;
    for (j = 0; j < 3; j++) {
        const bti_pt *q = root_corner(rt, j), *o = root_corner(lr, j);
        moved[j] = q->z != o->z || q->morph != o->morph;
    }
    if (pm->nv <= ps->vbits) memset(vm, 0, (pm->nv + 7) >> 3);
    else vm = NULL;
    for (i = 0; i < n; i++) {
        bti_rec *r = &R[i];
        unsigned mask = r->cref >= BTI_REF_A ? rt->mask : R[r->cref].m_out;  /* as the walk hands it on */
        uint16_t morph;
        int32_t z;
        int same;
        if (replay_decide(&e, &ps->wt, r, &mask, &morph, &same) != r->sp) return 0;
        r->m_out = (uint8_t)mask;
        if (r->sp != 1) continue;
        /* the same weight between ends that stayed: the same height (bti_mid_z) */
        if (same && !ref_moved(moved, R, r->aref) && !ref_moved(moved, R, r->bref)) {
            r->moved = 0;
            continue;
        }
        z = bti_mid_z(&e, ref_z(rt, R, r->aref), ref_z(rt, R, r->bref), r->x, r->y, &morph);
        r->moved = z != r->z || morph != r->morph;
        r->z = z;
        r->morph = morph;
        if (r->moved && r->vidx != BTI_NO_IDX) { set_height(pm, vm, r->vidx, z, morph); nmoved++; }
    }
    for (j = 0; j < 3; j++) {
        const bti_pt *q = root_corner(rt, j);
        if (moved[j] && ps->slot[k].ridx[j] != BTI_NO_IDX) {
            set_height(pm, vm, ps->slot[k].ridx[j], q->z, q->morph);
            nmoved++;
        }
    }
    /* the strip writer read heights only in these tests: the same answers, the same
     * strip (a test of three vertices whose heights stayed gives its answer again) */
    for (i = 0; nmoved && i < pm->nz; i++) {
        const bti_ztest *t = &pm->zlog[i];
        int now;
        if (vm && !(moved_bit(vm, t->a) | moved_bit(vm, t->b) | moved_bit(vm, t->c))) continue;
        now = t->kind == 0 ? bti_rim_line(&e, t->a, t->b, t->c) : bti_flat(&pm->v[t->a], &pm->v[t->b], &pm->v[t->c]);
        if (now != t->answer) return 0;
    }
    ps->slot[k].last_root = *rt;
    ps->slot[k].reuse = 1;
    return 1;
}
