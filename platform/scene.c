/* platform/scene.c — see scene.h. */
#include "platform/scene.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

br_status scene_open(scene *s, const char *const *in, int n, const scene_opts *o, br_err *err)
{
    scene_opts d;
    fx_q14 sun[3];
    void *scratch;
    size_t tb, sb, mb;
    uint32_t cap;
    memset(s, 0, sizeof *s);
    memset(&d, 0, sizeof d);
    if (!o) o = &d;
    if (dem_load_many(in, n, &o->dem, &s->f, err) != BR_OK) return err ? err->code : BR_E_IO;
    hf_stats_get(&s->f, &s->st);
    s->zmin_m = (double)hf_z_to_mm(&s->f, s->st.zmin) / 1000;
    s->zmax_m = (double)hf_z_to_mm(&s->f, s->st.zmax) / 1000;
    s->width_m = (double)(s->f.w - 1) * s->f.dx_um / 1e6;
    s->depth_m = (double)(s->f.h - 1) * s->f.dy_um / 1e6;
    rs_ramp_default(&s->ramp, hf_z_to_mm(&s->f, s->st.zmin), hf_z_to_mm(&s->f, s->st.zmax));
    rs_sun_dir((int32_t)lround((o->sun_az != 0 || o->sun_alt != 0 ? o->sun_az : 315) * 1000),
               (int32_t)lround((o->sun_az != 0 || o->sun_alt != 0 ? o->sun_alt : 45) * 1000), sun);
    if (rt_scene_init(&s->rt, &s->f, &s->ramp, sun,
                      (int32_t)lround((o->ambient > 0 ? o->ambient : 0.3) * FX_Q14_ONE)) != BR_OK) {
        scene_close(s);
        return br_err_set(err, BR_E_ARG, in[0], "invalid heightfield");
    }
    tb = bt_mem_size(s->f.w, s->f.h);
    sb = bt_scratch_size(s->f.w, s->f.h);
    cap = o->max_tri ? o->max_tri : 2000000;
    mb = bt_mesh_mem_size(cap);
    s->tree_mem = malloc(tb);
    scratch = malloc(sb);
    s->mesh_mem = malloc(mb);
    if (!s->tree_mem || !scratch || !s->mesh_mem) {
        free(scratch);
        scene_close(s);
        return br_err_set(err, BR_E_NOMEM, in[0], "out of memory for the bitree (%zu + %zu bytes)", tb, mb);
    }
    if (bt_build(&s->tree, &s->f, BT_METRIC_EXACT, s->tree_mem, tb, scratch, sb) != BR_OK ||
        bt_mesh_init(&s->mesh, cap, s->mesh_mem, mb) != BR_OK) {
        free(scratch);
        scene_close(s);
        return br_err_set(err, BR_E_ARG, in[0], "cannot build the bitree");
    }
    free(scratch);
    s->verts = malloc(sizeof *s->verts * s->mesh.cap_v);
    s->cache = malloc(rs_cache_mem_size(s->mesh.cap_v));
    if (!s->verts || !s->cache) {
        scene_close(s);
        return br_err_set(err, BR_E_NOMEM, in[0], "out of memory for %u vertices", s->mesh.cap_v);
    }
    return BR_OK;
}

void scene_close(scene *s)
{
    free(s->verts);
    free(s->cache);
    free(s->tree_mem);
    free(s->mesh_mem);
    dem_free(&s->f);
    memset(s, 0, sizeof *s);
}

void scene_default_view(const scene *s, double eye[3], double target[3])
{
    double ext = s->width_m > s->depth_m ? s->width_m : s->depth_m;
    eye[0] = -0.15 * s->width_m; eye[1] = -0.15 * s->depth_m; eye[2] = s->zmax_m + 0.35 * ext;
    target[0] = 0.5 * s->width_m; target[1] = 0.5 * s->depth_m; target[2] = 0.5 * (s->zmin_m + s->zmax_m);
}

double scene_ground(const scene *s, double x, double y)
{
    long col = lround(x * 1e6 / s->f.dx_um), row = (long)(s->f.h - 1) - lround(y * 1e6 / s->f.dy_um);
    int32_t z;
    if (col < 0 || row < 0 || col >= s->f.w || row >= s->f.h) return s->zmin_m;
    z = s->f.z[(size_t)row * (size_t)s->f.w + (size_t)col];
    return z == HF_NODATA ? s->zmin_m : (double)hf_z_to_mm(&s->f, z) / 1000;
}

br_status scene_camera(const scene *s, const double eye[3], const double target[3], double fovy_deg,
                       int32_t w, int32_t h, cam *out)
{
    double scale = ldexp(1.0, s->rt.shift), ext = s->width_m > s->depth_m ? s->width_m : s->depth_m;
    double agl = eye[2] - scene_ground(s, eye[0], eye[1]), dist, nearm, farm;
    int32_t e[3], t[3], znear, zfar;
    int i;
    for (i = 0; i < 3; i++) {
        if (!(fabs(eye[i] * scale) < CAM_COORD_MAX && fabs(target[i] * scale) < CAM_COORD_MAX)) return BR_E_ARG;
        e[i] = (int32_t)lround(eye[i] * scale);
        t[i] = (int32_t)lround(target[i] * scale);
    }
    dist = sqrt((eye[0] - 0.5 * s->width_m) * (eye[0] - 0.5 * s->width_m) +
                (eye[1] - 0.5 * s->depth_m) * (eye[1] - 0.5 * s->depth_m));
    /* 1/w depth resolves best with the near plane as far out as the view allows:
     * a quarter of the height above the ground, at least 0.25 m */
    nearm = agl > 1 ? agl / 4 : 0.25;
    farm = 2 * (dist + ext) + (s->zmax_m - s->zmin_m);
    znear = (int32_t)lround(nearm * scale);
    zfar = (int32_t)fmin((double)CAM_COORD_MAX, farm * scale);
    if (znear < 1) znear = 1;
    if (zfar <= znear) zfar = znear + 1;
    return cam_look_at(out, e, t, (int32_t)lround(fovy_deg * 1000), w, h, znear, zfar);
}

br_status scene_frame(scene *s, const cam *c, bt_params *p, rs_frame *fr, rs_prim *prim)
{
    br_status st;
    p->mode = BT_VIEW;
    p->c = c;
    p->fr = s->rt.fr;
    st = bt_extract(&s->tree, p, &s->mesh);
    if (st != BR_OK) return st;
    rt_from_mesh(&s->rt, &s->mesh, s->verts);
    prim->kind = RS_STRIP;
    prim->n = s->mesh.ns;
    prim->idx = s->mesh.strip;
    fr->w = c->w;
    fr->h = c->h;
    fr->v = s->verts;
    fr->nv = s->mesh.nv;
    fr->cache = s->cache;
    fr->prims = prim;
    fr->nprims = 1;
    cam_viewproj(c, &fr->vp);
    return rs_frame_prepare(fr);
}
