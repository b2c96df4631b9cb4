/* benchmarks/arm/peer_dump.c — writes the peer scene (benchmarks/peer_scene.c, built from
 * fuji.png with libpng) as the raw file of peer_file.h, for peer_run on a foreign
 * architecture.  With CAM and WxH it also renders that frame the way `bitrain bench`
 * does (peer_frame + rs_frame_prepare + rs_draw_band) and prints its checksum
 * line, the reference peer_run's output must equal on every target.
 *
 *   peer_dump FUJI.png OUT.bin [A|B WxH]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "benchmarks/peer_scene.h"
#include "benchmarks/arm/peer_file.h"

static int put(FILE *f, uint32_t v)
{
    unsigned char b[4];
    b[0] = (unsigned char)v; b[1] = (unsigned char)(v >> 8);
    b[2] = (unsigned char)(v >> 16); b[3] = (unsigned char)(v >> 24);
    return fwrite(b, 1, 4, f) == 4 ? 0 : -1;
}

int main(int argc, char **argv)
{
    peer_scene *ps;
    rs_vertex *v;
    rs_prim prims[PEER_NSTRIP];
    FILE *f;
    int i, k, err = 0;
    const char cams[2] = { 'A', 'B' };
    if (argc != 3 && argc != 5) {
        fprintf(stderr, "usage: peer_dump FUJI.png OUT.bin [A|B WxH]\n");
        return 2;
    }
    ps = (peer_scene *)malloc(sizeof *ps);
    v = (rs_vertex *)malloc(sizeof *v * PEER_NV);
    if (!ps || !v) { fprintf(stderr, "peer_dump: out of memory\n"); return 1; }
    if (peer_scene_build(argv[1], ps) != 0) return 1;
    peer_scene_raster(ps, v, prims);
    f = fopen(argv[2], "wb");
    if (!f) { fprintf(stderr, "peer_dump: %s: cannot create\n", argv[2]); return 1; }
    err |= put(f, PF_MAGIC) | put(f, PF_VERSION) | put(f, PEER_NV);
    for (i = 0; i < PEER_NV; i++)
        err |= put(f, (uint32_t)v[i].p[0]) | put(f, (uint32_t)v[i].p[1]) | put(f, (uint32_t)v[i].p[2]) | put(f, v[i].rgb);
    err |= put(f, PEER_NSTRIP) | put(f, PEER_STRIP_LEN);
    for (i = 0; i < PEER_NSTRIP; i++)
        for (k = 0; k < (int)prims[i].n; k++) err |= put(f, prims[i].idx[k]);
    err |= put(f, 2);
    for (i = 0; i < 2; i++) {
        int32_t eye[3], tg[3], fovy, zn, zf;
        if (peer_camera(cams[i], NULL, eye, tg, &fovy, &zn, &zf) != 0) return 1;
        err |= put(f, (uint32_t)cams[i]);
        for (k = 0; k < 3; k++) err |= put(f, (uint32_t)eye[k]);
        for (k = 0; k < 3; k++) err |= put(f, (uint32_t)tg[k]);
        err |= put(f, (uint32_t)fovy) | put(f, (uint32_t)zn) | put(f, (uint32_t)zf);
    }
    if (fclose(f) != 0 || err) { fprintf(stderr, "peer_dump: %s: write failed\n", argv[2]); return 1; }
    if (argc == 5) {   /* the reference frame, as bitrain bench draws it */
        int w, h;
        rs_frame fr;
        rs_band_stats st = { 0, 0, 0, 0 };
        uint32_t *color, *zbuf;
        if (sscanf(argv[4], "%dx%d", &w, &h) != 2 || w < 1 || h < 1 || w > RS_MAX_DIM || h > RS_MAX_DIM) {
            fprintf(stderr, "peer_dump: bad size '%s'\n", argv[4]);
            return 2;
        }
        if (peer_frame(argv[3][0], w, h, v, prims, &fr) != 0) { fprintf(stderr, "peer_dump: bad camera\n"); return 2; }
        fr.cache = (rs_cvert *)malloc(rs_cache_mem_size(PEER_NV));
        fr.chunks = (int16_t *)malloc(rs_chunk_mem_size(prims, fr.nprims));
        fr.one_band = 1;
        color = (uint32_t *)malloc((size_t)w * (size_t)h * 4);
        zbuf = (uint32_t *)malloc((size_t)w * (size_t)h * 4);
        if (!fr.cache || !fr.chunks || !color || !zbuf) { fprintf(stderr, "peer_dump: out of memory\n"); return 1; }
        if (rs_frame_prepare(&fr) != BR_OK || rs_draw_band(&fr, 0, h, color, (size_t)w * 4, zbuf, &st) != BR_OK) {
            fprintf(stderr, "peer_dump: render failed\n");
            return 1;
        }
        printf("camera=%c size=%dx%d checksum=%016llx drawn_tris=%u clipped=%u span_px=%u\n", argv[3][0], w, h,
               (unsigned long long)pf_checksum(color, w, h, (size_t)w), st.tris, st.clipped,
               st.pixels);
        free(fr.cache); free(fr.chunks); free(color); free(zbuf);
    }
    free(ps); free(v);
    return 0;
}
