/* raster/water.c — reflection pass and the post hook that composites water, sky and fog
 * (see water.h; the water pass is raster/water_pass.c, the per-frame set-up
 * raster/water_setup.c).  Right shifts of negative values are arithmetic (checked once
 * in core/fx.h's users; gcc and clang on every target we build). */
#include "raster/water_int.h"     /* first: the v3 copy's names (water_int.h) */
#include <string.h>
#include "core/fx.h"

#if defined(__GNUC__)
#define RW_INLINE inline __attribute__((always_inline))   /* inner loops' helpers */
#define RW_NOINLINE __attribute__((noinline))              /* their less frequent cases */
#define RW_COLD __attribute__((noinline, cold))            /* their rare cases */
#else
#define RW_INLINE inline
#define RW_NOINLINE
#define RW_COLD
#endif

/* RW_VEC: the x86-64-v3 copy draws the common water pixels eight at a time in AVX2 lanes
 * (raster/water_vec.h; GCC's builtin names, as raster_span.h's GS_MASKED) */
#if defined(RS_BUILD_V3) && defined(__AVX2__) && defined(__GNUC__) && !defined(__clang__)
#define RW_VEC 1
#else
#define RW_VEC 0
#endif
/* ---------------------------------------------------------------- passes */

/* The reduced reflection row that full-resolution row y reads: the first whose sample
 * (its centre, full-resolution row ry 2^s + 2^(s-1)) lies at or below row y's centre
 * y + 1/2, that is ceil((y + 1/2 - 2^(s-1)) / 2^s) = (y + 2^(s-1)) >> s for s >= 1 (y
 * itself at full resolution).  Never above: the mirror image of a shore begins at the
 * shore line, so the water row just below it always reads mirrored terrain; the nearest
 * sample (y >> s) lies half a row above it on every other row, and there the far
 * shore's first water row read the sky, a bright line between the hills and their
 * reflection (half resolution, 1 row in 2).  The image moves down by 1/2 row on average
 * at half resolution, 3/2 at quarter. */
static inline int32_t refl_row(int32_t y, int32_t s)
{
    return (y + ((1 << s) >> 1)) >> s;
}

/* Reflection rows (of the reduced frame) stored for scratch rows [top, bottom): those
 * the post hook can read, the water rows widened by the waves' reach. */
static void refl_rows(const rw_frame *r, int32_t top, int32_t bottom, int32_t *h0, int32_t *h1)
{
    const int32_t s = r->p.res_shift;
    int32_t lo = r->wlo - RW_WAVE_PX, hi = r->whi + RW_WAVE_PX + 1;
    if (lo < top) lo = top;
    if (hi > bottom) hi = bottom;
    if (lo >= hi) { *h0 = *h1 = 0; return; }
    *h0 = refl_row(lo, s);
    *h1 = refl_row(hi - 1, s) + 1;
    if (*h1 > r->h >> s) *h1 = r->h >> s;
    if (*h0 > *h1) *h0 = *h1;
}

static int refl_touched(const void *user, int32_t y0, int32_t rows)
{
    const rw_frame *r = (const rw_frame *)user;
    return r->refl && r->wlo <= r->whi && y0 <= r->whi + RW_WAVE_PX && y0 + rows > r->wlo - RW_WAVE_PX;
}

static inline int32_t next_water(const uint8_t *wc, int32_t x, int32_t w, const int32_t fmt);

static inline uint32_t get_id(int32_t fmt, const void *row, int32_t x);

/* 1 when row y of the band's water-pass scratch (y in the band and in wlo .. whi) holds
 * the id of the body with the mirror (refl_body: the hook reads the reflection for that
 * body's pixels only). */
static int refl_body_in_row(const rw_frame *r, const rs_band *b, int32_t y)
{
    const int32_t i = r->water_pass;
    const uint32_t id = (uint32_t)r->p.refl_body;
    const uint8_t *row = (const uint8_t *)b->scratch[i] + (size_t)(y - b->scratch_y0[i]) * b->scratch_stride[i];
    int32_t x, x0, xe;
    rw_row_cols(r, y, &x0, &xe);        /* (the pass wrote and cleared no other column) */
    if (r->fmt == RS_FMT_RGB565) {
        for (x = next_water(row, x0, xe, RS_FMT_RGB565); x < xe; x = next_water(row, x + 1, xe, RS_FMT_RGB565))
            if (get_id(RS_FMT_RGB565, row, x) == id) return 1;
    } else {
        for (x = next_water(row, x0, xe, RS_FMT_XRGB8888); x < xe; x = next_water(row, x + 1, xe, RS_FMT_XRGB8888))
            if (get_id(RS_FMT_XRGB8888, row, x) == id) return 1;
    }
    return 0;
}

/* The reflection of the band: when the water pass ran before this one (ws_frame adds it
 * first), only the reduced rows the hook can read, those of the band's rows that hold
 * refl_body's id widened by the waves' reach (RW_WAVE_PX; the hook reads row y + dy,
 * |dy| <= RW_WAVE_PX, of that body's water pixels only), drawn at their places in the
 * scratch; nothing when the band holds none.  Otherwise every row refl_rows gives. */
