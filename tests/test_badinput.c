/* tests/test_badinput.c — broken copies of the real files, made in memory:
 * every reader must refuse them with the expected status and a message that
 * names the file, never crash or read out of bounds (the suite runs this
 * under ASan+UBSan too). */
#include <math.h>
#include <unistd.h>
#include "tests/test.h"
#include "tests/zipmk.h"
#include "platform/load.h"

static unsigned char *hgt, *png, *asc, *bt, *tif, *xyz, *tifz, *fuji;
static size_t hgt_n, png_n, asc_n, bt_n, tif_n, xyz_n, tifz_n, fuji_n;

/* loads (name, p, n) and expects status want; the message must name the file */
static void bad_(const char *name, const void *p, size_t n, const dem_opts *o, br_status want, int line)
{
    hf f;
    br_err e;
    br_status s;
    memset(&e, 0, sizeof e);
    s = dem_load_mem(name, p, n, o, &f, &e);
    if (s == BR_OK) dem_free(&f);
    CHECK_MSG(s == want, "line %d: %s: got %s (%d), want %s: %s", line, name, br_status_name(s), s,
              br_status_name(want), e.msg);
    if (s != BR_OK) CHECK_MSG(strstr(e.msg, name) != NULL, "line %d: message '%s' lacks the file name", line, e.msg);
}
#define BAD(name, p, n, o, want) bad_(name, p, n, o, want, __LINE__)

static unsigned char *dup_(const unsigned char *p, size_t n, size_t cap)
{
    unsigned char *q = calloc(cap > n ? cap : n, 1);
    if (q) memcpy(q, p, n);
    return q;
}

static void put_le32(unsigned char *q, uint32_t v) { q[0] = (unsigned char)v; q[1] = (unsigned char)(v >> 8); q[2] = (unsigned char)(v >> 16); q[3] = (unsigned char)(v >> 24); }
static void put_be32(unsigned char *q, uint32_t v) { q[3] = (unsigned char)v; q[2] = (unsigned char)(v >> 8); q[1] = (unsigned char)(v >> 16); q[0] = (unsigned char)(v >> 24); }

static void test_hgt(void)
{
    unsigned char *q;
    BAD("N47E009.hgt", hgt, hgt_n - 2402, NULL, BR_E_TRUNCATED);  /* two rows missing */
    BAD("N47E009.hgt", hgt, hgt_n - 1, NULL, BR_E_TRUNCATED);     /* odd length */
    BAD("N47E009.hgt", hgt, 1000, NULL, BR_E_FORMAT);             /* not 2n^2 */
    BAD("N47E009.hgt", hgt, 6, NULL, BR_E_FORMAT);
    BAD("N47E009.hgt", hgt, 0, NULL, BR_E_FORMAT);
    q = dup_(hgt, hgt_n, hgt_n + 4000);
    BAD("N47E009.hgt", q, hgt_n + 4000, NULL, BR_E_FORMAT);        /* oversized */
    free(q);
    /* a square of any size is a valid tile: 2x2 */
    {
        static const unsigned char four[8] = { 0, 1, 0x80, 0, 0, 3, 0xff, 0xff };
        hf f;
        br_err e;
        CHECK_EQ(dem_load_mem("tiny.hgt", four, 8, NULL, &f, &e), BR_OK);
        CHECK_EQ(f.z[0], 1);
        CHECK_EQ(f.z[1], HF_NODATA);
        CHECK_EQ(f.z[3], -1);
        dem_free(&f);
    }
}

