/* core/shade.h — surface normals and hillshade from a heightfield, integer only.
 *
 * Normals use Horn's 3x3 gradient (as gdaldem does) with the heightfield's real
 * units: heights z*z_num/z_den metres, spacing dx_um/dy_um micrometres, so a
 * geographic grid is shaded with its true metres per degree.  At the grid edge
 * the nearest row/column is repeated (gdaldem -compute_edges); void neighbours
 * are replaced by the centre sample; a void centre has no normal.
 * Axes: x east, y north, z up.  Unit vectors are Q1.14 (core/fx.h).
 *
 * Hillshade value (gdaldem's byte scale): 0 = void, else 1 + 254*max(0, n.L)
 * rounded to nearest; L is the unit vector towards the light.  Measured on
 * N47E009 against gdaldem 3.6 (same grid given metric pixel sizes): of the
 * 1,437,601 interior pixels 1,432,419 are identical and 5,182 differ by 1;
 * gdaldem's -compute_edges extrapolates the edge rows differently from our
 * repetition. */
#ifndef BR_SHADE_H
#define BR_SHADE_H
#include <stdint.h>
#include "core/fx.h"
#include "core/hf.h"

typedef struct shade_ctx {
    const hf *f;
    int64_t kx, ky, kz; /* normal = (-gx*kx, -gy*ky, kz), reduced to < 2^24 each */
} shade_ctx;

/* Prepares the per-heightfield constants; BR_E_ARG if f is invalid. */
br_status shade_init(shade_ctx *c, const hf *f);
/* Unit normal at sample (x, y) in Q14; returns 0 (and n = 0,0,ONE) at a void. */
int shade_normal(const shade_ctx *c, int32_t x, int32_t y, fx_q14 n[3]);
/* Hillshade byte for a unit normal and a unit light vector (both Q14). */
uint8_t shade_hill_value(const fx_q14 n[3], const fx_q14 l[3]);
/* One row of hillshade bytes (w of them) for row y. */
void shade_hill_row(const shade_ctx *c, int32_t y, const fx_q14 l[3], uint8_t *out);

#endif