static br_status refl_run(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    const rw_frame *r = (const rw_frame *)user;
    const size_t bpp = r->fmt == RS_FMT_RGB565 ? 2u : 4u, dbp = r->depth == RS_DEPTH16 ? 2u : 4u;
    const int32_t s = r->p.res_shift, wp = r->water_pass;
    int32_t h0, h1, g0, g1;
    refl_rows(r, b->scratch_y0[self], b->scratch_y0[self] + b->scratch_rows[self], &h0, &h1);
    if (h1 <= h0) return BR_OK;
    g0 = h0; g1 = h1;
    if (wp >= 0 && wp < self && b->scratch[wp] && b->scratch_y0[wp] == b->y0 && b->scratch_rows[wp] == b->rows) {
        /* the rows of the band that can hold refl_body's pixels (the water pass drew
         * rows wlo .. whi only) */
        const int32_t wl = r->wlo > r->rlo ? r->wlo : r->rlo, wh = r->whi < r->rhi ? r->whi : r->rhi;
        const int32_t lo = wl > b->y0 ? wl : b->y0;
        const int32_t hi = wh < b->y0 + b->rows - 1 ? wh : b->y0 + b->rows - 1;
        int32_t ya = lo, yb = hi;
        while (ya <= hi && !refl_body_in_row(r, b, ya)) ya++;
        if (ya > hi) return BR_OK;                  /* none in the band: nothing reads it */
        while (yb > ya && !refl_body_in_row(r, b, yb)) yb--;
        ya = ya - RW_WAVE_PX < 0 ? 0 : ya - RW_WAVE_PX;
        yb = yb + RW_WAVE_PX > r->h - 1 ? r->h - 1 : yb + RW_WAVE_PX;
        if (refl_row(ya, s) > g0) g0 = refl_row(ya, s);
        if (refl_row(yb, s) + 1 < g1) g1 = refl_row(yb, s) + 1;
        if (g1 <= g0) return BR_OK;
    } else if (wp >= 0 && wp < self) return BR_OK;  /* the water pass skipped the band */
    return rs_draw_band(r->refl, g0, g1 - g0, (uint8_t *)b->scratch[self] + (size_t)(g0 - h0) * (size_t)r->refl->w * bpp,
                        (size_t)r->refl->w * bpp,
                        (uint8_t *)b->scratch_depth[self] + (size_t)(g0 - h0) * (size_t)r->refl->w * dbp, st);
}

br_status rw_pass_reflection(rs_pass *pass, const rw_frame *r)
{
    if (!pass || !r || !r->refl) return BR_E_ARG;
    memset(pass, 0, sizeof *pass);
    pass->name = "reflection";
    pass->margin = RW_WAVE_PX;
    pass->scratch = 1;
    pass->rows_touched = refl_touched;
    pass->run = refl_run;
    pass->user = r;
    return BR_OK;
}

/* ---------------------------------------------------------------- the post hook */

static uint32_t get_rgb(int32_t fmt, const void *row, int32_t x)
{
    if (fmt == RS_FMT_RGB565) return unpack565(((const uint16_t *)row)[x]);
    return ((const uint32_t *)row)[x] & 0xffffffu;
}

static uint32_t get_depth(int32_t depth, const void *row, int32_t x)
{
    return depth == RS_DEPTH16 ? ((const uint16_t *)row)[x] : ((const uint32_t *)row)[x];
}

/* The water id of a water-pass pixel (RW_ID_RGB: the top five bits of red). */
static inline uint32_t get_id(int32_t fmt, const void *row, int32_t x)
{
    return fmt == RS_FMT_RGB565 ? (uint32_t)((const uint16_t *)row)[x] >> 11 : (((const uint32_t *)row)[x] >> 19) & 31u;
}

/* Whether a water-pass pixel is of a tested block (RW_TESTED_RGB). */
static inline int get_tested(int32_t fmt, const void *row, int32_t x)
{
    return fmt == RS_FMT_RGB565 ? (((const uint16_t *)row)[x] >> 10) & 1u : (((const uint32_t *)row)[x] >> 15) & 1u;
}

/* The reflection scratch as the hook reads it. */
typedef struct refl_view {
    const uint8_t *col, *dep;
    int32_t h0, h1, rw;
} refl_view;

/* sdd of a row with no plane point: a pixel whose terrain is nearer is land (dt - dw > 0) */
static const uint32_t no_shore[RW_MAX_ID + 1];

/* Row y's values for the per-pixel functions below, read once a row (the hook's pixel
 * stores may alias the frame's 32-bit tables, so the compiler would reload them, and
 * redo their products, at every pixel). */
