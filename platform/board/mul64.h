/* platform/board/mul64.h — see mul64.c. */
#ifndef BR_BOARD_MUL64_H
#define BR_BOARD_MUL64_H
#include <stdint.h>

/* The low 64 bits of a b (of either signedness), in 32-bit multiplies only. */
uint64_t board_mul64(uint64_t a, uint64_t b);
#if defined(__ARM_ARCH_6M__)
uint64_t __aeabi_lmul(uint64_t a, uint64_t b);      /* the same, in Thumb-1 */
#endif

#endif
