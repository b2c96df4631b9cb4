/* tests/test_framecost.c — the per-frame path of the users' frame (issue 20): camera
 * path files (platform/campath.h), the selection's divide-free arithmetic
 * (core/bt_int.h bti_morph_nodiv, core/fx.h fx_udiv_bits) against C's `/`, and a
 * pinned view-dependent mesh sequence (moving camera, hysteresis and geomorph on, the
 * selection's decision memo across its generation wrap) that
 * the normal build and the divide-free build (build/div32-tests, BR_DIV64_NATIVE = 0)
 * must both reproduce byte for byte. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include "tests/test.h"
#include "tests/support/btcheck.h"
#include "core/bt_int.h"
#include "core/cam.h"
#include "platform/campath.h"
#include "platform/load.h"
#include "platform/scene.h"

static uint64_t rnd_state = 0x9e3779b97f4a7c15ull;
static uint64_t rnd(void)
{
    rnd_state ^= rnd_state << 13; rnd_state ^= rnd_state >> 7; rnd_state ^= rnd_state << 17;
    return rnd_state;
}

/* Writes n bytes of text to path; 0 (a failed check) when it cannot. */
static int put_text(const char *path, const char *text, size_t n)
{
    FILE *fp = fopen(path, "wb");
    CHECK(fp != NULL);
    if (!fp) return 0;
    CHECK_EQ(fwrite(text, 1, n, fp), n);
    fclose(fp);
    return 1;
}
#define PUT_TEXT(path, lit) put_text(path, lit, sizeof lit - 1)

static void test_campath(void)
{
    char path[256];
    campath p;
    br_err err;
    double v[6];
    snprintf(path, sizeof path, "%s/framecost_path.txt", t_outdir());
    CHECK_EQ(campath_parse_line("1,2,3,4,5,6", v), 0);
    CHECK(v[0] == 1 && v[5] == 6);
    CHECK_EQ(campath_parse_line(" 1.5 , -2e3,3,4,5, 6 \n", v), 0);
    CHECK(v[1] == -2000);
    CHECK_EQ(campath_parse_line("1,2,3,4,5", v), -1);
    CHECK_EQ(campath_parse_line("1,2,3,4,5,6,7", v), -1);
    CHECK_EQ(campath_parse_line("1,2,3,4,5,x", v), -1);
    CHECK_EQ(campath_parse_line("1,2,3,4,5,nan", v), -1);
    if (!PUT_TEXT(path, "# a path\n\n100,200,3000,5000,5000,500  # first\n110,200,3000,5000,5000,500\n")) return;
    CHECK_EQ(campath_read(path, &p, &err), BR_OK);
    CHECK_EQ(p.n, 2);
    if (p.n == 2) CHECK(p.cam[1][0] == 110 && p.cam[1][5] == 500);
    campath_free(&p);
    if (!PUT_TEXT(path, "1,2,3,4,5,6\n1,2,3,4,5\n")) return;
    CHECK_EQ(campath_read(path, &p, &err), BR_E_FORMAT);
    CHECK(strstr(err.msg, path) != NULL);
    CHECK_EQ(p.n, 0);
    if (!PUT_TEXT(path, "1,2,3,1,2,3\n")) return;
    CHECK_EQ(campath_read(path, &p, &err), BR_E_VALUE);
    if (!PUT_TEXT(path, "# nothing\n")) return;
    CHECK_EQ(campath_read(path, &p, &err), BR_E_VALUE);
    CHECK_EQ(campath_read("tests/out/no_such_path.txt", &p, &err), BR_E_IO);
    /* beyond --camera's range: refused with the file, the line and the range */
    if (!PUT_TEXT(path, "1,2,3,4,5,6\n1e300,0,1000,10,10,0\n")) return;
    CHECK_EQ(campath_read(path, &p, &err), BR_E_VALUE);
    CHECK(strstr(err.msg, path) != NULL && strstr(err.msg, "line 2") && strstr(err.msg, "out of range"));
    CHECK_EQ(p.n, 0);
    /* a NUL byte: said as such, not as a long line */
    if (!PUT_TEXT(path, "1,2,3,4,5,6\n\0garbage\n")) return;
    CHECK_EQ(campath_read(path, &p, &err), BR_E_FORMAT);
    CHECK(strstr(err.msg, "line 2: a NUL byte") != NULL);
    /* no commas, an infinity, a line too long for the reader: each named by its line */
    CHECK_EQ(campath_parse_line("1 2 3 4 5 6", v), -1);
    CHECK_EQ(campath_parse_line("0,0,inf,1,1,1", v), -1);
    {
        static char longline[1100] = "1,2,3,4,5,6\n";      /* then 1,086 digits and a newline */
        memset(longline + 12, '1', sizeof longline - 14);
        longline[sizeof longline - 2] = '\n';
        if (!put_text(path, longline, sizeof longline - 1)) return;
        CHECK_EQ(campath_read(path, &p, &err), BR_E_FORMAT);
        CHECK(strstr(err.msg, path) != NULL && strstr(err.msg, "line 2: longer than") != NULL);
        CHECK_EQ(p.n, 0);
    }
    /* CRLF line ends, blank lines of spaces, no newline after the last line */
    if (!PUT_TEXT(path, "# a path\r\n   \r\n 10 , 20,30 ,40,50, -60 # first\r\n\r\n1.5e3,2,3,4,5,6")) return;
    CHECK_EQ(campath_read(path, &p, &err), BR_OK);
    CHECK_EQ(p.n, 2);
    if (p.n == 2) CHECK(p.cam[0][5] == -60 && p.cam[1][0] == 1500);
    campath_free(&p);
}

