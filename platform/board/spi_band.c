/* platform/board/spi_band.c — see spi_band.h. */
#include "platform/board/spi_band.h"
#include <string.h>

enum { C_CASET = 0x2a, C_RASET = 0x2b, C_RAMWR = 0x2c };   /* ST7789V and ILI9341 data sheets */

static void window(spib_put_fn *put, void *user, uint8_t c, int32_t a, int32_t b)
{
    const uint8_t p[4] = { (uint8_t)(a >> 8), (uint8_t)a, (uint8_t)(b >> 8), (uint8_t)b };
    put(user, 0, &c, 1);
    put(user, 1, p, 4);
}

uint32_t spib_sum(uint32_t h, int *dc_last, int dc, const uint8_t *p, size_t n)
{
    uint32_t prime = 16777619u;     /* FNV's 32-bit prime */
    size_t i;
#if defined(__GNUC__) && defined(__ARM_ARCH_6M__)
    /* a value GCC cannot see, so that it multiplies: for ARMv6-M it turns a multiply by
     * this constant into ten shifts and adds a byte */
    __asm__("" : "+r"(prime));
#endif
    if (dc != *dc_last) {
        h = (h ^ (uint32_t)(0x100 + dc)) * prime;
        *dc_last = dc;
    }
    /* eight bytes a step: one loop test for eight (the same sum) */
    for (i = 0; i + 8 <= n; i += 8) {
        h = (h ^ p[i]) * prime;
        h = (h ^ p[i + 1]) * prime;
        h = (h ^ p[i + 2]) * prime;
        h = (h ^ p[i + 3]) * prime;
        h = (h ^ p[i + 4]) * prime;
        h = (h ^ p[i + 5]) * prime;
        h = (h ^ p[i + 6]) * prime;
        h = (h ^ p[i + 7]) * prime;
    }
    for (; i < n; i++) h = (h ^ p[i]) * prime;
    return h;
}

void spib_band(spib_put_fn *put, void *user, int32_t w, int32_t y0, int32_t rows, const void *px, size_t stride,
               uint8_t *row)
{
    const uint8_t ramwr = C_RAMWR;
    int32_t y, x;
    window(put, user, C_CASET, 0, w - 1);
    window(put, user, C_RASET, y0, y0 + rows - 1);
    put(user, 0, &ramwr, 1);
    for (y = 0; y < rows; y++) {
        const uint16_t *r = (const uint16_t *)(const void *)((const uint8_t *)px + (size_t)y * stride);
        x = 0;
#if defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
        if ((((uintptr_t)r | (uintptr_t)row) & 3) == 0) {
            /* little-endian: two pixels a word, each 16-bit half byte-swapped (the
             * word's bytes reversed, then its halves swapped: REV and a rotate on ARM),
             * stores high, low of the first pixel, then of the second; two words a step */
            const uint8_t *ra = (const uint8_t *)__builtin_assume_aligned(r, 4);
            uint8_t *oa = (uint8_t *)__builtin_assume_aligned(row, 4);
            for (; x + 4 <= w; x += 4) {
                uint32_t v, u;
                memcpy(&v, ra + 2 * x, 4);
                memcpy(&u, ra + 2 * x + 4, 4);
                v = __builtin_bswap32(v); u = __builtin_bswap32(u);
                v = v >> 16 | v << 16; u = u >> 16 | u << 16;
                memcpy(oa + 2 * x, &v, 4);
                memcpy(oa + 2 * x + 4, &u, 4);
            }
        }
#endif
        for (; x < w; x++) {
            row[2 * x] = (uint8_t)(r[x] >> 8);
            row[2 * x + 1] = (uint8_t)r[x];
        }
        put(user, 1, row, (size_t)w * 2);
    }
}
