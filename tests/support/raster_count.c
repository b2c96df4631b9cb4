/* tests/support/raster_count.c — see raster_count.h: raster.c and xform.c compiled a
 * second time with RS_WITH_COUNT = 1, their external functions renamed cnt_* so that
 * they link beside the library. */
#define RS_WITH_COUNT 1
#define rs_cache_mem_size cnt_cache_mem_size
#define rs_band_mem_size cnt_band_mem_size
#define rs_chunk_mem_size cnt_chunk_mem_size
#define rs_clip_mem_size cnt_clip_mem_size
#define rs_cvert_set cnt_cvert_set
#define rs_cvert_recolour cnt_cvert_recolour
#define rs_frame_prepare cnt_frame_prepare
#define rs_draw_band cnt_draw_band
#define rs_variant_built cnt_variant_built
#define rs_to_rgb888 cnt_to_rgb888
#include "tests/support/raster_count.h"
#include "raster/raster.c"
#include "raster/xform.c"
