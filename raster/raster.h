/* raster/raster.h — the integer software rasteriser: vertex arrays + triangle
 * strips/lists in, exact pixels out, a whole frame or one band of rows at a time.
 *
 * CONVENTIONS
 * - World: int32 x east, y north, z up, in the scene's world unit; |coord| <= CAM_COORD_MAX.
 *   The camera is core/cam.h (gluLookAt/gluPerspective conventions, square pixels).
 * - Screen: origin at the top-left corner, x right, y DOWN; row 0 is the top row and
 *   bands run top to bottom.  Pixel (i, j) is sampled at its centre (i + 1/2, j + 1/2).
 * - Sub-pixel precision: RS_SUBPIX_BITS = 4 (vertices snap to 1/16 pixel, rounded).
 *   Guard band: vertices within RS_GUARD_PX = 2^14 pixels of the screen centre are
 *   drawn unclipped; screen coordinates then stay below 2^18 sub-pixels, so edge
 *   functions (products of two differences < 2^19) need 39 bits (int64) and never
 *   overflow.  Largest viewport: RS_MAX_DIM = 4096 x 4096 (inside the guard band;
 *   also bounds the colour rounding drift along a span, see raster.c).
 * - Fill rule: top-left, on pixel centres: a centre exactly on an edge belongs to the
 *   triangle when that edge is a left edge or a horizontal top edge; so triangles
 *   sharing an edge cover every centre exactly once.  Zero-area (line, degenerate)
 *   triangles draw nothing.
 * - Orientation / culling: front faces are counter-clockwise seen from the camera
 *   (OpenGL default; the terrain's triangles are CCW seen from +z).  Back faces are
 *   culled unless rs_frame.no_cull is set.
 * - Near plane: triangles are clipped in camera (homogeneous) space against
 *   zc >= znear BEFORE the divide (terrain cameras sit on the ground), and against
 *   the guard band; a clipped polygon has at most 3 + 5 = 8 vertices (each of the 5
 *   planes adds at most one), the fixed clip buffer size.  Far plane: the depth buffer
 *   is cleared to the depth of zfar, so every pixel beyond zfar fails the depth test
 *   (a per-pixel far cut-off); triangles wholly beyond zfar are rejected early.
 * - Depth: d = D * znear / zc with D = 2^30 - 2^18 (1/w, "reversed": larger is nearer,
 *   the near plane maps to D).  1/w is affine in screen space, so linear interpolation
 *   is exact up to rounding, and its resolution is finest near the camera and falls
 *   off as zc^2: with 32-bit depth the step at distance zc is zc^2 / (znear * 2^30)
 *   (peer camera B, znear 0.25: 0.0004 units at 300 units; 0.004 units at 1000 units),
 *   far below the spacing of terrain surfaces that overlap on screen.  The 16-bit
 *   buffer keeps d >> 14 (step zc^2 / (znear * 2^16)); it is for small screens with a
 *   near plane that is not tiny relative to the far distance.  Depth test: greater wins.
 * - Colour: per-vertex 0xRRGGBB, Gouraud-interpolated affinely in screen space with
 *   16 fraction bits, rounded to nearest; RGB565 takes the top 5/6/5 bits of the same
 *   8-bit values, so an RGB565 frame equals the RGB888 frame reduced.
 * - Bands: a band is rows [y0, y0 + rows) of the frame.  Triangle set-up depends only
 *   on the transformed vertices, and every pixel value is computed from the
 *   triangle's own reference point (never from the band's first row), so any band
 *   height gives exactly the pixels of the full frame.
 *
 * MEMORY (caller-owned; nothing is allocated here)
 * - vertex cache: rs_cache_mem_size(nv) = 32 bytes per vertex (one transform per vertex
 *   per frame, shared by all bands);
 * - band: rs_band_mem_size(w, rows, fmt, depth) = w * rows * (2 or 4 colour + 2, 4 or no
 *   depth);
 * - chunk table: rs_chunk_mem_size(prims, nprims) = 4 bytes per RS_CHUNK = 64 triangles.
 *   REQUIRED: rs_frame_prepare refuses a frame without it (BR_E_ARG), so no caller can
 *   forget it; with it a band skips every chunk that cannot touch its rows, and a chunk
 *   wholly off screen is skipped by every band.  Filling it costs about a tenth of a
 *   whole-frame draw, which a single band gains nothing from: a frame drawn only whole
 *   sets rs_frame.one_band (the table is then filled with "every row" for the cost of
 *   two stores a chunk), and the frame driver refuses to band such a frame.
 *   320x240 RGB565 with 16-bit depth, bands of 16 rows: 20,480 bytes (+ 32 per vertex);
 *   with 32-bit depth 30,720 bytes.
 *
 * Not checked in the hot path (debug asserts only): indices < nv, band inside the frame.
 */
