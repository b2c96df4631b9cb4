/* platform/load.c — choose a reader by content and extension, unpack .gz and
 * .zip, load one file (see load.h; several files: merge.c), and the helpers the readers
 * share (load_internal.h).
 *
 * Containers: a gzip stream (1f 8b) is inflated and the name loses its ".gz";
 * a zip archive (PK\3\4) is read through its central directory and the member
 * that looks like heights (.hgt first, then the other height extensions) is
 * inflated, CRC-checked and read under the name "archive/member".  Containers
 * do not nest.  Decompressed sizes are capped by what the payload's format can
 * take (load_io.c). */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>
#include "platform/load.h"
#include "platform/load_internal.h"
#include "platform/assets.h"

/* ---- helpers shared by the readers ---- */

static dem_note_fn *note_fn;

void dem_set_note(dem_note_fn *fn) { note_fn = fn; }

void dem_note(const char *name, const char *msg)
{
    if (note_fn) note_fn(name, msg);
}

br_status dem_alloc(hf *out, int64_t w, int64_t h, const char *name, br_err *err)
{
    br_status s = hf_check_dims(w, h);
    if (s == BR_E_TOO_BIG)
        return br_err_set(err, s, name, "%lldx%lld samples is too big (limit %d per side, %ld in all)",
                          (long long)w, (long long)h, BR_MAX_SIDE, (long)BR_MAX_SAMPLES);
    if (s != BR_OK)
        return br_err_set(err, BR_E_FORMAT, name, "bad dimensions %lldx%lld", (long long)w, (long long)h);
    memset(out, 0, sizeof *out);
    out->z = malloc((size_t)w * (size_t)h * sizeof(int32_t));
    if (!out->z)
        return br_err_set(err, BR_E_NOMEM, name, "out of memory for %lldx%lld samples", (long long)w, (long long)h);
    out->w = (int32_t)w;
    out->h = (int32_t)h;
    out->z_num = out->z_den = 1;
    out->dx_um = out->dy_um = 1000000;
    out->geo.kind = HF_GEO_NONE;
    return BR_OK;
}

void dem_m_per_degree(double lat_deg, double *m_lat, double *m_lon)
{
    double phi = lat_deg * (3.14159265358979323846 / 180.0);
    *m_lat = 111132.954 - 559.822 * cos(2 * phi) + 1.175 * cos(4 * phi);
    *m_lon = 111412.84 * cos(phi) - 93.5 * cos(3 * phi) + 0.118 * cos(5 * phi);
}

static br_status spacing_um(double metres, int64_t *out, const char *name, br_err *err)
{
    double um = floor(metres * 1e6 + 0.5);
    if (!(um <= (double)HF_MAX_SPACING_UM))
        return br_err_set(err, BR_E_VALUE, name, "sample spacing %.6g m is too large (limit %.0f m)", metres,
                          (double)HF_MAX_SPACING_UM * 1e-6);
    *out = um < 1 ? 1 : (int64_t)um;
    return BR_OK;
}

static double geo_centre_lat(const hf *f)
{
    return ((double)f->geo.y0 - (double)f->geo.sy * (f->h - 1) * 0.5) * 1e-9;
}

static br_status spacing_at(hf *f, double lat_c, double slon, double slat, const char *name, br_err *err)
{
    double m_lat, m_lon;
    br_status s;
    dem_m_per_degree(lat_c, &m_lat, &m_lon);
    if (m_lon < 0) m_lon = 0;
    s = spacing_um(m_lon * slon, &f->dx_um, name, err);
    if (s == BR_OK) s = spacing_um(m_lat * slat, &f->dy_um, name, err);
    return s;
}

