/* core/bt_err.c — the bitree's error hierarchy (see core/bitree.h).
 *
 * Geometry of the implicit tree (002 2.1, "4-8" layout; the RTIN of Evans,
 * Franklin & Kirkpatrick 2001, ROAM's diamonds, Duchaineau et al. 1997).  For a sample (x, y)
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
 * (+-2h for both kinds of triangle: a power of two, so * D is a shift), the integer
 *     N(P) = D*(zc - zP) + s*(za - zc) + t*(zb - zc),
 *     s = cross(P - c, v) / m,  t = cross(u, P - c) / m  (exact integers),
 * is |D| times (plane - zP); along a row s and t change by constants, so a row
 * is a span over which N is a running sum (one add, one shift and a max/min per
 * sample, 8 lanes at a time).  The two finest levels are stencils, h = 2 and 4
 * use per-shape sample tables, and a half whose sound bound e_m + max(child
 * half bounds) is already below its children's maximum skips the scan.  The triangle's error is ceil(max |N| / |D|), stored as
 * a code that rounds up (bt_code_encode): a TRUE bound.  Diamond value =
 * max(its triangles, its children), so the hierarchy is monotone.
 *
 * Voids (000): a triangle with no valid sample gets 0 (never emitted: its corners
 * are voids).  A MIXED triangle (valid and void samples) is always split
 * (BT_CODE_SPLIT) when one of its samples lies in the padding beyond w x h, or
 * with the curvature metric.  Mixed over the grid's own voids (inside w x h, exact
 * metric), its value is instead its EXTENT (void_extent: a bound on the distance
 * between two of its points, in height units) joined with the error over its
 * valid samples when its 3 corners are valid; left unsplit, such a triangle is
 * drawn over the void (valid corners; every valid sample within the error) or
 * dropped (a void corner): either way the hole is misplaced by at most that
 * distance, which a view rule projects like any error.  So a void costs triangles
 * in proportion to what the error asks for, not refinement to the sample at any
 * distance (a floor that SRTM's scattered voids put on every frame), and below
 * a unit triangle's extent holes are exact as before.  Diamond triangles always
 * have >= 4 samples, so splitting mixed ones ends at unit triangles whose 3
 * corners decide.
 * Empty triangles: what a mixed triangle finally contributes are its descendant
 * unit triangles with 3 valid corners (its CONTENT, computed bottom-up: a unit
 * pair's corners, else the OR of the two child halves).  A mixed triangle with no
 * content and a void corner is EMPTY: it gets 0 like an all-void one, so nothing
 * forces it to split, and when left unsplit the selection drops it by its void
 * corner; splitting it all the way would have emitted nothing either, so every
 * mesh is the one the SPLIT rule gives minus needless splits.  This is what makes
 * the padding beyond w x h (voids to n x n) cost nothing along the data's east and
 * south edges: a triangle outside whose only valid samples lie on the edge is
 * empty, not mixed.  (A mixed triangle whose 3 corners are valid stays SPLIT even
 * without content: left unsplit it would be drawn over its voids.)
 *
 * Curvature metric (001 eq. 2-4, 004): per sample the Frobenius norm of the
 * centred-difference Hessian, kappa = isqrt(kxx^2 + kxy^2 + kyx^2 + kyy^2) / 8
 * with k.. the second differences over two grid steps (kappa is in height units:
 * for z = c x^2, kxx = 8c and kappa = c); per triangle the sum over its samples
 * (the extensive indicator K of 001 eq. 1).  Not a bound: the CLI prints the
 * true error of the result. */
#include <string.h>
#include "core/bitree.h"
#include "core/fx.h"
#include "core/bt_int.h"

/* ------------------------------------------------------------ build */


typedef struct tri_res {
    int64_t err;           /* exact error (ceil) or curvature sum */
    int32_t cls;           /* 0 full, 1 mixed, 2 all void */
    int32_t zlo, zhi;      /* own volume (full triangles, and mixed ones with vc) */
    int32_t vc;            /* mixed, inside w x h, three valid corners, exact metric:
                              err, zlo and zhi are over its valid samples */
} tri_res;

static int64_t max64(int64_t a, int64_t b) { return a > b ? a : b; }
static int64_t min64(int64_t a, int64_t b) { return a < b ? a : b; }

/* Row spans of the triangle (a, c, b), apex c, into c->ry/rx0/rx1 (no division:
 * the legs are axis-parallel (type D) or diagonal (type A)).  Returns the row count. */