#ifndef BR_RASTER_H
#define BR_RASTER_H
#include <stddef.h>
#include <stdint.h>
#include "core/cam.h"
#include "core/status.h"
#include "core/config.h"

#define RS_SUBPIX_BITS 4
#define RS_GUARD_PX (1 << 14)
#define RS_MAX_DIM 4096
#define RS_DEPTH_ONE ((1u << 30) - (1u << 18))
#define RS_CLIP_MAX 9   /* 3 vertices + one per clip plane (near, 4 guard-band sides, the
                           optional world plane z >= clip_z of rs_frame) */

enum { RS_FMT_XRGB8888 = 0, RS_FMT_RGB565 = 1 };
/* RS_DEPTH_NONE: no depth buffer; each covered pixel centre is written, so a pixel shows
 * the last triangle drawn over it: the caller draws back to front (painter's order, as
 * core/bitree.h's streamed walk hands its leaves with BT_STREAM_BACK_TO_FRONT).  Lists
 * only (rs_draw_band: BR_E_ARG for a strip), no textures; no far plane test per pixel
 * (the far plane's depth is the buffer's clear value): the caller draws nothing beyond
 * it.  Half the band's bytes at RGB565. */
enum { RS_DEPTH32 = 0, RS_DEPTH16 = 1, RS_DEPTH_NONE = 2 };
/* Bytes of one depth entry: 4, 2, or 0 without depth */
static inline size_t rs_depth_bytes(int32_t depth)
{
    return depth == RS_DEPTH_NONE ? 0u : depth == RS_DEPTH16 ? 2u : 4u;
}
enum { RS_STRIP = 0, RS_LIST = 1 };

/* Input vertex: world position, colour 0x00RRGGBB (shaded per vertex by the caller or
 * by raster/ramp.h) and, for textured frames, texture coordinates in texels, Q8
 * (0 .. tex.w * 256; v = 0 is the texture's top row). */
typedef struct rs_vertex {
    int32_t p[3];
    uint32_t rgb;
#if RS_TEX_FIELDS
    int32_t uv[2];
#endif
} rs_vertex;

/* A texture (colour map, orthophoto): w x h XRGB8888 texels, row 0 at the top,
 * 1 .. RS_MAX_TEX texels a side.  Sampling: nearest texel, coordinates clamped to the
 * edge.  A textured pixel is the texel times the Gouraud colour / 255 (so a vertex
 * colour of white shows the texel unchanged and the lighting can be baked as grey).
 * Perspective: at every pixel u = sum(e_i q_i u_i) / sum(e_i q_i) from the pixel's exact
 * edge values e_i (20 significant bits) and the vertices' 1/w q_i (16 bits relative to
 * the triangle's nearest vertex): texel position error below (2^-20 + 2^-16 * the
 * triangle's far/near depth ratio) of its texel extent, plus 1/256 texel rounding. */
#define RS_MAX_TEX 16384
typedef struct rs_texture {
    int32_t w, h;
    const uint32_t *px;
} rs_texture;

/* A generalised triangle strip (GL convention: triangle k = s[k], s[k+1], s[k+2], the
 * first two swapped for odd k) or a plain list (triangle k = s[3k..3k+2]). */
typedef struct rs_prim {
    int32_t kind;               /* RS_STRIP or RS_LIST */
    uint32_t n;                 /* number of indices */
    const br_index *idx;        /* (core/config.h: 32 bits, or 16 with BR_INDEX16) */
} rs_prim;

/* Triangles of a primitive (a strip's line triangles, whose indices repeat, included). */
static inline uint32_t rs_prim_tris(const rs_prim *pr)
{
    if (pr->n < 3) return 0;
    return pr->kind == RS_STRIP ? pr->n - 2 : pr->n / 3;
}

/* Triangle t of pr, its vertices in the order the rasteriser draws them: a strip's even
 * triangles s[t], s[t + 1], s[t + 2], its odd ones s[t + 1], s[t], s[t + 2]; a list's
 * s[3t] .. s[3t + 2]. */
static inline void rs_prim_tri(const rs_prim *pr, uint32_t t, uint32_t *ia, uint32_t *ib, uint32_t *ic)
{
    const br_index *s = pr->idx;
    if (pr->kind == RS_STRIP) {
        *ia = s[t + (t & 1)]; *ib = s[t + 1 - (t & 1)]; *ic = s[t + 2];
    } else {
        *ia = s[3 * t]; *ib = s[3 * t + 1]; *ic = s[3 * t + 2];
    }
}

/* Vertex cache entry (32 bytes; 24 without RS_TEX_FIELDS): screen position in
 * sub-pixels, depth, colour with the outcode in the top byte of c, the colour in the
 * rasteriser's packed interpolation form (8-bit R, G, B at bits 42, 21, 0, see
 * raster.c), texture coordinates. */
