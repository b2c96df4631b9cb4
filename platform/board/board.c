/* platform/board/board.c — the board's frames (see board.h).  Freestanding: core/,
 * raster/, the baked arrays and memset/memcpy, nothing else. */
#include "platform/board/board.h"
#include <string.h>
#include "core/bitree.h"
#include "mcu/bake.h"
#include "mcu/board_tree.h"
#include "platform/board/board_scene.h"
#include "raster/frame.h"
#include "raster/ramp.h"
#include "raster/terrain.h"

struct board_state {
    hf f;
    rs_ramp ramp;
    rt_scene rt;
    bt_tree tree;
    bt_mesh mesh;
    rs_vertex *verts;
    rs_cvert *cache;
    int16_t *chunks;
    void *band;
    size_t band_bytes;
    uint8_t *row;               /* the SPI row buffer, 2 w bytes */
    uint32_t vcap;
    uint32_t budget;            /* triangles the mesh's budget fallback is sized for (budget_for) */
    int lend;                   /* 1: the raster's parts lie in the mesh's scratch */
    int reuse_v;                /* 1: the band and the row lie in the mesh's vertex array */
    int in_place;               /* 1: the raster vertices lie in the mesh's vertex array */
    size_t borrowed[BP_N];      /* bytes each part takes in the mesh's memory */
};

static struct board_state B;

static const char *const part_name[BP_N] = {
    "LOD state (bt_tree.st)", "mesh (bt_mesh)", "raster vertices", "vertex cache", "chunk table",
    "band colour + depth", "SPI row buffer"
};

const char *board_part_name(int part)
{
    return part >= 0 && part < BP_N ? part_name[part] : "?";
}

/* 1 when a borrowed part lies in the mesh's vertex array, 0 in its scratch */
static int in_mesh_v(int part)
{
    return (part == BP_VERTS && B.in_place) || (part >= BP_BAND && B.reuse_v);
}

size_t board_part_borrowed(int part, const char **from)
{
    if (part < 0 || part >= BP_N || !B.borrowed[part]) return 0;
    if (from) *from = in_mesh_v(part) ? "the mesh's vertices" : "the mesh's scratch";
    return B.borrowed[part];
}

size_t board_state_size(void)
{
    return sizeof B;
}


/* The mesh's vertex capacity (core/bitree.h bt_mesh_init_v) */
static uint32_t mesh_cap_v(void)
{
    const uint32_t most = 3u * BOARD_MAX_TRI + 3u;
    return BOARD_MAX_V == 0 || BOARD_MAX_V > most ? most : BOARD_MAX_V;
}

/* The smallest budget fallback (bt_mesh_init_vb) whose mesh scratch still holds `parts`
 * bytes, 0 (the fallback bt_mesh_init_v sizes) when none does: the heap is the one part
 * of the scratch a fitting view never uses. */
