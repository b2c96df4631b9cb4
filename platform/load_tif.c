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

/* the tags the reader looks at, by index into a tag array of TG_N */
enum { TG_W, TG_H, TG_BPS, TG_COMP, TG_SOFF, TG_SPP, TG_RPS, TG_SBC, TG_PLANAR, TG_PRED, TG_TW, TG_TH,
       TG_TOFF, TG_TBC, TG_SFMT, TG_SCALE, TG_TIE, TG_GEOKEYS, TG_NODATA, TG_N };
static const uint16_t tag_ids[TG_N] = { 256, 257, 258, 259, 273, 277, 278, 279, 284, 317, 322, 323, 324,
                                        325, 339, 33550, 33922, 34735, 42113 };

/* the image's sample format and its cut into blocks (strips or tiles) */
typedef struct tif_layout {
    uint32_t w, h, bps, comp, pred, sfmt;
    uint32_t bw, bh, across, down, nblocks;     /* block size and grid */
    size_t bpsb;                                /* bytes per sample: 1, 2 or 4 */
    int tiled;
} tif_layout;

/* which sample values are voids: the GDAL_NODATA tag's, the user's, NaN */
typedef struct tif_voids {
    int have_tag, nan, have_user;
    double tag_v, user_v;
} tif_voids;

/* step 1: header and first directory; fills g[] with the tags of tag_ids
 * (every value range checked against the file) */
static br_status tif_read_dir(tif *t, tag *g)
{
    const uint8_t *p = t->p;
    size_t n = t->n;
    uint32_t ifd, nent, i;
    if (n < 8) return br_err_set(t->err, BR_E_TRUNCATED, t->name, "TIFF header truncated");
    if (!memcmp(p, "II", 2)) t->be = 0;
    else if (!memcmp(p, "MM", 2)) t->be = 1;
    else return br_err_set(t->err, BR_E_FORMAT, t->name, "not a TIFF file (wrong magic)");
    if (rd16(t, p + 2) == 43) return br_err_set(t->err, BR_E_UNSUPPORTED, t->name, "BigTIFF is not supported");
    if (rd16(t, p + 2) != 42) return br_err_set(t->err, BR_E_FORMAT, t->name, "not a TIFF file (wrong magic)");
    ifd = rd32(t, p + 4);
    if (ifd < 8) return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF directory offset %u is bad", ifd);
    if (ifd > n - 2)
        return br_err_set(t->err, BR_E_TRUNCATED, t->name, "TIFF directory at %u is past the end (%zu bytes)", ifd, n);
    nent = rd16(t, p + ifd);
    if ((size_t)nent * 12 > n - ifd - 2)
        return br_err_set(t->err, BR_E_TRUNCATED, t->name, "TIFF directory of %u entries runs past the end", nent);
    for (i = 0; i < nent; i++) {
        const uint8_t *e = p + ifd + 2 + 12 * (size_t)i;
        uint16_t id = rd16(t, e), type = rd16(t, e + 2);
        uint32_t count = rd32(t, e + 4);
        size_t ts = type_size(type), total;
        int k;
        for (k = 0; k < TG_N && tag_ids[k] != id; k++) {}
        if (k == TG_N) continue;
        if (!ts || count == 0)
            return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF tag %u has type %u and %u values", id, type, count);
        if (g[k].present) return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF tag %u given twice", id);
        total = ts * count;
        if (total / ts != count) return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF tag %u too large", id);
        g[k].id = id; g[k].type = type; g[k].count = count; g[k].present = 1;
        if (total <= 4) g[k].off = (size_t)(e + 8 - p);
        else {
            uint32_t vo = rd32(t, e + 8);
            if (vo > n || total > n - vo)
                return br_err_set(t->err, BR_E_TRUNCATED, t->name, "TIFF tag %u values at %u run past the end", id, vo);
            g[k].off = vo;
        }
    }
    return BR_OK;
}

/* step 2: image size, sample format, compression and the block grid, each
 * refused with the reason when it is not one this reader decodes */
