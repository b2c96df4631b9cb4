/* raster/terrain_stream.h — the terrain drawn band by band straight from the bitree's
 * streamed walk (core/bitree.h bt_stream_*), with no whole-frame vertex array, strip or
 * vertex cache: the frame path of a board whose RAM holds one band (docs/mcu.md).
 *
 * Each band walks the tree for its rows; the leaves it is handed go into a small batch
 * (cap_v raster vertices shaded by rt_vertex, their transforms, cap_t triangles as a
 * list), and a full batch is prepared (rs_frame_prepare) and drawn into the band over
 * what the batch before drew (rs_draw_band, the band cleared by the first).  A vertex is
 * shaded and transformed once a batch: points the walk hands again keep their batch
 * index in bt_svert.tag, others are found by a small hash of grid positions.
 *
 * Pixels.  The triangles each band draws are the walk's leaves that may reach its rows,
 * in the walk's order, each apex first: a pixel is the one the whole leaf list drawn in
 * that order gives, whatever the band height and the batch size (a batch boundary only
 * splits the list; the depth test sees the same triangles in the same order, and without
 * depth, RS_DEPTH_NONE, the last drawn over a pixel is the same triangle).  They are
 * the real triangles of bt_extract's mesh without hysteresis, so the frame is that mesh
 * drawn as a list with each triangle's first vertex at its apex; the strip's own
 * frames differ from it by the rasteriser's rounding from another first vertex and by
 * the strip's line triangles (tests/test_stream.c pins both).
 *
 * Memory (caller's): rt_stream_mem_size(cap_v, cap_t), per vertex 16 (rs_vertex) + 24
 * (rs_cvert, 32 with RS_TEX_FIELDS) + 12 (two hash slots), per triangle 3 indices and a
 * chunk entry per 64; the walk's bt_stream and the band are the caller's too.
 *
 * Threads: a stream pass writes its batch while it draws a band, so a pipe with it runs
 * its bands one after the other (the board's single core). */
#ifndef BR_TERRAIN_STREAM_H
#define BR_TERRAIN_STREAM_H
#include <stddef.h>
#include <stdint.h>
#include "core/bitree.h"
#include "raster/frame.h"
#include "raster/terrain.h"

typedef struct rt_stream {
    const rt_scene *scene;      /* shading and the grid's world frame */
    bt_stream *walk;            /* bt_stream_frame done for this frame */
    rs_frame fr;                /* the frame's w, h, fmt, depth, vp, clear_rgb, clear_rows,
                                   no_cull (the rest is the batch's, set per batch) */
    /* the batch (rt_stream_init carves them) */
    rs_vertex *v;
    rs_cvert *cache;
    br_index *idx;
    int16_t *chunks;
    uint32_t *hkey;             /* grid key + 1 per slot, 0: empty */
    uint16_t *hval;             /* the slot's batch index */
    uint32_t cap_v, cap_t, hmask, n_key;
    uint32_t nv, nt, gen;
    rs_prim prim;
    /* the band being drawn */
    rs_band *band;
    rs_band_stats *st;
    int cleared;
    br_status err;
    uint32_t leaves, batches;   /* since rt_stream_init: leaves drawn, batches prepared */
} rt_stream;

/* Bytes for a batch of cap_v vertices (3 .. 4096) and cap_t triangles (>= 1); 0 if bad. */
size_t rt_stream_mem_size(uint32_t cap_v, uint32_t cap_t);
/* Carves mem (8-byte aligned) for s; s->scene, s->walk and s->fr are the caller's to set
 * before a frame.  BR_E_ARG on bad sizes. */
br_status rt_stream_init(rt_stream *s, uint32_t cap_v, uint32_t cap_t, void *mem, size_t mem_bytes);
/* The pass that draws the stream into each band (raster/frame.h); the pipe's format and
 * depth must be s->fr's.  The pass's run fails with the first error of a batch. */
br_status rs_pass_stream(rs_pass *pass, rt_stream *s);
/* A frame of camera c (its w, h) in pixel format fmt and depth (RS_DEPTH_*; RS_DEPTH_NONE
 * for a walk that hands its leaves back to front, bt_stream_order) over the sky colour
 * clear_rgb: sets s->fr, and *pipe to draw it with s's pass alone (rs_pipe_run; the
 * walk's bt_stream_frame for c is the caller's). */
br_status rt_stream_pipe(rt_stream *s, const cam *c, int32_t fmt, int32_t depth, uint32_t clear_rgb, rs_pipe *pipe);

#endif
