/* core/bt_mesh.c — selection (fidelity, view-dependent, budget, hysteresis,
 * geomorph) and the strip emitter of the bitree (contract: core/bitree.h).
 *
 * Selection.  A diamond (sample) is SPLIT when its value exceeds the threshold:
 *   fidelity  err code > largest code whose value <= max_err (exact compare);
 *   view      rho > tau, rho = projected error (000): object error E (world
 *             units) * f / d, d = a lower bound of the distance from the eye to
 *             the diamond's nested bounding volume (box of half-side 3h / 2h
 *             around the centre x quantised height range), so rho is an upper
 *             bound of the error seen on screen.  Diamonds whose volume lies
 *             outside a frustum plane are culled: neither split nor emitted.
 *             Hysteresis (003): a diamond split in the previous frame stays
 *             split while rho > tau * (1 - hyst).
 *   budget    (003) diamonds are split in decreasing rho order (a heap; ties
 *             coarser first) while the nominal triangle count stays <= budget.
 * E and the volume are monotone up the tree, so every rule splits a set closed
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
 * triangle of three collinear vertices for two turns (004; see write_leaf).
 * Where the walk breaks (after a void or a culled subtree) core/bt_strip.c
 * bridges to the next leaf by the shortest run of line triangles; in fidelity
 * mode a strip with breaks is then written again in a greedy leaf order over
 * the edge adjacency (see reorder), which needs fewer references.  Winding: the first triangle is
 * written counter-clockwise seen from +z (x east, y north); the GL parity rule
 * keeps every later edge-adjacent triangle the same. */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"

enum { ST_PREV = 1, ST_SPLIT = 2, ST_PUSHED = 4, ST_CUR = 8 };

/* A vertex on its way down the recursion; idx caches its output index (the
 * children of a split share their parent's pt instances, so most lookups are
 * answered here and only the first use per instance goes to the hash). */
typedef struct pt { int32_t x, y, z; uint32_t idx; uint16_t morph; } pt;
#define NO_IDX 0xFFFFFFFFu

typedef struct heap_ent { int64_t key; uint32_t id; uint32_t pad_; } heap_ent;

typedef struct em {
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
    int64_t morph_span;     /* q8 pixels: tau * morph/256 */
    int full;               /* mesh full: stop emitting */
    int rec_splits;         /* record this frame's splits (view mode, hysteresis) */
    int lost;               /* the split list overflowed */
    int nonvoid;            /* the padded grid has no void sample: skip the checks */
    int64_t wz_lo[256], wz_hi[256]; /* world z of the quantised height codes (floor, ceil) */
    struct pend_s { uint32_t ia, ic, ib, o0, o1, other; } pend; /* see pend */
    int has_pend;
    uint32_t plan[BTS_PLAN]; int nplan; /* a bridge's way on to the next leaf */
    uint32_t lim_nv, lim_ns;  /* room for two more leaves: vertices, strip indices */
    int fid;                /* plain fidelity rule (no budget marks) */
    int direct;             /* vertex hash slots by grid key (see home) */
    uint32_t hbase;         /* vertex hash generation (see reset_mesh) */
    uint32_t nbreak;        /* breaks of the walk bridged (the reorder pass runs if > 0) */
} em;

/* ------------------------------------------------------------ mesh memory */
static uint32_t hash_size(uint32_t cap_v)
{
    uint32_t s = 16;
    while (s < 2 * cap_v && s < 0x80000000u) s <<= 1;
    return s;
}

size_t bt_mesh_mem_size(uint32_t max_tri)
{
    uint64_t cap_v, cap_s, hs, heap, sz;
    if (max_tri < 2 || max_tri > 0x10000000u) return 0;
    cap_v = 3ull * max_tri + 3;
    cap_s = 5ull * max_tri + 8;
    hs = hash_size(2 * max_tri + 16);
    heap = 4ull * max_tri + 8;
    sz = cap_v * sizeof(bt_vert) + cap_s * 4 + hs * 4 + 4 + heap * sizeof(heap_ent) + heap * 4 + 64;
    if (sz > (uint64_t)SIZE_MAX) return 0;      /* 32-bit hosts */
    return (size_t)sz;
}

br_status bt_mesh_init(bt_mesh *m, uint32_t max_tri, void *mem, size_t mem_bytes)
{
    uint8_t *p = (uint8_t *)mem;
    uint32_t cap_v, cap_s, hs;
    if (!m || !mem || max_tri < 2 || max_tri > 0x10000000u) return BR_E_ARG;
    if (mem_bytes < bt_mesh_mem_size(max_tri)) return BR_E_ARG;
    if (((uintptr_t)mem & 7) != 0) return BR_E_ARG;
    memset(m, 0, sizeof *m);
    cap_v = 3 * max_tri + 3;
    cap_s = 5 * max_tri + 8;
    hs = hash_size(2 * max_tri + 16);
    m->max_tri = max_tri;
    m->v = (bt_vert *)(void *)p; p += (size_t)cap_v * sizeof(bt_vert);
    m->cap_v = cap_v;
    m->hash = (uint32_t *)(void *)p; p += (size_t)hs * 4 + 4;
    m->hmask = hs - 1;
    memset(m->hash, 0, (size_t)hs * 4 + 4);   /* + the generation word, see reset_mesh */
    m->strip = (uint32_t *)(void *)p; p += (size_t)cap_s * 4;
    m->cap_s = cap_s;
    p += (8 - ((uintptr_t)p & 7)) & 7;
    m->splits = (uint32_t *)(void *)p;   /* heap entries + id list share this tail */
    return BR_OK;
}

static heap_ent *heap_of(const bt_mesh *m) { return (heap_ent *)(void *)m->splits; }
static uint32_t heap_cap(const bt_mesh *m) { return 4 * m->max_tri + 8; }
static uint32_t *ids_of(const bt_mesh *m) { return (uint32_t *)(void *)(heap_of(m) + heap_cap(m)); }

/* ------------------------------------------------------------ samples */
static int valid(const bt_tree *t, int32_t x, int32_t y)
{
    const hf *f = t->f;
    if (x >= f->w || y >= f->h) return 0;
    return f->z[(size_t)y * f->w + x] != HF_NODATA;
}

