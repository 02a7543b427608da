/* SPDX-License-Identifier: MIT */
/*
 * np_hatch.h - the procedural hatching unit of Szécsi & Szirányi, "Recursive
 * Procedural Tonal Art Maps" (shared/seeds/003; design/scene-pipeline.md,
 * "Seed 003"; docs/hatch.md). One shading point per transaction: the colour
 * left on white paper by every stroke of every layer (Algorithm 1).
 *
 * This header is the bit-exact specification. Signals and formats (value =
 * word / 2^fraction bits; "unorm8": value = word / 255). "Rounded half up"
 * to n fraction bits is floor(v 2^n + 1/2) of the exact value: ties go
 * toward +infinity, for negative values too (Q = -2.5 ulp gives -2 ulp).
 *
 *   xu, xv    u33 Q1.32   seed-space position mod 2 (the host computes it per
 *                         span from UV and the level in 128 bits: np_hatch_xs).
 *   tone      u8 unorm8   a = tone / 255: darkness to draw (0 white, 1 black).
 *   pm        u17 Q1.16   2^-m (the host's, per span); strokes scale by 2^m.
 *   om        u17 Q1.16   1 - m; saturated to 1.0 before use: oms = min(om,
 *                         0x10000) (u17 Q1.16, stage A); only oms is used.
 *   out       u8 unorm8   the paper's colour after all strokes, round(255 c).
 *
 * Per configuration (np_hatch_cfg; per layer l < layers <= 4):
 *   b_u, b_v      N-bit patterns (N = 16 or 64), seed i = rotl_N(b, i)/(2^N-1)
 *   R             2x2 s16 Q1.14 stroke rotation R = [[c, s], [-s, c]] with
 *                 c = round(2^14 cos theta), s = round(2^14 sin theta) (sin's
 *                 sign as is): 45 deg c = s = 11585; -45 deg c = 11585,
 *                 s = -11585; 0 deg (16384, 0); 90 deg (0, 16384); 1e-4 rad
 *                 (16384, 2). Layer l's theta (PIN, rot=pin): 45, -45, 0, 90
 *                 deg for l = 0, 1, 2, 3; rot=ANGLE gives every layer ANGLE.
 *   inv_u, inv_v  u16 Q8.8 1/(F e) along and across the stroke (every layer)
 *
 * Set-up (stage A, once per point):
 *   A         u31 Q1.30   round(tone 2^30 / 255): |A - a| <= 2^-31 (a constant
 *                         multiplier; exhaustive check in test_hatch).
 *   al[l]     u31 Q1.30   clamp(4 A - l, 0, 1): layer l draws tone range
 *                         [l/4, (l+1)/4] (PIN), exact.
 *   ku, kv    u33 Q9.24   pm * inv_u, pm * inv_v, exact: 1 / (2^m F e).
 *   oms       u17 Q1.16   min(om, 0x10000).
 *   m30       u31 Q1.30   (0x10000 - oms) << 14: m = 1 - oms, exact (one by
 *                         one fading only).
 *
 * Per seed (layers l = 0, 1, ..., layers-1 in turn, within each i = 0, 1,
 * ..., N-1 counting UP, in that order: compositing order matters, and i is
 * also the seed's index in the one-by-one ramps below):
 *   W         N bits      rotl_N(b, i): wiring.
 *   st        u32 Q0.32   the first 32 bits of the periodic fraction 0.WWW...
 *                         (wiring). The exact seed is st + delta with
 *                         0 < delta < 2^-32 (the tail is never zero: W != 0).
 *   d         u33 Q1.32   x + NOT33(st) + 2^31 = x - st - 2^-32 + 1/2 (mod 2):
 *                         one 33-bit add, no carry-in. floor(d) = floor(x - s
 *                         + 1/2) EXACTLY for the exact rational s (d lies in
 *                         (e - 2^-32, e) and is a multiple of 2^-32, so no
 *                         integer lies between), so bit 32 of d is the parity
 *                         of w = floor(x_s - s_i + eta) (§5.3). The -2^-32
 *                         matters: at x = st + 1/2 (mod 1) d = 1 - 2^-32 (bit
 *                         32 even, r = 1/2 - 2^-32), where x - st + 1/2 would
 *                         give 1 (odd, r = -1/2); the exact x - s + 1/2 is
 *                         1 - delta < 1. Not x - st + 1/2, not NOT32.
 *   surv      1 bit       d_u[32] == W_u[0] and d_v[32] == W_v[0]: the seed
 *                         coincides with a seed of the sparse level (the first
 *                         bit of s_{i-1}, i.e. the last of W, is the corner the
 *                         chaos game used). Proved exhaustively in test_hatch.
 *   ru, rv    s33 Q0.32   frac(d) - 1/2 in [-1/2, 1/2): |r - r_exact| < 2^-32.
 *   qu, qv    s49 Q3.46   R (r_u, r_v), exact: qu = c ru + s rv,
 *                         qv = -s ru + c rv.
 *   Qu, Qv    s42 Q11.30  2 q k rounded half up (z = (Q + 1) / 2 addresses the
 *                         stroke, which is 0 outside (0, 1)^2, i.e. where
 *                         |Qu| >= 1 or |Qv| >= 1, compared on the Q1.30 word).
 *   y_alpha   u31 Q1.30   the stroke profile (signal "profile" in traces):
 *                         (1 - Qu^8)(1 - Qv^4) (procedural stroke: flat along,
 *                         rounded across) for |Qu| < 1 and |Qv| < 1, else 0;
 *                         u2 = round(Qu^2), u4 = round(u2^2), u8 = round(u4^2),
 *                         v2 = round(Qv^2), v4 = round(v2^2), y_alpha =
 *                         round((1 - u8)(1 - v4)), each rounded half up in Q1.30.
 *   S(t)      u31 Q1.30   smoothstep of t in [0, 1] Q1.30, no divide:
 *                         S(t) = round(round(t^2) (3 - 2t)), both products
 *                         rounded half up in Q1.30; S(0) = 0, S(1) = 1 exactly.
 *   at        u31 Q1.30   tone part. smooth: al[l]. one by one:
 *                         S(clamp((N+1) al[l] - i, 0, 1)), the ramp exact in
 *                         Q1.30 ((N+1) times the word minus i 2^30, clamped).
 *   am        u31 Q1.30   level part: 1 if surv; else smooth oms << 14, one by
 *                         one 1 - S(clamp((N+1) m30 - i, 0, 1)) (exact ramp).
 *   alpha     u31 Q1.30   round(round(at am) y_alpha), both rounded half up.
 *   c         u(F+1) Q1.F colour register, F = 8 + guard; starts at 1 (white);
 *                         c <- c - floor(alpha c / 2^30) on the words (black
 *                         ink, PIN: the ink colour is 0), i.e. c (1 - alpha)
 *                         rounded UP (ceil) to a multiple of 2^-F (toward
 *                         white), never below the exact c (1 - alpha), never
 *                         negative. Not floor(c (1 - alpha)), not rounded to
 *                         nearest.
 *   out       u8          floor((255 c + 2^(F-1)) / 2^F) on the word:
 *                         round(255 c) half up. The only tie is c = 1/2
 *                         (127.5 -> 128), since 255 is odd.
 *
 * Error bound. Let e_k be the colour error after k blends against the exact
 * c_k and da_k = |alpha_k(model) - alpha_k(exact)|. Since 0 <= alpha <= 1 and
 * 0 <= c <= 1, e_{k+1} <= e_k + da_k + 2^-F (the floor loses less than one
 * ulp, and only when alpha != 0). The output rounds once more (1/2 LSB), so
 *   |out - 255 c| <= 1/2 + 255 (n 2^-F + sum da_k)   LSB,
 * n the number of strokes with a nonzero alpha at the point. Faithful (<= 1
 * LSB) when n (2^-F + da) <= 1/510. The blends alone, n = 256 (64 seeds x 4
 * layers all covering the point): 1/2 + 255 256 2^-F <= 1 needs F >= 17, i.e.
 * guard = 9, the default; test_hatch guard_bits drives 256 blends through the
 * seed stages against the exact product of the unit's own alphas and shows 9
 * holds (max 0.78 LSB) and 8 fails (1.16 LSB). The alpha error da
 * (np_hatch_alpha_bound, below; 2^-23 .. 2^-21 for the shipped sets) adds
 * 255 n da: with the default stroke sizes at most 4 strokes per layer can
 * reach a point (the coverage lists' longest), n <= 16, so the bound is
 * 1/2 + 255 16 (2^-17 + da) <= 0.532 LSB (`noisepipe units` prints it).
 */
