/* platform/water_mesh.c — the water surfaces' mesh, built once per scene (see
 * water_scene.h, wm_build).
 *
 * A quadtree of grid blocks per body: aligned blocks of s x s cells (s a power of two,
 * corners x0 .. x0 + s, y0 .. y0 + s inclusive) from one block covering the grid.  A
 * block is CLEAN for body b when
 *   - it holds at least one sample wet with b,
 *   - every wet sample in it lies at b's level (flat), and
 *   - every other sample in it lies inside the grid, is valid and is dry land at or above
 *     b's level (the terrain pass draws that land above the plane, so it hides the part
 *     of the block under it by the depth test; terrain under the water was lowered), or
 *     dry land below the level enclosed by such land (a pocket, reach_low: where the
 *     terrain's LOD keeps it, the plane shows as shallow water over it; where the LOD
 *     sinks the island around it, the plane covers it as it covers the island);
 * a clean block is one quad at b's level, and a block that holds water of b but is not
 * clean is split into its four children, unless it is TESTED (WM_TESTED_S below: small,
 * and only a few low or void samples fail), one quad whose pixels the post hook tests.
 * A single cell that is not clean keeps those of its two triangles (split along the
 * south-west / north-east diagonal) whose three corners pass the rule above, at the
 * corners' own heights (wet: the surface height, dry: the level).  A cell with corners of
 * two bodies belongs to ONE of them, the lower (the larger, lower id, at equal levels;
 * under()): its corners on the higher body's samples pass at that body's surface height,
 * so the cell slopes from one surface to the other and shares the higher body's edge, and
 * the higher body skips the cell.  Blocks meet along their edges with T-junctions where a
 * block meets smaller ones; to keep the mesh watertight (no pixel gaps along a T-junction
 * after snapping), a block whose edges carry corners of smaller blocks of the same body is
 * drawn as a fan around its centre through every such corner.  So a lake whose shore
 * rises is a few dozen quads; the mesh only refines where water meets land below its
 * level (an outlet; where such land is little, one tested block), another body or the grid's
 * edge.
 *
 * Cost: the classification visits every cell once per body (bottom-up), the fans walk
 * every block's edges once. */
#include <stdlib.h>
#include <string.h>
#include "platform/water_scene.h"

typedef struct wm_ctx {
    const hf *f;
    const uint8_t *id;
    const int32_t *wz;
    const int32_t *levels;      /* level of body b at levels[b - 1] */
    uint8_t *low;               /* per sample: 1 for dry land below the level that the body's
                                   water or the grid's edge reaches (reach_low) */
    uint8_t body;
    int32_t level;
    int32_t tested_s;           /* the largest tested block's side (WM_TESTED_S by default) */
    int32_t (*leaf)[3];         /* x0, y0, s; s negated: a cell that is not clean;
                                   s + WM_LEAF_TESTED: a tested block */
    size_t nleaf, capleaf;
    int oom;
} wm_ctx;

/* WM_EDGE, WM_LOW and WM_SLOPE say why a sample fails (with WM_FAIL): beyond the grid;
 * dry land the plane may not cover (reach_low) or a void; wet but not at the level. */
enum { WM_WET = 1, WM_FAIL = 2, WM_ABOVE = 4, WM_BELOW = 8, WM_EDGE = 16, WM_LOW = 32, WM_SLOPE = 64 };

/* The largest TESTED block: a block of at most WM_TESTED_S cells a side whose samples
 * fail only as low land or voids (WM_LOW), at most one in WM_TESTED_LOW of them, is one
 * quad at the level whose pixels the post hook keeps only where the plane's point on the
 * pixel's ray lies in a half cell emit_cell would keep (raster/water.h, RW_TESTED_RGB;
 * wm_mesh.low marks the block's low samples), instead of a quadtree down to single cells
 * along the low shore, whose cells cover less than a pixel from afar.  The bounds keep
 * the tested pixels few near the camera, where each costs the hook its look-ups
 * (docs/water.md). */