typedef struct rs_cvert {
    int32_t x, y;
    uint32_t d;
    uint32_t c;
    uint64_t cp;
#if RS_TEX_FIELDS
    int32_t u, v;       /* texture coordinates, texels Q8 (rs_frame_prepare writes them
                           for textured frames only; untextured drawing never reads them) */
#endif
} rs_cvert;

/* Outcode bits (in rs_cvert.c >> 24). */
enum {
    RS_OUT_LEFT = 1, RS_OUT_RIGHT = 2, RS_OUT_TOP = 4, RS_OUT_BOTTOM = 8,
    RS_OUT_FAR = 16,            /* zc > zfar */
    RS_OUT_NEAR = 32,           /* zc < znear: x, y, d invalid */
    RS_OUT_GUARD = 64,          /* outside the guard band: x, y invalid */
    RS_OUT_CLIPZ = 128          /* rs_frame.clip_z_on: the vertex's world z < clip_z */
};

/* A polygon the clipper made, in a frame's clip table (rs_frame.clips): triangle (ia,
 * ib, ic) in the order the draw hands it to the clipper, n projected vertices (0: none
 * left), made by the last prepare of frame owner (NULL: an empty entry). */
typedef struct rs_clip_poly {
    const void *owner;
    uint32_t ia, ib, ic;
    int32_t n;
    rs_cvert v[RS_CLIP_MAX];
} rs_clip_poly;

/* One frame.  Zero-initialise, fill the inputs, call rs_frame_prepare, then render
 * (whole frame or bands).  Zero fields mean defaults. */
typedef struct rs_frame {
    int32_t w, h;               /* viewport, 1 .. RS_MAX_DIM */
    int32_t fmt;                /* RS_FMT_* */
    int32_t depth;              /* RS_DEPTH32, RS_DEPTH16 or RS_DEPTH_NONE */
    int32_t no_cull;            /* 1: draw back faces too */
    uint32_t clear_rgb;         /* background (sky) colour 0xRRGGBB */
    const rs_vertex *v;         /* nv vertices */
    uint32_t nv;
    rs_cvert *cache;            /* caller memory, rs_cache_mem_size(nv) bytes */
    const rs_prim *prims;
    int32_t nprims;
    cam_vp vp;                  /* from cam_viewproj; the camera's w, h must equal w, h */
    const rs_texture *tex;      /* NULL: Gouraud colour only */
    int16_t *chunks;            /* required by rs_frame_prepare: rs_chunk_mem_size(prims,
                                   nprims) bytes; per RS_CHUNK triangles the rows they can
                                   touch, filled by rs_frame_prepare; bands skip the chunks
                                   that miss them */
    int32_t one_band;           /* 1: drawn only as one whole-frame band; rs_frame_prepare
                                   then marks every chunk as touching every row instead of
                                   computing its rows (which a single band would not use),
                                   and the terrain pass (raster/frame.h) refuses shorter
                                   bands.  0 (default): any bands */
    int32_t clip_z_on;          /* 1: draw only what lies at world z >= clip_z (the vertices'
                                   own z, before vp): a clip plane in the clipper (planar
                                   reflections: nothing under the water plane leaks in) */
    int32_t clip_z;
    int32_t no_clear;           /* 1: rs_draw_band draws over the colour and depth the caller
                                   put in the band (a pass seeding the depth test) */
    const uint32_t *clear_rows; /* NULL: the background is clear_rgb.  Else 4 colours 0xRRGGBB
                                   per frame row: pixel (x, y) is cleared to
                                   clear_rows[4 y + (x & 3)] in the frame's format (a sky
                                   gradient by row with a 4x4 ordered dither for RGB565,
                                   raster/water.h) */
    rs_clip_poly *clips;        /* optional (NULL: none): clip_cap entries, a power of two,
                                   of caller memory (rs_clip_mem_size).  rs_frame_prepare
                                   clips each triangle of the chunks that reach the near
                                   plane or the guard band once, into it, until it is
                                   full; a band draws those from their polygon instead of
                                   clipping them again (the same polygon: the same pixels
                                   with or without it, at any band height and thread
                                   count).  The others, the world plane's and any beyond
                                   the table's room, are clipped by each band they meet */
    uint32_t clip_cap;
    int32_t debug_count;        /* tests: colour must be XRGB8888; each covered pixel's
                                   32-bit value counts the writes (no depth test, no sky).
                                   Only builds with RS_WITH_COUNT = 1 draw it (the tests'
                                   tests/support/raster_count.c); the library refuses it
                                   with BR_E_UNSUPPORTED */
} rs_frame;
/* A prepared rs_frame is read-only to drawing: what a band cost comes back in the
 * caller's rs_band_stats (below), so bands on several threads share nothing. */

