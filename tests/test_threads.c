/* tests/test_threads.c — the frame driver on N threads (platform/pipe_threads.h) gives
 * the pixels of the one-thread, whole-frame driver for every thread count and band
 * height, hands the bands to the sink in order, and stops on the first error.
 * The view selection in parts (core/bitree.h bt_extract_begin) on N threads gives the
 * same mesh, and the serial extraction's strip, pixels and hysteresis state.
 * Scene: the default terrain (assets/N47E009.hgt.gz) at 640x480, from the default view
 * and from a low camera over the lake, and along the default camera path; fuji.png and
 * mt_rainier_90m.tif (../shared/data/dem) for voids. */
#include "tests/test.h"
#include "platform/campath.h"
#include "platform/pipe_threads.h"
#include "platform/scene.h"
#include "platform/view.h"

#define W 640
#define H 480

typedef struct frame_sink {
    uint32_t *px;           /* W x H */
    int32_t next_y0;        /* where the next band must start */
    int out_of_order;
    int calls, fail_at;     /* fail_at > 0: the fail_at-th call returns an error */
} frame_sink;

static br_status sink_copy(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    frame_sink *s = (frame_sink *)user;
    int32_t y;
    if (y0 != s->next_y0) s->out_of_order = 1;
    s->next_y0 = y0 + rows;
    if (++s->calls == s->fail_at) return BR_E_IO;
    for (y = 0; y < rows; y++)
        memcpy(s->px + (size_t)(y0 + y) * W, (const uint8_t *)px + (size_t)y * stride, W * 4);
    return BR_OK;
}

/* A post hook that reads the depth of the band: darkens far pixels (a fog stand-in),
 * so that the comparison covers post hooks run on several threads too. */
static br_status post_darken(const void *user, rs_band *b, rs_band_stats *st)
{
    int32_t i, n = b->w * b->rows;
    uint32_t *c = (uint32_t *)b->color;
    const uint32_t *d = (const uint32_t *)b->depth;
    (void)user; (void)st;
    for (i = 0; i < n; i++)
        if (d[i] < (RS_DEPTH_ONE >> 12)) c[i] = (c[i] >> 1) & 0x7f7f7fu;
    return BR_OK;
}

static scene sc;
static int sc_ok;
static int16_t *chunks;

static int open_scene(void)
{
    br_err err;
    rs_prim cap;
    if (sc_ok) return 1;
    {
        const char *in[1] = { "assets/N47E009.hgt.gz" };
        scene_opts o;
        memset(&o, 0, sizeof o);
        if (scene_open(&sc, in, 1, &o, &err) != BR_OK) { fprintf(stderr, "%s\n", err.msg); return 0; }
    }
    if (scene_tree(&sc, &err) != BR_OK || scene_reserve(&sc, 2000000, &err) != BR_OK) return 0;
    cap.kind = RS_STRIP; cap.n = sc.mesh.cap_s; cap.idx = NULL;
    chunks = malloc(rs_chunk_mem_size(&cap, 1) + 4);
    sc_ok = chunks != NULL;
    return sc_ok;
}

/* Prepares the frame for eye/target and its pipe (terrain pass, post hook). */
static int prepare(const double eye[3], const double tgt[3], rs_frame *fr, rs_prim *prim, rs_pipe *p)
{
    cam c;
    bt_params bp;
    rs_pass terrain;
    memset(&bp, 0, sizeof bp);
    memset(fr, 0, sizeof *fr);
    memset(p, 0, sizeof *p);
    if (scene_camera(&sc, eye, tgt, 60, W, H, &c) != BR_OK) return 0;
    fr->fmt = RS_FMT_XRGB8888;
    fr->depth = RS_DEPTH32;
    fr->clear_rgb = 0x99ccffu;
    fr->chunks = chunks;
    if (scene_frame(&sc, &c, &bp, fr, prim) != BR_OK) return 0;
    if (rs_pass_terrain(&terrain, fr) != BR_OK) return 0;
    p->w = W; p->h = H; p->fmt = RS_FMT_XRGB8888; p->depth = RS_DEPTH32;
    if (rs_pipe_add(p, &terrain) != BR_OK) return 0;
    p->post = post_darken;
    return 1;
}

