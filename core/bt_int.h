/* core/bt_int.h — internals shared by the bitree's files (error hierarchy:
 * core/bt_err.c, core/bt_lvl.c; strip: core/bt_mesh.c, core/bt_strip.c; the frame
 * state's layout); not part of the public contract (bitree.h). */
#ifndef BR_BT_INT_H
#define BR_BT_INT_H
#include <stddef.h>
#include <stdint.h>
#include "core/bitree.h"
#include "core/fx.h"

/* The frame state (bt_tree.st, bt_state_size bytes): one bit per slot in each of
 * two planes of (nslot + 7) / 8 bytes, slot i at byte i >> 3, bit i & 7.  ST_PREV:
 * split in the previous view frame (hysteresis); ST_MARK: split by the budget rule
 * (core/bt_budget.c, which also uses it for "pushed" while its heap runs).  Only
 * serial code writes a plane (the walks read ST_PREV only; the end of an extraction
 * sets it from the listed splits), so sharing a byte between eight slots races with
 * nothing. */
enum { ST_PREV = 0, ST_MARK = 1, ST_PLANES = 2 };

/* Bytes of one plane for a tree of nslot slots */
static inline size_t bti_plane_bytes(uint32_t nslot)
{
    return ((size_t)nslot + 7) >> 3;
}

static inline uint8_t *bti_st(const bt_tree *t, int plane)
{
    return t->st + bti_plane_bytes(t->nslot) * (size_t)plane;
}

static inline int bti_bit(const uint8_t *plane, uint32_t i)
{
    return (plane[i >> 3] >> (i & 7u)) & 1;
}

static inline void bti_bit_set(uint8_t *plane, uint32_t i)
{
    plane[i >> 3] = (uint8_t)(plane[i >> 3] | (1u << (i & 7u)));
}

static inline void bti_bit_clear(uint8_t *plane, uint32_t i)
{
    plane[i >> 3] = (uint8_t)(plane[i >> 3] & ~(1u << (i & 7u)));
}

/* Clears slot i's bit and its seven neighbours': for a plane whose set bits are all
 * listed (ST_PREV: the previous frame's split list; ST_MARK: the budget rule's
 * ids), clearing every listed slot this way clears the plane, in one store a
 * slot. */
static inline void bti_byte_clear(uint8_t *plane, uint32_t i)
{
    plane[i >> 3] = 0;
}

#define BTI_TAB_MAX 48   /* samples per small-level table (D4: 45 - 3 vertices) */

/* The build context: the heightfield prepared for the scans (biased heights,
 * void bookkeeping), scratch rows and tables, and the per-half bounds. */
typedef struct bti_build_ctx {
    int32_t w, h, n;
    uint32_t *node;        /* the tree's node array, written by the build only */
    const int32_t *z;      /* sanitised heights, w*h (voids = 0) */
    const uint16_t *vp;    /* void prefix counts, (w+1)*h, or NULL if no voids */
    const int32_t *kap;    /* curvature per sample (curvature metric), else NULL */
    int32_t metric;
    int32_t narrow;        /* 1: the exact metric fits int32 (see bt_build) */
    int32_t *ry, *rx0, *rx1; /* row spans of the triangle being evaluated (n each) */
    int64_t qr, qm;        /* height quantisation: range R and floor(255 * 2^24 / R) */
    /* sample tables of the small levels (h = 2, 4): per shape (8 apex
     * directions x 2 sizes) the samples off the vertices as (offset, dx, dy)
     * from the apex; used for triangles inside the domain of void-free grids */
    int32_t *tab;          /* 16 tables of BTI_TAB_MAX entries x 3 */
    int32_t *ub;           /* 2 per slot: upper bound of each half's error (exact metric) */
    const uint8_t *vblk;   /* per 16 x 16 block of the domain: 1 if it holds a void (NULL: none) */
    int32_t bw;            /* blocks per row */
    uint8_t *emp;          /* per slot, bit (1 << half): that half is EMPTY, bit
                              (4 << half): it is MIXED over the grid's own voids with
                              three valid corners (see bt_err.c "Voids") */
    int64_t step_um[2];    /* the longer of a grid step along x and along y, and the
                              diagonal step (rounded up), micrometres (bt_err.c
                              void_extent) */
    int64_t ext_den;       /* z_num * 10^6 (micrometres to heightfield units, times
                              z_den) */
    int32_t ext_zden;      /* z_den */
    int32_t tabn[16];
} bti_build_ctx;

