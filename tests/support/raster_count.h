/* tests/support/raster_count.h — a copy of the rasteriser with the tests' write-counting
 * variant (rs_frame.debug_count: no depth test, each covered pixel's XRGB8888 value
 * incremented), which the shipped library leaves out (core/config.h RS_WITH_COUNT = 0).
 * The same code as the library's, so frames without debug_count draw the same bytes. */
#ifndef BR_TESTS_RASTER_COUNT_H
#define BR_TESTS_RASTER_COUNT_H
#include "raster/raster.h"

br_status cnt_frame_prepare(rs_frame *f);
br_status cnt_draw_band(const rs_frame *f, int32_t y0, int32_t rows, void *color, size_t stride, void *depth,
                        rs_band_stats *st);

#endif
