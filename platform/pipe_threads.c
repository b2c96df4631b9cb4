#define _POSIX_C_SOURCE 200809L   /* pthreads, clock_gettime, posix_memalign, sysconf */
/* platform/pipe_threads.c — see pipe_threads.h. */
#include "platform/clock.h"
#include "platform/pipe_threads.h"
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

typedef struct pt_worker {
    pt_pool *pool;
    int index;
    void *mem;
    size_t mem_size;
    pthread_t tid;
    pt_thread_time time;
} pt_worker;

struct pt_pool {
    int n, started;                 /* threads in all (caller included); workers started */
    pt_worker w[PT_MAX_THREADS];
    pthread_mutex_t lock;
    pthread_cond_t go;              /* a new frame (or quit) for the workers */
    pthread_cond_t turn;            /* sink_next moved on, or an error */
    pthread_cond_t done;            /* a worker finished the frame, or the last job ended */
    unsigned long gen;              /* frames started */
    int quit, finished;
    /* the frame in progress: read-only while it runs except where noted */
    const rs_pipe *p;
    int32_t band_rows, nbands;
    rs_sink sink;
    void *sink_user;
    int32_t next_band;              /* under lock: the next band nobody has taken */
    int32_t sink_next;              /* under lock: the band whose turn at the sink it is */
    br_status err;                  /* under lock: the first error */
    rs_band_stats total;            /* under lock */
    pt_job job;                     /* pt_jobs in progress (NULL: bands) */
    void *job_user;
    uint32_t njobs, next_job, jobs_done;  /* under lock */
};

int pt_online_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1) return 1;
    return n > PT_MAX_THREADS ? PT_MAX_THREADS : (int)n;
}

static void add_stats(rs_band_stats *t, const rs_band_stats *s)
{
    t->tris += s->tris;
    t->clipped += s->clipped;
    t->pixels += s->pixels;
    t->passes_run |= s->passes_run;
}

/* One thread's share of the frame: take bands until none is left or an error stops it. */
static void draw_bands(pt_pool *pool, pt_worker *wk)
{
    rs_band_stats mine;
    memset(&mine, 0, sizeof mine);
    memset(&wk->time, 0, sizeof wk->time);
    for (;;) {
        int32_t i, y0, rows;
        rs_band b;
        rs_band_stats st;
        br_status s;
        double t0, t1, t2;
        pthread_mutex_lock(&pool->lock);
        i = pool->err == BR_OK ? pool->next_band++ : pool->nbands;
        pthread_mutex_unlock(&pool->lock);
        if (i >= pool->nbands) break;
        y0 = i * pool->band_rows;
        rows = pool->p->h - y0 < pool->band_rows ? pool->p->h - y0 : pool->band_rows;
        t0 = br_now_ms();
        s = rs_pipe_band(pool->p, y0, rows, wk->mem, wk->mem_size, &b, &st);
        t1 = br_now_ms();
        pthread_mutex_lock(&pool->lock);
        while (pool->sink_next != i && pool->err == BR_OK) pthread_cond_wait(&pool->turn, &pool->lock);
        if (pool->err == BR_OK && s != BR_OK) pool->err = s;
        if (pool->err != BR_OK) {
            pthread_cond_broadcast(&pool->turn);
            pthread_mutex_unlock(&pool->lock);
            break;
        }
        pthread_mutex_unlock(&pool->lock);
        t2 = br_now_ms();
        /* only the thread holding band sink_next gets here: the sink runs alone */
        s = pool->sink(pool->sink_user, y0, rows, b.color, b.stride);
        add_stats(&mine, &st);
        wk->time.draw_ms += t1 - t0;
        wk->time.wait_ms += t2 - t1;
        wk->time.sink_ms += br_now_ms() - t2;
        wk->time.bands++;
        pthread_mutex_lock(&pool->lock);
        if (s != BR_OK && pool->err == BR_OK) pool->err = s;
        pool->sink_next++;
        pthread_cond_broadcast(&pool->turn);
        pthread_mutex_unlock(&pool->lock);
    }
    pthread_mutex_lock(&pool->lock);
    add_stats(&pool->total, &mine);
    pthread_mutex_unlock(&pool->lock);
}

/* One thread's share of pt_jobs, called and returning with the lock held: take the next
 * k of generation gen until none is left or a later generation began. */
static void run_jobs(pt_pool *pool, unsigned long gen)
{
    while (pool->gen == gen && pool->next_job < pool->njobs) {
        uint32_t k = pool->next_job++;
        pt_job fn = pool->job;
        void *user = pool->job_user;
        pthread_mutex_unlock(&pool->lock);
        fn(user, k);
        pthread_mutex_lock(&pool->lock);
        if (++pool->jobs_done == pool->njobs) pthread_cond_broadcast(&pool->done);
    }
}

/* A worker: each generation is a frame of bands (pool->job NULL, every worker takes
 * part and counts itself in `finished`) or a set of jobs (pool->job set; the caller
 * waits for the jobs, not for the workers, so a worker that wakes after every job was
 * taken just waits for the next generation).  pool->job and the generation change
 * together under the lock. */
static void *worker_main(void *arg)
{
    pt_worker *wk = (pt_worker *)arg;
    pt_pool *pool = wk->pool;
    unsigned long seen = 0;
    pthread_mutex_lock(&pool->lock);
    for (;;) {
        while (pool->gen == seen && !pool->quit) pthread_cond_wait(&pool->go, &pool->lock);
        if (pool->quit) break;
        seen = pool->gen;
        if (pool->job) { run_jobs(pool, seen); continue; }
        pthread_mutex_unlock(&pool->lock);
        draw_bands(pool, wk);
        pthread_mutex_lock(&pool->lock);
        pool->finished++;
        pthread_cond_signal(&pool->done);
    }
    pthread_mutex_unlock(&pool->lock);
    return NULL;
}

