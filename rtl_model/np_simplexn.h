/* SPDX-License-Identifier: MIT */
/*
 * np_simplexn.h - simplex noise in n = 2..5 dimensions (Perlin, "Noise
 * Hardware", shared/seeds/002, "Generalization to higher dimensions"): the
 * value f (no derivative), one generic datapath whose per-n constants are
 * the table np_simplexn_geom(). n = 3 with Appendix B's constants
 * reproduces the simplex3 unit's f bit for bit (np_simplex.h; the test
 * ndim.simplex3_bit_exact compares them); docs/noise-nd.md is the spec.
 *
 * FUNCTION (real point p = X / 256 per axis, X a u16 Q8.8 word):
 *   skew:    i_a = floor(x_a + F sum_b x_b)             F = p/q (below)
 *   unskew:  u_a = x_a - i_a + G sum_b i_b              G = p/L, L = q + n p
 *   rank:    axes in decreasing u, ties to the lower axis (Appendix B's rule)
 *   corner c (0..n): skewed offset A_c = the first c axes of the ranking
 *            (A_ca = 1 when axis a is one of them, else 0)
 *            d_c = u - A_c + c G                      (the unskewed offset)
 *   f = A sum_c max(0, r^2 - |d_c|^2)^4 (G_c . d_c),  G_c = np_gradn_decode(
 *            n, np_hashn(n, k_c)), k_ca = (i_a + A_ca) mod 256
 * Axis a is input field a: x, y, z, w, v (the first n); the output field is
 * f. For n != 3 the tie rule cannot show in f: on a tie the two simplices
 * differ in one corner, at distance >= sqrt(1/2) = r from the point, where
 * T = 0 exactly (docs/noise-nd.md, "Ranking").
 * Since G = F / (1 + n F) exactly, skew and unskew are exact inverses for the
 * rational F: the lattice is the regular one's image up to the rounding of
 * F (docs/noise-nd.md bounds its effect on the geometry).
 *
 * CONSTANTS (np_simplexn_geom):
 *   n  p    q    L     F         G = p/L    r^2  A (amplitude)
 *   2  216  592  1024  0.364865  0.2109375  1/2  12
 *   3  1    3    6     1/3       1/6        0.6  8     (Appendix B)
 *   4  141  460  1024  0.306522  0.1376953  1/2  6
 *   5  121  419  1024  0.288783  0.1181641  1/2  4
 * For n != 3, G = floor(G_n 1024) / 1024 with G_n = (1 - 1/sqrt(n+1)) / n,
 * which keeps the smallest vertex-to-opposite-face distance of the simplex
 * at exactly sqrt(1/2) (docs/noise-nd.md), so r^2 = 1/2 makes every kernel
 * zero on the faces it does not touch: f is continuous. A is the largest
 * integer with A (n+1) |G|max max_s (r^2 - s)^4 sqrt(s) < 1/2, so |f| < 1/2
 * provably (the output is sN Q-1.N for every n).
 *
 * EXACT FRONT END (every decision on exact integers; W = the offset unit):
 *   SX_a = q X_a + p sum_b X_b        u26 (n = 3: 4X + Y + Z, u19)
 *   i_a  = floor(floor(SX_a / 256) / q)   u9 (n = 2, 3), u10 (n = 4, 5)
 *   U_a  = (W/256) X_a - W i_a + (W p / L) sum_b i_b   = W u_a, s12
 *   D_ca = U_a - W A_ca + (W p / L) c                = W d_ca, s12
 *   k_ca = (i_a + A_ca) mod 256   u8, corner c's lattice point
 *   G_c  = np_gradn_decode(n, np_hashn(n, k_c))       coefficients in {-1, 0, 1}
 *   R2_c = sum_a D_ca^2          u20 (n = 2), u21 (n = 4, 5), u22 (n = 3)
 *   T_c  = max(0, Tv - k R2_c)   u(TB) Q0.TB holding tau = c_t t exactly
 *                                (n != 3: u20 Q0.20, T <= 2^19)
 *   gd_c = sum_a G_ca D_ca       s12 (n = 2, 4), s13 (n = 3, 5), read as Q.GDF
 *                                (gd = G.d W / 2^GDF); widths as declared
 *   n != 3: W = 1024, TB = 20, Tv = 2^19, k = 1, GDF = 10: tau = t, gd = G.d.
 *   n = 3:  W = 1536, TB = 23, Tv = 7077888, k = 5, GDF = 9 (np_simplex.h).
 * ROUNDED DATAPATH (every rescaling np_simplexn_requant: dropping bits
 * rounds half up, floor(v / 2^k + 1/2) on the two's-complement value, ties
 * toward +inf for negative values too (np_shr_round_half_up); adding bits
 * is the exact left shift):
 *   tau2 = round(T^2 / 2^(2 TB - WT))   u(WT-1) Q0.WT (n = 3: u(WT))
 *   tau4 = round(tau2^2 / 2^WT)          u(WT-3) Q0.WT (n = 3: u(WT))
 *   fc   = rescale(tau4 gd, WT + GDF -> WP)   s(WP+1) Q0.WP (a left shift
 *          when WP > WT + GDF)
 *   S    = sum of the n + 1 fc           s(WP+3) Q2.WP
 *   f    = sat(rescale(Kf' S, WK + WP -> N))   sN Q-1.N (a left shift
 *          when WK + WP < N); sat clamps to [-2^(N-1), 2^(N-1) - 1]
 *   Kf   = A 2^GDF / (c_t^4 W): n != 3: Kf = A (an integer: Kf' = A 2^WK is
 *          exact, WK = 0); n = 3: 2^23 / 12301875 rounded to WK bits.
 * ERROR BOUND (argument; np_simplexn_error_bound_lsb): e = 2^-(WT+1),
 * p = 2^-(WP+1), k = 2^-(WK+1) (0 when Kf' is exact), tau <= tau0 (1/2;
 * n = 3: 0.84375):
 *   e4 = e (2 tau0^2 + e) + e >= |tau4 - tau^4|
 *   Ef = (n + 1) (e4 gmax + p)      gmax >= |gd| where T > 0:
 *                                   sqrt(K r^2) (n = 3: sqrt(3 * 5.4))
 *   |f - 2^N f_true| <= 1/2 + 2^N (Kf Ef + k (Smax + Ef))  LSB
 * with Smax = np_simplexn_geom.smax, the bound on |S| (n = 3: 1.6981). At
 * n = 3 this is np_simplex_error_bound_lsb's f bound. The saturation never
 * widens the error: |f_true| 2^N <= 2^(N-1) - 1 for every N >= 8 (fmax
 * < 1/2 leaves at least 0.0063), so clamping moves the output toward the
 * true value. The defaults (np_simplexn_cfg_default) make the bound < 1
 * LSB (0.579..0.703 for every N): faithful by this argument;
 * ndim.error_simplex measures it.
 */
