/* SPDX-License-Identifier: MIT */
/*
 * np_aacount.h - the sample-count unit `aacount` of Hollaender, Boubekeur and
 * Eisemann, "Adaptive Supersampling for Deferred Anti-Aliasing" (JCGT 2013,
 * shared/seeds/001; PIN choices: shared/design/scene-pipeline.md, "Seed 001").
 * Per pixel it reads the m x m window of the G-buffer and five lumas of the
 * one-sample image S and says how many samples s to shade and which (mask).
 * Exact integers throughout: no divide, no square root, no rounding; the host
 * turns the real constants into integer threshold registers (np_aacount_regs).
 *
 * This header is the bit-exact specification. Signals and formats
 * (n = m^2 samples, i = sample index b*m + a of sample (a, b)):
 *
 *   d[i]     u24 Q0.24  linear view depth over the scene's depth range
 *   nrm[i]   3 x s8 Q0.7 normal (x, y, z); (0,0,0) = no surface: the sample
 *                       takes no part in the cone test (background)
 *   luma[5]  u8         Y = (77R + 150G + 29B + 128) >> 8 of S at the pixel
 *                       (centre) and its left, right, upper, lower neighbour,
 *                       border-clamped by the host
 *   sum_d    u28        sum d[i]            (16 (2^24 - 1) < 2^28)
 *   sum_d2   u52        sum d[i]^2          (16 (2^24 - 1)^2 < 2^52)
 *   v        u56        n sum_d2 - sum_d^2 = n^2 Var(d) exactly, >= 0
 *                       (Cauchy-Schwarz); n sum_d2 < 2^56, sum_d^2 < 2^56;
 *                       v itself <= floor(n^2 / 4) (2^24 - 1)^2 < 2^54 (half the
 *                       samples at 0, half at 2^24 - 1), the width the datapath
 *                       declares per m (m = 3: 53 bits)
 *   nbar[3]  s12        sum nrm[i]          (16 x [-128, 127] = [-2048, 2032])
 *   dot[i]   s21        nbar . nrm[i]       (|.| <= 3 * 2048 * 128 < 2^20)
 *   nb2      u24        |nbar|^2            (<= 3 * 2048^2 < 2^24)
 *   nn2[i]   u16        |nrm[i]|^2          (<= 3 * 128^2 < 2^16)
 *   p[i]     u40        dot^2 = (|cos| |nbar| |n|)^2, p <= q (Cauchy-Schwarz)
 *   q[i]     u40        nb2 * nn2           (< 2^40)
 *   pmin,qmin u40       the sample with the least p/q (cross products p q' < p' q,
 *                       u80, exact; ties keep the earlier sample)
 *   lmax,lmin u8        over the 4 neighbours (luma_taps=4) or all 5 (luma_taps=5)
 *   r        u8         lmax - lmin
 *   sd,sn,ss u5         the count of each metric, 1..n; 0 when the metric is
 *                       not built (key off): s = clamp(ceil(k_x), 1, n)
 *   s        u5         max(sd, sn, ss), at least 1
 *   mask     u16        bit i set iff B_m[b][a] < s (the paper's matrices, below)
 *
 * The metrics (the paper's section 3.1; c_d, c_n, c_s are three constants, PIN):
 *   k_d = c_d Var(d / 2^24)                  = c_d v / (n^2 2^48)
 *   k_n = c_n sqrt(1 - min_i |nbar.nrm[i]| / (|nbar| |nrm[i]|))  (normalised, PIN)
 *   k_s = 0 if r < max(t_min, lmax t_edge), else c_s r / 255    (lumas on [0, 1])
 *   s   = clamp(ceil(max(k_d, k_n, k_s)), 1, n)
 * Since s >= j + 1 iff k > j (j integer), s = 1 + #{ j in 1..n-1 : k > j }, and
 * each metric's "k_x > j" is one integer comparison against a register:
 *   depth   k_d > j  iff  v >= vd[j],  vd[j] = floor(j n^2 2^48 / c_d) + 1
 *           (vd = 2^56 exactly - never, as v < 2^56 - when c_d = 0 or when
 *           floor(j n^2 2^48 / c_d) + 1 would reach 2^56)
 *   normal  with C the c_n register (u8 Q6.2: the code of 4 c_n, c_n the real
 *           constant): k_n > j iff min|cos| < a_j =
 *           (C^2 - 16 j^2) / C^2; never when a_j <= 0 (C^2 <= 16 j^2; the
 *           square below would lose the sign); otherwise, both sides being
 *           >= 0, iff min p/q < a_j^2 iff pmin nd < na[j] qmin with
 *           nd = C^4 (u32) and na[j] = (C^2 - 16 j^2)^2 (u32): two u72
 *           products. |cos| is taken by squaring: the sign of dot is
 *           irrelevant, as the paper's abs() says.
 *           nbar = 0 with some nrm[i] != 0 (normals that cancel) gives
 *           sn = n (PIN) when c_n > 0 (c_n = 0: sn = 1, so that c = 0 gives
 *           S alone); no nrm[i] != 0 at all gives sn = 1. Identical
 *           normals give p = q exactly whatever |nrm| is, so min p/q = 1
 *           and sn = 1: never a NaN, never a spurious sample.
 *   luma    the gate r < t_min or 256 r < t_edge lmax (t_min u8 on the luma
 *           scale, t_edge u8 Q0.8: 32 = 1/8 is 8 r < lmax, exactly the
 *           paper's r < lmax / 8; a floor(lmax / 8) compare would not be:
 *           lmax = 9, r = 1) gives ss = 1; otherwise k_s > j iff
 *           r >= rs[j], rs[j] = min(floor(255 * 16 j / C_s) + 1, 256) (C_s the
 *           c_s register, u16 Q12.4, the code of 16 c_s; rs = 256 means never,
 *           as r <= 255: when C_s = 0, or when the quotient + 1 exceeds 255).
 * Every register is the exact integer image of its real comparison, so the
 * counts equal the exact rational reference (src/ref/ref_aacount.c) on every
 * window: there is no rounding anywhere to bound.
 *
 * Sample choice (section 3.2), the paper's matrices used literally, B[b][a]:
 *   B2 = [[0,2],[3,1]]  B3 = [[2,6,3],[5,0,8],[1,7,4]]
 *   B4 = [[1,8,2,10],[12,4,14,6],[3,11,0,9],[15,7,13,5]]
 * Index 0 is the sample S was shaded at (for m = 3 the pixel centre).
 *
 * Resolve: the mean of the s shaded samples per channel, sum u12 (<= 16 x 255),
 *   out = (sum * rom[s] + 2^16) >> 17,  rom[s] = ceil(2^17 / s)  (16 x u18 ROM,
 *   a 12 x 18 product and a constant add), which is round-half-up(sum / s) =
 * floor((2 sum + s) / (2 s)) for every s in 1..16 and every sum in 0..255 s
 * (proved exhaustively: aacount.resolve_exhaustive; 17 is the least fraction
 * width: with 16, 102 pairs round wrong). Why it holds: rom = (2^17 + e) / s,
 * 0 <= e < s, so sum * rom / 2^17 = sum / s + sum e / (s 2^17), and the added
 * term (< 255 * 15 / 2^17 < 1/32) never carries sum / s + 1/2 across an
 * integer: sum / s + 1/2 is a multiple of 1 / (2 s) and so at least 1 / (2 s)
 * below the next integer unless it is one. The G-buffer renderer
 * (src/render/np_gbuf.h) calls this resolve and np_aacount_mask: the one
 * definition of the matrices and the ROM.
 *
 * Tile option (the paper's Fig. 6c): tile = 6 replaces every s of a 6 x 6 block
 * of pixels by the block's maximum (np_aacount_tile_max), after the unit.
 */
