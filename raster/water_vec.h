/* raster/water_vec.h — water_row_px's usual case eight pixels at a time, in the x86-64-v3
 * copy of raster/water.c (RW_VEC): XRGB8888 with 32-bit depth, waves, the fixed tint and
 * Schlick's Fresnel term (rw_post's `common` at any reflection resolution: wv_case), the
 * viewer's and the benchmark's water.  raster/water.c's own, included once, after
 * water_one.
 *
 * Same pixels: each lane makes water_one's integers for its pixel with the same
 * operations in 32- and 64-bit lanes (the bounds are stated where a lane is narrower
 * than the scalar code's type), so the bytes are the scalar loop's (tests/test_isa.c
 * draws water frames with both copies and compares them).  A lane takes the water pixels
 * that water_shows accepts without a test of its own: the water nearer than the terrain
 * (dw > dt), not a tested triangle's pixel in a row that may hold them, nor one the land
 * test may make land (within the shore reach with a dry sample nearest its plane point,
 * found in lanes); a lane whose terrain is nearer by more than the row's shore reach
 * (sdd) is dry, as water_shows says.  The tested triangles' pixels whose water is nearer
 * are decided in lanes (wv_plane_cell), the ties and shore tests in lanes where three or
 * more of a group wait (wv_shore), the rest of them and the land test's candidates one by
 * one with water_shows; the water is then drawn in the lanes, the land one by one.
 *
 * Table lookups are AVX2 gathers.  A byte table (fres, fog, wsine) is read as the 32-bit
 * word at the entry's byte and masked or sign-extended: the three bytes past an entry
 * lie inside rw_frame (each of those tables is followed by another member); a byte of
 * the wet or low grid as the aligned word that holds it (wv_wet, wv_byte_at). */
#ifndef BR_RWATER_VEC_H
#define BR_RWATER_VEC_H

typedef int32_t wv_i __attribute__((vector_size(32)));
typedef uint32_t wv_u __attribute__((vector_size(32)));
typedef int32_t wv_iun __attribute__((vector_size(32), aligned(4)));   /* at any 32-bit boundary */
typedef int64_t wv_q __attribute__((vector_size(32)));
typedef uint64_t wv_uq __attribute__((vector_size(32)));
typedef char wv_c __attribute__((vector_size(32)));
typedef long long wv_ll __attribute__((vector_size(32)));     /* GCC's 64-bit lanes (permdi256) */

#define WV_LD(P) (*(const wv_iun *)(const void *)(P))
#define WV_SET(S) ((wv_i){ (S), (S), (S), (S), (S), (S), (S), (S) })
/* one bit a lane (bit 4i: lane i) of a lane mask (-1 or 0) */
#define WV_BITS(M) ((uint32_t)__builtin_ia32_pmovmskb256((wv_c)(M)) & 0x11111111u)
/* the 32-bit words at BASE + SCALE IDX (SCALE 1 or 4) in the lanes MASK sets, 0 in the others */
#define WV_GATHER(BASE, IDX, MASK, SCALE) \
    __builtin_ia32_gathersiv8si(WV_SET(0), (const int *)(const void *)(BASE), (IDX), (MASK), (SCALE))
#define WV_MIN_U(A, B) ((wv_i)__builtin_ia32_pminud256((A), (B)))
#define WV_MIN(A, B) ((wv_i)__builtin_ia32_pminsd256((A), (B)))
#define WV_MAX(A, B) ((wv_i)__builtin_ia32_pmaxsd256((A), (B)))

/* The high 32 bits of each lane's product a b (unsigned, b < 2^32). */
static inline wv_i wv_mulhi(wv_i a, uint32_t b)
{
    const wv_i bv = WV_SET((int32_t)b);
    const wv_uq ev = (wv_uq)__builtin_ia32_pmuludq256(a, bv) >> 32;                    /* lanes 0, 2, .. */
    const wv_uq od = (wv_uq)__builtin_ia32_pmuludq256((wv_i)((wv_uq)a >> 32), bv);       /* lanes 1, 3, .. */
    return (wv_i)(ev | (od & 0xffffffff00000000ull));
}

/* Lane i = (uint32_t)((a_i^2 + bb) >> 8), water_px's den, for a_i^2 + bb >= 0 (bb >= 0). */
static inline wv_i wv_den(wv_i a, int64_t bb)
{
    const wv_q ev = (wv_q)__builtin_ia32_pmuldq256(a, a) + bb;
    const wv_i ao = (wv_i)((wv_uq)a >> 32);                                             /* (pmuldq: low words, signed) */
    const wv_q od = (wv_q)__builtin_ia32_pmuldq256(ao, ao) + bb;
    return (wv_i)((((wv_uq)ev >> 8) & 0xffffffffull) | ((wv_uq)od >> 8) << 32);
}

