/* SPDX-License-Identifier: MIT */
/*
 * The one registry adapter of the span units (unit_span.h): textures,
 * descriptors, the float reference, and the engine of rtl_model/np_span.h
 * behind eval, the per-transaction pipe and the stream model.
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_ref.h"
#include "np_texreg.h"
#include "unit_span.h"

/* --- Textures and descriptors --- */

void np_su_fields(const void *cfg, np_unit_fields *f)
{
    (void)cfg;
    memset(f, 0, sizeof *f);
    f->n_in = UT_NIN;
    f->n_out = 3;
    np_unit_set_field(&f->in[UT_S], "s", NP_TEX_S_BITS, 1, NP_TEX_FC, "s48 Q15.32");
    np_unit_set_field(&f->in[UT_T], "t", NP_TEX_S_BITS, 1, NP_TEX_FC, "s48 Q15.32");
    np_unit_set_field(&f->in[UT_R], "r", NP_TEX_S_BITS, 1, NP_TEX_FC, "s48 Q15.32");
    np_unit_set_field(&f->in[UT_DS], "ds", NP_TEX_DS_BITS, 1, NP_TEX_FC, "s41 Q8.32");
    np_unit_set_field(&f->in[UT_DT], "dt", NP_TEX_DS_BITS, 1, NP_TEX_FC, "s41 Q8.32");
    np_unit_set_field(&f->in[UT_DR], "dr", NP_TEX_DS_BITS, 1, NP_TEX_FC, "s41 Q8.32");
    np_unit_set_field(&f->in[UT_N], "n", NP_TEX_N_BITS, 0, 0, "u17");
    np_unit_set_field(&f->in[UT_K], "k", 16, 0, 0, "u16");
    np_unit_set_field(&f->out[0], "cr", 8, 0, 0, "u8");
    np_unit_set_field(&f->out[1], "cg", 8, 0, 0, "u8");
    np_unit_set_field(&f->out[2], "cb", 8, 0, 0, "u8");
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
enum { N_TEX = 3, N_SCENE_TEX = 16 };
static np_tex_regs ut_regs[N_TEX + N_SCENE_TEX];
static np_ref_texture ut_scene_tex[N_SCENE_TEX];
static char ut_scene_name[N_SCENE_TEX][80];
static np_texreg_scene_bound ut_scene_bound[N_SCENE_TEX]; /* set by np_su_cfg_scene */
static int ut_scene_has_bound[N_SCENE_TEX];
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

/* np_ut_texture_add with the registers already compiled (r). */
static int ut_texture_add_regs(const char *name, const np_ref_texture *t, const np_tex_regs *rr, unsigned *tex,
                               char *err, size_t errlen)
{
    const np_tex_regs r = *rr;
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

int np_ut_texture_add(const char *name, const np_ref_texture *t, unsigned *tex, char *err, size_t errlen)
{
    np_tex_regs r;
    if (np_texreg_compile(t, &r, err, errlen) != 0)
        return -1;
    return ut_texture_add_regs(name, t, &r, tex, err, errlen);
}

const np_texreg_scene_bound *np_ut_texture_bound(unsigned tex)
{
    return tex >= N_TEX && tex < N_TEX + ut_n_scene && ut_scene_has_bound[tex - N_TEX] ? &ut_scene_bound[tex - N_TEX]
                                                                                         : NULL;
}

const char *np_su_scene_index_check(const np_unit_span *s, const void *cfg, unsigned idx_int_max)
{
    static _Thread_local char msg[400];
    unsigned tex = np_su_texture(s, cfg);
    const np_texreg_scene_bound *b = np_ut_texture_bound(tex);
    const unsigned I = *(const unsigned *)np_su_engine_cfg(s, cfg);
    if (!b || b->idx_int_need <= I)
        return NULL;
    np_texreg_scene_check(np_ut_texture_name(tex), b, 0, I, idx_int_max, msg, sizeof msg);
    return msg;
}

/* The unsigned key name of u's configuration block cfg, or NULL. */
static unsigned *ut_key(const np_unit *u, void *cfg, const char *name)
{
    for (const np_unit_key *k = u->keys; k && k->name; k++)
        if (strcmp(k->name, name) == 0 && k->size == sizeof(unsigned))
            return (unsigned *)(void *)((char *)cfg + k->offset);
    return NULL;
}

static double ut_own_bound(const np_su *su, const np_unit *u, const void *cfg, unsigned max_span)
{
    if (su->bound_span)
        return su->bound_span(cfg, max_span);
    return u->error_bound_lsb ? u->error_bound_lsb(cfg) : 0.5;
}

double np_su_predicted_lsb(const np_unit *u, const void *cfg, unsigned max_span)
{
    const np_su *su = (const np_su *)(const void *)u->span; /* np_unit.span is np_su's first member */
    const np_texreg_scene_bound *b = np_ut_texture_bound(np_su_texture(u->span, cfg));
    if (!b)
        return (double)NAN;
    return ut_own_bound(su, u, cfg, max_span) + b->reg_lsb;
}

int np_su_cfg_scene(const np_su *su, const np_unit *u, void *cfg, const np_unit_scene *sc, char *err, size_t errlen)
{
    unsigned *tex = (unsigned *)(void *)((char *)cfg + su->span.texture_offset);
    char name[80];
    if (sc->noise_unit) /* the octaves read a 4-D noise unit, not the span units' value noise */
        return 0;
    const int sized = sc->size_registers && su->idx_int_max;
    snprintf(name, sizeof name, "%s:%s", sized ? "sized" : "scene", sc->name);
    if (!sized && np_ut_texture_add(name, sc->tex, tex, err, errlen) != 0)
        return -1;
    if (!su->idx_int_max)
        return 1;
    /*
     * Register rounding inside the bound (issue 10): over the box of the
     * scene's texture coordinates and its longest possible span (the image
     * width), the unit's own bound plus the registers' must be <= 1 LSB, and
     * a clamped map's index must fit; else the scene is refused.
     */
    const double *lo = sc->tex_lo, *hi = sc->tex_hi;
    np_texreg_scene_bound b;
    if (sized) {
        /*
         * Registers sized by the scene (issue 10): the transform and quadric
         * formats within NP_TEXREG_SIZE_BUDGET (np_texreg_size), the fewest
         * index integer bits (a clamped map's index range; log2 N for a
         * repeating one), then the fewest guard bits whose own bound over the
         * scene's widest span plus the registers' is <= 1 LSB.
         */
        np_texreg_fmt fmt;
        np_tex_regs r;
        if (np_texreg_size(sc->tex, lo, hi, sc->width, NP_TEXREG_SIZE_BUDGET, &fmt, &r, &b, err, errlen) != 0 ||
            ut_texture_add_regs(name, sc->tex, &r, tex, err, errlen) != 0)
            return -1;
        unsigned *I = (unsigned *)(void *)((char *)cfg + su->span.engine_cfg_offset), need = b.idx_int_need;
        if (r.cmap_repeat)
            while ((1u << need) < r.cmap_n)
                need++;
        if (need <= su->idx_int_max)
            *I = need;
        unsigned *G = ut_key(u, cfg, "guard");
        if (G) {
            const np_unit_key *gk = u->keys;
            while (strcmp(gk->name, "guard") != 0)
                gk++;
            const unsigned g0 = *G;
            for (*G = gk->lo; *G <= gk->hi; ++*G)
                if (ut_own_bound(su, u, cfg, sc->width) + b.reg_lsb <= 1.0)
                    break;
            if (*G > gk->hi)
                *G = g0; /* none holds: the check below refuses with the default's numbers */
        }
    } else {
        np_texreg_scene_bound_compute(sc->tex, np_ut_regs(*tex), lo, hi, sc->width, &b);
    }
    pthread_mutex_lock(&ut_lock);
    ut_scene_bound[*tex - N_TEX] = b;
    ut_scene_has_bound[*tex - N_TEX] = 1;
    pthread_mutex_unlock(&ut_lock);
    const double own = ut_own_bound(su, u, cfg, sc->width);
    return np_texreg_scene_check(sc->name, &b, own, *(const unsigned *)np_su_engine_cfg(&su->span, cfg),
                                 su->idx_int_max, err, errlen) == 0
               ? 1
               : -1;
}

void np_su_ref(const np_su *su, const void *cfg, const uint64_t *in, double *out)
{
    if (su->ref) {
        su->ref(cfg, in, out);
        return;
    }
    const np_ref_texture *t = ut_ref_texture(np_su_texture(&su->span, cfg));
    np_span sp;
    np_ut_span(in, &sp);
    double k = (double)np_trunc_u(in[UT_K], 16);
    double st[3];
    for (unsigned a = 0; a < 3; a++) /* equation 14 on the descriptor's exact values */
        st[a] = ldexp((double)sp.s[a], -NP_TEX_FC) + k * ldexp((double)sp.ds[a], -NP_TEX_FC);
    np_ref_colour(&t->cmap, np_ref_texture_f(t, st, NULL), out);
}

uint64_t np_su_beats(const void *cfg, const uint64_t *desc)
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

size_t np_su_descriptors(const void *cfg, uint64_t (*desc)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
    for (unsigned i = 0; i < N_UT_DESC && i < max; i++)
        desc_words(i, desc[i]);
    return N_UT_DESC;
}

void np_su_random_desc(const void *cfg, np_rng *rng, uint64_t *d)
{
    (void)cfg;
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

size_t np_su_boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
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

/* --- The adapter: the engine behind eval and the per-transaction pipe --- */

/* Any engine's bundle, aligned for its widest field. */
typedef union su_align {
    np_s128 a;
    uint64_t b;
    long double c;
    void *d;
} su_align;

/*
 * The per-transaction bundle: the transaction's words, then (set by the
 * front stage) which unit and the stage context, then the engine's bundle.
 */
typedef struct su_sig {
    uint64_t in[NP_UNIT_MAX_FIELDS];
    const np_su *su;
    np_span_ctx ctx;
    su_align t[];
} su_sig;

static size_t su_sig_size(const np_su *su) { return offsetof(su_sig, t) + su->span.engine->sig_size; }
_Static_assert(offsetof(su_sig, t) <= NP_SU_SIG_HEAD, "NP_SU_SIG_HEAD holds the bundle's head");

/*
 * The state at pixel k of a sequential engine (no seek): run from the span's
 * start. A per-thread cache continues the last span when the next pixel
 * asked for is of the same span and not before it, so a span's pixels in
 * order cost one step each.
 */
typedef struct su_cache {
    int valid;
    const np_span_engine *eng;
    su_align ecfg[NP_UNIT_CFG_MAX / sizeof(su_align)];
    unsigned tex;
    np_span sp;
    uint32_t k;
    np_span_counts cnt;
    su_align core[NP_SU_CORE_MAX / sizeof(su_align)];
} su_cache;
static _Thread_local su_cache cache;

static const void *su_place(const np_su *su, const void *cfg, const np_span *sp, uint32_t k, void *local)
{
    const np_span_engine *e = su->span.engine;
    const void *ecfg = np_su_engine_cfg(&su->span, cfg);
    const unsigned tex = np_su_texture(&su->span, cfg);
    if (e->seek) {
        e->init(local, ecfg, np_ut_regs(tex));
        e->seek(local, sp, k);
        return local;
    }
    su_cache *c = &cache;
    if (!c->valid || c->eng != e || memcmp(c->ecfg, ecfg, su->engine_cfg_size) != 0 || c->tex != tex ||
        memcmp(c->sp.s, sp->s, sizeof sp->s) != 0 || memcmp(c->sp.ds, sp->ds, sizeof sp->ds) != 0 || c->k > k) {
        memset(c, 0, sizeof *c);
        c->eng = e;
        memcpy(c->ecfg, ecfg, su->engine_cfg_size);
        c->tex = tex;
        c->sp = *sp;
        e->init(c->core, c->ecfg, np_ut_regs(tex));
        e->begin(c->core, &c->sp, &c->cnt);
        c->valid = 1;
    }
    for (; c->k < k; c->k++)
        e->advance(c->core, &c->cnt);
    return c->core;
}

void np_su_front(const np_su *su, const void *cfg, void *sig)
{
    su_sig *s = sig;
    const np_span_engine *e = su->span.engine;
    np_span sp;
    su_align local[NP_SU_CORE_MAX / sizeof(su_align)];
    np_ut_span(s->in, &sp);
    sp.n = NP_TEX_SPAN_MAX; /* the value of pixel k does not depend on n */
    const uint32_t k = (uint32_t)np_trunc_u(s->in[UT_K], 16);
    const void *core = su_place(su, cfg, &sp, k, local);
    s->su = su;
    s->ctx = *np_span_ctx_of(core);
    s->ctx.cfg = np_su_engine_cfg(&su->span, cfg); /* the unit's block outlives the bundle; the cache may not */
    memset(s->t, 0, e->sig_size);
    e->issue(core, s->t);
}

/* The engine's stage i on the bundle (the pipe's stages after the front one). */
static void su_stage(unsigned i, void *sig)
{
    su_sig *s = sig;
    s->su->span.engine->stages[i].fn(&s->ctx, s->t);
}

#define SU_STAGE(i) static void su_stage_##i(const void *cfg, void *sig) { (void)cfg; su_stage(i, sig); }
SU_STAGE(0) SU_STAGE(1) SU_STAGE(2) SU_STAGE(3) SU_STAGE(4) SU_STAGE(5) SU_STAGE(6) SU_STAGE(7)
SU_STAGE(8) SU_STAGE(9) SU_STAGE(10) SU_STAGE(11) SU_STAGE(12) SU_STAGE(13) SU_STAGE(14)
static const np_stage_fn su_stage_fn[NP_SU_STAGES_MAX] = {
    su_stage_0, su_stage_1, su_stage_2,  su_stage_3,  su_stage_4,  su_stage_5,  su_stage_6, su_stage_7,
    su_stage_8, su_stage_9, su_stage_10, su_stage_11, su_stage_12, su_stage_13, su_stage_14,
};

static pthread_mutex_t su_lock = PTHREAD_MUTEX_INITIALIZER;

int np_su_pipe_init(np_su *su, np_stage_fn front, np_pipe *p, const void *cfg)
{
    const np_span_engine *e = su->span.engine;
    if (e->n_stages > NP_SU_STAGES_MAX || su_sig_size(su) > NP_SU_SIG_MAX || e->core_size > NP_SU_CORE_MAX)
        return -1;
    pthread_mutex_lock(&su_lock);
    if (!su->built) {
        su->stages[0] = (np_stage_desc){ su->front_name, front };
        for (unsigned i = 0; i < e->n_stages; i++)
            su->stages[1 + i] = (np_stage_desc){ e->stages[i].name, su_stage_fn[i] };
        su->built = 1;
    }
    pthread_mutex_unlock(&su_lock);
    return np_pipe_init(p, su->stages, 1u + e->n_stages, su_sig_size(su), cfg);
}

void np_su_sig_set_in(void *sig, const uint64_t *in)
{
    su_sig *s = sig;
    memset(s, 0, offsetof(su_sig, t));
    memcpy(s->in, in, UT_NIN * sizeof in[0]);
}

void np_su_sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    (void)cfg;
    const np_span_sig *h = (const np_span_sig *)(const void *)((const su_sig *)sig)->t;
    for (int ch = 0; ch < 3; ch++)
        out[ch] = h->pix.rgb[ch];
}

void np_su_eval(const np_su *su, const void *cfg, const uint64_t *in, uint64_t *out)
{
    su_align buf[NP_SU_SIG_MAX / sizeof(su_align)];
    const np_span_engine *e = su->span.engine;
    np_su_sig_set_in(buf, in);
    np_su_front(su, cfg, buf);
    for (unsigned i = 0; i < e->n_stages; i++)
        su_stage(i, buf);
    np_su_sig_get_out(cfg, buf, out);
}

void np_su_eval_n(const np_su *su, const void *cfg, const uint64_t *in, uint64_t *out, size_t n)
{
    const np_span_engine *e = su->span.engine;
    const void *ecfg = np_su_engine_cfg(&su->span, cfg);
    const np_tex_regs *regs = np_ut_regs(np_su_texture(&su->span, cfg));
    su_align core[NP_SU_CORE_MAX / sizeof(su_align)], t[NP_SU_SIG_MAX / sizeof(su_align)];
    np_span cur; /* the span the engine holds (begin and seek may keep its address) */
    np_span_counts cnt;
    uint32_t kc = 0;
    int placed = 0;
    if (e->core_size > sizeof core || e->sig_size > sizeof t)
        return;
    for (size_t i = 0; i < n; i++) {
        uint64_t w[UT_NIN];
        np_span sp;
        for (unsigned f = 0; f < UT_NIN; f++)
            w[f] = in[f * n + i];
        np_ut_span(w, &sp);
        sp.n = NP_TEX_SPAN_MAX; /* as np_su_front: the value of pixel k does not depend on n */
        const uint32_t k = (uint32_t)np_trunc_u(w[UT_K], 16);
        int same = placed && memcmp(cur.s, sp.s, sizeof sp.s) == 0 && memcmp(cur.ds, sp.ds, sizeof sp.ds) == 0;
        if (!same || k < kc || (e->seek && k > kc + 1u)) {
            cur = sp;
            memset(&cnt, 0, sizeof cnt);
            e->init(core, ecfg, regs);
            if (e->seek) {
                e->seek(core, &cur, k);
                kc = k;
            } else {
                e->begin(core, &cur, &cnt);
                kc = 0;
            }
            placed = 1;
        }
        for (; kc < k; kc++)
            e->advance(core, &cnt);
        np_span_ctx ctx = *np_span_ctx_of(core);
        ctx.cfg = ecfg;
        memset(t, 0, e->sig_size);
        e->issue(core, t);
        for (unsigned st = 0; st < e->n_stages; st++)
            e->stages[st].fn(&ctx, t);
        const np_span_sig *h = (const np_span_sig *)(const void *)t;
        for (unsigned ch = 0; ch < 3; ch++)
            out[ch * n + i] = h->pix.rgb[ch];
    }
}

/* --- The stream model: np_span_sim behind the generic stream port --- */

int np_su_stream_init(const np_su *su, void *state, const void *cfg)
{
    np_su_stream *s = state;
    return np_span_sim_init(&s->sim, su->span.engine, np_su_engine_cfg(&su->span, cfg),
                            np_ut_regs(np_su_texture(&su->span, cfg)));
}

size_t np_su_datapath(const np_su *su, const void *cfg, np_op *ops, size_t max)
{
    return su->span.engine->datapath(np_su_engine_cfg(&su->span, cfg), np_ut_regs(np_su_texture(&su->span, cfg)),
                                     ops, max);
}

void np_su_stream_free(void *state) { np_span_sim_free(&((np_su_stream *)state)->sim); }

void np_su_stream_eval(void *state, np_unit_stream_port *p)
{
    np_su_stream *s = state;
    memset(&s->port, 0, sizeof s->port);
    s->port.in_valid = p->in_valid;
    if (p->in_valid)
        np_ut_span(p->in, &s->in);
    s->port.in = &s->in;
    s->port.out_ready = p->out_ready;
    np_span_sim_eval(&s->sim, &s->port);
    p->in_ready = s->port.in_ready;
    p->out_valid = s->port.out_valid;
    for (int ch = 0; ch < 3; ch++)
        p->out[ch] = s->port.out.rgb[ch];
}

void np_su_stream_clock(void *state, const np_unit_stream_port *p)
{
    (void)p;
    np_su_stream *s = state;
    np_span_sim_clock(&s->sim, &s->port);
}

int np_su_stream_idle(const void *state) { return np_span_sim_idle(&((const np_su_stream *)state)->sim); }

void np_su_stream_counters(const void *state, uint64_t *cycles, uint64_t *setup)
{
    const np_su_stream *s = state;
    *cycles = s->sim.stats.cycles;
    *setup = s->sim.stats.setup_stalls;
}

void np_su_add_setup(np_unit_timing *t, const char *what, unsigned products, unsigned cycles)
{
    if (t->n_setup < NP_UNIT_MAX_SETUPS) {
        np_unit_setup *s = &t->setup[t->n_setup++];
        snprintf(s->what, sizeof s->what, "%s", what);
        s->products = products;
        s->cycles = cycles;
    }
}
