/* tests/support/meshcheck.c — see meshcheck.h for the contract.
 *
 * Everything is exact: positions and cross products in int64, plane errors as
 * rationals num/den compared through a portable 64x64->128-bit product, so the
 * referee never rounds in the mesher's favour. */
#include "tests/support/meshcheck.h"
#include <stdlib.h>
#include <string.h>

/* ---- exact rational helpers ------------------------------------------- */

/* a*b as a 128-bit value (hi, lo), a and b unsigned 64-bit. */
static void mul128(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
    uint64_t al = a & 0xffffffffu, ah = a >> 32, bl = b & 0xffffffffu, bh = b >> 32;
    uint64_t ll = al * bl, lh = al * bh, hl = ah * bl, hh = ah * bh;
    uint64_t mid = (ll >> 32) + (lh & 0xffffffffu) + (hl & 0xffffffffu);
    *lo = (ll & 0xffffffffu) | (mid << 32);
    *hi = hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
}

/* Compares a/b with c/d (all >= 0, b, d > 0): -1, 0, +1. */
static int cmp_frac(uint64_t a, uint64_t b, uint64_t c, uint64_t d)
{
    uint64_t h1, l1, h2, l2;
    mul128(a, d, &h1, &l1);
    mul128(c, b, &h2, &l2);
    if (h1 != h2) return h1 < h2 ? -1 : 1;
    if (l1 != l2) return l1 < l2 ? -1 : 1;
    return 0;
}

static uint64_t gcd64(uint64_t a, uint64_t b)
{
    while (b) { uint64_t t = a % b; a = b; b = t; }
    return a;
}

/* ceil(1024 * num / den) without overflow (den < 2^62). */
static int64_t ceil_q10(uint64_t num, uint64_t den)
{
    uint64_t q = num / den, r = num % den, frac = 0;
    int i;
    for (i = 0; i < 10; i++) {
        r <<= 1;
        frac <<= 1;
        if (r >= den) { r -= den; frac |= 1; }
    }
    if (r) frac++;
    return (int64_t)(q * 1024u + frac);
}

int mc_err_exceeds(const mc_report *r, int64_t lim_num, int64_t lim_den)
{
    if (lim_num < 0) return 1;
    return cmp_frac((uint64_t)r->err_num, (uint64_t)r->err_den,
                    (uint64_t)lim_num, (uint64_t)lim_den) > 0;
}

/* ---- geometry ----------------------------------------------------------- */

