/* SPDX-License-Identifier: MIT */
/* The classic noise unit (rtl_model/np_classic.h) in the unit registry. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_ref.h"
#include "np_rng.h"
#include "np_unit.h"
#include "unit_entry.h"
#include "np_unit_sweep.h"

/* The registry's configuration block: the model's. */
typedef struct classic_cfg {
    np_classic_cfg c;
} classic_cfg;
_Static_assert(sizeof(classic_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

/* The faithful widths for the output width (np_classic_cfg_default) unless given. */
static unsigned s_frac_default(const void *cfg)
{
    return np_classic_cfg_default(((const classic_cfg *)cfg)->c.out_bits).s_frac;
}
static unsigned lerp_frac_default(const void *cfg)
{
    return np_classic_cfg_default(((const classic_cfg *)cfg)->c.out_bits).lerp_frac;
}

static const np_unit_key keys[] = {
    NP_UNIT_KEY("out_bits", classic_cfg, c.out_bits, NP_CLASSIC_OUT_MIN, NP_CLASSIC_OUT_MAX, 8,
                "N: output f is sN Q2.(N-2)"),
    NP_UNIT_KEY_DERIVED("s_frac", classic_cfg, c.s_frac, NP_CLASSIC_WS_MIN, NP_CLASSIC_WS_MAX, s_frac_default,
                        "WS: s-curve fraction bits (default N - 2 + 6, at most 24)"),
    /* At least out_bits - 2: the unit's cfg_check says so, as it involves two keys. */
    NP_UNIT_KEY_DERIVED("lerp_frac", classic_cfg, c.lerp_frac, 0, NP_CLASSIC_WL_MAX, lerp_frac_default,
                        "WL: interpolator fraction bits, at least N - 2 (default N - 2 + 5)"),
    NP_UNIT_KEY_END,
};

static const char *cfg_check(const void *cfg) { return np_classic_cfg_check(&((const classic_cfg *)cfg)->c); }

static void fields(const void *cfg, np_unit_fields *f)
{
    const classic_cfg *k = cfg;
    char fmt[32];
    memset(f, 0, sizeof *f);
    f->n_in = 3;
    f->n_out = 1;
    np_unit_set_field(&f->in[0], "x", 16, 0, 8, "u16 Q8.8");
    np_unit_set_field(&f->in[1], "y", 16, 0, 8, "u16 Q8.8");
    np_unit_set_field(&f->in[2], "z", 16, 0, 8, "u16 Q8.8");
    snprintf(fmt, sizeof fmt, "s%u Q2.%u", k->c.out_bits, k->c.out_bits - 2u);
    np_unit_set_field(&f->out[0], "f", k->c.out_bits, 1, k->c.out_bits - 2u, fmt);
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    const classic_cfg *k = cfg;
    int32_t v = np_classic_eval(&k->c, (uint16_t)in[0], (uint16_t)in[1], (uint16_t)in[2]);
    out[0] = np_trunc_u((uint64_t)(int64_t)v, k->c.out_bits);
}

/* np_unit.eval_n: np_classic_eval_n (its int32 default path) over chunks of the words. */
static void eval_n(const void *cfg, const uint64_t *in, uint64_t *out, size_t n)
{
    enum { CHUNK = 256 };
    const classic_cfg *k = cfg;
    uint16_t x[CHUNK], y[CHUNK], z[CHUNK];
    int32_t f[CHUNK];
    for (size_t i0 = 0; i0 < n; i0 += CHUNK) {
        size_t m = n - i0 < CHUNK ? n - i0 : CHUNK;
        np_unit_chunk_u16(in, n, 0, i0, m, x);
        np_unit_chunk_u16(in, n, 1, i0, m, y);
        np_unit_chunk_u16(in, n, 2, i0, m, z);
        np_classic_eval_n(&k->c, x, y, z, f, m);
        for (size_t i = 0; i < m; i++)
            out[i0 + i] = np_trunc_u((uint64_t)(int64_t)f[i], k->c.out_bits);
    }
}

static void ref(const void *cfg, const uint64_t *in, double *out)
{
    (void)cfg;
    out[0] = np_ref_classic3_q88((uint16_t)in[0], (uint16_t)in[1], (uint16_t)in[2]);
}

static double error_bound(const void *cfg) { return np_classic_error_bound_lsb(&((const classic_cfg *)cfg)->c); }

static size_t datapath(const void *cfg, np_op *ops, size_t max)
{
    return np_classic_datapath(&((const classic_cfg *)cfg)->c, ops, max);
}

static int pipe_init(np_pipe *p, const void *cfg) { return np_classic_pipe_init(p, &((const classic_cfg *)cfg)->c); }

static void trace(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n)
{
    np_classic_trace(&((const classic_cfg *)cfg)->c, k, sig, t, n);
}

/* Checked by the conformance test besides the default: widest, cheapest s-curve, widest s-curve. */
static const char *const conformance_configs[] = { "out_bits=16", "s_frac=6,lerp_frac=6",
                                                   "s_frac=24,lerp_frac=10", NULL };

static void sig_set_in(void *sig, const uint64_t *in)
{
    np_classic_sig *s = sig;
    memset(s, 0, sizeof *s);
    s->x = (uint16_t)in[0];
    s->y = (uint16_t)in[1];
    s->z = (uint16_t)in[2];
}

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    const classic_cfg *k = cfg;
    const np_classic_sig *s = sig;
    out[0] = np_trunc_u((uint64_t)(int64_t)s->out, k->c.out_bits);
}

/*
 * Boundary values of one 8.8 coordinate, each with the reason it is there.
 * The generator takes every combination over x, y and z.
 */
static const uint16_t boundary_axis[] = {
    0x0000, /* origin: every corner-relative offset is 0 or -1 */
    0x0001, /* smallest non-zero fraction: s(1/256) rounds to almost 0 */
    0x0080, /* fraction 1/2: s = 1/2 exactly, largest |noise| bound */
    0x00ff, /* fraction 255/256: s rounds near 1 (can reach 1.0 when WS <= 13) */
    0x0100, /* next cell, fraction 0: continuity across the face */
    0x7f80, /* mid-tile, fraction 1/2 */
    0x8000, /* cell 128: top bit of the cell index set, all others clear */
    0x5555, /* alternating bits in cell and fraction */
    0xaaaa, /* the other alternating pattern */
    0xfeff, /* last fraction before cell 255 */
    0xff00, /* cell 255, fraction 0: the far corners wrap to cell 0 */
    0xff01, /* cell 255, smallest fraction: wrap with s near 0 */
    0xff80, /* cell 255, fraction 1/2: wrap, equal weights */
    0xffff, /* 255 + 255/256, the largest input: wrap, s near 1 */
};
enum { N_AXIS = sizeof boundary_axis / sizeof boundary_axis[0] };

static size_t boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
    size_t n = 0;
    for (unsigned a = 0; a < N_AXIS; a++)
        for (unsigned b = 0; b < N_AXIS; b++)
            for (unsigned c = 0; c < N_AXIS; c++, n++)
                if (n < max) {
                    in[n][0] = boundary_axis[a];
                    in[n][1] = boundary_axis[b];
                    in[n][2] = boundary_axis[c];
                }
    return n;
}

