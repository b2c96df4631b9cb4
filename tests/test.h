/* tests/test.h — the tiny harness every test program uses.
 *
 * A test program is a main() that calls T_RUN(fn) for each test function; a
 * test function uses CHECK/CHECK_EQ and returns.  The program prints one line per
 * failed check, ends with "N passed, N failed" and exits non-zero on any failure.
 * Counting is per test function: a function with any failed check counts once as
 * failed.  Paths to the shared data are built with t_data("hgt/N47E009.hgt"). */
#ifndef BR_TEST_H
#define BR_TEST_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>

extern int t_passed, t_failed, t_skipped, t_cur_failed;
extern const char *t_cur_name;

#define CHECK(cond) do { if (!(cond)) { t_cur_failed++; \
    fprintf(stderr, "FAIL %s: %s:%d: %s\n", t_cur_name, __FILE__, __LINE__, #cond); } } while (0)
#define CHECK_MSG(cond, ...) do { if (!(cond)) { t_cur_failed++; \
    fprintf(stderr, "FAIL %s: %s:%d: %s: ", t_cur_name, __FILE__, __LINE__, #cond); \
    fprintf(stderr, __VA_ARGS__); fputc('\n', stderr); } } while (0)
#define CHECK_EQ(a, b) do { long long t_a_ = (long long)(a), t_b_ = (long long)(b); \
    if (t_a_ != t_b_) { t_cur_failed++; fprintf(stderr, "FAIL %s: %s:%d: %s == %s (%lld != %lld)\n", \
    t_cur_name, __FILE__, __LINE__, #a, #b, t_a_, t_b_); } } while (0)
#define T_RUN(fn) t_run(#fn, fn)

void t_run(const char *name, void (*fn)(void));
/* A check that cannot run here (why: what it needs): counted and printed, never
 * dropped silently; the summary then ends ", N skipped". */
void t_skip(const char *name, const char *why);
int t_finish(void);                 /* prints the summary; returns the exit code */
/* 1 under qemu-user (tests/cross/suite.sh sets BITRAIN_EMULATED): the programs then
 * run their sanitized-run sizes, where the emulator's 5-10x would not fit make test */
int t_emulated(void);
const char *t_data(const char *rel);/* "../shared/data/dem/" + rel (BITRAIN_DATA overrides) */
const char *t_outdir(void);         /* tests/out, created on demand */
unsigned char *t_read_file(const char *path, size_t *len); /* malloc'd, NULL on error */
int t_write_file(const char *path, const void *p, size_t len);
/* xorshift64 from a fixed seed, one sequence a program: the same draws on every target */
uint64_t t_xs64(void);

#endif
