/* SPDX-License-Identifier: MIT */
/*
 * np_hatch.c - the hatching unit: bit-exact model, coverage lists, the host's
 * zoom, the cycle model and the datapath declaration (np_hatch.h).
 */
#include "np_hatch.h"

#include <stdlib.h>
#include <string.h>

#define ONE30 ((uint64_t)1 << NP_HATCH_AF)

const np_hatch_set np_hatch_sets[NP_HATCH_SETS] = {
    { "fkm16", "noisepipe seeds --order 2 (FKM)", 2, 16, 0x0A5Fu, 0x23B3u, 0.1154 },
    { "best16", "noisepipe seeds --order 2 --all (one of the 8 best; digits 0011331230210322)", 2, 16, 0x0DA7u,
      0x3E94u, 0.1668 },
    { "fkm64", "noisepipe seeds --order 3 (FKM)", 3, 64, 0x024129B4D896DBFFu, 0x105A64169F797717u, 0.0291 },
    { "best64", "noisepipe seeds --order 3 --search --count 3688960 --seed 1 (a 60 s run)", 3, 64,
      0x1FB34B5AD1F8C844u, 0x6EA31EBC148D2E3Cu, 0.0678 },
};

const char *np_hatch_cfg_check(const np_hatch_cfg *cfg)
{
    if (cfg->set >= NP_HATCH_SETS)
        return "set: fkm16, best16, fkm64 or best64";
    unsigned n = np_hatch_n(cfg);
    if (cfg->layers < 1u || cfg->layers > NP_HATCH_LAYERS_MAX)
        return "layers: 1..4";
    if (cfg->guard > NP_HATCH_GUARD_MAX)
        return "guard: 0..22";
    if (cfg->lanes < 1u || cfg->lanes > NP_HATCH_LANES_MAX || (cfg->lanes & (cfg->lanes - 1u)) || n % cfg->lanes)
        return "lanes: a power of two that divides N (16 or 64), at most 16";
    if (cfg->fade > NP_HATCH_FADE_ONE_BY_ONE)
        return "fade: 0 (smooth) or 1 (one by one)";
    if (cfg->rot >= NP_HATCH_ROTS)
        return "rot: pin, 0, 45, 90 or 1e-4";
    if (cfg->inv_u < 1u || cfg->inv_u > 0xFFFFu || cfg->inv_v < 1u || cfg->inv_v > 0xFFFFu)
        return "inv_len, inv_wid: u16 Q8.8, nonzero";
    if (cfg->cover_slots && (cfg->cover_slots % cfg->lanes || cfg->cover_slots > NP_HATCH_LANES_MAX ||
                             (cfg->cover_slots > NP_HATCH_COVER_MAX && cfg->cover_slots != cfg->lanes)))
        return "coverage slots: a multiple of lanes, at most 8 (or the lanes)";
    return NULL;
}

static uint64_t nmask(unsigned n) { return n >= 64u ? ~(uint64_t)0 : NP_MASK(n); }


void np_hatch_layer_b(const np_hatch_cfg *cfg, unsigned l, uint64_t *bu, uint64_t *bv)
{
    const np_hatch_set *st = &np_hatch_sets[cfg->set];
    uint64_t m = nmask(st->n);
    *bu = (l & 1u ? ~st->bu : st->bu) & m;
    *bv = (l & 2u ? ~st->bv : st->bv) & m;
}

void np_hatch_layer_r(const np_hatch_cfg *cfg, unsigned l, int16_t r[2][2])
{
    /*
     * R = [[c, s], [-s, c]] in Q1.14: cos 45 = round(16384 / sqrt 2) = 11585; 1e-4 rad: cos rounds
     * to 16384, sin to round(1.6384) = 2.
     */
    static const int16_t rot[][2][2] = {
        { { 16384, 0 }, { 0, 16384 } },           /* 0 */
        { { 11585, 11585 }, { -11585, 11585 } },  /* 45 */
        { { 0, 16384 }, { -16384, 0 } },          /* 90 */
        { { 16384, 2 }, { -2, 16384 } },          /* 1e-4 rad */
        { { 11585, -11585 }, { 11585, 11585 } },  /* -45 */
    };
    static const unsigned pin[NP_HATCH_LAYERS_MAX] = { 1, 4, 0, 2 }; /* 45, -45, 0, 90 */
    unsigned k = cfg->rot == NP_HATCH_ROT_PIN ? pin[l] : cfg->rot - 1u;
    memcpy(r, rot[k], sizeof rot[k]);
}

/* x * y rounded half up to Q1.30, both Q1.30 in [0, 1]. */
static uint32_t mul30(uint64_t x, uint64_t y) { return (uint32_t)np_shr_round_half_up_u(x * y, NP_HATCH_AF); }

/* S(t) = t^2 (3 - 2t), t in [0, 1] Q1.30: two products rounded half up; S(0) = 0, S(1) = 1 exactly. */
static uint32_t smoothstep30(uint32_t t)
{
    uint32_t t2 = mul30(t, t);
    return mul30(t2, 3u * ONE30 - 2u * (uint64_t)t);
}

/* clamp((N+1) x - i, 0, 1) in Q1.30: a constant multiply and a subtract, no divide. */
static uint32_t ramp30(unsigned n, uint32_t x, unsigned i)
{
    int64_t v = (int64_t)(n + 1u) * (int64_t)x - (int64_t)i * (int64_t)ONE30;
    return (uint32_t)(v < 0 ? 0 : (v > (int64_t)ONE30 ? (int64_t)ONE30 : v));
}

