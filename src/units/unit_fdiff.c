/* SPDX-License-Identifier: MIT */
/*
 * The forward-difference scanline texturing unit (rtl_model/np_fdiff.h) in
 * the unit registry: its configuration, error bound, datapath and timing;
 * the rest is the span-unit adapter (unit_span.h) around its engine,
 * np_fdiff_engine. Its pipe's front stage R runs the core from the span's
 * start (the forward differences are sequential).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_fdiff.h"
#include "np_rng.h"
#include "unit_span.h"

typedef struct fd_cfg {
    np_fdiff_cfg c;
    unsigned tex;
} fd_cfg;
_Static_assert(sizeof(fd_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

/* The defaults are np_fdiff_cfg_default()'s (test core.unit_keys_model_defaults compares them). */
static const np_unit_key keys[] = {
    UT_TEXTURE_KEY(fd_cfg, tex),
    NP_UNIT_KEY("idx_int", fd_cfg, c.idx_int, NP_TEX_IDX_INT_MIN, 11, 10, "I: colour-map index integer bits"),
    NP_UNIT_KEY("w_frac", fd_cfg, c.w_frac, NP_TEX_W_FRAC_MIN, NP_TEX_W_FRAC_MAX, 12, "Fw: colour weight fraction bits"),
    NP_UNIT_KEY("guard", fd_cfg, c.guard, 0, NP_FDIFF_GUARD_MAX, 44,
                "G: guard bits of the difference registers, index fraction F = Fw + G"),
    NP_UNIT_KEY("resetup", fd_cfg, c.resetup, 0, NP_TEX_SPAN_MAX, 0, "K: re-set-up after K steps without one; 0: off"),
    NP_UNIT_KEY("setup_mults", fd_cfg, c.setup_mults, 1, NP_FDIFF_MULTS_MAX, 2, "P: multipliers of the set-up engine"),
    NP_UNIT_KEY("mult_lat", fd_cfg, c.mult_lat, 1, NP_FDIFF_LAT_MAX, 2, "Lm: their pipeline latency, clocks"),
    NP_UNIT_KEY_END,
};

static np_su fd_su;
static const char *cfg_check(const void *cfg)
{
    const char *why = np_fdiff_cfg_check(&((const fd_cfg *)cfg)->c);
    return why ? why : np_su_scene_index_check(&fd_su.span, cfg, 11);
}

/*
 * The colour bound at the map's slope, every octave drifting over runs of at
 * most m = max_span - 1 steps (or K, the re-set-up interval, when shorter)
 * and the quadric over the span, against the exact texture at the unit's
 * coordinates (np_fdiff.h); the float reference adds the front end's and the
 * registers' roundings (docs/fdiff.md).
 */
static double bound_span(const void *cfg, unsigned max_span)
{
    const fd_cfg *k = cfg;
    const np_tex_regs *r = np_ut_regs(k->tex);
    const uint64_t ms = max_span > 1u ? max_span - 1u : 0u;
    const uint64_t m = k->c.resetup && k->c.resetup < ms ? k->c.resetup : ms;
    double idx = (double)r->n_oct * np_fdiff_drift_bound_noise(np_fdiff_frac(&k->c), m) +
                 np_fdiff_drift_bound_quad(np_fdiff_frac(&k->c), ms);
    return 0.5 + (double)np_tex_colour_slope(r) * (idx + ldexp(1.0, -(int)k->c.w_frac - 1));
}

/* Over any span (m <= 65,535 steps). */
static double error_bound(const void *cfg) { return bound_span(cfg, NP_TEX_SPAN_MAX); }

/*
 * The stream model's timing (np_fdiff.h): 1 clock to accept a descriptor,
 * the span set-up stall, then the colour pipeline; one pixel per clock while
 * no set-up stalls the core. test report.latency_matches_model drives it.
 */
