/* core/fx.c — see fx.h. */
#include "core/fx.h"

uint32_t fx_isqrt64(uint64_t v)
{
    /* bit-by-bit method: one result bit per iteration, exact, no division */
    uint64_t res = 0, bit = (uint64_t)1 << 62;
    while (bit > v) bit >>= 2;
    while (bit) {
        if (v >= res + bit) { v -= res + bit; res = (res >> 1) + bit; }
        else res >>= 1;
        bit >>= 2;
    }
    return (uint32_t)res;
}