#ifndef NP_SIMPLEXN_H
#define NP_SIMPLEXN_H

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
    NP_SIMPLEXN_MAX = 5,          /* largest n */
    NP_SIMPLEXN_CORNERS = 6,      /* n + 1 at most */
    NP_SIMPLEXN_OUT_MIN = 8,      /* f: sN, the saturation argument needs N >= 8 */
    NP_SIMPLEXN_OUT_MAX = 20,
    NP_SIMPLEXN_WT_MAX = 30,
    NP_SIMPLEXN_WP_MAX = 32,
    NP_SIMPLEXN_WK_MAX = 26
};

/* The per-n constants of the datapath (the table above). */
typedef struct np_simplexn_geom {
    unsigned n;
    uint32_t p, q, l;     /* F = p/q, G = p/l, l = q + n p */
    uint32_t w;           /* offset unit: U = W u */
    uint32_t wx;          /* W / 256: U's multiplier of the input word */
    uint32_t wc;          /* W p / l: U's and D's multiplier of sum i and of c */
    unsigned tb;          /* T is u(TB) Q0.TB */
    uint32_t tv;          /* T at |d| = 0 */
    uint32_t k;           /* T = Tv - k R2 */
    unsigned gdf;         /* gd is read as Q.GDF */
    uint64_t kf_num, kf_den; /* Kf = kf_num / kf_den */
    unsigned amp;         /* A */
    double r2;            /* r^2 (the kernel's squared radius) */
    double tau0;          /* tau at |d| = 0: Tv / 2^TB */
    double gmax;          /* a bound on |gd| (real value) where T > 0 */
    double smax;          /* a bound on |S| (real value), before rounding errors */
    double fmax;          /* the bound on |f| the amplitude was tuned to (< 1/2) */
    double edge2;         /* the longest simplex edge, squared (rounded up): |d|^2 <= edge2 */
    double fcmax;         /* a bound on one corner's |tau^4 G.d| in gd's units (real value) */
} np_simplexn_geom;