typedef struct rw_rowk {
    int32_t y;
    int shore;                  /* the shore test has a plane point in this row: wet and tkr >= 0 */
    int wbound;                 /* the shore bound has a world term (shore_bound and shore_w) */
    int ws32;                   /* ws0 and ws1 fit 32 bits, as ws0_32 and ws1_32 (grid_pos) */
    int32_t ws0_32, ws1_32;
    const uint32_t *sdd;        /* per body: the largest dt - dw worth a shore test in this row,
                                   shore_tdd, or no_shore where the row has no plane point */
    uint32_t cnum;              /* (rz^2 >> 8) << 10 as 32 bits: cos^2 t's numerator */
    int64_t bb;                 /* bq^2 + Q12^2: the row's part of cos^2 t's denominator */
    int64_t ws0, ws1, wrel0, wrel1, tkr;        /* wstep[y], wrel[y], tkr[y] */
    /* wave k's phase at column x, 2^-32 turns (mod 2^32; bits 24..31 index wsine):
     * ph_k + u dph_k, u = 2x + 1 - w: at the row's plane point eye + wrel and time_ms,
     * a quarter turn on (the slope of a sine is its cosine), plus u times the point's move
     * per unit of u (wsig) times the wave numbers.  Two waves share a 64-bit word, wave 2j
     * in the low half of ph[j] and dph[j], 2j + 1 in the high half: one product gives
     * both phases.  The low half's product spills floor(u dph_2j / 2^32) into the high
     * half's bit 0: |u| <= RS_MAX_DIM = 2^12 and dph_2j < 2^32, so at most 2^12 units of
     * 2^-32 turns (and the low half's carry, 1): the high half's index (bits 24..31)
     * moves only where its phase lies within 2^-20 turns of a 1/256 turn step. */
    uint64_t ph[RW_WAVES / 2], dph[RW_WAVES / 2];
    /* when every row y + dy, |dy| <= RW_WAVE_PX, lies in the frame and its reduced row
     * refl_row(y + dy) in the stored rows [h0, h1) (row_k), their colour and depth rows are
     * rcol[dy + RW_WAVE_PX], rdep[dy + RW_WAVE_PX], and for x in [rx0, rx1] every x + dx
     * lies in the frame's columns and (x + dx) >> s below rw: water_px's clamps change
     * nothing there (|dx|, |dy| <= RW_WAVE_PX: see water_px).  Otherwise rx0 > rx1. */
    int32_t rx0, rx1;
    int32_t s;                  /* the reflection's resolution shift (res_shift) */
    const uint8_t *rcol[2 * RW_WAVE_PX + 1], *rdep[2 * RW_WAVE_PX + 1];
} rw_rowk;

static RW_INLINE void row_k(const rw_frame *r, const refl_view *rv, int32_t y, rw_rowk *k, const int32_t fmt,
                            const int32_t depth)
{
    const int32_t rz = r->rz[y], s = r->p.res_shift;
    const int64_t b = r->bq[y];
    if (rv->col && y >= RW_WAVE_PX && y + RW_WAVE_PX < r->h && refl_row(y - RW_WAVE_PX, s) >= rv->h0
        && refl_row(y + RW_WAVE_PX, s) < rv->h1) {
        const size_t bpp = fmt == RS_FMT_RGB565 ? 2u : 4u, dbp = depth == RS_DEPTH16 ? 2u : 4u;
        const int32_t xmax = (rv->rw << s) - 1 < r->w - 1 ? (rv->rw << s) - 1 : r->w - 1;
        int32_t j, ry = refl_row(y - RW_WAVE_PX, s);
        const uint8_t *pc = rv->col + (size_t)(ry - rv->h0) * (size_t)rv->rw * bpp;
        const uint8_t *pd = rv->dep + (size_t)(ry - rv->h0) * (size_t)rv->rw * dbp;
        for (j = 0; j <= 2 * RW_WAVE_PX; j++) {     /* refl_row(y + j - RW_WAVE_PX) grows by 0 or 1 */
            if (refl_row(y + j - RW_WAVE_PX, s) != ry) {
                ry++;
                pc += (size_t)rv->rw * bpp;
                pd += (size_t)rv->rw * dbp;
            }
            k->rcol[j] = pc;
            k->rdep[j] = pd;
        }
        k->rx0 = RW_WAVE_PX;
        k->rx1 = xmax - RW_WAVE_PX;
    } else {
        k->rx0 = 1; k->rx1 = 0;     /* no column */
    }
    k->y = y;
    k->s = s;
    k->tkr = r->tkr[y];
    k->shore = r->p.wet && k->tkr >= 0;
    k->sdd = k->shore ? r->shore_tdd : no_shore;
    k->wbound = r->p.shore_bound && r->p.shore_w;
    k->cnum = (uint32_t)(((uint64_t)((int64_t)rz * rz) >> 8) << 10);
    k->bb = b * b + (int64_t)Q12 * Q12;
    k->ws0 = r->wstep[y][0]; k->ws1 = r->wstep[y][1];
    k->ws32 = k->ws0 >= INT32_MIN && k->ws0 <= INT32_MAX && k->ws1 >= INT32_MIN && k->ws1 <= INT32_MAX;
    k->ws0_32 = k->ws32 ? (int32_t)k->ws0 : 0;
    k->ws1_32 = k->ws32 ? (int32_t)k->ws1 : 0;
    k->wrel0 = r->wrel[y][0]; k->wrel1 = r->wrel[y][1];
    {
        const uint32_t px = (uint32_t)(r->eye[0] + k->wrel0), py = (uint32_t)(r->eye[1] + k->wrel1);
        const uint64_t s0 = (uint64_t)r->wsig[y][0], s1 = (uint64_t)r->wsig[y][1];
        int j;
        for (j = 0; j < RW_WAVES; j++) {
            /* products mod 2^32 (the phase's own modulus); dph's Q16 products wrap mod 2^64,
             * and only their bits 16..47 are kept */
            const uint32_t ph = px * (uint32_t)r->kx[j] + py * (uint32_t)r->ky[j]
                                + (uint32_t)r->p.time_ms * r->kt[j] + (64u << 24);
            const uint32_t dph = (uint32_t)((s0 * (uint64_t)r->kx[j] + s1 * (uint64_t)r->ky[j]) >> 16);
            if (j & 1) { k->ph[j >> 1] |= (uint64_t)ph << 32; k->dph[j >> 1] |= (uint64_t)dph << 32; }
            else { k->ph[j >> 1] = ph; k->dph[j >> 1] = dph; }
        }
    }
}

