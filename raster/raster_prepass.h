/* raster/raster_prepass.h — the strip pre-pass of the per-triangle code (pp_prepass and
 * what it fills, pp_soa): the set-up and coverage of a chunk's strip pairs in 16-bit
 * vector lanes, which raster_draw.h's strip loop (pp_steps) then shades.  Part of
 * raster.c: included by it once, when RS_PREPASS (targets with GCC's vectors, see the
 * comment above RS_PREPASS there), before the triangle code; it uses raster.c's macros
 * (RS_SHUFFLE, PP_SCHED, RS_VBYTES, TINY_W, TINY_H, RSI_SUB, RSI_HALF, REJECT, SLOW) and band.
 * raster.c's only. */
#ifndef BR_RASTER_PREPASS_H
#define BR_RASTER_PREPASS_H

/* Index of the lowest set bit of m (m != 0), 32 bits (the strip loop's work list). */
static uint32_t ctz32(uint32_t m)
{
    return (uint32_t)__builtin_ctz(m);      /* (RS_PREPASS: GCC or clang) */
}

enum { PK_NONE = 0, PK_QUAD, PK_WIDE, PK_SLOW };
#define PP_STEPS (RS_CHUNK / 2)
#define PP_IN (PP_STEPS + 16)   /* vertex slots 0 .. n rounded up to PP_L (n <= PP_STEPS steps); a multiple of 16 */
#define PP_OFF 32768            /* coordinates are taken as x - PP_OFF: [-32760, 32760] on screen */
#define PP_ROFF (PP_OFF >> RSI_SUB) /* the same in rows and columns */
/* PP_L steps per group: 8 in 128-bit vectors; 16 in the 256-bit ones of x86-64-v3
 * (AVX2; raster/isa.c's second copy), where one group's instructions serve twice the
 * steps (the candidate loop runs over the largest quad box among sixteen lanes instead
 * of eight, which costs far less than the halved set-up saves).  Not at SSE2 or NEON:
 * GCC splits 256-bit generic vectors into pairs of 128-bit ones and runs out of
 * registers, which about doubles the pre-pass's cost.  The gather's transposition
 * stays in 128-bit vectors (pp_h8), eight slots at a time. */
#define PP_L (RS_VBYTES / 2)
typedef int16_t pp_v8 __attribute__((vector_size(2 * PP_L)));
typedef uint16_t pp_v8u __attribute__((vector_size(2 * PP_L)));
typedef int16_t pp_v8un __attribute__((vector_size(2 * PP_L), aligned(2)));
typedef int16_t pp_h8 __attribute__((vector_size(16)));
typedef int16_t pp_h8un __attribute__((vector_size(16), aligned(2)));
/* A chunk's steps: vertices at even / odd strip positions (step j: v0 = even j, v1 =
 * odd j, v2 = even j+1, v3 = odd j+1; their cache entries, then the low 16 bits of x
 * and y and the outcodes), then the pre-pass's results per step (the fields after kind
 * as pp_prepass describes). */
typedef struct pp_soa {
    const rs_cvert *ve[PP_IN], *vo[PP_IN];
    int16_t xe[PP_IN], xo[PP_IN], ye[PP_IN], yo[PP_IN], ce[PP_IN], co[PP_IN];
    int16_t kind[PP_STEPS], px0[PP_STEPS], py0[PP_STEPS], nx[PP_STEPS], ny[PP_STEPS];
    int16_t a1[PP_STEPS], a2[PP_STEPS], nt[PP_STEPS];
    /* PK_QUAD steps: the coverage of T1 / T2 (bit 8 j + i: candidate (px0 + i, py0 + j)
     * of the step's nx x ny box), and for
     * each covered candidate the two edge values shading needs: e[cand][0 / 1][step]
     * T1's e20, e01 (the weights of v1, v2), e[cand][2 / 3][step] T2's e32, eT (of v1,
     * v3) */
    uint32_t m1[PP_STEPS], m2[PP_STEPS];
    int16_t e[TINY_W * TINY_H][4][PP_STEPS];
    uint32_t work;      /* the strip loop's work list (the end of pp_prepass) */
} pp_soa;
/* The strip loop reads a step's fields (raster_draw.h's pp_steps) as q.F[st] where one
 * operand adds a base, a scaled index and a displacement (x86); elsewhere (ARM: an
 * index register or an offset, not both) from a base per field size, st added once. */
