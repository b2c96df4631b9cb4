/* platform/merge.c — join adjacent heightfields by georeference (see merge.h).
 *
 * SRTM tiles repeat their shared edge row/column (DESIGN.md, paper 004 merges
 * adjacent DEMs into one region): both copies land on the same merged sample
 * and must be equal there, so the edge is kept once.  Anything else that
 * lands twice with a different value is an error, never a silent seam. */
#include <stdlib.h>
#include <string.h>
#include "platform/load.h"
#include "platform/load_internal.h"
#include "platform/fill.h"
#include "platform/merge.h"

static const char *nm(const char *const *names, int i)
{
    return names && names[i] ? names[i] : "(tile)";
}

static int64_t gcd64(int64_t a, int64_t b)
{
    while (b) { int64_t t = a % b; a = b; b = t; }
    return a < 0 ? -a : a;
}

static int64_t llabs64(int64_t v) { return v < 0 ? -v : v; }

/* (a + b/2) / b rounded to nearest for b > 0 */
static int64_t div_round(int64_t a, int64_t b)
{
    return a >= 0 ? (a + b / 2) / b : -((-a + b / 2) / b);
}

br_status dem_merge(const hf *tiles, const char *const *names, int n, hf *out, br_err *err)
{
    return dem_merge_prefer(tiles, names, n, DEM_MERGE_REFUSE, out, err);
}

