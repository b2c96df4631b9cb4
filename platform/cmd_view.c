/* platform/cmd_view.c — bitrain view IN...: the interactive viewer (SDL2 window).
 *
 * Each frame: the bitree's view-dependent mesh for the camera (hysteresis and
 * geomorphing on), turned into raster vertices, drawn by the integer rasteriser
 * band by band straight into a streaming SDL texture (XRGB8888), which SDL then
 * shows.  No allocation per frame.
 *
 * Controls: mouse drag look, W/S forward/back, A/D left/right, E/Q or PgUp/PgDn
 * up/down, arrow keys turn, Shift = 5x speed, +/- pixel error, H hysteresis,
 * G geomorph, C back-face culling, P screenshot, Space reset view, Esc quit. */
#include <SDL.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "platform/cmd.h"
#include "platform/dem_args.h"
#include "platform/png_io.h"
#include "platform/scene.h"

#define VIEW_BAND_ROWS 64
#define VIEW_MAX_TRI 2000000  /* beyond it the bitree falls back to its budget mode */

typedef struct view_state {
    double pos[3], yaw, pitch;       /* metres; radians, yaw clockwise from north */
    double fov, pix_err;
    int hyst, morph, no_cull;
} view_state;

static void look_from(view_state *v, const double eye[3], const double target[3])
{
    double dx = target[0] - eye[0], dy = target[1] - eye[1], dz = target[2] - eye[2];
    memcpy(v->pos, eye, sizeof v->pos);
    v->yaw = atan2(dx, dy);
    v->pitch = atan2(dz, sqrt(dx * dx + dy * dy));
}

static void view_dir(const view_state *v, double d[3])
{
    d[0] = sin(v->yaw) * cos(v->pitch);
    d[1] = cos(v->yaw) * cos(v->pitch);
    d[2] = sin(v->pitch);
}

static int save_png(const char *path, const uint32_t *px, int w, int h, br_err *err)
{
    uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
    int ok;
    if (!rgb) return 0;
    rs_to_rgb888(RS_FMT_XRGB8888, px, w * h, rgb);
    ok = png_write_rgb(path, w, h, rgb, (size_t)w * 3, err) == BR_OK;
    free(rgb);
    return ok;
}

static int usage(void)
{
    fprintf(stderr,
            "usage: bitrain view IN... [--size WxH] [--fov DEG] [--pixel-error P]\n"
            "         [--camera EX,EY,EZ,TX,TY,TZ] [--frames N] [--screenshot OUT.png]\n"
            "  camera in metres: x east from the west edge, y north from the south edge, z height\n"
            "  --frames N: quit after N frames (with --screenshot: save the last one)\n"
            "controls: mouse drag look, W/S forward/back, A/D left/right, E/Q up/down, arrows turn,\n"
            "  Shift faster, +/- pixel error, H hysteresis, G geomorph, C culling, P screenshot,\n"
            "  Space reset view, Esc quit\n" DEM_ARGS_USAGE);
    return 2;
}

