/* raster/raster_general.h — the general path of the per-triangle code: triangles whose
 * bounding box has more than TINY_W x TINY_H candidate centres, drawn row by row (exact
 * row starts from the barycentric weights, stepped gradients along the row).  raster.c's
 * own, included once; every function takes the variant as its constant last argument
 * (raster_pixel.h).
 *
 * The plain span (no texture, no counting) is drawn GS_N pixels at a time in 32-bit
 * vector lanes (GCC's generic vectors: SSE2 on x86-64, NEON on AArch64) for spans of
 * eight or more pixels (from four, with masked loads and stores, in the x86-64-v3 copy's
 * XRGB8888 with 32-bit depth: GS_MASKED); shorter spans and targets without such
 * vectors keep the scalar loop (a span's two end groups cost about as many instructions
 * as eight scalar pixels).  Same pixels: see gen_span_plain.  RS_SPANV (core/config.h)
 * chooses. */
#ifndef BR_RASTER_GENERAL_H
#define BR_RASTER_GENERAL_H

/* GEN_OPAQUE(x): x's value unknown to the optimiser from here on (an empty asm with x as
 * its in-out operand; no code), to keep GCC from deriving induction variables from it */
#if defined(__GNUC__)
#define GEN_OPAQUE(X) __asm__("" : "+r"(X))
#else
#define GEN_OPAQUE(X) ((void)0)
#endif
#if RS_SPANV
/* GS_N pixels a group: 4 in 128-bit vectors, 8 in the 256-bit ones of x86-64-v3 (AVX2;
 * raster/isa.c's second copy).  Everything below holds for either: gs_lanes_make's bound
 * takes the fields at pixels 0 and 3 of a span, and every span that makes the lanes has
 * four pixels or more (eight, or GS_MASK_MIN). */
#define GS_N (RS_VBYTES / 4)
/* GS_MASKED: the x86-64-v3 copy (eight lanes) draws the XRGB8888 spans with 32-bit depth
 * through AVX2's masked loads and stores (gen_span_plain), from GS_MASK_MIN pixels on;
 * GCC's builtin names, as raster_prepass.h's, so not with clang */
#if GS_N == 8 && !defined(__clang__)
#define GS_MASKED 1
#define GS_MASK_MIN 4
#else
#define GS_MASKED 0
#endif
typedef uint32_t gs_v4u __attribute__((vector_size(4 * GS_N)));
typedef int32_t gs_v4i __attribute__((vector_size(4 * GS_N)));
typedef uint32_t gs_v4un __attribute__((vector_size(4 * GS_N), aligned(2)));  /* at any 16-bit boundary */
typedef uint16_t gs_v8h __attribute__((vector_size(16)));
typedef uint64_t gs_v2q __attribute__((vector_size(16)));
/* Four depths or pixels at P (SZ = 4: uint32_t, 2: uint16_t) to the 32-bit lanes of V,
 * and back; macros, not functions: a vector argument or result needs vector registers,
 * which -mgeneral-regs-only does not have.  16-bit elements come as eight bytes into
 * the low half, interleaved with zeros (SSE2 punpcklwd, NEON zip1), and go back as the
 * low halves of the lanes (the values are below 2^16): q | q >> 16 puts lanes 2i and
 * 2i + 1 side by side in the low 32 bits of 64-bit lane i, one 32-bit shuffle joins
 * them (GCC's own 16-bit shuffle for this is four pextrw and pinsrw). */
#if GS_N == 8
/* (eight 16-bit elements: one 16-byte load widened, vpmovzxwd; back by truncation) */
typedef uint16_t gs_v8hn __attribute__((vector_size(16), aligned(2)));
#define GS_LD(V, P, SZ) do { \
        if ((SZ) == 4) V = *(const gs_v4un *)(const void *)(P); \
        else V = __builtin_convertvector(*(const gs_v8hn *)(const void *)(P), gs_v4u); } while (0)
#define GS_ST(P, V, SZ) do { \
        if ((SZ) == 4) *(gs_v4un *)(void *)(P) = (V); \
        else *(gs_v8hn *)(void *)(P) = __builtin_convertvector((V), gs_v8hn); } while (0)
#elif defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
/* (big-endian: a 32-bit lane's low half is its second 16-bit word; the elements go in
 * there and come back from there with one 16-bit shuffle each way) */
#define GS_LD(V, P, SZ) do { \
        if ((SZ) == 4) V = *(const gs_v4un *)(const void *)(P); \
        else { uint64_t u_; gs_v2q q_; memcpy(&u_, (const void *)(P), 8); q_ = (gs_v2q){ u_, 0 }; \
               V = (gs_v4u)RS_SHUFFLE((gs_v8h)q_, (gs_v8h)(q_ - q_), gs_v8h, 8, 0, 8, 1, 8, 2, 8, 3); } } while (0)
#define GS_ST(P, V, SZ) do { \
        if ((SZ) == 4) *(gs_v4un *)(void *)(P) = (V); \
        else { const gs_v8h h_ = RS_SHUFFLE((gs_v8h)(V), (gs_v8h)(V), gs_v8h, 1, 3, 5, 7, 1, 3, 5, 7); \
               memcpy((void *)(P), &h_, 8); } } while (0)
#else
#define GS_LD(V, P, SZ) do { \
        if ((SZ) == 4) V = *(const gs_v4un *)(const void *)(P); \
        else { uint64_t u_; gs_v2q q_; memcpy(&u_, (const void *)(P), 8); q_ = (gs_v2q){ u_, 0 }; \
               V = (gs_v4u)RS_SHUFFLE((gs_v8h)q_, (gs_v8h)(q_ - q_), gs_v8h, 0, 8, 1, 9, 2, 10, 3, 11); } } while (0)
#define GS_ST(P, V, SZ) do { \
        if ((SZ) == 4) *(gs_v4un *)(void *)(P) = (V); \
        else { gs_v2q q_ = (gs_v2q)(V); uint64_t u_; q_ |= q_ >> 16; \
               u_ = ((gs_v2q)RS_SHUFFLE((gs_v4u)q_, (gs_v4u)q_, gs_v4u, 0, 2, 0, 2))[0]; memcpy((void *)(P), &u_, 8); } } while (0)
#endif
/* The lanes of a triangle's plain spans: lane l of a group at pixel j holds pixel j + l,
 * each value from the span start plus (j + l) times its step, so the lanes start at
 * {0, 1, 2, 3} steps (the *off) and step by 4 (the *step). */
