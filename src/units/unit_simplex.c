/* SPDX-License-Identifier: MIT */
/* The simplex noise unit (rtl_model/np_simplex.h) in the unit registry. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_ref.h"
#include "np_rng.h"
#include "np_simplex.h"
#include "np_unit.h"
#include "unit_entry.h"
#include "np_unit_sweep.h"

/* The registry's configuration block: the model's. */
typedef struct simplex_cfg {
    np_simplex_cfg c;
} simplex_cfg;
_Static_assert(sizeof(simplex_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

/* The faithful internal widths for the output widths and deriv (np_simplex_cfg_default) unless given. */
static np_simplex_cfg faithful(const void *cfg)
{
    const np_simplex_cfg *c = &((const simplex_cfg *)cfg)->c;
    return np_simplex_cfg_default(c->out_bits, c->dout_bits, c->deriv);
}
static unsigned t_frac_default(const void *cfg) { return faithful(cfg).t_frac; }
static unsigned p_frac_default(const void *cfg) { return faithful(cfg).p_frac; }
static unsigned k_frac_default(const void *cfg) { return faithful(cfg).k_frac; }

static const np_unit_key keys[] = {
    NP_UNIT_KEY("out_bits", simplex_cfg, c.out_bits, NP_SIMPLEX_OUT_MIN, NP_SIMPLEX_OUT_MAX, 16,
                "N: f is sN Q-1.N"),
    NP_UNIT_KEY("dout_bits", simplex_cfg, c.dout_bits, NP_SIMPLEX_DOUT_MIN, NP_SIMPLEX_OUT_MAX, 16,
                "ND: df/dx, df/dy, df/dz are sND Q1.(ND-2)"),
    NP_UNIT_KEY("deriv", simplex_cfg, c.deriv, 0, 1, 1, "1: the derivative datapath is present; 0: f only"),
    NP_UNIT_KEY_DERIVED("t_frac", simplex_cfg, c.t_frac, 1, NP_SIMPLEX_WT_MAX, t_frac_default,
                        "WT: fraction bits of tau^2, tau^3, tau^4 (default: faithful for the outputs)"),
    NP_UNIT_KEY_DERIVED("p_frac", simplex_cfg, c.p_frac, 1, NP_SIMPLEX_WP_MAX, p_frac_default,
                        "WP: fraction bits of products and sums (default: faithful for the outputs)"),
    NP_UNIT_KEY_DERIVED("k_frac", simplex_cfg, c.k_frac, 1, NP_SIMPLEX_WK_MAX, k_frac_default,
                        "WK: fraction bits of the output constants (default: faithful for the outputs)"),
    NP_UNIT_KEY_END,
};

static const char *cfg_check(const void *cfg) { return np_simplex_cfg_check(&((const simplex_cfg *)cfg)->c); }

static void fields(const void *cfg, np_unit_fields *f)
{
    const simplex_cfg *k = cfg;
    static const char *const dnames[3] = { "dfdx", "dfdy", "dfdz" };
    char fmt[32];
    memset(f, 0, sizeof *f);
    f->n_in = 3;
    f->n_out = k->c.deriv ? 4u : 1u;
    np_unit_set_field(&f->in[0], "x", 16, 0, 8, "u16 Q8.8");
    np_unit_set_field(&f->in[1], "y", 16, 0, 8, "u16 Q8.8");
    np_unit_set_field(&f->in[2], "z", 16, 0, 8, "u16 Q8.8");
    snprintf(fmt, sizeof fmt, "s%u Q-1.%u", k->c.out_bits, np_simplex_f_frac(&k->c));
    np_unit_set_field(&f->out[0], "f", k->c.out_bits, 1, np_simplex_f_frac(&k->c), fmt);
    if (k->c.deriv) {
        snprintf(fmt, sizeof fmt, "s%u Q1.%u", k->c.dout_bits, np_simplex_d_frac(&k->c));
        for (unsigned a = 0; a < 3; a++)
            np_unit_set_field(&f->out[1 + a], dnames[a], k->c.dout_bits, 1, np_simplex_d_frac(&k->c), fmt);
    }
}

static void put_out(const np_simplex_cfg *c, const np_simplex_out *o, uint64_t *out)
{
    out[0] = np_trunc_u((uint64_t)(int64_t)o->f, c->out_bits);
    if (c->deriv)
        for (unsigned a = 0; a < 3; a++)
            out[1 + a] = np_trunc_u((uint64_t)(int64_t)o->df[a], c->dout_bits);
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    const simplex_cfg *k = cfg;
    np_simplex_out o;
    np_simplex_eval(&k->c, (uint16_t)in[0], (uint16_t)in[1], (uint16_t)in[2], &o);
    put_out(&k->c, &o, out);
}

/* np_unit.eval_n: np_simplex_eval_n (its default-width paths) over chunks of the words. */
static void eval_n(const void *cfg, const uint64_t *in, uint64_t *out, size_t n)
{
    enum { CHUNK = 256 };
    const simplex_cfg *k = cfg;
    uint16_t x[CHUNK], y[CHUNK], z[CHUNK];
    np_simplex_out o[CHUNK];
    for (size_t i0 = 0; i0 < n; i0 += CHUNK) {
        size_t m = n - i0 < CHUNK ? n - i0 : CHUNK;
        np_unit_chunk_u16(in, n, 0, i0, m, x);
        np_unit_chunk_u16(in, n, 1, i0, m, y);
        np_unit_chunk_u16(in, n, 2, i0, m, z);
        np_simplex_eval_n(&k->c, x, y, z, o, m);
        for (size_t i = 0; i < m; i++) {
            uint64_t w[4];
            put_out(&k->c, &o[i], w);
            out[i0 + i] = w[0];
            if (k->c.deriv)
                for (unsigned a = 0; a < 3; a++)
                    out[(1 + a) * n + i0 + i] = w[1 + a];
        }
    }
}

static void ref(const void *cfg, const uint64_t *in, double *out)
{
    const simplex_cfg *k = cfg;
    double g[3];
    out[0] = np_ref_simplex3_q88((uint16_t)in[0], (uint16_t)in[1], (uint16_t)in[2], g);
    if (k->c.deriv)
        for (unsigned a = 0; a < 3; a++)
            out[1 + a] = g[a];
}

static double error_bound(const void *cfg)
{
    const simplex_cfg *k = cfg;
    double bf = np_simplex_error_bound_lsb(&k->c, 0);
    double bd = k->c.deriv ? np_simplex_error_bound_lsb(&k->c, 1) : 0.0;
    return bf > bd ? bf : bd;
}

static size_t datapath(const void *cfg, np_op *ops, size_t max)
{
    return np_simplex_datapath(&((const simplex_cfg *)cfg)->c, ops, max);
}

static int pipe_init(np_pipe *p, const void *cfg) { return np_simplex_pipe_init(p, &((const simplex_cfg *)cfg)->c); }

static void trace(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n)
{
    np_simplex_trace(&((const simplex_cfg *)cfg)->c, k, sig, t, n);
}

/* Checked by the conformance test besides the default: f only, narrow, every fraction width 8. */
static const char *const conformance_configs[] = { "deriv=0", "out_bits=8,dout_bits=8",
                                                   "out_bits=8,dout_bits=8,t_frac=8,p_frac=8,k_frac=8", NULL };

static void sig_set_in(void *sig, const uint64_t *in)
{
    np_simplex_sig *s = sig;
    memset(s, 0, sizeof *s);
    s->x = (uint16_t)in[0];
    s->y = (uint16_t)in[1];
    s->z = (uint16_t)in[2];
}

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    const simplex_cfg *k = cfg;
    const np_simplex_sig *s = sig;
    np_simplex_out o;
    o.f = s->f;
    for (unsigned a = 0; a < 3; a++)
        o.df[a] = s->df[a];
    put_out(&k->c, &o, out);
}

/*
 * Hand-annotated boundary inputs (x, y, z as u16 Q8.8 words). Notation: U, V,
 * W are the exact offsets from corner 0 in units of 1/1536 (np_simplex.h),
 * (i, j, k) the skewed cell, T the exact kernel variable of a corner.
 */
static const uint16_t boundary_table[][3] = {
    /* 0 and 0xffff per axis, every combination. */
    { 0x0000, 0x0000, 0x0000 }, /* origin: U=V=W=0 (u=v=w tie), corner 0 at d=0: f=0, df=8*0.6^4*G */
    { 0xffff, 0x0000, 0x0000 }, /* x at its maximum: cell (341,85,85) */
    { 0x0000, 0xffff, 0x0000 }, /* y at its maximum */
    { 0x0000, 0x0000, 0xffff }, /* z at its maximum */
    { 0xffff, 0xffff, 0x0000 }, /* x, y at their maximum: u=v face */
    { 0xffff, 0x0000, 0xffff }, /* x, z: u=w face */
    { 0x0000, 0xffff, 0xffff }, /* y, z: v=w face */
    { 0xffff, 0xffff, 0xffff }, /* largest input: cell (511,511,511), hashed as (255,255,255); u=v=w */
    /* Simplex faces: the exact tie, then one input step either side (Appendix B's tie rule decides). */
    { 0x1234, 0x1234, 0x0abc }, /* u=v face (X=Y) with w below: hi=0 by the tie rule */
    { 0x1235, 0x1234, 0x0abc }, /* u just above v */
    { 0x1233, 0x1234, 0x0abc }, /* u just below v: the other simplex */
    { 0x0abc, 0x5678, 0x5678 }, /* v=w face (Y=Z) with u below */
    { 0x0abc, 0x5679, 0x5678 }, /* v just above w */
    { 0x0abc, 0x5677, 0x5678 }, /* v just below w */
    { 0x9abc, 0x3def, 0x9abc }, /* u=w face (X=Z) with v below */
    { 0x9abd, 0x3def, 0x9abc }, /* u just above w */
    { 0x9abb, 0x3def, 0x9abc }, /* u just below w */
    { 0x4321, 0x4321, 0x4321 }, /* u=v=w: the main diagonal, all three ties at once */
    { 0x4322, 0x4321, 0x4321 }, /* u above the others */
    { 0x4321, 0x4322, 0x4321 }, /* v above the others */
    { 0x4321, 0x4321, 0x4322 }, /* w above the others */
    { 0x4320, 0x4321, 0x4321 }, /* u below the others */
    { 0xf6b0, 0xf6b0, 0xee28 }, /* u=v tie on a z' cell face too (an edge): Appendix B's limits differ by 161 LSB */
    { 0xf6b1, 0xf6b0, 0xee28 }, /* u just above v, cell (490,490,482) */
    { 0xf6af, 0xf6b0, 0xee28 }, /* u just below v: cell (490,490,481), another simplex and hash */
    /* Kernel support: t = 0 is unreachable from 8.8 inputs (np_simplex.h); the nearest T on either side. */
    { 0x0efe, 0x0f00, 0x0f18 }, /* corner 1 at T = 48, the smallest t > 0 (+4.1e-6): tau2 rounds to 0 */
    { 0x0eff, 0x0f00, 0x0f18 }, /* one step in x: corner 1 at T = -14772, out of the support */
    { 0x0efd, 0x0f00, 0x0f18 }, /* one step back: corner 1 at T = 14508 */
    { 0x0ebc, 0x0f8d, 0x0f8f }, /* corner 1 at T = -72, the largest t < 0 (-6.1e-6) */
    { 0x0ebd, 0x0f8d, 0x0f8f }, /* one step in x: corner 1 at T = 8868, in the support */
    { 0x0ebb, 0x0f8d, 0x0f8f }, /* one step back: corner 1 at T = -9372 */
    /* Largest magnitudes. */
    { 0x0640, 0x0040, 0x0340 }, /* cell centre U=V=W=384, gradients aligned: f = -0.347438, the bound; df = 0 */
    { 0xe1ea, 0xcc99, 0xfd3a }, /* largest |df| seen in 1e6 random inputs: df/dy = 1.7226 */
    /* Skewed cell wrap: the hash reads the cell mod 256. */
    { 0x7fff, 0x7fff, 0x7fff }, /* cell (255,255,255), just below the wrap */
    { 0x8000, 0x8000, 0x8000 }, /* cell (256,256,256) hashed as (0,0,0): same bits as the origin */
    { 0xbfff, 0x0000, 0x0000 }, /* i = 255 (4x+y+z = 196604) */
    { 0xc000, 0x0000, 0x0000 }, /* i = 256 exactly (4x+y+z = 196608): the hash's i wraps to 0 */
    { 0x0000, 0xa000, 0x8000 }, /* j = 256 exactly (4y+x+z = 196608), i = 96, k = 224 */
    /* Input wrap: 0xffff -> 0x0000 on one axis (no tiling at 256: the output jumps). */
    { 0xffff, 0x1357, 0x2468 }, /* x = 256 - 1/256 */
    { 0x0000, 0x1357, 0x2468 }, /* x = 0: not the continuation of the line above */
};
enum { N_TABLE = sizeof boundary_table / sizeof boundary_table[0] };

static size_t boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
    for (size_t n = 0; n < N_TABLE && n < max; n++)
        for (unsigned a = 0; a < 3; a++)
            in[n][a] = boundary_table[n][a];
    return N_TABLE;
}

