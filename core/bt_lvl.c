/* core/bt_lvl.c — the two finest levels of the bitree's exact error hierarchy
 * as stencils (bt_err.c does the rest; shared internals in core/bt_int.h).
 * They hold 3/4 and 3/16 of all triangles, so they run without the general
 * span walker: only the samples off each triangle's vertices, with the plane
 * written out in integers.  Results are bit for bit those of the general path
 * (tests/test_bitree.c checks a fixed hash of the output). */
#include <stddef.h>
#include "core/bitree.h"
#include "core/bt_int.h"

/* A node's error code is at least its children's (c0..c3: the 4 child diamonds'
 * nodes), and its volume [lo, hi] (quantised) holds theirs: both stencil levels
 * finish a node this way. */
static inline uint16_t err_with_children(uint16_t code, uint32_t c0, uint32_t c1, uint32_t c2, uint32_t c3)
{
    uint16_t e0 = BT_NODE_ERR(c0) > BT_NODE_ERR(c1) ? BT_NODE_ERR(c0) : BT_NODE_ERR(c1);
    uint16_t e1 = BT_NODE_ERR(c2) > BT_NODE_ERR(c3) ? BT_NODE_ERR(c2) : BT_NODE_ERR(c3);
    if (e0 > code) code = e0;
    if (e1 > code) code = e1;
    return code;
}

static inline uint32_t node_with_children(uint16_t code, int lo, int hi, uint32_t c0, uint32_t c1, uint32_t c2,
                                          uint32_t c3)
{
    int l0 = BT_NODE_ZLO(c0) < BT_NODE_ZLO(c1) ? BT_NODE_ZLO(c0) : BT_NODE_ZLO(c1);
    int l1 = BT_NODE_ZLO(c2) < BT_NODE_ZLO(c3) ? BT_NODE_ZLO(c2) : BT_NODE_ZLO(c3);
    int h0 = BT_NODE_ZHI(c0) > BT_NODE_ZHI(c1) ? BT_NODE_ZHI(c0) : BT_NODE_ZHI(c1);
    int h1 = BT_NODE_ZHI(c2) > BT_NODE_ZHI(c3) ? BT_NODE_ZHI(c2) : BT_NODE_ZHI(c3);
    if (l0 < lo) lo = l0;
    if (l1 < lo) lo = l1;
    if (h0 > hi) hi = h0;
    if (h1 > hi) hi = h1;
    return BT_NODE(code, lo, hi);
}

/* Interior A1 diamond (hypotenuse a-b of length 2 through m, apexes p and q):
 * only m is off the planes, so e = ceil(|za + zb - 2 zm| / 2) for both halves. */
static inline void a1_fast(bt_tree *t, const bti_build_ctx *c, size_t idx, int32_t za, int32_t zb, int32_t zm,
                    int32_t zp, int32_t zq)
{
    int32_t e = (bti_iabs32(za + zb - 2 * zm) + 1) >> 1;
    int32_t lo = za < zb ? za : zb, hi = za > zb ? za : zb;
    if (zp < lo) lo = zp;
    if (zp > hi) hi = zp;
    if (zq < lo) lo = zq;
    if (zq > hi) hi = zq;
    c->node[idx] = BT_NODE(bti_enc_small(e), bti_q_lo(c, (int64_t)lo - e), bti_q_hi(c, (int64_t)hi + e));
    (void)t;
    if (c->ub) c->ub[2 * idx] = c->ub[2 * idx + 1] = e;
}

/* exact error of the D1 half with apex (px, py) (both hypotenuse-end legs
 * hold one A1 child whose half towards (x, y) has its exact error in ub) */
static int32_t d1_half(const bti_build_ctx *c, int32_t w, int32_t x, int32_t y, int32_t px, int32_t py, int32_t ec)
{
    int32_t m1x = px, m1y = y, m2x = x, m2y = py, u1, u2;   /* legs are axis-parallel */
    u1 = c->ub[2 * ((size_t)m1y * w + m1x) + bti_half_of(m1x, m1y, x, y)];
    u2 = c->ub[2 * ((size_t)m2y * w + m2x) + bti_half_of(m2x, m2y, x, y)];
    if (u1 > ec) ec = u1;
    if (u2 > ec) ec = u2;
    return ec;
}

