/* core/bt_stream.c — the view selection streamed to a callback, one window of the
 * screen at a time, without a mesh (contract: core/bitree.h "streamed walk").
 *
 * The walk is core/bt_mesh.c's rec with the view rule (decide): the same diamonds
 * split, the same geomorph heights (bti_mid_z), the same leaves in the same order (or,
 * asked, back to front: near_is_a).  What it leaves out is the output: no vertex array,
 * no strip, no vertex hash, no split list.  Each leaf goes to the caller as its three
 * grid points.  What it keeps is the frame's
 * answers (decide below), so that the walks of a frame decide each diamond about once.
 *
 * Why no hysteresis.  A split's answer depends on ST_PREV only through tau_lo; with
 * hyst_q8 = 0 (tau_lo = tau) the rule reads the diamond and the camera alone, so every
 * walk of a frame, whatever its window, gives every diamond the same answer, and the
 * union of the walks' leaves is one conforming mesh (the rule splits a set closed under
 * "parent of": monotone errors and nested volumes, bt_mesh.c).  With hysteresis a walk
 * would have to record this frame's splits for the next one, and a diamond that no
 * window visits (its volume passes each frustum plane of the frame but lies outside
 * every window's) would record nothing: the next frame's mesh, and so its pixels, would
 * depend on how the screen was cut.  The geomorph already hides a split's change of
 * answer at the threshold (a vertex there sits at its fictitious height), which is what
 * hysteresis is for.
 *
 * The window.  A walk for rows [y0, y1) of the screen tests each triangle's prism (below:
 * out_of_window) against the two planes through the window's top and bottom edges
 * (cam_frustum_rows) and skips the subtree of one that lies wholly outside either, and
 * each leaf's own three points: none of those triangles can cover a pixel centre of the
 * rows (the planes' rounding, about 2^-30 of a distance, is far below the half pixel
 * between a row's edge and its centres).  The plane test only prunes; the decision is
 * the whole frustum's, so the same diamond splits in every window that reaches it. */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/config.h"
#include "core/bt_em.h"

struct bt_stream {
    bti_extract e;
    bt_params p;            /* the frame's parameters and camera, copied (e.p points here) */
    cam c;
    cam_plane win[2];       /* the walk's window: its bottom and top planes */
    int32_t last_y1;        /* the last window's bottom row (-1: none this frame) */
    unsigned zlo_and, zhi_or; /* a node's height codes as the prism takes them: the node's
                               (0xFF, 0), or the whole tree's (0, 0xFF) on a grid with
                               voids inside its data */
    uint8_t *ans;           /* this frame's answers: two bit planes of nslot bits */
    size_t plane;           /* the frame's tree's plane bytes: plane 1 at ans + plane */
    uint32_t nslot;
    uint32_t *wkey;         /* the weight cache: slot + 1 (0: empty), wmask + 1 entries */
    uint16_t *wval;         /* and the plane mask the split handed on << 8 | its weight /
                               BT_MORPH_STEP, or CULLED */
    uint32_t wmask;
    bt_stream_leaf fn;
    void *user;
    uint32_t count;
    int order;              /* BT_STREAM_STRIP or BT_STREAM_BACK_TO_FRONT */
};
#define CULLED 0xFFu

static size_t head_size(void)
{
    return (sizeof(bt_stream) + 7) & ~(size_t)7;
}

size_t bt_stream_mem_size(uint32_t cache_entries, uint32_t nslot)
{
    if (cache_entries < 16 || (cache_entries & (cache_entries - 1)) || cache_entries > (1u << 24) || nslot < 1)
        return 0;
    return head_size() + (size_t)cache_entries * 6u + 2 * bti_plane_bytes(nslot);
}

br_status bt_stream_init(bt_stream **out, uint32_t cache_entries, uint32_t nslot, void *mem, size_t mem_bytes)
{
    bt_stream *s = (bt_stream *)mem;
    const size_t need = bt_stream_mem_size(cache_entries, nslot);
    if (!out || !mem || !need || mem_bytes < need || ((uintptr_t)mem & 7)) return BR_E_ARG;
    memset(s, 0, sizeof *s);
    s->wkey = (uint32_t *)(void *)((uint8_t *)mem + head_size());
    s->wval = (uint16_t *)(void *)(s->wkey + cache_entries);
    s->wmask = cache_entries - 1;
    s->ans = (uint8_t *)(s->wval + cache_entries);
    s->nslot = nslot;
    *out = s;
    return BR_OK;
}

