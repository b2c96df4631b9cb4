/* raster/xform.c — the per-frame vertex transform of the rasteriser (see raster.h for
 * the conventions; raster.c draws the bands from what this file leaves in the cache).
 *
 * rs_frame_prepare checks the frame, transforms each vertex once (camera space by the
 * Q30 view matrix, then divide) into the vertex cache with an outcode, and notes in
 * the chunk table (required) the rows each chunk of triangles can touch, so the band
 * loop skips chunks that miss its band (unless the frame is drawn as one band only).
 */
#include <string.h>
#include "raster/raster_int.h"
#include "raster/raster_clip.h"

size_t rs_cache_mem_size(uint32_t nv) { return (size_t)nv * sizeof(rs_cvert); }

size_t rs_chunk_mem_size(const rs_prim *prims, int32_t nprims)
{
    size_t n = 0;
    int32_t p;
    for (p = 0; p < nprims; p++) n += (rs_prim_tris(&prims[p]) + RS_CHUNK - 1) / RS_CHUNK;
    return (n ? n : 1) * 2 * sizeof(int16_t);    /* never 0: malloc(0) may give NULL */
}

size_t rs_clip_mem_size(uint32_t n) { return (size_t)n * sizeof(rs_clip_poly); }

/* The frame's clip table (rs_frame.clips), emptied, then filled with the polygon of every
 * triangle the bands would clip for the near plane or the guard band (its vertices not
 * all beyond one rejecting plane), from the chunks chunk_rows gave every row (the only
 * ones that can hold such a triangle), until the table is full.  Not for a frame drawn
 * as one band, which clips each triangle once anyway. */
static void clip_table(rs_frame *f)
{
    const uint32_t slow = (uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD) << 24;
    const uint32_t mask = f->clip_cap - 1;
    const rs_cvert *const cache = f->cache;
    const int16_t *ch = f->chunks;
    uint32_t i, used = 0;
    int32_t p;
    for (i = 0; i <= mask; i++) f->clips[i].owner = NULL;
    if (f->one_band) return;
    for (p = 0; p < f->nprims; p++) {
        const rs_prim *pr = &f->prims[p];
        const uint32_t nt = rs_prim_tris(pr);
        uint32_t t0, t;
        for (t0 = 0; t0 < nt; t0 += RS_CHUNK, ch += 2) {
            const uint32_t t1 = nt - t0 < RS_CHUNK ? nt : t0 + RS_CHUNK;
            if (ch[0] != -1 || ch[1] != f->h) continue;
            for (t = t0; t < t1; t++) {
                uint32_t ia, ib, ic, h, k;
                rs_prim_tri(pr, t, &ia, &ib, &ic);    /* as the draw hands it to the clipper */
                if ((cache[ia].c & cache[ib].c & cache[ic].c & REJECT)
                    || !((cache[ia].c | cache[ib].c | cache[ic].c) & slow))
                    continue;
                h = clip_slot(ia, ib, ic, mask);
                for (k = 0; k <= mask && clip_mine(f, &f->clips[h]); k++, h = (h + 1) & mask)
                    if (f->clips[h].ia == ia && f->clips[h].ib == ib && f->clips[h].ic == ic) break;
                if (k > mask || clip_mine(f, &f->clips[h])) continue;      /* (full, or there) */
                f->clips[h].owner = f;
                f->clips[h].ia = ia; f->clips[h].ib = ib; f->clips[h].ic = ic;
                f->clips[h].n = clip_polygon(f, ia, ib, ic, f->clips[h].v);
                if (++used > mask) return;
            }
        }
    }
}

/* Rows [lo, hi] that chunks' triangles can touch (conservative: the pixel-centre rows
 * of their vertices; everything when a vertex needs clipping; none, lo > hi, when all
 * its vertices share an outcode bit that rejects every triangle: beyond one side of the
 * screen, behind the near plane or beyond the far one), once per frame for all bands. */
