/* tests/test_stream.c — the streamed walk (core/bitree.h bt_stream_*) and the stream pass
 * (raster/terrain_stream.h) on real terrain, two crops of N47E009 (Lake Constance's south
 * shore; the board's Alpine Rhine valley) at 11 cameras (cams below), geomorph on:
 * - the walk's leaves over the whole viewport are the real triangles of bt_extract's
 *   mesh without hysteresis, in its strip's order, apex first, same heights;
 * - the stream pass's frames are that list drawn whole, byte for byte, for bands of
 *   240, 16 and 7 rows and batches of 1, 256 and 8192 triangles, in both pixel layouts
 *   (a band that missed a leaf reaching its rows, or a batch that mixed up its
 *   vertices, differs);
 * - what it refuses. */
#include <stdint.h>
#include <string.h>
#include "tests/test.h"
#include "tests/support/btcheck.h"
#include "core/cam.h"
#include "raster/terrain_stream.h"

#define W 320
#define H 240
#define MAXT 200000

/* Two crops of N47E009: the south shore of Lake Constance (hills, the lake's flat
 * water) and the board's (mcu/bake.c: the Alpine Rhine valley and the Raetikon) */
typedef struct site {
    int32_t x0, y0, w, h;
    hf crop;
    bt_tree tree;
    void *mem;
} site;
static site sites[2] = { { 300, 100, 400, 300, { 0 }, { 0 }, NULL }, { 560, 880, 257, 257, { 0 }, { 0 }, NULL } };
static hf full;
static int have;

static int load(void)
{
    int32_t x, y, i;
    void *scr;
    if (have) return have > 0;
    have = -1;
    if (btc_load("hgt/N47E009.hgt", &full)) return 0;
    for (i = 0; i < 2; i++) {
        site *st = &sites[i];
        hf *f = &st->crop;
        *f = full;
        f->w = st->w; f->h = st->h;
        f->z = malloc((size_t)f->w * f->h * 4);
        for (y = 0; y < f->h; y++)
            for (x = 0; x < f->w; x++) f->z[(size_t)y * f->w + x] = full.z[(size_t)(y + st->y0) * full.w + x + st->x0];
        st->mem = malloc(bt_mem_size(f->w, f->h));
        scr = malloc(bt_scratch_size(f->w, f->h));
        if (bt_build(&st->tree, f, BT_METRIC_EXACT, st->mem, bt_mem_size(f->w, f->h), scr,
                     bt_scratch_size(f->w, f->h)) != BR_OK) { free(scr); return 0; }
        free(scr);
    }
    have = 1;
    return 1;
}

typedef struct leaves { int32_t *p; uint32_t n; } leaves;   /* 9 ints a leaf: x, y, z thrice */

static void keep(void *user, bt_svert *a, bt_svert *b, bt_svert *c)
{
    leaves *l = (leaves *)user;
    int32_t *q = &l->p[9 * (size_t)l->n++];
    q[0] = a->x; q[1] = a->y; q[2] = a->z; q[3] = b->x; q[4] = b->y; q[5] = b->z; q[6] = c->x; q[7] = c->y; q[8] = c->z;
}

/* Mesh m's real triangles in strip order (odd ones' first two swapped), without the
 * repeated-index and collinear (line) ones, each turned (winding kept) to start at its
 * right angle: into list (indices) and l (points) */
