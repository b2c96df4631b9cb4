/* raster/raster_tmpl.h — the per-triangle code, specialised per state set.
 * Included by raster.c once per (pixel format, depth size) with:
 *   RS_FN(name)   name suffixing, RS_PIX colour type, RS_Z depth type, RS_ZSH depth
 *   shift (32-bit depth keeps d, 16-bit keeps d >> 14), RS_PACK(c) packed colour ->
 *   pixel, RS_PACK24(rgb) 0xRRGGBB -> pixel, RS_TEX 1 for textured frames
 *   (perspective-correct texel times the Gouraud colour), RS_COUNT 1 for the
 *   write-counting test variant (no depth test; each write adds 1 to a 32-bit pixel).
 * No header guard on purpose.  See raster.c for the derivations.  The general path for
 * large triangles is in raster_general.h and the tiny boxes in raster_tiny.h, included
 * here; then the one-triangle entry tri_raster, the strip pairs (tri_quad, pair_tiny,
 * pair_wide, tri_pair, quad_shade) and the strip and list loop, draw. */

/* the general path (tri_general): large triangles */
#include "raster/raster_general.h"

/* the tiny path (tiny_shade, tri_tiny, tri_tiny_own) and the shading macros shared
 * with the strip pairs and the pre-pass's quads */
#include "raster/raster_tiny.h"

/* One triangle (a, b, c as seen; either orientation): its box of candidate centres,
 * then the general or the tiny path.  o is the vertex of the three not in the pair whose
 * coordinate extremes ymn, ymx, xmn, xmx the caller passes (pair_wide: v1 and v2, which
 * both of a strip pair's triangles have, once for both); the box is the same.
 * onscreen: all three vertices are on screen (no outcode bits: HALF <= x <= 16 w -
 * HALF), so the columns px0 >= 0 and px1 <= w - 1 need no clamping. */
RS_INLINE static void RS_FN(tri_box)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                     const rs_cvert *o, int32_t ymn, int32_t ymx, int32_t xmn, int32_t xmx,
                                     const int onscreen)
{
    int32_t xmin, xmax, ymin, ymax, px0, px1, py0, py1;
    int32_t tiny;

    {
        const int32_t ox = o->x, oy = o->y;
        int32_t lo, hi;
        ymin = ymn < oy ? ymn : oy;
        ymax = ymx > oy ? ymx : oy;
        lo = (ymin + HALF - 1) >> SUB;    /* first row whose centre is >= ymin */
        hi = (ymax - HALF) >> SUB;        /* last row whose centre is <= ymax */
        py0 = lo < bd->y0 ? bd->y0 : lo;
        py1 = hi >= bd->y1 ? bd->y1 - 1 : hi;
        if (py0 > py1) return;
        xmin = xmn < ox ? xmn : ox;
        xmax = xmx > ox ? xmx : ox;
        px0 = (xmin + HALF - 1) >> SUB;
        px1 = (xmax - HALF) >> SUB;
        /* the path choice depends on the triangle only (not on the band or screen clip) */
        tiny = px1 - px0 < TINY_W && hi - lo < TINY_H;
        if (!onscreen) {
            if (px0 < 0) px0 = 0;
            if (px1 >= bd->w) px1 = bd->w - 1;
        }
        if (px0 > px1) return;
    }
    if (RS_UNLIKELY(!tiny)) {
        /* small: the reciprocal's bounds (raster_general.h); wide: the span by division */
        RS_FN(tri_general)(bd, a, b, c, px0, px1, py0, py1, xmax - xmin < SMALL && ymax - ymin < SMALL,
                           px1 - px0 >= NARROW);
        return;
    }
    RS_FN(tri_tiny_own)(bd, a, b, c, px0, px1 - px0 + 1, py0, py1 - py0 + 1);
}

/* One triangle (a, b, c as seen; either orientation): the out-of-line code for lists,
 * the clipper and strip triangles that are not drawn as a pair. */
RS_NOINLINE static void RS_FN(tri_raster)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c)
{
    const int32_t ax = a->x, ay = a->y, bx = b->x, by = b->y;
    RS_FN(tri_box)(bd, a, b, c, c, ay < by ? ay : by, ay > by ? ay : by, ax < bx ? ax : bx, ax > bx ? ax : bx, 0);
}