static int32_t zreal(const bt_tree *t, int32_t x, int32_t y)
{
    const hf *f = t->f;
    if (x >= f->w || y >= f->h) return 0;
    {
        int32_t v = f->z[(size_t)y * f->w + x];
        return v == HF_NODATA ? 0 : v;
    }
}

/* diamond geometry: scale h and type (1 = D) of sample (x, y), not a corner */
static int32_t dscale(int32_t x, int32_t y, int32_t S, int *typeD)
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

/* ------------------------------------------------------------ view */
static int64_t isat_mul(int64_t a, int64_t b)
{
    if (a == 0 || b == 0) return 0;
    if (a > INT64_MAX / b) return INT64_MAX;
    return a * b;
}

/* Lower bound of the distance from the eye to the box [lo, hi] (world units):
 * max(|dmax|, (|dx|+|dy|+|dz|) * 147/256), 147/256 < 1/sqrt(3). */
static int64_t box_dist(const int32_t eye[3], const int64_t lo[3], const int64_t hi[3])
{
    int64_t d[3], mx = 0, s = 0, l1;
    int i;
    for (i = 0; i < 3; i++) {
        int64_t e = eye[i];
        d[i] = e < lo[i] ? lo[i] - e : (e > hi[i] ? e - hi[i] : 0);
        if (d[i] > mx) mx = d[i];
        s += d[i];
    }
    l1 = (s * 147) >> 8;
    return l1 > mx ? l1 : mx;
}

static void dvolume(const em *e, int32_t x, int32_t y, int64_t lo[3], int64_t hi[3])
{
    const bt_tree *t = e->t;
    const bt_frame *fr = &e->p->fr;
    int typeD;
    int32_t h = dscale(x, y, e->S, &typeD);
    int32_t r = typeD ? 3 * h : 2 * h;
    int32_t x0 = x - r < 0 ? 0 : x - r, x1 = x + r > e->S ? e->S : x + r;
    int32_t y0 = y - r < 0 ? 0 : y - r, y1 = y + r > e->S ? e->S : y + r;
    size_t idx = (size_t)y * e->n + x;
    lo[0] = fr->ox + (int64_t)x0 * fr->sx;
    hi[0] = fr->ox + (int64_t)x1 * fr->sx;
    lo[1] = fr->oy - (int64_t)y1 * fr->sy;
    hi[1] = fr->oy - (int64_t)y0 * fr->sy;
    lo[2] = e->wz_lo[BT_NODE_ZLO(t->node[idx])];
    hi[2] = e->wz_hi[BT_NODE_ZHI(t->node[idx])];
    (void)t;
}

/* Frustum test of a box against the planes in *mask: 1 when it lies wholly
 * outside one of them (culled); planes it lies wholly inside are removed from
 * *mask, so descendants (whose volumes nest inside) skip them. */
static int culled(const em *e, const int64_t lo[3], const int64_t hi[3], unsigned *mask)
{
    int i, k;
    if (e->p->no_cull) { *mask = 0; return 0; }
    for (i = 0; i < CAM_NPLANES; i++) {
        int64_t sp, sn;
        if (!(*mask & (1u << i))) continue;
        sp = sn = e->pl[i].d;
        for (k = 0; k < 3; k++) {
            int64_t nk = e->pl[i].n[k];
            sp += nk * (nk >= 0 ? hi[k] : lo[k]);
            sn += nk * (nk >= 0 ? lo[k] : hi[k]);
        }
        if (sp < 0) return 1;
        if (sn >= 0) *mask &= ~(1u << i);
    }
    return 0;
}

/* Screen-space error of diamond (x, y): *ew = object error in world units
 * (rounded up), *d = lower bound of the distance to its volume.  Returns -1 when
 * culled (all void or outside the frustum), 1 when the error is unbounded (mixed
 * voids, or the eye inside the volume with a nonzero error), 0 otherwise. */
static int view_err(const em *e, int32_t x, int32_t y, unsigned *mask, int64_t *ew, int64_t *d)
{
    const bt_tree *t = e->t;
    size_t idx = (size_t)y * e->n + x;
    int64_t lo[3], hi[3];
    uint32_t nv = t->node[idx];
    uint16_t code = BT_NODE_ERR(nv);
    if (BT_NODE_ZLO(nv) > BT_NODE_ZHI(nv)) return -1; /* all void */
    dvolume(e, x, y, lo, hi);
    if (*mask && culled(e, lo, hi, mask)) return -1;
    if (code == BT_CODE_SPLIT) return 1;
    *ew = isat_mul(bt_code_value(code), e->p->fr.sz_q16);
    *ew = *ew == INT64_MAX ? *ew : (*ew + 65535) >> 16;
    *d = box_dist(e->p->c->eye, lo, hi);
    if (*d <= 0) { *d = 0; return *ew > 0 ? 1 : 0; }
    return 0;
}

/* rho in q8 pixels; -1 when culled */
static int64_t rho_q8(const em *e, int32_t x, int32_t y)
{
    unsigned mask = 0x3f;
    int64_t ew = 0, d = 0;
    int r = view_err(e, x, y, &mask, &ew, &d);
    if (r < 0) return -1;
    if (r > 0) return INT64_MAX;
    if (d == 0) return 0;
    return isat_mul(ew, e->fq8) / d;
}

static br_status setup(em *e, bt_tree *t, const bt_params *p);

int64_t bt_screen_error_q8(const bt_tree *t, const bt_params *p, int32_t x, int32_t y)
{
    em e;
    int64_t r;
    if (!p || p->mode == BT_FIDELITY || setup(&e, (bt_tree *)t, p) != BR_OK) return 0;
    r = rho_q8(&e, x, y);
    return r < 0 ? 0 : r;
}

/* ------------------------------------------------------------ split rule */
static uint16_t morph_of(const em *e, int64_t rho)
{
    int64_t q = rho - e->tau;
    if (e->morph_span <= 0) return BT_MORPH_ONE;
    if (q < 0) q = 0;
    if (q >= e->morph_span) return BT_MORPH_ONE;
    return (uint16_t)((q * BT_MORPH_ONE) / e->morph_span);
}

