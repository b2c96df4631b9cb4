/* raster/water.c — reflection pass, water pass, and the post hook that composites water,
 * sky and fog (see water.h).  Right shifts of negative values are arithmetic (checked
 * once in core/fx.h's users; gcc and clang on every target we build). */
#include <string.h>
#include "core/fx.h"
#include "raster/water.h"

#define Q12 4096
#if defined(__GNUC__)
#define RW_INLINE inline __attribute__((always_inline))   /* inner loops' helpers */
#else
#define RW_INLINE inline
#endif

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

static uint32_t mix_rgb(uint32_t a, uint32_t b, uint32_t t)    /* t Q8: a (0) .. b (256) */
{
    /* red and blue in one word, green in another: each field's sum is below 2^16 */
    const uint32_t u = 256u - t;
    const uint32_t rb = ((a & 0xff00ffu) * u + (b & 0xff00ffu) * t + 0x800080u) >> 8;
    const uint32_t g = ((a & 0xff00u) * u + (b & 0xff00u) * t + 0x8000u) >> 8;
    return (rb & 0xff00ffu) | (g & 0xff00u);
}

/* mix_rgb(a, b, t) with b and t fixed: u = 256 - t, brb = (b & 0xff00ff) t + 0x800080,
 * bg = (b & 0xff00) t + 0x8000 (the same sums, so the same value). */
static uint32_t mix_pre(uint32_t a, uint32_t u, uint32_t brb, uint32_t bg)
{
    const uint32_t rb = ((a & 0xff00ffu) * u + brb) >> 8, g = ((a & 0xff00u) * u + bg) >> 8;
    return (rb & 0xff00ffu) | (g & 0xff00u);
}

/* Quotients of the per-frame set-up with no 64-bit divide where the target has none
 * (core/config.h BR_DIV64_NATIVE = 0, 32-bit boards: each int64 `/` would be a libgcc
 * call): a divisor below 2^32 divides the high word by a 32-bit divide and the rest,
 * (nh mod d) 2^32 + nl < d 2^32, through one fx_recip of d (exact: fx_udiv_r's bound);
 * a divisor of 2^32 or more leaves a quotient below 2^32, by fx_udiv_bits' 32
 * compare-and-subtract steps.  The quotients equal C's `/` (BR_DIV64_NATIVE = 1 uses
 * it), so the pixels do not depend on the build. */
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
    const uint32_t d = (uint32_t)q->d, nh = (uint32_t)(n >> 32);
    uint32_t qh;
    if (q->d > 0xffffffffu) return fx_udiv_bits(n, q->d, 32);
    qh = nh / d;
    return ((uint64_t)qh << 32) | fx_udiv_r(((uint64_t)(nh - qh * d) << 32) | (uint32_t)n, &q->rc);
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

/* 4x4 ordered dither (Bayer), 0 .. 15, by screen position. */
static const uint8_t bayer4[4][4] = { { 0, 8, 2, 10 }, { 12, 4, 14, 6 }, { 3, 11, 1, 9 }, { 15, 7, 13, 5 } };

static uint16_t pack565_dither(uint32_t rgb, int32_t x, int32_t y)
{
    const uint32_t d = bayer4[y & 3][x & 3];
    uint32_t rr = (((rgb >> 16) & 255u) + (d >> 1)) >> 3, g = (((rgb >> 8) & 255u) + (d >> 2)) >> 2,
             bb = ((rgb & 255u) + (d >> 1)) >> 3;
    if (rr > 31u) rr = 31u;
    if (g > 63u) g = 63u;
    if (bb > 31u) bb = 31u;
    return (uint16_t)((rr << 11) | (g << 5) | bb);
}

/* The 888 colour whose 5/6/5 truncation is rgb's dithered value at (x, y). */
static uint32_t dither888(uint32_t rgb, int32_t x, int32_t y)
{
    const uint32_t v = pack565_dither(rgb, x, y), rr = v >> 11, g = (v >> 5) & 63u, bb = v & 31u;
    return ((rr << 3 | rr >> 2) << 16) | ((g << 2 | g >> 4) << 8) | (bb << 3 | bb >> 2);
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
        fx_sincos((fx_angle)(i << 24), &s, &c);
        r->sine[i] = (int8_t)((s * (int64_t)127 + ((int64_t)1 << 29)) >> 30);
    }
}

/* Rows where water may show: the water frame's vertices' rows (everything when one
 * needs the clipper). */
