/* platform/cmd_mesh.c — bitrain mesh: export a bitree mesh (core/bitree.h) as
 * OBJ, PLY or binary STL, in metres: x east from column 0, y north from the
 * southern row, z up; faces counter-clockwise seen from above.
 *
 *   bitrain mesh IN... --max-error M -o out.{obj,ply,stl} [--json]
 *                [--metric exact|curvature] [--no-line-triangles]
 *                [--camera EX,EY,EZ,TX,TY,TZ --fov DEG --pixel-error P --size WxH]
 *                [--budget N]
 * Prints triangles, vertices, fictitious points, strip references, line
 * triangles and the TRUE maximum vertical error (evaluated at every grid sample),
 * or the same as one JSON object with --json.  Camera coordinates are metres in
 * the same frame as the output. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "platform/campath.h"
#include "platform/cmd.h"
#include "platform/load.h"
#include "platform/dem_args.h"
#include "platform/opt.h"
#include "core/bitree.h"
#include "core/cam.h"
#include "platform/tree_file.h"

#define MESH_SYNOPSIS "IN... [-o OUT.obj|.ply|.stl] [options]"

/* Output format from the file name: 0 OBJ, 1 PLY, 2 STL, -1 unknown. */
static int out_kind(const char *path)
{
    const char *d = strrchr(path, '.'), *ext = d ? d + 1 : "";
    return !strcmp(ext, "obj") ? 0 : !strcmp(ext, "ply") ? 1 : !strcmp(ext, "stl") ? 2 : -1;
}

/* Writes the mesh to fp (opened by the caller before any work, so that a path that
 * cannot be written fails at once) and closes it. */
static int write_mesh(FILE *fp, const char *out, int kind, const hf *f, const bt_mesh *m, const uint32_t *list,
                      uint32_t nt, br_err *e)
{
    uint32_t i;
    double sx = (double)f->dx_um * 1e-6, sy = (double)f->dy_um * 1e-6, sz = (double)f->z_num / f->z_den;
#define VX(i) (m->v[i].x * sx)
#define VY(i) ((f->h - 1 - m->v[i].y) * sy)
#define VZ(i) (m->v[i].z * sz)
    if (kind == 0) {
        fprintf(fp, "# bitrain mesh: %u vertices, %u triangles, metres (x east, y north, z up)\n", m->nv, nt);
        for (i = 0; i < m->nv; i++) fprintf(fp, "v %.6f %.6f %.6f\n", VX(i), VY(i), VZ(i));
        for (i = 0; i < nt; i++) fprintf(fp, "f %u %u %u\n", list[3 * i] + 1, list[3 * i + 1] + 1, list[3 * i + 2] + 1);
    } else if (kind == 1) {
        fprintf(fp, "ply\nformat ascii 1.0\ncomment bitrain mesh, metres (x east, y north, z up)\n"
                    "element vertex %u\nproperty float x\nproperty float y\nproperty float z\n"
                    "property uchar fictitious\nelement face %u\nproperty list uchar int vertex_indices\n"
                    "end_header\n", m->nv, nt);
        for (i = 0; i < m->nv; i++)
            fprintf(fp, "%.6f %.6f %.6f %d\n", VX(i), VY(i), VZ(i), m->v[i].state == BT_F);
        for (i = 0; i < nt; i++) fprintf(fp, "3 %u %u %u\n", list[3 * i], list[3 * i + 1], list[3 * i + 2]);
    } else {
        unsigned char hdr[80];
        memset(hdr, 0, sizeof hdr);
        memcpy(hdr, "bitrain mesh, metres, x east y north z up", 41);
        fwrite(hdr, 1, 80, fp);
        {
            unsigned char c4[4] = { (unsigned char)nt, (unsigned char)(nt >> 8), (unsigned char)(nt >> 16),
                                    (unsigned char)(nt >> 24) };
            fwrite(c4, 1, 4, fp);
        }
        for (i = 0; i < nt; i++) {
            float v[12];
            int k;
            unsigned char rec[50];
            double ax = VX(list[3 * i]), ay = VY(list[3 * i]), az = VZ(list[3 * i]);
            double bx = VX(list[3 * i + 1]) - ax, by = VY(list[3 * i + 1]) - ay, bz = VZ(list[3 * i + 1]) - az;
            double cx = VX(list[3 * i + 2]) - ax, cy = VY(list[3 * i + 2]) - ay, cz = VZ(list[3 * i + 2]) - az;
            double nx = by * cz - bz * cy, ny = bz * cx - bx * cz, nz = bx * cy - by * cx;
            double l = nx * nx + ny * ny + nz * nz;
            l = l > 0 ? 1.0 / __builtin_sqrt(l) : 0;
            v[0] = (float)(nx * l); v[1] = (float)(ny * l); v[2] = (float)(nz * l);
            for (k = 0; k < 3; k++) {
                uint32_t vi = list[3 * i + k];
                v[3 + 3 * k] = (float)VX(vi); v[4 + 3 * k] = (float)VY(vi); v[5 + 3 * k] = (float)VZ(vi);
            }
            for (k = 0; k < 12; k++) {
                uint32_t u;
                memcpy(&u, &v[k], 4);
                rec[4 * k] = (unsigned char)u; rec[4 * k + 1] = (unsigned char)(u >> 8);
                rec[4 * k + 2] = (unsigned char)(u >> 16); rec[4 * k + 3] = (unsigned char)(u >> 24);
            }
            rec[48] = rec[49] = 0;
            fwrite(rec, 1, 50, fp);
        }
    }
#undef VX
#undef VY
#undef VZ
    if (fclose(fp) != 0) return br_err_set(e, BR_E_IO, out, "write failed");
    return BR_OK;
}