/* returns 1 split, 0 leaf, -1 drop (culled); *morph set for split vertices;
 * *mask: frustum planes still to test (view and budget modes) */
static int decide(em *e, int32_t x, int32_t y, unsigned *mask, uint16_t *morph)
{
    bt_tree *t = e->t;
    size_t idx = (size_t)y * e->n + x;
    int64_t ew = 0, d = 0;
    int r;
    *morph = BT_MORPH_ONE;
    if (e->fid) return BT_NODE_ERR(e->t->node[idx]) > e->cthr;
    if (e->p->mode == BT_BUDGET || e->tau < 0) {
        if (e->p->mode == BT_FIDELITY) return (t->st[idx] & ST_SPLIT) != 0;
        r = view_err(e, x, y, mask, &ew, &d);
        if (r < 0) return -1;
        if (!(t->st[idx] & ST_SPLIT)) return 0;
        if (e->morph_span > 0 && r == 0 && d > 0) *morph = morph_of(e, isat_mul(ew, e->fq8) / d);
        return 1;
    }
    r = view_err(e, x, y, mask, &ew, &d);
    if (r < 0) return -1;
    if (r > 0) return 1;
    {
        /* rho = ew * f / d > tau  <=>  ew * f > tau * d (no division) */
        int64_t lhs = isat_mul(ew, e->fq8);
        int sp = lhs > isat_mul(e->tau, d) ||
                 ((t->st[idx] & ST_PREV) && lhs > isat_mul(e->tau_lo, d));
        if (sp && e->morph_span > 0) *morph = morph_of(e, d > 0 ? lhs / d : INT64_MAX);
        return sp;
    }
}

/* ------------------------------------------------------------ strip */
/* Home slot of grid key y n + x in the dedup hash: the key itself when the table
 * has >= n^2 / 2 slots (<= 2 keys per slot; the walk's spatial coherence stays in
 * the table's cache lines), else a multiplicative hash.  Collisions of direct
 * slots probe with a scattered odd step (double hashing), never along the dense
 * run a fully refined region forms; hashed slots probe linearly (cache lines).
 * Only speed depends on it. */
static uint32_t home(uint32_t key, uint32_t mask, int direct)
{
    return (direct ? key : key * 2654435761u) & mask;
}

static uint32_t vid_find(em *e, pt *q)
{
    bt_mesh *m = e->m;
    uint32_t key = (uint32_t)q->y * (uint32_t)e->n + (uint32_t)q->x;
    uint32_t h = home(key, m->hmask, e->direct);
    for (;;) {
        uint32_t s = m->hash[h] - e->hbase;   /* 1 + index; <= 0 (wrapped): empty */
        if (s == 0 || s > m->nv) break;
        if (m->v[s - 1].x == q->x && m->v[s - 1].y == q->y) return q->idx = s - 1;
        h = (h + (e->direct ? ((key * 2654435761u) >> 15) | 1u : 1u)) & m->hmask;
    }
    {
        uint32_t i = m->nv++;
        bt_vert *v = &m->v[i];
        v->x = q->x; v->y = q->y; v->z = q->z;
        v->morph = q->morph;
        v->state = q->morph == BT_MORPH_ONE ? BT_S : BT_F;
        v->pad_ = 0;
        if (v->state == BT_F) m->nfict++;
        m->hash[h] = e->hbase + i + 1;
        return q->idx = i;
    }
}


static uint32_t vid(em *e, pt *q) { return q->idx != NO_IDX ? q->idx : vid_find(e, q); }
static void push(bt_mesh *m, uint32_t i) { m->strip[m->ns++] = i; }

/* A leaf waiting to be written: its vertex indices, exit edge {o0, o1} and the
 * third vertex */
typedef struct pend_s pend;

static int collinear(const bt_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    const bt_vert *A = &m->v[a], *B = &m->v[b], *C = &m->v[c];
    return (int64_t)(B->x - A->x) * (C->y - A->y) == (int64_t)(B->y - A->y) * (C->x - A->x);
}

/* Writes leaf L (the next leaf N, if any, is known: one leaf of lookahead).
 * Returns 1 when N was written too.  The strip's last two indices are kept equal
 * to the written leaf's exit edge, so the next leaf shares them.  When L must
 * swap (its pivot is the older index) and N turns around the same pivot with
 * L's new vertex, the old one and N's new vertex collinear (a straight rim of
 * the fan), the rim itself makes the line triangle (002 figure 10, 004's
 * collinearity): "z r2 P" writes both leaves with one line triangle instead of
 * two swaps, and leaves the pivot newest for N's successor. */
