/* core/bt_err.c — the bitree's error hierarchy (see core/bitree.h).
 *
 * Geometry of the implicit tree (002 2.1, "4-8" layout).  For a sample (x, y)
 * of the padded n x n grid (n = 2^k + 1, not a corner) let h = 2^j with
 * j = min(ctz(x), ctz(y)).  Then (x, y) is the centre of exactly one diamond:
 *   type D (x/h and y/h odd): the square [x-h, x+h] x [y-h, y+h] cut along a
 *     diagonal; the diagonal runs (1,1) when (x>>(j+1)) + (y>>(j+1)) is even,
 *     (1,-1) otherwise; its two triangles have axis legs of length 2h and their
 *     right angles at the two other corners.  Children: the 4 edge midpoints
 *     (x +- h, y), (x, y +- h), type A at the same h.
 *   type A (one of x/h, y/h odd): the midpoint of an axis edge of length 2h
 *     (horizontal when x/h is odd); its triangles have that edge as hypotenuse
 *     and their right angles at distance h on each side.  Children (h >= 2):
 *     the 4 points (x +- h/2, y +- h/2), type D at h/2.
 * The root is the type D diamond at the centre, h = (n-1)/2.
 *
 * Exact metric (issue 3): for each triangle, the maximum over every grid sample
 * in the closed triangle of |plane - z|.  With apex c, hypotenuse ends a and b,
 * u = a - c, v = b - c, m = max |component of u| and D = cross(u, v) / m
 * (+-2h or +-2h... a power of two), the integer
 *     N(P) = D*(zc - zP) + s*(za - zc) + t*(zb - zc),
 *     s = cross(P - c, v) / m,  t = cross(u, P - c) / m  (exact integers),
 * is |D| times (plane - zP); along a row s and t change by constants, so a row
 * is a span over which N is a running sum (one add, one multiply-by-D and a
 * max/min per sample).  The triangle's error is ceil(max |N| / |D|), stored as
 * a code that rounds up (bt_code_encode): a TRUE bound.  Diamond value =
 * max(its triangles, its children), so the hierarchy is monotone.
 *
 * Voids (000): a triangle containing both valid and void samples gets
 * BT_CODE_SPLIT (always split); one with no valid sample gets 0 (never emitted:
 * its corners are voids).  Diamond triangles always have >= 4 samples, so
 * splitting mixed ones ends at unit triangles whose 3 corners decide.
 *
 * Curvature metric (001 eq. 2-4, 004): per sample the Frobenius norm of the
 * centred-difference Hessian, kappa = isqrt(kxx^2 + kxy^2 + kyx^2 + kyy^2) / 8
 * with k.. the doubled second differences over two grid steps (so kappa is in
 * height units, comparable to an interpolation error: for a quadric with second
 * derivative h'' per step, kappa = h''/2); per triangle the sum over its samples
 * (the extensive indicator K of 001 eq. 1).  Not a bound: the CLI prints the
 * true error of the result. */
#include <string.h>
#include "core/bitree.h"
#include "core/fx.h"

/* ------------------------------------------------------------ codes */
int64_t bt_code_value(uint16_t code)
{
    if (code == BT_CODE_SPLIT) return INT64_MAX;
    if (code < 4096) return code;
    {
        int e = (code >> 11) - 1;
        int64_t mant = (int64_t)((code & 2047) | 2048);
        return mant << e;
    }
}

uint16_t bt_code_encode(int64_t v)
{
    int e = 0;
    int64_t mant;
    if (v <= 0) return 0;
    if (v < 4096) return (uint16_t)v;
    e = 1;
    for (;;) {
        mant = (v + ((int64_t)1 << e) - 1) >> e;
        if (mant < 4096) break;
        e++;
    }
    if (e > 30) return (uint16_t)(BT_CODE_SPLIT - 1);
    return (uint16_t)(((e + 1) << 11) | (int)(mant & 2047));
}

int64_t bt_mm_to_units(const hf *f, int64_t mm)
{
    /* units * z_num / z_den metres <= mm / 1000  <=>  units <= mm * z_den / (1000 z_num) */
    if (mm <= 0) return 0;
    return (mm * f->z_den) / (1000LL * f->z_num);
}

/* ------------------------------------------------------------ sizes */
static int32_t padded_k(int32_t w, int32_t h)
{
    int32_t m = w > h ? w : h, k = 1;
    while (((int32_t)1 << k) + 1 < m) k++;
    return k;
}

