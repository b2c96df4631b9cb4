/* raster/ramp.c — hypsometric ramp and lighting (see ramp.h). */
#include "raster/ramp.h"

void rs_ramp_default(rs_ramp *r, int64_t zmin_mm, int64_t zmax_mm)
{
    /* land part in 1/1000 of [max(zmin, 0), zmax] */
    static const int32_t pos[] = { 0, 150, 350, 550, 750, 900, 1000 };
    static const uint32_t col[] = { 0x3c7a3cu, 0x5a9646u, 0x9aa760u, 0xb49a6eu, 0x8c7460u, 0xbdbdbdu, 0xffffffu };
    int64_t lo = zmin_mm > 0 ? zmin_mm : 0, hi = zmax_mm > lo ? zmax_mm : lo + 1;
    int32_t i, k = 0;
    if (zmin_mm < 0) {   /* bathymetry: deep blue to light blue at the shore */
        r->z_mm[k] = zmin_mm; r->rgb[k++] = 0x1a3c78u;
        r->z_mm[k] = -1;      r->rgb[k++] = 0x5a96c8u;
    }
    for (i = 0; i < 7; i++) {
        r->z_mm[k] = lo + (hi - lo) * pos[i] / 1000;
        r->rgb[k++] = col[i];
    }
    r->n = k;
    r->has_nv = 1;
    r->nv_rgb = 0x000000u;
}

void rs_ramp_absolute(rs_ramp *r)
{
    static const int32_t z_m[] = { -6000, -200, -1, 0, 250, 600, 1200, 1800, 2200, 2700, 3200 };
    static const uint32_t col[] = { 0x0c2a5au, 0x1a4a82u, 0x5a96c8u, 0x4f8a48u, 0x6e9e50u, 0x9aa764u,
                                    0xb49a6eu, 0x8c7460u, 0x8e8a86u, 0xd8d8d8u, 0xffffffu };
    int32_t i;
    for (i = 0; i < (int32_t)(sizeof z_m / sizeof z_m[0]); i++) {
        r->z_mm[i] = (int64_t)z_m[i] * 1000;
        r->rgb[i] = col[i];
    }
    r->n = i;
    r->has_nv = 1;
    r->nv_rgb = 0x000000u;
}

uint32_t rs_ramp_rgb(const rs_ramp *r, int64_t z_mm)
{
    int32_t i;
    if (r->n <= 0) return 0x808080u;
    if (z_mm <= r->z_mm[0]) return r->rgb[0];
    for (i = 1; i < r->n; i++) {
        if (z_mm <= r->z_mm[i]) {
            int64_t z0 = r->z_mm[i - 1], z1 = r->z_mm[i], t, out = 0;
            int k;
            /* t in Q16; (z - z0) < 2^48 for any sane elevation so the product fits */
            /* 0 < z - z0 <= z1 - z0: t <= 2^16, 17 quotient bits (no 64-bit divide
             * on 32-bit targets, where this runs per vertex per frame) */
#if BR_DIV64_NATIVE
            t = z1 > z0 ? ((z_mm - z0) << 16) / (z1 - z0) : 65536;
#else
            t = z1 > z0 ? (int64_t)fx_udiv_bits((uint64_t)(z_mm - z0) << 16, (uint64_t)(z1 - z0), 17) : 65536;
#endif
            for (k = 16; k >= 0; k -= 8) {
                int64_t c0 = (r->rgb[i - 1] >> k) & 255, c1 = (r->rgb[i] >> k) & 255;
                int64_t c = c0 + (((c1 - c0) * t + 32768) >> 16);
                out |= c << k;
            }
            return (uint32_t)out;
        }
    }
    return r->rgb[r->n - 1];
}

void rs_sun_dir(int32_t az_mdeg, int32_t alt_mdeg, fx_q14 out[3])
{
    fx_q30 sa, ca, se, ce;
    fx_sincos(fx_angle_from_mdeg(az_mdeg), &sa, &ca);
    fx_sincos(fx_angle_from_mdeg(alt_mdeg), &se, &ce);
    out[0] = (fx_q14)(((int64_t)sa * ce + ((int64_t)1 << 45)) >> 46);
    out[1] = (fx_q14)(((int64_t)ca * ce + ((int64_t)1 << 45)) >> 46);
    out[2] = (fx_q14)((se + (1 << 15)) >> 16);
}

int32_t rs_light_level(const fx_q14 n[3], const fx_q14 l[3], int32_t ambient_q14)
{
    int64_t d = (int64_t)n[0] * l[0] + (int64_t)n[1] * l[1] + (int64_t)n[2] * l[2]; /* Q28 */
    if (d < 0) d = 0;
    /* ambient + (1 - ambient) * d, Q14 (ramp.h: at most FX_Q14_ONE + 1) */
    return (int32_t)(ambient_q14 + ((((int64_t)FX_Q14_ONE - ambient_q14) * (d >> 14) + (1 << 13)) >> 14));
}

uint32_t rs_light_rgb(uint32_t rgb, const fx_q14 n[3], const fx_q14 l[3], int32_t ambient_q14)
{
    return rs_light_apply(rgb, rs_light_level(n, l, ambient_q14));
}
