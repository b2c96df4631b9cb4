/* tests/test_meshcheck.c — the mesh referee must catch every defect it claims to.
 *
 * Small hand-made meshes over real terrain (9x9 and 17x17 crops of SRTM3
 * N47E009, the Raetikon Alps at column 800, row 1100: 1638..2525 m), each with
 * one defect planted: a hole, a 3D crack (split vertex), a T-junction, an
 * overlap, a flipped triangle, a wrong height; plus the exact error against an
 * independent floating-point brute force, and strip decoding. */
#include "tests/test.h"
#include "tests/support/meshcheck.h"
#include "platform/load.h"
#include <math.h>
/* the baselines (benchmark code, compiled into this test only): real adaptive
 * meshes for the referee to judge, and the referee pins their behaviour */
#include "benchmarks/martini_ref.c"
#include "benchmarks/rqt_ref.c"

#define CX 800
#define CY 1100

static int32_t g_crop9[9 * 9], g_crop17[17 * 17];
static int g_have;

/* Reads an n x n crop at (CX, CY) of N47E009.hgt with plain stdio
 * (big-endian int16, 1201x1201, row 0 = north). */
static int read_crop(int n, int32_t *out)
{
    FILE *f = fopen(t_data("hgt/N47E009.hgt"), "rb");
    int x, y;
    if (!f) return 0;
    for (y = 0; y < n; y++) {
        unsigned char row[64];
        if (fseek(f, ((long)(CY + y) * 1201 + CX) * 2, SEEK_SET) != 0 ||
            fread(row, 2, (size_t)n, f) != (size_t)n) { fclose(f); return 0; }
        for (x = 0; x < n; x++)
            out[y * n + x] = (int16_t)(uint16_t)((row[2 * x] << 8) | row[2 * x + 1]);
    }
    fclose(f);
    return 1;
}

/* ---- mesh builders -------------------------------------------------------- */

typedef struct tmesh {
    mc_vert v[17 * 17 + 64];
    int32_t nv;
    int32_t t[3 * 1024];
    int64_t nt;
} tmesh;

static tmesh g_m;

/* Every grid sample is a vertex (index y*n + x), height zq = z << zbits. */
static void verts_all(tmesh *m, int n, const int32_t *z, int zbits)
{
    int x, y;
    m->nv = 0;
    m->nt = 0;
    for (y = 0; y < n; y++)
        for (x = 0; x < n; x++) {
            mc_vert *p = &m->v[m->nv++];
            p->x = x; p->y = y; p->zq = (int64_t)z[y * n + x] * ((int64_t)1 << zbits);
        }
}

static void add_tri(tmesh *m, int32_t a, int32_t b, int32_t c)
{
    m->t[3 * m->nt] = a; m->t[3 * m->nt + 1] = b; m->t[3 * m->nt + 2] = c;
    m->nt++;
}

/* Block (x, y, s): the square [x, x+s] x [y, y+s] as two triangles split by the
 * diagonal (x+s, y)-(x, y+s), both with orientation -1 (see meshcheck.h). */
static void add_block(tmesh *m, int n, int x, int y, int s)
{
    int32_t A = y * n + x, B = (y + s) * n + x, C = y * n + x + s, D = (y + s) * n + x + s;
    add_tri(m, A, B, C);
    add_tri(m, C, B, D);
}

static void blocks_uniform(tmesh *m, int n, int s)
{
    int x, y;
    for (y = 0; y + s < n; y += s)
        for (x = 0; x + s < n; x += s) add_block(m, n, x, y, s);
}

static mc_mesh as_mesh(const tmesh *m, int zbits)
{
    mc_mesh mm;
    mm.v = m->v; mm.nv = m->nv; mm.tri = m->t; mm.nt = m->nt; mm.zbits = zbits;
    return mm;
}

/* Independent reference: max |plane - z| over all samples in each triangle,
 * in double precision with a different formula (plane through three points). */
static double ref_max_error(const tmesh *m, int n, const int32_t *z, int zbits)
{
    double best = 0, sc = 1.0 / (double)((int64_t)1 << zbits);
    int64_t t;
    int x, y;
    for (t = 0; t < m->nt; t++) {
        const mc_vert *a = &m->v[m->t[3 * t]], *b = &m->v[m->t[3 * t + 1]], *c = &m->v[m->t[3 * t + 2]];
        double ux = b->x - a->x, uy = b->y - a->y, uz = (double)(b->zq - a->zq) * sc;
        double vx = c->x - a->x, vy = c->y - a->y, vz = (double)(c->zq - a->zq) * sc;
        double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
        for (y = 0; y < n; y++)
            for (x = 0; x < n; x++) {
                double d1 = (b->x - a->x) * (double)(y - a->y) - (b->y - a->y) * (double)(x - a->x);
                double d2 = (c->x - b->x) * (double)(y - b->y) - (c->y - b->y) * (double)(x - b->x);
                double d3 = (a->x - c->x) * (double)(y - c->y) - (a->y - c->y) * (double)(x - c->x);
                double pz, e;
                if (!((d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0))) continue;
                pz = (double)a->zq * sc - (nx * (x - a->x) + ny * (y - a->y)) / nz;
                e = fabs(pz - z[y * n + x]);
                if (e > best) best = e;
            }
    }
    return best;
}

