/* benchmarks/table1.h — table 1 of papers/002 and the real 65x65 crops on which
 * bench_baselines (restricted quadtree, 002's rules) and bench_bitree (bitrain)
 * reproduce it: one list, so the two benchmarks always measure the same terrain. */
#ifndef BR_TABLE1_H
#define BR_TABLE1_H
#include <stdint.h>
#include <string.h>
#include "platform/load.h"
#include "tests/test.h"

/* papers/002, tabla 1 (65x65, heights 0..1445 m): points added against cracks,
 * points to transmit, triangles, strip references; bitree (BT) and quadtree (QT) */
typedef struct paper_row { const char *tol; int bt_add, qt_add, bt_tx, qt_tx, bt_tri, qt_tri, bt_ref, qt_ref; } paper_row;
static const paper_row paper[8] = {
    { "Orig.", 0, 0, 4225, 4225, 8192, 8192, 13655, 12972 },
    { "0%", 215, 272, 2533, 2805, 5296, 5843, 8685, 8467 },
    { "1%", 344, 407, 1235, 1642, 2899, 3184, 4643, 4788 },
    { "2%", 281, 360, 704, 1064, 1736, 2041, 2803, 3049 },
    { "7%", 161, 241, 229, 470, 647, 884, 1037, 1307 },
    { "10%", 144, 202, 182, 384, 527, 715, 851, 1061 },
    { "14%", 89, 142, 88, 230, 268, 418, 443, 601 },
    { "50%", 10, 19, 9, 28, 23, 41, 37, 62 },
};
/* tolerance in % of the crop's height range; -1 = the full grid ("Orig.") */
static const int pct[8] = { -1, 0, 1, 2, 7, 10, 14, 50 };

typedef struct crop { const char *file; int png_grey_dm; int32_t x0, y0; const char *what; } crop;
static const crop crops[] = {
    { "png/ps_height_1k.png", 1, 160, 0, "Puget Sound shore: sea (22% at 0 m) to 1220 m" },
    { "png/ps_height_1k.png", 1, 112, 48, "Puget Sound: 0 to 1317 m" },
    { "hgt/N47E009.hgt", 0, 176, 1040, "Raetikon valley floor (26% flat at 419 m) to 2337 m" },
};
#define NCROPS ((int)(sizeof crops / sizeof crops[0]))

/* Loads crop c's file into f (caller dem_frees it) and copies the 65x65 window to
 * z with its height range; BR_OK or the loader's status (err filled). */
static br_status load_crop(int c, hf *f, int32_t z[65 * 65], int32_t *zmin, int32_t *zmax, br_err *err)
{
    dem_opts o;
    int32_t x, y;
    memset(&o, 0, sizeof o);
    if (crops[c].png_grey_dm) { o.png_encoding = DEM_PNG_GREY; o.png_scale = 0.1; }
    if (dem_load(t_data(crops[c].file), &o, f, err) != BR_OK) return err->code;
    *zmin = INT32_MAX;
    *zmax = INT32_MIN;
    for (y = 0; y < 65; y++)
        for (x = 0; x < 65; x++) {
            int32_t v = f->z[(crops[c].y0 + y) * f->w + crops[c].x0 + x];
            z[y * 65 + x] = v;
            if (v < *zmin) *zmin = v;
            if (v > *zmax) *zmax = v;
        }
    return BR_OK;
}

#endif
