/* tests/test_coherence.c — frame coherence of the view selection (core/bt_coh.c,
 * docs/bitree.md "Frame coherence"): with decisions reused across frames, every
 * frame's mesh is byte for byte the one a from-scratch extraction (p->no_coherence)
 * gives for the same camera and hysteresis state, serially and in parts.
 * Two copies of the tree share its nodes and keep their own frame state; each frame
 * both extract and the vertices, strip, counts and frame state (the split list the
 * next frame's hysteresis reads) are compared.
 * Scenes: the default terrain (assets/N47E009.hgt.gz) along the shipped camera paths
 * and a 20 m a frame flight with stops, jumps, turns and parameter changes; the
 * same flight over mt_rainier_90m.tif and fuji.png (../shared/data/dem, with voids).
 * A margin made too generous by the test hook (bt_coh.slack) must show.  The view
 * rule's distance itself: a lower bound, near the Euclidean one, 1-Lipschitz. */
#include <math.h>
#include "tests/test.h"
#include "platform/campath.h"
#include "platform/scene.h"
#include "core/bt_em.h"
#include "core/config.h"

#define W 320
#define H 240
#define MAX_TRI 400000u

typedef struct side {
    bt_tree t;
    bt_mesh m;
    void *mm;
    bt_parts *ps;
    void *pm;
} side;

static scene sc;
static side A, B;           /* A: coherent, B: from scratch */
static long frames, differ;
static long parts_run, parts_reused;   /* A's parts, and those its last mesh served */
static long parts_resumed;             /* A's parts walked again from a changed decision */
static uint32_t parts_most;            /* A's most parts in a frame */
static long serial_frames;             /* A's frames extracted serially after all */
static uint32_t part_tri = 4096;       /* triangles a part holds (side_open; the scene's) */
static double fovy = 60;               /* the cameras' vertical field of view, degrees */
static int windowed;                   /* 1: frame() culls to a window that moves each frame */

static int side_open(side *s)
{
    size_t mb = bt_mesh_mem_size(MAX_TRI), pb = bt_parts_mem_size(part_tri);
    memset(s, 0, sizeof *s);
    s->t = sc.tree;
    s->t.st = calloc(bt_state_size(sc.tree.nslot), 1);
    s->mm = malloc(mb);
    s->pm = malloc(pb);
    if (!s->t.st || !s->mm || !s->pm) return 0;
    return bt_mesh_init(&s->m, MAX_TRI, s->mm, mb) == BR_OK && bt_parts_init(&s->ps, part_tri, s->pm, pb) == BR_OK;
}

static void side_close(side *s)
{
    free(s->t.st); free(s->mm); free(s->pm);
    memset(s, 0, sizeof *s);
}

static int open_dem(const char *path)
{
    br_err err;
    const char *in[1];
    scene_opts o;
    in[0] = path;
    memset(&o, 0, sizeof o);
    o.quiet = 1;
    memset(&sc, 0, sizeof sc);
    if (scene_open(&sc, in, 1, &o, &err) != BR_OK) { fprintf(stderr, "%s\n", err.msg); return 0; }
    if (scene_tree(&sc, &err) != BR_OK) { fprintf(stderr, "%s\n", err.msg); return 0; }
    return side_open(&A) && side_open(&B);
}

static void close_dem(void)
{
    side_close(&A); side_close(&B);
    scene_close(&sc);
}

static br_status extract(side *s, const bt_params *p, int parts)
{
    uint32_t n, k, v0, nv;
    br_status st;
    if (!parts) return bt_extract(&s->t, p, &s->m);
    st = bt_extract_begin(s->ps, &s->t, p, &s->m, &n);
    if (st != BR_OK) return st;
    for (k = n; k-- > 0;) bt_extract_part(s->ps, k);     /* any order */
    st = bt_extract_end(s->ps, &n);
    for (k = 0; k < n; k++) bt_extract_join(s->ps, k, &v0, &nv);
    if (s == &A) {
        serial_frames += n == 0;
        parts_run += n;
        parts_reused += bt_parts_reused(s->ps);
        parts_resumed += bt_parts_resumed(s->ps);
        if (n > parts_most) parts_most = n;
    }
    return st;
}

/* 1 when A's and B's meshes and frame states are the same */
static int same(void)
{
    const bt_mesh *a = &A.m, *b = &B.m;
    return a->nv == b->nv && a->ns == b->ns && a->ntri == b->ntri && a->nline == b->nline && a->nfict == b->nfict
        && a->overflow == b->overflow && a->nsplits == b->nsplits
        && !memcmp(a->v, b->v, (size_t)a->nv * sizeof *a->v) && !memcmp(a->strip, b->strip, (size_t)a->ns * 4)
        && !memcmp(A.t.st, B.t.st, bt_state_size(sc.tree.nslot));
}

