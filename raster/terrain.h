/* raster/terrain.h — the adapter from a heightfield and its bitree mesh (core/bitree.h)
 * to the rasteriser's vertices (raster/raster.h), and the world frame of a scene.
 *
 * World frame: the world unit is 2^-shift metres, shift chosen per heightfield as
 * the largest in [-8, 16] for which the terrain's extent (width, depth and |height|,
 * in metres, heights times the vertical exaggeration) times 2^shift stays <= 2^27,
 * so the scene and cameras up to several extents away fit CAM_COORD_MAX (2^30) with
 * headroom, and for which the vertical scale sz_q16 fits an int32 (heights in whole
 * metres allow at most shift 14: sz_q16 = 2^(shift + 16)).  x east from the west edge
 * (column 0), y north from the south edge (last row), z up from 0 m (sea level):
 *   wx = x * sx, wy = (h - 1 - y) * sy, wz = z * sz_q16 >> 16   (bt_frame form)
 * with sx = dx_um * 2^shift / 10^6 rounded (>= 1; for a DEM of up to 16385 columns
 * the extent bound makes sx >= 2^27 / 16385 / 2 > 4000 units unless the DEM is smaller
 * than 2^27 units at shift 16, so the rounding error is below 2^-13 of a step),
 * sz_q16 = z_num / z_den * 2^(shift + 16) rounded. */
#ifndef BR_TERRAIN_H
#define BR_TERRAIN_H
#include <stdint.h>
#include "core/hf.h"
#include "core/bitree.h"
#include "core/shade.h"
#include "raster/raster.h"
#include "raster/ramp.h"

typedef struct rt_scene {
    const hf *f;
    bt_frame fr;             /* grid -> world */
    int32_t shift;           /* world unit = 2^-shift m */
    const rs_ramp *ramp;
    fx_q14 sun[3];           /* towards the sun, Q14 */
    int32_t ambient_q14;
    shade_ctx sc;
    int32_t tex_w, tex_h;    /* 0: no texture; else a texture of this size covers the
                                grid (sample (0,0) at texel (0,0), sample (w-1,h-1) at
                                texel (tex_w, tex_h)) and the vertex colour is the
                                lighting alone (lit white) */
    int32_t zlo, zhi;        /* the heightfield's non-void height range (hf_stats) */
    /* the per-sample shading cache (rt_scene_cache), NULL when none is attached: */
    uint16_t *lvl;           /* w*h entries, 0 = not yet computed, else RT_LVL | the
                                sample's light level (rs_light_level of its normal:
                                at most FX_Q14_ONE + 1 < RT_LVL) */
    uint32_t *ztab;          /* nz entries: the ramp colour of height zlo + i */
    int32_t nz;              /* 0: no height table (range wider than RT_ZTAB_MAX) */
} rt_scene;

#define RT_LVL 0x8000u
/* A vertex colour that rt_from_mesh_range left for rt_from_mesh_pending. */
#define RT_PENDING 0x01000000u
/* Largest height range (heightfield units) given a colour table: 256 KiB. */
#define RT_ZTAB_MAX 65536

/* Chooses the world frame for f and prepares shading; BR_E_ARG on a bad hf or an
 * ambient term outside 0 .. FX_Q14_ONE.  No cache is attached. */
br_status rt_scene_init(rt_scene *s, const hf *f, const rs_ramp *ramp, const fx_q14 sun[3],
                        int32_t ambient_q14);

/* Vertical exaggeration num/den (0 < num, den < 2^31; the scene's heights are
 * multiplied by it; call it once, after rt_scene_init): scales the world frame's z
 * (lowering the shift when the exaggerated heights or their scale would not fit) and makes the shading normals
 * follow the scaled surface (n = (-gx kx, -gy ky, kz) of core/shade.h: kx, ky
 * scale down when num < den, kz scales down otherwise, so the constants stay
 * below 2^24).  BR_E_ARG (s unchanged) for a non-positive ratio. */
br_status rt_scene_zscale(rt_scene *s, int32_t num, int32_t den);

/* Millimetres to world units (rounded to nearest). */
int64_t rt_mm_to_world(const rt_scene *s, int64_t mm);

/* The per-sample shading cache.  A vertex's colour is its ramp colour at its height
 * z (which geomorphing and fictitious points move between real heights) lit by the
 * normal of its grid sample (which does not depend on z): rs_light_apply(ramp(z),
 * level(x, y)).  The level depends only on the heightfield, the sun, the ambient
 * term and the vertical scale; the ramp colour only on the height.  With the cache
 * the level is computed once per sample, on first use, and kept in 2 bytes; the
 * ramp colour is a table of 4 bytes per height unit over [zlo, zhi] (when that
 * range has at most RT_ZTAB_MAX heights; others, and heights outside it such as a
 * water level, go through rs_ramp_rgb).  Bytes: 2 w h rounded up to 4, plus 4 nz;
 * 2.9 MB + 10 KB for N47E009 (1201^2 samples, heights 388 .. 2937 m).  The same
 * bytes as without the cache.  rt_cache_mem_size: 0 if too big.  rt_scene_cache
 * attaches (mem != NULL) or detaches (mem == NULL) it, cleared; BR_E_ARG when
 * mem_bytes is too small or mem not 4-byte aligned (s unchanged).  Call
 * rt_cache_clear after changing the ramp, sun or ambient term (rt_scene_zscale does
 * it for the scale; a texture only makes the colour white, checked per vertex); it
 * fills the height table (nz rs_ramp_rgb calls) and forgets the levels. */
size_t rt_cache_mem_size(const rt_scene *s);
br_status rt_scene_cache(rt_scene *s, void *mem, size_t mem_bytes);
void rt_cache_clear(rt_scene *s);

/* Vertex of grid sample (x, y) with height z (heightfield units), shaded; with a
 * texture, uv = (x * tex_w / (w - 1), y * tex_h / (h - 1)) texels in Q8. */
void rt_vertex(const rt_scene *s, int32_t x, int32_t y, int32_t z, rs_vertex *out);

/* The lit colour of grid sample (x, y) at its own height, rt_vertex's (the void colour
 * for a void; the lighting alone under a texture).  Reads the cache's level where it is
 * set and computes it otherwise, storing nothing: threads may call it at once while no
 * rt_from_mesh* runs (the water hook's land pixels, raster/water.c). */
uint32_t rt_sample_rgb(const rt_scene *s, int32_t x, int32_t y);

/* The bitree mesh's vertices (m->nv of them) into out (serial; fills the cache). */
void rt_from_mesh(const rt_scene *s, const bt_mesh *m, rs_vertex *out);
/* The same for m->v[first .. first + n) into out[first .. first + n), for threads
 * filling disjoint ranges at once: it only reads the cache, so a vertex whose sample
 * has no level yet gets RT_PENDING in its rgb (a sample on a seam between two ranges
 * may be in both), and rt_from_mesh_pending, serial, after the ranges, computes
 * those levels, stores them and finishes those vertices.  The result is
 * rt_from_mesh's. */
void rt_from_mesh_range(const rt_scene *s, const bt_mesh *m, uint32_t first, uint32_t n, rs_vertex *out);
void rt_from_mesh_pending(const rt_scene *s, const bt_mesh *m, rs_vertex *out);
/* rt_from_mesh_range for the vertices of that range whose bit is set in moved (bit i & 7
 * of byte i >> 3 for m->v[first + i], core/bitree.h bt_part_moved_from), the others left as
 * they are in out. */
void rt_from_mesh_moved(const rt_scene *s, const bt_mesh *m, uint32_t first, uint32_t n, const uint8_t *moved,
                        rs_vertex *out);

#endif
