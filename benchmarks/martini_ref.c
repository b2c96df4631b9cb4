/* benchmarks/martini_ref.c — see martini_ref.h.  A port of the algorithm of
 * mapbox/martini index.js (constructor, Tile.update, Tile.getMesh); the structure
 * and the order of operations follow it so triangle and vertex order match. */
#include "benchmarks/martini_ref.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

int mr_grid_init(mr_grid *g, int32_t size)
{
    int32_t tile = size - 1;
    int64_t i;
    memset(g, 0, sizeof *g);
    if (size < 3 || size > 32769 || (tile & (tile - 1))) return -1;
    g->size = size;
    g->ntri = (int64_t)tile * tile * 2 - 2;
    g->nparent = g->ntri - (int64_t)tile * tile;
    g->coords = malloc((size_t)g->ntri * 4 * sizeof *g->coords);
    g->indices = malloc((size_t)size * (size_t)size * sizeof *g->indices);
    if (!g->coords || !g->indices) { mr_grid_free(g); return -1; }
    /* triangle coordinates from the index in the implicit binary tree */
    for (i = 0; i < g->ntri; i++) {
        int64_t id = i + 2;
        int32_t ax = 0, ay = 0, bx = 0, by = 0, cx = 0, cy = 0;
        if (id & 1) { bx = by = cx = tile; }      /* bottom-left triangle */
        else { ax = ay = cy = tile; }            /* top-right triangle */
        while ((id >>= 1) > 1) {
            int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;
            if (id & 1) { bx = ax; by = ay; ax = cx; ay = cy; }   /* left half */
            else { ax = bx; ay = by; bx = cx; by = cy; }          /* right half */
            cx = mx; cy = my;
        }
        g->coords[4 * i + 0] = (uint16_t)ax;
        g->coords[4 * i + 1] = (uint16_t)ay;
        g->coords[4 * i + 2] = (uint16_t)bx;
        g->coords[4 * i + 3] = (uint16_t)by;
    }
    return 0;
}

void mr_grid_free(mr_grid *g)
{
    free(g->coords);
    free(g->indices);
    g->coords = NULL;
    g->indices = NULL;
}

int mr_mesh_alloc(const mr_grid *g, mr_mesh *m)
{
    size_t n = (size_t)g->size * (size_t)g->size;
    m->vert = malloc(2 * n * sizeof *m->vert);
    m->tri = malloc((size_t)3 * 2 * (size_t)(g->size - 1) * (size_t)(g->size - 1) * sizeof *m->tri);
    m->nv = m->nt = 0;
    if (!m->vert || !m->tri) { mr_mesh_free(m); return -1; }
    return 0;
}

void mr_mesh_free(mr_mesh *m)
{
    free(m->vert);
    free(m->tri);
    m->vert = NULL;
    m->tri = NULL;
}

float mr_terrain_rgb_f32(int32_t raw)
{
    return (float)((double)raw / 10.0 - 10000.0);
}

void mr_errors_f32(const mr_grid *g, const float *terrain, float *errors)
{
    int64_t i, size = g->size;
    const uint16_t *coords = g->coords;
    memset(errors, 0, (size_t)(size * size) * sizeof *errors);
    for (i = g->ntri - 1; i >= 0; i--) {
        int32_t ax = coords[4 * i], ay = coords[4 * i + 1], bx = coords[4 * i + 2], by = coords[4 * i + 3];
        int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;
        int32_t cx = mx + my - ay, cy = my + ax - mx;
        double interp = ((double)terrain[ay * size + ax] + (double)terrain[by * size + bx]) / 2;
        int64_t mid = my * size + mx;
        double me = fabs(interp - (double)terrain[mid]);
        double e = (double)errors[mid];
        if (me > e) e = me;
        errors[mid] = (float)e;
        if (i < g->nparent) {
            int64_t l = ((ay + cy) >> 1) * size + ((ax + cx) >> 1);
            int64_t r = ((by + cy) >> 1) * size + ((bx + cx) >> 1);
            float f = errors[mid];
            if (errors[l] > f) f = errors[l];
            if (errors[r] > f) f = errors[r];
            errors[mid] = f;
        }
    }
}

