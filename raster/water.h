/* raster/water.h — water and atmosphere on the one frame driver (raster/frame.h):
 * the reflection pass, the water pass and the post hook that composites water, sky
 * gradient and fog.  Integer only; every pixel from frame-wide data, so any band height
 * gives the frame's pixels (DESIGN.md invariant 4).
 *
 * PASSES (the caller adds them in this order after the terrain pass):
 *   terrain (rs_pass_terrain);
 *   water (scratch, no margin): the water surfaces' strips, their vertex colour the body
 *     id (RW_ID_RGB), into the pass's scratch: id and depth of the water per pixel, in the
 *     rows wlo .. whi only (below the horizon when every water vertex is below the eye);
 *   reflection (scratch, margin RW_WAVE_PX): the terrain mirrored in the reflected water
 *     plane z = plane_z (z -> 2 plane_z - z by the view matrix, rw_mirror_vp), only what
 *     lies at or above the plane (rs_frame.clip_z: the clipper's plane, so nothing under
 *     the water leaks in), winding flipped by the caller (the strip with its first index
 *     doubled), drawn at full, half or quarter resolution (res_shift 0, 1, 2) into the
 *     pass's scratch band, only in the rows the hook reads: those of the band's rows that
 *     hold a water id in the water pass's scratch, widened by RW_WAVE_PX (added before
 *     the water pass, it draws every row where water may show).
 * POST HOOK rw_post (user: the rw_frame):
 *   water pixels: a water id whose depth is nearer than the terrain's (of a tested
 *     triangle, RW_TESTED_RGB: and whose plane point lies in a half cell with a wet corner
 *     and no low one), or whose terrain
 *     lies on a wet sample of that body (the shore test: the terrain's point on the
 *     pixel's ray, found from the plane's point by the ratio of the two depths, looked up
 *     in `wet`): the coarse terrain LOD may draw the bottom under flattened water above
 *     the surface (its screen error allows it far away), while dry land, however low,
 *     stays land and hills in front of the water stay in front; and land where the
 *     terrain's LOD sank dry land under the plane (the land test, rw_params.land);
 *     colour = refraction (1 - F) + reflection F,
 *     F = R0 + (1 - R0)(1 - cos t)^5 (Schlick), R0 = ((n - 1)/(n + 1))^2, n = 1.33,
 *       cos t = |ray_z| / |ray| of the pixel's view ray, from a table by cos^2 t;
 *     reflection: the reflection scratch at the pixel moved by the waves (RW_WAVE_PX at
 *       most), or, where it holds no terrain, the sky gradient in the reflected direction;
 *       bodies other than refl_body reflect the sky only (the cheaper approximation);
 *     refraction: the terrain under the water tinted towards water_rgb by
 *       1 - exp(-L / tint_len), L the path through the water along the ray
 *       (zc_terrain - zc_water = zc_water (dw / dt - 1): zc_water of the row's plane point,
 *       dw / dt from the two depths brought to 16 bits, a 32-bit division);
 *     fogged by the water's own depth;
 *   sky pixels (the terrain pass's far depth): the sky gradient by row, horizon to zenith
 *     by the sine of the row's elevation (the camera's pitch included), the terrain
 *     frame's clear_rows (rw_fog_vertices);
 *   fog: a weight rising from 0 at fog_start to 1 at fog_end (squared), distances along
 *     the view axis, mixing towards the row's sky colour: per vertex for the terrain
 *     (rw_fog_vertices), per pixel for water (and for textured terrain, whose texels
 *     the vertex colour would only modulate);
 *   RGB565: the sky and the pixels this hook writes get a 4x4 ordered dither before the
 *     5/6/5 truncation (fixed by screen position, so bands stay exact); the fogged
 *     terrain is truncated as all terrain shading is.
 * Waves: RW_WAVES travelling sines of world position on the water plane and time (003's
 * parametric wave of per-vertex time and flow direction, per pixel here), of different
 * directions, lengths and periods (water_setup.c wave_set); their slopes move the
 * reflection lookup (at most RW_WAVE_PX pixels, scaled by 1/distance) and tilt cos t.
 * time_ms fixes the instant.
 *
 * Approximations (docs/water.md): the per-row ray z ignores the camera's roll term (cam
 * look-at cameras have none); the reflection at half or quarter resolution is sampled
 * at the nearest reduced row at or below the pixel (water.c refl_row); one plane per
 * frame gets a mirror.
 *
 * DIVISION: no 64-bit division per frame where core/config.h's BR_DIV64_NATIVE is 0
 * (the set-up's quotients through fx_recip, the per-pixel ones 32-bit).
 *
 * MEMORY: rw_frame is caller-owned (about 370 KB: per-row and per-column tables for up to
 * RS_MAX_DIM), zero-initialised by the caller before its first rw_setup, then filled by
 * rw_setup each frame (the frame-independent tables only the first time); nothing is
 * allocated. */
