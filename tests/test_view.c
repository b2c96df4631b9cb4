#define _POSIX_C_SOURCE 200809L
/* tests/test_view.c — the viewer and `bitrain run`, headless.
 * The viewer runs on SDL's dummy video driver for a few frames and saves its last
 * frame; `run` without a display renders the default terrain to out/terrain.png.
 * What needs no window is tested directly: the controls table, the camera limits,
 * latitude/longitude, --record, idling, thread counts. */
#include <math.h>
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/geocam.h"
#include "platform/png_io.h"
#include "platform/view.h"

/* Fraction (per mille) of pixels that are not the sky colour. */
static int terrain_permille(const char *path, int ew, int eh)
{
    int w, h, i, n = 0;
    uint8_t *rgb;
    br_err err;
    if (png_read_rgb(path, &w, &h, &rgb, &err) != BR_OK) return -1;
    if (w != ew || h != eh) { free(rgb); return -2; }
    for (i = 0; i < w * h; i++)
        if (!(rgb[3 * i] == 0x99 && rgb[3 * i + 1] == 0xcc && rgb[3 * i + 2] == 0xff)) n++;
    free(rgb);
    return (int)((long)n * 1000 / ((long)w * h));
}

static void test_viewer_frames(void)
{
    char shot[256], size[] = "--size", wh[] = "320x200", fr[] = "--frames", three[] = "3", ss[] = "--screenshot";
    char camo[] = "--camera", cv[] = "20000,20000,3500,40000,70000,800";
    char dem[] = "assets/N47E009.hgt.gz";
    char *argv[10];
    snprintf(shot, sizeof shot, "%s/view_frame.png", t_outdir());
    argv[0] = dem; argv[1] = size; argv[2] = wh; argv[3] = fr; argv[4] = three; argv[5] = ss; argv[6] = shot;
    argv[7] = camo; argv[8] = cv; argv[9] = NULL;
    setenv("SDL_VIDEODRIVER", "dummy", 1);
    CHECK_EQ(cmd_view(9, argv), 0);
    /* looking north from the Alps over the lake: terrain fills most of the frame */
    CHECK(terrain_permille(shot, 320, 200) > 400);
}

static void test_view_bad_input(void)
{
    char missing[] = "tests/out/no_such_file.hgt", bad[] = "--size", badv[] = "0x0";
    char *a1[1], *a2[3];
    a1[0] = missing;
    CHECK_EQ(cmd_view(1, a1), 1);
    a2[0] = missing; a2[1] = bad; a2[2] = badv;
    CHECK_EQ(cmd_view(3, a2), 2);
}

/* Without X11 or Wayland, SDL falls back to its invisible "offscreen" driver: the viewer
 * refuses (status 1) instead of drawing unseen (here 2 frames, else until killed), unless
 * SDL_VIDEODRIVER asks for an invisible driver (here "dummy": a window on "offscreen"
 * loads EGL, whose allocations LeakSanitizer reports in the sanitized run). */
static void test_view_no_display(void)
{
    char dem[] = "assets/N47E009.hgt.gz", size[] = "--size", wh[] = "64x48", fr[] = "--frames", two[] = "2";
    char *argv[6];
    argv[0] = dem; argv[1] = size; argv[2] = wh; argv[3] = fr; argv[4] = two; argv[5] = NULL;
    unsetenv("SDL_VIDEODRIVER");
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    CHECK_EQ(cmd_view(5, argv), 1);
    setenv("SDL_VIDEODRIVER", "dummy", 1);
    CHECK_EQ(cmd_view(5, argv), 0);
}

/* Runs `bitrain view` with argv (a NULL-terminated list after the input file) on the
 * dummy video driver. */
static int view_run(const char *const *args)
{
    char *argv[40];
    char dem[] = "assets/N47E009.hgt.gz";
    int n = 0;
    argv[n++] = dem;
    while (*args && n < 39) argv[n++] = (char *)*args++;
    argv[n] = NULL;
    setenv("SDL_VIDEODRIVER", "dummy", 1);
    return cmd_view(n, argv);
}

