/* platform/water_args.c — the water and atmosphere options as one option table
 * (platform/opt.h); see water_scene.h. */
#include <string.h>
#include "platform/water_scene.h"

void ws_args_table(ws_args *a, ws_opts *o, opt_spec t[WS_ARGS_N])
{
    const opt_spec src[WS_ARGS_N] = {
        { "--no-water", OPT_FLAG, &o->no_water, 0, 0, 0, NULL, NULL, "no water (default: found automatically)", NULL },
        { "--water-level", OPT_NUM, &o->level_m, -1e6, 1e6, 0, NULL, "M", "water everywhere at or below M metres",
          &o->have_level },
        { "--water", OPT_STR, &o->water_file, 0, 0, 0, NULL, "FILE",
          "water surface heights, nodata where dry (grid of the terrain's size)", NULL },
        { "--fog", OPT_FLAG, &a->fog, 0, 0, 0, NULL, NULL, "distance fog and sky gradient (default)", NULL },
        { "--no-fog", OPT_FLAG, &o->no_fog, 0, 0, 0, NULL, NULL, "no fog, flat sky", NULL },
        { "--time", OPT_NUM, &o->time_s, -1e6, 1e6, 0, NULL, "T", "the instant of the waves, seconds (render: default 0; view: default the clock)", &a->time_seen },
        { "--reflection", OPT_CHOICE, &a->refl, 0, 0, 0, "full|half|quarter|none", "R",
          "reflection resolution (default half)", &a->refl_seen },
        { "--reflection-error", OPT_NUM, &o->refl_err, 0, 64, 0, NULL, "F",
          "the reflection's own LOD at F times --pixel-error, F >= 1, or 0: the terrain's mesh (default 4)",
          &a->refl_err_seen },
        OPT_END
    };
    memset(a, 0, sizeof *a);
    a->o = o;
    o->refl_err = WS_REFL_ERR;
    memcpy(t, src, sizeof src);
}

int ws_args_finish(ws_args *a, const char *cmd)
{
    if (a->fog && a->o->no_fog) return opt_fail(cmd, "--fog", "cannot be used with --no-fog");
    if (a->refl_seen) a->o->reflection = a->refl + 1;
    if (a->o->refl_err > 0 && a->o->refl_err < 1)
        return opt_fail(cmd, "--reflection-error", "is 0 (the terrain's mesh) or at least 1");
    if ((a->o->have_level != 0) + (a->o->water_file != NULL) + (a->o->no_water != 0) > 1)
        return opt_fail(cmd, "--water", "--water, --water-level and --no-water exclude each other");
    return OPT_OK;
}