#if RW_WAVES != 4
#error "raster/water.c: water_px sums exactly four waves (RW_WAVES)"
#endif

/* The waves' displacement at water depth dw (30-bit units), Q8 pixels: A f / zc, at most
 * RW_WAVE_PX / 2 (the slopes' sums reach 2 x it, water_px), fading as 1 / zc^2 beyond
 * wave_fade_d; 0 with the waves off.  A function of dw alone: water_row_px keeps the last
 * one of the row (a plane's pixels along a row mostly share their depth).  0 <= q8 <=
 * RW_WAVE_PX 128: amp_m >= 0 (rw_setup refuses wave_amp < 0), and the fade's factor
 * (dw >> 14) inv_fade is at most 2^32 below wave_fade_d. */
static RW_INLINE int32_t wave_q8(const rw_frame *r, uint32_t dw)
{
    int64_t q8 = ((int64_t)dw * r->amp_m) >> 32;
    if (q8 > RW_WAVE_PX * 128) q8 = RW_WAVE_PX * 128;
    /* beyond wave_fade_d (far away) the waves fade as 1/zc^2: shorter than a pixel there,
     * they would only alias */
    if (dw < r->wave_fade_d) q8 = (int64_t)(((uint64_t)q8 * (dw >> 14) * r->inv_fade) >> 32);
    return (int32_t)q8;
}

/* A row's running values for its pixels, left to right (water_row_px, post_rows): the
 * water depth the last wave displacement was made for (qdw; 0: none, as a water depth is
 * > 0) and that displacement (q8, wave_q8's, or 0 with the waves off); the last cos^2 t
 * index (qci, cos2_index's; RW_TAB + 1: none yet); the land test's run (land_gate: its
 * last column lx1, -1 for none yet, its body lid, and lskip 1 when no pixel of it passes
 * the land test). */
typedef struct rw_walk {
    uint32_t qdw, qci;
    int32_t q8;
    int32_t lx1, lskip;
    uint32_t lid;
} rw_walk;

static inline void rw_walk_start(rw_walk *wk)
{
    wk->qdw = 0; wk->qci = RW_TAB + 1; wk->q8 = 0;
    wk->lx1 = -1; wk->lskip = 0; wk->lid = 0;
}

/* RW_SOFT_DIV: 32-bit `/` is a library call (Armv7-A without the divide extension, as
 * Debian's armhf; __aeabi_uidiv, tens of instructions), or the BR_DIV64_NATIVE=0 test
 * build (RS_TEST_32BIT), which runs the same code on the host. */
#if (defined(__arm__) && !defined(__ARM_FEATURE_IDIV)) || defined(RS_TEST_32BIT)
#define RW_SOFT_DIV 1
#else
#define RW_SOFT_DIV 0
#endif

/* RW_MUL32: 64 x 64-bit products take three multiplies (32-bit targets: core/config.h
 * BR_REG64): the shore and land tests' grid positions from 32-bit ones where the operands
 * fit (raster/water_shore.h grid_pos, grid_index). */
#define RW_MUL32 (!BR_REG64)

/* 1 when q = floor(cnum / den) (den > 0): q den <= cnum < (q + 1) den. */
static inline int rw_is_quot(uint32_t q, uint32_t cnum, uint32_t den)
{
    const uint64_t p = (uint64_t)q * den;
    return p <= cnum && cnum - p < den;
}

/* cos^2 t's table index min(cnum / den, RW_TAB) (den >= 2^16).  With RW_SOFT_DIV, *qci
 * is the row's last index (RW_TAB + 1: none yet), which serves, or a neighbour of it,
 * when it passes rw_is_quot (RW_TAB when RW_TAB den <= cnum): cos^2 t moves by at most
 * one entry between most neighbouring pixels.  Else the division.  The same index
 * either way. */
static RW_INLINE uint32_t cos2_index(uint32_t cnum, uint32_t den, uint32_t *qci)
{
    uint32_t c = *qci;
#if RW_SOFT_DIV
    if (c == RW_TAB && (uint64_t)RW_TAB * den <= cnum) return c;
    if (c < RW_TAB && rw_is_quot(c, cnum, den)) return c;
    if (c < RW_TAB && rw_is_quot(c + 1, cnum, den)) return *qci = c + 1;
    if (c - 1 < RW_TAB && rw_is_quot(c - 1, cnum, den)) return *qci = c - 1;   /* 1 <= c <= RW_TAB */
#endif
    c = cnum / den;
    c = c < RW_TAB ? c : RW_TAB;
    *qci = c;
    return c;
}

/* The colour of water pixel (x, k->y): terrain colour ct and depth dt under it, water
 * depth dw (30-bit units), body id, the row's walk wk (wk->q8 = wave_q8(dw), 0 with the
 * waves off; its cos^2 t index moves on to x); fmt and
 * depth are the frame's (constants at each call, as in post_rows); common (a constant
 * too) promises what rw_post checked: waves on, the fixed tint, Schlick's Fresnel term, the
 * half-resolution reflection (res_shift 1: k->s is 1). */
