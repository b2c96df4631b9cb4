/* platform/cmd_view.c — bitrain view (not built yet). */
#include <stdio.h>
#include "platform/cmd.h"

int cmd_view(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "bitrain view: not implemented yet\n");
    return 1;
}