br_status dem_geo_spacing(hf *f, const hf *like, const char *name, br_err *err)
{
    double lat_c, m_lat, m_lon, l_lat, l_lon;
    if (f->geo.kind != HF_GEO_DEGREES) return BR_OK;
    lat_c = geo_centre_lat(f);
    if (!like) return spacing_at(f, lat_c, (double)f->geo.sx * 1e-9, (double)f->geo.sy * 1e-9, name, err);
    /* scale like's spacing (computed from its exact step) to our centre latitude */
    dem_m_per_degree(lat_c, &m_lat, &m_lon);
    dem_m_per_degree(geo_centre_lat(like), &l_lat, &l_lon);
    if (!(l_lon > 0) || !(l_lat > 0))
        return spacing_at(f, lat_c, (double)f->geo.sx * 1e-9, (double)f->geo.sy * 1e-9, name, err);
    if (m_lon < 0) m_lon = 0;
    {
        br_status s = spacing_um((double)like->dx_um * 1e-6 * m_lon / l_lon, &f->dx_um, name, err);
        if (s == BR_OK) s = spacing_um((double)like->dy_um * 1e-6 * m_lat / l_lat, &f->dy_um, name, err);
        return s;
    }
}

static int fits_geo(double v) { return v == v && fabs(v) < 9.0e12; }

br_status dem_geo_degrees(hf *f, double lon0, double lat0, double slon, double slat,
                          const char *name, br_err *err)
{
    if (!fits_geo(lon0) || !fits_geo(lat0) || fabs(lat0) > 1000 || fabs(lon0) > 1000 ||
        !(slon > 0 && slon < 360) || !(slat > 0 && slat < 180))
        return br_err_set(err, BR_E_VALUE, name, "bad geographic georeference (%g, %g, step %g, %g)",
                          lon0, lat0, slon, slat);
    f->geo.kind = HF_GEO_DEGREES;
    f->geo.x0 = (int64_t)llround(lon0 * 1e9);
    f->geo.y0 = (int64_t)llround(lat0 * 1e9);
    f->geo.sx = (int64_t)llround(slon * 1e9);
    f->geo.sy = (int64_t)llround(slat * 1e9);
    if (f->geo.sx < 1 || f->geo.sy < 1)
        return br_err_set(err, BR_E_VALUE, name, "sample step below one nano-degree");
    return spacing_at(f, lat0 - slat * (f->h - 1) * 0.5, slon, slat, name, err);
}

br_status dem_geo_projected(hf *f, double x0, double y0, double sx, double sy,
                            const char *name, br_err *err)
{
    br_status s;
    if (!fits_geo(x0 * 1e6) || !fits_geo(y0 * 1e6) || !(sx > 0 && sx < 1e7) || !(sy > 0 && sy < 1e7))
        return br_err_set(err, BR_E_VALUE, name, "bad georeference (%g, %g, step %g, %g)", x0, y0, sx, sy);
    f->geo.kind = HF_GEO_PROJECTED;
    f->geo.x0 = (int64_t)llround(x0 * 1e6);
    f->geo.y0 = (int64_t)llround(y0 * 1e6);
    f->geo.sx = (int64_t)llround(sx * 1e6);
    f->geo.sy = (int64_t)llround(sy * 1e6);
    s = spacing_um(sx, &f->dx_um, name, err);
    if (s == BR_OK) s = spacing_um(sy, &f->dy_um, name, err);
    return s;
}

int32_t dem_float_den(double maxabs)
{
    static const int32_t dens[] = { 1000000, 100000, 10000, 1000 };
    size_t i;
    for (i = 0; i < sizeof dens / sizeof dens[0]; i++)
        if (maxabs * dens[i] <= (double)(1L << 27)) return dens[i];
    return 0;
}

int32_t dem_float_z(double h, int32_t den)
{
    return (int32_t)llround(h * den);
}

int dem_rational(double v, int64_t maxden, int64_t *num, int64_t *den)
{
    int64_t d, h0 = 0, h1 = 1, k0 = 1, k1 = 0;
    double x, tol;
    if (!(v == v) || fabs(v) > 1e12) return 0;
    tol = fabs(v) * 1e-9 + 1e-12;
    for (d = 1; d <= maxden; d *= 10) {
        double nv = floor(v * (double)d + 0.5);
        if (fabs(nv / (double)d - v) <= tol) { *num = (int64_t)nv; *den = d; return 1; }
    }
    /* continued fractions */
    x = v;
    for (;;) {
        double a = floor(x), frac;
        int64_t ai = (int64_t)a, h2, k2;
        if (fabs(a) > 1e12) return 0;
        h2 = ai * h1 + h0;
        k2 = ai * k1 + k0;
        if (k2 > maxden) return 0;
        h0 = h1; h1 = h2; k0 = k1; k1 = k2;
        if (fabs((double)h1 / (double)k1 - v) <= tol) { *num = h1; *den = k1; return 1; }
        frac = x - a;
        if (frac < 1e-15) return 0;
        x = 1.0 / frac;
    }
}