typedef struct gs_lanes {
    gs_v4u zoff, roff, goff, boff, zstep, rstep, gstep, bstep;
#if GS_MASKED
    /* the masked spans' constants (XRGB8888's GS_PX masks, the depth's flipped top bit):
     * loaded from here, one instruction each; as literals GCC makes each again at every
     * span (three instructions) */
    gs_v4u k80, kr, kg;
#endif
} gs_lanes;
/* Made at a triangle's first span of eight (GS_MASKED: four) or more pixels (most calls
 * draw a few short rows and no such span), out of line and into memory: inline, GCC may
 * hoist it out of the row loop (it is loop invariant), making it for every call.  The
 * signed colour gradients G_k from the packed gc = G_R 2^42 + G_G 2^21 + G_B (mod 2^64):
 * on a span of n >= 4 pixels the fields at pixels 0 and 3 both lie in [0, 2^21), so 3 |G_k| < 2^21
 * and |G_k| < 2^20, which the 21-bit sign extensions recover exactly, field by field
 * from the bottom.  rl: R's shift (see GS_PX). */
RSI_NOINLINE static void gs_lanes_make(gs_lanes *L, uint32_t gzu, uint64_t gc, int rl)
{
    const uint32_t g_b = (uint32_t)((int64_t)(gc << 43) >> 43);
    const uint32_t g_g = (uint32_t)((int64_t)((gc - (uint64_t)(int32_t)g_b) << 22) >> 43);
    const uint32_t g_r = (uint32_t)((int64_t)(gc - (uint64_t)(int32_t)g_b - ((uint64_t)(int32_t)g_g << 21)) >> 42) << rl;
#if GS_N == 8
    const gs_v4u io = { 0, 1, 2, 3, 4, 5, 6, 7 };
#else
    const gs_v4u io = { 0, 1, 2, 3 };
#endif
    L->zoff = io * gzu; L->zstep = io - io + GS_N * gzu;
    L->roff = io * g_r; L->rstep = io - io + GS_N * g_r;
    L->goff = io * g_g; L->gstep = io - io + GS_N * g_g;
    L->boff = io * g_b; L->bstep = io - io + GS_N * g_b;
#if GS_MASKED
    L->k80 = io - io + 0x80000000u; L->kr = io - io + 0xff0000u; L->kg = io - io + 0xff00u;
#endif
}
#endif


/* The gradients and row-start constants of one triangle (gen_grad).  x-gradients per
 * pixel: colour per channel in Q13, packed into the 21-bit fields (exact modulo 2^64,
 * see RS_CBIAS in raster.c) as gc; depth in Q0 as gz.  dcbk, dcck: colour channel k's
 * differences b - a and c - a (|.| <= 255); the row start takes R's and G's as one
 * pair of packed products on 64-bit targets (prg_b, prg_c), one by one on 32-bit ones. */
typedef struct gen_grad_t {
    int64_t gz, inv, dzb, dzc, dcb2, dcc2;
    uint64_t gc, ca;
#if RSI_REG64
    int64_t prg_b, prg_c;
#else
    int32_t dcb0, dcb1, dcc0, dcc1;
#endif
} gen_grad_t;

/* Colour difference of channel k (0 = R, 1 = G, 2 = B) between v and a, from the packed
 * colours: the difference plus 256 in each 21-bit field is in [1, 511], so the fields of
 * v->cp - a->cp + 256 (1 + 2^21 + 2^42) do not borrow, and the whole is below 2^51: R's
 * field, the top one, needs no mask. */
RSI_INLINE static int64_t gen_dch(const rs_cvert *v, const rs_cvert *a, const int k)
{
    return (int64_t)(((v->cp - a->cp + RS_C256) >> (42 - 21 * k)) & (k ? (uint64_t)0x1fffff : ~(uint64_t)0)) - 256;
}

/* Made before the row loop, or, for one-row boxes, once the row's span is known not to
 * be empty (gen_tri's `one`).  Small triangles (box below SMALL, area2 < 2^21): through
 * the reciprocal inv = 2^40 / area2, |colour numerator| < 2^19, products below 2^59;
 * large ones: quotients by the divisor ad of area2, made here.  A span of two or more
 * pixels bounds |gz| by the depth range (< 2^31); the clamp only affects one-pixel spans,
 * where the step is never used, and the reciprocal's gz needs none (|gzn| < 2^22, inv <=
 * 2^40: |gz| < 2^26).  The row start's R and G in one pair of products (prg_b, prg_c:
 * see gen_tri's row start). */
RSI_INLINE static void gen_grad(gen_grad_t *g, fx_divisor *ad, const rs_cvert *a, const rs_cvert *b,
                               const rs_cvert *c, int64_t dy1, int64_t dy2, int64_t area2, const int small)
{
    int64_t gzn;
    g->dzb = (int64_t)b->d - a->d; g->dzc = (int64_t)c->d - a->d;
    const int64_t dcb0 = gen_dch(b, a, 0), dcb1 = gen_dch(b, a, 1);
    g->dcb2 = gen_dch(b, a, 2);
    const int64_t dcc0 = gen_dch(c, a, 0), dcc1 = gen_dch(c, a, 1);
    g->dcc2 = gen_dch(c, a, 2);
    gzn = g->dzb * dy2 - g->dzc * dy1;
    if (small) {
        const int64_t inv = fx_div40((uint32_t)area2);
        g->inv = inv;
        /* colour differences (|.| <= 255) times vertex differences (< 2^10): 32-bit */
        const int32_t y1 = (int32_t)dy1, y2 = (int32_t)dy2;
        g->gc = ((uint64_t)(((int64_t)((int32_t)dcb0 * y2 - (int32_t)dcc0 * y1) * inv) >> 23) << 42)
              + ((uint64_t)(((int64_t)((int32_t)dcb1 * y2 - (int32_t)dcc1 * y1) * inv) >> 23) << 21)
              + (uint64_t)(((int64_t)((int32_t)g->dcb2 * y2 - (int32_t)g->dcc2 * y1) * inv) >> 23);
        if (gzn < ((int64_t)1 << 22) && gzn > -((int64_t)1 << 22)) g->gz = (gzn * inv) >> 36;
        else {      /* rare: a divisor made for it alone; a quotient of 2^32 or more
                       (which fx_divisor_trunc32 may refuse) clamps as any beyond INT32_MAX */
            fx_divisor za;
            fx_divisor_make(&za, area2);
            if (!fx_divisor_trunc32(&za, gzn * RSI_SUBONE, &g->gz)) g->gz = gzn < 0 ? -INT32_MAX : INT32_MAX;
            if (g->gz > INT32_MAX) g->gz = INT32_MAX;
            if (g->gz < -INT32_MAX) g->gz = -INT32_MAX;
        }
    } else {
        fx_divisor_make(ad, area2);
        g->gc = ((uint64_t)fx_divisor_trunc(ad, (dcb0 * dy2 - dcc0 * dy1) * ((int64_t)1 << 17)) << 42)
              + ((uint64_t)fx_divisor_trunc(ad, (dcb1 * dy2 - dcc1 * dy1) * ((int64_t)1 << 17)) << 21)
              + (uint64_t)fx_divisor_trunc(ad, (g->dcb2 * dy2 - g->dcc2 * dy1) * ((int64_t)1 << 17));
        g->gz = fx_divisor_trunc(ad, gzn * RSI_SUBONE);
        if (g->gz > INT32_MAX) g->gz = INT32_MAX;
        if (g->gz < -INT32_MAX) g->gz = -INT32_MAX;
    }
#if RSI_REG64
    g->prg_b = dcb0 * ((int64_t)1 << 32) + dcb1; g->prg_c = dcc0 * ((int64_t)1 << 32) + dcc1;
#else
    g->dcb0 = (int32_t)dcb0; g->dcb1 = (int32_t)dcb1; g->dcc0 = (int32_t)dcc0; g->dcc1 = (int32_t)dcc1;
#endif
    g->ca = (a->cp << 13) + RS_CBIAS - ((uint64_t)1 << 42);
}

