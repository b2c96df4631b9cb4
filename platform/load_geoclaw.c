/* platform/load_geoclaw.c — GeoClaw topography files, topotype 2 and 3.
 *
 * Layout (clawpack.geoclaw.topotools, Topography.read_header and write): six
 * header lines, each one value and one keyword, the value FIRST in GeoClaw's
 * own files ("393 ncols") and the keyword first in ESRI-style ones (both are
 * read, line by line):
 *   ncols (or mx), nrows (or my), x of the grid (xlower, xllcorner, xllcenter),
 *   y likewise, cellsize (one value, or dx and dy), nodata_value (optional).
 * Then nrows * ncols values, the north row first: topotype 2 puts one value on
 * a line, topotype 3 one row on a line; both are read as a stream of numbers.
 * Registration as topotools reads it: a label ending in "llcorner" gives the
 * lower-left corner of the lower-left cell, so the first data point is half a
 * cell in; "lower", "llcenter" and other labels give the data point itself.
 * Topotype 1 (x y z per line, from the north-west corner) is read by the XYZ
 * reader; dem_opts.xyz_depth negates the values (GeoClaw's negative topotypes).
 * Coordinates are degrees when they look geographic (dem_looks_degrees), else
 * metres; heights as in load_asc.c (dem_text_values). */
#include <ctype.h>
#include <math.h>
#include <string.h>
#include "platform/load_internal.h"

enum { G_NCOLS, G_NROWS, G_X, G_Y, G_CELL, G_NODATA, G_COUNT };
static const char *const gnames[G_COUNT] = { "ncols", "nrows", "x lower", "y lower", "cellsize", "nodata_value" };

/* The header keyword of token t (case-insensitive), or -1; *corner is set for
 * an x/y label that ends in "llcorner". */
static int gkey(const uint8_t *t, size_t len, int *corner)
{
    char k[24];
    size_t i;
    if (len == 0 || len >= sizeof k || !isalpha(t[0])) return -1;
    for (i = 0; i < len; i++) k[i] = (char)tolower(t[i]);
    k[len] = 0;
    if (!strcmp(k, "ncols") || !strcmp(k, "mx")) return G_NCOLS;
    if (!strcmp(k, "nrows") || !strcmp(k, "my")) return G_NROWS;
    if (!strcmp(k, "cellsize") || !strcmp(k, "dx")) return G_CELL;
    if (!strncmp(k, "nodata", 6)) return G_NODATA;
    if ((k[0] == 'x' || k[0] == 'y') && (!strcmp(k + 1, "lower") || !strcmp(k + 1, "llcorner") ||
                                         !strcmp(k + 1, "llcenter") || !strcmp(k + 1, "ll"))) {
        *corner = !strcmp(k + 1, "llcorner");
        return k[0] == 'x' ? G_X : G_Y;
    }
    return -1;
}

/* Past the white space before the next token of the line: every isspace byte but the
 * newline.  The token loops stop a token at any isspace byte, so this must skip all of
 * them, or a vertical tab or form feed would leave them where they stand (a hang). */
static size_t skip_blank(const uint8_t *p, size_t n, size_t i)
{
    while (i < n && p[i] != '\n' && isspace(p[i])) i++;
    return i;
}

int dem_geoclaw_start(const uint8_t *p, size_t n)
{
    size_t i = 0, b;
    int corner = 0, k;
    while (i < n && isspace(p[i])) i++;
    b = i;
    if (i >= n || !(isdigit(p[i]) || p[i] == '+' || p[i] == '.')) return 0;
    while (i < n && !isspace(p[i])) i++;
    i = skip_blank(p, n, i);
    if (i == b || i >= n) return 0;
    b = i;
    while (i < n && !isspace(p[i])) i++;
    k = gkey(p + b, i - b, &corner);
    return k == G_NCOLS || k == G_NROWS;
}

