/* tests/test_hf.c — heightfield checks and statistics. */
#include "tests/test.h"
#include "core/hf.h"

static void test_dims(void)
{
    CHECK_EQ(hf_check_dims(1201, 1201), BR_OK);
    CHECK_EQ(hf_check_dims(0, 5), BR_E_FORMAT);
    CHECK_EQ(hf_check_dims(5, -1), BR_E_FORMAT);
    CHECK_EQ(hf_check_dims(BR_MAX_SIDE + 1, 2), BR_E_TOO_BIG);
    CHECK_EQ(hf_check_dims(2000000000LL, 2000000000LL), BR_E_TOO_BIG);
}

static void test_stats(void)
{
    /* 3x2, asymmetric, one void */
    int32_t z[6] = { 5, -7, HF_NODATA, 12, 0, 3 };
    hf f = { 3, 2, z, 1, 10, 1000000, 1000000, { 0, 0, 0, 0, 0 } };
    hf_stats s;
    hf_stats_get(&f, &s);
    CHECK_EQ(s.zmin, -7);
    CHECK_EQ(s.zmax, 12);
    CHECK_EQ(s.voids, 1);
    CHECK_EQ(hf_z_to_mm(&f, 12), 1200);
    CHECK_EQ(hf_z_to_mm(&f, -7), -700);
    CHECK_EQ(hf_validate(&f), BR_OK);
    f.dx_um = 0;
    CHECK_EQ(hf_validate(&f), BR_E_ARG);
}

int main(void)
{
    T_RUN(test_dims);
    T_RUN(test_stats);
    return t_finish();
}
