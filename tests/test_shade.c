/* tests/test_shade.c — integer hillshade against a double-precision gdaldem
 * formula on real terrain (Lake Constance, N47E009). */
#include <math.h>
#include "tests/test.h"
#include "core/shade.h"
#include "platform/hillshade.h"
#include "platform/load.h"
#include "platform/png_io.h"

static hf lake;
static int have_lake;

/* gdaldem's hillshade (Horn, edges repeated) in double, from the same units. */
static double ref_value(const hf *f, int x, int y, double az, double alt)
{
    double z[3][3], mz = (double)f->z_num / f->z_den, dx = (double)f->dx_um * 1e-6, dy = (double)f->dy_um * 1e-6;
    double gx, gy, nx, ny, nz, len, lx, ly, lz, d;
    int i, j;
    int32_t e = f->z[(size_t)y * f->w + x];
    for (j = -1; j <= 1; j++)
        for (i = -1; i <= 1; i++) {
            int xx = x + i < 0 ? 0 : x + i >= f->w ? f->w - 1 : x + i;
            int yy = y + j < 0 ? 0 : y + j >= f->h ? f->h - 1 : y + j;
            int32_t v = f->z[(size_t)yy * f->w + xx];
            z[j + 1][i + 1] = (v == HF_NODATA ? e : v) * mz;
        }
    gx = ((z[0][2] + 2 * z[1][2] + z[2][2]) - (z[0][0] + 2 * z[1][0] + z[2][0])) / (8 * dx);
    gy = ((z[0][0] + 2 * z[0][1] + z[0][2]) - (z[2][0] + 2 * z[2][1] + z[2][2])) / (8 * dy);
    nx = -gx; ny = -gy; nz = 1;
    len = sqrt(nx * nx + ny * ny + nz * nz);
    az *= 3.14159265358979323846 / 180; alt *= 3.14159265358979323846 / 180;
    lx = sin(az) * cos(alt); ly = cos(az) * cos(alt); lz = sin(alt);
    d = (nx * lx + ny * ly + nz * lz) / len;
    return d <= 0 ? 1 : 1 + 254 * d;
}

static void test_matches_double_formula(void)
{
    shade_ctx c;
    fx_q14 l[3];
    uint8_t *row;
    int x, y, worst = 0, step = getenv("BITRAIN_SANITIZED") ? 7 : 1;
    long n = 0, same = 0;
    if (!have_lake) { CHECK(have_lake); return; }
    CHECK_EQ(shade_init(&c, &lake), BR_OK);
    hillshade_light(315, 45, l);
    row = malloc((size_t)lake.w);
    for (y = 0; y < lake.h; y += step) {
        shade_hill_row(&c, y, l, row);
        for (x = 0; x < lake.w; x++) {
            double r = ref_value(&lake, x, y, 315, 45);
            int d = abs((int)row[x] - (int)lround(r)); /* both rounded to nearest */
            if (d > worst) worst = d;
            if (d == 0) same++;
            n++;
        }
    }
    free(row);
    CHECK_MSG(worst <= 1, "max difference %d over %ld samples", worst, n);
    CHECK_MSG(same * 1000 >= n * 995, "only %ld of %ld samples identical", same, n);
}

/* The largest unit and spacing hf accepts (z_den, dx_um, dy_um = INT32_MAX: the
 * constants' products reach 2^65 before scaling; UBSan run): real heights, and the
 * same values as the double formula. */
