/* raster/water_setup.c — the water frame's per-frame set-up (see water.h): the mirror's
 * view, the per-row and per-column tables, the fog table, the per-vertex fog.  Right
 * shifts of negative values are arithmetic (checked once in core/fx.h's users; gcc and
 * clang on every target we build). */
#include <string.h>
#include "core/fx.h"
#include "raster/water.h"
#include "raster/water_int.h"

/* ---------------------------------------------------------------- set-up */

br_status rw_mirror_vp(const cam_vp *vp, int32_t plane_z, int32_t res_shift, int32_t w, int32_t h,
                       cam_vp *out)
{
    int i;
    if (!vp || !out || res_shift < 0 || res_shift > 2 || (w >> res_shift) < 1 || (h >> res_shift) < 1
        || plane_z > CAM_COORD_MAX / 2 || plane_z < -(CAM_COORD_MAX / 2))
        return BR_E_ARG;
    *out = *vp;
    /* r (x, y, 2 H - z) + t = r' p + t' with r'[i][2] = -r[i][2], t' = t + 2 H r[i][2]:
     * |2 H r| < 2^30 2^30, the sum stays within cam_vp's bound */
    for (i = 0; i < 3; i++) {
        out->r[i][2] = -vp->r[i][2];
        out->t[i] = vp->t[i] + 2 * (int64_t)plane_z * vp->r[i][2];
    }
    out->f_q16 = vp->f_q16 >> res_shift;
    out->cx_q16 = (w >> res_shift) * (FX_Q16_ONE / 2);
    out->cy_q16 = (h >> res_shift) * (FX_Q16_ONE / 2);
    return BR_OK;
}

/* The waves (water.h): four travelling sines whose directions spread over 130 degrees
 * around a wind from the south-west, lengths 1, 0.62, 0.41 and 0.27 times wave_len,
 * periods as deep water's (T proportional to the square root of the length: 2.1 s for
 * the longest), slope amplitudes falling with the length and summing to 254 (so the sums
 * of four table entries stay within the two Q7 sines' +-254 that water_px's bounds
 * assume).  Two sines at right angles, as before, drew a regular lattice of bright
 * spots (an egg crate) over the whole lake; four of unrelated lengths do not repeat
 * within the view.  dir: unit vector (Q14) at 37, 112, -17 and 71 degrees from east;
 * len_q8: length / wave_len, Q8; kt: 2^32 / period in ms, rounded. */
static const struct { int32_t dir[2]; int32_t len_q8; uint32_t kt; int32_t amp; } wave_set[RW_WAVES] = {
    { { 13085, 9860 }, 256, 2045223u, 88 },        /* 2100 ms */
    { { -6138, 15191 }, 159, 2596715u, 70 },       /* 1654 ms */
    { { 15668, -4790 }, 105, 3193284u, 54 },       /* 1345 ms */
    { { 5334, 15491 }, 69, 3936725u, 42 },         /* 1091 ms */
};

/* Quotients of the per-frame set-up with no 64-bit divide where the target has none
 * (core/config.h BR_DIV64_NATIVE = 0, 32-bit boards: each int64 `/` would be a libgcc
 * call): core/fx.h's fx_udiv_wide with one fx_recip of d.  The quotients equal C's `/`
 * (BR_DIV64_NATIVE = 1 uses it), so the pixels do not depend on the build. */
typedef struct wdiv {
    uint64_t d;                 /* >= 1 */
    fx_recip rc;                /* of d when d < 2^32 (BR_DIV64_NATIVE = 0) */
} wdiv;

static void wdiv_make(wdiv *q, uint64_t d)
{
    q->d = d;
    memset(&q->rc, 0, sizeof q->rc);
#if !BR_DIV64_NATIVE
    if (d <= 0xffffffffu) q->rc = fx_recip_make((uint32_t)d);
#endif
}

static uint64_t wdiv_u(const wdiv *q, uint64_t n)    /* floor(n / d) */
{
#if BR_DIV64_NATIVE
    return n / q->d;
#else
    return fx_udiv_wide(n, q->d, q->rc);
#endif
}

static int64_t wdiv_s(const wdiv *q, int64_t n)      /* n / d truncated, as C's `/`; |n| < 2^63 */
{
    return n < 0 ? -(int64_t)wdiv_u(q, (uint64_t)-n) : (int64_t)wdiv_u(q, (uint64_t)n);
}