static uint32_t budget_for(size_t parts)
{
    uint32_t lo = 1, hi = BOARD_MAX_TRI;
    if (bt_mesh_scratch_size_vb(BOARD_MAX_TRI, BOARD_MAX_V, hi) < parts) return 0;
    while (lo < hi) {       /* the scratch grows with the budget */
        const uint32_t mid = lo + (hi - lo) / 2;
        if (bt_mesh_scratch_size_vb(BOARD_MAX_TRI, BOARD_MAX_V, mid) >= parts) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}

br_status board_init(void *arena, size_t arena_bytes, size_t size[BP_N])
{
    size_t sz[BP_N], total = 0, parts = 0;
    uint8_t *p = (uint8_t *)arena;
    rs_pipe pipe;
    rs_prim longest;
    int i, first, last;
    memset(&B, 0, sizeof B);
    if (board_scene(&B.f, &B.ramp, &B.rt) != BR_OK) return BR_E_ARG;
    B.vcap = BOARD_MAX_V;
    memset(&pipe, 0, sizeof pipe);
    pipe.w = bake.fb_w; pipe.h = bake.fb_h; pipe.fmt = RS_FMT_RGB565; pipe.depth = RS_DEPTH16;
    longest.kind = RS_STRIP; longest.n = 5u * BOARD_MAX_TRI + 8u; longest.idx = NULL;
    sz[BP_STATE] = board_up8(board_tree_ram_size(&bake));
    sz[BP_VERTS] = board_up8(sizeof(rs_vertex) * B.vcap);
    sz[BP_CACHE] = board_up8(rs_cache_mem_size(B.vcap));
    sz[BP_CHUNKS] = board_up8(rs_chunk_mem_size(&longest, 1));
    sz[BP_BAND] = board_up8(rs_pipe_mem_size(&pipe, BOARD_BAND_ROWS));
    sz[BP_ROW] = board_up8((size_t)bake.fb_w * 2);
    /* The raster's per-frame parts are written after the selection and read before the
     * next one, so they may take mesh memory that only an extraction reads (core/bitree.h):
     * - the raster vertices the mesh's vertex array itself when the two layouts have one
     *   size (RS_TEX_FIELDS 0): rt_from_mesh reads vertex i before it writes raster
     *   vertex i, and the next extraction writes the array anew without reading it;
     * - the parts from `first` to `last` the mesh's scratch (bt_mesh_lend_scratch), whose
     *   budget heap is sized to hold them (budget_for);
     * - else the band and the SPI row the vertex array, once rt_from_mesh has read it. */
    B.in_place = sizeof(rs_vertex) == sizeof(bt_vert) && mesh_cap_v() >= B.vcap;
    first = B.in_place ? BP_CACHE : BP_VERTS;
    last = B.in_place ? BP_ROW : BP_CHUNKS;
    for (i = first; i <= last; i++) parts += sz[i];
    B.budget = budget_for(parts);
    sz[BP_MESH] = board_up8(bt_mesh_mem_size_vb(BOARD_MAX_TRI, BOARD_MAX_V, B.budget));
    if (B.in_place) {
        B.borrowed[BP_VERTS] = sz[BP_VERTS];
        sz[BP_VERTS] = 0;
    }
    if (parts <= bt_mesh_scratch_size_vb(BOARD_MAX_TRI, BOARD_MAX_V, B.budget)) {
        B.lend = 1;
        for (i = first; i <= last; i++) {
            B.borrowed[i] = sz[i];
            sz[i] = 0;
        }
    }
    if (!B.in_place && sz[BP_BAND] + sz[BP_ROW] <= (size_t)mesh_cap_v() * sizeof(bt_vert)) {
        B.reuse_v = 1;
        for (i = BP_BAND; i <= BP_ROW; i++) {
            B.borrowed[i] = sz[i];
            sz[i] = 0;
        }
    }
    for (i = 0; i < BP_N; i++) {
        if (size) size[i] = sz[i];
        total += sz[i];
    }
    if (!arena || ((uintptr_t)arena & 7) != 0 || total > arena_bytes) return BR_E_NOMEM;
    if (board_tree_attach(&B.tree, &B.f, &bake, bake_tree, bake_tree_bytes, p, sz[BP_STATE]) != BR_OK) return BR_E_ARG;
    p += sz[BP_STATE];
    if (bt_mesh_init_vb(&B.mesh, BOARD_MAX_TRI, BOARD_MAX_V, B.budget, p, sz[BP_MESH]) != BR_OK) return BR_E_ARG;
    p += sz[BP_MESH];
    {   /* each part at its place: the arena (p), the scratch (q) or the vertex array (v) */
        uint8_t *q = B.lend ? (uint8_t *)bt_mesh_lend_scratch(&B.mesh, NULL) : NULL, *v = (uint8_t *)B.mesh.v;
        uint8_t *at[BP_N];
        for (i = BP_VERTS; i < BP_N; i++) {
            uint8_t **from = !B.borrowed[i] ? &p : in_mesh_v(i) ? &v : &q;
            at[i] = *from;
            *from += B.borrowed[i] ? B.borrowed[i] : sz[i];
        }
        B.verts = (rs_vertex *)(void *)at[BP_VERTS];
        B.cache = (rs_cvert *)(void *)at[BP_CACHE];
        B.chunks = (int16_t *)(void *)at[BP_CHUNKS];
        B.band = at[BP_BAND]; B.band_bytes = B.borrowed[BP_BAND] ? B.borrowed[BP_BAND] : sz[BP_BAND];
        B.row = at[BP_ROW];
    }
    return BR_OK;
}

br_status board_frame(int32_t i, rs_sink tap, void *tap_user, board_frame_info *out)
{
    const bake_cam *bc;
    cam c;
    bt_params bp;
    rs_prim prim;
    rs_frame fr;
    rs_pipe pipe;
    rs_pass terrain;
    rs_band_stats total;
    board_sum s;
    br_status st;
    if (i < 0 || i >= bake.nframes || !B.row) return BR_E_ARG;
    bc = &bake.cam[i];
    st = cam_look_at(&c, bc->eye, bc->tgt, bake.fovy_mdeg, bake.fb_w, bake.fb_h, bc->znear, bc->zfar);
    if (st != BR_OK) return st;
    memset(&bp, 0, sizeof bp);
    bp.mode = BT_VIEW;
    bp.c = &c;
    bp.fr = B.rt.fr;
    bp.pixel_err_q8 = bake.pixel_err_q8;
    bp.hyst_q8 = bake.hyst_q8;
    bp.morph_q8 = bake.morph_q8;
    if ((st = bt_extract(&B.tree, &bp, &B.mesh)) != BR_OK) return st;
    if (B.mesh.nv > B.vcap) return BR_E_NOMEM;
    if (B.lend) (void)bt_mesh_lend_scratch(&B.mesh, NULL);   /* the same block as at init */
    rt_from_mesh(&B.rt, &B.mesh, B.verts);
    prim.kind = RS_STRIP; prim.n = B.mesh.ns; prim.idx = B.mesh.strip;
    memset(&fr, 0, sizeof fr);
    fr.w = bake.fb_w; fr.h = bake.fb_h; fr.fmt = RS_FMT_RGB565; fr.depth = RS_DEPTH16;
    fr.clear_rgb = bake.clear_rgb;
    fr.v = B.verts; fr.nv = B.mesh.nv; fr.cache = B.cache;
    fr.prims = &prim; fr.nprims = 1; fr.chunks = B.chunks;
    cam_viewproj(&c, &fr.vp);
    if ((st = rs_frame_prepare(&fr)) != BR_OK) return st;
    memset(&pipe, 0, sizeof pipe);
    pipe.w = fr.w; pipe.h = fr.h; pipe.fmt = fr.fmt; pipe.depth = fr.depth;
    if ((st = rs_pass_terrain(&terrain, &fr)) != BR_OK || (st = rs_pipe_add(&pipe, &terrain)) != BR_OK) return st;
    board_sum_start(&s, B.row, tap, tap_user);
    st = rs_pipe_run(&pipe, BOARD_BAND_ROWS, B.band, B.band_bytes, board_sum_band, &s, &total);
    if (st != BR_OK) return st;
    out->sum = s.sum;
    out->expect = bake.scene_sum[i];
    out->ntri = B.mesh.ntri; out->nv = B.mesh.nv; out->ns = B.mesh.ns;
    out->overflow = B.mesh.overflow;
    out->pixels = total.pixels;
    return BR_OK;
}

uint32_t board_last_triangles(void)
{
    return B.mesh.ntri;
}

void board_last_frame(const rs_cvert **cache, uint32_t *nv, const br_index **strip, uint32_t *ns)
{
    *cache = B.cache;
    *nv = B.mesh.nv;
    *strip = B.mesh.strip;
    *ns = B.mesh.ns;
}
