#define _POSIX_C_SOURCE 200809L
/* tests/test_cli_mesh.c — `bitrain mesh` end to end, as a user runs it: the
 * command writes OBJ / PLY / STL and prints its figures (--json); the test reads
 * the files back, maps the vertices in metres onto the grid again and has the
 * independent referee (tests/support/meshcheck) judge the exported triangles
 * against every sample of the real DEM: watertight, no T-junctions, true error
 * <= --max-error, and the printed figures equal what the files hold. */
#include <fcntl.h>
#include <math.h>
#include <unistd.h>
#include "tests/test.h"
#include "tests/support/meshcheck.h"
#include "platform/cmd.h"
#include "platform/load.h"

/* Runs cmd_mesh with stdout sent to file out; returns its exit code. */
/* Sends file descriptor fd to path (returns the saved descriptor, -1 on failure), and back. */
static int redirect(int fd, const char *path)
{
    int saved = dup(fd), f = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (saved < 0 || f < 0) return -1;
    dup2(f, fd);
    close(f);
    return saved;
}

static void restore(int fd, int saved)
{
    dup2(saved, fd);
    close(saved);
}

/* Runs a command (cmd_mesh, cmd_render) with its standard output sent to out. */
static int run_cmd(int (*cmd)(int, char **), int argc, char **argv, const char *out)
{
    int saved, rc;
    fflush(stdout);
    if ((saved = redirect(1, out)) < 0) return -1;
    rc = cmd(argc, argv);
    fflush(stdout);
    restore(1, saved);
    return rc;
}

static int run_mesh(int argc, char **argv, const char *out) { return run_cmd(cmd_mesh, argc, argv, out); }
static int run_render(int argc, char **argv, const char *out) { return run_cmd(cmd_render, argc, argv, out); }

typedef struct figs { long tri, vert, fict, refs, lines; double err; } figs;

static int read_json(const char *path, figs *g)
{
    FILE *f = fopen(path, "r");
    char line[512];
    int n;
    if (!f) return -1;
    if (!fgets(line, sizeof line, f)) { fclose(f); return -1; }
    fclose(f);
    n = sscanf(line, "{\"triangles\": %ld, \"vertices\": %ld, \"fictitious\": %ld, \"strip_refs\": %ld, "
               "\"line_triangles\": %ld, \"max_error\": %lf}", &g->tri, &g->vert, &g->fict, &g->refs,
               &g->lines, &g->err);
    return n == 6 ? 0 : -1;
}

/* Reads an OBJ written by bitrain mesh back onto grid f: vertex (x, y, z metres)
 * -> column x / dx, row (h - 1) - y / dy, height z / unit (exact: micrometres
 * are written, the units here are 1 m).  Judges
 * the faces with the referee; *nf, *nv: counts in the file. */
static int judge_obj(const char *path, const hf *f, int partial, mc_report *r, long *nv, long *nf)
{
    FILE *fp = fopen(path, "r");
    char line[256];
    long cap = 1024, capf = 1024;
    mc_vert *v = malloc(sizeof *v * (size_t)cap);
    int32_t *t = malloc(sizeof *t * 3 * (size_t)capf);
    double dx = (double)f->dx_um / 1e6, dy = (double)f->dy_um / 1e6, unit = (double)f->z_num / f->z_den;
    int ok = 0, bad = 0;
    *nv = *nf = 0;
    if (!fp || !v || !t) { if (fp) fclose(fp); free(v); free(t); return -1; }
    while (fgets(line, sizeof line, fp)) {
        double x, y, z;
        long a, b, c;
        if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) == 3) {
            double col = x / dx, row = (f->h - 1) - y / dy, zq = z / unit;
            if (*nv == cap) { cap *= 2; v = realloc(v, sizeof *v * (size_t)cap); if (!v) { bad = 1; break; } }
            /* positions are grid samples, heights whole units */
            if (fabs(col - floor(col + 0.5)) > 1e-3 || fabs(row - floor(row + 0.5)) > 1e-3 || fabs(zq - floor(zq + 0.5)) > 1e-3)
                bad = 1;
            v[*nv].x = (int32_t)lround(col); v[*nv].y = (int32_t)lround(row); v[*nv].zq = llround(zq);
            (*nv)++;
        } else if (sscanf(line, "f %ld %ld %ld", &a, &b, &c) == 3) {
            if (*nf == capf) { capf *= 2; t = realloc(t, sizeof *t * 3 * (size_t)capf); if (!t) { bad = 1; break; } }
            t[3 * *nf] = (int32_t)(a - 1); t[3 * *nf + 1] = (int32_t)(b - 1); t[3 * *nf + 2] = (int32_t)(c - 1);
            (*nf)++;
        }
    }
    fclose(fp);
    if (!bad && v && t) {
        mc_mesh m;
        mc_opts o;
        memset(&o, 0, sizeof o);
        m.v = v; m.nv = (int32_t)*nv; m.tri = t; m.nt = *nf; m.zbits = 0;
        o.allow_uncovered = 1;
        o.partial = partial;
        ok = mc_check(&m, f->w, f->h, f->z, &o, r) == 1;
        if (!ok) mc_report_print(stderr, r);
    }
    free(v); free(t);
    return bad ? -1 : ok;
}