static uint64_t udiv64(uint64_t n, uint64_t d)       /* floor(n / d), d >= 1, one divisor once */
{
    wdiv q;
    wdiv_make(&q, d);
    return wdiv_u(&q, n);
}

static int64_t sdiv64(int64_t n, int64_t d)          /* n / d truncated, d != 0, |n|, |d| < 2^63 */
{
    wdiv q;
    wdiv_make(&q, (uint64_t)(d < 0 ? -d : d));
    return d < 0 ? -wdiv_s(&q, n) : wdiv_s(&q, n);
}

static int64_t sfloor64(int64_t n, int64_t d)        /* floor(n / d), d >= 1, |n| < 2^63 */
{
    return n >= 0 ? (int64_t)udiv64((uint64_t)n, (uint64_t)d) : -(int64_t)udiv64((uint64_t)(-n - 1), (uint64_t)d) - 1;
}

static void tables(rw_frame *r)
{
    /* R0 = ((1.33 - 1) / (1.33 + 1))^2 = 33^2 / 233^2, Q16 */
    const uint32_t r0 = (uint32_t)((33u * 33u * 65536u + 233u * 233u / 2) / (233u * 233u));
    uint32_t i, e = 65536u;
    for (i = 0; i <= RW_TAB; i++) {
        uint32_t c = fx_isqrt64((uint64_t)i << 22);        /* cos t, Q16 (i / 1024 = cos^2) */
        uint64_t m = 65536u - (c > 65536u ? 65536u : c), p = m;
        uint32_t f, s;
        int k;
        for (k = 1; k < 5; k++) p = (p * m) >> 16;          /* (1 - cos)^5, Q16 */
        f = r0 + (uint32_t)(((65536u - r0) * p) >> 16);
        r->fres[i] = (uint8_t)((f + 128u) >> 8 > 255u ? 255u : (f + 128u) >> 8);
        s = (c * 3u) >> 1;                                  /* 1.5 sin of the elevation, Q16 */
        r->skyw[i] = (uint8_t)((s + 128u) >> 8 > 255u ? 255u : (s + 128u) >> 8);
    }
    for (i = 0; i < 256; i++) {     /* e = exp(-i / 32), Q16: exp(-1/32) = 63520 / 65536 */
        r->tint[i] = (uint8_t)(255u - (e >> 8 > 255u ? 255u : e >> 8));
        e = (e * 63520u + 32768u) >> 16;
    }
    for (i = 0; i < 256; i++) {
        fx_q30 s, c;
        int k;
        fx_sincos((fx_angle)(i << 24), &s, &c);
        for (k = 0; k < RW_WAVES; k++)
            r->wsine[k][i] = (int8_t)((s * (int64_t)wave_set[k].amp + ((int64_t)1 << 29)) >> 30);
    }
}

/* Rows lo .. hi (sub-pixels, near: a vertex needs the clipper) to frame rows. */
static void rows_of(const rw_frame *r, int32_t lo, int32_t hi, int near, int32_t *rlo, int32_t *rhi)
{
    if (near) { *rlo = 0; *rhi = r->h - 1; return; }
    if (lo > hi) { *rlo = 1; *rhi = 0; return; }
    *rlo = lo < 0 ? 0 : lo >> RS_SUBPIX_BITS;
    *rhi = hi >= r->h << RS_SUBPIX_BITS ? r->h - 1 : hi >> RS_SUBPIX_BITS;
}

/* Rows where water may show: the water frame's vertices' rows (everything when one
 * needs the clipper); and those of refl_body's vertices, the vertices whose colour is
 * its id (RW_ID_RGB): a water triangle's three vertices carry its body's id (the pass
 * interpolates them into its pixels' ids), so refl_body's pixels lie in those rows.
 * *top: the highest water vertex's z (for water_horizon). */
