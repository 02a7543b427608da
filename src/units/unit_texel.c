/* SPDX-License-Identifier: MIT */
/*
 * The per-pixel scanline texturing unit (rtl_model/np_texel.h) in the unit
 * registry: its configuration, error bound, datapath and timing; the rest is
 * the span-unit adapter (unit_span.h) around its engine, np_texel_engine.
 * Its pipe's front stage F places pixel k directly (u0 + k du, s + k ds: the
 * DDA's values, exactly, by a multiply) ahead of the unit's nine stages.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_rng.h"
#include "np_texel.h"
#include "unit_span.h"

typedef struct tx_cfg {
    np_texel_cfg c;
    unsigned tex;
} tx_cfg;
_Static_assert(sizeof(tx_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

/* The defaults are np_texel_cfg_default()'s (test core.unit_keys_model_defaults compares them). */
static const np_unit_key keys[] = {
    UT_TEXTURE_KEY(tx_cfg, tex),
    NP_UNIT_KEY("idx_int", tx_cfg, c.idx_int, NP_TEX_IDX_INT_MIN, 11, 10, "I: colour-map index integer bits"),
    NP_UNIT_KEY("w_frac", tx_cfg, c.w_frac, NP_TEX_W_FRAC_MIN, NP_TEX_W_FRAC_MAX, 12, "Fw: colour weight fraction bits"),
    NP_UNIT_KEY("guard", tx_cfg, c.guard, 0, 100, 20, "G: index fraction bits F = Fw + G"),
    NP_UNIT_KEY("weight_frac", tx_cfg, c.weight_frac, NP_TEXEL_WT_MIN, NP_TEXEL_WT_MAX, 16,
                "WT: trilinear weight fraction bits"),
    NP_UNIT_KEY("setup_mults", tx_cfg, c.setup_mults, 1, 64, 2, "P: multipliers of the span front end"),
    NP_UNIT_KEY("mult_lat", tx_cfg, c.mult_lat, 1, 16, 2, "Lm: their pipeline latency, clocks"),
    NP_UNIT_KEY_END,
};

static np_su tx_su;
static const char *cfg_check(const void *cfg)
{
    const char *why = np_texel_cfg_check(&((const tx_cfg *)cfg)->c);
    return why ? why : np_su_scene_index_check(&tx_su.span, cfg, 11);
}

static double error_bound(const void *cfg)
{
    const tx_cfg *k = cfg;
    const np_tex_regs *r = np_ut_regs(k->tex);
    double w = 1.0;
    for (unsigned i = 0; i < k->c.w_frac + 1u; i++)
        w *= 0.5;
    return 0.5 + (double)np_tex_colour_slope(r) * (np_texel_error_bound_index(&k->c, r) + w);
}

/*
 * The stream model's timing (np_texel.h): 1 clock to accept a descriptor,
 * the front end's set-up stall, then the nine pipeline stages; one pixel per
 * clock along the span. test report.latency_matches_model drives it.
 */
static int timing(const void *cfg, np_unit_timing *t, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    const tx_cfg *k = cfg;
    const np_tex_regs *r = np_ut_regs(k->tex);
    const np_tex_sched *front = np_tex_regs_diagonal(r) ? &np_tex_sched_octave_diag : &np_tex_sched_octave;
    memset(t, 0, sizeof *t);
    t->latency = 1u + np_texel_span_setup_cycles(&k->c, r) + NP_TEXEL_STAGES;
    t->throughput = 1.0;
    snprintf(t->throughput_note, sizeof t->throughput_note, "along a span; the span set-up stalls it (below)");
    t->n_multi = 1;
    t->multi[0].stage = "FE";
    t->multi[0].clocks = k->c.mult_lat;
    t->n_setup = 1;
    snprintf(t->setup[0].what, sizeof t->setup[0].what, "span: front end, per octave%s",
             np_tex_regs_diagonal(r) ? " (diagonal M)" : "");
    t->setup[0].products = r->n_oct * np_tex_sched_products(front);
    t->setup[0].cycles = np_texel_span_setup_cycles(&k->c, r);
    return 0;
}

/* The seek (np_unit_span.seek_cycles): u0 + k du and s + k ds, one more level of the front end after du, per octave and the quadric. */
static unsigned tx_seek_cycles(const void *ecfg, const np_tex_regs *r)
{
    const np_texel_cfg *c = ecfg;
    return (r->n_oct + 1u) * ((3u + c->setup_mults - 1u) / c->setup_mults + c->mult_lat - 1u);
}

