/* core/cam.h — the fixed-point perspective camera shared by the rasteriser
 * (raster/) and the bitree's view-dependent LOD (frustum culling, screen-space error).
 *
 * World coordinates: int32, x east, y north, z up (right-handed), in a world unit
 * the SCENE chooses (e.g. 2^-k metres, or one grid step of a benchmark scene); the
 * camera never needs to know it: every length below (eye, znear, zfar, camera-space
 * coordinates, plane offsets) is in that same unit.  Precondition for every input
 * point and for the eye: |x|, |y|, |z| <= CAM_COORD_MAX = 2^30 - 1, so differences
 * fit 31 bits and a Q30 dot product of a difference fits int64.
 *
 * Camera space (gluLookAt convention, but forward positive): xc = right.(p - eye),
 * yc = up.(p - eye), zc = forward.(p - eye); a point is in front when zc > 0.
 * Orientation: right/up/forward are Q30 unit vectors from cam_look_at (up hint +z;
 * +y when looking straight up or down), normalised with an integer square root.
 *
 * Screen (gluPerspective with aspect = w/h, square pixels): pixel units, origin at
 * the TOP-LEFT corner of the viewport, x to the right, y DOWN (row 0 is the top row),
 * pixel (i, j) covers [i, i+1) x [j, j+1), its centre is (i + 1/2, j + 1/2):
 *     sx = w/2 + f * xc / zc,    sy = h/2 - f * yc / zc,    f = (h/2) / tan(fovy/2).
 * f is the projection scale: pixels per world unit at a distance of one world
 * unit; an object-space error e at distance d covers about f * e / d pixels.
 *
 * Angles: fovy in millidegrees (1000 .. 170000), converted with CORDIC (core/fx.h).
 * No floating point anywhere. */
#ifndef BR_CAM_H
#define BR_CAM_H
#include <stdint.h>
#include "core/fx.h"
#include "core/status.h"

#define CAM_COORD_MAX ((int32_t)((1L << 30) - 1))

typedef struct cam {
    int32_t eye[3];            /* world units */
    int32_t w, h;              /* viewport in pixels, 1 .. 16384 */
    int32_t fovy_mdeg;         /* vertical field of view, millidegrees */
    int32_t znear, zfar;       /* distances along forward, world units, 0 < znear < zfar */
    fx_q30 right[3], up[3], fwd[3];  /* orthonormal basis, Q30 */
    fx_q16 tan_half;           /* tan(fovy / 2), Q16 */
    int64_t f_q16;             /* projection scale f in pixels, Q16 */
} cam;

/* A plane: a point p is inside (on the visible side) when n.p + d >= 0, where
 * n.p is computed as sum n_i * p_i (Q30 world units, int64) and d is in Q30 world
 * units.  n is a Q30 unit vector, so (n.p + d) / 2^30 is the signed distance in
 * world units. */
typedef struct cam_plane {
    fx_q30 n[3];
    int64_t d;
} cam_plane;

enum { CAM_LEFT, CAM_RIGHT, CAM_BOTTOM, CAM_TOP, CAM_NEAR, CAM_FAR, CAM_NPLANES };

/* The view-projection in the form the rasteriser uses (all exact integers):
 *   camera space  c = (r * p + t) >> 30 (world units; r rows = right, up, forward, Q30;
 *                 t = -r * eye in Q30 world units; the sum fits int64 by the
 *                 CAM_COORD_MAX precondition: |r*p| + |t| < 6 * 2^60);
 *   screen        sx = cx + f * c0 / c2,  sy = cy - f * c1 / c2  (pixels, Q16 below). */
typedef struct cam_vp {
    fx_q30 r[3][3];
    int64_t t[3];
    int64_t f_q16;             /* f, pixels, Q16 */
    int32_t cx_q16, cy_q16;    /* w/2, h/2, pixels, Q16 */
    int32_t znear, zfar;       /* copied from the camera */
} cam_vp;

/* Sets up c from eye, target (world units), fovy (millidegrees), viewport and
 * near/far.  BR_E_ARG (c unchanged) when eye == target, a coordinate exceeds
 * CAM_COORD_MAX, fovy is outside 1000..170000, w or h outside 1..16384, or
 * not 0 < znear < zfar. */
br_status cam_look_at(cam *c, const int32_t eye[3], const int32_t target[3],
                      int32_t fovy_mdeg, int32_t w, int32_t h, int32_t znear, int32_t zfar);

/* Camera-space coordinates of world point p, world units, rounded to nearest. */
void cam_to_view(const cam *c, const int32_t p[3], int64_t out[3]);

/* Projects p to the screen in Q16 pixels; returns 0 (out untouched) when p is not
 * in front of the near plane. */
int cam_project(const cam *c, const int32_t p[3], int64_t out_q16[2]);

void cam_viewproj(const cam *c, cam_vp *out);

/* The six frustum planes (CAM_LEFT .. CAM_FAR) in world space, normals inward. */
void cam_frustum(const cam *c, cam_plane out[CAM_NPLANES]);
/* The same for the screen rectangle win = x0, y0, x1, y1 (pixels, 0 <= x0 < x1 <= w,
 * 0 <= y0 < y1 <= h) instead of the whole viewport: its side planes pass through the
 * rectangle's edges (cam_frustum is the window 0, 0, w, h). */
void cam_frustum_window(const cam *c, const int32_t win[4], cam_plane out[CAM_NPLANES]);
/* cam_frustum_window's CAM_BOTTOM and CAM_TOP planes alone, for rows y0 .. y1 (the same
 * values; each side plane is a third of its cost); NULL leaves one out. */
void cam_frustum_rows(const cam *c, int32_t y0, int32_t y1, cam_plane *bottom, cam_plane *top);

/* Projection scale f (pixels per world unit at distance 1), Q16; same as c->f_q16. */
int64_t cam_proj_scale_q16(const cam *c);

#endif
