/* SPDX-License-Identifier: MIT */
/*
 * A toy span unit that lives in this file only and is registered at run
 * time (np_unit_register): the second worked example of
 * docs/adding-a-unit.md. With no other file touched the renderer picks it
 * for a scene and renders with it (bit-exact and cycle-accurate), and it
 * gets golden vectors, verification through its stream model, every
 * conformance check and a gate report.
 *
 * The unit "toyramp" colours each pixel by its first texture coordinate
 * alone: a constant gradient through the texture's colour map. Its engine
 * (np_span.h) is
 *
 *   begin    x = s (s48 Q15.32), dx = ds (s41 Q8.32); `setup` clocks
 *   advance  x += dx; every `every` pixels (0: never) a 1-clock re-set-up
 *   issue    the pixel's x into the bundle
 *   stages   G (x as the colour index, s58 Q25.32: F = 32, W = 58), then
 *            the shared colour stages C1 C2 C3 (weight bits Fw = w_frac)
 *
 * x never wraps: |s| <= 2^47 and |k ds| < 2^56 for k < 65536, so x is
 * s + k ds exactly, and its float reference (the colour map interpolated at
 * s + k ds, in double) differs from the model only by the weight's rounding
 * (<= 2^-(Fw+1) of a segment) and the colour's (1/2 LSB).
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_conformance.h"
#include "np_render.h"
#include "np_report.h"
#include "np_rng.h"
#include "np_scene.h"
#include "np_test.h"
#include "np_vec.h"
#include "unit_span.h"

/* --- The engine --- */

enum { RAMP_F = NP_TEX_FC, RAMP_W = 58, RAMP_STAGES = 1 + NP_SPAN_COLOUR_STAGES, SIDE_BITS = 2 * NP_TEX_XY_BITS };

typedef struct ramp_cfg {
    unsigned w_frac; /* Fw: colour weight fraction bits */
    unsigned setup;  /* set-up clocks per span */
    unsigned every;  /* a 1-clock re-set-up after this many pixels; 0: none */
} ramp_cfg;

typedef struct ramp_core {
    np_span_ctx ctx; /* first (np_span.h) */
    int64_t x, dx;   /* s58 Q25.32, s41 Q8.32 */
    uint32_t k, n;
} ramp_core;

typedef struct ramp_sig {
    np_span_sig head; /* first (np_span.h) */
    int64_t x;        /* the pixel's coordinate, s58 Q25.32 */
} ramp_sig;

static void ramp_init(void *core, const void *cfg, const np_tex_regs *r)
{
    ramp_core *c = core;
    memset(c, 0, sizeof *c);
    c->ctx.cfg = cfg;
    c->ctx.r = r;
    c->ctx.F = RAMP_F;
    c->ctx.W = RAMP_W;
    c->ctx.fw = ((const ramp_cfg *)cfg)->w_frac;
}

static unsigned ramp_begin(void *core, const np_span *sp, np_span_counts *cnt)
{
    ramp_core *c = core;
    const unsigned setup = ((const ramp_cfg *)c->ctx.cfg)->setup;
    c->x = sp->s[0];
    c->dx = sp->ds[0];
    c->k = 0;
    c->n = sp->n;
    cnt->spans++;
    if (sp->n == 0)
        return 0;
    cnt->span_setups++;
    cnt->setup_cycles += setup;
    return setup;
}

static unsigned ramp_advance(void *core, np_span_counts *cnt)
{
    ramp_core *c = core;
    const unsigned every = ((const ramp_cfg *)c->ctx.cfg)->every;
    if (++c->k >= c->n)
        return 0;
    c->x += c->dx;
    if (every && c->k % every == 0) {
        cnt->interval_setups++;
        cnt->setup_cycles++;
        return 1;
    }
    return 0;
}

static void ramp_issue(const void *core, void *sig) { ((ramp_sig *)sig)->x = ((const ramp_core *)core)->x; }

static void ramp_seek(void *core, const np_span *sp, uint32_t k)
{
    ramp_core *c = core;
    c->x = sp->s[0] + (int64_t)k * sp->ds[0];
    c->dx = sp->ds[0];
    c->k = k;
    c->n = sp->n;
}

static void stage_g(const void *ctx, void *sig)
{
    (void)ctx;
    ramp_sig *s = sig;
    s->head.x = (np_s128)s->x;
}

static const np_stage_desc ramp_stages[RAMP_STAGES] = {
    { "G", stage_g }, { "C1", np_span_stage_c1 }, { "C2", np_span_stage_c2 }, { "C3", np_span_stage_c3 },
};

