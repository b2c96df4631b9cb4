/* tests/test_threads.c — the frame driver on N threads (platform/pipe_threads.h) gives
 * the pixels of the one-thread, whole-frame driver for every thread count and band
 * height, hands the bands to the sink in order, and stops on the first error.
 * Scene: the default terrain (assets/N47E009.hgt.gz) at 640x480, from the default view
 * and from a low camera over the lake. */
#include "tests/test.h"
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
    T_RUN(test_threads_bad_args);
    scene_close(&sc);
    free(chunks);
    return t_finish();
}
