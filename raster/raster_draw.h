/* raster/raster_draw.h — the per-triangle code above the tiny and general paths: the
 * one-triangle entry (tri_box, tri_raster), the strip pairs (tri_quad, pair_tiny,
 * pair_wide, tri_pair, quad_shade), the pre-pass's steps (pp_steps) and the strip and
 * list loop (draw_strips), with its one named copy per variant (draw_888_z32 ..
 * draw_count), which raster.c's draw_for hands to rs_draw_band.  raster.c's own,
 * included once, after raster_tiny.h and raster_general.h; every function takes the
 * variant as its constant last argument (raster_pixel.h).
 *
 * From the band loop to a pixel: rs_draw_band -> draw_for(...) = draw_<variant> ->
 * draw_strips -> (pre-pass chunk) pp_steps -> quad_shade -> tiny_px, or (per pair)
 * tri_pair -> pair_tiny -> tri_quad -> quad_edges -> tiny_shade -> tiny_px, or (one
 * triangle) tri_raster -> tri_box -> tri_tiny_own / tri_general -> gen_tri ->
 * gen_span_plain. */
#ifndef BR_RASTER_DRAW_H
#define BR_RASTER_DRAW_H

/* One triangle (a, b, c as seen; either orientation): its box of candidate centres,
 * then the general or the tiny path.  o is the vertex of the three not in the pair whose
 * coordinate extremes ymn, ymx, xmn, xmx the caller passes (pair_wide: v1 and v2, which
 * both of a strip pair's triangles have, once for both); the box is the same.
 * onscreen: all three vertices are on screen (no outcode bits: RSI_HALF <= x <= 16 w -
 * RSI_HALF), so the columns px0 >= 0 and px1 <= w - 1 need no clamping. */
RSI_INLINE static void tri_box(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                              const rs_cvert *o, int32_t ymn, int32_t ymx, int32_t xmn, int32_t xmx,
                              const int onscreen, const int vf)
{
    int32_t xmin, xmax, ymin, ymax, px0, px1, py0, py1;
    int32_t tiny;

    {
        const int32_t ox = o->x, oy = o->y;
        int32_t lo, hi;
        ymin = ymn < oy ? ymn : oy;
        ymax = ymx > oy ? ymx : oy;
        lo = (ymin + RSI_HALF - 1) >> RSI_SUB;    /* first row whose centre is >= ymin */
        hi = (ymax - RSI_HALF) >> RSI_SUB;        /* last row whose centre is <= ymax */
        py0 = lo < bd->y0 ? bd->y0 : lo;
        py1 = hi >= bd->y1 ? bd->y1 - 1 : hi;
        if (py0 > py1) return;
        xmin = xmn < ox ? xmn : ox;
        xmax = xmx > ox ? xmx : ox;
        px0 = (xmin + RSI_HALF - 1) >> RSI_SUB;
        px1 = (xmax - RSI_HALF) >> RSI_SUB;
        /* the path choice depends on the triangle only (not on the band or screen clip) */
        tiny = px1 - px0 < TINY_W && hi - lo < TINY_H;
        if (!onscreen) {
            if (px0 < 0) px0 = 0;
            if (px1 >= bd->w) px1 = bd->w - 1;
        }
        if (px0 > px1) return;
    }
    if (RSI_UNLIKELY(!tiny)) {
        /* small: the reciprocal's bounds (raster_general.h); wide: the span by division */
        tri_general(bd, a, b, c, px0, px1, py0, py1, xmax - xmin < SMALL && ymax - ymin < SMALL,
                    px1 - px0 >= NARROW, vf);
        return;
    }
    tri_tiny_own(bd, a, b, c, px0, px1 - px0 + 1, py0, py1 - py0 + 1, vf);
}

/* One triangle (a, b, c as seen; either orientation): the out-of-line code for lists,
 * the clipper and strip triangles that are not drawn as a pair. */
RSI_NOINLINE static void tri_raster(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c, int vf)
{
    const int32_t ax = a->x, ay = a->y, bx = b->x, by = b->y;
#define TRI_RASTER_CASE(V) case V: if (RS_BUILT(V)) tri_box(bd, a, b, c, c, ay < by ? ay : by, ay > by ? ay : by, \
                                                             ax < bx ? ax : bx, ax > bx ? ax : bx, 0, V); return
    switch (vf) {
    TRI_RASTER_CASE(V_888_Z32);
    TRI_RASTER_CASE(V_888_Z16);
    TRI_RASTER_CASE(V_565_Z16);
    TRI_RASTER_CASE(V_565_Z32);
    TRI_RASTER_CASE(V_888_NOZ);
    TRI_RASTER_CASE(V_565_NOZ);
    TRI_RASTER_CASE(V_888_Z32_TEX);
    TRI_RASTER_CASE(V_888_Z16_TEX);
    TRI_RASTER_CASE(V_565_Z16_TEX);
    TRI_RASTER_CASE(V_565_Z32_TEX);
    TRI_RASTER_CASE(V_COUNT);
    default: return;
    }
#undef TRI_RASTER_CASE
}

/* Row j (1 .. 3) of quad_masks: the three outer edges stepped down one row, the
 * diagonal and the fourth edge from them, the rows' lanes at bit 15 - j. */
RSI_INLINE static void quad_row(uint64_t *P01, uint64_t *P20, uint64_t *P13, uint64_t K1, uint64_t K2,
                               uint64_t s01, uint64_t s20, uint64_t s13, uint64_t xm, int j,
                               uint64_t *M1, uint64_t *M2)
{
    uint64_t PD, P32;
    *P01 += s01; *P20 += s20; *P13 += s13;
    PD = K1 - *P01 - *P20;
    P32 = K2 + PD - *P13;
    *M1 |= (*P01 & *P20 & PD & xm) >> j;
    *M2 |= (*P13 & P32 & ~PD & xm) >> j;
}

