/* SPDX-License-Identifier: MIT */
/*
 * The forward-difference scanline texturing unit (rtl_model/np_fdiff.h) in
 * the unit registry, and what it shares with the per-pixel unit
 * (unit_tex.h). Transactions are pixels of spans (np_stream.h); the
 * cycle-accurate model is the stream model (np_unit.stream).
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_fdiff.h"
#include "np_ref.h"
#include "np_scene.h"
#include "np_texreg.h"
#include "unit_tex.h"

/* --- Shared with unit_texel.c --- */

void np_ut_set_field(np_field *f, const char *name, unsigned bits, int sgn, unsigned frac, const char *fmt)
{
    snprintf(f->name, sizeof f->name, "%s", name);
    f->bits = bits;
    f->is_signed = sgn;
    f->frac = frac;
    snprintf(f->format, sizeof f->format, "%s", fmt);
}

void np_ut_fields(np_unit_fields *f)
{
    memset(f, 0, sizeof *f);
    f->n_in = UT_NIN;
    f->n_out = 3;
    np_ut_set_field(&f->in[UT_S], "s", NP_TEX_S_BITS, 1, NP_TEX_FC, "s48 Q15.32");
    np_ut_set_field(&f->in[UT_T], "t", NP_TEX_S_BITS, 1, NP_TEX_FC, "s48 Q15.32");
    np_ut_set_field(&f->in[UT_R], "r", NP_TEX_S_BITS, 1, NP_TEX_FC, "s48 Q15.32");
    np_ut_set_field(&f->in[UT_DS], "ds", NP_TEX_DS_BITS, 1, NP_TEX_FC, "s41 Q8.32");
    np_ut_set_field(&f->in[UT_DT], "dt", NP_TEX_DS_BITS, 1, NP_TEX_FC, "s41 Q8.32");
    np_ut_set_field(&f->in[UT_DR], "dr", NP_TEX_DS_BITS, 1, NP_TEX_FC, "s41 Q8.32");
    np_ut_set_field(&f->in[UT_N], "n", NP_TEX_N_BITS, 0, 0, "u17");
    np_ut_set_field(&f->in[UT_K], "k", 16, 0, 0, "u16");
    np_ut_set_field(&f->out[0], "cr", 8, 0, 0, "u8");
    np_ut_set_field(&f->out[1], "cg", 8, 0, 0, "u8");
    np_ut_set_field(&f->out[2], "cb", 8, 0, 0, "u8");
}

void np_ut_span(const uint64_t *in, np_span *sp)
{
    memset(sp, 0, sizeof *sp);
    for (unsigned a = 0; a < 3; a++) {
        sp->s[a] = np_sext(in[UT_S + a], NP_TEX_S_BITS);
        sp->ds[a] = np_sext(in[UT_DS + a], NP_TEX_DS_BITS);
    }
    sp->n = (uint32_t)np_trunc_u(in[UT_N], NP_TEX_N_BITS);
}

/* Built-in textures, then the textures of scenes (np_ut_texture_add). */
enum { N_TEX = 3, N_SCENE_TEX = 8 };
static np_tex_regs ut_regs[N_TEX + N_SCENE_TEX];
static np_ref_texture ut_scene_tex[N_SCENE_TEX];
static char ut_scene_name[N_SCENE_TEX][80];
static unsigned ut_n_scene;
static pthread_once_t ut_once = PTHREAD_ONCE_INIT;
static pthread_mutex_t ut_lock = PTHREAD_MUTEX_INITIALIZER;

static void ut_compile(void)
{
    char err[256];
    for (unsigned i = 0; i < N_TEX; i++)
        if (np_texreg_compile(np_texreg_builtin(np_texreg_builtin_name(i)), &ut_regs[i], err, sizeof err) != 0)
            abort(); /* the built-in textures fit (test render.builtin_textures) */
}

const np_tex_regs *np_ut_regs(unsigned tex)
{
    pthread_once(&ut_once, ut_compile);
    return &ut_regs[tex < N_TEX + ut_n_scene ? tex : 0];
}

const char *np_ut_texture_name(unsigned tex)
{
    return tex >= N_TEX && tex < N_TEX + ut_n_scene ? ut_scene_name[tex - N_TEX] : np_texreg_builtin_name(tex);
}

