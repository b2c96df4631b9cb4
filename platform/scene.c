/* platform/scene.c — see scene.h. */
#include "platform/clock.h"
#include "platform/scene.h"
#include "platform/tree_file.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "platform/png_io.h"

#define SCENE_PI 3.14159265358979323846

/* gdaldem color-relief text: `elevation r g b [a]` per line (separators: blanks,
 * commas, tabs, colons), elevation may be `nv` (nodata) or a percentage `P%` of the
 * [zmin, zmax] range; `#` starts a comment.  Entries are sorted by elevation. */
static br_status read_colors(const char *path, rs_ramp *r, int64_t zmin_mm, int64_t zmax_mm, br_err *err)
{
    FILE *fp = fopen(path, "r");
    char line[512];
    int lineno = 0, i, j;
    if (!fp) return br_err_set(err, BR_E_IO, path, "cannot open colour file");
    r->n = 0;
    r->has_nv = 0;
    while (fgets(line, sizeof line, fp)) {
        char *p = line, *tok[5];
        int nt = 0;
        double e;
        long c[3];
        lineno++;
        if ((p = strchr(line, '#')) != NULL) *p = 0;
        for (p = line; *p; p++) if (*p == ',' || *p == '\t' || *p == ':' || *p == '\r' || *p == '\n') *p = ' ';
        p = strtok(line, " ");
        while (p && nt < 5) { tok[nt++] = p; p = strtok(NULL, " "); }
        if (nt == 0) continue;
        if (nt < 4) { fclose(fp); return br_err_set(err, BR_E_FORMAT, path, "line %d: expected 'elevation r g b [a]'", lineno); }
        for (i = 0; i < 3; i++) {
            char *end;
            c[i] = strtol(tok[1 + i], &end, 10);
            if (*end || c[i] < 0 || c[i] > 255) {
                fclose(fp);
                return br_err_set(err, BR_E_VALUE, path, "line %d: colour component '%s' is not 0..255", lineno, tok[1 + i]);
            }
        }
        if (!strcmp(tok[0], "nv")) {
            r->has_nv = 1;
            r->nv_rgb = (uint32_t)(c[0] << 16 | c[1] << 8 | c[2]);
            continue;
        }
        {
            char *end;
            e = strtod(tok[0], &end);
            if (end == tok[0] || !isfinite(e) || (*end && strcmp(end, "%"))) {
                fclose(fp);
                return br_err_set(err, BR_E_VALUE, path, "line %d: elevation '%s' is not a number", lineno, tok[0]);
            }
            if (*end == '%') e = ((double)zmin_mm + (double)(zmax_mm - zmin_mm) * e / 100.0) / 1000.0;
            if (fabs(e) > 1e7) {
                fclose(fp);
                return br_err_set(err, BR_E_VALUE, path, "line %d: elevation %g m is out of range", lineno, e);
            }
        }
        if (r->n >= RS_RAMP_MAX) { fclose(fp); return br_err_set(err, BR_E_TOO_BIG, path, "more than %d colour entries", RS_RAMP_MAX); }
        r->z_mm[r->n] = (int64_t)llround(e * 1000.0);
        r->rgb[r->n] = (uint32_t)(c[0] << 16 | c[1] << 8 | c[2]);
        r->n++;
    }
    fclose(fp);
    if (r->n == 0) return br_err_set(err, BR_E_FORMAT, path, "no colour entries");
    for (i = 1; i < r->n; i++)           /* insertion sort by elevation */
        for (j = i; j > 0 && r->z_mm[j - 1] > r->z_mm[j]; j--) {
            int64_t tz = r->z_mm[j]; uint32_t tc = r->rgb[j];
            r->z_mm[j] = r->z_mm[j - 1]; r->rgb[j] = r->rgb[j - 1];
            r->z_mm[j - 1] = tz; r->rgb[j - 1] = tc;
        }
    return BR_OK;
}

