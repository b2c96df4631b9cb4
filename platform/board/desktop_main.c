/* platform/board/desktop_main.c — the board main's frames (board.h) built for the
 * desktop: the same code and the same baked arrays as the Cortex-M build, printing
 *   desktop frame N checksum: XXXXXXXX
 * for each frame, which `make mcu` compares with the board's `mcu frame N checksum:`.
 * Each band also goes through platform/sink_spi.c's own sink (spi_sink_band) into a
 * writer that sums what it is given the same way: a frame whose board stream differs
 * from the Linux sink's is an error, and so is one whose checksum is not the one baked
 * from the product's frame path (mcu/bake.h scene_sum).
 *
 *   bitrain-board-desktop [-o DIR] [--mem] [--bare] [--band-load]
 *   -o DIR  also writes each frame as DIR/board-N.png (RGB565 expanded)
 *   --mem   prints the RAM each part of the board's arena takes
 *   --band-load  prints how each frame's triangles and vertices fall into bands of
 *           4, 8, 16 and 60 rows (band_load)
 *   --bare  no second sink (no check, no -o): board_frame does what the board does, so
 *           valgrind --tool=callgrind --toggle-collect=board_frame counts the same work */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "platform/board/board.h"
#include "platform/board/spi_band.h"
#include "platform/png_io.h"
#include "platform/sink_spi.h"

typedef struct tap {
    spi_sink ss;
    uint32_t sum;
    int dc;
    uint8_t *rgb;               /* -o: the frame as RGB888 */
    int32_t w;
} tap;

static br_status sum_write(void *user, int dc, const uint8_t *p, size_t n, br_err *err)
{
    tap *t = (tap *)user;
    (void)err;
    t->sum = spib_sum(t->sum, &t->dc, dc, p, n);
    return BR_OK;
}

static br_status tap_band(void *user, int32_t y0, int32_t rows, const void *px, size_t stride)
{
    tap *t = (tap *)user;
    int32_t y;
    br_status st = spi_sink_band(&t->ss, y0, rows, px, stride);
    if (st != BR_OK || !t->rgb) return st;
    for (y = 0; y < rows; y++)
        rs_to_rgb888(RS_FMT_RGB565, (const uint8_t *)px + (size_t)y * stride, t->w,
                     t->rgb + (size_t)(y0 + y) * (size_t)t->w * 3);
    return BR_OK;
}

/* One frame's triangles and vertices in bands of `rows` rows: a triangle counts in
 * every band that the rows of its vertices meet (one with a vertex behind the near plane
 * or outside the guard band in every band, one wholly off one side of the screen in
 * none), a vertex in every band one of its triangles counts in.  Prints the most any
 * band holds and the sums over the bands against the frame's own counts: what a frame
 * path that keeps only one band's vertices and triangles at a time would hold, and how
 * often it would set each up. */
static int band_load(int frame, int32_t h, int32_t rows)
{
    const rs_cvert *cv;
    const br_index *idx;
    uint32_t nv, ns, t, tris = 0, used = 0, most_t = 0, most_v = 0, sum_t = 0, sum_v = 0;
    uint8_t *seen;
    int32_t y0;
    board_last_frame(&cv, &nv, &idx, &ns);
    if (!(seen = calloc(nv ? nv : 1, 1))) return 1;
    for (t = 0; t + 2 < ns; t++) {
        const uint32_t a = idx[t], b = idx[t + 1], c = idx[t + 2];
        if (a == b || b == c || a == c) continue;       /* the strip's joins */
        tris++;
        seen[a] = seen[b] = seen[c] = 1;
    }
    for (t = 0; t < nv; t++) used += seen[t];
    for (y0 = 0; y0 < h; y0 += rows) {
        const int32_t lo_y = y0 << RS_SUBPIX_BITS, hi_y = (y0 + rows) << RS_SUBPIX_BITS;
        uint32_t nt = 0, nvb = 0;
        memset(seen, 0, nv);
        for (t = 0; t + 2 < ns; t++) {
            const uint32_t a = idx[t], b = idx[t + 1], c = idx[t + 2];
            const uint32_t all = cv[a].c & cv[b].c & cv[c].c, any = cv[a].c | cv[b].c | cv[c].c;
            if (a == b || b == c || a == c || (all >> 24 & 0x3fu)) continue;
            if (!(any >> 24 & (RS_OUT_NEAR | RS_OUT_GUARD))) {
                int32_t lo = cv[a].y, hi = cv[a].y;
                if (cv[b].y < lo) lo = cv[b].y;
                if (cv[b].y > hi) hi = cv[b].y;
                if (cv[c].y < lo) lo = cv[c].y;
                if (cv[c].y > hi) hi = cv[c].y;
                if (hi < lo_y || lo >= hi_y) continue;
            }
            nt++;
            nvb += !seen[a] + !seen[b] + !seen[c];
            seen[a] = seen[b] = seen[c] = 1;
        }
        if (nt > most_t) most_t = nt;
        if (nvb > most_v) most_v = nvb;
        sum_t += nt;
        sum_v += nvb;
    }
    printf("desktop frame %d band load, %2ld-row bands: at most %lu of %lu strip triangles and %lu of %lu vertices"
           " in one band; %.2f bands a triangle, %.2f a vertex\n", frame, (long)rows, (unsigned long)most_t,
           (unsigned long)tris, (unsigned long)most_v, (unsigned long)used, tris ? (double)sum_t / tris : 0.0,
           used ? (double)sum_v / used : 0.0);
    free(seen);
    return 0;
}

