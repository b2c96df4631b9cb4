/* platform/sink_frame.c — the band sink that keeps a whole frame (see sink_frame.h). */
#include "platform/sink_frame.h"
#include <string.h>

br_status sink_frame_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    const sink_frame *s = (const sink_frame *)user;
    int32_t y;
    for (y = 0; y < rows; y++)
        memcpy((uint8_t *)s->px + (size_t)(y0 + y) * s->row_bytes, (const uint8_t *)px + (size_t)y * stride,
               s->row_bytes);
    return BR_OK;
}
