/* platform/view_hud.c — what the viewer draws over the terrain, in the frame driver's
 * post hook (raster/frame.h): the wireframe, band boundaries, the HUD and the help.
 * Every pixel drawn here is a function of the frame (the strip, the vertex cache, the
 * text) and its position, never of the band: the hook gives the same pixels for every
 * band height and thread count (band boundaries, which mark the bands, excepted). */
#include <math.h>
#include <string.h>
#include "platform/font.h"
#include "platform/geocam.h"
#include "platform/view.h"

#define WIRE_RGB 0x1a2a40u
#define BAND_RGB 0xff00ffu

/* ---------------------------------------------------------------- wireframe */

/* The depth buffer entry of frame pixel (x, y) of the band. */
static uint32_t depth_at(const rs_band *b, int32_t x, int32_t y)
{
    size_t k = (size_t)(y - b->y0) * (size_t)b->w + (size_t)x;
    return b->depth_fmt == RS_DEPTH16 ? (uint32_t)((const uint16_t *)b->depth)[k] << 14 : ((const uint32_t *)b->depth)[k];
}

/* Plots (x, y) when the line's depth d is not behind the surface drawn there: a line
 * at most 1/32 of the surface's 1/w farther (the edge of the triangle that drew the
 * pixel lies on that surface) shows, hidden edges do not. */
static void wire_pixel(rs_band *b, int32_t x, int32_t y, int64_t d)
{
    if (x < 0 || x >= b->w || y < b->y0 || y >= b->y0 + b->rows) return;
    if (d + (d >> 5) < (int64_t)depth_at(b, x, y)) return;
    font_pixel(b, x, y, WIRE_RGB);
}

