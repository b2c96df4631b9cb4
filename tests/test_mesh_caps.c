/* tests/test_mesh_caps.c — a bitree mesh with a vertex capacity of its own
 * (core/bitree.h bt_mesh_init_v, what the board build sizes its mesh with): along a
 * camera path over a 257 x 257 crop of N47E009 (SRTM3, the Alpine Rhine valley and the
 * Raetikon: the board's terrain) it gives exactly the meshes of bt_mesh_init while they
 * fit, takes less memory, falls back to the budget rule when they do not (a budget
 * its smaller heap buys, which then fits the vertices; the memory is allocated to the
 * byte, ASan run), and refuses capacities below 16.  With the budget heap sized on its
 * own (bt_mesh_init_vb, as the board sizes it): the same meshes where they fit, 16 bytes
 * less a heap entry, and a coarser fallback where they do not. */
#include "tests/test.h"
#include "tests/support/btcheck.h"
#include "core/bitree.h"

#define SIDE 257
#define MAX_TRI 8192

/* the crop at column 560, row 880 and its tree (memory in *tm) */
static int crop_tree(const hf *f, hf *g, bt_tree *t, void **tm)
{
    void *scr;
    int32_t y;
    *g = *f;
    g->w = g->h = SIDE;
    g->z = malloc((size_t)SIDE * SIDE * 4);
    if (!g->z) return 1;
    for (y = 0; y < SIDE; y++) memcpy(g->z + (size_t)y * SIDE, f->z + (size_t)(y + 880) * f->w + 560, SIDE * 4);
    *tm = malloc(bt_mem_size(SIDE, SIDE));
    scr = malloc(bt_scratch_size(SIDE, SIDE));
    if (!*tm || !scr) { free(scr); return 1; }
    CHECK_EQ(bt_build(t, g, BT_METRIC_EXACT, *tm, bt_mem_size(SIDE, SIDE), scr, bt_scratch_size(SIDE, SIDE)), BR_OK);
    free(scr);
    return 0;
}

/* frame k of a camera 1.9 km up over the valley looking south-east, 250 m a frame */
static void camera(int32_t us, int32_t k, cam *c)
{
    int32_t eye[3], tgt[3];
    eye[0] = (2500 + 128 * k) << us; eye[1] = (20000 - 215 * k) << us; eye[2] = 1900 << us;
    tgt[0] = (12000 + 128 * k) << us; tgt[1] = (4000 - 215 * k) << us; tgt[2] = 1300 << us;
    CHECK_EQ(cam_look_at(c, eye, tgt, 60000, 320, 240, 1 << us, 60000 << us), BR_OK);
}

static void test_same_meshes_less_memory(void)
{
    hf f, g1, g2;
    bt_tree t1, t2;
    bt_mesh m1, m2;
    bt_params p;
    bt_frame fr;
    cam c;
    hf g3;
    bt_tree t3;
    bt_mesh m3;
    void *tm1 = NULL, *tm2 = NULL, *tm3 = NULL, *mem1, *mem2, *mem3;
    int32_t k, us;
    const uint32_t max_v = 3072;
    size_t s1 = bt_mesh_mem_size(MAX_TRI), s2 = bt_mesh_mem_size_v(MAX_TRI, max_v);
    /* a heap for 600 triangles: 4 x 600 + 8 entries instead of 4 x 1536 + 8 */
    size_t s3 = bt_mesh_mem_size_vb(MAX_TRI, max_v, 600);
    if (btc_load("hgt/N47E009.hgt", &f)) { CHECK(0); return; }
    if (crop_tree(&f, &g1, &t1, &tm1) || crop_tree(&f, &g2, &t2, &tm2) || crop_tree(&f, &g3, &t3, &tm3)) {
        CHECK(0);
        return;
    }
    CHECK(s2 > 0 && s2 + 500000 < s1);   /* vertices and hash: 344 KB + 229 KB less */
    CHECK_EQ(bt_mesh_mem_size_v(MAX_TRI, 0), s1);
    CHECK_EQ(bt_mesh_mem_size_v(MAX_TRI, 10 * MAX_TRI), s1);
    CHECK_EQ(s3 + (size_t)16 * 4 * (1536 - 600), s2);
    CHECK_EQ(bt_mesh_mem_size_vb(MAX_TRI, max_v, 0), s2);
    CHECK_EQ(bt_mesh_scratch_size_vb(MAX_TRI, max_v, 600) + (size_t)16 * 4 * (1536 - 600),
             bt_mesh_scratch_size_v(MAX_TRI, max_v));
    mem1 = malloc(s1); mem2 = malloc(s2); mem3 = malloc(s3);
    CHECK_EQ(bt_mesh_init_vb(&m3, MAX_TRI, max_v, 600, mem3, s3 - 1), BR_E_ARG);
    CHECK_EQ(bt_mesh_init_vb(&m3, MAX_TRI, max_v, 600, mem3, s3), BR_OK);
    CHECK_EQ(bt_mesh_init(&m1, MAX_TRI, mem1, s1), BR_OK);
    CHECK_EQ(bt_mesh_init_v(&m2, MAX_TRI, max_v, mem2, s2), BR_OK);
    CHECK_EQ(m2.cap_v, max_v);
    CHECK_EQ(bt_frame_auto(&g1, &fr, &us), BR_OK);
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW; p.fr = fr; p.c = &c; p.hyst_q8 = 64; p.morph_q8 = 128; p.pixel_err_q8 = 448;
    for (k = 0; k < 6; k++) {
        camera(us, k, &c);
        CHECK_EQ(bt_extract(&t1, &p, &m1), BR_OK);
        CHECK_EQ(bt_extract(&t2, &p, &m2), BR_OK);
        CHECK(m1.ntri > 3000 && m1.nv < max_v - 64);
        CHECK_EQ(m1.overflow, 0); CHECK_EQ(m2.overflow, 0);
        CHECK_EQ(m2.nv, m1.nv); CHECK_EQ(m2.ns, m1.ns); CHECK_EQ(m2.ntri, m1.ntri);
        CHECK(m1.nv == m2.nv && !memcmp(m1.v, m2.v, sizeof *m1.v * m1.nv));
        CHECK(m1.ns == m2.ns && !memcmp(m1.strip, m2.strip, 4 * (size_t)m1.ns));
        CHECK_EQ(bt_extract(&t3, &p, &m3), BR_OK);
        CHECK_EQ(m3.overflow, 0);
        CHECK(m3.nv == m2.nv && !memcmp(m3.v, m2.v, sizeof *m2.v * m2.nv));
        CHECK(m3.ns == m2.ns && !memcmp(m3.strip, m2.strip, 4 * (size_t)m2.ns));
    }
    free(mem1); free(mem2); free(mem3); free(tm1); free(tm2); free(tm3);
    free(g1.z); free(g2.z); free(g3.z); free(f.z);
}

