/* tests/test_limits.c — what a file may cost before it is refused (issue 16):
 * devices and directories are not read, a file beyond what its format can
 * hold is refused from its size, and compressed members stop inflating at the
 * size their container declares or their format can take. */
#define _POSIX_C_SOURCE 200809L   /* truncate: a sparse file */
#include <unistd.h>
#include "tests/test.h"
#include "tests/zipmk.h"
#include "platform/load.h"

static br_status load_path(const char *path)
{
    hf f;
    br_err e;
    br_status s;
    memset(&e, 0, sizeof e);
    s = dem_load(path, NULL, &f, &e);
    if (s == BR_OK) dem_free(&f);
    else CHECK_MSG(strstr(e.msg, path) != NULL, "message '%s' lacks the path", e.msg);
    return s;
}

static br_status load_mem(const char *name, const unsigned char *p, size_t n)
{
    hf f;
    br_err e;
    br_status s = dem_load_mem(name, p, n, NULL, &f, &e);
    if (s == BR_OK) dem_free(&f);
    else fprintf(stderr, "  (%s)\n", e.msg);
    return s;
}

static void test_not_regular(void)
{
    CHECK_EQ(load_path("/dev/zero"), BR_E_IO);        /* would read without end */
    CHECK_EQ(load_path(t_outdir()), BR_E_IO);         /* a directory */
    CHECK_EQ(load_path("/nonexistent/N47E009.hgt"), BR_E_IO);
}

/* A sparse 600 MB file named .hgt: more than any .hgt (2 x 16385^2 bytes) can
 * be, refused from its size without reading it. */
static void test_file_cap(void)
{
    char path[512];
    FILE *fp;
    snprintf(path, sizeof path, "%s/N47E009_huge.hgt", t_outdir());
    fp = fopen(path, "wb");
    CHECK(fp != NULL);
    if (!fp) return;
    fclose(fp);
    CHECK_EQ(truncate(path, 600000000L), 0);
    CHECK_EQ(load_path(path), BR_E_TOO_BIG);
    remove(path);
}

/* n bytes of zeros, deflated in pieces (no n-byte buffer) with wbits as zlib */
static unsigned char *deflate_zeros(size_t n, int wbits, size_t *outn)
{
    static unsigned char zero[1 << 16];
    z_stream zs;
    size_t cap = n / 500 + 4096, left = n;
    unsigned char *o = malloc(cap);
    int r = Z_OK;
    memset(&zs, 0, sizeof zs);
    if (!o || deflateInit2(&zs, 9, Z_DEFLATED, wbits, 8, Z_DEFAULT_STRATEGY) != Z_OK) { free(o); return NULL; }
    zs.next_out = o;
    zs.avail_out = (uInt)cap;
    while (r != Z_STREAM_END) {
        size_t k = left < sizeof zero ? left : sizeof zero;
        zs.next_in = zero;
        zs.avail_in = (uInt)k;
        left -= k;
        r = deflate(&zs, left ? Z_NO_FLUSH : Z_FINISH);
        if (r == Z_STREAM_ERROR || zs.avail_out == 0) { deflateEnd(&zs); free(o); return NULL; }
    }
    *outn = zs.total_out;
    deflateEnd(&zs);
    return o;
}

static void test_inflate_caps(void)
{
    size_t zn = 0, hn = 0;
    unsigned char *z, *hgt = t_read_file(t_data("hgt/N47E009.hgt"), &hn);
    const size_t big = (size_t)64 << 20;
    CHECK(hgt != NULL);
    /* gzip whose trailer says a 61x61 tile (7442 bytes) but that inflates to
     * 64 MiB: stops one byte past the declared size */
    z = deflate_zeros(big, 15 + 16, &zn);
    CHECK(z != NULL);
    if (z) {
        t_put32(z + zn - 4, 7442);
        CHECK_EQ(load_mem("N47E009.hgt.gz", z, zn), BR_E_TOO_BIG);
        free(z);
    }
    /* zip member declared bigger than any .hgt: refused before inflating */
    if (hgt) {
        unsigned char *zip = t_zip("N47E009.hgt", hgt, 7442, 1, &zn);
        CHECK(zip != NULL);
        if (zip) {
            CHECK_EQ(load_mem("N47E009.zip", zip, zn), BR_OK);
            t_put32(zip + zn - 22 - 46 - 11 + 24, 600000000UL);      /* central directory: uncompressed size */
            CHECK_EQ(load_mem("N47E009.zip", zip, zn), BR_E_TOO_BIG);
            free(zip);
        }
    }
    /* zip member declared 7442 bytes whose data inflates to 64 MiB */
    {
        unsigned char *raw = deflate_zeros(big, -15, &zn), *zip;
        size_t nl = 11, total = 30 + nl + zn + 46 + nl + 22, cd = 30 + nl + zn;
        CHECK(raw != NULL);
        zip = raw ? calloc(total, 1) : NULL;
        if (zip) {
            t_put32(zip, 0x04034b50UL); t_put16(zip + 4, 20); t_put16(zip + 8, 8);
            t_put32(zip + 18, (unsigned long)zn); t_put32(zip + 22, 7442); t_put16(zip + 26, (unsigned)nl);
            memcpy(zip + 30, "N47E009.hgt", nl);
            memcpy(zip + 30 + nl, raw, zn);
            t_put32(zip + cd, 0x02014b50UL); t_put16(zip + cd + 4, 20); t_put16(zip + cd + 6, 20);
            t_put16(zip + cd + 10, 8); t_put32(zip + cd + 20, (unsigned long)zn); t_put32(zip + cd + 24, 7442);
            t_put16(zip + cd + 28, (unsigned)nl);
            memcpy(zip + cd + 46, "N47E009.hgt", nl);
            t_put32(zip + cd + 46 + nl, 0x06054b50UL); t_put16(zip + cd + 46 + nl + 8, 1);
            t_put16(zip + cd + 46 + nl + 10, 1); t_put32(zip + cd + 46 + nl + 12, 46 + (unsigned long)nl);
            t_put32(zip + cd + 46 + nl + 16, (unsigned long)cd);
            CHECK_EQ(load_mem("N47E009.zip", zip, total), BR_E_TOO_BIG);
        }
        free(zip);
        free(raw);
    }
    free(hgt);
}

int main(void)
{
    T_RUN(test_not_regular);
    T_RUN(test_file_cap);
    T_RUN(test_inflate_caps);
    return t_finish();
}
