/* tests/test_load.c — every real file in ../shared/data/dem through the loaders:
 * dimensions, units, min/max, voids, spacing and georeference, and merging. */
#define _POSIX_C_SOURCE 200809L   /* dup, dup2, fileno: to capture `bitrain info` output */
#include <unistd.h>
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/load.h"
#include "platform/merge.h"
#include "tests/zipmk.h"

static void expect_path(const char *rel, const dem_opts *o, int w, int h, int num, int den,
                        long long zmin, long long zmax, long long voids)
{
    hf f;
    hf_stats st;
    br_err e;
    br_status s = dem_load(rel, o, &f, &e);
    CHECK_MSG(s == BR_OK, "%s: %s", rel, s ? e.msg : "");
    if (s) return;
    CHECK_EQ(hf_validate(&f), BR_OK);
    CHECK_EQ(f.w, w);
    CHECK_EQ(f.h, h);
    CHECK_EQ(f.z_num, num);
    CHECK_EQ(f.z_den, den);
    hf_stats_get(&f, &st);
    CHECK_EQ(st.zmin, zmin);
    CHECK_EQ(st.zmax, zmax);
    CHECK_EQ(st.voids, voids);
    dem_free(&f);
}

static void expect(const char *rel, const dem_opts *o, int w, int h, int num, int den,
                   long long zmin, long long zmax, long long voids)
{
    expect_path(t_data(rel), o, w, h, num, den, zmin, zmax, voids);
}

static void test_hgt(void)
{
    expect("hgt/N47E009.hgt", NULL, 1201, 1201, 1, 1, 388, 2937, 0);
    expect("hgt/N50E008.hgt", NULL, 1201, 1201, 1, 1, 62, 885, 50);
    expect("hgt/N50E009.hgt", NULL, 1201, 1201, 1, 1, 98, 950, 12);
    expect("hgt/N50E010.hgt", NULL, 1201, 1201, 1, 1, 185, 983, 28);
    expect("hgt/N57E011.hgt", NULL, 1201, 1201, 1, 1, -6, 163, 0);
}

/* sample (x, y) of a file, counted from the NW corner */
static int32_t at(const char *rel, const dem_opts *o, int x, int y)
{
    hf f;
    br_err e;
    int32_t v;
    if (dem_load(t_data(rel), o, &f, &e) != BR_OK) return INT32_MAX;
    v = f.z[(size_t)y * f.w + x];
    dem_free(&f);
    return v;
}

static void test_png(void)
{
    dem_opts o;
    memset(&o, 0, sizeof o);
    /* 16-bit grey, raw units by default, 0.1 m with --scale 0.1 */
    expect("png/ps_height_1k.png", NULL, 1025, 1025, 1, 1, 0, 43798, 0);
    o.png_scale = 0.1;
    expect("png/ps_height_1k.png", &o, 1025, 1025, 1, 10, 0, 43798, 0);
    /* scale 0.5 and offset -100.25: unit 1/4 m, z = raw*2 - 401 */
    o.png_scale = 0.5;
    o.png_offset = -100.25;
    expect("png/ps_height_1k.png", &o, 1025, 1025, 1, 4, -401, 43798 * 2 - 401, 0);
    /* terrain-RGB (auto for a colour PNG): 13.7 .. 3751.0 m in 0.1 m */
    expect("png/fuji.png", NULL, 512, 512, 1, 10, 137, 37510, 0);
    /* gdallocationinfo fuji.png 100 200 -> R,G,B = 1,160,238: -10000 + 106734 * 0.1 */
    CHECK_EQ(at("png/fuji.png", NULL, 100, 200), 6734);
    /* the same pixels read as Terrarium: R*256 + G + B/256 - 32768 in 1/256 m */
    memset(&o, 0, sizeof o);
    o.png_encoding = DEM_PNG_TERRARIUM;
    CHECK_EQ(at("png/fuji.png", &o, 100, 200), (1 * 65536 + 160 * 256 + 238) - 32768 * 256);
    /* grey asked for a colour PNG is refused */
    {
        hf f;
        br_err e;
        o.png_encoding = DEM_PNG_GREY;
        CHECK_EQ(dem_load(t_data("png/fuji.png"), &o, &f, &e), BR_E_UNSUPPORTED);
    }
}

