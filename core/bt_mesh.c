/* core/bt_mesh.c — selection (fidelity, view-dependent, budget, hysteresis,
 * geomorph) and the strip emitter of the bitree (contract: core/bitree.h).
 *
 * Selection.  A diamond (sample) is SPLIT when its value exceeds the threshold:
 *   fidelity  err code > largest code whose value <= max_err (exact compare);
 *   view      rho > tau, rho = projected error (000; Lindstrom et al. 1996's
 *             screen-space error): object error E (world
 *             units) * f / d, d = a lower bound of the distance from the eye to
 *             the diamond's nested bounding volume (box of half-side 3h / 2h
 *             around the centre x quantised height range), so rho is an upper
 *             bound of the error seen on screen.  Diamonds whose volume lies
 *             outside a frustum plane are culled: neither split nor emitted.
 *             Hysteresis (003): a diamond split in the previous frame stays
 *             split while rho > tau * (1 - hyst).
 *   budget    (003; ROAM's split queue, Duchaineau et al. 1997) diamonds are
 *             split in decreasing rho order (a heap; ties
 *             coarser first) while the nominal triangle count stays <= budget.
 * E and the volume are monotone up the tree (saturated as in Pajarola 1998),
 * so every rule splits a set closed
 * under "parent of": the mesh is conforming (002 2.2, no T-junctions).
 *
 * Geomorph (002 3.3): a split vertex's height moves from the fictitious height
 * (average of its hypotenuse ends) at rho = tau to its real height at
 * rho = tau * (1 + morph), so refinements rise instead of popping.
 *
 * Strip (002 section 4, figures 10-12; 004 figure 2).  Leaves are visited in the
 * recursive order left child (a, m, c) then right child (c, m, b), which makes
 * every leaf share an edge with the next one.  A subtree is entered through a
 * leg or its hypotenuse and left through a leg or its hypotenuse: 002's three
 * sequence types, A = (leg in, leg out), B = (hypotenuse in, leg out),
 * C = (leg in, hypotenuse out); the children of (in, out) are (!in, leg) and
 * (leg, !out), i.e. A -> B + C, B -> A + C, C -> B + A, 002 figure 11.  Each leaf appends one
 * index; when two consecutive leaves have the same pivot (a fan) the strip
 * needs a swap: the older index is repeated, one line triangle (002 figure 10);
 * with one leaf of lookahead, a fan whose rim is straight gets one line
 * triangle of three collinear vertices for two turns (004).  The writer is
 * core/bt_emit.c.
 * Where the walk breaks (after a void or a culled subtree) core/bt_strip.c
 * bridges to the next leaf by the shortest run of line triangles; in fidelity
 * mode (or when p->strip_order asks) a strip with breaks is then written again
 * in a greedy leaf order over the edge adjacency (btw_reorder), which needs
 * fewer references.  Winding: the
 * first triangle is written counter-clockwise seen from +z (x east, y north); the GL parity rule
 * keeps every later edge-adjacent triangle the same. */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/config.h"
#include "core/bt_em.h"

/* A vertex on its way down the recursion; idx caches its output index (the
 * children of a split share their parent's pt instances, so most lookups are
 * answered here and only the first use per instance goes to the hash). */
typedef bti_pt pt;
#define NO_IDX BTI_NO_IDX

/* ------------------------------------------------------------ samples and volumes
 * (core/bt_em.h: shared with the streamed walk, core/bt_stream.c) */
#define tri_valid bti_tri_valid
#define dvolume bti_dvolume
#define isat_mul bti_isat_mul

/* Frustum test of a box against the planes in *mask: 1 when it lies wholly
 * outside one of them (culled); planes it lies wholly inside are removed from
 * *mask, so descendants (whose volumes nest inside) skip them.  With frame
 * coherence, *cm is lowered to how far (Q30 world units) the tested planes' values
 * at the box may move before an answer changes: sp < 0 (outside) while the move is
 * <= -sp - 1, sn >= 0 (inside) while <= sn, both else.  The box's corners are 32-bit
 * (within +-CAM_COORD_MAX, bti_setup) and the normals Q30: each product is 32 x 32 ->
 * 64 bits, one instruction on 32-bit ARM. */
static int culled(const bti_extract *e, const int32_t lo[3], const int32_t hi[3], unsigned *mask, int64_t *cm)
{
    int i, k;
    if (e->p->no_cull) { *mask = 0; return 0; }
    for (i = 0; i < CAM_NPLANES; i++) {
        int64_t sp, sn;
        if (!(*mask & (1u << i))) continue;
        sp = sn = e->pl[i].d;
        for (k = 0; k < 3; k++) {
            const int32_t nk = e->pl[i].n[k];
            sp += (int64_t)nk * (nk >= 0 ? hi[k] : lo[k]);
            sn += (int64_t)nk * (nk >= 0 ? lo[k] : hi[k]);
        }
        if (e->coh) {
            int64_t g = sp < 0 ? -sp - 1 : (sn >= 0 ? sn : (sp < -sn - 1 ? sp : -sn - 1));
            if (sp < 0) { *cm = g; return 1; }
            if (g < *cm) *cm = g;
        }
        if (sp < 0) return 1;
        if (sn >= 0) *mask &= ~(1u << i);
    }
    return 0;
}

