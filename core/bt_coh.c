/* core/bt_coh.c — frame coherence of the view rule's decisions: how far the eye may
 * travel before a decision made now can change (contract: core/bt_em.h; the proof
 * is docs/bitree.md "Frame coherence").
 *
 * The view rule (core/bt_mesh.c decide) splits a diamond that is not culled iff
 * L > thr d, L = ew f (saturated product), d = bti_box_dist(eye, volume), thr = tau_lo
 * when the diamond has ST_PREV, else tau; a split vertex's geomorph weight is a
 * function of L and d, 0 when L < tau d and ONE when L >= (tau + span) d.  Every
 * quantity but d is fixed while the key (tree, frame, f, thresholds) is, and
 *   |bti_box_dist(e', V) - bti_box_dist(e, V)| <= |e' - e|_1                 (1)
 * (each per-axis distance to an interval moves by at most that axis' move; the
 * floored linear forms of bti_norm2_lo (core/bt_int.h), coefficients <= 1, by at most
 * the sum of the moves, an integer, and so does their maximum).  So a
 * decision holds for every eye whose distance d' lies in an interval [lo, hi]
 * around d, i.e. while the L1 travel since stays within min(hi - d, d - lo), given
 * the ST_PREV that the next frames will read: a split diamond is listed and has
 * ST_PREV next frame (tau_lo), an unsplit one has not (tau).  The memo checks that
 * bit on reuse, so a diamond whose state was lost (budget fallback, split list
 * overflow, not reached for a frame) is evaluated again.  The travel is summed
 * frame to frame into c->ctr[BT_COH_EYE] (triangle inequality: the sum bounds the travel
 * since any earlier frame), and an entry holds that sum + margin, its expiry.
 *
 * The bounds lo, hi need quotients L / c; they come from reciprocals computed when
 * the key changes (no 64-bit divide per frame), rounded towards the smaller
 * margin and then checked with the rule's own saturated products, so that the
 * interval is right whatever the rounding: the rule's products are monotone in d. */
#include <string.h>
#include "core/bitree.h"
#include "core/bt_int.h"
#include "core/bt_em.h"

/* d < 2^32: every coordinate of the eye and of the volumes is within +-CAM_COORD_MAX
 * < 2^30 (core/cam.h; bti_setup refuses larger frames), so each per-axis distance is
 * < 2^31 and bti_box_dist <= their Euclidean norm < sqrt(3) 2^31 < 2^32.  So a bound >= 2^32
 * never binds, margins are < 2^32, and an entry lives at most COH_JUMP - 1 of travel:
 * a key change adds COH_JUMP, past every expiry. */
#define COH_DMAX ((int64_t)1 << 32)
#define COH_JUMP ((uint64_t)1 << 34)
#define COH_LIMIT ((uint64_t)1 << 50)   /* + COH_JUMP + a margin < 2^51 (BTI_COH_EXP) */

#define sat_mul bti_isat_mul   /* the rule's own saturated product */

/* The plane accumulators count a quarter of the eye's travel (COH_EYE_SH): the entries
 * near a plane have distance margins many times their room to it (16 to 64 times on
 * N50E009, docs/perf-history.md), so a quarter seldom ends one first, while the room
 * lasts as long as the plane moves slower than a quarter of the eye (the side planes of
 * a camera moving forward move a third to a half of its travel) */
#define COH_EYE_SH 2

typedef char bti_coh_six_planes[CAM_NPLANES == 6 ? 1 : -1];     /* (the table below) */

/* BT_COH_EYE (0) for mask 0, BT_COH_PLANE(i) (1 + i) for the mask of plane i alone,
 * BT_COH_MANY (7) for two or more */
const uint8_t bti_coh_ctr_of[64] = {
    0, 1, 2, 7, 3, 7, 7, 7, 4, 7, 7, 7, 7, 7, 7, 7,
    5, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7,
    6, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7,
    7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7, 7
};