static long file_lines(const char *path, long *comments)
{
    FILE *f = fopen(path, "r");
    char line[512];
    long n = 0;
    *comments = 0;
    if (!f) return -1;
    while (fgets(line, sizeof line, f)) {
        double c[6];
        if (line[0] == '#') { (*comments)++; continue; }
        if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf", &c[0], &c[1], &c[2], &c[3], &c[4], &c[5]) == 6) n++;
        else n = -1000000;
    }
    fclose(f);
    return n;
}

static int same_png(const char *a, const char *b)
{
    int w1, h1, w2, h2, same;
    uint8_t *p1 = NULL, *p2 = NULL;
    br_err err;
    if (png_read_rgb(a, &w1, &h1, &p1, &err) != BR_OK || png_read_rgb(b, &w2, &h2, &p2, &err) != BR_OK) {
        free(p1);
        return 0;
    }
    same = w1 == w2 && h1 == h2 && !memcmp(p1, p2, (size_t)w1 * (size_t)h1 * 3);
    free(p1);
    free(p2);
    return same;
}

/* --record writes one camera line per frame drawn, after # comments. */
static void test_view_record(void)
{
    char rec[256];
    long com;
    const char *args[] = { "--size", "160x100", "--frames", "4", "--record", rec, NULL };
    snprintf(rec, sizeof rec, "%s/view_path.txt", t_outdir());
    CHECK_EQ(view_run(args), 0);
    CHECK_EQ(file_lines(rec, &com), 4);
    CHECK(com >= 1);
}

/* Nothing moves, nothing changes: the viewer draws its first frame and the one after
 * (hysteresis settles), then waits instead of redrawing. */
static void test_view_idle(void)
{
    char rec[256];
    long com, n;
    const char *args[] = { "--size", "160x100", "--seconds", "1.5", "--record", rec, NULL };
    snprintf(rec, sizeof rec, "%s/view_idle.txt", t_outdir());
    CHECK_EQ(view_run(args), 0);
    n = file_lines(rec, &com);
    CHECK_MSG(n >= 1 && n <= 3, "%ld frames drawn in 1.5 s of idling", n);
}

/* The same frame for 1, 2 and 3 threads and for bands of 64 and 5 rows. */
static void test_view_threads_same(void)
{
    char a[256], b[256], c[256];
    const char *base[] = { "--size", "320x200", "--frames", "2", "--no-hud", "--camera",
                           "20000,20000,3500,40000,70000,800", "--time", "1", "--threads", "1", "--screenshot", a, NULL };
    const char *two[] = { "--size", "320x200", "--frames", "2", "--no-hud", "--camera",
                          "20000,20000,3500,40000,70000,800", "--time", "1", "--threads", "2", "--screenshot", b, NULL };
    const char *three[] = { "--size", "320x200", "--frames", "2", "--no-hud", "--camera",
                            "20000,20000,3500,40000,70000,800", "--time", "1", "--threads", "3", "--bands", "5", "--screenshot", c, NULL };
    snprintf(a, sizeof a, "%s/view_t1.png", t_outdir());
    snprintf(b, sizeof b, "%s/view_t2.png", t_outdir());
    snprintf(c, sizeof c, "%s/view_t3.png", t_outdir());
    CHECK_EQ(view_run(base), 0);
    CHECK_EQ(view_run(two), 0);
    CHECK_EQ(view_run(three), 0);
    CHECK(same_png(a, b));
    CHECK(same_png(a, c));
}

