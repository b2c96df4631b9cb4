/* platform/sink_spi.c — ST7789 / ILI9341 band sink and its writers (see sink_spi.h). */
#define _POSIX_C_SOURCE 200809L   /* nanosleep, open, ioctl under -std=c99 */
#include "platform/sink_spi.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "raster/raster.h"
#ifdef __linux__
#include <fcntl.h>
#include <sys/ioctl.h>
#include <unistd.h>
#include <linux/gpio.h>
#include <linux/spi/spidev.h>
#endif

/* the controllers' commands (ST7789V and ILI9341 data sheets: same codes) */
enum {
    C_SWRESET = 0x01, C_SLPOUT = 0x11, C_NORON = 0x13, C_INVON = 0x21, C_DISPON = 0x29,
    C_CASET = 0x2a, C_RASET = 0x2b, C_RAMWR = 0x2c, C_MADCTL = 0x36, C_COLMOD = 0x3a
};

int spi_panel_parse(const char *name)
{
    if (!strcmp(name, "st7789")) return SPI_PANEL_ST7789;
    if (!strcmp(name, "ili9341")) return SPI_PANEL_ILI9341;
    return 0;
}

static br_status cmd(const spi_writer *wr, uint8_t c, const uint8_t *par, size_t n, br_err *err)
{
    br_status st = wr->write(wr->user, 0, &c, 1, err);
    if (st == BR_OK && n) st = wr->write(wr->user, 1, par, n, err);
    return st;
}

static br_status wait(const spi_writer *wr, int ms, br_err *err)
{
    return wr->wait_ms ? wr->wait_ms(wr->user, ms, err) : BR_OK;
}

/* CASET or RASET: first and last column (row), 16 bits each, high byte first */
static br_status window(const spi_writer *wr, uint8_t c, int32_t a, int32_t b, br_err *err)
{
    const uint8_t p[4] = { (uint8_t)(a >> 8), (uint8_t)a, (uint8_t)(b >> 8), (uint8_t)b };
    return cmd(wr, c, p, 4, err);
}

br_status spi_sink_open(spi_sink *s, const spi_writer *wr, int32_t panel, int32_t w, int32_t h, int32_t fmt,
                        int32_t madctl, br_err *err)
{
    const int land = w > h;
    uint8_t m;
    br_status st;
    if (panel != SPI_PANEL_ST7789 && panel != SPI_PANEL_ILI9341)
        return br_err_set(err, BR_E_ARG, NULL, "unknown SPI panel (st7789 or ili9341)");
    if (w < 1 || h < 1 || w > (land ? 320 : 240) || h > (land ? 240 : 320))
        return br_err_set(err, BR_E_ARG, NULL, "--size %dx%d does not fit the %s panel (240x320 or 320x240 at most)",
                          (int)w, (int)h, panel == SPI_PANEL_ST7789 ? "st7789" : "ili9341");
    if (fmt != RS_FMT_RGB565 && fmt != RS_FMT_XRGB8888)
        return br_err_set(err, BR_E_ARG, NULL, "SPI panel: unknown pixel format %d", (int)fmt);
    if (madctl > 255) return br_err_set(err, BR_E_ARG, NULL, "MADCTL value %d is not a byte", (int)madctl);
    memset(s, 0, sizeof *s);
    s->row = malloc((size_t)w * 2);
    if (!s->row) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory");
    s->wr = *wr; s->panel = panel; s->w = w; s->h = h; s->fmt = fmt; s->madctl = madctl; s->err = err;
    if (madctl >= 0) m = (uint8_t)madctl;
    else if (panel == SPI_PANEL_ST7789) m = land ? 0x60 : 0x00;
    else m = land ? 0x28 : 0x48;
    {
        const uint8_t colmod = 0x55;
        if ((st = cmd(wr, C_SWRESET, NULL, 0, err)) != BR_OK || (st = wait(wr, 150, err)) != BR_OK
            || (st = cmd(wr, C_SLPOUT, NULL, 0, err)) != BR_OK || (st = wait(wr, 120, err)) != BR_OK
            || (st = cmd(wr, C_COLMOD, &colmod, 1, err)) != BR_OK || (st = cmd(wr, C_MADCTL, &m, 1, err)) != BR_OK
            || (panel == SPI_PANEL_ST7789 && (st = cmd(wr, C_INVON, NULL, 0, err)) != BR_OK)
            || (st = cmd(wr, C_NORON, NULL, 0, err)) != BR_OK || (st = cmd(wr, C_DISPON, NULL, 0, err)) != BR_OK
            || (st = wait(wr, 20, err)) != BR_OK) {
            spi_sink_close(s);
            return st;
        }
    }
    return BR_OK;
}