static uint64_t fnv_mesh(const bt_mesh *m)
{
    const uint8_t *b = (const uint8_t *)m->v;
    uint64_t h = 0xcbf29ce484222325ull;
    size_t i;
    for (i = 0; i < (size_t)m->nv * sizeof *m->v; i++) h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

typedef struct knobs { int32_t mode, pix_q8, hyst_q8, morph_q8, w, h, parts; uint32_t budget; } knobs;

/* Every record of a part keeps its slot's bit of the ST_PREV plane (bti_rec.pbit): a
 * replay's proof reads that bit, and a wrong one would change a mesh only where the
 * neighbouring slot's bit differs from the record's own */
static int recs_keep_pbit(const bt_parts *ps)
{
    uint32_t k, i;
    if (!ps) return 1;
    for (k = 0; k < BT_PARTS; k++)
        for (i = 0; i < ps->slot[k].nrec && i < ps->cap_rec; i++)
            if (ps->slot[k].rec[i].pbit != 1u << (ps->slot[k].rec[i].idx & 7u)) return 0;
    return 1;
}

/* One frame on both sides; counts frames whose meshes differ, or whose records'
 * masks are wrong (differ). */
static int frame(const double eye[6], const knobs *k)
{
    cam c;
    bt_params pa, pb;
    if (scene_camera(&sc, eye, eye + 3, fovy, k->w, k->h, &c) != BR_OK) return 0;
    memset(&pa, 0, sizeof pa);
    pa.mode = k->mode;
    pa.c = &c;
    pa.fr = sc.rt.fr;
    pa.pixel_err_q8 = k->pix_q8; pa.hyst_q8 = k->hyst_q8; pa.morph_q8 = k->morph_q8;
    pa.budget = k->budget;
    if (windowed) {     /* a third of the screen a side or more, stepping over it; 2: the middle third */
        static int32_t win[4];
        win[0] = windowed == 2 ? k->w / 3 : (int32_t)(frames * 7 % (k->w / 2));
        win[1] = windowed == 2 ? k->h / 3 : (int32_t)(frames * 5 % (k->h / 2));
        win[2] = win[0] + k->w / 3 + (windowed == 2 ? 0 : (int32_t)(frames % 40));
        win[3] = win[1] + k->h / 3 + (windowed == 2 ? 0 : (int32_t)(frames % 30));
        pa.window = win;
    }
    pb = pa;
    pb.no_coherence = 1;
    if (extract(&A, &pa, k->parts) != BR_OK || extract(&B, &pb, k->parts) != BR_OK) return 0;
    frames++;
    if (!same() || !recs_keep_pbit(A.ps)) differ++;
    return A.m.ntri > (windowed ? 0u : 100u);
}

static const knobs VIEWER = { BT_VIEW, 256, 64, 128, W, H, 1, 0 };

static void fly_path(const char *file, int parts, int nmax, int32_t pix_q8)
{
    campath cp;
    br_err err;
    knobs k = VIEWER;
    int i, ok = 1;
    k.parts = parts;
    k.pix_q8 = pix_q8;
    CHECK(campath_read(file, &cp, &err) == BR_OK);
    if (!cp.n) return;
    frames = differ = 0;
    for (i = 0; i < cp.n && i < nmax; i++) ok &= frame(cp.cam[i], &k);
    CHECK_MSG(ok, "%s", file);
    CHECK_MSG(differ == 0, "%s: %ld of %ld frames differ", file, differ, frames);
    campath_free(&cp);
}

/* Fills a lent scratch as a hostile borrower would: random words, then in the memo's
 * slots entries of the next extraction's generation that say "split" for the diamonds
 * those slots hold (core/bt_mesh.c decide_memo's layout): reused, they would refine
 * everything. */
static void spoil_scratch(bt_mesh *m, uint64_t *w, size_t bytes)
{
    const uint64_t gen = (uint64_t)(m->memo_gen + 1) << 48;
    uint32_t idx, nidx = 4 * (m->memo_mask + 1);
    size_t i;
    for (i = 0; i < bytes / 8; i++) w[i] = t_xs64();
    for (idx = 0; idx < nidx && idx < sc.tree.nslot; idx++)
        m->memo[((idx * 2654435761u >> 8) & m->memo_mask) * BTI_MEMO_W] = gen | (uint64_t)2 << 46 | idx;
}

/* A mesh whose scratch is lent out between frames (bt_mesh_lend_scratch, what the board
 * does with its raster vertices): A lends its scratch after each extraction and spoils
 * it, and still gives B's meshes and frame states; the spoiling must not reach the
 * vertices, the strip or the split list the next frame's hysteresis reads.  Then A's
 * vertex array is overwritten too (the board draws its bands there): the next
 * extraction must not read the old vertices. */
static void test_coherence_lent_scratch(void)
{
    campath cp;
    br_err err;
    knobs k = VIEWER;
    size_t bytes = 0;
    uint32_t i;
    int f, ok = 1, lost_memo = 0;
    if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); return; }
    CHECK(campath_read("assets/lake-path.cam", &cp, &err) == BR_OK);
    k.parts = 0;
    frames = differ = 0;
    for (f = 0; f < cp.n && f < 40; f++) {
        uint64_t *w;
        ok &= frame(cp.cam[f], &k);
        CHECK(!A.m.lent);
        w = (uint64_t *)bt_mesh_lend_scratch(&A.m, &bytes);
        CHECK(w != NULL && ((uintptr_t)w & 7) == 0);
        CHECK_EQ(bytes, bt_mesh_scratch_size_v(MAX_TRI, 0));
        lost_memo += (uint8_t *)A.m.memo >= (uint8_t *)w && (uint8_t *)A.m.memo < (uint8_t *)w + bytes;
        spoil_scratch(&A.m, w, bytes);
        if (!same()) differ++;      /* the spoiling left the mesh and the frame state alone */
        for (i = 0; i < A.m.cap_v; i++) {          /* the vertices are output only */
            A.m.v[i].x = (int32_t)(i % 7); A.m.v[i].y = (int32_t)(i % 5); A.m.v[i].z = -1;
        }
    }
    CHECK_EQ(lost_memo, f);
    CHECK_MSG(ok, "lake path");
    CHECK_MSG(differ == 0, "lent scratch: %ld of %ld frames differ", differ, frames);
    CHECK(bt_mesh_lend_scratch(NULL, &bytes) == NULL && bytes == 0);
    CHECK_EQ(bt_mesh_scratch_size_v(1, 0), 0);
    campath_free(&cp);
    close_dem();
}

