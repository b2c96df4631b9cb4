/* platform/render_spi.h — `render --spi`: the frame streamed band by band to an SPI panel
 * (platform/sink_spi.h), its options as one table of the option parser (platform/opt.h):
 *   --spi DEV | --spi-capture FILE   the panel's spidev device, or a file that records the
 *                                    exact byte stream (tests, no hardware)
 *   --panel st7789|ili9341, --dc CHIP:LINE, --reset CHIP:LINE, --spi-hz HZ, --spi-mode 0-3,
 *   --madctl M (memory access control byte; default the panel's) */
#ifndef BR_RENDER_SPI_H
#define BR_RENDER_SPI_H
#include "platform/err.h"
#include "platform/opt.h"
#include "platform/sink_spi.h"

#define RENDER_SPI_N 9  /* entries of the table, OPT_END included */

typedef struct render_spi {
    const char *dev, *capture, *dc, *rst;
    int panel_choice;           /* 0 st7789, 1 ili9341 */
    int mode, madctl, madctl_seen;
    long hz;
    spi_writer wr;
    spi_sink ss;
} render_spi;

/* Fills t, writing into *o (defaults: st7789, D/C /dev/gpiochip0:25, 16 MHz, mode 0). */
void render_spi_table(render_spi *o, opt_spec t[RENDER_SPI_N]);
/* 1 when a panel or a capture file was asked for. */
int render_spi_on(const render_spi *o);
/* Opens the writer and starts the panel up for a w x h frame of format fmt. */
br_status render_spi_open(render_spi *o, int32_t w, int32_t h, int32_t fmt, br_err *err);
/* Closes the panel and its writer; err NULL when the frame failed (nothing reported). */
br_status render_spi_close(render_spi *o, br_err *err);

#endif