static int32_t spans(const bti_build_ctx *c, const int32_t a[2], const int32_t cc[2], const int32_t b[2])
{
    int32_t *ry = c->ry, *r0 = c->rx0, *r1 = c->rx1, nr = 0, t;
    if (a[0] != cc[0] && a[1] != cc[1]) {
        /* diagonal legs: hypotenuse a-b is axis-parallel, apex at distance h */
        if (a[1] == b[1]) {           /* horizontal hypotenuse */
            int32_t xm = (a[0] + b[0]) >> 1, h = cc[1] - a[1], sg = h < 0 ? -1 : 1;
            if (h < 0) h = -h;
            for (t = 0; t <= h; t++) { ry[nr] = a[1] + sg * t; r0[nr] = xm - h + t; r1[nr] = xm + h - t; nr++; }
        } else {                      /* vertical hypotenuse */
            int32_t ym = (a[1] + b[1]) >> 1, h = cc[0] - a[0], d;
            int32_t h2 = h < 0 ? -h : h;
            for (d = -h2; d <= h2; d++) {
                int32_t w = h2 - (d < 0 ? -d : d);
                ry[nr] = ym + d;
                if (h > 0) { r0[nr] = a[0]; r1[nr] = a[0] + w; } else { r0[nr] = a[0] - w; r1[nr] = a[0]; }
                nr++;
            }
        }
    } else {
        /* axis legs: one of a, b shares cc's row, the other its column */
        const int32_t *px = a[1] == cc[1] ? a : b, *py = a[1] == cc[1] ? b : a;
        int32_t L = px[0] - cc[0], sx = L < 0 ? -1 : 1, sy = py[1] > cc[1] ? 1 : -1;
        if (L < 0) L = -L;
        for (t = 0; t <= L; t++) {
            ry[nr] = cc[1] + sy * t;
            if (sx > 0) { r0[nr] = cc[0]; r1[nr] = cc[0] + (L - t); }
            else { r0[nr] = cc[0] - (L - t); r1[nr] = cc[0]; }
            nr++;
        }
    }
    return nr;
}

/* Accumulates max and min of P(x) - (z[x] << k) over a row of n samples into the
 * 8 lanes vmx/vmn, P(x0) = p, ramp[i] = A * i; int32 (callers guarantee the
 * range, see bt_build).  Whole blocks of 8 with the lanes past the end masked to
 * 0 (neutral: the lanes start at 0), so short rows cost one block and compilers
 * vectorise it with plain SSE2/NEON.  Reading up to 7 samples past the row is
 * safe: the sanitised copy has 8 spare entries at its end. */
static void row32(const int32_t *zr, int32_t n, int32_t p, int32_t A8, const int32_t *ramp, int k,
                  int32_t *vmx, int32_t *vmn)
{
    int32_t i, x;
    for (x = 0; x < n; x += 8) {
        int32_t rem = n - x;
        for (i = 0; i < 8; i++) {
            int32_t d = p + ramp[i] - (zr[x + i] << k);
            d = i < rem ? d : 0;
            vmx[i] = d > vmx[i] ? d : vmx[i];
            vmn[i] = d < vmn[i] ? d : vmn[i];
        }
        p += A8;
    }
}

/* height of sample (x, y) (biased) into *z; 0 if it is a void or outside w x h */
static int samp(const bti_build_ctx *c, int32_t x, int32_t y, int32_t *z)
{
    if (x >= c->w || y >= c->h) return 0;
    if (c->vp) {
        const uint16_t *pr = c->vp + (size_t)y * (size_t)(c->w + 1);
        if (pr[x + 1] != pr[x]) return 0;
    }
    *z = c->z[(size_t)y * c->w + x];
    return 1;
}


static int32_t sgn32(int32_t v) { return (v > 0) - (v < 0); }

/* The two finest diamond levels in closed form (they are 3/4 of all triangles):
 * hypotenuse 2 on an axis (samples a, b, c and the midpoint m: only m is off
 * the plane) or on a diagonal (also the two leg midpoints). */
