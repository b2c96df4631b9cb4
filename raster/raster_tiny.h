/* raster/raster_tiny.h — the tiny path of the per-triangle code: triangles whose
 * bounding box holds at most TINY_W x TINY_H candidate centres, as coverage masks and
 * per-centre shading from exact weights (tiny_mask, tiny_shade, tiny_pixel, tri_tiny,
 * tri_tiny_any), and the per-centre shading the strip pairs and the pre-pass's quads
 * share (tiny_setup, tiny_px).  raster.c's own, included once; every function takes the
 * variant as its constant last argument (raster_pixel.h). */
#ifndef BR_RASTER_TINY_H
#define BR_RASTER_TINY_H

/* ------------------------------------------------------------------ tiny boxes
 * Triangles (and strip pairs) whose bounding box holds at most TINY_W x TINY_H candidate
 * centres: a coverage mask first (SWAR: four candidates of a row per uint64, the edge
 * value e + 2^15 of each in a 16-bit lane, the lane's top bit set iff e >= 0), then, for
 * covered centres only, attributes straight from the exact barycentric weights.  A box
 * of more than four columns is two groups of four (columns px0 .. px0+3 and px0+4 ..
 * px0+7), the second group's lanes being the first's plus 4 pixels of each edge step.
 *
 * Lane bound.  A box of at most 8 x 4 centres around a triangle (or quad) means a
 * vertex extent below 9 px = 144 sub-pixels across and 5 px = 80 down, so an edge has
 * |A| <= 79 and |B| <= 143.  Every lane, masked or not, is a centre X within
 * [xmin - 143, xmax + 48] (a group's last lanes lie at most 3 columns past the box) and
 * Y within the box's rows, so |X - P.x| <= 191, |Y - P.y| <= 79 from any vertex P and
 * |e| <= 79 * 191 + 143 * 79 = 26,386 < 2^15 (plus a bias of 1): each lane value is in
 * [0, 2^16) and the packed sums, computed modulo 2^64, are exact lane by lane.  The
 * area is below 143 * 79 < 2^14, so the weights' products e * inv stay below 2^55. */

/* Top bits of the four 16-bit lanes; TINY_XM: the lanes of a box's first group of
 * columns (min(nx, 4) of them), TINY_XM2: of its second group (nx - 4, for 5 <= nx <= 8);
 * TINY_XM4 where nx <= 4 is known. */
#define TINY_LANES 0x8000800080008000u
#define TINY_XM4(n) (TINY_LANES >> (64 - 16 * (n)))    /* the first n lanes, 1 <= n <= 4 */
#define TINY_XM(nx) TINY_XM4((nx) < 4 ? (nx) : 4)
#define TINY_XM2(nx) TINY_XM4((nx) - 4)

/* The coverage of one triangle over one group of columns: P0 / P2 / k1 - P0 - P2 the
 * packed biased edge values of row 0, s0 / s2 the row steps, rows 0 .. ny-1 (ny <=
 * TINY_H = 4, unrolled: most tiny boxes have one or two rows); row j's lanes at bit
 * 15 - j of each 16-bit lane. */
RSI_INLINE static uint64_t tiny_mask(uint64_t P0, uint64_t P2, uint64_t k1, uint64_t s0, uint64_t s2,
                                    uint64_t xm, int32_t ny)
{
    uint64_t M = P0 & P2 & (k1 - P0 - P2) & xm;
    if (ny > 1) {
        P0 += s0; P2 += s2;
        M |= (P0 & P2 & (k1 - P0 - P2) & xm) >> 1;
        if (ny > 2) {
            P0 += s0; P2 += s2;
            M |= (P0 & P2 & (k1 - P0 - P2) & xm) >> 2;
            if (ny > 3) {
                P0 += s0; P2 += s2;
                M |= (P0 & P2 & (k1 - P0 - P2) & xm) >> 3;
            }
        }
    }
    return M;
}

