/* SPDX-License-Identifier: MIT */
/* The hatching unit (rtl_model/np_hatch.h, docs/hatch.md) in the unit registry. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_hatch.h"
#include "np_ref.h"
#include "np_unit.h"
#include "unit_entry.h"
#include "unit_hatch.h"

_Static_assert(sizeof(np_hatch_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

static const char *set_word(unsigned v) { return v < NP_HATCH_SETS ? np_hatch_sets[v].name : NULL; }
static const char *fade_word(unsigned v)
{
    static const char *const w[] = { "smooth", "onebyone" };
    return v < 2u ? w[v] : NULL;
}
static const char *rot_word(unsigned v)
{
    static const char *const w[] = { "pin", "0", "45", "90", "1e-4" };
    return v < NP_HATCH_ROTS ? w[v] : NULL;
}

/* Stroke length 4/sqrt(N) and width 0.48/sqrt(N) of a seed tile at m = 0, as Q8.8 inverses 1/(F e). */
static unsigned inv_len_default(const void *cfg)
{
    return np_hatch_n(cfg) == 64u ? 2048u : 1024u;
}
static unsigned inv_wid_default(const void *cfg)
{
    return np_hatch_n(cfg) == 64u ? 17067u : 8533u;
}

static const np_unit_key keys[] = {
    NP_UNIT_KEY_WORDS("set", np_hatch_cfg, set, 0, NP_HATCH_SETS - 1, 1,
                      "seed set: de Bruijn patterns (noisepipe seeds --set NAME)", set_word, 0u),
    NP_UNIT_KEY("layers", np_hatch_cfg, layers, 1, NP_HATCH_LAYERS_MAX, 4,
                "cross-hatching layers l, tone range [l/4, (l+1)/4] each (PIN)"),
    NP_UNIT_KEY_WORDS("fade", np_hatch_cfg, fade, 0, 1, 0,
                      "strokes fade all at once (smooth) or one by one (smoothstep, no divide)", fade_word, 0u),
    NP_UNIT_KEY("guard", np_hatch_cfg, guard, 0, NP_HATCH_GUARD_MAX, 9,
                "colour register guard bits: F = 8 + guard (9: proven for 256 blends)"),
    NP_UNIT_KEY("lanes", np_hatch_cfg, lanes, 1, NP_HATCH_LANES_MAX, 1,
                "P: seeds per pipeline stage (a power of two dividing N)"),
    NP_UNIT_KEY_WORDS("rot", np_hatch_cfg, rot, 0, NP_HATCH_ROTS - 1, 0,
                      "stroke angles: pin (45, -45, 0, 90 degrees by layer) or one for all", rot_word, 0u),
    NP_UNIT_KEY_DERIVED("inv_len", np_hatch_cfg, inv_u, 1, 65535, inv_len_default,
                        "1/(F e) along the stroke, u16 Q8.8 (default 4.0 at N=16, 8.0 at N=64)"),
    NP_UNIT_KEY_DERIVED("inv_wid", np_hatch_cfg, inv_v, 1, 65535, inv_wid_default,
                        "1/(F e) across the stroke, u16 Q8.8 (default 33.3 at N=16, 66.7 at N=64)"),
    NP_UNIT_KEY_END,
};

static const char *cfg_check(const void *cfg) { return np_hatch_cfg_check(cfg); }

static void fields(const void *cfg, np_unit_fields *f)
{
    (void)cfg;
    memset(f, 0, sizeof *f);
    f->n_in = 5;
    f->n_out = 1;
    np_unit_set_field(&f->in[0], "xu", NP_HATCH_X_BITS, 0, NP_HATCH_X_FRAC, "u33 Q1.32 seed space");
    np_unit_set_field(&f->in[1], "xv", NP_HATCH_X_BITS, 0, NP_HATCH_X_FRAC, "u33 Q1.32 seed space");
    np_unit_set_field(&f->in[2], "tone", 8, 0, 0, "u8 unorm8 a = tone/255");
    np_unit_set_field(&f->in[3], "pm", NP_HATCH_M_BITS, 0, NP_HATCH_M_FRAC, "u17 Q1.16 2^-m");
    np_unit_set_field(&f->in[4], "om", NP_HATCH_M_BITS, 0, NP_HATCH_M_FRAC, "u17 Q1.16 1-m");
    /* frac 0: the value is the word, 255 c; the reference returns 255 c. */
    np_unit_set_field(&f->out[0], "c", 8, 0, 0, "u8 unorm8 c = word/255");
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    out[0] = np_hatch_eval(cfg, in[0], in[1], (uint32_t)in[2], (uint32_t)in[3], (uint32_t)in[4], NULL);
}