static RW_INLINE uint32_t water_px(const rw_frame *r, const refl_view *rv, const rw_rowk *k, int32_t x, uint32_t ct,
                         uint32_t dt, uint32_t dw, uint32_t id, rw_walk *wk, const int32_t fmt,
                         const int32_t depth, const int common)
{
    const int32_t a = r->aq[x], y = k->y, s = common ? 1 : k->s;
    /* den >= Q12^2 >> 8 = 2^16 (k->bb includes Q12^2), so never 0 */
    const uint32_t den = (uint32_t)(((int64_t)a * a + k->bb) >> 8);
    uint32_t ci = cos2_index(k->cnum, den, &wk->qci);
    const int32_t q8 = wk->q8;
    int32_t dx = 0, dy = 0;
    uint32_t refl, refr, fr, x32;
    if (q8 != 0) {      /* else dx = dy = 0 and ci untilted, whatever the phase */
        /* each wave's slope at the pixel (row_k's phases); |sx|, |sy| <= 254, the sum
         * of the amplitudes (wave_set), so |dx|, |dy| <= 512 254 >> 15 < RW_WAVE_PX;
         * |q8 sx| <= 512 254 < 2^31 */
        const uint64_t u = (uint64_t)(int64_t)(2 * x + 1 - r->w);
        const uint64_t p01 = k->ph[0] + u * k->dph[0], p23 = k->ph[1] + u * k->dph[1];
        const int32_t c0 = r->wsine[0][(p01 >> 24) & 255u], c1 = r->wsine[1][p01 >> 56];
        const int32_t c2 = r->wsine[2][(p23 >> 24) & 255u], c3 = r->wsine[3][p23 >> 56];
        const int32_t ce = c0 + c2, co = c1 + c3, sx = ce + co, sy = ce - co;
        int32_t ti;
        dx = (q8 * sx) >> 15;
        dy = (q8 * sy) >> 15;
        ti = (int32_t)ci + ((sx * q8) >> 10);    /* the slope tilts cos t */
        ci = ti < 0 ? 0u : ti > RW_TAB ? (uint32_t)RW_TAB : (uint32_t)ti;
    }
    fr = !common && r->p.fresnel_one ? 256u : r->fres[ci];
    refl = r->skyrefl[ci];      /* the reflected sky */
    if (id == (uint32_t)r->p.refl_body) {     /* only the mirror's body reads the mirror */
        if (x >= k->rx0 && x <= k->rx1) {      /* (rx0 <= rx1 only with rv->col) */
            /* the lookup below without its clamps, which change nothing here */
            const int32_t rx = (x + dx) >> s;
            if (get_depth(depth, k->rdep[dy + RW_WAVE_PX], rx) != r->rdfar)
                refl = get_rgb(fmt, k->rcol[dy + RW_WAVE_PX], rx);
        } else if (rv->col) {
            int32_t yy = y + dy, xx = x + dx, ry, rx;
            if (yy < 0) yy = 0;
            if (yy >= r->h) yy = r->h - 1;
            if (xx < 0) xx = 0;
            if (xx >= r->w) xx = r->w - 1;
            ry = refl_row(yy, s); rx = xx >> s;
            if (ry > (r->h >> s) - 1) ry = (r->h >> s) - 1;    /* (the last row, h even) */
            if (rx >= rv->rw) rx = rv->rw - 1;
            if (ry >= rv->h0 && ry < rv->h1) {
                const size_t o = (size_t)(ry - rv->h0) * (size_t)rv->rw;
                const size_t bpp = fmt == RS_FMT_RGB565 ? 2u : 4u, dbp = depth == RS_DEPTH16 ? 2u : 4u;
                if (get_depth(depth, rv->dep + o * dbp, rx) != r->rdfar) refl = get_rgb(fmt, rv->col + o * bpp, rx);
            }
        }
    }
    /* refraction: x32 = 32 L / tint_len, L = zc_w (dw / dt - 1) (dt < dw), zc_w the
     * body's plane point's zc = the reflected plane's times bratio: tkr[y] bratio q >> 48
     * with q = (dw - dt) / dt, Q16, from both depths brought to 16 bits */
    x32 = 255;
    if (common || r->p.tint_fixed) return mix_rgb(mix_pre(ct, r->tint_u, r->tint_rb, r->tint_g), refl, fr);
    if (k->tkr >= 0 && r->bratio[id] && dt < dw) {
        const int32_t sh = dw >= 65536u ? 16 - fx_clz32(dw) : 0;    /* dw >> sh < 2^16 */
        uint32_t w16, t16;
        w16 = dw >> sh; t16 = dt >> sh;
        if (t16) {
            uint32_t q = ((w16 - t16) << 16) / t16;
            int64_t tb = (k->tkr * r->bratio[id]) >> 16;
            uint64_t v;
            if (tb > ((int64_t)1 << 40)) tb = (int64_t)1 << 40;
            v = ((uint64_t)tb * (q > (1u << 20) ? (1u << 20) : q)) >> 32;
            x32 = v > 255u ? 255u : (uint32_t)v;
        }
    }
    refr = mix_rgb(ct, r->p.water_rgb, r->tint[x32 > 255u ? 255u : x32]);
    return mix_rgb(refr, refl, fr);
}

#include "raster/water_shore.h"

/* The first pixel at or after x of a water-pass row whose id is set (w if none): x itself
 * first (runs of water), then sixteen pixels a test (64-bit words, read with memcpy: rows
 * need no alignment), then one by one. */
static inline uint64_t ld64(const void *p)
{
    uint64_t v;
    memcpy(&v, p, sizeof v);
    return v;
}

