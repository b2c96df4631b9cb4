/* platform/font.h — a 5x7 bitmap font for text bitrain draws itself (the viewer's HUD
 * and help), drawn into a band of the frame driver (raster/frame.h) in a post hook.
 *
 * Glyphs: printable ASCII (32..126), 5 x 7 pixels in a cell of FONT_ADV x FONT_LINE
 * pixels (one column and two rows of spacing), scaled by a whole factor.  Other bytes
 * draw as '?'.  Integer only; a pixel's value depends on its frame position and the
 * text, never on the band it is drawn in, so text crossing band boundaries comes out
 * the same for every band height and thread count. */
#ifndef BR_FONT_H
#define BR_FONT_H
#include <stdint.h>
#include "raster/frame.h"

#define FONT_GW 5       /* glyph width, pixels */
#define FONT_GH 7       /* glyph height */
#define FONT_ADV 6      /* advance per character */
#define FONT_LINE 9     /* advance per line */

/* Width in pixels of text at scale s (the longest line when it holds '\n'). */
int32_t font_width(const char *text, int32_t s);
/* Lines in text. */
int32_t font_lines(const char *text);

/* Draws text with its top-left cell corner at frame pixel (x, y), scale s >= 1, colour
 * 0xRRGGBB, each glyph pixel with a dark shadow one pixel (times s) down and right so
 * that it reads on any terrain.  '\n' starts a new line.  Only the band's rows are
 * touched; anything outside the frame is clipped. */
void font_draw(rs_band *b, int32_t x, int32_t y, int32_t s, uint32_t rgb, const char *text);

/* Darkens the rectangle [x, x + w) x [y, y + h) of the frame to 3/8 of its value
 * (a panel behind text), clipped to the band and the frame. */
void font_panel(rs_band *b, int32_t x, int32_t y, int32_t w, int32_t h);

/* Sets one frame pixel (x, y) to 0xRRGGBB when it lies in the band. */
void font_pixel(rs_band *b, int32_t x, int32_t y, uint32_t rgb);

#endif