static void ref(const void *cfg, const uint64_t *in, double *out)
{
    out[0] = np_ref_hatch(cfg, in[0], in[1], (uint32_t)in[2], (uint32_t)in[3], (uint32_t)in[4], NULL);
}

/*
 * 1/2 + 255 n (2^-F + da), n the strokes that can have a nonzero alpha at one
 * point: the coverage lists' longest per layer (conservative, test_hatch
 * cover_identical), or every seed when the lists overflow.
 */
static double error_bound(const void *cfgv)
{
    const np_hatch_cfg *cfg = cfgv;
    np_hatch_cover cv;
    unsigned n = cfg->layers * np_hatch_n(cfg);
    if (np_hatch_cover_build(cfg, &cv) == 0)
        n = cfg->layers * cv.max_len;
    np_hatch_cover_free(&cv);
    return np_hatch_error_bound_lsb(cfg, n, 65536u);
}

static int pipe_init(np_pipe *p, const void *cfg) { return np_hatch_pipe_init(p, cfg); }

static void sig_set_in(void *sig, const uint64_t *in)
{
    np_hatch_sig *s = sig;
    memset(s, 0, sizeof *s);
    s->xu = in[0] & NP_MASK(NP_HATCH_X_BITS);
    s->xv = in[1] & NP_MASK(NP_HATCH_X_BITS);
    s->tone = (uint32_t)in[2] & 0xFFu;
    s->pm = (uint32_t)in[3] & (uint32_t)NP_MASK(NP_HATCH_M_BITS);
    s->om = (uint32_t)in[4] & (uint32_t)NP_MASK(NP_HATCH_M_BITS);
}

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    (void)cfg;
    out[0] = ((const np_hatch_sig *)sig)->out;
}

/* st of seed i of layer 0 on axis v (0: u, 1: v): the first 32 bits of 0.WWW..., the seed's truncation. */
static uint64_t seed_st(const np_hatch_cfg *cfg, int v, unsigned i)
{
    uint64_t bu, bv;
    unsigned n = np_hatch_n(cfg);
    np_hatch_layer_b(cfg, 0, &bu, &bv);
    return np_hatch_seed_st(np_hatch_rotl(v ? bv : bu, i, n), n);
}

/* The ceiling of seed i of layer 0 (a point at the seed: r = 0, frac(d) = 1/2 exactly up to 2^-32). */
static uint64_t seed_word(const np_hatch_cfg *cfg, int v, unsigned i)
{
    return seed_st(cfg, v, i) + 1u; /* ceil: the exact seed is above the truncation */
}

enum { HATCH_BND_MAX = 512 };

typedef struct bnd_tab {
    uint64_t (*t)[5];
    size_t n;
} bnd_tab;

static void bnd_add(bnd_tab *b, uint64_t xu, uint64_t xv, uint64_t tone, uint64_t pm, uint64_t om)
{
    if (b->n >= HATCH_BND_MAX)
        return;
    uint64_t *r = b->t[b->n++];
    r[0] = xu;
    r[1] = xv;
    r[2] = tone;
    r[3] = pm;
    r[4] = om;
}