/* The float texture of texture number tex. */
static const np_ref_texture *ut_ref_texture(unsigned tex)
{
    if (tex >= N_TEX && tex < N_TEX + ut_n_scene)
        return &ut_scene_tex[tex - N_TEX];
    return np_texreg_builtin(np_texreg_builtin_name(tex < N_TEX ? tex : 0));
}

int np_ut_texture_add(const char *name, const np_ref_texture *t, unsigned *tex, char *err, size_t errlen)
{
    np_tex_regs r;
    if (np_texreg_compile(t, &r, err, errlen) != 0)
        return -1;
    pthread_once(&ut_once, ut_compile);
    pthread_mutex_lock(&ut_lock);
    int rc = 0;
    unsigned i = 0;
    while (i < ut_n_scene && strcmp(ut_scene_name[i], name) != 0)
        i++;
    if (i == N_SCENE_TEX) {
        snprintf(err, errlen, "texture %s: at most %d scene textures", name, N_SCENE_TEX);
        rc = -1;
    } else {
        snprintf(ut_scene_name[i], sizeof ut_scene_name[i], "%s", name);
        ut_scene_tex[i] = *t;
        ut_regs[N_TEX + i] = r;
        if (i == ut_n_scene)
            ut_n_scene++;
    }
    pthread_mutex_unlock(&ut_lock);
    if (rc == 0)
        *tex = N_TEX + i;
    return rc;
}

int np_ut_cfg_scene(const np_scene *sc, unsigned *tex, char *err, size_t errlen)
{
    char name[80];
    snprintf(name, sizeof name, "scene:%s", sc->name);
    return np_ut_texture_add(name, &sc->tex, tex, err, errlen) == 0 ? 1 : -1;
}

void np_ut_ref(unsigned tex, const uint64_t *in, double *out)
{
    const np_ref_texture *t = ut_ref_texture(tex);
    np_span sp;
    np_ut_span(in, &sp);
    double k = (double)np_trunc_u(in[UT_K], 16);
    double st[3];
    for (unsigned a = 0; a < 3; a++) /* equation 14 on the descriptor's exact values */
        st[a] = ldexp((double)sp.s[a], -NP_TEX_FC) + k * ldexp((double)sp.ds[a], -NP_TEX_FC);
    np_ref_colour(&t->cmap, np_ref_texture_f(t, st, NULL), out);
}

uint64_t np_ut_beats(const void *cfg, const uint64_t *desc)
{
    (void)cfg;
    return np_trunc_u(desc[UT_N], NP_TEX_N_BITS);
}

/*
 * Annotated descriptors, each with the reason it is there (the stiff and
 * extreme cases of docs/fdiff.md; testbench/test_fdiff.c measures them).
 * Values in Q15.32 / Q8.32 units.
 */
#define Q32(x) ((int64_t)((x) * 4294967296.0))
static const struct {
    int64_t s[3], ds[3];
    uint32_t n;
} ut_desc[] = {
    /* One pixel: only the set-up value. */
    { { Q32(12.3125), Q32(45.5), Q32(6.0078125) }, { Q32(0.5), Q32(0.5), Q32(0.5) }, 1 },
    /* Cell boundaries exactly on pixel centres, on all three axes (up, up, down). */
    { { Q32(0.5), Q32(3.5), Q32(9.5) }, { Q32(0.25), Q32(0.25), -Q32(0.25) }, 64 },
    /* The lattice wrap at 256, upward and downward. */
    { { Q32(255.5), Q32(511.75), Q32(100.0) }, { Q32(1.0 / 256), Q32(1.0 / 512), Q32(1.0 / 128) }, 400 },
    { { Q32(0.5), -Q32(255.75), Q32(256.25) }, { -Q32(1.0 / 256), -Q32(1.0 / 512), -Q32(1.0 / 128) }, 400 },
    /* The largest step s41 Q8.32 holds (256 - 2^-32): wraps to -2^-32 in the lattice. */
    { { -Q32(15000.25), -Q32(15000.5), Q32(100.125) }, { 0xffffffffffLL, 0xffffffffffLL, -0xffffffffffLL }, 120 },
    /* A new cell every pixel. */
    { { Q32(0.5), Q32(0.25), Q32(0.125) }, { Q32(127.75), -Q32(127.5), Q32(100.0) }, 200 },
    /* The smallest non-zero step, one LSB per pixel, 65,536 pixels. */
    { { Q32(5.5), Q32(6.25), Q32(7.75) }, { 1, 1, 1 }, 65536 },
    /* 65,536 pixels inside one cell, all three axes moving: the longest drift. */
    { { Q32(10.0) + (1 << 12), Q32(20.0) + (1 << 20), Q32(30.0) + (1 << 16) }, { 0xfff0, 0xff00, 0xfe00 }, 65536 },
    /* Zero steps: a constant span. */
    { { Q32(77.125), Q32(3.0625), Q32(1.5) }, { 0, 0, 0 }, 100 },
    /* A diagonal through the seed's texture cube, 256 pixels from (0,0,0) to (2,2,2) (the seed's figure 9). */
    { { 0, 0, 0 }, { Q32(2.0 / 256), Q32(2.0 / 256), Q32(2.0 / 256) }, 256 },
};
enum { N_UT_DESC = sizeof ut_desc / sizeof ut_desc[0] };