/* Narrow boxes: a row's span [*xl, *xr] found by scanning from px0, e1 stepped by its own
 * x step (the same values as S - e0 - e2, exact integers); *e0, *e2 the edge values at
 * *xl.  0 when the row has no centre inside.  Two instantiations, the same values:
 * gen_scan in 64-bit arithmetic, any box; gen_scan32 in 32-bit arithmetic (two
 * instructions fewer per step and edge on 32-bit cores) for small boxes: their extent is
 * below SMALL <= 2^10 sub-pixels both ways, so every |A_k|, |B_k| < 2^10 (vertex
 * differences), and a scanned centre, at most one column past px1, lies within 2^10 +
 * RSI_SUBONE of vertex a on each axis; so every edge value the scan forms is below
 * 2^10 (2^10 + 2^4) 2 + 1 < 2^22 in magnitude, as are e0r, e2r and S. */
#define GEN_SCAN(NAME, T) \
RSI_INLINE static int NAME(int32_t px0, int32_t px1, T e0r, T e2r, T S, T sx0, T sx2, int32_t *xl, int32_t *xr, \
                           int64_t *e0, int64_t *e2) \
{ \
    T a0 = e0r, a2 = e2r, a1 = S - e0r - e2r; \
    const T sx1 = -(sx0 + sx2); \
    int32_t l = px0, r; \
    while ((a0 | a1 | a2) < 0) { \
        if (++l > px1) return 0; \
        a0 += sx0; a1 += sx1; a2 += sx2; \
    } \
    { \
        T f0 = a0 + sx0, f1 = a1 + sx1, f2 = a2 + sx2; \
        r = l; \
        while (r < px1 && (f0 | f1 | f2) >= 0) { r++; f0 += sx0; f1 += sx1; f2 += sx2; } \
    } \
    *xl = l; *xr = r; *e0 = a0; *e2 = a2; \
    return 1; \
}
GEN_SCAN(gen_scan, int64_t)
GEN_SCAN(gen_scan32, int32_t)
#undef GEN_SCAN

#if RS_SPANV && NARROW <= 8 && !defined(__OPTIMIZE_SIZE__)
/* Narrow small boxes of the plain variants in vector lanes (their own copy, tri_gen_sn;
 * not in builds for size, whose one copy decides small and wide at run time): lane i
 * holds the three edge values at column px0 + i of the current row (gen_scan's a0, a1,
 * a2 there), stepped down the rows by the y steps; bit i of bits is set for the box's
 * columns (i <= px1 - px0).  A row's inside
 * columns are an interval (three half-planes met by a line), so the lowest and highest
 * inside lanes are gen_scan's l and r: the same spans.  Every value a lane takes lies
 * within gen_scan32's bound (below 2^22: a lane's centre is at most NARROW - 1 <= 7
 * columns past px0, within 2^10 + 2^7 sub-pixels of vertex a on each axis, as the box is
 * below SMALL both ways), so the 32-bit lanes are exact; they add modulo 2^32 (unsigned)
 * and take the sign as signed. */
typedef uint32_t gn_v8u __attribute__((vector_size(32)));
typedef int32_t gn_v8i __attribute__((vector_size(32)));
typedef struct gn_rows { gn_v8u e0, e1, e2, y0, y1, y2, bits; } gn_rows;

RSI_INLINE static void gn_rows_make(gn_rows *g, int32_t px0, int32_t px1, int64_t e0r, int64_t e2r, int64_t S,
                                   int64_t sx0, int64_t sx2, int64_t sy0, int64_t sy2)
{
    const gn_v8u io = { 0, 1, 2, 3, 4, 5, 6, 7 };
    const gn_v8u one = { 1, 2, 4, 8, 16, 32, 64, 128 };
    g->e0 = (uint32_t)e0r + io * (uint32_t)sx0;
    g->e2 = (uint32_t)e2r + io * (uint32_t)sx2;
    g->e1 = (uint32_t)(S - e0r - e2r) - io * (uint32_t)(sx0 + sx2);
    g->y0 = io - io + (uint32_t)sy0;
    g->y2 = io - io + (uint32_t)sy2;
    g->y1 = io - io - (uint32_t)(sy0 + sy2);
    g->bits = one & (gn_v8u)(io <= (uint32_t)(px1 - px0));
}

/* This row's inside columns as a bit mask (bit i: column px0 + i), then the lanes
 * stepped to the next row. */
RSI_INLINE static uint32_t gn_row_mask(gn_rows *g)
{
    const gn_v8u out = (gn_v8u)((gn_v8i)(g->e0 | g->e1 | g->e2) >> 31);
    gn_v8u m = g->bits & ~out;
    m |= RS_SHUFFLE(m, m, gn_v8u, 4, 5, 6, 7, 4, 5, 6, 7);
    m |= RS_SHUFFLE(m, m, gn_v8u, 2, 3, 2, 3, 2, 3, 2, 3);
    m |= RS_SHUFFLE(m, m, gn_v8u, 1, 1, 1, 1, 1, 1, 1, 1);
    g->e0 += g->y0; g->e1 += g->y1; g->e2 += g->y2;
    return m[0];
}
#define GN_VEC 1
#else
#define GN_VEC 0
#endif