/*
 * The output tie c = 1/2 (255 c = 127.5: round half up gives 128, the only
 * tie since 255 is odd). One stroke of alpha exactly 1/2 and no other ink:
 * a seed's centre (profile 1), tone 64 (layer 0's alpha_tone 1), om = 1/2
 * (alpha_level 1/2 where the seed does not survive; one by one, seed N/2's
 * ramp (N+1)/2 - N/2 = 1/2 gives S = 1/2 too). Which seed and tile leave
 * every other stroke off depends on the set and sizes: the first candidate
 * whose colour register is exactly 1/2 in the bit-exact model (seed N/2
 * first, then every seed; the four tiles of each), else the first candidate.
 */
static void tie_case(const np_hatch_cfg *cfg, uint64_t out[5])
{
    unsigned n = np_hatch_n(cfg);
    int found = 0;
    for (unsigned k = 0; k <= n && !found; k++) {
        unsigned i = k == 0 ? n / 2u : k - 1u;
        for (unsigned w = 0; w < 4u && !found; w++) {
            uint64_t xu = seed_word(cfg, 0, i) | (uint64_t)(w & 1u) << 32;
            uint64_t xv = seed_word(cfg, 1, i) | (uint64_t)(w >> 1) << 32;
            np_hatch_sig s;
            np_hatch_eval(cfg, xu, xv, 64u, 0x10000u, 0x8000u, &s);
            found = s.c == (uint32_t)1u << (7u + cfg->guard);
            if (found || (k == 0 && w == 0)) {
                out[0] = xu;
                out[1] = xv;
            }
        }
    }
    out[2] = 64u;
    out[3] = 0x10000u;
    out[4] = 0x8000u;
}

/*
 * Rounding probes: the internal roundings (Q, the profile, S, alpha) are
 * 2^-30 steps that an 8-bit output shows only where it changes. Along a ray
 * from a seed's centre, x(t) = x0 + t d (mod 2), the probe bisects for an
 * adjacent pair t, t + 1 (2^-32 apart) across which the model's output
 * passes a level L, and emits both points: an implementation whose alpha
 * differs by a few ulps there moves the crossing and misses one of the two.
 * Up to `levels` levels, evenly spaced between the outputs at t = 0 and at
 * t = 2^29 (1/8 of a tile).
 */
/* The ray's point t: x0 + t d (mod 2), d = -1, 0 or 1. */
static uint64_t ray_x(uint64_t x0, int d, uint64_t t)
{
    return (x0 + (uint64_t)(int64_t)d * t) & NP_MASK(NP_HATCH_X_BITS);
}

typedef struct hatch_ray {
    uint64_t xu0, xv0;
    int du, dv;
    const uint64_t *ctl; /* tone, pm, om */
} hatch_ray;

static uint32_t ray_out(const np_hatch_cfg *cfg, const hatch_ray *r, uint64_t t)
{
    return np_hatch_eval(cfg, ray_x(r->xu0, r->du, t), ray_x(r->xv0, r->dv, t), (uint32_t)r->ctl[0],
                         (uint32_t)r->ctl[1], (uint32_t)r->ctl[2], NULL);
}

static void probe_ray(const np_hatch_cfg *cfg, bnd_tab *b, uint64_t xu0, uint64_t xv0, int du, int dv,
                      const uint64_t ctl[3], unsigned levels)
{
    const hatch_ray r = { xu0, xv0, du, dv, ctl };
    const uint64_t tmax = (uint64_t)1 << 29;
    uint32_t o0 = ray_out(cfg, &r, 0), o1 = ray_out(cfg, &r, tmax);
    int up = o1 > o0;
    uint32_t span = up ? o1 - o0 : o0 - o1;
    unsigned nl = span < levels ? span : levels;
    for (unsigned k = 1; k <= nl; k++) {
        /* Level L: out(lo) on o0's side of L, out(hi) on o1's (L counts from o0 toward o1). */
        uint32_t step = (uint32_t)((uint64_t)span * k / (nl + 1u));
        uint32_t lvl = up ? o0 + (step ? step : 1u) : o0 - (step ? step : 1u);
        uint64_t lo = 0, hi = tmax;
        while (hi - lo > 1u) {
            uint64_t mid = lo + (hi - lo) / 2u;
            uint32_t om = ray_out(cfg, &r, mid);
            if (up ? om < lvl : om > lvl)
                lo = mid;
            else
                hi = mid;
        }
        bnd_add(b, ray_x(xu0, du, lo), ray_x(xv0, dv, lo), ctl[0], ctl[1], ctl[2]);
        bnd_add(b, ray_x(xu0, du, hi), ray_x(xv0, dv, hi), ctl[0], ctl[1], ctl[2]);
    }
}