static double rep_err(const mc_report *r) { return (double)r->err_num / (double)r->err_den; }

/* ---- tests ------------------------------------------------------------------ */

static void test_data(void)
{
    CHECK(g_have);
    /* real relief: the crop is not flat */
    CHECK_EQ(g_crop9[0], g_crop17[0]);
    CHECK(g_crop17[16 * 17 + 16] != g_crop17[0]);
}

static void test_full_resolution_is_exact(void)
{
    mc_mesh mm;
    mc_report r;
    int n;
    for (n = 9; n <= 17; n += 8) {
        const int32_t *z = n == 9 ? g_crop9 : g_crop17;
        verts_all(&g_m, n, z, 0);
        blocks_uniform(&g_m, n, 1);
        mm = as_mesh(&g_m, 0);
        CHECK_EQ(mc_check(&mm, n, n, z, NULL, &r), 1);
        if (!r.ok) mc_report_print(stderr, &r);
        CHECK_EQ(r.triangles, 2 * (n - 1) * (n - 1));
        CHECK_EQ(r.orientation, -1);
        CHECK_EQ(r.area2, 2 * (n - 1) * (n - 1));
        CHECK_EQ(r.boundary_edges, 4 * (n - 1));
        CHECK_EQ(r.edges, (n - 1) * n * 2 + (n - 1) * (n - 1));
        CHECK_EQ(r.err_num, 0);
        CHECK_EQ(r.err_q10, 0);
        CHECK_EQ(r.uncovered, 0);
    }
}

static void test_coarse_error_matches_reference(void)
{
    static const int sizes[] = { 16, 8, 4, 2 };
    mc_mesh mm;
    mc_report r;
    int k;
    for (k = 0; k < 4; k++) {
        double ref;
        verts_all(&g_m, 17, g_crop17, 0);
        blocks_uniform(&g_m, 17, sizes[k]);
        mm = as_mesh(&g_m, 0);
        CHECK_EQ(mc_check(&mm, 17, 17, g_crop17, NULL, &r), 1);
        ref = ref_max_error(&g_m, 17, g_crop17, 0);
        CHECK_MSG(fabs(rep_err(&r) - ref) < 1e-9, "block %d: %g vs ref %g", sizes[k], rep_err(&r), ref);
        CHECK(ref > 1.0);  /* real terrain: a coarse mesh has a real error */
        /* the conservative 1/1024 ceiling brackets the exact value */
        CHECK((double)r.err_q10 / 1024.0 >= rep_err(&r));
        CHECK((double)r.err_q10 / 1024.0 < rep_err(&r) + 1.0 / 1024.0 + 1e-12);
        /* the reported sample really has that error */
        CHECK(r.err_x >= 0 && r.err_y >= 0 && r.err_tri >= 0);
        /* exceeds: exact comparisons at the value itself */
        CHECK_EQ(mc_err_exceeds(&r, r.err_num, r.err_den), 0);
        CHECK_EQ(mc_err_exceeds(&r, r.err_num - 1, r.err_den), 1);
        CHECK_EQ(mc_err_exceeds(&r, 2 * r.err_num + 1, 2 * r.err_den), 0);
    }
}

static void test_wrong_height_is_caught(void)
{
    /* a vertex 5 units off its sample: the error there is exactly 5 more than
     * the sample's own (zero, at full resolution) */
    mc_mesh mm;
    mc_report r;
    verts_all(&g_m, 9, g_crop9, 0);
    blocks_uniform(&g_m, 9, 1);
    g_m.v[4 * 9 + 3].zq += 5;
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 1);   /* topology is fine */
    CHECK_EQ(r.err_num, 5);
    CHECK_EQ(r.err_den, 1);
    CHECK_EQ(r.err_x, 3);
    CHECK_EQ(r.err_y, 4);
    CHECK_EQ(mc_err_exceeds(&r, 4, 1), 1);
    CHECK_EQ(mc_err_exceeds(&r, 5, 1), 0);
    /* same with 1 fractional bit: 2.5 units too high */
    verts_all(&g_m, 9, g_crop9, 1);
    blocks_uniform(&g_m, 9, 1);
    g_m.v[4 * 9 + 3].zq += 5;
    mm = as_mesh(&g_m, 1);
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 1);
    CHECK_EQ(r.err_num, 5);
    CHECK_EQ(r.err_den, 2);
    CHECK_EQ(r.err_q10, 2560);
    CHECK_EQ(mc_err_exceeds(&r, 249, 100), 1);
    CHECK_EQ(mc_err_exceeds(&r, 5, 2), 0);
}