static br_status tif_layout_of(const tif *t, const tag *g, tif_layout *L)
{
    int ok = 1;
    uint32_t spp;
    if (!g[TG_W].present || !g[TG_H].present)
        return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF lacks ImageWidth or ImageLength");
    L->w = tag_uint(t, &g[TG_W], 0, &ok);
    L->h = tag_uint(t, &g[TG_H], 0, &ok);
    L->bps = g[TG_BPS].present ? tag_uint(t, &g[TG_BPS], 0, &ok) : 1;
    L->comp = g[TG_COMP].present ? tag_uint(t, &g[TG_COMP], 0, &ok) : 1;
    spp = g[TG_SPP].present ? tag_uint(t, &g[TG_SPP], 0, &ok) : 1;
    L->pred = g[TG_PRED].present ? tag_uint(t, &g[TG_PRED], 0, &ok) : 1;
    L->sfmt = g[TG_SFMT].present ? tag_uint(t, &g[TG_SFMT], 0, &ok) : 1;
    if (!ok) return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF basic tag of the wrong type");
    if (L->w < 1 || L->h < 1)
        return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF image of %ux%u pixels", L->w, L->h);
    if (hf_check_dims(L->w, L->h) != BR_OK) {   /* dem_alloc says why, and fails */
        hf f;
        return dem_alloc(&f, L->w, L->h, t->name, t->err);
    }
    if (spp != 1)
        return br_err_set(t->err, BR_E_UNSUPPORTED, t->name, "TIFF has %u samples per pixel (heights need 1)", spp);
    if (!((L->bps == 8 && L->sfmt == 1) || (L->bps == 16 && (L->sfmt == 1 || L->sfmt == 2)) ||
          (L->bps == 32 && (L->sfmt == 1 || L->sfmt == 2 || L->sfmt == 3))))
        return br_err_set(t->err, BR_E_UNSUPPORTED, t->name, "TIFF samples of %u bits, format %u are not read",
                          L->bps, L->sfmt);
    if (L->comp != 1 && L->comp != 5 && L->comp != 8 && L->comp != 32946)
        return br_err_set(t->err, BR_E_UNSUPPORTED, t->name,
                          "TIFF compression %u is not read (none, LZW, deflate)", L->comp);
    if (L->pred != 1 && !(L->pred == 2 && L->sfmt != 3))
        return br_err_set(t->err, BR_E_UNSUPPORTED, t->name, "TIFF predictor %u with sample format %u is not read",
                          L->pred, L->sfmt);
    L->bpsb = L->bps / 8;
    L->tiled = g[TG_TW].present || g[TG_TOFF].present;
    if (L->tiled) {
        if (!g[TG_TW].present || !g[TG_TH].present || !g[TG_TOFF].present || !g[TG_TBC].present)
            return br_err_set(t->err, BR_E_FORMAT, t->name,
                              "TIFF tiles lack TileWidth/TileLength/TileOffsets/TileByteCounts");
        L->bw = tag_uint(t, &g[TG_TW], 0, &ok);
        L->bh = tag_uint(t, &g[TG_TH], 0, &ok);
        if (!ok || L->bw < 1 || L->bh < 1 || L->bw > 65536 || L->bh > 65536)
            return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF tile size %ux%u is absurd", L->bw, L->bh);
        L->across = (L->w + L->bw - 1) / L->bw;
        L->down = (L->h + L->bh - 1) / L->bh;
    } else {
        if (!g[TG_SOFF].present || !g[TG_SBC].present)
            return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF lacks StripOffsets or StripByteCounts");
        L->bw = L->w;
        L->bh = g[TG_RPS].present ? tag_uint(t, &g[TG_RPS], 0, &ok) : L->h;
        if (!ok || L->bh < 1) return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF RowsPerStrip %u is bad", L->bh);
        if (L->bh > L->h) L->bh = L->h;
        L->across = 1;
        L->down = (L->h + L->bh - 1) / L->bh;
    }
    /* a block may exceed the image (tiles pad it) but not absurdly */
    if ((uint64_t)L->bw * L->bh > 4 * ((uint64_t)L->w * L->h > 65536 ? (uint64_t)L->w * L->h : 65536))
        return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF block %ux%u is absurd for a %ux%u image",
                          L->bw, L->bh, L->w, L->h);
    L->nblocks = L->across * L->down;
    return BR_OK;
}

/* step 3: every block against the file, before allocating: a header that lies
 * about the image size cannot make us allocate more than the data could fill
 * (deflate expands at most ~1032x, LZW at most 4096x) */
