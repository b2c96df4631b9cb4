/* mcu/board_tree.c — see board_tree.h. */
#include "mcu/board_tree.h"
#include <string.h>

size_t board_tree_ram_size(const bake_info *b)
{
    return (size_t)b->n * (size_t)b->n;
}

br_status board_tree_attach(bt_tree *t, const hf *f, const bake_info *b, const uint32_t *node, uint8_t *st,
                            size_t st_bytes)
{
    if (!t || !f || !b || !node || !st || f->w != b->w || f->h != b->h || b->k < 1 || b->k > 14
        || b->n != (1 << b->k) + 1 || b->n < f->w || b->n < f->h || st_bytes < board_tree_ram_size(b))
        return BR_E_ARG;
    memset(t, 0, sizeof *t);
    t->f = f;
    t->n = b->n;
    t->k = b->k;
    t->metric = b->metric;
    t->zmin = b->zmin;
    t->zmax = b->zmax;
    t->nvalid = b->nvalid;
    t->node = (uint32_t *)(uintptr_t)node;   /* read only: see board_tree.h */
    t->st = st;
    memset(st, 0, board_tree_ram_size(b));
    return BR_OK;
}
