#define _POSIX_C_SOURCE 200809L   /* mkdir, access */
/* platform/cmd_view.c — bitrain view IN...: the interactive viewer (SDL2 window).
 *
 * Each frame: the bitree's view-dependent mesh for the camera (hysteresis and
 * geomorphing on), its raster vertices, then the frame driver (raster/frame.h: the
 * terrain pass and the viewer's post hook, platform/view_hud.c; with water and fog the
 * water scene's passes and its fog and sky hook first, platform/water_scene.h) on N threads
 * (platform/pipe_threads.h) in bands of --bands rows into the frame buffer, which goes
 * to a streaming SDL texture.  The internal resolution follows the window (re-rendered
 * at the new size when it changes) unless --size fixes it, and then SDL scales it up.
 * Nothing is drawn while nothing moves.  No allocation per frame (only when the
 * window grows). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "platform/cmd.h"
#include "platform/campath.h"
#include "platform/dem_args.h"
#include "platform/geocam.h"
#include "platform/opt.h"
#include "platform/pipe_threads.h"
#include "platform/png_io.h"
#include "platform/scene_args.h"
#include "platform/sink_frame.h"
#include "platform/view.h"
#include "platform/water_scene.h"

#define VIEW_MAX_TRI 2000000  /* beyond it the bitree falls back to its budget mode */
#define SKY_RGB 0x99ccffu

typedef struct view_app {
    scene s;
    view_state v;
    view_stats st;
    view_overlay ov;
    pt_pool *pool;
    SDL_Window *win;
    SDL_Renderer *ren;
    SDL_Texture *tex;
    int w, h, fixed;            /* internal resolution; 1: fixed by --size */
    uint32_t *px;               /* the frame, w * h */
    size_t px_cap;
    int16_t *chunks;
    rs_vertex *lod_v;           /* LOD colouring: a list of triangles with vertices of their own */
    uint32_t *lod_idx;
    rs_cvert *lod_cache;
    size_t lod_cap;
    int band_rows;
    double base_err;            /* --pixel-error: where --fps starts and where it settles when idle */
    FILE *rec;
    campath path;               /* --path: one camera a frame (path.n == 0: the user flies) */
    int nframe, shots, sdl_on;
    char hud[1024];
    double sum_ms, sum_tri;
    water_scene ws;             /* water and fog (ws_on: opened by ws_open) */
    int ws_on, nbodies;         /* nbodies: the water bodies ws_open found */
    int clock_waves;            /* 1: the ripples follow the clock (no --time) */
    double t_start;             /* seconds, the first frame */
} view_app;

/* The two post hooks of a water frame: fog and sky (raster/water.h rw_post) first, then
 * the HUD and wireframe over them.  Read-only while the bands are drawn. */
typedef struct view_posts {
    const void *rw;
    const view_overlay *ov;
} view_posts;

static br_status post_both(const void *user, rs_band *b, rs_band_stats *st)
{
    const view_posts *p = (const view_posts *)user;
    br_status r = rw_post(p->rw, b, st);
    return r != BR_OK ? r : view_post(p->ov, b, st);
}

/* The water scene's pipe for the prepared terrain frame fr (V: water, F: fog); NULL when
 * both are off or on failure (message in the note). */
static rs_pipe *water_pipe(view_app *a, const cam *c, rs_frame *fr)
{
    view_state *v = &a->v;
    br_err err;
    br_status st;
    if (!a->ws_on || (!v->on[VT_FOG] && !v->on[VT_WATER])) return NULL;
    memset(&err, 0, sizeof err);
    a->ws.o.no_fog = !v->on[VT_FOG];
    a->ws.nbodies = v->on[VT_WATER] ? a->nbodies : 0;
    if (a->clock_waves) a->ws.o.time_s = v->now - a->t_start;
    a->ws.o.shore_bound = 1;              /* the selection's screen error (+/-, --fps) */
    a->ws.o.shore_px = v->pix_err;
    a->ws.o.view_px = v->pix_err;         /* the reflection's own selection scales it */
    st = ws_frame(&a->ws, &a->s, c, fr, &err);
    a->ws.nbodies = a->nbodies;
    if (st != BR_OK) { view_note(v, 3, "water: %s", err.msg); return NULL; }
    return &a->ws.pipe;
}

