/* tests/support/blob_sums.h — makes a saved bitree's checksums right again after its
 * bytes were changed (core/bt_blob.c's format: the node checksum, FNV-1a of the node
 * array as saved, in header word 12; the header's, FNV-1a of bytes 0 .. 51, in word
 * 13), so that a forged blob attaches.  For tests and fuzz harnesses: header-only,
 * as the harnesses link no test support objects. */
#ifndef BR_TEST_BLOB_SUMS_H
#define BR_TEST_BLOB_SUMS_H
#include <stddef.h>
#include <stdint.h>

#define BLOB_HDR 64         /* header bytes before the node array */

static inline uint32_t blob_fnv32(uint32_t h, const uint8_t *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) h = (h ^ p[i]) * 16777619u;
    return h;
}

static inline void blob_put_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v; p[1] = (uint8_t)(v >> 8); p[2] = (uint8_t)(v >> 16); p[3] = (uint8_t)(v >> 24);
}

/* blob: n bytes as saved (little-endian words, before bt_blob_to_host), n >= BLOB_HDR */
static inline void blob_fix_sums(uint8_t *blob, size_t n)
{
    blob_put_le32(blob + 48, blob_fnv32(2166136261u, blob + BLOB_HDR, n - BLOB_HDR));
    blob_put_le32(blob + 52, blob_fnv32(2166136261u, blob, 52));
}

#endif
