/* mcu/board_tree.c — see board_tree.h. */
#include "mcu/board_tree.h"

size_t board_tree_ram_size(const bake_info *b)
{
    return bt_state_size(b->nslot);
}

br_status board_tree_attach(bt_tree *t, const hf *f, const bake_info *b, const uint32_t *blob, size_t bytes,
                            uint8_t *st, size_t st_bytes)
{
    if (!t || !f || !b || !blob || !st || st_bytes < board_tree_ram_size(b)) return BR_E_ARG;
    return bt_attach(t, f, blob, bytes, st, st_bytes);
}
