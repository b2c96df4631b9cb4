/* platform/board/spi_band.h — the band byte stream of platform/sink_spi.h (ST7789 /
 * ILI9341: CASET, RASET, RAMWR, then the band's RGB565 pixels high byte first) for a
 * board with no C library: the same bytes, handed to a put function instead of a
 * spi_writer, from RGB565 bands only.  The desktop build of the board main checks every
 * band against spi_sink_band itself (platform/board/desktop_main.c). */
#ifndef BR_BOARD_SPI_BAND_H
#define BR_BOARD_SPI_BAND_H
#include <stddef.h>
#include <stdint.h>

/* n bytes, dc 0 = command (D/C low), 1 = parameters or pixels */
typedef void spib_put_fn(void *user, int dc, const uint8_t *p, size_t n);

/* Writes band rows [y0, y0 + rows) of a w-wide RGB565 frame (px: rows of w pixels,
 * stride bytes apart) with row (2 w bytes) as the pixel row buffer. */
void spib_band(spib_put_fn *put, void *user, int32_t w, int32_t y0, int32_t rows, const void *px, size_t stride,
               uint8_t *row);

/* The stream's checksum: FNV-1a (32 bits) over its bytes, and over 0x100 + dc wherever
 * the D/C level changes (*dc_last: the level of the previous byte, -1 before the
 * first), so it does not depend on how the stream is cut into writes.  Start from
 * SPIB_SUM_INIT with *dc_last = -1. */
#define SPIB_SUM_INIT 2166136261u
uint32_t spib_sum(uint32_t h, int *dc_last, int dc, const uint8_t *p, size_t n);

#endif