/* The per-triangle values of the tiny shading (tiny_shade, quad_shade, tiny_pixel): a the
 * base vertex, b and c the others, area2 > 0.  inv = 2^40 / area2 (fx_div40) turns edge
 * values into Q16 weights; depth and colour differences from a; textured: the 1/w
 * weights q = d >> tsh (16 bits for the nearest vertex) and q u, q v per vertex. */
typedef struct tiny_tri {
    int64_t inv, ad;
    dz_t dzb, dzc;
    uint64_t db, dc, ca;
    const rs_texture *tx;
    int64_t qa, qb, qc, ua, ub, uc, va, vb, vc;
} tiny_tri;

RSI_INLINE static void tiny_setup(tiny_tri *t, const band *bd, const rs_cvert *a, const rs_cvert *b,
                                 const rs_cvert *c, int32_t area2, const int vf)
{
    if (vf & VF_COUNT) return;          /* counting reads none of it */
    t->inv = fx_div40((uint32_t)area2);
    t->ad = a->d;
    t->dzb = (dz_t)((int64_t)b->d - t->ad);
    t->dzc = (dz_t)((int64_t)c->d - t->ad);
    t->db = b->cp - a->cp;
    t->dc = c->cp - a->cp;
    t->ca = (a->cp << 13) + RS_CBIAS;
    if (vf & VF_TEX) {
        const int32_t tsh = tex_shift(a->d, b->d, c->d);
        t->tx = bd->f->tex;
        t->qa = a->d >> tsh; t->qb = b->d >> tsh; t->qc = c->d >> tsh;
#if RS_TEX_FIELDS
        t->ua = t->qa * a->u; t->ub = t->qb * b->u; t->uc = t->qc * c->u;
        t->va = t->qa * a->v; t->vb = t->qb * b->v; t->vc = t->qc * c->v;
#endif
    }
}

/* One covered centre: its edge values E2 (opposite b: the weight of b times area2) and
 * E0 (of c), its depth at zp and colour at cp.  Weights w1, w2 in Q16; the pixel is the
 * packed colour, or (textured) the texel at the perspective-correct (u, v) times it. */
RSI_INLINE static void tiny_px(band *bd, const tiny_tri *t, int64_t E2, int64_t E0, void *zp, void *cp,
                              const int vf)
{
    if (vf & VF_COUNT) {
        bd->pixels++;
        *(uint32_t *)cp += 1;
        return;
    }
    const int64_t w1 = (E2 * t->inv) >> 24, w2 = (E0 * t->inv) >> 24;
    const uint32_t zz = z_store((uint32_t)(t->ad + ((DZ_MUL(t->dzb, w1) + DZ_MUL(t->dzc, w2)) >> 16)), vf);
    bd->pixels++;
    if (zz > z_get(zp, vf)) {
        const uint64_t col = t->ca + CW_MUL(t->db, w1) + CW_MUL(t->dc, w2);
        z_put(zp, zz, vf);
        if (vf & VF_TEX) {
            const int64_t wa = 65536 - w1 - w2, q = wa * t->qa + w1 * t->qb + w2 * t->qc;
            px_put(cp, px_pack24(tex_mod(tex_fetch(t->tx, tex_div(wa * t->ua + w1 * t->ub + w2 * t->uc, q),
                                                   tex_div(wa * t->va + w1 * t->vb + w2 * t->vc, q)), col), vf), vf);
        } else {
            px_put(cp, px_pack(col, vf), vf);
        }
    }
}

/* The edge value e of lane I (bits 16 I .. 16 I + 15) of a packed row P of biased
 * values (e + 2^15).  64-bit little-endian targets copy a row's lanes into int16 arrays
 * first (tiny_lanes_to), so that a lane is one indexed load instead of a shift by a
 * variable amount and a zero extension; 32-bit targets, where a 64-bit shift is several
 * instructions and LANE16 picks the word first, extract it (the arrays unused). */
