/* tests/test_pictures.c — what the pictures of real DEMs must not show (issue 16,
 * "wrong pictures"), checked by numbers rather than by golden images:
 * heights at their real value in the world frame (hugo_site.asc, metre heights on a
 * 760 m grid: the Q16 vertical scale must fit its int32), line triangles of the
 * bitree strips that draw nothing (no vertical slivers: fidelity streaks, floating
 * dashes above the far edge), grid edges at an odd row or column that the view
 * mesh reaches whole (no notch per sample), and the automatic vertical scale of
 * grids without georeference (plausible relief, no spikes), small grids in the
 * default view's frame, all-void grids refused, voids as holes in every path and
 * --fill-voids. */
#include <math.h>
#include "tests/test.h"
#include "tests/support/btcheck.h"
#include "core/bitree.h"
#include "platform/cmd.h"
#include "platform/fill.h"
#include "platform/load.h"
#include "platform/png_io.h"
#include "platform/scene.h"

/* ------------------------------------------------------------- vertical scale */

/* World z of sample (x, y) against its height in millimetres, in world units. */
static int64_t z_error(const scene *s, int32_t x, int32_t y)
{
    rs_vertex v;
    int32_t z = s->f.z[(size_t)y * s->f.w + x];
    int64_t want = rt_mm_to_world(&s->rt, (int64_t)llround((double)hf_z_to_mm(&s->f, z) * s->zscale));
    rt_vertex(&s->rt, x, y, z, &v);
    return v.p[2] > want ? v.p[2] - want : want - v.p[2];
}

static void test_world_height(void)
{
    static const double zs[] = { 1, 3, 40 };
    const char *in[1];
    size_t k;
    in[0] = t_data("asc/hugo_site.asc");
    for (k = 0; k < sizeof zs / sizeof zs[0]; k++) {
        scene s;
        scene_opts o;
        br_err err;
        int32_t x, y, bx = -1, by = -1;
        memset(&o, 0, sizeof o);
        o.zscale = zs[k];
        o.quiet = 1;
        if (scene_open(&s, in, 1, &o, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); return; }
        for (y = 0; y < s.f.h; y++)
            for (x = 0; x < s.f.w; x++)
                if (s.f.z[(size_t)y * s.f.w + x] == s.st.zmax) { bx = x; by = y; }
        CHECK(bx >= 0);
        CHECK_EQ(hf_z_to_mm(&s.f, s.st.zmax), 1711000);
        /* within 1 world unit of 1711 m * zscale (rounding of the vertical scale) */
        CHECK_MSG(z_error(&s, bx, by) <= 1 + (int64_t)zs[k], "zscale %g: world z off by %lld units (2^%d m)",
                  zs[k], (long long)z_error(&s, bx, by), -s.rt.shift);
        CHECK(s.rt.shift <= 14);
        scene_close(&s);
    }
}

/* ------------------------------------------------------------- line triangles */

/* Grid-collinear strip triangles of distinct vertices whose heights are off their
 * line (vertical slivers), except those under the surface that rim_line allows
 * (void-free grid, middle vertex above the chord, not along the grid's edge). */
static uint32_t visible_slivers(const bt_tree *t, const bt_mesh *m)
{
    uint32_t k, n = 0;
    int nov = t->nvalid == (int64_t)t->f->w * t->f->h;
    for (k = 0; k + 2 < m->ns; k++) {
        const bt_vert *p[3];
        int64_t dx1, dy1, dx2, dy2, dz1, dz2;
        int i, mid;
        if (m->strip[k] == m->strip[k + 1] || m->strip[k + 1] == m->strip[k + 2] || m->strip[k] == m->strip[k + 2])
            continue;
        for (i = 0; i < 3; i++) p[i] = &m->v[m->strip[k + i]];
        dx1 = p[1]->x - p[0]->x; dy1 = p[1]->y - p[0]->y; dz1 = (int64_t)p[1]->z - p[0]->z;
        dx2 = p[2]->x - p[0]->x; dy2 = p[2]->y - p[0]->y; dz2 = (int64_t)p[2]->z - p[0]->z;
        if (dx1 * dy2 - dy1 * dx2 != 0) continue;                    /* a real triangle */
        if (dz1 * dx2 == dz2 * dx1 && dz1 * dy2 == dz2 * dy1) continue; /* flat: draws nothing */
        /* the middle one of the three along the line */
        for (mid = 0; mid < 3; mid++) {
            const bt_vert *a = p[(mid + 1) % 3], *b = p[(mid + 2) % 3], *c = p[mid];
            int64_t ta = a->x != b->x ? a->x : a->y, tb = a->x != b->x ? b->x : b->y, tc = a->x != b->x ? c->x : c->y;
            if ((tc - ta) * (tc - tb) < 0) {
                int edge = (a->x == b->x && (a->x == 0 || a->x == t->f->w - 1)) ||
                           (a->y == b->y && (a->y == 0 || a->y == t->f->h - 1));
                int64_t above = ((int64_t)c->z - a->z) * (tb - ta) - ((int64_t)b->z - a->z) * (tc - ta);
                if (tb < ta) above = -above;
                if (!(nov && !edge && above > 0)) n++;
                break;
            }
        }
    }
    return n;
}

