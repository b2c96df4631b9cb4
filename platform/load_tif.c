/* platform/load_tif.c — a minimal GeoTIFF reader for single-band elevation.
 *
 * Reads: classic TIFF, little- or big-endian (BigTIFF is refused); the first
 * image; strips or tiles; no compression, deflate (8 and 32946) and LZW (5,
 * MSB-first with TIFF's early code-width change); predictor 1 or 2 (integer
 * samples); one sample per pixel of int16, uint16, int32, uint32, uint8 or
 * float32.  Every offset and count is checked against the file before use, and
 * the image size against core/hf.h's limits before anything is allocated.
 * Georeference: ModelPixelScale (33550) + the first ModelTiepoint (33922),
 * PixelIsArea or PixelIsPoint (GTRasterTypeGeoKey 1025), geographic when
 * GTModelTypeGeoKey (1024) is 2, projected (metres, or feet by
 * ProjLinearUnitsGeoKey 3076) when 1, guessed from the numbers without keys.
 * GDAL_NODATA (42113) marks voids ("nan" makes NaN a void), and so does
 * dem_opts.nodata (besides the tag; float samples compared as float32); other
 * NaN/inf samples are errors.  Integers keep 1 m; floats use the float rule. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "platform/load_internal.h"

enum { T_BYTE = 1, T_ASCII = 2, T_SHORT = 3, T_LONG = 4, T_RATIONAL = 5, T_SBYTE = 6, T_UNDEF = 7,
       T_SSHORT = 8, T_SLONG = 9, T_SRATIONAL = 10, T_FLOAT = 11, T_DOUBLE = 12 };

typedef struct tif {
    const char *name;
    const uint8_t *p;
    size_t n;
    int be;
    br_err *err;
} tif;

typedef struct tag {
    uint16_t id, type;
    uint32_t count;
    size_t off;         /* where the values are (inline or at the offset) */
    int present;
} tag;

static uint16_t rd16(const tif *t, const uint8_t *q) { return t->be ? dem_be16(q) : dem_le16(q); }
static uint32_t rd32(const tif *t, const uint8_t *q) { return t->be ? dem_be32(q) : dem_le32(q); }

static size_t type_size(uint16_t type)
{
    switch (type) {
    case T_BYTE: case T_ASCII: case T_SBYTE: case T_UNDEF: return 1;
    case T_SHORT: case T_SSHORT: return 2;
    case T_LONG: case T_SLONG: case T_FLOAT: return 4;
    case T_RATIONAL: case T_SRATIONAL: case T_DOUBLE: return 8;
    default: return 0;
    }
}

/* value i of an integer tag (SHORT or LONG, also BYTE); 0 with *ok = 0 if not */
static uint32_t tag_uint(const tif *t, const tag *g, uint32_t i, int *ok)
{
    const uint8_t *q;
    if (!g->present || i >= g->count) { *ok = 0; return 0; }
    q = t->p + g->off;
    switch (g->type) {
    case T_BYTE: return q[i];
    case T_SHORT: return rd16(t, q + 2 * (size_t)i);
    case T_LONG: return rd32(t, q + 4 * (size_t)i);
    default: *ok = 0; return 0;
    }
}

static double tag_double(const tif *t, const tag *g, uint32_t i, int *ok)
{
    const uint8_t *q;
    if (!g->present || i >= g->count) { *ok = 0; return 0; }
    q = t->p + g->off;
    if (g->type == T_DOUBLE) {
        uint64_t u = t->be ? (uint64_t)dem_be32(q + 8 * (size_t)i) << 32 | dem_be32(q + 8 * (size_t)i + 4)
                           : (uint64_t)dem_le32(q + 8 * (size_t)i + 4) << 32 | dem_le32(q + 8 * (size_t)i);
        double d;
        memcpy(&d, &u, sizeof d);
        return d;
    }
    if (g->type == T_FLOAT) {
        uint32_t u = rd32(t, q + 4 * (size_t)i);
        float f;
        memcpy(&f, &u, sizeof f);
        return (double)f;
    }
    return tag_uint(t, g, i, ok);
}

/* ---- LZW (TIFF 6.0 section 13) ---- */