#define WM_TESTED_S 32
#define WM_TESTED_LOW 4
#define WM_LEAF_TESTED (1 << 24)    /* added to a tested leaf's size (sizes < 2^15) */

/* Whether body a's plane goes on under body b's samples in a cell they share: the lower
 * body takes the cell (its plane lies under the higher body's surface there, so it hides
 * no water of the other; the higher body's plane over the lower body's samples would
 * stand above their surface), the larger body (lower id) at equal levels.  A total order,
 * so every cell between two bodies has exactly one owner. */
static int under(const wm_ctx *c, uint8_t a, uint8_t b)
{
    const int32_t la = c->levels[a - 1], lb = c->levels[b - 1];
    return la < lb || (la == lb && a < b);
}

/* WM_WET when (x, y) is wet with the body at its level, WM_WET | WM_FAIL | WM_SLOPE when
 * wet but not at the level (a --water layer that is not flat), WM_ABOVE when wet with a
 * body above this one (under(): the cells between them are this body's, larger blocks are
 * not), WM_FAIL | WM_BELOW when wet with a body under this one (the cells between them are
 * that body's), WM_FAIL | WM_LOW when it may not lie under the body's plane, WM_FAIL |
 * WM_EDGE beyond the grid, 0 for dry land at or above the level. */
static int sample_bits(const wm_ctx *c, int32_t x, int32_t y)
{
    size_t i;
    if (x >= c->f->w || y >= c->f->h) return WM_FAIL | WM_EDGE;
    i = (size_t)y * (size_t)c->f->w + (size_t)x;
    if (c->id[i] == c->body) return c->wz[i] == c->level ? WM_WET : WM_WET | WM_FAIL | WM_SLOPE;
    if (c->id[i]) return under(c, c->body, c->id[i]) ? WM_ABOVE : WM_FAIL | WM_BELOW;
    if (c->f->z[i] == HF_NODATA || c->low[i]) return WM_FAIL | WM_LOW;
    return 0;
}

static int dry_below(const wm_ctx *c, size_t i)
{
    return !c->id[i] && c->f->z[i] != HF_NODATA && c->f->z[i] < c->level;
}

/* c->low: dry land below the level 4-connected through such land to water (of any body)
 * or to the grid's edge (an outlet, a valley beyond the shore, a coast): the plane may
 * not go over it.  Dry land below the level enclosed by land at or above it (a pocket: SRTM's -1 and
 * -2 m in Laesoe's marshes, N57E011) may lie under the plane like the land around it;
 * left out, it was a hole in the water where the terrain's LOD, which sinks a low island
 * into the lowered sea bottom, showed the bottom.  q: a queue of w * h entries. */
static void reach_low(wm_ctx *c, uint32_t *q)
{
    const int32_t w = c->f->w, h = c->f->h;
    size_t head = 0, tail = 0;
    int32_t x, y;
    memset(c->low, 0, (size_t)w * (size_t)h);
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            const size_t i = (size_t)y * (size_t)w + (size_t)x;
            if (!dry_below(c, i)) continue;
            if (x == 0 || y == 0 || x == w - 1 || y == h - 1
                || c->id[i - 1] || c->id[i + 1] || c->id[i - (size_t)w] || c->id[i + (size_t)w]) {
                c->low[i] = 1;
                q[tail++] = (uint32_t)i;
            }
        }
    while (head < tail) {
        const size_t j = q[head++];
        const int32_t jx = (int32_t)(j % (size_t)w), jy = (int32_t)(j / (size_t)w);
        size_t nb[4];
        int k, nn = 0;
        if (jx > 0) nb[nn++] = j - 1;
        if (jx + 1 < w) nb[nn++] = j + 1;
        if (jy > 0) nb[nn++] = j - (size_t)w;
        if (jy + 1 < h) nb[nn++] = j + (size_t)w;
        for (k = 0; k < nn; k++)
            if (!c->low[nb[k]] && dry_below(c, nb[k])) { c->low[nb[k]] = 1; q[tail++] = (uint32_t)nb[k]; }
    }
}