void np_hatch_setup(const np_hatch_cfg *cfg, np_hatch_sig *s)
{
    s->A = (uint32_t)(((uint64_t)s->tone * ONE30 + 127u) / 255u); /* round(tone 2^30 / 255): 255 is odd, no ties */
    for (unsigned l = 0; l < NP_HATCH_LAYERS_MAX; l++) {
        int64_t v = 4 * (int64_t)s->A - (int64_t)l * (int64_t)ONE30;
        s->al[l] = l < cfg->layers ? (uint32_t)(v < 0 ? 0 : (v > (int64_t)ONE30 ? (int64_t)ONE30 : v)) : 0u;
    }
    s->oms = s->om > (1u << NP_HATCH_M_FRAC) ? 1u << NP_HATCH_M_FRAC : s->om;
    s->ku = (uint64_t)s->pm * (uint16_t)cfg->inv_u;
    s->kv = (uint64_t)s->pm * (uint16_t)cfg->inv_v;
    s->c = (uint32_t)1u << (8u + cfg->guard);
    s->pos = 0;
    s->nz = 0;
    memset(&s->last, 0, sizeof s->last);
}

/* Q = 2 q k rounded half up: q Q3.46, k Q9.24 -> Q11.30 (shift 46 + 24 - 30 - 1 = 39). */
static int64_t stroke_q(int64_t q, uint64_t k)
{
    np_s128 p = np_mul128((np_s128)q, (np_s128)k);
    return (int64_t)np_asr128(np_add128(p, (np_s128)1 << 38), 39);
}

/* y = (1 - U^8)(1 - V^4) for |U|, |V| < 1 (Q1.30), else 0. */
static uint32_t profile30(int64_t Qu, int64_t Qv)
{
    uint64_t U = (uint64_t)(Qu < 0 ? -Qu : Qu), V = (uint64_t)(Qv < 0 ? -Qv : Qv);
    if (U >= ONE30 || V >= ONE30)
        return 0;
    uint32_t u2 = mul30(U, U), u4 = mul30(u2, u2), u8 = mul30(u4, u4);
    uint32_t v2 = mul30(V, V), v4 = mul30(v2, v2);
    return mul30(ONE30 - u8, ONE30 - v4);
}

void np_hatch_seed(const np_hatch_cfg *cfg, np_hatch_sig *s, unsigned l, unsigned i, np_hatch_seed_sig *o)
{
    np_hatch_seed_sig z;
    unsigned n = np_hatch_n(cfg);
    uint64_t bu, bv;
    int16_t R[2][2];
    np_hatch_layer_b(cfg, l, &bu, &bv);
    np_hatch_layer_r(cfg, l, R);
    uint64_t wu = np_hatch_rotl(bu, i, n), wv = np_hatch_rotl(bv, i, n);
    uint64_t m33 = NP_MASK(NP_HATCH_X_BITS), half = (uint64_t)1 << 31;
    z.du = (s->xu + (m33 ^ np_hatch_seed_st(wu, n)) + half) & m33;
    z.dv = (s->xv + (m33 ^ np_hatch_seed_st(wv, n)) + half) & m33;
    z.surv = ((z.du >> 32) & 1u) == (wu & 1u) && ((z.dv >> 32) & 1u) == (wv & 1u);
    z.ru = (int64_t)(z.du & NP_MASK(32)) - (int64_t)half;
    z.rv = (int64_t)(z.dv & NP_MASK(32)) - (int64_t)half;
    z.qu = (int64_t)R[0][0] * z.ru + (int64_t)R[0][1] * z.rv;
    z.qv = (int64_t)R[1][0] * z.ru + (int64_t)R[1][1] * z.rv;
    z.Qu = stroke_q(z.qu, s->ku);
    z.Qv = stroke_q(z.qv, s->kv);
    z.profile = profile30(z.Qu, z.Qv);
    if (cfg->fade == NP_HATCH_FADE_ONE_BY_ONE) {
        z.at = smoothstep30(ramp30(n, s->al[l], i));
        uint32_t m30 = (uint32_t)(((1u << NP_HATCH_M_FRAC) - s->oms) << (NP_HATCH_AF - NP_HATCH_M_FRAC));
        z.am = z.surv ? (uint32_t)ONE30 : (uint32_t)(ONE30 - smoothstep30(ramp30(n, m30, i)));
    } else {
        z.at = s->al[l];
        z.am = z.surv ? (uint32_t)ONE30 : s->oms << (NP_HATCH_AF - NP_HATCH_M_FRAC);
    }
    z.alpha = mul30(mul30(z.at, z.am), z.profile);
    /* Blend with black ink: c <- c - floor(alpha c); alpha <= 1 keeps c >= 0. */
    s->c -= (uint32_t)(((uint64_t)z.alpha * s->c) >> NP_HATCH_AF);
    s->nz += z.alpha != 0u;
    s->last = z;
    if (o)
        *o = z;
}

void np_hatch_output(const np_hatch_cfg *cfg, np_hatch_sig *s)
{
    unsigned f = 8u + cfg->guard;
    s->out = (uint32_t)np_shr_round_half_up_u((uint64_t)s->c * 255u, f);
}

static void load_inputs(np_hatch_sig *s, uint64_t xu, uint64_t xv, uint32_t tone, uint32_t pm, uint32_t om)
{
    memset(s, 0, sizeof *s);
    s->xu = xu & NP_MASK(NP_HATCH_X_BITS);
    s->xv = xv & NP_MASK(NP_HATCH_X_BITS);
    s->tone = tone & 0xFFu;
    s->pm = pm & (uint32_t)NP_MASK(NP_HATCH_M_BITS);
    s->om = om & (uint32_t)NP_MASK(NP_HATCH_M_BITS);
}

uint32_t np_hatch_eval(const np_hatch_cfg *cfg, uint64_t xu, uint64_t xv, uint32_t tone, uint32_t pm, uint32_t om,
                       np_hatch_sig *sig_out)
{
    np_hatch_sig s;
    load_inputs(&s, xu, xv, tone, pm, om);
    np_hatch_setup(cfg, &s);
    for (unsigned l = 0; l < cfg->layers; l++)
        for (unsigned i = 0; i < np_hatch_n(cfg); i++)
            np_hatch_seed(cfg, &s, l, i, NULL);
    np_hatch_output(cfg, &s);
    if (sig_out)
        *sig_out = s;
    return s.out;
}