static void test_line_triangles_draw_nothing(void)
{
    const char *in[1];
    scene s;
    scene_opts o;
    br_err err;
    cam c;
    double cv[6] = { 37000, 55000, 3000, 45000, 0, 1500 };   /* the dashes */
    bt_params p;
    uint64_t nt = 0;
    int mode;
    in[0] = "assets/N47E009.hgt.gz";
    memset(&o, 0, sizeof o);
    if (scene_open(&s, in, 1, &o, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); return; }
    CHECK_EQ(scene_camera(&s, cv, cv + 3, 60, 1280, 720, &c), BR_OK);
    CHECK_EQ(scene_tree(&s, &err), BR_OK);
    CHECK_EQ(scene_reserve(&s, 1200000, &err), BR_OK);
    for (mode = 0; mode < 3; mode++) {
        memset(&p, 0, sizeof p);
        p.mode = mode == 0 ? BT_VIEW : BT_FIDELITY;
        p.max_err = mode == 1 ? 5 : 20;
        p.c = &c;
        p.fr = s.rt.fr;
        CHECK_EQ(bt_count(&s.tree, &p, &nt), BR_OK);
        CHECK(nt < 1200000);
        CHECK_EQ(bt_extract(&s.tree, &p, &s.mesh), BR_OK);
        CHECK(s.mesh.nline > 1000);
        CHECK_MSG(visible_slivers(&s.tree, &s.mesh) == 0, "mode %d: %u slivers of %u line triangles", mode,
                  visible_slivers(&s.tree, &s.mesh), s.mesh.nline);
    }
    scene_close(&s);
}

/* A void-free grid (rim_line's relaxed rule applies) */
static void test_line_triangles_void_free(void)
{
    hf f;
    bt_tree t;
    bt_params p;
    bt_mesh m;
    void *tm, *sc, *mm = NULL;
    int32_t x, y;
    if (btc_load("png/fuji.png", &f)) { CHECK(0); return; }
    for (y = 0; y < 257; y++)                 /* the north-west 257 x 257 (2^8 + 1): no padding */
        for (x = 0; x < 257; x++) f.z[y * 257 + x] = f.z[(size_t)y * f.w + x];
    f.w = f.h = 257;
    tm = malloc(bt_mem_size(f.w, f.h));
    sc = malloc(bt_scratch_size(f.w, f.h));
    CHECK_EQ(bt_build(&t, &f, BT_METRIC_EXACT, tm, bt_mem_size(f.w, f.h), sc, bt_scratch_size(f.w, f.h)), BR_OK);
    CHECK_EQ(t.nvalid, 257 * 257);
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = 30;
    CHECK_EQ(btc_extract(&t, &p, 0, &m, &mm), 0);
    CHECK(m.nline > 100);
    CHECK_EQ(visible_slivers(&t, &m), 0);
    free(mm); free(tm); free(sc); free(f.z);
}

/* ------------------------------------------------------------- odd edges */

/* Colorado (240x144: last row 143, last column 239, both odd): the view mesh,
 * culling off, covers the whole grid (doubled grid area 2 (w-1)(h-1)). */