static void desc_words(unsigned i, uint64_t *d)
{
    for (unsigned a = 0; a < 3; a++) {
        d[UT_S + a] = np_trunc_u((uint64_t)ut_desc[i].s[a], NP_TEX_S_BITS);
        d[UT_DS + a] = np_trunc_u((uint64_t)ut_desc[i].ds[a], NP_TEX_DS_BITS);
    }
    d[UT_N] = ut_desc[i].n;
}

size_t np_ut_descriptors(uint64_t (*desc)[NP_UNIT_MAX_FIELDS], size_t max)
{
    for (unsigned i = 0; i < N_UT_DESC && i < max; i++)
        desc_words(i, desc[i]);
    return N_UT_DESC;
}

void np_ut_random_desc(np_rng *rng, uint64_t *d)
{
    /* Spans of 1..64 pixels over a texture region of up to +-64, steps from 2^-32 to 8 per pixel. */
    for (unsigned a = 0; a < 3; a++) {
        int64_t s = (int64_t)np_rng_below(rng, (uint64_t)1 << 39) - ((int64_t)1 << 38);
        unsigned sh = (unsigned)np_rng_below(rng, 34);
        int64_t ds = np_asr((int64_t)np_rng_below(rng, (uint64_t)1 << 36) - ((int64_t)1 << 35), sh);
        d[UT_S + a] = np_trunc_u((uint64_t)s, NP_TEX_S_BITS);
        d[UT_DS + a] = np_trunc_u((uint64_t)ds, NP_TEX_DS_BITS);
    }
    d[UT_N] = 1u + np_rng_below(rng, 64);
}

size_t np_ut_boundary(uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    size_t n = 0;
    for (unsigned i = 0; i < N_UT_DESC; i++) {
        if (ut_desc[i].n > 64)
            continue; /* the generic generator's table holds whole short spans; np_stream_generate takes all */
        for (uint32_t k = 0; k < ut_desc[i].n; k++, n++)
            if (n < max) {
                desc_words(i, in[n]);
                in[n][UT_K] = k;
            }
    }
    return n;
}

/* --- The forward-difference unit --- */

