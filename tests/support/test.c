/* The harness behind tests/test.h. */
#include "tests/test.h"
#include <sys/stat.h>

int t_passed, t_failed, t_skipped, t_cur_failed;
const char *t_cur_name = "";

void t_run(const char *name, void (*fn)(void))
{
    t_cur_name = name;
    t_cur_failed = 0;
    fn();
    if (t_cur_failed) { t_failed++; fprintf(stderr, "  %s: failed\n", name); }
    else t_passed++;
}

void t_skip(const char *name, const char *why)
{
    t_skipped++;
    fprintf(stderr, "  %s: skipped (%s)\n", name, why);
}

int t_emulated(void)
{
    return getenv("BITRAIN_EMULATED") != NULL;
}

int t_finish(void)
{
    if (t_skipped) printf("%d passed, %d failed, %d skipped\n", t_passed, t_failed, t_skipped);
    else printf("%d passed, %d failed\n", t_passed, t_failed);
    return t_failed ? 1 : 0;
}

const char *t_data(const char *rel)
{
    static char buf[8][1024];
    static int k;
    const char *root = getenv("BITRAIN_DATA");
    char *b = buf[k++ & 7];
    snprintf(b, sizeof buf[0], "%s/%s", root ? root : "../shared/data/dem", rel);
    return b;
}

const char *t_outdir(void)
{
    mkdir("tests/out", 0777);
    return "tests/out";
}

unsigned char *t_read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    unsigned char *p = NULL;
    long n;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0) {
        p = malloc((size_t)n + 1);
        if (p && fread(p, 1, (size_t)n, f) != (size_t)n) { free(p); p = NULL; }
        if (p) *len = (size_t)n;
    }
    fclose(f);
    return p;
}

int t_write_file(const char *path, const void *p, size_t len)
{
    FILE *f = fopen(path, "wb");
    int ok;
    if (!f) return 0;
    ok = fwrite(p, 1, len, f) == len;
    return fclose(f) == 0 && ok;
}

uint64_t t_xs64(void)
{
    static uint64_t x = 0x9e3779b97f4a7c15u;
    x ^= x << 13; x ^= x >> 7; x ^= x << 17;
    return x;
}
