/* platform/cmd_info.c — bitrain info: size, heights, voids, spacing and
 * origin of elevation files (or of their merge), as text or JSON lines.
 * Heights are printed in metres exactly (our units are n/2^a5^b metres). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "platform/cmd.h"
#include "platform/dem_args.h"
#include "platform/opt.h"
#include "platform/load.h"
#include "core/bitree.h"

#define INFO_SYNOPSIS "[options] FILE..."

/* z * num / den metres as an exact decimal when den divides a power of ten <= 10^9 */
static void fmt_m(char *buf, size_t bn, int64_t z, int32_t num, int32_t den)
{
    int64_t p10 = 1, v, ip, fp;
    int k;
    for (k = 0; k <= 9; k++, p10 *= 10) {
        if ((int64_t)num * p10 % den == 0) break;
    }
    if (k > 9) { snprintf(buf, bn, "%.9g", (double)z * num / den); return; }
    v = z * ((int64_t)num * p10 / den);
    ip = (v < 0 ? -v : v) / p10;
    fp = (v < 0 ? -v : v) % p10;
    if (k == 0 || fp == 0) { snprintf(buf, bn, "%s%lld", v < 0 ? "-" : "", (long long)ip); return; }
    while (fp % 10 == 0) { fp /= 10; k--; }
    snprintf(buf, bn, "%s%lld.%0*lld", v < 0 ? "-" : "", (long long)ip, k, (long long)fp);
}

static void json_str(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') printf("\\%c", c);
        else if (c < 0x20) printf("\\u%04x", c);
        else putchar(c);
    }
    putchar('"');
}

static void report(const char *label, const hf *f, int json, int64_t filled)
{
    hf_stats st;
    char mn[48], mx[48], unit[48];
    const char *kind = f->geo.kind == HF_GEO_DEGREES ? "degrees" : f->geo.kind == HF_GEO_PROJECTED ? "projected" : "none";
    double gs = f->geo.kind == HF_GEO_DEGREES ? 1e-9 : 1e-6;
    hf_stats_get(f, &st);
    fmt_m(mn, sizeof mn, st.zmin, f->z_num, f->z_den);
    fmt_m(mx, sizeof mx, st.zmax, f->z_num, f->z_den);
    fmt_m(unit, sizeof unit, 1, f->z_num, f->z_den);
    if (json) {
        int all_void = st.voids == (int64_t)f->w * f->h;
        printf("{\"file\":");
        json_str(label);
        printf(",\"width\":%d,\"height\":%d,\"min\":%s,\"max\":%s,\"voids\":%lld,"
               "\"unit\":%s,\"z_num\":%d,\"z_den\":%d,\"spacing\":{\"dx\":%.6f,\"dy\":%.6f},"
               "\"origin\":{\"kind\":\"%s\"",
               f->w, f->h, all_void ? "null" : mn, all_void ? "null" : mx, (long long)st.voids, unit,
               f->z_num, f->z_den, (double)f->dx_um * 1e-6, (double)f->dy_um * 1e-6, kind);
        if (f->geo.kind != HF_GEO_NONE)
            printf(",\"x\":%.9f,\"y\":%.9f,\"sx\":%.9f,\"sy\":%.9f", (double)f->geo.x0 * gs,
                   (double)f->geo.y0 * gs, (double)f->geo.sx * gs, (double)f->geo.sy * gs);
        printf("}");
        if (filled >= 0) printf(",\"filled\":%lld", (long long)filled);
        printf("}\n");
        return;
    }
    printf("%s: %dx%d samples\n", label, f->w, f->h);
    if (st.voids == (int64_t)f->w * f->h) printf("  heights: all void\n");
    else printf("  heights: %s .. %s m (kept in units of %s m)\n", mn, mx, unit);
    printf("  voids:   %lld\n", (long long)st.voids);
    if (filled >= 0) printf("  filled:  %lld voids (--fill-voids: inverse-distance mean of the border)\n", (long long)filled);
    printf("  spacing: %.6f x %.6f m\n", (double)f->dx_um * 1e-6, (double)f->dy_um * 1e-6);
    if (f->geo.kind == HF_GEO_DEGREES)
        printf("  origin:  sample (0,0) centre at lon %.9f, lat %.9f; step %.9f x %.9f degrees\n",
               (double)f->geo.x0 * gs, (double)f->geo.y0 * gs, (double)f->geo.sx * gs, (double)f->geo.sy * gs);
    else if (f->geo.kind == HF_GEO_PROJECTED)
        printf("  origin:  sample (0,0) centre at x %.6f, y %.6f m; step %.6f x %.6f m\n",
               (double)f->geo.x0 * gs, (double)f->geo.y0 * gs, (double)f->geo.sx * gs, (double)f->geo.sy * gs);
    else printf("  origin:  none (no georeference in the file)\n");
    if (f->w >= 2 && f->h >= 2) {
        double tb = (double)bt_mem_size(f->w, f->h), sb = (double)bt_scratch_size(f->w, f->h);
        printf("  bitree:  %.2f MB, %.2f bytes a sample (build scratch %.2f MB)\n", tb / 1e6,
               tb / ((double)f->w * f->h), sb / 1e6);
    }
}

int cmd_info(int argc, char **argv)
{
    dem_opts o;
    int json = 0, merge = 0, i, nf = 0, rc = 0, r;
    int64_t filled = 0;
    const char **files = calloc((size_t)(argc > 0 ? argc : 1), sizeof *files);
    dem_args da;
    opt_spec dem_t[DEM_ARGS_N];
    const opt_spec own[] = {
        { "--json", OPT_FLAG, &json, 0, 0, 0, NULL, NULL, "one JSON object per file (or per merge) per line", NULL },
        { "--merge", OPT_FLAG, &merge, 0, 0, 0, NULL, NULL, "merge the files by georeference and report the result", NULL },
        { "--depth", OPT_FLAG, &o.xyz_depth, 0, 0, 0, NULL, NULL, "same as --xyz-depth", NULL },
        OPT_END
    };
    const opt_spec *const tables[] = { own, dem_t, NULL };
    memset(&o, 0, sizeof o);
    o.filled_out = &filled;
    if (!files) { fprintf(stderr, "bitrain info: out of memory\n"); return 1; }
    dem_args_table(&da, &o, dem_t);
    r = opt_parse("info", INFO_SYNOPSIS, tables, argc, argv, files, argc > 0 ? argc : 1, &nf);
    if (r != OPT_OK) { free(files); return r == OPT_HELP ? 0 : 2; }
    if (dem_args_finish(&da, "info") != OPT_OK) { free(files); return 2; }
    if (nf == 0) { fprintf(stderr, "bitrain info: no input file (`bitrain info --help`)\n"); free(files); return 2; }
    if (merge) {
        hf f;
        br_err e;
        if (dem_load_many(files, nf, &o, &f, &e) != BR_OK) {
            fprintf(stderr, "bitrain info: %s\n", e.msg);
            rc = 1;
        } else {
            report(nf == 1 ? files[0] : "merged", &f, json, o.fill_voids ? filled : -1);
            dem_free(&f);
        }
    } else {
        for (i = 0; i < nf; i++) {
            hf f;
            br_err e;
            if (dem_load_many(&files[i], 1, &o, &f, &e) != BR_OK) {
                fprintf(stderr, "bitrain info: %s\n", e.msg);
                rc = 1;
                continue;
            }
            report(files[i], &f, json, o.fill_voids ? filled : -1);
            dem_free(&f);
        }
    }
    free(files);
    return rc;
}
