/* platform/dem_args.h — the reader flags every command that reads DEM files
 * accepts (info, hillshade, mesh, render, view, run), parsed in one place:
 *   --png-encoding grey|terrain-rgb|terrarium   how PNG pixels hold heights
 *   --scale S, --offset O                       grey PNG: metres = raw * S + O
 *   --xyz-depth                                 XYZ: third column is depth (positive down)
 *   --fill-voids                                fill voids from their borders (platform/fill.h)
 * (`info` also accepts --depth for --xyz-depth.) */
#ifndef BR_DEM_ARGS_H
#define BR_DEM_ARGS_H
#include "platform/load.h"

#define DEM_ARGS_USAGE \
    "  reader flags: --png-encoding grey|terrain-rgb|terrarium, --scale S --offset O (grey PNG:\n" \
    "    metres = raw * S + O), --xyz-depth (XYZ third column is depth, positive down),\n" \
    "    --fill-voids (voids take the inverse-distance mean of the valid samples around them)\n"

/* If argv[*i] is a reader flag, applies it to o (consuming its value, *i advanced)
 * and returns 1; returns 0 when it is not one; prints "bitrain CMD: ..." and
 * returns -1 when its value is missing or bad. */
int dem_args_parse(dem_opts *o, int argc, char **argv, int *i, const char *cmd);

#endif