/* The lanes' constants and a row's values, made once a row and opaque to the compiler
 * (WV_OPAQUE: an empty asm), so that the loop keeps them in registers or reads them from
 * the stack instead of building each again at every group (mov, vmovd, vpbroadcastd) or
 * reading the frame again after each store (which may alias it). */
#define WV_OPAQUE(V) __asm__("" : "+x"(V))
typedef struct wv_row {
    wv_i lane, toff, m255, m888, mrb, mg, k256, hrb, hg, tab, wmax, zero;
    wv_i tint_u, tint_rb, tint_g, body, rdfar, sky, fade_d, fog_d30, xmax, rwmax, rsel, rw;
    int32_t s;                        /* the reflection's resolution shift (res_shift) */
    wv_uq s01a, s01b, s23a, s23b;     /* lane i's phase step from the group's first pixel */
    /* wet_at's values (wv_wet), when wet_lanes: ws0, ws1 in the low words (|ws| < 2^31),
     * inv_sx and inv_sy as low and high words, the grid's width, and the grid as the
     * aligned words that hold it (wet = wet_al + wet_mis) */
    int wet_lanes;
    wv_q ws0, ws1, wrel0, wrel1, gx0, gy0;
    wv_uq gxmax, gymax, isxl, isxh, isyl, isyh, wetw;
    const uint8_t *wet_al;
    int32_t wet_mis;
    /* plane_cell's values (wv_plane_cell), when cell_lanes (wet_lanes, and a grid whose
     * steps and sample count fit 31 bits): half a step, the steps, the grid's height, and
     * low as the aligned words that hold it (NULL: none) */
    int cell_lanes;
    wv_q hsx, hsy, sx, sy;
    wv_uq weth;
    int64_t sxsy;
    const uint8_t *low_al;
    int32_t low_mis;
} wv_row;

/* v < c (unsigned lanes) */
#define WV_LT_U(V, C) ((wv_i)((wv_u)(V) < (wv_u)(C)))

/* mix_pre and mix_rgb in lanes (the same sums: each field's below 2^16, so 32-bit lanes
 * hold them) */
static inline wv_i wv_mix_pre(const wv_row *c, wv_i a)
{
    const wv_u rb = ((wv_u)(a & c->mrb) * (wv_u)c->tint_u + (wv_u)c->tint_rb) >> 8;
    const wv_u g = ((wv_u)(a & c->mg) * (wv_u)c->tint_u + (wv_u)c->tint_g) >> 8;
    return ((wv_i)rb & c->mrb) | ((wv_i)g & c->mg);
}

static inline wv_i wv_mix(const wv_row *c, wv_i a, wv_i b, wv_i t)
{
    const wv_i u = c->k256 - t;
    const wv_u rb = ((wv_u)((a & c->mrb) * u) + (wv_u)((b & c->mrb) * t) + (wv_u)c->hrb) >> 8;
    const wv_u g = ((wv_u)((a & c->mg) * u) + (wv_u)((b & c->mg) * t) + (wv_u)c->hg) >> 8;
    return ((wv_i)rb & c->mrb) | ((wv_i)g & c->mg);
}

/* 1 when the lanes draw the frame's water: the usual case (waves on, the fixed tint,
 * Schlick's Fresnel term) and wave constants that fit them: wave_q8's amp_m (at most
 * 2^33 by rw_setup) split as 2^32 hi + lo, and inv_fade below 2^32 (it is 2^32 only when
 * wave_fade_d < 2^15, waves fading from under a unit of depth). */
static inline int wv_case(const rw_frame *r)
{
    return r->p.waves_on && r->p.tint_fixed && !r->p.fresnel_one && r->amp_m >= 0
           && r->amp_m <= ((int64_t)1 << 33) && r->inv_fade <= 0xffffffffu;
}