static int tri_small(const bti_build_ctx *c, const int32_t a[2], const int32_t cc[2], const int32_t b[2],
                     tri_res *r)
{
    int32_t dx = b[0] - a[0], dy = b[1] - a[1];
    int32_t px[6], py[6], z[6], np, i, nv = 0, e2;
    int ok[6];
    if (!((bti_iabs32(dx) == 2 && dy == 0) || (dx == 0 && bti_iabs32(dy) == 2) ||
          (bti_iabs32(dx) == 2 && bti_iabs32(dy) == 2))) return 0;
    px[0] = a[0]; py[0] = a[1]; px[1] = b[0]; py[1] = b[1]; px[2] = cc[0]; py[2] = cc[1];
    px[3] = (a[0] + b[0]) >> 1; py[3] = (a[1] + b[1]) >> 1;
    np = 4;
    if (dx != 0 && dy != 0) {
        px[4] = (a[0] + cc[0]) >> 1; py[4] = (a[1] + cc[1]) >> 1;
        px[5] = (b[0] + cc[0]) >> 1; py[5] = (b[1] + cc[1]) >> 1;
        np = 6;
    }
    for (i = 0; i < np; i++) { ok[i] = samp(c, px[i], py[i], &z[i]); nv += ok[i]; }
    r->err = 0; r->zlo = 0; r->zhi = 0; r->vc = 0;
    r->cls = nv == np ? 0 : nv > 0 ? 1 : 2;
    if (r->cls != 0 && !(r->cls == 1 && ok[0] && ok[1] && ok[2])) return 1;   /* (exact metric only) */
    r->vc = r->cls == 1;
    /* the samples off the plane: the hypotenuse's midpoint, and the legs' on a
     * diagonal hypotenuse; a mixed triangle's valid ones only */
    e2 = ok[3] ? bti_iabs32(z[0] + z[1] - 2 * z[3]) : 0;
    if (np == 6) {
        int32_t e4 = ok[4] ? bti_iabs32(z[2] + z[0] - 2 * z[4]) : 0;
        int32_t e5 = ok[5] ? bti_iabs32(z[2] + z[1] - 2 * z[5]) : 0;
        if (e4 > e2) e2 = e4;
        if (e5 > e2) e2 = e5;
    }
    r->err = (e2 + 1) >> 1;
    {
        int32_t zl = z[0], zh = z[0];
        for (i = 1; i < 3; i++) { if (z[i] < zl) zl = z[i]; if (z[i] > zh) zh = z[i]; }
        r->zlo = zl - (int32_t)r->err; if (r->zlo < 0) r->zlo = 0;
        r->zhi = zh + (int32_t)r->err;
    }
    return 1;
}



/* table index of triangle (a, cc, b) of a small level, or -1 */
static int tab_index(const int32_t a[2], const int32_t cc[2], const int32_t b[2])
{
    int32_t mx2 = a[0] + b[0] - 2 * cc[0], my2 = a[1] + b[1] - 2 * cc[1]; /* 2 (mid - apex) */
    int32_t len = bti_iabs32(a[0] - b[0]) + bti_iabs32(a[1] - b[1]);           /* 2h*2 (D) or 2h (A) */
    int dir, lv;
    if (a[0] != cc[0] && a[1] != cc[1]) {            /* type A: diagonal legs, hyp 2h */
        if (len == 4) lv = 0; else if (len == 8) lv = 1; else return -1;
        dir = my2 < 0 ? 0 : my2 > 0 ? 1 : mx2 < 0 ? 2 : 3;
    } else {                                         /* type D: axis legs 2h, diagonal hyp */
        if (len == 8) lv = 0; else if (len == 16) lv = 1; else return -1;
        dir = 4 + (mx2 > 0) + 2 * (my2 > 0);
    }
    return lv * 8 + dir;
}

static void tab_build(bti_build_ctx *c, const int32_t a[2], const int32_t cc[2], const int32_t b[2])
{
    int ti = tab_index(a, cc, b), nr, i, n = 0;
    int32_t x, *e;
    if (ti < 0 || c->tabn[ti] >= 0) return;
    e = c->tab + (size_t)ti * BTI_TAB_MAX * 3;
    nr = spans(c, a, cc, b);
    for (i = 0; i < nr; i++)
        for (x = c->rx0[i]; x <= c->rx1[i]; x++) {
            int32_t y = c->ry[i];
            if ((x == a[0] && y == a[1]) || (x == b[0] && y == b[1]) || (x == cc[0] && y == cc[1])) continue;
            if (n >= BTI_TAB_MAX) return;
            e[3 * n] = (y - cc[1]) * c->w + (x - cc[0]);
            e[3 * n + 1] = x - cc[0];
            e[3 * n + 2] = y - cc[1];
            n++;
        }
    c->tabn[ti] = n;
}

/* The plane of triangle (a, cc, b), apex cc, times D: P(x, y) = D zc + (x - cx) A +
 * (y - cy) B, D = cross(u, v) / m, u = a - c, v = b - c, m = max |u component| (so
 * u/m, v/m are in {-1, 0, 1}: the signs of the components); normalised to D > 0, a
 * power of two, D = 2^k. */
typedef struct tri_plane {
    int64_t D, A, B;
    int32_t k;
} tri_plane;

