/* SPDX-License-Identifier: MIT */
/*
 * The per-pixel scanline texturing unit (rtl_model/np_texel.h) in the unit
 * registry. Transactions are pixels of spans (unit_tex.h, np_stream.h).
 * Besides the stream model (the unit's own timing: a span in, a pixel per
 * clock out) it has a true per-transaction pipeline: a front-end stage F
 * that places pixel k directly (u0 + k du, s + k ds: the DDA's values,
 * exactly, by a multiply) ahead of the unit's nine stages.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_scene.h"
#include "np_texel.h"
#include "unit_tex.h"

typedef struct tx_cfg {
    np_texel_cfg c;
    unsigned tex;
} tx_cfg;
_Static_assert(sizeof(tx_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

const np_texel_cfg *np_ut_texel_cfg(const void *cfg) { return &((const tx_cfg *)cfg)->c; }

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

static const char *cfg_check(const void *cfg) { return np_texel_cfg_check(&((const tx_cfg *)cfg)->c); }

static void fields(const void *cfg, np_unit_fields *f)
{
    (void)cfg;
    np_ut_fields(f);
}

/* The signal bundle of the per-transaction pipe: the transaction's words, then the unit's bundle. */
typedef struct tx_sig {
    uint64_t in[NP_UNIT_MAX_FIELDS];
    np_texel_sig t;
} tx_sig;

static np_texel_ctx ctx_of(const tx_cfg *k)
{
    np_texel_ctx c = { &k->c, np_ut_regs(k->tex) };
    return c;
}

/* F: the front end for pixel k: octave coordinates u0 + k du (mod 256) and s + k ds, as the DDAs reach them. */
static void st_f(const void *cfg, void *sig)
{
    const tx_cfg *k = cfg;
    tx_sig *s = sig;
    const np_tex_regs *r = np_ut_regs(k->tex);
    np_span sp;
    np_ut_span(s->in, &sp);
    uint64_t kk = np_trunc_u(s->in[UT_K], 16);
    s->t.px = (uint16_t)kk;
    s->t.py = 0;
    for (unsigned o = 0; o < r->n_oct; o++) {
        np_tex_oct_span os;
        np_tex_octave_span(r, o, sp.s, sp.ds, &os);
        for (unsigned a = 0; a < 3; a++)
            s->t.u[o][a] = np_trunc_u(os.u[a] + kk * (uint64_t)os.du[a], NP_TEX_U_BITS);
    }
    for (unsigned a = 0; a < 3; a++)
        s->t.s[a] = sp.s[a] + (int64_t)kk * sp.ds[a];
}

#define UNIT_STAGE(name, i)                                                                                            \
    static void name(const void *cfg, void *sig)                                                                       \
    {                                                                                                                  \
        np_texel_ctx c = ctx_of(cfg);                                                                                  \
        np_texel_stages[i].fn(&c, &((tx_sig *)sig)->t);                                                                \
    }
UNIT_STAGE(st_0, 0)
UNIT_STAGE(st_1, 1)
UNIT_STAGE(st_2, 2)
UNIT_STAGE(st_3, 3)
UNIT_STAGE(st_4, 4)
UNIT_STAGE(st_5, 5)
UNIT_STAGE(st_6, 6)
UNIT_STAGE(st_7, 7)
UNIT_STAGE(st_8, 8)
_Static_assert(NP_TEXEL_STAGES == 9, "one wrapper per stage of np_texel_stages");

static const np_stage_desc tx_stages[1 + NP_TEXEL_STAGES] = {
    { "F", st_f },   { "L", st_0 },  { "I1", st_1 }, { "I2", st_2 }, { "I3", st_3 },
    { "A", st_4 },   { "S", st_5 },  { "C1", st_6 }, { "C2", st_7 }, { "C3", st_8 },
};

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    tx_sig s;
    memset(&s, 0, sizeof s);
    memcpy(s.in, in, UT_NIN * sizeof in[0]);
    for (unsigned i = 0; i < 1 + NP_TEXEL_STAGES; i++)
        tx_stages[i].fn(cfg, &s);
    for (int ch = 0; ch < 3; ch++)
        out[ch] = s.t.rgb[ch];
}

static void ref(const void *cfg, const uint64_t *in, double *out) { np_ut_ref(((const tx_cfg *)cfg)->tex, in, out); }

