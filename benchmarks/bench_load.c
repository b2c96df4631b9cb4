/* benchmarks/bench_load.c — load time of every real DEM (median of 9 loads)
 * and of the three-tile N50 merge.  Prints figures; never fails on time.
 * Run from the repo root: build/bench/bench_load (make bench runs it). */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "platform/load.h"
#include "tests/support/timing.h"
#include "tests/test.h"

#define RUNS 9

static void bench(const char *label, const char *const *paths, int n)
{
    double t[RUNS];
    int k;
    for (k = 0; k < RUNS; k++) {
        hf f;
        br_err e;
        double t0 = tm_now_ms();
        if (dem_load_many(paths, n, NULL, &f, &e) != BR_OK) { printf("%-34s error: %s\n", label, e.msg); return; }
        t[k] = tm_now_ms() - t0;
        if (k == 0) printf("%-34s %5dx%-5d ", label, f.w, f.h);
        dem_free(&f);
    }
    {
        double med = tm_median(t, RUNS);   /* sorts t: t[0] is then the minimum */
        printf("median %8.2f ms  (min %.2f)\n", med, t[0]);
    }
}

int main(void)
{
    static const char *const files[] = {
        "hgt/N47E009.hgt", "png/ps_height_1k.png", "png/fuji.png", "asc/colorado_front_range.asc",
        "asc/hugo_site.asc", "bt/crater_0513.bt", "tif/mt_rainier_90m.tif", "xyz/monai_valley_bathymetry.txt"
    };
    const char *p[3];
    size_t i;
    for (i = 0; i < sizeof files / sizeof files[0]; i++) {
        p[0] = t_data(files[i]);
        bench(files[i], p, 1);
    }
    p[0] = "assets/N47E009.hgt.gz";
    bench(p[0], p, 1);
    p[0] = t_data("hgt/N50E008.hgt");
    p[1] = t_data("hgt/N50E009.hgt");
    p[2] = t_data("hgt/N50E010.hgt");
    bench("merge N50E008+N50E009+N50E010", p, 3);
    return 0;
}