static void plane_of(const int32_t a[2], const int32_t cc[2], const int32_t b[2], int32_t za, int32_t zb,
                     int32_t zc, tri_plane *pl)
{
    int32_t ux = a[0] - cc[0], uy = a[1] - cc[1], vx = b[0] - cc[0], vy = b[1] - cc[1];
    int64_t dza = (int64_t)za - zc, dzb = (int64_t)zb - zc;
    pl->D = (int64_t)ux * sgn32(vy) - (int64_t)uy * sgn32(vx);
    pl->A = (int64_t)sgn32(vy) * dza - (int64_t)sgn32(uy) * dzb;
    pl->B = -(int64_t)sgn32(vx) * dza + (int64_t)sgn32(ux) * dzb;
    if (pl->D < 0) { pl->D = -pl->D; pl->A = -pl->A; pl->B = -pl->B; }
    pl->k = 0;
    while (((int64_t)1 << pl->k) < pl->D) pl->k++;
}

/* max |P - (z << k)| over the rows c->ry/rx0/rx1 (nr) in int64, one sample at a time;
 * with skip_voids the void samples (c->vp) are left out */
static int64_t scan_wide(const bti_build_ctx *c, const tri_plane *pl, const int32_t cc[2], int32_t zc, int32_t nr,
                         int skip_voids)
{
    int64_t mx = 0, mn = 0;
    int32_t i;
    for (i = 0; i < nr; i++) {
        int32_t y = c->ry[i], x;
        const int32_t *zr = c->z + (size_t)y * c->w;
        const uint16_t *pr = skip_voids ? c->vp + (size_t)y * (size_t)(c->w + 1) : NULL;
        int64_t p = pl->D * zc + (int64_t)(c->rx0[i] - cc[0]) * pl->A + (int64_t)(y - cc[1]) * pl->B;
        for (x = c->rx0[i]; x <= c->rx1[i]; x++, p += pl->A) {
            int64_t d;
            if (pr && pr[x + 1] != pr[x]) continue;
            d = p - ((int64_t)zr[x] << pl->k);
            mx = d > mx ? d : mx;
            mn = d < mn ? d : mn;
        }
    }
    return max64(mx, -mn);
}

/* r's error from e = max |P - (z << k)| (rounded up) and its volume: the corners'
 * heights +- the error */
static void set_err(tri_res *r, int64_t e, const tri_plane *pl, int32_t za, int32_t zb, int32_t zc)
{
    int32_t zl = za < zb ? za : zb, zh = za > zb ? za : zb;
    if (zc < zl) zl = zc;
    if (zc > zh) zh = zc;
    r->err = (e + pl->D - 1) >> pl->k;
    r->zlo = (int32_t)max64((int64_t)zl - r->err, 0);
    r->zhi = (int32_t)min64((int64_t)zh + r->err, INT32_MAX);
}