static int timing(const void *cfg, np_unit_timing *t, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    const fd_cfg *k = cfg;
    const np_tex_regs *r = np_ut_regs(k->tex);
    const np_tex_sched *front = np_tex_regs_diagonal(r) ? &np_tex_sched_octave_diag : &np_tex_sched_octave;
    const unsigned pc = np_tex_sched_products(&np_fdiff_sched_cell), pq = np_tex_sched_products(&np_fdiff_sched_quad),
                   pf = np_tex_sched_products(front);
    memset(t, 0, sizeof *t);
    t->latency = 1u + np_fdiff_span_setup_latency(&k->c, r) + NP_FDIFF_TAIL_STAGES;
    t->throughput = 1.0;
    snprintf(t->throughput_note, sizeof t->throughput_note,
             "a set-up overlaps stepping; a cell shorter than its set-up stalls it (below)");
    t->n_multi = 1;
    t->multi[0].stage = "SU";
    t->multi[0].clocks = k->c.mult_lat;
    np_su_add_setup(t, "span: quadric, per octave front end + cell",
                    pq + r->n_oct * (pf + pc), np_fdiff_span_setup_latency(&k->c, r));
    np_su_add_setup(t, "cell, per octave (overlaps the cells before)", pc, np_fdiff_cell_cycles(&k->c));
    np_su_add_setup(t, "quadric", pq, np_fdiff_quad_cycles(&k->c));
    np_su_add_setup(t, np_tex_regs_diagonal(r) ? "front end, per octave (diagonal M)" : "front end, per octave", pf,
              np_tex_sched_cycles(front, k->c.setup_mults, k->c.mult_lat));
    if (k->c.resetup)
        np_su_add_setup(t, "re-set-up after K steps: cell / quadric", pc, np_fdiff_cell_cycles(&k->c));
    return 0;
}

/*
 * The runtime report's sweeps (docs/fdiff.md): guard bits against the
 * re-set-up interval K (the guard bits do not change the cycles), and the
 * set-up engine's multipliers (the bits do not change).
 */
static const unsigned rep_guard[] = { 0, 2, 4, 6, 8, 10, 12, 16, 20, 24, 32, 44 };
static const unsigned rep_p[] = { 1, 4, 16 }; /* besides the default */
enum { N_G = sizeof rep_guard / sizeof rep_guard[0], N_P = sizeof rep_p / sizeof rep_p[0] };
static const np_unit_sweep fd_sweeps[] = {
    { "fdiff K=0, guard", "resetup=0", "guard", rep_guard, N_G, 1, 0 },
    { "fdiff K=8, guard", "resetup=8", "guard", rep_guard, N_G, 1, 1 },
    { "fdiff K=32, guard", "resetup=32", "guard", rep_guard, N_G, 1, 2 },
    { "fdiff K=0, set-up multipliers", NULL, "setup_mults", rep_p, N_P, 0, 4 },
};

/*
 * The signals for the conformance test's width check (np_unit_span.trace):
 * cell set-ups (random cells and steps, and every fourth one at the extremes:
 * fractions 0 or all ones, steps -2^39 or 2^39 - 1), then spans through the
 * core and the colour stages. The set-up's window must give the rounding's bits.
 */
