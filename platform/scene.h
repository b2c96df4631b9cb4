/* platform/scene.h — one terrain scene, shared by `render`, `view` and `run`:
 * the loaded heightfield, its colour ramp (built-in or a gdaldem colour file),
 * optional colour map / orthophoto, vertical scale, world frame
 * (raster/terrain.h), the default camera and near/far choice, and, for the
 * bitree paths, the tree built once plus mesh, vertex buffers and the rasteriser's
 * chunk table allocated once, so a frame (scene_mesh + scene_terrain) allocates nothing.
 *
 * Positions are in metres in the scene's frame: x east from the west edge,
 * y north from the south edge, z height above 0 m times the vertical scale (the
 * frame of `--camera`). */
#ifndef BR_SCENE_H
#define BR_SCENE_H
#include "core/bitree.h"
#include "core/hf.h"
#include "platform/err.h"
#include "platform/load.h"
#include "platform/pipe_threads.h"
#include "raster/frame.h"
#include "raster/raster.h"
#include "raster/terrain.h"

typedef struct scene_opts {          /* zero = defaults */
    dem_opts dem;
    const char *colors;              /* gdaldem color-relief file, or NULL for the built-in ramp */
    const char *texture;             /* colour map / orthophoto PNG over the whole grid, or NULL */
    const char *tree;                /* a saved bitree to attach instead of building (--tree) */
    double sun_az, sun_alt;          /* degrees (both 0: 315, 45) */
    double ambient;                  /* 0..1, used when ambient_set (else 0.3) */
    int ambient_set;
    double zscale;                   /* vertical scale (0: 1, or automatic for grids without a
                                        georeference: 99 % of the slopes at most 0.75 at the
                                        assumed 1 m spacing) */
    int quiet;                       /* do not print the automatic vertical scale */
    int ramp_abs;                    /* 1: georeferenced grids take the absolute-elevation ramp
                                        (rs_ramp_absolute) instead of the relative one */
} scene_opts;

/* Entries of a frame's clip table (rs_frame.clips): room for the triangles one frame
 * clips for the near plane or the guard band; any beyond it each band clips again. */
#define SCENE_CLIPS 128

typedef struct scene {
    hf f;
    hf_stats st;
    rs_ramp ramp;
    rt_scene rt;
    rs_texture tex;                  /* valid when rt.tex_w > 0 */
    uint32_t *texpx;
    double zscale;
    int64_t filled;                  /* samples filled by --fill-voids (dem_opts.fill_voids) */
    double width_m, depth_m, zmin_m, zmax_m;  /* extent; heights times zscale */
    /* bitree paths (scene_tree, scene_reserve) */
    bt_tree tree;
    bt_mesh mesh;
    rs_vertex *verts;                /* mesh.cap_v of them */
    rs_vertex *vprev;                /* the last frame's verts (scene_mesh swaps the two) */
    rs_cvert *cache;                 /* vertex cache for the rasteriser */
    void *tree_mem, *mesh_mem;
    const char *tree_file;           /* scene_opts.tree: attach it instead of building */
    int beds_lowered;                /* platform/water_scene.c lowered flattened water's
                                        samples (its bottom) before the tree: a tree saved
                                        from the file's heights does not belong to them */
    /* the view extraction in parts (core/bitree.h bt_extract_begin), on pool's threads
     * (NULL: the caller's only); the same mesh for every pool */
    bt_parts *parts;
    void *parts_mem;
    pt_pool *pool;
    uint32_t part_order[BT_PARTS], part_cost[BT_PARTS];   /* the parts' schedule (scene_mesh) */
    void *lit_mem;                   /* the shading cache (rt_scene_cache): 2 bytes a sample + 4 a height unit */
    /* full-grid path (scene_grid): row strips of every step-th sample */
    rs_vertex *grid_v;
    uint32_t grid_nv, *grid_idx;
    rs_prim *grid_prims;
    int32_t grid_nprims;
    rs_cvert *grid_cache;
    /* the terrain the next frame draws: the last scene_mesh or scene_grid */
    rs_prim prim;                    /* the bitree mesh's strip */
    const rs_prim *prims;
    int32_t nprims;
    int16_t *chunks;                 /* the rasteriser's chunk table, chunks_size bytes */
    size_t chunks_size;
    rs_clip_poly *clips;             /* the terrain frame's clip table, SCENE_CLIPS entries */
} scene;