static inline void wv_row_make(wv_row *c, const rw_frame *r, const refl_view *rv, const rw_rowk *k, uint32_t sky)
{
    /* a pixel's step of u = 2x + 1 - w is 2: lane i's phases are the group's plus i 2 dph
     * (mod 2^64, as row_k's products) */
    const wv_uq l03 = { 0, 1, 2, 3 }, l47 = { 4, 5, 6, 7 };
    const wv_i lane = { 0, 1, 2, 3, 4, 5, 6, 7 };
    /* a phase pair's words index waves 2j (even words) and 2j + 1 (odd): the next table */
    const wv_i toff = { 0, 256, 0, 256, 0, 256, 0, 256 };
    c->lane = lane; c->toff = toff;
    c->m255 = WV_SET(255); c->m888 = WV_SET(0xffffff); c->mrb = WV_SET(0xff00ff); c->mg = WV_SET(0xff00);
    c->k256 = WV_SET(256); c->hrb = WV_SET(0x800080); c->hg = WV_SET(0x8000);
    c->tab = WV_SET(RW_TAB); c->wmax = WV_SET(RW_WAVE_PX * 128); c->zero = WV_SET(0);
    c->tint_u = WV_SET((int32_t)r->tint_u); c->tint_rb = WV_SET((int32_t)r->tint_rb);
    c->tint_g = WV_SET((int32_t)r->tint_g); c->body = WV_SET(r->p.refl_body);
    c->rdfar = WV_SET((int32_t)r->rdfar); c->sky = WV_SET((int32_t)sky);
    c->fade_d = WV_SET((int32_t)r->wave_fade_d); c->fog_d30 = WV_SET((int32_t)r->fog_d30);
    c->xmax = WV_SET(r->w - 1); c->rwmax = WV_SET(rv->rw - 1); c->rw = WV_SET(rv->rw);
    /* row_k's rcol[j] and rdep[j] lie (j + par) >> s rows of the reflection below
     * rcol[0] and rdep[0], par = m mod 2^s for m = y - RW_WAVE_PX + 2^(s-1) >= 0
     * (refl_row(y + j - RW_WAVE_PX, s) = (m + j) >> s, y >= RW_WAVE_PX; 2^(s-1) is 0 at
     * s = 0): j = dy + RW_WAVE_PX */
    c->s = k->s;
    c->rsel = WV_SET(RW_WAVE_PX + ((k->y - RW_WAVE_PX + ((1 << k->s) >> 1)) & ((1 << k->s) - 1)));
    c->s01a = l03 * (2 * k->dph[0]); c->s01b = l47 * (2 * k->dph[0]);
    c->s23a = l03 * (2 * k->dph[1]); c->s23b = l47 * (2 * k->dph[1]);
    c->wet_lanes = k->shore && !k->wbound && r->p.wet && k->ws0 > INT32_MIN && k->ws0 <= INT32_MAX
                   && k->ws1 > INT32_MIN && k->ws1 <= INT32_MAX;
    if (c->wet_lanes) {
        const wv_q one = { 1, 1, 1, 1 };
        const wv_uq uone = { 1, 1, 1, 1 };
        c->ws0 = one * k->ws0; c->ws1 = one * k->ws1; c->wrel0 = one * k->wrel0; c->wrel1 = one * k->wrel1;
        c->gx0 = one * r->gx0; c->gy0 = one * r->gy0;
        c->gxmax = uone * r->gxmax; c->gymax = uone * r->gymax;
        c->isxl = uone * (r->inv_sx & 0xffffffffu); c->isxh = uone * (r->inv_sx >> 32);
        c->isyl = uone * (r->inv_sy & 0xffffffffu); c->isyh = uone * (r->inv_sy >> 32);
        c->wetw = uone * (uint64_t)r->p.wet_w;
        c->wet_al = (const uint8_t *)((uintptr_t)r->p.wet & ~(uintptr_t)3);
        c->wet_mis = (int32_t)((uintptr_t)r->p.wet & 3u);
    }
    c->cell_lanes = 0;
    WV_OPAQUE(c->lane); WV_OPAQUE(c->toff); WV_OPAQUE(c->m255); WV_OPAQUE(c->m888); WV_OPAQUE(c->mrb);
    WV_OPAQUE(c->mg); WV_OPAQUE(c->k256); WV_OPAQUE(c->hrb); WV_OPAQUE(c->hg); WV_OPAQUE(c->tab);
    WV_OPAQUE(c->wmax); WV_OPAQUE(c->zero);
}

/* wv_plane_cell's values (cell_lanes), for a row that may hold tested pixels */
static RW_NOINLINE void wv_cell_make(wv_row *c, const rw_frame *r)
{
    const wv_q one = { 1, 1, 1, 1 };
    c->cell_lanes = c->wet_lanes && r->p.grid_sx > 0 && r->p.grid_sx <= INT32_MAX && r->p.grid_sy > 0
                    && r->p.grid_sy <= INT32_MAX && (int64_t)r->p.wet_w * r->p.wet_h <= INT32_MAX;
    if (!c->cell_lanes) return;
    c->hsx = one * r->half_sx; c->hsy = one * r->half_sy;
    c->sx = one * r->p.grid_sx; c->sy = one * r->p.grid_sy;
    c->weth = (wv_uq)(one * r->p.wet_h);
    c->sxsy = r->p.grid_sx * r->p.grid_sy;
    c->low_al = r->p.low ? (const uint8_t *)((uintptr_t)r->p.low & ~(uintptr_t)3) : NULL;
    c->low_mis = (int32_t)((uintptr_t)r->p.low & 3u);
}

