/* tests/test_water_setup.c — raster/water_setup.c's per-frame fog table against its
 * definition (raster/water.h: entry i weighs depth d_i = i 2^fog_sh + 2^(fog_sh - 1),
 * whose distance along the view axis is zc = floor(K / d_i), K = RS_DEPTH_ONE znear),
 * through rw_setup over random near planes and fog ranges: the table is made by a walk
 * over the weights' steps, not one quotient an entry, and has to give the same bytes.
 * In the divide-free build (BR_DIV64_NATIVE = 0) its quotients come from reciprocals. */
#include "tests/test.h"
#include "core/cam.h"
#include "raster/raster.h"
#include "raster/water.h"

/* The weight of entry i by the definition: t = 256 where zc >= ze (depth 0: infinitely
 * far), 256 (zc - zs) / (ze - zs) rounded down between, 0 at or below zs; the weight
 * (t^2 + 128) >> 8, at most 255. */
static uint8_t fog_ref(int64_t K, int64_t zs, int64_t ze, int32_t sh, int32_t i)
{
    const int64_t d = ((int64_t)i << sh) + (((int64_t)1 << sh) >> 1), zc = d ? K / d : INT64_MAX;
    const int64_t t = zc <= zs ? 0 : zc >= ze ? 256 : ((zc - zs) << 8) / (ze - zs);
    return (uint8_t)((t * t + 128) >> 8 > 255 ? 255 : (t * t + 128) >> 8);
}

/* a draw below 2^bits, bits itself drawn below `most` (so that small values come too) */
static int64_t draw(int most)
{
    const int bits = (int)(t_xs64() % (uint64_t)most) + 1;
    return (int64_t)(t_xs64() >> (64 - bits));
}

static void test_fog_table(void)
{
    rw_frame *r = calloc(1, sizeof *r);
    const int32_t eye[3] = { 0, 0, 5000 }, target[3] = { 40000, 30000, 0 };
    int n, wrong = 0, shift = 0;
    CHECK(r != NULL);
    if (!r) return;
    for (n = 0; n < 600; n++) {
        cam c;
        rs_frame tf;
        rw_params p;
        const int32_t znear = (int32_t)draw(24) + 1, zfar = znear + (int32_t)draw(30) + 1;
        int64_t K;
        int32_t i, sh = 0;
        memset(&p, 0, sizeof p);
        p.fog_on = 1;
        p.sky_on = 1;
        p.fog_start = draw(44) + 1;
        p.fog_end = p.fog_start + draw(n % 3 ? 44 : 12) + 1;
        if (cam_look_at(&c, eye, target, 60000, 64, 48, znear, zfar) != BR_OK) { CHECK(0); break; }
        memset(&tf, 0, sizeof tf);
        tf.w = 64; tf.h = 48; tf.fmt = RS_FMT_XRGB8888; tf.depth = RS_DEPTH32;
        cam_viewproj(&c, &tf.vp);
        if (n == 0) {   /* water reads the terrain's depth: a frame without it is refused */
            tf.depth = RS_DEPTH_NONE;
            CHECK_EQ(rw_setup(r, &p, &c, &tf, NULL, NULL), BR_E_ARG);
            tf.depth = RS_DEPTH32;
        }
        if (rw_setup(r, &p, &c, &tf, NULL, NULL) != BR_OK) { CHECK(0); break; }
        K = (int64_t)RS_DEPTH_ONE * tf.vp.znear;
        while ((K / p.fog_start) >> sh > RW_TAB) sh++;      /* the table reaches K / zs */
        shift += r->fog_sh != sh;
        for (i = 0; i <= RW_TAB; i++) wrong += r->fog[i] != fog_ref(K, p.fog_start, p.fog_end, sh, i);
    }
    CHECK_EQ(shift, 0);
    CHECK_EQ(wrong, 0);
    printf("test_water_setup: %d fog tables against their definition\n", n);
    free(r);
}

int main(void)
{
    T_RUN(test_fog_table);
    return t_finish();
}
