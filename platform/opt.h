/* platform/opt.h — the one command-line parser every bitrain command uses.
 *
 * A command describes its options as a table of opt_spec (name, kind, destination,
 * accepted range, help line) and calls opt_parse.  Values are checked as they are read:
 * a non-number, a malformed value ("640x360x3", "1,2"), NaN, infinity or a number
 * outside [lo, hi] is refused with one line that names the command, the option, the
 * value and what is accepted, e.g.
 *     bitrain render: --size: '640x360x3' is not WxH (W and H whole numbers 1..4096)
 * and the command exits with status 2.  Nothing is clamped silently: a range is the set
 * of values that mean something, so results stay monotone in every threshold.
 * `--help`/`-h` prints the synopsis and the table (one line per option, with its range)
 * to stdout.  Options may come before, between or after the positional arguments;
 * `--` ends the options. */
#ifndef BR_OPT_H
#define BR_OPT_H
#include <stdio.h>

typedef enum opt_kind {
    OPT_FLAG,       /* no value: *(int *)dst = 1 */
    OPT_INT,        /* a whole number in [lo, hi]: *(int *)dst */
    OPT_LONG,       /* a whole number in [lo, hi] (|x| < 2^53): *(long *)dst */
    OPT_NUM,        /* a finite decimal number in [lo, hi]: *(double *)dst */
    OPT_NUMS,       /* n comma-separated finite numbers, each in [lo, hi]: double[n] at dst */
    OPT_SIZE,       /* WxH, whole numbers in [lo, hi]: int[2] at dst */
    OPT_STR,        /* a non-empty string: *(const char **)dst; given twice is an error (a
                       second file name would silently replace the first) */
    OPT_STRS,       /* a non-empty string each time the option is given, in order: an
                       opt_strs at dst; more than its max is an error */
    OPT_CHOICE,     /* one of the '|'-separated words of `choices`: *(int *)dst = its index */
    OPT_INT_OPT     /* an optional whole number in [lo, hi]: taken when the next argument is
                       one, else *(int *)dst = (int)lo (e.g. `--full [STEP]`) */
} opt_kind;

typedef struct opt_spec {
    const char *name;       /* "--size", "-o" */
    opt_kind kind;
    void *dst;
    double lo, hi;          /* accepted range (OPT_INT, OPT_LONG, OPT_NUM, OPT_NUMS, OPT_SIZE,
                               OPT_INT_OPT) */
    int n;                  /* OPT_NUMS: how many numbers */
    const char *choices;    /* OPT_CHOICE: "rgb565|rgb888" */
    const char *meta;       /* the value's name in the help: "WxH", "M" (NULL: none) */
    const char *help;       /* one line */
    int *seen;              /* optional: set to 1 when the option is given */
} opt_spec;

/* OPT_STRS's destination: v[0..n) the values given, at most max (the caller's array). */
typedef struct opt_strs { const char **v; int n, max; } opt_strs;

/* The end of a table. */
#define OPT_END { NULL, OPT_FLAG, NULL, 0, 0, 0, NULL, NULL, NULL, NULL }

enum { OPT_OK = 0, OPT_HELP = 1, OPT_ERR = 2 };

/* Parses argv[0..argc) against the tables (a NULL-terminated list of OPT_END-terminated
 * tables: a command's own and shared ones such as the reader flags).  Positional
 * arguments go to pos[0..*npos) (at most maxpos: more is an error).  Returns OPT_OK,
 * OPT_HELP (help printed to stdout) or OPT_ERR (message printed to stderr). */
int opt_parse(const char *cmd, const char *synopsis, const opt_spec *const *tables, int argc, char **argv,
              const char **pos, int maxpos, int *npos);

/* The help text: "usage: bitrain CMD SYNOPSIS" then one line per option. */
void opt_help(FILE *f, const char *cmd, const char *synopsis, const opt_spec *const *tables);

/* Prints "bitrain CMD: OPTION: MESSAGE" to stderr and returns OPT_ERR, for checks that
 * involve several options (e.g. two that exclude each other). */
int opt_fail(const char *cmd, const char *option, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