static double error_bound(const void *cfg)
{
    const tx_cfg *k = cfg;
    const np_tex_regs *r = np_ut_regs(k->tex);
    double w = 1.0;
    for (unsigned i = 0; i < k->c.w_frac + 1u; i++)
        w *= 0.5;
    return 0.5 + (double)np_tex_colour_slope(r) * (np_texel_error_bound_index(&k->c, r) + w);
}

static int pipe_init(np_pipe *p, const void *cfg)
{
    return np_pipe_init(p, tx_stages, 1 + NP_TEXEL_STAGES, sizeof(tx_sig), cfg);
}

static void sig_set_in(void *sig, const uint64_t *in)
{
    tx_sig *s = sig;
    memset(s, 0, sizeof *s);
    memcpy(s->in, in, UT_NIN * sizeof in[0]);
}

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    (void)cfg;
    const tx_sig *s = sig;
    for (int ch = 0; ch < 3; ch++)
        out[ch] = s->t.rgb[ch];
}

static size_t boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
    return np_ut_boundary(in, max);
}

/* --- The stream model: np_texel_sim behind the generic stream port --- */

typedef struct tx_stream {
    np_texel_sim sim;
    np_span in;
    np_texel_port port;
} tx_stream;

static int s_init(void *state, const void *cfg)
{
    const tx_cfg *k = cfg;
    tx_stream *s = state;
    return np_texel_sim_init(&s->sim, &k->c, np_ut_regs(k->tex));
}

static void s_free(void *state) { np_texel_sim_free(&((tx_stream *)state)->sim); }

static void s_eval(void *state, np_unit_stream_port *p)
{
    tx_stream *s = state;
    memset(&s->port, 0, sizeof s->port);
    s->port.in_valid = p->in_valid;
    if (p->in_valid)
        np_ut_span(p->in, &s->in);
    s->port.in = &s->in;
    s->port.out_ready = p->out_ready;
    np_texel_sim_eval(&s->sim, &s->port);
    p->in_ready = s->port.in_ready;
    p->out_valid = s->port.out_valid;
    for (int ch = 0; ch < 3; ch++)
        p->out[ch] = s->port.out.rgb[ch];
}

static void s_clock(void *state, const np_unit_stream_port *p)
{
    (void)p;
    tx_stream *s = state;
    np_texel_sim_clock(&s->sim, &s->port);
}

static int s_idle(const void *state) { return np_texel_sim_idle(&((const tx_stream *)state)->sim); }

static void s_counters(const void *state, uint64_t *cycles, uint64_t *setup)
{
    const tx_stream *s = state;
    *cycles = s->sim.stats.cycles;
    *setup = s->sim.stats.setup_stalls;
}

static size_t s_descriptors(const void *cfg, uint64_t (*desc)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
    return np_ut_descriptors(desc, max);
}

static void s_random(const void *cfg, np_rng *rng, uint64_t *desc)
{
    (void)cfg;
    np_ut_random_desc(rng, desc);
}

static const np_unit_stream tx_stream_ops = {
    .n_desc = UT_NDESC,
    .length_field = UT_N,
    .beats = np_ut_beats,
    .descriptors = s_descriptors,
    .random_desc = s_random,
    .state_size = sizeof(tx_stream),
    .init = s_init,
    .free = s_free,
    .eval = s_eval,
    .clock = s_clock,
    .idle = s_idle,
    .counters = s_counters,
};

/* --- Gate and latency report --- */

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

static int cfg_scene(void *cfg, const np_scene *sc, char *err, size_t errlen)
{
    tx_cfg *k = cfg;
    np_unit_cfg_default(&np_unit_texel, k);
    return np_ut_cfg_scene(sc, &k->tex, err, errlen);
}

const np_unit np_unit_texel = {
    .name = "texel",
    .summary = "per-pixel scanline texturing unit (trilinear value noise, pipelined): span in, pixels out",
    .keys = keys,
    .cfg_check = cfg_check,
    .fields = fields,
    .eval = eval,
    .ref = ref,
    .tolerance_lsb = 1.0,
    .error_bound_lsb = error_bound,
    .pipe_init = pipe_init,
    .sig_set_in = sig_set_in,
    .sig_get_out = sig_get_out,
    .boundary = boundary,
    .stream = &tx_stream_ops,
    .datapath = datapath,
    .timing = timing,
    .cfg_scene = cfg_scene,
};