static void test_asc(void)
{
    hf f;
    br_err e;
    expect("asc/colorado_front_range.asc", NULL, 240, 144, 1, 1, 1943, 3286, 0);
    expect("asc/hugo_site.asc", NULL, 76, 55, 1, 1, 1660, 1711, 2028);
    /* gdallocationinfo values */
    CHECK_EQ(at("asc/hugo_site.asc", NULL, 40, 30), 1684);
    CHECK_EQ(at("asc/colorado_front_range.asc", NULL, 239, 143), 2028);
    CHECK_EQ(dem_load(t_data("asc/colorado_front_range.asc"), NULL, &f, &e), BR_OK);
    CHECK_EQ(f.geo.kind, HF_GEO_DEGREES);
    CHECK_EQ(f.geo.x0, -105550000000LL);        /* xllcorner + cellsize/2 */
    CHECK_EQ(f.geo.y0, 40210000000LL);          /* yllcorner + 144 cells - cellsize/2 */
    CHECK_EQ(f.geo.sx, 833333);
    dem_free(&f);
    CHECK_EQ(dem_load(t_data("asc/hugo_site.asc"), NULL, &f, &e), BR_OK);
    CHECK_EQ(f.geo.kind, HF_GEO_PROJECTED);
    CHECK_EQ(f.geo.x0, 5000000);                /* metres in micrometres */
    CHECK_EQ(f.geo.y0, 545000000);
    CHECK_EQ(f.dx_um, 10000000);
    dem_free(&f);
}

static void test_bt(void)
{
    hf f;
    br_err e;
    /* float32: 1524 .. 2478 m kept in 1e-4 m (2478e5 would pass 2^27) */
    expect("bt/crater_0513.bt", NULL, 513, 513, 1, 10000, 15240000, 24780000, 0);
    /* column-major, south first in the file; gdallocationinfo (x, y from NW) */
    CHECK_EQ(at("bt/crater_0513.bt", NULL, 0, 0), 16250000);
    CHECK_EQ(at("bt/crater_0513.bt", NULL, 512, 0), 20540000);
    CHECK_EQ(at("bt/crater_0513.bt", NULL, 7, 500), 16850000);
    CHECK_EQ(dem_load(t_data("bt/crater_0513.bt"), NULL, &f, &e), BR_OK);
    CHECK_EQ(f.geo.kind, HF_GEO_PROJECTED);
    CHECK_EQ(f.geo.x0, 561133125000LL);         /* UTM metres, extents are sample positions */
    CHECK_EQ(f.geo.y0, 4760971500000LL);
    CHECK_EQ(f.dx_um, 20182251);                /* (571466.4375 - 561133.125) / 512 */
    CHECK_EQ(f.dy_um, 27304688);
    dem_free(&f);
}

