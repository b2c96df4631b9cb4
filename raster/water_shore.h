/* raster/water_shore.h — which water-pass pixels are water where the terrain and the
 * water plane meet (raster/water.c's water_shows): the shore test (the terrain's point
 * on a pixel's ray wet with the body: the LOD over water), the tested quads' cells
 * (plane_cell) and the land test (the plane's point over dry land: the LOD sank land).
 * Private to raster/water.c, included once, after rw_rowk and rw_walk; its per-pixel
 * look-ups use the frame's grid position and its reciprocals (rw_frame: gx0, gy0, inv_sx,
 * inv_sy). */
#ifndef BR_RWATER_SHORE_H
#define BR_RWATER_SHORE_H

/* Depths (buffer units) this close are a tie: the terrain lies at the water's surface
 * within the depth buffer's resolution (a near plane far below the distance, as in the
 * viewer's fly camera, leaves metres a unit far away), and which is nearer is decided by
 * whether the water plane's point on the pixel's ray is wet, not by the rounding. */
#define RW_DEPTH_TIE 2u

#if RW_MUL32
/* p f mod 2^64 for 0 <= f < 2^32: p's low word times f (one 32 x 32 -> 64-bit multiply)
 * plus its high word times f (one 32-bit multiply), shifted */
static inline int64_t mul64_u32(int64_t p, uint32_t f)
{
    const uint64_t lo = (uint64_t)(uint32_t)p * f, hi = (uint32_t)((uint64_t)p >> 32) * f;
    return (int64_t)(lo + (hi << 32));
}
#endif

/* The point P = E + (P_0 - E) f >> 16 on pixel (x, k->y)'s ray (P_0 the reflected plane's
 * point, f in Q16) as a grid position in world units plus half a step: *gx east from
 * column 0, *gy south from row 0. */
static RW_INLINE void grid_pos(const rw_frame *r, const rw_rowk *k, int32_t x, int64_t f, int64_t *gx, int64_t *gy)
{
#if RW_MUL32
    /* the same products from 32-bit multiplies (three make a 64 x 64-bit one here): aq
     * times ws in one when ws fits 32 bits (k->ws32, kept as int32 fields, which the
     * compiler cannot fold back into the 64-bit product); p f by mul64_u32 (0 <= f < 2^21) */
    const int32_t a = r->aq[x];
    const int64_t p0 = k->wrel0 + ((k->ws32 ? (int64_t)a * k->ws0_32 : (int64_t)a * k->ws0) >> 12);
    const int64_t p1 = k->wrel1 + ((k->ws32 ? (int64_t)a * k->ws1_32 : (int64_t)a * k->ws1) >> 12);
    *gx = r->gx0 + (mul64_u32(p0, (uint32_t)f) >> 16);
    *gy = r->gy0 - (mul64_u32(p1, (uint32_t)f) >> 16);
#else
    *gx = r->gx0 + (((k->wrel0 + (((int64_t)r->aq[x] * k->ws0) >> 12)) * f) >> 16);
    *gy = r->gy0 - (((k->wrel1 + (((int64_t)r->aq[x] * k->ws1) >> 12)) * f) >> 16);
#endif
}

/* Grid position g (0 <= g < gxmax or gymax) times the reciprocal inv of a step, >> 32: the
 * sample or cell index.  On 32-bit targets one 32 x 32-bit multiply when both fit 32
 * bits (r->idx32), as they do unless the world frame is beyond 2^32 units. */
static RW_INLINE size_t grid_index(const rw_frame *r, int64_t g, uint64_t inv)
{
#if RW_MUL32
    if (r->idx32) return (size_t)(((uint64_t)(uint32_t)g * (uint32_t)inv) >> 32);
#else
    (void)r;
#endif
    return (size_t)(((uint64_t)g * inv) >> 32);
}

/* 1 when the grid sample nearest that point is wet with body id; 0 otherwise, or when the
 * point lies off the grid.  For a row with a plane point for the shore test (k->shore). */