/* Wide boxes, one edge K + s l (l the column relative to px0; floor((K + s px0) / s) =
 * floor(K / s) + px0: the same centres as from column 0, with no products by px0 to keep
 * across the rows), q the divisor |s|:
 *   s > 0: l >= ceil(-K / s), no limit for K >= 0 (l >= 0), else with m = -K >= 1,
 *     ceil(m / s) = floor((m - 1) / s) + 1, m - 1 = ~K >= 0;
 *   s < 0: l <= floor(K / |s|): none for K < 0, else the truncated quotient;
 *   s == 0: all or none, as K >= 0.
 * In 64 bits, so no clamps (the quotients may lie far outside the box).  0: no column.
 * (~K of a copy of K that GEN_OPAQUE hides from the optimiser: GCC's induction
 * variables would otherwise step ~K of every edge on every row, a derived value it keeps
 * in memory.  K's sign is tested first, then s's: the same cases, fewer instructions.) */
RSI_INLINE static int gen_edge(int64_t s, int64_t K, const fx_divisor *q, int64_t *l, int64_t *r)
{
    if (K < 0) {
        if (s > 0) {
            int64_t k = K;
            GEN_OPAQUE(k);
            const int64_t t = fx_divisor_trunc(q, ~k) + 1;
            if (t > *l) *l = t;
        } else return 0;
    } else if (s < 0) {
        const int64_t t = fx_divisor_trunc(q, K);
        if (t < *r) *r = t;
    }
    return 1;
}

/* gen_edge for small boxes where the target divides 32-bit integers (RSI_IDIV32):
 * |K| < 2^22 and |s| < 2^14 (gen_scan32's bounds), the same quotients by C's
 * unsigned 32-bit `/`, whose truncation is fx_divisor_trunc's for these signs. */
RSI_INLINE static int gen_edge32(int32_t s, int32_t K, int32_t *l, int32_t *r)
{
    if (K < 0) {
        if (s > 0) {
            const int32_t t = (int32_t)((uint32_t)~K / (uint32_t)s) + 1;
            if (t > *l) *l = t;
        } else return 0;
    } else if (s < 0) {
        const int32_t t = (int32_t)((uint32_t)K / (0u - (uint32_t)s));
        if (t < *r) *r = t;
    }
    return 1;
}

#if RS_SPANV
/* The lanes at pixel j from the scalar depth Z and packed colour C there, into ZV, RV,
 * GV, BV (depth with its top bit flipped, for the signed compare of 32-bit depths).  R
 * and G are taken with the bits below them in C (shifts, no masks): lane k holds (F + k
 * G) 2^RL + junk modulo 2^32 with F + k G the true field, in [0, 2^21), so adding the
 * junk changes no bit that GS_PX takes.  R: C >> (42 - RL), junk the top RL bits of G's
 * field (< 2^RL, below the multiple of 2^RL: no carry); G: C >> 21, junk R's low bits
 * times 2^21 (above the field, which neither borrows nor carries into them), cut by
 * GS_PX's mask.  B's field has G's bits above it, which GS_PX's BV >> 13 or >> 16 would
 * take: masked. */
#define GS_LANES(ZV, RV, GV, BV, L, RL, Z, C) do { \
        ZV = ((Z) ^ 0x80000000u) + (L).zoff; RV = (uint32_t)((C) >> (42 - (RL))) + (L).roff; \
        GV = (uint32_t)((C) >> 21) + (L).goff; BV = ((uint32_t)(C) & 0x1fffffu) + (L).boff; } while (0)
/* The depth test of a group: its depths OD against the lanes' ZV, the write mask M and
 * the depths to store ND (OD ^ ((OD ^ zz) & M) picks zz where M is set).  32-bit depths:
 * the unsigned compare as a signed one with the top bits flipped (ZV has its top bit
 * flipped already, and odb ^ ZV = OD ^ zz); 16-bit depths (Z16): both sides below 2^16,
 * a signed compare (the flipped top bit of ZV lies above the 16 bits that the shift by
 * 14 and the mask take). */
#define GS_TEST(OD, ND, M, ZV, Z16) do { \
        if (Z16) { const gs_v4u zz_ = ((ZV) >> 14) & 0xffffu; \
                   M = (gs_v4u)((gs_v4i)zz_ > (gs_v4i)(OD)); ND = (OD) ^ (((OD) ^ zz_) & (M)); } \
        else { const gs_v4u odb_ = (OD) ^ 0x80000000u; \
               M = (gs_v4u)((gs_v4i)(ZV) > (gs_v4i)odb_); ND = (OD) ^ ((odb_ ^ (ZV)) & (M)); } } while (0)
/* The pixels of lanes RV, GV, BV, the bits of each field that px_pack takes: XRGB8888
 * bits 13..20 (R's at 16..23 after the lanes' << 3, which saves a shift), RGB565 (C565)
 * bits 16..20, 15..20, 16..20. */
#define GS_PX(RV, GV, BV, C565) (!(C565) ? ((RV) & 0xff0000u) | (((GV) >> 5) & 0xff00u) | ((BV) >> 13) \
                                 : (((RV) >> 5) & 0xf800u) | (((GV) >> 10) & 0x07e0u) | ((BV) >> 16))
#else
typedef struct gs_lanes { int unused; } gs_lanes;      /* (no vector spans) */
#define GS_MASKED 0
#endif

/* The plain span (no texture, no counting): n >= 1 pixels ending at ze / ce (depth and
 * colour one past the last pixel), depth z and packed colour col at the first, steps gzu
 * and gc per pixel: depth test, colour step, write.
 * With RS_SPANV and n >= 8: GS_N pixels per group, lane l of the group at pixel j holding
 * pixel j + l: groups at pixels 0, GS_N, .. below n - GS_N, then one at n - GS_N
 * (overlapping the one before it unless GS_N divides n), so every access is inside the
 * span and there is no scalar tail.  The same pixels as the scalar loop: its depth is z
 * + j gzu modulo 2^32, as in the lanes; its colour fields are exact (their true values
 * lie in [0, 2^21), RS_CBIAS in raster.c), field k at pixel j being F_k + j G_k (F_k that
 * of col, G_k the signed gradient), which the lanes compute modulo 2^32, exactly since
 * the result lies in [0, 2^21) (R times 8 for XRGB8888: below 2^24), and the pixel takes
 * the same bits of each field as px_pack.  Each pixel's test reads and writes only its
 * own depth (the pixels of a span are distinct), so GS_N at once give the same bytes;
 * lanes that fail write back what they read.  The last group is loaded and computed
 * before the others are stored: where it overlaps the group before it, both start from
 * the same bytes and so store the same ones (loading it after that store would give the
 * same bytes too, but a load partly overlapping a just-made store waits for it).
 * GS_MASKED (x86-64-v3), XRGB8888 with 32-bit depth and n >= GS_MASK_MIN: groups at
 * pixels 0, 8, .. and, where 8 does not divide n, a last group of the n mod 8 pixels
 * left, through AVX2's masked load and stores (vpmaskmovd), which neither read nor
 * write a lane outside the span nor fault on one; so no overlapping group with lanes of
 * its own, and spans of four to seven pixels in one group, not the scalar loop.  The
 * same pixels: each lane inside the span is the scalar loop's pixel, as above, and the
 * write mask is the depth test's and the span's.  (The 16-bit layouts keep the
 * overlapping group: AVX2 has no 16-bit masked store.)
 * L / lanes: the triangle's lane constants, made at its first such span. */