#if defined(__x86_64__) || defined(__i386__)
#define PP_IDX 1
#else
#define PP_IDX 0
#endif
#define PPL(A, K) (*(const pp_v8un *)(const void *)&(A)[K])
#define PPS(A, K, V) (*(pp_v8un *)(void *)&(A)[K] = (V))
/* wrapping arithmetic (unsigned lanes); comparisons and >> on the signed ones */
#define VU(x) ((pp_v8u)(x))
#define VI(x) ((pp_v8)(x))
#define VADD(a, b) VI(VU(a) + VU(b))
#define VSUB(a, b) VI(VU(a) - VU(b))
#define VMUL(a, b) VI(VU(a) * VU(b))
#define VSEL(m, a, b) (((a) & (m)) | ((b) & ~(m)))
/* macros, not functions: a vector argument or result needs vector registers, which
 * check-nofloat.sh's -mgeneral-regs-only build does not have */
#if defined(__AVX2__) && !defined(__clang__)
#define PP_MIN(a, b) __builtin_ia32_pminsw256((a), (b))
#define PP_MAX(a, b) __builtin_ia32_pmaxsw256((a), (b))
#elif defined(__SSE2__) && !defined(__clang__)     /* GCC's names for pminsw / pmaxsw */
#define PP_MIN(a, b) __builtin_ia32_pminsw128((a), (b))
#define PP_MAX(a, b) __builtin_ia32_pmaxsw128((a), (b))
#else
#define PP_MIN(a, b) VSEL((a) < (b), (a), (b))
#define PP_MAX(a, b) VSEL((a) > (b), (a), (b))
#endif

/* The largest lane of V, in every lane (three rounds of swaps and maxima) */
#if PP_L == 16
#define PP_HMAX1(V, ...) PP_MAX((V), RS_SHUFFLE((V), (V), pp_v8, __VA_ARGS__))
#define PP_HMAX(V) PP_HMAX1(PP_HMAX1(PP_HMAX1(PP_HMAX1((V), 8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2, 3, 4, 5, 6, 7), \
    4, 5, 6, 7, 0, 1, 2, 3, 12, 13, 14, 15, 8, 9, 10, 11), 2, 3, 0, 1, 6, 7, 4, 5, 10, 11, 8, 9, 14, 15, 12, 13), \
    1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14)
#else
#define PP_HMAX1(V, A, B, C, D, E, F, G, H) PP_MAX((V), RS_SHUFFLE((V), (V), pp_v8, A, B, C, D, E, F, G, H))
#define PP_HMAX(V) PP_HMAX1(PP_HMAX1(PP_HMAX1((V), 4, 5, 6, 7, 0, 1, 2, 3), 2, 3, 0, 1, 6, 7, 4, 5), 1, 0, 3, 2, 5, 4, 7, 6)
#endif

/* The strip loop's work list from the kinds (the end of pp_prepass).  Eight lanes:
 * PP_BITS2(M, V, W), bit i of M for each lane i of V, bit 8 + i for W (vectors of all-ones
 * or zero lanes; packsswb and pmovmskb, elsewhere lane i's bit, the lanes folded with or;
 * two groups per call, which is cheaper than one).  Sixteen (AVX2): PP_BITS(M,
 * V), bit i for lane i, from the bytes' top bits (vpmovmskb), every other one (pext). */
#if PP_L == 16
typedef char pp_v32c __attribute__((vector_size(32)));
#define PP_BITS(M, V) ((M) = __builtin_ia32_pext_si((uint32_t)__builtin_ia32_pmovmskb256((pp_v32c)(V)), 0x55555555u))
#elif defined(__SSE2__) && !defined(__clang__)
typedef char pp_v16c __attribute__((vector_size(16)));
#define PP_BITS2(M, V, W) ((M) = (uint32_t)__builtin_ia32_pmovmskb128((pp_v16c)__builtin_ia32_packsswb128((V), (W))))
#else
#define PP_BITS2(M, V, W) do {                                                         \
        const pp_v8 b_ = ((V) & (pp_v8){ 1, 2, 4, 8, 16, 32, 64, 128 })                \
                         | ((W) & (pp_v8){ 256, 512, 1024, 2048, 4096, 8192, 16384, -32768 }); \
        uint64_t w_[2];                                                                \
        memcpy(w_, &b_, sizeof w_);                                                    \
        w_[0] |= w_[1]; w_[0] |= w_[0] >> 32;                                          \
        (M) = (uint32_t)(w_[0] | w_[0] >> 16) & 0xffffu;                               \
    } while (0)
#endif

/* The 16-bit words of each 32-bit field of W in little-endian order (low word first):
 * swapped on big-endian targets, nothing to do on the others. */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#define PP_LEW(W) ((W) = RS_SHUFFLE((W), (W), pp_h8, 1, 0, 3, 2, 5, 4, 7, 6))