/* The object error of code (not BT_CODE_SPLIT) in world units, rounded up;
 * bt_code_value's exact codes below 4096 without the call */
static inline int64_t obj_err(const bti_extract *e, uint16_t code)
{
    int64_t ew;
    if (code < 4096 && e->p->fr.sz_q16 >= 0)        /* below 2^43: one 32 x 32 -> 64 product */
        return ((int64_t)code * e->p->fr.sz_q16 + 65535) >> 16;
    ew = isat_mul(code < 4096 ? (int64_t)code : bt_code_value(code), e->p->fr.sz_q16);
    return ew == INT64_MAX ? ew : (ew + 65535) >> 16;
}

/* Screen-space error of diamond (x, y) in slot id: *ew = object error in world units
 * (rounded up), *d = lower bound of the distance to its volume.  Returns -1 when
 * culled (all void or outside the frustum), 1 when the error is unbounded
 * (BT_CODE_SPLIT, or the eye inside the volume with a nonzero error), 0 otherwise. */
static int view_err(const bti_extract *e, int32_t x, int32_t y, uint32_t id, unsigned *mask, int64_t *ew,
                    int64_t *d, int64_t *cm)
{
    const bt_tree *t = e->t;
    int32_t lo[3], hi[3];
    uint32_t nv = t->node[id];
    uint16_t code = BT_NODE_ERR(nv);
    if (BT_NODE_ZLO(nv) > BT_NODE_ZHI(nv)) return -1; /* all void */
    dvolume(e, x, y, id, lo, hi);
    if (*mask && culled(e, lo, hi, mask, cm)) return -1;
    if (code == BT_CODE_SPLIT) return 1;
    *ew = obj_err(e, code);
    *d = bti_box_dist(e->p->c->eye, lo, hi);
    if (*d <= 0) { *d = 0; return *ew > 0 ? 1 : 0; }
    return 0;
}

/* rho in q8 pixels; -1 when culled */
static int64_t rho_q8(const bti_extract *e, int32_t x, int32_t y)
{
    unsigned mask = 0x3f;
    int64_t ew = 0, d = 0, cm = INT64_MAX;
    int r = view_err(e, x, y, bti_slot(e->t, x, y), &mask, &ew, &d, &cm);
    if (r < 0) return -1;
    if (r > 0) return INT64_MAX;
    if (d == 0) return 0;
    {
        int64_t lhs = isat_mul(ew, e->fq8);
#if BR_DIV64_NATIVE
        return lhs / d;
#else
        /* the budget's priority caps rho at 2^50 (prio): 50 restoring steps
         * below that, all 63 only above it */
        return (int64_t)fx_udiv_bits((uint64_t)lhs, (uint64_t)d, (lhs >> 50) >= d ? 63 : 50);
#endif
    }
}

int64_t bt_screen_error_q8(const bt_tree *t, const bt_params *p, int32_t x, int32_t y)
{
    bti_extract e;
    int64_t r;
    if (!p || p->mode == BT_FIDELITY || bti_setup(&e, (bt_tree *)t, p) != BR_OK) return 0;
    r = rho_q8(&e, x, y);
    return r < 0 ? 0 : r;
}

/* ------------------------------------------------------------ split rule */
static uint16_t morph_of(const bti_extract *e, int64_t rho)
{
    int64_t q = rho - e->tau;
    if (e->morph_span <= 0) return BT_MORPH_ONE;
    if (q < 0) q = 0;
    if (q >= e->morph_span) return BT_MORPH_ONE;
    return (uint16_t)((q * BT_MORPH_ONE) / e->morph_span);
}

/* morph_of(e, lhs / d) for lhs = ew f >= 0 and d > 0: with a 64-bit divide as written,
 * without one by bti_morph_nodiv (core/bt_int.h), the same weight (morph_exact); the
 * rule's weight rounded down to a multiple of BT_MORPH_STEP (morph_at; ONE is one). */
static uint16_t morph_exact(const bti_extract *e, int64_t lhs, int64_t d)
{
#if BR_DIV64_NATIVE
    return morph_of(e, lhs / d);
#else
    (void)morph_of;
    if (e->tau < 0) {
        /* the budget rule's tau = -1 (bt_extract): morph_of's q = lhs / d + 1 =
         * floor((lhs + d) / d), below 2^64; q < span < 2^39 needs bti_bits(span) steps */
        uint64_t L = (uint64_t)lhs + (uint64_t)d, D = (uint64_t)d, S = (uint64_t)e->morph_span, q;
        if (fx_mul_ge(L, S, D)) return BT_MORPH_ONE;
        q = fx_udiv_bits(L, D, bti_bits(S));
        return (uint16_t)fx_udiv_bits(q << 15, S, 15);
    }
    return bti_morph_nodiv(lhs, d, e->tau, e->morph_span);
#endif
}
static uint16_t morph_at(const bti_extract *e, int64_t lhs, int64_t d)
{ return (uint16_t)(morph_exact(e, lhs, d) & ~(BT_MORPH_STEP - 1u)); }

/* Diamond (x, y) in slot idx: returns 1 split, 0 leaf, -1 drop (culled); *morph
 * set for split vertices; *mask: frustum planes still to test (view and budget
 * modes); *exp: how long the view rule's answer holds (core/bt_coh.c), 0 for one
 * frame */