static RW_INLINE int wet_at(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id, int64_t f)
{
    int64_t gx, gy;
    size_t ix, iy;
    grid_pos(r, k, x, f, &gx, &gy);
    if ((uint64_t)gx >= r->gxmax || (uint64_t)gy >= r->gymax) return 0;       /* negative: huge */
    ix = grid_index(r, gx, r->inv_sx);     /* < wet_w, as gx < gxmax (grid_max) */
    iy = grid_index(r, gy, r->inv_sy);     /* < wet_h */
    return r->p.wet[iy * (size_t)r->p.wet_w + ix] == id;
}

/* The terrain's point on the ray for shore_wet: bratio dw / dt (Q16, below 2^21 as
 * bratio is), dw / dt from the depths brought to 16 bits (sh the smallest with
 * dt >> sh < 2^16; a 32-bit division), for dt > dw >= 1 (so dt >> sh >= 1).  With
 * RW_SOFT_DIV by fx_udiv_short (the same floor: dw >> sh <= dt >> sh, so the quotient
 * is at most 2^16). */
static inline int64_t shore_point(int32_t bratio, uint32_t dt, uint32_t dw)
{
    const int32_t sh = dt >= 65536u ? 16 - fx_clz32(dt) : 0;
#if RW_SOFT_DIV
    return ((int64_t)bratio * fx_udiv_short((dw >> sh) << 16, dt >> sh)) >> 16;
#else
    return ((int64_t)bratio * (((dw >> sh) << 16) / (dt >> sh))) >> 16;
#endif
}

/* The shore test for water pixel (x, y) of body id whose terrain is nearer (dt > dw): 1
 * when the terrain's point on the pixel's ray lies on a sample wet with that body (the
 * terrain LOD over flattened water), 0 otherwise (land, or no plane point for the row).
 * P_t = E + (P_0 - E) bratio dw / dt, P_0 the reflected plane's point (shore_point); the
 * grid sample nearest P_t.  Called only where k->sdd[id] is not 0 (water_shows), so with
 * k->shore and bratio[id] set, and with dt > dw >= 1. */
static RW_INLINE int shore_wet(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id, uint32_t dt, uint32_t dw)
{
    return wet_at(r, k, x, id, shore_point(r->bratio[id], dt, dw));
}

/* The shore test at the plane's own point: shore_wet with dt = dw, whose quotient q is
 * then 2^16 (f = bratio) for any nonzero dw. */
static RW_INLINE int plane_wet(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id)
{
    return k->shore && r->bratio[id] && wet_at(r, k, x, id, r->bratio[id]);
}

/* The grid cell under the plane's point on pixel (x, k->y)'s ray for body id (with
 * bratio[id] set): 1, with its north-west corner (*ix, *iy) (rows run south) and the
 * point's own grid position (*gx east, *gy south, world units), when the whole cell lies
 * on the grid; 0 otherwise. */
static RW_INLINE int plane_cell_of(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id, size_t *ix, size_t *iy,
                                   int64_t *gx, int64_t *gy)
{
    grid_pos(r, k, x, r->bratio[id], gx, gy);
    *gx -= r->half_sx;               /* the point's own grid position */
    *gy -= r->half_sy;
    if (*gx < 0 || *gy < 0 || (uint64_t)*gx >= r->gxmax || (uint64_t)*gy >= r->gymax) return 0;
    *ix = grid_index(r, *gx, r->inv_sx);
    *iy = grid_index(r, *gy, r->inv_sy);
    return *ix + 1 < (size_t)r->p.wet_w && *iy + 1 < (size_t)r->p.wet_h;
}

/* Sample i of the land test's grid is dry land at or above level zl (the heightfield's
 * units): not wet, not a void, not below it (a pocket under the plane stays water, as
 * the full grid draws it). */
static inline int land_sample(const rw_frame *r, size_t i, int32_t zl)
{
    const int32_t z = r->p.land->f->z[i];
    return !r->p.wet[i] && z != HF_NODATA && z >= zl;
}

