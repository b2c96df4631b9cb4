/* platform/water_scene.c — see water_scene.h. */
#include "platform/water_scene.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "platform/load.h"

static int32_t mm_to_units(const hf *f, int64_t mm)   /* rounded */
{
    double u = (double)mm * f->z_den / ((double)f->z_num * 1000.0);
    return (int32_t)llround(u);
}

static int32_t world_z(const scene *s, int32_t z)   /* heightfield units -> world (as rt_vertex) */
{
    return s->rt.fr.oz + (int32_t)(((int64_t)z * s->rt.fr.sz_q16) >> 16);
}

/* The water from the options: id per sample and the surface heights wz (terrain units). */
static br_status find_water(water_scene *w, scene *s, int32_t *wz, br_err *err)
{
    const hf *f = &s->f;
    const size_t n = (size_t)f->w * (size_t)f->h;
    size_t i;
    if (w->o.water_file) {
        hf wfile;
        dem_opts d;
        int64_t sum = 0, cnt = 0;
        memset(&d, 0, sizeof d);
        if (dem_load(w->o.water_file, &d, &wfile, err) != BR_OK) return err->code;
        if (wfile.w != f->w || wfile.h != f->h) {
            dem_free(&wfile);
            return br_err_set(err, BR_E_VALUE, w->o.water_file, "water surface grid is %dx%d, the terrain %dx%d",
                              wfile.w, wfile.h, f->w, f->h);
        }
        for (i = 0; i < n; i++) {
            int32_t z = wfile.z[i];
            w->id[i] = 0;
            if (z == HF_NODATA || f->z[i] == HF_NODATA) continue;
            w->id[i] = 1;
            wz[i] = mm_to_units(f, hf_z_to_mm(&wfile, z));
            sum += wz[i]; cnt++;
        }
        dem_free(&wfile);
        memset(&w->bodies, 0, sizeof w->bodies);
        if (cnt) {
            w->bodies.n = 1; w->bodies.kind[0] = WT_USER; w->bodies.area[0] = cnt; w->bodies.joined[0] = 1;
            w->bodies.level[0] = (int32_t)(sum / cnt);
        }
        return BR_OK;
    }
    if (w->o.have_level) wt_level(f, mm_to_units(f, llround(w->o.level_m * 1000)), w->id, &w->bodies);
    else {
        wt_params p;
        size_t ws = wt_work_size(f->w, f->h);
        void *work = malloc(ws);
        double cell = (double)f->dx_um * (double)f->dy_um / 1e12;
        br_status st;
        if (!work) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for water detection");
        memset(&p, 0, sizeof p);
        p.sea_on = f->geo.kind != HF_GEO_NONE || s->st.zmin < 0;
        p.sea_level = 0;
        p.min_area = (int64_t)ceil(WS_MIN_AREA_M2 / (cell > 0 ? cell : 1));
        p.join_dz = mm_to_units(f, WS_JOIN_DZ_MM);
        st = wt_detect(f, &p, w->id, work, ws, &w->bodies);
        free(work);
        if (st != BR_OK) return br_err_set(err, st, NULL, "water detection failed");
    }
    for (i = 0; i < n; i++) if (w->id[i]) wz[i] = w->bodies.level[w->id[i] - 1];
    if (w->bodies.n > RW_MAX_ID) w->bodies.n = RW_MAX_ID;
    for (i = 0; i < n; i++) if (w->id[i] > RW_MAX_ID) w->id[i] = 0;
    return BR_OK;
}

/* One water mesh (platform/water_mesh.c) with tested blocks of up to tested_s cells, as
 * world vertices carrying their body's id, and its chunk table. */
static br_status surf_build(water_scene *w, scene *s, int32_t tested_s, ws_surf *u, br_err *err)
{
    uint32_t i;
    if (wm_build(&s->f, w->id, w->wf.z, w->bodies.level, w->nbodies, tested_s, &u->mesh) != BR_OK)
        return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for the water surfaces' mesh");
    u->verts = malloc(sizeof *u->verts * (u->mesh.nv ? u->mesh.nv : 1));
    u->cache = malloc(rs_cache_mem_size(u->mesh.nv ? u->mesh.nv : 1));
    u->tid = malloc(u->mesh.nidx / 3 + 1);
    if (!u->verts || !u->cache || !u->tid) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory");
    for (i = 0; i < u->mesh.nv; i++) {
        const wm_vert *v = &u->mesh.v[i];
        rt_vertex(&s->rt, v->x, v->y, v->z, &u->verts[i]);
        u->verts[i].uv[0] = u->verts[i].uv[1] = 0;
        u->verts[i].rgb = RW_ID_RGB(v->id) | (v->tested ? RW_TESTED_RGB : 0);
    }
    u->prim.kind = RS_LIST; u->prim.n = u->mesh.nidx; u->prim.idx = u->mesh.idx;
    /* each triangle's body: a surface triangle's vertices are all of its body */
    for (i = 0; i + 2 < u->mesh.nidx; i += 3) u->tid[i / 3] = (uint8_t)u->mesh.v[u->mesh.idx[i]].id;
    u->chunks = malloc(rs_chunk_mem_size(&u->prim, 1) + 4);
    if (!u->chunks) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory");
    return BR_OK;
}

