/* platform/merge.h — join adjacent heightfields into one by georeference.
 *
 * Tiles are placed by their hf_geo (same kind, same steps within 1e-6), not by
 * order.  Samples covered by several tiles (SRTM's repeated edge row/column)
 * must agree exactly (void = void) and are kept once (unless dem_merge_prefer
 * says which tile wins); different values, a
 * hole in the bounding rectangle, tiles off each other's grid or without a
 * georeference are BR_E_MERGE with a message naming the file(s) and place.
 * Heights are converted to the finest unit that represents every tile exactly. */
#ifndef BR_MERGE_H
#define BR_MERGE_H
#include "core/hf.h"
#include "platform/err.h"
#include "platform/load.h"

br_status dem_merge(const hf *tiles, const char *const *names, int n, hf *out, br_err *err);
/* The same where overlapping samples may disagree: prefer is DEM_MERGE_REFUSE
 * (as dem_merge), _FIRST or _LAST (that tile's height is kept, as gdal_merge's
 * order does; a void never replaces a height, with either). */
br_status dem_merge_prefer(const hf *tiles, const char *const *names, int n, int prefer, hf *out, br_err *err);

#endif
