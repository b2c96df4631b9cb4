/* core/bt_em.h — the extraction state shared by the bitree's selection
 * (core/bt_mesh.c) and its strip writer (core/bt_emit.c); internal, not part of
 * the public contract (bitree.h). */
#ifndef BR_BT_EM_H
#define BR_BT_EM_H
#include <stdint.h>
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/config.h"

/* Every slot's ST_PREV cleared (a split list that overflowed) */
static inline void bti_st_wipe(bt_tree *t)
{
    memset(bti_st(t, ST_PREV), 0, bti_plane_bytes(t->nslot));
}

/* The budget rule's marks cleared: ids[0 .. n) are the slots it pushed, which hold
 * every ST_MARK bit (bti_budget_mark) */
static inline void bti_st_unmark(bt_tree *t, const uint32_t *ids, uint32_t n)
{
    uint8_t *mark = bti_st(t, ST_MARK);
    uint32_t i;
    for (i = 0; i < n; i++) bti_byte_clear(mark, ids[i]);
}

/* Words of a decision memo entry: the decision, and with BR_COHERENCE its expiry
 * (core/bt_mesh.c decide_memo) */
#if BR_COHERENCE
#define BTI_MEMO_W 2
#else
#define BTI_MEMO_W 1
#endif

/* The memo entry slot idx maps to (core/bt_mesh.c decide_memo) */
static inline uint64_t *bti_memo_slot(const bt_mesh *m, uint32_t idx)
{
    return &m->memo[((idx * 2654435761u >> 8) & m->memo_mask) * BTI_MEMO_W];
}

/* The second word of slot idx's memo entry (its expiry), 0 when the entry is another's */
static inline uint64_t bti_memo_w(const bt_mesh *m, uint32_t idx)
{
#if BR_COHERENCE
    const uint64_t *slot = bti_memo_slot(m, idx);
    return (uint32_t)(slot[0] & 0x3fffffffu) == idx ? slot[1] : 0;
#else
    (void)m; (void)idx;
    return 0;
#endif
}

/* bt_mesh_init_v's layout of m in mem without clearing its hash and memo, which the
 * caller clears before use (core/bt_part.c clears what each part uses). */
br_status bti_mesh_layout(bt_mesh *m, uint32_t max_tri, uint32_t max_v, uint32_t max_budget, void *mem,
                          size_t mem_bytes);

/* Forgets every decision of a memo of `entries` entries (no generation matches 0) */
static inline void bti_memo_clear(uint64_t *memo, uint32_t entries)
{
    memset(memo, 0, (size_t)entries * 8 * BTI_MEMO_W);
}

/* A vertex on its way down the recursion; idx caches its output index (the
 * children of a split share their parent's pt instances, so most lookups are
 * answered here and only the first use per instance goes to the hash). */
typedef struct bti_pt { int32_t x, y, z; uint32_t idx; uint16_t morph; uint32_t ri; } bti_pt;
#define BTI_NO_IDX 0xFFFFFFFFu

/* A leaf waiting to be written: its vertex indices, exit edge {o0, o1} and the
 * third vertex */
typedef struct bti_leaf { uint32_t ia, ic, ib, o0, o1, other; } bti_leaf;

/* The walk's output state when a record is made (before its triangle's leaves): the part
 * mesh's counts and the strip writer's, from which a walk can resume there (core/
 * bt_replay.c bti_part_resume) */
typedef struct bti_rec_at {
    uint64_t count;
    uint32_t nv, ns, ntri, nline, nz, nsplits, nsnap;
    int32_t has_pend;
    bti_leaf pend;
} bti_rec_at;

/* A part's walk records each decision it makes (core/bt_replay.c bti_part_replay): the
 * diamond (x, y) in slot idx, the answer sp, the plane mask it handed on (m_out);
 * the records of its triangle's apex (cref: the split whose children it is, which
 * handed it its plane mask) and hypotenuse ends (aref, bref); for a split, the split
 * vertex's height z and weight morph and its index in the part's vertices (vidx,
 * BTI_NO_IDX when no leaf used it).  A point's ri is the record of the split that
 * made it, or BTI_REF_A / C / B for the part root's corners. */
