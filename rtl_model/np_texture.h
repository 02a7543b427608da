/* SPDX-License-Identifier: MIT */
/*
 * np_texture.h - what the two scanline texturing units share: the texture
 * registers, the span descriptor they read, the span front end (octave
 * coordinates), the lattice values, the colour map stage and the set-up
 * cycle cost. The units are
 *
 *   np_fdiff   forward differences per cell and scanline (Kameya & Hart,
 *              "Bresenham Noise", shared/seeds/000): three additions per
 *              pixel and octave, a set-up on each cell change;
 *   np_texel   the same texture evaluated per pixel by a pipeline.
 *
 * Both compute the seed's texture model (equations 1 and 2)
 *
 *   f(s) = q(s) + sum_i a_i n(T_i(s)),   colour = c(f),
 *   q(s) = A s^2 + 2B st + 2C sr + 2D s + E t^2 + 2F tr + 2G t + H r^2 + 2I r + J,
 *   T_i(s) = M_i s + o_i  (a 3x3 matrix and an offset per octave),
 *   n     = trilinear lattice value noise, lattice values from np_hash6,
 *
 * for the pixels of a span, in the same fixed-point formats, so that they
 * differ only where their algorithms differ.
 *
 * --- Colour index ---
 * The colour map c is a table of N RGB entries (u8 each) with linear
 * interpolation between entries. The unit works directly in table units:
 * the host folds the map's scale S and origin f0 into the registers,
 *
 *   x(s) = S (f(s) - f0) = q'(s) + sum_i a'_i n(T_i(s)),
 *   q' = S q with J' = S (J - f0),   a'_i = S a_i,
 *
 * (S = N / period for a repeating map, (N - 1) / (f1 - f0) for a clamped
 * one), so the datapath never multiplies by S. x is carried as
 *
 *   x      s(W) QI.F   W = 1 + I + F; I (index integer bits) and F (index
 *                      fraction bits) are unit configuration. Every adder
 *                      of x wraps modulo 2^W. A repeating map needs only
 *                      x mod N (N a power of two <= 2^I), which wrapping
 *                      keeps; a clamped map needs |x| < 2^I (the host
 *                      checks the scene's range).
 *
 * --- Registers (formats) ---
 *   k[10]    s48 Q23.24   A'..J' (folded quadric coefficients, order A B C D E F G H I J)
 *   m[3][3]  s24 Q7.16    octave transform matrix, |m| < 128
 * (the default formats; a texture compiled for a scene may size the quadric
 * and the transform: k in s(k_bits) Q(k_bits-1-k_frac).k_frac, k_frac <= 48,
 * k_bits <= 64, and m in s(m_bits) Q(m_bits-1-m_frac).m_frac, m_frac <= 40,
 * m_bits <= 48, |m| < 128 - np_tex_regs.k_bits / m_bits, 0 for the defaults)
 *   o[3]     s48 Q15.32   octave transform offset
 *   amp      s32 Q17.14   octave amplitude a'_i
 *   cmap     N x 3 u8     colour entries, 2 <= N <= 256 (repeat: N a power of two)
 *
 * --- Span descriptor (one per span: a run of pixels on one scanline) ---
 *   y        u16          scanline
 *   x0       u16          first pixel
 *   n        u17          pixels, 0..65536 (0: an empty span, consumed with no work)
 *   s,t,r    s48 Q15.32   texture coordinate at the centre of pixel x0
 *   ds,dt,dr s41 Q8.32    its change per pixel (seed, equation 13)
 * Pixel k of the span (0 <= k < n) is at x0 + k with coordinate s + k ds
 * (equation 14), exact in Q15.32 (the host keeps it within s48).
 *
 * --- Span front end (both units, bit-identical) ---
 * Octave i's lattice coordinates along the span are linear in k too:
 *   u0 = round(M s + o)  u40 Q8.32   wrapped mod 256: the lattice tiles every
 *                                    256 (np_hash6 takes u8 coordinates)
 *   du = round(M ds)     s40 Q7.32   wrapped to [-128, 128): a step of du + 256j
 *                                    visits the same lattice points (period 256)
 * computed exactly at 48 fraction bits and rounded once
 * (np_shr_round_half_up): |u0 - exact| <= 2^-33 and |du - exact| <= 2^-33.
 * Pixel k's coordinate is u_k = u0 + k du mod 256 (a DDA, exact); its cell
 * (i, j, k) is the integer part (u8 per axis), its fraction the low 32 bits:
 *
 *    39        32 31                              0
 *   +-----------+---------------------------------+
 *   | cell  u8  |        fraction  u32 Q0.32      |   u40 Q8.32
 *   +-----------+---------------------------------+
 *   (np_tex_cell, np_tex_frac: positions from NP_TEX_FC and NP_TEX_CELL_BITS)
 *
 * --- Lattice values ---
 * n_c = np_hash6(corner) / 64, u6 Q0.6 in [0, 63/64]. The 64 hash values are
 * not equally likely over the 2^24 lattice points of the tile; the measured
 * distribution is in docs/fdiff.md (testbench/test_fdiff.c, case
 * lattice_distribution, measures it).
 */
