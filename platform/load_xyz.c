/* platform/load_xyz.c — text "x y z" points on a regular grid (.xyz, .txt).
 *
 * One point per line, three numbers separated by blanks, commas or
 * semicolons; empty lines and lines starting with '#' are skipped, and so is a
 * first line of column names.  The grid is detected from the values: the
 * column step is the smallest gap between distinct x values and every x must
 * lie on that lattice (same for y); points may come in any order.  A lattice
 * cell without a point is a void, but at least half the cells must be present
 * (checked before allocating) and no cell may be given twice.  Row 0 is the
 * largest y (north).  Heights use the float rule; dem_opts.xyz_depth negates
 * z (depth positive down); a z equal to dem_opts.nodata (as written) is a
 * void.  Coordinates are metres unless they look
 * geographic (dem_looks_degrees). */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "platform/clock.h"
#include "platform/load_internal.h"

/* Sorts v (n values) and finds the lattice min + k*step they lie on. */
static br_status lattice(double *v, size_t n, const char *axis, double *vmin, double *step,
                         int64_t *count, const char *name, br_err *err)
{
    double span, gap = 0;
    size_t i;
    qsort(v, n, sizeof *v, br_cmp_double);
    span = v[n - 1] - v[0];
    *vmin = v[0];
    /* Neighbouring values closer than text rounding allows are one grid line:
     * 1e-5 of their own magnitude (six significant digits, as "%e" and "%g"
     * print) plus 1e-9 of the span.  Judged per pair, not on the whole span, so
     * one far outlier does not widen the tolerance until distinct grid lines
     * merge (it makes the span too many steps instead, refused below). */
    for (i = 1; i < n; i++) {
        double d = v[i] - v[i - 1];
        double tol = 1e-5 * fmax(fabs(v[i]), fabs(v[i - 1])) + 1e-9 * span;
        if (d > tol && (gap == 0 || d < gap)) gap = d;
    }
    if (gap == 0) { *step = 0; *count = 1; return BR_OK; }
    if (span / gap > (double)BR_MAX_SIDE)
        return br_err_set(err, BR_E_TOO_BIG, name, "XYZ %s values span %.0f steps of %g (limit %d)",
                          axis, span / gap, gap, BR_MAX_SIDE);
    *count = (int64_t)floor(span / gap + 0.5) + 1;
    *step = span / (double)(*count - 1);
    for (i = 0; i < n; i++) {
        double k = (v[i] - v[0]) / *step;
        if (fabs(k - floor(k + 0.5)) > 0.01)
            return br_err_set(err, BR_E_FORMAT, name, "XYZ %s values are not on a regular grid (%g is off the step %g)",
                              axis, v[i], *step);
    }
    return BR_OK;
}