/* The coverage of a strip quad's two triangles over one group of columns (see
 * tri_quad): P01, P20, P13 the packed biased values of row 0 of three outer edges, K1,
 * K2 the packed S + lane offsets from which the diagonal and the fourth edge follow,
 * s01, s20, s13 the row steps; rows 0 .. ny-1 at bit 15 - j. */
RS_INLINE static void RS_FN(quad_masks)(uint64_t P01, uint64_t P20, uint64_t P13, uint64_t K1, uint64_t K2,
                                        uint64_t s01, uint64_t s20, uint64_t s13, uint64_t xm, int32_t ny,
                                        uint64_t *m1, uint64_t *m2)
{
    uint64_t PD = K1 - P01 - P20, P32 = K2 + PD - P13;
    uint64_t M1 = P01 & P20 & PD & xm, M2 = P13 & P32 & ~PD & xm;
    /* rows 1 .. ny-1 (ny <= TINY_H = 4), unrolled */
#define QROW(J) do {                                                                   \
        P01 += s01; P20 += s20; P13 += s13;                                            \
        PD = K1 - P01 - P20;                                                           \
        P32 = K2 + PD - P13;                                                           \
        M1 |= (P01 & P20 & PD & xm) >> (J);                                            \
        M2 |= (P13 & P32 & ~PD & xm) >> (J);                                           \
    } while (0)
    if (ny > 1) {
        QROW(1);
        if (ny > 2) {
            QROW(2);
            if (ny > 3) QROW(3);
        }
    }
#undef QROW
    *m1 = M1; *m2 = M2;
}

/* The coverage and shading of a strip quad from its edge set-up (tri_quad's second half,
 * for the per-pair code; the pre-pass's quads get their coverage from raster.c's
 * pp_prepass and shade in quad_shade): a1, a2 the two triangles' doubled areas (> 0), f01, f20, f13 the
 * biased values of three outer edges at the first candidate (px0, py0), A, B their steps
 * per sub-pixel across and down, S1, S2 the areas minus the biases; wide: the box may have
 * a second group of columns (nx up to TINY_W). */
RS_INLINE static void RS_FN(quad_edges)(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                        const rs_cvert *v3, int32_t px0, int32_t nx, int32_t py0, int32_t ny,
                                        uint64_t xm, int32_t a1, int32_t a2, int32_t f01, int32_t f20, int32_t f13,
                                        int32_t A01, int32_t A20, int32_t A13, int32_t B01, int32_t B20, int32_t B13,
                                        int32_t S1, int32_t S2, const int wide)
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
    RS_FN(quad_masks)(P01, P20, P13, K1, K2, s01, s20, s13, xm, ny, &M1, &M2);
    if (wide && nx > 4) {
        /* the second group: four pixels (64 A sub-pixels) to the right */
        P01w = P01 + (uint64_t)(int64_t)(A01 * 64) * ones;
        P20w = P20 + (uint64_t)(int64_t)(A20 * 64) * ones;
        P13w = P13 + (uint64_t)(int64_t)(A13 * 64) * ones;
        RS_FN(quad_masks)(P01w, P20w, P13w, K1, K2, s01, s20, s13, TINY_XM2(nx), ny,
                          &M1w, &M2w);
    }
    /* T1: base v0, weight of v1 from the edge v2-v0 (P20), of v2 from v0-v1 (P01);
     * T2: base v2, weight of v1 from the edge v3-v2 (P32), of v3 from the diagonal (~PD) */
    if (M1 | M1w | M2 | M2w) {
        /* the addresses once for both triangles */
        TINY_ROWS(bd, py0, px0, crow, zrow);
        if (M1 | M1w)
            RS_FN(tiny_shade)(bd, v0, v1, v2, a1, M1, P01, s01, P20, s20, crow, zrow, M1w, P01w, P20w);
        if (M2 | M2w) {
            const uint64_t PD = K1 - P01 - P20, PDw = K1 - P01w - P20w;
            RS_FN(tiny_shade)(bd, v2, v1, v3, a2, M2, ~PD, s01 + s20, K2 + PD - P13,
                              (uint64_t)0 - s01 - s20 - s13, crow, zrow, M2w, ~PDw, K2 + PDw - P13w);
        }
    }
}

