/* raster/water_int.h — what raster/water.c (the reflection pass and the post hook),
 * raster/water_pass.c (the water pass) and raster/water_setup.c (the per-frame set-up)
 * share: colour mixing, the RGB565 dither, the water pass's columns.  Private to those
 * files. */
#ifndef BR_RWATER_INT_H
#define BR_RWATER_INT_H
/* Run-time instruction-set choice (raster/isa.c), as raster_int.h's for raster.c: on
 * x86-64 the Makefile compiles water.c and water_pass.c twice, the second time with
 * -march=x86-64-v3 -DRS_BUILD_V3, whose external functions end in _v3 (set before
 * water.h declares them), and the first with -DRS_ISA_DISPATCH=1, whose post hook and
 * water pass call the v3 copy's rw_post_v3 and rw_water_run_v3 when rs_isa() says V3.
 * water.c and water_pass.c include this header first. */
#if defined(RS_BUILD_V3)
#define rw_pass_reflection rw_pass_reflection_v3
#define rw_pass_water rw_pass_water_v3
#define rw_post rw_post_v3
#endif
#include <stdint.h>
#include "raster/water.h"
#if defined(RS_BUILD_V3) || (defined(RS_ISA_DISPATCH) && RS_ISA_DISPATCH)
br_status rw_post_v3(const void *user, rs_band *b, rs_band_stats *st);
br_status rw_water_run_v3(const void *user, rs_band *b, int32_t self, rs_band_stats *st);
#endif

#define Q12 4096

static inline uint32_t mix_rgb(uint32_t a, uint32_t b, uint32_t t)    /* t Q8: a (0) .. b (256) */
{
    /* red and blue in one word, green in another: each field's sum is below 2^16 */
    const uint32_t u = 256u - t;
    const uint32_t rb = ((a & 0xff00ffu) * u + (b & 0xff00ffu) * t + 0x800080u) >> 8;
    const uint32_t g = ((a & 0xff00u) * u + (b & 0xff00u) * t + 0x8000u) >> 8;
    return (rb & 0xff00ffu) | (g & 0xff00u);
}

/* mix_rgb(a, b, t) with b and t fixed: u = 256 - t, brb = (b & 0xff00ff) t + 0x800080,
 * bg = (b & 0xff00) t + 0x8000 (the same sums, so the same value). */
static inline uint32_t mix_pre(uint32_t a, uint32_t u, uint32_t brb, uint32_t bg)
{
    const uint32_t rb = ((a & 0xff00ffu) * u + brb) >> 8, g = ((a & 0xff00u) * u + bg) >> 8;
    return (rb & 0xff00ffu) | (g & 0xff00u);
}

/* The fog weight (Q8) of 30-bit depth d from rw_frame's fog table: fog[d >> sh] below
 * d30 (rw_frame.fog_d30), 0 from there on, where every entry is 0 or past the table
 * (d30 is 0 when fog is off).  Values, not the frame: callers keep them in locals where
 * their stores could alias it. */
static inline uint32_t fog_weight(const uint8_t *fog, uint32_t sh, uint32_t d30, uint32_t d)
{
    return d < d30 ? fog[d >> sh] : 0u;
}

/* 4x4 ordered dither (Bayer), 0 .. 15, by screen position. */
static const uint8_t bayer4[4][4] = { { 0, 8, 2, 10 }, { 12, 4, 14, 6 }, { 3, 11, 1, 9 }, { 15, 7, 13, 5 } };

static inline uint16_t pack565_dither(uint32_t rgb, int32_t x, int32_t y)
{
    const uint32_t d = bayer4[y & 3][x & 3];
    uint32_t rr = (((rgb >> 16) & 255u) + (d >> 1)) >> 3, g = (((rgb >> 8) & 255u) + (d >> 2)) >> 2,
             bb = ((rgb & 255u) + (d >> 1)) >> 3;
    if (rr > 31u) rr = 31u;
    if (g > 63u) g = 63u;
    if (bb > 31u) bb = 31u;
    return (uint16_t)((rr << 11) | (g << 5) | bb);
}

/* RGB565 v as 0xRRGGBB, each field's top bits repeated into its low ones. */
static inline uint32_t unpack565(uint32_t v)
{
    const uint32_t rr = v >> 11, g = (v >> 5) & 63u, bb = v & 31u;
    return ((rr << 3 | rr >> 2) << 16) | ((g << 2 | g >> 4) << 8) | (bb << 3 | bb >> 2);
}

/* The 888 colour whose 5/6/5 truncation is rgb's dithered value at (x, y). */
static inline uint32_t dither888(uint32_t rgb, int32_t x, int32_t y)
{
    return unpack565(pack565_dither(rgb, x, y));
}

/* The columns x0 .. *xe - 1 of row y (wlo <= y <= whi) that the water pass seeded and
 * cleared, its row group's (rw_frame.wx0, wx1; none when *x0 >= *xe). */
static inline void rw_row_cols(const rw_frame *r, int32_t y, int32_t *x0, int32_t *xe)
{
    *x0 = r->wx0[y / RW_COL_ROWS];
    *xe = r->wx1[y / RW_COL_ROWS] + 1;
}

#endif