#ifndef NP_AACOUNT_H
#define NP_AACOUNT_H

#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_pipe.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_AAC_M_MAX = 4,
    NP_AAC_N_MAX = 16,
    NP_AAC_DEPTH_BITS = 24, /* d: u24 Q0.24 */
    NP_AAC_NRM_BITS = 8,    /* each normal component: s8 Q0.7 */
    NP_AAC_LUMA_BITS = 8,
    NP_AAC_LUMAS = 5,       /* centre, left, right, up, down */
    NP_AAC_V_BITS = 56,
    NP_AAC_S_BITS = 5,
    NP_AAC_MASK_BITS = 16,
    NP_AAC_ROM_FRAC = 17,   /* rom[s] = ceil(2^17 / s): u18 */
    NP_AAC_ROM_BITS = 18,
    NP_AAC_TILE = 6,
    NP_AAC_PIPE_STAGES = 4  /* A, V, P, C (parallel variant) */
};

/* The never-firing depth threshold: above every v (v < 2^56). */
#define NP_AAC_VD_NEVER ((uint64_t)1 << NP_AAC_V_BITS)

/* Configuration: the unit's keys (src/units/unit_aacount.c has their table). */
typedef struct np_aacount_cfg {
    uint8_t m;         /* 1..4, n = m^2 */
    uint8_t depth;     /* 1: depth-variance metric built */
    uint8_t normal;    /* 1: normal-cone metric built */
    uint8_t luma;      /* 1: luma-range metric built */
    uint8_t luma_taps; /* 4: the four neighbours (the paper); 5: and the centre (FXAA) */
    uint8_t tile;      /* 0, or 6: the 6 x 6 tile maximum after the unit */
    uint8_t serial;    /* 0: parallel (one window a clock); 1: serial (one beat a clock) */
    uint8_t c_n;       /* the code C itself, u8 Q6.2: the real constant c_n = C / 4 (key c_n=32: c_n = 8) */
    uint32_t c_d;      /* c_d, u32, per (depth range)^2 */
    uint16_t c_s;      /* the code C_s itself, u16 Q12.4: the real c_s = C_s / 16 per luma range [0, 1] (key 128: 8) */
    uint8_t t_min;     /* luma code: t_min = t_min / 255 (PIN 16) */
    uint8_t t_edge;    /* Q0.8: t_edge = t_edge / 256 (PIN 32 = 1/8) */
} np_aacount_cfg;

