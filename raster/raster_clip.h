/* raster/raster_clip.h — the clipper's polygon, shared by the band's draw (raster.c
 * tri_clip) and rs_frame_prepare's table of polygons (xform.c clip_table), so that both
 * make the same one; and that table's look-up.  Private to raster/: included by raster.c
 * and xform.c (test_raster_variants.c compiles both in one translation unit: the guard
 * keeps one copy). */
#ifndef BR_RASTER_CLIP_H
#define BR_RASTER_CLIP_H

/* The draw's outcode tests of a triangle's three vertices: all share a REJECT bit, no
 * pixel; one has a SLOW bit, the clipper (raster_draw.h strip_tri and the list loop;
 * xform.c clip_table picks the same triangles, less those of the world plane alone). */
#define REJECT ((uint32_t)(RS_OUT_LEFT | RS_OUT_RIGHT | RS_OUT_TOP | RS_OUT_BOTTOM | RS_OUT_FAR | RS_OUT_NEAR \
                              | RS_OUT_CLIPZ) << 24)
#define SLOW ((uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD | RS_OUT_CLIPZ) << 24)

typedef struct clipv {
    int64_t c[3];         /* camera space, world units */
    int32_t col[3];       /* 0..255 */
    int32_t uv[2];        /* texels Q8 */
    int64_t pz;           /* world z - clip_z (rs_frame.clip_z_on), affine like c */
} clipv;

/* Signed distance-like value of plane p (>= 0 inside): 0 near, 1..4 guard band, 5 the
 * world plane z >= clip_z. */
static int64_t plane_val(int p, const clipv *v, int64_t f8, int64_t g8, int64_t znear)
{
    const int64_t *c = v->c;
    switch (p) {
    case 5: return v->pz;
    case 0: return c[2] - znear;
    case 1: return g8 * c[2] + f8 * c[0];
    case 2: return g8 * c[2] - f8 * c[0];
    case 3: return g8 * c[2] + f8 * c[1];
    default: return g8 * c[2] - f8 * c[1];
    }
}

/* Point on P->Q where the plane value crosses 0, P inside (dp >= 0), Q outside (dq < 0).
 * Always computed from the inside end, so the two triangles sharing a clipped edge get
 * the same point. */
static void intersect(const clipv *P, const clipv *Q, int64_t dp, int64_t dq, int plane,
                      int64_t znear, int tex, clipv *o)
{
    int64_t num = dp, den = dp - dq, t;
    int k;
    while (den >= ((int64_t)1 << 31)) { num >>= 1; den >>= 1; }
    /* Q24, 0..1: 0 <= num <= den (dp >= 0 > dq), so 25 quotient bits */
#if BR_DIV64_NATIVE
    t = den ? (num << 24) / den : 0;
#else
    t = den ? fx_udiv_once((uint64_t)num << 24, (uint32_t)den) : 0;   /* (den < 2^31) */
#endif
    for (k = 0; k < 3; k++) o->c[k] = P->c[k] + (((Q->c[k] - P->c[k]) * t) >> 24);
    for (k = 0; k < 3; k++)
        o->col[k] = P->col[k] + (int32_t)((((int64_t)Q->col[k] - P->col[k]) * t) >> 24);
    for (k = 0; k < 2; k++)     /* read by the textured variants only */
        o->uv[k] = tex ? P->uv[k] + (int32_t)((((int64_t)Q->uv[k] - P->uv[k]) * t) >> 24) : 0;
    /* |pz| < 2^32 and t <= 2^24: the product fits */
    o->pz = plane == 5 ? 0 : P->pz + (((Q->pz - P->pz) * t) >> 24);
    if (plane == 0 || o->c[2] < znear) o->c[2] = znear;
}

/* Triangle (ia, ib, ic) of frame f with a vertex behind the near plane or outside the
 * guard band: clipped in camera space (Sutherland-Hodgman against the near plane and the
 * four guard-band planes: at most 3 + 5 = RS_CLIP_MAX vertices) and projected into sv;
 * returns the polygon's vertex count, 0 when fewer than three remain.  The outcodes are
 * exact (xform.c: RS_OUT_NEAR is plane 0's value < 0, RS_OUT_GUARD one of planes 1 ..
 * 4's): when no vertex has either, planes 0 .. 4 pass the three vertices unchanged, so
 * they are not evaluated and only plane 5 (the world plane: the reflection's shore
 * triangles) cuts, giving the same polygon.  A function of the frame and the ordered
 * triple alone (the band plays no part), so a polygon made once a frame (clip_table)
 * is the one every band would make. */
