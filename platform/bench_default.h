/* platform/bench_default.h — the default scene's frame of `bitrain bench --scene default`
 * (platform/bench_default.c) as an API, so that `bitrain bench` (platform/bench_board.c)
 * flies exactly the frame that command measures: the bitree's view-dependent selection,
 * strip and raster vertices and the transform (bd_select), then the rasteriser over the
 * prepared frame (bd_frame: rs_pass_terrain draws it, band by band, on any thread). */
#ifndef BR_BENCH_DEFAULT_H
#define BR_BENCH_DEFAULT_H
#include <stdint.h>
#include "core/cam.h"
#include "platform/err.h"
#include "platform/pipe_threads.h"
#include "raster/raster.h"

typedef struct bd_run bd_run;

/* Opens dem (NULL: assets/N47E009.hgt.gz) with its tree and mesh memory, pixel error
 * pix_err, XRGB8888 frames with 32-bit depth.  NULL with err set on failure. */
bd_run *bd_open(const char *dem, double pix_err, br_err *err);
void bd_close(bd_run *r);
/* The scene's default eye and target (the benchmark's field of view). */
void bd_default_view(const bd_run *r, double eye[3], double tgt[3]);
/* The camera for eye/target at w x h; BR_E_ARG when unusable. */
br_status bd_camera(const bd_run *r, const double eye[3], const double tgt[3], int32_t w, int32_t h, cam *c);
/* Selection, strip, vertices and transform for c: the frame is then prepared. */
br_status bd_select(bd_run *r, const cam *c);
/* The prepared frame of the last bd_select (fmt, depth, chunks set; not one_band). */
const rs_frame *bd_frame(const bd_run *r);
/* Triangles of the last bd_select's mesh. */
uint32_t bd_tris(const bd_run *r);
/* The selection's parts run on pool's threads (NULL: the caller's). */
void bd_set_pool(bd_run *r, pt_pool *pool);

#endif
