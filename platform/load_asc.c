/* platform/load_asc.c — ESRI ASCII grid (.asc).
 *
 * Header: "keyword value" lines, keywords case-insensitive: ncols, nrows,
 * xllcorner | xllcenter, yllcorner | yllcenter, cellsize (or dx and dy), and
 * optionally NODATA_value.  Then exactly ncols*nrows numbers, north row first.
 * Values equal to NODATA_value are voids; any other non-numeric token, NaN or
 * infinity is an error, and so are missing or extra values.
 * Units: integer-valued grids keep 1 m; grids with fractions use the float rule
 * (load_internal.h: at least 1 mm).  Georeference: degrees when the corner and
 * cell size look geographic (dem_looks_degrees), otherwise metres. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "platform/load_internal.h"

enum { K_NCOLS, K_NROWS, K_XLLCORNER, K_XLLCENTER, K_YLLCORNER, K_YLLCENTER, K_CELLSIZE, K_DX, K_DY,
       K_NODATA, K_COUNT };
static const char *const keys[K_COUNT] = { "ncols", "nrows", "xllcorner", "xllcenter", "yllcorner",
                                           "yllcenter", "cellsize", "dx", "dy", "nodata_value" };

static int key_of(const uint8_t *t, size_t len)
{
    int k;
    size_t i;
    for (k = 0; k < K_COUNT; k++) {
        if (strlen(keys[k]) != len) continue;
        for (i = 0; i < len && tolower(t[i]) == keys[k][i]; i++) {}
        if (i == len) return k;
    }
    return -1;
}

br_status dem_text_values(const char *name, const char *fmt, const uint8_t *p, size_t n, size_t pos,
                          int64_t w, int64_t h, int have_nd, double nd, int negate, const dem_opts *o,
                          hf *out, br_err *err)
{
    double v, maxabs = 0, sgn = negate ? -1.0 : 1.0;
    int allint = 1, r, user_nd = o && o->has_nodata && o->nodata == o->nodata;
    size_t data_pos, i, cnt, toklen;
    const uint8_t *tok;
    char ts[32];
    int32_t den = 1;
    hf f;
    br_status s;
    if (hf_check_dims(w, h) != BR_OK)
        return dem_alloc(&f, w, h, name, err); /* sets the too-big message */
    /* a grid needs at least 2 bytes of text per value: a lying header is caught before allocating */
    cnt = (size_t)w * (size_t)h;
    if ((n - pos) / 2 + 1 < cnt)
        return br_err_set(err, BR_E_TRUNCATED, name, "%s header says %lldx%lld values but the file is only %zu bytes",
                          fmt, (long long)w, (long long)h, n);
    /* pass 1: count and check every value, find the range and whether all are integers */
    data_pos = pos;
    for (i = 0; i < cnt; i++) {
        r = dem_scan_number(p, n, &pos, 0, &v, &tok, &toklen);
        if (r == 0)
            return br_err_set(err, BR_E_TRUNCATED, name, "%s grid has %zu of %zu values (%lldx%lld)",
                              fmt, i, cnt, (long long)w, (long long)h);
        if (r < 0) {
            dem_token_str(tok, toklen, ts);
            return br_err_set(err, BR_E_VALUE, name, "%s value '%s' at row %zu, column %zu is %s",
                              fmt, ts, i / (size_t)w, i % (size_t)w, r == -2 ? "not finite" : "not a number");
        }
        if ((have_nd && v == nd) || (user_nd && v == o->nodata)) continue;
        if (fabs(v) > maxabs) maxabs = fabs(v);
        if (v != floor(v)) allint = 0;
    }
    r = dem_scan_number(p, n, &pos, 0, &v, &tok, &toklen);
    if (r != 0)
        return br_err_set(err, BR_E_FORMAT, name, "%s grid has more than ncols*nrows = %zu values", fmt, cnt);
    if (allint && maxabs <= (double)BR_Z_LIMIT) den = 1;
    else if ((den = dem_float_den(maxabs)) == 0)
        return br_err_set(err, BR_E_VALUE, name, "%s height %g m is out of range", fmt, maxabs);

    s = dem_alloc(&f, w, h, name, err);
    if (s != BR_OK) return s;
    f.z_den = den;
    pos = data_pos;
    for (i = 0; i < cnt; i++) {
        (void)dem_scan_number(p, n, &pos, 0, &v, &tok, &toklen);
        f.z[i] = (have_nd && v == nd) || (user_nd && v == o->nodata) ? HF_NODATA : dem_float_z(sgn * v, den);
    }
    *out = f;
    return BR_OK;
}