size_t bt_mem_size(int32_t w, int32_t h)
{
    int32_t n;
    if (hf_check_dims(w, h) != BR_OK || w < 2 || h < 2) return 0;
    n = ((int32_t)1 << padded_k(w, h)) + 1;
    return (size_t)n * (size_t)n * 5;
}

size_t bt_scratch_size(int32_t w, int32_t h)
{
    if (hf_check_dims(w, h) != BR_OK || w < 2 || h < 2) return 0;
    /* sanitised heights (int32) + per-row void prefix counts (uint16, w+1 per row) */
    /* sanitised heights (int32), per-row void prefix counts (uint16, w+1 per row),
     * curvature per sample (int32, curvature metric only) */
    return (size_t)w * (size_t)h * 8 + (size_t)(w + 1) * (size_t)h * 2 + 16;
}

/* ------------------------------------------------------------ build */
typedef struct ctx {
    int32_t w, h, n;
    const int32_t *z;      /* sanitised heights, w*h (voids = 0) */
    const uint16_t *vp;    /* void prefix counts, (w+1)*h, or NULL if no voids */
    const int32_t *kap;    /* curvature per sample (curvature metric), else NULL */
    int32_t metric;
} ctx;

typedef struct tri_res {
    int64_t err;           /* exact error (ceil) or curvature sum */
    int32_t cls;           /* 0 full, 1 mixed, 2 all void */
    int32_t zlo, zhi;      /* own volume (full triangles only) */
} tri_res;

/* Number of void samples in row y, columns [x0, x1] (inclusive, inside the domain). */
static int32_t row_voids(const ctx *c, int32_t y, int32_t x0, int32_t x1)
{
    const uint16_t *p;
    if (!c->vp) return 0;
    p = c->vp + (size_t)y * (size_t)(c->w + 1);
    return (int32_t)p[x1 + 1] - (int32_t)p[x0];
}

static int64_t max64(int64_t a, int64_t b) { return a > b ? a : b; }
static int64_t min64(int64_t a, int64_t b) { return a < b ? a : b; }

/* The span of row y (absolute) of the triangle (a, c, b), apex c.  Returns 0 if
 * the row is outside the triangle.  Triangles here are right isosceles with
 * axis or diagonal legs, so each edge bounds x by a line of slope 0 or +-1. */
static int span_of(const int32_t a[2], const int32_t cc[2], const int32_t b[2], int32_t y,
                   int32_t *x0, int32_t *x1)
{
    const int32_t *p[3];
    int32_t lo = INT32_MIN, hi = INT32_MAX, i;
    int32_t ymin, ymax;
    p[0] = a; p[1] = cc; p[2] = b;
    ymin = a[1]; if (b[1] < ymin) ymin = b[1]; if (cc[1] < ymin) ymin = cc[1];
    ymax = a[1]; if (b[1] > ymax) ymax = b[1]; if (cc[1] > ymax) ymax = cc[1];
    if (y < ymin || y > ymax) return 0;
    for (i = 0; i < 3; i++) {
        const int32_t *e0 = p[i], *e1 = p[(i + 1) % 3], *o = p[(i + 2) % 3];
        int32_t dx = e1[0] - e0[0], dy = e1[1] - e0[1];
        /* side of o: sign of cross(e1 - e0, o - e0) */
        int64_t so = (int64_t)dx * (o[1] - e0[1]) - (int64_t)dy * (o[0] - e0[0]);
        if (dy == 0) {
            /* horizontal edge: bounds y only, already within [ymin, ymax] */
            continue;
        }
        /* point (X, y) is on o's side when sign(dx*(y-e0y) - dy*(X-e0x)) == sign(so).
         * |dy| == |dx| or dx == 0, so the boundary X = e0x + dx*(y-e0y)/dy is exact. */
        {
            int64_t num = (int64_t)dx * (y - e0[1]);
            int32_t xb = e0[0] + (int32_t)(num / dy);
            /* f(X) = dx*(y-e0y) - dy*(X - e0x): decreasing in X if dy > 0 */
            int inside_right = (so > 0) ? (dy < 0) : (dy > 0);
            if (inside_right) { if (xb > lo) lo = xb; }
            else { if (xb < hi) hi = xb; }
        }
    }
    if (lo > hi) return 0;
    *x0 = lo; *x1 = hi;
    return 1;
}