#else
#define PP_LEW(W) ((void)0)
#endif
/* Eight cache entries' first 16 bytes (P[0 .. 7]; x, y, d, c: as 16-bit words x, x >> 16,
 * y, y >> 16, d, d >> 16, c, c >> 16 after PP_LEW) transposed into slots
 * K .. K + 7 of X, Y, C: the low words of x and y less PP_OFF (modulo 2^16: the top bit
 * flipped, fl holds PP_OFF's flip in every lane) and c >> 16 (the outcode byte above the
 * colour's red), by interleaving words, pairs of words and halves (17 shuffles). */
#define PP_ZIP(A, B, I0, I1, I2, I3, I4, I5, I6, I7) RS_SHUFFLE((A), (B), pp_h8, I0, I1, I2, I3, I4, I5, I6, I7)
RSI_INLINE static void pp_store8(int16_t *a, int32_t k, pp_h8 v) { *(pp_h8un *)(void *)&a[k] = v; }
RSI_INLINE static void pp_t8(const rs_cvert *const p[8], int16_t *x, int16_t *y, int16_t *c, int32_t k, pp_h8 fl)
{
    pp_h8 w0, w1, w2, w3, w4, w5, w6, w7;
    memcpy(&w0, p[0], 16); memcpy(&w1, p[1], 16); memcpy(&w2, p[2], 16);
    memcpy(&w3, p[3], 16); memcpy(&w4, p[4], 16); memcpy(&w5, p[5], 16);
    memcpy(&w6, p[6], 16); memcpy(&w7, p[7], 16);
    PP_LEW(w0); PP_LEW(w1); PP_LEW(w2); PP_LEW(w3);
    PP_LEW(w4); PP_LEW(w5); PP_LEW(w6); PP_LEW(w7);
    {
        /* l01: x0 x1 x0' x1' y0 y1 y0' y1' (' the high words), h01: d0 d1 d0' d1' c0 c1 c0' c1' */
        const pp_h8 l01 = PP_ZIP(w0, w1, 0, 8, 1, 9, 2, 10, 3, 11), h01 = PP_ZIP(w0, w1, 4, 12, 5, 13, 6, 14, 7, 15);
        const pp_h8 l23 = PP_ZIP(w2, w3, 0, 8, 1, 9, 2, 10, 3, 11), h23 = PP_ZIP(w2, w3, 4, 12, 5, 13, 6, 14, 7, 15);
        const pp_h8 l45 = PP_ZIP(w4, w5, 0, 8, 1, 9, 2, 10, 3, 11), h45 = PP_ZIP(w4, w5, 4, 12, 5, 13, 6, 14, 7, 15);
        const pp_h8 l67 = PP_ZIP(w6, w7, 0, 8, 1, 9, 2, 10, 3, 11), h67 = PP_ZIP(w6, w7, 4, 12, 5, 13, 6, 14, 7, 15);
        /* x03: x0 x1 x2 x3 x0' x1' x2' x3', y03 the same of y, c03 of c */
        const pp_h8 x03 = PP_ZIP(l01, l23, 0, 1, 8, 9, 2, 3, 10, 11), x47 = PP_ZIP(l45, l67, 0, 1, 8, 9, 2, 3, 10, 11);
        const pp_h8 y03 = PP_ZIP(l01, l23, 4, 5, 12, 13, 6, 7, 14, 15), y47 = PP_ZIP(l45, l67, 4, 5, 12, 13, 6, 7, 14, 15);
        const pp_h8 c03 = PP_ZIP(h01, h23, 4, 5, 12, 13, 6, 7, 14, 15), c47 = PP_ZIP(h45, h67, 4, 5, 12, 13, 6, 7, 14, 15);
        pp_store8(x, k, PP_ZIP(x03, x47, 0, 1, 2, 3, 8, 9, 10, 11) ^ fl);
        pp_store8(y, k, PP_ZIP(y03, y47, 0, 1, 2, 3, 8, 9, 10, 11) ^ fl);
        pp_store8(c, k, PP_ZIP(c03, c47, 4, 5, 6, 7, 12, 13, 14, 15));
    }
}

/* Vertex slot k + j of one parity (odd: 0 even, 1 odd) of the gather below: the cache
 * entry of strip index 2 s + odd, s = k + j, or n for slots past n when clamp; kept in
 * *slot for the strip loop and returned for the transposition. */