static void mesh_leaves(const bt_mesh *m, br_index *list, leaves *l)
{
    uint32_t t;
    l->n = 0;
    for (t = 0; t + 2 < m->ns; t++) {
        br_index v[3], r;
        int k, j;
        const bt_vert *p[3];
        v[0] = m->strip[t]; v[1] = m->strip[t + 1]; v[2] = m->strip[t + 2];
        if (t & 1) { r = v[0]; v[0] = v[1]; v[1] = r; }
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
        for (k = 0; k < 3; k++) p[k] = &m->v[v[k]];
        if ((int64_t)(p[1]->x - p[0]->x) * (p[2]->y - p[0]->y) == (int64_t)(p[1]->y - p[0]->y) * (p[2]->x - p[0]->x))
            continue;
        for (k = 0; k < 3; k++) {   /* the right angle: the legs' dot product is 0 */
            const bt_vert *o = p[k], *u = p[(k + 1) % 3], *w = p[(k + 2) % 3];
            if ((int64_t)(u->x - o->x) * (w->x - o->x) + (int64_t)(u->y - o->y) * (w->y - o->y) == 0) break;
        }
        CHECK(k < 3);
        for (j = 0; j < 3; j++) {
            const bt_vert *q = p[(k + j) % 3];
            int32_t *o = &l->p[9 * (size_t)l->n + 3 * j];
            list[3 * l->n + j] = v[(k + j) % 3];
            o[0] = q->x; o[1] = q->y; o[2] = q->z;
        }
        l->n++;
    }
}

/* Layouts: 0 XRGB8888 with 32-bit depth, 1 RGB565 with 16-bit depth, 2 and 3 the same
 * colours without depth (RS_DEPTH_NONE) */
static void frame_of(rs_frame *f, int lay, const cam *c)
{
    memset(f, 0, sizeof *f);
    f->w = W; f->h = H;
    f->fmt = lay & 1 ? RS_FMT_RGB565 : RS_FMT_XRGB8888;
    f->depth = lay & 2 ? RS_DEPTH_NONE : lay ? RS_DEPTH16 : RS_DEPTH32;
    f->clear_rgb = 0x99ccffu;
    cam_viewproj(c, &f->vp);
}

typedef struct grab { uint8_t *px; size_t row; } grab;
static br_status grab_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    grab *g = (grab *)user;
    int32_t y;
    for (y = 0; y < rows; y++) memcpy(g->px + (size_t)(y0 + y) * g->row, (const uint8_t *)px + (size_t)y * stride, g->row);
    return BR_OK;
}

/* The stream pass's frame for layout lay in bands of `rows`, batches of cap_t triangles */
static uint8_t *draw_stream(bt_stream *walk, const rt_scene *sc, const cam *c, int lay, int32_t rows, uint32_t cap_v,
                            uint32_t cap_t)
{
    rt_stream s;
    rs_frame f;
    rs_pipe pipe;
    grab g;
    void *mem = malloc(rt_stream_mem_size(cap_v, cap_t)), *band;
    memset(&s, 0, sizeof s);
    CHECK_EQ(rt_stream_init(&s, cap_v, cap_t, mem, rt_stream_mem_size(cap_v, cap_t)), BR_OK);
    s.scene = sc; s.walk = walk;
    frame_of(&f, lay, c);
    CHECK_EQ(rt_stream_pipe(&s, c, f.fmt, f.depth, f.clear_rgb, &pipe), BR_OK);
    band = malloc(rs_pipe_mem_size(&pipe, rows));
    g.row = (size_t)W * (lay & 1 ? 2 : 4);
    g.px = calloc(H, g.row);
    CHECK_EQ(rs_pipe_run(&pipe, rows, band, rs_pipe_mem_size(&pipe, rows), grab_band, &g, NULL), BR_OK);
    free(band); free(mem);
    return g.px;
}

/* The crop's height in metres at (x, y) metres (its sample there) */
static int32_t ground(const rt_scene *sc, int32_t x, int32_t y)
{
    const hf *f = sc->f;
    const int32_t col = (int32_t)(((int64_t)x << sc->shift) / sc->fr.sx);
    const int32_t row = f->h - 1 - (int32_t)(((int64_t)y << sc->shift) / sc->fr.sy);
    return (int32_t)hf_z_to_mm(f, f->z[(size_t)row * f->w + col]) / 1000;
}