static void test_odd_edges_whole(void)
{
    const char *in[1];
    scene s;
    scene_opts o;
    br_err err;
    cam c;
    double e[3], tg[3];
    bt_params p;
    uint64_t nt = 0, area2 = 0;
    uint32_t *tri, n, k;
    int32_t x;
    in[0] = t_data("asc/colorado_front_range.asc");
    memset(&o, 0, sizeof o);
    if (scene_open(&s, in, 1, &o, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); return; }
    scene_default_view(&s, 50, e, tg);
    CHECK_EQ(scene_camera(&s, e, tg, 50, 640, 400, &c), BR_OK);
    CHECK_EQ(scene_tree(&s, &err), BR_OK);
    /* every finest diamond on the last row holds a height range (ZLO <= ZHI) */
    for (x = 1; x < s.f.w - 1; x++) {
        uint32_t nv = bt_node_at(&s.tree, x, s.f.h - 1);
        CHECK_MSG(BT_NODE_ZLO(nv) <= BT_NODE_ZHI(nv), "x %d", x);
    }
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW;
    p.c = &c;
    p.fr = s.rt.fr;
    p.no_cull = 1;
    CHECK_EQ(bt_count(&s.tree, &p, &nt), BR_OK);
    CHECK_EQ(scene_reserve(&s, (uint32_t)nt + 16, &err), BR_OK);
    CHECK_EQ(bt_extract(&s.tree, &p, &s.mesh), BR_OK);
    tri = malloc(sizeof *tri * 3 * (s.mesh.ns + 1));
    n = bt_strip_to_list(&s.mesh, tri);
    for (k = 0; k < n; k++) {
        const bt_vert *a = &s.mesh.v[tri[3 * k]], *b = &s.mesh.v[tri[3 * k + 1]], *d = &s.mesh.v[tri[3 * k + 2]];
        int64_t cr = (int64_t)(b->x - a->x) * (d->y - a->y) - (int64_t)(b->y - a->y) * (d->x - a->x);
        area2 += (uint64_t)(cr < 0 ? -cr : cr);
    }
    CHECK_EQ(area2, 2 * (uint64_t)(s.f.w - 1) * (uint64_t)(s.f.h - 1));
    free(tri);
    scene_close(&s);
}

/* ------------------------------------------------------------- automatic scale */

/* Grids without georeference: the relief over the extent stays plausible (Puget
 * Sound's real ratio is about 0.027; 0.25 was a field of spikes); georeferenced
 * grids keep scale 1. */
static void test_auto_zscale(void)
{
    static const struct { const char *rel; double lo, hi; } c[] = {
        { "png/ps_height_1k.png", 0.01, 0.05 },   /* relief / extent after scaling */
        { "png/fuji.png", 0.05, 0.3 },
    };
    size_t k;
    for (k = 0; k < sizeof c / sizeof c[0]; k++) {
        const char *in[1];
        scene s;
        scene_opts o;
        br_err err;
        double ratio;
        in[0] = t_data(c[k].rel);
        memset(&o, 0, sizeof o);
        o.quiet = 1;
        if (scene_open(&s, in, 1, &o, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); continue; }
        ratio = (s.zmax_m - s.zmin_m) / s.width_m;
        CHECK_MSG(ratio >= c[k].lo && ratio <= c[k].hi, "%s: relief / extent %g (scale %g)", c[k].rel, ratio, s.zscale);
        scene_close(&s);
    }
    {
        const char *in[1];
        scene s;
        scene_opts o;
        br_err err;
        in[0] = t_data("asc/colorado_front_range.asc");
        memset(&o, 0, sizeof o);
        o.quiet = 1;
        if (scene_open(&s, in, 1, &o, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); return; }
        CHECK(s.zscale == 1);
        scene_close(&s);
    }
}

/* ------------------------------------------------------------- small grids */

/* Writes the n x n block of f at (x0, y0) as an ESRI ASCII grid with 10 m cells
 * (nodata -9999; all void when void_all). */
static int write_asc(const char *path, const hf *f, int32_t x0, int32_t y0, int32_t n, int void_all)
{
    FILE *fp = fopen(path, "w");
    int32_t x, y;
    if (!fp) return -1;
    fprintf(fp, "ncols %d\nnrows %d\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n", n, n);
    for (y = 0; y < n; y++) {
        for (x = 0; x < n; x++) {
            int32_t z = f->z[(size_t)(y0 + y) * f->w + x0 + x];
            fprintf(fp, "%s%ld", x ? " " : "", void_all ? -9999L : (long)hf_z_to_mm(f, z) / 1000);
        }
        fputc('\n', fp);
    }
    return fclose(fp) == 0 ? 0 : -1;
}

