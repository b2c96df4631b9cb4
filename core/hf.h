/* core/hf.h — the heightfield: a grid of integer heights with its units.
 *
 * Layout: w samples per row, h rows, row-major, row 0 is the NORTH edge and
 * column 0 the WEST edge (the order of SRTM, PNG, ASC and GeoTIFF rows).
 * Heights: int32 in units of z_num/z_den metres (HGT 1/1, terrain-RGB 1/10,
 * Terrarium 1/256, files with decimal heights a power of ten chosen to keep at least 1 mm),
 * |z| <= BR_Z_LIMIT; HF_NODATA marks a void (never a vertex, never shaded).
 * Ground spacing: dx_um between columns, dy_um between rows, in micrometres
 * (for geographic grids: metres per degree at the grid's centre latitude),
 * 1 .. HF_MAX_SPACING_UM.
 * Georeference (optional): where sample (0,0) lies and the step per column/row,
 * in nano-degrees (geographic) or micrometres (projected).
 *
 * The struct is public and caller-owned: the caller provides z (w*h int32). */
#ifndef BR_HF_H
#define BR_HF_H
#include <stddef.h>
#include <stdint.h>
#include "core/config.h"
#include "core/status.h"

#define HF_NODATA INT32_MIN

/* Largest ground spacing, 2^37 um = 137.4 km: above one degree at the equator
 * (111.32 km), so ETOPO/GEBCO-class grids up to 1.2 degrees fit.  The bound keeps
 * every product of a spacing in int64: bt_frame_auto's w * dx_um << 10 is below
 * 16385 * 2^37 * 2^10 < 2^62; raster/terrain.c's dx_um << 16 is below 2^53; and
 * core/shade.c brings dx_um, dy_um below 2^31 by at most 6 halvings. */
#define HF_MAX_SPACING_UM ((int64_t)1 << 37)

enum { HF_GEO_NONE = 0, HF_GEO_DEGREES = 1, HF_GEO_PROJECTED = 2 };

typedef struct hf_geo {
    int32_t kind;       /* HF_GEO_NONE, HF_GEO_DEGREES or HF_GEO_PROJECTED */
    int64_t x0, y0;     /* centre of sample (0,0): east and north, nano-degrees or micrometres */
    int64_t sx, sy;     /* step per column (eastwards, > 0) and per row (southwards, > 0) */
} hf_geo;

typedef struct hf {
    int32_t w, h;       /* samples per row, rows */
    int32_t *z;         /* w*h heights, HF_NODATA = void */
    int32_t z_num, z_den; /* metres = z * z_num / z_den; both > 0 */
    int64_t dx_um, dy_um; /* ground spacing in micrometres, 1 .. HF_MAX_SPACING_UM */
    hf_geo geo;
} hf;

typedef struct hf_stats {
    int32_t zmin, zmax; /* over non-void samples; 0, 0 when all are void */
    int64_t voids;      /* number of HF_NODATA samples */
} hf_stats;

/* Checks w, h (1..BR_MAX_SIDE, w*h <= BR_MAX_SAMPLES), units and spacing. */
br_status hf_check_dims(int64_t w, int64_t h);
br_status hf_validate(const hf *f);
void hf_stats_get(const hf *f, hf_stats *out);

/* Height of sample (x, y) in millimetres, rounded to nearest (HF_NODATA stays). */
int64_t hf_z_to_mm(const hf *f, int32_t z);

#endif