static size_t ramp_datapath(const void *cfg, const np_tex_regs *r, np_op *ops, size_t max)
{
    const ramp_cfg *c = cfg;
    np_dp d = { ops, max, 0 };
    np_dp_op(&d, "T", NULL, NP_OP_REG, 1, 24u * r->cmap_n + 9u, 0, 0, 0, 0); /* the colour table, N and the mode */
    /* D: x += dx; the pixel counter; with a re-set-up interval its counter. */
    np_dp_op(&d, "D", "x", NP_OP_ADD, 1, RAMP_W, 0, RAMP_W, 1, 0);
    np_dp_op(&d, "D", NULL, NP_OP_ADD, c->every ? 2 : 1, NP_TEX_N_BITS, 0, 0, 0, 0);
    np_dp_op(&d, "D", NULL, NP_OP_CMP, c->every ? 2 : 1, NP_TEX_N_BITS, 0, 0, 0, 1);
    np_dp_op(&d, "D", NULL, NP_OP_REG, 1,
             RAMP_W + NP_TEX_DS_BITS + (c->every ? 3u : 2u) * NP_TEX_N_BITS + SIDE_BITS + 1u, 0, 0, 0, 0);
    /* G: x is the index as it is (wiring). */
    np_dp_op(&d, "G", NULL, NP_OP_REG, 1, RAMP_W + SIDE_BITS + 1u, 0, 0, 0, 0);
    np_tex_dp_colour(&d, r, RAMP_F, RAMP_W, c->w_frac, 0, SIDE_BITS);
    return d.n;
}

static const np_span_engine ramp_engine = {
    .name = "toyramp",
    .core_size = sizeof(ramp_core),
    .sig_size = sizeof(ramp_sig),
    .stages = ramp_stages,
    .n_stages = RAMP_STAGES,
    .init = ramp_init,
    .begin = ramp_begin,
    .advance = ramp_advance,
    .issue = ramp_issue,
    .seek = ramp_seek,
    .datapath = ramp_datapath,
};

/* --- The unit: configuration, reference, timing, trace; the span-unit adapter does the rest --- */