br_status bt_stream_order(bt_stream *s, int order)
{
    if (!s || (order != BT_STREAM_STRIP && order != BT_STREAM_BACK_TO_FRONT)) return BR_E_ARG;
    s->order = order;
    return BR_OK;
}

br_status bt_stream_frame(bt_stream *s, bt_tree *t, const bt_params *p)
{
    br_status st;
    if (!s || !t || !p || !p->c || p->mode != BT_VIEW || p->hyst_q8 != 0 || p->window || t->nslot > s->nslot)
        return BR_E_ARG;
    s->p = *p;
    s->c = *p->c;
    s->p.c = &s->c;
    if ((st = bti_setup(&s->e, t, &s->p)) != BR_OK) return st;
    s->last_y1 = -1;
    s->zlo_and = s->e.nodata_free ? 0xFFu : 0u;
    s->zhi_or = s->e.nodata_free ? 0u : 0xFFu;
    s->plane = bti_plane_bytes(t->nslot);
    memset(s->ans, 0, 2 * s->plane);
    memset(s->wkey, 0, ((size_t)s->wmask + 1) * 4);
    return BR_OK;
}

/* Diamond id's code in the answer planes (decide below) */
static unsigned answer(const bt_stream *s, uint32_t id)
{
    const uint8_t *const p0 = &s->ans[id >> 3];
    return ((*p0 >> (id & 7u)) & 1u) | ((p0[s->plane] >> (id & 7u)) & 1u) << 1;
}

/* The view rule's answer for diamond (x, y) in slot id (core/bt_mesh.c decide), kept for
 * the whole frame in the two bit planes: code (plane 0 bit) | (plane 1 bit) << 1 = 1
 * split with the full weight, 2 leaf, 3 split with a partial weight, 0 not yet decided
 * or culled (few: the weight cache marks them, else they are decided again).  A partial
 * weight comes from the weight cache (slot + 1 and the weight's step, direct-mapped)
 * while it holds it, else is computed again (bti_morph_now: the same weight, without the
 * frustum test).  The plane mask is handed on only by a first decision; a later visit
 * keeps its parent's, whose extra planes give the same answers (bt_mesh.c decide_memo).
 * code: answer(s, id). */
static int decide(bt_stream *s, int32_t x, int32_t y, uint32_t id, unsigned code, unsigned *mask, uint16_t *morph)
{
    bti_extract *e = &s->e;
    uint8_t *const p0 = &s->ans[id >> 3], *const p1 = p0 + s->plane;
    const uint8_t bit = (uint8_t)(1u << (id & 7u));
    const uint32_t h = (id * 2654435761u >> 8) & s->wmask;
    int sp;
    const int hit = s->wkey[h] == id + 1;
    switch (code) {
    case 2: return 0;
    case 1: case 3:
        if (hit) {
            *morph = (uint16_t)((s->wval[h] & 0xFFu) * BT_MORPH_STEP);
            *mask = s->wval[h] >> 8;
        } else *morph = code == 1 ? BT_MORPH_ONE : bti_morph_now(e, x, y, id);
        return 1;
    default:
        if (hit && s->wval[h] == CULLED) return -1;
        break;
    }
    sp = bti_decide_view(e, x, y, id, mask, morph);
    if (sp == 0) *p1 |= bit;
    else if (sp < 0) {
        s->wkey[h] = id + 1;
        s->wval[h] = CULLED;
    } else {
        *p0 |= bit;
        if (*morph != BT_MORPH_ONE) *p1 |= bit;     /* a multiple of BT_MORPH_STEP (morph_at) */
        /* a full weight's entry (only its mask to keep) does not push out a partial
         * weight's, which would have to be computed again */
        if (*morph != BT_MORPH_ONE || !s->wkey[h] || (s->wval[h] & 0xFFu) >= BT_MORPH_ONE / BT_MORPH_STEP) {
            s->wkey[h] = id + 1;
            s->wval[h] = (uint16_t)(*mask << 8 | *morph / BT_MORPH_STEP);
        }
    }
    return sp;
}

