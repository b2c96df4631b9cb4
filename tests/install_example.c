/* tests/install_example.c — the README's library example: load a DEM, build its bitree,
 * extract the view-dependent mesh for a camera and draw one 16-row band of a 320x240
 * RGB565 frame, against an installed bitrain (mk/check-install.sh builds it with
 * `pkg-config --cflags --static --libs bitrain` after `make install DESTDIR=...`). */
#include <stdio.h>
#include "platform/scene.h"
#include "raster/frame.h"

int main(int argc, char **argv)
{
    const char *in[1] = { argc > 1 ? argv[1] : "assets/N47E009.hgt.gz" };
    static uint8_t mem[320 * 16 * 4];           /* one band: RGB565 colour + 16-bit depth */
    scene s = { 0 }; scene_opts o = { 0 }; bt_params p = { 0 }; rs_frame f = { 0 }; rs_pipe pipe = { 0 };
    br_err err; cam c; rs_pass terrain; rs_band band; rs_band_stats st; double eye[3], target[3];
    if (scene_open(&s, in, 1, &o, &err) || scene_tree(&s, &err) || scene_reserve(&s, 200000, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    scene_default_view(&s, 50, eye, target);              /* from the south-west, metres */
    p.mode = BT_VIEW; p.pixel_err_q8 = 256;                /* 1 pixel of screen-space error */
    f.fmt = RS_FMT_RGB565; f.depth = RS_DEPTH16; f.clear_rgb = 0x99ccff;
    pipe.w = 320; pipe.h = 240; pipe.fmt = f.fmt; pipe.depth = f.depth;
    if (scene_camera(&s, eye, target, 50, 320, 240, &c) || scene_mesh(&s, &c, &p)
        || scene_terrain(&s, &c, &f, &terrain) || rs_pipe_add(&pipe, &terrain)
        || rs_pipe_band(&pipe, 112, 16, mem, sizeof mem, &band, &st)) return 1;   /* rows 112..127 */
    printf("%u triangles in the mesh, %u set up and %u pixels drawn in rows 112-127\n", s.mesh.ntri, st.tris, st.pixels);
    scene_close(&s);
    return st.pixels == 0;
}