/* The coverage of a strip quad's two triangles over one group of columns (see
 * tri_quad): P01, P20, P13 the packed biased values of row 0 of three outer edges, K1,
 * K2 the packed S + lane offsets from which the diagonal and the fourth edge follow,
 * s01, s20, s13 the row steps; rows 0 .. ny-1 (ny <= TINY_H = 4, unrolled) at bit 15 - j. */
RSI_INLINE static void quad_masks(uint64_t P01, uint64_t P20, uint64_t P13, uint64_t K1, uint64_t K2,
                                 uint64_t s01, uint64_t s20, uint64_t s13, uint64_t xm, int32_t ny,
                                 uint64_t *m1, uint64_t *m2)
{
    uint64_t PD = K1 - P01 - P20, P32 = K2 + PD - P13;
    uint64_t M1 = P01 & P20 & PD & xm, M2 = P13 & P32 & ~PD & xm;
    if (ny > 1) {
        quad_row(&P01, &P20, &P13, K1, K2, s01, s20, s13, xm, 1, &M1, &M2);
        if (ny > 2) {
            quad_row(&P01, &P20, &P13, K1, K2, s01, s20, s13, xm, 2, &M1, &M2);
            if (ny > 3) quad_row(&P01, &P20, &P13, K1, K2, s01, s20, s13, xm, 3, &M1, &M2);
        }
    }
    *m1 = M1; *m2 = M2;
}

/* The coverage and shading of a strip quad from its edge set-up (tri_quad's second half,
 * for the per-pair code; the pre-pass's quads get their coverage from raster.c's
 * pp_prepass and shade in quad_shade): a1, a2 the two triangles' doubled areas (> 0), f01, f20, f13 the
 * biased values of three outer edges at the first candidate (px0, py0), A, B their steps
 * per sub-pixel across and down, S1, S2 the areas minus the biases; wide: the box may have
 * a second group of columns (nx up to TINY_W). */
RSI_INLINE static void quad_edges(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                        const rs_cvert *v3, int32_t px0, int32_t nx, int32_t py0, int32_t ny,
                                        uint64_t xm, int32_t a1, int32_t a2, int32_t f01, int32_t f20, int32_t f13,
                                        int32_t A01, int32_t A20, int32_t A13, int32_t B01, int32_t B20, int32_t B13,
                                        int32_t S1, int32_t S2, const int wide, const int vf)
{
    const uint64_t ones = bd->ones, st = bd->steps16;
    /* lanes as in tri_tiny: e + 2^15 of candidates px0 .. px0+3; PD = T1's diagonal,
     * P32 = T2's third edge = S2 - (-1 - eD) - e13, i.e. K2 + PD - P13 with K2 = S2 + 0x8001 */
    uint64_t P01 = (uint64_t)(int64_t)(f01 + 0x8000) * ones + (uint64_t)(int64_t)A01 * st;
    uint64_t P20 = (uint64_t)(int64_t)(f20 + 0x8000) * ones + (uint64_t)(int64_t)A20 * st;
    uint64_t P13 = (uint64_t)(int64_t)(f13 + 0x8000) * ones + (uint64_t)(int64_t)A13 * st;
    const uint64_t K1 = (uint64_t)(int64_t)(S1 + 3 * 0x8000) * ones;
    const uint64_t K2 = (uint64_t)(int64_t)(S2 + 0x8001) * ones;
    uint64_t s01 = 0, s20 = 0, s13 = 0, M1, M2;
    if (ny > 1) {
        const uint64_t o16 = bd->ones16;
        s01 = (uint64_t)(int64_t)B01 * o16;
        s20 = (uint64_t)(int64_t)B20 * o16;
        s13 = (uint64_t)(int64_t)B13 * o16;
    }
    uint64_t M1w = 0, M2w = 0, P01w = 0, P20w = 0, P13w = 0;
    quad_masks(P01, P20, P13, K1, K2, s01, s20, s13, xm, ny, &M1, &M2);
    if (wide && nx > 4) {
        /* the second group: four pixels (64 A sub-pixels) to the right */
        P01w = P01 + (uint64_t)(int64_t)(A01 * 64) * ones;
        P20w = P20 + (uint64_t)(int64_t)(A20 * 64) * ones;
        P13w = P13 + (uint64_t)(int64_t)(A13 * 64) * ones;
        quad_masks(P01w, P20w, P13w, K1, K2, s01, s20, s13, TINY_XM2(nx), ny,
                          &M1w, &M2w);
    }
    /* T1: base v0, weight of v1 from the edge v2-v0 (P20), of v2 from v0-v1 (P01);
     * T2: base v2, weight of v1 from the edge v3-v2 (P32), of v3 from the diagonal (~PD) */
    if (M1 | M1w | M2 | M2w) {
        /* the addresses once for both triangles */
        void *const crow = band_crow(bd, py0, px0, vf), *const zrow = band_zrow(bd, py0, px0, vf);
        if (M1 | M1w)
            tiny_shade(bd, v0, v1, v2, a1, M1, P01, s01, P20, s20, crow, zrow, M1w, P01w, P20w, vf);
        if (M2 | M2w) {
            const uint64_t PD = K1 - P01 - P20, PDw = K1 - P01w - P20w;
            tiny_shade(bd, v2, v1, v3, a2, M2, ~PD, s01 + s20, K2 + PD - P13,
                              (uint64_t)0 - s01 - s20 - s13, crow, zrow, M2w, ~PDw, K2 + PDw - P13w, vf);
        }
    }
}

