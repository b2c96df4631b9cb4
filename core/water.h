/* core/water.h — where the water is on a heightfield: the sea, lakes found as large flat
 * regions, or levels the caller states; each water body gets one level (heightfield units).
 *
 * Rules (docs/water.md states them with their thresholds and the cases they come from):
 * - Sea: samples at or below sea_level 4-connected to the grid's edge through samples at
 *   or below it (SRTM writes the sea as exactly 0 m).  On when sea_on.
 * - Lakes: 4-connected regions of samples of exactly the same height (SRTM flattens
 *   lakes to one value) of at least min_area samples, each at its own level.
 * - Seams: two such regions whose levels differ by at most join_dz and that touch along a
 *   straight seam (every 4-neighbour pair between them lies across one column boundary,
 *   or one row boundary) of at least join_seam pairs are one lake (source tiles
 *   flattened differently: Lake Constance in N47E009, 392 m and 396 m meeting between
 *   columns 599 and 600).  The joined lake takes the level of its largest region; the
 *   caller lowers the terrain under every water sample (platform/water_scene.c), so no
 *   part of it stands out of the water as a step.
 * - Rim: a lake is kept only when at most 1/32 of its rim (4-neighbour pairs leaving
 *   it) goes down (one outflow); terraces of a flattened valley floor step down along
 *   a whole edge and are not water.
 * - Voids (HF_NODATA) are never water.
 *
 * Memory: the caller hands in id (w * h bytes: 0 dry, 1 + body index) and work
 * (wt_work_size bytes); nothing is allocated.  Integer only. */
#ifndef BR_WATER_H
#define BR_WATER_H
#include <stddef.h>
#include <stdint.h>
#include "core/hf.h"
#include "core/status.h"

#define WT_MAX_BODIES 32        /* bodies kept (the largest); ids 1 .. WT_MAX_BODIES */
#define WT_MAX_CAND 64          /* flat regions considered for the seam rule (largest first) */

enum { WT_SEA = 1, WT_LAKE = 2, WT_USER = 3 };

typedef struct wt_params {      /* zero = defaults as stated */
    int32_t sea_on;             /* 1: detect the sea */
    int32_t sea_level;          /* heightfield units (0) */
    int64_t min_area;           /* samples of a flat region to be a lake (0: no lakes) */
    int32_t join_dz;            /* heightfield units (0: no joining) */
    int32_t join_seam;          /* pairs along the seam (0: 16) */
} wt_params;

typedef struct wt_bodies {
    int32_t n;                          /* bodies, 0 .. WT_MAX_BODIES */
    int32_t level[WT_MAX_BODIES];       /* heightfield units */
    int32_t kind[WT_MAX_BODIES];        /* WT_SEA, WT_LAKE, WT_USER */
    int64_t area[WT_MAX_BODIES];        /* samples */
    int32_t joined[WT_MAX_BODIES];      /* flat regions joined into this body by the seam rule */
} wt_bodies;

/* Bytes of work for a w x h grid. */
size_t wt_work_size(int32_t w, int32_t h);

/* Finds the water bodies of f into id (w * h) and *out, largest first.  BR_E_ARG on a
 * bad hf or too small work. */
br_status wt_detect(const hf *f, const wt_params *p, uint8_t *id, void *work, size_t work_size,
                    wt_bodies *out);

/* The user's one plane: every non-void sample at or below level is water, one body
 * (WT_USER) at that level. */
void wt_level(const hf *f, int32_t level, uint8_t *id, wt_bodies *out);

#endif