/* dclean: the caller knows every sample of the triangle is valid (1), or not (0) */
static void tri_eval(const bti_build_ctx *c, const int32_t a[2], const int32_t cc[2], const int32_t b[2],
                     int ti, int dclean, tri_res *r)
{
    int32_t nr, i;
    int64_t valid = 0, voids = 0;
    if (c->metric == BT_METRIC_EXACT && c->narrow && ti >= 0 && c->tabn[ti] > 0) {
        if (dclean) {
            const int32_t *e = c->tab + (size_t)ti * BTI_TAB_MAX * 3;
            const int32_t *zc0 = c->z + (size_t)cc[1] * c->w + cc[0];
            int32_t za = c->z[(size_t)a[1] * c->w + a[0]], zb = c->z[(size_t)b[1] * c->w + b[0]], zc = *zc0;
            int32_t ux = a[0] - cc[0], uy = a[1] - cc[1], vx = b[0] - cc[0], vy = b[1] - cc[1];
            int32_t D = ux * sgn32(vy) - uy * sgn32(vx), dza = za - zc, dzb = zb - zc;
            int32_t A = sgn32(vy) * dza - sgn32(uy) * dzb, B = -sgn32(vx) * dza + sgn32(ux) * dzb;
            int32_t k = 0, mx = 0, mn = 0, base, n = c->tabn[ti], zl, zh, err;
            if (D < 0) { D = -D; A = -A; B = -B; }
            while ((1 << k) < D) k++;
            base = D * zc;
            for (i = 0; i < n; i++) {
                int32_t d = base + e[3 * i + 1] * A + e[3 * i + 2] * B - (zc0[e[3 * i]] << k);
                mx = d > mx ? d : mx;
                mn = d < mn ? d : mn;
            }
            if (-mn > mx) mx = -mn;
            err = (mx + D - 1) >> k;
            zl = za < zb ? za : zb; zh = za > zb ? za : zb;
            if (zc < zl) zl = zc;
            if (zc > zh) zh = zc;
            r->cls = 0; r->vc = 0; r->err = err;
            r->zlo = zl - err < 0 ? 0 : zl - err;
            r->zhi = zh + err;
            return;
        }
    }
    if (c->metric == BT_METRIC_EXACT && c->narrow && ti < 0 && tri_small(c, a, cc, b, r)) return;
    r->err = 0; r->cls = 0; r->zlo = 0; r->zhi = 0; r->vc = 0;
    nr = spans(c, a, cc, b);
    /* pass 1: classify (samples outside w x h are voids) */
    {
        int32_t bx = a[0] > b[0] ? a[0] : b[0], by = a[1] > b[1] ? a[1] : b[1];
        int32_t lx = a[0] < b[0] ? a[0] : b[0], ly = a[1] < b[1] ? a[1] : b[1];
        if (cc[0] > bx) bx = cc[0];
        if (cc[1] > by) by = cc[1];
        if (cc[0] < lx) lx = cc[0];
        if (cc[1] < ly) ly = cc[1];
        if (lx >= c->w || ly >= c->h) { r->cls = 2; return; }   /* wholly outside: void */
        if (bti_box_clean(c, lx, ly, bx, by)) nr = -nr;                 /* wholly valid: full */
    }
    if (nr < 0) nr = -nr;
    else for (i = 0; i < nr; i++) {
        int32_t y = c->ry[i], x0 = c->rx0[i], x1 = c->rx1[i], cx1, len = x1 - x0 + 1;
        if (y >= c->h || x0 >= c->w) { voids += len; continue; }
        cx1 = x1 < c->w - 1 ? x1 : c->w - 1;
        voids += len - (cx1 - x0 + 1);
        if (c->vp) {
            const uint16_t *pr = c->vp + (size_t)y * (size_t)(c->w + 1);
            int32_t v = (int32_t)pr[cx1 + 1] - (int32_t)pr[x0];
            voids += v;
            valid += (cx1 - x0 + 1) - v;
        } else valid += cx1 - x0 + 1;
    }
    if (voids > 0) {
        int32_t za, zb, zc;
        r->cls = valid > 0 ? 1 : 2;
        /* mixed with three valid corners (so inside w x h): its valid samples' error */
        if (r->cls == 1 && c->metric == BT_METRIC_EXACT && samp(c, a[0], a[1], &za) && samp(c, b[0], b[1], &zb)
            && samp(c, cc[0], cc[1], &zc)) {
            tri_plane pl;
            plane_of(a, cc, b, za, zb, zc, &pl);
            set_err(r, scan_wide(c, &pl, cc, zc, nr, 1), &pl, za, zb, zc);
            r->vc = 1;
        }
        return;
    }
    {
        int32_t za = c->z[(size_t)a[1] * c->w + a[0]];
        int32_t zb = c->z[(size_t)b[1] * c->w + b[0]];
        int32_t zc = c->z[(size_t)cc[1] * c->w + cc[0]];
        if (c->metric == BT_METRIC_CURVATURE) {
            int64_t sum = 0;
            int32_t lo = za < zb ? za : zb, hi = za > zb ? za : zb;
            if (zc < lo) lo = zc;
            if (zc > hi) hi = zc;
            for (i = 0; i < nr; i++) {
                const int32_t *kr = c->kap + (size_t)c->ry[i] * c->w;
                const int32_t *zr = c->z + (size_t)c->ry[i] * c->w;
                int32_t x;
                for (x = c->rx0[i]; x <= c->rx1[i]; x++) {
                    sum += kr[x];
                    if (zr[x] < lo) lo = zr[x];
                    if (zr[x] > hi) hi = zr[x];
                }
            }
            r->err = sum; r->zlo = lo; r->zhi = hi;
            return;
        }
        {
            tri_plane pl;
            int64_t e;
            plane_of(a, cc, b, za, zb, zc, &pl);
            if (c->narrow) {
                int32_t mx = 0, mn = 0, vmx[8], vmn[8], ramp[8], l, A = (int32_t)pl.A;
                for (l = 0; l < 8; l++) { vmx[l] = 0; vmn[l] = 0; ramp[l] = A * l; }
                for (i = 0; i < nr; i++) {
                    int32_t y = c->ry[i], x0 = c->rx0[i];
                    int32_t p = (int32_t)(pl.D * zc + (int64_t)(x0 - cc[0]) * pl.A + (int64_t)(y - cc[1]) * pl.B);
                    row32(c->z + (size_t)y * c->w + x0, c->rx1[i] - x0 + 1, p, 8 * A, ramp, pl.k, vmx, vmn);
                }
                for (l = 0; l < 8; l++) { mx = vmx[l] > mx ? vmx[l] : mx; mn = vmn[l] < mn ? vmn[l] : mn; }
                e = max64(mx, -(int64_t)mn);
            } else e = scan_wide(c, &pl, cc, zc, nr, 0);
            set_err(r, e, &pl, za, zb, zc);
        }
    }
}





