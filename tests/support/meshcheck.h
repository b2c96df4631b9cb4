/* tests/support/meshcheck.h — independent referee for triangle meshes over a grid.
 *
 * Test support only (links into every test and benchmark program; uses stdio and
 * malloc; never part of libbitrain).  It trusts nothing the mesher says: it checks
 * topology, coverage and the TRUE vertical error against every grid sample, with
 * exact integer arithmetic (int64, plus a portable 64x64->128 multiply for
 * comparing rationals).  It does not look at the bitree; any mesher can be judged.
 *
 * ---------------------------------------------------------------------------
 * CONVENTIONS
 * ---------------------------------------------------------------------------
 * Grid: w x h samples, row-major, z[y*w + x], x = column (east), y = row (south,
 *   row 0 = north), exactly as core/hf.h.  Heights are int32 in the heightfield's
 *   own unit; MC_VOID (== HF_NODATA == INT32_MIN) marks a void sample.  Valid
 *   heights must satisfy |z| <= BR_Z_LIMIT.  w, h >= 2, w, h <= BR_MAX_SIDE.
 * Vertices (mc_vert): integer grid position (x, y), 0 <= x < w, 0 <= y < h, and a
 *   height zq in units of 2^-zbits of the heightfield unit (zbits 0..30, one value
 *   for the whole mesh: lets a mesher hand in fictitious points whose interpolated
 *   height is not an integer, e.g. zbits = 1 for a hypotenuse midpoint).
 *   Vertices are identified by POSITION: two indices at the same (x, y) are the
 *   same point; if their heights differ that is a "split vertex" (a 3D crack).
 *   Vertices not referenced by any triangle are ignored.
 * Triangles: index triples into the vertex array (int32).
 * Orientation: cross(p0,p1,p2) = (x1-x0)(y2-y0) - (y1-y0)(x2-x0) in GRID
 *   coordinates.  cross > 0 is orientation +1: clockwise seen from +z with north
 *   up (= counter-clockwise on a screen whose y axis points down, i.e. as the
 *   grid is stored).  cross < 0 is orientation -1: counter-clockwise seen from
 *   +z with north up (the usual OBJ/GL convention if you map y -> -north).
 *   The checker accepts either, but ALL triangles must share one; it reports
 *   which (mc_report.orientation) and counts the others as flipped.
 *   cross == 0 is a degenerate (zero-area, "line") triangle: an error in a
 *   triangle list (strip decoding separates them first, see below).
 * Covered region: the closed rectangle [0,w-1]x[0,h-1] minus the voids.  Doubled
 *   areas: a unit cell has doubled area 2.
 *
 * ---------------------------------------------------------------------------
 * mc_check: WHAT IS CHECKED (each count is 0 in a correct mesh unless noted)
 * ---------------------------------------------------------------------------
 * bad_vertex      triangle index out of range, vertex outside the grid, or vertex
 *                 on a void sample (no vertex lies on a void).
 * split_vertex    two referenced vertices at one position with different heights.
 * degenerate      triangles with zero 2D area.
 * flipped         non-degenerate triangles whose orientation is not the majority's.
 * orientation     +1 / -1 as above (majority sign; 0 when there are no triangles).
 * nonmanifold_edges  edges (by position pair) used by more than two triangles.
 * same_dir_edges  edges used by exactly two triangles in the SAME direction (a
 *                 flipped triangle or two triangles folded over each other).
 * boundary_edges  edges used by exactly one triangle (informative count).
 * bad_boundary_edges  boundary edges that are neither on the grid border (both ends
 *                 on the same side x=0, x=w-1, y=0 or y=h-1) nor next to a void:
 *                 "next to a void" = some void sample lies in the closed square
 *                 erected on the edge on its uncovered side (strictly off the
 *                 edge's line).  A crack shows up here.  (The void rule is a
 *                 necessary condition, not a proof; with no voids the check is exact.)
 * tjunctions      (vertex, edge) pairs where a referenced vertex lies strictly inside
 *                 the segment of another triangle's edge (lattice walk, exact).
 * area2           sum of |doubled area| over non-degenerate triangles.
 * area2_max       doubled area the valid samples allow: per cell, 2 if all four
 *                 corners are valid, 1 if exactly three are (one half cell), else 0.
 *                 With no voids area2 must EQUAL area2_max = 2(w-1)(h-1); with voids
 *                 area2 <= area2_max is required (2(w-1)(h-1) with void_reach) and, when the caller passes
 *                 expect_area2 > 0 in mc_check's options, area2 == expect_area2.
 * overlap_samples samples strictly inside one triangle and covered (closed) by
 *                 another one as well.
 * uncovered       valid samples covered by no triangle: an error unless
 *                 opts.allow_uncovered = 1 (for grids with voids, where a valid sample
 *                 beside a void may be left out when every half cell around it, in the
 *                 mesher's diagonal pattern, touches the void).
 * uncovered_far   those of them with no void among their 8 neighbours: ALWAYS an
 *                 error (a hole), whatever allow_uncovered says.
 * void_covered    void samples inside (closed) some triangle.  With opts.void_reach
 *                 = R > 0 (a mesher that treats a void's extent as error, core/bt_err.c
 *                 "Voids"): (void sample, triangle) pairs whose triangle's bounding box
 *                 is wider or higher than R samples; those within R are counted in
 *                 void_covered_near and are no error.  R also widens "near a void"
 *                 for uncovered_far and bad_boundary_edges from the 8 neighbours and
 *                 the edge's square to every sample within R (Chebyshev) of the sample
 *                 or of the edge.
 * range_errors    triangles whose |vertex height| or |sample height| times their
 *                 doubled area would overflow int64 (then their error is not
 *                 evaluated; cannot happen with zbits <= 2 up to 16385^2 grids).
 * Error: for every sample inside (closed) each triangle, with integer barycentric
 *   weights b0+b1+b2 = D (D = |cross|), the plane height is (sum bi*zq_i)/(D*2^zbits)
 *   and the error |plane - z| = |sum bi*zq_i - D*2^zbits*z| / (D*2^zbits).  A sample
 *   on a shared edge is evaluated in every triangle containing it (they agree when
 *   the mesh is watertight).  max error = the largest such rational:
 *     err_num / err_den  (reduced, heightfield units; 0/1 for an empty mesh)
 *     err_q10            ceil(1024 * err) : conservative, in 1/1024 units
 *     err_x, err_y, err_tri  where it happens (the first in scan order on ties)
 * ok = 1 when every error count above is zero (uncovered per the rule above) and
 *   the area rule holds; with opts.partial = 1 bad_boundary_edges, uncovered and
 *   uncovered_far are not errors and area2 <= area2_max is the only area rule.
 *   bad_x, bad_y, bad_what name the first defect found.  The error is reported,
 *   not judged: compare it with mc_err_exceeds().  mc_check returns ok (or -1 if
 *   memory runs out).
 *   Cost: 14 bytes of scratch per grid sample and 8 per triangle edge use; time
 *   O(w*h + T) for the edges (bucketed by lower end), O(sum of triangle bounding
 *   boxes) for the raster pass, O(sum of edge lengths) for T-junctions: about
 *   0.45 s for 2 million triangles over 1025x1025 on the development machine.
 *
 * ---------------------------------------------------------------------------
 * STRIPS (GL convention)
 * ---------------------------------------------------------------------------
 * Triangle k of strip s[0..n) (k = 0..n-3) is (s[k], s[k+1], s[k+2]) for even k
 * and (s[k+1], s[k], s[k+2]) for odd k, so a proper strip keeps one winding.
 * A "line triangle" is one with zero 2D area: a repeated index, two indices at one
 * position, or three collinear positions.  mc_strip_decode splits them off.
 * mc_strip_compare checks that the strip's non-line triangles equal a given
 * triangle list as MULTISETS OF VERTEX POSITION SETS ({p0,p1,p2} ignoring order),
 * that all of them have one orientation, and that it is the list's (per matched
 * triangle).  Line triangles are counted, never compared.
 */