#ifndef BR_RWATER_H
#define BR_RWATER_H
#include <stdint.h>
#include "core/cam.h"
#include "raster/frame.h"
#include "raster/terrain.h"

#define RW_COL_ROWS 8           /* rows that share one column range of the water pass's seed */
#define RW_WAVE_PX 4            /* largest wave displacement of the reflection lookup, pixels */
#define RW_WAVES 4              /* travelling sines summed (water_setup.c wave_set) */
#define RW_MAX_ID 31            /* body ids 1 .. 31 survive RGB565 in the water pass's red bits */
#define RW_ID_RGB(id) ((uint32_t)(id) << 19)
#define RW_ID_MASK RW_ID_RGB(31)
/* A water vertex colour's flag (green's top bit, which RGB565 keeps as its bit 10): where
 * its triangles are nearer than the terrain, their pixels are water only where the
 * plane's point on the pixel's ray lies in a half cell the water mesh split down to cells
 * would cover (wet and `low`, rw_params): the mesh's tested blocks cover low dry land
 * beside the water (platform/water_mesh.c). */
#define RW_TESTED_RGB ((uint32_t)1 << 15)
#define RW_TAB 1024             /* tables by cos^2 t, Q10 */

typedef struct rw_params {      /* zero = off / defaults as stated */
    int32_t water_on;           /* 1: reflection and water passes run */
    int32_t fog_on, sky_on;     /* 1: fog; 1: sky gradient */
    int32_t res_shift;          /* reflection resolution: 0 full, 1 half, 2 quarter */
    int32_t plane_z;            /* world units: the reflected plane */
    int32_t refl_body;          /* body id with the mirror (0: none, sky only) */
    uint32_t water_rgb;         /* deep water colour (0: 0x1c4660) */
    uint32_t sky_horizon, sky_zenith;   /* (0: 0xc8dcf0, 0x5a8cd2) */
    int64_t fog_start, fog_end; /* world units along the view axis, 0 < start < end */
    int64_t tint_len;           /* world units: light falls to 1/e over this path (> 0) */
    int32_t tint_fixed;         /* 1 .. 256: the refraction's tint weight (Q8) for every
                                   water pixel, the stated default for water without
                                   bathymetry (SRTM's flattened lakes and sea); 0: from
                                   the path through the water, as above */
    int32_t waves_on;
    int32_t time_ms;            /* the instant drawn */
    int64_t wave_len;           /* world units, the longer of the two waves (> 0) */
    int64_t wave_amp;           /* world units: displacement at distance 1 scales as f / zc */
    int32_t fresnel_one;        /* tests: F = 1 everywhere */
    /* Where the water is (the shore test below; NULL: none, nearer terrain always wins):
     * wet[y * wet_w + x] the body id of grid sample (x, y) where it is wet, 0 dry; the grid
     * maps to world x = grid_ox + x grid_sx, y = grid_oy - y grid_sy; body_z[id] the world
     * height of body id's plane. */
    const uint8_t *wet;
    /* low[y * wet_w + x] (same grid; NULL: none): 1 where a tested triangle's plane may
     * not lie (dry land below its level that reaches water or the grid's edge, a void):
     * a tested pixel in a half cell with such a corner is not water. */
    const uint8_t *low;
    /* The land test (NULL: none; wet set, the terrain's grid): a pixel whose water is
     * nearer than the terrain, by no more than the shore bound below allows for dry
     * land at or above the body's level that the LOD drew lower, is land where the plane's
     * point on its ray lies on a valid dry sample, coloured as that sample
     * (rt_sample_rgb), or under a texture (land->tex_w > 0: land_tex, the frame's
     * texture) the texel at the plane's point times that sample's lighting. */
    const rt_scene *land;
    const rs_texture *land_tex;
    int32_t land_z[RW_MAX_ID + 1];      /* body id's level in the heightfield's units: a
                                           corner lower than it is not land */
    int32_t wet_w, wet_h;
    int64_t grid_ox, grid_oy, grid_sx, grid_sy;
    int32_t body_z[RW_MAX_ID + 1];
    /* What bounds the shore test (0: every water pixel with nearer terrain is tested).
     * The terrain drawn over a wet sample lies at most shore_w + shore_px zc / f world units
     * above the true bottom (below the surface): shore_w the LOD's error in world units
     * (fidelity meshes), shore_px its screen error in pixels (view-dependent meshes), with a
     * margin; a terrain point higher above a body's plane is land.  In depths: E (dt - dw)
     * <= shore_w dt + shore_c, E = eye z - body z, shore_c = shore_px K / f, K = D znear. */
    int32_t shore_bound;
    int64_t shore_w, shore_c;
    uint32_t seen_mask;         /* bit id: body id may show in this frame (0: unknown, any) */
} rw_params;