static void test_gz_zip(void)
{
    size_t zn = 0;
    unsigned char *z = t_gzip(hgt, hgt_n, &zn), *q;
    CHECK(z != NULL);
    if (!z) return;
    BAD("N47E009.hgt.gz", z, zn / 2, NULL, BR_E_TRUNCATED);
    q = dup_(z, zn, zn);
    memset(q + zn / 2, 0x55, 64);                               /* corrupt the deflate stream */
    BAD("N47E009.hgt.gz", q, zn, NULL, BR_E_FORMAT);
    memcpy(q, z, zn);
    q[zn - 6] ^= 0xff;                                          /* wrong CRC in the trailer */
    BAD("N47E009.hgt.gz", q, zn, NULL, BR_E_FORMAT);
    free(q);
    free(z);
    BAD("N47E009.hgt.gz", hgt, 4096, NULL, BR_E_FORMAT);        /* named .gz, not gzip */
    z = t_gzip((const unsigned char *)"hello", 5, &zn);
    BAD("N47E009.hgt.gz", z, zn, NULL, BR_E_FORMAT);            /* gz of something that is not heights */
    free(z);
    /* a gzip inside a gzip is not unpacked twice */
    {
        size_t z2n = 0;
        unsigned char *z1 = t_gzip(hgt, hgt_n, &zn), *z2 = t_gzip(z1, zn, &z2n);
        BAD("N47E009.hgt.gz.gz", z2, z2n, NULL, BR_E_UNSUPPORTED);
        free(z1);
        free(z2);
    }

    /* zip members that are not heights */
    z = t_zip("license.pdf", hgt, 4096, 1, &zn);
    BAD("N47E009.zip", z, zn, NULL, BR_E_FORMAT);
    free(z);
    z = t_zip("N47E009.hgt", (const unsigned char *)"not heights, at all", 19, 1, &zn);
    BAD("N47E009.zip", z, zn, NULL, BR_E_FORMAT);
    free(z);
    /* damaged archives */
    z = t_zip("N47E009.hgt", hgt, hgt_n, 1, &zn);
    BAD("N47E009.hgt.zip", z, zn - 30, NULL, BR_E_TRUNCATED);   /* end record cut */
    BAD("N47E009.hgt.zip", z, 10, NULL, BR_E_TRUNCATED);
    q = dup_(z, zn, zn);
    put_le32(q + 14, 0x12345678);                               /* local CRC (ignored) ... */
    put_le32(q + zn - 22 - 46 - 11 + 16, 0x12345678);           /* ... central CRC is checked */
    BAD("N47E009.hgt.zip", q, zn, NULL, BR_E_FORMAT);
    memcpy(q, z, zn);
    put_le32(q + zn - 22 + 16, (uint32_t)zn);                   /* central directory past the end */
    BAD("N47E009.hgt.zip", q, zn, NULL, BR_E_FORMAT);
    memcpy(q, z, zn);
    put_le32(q + zn - 22 - 46 - 11 + 42, (uint32_t)zn - 10);    /* local header offset lies */
    BAD("N47E009.hgt.zip", q, zn, NULL, BR_E_FORMAT);
    memcpy(q, z, zn);
    put_le32(q + zn - 22 - 46 - 11 + 20, (uint32_t)zn * 2);     /* compressed size lies */
    BAD("N47E009.hgt.zip", q, zn, NULL, BR_E_TRUNCATED);
    memcpy(q, z, zn);
    put_le32(q + zn - 22 - 46 - 11 + 24, (uint32_t)hgt_n + 2);  /* uncompressed size lies */
    BAD("N47E009.hgt.zip", q, zn, NULL, BR_E_FORMAT);
    memcpy(q, z, zn);
    q[zn - 22 - 46 - 11 + 10] = 12;                             /* bzip2 member */
    BAD("N47E009.hgt.zip", q, zn, NULL, BR_E_UNSUPPORTED);
    memcpy(q, z, zn);
    memset(q + 30 + 11 + 1000, 0xAA, 200);                      /* corrupt deflate data */
    {
        hf f;
        br_err e;
        br_status s = dem_load_mem("N47E009.hgt.zip", q, zn, NULL, &f, &e);
        CHECK_MSG(s == BR_E_FORMAT || s == BR_E_TRUNCATED, "%d %s", s, e.msg);
        if (s == BR_OK) dem_free(&f);
    }
    free(q);
    free(z);
}