/* Cameras: the site, eye and target in metres over its crop (x east from its west
 * edge, y north from its south edge), the near plane in metres and the screen error in
 * 1/256 pixel.  The shore: low over it looking across, 20 m a frame; high looking down
 * steeply; grazing towards the far edge (the far terrain crowds into a few rows); two
 * metres above the ground (heights 0; the near plane cuts triangles); looking along the
 * shore.  The board's: frames 0, 4, 7 and 9 of mcu/board-path.cam, as the board draws
 * them (1.75 px, its near plane). */
#define NCAM 11
static const int32_t cams[NCAM][9] = {
    { 0, 3000, 500, 1200, 9000, 12000, 700, 1, 256 },
    { 0, 3020, 500, 1200, 9020, 12000, 700, 1, 256 },
    { 0, 3040, 500, 1200, 9040, 12000, 700, 1, 256 },
    { 0, 12000, 8000, 4000, 13000, 14000, 400, 1, 256 },
    { 0, 2000, 1000, 700, 24000, 27000, 600, 1, 256 },
    { 0, 15000, 20000, 0, 16000, 22000, 0, 1, 256 },
    { 0, 500, 14000, 600, 24000, 15000, 400, 1, 256 },
    { 1, 2500, 20000, 1900, 12000, 4000, 1300, 9, 448 },
    { 1, 3011, 19140, 1900, 12511, 3140, 1300, 9, 448 },
    { 1, 3393, 18495, 1900, 12893, 2495, 1300, 9, 448 },
    { 1, 3649, 18065, 1900, 13149, 2065, 1300, 9, 448 },
};

/* Camera k of cams: its crop's scene (sc, ramp), view parameters p and camera c */
static site *cam_setup(int k, rt_scene *sc, rs_ramp *ramp, bt_params *p, cam *c)
{
    site *st = &sites[cams[k][0]];
    const hf *crop = &st->crop;
    fx_q14 sun[3];
    int32_t eye[3], tgt[3], us, j;
    rs_sun_dir(315000, 45000, sun);
    rs_ramp_default(ramp, hf_z_to_mm(crop, 395), hf_z_to_mm(crop, 2500));
    CHECK_EQ(rt_scene_init(sc, crop, ramp, sun, 4915), BR_OK);
    us = sc->shift;
    memset(p, 0, sizeof *p);
    p->mode = BT_VIEW; p->fr = sc->fr; p->c = c; p->morph_q8 = 128; p->pixel_err_q8 = cams[k][8];
    for (j = 0; j < 3; j++) { eye[j] = cams[k][1 + j] << us; tgt[j] = cams[k][4 + j] << us; }
    if (cams[k][3] == 0) {  /* heights 0: 2 m above the ground there, looking at the ground */
        eye[2] = (ground(sc, cams[k][1], cams[k][2]) + 2) << us;
        tgt[2] = ground(sc, cams[k][4], cams[k][5]) << us;
    }
    CHECK_EQ(cam_look_at(c, eye, tgt, 60000, W, H, cams[k][7] << us, 60000 << us), BR_OK);
    return st;
}

