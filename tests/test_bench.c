#define _POSIX_C_SOURCE 200809L   /* popen */
/* tests/test_bench.c — `bitrain bench` (the board table, platform/bench_board.c) run
 * quickly (two frames a row, no callgrind): every row of the table is printed, --json
 * writes valid JSON with the keys users read, --chart a PNG with axes and a line per
 * configuration; the chart writer (platform/bench_chart.c) alone; and --visibility's
 * count (platform/bench_vis.c). */
#include <ctype.h>
#include "tests/test.h"
#include "platform/bench_chart.h"
#include "platform/bench_vis.h"
#include "platform/png_io.h"

/* ---------------------------------------------------------------- a small JSON checker */

typedef struct jp {
    const char *p;
    int depth;
} jp;

static void ws(jp *j)
{
    while (*j->p == ' ' || *j->p == '\n' || *j->p == '\r' || *j->p == '\t') j->p++;
}

static int value(jp *j);

static int string(jp *j)
{
    if (*j->p != '"') return 0;
    for (j->p++; *j->p != '"'; j->p++) {
        if ((unsigned char)*j->p < 32) return 0;
        if (*j->p == '\\') {
            j->p++;
            if (*j->p == 'u') { int k; for (k = 1; k <= 4; k++) if (!isxdigit((unsigned char)j->p[k])) return 0; j->p += 4; }
            else if (!strchr("\"\\/bfnrt", *j->p) || !*j->p) return 0;
        }
    }
    j->p++;
    return 1;
}

static int number(jp *j)
{
    const char *s = j->p;
    if (*j->p == '-') j->p++;
    if (!isdigit((unsigned char)*j->p)) return 0;
    while (isdigit((unsigned char)*j->p)) j->p++;
    if (*j->p == '.') { j->p++; if (!isdigit((unsigned char)*j->p)) return 0; while (isdigit((unsigned char)*j->p)) j->p++; }
    if (*j->p == 'e' || *j->p == 'E') {
        j->p++;
        if (*j->p == '+' || *j->p == '-') j->p++;
        if (!isdigit((unsigned char)*j->p)) return 0;
        while (isdigit((unsigned char)*j->p)) j->p++;
    }
    return j->p > s;
}

static int list(jp *j, char close, int members)
{
    j->p++;
    if (++j->depth > 64) return 0;
    ws(j);
    if (*j->p == close) { j->p++; j->depth--; return 1; }
    for (;;) {
        ws(j);
        if (members) {
            if (!string(j)) return 0;
            ws(j);
            if (*j->p++ != ':') return 0;
        }
        if (!value(j)) return 0;
        ws(j);
        if (*j->p == ',') { j->p++; continue; }
        if (*j->p++ != close) return 0;
        j->depth--;
        return 1;
    }
}

static int value(jp *j)
{
    ws(j);
    if (*j->p == '{') return list(j, '}', 1);
    if (*j->p == '[') return list(j, ']', 0);
    if (*j->p == '"') return string(j);
    if (!strncmp(j->p, "null", 4) || !strncmp(j->p, "true", 4)) { j->p += 4; return 1; }
    if (!strncmp(j->p, "false", 5)) { j->p += 5; return 1; }
    return number(j);
}

static int json_valid(const char *s)
{
    jp j;
    j.p = s; j.depth = 0;
    if (!value(&j)) return 0;
    ws(&j);
    return *j.p == 0;
}

static int count(const char *s, const char *needle)
{
    int n = 0;
    for (; (s = strstr(s, needle)) != NULL; s += strlen(needle)) n++;
    return n;
}

/* Distinct colours of an RGB picture (up to 64 counted). */
static int colours(const uint8_t *rgb, int n)
{
    uint32_t seen[64];
    int k = 0, i, j;
    for (i = 0; i < n && k < 64; i++) {
        uint32_t c = (uint32_t)rgb[3 * i] << 16 | (uint32_t)rgb[3 * i + 1] << 8 | rgb[3 * i + 2];
        for (j = 0; j < k && seen[j] != c; j++) {}
        if (j == k) seen[k++] = c;
    }
    return k;
}

