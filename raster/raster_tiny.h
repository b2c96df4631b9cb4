/* raster/raster_tiny.h — the tiny path of the per-triangle code: triangles whose
 * bounding box holds at most TINY_W x TINY_H candidate centres, as coverage masks and
 * per-centre shading from exact weights (tiny_mask, tiny_shade, tiny_pixel, tri_tiny,
 * tri_tiny_any, tri_tiny_own), and the shading macros the strip pairs and the pre-pass's
 * quads share (TINY_SETUP, TINY_SHADE, TINY_ROWS).  Part of the template: included by
 * raster_tmpl.h, once per variant, with its macros (RS_FN, RS_PIX, RS_Z, RS_ZSH, RS_PACK,
 * RS_PACK24, RS_TEX, RS_COUNT); raster_tmpl.h undefines the TINY_ macros after its strip
 * loop.  No header guard on purpose. */

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

/* The strip pairs and their shading are inlined into the strip loop of the plain
 * variants; the textured and write-counting ones call them (their speed matters less
 * than their code size). */
#if RS_TEX || RS_COUNT
#define RS_HOT RS_NOINLINE
#else
#define RS_HOT RS_INLINE
#endif

/* The coverage of one triangle over one group of columns: P0 / P2 / k1 - P0 - P2 the
 * packed biased edge values of row 0, s0 / s2 the row steps, rows 0 .. ny-1 (ny <=
 * TINY_H = 4, unrolled: most tiny boxes have one or two rows); row j's lanes at bit
 * 15 - j of each 16-bit lane. */
RS_INLINE static uint64_t RS_FN(tiny_mask)(uint64_t P0, uint64_t P2, uint64_t k1, uint64_t s0, uint64_t s2,
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

/* The pixel of a covered centre from its weights W1 (of b), W2 (of c), Q16 */
#if RS_TEX
#define TINY_PIX(COL, W1, W2) RS_PACK24(tex_mod(tex_fetch(tx,                          \
                tex_div(((65536 - (W1) - (W2)) * ua + (W1) * ub + (W2) * uc),           \
                        ((65536 - (W1) - (W2)) * qa + (W1) * qb + (W2) * qc)),          \
                tex_div(((65536 - (W1) - (W2)) * va + (W1) * vb + (W2) * vc),           \
                        ((65536 - (W1) - (W2)) * qa + (W1) * qb + (W2) * qc))), (COL)))
#else
#define TINY_PIX(COL, W1, W2) RS_PACK(COL)
#endif

/* The colour and depth addresses of candidate (px0, py0) (py0 in the band). */
#define TINY_ROWS(BD, PY0, PX0, CROW, ZROW)                                                               \
    RS_PIX *const CROW = (RS_PIX *)(void *)((BD)->color + (size_t)((PY0) - (BD)->y0) * (BD)->stride) + (PX0); \
    RS_Z *const ZROW = (RS_Z *)(BD)->depth + (size_t)((PY0) - (BD)->y0) * (size_t)(BD)->w + (PX0)

/* The per-triangle values of the tiny shading (tiny_shade, quad_shade): a the base
 * vertex, b and c the others, area2 > 0. */
#if RS_TEX
#define TINY_SETUP                                                                     \
    TINY_SETUP_PLAIN;                                                                  \
    /* perspective: 1/w weights d >> tsh (16 bits for the nearest vertex) */          \
    const rs_texture *tx = bd->f->tex;                                                 \
    const int32_t tsh = tex_shift(a->d, b->d, c->d);                                   \
    const int64_t qa = a->d >> tsh, qb = b->d >> tsh, qc = c->d >> tsh;                \
    const int64_t ua = qa * a->u, ub = qb * b->u, uc = qc * c->u;                      \
    const int64_t va = qa * a->v, vb = qb * b->v, vc = qc * c->v
#else
#define TINY_SETUP TINY_SETUP_PLAIN
#endif
#define TINY_SETUP_PLAIN                                                               \
    const int64_t inv = fx_div40((uint32_t)area2), ad = a->d;                          \
    const dz_t dzb = (dz_t)((int64_t)b->d - ad), dzc = (dz_t)((int64_t)c->d - ad);     \
    const uint64_t db = b->cp - a->cp, dc = c->cp - a->cp, ca = (a->cp << 13) + RS_CBIAS