/* A strip pair T1 = (v0, v1, v2), T2 = (v2, v1, v3) whose two triangles have the same
 * orientation (neg = 1: both front faces, is_front of the areas as computed) and a tiny joint box
 * (px0, py0, nx x ny candidates, xm the first group's lane mask): a quad split by the
 * diagonal v1-v2.  Four outer edges and the diagonal: T2's diagonal edge function is
 * the exact negation of T1's and its top-left bias the complement (b21 = 1 - b12; v1 !=
 * v2 since both areas are non-zero), so T2's biased diagonal value is -1 - T1's, the
 * bitwise complement of T1's packed lanes.  (X_k, Y_k) = v_k relative to the first
 * candidate centre; e_PQ = X_P Y_Q - Y_P X_Q is the edge function P->Q there (the same
 * line function tri_tiny evaluates from its vertex a).  Edges are oriented so that the
 * inside is positive (reversed when neg).  Every value is the one tri_tiny computes
 * for the same triangle, so the pixels are those of two tri_tiny calls (the two
 * triangles cover disjoint centres: order does not matter). */
RSI_INLINE static void tri_quad(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                      const rs_cvert *v3, int32_t px0, int32_t nx, int32_t py0, int32_t ny,
                                      uint64_t xm, int32_t ar1, int32_t ar2, const int neg, const int wide,
                              const int vf)
{
    const int32_t ox0 = px0 * RSI_SUBONE + RSI_HALF, oy0 = py0 * RSI_SUBONE + RSI_HALF;   /* the first candidate */
    const int32_t X0 = v0->x - ox0, Y0 = v0->y - oy0, X1 = v1->x - ox0, Y1 = v1->y - oy0;
    const int32_t X2 = v2->x - ox0, Y2 = v2->y - oy0, X3 = v3->x - ox0, Y3 = v3->y - oy0;
    const int32_t e01 = X0 * Y1 - Y0 * X1, e12 = X1 * Y2 - Y1 * X2, e20 = X2 * Y0 - Y2 * X0;
    const int32_t e13 = X1 * Y3 - Y1 * X3, e32 = X3 * Y2 - Y3 * X2;
    bd->tris += 2;
    if (nx == 1 && ny == 1) {
        /* one candidate, at the origin: its edge values are the e_PQ themselves; an edge
         * value < 0 rejects whatever the bias, so biases only for a triangle that may hold it */
        const int32_t g01 = sg(e01, neg), g12 = sg(e12, neg), g20 = sg(e20, neg);
        if ((g01 | g12 | g20) >= 0) {
            const int32_t f01 = g01 - tl_bias16(sg(v0->y - v1->y, neg), sg(v1->x - v0->x, neg)), f20 = g20 - tl_bias16(sg(v2->y - v0->y, neg), sg(v0->x - v2->x, neg));
            const int32_t fD = g12 - tl_bias16(sg(v1->y - v2->y, neg), sg(v2->x - v1->x, neg));
            if ((f01 | f20 | fD) >= 0) {
                tiny_pixel(bd, v0, v1, v2, sg(ar1, neg), f01, f20, py0, px0, vf);
                return;     /* T2 cannot hold it: T2's diagonal value is -1 - fD */
            }
        }
        {
            const int32_t g13 = sg(e13, neg), g32 = sg(e32, neg);
            if ((g13 | g32 | -g12) >= 0) {
                const int32_t f13 = g13 - tl_bias16(sg(v1->y - v3->y, neg), sg(v3->x - v1->x, neg)), f32 = g32 - tl_bias16(sg(v3->y - v2->y, neg), sg(v2->x - v3->x, neg));
                const int32_t fT = -g12 - 1 + tl_bias16(sg(v1->y - v2->y, neg), sg(v2->x - v1->x, neg));
                if ((f13 | f32 | fT) >= 0)
                    tiny_pixel(bd, v2, v1, v3, sg(ar2, neg), fT, f32, py0, px0, vf);
            }
            return;
        }
    }
    {
        const int32_t A01 = sg(v0->y - v1->y, neg), B01 = sg(v1->x - v0->x, neg), A12 = sg(v1->y - v2->y, neg), B12 = sg(v2->x - v1->x, neg);
        const int32_t A20 = sg(v2->y - v0->y, neg), B20 = sg(v0->x - v2->x, neg), A13 = sg(v1->y - v3->y, neg), B13 = sg(v3->x - v1->x, neg);
        const int32_t A32 = sg(v3->y - v2->y, neg), B32 = sg(v2->x - v3->x, neg);
        const int32_t b01 = tl_bias16(A01, B01), b12 = tl_bias16(A12, B12), b20 = tl_bias16(A20, B20);
        const int32_t b13 = tl_bias16(A13, B13), b32 = tl_bias16(A32, B32);
        /* S = area2 - the three biases; T2's diagonal bias is 1 - b12 */
        const int32_t S1 = sg(ar1, neg) - b01 - b12 - b20, S2 = sg(ar2, neg) - 1 + b12 - b13 - b32;
        const int32_t f01 = sg(e01, neg) - b01, f20 = sg(e20, neg) - b20, f13 = sg(e13, neg) - b13;
        quad_edges(bd, v0, v1, v2, v3, px0, nx, py0, ny, xm, sg(ar1, neg), sg(ar2, neg), f01, f20, f13,
                          A01, A20, A13, B01, B20, B13, S1, S2, wide, vf);
    }
}

