/* platform/sink_rgb565.c — see sink_rgb565.h. */
#include "platform/sink_rgb565.h"
#include <stdlib.h>
#include <string.h>
#include "raster/raster.h"

void sink_rgb565_row(int32_t fmt, const void *src, int32_t n, uint8_t *out)
{
    int32_t i;
    if (fmt == RS_FMT_RGB565) {
        const uint16_t *p = (const uint16_t *)src;
        for (i = 0; i < n; i++) {
            out[2 * i] = (uint8_t)(p[i] >> 8);
            out[2 * i + 1] = (uint8_t)p[i];
        }
    } else {
        const uint32_t *p = (const uint32_t *)src;
        for (i = 0; i < n; i++) {
            uint32_t c = p[i];
            uint32_t v = (c >> 8 & 0xf800u) | (c >> 5 & 0x07e0u) | (c >> 3 & 0x001fu);
            out[2 * i] = (uint8_t)(v >> 8);
            out[2 * i + 1] = (uint8_t)v;
        }
    }
}

br_status sink_rgb565_open(sink_rgb565 *s, const char *path, int32_t w, int32_t fmt, br_err *err)
{
    memset(s, 0, sizeof *s);
    if (w < 1 || (fmt != RS_FMT_XRGB8888 && fmt != RS_FMT_RGB565))
        return br_err_set(err, BR_E_ARG, path, "bad frame width or pixel format");
    s->row = malloc((size_t)w * 2);
    if (!s->row) return br_err_set(err, BR_E_NOMEM, path, "out of memory");
    s->fp = strcmp(path, "-") ? fopen(path, "wb") : stdout;
    if (!s->fp) {
        free(s->row);
        s->row = NULL;
        return br_err_set(err, BR_E_IO, path, "cannot create file");
    }
    s->path = path; s->w = w; s->fmt = fmt; s->err = err;
    return BR_OK;
}

br_status sink_rgb565_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    sink_rgb565 *s = (sink_rgb565 *)user;
    int32_t y;
    (void)y0;
    for (y = 0; y < rows; y++) {
        sink_rgb565_row(s->fmt, (const uint8_t *)px + (size_t)y * stride, s->w, s->row);
        if (fwrite(s->row, 2, (size_t)s->w, s->fp) != (size_t)s->w)
            return br_err_set(s->err, BR_E_IO, s->path, "write failed");
    }
    return BR_OK;
}

br_status sink_rgb565_close(sink_rgb565 *s, br_err *err)
{
    br_status st = BR_OK;
    if (s->fp && (fflush(s->fp) != 0 || ferror(s->fp))) st = br_err_set(err, BR_E_IO, s->path, "write failed");
    if (s->fp && s->fp != stdout && fclose(s->fp) != 0 && st == BR_OK)
        st = br_err_set(err, BR_E_IO, s->path, "write failed");
    free(s->row);
    memset(s, 0, sizeof *s);
    return st;
}