/* v >> n in 64-bit lanes, arithmetic (AVX2 has none): with s = -1 where v < 0, 0 elsewhere,
 * ((v ^ s) >>> n) ^ s = floor(v / 2^n) */
static inline wv_q wv_sra64(wv_q v, int n)
{
    const wv_q s = v < 0;
    return (wv_q)((wv_uq)(v ^ s) >> n) ^ s;
}

/* ((wrel + ((a ws) >> 12)) f) >> 16, grid_pos's offset along one axis: a (sign-extended
 * 32 bits) times ws (|ws| < 2^31, low words) is vpmuldq's exact product; p f for f below
 * 2^21 as p's low word times f plus its high word (signed) times f, shifted (mod 2^64,
 * as the 64-bit product). */
static inline wv_q wv_grid(wv_q a, wv_q ws, wv_q wrel, wv_q f)
{
    const wv_q p = wv_sra64((wv_q)__builtin_ia32_pmuldq256((wv_i)a, (wv_i)ws), 12) + wrel;
    const wv_q lo = (wv_q)__builtin_ia32_pmuludq256((wv_i)p, (wv_i)f);
    const wv_q hi = (wv_q)__builtin_ia32_pmuldq256((wv_i)((wv_uq)p >> 32), (wv_i)f);
    return wv_sra64(lo + (wv_q)((wv_uq)hi << 32), 16);
}

/* ((uint64_t)g inv) >> 32 in the low words (mod 2^32), inv = h 2^32 + l: the low word of
 * g_lo l >> 32 + g_hi l + g_lo h (the rest of the product lies above bit 63). */
static inline wv_uq wv_cell(wv_uq g, wv_uq l, wv_uq h)
{
    return ((wv_uq)__builtin_ia32_pmuludq256((wv_i)g, (wv_i)l) >> 32)
           + (wv_uq)__builtin_ia32_pmuludq256((wv_i)(g >> 32), (wv_i)l) + (wv_uq)__builtin_ia32_pmuludq256((wv_i)g, (wv_i)h);
}

typedef int32_t wv_i4un __attribute__((vector_size(16), aligned(4)));

/* grid_pos for the four lanes at aq and f (Q16, below 2^21): *gx east, *gy south, world
 * units plus half a step */
static inline void wv_pos_half(const wv_row *c, const int32_t *aq, const int32_t *f, wv_q *gx, wv_q *gy)
{
    const wv_q a = __builtin_convertvector(*(const wv_i4un *)(const void *)aq, wv_q);
    const wv_q fq = __builtin_convertvector(*(const wv_i4un *)(const void *)f, wv_q);
    *gx = c->gx0 + wv_grid(a, c->ws0, c->wrel0, fq);
    *gy = c->gy0 - wv_grid(a, c->ws1, c->wrel1, fq);
}

/* wet_at for the four lanes at aq and f: the grid index (low words) and -1 where the
 * point lies on the grid */
static inline void wv_wet_half(const wv_row *c, const int32_t *aq, const int32_t *f, wv_q *idx, wv_q *in)
{
    wv_q gx, gy;
    wv_pos_half(c, aq, f, &gx, &gy);
    *in = ((wv_uq)gx < c->gxmax) & ((wv_uq)gy < c->gymax);
    *idx = (wv_q)((wv_uq)__builtin_ia32_pmuludq256((wv_i)wv_cell((wv_uq)gy, c->isyl, c->isyh), (wv_i)c->wetw)
                  + wv_cell((wv_uq)gx, c->isxl, c->isxh));
}

/* The bytes of grid g (read as the aligned words at g_al that hold them, g = g_al + mis)
 * at index idx in the lanes of m, 0 in the others. */
static inline wv_i wv_byte_at(const uint8_t *g_al, int32_t mis, wv_i idx, wv_i m)
{
    const wv_i i = idx + mis;
    const wv_i w = WV_GATHER(g_al, (wv_i)((wv_u)i >> 2), m, 4);
    return m & (wv_i)(((wv_u)w >> (((wv_u)i & 3u) << 3)) & 255u);
}

/* wet_at in the lanes of m, f[i] lane i's point along its ray (Q16, below 2^21): -1 where
 * the grid sample nearest the point is wet with id (the index below wet_w wet_h there,
 * as wet_at's), 0 elsewhere.  The sample's byte is read as the aligned word that holds
 * it, which never reaches past the grid's last word. */
