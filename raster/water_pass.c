/* raster/water_pass.c — the water pass (see water.h): the water frame's triangles drawn
 * into a scratch band whose depth is seeded from the terrain pass's, so that the post
 * hook (raster/water.c) finds each water pixel's body id and depth beside the
 * terrain's. */
#include "raster/water_int.h"     /* first: the v3 copy's names (water_int.h) */
#include <string.h>
#include "core/config.h"      /* RS_SPANV */

static int water_touched(const void *user, int32_t y0, int32_t rows)
{
    const rw_frame *r = (const rw_frame *)user;
    return r->water && r->wlo <= r->whi && y0 <= r->whi && y0 + rows > r->wlo;
}

/* One row of the water pass's scratch: depth o = max(t - bias, dfar) from the terrain's
 * row t, colour c = 0 (no id), n pixels (buffers that do not overlap).  t - bias > dfar
 * exactly when t > bias + dfar (all three below 2^30 for 30-bit depths, 2^16 for 16-bit
 * ones: no overflow, and signed lanes compare them).  Where the target has vector
 * registers (RS_SPANV, core/config.h: GCC's vector extension on SSE2 or NEON) 16 bytes a
 * step, 32 in the x86-64-v3 copy (AVX2) for 32-bit depths, the colour cleared in the same
 * loop (one store per vector of depths, no second pass over the row); elsewhere (32-bit
 * ARM without NEON) the plain loop, as GCC's lowering of the vectors to scalar code costs
 * several times its instructions. */
#if RS_SPANV
typedef uint32_t seed_u32x4 __attribute__((vector_size(16)));
typedef uint16_t seed_u16x8 __attribute__((vector_size(16)));
#if defined(__AVX2__)
#define SEED_VB 32
#else
#define SEED_VB 16
#endif
#define SEED_N (SEED_VB / 4)    /* 32-bit depths a vector */
typedef uint32_t seed_u32v __attribute__((vector_size(SEED_VB)));
typedef int32_t seed_i32v __attribute__((vector_size(SEED_VB)));

/* A zero vector that GCC cannot see is zero: stores of a known zero in a loop become a
 * memset, a second pass over the row (and glibc's `rep stosb`, which callgrind counts a
 * byte an instruction). */
