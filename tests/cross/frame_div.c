/* tests/cross/frame_div.c — the default scene's terrain frame built from core/ and
 * raster/ alone (no zlib, libpng or threads), for tests/cross/div64.sh, which runs it
 * under qemu-arm with the instruction-count plugin (benchmarks/qemu_insn.c) and counts
 * the calls of libgcc's 64-bit division helpers made by its frames.
 *
 *   frame_div N47E009.hgt PATH.cam FRAMES [WxH]
 *
 * Set-up (not counted by the check: it runs the same with FRAMES 0): the raw SRTM
 * tile (1201 x 1201 big-endian int16, -32768 void) with the spacing platform/load.c
 * gives N47E009 (`bitrain info`: 62.786282 x 92.650490 m), the relative ramp, sun
 * 315/45, ambient 0.3, the bitree, the mesh, the parts, the vertex caches, the
 * shading cache (what platform/scene.c's scene_open, scene_tree and scene_reserve
 * do).  Then FRAMES frames of the path (line i for frame i, wrapping), each what
 * `bitrain bench --scene default` times: the view selection in parts (serially, in
 * the order a pool would take them), the joins and vertex set-up
 * (rt_from_mesh_range, rt_from_mesh_pending), rs_frame_prepare and the terrain pass
 * in bands, in the board configuration of issue 20 (RGB565, 16-bit depth, 16-row
 * bands), 1 px, hysteresis 64/256, geomorph 128/256.  Prints one line per frame:
 * triangles and a hash of the pixels. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/bitree.h"
#include "core/cam.h"
#include "raster/frame.h"
#include "raster/raster.h"
#include "raster/terrain.h"

enum { SIDE = 1201, MAX_TRI = 400000, PART_TRI = 4096, BAND = 16 };

static uint32_t px_hash;

static br_status sink_hash(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    const uint8_t *p = (const uint8_t *)px;
    int32_t w = *(const int32_t *)user, y, x;
    (void)y0;
    for (y = 0; y < rows; y++)
        for (x = 0; x < 2 * w; x++) px_hash = (px_hash ^ p[(size_t)y * stride + (size_t)x]) * 16777619u;
    return BR_OK;
}

static int read_path(const char *name, double (*cams)[6], int max)
{
    FILE *fp = fopen(name, "r");
    char line[512];
    int n = 0;
    if (!fp) return 0;
    while (n < max && fgets(line, sizeof line, fp)) {
        double *c = cams[n];
        if (line[0] == '#' || sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf", c, c + 1, c + 2, c + 3, c + 4, c + 5) != 6) continue;
        n++;
    }
    fclose(fp);
    return n;
}

/* platform/scene.c scene_camera's near and far planes, from the eye's ground height */
static int make_cam(const hf *f, const rt_scene *rt, const double *k, int32_t w, int32_t h, cam *out)
{
    double scale = ldexp(1.0, rt->shift), dist = 0, nearm, ground, zmax = (double)rt->zhi;
    double ext = (SIDE - 1) * 92.650490, gx = k[0] * 1e6 / (double)f->dx_um, gy = (SIDE - 1) - k[1] * 1e6 / (double)f->dy_um;
    int32_t e[3], t[3], znear, zfar, i;
    for (i = 0; i < 3; i++) {
        e[i] = (int32_t)lround(k[i] * scale);
        t[i] = (int32_t)lround(k[3 + i] * scale);
        dist += (k[i] - k[3 + i]) * (k[i] - k[3 + i]);
    }
    dist = sqrt(dist);
    ground = gx >= 0 && gy >= 0 && gx <= SIDE - 1 && gy <= SIDE - 1 ? f->z[lround(gy) * SIDE + lround(gx)] : zmax;
    nearm = fmin(dist / 2000, 0.5 * fabs(k[2] - ground));
    znear = (int32_t)lround(fmax(0.05, nearm) * scale);
    zfar = (int32_t)fmin((double)CAM_COORD_MAX, (4 * (dist + ext) + fabs(zmax) + fabs((double)rt->zlo)) * scale);
    if (znear < 1) znear = 1;
    if (zfar <= znear) zfar = znear + 1;
    return cam_look_at(out, e, t, 60000, w, h, znear, zfar) == BR_OK;
}