static int decide(bti_extract *e, int32_t x, int32_t y, uint32_t idx, unsigned *mask, uint16_t *morph,
                  uint64_t *exp)
{
    bt_tree *t = e->t;
    int64_t ew = 0, d = 0, cm = INT64_MAX;
    unsigned m_in = *mask;
    int r;
    *morph = BT_MORPH_ONE;
    *exp = 0;
    if (e->fid) return BT_NODE_ERR(e->t->node[idx]) > e->cthr;
    if (e->p->mode == BT_BUDGET || e->tau < 0) {
        if (e->p->mode == BT_FIDELITY) return bti_bit(bti_st(t, ST_MARK), idx);
        r = view_err(e, x, y, idx, mask, &ew, &d, &cm);
        if (r < 0) return -1;
        if (!bti_bit(bti_st(t, ST_MARK), idx)) return 0;
        if (e->morph_span > 0 && r == 0 && d > 0) *morph = morph_at(e, isat_mul(ew, e->fq8), d);
        return 1;
    }
    r = view_err(e, x, y, idx, mask, &ew, &d, &cm);
    if (r != 0) {
        /* culled (outside a plane, or all void: cm stays INT64_MAX), split whatever
         * the distance (BT_CODE_SPLIT), or split with the eye inside the volume (d = 0,
         * weight full: the rule's answer for every distance up to margin's bound) */
        if (e->coh)
            *exp = r < 0 || BT_NODE_ERR(t->node[idx]) == BT_CODE_SPLIT
                 ? bti_coh_entry(e, r, 0, -1, BT_MORPH_ONE, m_in, *mask, cm)
                 : bti_coh_entry(e, 1, isat_mul(ew, e->fq8), 0, BT_MORPH_ONE, m_in, *mask, cm);
        return r < 0 ? -1 : 1;
    }
    {
        /* rho = ew * f / d > tau  <=>  ew * f > tau * d (no division) */
        int64_t lhs = isat_mul(ew, e->fq8);
        int sp = lhs > isat_mul(e->tau, d) ||
                 (bti_bit(e->prev, idx) && lhs > isat_mul(e->tau_lo, d));
        if (sp && e->morph_span > 0) *morph = d > 0 ? morph_at(e, lhs, d) : BT_MORPH_ONE;
        if (e->coh) *exp = bti_coh_entry(e, sp, lhs, d, *morph, m_in, *mask, cm);
        return sp;
    }
}

/* The geomorph weight decide() gives diamond (x, y) in slot idx, known to be split
 * and not culled: view_err's distance and object error, decide's morph_at. */
static inline void morph_terms(const bti_extract *e, int32_t x, int32_t y, uint32_t idx, int32_t lo[3],
                               int32_t hi[3], int64_t *lhs)
{
    dvolume(e, x, y, idx, lo, hi);
    *lhs = isat_mul(obj_err(e, BT_NODE_ERR(e->t->node[idx])), e->fq8);
}

static inline uint16_t morph_of_terms(const bti_extract *e, const int32_t lo[3], const int32_t hi[3], int64_t lhs)
{
    const int64_t d = bti_box_dist(e->p->c->eye, lo, hi);
    return d <= 0 ? BT_MORPH_ONE : morph_at(e, lhs, d);
}

static uint16_t morph_now(const bti_extract *e, int32_t x, int32_t y, uint32_t idx)
{
    int32_t lo[3], hi[3];
    int64_t lhs;
    morph_terms(e, x, y, idx, lo, hi, &lhs);
    return morph_of_terms(e, lo, hi, lhs);
}

void bti_morph_terms(const bti_extract *e, int32_t x, int32_t y, uint32_t idx, int32_t lo[3], int32_t hi[3],
                     int64_t *lhs)
{ morph_terms(e, x, y, idx, lo, hi, lhs); }

uint16_t bti_morph_at(const bti_extract *e, int64_t lhs, int64_t d)
{ return d <= 0 ? BT_MORPH_ONE : morph_at(e, lhs, d); }

int bti_decide_view(bti_extract *e, int32_t x, int32_t y, uint32_t idx, unsigned *mask, uint16_t *morph)
{
    uint64_t exp;
    return decide(e, x, y, idx, mask, morph, &exp);
}

uint16_t bti_morph_now(const bti_extract *e, int32_t x, int32_t y, uint32_t idx)
{
    return e->morph_span <= 0 || BT_NODE_ERR(e->t->node[idx]) == BT_CODE_SPLIT ? BT_MORPH_ONE : morph_now(e, x, y, idx);
}

