/* core/water.c — water bodies of a heightfield (see water.h). */
#include <string.h>
#include "core/water.h"

/* work: lab (int32 per sample), the queue (uint32 per sample), the seam table.  lab: 0 unvisited,
 * 1 visited and not a candidate, 2 + k candidate region k, -1 sea. */
#define LAB_NONE 1
#define LAB_SEA (-1)

typedef struct cand {
    int32_t level;
    int64_t area;
    int32_t parent;             /* union-find over the seam rule */
    int32_t joined;
    int64_t rim, down;          /* the rim rule (rims) */
    int64_t big;                /* area of the largest region joined in: its level is the body's */
} cand;

/* Seam statistics of one pair of candidates: 4-neighbour pairs across a column boundary
 * (h) and a row boundary (v); the first boundary seen of each kind and whether all
 * others lie on it. */
typedef struct seam {
    int32_t nh, nv, col, row, straight;
} seam;

size_t wt_work_size(int32_t w, int32_t h)
{
    if (w < 1 || h < 1) return 0;
    return (size_t)w * (size_t)h * (sizeof(int32_t) + sizeof(uint32_t))
         + (size_t)WT_MAX_CAND * WT_MAX_CAND * sizeof(seam);
}

static int32_t find(cand *c, int32_t k)
{
    while (c[k].parent != k) k = c[k].parent = c[c[k].parent].parent;
    return k;
}

/* Breadth-first fill from the queued seeds (lab already set to mark) through samples
 * with lab 0 accepted by the test; returns the number of samples queued in total. */
static uint32_t fill(const hf *f, int32_t *lab, uint32_t *q, uint32_t head, uint32_t tail, int32_t mark,
                     int sea, int32_t zref)
{
    const int32_t w = f->w, h = f->h;
    while (head < tail) {
        uint32_t i = q[head++], x = i % (uint32_t)w, y = i / (uint32_t)w;
        uint32_t nb[4];
        int k, nn = 0;
        if (x > 0) nb[nn++] = i - 1;
        if (x + 1 < (uint32_t)w) nb[nn++] = i + 1;
        if (y > 0) nb[nn++] = i - (uint32_t)w;
        if (y + 1 < (uint32_t)h) nb[nn++] = i + (uint32_t)w;
        for (k = 0; k < nn; k++) {
            uint32_t j = nb[k];
            int32_t z = f->z[j];
            if (lab[j] != 0 || z == HF_NODATA) continue;
            if (sea ? z > zref : z != zref) continue;
            lab[j] = mark;
            q[tail++] = j;
        }
    }
    return tail;
}

/* The rim rule: a lake (after the seam rule) is kept only when at most 1/32 of its rim
 * (4-neighbour pairs leaving it, voids aside) goes down from its region's level (an
 * outflow); terraces of a flattened valley floor step down along a whole edge. */
static void rims(const hf *f, const int32_t *lab, cand *c, int32_t nc)
{
    const int32_t w = f->w, h = f->h;
    int32_t x, y, k;
    for (k = 0; k < nc; k++) c[k].rim = c[k].down = 0;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            int32_t a = lab[i] - 2, r, d;
            if (a < 0 || a >= nc) continue;
            r = find(c, a);
            for (d = 0; d < 4; d++) {
                int32_t nx = x + (d == 0) - (d == 1), ny = y + (d == 2) - (d == 3), b, z;
                size_t j;
                if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                j = (size_t)ny * (size_t)w + (size_t)nx;
                b = lab[j] - 2;
                z = f->z[j];
                if (z == HF_NODATA || (b >= 0 && b < nc && find(c, b) == r)) continue;
                c[r].rim++;
                c[r].down += z < f->z[i];
            }
        }
}

static void seams(const hf *f, const int32_t *lab, const cand *c, int32_t nc, seam *sm)
{
    const int32_t w = f->w, h = f->h;
    int32_t x, y;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            int32_t a = lab[(size_t)y * (size_t)w + (size_t)x] - 2, d;
            if (a < 0 || a >= nc) continue;
            for (d = 0; d < 2; d++) {
                int32_t b, lo, hi;
                seam *s;
                if (d == 0 ? x + 1 >= w : y + 1 >= h) continue;
                b = lab[(size_t)(y + d) * (size_t)w + (size_t)(x + 1 - d)] - 2;
                if (b < 0 || b >= nc || b == a) continue;
                lo = a < b ? a : b; hi = a < b ? b : a;
                s = &sm[lo * WT_MAX_CAND + hi];
                if (d == 0) {
                    if (s->nh == 0) s->col = x;
                    else if (s->col != x) s->straight = 0;
                    s->nh++;
                } else {
                    if (s->nv == 0) s->row = y;
                    else if (s->row != y) s->straight = 0;
                    s->nv++;
                }
                (void)c;
            }
        }
}

