/* SPDX-License-Identifier: MIT */
/*
 * A toy unit that lives in this file only and is registered at run time
 * (np_unit_register): the worked example of docs/adding-a-unit.md. With no
 * other file touched it gets golden vectors, verification through its cycle
 * model, every conformance check and a gate report.
 *
 * The unit "toy2": two inputs a, b (u8), one output f, two pipeline stages
 *
 *   X   x = a ^ b                  u8   (8 two-input XOR gates)
 *   A   f = (x + b) mod 2^out_bits u9 or u8 (out_bits = 9: exact, 8: wraps)
 *
 * Every intermediate is an integer, so the float reference is exact and the
 * tolerance is 0 LSB.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "np_conformance.h"
#include "np_report.h"
#include "np_test.h"
#include "np_vec.h"

/* --- The unit --- */

typedef struct toy_cfg {
    unsigned out_bits; /* 8 or 9 */
} toy_cfg;

typedef struct toy_sig {
    uint8_t a, b, x;
    uint16_t f;
} toy_sig;

/* The one key, declared as data: configure, format, `noisepipe units` and the checks read it. */
static const np_unit_key toy_keys[] = {
    NP_UNIT_KEY("out_bits", toy_cfg, out_bits, 8, 9, 9, "width of f: 9 holds every sum, 8 wraps it mod 256"),
    NP_UNIT_KEY_END,
};

static void toy_fields(const void *cfg, np_unit_fields *f)
{
    unsigned o = ((const toy_cfg *)cfg)->out_bits;
    memset(f, 0, sizeof *f);
    f->n_in = 2;
    f->n_out = 1;
    np_unit_set_field(&f->in[0], "a", 8, 0, 0, "u8");
    np_unit_set_field(&f->in[1], "b", 8, 0, 0, "u8");
    np_unit_set_field(&f->out[0], "f", o, 0, 0, o == 9 ? "u9" : "u8");
}

/* The two stages; the bit-exact model is the same two functions in a row. */
static void stage_x(const void *cfg, void *sig)
{
    (void)cfg;
    toy_sig *s = sig;
    s->x = (uint8_t)(s->a ^ s->b);
}

static void stage_a(const void *cfg, void *sig)
{
    toy_sig *s = sig;
    s->f = (uint16_t)(((unsigned)s->x + s->b) & ((1u << ((const toy_cfg *)cfg)->out_bits) - 1u));
}

static const np_stage_desc toy_stages[] = { { "X", stage_x }, { "A", stage_a } };

static void toy_eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    toy_sig s = { (uint8_t)in[0], (uint8_t)in[1], 0, 0 };
    stage_x(cfg, &s);
    stage_a(cfg, &s);
    out[0] = s.f;
}

static void toy_ref(const void *cfg, const uint64_t *in, double *out)
{
    double m = ldexp(1.0, (int)((const toy_cfg *)cfg)->out_bits);
    out[0] = fmod((double)(in[0] ^ in[1]) + (double)in[1], m);
}

/* Every value is an integer below 2^9: the model equals the reference. */
static double toy_error_bound(const void *cfg)
{
    (void)cfg;
    return 0.0;
}

static int toy_pipe_init(np_pipe *p, const void *cfg)
{
    return np_pipe_init(p, toy_stages, 2, sizeof(toy_sig), cfg);
}

static void toy_sig_set_in(void *sig, const uint64_t *in)
{
    toy_sig *s = sig;
    memset(s, 0, sizeof *s);
    s->a = (uint8_t)in[0];
    s->b = (uint8_t)in[1];
}

static void toy_sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    (void)cfg;
    out[0] = ((const toy_sig *)sig)->f;
}

/* a, b: zeros, ones, one of each, the alternating patterns, the largest sum, a carry out of bit 7. */
static const uint8_t toy_bnd[][2] = { { 0x00, 0x00 }, { 0xff, 0xff }, { 0xff, 0x00 }, { 0x00, 0xff },
                                      { 0x55, 0xaa }, { 0xaa, 0x55 }, { 0x01, 0xfe }, { 0x80, 0x80 } };

static size_t toy_boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    (void)cfg;
    size_t n = sizeof toy_bnd / sizeof toy_bnd[0];
    for (size_t i = 0; i < n && i < max; i++) {
        in[i][0] = toy_bnd[i][0];
        in[i][1] = toy_bnd[i][1];
    }
    return n;
}

static size_t toy_datapath(const void *cfg, np_op *ops, size_t max)
{
    unsigned o = ((const toy_cfg *)cfg)->out_bits;
    np_dp d = { ops, max, 0 };
    np_dp_op(&d, "X", "x", NP_OP_LUT, 8, 2, 1, 8, 0, 0); /* XOR: a 2-input function per bit */
    np_dp_op(&d, "X", NULL, NP_OP_REG, 1, 16, 0, 0, 0, 0); /* x, b */
    np_dp_op(&d, "A", "f", NP_OP_ADD, 1, o, 0, o, 0, 0);
    np_dp_op(&d, "A", NULL, NP_OP_REG, 1, o, 0, 0, 0, 0);
    return d.n;
}

