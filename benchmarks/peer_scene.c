/* benchmarks/peer_scene.c — see peer_scene.h.  Platform-side code (floating point
 * allowed: it builds the scene INPUT once); linked into the program (`bitrain bench`),
 * the tests and the benchmark programs, never into libbitrain.a. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "benchmarks/peer_scene.h"
#include "platform/png_io.h"

static const double peer_ramp[6][4] = {
    { 0.00, 0.18, 0.40, 0.16 },
    { 0.25, 0.35, 0.55, 0.22 },
    { 0.50, 0.55, 0.45, 0.30 },
    { 0.75, 0.55, 0.50, 0.46 },
    { 0.88, 0.85, 0.85, 0.85 },
    { 1.00, 1.00, 1.00, 1.00 },
};

static void peer_rampc(double t, double c[3])
{
    int k, m;
    for (k = 0; k < 5; k++) {
        if (t <= peer_ramp[k + 1][0]) {
            double u = (t - peer_ramp[k][0]) / (peer_ramp[k + 1][0] - peer_ramp[k][0]);
            for (m = 0; m < 3; m++)
                c[m] = peer_ramp[k][1 + m] + (peer_ramp[k + 1][1 + m] - peer_ramp[k][1 + m]) * u;
            return;
        }
    }
    for (m = 0; m < 3; m++) c[m] = peer_ramp[5][1 + m];
}

static double peer_Z(const double *hm, double hmin, double zs, int i, int j)
{
    i = i < 0 ? 0 : (i > PEER_N - 1 ? PEER_N - 1 : i);
    j = j < 0 ? 0 : (j > PEER_N - 1 ? PEER_N - 1 : j);
    return (hm[j * PEER_N + i] - hmin) * zs;
}

int peer_scene_build(const char *fuji_png, peer_scene *s)
{
    int w, h, i, j, m;
    uint8_t *px = NULL;
    double *hm, hmin, hmax, zs, L[3] = { -1.0, -1.0, 1.5 }, ll;
    br_err err;
    if (png_read_rgb(fuji_png, &w, &h, &px, &err) != BR_OK) {
        fprintf(stderr, "peer scene: %s\n", err.msg);
        return -1;
    }
    hm = (double *)malloc(sizeof(double) * PEER_NV);
    if (!hm) { free(px); return -1; }
    for (j = 0; j < PEER_N; j++) {
        int sy = 2 * j < h - 1 ? 2 * j : h - 1;
        for (i = 0; i < PEER_N; i++) {
            int sx = 2 * i < w - 1 ? 2 * i : w - 1;
            const uint8_t *p = px + ((size_t)sy * (size_t)w + (size_t)sx) * 3;
            hm[j * PEER_N + i] = -10000.0 + (double)(p[0] * 65536 + p[1] * 256 + p[2]) * 0.1;
        }
    }
    free(px);
    hmin = hmax = hm[0];
    for (i = 0; i < PEER_NV; i++) {
        if (hm[i] < hmin) hmin = hm[i];
        if (hm[i] > hmax) hmax = hm[i];
    }
    zs = 64.0 / (hmax - hmin);
    ll = sqrt(0.0 + L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
    for (m = 0; m < 3; m++) L[m] /= ll;
    for (j = 0; j < PEER_N; j++)
        for (i = 0; i < PEER_N; i++) {
            size_t v = (size_t)j * PEER_N + (size_t)i;
            double z = peer_Z(hm, hmin, zs, i, j);
            double dzdx = (peer_Z(hm, hmin, zs, i + 1, j) - peer_Z(hm, hmin, zs, i - 1, j)) * 0.5;
            double dzdy = -(peer_Z(hm, hmin, zs, i, j + 1) - peer_Z(hm, hmin, zs, i, j - 1)) * 0.5;
            double n[3], nl, d, sh, c[3];
            n[0] = -dzdx; n[1] = -dzdy; n[2] = 1.0;
            nl = sqrt(0.0 + n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (m = 0; m < 3; m++) n[m] /= nl;
            d = 0.0 + n[0] * L[0] + n[1] * L[1] + n[2] * L[2];
            if (d < 0.0) d = 0.0;
            sh = 0.30 + 0.70 * d;
            peer_rampc(z / 64.0, c);
            s->pos[3 * v] = (float)i;
            s->pos[3 * v + 1] = (float)(PEER_N - 1 - j);
            s->pos[3 * v + 2] = (float)z;
            s->ipos[3 * v] = i * PEER_UNIT;
            s->ipos[3 * v + 1] = (PEER_N - 1 - j) * PEER_UNIT;
            s->ipos[3 * v + 2] = (int32_t)lrint(z * PEER_UNIT);
            for (m = 0; m < 3; m++) {
                double cc = c[m] * sh;
                if (cc > 1.0) cc = 1.0;
                s->col[3 * v + m] = (float)cc;
                s->rgba[4 * v + m] = (uint8_t)nearbyint(cc * 255); /* Python round(): half to even */
            }
            s->rgba[4 * v + 3] = 255;
        }
    free(hm);
    for (j = 0; j < PEER_NSTRIP; j++)
        for (i = 0; i < PEER_N; i++) {
            s->strip[j * PEER_STRIP_LEN + 2 * i] = (uint32_t)(j * PEER_N + i);
            s->strip[j * PEER_STRIP_LEN + 2 * i + 1] = (uint32_t)((j + 1) * PEER_N + i);
        }
    m = 0;
    for (j = 0; j < PEER_N - 1; j++)
        for (i = 0; i < PEER_N - 1; i++) {
            uint32_t a = (uint32_t)(j * PEER_N + i), b = (uint32_t)((j + 1) * PEER_N + i);
            uint32_t c = a + 1, d = b + 1;
            s->list[m++] = a; s->list[m++] = b; s->list[m++] = c;
            s->list[m++] = c; s->list[m++] = b; s->list[m++] = d;
        }
    return 0;
}