static void tri_eval(const ctx *c, const int32_t a[2], const int32_t cc[2], const int32_t b[2],
                     tri_res *r)
{
    int32_t ymin, ymax, y, x0, x1;
    int64_t valid = 0, voids = 0;
    r->err = 0; r->cls = 0; r->zlo = 0; r->zhi = 0;
    ymin = a[1]; if (b[1] < ymin) ymin = b[1]; if (cc[1] < ymin) ymin = cc[1];
    ymax = a[1]; if (b[1] > ymax) ymax = b[1]; if (cc[1] > ymax) ymax = cc[1];
    /* pass 1: classify */
    for (y = ymin; y <= ymax; y++) {
        int32_t cx0, cx1, len;
        if (!span_of(a, cc, b, y, &x0, &x1)) continue;
        len = x1 - x0 + 1;
        if (y >= c->h) { voids += len; continue; }
        cx0 = x0; cx1 = x1 < c->w - 1 ? x1 : c->w - 1;
        if (cx1 < cx0) { voids += len; continue; }
        voids += len - (cx1 - cx0 + 1);
        {
            int32_t v = row_voids(c, y, cx0, cx1);
            voids += v;
            valid += (cx1 - cx0 + 1) - v;
        }
    }
    if (voids > 0) { r->cls = valid > 0 ? 1 : 2; return; }
    {
        int32_t za = c->z[(size_t)a[1] * c->w + a[0]];
        int32_t zb = c->z[(size_t)b[1] * c->w + b[0]];
        int32_t zc = c->z[(size_t)cc[1] * c->w + cc[0]];
        int32_t zl = za < zb ? za : zb, zh = za > zb ? za : zb;
        if (zc < zl) zl = zc;
        if (zc > zh) zh = zc;
        if (c->metric == BT_METRIC_CURVATURE) {
            int64_t sum = 0;
            for (y = ymin; y <= ymax; y++) {
                const int32_t *kr;
                int32_t x;
                if (!span_of(a, cc, b, y, &x0, &x1)) continue;
                kr = c->kap + (size_t)y * c->w;
                for (x = x0; x <= x1; x++) sum += kr[x];
            }
            r->err = sum;
            r->zlo = zl; r->zhi = zh;   /* curvature is no height bound: volume from vertices */
            /* widen by the true vertical error of the plane is unknown here; use the
             * sample range instead (exact, computed below) */
            {
                int32_t lo = zl, hi = zh;
                for (y = ymin; y <= ymax; y++) {
                    const int32_t *zr;
                    int32_t x;
                    if (!span_of(a, cc, b, y, &x0, &x1)) continue;
                    zr = c->z + (size_t)y * c->w;
                    for (x = x0; x <= x1; x++) {
                        if (zr[x] < lo) lo = zr[x];
                        if (zr[x] > hi) hi = zr[x];
                    }
                }
                r->zlo = lo; r->zhi = hi;
            }
            return;
        }
        {
            int32_t ux = a[0] - cc[0], uy = a[1] - cc[1], vx = b[0] - cc[0], vy = b[1] - cc[1];
            int32_t m = ux < 0 ? -ux : ux;
            int64_t D, dza = (int64_t)za - zc, dzb = (int64_t)zb - zc, A;
            int64_t mx = 0, mn = 0, e;
            if ((uy < 0 ? -uy : uy) > m) m = uy < 0 ? -uy : uy;
            D = ((int64_t)ux * vy - (int64_t)uy * vx) / m;
            A = ((int64_t)vy * dza - (int64_t)uy * dzb) / m;
            for (y = ymin; y <= ymax; y++) {
                const int32_t *zr;
                int64_t s, t, p;
                int32_t x;
                if (!span_of(a, cc, b, y, &x0, &x1)) continue;
                s = ((int64_t)(x0 - cc[0]) * vy - (int64_t)(y - cc[1]) * vx) / m;
                t = ((int64_t)ux * (y - cc[1]) - (int64_t)uy * (x0 - cc[0])) / m;
                p = D * zc + s * dza + t * dzb;
                zr = c->z + (size_t)y * c->w;
                for (x = x0; x <= x1; x++) {
                    int64_t d = p - D * zr[x];
                    mx = d > mx ? d : mx;
                    mn = d < mn ? d : mn;
                    p += A;
                }
            }
            if (D < 0) D = -D;
            e = max64(mx, -mn);
            r->err = (e + D - 1) / D;
            r->zlo = (int32_t)max64((int64_t)zl - r->err, INT32_MIN + 1);
            r->zhi = (int32_t)min64((int64_t)zh + r->err, INT32_MAX);
        }
    }
}

