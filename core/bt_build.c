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

uint32_t bt_slot_count(int32_t w, int32_t h)
{
    bt_layout ly;
    uint32_t ns;
    if (hf_check_dims(w, h) != BR_OK || w < 2 || h < 2) return 0;
    bti_layout(&ly, w, h, ((int32_t)1 << padded_k(w, h)) + 1, &ns);
    return ns;
}

size_t bt_state_size(uint32_t nslot)
{
    return bti_plane_bytes(nslot) * ST_PLANES;
}

size_t bt_mem_size(int32_t w, int32_t h)
{
    const uint32_t ns = bt_slot_count(w, h);
    return ns ? (size_t)ns * 4 + bt_state_size(ns) : 0;
}

/* the region shared by the exact metric's half bounds (2 x int32 per slot) and the
 * curvature (int32 per sample), whichever is used */
static size_t ub_bytes(int32_t w, int32_t h, uint32_t ns)
{
    size_t a = (size_t)ns * 8, b = (size_t)w * (size_t)h * 4;
    return a > b ? a : b;
}

size_t bt_scratch_size(int32_t w, int32_t h)
{
    uint32_t ns = bt_slot_count(w, h);
    if (!ns) return 0;
    /* sanitised heights (int32), per-row void prefix counts (uint16, w+1 per row),
     * the row spans (3 x int32 per padded row) and sample tables, the half bounds or
     * curvature, the empty-half bits (a byte per slot), the void block map */
    return (size_t)w * (size_t)h * 4 + 32 + (size_t)(w + 1) * (size_t)h * 2 + 4
         + (size_t)(((int32_t)1 << padded_k(w, h)) + 1) * 12 + 16 * BTI_TAB_MAX * 12
         + ub_bytes(w, h, ns) + ns + (size_t)(w / 16 + 1) * (size_t)(h / 16 + 1);
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
    uint32_t ns, *node;
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
    nt.w = w; nt.h = h;
    bti_layout(&nt.lay, w, h, n, &nt.nslot);
    ns = nt.nslot;
    if (((uintptr_t)mem & 3) != 0) return BR_E_ARG;
    node = (uint32_t *)mem;
    nt.node = node;
    nt.st = (uint8_t *)mem + (size_t)ns * 4;
    memset(nt.st, 0, bt_state_size(ns));
    /* every diamond's slot is written below; the corners (never read) are 0 so that
     * the tree's bytes are a function of the input alone; the void slot is VOID */
    memset(node, 0, (size_t)ns * 4);
    node[ns - 1] = BT_NODE_VOID;
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
    c.node = node;
    c.kap = NULL;
    bte_extent_init(&c, f);
    /* int32 is enough when |N| <= 2 D R + 16 |A| < 2^31 with D <= S, |A| <= 2R */
    c.qr = (int64_t)nt.zmax - nt.zmin;
    c.qm = c.qr > 0 ? (255LL << 24) / c.qr : 0;
    c.narrow = (int64_t)(2 * (int64_t)S + 64) * ((int64_t)nt.zmax - nt.zmin) < ((int64_t)1 << 31);
    {
        uint8_t *q = (uint8_t *)vp + (size_t)(w + 1) * h * 2;
        size_t ubb = (size_t)ns * 8 > (size_t)w * h * 4 ? (size_t)ns * 8 : (size_t)w * h * 4;
        q += (4 - ((uintptr_t)q & 3)) & 3;
        c.ry = (int32_t *)(void *)q;
        c.rx0 = c.ry + n;
        c.rx1 = c.rx0 + n;
        c.tab = c.rx1 + n;
        for (j = 0; j < 16; j++) c.tabn[j] = -1;
        q = (uint8_t *)(c.tab + 16 * BTI_TAB_MAX * 3);
        c.ub = metric == BT_METRIC_EXACT ? (int32_t *)(void *)q : NULL;
        if (c.ub) c.ub[2 * (size_t)(ns - 1)] = c.ub[2 * (size_t)(ns - 1) + 1] = BTI_UB_INF;   /* the void slot */
        c.vblk = NULL;
        c.bw = w / 16 + 1;
        c.emp = q + ubb;
        memset(c.emp, 0, ns);
        c.emp[ns - 1] = 3;       /* the void slot: both halves empty */
        if (voids) {   /* void block map after the bounds / curvature and empty-half regions */
            uint8_t *vb = c.emp + ns;
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
        int32_t hh = (int32_t)1 << j, xe = w - 1 < S ? w - 1 : S, ye = h - 1 < S ? h - 1 : S;
        if (j == 0 && metric == BT_METRIC_EXACT && c.narrow) { bte_level1(t, &c); continue; }
        if (j == 1 && metric == BT_METRIC_EXACT && c.narrow) { bte_level2(t, &c); continue; }
        /* the interior's diamonds of scale hh, then the bands' (bte_pad): type A
         * (horizontal edges: x odd multiple of hh, y multiple of 2hh; vertical
         * edges), then type D, whose children are the type A diamonds */
        for (y = 0; y <= ye; y += 2 * hh)
            for (x = hh; x < S && x <= xe; x += 2 * hh) bte_diamond(t, &c, x, y, hh, 0);
        for (y = hh; y < S && y <= ye; y += 2 * hh)
            for (x = 0; x <= xe; x += 2 * hh) bte_diamond(t, &c, x, y, hh, 0);
        bte_pad(t, &c, hh, 0);
        for (y = hh; y < S && y <= ye; y += 2 * hh)
            for (x = hh; x < S && x <= xe; x += 2 * hh) bte_diamond(t, &c, x, y, hh, 1);
        bte_pad(t, &c, hh, 1);
    }
    t->sum = bti_node_sum(t->node, t->nslot);
    return BR_OK;
}