static br_status lzw_decode(const tif *t, const uint8_t *src, size_t n, uint8_t *dst, size_t dn)
{
    uint16_t prefix[4096];
    uint8_t suffix[4096], first[4096];
    uint16_t len[4096];
    uint32_t bitbuf = 0;
    int bits = 0, width = 9, next = 258, prev = -1, i;
    size_t ip = 0, op = 0;
    if (n >= 2 && src[0] == 0 && (src[1] & 1))
        return br_err_set(t->err, BR_E_UNSUPPORTED, t->name, "old-style (LSB-first) LZW is not supported");
    for (i = 0; i < 256; i++) { prefix[i] = 0xffff; suffix[i] = (uint8_t)i; first[i] = (uint8_t)i; len[i] = 1; }
    while (op < dn) {
        int code, c, l;
        while (bits < width) {
            if (ip >= n) goto done;
            bitbuf = (bitbuf << 8 | src[ip++]) & 0xffffffu;
            bits += 8;
        }
        code = (int)(bitbuf >> (bits - width)) & ((1 << width) - 1);
        bits -= width;
        if (code == 257) break;
        if (code == 256) { width = 9; next = 258; prev = -1; continue; }
        if (prev < 0) {
            if (code > 255) return br_err_set(t->err, BR_E_FORMAT, t->name, "corrupt LZW data");
            dst[op++] = (uint8_t)code;
            prev = code;
            continue;
        }
        if (code > next || (code == next && next >= 4096))
            return br_err_set(t->err, BR_E_FORMAT, t->name, "corrupt LZW data");
        if (next < 4096) {
            prefix[next] = (uint16_t)prev;
            suffix[next] = code < next ? first[code] : first[prev];
            first[next] = first[prev];
            len[next] = (uint16_t)(len[prev] + 1);
            next++;
            if (next == (1 << width) - 1 && width < 12) width++;
        }
        /* write the string of code backwards, clipped to dst */
        l = len[code];
        for (c = code, i = l - 1; i >= 0; i--) {
            if (op + (size_t)i < dn) dst[op + (size_t)i] = suffix[c];
            c = prefix[c];
        }
        op += (size_t)l;
        prev = code;
    }
done:
    if (op < dn)
        return br_err_set(t->err, BR_E_TRUNCATED, t->name, "LZW block holds %zu of %zu bytes", op, dn);
    return BR_OK;
}

static int parse_nodata(const tif *t, const tag *g, double *v, int *is_nan)
{
    char buf[64];
    size_t i, k = 0;
    char *end;
    if (!g->present || g->type != T_ASCII || g->count == 0) return 0;
    for (i = 0; i < g->count && k < sizeof buf - 1; i++) {
        char c = (char)t->p[g->off + i];
        if (c == 0) break;
        if (c != ' ') buf[k++] = c;
    }
    buf[k] = 0;
    if (!k) return 0;
    if (!strcmp(buf, "nan") || !strcmp(buf, "NaN") || !strcmp(buf, "-nan")) { *is_nan = 1; return 1; }
    *v = strtod(buf, &end);
    return *end == 0 && isfinite(*v);
}