/* quantise a height to the tree's 8-bit range, rounding down (lo) or up (hi) */
static uint8_t q_lo(const bt_tree *t, int64_t z)
{
    int64_t r = (int64_t)t->zmax - t->zmin;
    if (z <= t->zmin || r <= 0) return 0;
    if (z >= t->zmax) return 255;
    return (uint8_t)(((z - t->zmin) * 255) / r);
}
static uint8_t q_hi(const bt_tree *t, int64_t z)
{
    int64_t r = (int64_t)t->zmax - t->zmin;
    if (r <= 0) return 255;
    if (z <= t->zmin) return 0;
    if (z >= t->zmax) return 255;
    return (uint8_t)(((z - t->zmin) * 255 + r - 1) / r);
}

static void diamond(bt_tree *t, const ctx *c, int32_t x, int32_t y, int32_t h, int typeD)
{
    int32_t n = t->n, S = n - 1;
    int32_t ap[2][2], a[2], b[2];
    int na = 0, i;
    uint16_t code = 0;
    int lo = 255, hi = 0;
    size_t idx = (size_t)y * n + x;
    if (typeD) {
        int diag = (((x >> 1) / h + (y >> 1) / h) & 1) == 0; /* (x>>(j+1)) + (y>>(j+1)) even */
        if (diag) { a[0] = x - h; a[1] = y - h; b[0] = x + h; b[1] = y + h;
                    ap[0][0] = x + h; ap[0][1] = y - h; ap[1][0] = x - h; ap[1][1] = y + h; }
        else      { a[0] = x - h; a[1] = y + h; b[0] = x + h; b[1] = y - h;
                    ap[0][0] = x - h; ap[0][1] = y - h; ap[1][0] = x + h; ap[1][1] = y + h; }
        na = 2;
    } else if ((x / h) & 1) {      /* horizontal edge */
        a[0] = x - h; a[1] = y; b[0] = x + h; b[1] = y;
        if (y - h >= 0) { ap[na][0] = x; ap[na][1] = y - h; na++; }
        if (y + h <= S) { ap[na][0] = x; ap[na][1] = y + h; na++; }
    } else {                       /* vertical edge */
        a[0] = x; a[1] = y - h; b[0] = x; b[1] = y + h;
        if (x - h >= 0) { ap[na][0] = x - h; ap[na][1] = y; na++; }
        if (x + h <= S) { ap[na][0] = x + h; ap[na][1] = y; na++; }
    }
    for (i = 0; i < na; i++) {
        tri_res r;
        tri_eval(c, a, ap[i], b, &r);
        if (r.cls == 1) code = BT_CODE_SPLIT;
        else if (r.cls == 0) {
            uint16_t e = bt_code_encode(r.err);
            uint8_t l = q_lo(t, r.zlo), u = q_hi(t, r.zhi);
            if (e > code) code = e;
            if (l < lo) lo = l;
            if (u > hi) hi = u;
        }
    }
    /* children */
    {
        int32_t cx[4], cy[4];
        int nc = 0;
        if (typeD) {
            cx[0] = x - h; cy[0] = y; cx[1] = x + h; cy[1] = y;
            cx[2] = x; cy[2] = y - h; cx[3] = x; cy[3] = y + h; nc = 4;
        } else if (h >= 2) {
            int32_t g = h >> 1;
            cx[0] = x - g; cy[0] = y - g; cx[1] = x + g; cy[1] = y - g;
            cx[2] = x - g; cy[2] = y + g; cx[3] = x + g; cy[3] = y + g; nc = 4;
        }
        for (i = 0; i < nc; i++) {
            size_t ci;
            if (cx[i] < 0 || cy[i] < 0 || cx[i] > S || cy[i] > S) continue;
            ci = (size_t)cy[i] * n + cx[i];
            if (t->err[ci] > code) code = t->err[ci];
            if (t->zlo[ci] < lo) lo = t->zlo[ci];
            if (t->zhi[ci] > hi) hi = t->zhi[ci];
        }
    }
    t->err[idx] = code;
    t->zlo[idx] = (uint8_t)lo;
    t->zhi[idx] = (uint8_t)hi;
}