static void test_too_few_vertices_fall_back(void)
{
    hf f, g;
    bt_tree t;
    bt_mesh m;
    bt_params p;
    bt_frame fr;
    cam c;
    void *tm = NULL, *mem;
    int32_t us;
    size_t s = bt_mesh_mem_size_v(MAX_TRI, 256);
    br_status st;
    if (btc_load("hgt/N47E009.hgt", &f)) { CHECK(0); return; }
    if (crop_tree(&f, &g, &t, &tm)) { CHECK(0); return; }
    mem = malloc(s);                      /* to the byte: ASan sees any write past it */
    CHECK_EQ(bt_mesh_init_v(&m, MAX_TRI, 256, mem, s), BR_OK);
    CHECK_EQ(bt_frame_auto(&g, &fr, &us), BR_OK);
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW; p.fr = fr; p.c = &c; p.hyst_q8 = 64; p.morph_q8 = 128; p.pixel_err_q8 = 448;
    camera(us, 0, &c);
    /* the budget fallback's heap is sized by the vertices too, so what it buys fits them */
    st = bt_extract(&t, &p, &m);
    CHECK_EQ(st, BR_OK);
    CHECK_EQ(m.overflow, 1);
    CHECK(m.nv <= 256 && m.ntri >= 64);
    /* its heap and id list: 20 bytes an entry, 4 entries a triangle, 128 triangles */
    CHECK(bt_mesh_mem_size_v(MAX_TRI, 256) + (size_t)20 * 4 * (MAX_TRI - 128) <= bt_mesh_mem_size(MAX_TRI));
    {   /* a heap for 40 triangles (168 entries; the least is 520 / 4 + 2 = 132): the
         * fallback stops when the heap is full, with fewer triangles, still a mesh (the
         * fallback above left t's hysteresis clear: mb starts where m did) */
        const uint32_t full = m.ntri;
        size_t s40 = bt_mesh_mem_size_vb(MAX_TRI, 256, 40);
        void *m40 = malloc(s40);
        bt_mesh mb;
        CHECK_EQ(s40 + (size_t)16 * (520 - 168), s);
        CHECK_EQ(bt_mesh_mem_size_vb(MAX_TRI, 256, 1) + (size_t)16 * (520 - 132), s);   /* the least */
        CHECK_EQ(bt_mesh_init_vb(&mb, MAX_TRI, 256, 40, m40, s40), BR_OK);
        st = bt_extract(&t, &p, &mb);
        CHECK_EQ(st, BR_OK);
        CHECK_EQ(mb.overflow, 1);
        CHECK_MSG(mb.ntri >= 40 && mb.ntri < full, "%u triangles with the small heap, %u with the full one", mb.ntri,
                  full);
        CHECK(mb.ns >= mb.ntri + 2);
        free(m40);
    }
    free(mem); free(tm); free(g.z); free(f.z);
}

static void test_bad_capacity(void)
{
    static uint64_t mem[1 << 12];
    bt_mesh m;
    CHECK_EQ(bt_mesh_mem_size_v(64, 8), 0);
    CHECK_EQ(bt_mesh_init_v(&m, 64, 8, mem, sizeof mem), BR_E_ARG);
    CHECK_EQ(bt_mesh_init_v(&m, 64, 16, mem, bt_mesh_mem_size_v(64, 16) - 1), BR_E_ARG);
    CHECK_EQ(bt_mesh_init_v(&m, 64, 16, mem, sizeof mem), BR_OK);
    CHECK_EQ(m.cap_v, 16);
}

int main(void)
{
    T_RUN(test_same_meshes_less_memory);
    T_RUN(test_too_few_vertices_fall_back);
    T_RUN(test_bad_capacity);
    return t_finish();
}