/* --- The exhaustive sweep's kernel (np_unit.sweep_rows) --- */

/*
 * The float reference's s-curve and interpolation: the expressions of
 * ref_classic.c, the same operations in the same order, so the same doubles
 * (with -ffp-contract=off; testbench/test_sweep.c compares every bit with
 * np_ref_classic3_q88).
 */
static double ref_scurve(double t) { return t * t * (3.0 - 2.0 * t); }
static double ref_lerp(double t, double a, double b) { return a + t * (b - a); }

/*
 * The reference gradient of one corner along a row (dv, dw fixed, du the
 * corner-relative x offset varying) as g = c1 + (c2 + s * du), the very
 * double np_ref_grad(h, du, dv, dw) returns, signed zeros included.
 * np_ref_grad adds two or three terms p, q, r, each an offset or its
 * negation (multiplying by a coefficient +-1.0 from np_ref_grad gives the
 * same bits); its sums are exact (multiples of 2^-8 below 4), so only the
 * sign of a zero sum depends on the order, and IEEE addition is commutative:
 *   three terms (Appendix B: b == 0): p + (q + r) = z' + (x' + y')
 *                                     = c1 + (c2 + s du), c1 = z', c2 = y';
 *   two terms, one of them x':        x' + o = c1 + (-0 + s du), c1 = o
 *                                     (-0 + a == a for every a);
 *   two terms, no x':                 y' + z' = c1 + (-0 + s du), c1 = y' + z',
 *                                     s = +-0 with s du == -0 for every du of
 *                                     the corner (du >= 0 at cx = 0, < 0 at 1).
 */
