/* SPDX-License-Identifier: MIT */
#include "np_fdiff.h"

#include <stddef.h>
#include <string.h>

/* Index of the quadric's bit in the set-up masks. */
enum { SETUP_QUAD_BIT = 8 };

np_fdiff_cfg np_fdiff_cfg_default(void)
{
    np_fdiff_cfg c;
    c.idx_int = 10;
    c.w_frac = 12;
    /*
     * 44 guard bits (F = 56), no re-set-up interval. The drift bound
     * (np_fdiff.h) then keeps up to four octaves at the steepest colour map
     * (255 LSB per index unit) within 1 LSB over any run of up to 65,535
     * steps: 0.5 + 255 (4 * 2^-57 B3(65535) + 2^-13) = 0.86 LSB. 42 bits are
     * the fewest the bound guarantees for one octave, and the fewest that
     * hold: test fdiff.guard_min_both_ways finds a 65,536-pixel span over
     * 1 LSB at 41 (the fixed stiff cases of fdiff.guard_search happen to hold
     * at 41); docs/fdiff.md shows what fewer bits do.
     */
    c.guard = 44;
    c.resetup = 0;
    c.setup_mults = 2;
    c.mult_lat = 2;
    c.carry = 0;
    return c;
}

const char *np_fdiff_cfg_check(const np_fdiff_cfg *c)
{
    if (c->idx_int < NP_TEX_IDX_INT_MIN || c->idx_int > 11)
        return "idx_int must be 1..11 (the exact set-up needs 1 + idx_int + 116 <= 128)";
    if (c->w_frac < NP_TEX_W_FRAC_MIN || c->w_frac > NP_TEX_W_FRAC_MAX)
        return "w_frac must be 1..24";
    if (c->guard > NP_FDIFF_GUARD_MAX || np_fdiff_width(c) > 127)
        return "guard too large: 1 + idx_int + w_frac + guard must be <= 127";
    if (c->setup_mults < 1 || c->setup_mults > NP_FDIFF_MULTS_MAX)
        return "setup_mults must be 1..64";
    if (c->mult_lat < 1 || c->mult_lat > NP_FDIFF_LAT_MAX)
        return "mult_lat must be 1..16";
    if (c->carry > 1)
        return "carry must be 0 (multiplier set-up) or 1 (carried set-up)";
    return NULL;
}

/* One cell: hash and coefficient adders (2), difference adders and round/load (2). */
const np_tex_sched np_fdiff_sched_cell = { "cell", 4, 4, { 4, 14, 6, 4 } };
/* Quadric: M_q s, M_q ds (18); s.M_q s, s.M_q ds, ds.M_q ds, b.s, b.ds (15); sum, round/load. */
const np_tex_sched np_fdiff_sched_quad = { "quadric", 2, 2, { 18, 15 } };

double np_fdiff_drift_bound_noise(unsigned F, uint64_t m)
{
    double k = (double)m;
    return np_pow2i(-(int)F - 1) * (1.0 + k + k * (k - 1.0) / 2.0 + k * (k - 1.0) * (k - 2.0) / 6.0);
}

double np_fdiff_drift_bound_quad(unsigned F, uint64_t m)
{
    double k = (double)m;
    return np_pow2i(-(int)F - 1) * (1.0 + k + k * (k - 1.0) / 2.0);
}

/* Modular multiply-add shorthands of the set-up engine (np_fixed.h: exact mod 2^128). */
static np_s128 mul(np_s128 a, np_s128 b) { return np_mul128(a, b); }
static np_s128 add(np_s128 a, np_s128 b) { return np_add128(a, b); }
static np_s128 shl(np_s128 a, unsigned s) { return np_shl128(a, s); }

