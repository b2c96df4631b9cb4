/* platform/cmd_hillshade.c — bitrain hillshade (not built yet). */
#include <stdio.h>
#include "platform/cmd.h"

int cmd_hillshade(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "bitrain hillshade: not implemented yet\n");
    return 1;
}