/* The constants of n (2..5), or NULL. */
const np_simplexn_geom *np_simplexn_geom_of(unsigned n);

typedef struct np_simplexn_cfg {
    unsigned dims;     /* n: 2..5 */
    unsigned out_bits; /* N: f is sN Q-1.N; 8..20 */
    unsigned t_frac;   /* WT: fraction bits of tau^2, tau^4; 1..30 */
    unsigned p_frac;   /* WP: fraction bits of the terms and their sum; 1..32 */
    unsigned k_frac;   /* WK: fraction bits of Kf' (0 for n != 3: Kf = A exactly); n = 3: 1..26 */
} np_simplexn_cfg;

/* The faithful default for n and N (n = 3: np_simplex_cfg_default(N, N, 0)'s widths). */
np_simplexn_cfg np_simplexn_cfg_default(unsigned dims, unsigned out_bits);
/* NULL when cfg is valid, else a static message naming the bad field. */
const char *np_simplexn_cfg_check(const np_simplexn_cfg *cfg);
/* The error bound of the argument above, in output LSB. */
double np_simplexn_error_bound_lsb(const np_simplexn_cfg *cfg);

/* --- Datapath primitives --- */

/* SK: SX_a = q X_a + p sum_b X_b (sum = sum of all n words), exact. */
static inline uint32_t np_simplexn_skew(const np_simplexn_geom *g, uint16_t a, uint32_t sum)
{
    return g->q * (uint32_t)a + g->p * sum;
}

/* SK: the skewed cell floor(floor(SX / 256) / q), exact (a constant divider in hardware). */
static inline uint32_t np_simplexn_cell(const np_simplexn_geom *g, uint32_t sx)
{
    return (sx >> 8) / g->q;
}

/* RK: U_a = (W/256) X_a - W i_a + (W p / l) n_sum, s12, exact. */
static inline int32_t np_simplexn_offset(const np_simplexn_geom *g, uint16_t a, uint32_t i, uint32_t nsum)
{
    return (int32_t)g->wx * (int32_t)a - (int32_t)g->w * (int32_t)i + (int32_t)g->wc * (int32_t)nsum;
}

/*
 * RK: the ranking by a sorting network of compare-exchange elements
 * (value, axis): element a goes before b when off[a] > off[b], or they are
 * equal and a < b (Appendix B's tie rule, a strict total order, so the
 * network's result is unique). order[0..n) = the axes, first = largest.
 */
void np_simplexn_rank(unsigned n, const int32_t *off, uint8_t *order);
/* The network of n: comparators (i, j) in order, count returned; i gets the "before" element. */
unsigned np_simplexn_network(unsigned n, const uint8_t (**pairs)[2]);

/* CH: D = U - W A + (W p / l) c, exact. */
static inline int32_t np_simplexn_corner_d(const np_simplexn_geom *g, int32_t off, unsigned a_bit, unsigned c)
{
    return off - (int32_t)g->w * (int32_t)a_bit + (int32_t)g->wc * (int32_t)c;
}

/* KT: T = max(0, Tv - k R2), u(TB), exact; 0 outside the support. */
static inline uint32_t np_simplexn_kernel_t(const np_simplexn_geom *g, uint64_t r2)
{
    int64_t td = (int64_t)g->tv - (int64_t)g->k * (int64_t)r2;
    return td > 0 ? (uint32_t)td : 0u;
}

/* P2: round(T^2) to WT bits, error <= 1/2 LSB. */
static inline uint32_t np_simplexn_tau2(const np_simplexn_geom *g, const np_simplexn_cfg *c, uint32_t t)
{
    return (uint32_t)np_shr_round_half_up_u((uint64_t)t * t, 2u * g->tb - c->t_frac);
}

/* P4: round(tau2^2) to WT bits, error of the rounding <= 1/2 LSB. */
static inline uint32_t np_simplexn_tau4(const np_simplexn_cfg *c, uint32_t tau2)
{
    return (uint32_t)np_shr_round_half_up_u((uint64_t)tau2 * tau2, c->t_frac);
}