#define BTI_UB_INF INT32_MAX

/* Slot of a padding diamond (x >= w or y >= h; core/bt_util.c), the void slot
 * (t->nslot - 1) when it has none; and the layout's bands for a w x h grid in a
 * padded side n (*nslot: all slots). */
uint32_t bti_slot_pad(const bt_tree *t, int32_t x, int32_t y);
void bti_layout(bt_layout *l, int32_t w, int32_t h, int32_t n, uint32_t *nslot);

/* Slot of diamond (x, y), 0 <= x, y < n (see bitree.h LAYOUT) */
static inline uint32_t bti_slot(const bt_tree *t, int32_t x, int32_t y)
{
    if (x < t->w && y < t->h) return (uint32_t)y * (uint32_t)t->w + (uint32_t)x;
    return bti_slot_pad(t, x, y);
}

static inline int32_t bti_iabs32(int32_t v) { return v < 0 ? -v : v; }

/* The largest of five linear forms of a, b whose coefficient pairs, Q12 and rounded
 * down, are unit vectors at 0, 22.5, 45, 67.5 and 90 degrees or shorter: a lower bound
 * of sqrt(a^2 + b^2) (Cauchy-Schwarz) within cos(11.25 deg) = 0.981 of it, and
 * 1-Lipschitz in |da| + |db| (no coefficient exceeds 1; the floor of a real that moves
 * by at most an integer k moves by at most k).  3784^2 + 1567^2 and 2 * 2896^2 are
 * below 4096^2.  32 x 32 -> 64-bit products (one instruction on 32-bit ARM); each
 * form is below 2^32 (a, b < 2^31.5: at most sqrt(a^2 + b^2) < 2^32), so it is kept in
 * 32 bits.  Only three forms can be the largest: with h = max(a, b), l = min(a, b),
 * the 22.5-degree form that weights h more is at least the one that weights l more
 * ((3784 - 1567)(h - l) >= 0, and the floor keeps the order), and 0 or 90 degrees is h. */
static inline uint32_t bti_norm2_lo(uint32_t a, uint32_t b)
{
    const uint32_t h = a > b ? a : b, l = a > b ? b : a;
    uint32_t n = h, v;
    v = (uint32_t)(((uint64_t)h * 3784u + (uint64_t)l * 1567u) >> 12); if (v > n) n = v;
#if BR_REG64
    v = (uint32_t)((((uint64_t)h + l) * 2896u) >> 12);
#else
    {
        /* the 45-degree form (h + l) 2896 / 2^12 from the 32-bit sum s = h + l: a carry
         * out of it (h + l = s + 2^32) adds 2896 2^20 to the quotient exactly (a multiple
         * of 2^12 taken out of the floor), and the form is below 2^32; one 32 x 32 -> 64
         * product (GCC makes the 64-bit sum times 2896 a chain of shifts and adds there) */
        const uint32_t s = h + l;
        v = (uint32_t)(((uint64_t)s * 2896u) >> 12) + (s < h ? 2896u << 20 : 0u);
    }
#endif
    if (v > n) n = v;
    return n;
}

/* The view rule's distance (core/bt_mesh.c): a lower bound of the distance from the eye
 * to the box [lo, hi] (world units), the per-axis distances' horizontal norm, then its
 * norm with the vertical distance, each by bti_norm2_lo: at least 0.962 of the
 * Euclidean distance (0.981^2), never more, and 1-Lipschitz in the eye's L1 move (each
 * per-axis distance moves by at most its coordinate's move; core/bt_coh.c (1)).  Each
 * per-axis distance is below 2^31 (eye and box within CAM_COORD_MAX, checked by
 * bti_setup), the horizontal norm below 2^31.5.  tests/test_coherence.c checks all
 * three. */
static inline int64_t bti_box_dist(const int32_t eye[3], const int32_t lo[3], const int32_t hi[3])
{
    uint32_t d[3];
    int i;
    for (i = 0; i < 3; i++) {
        const int32_t e = eye[i];
        d[i] = e < lo[i] ? (uint32_t)lo[i] - (uint32_t)e : (e > hi[i] ? (uint32_t)e - (uint32_t)hi[i] : 0u);
    }
    return bti_norm2_lo(bti_norm2_lo(d[0], d[1]), d[2]);
}