/* tbox: the world box of each of the far mesh's tested triangles (far_pays). */
static br_status tested_boxes(water_scene *w)
{
    const ws_surf *u = &w->surf[1];
    uint32_t t;
    w->tbox = malloc(sizeof *w->tbox * (u->mesh.nidx / 3 + 1));
    if (!w->tbox) return BR_E_NOMEM;
    for (t = 0; t + 2 < u->mesh.nidx; t += 3) {
        int k, j;
        if (!u->mesh.v[u->mesh.idx[t]].tested) continue;    /* (a tested triangle's vertices all are) */
        for (k = 0; k < 3; k++) {
            int32_t lo = INT32_MAX, hi = INT32_MIN;
            for (j = 0; j < 3; j++) {
                const int32_t q = u->verts[u->mesh.idx[t + (uint32_t)j]].p[k];
                lo = q < lo ? q : lo;
                hi = q > hi ? q : hi;
            }
            w->tbox[w->ntbox][k] = lo;
            w->tbox[w->ntbox][3 + k] = hi;
        }
        w->ntbox++;
    }
    return BR_OK;
}

/* The water surfaces' meshes, once per scene: the fine one, and the far one with larger
 * tested blocks (ws_frame picks one a frame). */
static br_status water_mesh_once(water_scene *w, scene *s, br_err *err)
{
    br_status st;
    if ((st = surf_build(w, s, 0, &w->surf[0], err)) != BR_OK) return st;     /* WM_TESTED_S */
    if ((st = surf_build(w, s, WS_FAR_TESTED_S, &w->surf[1], err)) != BR_OK) return st;
    if (tested_boxes(w) != BR_OK) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory");
    if (!w->o.quiet)
        printf("water surfaces: %u triangles, %u vertices\n", w->surf[0].mesh.nidx / 3, w->surf[0].mesh.nv);
    return BR_OK;
}

br_status ws_open(water_scene *w, scene *s, const ws_opts *o, br_err *err)
{
    hf *f = &s->f;
    const size_t n = (size_t)f->w * (size_t)f->h;
    int32_t depth;
    int32_t *wz;
    size_t i;
    memset(w, 0, sizeof *w);
    if (o) w->o = *o;
    w->rw = calloc(1, sizeof *w->rw);
    w->wclips = malloc(rs_clip_mem_size(SCENE_CLIPS));
    w->rclips = malloc(rs_clip_mem_size(SCENE_CLIPS));
    if (!w->rw || !w->wclips || !w->rclips) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory");
    rw_tables(w->rw);                   /* here, not in the first frame */
    {   /* the refraction tint's length, once: a quarter of the relief, at most WS_TINT_MM
         * (hf_z_to_mm and rt_mm_to_world divide in 64 bits) */
        int64_t relief_mm = hf_z_to_mm(f, s->st.zmax) - hf_z_to_mm(f, s->st.zmin);
        w->tint_len = rt_mm_to_world(&s->rt, relief_mm / 4 < WS_TINT_MM ? relief_mm / 4 : WS_TINT_MM);
        if (w->tint_len < 1) w->tint_len = 1;
    }
    if (w->o.no_water) return BR_OK;
    w->id = malloc(n);
    wz = malloc(n * sizeof *wz);
    if (!w->id || !wz) { free(wz); return br_err_set(err, BR_E_NOMEM, NULL, "out of memory"); }
    if (find_water(w, s, wz, err) != BR_OK) { free(wz); return err->code; }
    w->nbodies = w->bodies.n;
    if (!w->o.quiet)
        for (i = 0; i < (size_t)w->bodies.n; i++)
            printf("water %d: %s at %.2f m, %lld samples%s\n", (int)i + 1,
                   w->bodies.kind[i] == WT_SEA ? "sea" : w->bodies.kind[i] == WT_LAKE ? "lake" : "user",
                   (double)hf_z_to_mm(f, w->bodies.level[i]) / 1000, (long long)w->bodies.area[i],
                   w->bodies.joined[i] > 1 ? " (flat regions joined along a seam)" : "");
    if (!w->nbodies) { free(wz); return BR_OK; }
    /* flattened water (terrain at or above its surface) lies on a bottom WS_DEPTH_MM
     * below it, a small step for the LOD (a deep one made the selection refine every
     * shore to the finest level); where the coarse LOD draws the bottom above the
     * surface, the post hook's shore test still shows water (raster/water.h) */
    depth = mm_to_units(f, WS_DEPTH_MM);
    if (depth < 1) depth = 1;
    if (!w->o.water_file && !w->o.have_level)     /* the user's water keeps its bathymetry */
        for (i = 0; i < n; i++)
            if (w->id[i] && f->z[i] != HF_NODATA && f->z[i] > wz[i] - depth) {
                f->z[i] = wz[i] - depth;
                s->beds_lowered = 1;
            }
    for (i = 0; i < n; i++) if (!w->id[i]) wz[i] = HF_NODATA;
    w->wf = *f;
    w->wf.z = wz;
    return water_mesh_once(w, s, err);
}

