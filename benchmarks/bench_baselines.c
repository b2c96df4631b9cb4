/* benchmarks/bench_baselines.c — the baselines the bitree is measured against
 * (issue 3), judged by the independent referee tests/support/meshcheck.h.
 *
 * 1. @mapbox/martini ported to C (benchmarks/martini_ref.h) on fuji.png padded to
 *    513x513 (last row and column repeated, as martini's test does):
 *    metric build times (median of 11), extraction at 10 m (median of 11),
 *    triangles and the TRUE max error of martini's metric and of the sound bound
 *    e_m + max(child bounds); the triangles martini's metric needs before its
 *    mesh really holds 10 m (bisection on its threshold); the port's triangle
 *    counts at a few thresholds, in the same format as benchmarks/martini_npm.
 * 2. Table 1 of papers/002 on real 65x65 crops: restricted quadtree (QT) and
 *    002's bitree rules (BT-002) from benchmarks/rqt_ref.h, beside the published
 *    numbers.
 *
 * Run: make B=build bench   or   build/bench/bench_baselines [--quick]
 * (from the repository root; data from ../shared/data/dem or $BITRAIN_DATA). */
#define _POSIX_C_SOURCE 200809L   /* clock_gettime under -std=c99 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "platform/load.h"
#include "tests/support/meshcheck.h"
#include "tests/support/timing.h"
#include "tests/test.h"
#include "benchmarks/martini_ref.c"
#include "benchmarks/rqt_ref.c"
#include "benchmarks/table1.h"


/* ---- meshcheck glue -------------------------------------------------------- */

static mc_vert *g_verts;     /* every grid sample as a vertex, index y*size + x */

static void grid_verts(int32_t size, const int32_t *z)
{
    int64_t i, n = (int64_t)size * size;
    free(g_verts);
    g_verts = malloc((size_t)n * sizeof *g_verts);
    for (i = 0; i < n; i++) {
        g_verts[i].x = (int32_t)(i % size);
        g_verts[i].y = (int32_t)(i / size);
        g_verts[i].zq = z[i];
    }
}

/* martini output (compact vertices) -> grid-index triangles */
static int32_t *martini_tris(const mr_mesh *m, int32_t size)
{
    int32_t *t = malloc((size_t)(3 * m->nt + 1) * sizeof *t);
    int64_t i;
    for (i = 0; i < 3 * m->nt; i++) {
        uint32_t v = m->tri[i];
        t[i] = (int32_t)m->vert[2 * v + 1] * size + m->vert[2 * v];
    }
    return t;
}

static void judge(const int32_t *tri, int64_t nt, int32_t size, const int32_t *z, mc_report *r)
{
    mc_mesh mm;
    mm.v = g_verts; mm.nv = size * size; mm.tri = tri; mm.nt = nt; mm.zbits = 0;
    if (mc_check(&mm, size, size, z, NULL, r) < 0) { fprintf(stderr, "meshcheck: out of memory\n"); exit(1); }
}

/* ---- part 1: martini on fuji ------------------------------------------------ */

