/* tests/support/btcheck.h — helpers shared by the bitree tests (tests/test_bitree.c,
 * tests/test_bitree_big.c): loading a DEM of ../shared/data/dem, a mesh sized for a
 * selection, the mesh's strip decoded for the referee (tests/support/meshcheck.h),
 * the exact hole area, and a byte hash of a mesh (determinism).  Test support only:
 * stdio and malloc. */
#ifndef BR_BTCHECK_H
#define BR_BTCHECK_H
#include <stddef.h>
#include <stdint.h>
#include "core/bitree.h"
#include "tests/support/meshcheck.h"

/* Loads ../shared/data/dem/<rel> (t_data) with default reader options; prints the
 * loader's message and returns -1 on failure. */
int btc_load(const char *rel, hf *f);

/* Extracts selection p of t into m, sized cap triangles (0: bt_count's exact count,
 * at least 2, at most 2^28).  *mem receives the mesh memory (NULL on early failure;
 * the caller frees it).  Returns 0 when bt_extract returned BR_OK. */
int btc_extract(bt_tree *t, const bt_params *p, uint32_t cap, bt_mesh *m, void **mem);

/* The mesh for the referee: *v its vertices (grid position, height in the
 * heightfield's unit, zbits 0), *s its strip, *tri the strip decoded (mc_strip_decode:
 * *nt proper triangles, *nl line triangles).  Returns 0, or -1 (no memory or a bad
 * strip); the caller frees *v, *s, *tri either way. */
int btc_decode(const bt_mesh *m, mc_vert **v, int32_t **s, int32_t **tri, int64_t *nt, int64_t *nl);

/* Doubled area an exact hole gives: unit cells are split along the diagonal through
 * their (odd, odd) corner (the finest bitree level); each half counts when its three
 * corners are valid. */
int64_t btc_exact_area2(const hf *f);

/* FNV-1a over n bytes, and over a mesh's vertices (x, y, z, morph | state << 16) and
 * strip as little-endian words: the same value on every architecture. */
uint64_t btc_fnv(uint64_t h, const void *p, size_t n);
#define BTC_FNV_INIT 1469598103934665603ull
uint64_t btc_mesh_hash(const bt_mesh *m);

#endif