static void chunk_rows(rs_frame *f)
{
    const uint32_t slow = (uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD) << 24;
    const uint32_t reject = (uint32_t)(RS_OUT_LEFT | RS_OUT_RIGHT | RS_OUT_TOP | RS_OUT_BOTTOM
                                       | RS_OUT_FAR | RS_OUT_NEAR) << 24;
    int16_t *ch = f->chunks;
    const rs_cvert *const cache = f->cache;
    int32_t p;
    for (p = 0; p < f->nprims; p++) {
        const rs_prim *pr = &f->prims[p];
        uint32_t nt = rs_prim_tris(pr), t0;
        for (t0 = 0; t0 < nt; t0 += RS_CHUNK, ch += 2) {
            uint32_t t1 = nt - t0 < RS_CHUNK ? nt : t0 + RS_CHUNK, i0, i1;
            /* two sets of bounds and outcodes (or, and), one for each vertex of a pair,
             * merged after the loop: two vertices per iteration, and gcc does not
             * reassociate them into a min of the pair (a copy each) */
            int32_t lo = INT32_MAX, hi = INT32_MIN, lo2 = INT32_MAX, hi2 = INT32_MIN;
            uint32_t any = 0, common = reject, any2 = 0, common2 = reject;
            const br_index *ix, *ie;
            if (pr->kind == RS_STRIP) { i0 = t0; i1 = t1 + 2; } else { i0 = 3 * t0; i1 = 3 * t1; }
            ix = pr->idx + i0; ie = pr->idx + i1;
            if ((i1 - i0) & 1) {
                const rs_cvert *v = &cache[*ix++];
                any = v->c; common &= v->c; lo = hi = v->y;
            }
            for (; ix != ie; ix += 2) {
                const rs_cvert *v = &cache[ix[0]], *w = &cache[ix[1]];
                any |= v->c; common &= v->c;
                if (v->y < lo) lo = v->y;
                if (v->y > hi) hi = v->y;
                any2 |= w->c; common2 &= w->c;
                if (w->y < lo2) lo2 = w->y;
                if (w->y > hi2) hi2 = w->y;
            }
            any |= any2; common &= common2;
            if (lo2 < lo) lo = lo2;
            if (hi2 > hi) hi = hi2;
            lo = (lo + RSI_HALF - 1) >> RSI_SUB;
            hi = (hi - RSI_HALF) >> RSI_SUB;
            if (any & slow) { lo = -1; hi = f->h; }
            if (lo < -1) lo = -1;
            if (hi > f->h) hi = f->h;
            if (common) { lo = f->h; hi = -1; }
            ch[0] = (int16_t)lo;
            ch[1] = (int16_t)hi;
        }
    }
}

/* A frame drawn as one whole-frame band (rs_frame.one_band): every chunk may touch every
 * row, which the band loop then treats as it treats a frame without a table. */
static void chunk_all_rows(rs_frame *f)
{
    int16_t *ch = f->chunks;
    int32_t p;
    for (p = 0; p < f->nprims; p++) {
        uint32_t nt = rs_prim_tris(&f->prims[p]), t0;
        for (t0 = 0; t0 < nt; t0 += RS_CHUNK, ch += 2) {
            ch[0] = 0;
            ch[1] = (int16_t)(f->h - 1);
        }
    }
}

/* The side bits of a screen position (sub-pixels) beyond the w x h frame's outermost
 * pixel centres. */
static uint32_t screen_oc(int32_t x, int32_t y, int32_t w, int32_t h)
{
    uint32_t oc = 0;
    if (x < RSI_HALF) oc |= RS_OUT_LEFT;
    if (x > w * RSI_SUBONE - RSI_HALF) oc |= RS_OUT_RIGHT;
    if (y < RSI_HALF) oc |= RS_OUT_TOP;
    if (y > h * RSI_SUBONE - RSI_HALF) oc |= RS_OUT_BOTTOM;
    return oc;
}

void rs_cvert_set(rs_cvert *o, int32_t w, int32_t h, int32_t x, int32_t y, uint32_t d, uint32_t rgb)
{
    o->x = x; o->y = y; o->d = d;
    o->c = (rgb & 0xffffffu) | (screen_oc(x, y, w, h) << 24);
    o->cp = rsi_pack_rgb(rgb);
#if RS_TEX_FIELDS
    o->u = o->v = 0;
#endif
}

void rs_cvert_recolour(rs_cvert *o, uint32_t rgb)
{
    o->c = (o->c & 0xff000000u) | (rgb & 0xffffffu);
    o->cp = rsi_pack_rgb(rgb & 0xffffffu);
}