static void test_png(void)
{
    unsigned char *q = dup_(png, png_n, png_n);
    dem_opts o;
    memset(&o, 0, sizeof o);
    BAD("ps_height_1k.png", png, png_n / 2, NULL, BR_E_TRUNCATED);
    BAD("ps_height_1k.png", png, 40, NULL, BR_E_TRUNCATED);
    q[1] = 'X';
    BAD("ps_height_1k.png", q, png_n, NULL, BR_E_FORMAT);       /* named .png, wrong magic */
    memcpy(q, png, png_n);
    q[png_n / 2] ^= 0x5a;                                       /* IDAT damaged: CRC error */
    BAD("ps_height_1k.png", q, png_n, NULL, BR_E_FORMAT);
    /* IHDR lies: width 100000 (CRC recomputed) is refused before allocating */
    memcpy(q, png, png_n);
    put_be32(q + 16, 100000);
    put_be32(q + 29, (uint32_t)crc32(0L, q + 12, 17));
    BAD("ps_height_1k.png", q, png_n, NULL, BR_E_TOO_BIG);
    /* IHDR lies: more rows than the data holds */
    memcpy(q, png, png_n);
    put_be32(q + 20, 1100);
    put_be32(q + 29, (uint32_t)crc32(0L, q + 12, 17));
    {
        hf f;
        br_err e;
        br_status s = dem_load_mem("ps_height_1k.png", q, png_n, NULL, &f, &e);
        CHECK_MSG(s == BR_E_FORMAT || s == BR_E_TRUNCATED, "%d %s", s, e.msg);
        if (s == BR_OK) dem_free(&f);
    }
    free(q);
    /* flags that do not fit the file */
    o.png_encoding = DEM_PNG_TERRAIN_RGB;
    BAD("ps_height_1k.png", png, png_n, &o, BR_E_UNSUPPORTED);  /* grey 16-bit as terrain-RGB */
    o.png_encoding = DEM_PNG_GREY;
    BAD("fuji.png", fuji, fuji_n, &o, BR_E_UNSUPPORTED);
    o.png_encoding = 0;
    o.png_scale = (double)NAN;
    BAD("ps_height_1k.png", png, png_n, &o, BR_E_ARG);
    o.png_scale = 1e-6;                                         /* unit 1e-6 m: 5000 m + 65535 um overflow */
    o.png_offset = 5000;
    BAD("ps_height_1k.png", png, png_n, &o, BR_E_ARG);
}

