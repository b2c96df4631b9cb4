/* platform/load.h — read elevation files into a heightfield (core/hf.h).
 *
 * The format is chosen by content (magic bytes, size) and extension:
 *   SRTM .hgt (also .hgt.gz, .hgt.zip), PNG (16/8-bit grey, terrain-RGB,
 *   Terrarium), ESRI ASCII grid .asc, VTP Binary Terrain .bt, GeoTIFF .tif,
 *   XYZ text grids (.xyz, .txt, GeoClaw topotype 1), GeoClaw topotype 2 and 3
 *   (.tt2, .tt3, or by content: a value-first header).
 * Every reader refuses bad input with a status and a message naming the file
 * and the problem; absurd dimensions are refused before allocating.
 * The heights buffer is malloc'd; free it with dem_free. */
#ifndef BR_LOAD_H
#define BR_LOAD_H
#include "core/hf.h"
#include "platform/err.h"

enum { DEM_PNG_AUTO = 0, DEM_PNG_GREY, DEM_PNG_TERRAIN_RGB, DEM_PNG_TERRARIUM };

typedef struct dem_opts {     /* zero = defaults */
    int png_encoding;         /* DEM_PNG_*: AUTO = grey for grey PNGs, terrain-RGB for colour ones */
    double png_scale;         /* grey PNG: metres per raw unit (0 = 1) */
    double png_offset;        /* grey PNG: metres added after scaling */
    int xyz_depth;            /* XYZ, GeoClaw: values are depths (positive down): heights = -z */
    int has_nodata;           /* samples equal to nodata are voids, besides the file's own voids */
    double nodata;            /* compared with the value as the file stores it (grey PNG: the raw
                                 sample; terrain-RGB, Terrarium: metres); NaN: NaN samples of
                                 float TIFF and BT files are voids */
    int merge_prefer;         /* DEM_MERGE_*: what a merge does where tiles disagree */
    int fill_voids;           /* dem_load_many: fill voids from their borders (platform/fill.h) */
    int64_t *filled_out;      /* with fill_voids: receives the number of filled samples (or NULL) */
} dem_opts;

/* Merging tiles whose samples disagree where they overlap: refuse (default), or
 * keep the first / the last file's height (gdal_merge's order); a void never
 * replaces a height. */
enum { DEM_MERGE_REFUSE = 0, DEM_MERGE_FIRST, DEM_MERGE_LAST };

/* Where readers say which of several readings of a file they chose and why
 * (e.g. the encoding of a colour PNG): none by default; the bitrain program
 * prints them on stderr. */
typedef void dem_note_fn(const char *name, const char *msg);
void dem_set_note(dem_note_fn *fn);

/* Reads and decodes the file path (a name under assets/ is found as platform/assets.h
 * says, so the bundled terrain opens from any directory). */
br_status dem_load(const char *path, const dem_opts *o, hf *out, br_err *err);
/* The same from bytes in memory (fuzzers, tests, archives): name is used for
 * messages, the extension and SRTM tile names; bytes are not modified or kept. */
br_status dem_load_mem(const char *name, const uint8_t *bytes, size_t len, const dem_opts *o,
                       hf *out, br_err *err);
/* Loads n files and, when n > 1, merges them by georeference (shared edges kept
 * once; overlaps with different values or gaps are errors); with o->fill_voids,
 * fills the voids of the result (after the merge, so across seams too). */
br_status dem_load_many(const char *const *paths, int n, const dem_opts *o, hf *out, br_err *err);
void dem_free(hf *f);

#endif