static int64_t cross3(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t x2, int64_t y2)
{
    return (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
}

static int64_t vcross(const mc_vert *a, const mc_vert *b, const mc_vert *c)
{
    return cross3(a->x, a->y, b->x, b->y, c->x, c->y);
}

static int64_t abs64(int64_t a) { return a < 0 ? -a : a; }
static int64_t min64(int64_t a, int64_t b) { return a < b ? a : b; }
static int64_t max64(int64_t a, int64_t b) { return a > b ? a : b; }

static void set_bad(mc_report *r, int32_t x, int32_t y, const char *what)
{
    if (r->bad_x < 0) { r->bad_x = x; r->bad_y = y; r->bad_what = what; }
}

/* The raster pass: error of every triangle at every sample it covers, and the
 * coverage counts (cover saturates at 255; inner = strictly inside some triangle).
 * ok_tri[t] = 0 skips triangle t (bad vertex). */
static void raster_pass(const mc_mesh *m, int32_t w, int32_t h, const int32_t *z,
                        const unsigned char *ok_tri, unsigned char *cover,
                        unsigned char *inner, int32_t reach, mc_report *r)
{
    uint64_t best_n = 0, best_d = 1;
    int64_t t;
    int zb = m->zbits;
    int64_t zlim = (int64_t)BR_Z_LIMIT << zb;
    r->err_x = r->err_y = -1;
    r->err_tri = -1;
    for (t = 0; t < m->nt; t++) {
        const mc_vert *p0, *p1, *p2, *tmp;
        int64_t D, Dz, zmax, lim, x, y, x0, x1, y0, y1, ext;
        if (ok_tri && !ok_tri[t]) continue;
        p0 = &m->v[m->tri[3 * t]];
        p1 = &m->v[m->tri[3 * t + 1]];
        p2 = &m->v[m->tri[3 * t + 2]];
        D = vcross(p0, p1, p2);
        if (D == 0) continue;
        if (D < 0) { tmp = p1; p1 = p2; p2 = tmp; D = -D; }
        zmax = abs64(p0->zq);
        if (abs64(p1->zq) > zmax) zmax = abs64(p1->zq);
        if (abs64(p2->zq) > zmax) zmax = abs64(p2->zq);
        if (zlim > zmax) zmax = zlim;
        lim = INT64_MAX / 4 / D;
        if (zb > 30 || D > (INT64_MAX >> (zb + 2)) || zmax > lim) { r->range_errors++; continue; }
        Dz = D << zb;
        ext = max64(max64(p0->x, max64(p1->x, p2->x)) - min64(p0->x, min64(p1->x, p2->x)),
                    max64(p0->y, max64(p1->y, p2->y)) - min64(p0->y, min64(p1->y, p2->y)));
        x0 = max64(0, min64(p0->x, min64(p1->x, p2->x)));
        x1 = min64(w - 1, max64(p0->x, max64(p1->x, p2->x)));
        y0 = max64(0, min64(p0->y, min64(p1->y, p2->y)));
        y1 = min64(h - 1, max64(p0->y, max64(p1->y, p2->y)));
        for (y = y0; y <= y1; y++) {
            for (x = x0; x <= x1; x++) {
                int64_t b0 = cross3(p1->x, p1->y, p2->x, p2->y, x, y);
                int64_t b1 = cross3(p2->x, p2->y, p0->x, p0->y, x, y);
                int64_t b2 = D - b0 - b1;
                int64_t i = y * w + x, num;
                int32_t zs;
                if (b0 < 0 || b1 < 0 || b2 < 0) continue;
                if (cover && cover[i] < 255) cover[i]++;
                if (inner && b0 > 0 && b1 > 0 && b2 > 0) inner[i] = 1;
                zs = z[i];
                if (zs == MC_VOID) {
                    if (reach > 0 && ext <= reach) r->void_covered_near++;
                    else if (reach > 0 || !cover) {
                        r->void_covered++;
                        set_bad(r, (int32_t)x, (int32_t)y, "void sample covered");
                    }
                    continue;
                }
                num = b0 * p0->zq + b1 * p1->zq + b2 * p2->zq - Dz * (int64_t)zs;
                num = abs64(num);
                if (cmp_frac((uint64_t)num, (uint64_t)Dz, best_n, best_d) > 0) {
                    best_n = (uint64_t)num; best_d = (uint64_t)Dz;
                    r->err_x = (int32_t)x; r->err_y = (int32_t)y; r->err_tri = t;
                }
            }
        }
    }
    {
        uint64_t g = gcd64(best_n, best_d);
        if (g > 1) { best_n /= g; best_d /= g; }
    }
    r->err_num = (int64_t)best_n;
    r->err_den = (int64_t)best_d;
    r->err_q10 = ceil_q10(best_n, best_d);
}

/* ---- mc_check ------------------------------------------------------------ */

/* One directed use of an edge, kept in the bucket of its lower end position. */
typedef struct edge_rec {
    int32_t hi;         /* the higher end position y*w+x */
    int32_t td;         /* 2 * (third vertex position) + (1 if walked lo->hi) */
} edge_rec;

static int edge_cmp(const void *pa, const void *pb)
{
    const edge_rec *a = pa, *b = pb;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return ((a->td & 1) > (b->td & 1)) - ((a->td & 1) < (b->td & 1));
}

/* A boundary edge off the grid border must have a void sample in the closed square
 * erected on it on its uncovered side (strictly off its line). */
static int void_next_to(int32_t w, int32_t h, const int32_t *z,
                        int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t cx, int64_t cy)
{
    int64_t dx = bx - ax, dy = by - ay, L2 = dx * dx + dy * dy;
    int64_t side = cross3(ax, ay, bx, by, cx, cy) > 0 ? -1 : 1; /* uncovered side sign */
    /* normal pointing to the uncovered side: (-dy, dx) has cross sign +1 */
    int64_t nx = -dy * side, ny = dx * side;
    int64_t xs[4] = { ax, bx, ax + nx, bx + nx }, ys[4] = { ay, by, ay + ny, by + ny };
    int64_t x0 = xs[0], x1 = xs[0], y0 = ys[0], y1 = ys[0], x, y;
    int k;
    for (k = 1; k < 4; k++) {
        x0 = min64(x0, xs[k]); x1 = max64(x1, xs[k]);
        y0 = min64(y0, ys[k]); y1 = max64(y1, ys[k]);
    }
    x0 = max64(x0, 0); y0 = max64(y0, 0);
    x1 = min64(x1, w - 1); y1 = min64(y1, h - 1);
    for (y = y0; y <= y1; y++)
        for (x = x0; x <= x1; x++) {
            int64_t s, d;
            if (z[y * w + x] != MC_VOID) continue;
            s = cross3(ax, ay, bx, by, x, y) * side;
            d = (x - ax) * dx + (y - ay) * dy;
            if (s > 0 && s <= L2 && d >= 0 && d <= L2) return 1;
        }
    return 0;
}

/* Summed-area table of the voids: t[(y + 1)(w + 1) + x + 1] = voids in [0,x] x [0,y]. */
static int32_t *void_table(int32_t w, int32_t h, const int32_t *z)
{
    int32_t *t = calloc((size_t)(w + 1) * (size_t)(h + 1), sizeof *t), x, y;
    if (!t) return NULL;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++)
            t[(int64_t)(y + 1) * (w + 1) + x + 1] = (z[(int64_t)y * w + x] == MC_VOID) +
                t[(int64_t)y * (w + 1) + x + 1] + t[(int64_t)(y + 1) * (w + 1) + x] - t[(int64_t)y * (w + 1) + x];
    return t;
}

