/* platform/dem_args.h — the reader flags every command that reads DEM files accepts
 * (info, hillshade, mesh, render, view, run), as one option table (platform/opt.h):
 *   --png-encoding auto|grey|terrain-rgb|terrarium   how PNG pixels hold heights
 *   --scale S, --offset O                            grey PNG: metres = raw * S + O
 *   --xyz-depth                                      XYZ, GeoClaw: values are depths (positive down)
 *   --nodata V                                       samples equal to V are voids too (any finite
 *                                                    number as the file stores it, or nan)
 *   --merge-prefer first|last                        where merged tiles disagree, that file's height
 *                                                    wins (default: refuse)
 *   --fill-voids                                     fill voids from their borders (platform/fill.h)
 * (`info` also accepts --depth for --xyz-depth.) */
#ifndef BR_DEM_ARGS_H
#define BR_DEM_ARGS_H
#include "platform/load.h"
#include "platform/opt.h"

#define DEM_ARGS_N 8    /* entries of the table, OPT_END included */

typedef struct dem_args {
    dem_opts *o;
    const char *nodata;           /* --nodata's text: a number or nan */
    int merge_choice;             /* 0 none, 1 first, 2 last */
} dem_args;

/* Fills t with the reader flags, writing into *a and *o (t points into both: keep them
 * alive while parsing). */
void dem_args_table(dem_args *a, dem_opts *o, opt_spec t[DEM_ARGS_N]);

/* After opt_parse: turns the parsed spelling into dem_opts' values (gray is grey, the
 * --nodata text a number); OPT_ERR with a message naming cmd when a value is unusable. */
int dem_args_finish(dem_args *a, const char *cmd);

#endif
