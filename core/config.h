/* core/config.h — every build-time knob of core/ and raster/, with its default,
 * its allowed values and what it costs.  Override with -DNAME=VALUE.
 *
 * Invariant: no knob may change the pixels of a given configuration between
 * architectures; knobs select configurations, they do not trade determinism. */
#ifndef BR_CONFIG_H
#define BR_CONFIG_H
#include <limits.h>
#include <stdint.h>

/* Largest heightfield side accepted by the loaders and the bitree, in samples.
 * 16385 = 2^14+1: a padded bitree of that side has 2^29 triangles at full depth,
 * which fits the 32-bit node numbering; the int32 sample buffer is 1 GiB. */
#ifndef BR_MAX_SIDE
#define BR_MAX_SIDE 16385
#endif

/* Largest heightfield accepted, in samples (w*h), checked before allocating. */
#ifndef BR_MAX_SAMPLES
#define BR_MAX_SAMPLES (16385L * 16385L)
#endif

/* Heights are int32 in the heightfield's own unit (see core/hf.h); loaders
 * guarantee |z| <= BR_Z_LIMIT so that differences and sums of a few heights
 * never overflow 32 bits. */
#ifndef BR_Z_LIMIT
#define BR_Z_LIMIT (1L << 28)
#endif

/* BR_REG64: 1 on targets with 64-bit registers (pointers of 64 bits), where a 64 x 64-bit
 * product is one instruction.  A few choices of types and helpers in raster/ differ on
 * 32-bit targets (raster_int.h RSI_REG64, water_shore.h grid_pos), with the same results;
 * RS_TEST_32BIT (make test's BR_DIV64_NATIVE=0 build) selects the 32-bit targets' code on
 * a 64-bit machine. */
#if UINTPTR_MAX > 0xffffffffu && !defined(RS_TEST_32BIT)
#define BR_REG64 1
#else
#define BR_REG64 0
#endif

/* How the rasteriser's per-vertex and per-triangle 64-bit quotients are computed:
 * 1 = the compiler's `/` (one instruction on 64-bit targets), 0 = core/fx.h's
 * fx_recip / fx_udiv_r (no divide instruction; for 32-bit ARM and Cortex-M, where an
 * int64 `/` is a call to libgcc's __aeabi_ldivmod, ~280 instructions).  Both give the
 * same quotients, hence the same pixels.  Default: 1 where pointers are 64-bit. */
#ifndef BR_DIV64_NATIVE
#if UINTPTR_MAX > 0xffffffffu
#define BR_DIV64_NATIVE 1
#else
#define BR_DIV64_NATIVE 0
#endif
#endif

/* Frame coherence of the view rule's decisions (core/bt_mesh.c decide_memo;
 * docs/bitree.md "Frame coherence"): 1 = a decision memo entry carries the eye travel
 * up to which it stays valid, so later frames reuse it instead of evaluating the
 * diamond again (16 bytes an entry: the memo's bytes hold half as many; the same
 * meshes); 0 = the memo holds one frame's decisions only (8 bytes an entry). */
#ifndef BR_COHERENCE
#define BR_COHERENCE 1
#endif

/* ------------------------------------------------------------------ raster/ */

/* Which variants of the per-triangle code are compiled (raster/raster_pixel.h): pixel
 * format XRGB8888 / RGB565, depth size 32 / 16 bits, textured frames, and the tests'
 * write-counting variant.  Each left-out variant saves its copy of the triangle code
 * (about 10-20 KB of flash each at -O2; the counting one is left out of the shipped
 * library and compiled by tests/support/raster_count.c); rs_draw_band refuses a frame
 * of a left-out variant with BR_E_UNSUPPORTED.  A board drawing RGB565 with 16-bit
 * depth: -DRS_WITH_888=0 -DRS_WITH_Z32=0 -DRS_WITH_TEX=0.  Pixels: unchanged (a variant
 * is drawn by its own copy or refused). */
#ifndef RS_WITH_888
#define RS_WITH_888 1
#endif
#ifndef RS_WITH_565
#define RS_WITH_565 1
#endif
#ifndef RS_WITH_Z32
#define RS_WITH_Z32 1
#endif
#ifndef RS_WITH_Z16
#define RS_WITH_Z16 1
#endif
#ifndef RS_WITH_TEX
#define RS_WITH_TEX 1
#endif
#ifndef RS_WITH_COUNT
#define RS_WITH_COUNT 0
#endif
/* The variants without a depth buffer (RS_DEPTH_NONE: triangle lists drawn in the
 * caller's back-to-front order, the board's stream path) */
#ifndef RS_WITH_NOZ
#define RS_WITH_NOZ 1
#endif
/* BR_INDEX16 1 makes strip indices 16 bits (br_index: core/bitree.h bt_mesh.strip,
 * raster/raster.h rs_prim.idx): half the strip's RAM on a board, for meshes of at most
 * 65,536 vertices (bt_mesh_init refuses a larger vertex capacity).  A layout, as
 * RS_TEX_FIELDS below: everything linked together must agree.  Pixels: unchanged. */
#ifndef BR_INDEX16
#define BR_INDEX16 0
#endif
#if BR_INDEX16
typedef uint16_t br_index;
#define BR_INDEX_MAX 65535u
#else
typedef uint32_t br_index;
#define BR_INDEX_MAX 4294967295u
#endif
/* RS_TEX_FIELDS 0 drops the texture coordinates from the vertex layouts (raster/raster.h
 * rs_vertex 24 -> 16 bytes, rs_cvert 32 -> 24): RAM a board without textures spends on
 * every vertex of the frame.  A layout, not a variant: everything linked together must
 * agree on it (tests/test_raster_variants.c keeps 1 beside the full library), and it
 * needs RS_WITH_TEX 0.  Pixels: unchanged. */