static void water_rows(rw_frame *r, int32_t *top)
{
    const rs_frame *wf = r->water;
    const uint32_t rid = RW_ID_RGB(r->p.refl_body);
    uint32_t i;
    int32_t lo = INT32_MAX, hi = INT32_MIN, blo = INT32_MAX, bhi = INT32_MIN;
    int near = 0, bnear = 0;
    r->wlo = r->rlo = 1; r->whi = r->rhi = 0;
    *top = INT32_MIN;
    if (!wf || !r->p.water_on || wf->nv == 0 || wf->nprims == 0) return;
    for (i = 0; i < wf->nv; i++) {
        const rs_cvert *v = &wf->cache[i];
        const int body = (v->c & RW_ID_MASK) == rid;
        if (wf->v[i].p[2] > *top) *top = wf->v[i].p[2];
        if (v->c & ((uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD) << 24)) {
            near = 1;
            bnear |= body;
            continue;
        }
        if (v->y < lo) lo = v->y;
        if (v->y > hi) hi = v->y;
        if (body && v->y < blo) blo = v->y;
        if (body && v->y > bhi) bhi = v->y;
    }
    rows_of(r, lo, hi, near, &r->wlo, &r->whi);
    rows_of(r, blo, bhi, bnear, &r->rlo, &r->rhi);
}

/* trow: the rows each tested water triangle (RW_TESTED_RGB) may cover, from its vertices'
 * rows (every row when one needs the clipper); a list's triangles, or every row when a
 * strip holds a tested vertex.  The hook tests a pixel's flag only in those rows. */
static void tested_rows(rw_frame *r)
{
    const rs_frame *wf = r->water;
    int32_t p;
    memset(r->trow, 0, (size_t)r->h);
    if (!wf || !r->p.water_on || wf->nv == 0) return;
    for (p = 0; p < wf->nprims; p++) {
        const rs_prim *pr = &wf->prims[p];
        uint32_t t;
        if (pr->kind != RS_LIST) {
            for (t = 0; t < pr->n; t++)
                if (wf->cache[pr->idx[t]].c & RW_TESTED_RGB) { memset(r->trow, 1, (size_t)r->h); return; }
            continue;
        }
        for (t = 0; t + 2 < pr->n; t += 3) {
            const rs_cvert *a = &wf->cache[pr->idx[t]], *b = &wf->cache[pr->idx[t + 1]], *c = &wf->cache[pr->idx[t + 2]];
            const uint32_t out = (a->c | b->c | c->c) >> 24;
            int32_t lo, hi, ylo, yhi;
            if (!(a->c & RW_TESTED_RGB) || ((a->c & b->c & c->c) >> 24 & 0x3fu)) continue;   /* untested, off screen */
            ylo = a->y < b->y ? a->y : b->y;
            ylo = c->y < ylo ? c->y : ylo;
            yhi = a->y > b->y ? a->y : b->y;
            yhi = c->y > yhi ? c->y : yhi;
            rows_of(r, ylo, yhi, (out & (RS_OUT_NEAR | RS_OUT_GUARD)) != 0, &lo, &hi);
            if (lo <= hi) memset(r->trow + lo, 1, (size_t)(hi - lo + 1));
        }
    }
}

/* The bound gxmax (gymax) of grid positions for n samples of step sx, inv = ceil(2^32 /
 * sx): n sx, or less where the rounded-up reciprocal would index sample n below it.
 * Every g < gxmax then has (g inv) >> 32 < n, as g inv < n 2^32 for g < ceil(n 2^32 /
 * inv); a g between the two bounds indexed sample n or more, off the grid either way. */
static uint64_t grid_max(int32_t n, int64_t sx, uint64_t inv)
{
    const uint64_t whole = (uint64_t)((int64_t)n * sx);
    const uint64_t lim = udiv64(((uint64_t)n << 32) + inv - 1, inv);
    return lim < whole ? lim : whole;
}

/* Pixels beyond a water triangle's vertices' columns that the pass's seed covers: the
 * rasteriser reads and writes depth only at pixel centres inside a triangle, so within
 * the columns of its vertices; the margin keeps any wider access of the drawing code
 * and the seed's 8-pixel vector steps inside seeded pixels. */
#define RW_SEED_REACH 16

/* wx0, wx1 of the row groups of rows wlo .. whi (RW_COL_ROWS rows a group, groups touched
 * by those rows): the columns of the water triangles that may cover a row of the group
 * (their vertices' rows and columns, from the pixel that holds the leftmost vertex to the
 * one that holds the rightmost, RW_SEED_REACH wider), every column when a triangle needs
 * the clipper (its vertices' positions are not valid). */
