/* benchmarks/rqt_ref.c — see rqt_ref.h.  Restricted quadtree (Pajarola 98 as in
 * papers/002 2.2) and 002's bitree rules on the RTIN numbering of martini_ref.h:
 * triangle index i has tree id i + 2 = binary 1 b_L ... b_1 b_0 where b_0 picks the
 * root and b_1, b_2, ... the child at each split from the root DOWN (martini reads
 * the path from the low bits): the parent drops b_L, a child appends a bit just
 * under the leading 1; bit 1 = (c, a, m) ("left half"), 0 = (b, c, m). */
#include "benchmarks/rqt_ref.h"
#include "benchmarks/martini_ref.h"
#include <stdlib.h>
#include <string.h>

typedef struct rq_ctx {
    const int32_t *z;
    int32_t size;
    int64_t tol_num, tol_den;
    const mr_grid *g;
    unsigned char *split_err;   /* per triangle: split by the error criterion */
    unsigned char *need;        /* per triangle: split in the scheme being built */
    int32_t *mate0, *mate1;     /* per grid point: the (up to 2) triangles it is the midpoint of */
    int32_t *leaves;            /* 3 * 2 (size-1)^2 scratch */
} rq_ctx;

static int64_t top_bit(int64_t id)
{
    int64_t t = 1;
    while (t <= id / 2) t <<= 1;
    return t;
}

static int64_t parent_id(int64_t id)
{
    int64_t t = top_bit(id);
    return t / 2 + (id & (t / 2 - 1));
}

static int64_t child_id(int64_t id, int left)
{
    int64_t t = top_bit(id);
    return 2 * t + (left ? t : 0) + (id - t);
}