/* --look-from/--look-at give the frame of the --camera they convert to. */
static void test_view_look_from(void)
{
    char a[256], b[256], from[96], at[96], camarg[200];
    const char *bad1[] = { "--look-from", "47.5,9.5,2000", NULL };
    const char *bad2[] = { "--look-from", "47.5,9.5,2000", "--look-at", "10,10,0", NULL };
    const char *bad3[] = { "--look-from", "47.5,9.5,2000", "--look-at", "47.6,9.5,400", "--camera", "1,2,3,4,5,6", NULL };
    const char *geo[] = { "--size", "160x100", "--frames", "1", "--no-hud", "--time", "1", "--look-from", from, "--look-at", at,
                          "--screenshot", a, NULL };
    const char *met[] = { "--size", "160x100", "--frames", "1", "--no-hud", "--time", "1", "--camera", camarg, "--screenshot", b, NULL };
    scene s;
    scene_opts o;
    br_err err;
    const char *in[1] = { "assets/N47E009.hgt.gz" };
    double e[3], t[3], lat, lon;
    memset(&o, 0, sizeof o);
    CHECK_EQ(scene_open(&s, in, 1, &o, &err), BR_OK);
    CHECK(geocam_ok(&s));
    /* the south-west corner sample of N47E009 is at 47 N 9 E */
    geocam_to_deg(&s, 0, 0, &lat, &lon);
    CHECK(fabs(lat - 47) < 1e-6 && fabs(lon - 9) < 1e-6);
    geocam_from_deg(&s, 47.6, 9.45, 1500, e);
    geocam_to_deg(&s, e[0], e[1], &lat, &lon);
    CHECK(fabs(lat - 47.6) < 1e-9 && fabs(lon - 9.45) < 1e-9 && fabs(e[2] - 1500) < 1e-9);
    geocam_from_deg(&s, 47.55, 9.6, 395, t);
    scene_close(&s);
    snprintf(from, sizeof from, "47.6,9.45,1500");
    snprintf(at, sizeof at, "47.55,9.6,395");
    snprintf(camarg, sizeof camarg, "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f", e[0], e[1], e[2], t[0], t[1], t[2]);
    snprintf(a, sizeof a, "%s/view_geo.png", t_outdir());
    snprintf(b, sizeof b, "%s/view_met.png", t_outdir());
    CHECK_EQ(view_run(geo), 0);
    CHECK_EQ(view_run(met), 0);
    CHECK(same_png(a, b));
    CHECK(terrain_permille(a, 160, 100) > 300);
    CHECK_EQ(view_run(bad1), 2);        /* --look-from without --look-at */
    CHECK_EQ(view_run(bad2), 2);        /* far outside the terrain */
    CHECK_EQ(view_run(bad3), 2);        /* with --camera */
}

/* No key does two things. */
static void test_view_controls(void)
{
    const char *help = view_controls_text();
    CHECK_EQ(view_controls_clash(), 0);
    CHECK(strstr(help, "Esc") && strstr(help, "Tab") && strstr(help, "F11"));
}

/* The camera never ends under the terrain, past the world's edge or above the ceiling,
 * and says so when it stops. */
/* The fly camera's near plane follows its height above ground: from the default view,
 * 60 km over the tile, a near plane of 0.5 m (a target 1 km ahead) left the depth
 * buffer metres a unit at the lakes, and the water's shore test drew water over land. */
static void test_view_near_plane(void)
{
    scene s;
    scene_opts o;
    br_err err;
    view_state v;
    cam c;
    const char *in[1] = { "assets/N47E009.hgt.gz" };
    double e[3], t[3], eye[3], tgt[3];
    memset(&o, 0, sizeof o);
    memset(&v, 0, sizeof v);
    CHECK_EQ(scene_open(&s, in, 1, &o, &err), BR_OK);
    scene_default_view(&s, 60, e, t);
    view_init(&v, &s, e, t);
    view_eye_target(&v, eye, tgt);
    CHECK_EQ(scene_camera(&s, eye, tgt, 60, 320, 200, &c), BR_OK);
    CHECK_MSG((double)c.znear >= 10.0 * (double)(1 << s.rt.shift), "near plane %d units (2^%d m) from 60 km", c.znear,
              -s.rt.shift);
    scene_close(&s);
}