static br_status tif_check_blocks(const tif *t, const tag *g, const tif_layout *L)
{
    const tag *go = &g[L->tiled ? TG_TOFF : TG_SOFF], *gc = &g[L->tiled ? TG_TBC : TG_SBC];
    uint32_t b;
    int ok = 1;
    if (go->count < L->nblocks || gc->count < L->nblocks)
        return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF lists %u offsets and %u byte counts for %u blocks",
                          go->count, gc->count, L->nblocks);
    for (b = 0; b < L->nblocks; b++) {
        uint32_t off = tag_uint(t, go, b, &ok), bc = tag_uint(t, gc, b, &ok);
        uint32_t by = (b / L->across) * L->bh, rows = L->bh;
        uint64_t need, can;
        if (!L->tiled && by + rows > L->h) rows = L->h - by;
        need = (uint64_t)L->bw * rows * L->bpsb;
        can = L->comp == 1 ? bc : L->comp == 5 ? (uint64_t)bc * 4096 + 64 : (uint64_t)bc * 1032 + 64;
        if (!ok) return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF block offsets of the wrong type");
        if (off > t->n || bc > t->n - off)
            return br_err_set(t->err, BR_E_TRUNCATED, t->name,
                              "TIFF block %u at %u (+%u bytes) runs past the end (%zu)", b, off, bc, t->n);
        if (can < need)
            return br_err_set(t->err, BR_E_TRUNCATED, t->name,
                              "TIFF block %u has %u bytes, too few for %llu bytes of samples",
                              b, bc, (unsigned long long)need);
    }
    return BR_OK;
}

/* GeoKeyDirectory (34735): model type (1024), raster type (1025) and linear
 * units (3076) when given inline (location 0); the defaults stay otherwise */
static void tif_geokeys(const tif *t, const tag *gk, int *model, int *raster, int *lin_units)
{
    int ok = 1;
    uint32_t nk, k;
    if (!gk->present || gk->type != T_SHORT || gk->count < 4) return;
    nk = tag_uint(t, gk, 3, &ok);
    for (k = 0; k < nk && 4 + 4 * k + 3 < gk->count; k++) {
        uint32_t key = tag_uint(t, gk, 4 + 4 * k, &ok);
        uint32_t loc = tag_uint(t, gk, 4 + 4 * k + 1, &ok);
        uint32_t val = tag_uint(t, gk, 4 + 4 * k + 3, &ok);
        if (loc != 0) continue;
        if (key == 1024) *model = (int)val;
        else if (key == 1025) *raster = (int)val;
        else if (key == 3076) *lin_units = (int)val;
    }
}

/* predictor 2: undo horizontal differencing, per row, in samples (mod 2^bits) */
static void tif_unpredict(const tif *t, uint8_t *blk, uint32_t rows, uint32_t bw, size_t bpsb)
{
    uint32_t r, c;
    for (r = 0; r < rows; r++) {
        uint8_t *q = blk + (size_t)r * bw * bpsb;
        for (c = 1; c < bw; c++) {
            uint8_t *a = q + (size_t)(c - 1) * bpsb, *d = q + (size_t)c * bpsb;
            if (bpsb == 1) d[0] = (uint8_t)(d[0] + a[0]);
            else if (bpsb == 2) {
                uint16_t v = (uint16_t)(rd16(t, d) + rd16(t, a));
                if (t->be) { d[0] = (uint8_t)(v >> 8); d[1] = (uint8_t)v; }
                else { d[0] = (uint8_t)v; d[1] = (uint8_t)(v >> 8); }
            } else {
                uint32_t v = rd32(t, d) + rd32(t, a);
                int k;
                for (k = 0; k < 4; k++)
                    d[k] = (uint8_t)(t->be ? v >> (24 - 8 * k) : v >> (8 * k));
            }
        }
    }
}

/* step 4: decode every block into blk (bw * bh samples) and copy its part
 * inside the image into raw (w * h samples, file byte order) */