static void push_leaf(wm_ctx *c, int32_t x0, int32_t y0, int32_t s)
{
    if (c->nleaf == c->capleaf) {
        size_t cap = c->capleaf ? 2 * c->capleaf : 256;
        void *p = realloc(c->leaf, cap * sizeof *c->leaf);
        if (!p) { c->oom = 1; return; }
        c->leaf = (int32_t (*)[3])p;
        c->capleaf = cap;
    }
    c->leaf[c->nleaf][0] = x0; c->leaf[c->nleaf][1] = y0; c->leaf[c->nleaf][2] = s;
    c->nleaf++;
}

/* The samples of block (x0, y0, s) that fail as low land or voids. */
static int32_t low_samples(const wm_ctx *c, int32_t x0, int32_t y0, int32_t s)
{
    int32_t x, y, n = 0;
    for (y = y0; y <= y0 + s; y++)
        for (x = x0; x <= x0 + s; x++) n += (sample_bits(c, x, y) & WM_LOW) != 0;
    return n;
}

/* The block's bits (OR over its samples); its leaves appended to c->leaf. */
static int classify(wm_ctx *c, int32_t x0, int32_t y0, int32_t s)
{
    size_t mark = c->nleaf;
    int bits;
    if (x0 >= c->f->w || y0 >= c->f->h) return WM_FAIL;
    if (s == 1) {
        bits = sample_bits(c, x0, y0) | sample_bits(c, x0 + 1, y0) | sample_bits(c, x0, y0 + 1)
               | sample_bits(c, x0 + 1, y0 + 1);
        if (bits & WM_WET) push_leaf(c, x0, y0, bits == WM_WET ? 1 : -1);
        return bits;
    }
    s /= 2;
    bits = classify(c, x0, y0, s) | classify(c, x0 + s, y0, s) | classify(c, x0, y0 + s, s)
           | classify(c, x0 + s, y0 + s, s);
    if (bits == WM_WET) {
        c->nleaf = mark;
        push_leaf(c, x0, y0, 2 * s);
    } else if (2 * s <= c->tested_s && (bits & WM_WET) && !(bits & ~(WM_WET | WM_FAIL | WM_LOW))
               && low_samples(c, x0, y0, 2 * s) * WM_TESTED_LOW <= (2 * s + 1) * (2 * s + 1)) {
        c->nleaf = mark;
        push_leaf(c, x0, y0, 2 * s + WM_LEAF_TESTED);
    }
    return bits;
}

typedef struct wm_out {
    wm_mesh *m;
    size_t capv, capi;
    int32_t *vmap;              /* per sample: vertex index of this body, -1 none */
    int oom;
} wm_out;

static int32_t add_vert(wm_out *o, int32_t x, int32_t y, int32_t z, uint8_t body, uint8_t tested)
{
    wm_mesh *m = o->m;
    if (m->nv == o->capv) {
        size_t cap = o->capv ? 2 * o->capv : 1024;
        void *p = realloc(m->v, cap * sizeof *m->v);
        if (!p) { o->oom = 1; return 0; }
        m->v = (wm_vert *)p;
        o->capv = cap;
    }
    m->v[m->nv].x = x; m->v[m->nv].y = y; m->v[m->nv].z = z; m->v[m->nv].id = body;
    m->v[m->nv].tested = tested;
    return (int32_t)m->nv++;
}

static void add_tri(wm_out *o, int32_t a, int32_t b, int32_t c)
{
    wm_mesh *m = o->m;
    if (m->nidx + 3 > o->capi) {
        size_t cap = o->capi ? 2 * o->capi : 3072;
        void *p = realloc(m->idx, cap * sizeof *m->idx);
        if (!p) { o->oom = 1; return; }
        m->idx = (uint32_t *)p;
        o->capi = cap;
    }
    m->idx[m->nidx++] = (uint32_t)a; m->idx[m->nidx++] = (uint32_t)b; m->idx[m->nidx++] = (uint32_t)c;
}

/* The vertex of sample (x, y) for the body (made on first use): a wet sample at its own
 * surface height (of this body, or of a body above it in a cell between the two: the cell
 * slopes from one surface to the other, and its edge on the higher body's samples is that
 * body's edge, so no gap opens along the step), dry land at the body's level. */
