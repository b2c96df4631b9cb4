/* platform/scene_args.c — see scene_args.h. */
#include "platform/scene_args.h"
#include <string.h>

void scene_args_table(scene_args *a, scene_opts *o, opt_spec t[SCENE_ARGS_N])
{
    const opt_spec src[SCENE_ARGS_N] = {
        { "--colors", OPT_STR, &o->colors, 0, 0, 0, NULL, "FILE", "gdaldem color-relief file (default: built-in ramp)", NULL },
        { "--texture", OPT_STR, &o->texture, 0, 0, 0, NULL, "PNG", "colour map / orthophoto over the whole grid", NULL },
        { "--tree", OPT_STR, &o->tree, 0, 0, 0, NULL, "FILE", "attach the bitree saved by `bitrain mesh --save-tree` instead of building it", NULL },
        { "--sun", OPT_NUMS, a->sun, 0, 360, 2, NULL, "AZ,ALT", "sun azimuth and altitude, degrees (default 315,45)",
          &a->sun_seen },
        { "--ambient", OPT_NUM, &o->ambient, 0, 1, 0, NULL, "A", "ambient light (default 0.3)", &a->ambient_seen },
        { "--zscale", OPT_NUM, &o->zscale, 0.001, 1000, 0, NULL, "F",
          "vertical exaggeration (default 1, or automatic without a georeference)", NULL },
        OPT_END
    };
    memset(a, 0, sizeof *a);
    a->o = o;
    memcpy(t, src, sizeof src);
}

int scene_args_finish(scene_args *a, const char *cmd)
{
    if (a->sun_seen) {
        if (a->sun[1] > 90) return opt_fail(cmd, "--sun", "altitude %g is out of range (accepted: 0..90)", a->sun[1]);
        if (a->sun[0] == 0 && a->sun[1] == 0) a->sun[0] = 360;   /* 0,0 is a sun on the horizon in the north, not "default" */
        a->o->sun_az = a->sun[0];
        a->o->sun_alt = a->sun[1];
    }
    a->o->ambient_set = a->ambient_seen;
    return OPT_OK;
}