static void check_view(const double eye[3], const double tgt[3])
{
    static const int threads[] = { 1, 2, 3, 8 };
    static const int32_t bands[] = { 64, 16, 7, H };
    rs_frame fr;
    rs_prim prim;
    rs_pipe p;
    frame_sink ref, got;
    rs_band_stats tref, tgot;
    void *mem;
    size_t ms;
    int ti, bi;
    long sky = 0, k;
    CHECK(prepare(eye, tgt, &fr, &prim, &p));
    memset(&ref, 0, sizeof ref);
    ref.px = malloc((size_t)W * H * 4);
    ms = rs_pipe_mem_size(&p, H);
    mem = malloc(ms);
    CHECK(ref.px && mem);
    if (!ref.px || !mem) return;
    CHECK_EQ(rs_pipe_run(&p, H, mem, ms, sink_copy, &ref, &tref), BR_OK);
    for (k = 0; k < (long)W * H; k++) sky += ref.px[k] == 0x99ccffu;
    CHECK(sky < (long)W * H * 9 / 10);       /* the frame shows terrain */
    CHECK(tref.tris > 1000);
    for (ti = 0; ti < 4; ti++) {
        pt_pool *pool;
        CHECK_EQ(pt_open(&pool, threads[ti]), BR_OK);
        CHECK_EQ(pt_threads(pool), threads[ti]);
        for (bi = 0; bi < 4; bi++) {
            memset(&got, 0, sizeof got);
            got.px = calloc((size_t)W * H, 4);
            CHECK_EQ(pt_run(pool, &p, bands[bi], sink_copy, &got, &tgot), BR_OK);
            CHECK_MSG(!memcmp(got.px, ref.px, (size_t)W * H * 4), "%d threads, bands of %d rows",
                      threads[ti], (int)bands[bi]);
            CHECK(!got.out_of_order);
            CHECK_EQ(got.next_y0, H);
            CHECK_EQ(tgot.pixels, tref.pixels);
            free(got.px);
        }
        pt_close(pool);
    }
    free(ref.px);
    free(mem);
}

static void test_threads_default_view(void)
{
    double eye[3], tgt[3];
    CHECK(open_scene());
    if (!sc_ok) return;
    scene_default_view(&sc, 60, eye, tgt);
    check_view(eye, tgt);
}

static void test_threads_low_view(void)
{
    const double eye[3] = { 20000, 20000, 3500 }, tgt[3] = { 40000, 70000, 800 };
    CHECK(open_scene());
    if (!sc_ok) return;
    check_view(eye, tgt);
}

/* The viewer's post hook (wireframe, HUD and help text) gives the same pixels on 3
 * threads in bands of 7 rows as on one thread over the whole frame, and draws. */
static void test_threads_view_overlay(void)
{
    const double eye[3] = { 20000, 20000, 3500 }, tgt[3] = { 40000, 70000, 800 };
    rs_frame fr;
    rs_prim prim;
    rs_pipe p;
    view_overlay ov;
    frame_sink ref, got, plain;
    pt_pool *pool;
    void *mem;
    size_t ms;
    long k, differ = 0;
    CHECK(open_scene());
    if (!sc_ok) return;
    CHECK(prepare(eye, tgt, &fr, &prim, &p));
    memset(&ov, 0, sizeof ov);
    memset(&ref, 0, sizeof ref);
    memset(&got, 0, sizeof got);
    memset(&plain, 0, sizeof plain);
    ref.px = malloc((size_t)W * H * 4);
    got.px = malloc((size_t)W * H * 4);
    plain.px = malloc((size_t)W * H * 4);
    ms = rs_pipe_mem_size(&p, H);
    mem = malloc(ms);
    CHECK(ref.px && got.px && plain.px && mem);
    if (!ref.px || !got.px || !plain.px || !mem) return;
    p.post = NULL;
    CHECK_EQ(rs_pipe_run(&p, H, mem, ms, sink_copy, &plain, NULL), BR_OK);
    ov.fr = &fr; ov.wire = 1; ov.scale = 2; ov.h = H;
    ov.hud = "12.3 fps  HUD text\ncrossing band 0 and 1";
    ov.help = view_controls_text();
    p.post = view_post;
    p.post_user = &ov;
    CHECK_EQ(rs_pipe_run(&p, H, mem, ms, sink_copy, &ref, NULL), BR_OK);
    CHECK_EQ(pt_open(&pool, 3), BR_OK);
    CHECK_EQ(pt_run(pool, &p, 7, sink_copy, &got, NULL), BR_OK);
    pt_close(pool);
    CHECK(!memcmp(got.px, ref.px, (size_t)W * H * 4));
    for (k = 0; k < (long)W * H; k++) differ += got.px[k] != plain.px[k];
    CHECK(differ > (long)W * H / 20);
    free(ref.px); free(got.px); free(plain.px); free(mem);
}