static int is_sep(uint8_t c, int commas)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' ||
           (commas && (c == ',' || c == ';'));
}

int dem_scan_number(const uint8_t *p, size_t n, size_t *pos, int commas, double *v,
                    const uint8_t **tok, size_t *toklen)
{
    size_t i = *pos, b, len, k;
    char buf[72], *end;
    while (i < n && is_sep(p[i], commas)) i++;
    if (i >= n) { *pos = i; return 0; }
    b = i;
    while (i < n && !is_sep(p[i], commas)) i++;
    *pos = i;
    len = i - b;
    *tok = p + b;
    *toklen = len;
    /* fast path: plain integers of up to 9 digits */
    k = p[b] == '-' || p[b] == '+';
    if (len > k && len - k <= 9) {
        int32_t a = 0;
        size_t j;
        for (j = b + k; j < i && p[j] >= '0' && p[j] <= '9'; j++) a = a * 10 + (p[j] - '0');
        if (j == i) { *v = p[b] == '-' ? -(double)a : (double)a; return 1; }
    }
    if (len >= sizeof buf) return -1;
    for (k = 0; k < len; k++) {
        uint8_t c = p[b + k];
        /* strtod would also take hex floats and "nan(...)": keep to decimal notation */
        if (!((c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E' ||
              c == 'n' || c == 'N' || c == 'a' || c == 'A' || c == 'i' || c == 'I' || c == 'f' || c == 'F' ||
              c == 't' || c == 'T' || c == 'y' || c == 'Y'))
            return -1;
        buf[k] = (char)c;
    }
    buf[len] = 0;
    *v = strtod(buf, &end);
    if (end != buf + len) return -1;
    if (!isfinite(*v)) return -2;
    return 1;
}

void dem_token_str(const uint8_t *tok, size_t len, char out[32])
{
    size_t i, m = len > 24 ? 24 : len;
    for (i = 0; i < m; i++) out[i] = isprint(tok[i]) ? (char)tok[i] : '?';
    if (len > m) { out[m] = '.'; out[m + 1] = '.'; out[m + 2] = '.'; m += 3; }
    out[m] = 0;
}

int dem_looks_degrees(double xmin, double ymin, double xmax, double ymax, double sx, double sy)
{
    return sx <= 1 && sy <= 1 && xmin >= -360 && xmax <= 360 && ymin >= -90 && ymax <= 90 &&
           !(fabs(xmin) <= 1e-3 * sx && fabs(ymin) <= 1e-3 * sy);
}

const char *dem_basename(const char *name)
{
    const char *b = name, *p;
    for (p = name; *p; p++)
        if (*p == '/' || *p == '\\') b = p + 1;
    return b;
}

int dem_has_ext(const char *name, const char *ext)
{
    size_t n = strlen(name), e = strlen(ext), i;
    if (n < e) return 0;
    for (i = 0; i < e; i++)
        if (tolower((unsigned char)name[n - e + i]) != tolower((unsigned char)ext[i])) return 0;
    return 1;
}

int dem_srtm_name(const char *name, int *lat, int *lon)
{
    const char *b = dem_basename(name);
    for (; *b; b++) {
        const char *p = b;
        int ns = toupper((unsigned char)p[0]), ew;
        if (ns != 'N' && ns != 'S') continue;
        if (!isdigit((unsigned char)p[1]) || !isdigit((unsigned char)p[2])) continue;
        ew = toupper((unsigned char)p[3]);
        if (ew != 'E' && ew != 'W') continue;
        if (!isdigit((unsigned char)p[4]) || !isdigit((unsigned char)p[5]) || !isdigit((unsigned char)p[6]))
            continue;
        *lat = (p[1] - '0') * 10 + (p[2] - '0');
        *lon = (p[4] - '0') * 100 + (p[5] - '0') * 10 + (p[6] - '0');
        if (*lat > 90 || *lon > 180) continue;
        if (ns == 'S') *lat = -*lat;
        if (ew == 'W') *lon = -*lon;
        return 1;
    }
    return 0;
}

/* ---- zip ---- */

static int zip_rank(const char *member, size_t len)
{
    static const char *const ext[] = { ".asc", ".bt", ".tif", ".tiff", ".png", ".xyz", ".txt" };
    char tmp[260];
    size_t i;
    if (len == 0 || len >= sizeof tmp || member[len - 1] == '/') return 0;
    memcpy(tmp, member, len);
    tmp[len] = 0;
    if (!strncmp(tmp, "__MACOSX/", 9)) return 0;
    if (dem_has_ext(tmp, ".hgt")) return 3;
    for (i = 0; i < sizeof ext / sizeof ext[0]; i++)
        if (dem_has_ext(tmp, ext[i])) return 2;
    return 0;
}

static br_status load_mem_depth(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                                hf *out, br_err *err, int depth);

static br_status load_zip(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                          hf *out, br_err *err, int depth)
{
    size_t eocd = 0, i, off, cd_off, cd_size, best_off = 0;
    uint32_t entries, k, best_comp = 0, best_size = 0, best_crc = 0;
    int found = 0, best_rank = 0, best_method = 0;
    const uint8_t *best_name = NULL;
    size_t best_nlen = 0;
    char first[128] = "";
    char inner[1024];
    uint8_t *data = NULL;
    size_t data_n = 0;
    const uint8_t *src;
    size_t lh_name, lh_extra, dpos;
    br_status s;

    if (n < 22) return br_err_set(err, BR_E_TRUNCATED, name, "zip archive too short");
    for (i = n - 22 + 1; i-- > 0 && n - i <= 22 + 65535;) {
        if (dem_le32(p + i) == 0x06054b50u) { eocd = i; found = 1; break; }
    }
    if (!found) return br_err_set(err, BR_E_TRUNCATED, name, "zip end-of-directory record missing");
    entries = dem_le16(p + eocd + 10);
    cd_size = dem_le32(p + eocd + 12);
    cd_off = dem_le32(p + eocd + 16);
    if (cd_off == 0xffffffffu || entries == 0xffff)
        return br_err_set(err, BR_E_UNSUPPORTED, name, "zip64 archives are not supported");
    if (cd_off > eocd || cd_size > eocd - cd_off)
        return br_err_set(err, BR_E_FORMAT, name, "zip central directory out of bounds");
    off = cd_off;
    for (k = 0; k < entries; k++) {
        uint32_t nlen, xlen, clen;
        int rank;
        if (eocd - off < 46 || dem_le32(p + off) != 0x02014b50u)
            return br_err_set(err, BR_E_FORMAT, name, "zip central directory entry %u is corrupt", k);
        nlen = dem_le16(p + off + 28);
        xlen = dem_le16(p + off + 30);
        clen = dem_le16(p + off + 32);
        if (eocd - off - 46 < (size_t)nlen + xlen + clen)
            return br_err_set(err, BR_E_FORMAT, name, "zip central directory entry %u is corrupt", k);
        if (k == 0) {
            size_t c = nlen < sizeof first - 1 ? nlen : sizeof first - 1;
            memcpy(first, p + off + 46, c);
            first[c] = 0;
            for (i = 0; i < c; i++) if (!isprint((unsigned char)first[i])) first[i] = '?';
        }
        rank = zip_rank((const char *)p + off + 46, nlen);
        if (rank > best_rank) {
            best_rank = rank;
            best_method = dem_le16(p + off + 10);
            best_crc = dem_le32(p + off + 16);
            best_comp = dem_le32(p + off + 20);
            best_size = dem_le32(p + off + 24);
            best_off = dem_le32(p + off + 42);
            best_name = p + off + 46;
            best_nlen = nlen;
            if (dem_le16(p + off + 8) & 1)
                return br_err_set(err, BR_E_UNSUPPORTED, name, "zip member is encrypted");
        }
        off += 46 + (size_t)nlen + xlen + clen;
    }
    if (!best_rank)
        return br_err_set(err, BR_E_FORMAT, name, "zip archive has no height data among its %u member(s)%s%s",
                          entries, entries ? " (first: " : "", entries ? first : "");
    if (best_comp == 0xffffffffu || best_size == 0xffffffffu)
        return br_err_set(err, BR_E_UNSUPPORTED, name, "zip64 members are not supported");
    snprintf(inner, sizeof inner, "%s/%.*s", name, (int)best_nlen, (const char *)best_name);
    for (i = strlen(name) + 1; inner[i]; i++) if (!isprint((unsigned char)inner[i])) inner[i] = '?';
    if (best_off > n || n - best_off < 30 || dem_le32(p + best_off) != 0x04034b50u)
        return br_err_set(err, BR_E_FORMAT, inner, "zip local header missing or out of bounds");
    lh_name = dem_le16(p + best_off + 26);
    lh_extra = dem_le16(p + best_off + 28);
    dpos = best_off + 30 + lh_name + lh_extra;
    if (dpos > n || n - dpos < best_comp)
        return br_err_set(err, BR_E_TRUNCATED, inner, "zip member data runs past the end of the archive");
    src = p + dpos;
    if (best_method == 0) {
        if (best_comp != best_size)
            return br_err_set(err, BR_E_FORMAT, inner, "stored zip member sizes disagree");
        if (crc32(0L, src, best_size) != best_crc)
            return br_err_set(err, BR_E_FORMAT, inner, "zip member fails its CRC check");
        return load_mem_depth(inner, src, best_size, o, out, err, depth + 1);
    }
    if (best_method != 8)
        return br_err_set(err, BR_E_UNSUPPORTED, inner, "zip compression method %d (only stored and deflate)",
                          best_method);
    s = dem_inflate_alloc(inner, inner, src, best_comp, -15, best_size, DEM_DECLARED_EXACT, &data, &data_n, err);
    if (s != BR_OK) return s;
    if (data_n != best_size) {
        free(data);
        return br_err_set(err, BR_E_FORMAT, inner, "zip member inflates to %zu bytes, directory says %u",
                          data_n, best_size);
    }
    if (crc32(0L, data, (uInt)data_n) != best_crc) {
        free(data);
        return br_err_set(err, BR_E_FORMAT, inner, "zip member fails its CRC check");
    }
    s = load_mem_depth(inner, data, data_n, o, out, err, depth + 1);
    free(data);
    return s;
}

/* ---- dispatch ---- */

static int is_text_start(const uint8_t *p, size_t n, const char *word)
{
    size_t i = 0, k;
    while (i < n && (p[i] == ' ' || p[i] == '\t' || p[i] == '\r' || p[i] == '\n')) i++;
    for (k = 0; word[k]; k++, i++)
        if (i >= n || tolower(p[i]) != word[k]) return 0;
    return 1;
}

static int is_numeric_start(const uint8_t *p, size_t n)
{
    size_t i = 0;
    while (i < n && (p[i] == ' ' || p[i] == '\t' || p[i] == '\r' || p[i] == '\n')) i++;
    return i < n && (isdigit(p[i]) || p[i] == '-' || p[i] == '+' || p[i] == '.');
}

static int is_square_hgt(size_t n)
{
    size_t k;
    if (n < 8 || n % 2) return 0;
    k = (size_t)sqrt((double)(n / 2));
    while (k * k > n / 2) k--;
    while ((k + 1) * (k + 1) <= n / 2) k++;
    return k * k * 2 == n;
}

static br_status load_mem_depth(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                                hf *out, br_err *err, int depth)
{
    static const dem_opts zero;
    dem_reader *rd = NULL;
    char ext[1024];
    const char *en = name;   /* the name whose extension selects the reader */
    if (!o) o = &zero;
    if (n >= 3 && p[0] == 0x1f && p[1] == 0x8b && p[2] == 8) {
        uint8_t *data;
        size_t dn;
        br_status s;
        if (depth) return br_err_set(err, BR_E_UNSUPPORTED, name, "nested compressed archives are not read");
        /* the payload's name is ours without ".gz" (the format's cap follows it) */
        size_t len = strlen(name);
        if (dem_has_ext(name, ".gz") && len - 3 < sizeof ext) { memcpy(ext, name, len - 3); ext[len - 3] = 0; }
        else snprintf(ext, sizeof ext, "%s", name);
        s = dem_inflate_alloc(name, ext, p, n, 15 + 16, n >= 18 ? dem_le32(p + n - 4) : 0,
                              n >= 18 ? DEM_DECLARED_MOD32 : DEM_DECLARED_NONE, &data, &dn, err);
        if (s != BR_OK) return s;
        s = load_mem_depth(name, data, dn, o, out, err, depth + 1);
        free(data);
        return s;
    }
    if (n >= 4 && dem_le32(p) == 0x04034b50u) {
        if (depth) return br_err_set(err, BR_E_UNSUPPORTED, name, "nested compressed archives are not read");
        return load_zip(name, p, n, o, out, err, depth);
    }
    if (!depth && (dem_has_ext(name, ".gz") || dem_has_ext(name, ".zip")))
        return br_err_set(err, BR_E_FORMAT, name, "not a %s archive (wrong magic)",
                          dem_has_ext(name, ".gz") ? "gzip" : "zip");
    /* inside a .gz the extension that counts is the one before ".gz" */
    if (dem_has_ext(name, ".gz")) {
        size_t len = strlen(name);
        if (len - 3 < sizeof ext) { memcpy(ext, name, len - 3); ext[len - 3] = 0; en = ext; }
    }
    if (n >= 8 && !memcmp(p, "\x89PNG\r\n\x1a\n", 8)) rd = dem_read_png;
    else if (n >= 4 && (!memcmp(p, "II", 2) || !memcmp(p, "MM", 2)) &&
             (dem_le16(p + 2) == 42 || dem_be16(p + 2) == 42 || dem_le16(p + 2) == 43 || dem_be16(p + 2) == 43))
        rd = dem_read_tif;
    else if (n >= 7 && !memcmp(p, "binterr", 7)) rd = dem_read_bt;
    else if (dem_has_ext(en, ".hgt")) rd = dem_read_hgt;
    else if (dem_has_ext(en, ".png")) rd = dem_read_png;
    else if (dem_has_ext(en, ".tif") || dem_has_ext(en, ".tiff")) rd = dem_read_tif;
    else if (dem_has_ext(en, ".bt")) rd = dem_read_bt;
    else if (dem_geoclaw_start(p, n)) rd = dem_read_geoclaw;   /* before the text extensions */
    else if (dem_has_ext(en, ".tt2") || dem_has_ext(en, ".tt3") || dem_has_ext(en, ".topotype2") ||
             dem_has_ext(en, ".topotype3")) rd = dem_read_geoclaw;
    else if (dem_has_ext(en, ".asc")) rd = dem_read_asc;
    else if (dem_has_ext(en, ".xyz") || dem_has_ext(en, ".txt") || dem_has_ext(en, ".tt1") ||
             dem_has_ext(en, ".topotype1") || dem_has_ext(en, ".txyz")) rd = dem_read_xyz;
    else if (is_text_start(p, n, "ncols") || is_text_start(p, n, "nrows")) rd = dem_read_asc;
    else if (is_square_hgt(n)) rd = dem_read_hgt;
    else if (is_numeric_start(p, n)) rd = dem_read_xyz;
    else return br_err_set(err, BR_E_FORMAT, name, "unknown elevation format (%zu bytes)", n);
    return rd(name, p, n, o, out, err);
}

br_status dem_load_mem(const char *name, const uint8_t *bytes, size_t len, const dem_opts *o,
                       hf *out, br_err *err)
{
    if (!name) name = "(memory)";
    if (!out || (!bytes && len)) return br_err_set(err, BR_E_ARG, name, "no output or no data");
    if (!bytes) bytes = (const uint8_t *)"";
    return load_mem_depth(name, bytes, len, o, out, err, 0);
}

br_status dem_load(const char *path, const dem_opts *o, hf *out, br_err *err)
{
    uint8_t *data = NULL;
    size_t n = 0;
    char where[ASSET_PATH_MAX];
    br_status s = asset_resolve(path, where, sizeof where, &path, err);
    if (s != BR_OK) return s;
    s = dem_read_file(path, &data, &n, err);
    if (s != BR_OK) return s;
    s = dem_load_mem(path, data, n, o, out, err);
    free(data);
    return s;
}

void dem_free(hf *f)
{
    if (!f) return;
    free(f->z);
    f->z = NULL;
}
