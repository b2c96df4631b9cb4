/* core/bt_part.c — the view-dependent extraction cut into a fixed set of parts
 * that threads may extract concurrently (contract: core/bitree.h, "Partitioned
 * view extraction").
 *
 * Same selection as bt_extract.  A part is the subtree of one triangle at depth
 * BTI_PART_DEPTH below the two roots (core/bt_mesh.c bti_part_roots); its rec
 * makes the serial walk's decisions in the serial walk's order, because every
 * decision is a function of the diamond, the camera and ST_PREV alone (core/
 * bt_mesh.c decide_memo) and ST_PREV changes only in bt_extract_end.  So the
 * real triangles of the joined strip are the serial walk's leaves in order.
 *
 * Data races: between begin and end the parts write only their own part mesh and
 * extraction context and read t, p and ps->root; a diamond on the edge of two
 * parts is listed by both (its split is decided identically in both), and
 * bt_extract_end, alone, sets ST_PREV on every listed id (idempotent).  Joins
 * write disjoint ranges of m->v and m->strip (the offsets of bt_extract_end). */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/bt_em.h"

/* match_slots numbers slots in a byte */
typedef char bti_parts_fit_a_byte[BT_PARTS <= 255 ? 1 : -1];

/* A part's smallest vertex hash (bt_extract_part), its memo 4 times that */
#define PART_HASH_MIN 1024u

static uint64_t round8(uint64_t v) { return (v + 7) & ~(uint64_t)7; }

/* Records of a part's walk (bti_rec): a decision a triangle of the part's room and 64;
 * a walk that makes more is not replayed (bti_part_replay), nothing else changes. */
static uint32_t rec_cap(uint32_t part_tri) { return part_tri + 64; }
/* Its strip writer's height tests (bti_ztest): one per four triangles; more: not replayed */
static uint32_t ztest_cap(uint32_t part_tri) { return part_tri / 4 + 64; }
/* A replay's moved vertices, a bit each: the root's 3 corners and a vertex a record,
 * so a replayed part has at most rec_cap + 3 (more: every test made again); whole
 * 64-bit words */
static uint32_t vbits_cap(uint32_t part_tri) { return (rec_cap(part_tri) + 3 + 63) & ~63u; }

/* Clears slot sl's hash and memo up to hs and ms slots where they are not yet (zero is
 * empty for any hash base and memo generation). */
static void clear_to(struct bti_slot *sl, uint32_t hs, uint32_t ms)
{
    if (hs > sl->hclean) {
        memset(sl->m.hash + sl->hclean, 0, (size_t)(hs - sl->hclean) * 4);
        sl->hclean = hs;
    }
    if (ms > sl->mclean) {
        bti_memo_clear(sl->m.memo + (size_t)sl->mclean * BTI_MEMO_W, ms - sl->mclean);
        sl->mclean = ms;
    }
}

/* No slot's vertices are where the caller last set them up (bt_part_moved_from): after a
 * frame not joined from parts, and at the start */
static void forget_places(bt_parts *ps)
{
    uint32_t k;
    for (k = 0; k < BT_PARTS; k++) {
        ps->slot[k].last_voff = UINT32_MAX;
        ps->slot[k].from_voff = UINT32_MAX;
    }
}

size_t bt_parts_mem_size(uint32_t part_tri)
{
    size_t mb = bt_mesh_mem_size(part_tri);
    uint64_t sz;
    if (!mb) return 0;
    sz = round8(sizeof(bt_parts)) + (uint64_t)BT_PARTS * round8(mb)
       + (uint64_t)BT_PARTS * (rec_cap(part_tri) * sizeof(bti_rec) + round8(ztest_cap(part_tri) * sizeof(bti_ztest))
                               + round8(vbits_cap(part_tri) / 8))
       + 3 * round8((uint64_t)rec_cap(part_tri) * 4);     /* regroup's counts */
    if (sz > (uint64_t)SIZE_MAX) return 0;
    return (size_t)sz;
}