int main(int argc, char **argv)
{
    const char *dir = NULL;
    int mem = 0, bare = 0, load = 0, i, rc = 0;
    size_t size[BP_N], total = 0;
    void *arena;
    tap t;
    spi_writer wr;
    br_err err;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-o") && i + 1 < argc) dir = argv[++i];
        else if (!strcmp(argv[i], "--mem")) mem = 1;
        else if (!strcmp(argv[i], "--bare")) bare = 1;
        else if (!strcmp(argv[i], "--band-load")) load = 1;
        else { fprintf(stderr, "usage: %s [-o DIR] [--mem] [--bare] [--band-load]\n", argv[0]); return 2; }
    }
    if (load && !*board_part_name(BP_MESH)) {
        fprintf(stderr, "%s: --band-load counts the mesh path's strip (bitrain-board-desktop-mesh)\n", argv[0]);
        return 2;
    }
    board_init(NULL, 0, size);
    for (i = 0; i < BP_N; i++) total += size[i];
    arena = malloc(total);
    if (!arena || board_init(arena, total, size) != BR_OK) { fprintf(stderr, "board: cannot set up the scene\n"); return 1; }
    if (mem) {
        for (i = 0; i < BP_N; i++) {
            const char *from = "";
            size_t lent = board_part_borrowed(i, &from);
            if (!*board_part_name(i)) continue;     /* a part this path does not have */
            if (lent) printf("board ram: %-24s %8zu bytes (in %s: %zu)\n", board_part_name(i), size[i], from, lent);
            else printf("board ram: %-24s %8zu bytes\n", board_part_name(i), size[i]);
        }
        printf("board ram: %-24s %8zu bytes\n", "board state (static)", board_state_size());
        printf("board ram: %-24s %8zu bytes\n", "arena total", total);
    }
    memset(&t, 0, sizeof t);
    wr.write = sum_write; wr.wait_ms = NULL; wr.user = &t;
    t.w = 320;   /* bake.fb_w: the baked frames are 320 x 240 */
    if (spi_sink_open(&t.ss, &wr, SPI_PANEL_ST7789, 320, 240, RS_FMT_RGB565, -1, &err) != BR_OK) {
        fprintf(stderr, "board: %s\n", err.msg);
        return 1;
    }
    if (dir && !bare && !(t.rgb = malloc((size_t)320 * 240 * 3))) return 1;
    for (i = 0; i < board_frames(); i++) {
        board_frame_info fi;
        br_status st;
        t.sum = SPIB_SUM_INIT; t.dc = -1;
        st = board_frame(i, bare ? NULL : tap_band, &t, &fi);
        if (st != BR_OK) { fprintf(stderr, "board: frame %d failed: %s\n", i, br_status_name(st)); rc = 1; break; }
        printf("desktop frame %d checksum: %08lx\n", i, (unsigned long)fi.sum);
        if (fi.ns)
            printf("desktop frame %d: %lu triangles, %lu vertices, %lu strip indices, %lu pixels%s\n", i,
                   (unsigned long)fi.ntri, (unsigned long)fi.nv, (unsigned long)fi.ns, (unsigned long)fi.pixels,
                   fi.overflow ? ", budget fallback" : "");
        else if (!bare)
            printf("desktop frame %d: %lu triangles, %lu triangle set-ups in bands, %lu pixels\n", i,
                   (unsigned long)board_last_triangles(), (unsigned long)fi.ntri, (unsigned long)fi.pixels);
        if (load && fi.ns) {
            static const int32_t rows[] = { 4, 8, BOARD_BAND_ROWS, 60 };
            size_t k;
            for (k = 0; k < sizeof rows / sizeof rows[0]; k++)
                if (band_load(i, 240, rows[k])) { rc = 1; break; }     /* 240: bake.fb_h */
        }
        if (fi.sum != fi.expect) {
            fprintf(stderr, "board: frame %d: %08lx differs from the host library's %08lx (mcu/bake.h scene_sum or stream_sum)\n", i,
                    (unsigned long)fi.sum, (unsigned long)fi.expect);
            rc = 1;
        }
        if (!bare && t.sum != fi.sum) {
            fprintf(stderr, "board: frame %d: the board's SPI stream (%08lx) differs from spi_sink_band's (%08lx)\n", i,
                    (unsigned long)fi.sum, (unsigned long)t.sum);
            rc = 1;
        }
        if (t.rgb) {
            char path[4096];
            snprintf(path, sizeof path, "%s/board-%d.png", dir, i);
            if (png_write_rgb(path, 320, 240, t.rgb, 320 * 3, &err) != BR_OK) { fprintf(stderr, "board: %s\n", err.msg); rc = 1; }
        }
    }
    spi_sink_close(&t.ss);
    free(t.rgb);
    free(arena);
    return rc;
}