/* <= floor(L / c) for r = floor(2^sh / c), c < 2^32 (sh = 31 + bits(c)): with s =
 * max(0, bits(L) - 32), (L >> s) r 2^s / 2^sh <= L / c, and the product < 2^64. */
static int64_t quot_lo(uint64_t L, uint64_t r, int32_t sh)
{
    int32_t s = bti_bits(L) - 32;
    if (s < 0) s = 0;
    return (int64_t)(((L >> s) * r) >> (sh - s));
}

/* Smallest-margin-safe bounds: the largest d' (>= 0) with c d' < L (strict) or
 * c d' <= L, from below; -1 when unknown.  Checked: the product at the bound. */
static int64_t below_r(int64_t L, uint64_t r, int32_t sh, int64_t cv, int strict)
{
    int64_t q;
    if (!r) return -1;
    q = quot_lo((uint64_t)(strict ? L - 1 : L), r, sh);
    if (strict ? sat_mul(cv, q) >= L : sat_mul(cv, q) > L) return -1;
    return q;
}

/* The smallest d' with c d' >= L (or > L when strict), from above; -1 when unknown. */
static int64_t above_r(int64_t L, uint64_t r, int32_t sh, int64_t cv, int strict)
{
    int64_t q;
    if (!r) return -1;
    q = quot_lo((uint64_t)L, r, sh);
    q += (q >> 28) + 2;       /* quot_lo is within 2^-29 L / c + 2 of L / c */
    if (strict ? sat_mul(cv, q) <= L : sat_mul(cv, q) < L) return -1;
    return q;
}

/* The least q = floor(L / d) - tau whose geomorph weight is not 0 (a step, BT_MORPH_STEP,
 * rounded up; 1 .. span for span >= 1: morph_at rounds the weight down to a step) */
static int64_t weight0_q(int64_t span) { return ((int64_t)BT_MORPH_STEP * span + 32767) >> 15; }

/* below_r, above_r for threshold k of c (0 tau_lo, 1 tau, 2 tau + span, 3 tau + weight0_q) */
static int64_t below(int64_t L, int k, const bt_coh *c, int64_t cv, int strict)
{ return below_r(L, c->r[k], c->sh[k], cv, strict); }
static int64_t above(int64_t L, int k, const bt_coh *c, int64_t cv, int strict)
{ return above_r(L, c->r[k], c->sh[k], cv, strict); }

/* How far (L1 eye travel, world units) the answer sp (0, 1) for L and d holds: the
 * distance interval [lo, hi] around d where it does, as margin min(hi - d, d - lo),
 * at most COH_JUMP - 1; -1 when none is known.  *moving: the split holds, its weight
 * does not (strictly between 0 and full, it moves with d). */
static int64_t margin(const bti_extract *e, int sp, int64_t L, int64_t d, uint16_t morph, int *moving)
{
    const bt_coh *c = e->coh;
    int64_t lo = 0, hi = INT64_MAX, m = (int64_t)COH_JUMP - 1;
    if (L == INT64_MAX) return -1;                   /* a saturated L: no exact bound */
    if (L == 0) return sp ? -1 : m;                  /* ew = 0: never split (unless culled) */
    if (d < 0 || (d == 0 && !sp)) return -1;         /* d = 0: the eye inside, split */
    if (sp) {
        if (e->morph_span > 0 && morph == BT_MORPH_ONE) {
            /* (tau + span) d' <= L implies tau_lo d' < L: tau_lo <= tau < tau + span, L > 0 */
            if ((hi = below(L, 2, c, e->tau + e->morph_span, 0)) < 0) return -1;
        } else {
            *moving = e->morph_span > 0 && morph != 0;
            if (e->tau_lo > 0 && (hi = below(L, 0, c, e->tau_lo, 1)) < 0) return -1;
            /* weight 0 (morph_at: floor(L / d) - tau below q0 = ceil(BT_MORPH_STEP
             * span / 2^15), q0 >= 1) while (tau + q0) d' > L */
            if (e->morph_span > 0 && !*moving && (lo = above(L, 3, c, e->tau + weight0_q(e->morph_span), 1)) < 0)
                return -1;
        }
    } else {
        if ((lo = above(L, 1, c, e->tau, 0)) < 0) return -1;
        if (lo < 1) lo = 1;                           /* d' = 0: the eye inside, split */
    }
    if (d > hi || d < lo) return -1;
    if (hi < COH_DMAX && hi - d < m) m = hi - d;
    if (lo > 0 && d - lo < m) m = d - lo;
    return m;
}