static void toy_trace(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n)
{
    (void)cfg;
    const toy_sig *s = sig;
    for (size_t i = 0; i < n; i++)
        if (strcmp(t[i].signal, k == 0 ? "x" : "f") == 0)
            np_trace_add(&t[i], k == 0 ? s->x : s->f);
}

static const char *const toy_configs[] = { "out_bits=8", NULL };

static const np_unit toy_unit = {
    .name = "toy2",
    .summary = "toy: f = (a ^ b) + b in two stages (the example of docs/adding-a-unit.md)",
    .keys = toy_keys,
    .fields = toy_fields,
    .eval = toy_eval,
    .ref = toy_ref,
    .tolerance_lsb = 0.0,
    .error_bound_lsb = toy_error_bound,
    .pipe_init = toy_pipe_init,
    .sig_set_in = toy_sig_set_in,
    .sig_get_out = toy_sig_get_out,
    .boundary = toy_boundary,
    .datapath = toy_datapath,
    .trace = toy_trace,
    .conformance_configs = toy_configs,
};
_Static_assert(sizeof(toy_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

/* --- The test --- */

static const np_unit *toy(void)
{
    if (!np_unit_find("toy2"))
        NP_CHECK(np_unit_register(&toy_unit) == 0, "register toy2");
    return np_unit_find("toy2");
}

/* The toy's golden set and KAT, written in the build tree by each case that needs them (np_conf_toy_generate). */
static np_conf_toy files;

static int toy_register(void)
{
    const np_unit *u = toy();
    NP_CHECK(u == &toy_unit, "np_unit_find sees the registered unit");
    NP_CHECK(np_unit_register(&toy_unit) != 0, "the same name registered twice");
    np_unit half = toy_unit;
    half.name = "toy_half";
    half.eval = NULL;
    NP_CHECK(np_unit_register(&half) != 0, "a unit without eval registered");
    size_t n = 0, at = SIZE_MAX;
    for (const np_unit *v; (v = np_unit_at(n)) != NULL; n++)
        if (v == u)
            at = n;
    size_t builtin = 0;
    while (np_units[builtin])
        builtin++;
    NP_CHECK(at == builtin && n == builtin + 1, "np_unit_at: %zu units, toy at %zu", n, at);
    char names[256];
    np_vec_unit_names(names, sizeof names);
    NP_CHECK(strstr(names, "toy2") != NULL, "unit names: %s", names);
    printf("toy2 registered after the %zu built-in units: %s\n", builtin, names);
    return 0;
}

static int toy_generate(const char *tag) { return np_conf_toy_generate(&files, toy(), NP_CONF_WORK, tag, "out_bits=8"); }

static int toy_vectors(void)
{
    np_vec_reader r;
    if (toy_generate("vectors") != 0 || np_conf_toy_open(&files, &r) != 0)
        return 1;
    np_vec_rec rec;
    uint64_t n = 0, exact = 0;
    int rc;
    while ((rc = np_vec_read(&r, &rec)) == 1) {
        uint64_t a = rec.w[NP_VEC_IN][0], b = rec.w[NP_VEC_IN][1], f = rec.w[NP_VEC_OUT][0];
        NP_CHECK(f == (((a ^ b) + b) & 511u), "vector %llu: f(%02llx, %02llx) = %llx", (unsigned long long)n,
                 (unsigned long long)a, (unsigned long long)b, (unsigned long long)f);
        exact += np_vec_ref_value(rec.w[NP_VEC_REF][0]) == (double)f;
        n++;
    }
    NP_CHECK(rc == 0 && n == r.h.count && n > 1000, "%llu vectors read: %s", (unsigned long long)n, r.L.err);
    NP_CHECK(exact == n, "the reference equals the model on %llu of %llu", (unsigned long long)exact,
             (unsigned long long)n);
    printf("toy2: %llu golden vectors (%s), f = (a ^ b) + b on each, the reference exact\n", (unsigned long long)n,
           files.sources);
    np_vec_close(&r);
    return 0;
}

static int toy_verify(void) { return toy_generate("verify") || np_conf_toy_verify(&files); }

static int toy_conformance(void) { return toy_generate("conformance") || np_conf_toy_conformance(&files); }

static int toy_gates(void)
{
    const np_unit *u = toy();
    np_vec_header h;
    np_unit_cost c;
    char err[256];
    NP_CHECK(np_vec_header_init(&h, u, NULL, err, sizeof err) == 0, "%s", err);
    NP_CHECK(np_unit_cost_compute(u, &h.cfg, &np_cost_default, &c, err, sizeof err) == 0, "%s", err);
    np_report_gates_md(stdout, &c, 1, "toy2 gates");
    NP_CHECK(c.n_stages == 2 && c.latency == 2 && c.total > 0.0 && c.reg_bits == 16 + 9,
             "%u stages, latency %u, %.1f gates, %u register bits", c.n_stages, c.latency, c.total, c.reg_bits);
    return 0;
}

static const np_test_case cases[] = {
    { "register", toy_register },     { "vectors", toy_vectors }, { "verify", toy_verify },
    { "conformance", toy_conformance }, { "gates", toy_gates },   { NULL, NULL },
};
NP_TEST_MAIN(cases)