static void martini_part(int quick)
{
    hf f;
    br_err err;
    int32_t size = 513, x, y, *z;
    float *terrain, *errors;
    uint32_t *e_mar, *e_snd;
    mr_grid g;
    mr_mesh m;
    mc_report r;
    double t[31], t2[31], t3[31], t_f32, t_int, t_snd, t_mesh;
    int i, runs = quick ? 3 : 31;
    int32_t *tri;
    static const double thr[] = { 500, 50, 20, 10, 5, 1, 0 };
    memset(&f, 0, sizeof f);
    if (dem_load(t_data("png/fuji.png"), NULL, &f, &err) != BR_OK) {
        printf("martini: skipped: %s\n", err.msg);
        return;
    }
    z = malloc((size_t)size * size * sizeof *z);
    for (y = 0; y < size; y++)
        for (x = 0; x < size; x++) {
            int32_t sx = x < f.w ? x : f.w - 1, sy = y < f.h ? y : f.h - 1;
            z[y * size + x] = f.z[sy * f.w + sx];
        }
    terrain = malloc((size_t)size * size * sizeof *terrain);
    errors = malloc((size_t)size * size * sizeof *errors);
    e_mar = malloc((size_t)size * size * sizeof *e_mar);
    e_snd = malloc((size_t)size * size * sizeof *e_snd);
    for (i = 0; i < size * size; i++) terrain[i] = mr_terrain_rgb_f32(z[i] + 100000);
    grid_verts(size, z);
    if (mr_grid_init(&g, size) != 0 || mr_mesh_alloc(&g, &m) != 0) { printf("martini: no memory\n"); return; }

    printf("martini (C port of @mapbox/martini 0.2.0) on fuji.png padded to 513x513, heights in dm\n");
    /* interleaved, so a busy neighbour on this shared machine slows all three alike */
    for (i = 0; i < runs; i++) {
        double t0 = tm_now_ms();
        mr_errors_f32(&g, terrain, errors);
        t[i] = tm_now_ms() - t0;
        t0 = tm_now_ms();
        mr_errors_int(&g, z, e_mar, 0);
        t2[i] = tm_now_ms() - t0;
        t0 = tm_now_ms();
        mr_errors_int(&g, z, e_snd, 1);
        t3[i] = tm_now_ms() - t0;
    }
    t_f32 = tm_median(t, runs);
    t_int = tm_median(t2, runs);
    t_snd = tm_median(t3, runs);
    printf("  metric build, median of %d: martini f32 %.3f ms | martini int %.3f ms | sound bound int %.3f ms\n",
           runs, t_f32, t_int, t_snd);

    /* extraction at 10 m and the truth about each mesh */
    for (i = 0; i < runs; i++) { double t0 = tm_now_ms(); mr_mesh_f32(&g, errors, 10.0, &m); t[i] = tm_now_ms() - t0; }
    t_mesh = tm_median(t, runs);
    tri = martini_tris(&m, size);
    judge(tri, m.nt, size, z, &r);
    printf("  martini metric (f32) at 10 m: %lld triangles, %lld vertices, extraction %.3f ms (%.1f M triangles/s),"
           " TRUE max error %.4f m at (%d,%d) = %.2fx the request, watertight %s\n",
           (long long)m.nt, (long long)m.nv, t_mesh, (double)m.nt / t_mesh / 1e3,
           (double)r.err_num / (double)r.err_den / 10.0, r.err_x, r.err_y,
           (double)r.err_num / (double)r.err_den / 100.0, r.ok ? "yes" : "NO");
    if (!r.ok) mc_report_print(stdout, &r);
    free(tri);
    for (i = 0; i < runs; i++) { double t0 = tm_now_ms(); mr_mesh_int(&g, e_mar, 200, &m); t[i] = tm_now_ms() - t0; }
    t_mesh = tm_median(t, runs);
    tri = martini_tris(&m, size);
    judge(tri, m.nt, size, z, &r);
    printf("  martini metric (int, doubled dm) at 10 m: %lld triangles, extraction %.3f ms, TRUE max error %.4f m, watertight %s\n",
           (long long)m.nt, t_mesh, (double)r.err_num / (double)r.err_den / 10.0, r.ok ? "yes" : "NO");
    free(tri);
    for (i = 0; i < runs; i++) { double t0 = tm_now_ms(); mr_mesh_int(&g, e_snd, 200, &m); t[i] = tm_now_ms() - t0; }
    t_mesh = tm_median(t, runs);
    tri = martini_tris(&m, size);
    judge(tri, m.nt, size, z, &r);
    printf("  sound bound e_m + max(child) at 10 m: %lld triangles, extraction %.3f ms (%.1f M triangles/s), TRUE max error %.4f m (<= 10: %s), watertight %s\n",
           (long long)m.nt, t_mesh, (double)m.nt / t_mesh / 1e3, (double)r.err_num / (double)r.err_den / 10.0,
           mc_err_exceeds(&r, 100, 1) ? "NO" : "yes", r.ok ? "yes" : "NO");
    free(tri);

    {   /* per-triangle sound bounds + martini's closure */
        uint32_t *tb = malloc((size_t)g.ntri * sizeof *tb), *e_t = malloc((size_t)size * size * sizeof *e_t);
        double tt = 0;
        for (i = 0; i < runs; i++) {
            double t0 = tm_now_ms();
            mr_errors_tight(&g, z, tb, e_t);
            t[i] = tm_now_ms() - t0;
            t0 = tm_now_ms();
            mr_errors_f32(&g, terrain, errors);     /* interleaved reference */
            t2[i] = tm_now_ms() - t0;
        }
        tt = tm_median(t, runs);
        mr_mesh_int(&g, e_t, 200, &m);
        tri = martini_tris(&m, size);
        judge(tri, m.nt, size, z, &r);
        printf("  per-triangle sound bound + martini closure (mr_errors_tight) at 10 m: %lld triangles, build %.3f ms"
               " (martini f32 %.3f ms in the same loop), TRUE max error %.4f m (<= 10: %s), watertight %s\n",
               (long long)m.nt, tt, tm_median(t2, runs), (double)r.err_num / (double)r.err_den / 10.0,
               mc_err_exceeds(&r, 100, 1) ? "NO" : "yes", r.ok ? "yes" : "NO");
        free(tri); free(tb); free(e_t);
    }
    /* How far must martini's threshold drop before its mesh really holds 10 m?
     * Heights are decimetres, so every midpoint error is a multiple of 0.05 m (up
     * to float32 rounding) and the mesh only changes there: try the thresholds
     * 9.975, 9.925, ... (half-way between) downwards and stop at the first mesh
     * whose TRUE error is <= 10 m.  (The true error is not monotone in the
     * threshold, so this is the largest such threshold, not a bisection guess.) */
    {
        int k;
        for (k = 199; k >= 0; k--) {
            double th = (double)k * 0.05 + 0.025;
            mc_mesh mm;
            mr_mesh_f32(&g, errors, th, &m);
            tri = martini_tris(&m, size);
            mm.v = g_verts; mm.nv = size * size; mm.tri = tri; mm.nt = m.nt; mm.zbits = 0;
            mc_max_error(&mm, size, size, z, &r);
            free(tri);
            if (!mc_err_exceeds(&r, 100, 1)) {
                printf("  martini metric needs threshold %.3f m -> %lld triangles before its TRUE max error is <= 10 m"
                       " (%.4f m)\n", th, (long long)m.nt, (double)r.err_num / (double)r.err_den / 10.0);
                break;
            }
        }
    }
    /* the exact per-triangle metric with martini's conforming closure: the
     * restricted quadtree of rqt_ref with every triangle judged on its own */
    {
        rq_result rr;
        rq_mesh qm;
        double t0;
        mc_strip_report sr;
        qm.tri = malloc((size_t)6 * 512 * 512 * sizeof *qm.tri);
        qm.strip = malloc((size_t)16 * 512 * 512 * sizeof *qm.strip);
        t0 = tm_now_ms();
        if (qm.tri && qm.strip && rq_run(z, size, 100, 1, RQ_SEL_EACH, &rr, &qm, NULL) == 0) {
            double dt = tm_now_ms() - t0;
            judge(qm.tri, qm.nt, size, z, &r);
            mc_strip_compare(qm.strip, qm.ns, qm.tri, qm.nt, g_verts, size * size, &sr);
            printf("  exact per-triangle error + conforming closure (rqt_ref RQ_SEL_EACH QT) at 10 m: %lld triangles,"
                   " TRUE max error %.4f m, watertight %s, strip %lld refs (%.3f per triangle, decodes %s); %.0f ms unoptimised\n",
                   (long long)qm.nt, (double)r.err_num / (double)r.err_den / 10.0, r.ok ? "yes" : "NO",
                   (long long)qm.ns, (double)qm.ns / (double)qm.nt, sr.ok ? "ok" : "BAD", dt);
        }
        free(qm.tri); free(qm.strip);
    }
    /* the same lines as benchmarks/martini_npm/run.mjs prints, for a side-by-side diff */
    for (i = 0; i < (int)(sizeof thr / sizeof thr[0]); i++) {
        mc_mesh mm;
        mr_mesh_f32(&g, errors, thr[i], &m);
        tri = martini_tris(&m, size);
        mm.v = g_verts; mm.nv = size * size; mm.tri = tri; mm.nt = m.nt; mm.zbits = 0;
        mc_max_error(&mm, size, size, z, &r);
        printf("martini_c max_error=%g triangles=%lld vertices=%lld true_max_error=%.4f at=(%d,%d)", thr[i],
               (long long)m.nt, (long long)m.nv, (double)r.err_num / (double)r.err_den / 10.0, r.err_x, r.err_y);
        if (thr[i] > 0) printf(" (%.2fx)", (double)r.err_num / (double)r.err_den / 10.0 / thr[i]);
        printf("\n");
        free(tri);
    }
    mr_mesh_free(&m);
    mr_grid_free(&g);
    free(z); free(terrain); free(errors); free(e_mar); free(e_snd);
    dem_free(&f);
}

