/* platform/sink_png.h — the PNG sink: bands of a frame streamed into an 8-bit RGB PNG
 * (platform/png_io.h), so the frame never exists whole in memory.
 *
 *   sink_png ps;
 *   sink_png_open(&ps, "out.png", w, h, RS_FMT_XRGB8888, &err);
 *   rs_pipe_run(&pipe, rows, mem, size, sink_png_band, &ps, NULL);   (raster/frame.h)
 *   sink_png_close(&ps, &err);         (or sink_png_abort(&ps) on an error path)
 */
#ifndef BR_SINK_PNG_H
#define BR_SINK_PNG_H
#include <stddef.h>
#include <stdint.h>
#include "platform/err.h"
#include "platform/png_io.h"

typedef struct sink_png {
    png_out *po;
    int32_t w, fmt;             /* frame width, RS_FMT_* of the bands */
    uint8_t *rgb;               /* one RGB888 row */
    br_err *err;                /* where a write error goes (sink_png_open's err) */
} sink_png;

/* Creates path for a w x h image of bands in format fmt (RS_FMT_*). */
br_status sink_png_open(sink_png *s, const char *path, int32_t w, int32_t h, int32_t fmt, br_err *err);
/* An rs_sink (raster/raster.h): user is the sink_png; bands in order, top to bottom. */
br_status sink_png_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride);
/* Finishes the file (BR_E_ARG-like error when fewer than h rows came) and frees s. */
br_status sink_png_close(sink_png *s, br_err *err);
/* Discards the unfinished file's state and frees s. */
void sink_png_abort(sink_png *s);

#endif
