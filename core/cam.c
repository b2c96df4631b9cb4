/* core/cam.c — fixed-point camera (see cam.h). */
#include "core/cam.h"

static int in_range(int32_t v) { return v >= -CAM_COORD_MAX && v <= CAM_COORD_MAX; }

br_status cam_look_at(cam *c, const int32_t eye[3], const int32_t target[3],
                      int32_t fovy_mdeg, int32_t w, int32_t h, int32_t znear, int32_t zfar)
{
    int64_t d[3], rt[3], up[3];
    fx_q30 fwd[3], right[3], upn[3], s, co;
    int i;
    for (i = 0; i < 3; i++)
        if (!in_range(eye[i]) || !in_range(target[i])) return BR_E_ARG;
    if (fovy_mdeg < 1000 || fovy_mdeg > 170000 || w < 1 || h < 1 || w > 16384 || h > 16384
        || znear <= 0 || zfar <= znear) return BR_E_ARG;
    for (i = 0; i < 3; i++) d[i] = (int64_t)target[i] - eye[i];
    if (!fx_normalize3(d, fwd)) return BR_E_ARG;
    /* right = fwd x upHint; upHint = +z, or +y when fwd is (nearly) vertical */
    if (fwd[0] == 0 && fwd[1] == 0) {
        /* fwd x (0,1,0) = (-fz, 0, fx) */
        rt[0] = -(int64_t)fwd[2]; rt[1] = 0; rt[2] = fwd[0];
    } else {
        /* fwd x (0,0,1) = (fy, -fx, 0) */
        rt[0] = fwd[1]; rt[1] = -(int64_t)fwd[0]; rt[2] = 0;
    }
    if (!fx_normalize3(rt, right)) return BR_E_ARG;
    /* up = right x fwd (Q60 products, kept as int64 before normalising) */
    up[0] = (int64_t)right[1] * fwd[2] - (int64_t)right[2] * fwd[1];
    up[1] = (int64_t)right[2] * fwd[0] - (int64_t)right[0] * fwd[2];
    up[2] = (int64_t)right[0] * fwd[1] - (int64_t)right[1] * fwd[0];
    if (!fx_normalize3(up, upn)) return BR_E_ARG;
    for (i = 0; i < 3; i++) {
        c->eye[i] = eye[i]; c->fwd[i] = fwd[i]; c->right[i] = right[i]; c->up[i] = upn[i];
    }
    c->w = w; c->h = h; c->fovy_mdeg = fovy_mdeg; c->znear = znear; c->zfar = zfar;
    fx_sincos(fx_angle_from_mdeg(fovy_mdeg / 2), &s, &co);
    /* half the field of view is 0.5 .. 85 degrees: tan < 11.5 (< 2^20 in Q16) and
     * (h / 2) cot <= 8192 * 114.6 (< 2^36 in Q16), short quotients (fx_div_round_bits) */
    c->tan_half = (fx_q16)fx_div_round_bits((int64_t)s * FX_Q16_ONE, co, 20);
    /* f = (h/2) cos/sin, Q16 */
    c->f_q16 = fx_div_round_bits((int64_t)h * co * (FX_Q16_ONE / 2), s, 36);
    return BR_OK;
}

void cam_to_view(const cam *c, const int32_t p[3], int64_t out[3])
{
    int64_t d0 = (int64_t)p[0] - c->eye[0], d1 = (int64_t)p[1] - c->eye[1], d2 = (int64_t)p[2] - c->eye[2];
    const fx_q30 *b[3];
    int i;
    b[0] = c->right; b[1] = c->up; b[2] = c->fwd;
    for (i = 0; i < 3; i++)
        out[i] = (b[i][0] * d0 + b[i][1] * d1 + b[i][2] * d2 + ((int64_t)1 << 29)) >> 30;
}

int cam_project(const cam *c, const int32_t p[3], int64_t out_q16[2])
{
    int64_t v[3];
    cam_to_view(c, p, v);
    if (v[2] < c->znear) return 0;
    /* |f_q16 * v| < 2^(16+14) * 2^32: fits */
    out_q16[0] = (int64_t)c->w * (FX_Q16_ONE / 2) + fx_div_round(c->f_q16 * v[0], v[2]);
    out_q16[1] = (int64_t)c->h * (FX_Q16_ONE / 2) - fx_div_round(c->f_q16 * v[1], v[2]);
    return 1;
}

