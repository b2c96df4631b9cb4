/* core/bt_mesh_mem.c — a mesh's memory (core/bitree.h bt_mesh_mem_size, bt_mesh_init
 * and their _v forms with a vertex capacity of their own), and the scratch a caller may
 * borrow between extractions (bt_mesh_lend_scratch).  One caller block, in this order:
 *
 *   vertices | strip | split id list | budget heap | vertex hash + its base word | memo
 *   \----------- kept between frames ----------/ \------------- scratch -------------/
 *
 * The split id list holds the previous frame's splits (hysteresis) and the heap's ids in
 * a budget frame; the heap holds the previous splits while a frame is selected.  The
 * scratch is what only an extraction reads: the heap, the hash (stamped per extraction,
 * core/bt_mesh.c bti_reset_mesh) and the memo (a cache). */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/bt_em.h"

static uint32_t hash_size(uint32_t cap_v)
{
    uint32_t s = 16;
    while (s < 2 * cap_v && s < 0x80000000u) s <<= 1;
    return s;
}

/* Words of the decision memo: 2 per triangle, 64 .. 2^18 (2 MiB), an entry of
 * BTI_MEMO_W of them each (BR_COHERENCE: 2, the expiry); a lossy cache */
static uint32_t memo_size(uint32_t max_tri)
{
    uint32_t s = 64;
    while (s < 2 * (uint64_t)max_tri && s < (1u << 18)) s <<= 1;
    return s;
}

/* The vertex capacity for max_v (0: 3 max_tri + 3, each triangle's own vertices) and the
 * count the hash is sized for: 2 max_tri + 16, or an explicit max_v when that is smaller
 * (the hash then still has at least twice the slots of the vertices it can hold). */
static uint32_t cap_v_of(uint32_t max_tri, uint32_t max_v)
{
    return max_v == 0 || max_v > 3 * max_tri + 3 ? 3 * max_tri + 3 : max_v;
}

static uint32_t hash_for(uint32_t max_tri, uint32_t max_v)
{
    return max_v != 0 && max_v < 2 * max_tri + 16 ? max_v : 2 * max_tri + 16;
}

/* Strip capacity: 5 indices a triangle, or 4 a vertex for an explicit max_v when that is
 * smaller (a terrain strip has about 3 indices a vertex: 1.5 a triangle). */
static uint32_t strip_for(uint32_t max_tri, uint32_t max_v)
{
    return max_v != 0 && 4 * (uint64_t)max_v < 5 * (uint64_t)max_tri ? 4 * max_v + 8 : 5 * max_tri + 8;
}

/* Triangles the decision memo is sized for: max_tri, or max_v / 2 for an explicit max_v
 * when that is smaller (the memo is a lossy cache: fewer slots cost time, never a
 * different mesh). */
static uint32_t memo_for(uint32_t max_tri, uint32_t max_v)
{
    return max_v != 0 && max_v / 2 < max_tri ? max_v / 2 : max_tri;
}

/* Entries of the budget heap (and of the split id list after it): 4 per triangle the
 * budget rule may buy: max_tri, or max_v / 2 for an explicit max_v when that is smaller
 * (a terrain mesh has about one vertex for two triangles). */
static uint32_t heap_for(uint32_t max_tri, uint32_t max_v)
{
    return 4 * (max_v != 0 && max_v / 2 < max_tri ? max_v / 2 : max_tri) + 8;
}

/* Entries of the budget heap for a fallback of max_budget triangles (0: heap_for's): 4
 * a triangle and 8, at most the split list's heap_for and at least a quarter of it + 2
 * (16-byte entries: the list's 4-byte ids fit in the heap's bytes, where bt_extract
 * moves the previous frame's while it selects). */
