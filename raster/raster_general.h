/* raster/raster_general.h — the general path of the per-triangle code: triangles whose
 * bounding box has more than TINY_W x TINY_H candidate centres, drawn row by row (exact
 * row starts from the barycentric weights, stepped gradients along the row).  Part of
 * the template: included by raster_tmpl.h, once per variant, with its macros (RS_FN,
 * RS_PIX, RS_Z, RS_ZSH, RS_PACK, RS_PACK24, RS_TEX, RS_COUNT).  No header guard on
 * purpose. */

/* The plain span (no texture, no counting) four pixels at a time in 32-bit vector lanes
 * (GCC's generic vectors: SSE2 on x86-64, NEON on AArch64), for spans of eight or more
 * pixels; shorter spans and targets without such vectors keep the scalar loop (a span's
 * two end groups cost about as many instructions as eight scalar pixels: from four
 * pixels on, B 640x480 took 0.15 M more per frame, from ten or twelve 0.015 M fewer,
 * kept at eight for the data-dependent branches of the scalar loop).  Same
 * pixels: see the span code below.  RS_SPANV defaults to RS_PREPASS (raster.c), so the
 * -mgeneral-regs-only builds of check-nofloat.sh (RS_PREPASS=0 and 1) compile both
 * paths (GCC lowers the vectors to general registers there) and the RS_PREPASS=0 test
 * build runs the scalar one; RS_SPANV=0 or 1 overrides.  The types and the memory
 * macros once for all the variants (no header guard for the rest of the file). */
#ifndef RS_SPANV
#define RS_SPANV RS_PREPASS
#endif
/* GEN_OPAQUE(x): x's value unknown to the optimiser from here on (an empty asm with x as
 * its in-out operand; no code), to keep GCC from deriving induction variables from it */
#ifndef GEN_OPAQUE
#if defined(__GNUC__)
#define GEN_OPAQUE(X) __asm__("" : "+r"(X))
#else
#define GEN_OPAQUE(X) ((void)0)
#endif
#endif
#if RS_SPANV && !defined(GS_LD)
/* GS_N pixels a group: 4 in 128-bit vectors, 8 in the 256-bit ones of x86-64-v3 (AVX2;
 * raster/isa.c's second copy; B 640x480 19.60 -> 19.01 M instructions per frame, A the
 * same).  Everything below holds for either: the spans take groups from GS_N pixels on,
 * and gs_lanes_make's bound (the fields at pixels 0 and GS_N - 1 of such a span both in
 * [0, 2^21)) only gets tighter. */
#define GS_N (RS_VBYTES / 4)
typedef uint32_t gs_v4u __attribute__((vector_size(4 * GS_N)));
typedef int32_t gs_v4i __attribute__((vector_size(4 * GS_N)));
typedef uint32_t gs_v4un __attribute__((vector_size(4 * GS_N), aligned(2)));  /* at any 16-bit boundary */
typedef uint16_t gs_v8h __attribute__((vector_size(16)));
typedef uint64_t gs_v2q __attribute__((vector_size(16)));
/* Four depths or pixels at P (uint32_t or uint16_t, by sizeof) to the 32-bit lanes of V,
 * and back; macros, not functions: a vector argument or result needs vector registers,
 * which -mgeneral-regs-only does not have.  16-bit elements come as eight bytes into
 * the low half, interleaved with zeros (SSE2 punpcklwd, NEON zip1), and go back as the
 * low halves of the lanes (the values are below 2^16): q | q >> 16 puts lanes 2i and
 * 2i + 1 side by side in the low 32 bits of 64-bit lane i, one 32-bit shuffle joins
 * them (GCC's own 16-bit shuffle for this is four pextrw and pinsrw). */
#if GS_N == 8
/* (eight 16-bit elements: one 16-byte load widened, vpmovzxwd; back by truncation) */
typedef uint16_t gs_v8hn __attribute__((vector_size(16), aligned(2)));
#define GS_LD(V, P) do { \
        if (sizeof *(P) == 4) V = *(const gs_v4un *)(const void *)(P); \
        else V = __builtin_convertvector(*(const gs_v8hn *)(const void *)(P), gs_v4u); } while (0)