static br_status load_texture(scene *s, const char *path, br_err *err)
{
    int tw, th;
    uint8_t *rgb = NULL;
    size_t k;
    if (png_read_rgb(path, &tw, &th, &rgb, err) != BR_OK) return err ? err->code : BR_E_FORMAT;
    if (tw < 1 || th < 1 || tw > RS_MAX_TEX || th > RS_MAX_TEX) {
        free(rgb);
        return br_err_set(err, BR_E_TOO_BIG, path, "texture of %dx%d texels (at most %d a side)", tw, th, RS_MAX_TEX);
    }
    s->texpx = malloc(sizeof *s->texpx * (size_t)tw * (size_t)th);
    if (!s->texpx) { free(rgb); return br_err_set(err, BR_E_NOMEM, path, "out of memory"); }
    for (k = 0; k < (size_t)tw * (size_t)th; k++)
        s->texpx[k] = (uint32_t)rgb[3 * k] << 16 | (uint32_t)rgb[3 * k + 1] << 8 | rgb[3 * k + 2];
    free(rgb);
    s->tex.w = tw; s->tex.h = th; s->tex.px = s->texpx;
    s->rt.tex_w = tw; s->rt.tex_h = th;
    return BR_OK;
}

/* The 99th percentile of |dz| / spacing between valid east and south neighbours
 * (metres per metre) over a regular subsample of at most 2^19 samples; 0 when the
 * grid has no such pair or no memory. */
static double slope_p99(const hf *f)
{
    int32_t sx = 1, sy = 1, x, y;
    size_t n = 0;
    double *g, dx = (double)f->dx_um / 1e6, dy = (double)f->dy_um / 1e6, zu = (double)f->z_num / f->z_den, r;
    while ((int64_t)((f->w + sx - 1) / sx) * ((f->h + sy - 1) / sy) > (1 << 19)) { sx *= 2; sy *= 2; }
    g = malloc(sizeof *g * 2 * (size_t)((f->w + sx - 1) / sx) * (size_t)((f->h + sy - 1) / sy));
    if (!g) return 0;
    for (y = 0; y < f->h; y += sy)
        for (x = 0; x < f->w; x += sx) {
            const int32_t *p = f->z + (size_t)y * f->w + x;
            if (*p == HF_NODATA) continue;
            if (x + 1 < f->w && p[1] != HF_NODATA) g[n++] = fabs((double)p[1] - *p) * zu / dx;
            if (y + 1 < f->h && p[f->w] != HF_NODATA) g[n++] = fabs((double)p[f->w] - *p) * zu / dy;
        }
    if (n == 0) { free(g); return 0; }
    qsort(g, n, sizeof *g, br_cmp_double);
    r = g[n * 99 / 100];
    free(g);
    return r;
}

/* Vertical scale: o->zscale, or automatic for grids without georeference (their
 * spacing is the loader's assumption, 1 m, so heights and spacing may be in
 * unrelated units).  The rule keeps the slopes plausible: the 99th percentile of
 * the slopes between neighbouring samples is brought down to 0.75 (37 degrees;
 * georeferenced SRTM tiles of the Alps and Mount Rainier and the Crater Lake BT
 * grid have 0.75 to 0.89, lowland tiles 0.13 to 0.6); a grid whose slopes are
 * already below it keeps scale 1. */