/* decide() for the view rule, memoised.  Within the frame: a diamond is reached
 * twice, once from each half, and the rule gives both visits the same answer: it
 * reads only the diamond, the camera and ST_PREV (unchanged until the frame ends),
 * and culled() answers the same under either half's plane mask, because a plane
 * leaves a mask only when an enclosing volume lies inside it (volumes nest).  A
 * memo hit keeps the parent's mask: the children test planes they could skip, with
 * the same answers.  Across frames (BR_COHERENCE): an entry of an earlier frame is
 * the answer now when it was made under the same plane mask, the travel since is
 * within its margin (core/bt_coh.c: the eye's, and with planes to test the planes'
 * too) and the diamond's ST_PREV is the one the margin assumed (set iff it was
 * split); the planes it left to its children then are the mask it hands on.  A
 * split whose geomorph weight moves with the distance keeps its answer, and the
 * weight is computed again (morph_now; the entry then holds it for this frame).  The
 * memo is a direct-mapped cache (a miss only recomputes); an entry's first word is
 * gen << 48 | (answer + 1) << 46 | morph << 30 | slot (< 2^30: w, h <= BR_MAX_SIDE =
 * 16385, so w*h < 2^28, plus the bands), the frame of the extraction whose 16-bit
 * generation (1 .. 0xFFFF, reset_mesh) it holds; its second mask_out << 58 |
 * mask_in << 52 | moving << 51 | expiry (bti_coh_entry).  Padding diamonds without a slot share the
 * void slot and its answer: VOID is culled (-1) in the view rule whatever the
 * diamond. */
static inline __attribute__((always_inline))
int decide_memo(bti_extract *e, int32_t x, int32_t y, uint32_t idx, unsigned *mask, uint16_t *morph)
{
    const bt_mesh *m = e->m;
    uint64_t *slot = bti_memo_slot(m, idx), v = *slot, exp;
    int sp;
    if ((uint32_t)(v & 0x3fffffffu) == idx) {
        sp = (int)((v >> 46) & 3) - 1;
        if ((uint32_t)(v >> 48) == m->memo_gen) {
            *morph = (uint16_t)(v >> 30);
            return sp;
        }
#if BR_COHERENCE
        {
            const uint64_t w = slot[1];
            if (bti_coh_proves(e, w, sp, idx, 1u << (idx & 7u), mask)) {
                if (!(w & BTI_COH_MOVING)) {
                    *morph = (uint16_t)(v >> 30);
                    return sp;
                }
                *morph = morph_now(e, x, y, idx);    /* the split holds, its weight moves */
                *slot = (uint64_t)m->memo_gen << 48 | (uint64_t)2 << 46 | (uint64_t)*morph << 30 | idx;
                return 1;
            }
        }
#endif
    }
    sp = decide(e, x, y, idx, mask, morph, &exp);
    *slot = (uint64_t)m->memo_gen << 48 | (uint64_t)(sp + 1) << 46 | (uint64_t)*morph << 30 | idx;
#if BR_COHERENCE
    slot[1] = exp;
#else
    (void)exp;
#endif
    return sp;
}

/* ------------------------------------------------------------ strip */
/* A part's walk (core/bt_part.c): the writer's state after leaf L was handed to it */
static void snap_take(bti_extract *e, const bti_leaf *L)
{
    bti_snap *sn = &e->snap[e->nsnap++];
    const bt_mesh *m = e->m;
    sn->L = *L;
    sn->ns = m->ns;
    sn->t0 = m->ns >= 2 ? m->strip[m->ns - 2] : 0;
    sn->t1 = m->ns >= 2 ? m->strip[m->ns - 1] : 0;
    sn->has_pend = e->has_pend;
    sn->pend = e->pend;
    sn->nplan = e->nplan;
}

/* Home slot of grid key y n + x in the dedup hash: the key itself when the table
 * has >= n^2 / 2 slots (<= 2 keys per slot; the walk's spatial coherence stays in
 * the table's cache lines), else a multiplicative hash.  Collisions of direct
 * slots probe with a scattered odd step taken from a second hash of the key, never along the dense
 * run a fully refined region forms; hashed slots probe linearly (cache lines).
 * Only speed depends on it. */
static uint32_t home(uint32_t key, uint32_t mask, int direct)
{
    uint32_t h = key * 2654435761u;
    /* the product's low bits depend only on the key's low bits (y n + x: x + y
     * for n = 2^k + 1), so the high half is folded in */
    return (direct ? key : h ^ (h >> 16)) & mask;
}

/* The index of the vertex at (x, y), or NO_IDX with *hs the free slot where it goes.
 * A slot reads as free when its index is not below m->nv (a vertex of an earlier walk,
 * or one past where core/bt_replay.c bti_part_resume cut the mesh back); one below it
 * that holds another vertex is passed.  Every slot a kept vertex's probe passed held a
 * vertex numbered before it, so it is passed again while that vertex is kept. */
static inline uint32_t vid_slot(const bti_extract *e, int32_t x, int32_t y, uint32_t *hs)
{
    const bt_mesh *m = e->m;
    uint32_t key = (uint32_t)y * (uint32_t)e->n + (uint32_t)x;
    uint32_t h = home(key, m->hmask, e->direct);
    for (;;) {
        uint32_t s = m->hash[h] - e->hbase;   /* 1 + index; <= 0 (wrapped): empty */
        if (s == 0 || s > m->nv) break;
        if (m->v[s - 1].x == x && m->v[s - 1].y == y) return s - 1;
        h = (h + (e->direct ? ((key * 2654435761u) >> 15) | 1u : 1u)) & m->hmask;
    }
    *hs = h;
    return NO_IDX;
}

uint32_t bti_vid_lookup(const bti_extract *e, int32_t x, int32_t y)
{
    uint32_t h;
    return vid_slot(e, x, y, &h);
}

