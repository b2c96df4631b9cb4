/* platform/board/mul64.c — the 64-bit multiply GCC calls for every 64-bit product on
 * ARMv6-M (the Cortex-M0+: MULS keeps only the low 32 bits of a 32 x 32 product), the
 * run-time ABI's __aeabi_lmul (RTABI 4.2): the low 64 bits of a b, which signed and
 * unsigned operands share.  libgcc's version is C that keeps r4 to r9; this one is
 * Thumb-1 that needs only r4 and r5 (its cost: docs/perf-history.md).  board_mul64 is the
 * same product in C, which the board checks it against at start-up (mcu_main.c) and the
 * host against its own 64-bit multiply (tests/test_board_mul64.c).
 *
 * With al bl = a1 b1 2^32 + (a1 b0 + a0 b1) 2^16 + a0 b0 (a1 a0, b1 b0 the 16-bit halves
 * of al, bl): mid first takes a1 b0 and the high half of a0 b0, at most (2^16 - 1)^2 +
 * 2^16 - 1 < 2^32, then a0 b1, whose carry out is worth 2^48; the cross terms ah bl and
 * al bh count only mod 2^32, at 2^32. */
#include <stdint.h>
#include "platform/board/mul64.h"

uint64_t board_mul64(uint64_t a, uint64_t b)
{
    const uint32_t al = (uint32_t)a, bl = (uint32_t)b;
    const uint32_t a0 = al & 0xffffu, a1 = al >> 16, b0 = bl & 0xffffu, b1 = bl >> 16;
    const uint32_t lo = a0 * b0, t = a0 * b1;
    uint32_t mid = a1 * b0 + (lo >> 16);
    uint32_t hi = a1 * b1 + (uint32_t)(a >> 32) * bl + al * (uint32_t)(b >> 32);
    mid += t;
    hi += (mid >> 16) + ((uint32_t)(mid < t) << 16);
    return (uint64_t)hi << 32 | (mid << 16 | (lo & 0xffffu));
}

#if defined(__ARM_ARCH_6M__)
/* a in r0 (low), r1; b in r2, r3; the product in r0, r1 */
__attribute__((naked)) uint64_t __aeabi_lmul(uint64_t a __attribute__((unused)), uint64_t b __attribute__((unused)))
{
    __asm__(
        ".syntax unified\n\t"
        "push {r4, r5, lr}\n\t"
        "muls r1, r2\n\t"           /* ah bl */
        "muls r3, r0\n\t"           /* bh al */
        "adds r1, r1, r3\n\t"       /* the cross terms, mod 2^32 */
        "uxth r4, r0\n\t"           /* a0 */
        "lsrs r0, r0, #16\n\t"      /* a1 */
        "uxth r5, r2\n\t"           /* b0 */
        "lsrs r2, r2, #16\n\t"      /* b1 */
        "movs r3, r4\n\t"
        "muls r3, r5\n\t"           /* lo = a0 b0 */
        "muls r4, r2\n\t"           /* t = a0 b1 */
        "muls r2, r0\n\t"           /* a1 b1 */
        "muls r0, r5\n\t"           /* a1 b0 */
        "lsrs r5, r3, #16\n\t"
        "adds r0, r0, r5\n\t"       /* mid = a1 b0 + lo >> 16: no carry */
        "adds r0, r0, r4\n\t"       /* mid += t: carry C */
        "movs r5, #0\n\t"           /* (MOVS #imm leaves C) */
        "adcs r5, r5\n\t"           /* C */
        "lsls r5, r5, #16\n\t"
        "lsrs r4, r0, #16\n\t"
        "adds r2, r2, r4\n\t"
        "adds r2, r2, r5\n\t"       /* a1 b1 + mid >> 16 + C 2^16 */
        "lsls r0, r0, #16\n\t"
        "uxth r3, r3\n\t"
        "orrs r0, r3\n\t"           /* low word: mid << 16 | lo & 0xffff */
        "adds r1, r1, r2\n\t"       /* high word */
        "pop {r4, r5, pc}\n\t");
}
#endif
