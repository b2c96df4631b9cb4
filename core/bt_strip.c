/* core/bt_strip.c — the strip emitter's bridge across a break of the bitree
 * walk (contract: core/bitree.h; the walk and its regular steps: core/bt_mesh.c).
 *
 * Where voids or culled subtrees interrupt the recursive walk, the next leaf
 * does not share the strip's last edge.  Instead of a fixed restart (2 or 4
 * line triangles), bts_bridge finds by breadth-first search the SHORTEST
 * sequence of indices that draws, after the strip's current end, only line
 * triangles (a repeated index, or three vertices collinear in (x, y, z): 002
 * figure 10, 004's collinearity test, with the heights on the line too, since a
 * triangle collinear in (x, y) only is a vertical sliver) and then leaf L, and then (when the next leaf N is
 * known) only line triangles and N, each with the contract's winding
 * (counter-clockwise seen from +z: grid cross < 0 in drawing order).  Only the
 * part up to L is written: N is written by the next call from the state that
 * part leaves, so it may still continue to its own successor (or, when that
 * successor continues N's walk exit edge where the rest ends, follow the rest).  Among shortest
 * sequences, one that leaves N's walk exit edge last is preferred (the walk
 * continues through it).  The useful indices are the strip's last two and the
 * leaves' vertices (at most 8), so the search has at most
 * 8 x 8 x 3 phases x 2 parities states; it runs only at breaks. */
#include <string.h>
#include "core/bt_int.h"
#include "core/bt_em.h"

#define NCAND 8                  /* a state key packs two slots in 3 bits each */
#define NKEY (NCAND * NCAND * 3 * 2)
#define MAXD BTS_PLAN
#define BTS_SLACK 2              /* the first bound over the lower bound (see bts_bridge) */



/* a state: the strip's last two candidates, the phase (0: L still to draw, 1: N
 * still to draw, 2: done) and the strip length's parity */
static int key_of(int a, int b, int ph, int par) { return ((ph * 2 + par) << 6) | (a << 3) | b; }

/* The search's view of the candidates: positions, the leaves as bit masks of
 * candidate slots, and for each pair (a, b) the candidates r by the triangle
 * (a, b, r) (computed on first use of the pair). */
typedef struct bsearch {
    bt_mesh *m;                      /* (its height tests go to m's log: bti_zlog) */
    const bt_vert *v[NCAND];
    int32_t x[NCAND], y[NCAND];
    unsigned lm, nm;                 /* candidates of L, of N */
    uint64_t known;                  /* bit a * NCAND + b: the pair's masks are set */
    uint8_t rz[NCAND * NCAND];       /* r giving a line triangle (a repeated index,
                                        or collinear in (x, y, z)): it draws nothing */
    uint8_t rp[NCAND * NCAND];       /* r with cross(b - a, r - a) > 0 */
    uint8_t rn[NCAND * NCAND];       /* r with cross(b - a, r - a) < 0; r collinear in
                                        (x, y) only (a vertical sliver, bti_flat) is in none */
    int hn0;                         /* hcost's part for N in phase 0 */
} bsearch;

static void pair_masks(bsearch *q, int a, int b, int nc)
{
    int ab = a * NCAND + b, ba = b * NCAND + a, r;
    unsigned z = (1u << a) | (1u << b), p = 0, n = 0;
    int64_t dx = (int64_t)q->x[b] - q->x[a], dy = (int64_t)q->y[b] - q->y[a];
    if (a == b) z = (1u << nc) - 1u;
    else
        for (r = 0; r < nc; r++) {
            int64_t cr;
            if (r == a || r == b) continue;
            cr = dx * (q->y[r] - q->y[a]) - dy * (q->x[r] - q->x[a]);
            if (cr > 0) p |= 1u << r;
            else if (cr < 0) n |= 1u << r;
            else if (bti_zlog(q->m, 1, (uint32_t)(q->v[a] - q->m->v), (uint32_t)(q->v[b] - q->m->v),
                              (uint32_t)(q->v[r] - q->m->v), bti_flat(q->v[a], q->v[b], q->v[r])))
                z |= 1u << r;
        }
    q->rz[ab] = (uint8_t)z; q->rp[ab] = (uint8_t)p; q->rn[ab] = (uint8_t)n;
    /* pair (b, a): cross(a - b, r - b) = -cross(b - a, r - a), and collinearity
     * in (x, y, z) does not depend on the order */
    q->rz[ba] = (uint8_t)z; q->rp[ba] = (uint8_t)n; q->rn[ba] = (uint8_t)p;
    q->known |= (uint64_t)1 << ab | (uint64_t)1 << ba;
}