typedef struct rw_frame {
    rw_params p;
    const rs_frame *terrain, *water, *refl;
    int32_t refl_pass, water_pass;      /* indices of the passes in the pipe (-1: absent) */
    int32_t w, h, fmt, depth;
    int32_t wlo, whi;           /* rows where water may show (wlo > whi: none) */
    int32_t rlo, rhi;           /* rows where refl_body's water may show (rlo > rhi: none) */
    uint32_t dfar, rdfar;       /* clear depths of terrain and reflection (buffer units) */
    int64_t eye[3];             /* world units */
    int32_t aq[RS_MAX_DIM];     /* per column: ray a = (x + 1/2 - cx) / f, Q12 */
    int32_t bq[RS_MAX_DIM];     /* per row: ray b = (cy - y - 1/2) / f, Q12 */
    int64_t abq_of[3];          /* the f_q16, w and h that aq and bq were made for (0: none) */
    int32_t rz[RS_MAX_DIM];     /* per row: world z of the ray (a = 0), Q12 */
    uint32_t sky[RS_MAX_DIM];   /* per row: sky colour */
    uint8_t trow[RS_MAX_DIM];   /* per row: 1 when a tested water triangle may cover it */
    int16_t wx0[RS_MAX_DIM / RW_COL_ROWS], wx1[RS_MAX_DIM / RW_COL_ROWS];
                                /* per RW_COL_ROWS rows (y / RW_COL_ROWS), in rows wlo .. whi: the
                                   columns the water frame's triangles may read or write there
                                   (wx0 > wx1: none); the pass seeds only those (water_cols) */
    int64_t wrel[RS_MAX_DIM][2], wstep[RS_MAX_DIM][2];  /* per row: plane point = eye + rel + a step
                                                           (Q12 a, world units); made in rows wlo ..
                                                           whi only (wrel, wstep, wsig, tkr: the
                                                           hook reads no others), 0 elsewhere */
    int64_t kx[RW_WAVES], ky[RW_WAVES]; /* wave phase per world unit (x, y), 2^-32 turns (mod 2^32) */
    uint32_t kt[RW_WAVES];              /* wave phase per ms, 2^-32 turns */
    int64_t wsig[RS_MAX_DIM][2];        /* per row: the plane point's move per unit of u = 2x + 1 - w,
                                           world units Q16 (wstep 2^31 / f_q16; 0: no plane point) */
    int64_t amp_m;              /* displacement, Q8 pixels = (d * amp_m) >> 32 */
    uint32_t wave_fade_d;       /* depth (30-bit) beyond which the waves fade */
    int64_t tkr[RS_MAX_DIM];    /* per row: 32 zc / tint_len of the reflected plane's point,
                                   Q16 (-1: the row does not meet the plane, or lies outside
                                   wlo .. whi) */
    int32_t bratio[RW_MAX_ID + 1];      /* (eye z - body z) / (eye z - plane_z), Q16 (0: none) */
    int64_t ebody[RW_MAX_ID + 1];       /* eye z - body z, world units (the shore bound) */
    uint32_t water_bias;        /* the water pass's depth seed: terrain depth minus this (buffer
                                   units), the largest shore_dd of the bodies on screen */
    uint32_t shore_dd[RW_MAX_ID + 1];   /* shore_c / ebody: the largest dt - dw (30-bit) worth a shore
                                           test when shore_w is 0 (0xffffffff: any) */
    uint32_t shore_tdd[RW_MAX_ID + 1];  /* shore_dd of a body with a plane point ratio (bratio), 0 for
                                           the others (their shore test finds no water) */
    uint64_t inv_sx, inv_sy;    /* 2^32 / grid step, rounded up */
    int64_t gx0, gy0;           /* the eye's grid position plus half a step, world units:
                                   eye x - grid_ox + grid_sx / 2, grid_oy - eye y + grid_sy / 2 */
    int64_t half_sx, half_sy;   /* grid_sx / 2, grid_sy / 2 */
    uint64_t inv_tu, inv_tv;    /* texels of land_tex per world unit, 2^32 times, rounded
                                   down (0: no texture) */
    int32_t idx32;              /* gxmax, gymax <= 2^32 and inv_sx, inv_sy < 2^32: a grid
                                   position and a reciprocal fit 32 bits (water_shore.h) */
    uint64_t gxmax, gymax;      /* at most wet_w grid_sx, wet_h grid_sy: positions below index
                                   samples of the grid (water_setup.c grid_max) */
    int32_t fog_sh;             /* fog table index: depth >> fog_sh */
    uint32_t dquiet;            /* buffer depth from which terrain gets no fog (> dfar) */
    uint32_t fog_d30;           /* 30-bit depth from which nothing gets fog: fog[d >> fog_sh] is 0
                                   or past the table for every d >= fog_d30 (0: fog off) */
    int32_t pixel_fog;          /* 1: the hook fogs terrain pixels (textured frames); 0: the
                                   terrain's vertices were fogged (rw_fog_vertices) */
    uint64_t inv_fade;          /* 2^32 / (wave_fade_d >> 14 | 1), rounded down */
    uint32_t clear4[4 * RS_MAX_DIM];    /* the sky rows for rs_frame.clear_rows (dithered for RGB565) */
    uint32_t skyrefl[RW_TAB + 1];       /* the reflected sky by cos^2 t: the horizon colour mixed
                                           towards the zenith colour by skyw */
    uint32_t skyrefl_of[2];     /* the horizon and zenith colours skyrefl was made for */
    uint32_t tint_u, tint_rb, tint_g;   /* mix_rgb(c, water_rgb, tint_fixed) = c's fields times
                                           tint_u plus these, >> 8 */
    uint8_t fres[RW_TAB + 1];   /* F by cos^2 t, Q8 (256 = 1) */
    uint8_t skyw[RW_TAB + 1];   /* zenith weight by sin^2 of elevation, Q8 */
    uint8_t tint[256];          /* 1 - exp(-x / 32), Q8, by x = L / tint_len in 1/32 */
    uint8_t fog[RW_TAB + 1];    /* fog weight by depth >> fog_sh, Q8 */
    int8_t wsine[RW_WAVES][256];        /* wave k's slope amplitude times sin(2 pi i / 256); the
                                           amplitudes sum to 254 (wave_set) */
    int32_t tables_ready;       /* 1: fres, skyw, tint and wsine are filled */
} rw_frame;