static void test_fictitious_half_height(void)
{
    /* the 3x3 corner of the crop as two level-1 triangles split at the centre
     * (1,1), whose height is interpolated on the diagonal (2,0)-(0,2) as a
     * bitree fictitious point would be: (z(2,0) + z(0,2)) / 2, a half-integer,
     * handed in with zbits = 1.  The edge samples (1,0), (0,1), (2,1), (1,2) are
     * not vertices, so they are not T-junctions. */
    static int32_t z3[9];
    mc_mesh mm;
    mc_report r;
    int x, y;
    double ref;
    for (y = 0; y < 3; y++) for (x = 0; x < 3; x++) z3[y * 3 + x] = g_crop9[y * 9 + x];
    verts_all(&g_m, 3, z3, 1);
    g_m.v[4].zq = (int64_t)z3[2] + z3[6];
    add_tri(&g_m, 4, 0, 6);       /* (1,1),(0,0),(0,2) */
    add_tri(&g_m, 4, 2, 0);       /* (1,1),(2,0),(0,0) */
    add_tri(&g_m, 4, 6, 8);       /* (1,1),(0,2),(2,2) */
    add_tri(&g_m, 4, 8, 2);       /* (1,1),(2,2),(2,0) */
    mm = as_mesh(&g_m, 1);
    CHECK_EQ(mc_check(&mm, 3, 3, z3, NULL, &r), 1);
    if (!r.ok) mc_report_print(stderr, &r);
    CHECK_EQ(r.tjunctions, 0);
    CHECK_EQ(r.orientation, -1);
    ref = ref_max_error(&g_m, 3, z3, 1);
    CHECK_MSG(fabs(rep_err(&r) - ref) < 1e-9, "%g vs ref %g", rep_err(&r), ref);
    CHECK(ref > 0.4);
    /* a rounded fictitious height is a different (integer) plane: the referee
     * sees the difference exactly */
    g_m.v[4].zq = ((int64_t)z3[2] + z3[6]) / 2 * 2;
    CHECK_EQ(mc_check(&mm, 3, 3, z3, NULL, &r), 1);
    CHECK(fabs(rep_err(&r) - ref_max_error(&g_m, 3, z3, 1)) < 1e-9);
}

static void test_hole_is_caught(void)
{
    mc_mesh mm;
    mc_report r;
    verts_all(&g_m, 9, g_crop9, 0);
    blocks_uniform(&g_m, 9, 1);
    /* drop one interior triangle: every sample is still a vertex of something */
    g_m.t[3 * 40] = g_m.t[3 * (g_m.nt - 1)];
    g_m.t[3 * 40 + 1] = g_m.t[3 * (g_m.nt - 1) + 1];
    g_m.t[3 * 40 + 2] = g_m.t[3 * (g_m.nt - 1) + 2];
    g_m.nt--;
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 0);
    CHECK_EQ(r.bad_boundary_edges, 3);
    CHECK_EQ(r.area2, 2 * 64 - 1);
    CHECK_EQ(r.uncovered, 0);
}

static void test_crack_split_vertex_is_caught(void)
{
    /* the right half uses its own copy of column 4 one unit higher: no 2D hole,
     * but a 3D crack along x = 4 */
    mc_mesh mm;
    mc_report r;
    int64_t t;
    int y, k;
    verts_all(&g_m, 9, g_crop9, 0);
    blocks_uniform(&g_m, 9, 1);
    for (y = 0; y < 9; y++) {
        g_m.v[81 + y] = g_m.v[y * 9 + 4];
        g_m.v[81 + y].zq += 1;
    }
    g_m.nv = 81 + 9;
    for (t = 0; t < g_m.nt; t++) {
        int32_t xs = 99;
        for (k = 0; k < 3; k++) if (g_m.v[g_m.t[3 * t + k]].x < xs) xs = g_m.v[g_m.t[3 * t + k]].x;
        if (xs == 4)   /* triangles right of the seam */
            for (k = 0; k < 3; k++)
                if (g_m.v[g_m.t[3 * t + k]].x == 4) g_m.t[3 * t + k] = 81 + g_m.v[g_m.t[3 * t + k]].y;
    }
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 0);
    CHECK_EQ(r.split_vertex, 9);
    CHECK_EQ(r.bad_boundary_edges, 0);
    CHECK_EQ(r.tjunctions, 0);
}

static void test_tjunction_is_caught(void)
{
    /* a 4x4 block beside 1x1 blocks: the fine vertices on its right and bottom
     * edges are T-junctions (3 each), and its two long edges are unmatched */
    mc_mesh mm;
    mc_report r;
    int x, y;
    verts_all(&g_m, 9, g_crop9, 0);
    add_block(&g_m, 9, 0, 0, 4);
    for (y = 0; y < 8; y++)
        for (x = 0; x < 8; x++)
            if (x >= 4 || y >= 4) add_block(&g_m, 9, x, y, 1);
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 0);
    CHECK_EQ(r.tjunctions, 6);
    CHECK_EQ(r.area2, 128);
    CHECK_EQ(r.overlap_samples, 0);
    CHECK_EQ(r.uncovered, 0);
    CHECK(r.bad_boundary_edges >= 2);
}