/* The candidates r that may follow (a, b) at strip length len with target
 * candidates tm: the line triangles, and (in *draw) those drawing the target
 * with the right winding (counter-clockwise; odd triangles are drawn (b, a, r),
 * so they need cross > 0, even ones cross < 0).  Every other r draws a triangle
 * that is not the target, or a vertical sliver. */
static unsigned next_set(bsearch *q, int a, int b, int nc, uint32_t len, unsigned tm, unsigned *draw)
{
    int ab = a * NCAND + b;
    unsigned d = 0;
    if (!((q->known >> ab) & 1u)) pair_masks(q, a, b, nc);
    if ((tm >> a) & (tm >> b) & 1u) d = (unsigned)((len & 1) ? q->rp[ab] : q->rn[ab]) & tm;
    *draw = d;
    return q->rz[ab] | d;
}

static const int8_t pc8[256] = {
#define P2(n) n, n + 1, n + 1, n + 2
#define P4(n) P2(n), P2(n + 1), P2(n + 1), P2(n + 2)
#define P6(n) P4(n), P4(n + 1), P4(n + 1), P4(n + 2)
    P6(0), P6(1), P6(1), P6(2)
#undef P2
#undef P4
#undef P6
};

/* Lower bound of the indices still to append from state (a, b) (ab: their bits)
 * in phase ph: every vertex of a leaf still to draw that is not among the last
 * two must be appended, and each leaf needs at least its own drawing index
 * (q->hn0: N's part when L is still to draw, its vertices not L's). */
static int hcost(const bsearch *q, unsigned ab, int ph, int goal)
{
    int h;
    if (ph >= goal) return 0;
    if (ph == 1) { h = pc8[q->nm & ~ab]; return h < 1 ? 1 : h; }
    h = pc8[q->lm & ~ab];
    return (h < 1 ? 1 : h) + q->hn0;
}

int bts_follow(bt_mesh *m, const uint32_t plan[BTS_PLAN], int *nplan, uint32_t o0, uint32_t o1, const uint32_t *N)
{
    uint32_t k = (uint32_t)*nplan, i, e1, e2;
    *nplan = 0;
    if (k == 0 || m->ns < 1 || m->ns + k > m->cap_s) return 0;
    e1 = k >= 2 ? plan[k - 2] : m->strip[m->ns - 1];
    e2 = plan[k - 1];
    if (!((e1 == o0 && e2 == o1) || (e1 == o1 && e2 == o0))) return 0;
    if (N && !((N[0] == o0 || N[1] == o0 || N[2] == o0) && (N[0] == o1 || N[1] == o1 || N[2] == o1))) return 0;
    for (i = 0; i < k; i++) m->strip[m->ns++] = (br_index)plan[i];
    m->nline += k - 1;
    return 1;
}