#define GS_ST(P, V) do { \
        if (sizeof *(P) == 4) *(gs_v4un *)(void *)(P) = (V); \
        else *(gs_v8hn *)(void *)(P) = __builtin_convertvector((V), gs_v8hn); } while (0)
#elif defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
/* (big-endian: a 32-bit lane's low half is its second 16-bit word; the elements go in
 * there and come back from there with one 16-bit shuffle each way) */
#define GS_LD(V, P) do { \
        if (sizeof *(P) == 4) V = *(const gs_v4un *)(const void *)(P); \
        else { uint64_t u_; gs_v2q q_; memcpy(&u_, (const void *)(P), 8); q_ = (gs_v2q){ u_, 0 }; \
               V = (gs_v4u)RS_SHUFFLE((gs_v8h)q_, (gs_v8h)(q_ - q_), gs_v8h, 8, 0, 8, 1, 8, 2, 8, 3); } } while (0)
#define GS_ST(P, V) do { \
        if (sizeof *(P) == 4) *(gs_v4un *)(void *)(P) = (V); \
        else { const gs_v8h h_ = RS_SHUFFLE((gs_v8h)(V), (gs_v8h)(V), gs_v8h, 1, 3, 5, 7, 1, 3, 5, 7); \
               memcpy((void *)(P), &h_, 8); } } while (0)
#else
#define GS_LD(V, P) do { \
        if (sizeof *(P) == 4) V = *(const gs_v4un *)(const void *)(P); \
        else { uint64_t u_; gs_v2q q_; memcpy(&u_, (const void *)(P), 8); q_ = (gs_v2q){ u_, 0 }; \
               V = (gs_v4u)RS_SHUFFLE((gs_v8h)q_, (gs_v8h)(q_ - q_), gs_v8h, 0, 8, 1, 9, 2, 10, 3, 11); } } while (0)
#define GS_ST(P, V) do { \
        if (sizeof *(P) == 4) *(gs_v4un *)(void *)(P) = (V); \
        else { gs_v2q q_ = (gs_v2q)(V); uint64_t u_; q_ |= q_ >> 16; \
               u_ = ((gs_v2q)RS_SHUFFLE((gs_v4u)q_, (gs_v4u)q_, gs_v4u, 0, 2, 0, 2))[0]; memcpy((void *)(P), &u_, 8); } } while (0)
#endif
/* The lanes of a triangle's plain spans: lane l of a group at pixel j holds pixel j + l,
 * each value from the span start plus (j + l) times its step, so the lanes start at
 * {0, 1, 2, 3} steps (the *off) and step by 4 (the *step). */
typedef struct gs_lanes { gs_v4u zoff, roff, goff, boff, zstep, rstep, gstep, bstep; } gs_lanes;
/* Made at a triangle's first span of eight or more pixels (a call draws 2.5 rows on
 * average; on B 640x480 0.9 K of the 4.3 K calls per frame draw such a span), out of
 * line and into memory: inline, GCC may hoist it out of the row loop (it is loop
 * invariant), making it for every call.  The signed colour gradients G_k from the packed
 * gc = G_R 2^42 + G_G 2^21 + G_B (mod 2^64): on a span of n >= 8 pixels the fields at
 * pixels 0 and 3 both lie in [0, 2^21), so 3 |G_k| < 2^21 and |G_k| < 2^20, which the
 * 21-bit sign extensions recover exactly, field by field from the bottom.  rl: R's
 * shift (see GS_PX). */
RS_NOINLINE static void gs_lanes_make(gs_lanes *L, uint32_t gzu, uint64_t gc, int rl)
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
}
#endif

/* Triangles whose bounding box has more than TINY_W x TINY_H candidate centres (kept
 * out of tri_raster so that the tiny path's code stays small).  The body of the copies
 * below: small (box below SMALL in both directions: gradients and row starts through a
 * reciprocal), wide (more than NARROW columns: spans by division, else by scanning) and
 * one (py0 == py1: no row loop) are constants of each copy; for a given triangle and
 * band the values are the same whichever copy draws it. */