br_status dem_read_geoclaw(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                           hf *out, br_err *err)
{
    double val[G_COUNT] = { 0 }, dy = 0, sx, sy, x0, y0, ymin;
    int have[G_COUNT] = { 0 }, corner[2] = { 0, 0 }, line = 0;
    size_t pos = 0;
    char ts[32];
    int64_t w, h;
    hf f;
    br_status s;

    /* header lines: one keyword and its value(s), in either order */
    for (;;) {
        size_t e, q, toklen;
        const uint8_t *tok;
        double v[3];
        int nv = 0, k = -1, c = 0, r;
        q = pos;
        while (q < n && isspace(p[q])) q++;
        if (q >= n) return br_err_set(err, BR_E_TRUNCATED, name, "GeoClaw header without values");
        for (e = q; e < n && p[e] != '\n'; e++) {}
        line++;
        /* the first line without a keyword is data */
        {
            size_t t = q;
            while (t < e) {
                size_t b = t;
                while (t < e && !isspace(p[t])) t++;
                if (k < 0 && (k = gkey(p + b, t - b, &c)) >= 0) break;
                t = skip_blank(p, e, t);
            }
        }
        if (k < 0) {
            if (!have[G_NCOLS] || !have[G_NROWS]) {
                size_t b = q, t = q;
                while (t < e && !isspace(p[t])) t++;
                dem_token_str(p + b, t - b, ts);
                return br_err_set(err, BR_E_FORMAT, name, "GeoClaw header line %d has no keyword (at '%s')", line, ts);
            }
            pos = q;
            break;
        }
        if (have[k]) return br_err_set(err, BR_E_FORMAT, name, "GeoClaw header gives %s twice", gnames[k]);
        /* the numbers on the line, skipping the keyword */
        {
            size_t t = q;
            while (t < e) {
                size_t b = t;
                int dummy = 0;
                while (t < e && !isspace(p[t])) t++;
                if (gkey(p + b, t - b, &dummy) < 0) {
                    size_t tp = b;
                    r = dem_scan_number(p, t, &tp, 0, &v[nv < 3 ? nv : 2], &tok, &toklen);
                    if (r != 1) {
                        dem_token_str(p + b, t - b, ts);
                        return br_err_set(err, BR_E_VALUE, name, "GeoClaw %s value '%s' is not a number", gnames[k], ts);
                    }
                    nv++;
                }
                t = skip_blank(p, e, t);
            }
        }
        if (nv < 1 || nv > (k == G_CELL ? 2 : 1))
            return br_err_set(err, BR_E_FORMAT, name, "GeoClaw header line %d (%s) has %d numbers", line, gnames[k], nv);
        val[k] = v[0];
        if (k == G_CELL) dy = nv == 2 ? v[1] : v[0];
        if (k == G_X) corner[0] = c;
        if (k == G_Y) corner[1] = c;
        have[k] = 1;
        pos = e;
    }
    if (!have[G_NCOLS] || !have[G_NROWS] || !have[G_X] || !have[G_Y] || !have[G_CELL])
        return br_err_set(err, BR_E_FORMAT, name, "GeoClaw header lacks %s",
                          !have[G_NCOLS] ? "ncols" : !have[G_NROWS] ? "nrows" : !have[G_X] ? "the x of the grid"
                          : !have[G_Y] ? "the y of the grid" : "cellsize");
    if (val[G_NCOLS] != floor(val[G_NCOLS]) || val[G_NROWS] != floor(val[G_NROWS]) ||
        val[G_NCOLS] < 1 || val[G_NROWS] < 1)
        return br_err_set(err, BR_E_FORMAT, name, "GeoClaw ncols %g / nrows %g are not positive integers",
                          val[G_NCOLS], val[G_NROWS]);
    if (val[G_NCOLS] > BR_MAX_SIDE || val[G_NROWS] > BR_MAX_SIDE)
        return br_err_set(err, BR_E_TOO_BIG, name, "GeoClaw grid %gx%g is too big (limit %d per side)",
                          val[G_NCOLS], val[G_NROWS], BR_MAX_SIDE);
    w = (int64_t)val[G_NCOLS];
    h = (int64_t)val[G_NROWS];
    sx = val[G_CELL];
    sy = dy;
    if (!(sx > 0) || !(sy > 0))
        return br_err_set(err, BR_E_VALUE, name, "GeoClaw cell size must be positive");
    s = dem_text_values(name, "GeoClaw", p, n, pos, w, h, have[G_NODATA], val[G_NODATA], o && o->xyz_depth,
                        o, &f, err);
    if (s != BR_OK) return s;
    /* georeference: centre of sample (0,0) = west column, north row */
    x0 = val[G_X] + (corner[0] ? sx / 2 : 0);
    y0 = val[G_Y] + (corner[1] ? sy / 2 : 0) + (double)(h - 1) * sy;
    /* judged on the data points, as the XYZ reader does (a lab grid starts at (0, 0)) */
    ymin = val[G_Y] + (corner[1] ? sy / 2 : 0);
    if (dem_looks_degrees(x0, ymin, x0 + (double)(w - 1) * sx, y0, sx, sy))
        s = dem_geo_degrees(&f, x0, y0, sx, sy, name, err);
    else
        s = dem_geo_projected(&f, x0, y0, sx, sy, name, err);
    if (s != BR_OK) { dem_free(&f); return s; }
    *out = f;
    return BR_OK;
}