static void test_tif(void)
{
    hf f, r, v;
    br_err e;
    int k, x, y;
    static const char *const variants[] = {
        "tests/data/tif/lzw_pred2_tiled.tif", "tests/data/tif/deflate_be_strips.tif",
        "tests/data/tif/lzw_pred2_be_int32.tif"
    };
    expect("tif/mt_rainier_90m.tif", NULL, 1201, 1201, 1, 1, 263, 4371, 9033);
    CHECK_EQ(at("tif/mt_rainier_90m.tif", NULL, 600, 300), 1388);
    CHECK_EQ(dem_load(t_data("tif/mt_rainier_90m.tif"), NULL, &f, &e), BR_OK);
    CHECK_EQ(f.geo.kind, HF_GEO_DEGREES);
    CHECK_EQ(f.geo.x0, -122000000000LL);        /* tie point corner + half a pixel */
    CHECK_EQ(f.geo.y0, 47000000000LL);
    /* GDAL-written crops (840, 5, 67x45) in other encodings equal the window */
    CHECK_EQ(dem_load("tests/data/tif/ref_int16.tif", NULL, &r, &e), BR_OK);
    CHECK_EQ(r.w, 67);
    CHECK_EQ(r.h, 45);
    for (y = 0; y < 45; y++)
        for (x = 0; x < 67; x++)
            if (r.z[y * 67 + x] != f.z[(size_t)(5 + y) * 1201 + 840 + x]) { CHECK_EQ(x * 1000 + y, -1); y = 45; break; }
    for (k = 0; k < 3; k++) {
        br_status s = dem_load(variants[k], NULL, &v, &e);
        CHECK_MSG(s == BR_OK, "%s", s ? e.msg : "");
        if (s) continue;
        CHECK_EQ(v.w, 67);
        CHECK_EQ(v.h, 45);
        CHECK_EQ(v.geo.x0, r.geo.x0);
        CHECK_EQ(v.geo.y0, r.geo.y0);
        CHECK(memcmp(v.z, r.z, 67 * 45 * sizeof(int32_t)) == 0);
        dem_free(&v);
    }
    /* uint16, deflate + predictor: raw = h + 32768, nodata 0 */
    CHECK_EQ(dem_load("tests/data/tif/deflate_pred2_uint16.tif", NULL, &v, &e), BR_OK);
    for (k = 0; k < 67 * 45; k++)
        if ((r.z[k] == HF_NODATA) != (v.z[k] == HF_NODATA) ||
            (r.z[k] != HF_NODATA && v.z[k] != r.z[k] + 32768)) { CHECK_EQ(k, -1); break; }
    dem_free(&v);
    dem_free(&r);
    dem_free(&f);
    /* float32, tiled deflate, heights / 10 (gdal: 99.7 .. 201.39999 m, nodata -9999) */
    expect_path("tests/data/tif/deflate_float32.tif", NULL, 41, 31, 1, 100000, 9970000, 20139999, 19);
}

static void test_xyz(void)
{
    dem_opts o;
    hf f;
    br_err e;
    /* z column as heights: -0.125 .. 0.13535 m, kept in micrometres */
    expect("xyz/monai_valley_bathymetry.txt", NULL, 393, 244, 1, 1000000, -125000, 135350, 0);
    memset(&o, 0, sizeof o);
    o.xyz_depth = 1;
    expect("xyz/monai_valley_bathymetry.txt", &o, 393, 244, 1, 1000000, -135350, 125000, 0);
    /* first line of the file: x 0, y 0 (south-west), z 0.13535 */
    CHECK_EQ(at("xyz/monai_valley_bathymetry.txt", NULL, 0, 243), 135350);
    CHECK_EQ(dem_load(t_data("xyz/monai_valley_bathymetry.txt"), NULL, &f, &e), BR_OK);
    CHECK_EQ(f.geo.kind, HF_GEO_PROJECTED);
    CHECK_EQ(f.dx_um, 14000);
    CHECK_EQ(f.geo.y0, 3402000);
    dem_free(&f);
}

/* crops written by GDAL (tests/data/README.md) equal the window of the real file */
static void same_window(const char *crop, const char *rel, int x0, int y0)
{
    hf c, f;
    br_err e;
    int x, y, bad = 0;
    br_status s1 = dem_load(crop, NULL, &c, &e), s2;
    CHECK_MSG(s1 == BR_OK, "%s", e.msg);
    if (s1) return;
    s2 = dem_load(t_data(rel), NULL, &f, &e);
    CHECK_MSG(s2 == BR_OK, "%s", e.msg);
    if (s2 == BR_OK) {
        CHECK_EQ(c.z_num * f.z_den, f.z_num * c.z_den);
        for (y = 0; y < c.h; y++)
            for (x = 0; x < c.w; x++)
                bad += c.z[y * c.w + x] != f.z[(size_t)(y0 + y) * f.w + x0 + x];
        CHECK_EQ(bad, 0);
        dem_free(&f);
    }
    dem_free(&c);
}