double np_hatch_alpha_bound(const np_hatch_cfg *cfg, uint32_t pm_max)
{
    const double h = np_pow2i(-31), t32 = np_pow2i(-32);
    double ru = 0, rv = 0;
    for (unsigned l = 0; l < cfg->layers; l++) {
        int16_t r[2][2];
        np_hatch_layer_r(cfg, l, r);
        double a = (abs(r[0][0]) + abs(r[0][1])) / 16384.0;
        double b = (abs(r[1][0]) + abs(r[1][1])) / 16384.0;
        ru = a > ru ? a : ru;
        rv = b > rv ? b : rv;
    }
    double p = pm_max / 65536.0;
    double dqu = 2.0 * p * cfg->inv_u / 256.0 * ru * t32 + h, dqv = 2.0 * p * cfg->inv_v / 256.0 * rv * t32 + h;
    double dy = 8.0 * dqu + 4.0 * dqv + 11.0 * h;
    double dat = 4.0 * h, dam = 0.0;
    if (cfg->fade == NP_HATCH_FADE_ONE_BY_ONE) {
        dat += 1.5 * (np_hatch_n(cfg) + 1u) * 4.0 * h + 4.0 * h;
        dam = 4.0 * h;
    }
    return dat + dam + dy + 2.0 * h;
}

double np_hatch_error_bound_lsb(const np_hatch_cfg *cfg, unsigned n, uint32_t pm_max)
{
    return 0.5 + 255.0 * n * (np_pow2i(-(int)(8u + cfg->guard)) + np_hatch_alpha_bound(cfg, pm_max));
}

/* --- coverage lists --- */

static unsigned log2u(unsigned v)
{
    unsigned k = 0;
    while ((1u << k) < v)
        k++;
    return k;
}

/* Does the rectangle centre c (seed space, torus), half-extents a (along e), b (across f) meet the texel? */
static int rect_meets_texel(double cu, double cv, double eu, double ev, double a, double b, double x0, double y0,
                            double w)
{
    /* Bring the centre to the copy nearest the texel's centre. */
    double tx = x0 + w / 2, ty = y0 + w / 2;
    double dx = cu - tx, dy = cv - ty;
    dx -= (double)(long)(dx + (dx >= 0 ? 0.5 : -0.5));
    dy -= (double)(long)(dy + (dy >= 0 ? 0.5 : -0.5));
    /* Separating axes: x, y (texel's), e, f (stroke's). */
    double fu = -ev, fv = eu;
    double hx = a * (eu < 0 ? -eu : eu) + b * (fu < 0 ? -fu : fu);
    double hy = a * (ev < 0 ? -ev : ev) + b * (fv < 0 ? -fv : fv);
    if ((dx < 0 ? -dx : dx) > hx + w / 2 || (dy < 0 ? -dy : dy) > hy + w / 2)
        return 0;
    double pe = dx * eu + dy * ev, pf = dx * fu + dy * fv;
    double te = w / 2 * ((eu < 0 ? -eu : eu) + (ev < 0 ? -ev : ev));
    double tf = w / 2 * ((fu < 0 ? -fu : fu) + (fv < 0 ? -fv : fv));
    if ((pe < 0 ? -pe : pe) > a + te || (pf < 0 ? -pf : pf) > b + tf)
        return 0;
    return 1;
}

int np_hatch_cover_build(const np_hatch_cfg *cfg, np_hatch_cover *cv)
{
    unsigned n = np_hatch_n(cfg), K = log2u(n) / 2u, t = 4u << K;
    memset(cv, 0, sizeof *cv);
    cv->t = t;
    cv->layers = cfg->layers;
    cv->len = calloc((size_t)cfg->layers * t * t, 1);
    cv->idx = calloc((size_t)cfg->layers * t * t * NP_HATCH_COVER_MAX, 1);
    if (!cv->len || !cv->idx) {
        np_hatch_cover_free(cv);
        return -1;
    }
    /*
     * Largest stroke: 2^-m = 1/2, so |Q| < 1 where |(R r)_u| < 1 / (2 k_u), k_u = inv_u / 2.
     * R's rows are (c, s) and (-s, c) of norm rho (Q1.14 rounding): the rectangle's half-extents in
     * seed space along the unit direction e = (c, s) / rho are 1 / (rho inv_u) and across 1 / (rho inv_v).
     */
    const double margin = 1.0 / 1048576.0, w = 1.0 / t;
    double sum = 0;
    int rc = 0;
    for (unsigned l = 0; l < cfg->layers; l++) {
        int16_t r[2][2];
        uint64_t bu, bv;
        np_hatch_layer_r(cfg, l, r);
        np_hatch_layer_b(cfg, l, &bu, &bv);
        double c = r[0][0] / 16384.0, s = r[0][1] / 16384.0;
        double rho = c * c + s * s;
        rho = rho > 0 ? __builtin_sqrt(rho) : 1.0;
        double eu = c / rho, ev = s / rho;
        double a = 256.0 / (rho * (double)cfg->inv_u) + margin, b = 256.0 / (rho * (double)cfg->inv_v) + margin;
        for (unsigned i = 0; i < n; i++) {
            double dn = n == 64u ? 18446744073709551615.0 : (double)nmask(n);
            double su = (double)np_hatch_rotl(bu, i, n) / dn, sv = (double)np_hatch_rotl(bv, i, n) / dn;
            for (unsigned tv = 0; tv < t; tv++)
                for (unsigned tu = 0; tu < t; tu++) {
                    if (!rect_meets_texel(su, sv, eu, ev, a, b, tu * w, tv * w, w))
                        continue;
                    size_t at = ((size_t)l * t + tv) * t + tu;
                    if (cv->len[at] >= NP_HATCH_COVER_MAX) {
                        rc = -1;
                        continue;
                    }
                    cv->idx[at * NP_HATCH_COVER_MAX + cv->len[at]++] = (uint8_t)i;
                }
        }
    }
    for (size_t k = 0; k < (size_t)cfg->layers * t * t; k++) {
        sum += cv->len[k];
        if (cv->len[k] > cv->max_len)
            cv->max_len = cv->len[k];
    }
    cv->mean_len = sum / ((double)cfg->layers * t * t);
    return rc;
}

