/* tests/test_terrain.c — the per-sample shading cache of raster/terrain.h on real
 * terrain (a 400 x 300 crop of N47E009, Lake Constance's south shore): the view
 * meshes of a moving camera with geomorphing on (vertices between fictitious and
 * real heights) get the same vertex bytes with the cache as without it, whether set
 * up serially (rt_from_mesh) or in ranges plus the serial pending pass (the threads'
 * form, with ranges cut anywhere); once a sample's level is cached no vertex on it is
 * left pending, whatever its height; heights outside the table and void samples; the
 * cache's stated size; the strip of such meshes drawn as a list of its triangles; and
 * the clipper's polygons made once a frame. */
#include <stdint.h>
#include <string.h>
#include "tests/test.h"
#include "tests/support/btcheck.h"
#include "core/cam.h"
#include "platform/load.h"
#include "raster/terrain.h"

static hf full, crop;
static bt_tree tree;
static void *tree_mem;
static int have;

static int load(void)
{
    int32_t x, y;
    void *scr;
    if (have) return have > 0;
    have = -1;
    if (btc_load("hgt/N47E009.hgt", &full)) return 0;
    crop = full;
    crop.w = 400; crop.h = 300;
    crop.z = malloc((size_t)crop.w * crop.h * 4);
    for (y = 0; y < crop.h; y++)
        for (x = 0; x < crop.w; x++) crop.z[(size_t)y * crop.w + x] = full.z[(size_t)(y + 100) * full.w + x + 300];
    tree_mem = malloc(bt_mem_size(crop.w, crop.h));
    scr = malloc(bt_scratch_size(crop.w, crop.h));
    if (bt_build(&tree, &crop, BT_METRIC_EXACT, tree_mem, bt_mem_size(crop.w, crop.h), scr,
                 bt_scratch_size(crop.w, crop.h)) != BR_OK) { free(scr); return 0; }
    free(scr);
    have = 1;
    return 1;
}

static void scene_pair(rt_scene *a, rt_scene *b, rs_ramp *ramp)
{
    fx_q14 sun[3];
    rs_ramp_default(ramp, hf_z_to_mm(&crop, 395), hf_z_to_mm(&crop, 2500));
    rs_sun_dir(315000, 45000, sun);
    CHECK_EQ(rt_scene_init(a, &crop, ramp, sun, 4915), BR_OK);
    CHECK_EQ(rt_scene_init(b, &crop, ramp, sun, 4915), BR_OK);
}

static int same_vertex(const rs_vertex *p, const rs_vertex *q)
{
    return p->p[0] == q->p[0] && p->p[1] == q->p[1] && p->p[2] == q->p[2] && p->rgb == q->rgb &&
           p->uv[0] == q->uv[0] && p->uv[1] == q->uv[1];
}

