/* platform/board/spi_band.c — see spi_band.h. */
#include "platform/board/spi_band.h"

enum { C_CASET = 0x2a, C_RASET = 0x2b, C_RAMWR = 0x2c };   /* ST7789V and ILI9341 data sheets */

static void window(spib_put_fn *put, void *user, uint8_t c, int32_t a, int32_t b)
{
    const uint8_t p[4] = { (uint8_t)(a >> 8), (uint8_t)a, (uint8_t)(b >> 8), (uint8_t)b };
    put(user, 0, &c, 1);
    put(user, 1, p, 4);
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
        for (x = 0; x < w; x++) {
            row[2 * x] = (uint8_t)(r[x] >> 8);
            row[2 * x + 1] = (uint8_t)r[x];
        }
        put(user, 1, row, (size_t)w * 2);
    }
}