RS_INLINE static void RS_FN(tri_gen_body)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                          int32_t px0, int32_t px1, int32_t py0, int32_t py1,
                                          const int small, const int wide, const int one)
{
    int32_t py;
    int64_t dx1, dy1, dx2, dy2, area2, A0, A1, A2, B0, B1, B2, S, e0r, e2r, sx0, sx2, sy0, sy2;
    int64_t bias0, bias1, bias2;
    const int32_t w = bd->w;

    dx1 = (int64_t)b->x - a->x; dy1 = (int64_t)b->y - a->y;
    dx2 = (int64_t)c->x - a->x; dy2 = (int64_t)c->y - a->y;
    area2 = dx1 * dy2 - dx2 * dy1;
    /* y points down: counter-clockwise as seen (a front face) has area2 < 0 */
    if (area2 >= 0) {
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
    /* Edge P->Q: E = A (X - P.x) + B (Y - P.y) >= 0 inside, at pixel centres.  Edge 0 =
     * a->b (the weight of c), 1 = b->c (weight of a), 2 = c->a (weight of b); since
     * E0 + E1 + E2 = area2 everywhere, E1 is never evaluated.  Edges that are not
     * top-left (A > 0, or A == 0 and B > 0) are biased by -1 so that E == 0 there is
     * outside: e_k = E_k - bias_k, inside iff all e_k >= 0, and e1 = S - e0 - e2.
     * bias_k = [2 A_k + (B_k > 0) <= 0] as the sign bit of 2 A_k + (B_k > 0) - 1 (A_k is
     * a vertex difference, far below 2^62; B 640x480: 0.02 M fewer than the compare). */
    A0 = -dy1; B0 = dx1;
    A2 = dy2; B2 = -dx2;
    A1 = -(A0 + A2); B1 = -(B0 + B2);
    bias0 = (int64_t)((uint64_t)(2 * A0 + (B0 > 0) - 1) >> 63);
    bias1 = (int64_t)((uint64_t)(2 * A1 + (B1 > 0) - 1) >> 63);
    bias2 = (int64_t)((uint64_t)(2 * A2 + (B2 > 0) - 1) >> 63);
    S = area2 - bias0 - bias1 - bias2;
    {
        int64_t ox = (int64_t)px0 * SUBONE + HALF - a->x, oy = (int64_t)py0 * SUBONE + HALF - a->y;
        e0r = A0 * ox + B0 * oy - bias0;
        e2r = A2 * ox + B2 * oy - bias2;
    }
    sx0 = A0 * SUBONE; sx2 = A2 * SUBONE; sy0 = B0 * SUBONE; sy2 = B2 * SUBONE;

    {
        /* General path.  x-gradients per pixel: colour per channel in Q13, packed into
         * the 21-bit fields (exact modulo 2^64, see RS_CBIAS in raster.c); depth in Q0.
         * Row starts are computed exactly from the barycentric weights at the first
         * inside centre of the row (no stepping across rows), so a row's values do not
         * depend on which band it is drawn in. */
        int64_t gz = 0, inv = 0, dzb = 0, dzc = 0, prg_b = 0, prg_c = 0, dcb2 = 0, dcc2 = 0;
        uint64_t gc = 0, ca = 0;
        fx_divisor ad = FX_DIVISOR_INIT;     /* area2, made for large triangles only */
#if RS_TEX
        /* Perspective-correct texture coordinates at every pixel from its exact edge
         * values: with q = d >> tsh (1/w, <= 2^16) and the edge values e (barycentric
         * weights times area2, shifted right by esh so that they stay below 2^20),
         *   u = (e1 qa ua + e2 qb ub + e0 qc uc) / (e1 qa + e2 qb + e0 qc),
         * products < 2^58 (u <= 2^22 texels Q8).  The edge values step exactly, so there
         * is no drift along long spans; the only errors are the 2^-20 truncation of the
         * weights and the 16 bits of q. */
        const rs_texture *tx = bd->f->tex;
        const int32_t tsh = tex_shift(a->d, b->d, c->d);
        int32_t esh = 0;
        const int64_t qa = a->d >> tsh, qb = b->d >> tsh, qc = c->d >> tsh;
        const int64_t qua = qa * a->u, qub = qb * b->u, quc = qc * c->u;
        const int64_t qva = qa * a->v, qvb = qb * b->v, qvc = qc * c->v;
        while ((area2 >> esh) >= ((int64_t)1 << 20)) esh++;
#endif
#if RS_SPANV && !RS_TEX && !RS_COUNT
        gs_lanes L;             /* made at the first span of eight or more pixels */
        int lanes = 0;
#endif
        /* wide boxes: the row spans' divisors |16 A|; a zero step is never divided by,
         * so with a 64-bit divide (C's `/`, no reciprocal) its divisor may stay 0
         * (branch-free: B 640x480 0.02 M fewer instructions per frame), without one it is
         * 1 (fx_recip_make needs d > 0) */
        fx_divisor q0 = FX_DIVISOR_INIT, q1 = FX_DIVISOR_INIT, q2 = FX_DIVISOR_INIT;    /* made when wide */
        if (wide) {
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
         * row at the end at most); per drawn row, products by the row and the band's
         * fields reloaded (the pixel stores may alias them) cost 0.09 M instructions per
         * frame more on B 640x480 */
        uint8_t *crow = bd->color + (size_t)(py0 - bd->y0) * bd->stride;
        RS_Z *zrow = (RS_Z *)bd->depth + (size_t)(py0 - bd->y0) * (size_t)w;
        const size_t cstride = bd->stride;
        /* The gradients and the row start's constants (a macro: made before the row loop,
         * or, for one-row boxes, once the row's span is known not to be empty: 0.28 K of
         * B 640x480's 1.6 K one-row calls per frame draw nothing; before the loop for
         * taller boxes, as lazily in the loop it cost 0.07 M more).  Colour differences
         * per channel k (0 = R, 1 = G, 2 = B; straight-line, no arrays) from the packed
         * colours: the difference plus 256 in each 21-bit field is in [1, 511], so the
         * fields of v->cp - a->cp + 256 (1 + 2^21 + 2^42) do not borrow, and the
         * whole is below 2^51: R's field, the top one, needs no mask.  Small
         * triangles: area2 < 2^21 and |colour numerator| < 2^19, products below 2^59;
         * large ones: the quotients by area2, gradients here, row starts below.  A span
         * of two or more pixels bounds |gz| by the depth range (< 2^31); the clamp only
         * affects one-pixel spans, where the step is never used, and the reciprocal's gz
         * needs none (|gzn| < 2^22, inv <= 2^40: |gz| < 2^26).
         * The row start's R and G in one pair of products: with v_k = dcb_k w1 + dcc_k w2
         * (|v_k| <= 255 (w1 + w2) < 2^30, as w1, w2 >= 0 and w1 + w2 <= 2^22: the weights
         * of inside centres, e0 + e2 <= S <= area2), rg = v_R 2^32 + v_G + 2^30 (every
         * partial sum below 2^63 in magnitude) has v_G + 2^30 in [0, 2^32) as its low 32
         * bits, so rg >> 41 = floor(v_R / 2^9) and (low 32 bits) >> 9 =
         * floor(v_G / 2^9) + 2^21, whose 2^21 (times 2^21) ca takes back. */
#define DCH(V, K) ((int64_t)((((V)->cp - a->cp + RS_C256) >> (42 - 21 * (K))) & ((K) ? (uint64_t)0x1fffff : ~(uint64_t)0)) - 256)
#define GC_S(B, C, K) ((uint64_t)((((B) * dy2 - (C) * dy1) * inv) >> 23) << (42 - 21 * (K)))
#define GC_L(B, C, K) ((uint64_t)fx_divisor_trunc(&ad, ((B) * dy2 - (C) * dy1) * ((int64_t)1 << 17)) << (42 - 21 * (K)))
#define GZ_CLAMP() do { if (gz > INT32_MAX) gz = INT32_MAX; if (gz < -INT32_MAX) gz = -INT32_MAX; } while (0)
#define GEN_GRAD() do { \
            int64_t gzn; \
            dzb = (int64_t)b->d - a->d; dzc = (int64_t)c->d - a->d; \
            const int64_t dcb0 = DCH(b, 0), dcb1 = DCH(b, 1); \
            dcb2 = DCH(b, 2); \
            const int64_t dcc0 = DCH(c, 0), dcc1 = DCH(c, 1); \
            dcc2 = DCH(c, 2); \
            gzn = dzb * dy2 - dzc * dy1; \
            if (small) { \
                inv = fx_div40((uint32_t)area2); \
                gc = GC_S(dcb0, dcc0, 0) + GC_S(dcb1, dcc1, 1) + GC_S(dcb2, dcc2, 2); \
                if (gzn < ((int64_t)1 << 22) && gzn > -((int64_t)1 << 22)) gz = (gzn * inv) >> 36; \
                else { gz = gzn * SUBONE / area2; GZ_CLAMP(); }    /* rare: no divisor made for it */ \
            } else { \
                fx_divisor_make(&ad, area2); \
                gc = GC_L(dcb0, dcc0, 0) + GC_L(dcb1, dcc1, 1) + GC_L(dcb2, dcc2, 2); \
                gz = fx_divisor_trunc(&ad, gzn * SUBONE); \
                GZ_CLAMP(); \
            } \
            prg_b = dcb0 * ((int64_t)1 << 32) + dcb1; prg_c = dcc0 * ((int64_t)1 << 32) + dcc1; \
            ca = (a->cp << 13) + RS_CBIAS - ((uint64_t)1 << 42); } while (0)
        if (!one) GEN_GRAD();
        if (one) py1 = py0;
        for (py = py0; py <= py1; py++, e0r += sy0, e2r += sy2, crow += cstride, zrow += w) {
            int32_t xl = px0, xr = px1;
            int64_t e0, e2;
            if (!wide) {
                /* narrow boxes: scanned from px0, e1 stepped by its own x step (the same
                 * values as S - e0 - e2, exact integers; B 640x480: 0.05 M fewer instructions
                 * per frame than recomputing it); an empty row leaves by the wide path's
                 * label */
                int64_t e1;
                const int64_t sx1 = -(sx0 + sx2);
                e0 = e0r; e2 = e2r; e1 = S - e0 - e2;
                while ((e0 | e1 | e2) < 0) {
                    if (++xl > px1) goto empty;
                    e0 += sx0; e1 += sx1; e2 += sx2;
                }
                {
                    int64_t f0 = e0 + sx0, f1 = e1 + sx1, f2 = e2 + sx2;
                    xr = xl;
                    while (xr < px1 && (f0 | f1 | f2) >= 0) { xr++; f0 += sx0; f1 += sx1; f2 += sx2; }
                }
            } else {
                /* e_k(px0 + l) = e_kr + sx_k l; e1 = S - e0 - e2; columns l relative to px0
                 * (floor((K + s px0) / s) = floor(K / s) + px0: the same centres as from
                 * column 0, with no products by px0 to keep across the rows).  Edge K + s l:
                 *   s > 0: l >= ceil(-K / s), no limit for K >= 0 (l >= 0), else with
                 *     m = -K >= 1, ceil(m / s) = floor((m - 1) / s) + 1, m - 1 = ~K >= 0
                 *     (= K ^ (K >> 63) for K < 0);
                 *   s < 0: l <= floor(K / |s|): none for K < 0, else the truncated quotient;
                 *   s == 0: all or none, as K >= 0.
                 * In 64 bits, so no clamps (the quotients may lie far outside the box). */
                int64_t l = 0, r = px1 - px0;
/* (~K of a copy of K that GEN_OPAQUE hides from the optimiser: GCC's induction
 * variables would otherwise step ~K of every edge on every row, a derived value it keeps
 * in memory; the earlier K ^ (K >> 63) no longer fooled it: 0.03 M more on B 640x480.
 * K's sign tested first, then SX's: the same cases, 0.04 M fewer than SX's first) */
#define GEN_EDGE(SX, K, Q) do { \
        if ((K) < 0) { if ((SX) > 0) { int64_t k_ = (K); GEN_OPAQUE(k_); \
                                       { const int64_t t_ = fx_divisor_trunc((Q), ~k_) + 1; if (t_ > l) l = t_; } } else goto empty; } \
        else if ((SX) < 0) { const int64_t t_ = fx_divisor_trunc((Q), (K)); if (t_ < r) r = t_; } } while (0)
                GEN_EDGE(sx0, e0r, &q0);
                GEN_EDGE(-(sx0 + sx2), S - e0r - e2r, &q1);
                GEN_EDGE(sx2, e2r, &q2);
#undef GEN_EDGE
                if (l > r) {
                empty:
                    continue;
                }
                xl = px0 + (int32_t)l; xr = px0 + (int32_t)r;     /* 0 <= l <= r <= px1 - px0 */
                e0 = e0r + sx0 * l; e2 = e2r + sx2 * l;
            }
            if (one) GEN_GRAD();
            {
                /* exact barycentric weights at (xl, py): b gets edge 2, c gets edge 0 (Q22) */
                int64_t w1, w2;
                uint64_t col;
                uint32_t z, gzu = (uint32_t)gz;
                RS_PIX *cp = (RS_PIX *)(void *)crow + xl;
                RS_Z *zp = zrow + xl;
                int32_t n = xr - xl + 1, i;
                if (small) { w1 = (e2 * inv) >> 18; w2 = (e0 * inv) >> 18; }
                else { w1 = fx_divisor_trunc(&ad, e2 * ((int64_t)1 << 22)); w2 = fx_divisor_trunc(&ad, e0 * ((int64_t)1 << 22)); }
                z = (uint32_t)((int64_t)a->d + ((dzb * w1 + dzc * w2) >> 22));
                {
                    const int64_t rg = prg_b * w1 + prg_c * w2 + ((int64_t)1 << 30);
                    col = ca + ((uint64_t)(rg >> 41) << 42) + ((uint64_t)((uint32_t)rg >> 9) << 21)
                          + (uint64_t)((dcb2 * w1 + dcc2 * w2) >> 9);
                }
                bd->pixels += (uint32_t)n;
#if !RS_TEX && !RS_COUNT
                {
                    /* the plain span: depth test, colour step, write */
                    RS_Z *const ze = zp + n;
                    RS_PIX *const ce = cp + n;
                    ptrdiff_t j = -(ptrdiff_t)n;      /* n >= 1; one counter to 0 */
                    (void)i;
#if RS_SPANV
                    if (n >= 8) {       /* (>= GS_N: the groups need GS_N pixels) */
                        /* Four pixels per group, lane l of the group at pixel j holding
                         * pixel j + l: groups at pixels 0, 4, .. below n - 4, then one at
                         * n - 4 (overlapping the one before it unless 4 divides n), so
                         * every access is inside [xl, xr] and there is no scalar tail.
                         * The same pixels as the scalar loop: its depth is z + j gzu modulo
                         * 2^32, as in the lanes; its colour fields are exact (their true
                         * values lie in [0, 2^21), RS_CBIAS in raster.c), field k at pixel j
                         * being F_k + j G_k (F_k that of col, G_k the signed gradient), which
                         * the lanes compute modulo 2^32, exactly since the result lies in
                         * [0, 2^21) (R times 8 for XRGB8888: below 2^24), and the pixel
                         * takes the same bits of each field as RS_PACK.  Each pixel's test
                         * reads and writes only its own depth (the pixels of a span are
                         * distinct), so four at once give the same bytes; lanes that fail
                         * write back what they read.  The last group is loaded and computed
                         * before the others are stored: where it overlaps the group before
                         * it, both start from the same bytes and so store the same ones.
                         * (Loading it after that store would give the same bytes too (a
                         * pixel written has depth == zz, which fails the test), but a load
                         * partly overlapping a just-made store waits for it: no forwarding.)
                         * Against a scalar tail (n mod 4 pixels), on B 640x480: 0.1 M fewer
                         * instructions per frame and no data-dependent branch. */
                        const int rl = sizeof(RS_PIX) == 4 ? 3 : 0;     /* R << 3: see GS_PX */
                        const uint32_t tl = (uint32_t)n - GS_N;
                        gs_v4u ndl, npl, m;
                        if (!lanes) { gs_lanes_make(&L, gzu, gc, rl); lanes = 1; }
/* The lanes at pixel j from the scalar depth Z and packed colour C there (depth with its
 * top bit flipped, for the signed compare of 32-bit depths).  R and G are taken with the
 * bits below them in C (shifts, no masks): lane k holds (F + k G) 2^rl + junk modulo
 * 2^32 with F + k G the true field, in [0, 2^21), so adding the junk changes no bit
 * that GS_PX takes.  R: C >> (42 - rl), junk the top rl bits of G's field (< 2^rl,
 * below the multiple of 2^rl: no carry); G: C >> 21, junk R's low bits times 2^21
 * (above the field, which neither borrows nor carries into them), cut by GS_PX's mask.
 * B's field has G's bits above it, which GS_PX's bv >> 13 or >> 16 would take: masked. */
#define GS_LANES(Z, C) zv = ((Z) ^ 0x80000000u) + L.zoff; rv = (uint32_t)((C) >> (42 - rl)) + L.roff; \
                       gv = (uint32_t)((C) >> 21) + L.goff; bv = ((uint32_t)(C) & 0x1fffffu) + L.boff
/* The depth test of a group: its depths OD, the write mask M and the depths to store ND
 * (OD ^ ((OD ^ zz) & M) picks zz where M is set).  32-bit depths: the unsigned compare
 * as a signed one with the top bits flipped (zv has its top bit flipped already, and
 * odb ^ zv = OD ^ zz); 16-bit depths: both sides below 2^16, a signed compare (the
 * flipped top bit of zv lies above the 16 bits that RS_ZSH and the mask take). */
#if RS_ZSH
#define GS_TEST(OD, ND) do { const gs_v4u zz_ = (zv >> RS_ZSH) & 0xffffu; \
                             m = (gs_v4u)((gs_v4i)zz_ > (gs_v4i)(OD)); ND = (OD) ^ (((OD) ^ zz_) & m); } while (0)
#else
#define GS_TEST(OD, ND) do { const gs_v4u odb_ = (OD) ^ 0x80000000u; \
                             m = (gs_v4u)((gs_v4i)zv > (gs_v4i)odb_); ND = (OD) ^ ((odb_ ^ zv) & m); } while (0)
#endif
/* The pixels, the bits of each field that RS_PACK takes: XRGB8888 bits 13..20 (R's at
 * 16..23 after the lanes' << 3, which saves a shift), RGB565 bits 16..20, 15..20, 16..20. */
#define GS_PX() (sizeof(RS_PIX) == 4 ? (rv & 0xff0000u) | ((gv >> 5) & 0xff00u) | (bv >> 13) \
                 : ((rv >> 5) & 0xf800u) | ((gv >> 10) & 0x07e0u) | (bv >> 16))
                        {
                            const uint32_t zl = z + tl * gzu;
                            const uint64_t cl = col + tl * gc;
                            gs_v4u zv, rv, gv, bv, od, op;
                            GS_LD(od, ze - GS_N); GS_LD(op, ce - GS_N);
                            GS_LANES(zl, cl);
                            GS_TEST(od, ndl);
                            npl = op ^ ((op ^ GS_PX()) & m);
                        }
                        if (j < -GS_N) {
                            const gs_v4u zstep = L.zstep, rstep = L.rstep, gstep = L.gstep, bstep = L.bstep;
                            gs_v4u zv, rv, gv, bv;
                            /* the groups at ze4 + k, k = j + 4 .. < 0 (ze4 = ze - 4, inside
                             * the span): the loop test is the sign of k */
                            RS_Z *const ze4 = ze - GS_N;
                            RS_PIX *const ce4 = ce - GS_N;
                            ptrdiff_t k = j + GS_N;
                            GS_LANES(z, col);
                            do {
                                gs_v4u od, op, nd;
                                GS_LD(od, ze4 + k); GS_LD(op, ce4 + k);
                                GS_TEST(od, nd);
                                GS_ST(ze4 + k, nd);
                                GS_ST(ce4 + k, op ^ ((op ^ GS_PX()) & m));
                                zv += zstep; rv += rstep; gv += gstep; bv += bstep;
                            } while ((k += GS_N) < 0);
                        }
                        GS_ST(ze - GS_N, ndl);
                        GS_ST(ce - GS_N, npl);
#undef GS_LANES
#undef GS_TEST
#undef GS_PX
                    } else
#endif
                    do {
                        RS_Z zz = (RS_Z)(z >> RS_ZSH);
                        if (zz > ze[j]) { ze[j] = zz; ce[j] = RS_PACK(col); }
                        z += gzu; col += gc;
                    } while (++j);
                }