void mr_errors_int(const mr_grid *g, const int32_t *z, uint32_t *err2, int sound)
{
    int64_t i, size = g->size;
    const uint16_t *coords = g->coords;
    memset(err2, 0, (size_t)(size * size) * sizeof *err2);
    for (i = g->ntri - 1; i >= 0; i--) {
        int32_t ax = coords[4 * i], ay = coords[4 * i + 1], bx = coords[4 * i + 2], by = coords[4 * i + 3];
        int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;
        int32_t cx = mx + my - ay, cy = my + ax - mx;
        int64_t mid = my * size + mx;
        int64_t d = (int64_t)z[ay * size + ax] + z[by * size + bx] - 2 * (int64_t)z[mid];
        uint32_t me = (uint32_t)(d < 0 ? -d : d), e;
        if (i < g->nparent) {
            int64_t l = ((ay + cy) >> 1) * size + ((ax + cx) >> 1);
            int64_t r = ((by + cy) >> 1) * size + ((bx + cx) >> 1);
            uint32_t c = err2[l] > err2[r] ? err2[l] : err2[r];
            if (sound) { e = me + c; if (e < me) e = UINT32_MAX; }   /* saturate */
            else e = me > c ? me : c;
        } else {
            e = me;
        }
        if (e > err2[mid]) err2[mid] = e;
    }
}

void mr_errors_tight(const mr_grid *g, const int32_t *z, uint32_t *tb, uint32_t *err2)
{
    int64_t i, size = g->size;
    const uint16_t *coords = g->coords;
    memset(err2, 0, (size_t)(size * size) * sizeof *err2);
    /* pass 1: per-triangle bounds, finest level first.  Tree ids (index + 2) of a
     * level are [lv, 2 lv); martini reads the path from the low bits, so the
     * children of id are 2 lv + (id - lv) ((b,c,m)) and 3 lv + (id - lv) ((c,a,m)). */
    {
        int64_t lv = 1;
        while (2 * lv + 2 <= g->ntri + 2) lv *= 2;      /* the finest level */
        for (; lv >= 2; lv /= 2) {
            int64_t id;
            for (id = 2 * lv - 1; id >= lv; id--) {
                int64_t k = id - 2;
                int32_t ax = coords[4 * k], ay = coords[4 * k + 1], bx = coords[4 * k + 2], by = coords[4 * k + 3];
                int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;
                int64_t d = (int64_t)z[ay * size + ax] + z[by * size + bx] - 2 * (int64_t)z[my * size + mx];
                uint32_t me = (uint32_t)(d < 0 ? -d : d), c = 0, e;
                if (k < g->nparent) {
                    uint32_t l = tb[3 * lv + (id - lv) - 2], r = tb[2 * lv + (id - lv) - 2];
                    c = l > r ? l : r;
                }
                e = me + c;
                if (e < me) e = UINT32_MAX;
                tb[k] = e;
                if (e > err2[my * size + mx]) err2[my * size + mx] = e;
            }
        }
    }
    /* pass 2: martini's max propagation of the diamond values keeps the
     * extraction crack-free (a split child forces its parents' diamonds) */
    for (i = g->nparent - 1; i >= 0; i--) {
        int32_t ax = coords[4 * i], ay = coords[4 * i + 1], bx = coords[4 * i + 2], by = coords[4 * i + 3];
        int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;
        int32_t cx = mx + my - ay, cy = my + ax - mx;
        int64_t mid = my * size + mx;
        int64_t l = ((ay + cy) >> 1) * size + ((ax + cx) >> 1);
        int64_t r = ((by + cy) >> 1) * size + ((bx + cx) >> 1);
        if (err2[l] > err2[mid]) err2[mid] = err2[l];
        if (err2[r] > err2[mid]) err2[mid] = err2[r];
    }
}