static RW_INLINE wv_i wv_wet(const wv_row *c, const rw_frame *r, int32_t x, wv_i id, const int32_t *f, wv_i m)
{
    wv_q i0, n0, i1, n1;
    wv_i idx, ok;
    wv_wet_half(c, &r->aq[x], f, &i0, &n0);
    wv_wet_half(c, &r->aq[x + 4], f + 4, &i1, &n1);
    idx = __builtin_shufflevector((wv_i)i0, (wv_i)i1, 0, 2, 4, 6, 8, 10, 12, 14);
    ok = m & __builtin_shufflevector((wv_i)n0, (wv_i)n1, 0, 2, 4, 6, 8, 10, 12, 14);
    return ok & (wv_byte_at(c->wet_al, c->wet_mis, idx, ok) == id);
}

/* The tie and shore lanes of l (water_shows: the plane's point, plane_wet, or the
 * terrain's, shore_wet) of a row with wet_lanes: -1 where the water shows. */
static inline wv_i wv_shore(const wv_row *c, const rw_frame *r, int32_t x, wv_i id, wv_i dt, wv_i dw, wv_i l)
{
    const wv_i br = WV_GATHER(r->bratio, id, l, 4), tie = dt - dw < (int32_t)RW_DEPTH_TIE;
    int32_t f[8];
    uint32_t sh;
    *(wv_iun *)(void *)f = br;
    for (sh = WV_BITS(l & ~tie); sh; sh &= sh - 1) {     /* shore_wet's point, one a lane */
        const int32_t i = __builtin_ctz(sh) >> 2;
        f[i] = (int32_t)shore_point(br[i], (uint32_t)dt[i], (uint32_t)dw[i]);
    }
    return wv_wet(c, r, x, id, f, l & (br != 0));
}

/* plane_cell_of for the four lanes at aq and f (Q16, below 2^21): the cell's corner
 * (*ix, *iy, low words), the point's offsets from it (*fx, *fy: within a step of it, as
 * grid_index rounds up by less than one) and -1 where the whole cell lies on the grid. */
static inline void wv_cell_half(const wv_row *c, const int32_t *aq, const int32_t *f, wv_q *ix, wv_q *iy, wv_q *fx,
                                wv_q *fy, wv_q *in)
{
    const wv_uq mlo = { 0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu };
    wv_q gx, gy;
    wv_pos_half(c, aq, f, &gx, &gy);
    gx -= c->hsx;                   /* the point's own grid position */
    gy -= c->hsy;
    *in = ((wv_uq)gx < c->gxmax) & ((wv_uq)gy < c->gymax);       /* (negative: huge) */
    *ix = (wv_q)(wv_cell((wv_uq)gx, c->isxl, c->isxh) & mlo);
    *iy = (wv_q)(wv_cell((wv_uq)gy, c->isyl, c->isyh) & mlo);
    *in &= ((wv_uq)*ix + 1 < c->wetw) & ((wv_uq)*iy + 1 < c->weth);
    /* ix sx < wet_w 2^31 < 2^63: vpmuludq's exact product (both below 2^32) */
    *fx = gx - (wv_q)__builtin_ia32_pmuludq256((wv_i)*ix, (wv_i)c->sx);
    *fy = gy - (wv_q)__builtin_ia32_pmuludq256((wv_i)*iy, (wv_i)c->sy);
}

/* plane_cell in the lanes of m (tested triangles' pixels of group x, body ids id, in a
 * row with cell_lanes): -1 where the plane's point on the pixel's ray lies in a half cell
 * emit_cell keeps, as plane_cell says.  The half test's sums: |fx|, |fy| below a step
 * (< 2^31), so fx sy + fy sx and sx sy lie below 2^63. */