static void test_gdal_crops(void)
{
    same_window("tests/data/png/ps_height_crop.png", "png/ps_height_1k.png", 500, 400);
    same_window("tests/data/png/fuji_crop.png", "png/fuji.png", 100, 200);
    same_window("tests/data/bt/crater_crop.bt", "bt/crater_0513.bt", 40, 60);   /* BT 1.3 */
}

/* 8-bit grey with scale and offset: fuji's green channel (GDAL band 2 crop) */
static void test_png_grey8(void)
{
    dem_opts o;
    hf g, f;
    br_err e;
    int x, y, bad = 0;
    memset(&o, 0, sizeof o);
    o.png_scale = 0.5;
    o.png_offset = 100;
    CHECK_EQ(dem_load("tests/data/png/fuji_green_crop.png", &o, &g, &e), BR_OK);
    CHECK_EQ(g.z_num, 1);                      /* 0.5 m: z = raw + 200 */
    CHECK_EQ(g.z_den, 2);
    CHECK_EQ(dem_load(t_data("png/fuji.png"), NULL, &f, &e), BR_OK);
    for (y = 0; y < g.h; y++)
        for (x = 0; x < g.w; x++) {
            int32_t rgb = f.z[(size_t)(200 + y) * f.w + 100 + x] + 100000;
            bad += g.z[y * g.w + x] != ((rgb >> 8) & 255) + 200;
        }
    CHECK_EQ(bad, 0);
    dem_free(&f);
    dem_free(&g);
}

static void test_containers(void)
{
    size_t n = 0, zn = 0;
    unsigned char *raw = t_read_file(t_data("hgt/N47E009.hgt"), &n);
    unsigned char *gz;
    hf a, b;
    br_err e;
    CHECK(raw != NULL);
    if (!raw) return;
    CHECK_EQ(dem_load_mem("N47E009.hgt", raw, n, NULL, &a, &e), BR_OK);
    gz = t_gzip(raw, n, &zn);
    CHECK_EQ(dem_load_mem("N47E009.hgt.gz", gz, zn, NULL, &b, &e), BR_OK);
    CHECK(memcmp(a.z, b.z, 1201 * 1201 * 4) == 0);
    CHECK_EQ(b.geo.y0, 48000000000LL);          /* the tile name survives ".gz" */
    dem_free(&b);
    free(gz);
    gz = t_zip("N47E009.hgt", raw, n, 1, &zn);
    CHECK_EQ(dem_load_mem("N47E009.hgt.zip", gz, zn, NULL, &b, &e), BR_OK);
    CHECK(memcmp(a.z, b.z, 1201 * 1201 * 4) == 0);
    CHECK_EQ(b.geo.x0, 9000000000LL);
    dem_free(&b);
    free(gz);
    gz = t_zip("N47E009.hgt", raw, n, 0, &zn);  /* stored, not deflated */
    CHECK_EQ(dem_load_mem("x.zip", gz, zn, NULL, &b, &e), BR_OK);
    CHECK_EQ(b.geo.x0, 9000000000LL);           /* the member's name gives the tile */
    dem_free(&b);
    free(gz);
    /* the shipped default terrain, if present */
    {
        FILE *f = fopen("assets/N47E009.hgt.gz", "rb");
        if (f) {
            fclose(f);
            CHECK_EQ(dem_load("assets/N47E009.hgt.gz", NULL, &b, &e), BR_OK);
            CHECK(memcmp(a.z, b.z, 1201 * 1201 * 4) == 0);
            dem_free(&b);
        }
    }
    dem_free(&a);
    free(raw);
}