static void test_fidelity_obj(void)
{
    char dem[] = "assets/N47E009.hgt.gz", me[] = "--max-error", mv[] = "20", o[] = "-o", js[] = "--json";
    char obj[256], out[256], *argv[6];
    hf f;
    br_err err;
    figs g;
    mc_report r;
    long nv, nf;
    snprintf(obj, sizeof obj, "%s/cli_mesh.obj", t_outdir());
    snprintf(out, sizeof out, "%s/cli_mesh.json", t_outdir());
    argv[0] = dem; argv[1] = me; argv[2] = mv; argv[3] = o; argv[4] = obj; argv[5] = js;
    CHECK_EQ(run_mesh(6, argv, out), 0);
    CHECK_EQ(read_json(out, &g), 0);
    if (dem_load(dem, NULL, &f, &err) != BR_OK) { CHECK(0); return; }
    CHECK_EQ(judge_obj(obj, &f, 0, &r, &nv, &nf), 1);
    CHECK_EQ(nf, g.tri);
    CHECK_EQ(nv, g.vert);
    CHECK(g.tri > 10000);
    CHECK(2 * g.refs <= 3 * g.tri);                    /* <= 1.5 strip references per triangle */
    CHECK(g.err <= 20.0 && g.err > 15.0);
    /* the referee's true error equals the printed one (heightfield unit 1 m) */
    CHECK(fabs((double)r.err_num / (double)r.err_den - g.err) < 1e-5);
    CHECK_EQ(r.tjunctions, 0);
    CHECK_EQ(r.orientation, -1);                       /* counter-clockwise seen from +z */
    printf("  N47E009 20 m: %ld triangles, %ld vertices, %.3f refs/tri, true error %.3f m\n",
           g.tri, g.vert, (double)g.refs / (double)g.tri, g.err);
    dem_free(&f);
}

/* The view mesh is about 1,000 triangles: on this void-cut terrain its references per
 * triangle move between 1.51 and 1.56 with the pixel error (the bridges around the
 * voids stay while the triangles between them come and go), 1.515 here. */