typedef struct toy_cfg {
    ramp_cfg e;
    unsigned tex;
} toy_cfg;
_Static_assert(sizeof(toy_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

static const np_unit_key toy_keys[] = {
    UT_TEXTURE_KEY(toy_cfg, tex),
    NP_UNIT_KEY("w_frac", toy_cfg, e.w_frac, 8, NP_TEX_W_FRAC_MAX, 12, "Fw: colour weight fraction bits"),
    NP_UNIT_KEY("setup", toy_cfg, e.setup, 1, 16, 3, "set-up clocks per span"),
    NP_UNIT_KEY("every", toy_cfg, e.every, 0, NP_TEX_SPAN_MAX, 0, "a 1-clock re-set-up after this many pixels; 0: none"),
    NP_UNIT_KEY_END,
};

/* The colour map of the registers at x (in segments), in double: what the colour stages round. */
static void toy_ref(const void *cfg, const uint64_t *in, double *out)
{
    const np_tex_regs *r = np_ut_regs(((const toy_cfg *)cfg)->tex);
    np_span sp;
    np_ut_span(in, &sp);
    const double x = ldexp((double)sp.s[0], -NP_TEX_FC) + (double)np_trunc_u(in[UT_K], 16) * ldexp((double)sp.ds[0], -NP_TEX_FC);
    const unsigned n = r->cmap_n;
    double seg = floor(x), f = x - seg;
    unsigned a, b;
    if (r->cmap_repeat) {
        a = (unsigned)((((int64_t)seg % (int64_t)n) + (int64_t)n) % (int64_t)n);
        b = (a + 1u) % n;
    } else if (x < 0) {
        a = b = 0;
        f = 0;
    } else if (x >= (double)(n - 1u)) {
        a = b = n - 1u;
        f = 0;
    } else {
        a = (unsigned)seg;
        b = a + 1u;
    }
    for (int ch = 0; ch < 3; ch++)
        out[ch] = (double)r->cmap[a][ch] + f * ((double)r->cmap[b][ch] - (double)r->cmap[a][ch]);
}

static double toy_error_bound(const void *cfg)
{
    const toy_cfg *k = cfg;
    return 0.5 + (double)np_tex_colour_slope(np_ut_regs(k->tex)) * ldexp(1.0, -(int)k->e.w_frac - 1);
}

static int toy_timing(const void *cfg, np_unit_timing *t, char *err, size_t errlen)
{
    (void)err;
    (void)errlen;
    const toy_cfg *k = cfg;
    memset(t, 0, sizeof *t);
    t->latency = 1u + k->e.setup + RAMP_STAGES;
    t->throughput = 1.0;
    snprintf(t->throughput_note, sizeof t->throughput_note, "along a span; set-ups stall it (below)");
    np_su_add_setup(t, "span", 0, k->e.setup);
    if (k->e.every)
        np_su_add_setup(t, "re-set-up after `every` pixels", 0, 1);
    return 0;
}

/*
 * The signals for the conformance width check: pixels of random spans
 * (placed by seek) and, every 16th, the far end: s at an s48 end, the
 * largest step of that sign, the last pixel (|x| just over 2^56).
 */
static const char *toy_trace(const void *ecfg, const np_tex_regs *r, np_rng *g, np_trace *t, size_t n)
{
    ramp_core c;
    ramp_sig s;
    ramp_init(&c, ecfg, r);
    for (unsigned i = 0; i < 20000; i++) {
        np_span sp;
        memset(&sp, 0, sizeof sp);
        sp.n = NP_TEX_SPAN_MAX;
        sp.s[0] = np_sext(np_rng_next(g), NP_TEX_S_BITS);
        sp.ds[0] = np_asr(np_sext(np_rng_next(g), NP_TEX_DS_BITS), (unsigned)np_rng_below(g, 41));
        uint32_t k = (uint32_t)np_rng_below(g, NP_TEX_SPAN_MAX);
        if (i % 16u == 0) {
            sp.s[0] = i & 32u ? -((int64_t)1 << 47) : ((int64_t)1 << 47) - 1;
            sp.ds[0] = i & 32u ? -((int64_t)1 << 40) : ((int64_t)1 << 40) - 1;
            k = NP_TEX_SPAN_MAX - 1u;
        }
        ramp_seek(&c, &sp, k);
        memset(&s, 0, sizeof s);
        ramp_issue(&c, &s);
        np_tex_trace(t, n, "x", c.x);
        for (unsigned st = 0; st < RAMP_STAGES; st++)
            ramp_stages[st].fn(&c.ctx, &s);
        np_tex_trace_colour(r, s.head.seg, s.head.cw, s.head.prod, s.head.pix.rgb, c.ctx.fw, t, n);
    }
    return NULL;
}

static const char *const toy_configs[] = { "w_frac=8,setup=1,every=1", "w_frac=24,setup=16,every=7", NULL };

_Static_assert(sizeof(ramp_core) <= NP_SU_CORE_MAX && sizeof(ramp_sig) + NP_SU_SIG_HEAD <= NP_SU_SIG_MAX &&
                   (unsigned)RAMP_STAGES <= (unsigned)NP_SU_STAGES_MAX,
               "the engine fits the span-unit adapter");
static np_su toy_su = {
    .span = { &ramp_engine, offsetof(toy_cfg, e), offsetof(toy_cfg, tex), NULL, 0, NULL, NULL, toy_trace },
    .engine_cfg_size = sizeof(ramp_cfg),
    .front_name = "F",
    .ref = toy_ref,
};
static const np_unit toy_unit;
NP_SU_DEFINE(toy_su, toy_unit);

static const np_unit toy_unit = {
    .name = "toyramp",
    .summary = "toy span unit: a constant gradient along s through the colour map (docs/adding-a-unit.md)",
    .keys = toy_keys,
    .error_bound_lsb = toy_error_bound,
    .timing = toy_timing,
    .conformance_configs = toy_configs,
    NP_SU_MEMBERS(toy_su),
};

/* --- The test --- */

static const np_unit *toy(void)
{
    if (!np_unit_find(toy_unit.name))
        NP_CHECK(np_unit_register(&toy_unit) == 0, "register %s", toy_unit.name);
    return np_unit_find(toy_unit.name);
}

static int toy_register(void)
{
    const np_unit *u = toy();
    NP_CHECK(u == &toy_unit, "np_unit_find sees the registered unit");
    size_t n = 0, at = SIZE_MAX;
    for (const np_unit *v; (v = np_unit_at(n)) != NULL; n++)
        if (v == u)
            at = n;
    NP_CHECK(at != SIZE_MAX && at + 1 == n, "np_unit_at: %zu units, toyramp at %zu", n, at);
    NP_CHECK(u->span && u->span->engine == &ramp_engine && u->stream, "a span unit with the adapter's stream model");
    printf("toyramp registered as unit %zu of %zu, a span unit (engine %s, %u stages)\n", at, n, ramp_engine.name,
           ramp_engine.n_stages);
    return 0;
}

/* The seed scene wood, its frame and the units that render it; 0, or 1 after a failed check. */
static np_scene scene;
static np_render_frame frame;
static np_render_unit_cfg units[NP_RENDER_MAX_UNITS];
static int n_units;

static int prepare(void)
{
    char err[512];
    toy();
    NP_CHECK(np_scene_load("embedded:wood", &scene, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_render_prepare(&scene, &frame, err, sizeof err) == 0, "%s", err);
    n_units = np_render_units(&scene, NULL, NULL, units, err, sizeof err);
    NP_CHECK(n_units > 0, "np_render_units: %s", err);
    return np_test_failures ? 1 : 0;
}

static np_render_unit_cfg *toy_in_units(void)
{
    for (int i = 0; i < n_units; i++)
        if (units[i].u == &toy_unit)
            return &units[i];
    return NULL;
}

static int toy_render_units(void)
{
    if (prepare())
        return 1;
    const np_render_unit_cfg *c = toy_in_units();
    char names[256] = "";
    for (int i = 0; i < n_units; i++)
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? ", " : "", units[i].u->name);
    NP_CHECK(c != NULL, "scene wood renders with %s, not toyramp", names);
    if (!c)
        return 1;
    char tex[64];
    np_unit_key_text(&toy_keys[0], &c->cfg, tex, sizeof tex);
    NP_CHECK(strcmp(tex, "scene:wood") == 0, "texture %s, not the scene's", tex);
    printf("scene wood renders with: %s; toyramp configured as %s, texture %s\n", names, c->text, tex);
    return 0;
}

/*
 * Render the frame with the toy at `more` over its scene configuration:
 * the cycle model's pixels and counts equal the bit-exact model's, the
 * cycles are what the engine says (spans + set-up clocks + pixels + stages,
 * no gaps, no stalls), and every pixel of the image is the unit's eval.
 */
static void render_with(const char *more)
{
    np_render_unit_cfg *c = toy_in_units();
    char err[512];
    NP_CHECK(np_render_unit_reconfigure(c, more, err, sizeof err) == 0, "%s", err);
    const toy_cfg *k = (const toy_cfg *)(const void *)&c->cfg;
    uint64_t spans = frame.n_spans, busy = 0, intervals = 0, pixels = 0;
    for (size_t i = 0; i < frame.n_spans; i++) {
        uint32_t n = frame.spans[i].hw.n;
        pixels += n;
        busy += n > 0;
        intervals += n > 0 && k->e.every ? (n - 1u) / k->e.every : 0u;
    }
    const uint64_t setup = busy * k->e.setup + intervals, want = spans + setup + pixels + RAMP_STAGES;
    np_render_run run;
    NP_CHECK(np_render_unit(&frame, &toy_unit, &c->cfg, 1, &run) == 0, "render");
    NP_CHECK(run.have_cycles && run.cycle_mismatch == 0, "cycle model against bit-exact: %llu mismatches",
             (unsigned long long)run.cycle_mismatch);
    NP_CHECK(run.cycles == want && run.setup_stalls == setup && run.out_stalls == 0,
             "%llu cycles (%llu set-up), the engine says %llu (%llu)", (unsigned long long)run.cycles,
             (unsigned long long)run.setup_stalls, (unsigned long long)want, (unsigned long long)setup);
    NP_CHECK(run.span_setups == busy && run.interval_setups == intervals && run.cell_setups == 0,
             "set-ups: %llu span, %llu interval", (unsigned long long)run.span_setups,
             (unsigned long long)run.interval_setups);
    /* Each covered pixel is the last span's over it (scene order): eval's colour at its k. */
    unsigned char *seen = calloc((size_t)scene.width * scene.height, 1);
    uint64_t checked = 0, bad = 0;
    for (size_t i = frame.n_spans; seen && i-- > 0;) {
        const np_span *sp = &frame.spans[i].hw;
        uint64_t in[NP_UNIT_MAX_FIELDS] = { 0 }, out[NP_UNIT_MAX_FIELDS];
        for (unsigned a = 0; a < 3; a++) {
            in[UT_S + a] = np_trunc_u((uint64_t)sp->s[a], NP_TEX_S_BITS);
            in[UT_DS + a] = np_trunc_u((uint64_t)sp->ds[a], NP_TEX_DS_BITS);
        }
        in[UT_N] = sp->n;
        for (uint32_t x = 0; x < sp->n; x++) {
            size_t p = (size_t)sp->y * scene.width + sp->x0 + x;
            if (seen[p]++)
                continue;
            in[UT_K] = x;
            toy_unit.eval(&c->cfg, in, out);
            checked++;
            bad += out[0] != run.rgb[3 * p] || out[1] != run.rgb[3 * p + 1] || out[2] != run.rgb[3 * p + 2];
        }
    }
    free(seen);
    NP_CHECK(checked > 0 && bad == 0, "%llu of %llu pixels differ from eval", (unsigned long long)bad,
             (unsigned long long)checked);
    printf("toyramp [%s]: %llu spans, %llu pixels: %llu cycles (%llu set-up: %llu span, %llu interval), as its engine "
           "says; cycle model = bit-exact model = eval on every pixel (%llu)\n",
           c->text, (unsigned long long)spans, (unsigned long long)pixels, (unsigned long long)run.cycles,
           (unsigned long long)setup, (unsigned long long)busy, (unsigned long long)intervals,
           (unsigned long long)checked);
    np_render_run_free(&run);
}

static int toy_render(void)
{
    if (prepare() || !toy_in_units())
        return 1;
    NP_CHECK(np_render_reference(&frame) == 0, "reference image"); /* the run's error is measured against it */
    render_with(NULL);
    render_with("every=5,setup=7");
    return 0;
}

/* The toy's golden set and KAT, written in the build tree by each case that needs them (np_conf_toy_generate). */
static np_conf_toy files;

static int toy_generate(const char *tag) { return np_conf_toy_generate(&files, toy(), NP_CONF_WORK, tag, "every=3"); }

static int toy_verify(void) { return toy_generate("verify") || np_conf_toy_verify(&files); }

static int toy_conformance(void) { return toy_generate("conformance") || np_conf_toy_conformance(&files); }

static int toy_vectors(void)
{
    np_vec_reader r;
    if (toy_generate("vectors") != 0 || np_conf_toy_open(&files, &r) != 0)
        return 1;
    np_vec_rec rec;
    uint64_t n = 0, spans = 0, bad = 0;
    double worst = 0;
    int rc;
    while ((rc = np_vec_read(&r, &rec)) == 1) {
        uint64_t out[NP_UNIT_MAX_FIELDS];
        toy_unit.eval(&r.h.cfg, rec.w[NP_VEC_IN], out);
        for (unsigned ch = 0; ch < 3; ch++) {
            bad += out[ch] != rec.w[NP_VEC_OUT][ch];
            worst = fmax(worst, fabs((double)rec.w[NP_VEC_OUT][ch] - np_vec_ref_value(rec.w[NP_VEC_REF][ch])));
        }
        spans += rec.w[NP_VEC_IN][UT_K] == 0;
        n++;
    }
    NP_CHECK(rc == 0 && n == r.h.count && n > 100, "%llu vectors read: %s", (unsigned long long)n, r.L.err);
    NP_CHECK(bad == 0, "%llu outputs differ from eval", (unsigned long long)bad);
    NP_CHECK(worst <= toy_error_bound(&r.h.cfg), "|model - reference| %.3f LSB over the bound %.3f", worst,
             toy_error_bound(&r.h.cfg));
    printf("toyramp: %llu golden vectors (pixels of %llu spans), each eval's; |model - reference| <= %.3f LSB "
           "(bound %.3f)\n",
           (unsigned long long)n, (unsigned long long)spans, worst, toy_error_bound(&r.h.cfg));
    np_vec_close(&r);
    return 0;
}

static int toy_gates(void)
{
    const np_unit *u = toy();
    np_unit_cfg cfg;
    np_unit_cost c;
    char err[256];
    for (int every = 0; every < 2; every++) {
        NP_CHECK(np_unit_configure(u, &cfg, every ? "every=4" : NULL, err, sizeof err) == 0, "%s", err);
        NP_CHECK(np_unit_cost_compute(u, &cfg, &np_cost_default, &c, err, sizeof err) == 0, "%s", err);
        np_report_gates_md(stdout, &c, 1, "toyramp gates");
        const toy_cfg *k = (const toy_cfg *)(const void *)&cfg;
        NP_CHECK(c.n_stages == 6 && c.has_timing && c.latency == 1u + k->e.setup + RAMP_STAGES && c.total > 0.0 &&
                     c.timing.n_setup == 1u + (unsigned)every,
                 "%u stages, latency %u, %.1f gates, %u set-ups", c.n_stages, c.latency, c.total, c.timing.n_setup);
    }
    return 0;
}

static const np_test_case cases[] = {
    { "register", toy_register }, { "render_units", toy_render_units }, { "render", toy_render },
    { "vectors", toy_vectors },   { "verify", toy_verify },             { "conformance", toy_conformance },
    { "gates", toy_gates },       { NULL, NULL },
};
NP_TEST_MAIN(cases)