typedef struct fd_cfg {
    np_fdiff_cfg c;
    unsigned tex;
} fd_cfg;
_Static_assert(sizeof(fd_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

const np_fdiff_cfg *np_ut_fdiff_cfg(const void *cfg) { return &((const fd_cfg *)cfg)->c; }

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

static const char *cfg_check(const void *cfg) { return np_fdiff_cfg_check(&((const fd_cfg *)cfg)->c); }

static void fields(const void *cfg, np_unit_fields *f)
{
    (void)cfg;
    np_ut_fields(f);
}

/*
 * Pixel k of a span: the core run from the span's start (the forward
 * differences are sequential). A per-thread cache continues the last span
 * when the next pixel asked for is of the same span and not before it, so a
 * span's pixels in order cost one step each.
 */
typedef struct fd_cache {
    int valid;
    np_fdiff_cfg cfg;
    unsigned tex;
    np_span sp;
    np_fdiff_core core;
    np_fdiff_counts cnt;
} fd_cache;
static _Thread_local fd_cache cache;

static np_s128 pixel_x(const fd_cfg *k, const uint64_t *in)
{
    np_span sp;
    np_ut_span(in, &sp);
    sp.n = NP_TEX_SPAN_MAX; /* the value of pixel k does not depend on n */
    uint32_t want = (uint32_t)np_trunc_u(in[UT_K], 16);
    fd_cache *c = &cache;
    if (!c->valid || memcmp(&c->cfg, &k->c, sizeof c->cfg) != 0 || c->tex != k->tex ||
        memcmp(c->sp.s, sp.s, sizeof sp.s) != 0 || memcmp(c->sp.ds, sp.ds, sizeof sp.ds) != 0 || c->core.k > want) {
        memset(c, 0, sizeof *c);
        c->cfg = k->c;
        c->tex = k->tex;
        c->sp = sp;
        np_fdiff_core_init(&c->core, &c->cfg, np_ut_regs(k->tex));
        np_fdiff_core_begin(&c->core, &c->sp, &c->cnt);
        c->valid = 1;
    }
    while (c->core.k < want)
        np_fdiff_core_advance(&c->core, &c->cnt);
    return np_fdiff_core_x(&c->core);
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    const fd_cfg *k = cfg;
    uint8_t rgb[3];
    np_tex_colour(np_ut_regs(k->tex), pixel_x(k, in), np_fdiff_frac(&k->c), k->c.w_frac, rgb);
    for (int ch = 0; ch < 3; ch++)
        out[ch] = rgb[ch];
}

static void ref(const void *cfg, const uint64_t *in, double *out) { np_ut_ref(((const fd_cfg *)cfg)->tex, in, out); }

static double error_bound(const void *cfg)
{
    /*
     * The colour bound for one octave at the map's slope over a run of m <= 65,535 steps,
     * against the exact texture at the unit's coordinates (np_fdiff.h); the float
     * reference adds the front end's and the registers' roundings (docs/fdiff.md).
     */
    const fd_cfg *k = cfg;
    const np_tex_regs *r = np_ut_regs(k->tex);
    uint64_t m = k->c.resetup ? k->c.resetup : NP_TEX_SPAN_MAX - 1u;
    double idx = (double)r->n_oct * np_fdiff_drift_bound_noise(np_fdiff_frac(&k->c), m) +
                 np_fdiff_drift_bound_quad(np_fdiff_frac(&k->c), NP_TEX_SPAN_MAX - 1u);
    return 0.5 + (double)np_tex_colour_slope(r) * (idx + ldexp(1.0, -(int)k->c.w_frac - 1));
}

/*
 * The per-transaction pipe (np_unit.pipe_init), for tools that drive one
 * input per clock: stage R computes the pixel's index by the core (run from
 * the span's start, as eval), then the unit's colour pipeline C1 C2 C3. It
 * gives the unit's bits but not its timing: the forward-difference core is
 * sequential, and its cycle-accurate model is the stream model below.
 */
typedef struct fd_sig {
    uint64_t in[NP_UNIT_MAX_FIELDS];
    np_fdiff_tail_sig t;
} fd_sig;

static np_fdiff_tail_ctx tail_ctx(const fd_cfg *k)
{
    np_fdiff_tail_ctx t = { np_ut_regs(k->tex), np_fdiff_frac(&k->c), k->c.w_frac };
    return t;
}

static void st_r(const void *cfg, void *sig)
{
    fd_sig *s = sig;
    s->t.x = pixel_x(cfg, s->in);
}

#define TAIL_STAGE(name, i)                                                                                            \
    static void name(const void *cfg, void *sig)                                                                       \
    {                                                                                                                  \
        np_fdiff_tail_ctx t = tail_ctx(cfg);                                                                           \
        np_fdiff_tail_stages[i].fn(&t, &((fd_sig *)sig)->t);                                                           \
    }
TAIL_STAGE(st_c1, 0)
TAIL_STAGE(st_c2, 1)
TAIL_STAGE(st_c3, 2)

static const np_stage_desc fd_stages[] = { { "R", st_r }, { "C1", st_c1 }, { "C2", st_c2 }, { "C3", st_c3 } };

static int pipe_init(np_pipe *p, const void *cfg) { return np_pipe_init(p, fd_stages, 4, sizeof(fd_sig), cfg); }

static void sig_set_in(void *sig, const uint64_t *in)
{
    fd_sig *s = sig;
    memset(s, 0, sizeof *s);
    memcpy(s->in, in, UT_NIN * sizeof in[0]);
}

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    (void)cfg;
    const fd_sig *s = sig;
    for (int ch = 0; ch < 3; ch++)
        out[ch] = s->t.rgb[ch];
}

static size_t boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
    return np_ut_boundary(in, max);
}