static void test_hgt_geo(void)
{
    hf f;
    br_err e;
    CHECK_EQ(dem_load(t_data("hgt/N50E008.hgt"), NULL, &f, &e), BR_OK);
    CHECK_EQ(f.geo.kind, HF_GEO_DEGREES);
    CHECK_EQ(f.geo.x0, 8000000000LL);          /* sample (0,0) = NW corner: 51 N, 8 E */
    CHECK_EQ(f.geo.y0, 51000000000LL);
    CHECK_EQ(f.geo.sx, 833333);                /* 3 arc-seconds in nano-degrees */
    CHECK_EQ(f.geo.sy, 833333);
    /* WGS84 series at 50.5 N over 1200 steps per degree (python: 59.12451241, 92.69890303 m) */
    CHECK_EQ(f.dx_um, 59124512);
    CHECK_EQ(f.dy_um, 92698903);
    /* the first sample of the file is the NW corner */
    {
        size_t n;
        unsigned char *raw = t_read_file(t_data("hgt/N50E008.hgt"), &n);
        CHECK(raw != NULL);
        if (raw) {
            int16_t v0 = (int16_t)(raw[0] << 8 | raw[1]);
            int16_t vl = (int16_t)(raw[n - 2] << 8 | raw[n - 1]);
            CHECK_EQ(f.z[0], v0 == -32768 ? HF_NODATA : v0);
            CHECK_EQ(f.z[1201 * 1201 - 1], vl == -32768 ? HF_NODATA : vl);
            free(raw);
        }
    }
    dem_free(&f);
}

static void test_merge_n50(void)
{
    const char *p[3];
    hf f, a;
    hf_stats st;
    br_err e;
    br_status s;
    /* file order must not matter: east tile first */
    p[0] = t_data("hgt/N50E010.hgt");
    p[1] = t_data("hgt/N50E008.hgt");
    p[2] = t_data("hgt/N50E009.hgt");
    s = dem_load_many(p, 3, NULL, &f, &e);
    CHECK_MSG(s == BR_OK, "%s", s ? e.msg : "");
    if (s) return;
    CHECK_EQ(f.w, 3601);
    CHECK_EQ(f.h, 1201);
    CHECK_EQ(f.geo.x0, 8000000000LL);
    CHECK_EQ(f.geo.y0, 51000000000LL);
    hf_stats_get(&f, &st);
    CHECK_EQ(st.zmin, 62);
    CHECK_EQ(st.zmax, 983);
    CHECK_EQ(st.voids, 50 + 12 + 28);          /* no void on the shared edges */
    CHECK_EQ(f.dx_um, 59124512);               /* same centre latitude as each tile */
    CHECK_EQ(f.dy_um, 92698903);
    CHECK_EQ(dem_load(p[2], NULL, &a, &e), BR_OK);
    /* N50E009 sits at columns 1200..2400 */
    CHECK_EQ(f.z[(size_t)600 * 3601 + 1200 + 17], a.z[600 * 1201 + 17]);
    CHECK_EQ(f.z[(size_t)1200 * 3601 + 2400], a.z[1201 * 1201 - 1]);
    dem_free(&a);
    dem_free(&f);
}

static void test_merge_errors(void)
{
    const char *p[2];
    hf f;
    br_err e;
    /* not adjacent: a gap between 8 E and 10 E */
    p[0] = t_data("hgt/N50E008.hgt");
    p[1] = t_data("hgt/N50E010.hgt");
    CHECK_EQ(dem_load_many(p, 2, NULL, &f, &e), BR_E_MERGE);
    /* different release / place under the same georeference: overlap with other values */
    {
        size_t n;
        unsigned char *raw = t_read_file(t_data("hgt/N47E009.hgt"), &n);
        hf t[2];
        const char *names[2] = { "N50E008.hgt", "N50E009.hgt" };
        CHECK(raw != NULL);
        if (!raw) return;
        CHECK_EQ(dem_load(t_data("hgt/N50E008.hgt"), NULL, &t[0], &e), BR_OK);
        CHECK_EQ(dem_load_mem("fake/N50E009.hgt", raw, n, NULL, &t[1], &e), BR_OK);
        CHECK_EQ(dem_merge(t, names, 2, &f, &e), BR_E_MERGE);
        dem_free(&t[1]);
        /* a tile without a georeference cannot be placed */
        CHECK_EQ(dem_load_mem("noname.hgt", raw, n, NULL, &t[1], &e), BR_OK);
        CHECK_EQ(t[1].geo.kind, HF_GEO_NONE);
        CHECK_EQ(dem_merge(t, names, 2, &f, &e), BR_E_MERGE);
        CHECK(strstr(e.msg, "N50E009.hgt") != NULL);
        dem_free(&t[1]);
        dem_free(&t[0]);
        free(raw);
    }
    /* the same tile twice is a full overlap with equal values: fine, 1201x1201 */
    p[0] = t_data("hgt/N50E008.hgt");
    p[1] = t_data("hgt/N50E008.hgt");
    CHECK_EQ(dem_load_many(p, 2, NULL, &f, &e), BR_OK);
    CHECK_EQ(f.w, 1201);
    dem_free(&f);
}