#define SCENE_SLOPE_P99 0.75
static void apply_zscale(scene *s, const scene_opts *o, const char *name)
{
    double zs = o->zscale;
    if (zs == 0) {
        double p99 = s->f.geo.kind == HF_GEO_NONE ? slope_p99(&s->f) : 0;
        zs = 1;
        if (p99 > SCENE_SLOPE_P99) {
            zs = SCENE_SLOPE_P99 / p99;
            if (zs < 1e-6) zs = 1e-6;
            if (!o->quiet)
                printf("%s: no georeference (1 m spacing assumed) and 99 %% of the slopes up to %.3g: vertical "
                       "scale %.4g brings them to %.2g (override with --zscale)\n", name, p99, zs, SCENE_SLOPE_P99);
        }
    }
    if (zs != 1) /* as the rational round(zs * 2^20) / 2^20: zs <= 1000 fits int32 */
        rt_scene_zscale(&s->rt, (int32_t)fmax(1, (double)llround(zs * 1048576.0)), 1048576);
    s->zscale = zs;
    s->zmin_m *= zs;
    s->zmax_m *= zs;
}

br_status scene_open(scene *s, const char *const *in, int n, const scene_opts *o, br_err *err)
{
    scene_opts d;
    dem_opts dd;
    memset(s, 0, sizeof *s);
    memset(&d, 0, sizeof d);
    if (!o) o = &d;
    if (!(o->zscale >= 0 && o->zscale <= 1000) || !(o->ambient >= 0 && o->ambient <= 1))
        return br_err_set(err, BR_E_ARG, in[0], "vertical scale or ambient out of range");
    dd = o->dem;
    dd.filled_out = &s->filled;
    s->tree_file = o->tree;
    if (dem_load_many(in, n, &dd, &s->f, err) != BR_OK) return err ? err->code : BR_E_IO;
    if (dd.fill_voids && !o->quiet)
        printf("%s: %lld void samples filled from their borders (--fill-voids)\n", in[0], (long long)s->filled);
    return scene_setup(s, o, in[0], err);
}

br_status scene_setup(scene *s, const scene_opts *o, const char *name, br_err *err)
{
    scene_opts d;
    fx_q14 sun[3];
    int def_sun;
    memset(&d, 0, sizeof d);
    if (!o) o = &d;
    hf_stats_get(&s->f, &s->st);
    if (s->st.voids == (int64_t)s->f.w * s->f.h) {
        scene_close(s);
        return br_err_set(err, BR_E_VALUE, name, "every sample is a void (nodata): nothing to draw");
    }
    s->zmin_m = (double)hf_z_to_mm(&s->f, s->st.zmin) / 1000;
    s->zmax_m = (double)hf_z_to_mm(&s->f, s->st.zmax) / 1000;
    s->width_m = (double)(s->f.w - 1) * (double)s->f.dx_um / 1e6;
    s->depth_m = (double)(s->f.h - 1) * (double)s->f.dy_um / 1e6;
    if (o->colors) {
        if (read_colors(o->colors, &s->ramp, hf_z_to_mm(&s->f, s->st.zmin), hf_z_to_mm(&s->f, s->st.zmax), err) != BR_OK) {
            scene_close(s);
            return err ? err->code : BR_E_FORMAT;
        }
    } else if (o->ramp_abs && s->f.geo.kind != HF_GEO_NONE) rs_ramp_absolute(&s->ramp);
    else rs_ramp_default(&s->ramp, hf_z_to_mm(&s->f, s->st.zmin), hf_z_to_mm(&s->f, s->st.zmax));
    def_sun = o->sun_az == 0 && o->sun_alt == 0;
    rs_sun_dir((int32_t)lround((def_sun ? 315 : o->sun_az) * 1000), (int32_t)lround((def_sun ? 45 : o->sun_alt) * 1000), sun);
    if (rt_scene_init(&s->rt, &s->f, &s->ramp, sun, (int32_t)lround((o->ambient_set ? o->ambient : 0.3) * FX_Q14_ONE)) != BR_OK) {
        scene_close(s);
        return br_err_set(err, BR_E_ARG, name, "invalid heightfield");
    }
    if (o->texture && load_texture(s, o->texture, err) != BR_OK) {
        scene_close(s);
        return err ? err->code : BR_E_FORMAT;
    }
    apply_zscale(s, o, name);
    return BR_OK;
}