/* Called with each finished band: rows [y0, y0+rows) of the frame, pixels in the
 * frame's format, stride bytes apart.  Return BR_OK to continue. */
typedef br_status (*rs_sink)(void *user, int32_t y0, int32_t rows, const void *pixels, size_t stride);

size_t rs_cache_mem_size(uint32_t nv);
/* Bytes for rs_frame.chunks: 4 per RS_CHUNK triangles of each primitive (at least 4). */
#define RS_CHUNK 64
size_t rs_chunk_mem_size(const rs_prim *prims, int32_t nprims);
size_t rs_band_mem_size(int32_t w, int32_t rows, int32_t fmt, int32_t depth);
/* Bytes for a clip table of n entries (rs_frame.clips; n a power of two). */
size_t rs_clip_mem_size(uint32_t n);

/* Fills one cache entry from screen-space data (sub-pixels, depth d <= RS_DEPTH_ONE,
 * colour 0xRRGGBB), for callers that project themselves (tests, 2D overlays): such a
 * frame skips rs_frame_prepare.  |x|, |y| must stay within the guard band
 * (< RS_GUARD_PX * 16 from the screen centre); the clipper is never needed. */
void rs_cvert_set(rs_cvert *o, int32_t w, int32_t h, int32_t x, int32_t y, uint32_t d, uint32_t rgb);

/* Gives a prepared cache entry the colour 0xRRGGBB (outcode, position and depth kept):
 * per-vertex effects after rs_frame_prepare (raster/water.h's fog). */
void rs_cvert_recolour(rs_cvert *o, uint32_t rgb);

/* Checks the frame (BR_E_ARG when chunks or cache is NULL, or a field is out of range),
 * transforms every vertex once into the cache and fills the chunk table (per frame).
 * A frame set up with rs_cvert_set instead may leave chunks NULL: rs_draw_band then walks
 * every triangle in every band. */
br_status rs_frame_prepare(rs_frame *f);

/* What drawing one band cost (raster/frame.h sums them per band, so that bands drawn on
 * several threads share nothing). */
typedef struct rs_band_stats {
    uint32_t tris;              /* triangles set up (not rejected before set-up) */
    uint32_t clipped;           /* triangles that went through the clipper */
    uint32_t pixels;            /* pixels written (depth test passed) */
    uint32_t passes_run;        /* raster/frame.h: bit i set when pass i ran on the band */
} rs_band_stats;

/* Renders rows [y0, y0+rows) into caller buffers: colour (stride bytes per row) and a
 * depth buffer of w*rows entries (uint32 or uint16; RS_DEPTH_NONE: none, depth may be
 * NULL).  Clears both first (unless
 * f->no_clear).  Reads f only
 * (several threads may draw bands of one prepared frame at once) and ADDS the band's
 * cost to *st (st may be NULL).
 * BR_E_UNSUPPORTED: this build left the frame's variant out (rs_variant_built). */
br_status rs_draw_band(const rs_frame *f, int32_t y0, int32_t rows, void *color, size_t stride, void *depth,
                       rs_band_stats *st);

/* 1 when this build draws frames of this pixel format, depth size and texturing.
 * Every combination is compiled by default; boards with little flash leave variants out
 * with core/config.h's RS_WITH_* knobs (each is about 20 KB of code on x86-64). */
int rs_variant_built(int32_t fmt, int32_t depth, int textured);

/* The instruction set the drawing code runs with.  x86-64 builds carry two copies of it,
 * compiled from the same source: baseline x86-64 (SSE2) and x86-64-v3 (AVX2, BMI2,
 * three-operand forms), chosen at the first frame from what the CPU supports.  The
 * copies give the same bytes (integer code; make test compares them).  Other targets
 * have one copy (RS_ISA_BASE).  rs_isa_set(RS_ISA_AUTO) restores the automatic choice,
 * RS_ISA_BASE or RS_ISA_V3 forces one (tests, benchmarks); it returns the set in use,
 * which is RS_ISA_BASE when V3 is asked for but not built or not supported.  Not
 * thread-safe against frames being drawn: set it before. */
enum { RS_ISA_AUTO = 0, RS_ISA_BASE = 1, RS_ISA_V3 = 2 };
int rs_isa_set(int isa);
/* The set in use (choosing it on first use) and its name ("x86-64", "x86-64-v3",
 * "generic"). */
int rs_isa(void);
const char *rs_isa_name(int isa);

/* XRGB8888 or RGB565 pixel rows to RGB888 bytes (RGB565 expanded by bit replication). */
void rs_to_rgb888(int32_t fmt, const void *src, int32_t n, uint8_t *rgb);

#endif