/* four projected ASC tiles in a 2x2 square sharing their middle row and
 * column, one with decimals: placed by corners, units unified */
static void test_merge_asc(void)
{
    static const char nw[] = "ncols 3\nnrows 2\nxllcorner 100\nyllcorner 210\ncellsize 10\n1 2 3\n4 5 6\n";
    static const char ne[] = "ncols 3\nnrows 2\nxllcorner 120\nyllcorner 210\ncellsize 10\n3 7.5 8\n6 9 10\n";
    static const char sw[] = "ncols 3\nnrows 2\nxllcorner 100\nyllcorner 200\ncellsize 10\n4 5 6\n11 12 13\n";
    static const char se[] = "ncols 3\nnrows 2\nxllcorner 120\nyllcorner 200\ncellsize 10\n6 9 10\n13 14 -99\n";
    static const char se_bad[] = "ncols 3\nnrows 2\nxllcorner 120\nyllcorner 200\ncellsize 10\n6 9.001 10\n13 14 15\n";
    static const char off[] = "ncols 3\nnrows 2\nxllcorner 125\nyllcorner 200\ncellsize 10\n6 9 10\n13 14 15\n";
    const char *src[4] = { se, nw, sw, ne };
    const char *names[4] = { "se.asc", "nw.asc", "sw.asc", "ne.asc" };
    hf t[4], m;
    br_err e;
    br_status s;
    int i;
    static const int32_t want[15] = { 1000, 2000, 3000, 7500, 8000,
                                      4000, 5000, 6000, 9000, 10000,
                                      11000, 12000, 13000, 14000, -99000 };
    for (i = 0; i < 4; i++)
        CHECK_EQ(dem_load_mem(names[i], (const uint8_t *)src[i], strlen(src[i]), NULL, &t[i], &e), BR_OK);
    CHECK_EQ(t[1].z_den, 1);
    CHECK_EQ(t[3].z_den, 1000000);
    s = dem_merge(t, names, 4, &m, &e);
    CHECK_MSG(s == BR_OK, "%s", e.msg);
    if (s != BR_OK) { for (i = 0; i < 4; i++) dem_free(&t[i]); return; }
    CHECK_EQ(m.w, 5);
    CHECK_EQ(m.h, 3);
    CHECK_EQ(m.z_num, 1);
    CHECK_EQ(m.z_den, 1000000);                /* the finest unit among the tiles */
    for (i = 0; i < 15; i++) CHECK_EQ(m.z[i], want[i] * 1000LL);
    CHECK_EQ(m.geo.x0, 105000000);             /* centre of the NW sample, micrometres */
    CHECK_EQ(m.geo.y0, 225000000);
    dem_free(&m);
    dem_free(&t[0]);
    /* the shared column disagrees by 1 mm */
    CHECK_EQ(dem_load_mem("se.asc", (const uint8_t *)se_bad, strlen(se_bad), NULL, &t[0], &e), BR_OK);
    CHECK_EQ(dem_merge(t, names, 4, &m, &e), BR_E_MERGE);
    dem_free(&t[0]);
    /* half a cell off the grid */
    CHECK_EQ(dem_load_mem("se.asc", (const uint8_t *)off, strlen(off), NULL, &t[0], &e), BR_OK);
    CHECK_EQ(dem_merge(t, names, 4, &m, &e), BR_E_MERGE);
    dem_free(&t[0]);
    for (i = 1; i < 4; i++) dem_free(&t[i]);
}