br_status scene_tree(scene *s, br_err *err)
{
    size_t tb = bt_mem_size(s->f.w, s->f.h), sb = bt_scratch_size(s->f.w, s->f.h);
    void *scratch;
    br_status st;
    if (s->tree_file) {
        br_status a = tree_file_attach(&s->tree, &s->f, s->tree_file, &s->tree_mem, err);
        if (a == BR_E_VALUE && s->beds_lowered)
            return br_err_set(err, a, s->tree_file, "not a bitree for these heights: the water found lowers the "
                              "flattened lakes' and sea's samples to a bottom before the tree is built, which a tree "
                              "saved by `bitrain mesh --save-tree` does not know; add --no-water");
        return a;
    }
    s->tree_mem = malloc(tb);
    scratch = malloc(sb);
    if (!s->tree_mem || !scratch) {
        free(scratch);
        return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for the bitree (%zu + %zu bytes)", tb, sb);
    }
    st = bt_build(&s->tree, &s->f, BT_METRIC_EXACT, s->tree_mem, tb, scratch, sb);
    free(scratch);
    if (st != BR_OK) return br_err_set(err, st, NULL, "cannot build the bitree");
    return BR_OK;
}

/* Grows the chunk table to at least n bytes. */
static br_status chunks_reserve(scene *s, size_t n)
{
    int16_t *c;
    if (n <= s->chunks_size) return BR_OK;
    c = realloc(s->chunks, n);
    if (!c) return BR_E_NOMEM;
    s->chunks = c;
    s->chunks_size = n;
    return BR_OK;
}

/* A part's room: BT_PARTS parts of 4,096 triangles (about 380 MB reserved, touched as
 * used; docs/bitree.md "Cutting the parts") */
#define SCENE_PART_TRI 4096

br_status scene_reserve(scene *s, uint32_t max_tri, br_err *err)
{
    size_t mb = bt_mesh_mem_size(max_tri);
    s->mesh_mem = malloc(mb);
    if (!s->mesh_mem || bt_mesh_init(&s->mesh, max_tri, s->mesh_mem, mb) != BR_OK)
        return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for a mesh of %u triangles", max_tri);
    {
        uint32_t pt_tri = max_tri < SCENE_PART_TRI ? max_tri : SCENE_PART_TRI;
        size_t pb = bt_parts_mem_size(pt_tri);
        s->parts_mem = pb ? malloc(pb) : NULL;
        if (!s->parts_mem || bt_parts_init(&s->parts, pt_tri, s->parts_mem, pb) != BR_OK)
            return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for %d part meshes of %u triangles",
                              BT_PARTS, pt_tri);
    }
    s->verts = malloc(sizeof *s->verts * (s->mesh.cap_v ? s->mesh.cap_v : 1));
    s->vprev = malloc(sizeof *s->vprev * (s->mesh.cap_v ? s->mesh.cap_v : 1));
    s->cache = malloc(rs_cache_mem_size(s->mesh.cap_v ? s->mesh.cap_v : 1));
    if (!s->verts || !s->vprev || !s->cache)
        return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for %u vertices", s->mesh.cap_v);
    if (rt_cache_mem_size(&s->rt) > 0) s->lit_mem = malloc(rt_cache_mem_size(&s->rt));
    if (s->lit_mem && rt_scene_cache(&s->rt, s->lit_mem, rt_cache_mem_size(&s->rt)) != BR_OK) {
        free(s->lit_mem);
        s->lit_mem = NULL;
    }
    {   /* the chunk table of the longest strip the mesh can hold */
        rs_prim longest;
        longest.kind = RS_STRIP; longest.n = s->mesh.cap_s; longest.idx = NULL;
        if (chunks_reserve(s, rs_chunk_mem_size(&longest, 1)) != BR_OK)
            return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for the chunk table");
    }
    if (!s->clips && !(s->clips = malloc(rs_clip_mem_size(SCENE_CLIPS))))
        return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for the clip table");
    return BR_OK;
}

