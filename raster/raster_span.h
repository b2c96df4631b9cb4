/* raster/raster_span.h — the general path's spans (raster_general.h): a row's pixels from
 * its first pixel's depth and packed colour and their steps along the row.  raster.c's own,
 * included once, before raster_general.h; every function takes the variant as its
 * constant last argument (raster_pixel.h).
 *
 * The plain span (no texture, no counting) is drawn GS_N pixels at a time in 32-bit
 * vector lanes (GCC's generic vectors: SSE2 on x86-64, NEON on AArch64) for spans of
 * eight or more pixels (from four, with masked loads and stores, in the x86-64-v3 copy's
 * XRGB8888 with 32-bit depth: GS_MASKED); shorter spans and targets without such
 * vectors keep the scalar loop (a span's two end groups cost about as many instructions
 * as eight scalar pixels).  Same pixels: see gen_span_plain.  RS_SPANV (core/config.h)
 * chooses. */
#ifndef BR_RASTER_SPAN_H
#define BR_RASTER_SPAN_H

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
    if (!(vf & (VF_565 | VF_Z16 | VF_NOZ)) && n >= GS_MASK_MIN) {
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
    if (n >= 8 && !(vf & VF_NOZ)) {    /* (>= GS_N: the groups need GS_N pixels; without
                                           depth the scalar loop's stores alone) */
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

#endif
