/* tests/zipmk.h — build .gz and .zip containers in memory for the loader tests
 * (one member; deflated or stored).  Results are malloc'd; NULL on failure. */
#ifndef BR_TESTS_ZIPMK_H
#define BR_TESTS_ZIPMK_H
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

static inline unsigned char *t_deflate(const unsigned char *p, size_t n, int wbits, size_t *outn)
{
    z_stream zs;
    size_t cap = compressBound((uLong)n) + 64;
    unsigned char *o = malloc(cap);
    memset(&zs, 0, sizeof zs);
    if (!o || deflateInit2(&zs, 6, Z_DEFLATED, wbits, 8, Z_DEFAULT_STRATEGY) != Z_OK) { free(o); return NULL; }
    zs.next_in = (Bytef *)(size_t)p;
    zs.avail_in = (uInt)n;
    zs.next_out = o;
    zs.avail_out = (uInt)cap;
    if (deflate(&zs, Z_FINISH) != Z_STREAM_END) { deflateEnd(&zs); free(o); return NULL; }
    *outn = zs.total_out;
    deflateEnd(&zs);
    return o;
}

static inline unsigned char *t_gzip(const unsigned char *p, size_t n, size_t *outn)
{
    return t_deflate(p, n, 15 + 16, outn);
}

static inline void t_put16(unsigned char *q, unsigned v) { q[0] = (unsigned char)v; q[1] = (unsigned char)(v >> 8); }
static inline void t_put32(unsigned char *q, unsigned long v)
{
    t_put16(q, (unsigned)(v & 0xffff));
    t_put16(q + 2, (unsigned)(v >> 16));
}

/* A zip archive with one member called name; deflated when deflate != 0. */
static inline unsigned char *t_zip(const char *name, const unsigned char *p, size_t n, int deflate, size_t *outn)
{
    size_t cn = n, nl = strlen(name), total, off = 0;
    unsigned char *c = deflate ? t_deflate(p, n, -15, &cn) : (unsigned char *)(size_t)p;
    unsigned char *z;
    unsigned long crc = crc32(0L, p, (uInt)n);
    if (!c) return NULL;
    total = 30 + nl + cn + 46 + nl + 22;
    z = calloc(total, 1);
    if (!z) { if (deflate) free(c); return NULL; }
    t_put32(z, 0x04034b50UL); t_put16(z + 4, 20); t_put16(z + 8, deflate ? 8 : 0);
    t_put32(z + 14, crc); t_put32(z + 18, (unsigned long)cn); t_put32(z + 22, (unsigned long)n);
    t_put16(z + 26, (unsigned)nl);
    memcpy(z + 30, name, nl);
    memcpy(z + 30 + nl, c, cn);
    off = 30 + nl + cn;
    t_put32(z + off, 0x02014b50UL); t_put16(z + off + 4, 20); t_put16(z + off + 6, 20);
    t_put16(z + off + 10, deflate ? 8 : 0); t_put32(z + off + 16, crc);
    t_put32(z + off + 20, (unsigned long)cn); t_put32(z + off + 24, (unsigned long)n);
    t_put16(z + off + 28, (unsigned)nl); t_put32(z + off + 42, 0);
    memcpy(z + off + 46, name, nl);
    t_put32(z + off + 46 + nl, 0x06054b50UL);
    t_put16(z + off + 46 + nl + 8, 1); t_put16(z + off + 46 + nl + 10, 1);
    t_put32(z + off + 46 + nl + 12, (unsigned long)(46 + nl)); t_put32(z + off + 46 + nl + 16, (unsigned long)off);
    if (deflate) free(c);
    *outn = total;
    return z;
}

#endif