/* voids in the box [x0,x1] x [y0,y1] clipped to the grid */
static int32_t voids_in(const int32_t *t, int32_t w, int32_t h, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    x0 = x0 < 0 ? 0 : x0; y0 = y0 < 0 ? 0 : y0;
    x1 = x1 > w - 1 ? w - 1 : x1; y1 = y1 > h - 1 ? h - 1 : y1;
    if (x0 > x1 || y0 > y1) return 0;
    return t[(int64_t)(y1 + 1) * (w + 1) + x1 + 1] - t[(int64_t)y0 * (w + 1) + x1 + 1] -
           t[(int64_t)(y1 + 1) * (w + 1) + x0] + t[(int64_t)y0 * (w + 1) + x0];
}

static int on_border(int32_t w, int32_t h, int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    return (ax == 0 && bx == 0) || (ax == w - 1 && bx == w - 1) ||
           (ay == 0 && by == 0) || (ay == h - 1 && by == h - 1);
}

static void report_init(mc_report *r)
{
    memset(r, 0, sizeof *r);
    r->err_den = 1;
    r->err_x = r->err_y = r->bad_x = r->bad_y = -1;
    r->err_tri = -1;
    r->bad_what = "";
}

int mc_check(const mc_mesh *m, int32_t w, int32_t h, const int32_t *z,
             const mc_opts *o, mc_report *r)
{
    static const mc_opts defaults;
    int64_t n = (int64_t)w * h, i, t, pos = 0, neg = 0, *start = NULL;
    int32_t *vid = NULL;
    unsigned char *ok_tri = NULL, *cover = NULL, *inner = NULL;
    int32_t *sat = NULL;
    edge_rec *e = NULL;
    int32_t x, y;
    if (!o) o = &defaults;
    report_init(r);
    r->triangles = m->nt;
    vid = malloc((size_t)n * sizeof *vid);
    cover = calloc((size_t)n, 1);
    inner = calloc((size_t)n, 1);
    ok_tri = calloc((size_t)(m->nt > 0 ? m->nt : 1), 1);
    e = malloc((size_t)(3 * m->nt + 1) * sizeof *e);
    if (!vid || !cover || !inner || !ok_tri || !e) {
        free(vid); free(cover); free(inner); free(ok_tri); free(e);
        return -1;
    }
    for (i = 0; i < n; i++) vid[i] = -1;
    if (o->void_reach > 0) {
        sat = void_table(w, h, z);
        if (!sat) { free(vid); free(cover); free(inner); free(ok_tri); free(e); return -1; }
    }

    /* voids and the area the valid samples allow */
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            if (z[(int64_t)y * w + x] == MC_VOID) r->voids++;
            if (x + 1 < w && y + 1 < h) {
                int c = (z[(int64_t)y * w + x] != MC_VOID) + (z[(int64_t)y * w + x + 1] != MC_VOID) +
                        (z[(int64_t)(y + 1) * w + x] != MC_VOID) + (z[(int64_t)(y + 1) * w + x + 1] != MC_VOID);
                r->area2_max += c == 4 ? 2 : c == 3 ? 1 : 0;
            }
        }

    /* vertices, orientation */
    for (t = 0; t < m->nt; t++) {
        int k, good = 1;
        int64_t c;
        for (k = 0; k < 3; k++) {
            int32_t vi = m->tri[3 * t + k];
            const mc_vert *p;
            if (vi < 0 || vi >= m->nv) { good = 0; break; }
            p = &m->v[vi];
            if (p->x < 0 || p->y < 0 || p->x >= w || p->y >= h ||
                z[(int64_t)p->y * w + p->x] == MC_VOID) { good = 0; break; }
        }
        if (!good) { r->bad_vertex++; continue; }
        ok_tri[t] = 1;
        for (k = 0; k < 3; k++) {
            int32_t vi = m->tri[3 * t + k];
            int64_t pp = (int64_t)m->v[vi].y * w + m->v[vi].x;
            if (vid[pp] < 0) vid[pp] = vi;
            else if (vid[pp] != vi && m->v[vid[pp]].zq != m->v[vi].zq && !inner[pp]) {
                inner[pp] = 1;          /* count each position once (inner is reset below) */
                r->split_vertex++;
                set_bad(r, m->v[vi].x, m->v[vi].y, "split vertex");
            }
        }
        c = vcross(&m->v[m->tri[3 * t]], &m->v[m->tri[3 * t + 1]], &m->v[m->tri[3 * t + 2]]);
        if (c > 0) pos++; else if (c < 0) neg++;
        else { r->degenerate++; ok_tri[t] = 0; }
        r->area2 += abs64(c);
    }
    r->orientation = (pos || neg) ? (pos >= neg ? 1 : -1) : 0;
    r->flipped = pos >= neg ? neg : pos;

    /* edges: bucket every directed use by its lower end (two passes over the
     * triangles), sort each small bucket, then walk the groups */
    start = calloc((size_t)n + 1, sizeof *start);
    if (!start) { free(vid); free(cover); free(inner); free(ok_tri); free(e); free(sat); return -1; }
    for (t = 0; t < m->nt; t++) {
        int k;
        if (!ok_tri[t]) continue;
        for (k = 0; k < 3; k++) {
            const mc_vert *a = &m->v[m->tri[3 * t + k]], *b = &m->v[m->tri[3 * t + (k + 1) % 3]];
            int32_t pa = a->y * w + a->x, pb = b->y * w + b->x;
            start[(pa < pb ? pa : pb) + 1]++;
        }
    }
    for (i = 0; i < n; i++) start[i + 1] += start[i];
    for (t = 0; t < m->nt; t++) {
        int k;
        if (!ok_tri[t]) continue;
        for (k = 0; k < 3; k++) {
            const mc_vert *a = &m->v[m->tri[3 * t + k]], *b = &m->v[m->tri[3 * t + (k + 1) % 3]];
            const mc_vert *c = &m->v[m->tri[3 * t + (k + 2) % 3]];
            int32_t pa = a->y * w + a->x, pb = b->y * w + b->x, lo = pa < pb ? pa : pb;
            edge_rec *er = &e[start[lo]++];
            er->hi = pa < pb ? pb : pa;
            er->td = 2 * (c->y * w + c->x) + (pa < pb);
        }
    }
    /* start[v] is now the end of bucket v, which begins at start[v - 1] */
    for (i = 0; i < n; i++) {
        int64_t b0 = i ? start[i - 1] : 0, end = start[i], u, q, j;
        int32_t ax = (int32_t)(i % w), ay = (int32_t)(i / w);
        if (end - b0 > 32) qsort(e + b0, (size_t)(end - b0), sizeof *e, edge_cmp);
        else
            for (u = b0 + 1; u < end; u++) {
                edge_rec cur = e[u];
                for (q = u; q > b0 && edge_cmp(&e[q - 1], &cur) > 0; q--) e[q] = e[q - 1];
                e[q] = cur;
            }
        for (u = b0; u < end; u = j) {
            int32_t bx = e[u].hi % w, by = e[u].hi / w;
            j = u;
            while (j < end && e[j].hi == e[u].hi) j++;
            r->edges++;
            if (j - u > 2) { r->nonmanifold_edges++; set_bad(r, ax, ay, "edge used by more than two triangles"); }
            else if (j - u == 2 && (e[u].td & 1) == (e[u + 1].td & 1)) {
                r->same_dir_edges++; set_bad(r, ax, ay, "edge walked twice in the same direction");
            } else if (j - u == 1) {
                int32_t third = e[u].td >> 1;
                r->boundary_edges++;
                int32_t R = o->void_reach;
                if (!on_border(w, h, ax, ay, bx, by) &&
                    !void_next_to(w, h, z, ax, ay, bx, by, third % w, third / w) &&
                    !(sat && voids_in(sat, w, h, (ax < bx ? ax : bx) - R, (ay < by ? ay : by) - R,
                                      (ax > bx ? ax : bx) + R, (ay > by ? ay : by) + R) > 0)) {
                    r->bad_boundary_edges++;
                    set_bad(r, ax, ay, "boundary edge inside the domain (crack)");
                }
            }
            /* T-junctions: lattice points strictly inside the segment */
            {
                int64_t dx = bx - ax, dy = by - ay;
                int64_t g = (int64_t)gcd64((uint64_t)abs64(dx), (uint64_t)abs64(dy)), k;
                for (k = 1; k < g; k++) {
                    int64_t px = ax + dx / g * k, py = ay + dy / g * k;
                    if (vid[py * w + px] >= 0) {
                        r->tjunctions++;
                        set_bad(r, (int32_t)px, (int32_t)py, "T-junction");
                    }
                }
            }
        }
    }
    free(start);

    /* raster pass: error and coverage */
    memset(inner, 0, (size_t)n);
    if (!o->skip_error) {
        raster_pass(m, w, h, z, ok_tri, cover, inner, o->void_reach, r);
        for (i = 0; i < n; i++) {
            int32_t xx = (int32_t)(i % w), yy = (int32_t)(i / w);
            if (z[i] == MC_VOID) {
                if (cover[i] && o->void_reach <= 0) { r->void_covered++; set_bad(r, xx, yy, "void sample covered"); }
            } else if (!cover[i]) {
                int near = 0, dx, dy;
                r->uncovered++;
                for (dy = -1; dy <= 1; dy++)
                    for (dx = -1; dx <= 1; dx++) {
                        int32_t nx = xx + dx, ny = yy + dy;
                        if (nx >= 0 && ny >= 0 && nx < w && ny < h && z[(int64_t)ny * w + nx] == MC_VOID) near = 1;
                    }
                if (!near && sat) near = voids_in(sat, w, h, xx - o->void_reach, yy - o->void_reach,
                                                  xx + o->void_reach, yy + o->void_reach) > 0;
                if (!near) { r->uncovered_far++; set_bad(r, xx, yy, "valid sample far from voids not covered"); }
                else if (!o->allow_uncovered && o->void_reach <= 0) set_bad(r, xx, yy, "valid sample not covered");
            }
            if (inner[i] && cover[i] >= 2) { r->overlap_samples++; set_bad(r, xx, yy, "overlap"); }
        }
    }

    r->ok = !(r->bad_vertex || r->split_vertex || r->degenerate || r->flipped ||
              r->nonmanifold_edges || r->same_dir_edges ||
              r->tjunctions || r->overlap_samples || r->void_covered || r->range_errors);
    if (!o->partial && (r->bad_boundary_edges || r->uncovered_far ||
                        (r->uncovered && !o->allow_uncovered && o->void_reach <= 0))) r->ok = 0;
    if ((r->voids == 0 && !o->partial) ? r->area2 != r->area2_max
        : r->area2 > (o->void_reach > 0 ? 2 * (int64_t)(w - 1) * (h - 1) : r->area2_max)) {
        r->ok = 0; set_bad(r, -1, -1, "area differs from the domain's");
    }
    if (o->expect_area2 > 0 && r->area2 != o->expect_area2) {
        r->ok = 0; set_bad(r, -1, -1, "area differs from the expected one");
    }
    free(vid); free(cover); free(inner); free(ok_tri); free(e); free(sat);
    return r->ok;
}

