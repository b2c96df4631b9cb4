/* core/bt_blob.c — a built hierarchy saved as bytes and attached read-only
 * (contract: core/bitree.h "Saved trees").
 *
 * Blob: a 64-byte header of little-endian 32-bit words, then the node array
 * (nslot little-endian uint32, the layout of core/bitree.h LAYOUT):
 *   0 magic "BTRE"   1 version (BT_BLOB_VERSION)   2 header bytes (64)
 *   3 w   4 h   5 k (padded side 2^k + 1)   6 metric   7 zmin   8 zmax
 *   9 nvalid (< 2^31: w*h <= BR_MAX_SAMPLES)   10 nslot
 *   11 FNV-1a (32-bit) of the heightfield: w, h, every height (the tree does not
 *      depend on the units or the spacing)
 *   12 FNV-1a (32-bit) of the node array's bytes (as saved: little-endian)
 *   13 FNV-1a (32-bit) of words 0 .. 12   14, 15 zero
 * Attach checks every word against the heightfield it is given (the layout and
 * the statistics recomputed, not trusted) and both checksums, so a blob that is
 * truncated, corrupt, for another grid or from another version is refused before
 * anything points into it.  The node values need no further check for memory
 * safety: the walk indexes only wz_lo/wz_hi[256] with their bytes.  The node
 * array is used in place (4-byte aligned), so it may live in read-only memory: the
 * selection never writes it (bt_tree.node is const).  In place means in the host's
 * byte order: attach checks the node checksum over the values as read, written
 * little-endian, so a saved blob attaches as it is on a little-endian host, and a
 * big-endian host first turns the node words around (bt_blob_to_host); the blob's
 * bytes, and so the file, are the same on every host. */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"

#define HDR_WORDS 16
#define HDR_BYTES (4 * HDR_WORDS)

static uint32_t fnv32(uint32_t h, const uint8_t *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) h = (h ^ p[i]) * 16777619u;
    return h;
}

static uint32_t fnv32_word(uint32_t h, uint32_t v)
{
    uint8_t b[4];
    b[0] = (uint8_t)v; b[1] = (uint8_t)(v >> 8); b[2] = (uint8_t)(v >> 16); b[3] = (uint8_t)(v >> 24);
    return fnv32(h, b, 4);
}

static uint32_t rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void wr32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v; p[1] = (uint8_t)(v >> 8); p[2] = (uint8_t)(v >> 16); p[3] = (uint8_t)(v >> 24);
}

static int little_endian(void)
{
    const uint32_t one = 1;
    return *(const uint8_t *)&one == 1;
}

