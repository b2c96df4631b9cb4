/* platform/cmd_hillshade.c — bitrain hillshade IN... -o OUT.png
 *
 * Shaded relief with gdaldem's defaults (azimuth 315, altitude 45, z-factor 1,
 * Horn gradient, byte scale 1..255, 0 for voids), computed by core/shade in
 * integers; geographic grids use their true metres per degree.  Unlike
 * gdaldem's default, edge samples are shaded too (as with -compute_edges).
 * The image is written row by row: memory is the heightfield plus one row. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/shade.h"
#include "platform/cmd.h"
#include "platform/dem_args.h"
#include "platform/opt.h"
#include "platform/hillshade.h"
#include "platform/load.h"
#include "platform/png_io.h"

void hillshade_light(double azimuth_deg, double altitude_deg, fx_q14 l[3])
{
    const double rad = 3.14159265358979323846 / 180.0;
    double az = azimuth_deg * rad, alt = altitude_deg * rad;
    /* azimuth clockwise from north; the vector points towards the light */
    l[0] = (fx_q14)lround(sin(az) * cos(alt) * FX_Q14_ONE);
    l[1] = (fx_q14)lround(cos(az) * cos(alt) * FX_Q14_ONE);
    l[2] = (fx_q14)lround(sin(alt) * FX_Q14_ONE);
}

br_status hillshade_write_png(const hf *f, const fx_q14 l[3], const char *out, br_err *err)
{
    shade_ctx c;
    png_out *po;
    uint8_t *row, *rgb;
    int32_t x, y;
    br_status s;
    if (shade_init(&c, f) != BR_OK) return br_err_set(err, BR_E_ARG, out, "invalid heightfield");
    row = malloc((size_t)f->w * 4);
    if (!row) return br_err_set(err, BR_E_NOMEM, out, "out of memory");
    rgb = row + f->w;
    s = png_out_open(&po, out, f->w, f->h, err);
    for (y = 0; s == BR_OK && y < f->h; y++) {
        shade_hill_row(&c, y, l, row);
        for (x = 0; x < f->w; x++) rgb[3 * x] = rgb[3 * x + 1] = rgb[3 * x + 2] = row[x];
        s = png_out_rows(po, rgb, 1, (size_t)f->w * 3, err);
    }
    if (s == BR_OK) s = png_out_close(po, err);
    else if (po) png_out_abort(po);
    free(row);
    return s;
}

int cmd_hillshade(int argc, char **argv)
{
    const char *out = NULL, *in[64];
    int n = 0, r;
    double az = 315, alt = 45;
    dem_opts o;
    hf f;
    br_err err;
    fx_q14 l[3];
    dem_args da;
    opt_spec dem_t[DEM_ARGS_N];
    const opt_spec own[] = {
        { "-o", OPT_STR, &out, 0, 0, 0, NULL, "OUT.png", "the image to write", NULL },
        { "--azimuth", OPT_NUM, &az, 0, 360, 0, NULL, "DEG", "light from this azimuth, clockwise from north (default 315)", NULL },
        { "--altitude", OPT_NUM, &alt, 0, 90, 0, NULL, "DEG", "light altitude above the horizon (default 45)", NULL },
        OPT_END
    };
    const opt_spec *const tables[] = { own, dem_t, NULL };
    memset(&o, 0, sizeof o);
    dem_args_table(&da, &o, dem_t);
    r = opt_parse("hillshade", "IN... -o OUT.png [options]\n"
                  "  shaded relief (gdaldem defaults: azimuth 315, altitude 45, z-factor 1); adjacent tiles are merged first",
                  tables, argc, argv, in, 64, &n);
    if (r != OPT_OK) return r == OPT_HELP ? 0 : 2;
    if (dem_args_finish(&da, "hillshade") != OPT_OK) return 2;
    if (!n) { fprintf(stderr, "bitrain hillshade: no input file (`bitrain hillshade --help`)\n"); return 2; }
    if (!out) { fprintf(stderr, "bitrain hillshade: no output file: -o OUT.png\n"); return 2; }
    if (dem_load_many(in, n, &o, &f, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); return 1; }
    hillshade_light(az, alt, l);
    if (hillshade_write_png(&f, l, out, &err) != BR_OK) {
        fprintf(stderr, "bitrain: %s\n", err.msg);
        dem_free(&f);
        return 1;
    }
    dem_free(&f);
    if (strcmp(out, "-")) printf("%s\n", out);     /* "-": stdout carries the image only */
    return 0;
}
