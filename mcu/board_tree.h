/* mcu/board_tree.h — a bt_tree over a hierarchy baked into flash (mcu/bake.h): the node
 * words are read where they lie, only the per-vertex frame state (bt_tree.st, n * n
 * bytes) is in RAM.  The one place that knows the baked layout: when core/bitree.h
 * gains its attach call for prebuilt hierarchies, this file becomes a call to it. */
#ifndef BR_MCU_BOARD_TREE_H
#define BR_MCU_BOARD_TREE_H
#include <stddef.h>
#include <stdint.h>
#include "core/bitree.h"
#include "mcu/bake.h"

/* Bytes of RAM the attached tree needs (its frame state). */
size_t board_tree_ram_size(const bake_info *b);
/* Fills t for heightfield f (made from the same bake) with node words node (const, never
 * written: the per-frame paths only read t->node) and frame state in st (st_bytes >=
 * board_tree_ram_size, cleared here).  BR_E_ARG when f or the sizes do not match b. */
br_status board_tree_attach(bt_tree *t, const hf *f, const bake_info *b, const uint32_t *node, uint8_t *st,
                            size_t st_bytes);

#endif
