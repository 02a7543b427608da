/* SPDX-License-Identifier: MIT */
/*
 * np_simplex.h - the 3-D simplex noise unit of Perlin, "Noise Hardware"
 * (shared/seeds/002, "A better method" and Appendix B, the reference), with
 * the analytic derivative (f, df/dx, df/dy, df/dz) and the shared table-free
 * hash and multiply-free gradient (np_hash.h).
 *
 * This header is the bit-exact specification.
 *
 * FUNCTION (Appendix B, for the real point p = (x, y, z) = (X, Y, Z) / 256):
 *   skew:    (i, j, k) = floor(p + (x+y+z)/3)           the skewed cell
 *   unskew:  (u, v, w) = p - (i, j, k) + (i+j+k)/6        offset from corner 0
 *   simplex: corner 0 = (0,0,0), then +e_hi, +e_mid, +e_lo in the skewed cell,
 *            hi/lo ranked by Appendix B's rule (ties included, see rank below)
 *   corner c (skewed offset A, |A| = c): d_c = (u,v,w) - A + c/6
 *   f  = sum_c 8 t_c^4 (G_c . d_c),   t_c = 0.6 - |d_c|^2, a term is 0 if t_c <= 0
 *   df = sum_c (8 t_c^4 G_c - 64 t_c^3 (G_c . d_c) d_c)
 *   G_c = np_grad_decode(np_hash6((i + A_x) mod 256, (j + A_y) mod 256, (k + A_z) mod 256))
 *
 * EXACT FRONT END. Every decision (cell, simplex, kernel support) is made on
 * exact integers, so no rounding can flip one; the only error is in the
 * kernel powers, products and the output constant:
 *   SX = 4X + Y + Z            u19 = 768 x' exactly (x' = skewed x); SY, SZ alike
 *   i  = floor(SX / 768)       u9  in [0, 511] (= floor(floor(SX/256) / 3))
 *   U  = 6X - 1536 i + 256 n   s12, n = i + j + k; U = 1536 u exactly,
 *                              u in (-1/3, 5/6)
 *   D_c = U - 1536 A_x + 256 c s12, = 1536 d_x exactly; |d| <= 1 (the longest
 *                              simplex edge), so |D| <= 1536. Equivalently
 *                              D_c is d'_x = 3 d_x in s12 Q2.9.
 *   R2_c = |D_c|^2             u22 <= 1536^2, = 9 |d|^2 in u22 Q4.18
 *   T_c = max(0, 7077888 - 5 R2_c)    u23 Q0.23 holding tau = 45 t / 32,
 *                              exact; 7077888 = 27 * 2^18 is tau(0) = 0.84375.
 *                              T > 0 <=> t > 0, exactly.
 *   gd_c = G_c . D_c           s14, |gd| <= 4608: G . d' = 3 G . d in s14 Q4.9, exact
 *   hash                       np_hash6 on (i + A_x) mod 256 etc.: the low 8 bits
 *                              of the skewed corner, which is what Appendix B's
 *                              b(N, B) = N >> B & 1 (B < 8) reads of an unbounded int.
 * With t = 32 tau / 45 and d = d'/3 the function becomes
 *   f    = Kf * S,     S      = sum_c tau^4 (G . d')                 Kf = 8 (32/45)^4 / 3
 *   df_a = Kd * Q_a,   Q_a    = sum_c (tau^4 G_a - 5/4 tau^3 (G . d') d'_a)  Kd = 8 (32/45)^4
 * Kf = 8388608/12301875 = 0.68190, Kd = 3 Kf = 2.04569: one constant
 * multiplier per output, after the sums; 5/4 is a shift-add.
 *
 * ROUNDED DATAPATH (WT = t_frac, WP = p_frac, WK = k_frac; all rounding is
 * np_shr_round_half_up, i.e. floor(v + 1/2) in the result's LSB):
 *   tau2 = round(T * T)          u(WT) Q0.WT  ~ tau^2 <= 0.7120
 *   tau4 = round(tau2 * tau2)    u(WT) Q0.WT  ~ tau^4 <= 0.5069
 *   tau3 = round(tau2 * T)       u(WT) Q0.WT  ~ tau^3 <= 0.6007   (derivative only)
 *   fc   = round(tau4 * gd)      s(WP+1) Q0.WP, |tau^4 G.d'| <= 0.4246
 *   S    = sum of 4 fc           s(WP+2) Q1.WP, |S| <= 1.6981 (4 * 0.4246)
 *   q    = round(tau3 * gd)      s(WP+1) Q0.WP, |tau^3 G.d'| <= 0.5755
 *   m_a  = round(5 q D_a / 2^11) s(WP+1) Q0.WP, 5/4 q d'_a, |.| <= 0.7407 (+ error)
 *   e_a  = G_a tau4 to WP bits   s(WP+1) Q0.WP
 *   Q_a  = sum of 4 (e_a - m_a)  s(WP+3) Q2.WP, per corner |.| <= 0.9274, |Q| <= 3.7093
 *   Kf'  = round(Kf 2^WK)        u(WK)   Q0.WK
 *   Kd'  = round(Kd 2^WK)        u(WK+2) Q2.WK
 *   f    = sat(round(Kf' S))     sN   Q-1.N   (value = word / 2^N, range [-1/2, 1/2))
 *   df_a = sat(round(Kd' Q_a))   sND  Q1.(ND-2) (value = word / 2^(ND-2), range [-2, 2))
 * The per-corner bounds are max over s = |d'|^2 in [0, 5.4) of tau^4 sqrt(3 s),
 * tau^3 sqrt(3 s), 5/4 sqrt(3) tau^3 s and tau^4 + 5/4 sqrt(3) tau^3 s with
 * tau = 5 (5.4 - s) / 32 (|G . d'| <= sqrt(3) |d'|); each sum has at most four
 * terms. So no intermediate overflows (simplex.max_magnitude asserts every
 * width, and that the saturation never acts, over random inputs and the
 * extreme ones, at five configurations).
 *
 * OUTPUT RANGE (why Q-1.N and Q1.(ND-2)). The unit's inputs fall into
 * 25,165,824 distinct local configurations (U, V, W) (3 residues of n mod 3
 * times 2^23 points per skewed cell). Over all of them, with every corner's
 * gradient chosen adversarially from the 20 gradients of np_grad_decode,
 *   |f|    <= max sum_c 8 t^4 |d|_1                                   = 0.347438
 *   |df_a| <= max sum_c (|8t^4 - 64t^3 d_a^2| + 64 t^3 |d_a| (|d_b|+|d_c|)) = 1.740774
 * (simplex.max_magnitude recomputes both). The f bound is attained: at the
 * cell centre (0x0640, 0x0040, 0x0340) only corners 0 and 3 are in reach and
 * their gradients are aligned, f = -0.347438; the largest |df_a| seen in
 * 1e6 random inputs is 1.7226. So f fits
 * [-1/2, 1/2) and each derivative [-2, 2) with margin; the saturation is a
 * safety net that no input reaches in a faithful configuration (error < 1
 * LSB): |f| 2^N + 1 < 2^(N-1) - 1 needs N >= 4 and |df| 2^(ND-2) + 1 <
 * 2^(ND-1) - 1 needs ND >= 5, the smallest widths allowed.
 *
 * ERROR BOUND (argument; simplex.random_1e7 measures it). With
 * e = 2^-(WT+1), p = 2^-(WP+1), k = 2^-(WK+1), tau <= 0.84375:
 *   |tau2 - tau^2| <= e; |tau4 - tau^4| <= e (2 tau^2 + e) + e =: e4 (<= 2.4239 e)
 *   |tau3 - tau^3| <= tau e + e
 *   f:  |S' - S| <= 4 (e4 sqrt(16.2) + p) =: Ef       (|G.d'| < sqrt(3 * 5.4))
 *       |f - 2^N f_true| <= 1/2 + 2^N (Kf Ef + k (1.6981 + Ef))      LSB
 *   df: per corner |e_a' - e_a| <= e4 + p,
 *       |m_a' - m_a| <= 5/4 |d'_a| (|G.d'| (tau + 1) e + p) + p
 *                    <= 5/4 sqrt(3) * 5.4 e + 2.9047 p + p (s (tau(s)+1) <= 5.4)
 *       |Q' - Q| <= 4 (e4 + 11.6913 e + 4.9047 p) =: Ed
 *       |df_a - 2^(ND-2) df_true| <= 1/2 + 2^(ND-2) (Kd Ed + k (3.7093 + Ed))  LSB
 * np_simplex_error_bound_lsb() evaluates these. The faithful default widths
 *   f only:      WT = N + 7,  WP = N + 4,  WK = N + 6
 *   derivative:  WT = max(N + 7, FD + 10), WP = max(N + 4, FD + 8),
 *                WK = max(N + 6, FD + 7),  FD = ND - 2
 * bound f by 0.587 LSB and df by 0.642 LSB at N = ND = 16 (every default is
 * < 1 LSB: each output is one of the two codes next to the true value).
 * The float reference's own error (~1e-15) is far below an LSB.
 *
 * WRAP. The input is an unsigned 8.8 word, so the domain is [0, 256)^3 and
 * the unit computes Appendix B's noise(X/256, Y/256, Z/256) there, exactly
 * as np_ref_simplex3 does for the same real point: the skewed cell i runs
 * 0..511 and the hash reads i mod 256, like b() reads bits 0..7 of Appendix
 * B's unbounded int. The function is periodic under skewed translations by
 * 256 (unskewed (640/3, -128/3, -128/3) etc.) and therefore under
 * (128, 128, 128) = 0x8000 on every input word, where the unit's outputs
 * repeat bit for bit. It does NOT tile at 256 along an axis: when an input
 * word wraps (0xffff -> 0x0000) the output jumps from noise(256 - 1/256, .)
 * to noise(0, .), not to noise(256, .), which the reference gives for 256.0.
 *
 * t = 0 IS NOT REACHABLE from 8.8 inputs: every D is even and its three
 * components are congruent mod 3 (D_a = 4(n + c) mod 6 on every axis), so
 * R2 = 4 r with r = 0 mod 3 and T = 7077888 - 60 r' = 48 (mod 60), never 0.
 * Over all local configurations the nearest values are T = 48
 * (t = +4.07e-6) and T = -72 (t = -6.1e-6) (simplex.kernel_t_zero finds
 * them; one input step moves T by about 9000-15000 there). At T = 48,
 * tau2 = round(2304 / 2^(46 - WT)) = 0 for every WT <= 30, so the unit's
 * term is exactly 0 against 8 t^4 |G.d| < 1e-20 in the reference: the
 * kernel switches off continuously (t^4), with no step at the support
 * boundary.
 */