#else
                {
#if RS_TEX
                    int64_t te0 = e0, te2 = e2;
#endif
                    for (i = 0; i < n; i++) {
#if RS_COUNT
                        (void)zp; (void)z; (void)gzu; (void)col;
                        cp[i] += 1;
#else
                        RS_Z zz = (RS_Z)(z >> RS_ZSH);
                        if (zz > zp[i]) {
                            zp[i] = zz;
#if RS_TEX
                            int64_t f0 = te0 >> esh, f2 = te2 >> esh, f1 = (S - te0 - te2) >> esh;
                            int64_t den = f1 * qa + f2 * qb + f0 * qc;
                            cp[i] = RS_PACK24(tex_mod(tex_fetch(tx, tex_div(f1 * qua + f2 * qub + f0 * quc, den),
                                                                tex_div(f1 * qva + f2 * qvb + f0 * qvc, den)), col));
#else
                            cp[i] = RS_PACK(col);
#endif
                        }
#endif
                        z += gzu; col += gc;
#if RS_TEX
                        te0 += sx0; te2 += sx2;
#endif
                    }
                }
#endif
            }
        }
    }
#undef GEN_GRAD
#undef GZ_CLAMP
#undef GC_L
#undef GC_S
#undef DCH
}

/* tri_general: the general path's entry, from tri_box (which finds small and wide).
 * The plain variants have a copy per case, so that GCC folds the case's branches and
 * allocates registers for it alone (B 640x480: -0.13 M instructions per frame): small
 * and wide (1.8 K calls per frame, 0.8 K narrow, 0.1 K large), and of those the boxes of
 * one row (1.6 K, mostly thin slivers near the horizon: -0.08 M more; a copy for two
 * rows saved nothing).  Textured and counting variants, and builds for size (-Os: the
 * boards with little flash; the copies are 2-3 KB each per variant): one copy, the
 * flags at run time. */
