/* core/bt_replay.c — a part's mesh of the last frame made this frame's without its
 * walk (bti_part_replay; the proof is docs/bitree.md "Part replay"): its recorded
 * decisions made again, its split vertices' heights and weights updated; where one
 * changed, the walk taken up there (bti_part_resume, docs/bitree.md "Resuming a walk"). */
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

/* 1 when the strip writer's height tests 0 .. n - 1 of part mesh pm give their answers
 * again; with moved bits (vm, else NULL: all of them) only those that read a moved vertex
 * are made again (a test of three vertices whose heights stayed gives its answer again) */
static int ztests_hold(const bti_extract *e, const bt_mesh *pm, const uint8_t *vm, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        const bti_ztest *t = &pm->zlog[i];
        int now;
        if (vm && !(moved_bit(vm, t->a) | moved_bit(vm, t->b) | moved_bit(vm, t->c))) continue;
        now = t->kind == 0 ? bti_rim_line(e, t->a, t->b, t->c) : bti_flat(&pm->v[t->a], &pm->v[t->b], &pm->v[t->c]);
        if (now != t->answer) return 0;
    }
    return 1;
}

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
int bti_part_replay(bt_parts *ps, uint32_t k, uint32_t *at)
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
        if (replay_decide(&e, &ps->wt, r, &mask, &morph, &same) != r->sp) {
            *at = i;
            return 0;
        }
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
    /* the strip writer read heights only in these tests: the same answers, the same strip */
    if (nmoved && !ztests_hold(&e, pm, vm, pm->nz)) return 0;
    ps->slot[k].last_root = *rt;
    ps->slot[k].reuse = 1;
    return 1;
}

/* Part k's extraction state for a walk with its mesh's tables as they are (the
 * allocated ones' first hmask + 1 and memo_mask + 1 slots: core/bt_part.c part_reset) */
void bti_part_extract_setup(bt_parts *ps, uint32_t k, bti_extract *e)
{
    bt_mesh *pm = &ps->slot[k].m;
    const uint32_t hl = pm->hmask - (pm->hmask >> 2);
    *e = ps->e0;
    e->m = pm;
    e->snap = ps->slot[k].snap;
    e->recs = ps->slot[k].rec;
    e->nrec = 0;
    e->cap_rec = ps->cap_rec;
    e->hbase = ps->slot[k].hbase;
    e->direct = (uint64_t)e->n * (uint64_t)e->n <= 2 * ((uint64_t)pm->hmask + 1);
    e->lim_nv = (hl < pm->cap_v ? hl : pm->cap_v) - 6;
    e->lim_ns = pm->cap_s - 10;
}

/* The depth of the recursion below a part's root that bti_part_resume follows (the
 * tree's own depth below a part root is at most 2 BR_MAX_SIDE's 14 bits) */
#define RESUME_DEPTH 64

/* Part k's walk taken up at record `at`, the first whose answer bti_part_replay found
 * changed: 1 when done (part k's mesh is then this frame's, as a walk from its root
 * makes it), 0 when it cannot be (walk it whole).  The replay made every record before
 * `at` again with the same answer, and their vertices' heights and weights this
 * frame's; a walk from the root would make the same decisions in the same order up to
 * `at`, so the same vertices (numbered by first use), strip indices, height tests, split
 * list and leaves as the last one up to there, whose counts and writer state the record
 * keeps (bti_rec_at).  So the mesh is cut back to them (the vertex hash needs nothing:
 * bti_vid_lookup reads a slot past the vertex count as free), the height tests kept are
 * checked where the heights moved, and the recursion goes on: record `at`'s triangle,
 * then the second half of every split on its way up whose first half it lies in, as rec
 * would return through them, each split's record finished as rec finishes it. */
