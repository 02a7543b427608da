/* SPDX-License-Identifier: MIT */
/*
 * np_fdiff.h - the forward-difference scanline texturing unit of Kameya &
 * Hart, "Bresenham Noise" (shared/seeds/000), bit-exact and cycle-accurate.
 * Texture registers, span descriptor, front end and colour map: np_texture.h.
 *
 * Along a span, trilinear value noise in one cell is a cubic in the pixel
 * step k (seed, equation 15): n(k) = alpha k^3 + beta k^2 + gamma k + delta.
 * The unit sets up its forward differences once per cell and per span and
 * then needs three additions per pixel and octave (equation 22):
 *
 *      n += dn;  dn += d2n;  d2n += d3n   (d3n = 6 alpha, constant)
 *
 * The quadric q'(s) is a quadratic in k along the span and is forward-
 * differenced the same way (two additions per pixel). Per pixel:
 *
 *   x = Q + sum_i N_i   (mod 2^W),  colour = C(x)   (np_texture.h)
 *
 * --- Signals and formats (I, F, W = 1 + I + F from the configuration) ---
 *   u, du      u40 Q8.32 / s40 Q7.32  octave coordinate and its step (front end);
 *                                     u advances by a DDA adder every pixel
 *                                     (exact), so a cell crossing is detected
 *                                     exactly: the integer part (u8) changes.
 *   n_c        u6 Q0.6      corner lattice values (np_tex_lattice)
 *   a..h       s10 Q3.6     the seed's trilinear coefficients (Appendix), exact:
 *                           |a| <= 63/64, |b|,|c|,|d| <= 63/64, |e|,|f|,|g| <= 126/64,
 *                           |h| <= 252/64
 *   alpha..delta            exact, 102 fraction bits (3 coordinates of 32 bits
 *                           and a coefficient of 6), held modulo 2^128
 *   Y_j        exact differences times the amplitude (Q17.14): 116 fraction
 *              bits, modulo 2^128 (NP_FDIFF_EXACT_FRAC)
 *   N_i[0..3]  s(W) QI.F    n, dn, d2n, d3n of octave i: Y_j rounded once to F
 *                           bits (np_round_wrap128), wrapping modulo 2^W
 *   Q[0..2]    s(W) QI.F    q', dq', d2q' (np_tex_quadric_exact rounded once)
 *   x          s(W) QI.F    colour index
 * Modulo 2^W is enough: every accumulator update is an addition, and the
 * integers modulo 2^W are a ring, so the recurrences give the true sums
 * modulo 2^W; only x mod N (repeat) or |x| < 2^I (clamp) is needed.
 *
 * --- Set-up (a shared engine of P multipliers of latency Lm) ---
 * Per octave and cell, with (fu, fv, fw) the fractions at the set-up pixel
 * and U = fu + k du etc., the seed's equation 12 is regrouped as
 *   n = P(U, V) + W R(U, V),  P = a + bU + cV + eUV,  R = d + fV + gU + hUV,
 * so that   level 1: uv, u dv, v du, du dv          (4 products)
 *           level 2: the coefficients of P and R    (14 products by a..h)
 *           level 3: W R                            (6 products)
 *           level 4: the amplitude                  (4 products)
 * give delta = p0 + fw r0, gamma = p1 + fw r1 + dw r0, beta = p2 + fw r2 +
 * dw r1, alpha = dw r2 (the Appendix's alpha..delta), and then (equation 21)
 *   n0 = delta, dn0 = alpha + beta + gamma, d2n0 = 6 alpha + 2 beta, d3n0 = 6 alpha.
 * Set-up happens at the first pixel of a span (with the span front end and
 * the quadric), when a pixel's cell differs from the cell set up (on any
 * axis, in any octave), and, when the re-set-up interval K is not 0, after
 * K steps without a set-up (per octave; the quadric after K steps too).
 * The set-up of a cell runs while the cell before it is stepped (double-
 * buffered differences, below the core's state): the bits are those of a
 * set-up at the cell's first pixel; only the timing differs.
 *
 * --- Error (argument; test_fdiff measures every term) ---
 * Additions are exact, so after k steps from a set-up the accumulated error
 * of n is exactly  e0 + k e1 + C(k,2) e2 + C(k,3) e3,  where e_j = N_j - Y_j
 * are the set-up rounding residuals, |e_j| <= 2^-(F+1). Growth per order:
 *   order 0: 2^-(F+1)           order 1: 2^-(F+1) k
 *   order 2: 2^-(F+1) k(k-1)/2  order 3: 2^-(F+1) k(k-1)(k-2)/6
 * and for the quadric (orders 0..2) likewise. With m the most steps between
 * set-ups (a cell's length in pixels, a span's for the quadric, or K), the
 * index error is at most 2^-(F+1) (n_oct B3(m) + B2(m)), B3 = 1 + m + C(m,2)
 * + C(m,3), B2 = 1 + m + C(m,2) (np_fdiff_drift_bound_noise, _quad). The colour error
 * against the exact texture at the unit's own coordinates is then at most
 * 1/2 + slope (index error + 2^-(Fw+1)) LSB (slope: np_tex_colour_slope).
 * The float reference differs further by the register and front-end
 * roundings (quantified in docs/fdiff.md).
 */
