/* raster/frame.h — the one frame driver: every frame bitrain draws (render, view, run,
 * bench, the tests, the board main) is a list of passes run band by band over the same
 * band memory, then a post-pass hook, then a sink.
 *
 * THE INTERFACE IS FROZEN: passes, margins, the post-pass hook, the sink and per-band
 * statistics below are what water, fog, the HUD, threads and the board build extend.
 * Add passes and hooks; do not change these types (docs/pipeline.md says why).
 *
 * A FRAME
 *   rs_pipe p = {0};
 *   p.w = ...; p.h = ...; p.fmt = ...; p.depth = ...;
 *   rs_pipe_add(&p, &terrain_pass);          (rs_pass_terrain: the rasteriser, rs_frame)
 *   rs_pipe_add(&p, &my_pass);               (reflection, water, ... in drawing order)
 *   p.post = fog_hook; p.post_user = ...;    (optional: sees colour and depth of the band)
 *   rs_pipe_run(&p, band_rows, mem, rs_pipe_mem_size(&p, band_rows), sink, sink_user);
 *
 * BANDS
 *   A band is rows [y0, y0 + rows) of the frame.  Every pass computes each pixel from
 *   frame-wide data only (never from the band's first row), so any band height gives
 *   exactly the pixels of the whole frame (DESIGN.md invariant 4).  rs_pipe_band draws
 *   one band into memory the caller owns and touches nothing shared but the passes'
 *   read-only frame data: N threads may draw N bands at once, each with its own memory
 *   and its own rs_band_stats, and hand the bands to the sink in order.
 *
 * MARGINS AND SCRATCH
 *   A pass that reads pixels of its own output a few rows away (the water's wave
 *   perturbation reads the reflection up to `margin` rows above or below) declares
 *   `margin` and `scratch` (colour + depth entries per pixel it draws into off-screen):
 *   the driver then gives it, per band, a scratch band covering rows
 *   [y0 - margin, y0 + rows + margin) clipped to the frame, which later passes of the
 *   same band may read through rs_band.scratch[i].  A pass without scratch draws into the
 *   band itself (colour and depth, depth test "greater wins" as raster.h states).
 *
 * SKIPPING
 *   rows_touched(user, y0, rows) returns 0 when the pass cannot touch any row of
 *   [y0 - margin, y0 + rows + margin): the driver then skips it for that band and marks
 *   its scratch absent (rs_band.scratch[i] == NULL); a later pass must cope.
 *
 * MEMORY: nothing is allocated here.  rs_pipe_mem_size gives the bytes for one band
 * (colour, depth and every pass's scratch with its margins); a thread needs one such
 * block of its own.
 */
#ifndef BR_FRAME_H
#define BR_FRAME_H
#include <stddef.h>
#include <stdint.h>
#include "core/status.h"
#include "raster/raster.h"

#define RS_PIPE_MAX_PASSES 8

/* rs_band_stats (raster.h): what one band cost, summed by the caller per band. */

/* One band being drawn.  color/depth are the band's rows [y0, y0 + rows): colour in the
 * pipe's format, stride bytes per row; depth w * rows entries (uint32 or uint16). */
typedef struct rs_band {
    int32_t w, y0, rows;
    int32_t fmt, depth_fmt;     /* RS_FMT_*, RS_DEPTH* */
    void *color;
    size_t stride;
    void *depth;
    /* scratch[i]: pass i's off-screen band (NULL when pass i has none or was skipped):
     * colour then depth, rows scratch_y0[i] .. scratch_y0[i] + scratch_rows[i] - 1,
     * scratch_stride[i] bytes a colour row, depth rows contiguous after the colour. */
    void *scratch[RS_PIPE_MAX_PASSES];
    int32_t scratch_y0[RS_PIPE_MAX_PASSES], scratch_rows[RS_PIPE_MAX_PASSES];
    size_t scratch_stride[RS_PIPE_MAX_PASSES];
    void *scratch_depth[RS_PIPE_MAX_PASSES];
} rs_band;

typedef struct rs_pass {
    const char *name;           /* "terrain", "reflection", "water", ... (statistics, HUD) */
    int32_t margin;             /* rows above and below the band this pass draws into its
                                   scratch (0 .. RS_MAX_DIM) */
    int32_t scratch;            /* 1: the pass draws into its own scratch band (colour +
                                   depth in the pipe's formats, over the band's rows plus
                                   margins); 0: it draws into the band itself */
    /* 0 when the pass cannot touch rows [y0, y0 + rows) (already widened by its margin);
     * NULL: it may touch every band */
    int (*rows_touched)(const void *user, int32_t y0, int32_t rows);
    /* Draws the band: into b->color/b->depth, or (scratch) into b->scratch[self]...  The
     * scratch band is cleared by the pass itself.  Adds its cost to st.  Must only read
     * frame-wide data through user (several bands may run at once). */
    br_status (*run)(const void *user, rs_band *b, int32_t self, rs_band_stats *st);
    const void *user;
} rs_pass;

/* Called with each band after all passes: sees and may change colour and depth (fog,
 * water compositing, the HUD).  Same thread rules as a pass. */
typedef br_status (*rs_post_fn)(const void *user, rs_band *b, rs_band_stats *st);

typedef struct rs_pipe {
    int32_t w, h;               /* frame size, 1 .. RS_MAX_DIM */
    int32_t fmt, depth;         /* RS_FMT_*, RS_DEPTH* of the band */
    rs_pass passes[RS_PIPE_MAX_PASSES];
    int32_t npasses;
    rs_post_fn post;            /* NULL: none */
    const void *post_user;
} rs_pipe;

/* Appends a pass; BR_E_ARG when full or the pass is malformed. */
br_status rs_pipe_add(rs_pipe *p, const rs_pass *pass);

/* Bytes of band memory for bands of band_rows rows: colour + depth + every scratch pass's
 * colour + depth over band_rows + 2 margin rows; 16-byte aligned parts. */
size_t rs_pipe_mem_size(const rs_pipe *p, int32_t band_rows);

/* Draws rows [y0, y0 + rows) (rows <= the band_rows mem was sized for) into mem: every
 * pass in order (skipping those whose rows_touched says 0), then the post hook.  Writes
 * the band's description into *b (colour at the start of mem, stride w * bytes per
 * pixel) and its cost into *st (zeroed first).  Thread-safe for distinct mem/b/st. */
br_status rs_pipe_band(const rs_pipe *p, int32_t y0, int32_t rows, void *mem, size_t mem_size,
                       rs_band *b, rs_band_stats *st);

/* The whole frame: bands of band_rows rows top to bottom (the last may be shorter), each
 * handed to sink in order; *total (may be NULL) gets the sum of the bands' statistics. */
br_status rs_pipe_run(const rs_pipe *p, int32_t band_rows, void *mem, size_t mem_size,
                      rs_sink sink, void *sink_user, rs_band_stats *total);

/* The terrain pass: draws the prepared rs_frame f (rs_frame_prepare done; chunk table
 * required: rs_pass_terrain fills pass->user = f and fails with BR_E_ARG when
 * f->chunks is NULL) into the band.  A frame prepared with one_band set is drawn only
 * as one whole-frame band: the pass fails with BR_E_ARG on a shorter band. */
br_status rs_pass_terrain(rs_pass *pass, const rs_frame *f);

#endif