static uint32_t vid_find(bti_extract *e, pt *q)
{
    bt_mesh *m = e->m;
    uint32_t h = 0, i = vid_slot(e, q->x, q->y, &h);
    if (i != NO_IDX) return q->idx = i;
    {
        bt_vert *v;
        i = m->nv++;
        v = &m->v[i];
        v->x = q->x; v->y = q->y; v->z = q->z;
        v->morph = q->morph;
        v->state = q->morph == BT_MORPH_ONE ? BT_S : BT_F;
        v->pad_ = 0;
        if (v->state == BT_F) m->nfict++;
        m->hash[h] = e->hbase + i + 1;
        return q->idx = i;
    }
}

static uint32_t vid(bti_extract *e, pt *q) { return q->idx != NO_IDX ? q->idx : vid_find(e, q); }
/* Leaf (a, c, b), apex c.  It is entered through edge {a, c} (or the hypotenuse
 * {a, b} when in_hyp) and left through {c, b} (or {a, b} when out_hyp). */
static void leaf(bti_extract *e, pt *a, pt *c, pt *b, int in_hyp, int out_hyp)
{
    bt_mesh *m = e->m;
    bti_leaf L;
    e->count++;
    if (e->count_only) return;
    /* room for this leaf and the pending one */
    if (e->full || m->nv > e->lim_nv || m->ns > e->lim_ns || m->ntri >= m->max_tri) {
        e->full = 1;
        return;
    }
    L.ia = vid(e, a); L.ic = vid(e, c); L.ib = vid(e, b);
    m->ntri++;
    if (out_hyp) { L.o0 = L.ia; L.o1 = L.ib; L.other = L.ic; }
    else { L.o0 = L.ic; L.o1 = L.ib; L.other = L.ia; }
    (void)in_hyp;
    if (e->has_pend && btw_write_leaf(e, &e->pend, &L)) e->has_pend = 0;
    else { e->pend = L; e->has_pend = 1; }
    if (e->snap && e->nsnap < BTI_SNAPS) snap_take(e, &L);
}

static void rec(bti_extract *e, pt *a, pt *c, pt *b, int in_hyp, int out_hyp, unsigned mask)
{
    int32_t dx = b->x - a->x, dy = b->y - a->y;
    pt mm;
    int sp;
    uint32_t id;
    if (e->full) return;
    if ((a->x + b->x) & 1) {     /* unit legs: the hypotenuse midpoint is no sample */
        if (tri_valid(e, a, c, b))
            leaf(e, a, c, b, in_hyp, out_hyp);
        return;
    }
    mm.idx = NO_IDX;
    mm.x = a->x + (dx >> 1);
    mm.y = a->y + (dy >> 1);
    id = bti_slot(e->t, mm.x, mm.y);
    if (e->rec_splits) {
        sp = decide_memo(e, mm.x, mm.y, id, &mask, &mm.morph);
        if (BR_COHERENCE && e->recs && (mm.ri = e->nrec++) < e->cap_rec) {     /* a part's walk: bti_rec */
            bti_rec *r = &e->recs[mm.ri];
            r->idx = id; r->pbit = (uint8_t)(1u << (id & 7u)); r->x = (uint16_t)mm.x; r->y = (uint16_t)mm.y;
            r->m_out = (uint8_t)mask; r->sp = (int8_t)sp; r->morph0 = mm.morph;
            r->aref = a->ri; r->bref = b->ri; r->cref = c->ri; r->vidx = NO_IDX; r->terms = 0;
            r->w = bti_memo_w(e->m, id);
            r->wdlo = 1; r->wdhi = 0; r->wexp = 0;
            bti_rec_at_take(e, &r->at);
        }
    } else {
        uint64_t exp;
        sp = decide(e, mm.x, mm.y, id, &mask, &mm.morph, &exp);
    }
    if (sp < 0) return;
    if (!sp) {
        /* one over padding voids (BT_CODE_SPLIT) that a budget left unsplit is
         * dropped, even with 3 valid corners (the grid's own: bt_err.c "Voids") */
        if (!e->nonvoid && BT_NODE_ERR(e->t->node[id]) == BT_CODE_SPLIT) return;
        if (tri_valid(e, a, c, b))
            leaf(e, a, c, b, in_hyp, out_hyp);
        return;
    }
    if (e->rec_splits) {
        /* record for the next frame's hysteresis; the walk reads t->st only.  A
         * diamond reached from both halves is listed twice: the end of the extraction
         * sets its ST_PREV twice, which is idempotent, and the list holds 4 entries a
         * triangle of capacity, a split making 2 */
        if (e->m->nsplits < bti_heap_cap(e->m)) bti_ids_of(e->m)[e->m->nsplits++] = id;
        else e->lost = 1;
    }
    mm.z = bti_mid_z(e, a->z, b->z, mm.x, mm.y, &mm.morph);
    rec(e, a, &mm, c, !in_hyp, 0, mask);
    rec(e, c, &mm, b, 0, !out_hyp, mask);
    if (BR_COHERENCE && e->recs && mm.ri < e->cap_rec) {
        e->recs[mm.ri].z = mm.z;
        e->recs[mm.ri].morph = mm.morph;
        e->recs[mm.ri].vidx = mm.idx;
    }
}

