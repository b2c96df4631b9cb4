/* tests/test_spi.c — the SPI panel sink (platform/sink_spi.h) without a panel: the
 * exact byte stream it writes (commands, their parameters, pixels) is decoded back
 * into an image as an ST7789 / ILI9341 would fill its RAM, and compared with the PNG of
 * the same render of real terrain (assets/N47E009.hgt.gz, SRTM3 Lake Constance). */
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/png_io.h"
#include "platform/sink_spi.h"
#include "raster/raster.h"

/* ---- a controller model: RAM of 320 x 320 RGB565 cells, filled as the data sheets say */
typedef struct panel_model {
    uint16_t ram[320 * 320];
    int xs, xe, ys, ye, x, y;       /* window, write position */
    int cmd, npar, colmod, madctl, on, awake, writing;
    uint8_t par[4], hi;
    int half;                       /* a pixel's high byte seen */
    long pixels, bad;               /* pixels written; protocol errors */
} panel_model;

static void model_cmd(panel_model *m, uint8_t c)
{
    m->cmd = c; m->npar = 0; m->writing = 0; m->half = 0;
    if (c == 0x01) { m->awake = 0; m->on = 0; }
    else if (c == 0x11) m->awake = 1;
    else if (c == 0x29) m->on = 1;
    else if (c == 0x2c) { m->writing = 1; m->x = m->xs; m->y = m->ys; }
    else if (c != 0x13 && c != 0x21 && c != 0x2a && c != 0x2b && c != 0x36 && c != 0x3a) m->bad++;
}

static void model_data(panel_model *m, const uint8_t *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (m->writing) {
            if (!m->half) { m->hi = p[i]; m->half = 1; continue; }
            m->half = 0;
            if (m->y > m->ye || m->x >= 320 || m->y >= 320) { m->bad++; continue; }
            m->ram[m->y * 320 + m->x] = (uint16_t)(m->hi << 8 | p[i]);
            m->pixels++;
            if (++m->x > m->xe) { m->x = m->xs; m->y++; }
            continue;
        }
        if (m->npar < 4) m->par[m->npar] = p[i];
        m->npar++;
        if (m->cmd == 0x3a && m->npar == 1) m->colmod = p[i];
        else if (m->cmd == 0x36 && m->npar == 1) m->madctl = p[i];
        else if ((m->cmd == 0x2a || m->cmd == 0x2b) && m->npar == 4) {
            const int a = m->par[0] << 8 | m->par[1], b = m->par[2] << 8 | m->par[3];
            if (m->cmd == 0x2a) { m->xs = a; m->xe = b; } else { m->ys = a; m->ye = b; }
        } else if (m->npar > (m->cmd == 0x2a || m->cmd == 0x2b ? 4 : 1)) m->bad++;
    }
}

/* a capture file (spi_capture_open's records) through the model; 0 when malformed */
static int model_run_capture(panel_model *m, const char *path)
{
    size_t n = 0, k = 0;
    unsigned char *f = t_read_file(path, &n);
    if (!f) return 0;
    while (k + 5 <= n) {
        const size_t len = (size_t)f[k + 1] | (size_t)f[k + 2] << 8 | (size_t)f[k + 3] << 16 | (size_t)f[k + 4] << 24;
        const int kind = f[k];
        k += 5;
        if (len > n - k) break;
        if (kind == 'C') { size_t i; for (i = 0; i < len; i++) model_cmd(m, f[k + i]); }
        else if (kind == 'D') model_data(m, f + k, len);
        else if (kind != 'W') break;
        k += len;
    }
    free(f);
    return k == n;
}

/* ---- a writer into memory: the stream as a list of (dc, byte) and the waits */
typedef struct mem_writer { uint8_t b[8192]; uint8_t dc[8192]; size_t n; int waits, fail_at; } mem_writer;

static br_status mw_write(void *user, int dc, const uint8_t *p, size_t n, br_err *err)
{
    mem_writer *w = (mem_writer *)user;
    size_t i;
    if (w->fail_at && w->n + n >= (size_t)w->fail_at) return br_err_set(err, BR_E_IO, "test", "write fails here");
    for (i = 0; i < n && w->n < sizeof w->b; i++, w->n++) { w->b[w->n] = p[i]; w->dc[w->n] = (uint8_t)dc; }
    return BR_OK;
}

static br_status mw_wait(void *user, int ms, br_err *err)
{
    (void)err;
    ((mem_writer *)user)->waits += ms;
    return BR_OK;
}

/* An asymmetric 6 x 5 "F", red on blue, in XRGB8888 and then RGB565 bands of 2 rows (the
 * last band 1 row): the exact bytes, start-up sequence included, for both panels. */
