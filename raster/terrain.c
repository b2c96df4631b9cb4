/* raster/terrain.c — heightfield / bitree mesh to raster vertices (see terrain.h). */
#include "raster/terrain.h"
#include <string.h>

/* The vertical scale in Q16 world units per height unit for world unit 2^-shift m
 * and exaggeration num/den: z_num / z_den * num / den * 2^(shift + 16), rounded in
 * two steps (the unexaggerated scale first).  -1 when it exceeds INT32_MAX: z_num <
 * 2^31 and shift + 16 <= 32 keep z_num << (shift + 16) below 2^63, and the first
 * step's result is <= INT32_MAX before it is multiplied by num < 2^31. */
static int64_t zscale_q16(const hf *f, int32_t shift, int32_t num, int32_t den)
{
    int64_t sz = (((int64_t)f->z_num << (shift + 16)) + f->z_den / 2) / f->z_den;
    if (sz > INT32_MAX) return -1;
    if (num != den) sz = fx_div_round(sz * num, den);
    if (sz > INT32_MAX) return -1;
    return sz < 1 ? 1 : sz;
}

/* Largest shift in [-8, hi] for which the extent (width, depth, and |height| times
 * num/den, in mm) times 2^shift / 1000 stays <= 2^27 and the vertical scale fits an
 * int32 (zscale_q16); -8 when none does. */
static int32_t frame_shift(const hf *f, int32_t zmin, int32_t zmax, int32_t hi, int32_t num, int32_t den)
{
    int64_t ext_mm, ex, ey, ez;
    int32_t shift;
    ex = (int64_t)f->w * f->dx_um / 1000;
    ey = (int64_t)f->h * f->dy_um / 1000;
    ez = hf_z_to_mm(f, zmax);
    if (-hf_z_to_mm(f, zmin) > ez) ez = -hf_z_to_mm(f, zmin);
    if (num != den) {   /* ez * num / den without overflow: quotient and remainder apart */
        int64_t q = ez / den, r = ez % den;
        ez = q > INT32_MAX ? (int64_t)1 << 62 : q * num + r * num / den;
    }
    ext_mm = ex > ey ? ex : ey;
    if (ez > ext_mm) ext_mm = ez;
    if (ext_mm < 1) ext_mm = 1;
    for (shift = hi; shift > -8; shift--) {
        int64_t v = shift >= 0 ? (ext_mm << shift) / 1000 : (ext_mm >> -shift) / 1000;
        if (v <= ((int64_t)1 << 27) && zscale_q16(f, shift, num, den) > 0) break;
    }
    return shift;
}

/* The world frame for a shift (terrain.h); sz = zscale_q16 (or INT32_MAX at shift -8
 * if even that does not fit). */
static void set_frame(rt_scene *s, int32_t shift, int32_t num, int32_t den)
{
    const hf *f = s->f;
    int64_t sx, sy, sz = zscale_q16(f, shift, num, den);
    if (shift >= 0) {
        sx = (((int64_t)f->dx_um << shift) + 500000) / 1000000;
        sy = (((int64_t)f->dy_um << shift) + 500000) / 1000000;
    } else {
        sx = ((int64_t)f->dx_um + (500000LL << -shift)) / (1000000LL << -shift);
        sy = ((int64_t)f->dy_um + (500000LL << -shift)) / (1000000LL << -shift);
    }
    s->shift = shift;
    s->fr.ox = 0; s->fr.oz = 0;
    s->fr.sx = (int32_t)(sx < 1 ? 1 : sx);
    s->fr.sy = (int32_t)(sy < 1 ? 1 : sy);
    s->fr.sz_q16 = (int32_t)(sz < 1 ? INT32_MAX : sz);
    s->fr.oy = (f->h - 1) * s->fr.sy;
}

br_status rt_scene_init(rt_scene *s, const hf *f, const rs_ramp *ramp, const fx_q14 sun[3],
                        int32_t ambient_q14)
{
    hf_stats st;
    if (hf_validate(f) != BR_OK || shade_init(&s->sc, f) != BR_OK || ambient_q14 < 0 || ambient_q14 > FX_Q14_ONE)
        return BR_E_ARG;
    hf_stats_get(f, &st);
    s->f = f;
    s->zlo = st.zmin;
    s->zhi = st.zmax;
    s->ramp = ramp;
    s->sun[0] = sun[0]; s->sun[1] = sun[1]; s->sun[2] = sun[2];
    s->ambient_q14 = ambient_q14;
    s->tex_w = s->tex_h = 0;
    s->lvl = NULL;
    s->ztab = NULL;
    s->nz = 0;
    set_frame(s, frame_shift(f, s->zlo, s->zhi, 16, 1, 1), 1, 1);
    return BR_OK;
}

