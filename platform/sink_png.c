/* platform/sink_png.c — see sink_png.h. */
#include "platform/sink_png.h"
#include <stdlib.h>
#include <string.h>
#include "raster/raster.h"

br_status sink_png_open(sink_png *s, const char *path, int32_t w, int32_t h, int32_t fmt, br_err *err)
{
    br_status st;
    memset(s, 0, sizeof *s);
    if (fmt != RS_FMT_XRGB8888 && fmt != RS_FMT_RGB565) return br_err_set(err, BR_E_ARG, path, "unknown pixel format");
    s->rgb = malloc((size_t)(w > 0 ? w : 1) * 3);
    if (!s->rgb) return br_err_set(err, BR_E_NOMEM, path, "out of memory");
    st = png_out_open(&s->po, path, w, h, err);
    if (st != BR_OK) { free(s->rgb); s->rgb = NULL; return st; }
    s->w = w; s->fmt = fmt; s->err = err;
    return BR_OK;
}

br_status sink_png_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    sink_png *s = (sink_png *)user;
    int32_t y;
    (void)y0;   /* png_out_rows refuses rows beyond the image's height */
    for (y = 0; y < rows; y++) {
        br_status st;
        rs_to_rgb888(s->fmt, (const uint8_t *)px + (size_t)y * stride, s->w, s->rgb);
        st = png_out_rows(s->po, s->rgb, 1, (size_t)s->w * 3, s->err);
        if (st != BR_OK) return st;
    }
    return BR_OK;
}

br_status sink_png_close(sink_png *s, br_err *err)
{
    br_status st = png_out_close(s->po, err);
    free(s->rgb);
    memset(s, 0, sizeof *s);
    return st;
}

void sink_png_abort(sink_png *s)
{
    if (s->po) png_out_abort(s->po);
    free(s->rgb);
    memset(s, 0, sizeof *s);
}