#ifndef NP_SIMPLEX_H
#define NP_SIMPLEX_H

#include <stddef.h>
#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_hash.h"
#include "np_pipe.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_SIMPLEX_IN_BITS = 16,    /* X, Y, Z: u16 Q8.8 */
    NP_SIMPLEX_FRAC_IN = 8,     /* input fraction bits */
    NP_SIMPLEX_SKEW_BITS = 19,  /* SX = 4X + Y + Z <= 393210 */
    NP_SIMPLEX_CELL_BITS = 9,   /* i in [0, 511] */
    NP_SIMPLEX_HASH_BITS = 8,   /* the hash reads the corner index mod 256 */
    NP_SIMPLEX_OFF_BITS = 12,   /* U, D: s12, units of 1/1536 */
    NP_SIMPLEX_GD_BITS = 14,    /* gd = G . D: s14 */
    NP_SIMPLEX_R2_BITS = 22,    /* R2 = |D|^2 <= 1536^2 */
    NP_SIMPLEX_TD_BITS = 24,    /* 7077888 - 5 R2 before the clamp: s24 */
    NP_SIMPLEX_T_BITS = 23,     /* T: u23 Q0.23 */
    NP_SIMPLEX_GD_FRAC = 9,     /* gd and D hold 3 G.d and 3 d in Q.9 */
    NP_SIMPLEX_M_SHIFT = 2,     /* 5/4 = (4 + 1) / 2^2 in m_a */
    NP_SIMPLEX_DIV3_MUL = 683,  /* floor(n / 3) = (683 n) >> 11 for n < 2048 */
    NP_SIMPLEX_DIV3_SHIFT = 11,
    NP_SIMPLEX_OUT_MIN = 4,     /* f: below 4 bits rounding alone could reach saturation */
    NP_SIMPLEX_DOUT_MIN = 5,    /* df: the same below 5 bits (see OUTPUT RANGE) */
    NP_SIMPLEX_OUT_MAX = 20,    /* both: wider outputs would need WT > 30 or WK > 26 */
    NP_SIMPLEX_WT_MAX = 30,
    NP_SIMPLEX_WP_MAX = 32,
    NP_SIMPLEX_WK_MAX = 26
};