int cmd_mesh(int argc, char **argv)
{
    const char *files[64], *out = NULL, *save_tree = NULL, *tree_in = NULL;
    int nf = 0, json = 0, nolines = 0, have_cam = 0, rc = 1, kind, r, metric_choice = 0, vsize[2] = { 640, 480 };
    int32_t metric;
    double maxerr = 1.0, fov = 60, pixerr = 1.0, camv[6];
    long budget = 0;
    hf f;
    br_err e;
    dem_opts o;
    bt_tree t;
    bt_params p;
    bt_mesh m;
    void *mem = NULL, *scr = NULL, *mm = NULL;
    uint32_t *list = NULL, nt;
    uint64_t cnt;
    cam c;
    FILE *fp = NULL;
    dem_args da;
    opt_spec dem_t[DEM_ARGS_N];
    const opt_spec own[] = {
        { "-o", OPT_STR, &out, 0, 0, 0, NULL, "OUT", ".obj, .ply or .stl (binary); omit to only print the figures", NULL },
        { "--max-error", OPT_NUM, &maxerr, 0, 100000, 0, NULL, "M", "fidelity mesh: true vertical error <= M metres (default 1)", NULL },
        { "--json", OPT_FLAG, &json, 0, 0, 0, NULL, NULL, "print the figures as one JSON object", NULL },
        { "--save-tree", OPT_STR, &save_tree, 0, 0, 0, NULL, "FILE", "save the bitree (attach it later with --tree)", NULL },
        { "--tree", OPT_STR, &tree_in, 0, 0, 0, NULL, "FILE", "attach the bitree saved by --save-tree instead of building it", NULL },
        { "--metric", OPT_CHOICE, &metric_choice, 0, 0, 0, "exact|curvature", "K",
          "exact (a true bound, default) or curvature (001's indicator)", NULL },
        { "--no-line-triangles", OPT_FLAG, &nolines, 0, 0, 0, NULL, NULL, "count the strip as a list without line triangles (004)", NULL },
        { "--camera", OPT_NUMS, camv, -CAMPATH_COORD_MAX, CAMPATH_COORD_MAX, 6, NULL, "EX,EY,EZ,TX,TY,TZ",
          "view-dependent mesh: eye and target in metres (x east, y north, z up)", &have_cam },
        { "--fov", OPT_NUM, &fov, 1, 170, 0, NULL, "DEG", "vertical field of view (default 60)", NULL },
        { "--pixel-error", OPT_NUM, &pixerr, 0.01, 1000, 0, NULL, "P", "screen-space error threshold, pixels (default 1)", NULL },
        { "--size", OPT_SIZE, vsize, 1, 16384, 0, NULL, "WxH", "viewport (default 640x480)", NULL },
        { "--budget", OPT_LONG, &budget, 1, 268435456, 0, NULL, "N",
          "at most N triangles, spent where the (screen-space) error is largest", NULL },
        OPT_END
    };
    const opt_spec *const tables[] = { own, dem_t, NULL };
    memset(&o, 0, sizeof o);
    memset(&e, 0, sizeof e);
    memset(&f, 0, sizeof f);
    dem_args_table(&da, &o, dem_t);
    r = opt_parse("mesh", MESH_SYNOPSIS, tables, argc, argv, files, 64, &nf);
    if (r != OPT_OK) return r == OPT_HELP ? 0 : 2;
    if (dem_args_finish(&da, "mesh") != OPT_OK) return 2;
    if (nf == 0) { fprintf(stderr, "bitrain mesh: no input file (`bitrain mesh --help`)\n"); return 2; }
    metric = metric_choice ? BT_METRIC_CURVATURE : BT_METRIC_EXACT;
    kind = out ? out_kind(out) : -1;
    if (out && kind < 0) {
        fprintf(stderr, "bitrain mesh: %s: unknown output format (want .obj, .ply or .stl)\n", out);
        return 2;   /* before any work: the mesh of a large DEM takes a while */
    }
    if (out && !(fp = fopen(out, kind == 2 ? "wb" : "w"))) {
        fprintf(stderr, "bitrain mesh: %s: cannot open for writing\n", out);
        return 1;
    }
    if (dem_load_many(files, nf, &o, &f, &e) != BR_OK) { fprintf(stderr, "bitrain mesh: %s\n", e.msg); goto done; }
    if (tree_in) {
        if (tree_file_attach(&t, &f, tree_in, &mem, &e) != BR_OK) { fprintf(stderr, "bitrain mesh: %s\n", e.msg); goto done; }
        if (t.metric != metric) {
            fprintf(stderr, "bitrain mesh: %s: saved with the other --metric\n", tree_in);
            goto done;
        }
    } else {
        mem = malloc(bt_mem_size(f.w, f.h));
        scr = malloc(bt_scratch_size(f.w, f.h));
        if (!mem || !scr) { fprintf(stderr, "bitrain mesh: %s: out of memory\n", files[0]); goto done; }
        if (bt_build(&t, &f, metric, mem, bt_mem_size(f.w, f.h), scr, bt_scratch_size(f.w, f.h)) != BR_OK) {
            fprintf(stderr, "bitrain mesh: %s: cannot build the bitree\n", files[0]);
            goto done;
        }
        free(scr); scr = NULL;
    }
    if (save_tree && tree_file_save(&t, save_tree, &e) != BR_OK) { fprintf(stderr, "bitrain mesh: %s\n", e.msg); goto done; }
    memset(&p, 0, sizeof p);
    p.mode = BT_FIDELITY;
    p.strip_order = BT_ORDER_BEST;   /* an export: the shortest strip in every mode */
    p.max_err = bt_mm_to_units(&f, (int64_t)(maxerr * 1000.0 + 1e-6));
    if (have_cam) {
        int32_t ushift, eye[3], tgt[3], k;
        double scale;
        if (bt_frame_auto(&f, &p.fr, &ushift) != BR_OK) { fprintf(stderr, "bitrain mesh: %s: grid too large for a world frame\n", files[0]); goto done; }
        scale = ushift >= 0 ? (double)(1 << ushift) : 1.0 / (1 << -ushift);
        for (k = 0; k < 3; k++) { eye[k] = (int32_t)(camv[k] * scale); tgt[k] = (int32_t)(camv[3 + k] * scale); }
        if (cam_look_at(&c, eye, tgt, (int32_t)(fov * 1000), vsize[0], vsize[1], (int32_t)(scale / 4 > 1 ? scale / 4 : 1),
                        (int32_t)(1 << 29)) != BR_OK) {
            fprintf(stderr, "bitrain mesh: bad camera (eye == target, fov or size out of range)\n");
            goto done;
        }
        p.mode = BT_VIEW;
        p.c = &c;
        p.pixel_err_q8 = (int32_t)lround(pixerr * 256);
        p.morph_q8 = 256;   /* geomorph: a vertex reaches its real height at 2x the threshold */
    }
    if (budget > 0) {
        p.mode = BT_BUDGET;
        p.budget = (uint32_t)budget;
        if (!have_cam) p.mode = BT_FIDELITY;   /* fidelity with a cap: error priority */
        cnt = (uint64_t)budget;
    } else if (bt_count(&t, &p, &cnt) != BR_OK) { fprintf(stderr, "bitrain mesh: bad parameters\n"); goto done; }
    if (cnt < 2) cnt = 2;
    if (cnt > 0x10000000ull) cnt = 0x10000000ull;
    mm = malloc(bt_mesh_mem_size((uint32_t)cnt));
    if (!mm || bt_mesh_init(&m, (uint32_t)cnt, mm, bt_mesh_mem_size((uint32_t)cnt)) != BR_OK) {
        fprintf(stderr, "bitrain mesh: %s: out of memory for %llu triangles\n", files[0], (unsigned long long)cnt);
        goto done;
    }
    if (bt_extract(&t, &p, &m) != BR_OK) { fprintf(stderr, "bitrain mesh: %s: mesh does not fit\n", files[0]); goto done; }
    list = malloc(12 * ((size_t)m.ntri + 1));
    if (!list) goto done;
    nt = bt_strip_to_list(&m, list);
    {
        int32_t ex, ey;
        int64_t eq = bt_true_error_q16(&t, &m, &ex, &ey);
        double em = (double)eq / 65536.0 * f.z_num / f.z_den;
        uint32_t refs = nolines ? 3 * nt : m.ns, lines = nolines ? 0 : m.nline;
        if (json)
            printf("{\"triangles\": %u, \"vertices\": %u, \"fictitious\": %u, \"strip_refs\": %u, "
                   "\"line_triangles\": %u, \"max_error\": %.6f}\n", nt, m.nv, m.nfict, refs, lines, em);
        else
            printf("triangles %u\nvertices %u\nfictitious %u\nstrip references %u (%.3f per triangle)\n"
                   "line triangles %u\ntrue max error %.6f m (at column %d, row %d)\n",
                   nt, m.nv, m.nfict, refs, nt ? (double)refs / nt : 0.0, lines, em, ex, ey);
    }
    if (fp) {
        br_status ws = write_mesh(fp, out, kind, &f, &m, list, nt, &e);
        fp = NULL;
        if (ws != BR_OK) { fprintf(stderr, "bitrain mesh: %s\n", e.msg); goto done; }
    }
    rc = 0;
done:
    if (fp) { fclose(fp); remove(out); }   /* nothing written: no empty file left behind */
    free(list); free(mm); free(mem); free(scr);
    dem_free(&f);
    return rc;
}