static void test_cache_same_bytes(void)
{
    rt_scene ref, sc;
    rs_ramp ramp;
    bt_params p;
    bt_mesh m;
    cam c;
    void *mesh_mem = NULL, *cache;
    rs_vertex *want, *got;
    uint32_t i, k, nmorph = 0, nfict = 0;
    if (!load()) { CHECK(0); return; }
    scene_pair(&ref, &sc, &ramp);
    cache = malloc(rt_cache_mem_size(&sc));
    CHECK_EQ(rt_scene_cache(&sc, cache, rt_cache_mem_size(&sc)), BR_OK);
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW; p.fr = ref.fr; p.c = &c; p.hyst_q8 = 64; p.morph_q8 = 128; p.pixel_err_q8 = 256;
    want = malloc(sizeof *want * 200000);
    got = malloc(sizeof *got * 200000);
    for (k = 0; k < 5; k++) {
        /* metres -> world units: eye 2 km up at the south-west, moving 20 m east a frame */
        int32_t eye[3], tgt[3], us = ref.shift;
        uint32_t cut[4];
        eye[0] = (2000 + 20 * (int32_t)k) << us; eye[1] = 1000 << us; eye[2] = 2500 << us;
        tgt[0] = (12000 + 20 * (int32_t)k) << us; tgt[1] = 9000 << us; tgt[2] = 400 << us;
        CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, 320, 240, 1 << us, 60000 << us), BR_OK);
        if (k == 0) CHECK_EQ(btc_extract(&tree, &p, 200000, &m, &mesh_mem), 0);
        else CHECK_EQ(bt_extract(&tree, &p, &m), BR_OK);
        if (m.nv > 200000) { CHECK(0); break; }
        rt_from_mesh(&ref, &m, want);
        for (i = 0; i < m.nv; i++) {
            int32_t zs = crop.z[(size_t)m.v[i].y * crop.w + m.v[i].x];
            nmorph += m.v[i].z != zs;
            nfict += m.v[i].state == BT_F;
        }
        /* odd frames: the serial form; even frames: ranges cut at uneven points */
        if (k & 1) rt_from_mesh(&sc, &m, got);
        else {
            cut[0] = 0; cut[1] = m.nv / 3; cut[2] = m.nv / 3 + 7 > m.nv ? m.nv : m.nv / 3 + 7; cut[3] = m.nv;
            for (i = 0; i < 3; i++) rt_from_mesh_range(&sc, &m, cut[i], cut[i + 1] - cut[i], got);
            rt_from_mesh_pending(&sc, &m, got);
        }
        for (i = 0; i < m.nv && same_vertex(&want[i], &got[i]); i++) {}
        CHECK_MSG(i == m.nv, "frame %u vertex %u of %u differs", k, i, m.nv);
        /* every sample of this mesh is cached now: no vertex is left pending */
        rt_from_mesh_range(&sc, &m, 0, m.nv, got);
        for (i = 0; i < m.nv && got[i].rgb != RT_PENDING && same_vertex(&want[i], &got[i]); i++) {}
        CHECK_MSG(i == m.nv, "frame %u vertex %u pending or different after the fill", k, i);
    }
    printf("5 frames: %u vertices off their real height (%u fictitious)\n", nmorph, nfict);
    CHECK(nmorph > 100);   /* the frames exercise heights between real ones */
    free(mesh_mem); free(want); free(got); free(cache);
}

/* Draws frame f whole, one band of f->h rows, into fresh buffers; returns the colour. */
static uint8_t *draw_whole(rs_frame *f)
{
    const size_t bpp = f->fmt == RS_FMT_RGB565 ? 2 : 4;
    uint8_t *col = calloc((size_t)f->w * (size_t)f->h, bpp);
    void *dep = calloc((size_t)f->w * (size_t)f->h, 4);
    CHECK(col && dep);
    CHECK_EQ(rs_frame_prepare(f), BR_OK);
    CHECK_EQ(rs_draw_band(f, 0, f->h, col, (size_t)f->w * bpp, dep, NULL), BR_OK);
    free(dep);
    return col;
}

/* The view rule's parameters of the drawing tests below: 1 px, hysteresis and geomorph on. */
static void view_params(bt_params *p, const rt_scene *sc, cam *c)
{
    memset(p, 0, sizeof *p);
    p->mode = BT_VIEW; p->fr = sc->fr; p->c = c; p->hyst_q8 = 64; p->morph_q8 = 128; p->pixel_err_q8 = 256;
}

/* A 320x240 frame of mesh m's strip (its vertices v, camera c) in layout lay: 0 XRGB8888
 * with 32-bit depth, 1 RGB565 with 16-bit depth. */
static void view_frame(rs_frame *f, int lay, const bt_mesh *m, const rs_vertex *v, rs_cvert *cache, int16_t *chunks,
                       const cam *c, rs_prim *strip)
{
    memset(f, 0, sizeof *f);
    f->w = 320; f->h = 240;
    f->fmt = lay ? RS_FMT_RGB565 : RS_FMT_XRGB8888; f->depth = lay ? RS_DEPTH16 : RS_DEPTH32;
    f->v = v; f->nv = m->nv; f->cache = cache; f->chunks = chunks; f->clear_rgb = 0x99ccffu;
    cam_viewproj(c, &f->vp);
    strip->kind = RS_STRIP; strip->n = m->ns; strip->idx = m->strip;
    f->prims = strip; f->nprims = 1;
}

/* A view mesh's strip drawn as a list of its triangles, in the strip's order and with
 * each triangle's vertices in the order the strip gives them (odd ones with their first
 * two swapped), degenerate ones left out: the same bytes as the strip, in both pixel
 * layouts.  A renderer that draws the mesh without its strip (a board drawing band by
 * band from the tree, issue 19) relies on it.  The strip's line triangles (a straight
 * rim, three vertices in one column or row of the grid, core/bt_emit.c) are part of
 * it: without them the frames differ where such a sliver wins a depth tie (counted and
 * printed, not required). */