/* Share (per mille) of non-sky pixels and their centroid, in per mille of the frame. */
static int terrain_stats(const char *path, int *cx, int *cy)
{
    int w, h, i, n = 0;
    long sx = 0, sy = 0;
    uint8_t *rgb;
    br_err err;
    if (png_read_rgb(path, &w, &h, &rgb, &err) != BR_OK) return -1;
    for (i = 0; i < w * h; i++)
        if (!(rgb[3 * i] == 0x99 && rgb[3 * i + 1] == 0xcc && rgb[3 * i + 2] == 0xff)) { n++; sx += i % w; sy += i / w; }
    free(rgb);
    *cx = n ? (int)(sx * 1000 / n / w) : -1;
    *cy = n ? (int)(sy * 1000 / n / h) : -1;
    return (int)((long)n * 1000 / ((long)w * h));
}

/* Crops of 2x2 to 17x17 samples of hugo_site.asc (metre heights near 1,700 m on
 * 10 m cells: world unit 2^-14 m) with the default view: the terrain is in the
 * frame and near its centre.  An all-void grid is refused. */
static void test_small_grids(void)
{
    static const int32_t sizes[] = { 2, 3, 4, 5, 8, 9, 16, 17 };
    hf f;
    br_err err;
    size_t k;
    char asc[256], png[256], sz[] = "--size", wh[] = "160x100", o[] = "-o";
    char *argv[6];
    if (dem_load(t_data("asc/hugo_site.asc"), NULL, &f, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); return; }
    snprintf(asc, sizeof asc, "%s/small.asc", t_outdir());
    snprintf(png, sizeof png, "%s/small.png", t_outdir());
    argv[0] = asc; argv[1] = sz; argv[2] = wh; argv[3] = o; argv[4] = png; argv[5] = NULL;
    for (k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        int pm, cx = -1, cy = -1;
        CHECK_EQ(write_asc(asc, &f, 32, 3, sizes[k], 0), 0);
        CHECK_EQ(cmd_render(5, argv), 0);
        pm = terrain_stats(png, &cx, &cy);
        CHECK_MSG(pm >= 30, "%dx%d: %d per mille terrain", sizes[k], sizes[k], pm);
        CHECK_MSG(cx > 350 && cx < 650 && cy > 300 && cy < 700, "%dx%d: terrain centred at (%d, %d) per mille",
                  sizes[k], sizes[k], cx, cy);
    }
    CHECK_EQ(write_asc(asc, &f, 32, 3, 4, 1), 0);
    CHECK(cmd_render(5, argv) != 0);
    dem_free(&f);
}

/* ------------------------------------------------------------- voids */

/* --fill-voids: a square hole cut into real terrain (N47E009, 24x24 samples) is
 * filled from its border, inside the border's range and close to the removed
 * heights; a hole farther than DEM_FILL_MAX_DIST from any valid sample stays. */
static void test_fill_voids(void)
{
    hf f;
    br_err err;
    dem_opts o;
    int64_t filled = -1, sum = 0, n = 0;
    int32_t x, y, x0 = 600, y0 = 300, k = 24, lo = INT32_MAX, hi = INT32_MIN, *orig;
    const char *in[1];
    in[0] = "assets/N47E009.hgt.gz";
    memset(&o, 0, sizeof o);
    if (dem_load_many(in, 1, &o, &f, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); return; }
    orig = malloc(sizeof *orig * (size_t)k * k);
    for (y = y0 - 1; y <= y0 + k; y++)
        for (x = x0 - 1; x <= x0 + k; x++) {
            int32_t z = f.z[(size_t)y * f.w + x];
            if (x >= x0 && x < x0 + k && y >= y0 && y < y0 + k) {
                orig[(y - y0) * k + x - x0] = z;
                f.z[(size_t)y * f.w + x] = HF_NODATA;
            } else { lo = z < lo ? z : lo; hi = z > hi ? z : hi; }
        }
    CHECK_EQ(dem_fill_voids(&f, &filled, &err), BR_OK);
    CHECK_EQ(filled, (int64_t)k * k);
    for (y = y0; y < y0 + k; y++)
        for (x = x0; x < x0 + k; x++) {
            int32_t z = f.z[(size_t)y * f.w + x], d = z - orig[(y - y0) * k + x - x0];
            CHECK(z >= lo && z <= hi);
            sum += d < 0 ? -d : d;
            n++;
        }
    /* mean error against the removed heights, m (the hole spans 1.5 km of hills) */
    CHECK_MSG(sum <= 60 * n, "mean |filled - original| %lld m", (long long)(sum / n));
    dem_free(&f);
    free(orig);
    /* out of reach: a 300 x 300 void in the middle of a 301 x 301 grid of one valid ring */
    {
        hf g;
        int32_t *z = malloc(sizeof *z * 401 * 401);
        memset(&g, 0, sizeof g);
        g.w = g.h = 401; g.z = z; g.z_num = g.z_den = 1; g.dx_um = g.dy_um = 1000000;
        for (y = 0; y < 401; y++)
            for (x = 0; x < 401; x++) z[y * 401 + x] = (x == 0 || y == 0 || x == 400 || y == 400) ? 100 : HF_NODATA;
        CHECK_EQ(dem_fill_voids(&g, &filled, &err), BR_OK);
        CHECK_EQ(z[200 * 401 + 200], HF_NODATA);     /* 200 samples from the ring */
        CHECK_EQ(z[50 * 401 + 50], 100);
        CHECK(filled > 0 && filled < 399 * 399);
        free(z);
    }
    /* through the reader flag */
    o.fill_voids = 1;
    o.filled_out = &filled;
    in[0] = t_data("asc/hugo_site.asc");
    if (dem_load_many(in, 1, &o, &f, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); return; }
    CHECK_EQ(filled, 2028);
    dem_free(&f);
}