/* The doubled signed areas of a strip pair's T1 = (v0, v1, v2) and T2 (from its vertex
 * v2, as tri_tiny); front faces: is_front. */
RSI_INLINE static int32_t pair_area1(const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2)
{
    return (v1->x - v0->x) * (v2->y - v0->y) - (v2->x - v0->x) * (v1->y - v0->y);
}
RSI_INLINE static int32_t pair_area2(const rs_cvert *v1, const rs_cvert *v2, const rs_cvert *v3)
{
    return (v1->x - v2->x) * (v3->y - v2->y) - (v3->x - v2->x) * (v1->y - v2->y);
}

/* A strip pair (see tri_pair) over its tiny joint box px0, py0, nx x ny with nx <= 4 (one
 * group of columns: the inlined common case): orientations (cull, zero area), then
 * tri_quad, or tri_tiny one triangle at a time. */
RSI_INLINE static void pair_tiny(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                       const rs_cvert *v3, int32_t px0, int32_t nx, int32_t py0, int32_t ny, const int vf)
{
    const uint64_t xm = TINY_XM4(nx);
    const int32_t ar1 = pair_area1(v0, v1, v2), ar2 = pair_area2(v1, v2, v3);
    if (bd->cull && !is_front(ar1) && !is_front(ar2)) return;    /* both culled or of zero area */
    if (is_front(ar1) && is_front(ar2))
        tri_quad(bd, v0, v1, v2, v3, px0, nx, py0, ny, xm, ar1, ar2, 1, 0, vf);
    else if (is_back(ar1) && is_back(ar2) && !bd->cull)
        tri_quad(bd, v0, v1, v2, v3, px0, nx, py0, ny, xm, ar1, ar2, 0, 0, vf);
    else {
        /* mixed orientations or a zero area (rare): one triangle at a time */
        const int32_t ox0 = px0 * RSI_SUBONE + RSI_HALF, oy0 = py0 * RSI_SUBONE + RSI_HALF;   /* the first candidate */
        if (bd->cull) {
            /* culled or zero area: area >= 0 draws nothing */
            if (is_front(ar1)) tri_tiny_any(bd, v0, v1, v2, px0, nx, py0, ny, xm, ox0, oy0, vf);
            else if (is_front(ar2)) tri_tiny_any(bd, v2, v1, v3, px0, nx, py0, ny, xm, ox0, oy0, vf);
        } else {
            tri_tiny_any(bd, v0, v1, v2, px0, nx, py0, ny, xm, ox0, oy0, vf);
            tri_tiny_any(bd, v2, v1, v3, px0, nx, py0, ny, xm, ox0, oy0, vf);
        }
    }
}

/* The strip pairs that tri_pair's inlined code leaves: joint boxes of more than four
 * columns (tiny up to TINY_W: both groups of columns) or more than TINY_H rows or
 * TINY_W columns (each triangle through tri_raster), out of line so that the strip
 * loop's code has one group of columns only.  lo .. hi, xl .. xh: the joint box's rows
 * and columns of centres, unclipped; lo <= hi (tri_pair returns when there is no row). */
RSI_INLINE static void pair_wide_body(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                      const rs_cvert *v3, int32_t lo, int32_t hi, int32_t xl, int32_t xh, const int vf)
{
    /* no column of centres: neither triangle's own (sub-)box holds one */
    if (xh < xl) return;
    if (hi - lo < TINY_H && xh - xl < TINY_W) {
        /* as pair_tiny, but one copy of tri_quad (the orientation a variable), and mixed
         * orientations one triangle at a time as below (the pixels of a pair are those of
         * two tri_raster calls; tri_tiny_own culls): less code for the rarer wide boxes */
        const int32_t py0 = lo < bd->y0 ? bd->y0 : lo, py1 = hi >= bd->y1 ? bd->y1 - 1 : hi;
        const int32_t nx = xh - xl + 1;
        if (py0 > py1) return;
        const int32_t ar1 = pair_area1(v0, v1, v2), ar2 = pair_area2(v1, v2, v3);
        if (bd->cull && !is_front(ar1) && !is_front(ar2)) return;    /* both culled or of zero area */
        if ((is_front(ar1) && is_front(ar2)) || (is_back(ar1) && is_back(ar2) && !bd->cull)) {
            tri_quad(bd, v0, v1, v2, v3, xl, nx, py0, py1 - py0 + 1, TINY_XM(nx), ar1, ar2, is_front(ar1), 1, vf);
            return;
        }
    }
    /* each triangle on its own, as tri_raster draws it (inlined: no calls for the
     * triangles without a row or column of centres, and none to tri_raster); both
     * callers (tri_pair, the pre-pass's PK_WIDE) have all four vertices on screen */
    {
        const int32_t x1 = v1->x, y1 = v1->y, x2 = v2->x, y2 = v2->y;
        const int32_t ymn = y1 < y2 ? y1 : y2, ymx = y1 > y2 ? y1 : y2, xmn = x1 < x2 ? x1 : x2, xmx = x1 > x2 ? x1 : x2;
        tri_box(bd, v0, v1, v2, v0, ymn, ymx, xmn, xmx, 1, vf);
        tri_box(bd, v2, v1, v3, v3, ymn, ymx, xmn, xmx, 1, vf);
    }
}