/* rec for the plain fidelity rule without voids: the same leaves in the same order
 * without the mode, mask, void and geomorph branches (morph 0 iff zs interpolates).
 * No void means w = h = n: every diamond is in the interior, slot y*n + x, the
 * sample's index too. */
static void rec_fid(bti_extract *e, pt *a, pt *c, pt *b, int in_hyp, int out_hyp)
{
    pt mm;
    size_t idx;
    int32_t zs;
    if (e->full) return;
    if ((a->x + b->x) & 1) { leaf(e, a, c, b, in_hyp, out_hyp); return; }
    mm.x = a->x + ((b->x - a->x) >> 1);
    mm.y = a->y + ((b->y - a->y) >> 1);
    idx = (size_t)mm.y * (size_t)e->n + (size_t)mm.x;
    if (BT_NODE_ERR(e->t->node[idx]) <= e->cthr) { leaf(e, a, c, b, in_hyp, out_hyp); return; }
    zs = e->t->f->z[idx];
    mm.z = zs;
    mm.morph = 2 * (int64_t)zs == (int64_t)a->z + b->z ? 0 : BT_MORPH_ONE;
    mm.idx = NO_IDX;
    rec_fid(e, a, &mm, c, !in_hyp, 0);
    rec_fid(e, c, &mm, b, 0, !out_hyp);
}

static void corner(const bt_tree *t, int32_t x, int32_t y, pt *q)
{
    q->x = x; q->y = y; q->z = bti_zreal(t, x, y); q->morph = BT_MORPH_ONE; q->idx = NO_IDX;
}

/* The grid's corners A (0, 0), B (S, 0), C (S, S), D (0, S): the two roots are (A, B, C)
 * entered through a leg and left through the hypotenuse, then (C, D, A) the reverse. */
static void corners(const bti_extract *e, pt q[4])
{
    corner(e->t, 0, 0, &q[0]); corner(e->t, e->S, 0, &q[1]);
    corner(e->t, e->S, e->S, &q[2]); corner(e->t, 0, e->S, &q[3]);
}

static void run(bti_extract *e)
{
    pt q[4];
    corners(e, q);
    e->has_pend = 0;
    e->nplan = 0;
    if (e->fid && e->nonvoid) { rec_fid(e, &q[0], &q[1], &q[2], 0, 1); rec_fid(e, &q[2], &q[3], &q[0], 1, 0); }
    else {
        rec(e, &q[0], &q[1], &q[2], 0, 1, 0x3f);
        rec(e, &q[2], &q[3], &q[0], 1, 0, 0x3f);
    }
    btw_flush(e);
}

/* ------------------------------------------------------------ parts */
/* The walk down to depth BTI_PART_DEPTH below the two roots, and below it through
 * the triangles ps->deep lists (bti_part_cut), in rec's order with rec's decisions:
 * each triangle where it stops (there, or earlier as a leaf of the selection) becomes
 * a part root, with the plane mask rec would hand it; the part's rec decides its
 * diamond again (the same answer: decide reads only the diamond, the camera and
 * ST_PREV) and emits its subtree.  Diamonds split here go to ps->top_ids.  Culled
 * triangles give no part.  e->m is ps->top_m: a memo of these decisions alone.  Roots:
 * 2 << BTI_PART_DEPTH, plus one a listed cut. */
static void top(bti_extract *e, bt_parts *ps, pt *a, pt *c, pt *b, int in_hyp, int out_hyp, unsigned mask,
                int depth, uint32_t code)
{
    pt mm;
    unsigned m0 = mask;
    int sp = 0;
    if ((depth < BTI_PART_DEPTH || bti_part_cut(ps, code)) && !((a->x + b->x) & 1)) {
        mm.idx = NO_IDX;
        mm.x = a->x + ((b->x - a->x) >> 1);
        mm.y = a->y + ((b->y - a->y) >> 1);
        sp = decide_memo(e, mm.x, mm.y, bti_slot(e->t, mm.x, mm.y), &mask, &mm.morph);
        if (sp < 0) return;
    }
    if (!sp) {
        bti_root *r = &ps->root[ps->nroot];
        ps->root_code[ps->nroot++] = code;
        r->a = *a; r->c = *c; r->b = *b;
        r->in_hyp = in_hyp; r->out_hyp = out_hyp; r->mask = m0;
        return;
    }
    if (depth >= BTI_PART_DEPTH) ps->used[ps->nused++] = code;
    ps->top_ids[ps->ntop++] = bti_slot(e->t, mm.x, mm.y);
    mm.z = bti_mid_z(e, a->z, b->z, mm.x, mm.y, &mm.morph);
    top(e, ps, a, &mm, c, !in_hyp, 0, mask, depth + 1, code << 1);
    top(e, ps, c, &mm, b, 0, !out_hyp, mask, depth + 1, code << 1 | 1);
}

void bti_part_roots(bti_extract *e, bt_parts *ps)
{
    pt q[4];
    corners(e, q);
    ps->nroot = 0;
    ps->ntop = 0;
    ps->nused = 0;
    top(e, ps, &q[0], &q[1], &q[2], 0, 1, 0x3f, 0, 2);
    top(e, ps, &q[2], &q[3], &q[0], 1, 0, 0x3f, 0, 3);
}