/* One rule for voids, the bitree's: a hole.  --full used to draw a void sample at
 * 0 m, a pit; looking straight down into a hole cut into hugo_site, its centre
 * shows the sky in both paths. */
static void test_void_is_hole(void)
{
    hf f;
    br_err err;
    char asc[256], png[256], sz[] = "--size", wh[] = "64x64", o[] = "-o", camo[] = "--camera";
    char cv[] = "80,80,2400,80,80.5,1600", fov[] = "--fov", fv[] = "10", full[] = "--full";
    char nw[] = "--no-water", nf[] = "--no-fog";       /* the flat sky colour */
    char *argv[12];
    int pass;
    if (dem_load(t_data("asc/hugo_site.asc"), NULL, &f, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); return; }
    snprintf(asc, sizeof asc, "%s/hole.asc", t_outdir());
    snprintf(png, sizeof png, "%s/hole.png", t_outdir());
    {
        /* the 17 x 17 valid block of test_small_grids with its 5 x 5 centre void */
        FILE *fp = fopen(asc, "w");
        int32_t x, y;
        CHECK(fp != NULL);
        if (!fp) { dem_free(&f); return; }
        fprintf(fp, "ncols 17\nnrows 17\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n");
        for (y = 0; y < 17; y++) {
            for (x = 0; x < 17; x++) {
                long z = (long)hf_z_to_mm(&f, f.z[(size_t)(3 + y) * f.w + 32 + x]) / 1000;
                fprintf(fp, "%s%ld", x ? " " : "", (x >= 6 && x <= 10 && y >= 6 && y <= 10) ? -9999L : z);
            }
            fputc('\n', fp);
        }
        fclose(fp);
    }
    dem_free(&f);
    for (pass = 0; pass < 2; pass++) {
        uint8_t *rgb;
        int w, h;
        argv[0] = asc; argv[1] = sz; argv[2] = wh; argv[3] = o; argv[4] = png; argv[5] = camo; argv[6] = cv;
        argv[7] = fov; argv[8] = fv; argv[9] = nw; argv[10] = nf; argv[11] = full;
        CHECK_EQ(cmd_render(pass ? 12 : 11, argv), 0);
        if (png_read_rgb(png, &w, &h, &rgb, &err) != BR_OK) { CHECK(0); continue; }
        CHECK_MSG(rgb[3 * (32 * w + 32)] == 0x99 && rgb[3 * (32 * w + 32) + 1] == 0xcc && rgb[3 * (32 * w + 32) + 2] == 0xff,
                  "%s: the hole shows #%02x%02x%02x", pass ? "--full" : "bitree", rgb[3 * (32 * w + 32)],
                  rgb[3 * (32 * w + 32) + 1], rgb[3 * (32 * w + 32) + 2]);
        CHECK(rgb[0] != 0x99 || rgb[1] != 0xcc);        /* the terrain around it is drawn */
        free(rgb);
    }
}

int main(void)
{
    T_RUN(test_world_height);
    T_RUN(test_line_triangles_draw_nothing);
    T_RUN(test_line_triangles_void_free);
    T_RUN(test_odd_edges_whole);
    T_RUN(test_auto_zscale);
    T_RUN(test_small_grids);
    T_RUN(test_fill_voids);
    T_RUN(test_void_is_hole);
    return t_finish();
}