/* Exact constants of the front end (see the top of this file). */
#define NP_SIMPLEX_UNIT 1536         /* offsets in units of 1/1536 */
#define NP_SIMPLEX_SKEW_CELL 768     /* SX / 768 = skewed coordinate */
#define NP_SIMPLEX_T_VERTEX 7077888  /* 27 * 2^18: T at |d| = 0 (tau = 0.84375) */
#define NP_SIMPLEX_R2_SCALE 5        /* T = T_VERTEX - 5 R2 */
#define NP_SIMPLEX_KF_NUM 8388608u   /* 2^23: Kf = 2^23 / (3 * 45^4), Kd = 2^23 / 45^4 */
#define NP_SIMPLEX_KF_DEN 12301875u  /* 3 * 45^4 */
#define NP_SIMPLEX_KD_DEN 4100625u   /* 45^4 */

/* Configuration: every width that is a design choice. */
typedef struct np_simplex_cfg {
    unsigned out_bits;  /* N: f is sN Q-1.N; 4..20, default 16 */
    unsigned dout_bits; /* ND: df/dx, df/dy, df/dz are sND Q1.(ND-2); 5..20, default 16 */
    unsigned deriv;     /* 1: derivative datapath present; 0: f only */
    unsigned t_frac;    /* WT: fraction bits of tau^2, tau^3, tau^4; 1..30 */
    unsigned p_frac;    /* WP: fraction bits of products and sums; 1..32 */
    unsigned k_frac;    /* WK: fraction bits of the output constants; 1..26 */
} np_simplex_cfg;