br_status wt_detect(const hf *f, const wt_params *p, uint8_t *id, void *work, size_t work_size,
                    wt_bodies *out)
{
    int32_t *lab;
    uint32_t *q;
    size_t n, i;
    int32_t nc = 0, k, j, seam_min = p->join_seam > 0 ? p->join_seam : 16;
    int64_t sea_area = 0;
    cand c[WT_MAX_CAND];
    if (!f || !p || !id || !work || !out || hf_validate(f) != BR_OK) return BR_E_ARG;
    n = (size_t)f->w * (size_t)f->h;
    if (work_size < wt_work_size(f->w, f->h)) return BR_E_ARG;
    lab = (int32_t *)work;
    q = (uint32_t *)(void *)(lab + n);
    memset(lab, 0, n * sizeof *lab);
    memset(out, 0, sizeof *out);
    /* the sea: seeds on the edge */
    if (p->sea_on) {
        uint32_t tail = 0;
        for (i = 0; i < n; i++) {
            uint32_t x = (uint32_t)(i % (size_t)f->w), y = (uint32_t)(i / (size_t)f->w);
            if (x != 0 && y != 0 && x + 1 != (uint32_t)f->w && y + 1 != (uint32_t)f->h) continue;
            if (f->z[i] == HF_NODATA || f->z[i] > p->sea_level) continue;
            lab[i] = LAB_SEA;
            q[tail++] = (uint32_t)i;
        }
        sea_area = fill(f, lab, q, 0, tail, LAB_SEA, 1, p->sea_level);
    }
    /* flat regions; the WT_MAX_CAND largest at least min_area are candidates */
    if (p->min_area > 0)
        for (i = 0; i < n; i++) {
            uint32_t tail, t;
            int32_t slot;
            if (lab[i] != 0 || f->z[i] == HF_NODATA) continue;
            lab[i] = LAB_NONE;
            q[0] = (uint32_t)i;
            tail = fill(f, lab, q, 0, 1, LAB_NONE, 0, f->z[i]);
            if ((int64_t)tail < p->min_area) continue;
            slot = nc;
            if (nc == WT_MAX_CAND) {        /* replace the smallest when larger */
                slot = 0;
                for (k = 1; k < nc; k++) if (c[k].area < c[slot].area) slot = k;
                if (c[slot].area >= (int64_t)tail) continue;
                for (j = 0; j < (int32_t)n; j++) if (lab[j] == 2 + slot) lab[j] = LAB_NONE;
            } else nc++;
            c[slot].level = f->z[i];
            c[slot].area = c[slot].big = tail;
            c[slot].parent = slot;
            c[slot].joined = 1;
            for (t = 0; t < tail; t++) lab[q[t]] = 2 + slot;
        }
    /* the seam rule */
    if (nc > 1 && p->join_dz > 0) {
        seam *sm = (seam *)(void *)(q + n);
        memset(sm, 0, (size_t)WT_MAX_CAND * WT_MAX_CAND * sizeof *sm);
        for (k = 0; k < WT_MAX_CAND * WT_MAX_CAND; k++) sm[k].straight = 1;
        seams(f, lab, c, nc, sm);
        for (k = 0; k < nc; k++)
            for (j = k + 1; j < nc; j++) {
                const seam *s = &sm[k * WT_MAX_CAND + j];
                int32_t dz = c[k].level - c[j].level;
                if (dz < 0) dz = -dz;
                if (dz > p->join_dz || !s->straight || (s->nh && s->nv) || s->nh + s->nv < seam_min) continue;
                {
                    int32_t a = find(c, k), b = find(c, j);
                    if (a == b) continue;
                    if (c[b].big > c[a].big) { int32_t t = a; a = b; b = t; }
                    c[b].parent = a;
                    c[a].area += c[b].area;
                    c[a].joined += c[b].joined;
                    c[a].big = c[a].big > c[b].big ? c[a].big : c[b].big;
                }
            }
    }
    /* bodies, largest first: the sea, then the roots */
    {
        int32_t order[WT_MAX_CAND + 1], no = 0, body_of[WT_MAX_CAND];
        int64_t area[WT_MAX_CAND + 1];
        for (k = 0; k < nc; k++) body_of[k] = -1;
        if (sea_area > 0) { order[no] = -1; area[no++] = sea_area; }
        rims(f, lab, c, nc);
        for (k = 0; k < nc; k++)
            if (find(c, k) == k && c[k].down * 32 <= c[k].rim) { order[no] = k; area[no++] = c[k].area; }
        for (k = 1; k < no; k++)        /* insertion sort, descending area, stable */
            for (j = k; j > 0 && area[j - 1] < area[j]; j--) {
                int32_t to = order[j]; int64_t ta = area[j];
                order[j] = order[j - 1]; area[j] = area[j - 1];
                order[j - 1] = to; area[j - 1] = ta;
            }
        if (no > WT_MAX_BODIES) no = WT_MAX_BODIES;
        for (k = 0; k < no; k++) {
            out->area[k] = area[k];
            if (order[k] < 0) {
                out->level[k] = p->sea_level; out->kind[k] = WT_SEA; out->joined[k] = 1;
            } else {
                body_of[order[k]] = k;
                out->level[k] = c[order[k]].level; out->kind[k] = WT_LAKE; out->joined[k] = c[order[k]].joined;
            }
        }
        out->n = no;
        {
            int32_t sea_id = 0;
            for (k = 0; k < no; k++) if (order[k] < 0) sea_id = k + 1;
            for (i = 0; i < n; i++) {
                int32_t l = lab[i], b = 0;
                if (l == LAB_SEA) b = sea_id;
                else if (l >= 2) { int32_t r = body_of[find(c, l - 2)]; b = r >= 0 ? r + 1 : 0; }
                id[i] = (uint8_t)b;
            }
        }
    }
    return BR_OK;
}

void wt_level(const hf *f, int32_t level, uint8_t *id, wt_bodies *out)
{
    size_t n = (size_t)f->w * (size_t)f->h, i;
    int64_t a = 0;
    memset(out, 0, sizeof *out);
    for (i = 0; i < n; i++) {
        id[i] = (uint8_t)(f->z[i] != HF_NODATA && f->z[i] <= level);
        a += id[i];
    }
    if (a) { out->n = 1; out->level[0] = level; out->kind[0] = WT_USER; out->area[0] = a; out->joined[0] = 1; }
}
