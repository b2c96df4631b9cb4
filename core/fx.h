/* core/fx.h — fixed-point helpers shared by core/ and raster/.
 *
 * Q formats used across modules (one typedef each, with its range):
 *   fx_q14:  Q1.14 in int32, unit vectors and weights, [-2, 2)      ONE = FX_Q14_ONE
 *   fx_q16:  Q15.16 in int32, general fractions, [-32768, 32768)     ONE = FX_Q16_ONE
 *   fx_q30:  Q1.30 in int32, precise unit vectors, [-2, 2)          ONE = FX_Q30_ONE
 * Multiplies go through helpers with a 64-bit intermediate.  Right shifts of
 * negative values are arithmetic (asserted once in core/config.h). */
#ifndef BR_FX_H
#define BR_FX_H
#include <stdint.h>
#include "core/config.h"

typedef int32_t fx_q14;
typedef int32_t fx_q16;
typedef int32_t fx_q30;
#define FX_Q14_ONE ((fx_q14)1 << 14)
#define FX_Q16_ONE ((fx_q16)1 << 16)
#define FX_Q30_ONE ((fx_q30)1 << 30)

/* (a * b) >> s, rounded to nearest (ties up), 64-bit intermediate. */
static inline int32_t fx_mul_shift(int32_t a, int32_t b, int s)
{
    int64_t p = (int64_t)a * b;
    return (int32_t)((p + ((int64_t)1 << (s - 1))) >> s);
}

/* floor(sqrt(v)) for v >= 0; exact for every uint64. */
uint32_t fx_isqrt64(uint64_t v);

#endif