static int32_t corner(wm_out *o, const wm_ctx *c, int32_t x, int32_t y)
{
    const size_t i = (size_t)y * (size_t)c->f->w + (size_t)x;
    if (o->vmap[i] < 0) o->vmap[i] = add_vert(o, x, y, c->id[i] ? c->wz[i] : c->level, c->body, 0);
    return o->vmap[i];
}

/* A cell that is not clean: its triangles whose corners all pass. */
static void emit_cell(wm_out *o, const wm_ctx *c, int32_t x0, int32_t y0)
{
    /* sw, se, ne, nw in grid rows (row y0 + 1 is south of y0) */
    const int32_t cx[4] = { x0, x0 + 1, x0 + 1, x0 }, cy[4] = { y0 + 1, y0 + 1, y0, y0 };
    int ok[4], k;
    for (k = 0; k < 4; k++) {
        const int bits = sample_bits(c, cx[k], cy[k]);
        if (bits & WM_BELOW) return;        /* the cell of a body under this one */
        ok[k] = !(bits & WM_FAIL) || (bits & WM_WET);
    }
    /* counter-clockwise seen from +z (x east, y north): sw se ne, sw ne nw */
    if (ok[0] && ok[1] && ok[2])
        add_tri(o, corner(o, c, cx[0], cy[0]), corner(o, c, cx[1], cy[1]), corner(o, c, cx[2], cy[2]));
    if (ok[0] && ok[2] && ok[3])
        add_tri(o, corner(o, c, cx[0], cy[0]), corner(o, c, cx[2], cy[2]), corner(o, c, cx[3], cy[3]));
}

/* A clean or tested block: two triangles, or a fan around its centre through every
 * corner of a smaller block of the body on its edges (counter-clockwise from +z: the
 * south edge west to east, the east edge south to north, the north edge east to west,
 * the west edge north to south).  A tested block's triangles get their own vertices,
 * flagged, at the same grid points (so the same screen points: still no gaps). */
static void emit_block(wm_out *o, const wm_ctx *c, int32_t x0, int32_t y0, int32_t s, int tested, int32_t *loop)
{
    int32_t n = 0, t, k, ctr;
    for (k = 0; k < 4; k++)
        for (t = 0; t < s; t++) {
            const int32_t x = k == 0 ? x0 + t : k == 1 ? x0 + s : k == 2 ? x0 + s - t : x0;
            const int32_t y = k == 0 ? y0 + s : k == 1 ? y0 + s - t : k == 2 ? y0 : y0 + t;
            const int32_t v = o->vmap[(size_t)y * (size_t)c->f->w + (size_t)x];
            if (v >= 0) loop[n++] = v;
        }
    if (tested)
        for (k = 0; k < n && !o->oom; k++) {
            const wm_vert a = o->m->v[loop[k]];
            loop[k] = add_vert(o, a.x, a.y, a.z, a.id, 1);
        }
    if (o->oom) return;
    if (n == 4) {
        add_tri(o, loop[0], loop[1], loop[2]);
        add_tri(o, loop[0], loop[2], loop[3]);
        return;
    }
    ctr = add_vert(o, x0 + s / 2, y0 + s / 2, c->level, c->body, (uint8_t)tested);
    for (k = 0; k < n; k++) add_tri(o, ctr, loop[k], loop[(k + 1) % n]);
}

/* The body's samples that are corners of cells a body under it takes (under()): vertices
 * made before the fans, so the body's blocks pass through them and the sloping cells
 * meet them without T-junctions. */
static void step_corners(wm_out *o, const wm_ctx *c, int32_t nbodies)
{
    const int32_t w = c->f->w, h = c->f->h;
    int32_t x, y, dx, dy, b, any = 0;
    for (b = 1; b <= nbodies; b++) any |= b != c->body && under(c, (uint8_t)b, c->body);
    if (!any) return;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            int found = 0;
            if (c->id[(size_t)y * (size_t)w + (size_t)x] != c->body) continue;
            for (dy = -1; dy <= 1 && !found; dy++)
                for (dx = -1; dx <= 1 && !found; dx++) {
                    uint8_t nid;
                    if (x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= h) continue;
                    nid = c->id[(size_t)(y + dy) * (size_t)w + (size_t)(x + dx)];
                    found = nid && nid != c->body && under(c, nid, c->body);
                }
            if (found) corner(o, c, x, y);
        }
}