/* `bitrain info --json` over every real file: the keys and figures the issue asks for */
static void test_info_json(void)
{
    static const struct { const char *file, *want; } rows[] = {
        { "hgt/N47E009.hgt", "\"width\":1201,\"height\":1201,\"min\":388,\"max\":2937,\"voids\":0," },
        { "hgt/N50E008.hgt", "\"width\":1201,\"height\":1201,\"min\":62,\"max\":885,\"voids\":50," },
        { "hgt/N50E009.hgt", "\"width\":1201,\"height\":1201,\"min\":98,\"max\":950,\"voids\":12," },
        { "hgt/N50E010.hgt", "\"width\":1201,\"height\":1201,\"min\":185,\"max\":983,\"voids\":28," },
        { "hgt/N57E011.hgt", "\"width\":1201,\"height\":1201,\"min\":-6,\"max\":163,\"voids\":0," },
        { "png/fuji.png", "\"width\":512,\"height\":512,\"min\":13.7,\"max\":3751,\"voids\":0," },
        { "asc/colorado_front_range.asc", "\"width\":240,\"height\":144,\"min\":1943,\"max\":3286,\"voids\":0," },
        { "asc/hugo_site.asc", "\"width\":76,\"height\":55,\"min\":1660,\"max\":1711,\"voids\":2028," },
        { "bt/crater_0513.bt", "\"width\":513,\"height\":513,\"min\":1524,\"max\":2478,\"voids\":0," },
        { "tif/mt_rainier_90m.tif", "\"width\":1201,\"height\":1201,\"min\":263,\"max\":4371,\"voids\":9033," },
        { "xyz/monai_valley_bathymetry.txt", "\"width\":393,\"height\":244,\"min\":-0.125,\"max\":0.13535,\"voids\":0," },
    };
    const size_t nrows = sizeof rows / sizeof rows[0];
    char *argv[32], path[512], files[16][512], *out;
    int argc = 0, rc, saved;
    size_t i, n = 0;
    FILE *f;
    snprintf(path, sizeof path, "%s/info.json", t_outdir());
    argv[argc++] = (char *)"--json";
    for (i = 0; i < nrows; i++) {      /* t_data's buffers rotate: keep copies */
        snprintf(files[i], sizeof files[i], "%s", t_data(rows[i].file));
        argv[argc++] = files[i];
    }
    fflush(stdout);
    saved = dup(fileno(stdout));
    f = fopen(path, "w");
    CHECK(f != NULL && saved >= 0);
    if (!f || saved < 0) return;
    dup2(fileno(f), fileno(stdout));
    rc = cmd_info(argc, argv);
    fflush(stdout);
    dup2(saved, fileno(stdout));
    close(saved);
    fclose(f);
    CHECK_EQ(rc, 0);
    out = (char *)t_read_file(path, &n);
    CHECK(out != NULL);
    if (!out) return;
    out[n] = 0;
    for (i = 0; i < nrows; i++) CHECK_MSG(strstr(out, rows[i].want) != NULL, "%s: %s", rows[i].file, rows[i].want);
    CHECK(strstr(out, "\"spacing\":{\"dx\":59.124512,\"dy\":92.698903}") != NULL);
    CHECK(strstr(out, "\"origin\":{\"kind\":\"degrees\",\"x\":-122.000000000,\"y\":47.000000000") != NULL);
    for (i = 0, n = 0; out[i]; i++) n += out[i] == '\n';
    CHECK_EQ(n, nrows);                        /* one object per file per line */
    free(out);
}

int main(void)
{
    T_RUN(test_hgt);
    T_RUN(test_hgt_geo);
    T_RUN(test_png);
    T_RUN(test_asc);
    T_RUN(test_bt);
    T_RUN(test_tif);
    T_RUN(test_xyz);
    T_RUN(test_containers);
    T_RUN(test_gdal_crops);
    T_RUN(test_png_grey8);
    T_RUN(test_info_json);
    T_RUN(test_merge_n50);
    T_RUN(test_merge_errors);
    T_RUN(test_merge_asc);
    return t_finish();
}
