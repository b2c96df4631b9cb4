/* platform/water_scene.h — water and atmosphere for a scene (platform/scene.h): finds
 * the water (core/water.h) or takes the user's (--water-level, --water FILE), lowers the
 * terrain under flattened water by a stated default depth, meshes the water surfaces
 * with their own bitree, and per frame builds the reflection frame, the water frame and
 * the pipe (raster/frame.h, raster/water.h) that `render` runs.
 *
 * Order: scene_open, ws_open (it changes the heightfield), scene_tree, scene_reserve;
 * ws_reserve (optional: else on the first frame);
 * per frame: the terrain frame prepared with a chunk table, then ws_frame, then
 * rs_pipe_run(&w->pipe, ...). */
#ifndef BR_WATER_SCENE_H
#define BR_WATER_SCENE_H
#include "core/water.h"
#include "platform/scene.h"
#include "raster/frame.h"
#include "raster/water.h"
#include "platform/opt.h"

#define WS_DEPTH_MM 3000        /* depth of the bottom under flattened water (SRTM lakes and sea) */
#define WS_TINT_MM 4000         /* absorption length of the depth tint */
#define WS_TINT_FIXED 248       /* the default tint of water without bathymetry, Q8 (0.97) */
#define WS_MIN_AREA_M2 1000000  /* a flat region of at least 1 km^2 is a lake */
#define WS_JOIN_DZ_MM 5000      /* the seam rule joins flat regions within 5 m */
#define WS_REFL_TRI 262144     /* the reflection's own mesh holds at most this many triangles */
/* The reflection's own LOD by default (--reflection-error): four times the terrain's
 * screen error, the reach of the waves that move its lookup (RW_WAVE_PX, 4 pixels;
 * docs/water.md, Optics) */
#define WS_REFL_ERR 4
#define WS_REFL_PART_TRI 1024  /* its parts' room (a part past 160 triangles is cut; core/bitree.h) */
#define WS_FAR_TESTED_S 64      /* the far water mesh's largest tested block, cells a side */
#define WS_FAR_TESTED_PX 48     /* ... drawn while each tested triangle spans at most this many pixels */

/* The water surfaces' mesh (platform/water_mesh.c): grid vertices (x column, y row, z in
 * heightfield units, body id), triangles counter-clockwise seen from +z, watertight. */
typedef struct wm_vert {
    int32_t x, y, z;
    uint8_t id;
    uint8_t tested;             /* of a tested block: the hook tests its pixels (RW_TESTED_RGB) */
} wm_vert;
typedef struct wm_mesh {
    wm_vert *v;
    uint32_t nv;
    uint32_t *idx;              /* 3 per triangle */
    uint32_t nidx;
    uint8_t *low;               /* per sample, 1 where a tested triangle's plane may not lie
                                   (rw_params.low): in a body's tested block, its low land
                                   and voids; NULL when no triangle is tested */
} wm_mesh;
/* Meshes the surfaces once: id per sample (0: none), wz the surface height where id is
 * set, level[b - 1] body b's level, bodies 1 .. nbodies; tested blocks of up to tested_s
 * cells a side (0: water_mesh.c's WM_TESTED_S, 32).  BR_E_NOMEM. */
br_status wm_build(const hf *f, const uint8_t *id, const int32_t *wz, const int32_t *level, int32_t nbodies,
                   int32_t tested_s, wm_mesh *m);
void wm_free(wm_mesh *m);

typedef struct ws_opts {        /* zero = defaults: water found automatically, fog on */
    int no_water;               /* --no-water */
    int have_level;             /* --water-level M */
    double level_m;
    const char *water_file;     /* --water FILE: water surface heights, nodata where dry */
    int no_fog;                 /* --no-fog */
    int reflection;             /* 0 half (default), 1 full, 2 half, 3 quarter, 4 none */
    double time_s;              /* --time T */
    int no_waves, fresnel_one;  /* tests */
    int refl_no_window;         /* tests: the reflection's own selection over the whole
                                   screen, not only around its water (refl_window) */
    int shore_bound;            /* 1: the terrain mesh's error is bounded by shore_px pixels
                                   on screen (view-dependent) or shore_m metres (fidelity;
                                   both 0: the full grid), which spares the shore test on land
                                   (raster/water.h rw_params.shore_bound); 0: test it everywhere */
    double shore_px, shore_m;
    double view_px;             /* the terrain's screen error in pixels when it is the scene's
                                   view-dependent bitree mesh (scene_mesh in BT_VIEW mode);
                                   0: another mesh, which the reflection then draws itself */
    double refl_err;            /* --reflection-error F: 0 the reflection draws the terrain's
                                   mesh; F >= 1 its own selection at F view_px (1: the
                                   terrain's screen error; ws_args_table's default
                                   WS_REFL_ERR) */
    int quiet;
} ws_opts;

