/* tests/cross/xdet.c — determinism probe: runs core/ (and raster/) on real terrain
 * and prints one FNV-1a hash per stage.  tests/cross/run.sh builds it for several
 * architectures (32/64-bit, little/big endian) and compilers, runs them (under
 * qemu-user for foreign ones) and requires identical output: invariant 3 of
 * DESIGN.md.  Only core/ and raster/ are linked, plus stdio here to read the
 * SRTM file and print. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/shade.h"
#include "tests/cross/xdet_stages.h"

uint32_t xdet_fnv(uint32_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    while (n--) { h ^= *b++; h *= 16777619u; }
    return h;
}

uint32_t xdet_fnv_i32(uint32_t h, int32_t v)
{
    unsigned char b[4];
    b[0] = (unsigned char)v; b[1] = (unsigned char)(v >> 8);
    b[2] = (unsigned char)(v >> 16); b[3] = (unsigned char)(v >> 24);
    return xdet_fnv(h, b, 4);
}

static uint32_t stage_shade(const hf *f)
{
    shade_ctx c;
    fx_q14 l[3] = { -8192, 8192, 11585 }, n[3];
    uint8_t *row = malloc((size_t)f->w);
    uint32_t h = 2166136261u;
    int32_t x, y;
    shade_init(&c, f);
    for (y = 0; y < f->h; y++) {
        shade_hill_row(&c, y, l, row);
        h = xdet_fnv(h, row, (size_t)f->w);
        for (x = 0; x < f->w; x += 97) {
            shade_normal(&c, x, y, n);
            h = xdet_fnv_i32(xdet_fnv_i32(xdet_fnv_i32(h, n[0]), n[1]), n[2]);
        }
    }
    free(row);
    return h;
}

int main(int argc, char **argv)
{
    /* a 513x513 window of N47E009 (lake and Alps), south-east part of the tile */
    enum { N = 513, X0 = 400, Y0 = 600, SIDE = 1201 };
    static int32_t z[N * N];
    unsigned char *raw;
    FILE *fp;
    hf f;
    int32_t x, y;
    if (argc < 2) { fprintf(stderr, "usage: xdet N47E009.hgt\n"); return 2; }
    fp = fopen(argv[1], "rb");
    raw = malloc((size_t)SIDE * SIDE * 2);
    if (!fp || !raw || fread(raw, 2, (size_t)SIDE * SIDE, fp) != (size_t)SIDE * SIDE) {
        fprintf(stderr, "xdet: cannot read %s\n", argv[1]);
        return 1;
    }
    fclose(fp);
    for (y = 0; y < N; y++)
        for (x = 0; x < N; x++) {
            const unsigned char *p = raw + 2 * ((size_t)(Y0 + y) * SIDE + (size_t)(X0 + x));
            z[y * N + x] = (int16_t)(uint16_t)((p[0] << 8) | p[1]);
        }
    free(raw);
    memset(&f, 0, sizeof f);
    f.w = N; f.h = N; f.z = z; f.z_num = 1; f.z_den = 1;
    f.dx_um = 62786282; f.dy_um = 92650490;
    printf("shade %08lx\n", (unsigned long)stage_shade(&f));
    xdet_stages(&f);
    return 0;
}
