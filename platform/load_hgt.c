/* platform/load_hgt.c — SRTM .hgt: n x n big-endian int16, north row first.
 *
 * The size gives n (any square; 1201 = 3", 3601 = 1").  Voids (-32768) become
 * HF_NODATA; unit 1 m.  A tile name (N50E008: lower-left corner 50 N 8 E) gives
 * the georeference: sample (0,0) is the NW corner (lat+1, lon), step 1/(n-1)
 * degree.  Without a tile name the file has no georeference and we assume the
 * angular step 1/(n-1) degree at the equator for the ground spacing. */
#include <math.h>
#include <stdlib.h>
#include "platform/load_internal.h"

static size_t isqrt_size(size_t v)
{
    size_t k = (size_t)sqrt((double)v);
    while (k > 0 && k * k > v) k--;
    while ((k + 1) * (k + 1) <= v) k++;
    return k;
}

br_status dem_read_hgt(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                       hf *out, br_err *err)
{
    size_t side, i, cnt;
    int lat, lon;
    hf f;
    br_status s;
    int user_nd = o && o->has_nodata && o->nodata == o->nodata;
    side = isqrt_size(n / 2);
    if (n % 2 || side * side * 2 != n) {
        /* name the nearest standard tile so a cut download reads as such */
        static const size_t std[] = { 1201, 3601 };
        size_t k;
        for (k = 0; k < 2; k++) {
            size_t full = std[k] * std[k] * 2;
            if (n < full && n > full / 2)
                return br_err_set(err, BR_E_TRUNCATED, name,
                                  "%zu bytes: a %zux%zu tile truncated (%zu bytes expected)",
                                  n, std[k], std[k], full);
            if (n > full && n < full + full / 4)
                return br_err_set(err, BR_E_FORMAT, name,
                                  "%zu bytes: longer than a %zux%zu tile (%zu bytes)", n, std[k], std[k], full);
        }
        return br_err_set(err, BR_E_FORMAT, name, "%zu bytes is not 2*n*n: not an SRTM .hgt tile", n);
    }
    if (side < 2) return br_err_set(err, BR_E_FORMAT, name, "%zu bytes is too small for an .hgt tile", n);
    s = dem_alloc(&f, (int64_t)side, (int64_t)side, name, err);
    if (s != BR_OK) return s;
    cnt = side * side;
    for (i = 0; i < cnt; i++) {
        int16_t v = (int16_t)dem_be16(p + 2 * i);
        f.z[i] = v == -32768 || (user_nd && v == o->nodata) ? HF_NODATA : v;
    }
    if (dem_srtm_name(name, &lat, &lon)) {
        s = dem_geo_degrees(&f, lon, lat + 1, 1.0 / (double)(side - 1), 1.0 / (double)(side - 1), name, err);
    } else {
        double m_lat, m_lon;
        dem_m_per_degree(0, &m_lat, &m_lon);
        f.dx_um = llround(m_lon / (double)(side - 1) * 1e6);
        f.dy_um = llround(m_lat / (double)(side - 1) * 1e6);
        if (f.dx_um < 1) f.dx_um = 1;
        if (f.dy_um < 1) f.dy_um = 1;
    }
    if (s != BR_OK) { dem_free(&f); return s; }
    *out = f;
    return BR_OK;
}