static int write_leaf(em *e, const pend *L, const pend *N)
{
    bt_mesh *m = e->m;
    uint32_t n3[3];
    if (e->nplan > 0) {
        if (N) { n3[0] = N->ia; n3[1] = N->ic; n3[2] = N->ib; }
        if (bts_follow(m, e->plan, &e->nplan, L->o0, L->o1, N ? n3 : NULL)) return 0;
    }
    if (m->ns >= 2) {
        uint32_t p = m->strip[m->ns - 2], q = m->strip[m->ns - 1];
        int hp = p == L->ia || p == L->ic || p == L->ib, hq = q == L->ia || q == L->ic || q == L->ib;
        int cont = !N || ((N->ia == L->o0 || N->ic == L->o0 || N->ib == L->o0) &&
                          (N->ia == L->o1 || N->ic == L->o1 || N->ib == L->o1));
        if (!(hp && hq && p != q && cont)) {
            /* a break of the walk before L or after it: bridge it (bt_strip.c) */
            uint32_t l3[3];
            l3[0] = L->ia; l3[1] = L->ic; l3[2] = L->ib;
            if (N) { n3[0] = N->ia; n3[1] = N->ic; n3[2] = N->ib; }
            e->nbreak++;
            if (bts_bridge(m, l3, N ? n3 : NULL, N ? N->o0 : 0, N ? N->o1 : 0, e->plan, &e->nplan) == 0) return 0;
        }
        if (hp && hq && p != q) {
            uint32_t z = (p != L->ia && q != L->ia) ? L->ia : ((p != L->ic && q != L->ic) ? L->ic : L->ib);
            int qin = q == L->o0 || q == L->o1, pin = p == L->o0 || p == L->o1;
            if (!qin && pin) {
                /* swap needed: try the straight-rim pair with N (pivot p) */
                if (N && ((N->o0 == p && N->o1 != z) || (N->o1 == p && N->o0 != z))) {
                    uint32_t r2 = N->o0 == p ? N->o1 : N->o0;
                    int nhas = (N->ia == p || N->ic == p || N->ib == p) && (N->ia == z || N->ic == z || N->ib == z);
                    if (nhas && r2 != q && collinear(m, q, z, r2)) {
                        push(m, z); push(m, r2); push(m, p);
                        m->nline++;
                        return 1;
                    }
                }
                push(m, p); m->nline++;
            }
            push(m, z);
            return 0;
        }
    }
    {
        /* (re)start: (other, v2, v3) drawn at index i counter-clockwise from +z, i.e.
         * grid cross < 0 for even i, > 0 for odd i (odd triangles are swapped) */
        uint32_t i0, v2 = L->o0, v3 = L->o1;
        int ccw_first;
        {
            const bt_vert *A = &m->v[L->other], *B = &m->v[L->o0], *C = &m->v[L->o1];
            ccw_first = (int64_t)(B->x - A->x) * (C->y - A->y) - (int64_t)(B->y - A->y) * (C->x - A->x) < 0;
        }
        if (m->ns > 0) {    /* only if no bridge fits (bt_strip.c): 4 line triangles */
            push(m, m->strip[m->ns - 1]);
            push(m, L->other);
            m->nline += 4;
        }
        i0 = m->ns;
        if (((i0 & 1) == 0) != ccw_first) { v2 = L->o1; v3 = L->o0; }
        push(m, L->other); push(m, v2); push(m, v3);
    }
    return 0;
}

/* Leaf (a, c, b), apex c.  It is entered through edge {a, c} (or the hypotenuse
 * {a, b} when in_hyp) and left through {c, b} (or {a, b} when out_hyp). */
static void leaf(em *e, pt *a, pt *c, pt *b, int in_hyp, int out_hyp)
{
    bt_mesh *m = e->m;
    pend L;
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
    if (e->has_pend) {
        if (write_leaf(e, &e->pend, &L)) { e->has_pend = 0; return; }
    }
    e->pend = L;
    e->has_pend = 1;
}

static void flush(em *e)
{
    if (e->has_pend && !e->count_only && !e->full) write_leaf(e, &e->pend, NULL);
    e->has_pend = 0;
}

/* ------------------------------------------------------------ reorder */
/* Leaf order where the walk broke (fidelity meshes).  The recursive walk's
 * order is fixed by the tree: where voids cut it, every break costs a bridge
 * of 1-5 line triangles, and along a void border (a vertex whose diamond has
 * a void half) it breaks every few leaves; reversing subtrees does not help
 * (the valid part of a border diamond is split into two runs either way).
 * When the walk bridged at least once, the strip's triangles are instead
 * ordered as a greedy path over the mesh's edge adjacency (the rule of greedy
 * strip builders, with the strip's exact cost of a turn) and written again by
 * the same writer (write_leaf: swaps, collinear rims, bridges), so the strip
 * holds exactly the same triangles with the same winding:
 *   - start at the walk's first leaf; after leaf t, go to the unwritten edge
 *     neighbour u of t with (1) the fewest unwritten neighbours of its own (one
 *     left with none becomes an isolated piece: a bridge later), then (2) no
 *     swap: t's pivot, the vertex its entry and exit edges share, differs from
 *     the previous leaf's pivot (a pivot kept for two leaves in a row is a fan
 *     turn: one line triangle, 002 figure 10), then the first in walk order;
 *   - with no unwritten edge neighbour, bridge to the unwritten leaf around a
 *     vertex of t with the fewest unwritten neighbours (a short bridge), else
 *     start anew at the leaf with the fewest unwritten neighbours among the
 *     next RO_WINDOW unwritten ones in walk order (first with <= 1).
 * It trades fan turns for bridges: fuji.png (unpadded) 21,275 swaps and 510
 * bridges (1,020 line triangles) in walk order, 12,362 swaps and 1,435 bridges
 * (5,186) in this order: 65,710 -> 60,967 references.  The result is kept only
 * if shorter than the walk's strip (else the walk's order is written again).
 * Cost: linear (3 neighbours per leaf), 3.5x the extraction's instructions
 * where it runs (fuji.png: 23.9 M -> 83.7 M, a third of it the bridges'
 * searches); it does not run on meshes without breaks (fuji 513 padded) nor in
 * view and budget modes (per-frame speed).
 * Scratch: the budget heap's area of the mesh (bt_mesh_mem_size: 64 bytes per
 * triangle of capacity), as 36 bytes per triangle (vertices, neighbours,
 * half-edge lists, then the written flags) + 4 per vertex. */
#define RNONE 0xFFFFFFFFu
#define RO_WINDOW 16   /* unwritten leaves looked at for a new start */

typedef struct ro {
    uint32_t nt;
    const uint32_t *tv;    /* 3 per leaf, counter-clockwise, in walk order */
    const uint32_t *nb;    /* 3 per leaf: the leaf across edge (tv[k], tv[k+1 mod 3]) */
    uint8_t *vis;          /* 1: written */
} ro;

/* unwritten neighbours of u */
static int rdeg(const ro *r, uint32_t u)
{
    int d = 0, j;
    for (j = 0; j < 3; j++) { uint32_t w = r->nb[3 * (size_t)u + j]; d += w != RNONE && !r->vis[w]; }
    return d;
}

/* the unwritten leaf around a vertex of t with the fewest unwritten neighbours
 * (ties: first in walk order), RNONE if none: turns around each vertex of t
 * through the edge neighbours, both ways (consistent winding: the edge out of
 * v in one leaf is the edge into v in the next) */
