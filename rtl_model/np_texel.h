/* SPDX-License-Identifier: MIT */
/*
 * np_texel.h - the per-pixel scanline texturing unit: the texture of
 * np_texture.h evaluated at every pixel by a pipeline (lattice value noise,
 * trilinear), the comparison point for the forward-difference unit np_fdiff
 * (the seed's "pixel by pixel" computation, Kameya & Hart, Section 5).
 * Same registers, span descriptor, front end and colour map as np_fdiff.
 *
 * Per pixel k of a span: the front end's DDAs give the octave coordinates
 * u_k (u40 Q8.32) and the texture coordinate s_k (s48 Q15.32), exactly as in
 * np_fdiff. Then, per octave (all octaves in parallel):
 *
 *   n_c      u6 Q0.6        8 corner lattice values (np_tex_lattice)
 *   wu,wv,ww u(WT+1) Q1.WT  the fractions rounded to WT bits
 *                           (np_shr_round_half_up_u, may reach 1.0):
 *                           |w - fraction| <= 2^-(WT+1)
 *   l1[4]    Q.(6+WT)       l = n0 2^WT + wu (n1 - n0), along x, exact
 *   l2[2]    Q.(6+2WT)      along y, exact
 *   l3       Q.(6+3WT)      along z, exact; 0 <= l3 <= 63/64 (convex)
 *   N        s(W) QI.F      amp * l3 (Q.(20+3WT)) rounded once to F bits
 * and the quadric per pixel, exact at 88 fraction bits and rounded once to F
 * bits; x = Q + sum N (mod 2^W); colour as np_fdiff. The quadric is a
 * quadratic in k along the span, so the front end forward-differences it
 * exactly: its span set-up computes q'(s), its first and (constant) second
 * difference (np_tex_quadric_exact, Q.88 modulo 2^128) and every pixel adds
 * q += dq, dq += d2q (two adders of the window the rounding reads): exact
 * additions modulo 2^128 give q'(s + k ds) exactly, the same bits as
 * evaluating it per pixel, for two adders instead of 15 multipliers.
 * Only the noise is evaluated per pixel.
 *
 * Error against the exact texture at the unit's coordinates (argument):
 * the weights move each lerp by at most |n1 - n0| 2^-(WT+1) <= (63/64)
 * 2^-(WT+1) per axis, so |l3 - n| <= 3 (63/64) 2^-(WT+1); with the
 * amplitude and one rounding per octave and the quadric's:
 *   |x - exact| <= sum_i |a'_i| 3 (63/64) 2^-(WT+1) + (n_oct + 1) 2^-(F+1).
 * Nothing accumulates from pixel to pixel.
 *
 * Span set-up timing (np_texel_span_setup_cycles, front_begin, front_prefetch):
 * C = sched(np_texel_sched_quad) + n_oct sched(octave) clocks, the octave's
 * schedule of 6 products when every octave's M is diagonal
 * (np_tex_regs_diagonal), else 18 (wood at P = 2, Lm = 2: 21 + 5 = 26). The
 * front end's engine runs one span's set-up at a time. A span begun from idle
 * starts its job in the next clock (or when the engine frees) and stalls C
 * clocks; a descriptor taken into the buffer while a span waits or steps
 * starts its job then, in the next clock or when the engine frees, and begins
 * (in the clock the previous span's last pixel issues) with a stall of only
 * what remains of it. An empty span takes no job and no stall.
 * The texture coordinate s is stepped (s += ds) and carried to stage L for the
 * width trace only: no stage reads it (the quadric is forward-differenced).
 * At WT = 32 the weight is the fraction itself, u32 (the datapath's wb = 32).
 *
 * Pipeline (np_pipe, one pixel per clock, latency NP_TEXEL_STAGES):
 *   L  lattice hashes, weights (the quadric is an input)   I1 x-lerps
 *   I2 y-lerps   I3 z-lerp   A amplitude, rounding to F   S sum
 *   C1 C2 C3 colour map (np_texture.h)
 */
#ifndef NP_TEXEL_H
#define NP_TEXEL_H

#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_pipe.h"
#include "np_span.h"
#include "np_texture.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_TEXEL_STAGES = 9,
    NP_TEXEL_WT_MIN = 1,
    NP_TEXEL_WT_MAX = 32
};

typedef struct np_texel_cfg {
    unsigned idx_int;     /* I: index integer bits, 1..11 (default 10) */
    unsigned w_frac;      /* Fw: colour weight bits, 1..24 (default 12) */
    unsigned guard;       /* G: index fraction bits F = Fw + G (default 20) */
    unsigned weight_frac; /* WT: trilinear weight bits, 1..32 (default 16) */
    unsigned setup_mults; /* P, Lm: the span front end's engine (as np_fdiff) */
    unsigned mult_lat;
} np_texel_cfg;

np_texel_cfg np_texel_cfg_default(void);
const char *np_texel_cfg_check(const np_texel_cfg *cfg);
static inline unsigned np_texel_frac(const np_texel_cfg *c) { return c->w_frac + c->guard; }
static inline unsigned np_texel_width(const np_texel_cfg *c) { return 1u + c->idx_int + np_texel_frac(c); }