/* A sink error stops the frame: later bands never reach the sink, the error comes back,
 * and the pool still draws the next frame whole. */
static void test_threads_sink_error(void)
{
    double eye[3], tgt[3];
    rs_frame fr;
    rs_prim prim;
    rs_pipe p;
    frame_sink s;
    pt_pool *pool;
    CHECK(open_scene());
    if (!sc_ok) return;
    scene_default_view(&sc, 60, eye, tgt);
    CHECK(prepare(eye, tgt, &fr, &prim, &p));
    CHECK_EQ(pt_open(&pool, 3), BR_OK);
    memset(&s, 0, sizeof s);
    s.px = calloc((size_t)W * H, 4);
    s.fail_at = 3;
    CHECK_EQ(pt_run(pool, &p, 32, sink_copy, &s, NULL), BR_E_IO);
    CHECK_EQ(s.calls, 3);
    CHECK(!s.out_of_order);
    memset(s.px, 0, (size_t)W * H * 4);
    s.fail_at = 0; s.calls = 0; s.next_y0 = 0;
    CHECK_EQ(pt_run(pool, &p, 32, sink_copy, &s, NULL), BR_OK);
    CHECK_EQ(s.calls, H / 32);
    free(s.px);
    pt_close(pool);
}

/* ---------------------------------------------------------------- the selection's parts */
static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const uint8_t *b = (const uint8_t *)p;
    size_t i;
    for (i = 0; i < n; i++) { h ^= b[i]; h *= 0x100000001b3ull; }
    return h;
}

/* The strip as (x, y, z, morph) per index: what is drawn, not how vertices are numbered */
static uint64_t walk_hash(const bt_mesh *m)
{
    uint64_t h = 0xcbf29ce484222325ull;
    uint32_t j;
    for (j = 0; j < m->ns; j++) {
        const bt_vert *v = &m->v[m->strip[j]];
        int32_t q[4];
        q[0] = v->x; q[1] = v->y; q[2] = v->z; q[3] = v->morph;
        h = fnv(h, q, sizeof q);
    }
    return h;
}

typedef struct sel_frame {
    uint64_t mesh;      /* vertices and strip, bytes */
    uint64_t walk;      /* the strip as (x, y, z, morph) per index: no vertex numbering */
    uint64_t st;        /* the tree's frame state after the frame (hysteresis) */
    uint64_t px;        /* the frame's pixels */
    uint32_t ntri, nline, ns;
} sel_frame;

#define SEL_FRAMES 12

/* Flies SEL_FRAMES lines of the default path (every 4th: hysteresis and geomorph at
 * work) from a cleared frame state with the viewer's parameters; parts on `pool`
 * (NULL: the caller's thread), or serially (bt_extract) when serial. */