void ws_close(water_scene *w)
{
    if (w->wf.z) free(w->wf.z);
    {
        int k;
        for (k = 0; k < 2; k++) {
            ws_surf *u = &w->surf[k];
            wm_free(&u->mesh); free(u->verts); free(u->tid); free(u->cache); free(u->chunks);
        }
    }
    free(w->id); free(w->tbox);
    free(w->rstrip); free(w->rcache); free(w->rchunks); free(w->rbed); free(w->rw);
    free(w->wclips); free(w->rclips);
    free(w->rmesh_mem); free(w->rverts); free(w->rvprev); free(w->rst); free(w->rparts_mem);
    memset(w, 0, sizeof *w);
}

/* This frame's water frame: the scene's water mesh seen by the terrain's camera. */
static br_status water_frame(water_scene *w, const ws_surf *u, const rs_frame *tf)
{
    memset(&w->wfr, 0, sizeof w->wfr);
    w->wfr.w = tf->w; w->wfr.h = tf->h; w->wfr.fmt = tf->fmt; w->wfr.depth = tf->depth;
    w->wfr.v = u->verts; w->wfr.nv = u->mesh.nv; w->wfr.cache = u->cache;
    w->wfr.prims = &u->prim; w->wfr.nprims = 1;
    w->wfr.chunks = u->chunks;
    w->wfr.clips = w->wclips; w->wfr.clip_cap = SCENE_CLIPS;
    w->wfr.no_clear = 1;                /* rw_pass_water seeds it from the terrain's depth */
    w->wfr.vp = tf->vp;
    return rs_frame_prepare(&w->wfr);
}

/* Sutherland-Hodgman: the part of polygon (x, y)[n] (n <= 8) where k (x) + l (y) <= m
 * (one screen edge), into (ox, oy); returns its vertex count (<= n + 1). */
static int clip_edge(const double *x, const double *y, int n, double k, double l, double m,
                     double *ox, double *oy)
{
    int i, o = 0;
    for (i = 0; i < n; i++) {
        const int j = (i + 1) % n;
        const double si = k * x[i] + l * y[i] - m, sj = k * x[j] + l * y[j] - m;
        if (si <= 0) { ox[o] = x[i]; oy[o] = y[i]; o++; }
        if ((si < 0 && sj > 0) || (si > 0 && sj < 0)) {
            const double t = si / (si - sj);
            ox[o] = x[i] + t * (x[j] - x[i]);
            oy[o] = y[i] + t * (y[j] - y[i]);
            o++;
        }
    }
    return o;
}

/* Twice the screen area, in sub-pixels squared (the units of the cross product of two
 * screen edges), of world triangle p[3] seen by c: the triangle cut
 * at the near plane (camera space, up to 4 corners), projected, cut to the w x h
 * screen (up to 8), shoelace.  For the triangles whose corners the transform left
 * without a screen position (behind the near plane or beyond the guard band). */
static int64_t near_area(const cam *c, const int32_t *p[3])
{
    double cx[4], cy[4], cz[4], x[16], y[16], x2[16], y2[16], a = 0;
    const double zn = c->znear, f = (double)c->f_q16 / 65536.0;
    int i, n = 0;
    for (i = 0; i < 3; i++) {
        int64_t v[3], u[3];
        cam_to_view(c, p[i], v);
        cam_to_view(c, p[(i + 1) % 3], u);
        if (v[2] >= c->znear) { cx[n] = (double)v[0]; cy[n] = (double)v[1]; cz[n] = (double)v[2]; n++; }
        if ((v[2] < c->znear) != (u[2] < c->znear)) {
            const double t = (zn - (double)v[2]) / ((double)u[2] - (double)v[2]);
            cx[n] = (double)v[0] + t * (double)(u[0] - v[0]);
            cy[n] = (double)v[1] + t * (double)(u[1] - v[1]);
            cz[n] = zn;
            n++;
        }
    }
    for (i = 0; i < n; i++) {
        x[i] = c->w * 0.5 + f * cx[i] / cz[i];
        y[i] = c->h * 0.5 - f * cy[i] / cz[i];
    }
    n = clip_edge(x, y, n, -1, 0, 0, x2, y2);                     /* x >= 0 */
    n = clip_edge(x2, y2, n, 1, 0, c->w, x, y);                   /* x <= w */
    n = clip_edge(x, y, n, 0, -1, 0, x2, y2);                     /* y >= 0 */
    n = clip_edge(x2, y2, n, 0, 1, c->h, x, y);                   /* y <= h */
    for (i = 0; i < n; i++) a += x[i] * y[(i + 1) % n] - x[(i + 1) % n] * y[i];
    return llround(fabs(a) * (double)(1 << RS_SUBPIX_BITS) * (double)(1 << RS_SUBPIX_BITS));
}

