/* raster/raster_general.h — the general path of the per-triangle code: triangles whose
 * bounding box has more than TINY_W x TINY_H candidate centres, drawn row by row (exact
 * row starts from the barycentric weights, stepped gradients along the row).  Part of
 * the template: included by raster_tmpl.h, once per variant, with its macros (RS_FN,
 * RS_PIX, RS_Z, RS_ZSH, RS_PACK, RS_PACK24, RS_TEX, RS_COUNT).  No header guard on
 * purpose. */

/* Triangles whose bounding box has more than TINY_W x TINY_H candidate centres (kept
 * out of tri_raster so that the tiny path's code stays small). */
RS_NOINLINE static void RS_FN(tri_general)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                           int32_t xmin, int32_t xmax, int32_t ymin, int32_t ymax,
                                           int32_t px0, int32_t px1, int32_t py0, int32_t py1)
{
    int32_t py;
    int64_t dx1, dy1, dx2, dy2, area2, A0, A1, A2, B0, B1, B2, S, e0r, e2r, sx0, sx2, sy0, sy2;
    int32_t bias0, bias1, bias2;
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
     * outside: e_k = E_k - bias_k, inside iff all e_k >= 0, and e1 = S - e0 - e2. */
    A0 = -dy1; B0 = dx1;
    A2 = dy2; B2 = -dx2;
    A1 = -(A0 + A2); B1 = -(B0 + B2);
    bias0 = (2 * A0 + (B0 > 0)) <= 0;
    bias1 = (2 * A1 + (B1 > 0)) <= 0;
    bias2 = (2 * A2 + (B2 > 0)) <= 0;
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
        int64_t gz, gzn, dzb = (int64_t)b->d - a->d, dzc = (int64_t)c->d - a->d, inv = 0;
        fx_divisor ad = FX_DIVISOR_INIT;     /* area2, made for large triangles only */
        /* colour differences per channel k (0 = R, 1 = G, 2 = B; straight-line, no arrays)
         * from the packed colours: the difference plus 256 in each 21-bit field is in
         * [1, 511], so the fields of v->cp - a->cp + 256 (1 + 2^21 + 2^42) do not borrow */
#define DCH(V, K) ((int64_t)((((V)->cp - a->cp + RS_C256) >> (42 - 21 * (K))) & 0x1fffffu) - 256)
        const int64_t dcb0 = DCH(b, 0), dcb1 = DCH(b, 1), dcb2 = DCH(b, 2);
        const int64_t dcc0 = DCH(c, 0), dcc1 = DCH(c, 1), dcc2 = DCH(c, 2);
#undef DCH
        uint64_t gc;
        int small = xmax - xmin < SMALL && ymax - ymin < SMALL;
        gzn = dzb * dy2 - dzc * dy1;
        if (small) {
            /* area2 < 2^21 and |colour numerator| < 2^19: products below 2^59 */
            inv = fx_div40((uint32_t)area2);
#define GC(B, C, K) ((uint64_t)((((B) * dy2 - (C) * dy1) * inv) >> 23) << (42 - 21 * (K)))
            gc = GC(dcb0, dcc0, 0) + GC(dcb1, dcc1, 1) + GC(dcb2, dcc2, 2);
#undef GC
            if (gzn < ((int64_t)1 << 22) && gzn > -((int64_t)1 << 22)) gz = (gzn * inv) >> 36;
            else gz = gzn * SUBONE / area2;     /* rare: no divisor made for it */
        } else {
            /* the quotients by area2: gradients here, row starts below */
            fx_divisor_make(&ad, area2);
#define GC(B, C, K) ((uint64_t)fx_divisor_trunc(&ad, ((B) * dy2 - (C) * dy1) * ((int64_t)1 << 17)) << (42 - 21 * (K)))
            gc = GC(dcb0, dcc0, 0) + GC(dcb1, dcc1, 1) + GC(dcb2, dcc2, 2);
#undef GC
            gz = fx_divisor_trunc(&ad, gzn * SUBONE);
        }
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
        /* a span of two or more pixels bounds |gz| by the depth range (< 2^31); the clamp
         * only affects one-pixel spans, where the step is never used */
        if (gz > INT32_MAX) gz = INT32_MAX;
        if (gz < -INT32_MAX) gz = -INT32_MAX;

        const uint64_t ca = (a->cp << 13) + RS_CBIAS;
        /* wide boxes: the row spans' divisors |16 A| (1 for a zero step, never divided by) */
        fx_divisor q0 = FX_DIVISOR_INIT, q1 = FX_DIVISOR_INIT, q2 = FX_DIVISOR_INIT;    /* made when wide */
        if (px1 - px0 >= NARROW) {
            const int64_t s1_ = sx0 + sx2;
            fx_divisor_make(&q0, sx0 < 0 ? -sx0 : sx0 ? sx0 : 1);
            fx_divisor_make(&q1, s1_ < 0 ? -s1_ : s1_ ? s1_ : 1);
            fx_divisor_make(&q2, sx2 < 0 ? -sx2 : sx2 ? sx2 : 1);
        }
        for (py = py0; py <= py1; py++, e0r += sy0, e2r += sy2) {
            int32_t xl = px0, xr = px1;
            int64_t e0, e2;
            if (px1 - px0 < NARROW) {
                int64_t e1;
                e0 = e0r; e2 = e2r; e1 = S - e0 - e2;
                while ((e0 | e1 | e2) < 0) {
                    if (++xl > px1) break;
                    e0 += sx0; e2 += sx2; e1 = S - e0 - e2;
                }
                if (xl > px1) continue;
                {
                    int64_t f0 = e0 + sx0, f2 = e2 + sx2, f1 = S - f0 - f2;
                    xr = xl;
                    while (xr < px1 && (f0 | f1 | f2) >= 0) { xr++; f0 += sx0; f2 += sx2; f1 = S - f0 - f2; }
                }
            } else {
                /* e_k(px0 + l) = e_kr + sx_k l; e1 = S - e0 - e2; columns l relative to px0
                 * (floor((K + s px0) / s) = floor(K / s) + px0: the same centres as from
                 * column 0, with no products by px0 to keep across the rows) */
                int64_t s1 = -(sx0 + sx2), e1r = S - e0r - e2r;
                int32_t l = 0, r = px1 - px0;
                if (!span_limits(sx0, e0r, &q0, 0, px1 - px0, &l, &r)
                    || !span_limits(s1, e1r, &q1, 0, px1 - px0, &l, &r)
                    || !span_limits(sx2, e2r, &q2, 0, px1 - px0, &l, &r) || l > r)
                    continue;
                xl = px0 + l; xr = px0 + r;
                e0 = e0r + sx0 * l; e2 = e2r + sx2 * l;
            }
            {
                /* exact barycentric weights at (xl, py): b gets edge 2, c gets edge 0 (Q22) */
                int64_t w1, w2;
                uint64_t col;
                uint32_t z, gzu = (uint32_t)gz;
                RS_PIX *cp = (RS_PIX *)(void *)(bd->color + (size_t)(py - bd->y0) * bd->stride) + xl;
                RS_Z *zp = (RS_Z *)bd->depth + (size_t)(py - bd->y0) * (size_t)w + (size_t)xl;
                int32_t n = xr - xl + 1, i;
                if (small) { w1 = (e2 * inv) >> 18; w2 = (e0 * inv) >> 18; }
                else { w1 = fx_divisor_trunc(&ad, e2 * ((int64_t)1 << 22)); w2 = fx_divisor_trunc(&ad, e0 * ((int64_t)1 << 22)); }
                z = (uint32_t)((int64_t)a->d + ((dzb * w1 + dzc * w2) >> 22));
                col = ca + ((uint64_t)((dcb0 * w1 + dcc0 * w2) >> 9) << 42)
                      + ((uint64_t)((dcb1 * w1 + dcc1 * w2) >> 9) << 21) + (uint64_t)((dcb2 * w1 + dcc2 * w2) >> 9);
                bd->pixels += (uint32_t)n;
#if !RS_TEX && !RS_COUNT
                {
                    /* the plain span: depth test, colour step, write */
                    RS_Z *const ze = zp + n;
                    RS_PIX *const ce = cp + n;
                    ptrdiff_t j = -(ptrdiff_t)n;      /* n >= 1; one counter to 0 */
                    (void)i;
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
}