static int fly(pt_pool *pool, int serial, sel_frame *out)
{
    static campath cp;
    static int cp_ok;
    br_err err;
    bt_parts *keep = sc.parts;
    size_t nn = bt_state_size(sc.tree.nslot);
    uint32_t *px = malloc((size_t)W * H * 4);
    void *mem = NULL;
    int i, ok = px != NULL;
    if (!cp_ok && campath_read("assets/default-path.cam", &cp, &err) != BR_OK) { free(px); return 0; }
    cp_ok = 1;
    memset(sc.tree.st, 0, nn);
    sc.mesh.nsplits = 0;
    rt_cache_clear(&sc.rt);   /* every run fills the shading cache from empty */
    sc.pool = pool;
    if (serial) sc.parts = NULL;
    bt_parts_reset(keep);     /* every run cuts the parts from the same start */
    for (i = 0; ok && i < SEL_FRAMES; i++) {
        const double *k = cp.cam[(4 * i) % cp.n];
        cam c;
        bt_params bp;
        rs_frame fr;
        rs_prim prim;
        rs_pipe p;
        rs_pass terrain;
        frame_sink fs;
        uint64_t h = 0xcbf29ce484222325ull;
        memset(&bp, 0, sizeof bp);
        memset(&fr, 0, sizeof fr);
        memset(&p, 0, sizeof p);
        bp.pixel_err_q8 = 256; bp.hyst_q8 = 64; bp.morph_q8 = 128;
        fr.fmt = RS_FMT_XRGB8888; fr.depth = RS_DEPTH32; fr.clear_rgb = 0x99ccffu; fr.chunks = chunks;
        ok = scene_camera(&sc, k, k + 3, 60, W, H, &c) == BR_OK && scene_frame(&sc, &c, &bp, &fr, &prim) == BR_OK
             && rs_pass_terrain(&terrain, &fr) == BR_OK;
        if (!ok) break;
        p.w = W; p.h = H; p.fmt = RS_FMT_XRGB8888; p.depth = RS_DEPTH32;
        ok = rs_pipe_add(&p, &terrain) == BR_OK;
        if (!mem) mem = malloc(rs_pipe_mem_size(&p, 64));
        memset(&fs, 0, sizeof fs);
        fs.px = px;
        ok = ok && mem && rs_pipe_run(&p, 64, mem, rs_pipe_mem_size(&p, 64), sink_copy, &fs, NULL) == BR_OK;
        out[i].mesh = fnv(fnv(h, sc.mesh.v, (size_t)sc.mesh.nv * sizeof *sc.mesh.v), sc.mesh.strip, (size_t)sc.mesh.ns * 4);
        out[i].walk = walk_hash(&sc.mesh);
        out[i].st = fnv(0xcbf29ce484222325ull, sc.tree.st, nn);
        out[i].px = fnv(0xcbf29ce484222325ull, px, (size_t)W * H * 4);
        out[i].ntri = sc.mesh.ntri; out[i].nline = sc.mesh.nline; out[i].ns = sc.mesh.ns;
    }
    sc.parts = keep;
    sc.pool = NULL;
    free(px);
    free(mem);
    return ok;
}

/* The view selection in parts on 1, 2, 3 and 8 threads gives the same mesh bytes
 * every frame of a path; its strip is the serial extraction's (the same vertices in
 * the same order, only numbered differently), and so are the pixels and the
 * hysteresis state the next frame reads. */
static void test_threads_selection(void)
{
    static const int threads[] = { 1, 2, 3, 8 };
    sel_frame ser[SEL_FRAMES], one[SEL_FRAMES], got[SEL_FRAMES];
    int ti, i;
    CHECK(open_scene());
    if (!sc_ok) return;
    CHECK(sc.parts != NULL);
    CHECK(fly(NULL, 1, ser));
    CHECK(fly(NULL, 0, one));
    for (i = 0; i < SEL_FRAMES; i++) {
        CHECK_MSG(one[i].walk == ser[i].walk, "frame %d: the joined strip is not the serial one", i);
        CHECK_MSG(one[i].px == ser[i].px, "frame %d: pixels differ from the serial extraction", i);
        CHECK_MSG(one[i].st == ser[i].st, "frame %d: hysteresis state differs", i);
        CHECK_EQ(one[i].ntri, ser[i].ntri);
        CHECK_EQ(one[i].nline, ser[i].nline);
        CHECK(one[i].ntri > 5000);
    }
    for (ti = 0; ti < 4; ti++) {
        pt_pool *pool;
        CHECK_EQ(pt_open(&pool, threads[ti]), BR_OK);
        CHECK(fly(pool, 0, got));
        for (i = 0; i < SEL_FRAMES; i++) {
            CHECK_MSG(got[i].mesh == one[i].mesh, "%d threads, frame %d: mesh bytes differ", threads[ti], i);
            CHECK_MSG(got[i].px == one[i].px && got[i].st == one[i].st, "%d threads, frame %d", threads[ti], i);
        }
        pt_close(pool);
    }
}