static RW_INLINE wv_i wv_plane_cell(const wv_row *c, const rw_frame *r, int32_t x, wv_i id, wv_i m)
{
    const wv_i br = WV_GATHER(r->bratio, id, m, 4);
    const int32_t w = r->p.wet_w;
    int32_t f[8];
    wv_q ix0, iy0, fx0, fy0, n0, ix1, iy1, fx1, fy1, n1, h0, h1;
    wv_i ok, ix, iy, i, nw, ne, sw, se, all, pnw, pne, psw, pse, half;
    *(wv_iun *)(void *)f = br;
    wv_cell_half(c, &r->aq[x], f, &ix0, &iy0, &fx0, &fy0, &n0);
    wv_cell_half(c, &r->aq[x + 4], f + 4, &ix1, &iy1, &fx1, &fy1, &n1);
    ok = m & (br != 0) & __builtin_shufflevector((wv_i)n0, (wv_i)n1, 0, 2, 4, 6, 8, 10, 12, 14);
    if (!WV_BITS(ok)) return c->zero;
    ix = __builtin_shufflevector((wv_i)ix0, (wv_i)ix1, 0, 2, 4, 6, 8, 10, 12, 14);
    iy = __builtin_shufflevector((wv_i)iy0, (wv_i)iy1, 0, 2, 4, 6, 8, 10, 12, 14);
    i = iy * w + ix;                /* < wet_w wet_h <= 2^31 - 1 */
    nw = wv_byte_at(c->wet_al, c->wet_mis, i, ok);
    ne = wv_byte_at(c->wet_al, c->wet_mis, i + 1, ok);
    sw = wv_byte_at(c->wet_al, c->wet_mis, i + w, ok);
    se = wv_byte_at(c->wet_al, c->wet_mis, i + w + 1, ok);
    all = ok & ((nw & ne & sw & se) == id) & ((nw | ne | sw | se) == id);     /* inside the water */
    ok &= ~all & ((nw == id) | (ne == id) | (sw == id) | (se == id));    /* a corner wet with the body */
    if (!WV_BITS(ok)) return all;
    /* corner_passes: wet with the body, or dry and not low */
    pnw = (nw == id) | (nw == 0); pne = (ne == id) | (ne == 0);
    psw = (sw == id) | (sw == 0); pse = (se == id) | (se == 0);
    if (c->low_al) {
        pnw &= (nw == id) | (wv_byte_at(c->low_al, c->low_mis, i, ok & (nw == 0)) == 0);
        pne &= (ne == id) | (wv_byte_at(c->low_al, c->low_mis, i + 1, ok & (ne == 0)) == 0);
        psw &= (sw == id) | (wv_byte_at(c->low_al, c->low_mis, i + w, ok & (sw == 0)) == 0);
        pse &= (se == id) | (wv_byte_at(c->low_al, c->low_mis, i + w + 1, ok & (se == 0)) == 0);
    }
    /* the south-east half (sw se ne) where fx sy + fy sx >= sx sy, else the north-west
     * one (nw ne sw); vpmuldq: fx, fy signed below 2^31, sx, sy below 2^31 */
    h0 = (wv_q)__builtin_ia32_pmuldq256((wv_i)fx0, (wv_i)c->sy) + (wv_q)__builtin_ia32_pmuldq256((wv_i)fy0, (wv_i)c->sx);
    h1 = (wv_q)__builtin_ia32_pmuldq256((wv_i)fx1, (wv_i)c->sy) + (wv_q)__builtin_ia32_pmuldq256((wv_i)fy1, (wv_i)c->sx);
    half = __builtin_shufflevector((wv_i)(h0 >= c->sxsy), (wv_i)(h1 >= c->sxsy), 0, 2, 4, 6, 8, 10, 12, 14);
    return all | (ok & pne & psw & ((half & pse) | (~half & pnw)));
}

/* The colour of the lanes in show (water_px's common case and water_one's fog): the
 * water pixels of the group at x, water depths dw, body ids id. */
