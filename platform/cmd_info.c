/* platform/cmd_info.c — bitrain info (not built yet). */
#include <stdio.h>
#include "platform/cmd.h"

int cmd_info(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "bitrain info: not implemented yet\n");
    return 1;
}