static void test_overlap_is_caught(void)
{
    mc_mesh mm;
    mc_report r;
    verts_all(&g_m, 9, g_crop9, 0);
    blocks_uniform(&g_m, 9, 1);
    add_tri(&g_m, 4 * 9 + 0, 4 * 9 + 4, 0 * 9 + 4);   /* (0,4),(4,4),(4,0): same orientation */
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 0);
    CHECK_EQ(r.overlap_samples, 3);         /* (3,2), (2,3), (3,3) */
    CHECK_EQ(r.tjunctions, 9);              /* 3 grid vertices inside each of its edges */
    CHECK_EQ(r.area2, 128 + 16);
    CHECK_EQ(r.flipped, 0);
    /* an exact duplicate triangle: no interior sample, but an edge walked thrice
     * or twice the same way */
    verts_all(&g_m, 9, g_crop9, 0);
    blocks_uniform(&g_m, 9, 1);
    add_tri(&g_m, g_m.t[30], g_m.t[31], g_m.t[32]);
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 0);
    CHECK(r.nonmanifold_edges + r.same_dir_edges >= 1);
}

static void test_flipped_is_caught(void)
{
    mc_mesh mm;
    mc_report r;
    int32_t tmp;
    verts_all(&g_m, 17, g_crop17, 0);
    blocks_uniform(&g_m, 17, 2);
    tmp = g_m.t[3 * 7 + 1]; g_m.t[3 * 7 + 1] = g_m.t[3 * 7 + 2]; g_m.t[3 * 7 + 2] = tmp;
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 17, 17, g_crop17, NULL, &r), 0);
    CHECK_EQ(r.flipped, 1);
    CHECK_EQ(r.orientation, -1);
    CHECK(r.same_dir_edges >= 1);
}

static void test_degenerate_and_bad_index(void)
{
    mc_mesh mm;
    mc_report r;
    verts_all(&g_m, 9, g_crop9, 0);
    blocks_uniform(&g_m, 9, 1);
    add_tri(&g_m, 0, 1, 2);          /* collinear along row 0 */
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 0);
    CHECK_EQ(r.degenerate, 1);
    g_m.t[3 * (g_m.nt - 1)] = 81;    /* out of range */
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 0);
    CHECK_EQ(r.bad_vertex, 1);
}

static void test_void(void)
{
    /* one void sample in the 9x9 crop: the 8 half-cells around it are dropped;
     * the hole's border is legal, covering the void is not */
    static int32_t zv[81];
    mc_mesh mm;
    mc_report r;
    int x, y;
    memcpy(zv, g_crop9, sizeof zv);
    zv[4 * 9 + 4] = MC_VOID;
    verts_all(&g_m, 9, zv, 0);
    for (y = 0; y < 8; y++)
        for (x = 0; x < 8; x++)
            if (!((x == 3 || x == 4) && (y == 3 || y == 4))) add_block(&g_m, 9, x, y, 1);
    /* of the 4 cells around the void, each keeps the half not touching it */
    add_tri(&g_m, 3 * 9 + 3, 4 * 9 + 3, 3 * 9 + 4);  /* cell (3,3): A,B,C (D is the void) */
    add_tri(&g_m, 4 * 9 + 5, 5 * 9 + 4, 5 * 9 + 5);  /* cell (4,4): C,B,D (A is the void) */
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, zv, NULL, &r), 1);
    if (!r.ok) mc_report_print(stderr, &r);
    CHECK_EQ(r.voids, 1);
    CHECK_EQ(r.area2, 128 - 6);
    CHECK_EQ(r.area2_max, 128 - 4);
    CHECK_EQ(r.bad_boundary_edges, 0);
    /* expecting the full-possible area flags the missing halves */
    {
        mc_opts o = { 124, 0, 0, 0, 0 };
        CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 0);
    }
    /* a triangle over the void */
    add_tri(&g_m, 3 * 9 + 4, 4 * 9 + 3, 4 * 9 + 5);
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, zv, NULL, &r), 0);
    CHECK(r.bad_vertex == 1 || r.void_covered >= 1);
    /* a hole far from the void is still a crack */
    g_m.nt--;
    g_m.t[0] = g_m.t[3 * (g_m.nt - 1)]; g_m.t[1] = g_m.t[3 * (g_m.nt - 1) + 1];
    g_m.t[2] = g_m.t[3 * (g_m.nt - 1) + 2];
    g_m.nt--;
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, zv, NULL, &r), 0);
    /* removed: triangle 0, cell (0,0)'s upper half: two border edges and one
     * interior edge, which is a crack */
    CHECK_EQ(r.bad_boundary_edges, 1);
    CHECK_EQ(r.uncovered, 1);          /* (0,0) was only in that triangle */
    CHECK_EQ(r.uncovered_far, 1);
    {
        mc_opts o = { 0, 1, 0, 0, 0 }; /* allowing uncovered samples does not excuse this one */
        CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 0);
        CHECK_EQ(r.uncovered_far, 1);
    }
}

