/* platform/opt.c — see opt.h. */
#include "platform/opt.h"
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int opt_fail(const char *cmd, const char *option, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "bitrain %s: %s: ", cmd, option);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return OPT_ERR;
}

/* A finite decimal number filling [s, end) exactly (strtod also takes "nan", "inf" and
 * hexadecimal: refused). */
static int read_number(const char *s, const char *end, double *out)
{
    char buf[64], *stop;
    size_t n = (size_t)(end - s);
    if (n == 0 || n >= sizeof buf) return 0;
    memcpy(buf, s, n);
    buf[n] = 0;
    if (strpbrk(buf, "xXnNiI")) return 0;               /* hex, nan, inf */
    errno = 0;
    *out = strtod(buf, &stop);
    return stop == buf + n && errno == 0 && isfinite(*out);
}

static void range_text(const opt_spec *o, char *buf, size_t len)
{
    if (o->kind == OPT_NUM || o->kind == OPT_NUMS) snprintf(buf, len, "%g..%g", o->lo, o->hi);
    else snprintf(buf, len, "%.0f..%.0f", o->lo, o->hi);
}

static int whole(double v) { return v == floor(v); }

/* The string options opt_parse remembers (a command has far fewer; one first given past
 * this many would not be refused when given again). */
#define OPT_MAX_STRS 64

/* Reads a value of kind o->kind from v into o->dst; OPT_ERR with a message. */
static int take_value(const char *cmd, const opt_spec *o, const char *v)
{
    char range[64];
    double x[8];
    range_text(o, range, sizeof range);
    switch (o->kind) {
    case OPT_INT: case OPT_LONG: case OPT_INT_OPT: case OPT_NUM:
        if (!read_number(v, v + strlen(v), &x[0]))
            return opt_fail(cmd, o->name, "'%s' is not a number (accepted: %s)", v, range);
        if (o->kind != OPT_NUM && !whole(x[0]))
            return opt_fail(cmd, o->name, "'%s' is not a whole number (accepted: %s)", v, range);
        if (x[0] < o->lo || x[0] > o->hi)
            return opt_fail(cmd, o->name, "%s is out of range (accepted: %s)", v, range);
        if (o->kind == OPT_NUM) *(double *)o->dst = x[0];
        else if (o->kind == OPT_LONG) *(long *)o->dst = (long)x[0];
        else *(int *)o->dst = (int)x[0];
        return OPT_OK;
    case OPT_NUMS: {
        const char *p = v;
        int i;
        for (i = 0; i < o->n; i++) {
            const char *e = strchr(p, ',');
            if (!e) e = p + strlen(p);
            if ((i < o->n - 1) != (*e == ',') || !read_number(p, e, &x[i]))
                return opt_fail(cmd, o->name, "'%s' is not %s (%d comma-separated numbers, each %s)", v,
                                o->meta ? o->meta : "a list", o->n, range);
            if (x[i] < o->lo || x[i] > o->hi)
                return opt_fail(cmd, o->name, "'%s': %g is out of range (accepted: %s)", v, x[i], range);
            p = e + 1;
        }
        for (i = 0; i < o->n; i++) ((double *)o->dst)[i] = x[i];
        return OPT_OK;
    }
    case OPT_SIZE: {
        const char *xs = strchr(v, 'x');
        if (!xs || !read_number(v, xs, &x[0]) || !read_number(xs + 1, xs + strlen(xs), &x[1])
            || !whole(x[0]) || !whole(x[1]) || x[0] < o->lo || x[0] > o->hi || x[1] < o->lo || x[1] > o->hi)
            return opt_fail(cmd, o->name, "'%s' is not WxH (W and H whole numbers %s)", v, range);
        ((int *)o->dst)[0] = (int)x[0];
        ((int *)o->dst)[1] = (int)x[1];
        return OPT_OK;
    }
    case OPT_STR:
        if (!v[0]) return opt_fail(cmd, o->name, "needs a non-empty value");
        *(const char **)o->dst = v;
        return OPT_OK;
    case OPT_STRS: {
        opt_strs *l = (opt_strs *)o->dst;
        if (!v[0]) return opt_fail(cmd, o->name, "needs a non-empty value");
        if (l->n >= l->max) return opt_fail(cmd, o->name, "'%s': at most %d are accepted", v, l->max);
        l->v[l->n++] = v;
        return OPT_OK;
    }
    case OPT_CHOICE: {
        const char *p = o->choices;
        int k = 0;
        size_t n = strlen(v);
        while (p && *p) {
            const char *e = strchr(p, '|');
            size_t len = e ? (size_t)(e - p) : strlen(p);
            if (len == n && !strncmp(p, v, n)) { *(int *)o->dst = k; return OPT_OK; }
            k++;
            p = e ? e + 1 : NULL;
        }
        return opt_fail(cmd, o->name, "'%s' is not one of %s", v, o->choices);
    }
    case OPT_FLAG: break;
    }
    return OPT_OK;
}