static void water_rows(rw_frame *r)
{
    const rs_frame *wf = r->water;
    uint32_t i;
    int32_t lo = INT32_MAX, hi = INT32_MIN;
    r->wlo = 1; r->whi = 0;
    if (!wf || !r->p.water_on || wf->nv == 0 || wf->nprims == 0) return;
    for (i = 0; i < wf->nv; i++) {
        const rs_cvert *v = &wf->cache[i];
        if (v->c & ((uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD) << 24)) { r->wlo = 0; r->whi = r->h - 1; return; }
        if (v->y < lo) lo = v->y;
        if (v->y > hi) hi = v->y;
    }
    lo = lo < 0 ? 0 : lo >> RS_SUBPIX_BITS;
    hi = hi >= r->h << RS_SUBPIX_BITS ? r->h - 1 : hi >> RS_SUBPIX_BITS;
    r->wlo = lo; r->whi = hi;
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
static void water_horizon(rw_frame *r, const cam *c, int64_t f16)
{
    const rs_frame *wf = r->water;
    int32_t top = INT32_MIN, y, sh = 0;
    uint32_t i;
    while (sh < 16 && (f16 >> sh) >= ((int64_t)1 << 30)) sh++;
    if (r->wlo > r->whi || !wf || c->right[2] != 0 || c->up[2] <= 0 || f16 <= 0 || (f16 >> sh) >= ((int64_t)1 << 30))
        return;
    for (i = 0; i < wf->nv; i++)
        if (wf->v[i].p[2] > top) top = wf->v[i].p[2];
    if (r->eye[2] <= top) return;
    for (y = r->wlo; y <= r->whi; y++)
        if ((int64_t)c->up[2] * (r->h - 2 * y - 1) * (65536 >> sh) + (int64_t)c->fwd[2] * 2 * (f16 >> sh) < 0) break;
    if (y - 2 > r->wlo) r->wlo = y - 2;
}

/* Fog table: weight by depth d >> fog_sh (d in 30-bit units, D znear / zc). */
static void fog_table(rw_frame *r, int64_t K)
{
    const int64_t zs = r->p.fog_start, ze = r->p.fog_end;
    int64_t dstart = (int64_t)udiv64((uint64_t)K, (uint64_t)zs);
    wdiv span;
    int32_t sh = 0, i;
    while ((dstart >> sh) > RW_TAB) sh++;
    r->fog_sh = sh;
    wdiv_make(&span, (uint64_t)(ze - zs));
    for (i = 0; i <= RW_TAB; i++) {
        int64_t d = ((int64_t)i << sh) + (((int64_t)1 << sh) >> 1), zc, t;
        if (d > dstart) break;      /* d >= K / zs + 1 > K / zs: zc < zs, no fog from here on */
        zc = d > 0 ? (int64_t)udiv64((uint64_t)K, (uint64_t)d) : ze;
        t = zc <= zs ? 0 : zc >= ze ? 256 : (int64_t)wdiv_u(&span, (uint64_t)(zc - zs) << 8);
        r->fog[i] = (uint8_t)((t * t + 128) >> 8 > 255 ? 255 : (t * t + 128) >> 8);
    }
    for (; i <= RW_TAB; i++) r->fog[i] = 0;
}

br_status rw_setup(rw_frame *r, const rw_params *p, const cam *c, const rs_frame *terrain,
                   const rs_frame *water, const rs_frame *refl)
{
    static const int32_t dir[2][2] = { { 13107, 9830 }, { -6226, 15073 } };   /* Q14 unit vectors */
    const cam_vp *vp;
    int64_t K, f16;
    int32_t x, y, k;
    wdiv df, dtint;
    if (!r || !p || !c || !terrain || terrain->w != c->w || terrain->h != c->h
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
    if (!r->tables_ready) {     /* they depend on no frame: once per rw_frame */
        tables(r);
        r->tables_ready = 1;
    }
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
    f16 = vp->f_q16;
    wdiv_make(&df, (uint64_t)f16);
    if (p->water_on) wdiv_make(&dtint, (uint64_t)p->tint_len);
    for (x = 0; x < r->w; x++) r->aq[x] = (int32_t)wdiv_s(&df, (int64_t)(2 * x + 1 - r->w) * ((int64_t)1 << 27));
    for (y = 0; y < r->h; y++) {
        int64_t b = wdiv_s(&df, (int64_t)(r->h - 2 * y - 1) * ((int64_t)1 << 27)), rz, len2;
        uint32_t s2;
        r->bq[y] = (int32_t)b;
        rz = ((int64_t)c->up[2] * b + (int64_t)c->fwd[2] * Q12) >> 30;
        r->rz[y] = (int32_t)rz;
        len2 = b * b + (int64_t)Q12 * Q12;
        /* the zenith weight 1.5 sin(elevation) of the row's centre ray, Q8 */
        s2 = rz > 0 ? (uint32_t)((fx_isqrt64(udiv64((uint64_t)((rz * rz) << 24), (uint64_t)len2)) * 3u + 16u) >> 5) : 0;
        r->sky[y] = p->sky_on ? mix_rgb(r->p.sky_horizon, r->p.sky_zenith, s2 > 256u ? 256u : s2)
                              : terrain->clear_rgb;
        for (k = 0; k < 4; k++)
            r->clear4[4 * y + k] = terrain->fmt == RS_FMT_RGB565 && p->sky_on ? dither888(r->sky[y], k, y) : r->sky[y];
        /* the plane point of the row's rays: E + lam ray, lam = (H - ez) / ray_z */
        r->wrel[y][0] = r->wrel[y][1] = r->wstep[y][0] = r->wstep[y][1] = 0;
        r->tkr[y] = -1;
        if (rz < 0 && r->eye[2] > p->plane_z) {
            int64_t lam = sdiv64(((int64_t)p->plane_z - r->eye[2]) * Q12, rz);    /* world units per unit ray */
            if (lam > ((int64_t)1 << 31)) lam = (int64_t)1 << 31;
            for (k = 0; k < 2; k++) {
                int64_t ray = (((int64_t)c->up[k] * b) >> 30) + (c->fwd[k] >> 18);   /* Q12 */
                r->wrel[y][k] = (lam * ray) >> 12;
                r->wstep[y][k] = (lam * c->right[k]) >> 30;
            }
            /* the ray's forward component is 1: lam is the plane point's zc */
            r->tkr[y] = p->water_on ? wdiv_s(&dtint, lam << 21) : -1;
            if (r->tkr[y] > ((int64_t)1 << 40)) r->tkr[y] = (int64_t)1 << 40;
        }
    }
    for (k = 0; k < 2; k++) {
        int64_t len = k == 0 ? p->wave_len : p->wave_len * 5 / 8;
        if (len < 1) len = 1;
        r->kx[k] = sdiv64((int64_t)dir[k][0] * ((int64_t)1 << 18), len);        /* 2^32 turns per world unit */
        r->ky[k] = sdiv64((int64_t)dir[k][1] * ((int64_t)1 << 18), len);
        r->kt[k] = k == 0 ? 2045222 : 3303820;      /* 2^32 / 2100, 2^32 / 1300 (periods in ms) */
    }
    for (y = 0; y < r->h; y++)      /* phase = px kx + py ky + t kt at the row's point, mod 2^32 */
        for (k = 0; k < 2; k++)
            r->wph[y][k] = (uint32_t)(r->eye[0] + r->wrel[y][0]) * (uint32_t)r->kx[k]
                           + (uint32_t)(r->eye[1] + r->wrel[y][1]) * (uint32_t)r->ky[k]
                           + (uint32_t)p->time_ms * (uint32_t)r->kt[k];
    {   /* displacement Q8 px = d amp_m >> 32 = A f 2^8 / zc */
        int64_t num = p->wave_amp * (f16 >> 4);
        int64_t m = K > 0 ? sfloor64(num << 12, K) << 16 : 0;
        r->amp_m = m > ((int64_t)1 << 33) ? (int64_t)1 << 33 : m;
        /* waves fade beyond 8 wave lengths */
        const uint64_t fd = udiv64((uint64_t)K, 8 * (uint64_t)(p->wave_len > 0 ? p->wave_len : 1));
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
    }
    r->inv_sx = p->grid_sx > 0 ? udiv64(((uint64_t)1 << 32) + (uint64_t)p->grid_sx - 1, (uint64_t)p->grid_sx) : 0;
    r->inv_sy = p->grid_sy > 0 ? udiv64(((uint64_t)1 << 32) + (uint64_t)p->grid_sy - 1, (uint64_t)p->grid_sy) : 0;
    r->gx0 = r->eye[0] - p->grid_ox + p->grid_sx / 2;
    r->gy0 = p->grid_oy - r->eye[1] + p->grid_sy / 2;
    r->gxmax = p->grid_sx > 0 && p->wet_w > 0 ? (uint64_t)((int64_t)p->wet_w * p->grid_sx) : 0;
    r->gymax = p->grid_sy > 0 && p->wet_h > 0 ? (uint64_t)((int64_t)p->wet_h * p->grid_sy) : 0;
    if (p->fog_on) fog_table(r, K);
    {   /* dquiet: terrain pixels at least this near (buffer units) get no fog */
        uint64_t d30 = 0;
        int32_t i;
        if (p->fog_on)
            for (i = RW_TAB; i >= 0; i--)
                if (r->fog[i]) { d30 = (uint64_t)(i + 1) << r->fog_sh; break; }
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
    water_rows(r);
    water_horizon(r, c, f16);
    return BR_OK;
}

void rw_fog_vertices(rw_frame *r, rs_frame *f)
{
    uint32_t i;
    if (!r || !f || !f->cache) return;
    f->clear_rows = r->clear4;
    if (!r->p.fog_on || r->pixel_fog) return;
    for (i = 0; i < f->nv; i++) {
        rs_cvert *o = &f->cache[i];
        const uint32_t oc = o->c >> 24, q = o->d >> r->fog_sh;
        uint32_t fw, rgb;
        int32_t y;
        if ((oc & (RS_OUT_NEAR | RS_OUT_GUARD)) || q > RW_TAB || (fw = r->fog[q]) == 0) continue;
        y = o->y >> RS_SUBPIX_BITS;
        y = y < 0 ? 0 : y >= r->h ? r->h - 1 : y;
        rgb = mix_rgb(o->c & 0xffffffu, r->sky[y], fw);
        rs_cvert_recolour(o, rgb);
    }
}

/* ---------------------------------------------------------------- passes */

/* Reflection rows (of the reduced frame) stored for scratch rows [top, bottom): those
 * the post hook can read, the water rows widened by the waves' reach. */
static void refl_rows(const rw_frame *r, int32_t top, int32_t bottom, int32_t *h0, int32_t *h1)
{
    const int32_t s = r->p.res_shift;
    int32_t lo = r->wlo - RW_WAVE_PX, hi = r->whi + RW_WAVE_PX + 1;
    if (lo < top) lo = top;
    if (hi > bottom) hi = bottom;
    if (lo >= hi) { *h0 = *h1 = 0; return; }
    *h0 = lo >> s;
    *h1 = ((hi - 1) >> s) + 1;
    if (*h1 > r->h >> s) *h1 = r->h >> s;
    if (*h0 > *h1) *h0 = *h1;
}

static int refl_touched(const void *user, int32_t y0, int32_t rows)
{
    const rw_frame *r = (const rw_frame *)user;
    return r->refl && r->wlo <= r->whi && y0 <= r->whi + RW_WAVE_PX && y0 + rows > r->wlo - RW_WAVE_PX;
}

static inline int32_t next_water(const uint8_t *wc, int32_t x, int32_t w, const int32_t fmt);

/* 1 when row y of the band's water-pass scratch (y in the band and in wlo .. whi) holds
 * a water id. */
static int water_in_row(const rw_frame *r, const rs_band *b, int32_t y)
{
    const int32_t i = r->water_pass;
    const uint8_t *row = (const uint8_t *)b->scratch[i] + (size_t)(y - b->scratch_y0[i]) * b->scratch_stride[i];
    return r->fmt == RS_FMT_RGB565 ? next_water(row, 0, b->w, RS_FMT_RGB565) < b->w
                                   : next_water(row, 0, b->w, RS_FMT_XRGB8888) < b->w;
}

/* The reflection of the band: when the water pass ran before this one (ws_frame adds it
 * first), only the reduced rows the hook can read, those of the band's rows that hold a
 * water id widened by the waves' reach (RW_WAVE_PX; the hook reads row y + dy, |dy| <=
 * RW_WAVE_PX, of water pixels only), drawn at their places in the scratch; nothing when
 * the band holds no water.  Otherwise every row refl_rows gives. */
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
        const int32_t lo = r->wlo > b->y0 ? r->wlo : b->y0;
        const int32_t hi = r->whi < b->y0 + b->rows - 1 ? r->whi : b->y0 + b->rows - 1;
        int32_t ya = lo, yb = hi;
        while (ya <= hi && !water_in_row(r, b, ya)) ya++;
        if (ya > hi) return BR_OK;                  /* no water in the band: nothing reads it */
        while (yb > ya && !water_in_row(r, b, yb)) yb--;
        ya = ya - RW_WAVE_PX < 0 ? 0 : ya - RW_WAVE_PX;
        yb = yb + RW_WAVE_PX > r->h - 1 ? r->h - 1 : yb + RW_WAVE_PX;
        if ((ya >> s) > g0) g0 = ya >> s;
        if ((yb >> s) + 1 < g1) g1 = (yb >> s) + 1;
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

static int water_touched(const void *user, int32_t y0, int32_t rows)
{
    const rw_frame *r = (const rw_frame *)user;
    return r->water && r->wlo <= r->whi && y0 <= r->whi && y0 + rows > r->wlo;
}

/* One row of the water pass's scratch: depth o = max(t - bias, dfar) from the terrain's
 * row t, colour c = 0 (no id), n pixels (buffers that do not overlap).  t - bias > dfar
 * exactly when t > bias + dfar (all three below 2^30 for 30-bit depths, 2^16 for 16-bit
 * ones: no overflow).  With GCC's vector extension (gcc, clang) 16 bytes a step; the
 * colour is cleared in the same loop (one store per vector of depths, no second pass
 * over the row). */
#if defined(__GNUC__)
typedef uint32_t seed_u32x4 __attribute__((vector_size(16)));
typedef uint16_t seed_u16x8 __attribute__((vector_size(16)));
#endif
static inline void seed32(uint32_t *restrict o, uint32_t *restrict c, const uint32_t *restrict t, int32_t n,
                          uint32_t bias, uint32_t dfar, const int clear)
{
    const uint32_t thr = bias + dfar;
    int32_t i = 0;
#if defined(__GNUC__)
    const seed_u32x4 vb = { bias, bias, bias, bias }, vf = { dfar, dfar, dfar, dfar }, vt = { thr, thr, thr, thr };
    uint32_t zero = 0;
    seed_u32x4 z;
    __asm__("" : "+r"(zero));   /* opaque: GCC would split the zero stores into a memset,
                                   a second pass over the row */
    z = (seed_u32x4){ zero, zero, zero, zero };
    for (; i + 8 <= n; i += 8) {
        seed_u32x4 v, u, m, k;
        memcpy(&v, t + i, sizeof v);
        memcpy(&u, t + i + 4, sizeof u);
        m = (seed_u32x4)(v > vt);
        k = (seed_u32x4)(u > vt);
        v = ((v - vb) & m) | (vf & ~m);
        u = ((u - vb) & k) | (vf & ~k);
        memcpy(o + i, &v, sizeof v);
        memcpy(o + i + 4, &u, sizeof u);
        if (clear) { memcpy(c + i, &z, sizeof z); memcpy(c + i + 4, &z, sizeof z); }
    }
#endif
    for (; i < n; i++) {
        o[i] = t[i] > thr ? t[i] - bias : dfar;
        if (clear) c[i] = 0;
    }
}

static inline void seed16(uint16_t *restrict o, uint16_t *restrict c, const uint16_t *restrict t, int32_t n,
                          uint32_t bias, uint32_t dfar, const int clear)
{
    int32_t i = 0;
    if (bias + dfar >= 65535u) {    /* no terrain depth passes: every pixel is dfar */
        for (; i < n; i++) {
            o[i] = (uint16_t)dfar;
            if (clear) c[i] = 0;
        }
        return;
    }
    {
        const uint16_t thr = (uint16_t)(bias + dfar), b16 = (uint16_t)bias, f16 = (uint16_t)dfar;
#if defined(__GNUC__)
        const seed_u16x8 vb = { b16, b16, b16, b16, b16, b16, b16, b16 };
        const seed_u16x8 vf = { f16, f16, f16, f16, f16, f16, f16, f16 };
        const seed_u16x8 vt = { thr, thr, thr, thr, thr, thr, thr, thr };
        uint16_t zero = 0;
        seed_u16x8 z;
        __asm__("" : "+r"(zero));   /* as in seed32 */
        z = (seed_u16x8){ zero, zero, zero, zero, zero, zero, zero, zero };
        for (; i + 8 <= n; i += 8) {
            seed_u16x8 v, m;
            memcpy(&v, t + i, sizeof v);
            m = (seed_u16x8)(v > vt);
            v = ((v - vb) & m) | (vf & ~m);
            memcpy(o + i, &v, sizeof v);
            if (clear) memcpy(c + i, &z, sizeof z);
        }
#endif
        for (; i < n; i++) {
            o[i] = t[i] > thr ? (uint16_t)(t[i] - b16) : f16;
            if (clear) c[i] = 0;
        }
    }
}

/* The water pass's scratch, seeded from the terrain pass's depth of the same rows (the
 * pass has no margin): depth max(dfar, terrain - water_bias), so a water pixel is drawn
 * only where it is nearer than the terrain, or farther by no more than the shore bound of
 * the bodies on screen allows (rw_post tests each body's own); colour 0 (no id).  The
 * water frame is drawn with no_clear. */
static br_status water_run(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    const rw_frame *r = (const rw_frame *)user;
    const uint32_t bias = r->water_bias, dfar = r->dfar;
    const int32_t w = b->w;
    const int32_t lo = r->wlo > b->y0 ? r->wlo : b->y0;
    const int32_t hi = r->whi < b->y0 + b->rows - 1 ? r->whi : b->y0 + b->rows - 1;
    int32_t y;
    if (b->scratch_y0[self] != b->y0 || b->scratch_rows[self] != b->rows) return BR_E_ARG;
    /* only the water rows wlo .. whi: no water triangle reaches the others, and rw_post
     * reads no other row of this scratch */
    for (y = lo; y <= hi; y++) {
        const size_t row = (size_t)(y - b->y0);
        uint8_t *c = (uint8_t *)b->scratch[self] + row * b->scratch_stride[self];
        uint8_t *o = (uint8_t *)b->scratch_depth[self] + row * (size_t)w * (r->depth == RS_DEPTH16 ? 2u : 4u);
        const uint8_t *t = (const uint8_t *)b->depth + row * (size_t)w * (r->depth == RS_DEPTH16 ? 2u : 4u);
        /* the colour is cleared with the depths where both have the same pixel size */
        if (r->depth == RS_DEPTH16 && r->fmt == RS_FMT_RGB565)
            seed16((uint16_t *)(void *)o, (uint16_t *)(void *)c, (const uint16_t *)(const void *)t, w, bias, dfar, 1);
        else if (r->depth != RS_DEPTH16 && r->fmt != RS_FMT_RGB565)
            seed32((uint32_t *)(void *)o, (uint32_t *)(void *)c, (const uint32_t *)(const void *)t, w, bias, dfar, 1);
        else {
            memset(c, 0, (size_t)w * (r->fmt == RS_FMT_RGB565 ? 2u : 4u));
            if (r->depth == RS_DEPTH16)
                seed16((uint16_t *)(void *)o, NULL, (const uint16_t *)(const void *)t, w, bias, dfar, 0);
            else
                seed32((uint32_t *)(void *)o, NULL, (const uint32_t *)(const void *)t, w, bias, dfar, 0);
        }
    }
    return rs_draw_band(r->water, b->scratch_y0[self], b->scratch_rows[self], b->scratch[self],
                        b->scratch_stride[self], b->scratch_depth[self], st);
}

br_status rw_pass_water(rs_pass *pass, const rw_frame *r)
{
    if (!pass || !r || !r->water) return BR_E_ARG;
    memset(pass, 0, sizeof *pass);
    pass->name = "water";
    pass->scratch = 1;
    pass->rows_touched = water_touched;
    pass->run = water_run;
    pass->user = r;
    return BR_OK;
}

/* ---------------------------------------------------------------- the post hook */

static uint32_t get_rgb(int32_t fmt, const void *row, int32_t x)
{
    if (fmt == RS_FMT_RGB565) {
        uint32_t v = ((const uint16_t *)row)[x], rr = v >> 11, g = (v >> 5) & 63u, bb = v & 31u;
        return ((rr << 3 | rr >> 2) << 16) | ((g << 2 | g >> 4) << 8) | (bb << 3 | bb >> 2);
    }
    return ((const uint32_t *)row)[x] & 0xffffffu;
}

static uint32_t get_depth(int32_t depth, const void *row, int32_t x)
{
    return depth == RS_DEPTH16 ? ((const uint16_t *)row)[x] : ((const uint32_t *)row)[x];
}

/* The water id of a water-pass pixel (RW_ID_RGB: the top five bits of red). */
static uint32_t get_id(int32_t fmt, const void *row, int32_t x)
{
    return fmt == RS_FMT_RGB565 ? (uint32_t)((const uint16_t *)row)[x] >> 11 : (((const uint32_t *)row)[x] >> 19) & 31u;
}

/* The reflection scratch as the hook reads it. */
typedef struct refl_view {
    const uint8_t *col, *dep;
    int32_t h0, h1, rw;
} refl_view;

/* The colour of water pixel (x, y): terrain colour ct and depth dt under it, water depth
 * dw (30-bit units), body id. */
static RW_INLINE uint32_t water_px(const rw_frame *r, const refl_view *rv, int32_t x, int32_t y, uint32_t ct,
                         uint32_t dt, uint32_t dw, uint32_t id)
{
    const int32_t a = r->aq[x], rz = r->rz[y], s = r->p.res_shift;
    const int64_t b = r->bq[y];
    uint32_t den = (uint32_t)(((int64_t)a * a + b * b + (int64_t)Q12 * Q12) >> 8);
    uint32_t ci = (uint32_t)(((uint64_t)((int64_t)rz * rz) >> 8) << 10) / (den ? den : 1);
    int32_t dx = 0, dy = 0;
    uint32_t refl, refr, fr, x32;
    if (ci > RW_TAB) ci = RW_TAB;
    if (r->p.waves_on) {
        /* the phase's bits 24..31 depend on it modulo 2^32 only: the row's phase at its point
         * plus the offset a wstep (floored, Q12) times the wave numbers, mod 2^32 */
        const uint32_t ox = (uint32_t)((a * r->wstep[y][0]) >> 12), oy = (uint32_t)((a * r->wstep[y][1]) >> 12);
        const uint32_t f0 = ((r->wph[y][0] + ox * (uint32_t)r->kx[0] + oy * (uint32_t)r->ky[0]) >> 24) & 255u;
        const uint32_t f1 = ((r->wph[y][1] + ox * (uint32_t)r->kx[1] + oy * (uint32_t)r->ky[1]) >> 24) & 255u;
        const int32_t c0 = r->sine[(f0 + 64u) & 255u], c1 = r->sine[(f1 + 64u) & 255u];
        int64_t q8 = ((int64_t)dw * r->amp_m) >> 32;
        int32_t ti;
        if (q8 > RW_WAVE_PX * 128) q8 = RW_WAVE_PX * 128;
        /* beyond wave_fade_d (far away) the waves fade as 1/zc^2: shorter than a pixel
         * there, they would only alias */
        if (dw < r->wave_fade_d) q8 = (int64_t)(((uint64_t)q8 * (dw >> 14) * r->inv_fade) >> 32);
        dx = (int32_t)((q8 * (c0 + c1)) >> 15);
        dy = (int32_t)((q8 * (c0 - c1)) >> 15);
        ti = (int32_t)ci + (int32_t)(((c0 + c1) * q8) >> 10);    /* the slope tilts cos t */
        ci = ti < 0 ? 0u : ti > RW_TAB ? (uint32_t)RW_TAB : (uint32_t)ti;
    }
    fr = r->p.fresnel_one ? 256u : r->fres[ci];
    refl = r->skyrefl[ci];      /* the reflected sky */
    if (rv->col && id == (uint32_t)r->p.refl_body) {
        int32_t yy = y + dy, xx = x + dx, ry, rx;
        if (yy < 0) yy = 0;
        if (yy >= r->h) yy = r->h - 1;
        if (xx < 0) xx = 0;
        if (xx >= r->w) xx = r->w - 1;
        ry = yy >> s; rx = xx >> s;
        if (rx >= rv->rw) rx = rv->rw - 1;
        if (ry >= rv->h0 && ry < rv->h1) {
            const size_t o = (size_t)(ry - rv->h0) * (size_t)rv->rw;
            const size_t bpp = r->fmt == RS_FMT_RGB565 ? 2u : 4u, dbp = r->depth == RS_DEPTH16 ? 2u : 4u;
            if (get_depth(r->depth, rv->dep + o * dbp, rx) != r->rdfar) refl = get_rgb(r->fmt, rv->col + o * bpp, rx);
        }
    }
    /* refraction: x32 = 32 L / tint_len, L = zc_w (dw / dt - 1) (dt < dw), zc_w the
     * body's plane point's zc = the reflected plane's times bratio: tkr[y] bratio q >> 48
     * with q = (dw - dt) / dt, Q16, from both depths brought to 16 bits */
    x32 = 255;
    if (r->p.tint_fixed) return mix_rgb(mix_pre(ct, r->tint_u, r->tint_rb, r->tint_g), refl, fr);
    if (r->tkr[y] >= 0 && r->bratio[id] && dt < dw) {
        const int32_t sh = dw >= 65536u ? 16 - fx_clz32(dw) : 0;    /* dw >> sh < 2^16 */
        uint32_t w16, t16;
        w16 = dw >> sh; t16 = dt >> sh;
        if (t16) {
            uint32_t q = ((w16 - t16) << 16) / t16;
            int64_t tb = (r->tkr[y] * r->bratio[id]) >> 16;
            uint64_t v;
            if (tb > ((int64_t)1 << 40)) tb = (int64_t)1 << 40;
            v = ((uint64_t)tb * (q > (1u << 20) ? (1u << 20) : q)) >> 32;
            x32 = v > 255u ? 255u : (uint32_t)v;
        }
    }
    refr = mix_rgb(ct, r->p.water_rgb, r->tint[x32 > 255u ? 255u : x32]);
    return mix_rgb(refr, refl, fr);
}

/* Depths (buffer units) this close are a tie: the terrain lies at the water's surface
 * within the depth buffer's resolution (a near plane far below the distance, as in the
 * viewer's fly camera, leaves metres a unit far away), and which is nearer is decided by
 * whether the water plane's point on the pixel's ray is wet, not by the rounding. */
#define RW_DEPTH_TIE 2u

/* The shore test for water pixel (x, y) of body id whose terrain is nearer (dt > dw): 1
 * when the terrain's point on the pixel's ray lies on a sample wet with that body (the
 * terrain LOD over flattened water), 0 otherwise (land, or no plane point for the row).
 * P_t = E + (P_0 - E) bratio dw / dt, P_0 the reflected plane's point; dw / dt from the
 * depths brought to 16 bits (a 32-bit division); the grid sample nearest P_t. */
static int shore_wet(const rw_frame *r, int32_t x, int32_t y, uint32_t id, uint32_t dt, uint32_t dw)
{
    int64_t f, gx, gy;
    uint32_t q, t16;
    int32_t sh;
    size_t ix, iy;
    if (!r->p.wet || r->tkr[y] < 0 || !r->bratio[id]) return 0;
    sh = dt >= 65536u ? 16 - fx_clz32(dt) : 0;      /* the smallest sh with dt >> sh < 2^16 */
    t16 = dt >> sh;
    if (!t16) return 0;
    q = ((dw >> sh) << 16) / t16;
    f = ((int64_t)r->bratio[id] * q) >> 16;
    /* P_t - E = (P_0 - E) f >> 16 per axis; the grid position of P_t plus half a step */
    gx = r->gx0 + (((r->wrel[y][0] + (((int64_t)r->aq[x] * r->wstep[y][0]) >> 12)) * f) >> 16);
    gy = r->gy0 - (((r->wrel[y][1] + (((int64_t)r->aq[x] * r->wstep[y][1]) >> 12)) * f) >> 16);
    if ((uint64_t)gx >= r->gxmax || (uint64_t)gy >= r->gymax) return 0;       /* negative: huge */
    ix = (size_t)(((uint64_t)gx * r->inv_sx) >> 32);
    iy = (size_t)(((uint64_t)gy * r->inv_sy) >> 32);
    if (ix >= (size_t)r->p.wet_w || iy >= (size_t)r->p.wet_h) return 0;
    return r->p.wet[iy * (size_t)r->p.wet_w + ix] == id;
}

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

/* Row y's water-pass scratch in the band: colour (returned) and depth (*wd); NULL where
 * the pass drew nothing there (water_run seeds only the water rows wlo .. whi). */
static inline const uint8_t *water_row(const rw_frame *r, const rs_band *b, const uint8_t *wcol, const uint8_t *wdep,
                                       int32_t wy0, int32_t wrows, int32_t y, size_t dbp, const uint8_t **wd)
{
    if (!wcol || y < wy0 || y >= wy0 + wrows || y < r->wlo || y > r->whi) return NULL;
    *wd = wdep + (size_t)(y - wy0) * (size_t)b->w * dbp;
    return wcol + (size_t)(y - wy0) * b->stride;
}

/* 1 when the water of body id at pixel (x, y) shows over the terrain, depths dt (terrain)
 * and dw (water) in buffer units (<< dsh: 30-bit): the water is nearer; or the two tie
 * (RW_DEPTH_TIE) and the plane's point is wet; or the terrain is nearer within the shore
 * bound and its point on the ray is wet (the LOD over water). */
static inline int water_shows(const rw_frame *r, int32_t x, int32_t y, uint32_t id, uint32_t dt, uint32_t dw,
                              int32_t dsh)
{
    if (dw + RW_DEPTH_TIE > dt) return dw > dt || shore_wet(r, x, y, id, dw << dsh, dw << dsh);
    if (((dt - dw) << dsh) > r->shore_dd[id]) return 0;
    if (r->p.shore_bound && r->p.shore_w
        && r->ebody[id] * (int64_t)((dt - dw) << dsh) > r->p.shore_w * (int64_t)(dt << dsh) + r->p.shore_c) return 0;
    return shore_wet(r, x, y, id, dt << dsh, dw << dsh);
}

/* Writes a pixel the hook computed (RGB565: dithered). */
static inline void put_px(uint8_t *crow, int32_t x, int32_t y, uint32_t rgb, const int32_t fmt)
{
    if (fmt == RS_FMT_RGB565) ((uint16_t *)(void *)crow)[x] = pack565_dither(rgb, x, y);
    else ((uint32_t *)(void *)crow)[x] = rgb;
}

/* The hook when the terrain frame carries its own fog and sky (rw_fog_vertices): only
 * water pixels change, fogged by the water's depth.  Same specialisation as post_rows. */
static inline void water_rows_only(const rw_frame *r, rs_band *b, const refl_view *rv, const uint8_t *wcol,
                                   const uint8_t *wdep, int32_t wy0, int32_t wrows, const int32_t fmt,
                                   const int32_t depth)
{
    const size_t dbp = depth == RS_DEPTH16 ? 2u : 4u;
    const int32_t dsh = depth == RS_DEPTH16 ? 14 : 0;
    int32_t row, x;
    for (row = 0; row < b->rows; row++) {
        const int32_t y = b->y0 + row;
        uint8_t *crow = (uint8_t *)b->color + (size_t)row * b->stride;
        const uint8_t *drow = (const uint8_t *)b->depth + (size_t)row * (size_t)b->w * dbp, *wd = NULL;
        const uint8_t *wc = water_row(r, b, wcol, wdep, wy0, wrows, y, dbp, &wd);
        if (!wc) continue;
        for (x = next_water(wc, 0, b->w, fmt); x < b->w; x = next_water(wc, x + 1, b->w, fmt)) {
            const uint32_t id = get_id(fmt, wc, x), dt = get_depth(depth, drow, x), dw = get_depth(depth, wd, x);
            uint32_t rgb, d, fw;
            if (!water_shows(r, x, y, id, dt, dw, dsh)) continue;
            rgb = water_px(r, rv, x, y, get_rgb(fmt, crow, x), dt << dsh, dw << dsh, id);
            d = dw << dsh;
            if (r->p.fog_on && (d >> r->fog_sh) <= RW_TAB && (fw = r->fog[d >> r->fog_sh]) != 0)
                rgb = mix_rgb(rgb, r->sky[y], fw);
            put_px(crow, x, y, rgb, fmt);
        }
    }
}

/* The hook's pixels for one band (textured terrain: fog per pixel), specialised by the
 * compiler for each format and depth (fmt, depth are constants at every call). */
static inline void post_rows(const rw_frame *r, rs_band *b, const refl_view *rv, const uint8_t *wcol,
                             const uint8_t *wdep, int32_t wy0, int32_t wrows, const int32_t fmt, const int32_t depth)
{
    const size_t dbp = depth == RS_DEPTH16 ? 2u : 4u;
    const int32_t dsh = depth == RS_DEPTH16 ? 14 : 0;
    int32_t row, x;
    for (row = 0; row < b->rows; row++) {
        const int32_t y = b->y0 + row;
        uint8_t *crow = (uint8_t *)b->color + (size_t)row * b->stride;
        const uint8_t *drow = (const uint8_t *)b->depth + (size_t)row * (size_t)b->w * dbp;
        const uint8_t *wd = NULL, *wc = water_row(r, b, wcol, wdep, wy0, wrows, y, dbp, &wd);
        const uint32_t sky = r->sky[y];
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
                if (wc) {
                    const uint32_t id = get_id(fmt, wc, x), dw = get_depth(depth, wd, x);
                    if (id && water_shows(r, x, y, id, dt, dw, dsh)) {
                        rgb = water_px(r, rv, x, y, get_rgb(fmt, crow, x), dt << dsh, dw << dsh, id);
                        d = dw << dsh;
                        changed = 1;
                    }
                }
                if (r->p.fog_on && (d >> r->fog_sh) <= RW_TAB && (fw = r->fog[d >> r->fog_sh]) != 0) {
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
        if (r->fmt == RS_FMT_RGB565) {
            if (r->depth == RS_DEPTH16) water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH16);
            else water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH32);
        } else if (r->depth == RS_DEPTH16) water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH16);
        else water_rows_only(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH32);
        return BR_OK;
    }
    if (r->fmt == RS_FMT_RGB565) {
        if (r->depth == RS_DEPTH16) post_rows(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH16);
        else post_rows(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_RGB565, RS_DEPTH32);
    } else if (r->depth == RS_DEPTH16) post_rows(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH16);
    else post_rows(r, b, &rv, wcol, wdep, wy0, wrows, RS_FMT_XRGB8888, RS_DEPTH32);
    return BR_OK;
}