/* Codes order as their values do (bt_code_encode) */
static uint16_t code_max(uint16_t a, uint16_t b) { return a > b ? a : b; }

void bte_extent_init(bti_build_ctx *c, const hf *f)
{
    int64_t dx = f->dx_um, dy = f->dy_um, dg;
    if (dx < ((int64_t)1 << 31) && dy < ((int64_t)1 << 31)) {
        uint64_t v = (uint64_t)(dx * dx) + (uint64_t)(dy * dy), r = fx_isqrt64(v);   /* v < 2^63 */
        dg = (int64_t)r + (r * r < v);
    } else dg = dx + dy;                   /* at least the diagonal (steps above 2 km) */
    c->step_um[0] = dx > dy ? dx : dy;
    c->step_um[1] = dg;
    c->ext_den = (int64_t)f->z_num * 1000000;
    c->ext_zden = f->z_den;
}

/* The EXTENT of a triangle of diamond scale h ("Voids" above): a bound on the
 * distance between any two of its points, in heightfield units rounded up.  Type A
 * (hypotenuse 2h steps on an axis, legs h diagonal steps): 2h times the longer axis
 * step, >= both; type D (legs 2h axis steps): 2h diagonal steps.  Either is at
 * least 2h times the longer axis step, which is what the referee relies on
 * (meshcheck's void_reach).  The largest finite code when the product would
 * overflow: 2h < 2^17 and a step < 2^39 um keep 2h * step below 2^56. */
static uint16_t void_extent(const bti_build_ctx *c, int32_t h, int typeD)
{
    int64_t um = 2 * (int64_t)h * c->step_um[typeD ? 1 : 0];
    if (um > (INT64_MAX - c->ext_den) / c->ext_zden) return (uint16_t)(BT_CODE_SPLIT - 1);
    return bt_code_encode((um * c->ext_zden + c->ext_den - 1) / c->ext_den);
}

/* 1 when the mixed half (a, p, b), apex p, of diamond (x, y) is EMPTY (see the top
 * of this file): a void corner and no content.  Its children are the unit
 * triangles (a, m, p), (p, m, b) for an A diamond of h = 1, else the halves of the
 * diamonds at the legs' midpoints whose apex is m = (x, y), built before it. */
static int half_empty(const bt_tree *t, const bti_build_ctx *c, int32_t x, int32_t y, int32_t h, int typeD,
                      const int32_t a[2], const int32_t p[2], const int32_t b[2])
{
    int32_t z, m1x, m1y, m2x, m2y;
    int va = samp(c, a[0], a[1], &z), vb = samp(c, b[0], b[1], &z), vp = samp(c, p[0], p[1], &z);
    if (va && vb && vp) return 0;
    if (!typeD && h == 1) {
        int vm = samp(c, x, y, &z);
        return !(vm && vp && (va || vb));
    }
    m1x = (a[0] + p[0]) >> 1; m1y = (a[1] + p[1]) >> 1;
    m2x = (b[0] + p[0]) >> 1; m2y = (b[1] + p[1]) >> 1;
    return (c->emp[bti_slot(t, m1x, m1y)] >> bti_half_of(m1x, m1y, x, y) & 1) &&
           (c->emp[bti_slot(t, m2x, m2y)] >> bti_half_of(m2x, m2y, x, y) & 1);
}

/* Per-triangle upper bounds ub (exact when scanned) let most triangles skip the
 * scan: |plane_T - z| <= e_m + |plane_C - z| on each child C (the planes agree
 * on C's other two vertices and differ by e_m at the midpoint m), so
 * e(T) <= sb = e_m + max(ub(C1), ub(C2)).  When sb is already <= the children's
 * maximum (which the diamond takes anyway), the diamond's value is the same as
 * with the exact e(T): no scan.  The result equals the exact hierarchy. */