typedef struct ref_corner {
    double c1, c2, s;
} ref_corner;

/* The gradient's coefficients, probed from np_ref_grad: a[0..2] for x, y, z, each +-1 or +-0. */
typedef struct ref_coef {
    double a[3];
} ref_coef;

static ref_coef ref_coef_of(unsigned h)
{
    ref_coef k = { { np_ref_grad(h, 1.0, 0.0, 0.0), np_ref_grad(h, 0.0, 1.0, 0.0),
                     np_ref_grad(h, 0.0, 0.0, 1.0) } };
    return k;
}

static ref_corner ref_corner_row(const ref_coef *g, unsigned cx, double dv, double dw)
{
    double ax = g->a[0], ay = g->a[1], az = g->a[2];
    ref_corner k;
    if (ax != 0.0 && ay != 0.0 && az != 0.0) {
        k.c1 = az * dw;
        k.c2 = ay * dv;
        k.s = ax;
    } else if (ax != 0.0) {
        k.c1 = ay != 0.0 ? ay * dv : az * dw;
        k.c2 = -0.0;
        k.s = ax;
    } else {
        k.c1 = ay * dv + az * dw;
        k.c2 = -0.0;
        k.s = cx ? 0.0 : -0.0;
    }
    return k;
}

/*
 * The model over rows of one cell: np_classic_eval_in_cell per input, the
 * model's own inline datapath, so the arithmetic has one definition. Inlined
 * into the two callers below so that, where the widths are constants, they
 * fold and the loop over the x fraction vectorises.
 */
NP_SWEEP_INLINE void model_rows(const np_classic_cfg *cfg, const np_classic_cell *cell, uint8_t v0,
                                uint8_t w, unsigned rows, int32_t *code)
{
    for (unsigned r = 0; r < rows; r++) {
        int32_t *out = code + (size_t)r * NP_SWEEP_ROW;
        uint8_t v = (uint8_t)(v0 + r);
        for (unsigned t = 0; t < NP_SWEEP_ROW; t++)
            out[t] = np_classic_eval_in_cell(cfg, cell, (uint8_t)t, v, w);
    }
}

/*
 * The widths the model loop is specialised for: the default's. Used only
 * when a configuration equals it field for field, so it cannot make a result
 * wrong; if the default changes, the default merely runs the general loop.
 */
static const np_classic_cfg fast_cfg = { .out_bits = 8, .s_frac = 12, .lerp_frac = 11 };

static int is_fast_cfg(const np_classic_cfg *c)
{
    return c->out_bits == fast_cfg.out_bits && c->s_frac == fast_cfg.s_frac &&
           c->lerp_frac == fast_cfg.lerp_frac;
}

NP_SWEEP_CLONES static void model_rows_fast(const np_classic_cell *cellp, uint8_t v0, uint8_t w,
                                            unsigned rows, int32_t *code)
{
    const np_classic_cell cell = *cellp;
    model_rows(&fast_cfg, &cell, v0, w, rows, code);
}

NP_SWEEP_CLONES static void model_rows_any(const np_classic_cfg *cfgp,
                                           const np_classic_cell *cellp, uint8_t v0, uint8_t w,
                                           unsigned rows, int32_t *code)
{
    /* Local copies: the stores to code[] cannot alias them, so they stay loop-invariant. */
    const np_classic_cfg cfg = *cfgp;
    const np_classic_cell cell = *cellp;
    model_rows(&cfg, &cell, v0, w, rows, code);
}

/*
 * The reference over rows of cell (i, j, k): the in-cell form of
 * np_ref_classic3 with the hash, the s-curves and the gradients' y and z
 * terms hoisted out of the row.
 */