static void test_view_limits(void)
{
    scene s;
    scene_opts o;
    br_err err;
    view_state v;
    const char *in[1] = { "assets/N47E009.hgt.gz" };
    double e[3] = { 30000, 40000, 0 }, t[3] = { 31000, 41000, 0 }, g;
    memset(&o, 0, sizeof o);
    memset(&v, 0, sizeof v);
    CHECK_EQ(scene_open(&s, in, 1, &o, &err), BR_OK);
    view_init(&v, &s, e, t);
    view_limit(&v);                     /* under the ground: lifted */
    g = scene_ground(&s, 30000, 40000);
    CHECK(v.cam.pos[2] >= g + 2);
    v.cam.pos[0] = -1e6;                /* far west: stopped at the edge, with a note */
    v.now = 0;
    view_limit(&v);
    CHECK(v.cam.pos[0] > -0.3 * s.depth_m);
    CHECK(strstr(v.note, "edge") != NULL && strstr(v.note, "west") != NULL);
    v.cam.pos[2] = 1e7;                 /* above the ceiling */
    view_limit(&v);
    CHECK(v.cam.pos[2] <= s.zmax_m + 2 * s.depth_m);
    CHECK(strstr(v.note, "ceiling") != NULL);
    scene_close(&s);
}

/* Pixels (per mille) of the lower half whose blue exceeds red and green by 24: water
 * (the terrain's ramp is green to brown, the sky only in the upper half). */
static int water_permille(const char *path)
{
    int w, h, x, y, n = 0;
    uint8_t *rgb;
    br_err err;
    if (png_read_rgb(path, &w, &h, &rgb, &err) != BR_OK) return -1;
    for (y = h / 2; y < h; y++)
        for (x = 0; x < w; x++) {
            const uint8_t *p = rgb + 3 * ((size_t)y * (size_t)w + (size_t)x);
            n += p[2] > p[0] + 24 && p[2] > p[1] + 24;
        }
    free(rgb);
    return (int)((long)n * 1000 / ((long)w * (h - h / 2)));
}

/* The viewer draws the water scene (the lake from the water, as test_water's golden):
 * water under the horizon, none with --no-water --no-fog; F and V toggle fog and water
 * when the scene has them, and say so when it has not. */
static void test_view_water(void)
{
    char a[256], b[256];
    const char *wet[] = { "--size", "160x96", "--frames", "1", "--no-hud", "--time", "1.5", "--camera",
                          "40000,66000,420,60000,50000,500", "--screenshot", a, NULL };
    const char *dry[] = { "--size", "160x96", "--frames", "1", "--no-hud", "--no-water", "--no-fog", "--camera",
                          "40000,66000,420,60000,50000,500", "--screenshot", b, NULL };
    view_state v;
    SDL_Event ev;
    snprintf(a, sizeof a, "%s/view_water.png", t_outdir());
    snprintf(b, sizeof b, "%s/view_dry.png", t_outdir());
    CHECK_EQ(view_run(wet), 0);
    CHECK_EQ(view_run(dry), 0);
    CHECK_MSG(water_permille(a) > 800, "%d per mille water", water_permille(a));
    CHECK_MSG(water_permille(b) < 50, "%d per mille water", water_permille(b));
    memset(&v, 0, sizeof v);
    memset(&ev, 0, sizeof ev);
    ev.type = SDL_KEYDOWN;
    ev.key.keysym.sym = SDLK_f;
    v.water_scene = 1;
    v.on[VT_FOG] = 1;
    view_event(&v, &ev);
    CHECK_EQ(v.on[VT_FOG], 0);
    ev.key.keysym.sym = SDLK_v;
    view_event(&v, &ev);
    CHECK_EQ(v.on[VT_WATER], 1);
    CHECK(strstr(v.note, "water on") != NULL);
    v.water_scene = 0;
    view_event(&v, &ev);
    CHECK_EQ(v.on[VT_WATER], 1);
    CHECK(strstr(v.note, "--no-water --no-fog") != NULL);
}

/* The HUD describes the camera the frame was drawn from: a --path line's, not the
 * state's (which stays at home while a path is flown). */