/* The reference transform of one vertex (camera space, near/far, guard band, divide,
 * screen outcodes), for the vertices the fast loop below does not finish: beyond the
 * far plane, or not provably inside the guard band.  Rare (terrain beyond the far plane
 * or far outside the screen), so it recomputes everything from the frame instead of
 * holding constants. */
static RSI_NOINLINE void xform_slow(const rs_frame *f, const rs_vertex *v, rs_cvert *o)
{
    const cam_vp *vp = &f->vp;
    const int64_t f8 = rsi_f_q8(vp), g8 = (int64_t)RS_GUARD_PX << 8;
    int64_t c[3], lim, ax, ay;
    uint32_t oc = 0;
    o->cp = rsi_pack_rgb(v->rgb);
#if RS_TEX_FIELDS
    o->u = v->uv[0]; o->v = v->uv[1];
#endif
    rsi_to_camera(vp, v->p, c);
    if (c[2] < vp->znear) {
        o->x = o->y = 0; o->d = 0;
        o->c = (v->rgb & 0xffffffu) | ((uint32_t)RS_OUT_NEAR << 24);
        return;
    }
    if (c[2] > vp->zfar) oc |= RS_OUT_FAR;
    lim = g8 * c[2]; ax = f8 * c[0]; ay = f8 * c[1];
    /* |ax| > lim or |ay| > lim, one unsigned compare each (lim > 0; |ax| < 2^61 and
     * lim < 2^55, so ax + lim cannot overflow) */
    if ((uint64_t)(ax + lim) > (uint64_t)(2 * lim) || (uint64_t)(ay + lim) > (uint64_t)(2 * lim)) {
        /* beyond the guard band on one side is outside the screen on that side */
        oc |= RS_OUT_GUARD;
        if (ax > lim) oc |= RS_OUT_RIGHT;
        if (-ax > lim) oc |= RS_OUT_LEFT;
        if (ay > lim) oc |= RS_OUT_TOP;
        if (-ay > lim) oc |= RS_OUT_BOTTOM;
        o->x = o->y = 0; o->d = 0;
    } else {
        rsi_project(vp, f8, c, f->w, f->h, o);
        oc |= screen_oc(o->x, o->y, f->w, f->h);
    }
    o->c = (v->rgb & 0xffffffu) | (oc << 24);
}

/* The per-frame transform loop; tex (a constant after inlining) says whether to copy
 * the texture coordinates, which only textured frames read.
 *
 * Every vertex gets exactly xform_slow's result; the loop takes a shorter road for the
 * common vertex, znear <= zc <= zfar and inside the guard band, with its constants in
 * an xform_k read through a pointer (memory operands instead of a dozen stack reloads):
 * - camera space is stepped along rows: a vertex whose x is the previous one's plus
 *   the current step dx, with the same y (a regular grid stored row by row, as the
 *   peer scene), gets the sums r[i][0] x + r[i][1] y + t[i] as the previous vertex's
 *   plus s[i] = r[i][0] dx, the same integers (sums of the same products, each within
 *   int64) before the floor shift adds r[i][2] z.  Any
 *   other vertex computes them, and takes its x - previous x as the new step when its
 *   y is the previous one's.  The test is one compare of the two coordinates as one
 *   word, key = (x, y) with x's sign bit flipped (x + 2^31, 0 .. 2^32 - 1), against
 *   ek = previous key + dx in x's half: as |previous x| <= CAM_COORD_MAX = 2^30 (raster.h)
 *   and |dx| < 2^30, x + 2^31 + dx stays in 1 .. 2^32 - 1, so the add never carries into
 *   (or borrows from) y's half and key = ek exactly when x = previous x + dx and y =
 *   previous y.  (A false match needs |previous x| > 2^30, and the vertex matched is
 *   then beyond it too.)  Any dx keeps the sums exact (s is r[i][0] times the same dx;
 *   the step is only a prediction), so a larger one is replaced by 0.  On a grid mesh
 *   only the row starts and the first step compute the sums; s lives in xform_k for
 *   the memory operands (a local copy would be spilled and reloaded into a register);
 * - near and far in one unsigned compare: tzn = t2 - znear 2^30 makes the shifted sum
 *   zc - znear exactly (a multiple of 2^30 passes through the floor shift); the sum
 *   still fits int64, as |r p| < 3 2^60, |t2| < 3 2^60 and znear 2^30 < 2^61.  A
 *   vertex behind the near plane (common when the camera flies low) only needs its
 *   colour, so it is done here too;
 * - the screen position folds the centre and the rounding into one constant:
 *   cx + ((q + 8) >> 4) = (q + 8 + 16 cx) >> 4 for q = f8 c0 / zc, and for y the
 *   quotient of -f8 c1 (truncation is symmetric, so it is -q exactly):
 *   cy - ((q + 8) >> 4) = (16 cy + 7 + (-q)) >> 4, as -floor(a / 16) =
 *   floor((15 - a) / 16).  sx, sy stay int64 until the guard band is settled;
 * - the guard band is not tested before the divide (|f8 c0| < 2^61, zc >= 1: the
 *   quotient is always defined).  An on-screen vertex (one compare per axis) is far
 *   inside it; off screen, |sx - cx| <= GUARD_S = 2^18 - 1 gives |q| < 2^22 = g8
 *   (sx - cx = floor((q + 8) / 16), so -2^22 + 16 <= q + 8 <= 2^22 - 1; for y the same
 *   with q' + 7, q' = -q), hence |f8 c0| < g8 zc, strictly inside, and the side bits
 *   follow from sx, sy as in xform_slow.  Only the side a coordinate is off needs the
 *   bound (a strip that leaves the screen has many vertices off it, nearly all inside
 *   the guard band).  Anything else goes to xform_slow, which decides exactly.
 *   (GUARD_S = 2^18 would be wrong: test_raster's test_transform fails on it);
 * - the packed colour: rgb (< 2^24) times 1 + 2^26 is rgb + (rgb << 26) without
 *   overlap, which holds B at bit 0 and R at bit 42 where rsi_pack_rgb puts them; G
 *   moves by its own shift. */
