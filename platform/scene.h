/* platform/scene.h — one terrain scene for the interactive paths (view, run):
 * the loaded heightfield, its colour ramp and world frame (raster/terrain.h),
 * the bitree built once, and per frame a mesh for a camera turned into raster
 * vertices.  All allocation happens in scene_open; scene_frame allocates nothing.
 *
 * Positions are in metres in the scene's frame: x east from the west edge,
 * y north from the south edge, z height above sea level (the same frame as
 * `bitrain render --camera`). */
#ifndef BR_SCENE_H
#define BR_SCENE_H
#include "core/bitree.h"
#include "core/hf.h"
#include "platform/err.h"
#include "platform/load.h"
#include "raster/raster.h"
#include "raster/terrain.h"

typedef struct scene_opts {          /* zero = defaults */
    dem_opts dem;
    double sun_az, sun_alt;          /* degrees (0, 0 = 315, 45) */
    double ambient;                  /* 0..1 (0 = 0.3) */
    uint32_t max_tri;                /* mesh capacity (0 = 2,000,000); beyond it the
                                        bitree falls back to its budget mode */
} scene_opts;

typedef struct scene {
    hf f;
    hf_stats st;
    rs_ramp ramp;
    rt_scene rt;
    bt_tree tree;
    bt_mesh mesh;
    rs_vertex *verts;                /* mesh.cap_v of them */
    rs_cvert *cache;                 /* vertex cache for the rasteriser */
    void *tree_mem, *mesh_mem;
    double width_m, depth_m, zmin_m, zmax_m;
} scene;

br_status scene_open(scene *s, const char *const *in, int n, const scene_opts *o, br_err *err);
void scene_close(scene *s);

/* A view of the whole terrain from the south-west, above it, towards the centre. */
void scene_default_view(const scene *s, double eye[3], double target[3]);
/* Terrain height (metres) under (x, y) metres, nearest sample; zmin_m outside or on voids. */
double scene_ground(const scene *s, double x, double y);
/* Camera for eye/target in metres; near and far are chosen from the distance to
 * the ground and the terrain's extent.  BR_E_ARG when the camera is unusable. */
br_status scene_camera(const scene *s, const double eye[3], const double target[3], double fovy_deg,
                       int32_t w, int32_t h, cam *out);
/* The view-dependent mesh for c (pixel error, hysteresis and geomorph in p; the
 * mode, camera and frame are filled in here) and its raster vertices; sets up fr
 * (w, h, vertices, strip, cache, view-projection) ready for rs_render/rs_render_band. */
br_status scene_frame(scene *s, const cam *c, bt_params *p, rs_frame *fr, rs_prim *prim);

#endif