typedef struct bti_rec {
    uint64_t w;             /* the answer's memo entry's second word then (0: none) */
    int32_t z;
    uint32_t idx, aref, bref, cref, vidx;
    uint16_t x, y, morph;
    uint16_t morph0;        /* the answer's weight (before bti_mid_z) */
    uint8_t m_out;
    int8_t sp;
    uint8_t terms;          /* lo, hi, lhs hold bti_morph_terms (a moving weight's) */
    uint8_t moved;          /* a replay changed z or morph (its children's ends moved) */
    uint8_t pbit;           /* 1 << (idx & 7): idx's bit in its byte of the ST_PREV plane */
    int32_t lo[3], hi[3];
    int64_t lhs;
    uint32_t wdlo, wdhi;    /* a moving weight: morph0 holds while the box distance stays
                               in [wdlo, wdhi] (bti_coh_weight_run; wdlo > wdhi: make it), */
    uint64_t wexp;          /* so while the eye's travel (coh_acc) stays <= wexp */
    bti_rec_at at;          /* the walk's state then */
} bti_rec;
/* A strip writer's test that reads vertex heights, kept by a part's walk (bt_mesh.zlog)
 * so that a replay can tell whether moved heights change the strip: kind 0 rim_line
 * (core/bt_emit.c) of vertices a, b, c, kind 1 bti_flat; its answer then. */
typedef struct bti_ztest { uint32_t a, b, c; uint8_t kind, answer; } bti_ztest;
static inline int bti_zlog(bt_mesh *m, int kind, uint32_t a, uint32_t b, uint32_t c, int answer)
{
    if (BR_COHERENCE && m->zlog) {      /* parts replay only with frame coherence */
        if (m->nz < m->cap_z) {
            bti_ztest *t = &m->zlog[m->nz];
            t->a = a; t->b = b; t->c = c; t->kind = (uint8_t)kind; t->answer = (uint8_t)answer;
        }
        m->nz++;
    }
    return answer;
}

#define BTI_REF_A 0xFFFFFFFDu
#define BTI_REF_C 0xFFFFFFFEu
#define BTI_REF_B 0xFFFFFFFFu

/* A budget heap entry: priority, padded grid index, its slot's place in the ids list */
typedef struct bti_heap_ent { int64_t key; uint32_t id; uint32_t pos; } bti_heap_ent;