static void cell_setup(const np_fdiff_cfg *cfg, const np_tex_regs *r, unsigned oct, const uint64_t u[3],
                       const int64_t du[3], np_s128 d[4], np_s128 exact[4], np_fdiff_setup_sig *sig)
{
    /* The Appendix's coefficients, s10 Q3.6, exact (np_fdiff_carry.c). */
    int64_t co8[8];
    np_fdiff_cell_coef(u, co8);
    const int64_t ca = co8[0], cb = co8[1], cc = co8[2], cd = co8[3], ce = co8[4], cf = co8[5], cg = co8[6],
                  ch = co8[7];
    /* Fractions u32 Q0.32 and steps s40 Q7.32. */
    const np_s128 fu = np_tex_frac(u[0]), fv = np_tex_frac(u[1]), fw = np_tex_frac(u[2]);
    const np_s128 dU = du[0], dV = du[1], dW = du[2];
    const unsigned C = NP_TEX_FC;

    /* Level 1 (Q.64). */
    np_s128 uv = mul(fu, fv), udv = mul(fu, dV), vdu = mul(fv, dU), dudv = mul(dU, dV);
    np_s128 cross = add(udv, vdu);
    /* Level 2 (Q.70): P = a + bU + cV + eUV and R = d + fV + gU + hUV as p0 + p1 k + p2 k^2. */
    np_s128 p0 = add(add(shl(ca, 2u * C), shl(add(mul(cb, fu), mul(cc, fv)), C)), mul(ce, uv));
    np_s128 p1 = add(shl(add(mul(cb, dU), mul(cc, dV)), C), mul(ce, cross));
    np_s128 p2 = mul(ce, dudv);
    np_s128 r0 = add(add(shl(cd, 2u * C), shl(add(mul(cf, fv), mul(cg, fu)), C)), mul(ch, uv));
    np_s128 r1 = add(shl(add(mul(cf, dV), mul(cg, dU)), C), mul(ch, cross));
    np_s128 r2 = mul(ch, dudv);
    if (sig) {
        const int64_t co[8] = { ca, cb, cc, cd, ce, cf, cg, ch };
        memcpy(sig->coef, co, sizeof co);
        sig->uv = uv;
        sig->cross = cross;
        sig->dudv = dudv;
        sig->p[0] = p0;
        sig->p[1] = p1;
        sig->p[2] = p2;
        sig->r[0] = r0;
        sig->r[1] = r1;
        sig->r[2] = r2;
    }
    /* Level 3 (Q.102): n = P + W R with W = fw + k dw. */
    np_s128 delta = add(shl(p0, C), mul(fw, r0));
    np_s128 gamma = add(add(shl(p1, C), mul(fw, r1)), mul(dW, r0));
    np_s128 beta = add(add(shl(p2, C), mul(fw, r2)), mul(dW, r1));
    np_s128 alpha = mul(dW, r2);
    /* Equation 21 (Q.102). */
    np_s128 x[4];
    x[0] = delta;
    x[1] = add(add(alpha, beta), gamma);
    x[2] = add(mul((np_s128)6, alpha), mul((np_s128)2, beta));
    x[3] = mul((np_s128)6, alpha);
    /* Level 4: the amplitude (Q.116), then one rounding per difference. */
    const unsigned F = np_fdiff_frac(cfg), W = np_fdiff_width(cfg);
    for (unsigned j = 0; j < 4; j++) {
        np_s128 y = mul((np_s128)r->oct[oct].amp, x[j]);
        if (exact)
            exact[j] = y;
        if (sig)
            sig->y[j] = y;
        d[j] = np_tex_to_index(y, NP_FDIFF_EXACT_FRAC, F, W);
    }
}

void np_fdiff_cell_setup(const np_fdiff_cfg *cfg, const np_tex_regs *r, unsigned oct,
                         const uint64_t u[3], const int64_t du[3], np_s128 d[4], np_s128 exact[4])
{
    cell_setup(cfg, r, oct, u, du, d, exact, NULL);
}

void np_fdiff_cell_setup_sig(const np_fdiff_cfg *cfg, const np_tex_regs *r, unsigned oct, const uint64_t u[3],
                             const int64_t du[3], np_s128 d[4], np_fdiff_setup_sig *sig)
{
    cell_setup(cfg, r, oct, u, du, d, NULL, sig);
}

void np_fdiff_quad_setup(const np_fdiff_cfg *cfg, const np_tex_regs *r, const int64_t s[3],
                         const int64_t ds[3], np_s128 q[3], np_s128 exact[3])
{
    np_s128 e[3];
    np_tex_quadric_exact(r, s, ds, e);
    const unsigned F = np_fdiff_frac(cfg), W = np_fdiff_width(cfg);
    for (unsigned j = 0; j < 3; j++) {
        if (exact)
            exact[j] = e[j];
        q[j] = np_tex_to_index(e[j], np_tex_q_frac(r), F, W);
    }
}

np_s128 np_fdiff_noise_exact(const np_tex_regs *r, unsigned oct, const uint64_t u[3],
                             const int64_t du[3], int64_t k)
{
    uint8_t n[8];
    np_tex_lattice(np_tex_cell(u[0]), np_tex_cell(u[1]), np_tex_cell(u[2]), n);
    const np_s128 one = (np_s128)1 << NP_TEX_FC;
    np_s128 t[3];
    for (unsigned a = 0; a < 3; a++)
        t[a] = add((np_s128)np_tex_frac(u[a]), mul((np_s128)k, (np_s128)du[a])); /* Q.32 */
    np_s128 sum = 0;
    for (unsigned c = 0; c < 8; c++) {
        np_s128 w = (np_s128)n[c]; /* Q.6 */
        for (unsigned a = 0; a < 3; a++)
            w = mul(w, (c >> a) & 1u ? t[a] : add(one, -t[a]));
        sum = add(sum, w); /* Q.102 */
    }
    return mul((np_s128)r->oct[oct].amp, sum); /* Q.116 */
}

/* --- The core: the same steps for the bit-exact and the cycle model --- */

unsigned np_fdiff_cell_cycles(const np_fdiff_cfg *c)
{
    return np_tex_sched_cycles(&np_fdiff_sched_cell, c->setup_mults, c->mult_lat);
}

unsigned np_fdiff_quad_cycles(const np_fdiff_cfg *c)
{
    return np_tex_sched_cycles(&np_fdiff_sched_quad, c->setup_mults, c->mult_lat);
}

unsigned np_fdiff_front_cycles(const np_fdiff_cfg *c, const np_tex_regs *r)
{
    const np_tex_sched *front = np_tex_regs_diagonal(r) ? &np_tex_sched_octave_diag : &np_tex_sched_octave;
    return np_tex_sched_cycles(front, c->setup_mults, c->mult_lat);
}