static void test_stream_frames(void)
{
    rt_scene sc;
    rs_ramp ramp;
    bt_params p;
    bt_mesh m;
    cam c;
    bt_stream *walk, *walk_planes;
    void *mesh_mem = NULL, *wmem, *wmem_planes;
    leaves want = { malloc(sizeof(int32_t) * 9 * MAXT), 0 }, got = { malloc(sizeof(int32_t) * 9 * MAXT), 0 };
    br_index *list = malloc(sizeof *list * 3 * MAXT);
    rs_vertex *v = malloc(sizeof *v * MAXT);
    rs_cvert *cache = malloc(sizeof *cache * MAXT);
    int16_t *chunks = malloc(rs_chunk_mem_size(&(rs_prim){ RS_LIST, 3u * MAXT, NULL }, 1));
    uint32_t k, nmorph = 0, ntri = 0;
    uint32_t nslot;
    if (!load()) { CHECK(0); return; }
    nslot = sites[0].tree.nslot > sites[1].tree.nslot ? sites[0].tree.nslot : sites[1].tree.nslot;
    /* two weight caches: 16 entries (most partial weights computed again) and 512 */
    wmem = malloc(bt_stream_mem_size(16, nslot));
    wmem_planes = malloc(bt_stream_mem_size(512, nslot));
    CHECK_EQ(bt_stream_init(&walk, 16, nslot, wmem, bt_stream_mem_size(16, nslot)), BR_OK);
    CHECK_EQ(bt_stream_init(&walk_planes, 512, nslot, wmem_planes, bt_stream_mem_size(512, nslot)), BR_OK);
    for (k = 0; k < NCAM; k++) {
        site *st = cam_setup((int)k, &sc, &ramp, &p, &c);
        const hf *crop = &st->crop;
        bt_tree *tree = &st->tree;
        int32_t lay;
        int r;
        uint32_t i;
        if (k == 0) CHECK_EQ(btc_extract(tree, &p, MAXT, &m, &mesh_mem), 0);
        else CHECK_EQ(bt_extract(tree, &p, &m), BR_OK);
        if (m.nv > MAXT || m.ns > MAXT) { CHECK(0); break; }
        mesh_leaves(&m, list, &want);
        CHECK_EQ(bt_stream_frame(walk, tree, &p), BR_OK);
        CHECK_EQ(bt_stream_frame(walk_planes, tree, &p), BR_OK);
        for (r = 0; r < 2; r++) {
            got.n = 0;
            CHECK_EQ(bt_stream_walk(r ? walk_planes : walk, NULL, keep, &got), got.n);
            CHECK_EQ(got.n, want.n);
            for (i = 0; i < want.n && !memcmp(&want.p[9 * i], &got.p[9 * i], 36); i++) {}
            CHECK_MSG(i == want.n, "frame %u: leaf %u of %u differs from the mesh's (cache %d)", k, i, want.n, r ? 512 : 16);
        }
        for (i = 0; i < m.nv; i++) nmorph += m.v[i].z != crop->z[(size_t)m.v[i].y * crop->w + m.v[i].x];
        ntri += want.n;
        rt_from_mesh(&sc, &m, v);
        for (lay = 0; lay < 2; lay++) {
            static const int32_t rows[3] = { H, 16, 7 };
            static const uint32_t capv[3] = { 3, 128, 4096 }, capt[3] = { 1, 256, 8192 };
            const size_t n = (size_t)W * H * (lay ? 2 : 4);
            rs_frame f;
            rs_prim lp;
            uint8_t *ref;
            int b;
            frame_of(&f, lay, &c);
            f.v = v; f.nv = m.nv; f.cache = cache; f.chunks = chunks;
            lp.kind = RS_LIST; lp.n = 3 * want.n; lp.idx = list;
            f.prims = &lp; f.nprims = 1;
            ref = calloc(n, 1);
            {
                void *dep = calloc((size_t)W * H, 4);
                CHECK_EQ(rs_frame_prepare(&f), BR_OK);
                CHECK_EQ(rs_draw_band(&f, 0, H, ref, n / H, dep, NULL), BR_OK);
                free(dep);
            }
            for (r = 0; r < 3; r++)
                for (b = 0; b < 3; b++) {
                    uint8_t *px = draw_stream((r + b) & 1 ? walk : walk_planes, &sc, &c, lay, rows[r], capv[b], capt[b]);
                    CHECK_MSG(!memcmp(px, ref, n), "frame %u layout %d: %d-row bands, batches of %u differ from the list",
                              k, lay, rows[r], capt[b]);
                    free(px);
                }
            free(ref);
        }
    }
    printf("%d frames: %u leaves, %u vertices off their real height\n", NCAM, ntri, nmorph);
    CHECK(ntri > 10000 && nmorph > 300);
    free(mesh_mem); free(wmem); free(wmem_planes); free(want.p); free(got.p); free(list); free(v); free(cache); free(chunks);
}