int peer_camera(char which, peer_camera_def *def, int32_t eye[3], int32_t target[3],
                int32_t *fovy_mdeg, int32_t *znear, int32_t *zfar)
{
    static const peer_camera_def A = { { 128, -100, 180 }, { 128, 100, 0 }, 55, 10, 1000 };
    static const peer_camera_def B = { { 110, 5, 1.1717901 }, { 190, 256, -10.828210 }, 75, 0.25, 1000 };
    const peer_camera_def *c = which == 'A' || which == 'a' ? &A : which == 'B' || which == 'b' ? &B : NULL;
    int k;
    if (!c) return -1;
    if (def) *def = *c;
    for (k = 0; k < 3; k++) {
        eye[k] = (int32_t)lrint(c->eye[k] * PEER_UNIT);
        target[k] = (int32_t)lrint(c->target[k] * PEER_UNIT);
    }
    *fovy_mdeg = (int32_t)lrint(c->fovy_deg * 1000);
    *znear = (int32_t)lrint(c->znear * PEER_UNIT);
    *zfar = (int32_t)lrint(c->zfar * PEER_UNIT);
    return 0;
}

void peer_scene_raster(const peer_scene *s, rs_vertex *v, rs_prim *prims)
{
    int i;
    for (i = 0; i < PEER_NV; i++) {
        v[i].p[0] = s->ipos[3 * i]; v[i].p[1] = s->ipos[3 * i + 1]; v[i].p[2] = s->ipos[3 * i + 2];
        v[i].rgb = ((uint32_t)s->rgba[4 * i] << 16) | ((uint32_t)s->rgba[4 * i + 1] << 8) | s->rgba[4 * i + 2];
        v[i].uv[0] = v[i].uv[1] = 0;
    }
    for (i = 0; i < PEER_NSTRIP; i++) {
        prims[i].kind = RS_STRIP; prims[i].n = PEER_STRIP_LEN; prims[i].idx = s->strip + i * PEER_STRIP_LEN;
    }
}

int peer_frame(char which, int32_t w, int32_t h, const rs_vertex *v, const rs_prim *prims, rs_frame *f)
{
    int32_t eye[3], tg[3], fovy, zn, zf;
    cam c;
    if (peer_camera(which, NULL, eye, tg, &fovy, &zn, &zf) != 0) return -1;
    if (cam_look_at(&c, eye, tg, fovy, w, h, zn, zf) != BR_OK) return -1;
    memset(f, 0, sizeof *f);
    f->w = w; f->h = h; f->fmt = RS_FMT_XRGB8888; f->depth = RS_DEPTH32; f->no_cull = 1;
    f->clear_rgb = 0x99ccffu;
    f->v = v; f->nv = PEER_NV; f->prims = prims; f->nprims = PEER_NSTRIP;
    cam_viewproj(&c, &f->vp);
    return 0;
}