static void grid_free(scene *s)
{
    free(s->grid_v); free(s->grid_idx); free(s->grid_prims); free(s->grid_cache);
    s->grid_v = NULL; s->grid_idx = NULL; s->grid_prims = NULL; s->grid_cache = NULL;
    s->grid_nv = 0; s->grid_nprims = 0;
}

void scene_close(scene *s)
{
    grid_free(s);
    free(s->verts);
    free(s->vprev);
    free(s->cache);
    free(s->chunks);
    free(s->clips);
    free(s->tree_mem);
    free(s->mesh_mem);
    free(s->parts_mem);
    free(s->lit_mem);
    free(s->texpx);
    dem_free(&s->f);
    memset(s, 0, sizeof *s);
}

void scene_default_view(const scene *s, double fovy_deg, double eye[3], double target[3])
{
    /* the sphere is loose for a flat tile: 3/4 of its fitting distance fills the
     * frame; the nearest corner may touch the bottom edge */
    double W = s->width_m, H = s->depth_m, Z = s->zmax_m - s->zmin_m;
    double R = 0.5 * sqrt(W * W + H * H + Z * Z);
    double d = 0.75 * R / sin(fovy_deg / 2 * SCENE_PI / 180), el = 35 * SCENE_PI / 180;
    target[0] = 0.5 * W; target[1] = 0.5 * H; target[2] = 0.5 * (s->zmin_m + s->zmax_m);
    eye[0] = target[0] - d * cos(el) * 0.7071;
    eye[1] = target[1] - d * cos(el) * 0.7071;
    eye[2] = target[2] + d * sin(el);
}

double scene_ground(const scene *s, double x, double y)
{
    double gx = x * 1e6 / (double)s->f.dx_um, gy = (double)(s->f.h - 1) - y * 1e6 / (double)s->f.dy_um;
    int32_t z;
    if (!(gx >= 0 && gy >= 0 && gx <= s->f.w - 1 && gy <= s->f.h - 1)) return (double)NAN;
    z = s->f.z[(size_t)lround(gy) * (size_t)s->f.w + (size_t)lround(gx)];
    if (z == HF_NODATA) return (double)NAN;
    return (double)hf_z_to_mm(&s->f, z) / 1000 * s->zscale;
}

br_status scene_camera(const scene *s, const double eye[3], const double target[3], double fovy_deg,
                       int32_t w, int32_t h, cam *out)
{
    double scale = ldexp(1.0, s->rt.shift), ext = s->width_m > s->depth_m ? s->width_m : s->depth_m;
    double ground = scene_ground(s, eye[0], eye[1]), dist = 0, nearm;
    int32_t e[3], t[3], znear, zfar;
    int i;
    for (i = 0; i < 3; i++) {
        if (!(fabs(eye[i] * scale) < CAM_COORD_MAX && fabs(target[i] * scale) < CAM_COORD_MAX)) return BR_E_ARG;
        e[i] = (int32_t)lround(eye[i] * scale);
        t[i] = (int32_t)lround(target[i] * scale);
        dist += (eye[i] - target[i]) * (eye[i] - target[i]);
    }
    dist = sqrt(dist);
    if (isnan(ground)) ground = s->zmax_m;
    nearm = fmin(dist / 2000, 0.5 * fabs(eye[2] - ground));
    znear = (int32_t)lround(fmax(0.05, nearm) * scale);
    zfar = (int32_t)fmin((double)CAM_COORD_MAX, (4 * (dist + ext) + fabs(s->zmax_m) + fabs(s->zmin_m)) * scale);
    if (znear < 1) znear = 1;
    if (zfar <= znear) zfar = znear + 1;
    return cam_look_at(out, e, t, (int32_t)lround(fovy_deg * 1000), w, h, znear, zfar);
}