/* Grids with voids inside the data (core/bitree.h: a leaf over a void is left out): the
 * walk's leaves are the mesh's, point for point, and a frame of 16-row bands is the list
 * drawn whole, at three cameras over each DEM. */
static void test_stream_voids(void)
{
    static const char *const dems[2] = { "tif/mt_rainier_90m.tif", "asc/hugo_site.asc" };
    leaves want = { malloc(sizeof(int32_t) * 9 * MAXT), 0 }, got = { malloc(sizeof(int32_t) * 9 * MAXT), 0 };
    br_index *list = malloc(sizeof *list * 3 * MAXT);
    rs_vertex *v = malloc(sizeof *v * MAXT);
    rs_cvert *cache = malloc(sizeof *cache * MAXT);
    int16_t *chunks = malloc(rs_chunk_mem_size(&(rs_prim){ RS_LIST, 3u * MAXT, NULL }, 1));
    int d, k;
    uint32_t nleaf = 0;
    for (d = 0; d < 2; d++) {
        hf f;
        bt_tree t;
        bt_mesh m;
        bt_stream *walk;
        rt_scene sc;
        rs_ramp ramp;
        fx_q14 sun[3];
        bt_params p;
        cam c;
        void *tmem, *scr, *wmem, *mesh_mem = NULL;
        int64_t nvoid = 0, i;
        if (btc_load(dems[d], &f)) { CHECK(0); continue; }
        for (i = 0; i < (int64_t)f.w * f.h; i++) nvoid += f.z[i] == HF_NODATA;
        CHECK_MSG(nvoid > 0, "%s: no void", dems[d]);
        tmem = malloc(bt_mem_size(f.w, f.h));
        scr = malloc(bt_scratch_size(f.w, f.h));
        CHECK_EQ(bt_build(&t, &f, BT_METRIC_EXACT, tmem, bt_mem_size(f.w, f.h), scr, bt_scratch_size(f.w, f.h)), BR_OK);
        free(scr);
        wmem = malloc(bt_stream_mem_size(64, t.nslot));
        CHECK_EQ(bt_stream_init(&walk, 64, t.nslot, wmem, bt_stream_mem_size(64, t.nslot)), BR_OK);
        rs_ramp_default(&ramp, 0, 4000000);
        rs_sun_dir(315000, 45000, sun);
        CHECK_EQ(rt_scene_init(&sc, &f, &ramp, sun, 4915), BR_OK);
        for (k = 0; k < 3; k++) {
            /* from the south-west corner at three heights, looking at the middle */
            const int64_t ex = (int64_t)(f.w - 1) * sc.fr.sx, ey = (int64_t)(f.h - 1) * sc.fr.sy;
            const int32_t eye[3] = { (int32_t)(ex / 8 + k * ex / 10), (int32_t)(ey / 10),
                                     (int32_t)((int64_t)(2000 + 800 * k) << sc.shift) };
            const int32_t tgt[3] = { (int32_t)(ex / 2), (int32_t)(ey / 2), (int32_t)((int64_t)1500 << sc.shift) };
            rs_frame fr;
            rs_prim lp;
            uint8_t *ref, *px;
            void *dep;
            uint32_t j;
            CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, W, H, 1 << sc.shift, 1 << 29), BR_OK);
            memset(&p, 0, sizeof p);
            p.mode = BT_VIEW; p.fr = sc.fr; p.c = &c; p.morph_q8 = 128; p.pixel_err_q8 = 256;
            if (k == 0) CHECK_EQ(btc_extract(&t, &p, MAXT, &m, &mesh_mem), 0);
            else CHECK_EQ(bt_extract(&t, &p, &m), BR_OK);
            if (m.nv > MAXT || m.ns > MAXT) { CHECK(0); break; }
            mesh_leaves(&m, list, &want);
            CHECK_EQ(bt_stream_frame(walk, &t, &p), BR_OK);
            got.n = 0;
            (void)bt_stream_walk(walk, NULL, keep, &got);
            CHECK_EQ(got.n, want.n);
            for (j = 0; j < want.n && !memcmp(&want.p[9 * j], &got.p[9 * j], 36); j++) {}
            CHECK_MSG(j == want.n, "%s camera %d: leaf %u of %u differs from the mesh's", dems[d], k, j, want.n);
            nleaf += want.n;
            rt_from_mesh(&sc, &m, v);
            frame_of(&fr, 1, &c);
            fr.v = v; fr.nv = m.nv; fr.cache = cache; fr.chunks = chunks;
            lp.kind = RS_LIST; lp.n = 3 * want.n; lp.idx = list;
            fr.prims = &lp; fr.nprims = 1;
            ref = calloc((size_t)W * H, 2);
            dep = calloc((size_t)W * H, 2);
            CHECK_EQ(rs_frame_prepare(&fr), BR_OK);
            CHECK_EQ(rs_draw_band(&fr, 0, H, ref, (size_t)W * 2, dep, NULL), BR_OK);
            px = draw_stream(walk, &sc, &c, 1, 16, 128, 256);
            CHECK_MSG(!memcmp(px, ref, (size_t)W * H * 2), "%s camera %d: 16-row bands differ from the list", dems[d], k);
            free(px); free(ref); free(dep);
        }
        free(mesh_mem); free(wmem); free(tmem); free(f.z);
    }
    printf("voids: %u leaves over 6 cameras\n", nleaf);
    CHECK(nleaf > 5000);
    free(want.p); free(got.p); free(list); free(v); free(cache); free(chunks);
}

