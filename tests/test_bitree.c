/* tests/test_bitree.c — the bitree triangulator (core/bitree.h) judged by the
 * independent referee tests/support/meshcheck.h: every fidelity mesh is
 * watertight, has no T-junctions, keeps its TRUE error (evaluated at every grid
 * sample) <= the requested error, and its strip decodes to exactly its
 * triangles with one winding (counter-clockwise seen from +z).  Every DEM of
 * ../shared/data/dem is meshed at full size in the normal run (crops under the
 * sanitizers). */
#include <stdint.h>
#include <math.h>
#include "tests/test.h"
#include "tests/support/meshcheck.h"
#include "tests/support/btcheck.h"
#include "core/bitree.h"
#include "core/cam.h"
#include "platform/load.h"

static int sanitized(void) { return getenv("BITRAIN_SANITIZED") != NULL; }

typedef struct built {
    bt_tree t;
    void *mem, *scr;
} built;

static int build(built *b, const hf *f, int metric)
{
    size_t ms = bt_mem_size(f->w, f->h), ss = bt_scratch_size(f->w, f->h);
    b->mem = malloc(ms); b->scr = malloc(ss);
    if (!b->mem || !b->scr) return -1;
    return bt_build(&b->t, f, metric, b->mem, ms, b->scr, ss) == BR_OK ? 0 : -1;
}
static void unbuild(built *b) { free(b->mem); free(b->scr); }

typedef struct omesh { bt_mesh m; void *mem; } omesh;

static int extract(built *b, const bt_params *p, uint32_t cap, omesh *o)
{
    return btc_extract(&b->t, p, cap, &o->m, &o->mem);
}

/* Runs meshcheck on o (strip decoded); returns ok and fills r. */
static int judge_reach(const hf *f, const omesh *o, int allow_uncovered, int64_t expect_area2,
                       int32_t void_reach, mc_report *r, mc_strip_report *sr)
{
    const bt_mesh *m = &o->m;
    mc_vert *v;
    int32_t *s, *tri;
    int64_t nt, nl;
    mc_opts opt;
    int ok = btc_decode(m, &v, &s, &tri, &nt, &nl) == 0;
    CHECK(ok);
    CHECK_EQ(nt, m->ntri);
    CHECK_EQ(nl, m->nline);
    if (ok) {
        mc_mesh mm = { v, (int32_t)m->nv, tri, nt, 0 };
        memset(&opt, 0, sizeof opt);
        opt.allow_uncovered = allow_uncovered;
        opt.expect_area2 = expect_area2;
        opt.void_reach = void_reach;
        ok = mc_check(&mm, f->w, f->h, f->z, &opt, r) == 1;
        if (!ok) mc_report_print(stderr, r);
        if (nt > 0) CHECK_EQ(r->orientation, -1);
        CHECK(mc_strip_compare(s, m->ns, tri, nt, v, (int32_t)m->nv, sr) == 1);
        if (nt > 0) CHECK_EQ(sr->orientation, -1);
    }
    free(v); free(s); free(tri);
    return ok;
}

static int judge(const hf *f, const omesh *o, int allow_uncovered, int64_t expect_area2,
                 mc_report *r, mc_strip_report *sr)
{
    return judge_reach(f, o, allow_uncovered, expect_area2, 0, r, sr);
}

/* How far (samples) a mesh within e heightfield units may draw over a void or widen
 * its hole: a triangle left unsplit over a void has an extent code <= e, and that
 * extent is at least its bounding box's side times the longer grid step (core/bt_err.c
 * void_extent). */
static int32_t reach_of(const hf *f, int64_t e)
{
    int64_t step = f->dx_um > f->dy_um ? f->dx_um : f->dy_um;
    return (int32_t)(e * 1000000 * f->z_num / f->z_den / step);
}

/* fuji.png padded to 513 x 513 by repeating the last row and column (martini's test) */
static int fuji513(hf *g)
{
    hf f;
    int32_t x, y;
    if (btc_load("png/fuji.png", &f)) return -1;
    *g = f;
    g->w = g->h = 513;
    g->z = malloc(513 * 513 * 4);
    for (y = 0; y < 513; y++)
        for (x = 0; x < 513; x++) g->z[y * 513 + x] = f.z[(y < 512 ? y : 511) * 512 + (x < 512 ? x : 511)];
    dem_free(&f);
    return 0;
}