br_status dem_read_xyz(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                       hf *out, br_err *err)
{
    double *pt = NULL, *tmp = NULL, xmin, ymin, sx, sy, gx, gy, maxabs = 0, sgn;
    size_t cap = 0, np = 0, pos = 0, line = 0, i;
    int64_t nx, ny;
    int32_t den;
    uint8_t *seen = NULL;
    hf f;
    br_status s;
    char ts[32];
    int user_nd;

    sgn = o && o->xyz_depth ? -1.0 : 1.0;
    user_nd = o && o->has_nodata && o->nodata == o->nodata;
    memset(&f, 0, sizeof f);
    while (pos < n) {
        size_t e = pos, lp;
        double v[3];
        int k, r = 1;
        const uint8_t *tok = NULL;
        size_t toklen = 0;
        while (e < n && p[e] != '\n') e++;
        line++;
        lp = pos;
        while (lp < e && isspace(p[lp])) lp++;
        if (lp == e || p[lp] == '#' || (np == 0 && line == 1 && isalpha(p[lp]))) { pos = e + 1; continue; }
        for (k = 0; k < 3; k++) {
            r = dem_scan_number(p, e, &lp, 1, &v[k], &tok, &toklen);
            if (r != 1) break;
        }
        if (k == 3) {
            double extra;
            r = dem_scan_number(p, e, &lp, 1, &extra, &tok, &toklen) == 0 ? 1 : 3;
        }
        if (r != 1) {
            free(pt);
            if (r == 0) return br_err_set(err, BR_E_FORMAT, name, "XYZ line %zu has %d number(s), not 3", line, k);
            if (r == 3) return br_err_set(err, BR_E_FORMAT, name, "XYZ line %zu has more than 3 numbers", line);
            dem_token_str(tok, toklen, ts);
            return br_err_set(err, BR_E_VALUE, name, "XYZ line %zu: '%s' is %s", line, ts,
                              r == -2 ? "not finite" : "not a number");
        }
        if (np == cap) {
            size_t ncap = cap ? cap * 2 : 4096;
            double *q;
            if (ncap > (size_t)BR_MAX_SAMPLES) ncap = (size_t)BR_MAX_SAMPLES;
            if (np >= ncap) { free(pt); return br_err_set(err, BR_E_TOO_BIG, name, "XYZ has more than %ld points", (long)BR_MAX_SAMPLES); }
            q = realloc(pt, ncap * 3 * sizeof *pt);
            if (!q) { free(pt); return br_err_set(err, BR_E_NOMEM, name, "out of memory"); }
            pt = q;
            cap = ncap;
        }
        pt[np * 3] = v[0];
        pt[np * 3 + 1] = v[1];
        pt[np * 3 + 2] = v[2] * sgn;
        if (fabs(v[2]) > maxabs && !(user_nd && v[2] == o->nodata)) maxabs = fabs(v[2]);
        np++;
        pos = e + 1;
    }
    if (np == 0) return br_err_set(err, BR_E_FORMAT, name, "XYZ file has no points");
    tmp = malloc(np * sizeof *tmp);
    if (!tmp) { free(pt); return br_err_set(err, BR_E_NOMEM, name, "out of memory"); }
    for (i = 0; i < np; i++) tmp[i] = pt[i * 3];
    s = lattice(tmp, np, "x", &xmin, &sx, &nx, name, err);
    if (s == BR_OK) {
        for (i = 0; i < np; i++) tmp[i] = pt[i * 3 + 1];
        s = lattice(tmp, np, "y", &ymin, &sy, &ny, name, err);
    }
    free(tmp);
    if (s != BR_OK) { free(pt); return s; }
    /* An axis of one grid line (its values within text rounding of each other, possibly
     * not equal) has step 0: its points all take index 0 there, and it borrows the other
     * axis's step only for the georeference below. */
    gx = sx; gy = sy;
    if (gx == 0) gx = sy;
    if (gy == 0) gy = sx;
    if (gx == 0) {
        free(pt);
        return br_err_set(err, BR_E_FORMAT, name, "XYZ points do not span a grid (one distinct x and y)");
    }
    if ((double)nx * (double)ny > 2.0 * (double)np)
        return free(pt), br_err_set(err, BR_E_FORMAT, name,
                                    "XYZ points fill only %zu of the %lldx%lld grid they span (under half)",
                                    np, (long long)nx, (long long)ny);
    if ((den = dem_float_den(maxabs)) == 0) {
        free(pt);
        return br_err_set(err, BR_E_VALUE, name, "XYZ height %g m is out of range", maxabs);
    }
    s = dem_alloc(&f, nx, ny, name, err);
    if (s != BR_OK) { free(pt); return s; }
    seen = calloc((size_t)nx * (size_t)ny, 1);
    if (!seen) { free(pt); dem_free(&f); return br_err_set(err, BR_E_NOMEM, name, "out of memory"); }
    f.z_den = den;
    for (i = 0; i < (size_t)nx * (size_t)ny; i++) f.z[i] = HF_NODATA;
    for (i = 0; i < np; i++) {
        /* lattice() put every value within 0.01 step of a line 0 .. count - 1 */
        const int64_t c = sx > 0 ? (int64_t)floor((pt[i * 3] - xmin) / sx + 0.5) : 0;
        const int64_t r = ny - 1 - (sy > 0 ? (int64_t)floor((pt[i * 3 + 1] - ymin) / sy + 0.5) : 0);
        size_t k;
        if (c < 0 || c >= nx || r < 0 || r >= ny) {     /* (not reached: a guard, not a rule) */
            s = br_err_set(err, BR_E_FORMAT, name, "XYZ point (%g, %g) is off the grid", pt[i * 3], pt[i * 3 + 1]);
            break;
        }
        k = (size_t)r * (size_t)nx + (size_t)c;
        if (seen[k]) {
            s = br_err_set(err, BR_E_FORMAT, name, "XYZ point (%g, %g) is given twice", pt[i * 3], pt[i * 3 + 1]);
            break;
        }
        seen[k] = 1;
        f.z[k] = user_nd && pt[i * 3 + 2] * sgn == o->nodata ? HF_NODATA : dem_float_z(pt[i * 3 + 2], den);
    }
    free(seen);
    free(pt);
    if (s == BR_OK) {
        double xmax = xmin + gx * (double)(nx - 1), ymax = ymin + gy * (double)(ny - 1);
        if (dem_looks_degrees(xmin, ymin, xmax, ymax, gx, gy))
            s = dem_geo_degrees(&f, xmin, ymax, gx, gy, name, err);
        else
            s = dem_geo_projected(&f, xmin, ymax, gx, gy, name, err);
    }
    if (s != BR_OK) { dem_free(&f); return s; }
    *out = f;
    return BR_OK;
}
