/* core/bitree.h — the fixed-point bitree (right-triangle binary tree, RTIN)
 * triangulator: heightfield in, crack-free adaptive mesh + one generalised
 * triangle strip out.  Integer only; all memory is the caller's.
 *
 * Sources.  The hierarchy is the right-triangulated irregular network (RTIN) of
 * Evans, Franklin & Kirkpatrick, "Right-triangulated irregular networks",
 * Algorithmica 30 (2001), the same right-triangle bintree as Lindstrom et al.,
 * "Real-time, continuous level of detail rendering of height fields", SIGGRAPH
 * 1996 (vertex dependencies, screen-space error), and ROAM (Duchaineau et al.,
 * "ROAMing terrain: real-time optimally adapting meshes", IEEE Visualization
 * 1997: diamonds, nested bounding volumes, a priority queue of splits);
 * errors are saturated up the tree (monotone) as in Pajarola, "Large scale
 * terrain visualization using the restricted quadtree triangulation", IEEE
 * Visualization 1998.  Papers in ../shared/papers (Spanish), cited by number:
 * 002 the bitree paper (section 2 "Triangulación jerárquica sin restricciones":
 * hierarchy, 2.2 crack prevention; 3.3 "Actualización del modelo": geomorph;
 * 4 "Implementación: estructura triangle strip": strips, figures 10-12);
 * 004 "Remallado de terrenos multirresolución" (section 2: S/F vertex states,
 * line triangles, merged tiles); 001 "Técnicas de simplificación de modelos
 * topográficos" (2.2: the curvature indicator); 000 "Visualización en tres
 * dimensiones de capas de información geográfica a partir de modelos digitales
 * de elevación" (screen-space error, nodata, reflections of water layers);
 * 003 "Arquitectura de software para control de nivel de detalle aplicado a
 * superficies basadas en mallas de polígonos" (1.5 LOD, budget, hysteresis;
 * 3.1.4 "Métrica").
 *
 * ===========================================================================
 * OUTPUT MESH CONTRACT (what the rasteriser and the exporters consume)
 * ===========================================================================
 * bt_mesh.v[0 .. nv): unique vertices, array of struct bt_vert:
 *   x, y    grid column (east) and row (south; row 0 = north), the sample
 *           indices of the input heightfield (0 <= x < w, 0 <= y < h);
 *   z       height in heightfield units (hf.z_num/hf.z_den metres) AFTER
 *           geomorphing: z = zf + ((zs - zf) * morph + 2^14) >> 15, where zs is
 *           the sample's real height and zf the interpolated ("fictitious")
 *           height (average of the two ends of the hypotenuse the vertex
 *           splits, themselves geomorphed; rounded down);
 *   morph   geomorph weight, Q15: 32768 = real height, 0 = fictitious height;
 *   state   BT_S (selected: real height, morph 32768) or BT_F (fictitious:
 *           morph < 32768, the height is (partly) interpolated; 002 2.2, 004 3).
 *   Vertices are never on a void sample.  No two vertices share (x, y).
 * bt_mesh.strip[0 .. ns): ONE generalised triangle strip of uint32 indices into
 *   v, GL convention: triangle k = (s[k], s[k+1], s[k+2]) for even k and
 *   (s[k+1], s[k], s[k+2]) for odd k.  Every non-degenerate triangle is
 *   COUNTER-CLOCKWISE SEEN FROM +z with x east and y north (in grid (x, y) with
 *   y = row that is cross((p1-p0),(p2-p0)) < 0: meshcheck orientation -1, the
 *   OBJ/GL convention).  Degenerate ("line") triangles (a repeated index, or
 *   three collinear vertices) draw nothing; nline counts them, ntri the real ones,
 *   and their heights are on their line too, or below the surface where it covers
 *   both sides (core/bt_emit.c rim_line), so no vertical sliver shows;
 *   ns - 2 = ntri + nline when ns >= 3.
 * The real triangles form a conforming mesh: watertight (each interior edge in
 * exactly two triangles), no T-junctions, no vertex on a void; a void sample lies
 * inside or on a triangle, and a valid sample beside a void is left out, only
 * within the triangle's extent, which the error bound covers (bt_err.c "Voids";
 * exact holes below a unit triangle's extent).
 *
 * ===========================================================================
 * TREE AND ERRORS
 * ===========================================================================
 * The hierarchy is that of the heightfield padded VIRTUALLY to n x n, n = 2^k + 1
 * >= max(w, h), the samples outside w x h being voids.  Two root triangles split
 * the square along (0,0)-(n-1,n-1); a triangle splits at the midpoint of its
 * hypotenuse (002 2.1).  Every sample except the 4 corners is the midpoint of
 * exactly one DIAMOND (the one or two triangles sharing that hypotenuse), so
 * per-diamond data is per sample:
 *   node  uint32: error code (low 16 bits), BT_METRIC_EXACT: a TRUE upper bound, in
 *         heightfield units, of |plane - z| over every grid sample of each
 *         triangle of the diamond AND of every descendant diamond (max, so the
 *         hierarchy is monotone); BT_METRIC_CURVATURE: the accumulated 001
 *         curvature indicator (sum over the triangle's samples, see bt_err.c),
 *         made monotone the same way.  Code BT_CODE_SPLIT: a triangle of the
 *         diamond covers padding voids and valid samples, or voids with the
 *         curvature metric (always split; 000's nodata).  Over the grid's own
 *         voids the exact code also bounds the triangle's extent (bt_err.c).
 *         Codes decode with bt_code_value (exact below 4096, then 12-bit
 *         mantissa, rounded UP so the bound stays a bound).
 *         and (high 16 bits) the uint8 quantised height range zlo, zhi of the
 *         diamond's nested bounding volume (its triangles' vertex range +- error,
 *         union with its children): one load per diamond.  zlo > zhi: VOID, no
 *         valid sample below it (BT_NODE_VOID: code 0, culled, never split).
 *   st    the frame state (hysteresis, budget marks): two bit planes of
 *         (nslot + 7) / 8 bytes, bt_state_size; bits, not bytes, so that a board's
 *         RAM holds it (docs/mcu.md).
 *
 * LAYOUT (core/bt_util.c bti_slot_pad; docs/bitree.md "Layout").  The padding is
 * not stored: a diamond (x, y) has a SLOT, its index in node[] and st[]:
 *   interior  x < w, y < h: slot y*w + x (one compare pair and a multiply-add in
 *             the walk, the only case for almost every diamond it visits);
 *   bands     a diamond in the padding whose descendants reach the data.  Its value
 *             depends on the diamonds within its reach (children, recursively: 3h - 1
 *             samples for a type D diamond of scale h, 2h - 1 for type A), and it is
 *             VOID unless that reach holds a unit triangle of three valid samples,
 *             i.e. unless x - w <= 3h - 3 (or y - h <= 3h - 3).  So an east column x
 *             >= w is stored, at the rows that are multiples of p, for p the least
 *             power of two with 3p - 3 >= x - w, and only when x is a multiple of p:
 *             one column for p = 1, at most two for each larger p; likewise rows
 *             below the data (x < w).  Slots w*h onwards, level by level (bt_layout).
 *   void      every other padding diamond: VOID by the reach argument; all share
 *             the last slot, which holds BT_NODE_VOID and whose st is never written.
 * So a tree holds nslot = w*h + O((n + w) * 3) slots: 4.25 bytes per slot (4 node
 * + 2 bits of st), 4.25-4.78 bytes per sample of the grid as read on the DEMs in the project
 * (tests/test_bitree_layout.c prints them), against 5 per PADDED sample before
 * (14.6 on a 1201^2 SRTM tile).  The values are bit for bit the padded
 * hierarchy's (bt_node_at reads any (x, y); tests/test_bitree_big.c hashes the
 * padded grid through it).  Tiles of this layout are what a store of terrain larger
 * than memory would page: a tile of 2^j + 1 samples has no bands at all.
 * Why slots and not a forest of (2^j + 1) tiles (BDAM, paper 000): the single tree
 * keeps every mesh byte-identical; docs/bitree.md "Layout".
 * Memory: bt_mem_size; build scratch (only during bt_build) about 6 bytes per
 * heightfield sample + 9 per slot, plus 12 per row of the padded side.
 * Monotone + shared per diamond => splitting every diamond whose value exceeds a
 * threshold gives a conforming mesh (no T-junctions, no cracks).
 *
 * Not checked in the hot paths (debug asserts only): that the tree was built
 * from the heightfield it is used with, and that the hf was not changed.
 */