void cam_viewproj(const cam *c, cam_vp *out)
{
    int i, j;
    for (j = 0; j < 3; j++) {
        out->r[0][j] = c->right[j]; out->r[1][j] = c->up[j]; out->r[2][j] = c->fwd[j];
    }
    for (i = 0; i < 3; i++) {
        int64_t t = 0;
        for (j = 0; j < 3; j++) t -= (int64_t)out->r[i][j] * c->eye[j];
        out->t[i] = t;
    }
    out->f_q16 = c->f_q16;
    out->cx_q16 = c->w * (FX_Q16_ONE / 2);
    out->cy_q16 = c->h * (FX_Q16_ONE / 2);
    out->znear = c->znear;
    out->zfar = c->zfar;
}

/* Plane through the eye with camera-space normal (a, b, e) (any scale). */
static void side_plane(const cam *c, int64_t a, int64_t b, int64_t e, cam_plane *pl)
{
    int64_t v[3], nc[3];
    fx_q30 n[3];
    int j;
    v[0] = a; v[1] = b; v[2] = e;
    fx_normalize3(v, n);
    for (j = 0; j < 3; j++)   /* world normal = R^T n */
        nc[j] = ((int64_t)n[0] * c->right[j] + (int64_t)n[1] * c->up[j]
                 + (int64_t)n[2] * c->fwd[j]) >> 30;
    fx_normalize3(nc, pl->n);
    pl->d = 0;
    for (j = 0; j < 3; j++) pl->d -= (int64_t)pl->n[j] * c->eye[j];
}

void cam_frustum(const cam *c, cam_plane out[CAM_NPLANES])
{
    const int32_t all[4] = { 0, 0, c->w, c->h };
    cam_frustum_window(c, all, out);
}

/* sx = cx + f xc / zc >= x0 is f xc + (cx - x0) zc >= 0 (zc > 0), and likewise for the
 * other three sides (sy = cy - f yc / zc); the whole viewport gives cx - 0 = w / 2 and
 * so the planes cam_frustum always had.  |x0 2^16| <= 2^30: the normals' terms fit. */
void cam_frustum_window(const cam *c, const int32_t win[4], cam_plane out[CAM_NPLANES])
{
    const int64_t f = c->f_q16, cx = (int64_t)c->w * (FX_Q16_ONE / 2), cy = (int64_t)c->h * (FX_Q16_ONE / 2);
    int64_t fe = 0;
    int j;
    side_plane(c, f, 0, cx - (int64_t)win[0] * FX_Q16_ONE, &out[CAM_LEFT]);     /* sx >= x0 */
    side_plane(c, -f, 0, (int64_t)win[2] * FX_Q16_ONE - cx, &out[CAM_RIGHT]);   /* sx <= x1 */
    side_plane(c, 0, f, (int64_t)win[3] * FX_Q16_ONE - cy, &out[CAM_BOTTOM]);   /* sy <= y1 */
    side_plane(c, 0, -f, cy - (int64_t)win[1] * FX_Q16_ONE, &out[CAM_TOP]);     /* sy >= y0 */
    for (j = 0; j < 3; j++) fe += (int64_t)c->fwd[j] * c->eye[j];
    for (j = 0; j < 3; j++) { out[CAM_NEAR].n[j] = c->fwd[j]; out[CAM_FAR].n[j] = -c->fwd[j]; }
    out[CAM_NEAR].d = -fe - (int64_t)c->znear * FX_Q30_ONE;
    out[CAM_FAR].d = fe + (int64_t)c->zfar * FX_Q30_ONE;
}

void cam_frustum_rows(const cam *c, int32_t y0, int32_t y1, cam_plane *bottom, cam_plane *top)
{
    const int64_t f = c->f_q16, cy = (int64_t)c->h * (FX_Q16_ONE / 2);
    if (bottom) side_plane(c, 0, f, (int64_t)y1 * FX_Q16_ONE - cy, bottom);
    if (top) side_plane(c, 0, -f, cy - (int64_t)y0 * FX_Q16_ONE, top);
}

int64_t cam_proj_scale_q16(const cam *c) { return c->f_q16; }