static void test_asc(void)
{
    static const char lie_big[] = "ncols 100000\nnrows 100000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n";
    static const char lie_count[] = "ncols 16000\nnrows 16000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n";
    static const char neg[] = "ncols -5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n";
    static const char frac[] = "ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n";
    static const char nocell[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\n1 2\n";
    static const char unknown[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\nfoo 3\n1 2\n";
    static const char twice[] = "ncols 2\nnrows 1\nncols 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n";
    static const char zerocell[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 0\n1 2\n";
    static const char nanv[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 nan\n";
    static const char infv[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\ninf 2\n";
    static const char text[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 abc\n";
    static const char hex[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 0x10\n";
    static const char extra[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n";
    static const char missing[] = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n";
    static const char huge[] = "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 1e300\n";
    static const char nohead[] = "ncols 2\nnrows 1\n";
    static const char ok[] = "NCOLS 2\nNROWS 1\nXLLCENTER 0\nYLLCENTER 0\nCELLSIZE 1\nNODATA_VALUE -1\n-1 2.5\n";
    /* GeoClaw (value-first header) with a vertical tab after a token: the token loops
     * stopped at it and the blank skip did not pass it, a hang (fuzz_asc, fuzz_file) */
    static const char vtab[] = "5 ncols\n3\vz nrows\n0 xll\n0 yll\n1 cellsize\n1 2 3 4 5\n";
    unsigned char *q;
    size_t i;
    BAD("hugo_site.asc", asc, asc_n / 2, NULL, BR_E_TRUNCATED);
    BAD("x.asc", lie_big, sizeof lie_big - 1, NULL, BR_E_TOO_BIG);
    BAD("x.asc", lie_count, sizeof lie_count - 1, NULL, BR_E_TRUNCATED);
    BAD("x.asc", neg, sizeof neg - 1, NULL, BR_E_FORMAT);
    BAD("x.asc", frac, sizeof frac - 1, NULL, BR_E_FORMAT);
    BAD("x.asc", nocell, sizeof nocell - 1, NULL, BR_E_FORMAT);
    BAD("x.asc", unknown, sizeof unknown - 1, NULL, BR_E_VALUE);     /* after ncols/nrows: a bad value */
    BAD("x.asc", twice, sizeof twice - 1, NULL, BR_E_FORMAT);
    BAD("x.asc", zerocell, sizeof zerocell - 1, NULL, BR_E_VALUE);
    BAD("x.asc", nanv, sizeof nanv - 1, NULL, BR_E_VALUE);
    BAD("x.asc", infv, sizeof infv - 1, NULL, BR_E_VALUE);
    BAD("x.asc", text, sizeof text - 1, NULL, BR_E_VALUE);
    BAD("x.asc", hex, sizeof hex - 1, NULL, BR_E_VALUE);
    BAD("x.asc", extra, sizeof extra - 1, NULL, BR_E_FORMAT);
    BAD("x.asc", missing, sizeof missing - 1, NULL, BR_E_TRUNCATED);
    BAD("x.asc", huge, sizeof huge - 1, NULL, BR_E_VALUE);
    BAD("x.asc", nohead, sizeof nohead - 1, NULL, BR_E_TRUNCATED);
    BAD("x.asc", "", 0, NULL, BR_E_TRUNCATED);
    alarm(20);                  /* a hang is a failure (SIGALRM ends the program) */
    BAD("x.asc", vtab, sizeof vtab - 1, NULL, BR_E_VALUE);
    alarm(0);
    {
        hf f;
        br_err e;
        CHECK_EQ(dem_load_mem("ok.asc", (const uint8_t *)ok, sizeof ok - 1, NULL, &f, &e), BR_OK);
        CHECK_EQ(f.z_den, 1000000);
        CHECK_EQ(f.z[0], HF_NODATA);
        CHECK_EQ(f.z[1], 2500000);
        dem_free(&f);
    }
    /* a non-numeric value in the real file (a '-9999' turned into '-99x9') */
    q = dup_(asc, asc_n, asc_n);
    for (i = 0; i + 5 < asc_n; i++)
        if (!memcmp(q + i, "-9999", 5) && i > 200) { q[i + 3] = 'x'; break; }
    BAD("hugo_site.asc", q, asc_n, NULL, BR_E_VALUE);
    free(q);
}

static void test_bt(void)
{
    unsigned char *q = dup_(bt, bt_n, bt_n + 8);
    const size_t H = 256;
    BAD("crater_0513.bt", bt, bt_n - 4, NULL, BR_E_TRUNCATED);
    BAD("crater_0513.bt", bt, 100, NULL, BR_E_TRUNCATED);
    BAD("crater_0513.bt", q, bt_n + 8, NULL, BR_E_FORMAT);        /* oversized */
    q[0] = 'B';
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_FORMAT);            /* wrong magic */
    memcpy(q, bt, bt_n);
    q[9] = '9';
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_UNSUPPORTED);
    memcpy(q, bt, bt_n);
    put_le32(q + 10, 100000);
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_TOO_BIG);
    memcpy(q, bt, bt_n);
    put_le32(q + 14, 0xffffffffu);                                /* rows = -1 */
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_FORMAT);
    memcpy(q, bt, bt_n);
    put_le32(q + 14, 514);                                        /* header lies: one row more */
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_TRUNCATED);
    memcpy(q, bt, bt_n);
    q[18] = 3;                                                    /* 3-byte samples */
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_FORMAT);
    memcpy(q, bt, bt_n);
    put_le32(q + H + 4 * 1000, 0x7fc00000u);                      /* NaN sample */
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_VALUE);
    memcpy(q, bt, bt_n);
    put_le32(q + H + 4 * 513 * 513 - 4, 0xff800000u);             /* -inf in the last sample */
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_VALUE);
    memcpy(q, bt, bt_n);
    put_le32(q + H + 4 * 7, 0x7f7fffffu);                         /* FLT_MAX: out of range */
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_VALUE);
    memcpy(q, bt, bt_n);
    put_le32(q + 28, 0); put_le32(q + 32, 0x7ff80000u);          /* left extent NaN */
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_VALUE);
    memcpy(q, bt, bt_n);
    q[22] = 9;                                                    /* unknown horizontal units */
    BAD("crater_0513.bt", q, bt_n, NULL, BR_E_UNSUPPORTED);
    /* a void (-32768.0f) is not an error */
    memcpy(q, bt, bt_n);
    put_le32(q + H, 0xc7000000u);
    {
        hf f;
        br_err e;
        CHECK_EQ(dem_load_mem("crater_0513.bt", q, bt_n, NULL, &f, &e), BR_OK);
        CHECK_EQ(f.z[(size_t)512 * 513], HF_NODATA);              /* file sample 0 = SW corner */
        dem_free(&f);
    }
    free(q);
}