/* Doubled signed area of grid vertices (a, b, c) in grid coordinates: < 0 when they
 * run counter-clockwise seen from +z (grid rows run south, so the sign is flipped),
 * 0 when collinear. */
static inline int64_t bti_cross(const bt_vert *a, const bt_vert *b, const bt_vert *c)
{
    return (int64_t)(b->x - a->x) * (c->y - a->y) - (int64_t)(b->y - a->y) * (c->x - a->x);
}

/* 1 when distinct grid-collinear vertices (bti_cross == 0) are collinear in (x, y, z)
 * too, so the triangle they make is empty in the world frame as well: a line
 * triangle whose heights are not on one line is a vertical sliver that the
 * rasteriser draws.  |dz| < 2^29 (BR_Z_LIMIT) and |dx|, |dy| < 2^15 keep the products
 * below 2^44. */
static inline int bti_flat(const bt_vert *a, const bt_vert *b, const bt_vert *c)
{
    int64_t dz1 = (int64_t)b->z - a->z, dz2 = (int64_t)c->z - a->z;
    return dz1 * (c->x - a->x) == dz2 * (b->x - a->x) && dz1 * (c->y - a->y) == dz2 * (b->y - a->y);
}

/* 1 when the box [x0, x1] x [y0, y1] (x0, y0 >= 0) lies inside w x h and touches
 * no 16 x 16 block that holds a void: every sample in it is valid */
static inline int bti_box_clean(const bti_build_ctx *c, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    int32_t bx, by;
    if (x1 >= c->w || y1 >= c->h) return 0;
    if (!c->vblk) return 1;
    for (by = y0 >> 4; by <= y1 >> 4; by++)
        for (bx = x0 >> 4; bx <= x1 >> 4; bx++)
            if (c->vblk[(size_t)by * c->bw + bx]) return 0;
    return 1;
}

/* which half of diamond (cx, cy) has its apex at (px, py): 1 = below / right */
static inline size_t bti_half_of(int32_t cx, int32_t cy, int32_t px, int32_t py)
{
    return (py > cy) || (py == cy && px > cx);
}

/* quantise a biased height (0 .. R = zmax - zmin) to 8 bits, rounding down (lo)
 * or up (hi), by a multiply: qm = floor(255 * 2^24 / R), so the estimate is at
 * most 1 below the exact floor (lo, conservative) and hi adds 1 (>= the ceiling). */
static inline uint8_t bti_q_lo(const bti_build_ctx *c, int64_t z)
{
    if (z <= 0 || c->qr <= 0) return 0;
    if (z >= c->qr) return 255;
    return (uint8_t)((z * c->qm) >> 24);
}
static inline uint8_t bti_q_hi(const bti_build_ctx *c, int64_t z)
{
    int64_t q;
    if (c->qr <= 0) return 255;
    if (z <= 0) return 0;
    if (z >= c->qr) return 255;
    q = ((z * c->qm) >> 24) + 1;
    return (uint8_t)(q > 255 ? 255 : q);
}

static inline uint16_t bti_enc_small(int64_t e) { return e < 4096 ? (uint16_t)e : bt_code_encode(e); }

/* a * b for a, b >= 0, INT64_MAX when it is larger (no divide: the high half of
 * the 64 x 64 product from 32-bit halves) */
static inline int64_t bti_isat_mul(int64_t a, int64_t b)
{
    uint64_t ua = (uint64_t)a, ub = (uint64_t)b, a1 = ua >> 32, b1 = ub >> 32, mid, lo, r;
    if ((ua | ub) < ((uint64_t)1 << 31)) return a * b;
    if (a1 && b1) return INT64_MAX;
    mid = a1 * (ub & 0xffffffffu) + b1 * (ua & 0xffffffffu);   /* one term is 0: < 2^63 */
    if (mid >> 31) return INT64_MAX;
    lo = (ua & 0xffffffffu) * (ub & 0xffffffffu);
    r = (mid << 32) + lo;
    return r < lo || r > (uint64_t)INT64_MAX ? INT64_MAX : (int64_t)r;
}

/* FNV-1a over the node words (bt_tree.sum) */
static inline uint64_t bti_node_sum(const uint32_t *node, uint32_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    uint32_t i;
    for (i = 0; i < n; i++) h = (h ^ node[i]) * 0x100000001b3ull;
    return h;
}