/* The shipped paths on the default terrain, frame by frame (about 16 m a frame), in
 * parts (the viewer's and the bench's way) and serially. */
static void test_coherence_paths(void)
{
    if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); return; }
    parts_run = parts_reused = 0;
    parts_most = 0;
    fly_path("assets/default-path.cam", 1, 300, 256);
    /* most parts keep their mesh from one frame to the next along the path (core/
     * bt_replay.c bti_part_replay); the comparison above proves those meshes, also while
     * the parts near the eye are cut finer than depth 4's 32 (core/bt_part.c regroup) */
    CHECK_MSG(parts_reused * 4 > parts_run * 3, "%ld of %ld parts reused", parts_reused, parts_run);
    CHECK_MSG(parts_most > 32, "at most %u parts", parts_most);
    parts_run = parts_reused = parts_resumed = 0;
    fly_path("assets/lake-path.cam", 1, 300, 256);
    /* where a part's decision changed, most of its walks took up the last one there
     * (core/bt_replay.c bti_part_resume): the comparison above proves those meshes */
    CHECK_MSG(parts_resumed * 2 > parts_run - parts_reused, "%ld parts resumed of %ld walked", parts_resumed,
              parts_run - parts_reused);
    /* 64 px: a coarse mesh, other parts replayed and other splits moving */
    fly_path("assets/default-path.cam", 1, 300, 64 * 256);
    fly_path("assets/alps-path.cam", 0, 120, 256);     /* its first 120 frames: 18 k triangles each */
    close_dem();
}

/* A selection culled to a screen window (bt_params.window, as the reflection's own LOD
 * reads only the rows and columns around its water) that moves every frame: the planes'
 * travel that frame coherence accounts for includes the window's, so every frame is the
 * from-scratch mesh, serially and in parts.  The window leaves triangles out; a window
 * outside the screen is refused. */
static void test_coherence_window(void)
{
    static const int32_t bad[4][4] = { { -1, 0, 10, 10 }, { 0, 0, W + 1, 10 }, { 5, 0, 5, 10 }, { 0, 20, 10, 19 } };
    const double eye[6] = { -20683.0, -2764.5, 59448.4, 37671.8, 55590.3, 1662.5 };
    bt_params p;
    cam c;
    uint32_t whole;
    int i;
    if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); return; }
    CHECK(frame(eye, &VIEWER));
    whole = A.m.ntri;
    windowed = 1;
    fly_path("assets/default-path.cam", 1, 100, 256);
    fly_path("assets/lake-path.cam", 1, 100, 256);
    fly_path("assets/default-path.cam", 0, 30, 256);
    windowed = 2;
    CHECK(frame(eye, &VIEWER));
    printf("the middle third of %d x %d: %u triangles, %u without\n", W, H, A.m.ntri, whole);
    CHECK_MSG(A.m.ntri * 2 < whole && A.m.ntri > 100, "%u triangles in the window, %u without", A.m.ntri, whole);
    windowed = 0;
    CHECK_EQ(scene_camera(&sc, eye, eye + 3, fovy, W, H, &c), BR_OK);
    memset(&p, 0, sizeof p);
    p.mode = BT_VIEW; p.c = &c; p.fr = sc.rt.fr; p.pixel_err_q8 = 256;
    for (i = 0; i < 4; i++) {
        p.window = bad[i];
        CHECK_EQ(bt_extract(&B.t, &p, &B.m), BR_E_ARG);
    }
    close_dem();
}