br_status bt_parts_init(bt_parts **out, uint32_t part_tri, void *mem, size_t mem_bytes)
{
    uint8_t *q = (uint8_t *)mem;
    size_t mb = bt_mesh_mem_size(part_tri), need = bt_parts_mem_size(part_tri);
    bt_parts *ps;
    int k;
    if (!out || !mem || !need || mem_bytes < need || ((uintptr_t)mem & 7) != 0) return BR_E_ARG;
    ps = (bt_parts *)mem;
    memset(ps, 0, sizeof *ps);
    ps->part_tri = part_tri;
    q += round8(sizeof(bt_parts));
    for (k = 0; k < BT_PARTS; k++, q += round8(mb))
        if (bti_mesh_layout(&ps->slot[k].m, part_tri, 0, 0, q, mb) != BR_OK) return BR_E_ARG;
    ps->cap_rec = rec_cap(part_tri);
    for (k = 0; k < BT_PARTS; k++, q += (size_t)ps->cap_rec * sizeof(bti_rec)) ps->slot[k].rec = (bti_rec *)(void *)q;
    for (k = 0; k < BT_PARTS; k++, q += round8(ztest_cap(part_tri) * sizeof(bti_ztest))) {
        ps->slot[k].m.zlog = (bti_ztest *)(void *)q;
        ps->slot[k].m.cap_z = ztest_cap(part_tri);
    }
    ps->vbits = vbits_cap(part_tri);
    for (k = 0; k < BT_PARTS; k++, q += round8(ps->vbits / 8)) ps->slot[k].vmoved = q;
    forget_places(ps);
    ps->cut_tris = (uint32_t *)(void *)q; q += round8((uint64_t)ps->cap_rec * 4);
    ps->cut_lo = (uint32_t *)(void *)q; q += round8((uint64_t)ps->cap_rec * 4);
    ps->cut_hi = (uint32_t *)(void *)q;
    ps->top_m.memo = ps->top_memo;          /* (zero: no entry) */
    ps->top_m.memo_mask = BTI_TOP_MEMO - 1;
    ps->hfull = ps->slot[0].m.hmask + 1;
    ps->mfull = ps->slot[0].m.memo_mask + 1;
    for (k = 0; k < BT_PARTS; k++) {     /* the smallest tables a walk uses, cleared now */
        const uint32_t hs = PART_HASH_MIN < ps->hfull ? PART_HASH_MIN : ps->hfull;
        clear_to(&ps->slot[k], hs, 4 * hs < ps->mfull ? 4 * hs : ps->mfull);
    }
    ps->cut_fresh = 1;
    *out = ps;
    return BR_OK;
}

/* Moves the slots so that root k's is the one that held root_code[k] last frame
 * (when one did); the others take the free places.  Only when the roots' codes
 * changed (a part cut or joined, one culled or back): a permutation by swaps, each
 * slot moved once at most per cycle. */
static void match_slots(bt_parts *ps)
{
    uint8_t dest[BT_PARTS], taken[BT_PARTS];
    uint32_t j, k, n = ps->nroot, free_k = 0;
    for (k = 0; k < n && ps->slot[k].code == ps->root_code[k]; k++) continue;
    if (k == n) return;
    memset(taken, 0, sizeof taken);
    for (j = 0; j < BT_PARTS; j++) {
        dest[j] = 0xFF;
        for (k = 0; k < n && ps->slot[j].code; k++)
            if (ps->root_code[k] == ps->slot[j].code) { dest[j] = (uint8_t)k; taken[k] = 1; break; }
    }
    for (j = 0; j < BT_PARTS; j++) {
        if (dest[j] != 0xFF) continue;
        while (taken[free_k]) free_k++;         /* BT_PARTS places for BT_PARTS slots */
        dest[j] = (uint8_t)free_k;
        taken[free_k] = 1;
    }
    for (j = 0; j < BT_PARTS; j++)
        while (dest[j] != j) {
            const uint32_t d = dest[j];
            struct bti_slot tmp = ps->slot[d];
            uint8_t td = dest[d];
            ps->slot[d] = ps->slot[j];
            ps->slot[j] = tmp;
            dest[d] = (uint8_t)d;
            dest[j] = td;
        }
    for (k = 0; k < BT_PARTS; k++) ps->slot[k].code = k < n ? ps->root_code[k] : 0;
}

/* The cut with no frame behind it (after bt_parts_init or bt_parts_reset), made at
 * the next bt_extract_begin: every triangle down to BTI_PART_DEPTH + extra - 1 cut,
 * 2 << (BTI_PART_DEPTH + extra) roots.  The first frame's sizes are unknown, and in a
 * view of many triangles the parts at BTI_PART_DEPTH near the eye overflow part_tri
 * (a full part sends the frame to the serial extraction); so extra grows with the
 * screen in threshold areas, S = w h / pixel_err^2: 0 below 2^17 (320x240 at 1 px), 1
 * below 2^19 (640x480 at 1 px), else 2 (1280x720).  (Views over N47E009 have a
 * triangle per 20 to 50 threshold areas: first parts of about 100 to 600 triangles at
 * these sizes.)  The next frames cut and join by size (regroup). */