#ifndef RS_TEX_FIELDS
#define RS_TEX_FIELDS 1
#endif
#if !RS_TEX_FIELDS && RS_WITH_TEX
#error "core/config.h: RS_TEX_FIELDS 0 leaves no texture coordinates: it needs RS_WITH_TEX 0"
#endif
#if !((RS_WITH_888 || RS_WITH_565) && (RS_WITH_Z32 || RS_WITH_Z16))
#error "core/config.h: RS_WITH_* leave no pixel format x depth variant to compile"
#endif

/* The strip pre-pass (raster/raster_prepass.h): the set-up and coverage of a chunk's
 * strip pairs in 16-bit vector lanes (GCC's generic vectors: SSE2 on x86-64, NEON on
 * AArch64), then shading per pair; 0: the per-pair code of targets without vector
 * registers (32-bit ARM without NEON, Cortex-M, other compilers).  Same values, same
 * pixels; costs the pp_soa of a chunk (about 6 KB of stack) and the pre-pass's code.
 * Default: 1 with GCC or clang on little-endian SSE2 / NEON targets.
 * RS_SPANV: the general path's plain spans GS_N pixels at a time in 32-bit vector lanes
 * (raster/raster_general.h); default RS_PREPASS.  Same pixels.  Both need GCC's vector
 * extensions (refused elsewhere).  On big-endian targets they give the same pixels too (the
 * pre-pass gather, the coverage masks' 16-bit halves and the 16-bit pixel widening swap
 * their lanes there; the cross probe runs them on s390x) but are off by default: no
 * big-endian target we build has such vectors. */
#ifndef RS_PREPASS
#if defined(__GNUC__) && (defined(__SSE2__) || defined(__ARM_NEON)) \
    && !(defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__)
#define RS_PREPASS 1
#else
#define RS_PREPASS 0
#endif
#endif
#ifndef RS_SPANV
#define RS_SPANV RS_PREPASS
#endif
#if (RS_PREPASS || RS_SPANV) && !defined(__GNUC__)
#error "core/config.h: RS_PREPASS and RS_SPANV need GCC's vector extensions"
#endif

/* RS_NARROW: triangles of the general path whose box has at most this many columns
 * find each row's span by stepping the edge functions pixel by pixel, wider ones by an
 * exact division per edge (three 64-bit divisions a row).  Both give the same pixels;
 * 8 is the fastest on the peer scene at 640x480 (docs/perf-history.md).  >= 1. */
#ifndef RS_NARROW
#define RS_NARROW 8
#endif
#if RS_NARROW < 1
#error "core/config.h: RS_NARROW must be at least 1"
#endif

/* RS_TINY_W x RS_TINY_H: bounding boxes of at most this many candidate centres take the
 * tiny path (coverage masks in 16-bit lanes, two groups of four columns, four rows
 * unrolled).  Not a free knob: raster_tiny.h's lane bound (every edge value below 2^15)
 * is proved for 8 x 4 and the lane layout is built for it; other values would overflow
 * the lanes and change pixels, so they are refused.
 * RS_SMALL: general-path boxes below this many sub-pixels in both directions use a
 * reciprocal of the area instead of a division (area2 < 2^21 keeps the products below
 * 2^59, raster_general.h); above 2^10 the bound fails, so it is refused. */
#ifndef RS_TINY_W
#define RS_TINY_W 8
#endif
#ifndef RS_TINY_H
#define RS_TINY_H 4
#endif
#if RS_TINY_W != 8 || RS_TINY_H != 4
#error "core/config.h: the tiny path's lane bound holds for RS_TINY_W = 8, RS_TINY_H = 4 only"
#endif
#ifndef RS_SMALL
#define RS_SMALL (1 << 10)
#endif
#if RS_SMALL > (1 << 10) || RS_SMALL < 1
#error "core/config.h: RS_SMALL must be in 1 .. 2^10 (the reciprocal's product bound)"
#endif

/* Set by the Makefile, not by hand: RS_ISA_DISPATCH=1 compiles the baseline copy of the
 * drawing code beside an x86-64-v3 copy (RS_BUILD_V3), chosen at run time by
 * raster/isa.c; RS_TEST_32BIT selects the 32-bit targets' code on a 64-bit host (make
 * test's BR_DIV64_NATIVE=0 build).  Neither changes a pixel (tests/test_isa.c, the
 * div32 tests). */

/* A compile-time assertion in C99 (_Static_assert is C11): an array of negative size
 * when cond is false, so the compiler stops at the line and shows name. */
#define BR_STATIC_ASSERT(cond, name) typedef char br_static_assert_##name[(cond) ? 1 : -1]

/* The code relies on two's complement and arithmetic right shift of negative
 * values (every compiler we target does it; C99 leaves it to the implementation). */
BR_STATIC_ASSERT((-1 >> 1) == -1, arithmetic_right_shift_of_negative_values);
BR_STATIC_ASSERT(sizeof(int) >= 4, int_is_at_least_32_bits);
BR_STATIC_ASSERT(CHAR_BIT == 8, bytes_are_8_bits);

#endif