/* The host-computed threshold registers (np_aacount_regs_compute), index j = 1..n-1. */
typedef struct np_aacount_regs {
    uint64_t vd[NP_AAC_N_MAX]; /* u57: k_d > j iff v >= vd[j] */
    uint32_t na[NP_AAC_N_MAX]; /* u32: (C^2 - 16 j^2)^2 */
    uint8_t na_on[NP_AAC_N_MAX]; /* 0: a_j <= 0, never */
    uint32_t nd;               /* u32: C^4 */
    uint16_t rs[NP_AAC_N_MAX]; /* u9: k_s > j iff r >= rs[j] */
    uint8_t t_min, t_edge;     /* the luma gate, as keyed */
} np_aacount_regs;

/* One window: the unit's inputs. */
typedef struct np_aacount_win {
    uint32_t d[NP_AAC_N_MAX];
    int8_t nrm[NP_AAC_N_MAX][3];
    uint8_t luma[NP_AAC_LUMAS];
} np_aacount_win;

typedef struct np_aacount_out {
    uint8_t s, sd, sn, ss;
    uint16_t mask;
} np_aacount_out;

/* The signal bundle of the cycle model (parallel variant), stage by stage. */
typedef struct np_aacount_sig {
    uint64_t bus[8];  /* the window bus as it arrives (np_aacount_sig_in_bus), or unused */
    uint8_t from_bus; /* 1: stage A first wires bus into w */
    np_aacount_win w;
    /* A: sums */
    uint32_t sum_d;
    uint64_t sum_d2;
    int32_t nbar[3];
    uint8_t lmax, lmin, any_n;
    /* V: variance, dots, norms, luma range and gate */
    uint64_t v;
    int32_t dot[NP_AAC_N_MAX];
    uint32_t nb2, nn2[NP_AAC_N_MAX];
    uint8_t r, gate;
    /* P: squares, the least ratio, depth and luma counts */
    uint64_t p[NP_AAC_N_MAX], q[NP_AAC_N_MAX];
    uint64_t pmin, qmin;
    uint8_t have_min;
    uint8_t sd, ss;
    /* C: normal count, s, mask */
    uint8_t sn, s;
    uint16_t mask;
} np_aacount_sig;

/* The paper's index matrices: B_m[b][a] (m = 1..4; m = 1: {0}). */
unsigned np_aacount_bayer(unsigned m, unsigned a, unsigned b);

/* NULL when cfg is consistent, else a message. */
const char *np_aacount_cfg_check(const np_aacount_cfg *cfg);
np_aacount_cfg np_aacount_cfg_default(void);

/* The host's threshold registers for cfg (exact integer arithmetic, no float). */
void np_aacount_regs_compute(const np_aacount_cfg *cfg, np_aacount_regs *r);

/* The bit-exact model: with registers r (any values: tests load them directly). */
void np_aacount_eval_regs(const np_aacount_cfg *cfg, const np_aacount_regs *r, const np_aacount_win *w,
                          np_aacount_out *o);
/* The same with the registers of cfg. */
void np_aacount_eval(const np_aacount_cfg *cfg, const np_aacount_win *w, np_aacount_out *o);

/* The mask of s samples for m (bit b*m + a set iff B_m[b][a] < s). */
uint16_t np_aacount_mask(unsigned m, unsigned s);

