/* mcu/bake.h — what mcu/bake.c writes for a board: a real heightfield, its bitree
 * hierarchy, the lit colour of every sample, and a camera path, all as const arrays
 * (flash), so that a board without a file system or the RAM to build the hierarchy
 * draws the same frames as the desktop.
 *
 * The arrays (build/mcu/bake_data.c, generated):
 *   bake_z[w * h]       heights, the heightfield's units (hf.z: row 0 north), no voids
 *                       removed (HF_NODATA stays)
 *   bake_tree[]         the hierarchy as bt_tree_save writes it (bake_tree_bytes bytes),
 *                       attached in place by bt_attach (core/bitree.h)
 *   bake_lvl[w * h]     the shading cache's light levels (raster/terrain.h rt_scene.lvl)
 *   bake_ztab[nz]       and its ramp colour per height unit (rt_scene.ztab), filled for
 *                       every valid sample, so the renderer only reads them
 * and bake_info below.  Cameras are in the world frame of raster/terrain.h (rt_scene_init
 * of the same heightfield gives the same frame on the board). */
#ifndef BR_MCU_BAKE_H
#define BR_MCU_BAKE_H
#include <stdint.h>

#define BAKE_MAX_FRAMES 16
/* Rows of the stream path's bands (platform/board/board_stream.c; the SPI stream, and so
 * its checksum, has a window a band): 6 bands of 40 rows at 320 x 240, RGB565 without a
 * depth buffer, the walk's leaves back to front */
#define BAKE_STREAM_ROWS 40

typedef struct bake_cam {
    int32_t eye[3], tgt[3];     /* world units */
    int32_t znear, zfar;        /* world units */
} bake_cam;

typedef struct bake_info {
    /* the heightfield (core/hf.h) */
    int32_t w, h, z_num, z_den;
    int64_t dx_um, dy_um;
    int32_t geo_kind;
    int64_t geo_x0, geo_y0, geo_sx, geo_sy;
    /* the hierarchy (core/bitree.h bt_tree) */
    int32_t n, k, metric, zmin, zmax;
    int64_t nvalid;
    uint32_t nslot;             /* the tree's slots (bt_tree.nslot; frame state: bt_state_size) */
    int32_t nz;                 /* entries of bake_ztab (rt_scene.nz) */
    /* shading: the default ramp over [ramp_zmin_mm, ramp_zmax_mm], sun, ambient */
    int64_t ramp_zmin_mm, ramp_zmax_mm;
    int32_t sun_az_mdeg, sun_alt_mdeg, ambient_q14;
    /* the frames: size, field of view, selection, the camera path */
    int32_t fb_w, fb_h, fovy_mdeg;
    int32_t pixel_err_q8, hyst_q8, morph_q8;
    uint32_t clear_rgb;
    int32_t nframes;
    bake_cam cam[BAKE_MAX_FRAMES];
    /* each frame's SPI stream checksum (platform/board/spi_band.h spib_sum) as the
     * product's own frame path draws it on the host (platform/scene.h scene_frame: the
     * view extraction in parts, the frame driver in 16-row RGB565 bands, 16-bit depth):
     * what the board's frames must give */
    uint32_t scene_sum[BAKE_MAX_FRAMES];
    /* the same through the stream path on the host (raster/terrain_stream.h: the view
     * rule without hysteresis, band by band, the library's own drawing code): what the
     * stream board's frames (platform/board/board_stream.c) must give */
    uint32_t stream_sum[BAKE_MAX_FRAMES];
} bake_info;

extern const int32_t bake_z[];
extern const uint32_t bake_tree[];
extern const uint32_t bake_tree_bytes;
extern const uint16_t bake_lvl[];
extern const uint32_t bake_ztab[];
extern const bake_info bake;

#endif