int bti_part_resume(bt_parts *ps, uint32_t k, uint32_t at)
{
    bt_mesh *pm = &ps->slot[k].m;
    bti_rec *R = ps->slot[k].rec;
    const bti_root *rt = &ps->root[k], *lr = &ps->slot[k].last_root;
    bti_extract *e = &ps->slot[k].e;
    const uint8_t *vm = pm->nv <= ps->vbits ? ps->slot[k].vmoved : NULL;   /* as the replay chose */
    bti_rec_at s;
    uint32_t chain[RESUME_DEPTH], d = 0, i, j, stale;
    bti_pt root[3], mm[RESUME_DEPTH], *ta[RESUME_DEPTH], *tc[RESUME_DEPTH], *tb[RESUME_DEPTH];
    int32_t in[RESUME_DEPTH], out[RESUME_DEPTH];
    uint8_t first[RESUME_DEPTH];
    if (at == 0 || at >= ps->slot[k].nrec || at >= ps->cap_rec) return 0;
    s = R[at].at;
    for (j = at;; j = R[j].cref) {                  /* `at` and its splits up to the root's */
        if (d == RESUME_DEPTH || j >= at + 1) return 0;
        chain[d++] = j;
        if (R[j].cref >= BTI_REF_A) break;
    }
    if (chain[d - 1] != 0) return 0;
    /* the root's corners: the replay sets their heights after its records, so a part
     * whose corners moved is walked whole (none did in tests/test_coherence.c's flights) */
    for (j = 0; j < 3; j++) {
        const bti_pt *q = root_corner(rt, j), *o = root_corner(lr, j);
        if (q->z != o->z || q->morph != o->morph) return 0;
        root[j] = *q;
    }
    /* the height tests before `at`: the same answers where the heights moved (the
     * extraction state depends on the mesh's tables, not on its counts) */
    bti_part_extract_setup(ps, k, e);
    if (s.nz > pm->nz || !ztests_hold(e, pm, vm, s.nz)) return 0;
    /* the mesh and the writer as they were at `at` */
    pm->nv = s.nv; pm->ns = s.ns; pm->ntri = s.ntri; pm->nline = s.nline; pm->nz = s.nz;
    pm->nsplits = s.nsplits;
    pm->overflow = 0;
    pm->nfict = 0;
    for (i = 0; i < pm->nv; i++) pm->nfict += pm->v[i].state == BT_F;
    /* the hash's load: the slots of vertices past `at` that earlier walks of its
     * generation wrote stay taken, so they count against the walk's limit (its table
     * at most 3/4 full, as a walk from the root keeps it) */
    if (ps->slot[k].hins < s.nv) return 0;
    stale = ps->slot[k].hins - s.nv;
    if (e->lim_nv <= stale + s.nv) return 0;
    e->lim_nv -= stale;
    e->nrec = at;
    e->count = s.count;
    e->nsnap = s.nsnap;
    e->has_pend = s.has_pend;
    e->pend = s.pend;
    e->nplan = 0;
    /* the recursion's triangles from the root down to `at`'s (rec's children: (a, m, c)
     * entered (!in, leg), then (c, m, b) entered (leg, !out)) */
    for (j = 0; j < 3; j++) {
        root[j].ri = BTI_REF_A + j;
        root[j].idx = bti_vid_lookup(e, root[j].x, root[j].y);
    }
    ta[0] = &root[0]; tc[0] = &root[1]; tb[0] = &root[2];
    in[0] = rt->in_hyp; out[0] = rt->out_hyp;
    for (i = 0; i + 1 < d; i++) {
        const bti_rec *P = &R[chain[d - 1 - i]], *Q = &R[chain[d - 2 - i]];
        bti_pt *m = &mm[i];
        if (P->sp != 1) return 0;
        m->x = P->x; m->y = P->y; m->z = P->z; m->morph = P->morph;
        m->ri = chain[d - 1 - i];
        m->idx = bti_vid_lookup(e, m->x, m->y);
        first[i] = Q->aref == ta[i]->ri && Q->bref == tc[i]->ri;
        if (first[i]) { ta[i + 1] = ta[i]; tc[i + 1] = m; tb[i + 1] = tc[i]; in[i + 1] = !in[i]; out[i + 1] = 0; }
        else if (Q->aref == tc[i]->ri && Q->bref == tb[i]->ri) {
            ta[i + 1] = tc[i]; tc[i + 1] = m; tb[i + 1] = tb[i]; in[i + 1] = 0; out[i + 1] = !out[i];
        } else return 0;
    }
    bti_walk_tri(e, ta[d - 1], tc[d - 1], tb[d - 1], in[d - 1], out[d - 1],
                 d > 1 ? R[chain[1]].m_out : rt->mask);
    for (i = d - 1; i-- > 0;) {                     /* back up through the splits */
        bti_rec *P = &R[chain[d - 1 - i]];
        if (first[i]) bti_walk_tri(e, tc[i], &mm[i], tb[i], 0, !out[i], P->m_out);
        P->z = mm[i].z;
        P->morph = mm[i].morph;
        P->vidx = mm[i].idx;
    }
    ps->slot[k].ridx[0] = root[0].idx; ps->slot[k].ridx[1] = root[1].idx; ps->slot[k].ridx[2] = root[2].idx;
    ps->slot[k].hins = stale + pm->nv;
    return !e->full;
}