#ifndef BR_BITREE_H
#define BR_BITREE_H
#include <stddef.h>
#include <stdint.h>
#include "core/hf.h"
#include "core/cam.h"
#include "core/status.h"

enum { BT_METRIC_EXACT = 0, BT_METRIC_CURVATURE = 1 };
enum { BT_S = 0, BT_F = 1 };
#define BT_CODE_SPLIT 0xFFFFu
#define BT_MORPH_ONE 32768
/* Geomorph weights are multiples of BT_MORPH_STEP: a split vertex rises to its real
 * height in BT_MORPH_ONE / BT_MORPH_STEP = 16 steps (docs/bitree.md, "geomorph") */
#define BT_MORPH_STEP 2048

/* The bands of the layout (see LAYOUT above): for each level l (p = 2^l) the east
 * columns x = (em0[l] + i) << l, i < enc[l], each of (S >> l) + 1 slots (rows y =
 * r << l), from slot east[l]; the south rows y = (sm0[l] + i) << l, i < snc[l], each
 * of ((w - 1) >> l) + 1 slots (x = c << l < w), from slot south[l]. */
#define BT_LAY_LEVELS 32
#define BT_LAY_NEAR 190    /* columns / rows next to the data with a direct entry (levels 0..6) */
typedef struct bt_layout {
    uint32_t east[BT_LAY_LEVELS], south[BT_LAY_LEVELS];
    int32_t em0[BT_LAY_LEVELS], enc[BT_LAY_LEVELS], sm0[BT_LAY_LEVELS], snc[BT_LAY_LEVELS];
    /* column w + d (row h + d), d < BT_LAY_NEAR: the slot of its row 0 (column 0), or -1
     * when it has none */
    int32_t enear[BT_LAY_NEAR], snear[BT_LAY_NEAR];
    uint8_t lnear[BT_LAY_NEAR];   /* the level of column w + d, row h + d */
} bt_layout;

