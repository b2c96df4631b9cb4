/* platform/render_spi.c — see render_spi.h. */
#include "platform/render_spi.h"
#include <string.h>

void render_spi_table(render_spi *o, opt_spec t[RENDER_SPI_N])
{
    const opt_spec src[RENDER_SPI_N] = {
        { "--spi", OPT_STR, &o->dev, 0, 0, 0, NULL, "DEV", "stream each band to an SPI panel (/dev/spidevB.C)", NULL },
        { "--spi-capture", OPT_STR, &o->capture, 0, 0, 0, NULL, "FILE", "write the panel's exact byte stream to FILE instead", NULL },
        { "--panel", OPT_CHOICE, &o->panel_choice, 0, 0, 0, "st7789|ili9341", "P", "the panel's controller (default st7789)", NULL },
        { "--dc", OPT_STR, &o->dc, 0, 0, 0, NULL, "CHIP:LINE", "GPIO line of the panel's D/C pin (default /dev/gpiochip0:25)", NULL },
        { "--reset", OPT_STR, &o->rst, 0, 0, 0, NULL, "CHIP:LINE", "GPIO line of the panel's RESET pin (default none)", NULL },
        { "--spi-hz", OPT_LONG, &o->hz, 1000, 100000000, 0, NULL, "HZ", "SPI clock (default 16000000)", NULL },
        { "--spi-mode", OPT_INT, &o->mode, 0, 3, 0, NULL, "M", "SPI mode (default 0)", NULL },
        { "--madctl", OPT_INT, &o->madctl, 0, 255, 0, NULL, "M", "memory access control byte (default the panel's)", &o->madctl_seen },
        OPT_END
    };
    memset(o, 0, sizeof *o);
    o->dc = "/dev/gpiochip0:25";
    o->hz = 16000000;
    memcpy(t, src, sizeof src);
}

int render_spi_on(const render_spi *o) { return o->dev || o->capture; }

br_status render_spi_open(render_spi *o, int32_t w, int32_t h, int32_t fmt, br_err *err)
{
    br_status st = o->capture ? spi_capture_open(&o->wr, o->capture, err)
                              : spi_linux_open(&o->wr, o->dev, (uint32_t)o->hz, o->mode, o->dc, o->rst, err);
    if (st != BR_OK) return st;
    st = spi_sink_open(&o->ss, &o->wr, o->panel_choice ? SPI_PANEL_ILI9341 : SPI_PANEL_ST7789, w, h, fmt,
                       o->madctl_seen ? o->madctl : -1, err);
    if (st != BR_OK) {
        if (o->capture) spi_capture_close(&o->wr, NULL);
        else spi_linux_close(&o->wr);
    }
    return st;
}

br_status render_spi_close(render_spi *o, br_err *err)
{
    spi_sink_close(&o->ss);
    if (o->capture) return spi_capture_close(&o->wr, err);
    spi_linux_close(&o->wr);
    return BR_OK;
}