#ifndef NP_FDIFF_H
#define NP_FDIFF_H

#include <stdint.h>

#include "np_datapath.h"
#include "np_fdiff_carry.h"
#include "np_fixed.h"
#include "np_pipe.h"
#include "np_span.h"
#include "np_texture.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_FDIFF_EXACT_FRAC = 3 * NP_TEX_FC + NP_TEX_LAT_FRAC + NP_TEX_AMP_FRAC, /* 116 */
    NP_FDIFF_GUARD_MAX = 100,
    NP_FDIFF_MULTS_MAX = 64,
    NP_FDIFF_LAT_MAX = 16,
    NP_FDIFF_TAIL_STAGES = NP_SPAN_COLOUR_STAGES /* colour map: C1 split, C2 mix, C3 round */
};

typedef struct np_fdiff_cfg {
    unsigned idx_int;     /* I: index integer bits, 1..11 (default 10) */
    unsigned w_frac;      /* Fw: colour weight fraction bits, 1..24 (default 12) */
    unsigned guard;       /* G: index fraction bits F = Fw + G (default: np_fdiff_cfg_default) */
    unsigned resetup;     /* K: re-set-up after K steps without one; 0 = off (default) */
    unsigned setup_mults; /* P: multipliers of the set-up engine, 1..64 (default 2) */
    unsigned mult_lat;    /* Lm: their pipeline latency in clocks, 1..16 (default 2) */
    /*
     * The cell set-up: 0 the multiplier set-up (default), 1 the carried one
     * (np_fdiff_carry.h: the monomials carried by additions, a crossing set
     * up by the products of a..h). The bits are the same; the cycle model's
     * timing and the datapath declaration are still the multiplier set-up's.
     */
    unsigned carry;
} np_fdiff_cfg;

np_fdiff_cfg np_fdiff_cfg_default(void);
/* NULL when valid, else a static message naming the field. */
const char *np_fdiff_cfg_check(const np_fdiff_cfg *cfg);
static inline unsigned np_fdiff_frac(const np_fdiff_cfg *c) { return c->w_frac + c->guard; }
static inline unsigned np_fdiff_width(const np_fdiff_cfg *c) { return 1u + c->idx_int + np_fdiff_frac(c); }

/* Set-up schedules (np_tex_sched): one noise cell; the quadric. */
extern const np_tex_sched np_fdiff_sched_cell, np_fdiff_sched_quad;

/* Worst-case drift after m steps, in index units: 2^-(F+1) B3(m) for a noise octave (order <= 3). */
double np_fdiff_drift_bound_noise(unsigned F, uint64_t m);
/* The same for the quadric (order <= 2). */
double np_fdiff_drift_bound_quad(unsigned F, uint64_t m);

/*
 * Set-up datapath of one octave's cell at coordinate u (u40 Q8.32, the cell
 * is its integer part) with step du: the four differences d[0..3] (s(W)
 * QI.F). If exact is not NULL it receives Y_0..Y_3 (116 fraction bits,
 * modulo 2^128), for the error analysis.
 */
void np_fdiff_cell_setup(const np_fdiff_cfg *cfg, const np_tex_regs *r, unsigned oct,
                         const uint64_t u[3], const int64_t du[3], np_s128 d[4], np_s128 exact[4]);

