/* tests/test_bitree_layout.c — the bitree's layout (core/bitree.h LAYOUT) and
 * saved trees (bt_tree_save, bt_attach): bytes per sample of the grid as read on
 * every DEM of ../shared/data/dem, a 2 x 16385 grid costing in proportion to its
 * samples, an attached tree giving the built tree's mesh bytes, corrupt blobs
 * refused without reading past them, and a tree without frame state. */
#if defined(__linux__)
#define _DEFAULT_SOURCE
#include <sys/mman.h>
#endif
#include <stdint.h>
#include "tests/test.h"
#include "tests/support/meshcheck.h"
#include "tests/support/btcheck.h"
#include "tests/support/blob_sums.h"
#include "core/bitree.h"
#include "platform/load.h"

static int sanitized(void) { return getenv("BITRAIN_SANITIZED") != NULL; }

static int build(bt_tree *t, const hf *f, void **mem)
{
    size_t ms = bt_mem_size(f->w, f->h), ss = bt_scratch_size(f->w, f->h);
    void *scr = malloc(ss);
    int rc;
    *mem = malloc(ms);
    if (!*mem || !scr) { free(scr); return -1; }
    rc = bt_build(t, f, BT_METRIC_EXACT, *mem, ms, scr, ss) == BR_OK ? 0 : -1;
    free(scr);
    return rc;
}

/* at most 6 bytes of hierarchy (node + frame state) per sample as read, scratch
 * at most 40, on every DEM and on the merged N50 tiles */
static void test_bytes_per_sample(void)
{
    static const char *dems[] = {
        "hgt/N47E009.hgt", "hgt/N50E008.hgt", "hgt/N50E009.hgt", "hgt/N50E010.hgt", "hgt/N57E011.hgt",
        "png/ps_height_1k.png", "bt/crater_0513.bt", "png/fuji.png", "asc/colorado_front_range.asc",
        "asc/hugo_site.asc", "tif/mt_rainier_90m.tif", "xyz/monai_valley_bathymetry.txt"
    };
    size_t i;
    for (i = 0; i <= sizeof dems / sizeof dems[0]; i++) {
        hf f;
        double s, b, sc;
        const char *name = i < sizeof dems / sizeof dems[0] ? dems[i] : "N50E008+N50E009+N50E010";
        if (i < sizeof dems / sizeof dems[0]) {
            if (btc_load(dems[i], &f)) { CHECK(0); continue; }
        } else {
            char p[3][256];
            const char *pp[3] = { p[0], p[1], p[2] };
            dem_opts o;
            br_err err;
            memset(&o, 0, sizeof o);
            snprintf(p[0], 256, "%s", t_data("hgt/N50E008.hgt"));
            snprintf(p[1], 256, "%s", t_data("hgt/N50E009.hgt"));
            snprintf(p[2], 256, "%s", t_data("hgt/N50E010.hgt"));
            if (dem_load_many(pp, 3, &o, &f, &err) != BR_OK) { CHECK_MSG(0, "%s", err.msg); continue; }
        }
        s = (double)f.w * f.h;
        b = (double)bt_mem_size(f.w, f.h) / s;
        sc = (double)bt_scratch_size(f.w, f.h) / s;
        printf("%s %dx%d: hierarchy %.2f bytes per sample (%u slots), build scratch %.2f\n", name, f.w, f.h, b,
               bt_slot_count(f.w, f.h), sc);
        CHECK_MSG(b <= 6.0, "%s: %.2f bytes per sample", name, b);
        CHECK_MSG(sc <= 40.0, "%s: scratch %.2f bytes per sample", name, sc);
        dem_free(&f);
    }
}

/* A 2 x 16385 grid of real heights: N47E009's samples in file order, two to a
 * row (the first 32770 of its 1442401).  The padded hierarchy was 16385^2 x 5
 * bytes (1.3 GB) and 45 s; now it is linear in the samples, and its meshes pass
 * the referee. */
