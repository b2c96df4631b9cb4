/* core/bt_emit.c — the bitree's strip writer: leaves, in the order the
 * selection (core/bt_mesh.c) visits them, to one generalised triangle strip
 * (002 section 4: each leaf shares an edge with the previous one and appends one
 * index; fan turns cost a swap, straight fan rims one line triangle, 004; breaks
 * of the walk are bridged by core/bt_strip.c), and the reorder pass that writes
 * a fidelity strip with breaks again in a better leaf order.  Contract:
 * core/bitree.h (bt_extract); shared state: core/bt_em.h. */
#include <string.h>
#include "core/bt_em.h"

static void push(bt_mesh *m, uint32_t i) { m->strip[m->ns++] = (br_index)i; }   /* i < cap_v <= BR_INDEX_MAX + 1 */

static int collinear(const bt_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    return bti_cross(&m->v[a], &m->v[b], &m->v[c]) == 0;
}

/* The straight rim q-z-r2 of two leaves around one pivot (z between q and r2, both
 * leaves' edges on it) may serve as a line triangle when it draws nothing visible:
 * collinear in (x, y, z) too (bti_flat), or with z above the chord q-r2 where
 * the mesh covers both sides of the rim (no void in the grid, the rim not on its
 * edge).  Then the sliver (q, z, r2) lies in the vertical plane of the rim, below
 * the polyline q-z-r2 that is the surface there, so any ray from above the surface
 * to a point of it crosses the surface first: the depth test hides it, up to the
 * rounding of the depths it compares (where the sliver's depth at a pixel rounds to
 * the surface's, the one drawn first keeps the pixel, and where it rounds nearer the
 * sliver does: its colour there is interpolated from the rim's own vertices, a few
 * bytes a frame that tests/test_terrain.c counts).  Any other
 * grid-collinear triple is a vertical sliver standing out of the surface (or
 * hanging off an edge), drawn by the rasteriser. */
int bti_rim_line(const bti_extract *e, uint32_t q, uint32_t z, uint32_t r2)
{
    const bt_mesh *m = e->m;
    const bt_vert *a = &m->v[q], *c = &m->v[z], *b = &m->v[r2];
    int32_t w = e->t->f->w, h = e->t->f->h, tb, tc;
    if (!collinear(m, q, z, r2)) return 0;
    if (bti_flat(a, c, b)) return 1;
    if (e->t->nvalid != (int64_t)w * h) return 0;
    if ((a->x == 0 && b->x == 0) || (a->x == w - 1 && b->x == w - 1) ||
        (a->y == 0 && b->y == 0) || (a->y == h - 1 && b->y == h - 1)) return 0;
    tb = b->x != a->x ? b->x - a->x : b->y - a->y;    /* position along the rim */
    tc = b->x != a->x ? c->x - a->x : c->y - a->y;
    if (tb < 0) { tb = -tb; tc = -tc; }
    return ((int64_t)c->z - a->z) * tb > ((int64_t)b->z - a->z) * tc;
}

/* Writes leaf L (the next leaf N, if any, is known: one leaf of lookahead).
 * Returns 1 when N was written too.  The strip's last two indices are kept equal
 * to the written leaf's exit edge, so the next leaf shares them.  When L must
 * swap (its pivot is the older index) and N turns around the same pivot with
 * L's new vertex, the old one and N's new vertex collinear (a straight rim of
 * the fan that draws nothing visible: rim_line), the rim itself makes the line triangle (002 figure 10, 004's
 * collinearity): "z r2 P" writes both leaves with one line triangle instead of
 * two swaps, and leaves the pivot newest for N's successor. */
int btw_write_leaf(bti_extract *e, const bti_leaf *L, const bti_leaf *N)
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
            if (e->bridge && bts_bridge(m, l3, N ? n3 : NULL, N ? N->o0 : 0, N ? N->o1 : 0, e->plan, &e->nplan) == 0)
                return 0;
        }
        if (hp && hq && p != q) {
            uint32_t z = (p != L->ia && q != L->ia) ? L->ia : ((p != L->ic && q != L->ic) ? L->ic : L->ib);
            int qin = q == L->o0 || q == L->o1, pin = p == L->o0 || p == L->o1;
            if (!qin && pin) {
                /* swap needed: try the straight-rim pair with N (pivot p) */
                if (N && ((N->o0 == p && N->o1 != z) || (N->o1 == p && N->o0 != z))) {
                    uint32_t r2 = N->o0 == p ? N->o1 : N->o0;
                    int nhas = (N->ia == p || N->ic == p || N->ib == p) && (N->ia == z || N->ic == z || N->ib == z);
                    if (nhas && r2 != q && bti_zlog(m, 0, q, z, r2, bti_rim_line(e, q, z, r2))) {
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
        const int ccw_first = bti_cross(&m->v[L->other], &m->v[L->o0], &m->v[L->o1]) < 0;
        if (m->ns > 0) {    /* no bridge searched (e->bridge) or none fits: 4 line triangles */
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

void btw_flush(bti_extract *e)
{
    if (e->has_pend && !e->count_only && !e->full) btw_write_leaf(e, &e->pend, NULL);
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
 * the same writer (btw_write_leaf: swaps, collinear rims, bridges), so the strip
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
 * It trades fan turns for bridges (figures: docs/perf-history.md, "Leaf
 * reorder").  The result is kept only if shorter than the walk's strip (else the
 * walk's order is written again).  Cost: linear (3 neighbours per leaf), a few
 * times the extraction's own work where it runs, much of it the bridges'
 * searches; so it does not run on meshes without breaks nor in view and budget
 * modes (per-frame speed).
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
static void re_emit(bti_extract *e, const ro *r, uint32_t t, uint32_t o0, uint32_t o1)
{
    bti_leaf L;
    const uint32_t *v = r->tv + 3 * (size_t)t;
    L.ia = v[0]; L.ic = v[1]; L.ib = v[2];
    L.o0 = o0; L.o1 = o1;
    L.other = (v[0] != o0 && v[0] != o1) ? v[0] : ((v[1] != o0 && v[1] != o1) ? v[1] : v[2]);
    if (e->has_pend && btw_write_leaf(e, &e->pend, &L)) { e->has_pend = 0; return; }
    e->pend = L;
    e->has_pend = 1;
}

/* Writes the strip in the greedy order (walk = 0) or the walk's (walk = 1).
 * Returns 0, or -1 if the strip would not fit (m->strip is then unusable). */
static int ro_write(bti_extract *e, const ro *r, int walk)
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
    btw_flush(e);
    return 0;
}

void btw_reorder(bti_extract *e)
{
    bt_mesh *m = e->m;
    uint32_t nt = 0, k, *tv, *nb, *nx, *head, walk_ns = m->ns;
    ro r;
    /* only where the walk broke, the mode asks for it and the mesh is complete */
    if (e->nbreak == 0 || !e->reorder || e->full || m->ns < 3 || m->ntri < 2) return;
    if ((size_t)m->ntri * 36 + (size_t)m->nv * 4 > (size_t)bti_heap_n(m) * sizeof(bti_heap_ent)) return;
    tv = (uint32_t *)(void *)bti_heap_of(m);
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