unsigned np_fdiff_span_setup_cycles(const np_fdiff_cfg *c, const np_tex_regs *r)
{
    return np_fdiff_quad_cycles(c) + r->n_oct * (np_fdiff_front_cycles(c, r) + np_fdiff_cell_cycles(c));
}

static unsigned cell_cycles(const np_fdiff_cfg *c) { return np_fdiff_cell_cycles(c); }
static unsigned quad_cycles(const np_fdiff_cfg *c) { return np_fdiff_quad_cycles(c); }

/* --- The set-up engine's timeline (np_fdiff.h: set-up overlapped with stepping) --- */

enum { LIST_CELL, LIST_QUAD, LIST_SPAN };
enum { B = NP_FDIFF_SHADOWS };

/* Append schedule sc's phases (levels, then its fixed clocks) to a list. */
static void tl_append(int16_t *ph, unsigned *n, const np_tex_sched *sc)
{
    for (unsigned l = 0; l < sc->levels; l++)
        if (sc->mults[l] && *n < NP_FDIFF_PHASES_MAX)
            ph[(*n)++] = (int16_t)sc->mults[l];
    if (sc->fixed && *n < NP_FDIFF_PHASES_MAX)
        ph[(*n)++] = (int16_t)-(int)sc->fixed;
}

static void tl_init(np_fdiff_core *c)
{
    np_fdiff_timeline *t = &c->tl;
    const np_tex_sched *front = np_tex_regs_diagonal(c->r) ? &np_tex_sched_octave_diag : &np_tex_sched_octave;
    tl_append(t->ph[LIST_CELL], &t->nph[LIST_CELL], &np_fdiff_sched_cell);
    tl_append(t->ph[LIST_QUAD], &t->nph[LIST_QUAD], &np_fdiff_sched_quad);
    tl_append(t->ph[LIST_SPAN], &t->nph[LIST_SPAN], front);
    tl_append(t->ph[LIST_SPAN], &t->nph[LIST_SPAN], &np_fdiff_sched_cell);
}

/*
 * Enter phase j->cur at clock at: fixed phases pass by themselves; past the
 * last, the job is finished.
 */
static void tl_enter(const np_fdiff_core *c, np_fdiff_job *j, uint64_t at)
{
    const np_fdiff_timeline *t = &c->tl;
    const int16_t *ph = t->ph[j->list];
    j->ready = at;
    while (j->cur < t->nph[j->list] && ph[j->cur] < 0)
        j->ready += (uint64_t)-ph[j->cur++];
    if (j->cur >= t->nph[j->list]) {
        j->state = 2;
        j->done = j->ready;
    } else {
        j->left = (unsigned)ph[j->cur];
    }
}

static void tl_start(np_fdiff_core *c, unsigned slot, unsigned list, uint32_t need, uint64_t key, uint64_t release)
{
    np_fdiff_timeline *t = &c->tl;
    np_fdiff_job *j = &t->job[slot];
    memset(j, 0, sizeof *j);
    j->state = 1;
    j->list = (uint8_t)list;
    j->need = need;
    j->key = key;
    tl_enter(c, j, release);
}

/* One clock x of the engine: the P multiplier slots to the ready jobs, most urgent first. */
static void tl_clock(np_fdiff_core *c, uint64_t x)
{
    np_fdiff_timeline *t = &c->tl;
    unsigned order[NP_FDIFF_JOBS], n = 0, slots = c->cfg->setup_mults;
    for (unsigned i = 0; i < NP_FDIFF_JOBS; i++) {
        if (t->job[i].state != 1 || t->job[i].ready > x)
            continue;
        unsigned p = n++;
        while (p > 0 && t->job[order[p - 1]].key > t->job[i].key) {
            order[p] = order[p - 1];
            p--;
        }
        order[p] = i;
    }
    for (unsigned q = 0; q < n && slots > 0; q++) {
        np_fdiff_job *j = &t->job[order[q]];
        unsigned take = j->left < slots ? j->left : slots;
        j->left -= take;
        slots -= take;
        if (j->left == 0) {
            j->cur++;
            tl_enter(c, j, x + c->cfg->mult_lat);
        }
    }
}

/* The earliest clock a job in flight can proceed (UINT64_MAX: none in flight). */
static uint64_t tl_next_ready(const np_fdiff_timeline *t)
{
    uint64_t m = UINT64_MAX;
    for (unsigned i = 0; i < NP_FDIFF_JOBS; i++)
        if (t->job[i].state == 1 && t->job[i].ready < m)
            m = t->job[i].ready;
    return m;
}

/* Allot every clock before T. */
static void tl_run_until(np_fdiff_core *c, uint64_t T)
{
    np_fdiff_timeline *t = &c->tl;
    while (t->clock < T) {
        uint64_t r = tl_next_ready(t);
        if (r > t->clock) {
            t->clock = r < T ? r : T;
            continue;
        }
        tl_clock(c, t->clock++);
    }
}

/* Run the engine until the job in slot finishes; its done clock. */
static uint64_t tl_finish(np_fdiff_core *c, unsigned slot)
{
    np_fdiff_timeline *t = &c->tl;
    while (t->job[slot].state == 1) {
        uint64_t r = tl_next_ready(t);
        if (r > t->clock)
            t->clock = r;
        tl_clock(c, t->clock++);
    }
    return t->job[slot].done;
}

