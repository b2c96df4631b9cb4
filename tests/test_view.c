#define _POSIX_C_SOURCE 200809L
/* tests/test_view.c — the viewer and `bitrain run`, headless.
 * The viewer runs on SDL's dummy video driver for a few frames and saves its last
 * frame; `run` without a display renders the default terrain to out/terrain.png. */
#include "tests/test.h"
#include "platform/cmd.h"
#include "platform/png_io.h"

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
    char cam[] = "--camera", cv[] = "20000,20000,3500,40000,70000,800";
    char dem[] = "assets/N47E009.hgt.gz";
    char *argv[10];
    snprintf(shot, sizeof shot, "%s/view_frame.png", t_outdir());
    argv[0] = dem; argv[1] = size; argv[2] = wh; argv[3] = fr; argv[4] = three; argv[5] = ss; argv[6] = shot;
    argv[7] = cam; argv[8] = cv; argv[9] = NULL;
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
    T_RUN(test_run_headless);
    return t_finish();
}