static inline wv_i wv_water(const wv_row *c, const rw_frame *r, const refl_view *rv, const rw_rowk *k,
                            const uint8_t *crow, int32_t x, wv_i dw, wv_i show, wv_i mirror)
{
    const wv_i a = WV_LD(&r->aq[x]), ones = WV_SET(-1), xv = c->lane + x;
    const uint64_t u = (uint64_t)(int64_t)(2 * x + 1 - r->w);
    const uint64_t b01 = k->ph[0] + u * k->dph[0], b23 = k->ph[1] + u * k->dph[1];
    const wv_uq p01a = c->s01a + b01, p01b = c->s01b + b01, p23a = c->s23a + b23, p23b = c->s23b + b23;
    const uint32_t amp_lo = (uint32_t)r->amp_m, amp_hi = (uint32_t)(r->amp_m >> 32);
    wv_i q8, fade, ci, g01a, g01b, g23a, g23b, ea, eb, sx, sy, dx, dy, fr, refl, rgb;
    uint32_t dn[8];
    int i;
    /* wave_q8: dw amp_m >> 32 = dw hi + (dw lo >> 32) below 2^31 + 2^30 (dw < 2^30,
     * hi <= 2), at most RW_WAVE_PX 128; the fade's q8 (dw >> 14) < 2^9 2^16 */
    q8 = WV_MIN_U(wv_mulhi(dw, amp_lo) + dw * (int32_t)amp_hi, c->wmax);
    fade = WV_LT_U(dw, c->fade_d);
    q8 = (wv_mulhi(q8 * (wv_i)((wv_u)dw >> 14), (uint32_t)r->inv_fade) & fade) | (q8 & ~fade);
    /* cos^2 t: den >= 2^16 (water_px); 32-bit quotients, one a lane */
    *(wv_iun *)(void *)dn = wv_den(a, k->bb);
#pragma GCC unroll 8
    for (i = 0; i < 8; i++) dn[i] = k->cnum / dn[i];
    ci = WV_MIN_U(WV_LD(dn), c->tab);
    /* the four slopes (the high byte of each phase word), wave 2j + 1 beside 2j */
    g01a = WV_GATHER(r->wsine[0], (wv_i)((wv_u)p01a >> 24) + c->toff, ones, 1);
    g01b = WV_GATHER(r->wsine[0], (wv_i)((wv_u)p01b >> 24) + c->toff, ones, 1);
    g23a = WV_GATHER(r->wsine[2], (wv_i)((wv_u)p23a >> 24) + c->toff, ones, 1);
    g23b = WV_GATHER(r->wsine[2], (wv_i)((wv_u)p23b >> 24) + c->toff, ones, 1);
    /* pixel k's words 2k, 2k + 1: ce = c0 + c2, co = c1 + c3 */
    ea = ((wv_i)((wv_u)g01a << 24) >> 24) + ((wv_i)((wv_u)g23a << 24) >> 24);
    eb = ((wv_i)((wv_u)g01b << 24) >> 24) + ((wv_i)((wv_u)g23b << 24) >> 24);
    /* sx = ce + co, sy = ce - co: the pair sums come as pixels 0 1 4 5 2 3 6 7 */
    sx = (wv_i)__builtin_ia32_permdi256((wv_ll)__builtin_ia32_phaddd256(ea, eb), 0xd8);
    sy = (wv_i)__builtin_ia32_permdi256((wv_ll)__builtin_ia32_phsubd256(ea, eb), 0xd8);
    /* |q8 sx| <= 512 508 < 2^31 */
    dx = (q8 * sx) >> 15;
    dy = (q8 * sy) >> 15;
    ci = WV_MAX(WV_MIN(ci + ((sx * q8) >> 10), c->tab), c->zero);
    fr = WV_GATHER(r->fres, ci, show, 1) & c->m255;
    refl = WV_GATHER(r->skyrefl, ci, show, 4);
    if (WV_BITS(mirror)) {
        /* water_px's lookup: column x + dx clamped to the frame's, (x + dx) >> s to rw - 1;
         * row y + dy, whose reflection row row_k found where rx0 <= rx1 (its rows need no
         * clamp there), clamped to the frame's rows and refl_row's to the last otherwise,
         * and read only in the stored rows h0 .. h1 - 1 */
        const wv_i rx = WV_MIN(WV_MAX(WV_MIN(xv + dx, c->xmax), c->zero) >> c->s, c->rwmax);
        const uint8_t *dep = rv->dep, *col = rv->col;
        wv_i off, hit;
        if (k->rx0 <= k->rx1) {
            off = ((dy + c->rsel) >> c->s) * c->rw + rx;
            dep = k->rdep[0];
            col = k->rcol[0];
        } else {
            const wv_i yy = WV_MAX(WV_MIN(dy + k->y, WV_SET(r->h - 1)), c->zero);
            const wv_i ry = WV_MIN((yy + ((1 << c->s) >> 1)) >> c->s, WV_SET((r->h >> c->s) - 1));
            mirror &= (ry >= rv->h0) & (ry < rv->h1);
            off = (ry - rv->h0) * c->rw + rx;
        }
        hit = mirror & (WV_GATHER(dep, off, mirror, 4) != c->rdfar);
        refl = (WV_GATHER(col, off, hit, 4) & c->m888 & hit) | (refl & ~hit);
    }
    rgb = wv_mix(c, wv_mix_pre(c, WV_LD(crow + 4 * (size_t)x) & c->m888), refl, fr);
    if (r->fog_d30) {
        const wv_i fw = WV_GATHER(r->fog, (wv_i)((wv_u)dw >> r->fog_sh), show & WV_LT_U(dw, c->fog_d30), 1) & c->m255;
        rgb = wv_mix(c, rgb, c->sky, fw);       /* (a weight of 0 keeps rgb) */
    }
    return rgb;
}

/* 1 when no lane of lt (of group x .. x + 7, body ids id) passes the land test: all of
 * one body, in a run of land_gate's that may skip it (wk: the row's walk). */
static inline int wv_land_skipped(const rw_frame *r, const rw_rowk *k, int32_t x, wv_i id, wv_i lt, rw_walk *wk)
{
    const uint32_t lid = (uint32_t)id[__builtin_ctz(WV_BITS(lt)) >> 2];
    if (WV_BITS(lt & (id != (int32_t)lid))) return 0;
    if (x + 7 > wk->lx1 || lid != wk->lid) land_gate(r, k, x, lid, wk);
    return wk->lskip && x + 7 <= wk->lx1;
}

