/* platform/load_io.c — the bytes behind the readers: reading a file and
 * inflating a .gz or .zip member, both bounded by what a heightfield of the
 * format at hand can take (load_internal.h, dem_format_cap).
 *
 * Files: only regular files are read (a directory, device, pipe or socket is
 * refused before any read: /dev/zero would never end); the size from fstat is
 * checked against the cap of the format named by the first 64 KiB and the
 * name, and the read itself stops past the cap (files whose st_size is 0, as
 * in /proc, are still bounded).
 * Compressed members: the size a zip directory declares is checked against the
 * cap before inflating; while the bytes arrive the output may pass neither the
 * declared size (zip; gzip's ISIZE when it is below the cap) nor the cap of
 * the format that the name and the first inflated bytes show. */
#define _POSIX_C_SOURCE 200809L
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>
#include "platform/load_internal.h"

/* Bytes a file may have beyond its samples: PNG ancillary chunks, TIFF
 * directories and tags, text headers and comments. */
#define CAP_SLACK ((uint64_t)16 << 20)
/* Text: a value token is at most 71 characters (dem_scan_number) but real
 * writers use up to 23 ("%22.15e" and a blank, GeoClaw's old default); 32 per
 * value leaves room for wide separators, 96 per XYZ line for three values. */
#define TEXT_BYTES_PER_VALUE 32
#define XYZ_BYTES_PER_POINT 96

static int is_text_byte(uint8_t c) { return c == '\t' || c == '\n' || c == '\r' || (c >= 32 && c < 127); }

uint64_t dem_format_cap(const char *name, const uint8_t *p, size_t n, const char **what)
{
    const uint64_t S = (uint64_t)BR_MAX_SAMPLES;
    const char *unused;
    uint64_t cap;
    if (!what) what = &unused;
    if (n >= 2 && p[0] == 0x1f && p[1] == 0x8b) { *what = "compressed (gzip)"; return XYZ_BYTES_PER_POINT * S + CAP_SLACK; }
    if (n >= 4 && dem_le32(p) == 0x04034b50u) { *what = "compressed (zip)"; return XYZ_BYTES_PER_POINT * S + CAP_SLACK; }
    if ((n >= 8 && !memcmp(p, "\x89PNG\r\n\x1a\n", 8)) || (n < 8 && dem_has_ext(name, ".png"))) {
        /* the deflated rows of IHDR's w x h at 8 bytes a pixel (16-bit RGBA,
         * more than any PNG we read holds) plus a filter byte a row */
        uint64_t w = BR_MAX_SIDE, h = BR_MAX_SIDE, raw;
        if (n >= 24 && !memcmp(p + 12, "IHDR", 4)) {
            w = dem_be32(p + 16);
            h = dem_be32(p + 20);
            if (w > BR_MAX_SIDE) w = BR_MAX_SIDE;
            if (h > BR_MAX_SIDE) h = BR_MAX_SIDE;
        }
        raw = h * (1 + 8 * w);
        *what = "PNG";
        return raw + raw / 8 + CAP_SLACK;
    }
    if ((n >= 4 && (!memcmp(p, "II", 2) || !memcmp(p, "MM", 2))) ||
        (n < 4 && (dem_has_ext(name, ".tif") || dem_has_ext(name, ".tiff")))) {
        /* 4 bytes a sample, LZW's 12-bit codes for 8-bit data at worst 1.5x */
        *what = "TIFF";
        return 6 * S + CAP_SLACK;
    }
    if ((n >= 7 && !memcmp(p, "binterr", 7)) || (n < 7 && dem_has_ext(name, ".bt"))) {
        *what = "BT";
        if (n >= 20) {   /* the header states the size exactly; the reader checks it */
            int64_t c = (int32_t)dem_le32(p + 10), r = (int32_t)dem_le32(p + 14);
            if (c >= 1 && r >= 1 && c <= BR_MAX_SIDE && r <= BR_MAX_SIDE && c * r <= (int64_t)S)
                return 256 + (uint64_t)(c * r) * 4;
        }
        return 256 + 4 * S;
    }
    if (dem_has_ext(name, ".hgt")) { *what = "SRTM .hgt"; return 2 * S; }
    cap = 0;
    if (dem_has_ext(name, ".asc") || dem_has_ext(name, ".tt2") || dem_has_ext(name, ".tt3") ||
        dem_has_ext(name, ".topotype2") || dem_has_ext(name, ".topotype3")) {
        *what = "text grid";
        cap = TEXT_BYTES_PER_VALUE * S + CAP_SLACK;
    } else {
        *what = "text";
        cap = XYZ_BYTES_PER_POINT * S + CAP_SLACK;
    }
    /* a file without magic whose first bytes are not text can only be an .hgt */
    {
        size_t i, m = n < 512 ? n : 512;
        for (i = 0; i < m && is_text_byte(p[i]); i++) {}
        if (i < m) { *what = "SRTM .hgt"; return 2 * S; }
    }
    return cap;
}