RSI_INLINE static void gen_span_plain(void *const ze, void *const ce, int32_t n, uint32_t z, uint64_t col,
                                     uint32_t gzu, uint64_t gc, gs_lanes *L, int *lanes, const int vf)
{
    ptrdiff_t j = -(ptrdiff_t)n;      /* n >= 1; one counter to 0 */
#if GS_MASKED
    if (!(vf & (VF_565 | VF_Z16)) && n >= GS_MASK_MIN) {
        const gs_v4u io = { 0, 1, 2, 3, 4, 5, 6, 7 };
        gs_v4u zv, rv, gv, bv, m, k80, kr, kg;
        if (!*lanes) { gs_lanes_make(L, gzu, gc, 3); *lanes = 1; }
        GS_LANES(zv, rv, gv, bv, *L, 3, z, col);
        k80 = L->k80; kr = L->kr; kg = L->kg;
        /* GS_PX's XRGB8888 pixel with the masks from L */
#define GS_PX888(RV, GV, BV) (((RV) & kr) | (((GV) >> 5) & kg) | ((BV) >> 13))
        if (j <= -GS_N) {
            const gs_v4u zstep = L->zstep, rstep = L->rstep, gstep = L->gstep, bstep = L->bstep;
            do {
                gs_v4u od, op, odb;
                GS_LD(od, z_at(ze, j, vf), 4); GS_LD(op, px_at(ce, j, vf), 4);
                odb = od ^ k80;
                m = (gs_v4u)((gs_v4i)zv > (gs_v4i)odb);
                GS_ST(z_at(ze, j, vf), od ^ ((odb ^ zv) & m), 4);
                GS_ST(px_at(ce, j, vf), op ^ ((op ^ GS_PX888(rv, gv, bv)) & m), 4);
                zv += zstep; rv += rstep; gv += gstep; bv += bstep;
            } while ((j += GS_N) <= -GS_N);
        }
        if (j < 0) {        /* 1 <= -j < GS_N pixels left: lane mask lm */
            const gs_v4i lm = (gs_v4i)io < (int32_t)-j;
            const gs_v4u od = (gs_v4u)__builtin_ia32_maskloadd256((const gs_v4i *)z_at(ze, j, vf), lm);
            m = (gs_v4u)((gs_v4i)zv > (gs_v4i)(od ^ k80)) & (gs_v4u)lm;
            __builtin_ia32_maskstored256((gs_v4i *)z_at(ze, j, vf), (gs_v4i)m, (gs_v4i)(zv ^ k80));
            __builtin_ia32_maskstored256((gs_v4i *)px_at(ce, j, vf), (gs_v4i)m, (gs_v4i)GS_PX888(rv, gv, bv));
        }
#undef GS_PX888
        return;
    }
#endif
#if RS_SPANV
    if (n >= 8) {       /* (>= GS_N: the groups need GS_N pixels) */
        const size_t zb = z_bytes(vf), cb = px_bytes(vf);
        const int rl = (vf & VF_565) ? 0 : 3;     /* R << 3: see GS_PX */
        const uint32_t tl = (uint32_t)n - GS_N;
        void *const ze4 = z_at(ze, -GS_N, vf), *const ce4 = px_at(ce, -GS_N, vf);
        gs_v4u ndl, npl, m;
        if (!*lanes) { gs_lanes_make(L, gzu, gc, rl); *lanes = 1; }
        {
            const uint32_t zl = z + tl * gzu;
            const uint64_t cl = col + tl * gc;
            gs_v4u zv, rv, gv, bv, od, op;
            GS_LD(od, ze4, zb); GS_LD(op, ce4, cb);
            GS_LANES(zv, rv, gv, bv, *L, rl, zl, cl);
            GS_TEST(od, ndl, m, zv, vf & VF_Z16);
            npl = op ^ ((op ^ GS_PX(rv, gv, bv, vf & VF_565)) & m);
        }
        if (j < -GS_N) {
            const gs_v4u zstep = L->zstep, rstep = L->rstep, gstep = L->gstep, bstep = L->bstep;
            gs_v4u zv, rv, gv, bv;
            /* the groups at ze4 + k, k = j + GS_N .. < 0 (inside the span): the loop
             * test is the sign of k */
            ptrdiff_t k = j + GS_N;
            GS_LANES(zv, rv, gv, bv, *L, rl, z, col);
            do {
                gs_v4u od, op, nd;
                GS_LD(od, z_at(ze4, k, vf), zb); GS_LD(op, px_at(ce4, k, vf), cb);
                GS_TEST(od, nd, m, zv, vf & VF_Z16);
                GS_ST(z_at(ze4, k, vf), nd, zb);
                GS_ST(px_at(ce4, k, vf), op ^ ((op ^ GS_PX(rv, gv, bv, vf & VF_565)) & m), cb);
                zv += zstep; rv += rstep; gv += gstep; bv += bstep;
            } while ((k += GS_N) < 0);
        }
        GS_ST(ze4, ndl, zb);
        GS_ST(ce4, npl, cb);
        return;
    }
#else
    (void)L; (void)lanes;
#endif
    do {
        const uint32_t zz = z_store(z, vf);
        void *const zp = z_at(ze, j, vf);
        if (zz > z_get(zp, vf)) { z_put(zp, zz, vf); px_put(px_at(ce, j, vf), px_pack(col, vf), vf); }
        z += gzu; col += gc;
    } while (++j);
}

/* The textured and counting spans: n pixels from zp / cp, depth z and colour col at the
 * first; textured: the perspective-correct coordinates at every pixel from its exact
 * edge values te0, te2 (stepped by sx0, sx2; e1 = S - e0 - e2), as gen_tri says. */
typedef struct gen_tex_t {
    const rs_texture *tx;
    int32_t esh;
    int64_t qa, qb, qc, qua, qub, quc, qva, qvb, qvc;
} gen_tex_t;