/* The samples go in as their IEEE 754 bit patterns, little-endian (put_le32), whatever
 * the host's byte order: a float is those 32 bits on every target we build (C99 static
 * assertion: the array's size is -1 otherwise), in the byte order of its uint32. */
typedef char float_is_32_bits[sizeof(float) == sizeof(uint32_t) ? 1 : -1];

/* a minimal little-endian TIFF: one uncompressed float32 strip, optional nodata */
static unsigned char *mk_tif_float(const float *v, int w, int h, const char *nodata, size_t *outn)
{
    size_t data = (size_t)w * h * 4, ntags = nodata ? 11 : 10, ifd = 8 + data, n = ifd + 2 + 12 * ntags + 4 + 16;
    unsigned char *p = calloc(n, 1), *e;
    size_t k = 0;
    const uint16_t tags[11] = { 256, 257, 258, 259, 262, 273, 277, 278, 279, 339, 42113 };
    uint32_t vals[11];
    if (!p) return NULL;
    vals[0] = (uint32_t)w; vals[1] = (uint32_t)h; vals[2] = 32; vals[3] = 1; vals[4] = 1; vals[5] = 8;
    vals[6] = 1; vals[7] = (uint32_t)h; vals[8] = (uint32_t)data; vals[9] = 3;
    memcpy(p, "II*\0", 4);
    put_le32(p + 4, (uint32_t)ifd);
    for (k = 0; k < (size_t)w * h; k++) {
        uint32_t b;
        memcpy(&b, &v[k], 4);
        put_le32(p + 8 + 4 * k, b);
    }
    p[ifd] = (unsigned char)ntags;
    for (k = 0; k < ntags; k++) {
        e = p + ifd + 2 + 12 * k;
        e[0] = (unsigned char)tags[k]; e[1] = (unsigned char)(tags[k] >> 8);
        if (tags[k] == 42113) {
            size_t l = strlen(nodata) + 1;
            e[2] = 2; put_le32(e + 4, (uint32_t)l);
            if (l <= 4) memcpy(e + 8, nodata, l);             /* fits: stored in the entry */
            else {
                put_le32(e + 8, (uint32_t)(n - 16));
                memcpy(p + n - 16, nodata, l < 16 ? l : 15);
            }
        } else {
            e[2] = (tags[k] == 273 || tags[k] == 279) ? 4 : 3;
            put_le32(e + 4, 1);
            put_le32(e + 8, vals[k]);
        }
    }
    *outn = n;
    return p;
}