static br_status too_big(br_err *err, const char *name, uint64_t size, const char *what, uint64_t cap,
                         const char *verb)
{
    return br_err_set(err, BR_E_TOO_BIG, name,
                      "%s %llu bytes, more than a %s heightfield of up to %dx%d samples can take (%llu)",
                      verb, (unsigned long long)size, what, BR_MAX_SIDE, BR_MAX_SIDE, (unsigned long long)cap);
}

br_status dem_read_file(const char *path, uint8_t **data, size_t *n, br_err *err)
{
    FILE *f;
    struct stat st;
    uint8_t *buf = NULL;
    size_t alloc, have = 0;
    uint64_t cap = 0, size;
    const char *what = "";
    int capped = 0;
    if (stat(path, &st) != 0) return br_err_set(err, BR_E_IO, path, "cannot open");
    if (S_ISDIR(st.st_mode)) return br_err_set(err, BR_E_IO, path, "is a directory, not a file");
    if (!S_ISREG(st.st_mode))
        return br_err_set(err, BR_E_IO, path, "is not a regular file (a device, pipe or socket): not read");
    f = fopen(path, "rb");
    if (!f) return br_err_set(err, BR_E_IO, path, "cannot open");
    /* the file may have changed between stat and fopen: check what was opened */
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        fclose(f);
        return br_err_set(err, BR_E_IO, path, "is not a regular file: not read");
    }
    size = st.st_size > 0 ? (uint64_t)st.st_size : 0;
    alloc = 65536;
    for (;;) {
        size_t got;
        if (!buf || have == alloc) {
            uint64_t want = !buf ? 65536 : (uint64_t)alloc * 2;
            uint8_t *nb;
            if (capped && size + 1 > want && size + 1 <= cap + 1) want = size + 1;
            if (capped && want > cap + 1) want = cap + 1;
            if (want > SIZE_MAX) want = SIZE_MAX;
            nb = realloc(buf, (size_t)want);
            if (!nb) { free(buf); fclose(f); return br_err_set(err, BR_E_NOMEM, path, "out of memory reading the file"); }
            buf = nb;
            alloc = (size_t)want;
        }
        got = fread(buf + have, 1, alloc - have, f);
        have += got;
        if (!capped && (have >= 65536 || got == 0 || have < alloc)) {
            cap = dem_format_cap(path, buf, have, &what);
            capped = 1;
            if (size > cap) { free(buf); fclose(f); return too_big(err, path, size, what, cap, "is"); }
        }
        if (capped && have > cap) { free(buf); fclose(f); return too_big(err, path, have, what, cap, "has more than"); }
        if (have < alloc) break;       /* end of file or an error */
    }
    if (ferror(f)) { free(buf); fclose(f); return br_err_set(err, BR_E_IO, path, "read error"); }
    fclose(f);
    *data = buf;
    *n = have;
    return BR_OK;
}

/* Whether the declared size bounds the output.  A zip's central directory sits
 * at the end of the archive and has been checked, so its size is the member's.
 * A gzip ISIZE is the size modulo 2^32 and, in a cut file, four arbitrary
 * bytes: it bounds the output only when it is below the format's cap (which is
 * below 2^32 for every binary format); otherwise the cap alone does. */
static int declared_bounds(int kind, uint64_t declared, uint64_t fcap)
{
    return kind == DEM_DECLARED_EXACT || (kind == DEM_DECLARED_MOD32 && declared <= fcap);
}