typedef struct bti_extract {
    bt_tree *t;
    const bt_params *p;
    bt_mesh *m;
    int count_only;
    uint64_t count;
    int32_t S, n;
    uint16_t cthr;          /* fidelity: split iff code > cthr */
    /* view */
    cam_plane pl[CAM_NPLANES];
    int64_t fq8;            /* f in Q8 pixels (f_q16 >> 8) */
    int64_t tau;            /* q8 pixels */
    int64_t tau_lo;         /* with hysteresis */
    const uint8_t *prev;    /* where decide reads ST_PREV: its plane of t->st (see bti_setup) */
    int64_t morph_span;     /* q8 pixels: tau * morph/256 */
    int full;               /* mesh full: stop emitting */
    int rec_splits;         /* 1: list this frame's splits in the mesh's id list (view mode,
                               hysteresis), serial walk and parts alike */
    int lost;               /* the split list overflowed */
    int nonvoid;            /* the padded grid has no void sample: skip the checks */
    int nodata_free;        /* the grid as read has none: a sample is valid iff in it */
    int32_t wz_lo[256], wz_hi[256]; /* world z of the quantised height codes (floor, ceil),
                                       within +-CAM_COORD_MAX (bti_setup) */
    bti_leaf pend;          /* the leaf waiting to be written (has_pend) */
    int has_pend;
    uint32_t plan[BTS_PLAN]; int nplan; /* a bridge's way on to the next leaf */
    uint32_t lim_nv, lim_ns;  /* room for two more leaves: vertices, strip indices */
    int fid;                /* plain fidelity rule (no budget marks) */
    int direct;             /* vertex hash slots by grid key (see home) */
    uint32_t hbase;         /* vertex hash generation (see reset_mesh) */
    uint32_t nbreak;        /* breaks of the walk, bridged or restarted (the reorder pass
                               runs if > 0) */
    int reorder;            /* p->strip_order asks for the reorder pass in this mode */
    int bridge;             /* a break of the walk gets the shortest bridge (core/bt_strip.c),
                               else the fixed restart (bti_setup: not per frame) */
    int64_t (*rho)(const struct bti_extract *e, int32_t x, int32_t y);
                            /* view and budget modes: the projected error of diamond (x, y)
                               in 1/256 pixel, -1 when culled (core/bt_mesh.c; the budget's
                               priority, core/bt_budget.c, calls it through here) */
    struct bti_snap *snap;  /* a part's walk: the writer's state after each of its first
                               BTI_SNAPS leaves (core/bt_part.c), else NULL */
    uint32_t nsnap;
    const bt_coh *coh;      /* frame coherence (bti_coh_frame): expiries are computed; NULL: not */
    uint64_t coh_acc;       /* its eye's accumulated travel now; UINT64_MAX: no entry of
                               an earlier frame is reused */
    uint64_t coh_ctr[BT_COH_NCTR];      /* bt_coh's ctr, an entry's expiry on
                               coh_ctr[bti_coh_ctr_of[its plane mask]] (UINT64_MAX where
                               coh_acc is) */
    bti_rec *recs;          /* a part's walk: its decisions (bti_rec), else NULL */
    uint32_t nrec, cap_rec; /* recorded, room; nrec > cap_rec: some were not */
} bti_extract;

/* The walk's output state as it stands, into a record's (bti_rec.at) */
static inline void bti_rec_at_take(const bti_extract *e, bti_rec_at *a)
{
    const bt_mesh *m = e->m;
    a->count = e->count;
    a->nv = m->nv; a->ns = m->ns; a->ntri = m->ntri; a->nline = m->nline; a->nz = m->nz;
    a->nsplits = m->nsplits; a->nsnap = e->nsnap;
    a->has_pend = e->has_pend;
    a->pend = e->pend;
}

/* The mesh's tail area (core/bt_mesh_mem.c): the split id list (heap_cap entries), then
 * the budget heap (bti_heap_n entries; heap_cap is even, so the heap stays 8-byte aligned); the
 * reorder pass borrows the heap as scratch.  The heap is the first of the scratch
 * bytes a caller may borrow between extractions (bt_mesh_lend_scratch). */
static inline uint32_t bti_heap_cap(const bt_mesh *m) { return m->heap_cap ? m->heap_cap : 4 * m->max_tri + 8; }
static inline uint32_t *bti_ids_of(const bt_mesh *m) { return m->splits; }
static inline bti_heap_ent *bti_heap_of(const bt_mesh *m) { return (bti_heap_ent *)(void *)(m->splits + bti_heap_cap(m)); }
/* entries of the budget heap: bti_heap_cap unless bt_mesh_init_vb gave fewer (at least
 * a quarter: bt_extract moves the split list into the heap's bytes) */
static inline uint32_t bti_heap_n(const bt_mesh *m) { return m->heap_n ? m->heap_n : bti_heap_cap(m); }

/* core/bt_emit.c: writes leaf L (N: the next leaf, or NULL), 1 when N was
 * written too; writes the pending leaf; after a complete extraction whose walk
 * broke, rewrites the strip in a greedy leaf order when the mode asks for it
 * (e->reorder) and that is shorter. */
