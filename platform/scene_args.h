/* platform/scene_args.h — the look options of every command that draws a scene (render,
 * view, run), as one option table (platform/opt.h), so that they accept the same ones:
 *   --colors FILE     gdaldem color-relief file instead of the built-in ramp
 *   --texture PNG     colour map / orthophoto stretched over the whole grid
 *   --sun AZ,ALT      sun azimuth (clockwise from north) and altitude, degrees
 *   --ambient A       ambient light 0..1
 *   --zscale F        vertical exaggeration */
#ifndef BR_SCENE_ARGS_H
#define BR_SCENE_ARGS_H
#include "platform/opt.h"
#include "platform/scene.h"

#define SCENE_ARGS_N 7  /* entries of the table, OPT_END included */

typedef struct scene_args {
    scene_opts *o;
    double sun[2];
    int sun_seen, ambient_seen;
} scene_args;

/* Fills t with the look options writing into a (which writes into *o on finish). */
void scene_args_table(scene_args *a, scene_opts *o, opt_spec t[SCENE_ARGS_N]);
/* After opt_parse: copies the parsed values into the scene options; OPT_ERR (with a
 * message naming cmd) when they do not fit together. */
int scene_args_finish(scene_args *a, const char *cmd);

#endif