/* The body whose water covers most of the screen (the reflection's plane), 0 when
 * none shows; *seen: bit i set when body i has area on screen.  Screen area in
 * sub-pixels squared from the water frame's vertices; a triangle that needs the clipper
 * gets its area from near_area (in the same units), which is 0 when it lies off the
 * screen: counting such a triangle as the whole screen gave the mirror to a body that
 * lay beside or behind the camera while the lake in view reflected only sky. */
static int32_t biggest_body(const water_scene *w, const ws_surf *u, const cam *c, uint32_t *seen)
{
    int64_t area[RW_MAX_ID + 1];
    const uint32_t nt = u->prim.n / 3;
    const uint32_t *ix = u->prim.idx;
    const rs_cvert *const wc = u->cache;
    const rs_vertex *const wv = w->wfr.v;
    const uint8_t *const tid = u->tid;
    const int16_t *const ch = w->wfr.chunks;
    uint32_t t;
    int32_t best = 0, i;
    memset(area, 0, sizeof area);
    for (t = 0; t < nt; t++, ix += 3) {
        const rs_cvert *a = &wc[ix[0]], *b = &wc[ix[1]], *cc = &wc[ix[2]];
        if (t % RS_CHUNK == 0 && ch[2 * (t / RS_CHUNK)] > ch[2 * (t / RS_CHUNK) + 1]) {
            /* no row: its vertices share an outcode that rejects all of its triangles
             * (rs_frame_prepare's chunk table), which the test below would skip */
            const uint32_t skip = nt - t < RS_CHUNK ? nt - t : RS_CHUNK;
            t += skip - 1;
            ix += 3 * (skip - 1);
            continue;
        }
        const uint32_t oa = a->c, ob = b->c, oc = cc->c;
        int64_t ar;
        if (oa & ob & oc & ((uint32_t)0x3f << 24)) continue;      /* off screen, or behind */
        if ((oa | ob | oc) & ((uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD) << 24)) {
            const int32_t *p[3];
            p[0] = wv[ix[0]].p; p[1] = wv[ix[1]].p; p[2] = wv[ix[2]].p;
            ar = near_area(c, p);
        } else ar = ((int64_t)(b->x - a->x) * (cc->y - a->y) - (int64_t)(cc->x - a->x) * (b->y - a->y));
        area[tid[t]] += ar < 0 ? -ar : ar;
    }
    *seen = 0;
    for (i = 1; i <= RW_MAX_ID; i++) {
        if (area[i] > area[best]) best = i;
        if (area[i] > 0) *seen |= 1u << i;
    }
    return best;
}

/* n strip indices, eight bytes a move: glibc's memcpy moves a block this size with rep
 * movsb, which callgrind (the benchmark's measure) counts as one instruction a byte; the
 * empty asm keeps GCC from turning the loop back into that call. */
static void copy_idx(uint32_t *restrict o, const uint32_t *restrict in, uint32_t n)
{
    uint32_t i = 0;
    for (; i + 4 <= n; i += 4) {
        uint64_t a, b;
        memcpy(&a, in + i, sizeof a);
        memcpy(&b, in + i + 2, sizeof b);
#if defined(__GNUC__)
        __asm__("" : "+r"(a), "+r"(b));
#endif
        memcpy(o + i, &a, sizeof a);
        memcpy(o + i + 2, &b, sizeof b);
    }
    for (; i < n; i++) o[i] = in[i];
}

/* The reflection's parts on the scene's threads (refl_select): part k extracted, or
 * joined with its vertices set up (scene_join_part, as the terrain's). */
typedef struct refl_jobs {
    water_scene *w;
    const rt_scene *rt;
} refl_jobs;

static void refl_job_part(void *user, uint32_t k)
{
    bt_extract_part(((refl_jobs *)user)->w->rparts, k);
}

static void refl_job_join(void *user, uint32_t k)
{
    const refl_jobs *j = (const refl_jobs *)user;
    scene_join_part(j->w->rparts, k, j->rt, &j->w->rmesh, j->w->rverts, j->w->rvprev);
}

/* bt_extract of the reflection's own selection into rmesh and its vertices into rverts,
 * by parts on the scene's threads (core/bitree.h bt_extract_begin: the same mesh for any
 * schedule; a part whose decisions still hold is replayed, and only the vertices of its
 * parts that moved are set up again). */
static br_status refl_select(water_scene *w, scene *s, bt_tree *t, const bt_params *bp)
{
    refl_jobs j;
    uint32_t n = 0;
    br_status st;
    {   /* as scene_mesh: this frame's vertices go to the other array */
        rs_vertex *tv = w->rverts;
        w->rverts = w->rvprev;
        w->rvprev = tv;
    }
    if (!w->rparts) {
        st = bt_extract(t, bp, &w->rmesh);
        if (st == BR_OK) rt_from_mesh(&s->rt, &w->rmesh, w->rverts);
        return st;
    }
    j.w = w; j.rt = &s->rt;
    st = bt_extract_begin(w->rparts, t, bp, &w->rmesh, &n);
    if (st == BR_OK) pt_jobs(s->pool, n, refl_job_part, &j);
    if (st == BR_OK) st = bt_extract_end(w->rparts, &n);
    if (st != BR_OK) return st;
    if (!n) {
        rt_from_mesh(&s->rt, &w->rmesh, w->rverts);
        return BR_OK;
    }
    pt_jobs(s->pool, n, refl_job_join, &j);
    rt_from_mesh_pending(&s->rt, &w->rmesh, w->rverts);
    return BR_OK;
}

