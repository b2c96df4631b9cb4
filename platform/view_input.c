/* platform/view_input.c — the viewer's controls (one table), camera motion and limits. */
#include <math.h>
#include <stdarg.h>
#include <string.h>
#include "platform/view.h"

#define VIEW_PI 3.14159265358979323846

/* What a key does.  A_HELD: read from the keyboard state every frame (movement). */
enum {
    A_HELD, A_QUIT, A_HELP, A_HUD, A_ORBIT, A_RESET, A_ERR_UP, A_ERR_DOWN, A_SPEED_UP, A_SPEED_DOWN,
    A_FOG, A_WATER, A_WIRE, A_LOD, A_CULL, A_HYST, A_MORPH, A_BANDS, A_SHOT, A_PRINT_CAM, A_FULLSCREEN
};

typedef struct control {
    SDL_Keycode keys[4];        /* 0-terminated; none: a mouse control */
    const char *label;          /* as shown to the user */
    const char *what;
    int action;
} control;

static const control controls[] = {
    { { SDLK_w, SDLK_UP, 0 }, "W / Up", "forward (orbit: closer)", A_HELD },
    { { SDLK_s, SDLK_DOWN, 0 }, "S / Down", "back (orbit: away)", A_HELD },
    { { SDLK_a, SDLK_d, 0 }, "A / D", "sideways left / right (orbit: around)", A_HELD },
    { { SDLK_LEFT, SDLK_RIGHT, 0 }, "Left / Right", "turn left / right (orbit: around)", A_HELD },
    { { SDLK_HOME, SDLK_END, 0 }, "Home / End", "look up / down", A_HELD },
    { { SDLK_q, SDLK_PAGEDOWN, 0 }, "Q / PgDn", "down (height-aware speed, capped)", A_HELD },
    { { SDLK_e, SDLK_PAGEUP, 0 }, "E / PgUp", "up", A_HELD },
    { { SDLK_LSHIFT, SDLK_RSHIFT, 0 }, "Shift", "4x faster while held", A_HELD },
    { { 0 }, "mouse drag", "look around (orbit: turn around the point)", A_HELD },
    { { 0 }, "wheel", "speed up / down", A_HELD },
    { { SDLK_RIGHTBRACKET, 0 }, "]", "speed up (x1.5, up to 16x)", A_SPEED_UP },
    { { SDLK_LEFTBRACKET, 0 }, "[", "speed down", A_SPEED_DOWN },
    { { SDLK_TAB, 0 }, "Tab", "fly / orbit the point under the screen centre", A_ORBIT },
    { { SDLK_r, 0 }, "R", "reset the view", A_RESET },
    { { SDLK_EQUALS, SDLK_PLUS, SDLK_KP_PLUS, 0 }, "+", "more pixel error (coarser, faster)", A_ERR_UP },
    { { SDLK_MINUS, SDLK_KP_MINUS, 0 }, "-", "less pixel error (finer)", A_ERR_DOWN },
    { { SDLK_f, 0 }, "F", "fog", A_FOG },
    { { SDLK_v, 0 }, "V", "water", A_WATER },
    { { SDLK_m, 0 }, "M", "wireframe: the mesh's edges over the image", A_WIRE },
    { { SDLK_l, 0 }, "L", "LOD colouring: triangles tinted by bitree level", A_LOD },
    { { SDLK_c, 0 }, "C", "back-face culling", A_CULL },
    { { SDLK_h, 0 }, "H", "hysteresis", A_HYST },
    { { SDLK_g, 0 }, "G", "geomorphing", A_MORPH },
    { { SDLK_b, 0 }, "B", "band preview: draw band by band, boundaries marked", A_BANDS },
    { { SDLK_t, SDLK_F2, 0 }, "T / F2", "HUD on / off", A_HUD },
    { { SDLK_F1, SDLK_SLASH, SDLK_QUESTION, 0 }, "F1 / ?", "this help", A_HELP },
    { { SDLK_p, SDLK_F12, 0 }, "P / F12", "screenshot to out/view-N.png", A_SHOT },
    { { SDLK_i, 0 }, "I", "print the camera as a --camera argument", A_PRINT_CAM },
    { { SDLK_F11, 0 }, "F11", "fullscreen", A_FULLSCREEN },
    { { SDLK_ESCAPE, 0 }, "Esc", "quit", A_QUIT },
};
#define NCONTROLS ((int)(sizeof controls / sizeof controls[0]))

