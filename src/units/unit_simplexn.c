/* SPDX-License-Identifier: MIT */
/*
 * The n-D simplex noise units simplex2, simplex4, simplex5
 * (rtl_model/np_simplexn.h) in the unit registry: one datapath, one set of
 * functions below, and per n a registry entry whose functions pass n on.
 * One unit per n rather than one unit with a dims key: a unit's inputs
 * (fields), its golden vector directory, its conformance cases and its
 * gate-report row are per unit in the registry, and n changes every one of
 * them; simplex3 is this family's n = 3 and stays the unit it is (with its
 * derivative), the test ndim.simplex3_bit_exact ties the two together.
 */
#include <stdio.h>
#include <string.h>

#include "np_refn.h"
#include "np_simplexn.h"
#include "np_unit.h"
#include "unit_ndim.h"

/*
 * The registry's configuration block. dims is a key fixed at the unit's n
 * (range n..n): the '# config' line names the dimension, and the block is
 * the model's whole configuration (the pipe reads it by reference).
 */
typedef struct sxn_block {
    np_simplexn_cfg c;
} sxn_block;
_Static_assert(sizeof(sxn_block) <= NP_UNIT_CFG_MAX, "configuration block too large");

static np_simplexn_cfg cfg_of(unsigned n, const void *cfg)
{
    np_simplexn_cfg c = ((const sxn_block *)cfg)->c;
    c.dims = n; /* k_frac: 0 for n != 3 (no key: Kf = A exactly), the key's for n = 3 */
    return c;
}

const char *const np_ndim_axis_names[5] = { "x", "y", "z", "w", "v" };

int np_ndim_cfg_scene(const np_unit *u, void *cfg, const np_unit_scene *sc)
{
    if (!sc->noise_unit || strcmp(sc->noise_unit, u->name) != 0)
        return 0;
    np_unit_cfg_default(u, cfg);
    return 1;
}

static unsigned t_frac_def(unsigned n, const void *cfg)
{
    return np_simplexn_cfg_default(n, ((const sxn_block *)cfg)->c.out_bits).t_frac;
}
static unsigned p_frac_def(unsigned n, const void *cfg)
{
    return np_simplexn_cfg_default(n, ((const sxn_block *)cfg)->c.out_bits).p_frac;
}

static const char *check(unsigned n, const void *cfg)
{
    np_simplexn_cfg c = cfg_of(n, cfg);
    return np_simplexn_cfg_check(&c);
}

static void fields(unsigned n, const void *cfg, np_unit_fields *f)
{
    np_simplexn_cfg c = cfg_of(n, cfg);
    char fmt[32];
    memset(f, 0, sizeof *f);
    f->n_in = n;
    f->n_out = 1;
    for (unsigned a = 0; a < n; a++)
        np_unit_set_field(&f->in[a], np_ndim_axis_names[a], 16, 0, 8, "u16 Q8.8");
    snprintf(fmt, sizeof fmt, "s%u Q-1.%u", c.out_bits, c.out_bits);
    np_unit_set_field(&f->out[0], "f", c.out_bits, 1, c.out_bits, fmt);
}

static void words_in(unsigned n, const uint64_t *in, uint16_t *x)
{
    for (unsigned a = 0; a < n; a++)
        x[a] = (uint16_t)in[a];
}

static void eval(unsigned n, const void *cfg, const uint64_t *in, uint64_t *out)
{
    np_simplexn_cfg c = cfg_of(n, cfg);
    uint16_t x[NP_SIMPLEXN_MAX] = { 0 };
    words_in(n, in, x);
    out[0] = np_trunc_u((uint64_t)(int64_t)np_simplexn_eval(&c, x), c.out_bits);
}

static void ref(unsigned n, const void *cfg, const uint64_t *in, double *out)
{
    (void)cfg;
    uint16_t x[NP_SIMPLEXN_MAX] = { 0 };
    words_in(n, in, x);
    out[0] = np_ref_simplexn_q88(n, x);
}

static double bound(unsigned n, const void *cfg)
{
    np_simplexn_cfg c = cfg_of(n, cfg);
    return np_simplexn_error_bound_lsb(&c);
}