/* Rescale: round half up when dropping bits, exact shift when adding. */
static inline int64_t np_simplexn_requant(int64_t v, unsigned from, unsigned to)
{
    return from >= to ? np_shr_round_half_up(v, from - to) : np_shl(v, to - from);
}

/* M: fc = round(tau4 gd) to WP bits, s(WP+1). */
static inline int64_t np_simplexn_fterm(const np_simplexn_geom *g, const np_simplexn_cfg *c, uint32_t tau4, int32_t gd)
{
    return np_simplexn_requant((int64_t)tau4 * gd, c->t_frac + g->gdf, c->p_frac);
}

/* O: Kf' = round(Kf 2^WK) (n != 3: A 2^0 = A exactly). */
static inline int64_t np_simplexn_kf(const np_simplexn_geom *g, const np_simplexn_cfg *c)
{
    np_u128 num = (np_u128)g->kf_num << c->k_frac;
    return (int64_t)((num + g->kf_den / 2u) / g->kf_den);
}

/* O: f = sat(round(Kf' S)) to sN Q-1.N. */
static inline int32_t np_simplexn_out(const np_simplexn_cfg *c, int64_t kf, int64_t s)
{
    int64_t r = np_simplexn_requant(kf * s, c->k_frac + c->p_frac, c->out_bits);
    return (int32_t)np_sat_s(r, c->out_bits);
}

/* The bit-exact model: f (sN Q-1.N, signed) at the n words x[0..n). */
int32_t np_simplexn_eval(const np_simplexn_cfg *cfg, const uint16_t *x);

/* --- Cycle-accurate model --- */

typedef struct np_simplexn_sig {
    uint16_t x[NP_SIMPLEXN_MAX];          /* input */
    uint32_t sk[NP_SIMPLEXN_MAX];         /* SK: SX */
    uint32_t cell[NP_SIMPLEXN_MAX];       /* SK: i */
    int32_t off[NP_SIMPLEXN_MAX];         /* RK: U */
    uint8_t order[NP_SIMPLEXN_MAX];       /* RK: ranking */
    int32_t d[NP_SIMPLEXN_CORNERS][NP_SIMPLEXN_MAX]; /* CH: D */
    uint8_t h[NP_SIMPLEXN_CORNERS];       /* CH: corner hashes */
    int8_t g[NP_SIMPLEXN_CORNERS][NP_SIMPLEXN_MAX];  /* CH: gradients */
    int32_t gd[NP_SIMPLEXN_CORNERS];      /* CH: G . D */
    uint32_t r2[NP_SIMPLEXN_CORNERS];     /* KT */
    uint32_t t[NP_SIMPLEXN_CORNERS];      /* KT */
    uint32_t tau2[NP_SIMPLEXN_CORNERS];   /* P2 */
    uint32_t tau4[NP_SIMPLEXN_CORNERS];   /* P4 */
    int64_t fc[NP_SIMPLEXN_CORNERS];      /* M */
    int64_t s;                            /* A */
    int32_t f;                            /* O */
} np_simplexn_sig;

/* SK RK CH KT P2 P4 M A O: the f-only simplex3 pipe's stages, for every n. */
enum { NP_SIMPLEXN_STAGES = 9 };
extern const np_stage_desc np_simplexn_stages[NP_SIMPLEXN_STAGES];
int np_simplexn_pipe_init(np_pipe *p, const np_simplexn_cfg *cfg);

/*
 * Datapath declaration (np_datapath.h) for cfg, the same accounting for
 * every n (so the report's ratios compare like with like); widths from the
 * range bounds written beside each op. Traced signals (the conformance
 * test's width check): "sk", "off", "d", "h", "gd", "r2", "t", "tau2",
 * "tau4", "fc". The sum S, the output product and the output port f are
 * declared from the provable |f| bound, which is loose (docs/noise-nd.md),
 * so they are not traced: the check's one-bit margin would reject a safe
 * width.
 */
size_t np_simplexn_datapath(const np_simplexn_cfg *cfg, np_op *ops, size_t max);
void np_simplexn_trace(const np_simplexn_cfg *cfg, unsigned k, const np_simplexn_sig *s, np_trace *t, size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_SIMPLEXN_H */