void view_controls_print(FILE *f)
{
    int i;
    fprintf(f, "controls:\n");
    for (i = 0; i < NCONTROLS; i++) fprintf(f, "  %-13s %s\n", controls[i].label, controls[i].what);
}

const char *view_controls_text(void)
{
    static char buf[4096];
    size_t n = 0;
    int i;
    if (buf[0]) return buf;
    n += (size_t)snprintf(buf + n, sizeof buf - n, "bitrain view - controls (F1 or ? closes)\n\n");
    for (i = 0; i < NCONTROLS && n < sizeof buf; i++)
        n += (size_t)snprintf(buf + n, sizeof buf - n, "%-13s %s%s", controls[i].label, controls[i].what,
                              i + 1 < NCONTROLS ? "\n" : "");
    return buf;
}

int view_controls_clash(void)
{
    int i, j, k, l;
    for (i = 0; i < NCONTROLS; i++)
        for (k = 0; controls[i].keys[k]; k++)
            for (j = 0; j < NCONTROLS; j++)
                for (l = 0; controls[j].keys[l]; l++)
                    if ((i != j || k != l) && controls[i].keys[k] == controls[j].keys[l]) return 1;
    return 0;
}

void view_note(view_state *v, double seconds, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->note, sizeof v->note, fmt, ap);
    va_end(ap);
    v->note_until = v->now + seconds;
}

/* ---------------------------------------------------------------- camera */

static void dir_of(double yaw, double pitch, double d[3])
{
    d[0] = sin(yaw) * cos(pitch);
    d[1] = cos(yaw) * cos(pitch);
    d[2] = sin(pitch);
}

static void look(view_cam *c, const double eye[3], const double tgt[3])
{
    double dx = tgt[0] - eye[0], dy = tgt[1] - eye[1], dz = tgt[2] - eye[2];
    memcpy(c->pos, eye, sizeof c->pos);
    c->yaw = atan2(dx, dy);
    c->pitch = atan2(dz, sqrt(dx * dx + dy * dy));
}

void view_cam_look(view_cam *c, const double eye[3], const double tgt[3])
{
    look(c, eye, tgt);
}

/* The highest sample of the grid cell around (x, y): the mesh never lies above it by
 * more than its screen error, so an eye above it stays above the drawn surface.  NAN
 * outside the grid. */
static double ground_max(const scene *s, double x, double y)
{
    double g = NAN, sx = (double)s->f.dx_um / 1e6, sy = (double)s->f.dy_um / 1e6;
    int i;
    for (i = 0; i < 4; i++) {
        double z = scene_ground(s, x + ((i & 1) ? sx : -sx) * 0.5, y + ((i & 2) ? sy : -sy) * 0.5);
        if (!isnan(z) && (isnan(g) || z > g)) g = z;
    }
    return g;
}

void view_init(view_state *v, const scene *s, const double eye[3], const double tgt[3])
{
    double fov = v->fov, pe = v->pix_err;
    memset(v, 0, sizeof *v);
    v->s = s;
    v->fov = fov > 0 ? fov : 60;
    v->pix_err = pe > 0 ? pe : 1;
    v->speed_mul = 1;
    v->on[VT_HUD] = v->on[VT_HYST] = v->on[VT_MORPH] = 1;
    look(&v->cam, eye, tgt);
    v->home = v->cam;
    v->dirty = 1;
}

/* The point under the screen centre: the first grid sample the view ray passes under,
 * marched in steps of a fraction of the height above ground; else where the ray meets
 * the middle height, else 1 km ahead. */