int btw_write_leaf(bti_extract *e, const bti_leaf *L, const bti_leaf *N);
void btw_flush(bti_extract *e);
void btw_reorder(bti_extract *e);

/* ------------------------------------------------------------ parts (core/bt_part.c)
 * The view walk cut into at most BT_PARTS subtrees: the triangles at depth
 * BTI_PART_DEPTH below the two roots (2 << depth of them), or shallower leaves. */
#define BTI_PART_DEPTH 4
/* Part roots below BTI_PART_DEPTH: a part whose mesh had more than BTI_PART_SPLIT
 * triangles is cut from the next frame on into pieces of at most that many (bt_part.c
 * cut_by_count), down to depth BTI_PART_DEPTH_MAX;
 * two halves with fewer than BTI_PART_MERGE between them are one again (bt_part.c
 * regroup).  A triangle of the part walk is named by its code: 2 and 3 for the two
 * roots, 2 code and 2 code + 1 for the halves of code (so depth + 1 bits). */
#define BTI_PART_SPLIT 160
#define BTI_PART_MERGE 80
#define BTI_PART_DEPTH_MAX 24
#define BTI_PART_DEEP (BT_PARTS - (2 << BTI_PART_DEPTH))
#define BTI_TOP_MEMO 512
typedef struct bti_root { bti_pt a, c, b; int32_t in_hyp, out_hyp; uint32_t mask; } bti_root;

static inline int bti_same_pt(const bti_pt *a, const bti_pt *b) { return a->x == b->x && a->y == b->y; }

/* Whether roots r and q are the same triangle, entered the same way (their corners'
 * heights and weights aside) */
static inline int bti_same_root(const bti_root *r, const bti_root *q)
{
    return bti_same_pt(&r->a, &q->a) && bti_same_pt(&r->c, &q->c) && bti_same_pt(&r->b, &q->b)
        && r->in_hyp == q->in_hyp && r->out_hyp == q->out_hyp;
}

/* The writer's state after a part's leaf L was handed to it: strip length, its
 * last two indices, the pending leaf, whether a bridge's plan is open */
#define BTI_SNAPS 16
typedef struct bti_snap {
    bti_leaf L, pend;
    uint32_t ns, t0, t1;
    int32_t has_pend, nplan;
} bti_snap;

/* The geomorph weights' own coherence (core/bt_replay.c bti_part_replay): a moving weight is
 * made again only when its box distance leaves the run of distances that give it
 * (bti_coh_weight_run), found from the reciprocals of tau + q, q = 1 .. span, for spans
 * up to BTI_WQ_MAX (larger: on = 0, the weight is made every frame). */
#define BTI_WQ_MAX 256
typedef struct bti_wtab {
    int64_t tau, span;          /* what r, sh were made for */
    int32_t on;                 /* the spans fit (zeroed: tau = span = 0, off) */
    uint32_t r[BTI_WQ_MAX + 1]; /* floor(2^sh[q] / (tau + q)), 0: none (quot_lo's) */
    uint8_t sh[BTI_WQ_MAX + 1];
    int64_t slack;              /* test hook: widens every run (other meshes); 0 outside tests */
} bti_wtab;