static inline int32_t next_water(const uint8_t *wc, int32_t x, int32_t w, const int32_t fmt)
{
    if (fmt == RS_FMT_RGB565) {
        const uint16_t *p = (const uint16_t *)(const void *)wc;
        const uint64_t m = 0xf800f800f800f800ull;
        if (x < w && (p[x] & 0xf800u)) return x;       /* inside a run of water */
        for (; x + 16 <= w; x += 16) {
            const uint8_t *q = (const uint8_t *)(p + x);
            if ((ld64(q) | ld64(q + 8) | ld64(q + 16) | ld64(q + 24)) & m) break;
        }
        while (x < w && !(p[x] & 0xf800u)) x++;
    } else {
        const uint32_t *p = (const uint32_t *)(const void *)wc;
        const uint64_t m = (uint64_t)(31u << 19) << 32 | (31u << 19);
        if (x < w && (p[x] & (31u << 19))) return x;   /* inside a run of water */
        for (; x + 16 <= w; x += 16) {
            const uint8_t *q = (const uint8_t *)(p + x);
            if ((ld64(q) | ld64(q + 8) | ld64(q + 16) | ld64(q + 24) | ld64(q + 32) | ld64(q + 40) | ld64(q + 48)
                 | ld64(q + 56)) & m)
                break;
        }
        while (x < w && !(p[x] & (31u << 19))) x++;
    }
    return x;
}

/* Row y's water-pass scratch in the band: colour (returned) and depth (*wd), valid in
 * columns *x0 .. *xe - 1; NULL where the pass drew nothing there (water_run seeds only
 * the water rows wlo .. whi, and in them the columns water_cols found). */
static inline const uint8_t *water_row(const rw_frame *r, const rs_band *b, const uint8_t *wcol, const uint8_t *wdep,
                                       int32_t wy0, int32_t wrows, int32_t y, size_t dbp, const uint8_t **wd,
                                       int32_t *x0, int32_t *xe)
{
    if (!wcol || y < wy0 || y >= wy0 + wrows || y < r->wlo || y > r->whi) return NULL;
    rw_row_cols(r, y, x0, xe);
    if (*x0 >= *xe) return NULL;
    *wd = wdep + (size_t)(y - wy0) * (size_t)b->w * dbp;
    return wcol + (size_t)(y - wy0) * b->stride;
}

/* Whether depths gap = |dt - dw| (buffer units, << dsh 30-bit) apart lie within the LOD's
 * reach for body id in row k (the shore bound, rw_params: the terrain drawn over a sample
 * lies within it above or under the sample's true surface): the row's sdd, and with a
 * world term E gap <= shore_w dt + shore_c. */
static RW_INLINE int within_reach(const rw_frame *r, const rw_rowk *k, uint32_t id, uint32_t gap, uint32_t dt,
                                  int32_t dsh)
{
    return (gap << dsh) <= k->sdd[id]
           && !(k->wbound && r->ebody[id] * (int64_t)(gap << dsh) > r->p.shore_w * (int64_t)(dt << dsh) + r->p.shore_c);
}

/* water_shows's answers: not water (the terrain pass's pixel stays), water, or the land of
 * a dry sample the terrain's LOD drew under the plane (the land test). */
enum { RW_NOT = 0, RW_WATER = 1, RW_LAND = 2 };

/* Whether the water of body id at pixel (x, y) shows over the terrain, depths dt (terrain)
 * and dw (water) in buffer units (<< dsh: 30-bit).  RW_WATER when the water is nearer
 * (and, for a tested triangle's pixel in a row trows allows, plane_cell says so); or the
 * two tie (RW_DEPTH_TIE) and the plane's point is wet; or the terrain is nearer within
 * the shore bound and its point on the ray is wet (the LOD over water).  RW_LAND, with
 * the sample in *lx, *ly, when the water is nearer but the terrain lies under the plane by
 * no more than the shore bound allows for land (the same bound: the LOD moves the surface
 * by at most it, up or down) and the plane's point lies on a dry sample (land_at: the
 * LOD sank land whose true height is at or above the level; lower, it would be wet). */
static RW_INLINE int water_shows(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id, const uint8_t *wc,
                                 uint32_t dt, uint32_t dw, int32_t dsh, const int32_t fmt, const int trows,
                                 rw_walk *wk, int32_t *lx, int32_t *ly)
{
    /* (dw >= 1: the pass drew the pixel over a seed of at least dfar >= 0) */
    if (dw + RW_DEPTH_TIE > dt) {
        if (dw <= dt) return plane_wet(r, k, x, id);
        if (trows && get_tested(fmt, wc, x)) return plane_cell(r, k, x, id);
        if (r->p.land && within_reach(r, k, id, dw - dt, dt, dsh)) {
            if (wk && (x > wk->lx1 || id != wk->lid)) land_gate(r, k, x, id, wk);
            if (!(wk && wk->lskip) && land_at(r, k, x, id, lx, ly)) return RW_LAND;
        }
        return RW_WATER;
    }
    if (!within_reach(r, k, id, dt - dw, dt, dsh)) return 0;     /* (dt - dw >= RW_DEPTH_TIE > 0) */
    return shore_wet(r, k, x, id, dt << dsh, dw << dsh);
}