static uint32_t vert_next(const ro *r, uint32_t t)
{
    uint32_t best = RNONE;
    int bd = 9, j, dir;
    for (j = 0; j < 3; j++) {
        uint32_t v = r->tv[3 * (size_t)t + j];
        for (dir = 0; dir < 2; dir++) {
            uint32_t u = t, steps = 0;
            for (;;) {
                const uint32_t *w = r->tv + 3 * (size_t)u;
                int i = w[0] == v ? 0 : (w[1] == v ? 1 : 2);
                uint32_t nx = r->nb[3 * (size_t)u + (dir == 0 ? i : (i + 2) % 3)];
                if (nx == RNONE || nx == t || ++steps > 12) break;
                u = nx;
                if (!r->vis[u]) {
                    int d = rdeg(r, u);
                    if (d < bd || (d == bd && u < best)) { bd = d; best = u; }
                }
            }
        }
    }
    return best;
}

static int adjacent(const ro *r, uint32_t t, uint32_t u)
{
    return r->nb[3 * (size_t)t] == u || r->nb[3 * (size_t)t + 1] == u || r->nb[3 * (size_t)t + 2] == u;
}

static int has_v(const uint32_t *v, uint32_t x) { return v[0] == x || v[1] == x || v[2] == x; }

/* exit edge of leaf t towards leaf u (u == RNONE: none): their shared edge, or
 * else the edge of t sharing most vertices with u, not the entry edge {i0, i1}
 * when there is a choice (the bridge to u starts from it) */
static void exit_edge(const ro *r, uint32_t t, uint32_t u, uint32_t i0, uint32_t i1,
                      uint32_t *o0, uint32_t *o1)
{
    const uint32_t *v = r->tv + 3 * (size_t)t;
    int j, best = 0, bs = -1;
    for (j = 0; j < 3; j++) {
        uint32_t a = v[j], b = v[(j + 1) % 3];
        int sc = 0;
        if (u != RNONE) sc = 2 * (has_v(r->tv + 3 * (size_t)u, a) + has_v(r->tv + 3 * (size_t)u, b));
        if (!((a == i0 && b == i1) || (a == i1 && b == i0))) sc++;
        if (sc > bs) { bs = sc; best = j; }
    }
    *o0 = v[best]; *o1 = v[(best + 1) % 3];
}

/* Appends leaf t with exit edge {o0, o1} through the regular writer. */
static void re_emit(em *e, const ro *r, uint32_t t, uint32_t o0, uint32_t o1)
{
    pend L;
    const uint32_t *v = r->tv + 3 * (size_t)t;
    L.ia = v[0]; L.ic = v[1]; L.ib = v[2];
    L.o0 = o0; L.o1 = o1;
    L.other = (v[0] != o0 && v[0] != o1) ? v[0] : ((v[1] != o0 && v[1] != o1) ? v[1] : v[2]);
    if (e->has_pend && write_leaf(e, &e->pend, &L)) { e->has_pend = 0; return; }
    e->pend = L;
    e->has_pend = 1;
}

/* Writes the strip in the greedy order (walk = 0) or the walk's (walk = 1).
 * Returns 0, or -1 if the strip would not fit (m->strip is then unusable). */
static int ro_write(em *e, const ro *r, int walk)
{
    bt_mesh *m = e->m;
    uint32_t cur = 0, nextw = 1, i0 = RNONE, i1 = RNONE, ppiv = RNONE;
    memset(r->vis, 0, r->nt);
    m->ns = 0; m->nline = 0;
    e->has_pend = 0; e->nplan = 0;
    r->vis[0] = 1;
    for (;;) {
        uint32_t nxt = RNONE, o0, o1;
        while (nextw < r->nt && r->vis[nextw]) nextw++;
        if (!walk) {
            int j, bs = -1;
            for (j = 0; j < 3; j++) {
                uint32_t u = r->nb[3 * (size_t)cur + j], a, b, pv;
                int sc;
                if (u == RNONE || r->vis[u]) continue;
                a = r->tv[3 * (size_t)cur + j]; b = r->tv[3 * (size_t)cur + (j + 1) % 3];
                pv = (a == i0 || a == i1) ? a : ((b == i0 || b == i1) ? b : RNONE);
                sc = (4 - rdeg(r, u)) * 2 + !(pv != RNONE && pv == ppiv);
                if (sc > bs || (sc == bs && u < nxt)) { bs = sc; nxt = u; }
            }
            if (nxt == RNONE) nxt = vert_next(r, cur);
        }
        if (nxt == RNONE && nextw < r->nt) {
            /* a new start: among the next RO_WINDOW unwritten leaves in walk
             * order, one with the fewest unwritten neighbours (a run started at
             * an end strands nothing behind it) */
            uint32_t u, seen = 0;
            int bd = 9;
            nxt = nextw;
            if (!walk)
                for (u = nextw; u < r->nt && seen < RO_WINDOW; u++) {
                    int d;
                    if (r->vis[u]) continue;
                    seen++;
                    d = rdeg(r, u);
                    if (d < bd) { bd = d; nxt = u; if (d <= 1) break; }
                }
        }
        if (m->ns > e->lim_ns) return -1;
        exit_edge(r, cur, nxt, i0, i1, &o0, &o1);
        re_emit(e, r, cur, o0, o1);
        if (nxt == RNONE) break;
        ppiv = (o0 == i0 || o0 == i1) ? o0 : ((o1 == i0 || o1 == i1) ? o1 : RNONE);
        i0 = o0; i1 = o1;
        if (!adjacent(r, cur, nxt)) i0 = i1 = ppiv = RNONE;
        cur = nxt;
        r->vis[cur] = 1;
    }
    if (m->ns > e->lim_ns) return -1;
    flush(e);
    return 0;
}