unsigned np_hatch_cover_slots(const np_hatch_cfg *cfg, const np_hatch_cover *cv)
{
    unsigned m = cv->max_len ? cv->max_len : 1u;
    return (m + cfg->lanes - 1u) / cfg->lanes * cfg->lanes;
}

void np_hatch_cover_free(np_hatch_cover *cv)
{
    free(cv->len);
    free(cv->idx);
    cv->len = cv->idx = NULL;
}

uint32_t np_hatch_eval_cover(const np_hatch_cfg *cfg, const np_hatch_cover *cv, uint64_t xu, uint64_t xv,
                             uint32_t tone, uint32_t pm, uint32_t om, unsigned *cycles)
{
    np_hatch_sig s;
    load_inputs(&s, xu, xv, tone, pm, om);
    np_hatch_setup(cfg, &s);
    unsigned tb = log2u(cv->t), cyc = 0;
    unsigned tu = (unsigned)((s.xu >> (32u - tb)) & (cv->t - 1u)), tv = (unsigned)((s.xv >> (32u - tb)) & (cv->t - 1u));
    for (unsigned l = 0; l < cfg->layers; l++) {
        size_t at = ((size_t)l * cv->t + tv) * cv->t + tu;
        for (unsigned k = 0; k < cv->len[at]; k++)
            np_hatch_seed(cfg, &s, l, cv->idx[at * NP_HATCH_COVER_MAX + k], NULL);
        cyc += (cv->len[at] + cfg->lanes - 1u) / cfg->lanes;
    }
    np_hatch_output(cfg, &s);
    if (cycles)
        *cycles = cyc ? cyc : 1u;
    return s.out;
}

/* --- zoom (host) --- */

uint64_t np_hatch_xs(np_u128 x_uv, int level)
{
    unsigned sh = (unsigned)(64 + level); /* Q32.96 -> Q.32 is >> 64; 2^-level is >> level more */
    return (uint64_t)(x_uv >> sh) & NP_MASK(NP_HATCH_X_BITS);
}

/* --- cycle model --- */

/* Stage A; with coverage, the point's lists too (the list memory's read: texel = the top fraction bits of x). */
static void st_setup(const void *vcfg, void *vsig)
{
    const np_hatch_cfg *cfg = vcfg;
    np_hatch_sig *s = vsig;
    np_hatch_setup(cfg, s);
    const np_hatch_cover *cv = cfg->cover;
    if (!cfg->cover_slots || !cv)
        return;
    unsigned tb = log2u(cv->t);
    unsigned tu = (unsigned)((s->xu >> (32u - tb)) & (cv->t - 1u)), tv = (unsigned)((s->xv >> (32u - tb)) & (cv->t - 1u));
    for (unsigned l = 0; l < cfg->layers; l++) {
        size_t at = ((size_t)l * cv->t + tv) * cv->t + tu;
        s->ln[l] = cv->len[at];
        memcpy(s->li[l], cv->idx + at * NP_HATCH_COVER_MAX, NP_HATCH_COVER_MAX);
    }
}

/* P seeds; the stage that takes the last seed also rounds the output (stage O folded into it). */
static void st_seeds(const void *vcfg, void *vsig)
{
    const np_hatch_cfg *cfg = vcfg;
    np_hatch_sig *s = vsig;
    unsigned n = cfg->cover_slots ? cfg->cover_slots : np_hatch_n(cfg);
    for (unsigned k = 0; k < cfg->lanes; k++, s->pos++) {
        unsigned l = s->pos / n, j = s->pos % n;
        if (!cfg->cover_slots)
            np_hatch_seed(cfg, s, l, j, NULL);
        else if (j < s->ln[l]) /* an empty slot: alpha 0, c unchanged */
            np_hatch_seed(cfg, s, l, s->li[l][j], NULL);
    }
    if (s->pos == cfg->layers * n)
        np_hatch_output(cfg, s);
}

unsigned np_hatch_depth(const np_hatch_cfg *cfg)
{
    return 1u + cfg->layers * (cfg->cover_slots ? cfg->cover_slots : np_hatch_n(cfg)) / cfg->lanes;
}

