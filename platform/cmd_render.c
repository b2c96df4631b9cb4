/* platform/cmd_render.c — bitrain render: one frame of a DEM, headless, to PNG.
 *
 *   bitrain render IN... -o out.png [--size WxH] [--camera EX,EY,EZ,TX,TY,TZ] [--fov DEG]
 *          [--max-error M | --pixel-error P | --full [STEP]] [--bands ROWS]
 *          [--format rgb565|rgb888] [--depth 32|16] [--colors FILE] [--texture PNG] [--no-cull]
 *          [--sun AZ,ALT] [--ambient A] [--zscale F]
 * Camera in the heightfield's metres: x east from the west edge, y north from the
 * south edge, z height above 0 m (times --zscale).  Default camera: from the south-west, above the
 * terrain, looking at its centre.  Mesh: the bitree (core/bitree.h), by default
 * view-dependent with a 1 pixel screen-space error; --max-error M selects the
 * fidelity mode (true vertical error <= M metres); --full [STEP] draws the full grid
 * (every STEP-th sample) as row strips instead.  Colours: a gdaldem color-relief file
 * (--colors) or the built-in ramp, lit by a sun (azimuth 315, altitude 45 by default)
 * with 30 % ambient.  --zscale F multiplies heights (default 1; grids without
 * georeference whose relief exceeds half their extent get an automatic scale, since
 * the loader can only assume 1 m spacing for them).  The frame is rendered in bands of ROWS rows (default: whole
 * frame) and streamed to the PNG band by band.  --texture PNG stretches a colour map or
 * orthophoto over the whole grid (perspective-correct, nearest texel), lit by the sun. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "core/bitree.h"
#include "core/cam.h"
#include "platform/cmd.h"
#include "platform/load.h"
#include "platform/png_io.h"
#include "raster/raster.h"
#include "raster/ramp.h"
#include "raster/terrain.h"

/* ---------------------------------------------------------------- colour file */

/* gdaldem color-relief text: `elevation r g b [a]` per line (separators: blanks,
 * commas, tabs, colons), elevation may be `nv` (nodata) or a percentage `P%` of the
 * [zmin, zmax] range; `#` starts a comment.  Entries are sorted by elevation. */
static br_status read_colors(const char *path, rs_ramp *r, int64_t zmin_mm, int64_t zmax_mm, br_err *err)
{
    FILE *fp = fopen(path, "r");
    char line[512];
    int lineno = 0, i, j;
    if (!fp) return br_err_set(err, BR_E_IO, path, "cannot open colour file");
    r->n = 0;
    r->has_nv = 0;
    while (fgets(line, sizeof line, fp)) {
        char *p = line, *tok[5];
        int nt = 0;
        double e;
        long c[3];
        lineno++;
        if ((p = strchr(line, '#')) != NULL) *p = 0;
        for (p = line; *p; p++) if (*p == ',' || *p == '\t' || *p == ':' || *p == '\r' || *p == '\n') *p = ' ';
        p = strtok(line, " ");
        while (p && nt < 5) { tok[nt++] = p; p = strtok(NULL, " "); }
        if (nt == 0) continue;
        if (nt < 4) { fclose(fp); return br_err_set(err, BR_E_FORMAT, path, "line %d: expected 'elevation r g b [a]'", lineno); }
        for (i = 0; i < 3; i++) {
            char *end;
            c[i] = strtol(tok[1 + i], &end, 10);
            if (*end || c[i] < 0 || c[i] > 255) {
                fclose(fp);
                return br_err_set(err, BR_E_VALUE, path, "line %d: colour component '%s' is not 0..255", lineno, tok[1 + i]);
            }
        }
        if (!strcmp(tok[0], "nv")) {
            r->has_nv = 1;
            r->nv_rgb = (uint32_t)(c[0] << 16 | c[1] << 8 | c[2]);
            continue;
        }
        {
            char *end;
            e = strtod(tok[0], &end);
            if (end == tok[0] || !isfinite(e) || (*end && strcmp(end, "%"))) {
                fclose(fp);
                return br_err_set(err, BR_E_VALUE, path, "line %d: elevation '%s' is not a number", lineno, tok[0]);
            }
            if (*end == '%') e = ((double)zmin_mm + (double)(zmax_mm - zmin_mm) * e / 100.0) / 1000.0;
            if (fabs(e) > 1e7) {
                fclose(fp);
                return br_err_set(err, BR_E_VALUE, path, "line %d: elevation %g m is out of range", lineno, e);
            }
        }
        if (r->n >= RS_RAMP_MAX) { fclose(fp); return br_err_set(err, BR_E_TOO_BIG, path, "more than %d colour entries", RS_RAMP_MAX); }
        r->z_mm[r->n] = (int64_t)llround(e * 1000.0);
        r->rgb[r->n] = (uint32_t)(c[0] << 16 | c[1] << 8 | c[2]);
        r->n++;
    }
    fclose(fp);
    if (r->n == 0) return br_err_set(err, BR_E_FORMAT, path, "no colour entries");
    for (i = 1; i < r->n; i++)           /* insertion sort by elevation */
        for (j = i; j > 0 && r->z_mm[j - 1] > r->z_mm[j]; j--) {
            int64_t tz = r->z_mm[j]; uint32_t tc = r->rgb[j];
            r->z_mm[j] = r->z_mm[j - 1]; r->rgb[j] = r->rgb[j - 1];
            r->z_mm[j - 1] = tz; r->rgb[j - 1] = tc;
        }
    return BR_OK;
}