void bti_part_walk(bti_extract *e, const bti_root *r, uint32_t ridx[3])
{
    pt a = r->a, c = r->c, b = r->b;
    a.ri = BTI_REF_A; c.ri = BTI_REF_C; b.ri = BTI_REF_B;
    e->has_pend = 0;
    e->nplan = 0;
    rec(e, &a, &c, &b, r->in_hyp, r->out_hyp, r->mask);
    ridx[0] = a.idx; ridx[1] = c.idx; ridx[2] = b.idx;
}

int bti_decide_memo(bti_extract *e, int32_t x, int32_t y, uint32_t idx, unsigned *mask, uint16_t *morph)
{ return decide_memo(e, x, y, idx, mask, morph); }

void bti_walk_tri(bti_extract *e, bti_pt *a, bti_pt *c, bti_pt *b, int in_hyp, int out_hyp, unsigned mask)
{ rec(e, a, c, b, in_hyp, out_hyp, mask); }

/* ------------------------------------------------------------ public */
br_status bti_setup(bti_extract *e, bt_tree *t, const bt_params *p)
{
    memset(e, 0, sizeof *e);
    if (!t || !p || !t->node) return BR_E_ARG;
    e->t = t; e->p = p; e->n = t->n; e->S = t->n - 1;
    e->nonvoid = t->nvalid == (int64_t)t->n * t->n;
    e->nodata_free = t->nvalid == (int64_t)t->w * t->h;
    e->fid = p->mode == BT_FIDELITY;
    if (p->strip_order < BT_ORDER_AUTO || p->strip_order > BT_ORDER_BEST) return BR_E_ARG;
    e->reorder = p->strip_order == BT_ORDER_BEST || (p->strip_order == BT_ORDER_AUTO && p->mode == BT_FIDELITY);
    /* a bridge search costs thousands of instructions a break and saves two or three
     * line triangles, which the rasteriser rejects in a few dozen: per frame (view and
     * budget modes) the automatic order takes the fixed restart */
    e->bridge = !(p->strip_order == BT_ORDER_AUTO && p->mode != BT_FIDELITY);
    if (p->mode == BT_FIDELITY) {
        int64_t thr = p->max_err;
        uint16_t lo = 0, hi = BT_CODE_SPLIT - 1;
        if (thr < 0) return BR_E_ARG;
        /* largest code with value <= thr */
        if (bt_code_value(hi) <= thr) e->cthr = hi;
        else {
            while (lo + 1 < hi) {
                uint16_t mid = (uint16_t)((lo + hi) / 2);
                if (bt_code_value(mid) <= thr) lo = mid; else hi = mid;
            }
            e->cthr = lo;
        }
        return BR_OK;
    }
    if (p->mode != BT_VIEW && p->mode != BT_BUDGET) return BR_E_ARG;
    if (!p->c || p->fr.sx <= 0 || p->fr.sy <= 0 || p->fr.sz_q16 <= 0) return BR_E_ARG;
    {
        /* the quantised heights zmin + floor / ceil(range i / 255), range <= 2^30
         * (hf.h's BR_Z_LIMIT): quotient and remainder stepped by range's, so the
         * frame divides only in 32 bits */
        uint32_t range = (uint32_t)((int64_t)t->zmax - t->zmin), qs = range / 255u, rs = range % 255u;
        int64_t q = 0;
        uint32_t rem = 0;
        int i;
        for (i = 0; i < 256; i++) {
            const int64_t zl = t->zmin + q, zh = zl + (rem != 0);
            const int64_t wl = p->fr.oz + ((zl * p->fr.sz_q16) >> 16), wh = p->fr.oz + ((zh * p->fr.sz_q16 + 65535) >> 16);
            if (wl < -CAM_COORD_MAX || wh > CAM_COORD_MAX) return BR_E_ARG;     /* see below */
            e->wz_lo[i] = (int32_t)wl;
            e->wz_hi[i] = (int32_t)wh;
            q += qs;
            rem += rs;
            if (rem >= 255u) { rem -= 255u; q++; }
        }
        /* the volumes' corners are camera inputs: every world coordinate of the
         * padded grid's box must be within CAM_COORD_MAX (core/cam.h), which keeps
         * culled()'s sums of Q30 normal x coordinate products (and the plane
         * offsets) below 2^62; a frame with a larger extent (e.g. sx = 2^20 over
         * 16384 steps: 2^34) would overflow them */
        if ((int64_t)p->fr.ox < -CAM_COORD_MAX || (int64_t)p->fr.ox + (int64_t)e->S * p->fr.sx > CAM_COORD_MAX ||
            (int64_t)p->fr.oy > CAM_COORD_MAX || (int64_t)p->fr.oy - (int64_t)e->S * p->fr.sy < -CAM_COORD_MAX)
            return BR_E_ARG;
    }
    if (p->window) {
        const int32_t *wn = p->window;
        if (wn[0] < 0 || wn[0] >= wn[2] || wn[2] > p->c->w || wn[1] < 0 || wn[1] >= wn[3] || wn[3] > p->c->h)
            return BR_E_ARG;
        cam_frustum_window(p->c, wn, e->pl);
    } else cam_frustum(p->c, e->pl);
    e->rho = rho_q8;
    e->fq8 = p->c->f_q16 >> 8;
    e->tau = p->pixel_err_q8 > 0 ? p->pixel_err_q8 : 256;
    e->tau_lo = p->hyst_q8 > 0 ? (e->tau * (256 - (p->hyst_q8 > 256 ? 256 : p->hyst_q8))) >> 8 : e->tau;
    /* no frame state (bt_attach with st NULL): no hysteresis, no budget rule */
    if (!t->st && (p->hyst_q8 > 0 || p->mode == BT_BUDGET)) return BR_E_ARG;
    /* decide reads ST_PREV through e->prev; without frame state tau_lo = tau, and
     * then the bit never changes an answer (lhs > tau_lo d is false where it is
     * read), so any nslot / 8 readable bytes do: the node array's */
    e->prev = t->st ? bti_st(t, ST_PREV) : (const uint8_t *)(const void *)t->node;
    /* morph_of multiplies (rho - tau) < morph_span by 2^15: morph_span < 2^31 * 2^16 / 2^8
     * = 2^39 keeps it below 2^54 (a range of 256 thresholds is already absurd) */
    if (p->morph_q8 < 0 || p->morph_q8 > 65536) return BR_E_ARG;
    e->morph_span = (e->tau * p->morph_q8) >> 8;
    return BR_OK;
}