br_status pt_open(pt_pool **out, int n)
{
    pt_pool *pool;
    int i;
    *out = NULL;
    if (n < 1 || n > PT_MAX_THREADS) return BR_E_ARG;
    pool = calloc(1, sizeof *pool);
    if (!pool) return BR_E_NOMEM;
    pool->n = n;
    if (pthread_mutex_init(&pool->lock, NULL) != 0) { free(pool); return BR_E_NOMEM; }
    pthread_cond_init(&pool->go, NULL);
    pthread_cond_init(&pool->turn, NULL);
    pthread_cond_init(&pool->done, NULL);
    for (i = 0; i < n; i++) { pool->w[i].pool = pool; pool->w[i].index = i; }
    /* the drawing code picks its instruction set on first use: pick it here, before
     * several threads could race to */
    (void)rs_isa();
    for (i = 1; i < n; i++) {
        if (pthread_create(&pool->w[i].tid, NULL, worker_main, &pool->w[i]) != 0) {
            pt_close(pool);
            return BR_E_NOMEM;
        }
        pool->started = i;
    }
    *out = pool;
    return BR_OK;
}

void pt_close(pt_pool *pool)
{
    int i;
    if (!pool) return;
    pthread_mutex_lock(&pool->lock);
    pool->quit = 1;
    pthread_cond_broadcast(&pool->go);
    pthread_mutex_unlock(&pool->lock);
    for (i = 1; i <= pool->started; i++) pthread_join(pool->w[i].tid, NULL);
    for (i = 0; i < pool->n; i++) free(pool->w[i].mem);
    pthread_cond_destroy(&pool->go);
    pthread_cond_destroy(&pool->turn);
    pthread_cond_destroy(&pool->done);
    pthread_mutex_destroy(&pool->lock);
    free(pool);
}

int pt_threads(const pt_pool *pool) { return pool ? pool->n : 0; }

const pt_thread_time *pt_last_times(const pt_pool *pool)
{
    static const pt_thread_time none[1];
    if (!pool) return none;
    return &pool->w[0].time;
}

/* Band memory of bytes for every thread that will draw (16-byte aligned parts). */
static br_status reserve(pt_pool *pool, int n, size_t bytes)
{
    int i;
    for (i = 0; i < n; i++) {
        pt_worker *wk = &pool->w[i];
        void *m = NULL;
        if (wk->mem_size >= bytes) continue;
        if (posix_memalign(&m, 64, bytes) != 0) return BR_E_NOMEM;
        free(wk->mem);
        wk->mem = m;
        wk->mem_size = bytes;
    }
    return BR_OK;
}

/* Wakes the workers for the frame of bands just described, takes part, waits for all. */
static void all_hands(pt_pool *pool, pt_worker *self)
{
    if (pool->n > 1) {
        pthread_mutex_lock(&pool->lock);
        pool->job = NULL;
        pool->finished = 0;
        pool->gen++;
        pthread_cond_broadcast(&pool->go);
        pthread_mutex_unlock(&pool->lock);
    }
    draw_bands(pool, self);
    if (pool->n > 1) {
        /* every worker takes part (some may find nothing left) */
        pthread_mutex_lock(&pool->lock);
        while (pool->finished < pool->started) pthread_cond_wait(&pool->done, &pool->lock);
        pthread_mutex_unlock(&pool->lock);
    }
}

void pt_jobs(pt_pool *pool, uint32_t n, pt_job fn, void *user)
{
    uint32_t k;
    unsigned long gen;
    if (!pool || pool->n == 1 || n < 2) {
        for (k = 0; k < n; k++) fn(user, k);
        return;
    }
    pthread_mutex_lock(&pool->lock);
    pool->job = fn;
    pool->job_user = user;
    pool->njobs = n;
    pool->next_job = 0;
    pool->jobs_done = 0;
    gen = ++pool->gen;
    pthread_cond_broadcast(&pool->go);
    run_jobs(pool, gen);
    while (pool->jobs_done < n) pthread_cond_wait(&pool->done, &pool->lock);
    pthread_mutex_unlock(&pool->lock);
}

br_status pt_run(pt_pool *pool, const rs_pipe *p, int32_t band_rows, rs_sink sink, void *sink_user,
                 rs_band_stats *total)
{
    size_t bytes;
    br_status s;
    if (!pool || !p || !sink || band_rows < 1 || p->h < 1) return BR_E_ARG;
    if (band_rows > p->h) band_rows = p->h;
    bytes = rs_pipe_mem_size(p, band_rows);
    if (!bytes) return BR_E_ARG;
    pool->nbands = (p->h + band_rows - 1) / band_rows;
    /* every thread may take a band (which ones is a race), so each gets memory */
    if ((s = reserve(pool, pool->n, bytes)) != BR_OK) return s;
    pool->p = p;
    pool->band_rows = band_rows;
    pool->sink = sink;
    pool->sink_user = sink_user;
    pool->next_band = 0;
    pool->sink_next = 0;
    pool->err = BR_OK;
    memset(&pool->total, 0, sizeof pool->total);
    all_hands(pool, &pool->w[0]);
    if (total) *total = pool->total;
    return pool->err;
}