/* texel t times lighting c per channel, / 255 rounded: a textured pixel's colour, as
 * raster.c's tex_mod makes it (fx_mul255) */
static inline uint32_t texel_lit(uint32_t t, uint32_t c)
{
    uint32_t out = 0, sh;
    for (sh = 0; sh <= 16; sh += 8) out |= fx_mul255((t >> sh) & 255u, (c >> sh) & 255u) << sh;
    return out;
}

/* The texel of land_tex at grid position (gx east, gy south, world units, >= 0 and below
 * gxmax, gymax: below 2^47 after the multiply, as a position is at most w sx and inv_tu
 * at most tex_w 2^32 / ((w - 1) sx)), nearest, clamped to the edge as the rasteriser's. */
static inline uint32_t land_texel(const rw_frame *r, int64_t gx, int64_t gy)
{
    const rs_texture *t = r->p.land_tex;
    uint64_t u = ((uint64_t)gx * r->inv_tu) >> 32, v = ((uint64_t)gy * r->inv_tv) >> 32;
    if (u >= (uint64_t)t->w) u = (uint64_t)t->w - 1;
    if (v >= (uint64_t)t->h) v = (uint64_t)t->h - 1;
    return t->px[(size_t)v * (size_t)t->w + (size_t)u] & 0xffffffu;
}

/* Cell (ix, iy) passes the land test for body id: its four corners are dry land at or
 * above the body's level (land_sample). */
static RW_INLINE int land_cell(const rw_frame *r, size_t ix, size_t iy, uint32_t id)
{
    const size_t w = (size_t)r->p.wet_w, i = iy * w + ix;
    const int32_t zl = r->p.land_z[id];
    return land_sample(r, i, zl) && land_sample(r, i + 1, zl) && land_sample(r, i + w, zl)
           && land_sample(r, i + w + 1, zl);
}

/* The land test (rw_params.land) at the plane's own point: 1, with the sample nearest it
 * in *lx, *ly, when the four corners of the grid cell under the point are dry land at or
 * above body id's plane (land_sample): there the terrain at full resolution lies above
 * the plane, whatever the LOD drew, and a cell with another corner keeps the geometry's
 * shore (the plane shows where the drawn terrain lies under it, as nearer).  0
 * otherwise, or off the grid.  For a row with a plane point (k->shore) and a body with
 * bratio[id] set, as the shore test's k->sdd promises. */
static RW_INLINE int land_at(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id, int32_t *lx, int32_t *ly)
{
    int64_t gx, gy;
    size_t ix, iy;
    if (!plane_cell_of(r, k, x, id, &ix, &iy, &gx, &gy) || !land_cell(r, ix, iy, id)) return 0;
    *lx = (int32_t)ix + (2 * (gx - (int64_t)ix * r->p.grid_sx) >= r->p.grid_sx);
    *ly = (int32_t)iy + (2 * (gy - (int64_t)iy * r->p.grid_sy) >= r->p.grid_sy);
    return 1;
}

/* The land test's gate (water_shows with a row walk, water_row_vec's groups): the run of
 * RW_LAND_RUN pixels from x (to the frame's last column) of body id into wk (its last
 * column lx1, body lid), with lskip 1 when no pixel of it passes land_at.  Along a row the
 * plane's point moves monotonically in both grid axes (grid_pos: aq[x] does not decrease
 * with x, and a product with one factor fixed, a floor and grid_index keep that order),
 * so the cell of every pixel between lies in the box of the run's two end cells; when
 * no cell of the box passes the land test (land_cell), none of the run's pixels does.
 * Ends off the grid, or a box of more than RW_LAND_CELLS cells (far away, where a pixel
 * spans many cells), leave lskip 0: each pixel is tested. */
