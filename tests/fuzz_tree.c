/* tests/fuzz_tree.c — libFuzzer harness for a saved bitree attached from a file
 * (`--tree FILE`: platform/tree_file.c, core/bt_blob.c) and the frames drawn with it
 * (tests/fuzz.sh).
 * The tree is built once from a real 61 x 61 crop of N47E009 (tests/data/zip) and
 * saved; each input patches that blob, which is then written to a file, attached by
 * scene_open's path and drawn three frames.  Input: byte 0's bit 0 asks for the
 * checksums to be made right again after the patch (so the node values reach the
 * selection: core/bt_blob.c says they need no check for memory safety, and this is
 * what tests it), bit 1 lets the patch reach the header too; bytes 1, 2 move the
 * camera; then groups of three bytes: a 16-bit offset into the blob (modulo its size)
 * and a byte XORed there.  Findings: any sanitizer report; a refusal without a code
 * or a message; a frame call that fails on a tree that attached (abort). */
#define _POSIX_C_SOURCE 200809L   /* getpid */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "platform/load.h"
#include "platform/scene.h"
#include "tests/support/blob_sums.h"
#include "tests/support/fuzz_frame.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define DEM "tests/data/zip/N47E009_61x61.hgt.zip"

/* The saved tree of the crop, made on the first call. */
static const uint8_t *pristine(size_t *n)
{
    static uint8_t *blob;
    static size_t bytes;
    if (!blob) {
        const char *in[1] = { DEM };
        scene s;
        scene_opts so;
        br_err e;
        memset(&so, 0, sizeof so);
        so.quiet = 1;
        if (scene_open(&s, in, 1, &so, &e) != BR_OK || scene_tree(&s, &e) != BR_OK) {
            fprintf(stderr, "fuzz_tree: %s: %s\n", DEM, e.msg);
            abort();
        }
        bytes = bt_tree_blob_size(&s.tree);
        blob = malloc(bytes);
        if (!blob || bt_tree_save(&s.tree, blob, bytes) != BR_OK) abort();
        scene_close(&s);
    }
    *n = bytes;
    return blob;
}

/* Three frames at 64 x 48 from the default view moved by (mx, my): the second and
 * third reuse the first's hysteresis and frame state. */
static void frames(scene *s, int mx, int my)
{
    static uint32_t px[64 * 48];
    bt_params p;
    br_err e;
    int i;
    if (scene_reserve(s, 1024, &e) != BR_OK) return;       /* (small: parts are reserved per run) */
    memset(&p, 0, sizeof p);
    p.pixel_err_q8 = 256;
    p.hyst_q8 = 64;
    p.morph_q8 = 128;
    for (i = 0; i < 3; i++) {
        double eye[3], tgt[3];
        scene_default_view(s, 60, eye, tgt);
        eye[0] += (mx - 128) * 40.0 * (i + 1);
        eye[1] += (my - 128) * 40.0 * (i + 1);
        eye[2] *= 1.0 - 0.3 * i;
        if (!fuzz_frame(s, eye, tgt, &p, 0, 48, px)) return;     /* a view it cannot place */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char path[64];
    const char *in[1] = { DEM };
    size_t n, i;
    const uint8_t *orig = pristine(&n);
    uint8_t *blob;
    scene s;
    scene_opts so;
    br_err e;
    br_status st;
    FILE *f;
    if (size < 3) return 0;
    if (!path[0]) snprintf(path, sizeof path, "/tmp/bitrain_fuzz_tree.%ld.tree", (long)getpid());
    blob = malloc(n);
    if (!blob) abort();
    memcpy(blob, orig, n);
    for (i = 3; i + 3 <= size; i += 3) {
        size_t at = ((size_t)data[i] << 8 | data[i + 1]) % n;
        if (!(data[0] & 2)) at = BLOB_HDR + at % (n - BLOB_HDR);
        blob[at] ^= data[i + 2];
    }
    if (data[0] & 1) blob_fix_sums(blob, n);
    f = fopen(path, "wb");
    if (!f || fwrite(blob, 1, n, f) != n || fclose(f) != 0) abort();
    free(blob);
    memset(&so, 0, sizeof so);
    so.quiet = 1;
    so.tree = path;
    memset(&e, 0, sizeof e);
    st = scene_open(&s, in, 1, &so, &e);
    if (st != BR_OK) abort();           /* the heightfield is the pristine one */
    st = scene_tree(&s, &e);
    if (st == BR_OK) frames(&s, data[1], data[2]);
    else if (st >= BR_E_COUNT || e.msg[0] == 0) abort();    /* a refusal must have a code and a message */
    scene_close(&s);
    remove(path);
    return 0;
}