/* A strip pair T1 = (v0, v1, v2), T2 = (v2, v1, v3) whose two triangles have the same
 * orientation (neg = 1: both front faces, area < 0 as computed) and a tiny joint box
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
RS_INLINE static void RS_FN(tri_quad)(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                      const rs_cvert *v3, int32_t px0, int32_t nx, int32_t py0, int32_t ny,
                                      uint64_t xm, int32_t ar1, int32_t ar2, const int neg, const int wide)
{
    const int32_t ox0 = px0 * SUBONE + HALF, oy0 = py0 * SUBONE + HALF;   /* the first candidate */
    const int32_t X0 = v0->x - ox0, Y0 = v0->y - oy0, X1 = v1->x - ox0, Y1 = v1->y - oy0;
    const int32_t X2 = v2->x - ox0, Y2 = v2->y - oy0, X3 = v3->x - ox0, Y3 = v3->y - oy0;
    const int32_t e01 = X0 * Y1 - Y0 * X1, e12 = X1 * Y2 - Y1 * X2, e20 = X2 * Y0 - Y2 * X0;
    const int32_t e13 = X1 * Y3 - Y1 * X3, e32 = X3 * Y2 - Y3 * X2;
#define SG(x) (neg ? -(x) : (x))
#define QBIAS(A, B) ((int32_t)((uint32_t)((A) * 65536 + (B) - 1) >> 31))
    bd->tris += 2;
    if (nx == 1 && ny == 1) {
        /* one candidate, at the origin: its edge values are the e_PQ themselves; an edge
         * value < 0 rejects whatever the bias, so biases only for a triangle that may hold it */
        const int32_t g01 = SG(e01), g12 = SG(e12), g20 = SG(e20);
        if ((g01 | g12 | g20) >= 0) {
            const int32_t f01 = g01 - QBIAS(SG(v0->y - v1->y), SG(v1->x - v0->x)), f20 = g20 - QBIAS(SG(v2->y - v0->y), SG(v0->x - v2->x));
            const int32_t fD = g12 - QBIAS(SG(v1->y - v2->y), SG(v2->x - v1->x));
            if ((f01 | f20 | fD) >= 0) {
                RS_FN(tiny_pixel)(bd, v0, v1, v2, SG(ar1), f01, f20, py0, px0);
                return;     /* T2 cannot hold it: T2's diagonal value is -1 - fD */
            }
        }
        {
            const int32_t g13 = SG(e13), g32 = SG(e32);
            if ((g13 | g32 | -g12) >= 0) {
                const int32_t f13 = g13 - QBIAS(SG(v1->y - v3->y), SG(v3->x - v1->x)), f32 = g32 - QBIAS(SG(v3->y - v2->y), SG(v2->x - v3->x));
                const int32_t fT = -g12 - 1 + QBIAS(SG(v1->y - v2->y), SG(v2->x - v1->x));
                if ((f13 | f32 | fT) >= 0)
                    RS_FN(tiny_pixel)(bd, v2, v1, v3, SG(ar2), fT, f32, py0, px0);
            }
            return;
        }
    }
    {
        const int32_t A01 = SG(v0->y - v1->y), B01 = SG(v1->x - v0->x), A12 = SG(v1->y - v2->y), B12 = SG(v2->x - v1->x);
        const int32_t A20 = SG(v2->y - v0->y), B20 = SG(v0->x - v2->x), A13 = SG(v1->y - v3->y), B13 = SG(v3->x - v1->x);
        const int32_t A32 = SG(v3->y - v2->y), B32 = SG(v2->x - v3->x);
        const int32_t b01 = QBIAS(A01, B01), b12 = QBIAS(A12, B12), b20 = QBIAS(A20, B20);
        const int32_t b13 = QBIAS(A13, B13), b32 = QBIAS(A32, B32);
        /* S = area2 - the three biases; T2's diagonal bias is 1 - b12 */
        const int32_t S1 = SG(ar1) - b01 - b12 - b20, S2 = SG(ar2) - 1 + b12 - b13 - b32;
        const int32_t f01 = SG(e01) - b01, f20 = SG(e20) - b20, f13 = SG(e13) - b13;
        RS_FN(quad_edges)(bd, v0, v1, v2, v3, px0, nx, py0, ny, xm, SG(ar1), SG(ar2), f01, f20, f13,
                          A01, A20, A13, B01, B20, B13, S1, S2, wide);
    }