static void test_codes(void)
{
    int64_t v;
    uint16_t c, prev = 0;
    CHECK_EQ(bt_code_value(bt_code_encode(0)), 0);
    CHECK_EQ(bt_code_value(bt_code_encode(4095)), 4095);
    for (v = 1; v < ((int64_t)1 << 40); v = v * 3 / 2 + 1) {
        c = bt_code_encode(v);
        CHECK(bt_code_value(c) >= v);                 /* rounds up: a bound stays a bound */
        CHECK(bt_code_value(c) - v <= (v >> 11) + 1); /* 12-bit mantissa */
        CHECK(c >= prev);
        prev = c;
    }
    CHECK_EQ(bt_code_value(BT_CODE_SPLIT), INT64_MAX);
}

static void test_fuji_10m(void)
{
    hf g;
    built b;
    omesh o;
    bt_params p;
    mc_report r;
    mc_strip_report sr;
    if (fuji513(&g)) { CHECK(0); return; }
    CHECK(build(&b, &g, BT_METRIC_EXACT) == 0);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = bt_mm_to_units(&g, 10000);
    CHECK_EQ(p.max_err, 100);
    CHECK(extract(&b, &p, 0, &o) == 0);
    CHECK(o.m.ntri <= 97500);                /* issue 3's target; exact-error reference 92,858 */
    CHECK_EQ(o.m.ntri, 92728);
    CHECK(judge(&g, &o, 0, 0, &r, &sr));
    CHECK(!mc_err_exceeds(&r, 10000LL * g.z_den, 1000LL * g.z_num));
    CHECK_EQ(r.tjunctions, 0);
    CHECK(btc_mesh_hash(&o.m) == 16123431594418414837ull);  /* determinism: fixed bytes */
    CHECK(o.m.ns * 50 <= o.m.ntri * 77);               /* <= 1.54 strip references per triangle (one_dem) */
    CHECK_EQ(o.m.nfict, 59);    /* vertices whose height is their hypotenuse's interpolation */
    printf("fuji 513 @10 m: %u triangles, %u vertices, %u refs (%.3f/tri), %u line, max err %lld/%lld\n",
           o.m.ntri, o.m.nv, o.m.ns, (double)o.m.ns / o.m.ntri, o.m.nline,
           (long long)r.err_num, (long long)r.err_den);
    free(o.mem);
    unbuild(&b);
    free(g.z);
}

/* Every DEM: fidelity mesh at ~0.5 % of its height range, judged.  On the full
 * grid the strip's references per triangle must be <= 1.54 and <= refs_pm / 1000
 * (the measured figure: a regression bound).  Issue 3's target, 1.5, held only while
 * any three grid-collinear vertices counted as a line triangle; those whose heights
 * are off the line are vertical slivers the rasteriser draws, and the strip writer
 * no longer uses them (test_line_triangles_draw_nothing). */