/* Parts too small for the first frames: a part that fills its mesh is cut and extracted
 * again in the same frame (core/bt_part.c retry_full); one still full after that sends
 * the frame to the serial extraction and is cut from the next frame on, until the parts
 * fit.  Parts of 700 triangles: the retries are enough; of 150: one frame goes serial.
 * Every frame is the from-scratch mesh. */
static void test_coherence_full_parts(void)
{
    static const uint32_t sizes[2] = { 700, 150 };
    int i;
    for (i = 0; i < 2; i++) {
        part_tri = sizes[i];
        if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); break; }
        parts_run = parts_reused = serial_frames = 0;
        fly_path("assets/default-path.cam", 1, 40, 256);
        CHECK_MSG(parts_run > 0 && parts_reused > 0, "%ld parts joined, %ld reused", parts_run, parts_reused);
        if (i == 0) CHECK_MSG(serial_frames == 0, "%ld frames serial with parts of 700", serial_frames);
        else CHECK_MSG(serial_frames > 0, "no frame serial with parts of 150");
        close_dem();
    }
    part_tri = 4096;
}

/* The first frame of a view with many triangles near the eye: low over the lake at
 * 1280x720 and 0.5 px (about 80 k triangles), parts of the scene's size (4096
 * triangles).  The first cut follows the screen (core/bt_part.c cut_initial: 128
 * triangles at depth 6, those in view become parts); the parts ahead of the eye still
 * fill their meshes, and are cut and extracted again in the same frame (retry_full):
 * the first frame is joined from its parts, not extracted serially (without the retry:
 * 0 parts).  Every frame is the from-scratch mesh. */
static void test_coherence_first_cut(void)
{
    campath cp;
    br_err err;
    knobs k = VIEWER;
    int i, ok = 1;
    if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); return; }
    CHECK(campath_read("assets/lake-path.cam", &cp, &err) == BR_OK);
    k.w = 1280; k.h = 720; k.pix_q8 = 128;
    frames = differ = 0;
    parts_most = 0;
    ok &= frame(cp.cam[0], &k);
    CHECK_MSG(parts_most > 32, "first frame joined from %u parts (0: serial)", parts_most);
    CHECK_MSG(A.m.ntri > 60000, "%u triangles", A.m.ntri);
    for (i = 1; i < 8 && i < cp.n; i++) ok &= frame(cp.cam[i], &k);
    CHECK(ok);
    CHECK_MSG(differ == 0, "%ld of %ld frames differ", differ, frames);
    campath_free(&cp);
    close_dem();
}

/* Part roots whose own corners move.  On N47E009 the diamonds above the parts are split
 * at full weight on every shipped path, so a replayed part's root corners keep their
 * heights there.  crater_0513.bt (513^2, no padding: the top diamonds carry their real
 * errors) at 32 px, descending 25 m a frame towards eight points of the grid's coarse
 * lattice: the top splits' weights move while the parts below keep their decisions, and
 * a replayed part must take its corners' new heights (without it, 264 of 288 frames
 * differ). */
static void test_coherence_root_corners(void)
{
    static const int at[8][2] = { { 128, 128 }, { 256, 256 }, { 384, 384 }, { 384, 128 },
                                  { 128, 384 }, { 256, 128 }, { 128, 256 }, { 256, 384 } };
    knobs k = VIEWER;
    int i, j;
    if (!open_dem("../shared/data/dem/bt/crater_0513.bt")) { CHECK(0); return; }
    k.pix_q8 = 32 * 256;
    frames = differ = 0;
    parts_run = parts_reused = 0;
    for (i = 0; i < 8; i++)
        for (j = 0; j < 36; j++) {
            const double x = at[i][0] * 20.182251, y = at[i][1] * 27.304688;   /* its spacing */
            const double eye[6] = { x - 300, y - 300, 7000 - 25 * j, x + 2000, y + 2000, 1500 };
            CHECK(frame(eye, &k) || A.m.ntri > 0);
        }
    CHECK_MSG(differ == 0, "%ld of %ld frames differ", differ, frames);
    CHECK_MSG(parts_reused * 2 > parts_run, "%ld of %ld parts reused", parts_reused, parts_run);
    close_dem();
}

/* A flight over the scene towards its far corner at 20 m a frame, 1500 m above the
 * highest sample at the start, descending, with stops (the same camera again), turns
 * on the spot, a slow pan from one place, jumps, and frames with other parameters
 * in between (hysteresis off, no geomorph, another pixel error, another size, the
 * budget rule); every frame compared. */