/* The set-up's intermediate signals (for the width check; formats in np_fdiff_datapath). */
typedef struct np_fdiff_setup_sig {
    int64_t coef[8];    /* a..h, Q2.6 */
    np_s128 uv, cross, dudv; /* level 1: fu fv, fu dv + fv du, du dv (Q.64) */
    np_s128 p[3], r[3]; /* level 2 (Q.70) */
    np_s128 y[4];       /* level 4: a' times n0, dn0, d2n0, d3n0 (Q.116, modulo 2^128) */
} np_fdiff_setup_sig;

/* np_fdiff_cell_setup, also returning its intermediate signals in sig. */
void np_fdiff_cell_setup_sig(const np_fdiff_cfg *cfg, const np_tex_regs *r, unsigned oct, const uint64_t u[3],
                             const int64_t du[3], np_s128 d[4], np_fdiff_setup_sig *sig);

/* Quadric set-up at coordinate s with step ds: q[0..2] (s(W) QI.F); exact (88 fraction bits) if not NULL. */
void np_fdiff_quad_setup(const np_fdiff_cfg *cfg, const np_tex_regs *r, const int64_t s[3],
                         const int64_t ds[3], np_s128 q[3], np_s128 exact[3]);

/*
 * Analysis (not hardware): the exact a'_i n at step k from a set-up at u with
 * step du, as the trilinear polynomial of that cell (116 fraction bits,
 * modulo 2^128). Equals the cubic the set-up expands, for every k.
 */
np_s128 np_fdiff_noise_exact(const np_tex_regs *r, unsigned oct, const uint64_t u[3],
                             const int64_t du[3], int64_t k);

/* Optional per-pixel observation of the bit-exact model (any pointer may be NULL). */
typedef struct np_fdiff_probe {
    np_s128 *x;                          /* index x per pixel */
    np_s128 *noise[NP_TEX_MAX_OCTAVES];  /* octave accumulator N_i[0] per pixel */
    uint16_t *setup;                     /* per pixel: bit i = octave i set up there, bit 8 = the quadric */
} np_fdiff_probe;

/*
 * The bit-exact model for one span: out[0..n) receives the pixels, counts
 * (may be NULL) is incremented. Preconditions: np_fdiff_cfg_check,
 * np_tex_regs_check and np_span_check pass.
 */
void np_fdiff_span(const np_fdiff_cfg *cfg, const np_tex_regs *r, const np_span *sp,
                   np_tex_pixel *out, np_span_counts *counts, const np_fdiff_probe *probe);

/* --- The engine (np_span.h): the core and its colour pipeline --- */

/*
 * The span sequencer of np_span.h runs this engine: np_span_run is the
 * bit-exact model above, np_span_sim the cycle-accurate one. Timing per span
 * (np_span.h): 1 clock to accept, the span set-up stall, then one pixel per
 * clock into the colour pipeline (NP_FDIFF_TAIL_STAGES deep) except for the
 * cell and interval set-up stalls.
 */
extern const np_span_engine np_fdiff_engine;

/*
 * --- Set-up overlapped with stepping (the timing of the cycle model) ---
 * The coefficient registers are buffered: every octave has its active
 * differences and B = NP_FDIFF_SHADOWS shadow sets (a FIFO; the quadric,
 * with K, one). While the core steps through a cell, the set-up engine
 * computes the next cells' differences into the shadows. Their first pixels
 * are known in advance from a per-octave crossing finder: a DDA that runs
 * ahead of the stepping R = NP_FDIFF_FINDER_RATE pixels per clock (u + du
 * .. u + R du: R u40 adders per axis, strides by shifts) from the span's
 * first pixel and holds at a cell start it found until a shadow set takes
 * it. At a cell's first pixel k_c the FIFO's head becomes active, in the
 * clock the pixel issues. Likewise a one-deep descriptor buffer: the next
 * span's set-up
 * (quadric, front end, first cells) runs while the current span steps.
 *
 * The engine: P multipliers (latency Lm) shared by the jobs in flight. A
 * job is a schedule's levels in order (np_tex_sched; a span's set-up is a
 * job for the quadric and one per octave for its front end then its first
 * cell, all released together); every clock the P multiplier slots go to the ready jobs in order
 * of need (the pixel a job is for; the next span's job last), so a job
 * alone takes exactly np_tex_sched_cycles. A cell's job is released when
 * the finder has found its first pixel and a shadow set is free. A pixel whose
 * set-up is not finished waits (the stall the model counts): a cell change
 * costs nothing when the cell before it is at least as long as the set-up
 * latency plus what higher-priority jobs take of the engine. The next
 * span's job starts no earlier than the clock it is read, nor during a
 * stall of the current span (the engine then serves the stalled set-up).
 */