static void one_dem(const char *rel, int crop, uint32_t refs_pm)
{
    hf f, g;
    built b;
    omesh o;
    bt_params p;
    mc_report r;
    mc_strip_report sr;
    hf_stats st;
    int64_t thr;
    if (btc_load(rel, &f)) { CHECK(0); return; }
    g = f;
    if (crop && (f.w > 200 || f.h > 160)) {   /* asymmetric crop from the interior */
        int32_t x, y, x0 = f.w / 3, y0 = f.h / 4;
        g.w = f.w > 200 ? 200 : f.w; g.h = f.h > 160 ? 160 : f.h;
        if (x0 + g.w > f.w) x0 = f.w - g.w;
        if (y0 + g.h > f.h) y0 = f.h - g.h;
        g.z = malloc((size_t)g.w * g.h * 4);
        for (y = 0; y < g.h; y++)
            for (x = 0; x < g.w; x++) g.z[y * g.w + x] = f.z[(size_t)(y + y0) * f.w + x + x0];
    }
    hf_stats_get(&g, &st);
    thr = ((int64_t)st.zmax - st.zmin) / 200;
    if (thr < 1) thr = 1;
    CHECK(build(&b, &g, BT_METRIC_EXACT) == 0);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = thr;
    CHECK(extract(&b, &p, 0, &o) == 0);
    CHECK_MSG(judge(&g, &o, st.voids > 0, st.voids > 0 ? btc_exact_area2(&g) : 0, &r, &sr), "%s", rel);
    if (!crop) {
        CHECK_MSG((uint64_t)o.m.ns * 1000 <= (uint64_t)o.m.ntri * refs_pm, "%s: %u refs for %u triangles > %u/1000",
                  rel, o.m.ns, o.m.ntri, refs_pm);
        CHECK_MSG((uint64_t)o.m.ns * 50 <= (uint64_t)o.m.ntri * 77, "%s: %u refs for %u triangles > 1.54",
                  rel, o.m.ns, o.m.ntri);
    }
    CHECK_MSG(!mc_err_exceeds(&r, thr, 1), "%s: error %lld/%lld > %lld", rel,
              (long long)r.err_num, (long long)r.err_den, (long long)thr);
    printf("%-34s %5dx%-5d thr %6lld: %7u tri %7u vert %.3f refs/tri, err %lld/%lld\n", rel, g.w, g.h,
           (long long)thr, o.m.ntri, o.m.nv, (double)o.m.ns / (o.m.ntri ? o.m.ntri : 1),
           (long long)r.err_num, (long long)r.err_den);
    free(o.mem);
    unbuild(&b);
    if (g.z != f.z) free(g.z);
    dem_free(&f);
}

static void test_every_dem(void)
{
    /* refs_pm: the measured figure (a regression bound, rounded up); in walk order with
     * bridges (before the reorder pass of bt_mesh.c) they were 1.497, 1.499, 1.499, 1.497,
     * 1.488 (HGT), 1.488, 1.496 (unchanged: no breaks), 1.514, 1.502, 1.578, 1.515, 1.545 */
    static const struct { const char *rel; uint32_t refs_pm; } dems[] = {
        { "hgt/N47E009.hgt", 1416 }, { "hgt/N50E008.hgt", 1420 }, { "hgt/N50E009.hgt", 1421 },
        { "hgt/N50E010.hgt", 1419 }, { "hgt/N57E011.hgt", 1417 }, { "png/ps_height_1k.png", 1533 },
        { "bt/crater_0513.bt", 1525 }, { "png/fuji.png", 1416 }, { "asc/colorado_front_range.asc", 1420 },
        { "asc/hugo_site.asc", 1491 }, { "tif/mt_rainier_90m.tif", 1435 },
        { "xyz/monai_valley_bathymetry.txt", 1435 }
    };
    size_t i;
    for (i = 0; i < sizeof dems / sizeof dems[0]; i++) one_dem(dems[i].rel, sanitized(), dems[i].refs_pm);
}