#undef SG
#undef QBIAS
}

/* The doubled signed areas of a strip pair's T1 = (v0, v1, v2) and T2 (from its vertex
 * v2, as tri_tiny); < 0 for front faces. */
#define PAIR_AREAS(AR1, AR2) \
    const int32_t AR1 = (v1->x - v0->x) * (v2->y - v0->y) - (v2->x - v0->x) * (v1->y - v0->y); \
    const int32_t AR2 = (v1->x - v2->x) * (v3->y - v2->y) - (v3->x - v2->x) * (v1->y - v2->y)

/* A strip pair (see tri_pair) over its tiny joint box px0, py0, nx x ny with nx <= 4 (one
 * group of columns: the inlined common case): orientations (cull, zero area), then
 * tri_quad, or tri_tiny one triangle at a time. */
RS_INLINE static void RS_FN(pair_tiny)(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                       const rs_cvert *v3, int32_t px0, int32_t nx, int32_t py0, int32_t ny)
{
    const uint64_t xm = TINY_XM4(nx);
    PAIR_AREAS(ar1, ar2);
    if (bd->cull && (ar1 | ar2) >= 0) return;    /* both culled or of zero area */
    if (ar1 < 0 && ar2 < 0)
        RS_FN(tri_quad)(bd, v0, v1, v2, v3, px0, nx, py0, ny, xm, ar1, ar2, 1, 0);
    else if (ar1 > 0 && ar2 > 0 && !bd->cull)
        RS_FN(tri_quad)(bd, v0, v1, v2, v3, px0, nx, py0, ny, xm, ar1, ar2, 0, 0);
    else {
        /* mixed orientations or a zero area (rare): one triangle at a time */
        const int32_t ox0 = px0 * SUBONE + HALF, oy0 = py0 * SUBONE + HALF;   /* the first candidate */
        if (bd->cull) {
            /* culled or zero area: area >= 0 draws nothing */
            if (ar1 < 0) RS_FN(tri_tiny_any)(bd, v0, v1, v2, px0, nx, py0, ny, xm, ox0, oy0);
            else if (ar2 < 0) RS_FN(tri_tiny_any)(bd, v2, v1, v3, px0, nx, py0, ny, xm, ox0, oy0);
        } else {
            RS_FN(tri_tiny_any)(bd, v0, v1, v2, px0, nx, py0, ny, xm, ox0, oy0);
            RS_FN(tri_tiny_any)(bd, v2, v1, v3, px0, nx, py0, ny, xm, ox0, oy0);
        }
    }
}

/* The strip pairs that tri_pair's inlined code leaves: joint boxes of more than four
 * columns (tiny up to TINY_W: both groups of columns) or more than TINY_H rows or
 * TINY_W columns (each triangle through tri_raster), out of line so that the strip
 * loop's code has one group of columns only.  lo .. hi, xl .. xh: the joint box's rows
 * and columns of centres, unclipped; lo <= hi (tri_pair returns when there is no row). */