/* The screen rectangle the reflection of body is read in, for its own selection
 * (bt_params.window): the box of the body's vertices in this frame's water frame (the hook
 * reads the reflection at that body's water pixels only, each at most RW_WAVE_PX pixels
 * off by the waves, and a row of the reduced reflection covers 2^res rows), grown by
 * RW_WAVE_PX + 2^res + 1 pixels and cut to the screen, then turned upside down for the
 * mirrored camera (its up is -M up: row y of the reflection is its row h - y).  0 when
 * the whole screen may be needed (a vertex of the body needs the clipper) or nothing. */
static int refl_window(const water_scene *w, int32_t body, int32_t res, int32_t sw, int32_t sh, int32_t win[4])
{
    const rs_frame *wf = &w->wfr;
    const uint32_t rid = RW_ID_RGB(body);
    const int32_t grow = RW_WAVE_PX + (1 << res) + 1;
    int32_t x0 = INT32_MAX, y0 = INT32_MAX, x1 = INT32_MIN, y1 = INT32_MIN;
    uint32_t i;
    for (i = 0; i < wf->nv; i++) {
        const rs_cvert *v = &wf->cache[i];
        if ((v->c & RW_ID_MASK) != rid) continue;
        if (v->c & ((uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD) << 24)) return 0;
        if (v->x < x0) x0 = v->x;
        if (v->x > x1) x1 = v->x;
        if (v->y < y0) y0 = v->y;
        if (v->y > y1) y1 = v->y;
    }
    if (x0 > x1) return 0;
    /* (guard-band sub-pixels: |x|, |y| < 2^30 / 2^4 pixels, so the sums below fit) */
    x0 = (x0 >> RS_SUBPIX_BITS) - grow; x1 = (x1 >> RS_SUBPIX_BITS) + 1 + grow;
    y0 = (y0 >> RS_SUBPIX_BITS) - grow; y1 = (y1 >> RS_SUBPIX_BITS) + 1 + grow;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > sw) x1 = sw;
    if (y1 > sh) y1 = sh;
    if (x0 >= x1 || y0 >= y1) return 0;
    win[0] = x0; win[2] = x1;
    win[1] = sh - y1; win[3] = sh - y0;
    return 1;
}

/* The reflection's own selection (water_scene.h rmesh): the mirrored camera's view
 * selection at refl_err times the terrain's screen error, without geomorph, from a copy
 * of the scene's tree with its own frame state (view mode without hysteresis, so the
 * state only keeps the decision memo's frame coherence honest; the terrain's state stays
 * as the terrain's selection left it), by parts on the scene's threads (refl_select; the
 * mesh and its vertices are the same for every thread count).  0 when it is drawn; -1:
 * the terrain's mesh is drawn instead (no view-dependent terrain mesh, or the selection
 * does not fit rmesh). */
static int refl_own(water_scene *w, scene *s, const cam *c, const rs_frame *tf, int32_t body, int32_t plane_z,
                    int32_t res)
{
    bt_tree t;
    bt_params bp;
    int32_t win[4];
    const double mult = w->o.refl_err;
    int k;
    w->rown = 0;
    if (!(mult >= 1) || !(w->o.view_px > 0) || !s->tree.node || !s->mesh_mem || s->prims != &s->prim || tf->v != s->verts)
        return -1;
    if ((int64_t)2 * plane_z - c->eye[2] < -CAM_COORD_MAX || (int64_t)2 * plane_z - c->eye[2] > CAM_COORD_MAX)
        return -1;
    if (!w->rmesh_mem && ws_reserve(w, s) != BR_OK) return -1;
    w->rcam = *c;
    w->rcam.eye[2] = 2 * plane_z - c->eye[2];
    for (k = 0; k < 3; k++) {
        w->rcam.right[k] = k == 2 ? -c->right[k] : c->right[k];
        w->rcam.up[k] = k == 2 ? c->up[k] : -c->up[k];
        w->rcam.fwd[k] = k == 2 ? -c->fwd[k] : c->fwd[k];
    }
    t = s->tree;
    t.st = w->rst;
    memset(&bp, 0, sizeof bp);
    bp.mode = BT_VIEW;
    bp.c = &w->rcam;
    bp.fr = s->rt.fr;
    bp.pixel_err_q8 = (int32_t)lround(w->o.view_px * mult * 256 < 1 << 30 ? w->o.view_px * mult * 256 : 1 << 30);
    if (!w->o.refl_no_window && refl_window(w, body, res, c->w, c->h, win)) bp.window = win;
    if (refl_select(w, s, &t, &bp) != BR_OK || w->rmesh.overflow || w->rmesh.ns < 3) return -1;
    w->rmprim.kind = RS_STRIP; w->rmprim.n = w->rmesh.ns; w->rmprim.idx = w->rmesh.strip;
    w->rown = 1;
    return 0;
}