struct bt_parts {
    uint32_t part_tri;             /* triangles each part mesh holds */
    bt_tree *t;                    /* the extraction in progress (begin .. end) */
    const bt_params *p;
    bt_mesh *m;
    int32_t serial;                /* 1: begin extracted serially, nothing to join */
    bti_extract e0;                /* set up once; each part starts from a copy */
    bti_root root[BT_PARTS];       /* part roots in walk order */
    uint32_t nroot;
    uint32_t top_ids[BT_PARTS];    /* diamonds split above the roots (< BT_PARTS of them) */
    uint32_t ntop;
    uint32_t root_code[BT_PARTS];  /* each root's code (BTI_PART_SPLIT) */
    /* the triangles below BTI_PART_DEPTH to cut this frame (deep) and those cut (used) */
    uint32_t deep[BTI_PART_DEEP + 1], ndeep, used[BTI_PART_DEEP + 1], nused;
    int cut_fresh;                 /* no cut yet: bt_extract_begin makes the first (cut_initial) */
    uint32_t voff[BT_PARTS];       /* part k's vertices go to m->v + voff[k] */
    uint32_t soff[BT_PARTS], skip[BT_PARTS]; /* its strip from index skip[k] to m->strip + soff[k] */
    /* A part's slot: its mesh and extraction, written by its thread at every leaf
     * (counts, pending leaf), and what the next frame's replay of the same root needs
     * (bti_part_replay).  Slot k holds root k's part; bt_extract_begin moves each slot to
     * the root of its code (match_slots), so a part that did not change stays
     * replayable when the parts before it are cut or joined.  The padding keeps the
     * slots off each other's cache lines. */
    struct bti_slot {
        bt_mesh m;
        bti_extract e;
        bti_snap snap[BTI_SNAPS];
        uint32_t code;             /* the root's code it last walked (0: none) */
        /* its decisions of that walk (bti_rec), the root and the indices of the root's
         * corners in its vertices; reuse 1 when the walk was complete and every
         * decision recorded */
        bti_rec *rec;
        uint32_t nrec;
        uint8_t *vmoved;           /* a replay's moved vertices, a bit each (vbits of them) */
        uint32_t last_voff;        /* where its vertices went in the last frame joined from
                                      parts (UINT32_MAX: none) */
        uint32_t from_voff;        /* this frame's joined vertices are the ones that went to
                                      from_voff in the frame before, but for vmoved's (UINT32_MAX:
                                      none; bt_part_moved_from) */
        bti_root last_root;
        uint32_t ridx[3];
        uint8_t reuse;
        uint8_t done;              /* extracted since this frame's bt_extract_begin */
        uint32_t hbase;            /* vertex hash generation (part_reset) */
        uint32_t hins;             /* hash slots this generation wrote (a resumed walk writes
                                      again slots of vertices past where it resumed, which
                                      stay taken); no walk of it had more vertices */
        uint32_t hint_nv;          /* vertices last frame: the hash and memo in use */
        /* the first hclean, mclean of the hfull, mfull hash and memo slots are cleared
         * (part_reset): memory a part never needed is never touched */
        uint32_t hclean, mclean;
        uint8_t pad_[64];
    } slot[BT_PARTS];
    uint32_t hfull, mfull, cap_rec; /* slots allocated for each part's hash, memo; records */
    uint32_t vbits;                /* bits of each slot's vmoved (a multiple of 64); a replay
                                      of a part with more vertices lists none */
    uint32_t *cut_tris, *cut_lo, *cut_hi; /* regroup's counts over a part's records (cap_rec) */
    uint8_t replayed[BT_PARTS];    /* part k's mesh this frame is its last one's (bti_part_replay) */
    uint32_t nreused;              /* parts replayed by the last extraction (bt_extract_end) */
    uint8_t resumed[BT_PARTS];     /* part k's walk this frame was taken up where its last
                                      one's first decision changed (bti_part_resume) */
    uint32_t nresumed;             /* such parts in the last extraction (bt_extract_end) */
    bti_extract fx;                /* the seams' writer (bt_extract_end) */
    /* the decision memo of the walk above the parts (bti_part_roots): a mesh with a memo
     * only, BTI_TOP_MEMO entries */
    bt_mesh top_m;
    uint64_t top_memo[BTI_TOP_MEMO * BTI_MEMO_W];
    uint32_t recent[96], nrecent;  /* its vertex identification by (x, y) */
    bt_coh coh;                    /* frame coherence of the parts' memos */
    bti_wtab wt;                   /* and of their records' moving weights (bti_part_replay) */
};

