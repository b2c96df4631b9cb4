/* platform/bench_chart.c — the line chart of platform/bench_chart.h.  The picture is an
 * XRGB8888 frame wrapped as one whole-frame band (raster/frame.h rs_band), so the HUD
 * font (platform/font.c) draws its text; lines are Bresenham's, two pixels thick. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "platform/bench_chart.h"
#include "platform/font.h"
#include "platform/png_io.h"

#define CH_BG 0x1c2026u
#define CH_GRID 0x3a424au
#define CH_AXIS 0xb0b8c0u
#define CH_TEXT 0xf0f0f0u

static const uint32_t series_rgb[CHART_MAX_SERIES] = {
    0xff6b5bu, 0x5bc0ffu, 0xffd24au, 0x7ee07eu, 0xd08cffu, 0xff9f40u, 0x40e0d0u, 0xf0f0f0u
};

static void hline(rs_band *b, int x0, int x1, int y, uint32_t rgb)
{
    for (; x0 <= x1; x0++) font_pixel(b, x0, y, rgb);
}

static void vline(rs_band *b, int x, int y0, int y1, uint32_t rgb)
{
    for (; y0 <= y1; y0++) font_pixel(b, x, y0, rgb);
}

/* Bresenham from (x0, y0) to (x1, y1), with the pixel below each one too. */
static void line(rs_band *b, int x0, int y0, int x1, int y1, uint32_t rgb)
{
    int dx = abs(x1 - x0), sx = x0 < x1 ? 1 : -1, dy = -abs(y1 - y0), sy = y0 < y1 ? 1 : -1, e = dx + dy, e2;
    for (;;) {
        font_pixel(b, x0, y0, rgb);
        font_pixel(b, x0, y0 + 1, rgb);
        if (x0 == x1 && y0 == y1) break;
        e2 = 2 * e;
        if (e2 >= dy) { e += dy; x0 += sx; }
        if (e2 <= dx) { e += dx; y0 += sy; }
    }
}

/* The smallest 1, 2 or 5 times a power of ten that is >= v (v > 0). */
static double nice_up(double v)
{
    double p = pow(10, floor(log10(v))), m = v / p;
    return (m <= 1 ? 1 : m <= 2 ? 2 : m <= 5 ? 5 : 10) * p;
}

br_status chart_png(const char *path, int w, int h, const char *title, const char *xlabel, const char *ylabel,
                    const chart_series *s, int ns, br_err *err)
{
    const int left = 64, right = 16, top = 40, bottom = 48;
    int px0 = left, px1 = w - 1 - right, py0 = top, py1 = h - 1 - bottom, i, k, nmax = 0;
    double ymax = 0, ystep, xstep;
    uint32_t *px;
    uint8_t *rgb;
    rs_band b;
    char buf[64];
    br_status st;
    if (w < 240 || h < 160 || w > 8192 || h > 8192 || ns < 1 || ns > CHART_MAX_SERIES || !s)
        return br_err_set(err, BR_E_ARG, path, "chart: bad size or series");
    for (k = 0; k < ns; k++) {
        if (s[k].n > nmax) nmax = s[k].n;
        for (i = 0; i < s[k].n; i++)
            if (isfinite(s[k].y[i]) && s[k].y[i] > ymax) ymax = s[k].y[i];
    }
    if (nmax < 1) return br_err_set(err, BR_E_ARG, path, "chart: no values");
    ystep = nice_up((ymax > 0 ? ymax : 1) / 5);
    ymax = ceil((ymax > 0 ? ymax : 1) / ystep) * ystep;
    xstep = nmax > 9 ? nice_up((nmax - 1) / 8.0) : 1;   /* whole frames */
    px = malloc((size_t)w * (size_t)h * 4);
    rgb = malloc((size_t)w * (size_t)h * 3);
    if (!px || !rgb) { free(px); free(rgb); return br_err_set(err, BR_E_NOMEM, path, "out of memory"); }
    for (i = 0; i < w * h; i++) px[i] = CH_BG;
    memset(&b, 0, sizeof b);
    b.w = w; b.y0 = 0; b.rows = h; b.fmt = RS_FMT_XRGB8888; b.depth_fmt = RS_DEPTH32;
    b.color = px; b.stride = (size_t)w * 4;
    /* grid and y tick labels */
    for (k = 0; k * ystep <= ymax * (1 + 1e-9); k++) {
        int y = py1 - (int)lround(k * ystep / ymax * (py1 - py0));
        hline(&b, px0, px1, y, k ? CH_GRID : CH_AXIS);
        snprintf(buf, sizeof buf, "%g", k * ystep);
        font_draw(&b, px0 - 6 - font_width(buf, 1), y - FONT_GH / 2, 1, CH_TEXT, buf);
    }
    for (k = 0; k * xstep <= nmax - 1 + 1e-9; k++) {
        int x = px0 + (nmax > 1 ? (int)lround(k * xstep / (nmax - 1) * (px1 - px0)) : 0);
        if (k) vline(&b, x, py0, py1, CH_GRID);
        vline(&b, x, py1, py1 + 4, CH_AXIS);
        snprintf(buf, sizeof buf, "%g", k * xstep);
        font_draw(&b, x - font_width(buf, 1) / 2, py1 + 8, 1, CH_TEXT, buf);
    }
    vline(&b, px0, py0, py1, CH_AXIS);
    /* the series */
    for (k = 0; k < ns; k++) {
        int have = 0, lx = 0, ly = 0;
        for (i = 0; i < s[k].n; i++) {
            double v = s[k].y[i];
            int x, y;
            if (!isfinite(v) || v < 0) { have = 0; continue; }
            x = px0 + (nmax > 1 ? (int)lround((double)i / (nmax - 1) * (px1 - px0)) : 0);
            y = py1 - (int)lround(v / ymax * (py1 - py0));
            if (have) line(&b, lx, ly, x, y, series_rgb[k]);
            else font_pixel(&b, x, y, series_rgb[k]);
            have = 1; lx = x; ly = y;
        }
    }
    /* title, axis labels, legend (top right, inside the plot) */
    if (title) font_draw(&b, (w - font_width(title, 2)) / 2, 10, 2, CH_TEXT, title);
    if (xlabel) font_draw(&b, px0 + (px1 - px0 - font_width(xlabel, 1)) / 2, h - 1 - FONT_LINE - 6, 1, CH_TEXT, xlabel);
    if (ylabel) font_draw(&b, 4, py0 - FONT_LINE - 6, 1, CH_TEXT, ylabel);
    {
        int lw = 0, lx, ly = py0 + 6;
        for (k = 0; k < ns; k++) {
            int tw = font_width(s[k].label ? s[k].label : "", 1);
            if (tw > lw) lw = tw;
        }
        lx = px1 - lw - 30;
        font_panel(&b, lx - 6, ly - 4, lw + 34, ns * (FONT_LINE + 3) + 6);
        for (k = 0; k < ns; k++, ly += FONT_LINE + 3) {
            hline(&b, lx, lx + 16, ly + 3, series_rgb[k]);
            hline(&b, lx, lx + 16, ly + 4, series_rgb[k]);
            font_draw(&b, lx + 22, ly, 1, CH_TEXT, s[k].label ? s[k].label : "");
        }
    }
    for (i = 0; i < h; i++) rs_to_rgb888(RS_FMT_XRGB8888, px + (size_t)i * (size_t)w, w, rgb + (size_t)i * (size_t)w * 3);
    st = png_write_rgb(path, w, h, rgb, (size_t)w * 3, err);
    free(px);
    free(rgb);
    return st;
}