int mc_max_error(const mc_mesh *m, int32_t w, int32_t h, const int32_t *z, mc_report *r)
{
    int64_t n = (int64_t)w * h, i, t;
    unsigned char *cover = calloc((size_t)n, 1), *ok_tri;
    report_init(r);
    r->triangles = m->nt;
    ok_tri = calloc((size_t)(m->nt > 0 ? m->nt : 1), 1);
    if (!cover || !ok_tri) { free(cover); free(ok_tri); return -1; }
    for (t = 0; t < m->nt; t++) {
        int k, good = 1;
        for (k = 0; k < 3; k++) {
            int32_t vi = m->tri[3 * t + k];
            if (vi < 0 || vi >= m->nv || m->v[vi].x < 0 || m->v[vi].y < 0 ||
                m->v[vi].x >= w || m->v[vi].y >= h) good = 0;
        }
        ok_tri[t] = (unsigned char)good;
        if (!good) r->bad_vertex++;
    }
    raster_pass(m, w, h, z, ok_tri, cover, NULL, 0, r);
    for (i = 0; i < n; i++) {
        if (z[i] == MC_VOID) { if (cover[i]) r->void_covered++; }
        else if (!cover[i]) r->uncovered++;
    }
    free(cover); free(ok_tri);
    return 0;
}

