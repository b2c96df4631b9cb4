/* platform/sink_rgb565.h — the raw RGB565 sink: a frame as the byte stream an SPI display
 * (ST7789, ILI9341 and the like in their 16-bit colour mode) takes: rows top to bottom,
 * w pixels a row, each pixel two bytes, big-endian (RRRRRGGG GGGBBBBB), nothing else (no
 * header: the receiver knows w and h).  An XRGB8888 band is reduced to the top 5/6/5 bits
 * of each channel, so it gives the same bytes as the RGB565 frame of the same view
 * (raster.h: an RGB565 frame equals the RGB888 frame reduced).
 *
 *   sink_rgb565 rs;
 *   sink_rgb565_open(&rs, "out.rgb565", w, RS_FMT_RGB565, &err);     ("-": stdout)
 *   rs_pipe_run(&pipe, rows, mem, size, sink_rgb565_band, &rs, NULL);
 *   sink_rgb565_close(&rs, &err);
 * A sink that sends the bytes elsewhere (an SPI bus) converts with sink_rgb565_row. */
#ifndef BR_SINK_RGB565_H
#define BR_SINK_RGB565_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "platform/err.h"

typedef struct sink_rgb565 {
    FILE *fp;
    const char *path;
    int32_t w, fmt;             /* frame width, RS_FMT_* of the bands */
    uint8_t *row;               /* 2 w bytes */
    br_err *err;
} sink_rgb565;

/* n pixels of format fmt (RS_FMT_*) at src to 2 n big-endian RGB565 bytes at out. */
void sink_rgb565_row(int32_t fmt, const void *src, int32_t n, uint8_t *out);

/* Creates path ("-": standard output) for bands w pixels wide in format fmt. */
br_status sink_rgb565_open(sink_rgb565 *s, const char *path, int32_t w, int32_t fmt, br_err *err);
/* An rs_sink (raster/raster.h): user is the sink_rgb565. */
br_status sink_rgb565_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride);
/* Flushes and closes the file (a write error is reported here too) and frees s. */
br_status sink_rgb565_close(sink_rgb565 *s, br_err *err);

#endif