typedef struct bt_tree {
    const hf *f;           /* the heightfield (caller keeps it alive and unchanged) */
    int32_t n, k;          /* padded side n = 2^k + 1 */
    int32_t metric;        /* BT_METRIC_* */
    int32_t zmin, zmax;    /* over valid samples (0, 0 if none) */
    int64_t nvalid;        /* valid samples */
    int32_t w, h;          /* the grid as read (f->w, f->h) */
    uint32_t nslot;        /* slots: w*h interior, the bands, the void slot (last) */
    const uint32_t *node;  /* per slot: error code (bits 0-15), quantised height range of
                              the diamond's volume: low (16-23), high (24-31); never
                              written after bt_build (may be read-only memory) */
    uint8_t *st;           /* per slot frame state bits */
    uint64_t sum;          /* a hash of node[] (bt_build, bt_attach): a mesh's decision memo
                              belongs to the tree with these nodes (frame coherence) */
    bt_layout lay;
} bt_tree;

#define BT_NODE_ERR(v) ((uint16_t)((v) & 0xFFFFu))
#define BT_NODE_ZLO(v) ((uint8_t)(((v) >> 16) & 0xFFu))
#define BT_NODE_ZHI(v) ((uint8_t)((v) >> 24))
#define BT_NODE(e, lo, hi) ((uint32_t)(e) | ((uint32_t)(lo) << 16) | ((uint32_t)(hi) << 24))
#define BT_NODE_VOID BT_NODE(0, 255, 0)

/* Slots of the layout for a w x h grid (see LAYOUT); 0 if w, h are invalid. */
uint32_t bt_slot_count(int32_t w, int32_t h);
/* The node of diamond (x, y) of the padded grid (0 <= x, y < n, not a corner):
 * the stored value, or BT_NODE_VOID for a padding diamond with no slot. */
uint32_t bt_node_at(const bt_tree *t, int32_t x, int32_t y);

/* Bytes of mem for bt_build (4 per slot and bt_state_size); 0 if w, h are invalid. */
size_t bt_mem_size(int32_t w, int32_t h);
/* Bytes of frame state (bt_tree.st) for a tree of nslot slots: 2 bits a slot. */
size_t bt_state_size(uint32_t nslot);
/* Bytes of build scratch (freed by the caller after bt_build). */
size_t bt_scratch_size(int32_t w, int32_t h);
/* Builds the error hierarchy of f with metric (BT_METRIC_*).  BR_E_ARG on a bad
 * hf (also a height outside +-BR_Z_LIMIT: the arithmetic bounds rest on it), bad
 * metric, too small buffers or mem not 4-byte aligned (t is then unchanged). */
br_status bt_build(bt_tree *t, const hf *f, int32_t metric,
                   void *mem, size_t mem_bytes, void *scratch, size_t scratch_bytes);

/* ---------------------------------------------------------------- saved trees (bt_blob.c)
 * Build once, save, attach later without building: the blob is a versioned
 * header of little-endian words (format in core/bt_blob.c; docs/bitree.md) and
 * the node array, used in place, so it may be a file read into memory or a const
 * array in flash.  bt_attach refuses (BR_E_ARG, before reading past `bytes`) a
 * blob that is truncated, corrupt (checksums of header and nodes), of another
 * version, or not built from f (dimensions, a fingerprint of f's heights and
 * units).  The node array is read in the host's byte order: a saved blob (its
 * bytes are the same on every host) attaches as it is on a little-endian host; on a
 * big-endian host call bt_blob_to_host on it first (it turns the node words around
 * in place; nothing on a little-endian host).  The blob must be 4-byte aligned
 * and outlive t; attach reads f once (fingerprint), nothing is written to the blob.
 * st: the caller's memory for the frame state, st_bytes >= bt_state_size(nslot)
 * (nslot: bt_slot_count), zeroed by attach; or NULL: no frame state, so view mode
 * without hysteresis (hyst_q8 must be 0) and no budget rule: BT_BUDGET gives
 * BR_E_ARG, and a selection larger than the mesh gives BR_E_NOMEM (mesh empty)
 * instead of the budget fallback.  Attaching gives the tree bt_build gave: the
 * same meshes, byte for byte. */
