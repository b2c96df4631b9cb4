/* platform/load_bt.c — VTP Binary Terrain .bt, versions 1.0 to 1.3.
 *
 * 256-byte little-endian header: "binterr1.x", columns and rows (int32), data
 * size (2 or 4), float flag, horizontal units (0 degrees, 1 metres, 2 and 3
 * feet), extents left/right/bottom/top (doubles, positions of the outer
 * SAMPLES as vtElevationGrid uses them: step = width / (columns - 1)), and in
 * 1.3 a vertical scale (float, metres per unit, 0 = 1).  The samples are
 * stored column by column from the west, each column from SOUTH to north; we
 * transpose to our north-west-first rows.  -32768 is a void (VTP's
 * INVALID_ELEVATION), and so is dem_opts.nodata; NaN/inf are errors (NaN a
 * void with nodata NaN).  int16/int32 with scale 1 keep 1 m;
 * float or scaled data use the float rule (at least 1 mm). */
#include <math.h>
#include <string.h>
#include "platform/load_internal.h"

static float le_float(const uint8_t *p)
{
    uint32_t u = dem_le32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static double le_double(const uint8_t *p)
{
    uint64_t u = (uint64_t)dem_le32(p) | (uint64_t)dem_le32(p + 4) << 32;
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

br_status dem_read_bt(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                      hf *out, br_err *err)
{
    int32_t cols, rows, den = 1;
    int dsize, isfloat, hunits, minor;
    double left, right, bottom, top, vscale = 1, maxabs = 0, ufac = 1, sx, sy;
    size_t cnt, i, need;
    int64_t c, r;
    int scaled;
    hf f;
    br_status s;
    /* dem_opts.nodata: compared with the stored sample (float samples as float32) */
    int user_nd = o && o->has_nodata, nd_nan = user_nd && o->nodata != o->nodata;
    float nd_f = user_nd && !nd_nan ? (float)o->nodata : 0;
    double nd_d = user_nd && !nd_nan ? o->nodata : 0;
    if (n < 10 || memcmp(p, "binterr1.", 9) != 0)
        return br_err_set(err, BR_E_FORMAT, name, "not a VTP BT file (wrong magic)");
    if (p[9] < '0' || p[9] > '3')
        return br_err_set(err, BR_E_UNSUPPORTED, name, "BT version 1.%c is not supported (1.0 to 1.3)", p[9]);
    minor = p[9] - '0';
    if (n < 256) return br_err_set(err, BR_E_TRUNCATED, name, "BT header truncated (%zu of 256 bytes)", n);
    cols = (int32_t)dem_le32(p + 10);
    rows = (int32_t)dem_le32(p + 14);
    dsize = (int16_t)dem_le16(p + 18);
    isfloat = (int16_t)dem_le16(p + 20);
    hunits = (int16_t)dem_le16(p + 22);
    left = le_double(p + 28);
    right = le_double(p + 36);
    bottom = le_double(p + 44);
    top = le_double(p + 52);
    if (minor >= 3) {
        float v = le_float(p + 62);
        if (!isfinite(v) || v < 0)
            return br_err_set(err, BR_E_VALUE, name, "BT vertical scale %g is not a positive number", (double)v);
        if (v > 0) vscale = (double)v;
    }
    if (cols < 1 || rows < 1)
        return br_err_set(err, BR_E_FORMAT, name, "BT dimensions %dx%d are not positive", cols, rows);
    if (hf_check_dims(cols, rows) != BR_OK) return dem_alloc(&f, cols, rows, name, err);
    if (!((dsize == 2 && isfloat == 0) || (dsize == 4 && (isfloat == 0 || isfloat == 1))))
        return br_err_set(err, BR_E_FORMAT, name, "BT data size %d with float flag %d is not int16, int32 or float32",
                          dsize, isfloat);
    cnt = (size_t)cols * (size_t)rows;
    need = 256 + cnt * (size_t)dsize;
    if (n < need)
        return br_err_set(err, BR_E_TRUNCATED, name, "BT data truncated: %zu bytes, header says %zu", n, need);
    if (n > need)
        return br_err_set(err, BR_E_FORMAT, name, "BT file has %zu bytes, header says %zu", n, need);
    if (hunits == 2) ufac = 0.3048;
    else if (hunits == 3) ufac = 1200.0 / 3937.0;
    else if (hunits != 0 && hunits != 1)
        return br_err_set(err, BR_E_UNSUPPORTED, name, "BT horizontal units %d unknown", hunits);
    if (!isfinite(left) || !isfinite(right) || !isfinite(bottom) || !isfinite(top) ||
        (cols > 1 && !(right > left)) || (rows > 1 && !(top > bottom)))
        return br_err_set(err, BR_E_VALUE, name, "BT extents (%g, %g, %g, %g) are not a rectangle",
                          left, right, bottom, top);

    /* pass 1: validate and find the range */
    scaled = isfloat || vscale != 1;
    for (i = 0; i < cnt; i++) {
        const uint8_t *q = p + 256 + i * (size_t)dsize;
        double v;
        if (isfloat) {
            float fv = le_float(q);
            if (nd_nan && fv != fv) continue;
            if (!isfinite(fv))
                return br_err_set(err, BR_E_VALUE, name, "BT sample %zu (column %zu) is not finite", i, i / (size_t)rows);
            if (fv == -32768.0f || (user_nd && !nd_nan && fv == nd_f)) continue;
            v = (double)fv;
        } else {
            int32_t iv = dsize == 2 ? (int16_t)dem_le16(q) : (int32_t)dem_le32(q);
            if (iv == -32768 || (user_nd && (double)iv == nd_d)) continue;
            v = iv;
        }
        v = fabs(v * vscale);
        if (v > maxabs) maxabs = v;
    }
    if (!scaled) {
        if (maxabs > (double)BR_Z_LIMIT)
            return br_err_set(err, BR_E_VALUE, name, "BT height %g m is out of range", maxabs);
    } else if ((den = dem_float_den(maxabs)) == 0)
        return br_err_set(err, BR_E_VALUE, name, "BT height %g m is out of range", maxabs);

    s = dem_alloc(&f, cols, rows, name, err);
    if (s != BR_OK) return s;
    f.z_den = den;
    for (c = 0; c < cols; c++) {
        const uint8_t *q = p + 256 + (size_t)c * (size_t)rows * (size_t)dsize;
        for (r = 0; r < rows; r++, q += dsize) {   /* r = 0 is the south end */
            int32_t *dst = &f.z[(size_t)(rows - 1 - r) * (size_t)cols + (size_t)c];
            if (isfloat) {
                float fv = le_float(q);
                *dst = fv == -32768.0f || fv != fv || (user_nd && !nd_nan && fv == nd_f) ? HF_NODATA
                       : dem_float_z((double)fv * vscale, den);
            } else {
                int32_t iv = dsize == 2 ? (int16_t)dem_le16(q) : (int32_t)dem_le32(q);
                *dst = iv == -32768 || (user_nd && (double)iv == nd_d) ? HF_NODATA
                       : scaled ? dem_float_z(iv * vscale, den) : iv;
            }
        }
    }
    sx = cols > 1 ? (right - left) / (cols - 1) : 1;
    sy = rows > 1 ? (top - bottom) / (rows - 1) : 1;
    if (hunits == 0) s = dem_geo_degrees(&f, left, top, sx, sy, name, err);
    else s = dem_geo_projected(&f, left * ufac, top * ufac, sx * ufac, sy * ufac, name, err);
    if (s != BR_OK) { dem_free(&f); return s; }
    *out = f;
    return BR_OK;
}
