/* core/bt_em.h — the extraction state shared by the bitree's selection
 * (core/bt_mesh.c) and its strip writer (core/bt_emit.c); internal, not part of
 * the public contract (bitree.h). */
#ifndef BR_BT_EM_H
#define BR_BT_EM_H
#include <stdint.h>
#include "core/bitree.h"
#include "core/bt_int.h"

/* per-sample frame state bits (bt_tree.st): ST_PREV split in the previous view
 * frame (hysteresis), ST_SPLIT / ST_PUSHED the budget rule's marks, ST_CUR the
 * serial walk's "already recorded this frame" */
enum { ST_PREV = 1, ST_SPLIT = 2, ST_PUSHED = 4, ST_CUR = 8 };

typedef struct bti_heap_ent { int64_t key; uint32_t id; uint32_t pad_; } bti_heap_ent;

typedef struct bti_extract {
    bt_tree *t;
    const bt_params *p;
    bt_mesh *m;
    int count_only;
    uint64_t count;
    int32_t S, n;
    uint16_t cthr;          /* fidelity: split iff code > cthr */
    /* view */
    cam_plane pl[CAM_NPLANES];
    int64_t fq8;            /* f in Q8 pixels (f_q16 >> 8) */
    int64_t tau;            /* q8 pixels */
    int64_t tau_lo;         /* with hysteresis */
    int64_t morph_span;     /* q8 pixels: tau * morph/256 */
    int full;               /* mesh full: stop emitting */
    int rec_splits;         /* record this frame's splits (view mode, hysteresis) */
    int lost;               /* the split list overflowed */
    int nonvoid;            /* the padded grid has no void sample: skip the checks */
    int64_t wz_lo[256], wz_hi[256]; /* world z of the quantised height codes (floor, ceil) */
    struct bti_leaf { uint32_t ia, ic, ib, o0, o1, other; } pend; /* see bti_leaf */
    int has_pend;
    uint32_t plan[BTS_PLAN]; int nplan; /* a bridge's way on to the next leaf */
    uint32_t lim_nv, lim_ns;  /* room for two more leaves: vertices, strip indices */
    int fid;                /* plain fidelity rule (no budget marks) */
    int direct;             /* vertex hash slots by grid key (see home) */
    uint32_t hbase;         /* vertex hash generation (see reset_mesh) */
    uint32_t nbreak;        /* breaks of the walk bridged (the reorder pass runs if > 0) */
    int reorder;            /* p->strip_order asks for the reorder pass in this mode */
} bti_extract;

/* A leaf waiting to be written: its vertex indices, exit edge {o0, o1} and the
 * third vertex */
typedef struct bti_leaf bti_leaf;

/* The mesh's tail area: the budget heap, then the split id list (bt_mesh_init);
 * the reorder pass borrows the heap's part as scratch. */
static inline bti_heap_ent *bti_heap_of(const bt_mesh *m) { return (bti_heap_ent *)(void *)m->splits; }
static inline uint32_t bti_heap_cap(const bt_mesh *m) { return 4 * m->max_tri + 8; }
static inline uint32_t *bti_ids_of(const bt_mesh *m) { return (uint32_t *)(void *)(bti_heap_of(m) + bti_heap_cap(m)); }

/* core/bt_emit.c: writes leaf L (N: the next leaf, or NULL), 1 when N was
 * written too; writes the pending leaf; after a complete extraction whose walk
 * broke, rewrites the strip in a greedy leaf order when the mode asks for it
 * (e->reorder) and that is shorter. */
int btw_write_leaf(bti_extract *e, const bti_leaf *L, const bti_leaf *N);
void btw_flush(bti_extract *e);
void btw_reorder(bti_extract *e);

/* core/bt_mesh.c: diamond scale h and type (1 = D) of sample (x, y); projected
 * error of diamond (x, y) in 1/256 pixel, -1 when culled.
 * core/bt_budget.c: marks ST_SPLIT (and ST_PUSHED) on the diamonds a budget of
 * `budget` nominal triangles buys; the ids it marked go to the mesh's id list
 * (*nid of them, to clear afterwards); sets e->tau to the last split's rho. */
int32_t bti_dscale(int32_t x, int32_t y, int32_t S, int *typeD);
int64_t bti_rho_q8(const bti_extract *e, int32_t x, int32_t y);
uint32_t bti_budget_mark(bti_extract *e, uint32_t budget, uint32_t *nid);

#endif
