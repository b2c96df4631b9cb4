/* benchmarks/osmesa/bench_osmesa.c — the peer scene through Mesa llvmpipe (OSMesa).
 *
 * A benchmark-only program, outside core/ and raster/ (floating point is fine here),
 * built by benchmarks/osmesa/build.sh only when pkg-config finds osmesa.  It is the
 * reference side of the side-by-side run in benchmarks/osmesa.sh.
 *
 * Scene: exactly ../shared/bench/peer_scene.py (see ../shared/bench/PEERS.md):
 *   fuji.png (terrain-RGB, h = -10000 + (R*65536 + G*256 + B) * 0.1 m) sampled at pixel
 *   (min(2i,511), min(2j,511)) into a 257x257 grid; world x = i, y = 256 - j,
 *   z = (h - hmin) * 64 / (hmax - hmin); per-vertex colour = height ramp *
 *   (0.30 + 0.70 max(0, N.L)), L = normalise(-1,-1,1.5), normals by central differences.
 *   The scene is computed in double in the same operation order as the Python script and
 *   stored as float (positions, colours) and bytes (RGBA), like scene.bin; --check compares.
 *   131,072 triangles drawn as 256 GL_TRIANGLE_STRIPs of 514 indices (client arrays,
 *   glDrawElements per row), depth test on, smooth shading, clear colour light blue,
 *   back-face culling off unless --cull.  Colours are 3 floats per vertex by default
 *   (--colour float): with them the callgrind counts equal PEERS.md's to 1 %; 4 bytes per
 *   vertex (--colour ubyte) cost llvmpipe about 1 % fewer instructions.
 * Cameras (gluLookAt + gluPerspective conventions, computed here by hand):
 *   A: eye (128,-100,180) target (128,100,0) up z, fovy 55, near 10, far 1000.
 *   B: eye (110,5,1.1717901) target (190,256,-10.828210) up z, fovy 75, near 0.25, far 1000.
 *
 * Usage: bench_osmesa [--camera A|B] [--size WxH] [--frames N] [--warmup N] [--cull]
 *                     [--colour ubyte|float] [--dem fuji.png] [-o last.png] [--check scene.bin]
 *        bench_osmesa --compare a.png b.png   (pixel difference of two renderers' frames)
 * Prints one line per run: `llvmpipe camera=A size=320x240 cull=0 frames=N ms/frame=M ...`
 * (median over the N timed frames; each frame = clear + 256 strips + glFinish).
 * The timed frames run inside timed_frame(), warm-up frames (shader JIT) inside
 * warm_frame(), so `valgrind --tool=callgrind --toggle-collect=timed_frame` counts the
 * instructions of the timed frames only; divide by N.
 * Environment for fair numbers (PEERS.md): LP_NUM_THREADS=0 and
 * GLIBC_TUNABLES=glibc.malloc.mmap_threshold=33554432:glibc.malloc.trim_threshold=2147483647.
 */
#define _POSIX_C_SOURCE 200809L
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <png.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "benchmarks/peer_scene.h"

/* The scene is built by bitrain's own builder (benchmarks/peer_scene.c), whose float
 * arrays are checked bit for bit against peer_scene.py's scene.bin (--check). */
typedef peer_scene scene_t;
#define N PEER_N
#define NV PEER_NV
#define STRIP_LEN PEER_STRIP_LEN
#define NSTRIP PEER_NSTRIP

static void die(const char *msg, const char *what)
{
    fprintf(stderr, "bench_osmesa: %s%s%s\n", msg, what ? ": " : "", what ? what : "");
    exit(1);
}

/* ---- fuji.png via libpng (low-level API: no gamma handling, bytes as stored) ---- */
static unsigned char *read_png(const char *path, int *w, int *h, int *bpp)
{
    FILE *f = fopen(path, "rb");
    if (!f) die("cannot open", path);
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (!png || !info) die("libpng init failed", path);
    if (setjmp(png_jmpbuf(png))) die("cannot decode PNG", path);
    png_init_io(png, f);
    png_read_png(png, info, PNG_TRANSFORM_STRIP_16 | PNG_TRANSFORM_PACKING | PNG_TRANSFORM_EXPAND, NULL);
    int ct = png_get_color_type(png, info);
    if (ct != PNG_COLOR_TYPE_RGB && ct != PNG_COLOR_TYPE_RGB_ALPHA) die("not an RGB(A) PNG", path);
    *w = (int)png_get_image_width(png, info);
    *h = (int)png_get_image_height(png, info);
    *bpp = png_get_channels(png, info);
    png_bytepp rows = png_get_rows(png, info);
    size_t stride = (size_t)*w * (size_t)*bpp;
    unsigned char *px = malloc(stride * (size_t)*h);
    if (!px) die("out of memory", NULL);
    for (int y = 0; y < *h; y++) memcpy(px + (size_t)y * stride, rows[y], stride);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    return px;
}