/* The pipe keeps the block's configuration by reference: dims is in it (the fixed key), k_frac is 0. */
static int pipe_init(unsigned n, np_pipe *p, const void *cfg)
{
    (void)n;
    return np_simplexn_pipe_init(p, &((const sxn_block *)cfg)->c);
}

static void sig_set_in(unsigned n, void *sig, const uint64_t *in)
{
    np_simplexn_sig *s = sig;
    memset(s, 0, sizeof *s);
    words_in(n, in, s->x);
}

static void sig_get_out(unsigned n, const void *cfg, const void *sig, uint64_t *out)
{
    np_simplexn_cfg c = cfg_of(n, cfg);
    out[0] = np_trunc_u((uint64_t)(int64_t)((const np_simplexn_sig *)sig)->f, c.out_bits);
}

static void trace_sig(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n)
{
    np_simplexn_trace(&((const sxn_block *)cfg)->c, k, sig, t, n);
}

static size_t datapath(unsigned n, const void *cfg, np_op *ops, size_t max)
{
    np_simplexn_cfg c = cfg_of(n, cfg);
    return np_simplexn_datapath(&c, ops, max);
}

/*
 * Boundary inputs (u16 Q8.8 words per axis), the same classes for every n:
 *   0: the origin (every offset 0: all axes tie; corner 0 at d = 0, f = 0)
 *   1: every word 0xffff (the largest input; all tie)
 *   2..n+1: one axis 0xffff, the others 0 (an extreme per axis)
 *   then, per pair of axes (a, b): X_a = X_b = 0x1234, others 0x0abc + 0x1111 a
 *        (the u_a = u_b face: a pair tie), and X_a one step above and below
 *   then per triple (a, b, c) (n >= 3) X = 0x5678 on the three (a triple tie),
 *        and one step above on a
 *   then all axes equal 0x4321 (the main diagonal: all tie) and one step
 *        above on each axis in turn
 *   then the skewed cell wrap: every word 0x7fff and 0x8000 (the hash reads
 *        the cell mod 256), and one axis 0xffff -> 0x0000 with the others
 *        0x1357 (the input wrap: no tiling at 256, the output jumps)
 * The classic units (unit_classicn.c) use the same table: there the pair,
 * triple and diagonal rows are points with equal fractions on those axes.
 */
enum { MAXB = 96 };

static void put_row(uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max, size_t *k, unsigned n, const uint16_t *x)
{
    if (*k < max)
        for (unsigned a = 0; a < n; a++)
            in[*k][a] = x[a];
    (*k)++;
}

size_t np_ndim_boundary(unsigned n, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    size_t k = 0;
    uint16_t x[NP_SIMPLEXN_MAX] = { 0 };
    for (unsigned a = 0; a < n; a++)
        x[a] = 0;
    put_row(in, max, &k, n, x);
    for (unsigned a = 0; a < n; a++)
        x[a] = 0xffff;
    put_row(in, max, &k, n, x);
    for (unsigned e = 0; e < n; e++) {
        for (unsigned a = 0; a < n; a++)
            x[a] = a == e ? 0xffff : 0;
        put_row(in, max, &k, n, x);
    }
    for (unsigned a = 0; a < n; a++)
        for (unsigned b = a + 1u; b < n; b++)
            for (int step = 0; step <= 2; step++) {
                for (unsigned c = 0; c < n; c++)
                    x[c] = (uint16_t)(0x0abc + 0x1111u * c);
                x[a] = (uint16_t)(0x1234 + (step == 1 ? 1 : step == 2 ? -1 : 0));
                x[b] = 0x1234;
                put_row(in, max, &k, n, x);
            }
    for (unsigned a = 0; a < n; a++)
        for (unsigned b = a + 1u; b < n; b++)
            for (unsigned c = b + 1u; c < n; c++)
                for (int step = 0; step <= 1; step++) {
                    for (unsigned e = 0; e < n; e++)
                        x[e] = (uint16_t)(0x0abc + 0x1111u * e);
                    x[a] = (uint16_t)(0x5678 + step);
                    x[b] = x[c] = 0x5678;
                    put_row(in, max, &k, n, x);
                }
    for (unsigned e = 0; e <= n; e++) {
        for (unsigned a = 0; a < n; a++)
            x[a] = (uint16_t)(0x4321 + (a + 1u == e ? 1 : 0));
        put_row(in, max, &k, n, x);
    }
    for (unsigned a = 0; a < n; a++)
        x[a] = 0x7fff;
    put_row(in, max, &k, n, x);
    for (unsigned a = 0; a < n; a++)
        x[a] = 0x8000;
    put_row(in, max, &k, n, x);
    for (unsigned w = 0; w < 2u; w++) {
        for (unsigned a = 0; a < n; a++)
            x[a] = 0x1357;
        x[0] = w ? 0x0000 : 0xffff;
        put_row(in, max, &k, n, x);
    }
    return k;
}

