/* core/bt_budget.c — the budget rule of the bitree's selection (003; ROAM's split
 * queue, Duchaineau et al. 1997): diamonds are split in decreasing priority order (a
 * heap; ties coarser first) while the nominal triangle count stays within the
 * budget, and marked ST_MARK; the recursive walk (core/bt_mesh.c) then follows the
 * marks.  Contract: core/bitree.h; shared state: core/bt_em.h. */
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/bt_em.h"

/* ------------------------------------------------------------ budget */

/* An ids entry's flag: the diamond was split (slots are below 2^31: bt_slot_count) */
#define SPLIT_FLAG 0x80000000u
static int64_t prio(bti_extract *e, int32_t x, int32_t y)
{
    int typeD;
    int32_t h = bti_dscale(x, y, e->S, &typeD);
    int32_t j = 0;
    int64_t r;
    while (((int32_t)1 << j) < h) j++;
    if (e->p->mode == BT_FIDELITY) {
        uint16_t c = BT_NODE_ERR(e->t->node[bti_slot(e->t, x, y)]);
        r = c == BT_CODE_SPLIT ? ((int64_t)1 << 50) : (int64_t)c;
    } else {
        r = e->rho(e, x, y);
        if (r < 0) return -1;
        if (r > ((int64_t)1 << 50)) r = (int64_t)1 << 50;
    }
    return (r << 8) | (int64_t)(2 * j + typeD);
}

static void hpush(bti_heap_ent *hp, uint32_t *n, int64_t key, uint32_t id, uint32_t pos)
{
    uint32_t i = (*n)++;
    while (i > 0) {
        uint32_t par = (i - 1) >> 1;
        if (hp[par].key > key || (hp[par].key == key && hp[par].id < id)) break;
        hp[i] = hp[par];
        i = par;
    }
    hp[i].key = key; hp[i].id = id; hp[i].pos = pos;
}

static bti_heap_ent hpop(bti_heap_ent *hp, uint32_t *n)
{
    bti_heap_ent top = hp[0], last = hp[--(*n)];
    uint32_t i = 0;
    for (;;) {
        uint32_t l = 2 * i + 1, r = l + 1, b = i;
        const bti_heap_ent *bb = &last;
        if (l < *n && (hp[l].key > bb->key || (hp[l].key == bb->key && hp[l].id < bb->id))) { b = l; bb = &hp[l]; }
        if (r < *n && (hp[r].key > bb->key || (hp[r].key == bb->key && hp[r].id < bb->id))) { b = r; bb = &hp[r]; }
        if (b == i) break;
        hp[i] = hp[b];
        i = b;
    }
    if (*n > 0) hp[i] = last;
    return top;
}

/* Marks ST_MARK on the diamonds a budget of `budget` nominal triangles buys.
 * Returns the number of slots recorded (to clear afterwards) in ids.  While the heap
 * runs, ST_MARK says "pushed" (each diamond is pushed once) and a split diamond's ids
 * entry carries SPLIT_FLAG (its heap entry keeps where); at the end only the split
 * keep their mark.  Sets e->tau to the last split's rho (for geomorph).  The heap
 * orders ties by the padded grid index y*n + x.  Padding diamonds without a slot are
 * VOID: never pushed (in the view rules their priority is -1, in the fidelity rule
 * their code 0 is never split, and the loop stops at the first such key). */
uint32_t bti_budget_mark(bti_extract *e, uint32_t budget, uint32_t *nid)
{
    bt_tree *t = e->t;
    bti_heap_ent *hp = bti_heap_of(e->m);
    uint32_t *ids = bti_ids_of(e->m);
    uint8_t *mark = bti_st(t, ST_MARK);
    uint32_t nh = 0, ni = 0, cap = bti_heap_cap(e->m), hcap = bti_heap_n(e->m), j;
    uint64_t count = 2;
    int32_t S = e->S, n = e->n;
    int64_t last = 0;
    {
        uint32_t root = (uint32_t)((S / 2) * n + S / 2), rs = bti_slot(t, S / 2, S / 2);
        int64_t k = prio(e, S / 2, S / 2);
        if (k >= 0 && rs != t->nslot - 1) { hpush(hp, &nh, k, root, ni); bti_bit_set(mark, rs); ids[ni++] = rs; }
    }
    while (nh > 0) {
        bti_heap_ent he = hpop(hp, &nh);
        int32_t x = (int32_t)(he.id % (uint32_t)n), y = (int32_t)(he.id / (uint32_t)n);
        int typeD, i, add = 0;
        int32_t h = bti_dscale(x, y, S, &typeD);
        int32_t cx[4], cy[4];
        if ((he.key >> 8) <= 0 && e->p->mode != BT_FIDELITY) break;  /* nothing to gain */
        if (e->p->mode == BT_FIDELITY && (he.key >> 8) <= (int64_t)e->cthr) break;
        /* triangles of the diamond */
        if (typeD) add = 2;
        else if (x & h) add = (y - h >= 0) + (y + h <= S);
        else add = (x - h >= 0) + (x + h <= S);
        if (count + (uint64_t)add > budget) break;
        if (ni + 4 > cap || nh + 4 > hcap) break;     /* (nh <= ni: the second only for a smaller heap) */
        count += (uint64_t)add;
        ids[he.pos] |= SPLIT_FLAG;
        last = he.key >> 8;
        if (typeD) {
            cx[0] = x - h; cy[0] = y; cx[1] = x + h; cy[1] = y;
            cx[2] = x; cy[2] = y - h; cx[3] = x; cy[3] = y + h;
        } else if (h >= 2) {
            int32_t g = h >> 1;
            cx[0] = x - g; cy[0] = y - g; cx[1] = x + g; cy[1] = y - g;
            cx[2] = x - g; cy[2] = y + g; cx[3] = x + g; cy[3] = y + g;
        } else continue;
        for (i = 0; i < 4; i++) {
            uint32_t cid, cs;
            int64_t k;
            if (cx[i] < 0 || cy[i] < 0 || cx[i] > S || cy[i] > S) continue;
            cid = (uint32_t)(cy[i] * n + cx[i]);
            cs = bti_slot(t, cx[i], cy[i]);
            if (cs == t->nslot - 1 || bti_bit(mark, cs)) continue;
            k = prio(e, cx[i], cy[i]);
            bti_bit_set(mark, cs);
            if (k >= 0) hpush(hp, &nh, k, cid, ni);
            ids[ni++] = cs;
        }
    }
    for (j = 0; j < ni; j++) {          /* pushed, not split: unmarked */
        if (ids[j] & SPLIT_FLAG) ids[j] &= ~SPLIT_FLAG;
        else bti_bit_clear(mark, ids[j]);
    }
    if (e->p->mode != BT_FIDELITY) e->tau = last;
    *nid = ni;
    return ni;
}
