/* platform/view.h — the parts of `bitrain view` (internal to the viewer):
 *   cmd_view.c    options, window, the frame loop (driver on N threads, SDL texture)
 *   view_input.c  the controls table, key and mouse handling, camera motion and limits
 *   view_hud.c    what the post hook draws over the terrain: wireframe, band
 *                 boundaries, HUD, help (after the water scene's fog and sky hook,
 *                 platform/water_scene.h, when that is on)
 * Positions are metres in the scene frame (platform/scene.h): x east from the west
 * edge, y north from the south edge, z height times the vertical scale. */
#ifndef BR_VIEW_H
#define BR_VIEW_H
#include <SDL.h>
#include <stdio.h>
#include "platform/scene.h"
#include "raster/frame.h"

/* What can be switched on and off; the controls table names the key of each. */
enum { VT_HUD, VT_HELP, VT_WIRE, VT_LOD, VT_NOCULL, VT_HYST, VT_MORPH, VT_BANDS, VT_FOG, VT_WATER, VT_N };

typedef struct view_cam {
    double pos[3];              /* the eye */
    double yaw, pitch;          /* radians: yaw clockwise from north, pitch up from level */
} view_cam;

typedef struct view_state {
    const scene *s;
    view_cam cam, home;         /* current; R goes back to home */
    int orbit;                  /* 1: the camera orbits pivot at distance dist */
    double pivot[3], dist;
    double fov, pix_err;        /* degrees; pixels */
    double speed_mul;           /* [ ] and the wheel: 1/16 .. 16 */
    int on[VT_N];
    int water_scene;            /* 1: the scene has the water and fog passes (F and V toggle
                                   them); 0: --no-water --no-fog */
    /* requests for the frame loop, set by the input, cleared by the loop */
    int quit, shot, print_cam, fullscreen;
    int dirty;                  /* the view changed: draw a frame */
    char note[160];             /* a message shown in the HUD for a while */
    double note_until;          /* seconds (SDL ticks / 1000) */
    double now;                 /* seconds, set by the loop before the input runs */
} view_state;

/* Frame figures for the HUD (the last frame, smoothed where said). */
typedef struct view_stats {
    double fps;                 /* smoothed */
    double select_ms, vert_ms, raster_ms, frame_ms;     /* smoothed; select: selection, strip and
                                                           raster vertices (scene_mesh, threaded),
                                                           vertices: their transform */
    uint32_t tris;
    double tris_per_s;          /* tris / frame_ms, smoothed */
    int w, h, band_rows, threads, cores;
    double target_fps;          /* --fps (0: none) */
} view_stats;

/* ---------------------------------------------------------------- view_input.c */

/* Prints the controls table (the one table: --help, README and the help overlay). */
void view_controls_print(FILE *f);
/* The controls as the help overlay shows them (static buffer). */
const char *view_controls_text(void);
/* 0 when no key is bound to two actions (tests). */
int view_controls_clash(void);

/* Sets the default state for scene s and the camera eye/target. */
void view_init(view_state *v, const scene *s, const double eye[3], const double tgt[3]);
/* One SDL event: keys, mouse, wheel (window events are the loop's). */
void view_event(view_state *v, const SDL_Event *ev);
/* Moves the camera for the keys held during dt seconds; 1 when it moved. */
int view_move(view_state *v, double dt);
/* Keeps the eye above the terrain, inside the world and under the ceiling; says so in
 * the note when it had to stop the camera. */
void view_limit(view_state *v);
/* Eye and target of the current camera, rounded as --camera prints them (so a printed
 * or recorded line reproduces the frame exactly). */
void view_eye_target(const view_state *v, double eye[3], double tgt[3]);
/* The camera at eye looking at tgt (yaw and pitch of the direction). */
void view_cam_look(view_cam *c, const double eye[3], const double tgt[3]);
/* Writes "EX,EY,EZ,TX,TY,TZ" (the --camera value) into buf. */
void view_camera_arg(const view_state *v, char *buf, size_t n);
void view_note(view_state *v, double seconds, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* ---------------------------------------------------------------- view_hud.c */

/* What the post hook draws; filled by the frame loop before each frame, read-only
 * while the bands are drawn (on several threads). */
typedef struct view_overlay {
    const rs_frame *fr;         /* wireframe: the frame's strip and vertex cache */
    int wire;
    int32_t band_rows;          /* > 0: mark each band's first row (band preview) */
    const char *hud;            /* NULL: none */
    const char *help;           /* NULL: none */
    int32_t scale;              /* text scale */
    int32_t h;                  /* the frame's height */
} view_overlay;

/* The post hook (raster/frame.h rs_post_fn); user is a view_overlay. */
br_status view_post(const void *user, rs_band *b, rs_band_stats *st);
/* The HUD text for the state and the last frame's figures. */
void view_hud_text(const view_state *v, const view_stats *st, char *buf, size_t n);
/* The HUD text for the camera a frame was drawn from (eye, tgt: a --path line when
 * flying a path, else the state's camera), the rest from the state. */
void view_hud_frame_text(const view_state *v, const double eye[3], const double tgt[3], const view_stats *st,
                         char *buf, size_t n);
/* LOD colouring: the mesh's strip as a triangle list with three vertices of its own per
 * triangle, each triangle tinted by its size in the grid (its level in the bitree);
 * out and idx hold 3 * (m->ns - 2) entries.  Returns the vertices (= indices) written. */
uint32_t view_lod_list(const bt_mesh *m, const rs_vertex *verts, rs_vertex *out, uint32_t *idx);

#endif
