/* SPDX-License-Identifier: MIT */
/*
 * The n-D classic noise units classic2, classic4, classic5
 * (rtl_model/np_classicn.h) in the unit registry, one per n for the reasons
 * unit_simplexn.c gives; classic3 is this family's n = 3 (the test
 * ndim.classic3_bit_exact compares them bit for bit).
 */
#include <stdio.h>
#include <string.h>

#include "np_classicn.h"
#include "np_refn.h"
#include "np_unit.h"
#include "unit_ndim.h"

/* The configuration block: the model's; dims is a key fixed at the unit's n. */
typedef struct cln_block {
    np_classicn_cfg c;
} cln_block;
_Static_assert(sizeof(cln_block) <= NP_UNIT_CFG_MAX, "configuration block too large");

static const np_classicn_cfg *cfg_of(const void *cfg) { return &((const cln_block *)cfg)->c; }

static unsigned s_frac_def(unsigned n, const void *cfg) { return np_classicn_cfg_default(n, cfg_of(cfg)->out_bits).s_frac; }
static unsigned lerp_frac_def(unsigned n, const void *cfg)
{
    return np_classicn_cfg_default(n, cfg_of(cfg)->out_bits).lerp_frac;
}

static const char *check(const void *cfg) { return np_classicn_cfg_check(cfg_of(cfg)); }

static void fields(const void *cfg, np_unit_fields *f)
{
    const np_classicn_cfg *c = cfg_of(cfg);
    unsigned fr = np_classicn_out_frac(c);
    char fmt[32];
    memset(f, 0, sizeof *f);
    f->n_in = c->dims;
    f->n_out = 1;
    for (unsigned a = 0; a < c->dims; a++)
        np_unit_set_field(&f->in[a], np_ndim_axis_names[a], 16, 0, 8, "u16 Q8.8");
    snprintf(fmt, sizeof fmt, "s%u Q%u.%u", c->out_bits, np_classicn_int_bits(c->dims), fr);
    np_unit_set_field(&f->out[0], "f", c->out_bits, 1, fr, fmt);
}

static void words_in(unsigned n, const uint64_t *in, uint16_t *x)
{
    for (unsigned a = 0; a < n; a++)
        x[a] = (uint16_t)in[a];
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    const np_classicn_cfg *c = cfg_of(cfg);
    uint16_t x[NP_CLASSICN_MAX];
    words_in(c->dims, in, x);
    out[0] = np_trunc_u((uint64_t)(int64_t)np_classicn_eval(c, x), c->out_bits);
}

static void ref(const void *cfg, const uint64_t *in, double *out)
{
    const np_classicn_cfg *c = cfg_of(cfg);
    uint16_t x[NP_CLASSICN_MAX];
    words_in(c->dims, in, x);
    out[0] = np_ref_classicn_q88(c->dims, x);
}

static double bound(const void *cfg) { return np_classicn_error_bound_lsb(cfg_of(cfg)); }
static int pipe_init(np_pipe *p, const void *cfg) { return np_classicn_pipe_init(p, cfg_of(cfg)); }

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    out[0] = np_trunc_u((uint64_t)(int64_t)((const np_classicn_sig *)sig)->out, cfg_of(cfg)->out_bits);
}

static size_t datapath(const void *cfg, np_op *ops, size_t max) { return np_classicn_datapath(cfg_of(cfg), ops, max); }

static void trace(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n)
{
    np_classicn_trace(cfg_of(cfg), k, sig, t, n);
}

static const char *const conf_configs[] = { "out_bits=16", "out_bits=8,s_frac=6,lerp_frac=6", NULL };

/*
 * The search's objective (np_unit.fine_cfg): the output rounded to WL
 * fraction bits (out_bits = WL + I, at most 16), every internal width
 * unchanged: the error before O's rounding.
 */
static void fine_cfg(const void *cfg, void *fine)
{
    cln_block *k = fine;
    *k = *(const cln_block *)cfg;
    unsigned b = k->c.lerp_frac + np_classicn_int_bits(k->c.dims);
    k->c.out_bits = b < NP_CLASSICN_OUT_MAX ? b : NP_CLASSICN_OUT_MAX;
}

#define CLASSICN_UNIT(N)                                                                                         \
    static unsigned s_frac_def##N(const void *c) { return s_frac_def(N, c); }                                 \
    static unsigned lerp_frac_def##N(const void *c) { return lerp_frac_def(N, c); }                           \
    static const np_unit_key keys##N[] = {                                                                      \
        NP_UNIT_KEY("dims", cln_block, c.dims, N, N, N, "n: the dimension (fixed for this unit)"),             \
        NP_UNIT_KEY("out_bits", cln_block, c.out_bits, NP_CLASSICN_OUT_MIN, NP_CLASSICN_OUT_MAX, 8,             \
                    "N: f is sN Q(I).(N-I), I = 2 (n <= 3), 3 (n >= 4), counting the sign"),                   \
        NP_UNIT_KEY_DERIVED("s_frac", cln_block, c.s_frac, 1, NP_CLASSICN_WS_MAX, s_frac_def##N,                \
                            "WS: s-curve fraction bits (default F + 6, n >= 4: F + 7)"),                      \
        NP_UNIT_KEY_DERIVED("lerp_frac", cln_block, c.lerp_frac, 0, NP_CLASSICN_WL_MAX, lerp_frac_def##N,       \
                            "WL: interpolator fraction bits, at least F (default F + 5)"),                     \
        NP_UNIT_KEY_END,                                                                                        \
    };                                                                                                          \
    static void sig_set_in##N(void *s, const uint64_t *in)                                                     \
    {                                                                                                           \
        memset(s, 0, sizeof(np_classicn_sig));                                                                  \
        words_in(N, in, ((np_classicn_sig *)s)->x);                                                            \
    }                                                                                                           \
    static size_t boundary##N(const void *c, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)                  \
    {                                                                                                           \
        (void)c;                                                                                                \
        return np_ndim_boundary(N, in, max);                                                                    \
    }                                                                                                           \
    extern const np_unit np_unit_classic##N;                                                                    \
    static int cfg_scene##N(void *c, const np_unit_scene *sc, char *err, size_t errlen)                         \
    {                                                                                                           \
        (void)err;                                                                                              \
        (void)errlen;                                                                                           \
        return np_ndim_cfg_scene(&np_unit_classic##N, c, sc);                                                   \
    }                                                                                                           \
    const np_unit np_unit_classic##N = {                                                                        \
        .name = "classic" #N,                                                                                   \
        .summary = #N "-D classic gradient noise, 8.8 inputs, 2^" #N " corner lanes "                         \
                      "(Perlin, Noise Hardware; docs/noise-nd.md)",                                            \
        .keys = keys##N,                                                                                        \
        .cfg_check = check,                                                                                     \
        .fields = fields,                                                                                       \
        .eval = eval,                                                                                           \
        .ref = ref,                                                                                             \
        .tolerance_lsb = 1.0,                                                                                   \
        .error_bound_lsb = bound,                                                                               \
        .pipe_init = pipe_init,                                                                                 \
        .sig_set_in = sig_set_in##N,                                                                            \
        .sig_get_out = sig_get_out,                                                                             \
        .boundary = boundary##N,                                                                                \
        .datapath = datapath,                                                                                   \
        .trace = trace,                                                                                         \
        .conformance_configs = conf_configs,                                                                    \
        .fine_cfg = fine_cfg,                                                                                   \
        .cfg_scene = cfg_scene##N,                                                                              \
    };

CLASSICN_UNIT(2)
CLASSICN_UNIT(4)
CLASSICN_UNIT(5)