/* ---- part 2: table 1 of 002 --------------------------------------------------- */

/* 002's "ahorro": how much fewer BT needs than QT, in % of QT */
static double save(int64_t bt, int64_t qt)
{
    return qt ? 100.0 * (double)(qt - bt) / (double)qt : 0.0;
}

static void table_part(void)
{
    int c;
    printf("\nTable 1 of papers/002 on real 65x65 crops (tolerance = %% of the crop's height range;"
           " QT = restricted quadtree, BT-002 = 002's bitree rules, both benchmarks/rqt_ref.c;"
           " refs = one generalised strip, optimal for the Sierpinski leaf order, see rqt_ref.h)\n");
    printf("paper (0..1445 m): tol | added BT QT | transmit BT QT | triangles BT QT | refs BT QT\n");
    for (c = 0; c < 8; c++)
        printf("  %-5s | %4d %4d | %4d %4d | %4d %4d | %5d %5d\n", paper[c].tol, paper[c].bt_add, paper[c].qt_add,
               paper[c].bt_tx, paper[c].qt_tx, paper[c].bt_tri, paper[c].qt_tri, paper[c].bt_ref, paper[c].qt_ref);
    for (c = 0; c < NCROPS; c++) {
        hf f;
        br_err err;
        int32_t z[65 * 65], zmin = 0, zmax = 0;
        int k, mode, m3;
        memset(&f, 0, sizeof f);
        if (load_crop(c, &f, z, &zmin, &zmax, &err) != BR_OK) {
            printf("crop %s: skipped: %s\n", crops[c].file, err.msg);
            continue;
        }
        grid_verts(65, z);
        printf("\n%s crop at column %d, row %d: %s; heights %.1f..%.1f m\n", crops[c].file, crops[c].x0, crops[c].y0,
               crops[c].what, (double)zmin * f.z_num / f.z_den, (double)zmax * f.z_num / f.z_den);
        for (m3 = 0; m3 < 3; m3++) {
            static const int order[3] = { RQ_SEL_VERTEX, RQ_SEL_EACH, RQ_SEL_TOPDOWN };
            mode = order[m3];
            printf("  selection %s\n", mode == RQ_SEL_EACH ? "RQ_SEL_EACH (002: every triangle of the hierarchy judged on its own)"
                                    : mode == RQ_SEL_TOPDOWN ? "RQ_SEL_TOPDOWN (split from the roots while e(T) > tol)"
                                    : "RQ_SEL_VERTEX (a point by its own midpoint error |z_m - (z_a + z_b)/2|)");
            printf("  tol   | selected | added BT-002 QT | transmit BT-002 QT | triangles BT-002 QT | refs BT-002 QT | line BT-002 QT |"
                   " BT-002 saves tx/tri/refs (paper) | QT checks\n");
            for (k = 0; k < 8; k++) {
                static int32_t qtri[3 * 8192], qstrip[8 * 8192], btri[3 * 8192], bstrip[8 * 8192];
                rq_mesh qm, bm;
                rq_result r;
                mc_report mr;
                mc_strip_report sq, sb;
                int64_t tol_num = pct[k] < 0 ? -1 : (int64_t)pct[k] * (zmax - zmin);
                qm.tri = qtri; qm.strip = qstrip; bm.tri = btri; bm.strip = bstrip;
                if (rq_run(z, 65, tol_num, 100, mode, &r, &qm, &bm) != 0) { printf("  rq_run failed\n"); break; }
                judge(qtri, qm.nt, 65, z, &mr);
                mc_strip_compare(qstrip, qm.ns, qtri, qm.nt, g_verts, 65 * 65, &sq);
                mc_strip_compare(bstrip, bm.ns, btri, bm.nt, g_verts, 65 * 65, &sb);
                printf("  %-5s | %8lld | %5lld %5lld | %5lld %5lld | %5lld %5lld | %5lld %5lld | %5lld %5lld |"
                       " %3.0f%% %3.0f%% %3.0f%% (%3.0f%% %3.0f%% %3.0f%%) |"
                       " watertight %s, strips decode %s/%s, max err %.1f m (tol %.1f m)\n",
                       paper[k].tol, (long long)r.selected, (long long)r.bt.added, (long long)r.qt.added,
                       (long long)r.bt.transmit, (long long)r.qt.transmit, (long long)r.bt.triangles,
                       (long long)r.qt.triangles, (long long)r.bt.refs, (long long)r.qt.refs,
                       (long long)r.bt.line, (long long)r.qt.line,
                       save(r.bt.transmit, r.qt.transmit), save(r.bt.triangles, r.qt.triangles),
                       save(r.bt.refs, r.qt.refs), save(paper[k].bt_tx, paper[k].qt_tx),
                       save(paper[k].bt_tri, paper[k].qt_tri), save(paper[k].bt_ref, paper[k].qt_ref),
                       mr.ok ? "yes" : "NO",
                       sq.ok ? "ok" : "BAD", sb.ok ? "ok" : "BAD",
                       (double)mr.err_num / (double)mr.err_den * f.z_num / f.z_den,
                       pct[k] < 0 ? 0.0 : (double)tol_num / 100.0 * f.z_num / f.z_den);
                if (!mr.ok) mc_report_print(stdout, &mr);
            }
        }
        dem_free(&f);
    }
}

int main(int argc, char **argv)
{
    int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    martini_part(quick);
    table_part();
    free(g_verts);
    return 0;
}
