/* platform/dem_args.c — see dem_args.h. */
#include "platform/dem_args.h"
#include <stdio.h>
#include <math.h>
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
    if (!strcmp(a, "--scale") || !strcmp(a, "--offset")) {
        int r = num_arg(cmd, a, v, a[2] == 's' ? &o->png_scale : &o->png_offset);
        if (r > 0) (*i)++;
        return r;
    }
    if (!strcmp(a, "--nodata")) {
        char *end;
        double d;
        if (!v) { fprintf(stderr, "bitrain %s: --nodata needs a value\n", cmd); return -1; }
        d = strtod(v, &end);
        if (end == v || *end || isinf(d) || (d != d && strcmp(v, "nan") && strcmp(v, "NaN"))) {
            fprintf(stderr, "bitrain %s: --nodata: '%s' is not usable: give a finite number (the void "
                            "marker as the file stores it) or nan\n", cmd, v);
            return -1;
        }
        o->has_nodata = 1;
        o->nodata = d;
        (*i)++;
        return 1;
    }
    if (!strcmp(a, "--merge-prefer")) {
        if (v && !strcmp(v, "first")) o->merge_prefer = DEM_MERGE_FIRST;
        else if (v && !strcmp(v, "last")) o->merge_prefer = DEM_MERGE_LAST;
        else {
            fprintf(stderr, "bitrain %s: --merge-prefer: '%s' is not usable: give first or last\n", cmd,
                    v ? v : "(missing)");
            return -1;
        }
        (*i)++;
        return 1;
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
