/* core/bt_util.c — helpers around the bitree (core/bitree.h): error codes and
 * units, a world frame for the camera, the strip decoded into a list without
 * line triangles (004's collinearity test), and the true error of a mesh. */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"

/* ------------------------------------------------------------ layout
 * (core/bitree.h LAYOUT).  A padding diamond at distance need = x - w >= 0 east
 * of the data (or y - h south of it) has a slot iff its scale h >= p(need), the
 * least power of two with 3p - 3 >= need: its value is VOID below that (the reach
 * of a diamond of scale h and its descendants is 3h - 1 samples, and a unit
 * triangle of valid samples needs two columns inside w).  With h = the lowest set
 * bit of x | y, h >= p iff p divides x and y.  The columns of level l are those
 * with need in [3p/2 - 2, 3p - 3] (need 0 for l = 0): at most 2 per level. */
static int32_t need_level(int32_t need)
{
    uint32_t q = (uint32_t)(need + 5) / 3u - 1u;   /* ceil((need + 3) / 3) - 1: l = its bit length */
    int32_t l = 0;
    if (q >> 16) { q >>= 16; l = 16; }
    if (q >> 8) { q >>= 8; l += 8; }
    if (q >> 4) { q >>= 4; l += 4; }
    if (q >> 2) { q >>= 2; l += 2; }
    if (q >> 1) { q >>= 1; l += 1; }
    return l + (int32_t)q;
}

static void band(int32_t edge, int32_t S, int32_t l, int32_t *m0, int32_t *nc)
{
    int32_t p = (int32_t)1 << l, lo = l ? 3 * (p >> 1) - 2 : 0, hi = 3 * p - 3;
    int64_t a = (int64_t)edge + lo, b = (int64_t)edge + hi;
    if (b > S) b = S;
    a = (a + p - 1) >> l;
    b = b >> l;
    *m0 = (int32_t)a;
    *nc = b >= a ? (int32_t)(b - a + 1) : 0;
}

void bti_layout(bt_layout *ly, int32_t w, int32_t h, int32_t n, uint32_t *nslot)
{
    int32_t S = n - 1, l;
    uint64_t s = (uint64_t)w * (uint64_t)h;
    memset(ly, 0, sizeof *ly);
    for (l = 0; l < BT_LAY_LEVELS && ((int32_t)1 << l) <= S; l++) {
        ly->east[l] = (uint32_t)s;
        band(w, S, l, &ly->em0[l], &ly->enc[l]);
        s += (uint64_t)ly->enc[l] * (uint64_t)((S >> l) + 1);
    }
    for (l = 0; l < BT_LAY_LEVELS && ((int32_t)1 << l) <= S; l++) {
        ly->south[l] = (uint32_t)s;
        band(h, S, l, &ly->sm0[l], &ly->snc[l]);
        s += (uint64_t)ly->snc[l] * (uint64_t)(((w - 1) >> l) + 1);
    }
    *nslot = (uint32_t)(s + 1);
    for (l = 0; l < BT_LAY_NEAR; l++) {
        int32_t lv = need_level(l), i;
        ly->lnear[l] = (uint8_t)lv;
        ly->enear[l] = ly->snear[l] = -1;
        if ((w + l) % ((int32_t)1 << lv) == 0 && (i = ((w + l) >> lv) - ly->em0[lv]) >= 0 && i < ly->enc[lv])
            ly->enear[l] = (int32_t)(ly->east[lv] + (uint32_t)i * (uint32_t)((S >> lv) + 1));
        if ((h + l) % ((int32_t)1 << lv) == 0 && (i = ((h + l) >> lv) - ly->sm0[lv]) >= 0 && i < ly->snc[lv])
            ly->snear[l] = (int32_t)(ly->south[lv] + (uint32_t)i * (uint32_t)(((w - 1) >> lv) + 1));
    }
}

/* One band of padding: `need` steps beyond the data across it, position `along` it,
 * (x | y) for the level's alignment; the band's near slots and its per-level first
 * slots, first index, count and row length (the east band's columns run along the
 * padded side n, the south band's rows along w). */
static inline uint32_t band_slot(const bt_tree *t, int32_t need, int32_t along, int32_t xy,
                                 const int32_t *nearv, const uint32_t *base, const int32_t *m0,
                                 const int32_t *nc, int32_t side, int32_t across)
{
    const bt_layout *ly = &t->lay;
    int32_t l, i;
    if (need < BT_LAY_NEAR) {
        l = ly->lnear[need];
        if (nearv[need] < 0 || (along & (((int32_t)1 << l) - 1)) != 0) return t->nslot - 1;
        return (uint32_t)nearv[need] + (uint32_t)(along >> l);
    }
    l = need_level(need);
    if ((xy & (((int32_t)1 << l) - 1)) != 0) return t->nslot - 1;
    i = (across >> l) - m0[l];
    if (i < 0 || i >= nc[l]) return t->nslot - 1;
    return base[l] + (uint32_t)i * (uint32_t)(((side - 1) >> l) + 1) + (uint32_t)(along >> l);
}

/* The walk's padding diamonds are mostly within BT_LAY_NEAR of the data: those
 * columns and rows have their level and first slot in the layout (bti_layout);
 * farther ones compute them. */
uint32_t bti_slot_pad(const bt_tree *t, int32_t x, int32_t y)
{
    const bt_layout *ly = &t->lay;
    if (x >= t->w)
        return band_slot(t, x - t->w, y, x | y, ly->enear, ly->east, ly->em0, ly->enc, t->n, x);
    return band_slot(t, y - t->h, x, x | y, ly->snear, ly->south, ly->sm0, ly->snc, t->w, y);
}