static void write_png(const char *path, const unsigned char *rgba, int w, int h)
{
    FILE *f = fopen(path, "wb");
    if (!f) die("cannot write", path);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (!png || !info) die("libpng init failed", path);
    if (setjmp(png_jmpbuf(png))) die("cannot encode PNG", path);
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    unsigned char *row = malloc((size_t)w * 3);
    if (!row) die("out of memory", NULL);
    for (int y = 0; y < h; y++) {
        const unsigned char *src = rgba + (size_t)(h - 1 - y) * (size_t)w * 4; /* GL is bottom-up */
        for (int x = 0; x < w; x++) {
            row[3 * x] = src[4 * x];
            row[3 * x + 1] = src[4 * x + 1];
            row[3 * x + 2] = src[4 * x + 2];
        }
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    fclose(f);
}

/* ---- --check: compare with scene.bin written by peer_scene.py ---- */
static uint32_t rd_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float rd_f32(const unsigned char *p)
{
    uint32_t u = rd_u32(p);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static int check_scene(const char *path, const scene_t *s)
{
    FILE *f = fopen(path, "rb");
    if (!f) die("cannot open", path);
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)len);
    if (!b || fread(b, 1, (size_t)len, f) != (size_t)len) die("cannot read", path);
    fclose(f);
    if (len < 48 || memcmp(b, "TRN1", 4) != 0) die("not a TRN1 scene.bin", path);
    uint32_t nx = rd_u32(b + 4), ny = rd_u32(b + 8), nv = rd_u32(b + 12);
    uint32_t ni = rd_u32(b + 16), ns = rd_u32(b + 20);
    long want = 48 + (long)nv * 28 + (long)ni * 4 + (long)ns * 4;
    if (nx != N || ny != N || nv != NV || ni != 6u * NSTRIP * NSTRIP || ns != NSTRIP * STRIP_LEN || len != want) {
        fprintf(stderr, "check: header/size mismatch: %u %u %u %u %u len %ld want %ld\n", nx, ny, nv, ni, ns, len, want);
        return 1;
    }
    const unsigned char *pp = b + 48, *pc = pp + (size_t)nv * 12, *pr = pc + (size_t)nv * 12;
    const unsigned char *pi = pr + (size_t)nv * 4, *ps = pi + (size_t)ni * 4;
    long pos_diff = 0, col_diff = 0, rgba_diff = 0, idx_diff = 0, strip_diff = 0;
    double pos_max = 0, col_max = 0;
    for (uint32_t k = 0; k < nv * 3; k++) {
        double d = fabs((double)rd_f32(pp + 4 * k) - (double)s->pos[k]);
        if (d != 0) pos_diff++;
        if (d > pos_max) pos_max = d;
        d = fabs((double)rd_f32(pc + 4 * k) - (double)s->col[k]);
        if (d != 0) col_diff++;
        if (d > col_max) col_max = d;
    }
    for (uint32_t k = 0; k < nv * 4; k++) rgba_diff += pr[k] != s->rgba[k];
    /* the list must be the triangles of the strips in GL parity order (PEERS.md) */
    for (uint32_t t = 0; t < ni / 3; t++) {
        uint32_t row = t / (2 * NSTRIP), k = t % (2 * NSTRIP);
        const GLuint *st = s->strip + row * STRIP_LEN;
        GLuint a = st[k], bb = st[k + 1], c = st[k + 2];
        GLuint want3[3] = { a, bb, c };
        if (k & 1) { want3[0] = bb; want3[1] = a; } /* odd strip triangle: (v1, v0, v2) */
        for (int m = 0; m < 3; m++) idx_diff += rd_u32(pi + 4 * (3 * t + (uint32_t)m)) != want3[m];
    }
    for (uint32_t k = 0; k < ns; k++) strip_diff += rd_u32(ps + 4 * k) != s->strip[k];
    free(b);
    printf("check %s: positions %ld differ (max %.3g), colours %ld differ (max %.3g), "
           "rgba %ld differ, list indices %ld differ, strip indices %ld differ\n",
           path, pos_diff, pos_max, col_diff, col_max, rgba_diff, idx_diff, strip_diff);
    int bad = pos_max > 1e-5 || col_max > 1e-6 || rgba_diff || idx_diff || strip_diff;
    printf("check: %s\n", bad ? "MISMATCH" : "ok");
    return bad;
}

