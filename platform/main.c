/* platform/main.c — the bitrain program: dispatch to a subcommand. */
#include <stdio.h>
#include <string.h>
#include "platform/cmd.h"
#include "platform/load.h"

/* The release; `bitrain --version` prints it. */
#define BR_VERSION "0.6.0"

static const struct { const char *name; int (*fn)(int, char **); const char *usage; } cmds[] = {
    { "info",      cmd_info,      "info [--json] [--merge] FILE...      size, heights, voids, spacing, origin" },
    { "hillshade", cmd_hillshade, "hillshade IN... -o OUT.png            shaded relief (gdaldem defaults)" },
    { "mesh",      cmd_mesh,      "mesh IN... --max-error M -o OUT.obj   export the bitree mesh (obj, ply, stl)" },
    { "render",    cmd_render,    "render IN... -o OUT.png [options]     draw one frame headless" },
    { "view",      cmd_view,      "view IN...                            interactive viewer (SDL2 window)" },
    { "bench",     cmd_bench,     "bench --scene peer [options]          render the benchmark scene" },
    { "run",       cmd_run,       "run [IN...]                           what `make run` does" },
};

static void usage(FILE *f)
{
    size_t i;
    fprintf(f, "usage: bitrain COMMAND [ARGS]\n\ncommands:\n");
    for (i = 0; i < sizeof cmds / sizeof cmds[0]; i++) fprintf(f, "  bitrain %s\n", cmds[i].usage);
    fprintf(f, "\n`bitrain COMMAND --help` for a command's options; `bitrain --version` for the release.\n");
}

static void note(const char *name, const char *msg) { fprintf(stderr, "bitrain: %s: %s\n", name, msg); }

int main(int argc, char **argv)
{
    size_t i;
    dem_set_note(note);
    if (argc < 2) { usage(stderr); return 2; }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "version")) {
        printf("bitrain %s\n", BR_VERSION);
        return 0;
    }
    if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (i = 0; i < sizeof cmds / sizeof cmds[0]; i++)
        if (!strcmp(argv[1], cmds[i].name)) return cmds[i].fn(argc - 2, argv + 2);
    fprintf(stderr, "bitrain: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