/* Lossless (max error 0) on a crop with voids: the mesh interpolates every sample. */
static void test_lossless_voids(void)
{
    hf f;
    built b;
    omesh o;
    bt_params p;
    mc_report r;
    mc_strip_report sr;
    if (btc_load("asc/hugo_site.asc", &f)) { CHECK(0); return; }
    CHECK(build(&b, &f, BT_METRIC_EXACT) == 0);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = 0;
    CHECK(extract(&b, &p, 0, &o) == 0);
    CHECK(judge(&f, &o, 1, btc_exact_area2(&f), &r, &sr));
    CHECK_EQ(r.err_num, 0);
    CHECK_EQ(r.void_covered, 0);
    CHECK(o.m.ns * 2 <= o.m.ntri * 3);      /* the reorder pass ran (voids break the walk) */
    free(o.mem);
    /* the same into a mesh too small: budget downgrade, then the reorder pass */
    CHECK(extract(&b, &p, 600, &o) == 0);
    CHECK_EQ(o.m.overflow, 1);
    CHECK(o.m.ntri <= 600 && o.m.ntri > 50);
    /* a budget has no bound: it may draw over voids (corners valid: bad_vertex) */
    CHECK(judge_reach(&f, &o, 1, 0, f.w + f.h, &r, &sr) || r.uncovered > 0);
    CHECK_EQ(r.tjunctions, 0);
    CHECK_EQ(r.void_covered, 0);
    CHECK_EQ(r.bad_vertex, 0);
    CHECK_EQ(r.nonmanifold_edges, 0);
    free(o.mem);
    {   /* view and budget modes over voids */
        cam c;
        int32_t u, eye[3], tgt[3];
        CHECK_EQ(bt_frame_auto(&f, &p.fr, &u), BR_OK);
        eye[0] = 10 << u; eye[1] = 10 << u; eye[2] = 1800 << u;
        tgt[0] = 400 << u; tgt[1] = 300 << u; tgt[2] = 1680 << u;
        CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, 160, 120, 1 << u, 1 << 28), BR_OK);
        p.c = &c;
        p.mode = BT_VIEW;
        p.pixel_err_q8 = 128;
        p.morph_q8 = 256;
        CHECK(extract(&b, &p, 20000, &o) == 0);
        CHECK(o.m.ntri > 0);
        {
            /* a triangle left over a void has extent <= tau d / f, d at most the
             * distance to the grid's far corner */
            double W = f.w * ((double)f.dx_um * 1e-6), H = f.h * ((double)f.dy_um * 1e-6), Z = 1800.0;
            double dmax = sqrt(W * W + H * H + Z * Z), fpx = (double)c.f_q16 / 65536.0;
            double step = (double)(f.dx_um > f.dy_um ? f.dx_um : f.dy_um) * 1e-6;
            int32_t reach = (int32_t)(0.5 * dmax / fpx / step) + 1;
            CHECK(judge_reach(&f, &o, 1, 0, reach, &r, &sr) || r.uncovered > 0);
        }
        CHECK_EQ(r.tjunctions, 0);
        CHECK_EQ(r.void_covered, 0);
        p.mode = BT_BUDGET;
        for (p.budget = 20; p.budget <= 2000; p.budget = p.budget * 3 + 7) {   /* small budgets too */
            CHECK(bt_extract(&b.t, &p, &o.m) == BR_OK);
            CHECK(o.m.ntri <= p.budget);
            CHECK(judge_reach(&f, &o, 1, 0, f.w + f.h, &r, &sr) || r.uncovered > 0);
            CHECK_EQ(r.tjunctions, 0);
            CHECK_EQ(r.bad_vertex, 0);         /* drawn over voids from valid corners only */
        }
        free(o.mem);
    }
    unbuild(&b);
    dem_free(&f);
}

/* SRTM voids (N50E008: 50 samples): a void's extent is its error ("Voids",
 * core/bt_err.c), so a coarse mesh no longer refines every void to the sample; it
 * draws over a void or widens its hole by at most the error, and below the extent
 * of a unit triangle (2 x 92.7 m) the voids are holes exactly. */
static void test_void_extent(void)
{
    static const struct { int64_t e; int64_t max_tri; } cases[] = {
        { 100000, 600 }, { 2000, 800 }, { 300, 1500 }, { 150, 0 }
    };
    hf f;
    built b;
    omesh o;
    bt_params p;
    mc_report r;
    mc_strip_report sr;
    size_t i;
    int64_t nvoid = 0;
    if (btc_load("hgt/N50E008.hgt", &f)) { CHECK(0); return; }
    for (i = 0; i < (size_t)f.w * (size_t)f.h; i++) nvoid += f.z[i] == HF_NODATA;
    CHECK_EQ(nvoid, 50);
    CHECK(build(&b, &f, BT_METRIC_EXACT) == 0);
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        memset(&p, 0, sizeof p);
        p.mode = BT_FIDELITY;
        p.max_err = cases[i].e;            /* metres: HGT units */
        CHECK(extract(&b, &p, 0, &o) == 0);
        CHECK(judge_reach(&f, &o, 1, 0, reach_of(&f, p.max_err), &r, &sr));
        CHECK(!mc_err_exceeds(&r, p.max_err, 1));
        if (cases[i].max_tri) {
            CHECK(o.m.ntri <= cases[i].max_tri);   /* refined to the sample: 1537+ */
            CHECK(r.void_covered_near > 0);
        } else CHECK_EQ(r.void_covered_near, 0);
        free(o.mem);
    }
    unbuild(&b);
    dem_free(&f);
}

