/* tests/fuzz_file.c — libFuzzer harness for the whole path from bytes on disk to
 * a rendered band (tests/fuzz.sh): the input is written to one or two files
 * under a temporary folder, then read as `bitrain render` reads them: by path
 * (platform/load_io.c: regular-file check, format caps), format detection by
 * name and content, .gz/.zip unpacking, merging by georeference, the scene
 * (platform/scene.c: ramp, world frame, shading), the bitree, the default view
 * and one band of pixels.
 * Input: byte 0 picks the file name's extension (low 4 bits), whether the
 * rest is split into two tiles to merge (bit 4: N47E009 and N47E010 with the
 * same extension, split at byte 1's fraction of the rest) and the reader flags
 * (bit 5: --nodata 0, bit 6: --merge-prefer last).  Findings: any sanitizer
 * report; a failure without a code or message; a frame call that fails on a
 * scene that loaded (abort).  Grids over 512 samples a side are loaded and
 * merged but not meshed, so one input cannot take seconds in the bitree. */
#define _POSIX_C_SOURCE 200809L   /* getpid, mkdir */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "platform/load.h"
#include "platform/scene.h"
#include "tests/support/fuzz_frame.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char *const exts[16] = { ".hgt", ".png", ".tif", ".bt", ".asc", ".xyz", ".tt3", ".hgt.gz",
                                      ".hgt.zip", ".txt", ".tt2", ".tiff", ".gz", ".zip", ".tt1", "" };

static int put(const char *path, const uint8_t *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    int ok;
    if (!f) return 0;
    ok = fwrite(p, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

static void frame(scene *s)
{
    double eye[3], tgt[3];
    bt_params p;
    br_err e;
    static uint32_t px[64 * 16];
    if (s->f.w > 512 || s->f.h > 512) return;
    if (scene_tree(s, &e) != BR_OK) return;      /* said in e; meshing is not this harness's finding */
    if (scene_reserve(s, 20000, &e) != BR_OK) return;
    scene_default_view(s, 60, eye, tgt);
    memset(&p, 0, sizeof p);
    p.pixel_err_q8 = 256;
    (void)fuzz_frame(s, eye, tgt, &p, 16, 16, px);      /* 0: a view it cannot place, said */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char dir[64];
    char a[128], b[128];
    const char *paths[2];
    scene s;
    scene_opts so;
    br_err e;
    br_status st;
    int two;
    size_t cut;
    if (size < 2) return 0;
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/bitrain_fuzz_file.%ld", (long)getpid());
        if (mkdir(dir, 0700) != 0) abort();
    }
    two = (data[0] >> 4) & 1;
    snprintf(a, sizeof a, "%s/N47E009%s", dir, exts[data[0] & 15]);
    snprintf(b, sizeof b, "%s/N47E010%s", dir, exts[data[0] & 15]);
    cut = two ? (size - 2) * data[1] / 255 : size - 2;
    if (!put(a, data + 2, cut) || (two && !put(b, data + 2 + cut, size - 2 - cut))) abort();
    paths[0] = a;
    paths[1] = b;
    memset(&so, 0, sizeof so);
    so.quiet = 1;
    so.dem.has_nodata = (data[0] >> 5) & 1;
    so.dem.merge_prefer = (data[0] >> 6) & 1 ? DEM_MERGE_LAST : DEM_MERGE_REFUSE;
    memset(&e, 0, sizeof e);
    st = scene_open(&s, paths, two ? 2 : 1, &so, &e);
    if (st == BR_OK) {
        if (hf_validate(&s.f) != BR_OK) abort();
        frame(&s);
        scene_close(&s);
    } else if (st >= BR_E_COUNT || e.msg[0] == 0) {
        abort();                      /* a failure must have a code and a message */
    }
    remove(a);
    if (two) remove(b);
    return 0;
}