/* the geomorph weight as core/bt_mesh.c's morph_of computes it with `/` */
static uint16_t morph_ref(int64_t lhs, int64_t d, int64_t tau, int64_t span)
{
    int64_t q = lhs / d - tau;
    if (q < 0) q = 0;
    if (q >= span) return BT_MORPH_ONE;
    return (uint16_t)((q * BT_MORPH_ONE) / span);
}

static void test_nodiv(void)
{
    int i, bad = 0;
    for (i = 0; i < 200000; i++) {
        uint64_t d = (rnd() >> (1 + rnd() % 62)) | 1, n, b = rnd() % 40;
        n = (rnd() >> 1) % (d << b > d ? (d << b) : d);
        if (d << b >> b != d) continue;
        if (fx_udiv_bits(n, d, (int)b) != n / d) bad++;
    }
    CHECK_EQ(bad, 0);
    for (i = 0; i < 400000; i++) {
        int64_t tau = (int64_t)(1 + rnd() % 100000), span = (int64_t)(1 + rnd() % (uint64_t)(tau * 4));
        int64_t d = (int64_t)(1 + (rnd() >> (2 + rnd() % 60)));
        int64_t lhs;
        switch (i & 3) {
        case 0: lhs = (int64_t)(rnd() >> 1); break;                      /* anything */
        case 1: lhs = (int64_t)(rnd() >> (1 + rnd() % 63)); break;
        default: {                                                       /* near the morph range */
            uint64_t lo = (uint64_t)tau * (uint64_t)d;
            if ((uint64_t)d > (uint64_t)INT64_MAX / (uint64_t)(tau + 2 * span)) { lhs = INT64_MAX; break; }
            lhs = (int64_t)(lo + rnd() % ((uint64_t)(2 * span) * (uint64_t)d)) - (int64_t)(rnd() % 3);
            if (lhs < 0) lhs = 0;
        }
        }
        if (bti_morph_nodiv(lhs, d, tau, span) != morph_ref(lhs, d, tau, span)) bad++;
    }
    CHECK_EQ(bad, 0);
    /* fx_div_round_bits (the camera's and fx_normalize3's short quotients) against
     * fx_div_round, at the bit widths they use, near the bound too */
    for (i = 0; i < 400000; i++) {
        static const int bits[4] = { 20, 31, 36, 50 };
        int b = bits[i & 3];
        int64_t d = (int64_t)(1 + (rnd() >> (1 + rnd() % 63))), n;
        uint64_t qmax = ((uint64_t)1 << b) - 1, q = (i & 4) ? qmax - rnd() % 4 : rnd() % qmax;
        if ((uint64_t)d > ((uint64_t)INT64_MAX >> 1) / (qmax + 1)) d = (int64_t)(((uint64_t)INT64_MAX >> 1) / (qmax + 1));
        n = (int64_t)(q * (uint64_t)d + rnd() % (uint64_t)((d + 1) / 2));
        if (i & 8) n = -n;
        if (fx_div_round_bits(n, d, b) != fx_div_round(n, d)) bad++;
    }
    CHECK_EQ(bad, 0);
    /* the camera's angle conversion (divide-free where BR_DIV64_NATIVE = 0) */
    for (i = 0; i < 200000; i++) {
        int32_t md = i < 1000 ? i * 360 - 180000 : (int32_t)(uint32_t)rnd();
        int64_t r = (int64_t)md % 360000;
        if (r < 0) r += 360000;
        if (fx_angle_from_mdeg(md) != (fx_angle)(uint64_t)((((uint64_t)r << 32) + 180000) / 360000)) bad++;
    }
    CHECK_EQ(bad, 0);
}