static void water_cols(rw_frame *r)
{
    const rs_frame *wf = r->water;
    const int32_t g0 = r->wlo / RW_COL_ROWS, g1 = r->whi / RW_COL_ROWS;
    int32_t p, g;
    if (r->wlo > r->whi) return;
    for (g = g0; g <= g1; g++) { r->wx0[g] = (int16_t)r->w; r->wx1[g] = -1; }
    for (p = 0; p < wf->nprims; p++) {
        const rs_prim *pr = &wf->prims[p];
        const uint32_t step = pr->kind == RS_LIST ? 3u : 1u;
        uint32_t t;
        for (t = 0; t + 2 < pr->n; t += step) {
            const rs_cvert *a = &wf->cache[pr->idx[t]], *b = &wf->cache[pr->idx[t + 1]], *c = &wf->cache[pr->idx[t + 2]];
            int32_t ylo, yhi, xlo, xhi, lo, hi;
            if ((a->c & b->c & c->c) >> 24 & 0x3fu) continue;      /* off screen: not drawn */
            if ((a->c | b->c | c->c) >> 24 & (RS_OUT_NEAR | RS_OUT_GUARD)) {
                for (g = g0; g <= g1; g++) { r->wx0[g] = 0; r->wx1[g] = (int16_t)(r->w - 1); }
                return;
            }
            ylo = a->y < b->y ? a->y : b->y;
            ylo = c->y < ylo ? c->y : ylo;
            yhi = a->y > b->y ? a->y : b->y;
            yhi = c->y > yhi ? c->y : yhi;
            rows_of(r, ylo, yhi, 0, &lo, &hi);
            if (lo < r->wlo) lo = r->wlo;
            if (hi > r->whi) hi = r->whi;
            if (lo > hi) continue;
            xlo = a->x < b->x ? a->x : b->x;
            xlo = c->x < xlo ? c->x : xlo;
            xhi = a->x > b->x ? a->x : b->x;
            xhi = c->x > xhi ? c->x : xhi;
            /* (inside the guard band: |x| < 2^22 sub-pixels, no overflow) */
            xlo = ((xlo >> RS_SUBPIX_BITS) - RW_SEED_REACH) & ~7;         /* whole vector steps */
            xhi = ((xhi >> RS_SUBPIX_BITS) + RW_SEED_REACH) | 7;
            if (xlo < 0) xlo = 0;
            if (xhi > r->w - 1) xhi = r->w - 1;
            for (g = lo / RW_COL_ROWS; g <= hi / RW_COL_ROWS; g++) {
                if (xlo < r->wx0[g]) r->wx0[g] = (int16_t)xlo;
                if (xhi > r->wx1[g]) r->wx1[g] = (int16_t)xhi;
            }
        }
    }
}

/* Water below the eye shows only below the horizon: a point of a water triangle lies at
 * most `top` (the highest water vertex) high, so with top < eye z its view ray goes down,
 * and with no roll (right z = 0: cam_look_at's up hint is +z) the ray of row y's pixel
 * centres goes down exactly when s(y) = up_z (h - 2 y - 1) 2^16 + fwd_z 2 f_q16 < 0
 * (twice f times the ray's z, Q30 + Q16; s falls with y when up_z > 0).  Both terms
 * are shifted right by sh so that f_q16 >> sh < 2^30: |s| < 2^30 2^13 2^16 + 2^30 2^31
 * < 2^63, and the shift moves the boundary by under 2^-29 of f, far below a row.  A
 * drawn pixel's centre lies within the subpixel snap and the transform's rounding (well
 * under a row) of such a point's projection: two rows of margin above the first row
 * whose rays go down.  Raises wlo, never lowers it. */
static void water_horizon(rw_frame *r, const cam *c, int64_t f16, int32_t top)
{
    const rs_frame *wf = r->water;
    int32_t y, sh = 0;
    while (sh < 16 && (f16 >> sh) >= ((int64_t)1 << 30)) sh++;
    if (r->wlo > r->whi || !wf || c->right[2] != 0 || c->up[2] <= 0 || f16 <= 0 || (f16 >> sh) >= ((int64_t)1 << 30))
        return;
    if (r->eye[2] <= top) return;
    for (y = r->wlo; y <= r->whi; y++)
        if ((int64_t)c->up[2] * (r->h - 2 * y - 1) * (65536 >> sh) + (int64_t)c->fwd[2] * 2 * (f16 >> sh) < 0) break;
    if (y - 2 > r->wlo) r->wlo = y - 2;
}