#ifndef NP_HATCH_H
#define NP_HATCH_H

#include <stddef.h>
#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_pipe.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_HATCH_X_BITS = 33,     /* xu, xv: u33 Q1.32 */
    NP_HATCH_X_FRAC = 32,
    NP_HATCH_M_BITS = 17,     /* pm, om: u17 Q1.16 */
    NP_HATCH_M_FRAC = 16,
    NP_HATCH_INV_FRAC = 8,    /* inv_u, inv_v: u16 Q8.8 */
    NP_HATCH_K_FRAC = 24,     /* ku, kv: u33 Q9.24 */
    NP_HATCH_R_FRAC = 14,     /* R: s16 Q1.14 */
    NP_HATCH_AF = 30,         /* alpha chain: Q1.30 */
    NP_HATCH_LAYERS_MAX = 4,
    NP_HATCH_GUARD_MAX = 22,
    NP_HATCH_LANES_MAX = 16,
    NP_HATCH_COVER_MAX = 8    /* coverage list entries per texel and layer (PIN) */
};

enum { NP_HATCH_FADE_SMOOTH = 0, NP_HATCH_FADE_ONE_BY_ONE = 1 };

/* Stroke rotations: the PIN per-layer angles, or one angle for every layer (the coverage stiff cases). */
enum { NP_HATCH_ROT_PIN = 0, NP_HATCH_ROT_0, NP_HATCH_ROT_45, NP_HATCH_ROT_90, NP_HATCH_ROT_1E4, NP_HATCH_ROTS };