#define BT_BLOB_VERSION 1u
size_t bt_tree_blob_size(const bt_tree *t);
br_status bt_tree_save(const bt_tree *t, void *buf, size_t bytes);
br_status bt_attach(bt_tree *t, const hf *f, const void *blob, size_t bytes, uint8_t *st, size_t st_bytes);
void bt_blob_to_host(void *blob, size_t bytes);

/* Value (heightfield units for the exact metric) of an error code; BT_CODE_SPLIT
 * gives INT64_MAX. */
int64_t bt_code_value(uint16_t code);
/* Smallest code whose value is >= v (v >= 0): the encoding rounds up. */
uint16_t bt_code_encode(int64_t v);
/* Threshold in millimetres to heightfield units (floor): an exact-metric error
 * <= this many units is <= max_err_mm millimetres. */
int64_t bt_mm_to_units(const hf *f, int64_t mm);

/* ---------------------------------------------------------------- output */
typedef struct bt_vert {
    int32_t x, y;          /* grid column (east), row (south) */
    int32_t z;             /* height after geomorph, heightfield units */
    uint16_t morph;        /* Q15 geomorph weight (BT_MORPH_ONE = real height) */
    uint8_t state;         /* BT_S or BT_F */
    uint8_t pad_;
} bt_vert;

/* Grid to world (core/cam.h units): wx = ox + x*sx, wy = oy - y*sy (north up),
 * wz = oz + (z*sz_q16 >> 16).  sx, sy in world units per grid step (> 0).
 * The PADDED grid (n x n, heights zmin..zmax) must map inside +-CAM_COORD_MAX on
 * every axis (the camera's precondition; bt_frame_auto's frames do): bt_count,
 * bt_extract and bt_screen_error_q8 refuse a larger frame (BR_E_ARG / 0). */
typedef struct bt_frame {
    int32_t ox, oy, oz;
    int32_t sx, sy;
    int32_t sz_q16;
} bt_frame;

/* Frame coherence state of a decision memo (internal; core/bt_mesh.c bti_coh_frame):
 * what the memo's decisions were made for besides the eye (the tree, frame, projection
 * scale and thresholds), the last eye, the eye's accumulated L1 travel and the
 * reciprocals of the thresholds that bound how far a decision stays valid. */
typedef struct bt_coh_key {
    const uint32_t *node;
    uint64_t sum;
    int32_t n, w, h, zmin, zmax, no_cull;
    bt_frame fr;
    int64_t fq8, tau, tau_lo, span;
} bt_coh_key;
/* bt_coh's plane accumulators: one per frustum plane, one for two or more planes */
#define BT_COH_NX (CAM_NPLANES + 1)
/* bt_coh's accumulators, by index: the eye's, plane j's alone, two or more planes' */
#define BT_COH_EYE 0
#define BT_COH_PLANE(j) (1 + (j))
#define BT_COH_MANY BT_COH_PLANE(CAM_NPLANES)
#define BT_COH_NCTR (1 + BT_COH_NX)
typedef struct bt_coh {
    bt_coh_key key;
    int32_t eye[3], valid;
    int32_t fresh;         /* this frame started afresh (a key change, a restart): no
                              earlier frame's answer holds */
    cam_plane pl[CAM_NPLANES];  /* the last frame's frustum */
    uint64_t ctr[BT_COH_NCTR];  /* accumulated travels, 1 .. 2^51, each past every expiry
                              at a key change: [BT_COH_EYE] the eye's L1 travel;
                              [BT_COH_PLANE(j)] that of entries with plane j alone to test,
                              [BT_COH_MANY] with two or more (core/bt_coh.c) */
    uint64_t r[4];         /* floor(2^sh / c) for c = tau_lo, tau, tau + span and tau + the
                              least q whose weight is not 0 (core/bt_coh.c); 0: none */
    int32_t sh[4];
    int64_t slack;         /* test hook: added to every margin (too generous: other meshes);
                              0 outside tests */
} bt_coh;

