/* platform/dem_args.h — the reader flags every command that reads DEM files accepts
 * (info, hillshade, mesh, render, view, run), as one option table (platform/opt.h):
 *   --png-encoding auto|grey|terrain-rgb|terrarium   how PNG pixels hold heights
 *   --scale S, --offset O                            grey PNG: metres = raw * S + O
 *   --xyz-depth                                      XYZ: third column is depth (positive down)
 * (`info` also accepts --depth for --xyz-depth.) */
#ifndef BR_DEM_ARGS_H
#define BR_DEM_ARGS_H
#include "platform/load.h"
#include "platform/opt.h"

#define DEM_ARGS_N 5    /* entries of the table, OPT_END included */

/* Fills t with the reader flags, writing into *o (t points into o: keep both alive
 * while parsing). */
void dem_args_table(dem_opts *o, opt_spec t[DEM_ARGS_N]);

/* After opt_parse: turns the parsed spelling into dem_opts' values (gray is grey). */
void dem_args_finish(dem_opts *o);

#endif