br_status spi_sink_band(void *user, int32_t y0, int32_t rows, const void *pixels, size_t stride)
{
    spi_sink *s = (spi_sink *)user;
    br_status st;
    int32_t y, x;
    if (y0 < 0 || rows < 1 || y0 + rows > s->h)
        return br_err_set(s->err, BR_E_ARG, NULL, "SPI panel: band rows %d..%d outside the frame", (int)y0, (int)(y0 + rows - 1));
    if ((st = window(&s->wr, C_CASET, 0, s->w - 1, s->err)) != BR_OK
        || (st = window(&s->wr, C_RASET, y0, y0 + rows - 1, s->err)) != BR_OK
        || (st = cmd(&s->wr, C_RAMWR, NULL, 0, s->err)) != BR_OK)
        return st;
    for (y = 0; y < rows; y++) {
        const uint8_t *r = (const uint8_t *)pixels + (size_t)y * stride;
        for (x = 0; x < s->w; x++) {
            uint32_t v;
            if (s->fmt == RS_FMT_RGB565) v = ((const uint16_t *)(const void *)r)[x];
            else {
                const uint32_t c = ((const uint32_t *)(const void *)r)[x];
                v = ((c >> 8) & 0xf800u) | ((c >> 5) & 0x07e0u) | ((c >> 3) & 0x001fu);
            }
            s->row[2 * x] = (uint8_t)(v >> 8);
            s->row[2 * x + 1] = (uint8_t)v;
        }
        if ((st = s->wr.write(s->wr.user, 1, s->row, (size_t)s->w * 2, s->err)) != BR_OK) return st;
    }
    return BR_OK;
}

void spi_sink_close(spi_sink *s)
{
    free(s->row);
    s->row = NULL;
}

/* ---------------------------------------------------------------- capture file */

static br_status cap_record(FILE *f, int kind, const uint8_t *p, size_t n, br_err *err)
{
    const uint8_t h[5] = { (uint8_t)kind, (uint8_t)n, (uint8_t)(n >> 8), (uint8_t)(n >> 16), (uint8_t)(n >> 24) };
    if (fwrite(h, 1, 5, f) != 5 || fwrite(p, 1, n, f) != n)
        return br_err_set(err, BR_E_IO, NULL, "SPI capture: write failed: %s", strerror(errno));
    return BR_OK;
}

static br_status cap_write(void *user, int dc, const uint8_t *p, size_t n, br_err *err)
{
    return cap_record((FILE *)user, dc ? 'D' : 'C', p, n, err);
}

static br_status cap_wait(void *user, int ms, br_err *err)
{
    const uint8_t b[4] = { (uint8_t)ms, (uint8_t)(ms >> 8), (uint8_t)(ms >> 16), (uint8_t)(ms >> 24) };
    return cap_record((FILE *)user, 'W', b, 4, err);
}

br_status spi_capture_open(spi_writer *wr, const char *path, br_err *err)
{
    FILE *f = fopen(path, "wb");
    if (!f) return br_err_set(err, BR_E_IO, path, "cannot create: %s", strerror(errno));
    wr->write = cap_write; wr->wait_ms = cap_wait; wr->user = f;
    return BR_OK;
}

br_status spi_capture_close(spi_writer *wr, br_err *err)
{
    FILE *f = (FILE *)wr->user;
    wr->user = NULL;
    if (f && fclose(f) != 0) return br_err_set(err, BR_E_IO, NULL, "SPI capture: close failed: %s", strerror(errno));
    return BR_OK;
}

/* ---------------------------------------------------------------- Linux spidev + GPIO */

#ifdef __linux__
typedef struct spi_linux {
    int spi, dc, rst;           /* spidev fd, line request fds (rst -1: none) */
    int dc_now;                 /* the D/C level last set (-1: unknown) */
    const char *dev;
} spi_linux;

/* "/dev/gpiochip0:25": one output line requested, initial level val; its fd or -1 */
static int gpio_line(const char *spec, int val, br_err *err)
{
    char chip[256];
    const char *colon = strrchr(spec, ':');
    struct gpio_v2_line_request rq;
    int fd, line;
    char *end;
    if (!colon || (size_t)(colon - spec) >= sizeof chip || !colon[1]) {
        br_err_set(err, BR_E_ARG, spec, "expected CHIP:LINE, e.g. /dev/gpiochip0:25");
        return -1;
    }
    line = (int)strtol(colon + 1, &end, 10);
    if (*end || line < 0) { br_err_set(err, BR_E_ARG, spec, "line '%s' is not a number", colon + 1); return -1; }
    memcpy(chip, spec, (size_t)(colon - spec));
    chip[colon - spec] = 0;
    fd = open(chip, O_RDWR | O_CLOEXEC);
    if (fd < 0) { br_err_set(err, BR_E_IO, chip, "cannot open GPIO chip: %s", strerror(errno)); return -1; }
    memset(&rq, 0, sizeof rq);
    rq.offsets[0] = (uint32_t)line;
    rq.num_lines = 1;
    rq.config.flags = GPIO_V2_LINE_FLAG_OUTPUT;
    rq.config.num_attrs = 1;
    rq.config.attrs[0].attr.id = GPIO_V2_LINE_ATTR_ID_OUTPUT_VALUES;
    rq.config.attrs[0].attr.values = (uint64_t)(val != 0);
    rq.config.attrs[0].mask = 1;
    strcpy(rq.consumer, "bitrain");
    if (ioctl(fd, GPIO_V2_GET_LINE_IOCTL, &rq) < 0) {
        br_err_set(err, BR_E_IO, spec, "cannot request the GPIO line as an output: %s", strerror(errno));
        close(fd);
        return -1;
    }
    close(fd);
    return rq.fd;
}