/* The window's planes bound the walk.  A plane's value at a world point is affine, so
 * over the prism of triangle (a, c, b) it lies between the least and the most of its
 * values at the three corners' (x, y), each plus the height term n2 z at the end of the
 * prism's height range that lowers or raises it.  The prism holds every descendant: in
 * x and y the triangle's hull holds their points; in height, a descendant split point
 * lies between its real height (within the nested volume's range [zlo, zhi] of the
 * triangle's diamond, slot id, which bounds the real heights below it) and the mean of
 * its hypotenuse's ends, so by induction within the range widened to the three
 * corners' own heights (a corner's geomorph weight comes from outside the triangle).
 * Each point keeps its two planes' values at (x, y, 0) (pa), made once when the walk
 * makes it: a test is then two products a plane.
 * On a grid with voids inside its data (not bti_extract.nodata_free) the nested volume's
 * range does not bound every leaf below it (tif/mt_rainier_90m.tif: 8 pixels of a frame
 * lost in 16-row bands, tests/test_stream.c), so there the prism takes the whole tree's
 * height range (codes 0 and 255: the least and most valid heights, which bound every
 * point's height, real or geomorphed between real ones). */

/* Plane i (a constant: the two planes' code apart) of out_of_window's test, the
 * prism's heights zlo .. zhi */
static inline int plane_out(const bt_stream *s, const int i, const bt_svert *a, const bt_svert *c, const bt_svert *b,
                            int32_t zlo, int32_t zhi, unsigned *wmask)
{
    const int64_t n2 = s->win[i].n[2];
    int64_t mx, mn;
    if (!(*wmask & (1u << i))) return 0;
    mx = a->pa[i] > b->pa[i] ? a->pa[i] : b->pa[i];
    mn = a->pa[i] ^ b->pa[i] ^ mx;
    if (c->pa[i] > mx) mx = c->pa[i];
    if (c->pa[i] < mn) mn = c->pa[i];
    if (mx + n2 * (n2 >= 0 ? zhi : zlo) < 0) return 1;
    if (mn + n2 * (n2 >= 0 ? zlo : zhi) >= 0) *wmask &= ~(1u << i);
    return 0;
}

/* 1 when the prism lies wholly outside one of the planes in *wmask; planes it lies
 * wholly inside leave *wmask */
static int out_of_window(const bt_stream *s, const bt_svert *a, const bt_svert *c, const bt_svert *b, uint32_t id,
                         unsigned *wmask)
{
    const uint32_t nv = s->e.t->node[id];
    int32_t zlo = s->e.wz_lo[BT_NODE_ZLO(nv) & s->zlo_and], zhi = s->e.wz_hi[BT_NODE_ZHI(nv) | s->zhi_or];
    if (a->wz < zlo) zlo = a->wz;
    if (a->wz > zhi) zhi = a->wz;
    if (b->wz < zlo) zlo = b->wz;
    if (b->wz > zhi) zhi = b->wz;
    if (c->wz < zlo) zlo = c->wz;
    if (c->wz > zhi) zhi = c->wz;
    return plane_out(s, 0, a, c, b, zlo, zhi, wmask) || plane_out(s, 1, a, c, b, zlo, zhi, wmask);
}

/* 1 when the three points lie outside one of the planes in wmask: the triangle, their
 * hull, covers no pixel centre of the window's rows */
static int tri_out(const bt_stream *s, const bt_svert *a, const bt_svert *c, const bt_svert *b, unsigned wmask)
{
    int i;
    for (i = 0; i < 2; i++) {
        const int64_t n2 = s->win[i].n[2];
        if ((wmask & (1u << i)) && a->pa[i] + n2 * a->wz < 0 && b->pa[i] + n2 * b->wz < 0 && c->pa[i] + n2 * c->wz < 0)
            return 1;
    }
    return 0;
}