int cmd_view(int argc, char **argv)
{
    const char *in[64], *shot = NULL;
    int r, nin = 0, i, w = 1024, h = 640, have_cam = 0, frames = 0, nframe = 0, shots = 0, rc = 1, quit = 0;
    double camv[6];
    view_state v;
    scene s;
    scene_opts so;
    br_err err;
    SDL_Window *win = NULL;
    SDL_Renderer *ren = NULL;
    SDL_Texture *tex = NULL;
    uint32_t *depth = NULL, *last = NULL;
    Uint64 t_prev;
    double mesh_ms = 0, raster_ms = 0, sum_mesh = 0, sum_raster = 0, sum_tri = 0;

    for (i = 0; i < argc; i++)      /* an SPI panel (no window): `render` draws to it band by band */
        if (!strcmp(argv[i], "--spi") || !strcmp(argv[i], "--spi-capture")) return cmd_render(argc, argv);
    memset(&so, 0, sizeof so);
    memset(&v, 0, sizeof v);
    v.fov = 60; v.pix_err = 1.5; v.hyst = 1; v.morph = 1;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i], *n = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--size") && n) { if (sscanf(n, "%dx%d", &w, &h) != 2) return usage(); i++; }
        else if (!strcmp(a, "--fov") && n) { v.fov = atof(n); i++; }
        else if (!strcmp(a, "--pixel-error") && n) { v.pix_err = atof(n); i++; }
        else if (!strcmp(a, "--frames") && n) { frames = atoi(n); i++; }
        else if (!strcmp(a, "--screenshot") && n) { shot = n; i++; }
        else if (!strcmp(a, "--camera") && n) {
            if (sscanf(n, "%lf,%lf,%lf,%lf,%lf,%lf", &camv[0], &camv[1], &camv[2], &camv[3], &camv[4], &camv[5]) != 6)
                return usage();
            have_cam = 1; i++;
        } else if ((r = dem_args_parse(&so.dem, argc, argv, &i, "view")) != 0) {
            if (r < 0) return 2;
        } else if (!strcmp(a, "-h") || !strcmp(a, "--help")) { usage(); return 0; }
        else if (a[0] == '-' && a[1]) { fprintf(stderr, "bitrain view: unknown option '%s'\n", a); return usage(); }
        else if (nin < 64) in[nin++] = a;
    }
    if (!nin || w < 16 || h < 16 || w > RS_MAX_DIM || h > RS_MAX_DIM || !(v.fov >= 5 && v.fov <= 150) ||
        !(v.pix_err > 0) || frames < 0)
        return usage();

    if (scene_open(&s, in, nin, &so, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); return 1; }
    if (scene_tree(&s, &err) != BR_OK || scene_reserve(&s, VIEW_MAX_TRI, &err) != BR_OK) {
        fprintf(stderr, "bitrain: %s: %s\n", in[0], err.msg);
        scene_close(&s);
        return 1;
    }
    if (have_cam) look_from(&v, camv, camv + 3);
    else { double e[3], t[3]; scene_default_view(&s, v.fov, e, t); look_from(&v, e, t); }

    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "bitrain view: cannot open a display: %s\n", SDL_GetError());
        scene_close(&s);
        return 1;
    }
    win = SDL_CreateWindow("bitrain", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, w, h, 0);
    ren = win ? SDL_CreateRenderer(win, -1, 0) : NULL;
    tex = ren ? SDL_CreateTexture(ren, SDL_PIXELFORMAT_RGB888, SDL_TEXTUREACCESS_STREAMING, w, h) : NULL;
    depth = malloc(rs_band_mem_size(w, VIEW_BAND_ROWS, RS_FMT_XRGB8888, RS_DEPTH32));
    last = malloc((size_t)w * (size_t)h * 4);
    if (!tex || !depth || !last) {
        fprintf(stderr, "bitrain view: cannot create the window: %s\n", SDL_GetError());
        goto done;
    }
    printf("bitrain view: %dx%d heightfield, %.1f x %.1f km, heights %.0f..%.0f m; F1 or --help for controls\n",
           s.f.w, s.f.h, s.width_m / 1000, s.depth_m / 1000, s.zmin_m, s.zmax_m);
    t_prev = SDL_GetPerformanceCounter();
    while (!quit) {
        SDL_Event ev;
        const Uint8 *k;
        double dt, d[3], speed, right[2], ground, tgt[3];
        Uint64 t_now, ta, tb, tc;
        cam c;
        bt_params bp;
        rs_frame fr;
        rs_prim prim;
        void *px;
        int pitch, y0;
        char title[256];

        while (SDL_PollEvent(&ev)) {
            if (ev.type == SDL_QUIT) quit = 1;
            else if (ev.type == SDL_MOUSEMOTION && (ev.motion.state & SDL_BUTTON_LMASK)) {
                v.yaw += ev.motion.xrel * 0.004;
                v.pitch -= ev.motion.yrel * 0.004;
            } else if (ev.type == SDL_KEYDOWN) {
                switch (ev.key.keysym.sym) {
                case SDLK_ESCAPE: quit = 1; break;
                case SDLK_PLUS: case SDLK_EQUALS: case SDLK_KP_PLUS: v.pix_err *= 1.5; break;
                case SDLK_MINUS: case SDLK_KP_MINUS: if (v.pix_err > 0.2) v.pix_err /= 1.5; break;
                case SDLK_h: v.hyst = !v.hyst; break;
                case SDLK_g: v.morph = !v.morph; break;
                case SDLK_c: v.no_cull = !v.no_cull; break;
                case SDLK_F1: usage(); break;
                case SDLK_SPACE: { double e[3], t[3]; scene_default_view(&s, v.fov, e, t); look_from(&v, e, t); } break;
                case SDLK_p: {
                    char path[64];
                    mkdir("out", 0777);
                    snprintf(path, sizeof path, "out/view-%d.png", ++shots);
                    if (save_png(path, last, w, h, &err)) printf("%s\n", path);
                    else fprintf(stderr, "bitrain: %s\n", err.msg);
                } break;
                default: break;
                }
            }
        }
        t_now = SDL_GetPerformanceCounter();
        dt = (double)(t_now - t_prev) / (double)SDL_GetPerformanceFrequency();
        t_prev = t_now;
        if (dt > 0.1) dt = 0.1;
        k = SDL_GetKeyboardState(NULL);
        if (k[SDL_SCANCODE_LEFT]) v.yaw -= 1.2 * dt;
        if (k[SDL_SCANCODE_RIGHT]) v.yaw += 1.2 * dt;
        if (k[SDL_SCANCODE_UP]) v.pitch += 0.8 * dt;
        if (k[SDL_SCANCODE_DOWN]) v.pitch -= 0.8 * dt;
        if (v.pitch > 1.5) v.pitch = 1.5;
        if (v.pitch < -1.5) v.pitch = -1.5;
        ground = scene_ground(&s, v.pos[0], v.pos[1]);
        if (isnan(ground)) ground = s.zmin_m;
        speed = fmax(20.0, 0.6 * (v.pos[2] - ground)) * ((k[SDL_SCANCODE_LSHIFT] || k[SDL_SCANCODE_RSHIFT]) ? 5 : 1);
        view_dir(&v, d);
        right[0] = cos(v.yaw); right[1] = -sin(v.yaw);
        for (i = 0; i < 3; i++) {
            double m = (k[SDL_SCANCODE_W] ? 1 : 0) - (k[SDL_SCANCODE_S] ? 1 : 0);
            v.pos[i] += d[i] * m * speed * dt;
        }
        for (i = 0; i < 2; i++)
            v.pos[i] += right[i] * ((k[SDL_SCANCODE_D] ? 1 : 0) - (k[SDL_SCANCODE_A] ? 1 : 0)) * speed * dt;
        v.pos[2] += ((k[SDL_SCANCODE_E] || k[SDL_SCANCODE_PAGEUP] ? 1 : 0) -
                     (k[SDL_SCANCODE_Q] || k[SDL_SCANCODE_PAGEDOWN] ? 1 : 0)) * speed * dt;
        ground = scene_ground(&s, v.pos[0], v.pos[1]);
        if (!isnan(ground) && v.pos[2] < ground + 2) v.pos[2] = ground + 2;
        for (i = 0; i < 3; i++) tgt[i] = v.pos[i] + d[i] * 1000;
        if (scene_camera(&s, v.pos, tgt, v.fov, w, h, &c) != BR_OK) {
            double e[3], t[3];
            scene_default_view(&s, v.fov, e, t);   /* flew out of the world's range: back home */
            look_from(&v, e, t);
            continue;
        }

        ta = SDL_GetPerformanceCounter();
        memset(&bp, 0, sizeof bp);
        memset(&fr, 0, sizeof fr);
        bp.pixel_err_q8 = (int32_t)lround(v.pix_err * 256);
        bp.hyst_q8 = v.hyst ? 64 : 0;
        bp.morph_q8 = v.morph ? 128 : 0;
        fr.fmt = RS_FMT_XRGB8888;
        fr.depth = RS_DEPTH32;
        fr.no_cull = v.no_cull;
        fr.clear_rgb = 0x99ccffu;
        if (scene_frame(&s, &c, &bp, &fr, &prim) != BR_OK) { fprintf(stderr, "bitrain view: frame failed\n"); goto done; }
        tb = SDL_GetPerformanceCounter();
        if (SDL_LockTexture(tex, NULL, &px, &pitch) != 0) { fprintf(stderr, "bitrain view: %s\n", SDL_GetError()); goto done; }
        for (y0 = 0; y0 < h; y0 += VIEW_BAND_ROWS) {
            int rows = h - y0 < VIEW_BAND_ROWS ? h - y0 : VIEW_BAND_ROWS;
            rs_render_band(&fr, y0, rows, (uint8_t *)px + (size_t)y0 * (size_t)pitch, (size_t)pitch, depth);
        }
        for (y0 = 0; y0 < h; y0++) memcpy(last + (size_t)y0 * (size_t)w, (uint8_t *)px + (size_t)y0 * (size_t)pitch, (size_t)w * 4);
        SDL_UnlockTexture(tex);
        tc = SDL_GetPerformanceCounter();
        SDL_RenderCopy(ren, tex, NULL, NULL);
        SDL_RenderPresent(ren);
        {
            double m_ms = 1e3 * (double)(tb - ta) / (double)SDL_GetPerformanceFrequency();
            double r_ms = 1e3 * (double)(tc - tb) / (double)SDL_GetPerformanceFrequency();
            mesh_ms = nframe ? 0.9 * mesh_ms + 0.1 * m_ms : m_ms;
            raster_ms = nframe ? 0.9 * raster_ms + 0.1 * r_ms : r_ms;
            sum_mesh += m_ms; sum_raster += r_ms; sum_tri += s.mesh.ntri;
        }
        snprintf(title, sizeof title, "bitrain  %u triangles  mesh %.1f ms  raster %.1f ms  pixel error %.2f%s%s",
                 s.mesh.ntri, mesh_ms, raster_ms, v.pix_err, v.hyst ? "" : "  (no hysteresis)",
                 v.morph ? "" : "  (no geomorph)");
        SDL_SetWindowTitle(win, title);
        if (++nframe >= frames && frames) quit = 1;
    }
    if (nframe)
        printf("bitrain view: %d frames, mean %.0f triangles, mesh %.2f ms, raster %.2f ms per frame\n",
               nframe, sum_tri / nframe, sum_mesh / nframe, sum_raster / nframe);
    if (shot) {
        if (!save_png(shot, last, w, h, &err)) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
        printf("%s\n", shot);
    }
    rc = 0;
done:
    free(depth);
    free(last);
    if (tex) SDL_DestroyTexture(tex);
    if (ren) SDL_DestroyRenderer(ren);
    if (win) SDL_DestroyWindow(win);
    SDL_Quit();
    scene_close(&s);
    return rc;
}