typedef struct bt_mesh {
    bt_vert *v;            /* vertices, capacity cap_v: output only (an extraction reads
                              none it did not write, so a caller may reuse the bytes once
                              it has read them; the board draws its bands there) */
    uint32_t nv, cap_v;
    br_index *strip;       /* strip indices into v, capacity cap_s (core/config.h br_index) */
    uint32_t ns, cap_s;
    uint32_t ntri;         /* real (non-degenerate) triangles */
    uint32_t nline;        /* line (degenerate) triangles in the strip */
    uint32_t nfict;        /* vertices with state BT_F */
    uint32_t max_tri;      /* capacity in triangles */
    uint32_t *hash;        /* vertex dedup table (internal), hmask + 1 entries */
    uint32_t hmask;
    uint32_t *splits;      /* diamonds split this frame (internal: hysteresis) */
    uint32_t nsplits;
    uint64_t *memo;        /* decisions (internal), memo_mask + 1 entries of BTI_MEMO_W words */
    uint32_t memo_mask, memo_gen;
    int32_t overflow;      /* 1 if the last extraction had to fall back to the budget */
    uint32_t heap_cap;     /* entries of the split list, and of the budget heap unless
                              heap_n says otherwise (internal; 0 reads as 4 max_tri + 8) */
    uint32_t heap_n;       /* entries of the budget heap (internal; 0 reads as heap_cap) */
    bt_coh coh;            /* frame coherence of memo (internal) */
    int32_t lent;          /* 1: the scratch was lent out since the last extraction
                              (bt_mesh_lend_scratch; internal) */
    struct bti_ztest *zlog; /* a part's strip tests that read heights (internal,
                              core/bt_em.h; NULL: none kept) */
    uint32_t nz, cap_z;
} bt_mesh;

/* Bytes for a mesh that holds up to max_tri triangles (>= 2). */
size_t bt_mesh_mem_size(uint32_t max_tri);
br_status bt_mesh_init(bt_mesh *m, uint32_t max_tri, void *mem, size_t mem_bytes);
/* The same with at most max_v vertices (>= 16; 0: 3 max_tri + 3, what no mesh of max_tri
 * triangles exceeds; larger values are taken as that), for callers that know their
 * meshes (terrain frames use about one vertex for two triangles) and have little RAM:
 * the vertex array, the vertex hash, the strip (4 indices a vertex), the decision memo
 * (a cache: fewer slots, same meshes) and the budget rule's heap shrink with it.  A
 * selection that needs more vertices falls back to the budget rule as one that needs
 * more triangles does (m->overflow = 1), and that fallback then buys at most about
 * min(max_tri, max_v / 2) triangles (its heap holds 4 entries a triangle); when even
 * that does not fit, bt_extract returns BR_E_NOMEM and the mesh is incomplete.  0 on a
 * bad size. */
size_t bt_mesh_mem_size_v(uint32_t max_tri, uint32_t max_v);
br_status bt_mesh_init_v(bt_mesh *m, uint32_t max_tri, uint32_t max_v, void *mem, size_t mem_bytes);
/* The same with the budget fallback's heap sized for max_budget triangles (0: as
 * bt_mesh_init_v; else 4 entries of 16 bytes a triangle, no more than bt_mesh_init_v's
 * and no fewer than a quarter of them, whose bytes hold the previous frame's split list
 * while a frame is selected): a board whose selections fit never runs the fallback, and
 * when one does not fit it gets a coarser mesh (the budget rule stops when its heap is
 * full; the mesh stays conforming).  The views that fit give the same meshes. */
size_t bt_mesh_mem_size_vb(uint32_t max_tri, uint32_t max_v, uint32_t max_budget);
br_status bt_mesh_init_vb(bt_mesh *m, uint32_t max_tri, uint32_t max_v, uint32_t max_budget, void *mem,
                          size_t mem_bytes);
/* The mesh's scratch: the bytes of its memory that only an extraction reads (the budget
 * heap, the vertex hash, the decision memo; core/bt_mesh_mem.c), one 8-byte aligned
 * block, free from the end of one extraction to the start of the next.  A caller short
 * of RAM may lend it out after bt_extract (the board puts its raster vertices there);
 * the next extraction clears what it needs first and starts without the memo's earlier
 * decisions (a cache: the same mesh, one frame without frame coherence).  The vertices,
 * the strip and the split list that hysteresis reads stay outside it.  *bytes gets its
 * size, which bt_mesh_scratch_size_v gives before init for the same max_tri, max_v. */
void *bt_mesh_lend_scratch(bt_mesh *m, size_t *bytes);
size_t bt_mesh_scratch_size_v(uint32_t max_tri, uint32_t max_v);
size_t bt_mesh_scratch_size_vb(uint32_t max_tri, uint32_t max_v, uint32_t max_budget);

