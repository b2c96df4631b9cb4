#define _POSIX_C_SOURCE 200809L   /* clock_gettime, readlink, isatty under -std=c99 */
/* platform/bench_board.c — bitrain bench (no --scene, or --scene all): the table users
 * compare across boards.
 *
 *   bitrain bench [--threads N] [--frames F] [--path FILE] [--json FILE] [--chart FILE.png]
 *                 [--no-ir] [--ir-frames K] [--dem FUJI.png] [--quiet]
 *
 * Rows: the peer scene (../shared/bench/PEERS.md, benchmarks/peer_scene.c) from cameras A
 * and B, and the default scene (platform/bench_default.h: exactly the frame of
 * `bench --scene default`) flown along a camera path (default assets/default-path.cam), each
 * at 320x240 and 640x480, on 1 thread and on N (default: the online cores), the bands
 * drawn by pt_run (platform/pipe_threads.h) into a sink that keeps nothing.  Bands: the
 * peer scene on one thread is one whole-frame band (as `bench --scene peer` and the peers'
 * table), else 64-row bands (the viewer's).
 *
 * Columns: median ms per frame and its fps; triangles per second for the whole frame
 * (mean triangles a frame / median frame ms) and for the rasteriser alone (/ median
 * raster ms); pixels per second; "sel ms", the median time before the rasteriser starts
 * (default scene: selection, strip, vertices and transform; peer scene: the transform, it
 * has no selection); triangles a frame (peer: the 131,072 submitted; default: the mesh's);
 * instructions a frame on one thread, when valgrind is present: the same configuration run by
 *   valgrind --tool=callgrind --toggle-collect=bench_frame bitrain bench --scene peer ...
 *   valgrind --tool=callgrind --toggle-collect=bench_default_frame bitrain bench --scene default ...
 * (K frames each, the total Ir over K).  Peer frames: 3 untimed warm-up frames, then F
 * (default 30) of the same camera; default scene: opened afresh for each row (so the
 * selection's hysteresis starts from nothing, as in `bench --scene default`), no warm-up,
 * F frames (default: every line of the path) along the path.  --chart draws the default scene's frame times along
 * the path (platform/bench_chart.h), --json writes the table with those frame times. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <sys/utsname.h>
#include "platform/clock.h"
#include "benchmarks/peer_scene.h"
#include "platform/assets.h"
#include "platform/bench_chart.h"
#include "platform/bench_default.h"
#include "platform/campath.h"
#include "platform/cmd.h"
#include "platform/opt.h"
#include "platform/pipe_threads.h"
#include "raster/frame.h"

#define BB_BAND 64
#define BB_ROWS 12

typedef struct bb_row {
    const char *scene;          /* "peer" or "default" */
    const char *view;           /* "A", "B" or "path" */
    int w, h, threads, frames;
    double ms, sel_ms, raster_ms;   /* medians */
    double tris;                /* mean triangles a frame */
    double ir;                  /* instructions a frame (callgrind), < 0: not measured */
    double *frame_ms;           /* the frames' ms in order */
} bb_row;

typedef struct bb_prog {
    int quiet, tty, nrows;
} bb_prog;

/* Median of v[0..n) (v is sorted in place). */
static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, br_cmp_double);
    return n & 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static br_status null_sink(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    (void)user; (void)y0; (void)rows; (void)px; (void)stride;
    return BR_OK;
}

static void progress(const bb_prog *pg, int r, const bb_row *row, int i)
{
    if (pg->quiet) return;
    if (pg->tty)
        fprintf(stderr, "\rbitrain bench: [%2d/%d] %-7s %-4s %dx%d %d thread%s: frame %d/%d   ", r + 1, pg->nrows,
                row->scene, row->view, row->w, row->h, row->threads, row->threads > 1 ? "s" : "", i, row->frames);
    else if (i == 0)
        fprintf(stderr, "bitrain bench: [%2d/%d] %s %s %dx%d %d thread%s\n", r + 1, pg->nrows, row->scene, row->view,
                row->w, row->h, row->threads, row->threads > 1 ? "s" : "");
}