static void test_strip_as_list(void)
{
    rt_scene sc, unused;
    rs_ramp ramp;
    bt_params p;
    bt_mesh m;
    cam c;
    void *mesh_mem = NULL;
    rs_vertex *v = malloc(sizeof *v * 200000);
    rs_cvert *cache = malloc(sizeof *cache * 200000);
    int16_t *chunks = malloc(rs_chunk_mem_size(&(rs_prim){ RS_LIST, 3u * 400000u, NULL }, 1));
    br_index *list = malloc(sizeof *list * 3 * 400000), *leaves = malloc(sizeof *leaves * 3 * 400000);
    uint32_t k, nline = 0, ntri = 0;
    long leaf_bytes = 0;
    int lay;
    if (!load()) { CHECK(0); return; }
    scene_pair(&sc, &unused, &ramp);
    view_params(&p, &sc, &c);
    for (k = 0; k < 4; k++) {
        /* low over the south shore looking across the crop, 20 m a frame */
        int32_t eye[3], tgt[3], us = sc.shift;
        uint32_t t, nl = 0, nf = 0, ndeg = 0;
        rs_prim strip, lp;
        eye[0] = (3000 + 20 * (int32_t)k) << us; eye[1] = 500 << us; eye[2] = 1200 << us;
        tgt[0] = (9000 + 20 * (int32_t)k) << us; tgt[1] = 12000 << us; tgt[2] = 700 << us;
        CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, 320, 240, 1 << us, 60000 << us), BR_OK);
        if (k == 0) CHECK_EQ(btc_extract(&tree, &p, 200000, &m, &mesh_mem), 0);
        else CHECK_EQ(bt_extract(&tree, &p, &m), BR_OK);
        if (m.nv > 200000 || m.ns > 3 * 400000) { CHECK(0); break; }
        rt_from_mesh(&sc, &m, v);
        for (t = 0; t + 2 < m.ns; t++) {       /* every triangle but the degenerate ones */
            br_index a = m.strip[t], b = m.strip[t + 1];
            const br_index d = m.strip[t + 2];
            if (t & 1) { const br_index x = a; a = b; b = x; }
            if (a == b || b == d || a == d) { ndeg++; continue; }
            list[nl++] = a; list[nl++] = b; list[nl++] = d;
        }
        {   /* the leaves: the referee's decoding, without its zero-area (line and degenerate) ones */
            mc_vert *mv = NULL;
            int32_t *ms = NULL, *tri = NULL;
            int64_t nt = 0, nz = 0, i;
            CHECK_EQ(btc_decode(&m, &mv, &ms, &tri, &nt, &nz), 0);
            for (i = 0; i < 3 * nt; i++) leaves[nf++] = (br_index)tri[i];
            nline += (uint32_t)nz - ndeg;
            free(mv); free(ms); free(tri);
        }
        ntri += nl / 3;
        for (lay = 0; lay < 2; lay++) {
            rs_frame f;
            uint8_t *want, *got;
            const size_t n = (size_t)320 * 240 * (lay ? 2 : 4);
            size_t i;
            view_frame(&f, lay, &m, v, cache, chunks, &c, &strip);
            want = draw_whole(&f);
            lp.kind = RS_LIST; lp.n = nl; lp.idx = list;
            f.prims = &lp;
            got = draw_whole(&f);
            CHECK_MSG(!memcmp(want, got, n), "frame %u layout %d: the strip's triangles as a list differ", k, lay);
            free(got);
            lp.n = nf; lp.idx = leaves;
            got = draw_whole(&f);
            for (i = 0; i < n; i++) leaf_bytes += want[i] != got[i];
            free(got);
            free(want);
        }
    }
    printf("4 frames: %u triangles, %u of them line triangles; without those, %ld bytes differ\n", ntri, nline,
           leaf_bytes);
    CHECK(nline > 0);   /* the frames exercise them */
    free(mesh_mem); free(v); free(cache); free(chunks); free(list); free(leaves);
}

/* Frame f drawn in bands of `rows` rows (the last one shorter) into fresh buffers, the
 * band's stats summed into *clipped; returns the colour. */