/* pair_wide out of line, one case a variant. */
RSI_NOINLINE static void pair_wide(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                  const rs_cvert *v3, int32_t lo, int32_t hi, int32_t xl, int32_t xh, int vf)
{
#define PAIR_WIDE_CASE(V) case V: if (RS_BUILT(V)) pair_wide_body(bd, v0, v1, v2, v3, lo, hi, xl, xh, V); return
    switch (vf) {
    PAIR_WIDE_CASE(V_888_Z32);
    PAIR_WIDE_CASE(V_888_Z16);
    PAIR_WIDE_CASE(V_565_Z16);
    PAIR_WIDE_CASE(V_565_Z32);
    PAIR_WIDE_CASE(V_888_Z32_TEX);
    PAIR_WIDE_CASE(V_888_Z16_TEX);
    PAIR_WIDE_CASE(V_565_Z16_TEX);
    PAIR_WIDE_CASE(V_565_Z32_TEX);
    PAIR_WIDE_CASE(V_COUNT);
    default: return;
    }
#undef PAIR_WIDE_CASE
}

/* Two consecutive strip triangles T1 = (v0, v1, v2) and T2 = (v2, v1, v3) whose four
 * vertices are all on screen (no outcode bits: no clipping, no column clamping).  When
 * the pair's joint bounding box has at most TINY_W x TINY_H candidate centres, both are
 * drawn by the tiny path over that joint box: one bounding box for two triangles.  The
 * pixels are those of two separate tri_raster calls: a triangle inside the joint box is
 * tiny on its own (its own box is a sub-box), the candidates of the joint box outside
 * its own box fail its edge tests (a centre with all e_k >= 0 lies in the closed
 * triangle), the joint box's extent is within the lane bound, and T1 is drawn before
 * T2.  Pairs whose triangles have the same orientation (the common case) go through
 * tri_quad (shared diagonal); others through tri_tiny one at a time.  A larger joint
 * box: each triangle through tri_raster. */
RSI_INLINE static void tri_pair_body(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                     const rs_cvert *v3, const int vf)
{
    int32_t lo, hi, xl, xh, py0, py1, px0, px1;
    {
        int32_t t, u, ymin, ymax, xmin, xmax;
        t = v0->y < v1->y ? v0->y : v1->y; u = v2->y < v3->y ? v2->y : v3->y; ymin = t < u ? t : u;
        t = v0->y > v1->y ? v0->y : v1->y; u = v2->y > v3->y ? v2->y : v3->y; ymax = t > u ? t : u;
        lo = (ymin + RSI_HALF - 1) >> RSI_SUB; hi = (ymax - RSI_HALF) >> RSI_SUB;
        /* no row of centres (common: slivers near the horizon):
         * done before the columns are looked at */
        if (hi < lo) return;
        t = v0->x < v1->x ? v0->x : v1->x; u = v2->x < v3->x ? v2->x : v3->x; xmin = t < u ? t : u;
        t = v0->x > v1->x ? v0->x : v1->x; u = v2->x > v3->x ? v2->x : v3->x; xmax = t > u ? t : u;
        xl = (xmin + RSI_HALF - 1) >> RSI_SUB; xh = (xmax - RSI_HALF) >> RSI_SUB;
    }
    if (RSI_UNLIKELY(hi - lo >= TINY_H || xh - xl >= 4)) {
        pair_wide(bd, v0, v1, v2, v3, lo, hi, xl, xh, vf);
        return;
    }
    py0 = lo < bd->y0 ? bd->y0 : lo;
    py1 = hi >= bd->y1 ? bd->y1 - 1 : hi;
    /* all four vertices on screen (no outcode bits): RSI_HALF <= x <= 16 w - RSI_HALF, so
     * 0 <= xl and xh <= w - 1 without clamping */
    px0 = xl;
    px1 = xh;
    if (py0 > py1 || px0 > px1) return;
    pair_tiny(bd, v0, v1, v2, v3, px0, px1 - px0 + 1, py0, py1 - py0 + 1, vf);
}


/* tri_pair for the textured and counting variants: out of line, one case a variant. */
RSI_NOINLINE static void tri_pair_slow(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                      const rs_cvert *v3, int vf)
{
#define TRI_PAIR_CASE(V) case V: if (RS_BUILT(V)) tri_pair_body(bd, v0, v1, v2, v3, V); return
    switch (vf) {
    TRI_PAIR_CASE(V_888_Z32_TEX);
    TRI_PAIR_CASE(V_888_Z16_TEX);
    TRI_PAIR_CASE(V_565_Z16_TEX);
    TRI_PAIR_CASE(V_565_Z32_TEX);
    TRI_PAIR_CASE(V_COUNT);
    default: return;
    }
#undef TRI_PAIR_CASE
}

RSI_INLINE static void tri_pair(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                               const rs_cvert *v3, const int vf)
{
    if (VF_SLOW(vf)) tri_pair_slow(bd, v0, v1, v2, v3, vf);
    else tri_pair_body(bd, v0, v1, v2, v3, vf);
}

#if RS_PREPASS
/* One triangle a, b, c (area2 > 0) of a pre-pass quad (PK_QUAD): m its covered
 * candidates (bit 8 j + i, see pp_soa), E its edge values (E[4 PP_STEPS k] opposite b,
 * E[4 PP_STEPS k + PP_STEPS] opposite c for candidate k), crow / zrow the colour and
 * depth of candidate 0, coff / zoff the candidates' offsets from them in bytes; tight (a
 * constant): colour and depth entries of one size and rows w entries apart, where
 * coff[k] is also candidate k's depth offset (one table load per pixel). */
