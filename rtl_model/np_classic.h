/* SPDX-License-Identifier: MIT */
/*
 * np_classic.h - the classic 3-D gradient noise unit of Perlin, "Noise
 * Hardware" (shared/seeds/002): stages L (lattice hash), H (gradient
 * contribution of each cube corner), S (s-curve 3t^2 - 2t^3 per axis) and
 * I (seven linear interpolators), with the seed's table-free hash and
 * multiply-free gradient (np_hash.h).
 *
 * This header is the bit-exact specification. Signals and formats:
 *
 *   x, y, z    u16 Q8.8   input; high byte = lattice cell (i, j, k), the lattice
 *                         tiles every 256; low byte = fraction (u, v, w).
 *   u, v, w    u8  Q0.8   fraction in the cell, value u/256 in [0, 255/256].
 *   i1,j1,k1   u8         (i + 1) mod 256 etc.: the far corners wrap.
 *   h[c]       u6         corner hash, corner c = 4*cz + 2*cy + cx (cx = 1:
 *                         the corner at i + 1), np_hash6 of the wrapped point.
 *   d          s9  Q1.8   corner-relative offset: u for cx = 0, u - 256 for
 *                         cx = 1; range [-256, 255]. Its conditional negate
 *                         needs s10 (-(-256) = 256); a -256 only ever meets
 *                         an interpolation weight s(0) = 0, so a 9-bit negate
 *                         would change g but no output bit (misread.classic3).
 *   g[c]       s11 Q2.8   gradient contribution, exact, range [-768, 768].
 *   s{x,y,z}   u(WS+1) Q1.WS  s-curve of the fraction, from the exact 24-bit
 *                         product u^2 (768 - 2u) = 2^24 s(u/256) rounded to WS
 *                         fraction bits (np_shr_round_half_up); WS = 24 is exact.
 *                         Range [0, 1]: rounding can reach 1.0 for u = 255.
 *   l1[4]      s(WL+3) Q2.WL  x-interpolations (corners paired along x), |l1| <= 2.5
 *   l2[2]      s(WL+3) Q2.WL  y-interpolations, |l2| <= 2
 *   l3         s(WL+2) Q1.WL  the z-interpolation, |l3| <= 1.5 (range argument below)
 *                         lerp(s, a, b) = round(a + s (b - a)) to WL fraction
 *                         bits, rounding once after the exact product-sum.
 *                         (The C model holds every level in int64_t; the
 *                         hardware widths are np_classic_datapath()'s.)
 *   out        sN  Q2.(N-2)  round(l3) to F = N - 2 fraction bits, saturated to
 *                         N bits (never reached: |noise| <= 1.5, see below).
 *
 * Range of the function: with gradient coefficients in {-1,0,1},
 * |noise| <= sum over axes of max_t [(1 - s(t)) t + s(t)(1 - t)] = 3 * 0.5 = 1.5,
 * so Q2.F holds every output without saturation.
 *
 * Error bound (argument; the sweep and the tests measure it). Let E_n be the
 * error of a level-n interpolation against the exact real lerp of the exact
 * inputs. With s' = s + e (|e| <= 2^-(WS+1), 0 when WS = 24) and a rounding
 * of at most 2^-(WL+1):
 *   lerp' - lerp = (1 - s')(a' - a) + s'(b' - b) + e (b - a) + rounding,
 * and 0 <= s' <= 1, |b - a| <= 6, so E_n <= E_{n-1} + 6 * 2^-(WS+1) + 2^-(WL+1)
 * with E_0 = 0 (g is exact). After three levels and the output rounding:
 *   |out - noise| <= 1/2 + 3 (3 * 2^(F-WS) + 2^(F-WL-1))  LSB.
 * The default WS = F + 6, WL = F + 5 gives <= 0.5 + 0.1875 = 0.6875 LSB:
 * every output is one of the two codes next to the true value (faithful).
 */
#ifndef NP_CLASSIC_H
#define NP_CLASSIC_H

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
    NP_CLASSIC_IN_BITS = 16,   /* x, y, z: u16 Q8.8 */
    NP_CLASSIC_FRAC_IN = 8,    /* input fraction bits */
    NP_CLASSIC_CELL_BITS = 8,  /* lattice tile of 256 */
    NP_CLASSIC_G_BITS = 11,    /* g: s11 Q2.8 */
    NP_CLASSIC_SNUM_BITS = 24, /* exact s-curve numerator, u24 Q0.24 */
    NP_CLASSIC_OUT_MIN = 2,
    NP_CLASSIC_OUT_MAX = 16,
    NP_CLASSIC_WS_MIN = 1,
    NP_CLASSIC_WS_MAX = 24,
    NP_CLASSIC_WL_MAX = 30
};