br_status wm_build(const hf *f, const uint8_t *id, const int32_t *wz, const int32_t *level, int32_t nbodies,
                   int32_t tested_s, wm_mesh *m)
{
    const size_t n = (size_t)f->w * (size_t)f->h;
    wm_ctx c;
    wm_out o;
    int32_t S = 1, b, *loop = NULL;
    size_t i, l;
    memset(m, 0, sizeof *m);
    memset(&c, 0, sizeof c);
    memset(&o, 0, sizeof o);
    o.m = m;
    o.vmap = malloc(n * sizeof *o.vmap);
    c.low = malloc(n);
    while (S < f->w - 1 || S < f->h - 1) S *= 2;
    loop = malloc(((size_t)4 * (size_t)S + 4) * sizeof *loop);
    if (!o.vmap || !loop || !c.low) { free(o.vmap); free(loop); free(c.low); return BR_E_NOMEM; }
    c.f = f; c.id = id; c.wz = wz; c.levels = level;
    c.tested_s = tested_s > 0 ? tested_s : WM_TESTED_S;
    for (b = 1; b <= nbodies; b++) {
        c.body = (uint8_t)b;
        c.level = level[b - 1];
        c.nleaf = 0;
        if (f->w < 2 || f->h < 2) break;
        reach_low(&c, (uint32_t *)(void *)o.vmap);     /* the queue: vmap is set below */
        classify(&c, 0, 0, S);
        if (c.oom) break;
        for (l = 0; l < c.nleaf; l++) {    /* tested leaves: their body's low land and voids */
            const int32_t x0 = c.leaf[l][0], y0 = c.leaf[l][1], s = c.leaf[l][2] - WM_LEAF_TESTED;
            int32_t x, y;
            if (s < 0) continue;
            if (!m->low && !(m->low = calloc(n, 1))) { c.oom = 1; break; }
            for (y = y0; y <= y0 + s && y < f->h; y++)
                for (x = x0; x <= x0 + s && x < f->w; x++) {
                    const size_t j = (size_t)y * (size_t)f->w + (size_t)x;
                    m->low[j] |= c.low[j] || f->z[j] == HF_NODATA;
                }
        }
        if (c.oom) break;
        for (i = 0; i < n; i++) o.vmap[i] = -1;
        /* every block's corners first, so that the fans see their neighbours' */
        for (l = 0; l < c.nleaf; l++) {
            const int32_t x0 = c.leaf[l][0], y0 = c.leaf[l][1], s = c.leaf[l][2] % WM_LEAF_TESTED;
            if (s < 0) continue;
            corner(&o, &c, x0, y0); corner(&o, &c, x0 + s, y0);
            corner(&o, &c, x0, y0 + s); corner(&o, &c, x0 + s, y0 + s);
        }
        step_corners(&o, &c, nbodies);
        for (l = 0; l < c.nleaf; l++)
            if (c.leaf[l][2] < 0) emit_cell(&o, &c, c.leaf[l][0], c.leaf[l][1]);
        for (l = 0; l < c.nleaf; l++)
            if (c.leaf[l][2] > 0)
                emit_block(&o, &c, c.leaf[l][0], c.leaf[l][1], c.leaf[l][2] % WM_LEAF_TESTED,
                           c.leaf[l][2] >= WM_LEAF_TESTED, loop);
        if (o.oom) break;
    }
    free(c.leaf); free(o.vmap); free(loop); free(c.low);
    if (c.oom || o.oom) { wm_free(m); return BR_E_NOMEM; }
    return BR_OK;
}

void wm_free(wm_mesh *m)
{
    free(m->v); free(m->idx); free(m->low);
    memset(m, 0, sizeof *m);
}
