/* platform/cmd_run.c — bitrain run (not built yet). */
#include <stdio.h>
#include "platform/cmd.h"

int cmd_run(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "bitrain run: not implemented yet\n");
    return 1;
}
