/* platform/sink_frame.h — the band sink that keeps a whole frame in memory: each band's
 * rows copied to their place in a caller's buffer (the viewer's window, bench's -o, a
 * frame read back).
 *
 *   sink_frame sf = { px, (size_t)w * 4 };        (row_bytes: w times the format's bytes)
 *   rs_pipe_run(&pipe, rows, mem, size, sink_frame_band, &sf, NULL); */
#ifndef BR_SINK_FRAME_H
#define BR_SINK_FRAME_H
#include <stddef.h>
#include <stdint.h>
#include "platform/err.h"

typedef struct sink_frame {
    void *px;                   /* the frame: h rows of row_bytes, top to bottom */
    size_t row_bytes;           /* the bytes of a frame row and of a band row's pixels */
} sink_frame;

/* An rs_sink (raster/raster.h): user is the sink_frame; rows y0 .. y0 + rows - 1 of the
 * frame from the band's rows (stride bytes apart).  Bands in any order. */
br_status sink_frame_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride);

#endif