/* The guaranteed bound above, in index units, for registers r. */
double np_texel_error_bound_index(const np_texel_cfg *cfg, const np_tex_regs *r);

/* The signal bundle (formats above); x, seg, cw, prod and the colour in the head (np_span.h). */
typedef struct np_texel_sig {
    np_span_sig head;                   /* first (np_span.h); head.x: S, then C1 C2 C3 */
    uint64_t u[NP_TEX_MAX_OCTAVES][3];  /* input: octave coordinates */
    int64_t s[3];                       /* input: texture coordinate */
    uint8_t n[NP_TEX_MAX_OCTAVES][8];   /* L */
    uint32_t w[NP_TEX_MAX_OCTAVES][3];  /* L */
    np_s128 qin;                        /* input: the exact quadric from the front end, Q.88 */
    np_s128 qx;                         /* L: the same, registered */
    np_s128 l1[NP_TEX_MAX_OCTAVES][4];  /* I1 */
    np_s128 l2[NP_TEX_MAX_OCTAVES][2];  /* I2 */
    np_s128 l3[NP_TEX_MAX_OCTAVES];     /* I3 */
    np_s128 N[NP_TEX_MAX_OCTAVES];      /* A */
    np_s128 q;                          /* A */
} np_texel_sig;

/* The pipeline L I1 I2 I3 A S C1 C2 C3 (np_pipe stage functions; cfg is the np_span_ctx of the state). */
extern const np_stage_desc np_texel_stages[NP_TEXEL_STAGES];

/*
 * The engine's state: the span front end (np_texture.h), the DDAs that step
 * the octave coordinates u and the texture coordinate s along the span.
 */
typedef struct np_texel_front {
    np_span_ctx ctx;     /* first (np_span.h); ctx.cfg is the np_texel_cfg */
    np_span sp;
    uint32_t k;
    uint64_t u[NP_TEX_MAX_OCTAVES][3];
    int64_t du[NP_TEX_MAX_OCTAVES][3];
    int64_t s[3];
    np_s128 q, dq, d2q;  /* the quadric and its differences along the span, Q.88 mod 2^128 */
    uint64_t fe_free;    /* timing: the front end's engine is free from this clock */
    uint64_t fe_done;    /* a prefetched span's set-up finishes at this clock */
    int fetched;
} np_texel_front;

/*
 * The engine (np_span.h): the sequencer runs it as the bit-exact model
 * (np_span_run, np_texel_span) and as the cycle-accurate model (np_span_sim):
 * 1 clock to accept a descriptor, the front end's set-up stall, then one
 * pixel per clock into the nine stages. Like np_fdiff it has a one-deep
 * descriptor buffer: the next span's set-up runs on the front end's engine
 * (idle while a span steps) and begin waits only for what remains of it. Its seek places pixel k directly
 * (u0 + k du mod 256, s + k ds: the DDA's values, by a multiply).
 */
extern const np_span_engine np_texel_engine;

typedef struct np_texel_probe {
    np_s128 *x;
    np_s128 *noise[NP_TEX_MAX_OCTAVES]; /* N_i per pixel */
} np_texel_probe;

/* The bit-exact model for one span (preconditions as np_fdiff_span). */
void np_texel_span(const np_texel_cfg *cfg, const np_tex_regs *r, const np_span *sp,
                   np_tex_pixel *out, np_span_counts *counts, const np_texel_probe *probe);

/* The span set-up: the quadric's schedule and the front end's per octave on the engine (np_tex_sched). */
unsigned np_texel_span_setup_cycles(const np_texel_cfg *cfg, const np_tex_regs *r);
extern const np_tex_sched np_texel_sched_quad;

/* --- Datapath declaration (np_datapath.h) --- */

/*
 * The unit's datapath for cfg and registers r (octaves, colour table): the
 * texture registers "T"; the front end "FE" (the set-up engine of P
 * multipliers, pipelined over Lm clocks: the span set-up) and "D" (the
 * DDAs, one step per pixel); then the pipeline L I1 I2 I3 A S C1 C2 C3.
 * Writes up to max ops, returns the full count.
 */
size_t np_texel_datapath(const np_texel_cfg *cfg, const np_tex_regs *r, np_op *ops, size_t max);
/* Trace the declared signals of sig after pipeline stage k (0 = L .. 8 = C3). */
void np_texel_trace(const np_texel_cfg *cfg, const np_tex_regs *r, unsigned k, const np_texel_sig *sig,
                    np_trace *t, size_t n);
/* Widths of the windows the datapath keeps of the exact products (np_tex_window). */
static inline unsigned np_texel_q_window(const np_texel_cfg *c, const np_tex_regs *r)
{
    return np_tex_window(np_tex_q_frac(r), np_texel_frac(c), np_texel_width(c));
}
static inline unsigned np_texel_al_window(const np_texel_cfg *c)
{
    return np_tex_window(NP_TEX_LAT_FRAC + 3u * c->weight_frac + NP_TEX_AMP_FRAC, np_texel_frac(c), np_texel_width(c));
}

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_TEXEL_H */
