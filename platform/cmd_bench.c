/* platform/cmd_bench.c — bitrain bench (not built yet). */
#include <stdio.h>
#include "platform/cmd.h"

int cmd_bench(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "bitrain bench: not implemented yet\n");
    return 1;
}