/* The crossing finder: the next pixel after the last one found where octave o needs a set-up (0: none). */
static uint32_t tl_find(np_fdiff_core *c, unsigned o)
{
    np_fdiff_timeline *t = &c->tl;
    const uint32_t K = c->cfg->resetup, n = c->sp.n, k0 = t->la[o].k;
    while (t->la[o].k + 1u < n) {
        int crossed = 0;
        t->la[o].k++;
        for (unsigned a = 0; a < 3; a++) {
            t->la[o].u[a] = np_tex_dda(t->la[o].u[a], c->oct[o].du[a]);
            crossed |= np_tex_cell(t->la[o].u[a]) != t->la[o].cell[a];
        }
        if (crossed || (K && t->la[o].k - k0 >= K)) {
            for (unsigned a = 0; a < 3; a++)
                t->la[o].cell[a] = np_tex_cell(t->la[o].u[a]);
            return t->la[o].k;
        }
    }
    t->la[o].end = 1;
    return 0;
}

/* Queue octave o's next cell set-up, released at clock at, if a shadow set is free and one remains. */
static void tl_queue(np_fdiff_core *c, unsigned o, uint64_t at)
{
    np_fdiff_timeline *t = &c->tl;
    if (t->la[o].end || t->la[o].cnt >= B)
        return;
    const uint32_t k0 = t->la[o].k, k = tl_find(c, o);
    if (!k)
        return;
    const uint64_t found = t->la[o].t + (k - k0 + NP_FDIFF_FINDER_RATE - 1u) / NP_FDIFF_FINDER_RATE;
    if (found > at)
        at = found;
    t->la[o].t = at; /* it held there until a shadow set took the start */
    unsigned slot = o * B + (t->la[o].head + t->la[o].cnt) % B;
    t->la[o].cnt++;
    tl_start(c, slot, LIST_CELL, k, k, at);
}

/* Release a span's set-up jobs at clock at (the next span's: last in priority). */
static void tl_span_start(np_fdiff_core *c, uint64_t at)
{
    tl_start(c, NP_FDIFF_JOB_SPAN, LIST_QUAD, 0, UINT64_MAX, at);
    for (unsigned o = 0; o < c->r->n_oct; o++)
        tl_start(c, NP_FDIFF_JOB_SPAN + 1u + o, LIST_SPAN, 0, UINT64_MAX, at);
}

/* Run a span's set-up jobs to the end; the clock the last finishes; their slots freed. */
static uint64_t tl_span_finish(np_fdiff_core *c)
{
    uint64_t done = 0;
    for (unsigned i = NP_FDIFF_JOB_SPAN; i <= NP_FDIFF_JOB_SPAN + c->r->n_oct; i++) {
        uint64_t d = tl_finish(c, i);
        if (d > done)
            done = d;
    }
    for (unsigned i = NP_FDIFF_JOB_SPAN; i < NP_FDIFF_JOBS; i++)
        c->tl.job[i].state = 0;
    return done;
}

static void tl_next_quad(np_fdiff_core *c, uint64_t at)
{
    np_fdiff_timeline *t = &c->tl;
    const uint32_t K = c->cfg->resetup;
    t->job[NP_FDIFF_JOB_QUAD].state = 0;
    if (K && (uint64_t)t->qk + K < c->sp.n) {
        t->qk += K;
        tl_start(c, NP_FDIFF_JOB_QUAD, LIST_QUAD, t->qk, t->qk, at);
    }
}

static void core_setup_octave(np_fdiff_core *c, unsigned o)
{
    if (c->cfg->carry)
        np_fdiff_carry_setup(&c->oct[o].cm, c->oct[o].u, c->F, c->W, c->oct[o].d, NULL);
    else
        np_fdiff_cell_setup(c->cfg, c->r, o, c->oct[o].u, c->oct[o].du, c->oct[o].d, NULL);
    for (unsigned a = 0; a < 3; a++)
        c->oct[o].cell[a] = np_tex_cell(c->oct[o].u[a]);
    c->oct[o].steps = 0;
}

static void core_setup_quad(np_fdiff_core *c)
{
    np_fdiff_quad_setup(c->cfg, c->r, c->s, c->sp.ds, c->q, NULL);
    c->qsteps = 0;
}

void np_fdiff_core_init(np_fdiff_core *c, const np_fdiff_cfg *cfg, const np_tex_regs *r)
{
    memset(c, 0, sizeof *c);
    c->cfg = cfg;
    c->r = r;
    c->F = np_fdiff_frac(cfg);
    c->W = np_fdiff_width(cfg);
    c->ctx.cfg = cfg;
    c->ctx.r = r;
    c->ctx.F = c->F;
    c->ctx.W = c->W;
    c->ctx.fw = cfg->w_frac;
    tl_init(c);
}