static void test_exact_stream(void)
{
    static const char *F[5] = { "RRRRR.", "R.....", "RRRR..", "R.....", "R....." };
    uint32_t px8[30];
    uint16_t px5[30];
    int panel, fmt, i, y;
    for (i = 0; i < 30; i++) {
        px8[i] = F[i / 6][i % 6] == 'R' ? 0xff1008u : 0x0010ffu;
        px5[i] = F[i / 6][i % 6] == 'R' ? (uint16_t)0xf881u : (uint16_t)0x009fu;
    }
    for (panel = SPI_PANEL_ST7789; panel <= SPI_PANEL_ILI9341; panel++)
        for (fmt = 0; fmt < 2; fmt++) {
            static mem_writer w;
            spi_writer wr = { mw_write, mw_wait, &w };
            spi_sink s;
            br_err e;
            const int f = fmt ? RS_FMT_RGB565 : RS_FMT_XRGB8888;
            /* SWRESET; SLPOUT; COLMOD 55; MADCTL (6 x 5: landscape); [INVON]; NORON; DISPON */
            const uint8_t st[] = { 0x01, 0x11, 0x3a, 0x55, 0x36, 0x60, 0x21, 0x13, 0x29 };
            const uint8_t il[] = { 0x01, 0x11, 0x3a, 0x55, 0x36, 0x28, 0x13, 0x29 };
            const uint8_t st_dc[] = { 0, 0, 0, 1, 0, 1, 0, 0, 0 }, il_dc[] = { 0, 0, 0, 1, 0, 1, 0, 0 };
            const uint8_t *ex = panel == SPI_PANEL_ST7789 ? st : il, *exdc = panel == SPI_PANEL_ST7789 ? st_dc : il_dc;
            const size_t nex = panel == SPI_PANEL_ST7789 ? sizeof st : sizeof il;
            size_t k;
            memset(&w, 0, sizeof w);
            CHECK_EQ(spi_sink_open(&s, &wr, panel, 6, 5, f, -1, &e), BR_OK);
            CHECK_EQ(w.n, nex);
            CHECK(memcmp(w.b, ex, nex) == 0 && memcmp(w.dc, exdc, nex) == 0);
            CHECK_EQ(w.waits, 150 + 120 + 20);
            for (y = 0; y < 5; y += 2) {
                const int rows = y + 2 <= 5 ? 2 : 1;
                const void *p = fmt ? (const void *)(px5 + 6 * y) : (const void *)(px8 + 6 * y);
                CHECK_EQ(spi_sink_band(&s, y, rows, p, fmt ? 12 : 24), BR_OK);
            }
            /* per band: 2a 00 00 00 05, 2b 00 y 00 y+rows-1, 2c, then the pixels */
            k = nex;
            for (y = 0; y < 5; y += 2) {
                const int rows = y + 2 <= 5 ? 2 : 1;
                const uint8_t hdr[11] = { 0x2a, 0, 0, 0, 5, 0x2b, 0, (uint8_t)y, 0, (uint8_t)(y + rows - 1), 0x2c };
                const uint8_t hdc[11] = { 0, 1, 1, 1, 1, 0, 1, 1, 1, 1, 0 };
                CHECK(k + 11 + 12 * (size_t)rows <= w.n);
                if (k + 11 + 12 * (size_t)rows > w.n) break;
                CHECK(memcmp(w.b + k, hdr, 11) == 0 && memcmp(w.dc + k, hdc, 11) == 0);
                k += 11;
                for (i = 0; i < 6 * rows; i++, k += 2) {
                    const uint16_t v = px5[6 * y + i];
                    CHECK(w.b[k] == v >> 8 && w.b[k + 1] == (v & 255) && w.dc[k] == 1 && w.dc[k + 1] == 1);
                }
            }
            CHECK_EQ(k, w.n);
            spi_sink_close(&s);
        }
}

/* render -o PNG and render --spi-capture of the same frame: the panel's RAM decoded from
 * the stream equals the PNG's pixels (RGB565 frames: the PNG holds them bit-replicated to
 * eight bits, whose top bits are the RGB565 fields) */