static void cut_initial(bt_parts *ps, const bt_params *p)
{
    /* (an error above 256 px counts as 256: no product overflows) */
    const uint64_t err = p->pixel_err_q8 <= 0 ? 256u : p->pixel_err_q8 < 65536 ? (uint64_t)p->pixel_err_q8 : 65536u;
    const uint64_t s16 = (uint64_t)p->c->w * (uint64_t)p->c->h * 65536u;   /* S err^2, below 2^44 */
    const int extra = s16 >= ((uint64_t)1 << 19) * err * err ? 2 : s16 >= ((uint64_t)1 << 17) * err * err ? 1 : 0;
    uint32_t c, n = 0;
    for (c = 2u << BTI_PART_DEPTH; c < 2u << (BTI_PART_DEPTH + extra) && n < BTI_PART_DEEP; c++) ps->deep[n++] = c;
    ps->ndeep = n;
    ps->cut_fresh = 0;
}

void bt_parts_reset(bt_parts *ps)
{
    uint32_t k;
    if (!ps) return;
    ps->ndeep = 0;
    ps->cut_fresh = 1;
    for (k = 0; k < BT_PARTS; k++) {
        ps->slot[k].code = 0;
        ps->slot[k].reuse = 0;
    }
    forget_places(ps);
}

/* This frame's roots from ps->deep (the walk above the parts, through its own memo),
 * each given its slot (match_slots) */
static void find_roots(bt_parts *ps)
{
    ps->e0.m = &ps->top_m;
    bti_part_roots(&ps->e0, ps);
    ps->e0.m = NULL;
    match_slots(ps);
}

br_status bt_extract_begin(bt_parts *ps, bt_tree *t, const bt_params *p, bt_mesh *m, uint32_t *nparts)
{
    br_status s;
    *nparts = 0;
    if (!ps || !m || !m->v) return BR_E_ARG;
    ps->t = t; ps->p = p; ps->m = m;
    ps->serial = 1;
    ps->nroot = 0;
    s = bti_setup(&ps->e0, t, p);
    if (s != BR_OK) return s;
    if (p->mode != BT_VIEW || ps->e0.reorder || !t->st) {
        forget_places(ps);
        return bt_extract(t, p, m);
    }
    ps->serial = 0;
    ps->e0.rec_splits = 1;
    if (bti_coh_frame(&ps->e0, &ps->coh)) {
        uint32_t k;
        for (k = 0; k < BT_PARTS; k++) bti_memo_clear(ps->slot[k].m.memo, ps->slot[k].mclean);
        bti_memo_clear(ps->top_memo, BTI_TOP_MEMO);
    }
    bti_wtab_set(&ps->wt, ps->e0.tau, ps->e0.morph_span);
    if (++ps->top_m.memo_gen > 0xFFFFu) {
        bti_memo_clear(ps->top_memo, BTI_TOP_MEMO);
        ps->top_m.memo_gen = 1;
    }
    {
        uint32_t k;
        for (k = 0; k < BT_PARTS; k++) ps->slot[k].done = 0;
    }
    if (ps->cut_fresh) cut_initial(ps, p);
    find_roots(ps);
    *nparts = ps->nroot;
    return BR_OK;
}

/* Empties part k for a walk with a vertex hash of hs slots and a decision memo of
 * ms slots, the first ones of the allocated tables.  Only speed depends on the
 * sizes: vertices are numbered in first-use order, and the memo is a cache.  A
 * hash slot holds base + 1 + index (core/bt_mesh.c reset_mesh) with the base of
 * ps->slot[k].hbase, which only grows past every index its generation used (at most
 * the slots it wrote, hins: a resumed walk, bti_part_resume, may end with fewer vertices
 * than an earlier walk of the generation had), so slots of any earlier walk read as empty
 * whatever the size then; both tables are cleared whole when a counter wraps. */
static void part_reset(bt_parts *ps, uint32_t k, uint32_t hs, uint32_t ms, bti_extract *e)
{
    bt_mesh *pm = &ps->slot[k].m;
    const uint32_t used = ps->slot[k].hins > pm->nv ? ps->slot[k].hins : pm->nv;
    if (ps->slot[k].hbase > 0xFFFFFFFFu - used - pm->cap_v - 1) {
        memset(pm->hash, 0, (size_t)ps->slot[k].hclean * 4);
        ps->slot[k].hbase = 0;
    } else ps->slot[k].hbase += used;
    ps->slot[k].hins = 0;
    if (++pm->memo_gen > 0xFFFFu) {
        bti_memo_clear(pm->memo, ps->slot[k].mclean);
        pm->memo_gen = 1;
    }
    clear_to(&ps->slot[k], hs, ms);
    pm->hmask = hs - 1;
    pm->memo_mask = ms - 1;
    pm->nv = 0; pm->ns = 0; pm->ntri = 0; pm->nline = 0; pm->nfict = 0; pm->overflow = 0;
    pm->nsplits = 0;
    pm->nz = 0;
    bti_part_extract_setup(ps, k, e);
}