unsigned np_fdiff_core_begin(np_fdiff_core *c, const np_span *sp, np_span_counts *cnt)
{
    np_fdiff_timeline *t = &c->tl;
    const uint64_t now = c->ctx.now;
    c->sp = *sp;
    c->k = 0;
    c->last_setup = 0;
    cnt->spans++;
    /* The previous span's jobs are all used (a job is only for a pixel of its span). */
    for (unsigned i = 0; i < NP_FDIFF_JOB_SPAN; i++)
        t->job[i].state = 0;
    const int fetched = t->job[NP_FDIFF_JOB_SPAN].state != 0;
    if (sp->n == 0) {
        for (unsigned i = NP_FDIFF_JOB_SPAN; i < NP_FDIFF_JOBS; i++)
            t->job[i].state = 0;
        return 0;
    }
    const unsigned cycles = np_fdiff_span_setup_cycles(c->cfg, c->r);
    memcpy(c->s, sp->s, sizeof c->s);
    core_setup_quad(c);
    for (unsigned o = 0; o < c->r->n_oct; o++) {
        np_tex_oct_span os;
        np_tex_octave_span(c->r, o, sp->s, sp->ds, &os);
        memcpy(c->oct[o].u, os.u, sizeof os.u);
        memcpy(c->oct[o].du, os.du, sizeof os.du);
        if (c->cfg->carry)
            np_fdiff_carry_init(&c->oct[o].cm, c->r, o, os.u, os.du);
        core_setup_octave(c, o);
        c->last_setup |= 1u << o;
    }
    c->last_setup |= 1u << SETUP_QUAD_BIT;
    cnt->span_setups++;
    cnt->setup_cycles += cycles;
    if (!c->ctx.timed) /* the bit-exact model: the set-up alone */
        return np_fdiff_span_setup_latency(c->cfg, c->r);
    /* Timing: the span's set-up job (started by prefetch, or now), then the second cells' jobs. */
    if (!fetched) {
        /* Nothing in flight: the engine's clock is the span's (np_span_run restarts it at 0 per span). */
        t->clock = now + 1u;
        tl_span_start(c, now + 1u);
    }
    uint64_t done = tl_span_finish(c);
    const uint64_t first = now + 1u, act = done > first ? done : first;
    for (unsigned o = 0; o < c->r->n_oct; o++) {
        memcpy(t->la[o].u, c->oct[o].u, sizeof t->la[o].u);
        memcpy(t->la[o].cell, c->oct[o].cell, sizeof t->la[o].cell);
        t->la[o].k = 0;
        t->la[o].end = 0;
        t->la[o].head = t->la[o].cnt = 0;
        t->la[o].t = act;
        for (unsigned i = 0; i < B; i++)
            tl_queue(c, o, act);
    }
    t->qk = 0;
    tl_next_quad(c, act);
    return (unsigned)(act - first);
}

unsigned np_fdiff_span_setup_latency(const np_fdiff_cfg *cfg, const np_tex_regs *r)
{
    static _Thread_local np_fdiff_core c; /* about 4 KB: not on the stack */
    np_fdiff_core_init(&c, cfg, r);
    tl_span_start(&c, 0);
    return (unsigned)tl_span_finish(&c);
}

np_s128 np_fdiff_core_x(const np_fdiff_core *c)
{
    np_s128 x = c->q[0];
    for (unsigned o = 0; o < c->r->n_oct; o++)
        x = np_wrap_s128(np_add128(x, c->oct[o].d[0]), c->W);
    return x;
}

unsigned np_fdiff_core_advance(np_fdiff_core *c, np_span_counts *cnt)
{
    const unsigned W = c->W, K = c->cfg->resetup;
    c->k++;
    c->last_setup = 0;
    if (c->k >= c->sp.n)
        return 0;
    tl_run_until(c, c->ctx.now + 1u);
    /* Texture coordinate DDA (exact; np_span_check keeps it within s48). */
    for (unsigned a = 0; a < 3; a++)
        c->s[a] += c->sp.ds[a];
    /* Quadric: two additions. */
    c->q[0] = np_wrap_s128(np_add128(c->q[0], c->q[1]), W);
    c->q[1] = np_wrap_s128(np_add128(c->q[1], c->q[2]), W);
    c->qsteps++;
    unsigned work = 0;
    for (unsigned o = 0; o < c->r->n_oct; o++) {
        np_s128 *d = c->oct[o].d;
        /* Equation 22: three additions (in hardware in parallel, on the old values). */
        d[0] = np_wrap_s128(np_add128(d[0], d[1]), W);
        d[1] = np_wrap_s128(np_add128(d[1], d[2]), W);
        d[2] = np_wrap_s128(np_add128(d[2], d[3]), W);
        c->oct[o].steps++;
        int32_t j[3];
        if (c->cfg->carry) {
            /* The carried monomials: a step (additions), and the crossing's integer shifts. */
            np_fdiff_carry_shift(c->oct[o].u, c->oct[o].du, j);
            np_fdiff_carry_step(&c->oct[o].cm);
            np_fdiff_carry_rebase(&c->oct[o].cm, j);
        }
        int crossed = 0;
        for (unsigned a = 0; a < 3; a++) {
            c->oct[o].u[a] = np_tex_dda(c->oct[o].u[a], c->oct[o].du[a]);
            crossed |= np_tex_cell(c->oct[o].u[a]) != c->oct[o].cell[a];
        }
        if (crossed || (K && c->oct[o].steps >= K)) {
            core_setup_octave(c, o);
            work += cell_cycles(c->cfg);
            if (crossed)
                cnt->cell_setups++;
            else
                cnt->interval_setups++;
            c->last_setup |= 1u << o;
        }
    }
    if (K && c->qsteps >= K) {
        core_setup_quad(c);
        work += quad_cycles(c->cfg);
        cnt->interval_setups++;
        c->last_setup |= 1u << SETUP_QUAD_BIT;
    }
    cnt->setup_cycles += work;
    if (!c->last_setup || !c->ctx.timed)
        return 0;
    /*
     * Timing: pixel k issued at clock now; pixel k + 1 waits for the set-ups
     * it swaps in (each released when its shadow freed), then their shadows
     * take the next ones.
     */
    np_fdiff_timeline *t = &c->tl;
    const uint64_t first = c->ctx.now + 1u;
    uint64_t act = first;
    for (unsigned o = 0; o < c->r->n_oct; o++)
        if (c->last_setup & (1u << o)) {
            unsigned slot = o * B + t->la[o].head;
            uint64_t d = t->la[o].cnt && t->job[slot].state ? tl_finish(c, slot) : first;
            if (d > act)
                act = d;
        }
    if (c->last_setup & (1u << SETUP_QUAD_BIT)) {
        uint64_t d = t->job[NP_FDIFF_JOB_QUAD].state ? tl_finish(c, NP_FDIFF_JOB_QUAD) : first;
        if (d > act)
            act = d;
    }
    /* The swap frees a shadow set: the next cell the finder found (or finds) takes it. */
    for (unsigned o = 0; o < c->r->n_oct; o++)
        if (c->last_setup & (1u << o) && t->la[o].cnt) {
            unsigned slot = o * B + t->la[o].head;
            t->job[slot].state = 0;
            t->la[o].head = (t->la[o].head + 1u) % B;
            t->la[o].cnt--;
            tl_queue(c, o, act);
        }
    if (c->last_setup & (1u << SETUP_QUAD_BIT))
        tl_next_quad(c, act);
    return (unsigned)(act - first);
}