static int gpio_set(int fd, int val)
{
    struct gpio_v2_line_values v;
    v.bits = (uint64_t)(val != 0);
    v.mask = 1;
    return ioctl(fd, GPIO_V2_LINE_SET_VALUES_IOCTL, &v);
}

static br_status lx_write(void *user, int dc, const uint8_t *p, size_t n, br_err *err)
{
    spi_linux *l = (spi_linux *)user;
    if (l->dc_now != dc) {
        if (gpio_set(l->dc, dc) < 0) return br_err_set(err, BR_E_IO, l->dev, "cannot set the D/C line: %s", strerror(errno));
        l->dc_now = dc;
    }
    while (n) {     /* spidev takes at most its bufsiz (4096 bytes by default) a transfer */
        const size_t k = n < 4096 ? n : 4096;
        const ssize_t r = write(l->spi, p, k);
        if (r != (ssize_t)k) return br_err_set(err, BR_E_IO, l->dev, "SPI write failed: %s", r < 0 ? strerror(errno) : "short write");
        p += k; n -= k;
    }
    return BR_OK;
}

static br_status lx_wait(void *user, int ms, br_err *err)
{
    struct timespec t;
    (void)user; (void)err;
    t.tv_sec = ms / 1000;
    t.tv_nsec = (long)(ms % 1000) * 1000000L;
    while (nanosleep(&t, &t) != 0 && errno == EINTR) {}
    return BR_OK;
}

br_status spi_linux_open(spi_writer *wr, const char *dev, uint32_t hz, int mode, const char *dc, const char *rst,
                         br_err *err)
{
    spi_linux *l = calloc(1, sizeof *l);
    uint8_t m = (uint8_t)mode, bits = 8;
    if (!l) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory");
    l->dev = dev; l->dc = l->rst = -1; l->dc_now = -1;
    l->spi = open(dev, O_RDWR | O_CLOEXEC);
    if (l->spi < 0) { br_err_set(err, BR_E_IO, dev, "cannot open the SPI device: %s", strerror(errno)); free(l); return BR_E_IO; }
    if (ioctl(l->spi, SPI_IOC_WR_MODE, &m) < 0 || ioctl(l->spi, SPI_IOC_WR_BITS_PER_WORD, &bits) < 0
        || ioctl(l->spi, SPI_IOC_WR_MAX_SPEED_HZ, &hz) < 0) {
        br_err_set(err, BR_E_IO, dev, "not an SPI device, or it refuses mode %d at %u Hz: %s", mode, (unsigned)hz, strerror(errno));
        close(l->spi); free(l);
        return BR_E_IO;
    }
    if ((l->dc = gpio_line(dc, 0, err)) < 0 || (rst && (l->rst = gpio_line(rst, 1, err)) < 0)) {
        if (l->dc >= 0) close(l->dc);
        close(l->spi); free(l);
        return err ? err->code : BR_E_IO;
    }
    wr->write = lx_write; wr->wait_ms = lx_wait; wr->user = l;
    if (l->rst >= 0) {      /* a hardware reset: low for 10 ms, then 120 ms to wake */
        if (gpio_set(l->rst, 0) < 0 || lx_wait(l, 10, err) != BR_OK || gpio_set(l->rst, 1) < 0) {
            br_err_set(err, BR_E_IO, rst, "cannot pulse the RESET line: %s", strerror(errno));
            spi_linux_close(wr);
            return BR_E_IO;
        }
        lx_wait(l, 120, err);
    }
    return BR_OK;
}

void spi_linux_close(spi_writer *wr)
{
    spi_linux *l = (spi_linux *)wr->user;
    if (!l) return;
    close(l->spi);
    if (l->dc >= 0) close(l->dc);
    if (l->rst >= 0) close(l->rst);
    free(l);
    wr->user = NULL;
}
#else
br_status spi_linux_open(spi_writer *wr, const char *dev, uint32_t hz, int mode, const char *dc, const char *rst,
                         br_err *err)
{
    (void)wr; (void)hz; (void)mode; (void)dc; (void)rst;
    return br_err_set(err, BR_E_UNSUPPORTED, dev, "SPI panels need Linux spidev");
}

void spi_linux_close(spi_writer *wr)
{
    (void)wr;
}
#endif