/* --- The adversarial search's classes (np_unit.adversarial, docs/search.md) --- */

enum { ADV_CANDIDATES = 16 }; /* candidates drawn per worst-rounding input */

/*
 * The exact front end of one input: the pipeline's first four stages (SK,
 * RK, CH, KT: skew, rank, corners, G.D, R2, T), no rounding in any of them.
 */
enum { ADV_FRONT_STAGES = 4 };

static void adv_front_of(const np_simplex_cfg *c, const uint16_t in[3], np_simplex_sig *sig)
{
    memset(sig, 0, sizeof *sig);
    sig->x = in[0];
    sig->y = in[1];
    sig->z = in[2];
    for (unsigned k = 0; k < ADV_FRONT_STAGES; k++)
        np_simplex_stage_table(c)[k].fn(c, sig);
}

/* v / 2^k - round_half_up(v / 2^k), negated: the rounding's signed error in result LSB. */
static double adv_round_err(uint64_t v, unsigned k)
{
    return k == 0 ? 0.0 : (double)np_shr_round_half_up_u(v, k) - ldexp((double)v, -(int)k);
}

/*
 * How much the kernel powers' roundings at WT (tau2, tau4, tau3) move the
 * outputs, to first order, in output LSB: per corner the errors e2, e4, e3
 * of the three roundings (in 2^-WT) give tau^4 an error 2 tau^2 e2 + e4 and
 * tau^3 an error tau e2 + e3; f moves by Kf 2^N sum_c (.) G.d', each df_a
 * by Kd 2^(ND-2) sum_c ((.) G_a - 5/4 (.) G.d' d'_a). The largest over the
 * outputs. Exact integer front end; the products' and constants' roundings
 * (WP, WK) are left out: they do not depend on where the input is.
 */