/* After part k's walk (whole or resumed): what the next frame's replay reads */
static void walked(bt_parts *ps, uint32_t k, const bti_extract *e)
{
    ps->slot[k].hint_nv = ps->slot[k].m.nv;
    ps->slot[k].nrec = e->nrec;
    ps->slot[k].last_root = ps->root[k];
    ps->slot[k].reuse = BR_COHERENCE && e->recs && !e->full && !e->lost && e->nrec <= e->cap_rec
                && ps->slot[k].m.nz <= ps->slot[k].m.cap_z;
}

void bt_extract_part(bt_parts *ps, uint32_t k)
{
    bti_extract *e;
    uint32_t hs = PART_HASH_MIN, ms;
    uint32_t at = 0;
    if (!ps || ps->serial || k >= ps->nroot) return;
    ps->replayed[k] = (uint8_t)bti_part_replay(ps, k, &at);
    ps->slot[k].done = 1;
    ps->resumed[k] = 0;
    if (ps->replayed[k]) return;
    e = &ps->slot[k].e;
    if (at && bti_part_resume(ps, k, at)) {
        ps->resumed[k] = 1;
        walked(ps, k, e);
        return;
    }
    /* tables for twice last frame's vertices (load <= 1/4 of the hash): a part's
     * hash and memo stay in cache where the allocated ones (sized for part_tri)
     * would spread its few thousand vertices over megabytes; the memo has 4 slots a
     * hash slot, so that most of last frame's decisions are still there to reuse */
    while (hs < 8 * (uint64_t)ps->slot[k].hint_nv && hs < ps->hfull) hs <<= 1;
    if (hs > ps->hfull) hs = ps->hfull;
    ms = 4 * hs < ps->mfull ? 4 * hs : ps->mfull;
    part_reset(ps, k, hs, ms, e);
    bti_part_walk(e, &ps->root[k], ps->slot[k].ridx);
    if (e->full && hs < ps->hfull) {     /* the small hash filled up: again with all of it */
        part_reset(ps, k, ps->hfull, ps->mfull, e);
        bti_part_walk(e, &ps->root[k], ps->slot[k].ridx);
    }
    ps->slot[k].hins = ps->slot[k].m.nv;
    walked(ps, k, e);
}

/* Old marks go, the listed splits become ST_PREV and m's id list (bt_extract
 * reads it next frame); a list that does not fit clears every mark, as
 * bt_extract does when its list overflows. */
static void hysteresis(bt_parts *ps, uint64_t nsp)
{
    bt_mesh *m = ps->m;
    bt_tree *t = ps->t;
    uint32_t *ids = bti_ids_of(m), i, k, n = 0, nold = m->nsplits;
    uint8_t *prev = bti_st(t, ST_PREV);     /* a local: a byte store may alias anything */
    for (i = 0; i < nold; i++) bti_byte_clear(prev, ids[i]);
    m->nsplits = 0;
    if (nsp > bti_heap_cap(m)) {
        bti_st_wipe(t);
        return;
    }
    for (i = 0; i < ps->ntop; i++) ids[n++] = ps->top_ids[i];
    for (k = 0; k < ps->nroot; k++) {
        const bt_mesh *pm = &ps->slot[k].m;
        memcpy(ids + n, bti_ids_of(pm), (size_t)pm->nsplits * 4);
        n += pm->nsplits;
    }
    for (i = 0; i < n; i++) bti_bit_set(prev, ids[i]);
    m->nsplits = n;
}

/* ------------------------------------------------------------ seams
 * Each part's writer started afresh, where the serial writer would have gone on
 * from the previous part's last leaf (pending, written with this part's first as
 * its lookahead).  At each seam the serial writer's own code (btw_write_leaf) is
 * run on, from the state the strip so far ends in, over the part's first leaves
 * (the snapshots), until its state equals the part's own writer's state after
 * the same leaf: the same last two strip vertices in the same order at the same
 * parity, the same pending leaf, no open bridge plan.  From there both writers
 * make the same decisions on the same input, so the rest of the part's strip is
 * the serial strip.  The writer tells vertices apart by index; a vertex on the
 * seam is in both parts' lists, so the seam writer identifies vertices by (x, y)
 * among those it has seen at this seam (recent[]), as the serial dedup would. */
static int same_xy(const bt_mesh *m, uint32_t a, uint32_t b)
{
    return m->v[a].x == m->v[b].x && m->v[a].y == m->v[b].y;
}

static uint32_t seam_v(bt_parts *ps, uint32_t g)
{
    uint32_t i;
    for (i = 0; i < ps->nrecent; i++)
        if (same_xy(ps->m, ps->recent[i], g)) return ps->recent[i];
    if (ps->nrecent < sizeof ps->recent / sizeof ps->recent[0]) ps->recent[ps->nrecent++] = g;
    return g;
}

