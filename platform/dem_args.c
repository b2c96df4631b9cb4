/* platform/dem_args.c — see dem_args.h. */
#include "platform/dem_args.h"
#include <string.h>

/* the choices in DEM_PNG_* order, then the American spelling of grey */
#define PNG_ENCODINGS "auto|grey|terrain-rgb|terrarium|gray"
#define PNG_GRAY_INDEX 4

void dem_args_table(dem_opts *o, opt_spec t[DEM_ARGS_N])
{
    const opt_spec src[DEM_ARGS_N] = {
        { "--png-encoding", OPT_CHOICE, &o->png_encoding, 0, 0, 0, PNG_ENCODINGS, "E",
          "how PNG pixels hold heights (auto: grey PNGs grey, colour ones terrain-RGB)", NULL },
        { "--scale", OPT_NUM, &o->png_scale, -1e9, 1e9, 0, NULL, "S", "grey PNG: metres = raw * S + O", NULL },
        { "--offset", OPT_NUM, &o->png_offset, -1e9, 1e9, 0, NULL, "O", "grey PNG: metres added after scaling", NULL },
        { "--xyz-depth", OPT_FLAG, &o->xyz_depth, 0, 0, 0, NULL, NULL, "XYZ: third column is depth (positive down)", NULL },
        OPT_END
    };
    memcpy(t, src, sizeof src);
}

void dem_args_finish(dem_opts *o)
{
    if (o->png_encoding == PNG_GRAY_INDEX) o->png_encoding = DEM_PNG_GREY;
}