RSI_INLINE static void quad_shade_body(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                      int32_t area2, uint32_t m, const int16_t *E, void *crow, void *zrow,
                                      const size_t *coff, const size_t *zoff, const int tight, const int vf)
{
    tiny_tri t;
    tiny_setup(&t, bd, a, b, c, area2, vf);
    do {
        const size_t k = ctz64(m);
        const size_t zo = tight ? coff[k] : zoff[k];
        m &= m - 1;
        tiny_px(bd, &t, E[4 * PP_STEPS * k], E[4 * PP_STEPS * k + PP_STEPS], (uint8_t *)zrow + zo,
                (uint8_t *)crow + coff[k], vf);
    } while (m);
}

/* quad_shade for the textured and counting variants: out of line, one case a variant. */
RSI_NOINLINE static void quad_shade_slow(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                        int32_t area2, uint32_t m, const int16_t *E, void *crow, void *zrow,
                                        const size_t *coff, const size_t *zoff, int tight, int vf)
{
#define QUAD_SHADE_CASE(V) case V: if (RS_BUILT(V)) quad_shade_body(bd, a, b, c, area2, m, E, crow, zrow, coff, zoff, tight, V); return
    switch (vf) {
    QUAD_SHADE_CASE(V_888_Z32_TEX);
    QUAD_SHADE_CASE(V_888_Z16_TEX);
    QUAD_SHADE_CASE(V_565_Z16_TEX);
    QUAD_SHADE_CASE(V_565_Z32_TEX);
    QUAD_SHADE_CASE(V_COUNT);
    default: return;
    }
#undef QUAD_SHADE_CASE
}

RSI_INLINE static void quad_shade(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                 int32_t area2, uint32_t m, const int16_t *E, void *crow, void *zrow,
                                 const size_t *coff, const size_t *zoff, const int tight, const int vf)
{
    if (VF_SLOW(vf)) quad_shade_slow(bd, a, b, c, area2, m, E, crow, zrow, coff, zoff, tight, vf);
    else quad_shade_body(bd, a, b, c, area2, m, E, crow, zrow, coff, zoff, tight, vf);
}
#endif

/* One strip triangle (draw_strips' loop and pp_steps): triangle = (p, q, v), v the new
 * vertex; outcodes read where tested (fewer live registers); the clipper gets the same
 * order (indices ip, iq, iv).  Rejected by the outcodes: nothing; near the near plane or
 * outside the guard band: the clipper; else tri_raster. */
RSI_INLINE static void strip_tri(band *bd, const rs_cvert *p, const rs_cvert *q, const rs_cvert *v,
                                uint32_t ip, uint32_t iq, uint32_t iv, const int vf)
{
    if (!(p->c & q->c & v->c & REJECT)) {
        if (RSI_UNLIKELY((p->c | q->c | v->c) & SLOW)) tri_clip(bd, ip, iq, iv, vf);
        else tri_raster(bd, p, q, v, vf);
    }
}

#if RS_PREPASS
/* A step's fields after pp_prepass: of int16_t and uint32_t arrays, and its vertices
 * (v0 = ve[st], v1 = vo[st], v2 = ve[st + 1], v3 = vo[st + 1]), read where used (none
 * are carried).  off: offsetof(pp_soa, field). */
RSI_INLINE static int32_t pp_i16(const pp_soa *q, size_t off, size_t st)
{
    return *(const int16_t *)(const void *)((const char *)(const void *)q + off + 2 * st);
}
RSI_INLINE static uint32_t pp_u32(const pp_soa *q, size_t off, size_t st)
{
    return *(const uint32_t *)(const void *)((const char *)(const void *)q + off + 4 * st);
}
RSI_INLINE static const rs_cvert *pp_v(const pp_soa *q, size_t off, size_t st)
{
    return *(const rs_cvert *const *)(const void *)((const char *)(const void *)q + off + sizeof(void *) * st);
}
#define PP_FIELD(F) offsetof(pp_soa, F)

/* The steps of a pre-pass chunk q after pp_prepass (sp: its first step's two new
 * indices): the work list's steps in order, by kind; ctight as in draw_strips, a
 * constant (draw_strips has a copy for each case: no test per step). */
