/* platform/clock.h — the two small helpers every timing and sorting place of platform/
 * shares: a monotonic clock in milliseconds and the qsort comparison of doubles. */
#ifndef BR_CLOCK_H
#define BR_CLOCK_H

/* CLOCK_MONOTONIC in milliseconds (only differences mean something). */
double br_now_ms(void);

/* qsort comparison of two doubles, ascending (-1, 0, 1; no NaN is ever sorted here). */
int br_cmp_double(const void *a, const void *b);

#endif