static br_status tif_read_blocks(const tif *t, const tag *g, const tif_layout *L, uint8_t *raw, uint8_t *blk)
{
    const tag *go = &g[L->tiled ? TG_TOFF : TG_SOFF], *gc = &g[L->tiled ? TG_TBC : TG_SBC];
    size_t bpsb = L->bpsb;
    uint32_t b;
    int ok = 1;
    for (b = 0; b < L->nblocks; b++) {
        uint32_t off = tag_uint(t, go, b, &ok), bc = tag_uint(t, gc, b, &ok);
        uint32_t bx = (b % L->across) * L->bw, by = (b / L->across) * L->bh, rows = L->bh, r;
        size_t need;
        br_status s;
        if (!L->tiled && by + rows > L->h) rows = L->h - by;
        need = (size_t)L->bw * rows * bpsb;
        if (!ok) return br_err_set(t->err, BR_E_FORMAT, t->name, "TIFF block offsets of the wrong type");
        if (off > t->n || bc > t->n - off)
            return br_err_set(t->err, BR_E_TRUNCATED, t->name,
                              "TIFF block %u at %u (+%u bytes) runs past the end (%zu)", b, off, bc, t->n);
        if (L->comp == 1) {
            if (bc < need)
                return br_err_set(t->err, BR_E_TRUNCATED, t->name, "TIFF block %u has %u of %zu bytes", b, bc, need);
            memcpy(blk, t->p + off, need);
            s = BR_OK;
        } else if (L->comp == 5) {
            s = lzw_decode(t, t->p + off, bc, blk, need);
        } else {
            s = dem_inflate_into(t->name, t->p + off, bc, blk, need, t->err);
        }
        if (s != BR_OK) return s;
        if (L->pred == 2) tif_unpredict(t, blk, rows, L->bw, bpsb);
        for (r = 0; r < rows && by + r < L->h; r++) {
            uint32_t cw = bx + L->bw > L->w ? L->w - bx : L->bw;
            memcpy(raw + ((size_t)(by + r) * L->w + bx) * bpsb, blk + (size_t)r * L->bw * bpsb, (size_t)cw * bpsb);
        }
    }
    return BR_OK;
}

/* sample i of raw as a double (exact: every format read fits a double) */
static double tif_sample(const tif *t, const tif_layout *L, const uint8_t *raw, size_t i)
{
    const uint8_t *q = raw + i * L->bpsb;
    if (L->sfmt == 3) { uint32_t u = rd32(t, q); float f; memcpy(&f, &u, 4); return (double)f; }
    if (L->bpsb == 1) return q[0];
    if (L->bpsb == 2) return L->sfmt == 2 ? (double)(int16_t)rd16(t, q) : (double)rd16(t, q);
    return L->sfmt == 2 ? (double)(int32_t)rd32(t, q) : (double)rd32(t, q);
}

static int tif_is_void(const tif_voids *vd, double v)
{
    return (vd->have_tag && v == vd->tag_v) || (vd->have_user && v == vd->user_v);
}

/* step 5: check every sample and find the range (a non-finite one is an error
 * unless NaN marks voids), pick the height unit, convert into f */
static br_status tif_convert(const tif *t, const tif_layout *L, const uint8_t *raw, const tif_voids *vd, hf *f)
{
    size_t i, cnt = (size_t)L->w * L->h;
    double maxabs = 0;
    int32_t den = 1;
    br_status s;
    for (i = 0; i < cnt; i++) {
        double v = tif_sample(t, L, raw, i);
        if (!isfinite(v)) {
            if (vd->nan && v != v) continue;
            return br_err_set(t->err, BR_E_VALUE, t->name, "TIFF sample at row %zu, column %zu is not finite",
                              (size_t)i / L->w, (size_t)i % L->w);
        }
        if (tif_is_void(vd, v)) continue;
        if (fabs(v) > maxabs) maxabs = fabs(v);
    }
    if (L->sfmt != 3) {
        if (maxabs > (double)BR_Z_LIMIT)
            return br_err_set(t->err, BR_E_VALUE, t->name, "TIFF height %g m is out of range", maxabs);
    } else if ((den = dem_float_den(maxabs)) == 0) {
        return br_err_set(t->err, BR_E_VALUE, t->name, "TIFF height %g m is out of range", maxabs);
    }
    s = dem_alloc(f, L->w, L->h, t->name, t->err);
    if (s != BR_OK) return s;
    f->z_den = den;
    for (i = 0; i < cnt; i++) {
        double v = tif_sample(t, L, raw, i);
        f->z[i] = !isfinite(v) || tif_is_void(vd, v) ? HF_NODATA
                  : L->sfmt == 3 ? dem_float_z(v, den) : (int32_t)v;
    }
    return BR_OK;
}

