/* platform/pipe_threads.h — the frame driver (raster/frame.h) on N threads.
 *
 * A pool of N - 1 POSIX threads plus the caller's thread draws the bands of one frame:
 * each thread takes the next band not yet taken, draws it with rs_pipe_band into band
 * memory of its own, then waits for its turn and hands the band to the sink, so the sink
 * sees the bands top to bottom, one call at a time (never two at once), exactly as
 * rs_pipe_run would hand them.  Bands are independent once the frame is prepared
 * (frame.h BANDS; DESIGN.md invariant 4), so the pixels do not depend on N.
 *
 * Ordering proof: bands are taken in increasing index order, and a thread waits only
 * for the band just before its own, which some thread has already taken and is drawing
 * or handing on without waiting on anything later: the wait always ends.
 *
 * The sink may be called from any thread of the pool (not only the caller's): it must
 * not use thread-bound state (an SDL renderer, OpenGL); copying into memory is fine.
 * The passes and post hook run on several threads at once (frame.h's thread rules).
 *
 * Memory: each thread's band memory is allocated in pt_run when a frame needs more
 * than the thread has (a larger window, taller bands), never otherwise. */
#ifndef BR_PIPE_THREADS_H
#define BR_PIPE_THREADS_H
#include "raster/frame.h"

#define PT_MAX_THREADS 64

typedef struct pt_pool pt_pool;

/* What the last frame cost each thread (wall-clock milliseconds). */
typedef struct pt_thread_time {
    double draw_ms;     /* inside rs_pipe_band */
    double wait_ms;     /* waiting for the band before its own to reach the sink */
    double sink_ms;     /* inside the sink */
    int bands;
} pt_thread_time;

/* Online processor cores (at least 1, at most PT_MAX_THREADS). */
int pt_online_cores(void);

/* A pool for n threads (1 .. PT_MAX_THREADS; 1 starts no thread).  BR_E_ARG for a bad
 * n, BR_E_NOMEM when threads or memory cannot be had. */
br_status pt_open(pt_pool **out, int n);
void pt_close(pt_pool *pool);
int pt_threads(const pt_pool *pool);

/* rs_pipe_run on the pool's threads: bands of band_rows rows top to bottom, each handed
 * to sink in order; *total (may be NULL) gets the sum of the bands' statistics.  The
 * first error (of a pass, the post hook or the sink) stops the frame and is returned;
 * the sink is then not called for later bands. */
br_status pt_run(pt_pool *pool, const rs_pipe *p, int32_t band_rows, rs_sink sink, void *sink_user,
                 rs_band_stats *total);

/* Runs fn(user, k) for k = 0 .. n - 1 on the pool's threads (each k once, any thread,
 * taken in increasing order) and returns when all are done.  For work whose result
 * does not depend on which thread ran which k (the bitree's parts). */
typedef void (*pt_job)(void *user, uint32_t k);
void pt_jobs(pt_pool *pool, uint32_t n, pt_job fn, void *user);
/* Per-thread cost of the last pt_run: times[0 .. pt_threads) (thread 0 is the caller). */
const pt_thread_time *pt_last_times(const pt_pool *pool);

#endif