br_status ws_reserve(water_scene *w, scene *s)
{
    uint32_t cap = s->mesh.max_tri < WS_REFL_TRI ? s->mesh.max_tri : WS_REFL_TRI;
    size_t mb;
    if (w->rmesh_mem || !w->nbodies || !(w->o.refl_err >= 1) || !s->mesh_mem || cap < 2) return BR_OK;
    mb = bt_mesh_mem_size(cap);
    w->rmesh_mem = mb ? malloc(mb) : NULL;
    w->rverts = malloc(sizeof *w->rverts * (size_t)(3 * cap + 3));
    w->rvprev = malloc(sizeof *w->rvprev * (size_t)(3 * cap + 3));
    w->rst = calloc(bt_state_size(s->tree.nslot) + 1, 1);
    {
        const uint32_t pt = cap < WS_REFL_PART_TRI ? cap : WS_REFL_PART_TRI;
        const size_t pb = bt_parts_mem_size(pt);
        w->rparts_mem = pb ? malloc(pb) : NULL;
        if (w->rparts_mem && bt_parts_init(&w->rparts, pt, w->rparts_mem, pb) != BR_OK) {
            free(w->rparts_mem);        /* (then refl_select extracts it whole) */
            w->rparts_mem = NULL;
            w->rparts = NULL;
        }
    }
    if (!w->rmesh_mem || !w->rverts || !w->rvprev || !w->rst || bt_mesh_init(&w->rmesh, cap, w->rmesh_mem, mb) != BR_OK) {
        free(w->rmesh_mem); free(w->rverts); free(w->rvprev); free(w->rst); free(w->rparts_mem);
        w->rmesh_mem = NULL; w->rverts = NULL; w->rvprev = NULL; w->rst = NULL; w->rparts_mem = NULL;
        w->rparts = NULL;
        return BR_E_NOMEM;
    }
    return BR_OK;
}

/* The mirror's vertices (nv of them, src, from mesh m) with the lowered bed of body
 * `body` back at the body's level plane_z: a vertex on one of its samples below
 * plane_z is raised to it.  ws_open lowered flattened water WS_DEPTH_MM under its
 * surface for the terrain pass; in the DEM those samples lie at (SRTM's flat lakes) or
 * above (a region joined along a seam) the level, so the reflection sees the DEM's
 * shore: the shore triangles end at the water plane and need no clipping, and the bed
 * lies in the plane, where the mirror's reversed winding culls it.  Anything else below
 * the plane is still clipped.  NULL when the vertices are not the mesh's or cannot be
 * copied (the clipper then does it all); else *below says whether a vertex is left
 * under the plane. */
static const rs_vertex *refl_bed_level(water_scene *w, const scene *s, const bt_mesh *m, const rs_vertex *src,
                                       uint32_t nv, int32_t body, int32_t plane_z, int *below)
{
    const uint32_t gw = (uint32_t)s->f.w, gh = (uint32_t)s->f.h;
    uint32_t i;
    if (!s->beds_lowered || body < 1 || m->nv != nv || !w->id) return NULL;
    if (w->rbed_cap < nv) {
        free(w->rbed);
        w->rbed_cap = nv + nv / 4;
        w->rbed = malloc(sizeof *w->rbed * w->rbed_cap);
        if (!w->rbed) { w->rbed_cap = 0; return NULL; }
    }
    *below = 0;
    for (i = 0; i < nv; i++) {      /* (whole structures: a vector copy; memcpy's `rep movsb`
                                       counts a byte an instruction under callgrind) */
        const rs_vertex *a = &src[i];
        rs_vertex *o = &w->rbed[i];
        *o = *a;
        if (a->p[2] < plane_z) {
            const bt_vert *g = &m->v[i];
            if ((uint32_t)g->x < gw && (uint32_t)g->y < gh && w->id[(size_t)g->y * gw + (size_t)g->x] == body)
                o->p[2] = plane_z;
            else *below = 1;
        }
    }
    return w->rbed;
}

/* The mirrored terrain frame for plane_z at res_shift: the reflection's own selection
 * (refl_own), or the terrain's strip and vertices; body's bed at its level
 * (refl_bed_level). */
