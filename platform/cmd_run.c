/* platform/cmd_run.c — bitrain run [IN...]: what `make run` does.
 *
 * Shows the terrain (default: the bundled Lake Constance tile) in the viewer
 * when there is a display; without one (no DISPLAY/WAYLAND_DISPLAY, or SDL
 * cannot open it) renders one 3D frame to out/terrain.png and prints the path. */
#include <SDL.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "platform/assets.h"
#include "platform/cmd.h"

#define RUN_PNG "out/terrain.png"

static int have_display(void)
{
    const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
    int ok;
    if ((!x || !*x) && (!wl || !*wl)) return 0;
    ok = SDL_Init(SDL_INIT_VIDEO) == 0;
    SDL_Quit();
    return ok;
}

int cmd_run(int argc, char **argv)
{
    char *args[80];
    char def[] = ASSET_DEFAULT_DEM, o[] = "-o", png[] = RUN_PNG, size[] = "--size", wh[] = "1280x720";
    int n = 0, i;
    if (argc > 64) { fprintf(stderr, "bitrain run: too many files\n"); return 2; }
    if (argc == 0) args[n++] = def;
    for (i = 0; i < argc; i++) args[n++] = argv[i];
    if (have_display()) return cmd_view(n, args);
    printf("bitrain run: no display here; rendering one frame to %s instead\n", RUN_PNG);
    mkdir("out", 0777);
    args[n++] = o; args[n++] = png; args[n++] = size; args[n++] = wh;
    return cmd_render(n, args);
}