/* Parts are taken largest first (by the previous frame's sizes: the longest
 * processing time rule), so no thread is left with a large part at the end;
 * only the schedule depends on it, never the mesh. */
static void job_part(void *user, uint32_t k)
{
    scene *s = (scene *)user;
    bt_extract_part(s->parts, s->part_order[k]);
}

static void order_parts(scene *s, uint32_t n)
{
    uint32_t i, j;
    for (i = 0; i < n; i++) s->part_order[i] = i;
    for (i = 1; i < n; i++)           /* insertion sort, stable: n <= BT_PARTS */
        for (j = i; j > 0 && s->part_cost[s->part_order[j - 1]] < s->part_cost[s->part_order[j]]; j--) {
            uint32_t tmp = s->part_order[j];
            s->part_order[j] = s->part_order[j - 1];
            s->part_order[j - 1] = tmp;
        }
}

void scene_join_part(bt_parts *ps, uint32_t k, const rt_scene *rt, bt_mesh *m, rs_vertex *out,
                     const rs_vertex *prev)
{
    uint32_t v0, nv, from = 0;
    const uint8_t *moved = bt_part_moved_from(ps, k, &from);
    bt_extract_join(ps, k, &v0, &nv);
    if (moved) memcpy(out + v0, prev + from, (size_t)nv * sizeof *out);
    if (moved) rt_from_mesh_moved(rt, m, v0, nv, moved, out);
    else rt_from_mesh_range(rt, m, v0, nv, out);
}

static void job_join(void *user, uint32_t k)
{
    scene *s = (scene *)user;
    scene_join_part(s->parts, k, &s->rt, &s->mesh, s->verts, s->vprev);
}

br_status scene_mesh(scene *s, const cam *c, bt_params *p)
{
    br_status st;
    uint32_t n = 0;
    p->c = c;
    p->fr = s->rt.fr;
    {   /* this frame's vertices go to the other array; the last frame's stay for the copies */
        rs_vertex *t = s->verts;
        s->verts = s->vprev;
        s->vprev = t;
    }
    if (s->parts) {
        uint32_t k;
        st = bt_extract_begin(s->parts, &s->tree, p, &s->mesh, &n);
        if (st != BR_OK) return st;
        order_parts(s, n);
        pt_jobs(s->pool, n, job_part, s);
        for (k = 0; k < BT_PARTS; k++) s->part_cost[k] = bt_part_tris(s->parts, k);
        st = bt_extract_end(s->parts, &n);
    } else st = bt_extract(&s->tree, p, &s->mesh);
    if (st != BR_OK) return st;
    if (n) {
        pt_jobs(s->pool, n, job_join, s);
        rt_from_mesh_pending(&s->rt, &s->mesh, s->verts);   /* the samples new to the cache */
    } else rt_from_mesh(&s->rt, &s->mesh, s->verts);
    s->prim.kind = RS_STRIP;
    s->prim.n = s->mesh.ns;
    s->prim.idx = s->mesh.strip;
    s->prims = &s->prim;
    s->nprims = 1;
    return BR_OK;
}