static void centre_point(const view_state *v, double p[3])
{
    const scene *s = v->s;
    double d[3], t = 0, ext = fmax(s->width_m, s->depth_m), mid = 0.5 * (s->zmin_m + s->zmax_m);
    int i;
    dir_of(v->cam.yaw, v->cam.pitch, d);
    for (i = 0; i < 4000 && t < 3 * ext; i++) {
        double q[3] = { v->cam.pos[0] + d[0] * t, v->cam.pos[1] + d[1] * t, v->cam.pos[2] + d[2] * t };
        double g = scene_ground(s, q[0], q[1]);
        if (!isnan(g) && q[2] <= g) { memcpy(p, q, sizeof q); p[2] = g; return; }
        t += fmax(5.0, 0.02 * (isnan(g) ? fabs(q[2] - mid) : q[2] - g));
    }
    t = d[2] < -1e-3 ? (mid - v->cam.pos[2]) / d[2] : 1000;
    for (i = 0; i < 3; i++) p[i] = v->cam.pos[i] + d[i] * t;
}

static void orbit_place(view_state *v)
{
    double d[3];
    int i;
    dir_of(v->cam.yaw, v->cam.pitch, d);
    for (i = 0; i < 3; i++) v->cam.pos[i] = v->pivot[i] - d[i] * v->dist;
}

void view_limit(view_state *v)
{
    const scene *s = v->s;
    double ext = fmax(s->width_m, s->depth_m), lo[2] = { -0.25 * ext, -0.25 * ext };
    double hi[2] = { s->width_m + 0.25 * ext, s->depth_m + 0.25 * ext }, ceiling = s->zmax_m + ext, g;
    static const char *const side[2][2] = { { "west", "east" }, { "south", "north" } };
    int i;
    for (i = 0; i < 2; i++) {
        if (v->cam.pos[i] < lo[i] || v->cam.pos[i] > hi[i]) {
            int east = v->cam.pos[i] > hi[i];
            v->cam.pos[i] = east ? hi[i] : lo[i];
            view_note(v, 2, "edge of the world: no further %s", side[i][east]);
        }
    }
    if (v->cam.pos[2] > ceiling) {
        v->cam.pos[2] = ceiling;
        view_note(v, 2, "ceiling: %.0f m is as high as the view goes", ceiling);
    }
    g = ground_max(s, v->cam.pos[0], v->cam.pos[1]);
    if (isnan(g)) g = s->zmin_m;
    if (v->cam.pos[2] < g + 2) {
        v->cam.pos[2] = g + 2;
        if (v->orbit) {         /* keep looking at the pivot from the raised eye */
            double dx = v->pivot[0] - v->cam.pos[0], dy = v->pivot[1] - v->cam.pos[1], dz = v->pivot[2] - v->cam.pos[2];
            v->dist = sqrt(dx * dx + dy * dy + dz * dz);
            v->cam.pitch = atan2(dz, sqrt(dx * dx + dy * dy));
        }
    }
    if (v->cam.pitch > 1.55) v->cam.pitch = 1.55;
    if (v->cam.pitch < -1.55) v->cam.pitch = -1.55;
}

static void set_orbit(view_state *v, int on)
{
    if (on) {
        double dx, dy, dz;
        centre_point(v, v->pivot);
        dx = v->pivot[0] - v->cam.pos[0]; dy = v->pivot[1] - v->cam.pos[1]; dz = v->pivot[2] - v->cam.pos[2];
        v->dist = fmax(10.0, sqrt(dx * dx + dy * dy + dz * dz));
        v->orbit = 1;
        view_note(v, 2, "orbit around %.0f, %.0f, %.0f m (%.0f m away)", v->pivot[0], v->pivot[1], v->pivot[2], v->dist);
    } else {
        v->orbit = 0;
        view_note(v, 2, "fly");
    }
}

/* Speed in metres per second: the height above ground sets it, so that the ground
 * moves across the screen about as fast at any height, capped so that it never runs
 * away (vertical motion under the same cap would double the height every 2 s). */
static double speed(const view_state *v, int vertical)
{
    double g = ground_max(v->s, v->cam.pos[0], v->cam.pos[1]), agl;
    if (isnan(g)) g = v->s->zmax_m;
    agl = fmax(0.0, v->cam.pos[2] - g);
    return vertical ? fmin(300.0, fmax(10.0, 0.35 * agl)) * v->speed_mul
                    : fmin(2000.0, fmax(20.0, 0.6 * agl)) * v->speed_mul;
}

