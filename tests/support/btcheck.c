/* tests/support/btcheck.c — see btcheck.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tests/support/btcheck.h"
#include "tests/test.h"
#include "platform/load.h"

int btc_load(const char *rel, hf *f)
{
    br_err e;
    dem_opts o;
    memset(&o, 0, sizeof o);
    if (dem_load(t_data(rel), &o, f, &e) != BR_OK) { fprintf(stderr, "%s\n", e.msg); return -1; }
    return 0;
}

int btc_extract(bt_tree *t, const bt_params *p, uint32_t cap, bt_mesh *m, void **mem)
{
    size_t sz;
    uint64_t cnt = cap;
    *mem = NULL;
    if (!cap) { if (bt_count(t, p, &cnt) != BR_OK || cnt > 0x10000000u) return -1; if (cnt < 2) cnt = 2; }
    sz = bt_mesh_mem_size((uint32_t)cnt);
    *mem = malloc(sz);
    if (!*mem || bt_mesh_init(m, (uint32_t)cnt, *mem, sz) != BR_OK) return -1;
    return bt_extract(t, p, m) == BR_OK ? 0 : -1;
}

int btc_decode(const bt_mesh *m, mc_vert **v, int32_t **s, int32_t **tri, int64_t *nt, int64_t *nl)
{
    uint32_t i;
    *v = malloc(sizeof **v * ((size_t)m->nv + 1));
    *s = malloc(4 * ((size_t)m->ns + 1));
    *tri = malloc(12 * ((size_t)m->ns + 1));
    *nt = *nl = 0;
    if (!*v || !*s || !*tri) return -1;
    for (i = 0; i < m->nv; i++) { (*v)[i].x = m->v[i].x; (*v)[i].y = m->v[i].y; (*v)[i].zq = m->v[i].z; }
    for (i = 0; i < m->ns; i++) (*s)[i] = (int32_t)m->strip[i];
    return mc_strip_decode(*s, m->ns, *v, (int32_t)m->nv, *tri, nt, NULL, nl) == 0 ? 0 : -1;
}

int64_t btc_exact_area2(const hf *f)
{
    int64_t a = 0;
    int32_t x, y;
#define OK(X, Y) (f->z[(size_t)(Y) * f->w + (X)] != HF_NODATA)
    for (y = 0; y + 1 < f->h; y++)
        for (x = 0; x + 1 < f->w; x++) {
            int tl = OK(x, y), tr = OK(x + 1, y), bl = OK(x, y + 1), br = OK(x + 1, y + 1);
            if (((x ^ y) & 1) == 0) a += (tl && br && tr) + (tl && br && bl); /* diagonal tl-br */
            else a += (tr && bl && tl) + (tr && bl && br);
        }
#undef OK
    return a;
}

uint64_t btc_fnv(uint64_t h, const void *p, size_t n)
{
    const uint8_t *b = (const uint8_t *)p;
    while (n--) { h ^= *b++; h *= 1099511628211ull; }
    return h;
}

uint64_t btc_mesh_hash(const bt_mesh *m)
{
    uint64_t h = BTC_FNV_INIT;
    uint32_t i;
    for (i = 0; i < m->nv; i++) {
        int32_t q[4] = { m->v[i].x, m->v[i].y, m->v[i].z, m->v[i].morph | (m->v[i].state << 16) };
        uint8_t le[16];
        int k;
        for (k = 0; k < 16; k++) le[k] = (uint8_t)((uint32_t)q[k / 4] >> (8 * (k % 4)));
        h = btc_fnv(h, le, 16);
    }
    for (i = 0; i < m->ns; i++) {
        uint8_t le[4] = { (uint8_t)m->strip[i], (uint8_t)(m->strip[i] >> 8),
                          (uint8_t)(m->strip[i] >> 16), (uint8_t)(m->strip[i] >> 24) };
        h = btc_fnv(h, le, 4);
    }
    return h;
}