/* ---------------------------------------------------------------- frame */

static double now_s(void) { return (double)SDL_GetPerformanceCounter() / (double)SDL_GetPerformanceFrequency(); }

static void smooth(double *acc, double x, int first) { *acc = first ? x : 0.9 * *acc + 0.1 * x; }

/* LOD colouring: the frame draws the mesh as a list of separately tinted triangles
 * (memory grows with the mesh, only in this mode). */
static int lod_frame(view_app *a, rs_frame *fr, rs_prim *prim)
{
    size_t need = a->s.mesh.ns > 2 ? 3 * (size_t)(a->s.mesh.ns - 2) : 3;
    if (need > a->lod_cap) {
        rs_vertex *lv = realloc(a->lod_v, need * sizeof *lv);
        uint32_t *li = lv ? realloc(a->lod_idx, need * sizeof *li) : NULL;
        rs_cvert *lc = li ? realloc(a->lod_cache, rs_cache_mem_size((uint32_t)need)) : NULL;
        if (lv) a->lod_v = lv;
        if (li) a->lod_idx = li;
        if (lc) a->lod_cache = lc;
        if (!lc) return 0;
        a->lod_cap = need;
    }
    prim->kind = RS_LIST;
    prim->n = view_lod_list(&a->s.mesh, a->s.verts, a->lod_v, a->lod_idx);
    prim->idx = a->lod_idx;
    fr->v = a->lod_v;
    fr->nv = prim->n;
    fr->cache = a->lod_cache;
    return 1;
}