static const char *const conf_configs[] = { "out_bits=8", "out_bits=12,t_frac=8,p_frac=8", NULL };

/*
 * The search's objective (np_unit.fine_cfg): f rounded to 20 fraction bits
 * (the widest output), WT and WP unchanged: the error before the output
 * rounding, to 1/16 LSB or finer.
 */
static void fine_cfg(const void *cfg, void *fine)
{
    sxn_block *k = fine;
    *k = *(const sxn_block *)cfg;
    k->c.out_bits = NP_SIMPLEXN_OUT_MAX;
}

#define SIMPLEXN_UNIT(N)                                                                                        \
    static unsigned t_frac_def##N(const void *c) { return t_frac_def(N, c); }                                \
    static unsigned p_frac_def##N(const void *c) { return p_frac_def(N, c); }                                \
    static const np_unit_key keys##N[] = {                                                                     \
        NP_UNIT_KEY("dims", sxn_block, c.dims, N, N, N, "n: the dimension (fixed for this unit)"),            \
        NP_UNIT_KEY("out_bits", sxn_block, c.out_bits, NP_SIMPLEXN_OUT_MIN, NP_SIMPLEXN_OUT_MAX, 16,           \
                    "N: f is sN Q-1.N"),                                                                      \
        NP_UNIT_KEY_DERIVED("t_frac", sxn_block, c.t_frac, 1, NP_SIMPLEXN_WT_MAX, t_frac_def##N,               \
                            "WT: fraction bits of tau^2, tau^4 (default: faithful, N + 9)"),                  \
        NP_UNIT_KEY_DERIVED("p_frac", sxn_block, c.p_frac, 1, NP_SIMPLEXN_WP_MAX, p_frac_def##N,               \
                            "WP: fraction bits of the terms and their sum (default: faithful, N + 9)"),       \
        NP_UNIT_KEY_END,                                                                                       \
    };                                                                                                         \
    static const char *check##N(const void *c) { return check(N, c); }                                       \
    static void fields##N(const void *c, np_unit_fields *f) { fields(N, c, f); }                             \
    static void eval##N(const void *c, const uint64_t *in, uint64_t *out) { eval(N, c, in, out); }           \
    static void ref##N(const void *c, const uint64_t *in, double *out) { ref(N, c, in, out); }               \
    static double bound##N(const void *c) { return bound(N, c); }                                            \
    static int pipe_init##N(np_pipe *p, const void *c) { return pipe_init(N, p, c); }                        \
    static void sig_set_in##N(void *s, const uint64_t *in) { sig_set_in(N, s, in); }                         \
    static void sig_get_out##N(const void *c, const void *s, uint64_t *out) { sig_get_out(N, c, s, out); }   \
    static size_t boundary##N(const void *c, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)                 \
    {                                                                                                          \
        (void)c;                                                                                               \
        return np_ndim_boundary(N, in, max);                                                                         \
    }                                                                                                          \
    static size_t datapath##N(const void *c, np_op *ops, size_t max) { return datapath(N, c, ops, max); }    \
    extern const np_unit np_unit_simplex##N;                                                                   \
    static int cfg_scene##N(void *c, const np_unit_scene *sc, char *err, size_t errlen)                        \
    {                                                                                                          \
        (void)err;                                                                                             \
        (void)errlen;                                                                                          \
        return np_ndim_cfg_scene(&np_unit_simplex##N, c, sc);                                                  \
    }                                                                                                          \
    const np_unit np_unit_simplex##N = {                                                                       \
        .name = "simplex" #N,                                                                                  \
        .summary = #N "-D simplex noise f, 8.8 inputs, exact skew/rank, sorting network "                    \
                      "(Perlin, Noise Hardware, higher dimensions; docs/noise-nd.md)",                        \
        .keys = keys##N,                                                                                       \
        .cfg_check = check##N,                                                                                 \
        .fields = fields##N,                                                                                   \
        .eval = eval##N,                                                                                       \
        .ref = ref##N,                                                                                         \
        .tolerance_lsb = 1.0,                                                                                  \
        .error_bound_lsb = bound##N,                                                                           \
        .pipe_init = pipe_init##N,                                                                             \
        .sig_set_in = sig_set_in##N,                                                                           \
        .sig_get_out = sig_get_out##N,                                                                         \
        .boundary = boundary##N,                                                                               \
        .datapath = datapath##N,                                                                               \
        .trace = trace_sig,                                                                                    \
        .conformance_configs = conf_configs,                                                                   \
        .fine_cfg = fine_cfg,                                                                                  \
        .cfg_scene = cfg_scene##N,                                                                             \
    };

