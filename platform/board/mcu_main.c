/* platform/board/mcu_main.c — the bare-metal board main (Cortex-M0+ / Cortex-M3, no C
 * library): start-up, the frames of board.h, output through semihosting (the debug
 * probe's console; QEMU's -semihosting).  Prints
 *   mcu frame N checksum: XXXXXXXX
 * for each frame (`make mcu` compares them with the desktop build's; a frame whose
 * checksum is not the one baked from the product's frame path fails here), a line of mesh
 * figures per frame, the RAM each part takes and the stack's high-water mark, then exits
 * through semihosting (status 0, or 1 after a failure).
 *
 * The stack is painted with a pattern at reset, from its limit (the linker script's
 * __stack_limit) to just below the reset handler's own frame; after the frames the
 * lowest word no longer holding the pattern is the high-water mark.
 *
 * With the semihosting command line "init" (QEMU: -semihosting-config arg=...,arg=init) it
 * stops after the set-up: `make mcu` counts the instructions of both runs, and their
 * difference over the frames is the frames' cost. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "platform/board/board.h"
#include "platform/board/mul64.h"

#ifndef BOARD_ARENA
#error "platform/board/mcu_main.c: BOARD_ARENA (bytes of the board's arena, make mcu sets it) is required"
#endif

extern uint32_t __data_load[], __data_start[], __data_end[], __bss_start[], __bss_end[];
extern uint32_t __stack_limit[], __stack_top[];

#define PAINT 0xa5c3a5c3u
enum { SYS_WRITE0 = 0x04, SYS_GET_CMDLINE = 0x15, SYS_EXIT = 0x18 };
#define ADP_EXIT_OK 0x20026u        /* ADP_Stopped_ApplicationExit */
#define ADP_EXIT_ERR 0x20023u       /* ADP_Stopped_RunTimeErrorUnknown */

static uint64_t arena[(BOARD_ARENA + 7) / 8];

