/* tests/test_cam.c — the fixed-point camera against a double-precision reference
 * (gluLookAt + gluPerspective), using camera A of the peer scene in 1/1024 units. */
#include <math.h>
#include <string.h>
#include "tests/test.h"
#include "core/cam.h"

#define U 1024
static void ref_project(const double e[3], const double t[3], double fovy, int w, int h,
                        const double p[3], double out[2], double *zc)
{
    double f[3], r[3], u[3], d[3], l;
    int i;
    for (i = 0; i < 3; i++) f[i] = t[i] - e[i];
    l = sqrt(f[0]*f[0] + f[1]*f[1] + f[2]*f[2]); for (i = 0; i < 3; i++) f[i] /= l;
    r[0] = f[1]; r[1] = -f[0]; r[2] = 0;
    l = sqrt(r[0]*r[0] + r[1]*r[1]); r[0] /= l; r[1] /= l;
    u[0] = r[1]*f[2] - r[2]*f[1]; u[1] = r[2]*f[0] - r[0]*f[2]; u[2] = r[0]*f[1] - r[1]*f[0];
    for (i = 0; i < 3; i++) d[i] = p[i] - e[i];
    {
        double xc = r[0]*d[0] + r[1]*d[1] + r[2]*d[2], yc = u[0]*d[0] + u[1]*d[1] + u[2]*d[2];
        double z = f[0]*d[0] + f[1]*d[1] + f[2]*d[2];
        double fo = h / 2.0 / tan(fovy / 2.0 * 3.14159265358979323846 / 180.0);
        out[0] = w / 2.0 + fo * xc / z; out[1] = h / 2.0 - fo * yc / z; *zc = z;
    }
}

static void test_project(void)
{
    cam c;
    int32_t eye[3] = { 128 * U, -100 * U, 180 * U }, tg[3] = { 128 * U, 100 * U, 0 };
    double de[3] = { 128, -100, 180 }, dt[3] = { 128, 100, 0 };
    int i, j;
    CHECK_EQ(cam_look_at(&c, eye, tg, 55000, 640, 480, 10 * U, 1000 * U), BR_OK);
    for (j = 0; j <= 256; j += 32)
        for (i = 0; i <= 256; i += 32) {
            int32_t p[3] = { i * U, j * U, (i * j % 64) * U };
            double dp[3] = { i, j, i * j % 64 }, r[2], zc;
            int64_t q[2];
            ref_project(de, dt, 55.0, 640, 480, dp, r, &zc);
            CHECK(cam_project(&c, p, q));
            CHECK_MSG(fabs((double)q[0] / 65536.0 - r[0]) < 0.01 && fabs((double)q[1] / 65536.0 - r[1]) < 0.01,
                      "(%d,%d): %f %f vs %f %f", i, j, (double)q[0] / 65536.0, (double)q[1] / 65536.0, r[0], r[1]);
        }
    /* f = 240 / tan(27.5 deg) = 461.02 px */
    CHECK(llabs(cam_proj_scale_q16(&c) - (int64_t)llround(240.0 / tan(27.5 * 3.14159265358979323846 / 180.0) * 65536.0)) < 64);
}

/* Every sample point is inside all six planes of cam_frustum_window(c, win) exactly
 * when it projects into the rectangle win within near .. far. */
static void frustum_check(const cam *c, const int32_t win[4])
{
    cam_plane pl[CAM_NPLANES];
    int i, j, k;
    cam_frustum_window(c, win, pl);
    for (j = -64; j <= 320; j += 16)
        for (i = -64; i <= 320; i += 16)
            for (k = -8; k <= 64; k += 8) {
                int32_t p[3] = { i * U + 7, j * U + 3, k * U };
                int64_t v[3], q[2];
                int in = 1, in2;
                for (int m = 0; m < CAM_NPLANES; m++) {
                    int64_t s = pl[m].d;
                    for (int n = 0; n < 3; n++) s += (int64_t)pl[m].n[n] * p[n];
                    if (s < -((int64_t)1 << 36)) in = 0;          /* margin: 1/16 unit */
                    else if (s < ((int64_t)1 << 36)) in = -1;      /* too close to call */
                }
                if (in < 0) continue;
                cam_to_view(c, p, v);
                in2 = v[2] >= c->znear && v[2] <= c->zfar && cam_project(c, p, q) && q[0] >= (int64_t)win[0] * 65536
                      && q[0] <= (int64_t)win[2] * 65536 && q[1] >= (int64_t)win[1] * 65536
                      && q[1] <= (int64_t)win[3] * 65536;
                CHECK_MSG(in == in2, "window %d %d %d %d, point %d %d %d: planes %d projection %d", win[0], win[1],
                          win[2], win[3], i, j, k, in, in2);
            }
}

/* The viewport's frustum, a window's (the reflection's selection reads part of the
 * screen), and the whole viewport as a window is cam_frustum to the bit. */
static void test_frustum(void)
{
    cam c;
    cam_plane pl[CAM_NPLANES], pw[CAM_NPLANES];
    int32_t eye[3] = { 110 * U, 5 * U, 1200 }, tg[3] = { 190 * U, 256 * U, -10 * U };
    const int32_t all[4] = { 0, 0, 640, 480 }, part[4] = { 96, 200, 420, 300 }, corner[4] = { 0, 0, 17, 480 };
    int i;
    CHECK_EQ(cam_look_at(&c, eye, tg, 75000, 640, 480, 256, 1000 * U), BR_OK);
    frustum_check(&c, all);
    frustum_check(&c, part);
    frustum_check(&c, corner);
    cam_frustum(&c, pl);
    cam_frustum_window(&c, all, pw);
    for (i = 0; i < CAM_NPLANES; i++)
        CHECK(pl[i].d == pw[i].d && !memcmp(pl[i].n, pw[i].n, sizeof pl[i].n));
}

static void test_args(void)
{
    cam c;
    int32_t e[3] = { 0, 0, 0 }, t[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1000 };
    CHECK_EQ(cam_look_at(&c, e, t, 60000, 100, 100, 1, 10), BR_E_ARG);
    CHECK_EQ(cam_look_at(&c, e, up, 60000, 100, 100, 1, 10), BR_OK);   /* straight up works */
    CHECK_EQ(c.right[0], -FX_Q30_ONE);   /* up hint +y: right = fwd x y = -x */
    CHECK_EQ(cam_look_at(&c, e, up, 500, 100, 100, 1, 10), BR_E_ARG);
    CHECK_EQ(cam_look_at(&c, e, up, 60000, 100, 100, 10, 10), BR_E_ARG);
    t[0] = INT32_MAX;
    CHECK_EQ(cam_look_at(&c, e, t, 60000, 100, 100, 1, 10), BR_E_ARG);
}

int main(void)
{
    T_RUN(test_project);
    T_RUN(test_frustum);
    T_RUN(test_args);
    return t_finish();
}