/* The finest level (h = 1) for grids without voids, as stencils: A1 diamonds
 * (one odd coordinate) and D1 diamonds (both odd), in the interior (slot y*w + x;
 * a diamond whose 3 x 3 box is valid has its children there too), then the
 * layout's bands through bte_pad.  A D1 triangle's samples
 * off its plane are the centre and its two leg midpoints, which are the D1
 * diamond's children (A1 centres, whose exact errors are those leg terms), so
 * E(D1) = max(ceil(|za + zb - 2 zm| / 2), children) is exact.  Diamonds on the
 * domain's edge go through the general path. */
void bte_level1(bt_tree *t, const bti_build_ctx *c)
{
    int32_t n = t->n, S = n - 1, w = c->w, x, y;
    int32_t xe = w - 1 < S ? w - 1 : S, ye = c->h - 1 < S ? c->h - 1 : S;
    const int32_t *z = c->z;
#define ZZ(X, Y) z[(size_t)(Y) * w + (X)]
    /* A1, horizontal hypotenuse: y even, x odd */
    for (y = 0; y <= ye; y += 2)
        for (x = 1; x < S && x <= xe; x += 2) {
            if (y >= 1 && y + 1 <= S && bti_box_clean(c, x - 1, y - 1, x + 1, y + 1))
                a1_fast(t, c, (size_t)y * w + x, ZZ(x - 1, y), ZZ(x + 1, y), ZZ(x, y), ZZ(x, y - 1), ZZ(x, y + 1));
            else bte_diamond(t, c, x, y, 1, 0);
        }
    /* A1, vertical hypotenuse: y odd, x even */
    for (y = 1; y < S && y <= ye; y += 2)
        for (x = 0; x <= xe; x += 2) {
            if (x >= 1 && x + 1 <= S && bti_box_clean(c, x - 1, y - 1, x + 1, y + 1))
                a1_fast(t, c, (size_t)y * w + x, ZZ(x, y - 1), ZZ(x, y + 1), ZZ(x, y), ZZ(x - 1, y), ZZ(x + 1, y));
            else bte_diamond(t, c, x, y, 1, 0);
        }
    bte_pad(t, c, 1, 0);
    /* D1: x, y odd; diagonal (1,1) when (x>>1) + (y>>1) is even.  The bti_box_clean
     * test reduces to x + 1 < w on rows inside h of grids without voids. */
    for (y = 1; y < S && y <= ye; y += 2) {
        int rowok = !c->vblk && y + 1 < c->h;
        for (x = 1; x < S && x <= xe; x += 2) {
            size_t idx = (size_t)y * w + x;
            if (rowok ? x + 1 < w : bti_box_clean(c, x - 1, y - 1, x + 1, y + 1)) {
                const int32_t *zc = z + (size_t)y * w + x;
                int32_t z00 = zc[-w - 1], z20 = zc[-w + 1], z02 = zc[w - 1], z22 = zc[w + 1];
                int32_t zm = zc[0], e, lo, hi;
                uint32_t c0 = c->node[idx - 1], c1 = c->node[idx + 1];
                uint32_t c2 = c->node[idx - (size_t)w], c3 = c->node[idx + (size_t)w];
                uint16_t code;
                int lq, hq;
                if ((((x >> 1) + (y >> 1)) & 1) == 0) {
                    e = (bti_iabs32(z00 + z22 - 2 * zm) + 1) >> 1;
                    if (c->ub) {   /* apexes (x+1, y-1): half 0, (x-1, y+1): half 1 */
                        c->ub[2 * idx] = d1_half(c, w, x, y, x + 1, y - 1, e);
                        c->ub[2 * idx + 1] = d1_half(c, w, x, y, x - 1, y + 1, e);
                    }
                } else {
                    e = (bti_iabs32(z20 + z02 - 2 * zm) + 1) >> 1;
                    if (c->ub) {   /* apexes (x-1, y-1): half 0, (x+1, y+1): half 1 */
                        c->ub[2 * idx] = d1_half(c, w, x, y, x - 1, y - 1, e);
                        c->ub[2 * idx + 1] = d1_half(c, w, x, y, x + 1, y + 1, e);
                    }
                }
                code = err_with_children(bti_enc_small(e), c0, c1, c2, c3);
                lo = z00 < z20 ? z00 : z20; hi = z00 > z20 ? z00 : z20;
                lo = z02 < lo ? z02 : lo; hi = z02 > hi ? z02 : hi;
                lo = z22 < lo ? z22 : lo; hi = z22 > hi ? z22 : hi;
                e = code < 4096 ? (int32_t)code : (int32_t)bt_code_value(code);
                lq = bti_q_lo(c, (int64_t)lo - e);
                hq = bti_q_hi(c, (int64_t)hi + e);
                c->node[idx] = node_with_children(code, lq, hq, c0, c1, c2, c3);
            } else bte_diamond(t, c, x, y, 1, 1);
        }
    }
    bte_pad(t, c, 1, 1);
#undef ZZ
}