br_status scene_grid(scene *s, int32_t step, br_err *err)
{
    int32_t gw, gh, x, y;
    uint32_t nidx = 0;
    if (step < 1) return br_err_set(err, BR_E_ARG, NULL, "grid step %d (at least 1)", step);
    gw = (s->f.w - 1) / step + 1;
    gh = (s->f.h - 1) / step + 1;
    grid_free(s);
    s->grid_nv = (uint32_t)gw * (uint32_t)gh;
    s->grid_v = malloc(sizeof *s->grid_v * s->grid_nv);
    s->grid_idx = malloc(sizeof *s->grid_idx * (size_t)2 * (size_t)gw * (size_t)(gh > 1 ? gh - 1 : 1));
    /* at most one run per two columns of a row (a void between runs) */
    s->grid_prims = malloc(sizeof *s->grid_prims * (size_t)(gh > 1 ? gh - 1 : 1) * (size_t)(gw / 2 + 1));
    s->grid_cache = malloc(rs_cache_mem_size(s->grid_nv));
    if (!s->grid_v || !s->grid_idx || !s->grid_prims || !s->grid_cache) {
        grid_free(s);
        return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for a grid of %d x %d vertices", gw, gh);
    }
    for (y = 0; y < gh; y++)
        for (x = 0; x < gw; x++) {
            int32_t z = s->f.z[(size_t)y * (size_t)step * (size_t)s->f.w + (size_t)x * (size_t)step];
            rt_vertex(&s->rt, x * step, y * step, z == HF_NODATA ? 0 : z, &s->grid_v[y * gw + x]);
        }
    /* row strips, south-west first vertex: CCW seen from +z (row y is north of y+1),
     * one per run of columns whose two samples are valid: a void is a hole (no
     * triangle touches a void sample; the bitree's meshes place one within their error) */
    for (y = 0; y + 1 < gh; y++) {
        const int32_t *zr = s->f.z + (size_t)y * (size_t)step * (size_t)s->f.w;
        const int32_t *zn = s->f.z + (size_t)(y + 1) * (size_t)step * (size_t)s->f.w;
        int32_t a = 0, b;
        while (a < gw) {
            for (b = a; b < gw && zr[(size_t)b * (size_t)step] != HF_NODATA && zn[(size_t)b * (size_t)step] != HF_NODATA; b++) {}
            if (b - a >= 2) {
                uint32_t *sp = s->grid_idx + nidx;
                rs_prim *pr = &s->grid_prims[s->grid_nprims++];
                for (x = a; x < b; x++) {
                    sp[2 * (x - a)] = (uint32_t)(y * gw + x);
                    sp[2 * (x - a) + 1] = (uint32_t)((y + 1) * gw + x);
                }
                pr->kind = RS_STRIP; pr->n = (uint32_t)(2 * (b - a)); pr->idx = sp;
                nidx += (uint32_t)(2 * (b - a));
            }
            a = b + 1;
        }
    }
    if (chunks_reserve(s, rs_chunk_mem_size(s->grid_prims, s->grid_nprims)) != BR_OK) {
        grid_free(s);
        return br_err_set(err, BR_E_NOMEM, NULL, "out of memory for the chunk table");
    }
    s->prims = s->grid_prims;
    s->nprims = s->grid_nprims;
    return BR_OK;
}

br_status scene_terrain(scene *s, const cam *c, rs_frame *fr, rs_pass *pass)
{
    br_status st;
    int grid = s->prims == s->grid_prims && s->grid_prims;
    if (!s->prims || rs_chunk_mem_size(s->prims, s->nprims) > s->chunks_size) return BR_E_ARG;
    fr->w = c->w;
    fr->h = c->h;
    fr->v = grid ? s->grid_v : s->verts;
    fr->nv = grid ? s->grid_nv : s->mesh.nv;
    fr->cache = grid ? s->grid_cache : s->cache;
    fr->prims = s->prims;
    fr->nprims = s->nprims;
    fr->chunks = s->chunks;
    fr->clips = s->clips;
    fr->clip_cap = s->clips ? SCENE_CLIPS : 0;
    fr->tex = s->rt.tex_w > 0 ? &s->tex : NULL;
    cam_viewproj(c, &fr->vp);
    st = rs_frame_prepare(fr);
    if (st == BR_OK && pass) st = rs_pass_terrain(pass, fr);
    return st;
}

br_status scene_frame(scene *s, const cam *c, bt_params *p, rs_frame *fr, rs_prim *prim)
{
    br_status st;
    p->mode = BT_VIEW;
    st = scene_mesh(s, c, p);
    if (st != BR_OK) return st;
    *prim = s->prim;
    return scene_terrain(s, c, fr, NULL);
}
