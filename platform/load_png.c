/* platform/load_png.c — PNG heights through libpng's low-level API.
 *
 * No gamma or colour conversion touches the samples (we never call the gamma
 * or rgb-to-grey transforms); only bit depths below 8 and palettes are
 * expanded, and 16-bit samples are read as stored (big-endian).
 * Encodings (dem_opts.png_encoding):
 *   grey        8/16-bit grey (+alpha): metres = raw * scale + offset, kept
 *               exactly in units of a rational g/D (scale 0.1 -> 1/10 m);
 *   terrain-RGB Mapbox: metres = -10000 + (R*65536 + G*256 + B) * 0.1, unit 1/10 m;
 *   Terrarium   metres = R*256 + G + B/256 - 32768, unit 1/256 m.
 * AUTO is grey for grey PNGs and for palette PNGs whose entries are all grey
 * levels (a palette index stands for its grey level), terrain-RGB for other
 * colour ones; a choice that is not plain grey is said (dem_note).  A sample
 * whose alpha (or tRNS entry) is 0 is a void, and so is one equal to
 * dem_opts.nodata (the raw grey sample; terrain-RGB/Terrarium: the metres). */
#include <png.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include "platform/load_internal.h"

typedef struct png_src {
    const uint8_t *p;
    size_t n, pos;
    char msg[200];
    uint8_t *img;            /* decoded image, freed by the caller */
    png_bytep *rows;
    int64_t za, zb;          /* grey: z = raw*za + zb */
    int32_t num, den;        /* unit of z */
    int pal_grey;            /* a palette whose entries are all grey levels */
    char why[64];            /* else the first colour entry, for messages */
} png_src;

static void palette_kind(png_structp png, png_infop info, png_src *s)
{
    png_colorp pal = NULL;
    int npal = 0, k;
    s->pal_grey = png_get_PLTE(png, info, &pal, &npal) != 0 && npal > 0;
    for (k = 0; s->pal_grey && k < npal; k++)
        if (pal[k].red != pal[k].green || pal[k].red != pal[k].blue) {
            s->pal_grey = 0;
            snprintf(s->why, sizeof s->why, "palette entry %d is (%d, %d, %d)", k, pal[k].red, pal[k].green,
                     pal[k].blue);
        }
}

static void read_fn(png_structp png, png_bytep dst, size_t len)
{
    png_src *s = png_get_io_ptr(png);
    if (len > s->n - s->pos) png_error(png, "file truncated");
    memcpy(dst, s->p + s->pos, len);
    s->pos += len;
}

static void error_fn(png_structp png, png_const_charp msg)
{
    png_src *s = png_get_error_ptr(png);
    snprintf(s->msg, sizeof s->msg, "%s", msg);
    png_longjmp(png, 1);
}

static void warn_fn(png_structp png, png_const_charp msg) { (void)png; (void)msg; }

static int64_t gcd64(int64_t a, int64_t b)
{
    if (a < 0) a = -a;
    if (b < 0) b = -b;
    while (b) { int64_t t = a % b; a = b; b = t; }
    return a;
}

/* grey unit: raw*scale + offset = (raw*A + B) * g / D metres with z = raw*A/g' + B/g' */
static br_status grey_unit(const dem_opts *o, int bits, int64_t *za, int64_t *zb,
                           int32_t *num, int32_t *den, const char *name, br_err *err)
{
    double sc = o->png_scale == 0 ? 1.0 : o->png_scale, of = o->png_offset;
    int64_t a, d1, b, d2, D, A, B, g, maxraw = (1LL << bits) - 1, gd;
    if (!dem_rational(sc, 1000000, &a, &d1) || a == 0)
        return br_err_set(err, BR_E_ARG, name, "PNG scale %g cannot be kept exactly (need a fraction with denominator <= 10^6)", sc);
    if (!dem_rational(of, 1000000, &b, &d2))
        return br_err_set(err, BR_E_ARG, name, "PNG offset %g cannot be kept exactly", of);
    D = d1 / gcd64(d1, d2) * d2;
    if (D > 1000000000LL) return br_err_set(err, BR_E_ARG, name, "PNG scale and offset need too fine a unit");
    A = a * (D / d1);
    B = b * (D / d2);
    g = gcd64(A, B);
    A /= g;
    B /= g;
    if ((A < 0 ? -A : A) * maxraw + (B < 0 ? -B : B) > BR_Z_LIMIT)
        return br_err_set(err, BR_E_ARG, name, "PNG scale %g and offset %g give heights beyond the integer range", sc, of);
    gd = gcd64(g, D);
    if (g / gd > INT32_MAX || D / gd > INT32_MAX)
        return br_err_set(err, BR_E_ARG, name, "PNG scale and offset need too fine a unit");
    *za = A;
    *zb = B;
    *num = (int32_t)(g / gd);
    *den = (int32_t)(D / gd);
    return BR_OK;
}