#define GUARD_S ((RS_GUARD_PX << RSI_SUB) - 1)
/* The view matrix's elements in xform_k: int64 on 64-bit targets, where the product
 * with a vertex coordinate takes the element as a memory operand; int32 on 32-bit
 * ones, where a 32 x 32 -> 64-bit multiply is one instruction and a 64 x 64 one three.
 * The same products either way. */
#if RSI_REG64
typedef int64_t xform_rq;
#else
typedef int32_t xform_rq;
#endif
/* Screen positions before the guard band is settled (see xform_div): int32 on targets
 * without a 64-bit divide, where xform_div's quotients are below 2^30 in magnitude. */
#if BR_DIV64_NATIVE
typedef int64_t xform_sc;
typedef uint64_t xform_usc;
#else
typedef int32_t xform_sc;
typedef uint32_t xform_usc;
#endif
typedef struct xform_k {
    xform_rq r[3][3];           /* view matrix (Q30, |r| <= 2^30) */
    int64_t t[3];               /* translation (Q30 world units) */
    int64_t tzn, zn, zspan;     /* t2 - znear 2^30; znear; zfar - znear */
    int64_t f8, nf8, kd;        /* f (Q8 pixels), -f, RS_DEPTH_ONE znear */
    xform_sc kx, ky;            /* 16 cx + 8, 16 cy + 7 (cx, cy: centre, sub-pixels) */
    xform_sc gx0, gx1, gy0, gy1;    /* cx -+ GUARD_S, cy -+ GUARD_S */
    xform_usc xspan, yspan;     /* on screen: sx - RSI_HALF <= xspan, sy - RSI_HALF <= yspan */
    uint64_t pmul, pmask;       /* colour packing: 1 + 2^26, bits of B (0..7) and R (42..49) */
    int64_t s[3];               /* the loop's steps r[i][0] dx (written by the loop) */
    uint64_t dk;                /* the key's step (dx in x's half; written by the loop) */
    uint64_t kbias;             /* a vertex's (x, y) key: x's sign bit (see xform_loop) */
    int32_t kshift;             /* where x sits in the key: bit 0 or 32 */
#if !BR_DIV64_NATIVE
    uint64_t kds[32];           /* kd 2^s, s = 0 .. 31: the depth's shifted dividend (fx_udiv_rn) */
#endif
} xform_k;