/* Resolve one channel: round-half-up(sum / s), s in 1..16, sum <= 255 s. */
uint8_t np_aacount_resolve(uint32_t sum, unsigned s);
/* The reciprocal ROM word of s (1..16): ceil(2^17 / s), u18. */
uint32_t np_aacount_rom(unsigned s);

/*
 * The 6 x 6 tile maximum over a w x h image of counts (row-major): each s of
 * a tile (tiles from (0, 0); the last row and column of tiles may be partial)
 * becomes the tile's maximum.
 */
void np_aacount_tile_max(uint8_t *s, unsigned w, unsigned h);

/* --- The window bus of the registry's vectors (a vector line carries one window) --- */

/*
 * Bits of the window bus: beat i (sample index i = b m + a) occupies bits
 * [i B, (i + 1) B), B = 24 (when depth is built) + 24 (when normal is built),
 * and holds from its lowest bit up: d (24), then nx, ny, nz (8 each, two's
 * complement). After the n beats, at bit n B, the five lumas, 8 bits each
 * from the lowest up: centre, left, right, up, down (40 bits, when luma is
 * built). The bus is cut into 64-bit words w0 (bits 0..63, the vector's first
 * input word), w1, ...; the last word holds what is left (its upper bits are
 * not part of the bus); at most 8 words (512 bits). A sample whose normal is
 * (0,0,0) takes no part in the cone test (nor in nbar).
 */
unsigned np_aacount_bus_bits(const np_aacount_cfg *cfg);
void np_aacount_bus_pack(const np_aacount_cfg *cfg, const np_aacount_win *w, uint64_t *words);
void np_aacount_bus_unpack(const np_aacount_cfg *cfg, const uint64_t *words, np_aacount_win *w);

/* --- The cycle-accurate models --- */

/*
 * Parallel variant: an np_pipe of NP_AAC_PIPE_STAGES stages over
 * np_aacount_sig (A: sums; V: variance, dots, norms, luma range; P: squares,
 * least ratio, depth and luma counts; C: normal count, max, mask), one window
 * a clock, latency 4. cfg is an np_aacount_cfg.
 */
int np_aacount_pipe_init(np_pipe *p, const np_aacount_cfg *cfg);
void np_aacount_sig_in(np_aacount_sig *s, const np_aacount_win *w);
/* The same from the window bus (the registry's input words, np_aacount_bus_pack's layout). */
void np_aacount_sig_in_bus(np_aacount_sig *s, const uint64_t *words);
void np_aacount_sig_out(const np_aacount_sig *s, np_aacount_out *o);

/*
 * Serial variant: one G-buffer beat a clock. Pass 1 accumulates sum_d, sum_d2,
 * nbar over n beats while the normals go into a buffer of n x 24 bits; pass 2
 * (the next n clocks, overlapped with the next window's pass 1: two buffers)
 * computes each beat's p, q and the running least ratio; then one clock of
 * counts and mask. A window every n clocks, latency 2n clocks from its first
 * beat (np_aacount_serial_latency).
 */
typedef struct np_aacount_serial {
    const np_aacount_cfg *cfg;
    np_aacount_regs regs;
    /* pass 1 */
    np_aacount_sig acc;
    unsigned beat;
    int acc_full;
    /* pass 2 */
    np_aacount_sig cmp;
    unsigned cbeat;
    int cmp_busy;
    /* the result register */
    np_aacount_out out;
    int out_valid;
    uint64_t cycles;
} np_aacount_serial;

void np_aacount_serial_init(np_aacount_serial *u, const np_aacount_cfg *cfg);
/*
 * One clock. in_valid: beat i of window w is offered (i = the unit's own beat
 * counter; the window's lumas ride on its first beat). Returns 1 when the
 * beat was taken. After the clock, u->out_valid says a result is in u->out
 * (held for one clock).
 */
int np_aacount_serial_clock(np_aacount_serial *u, int in_valid, const np_aacount_win *w);
/* Clocks from a window's first beat to its result, and between windows. */
unsigned np_aacount_serial_latency(const np_aacount_cfg *cfg);

/* --- Datapath declaration and trace --- */

/* The datapath of cfg's variant (serial or parallel) for the gate report; see np_datapath.h. */
size_t np_aacount_datapath(const np_aacount_cfg *cfg, np_op *ops, size_t max);
/* Widen the traces of the signals stage k (0..3) produced, from bundle s. */
void np_aacount_trace(const np_aacount_cfg *cfg, unsigned k, const np_aacount_sig *s, np_trace *t, size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_AACOUNT_H */