static br_status refl_frame(water_scene *w, scene *s, const cam *c, const rs_frame *tf, int32_t body, int32_t plane_z,
                            int32_t res)
{
    const int own = refl_own(w, s, c, tf, body, plane_z, res) == 0;
    const rs_prim *tp = own ? &w->rmprim : &tf->prims[0];
    const uint32_t nv = own ? w->rmesh.nv : tf->nv;
    const rs_vertex *bed;
    int below = 1;
    size_t cb;
    if (!own && (tf->nprims != 1 || tp->kind != RS_STRIP)) return BR_E_ARG;
    if (tp->n < 3) return BR_E_ARG;
    if (w->rstrip_cap < tp->n + 1) {
        free(w->rstrip);
        w->rstrip_cap = tp->n + 1 + tp->n / 4;
        w->rstrip = malloc(sizeof *w->rstrip * w->rstrip_cap);
        if (!w->rstrip) { w->rstrip_cap = 0; return BR_E_NOMEM; }
    }
    /* one doubled first index flips every triangle's parity: the winding the mirror
     * reversed is reversed back, and the extra triangle has zero area */
    w->rstrip[0] = tp->idx[0];
    copy_idx(w->rstrip + 1, tp->idx, tp->n);
    w->rprim.kind = RS_STRIP; w->rprim.n = tp->n + 1; w->rprim.idx = w->rstrip;
    if (w->rcache_cap < nv) {
        free(w->rcache);
        w->rcache_cap = nv + nv / 4;
        w->rcache = malloc(rs_cache_mem_size(w->rcache_cap));
        if (!w->rcache) { w->rcache_cap = 0; return BR_E_NOMEM; }
    }
    cb = rs_chunk_mem_size(&w->rprim, 1) + 4;
    if (w->rchunks_cap < cb) {
        free(w->rchunks);
        w->rchunks_cap = cb + cb / 4;
        w->rchunks = malloc(w->rchunks_cap);
        if (!w->rchunks) { w->rchunks_cap = 0; return BR_E_NOMEM; }
    }
    w->rfr = *tf;
    w->rfr.w = tf->w >> res; w->rfr.h = tf->h >> res;
    if (own) { w->rfr.v = w->rverts; w->rfr.nv = nv; }
    bed = own ? refl_bed_level(w, s, &w->rmesh, w->rverts, nv, body, plane_z, &below)
              : tf->v == s->verts ? refl_bed_level(w, s, &s->mesh, tf->v, nv, body, plane_z, &below)
                                  : NULL;
    if (bed) w->rfr.v = bed;
    w->rfr.cache = w->rcache;
    w->rfr.prims = &w->rprim; w->rfr.nprims = 1;
    w->rfr.chunks = w->rchunks;
    w->rfr.clips = w->rclips;           /* (not the terrain frame's, which *tf copied) */
    w->rfr.clip_cap = SCENE_CLIPS;
    /* the plane clips; with no vertex under it nothing is cut and no outcode is set */
    w->rfr.clip_z_on = below; w->rfr.clip_z = plane_z;
    w->rfr.clear_rows = NULL;           /* the reflection's sky comes from the hook */
    if (rw_mirror_vp(&tf->vp, plane_z, res, tf->w, tf->h, &w->rfr.vp) != BR_OK) return BR_E_ARG;
    return rs_frame_prepare(&w->rfr);
}

/* Fog from 55 % to 100 % of the farthest grid corner's distance from the eye (the
 * depth along the view axis of any point of the grid is at most that, so a camera
 * looking straight down from high sees no fog on the ground under it). */
static void fog_range(const scene *s, const cam *c, rw_params *p)
{
    int64_t far = 0;
    int k;
    for (k = 0; k < 4; k++) {
        double q[3], d;
        q[0] = (k & 1) ? (double)(s->f.w - 1) * (double)s->rt.fr.sx : 0;
        q[1] = (k & 2) ? (double)(s->f.h - 1) * (double)s->rt.fr.sy : 0;
        q[2] = world_z(s, (s->st.zmin + s->st.zmax) / 2);
        d = sqrt((q[0] - c->eye[0]) * (q[0] - c->eye[0]) + (q[1] - c->eye[1]) * (q[1] - c->eye[1])
                 + (q[2] - c->eye[2]) * (q[2] - c->eye[2]));
        if (d > (double)far) far = (int64_t)d;
    }
    p->fog_on = far > 16;
    p->fog_end = far;
    p->fog_start = far * 55 / 100;
    if (p->fog_start < 1) p->fog_start = 1;
}

/* 1 when this frame draws the far water mesh (surf[1]): while each of its tested
 * triangles, seen from the eye, spans at most WS_FAR_TESTED_PX pixels: f side <=
 * WS_FAR_TESTED_PX d, side the longer horizontal side of the triangle's box and d the
 * largest of the eye's distances to the box along the three axes (at most the Euclidean
 * distance, so the test is the stricter).  Their pixels are tested one by one in the
 * hook, so near them the fine mesh costs less; far away the far mesh's fewer, larger
 * triangles do.  In integers, so every target makes the same choice: world units below
 * 2^31, so side and d below 2^32, f (pixels) below 2^18 (4096 rows, 1 degree): both
 * products below 2^50. */
static int far_pays(const water_scene *w, const cam *c)
{
    const int64_t f = (int64_t)(c->f_q16 >> 16);
    uint32_t i;
    for (i = 0; i < w->ntbox; i++) {
        const int32_t *bx = w->tbox[i];
        int64_t d = 0, side = 0;
        int k;
        for (k = 0; k < 3; k++) {
            const int64_t e = c->eye[k];
            const int64_t o = e < bx[k] ? bx[k] - e : e > bx[3 + k] ? e - bx[3 + k] : 0;
            if (o > d) d = o;
            if (k < 2 && (int64_t)bx[3 + k] - bx[k] > side) side = (int64_t)bx[3 + k] - bx[k];
        }
        if (f * side > (int64_t)WS_FAR_TESTED_PX * d) return 0;
    }
    return 1;
}