/* Draws one frame into a->px; 0 on failure (message printed). */
static int draw_frame(view_app *a)
{
    view_state *v = &a->v;
    double eye[3], tgt[3], t0, t1, t2, t3;
    cam c;
    bt_params bp;
    rs_frame fr;
    rs_prim prim;
    rs_pass terrain;
    rs_pipe p, *run;
    rs_band_stats tot;
    sink_frame sf;
    view_posts posts;
    int first = a->nframe == 0;
    if (a->path.n) {
        const double *k = a->path.cam[a->nframe % a->path.n];
        memcpy(eye, k, sizeof eye);
        memcpy(tgt, k + 3, sizeof tgt);
    } else view_eye_target(v, eye, tgt);
    if (scene_camera(&a->s, eye, tgt, v->fov, a->w, a->h, &c) != BR_OK) {
        view_note(v, 3, "camera out of range: back to the start");
        v->cam = v->home;
        v->orbit = 0;
        view_eye_target(v, eye, tgt);
        if (scene_camera(&a->s, eye, tgt, v->fov, a->w, a->h, &c) != BR_OK) return 0;
    }
    memset(&bp, 0, sizeof bp);
    memset(&fr, 0, sizeof fr);
    memset(&p, 0, sizeof p);
    bp.mode = BT_VIEW;
    bp.pixel_err_q8 = (int32_t)lround(v->pix_err * 256);
    bp.hyst_q8 = v->on[VT_HYST] ? 64 : 0;
    bp.morph_q8 = v->on[VT_MORPH] ? 128 : 0;
    t0 = now_s();
    /* selection, strip and raster vertices, on the pool's threads */
    if (scene_mesh(&a->s, &c, &bp) != BR_OK) { fprintf(stderr, "bitrain view: mesh selection failed\n"); return 0; }
    t1 = now_s();
    prim.kind = RS_STRIP; prim.n = a->s.mesh.ns; prim.idx = a->s.mesh.strip;
    fr.w = a->w; fr.h = a->h; fr.fmt = RS_FMT_XRGB8888; fr.depth = RS_DEPTH32;
    fr.no_cull = v->on[VT_NOCULL];
    fr.clear_rgb = SKY_RGB;
    fr.v = a->s.verts; fr.nv = a->s.mesh.nv; fr.cache = a->s.cache;
    if (v->on[VT_LOD] && !lod_frame(a, &fr, &prim)) view_note(v, 3, "LOD colouring: out of memory");
    fr.prims = &prim; fr.nprims = 1;
    fr.tex = a->s.rt.tex_w > 0 ? &a->s.tex : NULL;
    fr.chunks = a->chunks;
    cam_viewproj(&c, &fr.vp);
    if (rs_frame_prepare(&fr) != BR_OK || rs_pass_terrain(&terrain, &fr) != BR_OK) {
        fprintf(stderr, "bitrain view: bad frame\n");
        return 0;
    }
    p.w = a->w; p.h = a->h; p.fmt = RS_FMT_XRGB8888; p.depth = RS_DEPTH32;
    rs_pipe_add(&p, &terrain);
    run = water_pipe(a, &c, &fr);
    t2 = now_s();
    a->ov.fr = &fr;
    a->ov.wire = v->on[VT_WIRE];
    a->ov.band_rows = v->on[VT_BANDS] ? a->band_rows : 0;
    a->ov.scale = a->w >= 1600 ? 2 : 1;
    a->ov.h = a->h;
    a->st.w = a->w; a->st.h = a->h;
    view_hud_frame_text(v, eye, tgt, &a->st, a->hud, sizeof a->hud);   /* the path's camera when flying one */
    a->ov.hud = v->on[VT_HUD] ? a->hud : NULL;
    a->ov.help = v->on[VT_HELP] ? view_controls_text() : NULL;
    if (run) {
        posts.rw = run->post_user;
        posts.ov = &a->ov;
        run->post = post_both;
        run->post_user = &posts;
    } else {
        run = &p;
        p.post = view_post;
        p.post_user = &a->ov;
    }
    sf.px = a->px;
    sf.row_bytes = (size_t)a->w * 4;
    if (pt_run(a->pool, run, a->band_rows, sink_frame_band, &sf, &tot) != BR_OK) {
        fprintf(stderr, "bitrain view: drawing the frame failed\n");
        return 0;
    }
    t3 = now_s();
    a->ov.fr = NULL;
    smooth(&a->st.select_ms, 1e3 * (t1 - t0), first);
    smooth(&a->st.vert_ms, 1e3 * (t2 - t1), first);
    smooth(&a->st.raster_ms, 1e3 * (t3 - t2), first);
    smooth(&a->st.frame_ms, 1e3 * (t3 - t0), first);
    smooth(&a->st.tris_per_s, a->s.mesh.ntri / fmax(1e-6, t3 - t0), first);
    a->st.tris = a->s.mesh.ntri;
    a->sum_ms += 1e3 * (t3 - t0);
    a->sum_tri += a->s.mesh.ntri;
    if (a->rec) fprintf(a->rec, "%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n", eye[0], eye[1], eye[2], tgt[0], tgt[1], tgt[2]);
    a->nframe++;
    return 1;
}

/* ---------------------------------------------------------------- window */

/* (Re)creates the texture and frame buffer for w x h; 0 on failure. */
static int set_size(view_app *a, int w, int h)
{
    if (w < 16) w = 16;
    if (h < 16) h = 16;
    if (w > RS_MAX_DIM) w = RS_MAX_DIM;
    if (h > RS_MAX_DIM) h = RS_MAX_DIM;
    if (a->tex && w == a->w && h == a->h) return 1;
    if ((size_t)w * (size_t)h > a->px_cap) {
        uint32_t *px = realloc(a->px, (size_t)w * (size_t)h * 4);
        if (!px) return 0;
        a->px = px;
        a->px_cap = (size_t)w * (size_t)h;
    }
    if (a->tex) SDL_DestroyTexture(a->tex);
    a->tex = SDL_CreateTexture(a->ren, SDL_PIXELFORMAT_RGB888, SDL_TEXTUREACCESS_STREAMING, w, h);
    a->w = w;
    a->h = h;
    if (a->fixed) SDL_RenderSetLogicalSize(a->ren, w, h);
    return a->tex != NULL;
}