static void seam_leaf(bt_parts *ps, const bti_leaf *L, uint32_t off, bti_leaf *out)
{
    out->ia = seam_v(ps, L->ia + off); out->ic = seam_v(ps, L->ic + off); out->ib = seam_v(ps, L->ib + off);
    out->o0 = seam_v(ps, L->o0 + off); out->o1 = seam_v(ps, L->o1 + off); out->other = seam_v(ps, L->other + off);
}

static int same_leaf(const bt_mesh *m, const bti_leaf *a, const bti_leaf *b, uint32_t off)
{
    return same_xy(m, a->ia, b->ia + off) && same_xy(m, a->ic, b->ic + off) && same_xy(m, a->ib, b->ib + off)
        && same_xy(m, a->o0, b->o0 + off) && same_xy(m, a->o1, b->o1 + off) && same_xy(m, a->other, b->other + off);
}

/* Sets the seam writer fx to part k's state at its end (indices + voff[k]). */
static void take_end(bt_parts *ps, uint32_t k)
{
    const bti_extract *pe = &ps->slot[k].e;
    bti_extract *fx = &ps->fx;
    uint32_t off = ps->voff[k];
    int i;
    fx->has_pend = pe->has_pend;
    fx->pend = pe->pend;
    fx->pend.ia += off; fx->pend.ic += off; fx->pend.ib += off;
    fx->pend.o0 += off; fx->pend.o1 += off; fx->pend.other += off;
    fx->nplan = pe->nplan;
    for (i = 0; i < pe->nplan; i++) fx->plan[i] = pe->plan[i] + off;
}

/* The seam before part k; the strip so far is m->strip[0 .. m->ns) (its last two
 * entries written).  0, or -1 when the part's snapshots ran out first. */
static int seam(bt_parts *ps, uint32_t k)
{
    bti_extract *fx = &ps->fx;
    bt_mesh *m = ps->m;
    const bt_mesh *pm = &ps->slot[k].m;
    uint32_t off = ps->voff[k], i;
    int j;
    ps->nrecent = 0;
    if (m->ns >= 2) { (void)seam_v(ps, m->strip[m->ns - 2]); (void)seam_v(ps, m->strip[m->ns - 1]); }
    if (fx->has_pend) { (void)seam_v(ps, fx->pend.ia); (void)seam_v(ps, fx->pend.ic); (void)seam_v(ps, fx->pend.ib); }
    for (j = 0; j < fx->nplan; j++) (void)seam_v(ps, fx->plan[j]);
    for (i = 0; i < ps->slot[k].e.nsnap; i++) {
        const bti_snap *sn = &ps->slot[k].snap[i];
        bti_leaf L;
        seam_leaf(ps, &sn->L, off, &L);
        if (fx->has_pend && btw_write_leaf(fx, &fx->pend, &L)) fx->has_pend = 0;
        else { fx->pend = L; fx->has_pend = 1; }
        if (sn->ns >= 2 && m->ns >= 2 && ((m->ns - sn->ns) & 1) == 0 && fx->nplan == 0 && sn->nplan == 0
            && fx->has_pend == sn->has_pend && (!sn->has_pend || same_leaf(m, &fx->pend, &sn->pend, off))
            && same_xy(m, m->strip[m->ns - 2], sn->t0 + off) && same_xy(m, m->strip[m->ns - 1], sn->t1 + off)) {
            ps->soff[k] = m->ns;
            ps->skip[k] = sn->ns;
            m->strip[m->ns - 2] = (br_index)(sn->t0 + off);    /* the part's own indices from here on */
            m->strip[m->ns - 1] = (br_index)(sn->t1 + off);
            m->ns += pm->ns - sn->ns;
            if (pm->ns >= 2) {
                m->strip[m->ns - 2] = (br_index)(pm->strip[pm->ns - 2] + off);
                m->strip[m->ns - 1] = (br_index)(pm->strip[pm->ns - 1] + off);
            }
            take_end(ps, k);
            return 0;
        }
    }
    if (ps->slot[k].e.count > BTI_SNAPS) return -1;
    ps->soff[k] = m->ns;       /* every leaf of the part went through the seam writer */
    ps->skip[k] = pm->ns;
    return 0;
}

/* Joins the parts' strips (seams), or returns -1 (nothing usable: a seam did not
 * settle within the snapshots, or the strip would not fit). */
