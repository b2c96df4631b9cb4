/* tests/test_board_spi.c — the board main's SPI band stream (platform/board/spi_band.h,
 * the code `make mcu` runs on Cortex-M) gives exactly the bytes, D/C levels and write
 * boundaries of the Linux sink (platform/sink_spi.h spi_sink_band) for the same RGB565
 * bands: an odd width (the word path's tail), rows with padding, a band pointer that is
 * not 4-byte aligned (the byte path), and a full 320-pixel band of an ST7789 frame.  And
 * the stream's checksum step (spib_sum) does not depend on how the stream is cut. */
#include "tests/test.h"
#include "platform/sink_spi.h"
#include "raster/raster.h"
#include "platform/board/spi_band.c"

/* a recorded stream: bytes, each with its D/C level, and the number of writes */
typedef struct rec {
    uint8_t b[1 << 16], dc[1 << 16];
    size_t n;
    int writes, over;
} rec;

static void rec_put(rec *r, int dc, const uint8_t *p, size_t n)
{
    size_t i;
    r->writes++;
    for (i = 0; i < n; i++) {
        if (r->n == sizeof r->b) { r->over = 1; return; }
        r->b[r->n] = p[i]; r->dc[r->n++] = (uint8_t)dc;
    }
}

static void board_put(void *user, int dc, const uint8_t *p, size_t n)
{
    rec_put((rec *)user, dc, p, n);
}

static br_status sink_write(void *user, int dc, const uint8_t *p, size_t n, br_err *err)
{
    (void)err;
    rec_put((rec *)user, dc, p, n);
    return BR_OK;
}

static rec ra, rb;

/* the band rows [y0, y0 + rows) of a w-wide frame through both, pixels at px (stride) */
static void compare(int32_t w, int32_t h, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    spi_sink ss;
    spi_writer wr;
    br_err err;
    uint8_t row[2 * 320 + 4];
    wr.write = sink_write; wr.wait_ms = NULL; wr.user = &rb;
    CHECK(spi_sink_open(&ss, &wr, SPI_PANEL_ST7789, w, h, RS_FMT_RGB565, -1, &err) == BR_OK);
    memset(&ra, 0, sizeof ra); memset(&rb, 0, sizeof rb);
    spib_band(board_put, &ra, w, y0, rows, px, stride, row);
    CHECK(spi_sink_band(&ss, y0, rows, px, stride) == BR_OK);
    spi_sink_close(&ss);
    CHECK(!ra.over && !rb.over);
    CHECK_EQ(ra.n, rb.n);
    CHECK_EQ(ra.n, 11 + (size_t)rows * w * 2);
    CHECK_EQ(ra.writes, rb.writes);
    CHECK(ra.n == rb.n && !memcmp(ra.b, rb.b, ra.n) && !memcmp(ra.dc, rb.dc, ra.n));
}

static uint16_t px[4 * 330 + 8];

static void fill(size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) px[i] = (uint16_t)(0xf81fu ^ (i * 2654435761u >> 7));
}

static void test_odd_width_padded_rows(void)
{
    fill(sizeof px / 2);
    compare(7, 5, 2, 3, px, 9 * 2);                 /* 7 pixels, 9-pixel stride */
}

static void test_unaligned_band(void)
{
    fill(sizeof px / 2);
    compare(6, 4, 0, 4, px + 1, 6 * 2);             /* 2 bytes off a word */
}

static void test_full_band(void)
{
    fill(sizeof px / 2);
    compare(320, 240, 224, 4, px, 330 * 2);
}

static void test_sum_cut_independent(void)
{
    static const uint8_t s[] = { 0x2a, 0, 0, 1, 0x3f, 0x2c, 0xf8, 0x1f, 0x07, 0xe0 };
    static const int dc[] = { 0, 1, 1, 1, 1, 0, 1, 1, 1, 1 };
    uint32_t whole = SPIB_SUM_INIT, bytes = SPIB_SUM_INIT;
    int dw = -1, db = -1, d0 = -1, d1 = -1;
    size_t i;
    whole = spib_sum(whole, &dw, 0, s, 1);
    whole = spib_sum(whole, &dw, 1, s + 1, 4);
    whole = spib_sum(whole, &dw, 0, s + 5, 1);
    whole = spib_sum(whole, &dw, 1, s + 6, 4);
    for (i = 0; i < sizeof s; i++) bytes = spib_sum(bytes, &db, dc[i], s + i, 1);
    CHECK_EQ(whole, bytes);
    /* the same byte as a command and as data sums differently */
    CHECK(spib_sum(SPIB_SUM_INIT, &d0, 0, s, 1) != spib_sum(SPIB_SUM_INIT, &d1, 1, s, 1));
}

int main(void)
{
    T_RUN(test_odd_width_padded_rows);
    T_RUN(test_unaligned_band);
    T_RUN(test_full_band);
    T_RUN(test_sum_cut_independent);
    return t_finish();
}
