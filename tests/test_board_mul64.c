/* tests/test_board_mul64.c — board_mul64 (platform/board/mul64.c), the C form of the
 * Cortex-M0+ board's 64-bit multiply, gives the low 64 bits of every product: the
 * operands whose 16-bit halves make the middle sum carry, and a million pseudo-random
 * pairs, against the host's own multiply.  (The board checks its Thumb-1 __aeabi_lmul
 * against board_mul64 at start-up: platform/board/mcu_main.c.) */
#include "tests/test.h"
#include "platform/board/mul64.c"

static uint64_t next(uint64_t *x)
{
    *x ^= *x << 13;
    *x ^= *x >> 7;
    *x ^= *x << 17;
    return *x;
}

static void test_edges(void)
{
    static const uint64_t v[] = { 0, 1, 2, 0xffffu, 0x10000u, 0x1ffffu, 0xffff0000u, 0xffffffffu, 0x100000000ull,
                                  0x7fffffffu, 0x80000000u, 0xffffffff00000000ull, 0x7fffffffffffffffull,
                                  0x8000000000000000ull, 0xffffffffffffffffull, 0xffff0000ffff0000ull,
                                  0x0000ffff0000ffffull, 0xfffffffffffffffeull };
    size_t i, j, bad = 0;
    for (i = 0; i < sizeof v / sizeof v[0]; i++)
        for (j = 0; j < sizeof v / sizeof v[0]; j++) bad += board_mul64(v[i], v[j]) != v[i] * v[j];
    CHECK_EQ(bad, 0);
}

static void test_random(void)
{
    uint64_t x = 0x9e3779b97f4a7c15ull, a, b;
    size_t i, bad = 0;
    for (i = 0; i < 1000000; i++) {
        a = next(&x);
        b = next(&x);
        if (i & 1) b >>= 32;                    /* a 32-bit operand, as most of the board's are */
        if (i & 2) a = (uint64_t)(int64_t)(int32_t)a;   /* a sign-extended one */
        bad += board_mul64(a, b) != a * b;
    }
    CHECK_EQ(bad, 0);
}

int main(void)
{
    T_RUN(test_edges);
    T_RUN(test_random);
    return t_finish();
}