/* ---------------------------------------------------------------- PNG sink */

typedef struct png_sink {
    png_out *po;
    int32_t w, fmt;
    uint8_t *rgb;
    br_err *err;
} png_sink;

static br_status sink_png(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    png_sink *s = (png_sink *)user;
    int32_t y;
    (void)y0;
    for (y = 0; y < rows; y++) {
        br_status st;
        rs_to_rgb888(s->fmt, (const uint8_t *)px + (size_t)y * stride, s->w, s->rgb);
        st = png_out_rows(s->po, s->rgb, 1, (size_t)s->w * 3, s->err);
        if (st != BR_OK) return st;
    }
    return BR_OK;
}

/* ---------------------------------------------------------------- command */

static double ms_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static int usage(void)
{
    fprintf(stderr,
            "usage: bitrain render IN... -o out.png [--size WxH] [--camera EX,EY,EZ,TX,TY,TZ] [--fov DEG]\n"
            "         [--max-error M | --pixel-error P | --full [STEP]] [--bands ROWS]\n"
            "         [--format rgb565|rgb888] [--depth 32|16] [--colors FILE] [--texture PNG] [--no-cull]\n"
            "         [--sun AZ,ALT] [--ambient A] [--zscale F]\n"
            "  camera in metres: x east from the west edge, y north from the south edge, z height\n");
    return 2;
}