static void flight(int parts, int64_t slack)
{
    int i;
    A.m.coh.slack = slack;
    A.ps->coh.slack = slack;
    for (i = 0; i < 160; i++) {
        knobs k = VIEWER;
        double e[6], a = 0.6 + 0.002 * i, t = i < 60 ? i : (i < 64 ? 60 : (i < 110 ? i - 4 : (i < 130 ? 106 : i - 24)));
        k.parts = parts;
        if (i >= 90 && i < 93) a += 0.4 * (i - 89);          /* turns on the spot */
        if (i >= 110 && i < 130) a += 0.004 * (i - 110);      /* a slow pan: only the planes move */
        e[0] = 0.15 * sc.width_m + 20.0 * t * 0.8;
        e[1] = 0.10 * sc.depth_m + 20.0 * t * 0.6;
        if (i >= 100) e[0] += 0.2 * sc.width_m;                /* jumps */
        if (i >= 101) e[1] += 0.2 * sc.depth_m;
        e[2] = sc.zmax_m + 1500.0 - 5.0 * i;
        e[3] = e[0] + 3000 * cos(a); e[4] = e[1] + 3000 * sin(a); e[5] = e[2] - 900;
        if (i == 70) k.hyst_q8 = 0;
        if (i == 72) k.morph_q8 = 0;
        if (i == 74) k.pix_q8 = 400;
        if (i == 76) { k.w = 640; k.h = 480; }
        if (i == 78) { k.mode = BT_BUDGET; k.budget = 3000; }
        (void)frame(e, &k);
    }
}

/* World units (core/cam.h) in a metre: the frame's grid step over the sample spacing */
static int64_t metre(void)
{
    return (int64_t)((double)sc.rt.fr.sx * (sc.f.w - 1) / sc.width_m + 0.5);
}

static void test_coherence_flights(void)
{
    static const char *dems[] = { "assets/N47E009.hgt.gz", "tif/mt_rainier_90m.tif", "png/fuji.png" };
    int d;
    for (d = 0; d < 3; d++) {
        const char *path = d ? t_data(dems[d]) : dems[d];
        if (!open_dem(path)) { CHECK_MSG(0, "%s", dems[d]); continue; }
        frames = differ = 0;
        flight(0, 0);
        flight(1, 0);
        CHECK_MSG(frames == 320 && differ == 0, "%s: %ld of %ld frames differ", dems[d], differ, frames);
        close_dem();
    }
}

/* The comparison sees a margin that is too generous: 20 m more travel before a
 * decision is evaluated again gives other meshes. */
static void test_coherence_margin_matters(void)
{
    if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); return; }
    frames = differ = 0;
    flight(1, 20 * metre());
    CHECK_MSG(differ > 0 || !BR_COHERENCE, "%ld of %ld frames differ", differ, frames);
    frames = differ = 0;
    flight(0, 20 * metre());
    CHECK_MSG(differ > 0 || !BR_COHERENCE, "%ld of %ld frames differ", differ, frames);
    /* the runs of distances that keep a replayed part's geomorph weights
     * (bti_coh_weight_run) 20 m longer at each end */
    frames = differ = 0;
    A.ps->wt.slack = 20 * metre();
    flight(1, 0);
    A.ps->wt.slack = 0;
    CHECK_MSG(differ > 0 || !BR_COHERENCE, "%ld of %ld frames differ", differ, frames);
    close_dem();
}

/* The distance margins of the two kinds of split that got entries last (core/bt_coh.c
 * margin), taken from bti_coh_entry with no planes to test (the expiry less the eye's
 * accumulator), against the rule itself at the margin's ends: a split with the eye
 * inside its volume (d = 0, full weight) stays split with a full weight out to that
 * distance; a split whose weight is 0 with floor(L / d) at tau or above keeps weight 0
 * and its split over the whole interval.  The flights cannot show a margin too long
 * here: these diamonds' rooms to the frustum planes end their entries first. */
static void test_entry_margins(void)
{
    long i, n = t_emulated() ? 20000 : 200000, inside = 0, zero = 0, above = 0, bad = 0;
    const bt_coh *c;
    bti_extract e;
    const double eye[6] = { 20000, 20000, 3000, 23000, 22000, 2000 };
    knobs k = VIEWER;
    if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); return; }
    k.parts = 0;
    (void)frame(eye, &k);             /* the coherent side's state: its thresholds' reciprocals */
    c = &A.m.coh;
    memset(&e, 0, sizeof e);
    e.coh = (bt_coh *)c;
    e.tau = c->key.tau; e.tau_lo = c->key.tau_lo; e.morph_span = c->key.span;
    for (i = 0; i < n && BR_COHERENCE; i++) {
        const unsigned bits = 20 + (unsigned)(t_xs64() % 20);     /* (one draw a statement) */
        const int64_t L = 1 + (int64_t)(t_xs64() % ((uint64_t)1 << bits));
        const int64_t d = i & 1 ? 1 + L / (e.tau + (int64_t)(t_xs64() % 8)) : 0;
        const uint16_t w = d ? bti_morph_at(&e, L, d) : BT_MORPH_ONE;
        uint64_t x;
        int64_t m;
        if (d && (w != 0 || L <= e.tau_lo * d)) continue;   /* not a split of weight 0 */
        x = bti_coh_entry(&e, 1, L, d, w, 0, 0, INT64_MAX);
        if (!x) { bad += !d; continue; }                    /* d = 0 always has one */
        m = (int64_t)((x & BTI_COH_EXP) - c->ctr[BT_COH_EYE]);
        if (!d) {
            inside++;
            bad += bti_morph_at(&e, L, m) != BT_MORPH_ONE || L <= e.tau_lo * m;
        } else {
            zero++;
            above += L / d >= e.tau;                        /* split by the rule, not hysteresis */
            bad += bti_morph_at(&e, L, d + m) != 0 || L <= e.tau_lo * (d + m);
            bad += d - m >= 1 && bti_morph_at(&e, L, d - m) != 0;
        }
    }
    printf("  entry margins: %ld splits with the eye inside, %ld of weight 0 (%ld with floor(L / d) >= tau)\n",
           inside, zero, above);
    CHECK(inside > n / 4 || !BR_COHERENCE);
    CHECK(above > n / 20 || !BR_COHERENCE);
    CHECK(zero > above || !BR_COHERENCE);
    CHECK_EQ(bad, 0);
    close_dem();
}