/* 1 when the part walk cuts the triangle of this code (listed in ps->deep, sorted) */
static inline int bti_part_cut(const bt_parts *ps, uint32_t code)
{
    uint32_t lo = 0, hi = ps->ndeep;
    while (lo < hi) {
        const uint32_t mid = (lo + hi) / 2;
        if (ps->deep[mid] < code) lo = mid + 1;
        else hi = mid;
    }
    return lo < ps->ndeep && ps->deep[lo] == code;
}

br_status bti_setup(bti_extract *e, bt_tree *t, const bt_params *p);
uint32_t bti_reset_mesh(bt_mesh *m);
void bti_part_roots(bti_extract *e, bt_parts *ps);
/* core/bt_emit.c rim_line: 1 when the straight rim q-z-r2 may serve as a line triangle */
int bti_rim_line(const bti_extract *e, uint32_t q, uint32_t z, uint32_t r2);
/* Walks part root r; ridx gets the indices of r's corners in the part's vertices. */
void bti_part_walk(bti_extract *e, const bti_root *r, uint32_t ridx[3]);
/* core/bt_replay.c: part k's mesh of the last frame made this frame's without its walk,
 * 1; 0: it cannot be (walk it), *at then the first record whose answer changed (0: none
 * found), where bti_part_resume may take up the walk: 1 when it did */
int bti_part_replay(bt_parts *ps, uint32_t k, uint32_t *at);
int bti_part_resume(bt_parts *ps, uint32_t k, uint32_t at);
/* part k's extraction state for a walk with its mesh's tables as they are */
void bti_part_extract_setup(bt_parts *ps, uint32_t k, bti_extract *e);
/* decide_memo (core/bt_mesh.c): diamond (x, y) in slot idx under plane mask *mask (then
 * the mask handed on), through the mesh's decision memo: -1 culled, 0 leaf, 1 split. */
int bti_decide_memo(bti_extract *e, int32_t x, int32_t y, uint32_t idx, unsigned *mask, uint16_t *morph);
/* The geomorph weight of a split diamond for this frame's eye (BR_COHERENCE), from what
 * does not depend on the eye: the volume lo..hi and lhs = object error times f of
 * diamond (x, y) in slot idx (bti_morph_terms; they change only with the frame key). */
void bti_morph_terms(const bti_extract *e, int32_t x, int32_t y, uint32_t idx, int32_t lo[3], int32_t hi[3],
                     int64_t *lhs);
/* for the box distance d = bti_box_dist(eye, lo, hi) */
uint16_t bti_morph_at(const bti_extract *e, int64_t lhs, int64_t d);
/* decide() itself, without the memo (core/bt_mesh.c) */
int bti_decide_view(bti_extract *e, int32_t x, int32_t y, uint32_t idx, unsigned *mask, uint16_t *morph);
/* The weight decide() gives diamond (x, y) in slot idx when it splits it (view rule) */
uint16_t bti_morph_now(const bti_extract *e, int32_t x, int32_t y, uint32_t idx);
/* The walk of triangle (a, c, b) (core/bt_mesh.c rec), for a part's walk resumed
 * (bti_part_resume) */
void bti_walk_tri(bti_extract *e, bti_pt *a, bti_pt *c, bti_pt *b, int in_hyp, int out_hyp, unsigned mask);
/* The index of e->m's vertex at (x, y), BTI_NO_IDX when it has none */
uint32_t bti_vid_lookup(const bti_extract *e, int32_t x, int32_t y);

/* Height of sample (x, y), 0 outside the grid as read or on a void. */
static inline int32_t bti_zreal(const bt_tree *t, int32_t x, int32_t y)
{
    const hf *f = t->f;
    if (x >= f->w || y >= f->h) return 0;
    {
        int32_t v = f->z[(size_t)y * f->w + x];
        return v == HF_NODATA ? 0 : v;
    }
}

/* Height of split vertex (x, y) with weight *morph on the hypotenuse whose ends have
 * heights az, bz: geomorphed between their interpolation and the real height.  Both
 * triangles of a diamond share the ends, so it is a function of the diamond (given the
 * ends').  A vertex whose real height IS the interpolation (in every mode) carries
 * topology but no information: fictitious (002: deducible, never transmitted), *morph 0;
 * its height is the same either way. */