static uint32_t heap_n_for(uint32_t max_tri, uint32_t max_v, uint32_t max_budget)
{
    const uint32_t ids = heap_for(max_tri, max_v), least = ids / 4 + 2;
    const uint64_t n = 4 * (uint64_t)max_budget + 8;
    return max_budget == 0 || n >= ids ? ids : n < least ? least : (uint32_t)n;
}

size_t bt_mesh_mem_size(uint32_t max_tri)
{
    return bt_mesh_mem_size_v(max_tri, 0);
}

size_t bt_mesh_mem_size_v(uint32_t max_tri, uint32_t max_v)
{
    return bt_mesh_mem_size_vb(max_tri, max_v, 0);
}

size_t bt_mesh_mem_size_vb(uint32_t max_tri, uint32_t max_v, uint32_t max_budget)
{
    uint64_t cap_v, cap_s, hs, heap, sz;
    if (max_tri < 2 || max_tri > 0x10000000u || (max_v != 0 && max_v < 16)) return 0;
    cap_v = cap_v_of(max_tri, max_v);
    if (cap_v - 1 > BR_INDEX_MAX) return 0;     /* (16-bit strip indices, BR_INDEX16) */
    cap_s = strip_for(max_tri, max_v);
    hs = hash_size(hash_for(max_tri, max_v));
    heap = heap_for(max_tri, max_v);
    sz = cap_v * sizeof(bt_vert) + cap_s * sizeof(br_index) + hs * 4 + 4
         + heap_n_for(max_tri, max_v, max_budget) * sizeof(bti_heap_ent) + heap * 4 + 8
         + (uint64_t)memo_size(memo_for(max_tri, max_v)) * 8 + 64;
    if (sz > (uint64_t)SIZE_MAX) return 0;      /* 32-bit hosts */
    return (size_t)sz;
}

br_status bt_mesh_init(bt_mesh *m, uint32_t max_tri, void *mem, size_t mem_bytes)
{
    return bt_mesh_init_v(m, max_tri, 0, mem, mem_bytes);
}

br_status bt_mesh_init_v(bt_mesh *m, uint32_t max_tri, uint32_t max_v, void *mem, size_t mem_bytes)
{
    return bt_mesh_init_vb(m, max_tri, max_v, 0, mem, mem_bytes);
}

br_status bt_mesh_init_vb(bt_mesh *m, uint32_t max_tri, uint32_t max_v, uint32_t max_budget, void *mem,
                          size_t mem_bytes)
{
    br_status s = bti_mesh_layout(m, max_tri, max_v, max_budget, mem, mem_bytes);
    if (s != BR_OK) return s;
    memset(m->hash, 0, ((size_t)m->hmask + 1) * 4 + 4);   /* + the generation word, see reset_mesh */
    bti_memo_clear(m->memo, m->memo_mask + 1);
    return BR_OK;
}

br_status bti_mesh_layout(bt_mesh *m, uint32_t max_tri, uint32_t max_v, uint32_t max_budget, void *mem,
                          size_t mem_bytes)
{
    uint8_t *p = (uint8_t *)mem;
    uint32_t cap_v, cap_s, hs;
    if (!m || !mem || max_tri < 2 || max_tri > 0x10000000u || (max_v != 0 && max_v < 16)) return BR_E_ARG;
    if (mem_bytes < bt_mesh_mem_size_vb(max_tri, max_v, max_budget)) return BR_E_ARG;
    if (((uintptr_t)mem & 7) != 0) return BR_E_ARG;
    memset(m, 0, sizeof *m);
    cap_v = cap_v_of(max_tri, max_v);
    if ((uint64_t)cap_v - 1 > BR_INDEX_MAX) return BR_E_ARG;      /* (BR_INDEX16) */
    cap_s = strip_for(max_tri, max_v);
    hs = hash_size(hash_for(max_tri, max_v));
    m->max_tri = max_tri;
    m->heap_cap = heap_for(max_tri, max_v);
    m->heap_n = heap_n_for(max_tri, max_v, max_budget);
    m->v = (bt_vert *)(void *)p; p += (size_t)cap_v * sizeof(bt_vert);
    m->cap_v = cap_v;
    m->strip = (br_index *)(void *)p; p += (size_t)cap_s * sizeof(br_index);
    m->cap_s = cap_s;
    p += (8 - ((uintptr_t)p & 7)) & 7;
    m->splits = (uint32_t *)(void *)p;   /* the id list, then the heap (bti_heap_of) */
    p = (uint8_t *)(void *)(bti_heap_of(m) + bti_heap_n(m));
    m->hash = (uint32_t *)(void *)p; p += (size_t)hs * 4 + 4;
    m->hmask = hs - 1;
    p += (8 - ((uintptr_t)p & 7)) & 7;
    m->memo = (uint64_t *)(void *)p;
    m->memo_mask = memo_size(memo_for(max_tri, max_v)) / BTI_MEMO_W - 1;
    m->memo_gen = 0;
    return BR_OK;
}