/* Cameras whose frustum planes move much less than the eye, so that an entry with
 * planes to test is kept by the eye's travel (its distance margin) as much as by the
 * planes' (core/bt_coh.c: each plane accumulator grows by the larger of its planes'
 * travel and a quarter of the eye's, not by the planes' alone): a 170-degree camera
 * sliding sideways (every plane nearly parallel to the slide), and a level camera
 * rising (its left and right planes contain the vertical). */
static void test_coherence_slide(void)
{
    int i, parts, lift;
    if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); return; }
    for (lift = 0; lift < 2; lift++)
        for (parts = 0; parts < 2; parts++) {
            knobs k = VIEWER;
            k.parts = parts;
            fovy = lift ? 60 : 170;
            frames = differ = 0;
            for (i = 0; i < 120; i++) {
                const double a = 0.5, s = 25.0 * i;
                double e[6];
                e[0] = 0.3 * sc.width_m + (lift ? 0 : s * sin(a));
                e[1] = 0.3 * sc.depth_m - (lift ? 0 : s * cos(a));
                e[2] = sc.zmax_m + (lift ? 200.0 + s : 800.0);
                e[3] = e[0] + 3000 * cos(a); e[4] = e[1] + 3000 * sin(a); e[5] = e[2] - (lift ? 0 : 1500);
                (void)frame(e, &k);
            }
            CHECK_MSG(frames == 120 && differ == 0, "%s, parts %d: %ld of %ld frames differ",
                      lift ? "rising" : "sliding", parts, differ, frames);
        }
    fovy = 60;
    close_dem();
}

/* A tree built again into the same memory from other heights (same size, node
 * pointer and height range) is another tree to the memo: the node hash (bt_tree.sum)
 * is part of its key, so the coherent side still matches. */
static void test_coherence_rebuilt_tree(void)
{
    size_t tb, sb;
    void *scratch;
    int32_t x, y, zmin, zmax;
    uint64_t before;
    knobs k = VIEWER;
    double e[6];
    int i;
    if (!open_dem("assets/N47E009.hgt.gz")) { CHECK(0); return; }
    tb = bt_mem_size(sc.f.w, sc.f.h);
    sb = bt_scratch_size(sc.f.w, sc.f.h);
    scratch = malloc(sb);
    CHECK(scratch != NULL);
    if (!scratch) { close_dem(); return; }
    frames = differ = 0;
    k.parts = 0;
    e[0] = 0.3 * sc.width_m; e[1] = 0.3 * sc.depth_m; e[2] = sc.zmax_m + 500;
    e[3] = 0.5 * sc.width_m; e[4] = 0.5 * sc.depth_m; e[5] = sc.zmin_m;
    for (i = 0; i < 3; i++) { CHECK(frame(e, &k)); e[0] += 20; }
    before = fnv_mesh(&B.m);
    zmin = sc.tree.zmin; zmax = sc.tree.zmax;
    /* the heights of the block the camera looks at, mirrored within their range */
    for (y = sc.f.h / 3; y < sc.f.h * 2 / 3; y++)
        for (x = sc.f.w / 3; x < sc.f.w * 2 / 3; x++) {
            int32_t *z = &sc.f.z[(size_t)y * sc.f.w + x];
            if (*z != HF_NODATA && *z > zmin + 1 && *z < zmax - 1) *z = zmax + zmin - *z;
        }
    CHECK_EQ(bt_build(&sc.tree, &sc.f, BT_METRIC_EXACT, sc.tree_mem, tb, scratch, sb), BR_OK);
    CHECK(sc.tree.node == A.t.node && sc.tree.zmin == zmin && sc.tree.zmax == zmax && sc.tree.sum != A.t.sum);
    A.t.node = B.t.node = sc.tree.node;
    A.t.sum = B.t.sum = sc.tree.sum;
    for (i = 0; i < 3; i++) { CHECK(frame(e, &k)); e[0] += 20; }
    CHECK(fnv_mesh(&B.m) != before);        /* the new heights change the mesh */
    CHECK_MSG(differ == 0, "%ld of %ld frames differ", differ, frames);
    free(scratch);
    close_dem();
}