/* ---- --compare a.png b.png: how far two renderers' pictures are apart ---- */
static int compare_png(const char *pa, const char *pb)
{
    int wa, ha, ba, wb, hb, bb;
    unsigned char *a = read_png(pa, &wa, &ha, &ba), *b = read_png(pb, &wb, &hb, &bb);
    if (wa != wb || ha != hb) {
        printf("compare: sizes differ (%dx%d vs %dx%d)\n", wa, ha, wb, hb);
        return 1;
    }
    long n = (long)wa * ha, diff = 0, diff8 = 0, diff32 = 0, sky_a = 0, sky_b = 0;
    double sum = 0;
    for (long k = 0; k < n; k++) {
        const unsigned char *x = a + k * ba, *y = b + k * bb;
        int m = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs(x[c] - y[c]);
            sum += d;
            if (d > m) m = d;
        }
        diff += m > 0;
        diff8 += m > 8;
        diff32 += m > 32;
        sky_a += x[0] == 153 && x[1] == 204 && x[2] == 255;
        sky_b += y[0] == 153 && y[1] == 204 && y[2] == 255;
    }
    printf("compare %dx%d: pixels differing %.2f %%, by >8 %.2f %%, by >32 %.2f %%, mean |d| %.2f per channel; "
           "sky pixels %ld vs %ld\n", wa, ha, 100.0 * (double)diff / (double)n, 100.0 * (double)diff8 / (double)n,
           100.0 * (double)diff32 / (double)n, sum / (3.0 * (double)n), sky_a, sky_b);
    free(a);
    free(b);
    return 0;
}

/* ---- matrices: gluPerspective and gluLookAt by hand (column-major, like GL) ---- */
static void perspective(double fovy_deg, double aspect, double zn, double zf, double m[16])
{
    double f = 1.0 / tan(fovy_deg * 3.14159265358979323846 / 360.0);
    memset(m, 0, 16 * sizeof m[0]);
    m[0] = f / aspect;
    m[5] = f;
    m[10] = (zf + zn) / (zn - zf);
    m[11] = -1.0;
    m[14] = 2.0 * zf * zn / (zn - zf);
}

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l; v[1] /= l; v[2] /= l;
}

