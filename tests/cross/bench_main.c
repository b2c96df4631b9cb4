/* tests/cross/bench_main.c — `bitrain bench --scene default` (platform/bench_default.c)
 * as a program of its own, for targets built without a display: tests/cross/div64.sh
 * runs the product's frame with water, fog and sky under qemu-arm with it.
 *
 *   bench_main --scene default [bench's options]   (`bitrain bench --scene default --help`) */
#include "platform/cmd.h"

int main(int argc, char **argv)
{
    return cmd_bench_default(argc - 1, argv + 1);
}
