/* platform/fill.h — `--fill-voids`: void samples filled from the void's border.
 *
 * The idea of gdal_fillnodata (GDAL, alg/gdalfillnodata.cpp): a void sample takes
 * the inverse-distance weighted mean of valid samples around it, searched out to
 * 100 samples (its default max distance).  Here the search follows the 8 grid
 * directions (N, NE, E, SE, S, SW, W, NW) from the void sample to the first valid
 * sample on each, weight 1 / d^2 (d in samples, diagonal steps sqrt 2), without
 * GDAL's optional smoothing passes.  Only original samples are read, so the result
 * does not depend on the order; a void with no valid sample within reach on any
 * direction stays void.  Heights stay in the grid's unit, rounded to nearest. */
#ifndef BR_FILL_H
#define BR_FILL_H
#include <stdint.h>
#include "core/hf.h"
#include "platform/err.h"

#define DEM_FILL_MAX_DIST 100

/* Fills f's voids in place; *filled (may be NULL) receives the number filled.
 * BR_E_NOMEM (f unchanged) when the copy of the grid cannot be allocated. */
br_status dem_fill_voids(hf *f, int64_t *filled, br_err *err);

#endif