/* The faithful default for the given output widths (see the error bound). */
np_simplex_cfg np_simplex_cfg_default(unsigned out_bits, unsigned dout_bits, unsigned deriv);
/* NULL when cfg is valid, else a static message naming the bad field. */
const char *np_simplex_cfg_check(const np_simplex_cfg *cfg);
/* Fraction bits of f (N) and of each derivative component (ND - 2). */
static inline unsigned np_simplex_f_frac(const np_simplex_cfg *cfg) { return cfg->out_bits; }
static inline unsigned np_simplex_d_frac(const np_simplex_cfg *cfg) { return cfg->dout_bits - 2u; }
/*
 * The guaranteed error bound of the argument above, in output LSB: of f
 * (deriv_field = 0) or of each derivative component (deriv_field = 1).
 */
double np_simplex_error_bound_lsb(const np_simplex_cfg *cfg, int deriv_field);

/* --- Datapath primitives (each one is one block of the diagram) --- */

/*
 * Rescale a signed fixed-point value from `from` to `to` fraction bits:
 * round half up (np_shr_round_half_up) when dropping bits, exact shift when
 * adding them. Error <= 1/2 LSB of the result, 0 when to >= from.
 */
static inline int64_t np_simplex_requant(int64_t v, unsigned from, unsigned to)
{
    return from >= to ? np_shr_round_half_up(v, from - to) : np_shl(v, to - from);
}

/*
 * SK: skewed numerator of one axis, 768 x' = 4 a + b + c for the 8.8 words
 * a (this axis) and b, c (the others). u19, exact.
 */
