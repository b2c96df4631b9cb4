/* core/shade.c — see shade.h.
 *
 * Derivation.  Horn, "Hill shading and the reflectance map", Proc. IEEE 69(1),
 * 1981 (the 3x3 weighted gradient gdaldem also uses): gx = (c+2f+i)-(a+2d+g) (east minus west), gy = (a+2b+c)-(g+2h+i)
 * (north minus south), in height units, over a 3x3 window a b c / d e f / g h i
 * with row a b c to the north.  dz/dx = gx*zn*1e6 / (8*zd*dx_um) (unitless), same for y.
 * Multiplying (-dz/dx, -dz/dy, 1) by 8*zd*dx_um*dy_um gives integer components
 * (-gx*zn*1e6*dy_um, -gy*zn*1e6*dx_um, 8*zd*dx_um*dy_um); the three constants
 * are divided by 1e6 and then by a common power of two until each is below 2^24,
 * which keeps 24 bits of the direction and lets gx (|gx| < 2^31 with |z| <= 2^28)
 * times a constant fit int64 with room to spare. */
#include "core/shade.h"

br_status shade_init(shade_ctx *c, const hf *f)
{
    int64_t kx, ky, kz, dx = f->dx_um, dy = f->dy_um;
    int32_t s = 0;
    if (hf_validate(f) != BR_OK) return BR_E_ARG;
    /* Spacings of 2^31 um and more (hf.h allows up to 2^37): the direction is
     * 2^s (zn*dy', zn*dx', 8*zd*dx'*dy' * 2^s / 1e6) with dx = dx' 2^s, dy = dy' 2^s,
     * so the steps below run on dx', dy' < 2^31 and the final division is by
     * 1e6 / 2^s, exact for s <= 6 (1e6 = 2^6 * 15625).  s = 0 for every spacing
     * under 2.1 km, which leaves those constants as they were. */
    while (dx >= ((int64_t)1 << 31) || dy >= ((int64_t)1 << 31)) { dx >>= 1; dy >>= 1; s++; }
    /* Divided by 1e6: (-gx*zn*dy_um, -gy*zn*dx_um, 8*zd*dx_um*dy_um/1e6).
     * kx, ky, zd*dx_um < 2^62 (int32 factors); 8*zd*dx_um would reach 2^65, so
     * zd*dx_um is first halved (kx, ky alike) below 2^59, then kz = 8*zd*dx_um is
     * brought below 2^32 before it is multiplied by dy_um.  (For zd*dx_um < 2^59,
     * every unit the loaders make, the first loop does nothing.) */
    kx = (int64_t)f->z_num * dy;
    ky = (int64_t)f->z_num * dx;
    kz = (int64_t)f->z_den * dx;
    while (kz >= ((int64_t)1 << 59)) { kx = (kx + 1) >> 1; ky = (ky + 1) >> 1; kz = (kz + 1) >> 1; }
    kz *= 8;
    while (kz >= ((int64_t)1 << 32)) { kx = (kx + 1) >> 1; ky = (ky + 1) >> 1; kz = (kz + 1) >> 1; }
    kz = kz * dy;
    /* keep precision through the division: scale all three up while they are small */
    while (kz < ((int64_t)1 << 52) && kx < ((int64_t)1 << 52) && ky < ((int64_t)1 << 52)) {
        kx <<= 1; ky <<= 1; kz <<= 1;
    }
    kz /= 1000000 >> s;
    if (kz < 1) kz = 1;
    while (kx >= ((int64_t)1 << 24) || ky >= ((int64_t)1 << 24) || kz >= ((int64_t)1 << 24)) {
        kx = (kx + 1) >> 1; ky = (ky + 1) >> 1; kz = (kz + 1) >> 1;
    }
    c->f = f; c->kx = kx; c->ky = ky; c->kz = kz;
    return BR_OK;
}

static int32_t at(const hf *f, int32_t x, int32_t y, int32_t centre)
{
    int32_t z;
    if (x < 0) x = 0;
    if (x >= f->w) x = f->w - 1;
    if (y < 0) y = 0;
    if (y >= f->h) y = f->h - 1;
    z = f->z[(size_t)y * (size_t)f->w + (size_t)x];
    return z == HF_NODATA ? centre : z;
}

int shade_normal(const shade_ctx *c, int32_t x, int32_t y, fx_q14 n[3])
{
    const hf *f = c->f;
    int32_t e = f->z[(size_t)y * (size_t)f->w + (size_t)x];
    int64_t a, b, cc, d, ff, g, h, i, gx, gy, v[3], m;
    uint64_t len;
    int k, sh = 0;
    n[0] = 0; n[1] = 0; n[2] = FX_Q14_ONE;
    if (e == HF_NODATA) return 0;
    a = at(f, x - 1, y - 1, e); b = at(f, x, y - 1, e); cc = at(f, x + 1, y - 1, e);
    d = at(f, x - 1, y, e);                             ff = at(f, x + 1, y, e);
    g = at(f, x - 1, y + 1, e); h = at(f, x, y + 1, e); i = at(f, x + 1, y + 1, e);
    gx = (cc + 2 * ff + i) - (a + 2 * d + g);
    gy = (a + 2 * b + cc) - (g + 2 * h + i);
    v[0] = -gx * c->kx;
    v[1] = -gy * c->ky;
    v[2] = c->kz;
    m = 0;
    for (k = 0; k < 3; k++) { int64_t t = v[k] < 0 ? -v[k] : v[k]; if (t > m) m = t; }
    while ((m >> sh) >= ((int64_t)1 << 30)) sh++;
    for (k = 0; k < 3; k++) v[k] >>= sh;
    len = fx_isqrt64((uint64_t)(v[0] * v[0]) + (uint64_t)(v[1] * v[1]) + (uint64_t)(v[2] * v[2]));
    if (len == 0) return 0;
    for (k = 0; k < 3; k++) {
        /* rounded to nearest, halves away from zero; |v[k]| <= len, so the quotient
         * is at most 2^14 and |q| + len / 2 < len 2^15: 15 quotient bits (no 64-bit
         * divide on 32-bit targets, where a vertex's first frame computes this) */
        n[k] = (fx_q14)fx_div_round_bits(v[k] * FX_Q14_ONE, (int64_t)len, 15);
    }
    return 1;
}

uint8_t shade_hill_value(const fx_q14 n[3], const fx_q14 l[3])
{
    int64_t dot = (int64_t)n[0] * l[0] + (int64_t)n[1] * l[1] + (int64_t)n[2] * l[2]; /* Q28 */
    if (dot <= 0) return 1;
    dot = 1 + ((254 * dot + ((int64_t)1 << 27)) >> 28); /* rounded, as gdaldem's byte output */
    return (uint8_t)(dot > 255 ? 255 : dot);
}

void shade_hill_row(const shade_ctx *c, int32_t y, const fx_q14 l[3], uint8_t *out)
{
    int32_t x;
    fx_q14 n[3];
    for (x = 0; x < c->f->w; x++)
        out[x] = shade_normal(c, x, y, n) ? shade_hill_value(n, l) : 0;
}