RSI_INLINE static const rs_cvert *pp_g1(const rs_cvert **slot, const rs_cvert *cache, const br_index *ip,
                                        int32_t k, int32_t j, int32_t n, int clamp, int odd)
{
    const int32_t s = clamp && k + j > n ? n : k + j;
    return *slot = &cache[ip[2 * s + odd]];
}

/* Slots k .. k + 7 of both parities: their pointers, then their first 16 bytes
 * transposed (pp_t8).  clamp: some of the slots are past n. */
RSI_INLINE static void pp_g8(pp_soa *q, const rs_cvert *cache, const br_index *ip, int32_t k, int32_t n,
                             int clamp, pp_h8 fl)
{
    const rs_cvert *pe[8], *po[8];
    pe[0] = pp_g1(&q->ve[k + 0], cache, ip, k, 0, n, clamp, 0);
    pe[1] = pp_g1(&q->ve[k + 1], cache, ip, k, 1, n, clamp, 0);
    pe[2] = pp_g1(&q->ve[k + 2], cache, ip, k, 2, n, clamp, 0);
    pe[3] = pp_g1(&q->ve[k + 3], cache, ip, k, 3, n, clamp, 0);
    pe[4] = pp_g1(&q->ve[k + 4], cache, ip, k, 4, n, clamp, 0);
    pe[5] = pp_g1(&q->ve[k + 5], cache, ip, k, 5, n, clamp, 0);
    pe[6] = pp_g1(&q->ve[k + 6], cache, ip, k, 6, n, clamp, 0);
    pe[7] = pp_g1(&q->ve[k + 7], cache, ip, k, 7, n, clamp, 0);
    pp_t8(pe, q->xe, q->ye, q->ce, k, fl);
    po[0] = pp_g1(&q->vo[k + 0], cache, ip, k, 0, n, clamp, 1);
    po[1] = pp_g1(&q->vo[k + 1], cache, ip, k, 1, n, clamp, 1);
    po[2] = pp_g1(&q->vo[k + 2], cache, ip, k, 2, n, clamp, 1);
    po[3] = pp_g1(&q->vo[k + 3], cache, ip, k, 3, n, clamp, 1);
    po[4] = pp_g1(&q->vo[k + 4], cache, ip, k, 4, n, clamp, 1);
    po[5] = pp_g1(&q->vo[k + 5], cache, ip, k, 5, n, clamp, 1);
    po[6] = pp_g1(&q->vo[k + 6], cache, ip, k, 6, n, clamp, 1);
    po[7] = pp_g1(&q->vo[k + 7], cache, ip, k, 7, n, clamp, 1);
    pp_t8(po, q->xo, q->yo, q->co, k, fl);
}

/* The gather: vertex slot k holds ip[2 k] (even) and ip[2 k + 1] (odd) for k <= n, the
 * slots past n repeat slot n (their lanes are ignored); eight slots at a time (pp_g8);
 * slots 0 .. nv - 1 (nv: n rounded up to PP_L). */
RSI_INLINE static void pp_gather(pp_soa *q, const rs_cvert *cache, const br_index *ip, int32_t n, int32_t nv)
{
    /* x - PP_OFF modulo 2^16 is the low 16 bits with the top one flipped */
    const pp_h8 fl = { -PP_OFF, -PP_OFF, -PP_OFF, -PP_OFF, -PP_OFF, -PP_OFF, -PP_OFF, -PP_OFF };
    int32_t k;
    for (k = 0; k < nv; k += 8) {
        if (k + 7 <= n) pp_g8(q, cache, ip, k, n, 0, fl);
        else pp_g8(q, cache, ip, k, n, 1, fl);
    }
}

/* The candidate loop's edge values for one step's pair, row by row: S1, S2 (the areas less
 * the biases), same (all ones in the lanes whose two triangles' areas have the same sign),
 * the steps per pixel across (c01, c20, c13) and down (r01s, r20s, r13s), and the values
 * at the current row's first centre (r01, r20, r13), which pp_row advances. */
typedef struct pp_row_edges {
    pp_v8 S1, S2, same, c01, c20, c13, r01s, r20s, r13s;
    pp_v8 r01, r20, r13;
} pp_row_edges;

/* Row j (0 .. 3) of the quads' candidates: the edge values of its nxm columns into
 * q->e[8 j + i] (lanes k ..), and the covered centres' bits (1 << i, masked to the lanes
 * whose box has row j: j < qny) into *ml / *mm at bit sh; then g's row values step down. */