RS_NOINLINE static void RS_FN(pair_wide)(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                         const rs_cvert *v3, int32_t lo, int32_t hi, int32_t xl, int32_t xh)
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
        PAIR_AREAS(ar1, ar2);
        if (bd->cull && (ar1 | ar2) >= 0) return;    /* both culled or of zero area */
        if ((ar1 < 0 && ar2 < 0) || (ar1 > 0 && ar2 > 0 && !bd->cull)) {
            RS_FN(tri_quad)(bd, v0, v1, v2, v3, xl, nx, py0, py1 - py0 + 1, TINY_XM(nx), ar1, ar2, ar1 < 0, 1);
            return;
        }
    }
    /* each triangle on its own, as tri_raster draws it (inlined: no calls for the
     * triangles without a row or column of centres, and none to tri_raster); both
     * callers (tri_pair, the pre-pass's PK_WIDE) have all four vertices on screen */
    {
        const int32_t x1 = v1->x, y1 = v1->y, x2 = v2->x, y2 = v2->y;
        const int32_t ymn = y1 < y2 ? y1 : y2, ymx = y1 > y2 ? y1 : y2, xmn = x1 < x2 ? x1 : x2, xmx = x1 > x2 ? x1 : x2;
        RS_FN(tri_box)(bd, v0, v1, v2, v0, ymn, ymx, xmn, xmx, 1);
        RS_FN(tri_box)(bd, v2, v1, v3, v3, ymn, ymx, xmn, xmx, 1);
    }
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
RS_HOT static void RS_FN(tri_pair)(band *bd, const rs_cvert *v0, const rs_cvert *v1, const rs_cvert *v2,
                                      const rs_cvert *v3)
{
    int32_t lo, hi, xl, xh, py0, py1, px0, px1;
    {
        int32_t t, u, ymin, ymax, xmin, xmax;
        t = v0->y < v1->y ? v0->y : v1->y; u = v2->y < v3->y ? v2->y : v3->y; ymin = t < u ? t : u;
        t = v0->y > v1->y ? v0->y : v1->y; u = v2->y > v3->y ? v2->y : v3->y; ymax = t > u ? t : u;
        lo = (ymin + HALF - 1) >> SUB; hi = (ymax - HALF) >> SUB;
        /* no row of centres (a quarter of camera B's pairs: slivers near the horizon):
         * done before the columns are looked at; 1-2 % faster on both peer cameras */
        if (hi < lo) return;
        t = v0->x < v1->x ? v0->x : v1->x; u = v2->x < v3->x ? v2->x : v3->x; xmin = t < u ? t : u;
        t = v0->x > v1->x ? v0->x : v1->x; u = v2->x > v3->x ? v2->x : v3->x; xmax = t > u ? t : u;
        xl = (xmin + HALF - 1) >> SUB; xh = (xmax - HALF) >> SUB;
    }
    if (RS_UNLIKELY(hi - lo >= TINY_H || xh - xl >= 4)) {
        RS_FN(pair_wide)(bd, v0, v1, v2, v3, lo, hi, xl, xh);
        return;
    }
    py0 = lo < bd->y0 ? bd->y0 : lo;
    py1 = hi >= bd->y1 ? bd->y1 - 1 : hi;
    /* all four vertices on screen (no outcode bits): HALF <= x <= 16 w - HALF, so
     * 0 <= xl and xh <= w - 1 without clamping */
    px0 = xl;
    px1 = xh;
    if (py0 > py1 || px0 > px1) return;
    RS_FN(pair_tiny)(bd, v0, v1, v2, v3, px0, px1 - px0 + 1, py0, py1 - py0 + 1);
}

#if RS_PREPASS
/* One triangle a, b, c (area2 > 0) of a pre-pass quad (PK_QUAD): m its covered
 * candidates (bit 8 j + i, see pp_soa), E its edge values (E[4 PP_STEPS k] opposite b, E[4 PP_STEPS k + PP_STEPS]
 * opposite c for candidate k), crow / zrow the colour and depth of candidate 0,
 * coff / zoff the candidates' offsets from them (bytes / depth entries); tight (a
 * constant): colour and depth entries of one size and rows w entries apart, where
 * coff[k] is also candidate k's depth offset in bytes (one table load per pixel). */
RS_HOT static void RS_FN(quad_shade)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                        int32_t area2, uint32_t m, const int16_t *E, RS_PIX *crow, RS_Z *zrow,
                                        const size_t *coff, const size_t *zoff, const int tight)
{
    TINY_SETUP;
    do {
        const size_t k = ctz64(m);
        m &= m - 1;
        if (tight) {
            const size_t o = coff[k];
            TINY_SHADE(E[4 * PP_STEPS * k], E[4 * PP_STEPS * k + PP_STEPS], (RS_Z *)(void *)((uint8_t *)zrow + o),
                       (RS_PIX *)(void *)((uint8_t *)crow + o));
        } else {
            TINY_SHADE(E[4 * PP_STEPS * k], E[4 * PP_STEPS * k + PP_STEPS], zrow + zoff[k], (RS_PIX *)(void *)((uint8_t *)crow + coff[k]));
        }
    } while (m);
}

