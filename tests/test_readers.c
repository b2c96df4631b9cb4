/* tests/test_readers.c — files that were refused or read wrong (issue 16): grey
 * palette PNGs, spacings coarser than 2.1 km, GeoClaw topography, --nodata,
 * merges that disagree or whose steps are rounded, XYZ with a far outlier.
 * Every fixture is made here from the real files in ../shared/data/dem. */
#include <math.h>
#include <png.h>
#include "tests/test.h"
#include "platform/load.h"
#include "platform/merge.h"
#include "platform/scene.h"

static int notes;
static char last_note[256];

static void on_note(const char *name, const char *msg)
{
    notes++;
    snprintf(last_note, sizeof last_note, "%s: %s", name, msg);
}

static br_status load(const char *path, const dem_opts *o, hf *f)
{
    br_err e;
    br_status s = dem_load(path, o, f, &e);
    if (s != BR_OK) fprintf(stderr, "  (%s)\n", e.msg);
    return s;
}

/* ---- 1. an 8-bit palette PNG whose palette is all grey ---- */

/* Writes g's heights (0..255) as an 8-bit palette PNG with entry k = grey level
 * 255 - k (so index and level differ); colour_entry >= 0 makes that entry red. */
static int write_palette_png(const char *path, const hf *g, int colour_entry)
{
    FILE *fp = fopen(path, "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    png_color pal[256];
    png_byte *row = malloc((size_t)g->w);
    int k, y, x;
    if (!fp || !png || !info || !row || setjmp(png_jmpbuf(png))) {
        if (png) png_destroy_write_struct(&png, &info);
        if (fp) fclose(fp);
        free(row);
        return 0;
    }
    for (k = 0; k < 256; k++) pal[k].red = pal[k].green = pal[k].blue = (png_byte)(255 - k);
    if (colour_entry >= 0) { pal[colour_entry].green = 0; pal[colour_entry].blue = 0; }
    png_init_io(png, fp);
    png_set_IHDR(png, info, (png_uint_32)g->w, (png_uint_32)g->h, 8, PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_PLTE(png, info, pal, 256);
    png_write_info(png, info);
    for (y = 0; y < g->h; y++) {
        for (x = 0; x < g->w; x++) row[x] = (png_byte)(255 - g->z[(size_t)y * g->w + x]);
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(fp);
    free(row);
    return 1;
}

static void test_png_grey_palette(void)
{
    char path[512], cpath[512];
    dem_opts o;
    hf g, f;
    int i, bad = 0;
    memset(&o, 0, sizeof o);
    if (load("tests/data/png/fuji_green_crop.png", NULL, &g) != BR_OK) { CHECK(0); return; }
    snprintf(path, sizeof path, "%s/grey_palette.png", t_outdir());
    snprintf(cpath, sizeof cpath, "%s/colour_palette.png", t_outdir());
    CHECK(write_palette_png(path, &g, -1));
    CHECK(write_palette_png(cpath, &g, 7));
    dem_set_note(on_note);
    notes = 0;
    CHECK_EQ(load(path, NULL, &f), BR_OK);               /* automatic: read as grey, and said so */
    CHECK_EQ(notes, 1);
    CHECK(strstr(last_note, "grey") != NULL);
    if (f.z) {
        CHECK_EQ(f.z_num, 1);
        CHECK_EQ(f.z_den, 1);
        for (i = 0; i < g.w * g.h; i++) bad += f.z[i] != g.z[i];
        CHECK_EQ(bad, 0);
        dem_free(&f);
    }
    o.png_encoding = DEM_PNG_GREY;                       /* asked for: accepted */
    notes = 0;
    CHECK_EQ(load(path, &o, &f), BR_OK);
    CHECK_EQ(notes, 0);
    if (f.z) { CHECK_EQ(f.z[0], g.z[0]); dem_free(&f); }
    /* a palette with one colour entry: not grey; automatic is terrain-RGB, said */
    CHECK_EQ(load(cpath, &o, &f), BR_E_UNSUPPORTED);
    notes = 0;
    CHECK_EQ(load(cpath, NULL, &f), BR_OK);
    CHECK_EQ(notes, 1);
    CHECK(strstr(last_note, "terrain-RGB") != NULL);
    if (f.z) { CHECK_EQ(f.z_den, 10); dem_free(&f); }
    dem_set_note(NULL);
    dem_free(&g);
}

/* ---- 2. spacing past 2,147 m: a real grid taken every 40th sample ---- */

/* N47E009 every 40th sample (31x31) as ESRI ASCII with the given header. */
static int write_coarse_asc(const char *path, const char *corner, double cell)
{
    hf t;
    FILE *fp;
    int x, y;
    if (load(t_data("hgt/N47E009.hgt"), NULL, &t) != BR_OK) return 0;
    fp = fopen(path, "w");
    if (!fp) { dem_free(&t); return 0; }
    fprintf(fp, "ncols 31\nnrows 31\n%s\ncellsize %.10g\n", corner, cell);
    for (y = 0; y < 31; y++)
        for (x = 0; x < 31; x++) fprintf(fp, "%d%c", t.z[(size_t)y * 40 * 1201 + (size_t)x * 40], x == 30 ? '\n' : ' ');
    fclose(fp);
    dem_free(&t);
    return 1;
}

/* Renders the default view of path (160x120, view-dependent mesh): triangles
 * drawn and pixels that are not sky. */
static void render_default(const char *path, uint32_t *tris, long *ground)
{
    scene s;
    scene_opts so;
    br_err e;
    cam c;
    bt_params p;
    rs_frame fr;
    rs_band_stats st;
    rs_prim prim;
    double eye[3], tgt[3];
    uint32_t *px = NULL;
    void *mem = NULL;
    int i;
    *tris = 0;
    *ground = 0;
    memset(&so, 0, sizeof so);
    so.quiet = 1;
    if (scene_open(&s, &path, 1, &so, &e) != BR_OK) { fprintf(stderr, "  (%s)\n", e.msg); return; }
    scene_default_view(&s, 60, eye, tgt);
    memset(&p, 0, sizeof p);
    memset(&fr, 0, sizeof fr);
    memset(&st, 0, sizeof st);
    p.pixel_err_q8 = 256;
    if (scene_camera(&s, eye, tgt, 60, 160, 120, &c) == BR_OK && scene_tree(&s, &e) == BR_OK &&
        scene_reserve(&s, 200000, &e) == BR_OK) {
        fr.fmt = RS_FMT_XRGB8888;
        fr.depth = RS_DEPTH32;
        fr.clear_rgb = 0x99ccffu;
        px = malloc((size_t)160 * 120 * 4);
        mem = malloc(rs_band_mem_size(160, 120, fr.fmt, fr.depth));
        if (px && mem && scene_frame(&s, &c, &p, &fr, &prim) == BR_OK &&
            (memset(&st, 0, sizeof st), rs_draw_band(&fr, 0, 120, px, 160 * 4, mem, &st)) == BR_OK) {
            *tris = st.tris;
            for (i = 0; i < 160 * 120; i++) *ground += (px[i] & 0xffffffu) != 0x99ccffu;
        }
    }
    free(px);
    free(mem);
    scene_close(&s);
}

static void test_coarse_spacing(void)
{
    char geo[512], prj[512], far[512];
    hf f;
    uint32_t tris;
    long ground;
    snprintf(geo, sizeof geo, "%s/coarse_1deg.asc", t_outdir());
    snprintf(prj, sizeof prj, "%s/coarse_111km.asc", t_outdir());
    snprintf(far, sizeof far, "%s/coarse_140km.asc", t_outdir());
    CHECK(write_coarse_asc(geo, "xllcorner -10.5\nyllcorner 20.5", 1.0));       /* one degree */
    CHECK(write_coarse_asc(prj, "xllcorner 500000\nyllcorner 4000000", 111000)); /* metres */
    CHECK(write_coarse_asc(far, "xllcorner 500000\nyllcorner 4000000", 140000));
    CHECK_EQ(load(geo, NULL, &f), BR_OK);
    if (f.z) {
        CHECK_EQ(f.geo.kind, HF_GEO_DEGREES);
        CHECK_EQ(f.geo.sx, 1000000000);
        CHECK(f.dy_um > 110000000000LL && f.dy_um < 112000000000LL);    /* ~111 km a degree of latitude */
        CHECK(f.dx_um > 89000000000LL && f.dx_um < 91000000000LL);      /* ~90 km a degree of longitude at 36 N */
        CHECK_EQ(hf_validate(&f), BR_OK);
        dem_free(&f);
    }
    CHECK_EQ(load(prj, NULL, &f), BR_OK);
    if (f.z) { CHECK_EQ(f.dx_um, 111000000000LL); CHECK_EQ(f.dy_um, 111000000000LL); dem_free(&f); }
    CHECK_EQ(load(far, NULL, &f), BR_E_VALUE);                          /* past 2^37 um: said, not wrapped */
    /* the world frame, shading and a picture: the terrain fills part of the frame */
    render_default(geo, &tris, &ground);
    CHECK(tris > 50);      /* 31 x 31 samples, 2.4 km of relief over 2,700 km: 73 triangles at 1 px */
    CHECK(ground > 160 * 120 / 10);
    render_default(prj, &tris, &ground);
    CHECK(tris > 50);      /* 31 x 31 samples, 2.4 km of relief over 2,700 km: 73 triangles at 1 px */
    CHECK(ground > 160 * 120 / 10);
}

/* ---- 3. GeoClaw topotype 1, 2 and 3 from the Monai Valley bathymetry ---- */

/* Writes m (heights, Monai grid) as GeoClaw topotype tt: value-first header
 * (keyword-first when esri), 'xlower' or 'xllcorner' labels. */
static int write_geoclaw(const char *path, const hf *m, int tt, int esri, int corner)
{
    FILE *fp = fopen(path, "w");
    double dx = (double)m->geo.sx * 1e-6, x0 = (double)m->geo.x0 * 1e-6;
    double ys = (double)m->geo.y0 * 1e-6 - dx * (m->h - 1);
    double unit = (double)m->z_num / m->z_den, sh = corner ? dx / 2 : 0;
    const char *reg = corner ? "llcorner" : "lower";
    int x, y;
    if (!fp) return 0;
    if (tt == 1) {
        for (y = 0; y < m->h; y++)
            for (x = 0; x < m->w; x++)
                fprintf(fp, "%.6f %.6f %.7e\n", x0 + dx * x, ys + dx * (m->h - 1 - y), m->z[(size_t)y * m->w + x] * unit);
        fclose(fp);
        return 1;
    }
    if (esri)
        fprintf(fp, "ncols %d\nnrows %d\nx%s %.15e\ny%s %.15e\ncellsize %.15e\nnodata_value -9999\n", m->w, m->h,
                reg, x0 - sh, reg, ys - sh, dx);
    else
        fprintf(fp, "%6d                              ncols\n%6d                              nrows\n"
                    "%22.15e              x%s\n%22.15e              y%s\n%22.15e              cellsize\n"
                    "%10d                          nodata_value\n", m->w, m->h, x0 - sh, reg, ys - sh, reg, dx, -9999);
    for (y = 0; y < m->h; y++)
        for (x = 0; x < m->w; x++)
            fprintf(fp, "%15.7e%s", m->z[(size_t)y * m->w + x] * unit, tt == 2 || x == m->w - 1 ? "\n" : " ");
    fclose(fp);
    return 1;
}

static void same_grid(const char *path, const dem_opts *o, const hf *m)
{
    hf f;
    int i, bad = 0;
    CHECK_MSG(load(path, o, &f) == BR_OK, "%s", path);
    if (!f.z) return;
    CHECK_EQ(f.w, m->w);
    CHECK_EQ(f.h, m->h);
    CHECK_MSG(f.geo.kind == HF_GEO_PROJECTED, "%s", path);
    CHECK_EQ(f.geo.x0, m->geo.x0);
    CHECK_EQ(f.geo.y0, m->geo.y0);
    CHECK_EQ(f.geo.sx, m->geo.sx);
    CHECK_EQ(f.dx_um, m->dx_um);
    if (f.w == m->w && f.h == m->h)
        for (i = 0; i < f.w * f.h; i++)
            bad += (double)f.z[i] * f.z_num / f.z_den != (double)m->z[i] * m->z_num / m->z_den;
    CHECK_EQ(bad, 0);
    dem_free(&f);
}

static void test_geoclaw(void)
{
    dem_opts o;
    hf m;
    char p[6][512];
    static const char *const names[6] = { "monai.tt3", "MonaiValley_topo.txt", "monai.tt2", "monai_esri.tt3",
                                          "monai.tt1", "monai_corner.topotype2" };
    int k;
    memset(&o, 0, sizeof o);
    o.xyz_depth = 1;
    if (load(t_data("xyz/monai_valley_bathymetry.txt"), &o, &m) != BR_OK) { CHECK(0); return; }
    for (k = 0; k < 6; k++) snprintf(p[k], sizeof p[k], "%s/%s", t_outdir(), names[k]);
    CHECK(write_geoclaw(p[0], &m, 3, 0, 0));
    CHECK(write_geoclaw(p[1], &m, 3, 0, 0));      /* by content, whatever the name */
    CHECK(write_geoclaw(p[2], &m, 2, 0, 0));
    CHECK(write_geoclaw(p[3], &m, 3, 1, 0));
    CHECK(write_geoclaw(p[4], &m, 1, 0, 0));
    CHECK(write_geoclaw(p[5], &m, 2, 0, 1));      /* llcorner: data half a cell in */
    for (k = 0; k < 6; k++) same_grid(p[k], NULL, &m);
    /* negative topotype: the values are depths */
    {
        hf f;
        o.xyz_depth = 1;
        CHECK_EQ(load(p[0], &o, &f), BR_OK);
        if (f.z) { CHECK_EQ(f.z[0], -m.z[0]); dem_free(&f); }
    }
    dem_free(&m);
}

/* ---- 4. --nodata for every reader ---- */

/* Loads path with --nodata = the value of its first non-void sample as the
 * file stores it, and expects as many more voids as samples equal that one. */
static void nodata_case(const char *path, int raw_units)
{
    dem_opts o;
    hf f, g;
    hf_stats a, b;
    int64_t same = 0, i, i0 = 0;
    memset(&o, 0, sizeof o);
    if (load(path, NULL, &f) != BR_OK) { CHECK_MSG(0, "%s", path); return; }
    while (f.z[i0] == HF_NODATA) i0++;
    for (i = 0; i < (int64_t)f.w * f.h; i++) same += f.z[i] == f.z[i0];
    o.has_nodata = 1;
    o.nodata = raw_units ? (double)f.z[i0] : (double)f.z[i0] * f.z_num / f.z_den;
    CHECK_MSG(load(path, &o, &g) == BR_OK, "%s", path);
    if (g.z) {
        hf_stats_get(&f, &a);
        hf_stats_get(&g, &b);
        CHECK_MSG(b.voids == a.voids + same && g.z[i0] == HF_NODATA, "%s: voids %lld -> %lld, %lld equal %.9g",
                  path, (long long)a.voids, (long long)b.voids, (long long)same, o.nodata);
        dem_free(&g);
    }
    dem_free(&f);
}

static void test_nodata(void)
{
    size_t n = 0;
    unsigned char *t = t_read_file("tests/data/tif/ref_int16.tif", &n);
    hf f;
    char path[512], tt3[512];
    nodata_case(t_data("hgt/N50E008.hgt"), 0);
    nodata_case("tests/data/tif/ref_int16.tif", 0);
    nodata_case("tests/data/tif/deflate_float32.tif", 0);            /* float32: compared as float32 */
    nodata_case("tests/data/bt/crater_crop.bt", 0);
    nodata_case("tests/data/png/ps_height_crop.png", 1);             /* the raw 16-bit grey sample */
    nodata_case("tests/data/png/fuji_crop.png", 0);                  /* terrain-RGB: metres */
    nodata_case(t_data("asc/colorado_front_range.asc"), 0);
    nodata_case(t_data("xyz/monai_valley_bathymetry.txt"), 0);
    snprintf(tt3, sizeof tt3, "%s/monai.tt3", t_outdir());           /* written by test_geoclaw */
    nodata_case(tt3, 0);
    /* SRTM_f03: voids marked -32767 in a GeoTIFF without a NoData tag */
    CHECK(t != NULL);
    if (!t) return;
    {
        dem_opts o;
        hf_stats st;
        memset(&o, 0, sizeof o);
        /* ref_int16.tif: uncompressed little-endian strips; sample 0 at its first strip */
        if (load("tests/data/tif/ref_int16.tif", NULL, &f) == BR_OK) {
            size_t i, off = 0;
            int64_t voids;
            hf_stats_get(&f, &st);
            voids = st.voids;
            for (i = 0; i + 1 < n && !off; i++)
                if ((int16_t)(t[i] | t[i + 1] << 8) == f.z[0] && (int16_t)(t[i + 2] | t[i + 3] << 8) == f.z[1]) off = i;
            dem_free(&f);
            CHECK(off > 0);
            t[off] = 0x01; t[off + 1] = 0x80;                        /* -32767 */
            snprintf(path, sizeof path, "%s/srtm_f03_void.tif", t_outdir());
            CHECK(t_write_file(path, t, n));
            CHECK_EQ(load(path, NULL, &f), BR_OK);
            if (f.z) { hf_stats_get(&f, &st); CHECK_EQ(st.zmin, -32767); dem_free(&f); }
            o.has_nodata = 1;
            o.nodata = -32767;
            CHECK_EQ(load(path, &o, &f), BR_OK);
            if (f.z) { hf_stats_get(&f, &st); CHECK_EQ(st.voids, voids + 1); CHECK(st.zmin > 0); dem_free(&f); }
        }
    }
    free(t);
}

/* ---- 5. merges: which tile wins, and rounded steps ---- */

static void test_merge_prefer(void)
{
    const char *names[2] = { "N50E008.hgt", "N50E009.hgt" };
    hf t[2], m;
    br_err e;
    int32_t a, b;
    if (load(t_data("hgt/N50E008.hgt"), NULL, &t[0]) != BR_OK) { CHECK(0); return; }
    if (load(t_data("hgt/N50E009.hgt"), NULL, &t[1]) != BR_OK) { CHECK(0); dem_free(&t[0]); return; }
    a = t[0].z[100 * 1201 + 1200];
    b = t[1].z[100 * 1201] += 5;                                 /* the shared column disagrees */
    t[1].z[200 * 1201] = HF_NODATA;                              /* and one void on it */
    CHECK_EQ(dem_merge_prefer(t, names, 2, DEM_MERGE_REFUSE, &m, &e), BR_E_MERGE);
    CHECK(strstr(e.msg, "--merge-prefer") != NULL);
    CHECK_EQ(dem_merge_prefer(t, names, 2, DEM_MERGE_FIRST, &m, &e), BR_OK);
    if (m.z) {
        CHECK_EQ(m.z[100 * (size_t)m.w + 1200], a);
        CHECK_EQ(m.z[200 * (size_t)m.w + 1200], t[0].z[200 * 1201 + 1200]);
        dem_free(&m);
    }
    CHECK_EQ(dem_merge_prefer(t, names, 2, DEM_MERGE_LAST, &m, &e), BR_OK);
    if (m.z) {
        CHECK_EQ(m.z[100 * (size_t)m.w + 1200], b);
        CHECK_EQ(m.z[200 * (size_t)m.w + 1200], t[0].z[200 * 1201 + 1200]);   /* a void never wins */
        dem_free(&m);
    }
    dem_free(&t[0]);
    dem_free(&t[1]);
}

/* Tiles 7 degrees apart on a 2-arc-second grid: the step 1/1800 degree is kept
 * as 555556 nano-degrees, 0.44 too long, so 12600 steps overshoot by 5600. */
static void test_merge_rounded_step(void)
{
    const char *names[2] = { "wide.tif", "east.tif" };
    hf t[2], m;
    br_err e;
    hf r;
    int32_t x, y;
    if (load(t_data("hgt/N47E009.hgt"), NULL, &r) != BR_OK) { CHECK(0); return; }
    memset(t, 0, sizeof t);
    t[0].w = 12601; t[1].w = 2;
    for (x = 0; x < 2; x++) {
        t[x].h = 2;
        t[x].z = malloc(sizeof(int32_t) * (size_t)t[x].w * 2);
        t[x].z_num = t[x].z_den = 1;
        t[x].dx_um = t[x].dy_um = 40000000;
        t[x].geo.kind = HF_GEO_DEGREES;
        t[x].geo.sx = t[x].geo.sy = 555556;
        t[x].geo.y0 = 44000000000LL;
    }
    t[0].geo.x0 = 42000000000LL;
    t[1].geo.x0 = 49000000000LL;
    for (y = 0; y < 2; y++) {
        for (x = 0; x < 12601; x++) t[0].z[y * 12601 + x] = r.z[(size_t)y * 1201 + x % 1201];
        t[1].z[y * 2] = t[0].z[y * 12601 + 12600];
        t[1].z[y * 2 + 1] = r.z[(size_t)(y + 2) * 1201];
    }
    CHECK_EQ(dem_merge(t, names, 2, &m, &e), BR_OK);
    if (m.z) { CHECK_EQ(m.w, 12602); CHECK_EQ(m.z[12601], t[1].z[1]); dem_free(&m); }
    /* one column further east: a gap, said as a gap, naming both files */
    t[1].geo.x0 = 49000000000LL + 2 * 555556;
    CHECK_EQ(dem_merge(t, names, 2, &m, &e), BR_E_MERGE);
    CHECK(strstr(e.msg, "gap") != NULL && strstr(e.msg, "east.tif") != NULL);
    /* truly off the grid: names the tile that sets the grid, not itself */
    t[1].geo.x0 = 49000000000LL + 555556 / 2;
    CHECK_EQ(dem_merge(t, names, 2, &m, &e), BR_E_MERGE);
    CHECK_MSG(strstr(e.msg, "east.tif: is not aligned with the sample grid of wide.tif") != NULL, "%s", e.msg);
    free(t[0].z);
    free(t[1].z);
    dem_free(&r);
}

/* ---- 6. XYZ: a far outlier must not merge grid lines ---- */

static void test_xyz_outlier(void)
{
    /* four Monai points on two grid lines each way, and one point far east */
    static const char txt[] = "0 0 0.13535\n0.014 0 0.13465\n0 0.014 0.13535\n0.014 0.014 0.13465\n"
                              "5000 0 0.1\n";
    hf f;
    br_err e;
    br_status s = dem_load_mem("outlier.xyz", (const uint8_t *)txt, sizeof txt - 1, NULL, &f, &e);
    CHECK_MSG(s == BR_E_TOO_BIG, "%s", e.msg);    /* the span in steps, not "given twice" */
    if (s == BR_OK) dem_free(&f);
}

int main(void)
{
    T_RUN(test_png_grey_palette);
    T_RUN(test_coarse_spacing);
    T_RUN(test_geoclaw);
    T_RUN(test_nodata);
    T_RUN(test_merge_prefer);
    T_RUN(test_merge_rounded_step);
    T_RUN(test_xyz_outlier);
    return t_finish();
}
