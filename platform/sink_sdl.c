/* platform/sink_sdl.c — see sink_sdl.h. */
#include "platform/sink_sdl.h"
#include <string.h>
#include "raster/raster.h"

uint32_t sink_sdl_format(int32_t fmt)
{
    return fmt == RS_FMT_RGB565 ? SDL_PIXELFORMAT_RGB565 : SDL_PIXELFORMAT_RGB888;
}

void sink_sdl_init(sink_sdl *s, SDL_Texture *tex, int32_t w, int32_t h, int32_t fmt, void *keep)
{
    memset(s, 0, sizeof *s);
    s->tex = tex;
    s->w = w; s->h = h; s->fmt = fmt;
    s->keep = keep;
}

br_status sink_sdl_lock(sink_sdl *s)
{
    void *px;
    int pitch;
    if (SDL_LockTexture(s->tex, NULL, &px, &pitch) != 0) return BR_E_IO;
    s->px = (uint8_t *)px;
    s->pitch = pitch;
    return BR_OK;
}

br_status sink_sdl_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    sink_sdl *s = (sink_sdl *)user;
    size_t row_bytes = (size_t)s->w * (s->fmt == RS_FMT_RGB565 ? 2u : 4u);
    int32_t y;
    if (!s->px || y0 < 0 || rows < 0 || y0 + rows > s->h || (size_t)s->pitch < row_bytes) return BR_E_ARG;
    for (y = 0; y < rows; y++) {
        const uint8_t *src = (const uint8_t *)px + (size_t)y * stride;
        memcpy(s->px + (size_t)(y0 + y) * (size_t)s->pitch, src, row_bytes);
        if (s->keep) memcpy((uint8_t *)s->keep + (size_t)(y0 + y) * row_bytes, src, row_bytes);
    }
    return BR_OK;
}

void sink_sdl_unlock(sink_sdl *s)
{
    if (s->px) SDL_UnlockTexture(s->tex);
    s->px = NULL;
}