static void test_thin_grid(void)
{
    hf f, g;
    bt_tree t;
    void *mem = NULL;
    bt_params p;
    bt_mesh m;
    void *mm = NULL;
    int32_t *tri, *s;
    mc_vert *v;
    int64_t nt, nl;
    mc_report r;
    mc_opts opt;
    int k;
    if (btc_load("hgt/N47E009.hgt", &f)) { CHECK(0); return; }
    for (k = 0; k < 2; k++) {
        g = f;
        g.w = k ? 16385 : 2; g.h = k ? 2 : 16385;
        g.z = f.z;     /* the first 32770 samples, row-major */
        printf("%dx%d: %zu bytes of hierarchy (%.2f per sample), %zu of scratch\n", g.w, g.h, bt_mem_size(g.w, g.h),
               (double)bt_mem_size(g.w, g.h) / 32770, bt_scratch_size(g.w, g.h));
        CHECK(bt_mem_size(g.w, g.h) <= 16 * 32770);
        CHECK(bt_scratch_size(g.w, g.h) <= 64 * 32770 + 16385 * 12 + 4096);
        if (build(&t, &g, &mem)) { CHECK(0); free(mem); continue; }
        memset(&p, 0, sizeof p);
        p.mode = BT_FIDELITY;
        p.max_err = 20;
        CHECK_EQ(btc_extract(&t, &p, 0, &m, &mm), 0);
        CHECK(m.ntri > 100);
        if (btc_decode(&m, &v, &s, &tri, &nt, &nl) == 0) {
            mc_mesh me = { v, (int32_t)m.nv, tri, nt, 0 };
            memset(&opt, 0, sizeof opt);
            CHECK(mc_check(&me, g.w, g.h, g.z, &opt, &r) == 1);
            CHECK(r.err_q10 <= ((int64_t)20 << 10));
            free(v); free(s); free(tri);
        } else CHECK(0);
        free(mm); free(mem);
    }
    dem_free(&f);
}

/* A read-only copy of the blob (as in flash): a page-protected mapping on Linux,
 * so a write from any extraction would fault; elsewhere a plain copy. */
