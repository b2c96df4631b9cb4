/* raster/raster_pixel.h — the state sets (variants) the per-triangle code is
 * specialised for, and the pixel and depth accesses that depend on them.  raster.c's
 * own: included by it once, before the triangle code (raster_tiny.h, raster_span.h,
 * raster_general.h, raster_draw.h).
 *
 * SPECIALISATION
 * A variant is a constant `vf`, an OR of the VF_ flags below.  Every function of the
 * triangle code that draws takes `const int vf` as its last argument and is
 * RSI_INLINE (always_inline), so GCC and clang fold each flag test and each access
 * width: a caller with a constant vf gets the code of that state set only, with no
 * per-pixel branch on state.  The copies the compiler keeps are named where they are
 * made: draw_888_z32 .. draw_count in raster_draw.h (one line each, what draw_for
 * hands out), and the out-of-line helpers (tri_raster, pair_wide, tri_tiny_own, the
 * tri_gen_* cases, and for the textured and counting variants tiny_shade_slow,
 * tri_pair_slow, quad_shade_slow) each with one `case` line per variant in its switch.
 *
 * PIXELS AND DEPTHS
 * Colour rows hold uint32_t XRGB8888 or uint16_t RGB565 pixels, depth rows uint32_t d
 * or uint16_t d >> 14 (raster.h, Depth).  The code keeps rows as void pointers and
 * reads and writes through px_put / z_get / z_put, which cast to the variant's type:
 * the same loads and stores as typed pointers. */
#ifndef BR_RASTER_PIXEL_H
#define BR_RASTER_PIXEL_H
#include <stddef.h>
#include <stdint.h>

enum {
    VF_565 = 1,         /* colour RGB565 (else XRGB8888) */
    VF_Z16 = 2,         /* 16-bit depth, d >> 14 (else 32-bit d) */
    VF_TEX = 4,         /* textured: perspective-correct texel times the Gouraud colour */
    VF_COUNT = 8,       /* the tests' write counting: no depth test, each covered pixel's
                           XRGB8888 value is incremented (RS_WITH_COUNT builds only) */
    VF_NOZ = 16         /* no depth buffer (RS_DEPTH_NONE): every covered centre is written,
                           so the last triangle drawn over a pixel is the one it shows
                           (the caller's order: back to front) */
};
/* The eleven variants: pixel format x depth size, each plain or textured; counting; and
 * each pixel format without depth (lists only: rs_draw_band refuses strips). */
enum {
    V_888_Z32 = 0, V_888_Z16 = VF_Z16, V_565_Z16 = VF_565 | VF_Z16, V_565_Z32 = VF_565,
    V_888_Z32_TEX = VF_TEX, V_888_Z16_TEX = VF_Z16 | VF_TEX,
    V_565_Z16_TEX = VF_565 | VF_Z16 | VF_TEX, V_565_Z32_TEX = VF_565 | VF_TEX,
    V_COUNT = VF_COUNT,
    V_888_NOZ = VF_NOZ, V_565_NOZ = VF_565 | VF_NOZ
};

/* 1 when this build compiles variant vf (core/config.h RS_WITH_*): a constant, so a
 * `case` for a left-out variant folds to nothing. */
#define RS_BUILT(vf) ((((vf) & VF_COUNT) ? RS_WITH_COUNT && RS_WITH_888 && RS_WITH_Z32 :                \
                       (((vf) & VF_565) ? RS_WITH_565 : RS_WITH_888)                                  \
                       && (((vf) & VF_NOZ) ? RS_WITH_NOZ : ((vf) & VF_Z16) ? RS_WITH_Z16 : RS_WITH_Z32) \
                       && (((vf) & VF_TEX) ? RS_WITH_TEX : 1)))

/* ORIENTATION AND FILL RULE (raster.h CONVENTIONS), the one place they are spelled.
 * Doubled signed areas are computed from screen positions as seen, (b - a) x (c - a)
 * with y pointing down, so a triangle counter-clockwise seen from the camera (a front
 * face, OpenGL's default) has a NEGATIVE area: is_front. */
