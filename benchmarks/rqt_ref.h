/* benchmarks/rqt_ref.h — the restricted quadtree triangulation (Pajarola 98, as
 * papers/002 section 2.2 and papers/001 section 2.1 describe it) over a
 * (2^k+1)^2 grid, the baseline of table 1 of 002; and, beside it, 002's own
 * bitree rules computed the same way, for reference.
 *
 * Benchmark code (malloc; integer arithmetic).  Uses the RTIN triangle numbering of
 * benchmarks/martini_ref.h (include both .c files in the bench program).
 *
 * Hierarchy.  The grid is two right triangles split recursively at the midpoint of
 * the hypotenuse (002 figure 2: the bitree; the quadtree blocks of 001/002 figure 1
 * are two such levels).  Every grid point other than the 4 corners is the
 * hypotenuse midpoint of one triangle (on the border) or two (inside): its
 * "diamond".  The apex (right-angle vertex) of a diamond triangle is the midpoint
 * of its parent.
 *
 * Selection (002 section 3.2).  002 does not pin down its criterion, so three
 * readings are offered; e(T) = max over the grid samples inside the closed
 * triangle T of |plane_T - z| (vertical distance, exact rational):
 *  RQ_SEL_VERTEX: a point is selected when its own interpolation error on the
 *    hypotenuse it splits, |z_m - (z_a + z_b)/2|, exceeds tol ("distancia del
 *    punto original a su proyección sobre el modelo simplificado"), whatever its
 *    ancestors do.  This reading reproduces table 1's savings (BT vs QT) closely
 *    on real crops (docs/baselines.md), so bench_baselines prints it first;
 *  RQ_SEL_EACH: a point is selected when a triangle of the hierarchy whose
 *    hypotenuse midpoint it is has e(T) > tol, whether or not that triangle's
 *    ancestors are split;
 *  RQ_SEL_TOPDOWN: from the two roots, split T while e(T) > tol; the midpoints of
 *    split triangles are selected (every selected point's ancestors are too, so
 *    few points are added against cracks).
 * The 4 corners are always selected.  tol = tol_num / tol_den height units
 * (tol_num = -1: select everything, the full grid); table 1 uses tol = pct% of
 * the crop's height range.  With RQ_SEL_EACH every leaf of the QT mesh has
 * e(T) <= tol (its midpoint was not selected), so the QT mesh holds the tolerance:
 * it is the exact per-triangle metric with the conforming closure.  The other two
 * readings do not bound the error (forced splits put real heights where a plane
 * was good enough); bench_baselines prints the true error of each QT mesh.

 * Restricted quadtree (002 fig. 6/7, Pajarola 98): a selected point depends on the
 * apexes of both triangles of its diamond (equivalently: a block centre on the two
 * opposite block corners, an edge midpoint on the centres of the two blocks
 * sharing the edge); dependencies are selected too, transitively.  In triangle
 * terms: split(T) => split(parent(T)) and split(partner(T)).  The result is a
 * conforming mesh (no T-junctions).  ADDED = points in the closure that were not
 * selected; TRANSMIT = all points of the mesh (all are real).
 *
 * 002's bitree rules (for comparison only; bitrain's core bitree is a separate,
 * T-junction-free design): a selected point splits both triangles of its diamond;
 * a triangle that must be split must exist, so its parent is split (its midpoint
 * becomes a FICTITIOUS point if not selected, height interpolated on the
 * hypotenuse, 002 fig. 9), but the fictitious point does not split the parent's
 * partner: that partner keeps a T-junction whose vertex lies exactly on its edge
 * (no crack, 002 section 2.2).  ADDED = fictitious points; TRANSMIT = selected.
 *
 * Triangles = 2 + number of split triangles (each split turns one into two).
 *
 * Strip references ("simplest honest count"): the leaves are visited in
 * Sierpinski order (the recursive order that walks each triangle's hypotenuse
 * from one end to the other, so consecutive leaves share a vertex and usually an
 * edge) and written as ONE generalised strip (GL convention, see
 * tests/support/meshcheck.h) that produces every leaf once, in that order, with
 * the mesh's winding; every other triangle it produces is a line triangle (zero
 * area: a repeated index or three collinear points).  Among such strips the
 * shortest is found exactly by dynamic programming over the strip's state after
 * each leaf (its last two indices and the parity of its length; the indices
 * appended for a leaf are drawn from the leaf's vertices and that state, at most
 * 5).  refs = strip length; line = line triangles in it = refs - 2 - triangles.
 * This is the best strip for that fixed order, not 002's A/B/C sequences; on the
 * full 65x65 grid it gives 12290 refs (1.50 per triangle, 4096 line triangles)
 * where 002 reports 13655 (bitree) and 12972 (quadtree).  bench_baselines checks
 * with meshcheck that every strip decodes to its mesh. */
#ifndef BR_RQT_REF_H
#define BR_RQT_REF_H
#include <stdint.h>

typedef struct rq_side {      /* one scheme's figures */
    int64_t added;            /* points added against cracks (QT: dependencies; BT: fictitious) */
    int64_t points;           /* vertices of the mesh (selected + added) */
    int64_t transmit;         /* QT: points; BT: selected (fictitious ones are deducible) */
    int64_t triangles;
    int64_t refs, line;       /* strip length and line triangles in it */
} rq_side;

typedef struct rq_result {
    int64_t selected;         /* including the 4 corners */
    rq_side qt, bt;
} rq_result;

typedef struct rq_mesh {      /* optional outputs, grid indices y*size + x; NULL = not wanted */
    int32_t *tri;             /* 3 per triangle, capacity 3 * 2 (size-1)^2 */
    int64_t nt;
    int32_t *strip;           /* capacity 8 * 2 (size-1)^2 */
    int64_t ns;
} rq_mesh;

enum { RQ_SEL_EACH = 0, RQ_SEL_TOPDOWN = 1, RQ_SEL_VERTEX = 2 };

/* z: size*size int32 heights (size = 2^k + 1, 3..4097); sel_mode RQ_SEL_*.
 * qt_out / bt_out may be NULL.  Returns 0, or -1 on a bad argument or no memory. */
int rq_run(const int32_t *z, int32_t size, int64_t tol_num, int64_t tol_den, int sel_mode,
           rq_result *r, rq_mesh *qt_out, rq_mesh *bt_out);

/* The strip count above, for any triangle list: the shortest single GL strip that
 * produces leaves[0..nt) (grid indices y*size + x, 3 per triangle, all of one
 * winding) in THIS order, every other triangle being a line triangle.  out (may be
 * NULL) gets the strip, capacity 5 * nt + 3.  Returns its length (refs) and sets
 * *line; -1 on no memory.  Give it the leaves in Sierpinski order to compare a
 * strip emitter with the best strip for that order. */
int64_t rq_strip_dp(int32_t size, const int32_t *leaves, int64_t nt, int32_t *out, int64_t *line);

#endif