#endif
#undef TINY_XM2
#undef PAIR_AREAS
#undef RS_HOT

/* Strip triangles not drawn as a pair go through the out-of-line triangle code. */
#define RS_STRIP_TRI RS_FN(tri_raster)

/* One strip triangle (draw's strip loop and pp_steps): triangle = (P, Q, V), V the
 * new vertex; outcodes read where tested (fewer live registers); the clipper gets the
 * same order (indices IP, IQ, IV) */
#define STRIP_TRI(P, Q, V, IP, IQ, IV) do {                                            \
    if (!((P)->c & (Q)->c & (V)->c & REJECT)) {                        \
        if (RS_UNLIKELY(((P)->c | (Q)->c | (V)->c) & SLOW))            \
            tri_clip(bd, RS_FN(tri_raster), (IP), (IQ), (IV));         \
        else RS_STRIP_TRI(bd, (P), (Q), (V));                          \
    }                                                                  \
} while (0)

#if RS_PREPASS
/* The steps of a pre-pass chunk q after pp_prepass (sp: its first step's two new
 * indices): the work list's steps in order, by kind; ctight as in draw, a constant
 * (draw has a copy for each case: no test per step; 640x480 A -0.06, B -0.04 M on
 * x86-64, -0.2 to -0.5 M on ARM). */
RS_INLINE static void RS_FN(pp_steps)(band *bd, const pp_soa *q, const uint32_t *sp, const size_t *coff,
                                      const size_t *zoff, const uintptr_t cdiff, const int ctight)
{
    /* the address of frame row 0's depth, were the band's buffer the whole frame's
     * (an integer, modulo 2^N): row py0's is zb0 plus py0 w entries */
    const uintptr_t zb0 = (uintptr_t)bd->depth - (uintptr_t)bd->y0 * (uintptr_t)bd->w * sizeof(RS_Z);
    for (uint32_t wk = q->work; wk; wk &= wk - 1) {
        /* the steps that are not PK_NONE (pp_prepass's work list), in order */
        const size_t st = ctz32(wk);
        /* the step's fields (Q16, Q32: of int16_t and uint32_t arrays, QV:
         * vertex pointers; PP_IDX in raster.c) */
#if PP_IDX
#define Q16(F) q->F[st]
#define Q32(F) q->F[st]
#define QV(F, D) q->F[st + (D)]
#else
        /* from one base per field size (immediate offsets: ARM has no
         * base + index + offset addressing) */
        const char *const q2 = (const char *)(const void *)q + 2 * st, *const q4 = q2 + 2 * st;
        const char *const qp = (const char *)(const void *)q + sizeof(void *) * st;
#define Q16(F) (*(const int16_t *)(const void *)(q2 + offsetof(pp_soa, F)))
#define Q32(F) (*(const uint32_t *)(const void *)(q4 + offsetof(pp_soa, F)))
#define QV(F, D) (*(const rs_cvert *const *)(const void *)(qp + offsetof(pp_soa, F) + (D) * sizeof(void *)))
#endif
        /* the step's vertices, read where used (none are carried) */
#define v0 QV(ve, 0)
#define v1 QV(vo, 0)
#define v2 QV(ve, 1)
#define v3 QV(vo, 1)
        const int32_t kind = Q16(kind);
        if (RS_LIKELY(kind == PK_QUAD)) {
            const uint32_t m1 = Q32(m1), m2 = Q32(m2);    /* coverage */
            bd->tris += (uint32_t)Q16(nt);
            if (m1 | m2) {
                const int16_t *E = &Q16(e[0][0]);
                if (ctight) {
                    const uintptr_t za = zb0 + ((size_t)Q16(py0) * (size_t)bd->w + (size_t)Q16(px0)) * sizeof(RS_Z);
                    RS_Z *const zrow = (RS_Z *)(void *)za;
                    RS_PIX *const crow = (RS_PIX *)(void *)(za + cdiff);
                    if (m1) RS_FN(quad_shade)(bd, v0, v1, v2, Q16(a1), m1, E, crow, zrow, coff, zoff, 1);
                    if (m2) RS_FN(quad_shade)(bd, v2, v1, v3, Q16(a2), m2, E + 2 * PP_STEPS, crow, zrow, coff, zoff, 1);
                } else {
                    TINY_ROWS(bd, Q16(py0), Q16(px0), crow, zrow);
                    if (m1) RS_FN(quad_shade)(bd, v0, v1, v2, Q16(a1), m1, E, crow, zrow, coff, zoff, 0);
                    if (m2) RS_FN(quad_shade)(bd, v2, v1, v3, Q16(a2), m2, E + 2 * PP_STEPS, crow, zrow, coff, zoff, 0);
                }
            }
        } else if (kind == PK_WIDE) {
            RS_FN(pair_wide)(bd, v0, v1, v2, v3, Q16(py0), Q16(ny), Q16(px0), Q16(nx));
        } else if (kind == PK_SLOW) {
            /* (pairs whose two triangles the outcodes reject are PK_NONE) */
            const uint32_t *const ip = sp + 2 * st;
            STRIP_TRI(v0, v1, v2, ip[-2], ip[-1], ip[0]);
            STRIP_TRI(v2, v1, v3, ip[0], ip[-1], ip[1]);
        }
#undef Q16
#undef Q32
#undef QV
#undef v0
#undef v1
#undef v2
#undef v3
    }
}
#endif

