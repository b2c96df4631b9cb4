/* tests/support/waterview.c — see waterview.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tests/test.h"
#include "platform/png_io.h"
#include "tests/support/waterview.h"

void wv_defaults(scene_opts *so, ws_opts *wo, bt_params *bp, rs_frame *fr, br_err *err)
{
    memset(so, 0, sizeof *so); memset(wo, 0, sizeof *wo);
    memset(fr, 0, sizeof *fr); memset(bp, 0, sizeof *bp); memset(err, 0, sizeof *err);
    so->quiet = 1;
    wo->quiet = 1; wo->view_px = 1;
    fr->fmt = RS_FMT_XRGB8888; fr->depth = RS_DEPTH32;
}

void wv_lake_frame(scene *s, const scene_opts *so, water_scene *ws, const ws_opts *wo, const double eye[3],
                   const double tgt[3], int32_t w, int32_t h, cam *c, bt_params *bp, rs_frame *fr)
{
    wv_dem_frame("hgt/N47E009.hgt", s, so, ws, wo, eye, tgt, w, h, c, bp, fr);
}

void wv_dem_frame(const char *dem, scene *s, const scene_opts *so, water_scene *ws, const ws_opts *wo,
                  const double eye[3], const double tgt[3], int32_t w, int32_t h, cam *c, bt_params *bp, rs_frame *fr)
{
    const char *in[1];
    br_err err;
    memset(s, 0, sizeof *s); memset(ws, 0, sizeof *ws); memset(&err, 0, sizeof err);
    in[0] = t_data(dem);
    CHECK_EQ(scene_open(s, in, 1, so, &err), BR_OK);
    CHECK_EQ(ws_open(ws, s, wo, &err), BR_OK);
    CHECK_EQ(scene_camera(s, eye, tgt, 50, w, h, c), BR_OK);
    CHECK_EQ(scene_tree(s, &err), BR_OK);
    CHECK_EQ(scene_reserve(s, 2000000, &err), BR_OK);
    bp->mode = BT_VIEW; bp->c = c; bp->fr = s->rt.fr; bp->pixel_err_q8 = 256;
    CHECK_EQ(scene_mesh(s, c, bp), BR_OK);
    CHECK_EQ(scene_terrain(s, c, fr, NULL), BR_OK);
}

void wv_golden(const char *name, const char *out)
{
    char gpath[256];
    uint8_t *a = NULL, *g = NULL;
    int aw = 0, ah = 0, gw = 0, gh = 0;
    br_err err;
    snprintf(gpath, sizeof gpath, "tests/golden/%s.png", name);
    if (png_read_rgb(out, &aw, &ah, &a, &err) != BR_OK) { CHECK_MSG(0, "cannot read %s", out); return; }
    if (getenv("BITRAIN_UPDATE_GOLDEN")) CHECK_EQ(png_write_rgb(gpath, aw, ah, a, (size_t)aw * 3, &err), BR_OK);
    if (png_read_rgb(gpath, &gw, &gh, &g, &err) != BR_OK) CHECK_MSG(0, "cannot read %s (BITRAIN_UPDATE_GOLDEN=1 writes it)", gpath);
    else CHECK_MSG(aw == gw && ah == gh && !memcmp(a, g, (size_t)aw * (size_t)ah * 3), "%s differs from %s", out, gpath);
    free(a); free(g);
}

void wv_view_open(wv_view *v, const char *dem, const double eye[3], const double tgt[3], int32_t w, int32_t h,
                  void (*opts)(wv_view *v))
{
    wv_defaults(&v->so, &v->wo, &v->bp, &v->fr, &v->err);
    if (opts) opts(v);
    wv_dem_frame(dem, &v->s, &v->so, &v->ws, &v->wo, eye, tgt, w, h, &v->c, &v->bp, &v->fr);
}

void wv_view_close(wv_view *v)
{
    ws_close(&v->ws);
    scene_close(&v->s);
}