/*
 * Hand-annotated boundary cases: inputs xu, xv, tone, pm, om, each with the
 * reason it is there. Rows are only ever appended (the checked-in vector
 * sets keep their earlier lines).
 */
static size_t boundary(const void *cfgv, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    const np_hatch_cfg *cfg = cfgv;
    uint64_t s0u = seed_word(cfg, 0, 0), s0v = seed_word(cfg, 1, 0);
    uint64_t s1u = seed_word(cfg, 0, 1), s1v = seed_word(cfg, 1, 1);
    const uint64_t t[][5] = {
        { 0, 0, 0, 0x10000, 0x10000 },                 /* tone 0: white paper whatever the strokes */
        { 0, 0, 255, 0x10000, 0x10000 },               /* tone 1 at the origin, level m = 0 */
        { s0u, s0v, 255, 0x10000, 0x10000 },           /* at seed 0: frac(x - s + 1/2) = 1/2, r = 0, profile 1 */
        { s0u, s0v, 255, 0, 0x10000 },                 /* 2^-m = 0: k = 0, Q = 0, every stroke covers the point */
        { s0u | (1ull << 32), s0v, 255, 0x10000, 0x10000 }, /* the same seed one tile over (w parity flips on u) */
        { s1u, s1v, 255, 0x8001, 0x0001 },             /* at seed 1, level seam: m = 1 - 2^-16, 2^-m just over 1/2 */
        { s1u, s1v, 255, 0x10000, 0x10000 },           /* the next level's side of the seam: m = 0 */
        { s1u, s1v, 128, 0xB505, 0x8000 },             /* m = 1/2 (2^-1/2 = 0xB505), tone 128 */
        { 0, 0, 1, 0x10000, 0x10000 },                 /* smallest tone: layer 0 at 4/255 */
        { 0x80000000, 0x80000000, 63, 0x10000, 0x10000 },   /* tone just below 1/4: layer 1 off */
        { 0x80000000, 0x80000000, 64, 0x10000, 0x10000 },   /* just above 1/4: layer 1 on */
        { 0x80000000, 0x80000000, 127, 0x10000, 0x10000 },  /* layer 2's edge */
        { 0x80000000, 0x80000000, 128, 0x10000, 0x10000 },
        { 0x80000000, 0x80000000, 191, 0x10000, 0x10000 },  /* layer 3's edge */
        { 0x80000000, 0x80000000, 192, 0x10000, 0x10000 },
        { 0x1FFFFFFFF, 0x1FFFFFFFF, 255, 0x10000, 0x10000 }, /* the largest x: wraps to 0 mod 2 */
        { 0xFFFFFFFF, 0xFFFFFFFF, 255, 0x10000, 0x10000 },  /* just below 1: the tile edge */
        { 0x100000000, 0x100000000, 255, 0x10000, 0x10000 }, /* exactly 1: odd tile, both parities */
        { 0x0AAAAAAAA, 0x155555555, 200, 0x10000, 0x10000 }, /* alternating bits */
        { 0x12345678, 0x87654321, 255, 0x1FFFF, 0x1FFFF },  /* pm and om at their largest: om saturates to 1 */
        { 0x12345678, 0x87654321, 255, 0x8000, 0 },       /* om = 0: non-surviving strokes vanish */
        { s0u - 0x7FFFFFFF, s0v, 255, 0x10000, 0x10000 }, /* r near -1/2: the seed's tile edge on u */
        { s0u + 0x7FFFFFFF, s0v, 255, 0x10000, 0x10000 }, /* r near +1/2 */
        { 0, 0, 255, 0x8000, 0x10000 },                 /* largest strokes (2^-m = 1/2) at the origin */
    };
    uint64_t rows[HATCH_BND_MAX][5];
    bnd_tab b = { rows, 0 };
    for (size_t k = 0; k < sizeof t / sizeof t[0]; k++)
        bnd_add(&b, t[k][0], t[k][1], t[k][2], t[k][3], t[k][4]);
    /*
     * The NOT33 edge of d: x = st + 1/2 (mod 1) exactly, where d = 1 - 2^-32
     * (parity even, r = 1/2 - 2^-32) and d without the -2^-32 would be 1
     * (odd). pm = 0 makes every stroke cover the point (Q = 0) and om = 0
     * leaves only the survivors drawing, so the survival bit of the edge seed
     * decides the colour; tone 4 (layer 0 alone, alpha_tone 16/255; one by
     * one: seeds 0 and 1) keeps c away from 0 at N = 64 (0.94^16). Seed 0
     * with both axes on the edge and seed 1 with u on the edge and v at its
     * centre, each in the four tiles (bit 32 of xu, xv).
     */
    for (unsigned i = 0; i < 2u; i++)
        for (unsigned w = 0; w < 4u; w++) {
            uint64_t eu = seed_st(cfg, 0, i) + 0x80000000u;
            uint64_t ev = i == 0 ? seed_st(cfg, 1, i) + 0x80000000u : seed_word(cfg, 1, i);
            bnd_add(&b, eu ^ (uint64_t)(w & 1u) << 32, ev ^ (uint64_t)(w >> 1) << 32, 4, 0, 0);
        }
    /* The output tie: c = 1/2 exactly, out = 128 (tie_case). */
    uint64_t tie[5] = { 0, 0, 0, 0, 0 };
    tie_case(cfg, tie);
    bnd_add(&b, tie[0], tie[1], tie[2], tie[3], tie[4]);
    /*
     * Walks that carry ink (the generic walk source's backgrounds mostly give
     * white paper): around seed 0's centre in a tile where it does not
     * survive (bit 32 of xu differs from W_u[0], of xv equals W_v[0]; bit 32
     * of d is the tile's there), tone 0x30 (layer 0 alone, alpha_tone 0.75
     * smooth, seed 0's 1 one by one), m = 0: each bit of xu, then of xv,
     * flipped in turn (33 + 33: sub-ulp moves that keep the ink up to
     * whole-tile moves); then, 2^-7 of a tile off the centre on u (Q depends
     * on k there), each bit of pm flipped (17), of om = 1 (17: below bit 16
     * om > 1 must saturate; bit 16 gives m = 1), of om = 1 - 2^-16 (16: m
     * from 2^-15 to 1/2 + 2^-16), and of the tone (8).
     */
    uint64_t b0u, b0v;
    np_hatch_layer_b(cfg, 0, &b0u, &b0v);
    uint64_t cu = s0u | (~b0u & 1u) << 32, cv = s0v | (b0v & 1u) << 32;
    for (unsigned j = 0; j < NP_HATCH_X_BITS; j++)
        bnd_add(&b, cu ^ (1ull << j), cv, 0x30, 0x10000, 0x10000);
    for (unsigned j = 0; j < NP_HATCH_X_BITS; j++)
        bnd_add(&b, cu, cv ^ (1ull << j), 0x30, 0x10000, 0x10000);
    uint64_t ou = (cu + 0x02000000u) & NP_MASK(NP_HATCH_X_BITS);
    for (unsigned j = 0; j < NP_HATCH_M_BITS; j++)
        bnd_add(&b, ou, cv, 0x30, 0x10000 ^ (1u << j), 0x10000);
    for (unsigned j = 0; j < NP_HATCH_M_BITS; j++)
        bnd_add(&b, ou, cv, 0x30, 0x10000, 0x10000 ^ (1u << j));
    for (unsigned j = 0; j < NP_HATCH_M_FRAC; j++)
        bnd_add(&b, ou, cv, 0x30, 0x10000, 0xFFFF ^ (1u << j));
    for (unsigned j = 0; j < 8u; j++)
        bnd_add(&b, ou, cv, 0x30 ^ (1u << j), 0x10000, 0x10000);
    /*
     * Rounding probes (probe_ray) from the same centre along u, v and both
     * diagonals, 8 levels each, in two settings. Tone 42 (alpha_tone 0.66,
     * and 42 2^30 / 255 has fraction .54: A rounds up) at om = 3/4: both
     * factors of alpha inexact (smooth). Tone 2 (fraction .50: A rounds up)
     * at m = 0.3 / (N + 1): one by one, seed 0's tone and level ramps are
     * fractional (S rounds), while smooth still inks faintly.
     */
    const uint64_t ctl1[3] = { 42, 0x10000, 0xC000 };
    const uint64_t ctl2[3] = { 2, 0x10000, 0x10000u - (0x10000u * 3u / (10u * (np_hatch_n(cfg) + 1u))) };
    const int dirs[4][2] = { { 1, 0 }, { 0, 1 }, { 1, 1 }, { 1, -1 } };
    for (unsigned k = 0; k < 4u; k++)
        probe_ray(cfg, &b, cu, cv, dirs[k][0], dirs[k][1], ctl1, 8u);
    for (unsigned k = 0; k < 4u; k++)
        probe_ray(cfg, &b, cu, cv, dirs[k][0], dirs[k][1], ctl2, 8u);
    /*
     * S's roundings move alpha by an ulp only for some ramp values t: four
     * more one-by-one settings (tones 1 and 3; m = 0.15 and 0.55 of the
     * first ramp step), along the diagonals, 6 levels each.
     */
    const unsigned n1 = np_hatch_n(cfg) + 1u;
    const uint64_t ctl3[4][3] = {
        { 1, 0x10000, 0x10000u - 0x10000u * 15u / (100u * n1) },
        { 3, 0x10000, 0x10000u - 0x10000u * 55u / (100u * n1) },
        { 1, 0x10000, 0x10000u - 0x10000u * 55u / (100u * n1) },
        { 3, 0x10000, 0x10000u - 0x10000u * 15u / (100u * n1) },
    };
    for (unsigned j = 0; j < 4u; j++)
        for (unsigned k = 2; k < 4u; k++)
            probe_ray(cfg, &b, cu, cv, dirs[k][0], dirs[k][1], ctl3[j], 6u);
    for (size_t k = 0; k < b.n && k < max; k++)
        for (unsigned f = 0; f < 5; f++)
            in[k][f] = rows[k][f] & (f < 2 ? NP_MASK(33) : f == 2 ? 0xFFu : NP_MASK(17));
    return b.n;
}