/* A, then S0..S(G-1): a prefix of one table serves every configuration. */
static const np_stage_desc stages[1 + NP_HATCH_LAYERS_MAX * 64] = {
    { "A", st_setup },
    { "S0", st_seeds },
    { "S1", st_seeds },
    { "S2", st_seeds },
    { "S3", st_seeds },
    { "S4", st_seeds },
    { "S5", st_seeds },
    { "S6", st_seeds },
    { "S7", st_seeds },
    { "S8", st_seeds },
    { "S9", st_seeds },
    { "S10", st_seeds },
    { "S11", st_seeds },
    { "S12", st_seeds },
    { "S13", st_seeds },
    { "S14", st_seeds },
    { "S15", st_seeds },
    { "S16", st_seeds },
    { "S17", st_seeds },
    { "S18", st_seeds },
    { "S19", st_seeds },
    { "S20", st_seeds },
    { "S21", st_seeds },
    { "S22", st_seeds },
    { "S23", st_seeds },
    { "S24", st_seeds },
    { "S25", st_seeds },
    { "S26", st_seeds },
    { "S27", st_seeds },
    { "S28", st_seeds },
    { "S29", st_seeds },
    { "S30", st_seeds },
    { "S31", st_seeds },
    { "S32", st_seeds },
    { "S33", st_seeds },
    { "S34", st_seeds },
    { "S35", st_seeds },
    { "S36", st_seeds },
    { "S37", st_seeds },
    { "S38", st_seeds },
    { "S39", st_seeds },
    { "S40", st_seeds },
    { "S41", st_seeds },
    { "S42", st_seeds },
    { "S43", st_seeds },
    { "S44", st_seeds },
    { "S45", st_seeds },
    { "S46", st_seeds },
    { "S47", st_seeds },
    { "S48", st_seeds },
    { "S49", st_seeds },
    { "S50", st_seeds },
    { "S51", st_seeds },
    { "S52", st_seeds },
    { "S53", st_seeds },
    { "S54", st_seeds },
    { "S55", st_seeds },
    { "S56", st_seeds },
    { "S57", st_seeds },
    { "S58", st_seeds },
    { "S59", st_seeds },
    { "S60", st_seeds },
    { "S61", st_seeds },
    { "S62", st_seeds },
    { "S63", st_seeds },
    { "S64", st_seeds },
    { "S65", st_seeds },
    { "S66", st_seeds },
    { "S67", st_seeds },
    { "S68", st_seeds },
    { "S69", st_seeds },
    { "S70", st_seeds },
    { "S71", st_seeds },
    { "S72", st_seeds },
    { "S73", st_seeds },
    { "S74", st_seeds },
    { "S75", st_seeds },
    { "S76", st_seeds },
    { "S77", st_seeds },
    { "S78", st_seeds },
    { "S79", st_seeds },
    { "S80", st_seeds },
    { "S81", st_seeds },
    { "S82", st_seeds },
    { "S83", st_seeds },
    { "S84", st_seeds },
    { "S85", st_seeds },
    { "S86", st_seeds },
    { "S87", st_seeds },
    { "S88", st_seeds },
    { "S89", st_seeds },
    { "S90", st_seeds },
    { "S91", st_seeds },
    { "S92", st_seeds },
    { "S93", st_seeds },
    { "S94", st_seeds },
    { "S95", st_seeds },
    { "S96", st_seeds },
    { "S97", st_seeds },
    { "S98", st_seeds },
    { "S99", st_seeds },
    { "S100", st_seeds },
    { "S101", st_seeds },
    { "S102", st_seeds },
    { "S103", st_seeds },
    { "S104", st_seeds },
    { "S105", st_seeds },
    { "S106", st_seeds },
    { "S107", st_seeds },
    { "S108", st_seeds },
    { "S109", st_seeds },
    { "S110", st_seeds },
    { "S111", st_seeds },
    { "S112", st_seeds },
    { "S113", st_seeds },
    { "S114", st_seeds },
    { "S115", st_seeds },
    { "S116", st_seeds },
    { "S117", st_seeds },
    { "S118", st_seeds },
    { "S119", st_seeds },
    { "S120", st_seeds },
    { "S121", st_seeds },
    { "S122", st_seeds },
    { "S123", st_seeds },
    { "S124", st_seeds },
    { "S125", st_seeds },
    { "S126", st_seeds },
    { "S127", st_seeds },
    { "S128", st_seeds },
    { "S129", st_seeds },
    { "S130", st_seeds },
    { "S131", st_seeds },
    { "S132", st_seeds },
    { "S133", st_seeds },
    { "S134", st_seeds },
    { "S135", st_seeds },
    { "S136", st_seeds },
    { "S137", st_seeds },
    { "S138", st_seeds },
    { "S139", st_seeds },
    { "S140", st_seeds },
    { "S141", st_seeds },
    { "S142", st_seeds },
    { "S143", st_seeds },
    { "S144", st_seeds },
    { "S145", st_seeds },
    { "S146", st_seeds },
    { "S147", st_seeds },
    { "S148", st_seeds },
    { "S149", st_seeds },
    { "S150", st_seeds },
    { "S151", st_seeds },
    { "S152", st_seeds },
    { "S153", st_seeds },
    { "S154", st_seeds },
    { "S155", st_seeds },
    { "S156", st_seeds },
    { "S157", st_seeds },
    { "S158", st_seeds },
    { "S159", st_seeds },
    { "S160", st_seeds },
    { "S161", st_seeds },
    { "S162", st_seeds },
    { "S163", st_seeds },
    { "S164", st_seeds },
    { "S165", st_seeds },
    { "S166", st_seeds },
    { "S167", st_seeds },
    { "S168", st_seeds },
    { "S169", st_seeds },
    { "S170", st_seeds },
    { "S171", st_seeds },
    { "S172", st_seeds },
    { "S173", st_seeds },
    { "S174", st_seeds },
    { "S175", st_seeds },
    { "S176", st_seeds },
    { "S177", st_seeds },
    { "S178", st_seeds },
    { "S179", st_seeds },
    { "S180", st_seeds },
    { "S181", st_seeds },
    { "S182", st_seeds },
    { "S183", st_seeds },
    { "S184", st_seeds },
    { "S185", st_seeds },
    { "S186", st_seeds },
    { "S187", st_seeds },
    { "S188", st_seeds },
    { "S189", st_seeds },
    { "S190", st_seeds },
    { "S191", st_seeds },
    { "S192", st_seeds },
    { "S193", st_seeds },
    { "S194", st_seeds },
    { "S195", st_seeds },
    { "S196", st_seeds },
    { "S197", st_seeds },
    { "S198", st_seeds },
    { "S199", st_seeds },
    { "S200", st_seeds },
    { "S201", st_seeds },
    { "S202", st_seeds },
    { "S203", st_seeds },
    { "S204", st_seeds },
    { "S205", st_seeds },
    { "S206", st_seeds },
    { "S207", st_seeds },
    { "S208", st_seeds },
    { "S209", st_seeds },
    { "S210", st_seeds },
    { "S211", st_seeds },
    { "S212", st_seeds },
    { "S213", st_seeds },
    { "S214", st_seeds },
    { "S215", st_seeds },
    { "S216", st_seeds },
    { "S217", st_seeds },
    { "S218", st_seeds },
    { "S219", st_seeds },
    { "S220", st_seeds },
    { "S221", st_seeds },
    { "S222", st_seeds },
    { "S223", st_seeds },
    { "S224", st_seeds },
    { "S225", st_seeds },
    { "S226", st_seeds },
    { "S227", st_seeds },
    { "S228", st_seeds },
    { "S229", st_seeds },
    { "S230", st_seeds },
    { "S231", st_seeds },
    { "S232", st_seeds },
    { "S233", st_seeds },
    { "S234", st_seeds },
    { "S235", st_seeds },
    { "S236", st_seeds },
    { "S237", st_seeds },
    { "S238", st_seeds },
    { "S239", st_seeds },
    { "S240", st_seeds },
    { "S241", st_seeds },
    { "S242", st_seeds },
    { "S243", st_seeds },
    { "S244", st_seeds },
    { "S245", st_seeds },
    { "S246", st_seeds },
    { "S247", st_seeds },
    { "S248", st_seeds },
    { "S249", st_seeds },
    { "S250", st_seeds },
    { "S251", st_seeds },
    { "S252", st_seeds },
    { "S253", st_seeds },
    { "S254", st_seeds },
    { "S255", st_seeds }
};