/* Leaves as 9-int records, compared as byte strings (any total order serves to compare
 * two lists as multisets) */
static int cmp_leaf(const void *x, const void *y) { return memcmp(x, y, 36); }

/* Frame `lay` of list l (3 vertices a leaf, shaded by rt_vertex as the stream pass
 * shades them) drawn whole, in reverse order when rev */
static uint8_t *draw_leaves(const rt_scene *sc, const cam *c, const leaves *l, int lay, int rev, rs_vertex *v,
                            rs_cvert *cache, br_index *list, int16_t *chunks)
{
    const size_t n = (size_t)W * H * (lay & 1 ? 2 : 4);
    uint8_t *px = calloc(n, 1);
    void *dep = calloc((size_t)W * H, 4);
    rs_frame f;
    rs_prim lp;
    uint32_t i;
    int j;
    for (i = 0; i < l->n; i++)
        for (j = 0; j < 3; j++) {
            const int32_t *q = &l->p[9 * (size_t)(rev ? l->n - 1 - i : i) + 3 * j];
            rt_vertex(sc, q[0], q[1], q[2], &v[3 * i + j]);
            list[3 * i + j] = (br_index)(3 * i + j);
        }
    frame_of(&f, lay, c);
    f.v = v; f.nv = 3 * l->n; f.cache = cache; f.chunks = chunks;
    lp.kind = RS_LIST; lp.n = 3 * l->n; lp.idx = list;
    f.prims = &lp; f.nprims = 1;
    CHECK_EQ(rs_frame_prepare(&f), BR_OK);
    CHECK_EQ(rs_draw_band(&f, 0, H, px, n / H, lay & 2 ? NULL : dep, NULL), BR_OK);
    free(dep);
    return px;
}

static uint32_t px_differ(const uint8_t *a, const uint8_t *b, int lay)
{
    const size_t sz = lay & 1 ? 2 : 4;
    uint32_t i, d = 0;
    for (i = 0; i < (uint32_t)(W * H); i++) d += memcmp(a + sz * i, b + sz * i, sz) != 0;
    return d;
}