static int join_strips(bt_parts *ps)
{
    bt_mesh *m = ps->m;
    bti_extract *fx = &ps->fx;
    uint32_t k;
    int any = 0;
    *fx = ps->e0;
    fx->m = m;
    fx->lim_ns = m->cap_s - 10;
    fx->has_pend = 0;
    fx->nplan = 0;
    m->ns = 0;
    m->nline = 0;
    for (k = 0; k < ps->nroot; k++) {
        const bt_mesh *pm = &ps->slot[k].m;
        if (ps->slot[k].e.count == 0) { ps->soff[k] = m->ns; ps->skip[k] = pm->ns; continue; }
        if ((uint64_t)m->ns + pm->ns + 32 * BTI_SNAPS + 64 > m->cap_s) return -1;
        if (!any) {
            ps->soff[k] = 0;
            ps->skip[k] = 0;
            m->ns = pm->ns;
            if (pm->ns >= 2) { m->strip[m->ns - 2] = pm->strip[pm->ns - 2]; m->strip[m->ns - 1] = pm->strip[pm->ns - 1]; }
            take_end(ps, k);
            any = 1;
        } else if (seam(ps, k) != 0) return -1;
    }
    if ((uint64_t)m->ns + 64 > m->cap_s) return -1;
    btw_flush(fx);
    return 0;
}

/* ps->deep in increasing order, for bti_part_cut's binary search (insertion sort:
 * at most BTI_PART_DEEP codes) */
static void sort_cuts(bt_parts *ps)
{
    uint32_t i, q;
    for (i = 1; i < ps->ndeep; i++) {
        const uint32_t c = ps->deep[i];
        for (q = i; q > 0 && ps->deep[q - 1] > c; q--) ps->deep[q] = ps->deep[q - 1];
        ps->deep[q] = c;
    }
}

static int depth_of(uint32_t code)
{
    int d = -1;
    while (code > 1) { code >>= 1; d++; }
    return d;
}

/* The leaves below each record of part k's walk this frame (ps->cut_tris; a half
 * without a record, of unit legs, is one leaf) and the records of its two halves
 * (cut_lo, cut_hi: the halves (a, m, c) and (c, m, b), as top and rec name them;
 * BTI_NO_IDX for none).  A split's halves' records follow it and name it as their
 * apex (cref), so in reverse order each is complete before it is added to its apex.
 * 0 when the part's records are not complete. */
static int count_below(bt_parts *ps, uint32_t k)
{
    const bti_rec *R = ps->slot[k].rec;
    uint32_t j, n = ps->slot[k].nrec;
    if (!ps->slot[k].reuse || n == 0 || n > ps->cap_rec) return 0;
    for (j = 0; j < n; j++) {
        ps->cut_tris[j] = R[j].sp == 0 ? 1u : 0u;
        ps->cut_lo[j] = ps->cut_hi[j] = BTI_NO_IDX;
    }
    for (j = n; j-- > 0;) {
        const bti_rec *r = &R[j];
        if (r->sp == 1)       /* halves of unit legs have no record and are leaves */
            ps->cut_tris[j] += (ps->cut_lo[j] == BTI_NO_IDX) + (ps->cut_hi[j] == BTI_NO_IDX);
        if (r->cref >= BTI_REF_A) continue;
        ps->cut_tris[r->cref] += ps->cut_tris[j];
        if (r->aref == R[r->cref].aref) ps->cut_lo[r->cref] = j;
        else ps->cut_hi[r->cref] = j;
    }
    return 1;
}

/* Cuts the triangle named code (at depth), whose diamond's record is i, when more than
 * BTI_PART_SPLIT leaves lie below it, and its halves by the same rule, down to levels
 * levels in one frame (a part near the eye may take the room the others need; the
 * next frame goes on). */
static void cut_by_count(bt_parts *ps, uint32_t i, uint32_t code, int depth, int levels, uint32_t *n)
{
    if (ps->cut_tris[i] <= BTI_PART_SPLIT || depth >= BTI_PART_DEPTH_MAX || !levels || *n >= BTI_PART_DEEP) return;
    ps->deep[(*n)++] = code;
    if (ps->cut_lo[i] != BTI_NO_IDX) cut_by_count(ps, ps->cut_lo[i], code << 1, depth + 1, levels - 1, n);
    if (ps->cut_hi[i] != BTI_NO_IDX) cut_by_count(ps, ps->cut_hi[i], code << 1 | 1, depth + 1, levels - 1, n);
}

/* Cuts the triangle named code, with t triangles below it and no complete records to
 * say where: halves at once down to about BTI_PART_SPLIT each, at most 3 levels (8
 * parts) and within BTI_PART_DEPTH_MAX and BTI_PART_DEEP, halves after what they halve. */
