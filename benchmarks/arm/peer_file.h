/* benchmarks/arm/peer_file.h — the peer scene as a raw file, so the rasteriser can be
 * driven on a foreign architecture (qemu-user, static binary, no libpng there).
 * Written by peer_dump.c (native, libbitrain + libpng), read by peer_run.c (core/ +
 * raster/ only).  Every field is a 32-bit little-endian word, independent of the host:
 *   "BRPS" 1                                   magic, format version
 *   nv, then nv x (x, y, z, rgb)               rs_vertex p[] (1/PEER_UNIT peer units), 0xRRGGBB
 *   nstrip, len, then nstrip*len indices       the row strips (RS_STRIP)
 *   ncam, then ncam x (code, eye[3], target[3], fovy_mdeg, znear, zfar)
 *                                              peer_camera()'s integer form, code 'A'/'B'
 * Also the frame checksum both sides print: 64-bit FNV-1a over the XRGB8888 pixel values,
 * row by row, each value fed as 4 bytes little-endian (so it does not depend on the
 * host's byte order). */
#ifndef BR_PEER_FILE_H
#define BR_PEER_FILE_H
#include <stddef.h>
#include <stdint.h>

#define PF_MAGIC 0x53505242u   /* "BRPS" read as a little-endian word */
#define PF_VERSION 1u

static inline uint64_t pf_checksum(const uint32_t *px, int32_t w, int32_t h, size_t stride_px)
{
    uint64_t s = 0xcbf29ce484222325ull;
    int32_t i, j, k;
    for (j = 0; j < h; j++)
        for (i = 0; i < w; i++) {
            uint32_t v = px[(size_t)j * stride_px + (size_t)i];
            for (k = 0; k < 4; k++) { s ^= (v >> (8 * k)) & 0xffu; s *= 0x100000001b3ull; }
        }
    return s;
}

#endif