/*
 * The shipped seed sets, as data (src/units/hatch_seeds.h generates and
 * checks them; `noisepipe seeds --set NAME` prints each): N-bit patterns.
 */
typedef struct np_hatch_set {
    const char *name;    /* "fkm16", "best16", "fkm64", "best64" */
    const char *origin;  /* the command that reproduces it */
    unsigned K, n;       /* N = 4^K seeds */
    uint64_t bu, bv;
    double spacing;      /* minimum toroidal spacing, 4 decimals (test_hatch seeds_shipped recomputes it) */
} np_hatch_set;
enum { NP_HATCH_SETS = 4 };
extern const np_hatch_set np_hatch_sets[NP_HATCH_SETS];

/* The configuration: every field a key of the registry entry (src/units/unit_hatch.c). */
typedef struct np_hatch_cfg {
    unsigned set;     /* index into np_hatch_sets */
    unsigned layers;  /* 1..4 */
    unsigned fade;    /* NP_HATCH_FADE_* (tone and level alike) */
    unsigned guard;   /* colour register F = 8 + guard */
    unsigned lanes;   /* P seeds per pipeline stage (cycle model); divides N */
    unsigned rot;     /* NP_HATCH_ROT_* */
    unsigned inv_u;   /* u16 Q8.8 1/(F e) along the stroke (every layer) */
    unsigned inv_v;   /* u16 Q8.8 1/(F e) across */
    /*
     * The coverage-prefiltered unit (not registry keys: the unit's vectors and
     * keys are brute force's; a scene with "hatch.mode": "coverage" sets them,
     * np_hatch_cfg_scene). cover_slots 0: brute force, every seed has a lane
     * of its own. Else each layer has cover_slots seed slots (a multiple of
     * lanes, at least the host's longest list): the point's list is read in
     * stage A and slot j of layer l evaluates the list's j-th seed when j < len
     * (alpha 0 otherwise). cover: the host's lists, read by the cycle model's
     * stage A (NULL in a gate report, which needs no data).
     */
    unsigned cover_slots;
    const struct np_hatch_cover *cover;
} np_hatch_cfg;

/* NULL when cfg is valid, else a static message naming the bad field. */
const char *np_hatch_cfg_check(const np_hatch_cfg *cfg);

/* rotl of an n-bit word by i mod n (1 <= n <= 64): seed i's pattern, wiring. */
static inline uint64_t np_hatch_rotl(uint64_t b, unsigned i, unsigned n)
{
    uint64_t m = n >= 64u ? ~(uint64_t)0 : NP_MASK(n);
    i %= n;
    return i == 0 ? b & m : ((b << i) | ((b & m) >> (n - i))) & m;
}