#if RSI_REG64 && !(defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__)
#define TINY_LANE_ARRAYS 1
#else
#define TINY_LANE_ARRAYS 0
#endif
RSI_INLINE static void tiny_lanes_to(int16_t L[4], uint64_t P)
{
    if (TINY_LANE_ARRAYS) {
        const uint64_t x = P ^ TINY_LANES;
        memcpy(L, &x, 8);
    }
}
RSI_INLINE static int32_t tiny_e(const int16_t L[4], uint64_t P, uint32_t i)
{
    return TINY_LANE_ARRAYS ? L[i] : (int32_t)LANE16(P, 16 * i) - 0x8000;
}

/* The covered centres of one tiny triangle a, b, c (a the base vertex; area2 > 0 its
 * doubled area) in one group of columns from crow0 / zrow0 (the colour and depth of
 * the group's first candidate): M its coverage (rows at bit 15 - j), P0 / P2 the packed
 * biased edge values (e + 2^15) of row 0 of the edges opposite c / b (e0 = the weight
 * of c times area2, e2 = that of b), sy0 / sy2 their row steps; Mw, P0w, P2w the same
 * for a second group four columns to the right.  tri_tiny and tri_quad shade here, the
 * pre-pass's quads in quad_shade, with the same per-centre code (tiny_px), so a
 * triangle's pixels do not depend on which of them drew it. */
RSI_INLINE static void tiny_shade_body(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                      int32_t area2, uint64_t M, uint64_t P0, uint64_t sy0,
                                      uint64_t P2, uint64_t sy2, void *const crow0, void *const zrow0,
                                      uint64_t Mw, uint64_t P0w, uint64_t P2w, const int vf)
{
    tiny_tri t;
    tiny_setup(&t, bd, a, b, c, area2, vf);
    const size_t stride = bd->stride, zw = (size_t)bd->w * z_bytes(vf);
    void *crow = crow0, *zrow = zrow0;
    for (;;) {
        uint64_t m = M & TINY_LANES;
        M ^= m;
        if (m) {
            int16_t l0[4], l2[4];
            tiny_lanes_to(l0, P0);
            tiny_lanes_to(l2, P2);
            do {
                const uint32_t i = ctz64(m) >> 4;     /* the lowest top bit: 15 + 16 i */
                m &= m - 1;
                tiny_px(bd, &t, tiny_e(l2, P2, i), tiny_e(l0, P0, i), z_at(zrow, i, vf), px_at(crow, i, vf), vf);
            } while (m);
        }
        if (M) {
            M <<= 1;
            P0 += sy0; P2 += sy2;
            crow = (uint8_t *)crow + stride; zrow = (uint8_t *)zrow + zw;
            continue;
        }
        if (!Mw) return;
        /* the second group of columns: same rows, four pixels to the right */
        M = Mw; Mw = 0; P0 = P0w; P2 = P2w;
        crow = px_at(crow0, 4, vf); zrow = z_at(zrow0, 4, vf);
    }
}

/* tiny_shade for the textured and counting variants: out of line, one case a variant. */
RSI_NOINLINE static void tiny_shade_slow(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                        int32_t area2, uint64_t M, uint64_t P0, uint64_t sy0,
                                        uint64_t P2, uint64_t sy2, void *const crow0, void *const zrow0,
                                        uint64_t Mw, uint64_t P0w, uint64_t P2w, int vf)
{
#define TINY_SHADE_CASE(V) case V: if (RS_BUILT(V)) tiny_shade_body(bd, a, b, c, area2, M, P0, sy0, P2, sy2, crow0, zrow0, Mw, P0w, P2w, V); return
    switch (vf) {
    TINY_SHADE_CASE(V_888_Z32_TEX);
    TINY_SHADE_CASE(V_888_Z16_TEX);
    TINY_SHADE_CASE(V_565_Z16_TEX);
    TINY_SHADE_CASE(V_565_Z32_TEX);
    TINY_SHADE_CASE(V_COUNT);
    default: return;
    }
#undef TINY_SHADE_CASE
}