void bte_diamond(bt_tree *t, const bti_build_ctx *c, int32_t x, int32_t y, int32_t h, int typeD)
{
    int32_t n = t->n, S = n - 1;
    int32_t ap[2][2], a[2], b[2];
    int na = 0, i;
    uint16_t code = 0;
    int lo = 255, hi = 0;
    size_t idx = bti_slot(t, x, y);
    int64_t em = -1, cmax;
    int32_t za = 0, zb = 0, zm = 0;
    int dclean;
    if (typeD) {
        int diag = ((x ^ y) & (2 * h)) == 0; /* (x>>(j+1)) + (y>>(j+1)) even; h = 2^j */
        if (diag) { a[0] = x - h; a[1] = y - h; b[0] = x + h; b[1] = y + h;
                    ap[0][0] = x + h; ap[0][1] = y - h; ap[1][0] = x - h; ap[1][1] = y + h; }
        else      { a[0] = x - h; a[1] = y + h; b[0] = x + h; b[1] = y - h;
                    ap[0][0] = x - h; ap[0][1] = y - h; ap[1][0] = x + h; ap[1][1] = y + h; }
        na = 2;
    } else if (x & h) {            /* horizontal edge (x/h odd) */
        a[0] = x - h; a[1] = y; b[0] = x + h; b[1] = y;
        if (y - h >= 0) { ap[na][0] = x; ap[na][1] = y - h; na++; }
        if (y + h <= S) { ap[na][0] = x; ap[na][1] = y + h; na++; }
    } else {                       /* vertical edge */
        a[0] = x; a[1] = y - h; b[0] = x; b[1] = y + h;
        if (x - h >= 0) { ap[na][0] = x - h; ap[na][1] = y; na++; }
        if (x + h <= S) { ap[na][0] = x + h; ap[na][1] = y; na++; }
    }
    /* children first: their maximum decides whether the halves need a scan */
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
            ci = bti_slot(t, cx[i], cy[i]);
            {
                uint32_t v = c->node[ci];
                if (BT_NODE_ERR(v) > code) code = BT_NODE_ERR(v);
                if (BT_NODE_ZLO(v) < lo) lo = BT_NODE_ZLO(v);
                if (BT_NODE_ZHI(v) > hi) hi = BT_NODE_ZHI(v);
            }
        }
    }
    cmax = bt_code_value(code);
    dclean = bti_box_clean(c, x - h < 0 ? 0 : x - h, y - h < 0 ? 0 : y - h, x + h, y + h);
    if (c->ub && h >= 2 && code != BT_CODE_SPLIT) {
        int ok;
        if (dclean) {
            za = c->z[(size_t)a[1] * c->w + a[0]];
            zb = c->z[(size_t)b[1] * c->w + b[0]];
            zm = c->z[(size_t)y * c->w + x];
            ok = 1;
        } else ok = samp(c, a[0], a[1], &za) && samp(c, b[0], b[1], &zb) && samp(c, x, y, &zm);
        if (ok) em = (bti_iabs32(za + zb - 2 * zm) + 1) >> 1;
    }
    for (i = 0; i < na; i++) {
        tri_res r;
        size_t hv = 2 * idx + bti_half_of(x, y, ap[i][0], ap[i][1]);
        if (em >= 0 && code != BT_CODE_SPLIT) {
            int32_t m1x = (a[0] + ap[i][0]) >> 1, m1y = (a[1] + ap[i][1]) >> 1;
            int32_t m2x = (b[0] + ap[i][0]) >> 1, m2y = (b[1] + ap[i][1]) >> 1;
            size_t s1 = bti_slot(t, m1x, m1y), s2 = bti_slot(t, m2x, m2y);
            size_t q1 = bti_half_of(m1x, m1y, x, y), q2 = bti_half_of(m2x, m2y, x, y);
            int64_t u1 = c->ub[2 * s1 + q1], u2 = c->ub[2 * s2 + q2];
            int64_t sb = em + (u1 > u2 ? u1 : u2);
            if (u1 != BTI_UB_INF && u2 != BTI_UB_INF && sb <= cmax) {
                int32_t zp = c->z[(size_t)ap[i][1] * c->w + ap[i][0]];
                int32_t zl = za < zb ? za : zb, zh = za > zb ? za : zb;
                uint8_t l, u;
                if (zp < zl) zl = zp;
                if (zp > zh) zh = zp;
                l = bti_q_lo(c, (int64_t)zl - sb); u = bti_q_hi(c, (int64_t)zh + sb);
                if (l < lo) lo = l;
                if (u > hi) hi = u;
                c->ub[hv] = (int32_t)sb;
                /* a child mixed over the grid's voids makes this half mixed: its extent */
                if (((c->emp[s1] >> q1) | (c->emp[s2] >> q2)) & 4) {
                    c->emp[idx] |= (uint8_t)(4u << (hv & 1));
                    code = code_max(code, void_extent(c, h, typeD));
                }
                continue;
            }
        }
        {
            int ti = -1;
            if (h <= 4 && h >= 2) {
                ti = tab_index(a, ap[i], b);
                if (c->tabn[ti] < 0) tab_build((bti_build_ctx *)c, a, ap[i], b);
            }
            tri_eval(c, a, ap[i], b, ti, dclean, &r);
        }
        if (c->ub) c->ub[hv] = (r.cls == 0 || r.vc) && r.err < BTI_UB_INF ? (int32_t)r.err : BTI_UB_INF;
        /* a mixed triangle with no descendant unit triangle of three valid corners draws
         * nothing: empty, not split (the padding to (2^k+1)^2 keeps no edge samples) */
        if (r.cls == 1 && half_empty(t, c, x, y, h, typeD, a, ap[i], b)) r.cls = 2;
        if (r.cls == 2) c->emp[idx] |= (uint8_t)(1u << (hv & 1));
        if (r.cls == 1 && r.vc) {
            /* mixed over the grid's own voids, three valid corners: drawn over them
             * when left unsplit, so its code bounds the valid samples' error and the
             * hole's extent ("Voids" above) */
            uint16_t e = code_max(bt_code_encode(r.err), void_extent(c, h, typeD));
            uint8_t l = bti_q_lo(c, r.zlo), u = bti_q_hi(c, r.zhi);
            c->emp[idx] |= (uint8_t)(4u << (hv & 1));
            if (e > code) code = e;
            if (l < lo) lo = l;
            if (u > hi) hi = u;
        } else if (r.cls == 1) {
            /* mixed with a void corner: never drawn.  Inside w x h with the exact
             * metric it may stay unsplit (dropped: the hole grows by at most its
             * extent, its code); over the padding, or with the curvature metric,
             * always split.  Its volume holds its valid corners and centre, the
             * heights of the valid leaves it ends in at h = 1 (no child diamond
             * holds them there): an empty range reads as all void and the view
             * modes would cull those leaves, notching an edge at an odd row or
             * column one sample in two */
            int32_t zv, k, mxx = a[0] > b[0] ? a[0] : b[0], myy = a[1] > b[1] ? a[1] : b[1];
            const int32_t px[4] = { a[0], b[0], ap[i][0], x }, py[4] = { a[1], b[1], ap[i][1], y };
            if (ap[i][0] > mxx) mxx = ap[i][0];
            if (ap[i][1] > myy) myy = ap[i][1];
            if (c->metric == BT_METRIC_EXACT && mxx < c->w && myy < c->h)
                code = code_max(code, void_extent(c, h, typeD));
            else code = BT_CODE_SPLIT;
            for (k = 0; k < 4; k++)
                if (samp(c, px[k], py[k], &zv)) {
                    uint8_t l = bti_q_lo(c, zv), u = bti_q_hi(c, zv);
                    if (l < lo) lo = l;
                    if (u > hi) hi = u;
                }
        } else if (r.cls == 0) {
            uint16_t e = bt_code_encode(r.err);
            uint8_t l = bti_q_lo(c, r.zlo), u = bti_q_hi(c, r.zhi);
            if (e > code) code = e;
            if (l < lo) lo = l;
            if (u > hi) hi = u;
        }
    }
    c->node[idx] = BT_NODE(code, lo, hi);
}