/* Fog table: weight by depth d >> fog_sh (d in 30-bit units, D znear / zc).  Entry i stands
 * for d_i = i 2^sh + 2^(sh-1), zc_i = floor(K / d_i), and gets (t_i^2 + 128) >> 8 with
 * t_i = 256 where zc_i >= ze, floor(256 (zc_i - zs) / span) between (span = ze - zs), 0 at
 * or below zs.  So t_i >= t (1 <= t <= 256) exactly when 256 (zc_i - zs) >= t span, that
 * is zc_i >= Z_t = zs + ceil(t span / 256) (zc_i is an integer; Z_256 = ze), that is
 * d_i Z_t <= K (fx_mul_ge).  d_i rises with i and Z_t with t, so one walk down the t, comparing
 * products, gives each entry between K / ze and K / zs its t_i with no quotient. */
static void fog_table(rw_frame *r, int64_t K)
{
    const int64_t zs = r->p.fog_start, ze = r->p.fog_end, span = ze - zs;
    const int64_t dstart = (int64_t)udiv64((uint64_t)K, (uint64_t)zs);    /* beyond it: zc < zs */
    const int64_t dend = (int64_t)udiv64((uint64_t)K, (uint64_t)ze);      /* up to it: zc >= ze */
    int64_t t = 256, z = ze;
    int32_t sh = 0, i;
    while ((dstart >> sh) > RW_TAB) sh++;
    r->fog_sh = sh;
    for (i = 0; i <= RW_TAB; i++) {
        const int64_t d = ((int64_t)i << sh) + (((int64_t)1 << sh) >> 1);
        if (d > dstart) break;
        if (d > dend) {
            /* (t reaches 0 at the latest where d Z_1 > K; 256 span < 2^63 for any range
             * in world coordinates) */
            while (t > 0 && !fx_mul_ge((uint64_t)K, (uint64_t)d, (uint64_t)z))
                if (--t > 0) z = zs + ((t * span + 255) >> 8);
        }
        r->fog[i] = (uint8_t)((t * t + 128) >> 8 > 255 ? 255 : (t * t + 128) >> 8);
    }
    for (; i <= RW_TAB; i++) r->fog[i] = 0;
}

void rw_tables(rw_frame *r)
{
    if (r && !r->tables_ready) {    /* they depend on no frame: once per rw_frame */
        tables(r);
        r->tables_ready = 1;
    }
}