/* Leaf (a, c, b), apex c: to the caller apex first, then counter-clockwise seen from
 * +z (core/bitree.h: cross < 0 in grid (x, row)).  |dx|, |dy| <= 2^14 (BR_MAX_SIDE):
 * the cross product stays below 2^29.  Planes of the window still in wmask are tested
 * against the triangle's own points (tighter than its box's height range). */
static void leaf(bt_stream *s, bt_svert *a, bt_svert *c, bt_svert *b, unsigned wmask)
{
    const int32_t cr = (a->x - c->x) * (b->y - c->y) - (a->y - c->y) * (b->x - c->x);
    if (wmask && tri_out(s, a, c, b, wmask)) return;
    s->count++;
    if (cr < 0) s->fn(s->user, c, a, b);
    else s->fn(s->user, c, b, a);
}

/* q's world height and the values at (x, y, 0) of the window planes in wmask (a split
 * point's triangles test no other) (bt_world's position, inside CAM_COORD_MAX for a
 * frame bti_setup took: Q30 normals times coordinates below 2^30, and d = -n . eye, so
 * |pa| < 2^62 and with the height term n2 wz (< 2^60) the tests' sums stay below 2^63) */
static void world(const bt_stream *s, bt_svert *q, unsigned wmask)
{
    const bt_frame *fr = &s->p.fr;
    const int32_t wx = (int32_t)(fr->ox + (int64_t)q->x * fr->sx), wy = (int32_t)(fr->oy - (int64_t)q->y * fr->sy);
    q->wz = (int32_t)(fr->oz + (((int64_t)q->z * fr->sz_q16) >> 16));
    if (wmask & 1u) q->pa[0] = (int64_t)s->win[0].n[0] * wx + (int64_t)s->win[0].n[1] * wy + s->win[0].d;
    if (wmask & 2u) q->pa[1] = (int64_t)s->win[1].n[0] * wx + (int64_t)s->win[1].n[1] * wy + s->win[1].d;
}

/* Back to front (painter's order).  Split (a, c, b) -> (a, m, c), (c, m, b): the vertical
 * plane through c and m separates the children (each lies, in x and y, on its own side of
 * the line c m), so nothing of the child on the far side of it from the eye can hide
 * anything of the near child (a ray from the eye to a point on the eye's side stays on
 * that side), and by induction on the walk, drawing the far child's leaves before the
 * near child's draws every pair of leaves back to front (their lowest common ancestor's
 * plane separates them).  Geomorphing moves points vertically only: the same planes.  An
 * eye on the plane sees either order the same.
 * 1 when the child (a, m, c) is the near one: the eye E and a on the same side of c m.
 * In world x, y (x = ox + col sx, y = oy - row sy, sx, sy > 0), E's side is the sign of
 * d x (E - c) = dx sx (Ey - cy') + dy sy (Ex - cx') with d = m - c in grid units and c'
 * c's world position: grid and eye lie inside +-CAM_COORD_MAX = 2^30 - 1 (bti_setup),
 * so each factor is below 2^31 in magnitude (an int32) and each product below 2^62.
 * a's side in world coordinates is -sx sy times its side in grid coordinates (the row
 * axis points south): the sign of -(dx (ay - cy) - dy (ax - cx)), grid values below
 * 2^29. */
static inline int near_is_a(const bt_stream *s, const bt_svert *a, const bt_svert *c, const bt_svert *m)
{
    const bt_frame *fr = &s->p.fr;
    const int32_t dx = m->x - c->x, dy = m->y - c->y;
    const int32_t ex = s->c.eye[0] - (fr->ox + c->x * fr->sx), ey = s->c.eye[1] - (fr->oy - c->y * fr->sy);
    const int64_t se = (int64_t)(dx * fr->sx) * ey + (int64_t)(dy * fr->sy) * ex;
    const int32_t ga = dx * (a->y - c->y) - dy * (a->x - c->x);
    return se > 0 ? ga < 0 : se < 0 && ga > 0;
}