/* Fills the row's medians from the per-frame arrays (ms is kept in order for the chart). */
static void finish_row(bb_row *row, const double *sel, const double *ras, double tris_sum)
{
    int n = row->frames;
    double *tmp = malloc(sizeof *tmp * (size_t)n);
    if (!tmp) return;
    memcpy(tmp, row->frame_ms, sizeof *tmp * (size_t)n);
    row->ms = median(tmp, n);
    memcpy(tmp, sel, sizeof *tmp * (size_t)n);
    row->sel_ms = median(tmp, n);
    memcpy(tmp, ras, sizeof *tmp * (size_t)n);
    row->raster_ms = median(tmp, n);
    row->tris = tris_sum / n;
    free(tmp);
}

/* One peer-scene row: camera row->view[0]. */
static int run_peer(const rs_vertex *v, const rs_prim *prims, bb_row *row, const bb_prog *pg, int r)
{
    int band_rows = row->threads > 1 ? BB_BAND : row->h, i, rc = 1;
    rs_frame f;
    rs_pipe p;
    rs_pass terrain;
    pt_pool *pool = NULL;
    double *sel = malloc(sizeof *sel * (size_t)row->frames), *ras = malloc(sizeof *ras * (size_t)row->frames);
    if (peer_frame(row->view[0], row->w, row->h, v, prims, &f) != 0) { fprintf(stderr, "bitrain bench: bad camera\n"); goto done; }
    f.cache = malloc(rs_cache_mem_size(PEER_NV));
    f.chunks = malloc(rs_chunk_mem_size(prims, PEER_NSTRIP));
    f.one_band = band_rows == row->h;
    row->frame_ms = malloc(sizeof *row->frame_ms * (size_t)row->frames);
    if (!sel || !ras || !f.cache || !f.chunks || !row->frame_ms) { fprintf(stderr, "bitrain bench: out of memory\n"); goto done; }
    memset(&p, 0, sizeof p);
    p.w = row->w; p.h = row->h; p.fmt = f.fmt; p.depth = f.depth;
    if (rs_pass_terrain(&terrain, &f) != BR_OK || rs_pipe_add(&p, &terrain) != BR_OK) goto done;
    if (pt_open(&pool, row->threads) != BR_OK) { fprintf(stderr, "bitrain bench: cannot start %d threads\n", row->threads); goto done; }
    for (i = -3; i < row->frames; i++) {   /* i < 0: untimed warm-up */
        double t0 = br_now_ms(), t1, t2;
        if (rs_frame_prepare(&f) != BR_OK) goto fail;
        t1 = br_now_ms();
        if (pt_run(pool, &p, band_rows, null_sink, NULL, NULL) != BR_OK) goto fail;
        t2 = br_now_ms();
        if (i < 0) continue;
        row->frame_ms[i] = t2 - t0; sel[i] = t1 - t0; ras[i] = t2 - t1;
        if (i % 8 == 0) progress(pg, r, row, i);
    }
    finish_row(row, sel, ras, (double)PEER_NTRI * row->frames);
    rc = 0;
    goto done;
fail:
    fprintf(stderr, "bitrain bench: peer scene camera %s: drawing failed\n", row->view);
done:
    pt_close(pool);
    free(f.cache); free(f.chunks); free(sel); free(ras);
    return rc;
}