static void test_json_checker(void)
{
    CHECK(json_valid("{\"a\": [1, 2.5, -3e2, null, \"x\\\"y\"], \"b\": {}}"));
    CHECK(!json_valid("{\"a\": [1, 2,]}"));
    CHECK(!json_valid("{\"a\": 1"));
    CHECK(!json_valid("{\"a\": nan}"));
}

static void test_board_table(void)
{
    char cmd[1024], json[256], chart[256], line[512], *out = NULL;
    size_t n = 0, cap = 0;
    int i, w = 0, h = 0;
    unsigned char *js;
    uint8_t *rgb = NULL;
    br_err err;
    FILE *p;
    static const char *const rows[6] = { "peer    A    320x240", "peer    A    640x480", "peer    B    320x240",
                                         "peer    B    640x480", "default path 320x240", "default path 640x480" };
    static const char *const keys[] = { "\"bitrain_bench\"", "\"board\"", "\"online_cores\"", "\"rows\"", "\"scene\"",
        "\"view\"", "\"width\"", "\"height\"", "\"threads\"", "\"ms_per_frame\"", "\"fps\"", "\"mtri_per_s_frame\"",
        "\"mtri_per_s_raster\"", "\"mpix_per_s\"", "\"select_ms\"", "\"instructions_per_frame\"", "\"frame_ms\"" };
    snprintf(json, sizeof json, "%s/bench.json", t_outdir());
    snprintf(chart, sizeof chart, "%s/bench_chart.png", t_outdir());
    remove(json); remove(chart);
    snprintf(cmd, sizeof cmd, "./bitrain bench --threads 2 --frames 2 --no-ir --quiet --json %s --chart %s", json, chart);
    p = popen(cmd, "r");
    CHECK(p != NULL);
    if (!p) return;
    while (fgets(line, sizeof line, p)) {
        size_t k = strlen(line);
        if (n + k + 1 > cap) { cap = 2 * (n + k + 1); out = realloc(out, cap); }
        if (!out) break;
        memcpy(out + n, line, k + 1);
        n += k;
    }
    CHECK_EQ(pclose(p), 0);
    CHECK(out != NULL);
    if (!out) return;
    for (i = 0; i < 6; i++) {   /* each configuration on 1 and on 2 threads */
        char r1[64], r2[64];
        snprintf(r1, sizeof r1, "%s   1 ", rows[i]);
        snprintf(r2, sizeof r2, "%s   2 ", rows[i]);
        CHECK_MSG(count(out, r1) == 1 && count(out, r2) == 1, "row '%s' in:\n%s", rows[i], out);
    }
    CHECK(strstr(out, "ms/frame") && strstr(out, "Mtri/s") && strstr(out, "Mpix/s") && strstr(out, "sel ms"));
    CHECK(strstr(out, "not counted (--no-ir)") != NULL);
    free(out);
    js = t_read_file(json, &n);
    CHECK(js != NULL);
    if (js) {
        char *s = realloc(js, n + 1);
        if (s) {
            s[n] = 0;
            CHECK(json_valid(s));
            for (i = 0; i < (int)(sizeof keys / sizeof *keys); i++) CHECK_MSG(strstr(s, keys[i]) != NULL, "%s", keys[i]);
            CHECK_EQ(count(s, "\"scene\": \"peer\""), 8);
            CHECK_EQ(count(s, "\"scene\": \"default\""), 4);
            CHECK_EQ(count(s, "\"instructions_per_frame\": null"), 12);
            free(s);
        } else free(js);
    }
    CHECK_EQ(png_read_rgb(chart, &w, &h, &rgb, &err), BR_OK);
    if (rgb) {
        CHECK(w == 800 && h == 450);
        CHECK(colours(rgb, w * h) >= 8);   /* background, grid, axes, text, four lines */
        free(rgb);
    }
}