/* FNV-1a over values as little-endian bytes (the same bytes as memory on little-endian
 * targets), so that the pinned hashes hold on big-endian ones too. */
static uint64_t fnv_le(uint64_t h, uint64_t v, int bytes)
{
    int i;
    for (i = 0; i < bytes; i++) { h ^= (uint8_t)(v >> (8 * i)); h *= 0x100000001b3ull; }
    return h;
}

static uint64_t fnv_u32s(uint64_t h, const uint32_t *p, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++) h = fnv_le(h, p[i], 4);
    return h;
}

/* bt_vert's fields in its layout's order (4 + 4 + 4 + 2 + 1 + 1 bytes, no padding) */
static uint64_t fnv_verts(uint64_t h, const bt_vert *v, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; i++) {
        h = fnv_le(h, (uint32_t)v[i].x, 4); h = fnv_le(h, (uint32_t)v[i].y, 4); h = fnv_le(h, (uint32_t)v[i].z, 4);
        h = fnv_le(h, v[i].morph, 2); h = fnv_le(h, v[i].state, 1); h = fnv_le(h, v[i].pad_, 1);
    }
    return h;
}

/* The 400 x 300 crop of N47E009 at column 300, row 100 that the pinned hashes below read,
 * and its tree (tree memory in *tm).  Nonzero when the tile cannot be read. */
static int crop_tree(hf *f, hf *g, bt_tree *t, void **tm)
{
    void *scr;
    int32_t x, y;
    if (btc_load("hgt/N47E009.hgt", f)) return 1;
    *g = *f;
    g->w = 400; g->h = 300;
    g->z = malloc((size_t)g->w * g->h * 4);
    for (y = 0; y < g->h; y++)
        for (x = 0; x < g->w; x++) g->z[(size_t)y * g->w + x] = f->z[(size_t)(y + 100) * f->w + x + 300];
    *tm = malloc(bt_mem_size(g->w, g->h));
    scr = malloc(bt_scratch_size(g->w, g->h));
    CHECK_EQ(bt_build(t, g, BT_METRIC_EXACT, *tm, bt_mem_size(g->w, g->h), scr, bt_scratch_size(g->w, g->h)), BR_OK);
    free(scr);
    return 0;
}

/* Five frames of a camera flying 20 m a frame over a 400 x 300 crop of N47E009
 * (Lake Constance's south shore), 1 px, hysteresis 64, geomorph 128: the hash of
 * every frame's vertices (x, y, z, morph) and strip. */
static void test_view_pinned(void)
{
    hf f, g;
    bt_tree t;
    bt_params p;
    bt_mesh m;
    void *mem = NULL, *tm;
    cam c;
    bt_frame fr;
    int32_t k, us;
    uint64_t h = 0xcbf29ce484222325ull;
    uint32_t i, ntri = 0, nmorph = 0;
    if (crop_tree(&f, &g, &t, &tm)) { CHECK(0); return; }
    CHECK_EQ(bt_frame_auto(&g, &fr, &us), BR_OK);
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW; p.fr = fr; p.c = &c; p.hyst_q8 = 64; p.morph_q8 = 128; p.pixel_err_q8 = 256;
    for (k = 0; k < 5; k++) {
        /* metres -> world units (2^-us m): eye 2 km up at the south-west, moving east */
        int32_t eye[3], tgt[3];
        eye[0] = (int32_t)((2000 + 20 * k) << us); eye[1] = (int32_t)(1000 << us); eye[2] = (int32_t)(2500 << us);
        tgt[0] = (int32_t)((12000 + 20 * k) << us); tgt[1] = (int32_t)(9000 << us); tgt[2] = (int32_t)(400 << us);
        CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, 320, 240, 1 << us, (int32_t)(60000 << us)), BR_OK);
        if (k == 0) CHECK_EQ(btc_extract(&t, &p, 200000, &m, &mem), 0);
        else CHECK_EQ(bt_extract(&t, &p, &m), BR_OK);
        if (k == 1) m.memo_gen = 0xFFFEu;   /* frame 3's decision memo wraps its generation */
        for (i = 0; i < m.nv; i++) {
            h = fnv_le(h, (uint32_t)m.v[i].x, 4); h = fnv_le(h, (uint32_t)m.v[i].y, 4); h = fnv_le(h, (uint32_t)m.v[i].z, 4);
            h = fnv_le(h, m.v[i].morph, 2);
            nmorph += m.v[i].morph > 0 && m.v[i].morph < BT_MORPH_ONE;
        }
        h = fnv_u32s(h, m.strip, m.ns);
        ntri += m.ntri;
    }
    printf("view sequence: %u triangles, %u vertices part-way morphed in 5 frames, hash %016llx\n", ntri,
           nmorph, (unsigned long long)h);
    CHECK(nmorph > 100);
    CHECK_EQ(h, 0xdc01a19f18e437ccull);   /* the same bytes in every build (the divide-free one too) */
    free(mem); free(tm); free(g.z);
    dem_free(&f);
}