/* Odd, non-square synthetic grid with a void blob and extreme heights in mm
 * (-11000 m .. 9000 m): the wide (int64) error path, exact bound. */
static void test_extremes(void)
{
    int32_t w = 301, h = 97, x, y;
    int32_t *z = malloc((size_t)w * h * 4);
    hf f;
    built b;
    omesh o;
    bt_params p;
    mc_report r;
    mc_strip_report sr;
    uint32_t s = 12345;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            s = s * 1103515245u + 12345u;
            z[y * w + x] = ((x + y) & 1) ? 9000000 : -11000000;
            if ((s >> 16) % 7 == 0) z[y * w + x] = (int32_t)((s >> 8) % 20000001) - 11000000;
            if ((x - 150) * (x - 150) + (y - 40) * (y - 40) < 90) z[y * w + x] = HF_NODATA;
        }
    memset(&f, 0, sizeof f);
    f.w = w; f.h = h; f.z = z; f.z_num = 1; f.z_den = 1000; f.dx_um = 1000000; f.dy_um = 1000000;
    CHECK(build(&b, &f, BT_METRIC_EXACT) == 0);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = 5000000;   /* 5 km: above the blob's extent, so it may be drawn over */
    CHECK(extract(&b, &p, 0, &o) == 0);
    CHECK(judge_reach(&f, &o, 1, 0, reach_of(&f, p.max_err), &r, &sr));
    CHECK(!mc_err_exceeds(&r, p.max_err, 1));
    free(o.mem);
    p.max_err = 1000;      /* 1 m, below a unit triangle's extent (2 m): holes exactly */
    CHECK(extract(&b, &p, 0, &o) == 0);
    CHECK(judge(&f, &o, 1, btc_exact_area2(&f), &r, &sr));
    CHECK(!mc_err_exceeds(&r, p.max_err, 1));
    free(o.mem);
    unbuild(&b);
    free(z);
}

/* A large grid (2049^2; 513^2 under the sanitizers) with heights in millimetres
 * spanning -11000 m .. 9000 m: a steep paraboloid plus single-sample spikes of
 * both extremes, so the exact metric runs its int64 path with large D; the mesh
 * must hold its bound at every sample. */
static void test_big_extremes(void)
{
    int32_t n = sanitized() ? 513 : 2049, x, y, c = n / 2;
    int32_t *z = malloc((size_t)n * n * 4);
    hf f;
    built b;
    omesh o;
    bt_params p;
    mc_report r;
    mc_strip_report sr;
    for (y = 0; y < n; y++)
        for (x = 0; x < n; x++) {
            int64_t d2 = (int64_t)(x - c) * (x - c) + (int64_t)(y - c) * (y - c);
            int64_t v = -11000000 + (20000000 * d2) / (2 * (int64_t)c * c);
            if (v > 9000000) v = 9000000;
            if (((x * 7 + y * 13) % 997) == 0) v = (x & 1) ? 9000000 : -11000000;
            z[(size_t)y * n + x] = (int32_t)v;
        }
    memset(&f, 0, sizeof f);
    f.w = n; f.h = n; f.z = z; f.z_num = 1; f.z_den = 1000; f.dx_um = 30000000; f.dy_um = 30000000;
    CHECK(build(&b, &f, BT_METRIC_EXACT) == 0);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = 2000000;   /* 2 km: the spikes force local refinement */
    CHECK(extract(&b, &p, 0, &o) == 0);
    CHECK(o.m.ntri > 1000);
    CHECK(judge(&f, &o, 0, 0, &r, &sr));
    CHECK(!mc_err_exceeds(&r, p.max_err, 1));
    free(o.mem);
    unbuild(&b);
    free(z);
}