static void test_view_hud_path_camera(void)
{
    scene s;
    scene_opts o;
    br_err err;
    view_state v;
    view_stats st;
    char hud[1024];
    const char *in[1] = { "assets/N47E009.hgt.gz" };
    double home_e[3] = { 10000, 10000, 3000 }, home_t[3] = { 20000, 20000, 500 };
    double e[3] = { 43210, 12345, 4321 }, t[3] = { 43210, 22345, 4321 };   /* due north, level */
    memset(&o, 0, sizeof o);
    memset(&v, 0, sizeof v);
    memset(&st, 0, sizeof st);
    o.quiet = 1;
    CHECK_EQ(scene_open(&s, in, 1, &o, &err), BR_OK);
    view_init(&v, &s, home_e, home_t);
    view_hud_frame_text(&v, e, t, &st, hud, sizeof hud);
    CHECK(strstr(hud, "x 43210  y 12345  z 4321 m") != NULL);
    CHECK(strstr(hud, "heading 0 N  pitch 0") != NULL);
    CHECK(v.cam.pos[0] == 10000);                     /* the state is untouched */
    view_hud_frame_text(&v, home_e, home_t, &st, hud, sizeof hud);
    CHECK(strstr(hud, "x 10000  y 10000  z 3000 m") != NULL);
    scene_close(&s);
}

/* render --path: one image per camera of the path, each byte-identical to
 * render --camera with that line. */
static void test_render_path(void)
{
    char cam_file[256], pat[256], f1[256], f2[256], c1[256], c2[256];
    static const char *const line[2] = { "-20671.4,-2752.9,59437.0,37683.4,55601.9,1651.0",
                                         "14000,9000,2500,30000,40000,400" };
    const char *a[] = { "render", "assets/N47E009.hgt.gz", "--size", "96x64", "--path", cam_file, "-o", pat, NULL };
    const char *bad[] = { "render", "assets/N47E009.hgt.gz", "--path", cam_file, "-o", c1, NULL };
    const char *b[] = { "render", "assets/N47E009.hgt.gz", "--size", "96x64", "--camera", line[0], "-o", c1, NULL };
    const char *d[] = { "render", "assets/N47E009.hgt.gz", "--size", "96x64", "--camera", line[1], "-o", c2, NULL };
    unsigned char *x, *y;
    size_t nx = 0, ny = 0;
    FILE *f;
    snprintf(cam_file, sizeof cam_file, "%s/render_path.cam", t_outdir());
    snprintf(pat, sizeof pat, "%s/render_path_%%03d.png", t_outdir());
    snprintf(f1, sizeof f1, "%s/render_path_001.png", t_outdir());
    snprintf(f2, sizeof f2, "%s/render_path_002.png", t_outdir());
    snprintf(c1, sizeof c1, "%s/render_path_cam1.png", t_outdir());
    snprintf(c2, sizeof c2, "%s/render_path_cam2.png", t_outdir());
    f = fopen(cam_file, "w");
    CHECK(f != NULL);
    if (!f) return;
    fprintf(f, "# two cameras\n%s\n\n%s\n", line[0], line[1]);
    fclose(f);
    remove(f1); remove(f2);
    CHECK_EQ(cmd_render(7, (char **)a + 1), 0);
    CHECK_EQ(cmd_render(5, (char **)bad + 1), 2);      /* -o without a %d */
    CHECK_EQ(cmd_render(7, (char **)b + 1), 0);
    CHECK_EQ(cmd_render(7, (char **)d + 1), 0);
    x = t_read_file(f1, &nx); y = t_read_file(c1, &ny);
    CHECK(x && y && nx == ny && nx > 100 && !memcmp(x, y, nx));
    free(x); free(y);
    x = t_read_file(f2, &nx); y = t_read_file(c2, &ny);
    CHECK(x && y && nx == ny && nx > 100 && !memcmp(x, y, nx));
    free(x); free(y);
}

static void test_run_headless(void)
{
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    remove("out/terrain.png");
    CHECK_EQ(cmd_run(0, NULL), 0);
    CHECK(terrain_permille("out/terrain.png", 1280, 720) > 200);
}

int main(void)
{
    T_RUN(test_viewer_frames);
    T_RUN(test_view_bad_input);
    T_RUN(test_view_no_display);
    T_RUN(test_view_record);
    T_RUN(test_view_idle);
    T_RUN(test_view_threads_same);
    T_RUN(test_view_look_from);
    T_RUN(test_view_controls);
    T_RUN(test_view_near_plane);
    T_RUN(test_view_limits);
    T_RUN(test_view_water);
    T_RUN(test_view_hud_path_camera);
    T_RUN(test_render_path);
    T_RUN(test_run_headless);
    return t_finish();
}