/* The name of the video driver SDL fell back to when it shows nothing ("offscreen",
 * "dummy") and the user did not ask for it by SDL_VIDEODRIVER, else NULL: with no X11
 * or Wayland display SDL 2.26 picks "offscreen", and the viewer would run unseen until
 * killed.  (A Linux console's "kmsdrm" shows.) */
static const char *unseen_driver(void)
{
    const char *drv = SDL_GetCurrentVideoDriver(), *asked = getenv("SDL_VIDEODRIVER");
    if (!drv || (strcmp(drv, "offscreen") != 0 && strcmp(drv, "dummy") != 0) || (asked && *asked)) return NULL;
    return drv;
}

static int open_window(view_app *a, const int win[2], int fullscreen)
{
    Uint32 flags = SDL_WINDOW_RESIZABLE | (fullscreen ? SDL_WINDOW_FULLSCREEN_DESKTOP : 0);
    const char *unseen;
    int ow, oh;
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "bitrain view: cannot open a display: %s\n", SDL_GetError());
        return 0;
    }
    a->sdl_on = 1;
    if ((unseen = unseen_driver()) != NULL) {
        fprintf(stderr, "bitrain view: no display to open (SDL fell back to its invisible \"%s\" video driver); "
                        "`bitrain render IN -o OUT.png` draws a frame to a file, and SDL_VIDEODRIVER=%s runs the "
                        "viewer unseen all the same\n", unseen, unseen);
        return 0;
    }
    SDL_SetHint(SDL_HINT_RENDER_SCALE_QUALITY, "0");     /* nearest: crisp when --size scales up */
    a->win = SDL_CreateWindow("bitrain", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, win[0], win[1], flags);
    a->ren = a->win ? SDL_CreateRenderer(a->win, -1, 0) : NULL;
    if (!a->ren) {
        fprintf(stderr, "bitrain view: cannot create the window: %s\n", SDL_GetError());
        return 0;
    }
    if (!a->fixed && SDL_GetRendererOutputSize(a->ren, &ow, &oh) == 0) { a->w = ow; a->h = oh; }
    if (!set_size(a, a->w, a->h)) {
        fprintf(stderr, "bitrain view: cannot create a %dx%d texture: %s\n", a->w, a->h, SDL_GetError());
        return 0;
    }
    return 1;
}