RSI_INLINE static int is_front(int64_t area2) { return area2 < 0; }
RSI_INLINE static int is_back(int64_t area2) { return area2 > 0; }
/* x, negated when neg (edges of front faces are reversed so that the inside is positive) */
RSI_INLINE static int32_t sg(int32_t x, const int neg) { return neg ? -x : x; }
/* The top-left rule's bias of an edge with x step A and y step B (edge function E =
 * A (X - P.x) + B (Y - P.y), inside positive; Pineda 1988): bias = 1 exactly when
 * 2 A + (B > 0) <= 0, i.e. A < 0, or A == 0 and B <= 0; a centre with E == 0 on such an
 * edge is outside (e = E - bias < 0), on the others (the left and horizontal top edges of
 * raster.h's fill rule) inside, so two triangles sharing an edge never both cover a
 * centre on it.  tl_bias16, for |A|, |B| < 2^15 (tiny boxes, quads): 2 A + (B > 0) <= 0
 * iff A 2^16 + B <= 0 (|B| < 2^15 cannot outweigh a unit of A), the sign bit of A 2^16 +
 * B - 1 (|A 2^16 + B| < 2^31: no overflow).  tl_bias64, for any vertex differences (far
 * below 2^62): the sign bit of 2 A + (B > 0) - 1. */
RSI_INLINE static int32_t tl_bias16(int32_t A, int32_t B)
{
    return (int32_t)((uint32_t)(A * 65536 + B - 1) >> 31);
}
RSI_INLINE static int64_t tl_bias64(int64_t A, int64_t B)
{
    return (int64_t)((uint64_t)(2 * A + (B > 0) - 1) >> 63);
}

/* Plain variants: the strip pairs and their shading are inlined into the strip loop;
 * the textured and counting ones call them out of line (their speed matters less than
 * their code size). */
#define VF_SLOW(vf) (((vf) & (VF_TEX | VF_COUNT)) != 0)

RSI_INLINE static size_t px_bytes(const int vf) { return (vf & VF_565) ? 2u : 4u; }
RSI_INLINE static size_t z_bytes(const int vf) { return (vf & VF_NOZ) ? 0u : (vf & VF_Z16) ? 2u : 4u; }

/* Entry i of a colour or depth row (i may be negative: rows walked from their end). */
RSI_INLINE static void *px_at(void *row, ptrdiff_t i, const int vf)
{
    return (uint8_t *)row + i * (ptrdiff_t)px_bytes(vf);
}
RSI_INLINE static void *z_at(void *row, ptrdiff_t i, const int vf)
{
    return (uint8_t *)row + i * (ptrdiff_t)z_bytes(vf);
}

/* The depth a 32-bit d is stored as: d itself, or (16-bit buffers) d >> 14 truncated to
 * 16 bits (d < 2^30, so nothing is lost by the truncation).  Without depth (VF_NOZ) the
 * test `z_store(d) > z_get(p)` is the constant 1 > 0 and nothing is read or stored, so
 * the compiler drops the depth's interpolation with them. */
RSI_INLINE static uint32_t z_store(uint32_t d, const int vf)
{
    if (vf & VF_NOZ) { (void)d; return 1; }
    return (vf & VF_Z16) ? (uint32_t)(uint16_t)(d >> 14) : d;
}
RSI_INLINE static uint32_t z_get(const void *p, const int vf)
{
    if (vf & VF_NOZ) { (void)p; return 0; }
    return (vf & VF_Z16) ? *(const uint16_t *)p : *(const uint32_t *)p;
}
RSI_INLINE static void z_put(void *p, uint32_t z, const int vf)
{
    if (vf & VF_NOZ) { (void)p; (void)z; }
    else if (vf & VF_Z16) *(uint16_t *)p = (uint16_t)z;
    else *(uint32_t *)p = z;
}
RSI_INLINE static void px_put(void *p, uint32_t px, const int vf)
{
    if (vf & VF_565) *(uint16_t *)p = (uint16_t)px;
    else *(uint32_t *)p = px;
}

/* The pixel of a packed colour (three 21-bit fields, see RS_CBIAS in raster.c), and of
 * a 0xRRGGBB value (the clear colour, texels). */
RSI_INLINE static uint32_t px_pack(uint64_t col, const int vf)
{
    return (vf & VF_565) ? (uint32_t)PACK565(col) : PACK888(col);
}
RSI_INLINE static uint32_t px_pack24(uint32_t rgb, const int vf)
{
    return (vf & VF_565) ? (uint32_t)PACK24_565(rgb) : PACK24_888(rgb);
}

/* Where pixel (px, py) (py in the band) starts in the band's colour and depth. */
RSI_INLINE static void *band_crow(const band *bd, int32_t py, int32_t px, const int vf)
{
    return px_at(bd->color + (size_t)(py - bd->y0) * bd->stride, px, vf);
}
RSI_INLINE static void *band_zrow(const band *bd, int32_t py, int32_t px, const int vf)
{
    return z_at(z_at(bd->depth, (ptrdiff_t)((size_t)(py - bd->y0) * (size_t)bd->w), vf), px, vf);
}

#endif