void mc_report_print(FILE *f, const mc_report *r)
{
    fprintf(f, "mesh: %lld triangles, orientation %+d, ok=%d\n", (long long)r->triangles,
            (int)r->orientation, r->ok);
    fprintf(f, "  bad_vertex %lld split_vertex %lld degenerate %lld flipped %lld\n",
            (long long)r->bad_vertex, (long long)r->split_vertex, (long long)r->degenerate,
            (long long)r->flipped);
    fprintf(f, "  edges %lld boundary %lld nonmanifold %lld same_dir %lld bad_boundary %lld tjunctions %lld\n",
            (long long)r->edges, (long long)r->boundary_edges, (long long)r->nonmanifold_edges,
            (long long)r->same_dir_edges, (long long)r->bad_boundary_edges, (long long)r->tjunctions);
    fprintf(f, "  area2 %lld (max %lld, voids %lld) overlap_samples %lld uncovered %lld (far from voids %lld) void_covered %lld range %lld\n",
            (long long)r->area2, (long long)r->area2_max, (long long)r->voids,
            (long long)r->overlap_samples, (long long)r->uncovered, (long long)r->uncovered_far,
            (long long)r->void_covered,
            (long long)r->range_errors);
    if (r->void_covered_near)
        fprintf(f, "  void samples covered within void_reach %lld\n", (long long)r->void_covered_near);
    fprintf(f, "  max error %lld/%lld (<= %lld/1024) at (%d,%d) triangle %lld\n",
            (long long)r->err_num, (long long)r->err_den, (long long)r->err_q10,
            (int)r->err_x, (int)r->err_y, (long long)r->err_tri);
    if (r->bad_what[0])
        fprintf(f, "  first defect: %s at (%d,%d)\n", r->bad_what, (int)r->bad_x, (int)r->bad_y);
}