br_status dem_read_tif(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                       hf *out, br_err *err)
{
    enum { G_W, G_H, G_BPS, G_COMP, G_SOFF, G_SPP, G_RPS, G_SBC, G_PLANAR, G_PRED, G_TW, G_TH, G_TOFF,
           G_TBC, G_SFMT, G_SCALE, G_TIE, G_GEOKEYS, G_NODATA, G_N };
    static const uint16_t ids[G_N] = { 256, 257, 258, 259, 273, 277, 278, 279, 284, 317, 322, 323, 324,
                                       325, 339, 33550, 33922, 34735, 42113 };
    tag g[G_N];
    tif t;
    uint32_t ifd, nent, i, w, h, bps, comp, spp, pred, sfmt, bw, bh, across, down, nblocks, b;
    int ok = 1, tiled, nodata_nan = 0, have_nodata, model = 0, raster = 1, lin_units = 9001;
    size_t bpsb, blockbytes, cnt;
    uint8_t *raw = NULL, *blk = NULL;
    double nodata = 0, maxabs = 0;
    int32_t den = 1;
    hf f;
    br_status s = BR_OK;
    int user_nd = 0;
    double user_v = 0;

    memset(&t, 0, sizeof t);
    memset(g, 0, sizeof g);
    t.name = name; t.p = p; t.n = n; t.err = err;
    if (n < 8) return br_err_set(err, BR_E_TRUNCATED, name, "TIFF header truncated");
    if (!memcmp(p, "II", 2)) t.be = 0;
    else if (!memcmp(p, "MM", 2)) t.be = 1;
    else return br_err_set(err, BR_E_FORMAT, name, "not a TIFF file (wrong magic)");
    if (rd16(&t, p + 2) == 43) return br_err_set(err, BR_E_UNSUPPORTED, name, "BigTIFF is not supported");
    if (rd16(&t, p + 2) != 42) return br_err_set(err, BR_E_FORMAT, name, "not a TIFF file (wrong magic)");
    ifd = rd32(&t, p + 4);
    if (ifd < 8) return br_err_set(err, BR_E_FORMAT, name, "TIFF directory offset %u is bad", ifd);
    if (ifd > n - 2) return br_err_set(err, BR_E_TRUNCATED, name, "TIFF directory at %u is past the end (%zu bytes)", ifd, n);
    nent = rd16(&t, p + ifd);
    if ((size_t)nent * 12 > n - ifd - 2)
        return br_err_set(err, BR_E_TRUNCATED, name, "TIFF directory of %u entries runs past the end", nent);
    for (i = 0; i < nent; i++) {
        const uint8_t *e = p + ifd + 2 + 12 * (size_t)i;
        uint16_t id = rd16(&t, e), type = rd16(&t, e + 2);
        uint32_t count = rd32(&t, e + 4);
        size_t ts = type_size(type), total;
        int k;
        for (k = 0; k < G_N && ids[k] != id; k++) {}
        if (k == G_N) continue;
        if (!ts || count == 0)
            return br_err_set(err, BR_E_FORMAT, name, "TIFF tag %u has type %u and %u values", id, type, count);
        if (g[k].present) return br_err_set(err, BR_E_FORMAT, name, "TIFF tag %u given twice", id);
        total = ts * count;
        if (total / ts != count) return br_err_set(err, BR_E_FORMAT, name, "TIFF tag %u too large", id);
        g[k].id = id; g[k].type = type; g[k].count = count; g[k].present = 1;
        if (total <= 4) g[k].off = (size_t)(e + 8 - p);
        else {
            uint32_t vo = rd32(&t, e + 8);
            if (vo > n || total > n - vo)
                return br_err_set(err, BR_E_TRUNCATED, name, "TIFF tag %u values at %u run past the end", id, vo);
            g[k].off = vo;
        }
    }
    if (!g[G_W].present || !g[G_H].present)
        return br_err_set(err, BR_E_FORMAT, name, "TIFF lacks ImageWidth or ImageLength");
    w = tag_uint(&t, &g[G_W], 0, &ok);
    h = tag_uint(&t, &g[G_H], 0, &ok);
    bps = g[G_BPS].present ? tag_uint(&t, &g[G_BPS], 0, &ok) : 1;
    comp = g[G_COMP].present ? tag_uint(&t, &g[G_COMP], 0, &ok) : 1;
    spp = g[G_SPP].present ? tag_uint(&t, &g[G_SPP], 0, &ok) : 1;
    pred = g[G_PRED].present ? tag_uint(&t, &g[G_PRED], 0, &ok) : 1;
    sfmt = g[G_SFMT].present ? tag_uint(&t, &g[G_SFMT], 0, &ok) : 1;
    if (!ok) return br_err_set(err, BR_E_FORMAT, name, "TIFF basic tag of the wrong type");
    if (w < 1 || h < 1) return br_err_set(err, BR_E_FORMAT, name, "TIFF image of %ux%u pixels", w, h);
    if (hf_check_dims(w, h) != BR_OK) return dem_alloc(&f, w, h, name, err);
    if (spp != 1) return br_err_set(err, BR_E_UNSUPPORTED, name, "TIFF has %u samples per pixel (heights need 1)", spp);
    if (!((bps == 8 && sfmt == 1) || (bps == 16 && (sfmt == 1 || sfmt == 2)) ||
          (bps == 32 && (sfmt == 1 || sfmt == 2 || sfmt == 3))))
        return br_err_set(err, BR_E_UNSUPPORTED, name, "TIFF samples of %u bits, format %u are not read", bps, sfmt);
    if (comp != 1 && comp != 5 && comp != 8 && comp != 32946)
        return br_err_set(err, BR_E_UNSUPPORTED, name, "TIFF compression %u is not read (none, LZW, deflate)", comp);
    if (pred != 1 && !(pred == 2 && sfmt != 3))
        return br_err_set(err, BR_E_UNSUPPORTED, name, "TIFF predictor %u with sample format %u is not read", pred, sfmt);
    bpsb = bps / 8;
    tiled = g[G_TW].present || g[G_TOFF].present;
    if (tiled) {
        if (!g[G_TW].present || !g[G_TH].present || !g[G_TOFF].present || !g[G_TBC].present)
            return br_err_set(err, BR_E_FORMAT, name, "TIFF tiles lack TileWidth/TileLength/TileOffsets/TileByteCounts");
        bw = tag_uint(&t, &g[G_TW], 0, &ok);
        bh = tag_uint(&t, &g[G_TH], 0, &ok);
        if (!ok || bw < 1 || bh < 1 || bw > 65536 || bh > 65536)
            return br_err_set(err, BR_E_FORMAT, name, "TIFF tile size %ux%u is absurd", bw, bh);
        across = (w + bw - 1) / bw;
        down = (h + bh - 1) / bh;
    } else {
        if (!g[G_SOFF].present || !g[G_SBC].present)
            return br_err_set(err, BR_E_FORMAT, name, "TIFF lacks StripOffsets or StripByteCounts");
        bw = w;
        bh = g[G_RPS].present ? tag_uint(&t, &g[G_RPS], 0, &ok) : h;
        if (!ok || bh < 1) return br_err_set(err, BR_E_FORMAT, name, "TIFF RowsPerStrip %u is bad", bh);
        if (bh > h) bh = h;
        across = 1;
        down = (h + bh - 1) / bh;
    }
    /* a block may exceed the image (tiles pad it) but not absurdly */
    if ((uint64_t)bw * bh > 4 * ((uint64_t)w * h > 65536 ? (uint64_t)w * h : 65536))
        return br_err_set(err, BR_E_FORMAT, name, "TIFF block %ux%u is absurd for a %ux%u image", bw, bh, w, h);
    nblocks = across * down;
    {
        const tag *go = &g[tiled ? G_TOFF : G_SOFF], *gc = &g[tiled ? G_TBC : G_SBC];
        if (go->count < nblocks || gc->count < nblocks)
            return br_err_set(err, BR_E_FORMAT, name, "TIFF lists %u offsets and %u byte counts for %u blocks",
                              go->count, gc->count, nblocks);
    }
    /* check every block against the file before allocating: a header that
     * lies about the image size cannot make us allocate more than the data
     * could fill (deflate expands at most ~1032x, LZW at most 4096x) */
    for (b = 0; b < nblocks; b++) {
        uint32_t off = tag_uint(&t, &g[tiled ? G_TOFF : G_SOFF], b, &ok);
        uint32_t bc = tag_uint(&t, &g[tiled ? G_TBC : G_SBC], b, &ok);
        uint32_t by = (b / across) * bh, rows = bh;
        uint64_t need, can;
        if (!tiled && by + rows > h) rows = h - by;
        need = (uint64_t)bw * rows * bpsb;
        can = comp == 1 ? bc : comp == 5 ? (uint64_t)bc * 4096 + 64 : (uint64_t)bc * 1032 + 64;
        if (!ok) return br_err_set(err, BR_E_FORMAT, name, "TIFF block offsets of the wrong type");
        if (off > n || bc > n - off)
            return br_err_set(err, BR_E_TRUNCATED, name, "TIFF block %u at %u (+%u bytes) runs past the end (%zu)",
                              b, off, bc, n);
        if (can < need)
            return br_err_set(err, BR_E_TRUNCATED, name, "TIFF block %u has %u bytes, too few for %llu bytes of samples",
                              b, bc, (unsigned long long)need);
    }
    have_nodata = parse_nodata(&t, &g[G_NODATA], &nodata, &nodata_nan);
    if (o && o->has_nodata) {           /* the user's value, besides the tag's */
        if (o->nodata != o->nodata) nodata_nan = 1;
        else { user_nd = 1; user_v = sfmt == 3 ? (double)(float)o->nodata : o->nodata; }
    }
    if (g[G_GEOKEYS].present && g[G_GEOKEYS].type == T_SHORT && g[G_GEOKEYS].count >= 4) {
        uint32_t nk = tag_uint(&t, &g[G_GEOKEYS], 3, &ok), k;
        for (k = 0; k < nk && 4 + 4 * k + 3 < g[G_GEOKEYS].count; k++) {
            uint32_t key = tag_uint(&t, &g[G_GEOKEYS], 4 + 4 * k, &ok);
            uint32_t loc = tag_uint(&t, &g[G_GEOKEYS], 4 + 4 * k + 1, &ok);
            uint32_t val = tag_uint(&t, &g[G_GEOKEYS], 4 + 4 * k + 3, &ok);
            if (loc != 0) continue;
            if (key == 1024) model = (int)val;
            else if (key == 1025) raster = (int)val;
            else if (key == 3076) lin_units = (int)val;
        }
        ok = 1;
    }

    cnt = (size_t)w * h;
    blockbytes = (size_t)bw * bh * bpsb;
    raw = malloc(cnt * bpsb);
    blk = malloc(blockbytes);
    if (!raw || !blk) { s = br_err_set(err, BR_E_NOMEM, name, "out of memory"); goto fail; }
    for (b = 0; b < nblocks; b++) {
        uint32_t off = tag_uint(&t, &g[tiled ? G_TOFF : G_SOFF], b, &ok);
        uint32_t bc = tag_uint(&t, &g[tiled ? G_TBC : G_SBC], b, &ok);
        uint32_t bx = (b % across) * bw, by = (b / across) * bh, rows = bh, r, c;
        size_t need;
        if (!tiled && by + rows > h) rows = h - by;
        need = (size_t)bw * rows * bpsb;
        if (!ok) { s = br_err_set(err, BR_E_FORMAT, name, "TIFF block offsets of the wrong type"); goto fail; }
        if (off > n || bc > n - off) {
            s = br_err_set(err, BR_E_TRUNCATED, name, "TIFF block %u at %u (+%u bytes) runs past the end (%zu)", b, off, bc, n);
            goto fail;
        }
        if (comp == 1) {
            if (bc < need) {
                s = br_err_set(err, BR_E_TRUNCATED, name, "TIFF block %u has %u of %zu bytes", b, bc, need);
                goto fail;
            }
            memcpy(blk, p + off, need);
        } else if (comp == 5) {
            s = lzw_decode(&t, p + off, bc, blk, need);
        } else {
            s = dem_inflate_into(name, p + off, bc, blk, need, err);
        }
        if (s != BR_OK) goto fail;
        if (pred == 2) {   /* horizontal differencing, per row, in samples */
            for (r = 0; r < rows; r++) {
                uint8_t *q = blk + (size_t)r * bw * bpsb;
                for (c = 1; c < bw; c++) {
                    uint8_t *a = q + (size_t)(c - 1) * bpsb, *d = q + (size_t)c * bpsb;
                    if (bpsb == 1) d[0] = (uint8_t)(d[0] + a[0]);
                    else if (bpsb == 2) {
                        uint16_t v = (uint16_t)(rd16(&t, d) + rd16(&t, a));
                        if (t.be) { d[0] = (uint8_t)(v >> 8); d[1] = (uint8_t)v; }
                        else { d[0] = (uint8_t)v; d[1] = (uint8_t)(v >> 8); }
                    } else {
                        uint32_t v = rd32(&t, d) + rd32(&t, a);
                        int k;
                        for (k = 0; k < 4; k++)
                            d[k] = (uint8_t)(t.be ? v >> (24 - 8 * k) : v >> (8 * k));
                    }
                }
            }
        }
        for (r = 0; r < rows && by + r < h; r++) {
            uint32_t cw = bx + bw > w ? w - bx : bw;
            memcpy(raw + ((size_t)(by + r) * w + bx) * bpsb, blk + (size_t)r * bw * bpsb, (size_t)cw * bpsb);
        }
    }
    free(blk);
    blk = NULL;

    /* pass over the samples: check, find the range, then convert */
#define SAMPLE(i, v, isnan_out) do { const uint8_t *q_ = raw + (i) * bpsb; \
        if (sfmt == 3) { uint32_t u_ = rd32(&t, q_); float f_; memcpy(&f_, &u_, 4); v = (double)f_; } \
        else if (bpsb == 1) v = q_[0]; \
        else if (bpsb == 2) v = sfmt == 2 ? (double)(int16_t)rd16(&t, q_) : (double)rd16(&t, q_); \
        else v = sfmt == 2 ? (double)(int32_t)rd32(&t, q_) : (double)rd32(&t, q_); \
        isnan_out = !isfinite(v); } while (0)
    for (i = 0; i < cnt; i++) {
        double v;
        int bad;
        SAMPLE(i, v, bad);
        if (bad) {
            if (nodata_nan && v != v) continue;
            s = br_err_set(err, BR_E_VALUE, name, "TIFF sample at row %zu, column %zu is not finite",
                           (size_t)i / w, (size_t)i % w);
            goto fail;
        }
        if ((have_nodata && v == nodata) || (user_nd && v == user_v)) continue;
        if (fabs(v) > maxabs) maxabs = fabs(v);
    }
    if (sfmt != 3) {
        if (maxabs > (double)BR_Z_LIMIT) {
            s = br_err_set(err, BR_E_VALUE, name, "TIFF height %g m is out of range", maxabs);
            goto fail;
        }
    } else if ((den = dem_float_den(maxabs)) == 0) {
        s = br_err_set(err, BR_E_VALUE, name, "TIFF height %g m is out of range", maxabs);
        goto fail;
    }
    s = dem_alloc(&f, w, h, name, err);
    if (s != BR_OK) goto fail;
    f.z_den = den;
    for (i = 0; i < cnt; i++) {
        double v;
        int bad;
        SAMPLE(i, v, bad);
        f.z[i] = bad || (have_nodata && v == nodata) || (user_nd && v == user_v) ? HF_NODATA : sfmt == 3 ? dem_float_z(v, den) : (int32_t)v;
    }