/* ---------------------------------------------------------------- selection */
enum { BT_FIDELITY = 0, BT_VIEW = 1, BT_BUDGET = 2 };

/* World position (core/cam.h units) of an output vertex: what the rasteriser
 * transforms.  Exact integers; the frame comes from the caller (bt_frame_auto). */
static inline void bt_world(const bt_frame *fr, const bt_vert *v, int32_t out[3])
{
    out[0] = (int32_t)(fr->ox + (int64_t)v->x * fr->sx);
    out[1] = (int32_t)(fr->oy - (int64_t)v->y * fr->sy);
    out[2] = (int32_t)(fr->oz + (((int64_t)v->z * fr->sz_q16) >> 16));
}

typedef struct bt_params {
    int32_t mode;          /* BT_FIDELITY, BT_VIEW or BT_BUDGET */
    int64_t max_err;       /* BT_FIDELITY: threshold in heightfield units (bt_mm_to_units) */
    const cam *c;          /* BT_VIEW, BT_BUDGET: the camera */
    bt_frame fr;           /* BT_VIEW, BT_BUDGET: grid -> world */
    int32_t pixel_err_q8;  /* BT_VIEW: screen-space threshold, 1/256 pixel (0 = 1 px) */
    int32_t hyst_q8;       /* BT_VIEW: hysteresis, 1/256 of the threshold: a diamond split in
                              the previous frame stays split while its error exceeds
                              threshold * (1 - hyst/256) (003); 0 = none */
    int32_t morph_q8;      /* BT_VIEW/BUDGET: geomorph range, 1/256 of the threshold: a
                              vertex rises from fictitious (at threshold) to real height
                              (at threshold * (1 + morph/256)); 0 = no geomorph;
                              0..65536, else BR_E_ARG */
    uint32_t budget;       /* BT_BUDGET: at most this many triangles */
    int32_t no_cull;       /* 1: no frustum culling */
    const int32_t *window; /* BT_VIEW, BT_BUDGET: cull to this rectangle of c's screen (x0, y0,
                              x1, y1 pixels, 0 <= x0 < x1 <= w, 0 <= y0 < y1 <= h; core/cam.h
                              cam_frustum_window) instead of the whole viewport, else
                              BR_E_ARG; NULL: the viewport.  The screen errors are the same;
                              only what lies outside goes (a view that reads part of the
                              screen, such as the reflection) */
    int32_t no_coherence;  /* BT_VIEW: 1: evaluate every diamond this frame instead of reusing
                              decisions of earlier frames that the eye's travel since cannot
                              have changed (core/config.h BR_COHERENCE; the same mesh) */
    int32_t strip_order;   /* where voids or culling break the recursive walk, the strip can
                              be written again in a greedy leaf order (fewer references, the
                              same triangles; about 4-5x the extraction's time where it runs),
                              and each break bridged by the shortest run of line triangles
                              (a search, thousands of instructions a break) instead of the
                              fixed restart (up to 4): BT_ORDER_AUTO (0) both in fidelity mode
                              (export), neither in view and budget modes (per frame);
                              BT_ORDER_WALK the bridges only; BT_ORDER_BEST both in every
                              mode */
} bt_params;

enum { BT_ORDER_AUTO = 0, BT_ORDER_WALK = 1, BT_ORDER_BEST = 2 };

/* Counts the triangles the selection p would produce (fidelity and view modes,
 * the latter without hysteresis; for BT_BUDGET returns the budget), e.g. to size
 * a fidelity mesh exactly.  Nothing is written except *ntri. */
br_status bt_count(bt_tree *t, const bt_params *p, uint64_t *ntri);

/* Selects and emits the mesh into m.  If the selection needs more triangles than
 * m holds, it falls back to budget mode with m's capacity (screen-space priority
 * in view mode, error priority in fidelity mode) and sets m->overflow = 1: a
 * coarser but still conforming mesh.  bt_extract updates the per-vertex state
 * used by hysteresis (call it once per frame).  In view mode it reuses decisions of
 * earlier extractions into m that the camera's travel since cannot have changed
 * (frame coherence, docs/bitree.md; the same mesh; p->no_coherence: none).  Returns
 * BR_E_ARG on bad params. */
br_status bt_extract(bt_tree *t, const bt_params *p, bt_mesh *m);

