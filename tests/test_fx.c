/* tests/test_fx.c — fixed-point helpers: the CORDIC and reciprocal seed tables are
 * recomputed from their generator formulas, sin/cos/isqrt/division checked against the
 * C library, the divide-free division (fx_recip) against C's `/`. */
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
    for (v = 1; v < ((uint64_t)1 << 24); v++) {     /* every v of the 32-bit steps' first 2^24 */
        const uint64_t r = fx_isqrt64(v);
        CHECK(r * r <= v && (r + 1) * (r + 1) > v);
    }
    for (v = 1; v < 5000000000000ULL; v = v * 3 + 7) {
        uint64_t r = fx_isqrt64(v);
        CHECK(r * r <= v && (r + 1) * (r + 1) > v);
    }
    {   /* around every power of two (where the first bit tried changes) and around squares
         * over the whole range: floor(sqrt(v)) exactly, (r + 1)^2 compared without overflow */
        int k, d;
        for (k = 0; k < 64; k++)
            for (d = -2; d <= 2; d++) {
                const uint64_t p2 = (uint64_t)1 << k, sq = (uint64_t)1 << (k / 2 * 2);
                const uint64_t vs[2] = { p2 + (uint64_t)(int64_t)d, (sq - 1) * (sq - 1) + (uint64_t)(int64_t)d };
                int j;
                for (j = 0; j < 2; j++) {
                    const uint64_t r = fx_isqrt64(vs[j]);
                    CHECK(r <= 0xffffffffu && r * r <= vs[j] && (r == 0xffffffffu || (r + 1) * (r + 1) > vs[j]));
                }
            }
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

/* a divisor: all magnitudes equally likely, then any bits below the top one */
static uint32_t any_divisor(void)
{
    const uint64_t r = t_xs64();
    const uint32_t top = (uint32_t)1 << (r & 31);
    return top | ((uint32_t)(r >> 32) & (top - 1u));
}

/* the reciprocal: never above floor((2^64 - 1) / dn) - 2^32, and at most 8 below it
 * (which bounds fx_udiv_r's correction loop); the quotients equal C's `/` */
static void check_recip(uint32_t d, uint64_t n)
{
    const fx_recip r = fx_recip_make(d);
    const uint64_t exact = UINT64_MAX / r.dn - ((uint64_t)1 << 32);
    CHECK_EQ(r.dn, (uint64_t)d << r.s);
    CHECK(r.dn >> 31 == 1u);
    CHECK_MSG(r.v <= exact && (uint64_t)r.v + 8u >= exact, "d=%lu v=%lu exact=%llu", (unsigned long)d,
              (unsigned long)r.v, (unsigned long long)exact);
    n %= (uint64_t)d << 32;                       /* any n < d 2^32 */
    CHECK_EQ(fx_udiv_r(n, &r), n / d);
    CHECK_EQ(fx_udiv_once(n, d), n / d);
    CHECK_EQ(fx_udiv_r(((uint64_t)d << 32) - 1u, &r), (((uint64_t)d << 32) - 1u) / d);
    CHECK_EQ(fx_udiv_r(d - 1u, &r), 0);
    CHECK_EQ(fx_udiv_r(d, &r), 1);
    {   /* signed, truncated toward zero like C's /; refused from |n| = d 2^32 on */
        const int64_t sn = (int64_t)(n >> 1) * ((n & 1) ? -1 : 1);
        int64_t q = 12345;
        CHECK(fx_sdiv_r(sn, &r, &q) && q == sn / (int64_t)d);
        if (d < 0x80000000u) {
            const int64_t lim = (int64_t)d << 32;
            CHECK(fx_sdiv_r(-(lim - 1), &r, &q) && q == -(lim - 1) / (int64_t)d);
            CHECK(fx_sdiv_r(lim - 1, &r, &q) && q == (lim - 1) / (int64_t)d);
            q = 12345;
            CHECK(!fx_sdiv_r(lim, &r, &q) && !fx_sdiv_r(-lim, &r, &q) && q == 12345);
        }
    }
}

static void test_recip(void)
{
    uint32_t i, d;
    for (i = 0; i < 256; i++) CHECK_EQ(fx_recip_seed[i], (1u << 25) / (257u + i) - 65536u);
    for (d = 1; d <= (1u << 20); d++) check_recip(d, t_xs64());
    for (i = 0; i < 32; i++) {                    /* powers of two and their neighbours */
        d = (uint32_t)1 << i;
        check_recip(d, t_xs64());
        check_recip(d + 1u, t_xs64());
        if (d > 1) check_recip(d - 1u, UINT64_MAX);
    }
    check_recip(0xffffffffu, UINT64_MAX);
    for (i = 0; i < 3000000; i++) check_recip(any_divisor(), t_xs64());
    /* the triangles' reciprocal of the doubled area: every a of the tiny and small
     * triangles (< 2^21), then any */
    for (d = 1; d < (1u << 21); d++) CHECK_EQ(fx_inv40(d), ((uint64_t)1 << 40) / d);
    for (i = 0; i < 1000000; i++) {
        d = any_divisor();
        CHECK_EQ(fx_inv40(d), ((uint64_t)1 << 40) / d);
    }
    CHECK_EQ(fx_inv40(0xffffffffu), 256);
}

/* fx_udiv_short: the reciprocal after its Newton step within 3 of 2^32 / D for every D,
 * and C's `/` for every divisor below 2^16 at the ends of its range and between */
static void test_udiv_short(void)
{
    uint32_t d, i;
    for (d = 32768; d < 65536; d++) {
        const uint32_t r0 = 65536u + fx_recip_seed[(d >> 7) - 256u], e = 0u - d * r0;
        const uint32_t r1 = r0 + (uint32_t)(((uint64_t)r0 * e) >> 32);
        const uint64_t x = ((uint64_t)1 << 32) / d;
        CHECK_MSG(r1 <= x && r1 + 3u >= x, "D=%lu R1=%lu", (unsigned long)d, (unsigned long)r1);
    }
    for (d = 1; d < 65536; d++) {
        const uint64_t lim = (uint64_t)d << 17;
        const uint32_t top = lim > 0xffffffffu ? 0xffffffffu : (uint32_t)(lim - 1u);
        CHECK_EQ(fx_udiv_short(top, d), top / d);
        CHECK_EQ(fx_udiv_short(0, d), 0);
        CHECK_EQ(fx_udiv_short(d - 1u, d), 0);
        CHECK_EQ(fx_udiv_short(d, d), 1);
        for (i = 0; i < 16; i++) {
            const uint32_t n = (uint32_t)(t_xs64() % (top + (uint64_t)1));
            CHECK_EQ(fx_udiv_short(n, d), n / d);
        }
    }
}

/* fx_divisor: C's `/` and floor for any divisor, large ones and large quotients included
 * (with BR_DIV64_NATIVE = 0, the fallbacks to `/`); trunc32 writes only quotients it
 * may compute that way */
static void test_divisor(void)
{
    int i;
    for (i = 0; i < 2000000; i++) {
        const uint64_t r = t_xs64();
        const int64_t d = (int64_t)(t_xs64() >> (1 + (r & 63) % 63)) + 1;
        const int64_t n = (int64_t)(t_xs64() >> (2 + (r >> 6) % 62)) * ((r >> 12) & 1 ? -1 : 1);
        fx_divisor q;
        int64_t t = 777;
        fx_divisor_make(&q, d);
        CHECK_EQ(fx_divisor_trunc(&q, n), n / d);
        CHECK_EQ(fx_divisor_floor(&q, n), fx_div_floor(n, d));
        if (fx_divisor_trunc32(&q, n, &t)) CHECK_EQ(t, n / d);
        else CHECK(t == 777 && !BR_DIV64_NATIVE && (d > 0xffffffff || n / d >= ((int64_t)1 << 32) || n / d <= -((int64_t)1 << 32)));
    }
    /* the wide quotients' edges (core/fx.c fx_udiv_wide): divisors whose top 32
     * bits are all ones or a power of two, numerators one below, at and one above a
     * multiple of the divisor, and the largest */
    for (i = 0; i < 200000; i++) {
        static const int64_t top[4] = { 0xffffffffLL, 0x80000000LL, 0xfffffffeLL, 0x80000001LL };
        const uint64_t r = t_xs64();
        const int sh = (int)(r % 32);
        const int64_t d = i & 1 ? (top[(r >> 5) & 3] << sh) + (int64_t)((r >> 7) & ((1u << sh) - 1u))
                                : (int64_t)((r >> 7) & 0xffffffff) + 1;
        const int64_t qmax = INT64_MAX / d, k = (int64_t)(t_xs64() % (uint64_t)qmax) + (i & 2 ? 0 : qmax - 3 > 0 ? qmax - 3 : 0);
        fx_divisor q;
        int j;
        fx_divisor_make(&q, d);
        for (j = -1; j <= 1; j++) {
            const uint64_t un = k > qmax ? (uint64_t)INT64_MAX : (uint64_t)k * (uint64_t)d + (uint64_t)(int64_t)j;
            const int64_t n = (int64_t)(un > (uint64_t)INT64_MAX ? (uint64_t)INT64_MAX : un);
            CHECK_EQ(fx_divisor_trunc(&q, n), n / d);
            CHECK_EQ(fx_divisor_trunc(&q, -n), -n / d);
        }
    }
    /* fx_udiv_wide itself over the whole unsigned range (raster/water_setup.c's n reach 2^64) */
    for (i = 0; i < 400000; i++) {
        const uint64_t r = t_xs64(), n = t_xs64() >> (r % 64);
        const uint64_t dr = t_xs64() >> ((r >> 6) % 64), d = dr ? dr : 1u;
        CHECK_EQ(fx_udiv_wide(n, d, fx_recip_make(d <= 0xffffffffu ? (uint32_t)d : 1u)), n / d);
        CHECK_EQ(fx_udiv_wide(~(uint64_t)0, d, fx_recip_make(d <= 0xffffffffu ? (uint32_t)d : 1u)), ~(uint64_t)0 / d);
    }
    for (i = 1; i < 100000; i++) CHECK_EQ(fx_div40((uint32_t)i), ((int64_t)1 << 40) / i);
}

int main(void)
{
    T_RUN(test_table_generator);
    T_RUN(test_sincos);
    T_RUN(test_isqrt_div);
    T_RUN(test_recip);
    T_RUN(test_udiv_short);
    T_RUN(test_divisor);
    return t_finish();
}