br_status rw_setup(rw_frame *r, const rw_params *p, const cam *c, const rs_frame *terrain,
                   const rs_frame *water, const rs_frame *refl)
{
    const cam_vp *vp;
    int64_t K, f16;
    int32_t x, y, k;
    wdiv df, dtint;
    int dither;
    if (!r || !p || !c || !terrain || terrain->w != c->w || terrain->h != c->h
        || (terrain->depth != RS_DEPTH32 && terrain->depth != RS_DEPTH16)    /* water reads it */
        || p->res_shift < 0 || p->res_shift > 2
        || (p->fog_on && !(p->fog_start > 0 && p->fog_end > p->fog_start))
        || (p->water_on && (p->tint_len <= 0 || p->wave_len <= 0 || p->wave_amp < 0))
        || p->tint_fixed < 0 || p->tint_fixed > 256
        || (water && (water->w != terrain->w || water->h != terrain->h))
        || (refl && (refl->w != terrain->w >> p->res_shift || refl->h != terrain->h >> p->res_shift)))
        return BR_E_ARG;
    vp = &terrain->vp;
    r->p = *p;
    if (!r->p.water_rgb) r->p.water_rgb = 0x1c4660u;
    if (!r->p.sky_horizon) r->p.sky_horizon = 0xc8dcf0u;
    if (!r->p.sky_zenith) r->p.sky_zenith = 0x5a8cd2u;
    r->terrain = terrain; r->water = water; r->refl = refl;
    r->refl_pass = r->water_pass = -1;
    r->w = terrain->w; r->h = terrain->h; r->fmt = terrain->fmt; r->depth = terrain->depth;
    K = (int64_t)RS_DEPTH_ONE * vp->znear;
    r->dfar = (uint32_t)udiv64((uint64_t)K, (uint64_t)vp->zfar);      /* zfar > znear > 0 */
    r->rdfar = r->dfar;
    if (r->depth == RS_DEPTH16) { r->dfar >>= 14; r->rdfar >>= 14; }
    for (k = 0; k < 3; k++) r->eye[k] = c->eye[k];
    rw_tables(r);
    if (r->skyrefl_of[0] != r->p.sky_horizon || r->skyrefl_of[1] != r->p.sky_zenith) {   /* never 0 */
        for (k = 0; k <= RW_TAB; k++) r->skyrefl[k] = mix_rgb(r->p.sky_horizon, r->p.sky_zenith, r->skyw[k]);
        r->skyrefl_of[0] = r->p.sky_horizon; r->skyrefl_of[1] = r->p.sky_zenith;
    }
    {
        const uint32_t t = (uint32_t)r->p.tint_fixed;     /* 0 .. 256 (checked above) */
        r->tint_u = 256u - t;
        r->tint_rb = (r->p.water_rgb & 0xff00ffu) * t + 0x800080u;
        r->tint_g = (r->p.water_rgb & 0xff00u) * t + 0x8000u;
    }
    dither = terrain->fmt == RS_FMT_RGB565 && p->sky_on;    /* the sky's clear pattern */
    f16 = vp->f_q16;
    wdiv_make(&df, (uint64_t)f16);
    if (p->water_on) wdiv_make(&dtint, (uint64_t)p->tint_len);
    {   /* the rows where water may show (wlo .. whi): the per-row water values below are
         * read only there (row_k, for the water pass's pixels) */
        int32_t top;        /* the highest water vertex */
        water_rows(r, &top);
        water_horizon(r, c, f16, top);
    }
    if (r->abq_of[0] != f16 || r->abq_of[1] != r->w || r->abq_of[2] != r->h) {
        /* the rays' screen terms depend on the focal length and the size alone */
        r->abq_of[0] = f16; r->abq_of[1] = r->w; r->abq_of[2] = r->h;      /* (f16 > 0) */
        for (x = 0; x < r->w; x++) r->aq[x] = (int32_t)wdiv_s(&df, (int64_t)(2 * x + 1 - r->w) * ((int64_t)1 << 27));
        for (y = 0; y < r->h; y++) r->bq[y] = (int32_t)wdiv_s(&df, (int64_t)(r->h - 2 * y - 1) * ((int64_t)1 << 27));
    }
    for (y = 0; y < r->h; y++) {
        int64_t b = r->bq[y], rz, len2;
        uint32_t s2;
        rz = ((int64_t)c->up[2] * b + (int64_t)c->fwd[2] * Q12) >> 30;
        r->rz[y] = (int32_t)rz;
        len2 = b * b + (int64_t)Q12 * Q12;
        /* the zenith weight 1.5 sin(elevation) of the row's centre ray, Q8 */
        s2 = rz > 0 ? (uint32_t)((fx_isqrt64(udiv64((uint64_t)((rz * rz) << 24), (uint64_t)len2)) * 3u + 16u) >> 5) : 0;
        r->sky[y] = p->sky_on ? mix_rgb(r->p.sky_horizon, r->p.sky_zenith, s2 > 256u ? 256u : s2)
                              : terrain->clear_rgb;
        if (dither) for (k = 0; k < 4; k++) r->clear4[4 * y + k] = dither888(r->sky[y], k, y);
        else for (k = 0; k < 4; k++) r->clear4[4 * y + k] = r->sky[y];
        /* the plane point of the row's rays: E + lam ray, lam = (H - ez) / ray_z */
        r->wrel[y][0] = r->wrel[y][1] = r->wstep[y][0] = r->wstep[y][1] = 0;
        r->wsig[y][0] = r->wsig[y][1] = 0;
        r->tkr[y] = -1;
        if (rz < 0 && r->eye[2] > p->plane_z && y >= r->wlo && y <= r->whi) {
            int64_t lam = sdiv64(((int64_t)p->plane_z - r->eye[2]) * Q12, rz);    /* world units per unit ray */
            if (lam > ((int64_t)1 << 31)) lam = (int64_t)1 << 31;
            for (k = 0; k < 2; k++) {
                int64_t ray = (((int64_t)c->up[k] * b) >> 30) + (c->fwd[k] >> 18);   /* Q12 */
                r->wrel[y][k] = (lam * ray) >> 12;
                r->wstep[y][k] = (lam * c->right[k]) >> 30;
                /* u = 2x + 1 - w moves a = u 2^27 / f_q16 (Q12), the point a wstep >> 12:
                 * wstep 2^15 / f_q16 world units, Q16 (|wstep| <= 2^31: below 2^63) */
                r->wsig[y][k] = wdiv_s(&df, r->wstep[y][k] * ((int64_t)1 << 31));
            }
            /* the ray's forward component is 1: lam is the plane point's zc */
            r->tkr[y] = p->water_on ? wdiv_s(&dtint, lam << 21) : -1;
            if (r->tkr[y] > ((int64_t)1 << 40)) r->tkr[y] = (int64_t)1 << 40;
        }
    }
    for (k = 0; k < RW_WAVES; k++) {
        int64_t len = (p->wave_len * wave_set[k].len_q8) >> 8;
        if (len < 1) len = 1;
        /* 2^32 turns per world unit: |dir 2^18| <= 2^32, so |kx| <= 2^32 */
        r->kx[k] = sdiv64((int64_t)wave_set[k].dir[0] * ((int64_t)1 << 18), len);
        r->ky[k] = sdiv64((int64_t)wave_set[k].dir[1] * ((int64_t)1 << 18), len);
        r->kt[k] = wave_set[k].kt;
    }
    {   /* displacement Q8 px = d amp_m >> 32 = A f 2^8 / zc */
        int64_t num = p->wave_amp * (f16 >> 4);
        int64_t m = K > 0 ? sfloor64(num << 12, K) << 16 : 0;
        r->amp_m = m > ((int64_t)1 << 33) ? (int64_t)1 << 33 : m;
        /* waves fade beyond 8 lengths of the second wave (the shorter ones alias beyond) */
        const uint64_t fd = udiv64((uint64_t)K << 8, 8 * (uint64_t)(p->wave_len > 0 ? p->wave_len : 1)
                                                       * (uint64_t)wave_set[1].len_q8);
        r->wave_fade_d = fd > 0xffffffffu ? 0xffffffffu : (uint32_t)fd;
        r->inv_fade = udiv64((uint64_t)1 << 32, (r->wave_fade_d >> 14) | 1u);
    }
    for (k = 0; k <= RW_MAX_ID; k++) {     /* the bodies' plane points from the reflected plane's */
        const int64_t e0 = r->eye[2] - p->plane_z, eb = r->eye[2] - p->body_z[k];
        int64_t q = e0 > 0 && eb > 0 ? (int64_t)udiv64((uint64_t)eb << 16, (uint64_t)e0) : 0;
        r->bratio[k] = (int32_t)(q > ((int64_t)1 << 20) ? 0 : q);
        r->ebody[k] = eb;
        /* the shore bound without a world term: dt - dw <= shore_c / E (30-bit depths);
         * 0xffffffff: no bound (every nearer terrain pixel is tested) */
        r->shore_dd[k] = 0xffffffffu;
        if (p->shore_bound && p->shore_w == 0 && eb > 0) {
            int64_t qd = sfloor64(p->shore_c, eb);
            r->shore_dd[k] = qd >= 0xffffffffLL ? 0xffffffffu : (uint32_t)qd;
        }
        r->shore_tdd[k] = r->bratio[k] ? r->shore_dd[k] : 0;
    }
    r->inv_sx = p->grid_sx > 0 ? udiv64(((uint64_t)1 << 32) + (uint64_t)p->grid_sx - 1, (uint64_t)p->grid_sx) : 0;
    r->inv_sy = p->grid_sy > 0 ? udiv64(((uint64_t)1 << 32) + (uint64_t)p->grid_sy - 1, (uint64_t)p->grid_sy) : 0;
    r->gx0 = r->eye[0] - p->grid_ox + p->grid_sx / 2;
    r->gy0 = p->grid_oy - r->eye[1] + p->grid_sy / 2;
    r->gxmax = p->grid_sx > 0 && p->wet_w > 0 ? grid_max(p->wet_w, p->grid_sx, r->inv_sx) : 0;
    r->gymax = p->grid_sy > 0 && p->wet_h > 0 ? grid_max(p->wet_h, p->grid_sy, r->inv_sy) : 0;
    r->half_sx = p->grid_sx / 2;
    r->half_sy = p->grid_sy / 2;
    /* the texture's sample (w - 1, h - 1) at texel (tex_w, tex_h) (rt_scene): a texel is
     * (w - 1) sx / tex_w world units wide */
    r->inv_tu = r->inv_tv = 0;
    if (p->land && p->land->tex_w > 0 && p->land_tex && p->wet_w > 1 && p->wet_h > 1 && p->grid_sx > 0
        && p->grid_sy > 0) {
        r->inv_tu = udiv64((uint64_t)p->land->tex_w << 32, (uint64_t)(p->wet_w - 1) * (uint64_t)p->grid_sx);
        r->inv_tv = udiv64((uint64_t)p->land->tex_h << 32, (uint64_t)(p->wet_h - 1) * (uint64_t)p->grid_sy);
    }
    r->idx32 = r->gxmax <= ((uint64_t)1 << 32) && r->gymax <= ((uint64_t)1 << 32) && r->inv_sx <= 0xffffffffu
               && r->inv_sy <= 0xffffffffu;
    if (p->fog_on) fog_table(r, K);
    {   /* dquiet: terrain pixels at least this near (buffer units) get no fog */
        uint64_t d30 = 0;
        int32_t i;
        if (p->fog_on)
            for (i = RW_TAB; i >= 0; i--)
                if (r->fog[i]) { d30 = (uint64_t)(i + 1) << r->fog_sh; break; }
        r->fog_d30 = d30 > 0xffffffffu ? 0xffffffffu : (uint32_t)d30;    /* (d < 2^30 always) */
        if (r->depth == RS_DEPTH16) d30 = (d30 + (1u << 14) - 1) >> 14;
        r->dquiet = d30 > r->dfar ? (d30 > 0xffffffffu ? 0xffffffffu : (uint32_t)d30) : r->dfar + 1;
    }
    r->pixel_fog = terrain->tex != NULL;
    {   /* the largest shore bound of the bodies on screen, in the depth buffer's units
         * (rounded up); no bound: every water pixel behind the terrain is drawn */
        uint64_t m = 0;
        for (k = 1; k <= RW_MAX_ID; k++)
            if (((p->seen_mask >> k) & 1u) && r->shore_dd[k] > m) m = r->shore_dd[k];
        if (!p->shore_bound || p->shore_w || !p->seen_mask) m = 0xffffffffu;
        if (r->depth == RS_DEPTH16) m = (m + (1u << 14) - 1) >> 14;
        r->water_bias = m > 0x3fffffffu ? 0x3fffffffu : (uint32_t)m;
    }
    tested_rows(r);
    water_cols(r);
    return BR_OK;
}

void rw_fog_vertices(rw_frame *r, rs_frame *f)
{
    uint32_t i;
    if (!r || !f || !f->cache) return;
    f->clear_rows = r->clear4;
    if (!r->p.fog_on || r->pixel_fog) return;
    {   /* the frame's values in locals: rs_cvert_recolour's stores could alias them */
        rs_cvert *const cache = f->cache;
        const uint8_t *const fog = r->fog;
        const uint32_t *const sky = r->sky;
        const uint32_t nv = f->nv, sh = (uint32_t)r->fog_sh, d30 = r->fog_d30;
        const int32_t h = r->h;
        for (i = 0; i < nv; i++) {
            rs_cvert *o = &cache[i];
            const uint32_t oc = o->c >> 24;
            uint32_t fw;
            int32_t y;
            if ((oc & (RS_OUT_NEAR | RS_OUT_GUARD)) || (fw = fog_weight(fog, sh, d30, o->d)) == 0) continue;
            y = o->y >> RS_SUBPIX_BITS;
            y = y < 0 ? 0 : y >= h ? h - 1 : y;
            rs_cvert_recolour(o, mix_rgb(o->c & 0xffffffu, sky[y], fw));
        }
    }
}