RSI_INLINE static void pp_row(pp_soa *q, int32_t k, pp_row_edges *g, int32_t j, int32_t nxm, pp_v8 qny,
                              pp_v8 *ml, pp_v8 *mm, int sh)
{
    const pp_v8 zero = { 0 }, one = zero + 1, rm = qny > (int16_t)j;
    pp_v8 g01 = g->r01, g20 = g->r20, g13 = g->r13, b1 = zero, b2 = zero, cb = one;
    int32_t i;
    for (i = 0; i < nxm; i++) {
        const pp_v8 eD = VSUB(VSUB(g->S1, g01), g20), eT = eD ^ g->same;
        const pp_v8 g32 = VSUB(VSUB(g->S2, eT), g13);
        b1 |= cb & ~((g01 | g20 | eD) >> 15);
        b2 |= cb & ~((g13 | g32 | eT) >> 15);
        PPS(q->e[8 * j + i][0], k, g20);
        PPS(q->e[8 * j + i][1], k, g01);
        PPS(q->e[8 * j + i][2], k, g32);
        PPS(q->e[8 * j + i][3], k, eT);
        g01 = VADD(g01, g->c01); g20 = VADD(g20, g->c20); g13 = VADD(g13, g->c13);
        cb = VADD(cb, cb);
    }
    *ml |= VI(VU(b1 & rm) << sh); *mm |= VI(VU(b2 & rm) << sh);
    g->r01 = VADD(g->r01, g->r01s); g->r20 = VADD(g->r20, g->r20s); g->r13 = VADD(g->r13, g->r13s);
}

/* The set-up of strip steps 0 .. n-1 of a chunk, PP_L at a time in 16-bit lanes (see
 * pp_soa above; strip indices ip[0 .. 2 n + 1], gathered first): for each step what
 * tri_pair, pair_tiny and tri_quad (raster_draw.h) compute before the coverage masks,
 * with the same values, so the pixels are theirs:
 * - kind: PK_SLOW (an outcode bit, and not both triangles rejected by the outcodes: the
 *   main pass does what the plain loop does), PK_NONE (no row of centres, an empty box in
 *   the band, neither triangle drawn (culled or of zero area), both rejected by the
 *   outcodes), PK_WIDE (more than TINY_H rows or TINY_W columns, and a row and a column
 *   of centres in the band: pair_wide with lo, hi, xl, xh in py0, ny, px0, nx; a wide
 *   box with none draws nothing there, as tri_box returns before counting), PK_QUAD
 *   (any other box of up to TINY_W x TINY_H centres, either orientation for each
 *   triangle).  One-candidate boxes are quads too (they
 *   are rare, and kinds of their own would cost more to classify than they save);
 * - for the quads the box, the areas, the number of triangles drawn (nt) and the coverage
 *   and edge values of each candidate (see the candidate loop below).
 * Every value is computed modulo 2^16.  For the pairs that use them it is exact: all four
 * vertices are on screen, so a coordinate minus PP_OFF is in [-32760, 32760] (w, h <=
 * 4096) and the box bounds lo, hi, xl, xh (and their differences) are exact; a box of at
 * most TINY_W x TINY_H centres has every vertex within 144 x 80 sub-pixels of its first
 * candidate (xmax - xmin < 16 (xh - xl + 1) + 16), so |X| < 144, |Y| < 80, the edge values
 * and doubled areas are below 23,040 in magnitude and the biased ones and S1, S2 within 3
 * of them.
 * Steps whose values overflow (wide boxes, vertices off screen) are classified from
 * exact quantities only (outcodes, lo, hi, xl, xh) before any of the rest is read. */