enum {
    NP_FDIFF_SHADOWS = 4, /* shadow difference sets per octave (B): the engine may run B cells ahead */
    NP_FDIFF_FINDER_RATE = 4, /* pixels per clock of the crossing finder (R) */
    NP_FDIFF_JOB_QUAD = NP_TEX_MAX_OCTAVES * NP_FDIFF_SHADOWS,
    NP_FDIFF_JOB_SPAN,                                  /* the next span: its quadric, */
    NP_FDIFF_JOBS = NP_FDIFF_JOB_SPAN + 1 + NP_TEX_MAX_OCTAVES, /* then per octave front end and first cell */
    NP_FDIFF_PHASES_MAX = 16
};

typedef struct np_fdiff_job {
    uint8_t state;    /* 0 none, 1 in flight, 2 finished */
    uint8_t list;     /* its schedule: 0 cell, 1 quadric, 2 front end and cell */
    uint16_t cur;     /* current phase */
    uint32_t left;    /* products of the current level still to issue */
    uint32_t need;    /* the pixel it is for (priority) */
    uint64_t key;     /* priority: need; the next span's job last */
    uint64_t ready;   /* clock from which the current phase proceeds */
    uint64_t done;    /* finished: the first clock its values can be used */
} np_fdiff_job;

typedef struct np_fdiff_timeline {
    int16_t ph[3][NP_FDIFF_PHASES_MAX]; /* phases: > 0 a level of that many products, < 0 fixed clocks */
    unsigned nph[3];
    uint64_t clock;                     /* the engine has allotted every clock before this one */
    np_fdiff_job job[NP_FDIFF_JOBS];    /* per octave its next B cells (a ring), the quadric's next, the next span */
    struct {
        uint64_t u[3];                  /* the crossing finder: the coordinate at pixel k */
        uint8_t cell[3];
        uint32_t k;
        int end;                        /* no further set-up in this span */
        uint64_t t;                     /* the clock it is at pixel k */
        unsigned head, cnt;             /* the ring of queued cells (slots o B + i) */
    } la[NP_TEX_MAX_OCTAVES];
    uint32_t qk;                        /* the quadric's last set-up pixel */
} np_fdiff_timeline;

/* The core's state (the engine state of np_fdiff_engine). */
typedef struct np_fdiff_core {
    np_span_ctx ctx;     /* first (np_span.h) */
    const np_fdiff_cfg *cfg;
    const np_tex_regs *r;
    unsigned F, W;
    np_span sp;
    uint32_t k;          /* current pixel of the span */
    int64_t s[3];        /* its texture coordinate (DDA), for the quadric's re-set-up */
    np_s128 q[3];
    uint32_t qsteps;
    struct {
        uint64_t u[3];
        int64_t du[3];
        uint8_t cell[3];
        np_s128 d[4];
        uint32_t steps;
        np_fdiff_carry cm;  /* the carried monomials (cfg->carry) */
    } oct[NP_TEX_MAX_OCTAVES];
    unsigned last_setup; /* what was set up for pixel k: bit i = octave i, bit 8 = quadric */
    np_fdiff_timeline tl; /* the set-up engine's timing (not the bits) */
} np_fdiff_core;

/*
 * The core step by step (the engine's begin and advance): init once; begin
 * loads a span and returns the set-up clocks before its first pixel (0 for
 * an empty span); x is pixel k's colour index (Q + sum of the octaves' n, an
 * adder tree mod 2^W); advance steps to pixel k + 1 and returns the set-up
 * clocks it needs first (0: none, or the span ended). counts is incremented
 * (not NULL).
 */