RSI_INLINE static void pp_steps(band *bd, const pp_soa *q, const br_index *sp, const size_t *coff,
                               const size_t *zoff, const uintptr_t cdiff, const int ctight, const int vf)
{
    /* the address of frame row 0's depth, were the band's buffer the whole frame's
     * (an integer, modulo 2^N): row py0's is zb0 plus py0 w entries */
    const uintptr_t zb0 = (uintptr_t)bd->depth - (uintptr_t)bd->y0 * (uintptr_t)bd->w * z_bytes(vf);
    for (uint32_t wk = q->work; wk; wk &= wk - 1) {
        /* the steps that are not PK_NONE (pp_prepass's work list), in order */
        const size_t st = ctz32(wk);
        const int32_t kind = pp_i16(q, PP_FIELD(kind), st);
        if (RSI_LIKELY(kind == PK_QUAD)) {
            const uint32_t m1 = pp_u32(q, PP_FIELD(m1), st), m2 = pp_u32(q, PP_FIELD(m2), st);    /* coverage */
            bd->tris += (uint32_t)pp_i16(q, PP_FIELD(nt), st);
            if (m1 | m2) {
                const int16_t *E = (const int16_t *)(const void *)((const char *)(const void *)q + PP_FIELD(e) + 2 * st);
                const int32_t py0 = pp_i16(q, PP_FIELD(py0), st), px0 = pp_i16(q, PP_FIELD(px0), st);
                void *zrow, *crow;
                if (ctight) {
                    const uintptr_t za = zb0 + ((size_t)py0 * (size_t)bd->w + (size_t)px0) * z_bytes(vf);
                    zrow = (void *)za;
                    crow = (void *)(za + cdiff);
                } else {
                    crow = band_crow(bd, py0, px0, vf);
                    zrow = band_zrow(bd, py0, px0, vf);
                }
                if (m1)
                    quad_shade(bd, pp_v(q, PP_FIELD(ve), st), pp_v(q, PP_FIELD(vo), st), pp_v(q, PP_FIELD(ve), st + 1),
                               pp_i16(q, PP_FIELD(a1), st), m1, E, crow, zrow, coff, zoff, ctight, vf);
                if (m2)
                    quad_shade(bd, pp_v(q, PP_FIELD(ve), st + 1), pp_v(q, PP_FIELD(vo), st), pp_v(q, PP_FIELD(vo), st + 1),
                               pp_i16(q, PP_FIELD(a2), st), m2, E + 2 * PP_STEPS, crow, zrow, coff, zoff, ctight, vf);
            }
        } else if (kind == PK_WIDE) {
            pair_wide(bd, pp_v(q, PP_FIELD(ve), st), pp_v(q, PP_FIELD(vo), st), pp_v(q, PP_FIELD(ve), st + 1),
                      pp_v(q, PP_FIELD(vo), st + 1), pp_i16(q, PP_FIELD(py0), st), pp_i16(q, PP_FIELD(ny), st),
                      pp_i16(q, PP_FIELD(px0), st), pp_i16(q, PP_FIELD(nx), st), vf);
        } else if (kind == PK_SLOW) {
            /* (pairs whose two triangles the outcodes reject are PK_NONE) */
            const br_index *const ip = sp + 2 * st;
            strip_tri(bd, pp_v(q, PP_FIELD(ve), st), pp_v(q, PP_FIELD(vo), st), pp_v(q, PP_FIELD(ve), st + 1),
                      ip[-2], ip[-1], ip[0], vf);
            strip_tri(bd, pp_v(q, PP_FIELD(ve), st + 1), pp_v(q, PP_FIELD(vo), st), pp_v(q, PP_FIELD(vo), st + 1),
                      ip[0], ip[-1], ip[1], vf);
        }
    }
}
#undef PP_FIELD
#endif

/* The strip and list loop of one band: per primitive, per chunk of RS_CHUNK triangles
 * that touches the band (the chunk table), the strip pairs through the pre-pass or the
 * per-pair code, list triangles one at a time. */