static void present(view_app *a)
{
    int y, shown = a->v.on[VT_BANDS] ? 0 : a->h;
    /* band preview: the new frame appears band by band over the last one */
    for (y = a->band_rows; shown < a->h && y < a->h + a->band_rows; y += a->band_rows) {
        SDL_Rect r = { 0, 0, a->w, y < a->h ? y : a->h };
        SDL_UpdateTexture(a->tex, &r, a->px, a->w * 4);
        SDL_RenderClear(a->ren);
        SDL_RenderCopy(a->ren, a->tex, NULL, NULL);
        SDL_RenderPresent(a->ren);
        SDL_Delay(25);
    }
    SDL_UpdateTexture(a->tex, NULL, a->px, a->w * 4);
    SDL_RenderClear(a->ren);
    SDL_RenderCopy(a->ren, a->tex, NULL, NULL);
    SDL_RenderPresent(a->ren);
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

/* The requests of the last input that need the window or the terminal. */
static void requests(view_app *a)
{
    view_state *v = &a->v;
    if (v->fullscreen) {
        int on = !(SDL_GetWindowFlags(a->win) & SDL_WINDOW_FULLSCREEN_DESKTOP);
        SDL_SetWindowFullscreen(a->win, on ? SDL_WINDOW_FULLSCREEN_DESKTOP : 0);
        v->fullscreen = 0;
    }
    if (v->print_cam) {
        char arg[200];
        view_camera_arg(v, arg, sizeof arg);
        printf("--camera %s --fov %g --pixel-error %g --size %dx%d\n", arg, v->fov, v->pix_err, a->w, a->h);
        fflush(stdout);
        view_note(v, 3, "camera printed on the terminal");
        v->print_cam = 0;
    }
}

static void screenshot(view_app *a)
{
    char path[64];
    br_err err;
    mkdir("out", 0777);
    do snprintf(path, sizeof path, "out/view-%d.png", ++a->shots); while (access(path, F_OK) == 0 && a->shots < 100000);
    if (save_png(path, a->px, a->w, a->h, &err)) {
        printf("%s\n", path);
        fflush(stdout);
        view_note(&a->v, 3, "saved %s", path);
    } else fprintf(stderr, "bitrain view: %s\n", err.msg);
    a->v.shot = 0;
}

/* --fps: the pixel error that holds the frame rate (the triangle count goes roughly
 * with 1 / error^2, so the error moves with the square root of the time ratio, a
 * bounded step per frame so that it does not oscillate). */
static void hold_fps(view_app *a)
{
    double r = a->st.frame_ms / (1000.0 / a->st.target_fps), f;
    if (r > 0.9 && r < 1.1) return;
    f = sqrt(r);
    f = f < 0.9 ? 0.9 : f > 1.15 ? 1.15 : f;
    a->v.pix_err = fmin(64.0, fmax(0.25, a->v.pix_err * f));
}

/* ---------------------------------------------------------------- loop */

static void handle_window(view_app *a, const SDL_Event *ev)
{
    if (ev->type != SDL_WINDOWEVENT) return;
    if (ev->window.event == SDL_WINDOWEVENT_SIZE_CHANGED && !a->fixed) {
        int ow, oh;
        if (SDL_GetRendererOutputSize(a->ren, &ow, &oh) == 0 && !set_size(a, ow, oh))
            fprintf(stderr, "bitrain view: cannot resize to %dx%d\n", ow, oh);
        a->v.dirty = 1;
    } else if (ev->window.event == SDL_WINDOWEVENT_EXPOSED || ev->window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
        a->v.dirty = 1;
    }
}

/* Runs until Esc, the window closes, --frames or --seconds; 0 on failure. */
static int loop(view_app *a, int frames, double seconds)
{
    view_state *v = &a->v;
    double t_prev = now_s(), t_start = t_prev, t_last = t_prev, note_shown = 0;
    a->t_start = t_start;
    int settle = 2;
    while (!v->quit) {
        SDL_Event ev;
        double t;
        int moved;
        v->now = now_s();
        if (a->path.n) v->dirty = 1;            /* a camera path animates every frame */
        /* idle: nothing moves and nothing changed: wait for input (a board idles) */
        if (!v->dirty && !settle && !frames && SDL_WaitEventTimeout(&ev, 250)) {
            v->now = now_s();
            view_event(v, &ev);
            handle_window(a, &ev);
        }
        while (SDL_PollEvent(&ev)) { view_event(v, &ev); handle_window(a, &ev); }
        t = now_s();
        v->now = t;
        moved = view_move(v, t - t_prev);
        t_prev = t;
        requests(a);
        if (note_shown > 0 && v->now >= note_shown) { v->dirty = 1; note_shown = 0; }
        if (seconds > 0 && t - t_start >= seconds) break;
        if (moved || v->dirty) settle = 2;      /* hysteresis settles one frame after a move */
        else if (!settle && !frames) {
            if (a->st.target_fps > 0 && v->pix_err > a->base_err) { v->pix_err = a->base_err; settle = 1; }
            continue;
        } else if (settle) settle--;
        v->dirty = 0;
        if (!draw_frame(a)) return 0;
        present(a);
        if (v->note[0] && v->note_until > v->now) note_shown = v->note_until;
        if (v->shot) screenshot(a);
        if (a->st.target_fps > 0 && (moved || settle == 2)) hold_fps(a);
        /* frames per second while frames follow each other; after an idle wait, what
         * the frame itself cost */
        {
            double tn = now_s(), dt = tn - t_last;
            double rate = dt < 0.5 && a->nframe > 1 ? 1 / dt : 1e3 / fmax(1e-3, a->st.frame_ms);
            smooth(&a->st.fps, rate, a->nframe == 1);
            t_last = tn;
        }
        if (frames && a->nframe >= frames) break;
        if (a->path.n && !frames && a->nframe >= a->path.n) break;   /* the path flown once */
    }
    return 1;
}

/* ---------------------------------------------------------------- command */

#define VIEW_SYNOPSIS "IN... [options]\n" \
    "  camera in metres: x east from the west edge, y north from the south edge, z height (times --zscale);\n" \
    "  the controls follow the options (F1 or ? in the window shows them too)"

typedef struct view_opts {
    int size[2], win[2], size_seen, win_seen, have_cam, frames, threads, bands, fullscreen, no_hud;
    double camv[6], fov, pix_err, fps, seconds;
    const char *shot, *record, *path;
} view_opts;

/* Parses the options and opens the scene; returns -1 to go on, else the exit code. */
static int setup(view_app *a, view_opts *o, int argc, char **argv)
{
    const char *in[64];
    int r, nin = 0;
    scene_opts so;
    scene_args sa;
    dem_args da;
    geocam_args ga;
    br_err err;
    opt_spec dem_t[DEM_ARGS_N], look_t[SCENE_ARGS_N], geo_t[GEOCAM_ARGS_N], water_t[WS_ARGS_N];
    ws_args wa;
    ws_opts wo;
    const opt_spec own[] = {
        { "--size", OPT_SIZE, o->size, 16, RS_MAX_DIM, 0, NULL, "WxH",
          "internal resolution, scaled up by SDL to the window (default: the window's)", &o->size_seen },
        { "--window", OPT_SIZE, o->win, 16, RS_MAX_DIM, 0, NULL, "WxH", "window size (default 1024x640)", &o->win_seen },
        { "--fullscreen", OPT_FLAG, &o->fullscreen, 0, 0, 0, NULL, NULL, "start fullscreen (F11 toggles)", NULL },
        { "--fov", OPT_NUM, &o->fov, 5, 150, 0, NULL, "DEG", "vertical field of view (default 60)", NULL },
        { "--pixel-error", OPT_NUM, &o->pix_err, 0.25, 64, 0, NULL, "P", "screen-space error, pixels (default 1)", NULL },
        { "--fps", OPT_NUM, &o->fps, 1, 240, 0, NULL, "N", "hold N frames per second by adjusting the pixel error", NULL },
        { "--camera", OPT_NUMS, o->camv, -CAMPATH_COORD_MAX, CAMPATH_COORD_MAX, 6, NULL, "EX,EY,EZ,TX,TY,TZ",
          "eye and target, metres", &o->have_cam },
        { "--threads", OPT_INT, &o->threads, 1, PT_MAX_THREADS, 0, NULL, "N", "drawing threads (default: online cores)", NULL },
        { "--bands", OPT_INT, &o->bands, 1, RS_MAX_DIM, 0, NULL, "ROWS", "band height (default 64)", NULL },
        { "--path", OPT_STR, &o->path, 0, 0, 0, NULL, "FILE",
          "fly a camera path (one --camera line a frame, # comments; assets/*.cam), then quit", NULL },
        { "--record", OPT_STR, &o->record, 0, 0, 0, NULL, "FILE", "write the camera path: one EX,EY,EZ,TX,TY,TZ line per frame", NULL },
        { "--frames", OPT_INT, &o->frames, 0, 100000000, 0, NULL, "N", "draw N frames and quit (0: until Esc)", NULL },
        { "--seconds", OPT_NUM, &o->seconds, 0, 1e6, 0, NULL, "S", "quit after S seconds (0: until Esc)", NULL },
        { "--no-hud", OPT_FLAG, &o->no_hud, 0, 0, 0, NULL, NULL, "start with the HUD off (T toggles it)", NULL },
        { "--screenshot", OPT_STR, &o->shot, 0, 0, 0, NULL, "OUT.png", "save the last frame on quitting", NULL },
        OPT_END
    };
    const opt_spec *const tables[] = { own, look_t, water_t, geo_t, dem_t, NULL };
    memset(&so, 0, sizeof so);
    memset(&wo, 0, sizeof wo);
    ws_args_table(&wa, &wo, water_t);
    dem_args_table(&da, &so.dem, dem_t);
    scene_args_table(&sa, &so, look_t);
    geocam_args_table(&ga, geo_t);
    r = opt_parse("view", VIEW_SYNOPSIS, tables, argc, argv, in, 64, &nin);
    if (r == OPT_HELP) { view_controls_print(stdout); return 0; }
    if (r != OPT_OK) return 2;
    if (dem_args_finish(&da, "view") != OPT_OK) return 2;
    if (scene_args_finish(&sa, "view") != OPT_OK) return 2;
    if (ws_args_finish(&wa, "view") != OPT_OK) return 2;
    if (!nin) { fprintf(stderr, "bitrain view: no input file (`bitrain view --help`)\n"); return 2; }
    if (o->have_cam && (ga.from_seen || ga.at_seen)) return opt_fail("view", "--camera", "cannot be used with --look-from/--look-at");
    if (o->record && !(a->rec = fopen(o->record, "w"))) {
        fprintf(stderr, "bitrain view: %s: cannot write the camera path\n", o->record);
        return 1;
    }
    if (o->path && campath_read(o->path, &a->path, &err) != BR_OK) { fprintf(stderr, "bitrain view: %s\n", err.msg); return 1; }
    if (o->path && (o->have_cam || ga.from_seen || ga.at_seen))
        return opt_fail("view", "--path", "cannot be used with --camera or --look-from/--look-at");
    so.ramp_abs = !(wo.no_water && wo.no_fog);
    if (scene_open(&a->s, in, nin, &so, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); return 1; }
    if (so.ramp_abs) {
        if (ws_open(&a->ws, &a->s, &wo, &err) != BR_OK) { fprintf(stderr, "bitrain: %s\n", err.msg); return 1; }
        a->ws_on = 1;
        a->nbodies = a->ws.nbodies;
        a->clock_waves = !wa.time_seen;
    }
    r = geocam_resolve(&ga, &a->s, "view", o->camv);
    if (r < 0) return 2;
    o->have_cam |= r;
    if (scene_tree(&a->s, &err) != BR_OK || scene_reserve(&a->s, VIEW_MAX_TRI, &err) != BR_OK) {
        fprintf(stderr, "bitrain: %s: %s\n", in[0], err.msg);
        return 1;
    }
    if (a->ws_on && ws_reserve(&a->ws, &a->s) != BR_OK) {
        fprintf(stderr, "bitrain: out of memory for the reflection's mesh\n");
        return 1;
    }
    {
        rs_prim cap;
        cap.kind = RS_STRIP; cap.n = a->s.mesh.cap_s; cap.idx = NULL;
        a->chunks = malloc(rs_chunk_mem_size(&cap, 1) + 4);
        if (!a->chunks) { fprintf(stderr, "bitrain: out of memory\n"); return 1; }
    }
    return -1;
}

int cmd_view(int argc, char **argv)
{
    view_app a;
    view_opts o;
    int rc = 1;
    double eye[3], tgt[3];
    int i;
    for (i = 0; i < argc; i++)      /* an SPI panel (no window): `render` draws to it band by band */
        if (!strcmp(argv[i], "--spi") || !strcmp(argv[i], "--spi-capture")) return cmd_render(argc, argv);
    memset(&a, 0, sizeof a);
    memset(&o, 0, sizeof o);
    o.fov = 60; o.pix_err = 1; o.bands = 64; o.threads = pt_online_cores();
    o.win[0] = 1024; o.win[1] = 640;
    rc = setup(&a, &o, argc, argv);
    if (rc >= 0) goto done;
    rc = 1;
    if (pt_open(&a.pool, o.threads) != BR_OK) { fprintf(stderr, "bitrain view: cannot start %d threads\n", o.threads); goto done; }
    a.s.pool = a.pool;
    a.band_rows = o.bands;
    a.fixed = o.size_seen;
    a.w = o.size_seen ? o.size[0] : o.win[0];
    a.h = o.size_seen ? o.size[1] : o.win[1];
    if (o.size_seen && !o.win_seen) {       /* an internal size scaled up a whole number of times */
        int k = 1;
        while ((k + 1) * o.size[0] <= 1280 && (k + 1) * o.size[1] <= 800) k++;
        o.win[0] = k * o.size[0]; o.win[1] = k * o.size[1];
    }
    if (o.have_cam) { memcpy(eye, o.camv, sizeof eye); memcpy(tgt, o.camv + 3, sizeof tgt); }
    else scene_default_view(&a.s, o.fov, eye, tgt);
    a.v.fov = o.fov;
    a.v.pix_err = o.pix_err;
    view_init(&a.v, &a.s, eye, tgt);
    a.v.on[VT_HUD] = !o.no_hud;
    a.v.water_scene = a.ws_on;
    a.v.on[VT_FOG] = a.ws_on && !a.ws.o.no_fog;
    a.v.on[VT_WATER] = a.ws_on && !a.ws.o.no_water;
    a.base_err = o.pix_err;
    a.st.target_fps = o.fps;
    a.st.threads = o.threads;
    a.st.cores = pt_online_cores();
    a.st.band_rows = o.bands;
    if (a.rec)
        fprintf(a.rec, "# bitrain view --record: camera path, one EX,EY,EZ,TX,TY,TZ line per frame drawn (metres)\n"
                       "# --fov %g --pixel-error %g (hysteresis and geomorph on in the viewer)\n", o.fov, o.pix_err);
    if (!open_window(&a, o.win, o.fullscreen)) goto done;
    printf("bitrain view: %dx%d heightfield, %.1f x %.1f km, heights %.0f..%.0f m; F1 in the window for the controls\n",
           a.s.f.w, a.s.f.h, a.s.width_m / 1000, a.s.depth_m / 1000, a.s.zmin_m, a.s.zmax_m);
    fflush(stdout);
    if (!loop(&a, o.frames, o.seconds)) goto done;
    if (a.nframe)
        printf("bitrain view: %d frames drawn, mean %.0f triangles, %.2f ms per frame (%d threads)\n",
               a.nframe, a.sum_tri / a.nframe, a.sum_ms / a.nframe, o.threads);
    if (o.shot) {
        br_err err;
        if (!save_png(o.shot, a.px, a.w, a.h, &err)) { fprintf(stderr, "bitrain: %s\n", err.msg); goto done; }
        printf("%s\n", o.shot);
    }
    rc = 0;
done:
    if (a.rec && fclose(a.rec) != 0 && rc == 0) { fprintf(stderr, "bitrain view: %s: write failed\n", o.record); rc = 1; }
    pt_close(a.pool);
    free(a.px);
    free(a.chunks);
    free(a.lod_v);
    free(a.lod_idx);
    free(a.lod_cache);
    if (a.tex) SDL_DestroyTexture(a.tex);
    if (a.ren) SDL_DestroyRenderer(a.ren);
    if (a.win) SDL_DestroyWindow(a.win);
    if (a.sdl_on) SDL_Quit();
    if (a.ws_on) ws_close(&a.ws);
    scene_close(&a.s);
    campath_free(&a.path);
    return rc;
}