/* ---- strips ---------------------------------------------------------------- */

int mc_strip_decode(const int32_t *s, int64_t n, const mc_vert *v, int32_t nv,
                    int32_t *tri, int64_t *n_tri, int32_t *line, int64_t *n_line)
{
    int64_t k, nt = 0, nl = 0;
    for (k = 0; k < n; k++)
        if (s[k] < 0 || s[k] >= nv) return -1;
    for (k = 0; k + 2 < n; k++) {
        int32_t a = s[k], b = s[k + 1], c = s[k + 2];
        if (k & 1) { int32_t tmp = a; a = b; b = tmp; }
        if (vcross(&v[a], &v[b], &v[c]) == 0) {
            if (line) { line[3 * nl] = a; line[3 * nl + 1] = b; line[3 * nl + 2] = c; }
            nl++;
        } else {
            if (tri) { tri[3 * nt] = a; tri[3 * nt + 1] = b; tri[3 * nt + 2] = c; }
            nt++;
        }
    }
    if (n_tri) *n_tri = nt;
    if (n_line) *n_line = nl;
    return 0;
}

typedef struct tri_key { int64_t p[3]; int32_t sign; } tri_key;

static int key_cmp(const void *pa, const void *pb)
{
    const tri_key *a = pa, *b = pb;
    int k;
    for (k = 0; k < 3; k++)
        if (a->p[k] != b->p[k]) return a->p[k] < b->p[k] ? -1 : 1;
    return 0;
}