/* the heightfield's fingerprint, and its statistics as bt_build computes them */
static uint32_t hf_print(const hf *f, int32_t *zmin, int32_t *zmax, int64_t *nvalid)
{
    uint32_t h = 2166136261u;
    int32_t lo = INT32_MAX, hi = INT32_MIN;
    int64_t nv = 0;
    size_t i, nn = (size_t)f->w * (size_t)f->h;
    h = fnv32_word(h, (uint32_t)f->w); h = fnv32_word(h, (uint32_t)f->h);
    for (i = 0; i < nn; i++) {
        int32_t v = f->z[i];
        h = fnv32_word(h, (uint32_t)v);
        if (v == HF_NODATA) continue;
        nv++;
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    if (lo > hi) lo = hi = 0;
    *zmin = lo; *zmax = hi; *nvalid = nv;
    return h;
}

static void header(const bt_tree *t, uint32_t hfp, uint32_t nodes, uint32_t w[HDR_WORDS])
{
    uint8_t b[HDR_BYTES];
    int i;
    memset(w, 0, sizeof(uint32_t) * HDR_WORDS);
    w[0] = 0x45525442u;      /* "BTRE" as little-endian bytes */
    w[1] = BT_BLOB_VERSION;
    w[2] = HDR_BYTES;
    w[3] = (uint32_t)t->w; w[4] = (uint32_t)t->h; w[5] = (uint32_t)t->k; w[6] = (uint32_t)t->metric;
    w[7] = (uint32_t)t->zmin; w[8] = (uint32_t)t->zmax; w[9] = (uint32_t)t->nvalid; w[10] = t->nslot;
    w[11] = hfp; w[12] = nodes;
    for (i = 0; i < 13; i++) wr32(b + 4 * i, w[i]);
    w[13] = fnv32(2166136261u, b, 52);
}

size_t bt_tree_blob_size(const bt_tree *t)
{
    if (!t || !t->node || !t->nslot) return 0;
    return HDR_BYTES + (size_t)t->nslot * 4;
}

br_status bt_tree_save(const bt_tree *t, void *buf, size_t bytes)
{
    uint8_t *p = (uint8_t *)buf;
    uint32_t w[HDR_WORDS], i, ck = 2166136261u;
    int32_t zl, zh;
    int64_t nv;
    if (!t || !t->node || !t->f || !buf || bytes < bt_tree_blob_size(t) || !bt_tree_blob_size(t)) return BR_E_ARG;
    for (i = 0; i < t->nslot; i++) {
        wr32(p + HDR_BYTES + 4 * (size_t)i, t->node[i]);
        ck = fnv32(ck, p + HDR_BYTES + 4 * (size_t)i, 4);
    }
    header(t, hf_print(t->f, &zl, &zh, &nv), ck, w);
    for (i = 0; i < HDR_WORDS; i++) wr32(p + 4 * i, w[i]);
    return BR_OK;
}

void bt_blob_to_host(void *blob, size_t bytes)
{
    uint8_t *p = (uint8_t *)blob;
    size_t i;
    if (little_endian() || !blob || bytes < HDR_BYTES) return;
    for (i = HDR_BYTES; i + 4 <= bytes; i += 4) {
        uint32_t v = rd32(p + i);
        memcpy(p + i, &v, 4);
    }
}

br_status bt_attach(bt_tree *t, const hf *f, const void *blob, size_t bytes, uint8_t *st, size_t st_bytes)
{
    const uint8_t *p = (const uint8_t *)blob;
    bt_tree nt;
    uint32_t w[HDR_WORDS], i;
    int32_t k;
    if (!t || !f || !blob || bytes < HDR_BYTES || ((uintptr_t)blob & 3) != 0) return BR_E_ARG;
    if (hf_validate(f) != BR_OK || f->w < 2 || f->h < 2) return BR_E_ARG;
    if (rd32(p + 52) != fnv32(2166136261u, p, 52)) return BR_E_ARG;
    if (rd32(p) != 0x45525442u || rd32(p + 4) != BT_BLOB_VERSION || rd32(p + 8) != HDR_BYTES) return BR_E_ARG;
    if ((int32_t)rd32(p + 12) != f->w || (int32_t)rd32(p + 16) != f->h) return BR_E_ARG;
    memset(&nt, 0, sizeof nt);
    nt.f = f; nt.w = f->w; nt.h = f->h;
    for (k = 1; ((int32_t)1 << k) + 1 < (f->w > f->h ? f->w : f->h); k++) {}
    nt.k = k;
    nt.n = ((int32_t)1 << k) + 1;
    bti_layout(&nt.lay, nt.w, nt.h, nt.n, &nt.nslot);
    if (rd32(p + 20) != (uint32_t)k || rd32(p + 40) != nt.nslot) return BR_E_ARG;
    if ((uint64_t)nt.nslot * 4 > (uint64_t)(SIZE_MAX - HDR_BYTES) || bytes - HDR_BYTES < (size_t)nt.nslot * 4)
        return BR_E_ARG;
    nt.metric = (int32_t)rd32(p + 24);
    if (nt.metric != BT_METRIC_EXACT && nt.metric != BT_METRIC_CURVATURE) return BR_E_ARG;
    if (st && st_bytes < bt_state_size(nt.nslot)) return BR_E_ARG;
    /* the heightfield: fingerprint and statistics; then the node array's checksum;
     * finally the whole header as this tree would write it */
    {
        const uint32_t *node = (const uint32_t *)(const void *)(p + HDR_BYTES);
        uint32_t ck = 2166136261u, hfp;
        for (i = 0; i < nt.nslot; i++) ck = fnv32_word(ck, node[i]);
        hfp = hf_print(f, &nt.zmin, &nt.zmax, &nt.nvalid);
        header(&nt, hfp, ck, w);
        for (i = 0; i < HDR_WORDS; i++)
            if (rd32(p + 4 * i) != w[i]) return BR_E_ARG;
    }
    nt.node = (const uint32_t *)(const void *)(p + HDR_BYTES);
    nt.sum = bti_node_sum(nt.node, nt.nslot);
    nt.st = st;
    if (st) memset(st, 0, bt_state_size(nt.nslot));
    *t = nt;
    return BR_OK;
}