#ifndef NP_TEXTURE_H
#define NP_TEXTURE_H

#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_hash.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_TEX_FC = 32,             /* fraction bits of coordinates and derivatives */
    NP_TEX_S_BITS = 48,         /* s, t, r: s48 Q15.32 */
    NP_TEX_DS_BITS = 41,        /* ds, dt, dr: s41 Q8.32 */
    NP_TEX_U_BITS = 40,         /* octave coordinate: u40 Q8.32 */
    NP_TEX_DU_BITS = 40,        /* octave derivative: s40 Q7.32 */
    NP_TEX_CELL_BITS = 8,       /* lattice tile of 256 */
    NP_TEX_M_BITS = 24, NP_TEX_M_FRAC = 16,   /* s24 Q7.16 */
    NP_TEX_O_BITS = 48,                       /* s48 Q15.32 */
    NP_TEX_K_BITS = 48, NP_TEX_K_FRAC = 24,   /* s48 Q23.24 */
    NP_TEX_AMP_BITS = 32, NP_TEX_AMP_FRAC = 14, /* s32 Q17.14 */
    NP_TEX_LAT_FRAC = 6,        /* lattice value u6 Q0.6 */
    NP_TEX_MAX_OCTAVES = 8,
    NP_TEX_CMAP_MAX = 256,
    NP_TEX_SPAN_MAX = 65536,    /* n: u17 */
    NP_TEX_N_BITS = 17,
    NP_TEX_XY_BITS = 16,
    /* Fraction bits of the exact quadric value: two coordinates and a coefficient. */
    NP_TEX_Q_EXACT_FRAC = 2 * NP_TEX_FC + NP_TEX_K_FRAC, /* 88 */
    NP_TEX_IDX_INT_MIN = 1, NP_TEX_IDX_INT_MAX = 16,
    /* Scene-sized register formats (np_tex_regs.m_bits, k_bits): the widest the units take. */
    NP_TEX_M_FRAC_MAX = 40, NP_TEX_M_BITS_MAX = 48, NP_TEX_M_INT_MAX = 7,
    NP_TEX_K_FRAC_MAX = 48, NP_TEX_K_BITS_MAX = 64,
    NP_TEX_W_FRAC_MIN = 1, NP_TEX_W_FRAC_MAX = 24
};

typedef struct np_tex_octave {
    int64_t m[3][3]; /* s24 Q7.16 (or the scene-sized s(m_bits) Q.m_frac) */
    int64_t o[3];    /* s48 Q15.32 */
    int32_t amp;     /* s32 Q17.14 */
} np_tex_octave;

typedef struct np_tex_regs {
    int64_t k[10];                 /* s48 Q23.24 (or s(k_bits) Q.k_frac): A' B' C' D' E' F' G' H' I' J' */
    unsigned n_oct;                /* 0..NP_TEX_MAX_OCTAVES */
    np_tex_octave oct[NP_TEX_MAX_OCTAVES];
    unsigned cmap_n;               /* N, 2..256 */
    int cmap_repeat;               /* 1: x wraps mod N (N a power of two); 0: clamp to [0, N-1] */
    uint8_t cmap[NP_TEX_CMAP_MAX][3];
    /*
     * Register formats sized by a scene (np_texreg_size, issue 10): 0 in
     * k_bits (m_bits) selects the default s48 Q23.24 (s24 Q7.16) and the
     * fraction field is then ignored. Read them through the accessors.
     */
    unsigned k_frac, k_bits, m_frac, m_bits;
} np_tex_regs;