uint32_t bt_node_at(const bt_tree *t, int32_t x, int32_t y)
{
    if (!t || !t->node || x < 0 || y < 0 || x >= t->n || y >= t->n) return BT_NODE_VOID;
    return t->node[bti_slot(t, x, y)];
}

/* Error codes: exact below 4096, then a 12-bit mantissa and an exponent,
 * always rounded up so that a bound stays a bound. */
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


br_status bt_frame_auto(const hf *f, bt_frame *fr, int32_t *unit_shift)
{
    int32_t u;
    if (!f || !fr || hf_validate(f) != BR_OK) return BR_E_ARG;
    for (u = 10; u >= -6; u--) {
        /* extents in world units: w*dx, h*dy (um -> 2^-u m), |z| <= BR_Z_LIMIT units */
        int64_t ex = u >= 0 ? ((int64_t)f->w * f->dx_um << u) / 1000000 : ((int64_t)f->w * f->dx_um >> -u) / 1000000;
        int64_t ey = u >= 0 ? ((int64_t)f->h * f->dy_um << u) / 1000000 : ((int64_t)f->h * f->dy_um >> -u) / 1000000;
        int64_t sx = u >= 0 ? (((int64_t)f->dx_um << u) + 500000) / 1000000 : 0;
        int64_t sy = u >= 0 ? (((int64_t)f->dy_um << u) + 500000) / 1000000 : 0;
        /* heights: metres = z * num / den; the loaders keep |z| * num / den under 2^16 m
         * for real terrain, so 2^16 m * 2^u must stay below 2^29 */
        int64_t ez = u >= 0 ? (int64_t)11000 << u : 11000 >> -u;
        if (ex < ((int64_t)1 << 29) && ey < ((int64_t)1 << 29) && ez < ((int64_t)1 << 29) && sx > 0 && sy > 0) {
            fr->sx = (int32_t)sx;
            fr->sy = (int32_t)sy;
            fr->ox = 0;
            fr->oy = (int32_t)((int64_t)(f->h - 1) * sy);
            fr->oz = 0;
            /* world z = z * num / den * 2^u, as Q16 */
            fr->sz_q16 = (int32_t)((((int64_t)f->z_num << (u + 16)) + f->z_den / 2) / f->z_den);
            if (fr->sz_q16 <= 0) continue;
            if (unit_shift) *unit_shift = u;
            return BR_OK;
        }
    }
    return BR_E_TOO_BIG;
}

uint32_t bt_strip_to_list(const bt_mesh *m, uint32_t *out)
{
    uint32_t k, n = 0;
    if (m->ns < 3) return 0;
    for (k = 0; k + 2 < m->ns; k++) {
        uint32_t i0 = m->strip[k], i1 = m->strip[k + 1], i2 = m->strip[k + 2];
        if (k & 1) { uint32_t tmp = i0; i0 = i1; i1 = tmp; }
        if (bti_cross(&m->v[i0], &m->v[i1], &m->v[i2]) == 0) continue;   /* line triangle */
        out[3 * n] = i0; out[3 * n + 1] = i1; out[3 * n + 2] = i2;
        n++;
    }
    return n;
}

/* ceil(num * 65536 / den), num >= 0, den > 0, without overflow for num < 2^62 */
static int64_t q16_ceil(int64_t num, int64_t den)
{
    int64_t q = num / den, r = num % den;
    return q * 65536 + (r * 65536 + den - 1) / den;
}

int64_t bt_true_error_q16(const bt_tree *t, const bt_mesh *m, int32_t *at_x, int32_t *at_y)
{
    const hf *f = t->f;
    int64_t best = 0;
    uint32_t k;
    int32_t bx = 0, by = 0;
    for (k = 0; k + 2 < m->ns; k++) {
        const bt_vert *p0 = &m->v[m->strip[k]], *p1 = &m->v[m->strip[k + 1]], *p2 = &m->v[m->strip[k + 2]];
        int64_t D = bti_cross(p0, p1, p2), ad;
        int32_t x0, x1, y0, y1, x, y;
        if (D == 0) continue;
        ad = D < 0 ? -D : D;
        x0 = p0->x; if (p1->x < x0) x0 = p1->x; if (p2->x < x0) x0 = p2->x;
        x1 = p0->x; if (p1->x > x1) x1 = p1->x; if (p2->x > x1) x1 = p2->x;
        y0 = p0->y; if (p1->y < y0) y0 = p1->y; if (p2->y < y0) y0 = p2->y;
        y1 = p0->y; if (p1->y > y1) y1 = p1->y; if (p2->y > y1) y1 = p2->y;
        for (y = y0; y <= y1; y++)
            for (x = x0; x <= x1; x++) {
                /* barycentric weights times D: b0 for p0 etc., all >= 0 (D > 0) or <= 0 */
                int64_t b0 = (int64_t)(p1->x - x) * (p2->y - y) - (int64_t)(p1->y - y) * (p2->x - x);
                int64_t b1 = (int64_t)(p2->x - x) * (p0->y - y) - (int64_t)(p2->y - y) * (p0->x - x);
                int64_t b2 = D - b0 - b1, num, e;
                int32_t zs;
                if (D > 0 ? (b0 < 0 || b1 < 0 || b2 < 0) : (b0 > 0 || b1 > 0 || b2 > 0)) continue;
                zs = f->z[(size_t)y * f->w + x];
                if (zs == HF_NODATA) continue;
                num = b0 * p0->z + b1 * p1->z + b2 * p2->z - D * (int64_t)zs;
                if (num < 0) num = -num;
                e = q16_ceil(num, ad);
                if (e > best) { best = e; bx = x; by = y; }
            }
    }
    if (at_x) *at_x = bx;
    if (at_y) *at_y = by;
    return best;
}