/* One default-scene row: frame i flies line i of the path (wrapping). */
static int run_default(bd_run *bd, const campath *cp, const char *path, bb_row *row, const bb_prog *pg, int r)
{
    int i, rc = 1;
    rs_pipe p;
    rs_pass terrain;
    pt_pool *pool = NULL;
    double tris = 0, *sel = malloc(sizeof *sel * (size_t)row->frames), *ras = malloc(sizeof *ras * (size_t)row->frames);
    row->frame_ms = malloc(sizeof *row->frame_ms * (size_t)row->frames);
    if (!sel || !ras || !row->frame_ms) { fprintf(stderr, "bitrain bench: out of memory\n"); goto done; }
    if (pt_open(&pool, row->threads) != BR_OK) { fprintf(stderr, "bitrain bench: cannot start %d threads\n", row->threads); goto done; }
    bd_set_pool(bd, pool);       /* the selection's parts on the row's threads too */
    for (i = 0; i < row->frames; i++) {
        const double *k = cp->cam[i % cp->n];
        double t0, t1, t2;
        cam c;
        if (bd_camera(bd, k, k + 3, row->w, row->h, &c) != BR_OK) {
            fprintf(stderr, "bitrain bench: %s: line %d: unusable camera\n", path, i % cp->n + 1);
            goto done;
        }
        t0 = br_now_ms();
        if (bd_select(bd, &c) != BR_OK) goto fail;
        memset(&p, 0, sizeof p);
        p.w = row->w; p.h = row->h; p.fmt = bd_frame(bd)->fmt; p.depth = bd_frame(bd)->depth;
        if (rs_pass_terrain(&terrain, bd_frame(bd)) != BR_OK || rs_pipe_add(&p, &terrain) != BR_OK) goto fail;
        t1 = br_now_ms();
        if (pt_run(pool, &p, BB_BAND, null_sink, NULL, NULL) != BR_OK) goto fail;
        t2 = br_now_ms();
        row->frame_ms[i] = t2 - t0; sel[i] = t1 - t0; ras[i] = t2 - t1;
        tris += bd_tris(bd);
        if (i % 8 == 0) progress(pg, r, row, i);
    }
    finish_row(row, sel, ras, tris);
    rc = 0;
    goto done;
fail:
    fprintf(stderr, "bitrain bench: default scene frame %d: drawing failed\n", i + 1);
done:
    bd_set_pool(bd, NULL);
    pt_close(pool);
    free(sel); free(ras);
    return rc;
}

/* s in single quotes for sh; 0 when s holds a quote (not passed on). */
static int shq(char *out, size_t n, const char *s)
{
    if (strchr(s, '\'') || strlen(s) + 3 > n) return 0;
    snprintf(out, n, "'%s'", s);
    return 1;
}

/* Instructions a frame of `bitrain bench ARGS` (K frames) under callgrind, toggled on fn;
 * < 0 when the run or its output failed. */
static double callgrind_ir(const char *exe, const char *fn, const char *args, int k)
{
    char out[64], cmd[2048], qexe[1100], line[256];
    double ir = -1;
    FILE *f;
    snprintf(out, sizeof out, "/tmp/bitrain-bench-%ld.cg", (long)getpid());
    if (!shq(qexe, sizeof qexe, exe)) return -1;
    snprintf(cmd, sizeof cmd, "valgrind --tool=callgrind --callgrind-out-file=%s --toggle-collect=%s %s bench %s "
             "--frames %d >/dev/null 2>&1", out, fn, qexe, args, k);
    if (system(cmd) != 0) { remove(out); return -1; }
    f = fopen(out, "r");
    if (!f) return -1;
    while (fgets(line, sizeof line, f))
        if (!strncmp(line, "summary:", 8) || !strncmp(line, "totals:", 7)) { ir = atof(strchr(line, ':') + 1) / k; break; }
    fclose(f);
    remove(out);
    return ir;
}

static void json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\') fprintf(f, "\\%c", *s);
        else if ((unsigned char)*s < 32) fprintf(f, "\\u%04x", (unsigned char)*s);
        else fputc(*s, f);
    }
    fputc('"', f);
}