/* --- The stream model: np_fdiff_sim behind the generic stream port --- */

typedef struct fd_stream {
    np_fdiff_sim sim;
    np_span in;
    np_fdiff_port port;
} fd_stream;

static int s_init(void *state, const void *cfg)
{
    const fd_cfg *k = cfg;
    fd_stream *s = state;
    return np_fdiff_sim_init(&s->sim, &k->c, np_ut_regs(k->tex));
}

static void s_free(void *state) { np_fdiff_sim_free(&((fd_stream *)state)->sim); }

static void s_eval(void *state, np_unit_stream_port *p)
{
    fd_stream *s = state;
    memset(&s->port, 0, sizeof s->port);
    s->port.in_valid = p->in_valid;
    if (p->in_valid)
        np_ut_span(p->in, &s->in);
    s->port.in = &s->in;
    s->port.out_ready = p->out_ready;
    np_fdiff_sim_eval(&s->sim, &s->port);
    p->in_ready = s->port.in_ready;
    p->out_valid = s->port.out_valid;
    for (int ch = 0; ch < 3; ch++)
        p->out[ch] = s->port.out.rgb[ch];
}

static void s_clock(void *state, const np_unit_stream_port *p)
{
    (void)p;
    fd_stream *s = state;
    np_fdiff_sim_clock(&s->sim, &s->port);
}

static int s_idle(const void *state) { return np_fdiff_sim_idle(&((const fd_stream *)state)->sim); }

static void s_counters(const void *state, uint64_t *cycles, uint64_t *setup)
{
    const fd_stream *s = state;
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

static const np_unit_stream fd_stream_ops = {
    .n_desc = UT_NDESC,
    .length_field = UT_N,
    .beats = np_ut_beats,
    .descriptors = s_descriptors,
    .random_desc = s_random,
    .state_size = sizeof(fd_stream),
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
    const fd_cfg *k = cfg;
    return np_fdiff_datapath(&k->c, np_ut_regs(k->tex), ops, max);
}

static void add_setup(np_unit_timing *t, const char *what, unsigned products, unsigned cycles)
{
    if (t->n_setup < NP_UNIT_MAX_SETUPS) {
        np_unit_setup *s = &t->setup[t->n_setup++];
        snprintf(s->what, sizeof s->what, "%s", what);
        s->products = products;
        s->cycles = cycles;
    }
}

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
    t->latency = 1u + np_fdiff_span_setup_cycles(&k->c, r) + NP_FDIFF_TAIL_STAGES;
    t->throughput = 1.0;
    snprintf(t->throughput_note, sizeof t->throughput_note, "inside a cell; a set-up stalls it (below)");
    t->n_multi = 1;
    t->multi[0].stage = "SU";
    t->multi[0].clocks = k->c.mult_lat;
    add_setup(t, "span: quadric + per octave front end and cell", pq + r->n_oct * (pf + pc),
              np_fdiff_span_setup_cycles(&k->c, r));
    add_setup(t, "cell, per octave on a cell change", pc, np_fdiff_cell_cycles(&k->c));
    add_setup(t, "quadric", pq, np_fdiff_quad_cycles(&k->c));
    add_setup(t, np_tex_regs_diagonal(r) ? "front end, per octave (diagonal M)" : "front end, per octave", pf,
              np_tex_sched_cycles(front, k->c.setup_mults, k->c.mult_lat));
    if (k->c.resetup)
        add_setup(t, "re-set-up after K steps: cell / quadric", pc, np_fdiff_cell_cycles(&k->c));
    return 0;
}

static int cfg_scene(void *cfg, const np_scene *sc, char *err, size_t errlen)
{
    fd_cfg *k = cfg;
    np_unit_cfg_default(&np_unit_fdiff, k);
    return np_ut_cfg_scene(sc, &k->tex, err, errlen);
}

const np_unit np_unit_fdiff = {
    .name = "fdiff",
    .summary = "forward-difference scanline texturing unit: span in, pixels out (Kameya & Hart, Bresenham Noise)",
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
    .stream = &fd_stream_ops,
    .datapath = datapath,
    .timing = timing,
    .cfg_scene = cfg_scene,
};
