/* raster/ramp.h — per-vertex colour for terrain: a hypsometric colour ramp (the
 * integer form of a gdaldem color-relief file) times Lambert lighting from a sun
 * direction with an ambient term.  Integer only.
 *
 * Ramp: up to RS_RAMP_MAX entries sorted by elevation in millimetres, colour
 * linearly interpolated between entries (gdaldem's default interpolation),
 * clamped to the first/last entry outside their range; an optional nodata colour.
 * Parsing the text file (`elevation r g b [a]`, `nv r g b`, percentages) lives in
 * platform/ (platform/cmd_render.c), which fills this table.
 * Lighting: rgb * (ambient + (1 - ambient) * max(0, n.L)), n and L Q14 unit vectors
 * (n from core/shade.h, Horn normals in real units), ambient Q14; rounded to nearest. */
#ifndef BR_RAMP_H
#define BR_RAMP_H
#include <stdint.h>
#include "core/fx.h"

#define RS_RAMP_MAX 64

typedef struct rs_ramp {
    int32_t n;                       /* entries, 1 .. RS_RAMP_MAX */
    int64_t z_mm[RS_RAMP_MAX];       /* ascending */
    uint32_t rgb[RS_RAMP_MAX];       /* 0xRRGGBB */
    int32_t has_nv;
    uint32_t nv_rgb;
} rs_ramp;

/* The built-in ramp over [zmin_mm, zmax_mm]: green lowlands, tan and brown slopes,
 * grey rock, white peaks; with a blue bathymetry part below 0 when zmin < 0. */
void rs_ramp_default(rs_ramp *r, int64_t zmin_mm, int64_t zmax_mm);

/* The built-in ramp by absolute elevation, for georeferenced terrain: sea-floor blues
 * below 0 m, lowland green from 0 m, pale green to 600 m, tan to 1,200 m, brown to
 * 1,800 m, grey rock from 2,200 m, snow from 2,700 m (white at 3,200 m): snow only
 * high up, whatever the file's maximum. */
void rs_ramp_absolute(rs_ramp *r);

/* Colour 0xRRGGBB at elevation z_mm. */
uint32_t rs_ramp_rgb(const rs_ramp *r, int64_t z_mm);

/* Sun direction (towards the sun) from azimuth (clockwise from north) and altitude,
 * millidegrees, as a Q14 unit vector (x east, y north, z up). */
void rs_sun_dir(int32_t az_mdeg, int32_t alt_mdeg, fx_q14 out[3]);

/* rgb lit by normal n under sun l with ambient (Q14, 0 .. FX_Q14_ONE):
 * rs_light_apply(rgb, rs_light_level(n, l, ambient_q14)). */
uint32_t rs_light_rgb(uint32_t rgb, const fx_q14 n[3], const fx_q14 l[3], int32_t ambient_q14);
/* The light level ambient + (1 - ambient) max(0, n.L), Q14: 0 .. FX_Q14_ONE + 1 (the
 * components of n and L are rounded to Q14, so n.L may exceed 2^28 by 2^15 at most,
 * and d >> 14 then exceeds 2^14 by 1 at most). */
int32_t rs_light_level(const fx_q14 n[3], const fx_q14 l[3], int32_t ambient_q14);
/* rgb times a light level (Q14, 0 .. FX_Q14_ONE + 1 as rs_light_level gives), each
 * channel rounded: 255 L + 2^13 < 256 * 2^14 for L <= 2^14 + 32, so a channel stays
 * at most 255 without a clamp. */
static inline uint32_t rs_light_apply(uint32_t rgb, int32_t level_q14)
{
    uint32_t l = (uint32_t)level_q14;
    return ((((rgb >> 16) & 255u) * l + (1u << 13)) >> 14) << 16 |
           ((((rgb >> 8) & 255u) * l + (1u << 13)) >> 14) << 8 |
           (((rgb & 255u) * l + (1u << 13)) >> 14);
}

#endif
