/* platform/cmd_mesh.c — bitrain mesh (not built yet). */
#include <stdio.h>
#include "platform/cmd.h"

int cmd_mesh(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "bitrain mesh: not implemented yet\n");
    return 1;
}