int bts_bridge(bt_mesh *m, const uint32_t L[3], const uint32_t *N, uint32_t ne0, uint32_t ne1,
               uint32_t plan[BTS_PLAN], int *nplan)
{
    uint32_t cand[NCAND], len0 = m->ns;
    int nc = 0, i, goal = N ? 2 : 1, d, best = -1, bestpref = -1;
    int16_t pred[NKEY];
    int8_t via[NKEY];
    int16_t cur[NKEY], nxt[NKEY];
    int ncur = 0, nnxt, a0 = 0, b0 = 0, bound;
    uint32_t src[6];
    bsearch q;
    if (m->ns < 2) return -1;
    src[0] = m->strip[m->ns - 2]; src[1] = m->strip[m->ns - 1];
    src[2] = L[0]; src[3] = L[1]; src[4] = L[2]; src[5] = 0;
    for (i = 0; i < 5; i++) {
        int k, dup = 0;
        for (k = 0; k < nc; k++) dup |= cand[k] == src[i];
        if (!dup) cand[nc++] = src[i];
    }
    if (N)
        for (i = 0; i < 3; i++) {
            int k, dup = 0;
            for (k = 0; k < nc; k++) dup |= cand[k] == N[i];
            if (!dup) cand[nc++] = N[i];
        }
    q.m = m;
    q.known = 0;
    q.lm = q.nm = 0;
    for (i = 0; i < nc; i++) {
        q.v[i] = &m->v[cand[i]];
        q.x[i] = m->v[cand[i]].x; q.y[i] = m->v[cand[i]].y;
        if (cand[i] == L[0] || cand[i] == L[1] || cand[i] == L[2]) q.lm |= 1u << i;
        if (N && (cand[i] == N[0] || cand[i] == N[1] || cand[i] == N[2])) q.nm |= 1u << i;
    }
    for (i = 0; i < nc; i++) { if (cand[i] == src[0]) a0 = i; if (cand[i] == src[1]) b0 = i; }
    q.hn0 = goal == 2 ? pc8[q.nm & ~q.lm] : 0;
    q.hn0 = goal == 2 && q.hn0 < 1 ? 1 : q.hn0;
    /* breadth-first, one layer per appended index, pruned by a lower bound of
     * the indices still needed (A*-style: bound = 1 + the previous one until a
     * goal is reached, so the first goal layer is the optimum D).  Any bound
     * B >= D gives the same answer: call a state live when the goal can be
     * reached from it within B - depth.  hcost is a lower bound, so no live
     * state is pruned; a live state's first generator is live (it reaches the
     * goal through it), so the live states of each layer, their order and their
     * predecessors are those of the search with B = D, and the goals of layer D
     * are all live.  Hence the first bound may exceed hcost's by BTS_SLACK, which
     * skips the rounds that find nothing. */
    bound = hcost(&q, (1u << a0) | (1u << b0), 0, goal) + BTS_SLACK;
    for (bound = bound < MAXD ? bound : MAXD; bound <= MAXD && best < 0; bound++) {
        int k0 = key_of(a0, b0, 0, (int)(len0 & 1));
        memset(pred, 0xff, sizeof pred);
        pred[k0] = (int16_t)k0;
        via[k0] = -1;
        ncur = 0;
        cur[ncur++] = (int16_t)k0;
        for (d = 0; d < bound && ncur > 0 && best < 0; d++) {
            uint32_t len = len0 + (uint32_t)d;
            nnxt = 0;
            for (i = 0; i < ncur; i++) {
                int k = cur[i], par = (k >> 6) & 1, ph = k >> 7;
                int a = (k >> 3) & 7, b = k & 7, r;
                unsigned draw, rs = next_set(&q, a, b, nc, len, ph == 0 ? q.lm : (ph == 1 ? q.nm : 0u), &draw);
                for (r = 0; rs != 0; r++, rs >>= 1) {
                    int nph = ph + (int)((draw >> r) & 1u), nk;
                    if (!(rs & 1u)) continue;
                    nk = key_of(b, r, nph, par ^ 1);
                    if (pred[nk] >= 0) continue;
                    if (d + 1 + hcost(&q, (1u << b) | (1u << r), nph, goal) > bound) continue;
                    pred[nk] = (int16_t)k;
                    via[nk] = (int8_t)r;
                    nxt[nnxt++] = (int16_t)nk;
                    if (nph == goal) {
                        int pref = (cand[b] == ne0 && cand[r] == ne1) || (cand[b] == ne1 && cand[r] == ne0);
                        if (pref > bestpref) { best = nk; bestpref = pref; }
                    }
                }
            }
            memcpy(cur, nxt, (size_t)nnxt * sizeof cur[0]);
            ncur = nnxt;
        }
    }
    if (best < 0) return -1;
    {
        /* walk back to the start, then write the part up to L's triangle */
        int path[MAXD], np = 0, k = best, j, first_l = -1;
        while (via[k] >= 0) {
            path[np++] = k;
            k = pred[k];
        }
        for (j = np - 1; j >= 0; j--)
            if ((path[j] >> 7) >= 1) { first_l = j; break; }
        if (first_l < 0 || m->ns + (uint32_t)(np - first_l) > m->cap_s) return -1;
        for (j = np - 1; j >= first_l; j--) m->strip[m->ns++] = (br_index)cand[(int)via[path[j]]];
        m->nline += (uint32_t)(np - 1 - first_l);
        *nplan = 0;    /* the rest: the way on to N (the next call may follow it) */
        for (j = first_l - 1; j >= 0; j--) plan[(*nplan)++] = cand[(int)via[path[j]]];
    }
    return 0;
}