/* opts.void_reach: a mesher that counts a void's extent as error (core/bt_err.c
 * "Voids") may draw over a void, or widen its hole, by at most the reach. */
static void test_void_reach(void)
{
    static int32_t zv[9 * 9];
    mc_mesh mm;
    mc_report r;
    mc_opts o;
    int x, y;
    memcpy(zv, g_crop9, sizeof zv);
    zv[3 * 9 + 3] = MC_VOID;
    memset(&o, 0, sizeof o);
    verts_all(&g_m, 9, zv, 0);
    blocks_uniform(&g_m, 9, 2);          /* block (2,2)'s two triangles hold (3,3) */
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 0);
    CHECK(r.void_covered >= 1);
    o.void_reach = 2;
    CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 1);
    CHECK_EQ(r.void_covered, 0);
    CHECK(r.void_covered_near >= 1);
    o.void_reach = 1;                    /* the blocks are 2 wide */
    CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 0);
    CHECK(r.void_covered >= 1);
    /* the hole widened: blocks (2,2) and (4,2) left out; (5,3) is 2 from the void,
     * the edge x = 6 is 3 from it */
    verts_all(&g_m, 9, zv, 0);
    for (y = 0; y < 8; y += 2)
        for (x = 0; x < 8; x += 2)
            if (!(y == 2 && (x == 2 || x == 4))) add_block(&g_m, 9, x, y, 2);
    mm = as_mesh(&g_m, 0);
    o.void_reach = 0;
    CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 0);
    CHECK(r.uncovered_far >= 1 && r.bad_boundary_edges >= 1);
    o.void_reach = 1;
    CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 0);
    CHECK_EQ(r.uncovered_far, 1);        /* (5,3) */
    o.void_reach = 2;
    CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 0);
    CHECK_EQ(r.uncovered_far, 0);
    CHECK_EQ(r.bad_boundary_edges, 1);
    o.void_reach = 3;
    CHECK_EQ(mc_check(&mm, 9, 9, zv, &o, &r), 1);
    if (!r.ok) mc_report_print(stderr, &r);
    CHECK_EQ(r.uncovered_far, 0);
    CHECK_EQ(r.bad_boundary_edges, 0);
}

/* A frustum-culled mesh covers part of the grid on purpose: with opts.partial
 * its holes are not errors, but a T-junction or an overlap still is. */
static void test_partial(void)
{
    mc_mesh mm;
    mc_report r;
    mc_opts o;
    int x, y;
    memset(&o, 0, sizeof o);
    o.partial = 1;
    verts_all(&g_m, 17, g_crop17, 0);
    for (y = 0; y < 16; y += 2)
        for (x = 0; x < 16; x += 2)
            if (x + y < 16) add_block(&g_m, 17, x, y, 2);      /* the north-west half */
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 17, 17, g_crop17, NULL, &r), 0);
    CHECK(r.bad_boundary_edges > 0 && r.uncovered > 0);
    CHECK_EQ(mc_check(&mm, 17, 17, g_crop17, &o, &r), 1);
    CHECK_EQ(r.tjunctions, 0);
    /* the 2-block at (0,0) (triangles 0, 1) refined into 1-blocks beside unrefined
     * neighbours: (2,1) and (1,2) are T-junctions */
    memcpy(g_m.t, g_m.t + 3 * (g_m.nt - 2), 6 * sizeof g_m.t[0]);
    g_m.nt -= 2;
    add_block(&g_m, 17, 0, 0, 1); add_block(&g_m, 17, 1, 0, 1);
    add_block(&g_m, 17, 0, 1, 1); add_block(&g_m, 17, 1, 1, 1);
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 17, 17, g_crop17, &o, &r), 0);
    CHECK_EQ(r.tjunctions, 2);
    CHECK_EQ(r.overlap_samples, 0);
    /* an overlapping extra triangle */
    verts_all(&g_m, 17, g_crop17, 0);
    for (y = 0; y < 16; y += 2)
        for (x = 0; x < 16; x += 2)
            if (x + y < 16) add_block(&g_m, 17, x, y, 2);
    add_tri(&g_m, 0, 4 * 17, 4);
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 17, 17, g_crop17, &o, &r), 0);
    CHECK(r.overlap_samples > 0);
}