static inline int32_t bti_mid_z(const bti_extract *e, int32_t az, int32_t bz, int32_t x, int32_t y, uint16_t *morph)
{
    int32_t zs = e->nonvoid ? e->t->f->z[(size_t)y * (size_t)e->n + (size_t)x] : bti_zreal(e->t, x, y);
    int64_t zf = ((int64_t)az + bz) >> 1;
    if (2 * (int64_t)zs == (int64_t)az + bz) *morph = 0;
    return *morph == BT_MORPH_ONE ? zs : (int32_t)(zf + ((((int64_t)zs - zf) * *morph + (1 << 14)) >> 15));
}
/* Frame coherence (core/bt_mesh.c): accounts the eye's travel since c's last frame,
 * or starts afresh when anything else changed; sets e->coh, e->coh_acc.  1 when
 * the memos that c covers must be cleared (the accumulator wrapped). */
int bti_coh_frame(bti_extract *e, bt_coh *c);
/* The second word of a memo entry (core/bt_mesh.c decide_memo) for decide's answer
 * sp (-1 culled, 0, 1) with morph, L = ew f and distance d (d < 0: the answer holds
 * at every distance), made under plane mask m_in, which left m_out, with cull margin
 * cm (Q30 world units, culled()): m_out << 58 | m_in << 52 | moving << 51 | expiry,
 * the expiry (< 2^51) a value of accumulator coh_ctr[bti_coh_ctr_of[m_in]] (the eye's
 * travel for m_in = 0, else that of m_in's plane, or of its planes, each frame's
 * larger of theirs and a quarter of the eye's) up to which the answer holds, moving:
 * a split whose geomorph weight moves with the distance (to be computed again); 0:
 * this frame only. */
#define BTI_COH_BITS 52
#define BTI_COH_MOVING ((uint64_t)1 << 51)
#define BTI_COH_EXP (BTI_COH_MOVING - 1)
uint64_t bti_coh_entry(const bti_extract *e, int sp, int64_t L, int64_t d, uint16_t morph, unsigned m_in,
                       unsigned m_out, int64_t cm);
/* The accumulator (index into coh_ctr) of an entry made under plane mask m_in: 0 for
 * none, 1 + i for plane i alone, 1 + CAM_NPLANES for two or more (core/bt_coh.c) */
extern const uint8_t bti_coh_ctr_of[64];
/* The weights' reciprocals for threshold tau and span (made again only when they change) */
void bti_wtab_set(bti_wtab *wt, int64_t tau, int64_t span);
/* The box distances [*dlo, *dhi] (empty: *dlo > *dhi) at which morph_at gives weight
 * morph for L = ew f (a run of distances: the weight falls as d grows) */
void bti_coh_weight_run(const bti_wtab *wt, int64_t L, uint16_t morph, uint32_t *dlo, uint32_t *dhi);

/* Whether memo word w (bti_coh_entry) proves answer sp of diamond idx now, under plane
 * mask *mask (then *mask is the mask it handed on): the same incoming mask, the travel
 * since within its margin, and the ST_PREV the margin assumed (set iff split): idx's
 * bit is bit pbit (1 << (idx & 7)) of the plane's byte idx >> 3.  An entry is a proof
 * wherever it is kept: decide_memo's memo, a part's records (which keep pbit). */
static inline int bti_coh_proves(const bti_extract *e, uint64_t w, int sp, uint32_t idx, unsigned pbit,
                                 unsigned *mask)
{
    const unsigned m_in = (unsigned)(w >> BTI_COH_BITS) & 63u;
    if (*mask != m_in || e->coh_ctr[bti_coh_ctr_of[m_in]] > (w & BTI_COH_EXP)
        || (sp > 0) != ((e->prev[idx >> 3] & pbit) != 0))
        return 0;
    *mask = (unsigned)(w >> (BTI_COH_BITS + 6));
    return 1;
}