/* rsi_pack_rgb(rgb) for rgb < 2^24, with one multiply (see above). */
static RSI_INLINE uint64_t xform_pack(const xform_k *k, uint32_t rgb)
{
    return (((uint64_t)rgb * k->pmul) & k->pmask) | ((uint64_t)(rgb & 0xff00u) << 13);
}

#if !BR_DIV64_NATIVE
/* fx_divisor_trunc32(dz, f8 c, q) for 0 < f8 < 2^28 and |c| < 2^34 on targets without
 * a 64-bit divide, in fewer 32-bit instructions, the same quotient: |f8 c| = f8 |c| (one
 * 32 x 64-bit multiply after the absolute value, not a 64 x 64 one before it), and the
 * shift of fx_udiv_r by s = clz c2 as two 32-bit halves with the caller's sr = 32 - s,
 * as c2 < 2^31 makes 1 <= s <= 31.  It refuses (0) |q| >= 2^30 as well, far beyond the
 * guard band (|q| < 2^22 inside; xform_slow decides), so the screen position is int32
 * arithmetic: |q| + 16 cx + 8 < 2^30 + 2^20 (xform_sc). */
static RSI_INLINE int xform_div(const fx_divisor *dz, uint32_t f8, int64_t c, uint32_t sr, int32_t *q)
{
    const uint64_t m = (uint64_t)f8 * (c < 0 ? 0 - (uint64_t)c : (uint64_t)c);
    const uint32_t mh = (uint32_t)(m >> 32), ml = (uint32_t)m, s = (uint32_t)dz->r.s;
    uint32_t u;
    if (mh >= dz->r.dn >> s) return 0;
    u = fx_udiv_rn(((uint64_t)((mh << s) | (ml >> sr)) << 32) | (ml << s), &dz->r);
    if (u >> 30) return 0;
    *q = c < 0 ? -(int32_t)u : (int32_t)u;
    return 1;
}
#endif

/* a textured frame's coordinates into the cache entry (no fields without RS_TEX_FIELDS) */
#if RS_TEX_FIELDS
#define XFORM_UV(tex, o, v) do { if (tex) { (o)->u = (v)->uv[0]; (o)->v = (v)->uv[1]; } } while (0)
#else
#define XFORM_UV(tex, o, v) ((void)(tex))
#endif

/* The stepping along rows (see above) on 64-bit targets only: on 32-bit ones the two
 * products and the add are multiply-accumulates, the 64-bit key compare and steps
 * cost more than they save, and three 64-bit sums held across the divides take six
 * registers. */
#define XFORM_STEP RSI_REG64
/* xform_k's fields in registers: a local copy of *k in xform_loop, whose address never
 * leaves it, so gcc keeps its fields in registers (k itself may alias the cache
 * entries' 64-bit cp stores, so every field was reloaded per vertex).  For 64-bit
 * targets without memory operands (AArch64: 31 registers hold the loop's state and
 * most of the constants; three go to the stack).  x86-64 keeps the memory operands
 * (see xform_k). */
#if RSI_REG64 && !defined(__x86_64__)
#define XFORM_KREG 1
#else
#define XFORM_KREG 0
#endif

/* The state the row stepping carries from one vertex to the next (locals of
 * xform_loop, in registers once xform_vert is inlined). */
typedef struct xform_st {
    int64_t a0, a1, a2;         /* the previous vertex's r[i][0] x + r[i][1] y + t[i] (tzn for i = 2) */
    uint64_t ek;                /* the key a vertex must have to step them by k->s */
} xform_st;

/* One vertex of xform_loop: v's entry o.  first = 0 promises v != f->v (v[-1] exists).
 * The next ek is key + dk for every vertex: a stepped vertex's key is ek, so one add
 * after the join serves both paths (the other sets ek = key); dk lives in xform_k
 * (one register fewer across the unrolled loop; the compiler reloads it after the
 * path that writes it; written as ek += dk on the stepped path and ek = key + dk on
 * the other, the compiler may move ek between registers in the unrolled copies).
 * Every exit to xform_slow goes through the one call at `slow`, so the compiler forms
 * the call's v and o there only (with several call sites it may keep v + i and o + i
 * of the unrolled copies in registers or on the stack for every vertex). */
