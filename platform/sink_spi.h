/* platform/sink_spi.h — a band sink (raster.h's rs_sink) for small SPI panels driven
 * by an ST7789 or ILI9341 controller: each finished band goes out as a window (CASET,
 * RASET), RAMWR and its pixels in RGB565, high byte first, so a board with such a panel
 * and no framebuffer shows the frame as it is drawn, one band in RAM at a time.
 *
 * THE BYTE STREAM (what spi_sink_open and spi_sink_band write, through spi_writer)
 *   open:  SWRESET (0x01), wait 150 ms; SLPOUT (0x11), wait 120 ms; COLMOD (0x3a) 0x55
 *          (16 bits a pixel); MADCTL (0x36) m; ST7789 only: INVON (0x21) (the IPS panels
 *          sold with it are inverted); NORON (0x13); DISPON (0x29), wait 20 ms.
 *   band:  CASET (0x2a) x0 >> 8, x0 & 255, x1 >> 8, x1 & 255 (x0 = 0, x1 = w - 1);
 *          RASET (0x2b) the same with the band's rows y0 .. y0 + rows - 1;
 *          RAMWR (0x2c); then rows * w pixels, left to right, top to bottom, each
 *          RGB565 high byte first.  XRGB8888 bands are packed to RGB565 by truncation
 *          (the top 5, 6, 5 bits: what the rasteriser's own RGB565 variant stores).
 *   Commands go with the D/C line low, their parameters and pixels with it high
 *   (spi_writer.write's dc argument).
 * MADCTL m: frames wider than tall are landscape (row/column exchange, MV): ST7789
 * 0x60 (MX | MV) landscape, 0x00 portrait; ILI9341 0x28 (MV | BGR) landscape, 0x48
 * (MX | BGR) portrait (the usual modules' wiring; spi_panel_cfg.madctl overrides).
 * Frame sizes: at most 240 x 320 portrait or 320 x 240 landscape (the controllers' RAM).
 *
 * On Linux, spi_linux_open makes a writer for /dev/spidevB.C (spidev) with the D/C line
 * (and optionally RESET) on a GPIO character device line (/dev/gpiochipN).  Tests use
 * their own writer and decode the stream (tests/test_spi.c). */
#ifndef BR_SINK_SPI_H
#define BR_SINK_SPI_H
#include <stddef.h>
#include <stdint.h>
#include "platform/err.h"

enum { SPI_PANEL_ST7789 = 1, SPI_PANEL_ILI9341 = 2 };

/* Where the bytes go.  write: n bytes, dc 0 = command (D/C low), 1 = parameters or
 * pixels (D/C high); wait_ms: a pause the controller needs (NULL: none).  Both return
 * BR_OK or fill err. */
typedef struct spi_writer {
    br_status (*write)(void *user, int dc, const uint8_t *p, size_t n, br_err *err);
    br_status (*wait_ms)(void *user, int ms, br_err *err);
    void *user;
} spi_writer;

/* Panel name ("st7789", "ili9341") to SPI_PANEL_*; 0 when unknown. */
int spi_panel_parse(const char *name);

typedef struct spi_sink {
    spi_writer wr;
    int32_t panel;              /* SPI_PANEL_* */
    int32_t w, h, fmt;          /* frame size, RS_FMT_* of the bands */
    int32_t madctl;             /* -1: the panel's default for the frame's orientation */
    uint8_t *row;               /* 2 w bytes (spi_sink_open allocates, spi_sink_close frees) */
    br_err *err;                /* where spi_sink_band reports a failed write */
} spi_sink;

/* Checks the size against the panel, allocates the row buffer and writes the panel's
 * start-up sequence.  BR_E_ARG (size, panel, format), BR_E_NOMEM, or the writer's error. */
br_status spi_sink_open(spi_sink *s, const spi_writer *wr, int32_t panel, int32_t w, int32_t h, int32_t fmt,
                        int32_t madctl, br_err *err);
/* The rs_sink: user is the spi_sink. */
br_status spi_sink_band(void *user, int32_t y0, int32_t rows, const void *pixels, size_t stride);
void spi_sink_close(spi_sink *s);

/* A writer on Linux spidev: dev "/dev/spidev0.0", hz the clock, mode 0 .. 3 (SPI_MODE_*),
 * dc and rst "/dev/gpiochip0:25" (chip path, colon, line offset; rst may be NULL: no
 * reset line).  The writer is freed by spi_linux_close.  BR_E_IO naming the device or
 * line that cannot be opened or set; BR_E_UNSUPPORTED off Linux. */
br_status spi_linux_open(spi_writer *wr, const char *dev, uint32_t hz, int mode, const char *dc, const char *rst,
                         br_err *err);
void spi_linux_close(spi_writer *wr);

/* A writer into a file, for looking at the stream without a panel (`--spi-capture`):
 * records of one kind byte ('C' command, 'D' data, 'W' wait), a 4-byte little-endian
 * length and the bytes (for 'W': the milliseconds as 4 little-endian bytes). */
br_status spi_capture_open(spi_writer *wr, const char *path, br_err *err);
br_status spi_capture_close(spi_writer *wr, br_err *err);

#endif