SIMPLEXN_UNIT(2)
SIMPLEXN_UNIT(4)
SIMPLEXN_UNIT(5)

/*
 * The n-D datapath at n = 3, not registered (simplex3 is the 3-D unit): the
 * same bits as simplex3's f (ndim.simplex3_bit_exact), priced with the n-D
 * declaration, so that `noisepipe report dims` compares the four n with
 * one accounting. Appendix B's Kf is not an integer: k_frac is a key here.
 */
static unsigned k_frac_def3(const void *c) { return np_simplexn_cfg_default(3, ((const sxn_block *)c)->c.out_bits).k_frac; }
static unsigned t_frac_def3(const void *c) { return t_frac_def(3, c); }
static unsigned p_frac_def3(const void *c) { return p_frac_def(3, c); }
static const np_unit_key keys3[] = {
    NP_UNIT_KEY("dims", sxn_block, c.dims, 3, 3, 3, "n: the dimension (fixed)"),
    NP_UNIT_KEY("out_bits", sxn_block, c.out_bits, NP_SIMPLEXN_OUT_MIN, NP_SIMPLEXN_OUT_MAX, 16, "N: f is sN Q-1.N"),
    NP_UNIT_KEY_DERIVED("t_frac", sxn_block, c.t_frac, 1, NP_SIMPLEXN_WT_MAX, t_frac_def3, "WT (default N + 7)"),
    NP_UNIT_KEY_DERIVED("p_frac", sxn_block, c.p_frac, 1, NP_SIMPLEXN_WP_MAX, p_frac_def3, "WP (default N + 4)"),
    NP_UNIT_KEY_DERIVED("k_frac", sxn_block, c.k_frac, 1, NP_SIMPLEXN_WK_MAX, k_frac_def3, "WK (default N + 6)"),
    NP_UNIT_KEY_END,
};
static const char *check3(const void *c) { return check(3, c); }
static void fields3(const void *c, np_unit_fields *f) { fields(3, c, f); }
static void eval3(const void *c, const uint64_t *in, uint64_t *out) { eval(3, c, in, out); }
static void ref3(const void *c, const uint64_t *in, double *out) { ref(3, c, in, out); }
static double bound3(const void *c) { return bound(3, c); }
static int pipe_init3(np_pipe *p, const void *c) { return pipe_init(3, p, c); }
static void sig_set_in3(void *s, const uint64_t *in) { sig_set_in(3, s, in); }
static void sig_get_out3(const void *c, const void *s, uint64_t *out) { sig_get_out(3, c, s, out); }
static size_t boundary3(const void *c, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)c;
    return np_ndim_boundary(3, in, max);
}
static size_t datapath3(const void *c, np_op *ops, size_t max) { return datapath(3, c, ops, max); }

const np_unit np_unit_simplexn3 = {
    .name = "simplexn3",
    .summary = "the n-D simplex datapath at n = 3 (f only; the bits of simplex3's f), for the dims report",
    .keys = keys3,
    .cfg_check = check3,
    .fields = fields3,
    .eval = eval3,
    .ref = ref3,
    .tolerance_lsb = 1.0,
    .error_bound_lsb = bound3,
    .pipe_init = pipe_init3,
    .sig_set_in = sig_set_in3,
    .sig_get_out = sig_get_out3,
    .boundary = boundary3,
    .datapath = datapath3,
};
