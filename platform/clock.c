#define _POSIX_C_SOURCE 200809L   /* clock_gettime under -std=c99 */
/* platform/clock.c — see clock.h. */
#include "platform/clock.h"
#include <time.h>

double br_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

int br_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