static void make_key(const mc_vert *v, int32_t a, int32_t b, int32_t c, tri_key *out)
{
    int64_t p[3], tmp;
    /* y * 2^32 + (x as unsigned 32-bit): a multiply, as << of a negative y is undefined */
    p[0] = (int64_t)v[a].y * 4294967296LL + (int64_t)(uint32_t)v[a].x;
    p[1] = (int64_t)v[b].y * 4294967296LL + (int64_t)(uint32_t)v[b].x;
    p[2] = (int64_t)v[c].y * 4294967296LL + (int64_t)(uint32_t)v[c].x;
    if (p[0] > p[1]) { tmp = p[0]; p[0] = p[1]; p[1] = tmp; }
    if (p[1] > p[2]) { tmp = p[1]; p[1] = p[2]; p[2] = tmp; }
    if (p[0] > p[1]) { tmp = p[0]; p[0] = p[1]; p[1] = tmp; }
    memcpy(out->p, p, sizeof p);
    tmp = vcross(&v[a], &v[b], &v[c]);
    out->sign = tmp > 0 ? 1 : tmp < 0 ? -1 : 0;
}

/* Sorts keys by (p0, p1, p2): counting sort on p0 over the vertices' bounding
 * box, then insertion sort of each (small) bucket; qsort when the box is huge. */