int view_move(view_state *v, double dt)
{
    const Uint8 *k = SDL_GetKeyboardState(NULL);
    double fwd = (k[SDL_SCANCODE_W] || k[SDL_SCANCODE_UP]) - (k[SDL_SCANCODE_S] || k[SDL_SCANCODE_DOWN]);
    double side = k[SDL_SCANCODE_D] - k[SDL_SCANCODE_A];
    double turn = k[SDL_SCANCODE_RIGHT] - k[SDL_SCANCODE_LEFT];
    double tilt = k[SDL_SCANCODE_HOME] - k[SDL_SCANCODE_END];
    double up = (k[SDL_SCANCODE_E] || k[SDL_SCANCODE_PAGEUP]) - (k[SDL_SCANCODE_Q] || k[SDL_SCANCODE_PAGEDOWN]);
    double fast = (k[SDL_SCANCODE_LSHIFT] || k[SDL_SCANCODE_RSHIFT]) ? 4 : 1;
    if (fwd == 0 && side == 0 && turn == 0 && tilt == 0 && up == 0) return 0;
    if (dt > 0.1) dt = 0.1;
    if (v->orbit) {
        v->cam.yaw += (turn + side) * 0.8 * dt * fast;
        v->cam.pitch += (tilt - up) * 0.6 * dt;
        v->dist *= exp(-fwd * 0.8 * dt * fast);
        if (v->dist < 5) v->dist = 5;
        if (v->dist > 4 * fmax(v->s->width_m, v->s->depth_m)) v->dist = 4 * fmax(v->s->width_m, v->s->depth_m);
        if (v->cam.pitch < -1.55) v->cam.pitch = -1.55;
        if (v->cam.pitch > 0.2) v->cam.pitch = 0.2;
        orbit_place(v);
    } else {
        double h = speed(v, 0) * fast * dt, vz = speed(v, 1) * fast * dt, d[3];
        dir_of(v->cam.yaw, v->cam.pitch, d);
        v->cam.yaw += turn * 1.2 * dt;
        v->cam.pitch += tilt * 0.8 * dt;
        v->cam.pos[0] += d[0] * fwd * h + cos(v->cam.yaw) * side * h;
        v->cam.pos[1] += d[1] * fwd * h - sin(v->cam.yaw) * side * h;
        v->cam.pos[2] += d[2] * fwd * h + up * vz;
    }
    view_limit(v);
    return 1;
}

static void toggle(view_state *v, int t, const char *name)
{
    v->on[t] = !v->on[t];
    view_note(v, 2, "%s %s", name, v->on[t] ? "on" : "off");
}

static void key(view_state *v, SDL_Keycode sym)
{
    int i, k, a = -1;
    for (i = 0; i < NCONTROLS && a < 0; i++)
        for (k = 0; controls[i].keys[k]; k++)
            if (controls[i].keys[k] == sym) { a = controls[i].action; break; }
    switch (a) {
    case A_QUIT: v->quit = 1; break;
    case A_HELP: v->on[VT_HELP] = !v->on[VT_HELP]; break;
    case A_HUD: v->on[VT_HUD] = !v->on[VT_HUD]; break;
    case A_ORBIT: set_orbit(v, !v->orbit); break;
    case A_RESET: v->cam = v->home; v->orbit = 0; v->speed_mul = 1; view_note(v, 2, "view reset"); break;
    case A_ERR_UP: v->pix_err = fmin(64.0, v->pix_err * 1.25); view_note(v, 2, "pixel error %.2f", v->pix_err); break;
    case A_ERR_DOWN: v->pix_err = fmax(0.25, v->pix_err / 1.25); view_note(v, 2, "pixel error %.2f", v->pix_err); break;
    case A_SPEED_UP: v->speed_mul = fmin(16.0, v->speed_mul * 1.5); view_note(v, 2, "speed x%.2f", v->speed_mul); break;
    case A_SPEED_DOWN: v->speed_mul = fmax(1.0 / 16, v->speed_mul / 1.5); view_note(v, 2, "speed x%.2f", v->speed_mul); break;
    case A_FOG:
        if (v->water_scene) toggle(v, VT_FOG, "fog");
        else view_note(v, 3, "fog: off for this run (--no-water --no-fog)");
        break;
    case A_WATER:
        if (v->water_scene) toggle(v, VT_WATER, "water");
        else view_note(v, 3, "water: off for this run (--no-water --no-fog)");
        break;
    case A_WIRE: toggle(v, VT_WIRE, "wireframe"); break;
    case A_LOD: toggle(v, VT_LOD, "LOD colouring"); break;
    case A_CULL:
        v->on[VT_NOCULL] = !v->on[VT_NOCULL];
        view_note(v, 2, "back-face culling %s", v->on[VT_NOCULL] ? "off" : "on");
        break;
    case A_HYST: toggle(v, VT_HYST, "hysteresis"); break;
    case A_MORPH: toggle(v, VT_MORPH, "geomorphing"); break;
    case A_BANDS: toggle(v, VT_BANDS, "band preview"); break;
    case A_SHOT: v->shot = 1; break;
    case A_PRINT_CAM: v->print_cam = 1; break;
    case A_FULLSCREEN: v->fullscreen = 1; break;
    default: return;            /* movement keys and unbound keys: no redraw by themselves */
    }
    v->dirty = 1;
}