/* floor(a / b) for b > 0. */
static int64_t floordiv(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/* One edge between two cache entries (sub-pixels, 16 a pixel; depth 1/w).  Steep lines
 * take one pixel per row whose centre they cross, shallow ones one per column: each
 * pixel is computed from the end points alone. */
static void wire_line(rs_band *b, const rs_cvert *p, const rs_cvert *q)
{
    int64_t x0 = p->x, y0 = p->y, x1 = q->x, y1 = q->y, d0 = p->d, d1 = q->d;
    int64_t dx = x1 - x0, dy = y1 - y0;
    int64_t top = (int64_t)b->y0 * 16, bot = (int64_t)(b->y0 + b->rows) * 16;
    if ((y0 < top && y1 < top) || (y0 >= bot && y1 >= bot)) return;
    if (dx == 0 && dy == 0) return;
    if ((dy < 0 ? -dy : dy) >= (dx < 0 ? -dx : dx)) {
        int64_t j, lo, hi;
        if (dy < 0) { int64_t t; t = x0; x0 = x1; x1 = t; t = y0; y0 = y1; y1 = t; t = d0; d0 = d1; d1 = t; dx = -dx; dy = -dy; }
        lo = floordiv(y0 - 8 + 15, 16);             /* first row whose centre is >= y0 */
        hi = floordiv(y1 - 8, 16);                  /* last row whose centre is <= y1 */
        if (lo < b->y0) lo = b->y0;
        if (hi > b->y0 + b->rows - 1) hi = b->y0 + b->rows - 1;
        for (j = lo; j <= hi; j++) {
            int64_t t = j * 16 + 8 - y0;
            wire_pixel(b, (int32_t)floordiv(x0 * dy + dx * t, dy * 16), (int32_t)j, d0 + (d1 - d0) * t / dy);
        }
    } else {
        int64_t i, lo, hi;
        if (dx < 0) { int64_t t; t = x0; x0 = x1; x1 = t; t = y0; y0 = y1; y1 = t; t = d0; d0 = d1; d1 = t; dx = -dx; dy = -dy; }
        lo = floordiv(x0 - 8 + 15, 16);
        hi = floordiv(x1 - 8, 16);
        if (lo < 0) lo = 0;
        if (hi > b->w - 1) hi = b->w - 1;
        /* the columns whose y falls in the band: y is monotone in x, so clip the
         * column range to where the line crosses the band's top and bottom (one
         * column of slack each side for the rounding; wire_pixel checks the row) */
        if (dy != 0) {
            int64_t xa = x0 + dx * (top - y0) / dy, xb = x0 + dx * (bot - y0) / dy;
            int64_t cl = (xa < xb ? xa : xb) / 16 - 1, ch = (xa < xb ? xb : xa) / 16 + 1;
            if (lo < cl) lo = cl;
            if (hi > ch) hi = ch;
        }
        for (i = lo; i <= hi; i++) {
            int64_t t = i * 16 + 8 - x0;
            wire_pixel(b, (int32_t)i, (int32_t)floordiv(y0 * dx + dy * t, dx * 16), d0 + (d1 - d0) * t / dx);
        }
    }
}

/* The strip's edges: triangle k has edges (k, k+1), (k+1, k+2), (k, k+2); the first is
 * triangle k-1's second, so each k >= 2 adds (k-2, k) and (k-1, k). */
static void wire(rs_band *b, const rs_frame *f)
{
    const uint32_t bad = (uint32_t)(RS_OUT_NEAR | RS_OUT_GUARD) << 24;
    int32_t pi;
    for (pi = 0; pi < f->nprims; pi++) {
        const rs_prim *pr = &f->prims[pi];
        uint32_t k;
        if (pr->kind == RS_LIST) {
            for (k = 0; k + 2 < pr->n; k += 3) {
                const rs_cvert *t0 = &f->cache[pr->idx[k]], *t1 = &f->cache[pr->idx[k + 1]], *t2 = &f->cache[pr->idx[k + 2]];
                if ((t0->c | t1->c | t2->c) & bad) continue;
                wire_line(b, t0, t1);
                wire_line(b, t1, t2);
                wire_line(b, t2, t0);
            }
            continue;
        }
        if (pr->n < 3) continue;
        for (k = 1; k < pr->n; k++) {
            uint32_t a = pr->idx[k], c = pr->idx[k - 1];
            const rs_cvert *va = &f->cache[a];
            if (va->c & bad) continue;
            if (a != c && !(f->cache[c].c & bad)) wire_line(b, &f->cache[c], va);
            if (k >= 2) {
                uint32_t e = pr->idx[k - 2];
                if (e != a && e != c && !(f->cache[e].c & bad)) wire_line(b, &f->cache[e], va);
            }
        }
    }
}

/* ---------------------------------------------------------------- the hook */

br_status view_post(const void *user, rs_band *b, rs_band_stats *st)
{
    const view_overlay *o = (const view_overlay *)user;
    int32_t s = o->scale < 1 ? 1 : o->scale, x;
    (void)st;
    if (o->wire && o->fr) wire(b, o->fr);
    if (o->band_rows > 0 && b->y0 > 0 && b->y0 % o->band_rows == 0)
        for (x = 0; x < b->w; x++) font_pixel(b, x, b->y0, BAND_RGB);
    if (o->hud) {
        int32_t pw = font_width(o->hud, s) + 8 * s, ph = font_lines(o->hud) * FONT_LINE * s + 6 * s;
        font_panel(b, 0, 0, pw, ph);
        font_draw(b, 4 * s, 4 * s, s, 0xf0f0f0u, o->hud);
    }
    if (o->help) {
        int32_t pw = font_width(o->help, s) + 16 * s, ph = font_lines(o->help) * FONT_LINE * s + 14 * s;
        int32_t px = (b->w - pw) / 2, py = (o->h - ph) / 2;
        if (py < 0) py = 0;
        font_panel(b, px, py, pw, ph);
        font_draw(b, px + 8 * s, py + 8 * s, s, 0xffffc0u, o->help);
    }
    return BR_OK;
}

/* ---------------------------------------------------------------- text */

void view_hud_text(const view_state *v, const view_stats *st, char *buf, size_t n)
{
    const scene *s = v->s;
    double g = scene_ground(s, v->cam.pos[0], v->cam.pos[1]);
    double head = fmod(v->cam.yaw * 180 / 3.14159265358979323846 + 720, 360);
    static const char *const compass[8] = { "N", "NE", "E", "SE", "S", "SW", "W", "NW" };
    size_t k = 0;
    k += (size_t)snprintf(buf + k, n - k,
        "%.1f fps  %.1f ms: select %.1f  vertices %.1f  raster %.1f\n"
        "%u triangles  %.2f M triangles/s  pixel error %.2f%s\n",
        st->fps, st->frame_ms, st->select_ms, st->vert_ms, st->raster_ms,
        st->tris, st->tris_per_s / 1e6, v->pix_err, st->target_fps > 0 ? " (auto)" : "");
    if (k < n) k += (size_t)snprintf(buf + k, n - k, "x %.0f  y %.0f  z %.0f m  ", v->cam.pos[0], v->cam.pos[1], v->cam.pos[2]);
    if (k < n) {
        if (isnan(g)) k += (size_t)snprintf(buf + k, n - k, "(off the terrain)\n");
        else k += (size_t)snprintf(buf + k, n - k, "%.0f m above ground\n", v->cam.pos[2] - g);
    }
    if (k < n && geocam_ok(s)) {
        double lat, lon;
        geocam_to_deg(s, v->cam.pos[0], v->cam.pos[1], &lat, &lon);
        k += (size_t)snprintf(buf + k, n - k, "%.5f %s  %.5f %s  ", fabs(lat), lat < 0 ? "S" : "N", fabs(lon), lon < 0 ? "W" : "E");
    }
    if (k < n)
        k += (size_t)snprintf(buf + k, n - k, "heading %.0f %s  pitch %.0f  %s  speed x%.2g\n", head,
                              compass[(int)((head + 22.5) / 45) % 8], v->cam.pitch * 180 / 3.14159265358979323846,
                              v->orbit ? "orbit" : "fly", v->speed_mul);
    if (k < n)
        k += (size_t)snprintf(buf + k, n - k, "%dx%d  bands of %d rows  %d thread%s of %d cores%s%s%s%s%s",
                              st->w, st->h, st->band_rows, st->threads, st->threads == 1 ? "" : "s", st->cores,
                              v->on[VT_HYST] ? "" : "  no hysteresis", v->on[VT_MORPH] ? "" : "  no geomorph",
                              v->on[VT_NOCULL] ? "  no culling" : "", v->on[VT_LOD] ? "  LOD colours" : "",
                              v->on[VT_WIRE] ? "  wireframe" : "");
    if (k < n && v->note[0] && v->now < v->note_until) snprintf(buf + k, n - k, "\n%s", v->note);
}

/* ---------------------------------------------------------------- LOD colours */

/* floor(log2(x)) for x > 0. */
static int ilog2(uint64_t x)
{
    int n = 0;
    while (x >>= 1) n++;
    return n;
}

uint32_t view_lod_list(const bt_mesh *m, const rs_vertex *verts, rs_vertex *out, uint32_t *idx)
{
    /* finest (red) to coarsest (purple), one colour per doubling of the legs */
    static const uint32_t pal[8] = { 0xff2020u, 0xff8020u, 0xf0e020u, 0x60e040u, 0x20d0b0u, 0x2090ffu, 0x4040ffu, 0x9020c0u };
    uint32_t k, n = 0;
    for (k = 0; k + 2 < m->ns; k++) {
        /* strip triangle k: s[k], s[k+1], s[k+2], the first two swapped for odd k */
        uint32_t t[3], j, p;
        const bt_vert *a, *b, *c;
        int64_t area2;
        t[0] = m->strip[k + (k & 1)]; t[1] = m->strip[k + 1 - (k & 1)]; t[2] = m->strip[k + 2];
        a = &m->v[t[0]]; b = &m->v[t[1]]; c = &m->v[t[2]];
        area2 = (int64_t)(b->x - a->x) * (c->y - a->y) - (int64_t)(b->y - a->y) * (c->x - a->x);
        if (area2 == 0) continue;                       /* line triangle */
        /* a right isosceles triangle of legs L has |area2| = L^2: two levels per
         * doubling of L */
        j = (uint32_t)ilog2((uint64_t)(area2 < 0 ? -area2 : area2)) / 2;
        p = pal[j > 7 ? 7 : j];
        for (j = 0; j < 3; j++) {
            uint32_t sc = verts[t[j]].rgb, o = 0;
            int sh;
            /* a third of the shaded colour (the relief stays readable), two thirds the level's */
            for (sh = 0; sh <= 16; sh += 8) o |= ((((sc >> sh) & 0xffu) + 2 * ((p >> sh) & 0xffu)) / 3) << sh;
            out[n] = verts[t[j]];
            out[n].rgb = o;
            idx[n] = n;
            n++;
        }
    }
    return n;
}

void view_hud_frame_text(const view_state *v, const double eye[3], const double tgt[3], const view_stats *st,
                         char *buf, size_t n)
{
    view_state hv = *v;
    view_cam_look(&hv.cam, eye, tgt);
    view_hud_text(&hv, st, buf, n);
}