/* Second level (h = 2) as stencils for diamonds whose 5 x 5 box is valid: the
 * exact error of each half from its samples off the vertices, with plane x 4
 * written out (A2: hypotenuse of length 4 and apex at distance 2; D2: axis legs
 * of length 4), then the usual maximum with the children.  Others: diamond(). */
static inline void level2_node(const bti_build_ctx *c, size_t idx, int32_t e0, int32_t e1, int32_t zl0,
                               int32_t zh0, int32_t zl1, int32_t zh1, size_t da, size_t db)
{
    /* children at idx -+ da, idx -+ db; bti_q_lo and bti_q_hi are monotone, so the
     * halves' volumes are merged before quantising (the same bytes) */
    uint32_t c0 = c->node[idx - da], c1 = c->node[idx + da], c2 = c->node[idx - db], c3 = c->node[idx + db];
    uint16_t code = bti_enc_small(e0), ce = bti_enc_small(e1);
    int64_t vl0 = (int64_t)zl0 - e0, vl1 = (int64_t)zl1 - e1, vh0 = (int64_t)zh0 + e0, vh1 = (int64_t)zh1 + e1;
    int lo = bti_q_lo(c, vl0 < vl1 ? vl0 : vl1), hi = bti_q_hi(c, vh0 > vh1 ? vh0 : vh1);
    if (ce > code) code = ce;
    c->node[idx] = node_with_children(err_with_children(code, c0, c1, c2, c3), lo, hi, c0, c1, c2, c3);
}

static int32_t max3i(int32_t a, int32_t b, int32_t c) { return a > b ? (a > c ? a : c) : (b > c ? b : c); }
static int32_t min3i(int32_t a, int32_t b, int32_t c) { return a < b ? (a < c ? a : c) : (b < c ? b : c); }

/* A2 half: hm = the largest |4 x plane - 4 z| over the three inner hypotenuse
 * samples, middle row through zr (samples x-1..x+1 of that row) */
static inline int32_t a2_half(int32_t za, int32_t zb, int32_t zc, int32_t hm, const int32_t *zr, ptrdiff_t st)
{
    int32_t m = hm, i;
    for (i = -1; i <= 1; i++) {
        int32_t v = za * (1 - i) + zb * (1 + i) + 2 * zc - 4 * zr[i * st];
        v = v < 0 ? -v : v;
        m = v > m ? v : m;
    }
    return (m + 3) >> 2;
}