static void test_curvature(void)
{
    hf f;
    built b;
    omesh o;
    bt_params p;
    mc_report r;
    mc_strip_report sr;
    if (btc_load("bt/crater_0513.bt", &f)) { CHECK(0); return; }
    CHECK(build(&b, &f, BT_METRIC_CURVATURE) == 0);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = bt_mm_to_units(&f, 20000);
    CHECK(extract(&b, &p, 0, &o) == 0);
    CHECK(o.m.ntri > 100 && o.m.ntri < 2 * 512 * 512);
    CHECK(judge(&f, &o, 0, 0, &r, &sr));
    free(o.mem);
    unbuild(&b);
    dem_free(&f);
}

/* View-dependent, budget, hysteresis, geomorph, capacity downgrade. */
static void test_view(void)
{
    hf g;
    built b;
    omesh o, o2, o3;
    bt_params p;
    mc_report r;
    mc_strip_report sr;
    cam c;
    int32_t eye[3] = { 100 * 64, -400 * 64, 4500 * 64 }, tgt[3] = { 256 * 64, -256 * 64, 1500 * 64 };
    uint32_t i, nf = 0;
    if (fuji513(&g)) { CHECK(0); return; }
    CHECK(build(&b, &g, BT_METRIC_EXACT) == 0);
    CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, 320, 240, 64, 2000 * 64), BR_OK);
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW;
    p.c = &c;
    p.fr.sx = 64; p.fr.sy = 64; p.fr.sz_q16 = 65536 * 64 / 10;  /* world unit 1/64 m; z in dm */
    p.pixel_err_q8 = 256;
    p.morph_q8 = 256;
    p.hyst_q8 = 64;
    CHECK(extract(&b, &p, 200000, &o) == 0);
    CHECK(o.m.ntri > 1000);
    CHECK(judge(&g, &o, 1, 0, &r, &sr) || r.uncovered > 0); /* culled parts leave holes */
    CHECK_EQ(r.tjunctions, 0);
    CHECK_EQ(r.nonmanifold_edges, 0);
    CHECK_EQ(r.split_vertex, 0);
    CHECK_EQ(r.flipped, 0);
    for (i = 0; i < o.m.nv; i++) nf += o.m.v[i].state == BT_F;
    CHECK_EQ(nf, o.m.nfict);
    CHECK(nf > 0);                          /* some vertices are still morphing */
    CHECK_EQ(o.m.ntri, 4184);
    CHECK(btc_mesh_hash(&o.m) == 14851907604528705762ull);  /* same bytes on every build */
    /* the same frame again: hysteresis keeps everything split, nothing is lost */
    {
        uint32_t t1 = o.m.ntri;
        CHECK(bt_extract(&b.t, &p, &o.m) == BR_OK);
        CHECK(o.m.ntri >= t1);
    }
    /* culling breaks the walk: BT_ORDER_WALK bridges each break by the shortest run
     * of line triangles where AUTO, per frame in view mode, takes the fixed restart;
     * BT_ORDER_BEST writes the same triangles in fewer references (<= 1.5) still */
    {
        omesh ob, ow;
        uint32_t ns_auto = o.m.ns;
        p.strip_order = BT_ORDER_WALK;
        CHECK(extract(&b, &p, 200000, &ow) == 0);
        p.strip_order = BT_ORDER_BEST;
        CHECK(extract(&b, &p, 200000, &ob) == 0);
        CHECK(ow.m.ns < ns_auto);
        CHECK_EQ(ow.m.ntri, o.m.ntri);
        CHECK_EQ(ob.m.ntri, ow.m.ntri);
        CHECK(ob.m.ns < ow.m.ns);
        CHECK(2 * (uint64_t)ob.m.ns <= 3 * (uint64_t)ob.m.ntri);
        printf("  view mesh, culling: %u triangles, restarts %.3f refs/tri, bridges %.3f, best order %.3f\n",
               ob.m.ntri, (double)ns_auto / o.m.ntri, (double)ow.m.ns / ow.m.ntri, (double)ob.m.ns / ob.m.ntri);
        CHECK(judge(&g, &ob, 1, 0, &r, &sr) || r.uncovered > 0);
        CHECK_EQ(r.tjunctions, 0);
        CHECK_EQ(r.nonmanifold_edges, 0);
        CHECK_EQ(r.flipped, 0);
        /* the same vertices, and the best strip decodes to exactly the walk's triangles */
        CHECK_EQ(ob.m.nv, ow.m.nv);
        CHECK(memcmp(ob.m.v, ow.m.v, sizeof *ob.m.v * ow.m.nv) == 0);
        {
            mc_vert *v;
            int32_t *sw, *tw, *sb = malloc(4 * ((size_t)ob.m.ns + 1));
            int64_t nt, nl;
            CHECK(btc_decode(&ow.m, &v, &sw, &tw, &nt, &nl) == 0 && sb);
            CHECK_EQ(nt, ow.m.ntri);
            for (i = 0; sb && i < ob.m.ns; i++) sb[i] = (int32_t)ob.m.strip[i];
            if (sb) CHECK(mc_strip_compare(sb, ob.m.ns, tw, nt, v, (int32_t)ow.m.nv, &sr) == 1);
            free(sb);
            /* and so does AUTO's, restarts and all */
            CHECK(o.m.nv == ow.m.nv && memcmp(o.m.v, ow.m.v, sizeof *o.m.v * ow.m.nv) == 0);
            sb = malloc(4 * ((size_t)o.m.ns + 1));
            for (i = 0; sb && i < o.m.ns; i++) sb[i] = (int32_t)o.m.strip[i];
            if (sb) CHECK(mc_strip_compare(sb, o.m.ns, tw, nt, v, (int32_t)ow.m.nv, &sr) == 1);
            free(v); free(sw); free(sb); free(tw);
        }
        p.strip_order = 3;
        CHECK_EQ(bt_extract(&b.t, &p, &ob.m), BR_E_ARG);
        p.strip_order = BT_ORDER_AUTO;
        /* an absurd geomorph range is refused (it would overflow morph_of) */
        p.morph_q8 = 65537;
        p.pixel_err_q8 = INT32_MAX;
        CHECK_EQ(bt_extract(&b.t, &p, &ob.m), BR_E_ARG);
        p.morph_q8 = 65536;
        CHECK_EQ(bt_extract(&b.t, &p, &ob.m), BR_OK);
        p.morph_q8 = 256;
        p.pixel_err_q8 = 256;
        free(ob.mem); free(ow.mem);
    }
    /* no culling: more triangles */
    p.no_cull = 1;
    CHECK(extract(&b, &p, 400000, &o2) == 0);
    CHECK(o2.m.ntri > o.m.ntri);
    CHECK(judge(&g, &o2, 0, 0, &r, &sr));
    /* budget */
    p.no_cull = 0;
    p.mode = BT_BUDGET;
    p.budget = 5000;
    CHECK(extract(&b, &p, 5000, &o3) == 0);
    CHECK(o3.m.ntri <= 5000 && o3.m.ntri > 4000);
    CHECK(judge(&g, &o3, 1, 0, &r, &sr) || r.uncovered > 0);
    CHECK_EQ(r.tjunctions, 0);
    CHECK_EQ(r.nonmanifold_edges, 0);
    /* view mode into a mesh too small: budget downgrade, twice (hysteresis state) */
    free(o3.mem);
    p.mode = BT_VIEW;
    CHECK(extract(&b, &p, 2000, &o3) == 0);
    CHECK_EQ(o3.m.overflow, 1);
    CHECK(o3.m.ntri <= 2000 && o3.m.ntri > 1000);
    CHECK(bt_extract(&b.t, &p, &o3.m) == BR_OK);
    CHECK(judge(&g, &o3, 1, 0, &r, &sr) || r.uncovered > 0);
    CHECK_EQ(r.tjunctions, 0);
    CHECK_EQ(r.nonmanifold_edges, 0);
    /* capacity downgrade: fidelity 1 m into a 3000-triangle mesh */
    free(o3.mem);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = 10;
    CHECK(extract(&b, &p, 3000, &o3) == 0);
    CHECK_EQ(o3.m.overflow, 1);
    CHECK(o3.m.ntri <= 3000 && o3.m.ntri > 2500);
    CHECK(judge(&g, &o3, 0, 0, &r, &sr));
    free(o.mem); free(o2.mem); free(o3.mem);
    unbuild(&b);
    free(g.z);
}