static void test_voids_view_ply_stl(void)
{
    char dem[256], me[] = "--max-error", mv[] = "0.5", o[] = "-o",
         js[] = "--json", cam[] = "--camera", cv[] = "0,0,1900,700,500,1700", px[] = "--pixel-error",
         pv[] = "0.9", sz[] = "--size", sv[] = "320x240";
    char path[256], out[256], *argv[12];
    figs g, gv;
    FILE *fp;
    char line[256];
    long nvert = -1, nface = -1;
    unsigned char hdr[84];
    snprintf(dem, sizeof dem, "%s", t_data("asc/hugo_site.asc"));
    /* PLY of the lossless-at-0.5 m mesh of a DEM with voids: the header's counts */
    snprintf(path, sizeof path, "%s/cli_mesh.ply", t_outdir());
    snprintf(out, sizeof out, "%s/cli_mesh_ply.json", t_outdir());
    argv[0] = dem; argv[1] = me; argv[2] = mv; argv[3] = o; argv[4] = path; argv[5] = js;
    CHECK_EQ(run_mesh(6, argv, out), 0);
    CHECK_EQ(read_json(out, &g), 0);
    CHECK(2 * g.refs <= 3 * g.tri);
    CHECK(g.err <= 0.5);
    fp = fopen(path, "r");
    CHECK(fp != NULL);
    while (fp && fgets(line, sizeof line, fp) && strncmp(line, "end_header", 10) != 0) {
        sscanf(line, "element vertex %ld", &nvert);
        sscanf(line, "element face %ld", &nface);
    }
    if (fp) fclose(fp);
    CHECK_EQ(nvert, g.vert);
    CHECK_EQ(nface, g.tri);
    /* STL (binary): 80-byte header, then the triangle count */
    snprintf(path, sizeof path, "%s/cli_mesh.stl", t_outdir());
    CHECK_EQ(run_mesh(6, argv, out), 0);
    fp = fopen(path, "rb");
    CHECK(fp && fread(hdr, 1, 84, fp) == 84);
    if (fp) {
        long n = hdr[80] | (long)hdr[81] << 8 | (long)hdr[82] << 16 | (long)hdr[83] << 24, end;
        fseek(fp, 0, SEEK_END);
        end = ftell(fp);
        fclose(fp);
        CHECK_EQ(n, g.tri);
        CHECK_EQ(end, 84 + 50 * n);
    }
    /* a view-dependent mesh, exported with the re-ordered strip */
    snprintf(path, sizeof path, "%s/cli_view.obj", t_outdir());
    argv[0] = dem; argv[1] = cam; argv[2] = cv; argv[3] = px; argv[4] = pv; argv[5] = sz; argv[6] = sv;
    argv[7] = o; argv[8] = path; argv[9] = js;
    CHECK_EQ(run_mesh(10, argv, out), 0);
    CHECK_EQ(read_json(out, &gv), 0);
    CHECK(gv.tri > 100 && gv.tri < g.tri);
    CHECK(50 * gv.refs <= 77 * gv.tri);   /* test_bitree.c one_dem: 1.54 */
    {
        hf f;
        br_err err;
        mc_report r;
        long nv, nf;
        if (dem_load(dem, NULL, &f, &err) != BR_OK) { CHECK(0); return; }
        CHECK(f.z_num == 1 && f.z_den == 1);   /* hugo is kept in whole metres */
        CHECK_EQ(judge_obj(path, &f, 1, &r, &nv, &nf), 1);
        CHECK_EQ(nf, gv.tri);
        CHECK_EQ(r.tjunctions, 0);
        dem_free(&f);
    }
}

static void test_bad_usage(void)
{
    char missing[] = "tests/out/no_such_file.hgt", o[] = "-o", obj[] = "tests/out/x.obj", me[] = "--max-error",
         neg[] = "-3", dem[] = "assets/N47E009.hgt.gz", ext[] = "tests/out/x.dxf";
    char *a[5];
    a[0] = missing; a[1] = o; a[2] = obj;
    CHECK_EQ(cmd_mesh(3, a), 1);                 /* unreadable input: error naming the file */
    a[0] = dem; a[1] = me; a[2] = neg; a[3] = o; a[4] = obj;
    CHECK_EQ(cmd_mesh(5, a), 2);                 /* negative error: usage */
    a[0] = dem; a[1] = o; a[2] = ext;
    CHECK_EQ(cmd_mesh(3, a), 2);                 /* unknown output format */
}

/* Reads a whole file; NULL if it cannot. */
static uint8_t *slurp(const char *path, size_t *n)
{
    FILE *fp = fopen(path, "rb");
    uint8_t *b;
    long len;
    if (!fp) return NULL;
    fseek(fp, 0, SEEK_END);
    len = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    b = malloc(len > 0 ? (size_t)len : 1);
    *n = b ? fread(b, 1, (size_t)len, fp) : 0;
    fclose(fp);
    return b;
}

/* --save-tree then --tree: the attached tree gives the same OBJ bytes as the built
 * one (a view mesh of mt_rainier_90m.tif, with voids); a tree for another tile, a
 * truncated one and a missing one are refused (exit 1), naming the file. */