static void walk(bt_stream *s, bt_svert *a, bt_svert *c, bt_svert *b, unsigned mask, unsigned wmask)
{
    bti_extract *e = &s->e;
    bt_svert mm;
    uint32_t id;
    unsigned code;
    int sp;
    if ((a->x + b->x) & 1) {     /* unit legs: the hypotenuse midpoint is no sample */
        if (bti_tri_valid6(e, a->x, a->y, c->x, c->y, b->x, b->y)) leaf(s, a, c, b, wmask);
        return;
    }
    mm.x = a->x + ((b->x - a->x) >> 1);
    mm.y = a->y + ((b->y - a->y) >> 1);
    id = bti_slot(e->t, mm.x, mm.y);
    code = answer(s, id);
    /* the window first: a triangle outside it needs no answer in this walk; but a leaf
     * already found this frame (code 2) goes straight to its own points' test (leaf),
     * which the prism, holding them, passes whenever they do */
    if (code == 2) sp = 0;
    else {
        if (wmask && out_of_window(s, a, c, b, id, &wmask)) return;
        sp = decide(s, mm.x, mm.y, id, code, &mask, &mm.morph);
        if (sp < 0) return;
    }
    if (!sp) {
        /* as rec: a leaf over padding voids is dropped */
        if (!e->nonvoid && BT_NODE_ERR(e->t->node[id]) == BT_CODE_SPLIT) return;
        if (bti_tri_valid6(e, a->x, a->y, c->x, c->y, b->x, b->y)) leaf(s, a, c, b, wmask);
        return;
    }
    mm.tag = 0;
    mm.z = bti_mid_z(e, a->z, b->z, mm.x, mm.y, &mm.morph);
    if (wmask) world(s, &mm, wmask);
    if (s->order == BT_STREAM_BACK_TO_FRONT && near_is_a(s, a, c, &mm)) {
        walk(s, c, &mm, b, mask, wmask);
        walk(s, a, &mm, c, mask, wmask);
        return;
    }
    walk(s, a, &mm, c, mask, wmask);
    walk(s, c, &mm, b, mask, wmask);
}

static void corner(const bt_stream *s, int32_t x, int32_t y, bt_svert *q)
{
    q->x = x; q->y = y; q->z = bti_zreal(s->e.t, x, y); q->morph = BT_MORPH_ONE; q->tag = 0;
    world(s, q, 3);
}

uint32_t bt_stream_walk(bt_stream *s, const int32_t window[4], bt_stream_leaf fn, void *user)
{
    bt_svert q[4];
    unsigned wmask = 0;
    const int32_t S = s->e.S;
    if (window) {
        if (window[0] < 0 || window[0] >= window[2] || window[2] > s->c.w || window[1] < 0 || window[1] >= window[3]
            || window[3] > s->c.h)
            return 0;
        if (window[1] == s->last_y1) {
            /* bands top to bottom: this top edge is the last bottom edge, whose plane
             * turned around (an exact negation: the same line, the other side) bounds
             * this window as well as cam_frustum_rows' own would */
            int k;
            for (k = 0; k < 3; k++) s->win[1].n[k] = -s->win[0].n[k];
            s->win[1].d = -s->win[0].d;
            cam_frustum_rows(&s->c, window[1], window[3], &s->win[0], NULL);
        } else cam_frustum_rows(&s->c, window[1], window[3], &s->win[0], &s->win[1]);
        s->last_y1 = window[3];
        wmask = 3;
    }
    s->fn = fn;
    s->user = user;
    s->count = 0;
    corner(s, 0, 0, &q[0]); corner(s, S, 0, &q[1]);
    corner(s, S, S, &q[2]); corner(s, 0, S, &q[3]);
    /* the roots' diagonal (0, 0) - (S, S) separates them as a split's line does: the
     * first root, with (S, 0), is the near one when (S, 0) lies on the eye's side */
    if (s->order == BT_STREAM_BACK_TO_FRONT && near_is_a(s, &q[1], &q[0], &q[2])) {
        walk(s, &q[2], &q[3], &q[0], 0x3f, wmask);
        walk(s, &q[0], &q[1], &q[2], 0x3f, wmask);
    } else {
        walk(s, &q[0], &q[1], &q[2], 0x3f, wmask);
        walk(s, &q[2], &q[3], &q[0], 0x3f, wmask);
    }
    return s->count;
}