void np_fdiff_core_init(np_fdiff_core *c, const np_fdiff_cfg *cfg, const np_tex_regs *r);
unsigned np_fdiff_core_begin(np_fdiff_core *c, const np_span *sp, np_span_counts *counts);
np_s128 np_fdiff_core_x(const np_fdiff_core *c);
unsigned np_fdiff_core_advance(np_fdiff_core *c, np_span_counts *counts);

/* --- Timing and datapath declaration (np_datapath.h) --- */

/* Set-up cycles of one cell, of the quadric, of a span (front end + quadric + every octave's first cell). */
unsigned np_fdiff_cell_cycles(const np_fdiff_cfg *cfg);
unsigned np_fdiff_quad_cycles(const np_fdiff_cfg *cfg);
unsigned np_fdiff_front_cycles(const np_fdiff_cfg *cfg, const np_tex_regs *r); /* per octave */
unsigned np_fdiff_span_setup_cycles(const np_fdiff_cfg *cfg, const np_tex_regs *r);
/* The span set-up's latency on an idle engine (its jobs in parallel on the P multipliers): <= the cycles above. */
unsigned np_fdiff_span_setup_latency(const np_fdiff_cfg *cfg, const np_tex_regs *r);

/* Bits of the exact set-up values the datapath keeps: what np_tex_to_index reads of Y_j (117 + I). */
static inline unsigned np_fdiff_y_window(const np_fdiff_cfg *c)
{
    return np_tex_window(NP_FDIFF_EXACT_FRAC, np_fdiff_frac(c), np_fdiff_width(c));
}

/*
 * The unit's datapath for cfg and registers r (octaves, colour table): the
 * texture registers "T"; the set-up datapath "SH" (lattice hash and the
 * coefficients a..h of one cell) and "SU" (the shared engine of P
 * multipliers, pipelined over Lm clocks, that runs the schedules
 * np_fdiff_sched_cell, np_fdiff_sched_quad and np_tex_sched_octave); the
 * per-pixel core "X" (DDAs, cell-change detection, three forward-difference
 * adders per octave, two for the quadric); the colour pipeline C1 C2 C3 (C1
 * also sums x = Q + sum n_i in the same clock). Writes up to max ops,
 * returns the full count.
 */
size_t np_fdiff_datapath(const np_fdiff_cfg *cfg, const np_tex_regs *r, np_op *ops, size_t max);
/*
 * What the carried set-up (np_fdiff_carry.h) adds, for the estimate of
 * docs/fdiff.md ("A multiplier-free set-up"); not yet part of
 * np_fdiff_datapath, whose SU stays the multiplier engine. "CA", per octave:
 * the carried values (1,741 bits by default: a'U mod 2^(yw-64), a'UV.. mod
 * 2^(yw-32), a'UVW mod 2^yw), their 12 stepping adders per pixel of
 * NP_FDIFF_CARRY_RATE, and the shift's
 * operand multiplexers and add/subtract control (one axis, |j| = 1, per
 * clock through the stepping adders). "CM": macs crossing MACs (an s10 x yw
 * multiplier, a yw-bit accumulator, a 20:1 operand multiplexer) each with a
 * snapshot of one octave's carried values. Writes up to max ops, returns the
 * full count.
 */
size_t np_fdiff_carry_datapath(const np_fdiff_cfg *cfg, const np_tex_regs *r, unsigned macs, np_op *ops, size_t max);
/*
 * Products by a..h of one carried cell set-up (20); the carrier's pixels per
 * clock in that estimate (2: it gains a pixel a clock on the stepping, so it
 * finds crossings ahead, as the crossing finder does today at 4).
 */
enum { NP_FDIFF_CARRY_PRODUCTS = 20, NP_FDIFF_CARRY_RATE = 2 };
/* Trace the per-pixel signals of the core at its current pixel (u, N, Q, x). */
void np_fdiff_trace_core(const np_fdiff_core *c, np_trace *t, size_t n);
/* Trace a cell set-up's signals (coef, uv, cross, dudv, r2, Y). */
void np_fdiff_trace_setup(const np_fdiff_cfg *cfg, const np_fdiff_setup_sig *sig, np_trace *t, size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_FDIFF_H */