static void cross3(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static void look_at(const double eye[3], const double at[3], const double up[3], double m[16])
{
    double fw[3] = { at[0] - eye[0], at[1] - eye[1], at[2] - eye[2] }, sd[3], u[3];
    normalize3(fw);
    cross3(fw, up, sd);
    normalize3(sd);
    cross3(sd, fw, u);
    memset(m, 0, 16 * sizeof m[0]);
    m[0] = sd[0]; m[4] = sd[1]; m[8] = sd[2];
    m[1] = u[0];  m[5] = u[1];  m[9] = u[2];
    m[2] = -fw[0]; m[6] = -fw[1]; m[10] = -fw[2];
    m[12] = -(sd[0] * eye[0] + sd[1] * eye[1] + sd[2] * eye[2]);
    m[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    m[14] = fw[0] * eye[0] + fw[1] * eye[1] + fw[2] * eye[2];
    m[15] = 1.0;
}

/* ---- rendering ---- */
static const scene_t *g_scene;

static void draw_frame(void)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (int j = 0; j < NSTRIP; j++)
        glDrawElements(GL_TRIANGLE_STRIP, STRIP_LEN, GL_UNSIGNED_INT, g_scene->strip + j * STRIP_LEN);
    glFinish();
}

/* Separate non-inlined entry points so callgrind can count timed frames only. */
__attribute__((noinline)) void warm_frame(void);
__attribute__((noinline)) void timed_frame(void);
__attribute__((noinline)) void warm_frame(void) { draw_frame(); }
__attribute__((noinline)) void timed_frame(void) { draw_frame(); }

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static long count_covered(const unsigned char *buf, int w, int h)
{
    /* pixels that are not the clear colour, as a sanity figure */
    long n = 0;
    for (long k = 0; k < (long)w * h; k++) {
        const unsigned char *p = buf + 4 * k;
        if (!(p[0] == 153 && p[1] == 204 && p[2] == 255)) n++;
    }
    return n;
}

int main(int argc, char **argv)
{
    const char *dem = "../shared/data/dem/png/fuji.png", *out = NULL, *check = NULL, *colour = "float";
    char which = 'A';
    int w = 320, h = 240, frames = 50, warmup = 3, cull = 0;
    for (int a = 1; a < argc; a++) {
        const char *o = argv[a], *v = a + 1 < argc ? argv[a + 1] : NULL;
        if (!strcmp(o, "--cull")) { cull = 1; continue; }
        if (!strcmp(o, "--compare")) {
            if (a + 2 >= argc) die("--compare needs two PNG files", NULL);
            return compare_png(argv[a + 1], argv[a + 2]);
        }
        if (!v) die("missing value after", o);
        if (!strcmp(o, "--camera")) which = v[0];
        else if (!strcmp(o, "--size")) { if (sscanf(v, "%dx%d", &w, &h) != 2 || w < 1 || h < 1 || w > 8192 || h > 8192) die("bad --size", v); }
        else if (!strcmp(o, "--frames")) frames = atoi(v);
        else if (!strcmp(o, "--warmup")) warmup = atoi(v);
        else if (!strcmp(o, "--dem")) dem = v;
        else if (!strcmp(o, "-o")) out = v;
        else if (!strcmp(o, "--check")) check = v;
        else if (!strcmp(o, "--colour")) colour = v;
        else die("unknown option", o);
        a++;
    }
    if (which != 'A' && which != 'B') die("--camera must be A or B", NULL);
    if (frames < 1) frames = 1;
    if (warmup < 0) warmup = 0;
    int use_float = !strcmp(colour, "float");
    if (!use_float && strcmp(colour, "ubyte")) die("--colour must be ubyte or float", colour);

    scene_t *s = malloc(sizeof *s);
    if (!s) die("out of memory", NULL);
    if (peer_scene_build(dem, s) != 0) die("cannot build the scene from", dem);
    g_scene = s;
    if (check) return check_scene(check, s);

    OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, NULL);
    if (!ctx) die("OSMesaCreateContextExt failed", NULL);
    unsigned char *fb = malloc((size_t)w * (size_t)h * 4);
    if (!fb) die("out of memory", NULL);
    if (!OSMesaMakeCurrent(ctx, fb, GL_UNSIGNED_BYTE, w, h)) die("OSMesaMakeCurrent failed", NULL);

    double proj[16], view[16];
    if (which == 'A') {
        const double eye[3] = { 128, -100, 180 }, at[3] = { 128, 100, 0 }, up[3] = { 0, 0, 1 };
        perspective(55.0, (double)w / h, 10.0, 1000.0, proj);
        look_at(eye, at, up, view);
    } else {
        const double eye[3] = { 110, 5, 1.1717901 }, at[3] = { 190, 256, -10.828210 }, up[3] = { 0, 0, 1 };
        perspective(75.0, (double)w / h, 0.25, 1000.0, proj);
        look_at(eye, at, up, view);
    }
    glViewport(0, 0, w, h);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixd(proj);
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixd(view);
    glClearColor(0.6f, 0.8f, 1.0f, 1.0f);   /* light blue: (153, 204, 255) */
    glClearDepth(1.0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glShadeModel(GL_SMOOTH);
    glDisable(GL_LIGHTING);
    glDisable(GL_DITHER);
    if (cull) {
        glFrontFace(GL_CCW);
        glCullFace(GL_BACK);
        glEnable(GL_CULL_FACE);
    } else {
        glDisable(GL_CULL_FACE);
    }
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, s->pos);
    if (use_float) glColorPointer(3, GL_FLOAT, 0, s->col);
    else glColorPointer(4, GL_UNSIGNED_BYTE, 0, s->rgba);

    for (int k = 0; k < warmup; k++) warm_frame();
    double *ms = malloc((size_t)frames * sizeof *ms);
    if (!ms) die("out of memory", NULL);
    for (int k = 0; k < frames; k++) {
        double t0 = now_ms();
        timed_frame();
        ms[k] = now_ms() - t0;
    }
    if (glGetError() != GL_NO_ERROR) die("GL error", NULL);
    qsort(ms, (size_t)frames, sizeof *ms, cmp_double);
    double med = frames & 1 ? ms[frames / 2] : 0.5 * (ms[frames / 2 - 1] + ms[frames / 2]);
    long covered = count_covered(fb, w, h);
    printf("llvmpipe camera=%c size=%dx%d cull=%d colour=%s frames=%d ms/frame=%.3f min=%.3f max=%.3f "
           "Mtri/s=%.2f Mpix/s=%.2f covered=%ld renderer=\"%s\" version=\"%s\"\n",
           which, w, h, cull, colour, frames, med, ms[0], ms[frames - 1],
           131072.0 / med / 1e3, (double)w * h / med / 1e3, covered,
           (const char *)glGetString(GL_RENDERER), (const char *)glGetString(GL_VERSION));
    if (out) write_png(out, fb, w, h);
    OSMesaDestroyContext(ctx);
    free(ms);
    free(fb);
    free(s);
    return 0;
}
