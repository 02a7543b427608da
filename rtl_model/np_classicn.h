/* SPDX-License-Identifier: MIT */
/*
 * np_classicn.h - classic gradient noise in n = 2..5 dimensions (Perlin,
 * "Noise Hardware", shared/seeds/002, "The original algorithm" generalised
 * to the hypercube lattice the paper's cost argument is about): 2^n corners,
 * the n-D table-free hash and multiply-free gradient (np_hashn.h), the
 * s-curve 3t^2 - 2t^3 per axis and 2^n - 1 linear interpolators in n
 * levels. The generic datapath is np_classic.h's with 3 replaced by n: for
 * n = 3 it is the classic3 unit bit for bit (ndim.classic3_bit_exact
 * compares every output; ndim.classic3_same_datapath the declaration).
 *
 * Signals (np_classic.h for the 3-D names):
 *   x_a        u16 Q8.8  input field a (x, y, z, w, v); cell c_a = high byte
 *                        (tile 256), fraction u_a = low byte (u8 Q0.8)
 *   h[c]       u6        np_hashn(n, k_c) of corner c = sum_a 2^a b_a:
 *                        k_ca = (c_a + b_a) mod 256
 *   d_ca       s9 Q1.8   u_a (b_a = 0) or u_a - 256 (b_a = 1)
 *   g[c]       s(GB) Q.8 sum_a G_ca d_ca, G_c = np_gradn_decode(n, h[c]), exact;
 *                        |g| <= K 256 (K = np_gradn_max_terms): GB = 11 (n <= 4), 12 (n = 5)
 *   s_a        u(WS+1) Q1.WS   round(u^2 (768 - 2u) / 2^(24 - WS)), as classic3
 *   l_m[p]     s(WL+1+vi_m) Q(vi_m).WL   level m = 1..n, p < 2^(n-m):
 *                        lerp(s_(m-1), l_(m-1)[2p], l_(m-1)[2p+1]) (along
 *                        axis m - 1), l_0 = g (Q.8); lerp(s, a, b) =
 *                        rescale(a 2^WS + s (b - a), fa + WS -> WL), fa = 8
 *                        at level 1, WL after
 *   out        sN Q(I).(N-I)   sat(rescale(l_n, WL -> F)); I = 2 (n <= 3),
 *                        3 (n = 4, 5); F = N - I fraction bits. I COUNTS THE
 *                        SIGN (as classic3's s8 Q2.6 and the vector headers):
 *                        Q(I-1).F in np_fixed.h's notation
 * rescale: dropping bits rounds half up (np_shr_round_half_up, ties toward
 * +inf), adding bits is the exact left shift (level 1 when WL > 8 + WS).
 * Range: each axis contributes at most 1 (|d_a| <= 1, |coefficient| <= 1)
 * and, once interpolated, at most max_t (1 - s)t + s(1 - t) = 1/2, so
 * |l_m| <= m/2 + (n - m) and |noise| <= n/2 = 1, 1.5, 2, 2.5 < 2^(I-1):
 * the saturation never acts.
 * Error (np_classic.h's argument with |b - a| <= 2n and n levels):
 *   |out - noise| <= 1/2 + n (n 2^(F-WS) + 2^(F-WL-1))  LSB
 * Defaults WS = F + 6 (n <= 3), F + 7 (n >= 4); WL = F + 5: bounds 0.5938
 * (n = 2), 0.6875 (n = 3), 0.6875 (n = 4), 0.7734 (n = 5): faithful.
 */
#ifndef NP_CLASSICN_H
#define NP_CLASSICN_H

#include <stddef.h>
#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_hashn.h"
#include "np_pipe.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_CLASSICN_MAX = 5,
    NP_CLASSICN_CORNERS = 32,
    NP_CLASSICN_OUT_MIN = 4,
    NP_CLASSICN_OUT_MAX = 16,
    NP_CLASSICN_WS_MAX = 24,
    NP_CLASSICN_WL_MAX = 30,
    NP_CLASSICN_SNUM_BITS = 24,
    NP_CLASSICN_FRAC_IN = 8
};

typedef struct np_classicn_cfg {
    unsigned dims;      /* n: 2..5 */
    unsigned out_bits;  /* N: sN Q(I).(N-I); 4..16 */
    unsigned s_frac;    /* WS: 1..24 */
    unsigned lerp_frac; /* WL: F..30 */
} np_classicn_cfg;

/* Integer bits (with the sign) of the output, I. */
static inline unsigned np_classicn_int_bits(unsigned dims) { return dims <= 3u ? 2u : 3u; }
static inline unsigned np_classicn_out_frac(const np_classicn_cfg *c) { return c->out_bits - np_classicn_int_bits(c->dims); }

np_classicn_cfg np_classicn_cfg_default(unsigned dims, unsigned out_bits);
const char *np_classicn_cfg_check(const np_classicn_cfg *cfg);
double np_classicn_error_bound_lsb(const np_classicn_cfg *cfg);

/* The bit-exact model: the signed output (sN Q(I).(N-I)) at x[0..n). */
int32_t np_classicn_eval(const np_classicn_cfg *cfg, const uint16_t *x);

typedef struct np_classicn_sig {
    uint16_t x[NP_CLASSICN_MAX];
    uint8_t h[NP_CLASSICN_CORNERS];   /* L */
    uint32_t s2[NP_CLASSICN_MAX];     /* L: u^2 */
    int16_t g[NP_CLASSICN_CORNERS];   /* H */
    uint32_t s[NP_CLASSICN_MAX];      /* H: the s-curves */
    int64_t opa[NP_CLASSICN_CORNERS / 2];  /* Im: the lerps' first operands a of the current level */
    int64_t prod[NP_CLASSICN_CORNERS / 2]; /* Im: products of the current level */
    int64_t l[NP_CLASSICN_CORNERS / 2];    /* Ia: values of the current level */
    int32_t out;                      /* O */
} np_classicn_sig;

/* Stages: L, H, I1m, I1a, ..., Inm, Ina, O: 2n + 3 (classic3: 9). */
static inline unsigned np_classicn_stage_count(unsigned dims) { return 2u * dims + 3u; }
const np_stage_desc *np_classicn_stage_table(unsigned dims);
int np_classicn_pipe_init(np_pipe *p, const np_classicn_cfg *cfg);

/* Datapath declaration: np_classic_datapath()'s accounting with n axes and 2^n corners. */
size_t np_classicn_datapath(const np_classicn_cfg *cfg, np_op *ops, size_t max);
/* Widen the traces whose signals stage k produced in s (the declaration's names). */
void np_classicn_trace(const np_classicn_cfg *cfg, unsigned k, const np_classicn_sig *s, np_trace *t, size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_CLASSICN_H */