static size_t datapath(const void *cfg, np_op *ops, size_t max) { return np_hatch_datapath(cfg, ops, max); }

/*
 * The pipe is A then G = layers N / P identical seed stages (the last also
 * rounds the output): one point per clock, latency 1 + G. The declaration
 * shows the G seed stages as one row S (np_hatch_datapath).
 */
static int timing(const void *cfgv, np_unit_timing *t, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    const np_hatch_cfg *cfg = cfgv;
    memset(t, 0, sizeof *t);
    t->latency = np_hatch_depth(cfg);
    t->throughput = 1.0;
    snprintf(t->throughput_note, sizeof t->throughput_note, "unrolled: %u seed stages of %u lanes, one point a clock",
             np_hatch_depth(cfg) - 1u, cfg->lanes);
    return 0;
}

/* Traces: stage A's signals, S0's (every S stage is the same datapath), the output. */
static void trace(const void *cfgv, unsigned k, const void *sigv, np_trace *t, size_t n)
{
    const np_hatch_cfg *cfg = cfgv;
    const np_hatch_sig *s = sigv;
    unsigned last = np_hatch_depth(cfg) - 1u;
    for (size_t j = 0; j < n; j++) {
        const char *g = t[j].signal;
        if (k == 0u) {
            if (strcmp(g, "A") == 0)
                np_trace_add(&t[j], s->A);
            else if (strcmp(g, "al") == 0)
                for (unsigned l = 0; l < cfg->layers; l++)
                    np_trace_add(&t[j], s->al[l]);
            else if (strcmp(g, "oms") == 0)
                np_trace_add(&t[j], s->oms);
            else if (strcmp(g, "k") == 0) {
                np_trace_add(&t[j], (int64_t)s->ku);
                np_trace_add(&t[j], (int64_t)s->kv);
            }
        }
        if (k == 1u) {
            const np_hatch_seed_sig *z = &s->last;
            if (strcmp(g, "d") == 0) {
                np_trace_add(&t[j], (int64_t)z->du);
                np_trace_add(&t[j], (int64_t)z->dv);
            } else if (strcmp(g, "q") == 0) {
                np_trace_add(&t[j], z->qu);
                np_trace_add(&t[j], z->qv);
            } else if (strcmp(g, "Q") == 0) {
                np_trace_add(&t[j], z->Qu);
                np_trace_add(&t[j], z->Qv);
            } else if (strcmp(g, "profile") == 0)
                np_trace_add(&t[j], z->profile);
            else if (strcmp(g, "alpha") == 0)
                np_trace_add(&t[j], z->alpha);
            else if (strcmp(g, "c") == 0)
                np_trace_add(&t[j], s->c);
        }
        if (k == last && strcmp(g, "out") == 0)
            np_trace_add(&t[j], s->out);
    }
}