int np_hatch_pipe_init(np_pipe *p, const np_hatch_cfg *cfg)
{
    return np_pipe_init(p, stages, np_hatch_depth(cfg), sizeof(np_hatch_sig), cfg);
}

/* --- datapath declaration --- */

/* Signed bits of [-m, m]. */
static unsigned sbits(uint64_t m)
{
    unsigned n = 1;
    while (n < 64u && m > NP_MASK(n - 1u))
        n++;
    return n;
}

unsigned np_hatch_q_bits(const np_hatch_cfg *cfg)
{
    uint64_t m = 0;
    for (unsigned l = 0; l < cfg->layers; l++) {
        int16_t r[2][2];
        np_hatch_layer_r(cfg, l, r);
        for (unsigned row = 0; row < 2; row++) {
            uint64_t v = ((uint64_t)abs(r[row][0]) + (uint64_t)abs(r[row][1])) << 31;
            m = v > m ? v : m;
        }
    }
    return sbits(m);
}

unsigned np_hatch_k_bits(const np_hatch_cfg *cfg)
{
    uint64_t inv = cfg->inv_u > cfg->inv_v ? cfg->inv_u : cfg->inv_v;
    return np_bits_for_range(0, (int64_t)(NP_MASK(NP_HATCH_M_BITS) * inv), 0);
}

unsigned np_hatch_bigq_bits(const np_hatch_cfg *cfg)
{
    uint64_t inv = cfg->inv_u > cfg->inv_v ? cfg->inv_u : cfg->inv_v;
    np_u128 qm = (np_u128)1 << (np_hatch_q_bits(cfg) - 1u), km = (np_u128)NP_MASK(NP_HATCH_M_BITS) * inv;
    return sbits((uint64_t)((qm * km) >> 39) + 1u);
}

#define OP(st, sg, k, cnt, a, b, o, sgn, lv) np_dp_op(&d, st, sg, k, cnt, a, b, o, sgn, lv)

/* Set bits of v. */
static unsigned ones(uint32_t v)
{
    unsigned n = 0;
    for (; v; v &= v - 1u)
        n++;
    return n;
}

/* Bits of 0x1FFFF (the largest pm) times inv: k's live width on one axis. */
static unsigned k_axis_bits(unsigned inv)
{
    return np_bits_for_range(0, (int64_t)(NP_MASK(NP_HATCH_M_BITS) * inv), 0);
}

/*
 * The adders of a constant multiply-add c x + s y or c x - s y (np_hatch_seed.v's
 * q_u = RC r_u + RS r_v, q_v = RC r_v - RS r_u: RC, RS the layer's Q1.14 constants,
 * the operands and the sums s49 words). Yosys keeps
 * one row of the operand shifted by j for each set bit j of a constant (the
 * constant as the product's 49-bit two's complement word: a negative one is
 * sign-extended, so its high bits are rows too), truncated to the 49-bit sum,
 * 49 - j bits wide; the rows are summed by rows - 1 adders, the widest row
 * needing none; c x - s y with s y one power-of-two row and c = 0 is a negation
 * (*neg). Returns the adder count, *bits their total width.
 */
enum { ROT_W = 49 };
static unsigned rot_adders(int c, int s, int sub, unsigned *bits, unsigned *neg)
{
    unsigned rows = 0, sum = 0, widest = 0;
    const int k[2] = { c, s };
    for (unsigned t = 0; t < 2; t++) {
        uint64_t w = (uint64_t)(int64_t)k[t] & NP_MASK(ROT_W);
        for (unsigned j = 0; j < ROT_W; j++)
            if (w >> j & 1u) {
                rows++;
                sum += ROT_W - j;
                widest = ROT_W - j > widest ? ROT_W - j : widest;
            }
    }
    *bits = rows > 1u ? sum - widest : 0u;
    *neg = rows == 1u && sub && c == 0;
    return rows > 1u ? rows - 1u : 0u;
}

/*
 * The live bits of q = R r for one layer (c, s its Q1.14 constants, |r| <= 2^31): the
 * trailing zeros common to c and s are zero bits of q (at 0 and 90 degrees, c or s = 2^14
 * and the other 0, q is r << 14), which Yosys drops from the product q k.
 */