/* st: the first 32 bits of the periodic binary fraction 0.WWW... of an n-bit word (n = 4, 16, 64: wiring). */
static inline uint32_t np_hatch_seed_st(uint64_t w, unsigned n)
{
    if (n >= 32u)
        return (uint32_t)(w >> (n - 32u));
    uint64_t acc = 0;
    for (unsigned k = 0; k < 32u; k += n)
        acc = (acc << n) | w;
    return (uint32_t)acc;
}

/* Seeds per layer N. */
static inline unsigned np_hatch_n(const np_hatch_cfg *cfg) { return np_hatch_sets[cfg->set].n; }

/*
 * Layer l's pattern (PIN): the set's (b_u, b_v) with u complemented when
 * l & 1 and v when l & 2 (reflections of the seed square: de Bruijn and
 * spacing are kept, each layer has a pattern of its own).
 */
void np_hatch_layer_b(const np_hatch_cfg *cfg, unsigned l, uint64_t *bu, uint64_t *bv);
/* Layer l's rotation R (s16 Q1.14): PIN angles 45, -45, 0, 90 degrees, or cfg->rot's for every layer. */
void np_hatch_layer_r(const np_hatch_cfg *cfg, unsigned l, int16_t r[2][2]);

/* One seed's datapath, for tests and traces (every signal of the table). */
typedef struct np_hatch_seed_sig {
    uint64_t du, dv;       /* u33 */
    unsigned surv;
    int64_t ru, rv;        /* s33 Q0.32 */
    int64_t qu, qv;        /* s49 Q3.46 */
    int64_t Qu, Qv;        /* s42 Q11.30 */
    uint32_t profile;      /* u31 Q1.30 */
    uint32_t at, am, alpha;
} np_hatch_seed_sig;

/* The signal bundle of the cycle model (np_pipe). */
typedef struct np_hatch_sig {
    uint64_t xu, xv;        /* u33 Q1.32 */
    uint32_t tone;          /* u8 */
    uint32_t pm, om;        /* u17 Q1.16 */
    /* stage A */
    uint32_t A;             /* u31 Q1.30 */
    uint32_t al[NP_HATCH_LAYERS_MAX];
    uint32_t oms;           /* u17 Q1.16 */
    uint64_t ku, kv;        /* u33 Q9.24 */
    /* coverage (cover_slots > 0): the point's lists, read in stage A */
    uint8_t li[NP_HATCH_LAYERS_MAX][NP_HATCH_COVER_MAX]; /* seed indices, log2 N bits each */
    uint8_t ln[NP_HATCH_LAYERS_MAX];                      /* list lengths, 0..8 */
    /* seed stages */
    uint32_t pos;           /* next seed: layer * N + i (a constant per bank in hardware) */
    uint32_t c;             /* u(F+1) Q1.F */
    uint32_t nz;            /* strokes with a nonzero alpha so far (statistics, not hardware) */
    np_hatch_seed_sig last; /* the last seed's signals (traces) */
    /* stage O */
    uint32_t out;           /* u8 unorm8 */
} np_hatch_sig;

/*
 * The bound da on |alpha(model) - alpha(exact)| for one seed (the error
 * argument above; test_hatch alpha_error measures it), for pm <= pm_max:
 *   dQ  <= 2 k |R row| 2^-32 + 2^-31          (seed and r truncation; Q rounding)
 *   dy  <= 8 dQu + 4 dQv + 11 2^-31           (profile slopes; its 6 roundings)
 *   dat <= 4 2^-31 smooth; + 1.5 (N+1) 4 2^-31 + 4 2^-31 one by one
 *   dam <= 0 smooth; 4 2^-31 one by one;  da <= dat + dam + dy + 2 2^-31.
 */
double np_hatch_alpha_bound(const np_hatch_cfg *cfg, uint32_t pm_max);
/* The output bound in LSB for at most n nonzero alphas: 1/2 + 255 n (2^-F + da). */
double np_hatch_error_bound_lsb(const np_hatch_cfg *cfg, unsigned n, uint32_t pm_max);

/* Stage A: set-up of a point. */
void np_hatch_setup(const np_hatch_cfg *cfg, np_hatch_sig *s);
/* One seed (layer l, index i) on the bundle: c updated; the signals into *o (may be NULL). */
void np_hatch_seed(const np_hatch_cfg *cfg, np_hatch_sig *s, unsigned l, unsigned i, np_hatch_seed_sig *o);
/* Stage O: the output rounding. */
void np_hatch_output(const np_hatch_cfg *cfg, np_hatch_sig *s);