static RSI_INLINE void xform_vert(const rs_frame *f, xform_k *k, const rs_vertex *v, rs_cvert *o, int tex,
                                 int first, xform_st *st)
{
#if XFORM_STEP
    const int64_t z = v->p[2];
#else
    const int64_t x = v->p[0], y = v->p[1], z = v->p[2];
#endif
    const uint32_t rgb = v->rgb & 0xffffffu;
    int64_t c0, c1, c2;
    xform_sc sx, sy, q;
    fx_divisor dz;          /* c2, for the three quotients */
#if !BR_DIV64_NATIVE
    uint32_t sr;            /* 32 - dz.r.s (xform_div) */
#endif
#if XFORM_STEP
    uint64_t key;           /* p[0], p[1] as one word, x's sign bit flipped */
    memcpy(&key, v->p, sizeof key);
    key ^= k->kbias;
    if (RSI_LIKELY(key == st->ek)) {     /* x = previous x + dx, same y */
        st->a0 += k->s[0]; st->a1 += k->s[1]; st->a2 += k->s[2];
    } else {
        const int64_t x = v->p[0], y = v->p[1];
        if ((!first || v != f->v) && y == v[-1].p[1]) {     /* a new step along the row */
            int64_t dx = x - v[-1].p[0];
            if (dx >= (1 << 30) || dx <= -(1 << 30)) dx = 0;  /* |dx| < 2^30 (see above) */
            k->dk = (uint64_t)dx << k->kshift;
            k->s[0] = k->r[0][0] * dx; k->s[1] = k->r[1][0] * dx; k->s[2] = k->r[2][0] * dx;
        }
        st->a0 = k->r[0][0] * x + k->r[0][1] * y + k->t[0];
        st->a1 = k->r[1][0] * x + k->r[1][1] * y + k->t[1];
        st->a2 = k->r[2][0] * x + k->r[2][1] * y + k->tzn;
        st->ek = key;
    }
    st->ek += k->dk;
#define XF_C(I) ((st->a##I + k->r[I][2] * z) >> 30)
#else
    /* each sum where it is used (fewer live values: 64-bit ones take two registers) */
#define XF_C(I) ((k->r[I][0] * x + k->r[I][1] * y + k->r[I][2] * z + XF_T##I) >> 30)
#define XF_T0 k->t[0]
#define XF_T1 k->t[1]
#define XF_T2 k->tzn
    (void)first; (void)st;
#endif
    c2 = XF_C(2);
    if (RSI_UNLIKELY((uint64_t)c2 > (uint64_t)k->zspan)) {
        if (c2 < 0) {       /* behind the near plane: only the colour is valid */
            o->x = o->y = 0; o->d = 0;
            o->c = rgb + ((uint32_t)RS_OUT_NEAR << 24);      /* = rgb | bit (rgb < 2^24), one lea */
            o->cp = xform_pack(k, rgb);
            XFORM_UV(tex, o, v);
            return;
        }
        goto slow;
    }
    c2 += k->zn;
#if BR_DIV64_NATIVE
    fx_divisor_make(&dz, c2);      /* 1 <= znear <= c2 <= zfar < 2^31 */
#else   /* fx_divisor_make without its test: c2 < 2^31 always has its reciprocal */
    dz.d = c2;
    dz.r = fx_recip_make((uint32_t)c2);
#endif
    c0 = XF_C(0);
    /* one axis at a time, each settled and stored before the next divide (c1 is
     * formed only then: one register move fewer).  Off screen: inside the guard
     * band when |s - c| <= GUARD_S, which needs a test only on the side the
     * coordinate is off; else the exact test in xform_slow (which rewrites the
     * whole entry).  The side bits are added, not or-ed: rgb < 2^24 and c holds no
     * side bit yet, so + sets the bit exactly as |, and the compiler can form rgb +
     * bit with one lea (rgb | bit takes a copy and an or) */
    o->c = rgb;
    /* without a 64-bit divide, |q| >= 2^30 (far beyond the guard band) is left to
     * xform_slow (xform_div), where the native path ends too */
#if BR_DIV64_NATIVE
    if (!fx_divisor_trunc32(&dz, k->f8 * c0, &q)) goto slow;
#else
    sr = 32u - (uint32_t)dz.r.s;
    if (!xform_div(&dz, (uint32_t)k->f8, c0, sr, &q)) goto slow;
#endif
    sx = (q + k->kx) >> 4;
    if (RSI_UNLIKELY((xform_usc)(sx - RSI_HALF) > k->xspan)) {
        if (sx < RSI_HALF) {
            if (sx < k->gx0) goto slow;
            o->c = rgb + ((uint32_t)RS_OUT_LEFT << 24);
        } else {
            if (sx > k->gx1) goto slow;
            o->c = rgb + ((uint32_t)RS_OUT_RIGHT << 24);
        }
    }
    o->x = (int32_t)sx;
    c1 = XF_C(1);
#if !BR_DIV64_NATIVE
    if (!xform_div(&dz, (uint32_t)k->f8, c1, sr, &q)) goto slow;
    sy = (k->ky - q) >> 4;
#elif XFORM_KREG  /* -q, one register fewer (x86-64: nf8 and ky are memory operands) */
    if (!fx_divisor_trunc32(&dz, k->f8 * c1, &q)) goto slow;
    sy = (k->ky - q) >> 4;
#else
    if (!fx_divisor_trunc32(&dz, k->nf8 * c1, &q)) goto slow;
    sy = (q + k->ky) >> 4;
#endif
    if (RSI_UNLIKELY((xform_usc)(sy - RSI_HALF) > k->yspan)) {
        if (sy < RSI_HALF) {
            if (sy < k->gy0) goto slow;
            o->c += (uint32_t)RS_OUT_TOP << 24;
        } else {
            if (sy > k->gy1) goto slow;
            o->c += (uint32_t)RS_OUT_BOTTOM << 24;
        }
    }
    o->y = (int32_t)sy;
#if BR_DIV64_NATIVE
    (void)fx_divisor_trunc32(&dz, k->kd, &q);        /* kd = RS_DEPTH_ONE znear < c2 2^30: fits */
    o->d = (uint32_t)q;
#else
    /* fx_divisor_trunc32's quotient without the sign, range and shift work: kd > 0,
     * kd < c2 2^30, and c2 <= zfar < 2^31 always has its reciprocal (dz.r.s = clz c2,
     * kd 2^s < 2^62) */
    o->d = fx_udiv_rn(k->kds[dz.r.s], &dz.r);
#endif
    o->cp = xform_pack(k, rgb);
    XFORM_UV(tex, o, v);
    return;
slow:
    xform_slow(f, v, o);
}