static void core_prefetch(np_fdiff_core *c, const np_span *sp)
{
    /* The next span's set-up: from the next clock, and not inside a stall already allotted. */
    np_fdiff_timeline *t = &c->tl;
    uint64_t rel = c->ctx.now + 1u;
    if (t->clock > rel)
        rel = t->clock;
    else
        tl_run_until(c, rel);
    if (sp->n)
        tl_span_start(c, rel);
}

/* --- The engine (np_span.h) --- */

static void e_init(void *core, const void *cfg, const np_tex_regs *r) { np_fdiff_core_init(core, cfg, r); }
static unsigned e_begin(void *core, const np_span *sp, np_span_counts *cnt) { return np_fdiff_core_begin(core, sp, cnt); }
static unsigned e_advance(void *core, np_span_counts *cnt) { return np_fdiff_core_advance(core, cnt); }
static void e_prefetch(void *core, const np_span *sp) { core_prefetch(core, sp); }
static void e_issue(const void *core, void *sig) { ((np_span_sig *)sig)->x = np_fdiff_core_x(core); }
static size_t e_datapath(const void *cfg, const np_tex_regs *r, np_op *ops, size_t max)
{
    return np_fdiff_datapath(cfg, r, ops, max);
}

const np_span_engine np_fdiff_engine = {
    .name = "fdiff",
    .core_size = sizeof(np_fdiff_core),
    .sig_size = sizeof(np_span_sig),
    .stages = np_span_colour_stages,
    .n_stages = NP_FDIFF_TAIL_STAGES,
    .init = e_init,
    .begin = e_begin,
    .advance = e_advance,
    .issue = e_issue,
    .seek = NULL, /* the forward differences are sequential */
    .datapath = e_datapath,
    .prefetch = e_prefetch,
};

static void probe_pixel(const void *pctx, const void *core, const void *sig, uint32_t k)
{
    const np_fdiff_probe *probe = pctx;
    const np_fdiff_core *c = core;
    if (probe->x)
        probe->x[k] = ((const np_span_sig *)sig)->x;
    for (unsigned o = 0; o < c->r->n_oct; o++)
        if (probe->noise[o])
            probe->noise[o][k] = c->oct[o].d[0];
    if (probe->setup)
        probe->setup[k] = (uint16_t)c->last_setup;
}

void np_fdiff_span(const np_fdiff_cfg *cfg, const np_tex_regs *r, const np_span *sp,
                   np_tex_pixel *out, np_span_counts *counts, const np_fdiff_probe *probe)
{
    np_fdiff_core c;
    np_span_sig sig;
    np_fdiff_core_init(&c, cfg, r);
    np_span_run(&np_fdiff_engine, &c, &sig, sp, out, counts, probe ? probe_pixel : NULL,
                probe);
}

/* --- Datapath declaration --- */

enum { SIDE_BITS = 2 * NP_TEX_XY_BITS, STALL_BITS = 16 };