static const void *ro_copy(const void *blob, size_t n)
{
#if defined(__linux__)
    void *p = mmap(NULL, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return NULL;
    memcpy(p, blob, n);
    if (mprotect(p, n, PROT_READ) != 0) return NULL;
    return p;
#else
    void *p = malloc(n);
    if (p) memcpy(p, blob, n);
    return p;
#endif
}

static void ro_free(const void *p, size_t n)
{
#if defined(__linux__)
    if (p) munmap((void *)(uintptr_t)p, n);
#else
    (void)n;
    free((void *)(uintptr_t)p);
#endif
}

static void view_params(const hf *f, bt_params *p, cam *c, int hyst)
{
    int32_t us, eye[3], tgt[3];
    memset(p, 0, sizeof *p);
    CHECK_EQ(bt_frame_auto(f, &p->fr, &us), BR_OK);
    eye[0] = (int32_t)((int64_t)f->w * f->dx_um / 1000000 / 3 * ((int64_t)1 << us));
    eye[1] = (int32_t)(-(int64_t)f->h * f->dy_um / 1000000 / 4 * ((int64_t)1 << us));
    eye[2] = (int32_t)((int64_t)5000 << us);
    tgt[0] = (int32_t)((int64_t)f->w * f->dx_um / 1000000 / 2 * ((int64_t)1 << us));
    tgt[1] = (int32_t)((int64_t)f->h * f->dy_um / 1000000 / 2 * ((int64_t)1 << us));
    tgt[2] = 0;
    CHECK_EQ(cam_look_at(c, eye, tgt, 60000, 320, 240, 1 << us, (int32_t)(60000 << us)), BR_OK);
    p->mode = BT_VIEW;
    p->c = c;
    p->hyst_q8 = hyst ? 64 : 0;
    p->morph_q8 = 128;
}

/* Saved, attached (from a copy, as from a file or flash) and used: the same mesh
 * bytes as the built tree in fidelity and view modes (a tile with voids), frame
 * after frame with hysteresis, and in budget mode; without frame state, the same
 * view mesh when there is no hysteresis, and BR_E_ARG for the budget rule.  The
 * attached blob is read-only memory: no extraction writes the node array. */
static void test_attach_same(void)
{
    hf f;
    bt_tree t, a, z;
    void *mem = NULL, *blob, *mm1 = NULL, *mm2 = NULL;
    const void *ro;
    uint8_t *st;
    size_t n;
    bt_params p;
    cam c;
    bt_mesh m1, m2;
    int k;
    if (btc_load(sanitized() ? "asc/hugo_site.asc" : "tif/mt_rainier_90m.tif", &f) || build(&t, &f, &mem)) {
        CHECK(0); return;
    }
    n = bt_tree_blob_size(&t);
    CHECK_EQ(n, 64 + (size_t)t.nslot * 4);
    blob = malloc(n);
    st = malloc(bt_state_size(t.nslot));
    CHECK_EQ(bt_tree_save(&t, blob, n), BR_OK);
    CHECK_EQ(bt_tree_save(&t, blob, n - 1), BR_E_ARG);
    bt_blob_to_host(blob, n);         /* big-endian hosts: the node words turned around */
    ro = ro_copy(blob, n);
    CHECK(ro != NULL);
    CHECK_EQ(bt_attach(&a, &f, ro, n, st, bt_state_size(t.nslot)), BR_OK);
    CHECK(!memcmp(a.node, t.node, (size_t)t.nslot * 4));
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.max_err = 10;
    CHECK_EQ(btc_extract(&t, &p, 0, &m1, &mm1), 0);
    CHECK_EQ(btc_extract(&a, &p, 0, &m2, &mm2), 0);
    CHECK(btc_mesh_hash(&m1) == btc_mesh_hash(&m2));
    free(mm1); free(mm2);
    view_params(&f, &p, &c, 1);
    CHECK_EQ(btc_extract(&t, &p, 300000, &m1, &mm1), 0);
    CHECK_EQ(btc_extract(&a, &p, 300000, &m2, &mm2), 0);
    for (k = 0; k < 4; k++) {     /* hysteresis state carried frame to frame */
        c.eye[0] += 40 << 10;
        CHECK_EQ(bt_extract(&t, &p, &m1), BR_OK);
        CHECK_EQ(bt_extract(&a, &p, &m2), BR_OK);
        CHECK(m1.ntri > (sanitized() ? 200u : 1000u));
        CHECK_MSG(btc_mesh_hash(&m1) == btc_mesh_hash(&m2), "frame %d", k);
    }
    free(mm1); free(mm2);
    /* no frame state */
    CHECK_EQ(bt_attach(&z, &f, blob, n, NULL, 0), BR_OK);
    CHECK_EQ(bt_attach(&z, &f, blob, n, st, bt_state_size(t.nslot) - 1), BR_E_ARG);
    view_params(&f, &p, &c, 0);
    CHECK_EQ(btc_extract(&t, &p, 300000, &m1, &mm1), 0);
    CHECK_EQ(btc_extract(&z, &p, 300000, &m2, &mm2), 0);
    CHECK(btc_mesh_hash(&m1) == btc_mesh_hash(&m2));
    p.hyst_q8 = 64;
    CHECK_EQ(bt_extract(&z, &p, &m2), BR_E_ARG);
    p.hyst_q8 = 0;
    p.mode = BT_BUDGET;
    p.budget = 1000;
    CHECK_EQ(bt_extract(&z, &p, &m2), BR_E_ARG);
    free(mm1); free(mm2);
    /* budget rule and its fallback on the read-only tree (frame state in st) */
    p.mode = BT_BUDGET;
    p.budget = 5000;
    CHECK_EQ(btc_extract(&t, &p, 6000, &m1, &mm1), 0);
    CHECK_EQ(btc_extract(&a, &p, 6000, &m2, &mm2), 0);
    CHECK(btc_mesh_hash(&m1) == btc_mesh_hash(&m2));
    free(mm1); free(mm2);
    ro_free(ro, n);
    free(blob); free(st); free(mem);
    dem_free(&f);
}

/* Corrupt blobs: every truncation, every header byte changed, random node bytes
 * and words changed, another grid of the same size: BR_E_ARG, and no read past
 * the given length (ASan in the sanitized run: each blob is copied to a buffer of
 * exactly its length). */
static void test_corrupt_blobs(void)
{
    hf f, g;
    bt_tree t, a;
    void *mem = NULL;
    uint8_t *blob, *bad;
    size_t n, i;
    int bads = 0;
    uint32_t rs = 12345;
    if (btc_load("asc/hugo_site.asc", &f) || build(&t, &f, &mem)) { CHECK(0); return; }
    n = bt_tree_blob_size(&t);
    blob = malloc(n);
    CHECK_EQ(bt_tree_save(&t, blob, n), BR_OK);
    bt_blob_to_host(blob, n);
    for (i = 0; i < n; i += (i < 128 ? 1 : 97)) {         /* truncations */
        bad = malloc(i ? i : 1);
        memcpy(bad, blob, i);
        if (bt_attach(&a, &f, bad, i, NULL, 0) != BR_E_ARG) bads++;
        free(bad);
    }
    CHECK_EQ(bads, 0);
    bad = malloc(n);
    for (i = 0; i < 64 * 8; i++) {                          /* every header bit */
        memcpy(bad, blob, n);
        bad[i / 8] ^= (uint8_t)(1u << (i % 8));
        if (bt_attach(&a, &f, bad, n, NULL, 0) != BR_E_ARG) bads++;
    }
    CHECK_EQ(bads, 0);
    for (i = 0; i < 2000; i++) {                            /* random node bytes */
        size_t at;
        memcpy(bad, blob, n);
        rs = rs * 1103515245u + 12345u;
        at = 64 + (rs >> 4) % (n - 64);
        bad[at] = (uint8_t)(bad[at] + 1 + (rs >> 24) % 255);
        if (bt_attach(&a, &f, bad, n, NULL, 0) != BR_E_ARG) bads++;
    }
    CHECK_EQ(bads, 0);
    CHECK_EQ(bt_attach(&a, &f, blob + 1, n - 1, NULL, 0), BR_E_ARG);   /* misaligned */
    /* the same size, other heights: the fingerprint */
    g = f;
    g.z = malloc((size_t)f.w * f.h * 4);
    memcpy(g.z, f.z, (size_t)f.w * f.h * 4);
    g.z[1234] = g.z[1234] == HF_NODATA ? 1700 : g.z[1234] + 1;
    CHECK_EQ(bt_attach(&a, &g, blob, n, NULL, 0), BR_E_ARG);
    g.w = f.h; g.h = f.w;                                   /* transposed dimensions */
    CHECK_EQ(bt_attach(&a, &g, blob, n, NULL, 0), BR_E_ARG);
    CHECK_EQ(bt_attach(&a, &f, blob, n, NULL, 0), BR_OK);
    free(g.z); free(bad); free(blob); free(mem);
    dem_free(&f);
}

/* Node values made wrong under right checksums (a blob forged, or corrupted where
 * FNV-1a cannot tell): core/bt_blob.c says the walk needs no check of them for memory
 * safety, indexing only 256-entry tables with their bytes.  Random errors and height
 * ranges (not nested), every diamond split (BT_CODE_SPLIT), and one in sixteen of the
 * diamonds void among random ones, each attached and drawn in the view rule frame
 * after frame (hysteresis, geomorph), the budget rule and the fidelity rule: every
 * extraction returns a status, every mesh index names one of its vertices, and the
 * sanitized run reads nothing out of bounds. */
static void test_forged_nodes(void)
{
    hf f;
    bt_tree t, a;
    void *mem = NULL, *mm = NULL;
    uint8_t *blob, *forged, *st;
    size_t n, i;
    uint32_t rs = 2463534242u;
    int kind;
    if (btc_load("asc/hugo_site.asc", &f) || build(&t, &f, &mem)) { CHECK(0); return; }
    n = bt_tree_blob_size(&t);
    blob = malloc(n);
    forged = malloc(n);
    st = malloc(bt_state_size(t.nslot));
    CHECK_EQ(bt_tree_save(&t, blob, n), BR_OK);
    for (kind = 0; kind < 3; kind++) {
        bt_params p;
        cam c;
        bt_mesh m;
        int k, r;
        memcpy(forged, blob, n);
        for (i = BLOB_HDR; i + 4 <= n; i += 4) {        /* the saved node words, little-endian */
            uint32_t lo, hi, v;
            rs ^= rs << 13; rs ^= rs >> 17; rs ^= rs << 5;
            lo = (rs >> 16) & 255u;
            hi = lo + ((rs >> 24) & 255u) > 255u ? 255u : lo + ((rs >> 24) & 255u);
            v = BT_NODE(rs & 0xffffu, lo, hi);      /* kind 0: any error, any height range */
            if (kind == 1) v = BT_NODE(BT_CODE_SPLIT, 0, 255);
            if (kind == 2 && (rs & 15u) == 0) v = BT_NODE_VOID;
            blob_put_le32(forged + i, v);
        }
        blob_fix_sums(forged, n);
        bt_blob_to_host(forged, n);
        CHECK_EQ(bt_attach(&a, &f, forged, n, st, bt_state_size(t.nslot)), BR_OK);
        view_params(&f, &p, &c, 1);
        r = btc_extract(&a, &p, 20000, &m, &mm);
        CHECK_MSG(r == 0, "kind %d: view rule", kind);
        CHECK_MSG(r != 0 || m.ntri > 1000, "kind %d: %u triangles (the forgery must reach the walk)", kind,
                  r == 0 ? m.ntri : 0);
        for (k = 0; r == 0 && k < 4; k++) {
            uint32_t j, bad = 0;
            c.eye[0] += 40 << 10;
            c.eye[2] -= 900 << 10;
            if (bt_extract(&a, &p, &m) != BR_OK) continue;      /* a refusal is a status */
            for (j = 0; j < m.ns; j++) bad += m.strip[j] >= m.nv;
            CHECK_MSG(bad == 0, "kind %d frame %d: %u indices past %u vertices", kind, k, bad, m.nv);
        }
        free(mm); mm = NULL;
        view_params(&f, &p, &c, 0);
        p.mode = BT_BUDGET;
        p.budget = 3000;
        CHECK_MSG(btc_extract(&a, &p, 4000, &m, &mm) == 0, "kind %d: budget rule", kind);
        free(mm); mm = NULL;
        memset(&p, 0, sizeof p);
        p.mode = BT_FIDELITY;
        p.max_err = 10;
        (void)btc_extract(&a, &p, 0, &m, &mm);      /* sized by bt_count: any status */
        free(mm); mm = NULL;
    }
    free(st); free(forged); free(blob); free(mem);
    dem_free(&f);
}

int main(void)
{
    T_RUN(test_bytes_per_sample);
    T_RUN(test_thin_grid);
    T_RUN(test_attach_same);
    T_RUN(test_corrupt_blobs);
    T_RUN(test_forged_nodes);
    return t_finish();
}