void bte_level2(bt_tree *t, const bti_build_ctx *c)
{
    int32_t n = t->n, S = n - 1, w = c->w, x, y, j;
    int32_t xe = w - 1 < S ? w - 1 : S, ye = c->h - 1 < S ? c->h - 1 : S;
    const int32_t *z = c->z;
#define ZZ(X, Y) z[(size_t)(Y) * w + (X)]
    /* A2, horizontal (x = 2 mod 4, y = 0 mod 4) and vertical (transposed); the
     * bti_box_clean test reduces to x + 2 < w on rows inside h of grids without voids */
    for (j = 0; j < 2; j++)
        for (y = j ? 2 : 0; y <= ye; y += 4) {
            int rowok = !c->vblk && y + 2 < c->h;
            ptrdiff_t along = j ? (ptrdiff_t)w : 1, across = j ? 1 : (ptrdiff_t)w;
            for (x = j ? 0 : 2; x <= xe; x += 4) {
                size_t idx = (size_t)y * w + x;
                int32_t za, zb, zc0, zc1, hm = 0, e0, e1, k;
                const int32_t *zm;
                if ((j == 0 && (x >= S || y - 2 < 0 || y + 2 > S)) || (j == 1 && (y >= S || x - 2 < 0 || x + 2 > S)) ||
                    !(rowok ? x + 2 < w : bti_box_clean(c, x - 2, y - 2, x + 2, y + 2))) {
                    if ((j == 0 && x < S) || (j == 1 && y < S)) bte_diamond(t, c, x, y, 2, 0);
                    continue;
                }
                zm = z + (size_t)y * w + x;
                za = zm[-2 * along]; zb = zm[2 * along];
                for (k = -1; k <= 1; k++) {
                    int32_t v = za * (2 - k) + zb * (2 + k) - 4 * zm[k * along];
                    v = v < 0 ? -v : v;
                    hm = v > hm ? v : hm;
                }
                /* apex at -2 (half 0) and +2 (half 1) across */
                zc0 = zm[-2 * across]; zc1 = zm[2 * across];
                e0 = a2_half(za, zb, zc0, hm, zm - across, along);
                e1 = a2_half(za, zb, zc1, hm, zm + across, along);
                if (c->ub) { c->ub[2 * idx] = e0; c->ub[2 * idx + 1] = e1; }
                level2_node(c, idx, e0, e1, min3i(za, zb, zc0), max3i(za, zb, zc0), min3i(za, zb, zc1),
                            max3i(za, zb, zc1), (size_t)w + 1, (size_t)w - 1);
            }
        }
    bte_pad(t, c, 2, 0);
    /* D2: x, y = 2 mod 4; diagonal (1,1) when ((x ^ y) & 4) == 0 */
    for (y = 2; y < S && y <= ye; y += 4)
        for (x = 2; x < S && x <= xe; x += 4) {
            size_t idx = (size_t)y * w + x;
            int32_t e[2], zl[2], zh[2], hh;
            if (!(!c->vblk && y + 2 < c->h ? x + 2 < w : bti_box_clean(c, x - 2, y - 2, x + 2, y + 2))) {
                bte_diamond(t, c, x, y, 2, 1);
                continue;
            }
            for (hh = 0; hh < 2; hh++) {
                /* apex of half hh: (x+2, y-2) / (x-2, y+2) on diagonal (1,1), else
                 * (x-2, y-2) / (x+2, y+2); legs of 4 along the row and the column */
                int32_t cx, cy, m = 0, zc, zr, zcol, p0, dr, dcl;
                ptrdiff_t ox, oy;
                const int32_t *zp;
                if (((x ^ y) & 4) == 0) { cx = hh ? x - 2 : x + 2; cy = hh ? y + 2 : y - 2; }
                else { cx = hh ? x + 2 : x - 2; cy = hh ? y + 2 : y - 2; }
                ox = cx < x ? 1 : -1; oy = cy < y ? (ptrdiff_t)w : -(ptrdiff_t)w;   /* towards the square */
                zp = &ZZ(cx, cy);
                zc = zp[0]; zr = zp[4 * ox]; zcol = zp[4 * oy];
                p0 = 4 * zc; dr = zr - zc; dcl = zcol - zc;
                /* the 12 samples (ii, jj), ii + jj <= 4, off the vertices, written out */
#define D2S(I, J) do { int32_t v = p0 + (I) * dr + (J) * dcl - 4 * zp[(I) * ox + (J) * oy]; \
                       v = v < 0 ? -v : v; m = v > m ? v : m; } while (0)
                D2S(1, 0); D2S(2, 0); D2S(3, 0);
                D2S(0, 1); D2S(1, 1); D2S(2, 1); D2S(3, 1);
                D2S(0, 2); D2S(1, 2); D2S(2, 2);
                D2S(0, 3); D2S(1, 3);
#undef D2S
                e[hh] = (m + 3) >> 2;
                zl[hh] = min3i(zc, zr, zcol); zh[hh] = max3i(zc, zr, zcol);
                if (c->ub) c->ub[2 * idx + (size_t)hh] = e[hh];
            }
            level2_node(c, idx, e[0], e[1], zl[0], zh[0], zl[1], zh[1], 2, 2 * (size_t)w);
        }
    bte_pad(t, c, 2, 1);
#undef ZZ
}