/* One covered centre, its edge values E2 (opposite b: the weight of b times area2) and
 * E0 (of c), depth at *ZP, colour at *CP. */
#if RS_COUNT
#define TINY_SHADE(E2, E0, ZP, CP) do {                                                \
        (void)inv; (void)dzb; (void)dzc; (void)db; (void)dc; (void)ca; (void)(E2); (void)(E0); (void)(ZP); \
        bd->pixels++;                                                                  \
        *(CP) += 1;                                                                    \
    } while (0)
#else
#define TINY_SHADE(E2, E0, ZP, CP) do {                                                \
        const int64_t w1 = ((int64_t)(E2) * inv) >> 24, w2 = ((int64_t)(E0) * inv) >> 24;   /* Q16 */ \
        const RS_Z zz = (RS_Z)((uint32_t)(ad + ((DZ_MUL(dzb, w1) + DZ_MUL(dzc, w2)) >> 16)) >> RS_ZSH); \
        bd->pixels++;                                                                  \
        if (zz > *(ZP)) {                                                              \
            const uint64_t col = ca + CW_MUL(db, w1) + CW_MUL(dc, w2);                 \
            *(ZP) = zz;                                                                \
            *(CP) = TINY_PIX(col, w1, w2);                                             \
        }                                                                              \
    } while (0)
#endif

/* The edge value e of lane I (bits 16 I .. 16 I + 15) of a packed row P of biased
 * values (e + 2^15).  64-bit little-endian targets copy a row's lanes into int16 arrays
 * L first (TINY_ROW_LANES: the lanes of P0, P2 into l0, l2), so that a lane is one
 * indexed load instead of a shift by a variable amount and a zero extension; 32-bit
 * targets, where a 64-bit shift is several instructions and LANE16 picks the word
 * first, extract it. */
#if RS_REG64 && !(defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__)
#define TINY_LANES_TO(L, P) do { const uint64_t x_ = (P) ^ TINY_LANES; memcpy((L), &x_, 8); } while (0)
#define TINY_ROW_LANES int16_t l0[4], l2[4]; TINY_LANES_TO(l0, P0); TINY_LANES_TO(l2, P2)
#define TINY_E(L, P, I) (L)[I]
#else
#define TINY_ROW_LANES
#define TINY_E(L, P, I) ((int32_t)LANE16((P), 16 * (I)) - 0x8000)
#endif

/* The covered centres of one tiny triangle a, b, c (a the base vertex; area2 > 0 its
 * doubled area) in one group of columns from crow0 / zrow0 (the colour and depth of
 * the group's first candidate): M its coverage (rows at bit 15 - j), P0 / P2 the packed
 * biased edge values (e + 2^15) of row 0 of the edges opposite c / b (e0 = the weight
 * of c times area2, e2 = that of b), sy0 / sy2 their row steps; Mw, P0w, P2w the same
 * for a second group four columns to the right.  tri_tiny and tri_quad shade here, the
 * pre-pass's quads in quad_shade, with the same per-centre code (TINY_SHADE), so a
 * triangle's pixels do not depend on which of them drew it. */
RS_HOT static void RS_FN(tiny_shade)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                        int32_t area2, uint64_t M, uint64_t P0, uint64_t sy0,
                                        uint64_t P2, uint64_t sy2, RS_PIX *const crow0, RS_Z *const zrow0,
                                        uint64_t Mw, uint64_t P0w, uint64_t P2w)
{
    TINY_SETUP;
    const size_t stride = bd->stride, zw = (size_t)bd->w;
    RS_PIX *crow = crow0;
    RS_Z *zrow = zrow0;
    for (;;) {
        uint64_t m = M & TINY_LANES;
        M ^= m;
        if (m) {
            TINY_ROW_LANES;
            do {
                const uint32_t i = ctz64(m) >> 4;     /* the lowest top bit: 15 + 16 i */
                m &= m - 1;
                TINY_SHADE(TINY_E(l2, P2, i), TINY_E(l0, P0, i), &zrow[i], &crow[i]);
            } while (m);
        }
        if (M) {
            M <<= 1;
            P0 += sy0; P2 += sy2;
            crow = (RS_PIX *)(void *)((uint8_t *)crow + stride); zrow += zw;
            continue;
        }
        if (!Mw) return;
        /* the second group of columns: same rows, four pixels to the right */
        M = Mw; Mw = 0; P0 = P0w; P2 = P2w;
        crow = crow0 + 4; zrow = zrow0 + 4;
    }
}