size_t np_fdiff_datapath(const np_fdiff_cfg *cfg, const np_tex_regs *r, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    const unsigned no = r->n_oct, F = np_fdiff_frac(cfg), W = np_fdiff_width(cfg), K = cfg->resetup;
    const unsigned P = cfg->setup_mults, Lm = cfg->mult_lat, yw = np_fdiff_y_window(cfg);
    np_dp_op(&d, "T", NULL, NP_OP_REG, 1, np_tex_reg_bits(r), 0, 0, 0, 0);
    /*
     * SH (once per cell set-up, one octave at a time): the 8 corner hashes,
     * then a..h (the Appendix, exact): 16 subtractions of s9 Q2.6 values
     * (|h| <= 252/64 < 4; the header's s10 has a bit to spare).
     */
    unsigned lv = np_tex_dp_lattice(&d, "SH", 1, 0);
    np_dp_op(&d, "SH", NULL, NP_OP_ADD, 8, 9, 0, 0, 0, lv);
    np_dp_op(&d, "SH", NULL, NP_OP_ADD, 5, 9, 0, 0, 0, lv + 1u);
    np_dp_op(&d, "SH", "coef", NP_OP_ADD, 3, 9, 0, 9, 1, lv + 2u);
    np_dp_op(&d, "SH", NULL, NP_OP_REG, 1, 8u * 9u + 1u, 0, 0, 0, 0);
    /*
     * SU: the engine. Its widest products: s48 operands of the quadric
     * (M_q s, s.(M_q s)), and the level-4 a' x_j, of which only the window
     * np_tex_to_index reads (117 + I bits, "Y") is kept: one multiplier of
     * 48 x yw covers every product of the three schedules. A product
     * accumulator per multiplier and one rounding adder (the W bits it keeps
     * plus the round bit). The register file holds the levels' results:
     * uv u64, cross s73 (|fu dv + fv du| < 2^72), dudv s80 (du, dv in
     * [-2^39, 2^39): up to 2^78), p0..r2 (r2 = h dudv: s87, the widest), and
     * alpha..delta (window yw each); the multipliers' pipeline Lm deep.
     */
    /* The narrow operand: s48 coordinates, or a scene-sized quadric register when wider (k_bits <= 64). */
    const unsigned aw = np_tex_k_bits(r) > NP_TEX_S_BITS ? np_tex_k_bits(r) : NP_TEX_S_BITS;
    np_dp_op(&d, "SU", "Y", NP_OP_MUL, P, aw, yw, yw, 1, 0);
    np_dp_op(&d, "SU", NULL, NP_OP_ADD, P, yw, 0, 0, 0, 1);
    np_dp_op(&d, "SU", NULL, NP_OP_ADD, 1, W + 1u, 0, 0, 0, 2);
    np_dp_op(&d, "SU", "uv", NP_OP_REG, 0, 0, 0, 2u * NP_TEX_FC, 0, 0);
    np_dp_op(&d, "SU", "cross", NP_OP_REG, 0, 0, 0, 73, 1, 0);
    np_dp_op(&d, "SU", "dudv", NP_OP_REG, 0, 0, 0, 2u * NP_TEX_DU_BITS, 1, 0);
    np_dp_op(&d, "SU", "r2", NP_OP_REG, 0, 0, 0, 87, 1, 0);
    np_dp_op(&d, "SU", NULL, NP_OP_REG, 1,
             2u * NP_TEX_FC + 73u + 2u * NP_TEX_DU_BITS + 6u * 87u + 4u * yw + P * Lm * (aw + yw) + P * yw +
                 STALL_BITS + 1u,
             0, 0, 0, 0);
    /*
     * X, per pixel: per octave three DDA adders (u40), cell-change detection
     * (three 8-bit compares against the cell set up), three forward-difference
     * adders n += dn, dn += d2n, d2n += d3n (s(W), wrapping); the quadric's
     * two; with a re-set-up interval K, a step counter per octave and the
     * quadric and the s DDA (s48) the quadric's re-set-up starts from.
     */
    np_dp_op(&d, "X", "u", NP_OP_ADD, 3u * no, NP_TEX_U_BITS, 0, NP_TEX_U_BITS, 0, 0);
    np_dp_op(&d, "X", NULL, NP_OP_CMP, 3u * no, NP_TEX_CELL_BITS, 0, 0, 0, 1);
    np_dp_op(&d, "X", "N", NP_OP_ADD, 3u * no, W, 0, W, 1, 0);
    np_dp_op(&d, "X", "Q", NP_OP_ADD, 2, W, 0, W, 1, 0);
    np_dp_op(&d, "X", NULL, NP_OP_ADD, 1, NP_TEX_N_BITS, 0, 0, 0, 0);
    np_dp_op(&d, "X", NULL, NP_OP_CMP, 1, NP_TEX_N_BITS, 0, 0, 0, 1);
    unsigned kbits = 0;
    if (K) {
        kbits = NP_TEX_N_BITS;
        np_dp_op(&d, "X", NULL, NP_OP_ADD, no + 1u, kbits, 0, 0, 0, 0);
        np_dp_op(&d, "X", NULL, NP_OP_CMP, no + 1u, kbits, 0, 0, 0, 1);
        np_dp_op(&d, "X", NULL, NP_OP_ADD, 3, NP_TEX_S_BITS, 0, 0, 0, 0);
    }
    np_dp_op(&d, "X", NULL, NP_OP_REG, 1,
             no * (3u * (NP_TEX_U_BITS + NP_TEX_DU_BITS + NP_TEX_CELL_BITS) + 4u * W + kbits) + 3u * W +
                 (K ? 3u * (NP_TEX_S_BITS + NP_TEX_DS_BITS) + kbits : 0u) + 2u * NP_TEX_N_BITS + SIDE_BITS + 1u,
             0, 0, 0, 0);
    /*
     * The overlap (np_fdiff.h): per octave the crossing finder (R DDA adders
     * per axis running ahead, 3R cell compares, its u and the cell it holds),
     * B shadow sets of the four differences with their first pixel (u17), and
     * the compare of the stepping's pixel with the FIFO head's; with K the
     * quadric's one shadow; the descriptor buffer and the next span's set-up
     * (the quadric's three and each octave's four differences, its first
     * cell's finder state). The engine's arbiter: a priority compare per job.
     */
    const unsigned R = NP_FDIFF_FINDER_RATE, NB = NP_TEX_N_BITS;
    np_dp_op(&d, "X", NULL, NP_OP_ADD, 3u * R * no, NP_TEX_U_BITS, 0, 0, 0, 0);
    np_dp_op(&d, "X", NULL, NP_OP_CMP, 3u * R * no, NP_TEX_CELL_BITS, 0, 0, 0, 1);
    np_dp_op(&d, "X", NULL, NP_OP_CMP, no, NB, 0, 0, 0, 0);
    np_dp_op(&d, "SU", NULL, NP_OP_CMP, NP_FDIFF_SHADOWS * no + 2u + no, NB, 0, 0, 0, 0);
    np_dp_op(&d, "X", NULL, NP_OP_REG, 1,
             no * (3u * (NP_TEX_U_BITS + NP_TEX_CELL_BITS) + NB + NP_FDIFF_SHADOWS * (4u * W + NB)) + (K ? 3u * W : 0u) +
                 3u * (NP_TEX_S_BITS + NP_TEX_DS_BITS) + NP_TEX_N_BITS + SIDE_BITS + 3u * W + no * 4u * W,
             0, 0, 0, 0);
    /* C1: x = Q + sum n_i (an adder tree, mod 2^W) ahead of the split, in the same clock. */
    lv = np_dp_add_tree(&d, "C1", "x", no + 1u, W, 1, 0);
    np_tex_dp_colour(&d, r, F, W, cfg->w_frac, lv, SIDE_BITS);
    return d.n;
}