static double adv_power_score(const np_simplex_cfg *c, const np_simplex_sig *fr)
{
    unsigned wt = c->t_frac;
    double lsb = ldexp(1.0, -(int)wt), sf = 0.0, sd[3] = { 0.0, 0.0, 0.0 };
    for (unsigned k = 0; k < 4; k++) {
        uint32_t t = fr->t[k];
        if (t == 0)
            continue;
        uint32_t tau2 = np_simplex_tau2(c, t);
        double tau = ldexp((double)t, -NP_SIMPLEX_T_BITS), t2 = ldexp((double)tau2, -(int)wt);
        double e2 = adv_round_err((uint64_t)t * t, 2u * NP_SIMPLEX_T_BITS - wt);
        double e4 = adv_round_err((uint64_t)tau2 * tau2, wt);
        double e3 = adv_round_err((uint64_t)tau2 * t, NP_SIMPLEX_T_BITS);
        double d4 = (2.0 * t2 * e2 + e4) * lsb, d3 = (tau * e2 + e3) * lsb;
        double gd = ldexp((double)fr->gd[k], -NP_SIMPLEX_GD_FRAC);
        const int coef[3] = { fr->g[k].cx, fr->g[k].cy, fr->g[k].cz };
        sf += d4 * gd;
        for (unsigned a = 0; a < 3; a++)
            sd[a] += d4 * coef[a] - 1.25 * d3 * gd * ldexp((double)fr->d[k][a], -NP_SIMPLEX_GD_FRAC);
    }
    double kf = (double)NP_SIMPLEX_KF_NUM / NP_SIMPLEX_KF_DEN, kd = (double)NP_SIMPLEX_KF_NUM / NP_SIMPLEX_KD_DEN;
    double score = fabs(sf) * kf * ldexp(1.0, (int)np_simplex_f_frac(c));
    for (unsigned a = 0; c->deriv && a < 3; a++) {
        double v = fabs(sd[a]) * kd * ldexp(1.0, (int)np_simplex_d_frac(c));
        score = v > score ? v : score;
    }
    return score;
}