/* Partitioned view extraction, for several threads (the caller schedules; core/
 * has none).  The walk is cut into at most BT_PARTS subtrees of the tree (those
 * at depth 4 below the two root triangles, or 5 or 6 for the first frame on a large
 * screen, a part that had more than 160 triangles cut from the next frame on where
 * its triangles are, two halves with fewer than 80 between them joined again),
 * each extracted into its own part mesh, then joined in walk order into m as one
 * strip: part k's strip is appended after line triangles that repeat the previous
 * part's last index and its first (parity kept).  The real triangles are the serial
 * walk's, in its order, with the same winding; a vertex on the edge between two parts may be listed once per part
 * (same x, y, z, morph), the one exception to "no two vertices share (x, y)".
 * The result never depends on how the parts were scheduled; which vertices are
 * listed twice depends on the cut, so on the frames since bt_parts_init or
 * bt_parts_reset (the strip's positions, and so the pixels, do not).  Protocol,
 * for one frame:
 *   bt_extract_begin(ps, t, p, m, &n)     serial; n parts to extract
 *   bt_extract_part(ps, k), k < n         any order, concurrently for distinct k
 *   bt_extract_end(ps, &j)                serial; hysteresis state, offsets
 *   bt_extract_join(ps, k, ..), k < j     any order, concurrently for distinct k
 * A part whose mesh is full is cut, and the new parts extracted, within
 * bt_extract_end (serially, up to 2 rounds; j is then the new count).  Only
 * BT_VIEW without the reorder pass is partitioned; other modes, and a frame
 * where a part mesh is still full or the joined mesh would not fit m, are
 * extracted by bt_extract (begin or end call it; n or j is then 0), so the
 * fallback to the budget rule is today's.  The walk of the parts reads t->st
 * only; bt_extract_end updates it, as bt_extract does.  ps, t, p and m must
 * stay unchanged from begin to the last join. */
#define BT_PARTS 255
typedef struct bt_parts bt_parts;
/* Bytes for parts of part_tri triangles each (>= 2); 0 if too large. */
size_t bt_parts_mem_size(uint32_t part_tri);
/* *out in mem (8-byte aligned, bt_parts_mem_size bytes). */
br_status bt_parts_init(bt_parts **out, uint32_t part_tri, void *mem, size_t mem_bytes);
/* Forgets the parts' history: the next extraction walks every part, cut at depth 4
 * (see below); the memory stays. */
void bt_parts_reset(bt_parts *ps);
br_status bt_extract_begin(bt_parts *ps, bt_tree *t, const bt_params *p, bt_mesh *m, uint32_t *nparts);
void bt_extract_part(bt_parts *ps, uint32_t k);
br_status bt_extract_end(bt_parts *ps, uint32_t *njoin);
/* Writes part k into m; m->v[*v0 .. *v0 + *nv) are its vertices. */
void bt_extract_join(bt_parts *ps, uint32_t k, uint32_t *v0, uint32_t *nv);
/* After bt_extract_end: the vertices of part k that may differ from the ones it had at
 * m->v[*v0_last ..] in the last frame joined from parts, a bit each (bit i & 7 of byte
 * i >> 3 for m->v[v0 + i], v0 as bt_extract_join gives), or NULL when any may.  A caller
 * that keeps the last frame's set-up vertices may copy the part's from there and set up
 * only these. */
const uint8_t *bt_part_moved_from(const bt_parts *ps, uint32_t k, uint32_t *v0_last);
/* Triangles of part k in the last extraction (0 if none): a scheduling hint. */
uint32_t bt_part_tris(const bt_parts *ps, uint32_t k);
/* Parts of the last extraction whose mesh was the frame before's with the heights of
 * its moving vertices updated, not walked again (frame coherence; a statistic). */
uint32_t bt_parts_reused(const bt_parts *ps);
/* Parts of the last extraction walked again only from their first decision that changed
 * (the part's records before it kept; a statistic). */
uint32_t bt_parts_resumed(const bt_parts *ps);

/* ---------------------------------------------------------------- streamed walk (bt_stream.c)
 * The view selection without a mesh, for a frame drawn band by band in little RAM (the
 * board, docs/mcu.md): each walk hands the leaves whose volume may reach a window of
 * the screen to a callback, as their three grid points, and keeps nothing of them.
 * The selection is bt_extract's view rule WITHOUT hysteresis (hyst_q8 must be 0; the
 * tree's frame state is neither read nor written, so bt_attach may give it none):
 * every walk of a frame gives every diamond the same answer, so the walks' leaves
 * together are one conforming mesh, the real triangles of bt_extract's mesh for the
 * same camera and hyst_q8 = 0 (same points, same geomorphed heights), met in the
 * order of its strip (or back to front: bt_stream_order); the leaves of one walk are
 * those not shown to lie wholly above or below the window's rows (a subtree by its
 * triangle's prism, a leaf by its own points), which covers every triangle that covers a
 * pixel centre in them (core/bt_stream.c).  A leaf comes apex first, then
 * counter-clockwise seen from +z, as bt_mesh's strip has its real triangles.
 * Memory: bt_stream_mem_size(cache_entries, nslot) bytes: about 2.8 KB of state, 2 bits a
 * slot for trees of up to nslot slots (bt_slot_count; >= 1): each diamond's answer kept
 * for the frame, so that the frame's walks decide each diamond about once; and 6 bytes a
 * cache entry, a power of two >= 16, for split diamonds' geomorph weights and plane
 * masks (a cache: fewer entries compute more weights again, the same leaves); 0 for bad
 * counts.
 * Protocol: bt_stream_init once; per frame bt_stream_frame (BR_E_ARG: not BT_VIEW,
 * hyst_q8 != 0, a window in p, a tree of more than nslot slots, or what bt_extract
 * refuses), then any number of
 * bt_stream_walk, each with its window (x0, y0, x1, y1 pixels as bt_params.window;
 * NULL: the whole viewport) and callback.  p and t are copied or read during the
 * frame's walks only; t must stay unchanged meanwhile. */