/* Writes a pixel the hook computed (RGB565: dithered). */
static inline void put_px(uint8_t *crow, int32_t x, int32_t y, uint32_t rgb, const int32_t fmt)
{
    if (fmt == RS_FMT_RGB565) ((uint16_t *)(void *)crow)[x] = pack565_dither(rgb, x, y);
    else ((uint32_t *)(void *)crow)[x] = rgb;
}

/* rgb fogged by depth d (30-bit) towards the row's sky colour: a water or land pixel's
 * (water_one, and water_row_vec's land pixels). */
static inline uint32_t fog_to_sky(const rw_frame *r, uint32_t rgb, uint32_t d, uint32_t sky)
{
    const uint32_t fw = fog_weight(r->fog, (uint32_t)r->fog_sh, r->fog_d30, d);
    return fw ? mix_rgb(rgb, sky, fw) : rgb;
}

/* Water-pass pixel x (its id set) of row k->y for water_rows_only: its colour when the
 * water shows there, fogged by the water's depth towards the row's sky colour.  wk: the
 * row's walk (a plane's pixels along a row mostly share their depth, so the wave
 * displacement is made again only where it changes); trows (a constant at each call):
 * the row may hold a tested triangle's pixels (rw_frame.trow), whose flag is read only
 * then. */
static RW_INLINE void water_one(const rw_frame *r, const refl_view *rv, const rw_rowk *k, uint8_t *crow,
                                const uint8_t *drow, const uint8_t *wc, const uint8_t *wd, int32_t x, uint32_t sky,
                                rw_walk *wk, const int32_t fmt, const int32_t depth,
                                const int common, const int trows)
{
    const int32_t dsh = depth == RS_DEPTH16 ? 14 : 0;
    const uint32_t id = get_id(fmt, wc, x), dt = get_depth(depth, drow, x), dw = get_depth(depth, wd, x);
    uint32_t rgb;
    int32_t lx, ly;
    const int shows = water_shows(r, k, x, id, wc, dt, dw, dsh, fmt, trows, wk, &lx, &ly);
    if (shows == RW_NOT) return;
    if (shows == RW_LAND) rgb = land_rgb(r, k, x, id, lx, ly);
    else {
        if ((common || r->p.waves_on) && dw != wk->qdw) { wk->qdw = dw; wk->q8 = wave_q8(r, dw << dsh); }
        rgb = water_px(r, rv, k, x, get_rgb(fmt, crow, x), dt << dsh, dw << dsh, id, wk, fmt, depth, common);
    }
    put_px(crow, x, k->y, fog_to_sky(r, rgb, dw << dsh, sky), fmt);
}

#if RW_VEC
#include "raster/water_vec.h"
#endif

/* water_rows_only's pixels of one row (water_one's, from x0 to xe - 1): in the x86-64-v3
 * copy's common case eight at a time first (water_vec.h). */
static RW_INLINE void water_row_px(const rw_frame *r, const refl_view *rv, const rw_rowk *k, uint8_t *crow,
                                   const uint8_t *drow, const uint8_t *wc, const uint8_t *wd, int32_t x0, int32_t xe,
                                   const int32_t fmt, const int32_t depth, const int common, const int trows)
{
    const uint32_t sky = r->sky[k->y];
    rw_walk wk;
    int32_t x;
#if RW_VEC
    if (fmt == RS_FMT_XRGB8888 && depth == RS_DEPTH32 && wv_case(r))
        x0 = water_row_vec(r, rv, k, crow, drow, wc, wd, x0, xe, sky, trows);
#endif
    rw_walk_start(&wk);
    for (x = next_water(wc, x0, xe, fmt); x < xe; x = next_water(wc, x, xe, fmt))
        for (; x < xe && get_id(fmt, wc, x); x++)       /* a run of water */
            water_one(r, rv, k, crow, drow, wc, wd, x, sky, &wk, fmt, depth, common, trows);
}

/* The hook when the terrain frame carries its own fog and sky (rw_fog_vertices): only
 * water pixels change, fogged by the water's depth.  Same specialisation as post_rows. */
static RW_INLINE void water_rows_only(const rw_frame *r, rs_band *b, const refl_view *rv, const uint8_t *wcol,
                                   const uint8_t *wdep, int32_t wy0, int32_t wrows, const int32_t fmt,
                                   const int32_t depth, const int common)
{
    const size_t dbp = depth == RS_DEPTH16 ? 2u : 4u;
    const int32_t w = b->w;      /* (the pixel stores may alias b) */
    int32_t row;
    for (row = 0; row < b->rows; row++) {
        const int32_t y = b->y0 + row;
        uint8_t *crow = (uint8_t *)b->color + (size_t)row * b->stride;
        const uint8_t *drow = (const uint8_t *)b->depth + (size_t)row * (size_t)w * dbp, *wd = NULL;
        int32_t x0, xe;
        const uint8_t *wc = water_row(r, b, wcol, wdep, wy0, wrows, y, dbp, &wd, &x0, &xe);
        rw_rowk k;
        if (!wc) continue;
        row_k(r, rv, y, &k, fmt, depth);
        if (r->trow[y]) water_row_px(r, rv, &k, crow, drow, wc, wd, x0, xe, fmt, depth, common, 1);
        else water_row_px(r, rv, &k, crow, drow, wc, wd, x0, xe, fmt, depth, common, 0);
    }
}

/* The hook's pixels for one band (textured terrain: fog per pixel), specialised for each
 * format and depth (fmt, depth are constants at every call; always inlined: as a plain
 * inline function GCC kept one copy that tested them at every pixel). */