static void cut_blind(bt_parts *ps, uint32_t code, uint32_t t, uint32_t *n)
{
    const int d = depth_of(code);
    int levels = 1, l;
    uint32_t j;
    while (levels < 3 && (t >> levels) > BTI_PART_SPLIT) levels++;
    if (levels > BTI_PART_DEPTH_MAX - d) levels = BTI_PART_DEPTH_MAX - d;
    for (l = 0; l < levels; l++)
        for (j = 0; j < 1u << l && *n < BTI_PART_DEEP; j++) ps->deep[(*n)++] = code << l | j;
}

/* Next frame's cuts below BTI_PART_DEPTH (bti_part_roots) from this frame's parts:
 * this frame's, less those whose halves are both roots with fewer than
 * BTI_PART_MERGE triangles between them; and each root with more than
 * BTI_PART_SPLIT, cut where its walk's records put its triangles (cut_by_count, so
 * the first frames settle in a few), within BTI_PART_DEPTH_MAX and while there is
 * room (BTI_PART_DEEP: at most BT_PARTS roots), the largest parts first.  Only the
 * parts' sizes depend on it, never the mesh: smaller parts near the eye, where the
 * mesh changes every frame, keep the rest replayable (bti_part_replay). */
static void regroup(bt_parts *ps)
{
    uint32_t i, k, n = 0, join[BT_PARTS], njoin = 0, next = 0, big[BT_PARTS], nbig = 0, q;
    /* the cuts whose halves are both roots, small together: two halves are roots k,
     * k + 1 (walk order), so these come in the order of the cuts (preorder; halves
     * of a triangle above BTI_PART_DEPTH are no cut's) */
    for (k = 0; k + 1 < ps->nroot; k++) {
        const uint32_t c = ps->root_code[k];
        if (!(c & 1) && ps->root_code[k + 1] == c + 1 && depth_of(c) > BTI_PART_DEPTH
            && ps->slot[k].m.ntri + ps->slot[k + 1].m.ntri < BTI_PART_MERGE)
            join[njoin++] = c >> 1;
    }
    for (i = 0; i < ps->nused; i++) {
        const uint32_t c = ps->used[i];
        if (next < njoin && join[next] == c) { next++; continue; }
        ps->deep[n++] = c;
    }
    for (k = 0; k < ps->nroot; k++) {      /* the parts to cut, largest first */
        const uint32_t t = ps->slot[k].m.ntri;
        if (t <= BTI_PART_SPLIT) continue;
        for (q = nbig++; q > 0 && ps->slot[big[q - 1]].m.ntri < t; q--) big[q] = big[q - 1];
        big[q] = k;
    }
    for (q = 0; q < nbig && n < BTI_PART_DEEP; q++) {
        const uint32_t c = ps->root_code[big[q]];
        if (count_below(ps, big[q]))        /* where its triangles are */
            cut_by_count(ps, 0, c, depth_of(c), 4, &n);
        else
            cut_blind(ps, c, ps->slot[big[q]].m.ntri, &n);
    }
    ps->ndeep = n;
    sort_cuts(ps);
}

/* The cut with the full parts cut (cut_blind, at least part_tri triangles each) and
 * the other cuts kept: for the retry in this frame (retry_full), and after a frame
 * that a part still full sent to bt_extract, from the next frame on. */
static void regroup_full(bt_parts *ps)
{
    uint32_t k, n = 0;
    for (k = 0; k < ps->nused; k++) ps->deep[n++] = ps->used[k];
    for (k = 0; k < ps->nroot && n < BTI_PART_DEEP; k++)
        if (ps->slot[k].e.full) cut_blind(ps, ps->root_code[k], ps->part_tri, &n);
    ps->ndeep = n;
    sort_cuts(ps);
}

/* Whether slot k's mesh is this frame's for root k: extracted this frame, whole, from
 * the same triangle */
static int slot_current(const bt_parts *ps, uint32_t k)
{
    return ps->slot[k].done && !ps->slot[k].e.full && !ps->slot[k].e.lost
        && bti_same_root(&ps->root[k], &ps->slot[k].last_root);
}

/* Parts that filled their mesh, cut here (regroup_full, 3 levels) and extracted again
 * in this frame, serially, up to BTI_PART_RETRY rounds: the roots are found again
 * through the top walk's memo (this frame's entries: the same decisions), the parts the
 * cut left alone keep the meshes they made this frame (slot_current), the pieces walk.
 * A part still full after that, or one whose seams were lost, leaves the frame to the
 * serial extraction (bt_extract_end); a cut that cannot grow (no room, or at
 * BTI_PART_DEPTH_MAX) stops the rounds.  Costs the walk of the full parts' triangles
 * again, where the serial extraction would walk every part's. */