#undef SAMPLE
    free(raw);
    raw = NULL;

    if (g[G_SCALE].present && g[G_TIE].present && g[G_SCALE].count >= 2 && g[G_TIE].count >= 6) {
        double sx = tag_double(&t, &g[G_SCALE], 0, &ok), sy = tag_double(&t, &g[G_SCALE], 1, &ok);
        double ti = tag_double(&t, &g[G_TIE], 0, &ok), tj = tag_double(&t, &g[G_TIE], 1, &ok);
        double tx = tag_double(&t, &g[G_TIE], 3, &ok), ty = tag_double(&t, &g[G_TIE], 4, &ok);
        double x0 = tx - ti * sx, y0 = ty + tj * sy, uf = 1;
        if (!ok || !isfinite(x0) || !isfinite(y0) || !(sx > 0) || !(sy > 0)) {
            s = br_err_set(err, BR_E_VALUE, name, "TIFF georeference (scale %g, %g) is bad", sx, sy);
            dem_free(&f);
            goto fail;
        }
        if (raster != 2) { x0 += sx / 2; y0 -= sy / 2; }   /* PixelIsArea: tie point is a pixel corner */
        if (model == 0)
            model = dem_looks_degrees(x0, y0 - sy * (h - 1), x0 + sx * (w - 1), y0, sx, sy) ? 2 : 1;
        if (lin_units == 9002) uf = 0.3048;
        else if (lin_units == 9003) uf = 1200.0 / 3937.0;
        if (model == 2) s = dem_geo_degrees(&f, x0, y0, sx, sy, name, err);
        else s = dem_geo_projected(&f, x0 * uf, y0 * uf, sx * uf, sy * uf, name, err);
        if (s != BR_OK) { dem_free(&f); goto fail; }
    }
    *out = f;
    return BR_OK;
fail:
    free(raw);
    free(blk);
    return s;
}