static RW_INLINE void post_rows(const rw_frame *r, rs_band *b, const refl_view *rv, const uint8_t *wcol,
                             const uint8_t *wdep, int32_t wy0, int32_t wrows, const int32_t fmt, const int32_t depth)
{
    const size_t dbp = depth == RS_DEPTH16 ? 2u : 4u;
    const int32_t dsh = depth == RS_DEPTH16 ? 14 : 0;
    int32_t row, x;
    for (row = 0; row < b->rows; row++) {
        const int32_t y = b->y0 + row;
        uint8_t *crow = (uint8_t *)b->color + (size_t)row * b->stride;
        const uint8_t *drow = (const uint8_t *)b->depth + (size_t)row * (size_t)b->w * dbp;
        int32_t x0 = 0, xe = 0;
        const uint8_t *wd = NULL, *wc = water_row(r, b, wcol, wdep, wy0, wrows, y, dbp, &wd, &x0, &xe);
        const uint32_t sky = r->sky[y];
        rw_walk wk;
        rw_rowk k;
        row_k(r, rv, y, &k, fmt, depth);
        rw_walk_start(&wk);
        for (x = 0; x < b->w; x++) {
            const uint32_t dt = get_depth(depth, drow, x);
            uint32_t rgb, d, fw;
            int changed = 0;
            if (dt >= r->dquiet && !wc) continue;   /* near terrain, no water in the row */
            if (dt == r->dfar) {                    /* sky */
                if (!r->p.sky_on) continue;
                rgb = sky;
                changed = 1;
                d = 0;
            } else {
                rgb = 0;
                d = dt << dsh;
                if (wc && x >= x0 && x < xe) {
                    const uint32_t id = get_id(fmt, wc, x), dw = get_depth(depth, wd, x);
                    int32_t lx, ly;
                    const int shows = id ? water_shows(r, &k, x, id, wc, dt, dw, dsh, fmt, r->trow[y], &wk, &lx, &ly)
                                         : RW_NOT;
                    if (shows == RW_LAND) rgb = land_rgb(r, &k, x, id, lx, ly);
                    else if (shows == RW_WATER) {
                        wk.q8 = r->p.waves_on ? wave_q8(r, dw << dsh) : 0;
                        rgb = water_px(r, rv, &k, x, get_rgb(fmt, crow, x), dt << dsh, dw << dsh, id, &wk, fmt,
                                       depth, 0);
                    }
                    if (shows != RW_NOT) {
                        d = dw << dsh;
                        changed = 1;
                    }
                }
                if ((fw = fog_weight(r->fog, (uint32_t)r->fog_sh, r->fog_d30, d)) != 0) {
                    if (!changed) rgb = get_rgb(fmt, crow, x);
                    rgb = mix_rgb(rgb, sky, fw);
                    changed = 1;
                }
            }
            if (changed) put_px(crow, x, y, rgb, fmt);
        }
    }
}

br_status rw_post(const void *user, rs_band *b, rs_band_stats *st)
{
    const rw_frame *r = (const rw_frame *)user;
    refl_view rv;
    const uint8_t *wcol = NULL, *wdep = NULL;
    int32_t wy0 = 0, wrows = 0;
#if defined(RS_ISA_DISPATCH) && RS_ISA_DISPATCH
    if (rs_isa() == RS_ISA_V3) return rw_post_v3(user, b, st);
#endif
    (void)st;
    memset(&rv, 0, sizeof rv);
    if (r->refl_pass >= 0 && r->refl_pass < RS_PIPE_MAX_PASSES && b->scratch[r->refl_pass] && r->refl) {
        const int32_t i = r->refl_pass;
        refl_rows(r, b->scratch_y0[i], b->scratch_y0[i] + b->scratch_rows[i], &rv.h0, &rv.h1);
        rv.col = (const uint8_t *)b->scratch[i];
        rv.dep = (const uint8_t *)b->scratch_depth[i];
        rv.rw = r->refl->w;
    }
    if (r->water_pass >= 0 && r->water_pass < RS_PIPE_MAX_PASSES && b->scratch[r->water_pass]) {
        const int32_t i = r->water_pass;
        wcol = (const uint8_t *)b->scratch[i];
        wdep = (const uint8_t *)b->scratch_depth[i];
        wy0 = b->scratch_y0[i];
        wrows = b->scratch_rows[i];
    }
    if (!r->pixel_fog) {
        /* the common case (waves, the fixed tint of detected water, Schlick's Fresnel,
         * the default half-resolution reflection) in the two pixel layouts of the
         * benchmarks and boards with its four tests settled at compile time: fewer
         * values live in the pixel loop */
        const int common = r->p.waves_on && r->p.tint_fixed && !r->p.fresnel_one && r->p.res_shift == 1;
        if (r->fmt == RS_FMT_RGB565) {
            if (r->depth == RS_DEPTH16) {
                if (common) water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH16, 1);
                else water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH16, 0);
            } else water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH32, 0);
        } else if (r->depth == RS_DEPTH16) water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH16, 0);
        else if (common) water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH32, 1);
        else water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH32, 0);
        return BR_OK;
    }
    if (r->fmt == RS_FMT_RGB565) {
        if (r->depth == RS_DEPTH16) post_rows(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH16);
        else post_rows(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH32);
    } else if (r->depth == RS_DEPTH16) post_rows(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH16);
    else post_rows(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH32);
    return BR_OK;
}