#if RS_TEX || RS_COUNT || defined(__OPTIMIZE_SIZE__)
RS_NOINLINE static void RS_FN(tri_general)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                           int32_t px0, int32_t px1, int32_t py0, int32_t py1, int small, int wide)
{
    RS_FN(tri_gen_body)(bd, a, b, c, px0, px1, py0, py1, small, wide, 0);
}
#else
RS_NOINLINE static void RS_FN(tri_gen_sw)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                          int32_t px0, int32_t px1, int32_t py0, int32_t py1)
{
    RS_FN(tri_gen_body)(bd, a, b, c, px0, px1, py0, py1, 1, 1, 0);
}
RS_NOINLINE static void RS_FN(tri_gen_sw1)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                          int32_t px0, int32_t px1, int32_t py0)
{
    RS_FN(tri_gen_body)(bd, a, b, c, px0, px1, py0, py0, 1, 1, 1);
}
RS_NOINLINE static void RS_FN(tri_gen_sn)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                          int32_t px0, int32_t px1, int32_t py0, int32_t py1)
{
    RS_FN(tri_gen_body)(bd, a, b, c, px0, px1, py0, py1, 1, 0, 0);
}
RS_NOINLINE static void RS_FN(tri_gen_l)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                         int32_t px0, int32_t px1, int32_t py0, int32_t py1, int wide)
{
    RS_FN(tri_gen_body)(bd, a, b, c, px0, px1, py0, py1, 0, wide, 0);
}
RS_INLINE static void RS_FN(tri_general)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                         int32_t px0, int32_t px1, int32_t py0, int32_t py1, int small, int wide)
{
    if (!small) RS_FN(tri_gen_l)(bd, a, b, c, px0, px1, py0, py1, wide);
    else if (wide && py0 == py1) RS_FN(tri_gen_sw1)(bd, a, b, c, px0, px1, py0);
    else if (wide) RS_FN(tri_gen_sw)(bd, a, b, c, px0, px1, py0, py1);
    else RS_FN(tri_gen_sn)(bd, a, b, c, px0, px1, py0, py1);
}
#endif
