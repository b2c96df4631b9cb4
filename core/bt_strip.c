/* core/bt_strip.c — the strip emitter's bridge across a break of the bitree
 * walk (contract: core/bitree.h; the walk and its regular steps: core/bt_mesh.c).
 *
 * Where voids or culled subtrees interrupt the recursive walk, the next leaf
 * does not share the strip's last edge.  Instead of a fixed restart (2 or 4
 * line triangles), bts_bridge finds by breadth-first search the SHORTEST
 * sequence of indices that draws, after the strip's current end, only line
 * triangles (a repeated index, or three collinear vertices: 002 figure 10,
 * 004's collinearity test) and then leaf L, and then (when the next leaf N is
 * known) only line triangles and N, each with the contract's winding
 * (counter-clockwise seen from +z: grid cross < 0 in drawing order).  Only the
 * part up to L is written: N is written by the next call from the state that
 * part leaves, so it may still continue to its own successor.  Among shortest
 * sequences, one that leaves N's walk exit edge last is preferred (the walk
 * continues through it).  The useful indices are the strip's last two and the
 * leaves' vertices (at most 8), so the search has at most
 * 8 x 8 x 3 phases x 2 parities states; it runs only at breaks. */
#include <string.h>
#include "core/bt_int.h"

#define NCAND 8
#define NKEY (NCAND * NCAND * 3 * 2)
#define MAXD 14

static int64_t cross3(const bt_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    const bt_vert *A = &m->v[a], *B = &m->v[b], *C = &m->v[c];
    return (int64_t)(B->x - A->x) * (C->y - A->y) - (int64_t)(B->y - A->y) * (C->x - A->x);
}

static int in3(const uint32_t t[3], uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

static int key_of(int a, int b, int ph, int par) { return ((a * NCAND + b) * 3 + ph) * 2 + par; }

/* Triangle (s[k], s[k+1], r) appended at strip length len: 0 line triangle,
 * 1 it draws target tg with the right winding, -1 anything else. */
static int step(const bt_mesh *m, uint32_t a, uint32_t b, uint32_t r, uint32_t len, const uint32_t *tg)
{
    int64_t cr;
    if (a == b || b == r || a == r) return 0;
    cr = cross3(m, a, b, r);
    if (cr == 0) return 0;
    if (!tg || !in3(tg, a) || !in3(tg, b) || !in3(tg, r)) return -1;
    if (len & 1) cr = -cr;          /* odd triangles are drawn (b, a, r) */
    return cr < 0 ? 1 : -1;
}

int bts_bridge(bt_mesh *m, const uint32_t L[3], const uint32_t *N, uint32_t ne0, uint32_t ne1)
{
    uint32_t cand[NCAND], len0 = m->ns;
    int nc = 0, i, goal = N ? 2 : 1, d, best = -1, bestpref = -1;
    int16_t pred[NKEY];
    int8_t via[NKEY];
    int16_t cur[NKEY], nxt[NKEY];
    int ncur = 0, nnxt;
    uint32_t src[6];
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
    memset(pred, 0xff, sizeof pred);
    {
        int a = 0, b = 0, k0;
        for (i = 0; i < nc; i++) { if (cand[i] == src[0]) a = i; if (cand[i] == src[1]) b = i; }
        k0 = key_of(a, b, 0, (int)(len0 & 1));
        pred[k0] = (int16_t)k0;
        via[k0] = -1;
        cur[ncur++] = (int16_t)k0;
    }
    /* breadth-first, one layer per appended index */
    for (d = 0; d < MAXD && ncur > 0 && best < 0; d++) {
        uint32_t len = len0 + (uint32_t)d;
        nnxt = 0;
        for (i = 0; i < ncur; i++) {
            int k = cur[i], par = k & 1, ph = (k >> 1) % 3, ab = (k >> 1) / 3;
            int a = ab / NCAND, b = ab % NCAND, r;
            for (r = 0; r < nc; r++) {
                int s = step(m, cand[a], cand[b], cand[r], len, ph == 0 ? L : (ph == 1 ? N : NULL));
                int nph = ph + (s > 0), nk;
                if (s < 0) continue;
                nk = key_of(b, r, nph, par ^ 1);
                if (pred[nk] >= 0) continue;
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
    if (best < 0) return -1;
    {
        /* walk back to the start, then write the part up to L's triangle */
        int path[MAXD], np = 0, k = best, j, first_l = -1;
        while (via[k] >= 0) {
            path[np++] = k;
            k = pred[k];
        }
        for (j = np - 1; j >= 0; j--)
            if (((path[j] >> 1) % 3) == 1 || ((path[j] >> 1) % 3) == 2) { first_l = j; break; }
        if (first_l < 0 || m->ns + (uint32_t)(np - first_l) > m->cap_s) return -1;
        for (j = np - 1; j >= first_l; j--) m->strip[m->ns++] = cand[(int)via[path[j]]];
        m->nline += (uint32_t)(np - 1 - first_l);
    }
    return 0;
}