static const char *fd_trace(const void *ecfg, const np_tex_regs *r, np_rng *g, np_trace *t, size_t n)
{
    const np_fdiff_cfg *cfg = ecfg;
    const unsigned F = np_fdiff_frac(cfg);
    for (unsigned i = 0; i < 40000; i++) {
        uint64_t u[3];
        int64_t du[3];
        for (int a = 0; a < 3; a++) {
            u[a] = np_rng_next(g) & NP_MASK(NP_TEX_U_BITS);
            unsigned sh = (unsigned)np_rng_below(g, 40);
            du[a] = np_asr(np_sext(np_rng_next(g), NP_TEX_DU_BITS), sh);
        }
        if (i % 4u == 0)
            for (int a = 0; a < 3; a++) {
                u[a] = (u[a] & ~(uint64_t)NP_MASK(NP_TEX_FC)) | (i & 8u ? NP_MASK(NP_TEX_FC) : 0u);
                du[a] = i & 16u ? -((int64_t)1 << 39) : ((int64_t)1 << 39) - 1;
            }
        unsigned o = (unsigned)np_rng_below(g, r->n_oct);
        np_s128 d[4];
        np_fdiff_setup_sig sig;
        np_fdiff_cell_setup_sig(cfg, r, o, u, du, d, &sig);
        np_fdiff_trace_setup(cfg, &sig, t, n);
        uint8_t lat[8];
        np_tex_lattice(np_tex_cell(u[0]), np_tex_cell(u[1]), np_tex_cell(u[2]), lat);
        for (int k = 0; k < 8; k++)
            np_tex_trace(t, n, "n", lat[k]);
        for (unsigned j = 0; j < 4; j++)
            if (np_tex_to_index(np_wrap_s128(sig.y[j], np_fdiff_y_window(cfg)), NP_FDIFF_EXACT_FRAC, F,
                                np_fdiff_width(cfg)) != d[j])
                return "the set-up's window Y is too narrow for the rounding";
    }
    for (unsigned i = 0; i < 300; i++) {
        np_span sp;
        memset(&sp, 0, sizeof sp);
        sp.n = 1u + (uint32_t)np_rng_below(g, 200);
        for (int a = 0; a < 3; a++) {
            sp.s[a] = np_sext(np_rng_next(g), 40);
            sp.ds[a] = np_asr(np_sext(np_rng_next(g), 32), (unsigned)np_rng_below(g, 24));
        }
        if (np_span_check(&sp) != NULL)
            continue;
        np_fdiff_core core;
        np_span_counts cnt;
        memset(&cnt, 0, sizeof cnt);
        np_fdiff_core_init(&core, cfg, r);
        np_fdiff_core_begin(&core, &sp, &cnt);
        for (uint32_t k = 0; k < sp.n; k++) {
            np_fdiff_trace_core(&core, t, n);
            np_span_sig s;
            memset(&s, 0, sizeof s);
            s.x = np_fdiff_core_x(&core);
            for (unsigned st = 0; st < NP_SPAN_COLOUR_STAGES; st++)
                np_span_colour_stages[st].fn(np_span_ctx_of(&core), &s);
            np_tex_trace_colour(r, s.seg, s.cw, s.prod, s.pix.rgb, cfg->w_frac, t, n);
            np_fdiff_core_advance(&core, &cnt);
        }
    }
    return NULL;
}

_Static_assert(sizeof(np_fdiff_core) <= NP_SU_CORE_MAX && sizeof(np_span_sig) + NP_SU_SIG_HEAD <= NP_SU_SIG_MAX &&
                   (unsigned)NP_FDIFF_TAIL_STAGES <= (unsigned)NP_SU_STAGES_MAX,
               "the engine fits the span-unit adapter");
static np_su fd_su = {
    .span = { &np_fdiff_engine, offsetof(fd_cfg, c), offsetof(fd_cfg, tex), fd_sweeps,
              sizeof fd_sweeps / sizeof fd_sweeps[0], "g4", "guard=4",
              fd_trace, NULL }, /* seek_cycles: none (only texel has a seek cost) */
    .engine_cfg_size = sizeof(np_fdiff_cfg),
    .idx_int_max = 11,
    .bound_span = bound_span,
    .front_name = "R",
};
NP_SU_DEFINE(fd_su, np_unit_fdiff);

/*
 * The conformance test's configurations besides the default (I, Fw, G, K):
 * few guard bits with K, narrow, the widest, the narrowest index.
 */
static const char *const fd_configs[] = {
    "guard=8,resetup=16", "idx_int=4,w_frac=8,guard=0", "idx_int=11,w_frac=24,guard=91,resetup=256",
    "idx_int=1,w_frac=1,guard=20", NULL,
};

const np_unit np_unit_fdiff = {
    .name = "fdiff",
    .summary = "forward-difference scanline texturing unit: span in, pixels out (Kameya & Hart, Bresenham Noise)",
    .keys = keys,
    .cfg_check = cfg_check,
    .error_bound_lsb = error_bound,
    .timing = timing,
    .conformance_configs = fd_configs,
    NP_SU_MEMBERS(fd_su),
};