uint64_t bti_coh_entry(const bti_extract *e, int sp, int64_t L, int64_t d, uint16_t morph, unsigned m_in,
                       unsigned m_out, int64_t cm)
{
    const bt_coh *c = e->coh;
    int moving = 0;
    int64_t m = sp < 0 || d < 0 ? (int64_t)COH_JUMP - 1 : margin(e, sp, L, d, morph, &moving);
    if (m < 0) return 0;
    if (m_in) {
        /* on m_in's plane accumulator (bti_coh_frame), which grows by at least a quarter
         * of the eye's travel and by at least the travel of m_in's planes: the distance
         * margin over four, rounded down, and the room to the planes, cm / 2^30 rounded
         * down (a plane's value at the box moves by at most the plane's travel) */
        const int64_t mc = cm >> 30;
        m >>= COH_EYE_SH;
        if (mc < m) m = mc;
    }
    m += c->slack;
    if (m < 0) return 0;
    return (uint64_t)m_out << (BTI_COH_BITS + 6) | (uint64_t)m_in << BTI_COH_BITS
         | (moving ? BTI_COH_MOVING : 0) | (c->ctr[bti_coh_ctr_of[m_in]] + (uint64_t)m);
}

/* *r = floor(2^sh / v), *sh = 31 + bits(v) (quot_lo's); *r = 0 (none) unless 0 < v < 2^32 */
static void recip_of(int64_t v, uint64_t *r, int32_t *sh)
{
    *r = 0;
    *sh = 0;
    if (v <= 0 || v >= ((int64_t)1 << 32)) return;
    *sh = 31 + bti_bits((uint64_t)v);
    *r = fx_udiv_bits((uint64_t)1 << *sh, (uint64_t)v, 33);   /* < 2^32 */
}

static void recip(bt_coh *c, int k, int64_t v) { recip_of(v, &c->r[k], &c->sh[k]); }

void bti_wtab_set(bti_wtab *wt, int64_t tau, int64_t span)
{
    int64_t q;
    if (wt->tau == tau && wt->span == span) return;
    wt->tau = tau;
    wt->span = span;
    wt->on = span > 0 && span <= BTI_WQ_MAX && tau > 0;
    for (q = 1; wt->on && q <= span; q++) {
        uint64_t r;
        int32_t sh;
        recip_of(tau + q, &r, &sh);
        wt->r[q] = (uint32_t)r;
        wt->sh[q] = (uint8_t)sh;
    }
}

/* A split's weight w (morph_at: floor((floor(L / d) - tau) 2^15 / span), clamped to
 * 0 .. ONE, rounded down to a multiple s of BT_MORPH_STEP) is a function of rho =
 * floor(L / d) that stays while rho stays in w's run [tau + qa, tau + qb1 - 1]: qa =
 * ceil(w span / 2^15) (none for w = 0: every rho <= tau gives 0), qb1 = ceil((w + s)
 * span / 2^15) (the rounding keeps w while (rho - tau) 2^15 / span < w + s; none for
 * ONE: every rho >= tau + span gives it; >= 1 for w = 0, as span <= 2^15).  So it
 * stays for every d > 0 with (tau + qa) d <= L < (tau + qb1) d, whose bounds below_r
 * and above_r give from the table's reciprocals (checked with the rule's products, so
 * the run may come out shorter, never longer). */
