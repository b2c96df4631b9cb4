/* tests/support/waterview.h — what the water tests (tests/test_water.c,
 * tests/test_water_pass.c) start from: N47E009 with its water, a camera, a view mesh
 * and its terrain frame, as the viewer makes them.  Test support only. */
#ifndef BR_WATERVIEW_H
#define BR_WATERVIEW_H
#include <stdint.h>
#include "platform/scene.h"
#include "platform/water_scene.h"

/* The options the water tests start from: everything zeroed (err too), then quiet
 * scene and water, the viewer's view-dependent shore bound (view_px) and an XRGB8888
 * frame with 32-bit depth; a test sets what it varies after. */
void wv_defaults(scene_opts *so, ws_opts *wo, bt_params *bp, rs_frame *fr, br_err *err);

/* N47E009 opened with so, its water with wo, the camera eye -> tgt (metres, fov 50) at
 * w x h, the tree, a view mesh at 1 px (bp's other fields, such as hysteresis, the
 * caller's) and the terrain frame fr (its format, depth and clear colour the caller's).
 * s, ws are zeroed first, so ws_close and scene_close may follow whatever failed; a step
 * that fails is a failed CHECK. */
void wv_lake_frame(scene *s, const scene_opts *so, water_scene *ws, const ws_opts *wo, const double eye[3],
                   const double tgt[3], int32_t w, int32_t h, cam *c, bt_params *bp, rs_frame *fr);
/* The same for ../shared/data/dem/<dem>. */
void wv_dem_frame(const char *dem, scene *s, const scene_opts *so, water_scene *ws, const ws_opts *wo,
                  const double eye[3], const double tgt[3], int32_t w, int32_t h, cam *c, bt_params *bp, rs_frame *fr);

/* Everything one water view holds, for tests that open several: wv_view_open is
 * wv_defaults on its options, then the caller's changes (a function that takes the
 * view), then wv_dem_frame; wv_view_close closes both scenes. */
typedef struct wv_view {
    scene s;
    scene_opts so;
    ws_opts wo;
    water_scene ws;
    br_err err;
    cam c;
    bt_params bp;
    rs_frame fr;
} wv_view;
void wv_view_open(wv_view *v, const char *dem, const double eye[3], const double tgt[3], int32_t w, int32_t h,
                  void (*opts)(wv_view *v));
void wv_view_close(wv_view *v);

/* The frame written at out (PNG) against tests/golden/NAME.png, byte for byte in RGB; with
 * BITRAIN_UPDATE_GOLDEN set in the environment it writes the golden first.  A mismatch or
 * a file that cannot be read is a failed CHECK. */
void wv_golden(const char *name, const char *out);

#endif