/* The padding to (2^k + 1)^2 costs nothing beyond what the error asks for: at an
 * error no sample reaches, the mesh of an odd-sized grid keeps only what the edges'
 * alignment forces (the bitree's triangles end on the grid's last row and column
 * only at multiples of their size: 1200 = 16 x 75 for SRTM tiles, 76 = 4 x 19), not
 * every edge sample (9,772 triangles on the whole N47E009 tile while triangles over
 * the padding counted as mixed).  An odd w - 1 still keeps every sample of the last
 * column: the alignment is 1 there. */
static void test_padding_floor(void)
{
    static const struct { int32_t w, h; uint32_t most; } cases[] = {
        { 1201, 1201, 470 }, { 1025, 1025, 2 }, { 1201, 721, 470 }, { 77, 1201, 930 }
    };
    hf f, g;
    size_t i;
    if (btc_load("hgt/N47E009.hgt", &f)) { CHECK(0); return; }
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        built b;
        omesh o;
        bt_params p;
        mc_report r;
        mc_strip_report sr;
        int32_t x, y;
        if (sanitized() && cases[i].w * cases[i].h > 200000) continue;
        g = f;
        g.w = cases[i].w; g.h = cases[i].h;
        g.z = malloc((size_t)g.w * g.h * 4);
        for (y = 0; y < g.h; y++)
            for (x = 0; x < g.w; x++) g.z[(size_t)y * g.w + x] = f.z[(size_t)(y + f.h - g.h) * f.w + x];
        CHECK(build(&b, &g, BT_METRIC_EXACT) == 0);
        memset(&p, 0, sizeof p);
        p.mode = BT_FIDELITY;
        p.max_err = (int64_t)1 << 40;
        CHECK(extract(&b, &p, 0, &o) == 0);
        CHECK(judge(&g, &o, 0, 0, &r, &sr));
        CHECK_MSG(o.m.ntri <= cases[i].most, "%dx%d: %u triangles > %u", g.w, g.h, o.m.ntri, cases[i].most);
        printf("padding floor %dx%d: %u triangles\n", g.w, g.h, o.m.ntri);
        free(o.mem);
        unbuild(&b);
        free(g.z);
    }
    dem_free(&f);
}