br_status dem_inflate_alloc(const char *name, const char *inner, const uint8_t *src, size_t n, int window_bits,
                            uint64_t declared, int declared_kind, uint8_t **out, size_t *outn, br_err *err)
{
    z_stream zs;
    uint8_t *buf = NULL;
    size_t cap, have = 0, in_left = n;
    uint64_t limit, fcap;
    const char *what;
    int r = Z_OK, sniffed = 0;
    fcap = dem_format_cap(inner, NULL, 0, &what);
    if (fcap > (uint64_t)DEM_MAX_INFLATE) fcap = DEM_MAX_INFLATE;
    if (declared_kind == DEM_DECLARED_EXACT && declared > fcap)
        return too_big(err, name, declared, what, fcap, "declares");
    limit = declared_bounds(declared_kind, declared, fcap) ? declared : fcap;
    /* deflate cannot expand by more than ~1032x: a larger size is a lie, and the
     * first allocation follows the compressed size instead */
    cap = declared_kind && declared / 1032 <= n + 64 ? (size_t)declared : n * 4 + 1024;
    if (cap > limit) cap = (size_t)limit;
    cap += 1;    /* one byte past the limit shows a stream that goes on */
    memset(&zs, 0, sizeof zs);
    if (inflateInit2(&zs, window_bits) != Z_OK)
        return br_err_set(err, BR_E_NOMEM, name, "cannot start zlib");
    buf = malloc(cap);
    if (!buf) { inflateEnd(&zs); return br_err_set(err, BR_E_NOMEM, name, "out of memory"); }
    zs.next_in = (Bytef *)(uintptr_t)src;
    for (;;) {
        uInt chunk_in = in_left > (1u << 30) ? (1u << 30) : (uInt)in_left;
        size_t room;
        if (have == cap) {     /* here have <= limit (checked below), so the buffer grows */
            size_t ncap = (uint64_t)cap * 2 > limit + 1 ? (size_t)limit + 1 : cap * 2;
            uint8_t *nb = realloc(buf, ncap);
            if (!nb) { free(buf); inflateEnd(&zs); return br_err_set(err, BR_E_NOMEM, name, "out of memory"); }
            buf = nb; cap = ncap;
        }
        room = cap - have;
        zs.avail_in = chunk_in;
        zs.next_out = buf + have;
        zs.avail_out = room > (1u << 30) ? (1u << 30) : (uInt)room;
        {
            uInt before_out = zs.avail_out;
            r = inflate(&zs, Z_NO_FLUSH);
            have += before_out - zs.avail_out;
            in_left -= chunk_in - zs.avail_in;
        }
        if (!sniffed && (have >= 4096 || r == Z_STREAM_END)) {
            /* the first bytes show the format, whose cap may be lower */
            uint64_t c2 = dem_format_cap(inner, buf, have, &what);
            sniffed = 1;
            if (c2 < fcap) fcap = c2;
            if (declared_kind == DEM_DECLARED_EXACT && declared > fcap) {
                free(buf); inflateEnd(&zs);
                return too_big(err, name, declared, what, fcap, "declares");
            }
            limit = declared_bounds(declared_kind, declared, fcap) ? declared : fcap;
        }
        if (have > limit) {
            free(buf); inflateEnd(&zs);
            if (declared_bounds(declared_kind, declared, fcap))
                return br_err_set(err, BR_E_TOO_BIG, name, "inflates to more than the %llu bytes its %s declares",
                                  (unsigned long long)declared,
                                  declared_kind == DEM_DECLARED_EXACT ? "zip directory" : "gzip trailer");
            return too_big(err, name, have, what, limit, "inflates to more than");
        }
        if (r == Z_STREAM_END) break;
        if (r == Z_NEED_DICT || r == Z_DATA_ERROR || r == Z_MEM_ERROR) {
            free(buf); inflateEnd(&zs);
            return br_err_set(err, r == Z_MEM_ERROR ? BR_E_NOMEM : BR_E_FORMAT, name,
                              "corrupt compressed data (%s)", zs.msg ? zs.msg : "zlib error");
        }
        if (in_left == 0 && zs.avail_out != 0 && (r == Z_BUF_ERROR || r == Z_OK)) {
            free(buf); inflateEnd(&zs);
            return br_err_set(err, BR_E_TRUNCATED, name, "compressed data ends early");
        }
    }
    inflateEnd(&zs);
    *out = buf;
    *outn = have;
    return BR_OK;
}

br_status dem_inflate_into(const char *name, const uint8_t *src, size_t n, uint8_t *dst,
                           size_t dn, br_err *err)
{
    z_stream zs;
    int r;
    if (n > UINT_MAX || dn > UINT_MAX)
        return br_err_set(err, BR_E_TOO_BIG, name, "compressed block too large");
    memset(&zs, 0, sizeof zs);
    if (inflateInit(&zs) != Z_OK) return br_err_set(err, BR_E_NOMEM, name, "cannot start zlib");
    zs.next_in = (Bytef *)(uintptr_t)src;
    zs.avail_in = (uInt)n;
    zs.next_out = dst;
    zs.avail_out = (uInt)dn;
    r = inflate(&zs, Z_FINISH);
    inflateEnd(&zs);
    if (r == Z_STREAM_END && zs.avail_out == 0) return BR_OK;
    /* a stream that fills dst exactly but has trailing data is accepted as GDAL does */
    if ((r == Z_OK || r == Z_BUF_ERROR) && zs.avail_out == 0) return BR_OK;
    if (r == Z_STREAM_END || (r == Z_BUF_ERROR && zs.avail_in == 0))
        return br_err_set(err, BR_E_TRUNCATED, name, "compressed block holds %zu of %zu bytes",
                          dn - zs.avail_out, dn);
    return br_err_set(err, BR_E_FORMAT, name, "corrupt deflate block");
}