RSI_INLINE static void tiny_shade(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                 int32_t area2, uint64_t M, uint64_t P0, uint64_t sy0,
                                 uint64_t P2, uint64_t sy2, void *const crow0, void *const zrow0,
                                 uint64_t Mw, uint64_t P0w, uint64_t P2w, const int vf)
{
    if (VF_SLOW(vf)) tiny_shade_slow(bd, a, b, c, area2, M, P0, sy0, P2, sy2, crow0, zrow0, Mw, P0w, P2w, vf);
    else tiny_shade_body(bd, a, b, c, area2, M, P0, sy0, P2, sy2, crow0, zrow0, Mw, P0w, P2w, vf);
}

/* The one covered centre (px0, py0) of a tiny triangle whose box has one candidate:
 * E0 / E2 its biased edge values opposite c / b; the values of tiny_shade. */
RSI_INLINE static void tiny_pixel(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                 int32_t area2, int64_t E0, int64_t E2, int32_t py0, int32_t px0, const int vf)
{
    void *const crow = band_crow(bd, py0, px0, vf), *const zrow = band_zrow(bd, py0, px0, vf);
    if (VF_SLOW(vf)) {
        tiny_shade_slow(bd, a, b, c, area2, 0x8000u, (uint64_t)(E0 + 0x8000), 0, (uint64_t)(E2 + 0x8000), 0,
                        crow, zrow, 0, 0, 0, vf);
    } else {
        tiny_tri t;
        tiny_setup(&t, bd, a, b, c, area2, vf);
        tiny_px(bd, &t, E2, E0, zrow, crow, vf);
    }
}

/* The tiny path for a triangle a, b, c with area2 > 0 (b, c already swapped for front
 * faces), b - a = (dx1, dy1), c - a = (dx2, dy2), over candidate centres px0 .. px0 +
 * nx - 1 x py0 .. py0 + ny - 1 (clipped to the band and the screen; nx <= TINY_W, ny <=
 * TINY_H), xm the lane mask of the first group's min(nx, 4) columns, (ox0, oy0) the
 * centre of candidate (px0, py0) in sub-pixels. */
RSI_INLINE static void tri_tiny(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                               int32_t px0, int32_t nx, int32_t py0, int32_t ny, uint64_t xm,
                               int32_t ox0, int32_t oy0,
                               int32_t dx1, int32_t dy1, int32_t dx2, int32_t dy2, int32_t area2, const int vf)
{
    /* every set-up value fits 32 bits (extent < 144 sub-pixels) */
    int32_t A0, A1, A2, B0, B1, B2, S, e0r, e2r, bias0, bias1, bias2;
    bd->tris++;
    /* Edge functions (Pineda 1988): edge P->Q, E = A (X - P.x) + B (Y - P.y) >= 0 inside,
     * at pixel centres.  Edge 0 = a->b (the weight of c), 1 = b->c (weight of a), 2 = c->a
     * (weight of b); since E0 + E1 + E2 = area2 everywhere, E1 is never evaluated.  The
     * top-left rule biases edges that are not top-left by -1 (tl_bias): e_k = E_k -
     * bias_k, inside iff all e_k >= 0, and e1 = S - e0 - e2. */
    A0 = -dy1; B0 = dx1;
    A2 = dy2; B2 = -dx2;
    A1 = -(A0 + A2); B1 = -(B0 + B2);
    bias0 = tl_bias16(A0, B0);
    bias1 = tl_bias16(A1, B1);
    bias2 = tl_bias16(A2, B2);
    S = area2 - bias0 - bias1 - bias2;
    {
        int32_t ox = ox0 - a->x, oy = oy0 - a->y;
        e0r = A0 * ox + B0 * oy - bias0;
        e2r = A2 * ox + B2 * oy - bias2;
    }
    if (nx == 1 && ny == 1) {
        /* one candidate (the commonest box on small screens) */
        if ((e0r | e2r | (S - e0r - e2r)) >= 0) tiny_pixel(bd, a, b, c, area2, e0r, e2r, py0, px0, vf);
        return;
    }
    {
        const uint64_t ones = bd->ones, o16 = bd->ones16;
        const uint64_t k1 = (uint64_t)(int64_t)(S + 3 * 0x8000) * ones;
        /* per-pixel steps: sx = 16 A, sy = 16 B (the 16 is in ones16, steps16) */
        uint64_t p0 = (uint64_t)(int64_t)(e0r + 0x8000) * ones + (uint64_t)(int64_t)A0 * bd->steps16;
        uint64_t p2 = (uint64_t)(int64_t)(e2r + 0x8000) * ones + (uint64_t)(int64_t)A2 * bd->steps16;
        const uint64_t sy0 = (uint64_t)(int64_t)B0 * o16, sy2 = (uint64_t)(int64_t)B2 * o16;
        const uint64_t M = tiny_mask(p0, p2, k1, sy0, sy2, xm, ny);
        uint64_t Mw = 0, p0w = 0, p2w = 0;
        if (nx > 4) {
            /* the second group: four pixels (64 A sub-pixels) to the right */
            p0w = p0 + (uint64_t)(int64_t)(A0 * 64) * ones;
            p2w = p2 + (uint64_t)(int64_t)(A2 * 64) * ones;
            Mw = tiny_mask(p0w, p2w, k1, sy0, sy2, TINY_XM2(nx), ny);
        }
        if (M | Mw)
            tiny_shade(bd, a, b, c, area2, M, p0, sy0, p2, sy2, band_crow(bd, py0, px0, vf),
                       band_zrow(bd, py0, px0, vf), Mw, p0w, p2w, vf);
    }
}