br_status dem_merge_prefer(const hf *tiles, const char *const *names, int n, int prefer, hf *out, br_err *err)
{
    int i, ix = 0, iy = 0;   /* the tiles that set the west and north edges: the grid's reference */
    int64_t xmin, ymax, sx, sy, W = 0, H = 0, G = 0, L = 1;
    int64_t *cx = NULL, *ry = NULL, *fac = NULL;
    uint8_t *seen = NULL;   /* one bit per merged sample: covered yet (page faults cost, so not a byte) */
    hf m;
    br_status s = BR_OK;
    size_t k, cnt;

    if (n < 1 || !tiles) return br_err_set(err, BR_E_ARG, NULL, "nothing to merge");
    if (n > 65535) return br_err_set(err, BR_E_TOO_BIG, NULL, "too many tiles (%d)", n);
    for (i = 0; i < n; i++) {
        if (tiles[i].geo.kind == HF_GEO_NONE)
            return br_err_set(err, BR_E_MERGE, nm(names, i),
                              "has no georeference, so it cannot be placed among the other tiles "
                              "(an SRTM tile needs its name, e.g. N50E008.hgt)");
        if (tiles[i].geo.kind != tiles[0].geo.kind)
            return br_err_set(err, BR_E_MERGE, nm(names, i), "is %s but %s is %s",
                              tiles[i].geo.kind == HF_GEO_DEGREES ? "geographic" : "projected", nm(names, 0),
                              tiles[0].geo.kind == HF_GEO_DEGREES ? "geographic" : "projected");
    }
    sx = tiles[0].geo.sx;
    sy = tiles[0].geo.sy;
    xmin = tiles[0].geo.x0;
    ymax = tiles[0].geo.y0;
    for (i = 0; i < n; i++) {
        int64_t tx = sx / 1000000 > 1 ? sx / 1000000 : 1, ty = sy / 1000000 > 1 ? sy / 1000000 : 1;
        if (llabs64(tiles[i].geo.sx - sx) > tx || llabs64(tiles[i].geo.sy - sy) > ty)
            return br_err_set(err, BR_E_MERGE, nm(names, i), "sample step differs from %s's (resolutions differ)",
                              nm(names, 0));
        if (tiles[i].geo.x0 < xmin) { xmin = tiles[i].geo.x0; ix = i; }
        if (tiles[i].geo.y0 > ymax) { ymax = tiles[i].geo.y0; iy = i; }
    }
    cx = calloc((size_t)n, sizeof *cx);
    ry = calloc((size_t)n, sizeof *ry);
    fac = calloc((size_t)n, sizeof *fac);
    if (!cx || !ry || !fac) { s = br_err_set(err, BR_E_NOMEM, NULL, "out of memory"); goto done; }
    for (i = 0; i < n; i++) {
        int64_t dx = tiles[i].geo.x0 - xmin, dy = ymax - tiles[i].geo.y0;
        cx[i] = div_round(dx, sx);
        ry[i] = div_round(dy, sy);
        /* The steps are rounded to whole nano-degrees (micrometres): 1/1200 degree
         * is kept as 833333, a third of a unit short, so k steps are known to
         * +-k/2 units; besides that a tile may sit 1% of a step off the grid. */
        if (llabs64(dx - cx[i] * sx) > sx / 100 + llabs64(cx[i]) / 2 + 1 ||
            llabs64(dy - ry[i] * sy) > sy / 100 + llabs64(ry[i]) / 2 + 1) {
            int x_off = llabs64(dx - cx[i] * sx) > sx / 100 + llabs64(cx[i]) / 2 + 1;
            s = br_err_set(err, BR_E_MERGE, nm(names, i), "is not aligned with the sample grid of %s "
                           "(%s %.3f samples from it)", nm(names, x_off ? ix : iy), x_off ? "west edge" : "north edge",
                           x_off ? (double)dx / (double)sx : (double)dy / (double)sy);
            goto done;
        }
        if (cx[i] + tiles[i].w > W) W = cx[i] + tiles[i].w;
        if (ry[i] + tiles[i].h > H) H = ry[i] + tiles[i].h;
        if (W > BR_MAX_SIDE || H > BR_MAX_SIDE) break;
    }
    /* the common unit U = gcd(num_i) / lcm(den_i); each tile's z scales by unit_i / U */
    for (i = 0; i < n; i++) {
        int64_t g = gcd64(tiles[i].z_num, tiles[i].z_den), num = tiles[i].z_num / g, den = tiles[i].z_den / g;
        G = gcd64(G, num);
        L = L / gcd64(L, den) * den;
        if (L > INT32_MAX) {
            s = br_err_set(err, BR_E_MERGE, nm(names, i), "height units cannot be combined with the other tiles'");
            goto done;
        }
    }
    for (i = 0; i < n; i++) {
        int64_t g = gcd64(tiles[i].z_num, tiles[i].z_den), num = tiles[i].z_num / g, den = tiles[i].z_den / g;
        hf_stats st;
        fac[i] = num * (L / den) / G;
        hf_stats_get(&tiles[i], &st);
        if (llabs64(st.zmin) * fac[i] > BR_Z_LIMIT || llabs64(st.zmax) * fac[i] > BR_Z_LIMIT) {
            s = br_err_set(err, BR_E_MERGE, nm(names, i),
                           "heights exceed the range of the common unit %lld/%lld m", (long long)G, (long long)L);
            goto done;
        }
    }
    s = dem_alloc(&m, W, H, "merged tiles", err);
    if (s != BR_OK) goto done;
    cnt = (size_t)W * (size_t)H;
    seen = calloc(cnt / 8 + 1, 1);
    if (!seen) { dem_free(&m); s = br_err_set(err, BR_E_NOMEM, NULL, "out of memory merging"); goto done; }
    for (i = 0; i < n && s == BR_OK; i++) {
        const hf *t = &tiles[i];
        int32_t r, c;
        for (r = 0; r < t->h && s == BR_OK; r++) {
            const int32_t *src = t->z + (size_t)r * (size_t)t->w;
            size_t base = (size_t)(ry[i] + r) * (size_t)W + (size_t)cx[i];
            for (c = 0; c < t->w; c++) {
                int32_t v = src[c] == HF_NODATA ? HF_NODATA : (int32_t)(src[c] * fac[i]);
                size_t q = base + c;
                if (seen[q >> 3] & (1u << (q & 7))) {
                    if (m.z[q] != v && prefer != DEM_MERGE_REFUSE && (v == HF_NODATA || m.z[q] == HF_NODATA)) {
                        if (m.z[q] == HF_NODATA) m.z[q] = v;     /* a void never replaces a height */
                    } else if (m.z[q] != v && prefer == DEM_MERGE_LAST) {
                        m.z[q] = v;
                    } else if (m.z[q] != v && prefer == DEM_MERGE_REFUSE) {
                        int j = 0;     /* an earlier tile that covers this sample */
                        while (j < i && !(cx[i] + c >= cx[j] && cx[i] + c < cx[j] + tiles[j].w &&
                                          ry[i] + r >= ry[j] && ry[i] + r < ry[j] + tiles[j].h)) j++;
                        s = br_err_set(err, BR_E_MERGE, nm(names, i),
                                       "overlaps %s with different heights at merged sample (%lld, %lld) "
                                       "(--merge-prefer first|last to let one win)",
                                       nm(names, j), (long long)(cx[i] + c), (long long)(ry[i] + r));
                        break;
                    }
                } else {
                    seen[q >> 3] = (uint8_t)(seen[q >> 3] | (1u << (q & 7)));
                    m.z[q] = v;
                }
            }
        }
    }
    for (k = 0; k < cnt && s == BR_OK; k++)
        if (!(seen[k >> 3] & (1u << (k & 7))))
            s = br_err_set(err, BR_E_MERGE, NULL,
                           "%s%s%s%s%s: the tiles leave a gap: no tile covers merged sample (%lld, %lld) of %lldx%lld",
                           nm(names, 0), n > 1 ? ", " : "", n > 1 ? nm(names, 1) : "", n > 2 ? ", " : "",
                           n > 2 ? (n > 3 ? "..." : nm(names, 2)) : "",
                           (long long)(k % (size_t)W), (long long)(k / (size_t)W), (long long)W, (long long)H);
    if (s == BR_OK) {
        m.z_num = (int32_t)G;
        m.z_den = (int32_t)L;
        m.geo = tiles[0].geo;
        m.geo.x0 = xmin;
        m.geo.y0 = ymax;
        m.dx_um = tiles[0].dx_um;
        m.dy_um = tiles[0].dy_um;
        s = dem_geo_spacing(&m, &tiles[0], "merged tiles", err);
    }
    if (s == BR_OK) *out = m;
    else dem_free(&m);
done:
    free(seen);
    free(cx);
    free(ry);
    free(fac);
    return s;
}

/* Several files: each loaded on its own (load.c), then merged.  Here rather than in
 * load.c so that calls run one way only, merge.c -> load.c. */
br_status dem_load_many(const char *const *paths, int n, const dem_opts *o, hf *out, br_err *err)
{
    hf *tiles;
    int i, k;
    br_status s = BR_OK;
    if (n < 1 || !paths) return br_err_set(err, BR_E_ARG, NULL, "no input files");
    if (n == 1) s = dem_load(paths[0], o, out, err);
    else {
        tiles = calloc((size_t)n, sizeof *tiles);
        if (!tiles) return br_err_set(err, BR_E_NOMEM, NULL, "out of memory");
        for (i = 0; i < n && s == BR_OK; i++) s = dem_load(paths[i], o, &tiles[i], err);
        if (s == BR_OK) s = dem_merge_prefer(tiles, paths, n, o ? o->merge_prefer : DEM_MERGE_REFUSE, out, err);
        for (k = 0; k < n; k++) dem_free(&tiles[k]);
        free(tiles);
    }
    if (s == BR_OK && o && o->fill_voids && (s = dem_fill_voids(out, o->filled_out, err)) != BR_OK) dem_free(out);
    return s;
}
