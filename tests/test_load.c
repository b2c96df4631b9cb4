/* tests/test_load.c — every real file in ../shared/data/dem through the loaders:
 * dimensions, units, min/max, voids, spacing and georeference, and merging. */
#include "tests/test.h"
#include "platform/load.h"
#include "platform/merge.h"

static void expect(const char *rel, const dem_opts *o, int w, int h, int num, int den,
                   long long zmin, long long zmax, long long voids)
{
    hf f;
    hf_stats st;
    br_err e;
    br_status s = dem_load(t_data(rel), o, &f, &e);
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

static void test_hgt(void)
{
    expect("hgt/N47E009.hgt", NULL, 1201, 1201, 1, 1, 388, 2937, 0);
    expect("hgt/N50E008.hgt", NULL, 1201, 1201, 1, 1, 62, 885, 50);
    expect("hgt/N50E009.hgt", NULL, 1201, 1201, 1, 1, 98, 950, 12);
    expect("hgt/N50E010.hgt", NULL, 1201, 1201, 1, 1, 185, 983, 28);
    expect("hgt/N57E011.hgt", NULL, 1201, 1201, 1, 1, -6, 163, 0);
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

int main(void)
{
    T_RUN(test_hgt);
    T_RUN(test_hgt_geo);
    T_RUN(test_merge_n50);
    T_RUN(test_merge_errors);
    return t_finish();
}
