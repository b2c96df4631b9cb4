/* platform/tree_file.c — see platform/tree_file.h. */
#include <stdio.h>
#include <stdlib.h>
#include "platform/tree_file.h"

br_status tree_file_save(const bt_tree *t, const char *path, br_err *err)
{
    size_t n = bt_tree_blob_size(t);
    void *buf = n ? malloc(n) : NULL;
    FILE *fp;
    int ok;
    if (!buf) return br_err_set(err, BR_E_NOMEM, path, "out of memory for the tree (%zu bytes)", n);
    if (bt_tree_save(t, buf, n) != BR_OK) { free(buf); return br_err_set(err, BR_E_ARG, path, "cannot save the tree"); }
    if (!(fp = fopen(path, "wb"))) { free(buf); return br_err_set(err, BR_E_IO, path, "cannot open for writing"); }
    ok = fwrite(buf, 1, n, fp) == n;
    ok = (fclose(fp) == 0) && ok;
    free(buf);
    return ok ? BR_OK : br_err_set(err, BR_E_IO, path, "write failed");
}

/* A little-endian 32-bit word of a blob's header (core/bt_blob.c: the header is
 * little-endian on every host; bt_blob_to_host turns only the node words around). */
static uint32_t rd_le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* 1 when a blob that bt_attach refused still starts as a saved tree of f's width and
 * height (header words 0, 3, 4: the magic "BTRE", w, h): saved from other heights of
 * that size, or its nodes corrupt, rather than some other file. */
static int blob_for_grid(const uint8_t *b, size_t n, const hf *f)
{
    return n >= 20 && rd_le32(b) == 0x45525442u && rd_le32(b + 12) == (uint32_t)f->w && rd_le32(b + 16) == (uint32_t)f->h;
}

br_status tree_file_attach(bt_tree *t, const hf *f, const char *path, void **mem, br_err *err)
{
    FILE *fp = fopen(path, "rb");
    long len;
    size_t ns = bt_slot_count(f->w, f->h), n, stoff;
    uint8_t *buf;
    br_status s;
    *mem = NULL;
    if (!fp) return br_err_set(err, BR_E_IO, path, "cannot open the tree file");
    if (fseek(fp, 0, SEEK_END) != 0 || (len = ftell(fp)) < 0 || fseek(fp, 0, SEEK_SET) != 0) {
        fclose(fp);
        return br_err_set(err, BR_E_IO, path, "cannot read the tree file");
    }
    n = (size_t)len;
    /* no tree for this grid is larger than its own blob: refuse before allocating */
    if (!ns || n > 64 + ns * 4) {
        fclose(fp);
        return br_err_set(err, BR_E_FORMAT, path, "not a bitree for this %dx%d grid (%zu bytes)", f->w, f->h, n);
    }
    stoff = (n + 7) & ~(size_t)7;
    buf = malloc(stoff + ns);    /* malloc's alignment suits the node array */
    if (!buf) { fclose(fp); return br_err_set(err, BR_E_NOMEM, path, "out of memory for the tree (%zu bytes)", n + ns); }
    if (fread(buf, 1, n, fp) != n) { fclose(fp); free(buf); return br_err_set(err, BR_E_IO, path, "read failed"); }
    fclose(fp);
    bt_blob_to_host(buf, n);
    s = bt_attach(t, f, buf, n, buf + stoff, ns);
    if (s != BR_OK) {
        const int same_grid = blob_for_grid(buf, n, f);
        free(buf);
        if (same_grid)
            return br_err_set(err, BR_E_VALUE, path, "a bitree for a %dx%d grid, but not for these heights (saved from "
                              "another file of that size) or with corrupt nodes", f->w, f->h);
        return br_err_set(err, BR_E_FORMAT, path, "not a bitree saved for this heightfield (%dx%d): truncated, corrupt, "
                          "another version or another grid", f->w, f->h);
    }
    *mem = buf;
    return BR_OK;
}
