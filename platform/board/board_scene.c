/* platform/board/board_scene.c — see board_scene.h. */
#include "platform/board/board_scene.h"
#include "mcu/bake.h"
#include "platform/board/board.h"
#include "platform/board/spi_band.h"

br_status board_scene(hf *f, rs_ramp *ramp, rt_scene *rt)
{
    fx_q14 sun[3];
    f->w = bake.w; f->h = bake.h;
    f->z = (int32_t *)(uintptr_t)bake_z;     /* read only: no path writes hf.z */
    f->z_num = bake.z_num; f->z_den = bake.z_den;
    f->dx_um = bake.dx_um; f->dy_um = bake.dy_um;
    f->geo.kind = bake.geo_kind;
    f->geo.x0 = bake.geo_x0; f->geo.y0 = bake.geo_y0; f->geo.sx = bake.geo_sx; f->geo.sy = bake.geo_sy;
    rs_ramp_default(ramp, bake.ramp_zmin_mm, bake.ramp_zmax_mm);
    rs_sun_dir(bake.sun_az_mdeg, bake.sun_alt_mdeg, sun);
    if (rt_scene_init(rt, f, ramp, sun, bake.ambient_q14) != BR_OK) return BR_E_ARG;
    /* the shading cache is baked for every valid sample, so rt_vertex only reads it */
    rt->lvl = (uint16_t *)(uintptr_t)bake_lvl;
    rt->ztab = (uint32_t *)(uintptr_t)bake_ztab;
    rt->nz = bake.nz;
    return BR_OK;
}

int32_t board_frames(void)
{
    return bake.nframes;
}

void board_sum_start(board_sum *s, uint8_t *row, rs_sink tap, void *tap_user)
{
    s->sum = SPIB_SUM_INIT; s->dc = -1; s->row = row; s->tap = tap; s->tap_user = tap_user;
}

static void put(void *user, int dc, const uint8_t *p, size_t n)
{
    board_sum *s = (board_sum *)user;
    s->sum = spib_sum(s->sum, &s->dc, dc, p, n);
}

br_status board_sum_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    board_sum *s = (board_sum *)user;
    spib_band(put, s, bake.fb_w, y0, rows, px, stride, s->row);
    return s->tap ? s->tap(s->tap_user, y0, rows, px, stride) : BR_OK;
}