/* Back to front (bt_stream_order): the same leaves as the strip order, in an order that
 * draws without depth what the depth test draws (the frame without depth against the
 * 32-bit depth test's: the few pixels where the test's rounding decides two nearly equal
 * depths; the same leaves in reverse, front to back, differ in many); and the stream
 * pass without depth draws that frame byte for byte in bands of 240, 16 and 7 rows and
 * batches of 1, 256 and 8192 triangles, in both pixel layouts. */
static void test_stream_back_to_front(void)
{
    rt_scene sc;
    rs_ramp ramp;
    bt_params p;
    cam c;
    bt_stream *walk;
    void *wmem;
    leaves strip = { malloc(sizeof(int32_t) * 9 * MAXT), 0 }, btf = { malloc(sizeof(int32_t) * 9 * MAXT), 0 };
    br_index *list = malloc(sizeof *list * 3 * MAXT);
    rs_vertex *v = malloc(sizeof *v * 3 * MAXT);
    rs_cvert *cache = malloc(sizeof *cache * 3 * MAXT);
    int16_t *chunks = malloc(rs_chunk_mem_size(&(rs_prim){ RS_LIST, 3u * MAXT, NULL }, 1));
    uint32_t nslot, nz = 0, nrev = 0, nleaf = 0;
    int k;
    if (!load()) { CHECK(0); return; }
    nslot = sites[0].tree.nslot > sites[1].tree.nslot ? sites[0].tree.nslot : sites[1].tree.nslot;
    wmem = malloc(bt_stream_mem_size(512, nslot));
    CHECK_EQ(bt_stream_init(&walk, 512, nslot, wmem, bt_stream_mem_size(512, nslot)), BR_OK);
    CHECK_EQ(bt_stream_order(walk, 2), BR_E_ARG);
    for (k = 0; k < NCAM; k++) {
        site *st = cam_setup(k, &sc, &ramp, &p, &c);
        uint8_t *z32, *noz, *rev;
        int lay, r, b;
        CHECK_EQ(bt_stream_frame(walk, &st->tree, &p), BR_OK);
        CHECK_EQ(bt_stream_order(walk, BT_STREAM_STRIP), BR_OK);
        strip.n = 0;
        (void)bt_stream_walk(walk, NULL, keep, &strip);
        CHECK_EQ(bt_stream_order(walk, BT_STREAM_BACK_TO_FRONT), BR_OK);
        btf.n = 0;
        (void)bt_stream_walk(walk, NULL, keep, &btf);
        CHECK_EQ(btf.n, strip.n);
        if (btf.n > MAXT || !btf.n) { CHECK(0); break; }
        nleaf += btf.n;
        z32 = draw_leaves(&sc, &c, &btf, 0, 0, v, cache, list, chunks);
        noz = draw_leaves(&sc, &c, &btf, 2, 0, v, cache, list, chunks);
        rev = draw_leaves(&sc, &c, &btf, 2, 1, v, cache, list, chunks);
        nz += px_differ(z32, noz, 0);
        nrev += px_differ(z32, rev, 0);
        free(z32); free(noz); free(rev);
        for (lay = 2; lay < 4; lay++) {
            static const int32_t rows[3] = { H, 16, 7 };
            static const uint32_t capv[3] = { 3, 128, 4096 }, capt[3] = { 1, 256, 8192 };
            const size_t n = (size_t)W * H * (lay & 1 ? 2 : 4);
            uint8_t *ref = draw_leaves(&sc, &c, &btf, lay, 0, v, cache, list, chunks);
            for (r = 0; r < 3; r++)
                for (b = 0; b < 3; b++) {
                    uint8_t *px = draw_stream(walk, &sc, &c, lay, rows[r], capv[b], capt[b]);
                    CHECK_MSG(!memcmp(px, ref, n), "frame %d layout %d: %d-row bands, batches of %u differ from the list",
                              k, lay, rows[r], capt[b]);
                    free(px);
                }
            free(ref);
        }
        qsort(strip.p, strip.n, 36, cmp_leaf);
        qsort(btf.p, btf.n, 36, cmp_leaf);
        CHECK_MSG(!memcmp(strip.p, btf.p, (size_t)36 * btf.n), "frame %d: back to front, other leaves", k);
    }
    printf("back to front: %u leaves over %d cameras; pixels unlike the depth test's: %u, front to back %u\n", nleaf,
           NCAM, nz, nrev);
    CHECK(nleaf > 10000);
    CHECK(nz <= 20 && nrev > 5000);
    free(wmem); free(strip.p); free(btf.p); free(list); free(v); free(cache); free(chunks);
}