static void test_saved_tree(void)
{
    char dem[512], dem2[512], o[] = "-o", st[] = "--save-tree", tr[] = "--tree", cm[] = "--camera",
         cv[] = "40000,-20000,8000,60000,60000,1500", me[] = "--max-error", mv[] = "30";
    char tree[256], trunc[256], none[256], a1[256], a2[256], out[256], *argv[9];
    uint8_t *b1, *b2;
    size_t n1 = 0, n2 = 0;
    FILE *fp;
    snprintf(dem, sizeof dem, "%s", t_data("tif/mt_rainier_90m.tif"));
    snprintf(dem2, sizeof dem2, "%s", t_data("hgt/N50E008.hgt"));
    snprintf(tree, sizeof tree, "%s/cli_tree.bt", t_outdir());
    snprintf(trunc, sizeof trunc, "%s/cli_tree_trunc.bt", t_outdir());
    snprintf(none, sizeof none, "%s/no_such_tree.bt", t_outdir());
    snprintf(a1, sizeof a1, "%s/cli_tree_built.obj", t_outdir());
    snprintf(a2, sizeof a2, "%s/cli_tree_attached.obj", t_outdir());
    snprintf(out, sizeof out, "%s/cli_tree.txt", t_outdir());
    argv[0] = dem; argv[1] = cm; argv[2] = cv; argv[3] = me; argv[4] = mv; argv[5] = o; argv[6] = a1;
    argv[7] = st; argv[8] = tree;
    CHECK_EQ(run_mesh(9, argv, out), 0);
    argv[6] = a2; argv[7] = tr;
    CHECK_EQ(run_mesh(9, argv, out), 0);
    b1 = slurp(a1, &n1); b2 = slurp(a2, &n2);
    CHECK(b1 && b2 && n1 > 100000 && n1 == n2 && !memcmp(b1, b2, n1));
    free(b1); free(b2);
    b1 = slurp(tree, &n1);
    CHECK(b1 && n1 > 64 + (size_t)1201 * 1201 * 4 && n1 < (size_t)1201 * 1201 * 5);   /* 4 bytes a slot */
    if (b1 && (fp = fopen(trunc, "wb"))) { fwrite(b1, 1, n1 - 4, fp); fclose(fp); }
    free(b1);
    argv[8] = trunc;
    CHECK_EQ(run_mesh(9, argv, out), 1);
    argv[8] = none;
    CHECK_EQ(run_mesh(9, argv, out), 1);
    argv[0] = dem2; argv[8] = tree;
    CHECK_EQ(run_mesh(9, argv, out), 1);
}

/* `bitrain render` with argv, its stdout to out and its stderr's first line to line
 * (size bytes, through the file err); returns its exit status, or -1 when stderr could
 * not be redirected. */
static int render_first_err(int argc, char **argv, const char *out, const char *err, char *line, int size)
{
    FILE *fp;
    int saved, rc;
    line[0] = 0;
    fflush(stderr);
    if ((saved = redirect(2, err)) < 0) return -1;
    rc = run_render(argc, argv, out);
    fflush(stderr);
    restore(2, saved);
    if ((fp = fopen(err, "r"))) { if (!fgets(line, size, fp)) line[0] = 0; fclose(fp); }
    return rc;
}

/* A tree saved by `mesh --save-tree` holds the file's heights; render with its water
 * found lowers the flattened lakes to a bottom first, so the tree is refused with a
 * message that says why and what to add; with --no-water it attaches.  A file that is
 * not a tree is refused as such, without that advice. */
static void test_saved_tree_water(void)
{
    char dem[] = "assets/N47E009.hgt.gz", cm[] = "--save-tree", o[] = "-o", tr[] = "--tree", sz[] = "--size",
         szv[] = "64x48", nw[] = "--no-water";
    char tree[256], obj[256], png[256], out[256], err[256], *argv[8];
    char line[512];
    snprintf(tree, sizeof tree, "%s/cli_tree_lakes.bt", t_outdir());
    snprintf(obj, sizeof obj, "%s/cli_tree_lakes.obj", t_outdir());
    snprintf(png, sizeof png, "%s/cli_tree_lakes.png", t_outdir());
    snprintf(out, sizeof out, "%s/cli_tree_lakes.txt", t_outdir());
    snprintf(err, sizeof err, "%s/cli_tree_lakes.err", t_outdir());
    argv[0] = dem; argv[1] = cm; argv[2] = tree; argv[3] = o; argv[4] = obj;
    CHECK_EQ(run_mesh(5, argv, out), 0);
    argv[0] = dem; argv[1] = tr; argv[2] = tree; argv[3] = sz; argv[4] = szv; argv[5] = o; argv[6] = png;
    CHECK_EQ(render_first_err(7, argv, out, err, line, sizeof line), 1);
    CHECK_MSG(strstr(line, "cli_tree_lakes.bt") && strstr(line, "add --no-water"), "%s", line);
    argv[7] = nw;
    CHECK_EQ(run_render(8, argv, out), 0);
    /* a file that is no tree at all (the DEM itself) gets no water hint */
    argv[2] = dem;
    CHECK_EQ(render_first_err(7, argv, out, err, line, sizeof line), 1);
    CHECK_MSG(strstr(line, "N47E009.hgt.gz: not a bitree") && !strstr(line, "--no-water"), "%s", line);
}

int main(void)
{
    T_RUN(test_fidelity_obj);
    T_RUN(test_saved_tree);
    T_RUN(test_saved_tree_water);
    T_RUN(test_voids_view_ply_stl);
    T_RUN(test_bad_usage);
    return t_finish();
}
