/* platform/bench_vis.h — where a frame's triangles go (`bitrain bench --scene default
 * --visibility`): how many own a pixel of the finished frame, and why the others own
 * none.  A diagnostic for LOD work, outside the timed frames: it draws the frame again. */
#ifndef BR_BENCH_VIS_H
#define BR_BENCH_VIS_H
#include <stdint.h>
#include "platform/err.h"
#include "raster/raster.h"

/* Triangles summed over the frames measured (line triangles of a strip, whose
 * indices repeat, left out).  Each counted triangle is in exactly one class:
 * - seen: it owns at least one pixel of the finished frame;
 * - tiny: alone it would cover no pixel centre (all three vertices on screen and in
 *   front of the near plane);
 * - edge: a vertex off screen or behind the near plane, and no pixel of its own;
 * - back: it faces away (the rasteriser culls it) and covers a pixel centre;
 * - hidden: it faces the camera and covers pixel centres, all of which nearer
 *   triangles own (it lost every depth test). */
typedef struct bd_vis {
    uint64_t frames, tris, seen, tiny, edge, back, hidden;
} bd_vis;

/* Adds frame f's triangles (f as rs_frame_prepare took it: its vertices, primitives,
 * view and depth format) to *acc.  f is not changed: its triangles are drawn again as
 * a list, one band of the whole frame, each triangle's three vertices coloured with its
 * number (equal vertex colours interpolate to exactly that colour, so the finished
 * frame names each pixel's owner).  BR_E_NOMEM, BR_E_ARG (more than 2^24 - 1
 * triangles, or the frame cannot be prepared) with err set. */
br_status bd_visibility(const rs_frame *f, bd_vis *acc, br_err *err);

#endif
