/* platform/bench_chart.h — a line chart drawn by bitrain itself into a PNG (libpng through
 * platform/png_io.h, text in the HUD font platform/font.c): `bitrain bench --chart`'s
 * frame time along the camera path, one line per configuration. */
#ifndef BR_BENCH_CHART_H
#define BR_BENCH_CHART_H
#include "platform/err.h"

#define CHART_MAX_SERIES 8

typedef struct chart_series {
    const char *label;          /* legend text */
    const double *y;            /* n values, y[i] at x = i (negative or non-finite: skipped) */
    int n;
} chart_series;

/* Writes a w x h chart (w >= 240, h >= 160) of ns series (1 .. CHART_MAX_SERIES) to path:
 * title on top, y axis from 0 to a round number above the largest value with labelled
 * ticks and grid lines, x axis 0 .. the longest series' n - 1 with labelled ticks, axis
 * labels, a legend.  BR_E_ARG for bad arguments, the PNG writer's error otherwise. */
br_status chart_png(const char *path, int w, int h, const char *title, const char *xlabel, const char *ylabel,
                    const chart_series *s, int ns, br_err *err);

#endif