/* The loop: on 64-bit targets unrolled by 4 after the nv mod 4 first vertices, so the
 * two pointer increments, the compare and the branch serve four vertices (the copies
 * address v + i, o + i with displacements; by 2 saves less, by 8 little more for twice
 * the code).  32-bit targets keep one vertex per iteration: there the unrolled loop
 * spills. */
static RSI_INLINE void xform_loop(const rs_frame *f, xform_k *k, int tex)
{
    const rs_vertex *v = f->v, *const end = f->v + f->nv, *const head = XFORM_STEP ? f->v + (f->nv & 3u) : end;
    rs_cvert *o = f->cache;
    xform_st st;
#if XFORM_KREG
    /* see XFORM_KREG; the multiplier and (when the byte order is known here) the key's
     * bias as constants, so neither takes a register: the multiply becomes a shifted
     * add */
    xform_k kl = *k;
    k = &kl;
    kl.pmul = 0x4000001u;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    kl.kbias = (uint64_t)1 << 31;
#endif
#endif
    /* the first vertex's key is never ek (its complement) */
    st.a0 = st.a1 = st.a2 = 0;
    st.ek = 0;
#if XFORM_STEP
    if (v != end) { memcpy(&st.ek, v->p, sizeof st.ek); st.ek = ~(st.ek ^ k->kbias); }
#endif
    for (; v != head; v++, o++) xform_vert(f, k, v, o, tex, 1, &st);
#if XFORM_STEP
    for (; v != end; v += 4, o += 4) {
        xform_vert(f, k, v, o, tex, 1, &st);
        xform_vert(f, k, v + 1, o + 1, tex, 0, &st);
        xform_vert(f, k, v + 2, o + 2, tex, 0, &st);
        xform_vert(f, k, v + 3, o + 3, tex, 0, &st);
    }
#endif
}
#undef XF_C
#undef XF_T0
#undef XF_T1
#undef XF_T2