/* The diamonds of scale h and type typeD (bte_diamond) that have a slot in the
 * layout's bands (core/bitree.h LAYOUT): in the east columns of levels l with
 * 2^l <= h (their rows are multiples of 2^l, so every diamond of scale h on them
 * is one), then in the south rows; each once, as the padded loop would. */
void bte_pad(bt_tree *t, const bti_build_ctx *c, int32_t h, int typeD)
{
    const bt_layout *ly = &t->lay;
    int32_t S = t->n - 1, l, i, x, y, h2 = 2 * h;
    for (l = 0; l < BT_LAY_LEVELS && ((int32_t)1 << l) <= h; l++) {
        for (i = 0; i < ly->enc[l]; i++) {
            x = (ly->em0[l] + i) << l;
            if (x & (h - 1)) continue;   /* no diamond of scale h in this column */
            if (x & h) {           /* type A horizontal (rows 0 mod 2h) or type D (rows h mod 2h) */
                for (y = typeD ? h : 0; y <= S; y += h2)
                    if (!typeD || y < S) bte_diamond(t, c, x, y, h, typeD);
            } else if (!typeD && (x & (h2 - 1)) == 0)   /* type A vertical: rows h mod 2h */
                for (y = h; y < S; y += h2) bte_diamond(t, c, x, y, h, 0);
        }
        for (i = 0; i < ly->snc[l]; i++) {
            y = (ly->sm0[l] + i) << l;
            if (y & (h - 1)) continue;
            if (y & h) {           /* type A vertical (x 0 mod 2h) or type D (x h mod 2h) */
                for (x = typeD ? h : 0; x < t->w; x += h2)
                    if (!typeD || x < S) bte_diamond(t, c, x, y, h, typeD);
            } else if (!typeD && (y & (h2 - 1)) == 0)   /* type A horizontal: x h mod 2h */
                for (x = h; x < t->w && x < S; x += h2) bte_diamond(t, c, x, y, h, 0);
        }
    }
}