static inline void opaque_zero(seed_u32x4 *z)
{
    uint32_t zero = 0;
    __asm__("" : "+r"(zero));
    *z = (seed_u32x4){ zero, zero, zero, zero };
}
#endif
static inline void seed32(uint32_t *restrict o, uint32_t *restrict c, const uint32_t *restrict t, int32_t n,
                          uint32_t bias, uint32_t dfar, const int clear)
{
    const uint32_t thr = bias + dfar;
    int32_t i = 0;
#if RS_SPANV
    const seed_u32v zero = { 0 }, vb = zero + bias, vf = zero + dfar;
    const seed_i32v vt = (seed_i32v)zero + (int32_t)thr;
    seed_u32x4 z4;
    seed_u32v z;
    opaque_zero(&z4);
    memcpy(&z, &z4, sizeof z4);
#if SEED_VB > 16
    memcpy((uint8_t *)&z + 16, &z4, sizeof z4);
#endif
    for (; i + 2 * SEED_N <= n; i += 2 * SEED_N) {
        seed_u32v v, u, m, k;
        memcpy(&v, t + i, sizeof v);
        memcpy(&u, t + i + SEED_N, sizeof u);
        m = (seed_u32v)((seed_i32v)v > vt);
        k = (seed_u32v)((seed_i32v)u > vt);
        v = ((v - vb) & m) | (vf & ~m);
        u = ((u - vb) & k) | (vf & ~k);
        memcpy(o + i, &v, sizeof v);
        memcpy(o + i + SEED_N, &u, sizeof u);
        if (clear) { memcpy(c + i, &z, sizeof z); memcpy(c + i + SEED_N, &z, sizeof z); }
    }
    for (; i < n; i++) {
        o[i] = t[i] > thr ? t[i] - bias : dfar;
        if (clear) c[i] = 0;
    }
#else
    /* no vectors: the id colour cleared by memset, the seed loop alone, unrolled */
    if (clear) memset(c, 0, (size_t)n * sizeof *c);
#pragma GCC unroll 4
    for (; i < n; i++) o[i] = t[i] > thr ? t[i] - bias : dfar;
#endif
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
#if RS_SPANV
        const seed_u16x8 vb = { b16, b16, b16, b16, b16, b16, b16, b16 };
        const seed_u16x8 vf = { f16, f16, f16, f16, f16, f16, f16, f16 };
        const seed_u16x8 vt = { thr, thr, thr, thr, thr, thr, thr, thr };
        seed_u32x4 z32;
        seed_u16x8 z;
        opaque_zero(&z32);
        z = (seed_u16x8)z32;
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

/* Zeroes the n bytes at c (whole pixels, so n is even) in 16-byte stores, not memset
 * (opaque_zero). */
static void clear_span(uint8_t *c, size_t n)
{
    size_t i = 0;
#if RS_SPANV
    seed_u32x4 z;
    opaque_zero(&z);
    for (; i + 32 <= n; i += 32) {
        memcpy(c + i, &z, sizeof z);
        memcpy(c + i + 16, &z, sizeof z);
    }
#endif
    for (; i + 2 <= n; i += 2) { c[i] = 0; c[i + 1] = 0; }
}

/* Depth o = max(t - bias, dfar) for n pixels from column x0 of a row of the water pass's
 * scratch (o) and the terrain's depth (t); unless c is NULL, the colour row c from x0 too
 * (c's pixels are the depth's size). */
static inline void seed_span(const rw_frame *r, uint8_t *o, uint8_t *c, const uint8_t *t, int32_t x0, int32_t n)
{
    const uint32_t bias = r->water_bias, dfar = r->dfar;
    const size_t at = (size_t)x0 * (r->depth == RS_DEPTH16 ? 2u : 4u);
    if (r->depth == RS_DEPTH16)
        seed16((uint16_t *)(void *)(o + at), c ? (uint16_t *)(void *)(c + at) : NULL,
               (const uint16_t *)(const void *)(t + at), n, bias, dfar, c != NULL);
    else
        seed32((uint32_t *)(void *)(o + at), c ? (uint32_t *)(void *)(c + at) : NULL,
               (const uint32_t *)(const void *)(t + at), n, bias, dfar, c != NULL);
}

/* The water pass's scratch, seeded from the terrain pass's depth of the same rows (the
 * pass has no margin): depth max(dfar, terrain - water_bias), so a water pixel is drawn
 * only where it is nearer than the terrain, or farther by no more than the shore bound of
 * the bodies on screen allows (rw_post tests each body's own); colour 0 (no id).  The
 * water frame is drawn with no_clear. */
static br_status water_run(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    const rw_frame *r = (const rw_frame *)user;
    const int32_t w = b->w;
    const int32_t lo = r->wlo > b->y0 ? r->wlo : b->y0;
    const int32_t hi = r->whi < b->y0 + b->rows - 1 ? r->whi : b->y0 + b->rows - 1;
    const size_t dbp = r->depth == RS_DEPTH16 ? 2u : 4u, cbp = r->fmt == RS_FMT_RGB565 ? 2u : 4u;
    int32_t y;
#if defined(RS_ISA_DISPATCH) && RS_ISA_DISPATCH
    if (rs_isa() == RS_ISA_V3) return rw_water_run_v3(user, b, self, st);
#endif
    if (b->scratch_y0[self] != b->y0 || b->scratch_rows[self] != b->rows) return BR_E_ARG;
    /* only the water rows wlo .. whi, and in them the columns of the row's group
     * (rw_row_cols): no water triangle reaches the others, and the reflection pass and
     * rw_post read no others of this scratch */
    for (y = lo; y <= hi; y++) {
        const size_t row = (size_t)(y - b->y0);
        uint8_t *c = (uint8_t *)b->scratch[self] + row * b->scratch_stride[self];
        uint8_t *o = (uint8_t *)b->scratch_depth[self] + row * (size_t)w * dbp;
        const uint8_t *t = (const uint8_t *)b->depth + row * (size_t)w * dbp;
        int32_t x0, xe;
        rw_row_cols(r, y, &x0, &xe);
        if (x0 >= xe) continue;
        /* the colour is cleared with the depths where both have the same pixel size */
        if (dbp == cbp) seed_span(r, o, c, t, x0, xe - x0);
        else {
            clear_span(c + (size_t)x0 * cbp, (size_t)(xe - x0) * cbp);
            seed_span(r, o, NULL, t, x0, xe - x0);
        }
    }
    return rs_draw_band(r->water, b->scratch_y0[self], b->scratch_rows[self], b->scratch[self],
                        b->scratch_stride[self], b->scratch_depth[self], st);
}

#if defined(RS_BUILD_V3)
br_status rw_water_run_v3(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    return water_run(user, b, self, st);
}
#endif

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