static int write_json(const char *file, const bb_row *rows, int n, const char *path, const char *board,
                      int cores, const char *ir_note)
{
    int i, j;
    FILE *f = fopen(file, "w");
    if (!f) { fprintf(stderr, "bitrain bench: %s: cannot write\n", file); return 1; }
    fprintf(f, "{\n  \"bitrain_bench\": 1,\n  \"board\": ");
    json_str(f, board);
    fprintf(f, ",\n  \"online_cores\": %d,\n  \"isa\": \"%s\",\n  \"path\": ", cores, rs_isa_name(rs_isa()));
    json_str(f, path);
    fprintf(f, ",\n  \"instructions\": ");
    json_str(f, ir_note);
    fprintf(f, ",\n  \"rows\": [\n");
    for (i = 0; i < n; i++) {
        const bb_row *r = &rows[i];
        fprintf(f, "    {\"scene\": \"%s\", \"view\": \"%s\", \"width\": %d, \"height\": %d, \"threads\": %d, "
                "\"frames\": %d, \"ms_per_frame\": %.4f, \"fps\": %.2f, \"mtri_per_s_frame\": %.3f, "
                "\"mtri_per_s_raster\": %.3f, \"mpix_per_s\": %.3f, \"select_ms\": %.4f, \"raster_ms\": %.4f, "
                "\"tris_per_frame\": %.1f, \"instructions_per_frame\": ",
                r->scene, r->view, r->w, r->h, r->threads, r->frames, r->ms, 1e3 / r->ms, r->tris / r->ms / 1e3,
                r->tris / r->raster_ms / 1e3, (double)r->w * r->h / r->ms / 1e3, r->sel_ms, r->raster_ms, r->tris);
        if (r->ir >= 0) fprintf(f, "%.0f", r->ir);
        else fprintf(f, "null");
        fprintf(f, ", \"frame_ms\": [");
        for (j = 0; j < r->frames; j++) fprintf(f, "%s%.4f", j ? ", " : "", r->frame_ms[j]);
        fprintf(f, "]}%s\n", i + 1 < n ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
    if (fclose(f) != 0) { fprintf(stderr, "bitrain bench: %s: cannot write\n", file); return 1; }
    return 0;
}

#define BOARD_SYNOPSIS "[--scene all] [options]\n" \
    "  the table to compare boards: the peer scene (cameras A, B) and the default scene along its path,\n" \
    "  320x240 and 640x480, 1 and N threads (`bench --scene peer|default --help`: one configuration)"

int cmd_bench_board(int argc, char **argv)
{
    static const char peer_dem[] = "../shared/data/dem/png/fuji.png";
    const char *path = ASSET_DEFAULT_PATH, *dem = peer_dem, *json = NULL, *peer_note = "";
    const char *chart = NULL, *pos[1];
    int threads = pt_online_cores(), frames = 0, no_ir = 0, ir_frames = 10, quiet = 0, scene_all = 0;
    int npos, r, i, nrows = 0, rc = 1, cores = pt_online_cores(), have_vg = 0;
    const opt_spec own[] = {
        { "--scene", OPT_CHOICE, &scene_all, 0, 0, 0, "all", "all", "every scene (the default)", NULL },
        { "--threads", OPT_INT, &threads, 1, PT_MAX_THREADS, 0, NULL, "N", "the threaded rows' threads (default: online cores)", NULL },
        { "--frames", OPT_INT, &frames, 1, 1000000, 0, NULL, "F", "frames a row (default: peer 30, default scene the whole path)", NULL },
        { "--path", OPT_STR, &path, 0, 0, 0, NULL, "FILE", "the default scene's camera path (default assets/default-path.cam)", NULL },
        { "--dem", OPT_STR, &dem, 0, 0, 0, NULL, "FILE", "the peer scene's terrain (default ../shared/data/dem/png/fuji.png)", NULL },
        { "--json", OPT_STR, &json, 0, 0, 0, NULL, "FILE", "write the table (and the path's frame times) as JSON", NULL },
        { "--chart", OPT_STR, &chart, 0, 0, 0, NULL, "FILE.png", "draw the frame time along the path", NULL },
        { "--no-ir", OPT_FLAG, &no_ir, 0, 0, 0, NULL, NULL, "no instruction counts (callgrind)", NULL },
        { "--ir-frames", OPT_INT, &ir_frames, 1, 100000, 0, NULL, "K", "frames each callgrind run counts (default 10)", NULL },
        { "--quiet", OPT_FLAG, &quiet, 0, 0, 0, NULL, NULL, "no progress line on stderr", NULL },
        OPT_END
    };
    const opt_spec *const tables[] = { own, NULL };
    static const char *const views[3] = { "A", "B", "path" };
    static const int sizes[2][2] = { { 320, 240 }, { 640, 480 } };
    bb_row rows[BB_ROWS];
    bb_prog pg;
    peer_scene *ps = NULL;
    rs_vertex *v = NULL;
    rs_prim prims[PEER_NSTRIP];
    campath cp = { NULL, 0 };
    bd_run *bd = NULL;
    br_err err;
    char board[256], exe[1024], ir_note[160];
    struct utsname un;
    (void)scene_all;
    r = opt_parse("bench", BOARD_SYNOPSIS, tables, argc, argv, pos, 0, &npos);
    if (r != OPT_OK) return r == OPT_HELP ? 0 : 2;
    memset(rows, 0, sizeof rows);
    memset(&err, 0, sizeof err);
    if (campath_read(path, &cp, &err) != BR_OK) { fprintf(stderr, "bitrain bench: %s\n", err.msg); return 1; }
    for (i = 0; i < 3; i++) {
        int s, t;
        for (s = 0; s < 2; s++)
            for (t = 0; t < (threads > 1 ? 2 : 1); t++) {
                bb_row *row = &rows[nrows++];
                row->scene = i < 2 ? "peer" : "default";
                row->view = views[i];
                row->w = sizes[s][0]; row->h = sizes[s][1];
                row->threads = t ? threads : 1;
                row->frames = frames ? frames : i < 2 ? 30 : cp.n;
                row->ir = -1;
            }
    }
    pg.quiet = quiet; pg.tty = isatty(2); pg.nrows = nrows;
    snprintf(board, sizeof board, "unknown");
    if (uname(&un) == 0) snprintf(board, sizeof board, "%s %s", un.machine, un.release);
    {   /* the CPU's name, where Linux says it */
        FILE *f = fopen("/proc/cpuinfo", "r");
        char line[256];
        while (f && fgets(line, sizeof line, f))
            if (!strncmp(line, "model name", 10) || !strncmp(line, "Model", 5) || !strncmp(line, "Hardware", 8)) {
                char *c = strchr(line, ':');
                size_t k = strlen(board);
                if (c && k + 3 < sizeof board) {
                    c[strcspn(c, "\n")] = 0;
                    snprintf(board + k, sizeof board - k, ",%s", c + 1);
                }
                break;
            }
        if (f) fclose(f);
    }
    ps = malloc(sizeof *ps);
    v = malloc(sizeof *v * PEER_NV);
    if (!ps || !v) { fprintf(stderr, "bitrain bench: out of memory\n"); goto done; }
    if (peer_scene_build(dem, ps) == 0) peer_scene_raster(ps, v, prims);
    else if (dem != peer_dem) goto done;
    else {  /* ../shared is not beside an installed program: the default scene's rows alone */
        int kept = 0;
        fprintf(stderr, "bitrain bench: the peer scene's rows left out (its terrain is read from ../shared; --dem FILE names it)\n");
        for (i = 0; i < nrows; i++)
            if (rows[i].view[0] == 'p') rows[kept++] = rows[i];
        nrows = kept;
        peer_note = "left out: its terrain is unreadable, ";
    }
    for (i = 0; i < nrows; i++) {
        int bad;
        if (rows[i].view[0] == 'p') {   /* a fresh scene a row: the selection's hysteresis starts from nothing */
            bd_close(bd);
            bd = bd_open(NULL, 1, &err);
            if (!bd) { fprintf(stderr, "bitrain bench: %s\n", err.msg); goto done; }
        }
        bad = rows[i].view[0] == 'p' ? run_default(bd, &cp, path, &rows[i], &pg, i) : run_peer(v, prims, &rows[i], &pg, i);
        if (bad) goto done;
    }
    if (!quiet && pg.tty) fprintf(stderr, "\r%70s\r", "");
    /* instructions a frame: each 1-thread configuration once more under callgrind */
    have_vg = !no_ir && system("valgrind --version >/dev/null 2>&1") == 0;
    r = (int)readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (r > 0) exe[r] = 0;
    if (no_ir) snprintf(ir_note, sizeof ir_note, "not counted (--no-ir)");
    else if (!have_vg) snprintf(ir_note, sizeof ir_note, "not counted: valgrind is not installed");
    else if (r <= 0) { have_vg = 0; snprintf(ir_note, sizeof ir_note, "not counted: /proc/self/exe unreadable"); }
    else snprintf(ir_note, sizeof ir_note, "callgrind Ir over %d frames, 1 thread", ir_frames);
    for (i = 0; have_vg && i < nrows; i++) {
        char args[1200], q[1100];
        if (rows[i].threads != 1) continue;
        if (!quiet) fprintf(stderr, "bitrain bench: callgrind %s %s %dx%d (%d frames) ...\n", rows[i].scene, rows[i].view,
                            rows[i].w, rows[i].h, ir_frames);
        if (rows[i].view[0] == 'p') {
            if (!shq(q, sizeof q, path)) continue;
            snprintf(args, sizeof args, "--scene default --path %s --size %dx%d", q, rows[i].w, rows[i].h);
            rows[i].ir = callgrind_ir(exe, "bench_default_frame", args, ir_frames);
        } else {
            if (!shq(q, sizeof q, dem)) continue;
            snprintf(args, sizeof args, "--scene peer --camera %s --dem %s --size %dx%d", rows[i].view, q, rows[i].w, rows[i].h);
            rows[i].ir = callgrind_ir(exe, "bench_frame", args, ir_frames);
        }
    }
    {
        FILE *f = fopen("/proc/loadavg", "r");
        double la = -1;
        if (f && fscanf(f, "%lf", &la) != 1) la = -1;
        if (f) fclose(f);
        printf("bitrain bench: %s, %d online cores, isa %s", board, cores, rs_isa_name(rs_isa()));
        if (la >= 0) printf(", load average %.2f", la);
        printf("\n  peer: ../shared/bench/PEERS.md scene, %s%d frames a row; default: " ASSET_DEFAULT_DEM " along %s\n"
               "  instructions: %s\n", peer_note, frames ? frames : 30, path, ir_note);
    }
    printf("%-7s %-4s %-7s %3s %6s %9s %7s %8s %8s %8s %7s %10s %9s\n", "scene", "view", "size", "thr", "frames",
           "ms/frame", "fps", "Mtri/s", "Mtri/s", "Mpix/s", "sel ms", "tris/frame", "Minstr/fr");
    printf("%-7s %-4s %-7s %3s %6s %9s %7s %8s %8s\n", "", "", "", "", "", "(median)", "", "(frame)", "(raster)");
    for (i = 0; i < nrows; i++) {
        const bb_row *w = &rows[i];
        char size[16], ir[16];
        snprintf(size, sizeof size, "%dx%d", w->w, w->h);
        if (w->ir >= 0) snprintf(ir, sizeof ir, "%.2f", w->ir / 1e6);
        else snprintf(ir, sizeof ir, "-");
        printf("%-7s %-4s %-7s %3d %6d %9.3f %7.1f %8.2f %8.2f %8.1f %7.3f %10.0f %9s\n", w->scene, w->view, size,
               w->threads, w->frames, w->ms, 1e3 / w->ms, w->tris / w->ms / 1e3, w->tris / w->raster_ms / 1e3,
               (double)w->w * w->h / w->ms / 1e3, w->sel_ms, w->tris, ir);
    }
    fflush(stdout);
    rc = 0;
    if (json && write_json(json, rows, nrows, path, board, cores, ir_note) != 0) rc = 1;
    if (chart) {
        chart_series cs[CHART_MAX_SERIES];
        char labels[CHART_MAX_SERIES][48], title[200];
        int ns = 0;
        for (i = 0; i < nrows && ns < CHART_MAX_SERIES; i++) {
            if (rows[i].view[0] != 'p') continue;
            snprintf(labels[ns], sizeof labels[ns], "%dx%d, %d thread%s", rows[i].w, rows[i].h, rows[i].threads,
                     rows[i].threads > 1 ? "s" : "");
            cs[ns].label = labels[ns]; cs[ns].y = rows[i].frame_ms; cs[ns].n = rows[i].frames;
            ns++;
        }
        snprintf(title, sizeof title, "bitrain bench: default scene along %s", path);
        if (chart_png(chart, 800, 450, title, "frame (line of the path)", "ms per frame", cs, ns, &err) != BR_OK) {
            fprintf(stderr, "bitrain bench: %s: %s\n", chart, err.msg);
            rc = 1;
        }
    }
done:
    for (i = 0; i < nrows; i++) free(rows[i].frame_ms);
    bd_close(bd);
    campath_free(&cp);
    free(ps);
    free(v);
    return rc;
}