static void test_uncovered_beside_void(void)
{
    /* 3x3 corner of the crop with its centre void: no cell has 4 valid corners;
     * an empty mesh leaves 8 valid samples uncovered, all beside the void */
    static int32_t z3[9];
    mc_mesh mm;
    mc_report r;
    mc_opts o = { 0, 1, 0, 0, 0 };
    int x, y;
    for (y = 0; y < 3; y++) for (x = 0; x < 3; x++) z3[y * 3 + x] = g_crop9[y * 9 + x];
    z3[4] = MC_VOID;
    verts_all(&g_m, 3, z3, 0);
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 3, 3, z3, NULL, &r), 0);
    CHECK_EQ(r.uncovered, 8);
    CHECK_EQ(r.uncovered_far, 0);
    CHECK_EQ(r.area2_max, 4);
    CHECK_EQ(mc_check(&mm, 3, 3, z3, &o, &r), 1);
    /* one legal half cell: (0,0),(0,1),(1,0) */
    add_tri(&g_m, 0, 3, 1);
    mm = as_mesh(&g_m, 0);
    CHECK_EQ(mc_check(&mm, 3, 3, z3, &o, &r), 1);
    CHECK_EQ(r.uncovered, 5);
    CHECK_EQ(r.bad_boundary_edges, 0);
    CHECK_EQ(r.area2, 1);
}

/* Row strip with joins: rows of cells, the strip alternates top and bottom
 * vertices; rows are joined by repeating the last and the first index. */
static int64_t build_grid_strip(int n, int32_t *s)
{
    int64_t k = 0;
    int x, y;
    for (y = 0; y + 1 < n; y++) {
        if (y > 0) { s[k] = s[k - 1]; k++; s[k++] = y * n; }
        for (x = 0; x < n; x++) { s[k++] = y * n + x; s[k++] = (y + 1) * n + x; }
    }
    return k;
}

static void test_strip(void)
{
    static int32_t s[4096], tri[3 * 4096], line[3 * 4096];
    mc_strip_report sr;
    int64_t n, nt, nl;
    mc_mesh mm;
    mc_report r;
    verts_all(&g_m, 9, g_crop9, 0);
    blocks_uniform(&g_m, 9, 1);
    n = build_grid_strip(9, s);
    CHECK_EQ(n, 8 * 18 + 7 * 2);
    CHECK_EQ(mc_strip_decode(s, n, g_m.v, g_m.nv, tri, &nt, line, &nl), 0);
    CHECK_EQ(nt, 128);
    CHECK_EQ(nl, 7 * 4);
    CHECK_EQ(nt + nl, n - 2);
    /* decoded triangles form a valid mesh with orientation -1 */
    mm.v = g_m.v; mm.nv = g_m.nv; mm.tri = tri; mm.nt = nt; mm.zbits = 0;
    CHECK_EQ(mc_check(&mm, 9, 9, g_crop9, NULL, &r), 1);
    CHECK_EQ(r.orientation, -1);
    CHECK_EQ(mc_strip_compare(s, n, g_m.t, g_m.nt, g_m.v, g_m.nv, &sr), 1);
    CHECK_EQ(sr.decoded, 128);
    CHECK_EQ(sr.line, 28);
    CHECK_EQ(sr.orientation, -1);
    /* the list with one triangle reversed: winding differs */
    {
        int32_t tmp = g_m.t[4]; g_m.t[4] = g_m.t[5]; g_m.t[5] = tmp;
        CHECK_EQ(mc_strip_compare(s, n, g_m.t, g_m.nt, g_m.v, g_m.nv, &sr), 0);
        CHECK_EQ(sr.winding_vs_list, 1);
        CHECK_EQ(sr.missing + sr.extra, 0);
        tmp = g_m.t[4]; g_m.t[4] = g_m.t[5]; g_m.t[5] = tmp;
    }
    /* a strip missing its first index: parity shifts, every triangle flips */
    CHECK_EQ(mc_strip_compare(s + 1, n - 1, g_m.t, g_m.nt, g_m.v, g_m.nv, &sr), 0);
    CHECK(sr.missing >= 1);
    /* a swapped pair in the middle: wrong triangles appear */
    {
        int32_t tmp = s[40]; s[40] = s[41]; s[41] = tmp;
        CHECK_EQ(mc_strip_compare(s, n, g_m.t, g_m.nt, g_m.v, g_m.nv, &sr), 0);
        CHECK(sr.extra >= 1 && sr.missing >= 1);
        tmp = s[40]; s[40] = s[41]; s[41] = tmp;
    }
    /* collinear distinct points are line triangles too (002's figure 10: "bcb") */
    {
        int32_t s2[4] = { 9, 0, 1, 2 };   /* (0,1),(0,0),(1,0),(2,0) */
        CHECK_EQ(mc_strip_decode(s2, 4, g_m.v, g_m.nv, tri, &nt, line, &nl), 0);
        CHECK_EQ(nt, 1);   /* (0,1),(0,0),(1,0) */
        CHECK_EQ(nl, 1);   /* k = 1: (1,0),(0,0),(2,0), collinear */
        CHECK_EQ(line[0], 1);
        CHECK_EQ(line[1], 0);
        CHECK_EQ(line[2], 2);
    }
    /* far-apart and negative positions (the sort falls back to qsort) */
    {
        static const mc_vert fv[4] = { { -100000, -5, 0 }, { 100000, -5, 0 }, { -100000, 90000, 0 }, { 100000, 90000, 0 } };
        int32_t s4[4] = { 0, 2, 1, 3 }, t4[6] = { 0, 2, 1, 1, 2, 3 };
        mc_strip_report fr;
        CHECK_EQ(mc_strip_compare(s4, 4, t4, 2, fv, 4, &fr), 1);
        CHECK_EQ(fr.decoded, 2);
        t4[5] = 0;
        CHECK_EQ(mc_strip_compare(s4, 4, t4, 2, fv, 4, &fr), 0);
        CHECK_EQ(fr.missing, 1);
        CHECK_EQ(fr.extra, 1);
    }
    /* a bad index */
    {
        int32_t s3[3] = { 0, 1, 81 };
        CHECK_EQ(mc_strip_decode(s3, 3, g_m.v, g_m.nv, tri, &nt, line, &nl), -1);
    }
}