void bti_coh_weight_run(const bti_wtab *wt, int64_t L, uint16_t morph, uint32_t *dlo, uint32_t *dhi)
{
    const int64_t tau = wt->tau, span = wt->span;
    int64_t lo = 1, hi = UINT32_MAX;
    *dlo = 1;
    *dhi = 0;
    if (!wt->on || L == INT64_MAX || morph > BT_MORPH_ONE) return;
    if (morph > 0) {
        const int64_t qa = ((int64_t)morph * span + 32767) >> 15;       /* 1 .. span */
        if ((hi = below_r(L, wt->r[qa], wt->sh[qa], tau + qa, 0)) < 0) return;
    }
    if (morph < BT_MORPH_ONE) {
        const int64_t qb1 = (((int64_t)morph + BT_MORPH_STEP) * span + 32767) >> 15; /* 1 .. span */
        if ((lo = above_r(L, wt->r[qb1], wt->sh[qb1], tau + qb1, 1)) < 0) return;
    }
    lo -= wt->slack;
    hi += wt->slack;
    if (lo < 1) lo = 1;
    if (hi > UINT32_MAX) hi = UINT32_MAX;
    if (lo > hi) return;
    *dlo = (uint32_t)lo;
    *dhi = (uint32_t)hi;
}

/* How far a plane's value may have moved at any point of box [lo, hi] (the terrain's:
 * every volume lies in it), over 2^30, rounded up.  d + n . p moves by at most
 * |d' - d| + sum |n'_k - n_k| CAM_COORD_MAX (every corner lies within CAM_COORD_MAX,
 * bti_setup), and |d| < 2^63 (core/cam.h), so that difference fits 64 bits unsigned.
 * Where that bound is below 2^32 the move itself, (d' - d) + (n' - n) . p, linear in p,
 * is largest at a corner of the box: the corner each sum picks is the one the signs of
 * n' - n point to, and |d' - d| < 2^62, |(n' - n) . p| < 2^32 2^30, so the sums fit.  A
 * camera that turns a little moves its normals by a few Q30 units a frame, which the
 * first bound charges as if the volumes lay CAM_COORD_MAX away.  At most COH_JUMP. */
static uint64_t plane_travel(const cam_plane *a, const cam_plane *b, const int32_t lo[3], const int32_t hi[3])
{
    const uint64_t dd = a->d >= b->d ? (uint64_t)a->d - (uint64_t)b->d : (uint64_t)b->d - (uint64_t)a->d;
    uint64_t t = (dd >> 30) + 1, m;
    int64_t up, down, dn[3];
    int k;
    for (k = 0; k < 3; k++) {
        dn[k] = (int64_t)a->n[k] - b->n[k];
        t += (uint64_t)(dn[k] < 0 ? -dn[k] : dn[k]);
    }
    if (t >= ((uint64_t)1 << 32)) return t < COH_JUMP ? t : COH_JUMP;
    up = down = a->d - b->d;        /* no overflow: |d' - d| < 2^62 where t < 2^32 */
    for (k = 0; k < 3; k++) {
        up += dn[k] * (dn[k] >= 0 ? hi[k] : lo[k]);
        down += dn[k] * (dn[k] >= 0 ? lo[k] : hi[k]);
    }
    m = up > -down ? (uint64_t)up : (uint64_t)-down;   /* max(|up|, |down|), as up >= down */
    m = (m >> 30) + 1;
    return m < t ? m : t;
}