/* Loads the files (merged when several), the ramp, texture and vertical scale.
 * A grid whose every sample is a void is refused (BR_E_VALUE): nothing to draw. */
br_status scene_open(scene *s, const char *const *in, int n, const scene_opts *o, br_err *err);
/* What scene_open does after loading, for a heightfield the caller put in s->f (the
 * rest of s zeroed; scene_close frees s->f's heights): statistics, colour ramp, sun,
 * shading and vertical scale from o (NULL: the defaults); name labels the messages. */
br_status scene_setup(scene *s, const scene_opts *o, const char *name, br_err *err);
/* Builds the bitree (exact metric) once. */
br_status scene_tree(scene *s, br_err *err);
/* Allocates the mesh (max_tri triangles; beyond it the bitree falls back to its
 * budget mode), the part meshes of the view extraction (min(max_tri, 32768) triangles
 * each, about 5.6 MB apiece of which 1 MB is written at once: 32 parts; a frame with a
 * larger part is extracted serially, the same mesh), its raster vertices, the vertex
 * cache, the chunk table (so that bands skip the chunks of triangles that miss them) and
 * the per-sample shading cache of rt_scene_cache (2 bytes a sample plus a height
 * table; none when that allocation fails). */
br_status scene_reserve(scene *s, uint32_t max_tri, br_err *err);
void scene_close(scene *s);

/* From the south-west at 35 degrees elevation towards the centre, at 3/4 of the
 * distance at which the terrain's bounding sphere fits the vertical field of view. */
void scene_default_view(const scene *s, double fovy_deg, double eye[3], double target[3]);
/* Terrain height (metres, scaled) under (x, y), nearest sample; NAN outside the
 * grid or on a void. */
double scene_ground(const scene *s, double x, double y);
/* Camera for eye/target in metres.  Near plane: as far out as the view allows
 * (1/w depth resolves ~ distance^2 / near): the distance to the target / 2000, but
 * at most half the eye's height above the ground below it (above the highest
 * sample when outside the grid), at least 5 cm; far: well beyond the terrain.
 * BR_E_ARG when the camera is unusable (too far away, eye == target). */
br_status scene_camera(const scene *s, const double eye[3], const double target[3], double fovy_deg,
                       int32_t w, int32_t h, cam *out);
/* The bitree mesh for c (p->mode BT_VIEW: pixel error, hysteresis, geomorph in p;
 * BT_FIDELITY: p->max_err; the camera and frame are filled in here) and its raster
 * vertices become the scene's terrain.  Needs scene_tree and scene_reserve.  In
 * BT_VIEW mode the extraction runs in parts, and with the vertices, on s->pool. */
br_status scene_mesh(scene *s, const cam *c, bt_params *p);
/* Part k of ps (after bt_extract_end) joined into m, its vertices set up into out: where
 * the part was replayed, only those that moved, the rest copied from the last frame's
 * vertices prev (another array: bt_part_moved_from); a sample new to the lit cache left
 * for rt_from_mesh_pending.  For any k on any thread; the terrain's parts (scene_mesh) and
 * the reflection's (platform/water_scene.c). */
void scene_join_part(bt_parts *ps, uint32_t k, const rt_scene *rt, bt_mesh *m, rs_vertex *out,
                     const rs_vertex *prev);
/* The full grid, every step-th sample (step >= 1) as row strips, becomes the scene's
 * terrain (allocated here, once per step; scene_close frees it). */
br_status scene_grid(scene *s, int32_t step, br_err *err);
/* Sets up fr for the scene's terrain (the last scene_mesh or scene_grid) seen by c: w, h,
 * vertices, primitives, vertex cache, chunk table, texture, view-projection (the caller
 * sets fmt, depth, no_cull, clear_rgb and one_band first), prepares it (rs_frame_prepare) and, when
 * pass is not NULL, makes the terrain pass that draws it (rs_pass_terrain,
 * raster/frame.h).  fr must outlive the pass. */
br_status scene_terrain(scene *s, const cam *c, rs_frame *fr, rs_pass *pass);
/* The viewer's frame: scene_mesh in BT_VIEW mode (p->mode is set here), then
 * scene_terrain without a pass; *prim gets the mesh's strip. */
br_status scene_frame(scene *s, const cam *c, bt_params *p, rs_frame *fr, rs_prim *prim);

#endif