br_status ws_frame(water_scene *w, scene *s, const cam *c, rs_frame *tf, br_err *err)
{
    static const int32_t res_of[5] = { 1, 0, 1, 2, -1 };
    rw_params p;
    rw_frame *r = w->rw;
    int32_t body = 0, res = res_of[w->o.reflection >= 0 && w->o.reflection < 5 ? w->o.reflection : 0];
    const rs_frame *wfr = NULL, *rfr = NULL;
    const ws_surf *u = &w->surf[0];     /* this frame's water mesh (far_pays) */
    rs_pass pass;
    int32_t k;
    memset(&p, 0, sizeof p);
    p.sky_on = 1;
    if (!w->o.no_fog) fog_range(s, c, &p);
    if (w->nbodies) {
        if (far_pays(w, c)) u = &w->surf[1];
        if (water_frame(w, u, tf) != BR_OK) return br_err_set(err, BR_E_ARG, NULL, "cannot set up the water frame");
        wfr = &w->wfr;
        body = biggest_body(w, u, c, &p.seen_mask);
    }
    if (wfr && w->wfr.nv) {
        int64_t hgt;
        p.water_on = 1;
        p.refl_body = body;
        p.plane_z = body ? world_z(s, w->bodies.level[body - 1]) : 0;
        hgt = c->eye[2] - p.plane_z;
        if (hgt < 1) hgt = 1;
        p.tint_len = w->tint_len;
        p.waves_on = !w->o.no_waves;
        p.time_ms = (int32_t)llround(w->o.time_s * 1000);
        p.wave_len = hgt / 4 > 1 ? hgt / 4 : 1;
        p.wave_amp = hgt / 60;
        p.fresnel_one = w->o.fresnel_one;
        /* SRTM's lakes and sea are flat surfaces with no bathymetry: the stated default
         * tint instead of one from the lowered bottom's depth */
        p.tint_fixed = w->o.water_file || w->o.have_level ? 0 : WS_TINT_FIXED;
        p.res_shift = res < 0 ? 0 : res;
        p.wet = w->id;
        p.low = u->mesh.low;
        p.land = w->id ? &s->rt : NULL;     /* the land test (rw_params) */
        p.land_tex = s->rt.tex_w > 0 ? &s->tex : NULL;
        p.wet_w = s->f.w; p.wet_h = s->f.h;
        p.grid_ox = s->rt.fr.ox; p.grid_oy = s->rt.fr.oy;
        p.grid_sx = s->rt.fr.sx; p.grid_sy = s->rt.fr.sy;
        for (k = 0; k < w->nbodies && k < RW_MAX_ID; k++) {
            p.body_z[k + 1] = world_z(s, w->bodies.level[k]);
            p.land_z[k + 1] = w->bodies.level[k];
        }
        if (w->o.shore_bound) {
            /* twice the screen error plus a pixel: the selection bounds the error by its
             * distance to the diamond's box, not by the depth along the view axis */
            double sc = (2 * w->o.shore_px + 1) * (double)RS_DEPTH_ONE * tf->vp.znear * 65536.0 / (double)tf->vp.f_q16;
            double ww = (double)mm_to_units(&s->f, llround(w->o.shore_m * 1000)) * (double)s->rt.fr.sz_q16 / 65536.0;
            p.shore_bound = 1;
            p.shore_c = sc < 4e18 ? (int64_t)sc : (int64_t)4e18;
            p.shore_w = ww < 2e9 ? (int64_t)ww : (int64_t)2e9;
        }
        if (body && res >= 0 && c->eye[2] > p.plane_z && tf->nprims == 1 && tf->prims[0].kind == RS_STRIP) {
            if (refl_frame(w, s, c, tf, body, p.plane_z, res) != BR_OK)
                return br_err_set(err, BR_E_NOMEM, NULL, "cannot set up the reflection");
            rfr = &w->rfr;
        }
    }
    if (rw_setup(r, &p, c, tf, wfr, rfr) != BR_OK) return br_err_set(err, BR_E_ARG, NULL, "bad water parameters");
    rw_fog_vertices(r, tf);
    memset(&w->pipe, 0, sizeof w->pipe);
    w->pipe.w = tf->w; w->pipe.h = tf->h; w->pipe.fmt = tf->fmt; w->pipe.depth = tf->depth;
    /* terrain, water, then the reflection: it draws only the rows around the band's
     * water pixels, which the water pass has found */
    if (rs_pass_terrain(&w->tpass, tf) != BR_OK) return br_err_set(err, BR_E_ARG, NULL, "terrain frame without a chunk table");
    rs_pipe_add(&w->pipe, &w->tpass);
    if (wfr) {
        rw_pass_water(&pass, r);
        r->water_pass = w->pipe.npasses;
        rs_pipe_add(&w->pipe, &pass);
    }
    if (rfr) {
        rw_pass_reflection(&pass, r);
        r->refl_pass = w->pipe.npasses;
        rs_pipe_add(&w->pipe, &pass);
    }
    w->pipe.post = rw_post;
    w->pipe.post_user = r;
    return BR_OK;
}
