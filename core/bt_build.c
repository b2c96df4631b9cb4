/* core/bt_build.c — bt_build and the sizes it needs (see core/bitree.h): the heightfield
 * prepared for the scans (biased heights, void counts and blocks, curvature), then the
 * error hierarchy level by level, finest first, through core/bt_lvl.c (the two finest
 * levels' stencils) and core/bt_err.c (one diamond at a time; the geometry of the
 * implicit tree and the exact metric are described there).
 *
 * A file of its own so that calls run one way: bt_build.c -> bt_lvl.c -> bt_err.c. */
#include <string.h>
#include "core/bitree.h"
#include "core/fx.h"
#include "core/bt_int.h"

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
    /* sanitised heights (int32), per-row void prefix counts (uint16, w+1 per row),
     * then per-diamond half bounds (exact metric: 2 x int32 per padded sample) or
     * curvature (int32 per sample), whichever is used, the empty-half bits (a byte
     * per padded sample), plus the row spans */
    size_t n = (size_t)(((int32_t)1 << padded_k(w, h)) + 1);
    return (size_t)w * (size_t)h * 4 + n * n * 9 + (size_t)(w + 1) * (size_t)h * 2 + 64 + 16 * BTI_TAB_MAX * 12
         + (size_t)(w / 16 + 1) * (size_t)(h / 16 + 1)
         + (size_t)(((int32_t)1 << padded_k(w, h)) + 1) * 12;
}

static int32_t kappa_at(const int32_t *z, int32_t w, int32_t h, int32_t x, int32_t y)
{
    /* doubled second differences over two steps (001, "Técnicas de
     * simplificación de modelos topográficos", section 2.2, eq. 2-3, dx = 1):
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
    bti_build_ctx c;
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
    if (((uintptr_t)mem & 3) != 0) return BR_E_ARG;
    nt.node = (uint32_t *)mem;
    nt.st = (uint8_t *)mem + nn * 4;
    memset(nt.st, 0, nn);
    /* every other node is written below; the 4 corners are never read, but are
     * zeroed so that the tree's bytes are a function of the input alone */
    nt.node[0] = nt.node[S] = nt.node[(size_t)S * n] = nt.node[(size_t)S * n + S] = 0;
    /* stats and void prefix counts, then heights biased by zmin (>= 0: shifts of
     * non-negative values only), voids = 0 */
    zs = (int32_t *)scratch;
    vp = (uint16_t *)((uint8_t *)scratch + (size_t)w * h * 4 + 32);
    memset((uint8_t *)scratch + (size_t)w * h * 4, 0, 32);   /* row32 reads up to 7 past the end */
    {
        int32_t lo = INT32_MAX, hi = INT32_MIN;
        for (y = 0; y < h; y++) {
            const int32_t *zr = f->z + (size_t)y * w;
            int64_t nv = 0;
            for (x = 0; x < w; x++) {
                int32_t v = zr[x];
                int isv = v == HF_NODATA;
                nv += isv;
                lo = !isv && v < lo ? v : lo;
                hi = !isv && v > hi ? v : hi;
            }
            voids += nv;
        }
        if (lo > hi) lo = hi = 0;          /* all void */
        /* hf.h's |z| <= BR_Z_LIMIT is what every bound below rests on (biased
         * heights 0 .. R <= 2^29, so za + zb - 2 zm and the like fit int32);
         * the loaders guarantee it, a caller's hf may not: refuse, don't overflow */
        if (lo < -(int32_t)BR_Z_LIMIT || hi > (int32_t)BR_Z_LIMIT) return BR_E_ARG;
        nt.zmin = lo; nt.zmax = hi;
        if (voids)                         /* per-row prefix counts of voids */
            for (y = 0; y < h; y++) {
                const int32_t *zr = f->z + (size_t)y * w;
                uint16_t *pr = vp + (size_t)y * (w + 1), cnt = 0;
                pr[0] = 0;
                for (x = 0; x < w; x++) { cnt = (uint16_t)(cnt + (zr[x] == HF_NODATA)); pr[x + 1] = cnt; }
            }
        for (y = 0; y < h; y++) {
            const int32_t *zr = f->z + (size_t)y * w;
            int32_t *sr = zs + (size_t)y * w;
            for (x = 0; x < w; x++) sr[x] = zr[x] == HF_NODATA ? 0 : zr[x] - nt.zmin;
        }
    }
    nt.nvalid = (int64_t)w * h - voids;
    c.w = w; c.h = h; c.n = n; c.z = zs; c.vp = voids ? vp : NULL; c.metric = metric;
    c.kap = NULL;
    /* int32 is enough when |N| <= 2 D R + 16 |A| < 2^31 with D <= S, |A| <= 2R */
    c.qr = (int64_t)nt.zmax - nt.zmin;
    c.qm = c.qr > 0 ? (255LL << 24) / c.qr : 0;
    c.narrow = (int64_t)(2 * (int64_t)S + 64) * ((int64_t)nt.zmax - nt.zmin) < ((int64_t)1 << 31);
    {
        uint8_t *q = (uint8_t *)vp + (size_t)(w + 1) * h * 2;
        q += (4 - ((uintptr_t)q & 3)) & 3;
        c.ry = (int32_t *)(void *)q;
        c.rx0 = c.ry + n;
        c.rx1 = c.rx0 + n;
        c.tab = c.rx1 + n;
        for (j = 0; j < 16; j++) c.tabn[j] = -1;
        q = (uint8_t *)(c.tab + 16 * BTI_TAB_MAX * 3);
        c.ub = metric == BT_METRIC_EXACT ? (int32_t *)(void *)q : NULL;
        c.vblk = NULL;
        c.bw = w / 16 + 1;
        c.emp = q + (size_t)n * n * 8;
        memset(c.emp, 0, nn);
        if (voids) {   /* void block map after the bounds / curvature and empty-half regions */
            uint8_t *vb = q + (size_t)n * n * 9;
            memset(vb, 0, (size_t)c.bw * (size_t)(h / 16 + 1));
            for (y = 0; y < h; y++)
                for (x = 0; x < w; x++)
                    if (f->z[(size_t)y * w + x] == HF_NODATA) vb[(size_t)(y >> 4) * c.bw + (x >> 4)] = 1;
            c.vblk = vb;
        }
        if (metric == BT_METRIC_CURVATURE) {
            int32_t *kap = (int32_t *)(void *)q;
            for (y = 0; y < h; y++)
                for (x = 0; x < w; x++)
                    kap[(size_t)y * w + x] = kappa_at(f->z, w, h, x, y);
            c.kap = kap;
        }
    }
    *t = nt;
    for (j = 0; j < nt.k; j++) {
        int32_t hh = (int32_t)1 << j;
        if (j == 0 && metric == BT_METRIC_EXACT && c.narrow) { bte_level1(t, &c); continue; }
        if (j == 1 && metric == BT_METRIC_EXACT && c.narrow) { bte_level2(t, &c); continue; }
        /* type A at h: horizontal edges (x odd multiple of h, y multiple of 2h) */
        for (y = 0; y <= S; y += 2 * hh)
            for (x = hh; x < S; x += 2 * hh) bte_diamond(t, &c, x, y, hh, 0);
        /* vertical edges */
        for (y = hh; y < S; y += 2 * hh)
            for (x = 0; x <= S; x += 2 * hh) bte_diamond(t, &c, x, y, hh, 0);
        /* type D at h */
        for (y = hh; y < S; y += 2 * hh)
            for (x = hh; x < S; x += 2 * hh) bte_diamond(t, &c, x, y, hh, 1);
    }
    return BR_OK;
}