static void test_bad_args(void)
{
    int32_t z[4] = { 1, 2, 3, 4 };
    hf f = { 2, 2, z, 1, 1, 1000000, 1000000, { 0, 0, 0, 0, 0 } };
    bt_tree t;
    uint32_t mem[64];
    uint8_t *scr = malloc(bt_scratch_size(2, 2));
    memset(&t, 0, sizeof t);
    CHECK(bt_mem_size(2, 2) <= sizeof mem);
    CHECK_EQ(bt_build(&t, &f, 7, mem, sizeof mem, scr, bt_scratch_size(2, 2)), BR_E_ARG);
    CHECK_EQ(bt_build(&t, &f, 0, mem, 3, scr, bt_scratch_size(2, 2)), BR_E_ARG);
    CHECK_EQ(bt_build(&t, &f, 0, mem, sizeof mem, scr, bt_scratch_size(2, 2) - 1), BR_E_ARG);
    CHECK(t.node == NULL);                 /* a failed call leaves t as it was */
    CHECK_EQ(bt_build(&t, &f, 0, (uint8_t *)mem + 1, sizeof mem - 1, scr, bt_scratch_size(2, 2)), BR_E_ARG);
    CHECK_EQ(bt_build(&t, &f, 0, mem, sizeof mem, scr, bt_scratch_size(2, 2)), BR_OK);
    CHECK_EQ(bt_mesh_mem_size(1), 0);
    free(scr);
}

int main(void)
{
    T_RUN(test_codes);
    T_RUN(test_bad_args);
    T_RUN(test_fuji_10m);
    T_RUN(test_lossless_voids);
    T_RUN(test_extremes);
    T_RUN(test_void_extent);
    T_RUN(test_big_extremes);
    T_RUN(test_curvature);
    T_RUN(test_view);
    T_RUN(test_every_dem);
    T_RUN(test_padding_floor);
    return t_finish();
}