static const opt_spec *find(const opt_spec *const *tables, const char *name)
{
    int t;
    for (t = 0; tables[t]; t++) {
        const opt_spec *o;
        for (o = tables[t]; o->name; o++)
            if (!strcmp(o->name, name)) return o;
    }
    return NULL;
}

static int looks_like_number(const char *s)
{
    double x;
    return s && read_number(s, s + strlen(s), &x);
}

/* Whether OPT_STR o was given before on this command line (its destination may hold a
 * default, so that cannot tell): strs[0..*n) are those given so far; o is added while
 * there is room. */
static int str_given_before(const opt_spec **strs, int *n, const opt_spec *o)
{
    int j;
    for (j = 0; j < *n; j++)
        if (strs[j] == o) return 1;
    if (*n < OPT_MAX_STRS) strs[(*n)++] = o;
    return 0;
}

int opt_parse(const char *cmd, const char *synopsis, const opt_spec *const *tables, int argc, char **argv,
              const char **pos, int maxpos, int *npos)
{
    const opt_spec *strs[OPT_MAX_STRS];
    int i, only_pos = 0, nstrs = 0;
    *npos = 0;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];
        const opt_spec *o;
        if (!only_pos && (!strcmp(a, "-h") || !strcmp(a, "--help"))) {
            opt_help(stdout, cmd, synopsis, tables);
            return OPT_HELP;
        }
        if (!only_pos && !strcmp(a, "--")) { only_pos = 1; continue; }
        if (only_pos || a[0] != '-' || !a[1] || looks_like_number(a)) {
            if (*npos >= maxpos) {
                fprintf(stderr, "bitrain %s: too many inputs (at most %d): '%s'\n", cmd, maxpos, a);
                return OPT_ERR;
            }
            pos[(*npos)++] = a;
            continue;
        }
        o = find(tables, a);
        if (!o) {
            fprintf(stderr, "bitrain %s: unknown option '%s' (`bitrain %s --help` lists them)\n", cmd, a, cmd);
            return OPT_ERR;
        }
        if (o->seen) *o->seen = 1;
        if (o->kind == OPT_FLAG) { *(int *)o->dst = 1; continue; }
        if (o->kind == OPT_INT_OPT) {
            if (i + 1 < argc && looks_like_number(argv[i + 1])) {
                if (take_value(cmd, o, argv[++i]) != OPT_OK) return OPT_ERR;
            } else *(int *)o->dst = (int)o->lo;
            continue;
        }
        if (i + 1 >= argc) return opt_fail(cmd, a, "needs a value%s%s", o->meta ? " " : "", o->meta ? o->meta : "");
        if (o->kind == OPT_STR && str_given_before(strs, &nstrs, o))
            return opt_fail(cmd, a, "given twice ('%s', then '%s'): it takes one %s", *(const char **)o->dst,
                            argv[i + 1], o->meta ? o->meta : "value");
        if (take_value(cmd, o, argv[++i]) != OPT_OK) return OPT_ERR;
    }
    return OPT_OK;
}

void opt_help(FILE *f, const char *cmd, const char *synopsis, const opt_spec *const *tables)
{
    int t;
    fprintf(f, "usage: bitrain %s %s\n", cmd, synopsis);
    for (t = 0; tables[t]; t++) {
        const opt_spec *o;
        for (o = tables[t]; o->name; o++) {
            char head[64], range[64] = "";
            snprintf(head, sizeof head, "%s%s%s", o->name, o->meta ? " " : "", o->meta ? o->meta : "");
            if (o->kind == OPT_CHOICE) snprintf(range, sizeof range, " (%s)", o->choices);
            else if (o->kind != OPT_FLAG && o->kind != OPT_STR && o->kind != OPT_STRS) {
                char r[48];
                range_text(o, r, sizeof r);
                snprintf(range, sizeof range, " (%s)", r);
            }
            fprintf(f, "  %-22s %s%s\n", head, o->help ? o->help : "", range);
        }
    }
}