br_status bt_count(bt_tree *t, const bt_params *p, uint64_t *ntri)
{
    bti_extract e;
    br_status s = bti_setup(&e, t, p);
    if (s != BR_OK) return s;
    if (p->mode == BT_BUDGET) { *ntri = p->budget; return BR_OK; }
    e.count_only = 1;
    e.tau_lo = e.tau;   /* counting ignores (and never touches) hysteresis state */
    run(&e);
    *ntri = e.count;
    return BR_OK;
}

br_status bt_extract(bt_tree *t, const bt_params *p, bt_mesh *m)
{
    bti_extract e;
    br_status s = bti_setup(&e, t, p);
    uint32_t i, nid = 0, nprev, *ids;
    uint32_t *old;
    uint8_t *prev;
    if (s != BR_OK) return s;
    if (!m || !m->v) return BR_E_ARG;
    e.m = m;
    e.direct = (uint64_t)t->n * (uint64_t)t->n <= 2 * ((uint64_t)m->hmask + 1);
    {
        uint32_t hl = m->hmask - (m->hmask >> 2);
        e.lim_nv = (hl < m->cap_v ? hl : m->cap_v) - 6;
        e.lim_ns = m->cap_s - 10;
    }
    ids = bti_ids_of(m);
    old = (uint32_t *)(void *)bti_heap_of(m);
    /* hysteresis bookkeeping: ids[0..nsplits) are the previous frame's splits
     * (ST_PREV set).  Move them aside (the heap area) before anything reuses ids. */
    nprev = t->st ? m->nsplits : 0;
    memmove(old, ids, (size_t)nprev * 4);
    m->nsplits = 0;
    prev = t->st ? bti_st(t, ST_PREV) : NULL;   /* (a local: a byte store may alias t) */
    if (p->mode != BT_VIEW) {
        for (i = 0; i < nprev; i++) bti_byte_clear(prev, old[i]);
        nprev = 0;
    }
    e.hbase = bti_reset_mesh(m);
    if (!t->st) {
        /* no frame state: the selection alone, no fallback to the budget rule */
        run(&e);
        if (e.full) { bti_reset_mesh(m); return BR_E_NOMEM; }
        btw_reorder(&e);
        return e.full ? BR_E_NOMEM : BR_OK;
    }
    if (p->mode == BT_BUDGET) {
        bti_budget_mark(&e, p->budget < m->max_tri ? p->budget : m->max_tri, &nid);
        e.tau = -1;
        e.fid = 0;
    } else {
        e.rec_splits = p->mode == BT_VIEW ? 1 : 0;
        if (e.rec_splits && bti_coh_frame(&e, &m->coh))
            bti_memo_clear(m->memo, m->memo_mask + 1);
        run(&e);
        if (!e.full) {
            if (e.rec_splits) {
                /* previous frame's marks go; this frame's splits get them */
                for (i = 0; i < nprev; i++) bti_byte_clear(prev, old[i]);
                if (e.lost) {
                    bti_st_wipe(t);
                    m->nsplits = 0;
                } else {
                    for (i = 0; i < m->nsplits; i++) bti_bit_set(prev, ids[i]);
                }
            }
            btw_reorder(&e);
            return e.full ? BR_E_NOMEM : BR_OK;
        }
        /* defined downgrade: the selection needs more than m holds; spend the
         * capacity by priority (the budget rule) instead */
        for (i = 0; i < nprev; i++) bti_byte_clear(prev, old[i]);
        m->nsplits = 0;
        e.hbase = bti_reset_mesh(m);
        e.full = 0; e.rec_splits = 0; e.lost = 0;
        bti_budget_mark(&e, m->max_tri, &nid);
        e.tau = -1;
        e.fid = 0;
        m->overflow = 1;
    }
    run(&e);
    bti_st_unmark(t, ids, nid);
    btw_reorder(&e);
    return e.full ? BR_E_NOMEM : BR_OK;
}