int main(int argc, char **argv)
{
    static double cams[4096][6];
    hf f;
    hf_stats st;
    rs_ramp ramp;
    rt_scene rt;
    fx_q14 sun[3];
    bt_tree tree;
    bt_mesh mesh;
    bt_parts *parts;
    rs_vertex *verts;
    rs_cvert *vcache;
    int16_t *chunks;
    rs_prim prim, longest;
    unsigned char *raw;
    void *tm, *scr, *mm, *pm, *lit, *band;
    size_t band_size;
    int32_t w = 320, h = 240, i;
    int ncam, frames;
    FILE *fp;
    if (argc < 4) { fprintf(stderr, "usage: frame_div N47E009.hgt PATH.cam FRAMES [WxH]\n"); return 2; }
    frames = atoi(argv[3]);
    if (argc > 4 && sscanf(argv[4], "%dx%d", &w, &h) != 2) return 2;
    ncam = read_path(argv[2], cams, 4096);
    fp = fopen(argv[1], "rb");
    raw = malloc((size_t)SIDE * SIDE * 2);
    memset(&f, 0, sizeof f);
    f.z = malloc((size_t)SIDE * SIDE * 4);
    if (!fp || !raw || !f.z || fread(raw, 2, (size_t)SIDE * SIDE, fp) != (size_t)SIDE * SIDE || ncam < 1) {
        fprintf(stderr, "frame_div: cannot read %s or %s\n", argv[1], argv[2]);
        return 1;
    }
    fclose(fp);
    for (i = 0; i < SIDE * SIDE; i++) f.z[i] = (int16_t)(raw[2 * i] << 8 | raw[2 * i + 1]);
    free(raw);
    f.w = f.h = SIDE; f.z_num = f.z_den = 1; f.dx_um = 62786282; f.dy_um = 92650490;
    hf_stats_get(&f, &st);
    rs_ramp_default(&ramp, hf_z_to_mm(&f, st.zmin), hf_z_to_mm(&f, st.zmax));
    rs_sun_dir(315000, 45000, sun);
    if (rt_scene_init(&rt, &f, &ramp, sun, 4915) != BR_OK) return 1;
    tm = malloc(bt_mem_size(f.w, f.h)); scr = malloc(bt_scratch_size(f.w, f.h));
    mm = malloc(bt_mesh_mem_size(MAX_TRI)); pm = malloc(bt_parts_mem_size(PART_TRI));
    lit = malloc(rt_cache_mem_size(&rt));
    if (!tm || !scr || !mm || !pm || !lit
        || bt_build(&tree, &f, BT_METRIC_EXACT, tm, bt_mem_size(f.w, f.h), scr, bt_scratch_size(f.w, f.h)) != BR_OK
        || bt_mesh_init(&mesh, MAX_TRI, mm, bt_mesh_mem_size(MAX_TRI)) != BR_OK
        || bt_parts_init(&parts, PART_TRI, pm, bt_parts_mem_size(PART_TRI)) != BR_OK
        || rt_scene_cache(&rt, lit, rt_cache_mem_size(&rt)) != BR_OK) { fprintf(stderr, "frame_div: set-up failed\n"); return 1; }
    free(scr);
    verts = malloc(sizeof *verts * mesh.cap_v);
    vcache = malloc(rs_cache_mem_size(mesh.cap_v));
    longest.kind = RS_STRIP; longest.n = mesh.cap_s; longest.idx = NULL;
    chunks = malloc(rs_chunk_mem_size(&longest, 1));
    band = NULL; band_size = 0;
    if (!verts || !vcache || !chunks) return 1;
    for (i = 0; i < frames; i++) {
        cam c;
        bt_params bp;
        rs_frame fr;
        rs_pass terrain;
        rs_pipe pipe;
        uint32_t n = 0, k;
        br_status s;
        if (!make_cam(&f, &rt, cams[i % ncam], w, h, &c)) return 1;
        memset(&bp, 0, sizeof bp);
        bp.mode = BT_VIEW; bp.c = &c; bp.fr = rt.fr;
        bp.pixel_err_q8 = 256; bp.hyst_q8 = 64; bp.morph_q8 = 128;
        s = bt_extract_begin(parts, &tree, &bp, &mesh, &n);
        for (k = 0; s == BR_OK && k < n; k++) bt_extract_part(parts, k);
        if (s == BR_OK) s = bt_extract_end(parts, &n);
        if (s != BR_OK) { fprintf(stderr, "frame_div: extraction failed (%d)\n", (int)s); return 1; }
        for (k = 0; k < n; k++) {
            uint32_t v0, nv;
            bt_extract_join(parts, k, &v0, &nv);
            rt_from_mesh_range(&rt, &mesh, v0, nv, verts);
        }
        if (n) rt_from_mesh_pending(&rt, &mesh, verts);
        else rt_from_mesh(&rt, &mesh, verts);
        prim.kind = RS_STRIP; prim.n = mesh.ns; prim.idx = mesh.strip;
        memset(&fr, 0, sizeof fr);
        fr.w = w; fr.h = h; fr.fmt = RS_FMT_RGB565; fr.depth = RS_DEPTH16; fr.clear_rgb = 0x99ccffu;
        fr.v = verts; fr.nv = mesh.nv; fr.cache = vcache; fr.prims = &prim; fr.nprims = 1; fr.chunks = chunks;
        cam_viewproj(&c, &fr.vp);
        memset(&pipe, 0, sizeof pipe);
        pipe.w = w; pipe.h = h; pipe.fmt = RS_FMT_RGB565; pipe.depth = RS_DEPTH16;
        if (rs_frame_prepare(&fr) != BR_OK || rs_pass_terrain(&terrain, &fr) != BR_OK || rs_pipe_add(&pipe, &terrain) != BR_OK)
            return 1;
        if (!band) { band_size = rs_pipe_mem_size(&pipe, BAND); band = malloc(band_size); if (!band) return 1; }
        px_hash = 2166136261u;
        if (rs_pipe_run(&pipe, BAND, band, band_size, sink_hash, &w, NULL) != BR_OK) return 1;
        printf("frame %d: %u triangles, pixels %08x\n", i, mesh.ntri, px_hash);
    }
    free(band); free(chunks); free(vcache); free(verts); free(lit); free(pm); free(mm); free(tm); free(f.z);
    return 0;
}