/* Seams where voids and culling break the walk (bridges): fuji.png (a void border around
 * the cone) and mt_rainier_90m.tif (SRTM voids), 8 frames closing in on the default
 * view's target with hysteresis: on 3 threads, the parts' strip (as positions) and the
 * hysteresis state are the serial extraction's. */
static void test_threads_voids(void)
{
    static const char *const dems[2] = { "png/fuji.png", "tif/mt_rainier_90m.tif" };
    int d, pass, i;
    for (d = 0; d < 2; d++) {
        scene s;
        scene_opts o;
        br_err err;
        const char *in[1];
        pt_pool *pool = NULL;
        bt_parts *keep;
        double eye[3], tgt[3];
        uint64_t w[2][8], st[2][8];
        uint32_t nt[2][8];
        in[0] = t_data(dems[d]);
        memset(&o, 0, sizeof o);
        o.quiet = 1;
        if (scene_open(&s, in, 1, &o, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); continue; }
        CHECK_EQ(scene_tree(&s, &err), BR_OK);
        CHECK_EQ(scene_reserve(&s, 400000, &err), BR_OK);
        CHECK_EQ(pt_open(&pool, 3), BR_OK);
        scene_default_view(&s, 60, eye, tgt);
        keep = s.parts;
        for (pass = 0; pass < 2; pass++) {
            memset(s.tree.st, 0, bt_state_size(s.tree.nslot));
            s.mesh.nsplits = 0;
            s.parts = pass ? keep : NULL;
            s.pool = pass ? pool : NULL;
            for (i = 0; i < 8; i++) {
                double e[3];
                cam c;
                bt_params bp;
                int k;
                for (k = 0; k < 3; k++) e[k] = eye[k] + (tgt[k] - eye[k]) * i / 12;
                memset(&bp, 0, sizeof bp);
                bp.mode = BT_VIEW; bp.pixel_err_q8 = 256; bp.hyst_q8 = 64; bp.morph_q8 = 128;
                CHECK_EQ(scene_camera(&s, e, tgt, 60, W, H, &c), BR_OK);
                CHECK_EQ(scene_mesh(&s, &c, &bp), BR_OK);
                w[pass][i] = walk_hash(&s.mesh);
                st[pass][i] = fnv(0xcbf29ce484222325ull, s.tree.st, bt_state_size(s.tree.nslot));
                nt[pass][i] = s.mesh.ntri;
            }
        }
        s.parts = keep;
        s.pool = NULL;
        for (i = 0; i < 8; i++) {
            CHECK_MSG(w[1][i] == w[0][i] && st[1][i] == st[0][i], "%s frame %d", dems[d], i);
            CHECK(nt[1][i] == nt[0][i] && nt[0][i] > 1000);
        }
        pt_close(pool);
        scene_close(&s);
    }
}

/* Core protocol: the parts extracted in any order give the same bytes; a frame that
 * does not fit the mesh falls back to bt_extract (the budget rule), the same mesh and
 * state as bt_extract's; other modes are extracted by bt_extract at once. */