/* A water mesh and what draws it: world vertices carrying their body's id, its vertex
 * cache and chunk table, the triangle list, each triangle's body id. */
typedef struct ws_surf {
    wm_mesh mesh;
    rs_vertex *verts;
    rs_cvert *cache;
    int16_t *chunks;
    rs_prim prim;
    uint8_t *tid;
} ws_surf;

typedef struct water_scene {
    ws_opts o;
    wt_bodies bodies;
    int nbodies;
    int64_t tint_len;           /* the refraction tint's length in world units (ws_open) */
    uint8_t *id;                /* per sample: body id (wet, or dry land the body's surface
                                   goes on under), 0 where no water is drawn */
    hf wf;                      /* water surface heights (terrain units), nodata where none */
    ws_surf surf[2];            /* the water surfaces meshed once by ws_open: [0] tested
                                   blocks of up to WM_TESTED_S cells, [1] of up to WS_FAR_TESTED_S */
    int32_t (*tbox)[6];         /* the world box (min x, y, z, max x, y, z) of each of surf[1]'s */
    uint32_t ntbox;             /* tested triangles (far_pays) */
    rs_frame wfr;
    rs_clip_poly *wclips, *rclips;      /* the water and mirror frames' clip tables (SCENE_CLIPS) */
    uint32_t *rstrip;           /* the terrain strip with its first index doubled */
    uint32_t rstrip_cap;
    rs_cvert *rcache;
    uint32_t rcache_cap;
    int16_t *rchunks;
    size_t rchunks_cap;
    rs_prim rprim;
    rs_vertex *rbed;            /* the mirror's vertices with the body's lowered bed at its
                                   level (refl_bed_level), rbed_cap of them */
    uint32_t rbed_cap;
    /* the reflection's own LOD (ws_frame): the view selection of the mirrored camera at
     * refl_err times the terrain's screen error, with its own frame state rst (one byte
     * a slot of the scene's tree, so the terrain's hysteresis is not touched; without
     * hysteresis, it serves the decision memo and its frame coherence), into rmesh
     * (ws_reserve, or the first frame that needs it: min(WS_REFL_TRI, the terrain
     * mesh's capacity) triangles, 43 MB); rown 1 when this frame's reflection draws it,
     * 0 when it draws the terrain's mesh (no view-dependent terrain mesh, or a selection
     * larger than rmesh: bt_extract's budget fallback is not drawn) */
    bt_mesh rmesh;
    void *rmesh_mem;
    bt_parts *rparts;           /* its parts (frame coherence: a part whose decisions hold
                                   is replayed, not walked; WS_REFL_PART_TRI triangles each) */
    void *rparts_mem;
    uint8_t *rst;
    rs_vertex *rverts, *rvprev; /* its vertices, and the last frame's (refl_select swaps them) */
    rs_prim rmprim;             /* rmesh's strip as it is (the mirrored camera's winding) */
    cam rcam;                   /* the mirrored camera */
    int rown;
    rs_frame rfr;
    rw_frame *rw;
    rs_pass tpass;
    rs_pipe pipe;
} water_scene;

/* The options --no-water, --water-level M, --water FILE, --fog, --no-fog, --time T,
 * --reflection full|half|quarter|none, --reflection-error F as a table for opt_parse
 * (platform/water_args.c). */
#define WS_ARGS_N 9     /* entries of the table, OPT_END included */
typedef struct ws_args {
    ws_opts *o;
    int fog, refl, refl_seen, refl_err_seen;
    int time_seen;              /* --time given (the viewer's ripples then stand still) */
} ws_args;
void ws_args_table(ws_args *a, ws_opts *o, opt_spec t[WS_ARGS_N]);
int ws_args_finish(ws_args *a, const char *cmd);

br_status ws_open(water_scene *w, scene *s, const ws_opts *o, br_err *err);
/* Builds this frame's water frame (the scene's water mesh transformed), reflection frame
 * and pipe for camera c and the prepared terrain frame tf (its chunk table set).  The
 * reflection draws its own selection (see rmesh) when o.refl_err >= 1, o.view_px > 0 and
 * tf draws the scene's bitree mesh; the mirrored camera C2 = (M right, -M up, M fwd) at M eye, M: z ->
 * 2 H - z in the reflected plane z = H, sees the terrain above the plane at the distances
 * the camera sees its mirror image, so its selection is the mirror image's LOD. */
br_status ws_frame(water_scene *w, scene *s, const cam *c, rs_frame *tf, br_err *err);
/* The reflection's own mesh (rmesh, rverts) when o.refl_err >= 1, once per scene, after
 * scene_reserve (ws_frame does it on the first frame that needs it otherwise).
 * BR_E_NOMEM. */
br_status ws_reserve(water_scene *w, scene *s);
void ws_close(water_scene *w);

#endif