/* Configuration: every internal width that is a design choice. */
typedef struct np_classic_cfg {
    unsigned out_bits;  /* N: output sN Q2.(N-2); 2..16, default 8 */
    unsigned s_frac;    /* WS: s-curve fraction bits; 1..24, default N - 2 + 6 */
    unsigned lerp_frac; /* WL: interpolator fraction bits; N-2..30, default N - 2 + 5 */
} np_classic_cfg;

/* The faithful default for an output width (see the error bound above). */
np_classic_cfg np_classic_cfg_default(unsigned out_bits);
/* NULL when cfg is valid, else a static message naming the bad field. */
const char *np_classic_cfg_check(const np_classic_cfg *cfg);
/* Output fraction bits F = N - 2: one output LSB is 2^-F. */
static inline unsigned np_classic_out_frac(const np_classic_cfg *cfg) { return cfg->out_bits - 2u; }
/* The guaranteed error bound of the argument above, in output LSB. */
double np_classic_error_bound_lsb(const np_classic_cfg *cfg);

/* --- Datapath primitives (each one is one block of the diagram) --- */

/* S: s-curve of a u8 Q0.8 fraction, as u(WS+1) Q1.WS. */
static inline uint32_t np_classic_scurve(const np_classic_cfg *cfg, uint8_t u)
{
    uint32_t u2 = (uint32_t)u * u;                       /* u16 Q0.16 */
    uint32_t num = u2 * (uint32_t)(768u - 2u * u);       /* u24 Q0.24, exact */
    return (uint32_t)np_shr_round_half_up_u(num, NP_CLASSIC_SNUM_BITS - cfg->s_frac);
}

/*
 * I, multiply half: s * (b - a), with a and b signed and fa fraction bits,
 * s u(WS+1) Q1.WS. Exact; the product has fa + WS fraction bits.
 */
static inline int64_t np_classic_lerp_mul(uint32_t s, int64_t a, int64_t b)
{
    return (int64_t)s * (b - a);
}

/* I, add half: round(a + product) to WL fraction bits. a has fa <= WL + WS - ... bits. */
static inline int64_t np_classic_lerp_add(const np_classic_cfg *cfg, int64_t a, unsigned fa,
                                          int64_t prod)
{
    int64_t sum = np_shl(a, cfg->s_frac) + prod; /* fa + WS fraction bits, exact */
    unsigned f = fa + cfg->s_frac;
    return f >= cfg->lerp_frac ? np_shr_round_half_up(sum, f - cfg->lerp_frac)
                               : np_shl(sum, cfg->lerp_frac - f);
}

static inline int64_t np_classic_lerp(const np_classic_cfg *cfg, uint32_t s, int64_t a,
                                      int64_t b, unsigned fa)
{
    return np_classic_lerp_add(cfg, a, fa, np_classic_lerp_mul(s, a, b));
}

/* Output: round Q2.WL to Q2.F and saturate to N bits; returns the signed value. */
static inline int32_t np_classic_output(const np_classic_cfg *cfg, int64_t l3)
{
    int64_t r = np_shr_round_half_up(l3, cfg->lerp_frac - np_classic_out_frac(cfg));
    return (int32_t)np_sat_s(r, cfg->out_bits);
}

/* L + the gradient decode, done once per cell: the 8 corners' gradients. */
typedef struct np_classic_cell {
    np_grad g[8]; /* corner c = 4*cz + 2*cy + cx */
} np_classic_cell;

void np_classic_cell_setup(uint8_t i, uint8_t j, uint8_t k, np_classic_cell *cell);

/* H + S + I for a point of a cell whose corners are set up. */
static inline int32_t np_classic_eval_in_cell(const np_classic_cfg *cfg,
                                              const np_classic_cell *cell, uint8_t u, uint8_t v,
                                              uint8_t w)
{
    const int16_t d0[3] = { (int16_t)u, (int16_t)v, (int16_t)w };         /* s9 Q1.8 */
    const int16_t d1[3] = { (int16_t)(u - 256), (int16_t)(v - 256), (int16_t)(w - 256) };
    int64_t g[8];
    for (unsigned c = 0; c < 8; c++)
        g[c] = np_grad_apply_q8(cell->g[c], (c & 1u) ? d1[0] : d0[0], (c & 2u) ? d1[1] : d0[1],
                                (c & 4u) ? d1[2] : d0[2]);
    uint32_t sx = np_classic_scurve(cfg, u), sy = np_classic_scurve(cfg, v),
             sz = np_classic_scurve(cfg, w);
    unsigned fl = cfg->lerp_frac;
    int64_t l1[4], l2[2];
    for (unsigned p = 0; p < 4; p++)
        l1[p] = np_classic_lerp(cfg, sx, g[2 * p], g[2 * p + 1], NP_CLASSIC_FRAC_IN);
    for (unsigned p = 0; p < 2; p++)
        l2[p] = np_classic_lerp(cfg, sy, l1[2 * p], l1[2 * p + 1], fl);
    return np_classic_output(cfg, np_classic_lerp(cfg, sz, l2[0], l2[1], fl));
}

