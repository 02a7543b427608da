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

#include "np_texel.h"
#include "unit_span.h"

typedef struct tx_cfg {
    np_texel_cfg c;
    unsigned tex;
} tx_cfg;
_Static_assert(sizeof(tx_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

static void cfg_default(void *cfg)
{
    tx_cfg *k = cfg;
    memset(k, 0, sizeof *k);
    k->c = np_texel_cfg_default();
}

static int cfg_set(void *cfg, const char *key, const char *value, char *err, size_t errlen)
{
    tx_cfg *k = cfg;
    static const struct { const char *name; size_t off; unsigned lo, hi; } keys[] = {
        { "idx_int", offsetof(np_texel_cfg, idx_int), 1, 11 },
        { "w_frac", offsetof(np_texel_cfg, w_frac), 1, 24 },
        { "guard", offsetof(np_texel_cfg, guard), 0, 100 },
        { "weight_frac", offsetof(np_texel_cfg, weight_frac), NP_TEXEL_WT_MIN, NP_TEXEL_WT_MAX },
        { "setup_mults", offsetof(np_texel_cfg, setup_mults), 1, 64 },
        { "mult_lat", offsetof(np_texel_cfg, mult_lat), 1, 16 },
    };
    if (strcmp(key, "texture") == 0)
        return np_ut_texture_set(value, &k->tex, err, errlen);
    for (unsigned i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (strcmp(key, keys[i].name) == 0) {
            char *end;
            unsigned long n = strtoul(value, &end, 10);
            if (*value == '\0' || *end != '\0' || *value == '-' || n < keys[i].lo || n > keys[i].hi) {
                snprintf(err, errlen, "%s=%s: out of range (%u..%u)", key, value, keys[i].lo, keys[i].hi);
                return -1;
            }
            *(unsigned *)(void *)((char *)&k->c + keys[i].off) = (unsigned)n;
            return 0;
        }
    snprintf(err, errlen, "unknown configuration key '%s' for unit texel (keys: texture, idx_int, w_frac, guard, "
             "weight_frac, setup_mults, mult_lat)", key);
    return -1;
}

static void cfg_format(const void *cfg, char *buf, size_t len)
{
    const tx_cfg *k = cfg;
    snprintf(buf, len, "texture=%s idx_int=%u w_frac=%u guard=%u weight_frac=%u setup_mults=%u mult_lat=%u",
             np_ut_texture_name(k->tex), k->c.idx_int, k->c.w_frac, k->c.guard, k->c.weight_frac, k->c.setup_mults,
             k->c.mult_lat);
}

static const char *cfg_check(const void *cfg) { return np_texel_cfg_check(&((const tx_cfg *)cfg)->c); }

static double error_bound(const void *cfg)
{
    const tx_cfg *k = cfg;
    const np_tex_regs *r = np_ut_regs(k->tex);
    double w = 1.0;
    for (unsigned i = 0; i < k->c.w_frac + 1u; i++)
        w *= 0.5;
    return 0.5 + (double)np_tex_colour_slope(r) * (np_texel_error_bound_index(&k->c, r) + w);
}

static size_t datapath(const void *cfg, np_op *ops, size_t max)
{
    const tx_cfg *k = cfg;
    return np_texel_datapath(&k->c, np_ut_regs(k->tex), ops, max);
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

/* The runtime report's sweep: the trilinear weights' bits. */
static const unsigned rep_wt[] = { 2, 4, 6, 8, 10, 12, 16, 32 };
static const np_unit_sweep tx_sweeps[] = {
    { "texel, weight bits", NULL, "weight_frac", rep_wt, sizeof rep_wt / sizeof rep_wt[0], 0, 3 },
};

static np_su tx_su = {
    .span = { &np_texel_engine, offsetof(tx_cfg, c), offsetof(tx_cfg, tex), tx_sweeps, 1, NULL, NULL },
    .engine_cfg_size = sizeof(np_texel_cfg),
    .front_name = "F",
};
NP_SU_DEFINE(tx_su, cfg_default);

const np_unit np_unit_texel = {
    .name = "texel",
    .summary = "per-pixel scanline texturing unit (trilinear value noise, pipelined): span in, pixels out",
    .cfg_default = cfg_default,
    .cfg_set = cfg_set,
    .cfg_format = cfg_format,
    .cfg_check = cfg_check,
    .error_bound_lsb = error_bound,
    .datapath = datapath,
    .timing = timing,
    NP_SU_MEMBERS(tx_su),
};
