/* platform/tree_file.h — a bitree hierarchy saved to a file and attached from it
 * (core/bitree.h bt_tree_save, bt_attach): `--save-tree FILE`, `--tree FILE`. */
#ifndef BR_TREE_FILE_H
#define BR_TREE_FILE_H
#include "core/bitree.h"
#include "platform/err.h"

/* Writes t's blob to path. */
br_status tree_file_save(const bt_tree *t, const char *path, br_err *err);
/* Reads path and attaches it as t for f, with frame state; *mem (free it after t)
 * holds the blob and the state.  A file that is not a tree for f gets an error
 * naming it: BR_E_VALUE for a saved tree of f's size whose heights or nodes do not
 * match, BR_E_FORMAT for anything else. */
br_status tree_file_attach(bt_tree *t, const hf *f, const char *path, void **mem, br_err *err);

#endif