static uint8_t *draw_bands(rs_frame *f, int32_t rows, uint32_t *clipped)
{
    const size_t bpp = f->fmt == RS_FMT_RGB565 ? 2 : 4, dbp = f->depth == RS_DEPTH16 ? 2 : 4;
    uint8_t *col = calloc((size_t)f->w * (size_t)f->h, bpp), *dep = calloc((size_t)f->w * (size_t)f->h, dbp);
    int32_t y0;
    CHECK(col && dep);
    CHECK_EQ(rs_frame_prepare(f), BR_OK);
    for (y0 = 0; y0 < f->h; y0 += rows) {
        const int32_t n = f->h - y0 < rows ? f->h - y0 : rows;
        rs_band_stats st;
        memset(&st, 0, sizeof st);
        CHECK_EQ(rs_draw_band(f, y0, n, col + (size_t)y0 * (size_t)f->w * bpp, (size_t)f->w * bpp,
                              dep + (size_t)y0 * (size_t)f->w * dbp, &st), BR_OK);
        *clipped += st.clipped;
    }
    free(dep);
    return col;
}

/* The clip table (rs_frame.clips): 15 m over the lake, looking along it, the flat
 * lake's large triangles under the camera cross the near plane and show in every band's
 * rows; drawn with their polygons from the table, in
 * bands of 1, 7, 16 and 240 rows, with a table too small for them (the rest clipped per
 * band) and with none, both pixel layouts: the same bytes, and the same count of clipped
 * triangles per band.  The table must have held such triangles, in the order the draw
 * hands them over (a strip's odd triangles with their first two swapped: a polygon of
 * another first vertex draws other bytes, which this test would see). */
static void test_clip_table(void)
{
    rt_scene sc, unused;
    rs_ramp ramp;
    bt_params p;
    bt_mesh m;
    cam c;
    void *mesh_mem = NULL;
    rs_vertex *v = malloc(sizeof *v * 200000);
    rs_cvert *cache = malloc(sizeof *cache * 200000);
    int16_t *chunks = malloc(rs_chunk_mem_size(&(rs_prim){ RS_STRIP, 3u * 400000u, NULL }, 1));
    rs_clip_poly *clips = malloc(rs_clip_mem_size(128));
    int32_t eye[3], tgt[3], us;
    int lay;
    if (!load()) { CHECK(0); return; }
    scene_pair(&sc, &unused, &ramp);
    us = sc.shift;
    view_params(&p, &sc, &c);
    eye[0] = 1900 << us; eye[1] = 830 << us; eye[2] = 407 << us;    /* 15 m over the lake */
    tgt[0] = 100 << us; tgt[1] = 900 << us; tgt[2] = 392 << us;
    CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, 320, 240, 1 << us, 60000 << us), BR_OK);
    CHECK_EQ(btc_extract(&tree, &p, 200000, &m, &mesh_mem), 0);
    if (m.nv > 200000 || m.ns > 3 * 400000) { CHECK(0); return; }
    rt_from_mesh(&sc, &m, v);
    for (lay = 0; lay < 2; lay++) {
        static const int32_t rows[4] = { 1, 7, 16, 240 };
        static const uint32_t caps[3] = { 0, 128, 2 };
        rs_frame f;
        rs_prim strip;
        uint8_t *want;
        uint32_t want_clipped = 0, k, i, held = 0;
        const size_t n = (size_t)320 * 240 * (lay ? 2 : 4);
        int r;
        view_frame(&f, lay, &m, v, cache, chunks, &c, &strip);
        want = draw_bands(&f, 16, &want_clipped);              /* no table */
        for (k = 0; k < 3; k++)
            for (r = 0; r < 4; r++) {
                uint32_t clipped = 0, cl16 = 0;
                uint8_t *got;
                f.clips = caps[k] ? clips : NULL;
                f.clip_cap = caps[k];
                got = draw_bands(&f, rows[r], &clipped);
                CHECK_MSG(!memcmp(want, got, n), "layout %d, table of %u, bands of %d rows: other bytes", lay,
                          caps[k], rows[r]);
                if (rows[r] == 16) cl16 = clipped;
                if (rows[r] == 16) CHECK_EQ(cl16, want_clipped);
                if (caps[k] == 128 && rows[r] == 16)
                    for (i = 0, held = 0; i < 128; i++) {
                        const rs_clip_poly *e = &clips[i];
                        uint32_t t;
                        if (e->owner != &f) continue;
                        held++;
                        for (t = 0; t + 2 < m.ns; t++) {        /* a triangle in the draw's order */
                            const br_index a = m.strip[t + (t & 1)], b = m.strip[t + 1 - (t & 1)];
                            if (e->ia == a && e->ib == b && e->ic == m.strip[t + 2]) break;
                        }
                        CHECK_MSG(t + 2 < m.ns, "entry %u (%u %u %u) is no triangle in the draw's order", i, e->ia,
                                  e->ib, e->ic);
                    }
                free(got);
            }
        printf("layout %d: %u polygons in the table, %u clipped triangles drawn in 16-row bands\n", lay, held,
               want_clipped);
        CHECK(held >= 8);       /* the view exercises the table */
        free(want);
    }
    free(mesh_mem); free(v); free(cache); free(chunks); free(clips);
}