static int32_t kappa_at(const int32_t *z, int32_t w, int32_t h, int32_t x, int32_t y)
{
    /* doubled second differences over two steps (001 eq. 2-3 with dx = 1):
     * kxx = G_x(x+1) - G_x(x-1) with 2 G_x(x) = z(x+1) - z(x-1), etc. */
    int64_t kxx, kyy, kxy, kyx, s;
#define Z(X, Y) ((int64_t)z[(size_t)(Y) * w + (X)])
#define B(X, Y) (z[(size_t)(Y) * w + (X)] == HF_NODATA)
    if (x < 2 || y < 2 || x >= w - 2 || y >= h - 2) return 0;
    if (B(x, y) || B(x - 2, y) || B(x + 2, y) || B(x, y - 2) || B(x, y + 2) ||
        B(x - 1, y - 1) || B(x + 1, y - 1) || B(x - 1, y + 1) || B(x + 1, y + 1)) return 0;
    kxx = Z(x + 2, y) - 2 * Z(x, y) + Z(x - 2, y);
    kyy = Z(x, y + 2) - 2 * Z(x, y) + Z(x, y - 2);
    kxy = (Z(x + 1, y + 1) - Z(x + 1, y - 1)) - (Z(x - 1, y + 1) - Z(x - 1, y - 1));
    kyx = kxy;
#undef Z
#undef B
    s = kxx * kxx + kyy * kyy + kxy * kxy + kyx * kyx;
    return (int32_t)(fx_isqrt64((uint64_t)s) / 8);
}

br_status bt_build(bt_tree *t, const hf *f, int32_t metric,
                   void *mem, size_t mem_bytes, void *scratch, size_t scratch_bytes)
{
    bt_tree nt;
    ctx c;
    int32_t *zs;
    uint16_t *vp;
    int32_t x, y, j, w, h, S, n;
    int64_t voids = 0;
    size_t nn;
    if (!t || !f || !mem || !scratch) return BR_E_ARG;
    if (hf_validate(f) != BR_OK || f->w < 2 || f->h < 2) return BR_E_ARG;
    if (metric != BT_METRIC_EXACT && metric != BT_METRIC_CURVATURE) return BR_E_ARG;
    if (mem_bytes < bt_mem_size(f->w, f->h)) return BR_E_ARG;
    if (scratch_bytes < bt_scratch_size(f->w, f->h)) return BR_E_ARG;
    w = f->w; h = f->h;
    memset(&nt, 0, sizeof nt);
    nt.f = f;
    nt.k = padded_k(w, h);
    nt.n = n = ((int32_t)1 << nt.k) + 1;
    S = n - 1;
    nt.metric = metric;
    nn = (size_t)n * n;
    nt.err = (uint16_t *)mem;
    nt.zlo = (uint8_t *)mem + nn * 2;
    nt.zhi = nt.zlo + nn;
    nt.st = nt.zhi + nn;
    memset(mem, 0, nn * 5);
    /* sanitised heights, stats */
    zs = (int32_t *)scratch;
    vp = (uint16_t *)((uint8_t *)scratch + (size_t)w * h * 4);
    {
        int first = 1;
        for (y = 0; y < h; y++) {
            const int32_t *zr = f->z + (size_t)y * w;
            int32_t *sr = zs + (size_t)y * w;
            uint16_t *pr = vp + (size_t)y * (w + 1);
            uint16_t cnt = 0;
            pr[0] = 0;
            for (x = 0; x < w; x++) {
                int32_t v = zr[x];
                if (v == HF_NODATA) { sr[x] = 0; cnt++; voids++; }
                else {
                    sr[x] = v;
                    if (first) { nt.zmin = nt.zmax = v; first = 0; }
                    if (v < nt.zmin) nt.zmin = v;
                    if (v > nt.zmax) nt.zmax = v;
                }
                pr[x + 1] = cnt;
            }
        }
    }
    nt.nvalid = (int64_t)w * h - voids;
    c.w = w; c.h = h; c.n = n; c.z = zs; c.vp = voids ? vp : NULL; c.metric = metric;
    c.kap = NULL;
    if (metric == BT_METRIC_CURVATURE) {
        int32_t *kap = (int32_t *)(void *)((uint8_t *)vp + (size_t)(w + 1) * h * 2 + 8);
        kap = (int32_t *)(void *)((uintptr_t)kap & ~(uintptr_t)3);
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++)
                kap[(size_t)y * w + x] = kappa_at(f->z, w, h, x, y);
        c.kap = kap;
    }
    *t = nt;
    for (j = 0; j < nt.k; j++) {
        int32_t hh = (int32_t)1 << j;
        /* type A at h: horizontal edges (x odd multiple of h, y multiple of 2h) */
        for (y = 0; y <= S; y += 2 * hh)
            for (x = hh; x < S; x += 2 * hh) diamond(t, &c, x, y, hh, 0);
        /* vertical edges */
        for (y = hh; y < S; y += 2 * hh)
            for (x = 0; x <= S; x += 2 * hh) diamond(t, &c, x, y, hh, 0);
        /* type D at h */
        for (y = hh; y < S; y += 2 * hh)
            for (x = hh; x < S; x += 2 * hh) diamond(t, &c, x, y, hh, 1);
    }
    return BR_OK;
}