static unsigned q_live_bits(int c, int s)
{
    unsigned m = (unsigned)abs(c) | (unsigned)abs(s), tz = 0;
    while (tz < 15u && !(m >> tz & 1u))
        tz++;
    return sbits((((uint64_t)abs(c) + (uint64_t)abs(s)) >> tz) << 31);
}

/*
 * Stages A and S; the G = layers N / P seed stages S0..S(G-1) of the pipe are
 * identical, so they are declared as one row "S" whose counts are G times one
 * stage's (the gate report's stages are the declaration's: unit_hatch.c's
 * timing). The widths are the configuration's: k from 1/(F e), q from R, Q
 * from both; the traced signals are S0's.
 *
 * What the RTL (np_hatch.v, np_hatch_seed.v) builds, operator for operator,
 * where it differs from the C model's arithmetic: a seed's K = NOT33(st) +
 * 2^31 and its layer's (c, s) are constants (brute force), so d is a constant
 * add and R r a sum of shifted rows (rot_adders); k = pm inv is a constant
 * multiply too (rows of pm). The squares of the profile are squarers; mul30's
 * operands are the RTL's 32-bit words (u2, u4 are not known to Yosys to be
 * <= 2^30); at is 29 live bits (al's two low bits are 0), am 17 (oms << 14,
 * or 2^30 for a survivor); q k is at q's live width (q_live_bits: r << 14
 * at 0 and 90 degrees); the one-by-one fades are at their inputs' live bits
 * (al's 2 low zeros, m's 14); |Q| is the RTL's 44-bit word, and "|Q| < 1" a
 * zero test of its 14 integer bits. docs/hatch.md, "Synthesis", has the lane
 * against Yosys.
 */