static void test_bad_options(void)
{
    CHECK(system("./bitrain bench --threads 0 2>/dev/null") != 0);
    CHECK(system("./bitrain bench --path /nonexistent.cam --no-ir --quiet 2>/dev/null") != 0);
    CHECK(system("./bitrain bench --help >/dev/null") == 0);
}

/* Triangles a frame of `bench --scene default` with extra options (-1: it failed) */
static long bench_tris(const char *opts)
{
    char cmd[1024], line[512];
    long tris = -1;
    FILE *p;
    snprintf(cmd, sizeof cmd, "./bitrain bench --scene default --frames 1 --dem %s %s", t_data("hgt/N50E008.hgt"), opts);
    p = popen(cmd, "r");
    if (!p) return -1;
    while (fgets(line, sizeof line, p)) {
        const char *t = strstr(line, "tris/frame=");
        if (t) tris = strtol(t + 11, NULL, 10);
    }
    return pclose(p) == 0 ? tris : -1;
}

/* --visibility on a real tile (N50E008's default view, from high over it): the line
 * is printed, and most triangles own a pixel (a misread frame owns none). */
static void test_visibility_real(void)
{
    char cmd[1024], line[512];
    double seen_pc = -1;
    FILE *p;
    snprintf(cmd, sizeof cmd, "./bitrain bench --scene default --frames 2 --visibility --dem %s",
             t_data("hgt/N50E008.hgt"));
    p = popen(cmd, "r");
    if (!p) { CHECK(p != NULL); return; }
    while (fgets(line, sizeof line, p)) {
        const char *t = strstr(line, "visibility: "), *q = t ? strstr(t, "seen=") : NULL;
        if (q && (q = strchr(q, '('))) seen_pc = strtod(q + 1, NULL);
    }
    CHECK_EQ(pclose(p), 0);
    CHECK_MSG(seen_pc > 50 && seen_pc <= 100, "seen %.1f %%", seen_pc);
}

/* --fill-voids benchmarks the terrain render and view draw with it: N50E008's 50 SRTM
 * void samples, holes otherwise, are refined around down to the sample whatever the
 * distance (docs/perf-history.md), so the filled tile's frame has fewer triangles. */
static void test_fill_voids(void)
{
    const long holes = bench_tris(""), filled = bench_tris("--fill-voids");
    CHECK_MSG(holes > 0 && filled > 0 && filled < holes, "%ld triangles with voids, %ld filled", holes, filled);
}

/* The chart alone: the series' colours are drawn where their values lie. */
static void test_chart(void)
{
    double a[50], b[50];
    chart_series s[2];
    char path[256];
    int i, w = 0, h = 0, red = 0, blue = 0, red_low = 0;
    uint8_t *rgb = NULL;
    br_err err;
    for (i = 0; i < 50; i++) { a[i] = 10; b[i] = 20 + (i & 1); }
    s[0].label = "ten"; s[0].y = a; s[0].n = 50;
    s[1].label = "twenty"; s[1].y = b; s[1].n = 50;
    snprintf(path, sizeof path, "%s/chart.png", t_outdir());
    CHECK_EQ(chart_png(path, 400, 200, "t", "x", "y", s, 0, &err), BR_E_ARG);
    CHECK_EQ(chart_png(path, 400, 200, "t", "x", "y", s, 2, &err), BR_OK);
    CHECK_EQ(png_read_rgb(path, &w, &h, &rgb, &err), BR_OK);
    if (!rgb) return;
    for (i = 0; i < w * h; i++) {
        uint32_t c = (uint32_t)rgb[3 * i] << 16 | (uint32_t)rgb[3 * i + 1] << 8 | rgb[3 * i + 2];
        if (c == 0xff6b5bu) { red++; if (i / w > h / 2) red_low++; }
        if (c == 0x5bc0ffu) blue++;
    }
    CHECK(red > 200 && blue > 200);
    CHECK(red_low > 200);   /* 10 of an axis to 25: the lower half */
    free(rgb);
}