static uint16_t adv_word(np_rng *r) { return (uint16_t)(np_rng_next(r) >> 48); }

/*
 * NP_ADV_ROUNDING: of ADV_CANDIDATES random inputs, the one whose power
 * roundings move the outputs most (adv_power_score, from the formats).
 * NP_ADV_FACES: the exact skew boundaries (4x + y + z a multiple of 768 on
 * one axis: the skewed cell changes there), and rank ties across cells
 * (x - y a multiple of 256, kept when the offsets tie exactly), each 0 or
 * 1 LSB off on one axis.
 */
static size_t adversarial(const void *cfgv, unsigned cls, np_rng *r, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t n)
{
    const np_simplex_cfg *c = &((const simplex_cfg *)cfgv)->c;
    for (size_t i = 0; i < n; i++) {
        uint16_t best[3] = { 0, 0, 0 }, w[3];
        if (cls == NP_ADV_ROUNDING) {
            double top = -1.0;
            for (unsigned k = 0; k < ADV_CANDIDATES; k++) {
                np_simplex_sig fr;
                for (unsigned a = 0; a < 3; a++)
                    w[a] = adv_word(r);
                adv_front_of(c, w, &fr);
                double sc = adv_power_score(c, &fr);
                if (sc > top) {
                    top = sc;
                    memcpy(best, w, sizeof best);
                }
            }
        } else if (cls == NP_ADV_FACES) {
            unsigned axis = (unsigned)np_rng_below(r, 3), b = (axis + 1u) % 3u, e = (axis + 2u) % 3u;
            if (np_rng_next(r) & 1u) { /* skew boundary of axis: 4 w[axis] + w[b] + w[e] = 768 m */
                for (;;) {
                    w[b] = adv_word(r);
                    w[e] = (uint16_t)(adv_word(r) & ~3u);
                    w[e] = (uint16_t)(w[e] + ((4u - ((unsigned)w[b] + w[e]) % 4u) % 4u));
                    uint32_t m = (uint32_t)np_rng_below(r, 512), sum = (uint32_t)w[b] + w[e];
                    uint32_t sx = m * NP_SIMPLEX_SKEW_CELL;
                    if (sx >= sum && (sx - sum) % 4u == 0 && (sx - sum) / 4u <= 0xffffu) {
                        w[axis] = (uint16_t)((sx - sum) / 4u);
                        break;
                    }
                }
            } else { /* offsets tied across cells: w[b] = w[axis] + 256 k */
                for (unsigned tries = 0;; tries++) {
                    w[axis] = adv_word(r);
                    w[b] = (uint16_t)(w[axis] + 256 * ((int)np_rng_below(r, 5) - 2));
                    w[e] = adv_word(r);
                    np_simplex_sig fr;
                    adv_front_of(c, w, &fr);
                    if (fr.off[axis] == fr.off[b] || tries > 16)
                        break;
                }
            }
            w[np_rng_below(r, 3)] += (uint16_t)(np_rng_below(r, 3) == 0 ? 1u : 0u);
            memcpy(best, w, sizeof best);
        } else
            return 0;
        for (unsigned a = 0; a < 3; a++)
            in[i][a] = best[a];
    }
    return n;
}

