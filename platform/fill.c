/* platform/fill.c — see fill.h. */
#include "platform/fill.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

br_status dem_fill_voids(hf *f, int64_t *filled, br_err *err)
{
    static const int dx8[8] = { 0, 1, 1, 1, 0, -1, -1, -1 }, dy8[8] = { -1, -1, 0, 1, 1, 1, 0, -1 };
    size_t n = (size_t)f->w * (size_t)f->h;
    int32_t *src, x, y;
    int64_t count = 0;
    if (filled) *filled = 0;
    src = malloc(sizeof *src * (n ? n : 1));
    if (!src) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory to fill voids");
    memcpy(src, f->z, sizeof *src * n);
    for (y = 0; y < f->h; y++)
        for (x = 0; x < f->w; x++) {
            double sw = 0, sz = 0, v;
            int k;
            if (src[(size_t)y * f->w + x] != HF_NODATA) continue;
            for (k = 0; k < 8; k++) {
                int32_t s, px = x, py = y;
                double d2 = (dx8[k] && dy8[k]) ? 2.0 : 1.0;
                for (s = 1; s <= DEM_FILL_MAX_DIST; s++) {
                    int32_t z;
                    px += dx8[k]; py += dy8[k];
                    if (px < 0 || py < 0 || px >= f->w || py >= f->h) break;
                    z = src[(size_t)py * f->w + px];
                    if (z != HF_NODATA) {
                        double w = 1.0 / (d2 * s * s);
                        sw += w;
                        sz += w * z;
                        break;
                    }
                }
            }
            if (sw == 0) continue;
            v = floor(sz / sw + 0.5);     /* a weighted mean of int32 heights: in range */
            f->z[(size_t)y * f->w + x] = (int32_t)v;
            count++;
        }
    free(src);
    if (filled) *filled = count;
    return BR_OK;
}