static void test_threads_parts_core(void)
{
    bt_mesh ma, mb;
    bt_parts *ps;
    void *a = NULL, *b = NULL, *pm = NULL;
    double eye[3], tgt[3];
    cam c;
    bt_params bp;
    uint32_t n, k, v0, nv, cap, pt;
    int round;
    CHECK(open_scene());
    if (!sc_ok) return;
    scene_default_view(&sc, 60, eye, tgt);
    CHECK_EQ(scene_camera(&sc, eye, tgt, 60, W, H, &c), BR_OK);
    for (round = 0; round < 2; round++) {
        cap = round == 0 ? 400000 : 3000;      /* round 1: the selection does not fit */
        pt = cap < 4096 ? cap : 4096;          /* a part's room: the scene's */
        a = malloc(bt_mesh_mem_size(cap)); b = malloc(bt_mesh_mem_size(cap));
        pm = malloc(bt_parts_mem_size(pt));
        CHECK(a && b && pm);
        if (!a || !b || !pm) break;
        CHECK_EQ(bt_mesh_init(&ma, cap, a, bt_mesh_mem_size(cap)), BR_OK);
        CHECK_EQ(bt_mesh_init(&mb, cap, b, bt_mesh_mem_size(cap)), BR_OK);
        CHECK_EQ(bt_parts_init(&ps, pt, pm, bt_parts_mem_size(pt)), BR_OK);
        memset(&bp, 0, sizeof bp);
        bp.mode = BT_VIEW; bp.c = &c; bp.fr = sc.rt.fr; bp.pixel_err_q8 = 256; bp.hyst_q8 = 64;
        memset(sc.tree.st, 0, bt_state_size(sc.tree.nslot));
        CHECK_EQ(bt_extract(&sc.tree, &bp, &ma), BR_OK);
        CHECK_EQ(ma.overflow, round);
        memset(sc.tree.st, 0, bt_state_size(sc.tree.nslot));
        CHECK_EQ(bt_extract_begin(ps, &sc.tree, &bp, &mb, &n), BR_OK);
        CHECK(n > 8 && n <= BT_PARTS);
        for (k = n; k-- > 0;) bt_extract_part(ps, k);     /* backwards */
        CHECK_EQ(bt_extract_end(ps, &n), BR_OK);
        for (k = n; k-- > 0;) bt_extract_join(ps, k, &v0, &nv);
        CHECK_EQ(mb.ntri, ma.ntri);
        CHECK_EQ(mb.ns, ma.ns);
        CHECK_EQ(mb.overflow, round);
        if (round == 1) {
            /* the fallback is bt_extract itself: the same bytes */
            CHECK_EQ(n, 0);
            CHECK(mb.nv == ma.nv && !memcmp(mb.v, ma.v, (size_t)ma.nv * sizeof *ma.v));
            CHECK(!memcmp(mb.strip, ma.strip, (size_t)ma.ns * 4));
        } else {
            CHECK(n > 0);
            CHECK(mb.nv >= ma.nv);      /* seam vertices once per part */
            for (k = 0; k < ma.ns && k < mb.ns; k++) {
                const bt_vert *p = &ma.v[ma.strip[k]], *q = &mb.v[mb.strip[k]];
                if (p->x != q->x || p->y != q->y || p->z != q->z) break;
            }
            CHECK_EQ(k, ma.ns);
        }
        /* fidelity mode goes to bt_extract */
        memset(&bp, 0, sizeof bp);
        bp.mode = BT_FIDELITY; bp.max_err = 20;
        CHECK_EQ(bt_extract_begin(ps, &sc.tree, &bp, &mb, &n), BR_OK);
        CHECK_EQ(n, 0);
        CHECK_EQ(bt_extract_end(ps, &n), BR_OK);
        CHECK_EQ(n, 0);
        CHECK(mb.ntri > 0);
        bp.mode = 7;
        CHECK_EQ(bt_extract_begin(ps, &sc.tree, &bp, &mb, &n), BR_E_ARG);
        free(a); free(b); free(pm);
        a = b = pm = NULL;
    }
    free(a); free(b); free(pm);
    CHECK_EQ(bt_parts_init(&ps, 1, NULL, 0), BR_E_ARG);
    CHECK_EQ(bt_parts_mem_size(1), 0);
    memset(sc.tree.st, 0, bt_state_size(sc.tree.nslot));
    sc.mesh.nsplits = 0;
}

static void test_threads_bad_args(void)
{
    pt_pool *pool = (pt_pool *)&pool;
    CHECK_EQ(pt_open(&pool, 0), BR_E_ARG);
    CHECK(pool == NULL);
    CHECK_EQ(pt_open(&pool, PT_MAX_THREADS + 1), BR_E_ARG);
    CHECK(pt_online_cores() >= 1);
}

int main(void)
{
    T_RUN(test_threads_default_view);
    T_RUN(test_threads_low_view);
    T_RUN(test_threads_view_overlay);
    T_RUN(test_threads_sink_error);
    T_RUN(test_threads_selection);
    T_RUN(test_threads_voids);
    T_RUN(test_threads_parts_core);
    T_RUN(test_threads_bad_args);
    scene_close(&sc);
    free(chunks);
    return t_finish();
}