/* Water_one's pixels of row k->y for x from x0 while x + 8 <= xe, eight at a time;
 * returns the first column not done (water_row_px does the rest).  The common case:
 * XRGB8888, 32-bit depth (dsh 0; depths below 2^30, RS_DEPTH_ONE, so signed lanes
 * compare them), wv_case. */
static inline int32_t water_row_vec(const rw_frame *r, const refl_view *rv, const rw_rowk *k, uint8_t *crow,
                                    const uint8_t *drow, const uint8_t *wc, const uint8_t *wd, int32_t x0,
                                    int32_t xe, uint32_t sky, const int trows)
{
    wv_row c;
    rw_walk wk;
    int32_t x;
    const int land = r->p.land && k->shore;
    wv_row_make(&c, r, rv, k, sky);
    if (trows) wv_cell_make(&c, r);
    rw_walk_start(&wk);
    for (x = x0; x + 8 <= xe; x += 8) {
        const wv_u wcv = (wv_u)WV_LD(wc + 4 * (size_t)x);
        const wv_i id = (wv_i)((wcv >> 19) & 31u), nz = id != 0;
        wv_i dt, dw, gap, sdd, cand, show, tl = c.zero;
        uint32_t test;
        if (!WV_BITS(nz)) continue;
        dt = WV_LD(drow + 4 * (size_t)x);
        dw = WV_LD(wd + 4 * (size_t)x);
        /* the terrain nearer by more than the row's shore reach: dry (water_shows) */
        gap = dt - dw;
        sdd = WV_GATHER(k->sdd, id, nz, 4);
        cand = nz & ~((gap >= (int32_t)RW_DEPTH_TIE) & ((wv_u)gap > (wv_u)sdd));
        show = cand & (dw > dt);
        if (trows) {    /* a tested triangle's pixels: plane_cell (below) */
            tl = show & (wv_i)((wcv & RW_TESTED_RGB) != 0);
            show &= ~tl;
        }
        if (land) {
            /* the land test's lanes (water_shows): the terrain under the plane within
             * the shore bound; those whose plane point's nearest sample is dry (one of
             * the four corners land_at wants dry), or all where the lanes cannot look
             * (wet_lanes), go one by one */
            wv_i lt = show & ~((wv_u)(dw - dt) > (wv_u)sdd);
            if (WV_BITS(lt) && wv_land_skipped(r, k, x, id, lt, &wk)) lt = c.zero;
            if (WV_BITS(lt)) {
                if (c.wet_lanes) {
                    const wv_i br = WV_GATHER(r->bratio, id, lt, 4);
                    int32_t f[8];
                    *(wv_iun *)(void *)f = br;
                    lt &= wv_wet(&c, r, x, c.zero, f, lt & (br != 0));
                }
                show &= ~lt;
            }
        }
        test = WV_BITS(cand & ~show);
        if (trows && c.cell_lanes && WV_BITS(tl)) {     /* plane_cell in lanes */
            show |= wv_plane_cell(&c, r, x, id, tl);
            test &= ~WV_BITS(tl);
        }
        if (test && c.wet_lanes) {
            /* the ties and shore tests in lanes where three or more wait (the gap's
             * sign: the others are tested triangles' pixels, plane_cell) */
            const wv_i l = cand & ~show & (gap >= 0);
            const uint32_t lb = WV_BITS(l);
            if (__builtin_popcount(lb) >= 3) {
                show |= wv_shore(&c, r, x, id, dt, dw, l);
                test &= ~lb;
            }
        }
        /* the candidates with a test of their own: water_shows, one by one */
        for (; test; test &= test - 1) {
            const int32_t i = __builtin_ctz(test) >> 2;
            int32_t lx, ly;
            const int shows = water_shows(r, k, x + i, (uint32_t)id[i], wc, (uint32_t)dt[i], (uint32_t)dw[i], 0,
                                          RS_FMT_XRGB8888, trows, NULL, &lx, &ly);
            if (shows == RW_WATER) show[i] = -1;
            else if (shows == RW_LAND)
                ((uint32_t *)(void *)crow)[x + i] =
                    fog_to_sky(r, land_rgb(r, k, x + i, (uint32_t)id[i], lx, ly), (uint32_t)dw[i], sky);
        }
        if (WV_BITS(show))      /* (without rv->col water_px reads the sky alone) */
            __builtin_ia32_maskstored256((wv_i *)(void *)(crow + 4 * (size_t)x), show,
                                         wv_water(&c, r, rv, k, crow, x, dw, show,
                                                  rv->col ? show & (id == c.body) : c.zero));
    }
    return x;
}

#endif