static void reorder(em *e)
{
    bt_mesh *m = e->m;
    uint32_t nt = 0, k, *tv, *nb, *nx, *head, walk_ns = m->ns;
    ro r;
    if (m->ns < 3 || m->ntri < 2) return;
    if ((size_t)m->ntri * 36 + (size_t)m->nv * 4 > (size_t)heap_cap(m) * sizeof(heap_ent)) return;
    tv = (uint32_t *)(void *)heap_of(m);
    nb = tv + 3 * (size_t)m->ntri;
    nx = nb + 3 * (size_t)m->ntri;
    head = nx + 3 * (size_t)m->ntri;
    /* the strip's real triangles in order, counter-clockwise */
    for (k = 0; k + 2 < m->ns; k++) {
        uint32_t a = m->strip[k], b = m->strip[k + 1], c = m->strip[k + 2];
        if (a == b || b == c || a == c || collinear(m, a, b, c)) continue;
        if (nt >= m->ntri) return;
        if (k & 1) { uint32_t x = a; a = b; b = x; }
        tv[3 * nt] = a; tv[3 * nt + 1] = b; tv[3 * nt + 2] = c;
        nt++;
    }
    if (nt != m->ntri) return;
    /* edge adjacency: the half-edges listed by their lower vertex index (vertices
     * are numbered in walk order, so the lists stay local), twins matched in the
     * list (each interior edge is met twice, a boundary edge once) */
    memset(head, 0xff, (size_t)m->nv * 4);
    for (k = 0; k < 3 * nt; k++) {
        uint32_t a = tv[k], b = tv[k % 3 == 2 ? k - 2 : k + 1], lo = a < b ? a : b;
        nb[k] = RNONE;
        nx[k] = head[lo];
        head[lo] = k;
    }
    for (k = 0; k < m->nv; k++) {
        uint32_t q, q2;
        for (q = head[k]; q != RNONE; q = nx[q]) {
            uint32_t hi;
            if (nb[q] != RNONE) continue;
            hi = tv[q] ^ tv[q % 3 == 2 ? q - 2 : q + 1] ^ k;
            for (q2 = nx[q]; q2 != RNONE; q2 = nx[q2])
                if (nb[q2] == RNONE && (tv[q2] ^ tv[q2 % 3 == 2 ? q2 - 2 : q2 + 1] ^ k) == hi) {
                    nb[q] = q2 / 3; nb[q2] = q / 3;
                    break;
                }
        }
    }
    r.nt = nt; r.tv = tv; r.nb = nb; r.vis = (uint8_t *)nx;
    if (ro_write(e, &r, 0) != 0 || m->ns >= walk_ns)
        if (ro_write(e, &r, 1) != 0) e->full = 1;
}

static void rec(em *e, pt *a, pt *c, pt *b, int in_hyp, int out_hyp, unsigned mask)
{
    int32_t dx = b->x - a->x, dy = b->y - a->y;
    pt mm;
    int sp;
    if (e->full) return;
    if ((a->x + b->x) & 1) {     /* unit legs: the hypotenuse midpoint is no sample */
        if (e->nonvoid || (valid(e->t, a->x, a->y) && valid(e->t, b->x, b->y) && valid(e->t, c->x, c->y)))
            leaf(e, a, c, b, in_hyp, out_hyp);
        return;
    }
    mm.idx = NO_IDX;
    mm.x = a->x + (dx >> 1);
    mm.y = a->y + (dy >> 1);
    sp = decide(e, mm.x, mm.y, &mask, &mm.morph);
    if (sp < 0) return;
    if (!sp) {
        /* a triangle over voids that a budget left unsplit is dropped, never
         * drawn over the void (its corners may all be valid) */
        if (!e->nonvoid && BT_NODE_ERR(e->t->node[(size_t)mm.y * e->n + mm.x]) == BT_CODE_SPLIT) return;
        if (e->nonvoid || (valid(e->t, a->x, a->y) && valid(e->t, b->x, b->y) && valid(e->t, c->x, c->y)))
            leaf(e, a, c, b, in_hyp, out_hyp);
        return;
    }
    if (e->rec_splits) {
        /* record for the next frame's hysteresis (a diamond is reached twice) */
        size_t idx = (size_t)mm.y * e->n + mm.x;
        if (!(e->t->st[idx] & ST_CUR)) {
            if (e->m->nsplits < heap_cap(e->m)) {
                e->t->st[idx] |= ST_CUR;
                ids_of(e->m)[e->m->nsplits++] = (uint32_t)idx;
            } else e->lost = 1;
        }
    }
    {
        int32_t zs = e->nonvoid ? e->t->f->z[(size_t)mm.y * (size_t)e->n + (size_t)mm.x] : zreal(e->t, mm.x, mm.y);
        int64_t zf = ((int64_t)a->z + b->z) >> 1;
        /* a vertex whose real height IS the interpolation of its hypotenuse ends
         * (in every mode) carries topology but no information: fictitious (002:
         * deducible, never transmitted); its height is the same either way */
        if (2 * (int64_t)zs == (int64_t)a->z + b->z) mm.morph = 0;
        mm.z = mm.morph == BT_MORPH_ONE ? zs
             : (int32_t)(zf + ((((int64_t)zs - zf) * mm.morph + (1 << 14)) >> 15));
    }
    rec(e, a, &mm, c, !in_hyp, 0, mask);
    rec(e, c, &mm, b, 0, !out_hyp, mask);
}

/* rec for the plain fidelity rule without voids: the same leaves in the same order
 * without the mode, mask, void and geomorph branches (morph 0 iff zs interpolates). */
static void rec_fid(em *e, pt *a, pt *c, pt *b, int in_hyp, int out_hyp)
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
    q->x = x; q->y = y; q->z = zreal(t, x, y); q->morph = BT_MORPH_ONE; q->idx = NO_IDX;
}

static void run(em *e)
{
    pt A, B, C, D;
    int32_t S = e->S;
    corner(e->t, 0, 0, &A); corner(e->t, S, 0, &B);
    corner(e->t, S, S, &C); corner(e->t, 0, S, &D);
    e->has_pend = 0;
    e->nplan = 0;
    if (e->fid && e->nonvoid) { rec_fid(e, &A, &B, &C, 0, 1); rec_fid(e, &C, &D, &A, 1, 0); }
    else {
        rec(e, &A, &B, &C, 0, 1, 0x3f);
        rec(e, &C, &D, &A, 1, 0, 0x3f);
    }
    flush(e);
}

