/* platform/sink_sdl.h — the SDL sink: bands of a frame written into a locked SDL2
 * streaming texture, row by row at the texture's pitch, for the viewer.
 *
 *   tex = SDL_CreateTexture(ren, sink_sdl_format(fmt), SDL_TEXTUREACCESS_STREAMING, w, h);
 *   sink_sdl ss;
 *   sink_sdl_init(&ss, tex, w, h, fmt, keep);        (keep: NULL, or w*h pixels to keep)
 *   per frame:
 *     sink_sdl_lock(&ss);
 *     rs_pipe_run(&pipe, 64, mem, size, sink_sdl_band, &ss, &stats);   (raster/frame.h)
 *     sink_sdl_unlock(&ss);
 *     SDL_RenderCopy(ren, tex, NULL, NULL); SDL_RenderPresent(ren);
 * keep, when given, also gets a copy of the frame (w pixels a row, rows packed, the
 * frame's format): the last frame for a screenshot, as the texture cannot be read back.
 * Same thread as the SDL renderer (SDL's rule for textures). */
#ifndef BR_SINK_SDL_H
#define BR_SINK_SDL_H
#include <SDL.h>
#include <stddef.h>
#include <stdint.h>
#include "core/status.h"

typedef struct sink_sdl {
    SDL_Texture *tex;
    int32_t w, h, fmt;          /* frame size, RS_FMT_* of the bands */
    uint8_t *px;                /* the locked texture (NULL when not locked) */
    int pitch;                  /* its bytes per row */
    void *keep;                 /* NULL or w * h pixels of the frame's format */
} sink_sdl;

/* The SDL texture format that holds pixels of format fmt unchanged (RS_FMT_XRGB8888:
 * SDL_PIXELFORMAT_RGB888, RS_FMT_RGB565: SDL_PIXELFORMAT_RGB565). */
uint32_t sink_sdl_format(int32_t fmt);
void sink_sdl_init(sink_sdl *s, SDL_Texture *tex, int32_t w, int32_t h, int32_t fmt, void *keep);
/* SDL_LockTexture on the whole texture; BR_E_IO when SDL refuses (SDL_GetError says why). */
br_status sink_sdl_lock(sink_sdl *s);
/* An rs_sink (raster/raster.h): user is the locked sink_sdl; BR_E_ARG when not locked
 * or the band lies outside the texture. */
br_status sink_sdl_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride);
void sink_sdl_unlock(sink_sdl *s);

#endif