/* Every grid sample as a vertex. */
static mc_vert *grid_verts(int32_t size, const int32_t *z)
{
    mc_vert *v = malloc((size_t)size * (size_t)size * sizeof *v);
    int64_t i;
    for (i = 0; v && i < (int64_t)size * size; i++) {
        v[i].x = (int32_t)(i % size); v[i].y = (int32_t)(i / size); v[i].zq = z[i];
    }
    return v;
}

static int32_t *martini_tris(const mr_mesh *m, int32_t size)
{
    int32_t *t = malloc((size_t)(3 * m->nt + 1) * sizeof *t);
    int64_t i;
    for (i = 0; t && i < 3 * m->nt; i++)
        t[i] = (int32_t)m->vert[2 * m->tri[i] + 1] * size + m->vert[2 * m->tri[i]];
    return t;
}

/* martini on fuji.png (513x513 padded) at 10 m: the C port gives the npm
 * package's mesh (89,513 triangles, measured with benchmarks/martini_npm.sh), which
 * the referee finds watertight and 17.0125 m off (1.7x the request); the sound
 * bound holds 10 m. */
static void test_martini_fuji(void)
{
    hf f;
    br_err err;
    int32_t size = 513, x, y, *z, *tri;
    float *terrain, *errors;
    uint32_t *e2;
    mr_grid g;
    mr_mesh m;
    mc_mesh mm;
    mc_report r;
    mc_vert *v;
    memset(&f, 0, sizeof f);
    CHECK_EQ(dem_load(t_data("png/fuji.png"), NULL, &f, &err), BR_OK);
    if (!f.z) return;
    CHECK_EQ(f.z_den, 10);
    z = malloc((size_t)size * size * sizeof *z);
    terrain = malloc((size_t)size * size * sizeof *terrain);
    errors = malloc((size_t)size * size * sizeof *errors);
    e2 = malloc((size_t)size * size * sizeof *e2);
    for (y = 0; y < size; y++)
        for (x = 0; x < size; x++)
            z[y * size + x] = f.z[(y < f.h ? y : f.h - 1) * f.w + (x < f.w ? x : f.w - 1)];
    for (x = 0; x < size * size; x++) terrain[x] = mr_terrain_rgb_f32(z[x] + 100000);
    v = grid_verts(size, z);
    CHECK_EQ(mr_grid_init(&g, size), 0);
    CHECK_EQ(mr_mesh_alloc(&g, &m), 0);
    mr_errors_f32(&g, terrain, errors);
    mr_mesh_f32(&g, errors, 10.0, &m);
    CHECK_EQ(m.nt, 89513);
    CHECK_EQ(m.nv, 45119);
    tri = martini_tris(&m, size);
    mm.v = v; mm.nv = size * size; mm.tri = tri; mm.nt = m.nt; mm.zbits = 0;
    CHECK_EQ(mc_check(&mm, size, size, z, NULL, &r), 1);
    CHECK_EQ(r.orientation, -1);
    CHECK_EQ(r.tjunctions, 0);
    CHECK_EQ(r.err_num, 1361);           /* 170.125 dm */
    CHECK_EQ(r.err_den, 8);
    CHECK_EQ(r.err_x, 226);
    CHECK_EQ(r.err_y, 21);
    CHECK_EQ(mc_err_exceeds(&r, 100, 1), 1);
    free(tri);
    /* 500 m: the mesh of martini's own test (46 vertices) */
    mr_mesh_f32(&g, errors, 500.0, &m);
    CHECK_EQ(m.nv, 46);
    CHECK_EQ(m.nt, 75);
    /* the sound bound, integer decimetres doubled: 10 m = 200 */
    mr_errors_int(&g, z, e2, 1);
    mr_mesh_int(&g, e2, 200, &m);
    tri = martini_tris(&m, size);
    mm.tri = tri; mm.nt = m.nt;
    CHECK_EQ(mc_check(&mm, size, size, z, NULL, &r), 1);
    CHECK_EQ(mc_err_exceeds(&r, 100, 1), 0);
    CHECK(m.nt > 89513);
    free(tri);
    /* the tighter per-triangle bound with martini's closure: still sound, still crack-free */
    {
        uint32_t *tb = malloc((size_t)g.ntri * sizeof *tb);
        mr_errors_tight(&g, z, tb, e2);
        mr_mesh_int(&g, e2, 200, &m);
        CHECK_EQ(m.nt, 148560);
        tri = martini_tris(&m, size);
        mm.tri = tri; mm.nt = m.nt;
        CHECK_EQ(mc_check(&mm, size, size, z, NULL, &r), 1);
        CHECK_EQ(mc_err_exceeds(&r, 100, 1), 0);
        free(tri); free(tb);
    }
    mr_mesh_free(&m);
    mr_grid_free(&g);
    free(v); free(z); free(terrain); free(errors); free(e2);
    dem_free(&f);
}