/* The one covered centre (px0, py0) of a tiny triangle whose box has one candidate:
 * E0 / E2 its biased edge values opposite c / b; the values of tiny_shade. */
RS_INLINE static void RS_FN(tiny_pixel)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                        int32_t area2, int64_t E0, int64_t E2, int32_t py0, int32_t px0)
{
#if RS_TEX || RS_COUNT
    TINY_ROWS(bd, py0, px0, crow, zrow);
    RS_FN(tiny_shade)(bd, a, b, c, area2, 0x8000u, (uint64_t)(E0 + 0x8000), 0, (uint64_t)(E2 + 0x8000), 0, crow, zrow, 0, 0, 0);
#else
    TINY_SETUP;
    TINY_ROWS(bd, py0, px0, crow, zrow);
    TINY_SHADE(E2, E0, zrow, crow);
#endif
}

/* The tiny path for a triangle a, b, c with area2 > 0 (b, c already swapped for front
 * faces), b - a = (dx1, dy1), c - a = (dx2, dy2), over candidate centres px0 .. px0 +
 * nx - 1 x py0 .. py0 + ny - 1 (clipped to the band and the screen; nx <= TINY_W, ny <=
 * TINY_H), xm the lane mask of the first group's min(nx, 4) columns, (ox0, oy0) the
 * centre of candidate (px0, py0) in sub-pixels. */
RS_INLINE static void RS_FN(tri_tiny)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                      int32_t px0, int32_t nx, int32_t py0, int32_t ny, uint64_t xm,
                                      int32_t ox0, int32_t oy0,
                                      int32_t dx1, int32_t dy1, int32_t dx2, int32_t dy2, int32_t area2)
{
    /* every set-up value fits 32 bits (extent < 144 sub-pixels) */
    int32_t A0, A1, A2, B0, B1, B2, S, e0r, e2r, bias0, bias1, bias2;
    bd->tris++;
    /* Edge P->Q: E = A (X - P.x) + B (Y - P.y) >= 0 inside, at pixel centres.  Edge 0 =
     * a->b (the weight of c), 1 = b->c (weight of a), 2 = c->a (weight of b); since
     * E0 + E1 + E2 = area2 everywhere, E1 is never evaluated.  Edges that are not
     * top-left (A > 0, or A == 0 and B > 0) are biased by -1 so that E == 0 there is
     * outside: e_k = E_k - bias_k, inside iff all e_k >= 0, and e1 = S - e0 - e2. */
    A0 = -dy1; B0 = dx1;
    A2 = dy2; B2 = -dx2;
    A1 = -(A0 + A2); B1 = -(B0 + B2);
    /* bias = (2 A + (B > 0)) <= 0, i.e. A < 0 or (A == 0 and B <= 0), i.e. (here
     * |A|, |B| < 2^15) A 2^16 + B <= 0: the sign bit of A 2^16 + B - 1 */
    bias0 = (int32_t)((uint32_t)(A0 * 65536 + B0 - 1) >> 31);
    bias1 = (int32_t)((uint32_t)(A1 * 65536 + B1 - 1) >> 31);
    bias2 = (int32_t)((uint32_t)(A2 * 65536 + B2 - 1) >> 31);
    S = area2 - bias0 - bias1 - bias2;
    {
        int32_t ox = ox0 - a->x, oy = oy0 - a->y;
        e0r = A0 * ox + B0 * oy - bias0;
        e2r = A2 * ox + B2 * oy - bias2;
    }
    if (nx == 1 && ny == 1) {
        /* one candidate (the commonest box on small screens) */
        if ((e0r | e2r | (S - e0r - e2r)) >= 0) RS_FN(tiny_pixel)(bd, a, b, c, area2, e0r, e2r, py0, px0);
        return;
    }
    {
        const uint64_t ones = bd->ones, o16 = bd->ones16;
        const uint64_t k1 = (uint64_t)(int64_t)(S + 3 * 0x8000) * ones;
        /* per-pixel steps: sx = 16 A, sy = 16 B (the 16 is in ones16, steps16) */
        uint64_t p0 = (uint64_t)(int64_t)(e0r + 0x8000) * ones + (uint64_t)(int64_t)A0 * bd->steps16;
        uint64_t p2 = (uint64_t)(int64_t)(e2r + 0x8000) * ones + (uint64_t)(int64_t)A2 * bd->steps16;
        const uint64_t sy0 = (uint64_t)(int64_t)B0 * o16, sy2 = (uint64_t)(int64_t)B2 * o16;
        const uint64_t M = RS_FN(tiny_mask)(p0, p2, k1, sy0, sy2, xm, ny);
        uint64_t Mw = 0, p0w = 0, p2w = 0;
        if (nx > 4) {
            /* the second group: four pixels (64 A sub-pixels) to the right */
            p0w = p0 + (uint64_t)(int64_t)(A0 * 64) * ones;
            p2w = p2 + (uint64_t)(int64_t)(A2 * 64) * ones;
            Mw = RS_FN(tiny_mask)(p0w, p2w, k1, sy0, sy2, TINY_XM2(nx), ny);
        }
        if (M | Mw) {
            TINY_ROWS(bd, py0, px0, crow, zrow);
            RS_FN(tiny_shade)(bd, a, b, c, area2, M, p0, sy0, p2, sy2, crow, zrow, Mw, p0w, p2w);
        }
    }
}