typedef struct bt_svert {
    int32_t x, y;          /* grid column and row */
    int32_t z;             /* height after geomorph (bt_vert.z) */
    int32_t wz;            /* world height (bt_world); made only while the walk has */
    int64_t pa[2];         /* a window plane to test: their values at world (x, y, 0) */
    uint32_t tag;          /* 0 when the walk makes the point; the callback may keep a
                              value here: the walk hands the same bt_svert to every leaf
                              of the triangle that made the point until it leaves it */
    uint16_t morph;        /* Q15 geomorph weight (bt_vert.morph) */
} bt_svert;
typedef void (*bt_stream_leaf)(void *user, bt_svert *v0, bt_svert *v1, bt_svert *v2);
typedef struct bt_stream bt_stream;
size_t bt_stream_mem_size(uint32_t cache_entries, uint32_t nslot);
br_status bt_stream_init(bt_stream **out, uint32_t cache_entries, uint32_t nslot, void *mem, size_t mem_bytes);
/* The order the leaves come in (from the next walk on): BT_STREAM_STRIP (bt_stream_init's)
 * is bt_extract's strip order; BT_STREAM_BACK_TO_FRONT a visibility order for the frame's
 * eye, each split's child on the far side of its split line from the eye first, so that
 * no leaf can hide part of a leaf that comes after it (painter's order: a frame drawn in
 * it needs no depth buffer, raster.h RS_DEPTH_NONE).  The same leaves either way. */
enum { BT_STREAM_STRIP = 0, BT_STREAM_BACK_TO_FRONT = 1 };
br_status bt_stream_order(bt_stream *s, int order);
br_status bt_stream_frame(bt_stream *s, bt_tree *t, const bt_params *p);
/* The leaves for window (NULL: all of them); returns how many went to fn (0 for a
 * window outside the viewport's bounds). */
uint32_t bt_stream_walk(bt_stream *s, const int32_t window[4], bt_stream_leaf fn, void *user);

/* Budget mode scratch: bt_extract with BT_BUDGET (or a fallback) needs a heap;
 * it is carved from m (bt_mesh_mem_size includes it).  When the recursive walk
 * broke and p->strip_order asks for it, the strip is written again in a greedy
 * leaf order (fewer references; same triangles, same winding) using the same area
 * as scratch (36 bytes per triangle + 4 per vertex, within the 64 per triangle
 * of capacity already counted). */

/* Projected (screen-space) error of diamond (x, y), 1/256 pixel, for tests and
 * the renderer's statistics; 0 when culled. */
int64_t bt_screen_error_q8(const bt_tree *t, const bt_params *p, int32_t x, int32_t y);

/* ---------------------------------------------------------------- utilities (bt_util.c) */
/* A world frame for f: world unit 2^-u metres with the largest u <= 10 that keeps
 * the grid (and heights) inside +-2^29 units; x east from column 0, y north from
 * the SOUTH row (row h-1 has y = 0), z up from 0 m.  *unit_shift = u. */
br_status bt_frame_auto(const hf *f, bt_frame *fr, int32_t *unit_shift);

/* Decodes m's strip into a triangle list (3 indices per triangle, winding kept),
 * dropping line triangles by 004's collinearity test (zero grid area), so a
 * consumer that wants no line triangles at all can draw the list.  out needs
 * 3 * ntri entries; returns the number of triangles written. */
uint32_t bt_strip_to_list(const bt_mesh *m, uint32_t *out);

/* TRUE maximum vertical error of m against the heightfield: max over every
 * triangle and every grid sample in it (closed) of |plane - z|, in 1/65536
 * heightfield units, rounded up; *at_x, *at_y (may be NULL) where it occurs.
 * Cost: the triangles' bounding boxes. */
int64_t bt_true_error_q16(const bt_tree *t, const bt_mesh *m, int32_t *at_x, int32_t *at_y);

#endif
