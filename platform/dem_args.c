/* platform/dem_args.c — see dem_args.h. */
#include "platform/dem_args.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the choices in DEM_PNG_* order, then the American spelling of grey */
#define PNG_ENCODINGS "auto|grey|terrain-rgb|terrarium|gray"
#define PNG_GRAY_INDEX 4

void dem_args_table(dem_args *a, dem_opts *o, opt_spec t[DEM_ARGS_N])
{
    const opt_spec src[DEM_ARGS_N] = {
        { "--png-encoding", OPT_CHOICE, &o->png_encoding, 0, 0, 0, PNG_ENCODINGS, "E",
          "how PNG pixels hold heights (auto: grey PNGs grey, colour ones terrain-RGB)", NULL },
        { "--scale", OPT_NUM, &o->png_scale, -1e9, 1e9, 0, NULL, "S", "grey PNG: metres = raw * S + O", NULL },
        { "--offset", OPT_NUM, &o->png_offset, -1e9, 1e9, 0, NULL, "O", "grey PNG: metres added after scaling", NULL },
        { "--xyz-depth", OPT_FLAG, &o->xyz_depth, 0, 0, 0, NULL, NULL, "XYZ, GeoClaw: values are depths (positive down)", NULL },
        { "--nodata", OPT_STR, &a->nodata, 0, 0, 0, NULL, "V",
          "samples equal to V (as the file stores it, or nan) are voids too", NULL },
        { "--merge-prefer", OPT_CHOICE, &a->merge_choice, 0, 0, 0, "none|first|last", "F",
          "where merged tiles disagree, that file's height wins (default none: refuse)", NULL },
        { "--fill-voids", OPT_FLAG, &o->fill_voids, 0, 0, 0, NULL, NULL,
          "fill voids from their borders, as gdal_fillnodata (default: voids are holes)", NULL },
        OPT_END
    };
    memset(a, 0, sizeof *a);
    a->o = o;
    memcpy(t, src, sizeof src);
}

int dem_args_finish(dem_args *a, const char *cmd)
{
    dem_opts *o = a->o;
    if (o->png_encoding == PNG_GRAY_INDEX) o->png_encoding = DEM_PNG_GREY;
    if (a->merge_choice == 1) o->merge_prefer = DEM_MERGE_FIRST;
    else if (a->merge_choice == 2) o->merge_prefer = DEM_MERGE_LAST;
    if (a->nodata) {
        char *end;
        double d = strtod(a->nodata, &end);
        if (end == a->nodata || *end || isinf(d) || (d != d && strcmp(a->nodata, "nan") && strcmp(a->nodata, "NaN")))
            return opt_fail(cmd, "--nodata", "'%s' is not usable: give a finite number (the void marker as "
                            "the file stores it) or nan", a->nodata);
        o->has_nodata = 1;
        o->nodata = d;
    }
    return OPT_OK;
}
