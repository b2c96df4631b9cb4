/* raster/raster_int.h — what raster.c (set-up, clipper, band loop) and xform.c (the
 * per-frame vertex transform, rs_frame_prepare) share.  Internal: not part of the
 * contract (that is raster.h), not installed, included by these two files only.
 *
 * The helpers are static inline rather than external functions: each file
 * keeps its own inlined copy (the clipper's rsi_project/rsi_to_camera calls stay
 * direct), and test_raster_variants.c,
 * which compiles both files into its own translation unit beside the full library,
 * needs no extra renames to avoid duplicate symbols.
 *
 * Units: screen positions in sub-pixels (RSI_SUB fraction bits, pixel centres at RSI_HALF),
 * camera space in world units, f in Q8 pixels (see raster.h). */
#ifndef BR_RASTER_INT_H
#define BR_RASTER_INT_H
/* Run-time instruction-set choice (raster/isa.c): on x86-64 the Makefile compiles
 * raster.c and xform.c twice, the second time with -march=x86-64-v3 -DRS_BUILD_V3, and
 * the first with -DRS_ISA_DISPATCH=1.  The copies' external functions get their own
 * names (set before raster.h declares them, so the prototypes follow): the v3 copy's
 * all end in _v3; in the baseline copy the two that draw (rs_frame_prepare,
 * rs_draw_band) end in _base, and isa.c defines the public names, which
 * call one copy or the other.  Other builds (boards, the sanitizer and test builds)
 * define neither and compile one copy under the public names. */
#if defined(RS_BUILD_V3)
#define rs_cache_mem_size rs_cache_mem_size_v3
#define rs_chunk_mem_size rs_chunk_mem_size_v3
#define rs_band_mem_size rs_band_mem_size_v3
#define rs_clip_mem_size rs_clip_mem_size_v3
#define rs_cvert_set rs_cvert_set_v3
#define rs_cvert_recolour rs_cvert_recolour_v3
#define rs_frame_prepare rs_frame_prepare_v3
#define rs_draw_band rs_draw_band_v3
#define rs_variant_built rs_variant_built_v3
#define rs_to_rgb888 rs_to_rgb888_v3
#elif defined(RS_ISA_DISPATCH) && RS_ISA_DISPATCH
#define rs_frame_prepare rs_frame_prepare_base
#define rs_draw_band rs_draw_band_base
#endif
#include <stdint.h>
#include "raster/raster.h"
#include "core/fx.h"

#define RSI_SUB RS_SUBPIX_BITS
#define RSI_SUBONE (1 << RSI_SUB)
#define RSI_HALF (RSI_SUBONE / 2)

/* 1 on targets with 64-bit registers (core/config.h BR_REG64). */
#define RSI_REG64 BR_REG64

/* 1 on 32-bit targets with a 32-bit divide instruction (Armv7-M: Cortex-M3, M4), where
 * the general path's small triangles find their row spans by C's 32-bit `/` (exact, as
 * the reciprocals it replaces; raster_general.h gen_edge32).  Armv6-M (Cortex-M0+) and
 * Debian's armv7-a have none. */
#if !RSI_REG64 && defined(__ARM_FEATURE_IDIV)
#define RSI_IDIV32 1
#else
#define RSI_IDIV32 0
#endif

#if defined(__GNUC__)
#define RSI_NOINLINE __attribute__((noinline))
#define RSI_INLINE inline __attribute__((always_inline))
#define RSI_UNLIKELY(x) __builtin_expect(!!(x), 0)
#define RSI_LIKELY(x) __builtin_expect(!!(x), 1)
#else
#define RSI_LIKELY(x) (x)
#define RSI_UNLIKELY(x) (x)
#define RSI_NOINLINE
#define RSI_INLINE
#endif

/* The packed colour of rs_cvert.cp: R, G, B at bits 42, 21, 0 of three 21-bit fields
 * (8 integer + 13 fraction bits; see RS_CBIAS in raster.c). */
static inline uint64_t rsi_pack_rgb(uint32_t rgb)
{
    return ((uint64_t)(rgb & 0xff0000u) << 26) | ((uint64_t)(rgb & 0xff00u) << 13) | (uint64_t)(rgb & 255u);
}

/* f in Q8 pixels (f <= 2^20 px for fovy >= 1 deg and h <= 16384, so < 2^28). */
static inline int64_t rsi_f_q8(const cam_vp *vp) { return (vp->f_q16 + 128) >> 8; }

/* Screen position of camera-space point c (c2 >= znear, inside the guard band). */
static inline void rsi_project(const cam_vp *vp, int64_t f8, const int64_t c[3], int32_t w, int32_t h, rs_cvert *o)
{
    /* |f8 * c| < 2^28 * 2^32; the quotient is within the guard band: |q| <= 2^22; the
     * depth quotient is below RS_DEPTH_ONE (c2 >= znear): 32-bit quotients, which
     * fx_divisor gives without a 64-bit divide on 32-bit targets */
    fx_divisor dz;
    int64_t qx, qy;
    fx_divisor_make(&dz, c[2]);
    qx = fx_divisor_trunc(&dz, f8 * c[0]);
    qy = fx_divisor_trunc(&dz, f8 * c[1]);
    o->x = w * RSI_HALF + (int32_t)((qx + 8) >> 4);
    o->y = h * RSI_HALF - (int32_t)((qy + 8) >> 4);
    o->d = (uint32_t)fx_divisor_trunc(&dz, (int64_t)RS_DEPTH_ONE * vp->znear);
}

/* Camera space of world point p: the Q30 view matrix and translation, floored to
 * world units: c = (R p + t) >> 30, each product below 2^60 (|R| <= 2^30 in Q30,
 * |p| < 2^30 by the world convention).  Only xform_slow and the clipper
 * call it, once each (off the fast paths), so it stays one out-of-line copy.  Not inline
 * (gcc warns on inline + noinline): both files use it, so no unused warning. */
static RSI_NOINLINE void rsi_to_camera(const cam_vp *vp, const int32_t p[3], int64_t c[3])
{
    int i;
    for (i = 0; i < 3; i++)
        c[i] = ((int64_t)vp->r[i][0] * p[0] + (int64_t)vp->r[i][1] * p[1]
                + (int64_t)vp->r[i][2] * p[2] + vp->t[i]) >> 30;
}

#endif