/* The heap (8-byte aligned: the split list before it has an even number of words), the
 * hash with its base word (hs 4 + 4 bytes, hs a power of two >= 16), 4 bytes of padding
 * to the memo's 8-byte alignment, the memo: what bt_mesh_init_v lays out. */
size_t bt_mesh_scratch_size_v(uint32_t max_tri, uint32_t max_v)
{
    return bt_mesh_scratch_size_vb(max_tri, max_v, 0);
}

size_t bt_mesh_scratch_size_vb(uint32_t max_tri, uint32_t max_v, uint32_t max_budget)
{
    uint64_t sz;
    if (bt_mesh_mem_size_vb(max_tri, max_v, max_budget) == 0) return 0;
    sz = (uint64_t)heap_n_for(max_tri, max_v, max_budget) * sizeof(bti_heap_ent)
         + (uint64_t)hash_size(hash_for(max_tri, max_v)) * 4 + 8
         + (uint64_t)memo_size(memo_for(max_tri, max_v)) * 8;
    return (size_t)sz;
}

void *bt_mesh_lend_scratch(bt_mesh *m, size_t *bytes)
{
    uint8_t *lo, *hi;
    if (!m || !m->v) {
        if (bytes) *bytes = 0;
        return NULL;
    }
    lo = (uint8_t *)(void *)bti_heap_of(m);
    hi = (uint8_t *)(void *)(m->memo + ((size_t)m->memo_mask + 1) * BTI_MEMO_W);
    m->lent = 1;
    if (bytes) *bytes = (size_t)(hi - lo);
    return lo;
}

/* Empties the mesh.  The vertex hash is not cleared: a slot holds base + 1 +
 * index, and the base (the word after the table) moves past every value of the
 * previous extraction, so old slots read as empty; cleared only when the base
 * would wrap, or when the scratch was lent out (bt_mesh_lend_scratch: the hash and
 * the memo hold anything then, and the memo's frame coherence starts again). */
uint32_t bti_reset_mesh(bt_mesh *m)
{
    uint32_t *base = &m->hash[m->hmask + 1];
    if (m->lent) {
        memset(m->hash, 0, ((size_t)m->hmask + 1) * 4 + 4);
        bti_memo_clear(m->memo, m->memo_mask + 1);
        m->memo_gen = 0;
        m->coh.valid = 0;
        m->lent = 0;
    }
    if (*base > 0xFFFFFFFFu - m->nv - m->cap_v - 1) {
        memset(m->hash, 0, ((size_t)m->hmask + 1) * 4);
        *base = 0;
    } else *base += m->nv;
    if (++m->memo_gen > 0xFFFFu) {   /* entries of generation 0 were written 2^16 extractions ago */
        bti_memo_clear(m->memo, m->memo_mask + 1);
        m->memo_gen = 1;
    }
    m->nv = 0; m->ns = 0; m->ntri = 0; m->nline = 0; m->nfict = 0; m->overflow = 0;
    return *base;
}