PP_SCHED static void RS_FN(draw)(band *bd)
{
    const rs_frame *f = bd->f;
    const rs_cvert *cache = f->cache;
    const int16_t *ch = f->chunks;     /* per chunk of RS_CHUNK triangles: rows touched */
    int32_t p;
#if RS_PREPASS
    /* the pre-pass quads' candidates 8 j + i: offsets of (i, j) in the colour and depth rows */
    /* ctight: colour and depth entries of the same size, rows w entries apart (XRGB8888
     * with 32-bit depth, RGB565 with 16-bit depth, no padding): a pixel's colour is cdiff
     * bytes after its depth (addresses as integers), and its offsets from the first
     * candidate's colour and depth are the same number of bytes */
    const int ctight = sizeof(RS_PIX) == sizeof(RS_Z) && bd->stride == (size_t)bd->w * sizeof(RS_PIX);
    const uintptr_t cdiff = (uintptr_t)bd->color - (uintptr_t)bd->depth;
    size_t coff[TINY_W * TINY_H], zoff[TINY_W * TINY_H];
    for (p = 0; p < TINY_W * TINY_H; p++) {
        coff[p] = (size_t)(p >> 3) * bd->stride + (size_t)(p & 7) * sizeof(RS_PIX);
        zoff[p] = (size_t)(p >> 3) * (size_t)bd->w + (size_t)(p & 7);
    }
#endif
    for (p = 0; p < f->nprims; p++) {
        const rs_prim *pr = &f->prims[p];
        const uint32_t *s = pr->idx;
        uint32_t k, nt = rs_prim_tris(pr), t0;
        if (nt == 0) continue;
        for (t0 = 0; t0 < nt; t0 += RS_CHUNK, ch = ch ? ch + 2 : ch) {
            uint32_t t1 = nt - t0 < RS_CHUNK ? nt : t0 + RS_CHUNK;
            if (ch && (ch[1] < bd->y0 || ch[0] >= bd->y1)) continue;   /* chunk misses the band */
            if (pr->kind == RS_STRIP) {
                /* sliding window: one new vertex per triangle; triangle t = (s[t], s[t+1],
                 * s[t+2]), the first two swapped for odd t */
                {
                    /* a chunk whose vertices s[t0 .. t1 + 1] all lie beyond one side (or
                     * behind the near plane, or beyond the far one): every triangle of it is
                     * rejected by its outcodes, as each would be below, so nothing is drawn
                     * or counted.  Read outcodes only, two vertices a test, and stop at the
                     * first pair that clears the last common bit (a chunk with a vertex on
                     * screen: its first pair or two; one test a pair: B 640x480 -0.03 M).
                     * With a chunk table, chunk_rows (xform.c) has
                     * already made such chunks miss every band, once per frame, and the
                     * others stop here at once (testing for the table first cost the
                     * whole-frame loop more: A 640x480 +0.04 M). */
                    const uint32_t *ip = s + t0 + 1, *const ie = s + t1 + 2;
                    uint32_t am = cache[s[t0]].c & REJECT;
                    /* (at least three vertices) */
                    for (; am && ip + 1 < ie; ip += 2) am &= cache[ip[0]].c & cache[ip[1]].c;
                    if (am && ip < ie) am &= cache[*ip].c;
                    if (am) continue;
                }
                const rs_cvert *v0 = &cache[s[t0]], *v1 = &cache[s[t0 + 1]];
                /* two triangles per step (even, then odd with its first two swapped):
                 * chunks start at even t0; sp points at the step's two new indices */
                const uint32_t *sp = s + t0 + 2;
                const uint32_t *const se = s + t1 + 1;     /* steps while sp < se */
#if RS_PREPASS
                /* A chunk inside the band (or any chunk of a whole-frame band): its steps
                 * set up by the pre-pass (the vertices gathered first: the low 16 bits of
                 * x and y, the outcode), then masks and shading here.  A chunk that
                 * crosses the band's edges (bands of a few rows) has most of its steps
                 * outside, which the per-pair code below rejects for less. */
                if ((bd->y0 == 0 && bd->y1 == f->h) || (ch && ch[0] >= bd->y0 && ch[1] < bd->y1)) {
                    pp_soa q;
                    const int32_t n = (int32_t)((se - sp + 1) / 2);
                    pp_prepass(bd, &q, cache, s + t0, n);
                    if (ctight) RS_FN(pp_steps)(bd, &q, sp, coff, zoff, cdiff, 1);
                    else RS_FN(pp_steps)(bd, &q, sp, coff, zoff, cdiff, 0);
                    v0 = q.ve[n]; v1 = q.vo[n];
                    sp += 2 * n;
                } else
#endif
                {
                    uint32_t c01 = v0->c | v1->c;      /* carried: the previous step's c23 */
                    for (; sp < se; sp += 2) {
                        const rs_cvert *v2 = &cache[sp[0]], *v3;
                        uint32_t c23;
                        v3 = &cache[sp[1]];
                        c23 = v2->c | v3->c;
                        if (RS_LIKELY(!((c01 | c23) & (SLOW | REJECT)))) {
                            /* all four vertices on screen (the common case): no further outcode
                             * tests, no clamping to the screen's columns */
                            RS_FN(tri_pair)(bd, v0, v1, v2, v3);
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
                        STRIP_TRI(v0, v1, v2, sp[-2], sp[-1], sp[0]);
                        v3 = &cache[sp[1]];
                        STRIP_TRI(v2, v1, v3, sp[0], sp[-1], sp[1]);
                        v0 = v2; v1 = v3;
                    }
                }
                if (sp < s + t1 + 2) {
                    const rs_cvert *v2 = &cache[sp[0]];
                    STRIP_TRI(v0, v1, v2, sp[-2], sp[-1], sp[0]);
                }
#undef STRIP_TRI
            } else {
                for (k = 3 * t0; k < 3 * t1; k += 3) {
                    uint32_t ia = s[k], ib = s[k + 1], ic = s[k + 2];
                    const rs_cvert *va = &cache[ia], *vb = &cache[ib], *vc = &cache[ic];
                    if (va->c & vb->c & vc->c & REJECT) continue;
                    if ((va->c | vb->c | vc->c) & SLOW) { tri_clip(bd, RS_FN(tri_raster), ia, ib, ic); continue; }
                    RS_FN(tri_raster)(bd, va, vb, vc);
                }
            }
        }
    }
}
#undef RS_STRIP_TRI
#undef TINY_XM
#undef TINY_XM4
#undef TINY_LANES
#undef TINY_PIX
#undef TINY_ROWS
#undef TINY_SETUP
#undef TINY_SETUP_PLAIN
#undef TINY_SHADE
#undef TINY_LANES_TO
#undef TINY_ROW_LANES
#undef TINY_E