/* Diamond geometry: scale h and type (1 = D) of sample (x, y), not a corner. */
static inline int32_t bti_dscale(int32_t x, int32_t y, int32_t S, int *typeD)
{
    uint32_t u = (uint32_t)(x | y);
    int32_t h;
    if (u == 0) u = (uint32_t)S;
    h = (int32_t)(u & (~u + 1u));
    if (x == 0) h = (int32_t)((uint32_t)y & (~(uint32_t)y + 1u));
    if (y == 0) h = (int32_t)((uint32_t)x & (~(uint32_t)x + 1u));
    if (x == 0 && y == 0) h = S;
    *typeD = (x & h) && (y & h);      /* h is a power of two */
    return h;
}

/* Sample (x, y) lies in the grid as read and is not a void */
static inline int bti_sample_valid(const hf *f, int32_t x, int32_t y)
{
    return x < f->w && y < f->h && f->z[(size_t)y * f->w + x] != HF_NODATA;
}
/* The three corners are valid samples.  Without a void in the grid as read (only the
 * padding), that is: they lie in it, x < w and y < h. */
static inline int bti_tri_valid6(const bti_extract *e, int32_t ax, int32_t ay, int32_t cx, int32_t cy, int32_t bx,
                                 int32_t by)
{
    const hf *f = e->t->f;
    if (e->nonvoid) return 1;
    if (e->nodata_free) {
        int32_t mx = ax > bx ? ax : bx, my = ay > by ? ay : by;
        mx = cx > mx ? cx : mx;
        my = cy > my ? cy : my;
        return mx < e->t->w && my < e->t->h;
    }
    return bti_sample_valid(f, ax, ay) && bti_sample_valid(f, bx, by) && bti_sample_valid(f, cx, cy);
}
static inline int bti_tri_valid(const bti_extract *e, const bti_pt *a, const bti_pt *c, const bti_pt *b)
{
    return bti_tri_valid6(e, a->x, a->y, c->x, c->y, b->x, b->y);
}

/* The nested bounding volume of diamond (x, y) in slot id, world units: the box of
 * half-side 3h (type D) or 2h around the centre, within the padded grid, times the
 * node's quantised height range (core/bt_mesh.c view_err) */
static inline void bti_dvolume(const bti_extract *e, int32_t x, int32_t y, uint32_t id, int32_t lo[3], int32_t hi[3])
{
    const bt_frame *fr = &e->p->fr;
    int typeD;
    int32_t h = bti_dscale(x, y, e->S, &typeD);
    int32_t r = typeD ? 3 * h : 2 * h;
    int32_t x0 = x - r < 0 ? 0 : x - r, x1 = x + r > e->S ? e->S : x + r;
    int32_t y0 = y - r < 0 ? 0 : y - r, y1 = y + r > e->S ? e->S : y + r;
    uint32_t nv = e->t->node[id];
    lo[0] = (int32_t)(fr->ox + (int64_t)x0 * fr->sx);
    hi[0] = (int32_t)(fr->ox + (int64_t)x1 * fr->sx);
    lo[1] = (int32_t)(fr->oy - (int64_t)y1 * fr->sy);
    hi[1] = (int32_t)(fr->oy - (int64_t)y0 * fr->sy);
    lo[2] = e->wz_lo[BT_NODE_ZLO(nv)];
    hi[2] = e->wz_hi[BT_NODE_ZHI(nv)];
}

/* core/bt_budget.c: marks ST_MARK on the diamonds a budget of
 * `budget` nominal triangles buys; the ids it marked go to the mesh's id list
 * (*nid of them, to clear afterwards); sets e->tau to the last split's rho. */
uint32_t bti_budget_mark(bti_extract *e, uint32_t budget, uint32_t *nid);

#endif