#define RW_LAND_RUN 32
#define RW_LAND_CELLS 64
static RW_NOINLINE void land_gate(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id, rw_walk *wk)
{
    const int32_t xb = x + RW_LAND_RUN - 1 < r->w - 1 ? x + RW_LAND_RUN - 1 : r->w - 1;
    size_t ia, ja, ib, jb, x0, x1, y0, y1, cx, cy;
    int64_t gx, gy;
    wk->lx1 = xb; wk->lid = id; wk->lskip = 0;
    if (!plane_cell_of(r, k, x, id, &ia, &ja, &gx, &gy) || !plane_cell_of(r, k, xb, id, &ib, &jb, &gx, &gy))
        return;
    x0 = ia < ib ? ia : ib; x1 = ia < ib ? ib : ia;
    y0 = ja < jb ? ja : jb; y1 = ja < jb ? jb : ja;
    if ((x1 - x0 + 1) * (y1 - y0 + 1) > RW_LAND_CELLS) return;
    for (cy = y0; cy <= y1; cy++)
        for (cx = x0; cx <= x1; cx++)
            if (land_cell(r, cx, cy, id)) return;
    wk->lskip = 1;
}

/* The colour of pixel (x, k->y) that land_at made land, with its sample (lx, ly): the
 * sample's lit colour (rt_sample_rgb), under a texture its lighting times the texel at the
 * plane's point (found again: land pixels are few, and out of line the water pixels'
 * loop keeps its registers). */
static RW_COLD uint32_t land_rgb(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id, int32_t lx,
                                 int32_t ly)
{
    const uint32_t rgb = rt_sample_rgb(r->p.land, lx, ly);
    int64_t gx = 0, gy = 0;
    size_t ix, iy;
    if (!r->inv_tu) return rgb;
    (void)plane_cell_of(r, k, x, id, &ix, &iy, &gx, &gy);      /* 1, as land_at found */
    return texel_lit(land_texel(r, gx, gy), rgb);
}

/* A cell corner of sample j, wet with v, passes the split mesh's rule (emit_cell) for body
 * id: wet with the body, or dry and not low. */
static inline uint32_t corner_passes(uint32_t v, uint32_t id, const uint8_t *low, size_t j)
{
    return v == id || (!v && !(low && low[j]));
}

/* A tested triangle's pixel (x, k->y) of body id: 1 when the plane's point on its ray lies
 * where the exact mesh would have a triangle (emit_cell, platform/water_mesh.c): in a grid
 * cell with a corner wet with the body, in that cell's half (split along its south-west /
 * north-east diagonal) whose three corners are wet with the body or dry and not low
 * (rw_params.low).  So a tested quad shows water where the cells along the shore would. */
static RW_INLINE int plane_cell(const rw_frame *r, const rw_rowk *k, int32_t x, uint32_t id)
{
    const int64_t sx = r->p.grid_sx, sy = r->p.grid_sy;
    const uint8_t *wet = r->p.wet, *low = r->p.low;
    int64_t gx, gy, fx, fy;
    size_t ix, iy, i, w = (size_t)r->p.wet_w;
    uint32_t nw, ne, sw, se, ok;
    if (!k->shore || !r->bratio[id] || !plane_cell_of(r, k, x, id, &ix, &iy, &gx, &gy)) return 0;
    i = iy * w + ix;
    nw = wet[i]; ne = wet[i + 1]; sw = wet[i + w]; se = wet[i + w + 1];
    if ((nw & ne & sw & se) == id && (nw | ne | sw | se) == id) return 1;     /* inside the water */
    if (nw != id && ne != id && sw != id && se != id) return 0;
    /* which corners pass (4 bits: nw ne sw se) */
    ok = corner_passes(nw, id, low, i) | corner_passes(ne, id, low, i + 1) << 1
         | corner_passes(sw, id, low, i + w) << 2 | corner_passes(se, id, low, i + w + 1) << 3;
    /* the south-east half (sw se ne) where fx / sx + fy / sy >= 1, fx, fy the offsets
     * from the north-west corner, in world units (|fx| sy < 2^31 2^31: int64) */
    fx = gx - (int64_t)ix * sx;
    fy = gy - (int64_t)iy * sy;
    return fx * sy + fy * sx >= sx * sy ? (ok & 14u) == 14u : (ok & 7u) == 7u;
}

#endif
