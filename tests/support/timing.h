/* tests/support/timing.h — wall-clock helpers for the benchmark programs
 * (linked into every test and benchmark program with the rest of tests/support).
 * Benchmarks report medians: the machines are shared and noisy. */
#ifndef BR_TIMING_H
#define BR_TIMING_H

double tm_now_ms(void);                 /* CLOCK_MONOTONIC in milliseconds */
double tm_median(double *v, int n);     /* sorts v in place, returns the median (upper middle) */

#endif