static void one_render(const char *panel, const char *size, int w, int h, const char *bands)
{
    static panel_model m;
    char png[256], cap[256], dem[] = "assets/N47E009.hgt.gz", o[] = "-o", sz[] = "--size", fm[] = "--format", f565[] = "rgb565";
    char sc[] = "--spi-capture", pn[] = "--panel", bd[] = "--bands", szv[32], pv[32], bv[16];
    char *a1[8], *a2[10];
    uint8_t *rgb = NULL;
    int pw = 0, ph = 0, x, y, diff = 0;
    br_err e;
    snprintf(png, sizeof png, "%s/spi_%s.png", t_outdir(), panel);
    snprintf(cap, sizeof cap, "%s/spi_%s.spi", t_outdir(), panel);
    snprintf(szv, sizeof szv, "%s", size); snprintf(pv, sizeof pv, "%s", panel); snprintf(bv, sizeof bv, "%s", bands);
    a1[0] = dem; a1[1] = o; a1[2] = png; a1[3] = sz; a1[4] = szv; a1[5] = fm; a1[6] = f565; a1[7] = NULL;
    a2[0] = dem; a2[1] = sc; a2[2] = cap; a2[3] = sz; a2[4] = szv; a2[5] = pn; a2[6] = pv; a2[7] = bd; a2[8] = bv; a2[9] = NULL;
    CHECK_EQ(cmd_render(7, a1), 0);
    CHECK_EQ(cmd_render(9, a2), 0);
    memset(&m, 0, sizeof m);
    CHECK(model_run_capture(&m, cap));
    CHECK_EQ(m.bad, 0);
    CHECK(m.awake && m.on);
    CHECK_EQ(m.colmod, 0x55);
    CHECK_EQ(m.madctl, strcmp(panel, "st7789") ? (w > h ? 0x28 : 0x48) : (w > h ? 0x60 : 0x00));
    CHECK_EQ(m.pixels, (long)w * h);
    CHECK_EQ(png_read_rgb(png, &pw, &ph, &rgb, &e), BR_OK);
    if (!rgb) return;
    CHECK(pw == w && ph == h);
    for (y = 0; y < h && pw == w && ph == h; y++)
        for (x = 0; x < w; x++) {
            const uint8_t *p = rgb + 3 * ((size_t)y * w + x);
            const uint16_t v = (uint16_t)((p[0] >> 3) << 11 | (p[1] >> 2) << 5 | p[2] >> 3);
            diff += m.ram[y * 320 + x] != v;
        }
    CHECK_EQ(diff, 0);
    {   /* the frame is terrain, not only sky (0x99ccff as RGB565: 0x9e7f) */
        long sky = 0;
        for (y = 0; y < h; y++) for (x = 0; x < w; x++) sky += m.ram[y * 320 + x] == 0x9e7f;
        CHECK(sky < (long)w * h * 3 / 4);
    }
    free(rgb);
}

static void test_render_st7789(void) { one_render("st7789", "240x240", 240, 240, "16"); }
static void test_render_ili9341(void) { one_render("ili9341", "320x240", 320, 240, "7"); }

static void test_bad_input(void)
{
    static mem_writer w;
    spi_writer wr = { mw_write, NULL, &w };
    spi_sink s;
    br_err e;
    uint16_t row[6] = { 0 };
    char dem[] = "assets/N47E009.hgt.gz", sp[] = "--spi", dev[] = "tests/out/no_such_spidev", pn[] = "--panel", bogus[] = "st7735";
    char sz[] = "--size", big[] = "321x240", sc[] = "--spi-capture", cap[] = "tests/out/spi_bad.spi";
    char *a[6];
    memset(&w, 0, sizeof w);
    CHECK_EQ(spi_panel_parse("ili9341"), SPI_PANEL_ILI9341);
    CHECK_EQ(spi_panel_parse("ST7789"), 0);
    CHECK_EQ(spi_sink_open(&s, &wr, 0, 10, 10, RS_FMT_RGB565, -1, &e), BR_E_ARG);
    CHECK_EQ(spi_sink_open(&s, &wr, SPI_PANEL_ST7789, 241, 241, RS_FMT_RGB565, -1, &e), BR_E_ARG);
    CHECK_EQ(spi_sink_open(&s, &wr, SPI_PANEL_ST7789, 6, 5, RS_FMT_RGB565, 256, &e), BR_E_ARG);
    CHECK_EQ(w.n, 0);                                       /* refused before any byte */
    w.fail_at = 3;                                          /* the writer fails: its error comes back */
    CHECK_EQ(spi_sink_open(&s, &wr, SPI_PANEL_ST7789, 6, 5, RS_FMT_RGB565, -1, &e), BR_E_IO);
    w.fail_at = 0;
    CHECK_EQ(spi_sink_open(&s, &wr, SPI_PANEL_ILI9341, 6, 5, RS_FMT_RGB565, 0x08, &e), BR_OK);
    CHECK_EQ(spi_sink_band(&s, 4, 2, row, 12), BR_E_ARG);   /* past the frame */
    spi_sink_close(&s);
    t_outdir();
    a[0] = dem; a[1] = sp; a[2] = dev; a[3] = NULL;
    CHECK_EQ(cmd_render(3, a), 1);                          /* no such device: named, exit 1 */
    a[1] = sc; a[2] = cap; a[3] = pn; a[4] = bogus; a[5] = NULL;
    CHECK_EQ(cmd_render(5, a), 2);                          /* unknown panel: usage */
    a[3] = sz; a[4] = big;
    CHECK_EQ(cmd_render(5, a), 1);                          /* too big for the panel */
}

int main(void)
{
    T_RUN(test_exact_stream);
    T_RUN(test_render_st7789);
    T_RUN(test_render_ili9341);
    T_RUN(test_bad_input);
    return t_finish();
}
