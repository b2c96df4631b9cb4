/* mcu/board_tree.h — the board's bt_tree: the hierarchy baked into flash (mcu/bake.h
 * bake_tree, saved by bt_tree_save) attached in place with bt_attach; only the frame
 * state (bt_tree.st, bt_state_size(bake.nslot) bytes) is in RAM. */
#ifndef BR_MCU_BOARD_TREE_H
#define BR_MCU_BOARD_TREE_H
#include <stddef.h>
#include <stdint.h>
#include "core/bitree.h"
#include "mcu/bake.h"

/* Bytes of RAM the attached tree needs (its frame state). */
size_t board_tree_ram_size(const bake_info *b);
/* Attaches the baked hierarchy (blob of `bytes` bytes) for heightfield f (made from the
 * same bake), frame state in st (st_bytes >= board_tree_ram_size, cleared by
 * bt_attach).  BR_E_ARG when the blob does not belong to f or the sizes are short. */
br_status board_tree_attach(bt_tree *t, const hf *f, const bake_info *b, const uint32_t *blob, size_t bytes,
                            uint8_t *st, size_t st_bytes);

#endif