RSI_INLINE static void draw_strips(band *bd, const int vf)
{
    const rs_frame *f = bd->f;
    const rs_cvert *cache = f->cache;
    const int16_t *ch = f->chunks;     /* per chunk of RS_CHUNK triangles: rows touched */
    int32_t p;
#if RS_PREPASS
    /* the pre-pass quads' candidates 8 j + i: offsets of (i, j) in the colour and depth rows,
     * in bytes */
    /* ctight: colour and depth entries of the same size, rows w entries apart (XRGB8888
     * with 32-bit depth, RGB565 with 16-bit depth, no padding): a pixel's colour is cdiff
     * bytes after its depth (addresses as integers), and its offsets from the first
     * candidate's colour and depth are the same number of bytes */
    const int ctight = px_bytes(vf) == z_bytes(vf) && bd->stride == (size_t)bd->w * px_bytes(vf);
    const uintptr_t cdiff = (uintptr_t)bd->color - (uintptr_t)bd->depth;
    size_t coff[TINY_W * TINY_H], zoff[TINY_W * TINY_H];
    for (p = 0; p < TINY_W * TINY_H; p++) {
        coff[p] = (size_t)(p >> 3) * bd->stride + (size_t)(p & 7) * px_bytes(vf);
        zoff[p] = ((size_t)(p >> 3) * (size_t)bd->w + (size_t)(p & 7)) * z_bytes(vf);
    }
#endif
    for (p = 0; p < f->nprims; p++) {
        const rs_prim *pr = &f->prims[p];
        const br_index *s = pr->idx;
        uint32_t k, nt = rs_prim_tris(pr), t0;
        if (nt == 0) continue;
        for (t0 = 0; t0 < nt; t0 += RS_CHUNK, ch = ch ? ch + 2 : ch) {
            uint32_t t1 = nt - t0 < RS_CHUNK ? nt : t0 + RS_CHUNK;
            if (ch && (ch[1] < bd->y0 || ch[0] >= bd->y1)) continue;   /* chunk misses the band */
            if (pr->kind == RS_STRIP) {
                if (vf & VF_NOZ) break;     /* (refused by rs_draw_band: no strip order is
                                               back to front) */
                /* sliding window: one new vertex per triangle; triangle t = (s[t], s[t+1],
                 * s[t+2]), the first two swapped for odd t */
                {
                    /* a chunk whose vertices s[t0 .. t1 + 1] all lie beyond one side (or
                     * behind the near plane, or beyond the far one): every triangle of it is
                     * rejected by its outcodes, as each would be below, so nothing is drawn
                     * or counted.  Read outcodes only, two vertices a test, and stop at the
                     * first pair that clears the last common bit (a chunk with a vertex on
                     * screen: its first pair or two; one test a pair).
                     * With a chunk table, chunk_rows (xform.c) has
                     * already made such chunks miss every band, once per frame, and the
                     * others stop here at once (testing for the table first costs the
                     * whole-frame loop more). */
                    const br_index *ip = s + t0 + 1, *const ie = s + t1 + 2;
                    uint32_t am = cache[s[t0]].c & REJECT;
                    /* (at least three vertices) */
                    for (; am && ip + 1 < ie; ip += 2) am &= cache[ip[0]].c & cache[ip[1]].c;
                    if (am && ip < ie) am &= cache[*ip].c;
                    if (am) continue;
                }
                const rs_cvert *v0 = &cache[s[t0]], *v1 = &cache[s[t0 + 1]];
                /* two triangles per step (even, then odd with its first two swapped):
                 * chunks start at even t0; sp points at the step's two new indices */
                const br_index *sp = s + t0 + 2;
                const br_index *const se = s + t1 + 1;     /* steps while sp < se */
#if RS_PREPASS
                /* The chunk's steps set up by the pre-pass (the vertices gathered first:
                 * the low 16 bits of x and y, the outcode), then masks and shading here,
                 * whether the chunk lies inside the band or crosses its edges: the
                 * pre-pass cuts each step's box to the band's rows and passes over a
                 * group of PP_L steps that draw nothing in the band at the cost of its
                 * bounds, which costs less than the per-pair code below at every band
                 * height (docs/perf-history.md). */
                {
                    pp_soa q;
                    const int32_t n = (int32_t)((se - sp + 1) / 2);
                    pp_prepass(bd, &q, cache, s + t0, n);
                    if (ctight) pp_steps(bd, &q, sp, coff, zoff, cdiff, 1, vf);
                    else pp_steps(bd, &q, sp, coff, zoff, cdiff, 0, vf);
                    v0 = q.ve[n]; v1 = q.vo[n];
                    sp += 2 * n;
                }
#else
                {
                    uint32_t c01 = v0->c | v1->c;      /* carried: the previous step's c23 */
                    for (; sp < se; sp += 2) {
                        const rs_cvert *v2 = &cache[sp[0]], *v3;
                        uint32_t c23;
                        v3 = &cache[sp[1]];
                        c23 = v2->c | v3->c;
                        if (RSI_LIKELY(!((c01 | c23) & (SLOW | REJECT)))) {
                            /* all four vertices on screen (the common case): no further outcode
                             * tests, no clamping to the screen's columns */
                            tri_pair(bd, v0, v1, v2, v3, vf);
                            v0 = v2; v1 = v3; c01 = c23;
                            continue;
                        }
                        c01 = c23;
                        {
                            const uint32_t c12 = v1->c & v2->c;
                            if ((c12 & v0->c & REJECT) && (c12 & v3->c & REJECT)) {
                                v0 = v2; v1 = v3;       /* both rejected by outcodes */
                                continue;
                            }
                            /* clipped, partly off screen or one of the two rejected: one at a time */
                        }
                        strip_tri(bd, v0, v1, v2, sp[-2], sp[-1], sp[0], vf);
                        v3 = &cache[sp[1]];
                        strip_tri(bd, v2, v1, v3, sp[0], sp[-1], sp[1], vf);
                        v0 = v2; v1 = v3;
                    }
                }
#endif
                if (sp < s + t1 + 2) {
                    const rs_cvert *v2 = &cache[sp[0]];
                    strip_tri(bd, v0, v1, v2, sp[-2], sp[-1], sp[0], vf);
                }
            } else {
                for (k = 3 * t0; k < 3 * t1; k += 3) {
                    uint32_t ia = s[k], ib = s[k + 1], ic = s[k + 2];
                    const rs_cvert *va = &cache[ia], *vb = &cache[ib], *vc = &cache[ic];
                    if (va->c & vb->c & vc->c & REJECT) continue;
                    if ((va->c | vb->c | vc->c) & SLOW) { tri_clip(bd, ia, ib, ic, vf); continue; }
                    /* tri_raster's body for this variant, without its call and switch: its
                     * first test leaves a triangle with no pixel-centre row in the band
                     * (many of a list's, as the water surfaces' shore slivers) */
                    tri_box(bd, va, vb, vc, vc, va->y < vb->y ? va->y : vb->y, va->y > vb->y ? va->y : vb->y,
                            va->x < vb->x ? va->x : vb->x, va->x > vb->x ? va->x : vb->x, 0, vf);
                }
            }
        }
    }
}

/* The named copies of the strip loop, one a variant: what draw_for (raster.c) hands
 * out.  PP_SCHED: raster.c (GCC's pre-RA scheduling with register pressure on x86-64). */
PP_SCHED static void draw_888_z32(band *bd) { draw_strips(bd, V_888_Z32); }
PP_SCHED static void draw_888_z16(band *bd) { draw_strips(bd, V_888_Z16); }
PP_SCHED static void draw_565_z16(band *bd) { draw_strips(bd, V_565_Z16); }
PP_SCHED static void draw_565_z32(band *bd) { draw_strips(bd, V_565_Z32); }
PP_SCHED static void draw_888_z32_tex(band *bd) { draw_strips(bd, V_888_Z32_TEX); }
PP_SCHED static void draw_888_z16_tex(band *bd) { draw_strips(bd, V_888_Z16_TEX); }
PP_SCHED static void draw_565_z16_tex(band *bd) { draw_strips(bd, V_565_Z16_TEX); }
PP_SCHED static void draw_565_z32_tex(band *bd) { draw_strips(bd, V_565_Z32_TEX); }
PP_SCHED static void draw_count(band *bd) { draw_strips(bd, V_COUNT); }
PP_SCHED static void draw_888_noz(band *bd) { draw_strips(bd, V_888_NOZ); }
PP_SCHED static void draw_565_noz(band *bd) { draw_strips(bd, V_565_NOZ); }

#endif