br_status dem_read_asc(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                       hf *out, br_err *err)
{
    double val[K_COUNT] = { 0 }, sx, sy, x0, y0, xmin, ymin;
    int have[K_COUNT] = { 0 }, k, r;
    size_t pos = 0, toklen;
    const uint8_t *tok;
    char ts[32];
    int64_t w, h;
    hf f;
    br_status s;

    /* header: keyword tokens until the first token that starts like a number */
    for (;;) {
        size_t b = pos;
        while (b < n && isspace(p[b])) b++;
        if (b >= n) return br_err_set(err, BR_E_TRUNCATED, name, "ASC header without values");
        if (!isalpha(p[b])) break;
        pos = b;
        while (pos < n && !isspace(p[pos])) pos++;
        k = key_of(p + b, pos - b);
        if (k < 0 && have[K_NCOLS] && have[K_NROWS]) { pos = b; break; }  /* "nan" etc.: a value */
        if (k < 0) {
            dem_token_str(p + b, pos - b, ts);
            return br_err_set(err, BR_E_FORMAT, name, "unknown ASC header keyword '%s'", ts);
        }
        if (have[k]) return br_err_set(err, BR_E_FORMAT, name, "ASC keyword %s given twice", keys[k]);
        r = dem_scan_number(p, n, &pos, 0, &val[k], &tok, &toklen);
        if (r != 1) {
            if (r == 0) return br_err_set(err, BR_E_TRUNCATED, name, "ASC keyword %s has no value", keys[k]);
            dem_token_str(tok, toklen, ts);
            return br_err_set(err, BR_E_VALUE, name, "ASC %s value '%s' is not a number", keys[k], ts);
        }
        have[k] = 1;
    }
    if (!have[K_NCOLS] || !have[K_NROWS])
        return br_err_set(err, BR_E_FORMAT, name, "ASC header lacks ncols or nrows");
    if (!have[K_CELLSIZE] && !(have[K_DX] && have[K_DY]))
        return br_err_set(err, BR_E_FORMAT, name, "ASC header lacks cellsize");
    if ((!have[K_XLLCORNER] && !have[K_XLLCENTER]) || (!have[K_YLLCORNER] && !have[K_YLLCENTER]) ||
        (have[K_XLLCORNER] && have[K_XLLCENTER]) || (have[K_YLLCORNER] && have[K_YLLCENTER]))
        return br_err_set(err, BR_E_FORMAT, name, "ASC header needs one of xllcorner/xllcenter and one of yllcorner/yllcenter");
    if (val[K_NCOLS] != floor(val[K_NCOLS]) || val[K_NROWS] != floor(val[K_NROWS]) ||
        val[K_NCOLS] < 1 || val[K_NROWS] < 1)
        return br_err_set(err, BR_E_FORMAT, name, "ASC ncols %g / nrows %g are not positive integers",
                          val[K_NCOLS], val[K_NROWS]);
    if (val[K_NCOLS] > BR_MAX_SIDE || val[K_NROWS] > BR_MAX_SIDE)
        return br_err_set(err, BR_E_TOO_BIG, name, "ASC grid %gx%g is too big (limit %d per side)",
                          val[K_NCOLS], val[K_NROWS], BR_MAX_SIDE);
    w = (int64_t)val[K_NCOLS];
    h = (int64_t)val[K_NROWS];
    sx = have[K_CELLSIZE] ? val[K_CELLSIZE] : val[K_DX];
    sy = have[K_CELLSIZE] ? val[K_CELLSIZE] : val[K_DY];
    if (!(sx > 0) || !(sy > 0))
        return br_err_set(err, BR_E_VALUE, name, "ASC cell size must be positive");
    s = dem_text_values(name, "ASC", p, n, pos, w, h, have[K_NODATA], val[K_NODATA], 0, o, &f, err);
    if (s != BR_OK) return s;
    /* georeference: centre of sample (0,0) = west column, north row */
    x0 = have[K_XLLCORNER] ? val[K_XLLCORNER] + sx / 2 : val[K_XLLCENTER];
    xmin = x0 - sx / 2;
    ymin = have[K_YLLCORNER] ? val[K_YLLCORNER] : val[K_YLLCENTER] - sy / 2;
    y0 = ymin + (double)h * sy - sy / 2;
    if (dem_looks_degrees(xmin, ymin, xmin + (double)w * sx, ymin + (double)h * sy, sx, sy))
        s = dem_geo_degrees(&f, x0, y0, sx, sy, name, err);
    else
        s = dem_geo_projected(&f, x0, y0, sx, sy, name, err);
    if (s != BR_OK) { dem_free(&f); return s; }
    *out = f;
    return BR_OK;
}