/* The restricted quadtree is watertight and its strip decodes to it; 002's
 * bitree rules leave T-junctions (fictitious points on an unsplit neighbour's
 * edge), which the referee reports. */
static void test_rqt(void)
{
    static int32_t z[65 * 65], qt[3 * 8192], qs[8 * 8192], bt[3 * 8192], bs[8 * 8192];
    FILE *fp = fopen(t_data("hgt/N47E009.hgt"), "rb");
    rq_mesh qm, bm;
    rq_result res;
    mc_report r;
    mc_strip_report sr;
    mc_mesh mm;
    mc_vert *v;
    int x, y;
    int32_t zmin = INT32_MAX, zmax = INT32_MIN;
    CHECK(fp != NULL);
    if (!fp) return;
    for (y = 0; y < 65; y++) {   /* column 176, row 1040: valley floor and peaks */
        unsigned char row[130];
        CHECK(fseek(fp, ((long)(1040 + y) * 1201 + 176) * 2, SEEK_SET) == 0 && fread(row, 2, 65, fp) == 65);
        for (x = 0; x < 65; x++) {
            z[y * 65 + x] = (int16_t)(uint16_t)((row[2 * x] << 8) | row[2 * x + 1]);
            if (z[y * 65 + x] < zmin) zmin = z[y * 65 + x];
            if (z[y * 65 + x] > zmax) zmax = z[y * 65 + x];
        }
    }
    fclose(fp);
    v = grid_verts(65, z);
    qm.tri = qt; qm.strip = qs; bm.tri = bt; bm.strip = bs;
    /* full grid: 8192 triangles; the DP strip needs 12290 references */
    CHECK_EQ(rq_run(z, 65, -1, 100, RQ_SEL_EACH, &res, &qm, &bm), 0);
    CHECK_EQ(res.qt.triangles, 8192);
    CHECK_EQ(res.qt.refs, 12290);
    CHECK_EQ(mc_strip_compare(qs, qm.ns, qt, qm.nt, v, 65 * 65, &sr), 1);
    /* 2% of the range */
    CHECK_EQ(rq_run(z, 65, 2LL * (zmax - zmin), 100, RQ_SEL_EACH, &res, &qm, &bm), 0);
    CHECK(res.qt.added > res.bt.added);
    CHECK(res.qt.triangles > res.bt.triangles);
    CHECK_EQ(res.qt.triangles, qm.nt);
    mm.v = v; mm.nv = 65 * 65; mm.tri = qt; mm.nt = qm.nt; mm.zbits = 0;
    CHECK_EQ(mc_check(&mm, 65, 65, z, NULL, &r), 1);
    if (!r.ok) mc_report_print(stderr, &r);
    CHECK_EQ(mc_strip_compare(qs, qm.ns, qt, qm.nt, v, 65 * 65, &sr), 1);
    CHECK_EQ(sr.line, res.qt.line);
    mm.tri = bt; mm.nt = bm.nt;
    CHECK_EQ(mc_check(&mm, 65, 65, z, NULL, &r), 0);
    CHECK(r.tjunctions > 0);
    CHECK_EQ(r.overlap_samples + r.flipped + r.uncovered, 0);
    CHECK_EQ(r.area2, 2 * 64 * 64);
    CHECK_EQ(mc_strip_compare(bs, bm.ns, bt, bm.nt, v, 65 * 65, &sr), 1);
    free(v);
}

int main(void)
{
    g_have = read_crop(9, g_crop9) && read_crop(17, g_crop17);
    T_RUN(test_data);
    if (!g_have) return t_finish();
    T_RUN(test_full_resolution_is_exact);
    T_RUN(test_coarse_error_matches_reference);
    T_RUN(test_wrong_height_is_caught);
    T_RUN(test_fictitious_half_height);
    T_RUN(test_hole_is_caught);
    T_RUN(test_crack_split_vertex_is_caught);
    T_RUN(test_tjunction_is_caught);
    T_RUN(test_overlap_is_caught);
    T_RUN(test_flipped_is_caught);
    T_RUN(test_degenerate_and_bad_index);
    T_RUN(test_void);
    T_RUN(test_uncovered_beside_void);
    T_RUN(test_partial);
    T_RUN(test_void_reach);
    T_RUN(test_strip);
    T_RUN(test_martini_fuji);
    T_RUN(test_rqt);
    return t_finish();
}