/* f and the derivative rounded to 20 fraction bits (the widest outputs): the error before O's rounding, to 1/16 LSB. */
static void fine_cfg(const void *cfg, void *fine)
{
    simplex_cfg *k = fine;
    *k = *(const simplex_cfg *)cfg;
    k->c.out_bits = NP_SIMPLEX_OUT_MAX;
    k->c.dout_bits = NP_SIMPLEX_OUT_MAX;
}

/* The exhaustive sweep's kernel (src/units/sweep_simplex.c). */
static void sweep_rows(const void *cfg, uint16_t x0, uint16_t y0, uint16_t z, unsigned rows, unsigned what,
                       int32_t *code, double *ref)
{
    np_sweep_simplex3_rows(&((const simplex_cfg *)cfg)->c, x0, y0, z, rows, what, code, ref);
}

const np_unit np_unit_simplex3 = {
    .name = "simplex3",
    .sweep_rows = sweep_rows,
    .summary = "3-D simplex noise with analytic derivative, 8.8 inputs, exact skew/rank "
               "(Perlin, Noise Hardware, Appendix B)",
    NP_UNIT_MODEL_ENTRY,
    .tolerance_lsb = 1.0,
    .adversarial = adversarial,
    .fine_cfg = fine_cfg,
    .eval_n = eval_n,
};
