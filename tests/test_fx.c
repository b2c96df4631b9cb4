/* tests/test_fx.c — fixed-point helpers: the CORDIC table is recomputed from its
 * generator formula, sin/cos/isqrt/division checked against the C library. */
#include <math.h>
#include "tests/test.h"
#include "core/fx.h"

static void test_table_generator(void)
{
    int i;
    double k = 1.0;
    for (i = 0; i < FX_CORDIC_N; i++) {
        double v = atan(ldexp(1.0, -i)) / (2.0 * 3.14159265358979323846) * 4294967296.0;
        CHECK_EQ(fx_cordic_atan[i], (long long)llround(v));
        k /= sqrt(1.0 + ldexp(1.0, -2 * i));
    }
    CHECK_EQ(FX_CORDIC_K, (long long)llround(k * 1073741824.0));
}

static void test_sincos(void)
{
    int32_t md;
    double maxerr = 0;
    for (md = -720000; md <= 720000; md += 997) {
        fx_q30 s, c;
        double a = md / 1000.0 * 3.14159265358979323846 / 180.0;
        fx_sincos(fx_angle_from_mdeg(md), &s, &c);
        double es = fabs(s / 1073741824.0 - sin(a)), ec = fabs(c / 1073741824.0 - cos(a));
        if (es > maxerr) maxerr = es;
        if (ec > maxerr) maxerr = ec;
    }
    CHECK_MSG(maxerr < 2e-8, "max error %g", maxerr);
    {   /* exact quadrants */
        fx_q30 s, c;
        fx_sincos(0, &s, &c);
        CHECK(c > FX_Q30_ONE - 8 && s >= -8 && s <= 8);
        fx_sincos(fx_angle_from_mdeg(90000), &s, &c);
        CHECK(s > FX_Q30_ONE - 8 && c >= -8 && c <= 8);
        fx_sincos(fx_angle_from_mdeg(180000), &s, &c);
        CHECK(c < -FX_Q30_ONE + 8);
    }
}

static void test_isqrt_div(void)
{
    uint64_t v;
    CHECK_EQ(fx_isqrt64(0), 0);
    CHECK_EQ(fx_isqrt64(UINT64_MAX), 4294967295LL);
    for (v = 1; v < 5000000000000ULL; v = v * 3 + 7) {
        uint64_t r = fx_isqrt64(v);
        CHECK(r * r <= v && (r + 1) * (r + 1) > v);
    }
    CHECK_EQ(fx_div_floor(-7, 2), -4);
    CHECK_EQ(fx_div_floor(7, -2), -4);
    CHECK_EQ(fx_div_floor(-8, 2), -4);
    {   /* the inline positive-divisor floor agrees with the general one */
        int64_t n, d;
        for (n = -40; n <= 40; n++)
            for (d = 1; d <= 17; d++) CHECK_EQ(fx_div_floor_pos(n, d), fx_div_floor(n, d));
        CHECK_EQ(fx_div_floor_pos(-((int64_t)1 << 40) - 1, 16), -((int64_t)1 << 36) - 1);
    }
    CHECK_EQ(fx_div_ceil(-7, 2), -3);
    CHECK_EQ(fx_div_ceil(7, 2), 4);
    CHECK_EQ(fx_div_round(-7, 2), -4);
    CHECK_EQ(fx_div_round(7, 2), 4);
    CHECK_EQ(fx_div_round(5, 3), 2);
    {
        int64_t a[3] = { 3, -4, 0 };
        fx_q30 n[3];
        CHECK(fx_normalize3(a, n));
        CHECK_EQ(n[0], 644245094);
        CHECK_EQ(n[1], -858993459);
        a[0] = a[1] = 0;
        CHECK(!fx_normalize3(a, n));
    }
}

int main(void)
{
    T_RUN(test_table_generator);
    T_RUN(test_sincos);
    T_RUN(test_isqrt_div);
    return t_finish();
}
