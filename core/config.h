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

/* The code relies on two's complement and arithmetic right shift of negative
 * values (every compiler we target does it; C99 leaves it to the implementation). */
_Static_assert((-1 >> 1) == -1, "arithmetic right shift of negative values required");
_Static_assert(sizeof(int) >= 4, "int must be at least 32 bits");
_Static_assert(CHAR_BIT == 8, "8-bit bytes required");

#endif