/* Besides the default: both 64-seed sets, one-by-one fading, lanes, one layer, a single angle, other guards. */
static const char *const conformance_configs[] = { "set=fkm64,fade=onebyone,lanes=4",
                                                   "set=fkm16,layers=1,rot=1e-4,guard=12,lanes=16",
                                                   "set=best64,layers=2,rot=0,guard=6,lanes=8", NULL };

/*
 * The registry's hook: a scene with a "hatch" section (docs/hatch.md,
 * "Scenes") uses the unit with its set, layers, fading and lanes, the other
 * keys at their defaults; "mode": "coverage" adds the coverage logic with the
 * host's lists for this configuration (slots: the longest list, rounded up to
 * a multiple of the lanes), brute force leaves it out. The gate report
 * (`report gates --scene`) prices the unit so.
 */
extern const np_unit np_unit_hatch;

static int cfg_scene(void *cfg, const np_unit_scene *sc, char *err, size_t errlen)
{
    const np_hatch_scene *h = sc->hatch;
    if (!h)
        return 0;
    np_hatch_cfg *c = cfg;
    char spec[160];
    snprintf(spec, sizeof spec, "set=%s,layers=%u,fade=%s,lanes=%u", np_hatch_sets[h->set].name, h->layers,
             h->fade ? "onebyone" : "smooth", h->lanes);
    if (np_unit_configure(&np_unit_hatch, c, spec, err, errlen) != 0)
        return -1;
    if (h->coverage) {
        np_hatch_cover cv;
        if (np_hatch_cover_build(c, &cv) != 0) {
            np_hatch_cover_free(&cv);
            snprintf(err, errlen, "hatch: a coverage list holds more than %d seeds", NP_HATCH_COVER_MAX);
            return -1;
        }
        c->cover_slots = np_hatch_cover_slots(c, &cv);
        np_hatch_cover_free(&cv);
    }
    return 1;
}