/* getMesh's two recursive passes, once per error type. */
#define MR_GETMESH(NAME, ETYPE, TTYPE, SPLIT)                                                  \
typedef struct NAME##_st {                                                                     \
    const ETYPE *errors; TTYPE thr; int32_t size; uint32_t *indices; mr_mesh *out;             \
} NAME##_st;                                                                                   \
static void NAME##_count(NAME##_st *s, int32_t ax, int32_t ay, int32_t bx, int32_t by,         \
                         int32_t cx, int32_t cy)                                               \
{                                                                                              \
    int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;                                          \
    int32_t ddx = ax - cx, ddy = ay - cy;                                                      \
    if ((ddx < 0 ? -ddx : ddx) + (ddy < 0 ? -ddy : ddy) > 1 &&                                 \
        SPLIT(s->errors[my * s->size + mx], s->thr)) {                                         \
        NAME##_count(s, cx, cy, ax, ay, mx, my);                                               \
        NAME##_count(s, bx, by, cx, cy, mx, my);                                               \
    } else {                                                                                   \
        uint32_t *ix = s->indices;                                                             \
        if (!ix[ay * s->size + ax]) ix[ay * s->size + ax] = (uint32_t)++s->out->nv;            \
        if (!ix[by * s->size + bx]) ix[by * s->size + bx] = (uint32_t)++s->out->nv;            \
        if (!ix[cy * s->size + cx]) ix[cy * s->size + cx] = (uint32_t)++s->out->nv;            \
        s->out->nt++;                                                                          \
    }                                                                                          \
}                                                                                              \
static void NAME##_emit(NAME##_st *s, int32_t ax, int32_t ay, int32_t bx, int32_t by,          \
                        int32_t cx, int32_t cy)                                                \
{                                                                                              \
    int32_t mx = (ax + bx) >> 1, my = (ay + by) >> 1;                                          \
    int32_t ddx = ax - cx, ddy = ay - cy;                                                      \
    if ((ddx < 0 ? -ddx : ddx) + (ddy < 0 ? -ddy : ddy) > 1 &&                                 \
        SPLIT(s->errors[my * s->size + mx], s->thr)) {                                         \
        NAME##_emit(s, cx, cy, ax, ay, mx, my);                                                \
        NAME##_emit(s, bx, by, cx, cy, mx, my);                                                \
    } else {                                                                                   \
        uint32_t a = s->indices[ay * s->size + ax] - 1, b = s->indices[by * s->size + bx] - 1; \
        uint32_t c = s->indices[cy * s->size + cx] - 1;                                        \
        uint16_t *v = s->out->vert;                                                            \
        uint32_t *t = s->out->tri + 3 * s->out->nt++;                                          \
        v[2 * a] = (uint16_t)ax; v[2 * a + 1] = (uint16_t)ay;                                  \
        v[2 * b] = (uint16_t)bx; v[2 * b + 1] = (uint16_t)by;                                  \
        v[2 * c] = (uint16_t)cx; v[2 * c + 1] = (uint16_t)cy;                                  \
        t[0] = a; t[1] = b; t[2] = c;                                                          \
    }                                                                                          \
}

#define MR_SPLIT_F32(e, thr) ((double)(e) > (thr))
#define MR_SPLIT_INT(e, thr) ((int64_t)(e) > (thr))
MR_GETMESH(mrf, float, double, MR_SPLIT_F32)
MR_GETMESH(mri, uint32_t, int64_t, MR_SPLIT_INT)

void mr_mesh_f32(mr_grid *g, const float *errors, double max_error, mr_mesh *out)
{
    int32_t max = g->size - 1;
    mrf_st s;
    s.errors = errors; s.thr = max_error; s.size = g->size; s.indices = g->indices; s.out = out;
    memset(g->indices, 0, (size_t)g->size * (size_t)g->size * sizeof *g->indices);
    out->nv = out->nt = 0;
    mrf_count(&s, 0, 0, max, max, max, 0);
    mrf_count(&s, max, max, 0, 0, 0, max);
    out->nt = 0;
    mrf_emit(&s, 0, 0, max, max, max, 0);
    mrf_emit(&s, max, max, 0, 0, 0, max);
}

void mr_mesh_int(mr_grid *g, const uint32_t *err2, int64_t thr2, mr_mesh *out)
{
    int32_t max = g->size - 1;
    mri_st s;
    s.errors = err2; s.thr = thr2; s.size = g->size; s.indices = g->indices; s.out = out;
    memset(g->indices, 0, (size_t)g->size * (size_t)g->size * sizeof *g->indices);
    out->nv = out->nt = 0;
    mri_count(&s, 0, 0, max, max, max, 0);
    mri_count(&s, max, max, 0, 0, 0, max);
    out->nt = 0;
    mri_emit(&s, 0, 0, max, max, max, 0);
    mri_emit(&s, max, max, 0, 0, 0, max);
}
