/* benchmarks/peer_scene.h — the shared terrain benchmark scene of
 * ../shared/bench/PEERS.md, rebuilt in C exactly as ../shared/bench/peer_scene.py does.
 *
 * fuji.png (terrain-RGB, h = -10000 + (R*65536 + G*256 + B) * 0.1 m) is sampled at
 * pixel (min(2i,511), min(2j,511)) into a 257x257 grid; peer-scene coordinates are
 * x = i, y = 256 - j, z = (h - hmin) * 64 / (hmax - hmin); per-vertex colour is the
 * height ramp times (0.30 + 0.70 max(0, N.L)), L = normalise(-1,-1,1.5), normals by
 * central differences, computed in double in the script's operation order (scene
 * INPUT may use floating point; everything drawn per frame is integer).
 * Outputs: float positions/colours exactly like scene.bin (for float renderers),
 * the RGBA bytes of scene.bin, and integer positions in 1/PEER_UNIT of a peer unit
 * (PEER_UNIT = 1024: x, y up to 262144, z up to 65536; rounded to nearest) for
 * bitrain's rasteriser.  Triangles: 256 row strips of 514 indices
 * v(0,j), v(0,j+1), v(1,j), v(1,j+1), ... (GL strip parity), counter-clockwise seen
 * from +z, 131,072 triangles; the list form is the same triangles in the same order.
 * Cameras A and B in integer world units (1/PEER_UNIT) via peer_camera(). */
#ifndef BR_PEER_SCENE_H
#define BR_PEER_SCENE_H
#include <stdint.h>
#include "raster/raster.h"

#define PEER_N 257
#define PEER_NV (PEER_N * PEER_N)
#define PEER_STRIP_LEN (2 * PEER_N)
#define PEER_NSTRIP (PEER_N - 1)
#define PEER_NTRI (2 * (PEER_N - 1) * (PEER_N - 1))
#define PEER_UNIT 1024

typedef struct peer_scene {
    float pos[PEER_NV * 3];           /* peer units */
    float col[PEER_NV * 3];           /* 0..1 */
    uint8_t rgba[PEER_NV * 4];        /* round(col*255) half to even, alpha 255 */
    int32_t ipos[PEER_NV * 3];        /* 1/PEER_UNIT peer units */
    uint32_t strip[PEER_NSTRIP * PEER_STRIP_LEN];
    uint32_t list[PEER_NTRI * 3];
} peer_scene;

typedef struct peer_camera_def {
    double eye[3], target[3];         /* peer units */
    double fovy_deg, znear, zfar;
} peer_camera_def;

/* Builds the scene from fuji.png (path); returns 0 on success, -1 with a message
 * on stderr when the file cannot be read. s is large (~3.7 MB): allocate it. */
int peer_scene_build(const char *fuji_png, peer_scene *s);

/* Camera 'A' or 'B' (anything else: -1).  Integer form in 1/PEER_UNIT units,
 * rounded to nearest; fovy in millidegrees. */
int peer_camera(char which, peer_camera_def *def, int32_t eye[3], int32_t target[3],
                int32_t *fovy_mdeg, int32_t *znear, int32_t *zfar);

/* bitrain's form of the scene: the PEER_NV vertices (integer positions, RGB colour of
 * the RGBA bytes) and the PEER_NSTRIP row strips over s->strip (s must outlive prims). */
void peer_scene_raster(const peer_scene *s, rs_vertex *v, rs_prim *prims);

/* A zeroed frame of peer camera `which` ('A' or 'B') at w x h over those vertices and
 * strips: the sky clear colour (153, 204, 255) as bench_osmesa, XRGB8888 + 32-bit depth,
 * culling off (the peers' table), the view of cam_look_at; the caller sets the cache
 * and anything else.  0, or -1 for an unknown camera or a size the camera refuses. */
int peer_frame(char which, int32_t w, int32_t h, const rs_vertex *v, const rs_prim *prims, rs_frame *f);

#endif