/* Sum of the IDAT chunk lengths (walking the chunk list in memory). */
static uint64_t idat_bytes(const uint8_t *p, size_t n)
{
    size_t pos = 8;
    uint64_t sum = 0;
    while (n - pos >= 12) {
        uint32_t len = dem_be32(p + pos);
        if (!memcmp(p + pos + 4, "IDAT", 4)) sum += len;
        if (!memcmp(p + pos + 4, "IEND", 4) || len > n - pos - 12) break;
        pos += 12 + (size_t)len;
    }
    return sum;
}

static br_status decode(const char *name, png_src *s, const dem_opts *o, hf *out, br_err *err)
{
    png_structp png;
    png_infop info;
    png_uint_32 w, h, y;
    int user_nd = o->has_nodata && o->nodata == o->nodata;
    int bits, ctype, enc, ch, x;
    size_t rowbytes;
    br_status st;

    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, s, error_fn, warn_fn);
    if (!png) return br_err_set(err, BR_E_NOMEM, name, "cannot start libpng");
    info = png_create_info_struct(png);
    if (!info) { png_destroy_read_struct(&png, NULL, NULL); return br_err_set(err, BR_E_NOMEM, name, "cannot start libpng"); }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        if (out->z) dem_free(out);
        return br_err_set(err, strstr(s->msg, "truncated") || strstr(s->msg, "Not enough") ? BR_E_TRUNCATED : BR_E_FORMAT,
                          name, "bad PNG: %s", s->msg);
    }
    png_set_read_fn(png, s, read_fn);
    png_set_user_limits(png, 0x7fffffffU, 0x7fffffffU); /* our own limit is checked below */
    png_set_crc_action(png, PNG_CRC_ERROR_QUIT, PNG_CRC_ERROR_QUIT);
    png_read_info(png, info);
    w = png_get_image_width(png, info);
    h = png_get_image_height(png, info);
    bits = png_get_bit_depth(png, info);
    ctype = png_get_color_type(png, info);
    {
        /* a header that lies about the size is caught before allocating: deflate
         * expands at most ~1032 times, so the IDAT chunks bound the pixel data */
        uint64_t raw = (uint64_t)h * (1 + ((uint64_t)w * png_get_channels(png, info) * (uint64_t)bits + 7) / 8);
        if (hf_check_dims(w, h) == BR_OK && raw > idat_bytes(s->p, s->n) * 1032 + 1024) {
            png_destroy_read_struct(&png, &info, NULL);
            return br_err_set(err, BR_E_TRUNCATED, name, "PNG image data is far too short for %ux%u pixels",
                              (unsigned)w, (unsigned)h);
        }
    }
    if (ctype == PNG_COLOR_TYPE_PALETTE) palette_kind(png, info, s);
    enc = o->png_encoding;
    if (enc == DEM_PNG_AUTO) {
        if (ctype == PNG_COLOR_TYPE_GRAY || ctype == PNG_COLOR_TYPE_GRAY_ALPHA) enc = DEM_PNG_GREY;
        else if (s->pal_grey) {
            enc = DEM_PNG_GREY;
            dem_note(name, "heights read as grey: a palette PNG whose entries are all grey levels "
                           "(--png-encoding to choose another encoding)");
        } else {
            enc = DEM_PNG_TERRAIN_RGB;
            dem_note(name, "heights read as terrain-RGB (Mapbox): the default for colour PNGs "
                           "(--png-encoding terrarium or grey to choose another)");
        }
    }
    if (enc == DEM_PNG_GREY) {
        if (ctype != PNG_COLOR_TYPE_GRAY && ctype != PNG_COLOR_TYPE_GRAY_ALPHA && !s->pal_grey) {
            png_destroy_read_struct(&png, &info, NULL);
            return br_err_set(err, BR_E_UNSUPPORTED, name, "grey heights asked for, but the PNG is in colour%s%s",
                              s->why[0] ? ": " : "", s->why);
        }
        if (s->pal_grey) png_set_palette_to_rgb(png);   /* grey level in R (= G = B), tRNS as alpha */
        else if (bits < 8) png_set_expand_gray_1_2_4_to_8(png);
        st = grey_unit(o, bits < 8 || s->pal_grey ? 8 : bits, &s->za, &s->zb, &s->num, &s->den, name, err);
        if (st != BR_OK) { png_destroy_read_struct(&png, &info, NULL); return st; }
    } else if (enc == DEM_PNG_TERRAIN_RGB || enc == DEM_PNG_TERRARIUM) {
        if (ctype == PNG_COLOR_TYPE_GRAY || ctype == PNG_COLOR_TYPE_GRAY_ALPHA || bits != 8) {
            png_destroy_read_struct(&png, &info, NULL);
            return br_err_set(err, BR_E_UNSUPPORTED, name, "%s needs an 8-bit colour PNG (this one: type %d, %d bits)",
                              enc == DEM_PNG_TERRARIUM ? "Terrarium" : "terrain-RGB", ctype, bits);
        }
        if (ctype == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
        s->num = 1;
        s->den = enc == DEM_PNG_TERRARIUM ? 256 : 10;
    } else {
        png_destroy_read_struct(&png, &info, NULL);
        return br_err_set(err, BR_E_ARG, name, "unknown PNG encoding %d", o->png_encoding);
    }
    (void)png_set_interlace_handling(png);
    png_read_update_info(png, info);
    ch = png_get_channels(png, info);
    rowbytes = png_get_rowbytes(png, info);
    bits = png_get_bit_depth(png, info);
    if (rowbytes != (size_t)w * (size_t)ch * (size_t)(bits / 8) || (bits != 8 && bits != 16)) {
        png_destroy_read_struct(&png, &info, NULL);
        return br_err_set(err, BR_E_UNSUPPORTED, name, "unexpected PNG layout (%d channels, %d bits)", ch, bits);
    }
    st = dem_alloc(out, w, h, name, err);
    if (st != BR_OK) { png_destroy_read_struct(&png, &info, NULL); return st; }
    s->img = malloc(rowbytes * h);
    s->rows = malloc(sizeof *s->rows * h);
    if (!s->img || !s->rows) {
        png_destroy_read_struct(&png, &info, NULL);
        dem_free(out);
        return br_err_set(err, BR_E_NOMEM, name, "out of memory for %ux%u pixels", (unsigned)w, (unsigned)h);
    }
    for (y = 0; y < h; y++) s->rows[y] = s->img + (size_t)y * rowbytes;
    png_read_image(png, s->rows);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    out->z_num = s->num;
    out->z_den = s->den;
    for (y = 0; y < h; y++) {
        const uint8_t *r = s->rows[y];
        int32_t *z = out->z + (size_t)y * w;
        for (x = 0; x < (int)w; x++) {
            if (enc == DEM_PNG_GREY) {
                int64_t raw, alpha = 1;
                if (bits == 16) {
                    raw = r[x * ch * 2] << 8 | r[x * ch * 2 + 1];
                    if (ch == 2) alpha = r[x * 4 + 2] << 8 | r[x * 4 + 3];
                } else {
                    raw = r[x * ch];
                    if (ch == 2 || ch == 4) alpha = r[x * ch + ch - 1];
                }
                z[x] = alpha && !(user_nd && (double)raw == o->nodata) ? (int32_t)(raw * s->za + s->zb) : HF_NODATA;
            } else {
                const uint8_t *px = r + x * ch;
                int32_t v = px[0] << 16 | px[1] << 8 | px[2];
                if (ch == 4 && px[3] == 0) z[x] = HF_NODATA;
                else z[x] = enc == DEM_PNG_TERRARIUM ? v - 8388608 : v - 100000;
                if (user_nd && z[x] != HF_NODATA) {
                    /* the metres as a double before the compare: with x87's wider
                     * registers (i686) the unrounded quotient never equals a stored one */
                    volatile double m = (double)z[x] / s->den;
                    if (m == o->nodata) z[x] = HF_NODATA;
                }
            }
        }
    }
    return BR_OK;
}

br_status dem_read_png(const char *name, const uint8_t *p, size_t n, const dem_opts *o,
                       hf *out, br_err *err)
{
    png_src s;
    hf f;
    br_status st;
    memset(&s, 0, sizeof s);
    memset(&f, 0, sizeof f);
    s.p = p;
    s.n = n;
    if (n < 8 || png_sig_cmp(p, 0, 8))
        return br_err_set(err, BR_E_FORMAT, name, "not a PNG file (wrong magic)");
    st = decode(name, &s, o, &f, err);
    free(s.img);
    free(s.rows);
    if (st == BR_OK) *out = f;
    return st;
}