/* ------------------------------------------------------------ budget */
static int64_t prio(em *e, int32_t x, int32_t y)
{
    int typeD;
    int32_t h = dscale(x, y, e->S, &typeD);
    int32_t j = 0;
    int64_t r;
    while (((int32_t)1 << j) < h) j++;
    if (e->p->mode == BT_FIDELITY) {
        uint16_t c = BT_NODE_ERR(e->t->node[(size_t)y * e->n + x]);
        r = c == BT_CODE_SPLIT ? ((int64_t)1 << 50) : (int64_t)c;
    } else {
        r = rho_q8(e, x, y);
        if (r < 0) return -1;
        if (r > ((int64_t)1 << 50)) r = (int64_t)1 << 50;
    }
    return (r << 8) | (int64_t)(2 * j + typeD);
}

static void hpush(heap_ent *hp, uint32_t *n, int64_t key, uint32_t id)
{
    uint32_t i = (*n)++;
    while (i > 0) {
        uint32_t par = (i - 1) >> 1;
        if (hp[par].key > key || (hp[par].key == key && hp[par].id < id)) break;
        hp[i] = hp[par];
        i = par;
    }
    hp[i].key = key; hp[i].id = id; hp[i].pad_ = 0;
}

static heap_ent hpop(heap_ent *hp, uint32_t *n)
{
    heap_ent top = hp[0], last = hp[--(*n)];
    uint32_t i = 0;
    for (;;) {
        uint32_t l = 2 * i + 1, r = l + 1, b = i;
        const heap_ent *bb = &last;
        if (l < *n && (hp[l].key > bb->key || (hp[l].key == bb->key && hp[l].id < bb->id))) { b = l; bb = &hp[l]; }
        if (r < *n && (hp[r].key > bb->key || (hp[r].key == bb->key && hp[r].id < bb->id))) { b = r; bb = &hp[r]; }
        if (b == i) break;
        hp[i] = hp[b];
        i = b;
    }
    if (*n > 0) hp[i] = last;
    return top;
}

/* Marks ST_SPLIT on the diamonds a budget of `budget` nominal triangles buys.
 * Returns the number of ids recorded (to clear afterwards) in ids. Sets e->tau
 * to the last split's rho (for geomorph). */
static uint32_t budget_mark(em *e, uint32_t budget, uint32_t *nid)
{
    bt_tree *t = e->t;
    heap_ent *hp = heap_of(e->m);
    uint32_t *ids = ids_of(e->m);
    uint32_t nh = 0, ni = 0, cap = heap_cap(e->m);
    uint64_t count = 2;
    int32_t S = e->S, n = e->n;
    int64_t last = 0;
    {
        uint32_t root = (uint32_t)((S / 2) * n + S / 2);
        int64_t k = prio(e, S / 2, S / 2);
        if (k >= 0) { hpush(hp, &nh, k, root); t->st[root] |= ST_PUSHED; ids[ni++] = root; }
    }
    while (nh > 0) {
        heap_ent he = hpop(hp, &nh);
        int32_t x = (int32_t)(he.id % (uint32_t)n), y = (int32_t)(he.id / (uint32_t)n);
        int typeD, i, add = 0;
        int32_t h = dscale(x, y, S, &typeD);
        int32_t cx[4], cy[4];
        if ((he.key >> 8) <= 0 && e->p->mode != BT_FIDELITY) break;  /* nothing to gain */
        if (e->p->mode == BT_FIDELITY && (he.key >> 8) <= (int64_t)e->cthr) break;
        /* triangles of the diamond */
        if (typeD) add = 2;
        else if (x & h) add = (y - h >= 0) + (y + h <= S);
        else add = (x - h >= 0) + (x + h <= S);
        if (count + (uint64_t)add > budget) break;
        if (ni + 4 > cap) break;
        count += (uint64_t)add;
        t->st[he.id] |= ST_SPLIT;
        last = he.key >> 8;
        if (typeD) {
            cx[0] = x - h; cy[0] = y; cx[1] = x + h; cy[1] = y;
            cx[2] = x; cy[2] = y - h; cx[3] = x; cy[3] = y + h;
        } else if (h >= 2) {
            int32_t g = h >> 1;
            cx[0] = x - g; cy[0] = y - g; cx[1] = x + g; cy[1] = y - g;
            cx[2] = x - g; cy[2] = y + g; cx[3] = x + g; cy[3] = y + g;
        } else continue;
        for (i = 0; i < 4; i++) {
            uint32_t cid;
            int64_t k;
            if (cx[i] < 0 || cy[i] < 0 || cx[i] > S || cy[i] > S) continue;
            cid = (uint32_t)(cy[i] * n + cx[i]);
            if (t->st[cid] & ST_PUSHED) continue;
            k = prio(e, cx[i], cy[i]);
            t->st[cid] |= ST_PUSHED;
            ids[ni++] = cid;
            if (k >= 0) hpush(hp, &nh, k, cid);
        }
    }
    if (e->p->mode != BT_FIDELITY) e->tau = last;
    *nid = ni;
    return ni;
}