RSI_INLINE static void gen_span_other(void *zp, void *cp, int32_t n, uint32_t z, uint64_t col, uint32_t gzu,
                                     uint64_t gc, const gen_tex_t *tx, int64_t te0, int64_t te2, int64_t S,
                                     int64_t sx0, int64_t sx2, const int vf)
{
    int32_t i;
    for (i = 0; i < n; i++) {
        if (vf & VF_COUNT) {
            ((uint32_t *)cp)[i] += 1;
        } else {
            const uint32_t zz = z_store(z, vf);
            void *const zq = z_at(zp, i, vf);
            if (zz > z_get(zq, vf)) {
                z_put(zq, zz, vf);
                if (vf & VF_TEX) {
                    const int64_t f0 = te0 >> tx->esh, f2 = te2 >> tx->esh, f1 = (S - te0 - te2) >> tx->esh;
                    const int64_t den = f1 * tx->qa + f2 * tx->qb + f0 * tx->qc;
                    px_put(px_at(cp, i, vf), px_pack24(tex_mod(tex_fetch(tx->tx, tex_div(f1 * tx->qua + f2 * tx->qub + f0 * tx->quc, den),
                                                                         tex_div(f1 * tx->qva + f2 * tx->qvb + f0 * tx->qvc, den)), col), vf), vf);
                } else {
                    px_put(px_at(cp, i, vf), px_pack(col, vf), vf);
                }
            }
        }
        z += gzu; col += gc;
        if (vf & VF_TEX) { te0 += sx0; te2 += sx2; }
    }
}

/* Triangles whose bounding box has more than TINY_W x TINY_H candidate centres (kept
 * out of tri_raster so that the tiny path's code stays small).  small (box below SMALL
 * in both directions: gradients and row starts through a reciprocal), wide (more than
 * NARROW columns: spans by division, else by scanning) and one (py0 == py1: no row loop)
 * are constants of each out-of-line copy (tri_general); for a given triangle and band
 * the values are the same whichever copy draws it.  Row starts are computed exactly from
 * the barycentric weights at the first inside centre of the row (no stepping across
 * rows), so a row's values do not depend on which band it is drawn in. */