/* bd_visibility (`bench --visibility`) on walls seen level from the south (96 x 64,
 * 60 degrees), one triangle of each class: A near, facing the camera; B behind A, wholly
 * covered by it; C beside A with its winding reversed (a back face); D far and smaller
 * than a pixel; E off screen to the left; and a strip of two triangles left of A (its odd
 * triangle drawn with its first two vertices swapped, as the rasteriser draws it) between
 * line triangles (an index repeated: not counted).  It fails when a class is taken for
 * another, the odd strip triangle is turned, or the owners of the pixels are misread. */
static void test_visibility_classes(void)
{
    static const int32_t at[19][3] = {
        { -100, 200, 0 }, { 100, 200, 0 }, { 0, 200, 200 },            /* A */
        { -50, 400, 0 }, { 50, 400, 0 }, { 0, 400, 100 },              /* B */
        { 170, 200, 0 }, { 120, 200, 0 }, { 145, 200, 100 },           /* C */
        { -300, 1000, 100 }, { -299, 1000, 100 }, { -299, 1000, 101 }, /* D */
        { -1000, 200, 0 }, { -900, 200, 0 }, { -950, 200, 100 },       /* E */
        { -75, 150, 130 }, { -75, 150, 100 }, { -45, 150, 130 }, { -45, 150, 100 }   /* the strip's */
    };
    br_index list[15] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14 };
    br_index strip[6] = { 16, 16, 15, 18, 17, 17 };
    rs_prim pr[2] = { { RS_LIST, 15, list }, { RS_STRIP, 6, strip } };
    const int32_t eye[3] = { 0, 0, 100 }, tg[3] = { 0, 1000, 100 };
    rs_vertex v[19];
    rs_cvert cache[19];
    bd_vis vc;
    rs_frame f;
    cam c;
    br_err err;
    int i;
    memset(v, 0, sizeof v);
    for (i = 0; i < 19; i++) {
        memcpy(v[i].p, at[i], sizeof at[i]);
        v[i].rgb = 0x808080u;
    }
    memset(&f, 0, sizeof f);
    memset(&vc, 0, sizeof vc);
    CHECK_EQ(cam_look_at(&c, eye, tg, 60000, 96, 64, 1, 100000), BR_OK);
    f.w = 96; f.h = 64; f.fmt = RS_FMT_XRGB8888; f.depth = RS_DEPTH32;
    f.v = v; f.nv = 19; f.cache = cache; f.prims = pr; f.nprims = 2;
    f.chunks = malloc(rs_chunk_mem_size(pr, 2));
    cam_viewproj(&c, &f.vp);
    CHECK_EQ(bd_visibility(&f, &vc, &err), BR_OK);
    CHECK_EQ(vc.frames, 1);
    CHECK_EQ(vc.tris, 7);     /* the strip's 16 16 15 and 18 17 17 left out */
    CHECK_MSG(vc.seen == 3 && vc.hidden == 1 && vc.back == 1 && vc.tiny == 1 && vc.edge == 1,
              "seen %llu hidden %llu back %llu tiny %llu edge %llu", (unsigned long long)vc.seen,
              (unsigned long long)vc.hidden, (unsigned long long)vc.back, (unsigned long long)vc.tiny,
              (unsigned long long)vc.edge);
    CHECK(f.cache == cache);  /* the caller's frame untouched */
    free(f.chunks);
}

int main(void)
{
    T_RUN(test_visibility_classes);
    T_RUN(test_json_checker);
    T_RUN(test_chart);
    /* these two run the program, ./bitrain, which is built for the host only (it needs
     * the display library): under qemu-user they would test the host's build, not this
     * target's (mk/cross.mk leaves out the test programs that name that library) */
    if (!t_emulated()) {
        T_RUN(test_bad_options);
        T_RUN(test_board_table);
        T_RUN(test_fill_voids);
        T_RUN(test_visibility_real);
    } else {
        t_skip("test_bad_options", "runs ./bitrain, built for the host only");
        t_skip("test_board_table", "runs ./bitrain, built for the host only");
        t_skip("test_fill_voids", "runs ./bitrain, built for the host only");
        t_skip("test_visibility_real", "runs ./bitrain, built for the host only");
    }
    return t_finish();
}