/* The bit-exact model: signed output value (sN Q2.(N-2)) for one input. */
int32_t np_classic_eval(const np_classic_cfg *cfg, uint16_t x, uint16_t y, uint16_t z);

/*
 * The bit-exact model over arrays: out[n] = np_classic_eval(cfg, x[n], y[n],
 * z[n]) for n < count, the same bits (fast.classic_batch_* prove it on random
 * inputs and a whole x cell). The configuration is checked once; the default
 * widths (np_classic_cfg_default(8): N = 8, WS = 12, WL = 11) run a
 * specialised int32 loop (np_classic.c gives its range argument), by hand in
 * AVX2 where the CPU has it; other configurations run the generic per-input
 * path. The arrays may not overlap out.
 */
void np_classic_eval_n(const np_classic_cfg *cfg, const uint16_t *x, const uint16_t *y,
                       const uint16_t *z, int32_t *out, size_t count);

/*
 * The batch model's implementations, each the same bits as np_classic_eval:
 *   GENERIC  np_classic_eval per input, any configuration;
 *   INT32    the default widths in an int32 loop (portable C);
 *   AVX2     the default widths, eight inputs a step with AVX2 gathers (x86-64
 *            with GCC or Clang, on a CPU with AVX2).
 * np_classic_eval_n runs the first of AVX2, INT32, GENERIC that applies.
 * np_classic_eval_n_path runs the one named, for the tests that prove each
 * path against np_classic_eval and for the bench; it returns -1 (writing
 * nothing) when that path does not apply to cfg or this CPU, else 0.
 */
enum { NP_CLASSIC_BATCH_GENERIC, NP_CLASSIC_BATCH_INT32, NP_CLASSIC_BATCH_AVX2, NP_CLASSIC_BATCH_PATHS };
int np_classic_eval_n_path(unsigned path, const np_classic_cfg *cfg, const uint16_t *x,
                           const uint16_t *y, const uint16_t *z, int32_t *out, size_t count);

/* --- Cycle-accurate model --- */

/* The signal bundle carried through the pipeline (formats as above). */
typedef struct np_classic_sig {
    uint16_t x, y, z;      /* input */
    uint8_t h[8];          /* after L */
    uint32_t s2[3];        /* after L: u^2, v^2, w^2, u16 Q0.16 (S, first half) */
    int16_t g[8];          /* after H */
    uint32_t s[3];         /* after H: sx, sy, sz (S, second half) */
    int64_t prod[4];       /* after I1m / I2m / I3m: lerp products */
    int64_t l1[4], l2[2], l3; /* after I1a, I2a, I3a */
    int32_t out;           /* after O */
} np_classic_sig;

enum { NP_CLASSIC_STAGES = 9 };
extern const np_stage_desc np_classic_stages[NP_CLASSIC_STAGES];

/* A pipe running the classic unit; cfg must outlive it. 0, or -1 on no memory. */
int np_classic_pipe_init(np_pipe *p, const np_classic_cfg *cfg);

/* --- Datapath declaration (np_datapath.h) --- */

/*
 * The operators and register bits of every stage, for cfg. Writes up to max
 * entries to ops and returns the full count. Traced signal names: "s2", "g",
 * "snum", "s", "diff1", "prod1", "sum1", "l1", "diff2", "prod2", "sum2",
 * "l2", "diff3", "prod3", "sum3", "l3", "f".
 */
size_t np_classic_datapath(const np_classic_cfg *cfg, np_op *ops, size_t max);

/*
 * Widen the traces t[0..n) whose names match the signals that stage k
 * produced in bundle s (call after applying np_classic_stages[k].fn).
 */
void np_classic_trace(const np_classic_cfg *cfg, unsigned k, const np_classic_sig *s, np_trace *t,
                      size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_CLASSIC_H */