RSI_INLINE static void gen_tri(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                              int32_t px0, int32_t px1, int32_t py0, int32_t py1,
                              const int small, const int wide, const int one, const int vf)
{
    int32_t py;
    int64_t dx1, dy1, dx2, dy2, area2, A0, A1, A2, B0, B1, B2, S, e0r, e2r, sx0, sx2, sy0, sy2;
    int64_t bias0, bias1, bias2;
    const int32_t w = bd->w;
    /* small boxes on 32-bit targets: the set-up and the row spans in 32-bit arithmetic,
     * the same values (on 64-bit targets the 64-bit forms cost no more) */
    const int small32 = small && !RSI_REG64;
    /* narrow small boxes: the rows' spans from vector lanes (gn_rows) where there are such */
    const int gnv = GN_VEC && !VF_SLOW(vf) && !wide && small;

    if (small32) {
        /* the box is below SMALL <= 2^10 sub-pixels both ways: vertex differences below
         * 2^10, area2 below 2^21, and (below) the row start's edge values below 2^22
         * (gen_scan32's bound): 32-bit products, the same values */
        const int32_t x1 = b->x - a->x, y1 = b->y - a->y, x2 = c->x - a->x, y2 = c->y - a->y;
        dx1 = x1; dy1 = y1; dx2 = x2; dy2 = y2;
        area2 = x1 * y2 - x2 * y1;
    } else {
        dx1 = (int64_t)b->x - a->x; dy1 = (int64_t)b->y - a->y;
        dx2 = (int64_t)c->x - a->x; dy2 = (int64_t)c->y - a->y;
        area2 = dx1 * dy2 - dx2 * dy1;
    }
    if (!is_front(area2)) {
        if (area2 == 0 || bd->cull) return;
    } else {
        const rs_cvert *t = b;
        int64_t u;
        b = c; c = t;
        u = dx1; dx1 = dx2; dx2 = u;
        u = dy1; dy1 = dy2; dy2 = u;
        area2 = -area2;
    }
    bd->tris++;
    /* Edge functions (Pineda 1988) as in tri_tiny (raster_tiny.h), in 64 bits: edge 0 =
     * a->b (the weight of c), 1 = b->c (weight of a), 2 = c->a (weight of b), biased by
     * the top-left rule (tl_bias64); inside iff all e_k >= 0, e1 = S - e0 - e2. */
    A0 = -dy1; B0 = dx1;
    A2 = dy2; B2 = -dx2;
    A1 = -(A0 + A2); B1 = -(B0 + B2);
    if (small32) {    /* |A_k|, |B_k| < SMALL <= 2^10: tl_bias16's bound, the same biases */
        bias0 = tl_bias16((int32_t)A0, (int32_t)B0);
        bias1 = tl_bias16((int32_t)A1, (int32_t)B1);
        bias2 = tl_bias16((int32_t)A2, (int32_t)B2);
    } else {
        bias0 = tl_bias64(A0, B0);
        bias1 = tl_bias64(A1, B1);
        bias2 = tl_bias64(A2, B2);
    }
    S = area2 - bias0 - bias1 - bias2;
    if (small32) {
        const int32_t ox = px0 * RSI_SUBONE + RSI_HALF - a->x, oy = py0 * RSI_SUBONE + RSI_HALF - a->y;
        e0r = (int32_t)A0 * ox + (int32_t)B0 * oy - (int32_t)bias0;
        e2r = (int32_t)A2 * ox + (int32_t)B2 * oy - (int32_t)bias2;
    } else {
        int64_t ox = (int64_t)px0 * RSI_SUBONE + RSI_HALF - a->x, oy = (int64_t)py0 * RSI_SUBONE + RSI_HALF - a->y;
        e0r = A0 * ox + B0 * oy - bias0;
        e2r = A2 * ox + B2 * oy - bias2;
    }
    sx0 = A0 * RSI_SUBONE; sx2 = A2 * RSI_SUBONE; sy0 = B0 * RSI_SUBONE; sy2 = B2 * RSI_SUBONE;

    {
        gen_grad_t g = { 0 };
        fx_divisor ad = FX_DIVISOR_INIT;     /* area2, made for large triangles only */
        gen_tex_t tx = { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };
        gs_lanes L;             /* made at the first span of eight or more pixels */
        int lanes = 0;
        if (vf & VF_TEX) {
            /* Perspective-correct texture coordinates at every pixel from its exact edge
             * values: with q = d >> tsh (1/w, <= 2^16) and the edge values e (barycentric
             * weights times area2, shifted right by esh so that they stay below 2^20),
             *   u = (e1 qa ua + e2 qb ub + e0 qc uc) / (e1 qa + e2 qb + e0 qc),
             * products < 2^58 (u <= 2^22 texels Q8).  The edge values step exactly, so
             * there is no drift along long spans; the only errors are the 2^-20
             * truncation of the weights and the 16 bits of q. */
            const int32_t tsh = tex_shift(a->d, b->d, c->d);
            tx.tx = bd->f->tex;
            tx.qa = a->d >> tsh; tx.qb = b->d >> tsh; tx.qc = c->d >> tsh;
#if RS_TEX_FIELDS
            tx.qua = tx.qa * a->u; tx.qub = tx.qb * b->u; tx.quc = tx.qc * c->u;
            tx.qva = tx.qa * a->v; tx.qvb = tx.qb * b->v; tx.qvc = tx.qc * c->v;
#endif
            while ((area2 >> tx.esh) >= ((int64_t)1 << 20)) tx.esh++;
        }
        /* wide boxes: the row spans' divisors |16 A|; a zero step is never divided by,
         * so with a 64-bit divide (C's `/`, no reciprocal) its divisor may stay 0
         * (branch-free), without one it is 1 (fx_recip_make needs d > 0) */
        fx_divisor q0 = FX_DIVISOR_INIT, q1 = FX_DIVISOR_INIT, q2 = FX_DIVISOR_INIT;    /* made when wide */
        if (wide && !(small32 && RSI_IDIV32)) {
            const int64_t s1_ = sx0 + sx2;
#if BR_DIV64_NATIVE
            fx_divisor_make(&q0, sx0 < 0 ? -sx0 : sx0);
            fx_divisor_make(&q1, s1_ < 0 ? -s1_ : s1_);
            fx_divisor_make(&q2, sx2 < 0 ? -sx2 : sx2);
#else
            fx_divisor_make(&q0, sx0 < 0 ? -sx0 : sx0 ? sx0 : 1);
            fx_divisor_make(&q1, s1_ < 0 ? -s1_ : s1_ ? s1_ : 1);
            fx_divisor_make(&q2, sx2 < 0 ? -sx2 : sx2 ? sx2 : 1);
#endif
        }
        /* the row's colour and depth, stepped across the rows (one past the band's last
         * row at the end at most); the band's fields are read once, before the loop (the
         * pixel stores may alias them) */
        uint8_t *crow = bd->color + (size_t)(py0 - bd->y0) * bd->stride;
        void *zrow = z_at(bd->depth, (ptrdiff_t)((size_t)(py0 - bd->y0) * (size_t)w), vf);
        const size_t cstride = bd->stride, zstride = (size_t)w * z_bytes(vf);
#if GN_VEC
        gn_rows gn;
        if (gnv) gn_rows_make(&gn, px0, px1, e0r, e2r, S, sx0, sx2, sy0, sy2);
#endif
        if (!one) gen_grad(&g, &ad, a, b, c, dy1, dy2, area2, small);
        if (one) py1 = py0;
        for (py = py0; py <= py1; py++, e0r += sy0, e2r += sy2, crow += cstride, zrow = (uint8_t *)zrow + zstride) {
            int32_t xl = px0, xr = px1;
            int64_t e0, e2;
            if (gnv) {
#if GN_VEC
                const uint32_t mk = gn_row_mask(&gn);
                int32_t l, r;
                if (!mk) continue;
                l = __builtin_ctz(mk); r = 31 - __builtin_clz(mk);
                xl = px0 + l; xr = px0 + r;
                e0 = e0r + sx0 * l; e2 = e2r + sx2 * l;
#endif
            } else if (!wide) {
                if (small32 ? !gen_scan32(px0, px1, (int32_t)e0r, (int32_t)e2r, (int32_t)S, (int32_t)sx0,
                                          (int32_t)sx2, &xl, &xr, &e0, &e2)
                            : !gen_scan(px0, px1, e0r, e2r, S, sx0, sx2, &xl, &xr, &e0, &e2))
                    continue;
            } else if (small32 && RSI_IDIV32) {
                const int32_t k0 = (int32_t)e0r, k2 = (int32_t)e2r, s0 = (int32_t)sx0, s2 = (int32_t)sx2;
                int32_t l = 0, r = px1 - px0;
                if (!gen_edge32(s0, k0, &l, &r) || !gen_edge32(-(s0 + s2), (int32_t)S - k0 - k2, &l, &r)
                    || !gen_edge32(s2, k2, &l, &r) || l > r)
                    continue;
                xl = px0 + l; xr = px0 + r;
                e0 = k0 + s0 * l; e2 = k2 + s2 * l;
            } else {
                int64_t l = 0, r = px1 - px0;
                if (!gen_edge(sx0, e0r, &q0, &l, &r) || !gen_edge(-(sx0 + sx2), S - e0r - e2r, &q1, &l, &r)
                    || !gen_edge(sx2, e2r, &q2, &l, &r) || l > r)
                    continue;
                xl = px0 + (int32_t)l; xr = px0 + (int32_t)r;     /* 0 <= l <= r <= px1 - px0 */
                e0 = e0r + sx0 * l; e2 = e2r + sx2 * l;
            }
            if (one) gen_grad(&g, &ad, a, b, c, dy1, dy2, area2, small);
            {
                /* Exact barycentric weights at (xl, py): b gets edge 2, c gets edge 0 (Q22).
                 * The row start's R and G in one pair of products: with v_k = dcb_k w1 +
                 * dcc_k w2 (|v_k| <= 255 (w1 + w2) < 2^30, as w1, w2 >= 0 and w1 + w2 <=
                 * 2^22: the weights of inside centres, e0 + e2 <= S <= area2), rg = v_R 2^32
                 * + v_G + 2^30 (every partial sum below 2^63 in magnitude) has v_G + 2^30 in
                 * [0, 2^32) as its low 32 bits, so rg >> 41 = floor(v_R / 2^9) and (low 32
                 * bits) >> 9 = floor(v_G / 2^9) + 2^21, whose 2^21 (times 2^21) ca takes back.
                 * 32-bit targets form each v_k alone in 32 bits (|v_k| < 2^30), the same
                 * fields: three pairs of one-instruction products instead of 64-bit ones. */
                int64_t w1, w2;
                uint64_t col;
                uint32_t z;
                const uint32_t gzu = (uint32_t)g.gz;
                const int32_t n = xr - xl + 1;
                if (small32) { w1 = ((int64_t)(int32_t)e2 * g.inv) >> 18; w2 = ((int64_t)(int32_t)e0 * g.inv) >> 18; }
                else if (small) { w1 = (e2 * g.inv) >> 18; w2 = (e0 * g.inv) >> 18; }
                else { w1 = fx_divisor_trunc(&ad, e2 * ((int64_t)1 << 22)); w2 = fx_divisor_trunc(&ad, e0 * ((int64_t)1 << 22)); }
                z = (uint32_t)((int64_t)a->d + ((g.dzb * w1 + g.dzc * w2) >> 22));
                {
#if RSI_REG64
                    const int64_t rg = g.prg_b * w1 + g.prg_c * w2 + ((int64_t)1 << 30);
                    col = g.ca + ((uint64_t)(rg >> 41) << 42) + ((uint64_t)((uint32_t)rg >> 9) << 21)
                          + (uint64_t)((g.dcb2 * w1 + g.dcc2 * w2) >> 9);
#else
                    const int32_t u1 = (int32_t)w1, u2 = (int32_t)w2;
                    const int32_t vr = g.dcb0 * u1 + g.dcc0 * u2, vg = g.dcb1 * u1 + g.dcc1 * u2;
                    const int32_t vb = (int32_t)g.dcb2 * u1 + (int32_t)g.dcc2 * u2;
                    col = g.ca + ((uint64_t)(int64_t)(vr >> 9) << 42)
                          + ((uint64_t)(uint32_t)((vg >> 9) + (1 << 21)) << 21) + (uint64_t)(int64_t)(vb >> 9);
#endif
                }
                bd->pixels += (uint32_t)n;
                if (VF_SLOW(vf))
                    gen_span_other(z_at(zrow, xl, vf), px_at(crow, xl, vf), n, z, col, gzu, g.gc, &tx, e0, e2, S,
                                   sx0, sx2, vf);
                else
                    gen_span_plain(z_at(zrow, xl + n, vf), px_at(crow, xl + n, vf), n, z, col, gzu, g.gc, &L,
                                   &lanes, vf);
            }
        }
    }
}