static void test_extreme_units(void)
{
    shade_ctx c;
    fx_q14 l[3];
    uint8_t *row;
    hf g;
    int x, worst = 0;
    if (!have_lake) { CHECK(have_lake); return; }
    g = lake;
    g.z_den = INT32_MAX; g.dx_um = INT32_MAX; g.dy_um = INT32_MAX;
    CHECK_EQ(shade_init(&c, &g), BR_OK);
    hillshade_light(315, 45, l);
    row = malloc((size_t)g.w);
    shade_hill_row(&c, g.h / 2, l, row);
    for (x = 0; x < g.w; x++) {
        int d = abs((int)row[x] - (int)lround(ref_value(&g, x, g.h / 2, 315, 45)));
        if (d > worst) worst = d;
    }
    free(row);
    CHECK_MSG(worst <= 1, "max difference %d", worst);
    /* and the other extreme: z_num large, the finest spacing */
    g.z_num = INT32_MAX; g.z_den = 1; g.dx_um = 1; g.dy_um = 1;
    CHECK_EQ(shade_init(&c, &g), BR_OK);
    /* the coarsest spacings (up to 2^37 um, halved below 2^31 first), unequal, with
     * heights large enough that the slopes are not flat: the double formula's values */
    {
        static const int32_t nums[2] = { 10000, INT32_MAX };
        int k;
        for (k = 0; k < 2; k++) {
            g = lake;
            g.z_num = nums[k]; g.z_den = 1;
            g.dx_um = HF_MAX_SPACING_UM; g.dy_um = ((int64_t)1 << 31) + 12345;
            CHECK_EQ(shade_init(&c, &g), BR_OK);
            row = malloc((size_t)g.w);
            shade_hill_row(&c, g.h / 2, l, row);
            worst = 0;
            for (x = 0; x < g.w; x++) {
                int d = abs((int)row[x] - (int)lround(ref_value(&g, x, g.h / 2, 315, 45)));
                if (d > worst) worst = d;
            }
            free(row);
            CHECK_MSG(worst <= 1, "spacing 2^37 um, z_num %d: max difference %d", nums[k], worst);
        }
    }
}

static void test_flat_lake_value(void)
{
    /* Lake Constance is flat at 396 m near (col 300, row 420) of N47E009? find a flat
     * 3x3 window instead of trusting a coordinate: flat ground lit from 45 degrees
     * gives 1 + 254*sin(45) = 180.6 -> 181 (rounded, as gdaldem). */
    shade_ctx c;
    fx_q14 l[3], n[3];
    int x, y, found = 0;
    if (!have_lake) { CHECK(have_lake); return; }
    shade_init(&c, &lake);
    hillshade_light(315, 45, l);
    for (y = 1; y < lake.h - 1 && !found; y++)
        for (x = 1; x < lake.w - 1 && !found; x++) {
            const int32_t *p = lake.z + (size_t)y * lake.w + x;
            int32_t v = p[0];
            if (v == 396 && p[-1] == v && p[1] == v && p[-lake.w] == v && p[lake.w] == v &&
                p[-lake.w - 1] == v && p[-lake.w + 1] == v && p[lake.w - 1] == v && p[lake.w + 1] == v) {
                found = 1;
                CHECK(shade_normal(&c, x, y, n));
                CHECK_EQ(n[0], 0); CHECK_EQ(n[1], 0); CHECK_EQ(n[2], FX_Q14_ONE);
                CHECK_EQ(shade_hill_value(n, l), 181);
            }
        }
    CHECK(found);
}

static void test_png_written(void)
{
    char path[256];
    int w, h;
    uint8_t *rgb;
    br_err err;
    fx_q14 l[3];
    if (!have_lake) { CHECK(have_lake); return; }
    snprintf(path, sizeof path, "%s/hillshade_N47E009.png", t_outdir());
    hillshade_light(315, 45, l);
    CHECK_EQ(hillshade_write_png(&lake, l, path, &err), BR_OK);
    CHECK_EQ(png_read_rgb(path, &w, &h, &rgb, &err), BR_OK);
    CHECK_EQ(w, 1201);
    CHECK_EQ(h, 1201);
    if (rgb) {
        /* north-west corner of the image is the north-west sample: compare row 0 */
        shade_ctx c;
        uint8_t row[1201];
        shade_init(&c, &lake);
        shade_hill_row(&c, 0, l, row);
        CHECK_EQ(rgb[0], row[0]);
        CHECK_EQ(rgb[3 * 1200 + 1], row[1200]);
        free(rgb);
    }
}

int main(void)
{
    br_err err;
    dem_opts o;
    memset(&o, 0, sizeof o);
    have_lake = dem_load(t_data("hgt/N47E009.hgt"), &o, &lake, &err) == BR_OK;
    if (!have_lake) fprintf(stderr, "cannot load: %s\n", err.msg);
    T_RUN(test_matches_double_formula);
    T_RUN(test_flat_lake_value);
    T_RUN(test_extreme_units);
    T_RUN(test_png_written);
    if (have_lake) dem_free(&lake);
    return t_finish();
}