/* Budget mode (3000 triangles) and the view mode's budget fallback (a mesh of 2000
 * triangles) over the same crop: the hash of both meshes, which the divide-free
 * build must reproduce (the priorities' rho by restoring division there). */
static void test_budget_pinned(void)
{
    hf f, g;
    bt_tree t;
    bt_params p;
    bt_mesh m, m2;
    void *mem = NULL, *mem2, *tm;
    cam c;
    int32_t us, eye[3], tgt[3];
    uint64_t h = 0xcbf29ce484222325ull;
    if (crop_tree(&f, &g, &t, &tm)) { CHECK(0); return; }
    memset(&p, 0, sizeof p);
    CHECK_EQ(bt_frame_auto(&g, &p.fr, &us), BR_OK);
    eye[0] = (int32_t)(2000 << us); eye[1] = (int32_t)(1000 << us); eye[2] = (int32_t)(2500 << us);
    tgt[0] = (int32_t)(12000 << us); tgt[1] = (int32_t)(9000 << us); tgt[2] = (int32_t)(400 << us);
    CHECK_EQ(cam_look_at(&c, eye, tgt, 60000, 320, 240, 1 << us, (int32_t)(60000 << us)), BR_OK);
    p.c = &c; p.pixel_err_q8 = 64; p.morph_q8 = 128;
    p.mode = BT_BUDGET; p.budget = 3000;
    CHECK_EQ(btc_extract(&t, &p, 4000, &m, &mem), 0);
    CHECK(m.ntri > 1000 && m.ntri <= 3000);
    h = fnv_verts(h, m.v, m.nv);
    h = fnv_u32s(h, m.strip, m.ns);
    p.mode = BT_VIEW;
    mem2 = malloc(bt_mesh_mem_size(2000));
    CHECK(mem2 && bt_mesh_init(&m2, 2000, mem2, bt_mesh_mem_size(2000)) == BR_OK);
    if (mem2) {
        CHECK_EQ(bt_extract(&t, &p, &m2), BR_OK);
        CHECK_EQ(m2.overflow, 1);
        h = fnv_verts(h, m2.v, m2.nv);
        h = fnv_u32s(h, m2.strip, m2.ns);
    }
    printf("budget %u triangles, fallback %u triangles, hash %016llx\n", m.ntri, mem2 ? m2.ntri : 0,
           (unsigned long long)h);
    CHECK_EQ(h, 0xc4dda91df5b4f7e1ull);
    free(mem); free(mem2); free(tm); free(g.z);
    dem_free(&f);
}

/* The viewer's frame (scene_frame) in 64-row bands: scene_frame hands the rasteriser
 * the scene's chunk table (without it every band walks the whole strip), and the bands
 * give the whole frame's pixels. */
static void test_scene_bands(void)
{
    const char *in[1] = { "assets/N47E009.hgt.gz" };
    enum { W = 640, H = 480, ROWS = 64 };
    scene s;
    scene_opts o;
    br_err err;
    cam c;
    bt_params p;
    rs_frame fr;
    rs_prim prim;
    double e[3], tg[3];
    uint32_t whole, banded = 0;
    int32_t y0;
    uint8_t *full = malloc((size_t)W * H * 4), *img = malloc((size_t)W * H * 4);
    void *z = malloc(rs_band_mem_size(W, H, RS_FMT_XRGB8888, RS_DEPTH32));
    memset(&o, 0, sizeof o);
    o.quiet = 1;
    if (!full || !img || !z || scene_open(&s, in, 1, &o, &err) != BR_OK) { CHECK(0); free(full); free(img); free(z); return; }
    CHECK_EQ(scene_tree(&s, &err), BR_OK);
    CHECK_EQ(scene_reserve(&s, 200000, &err), BR_OK);
    scene_default_view(&s, 60, e, tg);
    CHECK_EQ(scene_camera(&s, e, tg, 60, W, H, &c), BR_OK);
    memset(&p, 0, sizeof p);
    memset(&fr, 0, sizeof fr);
    p.pixel_err_q8 = 256; p.hyst_q8 = 64; p.morph_q8 = 128;
    fr.fmt = RS_FMT_XRGB8888; fr.depth = RS_DEPTH32; fr.clear_rgb = 0x99ccffu;
    CHECK_EQ(scene_frame(&s, &c, &p, &fr, &prim), BR_OK);
    CHECK(fr.chunks != NULL);
    {
        rs_band_stats st;
        memset(&st, 0, sizeof st);
        CHECK_EQ(rs_draw_band(&fr, 0, H, full, (size_t)W * 4, z, &st), BR_OK);
        whole = st.tris;
        for (y0 = 0; y0 < H; y0 += ROWS) {
            memset(&st, 0, sizeof st);
            CHECK_EQ(rs_draw_band(&fr, y0, H - y0 < ROWS ? H - y0 : ROWS, img + (size_t)y0 * W * 4, (size_t)W * 4, z, &st),
                     BR_OK);
            banded += st.tris;
        }
    }
    CHECK(!memcmp(full, img, (size_t)W * H * 4));
    CHECK(whole > 1000 && banded >= whole);
    scene_close(&s);
    free(full); free(img); free(z);
}