static inline uint32_t np_simplex_skew(uint16_t a, uint16_t b, uint16_t c)
{
    return 4u * (uint32_t)a + (uint32_t)b + (uint32_t)c;
}

/*
 * floor(n / 3) for 0 <= n < 2048 as a constant multiply: (683 n) >> 11.
 * Exact on that range (683/2048 = 1/3 + 1/6144; the excess n/6144 < 1/3).
 */
static inline uint32_t np_simplex_div3(uint32_t n)
{
    return (n * (uint32_t)NP_SIMPLEX_DIV3_MUL) >> NP_SIMPLEX_DIV3_SHIFT;
}

/* SK: skewed cell index, floor(SX / 768) = floor(floor(SX / 256) / 3); u9. */
static inline uint32_t np_simplex_cell(uint32_t sx)
{
    return np_simplex_div3(sx >> NP_SIMPLEX_FRAC_IN);
}

/*
 * RK: offset from the unskewed corner 0 in units of 1/1536: 6 a - 1536 i + 256 n
 * with a the axis's 8.8 word, i its cell and n = i + j + k. s12, exact.
 */
static inline int32_t np_simplex_offset(uint16_t a, uint32_t i, uint32_t n)
{
    return 6 * (int32_t)a - NP_SIMPLEX_UNIT * (int32_t)i + 256 * (int32_t)n;
}

/*
 * RK: Appendix B's ranking, exactly (three comparators, ties included):
 *   hi = u >= w ? (u >= v ? 0 : 1) : (v >= w ? 1 : 2)
 *   lo = u <  w ? (u <  v ? 0 : 1) : (v <  w ? 1 : 2)
 * The simplex is corner 0, +e_hi, +e_hi+e_mid (mid = 3 - hi - lo), +(1,1,1).
 */
static inline void np_simplex_rank(int32_t u, int32_t v, int32_t w, uint8_t *hi, uint8_t *lo)
{
    int uw = u >= w, uv = u >= v, vw = v >= w;
    *hi = (uint8_t)(uw ? (uv ? 0 : 1) : (vw ? 1 : 2));
    *lo = (uint8_t)(!uw ? (!uv ? 0 : 1) : (!vw ? 1 : 2));
}

/* Skewed offset of corner c (0..3) as a 3-bit mask (bit a = axis a). */
static inline unsigned np_simplex_corner_mask(uint8_t hi, uint8_t lo, unsigned c)
{
    switch (c) {
    case 0: return 0u;
    case 1: return 1u << hi;
    case 2: return 7u & ~(1u << lo);
    default: return 7u;
    }
}

/* CH: corner-relative offset of one axis, D = U - 1536 A_a + 256 c; s12, exact. */
static inline int32_t np_simplex_corner_d(int32_t off, unsigned a_bit, unsigned c)
{
    return off - NP_SIMPLEX_UNIT * (int32_t)a_bit + 256 * (int32_t)c;
}