static void test_tif(void)
{
    unsigned char *q = dup_(tif, tif_n, tif_n);
    size_t ifd = (size_t)q[4] | (size_t)q[5] << 8 | (size_t)q[6] << 16 | (size_t)q[7] << 24;
    size_t i, n;
    BAD("mt_rainier_90m.tif", tif, tif_n / 2, NULL, BR_E_TRUNCATED);
    BAD("mt_rainier_90m.tif", tif, 6, NULL, BR_E_TRUNCATED);
    q[2] = 'X';
    BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_FORMAT);
    memcpy(q, tif, tif_n);
    q[2] = 43;
    BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_UNSUPPORTED);  /* BigTIFF */
    memcpy(q, tif, tif_n);
    put_le32(q + 4, (uint32_t)tif_n + 100);
    BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_TRUNCATED);    /* IFD past the end */
    put_le32(q + 4, 3);
    BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_FORMAT);       /* IFD inside the header */
    memcpy(q, tif, tif_n);
    q[ifd] = 0xff; q[ifd + 1] = 0x0f;                             /* 4095 entries */
    BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_TRUNCATED);
    /* patch single tag values in the directory */
    for (i = 0; i < 17; i++) {
        unsigned char *e = q + ifd + 2 + 12 * i;
        unsigned tag;
        memcpy(q, tif, tif_n);
        e = q + ifd + 2 + 12 * i;
        tag = (unsigned)(e[0] | e[1] << 8);
        if (tag == 256) { e[8] = 0x60; e[9] = 0xea; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_TOO_BIG); }   /* 60000 wide */
        if (tag == 257) { e[8] = 0; e[9] = 0; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_FORMAT); }         /* 0 rows */
        if (tag == 258) { e[8] = 12; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_UNSUPPORTED); }             /* 12 bits */
        if (tag == 259) { e[8] = 7; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_UNSUPPORTED); }              /* JPEG */
        if (tag == 277) { e[8] = 3; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_UNSUPPORTED); }              /* RGB */
        if (tag == 322) { e[8] = 0; e[9] = 0; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_FORMAT); }         /* tile width 0 */
        if (tag == 323) { e[8] = 0xff; e[9] = 0xff; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_FORMAT); }   /* 65535 high tiles */
        if (tag == 324) { e[4] = 20; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_FORMAT); }                  /* 20 offsets for 25 tiles */
        if (tag == 324) {                                         /* first tile offset past the end */
            size_t vo;
            memcpy(q, tif, tif_n);
            vo = (size_t)e[8] | (size_t)e[9] << 8 | (size_t)e[10] << 16 | (size_t)e[11] << 24;
            put_le32(q + vo, (uint32_t)tif_n - 1000);
            BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_TRUNCATED);
        }
        if (tag == 325) { put_le32(e + 8, (uint32_t)tif_n); BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_TRUNCATED); } /* counts array past the end */
        if (tag == 339) { e[8] = 3; BAD("mt_rainier_90m.tif", q, tif_n, NULL, BR_E_UNSUPPORTED); }              /* 16-bit float */
    }
    free(q);
    /* damaged LZW and deflate data */
    q = dup_(tifz, tifz_n, tifz_n);
    for (i = 300; i + 200 < tifz_n; i += 997) q[i] ^= 0xa5;
    {
        hf f;
        br_err e;
        br_status s = dem_load_mem("lzw_pred2_tiled.tif", q, tifz_n, NULL, &f, &e);
        CHECK_MSG(s != BR_OK || 1, "%d", s);   /* may decode to wrong heights; must not crash */
        if (s == BR_OK) dem_free(&f);
        memset(q + 400, 0xff, 2000);
        s = dem_load_mem("lzw_pred2_tiled.tif", q, tifz_n, NULL, &f, &e);
        if (s == BR_OK) dem_free(&f);
    }
    free(q);
    /* NaN and infinity in float samples; the declared nodata value is a void */
    {
        float v[6] = { 1.5f, 2.25f, -3.0f, 4.0f, -9999.0f, 6.0f };
        br_status s;
        unsigned char *t = mk_tif_float(v, 3, 2, "-9999", &n);
        hf f;
        br_err e;
        s = dem_load_mem("float.tif", t, n, NULL, &f, &e);
        CHECK_MSG(s == BR_OK, "%s", e.msg);
        if (s == BR_OK) {
            CHECK_EQ(f.z_den, 1000000);
            CHECK_EQ(f.z[1], 2250000);
            CHECK_EQ(f.z[4], HF_NODATA);
            dem_free(&f);
        }
        free(t);
        v[1] = NAN;
        t = mk_tif_float(v, 3, 2, "-9999", &n);
        BAD("float.tif", t, n, NULL, BR_E_VALUE);
        free(t);
        t = mk_tif_float(v, 3, 2, "nan", &n);                    /* NaN declared as nodata */
        s = dem_load_mem("float.tif", t, n, NULL, &f, &e);
        CHECK_MSG(s == BR_OK, "%s", e.msg);
        if (s == BR_OK) {
            CHECK_EQ(f.z[1], HF_NODATA);
            CHECK_EQ(f.z_den, 10000);             /* 9999 m * 10^5 would pass 2^27 */
            CHECK_EQ(f.z[4], -99990000);
            dem_free(&f);
        }
        free(t);
        v[1] = INFINITY;
        t = mk_tif_float(v, 3, 2, NULL, &n);
        BAD("float.tif", t, n, NULL, BR_E_VALUE);
        BAD("float.tif", t, n - 30, NULL, BR_E_TRUNCATED);
        free(t);
    }
}