/* --- The hatching renderer's interface (np_unit_strokes) --- */

_Static_assert((int)NP_HATCH_LAYERS_MAX <= (int)NP_UNIT_STROKE_LAYERS_MAX, "more layers than the interface's lists");

static void st_info(const void *cfgv, np_unit_stroke_info *i)
{
    const np_hatch_cfg *cfg = cfgv;
    i->layers = cfg->layers;
    i->seeds = np_hatch_n(cfg);
    i->brute_cycles = cfg->layers * np_hatch_n(cfg) / cfg->lanes;
}

static void *st_cover_new(const void *cfg, char *err, size_t errlen)
{
    np_hatch_cover *cv = calloc(1, sizeof *cv);
    if (!cv) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    if (np_hatch_cover_build(cfg, cv) != 0) {
        snprintf(err, errlen, "hatch: a coverage list holds more than %d seeds (strokes too large)",
                 NP_HATCH_COVER_MAX);
        np_hatch_cover_free(cv);
        free(cv);
        return NULL;
    }
    return cv;
}

static void st_cover_free(void *cv)
{
    if (cv)
        np_hatch_cover_free(cv);
    free(cv);
}

static void st_cover_cfg(void *cfgv, const void *cv)
{
    np_hatch_cfg *cfg = cfgv;
    cfg->cover_slots = np_hatch_cover_slots(cfg, cv);
    cfg->cover = cv;
}