/* Bit-exact model, brute force: every seed of every layer. Returns out; *sig_out (may be NULL) the bundle. */
uint32_t np_hatch_eval(const np_hatch_cfg *cfg, uint64_t xu, uint64_t xv, uint32_t tone, uint32_t pm, uint32_t om,
                       np_hatch_sig *sig_out);

/*
 * Coverage lists (§6.1; built by the host, rebuilt when the artistic
 * parameters change). T = 4 * 2^K texels a side over seed space mod 1; texel
 * (tu, tv) of point x is the top log2 T fraction bits of xu, xv. Each list
 * holds, sorted by i, the seeds of one layer whose stroke at its largest size
 * (2^-m = 1/2) can have a nonzero alpha in the texel: the stroke's rotated
 * rectangle grown by a margin of 2^-20 in seed space (above the datapath's
 * rounding, < 2^-28 there) tested against the texel by separating axes.
 * Valid for pm >= 0x8000 (m < 1). More than NP_HATCH_COVER_MAX entries in a
 * list is an error (np_hatch_cover_build returns -1).
 */
typedef struct np_hatch_cover {
    unsigned t;                 /* texels a side */
    unsigned layers;
    uint8_t *len;               /* [layers][t][t] */
    uint8_t *idx;               /* [layers][t][t][NP_HATCH_COVER_MAX] */
    unsigned max_len;
    double mean_len;            /* over texels, per layer */
} np_hatch_cover;

int np_hatch_cover_build(const np_hatch_cfg *cfg, np_hatch_cover *cv);
/* The coverage unit's slots per layer for lists cv: the longest rounded up to a multiple of lanes. */
unsigned np_hatch_cover_slots(const np_hatch_cfg *cfg, const np_hatch_cover *cv);
void np_hatch_cover_free(np_hatch_cover *cv);
/* The coverage-prefiltered unit: only the listed seeds; *cycles (may be NULL): sum of ceil(len / lanes), >= 1. */
uint32_t np_hatch_eval_cover(const np_hatch_cfg *cfg, const np_hatch_cover *cv, uint64_t xu, uint64_t xv,
                             uint32_t tone, uint32_t pm, uint32_t om, unsigned *cycles);

/*
 * Zoom, in the host (§5.1): x_uv as u128 Q32.96 (UV mod 2^32), the level
 * M_f = floor(M) in [-64, 31]: x_s = (2^-M_f x_uv) mod 2 as u33 Q1.32,
 * truncated (shift right by 64 + M_f). The step per pixel is the same
 * shift of dx_uv (held mod 2^128), so for a span the host computes x_uv0 +
 * k dx_uv in 128 bits and the unit never sees the zoom: no zoom limit.
 */
uint64_t np_hatch_xs(np_u128 x_uv, int level);

/*
 * Cycle model: stages A, S0..S(G-1) (P = lanes seeds each, G = layers N / P;
 * the last also rounds the output). Coverage (cover_slots > 0): G = layers
 * cover_slots / P slot stages, stage A also reads the lists (cfg->cover).
 */
int np_hatch_pipe_init(np_pipe *p, const np_hatch_cfg *cfg);
unsigned np_hatch_depth(const np_hatch_cfg *cfg);
/* Declared widths that follow the configuration: k (u), q (s), Q (s). */
unsigned np_hatch_k_bits(const np_hatch_cfg *cfg);
unsigned np_hatch_q_bits(const np_hatch_cfg *cfg);
unsigned np_hatch_bigq_bits(const np_hatch_cfg *cfg);
/*
 * Datapath declaration for the gate report (np_datapath.h): stages A and S
 * (the G seed stages as one row). Brute force has no coverage logic;
 * fade=smooth no smoothstep; only the configured layers. Coverage adds, per
 * layer, the list memory (4 T^2 words of cover_slots log2 N + 4 bits: a RAM
 * the host writes, priced as a ROM of its size), the lists carried down the
 * banks, and per slot two N-bit rotators (W = rotl(b, i) for a variable i:
 * log2 N levels of 2:1 multiplexers), the enable j < len and alpha's gate.
 */
size_t np_hatch_datapath(const np_hatch_cfg *cfg, np_op *ops, size_t max);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_HATCH_H */