/* Called through a pointer (see rs_frame_prepare), so the compiler cannot propagate
 * xform_k's values into the loop: it would then expand the multiply by pmul into a
 * copy, shift and add and rebuild the 64-bit pmask every vertex, where a memory
 * operand costs nothing. */
static RSI_NOINLINE void xform_plain(const rs_frame *f, xform_k *k) { xform_loop(f, k, 0); }
static RSI_NOINLINE void xform_tex(const rs_frame *f, xform_k *k) { xform_loop(f, k, 1); }

br_status rs_frame_prepare(rs_frame *f)
{
    const cam_vp *vp = &f->vp;
    int64_t f8 = rsi_f_q8(vp);
    int32_t w = f->w, h = f->h;
    if (w < 1 || h < 1 || w > RS_MAX_DIM || h > RS_MAX_DIM || !f->cache || !f->chunks || (f->nv && !f->v)
        || (f->fmt != RS_FMT_XRGB8888 && f->fmt != RS_FMT_RGB565)
        || (f->depth != RS_DEPTH32 && f->depth != RS_DEPTH16 && f->depth != RS_DEPTH_NONE) || vp->znear <= 0
        || vp->zfar <= vp->znear || vp->cx_q16 != w * (FX_Q16_ONE / 2)
        || vp->cy_q16 != h * (FX_Q16_ONE / 2) || f8 <= 0 || f8 >= ((int64_t)1 << 28)
        || (f->tex && (!f->tex->px || f->tex->w < 1 || f->tex->h < 1 || f->tex->w > RS_MAX_TEX
                       || f->tex->h > RS_MAX_TEX))
        || (f->clips && (f->clip_cap < 1 || (f->clip_cap & (f->clip_cap - 1)))))
        return BR_E_ARG;
    if (f->nv) {
        xform_k k;
        int i, j;
        for (i = 0; i < 3; i++) {
            for (j = 0; j < 3; j++) k.r[i][j] = vp->r[i][j];
            k.t[i] = vp->t[i];
        }
        k.tzn = vp->t[2] - ((int64_t)vp->znear << 30);
        k.zn = vp->znear; k.zspan = (int64_t)vp->zfar - vp->znear;
        k.f8 = f8; k.nf8 = -f8; k.kd = (int64_t)RS_DEPTH_ONE * vp->znear;
        /* all below 2^20 in magnitude (w, h <= RS_MAX_DIM) */
        k.kx = (xform_sc)w * RSI_SUBONE * RSI_HALF + RSI_HALF; k.ky = (xform_sc)h * RSI_SUBONE * RSI_HALF + RSI_HALF - 1;
        k.xspan = (xform_usc)w * RSI_SUBONE - 2 * RSI_HALF; k.yspan = (xform_usc)h * RSI_SUBONE - 2 * RSI_HALF;
        k.gx0 = (xform_sc)w * RSI_HALF - GUARD_S; k.gx1 = (xform_sc)w * RSI_HALF + GUARD_S;
        k.gy0 = (xform_sc)h * RSI_HALF - GUARD_S; k.gy1 = (xform_sc)h * RSI_HALF + GUARD_S;
        k.pmul = 0x4000001u; k.pmask = 0x3fc00000000ffu;
#if !BR_DIV64_NATIVE
        for (i = 0; i < 32; i++) k.kds[i] = (uint64_t)k.kd << i;   /* (wraps only for s unused) */
#endif
        k.s[0] = k.s[1] = k.s[2] = 0;
        k.dk = 0;
        {   /* the key's layout, from the target's byte order */
            int32_t xy[2] = { 1, 0 };
            uint64_t one;
            memcpy(&one, xy, sizeof one);
            k.kshift = one == 1 ? 0 : 32;
            k.kbias = (uint64_t)1 << (k.kshift + 31);
        }
        (f->tex ? xform_tex : xform_plain)(f, &k);
    }
    if (f->clip_z_on) {     /* the clip plane's outcode (its triangles go to the clipper) */
        uint32_t i;
        for (i = 0; i < f->nv; i++)
            if (f->v[i].p[2] < f->clip_z) f->cache[i].c |= (uint32_t)RS_OUT_CLIPZ << 24;
    }
    if (f->one_band) chunk_all_rows(f);
    else chunk_rows(f);
    if (f->clips) clip_table(f);
    return BR_OK;
}