size_t np_hatch_datapath(const np_hatch_cfg *cfg, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    unsigned n = np_hatch_n(cfg), p = cfg->lanes, f1 = 9u + cfg->guard;
    unsigned slots = cfg->cover_slots ? cfg->cover_slots : n, g = cfg->layers * slots / cfg->lanes;
    unsigned gp = g * p, obo = cfg->fade == NP_HATCH_FADE_ONE_BY_ONE;
    unsigned kb = np_hatch_k_bits(cfg), qb = np_hatch_q_bits(cfg), Qb = np_hatch_bigq_bits(cfg);
    unsigned kbu = k_axis_bits(cfg->inv_u), kbv = k_axis_bits(cfg->inv_v);
    /* The RTL's Q and |Q| words (np_hatch_seed.v: s44 Q14.30) and their integer bits. */
    const unsigned qw = 44u, qint = qw - 30u;
    /* Coverage: a list word per layer, slots indices of log2 N bits and a 4-bit length. */
    unsigned nb = log2u(n), tb = log2u(4u << np_hatch_sets[cfg->set].K), lw = slots * nb + 4u;
    /* What every bank carries besides c: x (66), the layer tones, oms (17), ku, kv, valid (and the lists). */
    unsigned carry = 66u + 31u * cfg->layers + 17u + 2u * kb + 1u + (cfg->cover_slots ? cfg->layers * lw : 0u);
    /* A: tone -> A (a 256-word constant ROM), the (4A - l) clamps, 1 - m saturation, the two k products. */
    OP("A", "A", NP_OP_ROM, 1, 8, 31, 31, 0, 0);
    OP("A", "al", NP_OP_ADD, cfg->layers, 33, 0, 31, 0, 1);
    OP("A", NULL, NP_OP_MUX, cfg->layers, 31, 3, 0, 0, 2);
    OP("A", "oms", NP_OP_CMP, 1, 17, 0, 17, 0, 0);
    OP("A", NULL, NP_OP_MUX, 1, 17, 2, 0, 0, 1);
    /* k = pm inv per axis: a row of pm per set bit of the constant inv, rows - 1 adders. */
    unsigned kadd = (ones(cfg->inv_u) - 1u) + (ones(cfg->inv_v) - 1u);
    OP("A", "k", NP_OP_ADD, kadd, kb, 0, kb, 0, 0);
    if (cfg->cover_slots) /* the list memory, one per layer, addressed by the texel (wiring from x) */
        OP("A", "list", NP_OP_ROM, cfg->layers, 2 * tb, lw, lw, 0, 0);
    OP("A", NULL, NP_OP_REG, 1, carry + f1, 0, 0, 0, 0);
    /* S: per seed, the parity add, survival, R r, 2 q k, the profile, the fades, alpha; then the blends. */
    unsigned lv = 0;
    if (cfg->cover_slots) {
        /* The slot's seed: W = rotl(b, i) for the list's i, two N-bit rotators; st is wiring from W. */
        OP("S", "W", NP_OP_MUX, 2 * gp * nb, n, 2, n, 0, lv);
        lv += nb;
        OP("S", NULL, NP_OP_CMPK, gp, 4, 0, 0, 0, 0);              /* enable: j < len */
        OP("S", NULL, NP_OP_MUX, gp, 31, 2, 0, 0, 7);              /* alpha 0 in an empty slot */
        OP("S", "d", NP_OP_ADD, 2 * gp, 33, 0, 33, 0, lv++);       /* st from the rotator: not a constant */
    } else {
        OP("S", "d", NP_OP_INC, 2 * gp, 33, 0, 33, 0, lv++);       /* x + K, K a constant of the lane */
    }
    OP("S", NULL, NP_OP_LUT, gp, 4, 1, 0, 0, lv);                 /* survival: two XNOR, one AND */
    /* q = R r: each layer's lanes (slots of them) with the layer's constant rows, at their mean width. */
    unsigned radd = 0, rbits = 0, rneg = 0;
    for (unsigned l = 0; l < cfg->layers; l++) {
        int16_t r[2][2];
        np_hatch_layer_r(cfg, l, r); /* r[0] = (RC, RS) */
        for (unsigned sub = 0; sub < 2; sub++) {
            unsigned bits, ng;
            radd += slots * rot_adders(r[0][0], r[0][1], (int)sub, &bits, &ng);
            rbits += slots * bits;
            rneg += slots * ng;
        }
    }
    OP("S", "q", NP_OP_ADD, radd, radd ? (rbits + radd / 2u) / radd : qb, 0, qb, 1, lv);
    OP("S", NULL, NP_OP_INC, rneg, ROT_W, 0, 0, 0, lv++);
    /*
     * q k: a signed product (k zero-extended), each axis at its k's live width, q at its layer's
     * live width (q_live_bits: at 0 and 90 degrees q is r << 14, and the product is r's 33 bits).
     */
    for (unsigned l = 0; l < cfg->layers; l++) {
        int16_t r[2][2];
        np_hatch_layer_r(cfg, l, r);
        unsigned ql = q_live_bits(r[0][0], r[0][1]);
        OP("S", NULL, NP_OP_SMUL, slots, ql, kbu, 0, 0, lv);
        OP("S", NULL, NP_OP_SMUL, slots, ql, kbv, 0, 0, lv);
    }
    lv++;
    OP("S", "Q", NP_OP_INC, 2 * gp, Qb + 1u, 0, Qb, 1, lv++);     /* + 2^38: the rounding constant */
    OP("S", NULL, NP_OP_NEG, 2 * gp, qw, 0, 0, 0, lv++);           /* |Q| */
    OP("S", NULL, NP_OP_CMPK, 2 * gp, qint, 0, 0, 0, lv++);        /* |Q| < 1: integer bits 0 */
    OP("S", NULL, NP_OP_SQR, 2 * gp, 30, 0, 0, 0, lv++);           /* U^2, V^2 */
    OP("S", NULL, NP_OP_SQR, 2 * gp, 32, 0, 0, 0, lv++);           /* U^4, V^4 */
    OP("S", NULL, NP_OP_SQR, gp, 32, 0, 0, 0, lv++);               /* U^8 */
    OP("S", NULL, NP_OP_INC, 2 * gp, 32, 0, 0, 0, lv);             /* 1 - U^8, 1 - V^4 */
    OP("S", NULL, NP_OP_MUX, gp, 32, 2, 0, 0, lv + 1u);            /* 0 outside the box */
    OP("S", "profile", NP_OP_MUL, gp, 32, 32, 31, 0, lv++);
    if (obo) {
        /*
         * Tone and level beside the stroke, each clamp((N+1) x - i, 0, 1) then S(t) = t^2 (3 - 2t),
         * at the live bits of x: the tone's al has its two low bits 0 (bits 2..30), the level's
         * m = (1 - oms) << 14 its 14 (bits 14..30), and those zeros pass to t (bits z..31), 3 - 2t
         * (bits z+1..31) and t^2. (N+1) x is two rows of x (N + 1 = 2^K + 1): an add over x's
         * live bits; - i 2^30 a constant on the top 10 bits, the clamp a test against 2^30 (the
         * sign is a bit) and a 3:1 choice; t^2 a squarer, 3 - 2t a constant minus a shift, the
         * product of t^2's 32-bit word by it; 1 - S for the level.
         */
        static const unsigned fz[2] = { 2u, 14u }; /* the low zero bits of al and of m */
        for (unsigned t = 0; t < 2; t++) {
            unsigned z = fz[t];
            OP("S", NULL, NP_OP_ADD, gp, 31u - z, 0, 0, 0, 1);
            OP("S", NULL, NP_OP_INC, gp, 10, 0, 0, 0, 1);
            OP("S", NULL, NP_OP_CMPK, gp, 40, 0, 0, 0, 2);
            OP("S", NULL, NP_OP_MUX, gp, 32u - z, 3, 0, 0, 2);
            OP("S", NULL, NP_OP_SQR, gp, 32u - z, 0, 0, 0, 3);
            OP("S", NULL, NP_OP_INC, gp, 31u - z, 0, 0, 0, 3);
            OP("S", NULL, NP_OP_MUL, gp, 32, 31u - z, 0, 0, 4);
        }
        OP("S", NULL, NP_OP_INC, gp, 32, 0, 0, 0, 5);
        OP("S", NULL, NP_OP_MUX, gp, 32, 2, 0, 0, 5);              /* am: 1 for a survivor, or the fade */
        OP("S", NULL, NP_OP_MUL, gp, 32, 32, 0, 0, 6);             /* at am */
    } else {
        OP("S", NULL, NP_OP_MUX, gp, 17, 2, 0, 0, 2);              /* am: 2^30 or oms << 14 */
        OP("S", NULL, NP_OP_MUL, gp, 29, 17, 0, 0, 6);             /* at am: live bits */
    }
    OP("S", "alpha", NP_OP_MUL, gp, 32, 32, 31, 0, lv++);
    /* The P blends of a stage are serial (compositing order matters): P (multiply, subtract) pairs of levels. */
    for (unsigned q = 0; q < p; q++) {
        OP("S", NULL, NP_OP_MUL, g, 31, f1, 0, 0, lv++);
        OP("S", q + 1u == p ? "c" : NULL, NP_OP_ADD, g, f1, 0, q + 1u == p ? f1 : 0, 0, lv++);
    }
    /* The last stage rounds the output: 255 c = 256 c - c, then the rounding add. */
    OP("S", NULL, NP_OP_ADD, 1, f1 + 8u, 0, 0, 0, lv++);
    OP("S", "out", NP_OP_ADD, 1, 8, 0, 8, 0, lv++);
    OP("S", NULL, NP_OP_REG, g - 1u, carry + f1, 0, 0, 0, 0);
    OP("S", NULL, NP_OP_REG, 1, 8u + 1u, 0, 0, 0, 0);
    return d.n;
}
