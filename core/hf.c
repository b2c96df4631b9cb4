/* core/hf.c — heightfield checks and statistics (see hf.h). */
#include "core/hf.h"

br_status hf_check_dims(int64_t w, int64_t h)
{
    if (w < 1 || h < 1) return BR_E_FORMAT;
    if (w > BR_MAX_SIDE || h > BR_MAX_SIDE || w * h > (int64_t)BR_MAX_SAMPLES) return BR_E_TOO_BIG;
    return BR_OK;
}

br_status hf_validate(const hf *f)
{
    br_status s = hf_check_dims(f->w, f->h);
    if (s != BR_OK) return s;
    if (!f->z || f->z_num <= 0 || f->z_den <= 0 || f->dx_um <= 0 || f->dy_um <= 0 ||
        f->dx_um > HF_MAX_SPACING_UM || f->dy_um > HF_MAX_SPACING_UM) return BR_E_ARG;
    return BR_OK;
}

void hf_stats_get(const hf *f, hf_stats *out)
{
    int32_t lo = INT32_MAX, hi = INT32_MIN;
    int64_t voids = 0, i, n = (int64_t)f->w * f->h;
    for (i = 0; i < n; i++) {
        int32_t z = f->z[i];
        if (z == HF_NODATA) { voids++; continue; }
        if (z < lo) lo = z;
        if (z > hi) hi = z;
    }
    if (voids == n) lo = hi = 0;
    out->zmin = lo;
    out->zmax = hi;
    out->voids = voids;
}

int64_t hf_z_to_mm(const hf *f, int32_t z)
{
    int64_t num, den;
    if (z == HF_NODATA) return HF_NODATA;
    num = (int64_t)z * f->z_num * 1000;
    den = f->z_den;
    if (den == 1) return num;      /* whole units (HGT): the product, with no 64-bit divide
                                      (scene_camera asks for the ground height each frame) */
    /* round half away from zero; den > 0 */
    return num >= 0 ? (num + den / 2) / den : -((-num + den / 2) / den);
}
