/* platform/png_io.c — see png_io.h. */
#include "platform/png_io.h"
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct png_out {
    FILE *f;
    png_structp png;
    png_infop info;
    int w, h, rows_done;
    const char *path;
};

static void on_png_error(png_structp png, png_const_charp msg)
{
    br_err *e = png_get_error_ptr(png);
    if (e && e->code == BR_OK) br_err_set(e, BR_E_IO, NULL, "libpng: %s", msg);
    png_longjmp(png, 1);
}
static void on_png_warning(png_structp png, png_const_charp msg) { (void)png; (void)msg; }

br_status png_out_open(png_out **out, const char *path, int w, int h, br_err *err)
{
    png_out *o;
    static br_err scratch;
    br_err *e = err ? err : &scratch;
    *out = NULL;
    if (w <= 0 || h <= 0 || w > 1000000 || h > 1000000)
        return br_err_set(err, BR_E_ARG, path, "bad image size %dx%d", w, h);
    o = calloc(1, sizeof *o);
    if (!o) return br_err_set(err, BR_E_NOMEM, path, "out of memory");
    o->f = strcmp(path, "-") ? fopen(path, "wb") : stdout;      /* "-": standard output */
    if (!o->f) { free(o); return br_err_set(err, BR_E_IO, path, "cannot create file"); }
    e->code = BR_OK;
    o->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, e, on_png_error, on_png_warning);
    o->info = o->png ? png_create_info_struct(o->png) : NULL;
    if (!o->info) { png_out_abort(o); return br_err_set(err, BR_E_NOMEM, path, "libpng init failed"); }
    if (setjmp(png_jmpbuf(o->png))) {
        png_out_abort(o);
        return br_err_set(err, BR_E_IO, path, "cannot write PNG header");
    }
    png_init_io(o->png, o->f);
    png_set_compression_level(o->png, 6);
    png_set_filter(o->png, 0, PNG_FILTER_SUB);
    png_set_IHDR(o->png, o->info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(o->png, o->info);
    o->w = w; o->h = h; o->path = path;
    *out = o;
    return BR_OK;
}

br_status png_out_rows(png_out *o, const uint8_t *rows, int nrows, size_t stride, br_err *err)
{
    int i;
    if (nrows < 0 || o->rows_done + nrows > o->h)
        return br_err_set(err, BR_E_ARG, o->path, "too many rows for a %d-row image", o->h);
    if (setjmp(png_jmpbuf(o->png))) return br_err_set(err, BR_E_IO, o->path, "cannot write PNG rows");
    for (i = 0; i < nrows; i++) png_write_row(o->png, (png_const_bytep)(rows + (size_t)i * stride));
    o->rows_done += nrows;
    return BR_OK;
}

br_status png_out_close(png_out *o, br_err *err)
{
    int closed_ok;
    if (o->rows_done != o->h) {
        br_err_set(err, BR_E_ARG, o->path, "only %d of %d rows written", o->rows_done, o->h);
        png_out_abort(o);
        return BR_E_ARG;
    }
    if (setjmp(png_jmpbuf(o->png))) {
        png_out_abort(o);
        return br_err_set(err, BR_E_IO, o->path, "cannot finish PNG");
    }
    png_write_end(o->png, NULL);
    png_destroy_write_struct(&o->png, &o->info);
    closed_ok = (o->f == stdout ? fflush(o->f) == 0 && !ferror(o->f) : fclose(o->f) == 0);
    if (!closed_ok) br_err_set(err, BR_E_IO, o->path, "write failed (disk full?)");
    free(o);
    return closed_ok ? BR_OK : BR_E_IO;
}

void png_out_abort(png_out *o)
{
    if (!o) return;
    if (o->png) png_destroy_write_struct(&o->png, o->info ? &o->info : NULL);
    if (o->f && o->f != stdout) fclose(o->f);
    free(o);
}

br_status png_write_rgb(const char *path, int w, int h, const uint8_t *rgb, size_t stride, br_err *err)
{
    png_out *o;
    br_status s = png_out_open(&o, path, w, h, err);
    if (s != BR_OK) return s;
    s = png_out_rows(o, rgb, h, stride, err);
    if (s != BR_OK) { png_out_abort(o); return s; }
    return png_out_close(o, err);
}

br_status png_read_rgb(const char *path, int *w, int *h, uint8_t **rgb, br_err *err)
{
    png_image img;
    uint8_t *buf;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    *rgb = NULL;
    if (!png_image_begin_read_from_file(&img, path))
        return br_err_set(err, BR_E_FORMAT, path, "cannot read PNG: %s", img.message);
    img.format = PNG_FORMAT_RGB;
    buf = malloc(PNG_IMAGE_SIZE(img));
    if (!buf) { png_image_free(&img); return br_err_set(err, BR_E_NOMEM, path, "out of memory"); }
    if (!png_image_finish_read(&img, NULL, buf, 0, NULL)) {
        free(buf);
        return br_err_set(err, BR_E_FORMAT, path, "cannot decode PNG: %s", img.message);
    }
    *w = (int)img.width; *h = (int)img.height; *rgb = buf;
    return BR_OK;
}