#ifndef BR_MESHCHECK_H
#define BR_MESHCHECK_H
#include <stdint.h>
#include <stdio.h>
#include "core/hf.h"

#define MC_VOID INT32_MIN
BR_STATIC_ASSERT(MC_VOID == HF_NODATA, meshcheck_void_is_hf_nodata);

typedef struct mc_vert {
    int32_t x, y;      /* grid column, row */
    int64_t zq;        /* height in 2^-zbits heightfield units */
} mc_vert;

typedef struct mc_mesh {
    const mc_vert *v;  /* nv vertices */
    int32_t nv;
    const int32_t *tri;/* 3*nt indices */
    int64_t nt;
    int32_t zbits;     /* fractional bits of zq (0..30) */
} mc_mesh;

typedef struct mc_opts {        /* zero = defaults */
    int64_t expect_area2;       /* 0 = no check beyond the area2_max rule; > 0 = area2 must equal it */
    int allow_uncovered;        /* 1: valid samples left uncovered are not an error */
    int skip_error;             /* 1: topology only (no error evaluation) */
    int partial;                /* 1: the mesh covers only part of the grid on purpose
                                   (frustum-culled view meshes): boundary edges inside
                                   the domain and uncovered samples are counted but are
                                   not errors, and area2 <= area2_max is the only area
                                   rule; T-junctions, overlaps, edges used thrice or
                                   twice the same way, flips etc. still are errors */
    int32_t void_reach;         /* > 0: the mesher may draw over voids and leave holes
                                   wider than them, within this many samples (see
                                   void_covered; implies allow_uncovered); 0: voids
                                   are holes exactly */
} mc_opts;

