/* raster/frame.c — the one frame driver (see frame.h). */
#include <string.h>
#include "raster/frame.h"

/* Band memory is carved into 16-byte aligned parts (SIMD stores in the clear). */
#define PART_ALIGN 16u

static size_t align_up(size_t n) { return (n + (PART_ALIGN - 1)) & ~(size_t)(PART_ALIGN - 1); }

static size_t bytes_per_px(int32_t fmt) { return fmt == RS_FMT_RGB565 ? 2u : 4u; }

/* Rows of a scratch band for bands of `rows` rows: the margins above and below, at most
 * the frame's height (a margin beyond the frame is clipped away). */
static int32_t scratch_rows(const rs_pipe *p, const rs_pass *pass, int32_t rows)
{
    int64_t r = (int64_t)rows + 2 * (int64_t)pass->margin;
    return r > p->h ? p->h : (int32_t)r;
}

static size_t part_size(const rs_pipe *p, int32_t rows)
{
    return align_up((size_t)p->w * (size_t)rows * bytes_per_px(p->fmt))
         + align_up((size_t)p->w * (size_t)rows * rs_depth_bytes(p->depth));
}

br_status rs_pipe_add(rs_pipe *p, const rs_pass *pass)
{
    if (!p || !pass || !pass->run || p->npasses < 0 || p->npasses >= RS_PIPE_MAX_PASSES
        || pass->margin < 0 || pass->margin > RS_MAX_DIM || (pass->scratch != 0 && pass->scratch != 1)
        || (pass->scratch && p->depth == RS_DEPTH_NONE))    /* a scratch is colour and depth */
        return BR_E_ARG;
    p->passes[p->npasses++] = *pass;
    return BR_OK;
}

size_t rs_pipe_mem_size(const rs_pipe *p, int32_t band_rows)
{
    size_t n;
    int32_t i;
    if (!p || p->w < 1 || p->h < 1 || p->w > RS_MAX_DIM || p->h > RS_MAX_DIM || band_rows < 1) return 0;
    if (band_rows > p->h) band_rows = p->h;
    n = part_size(p, band_rows);
    for (i = 0; i < p->npasses; i++)
        if (p->passes[i].scratch) n += part_size(p, scratch_rows(p, &p->passes[i], band_rows));
    return n;
}

br_status rs_pipe_band(const rs_pipe *p, int32_t y0, int32_t rows, void *mem, size_t mem_size,
                       rs_band *b, rs_band_stats *st)
{
    uint8_t *m = (uint8_t *)mem;
    size_t used;
    int32_t i;
    if (!p || !mem || !b || !st || y0 < 0 || rows < 1 || y0 + rows > p->h) return BR_E_ARG;
    if (rs_pipe_mem_size(p, rows) > mem_size) return BR_E_ARG;
    memset(b, 0, sizeof *b);
    memset(st, 0, sizeof *st);
    b->w = p->w; b->y0 = y0; b->rows = rows;
    b->fmt = p->fmt; b->depth_fmt = p->depth;
    b->stride = (size_t)p->w * bytes_per_px(p->fmt);
    b->color = m;
    b->depth = m + align_up(b->stride * (size_t)rows);
    used = part_size(p, rows);
    for (i = 0; i < p->npasses; i++) {
        const rs_pass *pass = &p->passes[i];
        int32_t top = y0 - pass->margin, bottom = y0 + rows + pass->margin;   /* [top, bottom) */
        br_status s;
        if (top < 0) top = 0;
        if (bottom > p->h) bottom = p->h;
        if (pass->rows_touched && !pass->rows_touched(pass->user, top, bottom - top)) continue;
        if (pass->scratch) {
            /* the scratch part is sized for scratch_rows(rows) >= bottom - top */
            b->scratch[i] = m + used;
            b->scratch_y0[i] = top;
            b->scratch_rows[i] = bottom - top;
            b->scratch_stride[i] = b->stride;
            b->scratch_depth[i] = m + used + align_up(b->stride * (size_t)(bottom - top));
            used += part_size(p, scratch_rows(p, pass, rows));
        }
        s = pass->run(pass->user, b, i, st);
        if (s != BR_OK) return s;
        st->passes_run |= 1u << i;
    }
    return p->post ? p->post(p->post_user, b, st) : BR_OK;
}

br_status rs_pipe_run(const rs_pipe *p, int32_t band_rows, void *mem, size_t mem_size,
                      rs_sink sink, void *sink_user, rs_band_stats *total)
{
    int32_t y0;
    if (!p || !sink || band_rows < 1) return BR_E_ARG;
    if (band_rows > p->h) band_rows = p->h;
    if (total) memset(total, 0, sizeof *total);
    for (y0 = 0; y0 < p->h; y0 += band_rows) {
        int32_t rows = p->h - y0 < band_rows ? p->h - y0 : band_rows;
        rs_band b;
        rs_band_stats st;
        br_status s = rs_pipe_band(p, y0, rows, mem, mem_size, &b, &st);
        if (s != BR_OK) return s;
        if (total) {
            total->tris += st.tris;
            total->clipped += st.clipped;
            total->pixels += st.pixels;
            total->passes_run |= st.passes_run;
        }
        s = sink(sink_user, y0, rows, b.color, b.stride);
        if (s != BR_OK) return s;
    }
    return BR_OK;
}

/* ---------------------------------------------------------------- the terrain pass */

static br_status terrain_run(const void *user, rs_band *b, int32_t self, rs_band_stats *st)
{
    const rs_frame *f = (const rs_frame *)user;
    (void)self;
    if (f->one_band && b->rows != f->h) return BR_E_ARG;   /* its chunk table says "every row" */
    return rs_draw_band(f, b->y0, b->rows, b->color, b->stride, b->depth, st);
}

br_status rs_pass_terrain(rs_pass *pass, const rs_frame *f)
{
    if (!pass || !f || !f->chunks) return BR_E_ARG;
    memset(pass, 0, sizeof *pass);
    pass->name = "terrain";
    pass->run = terrain_run;
    pass->user = f;
    return BR_OK;
}