size_t np_fdiff_carry_datapath(const np_fdiff_cfg *cfg, const np_tex_regs *r, unsigned macs, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    const unsigned no = r->n_oct, yw = np_fdiff_y_window(cfg);
    const unsigned wl = yw - 2u * NP_TEX_FC, wq = yw - NP_TEX_FC, wc = yw; /* a'U, a'UV.., a'UVW windows */
    const unsigned bits = 3u * 2u * wl + 3u * 3u * wq + 4u * wc;
    /*
     * The carrier runs ahead of the stepping (it must reach a crossing before
     * the stepping does, as today's crossing finder): NP_FDIFF_CARRY_RATE
     * pixels per clock, each step a layer of the 12 adders.
     */
    const unsigned R = NP_FDIFF_CARRY_RATE;
    np_dp_op(&d, "CA", NULL, NP_OP_ADD, R * 3u * no, wl, 0, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_ADD, R * 6u * no, wq, 0, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_ADD, R * 3u * no, wc, 0, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_MUX, 3u * no, wl, 2, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_MUX, 6u * no, wq, 3, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_MUX, 3u * no, wc, 4, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_NEG, 3u * no, wl, 0, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_NEG, 6u * no, wq, 0, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_NEG, 3u * no, wc, 0, 0, 0, 0);
    np_dp_op(&d, "CA", NULL, NP_OP_REG, 1, no * bits, 0, 0, 0, 0);
    np_dp_op(&d, "CM", NULL, NP_OP_MUL, macs, 10, wc, 0, 0, 0);
    np_dp_op(&d, "CM", NULL, NP_OP_ADD, macs, wc, 0, 0, 0, 1);
    np_dp_op(&d, "CM", NULL, NP_OP_MUX, macs, wc, NP_FDIFF_CARRY_PRODUCTS, 0, 0, 0);
    np_dp_op(&d, "CM", NULL, NP_OP_REG, 1, macs * bits, 0, 0, 0, 0);
    return d.n;
}

void np_fdiff_trace_core(const np_fdiff_core *c, np_trace *t, size_t n)
{
    for (unsigned o = 0; o < c->r->n_oct; o++) {
        for (unsigned a = 0; a < 3; a++)
            np_tex_trace(t, n, "u", (int64_t)c->oct[o].u[a]);
        for (unsigned j = 0; j < 4; j++)
            np_tex_trace128(t, n, "N", c->oct[o].d[j]);
    }
    for (unsigned j = 0; j < 3; j++)
        np_tex_trace128(t, n, "Q", c->q[j]);
    np_tex_trace128(t, n, "x", np_fdiff_core_x(c));
}

void np_fdiff_trace_setup(const np_fdiff_cfg *cfg, const np_fdiff_setup_sig *sig, np_trace *t, size_t n)
{
    for (unsigned i = 0; i < 8; i++)
        np_tex_trace(t, n, "coef", sig->coef[i]);
    np_tex_trace128(t, n, "uv", sig->uv);
    np_tex_trace128(t, n, "cross", sig->cross);
    np_tex_trace128(t, n, "dudv", sig->dudv);
    np_tex_trace128(t, n, "r2", sig->r[2]);
    for (unsigned j = 0; j < 4; j++)
        np_tex_trace128(t, n, "Y", np_wrap_s128(sig->y[j], np_fdiff_y_window(cfg)));
}
