/* platform/dem_args.c — see dem_args.h. */
#include "platform/dem_args.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int num_arg(const char *cmd, const char *opt, const char *v, double *out)
{
    char *end;
    if (!v) { fprintf(stderr, "bitrain %s: %s needs a value\n", cmd, opt); return -1; }
    *out = strtod(v, &end);
    if (end == v || *end || *out != *out || *out > 1e9 || *out < -1e9) {
        fprintf(stderr, "bitrain %s: %s: '%s' is not a usable number\n", cmd, opt, v);
        return -1;
    }
    return 1;
}

int dem_args_parse(dem_opts *o, int argc, char **argv, int *i, const char *cmd)
{
    const char *a = argv[*i], *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (!strcmp(a, "--xyz-depth")) { o->xyz_depth = 1; return 1; }
    /* voids (platform/fill.h) */
    if (!strcmp(a, "--fill-voids")) { o->fill_voids = 1; return 1; }
    if (!strcmp(a, "--scale") || !strcmp(a, "--offset")) {
        int r = num_arg(cmd, a, v, a[2] == 's' ? &o->png_scale : &o->png_offset);
        if (r > 0) (*i)++;
        return r;
    }
    if (!strcmp(a, "--png-encoding")) {
        if (v && (!strcmp(v, "grey") || !strcmp(v, "gray"))) o->png_encoding = DEM_PNG_GREY;
        else if (v && !strcmp(v, "terrain-rgb")) o->png_encoding = DEM_PNG_TERRAIN_RGB;
        else if (v && !strcmp(v, "terrarium")) o->png_encoding = DEM_PNG_TERRARIUM;
        else {
            fprintf(stderr, "bitrain %s: --png-encoding must be grey, terrain-rgb or terrarium\n", cmd);
            return -1;
        }
        (*i)++;
        return 1;
    }
    return 0;
}
