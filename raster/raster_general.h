/* raster/raster_general.h — the general path of the per-triangle code: triangles whose
 * bounding box has more than TINY_W x TINY_H candidate centres, drawn row by row (exact
 * row starts from the barycentric weights, stepped gradients along the row).  raster.c's
 * own, included once; every function takes the variant as its constant last argument
 * (raster_pixel.h).  Each row's span is drawn by raster_span.h's code. */
#ifndef BR_RASTER_GENERAL_H
#define BR_RASTER_GENERAL_H

/* GEN_OPAQUE(x): x's value unknown to the optimiser from here on (an empty asm with x as
 * its in-out operand; no code), to keep GCC from deriving induction variables from it */
#if defined(__GNUC__)
#define GEN_OPAQUE(X) __asm__("" : "+r"(X))
#else
#define GEN_OPAQUE(X) ((void)0)
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
    GEN_CASE(V_888_NOZ, small, wide, 0);
    GEN_CASE(V_565_NOZ, small, wide, 0);
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
    GEN_CASE(V_888_NOZ, 1, 1, 0);
    GEN_CASE(V_565_NOZ, 1, 1, 0);
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
    GEN_CASE(V_888_NOZ, 1, 1, 1);
    GEN_CASE(V_565_NOZ, 1, 1, 1);
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
    GEN_CASE(V_888_NOZ, 1, 0, 0);
    GEN_CASE(V_565_NOZ, 1, 0, 0);
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
    GEN_CASE(V_888_NOZ, 0, wide, 0);
    GEN_CASE(V_565_NOZ, 0, wide, 0);
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
