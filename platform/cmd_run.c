/* platform/cmd_run.c — bitrain run [IN...]: what `make run` does.
 *
 * Shows the terrain (default: the bundled Lake Constance tile).  Until the 3D
 * view lands this writes a shaded-relief PNG into out/ and prints its path. */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include "platform/cmd.h"
#include "platform/hillshade.h"
#include "platform/load.h"

#define RUN_DEFAULT_DEM "assets/N47E009.hgt.gz"

int cmd_run(int argc, char **argv)
{
    const char *def = RUN_DEFAULT_DEM;
    const char *const *in = argc > 0 ? (const char *const *)argv : &def;
    int n = argc > 0 ? argc : 1;
    const char *out = "out/terrain_hillshade.png";
    dem_opts o;
    hf f;
    br_err err;
    fx_q14 l[3];
    memset(&o, 0, sizeof o);
    if (dem_load_many(in, n, &o, &f, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); return 1; }
    mkdir("out", 0777);
    hillshade_light(315, 45, l);
    if (hillshade_write_png(&f, l, out, &err) != BR_OK) {
        fprintf(stderr, "bitrain: %s\n", err.msg);
        dem_free(&f);
        return 1;
    }
    printf("bitrain: %dx%d heightfield from %s%s; shaded relief written to %s\n",
           f.w, f.h, in[0], n > 1 ? " (merged)" : "", out);
    dem_free(&f);
    return 0;
}