/* A tiny triangle (a, b, c as seen; either orientation) over a candidate box given
 * by its caller (pair_tiny: the pair's joint box; tri_raster has tri_tiny_own): orientation
 * (cull, zero area; front faces with b and c swapped, one inlined copy per
 * orientation, no moves), then tri_tiny. */
RSI_INLINE static void tri_tiny_any(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                   int32_t px0, int32_t nx, int32_t py0, int32_t ny, uint64_t xm,
                                   int32_t ox0, int32_t oy0, const int vf)
{
    const int32_t dx1 = b->x - a->x, dy1 = b->y - a->y, dx2 = c->x - a->x, dy2 = c->y - a->y;
    const int32_t area2 = dx1 * dy2 - dx2 * dy1;
    if (!is_front(area2)) {
        if (area2 == 0 || bd->cull) return;
        tri_tiny(bd, a, b, c, px0, nx, py0, ny, xm, ox0, oy0, dx1, dy1, dx2, dy2, area2, vf);
    } else {
        tri_tiny(bd, a, c, b, px0, nx, py0, ny, xm, ox0, oy0, dx2, dy2, dx1, dy1, -area2, vf);
    }
}

/* tri_raster's tiny triangles (a, b, c as seen; either orientation) over their own box,
 * candidates px0 .. px0 + nx - 1 x py0 .. py0 + ny - 1 (clipped to the band and the
 * screen): tri_tiny_any out of line, so that tri_raster's box and path choice, which
 * every call runs, keep few registers (inlined, its prologue saved six registers and
 * spilled a dozen values for every call). */
RSI_NOINLINE static void tri_tiny_own(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                     int32_t px0, int32_t nx, int32_t py0, int32_t ny, int vf)
{
#define TINY_OWN_CASE(V) case V: if (RS_BUILT(V)) tri_tiny_any(bd, a, b, c, px0, nx, py0, ny, TINY_XM(nx), \
                                                                px0 * RSI_SUBONE + RSI_HALF, py0 * RSI_SUBONE + RSI_HALF, V); return
    switch (vf) {
    TINY_OWN_CASE(V_888_Z32);
    TINY_OWN_CASE(V_888_Z16);
    TINY_OWN_CASE(V_565_Z16);
    TINY_OWN_CASE(V_565_Z32);
    TINY_OWN_CASE(V_888_NOZ);
    TINY_OWN_CASE(V_565_NOZ);
    TINY_OWN_CASE(V_888_Z32_TEX);
    TINY_OWN_CASE(V_888_Z16_TEX);
    TINY_OWN_CASE(V_565_Z16_TEX);
    TINY_OWN_CASE(V_565_Z32_TEX);
    TINY_OWN_CASE(V_COUNT);
    default: return;
    }
#undef TINY_OWN_CASE
}

#endif