/* The view-projection of the mirror: the same camera looking at the world mirrored in
 * z = plane_z, for a frame of (w >> res_shift) x (h >> res_shift) pixels (f scaled
 * alike).  BR_E_ARG when 2 plane_z - z would leave CAM_COORD_MAX or res_shift > 2. */
br_status rw_mirror_vp(const cam_vp *vp, int32_t plane_z, int32_t res_shift, int32_t w, int32_t h,
                       cam_vp *out);

/* Fills r's frame-independent tables (Fresnel, sky weights, tint, sine) if not yet
 * done; rw_setup does it at its first call otherwise.  For a zeroed rw_frame, at set-up
 * time, so that no frame pays for them. */
void rw_tables(rw_frame *r);

/* Fills r for one frame: terrain (prepared, with depth: water reads it), water and refl
 * (prepared frames or NULL), camera c (the terrain's).  BR_E_ARG on inconsistent sizes
 * or parameters, or a terrain frame without depth (RS_DEPTH_NONE). */
br_status rw_setup(rw_frame *r, const rw_params *p, const cam *c, const rs_frame *terrain,
                   const rs_frame *water, const rs_frame *refl);

/* Per-vertex fog (as OpenGL's fixed-function fog, evaluated at the vertices and
 * interpolated with the colour): mixes each vertex colour of the prepared terrain frame
 * f (rs_frame_prepare done, not textured) towards the sky colour of the vertex's row by
 * the fog weight of its depth, and sets f->clear_rows to the sky gradient, so the post
 * hook touches only rows with water.  Vertices behind the near plane or outside the
 * guard band keep their colour.  Call after rw_setup with the same terrain frame;
 * a no-op for the colour when fog is off. */
void rw_fog_vertices(rw_frame *r, rs_frame *f);

/* The passes (pass->user = r) and the post hook (post_user = r). */
br_status rw_pass_reflection(rs_pass *pass, const rw_frame *r);
br_status rw_pass_water(rs_pass *pass, const rw_frame *r);
br_status rw_post(const void *user, rs_band *b, rs_band_stats *st);

#endif