/* step 6: ModelPixelScale + the first ModelTiepoint, when both are there, as
 * the georeference of f (which is freed on error) */
static br_status tif_georef(const tif *t, const tag *g, const tif_layout *L, hf *f)
{
    int ok = 1, model = 0, raster = 1, lin_units = 9001;
    double sx, sy, ti, tj, tx, ty, x0, y0, uf = 1;
    br_status s;
    tif_geokeys(t, &g[TG_GEOKEYS], &model, &raster, &lin_units);
    if (!(g[TG_SCALE].present && g[TG_TIE].present && g[TG_SCALE].count >= 2 && g[TG_TIE].count >= 6))
        return BR_OK;
    sx = tag_double(t, &g[TG_SCALE], 0, &ok); sy = tag_double(t, &g[TG_SCALE], 1, &ok);
    ti = tag_double(t, &g[TG_TIE], 0, &ok); tj = tag_double(t, &g[TG_TIE], 1, &ok);
    tx = tag_double(t, &g[TG_TIE], 3, &ok); ty = tag_double(t, &g[TG_TIE], 4, &ok);
    x0 = tx - ti * sx; y0 = ty + tj * sy;
    if (!ok || !isfinite(x0) || !isfinite(y0) || !(sx > 0) || !(sy > 0)) {
        s = br_err_set(t->err, BR_E_VALUE, t->name, "TIFF georeference (scale %g, %g) is bad", sx, sy);
        dem_free(f);
        return s;
    }
    if (raster != 2) { x0 += sx / 2; y0 -= sy / 2; }   /* PixelIsArea: tie point is a pixel corner */
    if (model == 0)
        model = dem_looks_degrees(x0, y0 - sy * (L->h - 1), x0 + sx * (L->w - 1), y0, sx, sy) ? 2 : 1;
    if (lin_units == 9002) uf = 0.3048;
    else if (lin_units == 9003) uf = 1200.0 / 3937.0;
    if (model == 2) s = dem_geo_degrees(f, x0, y0, sx, sy, t->name, t->err);
    else s = dem_geo_projected(f, x0 * uf, y0 * uf, sx * uf, sy * uf, t->name, t->err);
    if (s != BR_OK) dem_free(f);
    return s;
}

/* the reader: the steps above, in order; raw and blk are its only allocations
 * besides the result, and are freed on every path */
br_status dem_read_tif(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                       hf *out, br_err *err)
{
    tag g[TG_N];
    tif t;
    tif_layout L;
    tif_voids vd;
    uint8_t *raw = NULL, *blk = NULL;
    hf f;
    br_status s;

    memset(&t, 0, sizeof t);
    memset(g, 0, sizeof g);
    memset(&vd, 0, sizeof vd);
    memset(&L, 0, sizeof L);
    t.name = name; t.p = p; t.n = n; t.err = err;
    if ((s = tif_read_dir(&t, g)) != BR_OK) return s;
    if ((s = tif_layout_of(&t, g, &L)) != BR_OK) return s;
    if ((s = tif_check_blocks(&t, g, &L)) != BR_OK) return s;
    vd.have_tag = parse_nodata(&t, &g[TG_NODATA], &vd.tag_v, &vd.nan);
    if (o && o->has_nodata) {           /* the user's value, besides the tag's */
        if (o->nodata != o->nodata) vd.nan = 1;
        else { vd.have_user = 1; vd.user_v = L.sfmt == 3 ? (double)(float)o->nodata : o->nodata; }
    }
    raw = malloc((size_t)L.w * L.h * L.bpsb);
    blk = malloc((size_t)L.bw * L.bh * L.bpsb);
    if (!raw || !blk) s = br_err_set(err, BR_E_NOMEM, name, "out of memory");
    else s = tif_read_blocks(&t, g, &L, raw, blk);
    free(blk);
    if (s == BR_OK) s = tif_convert(&t, &L, raw, &vd, &f);
    free(raw);
    if (s == BR_OK) s = tif_georef(&t, g, &L, &f);
    if (s == BR_OK) *out = f;
    return s;
}