static int32_t clip_polygon(const rs_frame *f, uint32_t ia, uint32_t ib, uint32_t ic, rs_cvert sv[RS_CLIP_MAX])
{
    const cam_vp *vp = &f->vp;
    int64_t f8 = rsi_f_q8(vp), g8 = (int64_t)RS_GUARD_PX << 8;
    clipv buf[2][RS_CLIP_MAX];
    int32_t n = 3, p, i, k, cur = 0, nplanes = f->clip_z_on ? 6 : 5;
    const int tex = f->tex != 0;
    uint32_t idx[3];
    idx[0] = ia; idx[1] = ib; idx[2] = ic;
    p = (f->cache[ia].c | f->cache[ib].c | f->cache[ic].c) & ((uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD) << 24) ? 0 : 5;
    for (i = 0; i < 3; i++) {
        uint32_t rgb = f->v[idx[i]].rgb;
        rsi_to_camera(vp, f->v[idx[i]].p, buf[0][i].c);
        for (k = 0; k < 3; k++) buf[0][i].col[k] = (int32_t)((rgb >> (16 - 8 * k)) & 255);
#if RS_TEX_FIELDS
        buf[0][i].uv[0] = f->v[idx[i]].uv[0];
        buf[0][i].uv[1] = f->v[idx[i]].uv[1];
#else
        buf[0][i].uv[0] = buf[0][i].uv[1] = 0;
#endif
        buf[0][i].pz = (int64_t)f->v[idx[i]].p[2] - f->clip_z;
    }
    for (; p < nplanes; p++) {
        clipv *in = buf[cur], *out = buf[cur ^ 1];
        int32_t m = 0, all_in = 1;
        int64_t d[RS_CLIP_MAX];
        for (i = 0; i < n; i++) {
            d[i] = plane_val(p, &in[i], f8, g8, vp->znear);
            if (d[i] < 0) all_in = 0;
        }
        if (all_in) continue;
        for (i = 0; i < n; i++) {
            int32_t j = i + 1 == n ? 0 : i + 1;
            if (d[i] >= 0) out[m++] = in[i];
            if ((d[i] >= 0) != (d[j] >= 0)) {
                if (d[i] >= 0) intersect(&in[i], &in[j], d[i], d[j], p, vp->znear, tex, &out[m]);
                else intersect(&in[j], &in[i], d[j], d[i], p, vp->znear, tex, &out[m]);
                m++;
            }
        }
        n = m;
        cur ^= 1;
        if (n < 3) return 0;
    }
    for (i = 0; i < n; i++) {
        const clipv *v = &buf[cur][i];
        rsi_project(vp, f8, v->c, f->w, f->h, &sv[i]);
        sv[i].c = ((uint32_t)v->col[0] << 16) | ((uint32_t)v->col[1] << 8) | (uint32_t)v->col[2];
        sv[i].cp = rsi_pack_rgb(sv[i].c);
#if RS_TEX_FIELDS
        sv[i].u = v->uv[0]; sv[i].v = v->uv[1];
#endif
    }
    return n;
}

/* The clip table (rs_frame.clips, clip_cap entries, a power of two): open addressing
 * from a hash of the ordered triple.  rs_frame_prepare empties it before it fills it, so
 * an entry is this frame's when its owner is the frame: a table that another frame
 * filled since only misses. */
static inline uint32_t clip_slot(uint32_t ia, uint32_t ib, uint32_t ic, uint32_t mask)
{
    return ((ia * 2654435761u) ^ (ib * 2246822519u) ^ (ic * 3266489917u)) >> 7 & mask;
}

static inline int clip_mine(const rs_frame *f, const rs_clip_poly *e)
{
    return e->owner == f;
}

/* The polygon of (ia, ib, ic) in f's table, or NULL (not there: the band clips it) */
static inline const rs_clip_poly *clip_find(const rs_frame *f, uint32_t ia, uint32_t ib, uint32_t ic)
{
    const uint32_t mask = f->clip_cap - 1;
    uint32_t h = clip_slot(ia, ib, ic, mask), k;
    for (k = 0; k <= mask; k++, h = (h + 1) & mask) {
        const rs_clip_poly *e = &f->clips[h];
        if (!clip_mine(f, e)) return NULL;
        if (e->ia == ia && e->ib == ib && e->ic == ic) return e;
    }
    return NULL;
}

#endif