void view_event(view_state *v, const SDL_Event *ev)
{
    if (ev->type == SDL_QUIT) v->quit = 1;
    else if (ev->type == SDL_KEYDOWN && !ev->key.repeat) key(v, ev->key.keysym.sym);
    else if (ev->type == SDL_MOUSEMOTION && (ev->motion.state & SDL_BUTTON_LMASK)) {
        v->cam.yaw += ev->motion.xrel * 0.004;
        v->cam.pitch -= ev->motion.yrel * 0.004;
        if (v->orbit) {
            if (v->cam.pitch > 0.2) v->cam.pitch = 0.2;
            orbit_place(v);
        }
        view_limit(v);
        v->dirty = 1;
    } else if (ev->type == SDL_MOUSEWHEEL && ev->wheel.y) {
        v->speed_mul = ev->wheel.y > 0 ? fmin(16.0, v->speed_mul * 1.25) : fmax(1.0 / 16, v->speed_mul / 1.25);
        view_note(v, 2, "speed x%.2f", v->speed_mul);
        v->dirty = 1;
    }
}

/* Rounds to 0.001 m, the precision --camera is printed with: the camera drawn is the
 * camera printed. */
static double mm(double x) { return (double)llround(x * 1000) / 1000; }

void view_eye_target(const view_state *v, double eye[3], double tgt[3])
{
    double d[3], ahead = 1000;
    int i;
    dir_of(v->cam.yaw, v->cam.pitch, d);
    if (v->s) {
        /* the fly camera's target 20 heights above ground ahead (1 to 200 km): the camera
         * takes its near plane from that distance (scene_camera), and a near plane of
         * 0.5 m seen from 60 km leaves the depth buffer metres a unit far away, where
         * the water's shore and the terrain tie */
        double g = ground_max(v->s, v->cam.pos[0], v->cam.pos[1]);
        double agl = v->cam.pos[2] - (isnan(g) ? v->s->zmin_m : g);
        ahead = agl * 20 < 1000 ? 1000 : agl * 20 > 200000 ? 200000 : agl * 20;
    }
    for (i = 0; i < 3; i++) {
        eye[i] = mm(v->cam.pos[i]);
        tgt[i] = mm(v->orbit ? v->pivot[i] : v->cam.pos[i] + d[i] * ahead);
    }
    if (eye[0] == tgt[0] && eye[1] == tgt[1] && eye[2] == tgt[2]) tgt[1] += 1;
}

void view_camera_arg(const view_state *v, char *buf, size_t n)
{
    double e[3], t[3];
    view_eye_target(v, e, t);
    snprintf(buf, n, "%.3f,%.3f,%.3f,%.3f,%.3f,%.3f", e[0], e[1], e[2], t[0], t[1], t[2]);
}