static int64_t scale_at_least_1(int64_t v, int64_t num, int64_t den, int64_t max)
{
    int64_t r = fx_div_round(v * num, den);   /* v < 2^31, num < 2^31: fits */
    return r < 1 ? 1 : (r > max ? max : r);
}

br_status rt_scene_zscale(rt_scene *s, int32_t num, int32_t den)
{
    if (num <= 0 || den <= 0) return BR_E_ARG;
    if (num == den) return BR_OK;
    /* the frame keeps its unit unless the exaggerated heights no longer fit it */
    set_frame(s, frame_shift(s->f, s->zlo, s->zhi, s->shift, num, den), num, den);
    if (num < den) {
        s->sc.kx = scale_at_least_1(s->sc.kx, num, den, INT64_MAX);
        s->sc.ky = scale_at_least_1(s->sc.ky, num, den, INT64_MAX);
    } else s->sc.kz = scale_at_least_1(s->sc.kz, den, num, INT64_MAX);
    rt_cache_clear(s);
    return BR_OK;
}

int64_t rt_mm_to_world(const rt_scene *s, int64_t mm)
{
    if (s->shift >= 0) return fx_div_round(mm * ((int64_t)1 << s->shift), 1000);
    return fx_div_round(mm, (int64_t)1000 << -s->shift);
}

/* Heights in the colour table: zhi - zlo + 1, or 0 beyond RT_ZTAB_MAX. */
static int32_t table_heights(const rt_scene *s)
{
    int64_t n = (int64_t)s->zhi - s->zlo + 1;
    return n >= 1 && n <= RT_ZTAB_MAX ? (int32_t)n : 0;
}

/* Bytes of the levels, rounded up to 4 so the table after them is aligned. */
static uint64_t level_bytes(const hf *f)
{
    return ((uint64_t)f->w * (uint64_t)f->h * 2u + 3u) & ~(uint64_t)3;
}

size_t rt_cache_mem_size(const rt_scene *s)
{
    uint64_t n = level_bytes(s->f) + (uint64_t)table_heights(s) * 4u;
    return n <= (uint64_t)SIZE_MAX ? (size_t)n : 0;
}

br_status rt_scene_cache(rt_scene *s, void *mem, size_t mem_bytes)
{
    size_t need = rt_cache_mem_size(s);
    if (mem && (need == 0 || mem_bytes < need || ((uintptr_t)mem & 3) != 0)) return BR_E_ARG;
    s->lvl = (uint16_t *)mem;
    s->nz = mem ? table_heights(s) : 0;
    s->ztab = mem && s->nz ? (uint32_t *)(void *)((uint8_t *)mem + level_bytes(s->f)) : NULL;
    rt_cache_clear(s);
    return BR_OK;
}

void rt_cache_clear(rt_scene *s)
{
    int32_t i;
    if (!s->lvl) return;
    memset(s->lvl, 0, (size_t)s->f->w * (size_t)s->f->h * 2u);
    for (i = 0; i < s->nz; i++) s->ztab[i] = rs_ramp_rgb(s->ramp, hf_z_to_mm(s->f, s->zlo + i));
}

/* The light level of sample (x, y) (not a void): its normal's (core/shade.h). */
static int32_t level_at(const rt_scene *s, int32_t x, int32_t y)
{
    fx_q14 n[3];
    shade_normal(&s->sc, x, y, n);
    return rs_light_level(n, s->sun, s->ambient_q14);
}

/* The unlit colour at height z: white under a texture, else the ramp's. */
static inline uint32_t ramp_at(const rt_scene *s, int32_t z)
{
    if (s->tex_w > 0) return 0xffffffu;
    if ((uint32_t)(z - s->zlo) < (uint32_t)s->nz) return s->ztab[z - s->zlo];
    return rs_ramp_rgb(s->ramp, hf_z_to_mm(s->f, z));
}

/* A void's colour: the ramp's nodata colour, or black. */
static inline uint32_t void_rgb(const rt_scene *s)
{
    return s->ramp->has_nv ? s->ramp->nv_rgb : 0;
}

/* uv = (x tex_w 256 / (w - 1), y tex_h 256 / (h - 1)), truncated: quotients of at most
 * tex 2^8, through fx_divisor (no 64-bit divide on 32-bit targets for textures below
 * 2^24 texels a side; the same quotients as `/`). */
static void vertex_uv(const rt_scene *s, int32_t x, int32_t y, rs_vertex *out)
{
#if RS_TEX_FIELDS
    const hf *f = s->f;
    fx_divisor d;
    out->uv[0] = out->uv[1] = 0;
    if (f->w > 1) {
        fx_divisor_make(&d, f->w - 1);
        out->uv[0] = (int32_t)fx_divisor_trunc(&d, (int64_t)x * s->tex_w * 256);
    }
    if (f->h > 1) {
        fx_divisor_make(&d, f->h - 1);
        out->uv[1] = (int32_t)fx_divisor_trunc(&d, (int64_t)y * s->tex_h * 256);
    }
#else
    (void)s; (void)x; (void)y; (void)out;
#endif
}