static inline unsigned np_tex_k_frac(const np_tex_regs *r) { return r->k_bits ? r->k_frac : (unsigned)NP_TEX_K_FRAC; }
static inline unsigned np_tex_k_bits(const np_tex_regs *r) { return r->k_bits ? r->k_bits : (unsigned)NP_TEX_K_BITS; }
static inline unsigned np_tex_m_frac(const np_tex_regs *r) { return r->m_bits ? r->m_frac : (unsigned)NP_TEX_M_FRAC; }
static inline unsigned np_tex_m_bits(const np_tex_regs *r) { return r->m_bits ? r->m_bits : (unsigned)NP_TEX_M_BITS; }
/* Fraction bits of the exact quadric value (np_tex_quadric_exact): 2 x 32 + k_frac (88 by default). */
static inline unsigned np_tex_q_frac(const np_tex_regs *r) { return 2u * NP_TEX_FC + np_tex_k_frac(r); }

/* NULL when the registers are consistent, else a static message. */
const char *np_tex_regs_check(const np_tex_regs *r);

/* Is every octave transform diagonal? (The span set-up then needs 6 products per octave, not 18.) */
int np_tex_regs_diagonal(const np_tex_regs *r);

typedef struct np_span {
    uint16_t y, x0;
    uint32_t n;      /* u17: 0..65536 */
    int64_t s[3];    /* s48 Q15.32 */
    int64_t ds[3];   /* s41 Q8.32 */
} np_span;

/* NULL when every field is within its width (and x0 + n <= 65536), else a static message. */
const char *np_span_check(const np_span *sp);

/* One output pixel. */
typedef struct np_tex_pixel {
    uint16_t x, y;
    uint8_t rgb[3];
} np_tex_pixel;

/* Octave coordinates along a span (front end). */
typedef struct np_tex_oct_span {
    uint64_t u[3];  /* u40 Q8.32 at pixel 0 */
    int64_t du[3];  /* s40 Q7.32 */
} np_tex_oct_span;

/* Span front end for octave i: u0 and du as specified above. */
void np_tex_octave_span(const np_tex_regs *r, unsigned i, const int64_t s[3], const int64_t ds[3],
                        np_tex_oct_span *o);

/* One DDA step of an octave coordinate: (u + du) mod 256, u40 Q8.32. */
static inline uint64_t np_tex_dda(uint64_t u, int64_t du)
{
    return np_trunc_u(u + (uint64_t)du, NP_TEX_U_BITS);
}

/* Cell (u8) and fraction (u32 Q0.32) of an octave coordinate. */
static inline uint8_t np_tex_cell(uint64_t u) { return (uint8_t)((u >> NP_TEX_FC) & NP_MASK(NP_TEX_CELL_BITS)); }
static inline uint32_t np_tex_frac(uint64_t u) { return (uint32_t)(u & NP_MASK(NP_TEX_FC)); }

/* Lattice values of the 8 corners of cell (i, j, k), corner c = 4cz + 2cy + cx, u6 Q0.6 (hash). */
void np_tex_lattice(uint8_t i, uint8_t j, uint8_t k, uint8_t n[8]);

/*
 * The quadric's value and forward differences along the span, exact modulo
 * 2^128 at np_tex_q_frac(r) fraction bits (NP_TEX_Q_EXACT_FRAC, 88, with the
 * default s48 Q23.24 registers):
 *   q[0] = q'(s), q[1] = q'(s + ds) - q'(s), q[2] = 2 ds^T M_q ds (constant).
 * (Both units call this; the per-pixel unit with ds = 0 for q[0] only.)
 */
void np_tex_quadric_exact(const np_tex_regs *r, const int64_t s[3], const int64_t ds[3],
                          np_s128 q[3]);

/*
 * Bring an exact value v (modulo 2^128, vfrac fraction bits) to an index
 * accumulator s(W) QI.F: round once to F bits (np_round_wrap128) when
 * vfrac >= F, else shift left (exact); wrap to W bits. Precondition:
 * vfrac - F + W <= 128.
 */
static inline np_s128 np_tex_to_index(np_s128 v, unsigned vfrac, unsigned F, unsigned W)
{
    if (vfrac >= F)
        return np_round_wrap128((np_u128)v, vfrac - F, W);
    return np_wrap_s128(np_shl128(v, F - vfrac), W);
}

/* --- Colour map stage (three pipeline steps, the same in both units) --- */

/*
 * C1, split: segment seg (u8) and weight w (u(Fw+1) Q1.Fw, 0..2^Fw) of the
 * index x (s(W) QI.F). Repeat: seg = floor(x) mod N, w = round(frac(x)) to
 * Fw bits (np_shr_round_half_up_u; may round up to 1.0). Clamp: x < 0 gives
 * (0, 0), x >= N - 1 gives (N - 2, 1.0), otherwise as repeat without the
 * wrap. Error of w against the exact fraction: <= 2^-(Fw+1).
 */