/* CH: corner hash; the skewed corner index is read mod 256 (its low 8 bits). */
static inline uint8_t np_simplex_corner_hash(const uint32_t cell[3], unsigned mask)
{
    return np_hash6_fast((uint8_t)((cell[0] + (mask & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS)),
                    (uint8_t)((cell[1] + (mask >> 1 & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS)),
                    (uint8_t)((cell[2] + (mask >> 2 & 1u)) & NP_MASK(NP_SIMPLEX_HASH_BITS)));
}

/* CH: gradient contribution G . D, each coefficient in {-1, 0, 1}: select,
 * negate and two additions; s14, exact (|gd| <= 3 * 1536). */
static inline int32_t np_simplex_gdot(np_grad g, const int32_t d[3])
{
    return g.cx * d[0] + g.cy * d[1] + g.cz * d[2];
}

/* KT: squared length R2 = |D|^2, u22 (<= 1536^2 since |d| <= 1), exact. */
static inline uint32_t np_simplex_r2(const int32_t d[3])
{
    return (uint32_t)(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/*
 * KT: the kernel variable T = max(0, 7077888 - 5 R2), u23 Q0.23 holding
 * tau = 45 t / 32 exactly; 0 outside the kernel's support (t <= 0), which
 * zeroes every power and term of the corner.
 */
static inline uint32_t np_simplex_kernel_t(uint32_t r2)
{
    int32_t td = NP_SIMPLEX_T_VERTEX - NP_SIMPLEX_R2_SCALE * (int32_t)r2; /* s24 */
    return td > 0 ? (uint32_t)td : 0u;
}

/* P2: tau2 = round(T^2) to WT bits, u(WT) Q0.WT; error <= 1/2 LSB. */
static inline uint32_t np_simplex_tau2(const np_simplex_cfg *cfg, uint32_t t)
{
    uint64_t sq = (uint64_t)t * t; /* u46 Q0.46, exact */
    return (uint32_t)np_shr_round_half_up_u(sq, 2u * NP_SIMPLEX_T_BITS - cfg->t_frac);
}

/* P4: tau4 = round(tau2^2) to WT bits, u(WT) Q0.WT; error of the rounding <= 1/2 LSB. */
static inline uint32_t np_simplex_tau4(const np_simplex_cfg *cfg, uint32_t tau2)
{
    return (uint32_t)np_shr_round_half_up_u((uint64_t)tau2 * tau2, cfg->t_frac);
}

/* P4: tau3 = round(tau2 * T) to WT bits, u(WT) Q0.WT (derivative only). */
static inline uint32_t np_simplex_tau3(uint32_t tau2, uint32_t t)
{
    return (uint32_t)np_shr_round_half_up_u((uint64_t)tau2 * t, NP_SIMPLEX_T_BITS);
}

/* M: fc = round(tau4 * gd) = tau^4 G.d' to WP bits, s(WP+1) Q0.WP. */
static inline int64_t np_simplex_fterm(const np_simplex_cfg *cfg, uint32_t tau4, int32_t gd)
{
    return np_simplex_requant((int64_t)tau4 * gd, cfg->t_frac + NP_SIMPLEX_GD_FRAC, cfg->p_frac);
}

/* M: q = round(tau3 * gd) = tau^3 G.d' to WP bits, s(WP+1) Q0.WP. */
static inline int64_t np_simplex_qterm(const np_simplex_cfg *cfg, uint32_t tau3, int32_t gd)
{
    return np_simplex_requant((int64_t)tau3 * gd, cfg->t_frac + NP_SIMPLEX_GD_FRAC, cfg->p_frac);
}

/* M: e_a = G_a tau4 to WP bits, s(WP+1) Q0.WP (a select and a negate). */
static inline int64_t np_simplex_eterm(const np_simplex_cfg *cfg, uint32_t tau4, int coef)
{
    return np_simplex_requant((int64_t)coef * (int64_t)tau4, cfg->t_frac, cfg->p_frac);
}

/*
 * M2: m_a = round(5/4 q d'_a) = round(5 q D_a / 2^11) to WP bits,
 * s(WP+1) Q0.WP; 5 q = 4 q + q is a shift-add, then one multiply by D_a.
 */
static inline int64_t np_simplex_mterm(int64_t q, int32_t d)
{
    int64_t q5 = np_shl(q, NP_SIMPLEX_M_SHIFT) + q;
    return np_shr_round_half_up(q5 * (int64_t)d, NP_SIMPLEX_GD_FRAC + NP_SIMPLEX_M_SHIFT);
}

/* O: the constants Kf' = round(Kf 2^WK) (u(WK)) and Kd' = round(Kd 2^WK) (u(WK+2)). */
static inline int64_t np_simplex_kf(const np_simplex_cfg *cfg)
{
    uint64_t num = (uint64_t)NP_SIMPLEX_KF_NUM << cfg->k_frac;
    return (int64_t)((num + NP_SIMPLEX_KF_DEN / 2u) / NP_SIMPLEX_KF_DEN);
}
static inline int64_t np_simplex_kd(const np_simplex_cfg *cfg)
{
    uint64_t num = (uint64_t)NP_SIMPLEX_KF_NUM << cfg->k_frac;
    return (int64_t)((num + NP_SIMPLEX_KD_DEN / 2u) / NP_SIMPLEX_KD_DEN);
}

/* O: f = sat(round(Kf' S)) to sN Q-1.N. */
static inline int32_t np_simplex_out_f(const np_simplex_cfg *cfg, int64_t kf, int64_t s)
{
    int64_t r = np_simplex_requant(kf * s, cfg->k_frac + cfg->p_frac, np_simplex_f_frac(cfg));
    return (int32_t)np_sat_s(r, cfg->out_bits);
}

/* O: df_a = sat(round(Kd' Q_a)) to sND Q1.(ND-2). */
static inline int32_t np_simplex_out_d(const np_simplex_cfg *cfg, int64_t kd, int64_t q)
{
    int64_t r = np_simplex_requant(kd * q, cfg->k_frac + cfg->p_frac, np_simplex_d_frac(cfg));
    return (int32_t)np_sat_s(r, cfg->dout_bits);
}

/* The outputs as signed values: f in sN Q-1.N, df[a] in sND Q1.(ND-2) (0 when deriv = 0). */
typedef struct np_simplex_out {
    int32_t f;
    int32_t df[3];
} np_simplex_out;

/* The bit-exact model. */
void np_simplex_eval(const np_simplex_cfg *cfg, uint16_t x, uint16_t y, uint16_t z,
                     np_simplex_out *out);

/*
 * The bit-exact model over arrays: out[n] = np_simplex_eval(cfg, x[n], y[n],
 * z[n]) for n < count, the same bits (fast.simplex_batch_* prove it). The
 * configuration is read once; the two default configurations (N = ND = 16
 * with and without the derivative, np_simplex_cfg_default) run specialised
 * loops in int32 lanes (np_simplex32.h), by hand in AVX-512 or AVX2 where
 * the CPU has it. The arrays may not overlap out.
 */
void np_simplex_eval_n(const np_simplex_cfg *cfg, const uint16_t *x, const uint16_t *y,
                       const uint16_t *z, np_simplex_out *out, size_t count);

/*
 * The batch model's implementations, each the same bits as np_simplex_eval:
 *   GENERIC  the model per input with the configuration read once, any
 *            configuration;
 *   WIDTHS   the model per input with the widths as compile-time constants
 *            (64-bit products, vectorised by the compiler where it can): the
 *            two defaults;
 *   INT32    the two defaults in int32 arithmetic (the split products of
 *            np_simplex32.h), portable C;
 *   AVX2     the same int32 arithmetic eight inputs a step, by hand for AVX2
 *            (x86-64 with GCC or Clang, on a CPU with AVX2);
 *   AVX512   the same sixteen inputs a step (a CPU with AVX-512F).
 * np_simplex_eval_n runs the first of AVX512, AVX2, WIDTHS, GENERIC that
 * applies (INT32 is the vector paths' tail; scalar, it is slower than
 * WIDTHS, which the compiler vectorises). np_simplex_eval_n_path runs the one named,
 * for the tests that prove each path against np_simplex_eval and for the
 * bench; it returns -1 (writing nothing) when that path does not apply to
 * cfg or this CPU, else 0.
 */
enum {
    NP_SIMPLEX_BATCH_GENERIC,
    NP_SIMPLEX_BATCH_WIDTHS,
    NP_SIMPLEX_BATCH_INT32,
    NP_SIMPLEX_BATCH_AVX2,
    NP_SIMPLEX_BATCH_AVX512,
    NP_SIMPLEX_BATCH_PATHS
};
int np_simplex_eval_n_path(unsigned path, const np_simplex_cfg *cfg, const uint16_t *x,
                           const uint16_t *y, const uint16_t *z, np_simplex_out *out, size_t count);

/* --- Cycle-accurate model --- */

/* The signal bundle carried through the pipeline (formats as above). */
typedef struct np_simplex_sig {
    uint16_t x, y, z;      /* input */
    uint32_t sk[3];        /* SK: SX, SY, SZ (u19) */
    uint32_t cell[3];      /* SK: i, j, k (u9) */
    int32_t off[3];        /* RK: U, V, W (s12) */
    uint8_t hi, lo;        /* RK: ranking */
    int32_t d[4][3];       /* CH: corner offsets D (s12) */
    uint8_t h[4];          /* CH: corner hashes (u6) */
    np_grad g[4];          /* CH: decoded gradients */
    int32_t gd[4];         /* CH: G . D (s14) */
    uint32_t r2[4];        /* KT: |D|^2 (u22) */
    uint32_t t[4];         /* KT: T (u23) */
    uint32_t tau2[4];      /* P2 */
    uint32_t tau3[4], tau4[4]; /* P4 */
    int64_t fc[4], q[4];   /* M */
    int64_t e[4][3];       /* M */
    int64_t m[4][3];       /* M2 (derivative only) */
    int64_t s;             /* A: sum of fc, s(WP+2) */
    int64_t qs[3];         /* A: sums Q_a, s(WP+3) */
    int32_t f, df[3];      /* O: outputs */
} np_simplex_sig;

/* Pipelines: with the derivative (10 banks) and f only (9 banks: no M2). */
enum { NP_SIMPLEX_STAGES_D = 10, NP_SIMPLEX_STAGES_F = 9 };
extern const np_stage_desc np_simplex_stages_d[NP_SIMPLEX_STAGES_D];
extern const np_stage_desc np_simplex_stages_f[NP_SIMPLEX_STAGES_F];

/* Number of stages (= latency in clocks) of the pipe for cfg. */
static inline unsigned np_simplex_stage_count(const np_simplex_cfg *cfg)
{
    return cfg->deriv ? NP_SIMPLEX_STAGES_D : NP_SIMPLEX_STAGES_F;
}
static inline const np_stage_desc *np_simplex_stage_table(const np_simplex_cfg *cfg)
{
    return cfg->deriv ? np_simplex_stages_d : np_simplex_stages_f;
}

/* A pipe running the simplex unit; cfg must outlive it. 0, or -1 on no memory. */
int np_simplex_pipe_init(np_pipe *p, const np_simplex_cfg *cfg);

/* --- Datapath declaration (np_datapath.h) --- */

/*
 * The operators and register bits of every stage of the pipe for cfg (the
 * stage names of np_simplex_stage_table(cfg)); with deriv = 0 no derivative
 * operator or register bit appears. Writes up to max entries to ops and
 * returns the full count.
 *
 * The declared widths are the hardware's, from the range argument written
 * next to each one in np_simplex.c; where that argument is tighter than the
 * C containers above, the declaration is narrower (the bits are the same):
 * gd is s13, not s14 (|gd| <= |D|_1 <= sqrt(3) 1536 = 2660); S and Q_a are
 * s(WP+1), not s(WP+2) and s(WP+3) (|S| <= 0.347438 / Kf = 0.5095 and
 * |Q_a| <= 1.740774 / Kd = 0.8510, the output bounds of OUTPUT RANGE, plus
 * the rounding errors of the ERROR BOUND), and fc is sWP (0.4245 < 1/2).
 * Traced signal names: "bc", "sk", "n5", "n11", "n341", "n683", "off", "d",
 * "h", "gd2", "gd", "dsq", "r2p", "r2", "r2x5", "td", "t", "tsq", "tau2",
 * "tau4p", "tau4", "fcp", "fc", "s", "fprod", "f", and with the derivative
 * "tau3p", "tau3", "qp", "q", "e", "q5", "mp", "m", "em", "qs", "dprod", "df".
 */
size_t np_simplex_datapath(const np_simplex_cfg *cfg, np_op *ops, size_t max);

/*
 * Widen the traces t[0..n) whose names match the signals that stage k of
 * np_simplex_stage_table(cfg) produced in bundle s (call after applying that
 * stage's fn).
 */
void np_simplex_trace(const np_simplex_cfg *cfg, unsigned k, const np_simplex_sig *s, np_trace *t,
                      size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_SIMPLEX_H */
