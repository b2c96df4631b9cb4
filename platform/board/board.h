/* platform/board/board.h — the board main's frames, shared by the bare-metal build
 * (platform/board/mcu_main.c, Cortex-M) and its desktop build (desktop_main.c): the
 * baked terrain (mcu/bake.h) flown along its camera path, each frame selected by the
 * bitree, drawn by the one frame driver (raster/frame.h) in bands of RGB565 with 16-bit
 * depth, and each band streamed as platform/sink_spi.h's byte stream into a checksum.
 * Two files implement it, one linked (mk/mcu.sh MCU_PATH): board_stream.c draws each band
 * of BAKE_STREAM_ROWS rows straight from the tree, board.c the whole frame's mesh and
 * strip in bands of BOARD_BAND_ROWS rows (docs/mcu.md).
 *
 * RAM: everything the frames write lies in the arena the caller hands to board_init
 * (carved in the parts of enum board_part; board_init's size[] says how much each takes;
 * a part a path does not have has the name "" and no bytes; the mesh path's raster parts
 * live in the mesh's memory when it holds them, board_part_borrowed) plus the board's own
 * state (struct board_state, sizeof in board_state_size) and the stack.  Build-time sizes
 * of the mesh path: BOARD_MAX_TRI triangles a mesh (beyond: the bitree's budget rule, a
 * coarser conforming mesh), BOARD_MAX_V raster vertices (a frame whose mesh has more
 * fails with BR_E_NOMEM, never writes past them).
 *
 * Checksum: spib_sum (platform/board/spi_band.h) over each frame's stream. */
#ifndef BR_BOARD_H
#define BR_BOARD_H
#include <stddef.h>
#include <stdint.h>
#include "core/status.h"
#include "raster/raster.h"

#ifndef BOARD_MAX_TRI
#define BOARD_MAX_TRI 4096
#endif
#ifndef BOARD_MAX_V
#define BOARD_MAX_V (3 * BOARD_MAX_TRI + 3)
#endif
#ifndef BOARD_BAND_ROWS
#define BOARD_BAND_ROWS 16
#endif

enum board_part { BP_STATE, BP_MESH, BP_VERTS, BP_CACHE, BP_CHUNKS, BP_BAND, BP_ROW, BP_N };

typedef struct board_frame_info {
    uint32_t sum;               /* the checksum of the frame's stream */
    uint32_t expect;            /* the same frame's checksum through the product's frame
                                   path on the host (mcu/bake.h scene_sum) */
    uint32_t ntri, nv, ns;      /* the mesh: triangles, vertices, strip indices; the stream
                                   path (ns 0): triangles set up in its bands (one reaching
                                   two bands counts twice), nv 0 */
    int32_t overflow;           /* the selection fell back to the budget rule */
    uint32_t pixels;            /* pixels written (depth test passed) */
} board_frame_info;

/* Name of a part ("LOD state", "mesh", ...). */
const char *board_part_name(int part);
/* Bytes a part borrows from the mesh's memory instead of the arena (board_init decides;
 * its size[] is then 0), else 0; *from (may be NULL) names where.  The raster vertices,
 * the vertex cache and the chunk table live in the mesh's scratch (core/bitree.h
 * bt_mesh_lend_scratch), the band and the SPI row in the mesh's vertex array once
 * rt_from_mesh has read it, when they fit. */
size_t board_part_borrowed(int part, const char **from);
/* Bytes of the board's own state (static, outside the arena). */
size_t board_state_size(void);
/* Carves the arena (8-byte aligned) and sets up the scene, the tree over the baked
 * hierarchy and the mesh; size[BP_N] (may be NULL) gets each part's bytes.  BR_E_NOMEM
 * when the arena is too small (size[] then says what was needed), BR_E_ARG when the
 * bake is inconsistent. */
br_status board_init(void *arena, size_t arena_bytes, size_t size[BP_N]);
/* Frames in the baked path. */
int32_t board_frames(void);
/* Draws frame i; each finished band also goes to tap (NULL: none) after the stream. */
br_status board_frame(int32_t i, rs_sink tap, void *tap_user, board_frame_info *out);
/* The triangles of the last frame's mesh (the stream path walks the whole view again to
 * count them: the desktop's figure, not the board's work). */
uint32_t board_last_triangles(void);
/* The last frame's transformed vertices (*nv of them) and strip (*ns indices), valid until
 * the next board_frame: what its bands drew, for the desktop build's --band-load. */
void board_last_frame(const rs_cvert **cache, uint32_t *nv, const br_index **strip, uint32_t *ns);

#endif