void np_tex_colour_split(const np_tex_regs *r, np_s128 x, unsigned F, unsigned fw, unsigned *seg,
                         uint32_t *w);
/*
 * C2 + C3: per channel, c = c[seg] 2^Fw + w (c[seg+1] - c[seg]) (exact,
 * s(10+Fw)), then rounded to 8 bits (np_shr_round_half_up). The result is a
 * rounded convex combination: it stays within [0, 255] without saturation.
 * Error against the exact interpolation at weight w: <= 1/2 LSB.
 */
void np_tex_colour_mix(const np_tex_regs *r, unsigned seg, uint32_t w, unsigned fw, int64_t prod[3]);
void np_tex_colour_round(const int64_t prod[3], unsigned fw, uint8_t rgb[3]);
/* All three. */
void np_tex_colour(const np_tex_regs *r, np_s128 x, unsigned F, unsigned fw, uint8_t rgb[3]);

/* Largest |c[k+1] - c[k]| over the map's segments (LSB per index unit): the colour's Lipschitz constant. */
unsigned np_tex_colour_slope(const np_tex_regs *r);

/* --- Set-up cost --- */

/*
 * A set-up datapath is a shared engine of P pipelined multipliers of
 * latency Lm (unit configuration). Its schedule is a list of dependency
 * levels: the products of one level issue P per clock, a level starts when
 * the previous level's last product is out. Cycles = fixed + sum over levels
 * of (ceil(products / P) + Lm - 1).
 */
typedef struct np_tex_sched {
    const char *name;
    unsigned fixed;      /* non-multiplier cycles (lookup, adders, round and load) */
    unsigned levels;
    unsigned mults[6];
} np_tex_sched;

unsigned np_tex_sched_cycles(const np_tex_sched *s, unsigned P, unsigned Lm);
unsigned np_tex_sched_products(const np_tex_sched *s);

/* The span front end's schedule for one octave (18 products, or 6 with a diagonal transform). */
extern const np_tex_sched np_tex_sched_octave, np_tex_sched_octave_diag;

/* --- Datapath declaration pieces (np_datapath.h) shared by both units --- */

/* Bits of a colour segment index (values 0 .. N - 1). */
unsigned np_tex_seg_bits(const np_tex_regs *r);
/* Bits of the texture registers: quadric, each octave's M, o and a', the colour table. */
unsigned np_tex_reg_bits(const np_tex_regs *r);
/*
 * The bits of an exact value v (vfrac fraction bits, modulo 2^128) that
 * np_tex_to_index(v, vfrac, F, W) reads: the low vfrac - F + W, so a
 * datapath may hold v modulo 2^window (a narrower multiplier or adder).
 */
static inline unsigned np_tex_window(unsigned vfrac, unsigned F, unsigned W) { return vfrac + W - F; }
/*
 * Lattice hashers for lanes cells (8 corners each, np_tex_lattice): cell + 1
 * incrementers, 64 pattern lookups and an adder tree per corner; signal "n"
 * (u6). From level0; returns the next free level.
 */
unsigned np_tex_dp_lattice(np_dp *d, const char *stage, unsigned lanes, unsigned level0);
/*
 * The colour stages C1 C2 C3 for registers r (table size and mode), index
 * s(W) QI.F and weight bits fw; C1's logic starts at level c1_level0 (the
 * forward-difference unit sums x in front of it in the same clock); side =
 * bits carried along each stage besides the valid bit (pixel x, y).
 * Signals: seg, cw, cd (c1 - c0), mix (w (c1 - c0)), prod, rgb.
 */
void np_tex_dp_colour(np_dp *d, const np_tex_regs *r, unsigned F, unsigned W, unsigned fw, unsigned c1_level0,
                      unsigned side);
/* Trace one named signal (np_datapath.h): a 64-bit value, or a 128-bit one by its width. */
void np_tex_trace(np_trace *t, size_t n, const char *name, int64_t v);
void np_tex_trace128(np_trace *t, size_t n, const char *name, np_s128 v);
/* Trace the colour stages' signals for one pixel (seg, w from C1; prod from C2; rgb from C3). */
void np_tex_trace_colour(const np_tex_regs *r, unsigned seg, uint32_t w, const int64_t prod[3],
                         const uint8_t rgb[3], unsigned fw, np_trace *t, size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_TEXTURE_H */
