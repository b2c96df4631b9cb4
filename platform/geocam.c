/* platform/geocam.c — see geocam.h. */
#include "platform/geocam.h"
#include <math.h>

void geocam_args_table(geocam_args *a, opt_spec t[GEOCAM_ARGS_N])
{
    const opt_spec d[GEOCAM_ARGS_N] = {
        { "--look-from", OPT_NUMS, a->from, -1e6, 1e6, 3, NULL, "LAT,LON,ALT",
          "eye: degrees, degrees, metres above sea level (grids in degrees)", &a->from_seen },
        { "--look-at", OPT_NUMS, a->at, -1e6, 1e6, 3, NULL, "LAT,LON,ALT",
          "point looked at, as --look-from", &a->at_seen },
        OPT_END
    };
    int i;
    a->from_seen = a->at_seen = 0;
    for (i = 0; i < GEOCAM_ARGS_N; i++) t[i] = d[i];
}

int geocam_ok(const scene *s) { return s->f.geo.kind == HF_GEO_DEGREES; }

/* Column and row of the grid at scene (x, y), fractional. */
void geocam_to_deg(const scene *s, double x, double y, double *lat, double *lon)
{
    double col = x * 1e6 / (double)s->f.dx_um, row = (double)(s->f.h - 1) - y * 1e6 / (double)s->f.dy_um;
    *lon = ((double)s->f.geo.x0 + col * (double)s->f.geo.sx) * 1e-9;
    *lat = ((double)s->f.geo.y0 - row * (double)s->f.geo.sy) * 1e-9;
}

void geocam_from_deg(const scene *s, double lat, double lon, double alt, double out[3])
{
    double col = (lon * 1e9 - (double)s->f.geo.x0) / (double)s->f.geo.sx;
    double row = ((double)s->f.geo.y0 - lat * 1e9) / (double)s->f.geo.sy;
    out[0] = col * (double)s->f.dx_um / 1e6;
    out[1] = ((double)(s->f.h - 1) - row) * (double)s->f.dy_um / 1e6;
    out[2] = alt * s->zscale;
}

static int check_point(const scene *s, const char *cmd, const char *opt, const double p[3])
{
    double ext = fmax(s->width_m, s->depth_m);
    if (!(p[0] >= -90 && p[0] <= 90 && p[1] >= -180 && p[1] <= 360))
        return opt_fail(cmd, opt, "%g,%g is not a latitude,longitude in degrees", p[0], p[1]);
    {
        double m[3];
        geocam_from_deg(s, p[0], p[1], p[2], m);
        if (m[0] < -2 * ext || m[0] > 3 * ext || m[1] < -2 * ext || m[1] > 3 * ext) {
            double la0, lo0, la1, lo1;
            geocam_to_deg(s, 0, 0, &la0, &lo0);
            geocam_to_deg(s, s->width_m, s->depth_m, &la1, &lo1);
            return opt_fail(cmd, opt, "%g,%g is far outside the terrain (latitude %.4f..%.4f, longitude %.4f..%.4f)",
                            p[0], p[1], la0, la1, lo0, lo1);
        }
    }
    return 0;
}

int geocam_resolve(const geocam_args *a, const scene *s, const char *cmd, double out[6])
{
    if (!a->from_seen && !a->at_seen) return 0;
    if (!a->from_seen || !a->at_seen)
        return -opt_fail(cmd, a->from_seen ? "--look-from" : "--look-at", "needs %s too",
                         a->from_seen ? "--look-at" : "--look-from");
    if (!geocam_ok(s))
        return -opt_fail(cmd, "--look-from", "the terrain is not georeferenced in degrees (use --camera)");
    if (check_point(s, cmd, "--look-from", a->from) || check_point(s, cmd, "--look-at", a->at)) return -OPT_ERR;
    geocam_from_deg(s, a->from[0], a->from[1], a->from[2], out);
    geocam_from_deg(s, a->at[0], a->at[1], a->at[2], out + 3);
    return 1;
}