int cmd_render(int argc, char **argv)
{
    const char *in[64], *out = NULL, *colors = NULL, *texture = NULL;
    rs_texture tex;
    uint32_t *texpx = NULL;
    int nin = 0, i, w = 800, h = 600, have_cam = 0, mode = BT_VIEW, full_step = 0, bands = 0;
    int fmt = RS_FMT_XRGB8888, depth = RS_DEPTH32, no_cull = 0;
    double camv[6], fov = 50, max_err = 0, pix_err = 1, sun_az = 315, sun_alt = 45, ambient = 0.3, zscale = 0;
    dem_opts o;
    hf f;
    br_err err;
    hf_stats st;
    rs_ramp ramp;
    rt_scene sc;
    fx_q14 sun[3];
    cam c;
    int32_t eye[3], tg[3], znear, zfar;
    rs_vertex *verts = NULL;
    uint32_t nv = 0, *idx = NULL, nidx = 0;
    rs_prim *prims = NULL;
    int32_t nprims = 0;
    rs_frame fr;
    void *bandmem = NULL;
    png_sink ps;
    bt_tree t;
    bt_mesh m;
    void *tmem = NULL, *mmem = NULL;
    double t0, t1, t2;
    int rc = 1;

    memset(&o, 0, sizeof o);
    memset(&fr, 0, sizeof fr);
    memset(&ps, 0, sizeof ps);
    memset(&f, 0, sizeof f);
    memset(&t, 0, sizeof t);
    memset(&m, 0, sizeof m);
    for (i = 0; i < argc; i++) {
        const char *a = argv[i], *n = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-o") && n) { out = n; i++; }
        else if (!strcmp(a, "--size") && n) { if (sscanf(n, "%dx%d", &w, &h) != 2) return usage(); i++; }
        else if (!strcmp(a, "--camera") && n) {
            if (sscanf(n, "%lf,%lf,%lf,%lf,%lf,%lf", &camv[0], &camv[1], &camv[2], &camv[3], &camv[4], &camv[5]) != 6)
                return usage();
            have_cam = 1; i++;
        } else if (!strcmp(a, "--fov") && n) { fov = atof(n); i++; }
        else if (!strcmp(a, "--max-error") && n) { max_err = atof(n); mode = BT_FIDELITY; i++; }
        else if (!strcmp(a, "--pixel-error") && n) { pix_err = atof(n); mode = BT_VIEW; i++; }
        else if (!strcmp(a, "--full")) {
            full_step = 1;
            if (n && isdigit((unsigned char)n[0])) { full_step = atoi(n); i++; }
        } else if (!strcmp(a, "--bands") && n) { bands = atoi(n); i++; }
        else if (!strcmp(a, "--format") && n) {
            if (!strcmp(n, "rgb565")) fmt = RS_FMT_RGB565;
            else if (!strcmp(n, "rgb888")) fmt = RS_FMT_XRGB8888;
            else return usage();
            i++;
        } else if (!strcmp(a, "--depth") && n) { depth = atoi(n) == 16 ? RS_DEPTH16 : RS_DEPTH32; i++; }
        else if (!strcmp(a, "--colors") && n) { colors = n; i++; }
        else if (!strcmp(a, "--texture") && n) { texture = n; i++; }
        else if (!strcmp(a, "--no-cull")) no_cull = 1;
        else if (!strcmp(a, "--sun") && n) { if (sscanf(n, "%lf,%lf", &sun_az, &sun_alt) != 2) return usage(); i++; }
        else if (!strcmp(a, "--ambient") && n) { ambient = atof(n); i++; }
        else if (!strcmp(a, "--zscale") && n) { zscale = atof(n); i++; }
        else if (!strcmp(a, "-h") || !strcmp(a, "--help")) { usage(); return 0; }
        else if (a[0] == '-' && a[1]) { fprintf(stderr, "bitrain render: unknown option '%s'\n", a); return usage(); }
        else if (nin < 64) in[nin++] = a;
    }
    if (!nin || !out || w < 1 || h < 1 || w > RS_MAX_DIM || h > RS_MAX_DIM || !(fov >= 1 && fov <= 170)
        || full_step < 0 || bands < 0 || !(ambient >= 0 && ambient <= 1) || !(pix_err > 0) || max_err < 0
        || !(zscale >= 0 && zscale <= 1000))
        return usage();
    if (bands == 0 || bands > h) bands = h;

    t0 = ms_now();
    if (dem_load_many(in, nin, &o, &f, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); return 1; }
    hf_stats_get(&f, &st);
    if (colors) {
        if (read_colors(colors, &ramp, hf_z_to_mm(&f, st.zmin), hf_z_to_mm(&f, st.zmax), &err) != BR_OK) {
            fprintf(stderr, "bitrain: %s\n", err.msg);
            goto done;
        }
    } else rs_ramp_default(&ramp, hf_z_to_mm(&f, st.zmin), hf_z_to_mm(&f, st.zmax));
    rs_sun_dir((int32_t)lround(sun_az * 1000), (int32_t)lround(sun_alt * 1000), sun);
    if (rt_scene_init(&sc, &f, &ramp, sun, (int32_t)lround(ambient * FX_Q14_ONE)) != BR_OK) {
        fprintf(stderr, "bitrain: %s: invalid heightfield\n", in[0]);
        goto done;
    }
    if (texture) {   /* a colour map / orthophoto stretched over the whole grid */
        int tw, th;
        uint8_t *rgb = NULL;
        size_t k;
        if (png_read_rgb(texture, &tw, &th, &rgb, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
        if (tw < 1 || th < 1 || tw > RS_MAX_TEX || th > RS_MAX_TEX) {
            free(rgb);
            fprintf(stderr, "bitrain: %s: texture of %dx%d texels (at most %d a side)\n", texture, tw, th, RS_MAX_TEX);
            goto done;
        }
        texpx = malloc(sizeof *texpx * (size_t)tw * (size_t)th);
        if (!texpx) { free(rgb); fprintf(stderr, "bitrain: out of memory\n"); goto done; }
        for (k = 0; k < (size_t)tw * (size_t)th; k++)
            texpx[k] = (uint32_t)rgb[3 * k] << 16 | (uint32_t)rgb[3 * k + 1] << 8 | rgb[3 * k + 2];
        free(rgb);
        tex.w = tw; tex.h = th; tex.px = texpx;
        sc.tex_w = tw; sc.tex_h = th;
    }

    /* vertical scale: --zscale, or automatic for grids without georeference whose
     * relief dwarfs their extent at the loader's default 1 m spacing */
    {
        double W = (double)(f.w - 1) * f.dx_um / 1e6, H = (double)(f.h - 1) * f.dy_um / 1e6;
        double relief = (double)(hf_z_to_mm(&f, st.zmax) - hf_z_to_mm(&f, st.zmin)) / 1000;
        double ext = W > H ? W : H;
        if (zscale == 0) {
            zscale = 1;
            if (f.geo.kind == HF_GEO_NONE && relief > 0.5 * ext && relief > 0) {
                zscale = ext / (4 * relief);
                printf("%s: no georeference and %.0f m of relief over %.0f m (1 m spacing assumed): "
                       "vertical scale %.4g (override with --zscale)\n", in[0], relief, ext, zscale);
            }
        }
        if (zscale != 1) {
            sc.fr.sz_q16 = (int32_t)fmax(1, fmin((double)INT32_MAX, sc.fr.sz_q16 * zscale));
            /* the normals follow the scaled heights (core/shade.h: n = (-gx kx, -gy ky, kz);
             * scale down only, so the constants stay below 2^24) */
            if (zscale < 1) {
                sc.sc.kx = (int64_t)fmax(1, (double)llround((double)sc.sc.kx * zscale));
                sc.sc.ky = (int64_t)fmax(1, (double)llround((double)sc.sc.ky * zscale));
            } else sc.sc.kz = (int64_t)fmax(1, (double)llround((double)sc.sc.kz / zscale));
        }
    }

    /* camera (metres -> world units) */
    {
        double W = (double)(f.w - 1) * f.dx_um / 1e6, H = (double)(f.h - 1) * f.dy_um / 1e6;
        double zmin = (double)hf_z_to_mm(&f, st.zmin) / 1000 * zscale, zmax = (double)hf_z_to_mm(&f, st.zmax) / 1000 * zscale;
        double ext = W > H ? W : H, dist, scale = ldexp(1.0, sc.shift);
        if (!have_cam) {
            /* from the south-west at 35 degrees elevation, at 3/4 of the distance at which
             * the terrain's bounding sphere would fit the vertical field of view (the
             * sphere is loose for a flat tile: this fills the frame, the nearest corner
             * may touch the bottom edge) */
            double R = 0.5 * sqrt(W * W + H * H + (zmax - zmin) * (zmax - zmin));
            double d = 0.75 * R / sin(fov / 2 * 3.14159265358979323846 / 180);
            double el = 35 * 3.14159265358979323846 / 180;
            camv[3] = 0.5 * W; camv[4] = 0.5 * H; camv[5] = 0.5 * (zmin + zmax);
            camv[0] = camv[3] - d * cos(el) * 0.7071; camv[1] = camv[4] - d * cos(el) * 0.7071;
            camv[2] = camv[5] + d * sin(el);
        }
        for (i = 0; i < 3; i++) {
            double e = camv[i] * scale, tt = camv[3 + i] * scale;
            if (fabs(e) > CAM_COORD_MAX || fabs(tt) > CAM_COORD_MAX) {
                fprintf(stderr, "bitrain render: camera too far from the terrain (world unit 2^%d m)\n", -sc.shift);
                goto done;
            }
            eye[i] = (int32_t)lround(e); tg[i] = (int32_t)lround(tt);
        }
        dist = sqrt((camv[0] - camv[3]) * (camv[0] - camv[3]) + (camv[1] - camv[4]) * (camv[1] - camv[4])
                    + (camv[2] - camv[5]) * (camv[2] - camv[5]));
        /* 1/w depth: near as large as the view allows (resolution ~ z^2 / near):
         * dist/2000, but at most half the eye's height above the ground below it (or
         * above the highest sample when outside the grid), at least 5 cm */
        {
            double gx = camv[0] / ((double)f.dx_um / 1e6), gy = (double)(f.h - 1) - camv[1] / ((double)f.dy_um / 1e6);
            double ground = zmax, nearm;
            if (gx >= 0 && gy >= 0 && gx <= f.w - 1 && gy <= f.h - 1) {
                int32_t zs = f.z[(size_t)lround(gy) * (size_t)f.w + (size_t)lround(gx)];
                if (zs != HF_NODATA) ground = (double)hf_z_to_mm(&f, zs) / 1000 * zscale;
            }
            nearm = fmin(dist / 2000, 0.5 * fabs(camv[2] - ground));
            znear = (int32_t)lround(fmax(0.05, nearm) * scale);
        }
        zfar = (int32_t)fmin((double)CAM_COORD_MAX, (4 * (dist + ext) + fabs(zmax) + fabs(zmin)) * scale);
        if (znear < 1) znear = 1;
        if (zfar <= znear) zfar = znear + 1;
        if (cam_look_at(&c, eye, tg, (int32_t)lround(fov * 1000), w, h, znear, zfar) != BR_OK) {
            fprintf(stderr, "bitrain render: bad camera (eye equals target?)\n");
            goto done;
        }
    }

    /* mesh */
    if (full_step > 0) {
        int32_t gw = (f.w - 1) / full_step + 1, gh = (f.h - 1) / full_step + 1, x, y;
        nv = (uint32_t)gw * (uint32_t)gh;
        verts = malloc(sizeof *verts * nv);
        idx = malloc(sizeof *idx * (size_t)2 * (size_t)gw * (size_t)(gh - 1 > 0 ? gh - 1 : 1));
        prims = malloc(sizeof *prims * (size_t)(gh > 1 ? gh - 1 : 1));
        if (!verts || !idx || !prims) { fprintf(stderr, "bitrain: out of memory\n"); goto done; }
        for (y = 0; y < gh; y++)
            for (x = 0; x < gw; x++) {
                int32_t z = f.z[(size_t)y * full_step * (size_t)f.w + (size_t)x * full_step];
                rt_vertex(&sc, x * full_step, y * full_step, z == HF_NODATA ? 0 : z, &verts[y * gw + x]);
            }
        /* row strips, south-west first vertex: CCW seen from +z (row y is north of y+1) */
        for (y = 0; y + 1 < gh; y++) {
            uint32_t *s = idx + nidx;
            for (x = 0; x < gw; x++) {
                s[2 * x] = (uint32_t)(y * gw + x);
                s[2 * x + 1] = (uint32_t)((y + 1) * gw + x);
            }
            prims[nprims].kind = RS_STRIP; prims[nprims].n = (uint32_t)(2 * gw); prims[nprims].idx = s;
            nprims++; nidx += (uint32_t)(2 * gw);
        }
    } else {
        bt_params bp;
        uint64_t ntri = 0;
        void *scratch;
        size_t tb = bt_mem_size(f.w, f.h), sb = bt_scratch_size(f.w, f.h), mb;
        uint32_t cap;
        tmem = malloc(tb);
        scratch = malloc(sb);
        if (!tmem || !scratch) { free(scratch); fprintf(stderr, "bitrain: out of memory\n"); goto done; }
        if (bt_build(&t, &f, BT_METRIC_EXACT, tmem, tb, scratch, sb) != BR_OK) {
            free(scratch);
            fprintf(stderr, "bitrain: %s: cannot build the bitree\n", in[0]);
            goto done;
        }
        free(scratch);
        memset(&bp, 0, sizeof bp);
        bp.mode = mode;
        bp.max_err = bt_mm_to_units(&f, (int64_t)llround(max_err * 1000));
        bp.c = &c;
        bp.fr = sc.fr;
        bp.pixel_err_q8 = (int32_t)lround(pix_err * 256);
        if (bt_count(&t, &bp, &ntri) != BR_OK) { fprintf(stderr, "bitrain: bad mesh parameters\n"); goto done; }
        cap = (uint32_t)(ntri + 16 > 16000000 ? 16000000 : ntri + 16);
        mb = bt_mesh_mem_size(cap);
        mmem = malloc(mb);
        if (!mmem || bt_mesh_init(&m, cap, mmem, mb) != BR_OK || bt_extract(&t, &bp, &m) != BR_OK) {
            fprintf(stderr, "bitrain: cannot extract the mesh\n");
            goto done;
        }
        nv = m.nv;
        verts = malloc(sizeof *verts * (nv ? nv : 1));
        prims = malloc(sizeof *prims);
        if (!verts || !prims) { fprintf(stderr, "bitrain: out of memory\n"); goto done; }
        rt_from_mesh(&sc, &m, verts);
        prims[0].kind = RS_STRIP; prims[0].n = m.ns; prims[0].idx = m.strip;
        nprims = 1;
    }
    t1 = ms_now();

    /* render in bands, streaming to the PNG */
    fr.w = w; fr.h = h; fr.fmt = fmt; fr.depth = depth; fr.no_cull = no_cull;
    fr.clear_rgb = 0x99ccffu;
    fr.tex = texture ? &tex : NULL;
    fr.v = verts; fr.nv = nv; fr.prims = prims; fr.nprims = nprims;
    fr.cache = malloc(rs_cache_mem_size(nv ? nv : 1));
    fr.chunks = bands < h ? malloc(rs_chunk_mem_size(prims, nprims) + 4) : NULL;
    bandmem = malloc(rs_band_mem_size(w, bands, fmt, depth));
    ps.rgb = malloc((size_t)w * 3);
    if (!fr.cache || !bandmem || !ps.rgb) { fprintf(stderr, "bitrain: out of memory\n"); goto done; }
    cam_viewproj(&c, &fr.vp);
    if (rs_frame_prepare(&fr) != BR_OK) { fprintf(stderr, "bitrain: bad frame parameters\n"); goto done; }
    if (png_out_open(&ps.po, out, w, h, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
    ps.w = w; ps.fmt = fmt; ps.err = &err;
    if (rs_render(&fr, bands, bandmem, sink_png, &ps) != BR_OK) {
        png_out_abort(ps.po);
        fprintf(stderr, "bitrain: %s\n", err.msg[0] ? err.msg : "render failed");
        goto done;
    }
    if (png_out_close(ps.po, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
    t2 = ms_now();
    printf("%s: %dx%d, %u vertices, %s, %u triangles drawn (%u clipped), load+mesh %.1f ms, "
           "render+write %.1f ms, world unit 2^%d m, band %d rows (%zu bytes + %zu bytes vertex cache)\n",
           out, w, h, nv, full_step ? "full grid" : (mode == BT_FIDELITY ? "bitree fidelity" : "bitree view"),
           fr.stat_tris, fr.stat_clipped, t1 - t0, t2 - t1, -sc.shift, bands,
           rs_band_mem_size(w, bands, fmt, depth), rs_cache_mem_size(nv));
    rc = 0;
done:
    free(texpx);
    free(verts); free(idx); free(prims); free(fr.cache); free(fr.chunks); free(bandmem); free(ps.rgb); free(tmem); free(mmem);
    dem_free(&f);
    return rc;
}