/* A tiny triangle (a, b, c as seen; either orientation) over a candidate box given
 * by its caller (pair_tiny: the pair's joint box; tri_raster has tri_tiny_own): orientation
 * (cull, zero area; front faces with b and c swapped, one inlined copy per
 * orientation, no moves), then tri_tiny. */
RS_INLINE static void RS_FN(tri_tiny_any)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                          int32_t px0, int32_t nx, int32_t py0, int32_t ny, uint64_t xm,
                                          int32_t ox0, int32_t oy0)
{
    const int32_t dx1 = b->x - a->x, dy1 = b->y - a->y, dx2 = c->x - a->x, dy2 = c->y - a->y;
    const int32_t area2 = dx1 * dy2 - dx2 * dy1;
    /* y points down: counter-clockwise as seen (a front face) has area2 < 0 */
    if (area2 >= 0) {
        if (area2 == 0 || bd->cull) return;
        RS_FN(tri_tiny)(bd, a, b, c, px0, nx, py0, ny, xm, ox0, oy0, dx1, dy1, dx2, dy2, area2);
    } else {
        RS_FN(tri_tiny)(bd, a, c, b, px0, nx, py0, ny, xm, ox0, oy0, dx2, dy2, dx1, dy1, -area2);
    }
}

/* tri_raster's tiny triangles (a, b, c as seen; either orientation) over their own box,
 * candidates px0 .. px0 + nx - 1 x py0 .. py0 + ny - 1 (clipped to the band and the
 * screen): tri_tiny_any out of line, so that tri_raster's box and path choice, which
 * every call runs, keep few registers (inlined, its prologue saved six and spilled a
 * dozen values for every call; B 640x480: 23.008 -> 22.962 M instructions per frame).
 * (A copy of tri_tiny_any's orientation code with one tri_tiny for both orientations
 * saved B another 0.03 M; not worth the second copy.) */
RS_NOINLINE static void RS_FN(tri_tiny_own)(band *bd, const rs_cvert *a, const rs_cvert *b, const rs_cvert *c,
                                            int32_t px0, int32_t nx, int32_t py0, int32_t ny)
{
    RS_FN(tri_tiny_any)(bd, a, b, c, px0, nx, py0, ny, TINY_XM(nx), px0 * SUBONE + HALF, py0 * SUBONE + HALF);
}