int bti_coh_frame(bti_extract *e, bt_coh *c)
{
    bt_coh_key k;
    const int32_t *eye = e->p->c->eye;
    const int on = BR_COHERENCE && !e->p->no_coherence;
    int wrap = 0, fresh = 0, j;
    memset(&k, 0, sizeof k);
    k.node = e->t->node; k.sum = e->t->sum; k.n = e->t->n; k.w = e->t->w; k.h = e->t->h;
    k.zmin = e->t->zmin; k.zmax = e->t->zmax; k.no_cull = e->p->no_cull != 0;
    k.fr = e->p->fr; k.fq8 = e->fq8; k.tau = e->tau; k.tau_lo = e->tau_lo; k.span = e->morph_span;
    /* ctr[BT_COH_MANY] grows at least as fast as every plane's */
    if (!c->valid || c->ctr[BT_COH_EYE] >= COH_LIMIT || c->ctr[BT_COH_MANY] >= COH_LIMIT) {
        int64_t slack = c->slack;
        wrap = c->valid;                              /* entries may hold any expiry */
        fresh = 1;
        memset(c, 0, sizeof *c);
        c->slack = slack;
        for (j = 0; j < BT_COH_NCTR; j++) c->ctr[j] = 1;
    }
    if (memcmp(&k, &c->key, sizeof k) != 0) {
        memcpy(&c->key, &k, sizeof k);   /* padding too: memcmp compares it */
        fresh = 1;
        for (j = 0; j < BT_COH_NCTR; j++)            /* every earlier expiry has passed */
            c->ctr[j] += c->valid ? COH_JUMP : 0;
        recip(c, 0, k.tau_lo);
        recip(c, 1, k.tau);
        recip(c, 2, k.tau + k.span);
        recip(c, 3, k.span > 0 ? k.tau + weight0_q(k.span) : 0);
    } else {
        /* ctr[BT_COH_EYE] grows by the eye's L1 travel t; ctr[BT_COH_PLANE(j)] by the
         * larger of t / 4 (rounded up) and plane j's travel, ctr[BT_COH_MANY] by the larger
         * of t / 4 and every plane's.  A sum of maxima is at least each sum, so an entry on
         * a plane's accumulator whose margin (the distance margin over four, the room to
         * the planes) is at least that accumulator's growth since its frame is within both */
        uint64_t t = 0, ts, pmax = 0;
        int32_t lo[3], hi[3];
        int i;
        /* the terrain's box in world units (core/bt_mesh.c bti_setup's checks) */
        lo[0] = e->p->fr.ox;
        hi[0] = (int32_t)((int64_t)e->p->fr.ox + (int64_t)e->S * e->p->fr.sx);
        lo[1] = (int32_t)((int64_t)e->p->fr.oy - (int64_t)e->S * e->p->fr.sy);
        hi[1] = e->p->fr.oy;
        lo[2] = e->wz_lo[0];
        hi[2] = e->wz_hi[255];
        for (i = 0; i < 3; i++) {
            int64_t dv = (int64_t)eye[i] - c->eye[i];
            t += (uint64_t)(dv < 0 ? -dv : dv);
        }
        ts = (t + ((uint64_t)1 << COH_EYE_SH) - 1) >> COH_EYE_SH;
        for (j = 0; j < CAM_NPLANES; j++) {
            const uint64_t pt = plane_travel(&e->pl[j], &c->pl[j], lo, hi);
            c->ctr[BT_COH_PLANE(j)] += pt > ts ? pt : ts;
            if (pt > pmax) pmax = pt;
        }
        c->ctr[BT_COH_MANY] += pmax > ts ? pmax : ts;
        c->ctr[BT_COH_EYE] += t;
    }
    c->valid = 1;
    c->fresh = fresh;
    memcpy(c->eye, eye, sizeof c->eye);
    memcpy(c->pl, e->pl, sizeof c->pl);
    e->coh = BR_COHERENCE ? c : NULL;
    /* coh_acc is coh_ctr[BT_COH_EYE] again, in its own field for the replay's weight runs
     * (bti_coh_proves picks an entry's accumulator by its plane mask, with no branch) */
    for (j = 0; j < BT_COH_NCTR; j++) e->coh_ctr[j] = on ? c->ctr[j] : UINT64_MAX;
    e->coh_acc = e->coh_ctr[BT_COH_EYE];
    return wrap;
}
