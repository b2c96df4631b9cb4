/* platform/merge.h — join adjacent heightfields into one by georeference.
 *
 * Tiles are placed by their hf_geo (same kind, same steps within 1e-6), not by
 * order.  Samples covered by several tiles (SRTM's repeated edge row/column)
 * must agree exactly (void = void) and are kept once; different values, a
 * hole in the bounding rectangle, tiles off each other's grid or without a
 * georeference are BR_E_MERGE with a message naming the file(s) and place.
 * Heights are converted to the finest unit that represents every tile exactly. */
#ifndef BR_MERGE_H
#define BR_MERGE_H
#include "core/hf.h"
#include "platform/err.h"

br_status dem_merge(const hf *tiles, const char *const *names, int n, hf *out, br_err *err);

#endif