/* ------------------------------------------------------------ public */
static br_status setup(em *e, bt_tree *t, const bt_params *p)
{
    memset(e, 0, sizeof *e);
    if (!t || !p || !t->node) return BR_E_ARG;
    e->t = t; e->p = p; e->n = t->n; e->S = t->n - 1;
    e->nonvoid = t->nvalid == (int64_t)t->n * t->n;
    e->fid = p->mode == BT_FIDELITY;
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
        int64_t range = (int64_t)t->zmax - t->zmin;
        int i;
        for (i = 0; i < 256; i++) {
            int64_t zl = t->zmin + (range * i) / 255, zh = t->zmin + (range * i + 254) / 255;
            e->wz_lo[i] = p->fr.oz + ((zl * p->fr.sz_q16) >> 16);
            e->wz_hi[i] = p->fr.oz + ((zh * p->fr.sz_q16 + 65535) >> 16);
        }
        /* the volumes' corners are camera inputs: every world coordinate of the
         * padded grid's box must be within CAM_COORD_MAX (core/cam.h), which keeps
         * culled()'s sums of Q30 normal x coordinate products (and the plane
         * offsets) below 2^62; a frame with a larger extent (e.g. sx = 2^20 over
         * 16384 steps: 2^34) would overflow them */
        if ((int64_t)p->fr.ox < -CAM_COORD_MAX || (int64_t)p->fr.ox + (int64_t)e->S * p->fr.sx > CAM_COORD_MAX ||
            (int64_t)p->fr.oy > CAM_COORD_MAX || (int64_t)p->fr.oy - (int64_t)e->S * p->fr.sy < -CAM_COORD_MAX ||
            e->wz_lo[0] < -CAM_COORD_MAX || e->wz_hi[255] > CAM_COORD_MAX) return BR_E_ARG;
    }
    cam_frustum(p->c, e->pl);
    e->fq8 = p->c->f_q16 >> 8;
    e->tau = p->pixel_err_q8 > 0 ? p->pixel_err_q8 : 256;
    e->tau_lo = p->hyst_q8 > 0 ? (e->tau * (256 - (p->hyst_q8 > 256 ? 256 : p->hyst_q8))) >> 8 : e->tau;
    e->morph_span = (e->tau * p->morph_q8) >> 8;
    return BR_OK;
}

br_status bt_count(bt_tree *t, const bt_params *p, uint64_t *ntri)
{
    em e;
    br_status s = setup(&e, t, p);
    if (s != BR_OK) return s;
    if (p->mode == BT_BUDGET) { *ntri = p->budget; return BR_OK; }
    e.count_only = 1;
    e.tau_lo = e.tau;   /* counting ignores (and never touches) hysteresis state */
    run(&e);
    *ntri = e.count;
    return BR_OK;
}

/* Empties the mesh.  The vertex hash is not cleared: a slot holds base + 1 +
 * index, and the base (the word after the table) moves past every value of the
 * previous extraction, so old slots read as empty; cleared only when the base
 * would wrap. */
static uint32_t reset_mesh(bt_mesh *m)
{
    uint32_t *base = &m->hash[m->hmask + 1];
    if (*base > 0xFFFFFFFFu - m->nv - m->cap_v - 1) {
        memset(m->hash, 0, ((size_t)m->hmask + 1) * 4);
        *base = 0;
    } else *base += m->nv;
    m->nv = 0; m->ns = 0; m->ntri = 0; m->nline = 0; m->nfict = 0; m->overflow = 0;
    return *base;
}

br_status bt_extract(bt_tree *t, const bt_params *p, bt_mesh *m)
{
    em e;
    br_status s = setup(&e, t, p);
    uint32_t i, nid = 0, nprev, *ids;
    uint32_t *old;
    if (s != BR_OK) return s;
    if (!m || !m->v) return BR_E_ARG;
    e.m = m;
    e.direct = (uint64_t)t->n * (uint64_t)t->n <= 2 * ((uint64_t)m->hmask + 1);
    {
        uint32_t hl = m->hmask - (m->hmask >> 2);
        e.lim_nv = (hl < m->cap_v ? hl : m->cap_v) - 6;
        e.lim_ns = m->cap_s - 10;
    }
    ids = ids_of(m);
    old = (uint32_t *)(void *)heap_of(m);
    /* hysteresis bookkeeping: ids[0..nsplits) are the previous frame's splits
     * (ST_PREV set).  Move them aside (the heap area) before anything reuses ids. */
    nprev = m->nsplits;
    memmove(old, ids, (size_t)nprev * 4);
    m->nsplits = 0;
    if (p->mode != BT_VIEW) {
        for (i = 0; i < nprev; i++) t->st[old[i]] &= (uint8_t)~ST_PREV;
        nprev = 0;
    }
    e.hbase = reset_mesh(m);
    if (p->mode == BT_BUDGET) {
        budget_mark(&e, p->budget < m->max_tri ? p->budget : m->max_tri, &nid);
        e.tau = -1;
        e.fid = 0;
    } else {
        e.rec_splits = p->mode == BT_VIEW;
        run(&e);
        if (!e.full) {
            if (e.rec_splits) {
                /* previous frame's marks go; this frame's ST_CUR become ST_PREV */
                for (i = 0; i < nprev; i++) t->st[old[i]] &= (uint8_t)~ST_PREV;
                if (e.lost) {
                    size_t nn = (size_t)t->n * t->n, k;
                    for (k = 0; k < nn; k++) t->st[k] &= (uint8_t)~(ST_CUR | ST_PREV);
                    m->nsplits = 0;
                } else {
                    for (i = 0; i < m->nsplits; i++)
                        t->st[ids[i]] = (uint8_t)((t->st[ids[i]] & ~ST_CUR) | ST_PREV);
                }
            }
            if (e.nbreak > 0 && p->mode == BT_FIDELITY) reorder(&e);
            return e.full ? BR_E_NOMEM : BR_OK;
        }
        /* defined downgrade: the selection needs more than m holds; spend the
         * capacity by priority (the budget rule) instead */
        for (i = 0; i < nprev; i++) t->st[old[i]] &= (uint8_t)~ST_PREV;
        for (i = 0; i < m->nsplits; i++) t->st[ids[i]] &= (uint8_t)~(ST_CUR | ST_PREV);
        if (e.lost) {
            size_t nn = (size_t)t->n * t->n, k;
            for (k = 0; k < nn; k++) t->st[k] &= (uint8_t)~(ST_CUR | ST_PREV);
        }
        m->nsplits = 0;
        e.hbase = reset_mesh(m);
        e.full = 0; e.rec_splits = 0; e.lost = 0;
        budget_mark(&e, m->max_tri, &nid);
        e.tau = -1;
        e.fid = 0;
        m->overflow = 1;
    }
    run(&e);
    for (i = 0; i < nid; i++) t->st[ids[i]] &= (uint8_t)~(ST_SPLIT | ST_PUSHED);
    if (!e.full && e.nbreak > 0 && p->mode == BT_FIDELITY) reorder(&e);
    return e.full ? BR_E_NOMEM : BR_OK;
}
