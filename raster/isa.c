/* raster/isa.c — which copy of the drawing code runs (see rs_isa_set in raster.h).
 *
 * With RS_ISA_DISPATCH=1 (the Makefile sets it on x86-64 when the compiler takes
 * -march=x86-64-v3 and __builtin_cpu_supports("x86-64-v3")), raster.c and xform.c are
 * in the library twice (raster_int.h names the copies): the baseline one and the v3
 * one; so are raster/water.c and water_pass.c, whose post hook (rw_post) and water
 * pass (water_run) call their v3 copies when rs_isa() says V3.  This file defines the
 * public rs_frame_prepare and rs_draw_band,
 * which call the copy chosen here.  Why a second copy: the strip pre-pass and the
 * spans are written with 128-bit generic vectors, and at baseline x86-64 (SSE2, two
 * operands) a third of the pre-pass's per-group instructions are register copies; the
 * same source compiled for x86-64-v3 (three-operand AVX forms, BMI2 shifts) draws the
 * peer scene with fewer instructions (docs/perf-history.md).  Every CPU sold since
 * 2015 takes the v3 copy; the copies compute the same integers, so the bytes are the
 * same (make test draws the peer scene and water frames with both and compares).
 *
 * The choice is made once, at the first call (a plain int: racing threads compute the
 * same value). */
#include "raster/raster.h"

#if defined(RS_ISA_DISPATCH) && RS_ISA_DISPATCH
br_status rs_frame_prepare_base(rs_frame *f);
br_status rs_draw_band_base(const rs_frame *f, int32_t y0, int32_t rows, void *color, size_t stride, void *depth,
                            rs_band_stats *st);
br_status rs_frame_prepare_v3(rs_frame *f);
br_status rs_draw_band_v3(const rs_frame *f, int32_t y0, int32_t rows, void *color, size_t stride, void *depth,
                          rs_band_stats *st);

static int g_isa;       /* 0 until chosen */

static int isa_best(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("x86-64-v3") ? RS_ISA_V3 : RS_ISA_BASE;
}

int rs_isa_set(int isa)
{
    g_isa = isa == RS_ISA_BASE || (isa == RS_ISA_V3 && isa_best() == RS_ISA_V3) ? isa : isa_best();
    return g_isa;
}

int rs_isa(void)
{
    if (!g_isa) g_isa = isa_best();
    return g_isa;
}

br_status rs_frame_prepare(rs_frame *f)
{
    return rs_isa() == RS_ISA_V3 ? rs_frame_prepare_v3(f) : rs_frame_prepare_base(f);
}

br_status rs_draw_band(const rs_frame *f, int32_t y0, int32_t rows, void *color, size_t stride, void *depth,
                       rs_band_stats *st)
{
    return rs_isa() == RS_ISA_V3 ? rs_draw_band_v3(f, y0, rows, color, stride, depth, st)
                                 : rs_draw_band_base(f, y0, rows, color, stride, depth, st);
}
#else
int rs_isa_set(int isa) { (void)isa; return RS_ISA_BASE; }
int rs_isa(void) { return RS_ISA_BASE; }
#endif

const char *rs_isa_name(int isa)
{
#if defined(__x86_64__)
    return isa == RS_ISA_V3 ? "x86-64-v3" : "x86-64";
#else
    (void)isa;
    return "generic";
#endif
}