/* The list of layer l at seed-space point (xu, xv): its texel's (the top bits of each axis). */
static unsigned cover_len(const np_hatch_cover *cv, unsigned l, uint64_t xu, uint64_t xv)
{
    unsigned bits = 0;
    while ((1u << bits) < cv->t)
        bits++;
    unsigned tu = (unsigned)((xu >> (32u - bits)) & (cv->t - 1u)), tv = (unsigned)((xv >> (32u - bits)) & (cv->t - 1u));
    return cv->len[((size_t)l * cv->t + tv) * cv->t + tu];
}

static uint64_t st_eval_cover(const void *cfgv, const void *cvv, const uint64_t *in, unsigned *cycles, unsigned *len)
{
    const np_hatch_cfg *cfg = cfgv;
    const np_hatch_cover *cv = cvv;
    uint32_t out = np_hatch_eval_cover(cfg, cv, in[0], in[1], (uint32_t)in[2], (uint32_t)in[3], (uint32_t)in[4], cycles);
    for (unsigned l = 0; l < cfg->layers; l++)
        len[l] = cover_len(cv, l, in[0], in[1]);
    return out;
}

static void st_stroke(const void *cfg, const uint64_t *in, unsigned l, unsigned i, np_unit_stroke *z)
{
    np_hatch_sig sg;
    np_hatch_seed_sig o;
    memset(&sg, 0, sizeof sg);
    sg.xu = in[0];
    sg.xv = in[1];
    sg.tone = (uint32_t)in[2];
    sg.pm = (uint32_t)in[3];
    sg.om = (uint32_t)in[4];
    np_hatch_setup(cfg, &sg);
    np_hatch_seed(cfg, &sg, l, i, &o);
    z->alpha = o.alpha;
    z->am = o.am;
    z->ru = o.ru;
    z->rv = o.rv;
}

/* Seed i of layer l: rotl_N(b, i) / (2^N - 1), exactly, as Q0.96 rounded down. */
static void st_centre(const void *cfg, unsigned l, unsigned i, np_u128 *su, np_u128 *sv)
{
    unsigned n = np_hatch_n(cfg);
    uint64_t bu, bv;
    np_hatch_layer_b(cfg, l, &bu, &bv);
    np_u128 D = ((np_u128)1 << n) - 1u;
    *su = ((np_u128)np_hatch_rotl(bu, i, n) << 96) / D;
    *sv = ((np_u128)np_hatch_rotl(bv, i, n) << 96) / D;
}

static const np_unit_strokes strokes = {
    .xs = np_hatch_xs,
    .info = st_info,
    .cover_new = st_cover_new,
    .cover_free = st_cover_free,
    .cover_cfg = st_cover_cfg,
    .eval_cover = st_eval_cover,
    .stroke = st_stroke,
    .centre = st_centre,
};

const np_unit np_unit_hatch = {
    .name = "hatch",
    .summary = "procedural hatching, de Bruijn seeds, 4 layers (Szecsi & Sziranyi, RPTAM)",
    NP_UNIT_MODEL_ENTRY,
    .tolerance_lsb = 1.0,
    .timing = timing,
    .cfg_scene = cfg_scene,
    .strokes = &strokes,
};