/* The bit length of v: 0 for 0, else 1 + the index of its highest set bit (1 .. 64) */
static inline int bti_bits(uint64_t v)
{
    int b = 0;
    if (v >> 32) { b = 32; v >>= 32; }
    return v ? b + 32 - fx_clz32((uint32_t)v) : b;
}

/* The geomorph weight of a split vertex (core/bt_mesh.c morph_of) for rho =
 * floor(lhs / d), without a 64-bit divide: with q = rho - tau, 0 for q < 0, ONE for
 * q >= span, else floor(q 2^15 / span).  rho >= tau iff lhs >= tau d, rho >= tau +
 * span iff lhs >= (tau + span) d (fx_mul_ge: products in 128 bits, so exact); between
 * them q = floor((lhs - tau d) / d) < span and the two quotients have at most
 * bits(span) and 15 bits.  lhs >= 0, d > 0, tau >= 0, span > 0 (all < 2^63).  When
 * tau + span and d fit 32 bits the products are 32 x 32 -> 64 bits; when lhs - tau d
 * does too and span < 2^17 (q << 15 < 2^32), two 32-bit divisions give the same
 * quotients: one instruction each on Cortex-M3, a short libgcc call where the target
 * has no divide, against the bit steps' 64-bit loop. */
static inline uint16_t bti_morph_nodiv(int64_t lhs, int64_t d, int64_t tau, int64_t span)
{
    uint64_t L = (uint64_t)lhs, D = (uint64_t)d, n, q;
    if ((((uint64_t)(tau + span) | D) >> 32) == 0) {
        /* tau d and (tau + span) d as 32 x 32 -> 64-bit products (one instruction on
         * 32-bit ARM, exact) */
        const uint64_t lo = (uint64_t)(uint32_t)tau * (uint32_t)D, hi = (uint64_t)(uint32_t)(tau + span) * (uint32_t)D;
        if (L < lo) return 0;
        if (L >= hi) return BT_MORPH_ONE;
        n = L - lo;
        if ((n >> 32) == 0 && ((uint64_t)span >> 17) == 0)
            return (uint16_t)((((uint32_t)n / (uint32_t)D) << 15) / (uint32_t)span);
    } else {
        if (!fx_mul_ge(L, (uint64_t)tau, D)) return 0;
        if (fx_mul_ge(L, (uint64_t)(tau + span), D)) return BT_MORPH_ONE;
        n = L - (uint64_t)tau * D;
    }
    q = fx_udiv_bits(n, D, bti_bits((uint64_t)span));
    return (uint16_t)fx_udiv_bits(q << 15, (uint64_t)span, 15);
}

void bte_diamond(bt_tree *t, const bti_build_ctx *c, int32_t x, int32_t y, int32_t h, int typeD);
void bte_extent_init(bti_build_ctx *c, const hf *f);
void bte_pad(bt_tree *t, const bti_build_ctx *c, int32_t h, int typeD);
void bte_level1(bt_tree *t, const bti_build_ctx *c);
void bte_level2(bt_tree *t, const bti_build_ctx *c);

/* Appends to m's strip the shortest run of line triangles that reaches leaf L
 * (vertex indices) and draws it, chosen so that N (may be NULL: the last leaf)
 * follows as cheaply as possible, preferring N's walk exit edge {ne0, ne1} last
 * (core/bt_strip.c).  Needs m->ns >= 2; counts the line triangles in m->nline.
 * The rest of the way (after L, drawing N) goes to plan[0 .. *nplan).
 * Returns 0, or -1 (nothing written) if none was found or it does not fit. */
#define BTS_PLAN 14
int bts_bridge(bt_mesh *m, const uint32_t L[3], const uint32_t *N, uint32_t ne0, uint32_t ne1,
               uint32_t plan[BTS_PLAN], int *nplan);
/* Follows the plan of the last bridge (which drew the leaf before L and planned
 * the way to L) when it leaves L's walk exit edge {o0, o1} last and N (NULL: none)
 * continues there: 1 (written), else 0.  Empties the plan either way. */
int bts_follow(bt_mesh *m, const uint32_t plan[BTS_PLAN], int *nplan, uint32_t o0, uint32_t o1,
               const uint32_t *N);

#endif