NP_SWEEP_CLONES static void ref_rows(uint8_t i, uint8_t j, uint8_t k, uint8_t v0, uint8_t w,
                                     unsigned rows, double *ref)
{
    ref_coef co[8];
    for (unsigned c = 0; c < 8; c++)
        co[c] = ref_coef_of(np_hash6((uint8_t)(i + (c & 1u)), (uint8_t)(j + (c >> 1 & 1u)),
                                     (uint8_t)(k + (c >> 2 & 1u))));
    double du0[NP_SWEEP_ROW], sx[NP_SWEEP_ROW];
    for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
        du0[t] = (double)t / 256.0; /* x - floor(x) of np_ref_classic3, exact */
        sx[t] = ref_scurve(du0[t]);
    }
    double dw = (double)w / 256.0, sz = ref_scurve(dw);
    for (unsigned r = 0; r < rows; r++) {
        double dv = (double)(uint8_t)(v0 + r) / 256.0, sy = ref_scurve(dv);
        ref_corner kc[8];
        for (unsigned c = 0; c < 8; c++)
            kc[c] = ref_corner_row(&co[c], c & 1u, (c & 2u) ? dv - 1.0 : dv,
                                   (c & 4u) ? dw - 1.0 : dw);
        double *out = ref + (size_t)r * NP_SWEEP_ROW;
        for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
            double u0 = du0[t], u1 = u0 - 1.0, s = sx[t], g[8];
            for (unsigned c = 0; c < 8; c++)
                g[c] = kc[c].c1 + (kc[c].c2 + kc[c].s * ((c & 1u) ? u1 : u0));
            double a = ref_lerp(s, g[0], g[1]), b = ref_lerp(s, g[2], g[3]);
            double c0 = ref_lerp(sy, a, b);
            a = ref_lerp(s, g[4], g[5]);
            b = ref_lerp(s, g[6], g[7]);
            double c1 = ref_lerp(sy, a, b);
            out[t] = ref_lerp(sz, c0, c1);
        }
    }
}

static void sweep_rows(const void *cfgv, uint16_t x0, uint16_t y0, uint16_t z, unsigned rows,
                       unsigned what, int32_t *code, double *ref)
{
    const np_classic_cfg *cfg = &((const classic_cfg *)cfgv)->c;
    uint8_t i = (uint8_t)(x0 >> 8), j = (uint8_t)(y0 >> 8), k = (uint8_t)(z >> 8);
    uint8_t v0 = (uint8_t)y0, w = (uint8_t)z;
    if (what & NP_SWEEP_MODEL) {
        np_classic_cell cell;
        np_classic_cell_setup(i, j, k, &cell);
        if (is_fast_cfg(cfg))
            model_rows_fast(&cell, v0, w, rows, code);
        else
            model_rows_any(cfg, &cell, v0, w, rows, code);
    }
    if (what & NP_SWEEP_REF)
        ref_rows(i, j, k, v0, w, rows, ref);
}

/* --- The adversarial search's classes (np_unit.adversarial, docs/search.md) --- */

enum { ADV_FRACS = 256, ADV_TOP = 16, ADV_D_MAX = 2 * 768 }; /* |g1 - g0| <= 1536 in Q.8 LSB */

/*
 * The s-curve rounding's error at fraction u, in s LSB (2^-WS): the exact
 * u24 numerator u^2 (768 - 2u) rounded half up to WS bits; 0 when WS = 24.
 */
static double adv_scurve_err(const np_classic_cfg *c, unsigned u)
{
    uint32_t num = (uint32_t)u * u * (768u - 2u * u);
    unsigned k = NP_CLASSIC_SNUM_BITS - c->s_frac;
    return ((double)np_classic_scurve(c, (uint8_t)u) * ldexp(1.0, (int)k) - (double)num) / ldexp(1.0, (int)k);
}

/*
 * The largest level-1 error at fraction u, in output LSB: over every
 * difference d = b - a of two gradient contributions (Q.8, |d| <= 1536) and
 * every value of a's bits that the rounding sees (a's low 8 - WL bits when
 * WL < 8; none otherwise), |lerp'(s', a, a + d) - (a + s d)|: the s-curve's
 * rounding times d plus the interpolator's rounding to WL bits, exactly as
 * np_classic_lerp does it.
 */