typedef struct mc_report {
    int64_t triangles, bad_vertex, split_vertex, degenerate, flipped;
    int32_t orientation;
    int64_t edges, boundary_edges, nonmanifold_edges, same_dir_edges, bad_boundary_edges;
    int64_t tjunctions;
    int64_t area2, area2_max, voids;
    int64_t overlap_samples, uncovered, uncovered_far, void_covered, void_covered_near, range_errors;
    int64_t err_num, err_den, err_q10;
    int32_t err_x, err_y;
    int64_t err_tri;
    /* first place of each kind of defect, for messages: -1 when none */
    int32_t bad_x, bad_y;        /* first bad boundary edge / T-junction / overlap / uncovered sample */
    const char *bad_what;        /* what that first defect was, or "" */
    int ok;
} mc_report;

/* Checks mesh m against the grid (w, h, z).  o may be NULL (defaults).
 * Returns r->ok (1 good, 0 defects) or -1 when scratch memory cannot be had. */
int mc_check(const mc_mesh *m, int32_t w, int32_t h, const int32_t *z,
             const mc_opts *o, mc_report *r);

/* 1 when the reported max error exceeds lim_num/lim_den heightfield units
 * (lim_den > 0), exactly.  Example, limit in metres for an hf f:
 * mc_err_exceeds(r, metres_mm * f.z_den, 1000LL * f.z_num) with metres_mm in mm. */
int mc_err_exceeds(const mc_report *r, int64_t lim_num, int64_t lim_den);

/* Prints a one-paragraph summary of r (for test failure messages and benchmarks). */
void mc_report_print(FILE *f, const mc_report *r);

/* Exact max vertical error only, as mc_check computes it (no topology).  Fills
 * r->err_* and r->uncovered/void_covered/range_errors; returns 0, or -1 on no memory. */
int mc_max_error(const mc_mesh *m, int32_t w, int32_t h, const int32_t *z, mc_report *r);

/* Strip decoding.  s has n indices (n < 3 gives no triangles).  tri and line may be
 * NULL; otherwise each has room for 3*(n-2) indices.  Proper triangles go to tri
 * (in GL winding order as above), line triangles to line; counts to *n_tri, *n_line.
 * Positions come from v (nv vertices); an index out of range makes the call return
 * -1 (nothing else is reported then); otherwise 0. */
int mc_strip_decode(const int32_t *s, int64_t n, const mc_vert *v, int32_t nv,
                    int32_t *tri, int64_t *n_tri, int32_t *line, int64_t *n_line);

typedef struct mc_strip_report {
    int64_t refs;           /* n */
    int64_t decoded;        /* proper (non-line) triangles in the strip */
    int64_t line;           /* line triangles in the strip */
    int64_t missing;        /* triangles of the list the strip does not produce */
    int64_t extra;          /* proper strip triangles not in the list (or duplicated) */
    int64_t winding_mixed;  /* proper strip triangles whose orientation differs from the
                               strip's first proper triangle */
    int64_t winding_vs_list;/* matched triangles whose strip orientation differs from the list's */
    int32_t orientation;    /* of the strip's first proper triangle (+1/-1), 0 if none */
    int ok;                 /* all of missing, extra, winding_mixed, winding_vs_list are 0 */
} mc_strip_report;

/* Compares strip s (n indices) with triangle list tri (nt triangles), both indexing v.
 * Returns r->ok, or -1 on a bad index or no memory. */
int mc_strip_compare(const int32_t *s, int64_t n, const int32_t *tri, int64_t nt,
                     const mc_vert *v, int32_t nv, mc_strip_report *r);

#endif