static void test_xyz(void)
{
    static const char nanv[] = "0 0 1\n1 0 nan\n0 1 2\n1 1 3\n";
    static const char infv[] = "0 0 1\n1 0 2\n0 1 -inf\n1 1 3\n";
    static const char text[] = "0 0 1\n1 0 2\n0 one 2\n1 1 3\n";
    static const char two[] = "0 0 1\n1 0\n0 1 2\n1 1 3\n";
    static const char four[] = "0 0 1\n1 0 2 5\n0 1 2\n1 1 3\n";
    static const char dup[] = "0 0 1\n1 0 2\n0 0 2\n1 1 3\n";
    static const char irregular[] = "0 0 1\n1 0 2\n2.5 0 2\n0 1 3\n1 1 3\n2.5 1 3\n";
    static const char sparse[] = "0 0 1\n1000 1000 2\n0.02 0 3\n";
    static const char holes[] = "0 0 1\n10 10 2\n0 1 3\n1 0 4\n";
    static const char empty[] = "# only a comment\n\n";
    static const char ok[] = "x,y,z\n0,0,1.5\n1,0,2\n0,1,3\n1,1,4\n";
    BAD("x.xyz", nanv, sizeof nanv - 1, NULL, BR_E_VALUE);
    BAD("x.xyz", infv, sizeof infv - 1, NULL, BR_E_VALUE);
    BAD("x.xyz", text, sizeof text - 1, NULL, BR_E_VALUE);
    BAD("x.xyz", two, sizeof two - 1, NULL, BR_E_FORMAT);
    BAD("x.xyz", four, sizeof four - 1, NULL, BR_E_FORMAT);
    BAD("x.xyz", dup, sizeof dup - 1, NULL, BR_E_FORMAT);
    BAD("x.xyz", irregular, sizeof irregular - 1, NULL, BR_E_FORMAT);
    BAD("x.xyz", sparse, sizeof sparse - 1, NULL, BR_E_TOO_BIG);
    BAD("x.xyz", holes, sizeof holes - 1, NULL, BR_E_FORMAT);
    BAD("x.xyz", empty, sizeof empty - 1, NULL, BR_E_FORMAT);
    {
        hf f;
        br_err e;
        CHECK_EQ(dem_load_mem("ok.xyz", (const uint8_t *)ok, sizeof ok - 1, NULL, &f, &e), BR_OK);
        CHECK_EQ(f.w, 2);
        CHECK_EQ(f.h, 2);
        CHECK_EQ(f.z[2], 1500000);              /* (0,0) is the south-west: row 1 */
        dem_free(&f);
    }
    /* x values within text rounding of each other are one grid line (load_xyz.c lattice),
     * though not equal: every point of that axis is in column 0.  They once took the y
     * axis's step for their column, so 1000008 fell in column 1 of a one-column grid
     * (past the end in the last row; found by fuzz_xyz); and the fuzzer's own file
     * (x 2.786e10 and 2.78599e10) is refused for its georeference, not read out of bounds */
    {
        static const char one_line[] = "1000008 0 5\n1000000 10 6\n1000000 20 7\n";
        static const char fuzzed[] = "2.78600e+10\t\t\t\t-02  0.3535000e-01\r\n2.78599e+10\t\t\t\t\t\t\t\t0 0 ";
        hf f;
        br_err e;
        CHECK_EQ(dem_load_mem("one_line.xyz", (const uint8_t *)one_line, sizeof one_line - 1, NULL, &f, &e), BR_OK);
        CHECK_EQ(f.w, 1);
        CHECK_EQ(f.h, 3);
        if (f.w == 1 && f.h == 3) CHECK(f.z[0] == 7000000 && f.z[1] == 6000000 && f.z[2] == 5000000);
        dem_free(&f);
        BAD("fuzzed.xyz", fuzzed, sizeof fuzzed - 1, NULL, BR_E_VALUE);
    }
    /* the real file cut in the middle of a line */
    {
        size_t i, lines = 0;
        for (i = 0; i < xyz_n && lines < 1000; i++) lines += xyz[i] == '\n';
        /* line 1001 is " x  y  z": keep its first two numbers only */
        BAD("monai_valley_bathymetry.txt", xyz, i + 25, NULL, BR_E_FORMAT);
    }
}