static double adv_lerp_loss(const np_classic_cfg *c, unsigned u)
{
    uint32_t sq = np_classic_scurve(c, (uint8_t)u);
    double s_exact = (double)((uint32_t)u * u * (768u - 2u * u)) / 16777216.0;
    int f = (int)np_classic_out_frac(c);
    int64_t a_n = c->lerp_frac < NP_CLASSIC_FRAC_IN ? (int64_t)1 << (NP_CLASSIC_FRAC_IN - c->lerp_frac) : 1;
    double worst = 0.0;
    for (int64_t a = 0; a < a_n; a++)
        for (int64_t d = -ADV_D_MAX; d <= ADV_D_MAX; d++) {
            int64_t l = np_classic_lerp(c, sq, a, a + d, NP_CLASSIC_FRAC_IN);
            double exact = ((double)a + s_exact * (double)d) / 256.0;
            double e = fabs(ldexp((double)l, -(int)c->lerp_frac) - exact) * ldexp(1.0, f);
            worst = e > worst ? e : worst;
        }
    return worst;
}

/* Fractions ranked by a score, largest first (ties: the smaller fraction). */
static void adv_rank(const double *score, uint8_t *top)
{
    unsigned char used[ADV_FRACS] = { 0 };
    for (unsigned k = 0; k < ADV_TOP; k++) {
        unsigned best = 0;
        int have = 0;
        for (unsigned u = 0; u < ADV_FRACS; u++)
            if (!used[u] && (!have || score[u] > score[best])) {
                best = u;
                have = 1;
            }
        used[best] = 1;
        top[k] = (uint8_t)best;
    }
}

/*
 * The worst-rounding fractions of a configuration: the ADV_TOP fractions
 * whose s-curve rounding is closest to 1/2 LSB and the ADV_TOP whose level-1
 * interpolation loses most. Kept per thread for the last configuration (the
 * lerp ranking costs 256 * 3073 interpolations).
 */
typedef struct adv_fracs {
    np_classic_cfg c;
    int valid;
    uint8_t top[2 * ADV_TOP];
} adv_fracs;

static const uint8_t *adv_worst_fracs(const np_classic_cfg *c)
{
    static _Thread_local adv_fracs cache;
    if (cache.valid && cache.c.out_bits == c->out_bits && cache.c.s_frac == c->s_frac &&
        cache.c.lerp_frac == c->lerp_frac)
        return cache.top;
    double sc[ADV_FRACS], lc[ADV_FRACS];
    for (unsigned u = 0; u < ADV_FRACS; u++) {
        sc[u] = fabs(adv_scurve_err(c, u));
        lc[u] = adv_lerp_loss(c, u);
    }
    adv_rank(sc, cache.top);
    adv_rank(lc, cache.top + ADV_TOP);
    cache.c = *c;
    cache.valid = 1;
    return cache.top;
}

/*
 * NP_ADV_ROUNDING: each axis's fraction from the worst-rounding list (the
 * s-curve's or the interpolator's), its cell random (the cells pick the
 * gradients, hence the differences the roundings are multiplied by).
 * NP_ADV_FACES: none beyond the search's lattice faces (the cell faces are
 * fraction 0).
 */
static size_t adversarial(const void *cfgv, unsigned cls, np_rng *r, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t n)
{
    if (cls != NP_ADV_ROUNDING)
        return 0;
    const uint8_t *top = adv_worst_fracs(&((const classic_cfg *)cfgv)->c);
    for (size_t i = 0; i < n; i++)
        for (unsigned a = 0; a < 3; a++) {
            uint64_t w = np_rng_next(r);
            in[i][a] = (w >> 56 << 8) | top[(w >> 8) % (2u * ADV_TOP)];
        }
    return n;
}

/* The output rounded to WL bits (out_bits = WL + 2), or to 14 when WL > 14: the error before O's rounding. */
static void fine_cfg(const void *cfg, void *fine)
{
    classic_cfg *k = fine;
    *k = *(const classic_cfg *)cfg;
    k->c.out_bits = k->c.lerp_frac + 2u < NP_CLASSIC_OUT_MAX ? k->c.lerp_frac + 2u : NP_CLASSIC_OUT_MAX;
}

const np_unit np_unit_classic3 = {
    .name = "classic3",
    .summary = "classic 3-D gradient noise, 8.8 inputs, L/H/S/I pipeline (Perlin, Noise Hardware)",
    NP_UNIT_MODEL_ENTRY,
    .tolerance_lsb = 1.0,
    .sweep_rows = sweep_rows,
    .adversarial = adversarial,
    .fine_cfg = fine_cfg,
    .eval_n = eval_n,
};