static void test_stream_refuses(void)
{
    uint64_t mem[64];
    bt_stream *s;
    bt_params p;
    cam c;
    const int32_t eye[3] = { 0, 0, 1 << 20 }, tgt[3] = { 1 << 20, 1 << 20, 0 };
    const int32_t bad[4] = { 0, 100, 320, 100 };
    uint64_t *big = malloc(bt_stream_mem_size(16, 100));
    CHECK_EQ(bt_stream_mem_size(15, 100), 0);
    CHECK_EQ(bt_stream_mem_size(24, 100), 0);
    CHECK_EQ(bt_stream_mem_size(16, 0), 0);
    CHECK(bt_stream_mem_size(16, 100) > 0);
    CHECK_EQ(bt_stream_init(&s, 16, 100, mem, sizeof mem / 4), BR_E_ARG);      /* too small */
    CHECK_EQ(bt_stream_init(&s, 16, 100, big, bt_stream_mem_size(16, 100)), BR_OK);
    CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, W, H, 16, 1 << 28), BR_OK);
    if (!load()) { CHECK(0); free(big); return; }
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW; p.c = &c; p.fr.sx = p.fr.sy = 1 << 10; p.fr.sz_q16 = 1 << 16;
    p.hyst_q8 = 64;
    free(big);
    big = malloc(bt_stream_mem_size(16, sites[0].tree.nslot));
    CHECK_EQ(bt_stream_init(&s, 16, sites[0].tree.nslot, big, bt_stream_mem_size(16, sites[0].tree.nslot)), BR_OK);
    CHECK_EQ(bt_stream_frame(s, &sites[0].tree, &p), BR_E_ARG);                  /* hysteresis */
    p.hyst_q8 = 0; p.mode = BT_BUDGET;
    CHECK_EQ(bt_stream_frame(s, &sites[0].tree, &p), BR_E_ARG);
    p.mode = BT_VIEW;
    CHECK_EQ(bt_stream_frame(s, &sites[0].tree, &p), BR_OK);
    CHECK_EQ(bt_stream_walk(s, bad, keep, NULL), 0);                     /* empty window */
    free(big);
    big = malloc(bt_stream_mem_size(16, sites[0].tree.nslot - 1));
    CHECK_EQ(bt_stream_init(&s, 16, sites[0].tree.nslot - 1, big, bt_stream_mem_size(16, sites[0].tree.nslot - 1)), BR_OK);
    CHECK_EQ(bt_stream_frame(s, &sites[0].tree, &p), BR_E_ARG);                  /* planes too small */
    CHECK_EQ(rt_stream_pipe(NULL, &c, RS_FMT_RGB565, RS_DEPTH_NONE, 0, NULL), BR_E_ARG);
    CHECK_EQ(rt_stream_mem_size(2, 1), 0);
    CHECK_EQ(rt_stream_mem_size(4097, 1), 0);
    CHECK_EQ(rt_stream_mem_size(3, 0), 0);
    free(big);
}

int main(void)
{
    T_RUN(test_stream_refuses);
    T_RUN(test_stream_frames);
    T_RUN(test_stream_voids);
    T_RUN(test_stream_back_to_front);
    {
        int i;
        for (i = 0; i < 2; i++) { free(sites[i].crop.z); free(sites[i].mem); }
    }
    return t_finish();
}
