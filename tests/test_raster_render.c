/* tests/test_raster_render.c — `bitrain render` end to end on real terrain (N47E009):
 * exit codes, a gdaldem colour-relief file (entries, nv, percentages, comments) and its
 * errors, bands giving the same PNG as the whole frame, RGB565 output, a texture. */
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/png_io.h"

#define RUN(a) run(a, (int)(sizeof a / sizeof a[0]))
static int run(const char *const *args, int n)
{
    char *argv[32];
    int i;
    for (i = 0; i < n; i++) argv[i] = (char *)args[i];
    return cmd_render(n, argv);
}

/* Counts pixels that are not the sky (0x99ccff) and, among them, those whose red
 * channel dominates. */
static void count_px(const char *path, int *terrain, int *reddish)
{
    int w, h, i;
    uint8_t *rgb = NULL;
    br_err err;
    *terrain = *reddish = -1;
    if (png_read_rgb(path, &w, &h, &rgb, &err) != BR_OK) return;
    *terrain = *reddish = 0;
    for (i = 0; i < w * h; i++) {
        const uint8_t *p = rgb + 3 * i;
        if (p[0] == 0x99 && p[1] == 0xcc && p[2] == 0xff) continue;
        (*terrain)++;
        if (p[0] > p[1] + 20 && p[0] > p[2] + 20) (*reddish)++;
    }
    free(rgb);
}

static void test_render_cli(void)
{
    char out1[256], out2[256], out3[256], col[256], bad[256];
    const char *dem = t_data("hgt/N47E009.hgt");
    int terrain, red;
    size_t n1 = 0, n2 = 0;
    unsigned char *b1, *b2;
    snprintf(out1, sizeof out1, "%s/render_full.png", t_outdir());
    snprintf(out2, sizeof out2, "%s/render_bands.png", t_outdir());
    snprintf(out3, sizeof out3, "%s/render_colors.png", t_outdir());
    snprintf(col, sizeof col, "%s/render_colors.txt", t_outdir());
    snprintf(bad, sizeof bad, "%s/render_bad_colors.txt", t_outdir());
    {   /* the default mesh (bitree, 1 px), whole frame vs bands of 7 rows, RGB565 */
        const char *a[] = { dem, "-o", out1, "--size", "96x64", "--format", "rgb565" };
        const char *b[] = { dem, "-o", out2, "--size", "96x64", "--format", "rgb565", "--bands", "7" };
        CHECK_EQ(RUN(a), 0);
        CHECK_EQ(RUN(b), 0);
        b1 = t_read_file(out1, &n1);
        b2 = t_read_file(out2, &n2);
        CHECK(b1 && b2 && n1 == n2 && n1 > 0 && !memcmp(b1, b2, n1));
        free(b1); free(b2);
        count_px(out1, &terrain, &red);
        CHECK(terrain > 96 * 64 / 5);
    }
    {   /* colour file: everything red except a blue top (percentages, comments, nv); the
         * plain sky and no water or fog, which this count reads (test_water.c has them) */
        const char txt[] = "# test ramp\n0 200 0 0\n50% 220,10,10\n100% 0 0 255 255\nnv 0 0 0\n";
        const char *a[] = { dem, "-o", out3, "--size", "96x64", "--colors", col, "--full", "8", "--ambient", "1",
                            "--no-water", "--no-fog" };
        CHECK(t_write_file(col, txt, sizeof txt - 1));
        CHECK_EQ(RUN(a), 0);
        count_px(out3, &terrain, &red);
        CHECK(terrain > 96 * 64 / 5);
        CHECK_MSG(red > terrain / 2, "%d of %d terrain pixels reddish", red, terrain);
    }
    {   /* errors: unreadable or malformed colour file -> 1; bad option -> 2 */
        const char txt[] = "100 20 30\n";
        const char *a[] = { dem, "-o", out3, "--size", "32x24", "--colors", bad, "--full", "8" };
        const char *m[] = { dem, "-o", out3, "--size", "32x24", "--colors", "tests/out/no_such.txt", "--full", "8" };
        const char *o[] = { dem, "-o", out3, "--bogus" };
        const char *s[] = { dem, "-o", out3, "--size", "0x10" };
        CHECK(t_write_file(bad, txt, sizeof txt - 1));
        CHECK_EQ(RUN(a), 1);
        CHECK_EQ(RUN(m), 1);
        CHECK_EQ(RUN(o), 2);
        CHECK_EQ(RUN(s), 2);
    }
    {   /* a texture (the golden test's own PNG stands in for an orthophoto) */
        const char *a[] = { dem, "-o", out3, "--size", "64x48", "--texture", "tests/golden/raster_n47e009_161x121.png",
                            "--full", "8", "--camera", "30000,20000,9000,40000,60000,500" };
        CHECK_EQ(RUN(a), 0);
        count_px(out3, &terrain, &red);
        CHECK(terrain > 64 * 48 / 5);
    }
}

int main(void)
{
    T_RUN(test_render_cli);
    return t_finish();
}