/* The runtime report's sweep: the trilinear weights' bits. */
static const unsigned rep_wt[] = { 2, 4, 6, 8, 10, 12, 16, 32 };
static const np_unit_sweep tx_sweeps[] = {
    { "texel, weight bits", NULL, "weight_frac", rep_wt, sizeof rep_wt / sizeof rep_wt[0], 0, 3 },
};

/*
 * The signals for the conformance test's width check (np_unit_span.trace):
 * the pipeline's stages on random pixels and, every 16th, fractions at their
 * extremes, every 16th (the next) coordinates at the s48 ends. The quadric's
 * and the amplitude product's windows must give the roundings' bits.
 */
static const char *tx_trace(const void *ecfg, const np_tex_regs *r, np_rng *g, np_trace *t, size_t n)
{
    const np_texel_cfg *cfg = ecfg;
    const unsigned F = np_texel_frac(cfg), W = np_texel_width(cfg);
    const unsigned nf = NP_TEX_LAT_FRAC + 3u * cfg->weight_frac + NP_TEX_AMP_FRAC;
    np_texel_front front;
    np_texel_engine.init(&front, cfg, r);
    for (unsigned i = 0; i < 20000; i++) {
        np_texel_sig s;
        memset(&s, 0, sizeof s);
        for (unsigned o = 0; o < r->n_oct; o++)
            for (int a = 0; a < 3; a++)
                s.u[o][a] = i % 16u == 0 ? ((np_rng_next(g) & 0xff00000000ull) | (i & 32u ? 0xffffffffu : 0u))
                                         : np_rng_next(g) & NP_MASK(NP_TEX_U_BITS);
        for (int a = 0; a < 3; a++)
            s.s[a] = i % 16u == 1 ? (i & 32u ? -((int64_t)1 << 47) : ((int64_t)1 << 47) - 1)
                                  : np_sext(np_rng_next(g), NP_TEX_S_BITS);
        /* The front end's quadric at s (what its forward differences reach there). */
        const int64_t zero[3] = { 0, 0, 0 };
        np_s128 q[3];
        np_tex_quadric_exact(r, s.s, zero, q);
        s.qin = q[0];
        for (unsigned k = 0; k < NP_TEXEL_STAGES; k++) {
            np_texel_stages[k].fn(np_span_ctx_of(&front), &s);
            np_texel_trace(cfg, r, k, &s, t, n);
        }
        if (np_tex_to_index(np_wrap_s128(s.qx, np_texel_q_window(cfg, r)), np_tex_q_frac(r), F, W) != s.q)
            return "the quadric's window is too narrow for the rounding";
        for (unsigned o = 0; o < r->n_oct; o++)
            if (np_tex_to_index(np_wrap_s128(np_mul128((np_s128)r->oct[o].amp, s.l3[o]), np_texel_al_window(cfg)), nf,
                                F, W) != s.N[o])
                return "the amplitude product's window is too narrow for the rounding";
    }
    return NULL;
}

_Static_assert(sizeof(np_texel_front) <= NP_SU_CORE_MAX && sizeof(np_texel_sig) + NP_SU_SIG_HEAD <= NP_SU_SIG_MAX &&
                   (unsigned)NP_TEXEL_STAGES <= (unsigned)NP_SU_STAGES_MAX,
               "the engine fits the span-unit adapter");
static np_su tx_su = {
    .span = { &np_texel_engine, offsetof(tx_cfg, c), offsetof(tx_cfg, tex), tx_sweeps, 1, NULL, NULL, tx_trace,
              tx_seek_cycles },
    .engine_cfg_size = sizeof(np_texel_cfg),
    .idx_int_max = 11,
    .front_name = "F",
};
NP_SU_DEFINE(tx_su, np_unit_texel);

/* The conformance test's configurations besides the default (I, Fw, G, WT): 8 weight bits, narrow, the widest, the narrowest. */
static const char *const tx_configs[] = {
    "weight_frac=8", "idx_int=4,w_frac=8,guard=4,weight_frac=24", "idx_int=1,w_frac=24,guard=40,weight_frac=32",
    "idx_int=11,w_frac=1,guard=0,weight_frac=1", NULL,
};

const np_unit np_unit_texel = {
    .name = "texel",
    .summary = "per-pixel scanline texturing unit (trilinear value noise, pipelined): span in, pixels out",
    .keys = keys,
    .cfg_check = cfg_check,
    .error_bound_lsb = error_bound,
    .timing = timing,
    .conformance_configs = tx_configs,
    NP_SU_MEMBERS(tx_su),
};