/* Position, texture coordinates and, for a void, the colour; 1 when the sample is
 * a void (out is then complete). */
static inline int vertex_base(const rt_scene *s, int32_t x, int32_t y, int32_t z, rs_vertex *out)
{
    const hf *f = s->f;
    out->p[0] = s->fr.ox + x * s->fr.sx;
    out->p[1] = s->fr.oy - y * s->fr.sy;
    out->p[2] = s->fr.oz + (int32_t)(((int64_t)z * s->fr.sz_q16) >> 16);
#if RS_TEX_FIELDS
    out->uv[0] = out->uv[1] = 0;
#endif
    if (s->tex_w > 0 && s->tex_h > 0) vertex_uv(s, x, y, out);
    if (f->z[(size_t)y * (size_t)f->w + (size_t)x] != HF_NODATA) return 0;
    out->rgb = void_rgb(s);
    return 1;
}

/* The level of sample (x, y) (not a void), from the cache when there is one,
 * computed and stored there on a miss. */
static int32_t level_get(const rt_scene *s, int32_t x, int32_t y)
{
    uint16_t *c;
    if (!s->lvl) return level_at(s, x, y);
    c = &s->lvl[(size_t)y * (size_t)s->f->w + (size_t)x];
    if (!*c) *c = (uint16_t)(RT_LVL | (uint32_t)level_at(s, x, y));
    return *c & ~RT_LVL;
}

void rt_vertex(const rt_scene *s, int32_t x, int32_t y, int32_t z, rs_vertex *out)
{
    if (vertex_base(s, x, y, z, out)) return;
    out->rgb = rs_light_apply(ramp_at(s, z), level_get(s, x, y));
}

uint32_t rt_sample_rgb(const rt_scene *s, int32_t x, int32_t y)
{
    const size_t i = (size_t)y * (size_t)s->f->w + (size_t)x;
    const int32_t z = s->f->z[i];
    int32_t lvl;
    if (z == HF_NODATA) return void_rgb(s);
    lvl = s->lvl && (s->lvl[i] & RT_LVL) ? (int32_t)(s->lvl[i] & ~RT_LVL) : level_at(s, x, y);
    return rs_light_apply(ramp_at(s, z), lvl);
}

void rt_from_mesh(const rt_scene *s, const bt_mesh *m, rs_vertex *out)
{
    uint32_t i;
    for (i = 0; i < m->nv; i++) rt_vertex(s, m->v[i].x, m->v[i].y, m->v[i].z, &out[i]);
}

void rt_from_mesh_range(const rt_scene *s, const bt_mesh *m, uint32_t first, uint32_t n, rs_vertex *out)
{
    uint32_t i;
    if (!s->lvl) {
        for (i = first; i < first + n; i++) rt_vertex(s, m->v[i].x, m->v[i].y, m->v[i].z, &out[i]);
        return;
    }
    {
        /* locals: out's stores could alias s as far as C knows */
        const uint16_t *lvl = s->lvl;
        const size_t w = (size_t)s->f->w;
        const bt_vert *v = m->v + first, *ve = v + n;
        rs_vertex *o = out + first;
        for (; v < ve; v++, o++) {
            uint32_t c;
            if (vertex_base(s, v->x, v->y, v->z, o)) continue;
            c = lvl[(size_t)v->y * w + (size_t)v->x];
            o->rgb = c ? rs_light_apply(ramp_at(s, v->z), (int32_t)(c & ~RT_LVL)) : RT_PENDING;
        }
    }
}

void rt_from_mesh_moved(const rt_scene *s, const bt_mesh *m, uint32_t first, uint32_t n, const uint8_t *moved,
                        rs_vertex *out)
{
    uint32_t i;
    for (i = 0; i < n; i += 8) {
        uint32_t b = moved[i >> 3];
        if (n - i < 8) b &= (1u << (n - i)) - 1u;
        for (; b; b &= b - 1u) {
            const uint32_t j = first + i + (uint32_t)(31 - fx_clz32(b & (~b + 1u)));   /* the lowest bit */
            rt_from_mesh_range(s, m, j, 1, out);
        }
    }
}

void rt_from_mesh_pending(const rt_scene *s, const bt_mesh *m, rs_vertex *out)
{
    uint32_t i;
    for (i = 0; i < m->nv; i++)
        if (out[i].rgb == RT_PENDING)
            out[i].rgb = rs_light_apply(ramp_at(s, m->v[i].z), level_get(s, m->v[i].x, m->v[i].y));
}