/* Heights outside the table (a water level below the lowest sample, one above the
 * highest), a texture (white lit), a void sample, a changed sun after rt_cache_clear,
 * and the stated size. */
static void test_cache_edges(void)
{
    rt_scene ref, sc;
    rs_ramp ramp;
    rs_vertex a, b;
    void *cache;
    int32_t x, y, t, z[4];
    size_t need;
    if (!load()) { CHECK(0); return; }
    scene_pair(&ref, &sc, &ramp);
    need = rt_cache_mem_size(&sc);
    CHECK_EQ(need, (((size_t)crop.w * crop.h * 2 + 3) & ~(size_t)3) + 4 * (size_t)(sc.zhi - sc.zlo + 1));
    cache = malloc(need + 4);
    CHECK_EQ(rt_scene_cache(&sc, cache, need - 1), BR_E_ARG);
    CHECK(sc.lvl == NULL);
    CHECK_EQ(rt_scene_cache(&sc, (uint8_t *)cache + 2, need), BR_E_ARG);
    CHECK_EQ(rt_scene_cache(&sc, cache, need), BR_OK);
    CHECK(sc.nz == sc.zhi - sc.zlo + 1 && sc.ztab != NULL);
    z[0] = sc.zlo - 40; z[1] = sc.zlo; z[2] = sc.zhi; z[3] = sc.zhi + 300;
    for (t = 0; t < 3; t++) {
        if (t == 1) { ref.tex_w = sc.tex_w = 640; ref.tex_h = sc.tex_h = 480; }
        if (t == 2) {   /* a new sun: the levels are stale until rt_cache_clear */
            ref.tex_w = sc.tex_w = ref.tex_h = sc.tex_h = 0;
            rs_sun_dir(100000, 20000, ref.sun);
            rs_sun_dir(100000, 20000, sc.sun);
            rt_cache_clear(&sc);
        }
        for (y = 0; y < crop.h; y += 7)
            for (x = 0; x < crop.w; x += 5) {
                int i;
                for (i = 0; i < 5; i++) {
                    int32_t zz = i < 4 ? z[i] : crop.z[(size_t)y * crop.w + x];
                    rt_vertex(&ref, x, y, zz, &a);
                    rt_vertex(&sc, x, y, zz, &b);
                    if (!same_vertex(&a, &b)) { CHECK_MSG(0, "pass %d sample %d,%d height %d", t, x, y, zz); return; }
                    if (t == 1 && (b.uv[0] != (int64_t)x * 640 * 256 / (crop.w - 1) ||
                                   b.uv[1] != (int64_t)y * 480 * 256 / (crop.h - 1))) {
                        CHECK_MSG(0, "uv of sample %d,%d", x, y);
                        return;
                    }
                }
            }
    }
    {   /* a void sample: the ramp's nodata colour, and no level */
        int32_t keep = crop.z[5 * crop.w + 9];
        crop.z[5 * crop.w + 9] = HF_NODATA;
        rt_vertex(&sc, 9, 5, 0, &b);
        CHECK_EQ(b.rgb, ramp.nv_rgb);
        CHECK_EQ(sc.lvl[5 * crop.w + 9], 0);
        crop.z[5 * crop.w + 9] = keep;
    }
    CHECK_EQ(rt_scene_cache(&sc, NULL, 0), BR_OK);
    CHECK(sc.lvl == NULL && sc.ztab == NULL && sc.nz == 0);
    free(cache);
}

int main(void)
{
    T_RUN(test_cache_same_bytes);
    T_RUN(test_cache_edges);
    T_RUN(test_strip_as_list);
    T_RUN(test_clip_table);
    if (have > 0) dem_free(&full);
    free(crop.z);
    free(tree_mem);
    return t_finish();
}
