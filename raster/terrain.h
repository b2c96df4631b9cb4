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
    uint32_t *lit;           /* NULL, or the per-sample cache (rt_scene_cache): w*h
                                entries, 0 = not yet computed, else RT_LIT | rgb, the
                                shaded colour at the sample's real height */
} rt_scene;

#define RT_LIT 0x01000000u

/* Chooses the world frame for f and prepares shading; BR_E_ARG on a bad hf. */
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

/* Bytes of the per-sample colour cache for f (4 per sample; 0 if too big). */
size_t rt_cache_mem_size(const hf *f);
/* Attaches (mem != NULL) or detaches (mem == NULL) the cache, cleared.  What depends
 * only on the heightfield, the ramp, the sun, the ambient term, the texture size and
 * the vertical scale (the normal and the lit colour of a sample at its real height)
 * is then computed once per sample, on first use, instead of once per vertex per
 * frame: the same bytes as without the cache.  Call rt_cache_clear after changing
 * any of those (rt_scene_zscale does).  BR_E_ARG when mem_bytes is too small or mem
 * not 4-byte aligned (s unchanged). */
br_status rt_scene_cache(rt_scene *s, void *mem, size_t mem_bytes);
void rt_cache_clear(rt_scene *s);

/* Vertex of grid sample (x, y) with height z (heightfield units), shaded; with a
 * texture, uv = (x * tex_w / (w - 1), y * tex_h / (h - 1)) texels in Q8. */
void rt_vertex(const rt_scene *s, int32_t x, int32_t y, int32_t z, rs_vertex *out);

/* The bitree mesh's vertices (m->nv of them) into out; with the cache, a vertex at
 * its real height (BT_S) takes its colour from it. */
void rt_from_mesh(const rt_scene *s, const bt_mesh *m, rs_vertex *out);
/* The same for m->v[first .. first + n) into out[first .. first + n) (threads may
 * fill disjoint ranges at once). */
void rt_from_mesh_range(const rt_scene *s, const bt_mesh *m, uint32_t first, uint32_t n, rs_vertex *out);

#endif
