/* benchmarks/martini_ref.h — a faithful C port of @mapbox/martini (RTIN), the
 * performance and quality baseline for the bitree (issue 3).
 *
 * Benchmark code, outside core/: it uses malloc and, for the faithful variant,
 * float, exactly as martini's JavaScript does.  Link it by including
 * "benchmarks/martini_ref.c" in a bench program (the Makefile links only
 * tests/support/ into benchmarks).
 *
 * The algorithm (mapbox/martini index.js, MIT): a (2^k+1)^2 grid is two right
 * triangles, (0,0),(max,max),(max,0) and (max,max),(0,0),(0,max), each split at the
 * midpoint m of its hypotenuse a-b into (c,a,m) and (b,c,m), down to triangles with
 * unit legs.  Every triangle of every level is numbered in an implicit binary
 * tree; mr_grid holds their (a, b) coordinates (martini's `coords`, 4 x uint16 per
 * triangle, 8 (size-1)^2 bytes) and martini's `indices` scratch.
 *
 * Error metric, martini's (NOT a bound): visiting triangles from the finest level
 * up, errors[m] = max(errors[m], |(z_a + z_b)/2 - z_m|) and, for triangles that
 * have children, errors[m] = max(errors[m], errors[left child m], errors[right child m]).
 * A triangle whose midpoint error is <= max_error is emitted whole, yet its plane
 * can miss a sample by more than max_error, because a child's error is measured
 * against the CHILD's plane, not the parent's.
 *
 * Sound variant: errors[m] = max(errors[m], e_m + max(left child bound, right child
 * bound)), e_m = |(z_a + z_b)/2 - z_m|.  The parent plane and a child's plane agree
 * on the child's two other vertices and differ by e_m at m, so |parent - z| <=
 * e_m + |child - z| everywhere in the child: a true upper bound, O(n) to build.
 * (Here a child's bound is its diamond's, the max over it and its neighbour across
 * the hypotenuse; mr_errors_tight keeps per-triangle bounds and is tighter.)
 *
 * Two arithmetic flavours:
 *  - f32 (faithful): heights float32, errors float32, midpoint errors in double,
 *    exactly the operations martini performs in JS (Float32Array storage, double
 *    arithmetic), so triangle counts equal the npm package's bit for bit.
 *  - int: heights int32 in the heightfield's units (e.g. decimetres for
 *    terrain-RGB), errors uint32 in DOUBLED units: e2 = |z_a + z_b - 2 z_m|, so the
 *    midpoint error is exact; a threshold of E units is thr2 = 2E (floor if E is
 *    fractional).  Ties at exactly E may differ from f32 by float32 rounding of the
 *    heights (see docs/baselines.md for the measured effect).
 *
 * Extraction (martini getMesh): recurse from the two root triangles; split while
 * the triangle has legs longer than 1 and errors[m] > max_error; emit (a, b, c)
 * otherwise.  Two passes as martini: count and number vertices in first-use
 * order, then write vertices and triangles.  Output vertices are (x, y) grid
 * positions (uint16), triangles index them, in martini's order and winding:
 * orientation -1 in tests/support/meshcheck.h's terms (counter-clockwise seen from
 * +z with north up). */
#ifndef BR_MARTINI_REF_H
#define BR_MARTINI_REF_H
#include <stdint.h>

typedef struct mr_grid {
    int32_t size;          /* 2^k + 1 */
    int64_t ntri;          /* all triangles of all levels: 2 (size-1)^2 - 2 */
    int64_t nparent;       /* those with children: ntri - (size-1)^2 */
    uint16_t *coords;      /* 4 per triangle: ax, ay, bx, by */
    uint32_t *indices;     /* size^2 scratch for getMesh */
} mr_grid;

typedef struct mr_mesh {
    uint16_t *vert;        /* 2 per vertex: x, y (capacity size^2) */
    uint32_t *tri;         /* 3 per triangle (capacity 2 (size-1)^2) */
    int64_t nv, nt;
} mr_mesh;

/* Allocates the coordinate table (martini's constructor).  0 ok, -1 bad size or no memory. */
int mr_grid_init(mr_grid *g, int32_t size);
void mr_grid_free(mr_grid *g);

/* Allocates an output mesh of full capacity for g.  0 ok, -1 no memory. */
int mr_mesh_alloc(const mr_grid *g, mr_mesh *m);
void mr_mesh_free(mr_mesh *m);

/* Faithful martini: terrain and errors are size^2 floats; errors is overwritten. */
void mr_errors_f32(const mr_grid *g, const float *terrain, float *errors);
/* Faithful getMesh: triangles until errors[m] <= max_error. */
void mr_mesh_f32(mr_grid *g, const float *errors, double max_error, mr_mesh *out);

/* Integer flavour: z is size^2 int32 heights (|z| <= 2^28); err2 (size^2) gets
 * doubled errors.  sound = 0: martini's max(midpoint, children) metric;
 * sound = 1: the true bound e_m + max(child bounds). */
void mr_errors_int(const mr_grid *g, const int32_t *z, uint32_t *err2, int sound);
/* A tighter sound bound, still O(n): per-triangle bounds B(T) = e_m + max(B of its
 * two children) (tb: ntri uint32 scratch), err2[m] = the larger B of the diamond
 * at m, then martini's max propagation of err2 so the extraction stays crack-free.
 * Emitted triangles have B(T) <= thr2, a true bound (docs/baselines.md). */
void mr_errors_tight(const mr_grid *g, const int32_t *z, uint32_t *tb, uint32_t *err2);

/* getMesh on doubled errors: triangles until err2[m] <= thr2. */
void mr_mesh_int(mr_grid *g, const uint32_t *err2, int64_t thr2, mr_mesh *out);

/* martini's test fixture decoding: terrain-RGB raw value v = R*65536 + G*256 + B to
 * the float32 height martini's test computes: (v / 10.0 - 10000.0) stored as float. */
float mr_terrain_rgb_f32(int32_t raw);

#endif