/* a coordinate in [-(2^30 - 1), 2^30 - 1], often near the ends or near 0 */
static int32_t coord(void)
{
    uint64_t r = t_xs64();
    int32_t v = (int32_t)((r >> 8) % ((1u << 30) - 1));
    switch (r & 3) {
    case 0: v = CAM_COORD_MAX - (int32_t)((r >> 40) & 1023); break;
    case 1: v = (int32_t)((r >> 40) & 4095); break;
    default: break;
    }
    return (r >> 2) & 1 ? -v : v;
}

static double euclid(const int32_t eye[3], const int32_t lo[3], const int32_t hi[3])
{
    double s = 0;
    int k;
    for (k = 0; k < 3; k++) {
        double d = eye[k] < lo[k] ? (double)(lo[k] - eye[k]) : eye[k] > hi[k] ? (double)(eye[k] - hi[k]) : 0;
        s += d * d;
    }
    return sqrt(s);
}

/* The view rule's distance (core/bt_int.h bti_box_dist), over the whole coordinate
 * range: never above the Euclidean distance from the eye to the box (so the screen
 * error stays an upper bound), at least 0.962 of it, and moving by at most the eye's
 * L1 move (what the coherence margins rest on, docs/bitree.md (1)). */
static void test_box_dist(void)
{
    long i, n = t_emulated() ? 200000 : 2000000, bad_lo = 0, bad_near = 0, bad_lip = 0;
    double worst = 1;
    for (i = 0; i < n; i++) {
        int32_t eye[3], e2[3], lo[3], hi[3];
        int64_t d, d2, l1 = 0;
        double ex;
        int k;
        for (k = 0; k < 3; k++) {
            int32_t a = coord(), b = coord();
            lo[k] = a < b ? a : b; hi[k] = a < b ? b : a;
            eye[k] = coord();
            e2[k] = eye[k];
            if (t_xs64() & 1) {        /* a move of the eye: small, or anywhere */
                int64_t m = (t_xs64() & 8) ? (int64_t)(t_xs64() % 2001) - 1000 : (int64_t)coord() - eye[k];
                int64_t v = eye[k] + m;
                if (v > CAM_COORD_MAX) v = CAM_COORD_MAX;
                if (v < -CAM_COORD_MAX) v = -CAM_COORD_MAX;
                e2[k] = (int32_t)v;
            }
            l1 += e2[k] > eye[k] ? (int64_t)e2[k] - eye[k] : (int64_t)eye[k] - e2[k];
        }
        d = bti_box_dist(eye, lo, hi);
        d2 = bti_box_dist(e2, lo, hi);
        ex = euclid(eye, lo, hi);
        bad_lo += d < 0 || (double)d > ex;
        bad_near += (double)d < 0.962 * ex - 1;
        bad_lip += (d2 > d ? d2 - d : d - d2) > l1;
        if (ex > 1000 && (double)d / ex < worst) worst = (double)d / ex;
    }
    printf("  box distance: %ld eyes and boxes, worst %.4f of the Euclidean distance\n", n, worst);
    /* bti_norm2_lo's 45-degree form from the 32-bit sum and its carry against the 64-bit
     * sum's product, as written before (its arguments below 2^31.5; the sum carries for
     * about half of these) */
    for (i = 0; i < n; i++) {
        const uint32_t a = (uint32_t)(t_xs64() % 3037000500u) >> (t_xs64() & 1 ? 0 : t_xs64() % 32);
        const uint32_t b = (uint32_t)(t_xs64() % 3037000500u) >> (t_xs64() & 1 ? 0 : t_xs64() % 32);
        const uint32_t h = a > b ? a : b, l = a > b ? b : a;
        uint32_t want = h, v = (uint32_t)(((uint64_t)h * 3784u + (uint64_t)l * 1567u) >> 12);
        if (v > want) want = v;
        v = (uint32_t)(((uint64_t)h * 2896u + (uint64_t)l * 2896u) >> 12);
        if (v > want) want = v;
        bad_lo += bti_norm2_lo(a, b) != want;
    }
    CHECK_EQ(bad_lo, 0);
    CHECK_EQ(bad_near, 0);
    CHECK_EQ(bad_lip, 0);
}

/* The geomorph weight without a 64-bit divide (core/bt_int.h bti_morph_nodiv, the
 * path of targets without one: armhf, the boards) against floor(lhs / d) and morph_of's
 * steps, over both of its ways (32-bit products and divisions, and the bit steps). */