static int semihost(int op, void *arg)
{
    register int r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

/* ---- output: one line at a time, numbers formatted here (no printf) */
static char line[160];
static size_t len;

static void out_s(const char *s)
{
    while (*s && len + 1 < sizeof line) line[len++] = *s++;
}

static void out_u(uint32_t v)
{
    char b[11];
    int n = 0;
    do { b[n++] = (char)('0' + v % 10); v /= 10; } while (v);
    while (n && len + 1 < sizeof line) line[len++] = b[--n];
}

static void out_x(uint32_t v)
{
    int i;
    for (i = 28; i >= 0; i -= 4) {
        char c[2] = { "0123456789abcdef"[(v >> i) & 15], 0 };
        out_s(c);
    }
}

static void out_end(void)
{
    line[len++] = '\n';
    line[len] = 0;
    semihost(SYS_WRITE0, line);
    len = 0;
}

static __attribute__((noreturn)) void stop(int ok)
{
    semihost(SYS_EXIT, (void *)(uintptr_t)(ok ? ADP_EXIT_OK : ADP_EXIT_ERR));
    for (;;) {}
}

/* 1 when the semihosting command line ends in the word "init" */
static int init_only(void)
{
    static char cmd[96];
    struct { char *p; int n; } blk = { cmd, (int)sizeof cmd - 1 };
    size_t n = 0;
    if (semihost(SYS_GET_CMDLINE, &blk) != 0) return 0;
    cmd[sizeof cmd - 1] = 0;
    while (cmd[n]) n++;
    return n >= 4 && !memcmp(cmd + n - 4, "init", 4);
}

/* 1 when the Thumb-1 __aeabi_lmul (mul64.c), which every 64-bit product of core/ and
 * raster/ calls on the M0+, agrees with board_mul64 (the C form the host tests against its
 * own multiply) on 4,096 products of pseudo-random operands, half of them 32-bit; 1 on
 * cores that multiply in hardware.  Both runs of `make mcu` do it, so it is not counted
 * in a frame's instructions. */
#if defined(__ARM_ARCH_6M__)
static uint64_t xorshift64(uint64_t *x)
{
    *x ^= *x << 13;
    *x ^= *x >> 7;
    *x ^= *x << 17;
    return *x;
}
#endif

static int lmul_ok(void)
{
#if defined(__ARM_ARCH_6M__)
    uint64_t x = 0x9e3779b97f4a7c15ull, a, b;
    int i;
    for (i = 0; i < 4096; i++) {
        a = xorshift64(&x);
        b = xorshift64(&x);
        if (i & 1) b >>= 32;
        if (a * b != board_mul64(a, b)) return 0;
    }
#endif
    return 1;
}

static int run(void)
{
    size_t size[BP_N], total = 0;
    int32_t i;
    int p;
    br_status st;
    if (!lmul_ok()) { out_s("mcu: __aeabi_lmul differs from board_mul64"); out_end(); return 0; }
    st = board_init(arena, sizeof arena, size);
    for (p = 0; p < BP_N; p++) {
        if (!*board_part_name(p)) continue;     /* a part this path does not have */
        out_s("mcu ram: "); out_s(board_part_name(p)); out_s(": "); out_u((uint32_t)size[p]); out_s(" bytes"); out_end();
        total += size[p];
    }
    out_s("mcu ram: board state (static): "); out_u((uint32_t)board_state_size()); out_s(" bytes"); out_end();
    if (st != BR_OK) {
        out_s("mcu: set-up failed (status "); out_u((uint32_t)st); out_s("), arena needs "); out_u((uint32_t)total);
        out_s(" bytes, has "); out_u((uint32_t)sizeof arena); out_end();
        return 0;
    }
    if (init_only()) { out_s("mcu: set-up only"); out_end(); return 1; }
    for (i = 0; i < board_frames(); i++) {
        board_frame_info fi;
        st = board_frame(i, NULL, NULL, &fi);
        if (st != BR_OK) { out_s("mcu: frame "); out_u((uint32_t)i); out_s(" failed, status "); out_u((uint32_t)st); out_end(); return 0; }
        out_s("mcu frame "); out_u((uint32_t)i); out_s(" checksum: "); out_x(fi.sum); out_end();
        if (fi.sum != fi.expect) {
            out_s("mcu frame "); out_u((uint32_t)i); out_s(": differs from the host library's "); out_x(fi.expect);
            out_end();
            return 0;
        }
        out_s("mcu frame "); out_u((uint32_t)i); out_s(": ");
        if (fi.ns) {
            out_u(fi.ntri); out_s(" triangles, "); out_u(fi.nv); out_s(" vertices, "); out_u(fi.ns);
            out_s(" strip indices, ");
        } else { out_u(fi.ntri); out_s(" triangle set-ups in bands, "); }
        out_u(fi.pixels); out_s(" pixels");
        if (fi.overflow) out_s(", budget fallback");
        out_end();
    }
    return 1;
}

static void stack_report(void)
{
    const uint32_t *w = __stack_limit;
    while (w < __stack_top && *w == PAINT) w++;
    out_s("mcu stack: "); out_u((uint32_t)((uintptr_t)__stack_top - (uintptr_t)w)); out_s(" of ");
    out_u((uint32_t)((uintptr_t)__stack_top - (uintptr_t)__stack_limit)); out_s(" bytes used (high-water mark)");
    out_end();
}

void board_reset(void);
void board_fault(void);

__attribute__((noreturn, used)) void board_reset(void)
{
    uint32_t *p, *s;
    int ok;
    for (p = __data_start, s = __data_load; p < __data_end;) *p++ = *s++;
    for (p = __bss_start; p < __bss_end;) *p++ = 0;
    __asm__ volatile("mov %0, sp" : "=r"(s));
    for (p = __stack_limit; p + 16 < s;) *p++ = PAINT;   /* below this frame, with a margin */
    ok = run();
    stack_report();
    stop(ok);
}

__attribute__((noreturn, used)) void board_fault(void)
{
    len = 0;
    out_s("mcu: hard fault");
    out_end();
    stop(0);
}

/* Cortex-M vector table: initial stack pointer, reset, NMI, hard fault (the M3's other
 * faults escalate to it when not enabled). */
__attribute__((section(".vectors"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))(uintptr_t)__stack_top, board_reset, board_fault, board_fault,
    board_fault, board_fault, board_fault, 0, 0, 0, 0, board_fault, board_fault, 0, board_fault, board_fault
};