PP_SCHED static void pp_prepass(const band *bd, pp_soa *q, const rs_cvert *cache, const br_index *ip, int32_t n)
{
    static const int16_t iota_a[16] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15 };
    const pp_v8 zero = { 0 }, one = zero + 1;
    const pp_v8 by0 = zero + (int16_t)(bd->y0 - PP_ROFF), by1 = zero + (int16_t)(bd->y1 - 1 - PP_ROFF);
    const pp_v8 cullm = zero - (int16_t)(bd->cull != 0);
    const pp_v8 iota = PPL(iota_a, 0);
    const int32_t nv = (n + PP_L - 1) & ~(PP_L - 1);    /* slots 0 .. nv: the groups read slots k .. k + PP_L */
    int32_t k;
    pp_gather(q, cache, ip, n, nv);
    {
        const rs_cvert *a0 = &cache[ip[2 * n]], *a1 = &cache[ip[2 * n + 1]];    /* slot nv alone */
        q->ve[nv] = a0; q->vo[nv] = a1;
        q->xe[nv] = (int16_t)(a0->x ^ PP_OFF); q->ye[nv] = (int16_t)(a0->y ^ PP_OFF); q->ce[nv] = (int16_t)(a0->c >> 16);
        q->xo[nv] = (int16_t)(a1->x ^ PP_OFF); q->yo[nv] = (int16_t)(a1->y ^ PP_OFF); q->co[nv] = (int16_t)(a1->c >> 16);
    }
    for (k = 0; k < n; k += PP_L) {
        const pp_v8 x0 = PPL(q->xe, k), x1 = PPL(q->xo, k), x2 = PPL(q->xe, k + 1), x3 = PPL(q->xo, k + 1);
        const pp_v8 y0 = PPL(q->ye, k), y1 = PPL(q->yo, k), y2 = PPL(q->ye, k + 1), y3 = PPL(q->yo, k + 1);
        const pp_v8 c0 = PPL(q->ce, k), c1 = PPL(q->co, k), c2 = PPL(q->ce, k + 1), c3 = PPL(q->co, k + 1);
        const pp_v8 c12 = c1 & c2 & (int16_t)(REJECT >> 16);
        /* slow: an outcode bit; rej: both triangles rejected by the outcodes (the per-pair
         * strip loop's test) */
        const pp_v8 slow = ((c0 | c1 | c2 | c3) & (int16_t)((SLOW | REJECT) >> 16)) != 0;
        const pp_v8 rej = ((c12 & c0) != 0) & ((c12 & c3) != 0);
        const pp_v8 ymin = PP_MIN(PP_MIN(y0, y1), PP_MIN(y2, y3)), ymax = PP_MAX(PP_MAX(y0, y1), PP_MAX(y2, y3));
        const pp_v8 xmin = PP_MIN(PP_MIN(x0, x1), PP_MIN(x2, x3)), xmax = PP_MAX(PP_MAX(x0, x1), PP_MAX(x2, x3));
        const pp_v8 lo = VADD(ymin, zero + (RSI_HALF - 1)) >> RSI_SUB, hi = VSUB(ymax, zero + RSI_HALF) >> RSI_SUB;
        const pp_v8 xl = VADD(xmin, zero + (RSI_HALF - 1)) >> RSI_SUB, xh = VSUB(xmax, zero + RSI_HALF) >> RSI_SUB;
        /* boxes of more than TINY_W x TINY_H centres: pair_wide */
        const pp_v8 empty = hi < lo, wide = ((hi - lo) > (TINY_H - 1)) | ((xh - xl) > (TINY_W - 1));
        const pp_v8 py0 = PP_MAX(lo, by0), py1 = PP_MIN(hi, by1);
        const pp_v8 bempty = (py0 > py1) | (xl > xh);
        {
            /* PP_L steps that all draw nothing here (strips off screen, slivers near the
             * horizon): kinds from the quantities above, nothing else is read */
            const pp_v8 skip = slow | empty | bempty | (iota >= (int16_t)(n - k));
            uint64_t w[PP_L / 4];
            memcpy(w, &skip, sizeof w);
            if ((w[0] & w[1]
#if PP_L == 16
                 & w[2] & w[3]
#endif
                 ) == ~(uint64_t)0) {
                PPS(q->kind, k, VSEL(slow & ~rej, zero + PK_SLOW, zero + PK_NONE));
                continue;
            }
        }
        const pp_v8 ox = VI((VU(xl) << RSI_SUB) + RSI_HALF), oy = VI((VU(py0) << RSI_SUB) + RSI_HALF);
        const pp_v8 X0 = VSUB(x0, ox), X1 = VSUB(x1, ox), X2 = VSUB(x2, ox), X3 = VSUB(x3, ox);
        const pp_v8 Y0 = VSUB(y0, oy), Y1 = VSUB(y1, oy), Y2 = VSUB(y2, oy), Y3 = VSUB(y3, oy);
        /* modulo 2^16; exact for the pairs that use them (tiny boxes: |e| < 2^15) */
        const pp_v8 e01 = VSUB(VMUL(X0, Y1), VMUL(Y0, X1)), e12 = VSUB(VMUL(X1, Y2), VMUL(Y1, X2));
        const pp_v8 e20 = VSUB(VMUL(X2, Y0), VMUL(Y2, X0)), e13 = VSUB(VMUL(X1, Y3), VMUL(Y1, X3));
        const pp_v8 e32 = VSUB(VMUL(X3, Y2), VMUL(Y3, X2));
        const pp_v8 ar1 = VADD(VADD(e01, e12), e20), ar2 = VSUB(VADD(e13, e32), e12);
        /* orientations: s1 / s2 -1 for a front face (T1 / T2), same -1 where they agree;
         * ok1 / ok2: the triangle is drawn (a non-zero area, not culled) */
        const pp_v8 s1 = ar1 < 0, s2 = ar2 < 0, same = ~(s1 ^ s2);
        const pp_v8 ok1 = (ar1 != 0) & (s1 | ~cullm), ok2 = (ar2 != 0) & (s2 | ~cullm);
#define SG1(x) VSUB((x) ^ s1, s1)
#define SG2(x) VSUB((x) ^ s2, s2)
        /* top-left bias masks (-1 for a biased edge): A = SG(yP - yQ) < 0, or A == 0 and
         * B = SG(xQ - xP) <= 0, i.e. 256 A + B <= 0 as |B| < 144 in a tiny box (and
         * |A| < 80: no overflow), with 256 A + B = SG(256 (yP - yQ) + xQ - xP) */
#define QB(SG, P, Q) (SG(VADD(VI(VU(VSUB(y##P, y##Q)) << 8), VSUB(x##Q, x##P))) < one)
        const pp_v8 b01 = QB(SG1, 0, 1), b12 = QB(SG1, 1, 2), b20 = QB(SG1, 2, 0), b13 = QB(SG2, 1, 3), b32 = QB(SG2, 3, 2);
        /* T2's diagonal is T1's edge reversed: with the same orientation its value is
         * -1 - eD (the negated edge function, the complementary bias), else eD itself
         * (the negation twice, the same bias); bT its bias */
        const pp_v8 bT = b12 ^ same;
        const pp_v8 f01 = VADD(SG1(e01), b01), f20 = VADD(SG1(e20), b20), f13 = VADD(SG2(e13), b13);
        pp_v8 kind = zero + PK_QUAD;
        kind = VSEL(~(ok1 | ok2) | bempty, zero + PK_NONE, kind);
        kind = VSEL(wide & ~bempty, zero + PK_WIDE, kind);
        kind = VSEL(empty, zero + PK_NONE, kind);
        kind = VSEL(slow, VSEL(rej, zero + PK_NONE, zero + PK_SLOW), kind);
        PPS(q->kind, k, kind);
        PPS(q->px0, k, xl + PP_ROFF);
        {
            const pp_v8 wk = kind == PK_WIDE;      /* pair_wide: lo, hi, xl, xh */
            PPS(q->py0, k, VSEL(wk, lo, py0) + PP_ROFF);
            PPS(q->nx, k, VSEL(wk, xh + PP_ROFF, xh - xl + 1));
            PPS(q->ny, k, VSEL(wk, hi + PP_ROFF, py1 - py0 + 1));
        }
        PPS(q->a1, k, SG1(ar1));
        PPS(q->a2, k, SG2(ar2));
        PPS(q->nt, k, VSUB(zero, VADD(ok1, ok2)));
        {
            /* The quads' coverage, for the candidates of the largest quad box among
             * the PP_L (rows j < nym, columns i < nxm; isq: the lanes of quads): per
             * candidate T1's edge values g01, g20 and diagonal eD = S1 - g01 - g20, T2's
             * g13, its diagonal eT = eD or -1 - eD and third edge g32 = S2 - eT - g13, and a bit
             * (8 j + i: rows 0-1 in the low half, 2-3 in the high one) for each triangle
             * whose three values are >= 0, in the lane's own rows only (j < ny: the band's
             * clip).  In those rows every value is exact at all TINY_W columns, not just
             * the box's: relative to the first candidate the vertices have -16 < X < 16 nx
             * <= 128 and Y within 16 of the rows lo .. hi (hi - lo < TINY_H), the
             * candidates 0 <= X <= 112 and rows inside lo .. hi, so each edge value,
             * (A - P) x (B - P) plus a bias, is below 128 * 64 * 2 + 3 < 2^15 in magnitude.
             * A centre right of the box (16 xh + 8 <= xmax < 16 xh + 24) lies strictly
             * outside both triangles, so one of its exact values is < 0: its bits are clear
             * with no column mask. */
            const pp_v8 isq = (kind == PK_QUAD) & (iota < (int16_t)(n - k));
            const pp_v8 qnx = VSEL(isq, xh - xl + 1, zero), qny = VSEL(isq, py1 - py0 + 1, zero);
            pp_v8 bx = PP_HMAX(qnx), by = PP_HMAX(qny);
            const int32_t nxm = bx[0], nym = by[0];
            pp_v8 m1l = zero, m2l = zero, m1h = zero, m2h = zero;
            if (nxm) {
                /* S1, S2: the areas less the biases; the edges' steps per pixel across
                 * (16 A) and down (16 B) */
                const pp_v8 S1 = VADD(VADD(VADD(SG1(ar1), b01), b12), b20), S2 = VADD(VADD(VADD(SG2(ar2), b13), bT), b32);
                const pp_v8 c01 = VI(VU(SG1(VSUB(y0, y1))) << RSI_SUB), c20 = VI(VU(SG1(VSUB(y2, y0))) << RSI_SUB);
                const pp_v8 c13 = VI(VU(SG2(VSUB(y1, y3))) << RSI_SUB);
                const pp_v8 r01s = VI(VU(SG1(VSUB(x1, x0))) << RSI_SUB), r20s = VI(VU(SG1(VSUB(x0, x2))) << RSI_SUB);
                const pp_v8 r13s = VI(VU(SG2(VSUB(x3, x1))) << RSI_SUB);
                pp_row_edges g;
                g.S1 = S1; g.S2 = S2; g.same = same; g.c01 = c01; g.c20 = c20; g.c13 = c13;
                g.r01s = r01s; g.r20s = r20s; g.r13s = r13s; g.r01 = f01; g.r20 = f20; g.r13 = f13;
                pp_row(q, k, &g, 0, nxm, qny, &m1l, &m2l, 0);
                if (nym > 1) {
                    pp_row(q, k, &g, 1, nxm, qny, &m1l, &m2l, 8);
                    if (nym > 2) {
                        pp_row(q, k, &g, 2, nxm, qny, &m1h, &m2h, 0);
                        if (nym > 3) pp_row(q, k, &g, 3, nxm, qny, &m1h, &m2h, 8);
                    }
                }
            }
            /* as 32-bit masks: the halves interleaved */
            m1l &= ok1; m1h &= ok1; m2l &= ok2; m2h &= ok2;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
            {   /* (big-endian: a 32-bit mask's high half comes first in memory) */
                const pp_v8 t1 = m1l, t2 = m2l;
                m1l = m1h; m1h = t1; m2l = m2h; m2h = t2;
            }
#endif
#if PP_L == 16
#define PP_LO16 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23
#define PP_HI16 8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31
            PPS((int16_t *)q->m1, 2 * k, RS_SHUFFLE(m1l, m1h, pp_v8, PP_LO16));
            PPS((int16_t *)q->m1, 2 * k + PP_L, RS_SHUFFLE(m1l, m1h, pp_v8, PP_HI16));
            PPS((int16_t *)q->m2, 2 * k, RS_SHUFFLE(m2l, m2h, pp_v8, PP_LO16));
            PPS((int16_t *)q->m2, 2 * k + PP_L, RS_SHUFFLE(m2l, m2h, pp_v8, PP_HI16));
#undef PP_LO16
#undef PP_HI16
#else
            PPS((int16_t *)q->m1, 2 * k, RS_SHUFFLE(m1l, m1h, pp_v8, 0, 8, 1, 9, 2, 10, 3, 11));
            PPS((int16_t *)q->m1, 2 * k + 8, RS_SHUFFLE(m1l, m1h, pp_v8, 4, 12, 5, 13, 6, 14, 7, 15));
            PPS((int16_t *)q->m2, 2 * k, RS_SHUFFLE(m2l, m2h, pp_v8, 0, 8, 1, 9, 2, 10, 3, 11));
            PPS((int16_t *)q->m2, 2 * k + 8, RS_SHUFFLE(m2l, m2h, pp_v8, 4, 12, 5, 13, 6, 14, 7, 15));
#endif
        }
#undef SG1
#undef SG2
#undef QB
    }
    {
        /* The strip loop's work list, from the kinds above: bit k of q->work for each step
         * k < n whose kind is not PK_NONE (the lanes past n of the last group are not
         * defined: masked off) */
        uint32_t work = 0, b;
#if PP_L == 16
        for (k = 0; k < n; k += 16) {
            PP_BITS(b, PPL(q->kind, k) == PK_NONE);
            work |= (b ^ 0xffffu) << k;
        }
#else
        /* (two groups per PP_BITS2: the kinds past the last group zeroed first) */
        for (k = (n + 7) & ~7; k < PP_STEPS; k += 8) PPS(q->kind, k, zero);
        for (k = 0; k < n; k += 16) {
            PP_BITS2(b, PPL(q->kind, k) == PK_NONE, PPL(q->kind, k + 8) == PK_NONE);
            work |= (b ^ 0xffffu) << k;
        }
#endif
        q->work = work & (uint32_t)(((uint64_t)1 << n) - 1);
    }
}

#endif