static int64_t cross3(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t x2, int64_t y2)
{
    return (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
}

/* 1 when some sample in the closed triangle is farther than tol from its plane. */
static int exceeds(const rq_ctx *c, int32_t ax, int32_t ay, int32_t bx, int32_t by,
                   int32_t cx, int32_t cy)
{
    int64_t D = cross3(ax, ay, bx, by, cx, cy), x, y, x0, x1, y0, y1;
    int64_t za, zb, zc;
    int32_t s = c->size;
    if (D < 0) { int32_t t = bx; bx = cx; cx = t; t = by; by = cy; cy = t; D = -D; }
    za = c->z[ay * s + ax]; zb = c->z[by * s + bx]; zc = c->z[cy * s + cx];
    x0 = ax < bx ? ax : bx; if (cx < x0) x0 = cx;
    x1 = ax > bx ? ax : bx; if (cx > x1) x1 = cx;
    y0 = ay < by ? ay : by; if (cy < y0) y0 = cy;
    y1 = ay > by ? ay : by; if (cy > y1) y1 = cy;
    for (y = y0; y <= y1; y++)
        for (x = x0; x <= x1; x++) {
            int64_t w0 = cross3(bx, by, cx, cy, x, y), w1 = cross3(cx, cy, ax, ay, x, y);
            int64_t w2 = D - w0 - w1, num;
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            num = w0 * za + w1 * zb + w2 * zc - D * c->z[y * s + x];
            if (num < 0) num = -num;
            if (num * c->tol_den > c->tol_num * D) return 1;
        }
    return 0;
}

/* Top-down selection: split while e(T) > tol. */
static void select_rec(rq_ctx *c, int64_t id, int32_t ax, int32_t ay, int32_t bx, int32_t by,
                       int32_t cx, int32_t cy)
{
    int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;
    if (id - 2 >= c->g->ntri) return;                 /* half-cell leaf */
    if (!exceeds(c, ax, ay, bx, by, cx, cy)) return;
    c->split_err[id - 2] = 1;
    select_rec(c, child_id(id, 1), cx, cy, ax, ay, mx, my);
    select_rec(c, child_id(id, 0), bx, by, cx, cy, mx, my);
}

static int32_t mid_of(const mr_grid *g, int64_t i)
{
    const uint16_t *k = g->coords + 4 * i;
    return ((k[1] + k[3]) >> 1) * g->size + ((k[0] + k[2]) >> 1);
}

static int32_t partner(const rq_ctx *c, int64_t i)
{
    int32_t m = mid_of(c->g, i);
    if (c->mate0[m] == i) return c->mate1[m];
    return c->mate0[m];
}

/* ---- strips ------------------------------------------------------------- */

static int64_t pcross(int32_t size, int32_t a, int32_t b, int32_t c)
{
    return cross3(a % size, a / size, b % size, b / size, c % size, c / size);
}

/* The strip is built by dynamic programming over the fixed leaf order.  After a
 * leaf is produced the strip's state is (p, q, par): its last two indices and the
 * parity of its length; each leaf has at most 12 such end states (an ordered pair
 * of its vertices x 2 parities).  A transition appends a sequence that produces
 * only line triangles and then, with its last index, the leaf itself with the
 * mesh's winding; its cost is its length.  Sequences use the leaf's vertices and
 * the current p, q; 5 indices always suffice (q, a, a, b, c or q, b, b, a, c). */
#define DP_MAXS 12
#define DP_MAXLEN 5

typedef struct dp_st {
    int32_t p, q;
    int32_t from;            /* index of the source state in the previous leaf's row */
    int32_t par;
    int64_t cost;
    int32_t len, seq[DP_MAXLEN];
} dp_st;

typedef struct dp_ctx {
    int32_t size;
    const int32_t *t;
    int sign;
    int32_t cand[5];
    int nc;
    int32_t seq[DP_MAXLEN];
    dp_st *row;              /* target row (DP_MAXS states) */
    int *nrow;
    int32_t from;
    int64_t base;
} dp_ctx;

static void dp_offer(dp_ctx *d, int32_t p, int32_t q, int32_t par, int len)
{
    int i;
    int64_t cost = d->base + len;
    for (i = 0; i < *d->nrow; i++) {
        dp_st *x = &d->row[i];
        if (x->p == p && x->q == q && x->par == par) {
            if (cost < x->cost) break;
            return;
        }
    }
    if (i == *d->nrow) {
        if (*d->nrow == DP_MAXS) return;   /* cannot happen: <= 6 pairs x 2 parities */
        (*d->nrow)++;
    }
    d->row[i].p = p; d->row[i].q = q; d->row[i].par = par; d->row[i].cost = cost;
    d->row[i].from = d->from; d->row[i].len = len;
    memcpy(d->row[i].seq, d->seq, sizeof d->seq);
}

/* k = number of the next strip triangle (its parity decides the winding). */
static void dp_dfs(dp_ctx *d, int32_t p, int32_t q, int64_t k, int depth)
{
    int i;
    if (depth == DP_MAXLEN) return;
    for (i = 0; i < d->nc; i++) {
        int32_t r = d->cand[i], a = p, b = q;
        int64_t cr;
        if (k & 1) { a = q; b = p; }
        cr = pcross(d->size, a, b, r);
        d->seq[depth] = r;
        if (a == b || b == r || a == r || cr == 0) {
            dp_dfs(d, q, r, k + 1, depth + 1);          /* a line triangle */
        } else {
            const int32_t *t = d->t;
            int in = (a == t[0] || a == t[1] || a == t[2]) && (b == t[0] || b == t[1] || b == t[2]) &&
                     (r == t[0] || r == t[1] || r == t[2]);
            if (in && (cr > 0 ? 1 : -1) == d->sign)
                dp_offer(d, q, r, (int32_t)((k + 3) & 1), depth + 1);   /* strip length n = k + 3 */
        }
    }
}

int64_t rq_strip_dp(int32_t size, const int32_t *leaves, int64_t nt, int32_t *out, int64_t *line)
{
    dp_st *rows;
    int *nrows;
    int64_t j, best = -1, n;
    int i, bi = 0;
    *line = 0;
    if (nt == 0) return 0;
    rows = malloc((size_t)nt * DP_MAXS * sizeof *rows);
    nrows = calloc((size_t)nt, sizeof *nrows);
    if (!rows || !nrows) { free(rows); free(nrows); return -1; }
    {   /* first leaf: its three rotations at the start of the strip */
        const int32_t *t = leaves;
        for (i = 0; i < 3; i++) {
            dp_st *x = &rows[nrows[0]++];
            x->seq[0] = t[i]; x->seq[1] = t[(i + 1) % 3]; x->seq[2] = t[(i + 2) % 3];
            x->p = x->seq[1]; x->q = x->seq[2]; x->par = 1; x->cost = 3; x->len = 3; x->from = -1;
        }
    }
    for (j = 1; j < nt; j++) {
        dp_ctx d;
        const int32_t *t = leaves + 3 * j;
        memset(&d, 0, sizeof d);
        d.size = size; d.t = t;
        d.sign = pcross(size, t[0], t[1], t[2]) > 0 ? 1 : -1;
        d.row = rows + j * DP_MAXS; d.nrow = &nrows[j];
        for (i = 0; i < nrows[j - 1]; i++) {
            const dp_st *src = &rows[(j - 1) * DP_MAXS + i];
            int32_t all[5];
            int u, v;
            all[0] = t[0]; all[1] = t[1]; all[2] = t[2]; all[3] = src->p; all[4] = src->q;
            d.nc = 0;
            for (u = 0; u < 5; u++) {
                for (v = 0; v < d.nc; v++) if (d.cand[v] == all[u]) break;
                if (v == d.nc) d.cand[d.nc++] = all[u];
            }
            d.from = i; d.base = src->cost;
            /* next strip triangle number k = n - 2, n = src->cost; parity from par */
            dp_dfs(&d, src->p, src->q, src->cost - 2, 0);
        }
    }
    for (i = 0; i < nrows[nt - 1]; i++)
        if (best < 0 || rows[(nt - 1) * DP_MAXS + i].cost < best) { best = rows[(nt - 1) * DP_MAXS + i].cost; bi = i; }
    n = best;
    if (out) {   /* backtrack, writing each leaf's sequence at its end position */
        int64_t pos = n;
        int cur = bi;
        for (j = nt - 1; j >= 0; j--) {
            const dp_st *x = &rows[j * DP_MAXS + cur];
            pos -= x->len;
            memcpy(out + pos, x->seq, (size_t)x->len * sizeof *out);
            cur = x->from;
        }
    }
    *line = n - 2 - nt;
    free(rows); free(nrows);
    return n;
}

/* ---- mesh emission --------------------------------------------------------- */

typedef struct emit_st {
    const rq_ctx *c;
    int32_t *leaves;          /* 3 per leaf triangle, in traversal order */
    int64_t nt;
} emit_st;

/* Sierpinski order: a triangle (a, b, c) with hypotenuse a-b is walked from a to b
 * (fwd) or from b to a; its children (c, a, m) and (b, c, m) are walked in the
 * order and direction that keep the path continuous, so consecutive leaves
 * share a vertex, and an edge wherever they are the same size. */
static void emit_rec(emit_st *e, int64_t id, int32_t ax, int32_t ay, int32_t bx, int32_t by,
                     int32_t cx, int32_t cy, int fwd)
{
    int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1, s = e->c->size;
    if (id - 2 < e->c->g->ntri && e->c->need[id - 2]) {
        if (fwd) {
            emit_rec(e, child_id(id, 1), cx, cy, ax, ay, mx, my, 0);
            emit_rec(e, child_id(id, 0), bx, by, cx, cy, mx, my, 0);
        } else {
            emit_rec(e, child_id(id, 0), bx, by, cx, cy, mx, my, 1);
            emit_rec(e, child_id(id, 1), cx, cy, ax, ay, mx, my, 1);
        }
        return;
    }
    e->leaves[3 * e->nt] = ay * s + ax;
    e->leaves[3 * e->nt + 1] = by * s + bx;
    e->leaves[3 * e->nt + 2] = cy * s + cx;
    e->nt++;
}

/* Builds need[] for one scheme, counts its figures and optionally emits it. */
static void scheme(rq_ctx *c, int qt, const unsigned char *is_sel, int64_t nsel,
                   unsigned char *is_vert, rq_side *side, rq_mesh *out)
{
    const mr_grid *g = c->g;
    int64_t i, n = (int64_t)c->size * c->size, nsplit = 0, nvert = 0;
    int32_t max = c->size - 1;
    emit_st e;
    memset(c->need, 0, (size_t)g->ntri);
    for (i = 0; i < g->ntri; i++)
        if (is_sel[mid_of(g, i)]) c->need[i] = 1;     /* both diamond triangles of a selected point */
    for (i = g->ntri - 1; i >= 0; i--) {
        int64_t par;
        if (!c->need[i]) continue;
        par = i + 2 >= 4 ? parent_id(i + 2) - 2 : -1;
        if (par >= 0) c->need[par] = 1;
        if (qt) {
            int32_t pt = partner(c, i);
            if (pt >= 0) {
                int64_t pp = pt + 2 >= 4 ? parent_id(pt + 2) - 2 : -1;
                c->need[pt] = 1;
                if (pp >= 0) c->need[pp] = 1;
            }
        }
    }
    memset(is_vert, 0, (size_t)n);
    is_vert[0] = is_vert[max] = is_vert[(int64_t)max * c->size] = is_vert[n - 1] = 1;
    for (i = 0; i < g->ntri; i++)
        if (c->need[i]) { nsplit++; is_vert[mid_of(g, i)] = 1; }
    for (i = 0; i < n; i++) nvert += is_vert[i];
    side->points = nvert;
    side->added = nvert - nsel;
    side->transmit = qt ? nvert : nsel;
    side->triangles = 2 + nsplit;
    memset(&e, 0, sizeof e);
    e.c = c;
    e.leaves = c->leaves;
    emit_rec(&e, 3, 0, 0, max, max, max, 0, 1);   /* (0,0) -> (max,max) */
    emit_rec(&e, 2, max, max, 0, 0, 0, max, 1);   /* and back to (0,0) */
    side->refs = rq_strip_dp(c->size, e.leaves, e.nt, out ? out->strip : NULL, &side->line);
    if (out) {
        out->nt = e.nt;
        out->ns = side->refs;
        if (out->tri) memcpy(out->tri, e.leaves, (size_t)(3 * e.nt) * sizeof *out->tri);
    }
}

int rq_run(const int32_t *z, int32_t size, int64_t tol_num, int64_t tol_den, int sel_mode,
           rq_result *r, rq_mesh *qt_out, rq_mesh *bt_out)
{
    mr_grid g;
    rq_ctx c;
    int64_t i, n = (int64_t)size * size, nsel = 0;
    int32_t max = size - 1;
    unsigned char *is_sel = NULL, *is_vert = NULL;
    int rc = -1;
    memset(r, 0, sizeof *r);
    if (sel_mode < RQ_SEL_EACH || sel_mode > RQ_SEL_VERTEX || size > 4097 || tol_den <= 0 || tol_num < -1 || mr_grid_init(&g, size) != 0) return -1;
    memset(&c, 0, sizeof c);
    c.z = z; c.size = size; c.tol_num = tol_num; c.tol_den = tol_den; c.g = &g;
    c.split_err = calloc((size_t)g.ntri, 1);
    c.need = calloc((size_t)g.ntri, 1);
    c.mate0 = malloc((size_t)n * sizeof *c.mate0);
    c.mate1 = malloc((size_t)n * sizeof *c.mate1);
    is_sel = calloc((size_t)n, 1);
    is_vert = calloc((size_t)n, 1);
    c.leaves = malloc((size_t)6 * (size_t)(size - 1) * (size_t)(size - 1) * sizeof *c.leaves);
    if (!c.leaves || !c.split_err || !c.need || !c.mate0 || !c.mate1 || !is_sel || !is_vert) goto done;
    for (i = 0; i < n; i++) c.mate0[i] = c.mate1[i] = -1;
    for (i = 0; i < g.ntri; i++) {
        int32_t m = mid_of(&g, i);
        if (c.mate0[m] < 0) c.mate0[m] = (int32_t)i; else c.mate1[m] = (int32_t)i;
    }
    if (sel_mode == RQ_SEL_TOPDOWN) {
        select_rec(&c, 3, 0, 0, max, max, max, 0);
        select_rec(&c, 2, max, max, 0, 0, 0, max);
    } else if (sel_mode == RQ_SEL_VERTEX) {   /* each point by its own midpoint error */
        for (i = 0; i < g.ntri; i++) {
            const uint16_t *k = g.coords + 4 * i;
            int32_t ax = k[0], ay = k[1], bx = k[2], by = k[3];
            int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;
            int64_t d = (int64_t)z[ay * size + ax] + z[by * size + bx] - 2 * (int64_t)z[my * size + mx];
            if (d < 0) d = -d;
            c.split_err[i] = (unsigned char)(d * tol_den > 2 * tol_num);
        }
    } else {            /* every triangle of the hierarchy on its own */
        for (i = 0; i < g.ntri; i++) {
            const uint16_t *k = g.coords + 4 * i;
            int32_t ax = k[0], ay = k[1], bx = k[2], by = k[3];
            int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;
            c.split_err[i] = (unsigned char)exceeds(&c, ax, ay, bx, by, mx + my - ay, my + ax - mx);
        }
    }
    is_sel[0] = is_sel[max] = is_sel[(int64_t)max * size] = is_sel[n - 1] = 1;
    for (i = 0; i < g.ntri; i++)
        if (c.split_err[i]) is_sel[mid_of(&g, i)] = 1;
    for (i = 0; i < n; i++) nsel += is_sel[i];
    r->selected = nsel;
    scheme(&c, 1, is_sel, nsel, is_vert, &r->qt, qt_out);
    scheme(&c, 0, is_sel, nsel, is_vert, &r->bt, bt_out);
    rc = 0;
done:
    free(c.leaves); free(c.split_err); free(c.need); free(c.mate0); free(c.mate1); free(is_sel); free(is_vert);
    mr_grid_free(&g);
    return rc;
}