/* Along a path, scene_frame sets up only the vertices of replayed parts that moved and
 * copies the rest from the last frame's, wherever the part's vertices were then
 * (core/bitree.h bt_part_moved_from, raster/terrain.h rt_from_mesh_moved): every frame's
 * vertices equal a whole set-up of its mesh, and every replayed part takes the short way. */
static void fly_vertices(const char *path, int32_t w, int32_t h, long *parts_kept, long *parts_run)
{
    const char *in[1] = { "assets/N47E009.hgt.gz" };
    scene s;
    scene_opts o;
    br_err err;
    campath cp;
    bt_params p;
    rs_frame fr;
    rs_prim prim;
    rs_vertex *ref = NULL;
    int i, bad = 0;
    memset(&o, 0, sizeof o);
    o.quiet = 1;
    if (campath_read(path, &cp, &err) != BR_OK) { CHECK_MSG(0, "%s", path); return; }
    if (scene_open(&s, in, 1, &o, &err) != BR_OK) { CHECK(0); campath_free(&cp); return; }
    CHECK_EQ(scene_tree(&s, &err), BR_OK);
    CHECK_EQ(scene_reserve(&s, 200000, &err), BR_OK);
    ref = malloc(sizeof *ref * (s.mesh.cap_v ? s.mesh.cap_v : 1));
    memset(&p, 0, sizeof p);
    memset(&fr, 0, sizeof fr);
    p.pixel_err_q8 = 256; p.hyst_q8 = 64; p.morph_q8 = 128;
    fr.fmt = RS_FMT_XRGB8888; fr.depth = RS_DEPTH32; fr.clear_rgb = 0x99ccffu;
    for (i = 0; ref && i < cp.n && i < 150; i++) {
        cam c;
        uint32_t k;
        if (scene_camera(&s, cp.cam[i], cp.cam[i] + 3, 60, w, h, &c) != BR_OK
            || scene_frame(&s, &c, &p, &fr, &prim) != BR_OK) { bad++; break; }
        rt_from_mesh(&s.rt, &s.mesh, ref);
        bad += memcmp(ref, s.verts, sizeof *ref * s.mesh.nv) != 0;
        for (k = 0; k < BT_PARTS; k++) {
            uint32_t from;
            *parts_kept += bt_part_moved_from(s.parts, k, &from) != NULL;
        }
        *parts_run += (long)bt_parts_reused(s.parts);
    }
    CHECK_MSG(ref && bad == 0, "%s %dx%d: %d frames' vertices differ", path, w, h, bad);
    free(ref);
    scene_close(&s);
    campath_free(&cp);
}

static void test_scene_vertices(void)
{
    long kept = 0, reused = 0;
    fly_vertices("assets/default-path.cam", 640, 480, &kept, &reused);
    fly_vertices("assets/lake-path.cam", 320, 240, &kept, &reused);
    printf("  vertex set-up: %ld of %ld replayed parts set up their moved vertices only\n", kept, reused);
    CHECK(kept <= reused && kept * 20 > reused * 19);   /* (a replay of more than vbits vertices lists none) */
}

int main(void)
{
    T_RUN(test_campath);
    T_RUN(test_nodiv);
    T_RUN(test_view_pinned);
    T_RUN(test_budget_pinned);
    T_RUN(test_scene_bands);
    T_RUN(test_scene_vertices);
    return t_finish();
}