/* tri_general, the general path's entry from tri_box (which finds small and wide), and
 * its out-of-line copies, one `case` per variant.  The plain variants have a copy per
 * case, so that GCC folds the case's branches and allocates registers for it alone:
 * small and wide, and of those the boxes of one row (mostly thin slivers near the
 * horizon); small and narrow; large.  Textured and counting variants, and builds for
 * size (-Os: the boards with little flash; the copies are 2-3 KB each per variant): one
 * copy, small and wide at run time. */
#define GEN_CASE(V, SMALL, WIDE, ONE) \
    case V: if (RS_BUILT(V)) gen_tri(bd, a, b, c, px0, px1, py0, py1, SMALL, WIDE, ONE, V); return
RSI_NOINLINE static void tri_gen_any(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                    int32_t px0, int32_t px1, int32_t py0, int32_t py1, int small, int wide, int vf)
{
    switch (vf) {
#if defined(__OPTIMIZE_SIZE__)
    GEN_CASE(V_888_Z32, small, wide, 0);
    GEN_CASE(V_888_Z16, small, wide, 0);
    GEN_CASE(V_565_Z16, small, wide, 0);
    GEN_CASE(V_565_Z32, small, wide, 0);
#endif
    GEN_CASE(V_888_Z32_TEX, small, wide, 0);
    GEN_CASE(V_888_Z16_TEX, small, wide, 0);
    GEN_CASE(V_565_Z16_TEX, small, wide, 0);
    GEN_CASE(V_565_Z32_TEX, small, wide, 0);
    GEN_CASE(V_COUNT, small, wide, 0);
    default: return;
    }
}
#if !defined(__OPTIMIZE_SIZE__)
/* small and wide */
RSI_NOINLINE static void tri_gen_sw(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                   int32_t px0, int32_t px1, int32_t py0, int32_t py1, int vf)
{
    switch (vf) {
    GEN_CASE(V_888_Z32, 1, 1, 0);
    GEN_CASE(V_888_Z16, 1, 1, 0);
    GEN_CASE(V_565_Z16, 1, 1, 0);
    GEN_CASE(V_565_Z32, 1, 1, 0);
    default: return;
    }
}
/* small and wide, one row (py1 = py0) */
RSI_NOINLINE static void tri_gen_sw1(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                    int32_t px0, int32_t px1, int32_t py0, int vf)
{
    const int32_t py1 = py0;
    switch (vf) {
    GEN_CASE(V_888_Z32, 1, 1, 1);
    GEN_CASE(V_888_Z16, 1, 1, 1);
    GEN_CASE(V_565_Z16, 1, 1, 1);
    GEN_CASE(V_565_Z32, 1, 1, 1);
    default: return;
    }
}
/* small and narrow */
RSI_NOINLINE static void tri_gen_sn(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                   int32_t px0, int32_t px1, int32_t py0, int32_t py1, int vf)
{
    switch (vf) {
    GEN_CASE(V_888_Z32, 1, 0, 0);
    GEN_CASE(V_888_Z16, 1, 0, 0);
    GEN_CASE(V_565_Z16, 1, 0, 0);
    GEN_CASE(V_565_Z32, 1, 0, 0);
    default: return;
    }
}
/* large (wide at run time) */
RSI_NOINLINE static void tri_gen_l(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                  int32_t px0, int32_t px1, int32_t py0, int32_t py1, int wide, int vf)
{
    switch (vf) {
    GEN_CASE(V_888_Z32, 0, wide, 0);
    GEN_CASE(V_888_Z16, 0, wide, 0);
    GEN_CASE(V_565_Z16, 0, wide, 0);
    GEN_CASE(V_565_Z32, 0, wide, 0);
    default: return;
    }
}
#endif
#undef GEN_CASE

RSI_INLINE static void tri_general(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                  int32_t px0, int32_t px1, int32_t py0, int32_t py1, int small, int wide,
                                  const int vf)
{
#if !defined(__OPTIMIZE_SIZE__)
    if (!VF_SLOW(vf)) {
        if (!small) tri_gen_l(bd, a, b, c, px0, px1, py0, py1, wide, vf);
        else if (wide && py0 == py1) tri_gen_sw1(bd, a, b, c, px0, px1, py0, vf);
        else if (wide) tri_gen_sw(bd, a, b, c, px0, px1, py0, py1, vf);
        else tri_gen_sn(bd, a, b, c, px0, px1, py0, py1, vf);
        return;
    }
#endif
    tri_gen_any(bd, a, b, c, px0, px1, py0, py1, small, wide, vf);
}

#endif