static void test_morph_nodiv(void)
{
    long i, n = t_emulated() ? 200000 : 2000000, bad = 0, fast = 0;
    for (i = 0; i < n; i++) {
        const int db = 1 + (int)(t_xs64() % 40), sb = 1 + (int)(t_xs64() % 20), tb = (int)(t_xs64() % 41);
        const int64_t d = (int64_t)(t_xs64() % ((uint64_t)1 << db)) + 1;
        const int64_t span = (int64_t)(t_xs64() % ((uint64_t)1 << sb)) + 1;
        const int64_t tau = (int64_t)(t_xs64() % ((uint64_t)1 << tb));
        int64_t rho = tau - span + (int64_t)(t_xs64() % (uint64_t)(3 * span + 1)), lhs, q, want;
        if (rho < 0) rho = 0;
        if ((double)rho * (double)d > 4e18) continue;
        lhs = rho * d + (int64_t)(t_xs64() % (uint64_t)d);
        q = lhs / d - tau;
        want = q < 0 ? 0 : q >= span ? BT_MORPH_ONE : q * BT_MORPH_ONE / span;
        bad += bti_morph_nodiv(lhs, d, tau, span) != (uint16_t)want;
        fast += ((uint64_t)(tau + span) | (uint64_t)d) >> 32 == 0;
    }
    printf("  geomorph weight: %ld cases, %ld with 32-bit products\n", n, fast);
    CHECK(fast > n / 4 && fast < n - n / 4);
    CHECK_EQ(bad, 0);
}

/* The distances at which the weight is w, from d (where it is): the first (dir -1) or
 * last (dir 1) one, by bisection (the weight falls as the distance grows). */
static int64_t weight_end(const bti_extract *e, int64_t L, int64_t d, uint16_t w, int dir)
{
    int64_t in = d, out = dir < 0 ? 0 : (int64_t)UINT32_MAX + 1;
    if (dir > 0 && bti_morph_at(e, L, out - 1) == w) return out - 1;
    while (out - in > 1 || in - out > 1) {
        const int64_t mid = in + (out - in) / 2;
        if (mid >= 1 && bti_morph_at(e, L, mid) == w) in = mid;
        else out = mid;
    }
    return in;
}

/* The geomorph weight is a multiple of BT_MORPH_STEP, and the run of box distances that
 * keeps it (core/bt_coh.c bti_coh_weight_run, for which a replayed part keeps a weight)
 * holds it at both ends and reaches within a unit of the last distances that give it
 * (its bounds round towards the shorter run): a whole step of the weight, not one of
 * floor(L / d)'s values. */
static void test_weight_run(void)
{
    long i, n = t_emulated() ? 20000 : 200000, runs = 0, bad = 0, level = 0;
    bti_extract e;
    bti_wtab wt;
    memset(&e, 0, sizeof e);
    memset(&wt, 0, sizeof wt);
    for (i = 0; i < n; i++) {
        const int64_t tau = 64 + (int64_t)(t_xs64() % 512), span = 1 + (int64_t)(t_xs64() % 256);
        const int64_t d = 1 + (int64_t)(t_xs64() % 1000000), L = (int64_t)(t_xs64() % (uint64_t)((tau + span + 8) * d));
        int64_t lo_x, hi_x;
        uint16_t w;
        uint32_t lo, hi;
        e.tau = tau;
        e.morph_span = span;
        bti_wtab_set(&wt, tau, span);
        w = bti_morph_at(&e, L, d);
        bad += w % BT_MORPH_STEP != 0;
        if (w == 0 || w == BT_MORPH_ONE) continue;
        bti_coh_weight_run(&wt, L, w, &lo, &hi);
        if (lo > hi) continue;
        runs++;
        lo_x = weight_end(&e, L, d, w, -1);
        hi_x = weight_end(&e, L, d, w, 1);
        bad += bti_morph_at(&e, L, lo) != w || bti_morph_at(&e, L, hi) != w;
        bad += lo < lo_x || hi > hi_x || lo > lo_x + 1 || hi + 1 < hi_x;
        /* a step of the weight spans several values of floor(L / d) */
        level += L / lo_x - L / hi_x > 0;
    }
    printf("  geomorph weight runs: %ld of %ld cases, %ld over more than one value of L / d\n", runs, n, level);
    CHECK(runs > n / 4);
    CHECK(level > runs / 2);
    CHECK_EQ(bad, 0);
}

int main(void)
{
    T_RUN(test_morph_nodiv);
    T_RUN(test_weight_run);
    T_RUN(test_entry_margins);
    T_RUN(test_box_dist);
    T_RUN(test_coherence_paths);
    T_RUN(test_coherence_full_parts);
    T_RUN(test_coherence_window);
    T_RUN(test_coherence_first_cut);
    T_RUN(test_coherence_root_corners);
    T_RUN(test_coherence_flights);
    T_RUN(test_coherence_margin_matters);
    T_RUN(test_coherence_slide);
    T_RUN(test_coherence_rebuilt_tree);
    T_RUN(test_coherence_lent_scratch);
    return t_finish();
}
