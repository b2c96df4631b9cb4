/* platform/cmd_render.c — bitrain render (not built yet). */
#include <stdio.h>
#include "platform/cmd.h"

int cmd_render(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "bitrain render: not implemented yet\n");
    return 1;
}
