/* platform/png_io.h — write (and read back) 8-bit RGB PNG images with libpng.
 *
 * Writing can stream: open, hand rows in any number of calls (a band of the
 * frame at a time), close; so a frame never has to exist whole in memory.
 * Output is deterministic: fixed zlib level and filter, no time chunk. */
#ifndef BR_PNG_IO_H
#define BR_PNG_IO_H
#include <stddef.h>
#include <stdint.h>
#include "platform/err.h"

typedef struct png_out png_out;

/* path "-" writes to standard output. */
br_status png_out_open(png_out **out, const char *path, int w, int h, br_err *err);
/* rows: nrows rows of w RGB888 pixels, stride bytes apart. */
br_status png_out_rows(png_out *o, const uint8_t *rows, int nrows, size_t stride, br_err *err);
/* Finishes the file (fails if fewer than h rows were given) and frees o. */
br_status png_out_close(png_out *o, br_err *err);
/* Discards o without finishing the file (on an error path). */
void png_out_abort(png_out *o);

br_status png_write_rgb(const char *path, int w, int h, const uint8_t *rgb, size_t stride, br_err *err);
/* Reads any PNG as 8-bit RGB (for golden tests); *rgb is malloc'd. */
br_status png_read_rgb(const char *path, int *w, int *h, uint8_t **rgb, br_err *err);

#endif