static void test_dispatch(void)
{
    static const unsigned char junk[16] = { 0xde, 0xad, 0xbe, 0xef, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12 };
    BAD("x.dat", junk, sizeof junk, NULL, BR_E_FORMAT);
    BAD("x.dat", junk, 0, NULL, BR_E_FORMAT);
    BAD("x.tif", hgt, 4096, NULL, BR_E_FORMAT);                 /* extension says TIFF, content does not */
    BAD("x.png", hgt, 4096, NULL, BR_E_FORMAT);
    BAD("x.bt", hgt, 4096, NULL, BR_E_FORMAT);
    {
        hf f;
        br_err e;
        CHECK_EQ(dem_load("no/such/file.hgt", NULL, &f, &e), BR_E_IO);
        CHECK(strstr(e.msg, "no/such/file.hgt") != NULL);
    }
}

int main(void)
{
    hgt = t_read_file(t_data("hgt/N47E009.hgt"), &hgt_n);
    png = t_read_file(t_data("png/ps_height_1k.png"), &png_n);
    fuji = t_read_file(t_data("png/fuji.png"), &fuji_n);
    asc = t_read_file(t_data("asc/hugo_site.asc"), &asc_n);
    bt = t_read_file(t_data("bt/crater_0513.bt"), &bt_n);
    tif = t_read_file(t_data("tif/mt_rainier_90m.tif"), &tif_n);
    xyz = t_read_file(t_data("xyz/monai_valley_bathymetry.txt"), &xyz_n);
    tifz = t_read_file("tests/data/tif/lzw_pred2_tiled.tif", &tifz_n);
    if (!hgt || !png || !fuji || !asc || !bt || !tif || !xyz || !tifz) {
        fprintf(stderr, "test_badinput: cannot read the real data files\n");
        printf("0 passed, 1 failed\n");
        return 1;
    }
    T_RUN(test_hgt);
    T_RUN(test_gz_zip);
    T_RUN(test_png);
    T_RUN(test_asc);
    T_RUN(test_bt);
    T_RUN(test_tif);
    T_RUN(test_xyz);
    T_RUN(test_dispatch);
    free(hgt); free(png); free(fuji); free(asc); free(bt); free(tif); free(xyz); free(tifz);
    return t_finish();
}