#define BTI_PART_RETRY 2
static void retry_full(bt_parts *ps)
{
    int round;
    for (round = 0; round < BTI_PART_RETRY; round++) {
        uint32_t k, full = 0;
        for (k = 0; k < ps->nroot; k++) {
            if (ps->slot[k].e.lost) return;
            full += ps->slot[k].e.full;
        }
        if (!full) return;
        regroup_full(ps);
        if (ps->ndeep <= ps->nused) return;
        find_roots(ps);
        for (k = 0; k < ps->nroot; k++) {
            if (slot_current(ps, k)) ps->replayed[k] = 0;
            else bt_extract_part(ps, k);
        }
    }
}

br_status bt_extract_end(bt_parts *ps, uint32_t *njoin)
{
    bt_mesh *m;
    uint64_t nv = 0, ntri = 0, nsp;
    uint32_t k, nfict = 0;
    *njoin = 0;
    if (!ps || ps->serial) return BR_OK;
    retry_full(ps);
    m = ps->m;
    nsp = ps->ntop;
    ps->nreused = 0;
    ps->nresumed = 0;
    for (k = 0; k < ps->nroot; k++) {
        const bt_mesh *pm = &ps->slot[k].m;
        ps->nreused += ps->replayed[k];
        ps->nresumed += ps->resumed[k];
        if (ps->slot[k].e.full || ps->slot[k].e.lost) break;
        nsp += pm->nsplits;
        ps->voff[k] = (uint32_t)nv;
        nv += pm->nv;
        ntri += pm->ntri;
        nfict += pm->nfict;
    }
    if (k == ps->nroot && nv <= m->cap_v && ntri <= m->max_tri) {
        (void)bti_reset_mesh(m);
        for (k = 0; k < ps->nroot; k++)
            memcpy(m->v + ps->voff[k], ps->slot[k].m.v, (size_t)ps->slot[k].m.nv * sizeof *m->v);
        m->nv = (uint32_t)nv;
        if (join_strips(ps) != 0) k = 0;
    } else k = 0;
    if (k != ps->nroot) {
        /* a part is full, a seam did not settle, or the joined mesh would not fit:
         * the serial extraction decides, with its fallback to the budget (t->st
         * is as the previous frame left it) */
        ps->serial = 1;
        regroup_full(ps);
        forget_places(ps);
        return bt_extract(ps->t, ps->p, m);
    }
    for (k = 0; k < BT_PARTS; k++) {
        struct bti_slot *sl = &ps->slot[k];
        const uint32_t at = k < ps->nroot ? ps->voff[k] : UINT32_MAX;
        /* (a replay lists its moved vertices when they fit the bits, bti_part_replay) */
        sl->from_voff = k < ps->nroot && ps->replayed[k] && sl->m.nv <= ps->vbits ? sl->last_voff : UINT32_MAX;
        sl->last_voff = at;
    }
    hysteresis(ps, nsp);
    regroup(ps);
    m->ntri = (uint32_t)ntri;
    m->nline = m->ns >= 3 ? m->ns - 2 - m->ntri : 0;
    m->nfict = nfict;
    m->overflow = 0;
    *njoin = ps->nroot;
    return BR_OK;
}

void bt_extract_join(bt_parts *ps, uint32_t k, uint32_t *v0, uint32_t *nv)
{
    const bt_mesh *pm;
    br_index *out;
    uint32_t off, i;
    *v0 = 0;
    *nv = 0;
    if (!ps || ps->serial || k >= ps->nroot) return;
    pm = &ps->slot[k].m;
    off = ps->voff[k];
    {
        /* locals: the stores could alias ps and pm as far as C knows (no vector loop) */
        const uint32_t sk = ps->skip[k], n = pm->ns > sk ? pm->ns - sk : 0;
        const br_index *in = pm->strip + sk;
        out = ps->m->strip + ps->soff[k];
        for (i = 0; i < n; i++) out[i] = (br_index)(in[i] + off);
    }
    *v0 = off;
    *nv = pm->nv;
}

const uint8_t *bt_part_moved_from(const bt_parts *ps, uint32_t k, uint32_t *v0_last)
{
    if (!ps || ps->serial || k >= ps->nroot || ps->slot[k].from_voff == UINT32_MAX) return NULL;
    *v0_last = ps->slot[k].from_voff;
    return ps->slot[k].vmoved;
}

uint32_t bt_part_tris(const bt_parts *ps, uint32_t k)
{
    return ps && !ps->serial && k < ps->nroot ? ps->slot[k].m.ntri : 0;
}

uint32_t bt_parts_reused(const bt_parts *ps)
{
    return ps && !ps->serial ? ps->nreused : 0;
}

uint32_t bt_parts_resumed(const bt_parts *ps)
{
    return ps && !ps->serial ? ps->nresumed : 0;
}