static int sort_keys(tri_key *k, int64_t n, const mc_vert *v, int32_t nv)
{
    int64_t minx = INT32_MAX, maxx = INT32_MIN, miny = INT32_MAX, maxy = INT32_MIN, W, span, i, *start;
    tri_key *tmp;
    for (i = 0; i < nv; i++) {
        minx = min64(minx, v[i].x); maxx = max64(maxx, v[i].x);
        miny = min64(miny, v[i].y); maxy = max64(maxy, v[i].y);
    }
    if (n < 2) return 0;
    W = maxx - minx + 1;
    span = W * (maxy - miny + 1);
    if (span > ((int64_t)1 << 26) || span > 16 * (n + nv)) {
        qsort(k, (size_t)n, sizeof *k, key_cmp);
        return 0;
    }
    start = calloc((size_t)span + 1, sizeof *start);
    tmp = malloc((size_t)n * sizeof *tmp);
    if (!start || !tmp) { free(start); free(tmp); return -1; }
#define KEY_IX(p) ((((p) >> 32) - miny) * W + ((int64_t)(int32_t)(uint32_t)((p) & 0xffffffff) - minx))
    for (i = 0; i < n; i++) start[KEY_IX(k[i].p[0]) + 1]++;
    for (i = 0; i < span; i++) start[i + 1] += start[i];
    for (i = 0; i < n; i++) tmp[start[KEY_IX(k[i].p[0])]++] = k[i];
#undef KEY_IX
    for (i = 0; i < span; i++) {
        int64_t b = i ? start[i - 1] : 0, end = start[i], u, q;
        for (u = b + 1; u < end; u++) {
            tri_key cur = tmp[u];
            for (q = u; q > b && key_cmp(&tmp[q - 1], &cur) > 0; q--) tmp[q] = tmp[q - 1];
            tmp[q] = cur;
        }
    }
    memcpy(k, tmp, (size_t)n * sizeof *k);
    free(start); free(tmp);
    return 0;
}

int mc_strip_compare(const int32_t *s, int64_t n, const int32_t *tri, int64_t nt,
                     const mc_vert *v, int32_t nv, mc_strip_report *r)
{
    int64_t nd = 0, nl = 0, i, j;
    int32_t *dec;
    tri_key *ka, *kb;
    memset(r, 0, sizeof *r);
    r->refs = n;
    for (i = 0; i < 3 * nt; i++)
        if (tri[i] < 0 || tri[i] >= nv) return -1;
    dec = malloc((size_t)(3 * (n > 2 ? n - 2 : 0) + 1) * sizeof *dec);
    if (!dec) return -1;
    if (mc_strip_decode(s, n, v, nv, dec, &nd, NULL, &nl) != 0) { free(dec); return -1; }
    r->decoded = nd;
    r->line = nl;
    ka = malloc((size_t)(nd + 1) * sizeof *ka);
    kb = malloc((size_t)(nt + 1) * sizeof *kb);
    if (!ka || !kb) { free(dec); free(ka); free(kb); return -1; }
    for (i = 0; i < nd; i++) {
        make_key(v, dec[3 * i], dec[3 * i + 1], dec[3 * i + 2], &ka[i]);
        if (i == 0) r->orientation = ka[0].sign;
        else if (ka[i].sign != r->orientation) r->winding_mixed++;
    }
    for (i = 0; i < nt; i++) make_key(v, tri[3 * i], tri[3 * i + 1], tri[3 * i + 2], &kb[i]);
    if (sort_keys(ka, nd, v, nv) != 0 || sort_keys(kb, nt, v, nv) != 0) {
        free(dec); free(ka); free(kb);
        return -1;
    }
    for (i = 0, j = 0; i < nd || j < nt;) {
        int c = i >= nd ? 1 : j >= nt ? -1 : key_cmp(&ka[i], &kb[j]);
        if (c < 0) { r->extra++; i++; }
        else if (c > 0) { r->missing++; j++; }
        else { if (ka[i].sign != kb[j].sign) r->winding_vs_list++; i++; j++; }
    }
    r->ok = !(r->missing || r->extra || r->winding_mixed || r->winding_vs_list);
    free(dec); free(ka); free(kb);
    return r->ok;
}
