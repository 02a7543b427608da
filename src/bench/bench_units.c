/* SPDX-License-Identifier: MIT */
/*
 * noisepipe bench: the table of every registered unit (issue 13). Each unit
 * in its default configuration, on 65,536 evaluations, one thread:
 *
 *   per input    np_unit.eval, one point a call (the words gathered per point);
 *   batch        np_unit_eval_n on blocks of 4,096 points (the unit's eval_n,
 *                or the generic fallback, named in the last column);
 *   kernel       the sweep kernel (np_unit.sweep_rows), rows of one x cell at
 *                z = 0x0080, model only (not the same points: a slice's);
 *   reference    np_unit.ref, one point a call;
 *   cycle model  the np_pipe at one input a clock, output always ready, or a
 *                stream unit's stream model fed its spans back to back
 *                (M cycles per second);
 *
 * each per CPU second of the measuring thread and as a ratio to
 * stb_perlin_noise3 measured at the top of the same table on 65,536 points:
 * the noise units' points are those very points (x, y, z the 8.8 words
 * next_input gives, stb gets word / 256), other units' are their level-1
 * vector cases (boundary table, walks, weighted random), a span unit's runs
 * of consecutive pixels of random spans.
 */
#define _DEFAULT_SOURCE /* getloadavg (glibc) */
#include "np_bench_units.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "np_common.h"
#include "np_stream.h"
#include "np_sweep.h"
#include "np_unit.h"
#include "np_vec.h"

#if defined(__has_include)
#if __has_include(<stb/stb_perlin.h>)
#define BU_HAVE_STB 1
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstrict-prototypes"
#include <stb/stb_perlin.h> /* the implementation is compiled in cmd_bench.c */
#pragma GCC diagnostic pop
#endif
#endif

enum { BU_N = 65536, BU_BLOCK = 4096, BU_BLOCKS = BU_N / BU_BLOCK };

static volatile uint64_t bu_sink;

/* The points the side-by-side table of cmd_bench.c uses too: an odd-step walk over cells and fractions. */
static uint64_t next_input(uint64_t k) { return k * 0x9e3779b97f4a7c15u >> 16; }

static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

typedef struct bu_rate {
    uint64_t n;          /* evaluations (cycles for a cycle model) */
    double wall, cpu;
} bu_rate;

static double bu_per_cpu(bu_rate r) { return r.cpu > 0 ? (double)r.n / r.cpu : 0.0; }

/* One unit under test: its configuration and its BU_N points. */
typedef struct bu_unit {
    const np_unit *u;
    np_unit_cfg cfg;
    np_unit_fields f;
    /* Block b, field k, point i at in[((size_t)b * n_in + k) * BU_BLOCK + i] (np_unit_eval_n's layout per block). */
    uint64_t *in;
    uint64_t *out;       /* one block's outputs */
    /* A stream unit: its spans in the order their pixels are in `in`. */
    uint64_t (*desc)[NP_UNIT_MAX_FIELDS];
    size_t n_desc;
    float *fx, *fy, *fz; /* stb's points */
} bu_unit;

static uint64_t *bu_word(bu_unit *b, size_t p, unsigned k)
{
    size_t blk = p / BU_BLOCK, i = p % BU_BLOCK;
    return &b->in[(blk * b->f.n_in + k) * BU_BLOCK + i];
}

/* A unit whose every input is an 8.8 coordinate (u16 Q8.8): a noise unit, fed stb's points. */
static int bu_is_noise(const np_unit_fields *f)
{
    for (unsigned k = 0; k < f->n_in; k++)
        if (f->in[k].bits != 16 || f->in[k].frac != 8 || f->in[k].is_signed)
            return 0;
    return f->n_in > 0;
}

/* What one evaluation of u is, for the table. */
static void bu_what(const bu_unit *b, char *buf, size_t len)
{
    static const struct {
        const char *unit, *what;
    } own[] = { { "wave", "wave grid point" }, { "aacount", "pixel's count" }, { "hatch", "hatch pixel" } };
    for (unsigned k = 0; k < sizeof own / sizeof own[0]; k++)
        if (strcmp(b->u->name, own[k].unit) == 0) {
            snprintf(buf, len, "%s", own[k].what);
            return;
        }
    if (b->u->stream)
        snprintf(buf, len, "span pixel");
    else if (bu_is_noise(&b->f))
        snprintf(buf, len, "%u-D point", b->f.n_in);
    else
        snprintf(buf, len, "transaction");
}

/* The noise units' points: coordinates 0..2 from next_input(p), 3.. from next_input(p + 2^32). */
static void bu_points_noise(bu_unit *b)
{
    for (size_t p = 0; p < BU_N; p++)
        for (unsigned k = 0; k < b->f.n_in; k++)
            *bu_word(b, p, k) = next_input(p + (k / 3u) * 0x100000000u) >> (16u * (k % 3u)) & 0xffffu;
}

/* A stream unit's points: every pixel of random spans (the last one cut to fill BU_N). */
static int bu_points_stream(bu_unit *b)
{
    const np_unit_stream *st = b->u->stream;
    np_rng g;
    np_rng_seed(&g, 13);
    size_t p = 0, cap = 64;
    b->desc = malloc(cap * sizeof *b->desc);
    for (unsigned tries = 0; b->desc && p < BU_N && tries < 100000u; tries++) {
        uint64_t d[NP_UNIT_MAX_FIELDS] = { 0 };
        st->random_desc(&b->cfg, &g, d);
        uint64_t beats = st->beats(&b->cfg, d);
        if (beats == 0)
            continue;
        if (beats > BU_N - p) { /* cut the last span to what is left */
            d[st->length_field] = BU_N - p;
            if (st->beats(&b->cfg, d) != BU_N - p)
                continue;
            beats = BU_N - p;
        }
        if (b->n_desc == cap) {
            void *q = realloc(b->desc, 2 * cap * sizeof *b->desc);
            if (!q)
                return -1;
            b->desc = q;
            cap *= 2;
        }
        memcpy(b->desc[b->n_desc++], d, sizeof d);
        for (uint64_t k = 0; k < beats; k++, p++) {
            for (unsigned f = 0; f < st->n_desc; f++)
                *bu_word(b, p, f) = d[f];
            *bu_word(b, p, st->n_desc) = k;
        }
    }
    return b->desc && p == BU_N ? 0 : -1;
}

/* Other units' points: their level-1 vector cases, in the generator's order, repeated to fill BU_N. */
static int bu_points_vectors(bu_unit *b, char *err, size_t errlen)
{
    np_vec_header h;
    np_vecgen g;
    np_vec_rec rec;
    char spec[512];
    np_unit_cfg_format_opt(b->u, &b->cfg, NP_UNIT_FMT_COMMAS, spec, sizeof spec);
    if (np_vec_header_init(&h, b->u, spec, err, errlen) != 0 || np_vecgen_init(&g, &h, 1, 1, BU_N, err, errlen) != 0)
        return -1;
    size_t p = 0;
    while (p < BU_N && np_vecgen_next(&g, &rec)) {
        for (unsigned k = 0; k < b->f.n_in; k++)
            *bu_word(b, p, k) = rec.w[NP_VEC_IN][k];
        p++;
    }
    np_vecgen_free(&g);
    for (size_t q = 0; p > 0 && p + q < BU_N; q++)
        for (unsigned k = 0; k < b->f.n_in; k++)
            *bu_word(b, p + q, k) = *bu_word(b, q % p, k);
    return p > 0 ? 0 : np_errf(err, errlen, "unit %s: the vector generator gave no case", b->u->name);
}

/* --- The figures: whole blocks of BU_BLOCK points, round the BU_N points, for about secs --- */

typedef uint64_t (*bu_block_fn)(bu_unit *b, size_t blk);

static uint64_t bu_blk_stb(bu_unit *b, size_t blk)
{
    float acc = 0.0f;
#ifdef BU_HAVE_STB
    for (size_t p = blk * BU_BLOCK; p < (blk + 1) * BU_BLOCK; p++)
        acc += stb_perlin_noise3(b->fx[p], b->fy[p], b->fz[p], 0, 0, 0);
#else
    (void)b;
    (void)blk;
#endif
    return acc != 0.0f;
}

static uint64_t bu_blk_eval(bu_unit *b, size_t blk)
{
    const uint64_t *in = b->in + blk * b->f.n_in * BU_BLOCK;
    uint64_t acc = 0;
    for (size_t i = 0; i < BU_BLOCK; i++) {
        uint64_t a[NP_UNIT_MAX_FIELDS], o[NP_UNIT_MAX_FIELDS];
        for (unsigned k = 0; k < b->f.n_in; k++)
            a[k] = in[k * BU_BLOCK + i];
        b->u->eval(&b->cfg, a, o);
        acc += o[0];
    }
    return acc;
}

static uint64_t bu_blk_batch(bu_unit *b, size_t blk)
{
    np_unit_eval_n(b->u, &b->cfg, b->in + blk * b->f.n_in * BU_BLOCK, b->out, BU_BLOCK);
    return b->out[BU_BLOCK / 2];
}

static uint64_t bu_blk_ref(bu_unit *b, size_t blk)
{
    const uint64_t *in = b->in + blk * b->f.n_in * BU_BLOCK;
    double acc = 0.0;
    for (size_t i = 0; i < BU_BLOCK; i++) {
        uint64_t a[NP_UNIT_MAX_FIELDS];
        double o[NP_UNIT_MAX_FIELDS];
        for (unsigned k = 0; k < b->f.n_in; k++)
            a[k] = in[k * BU_BLOCK + i];
        b->u->ref(&b->cfg, a, o);
        acc += o[0];
    }
    return acc != 0.0;
}

static bu_rate bu_run(bu_block_fn fn, bu_unit *b, double secs)
{
    bu_rate r = { 0, 0, 0 };
    uint64_t acc = 0;
    double t0 = np_now(), c0 = thread_cpu();
    size_t blk = 0;
    do {
        acc += fn(b, blk);
        blk = (blk + 1) % BU_BLOCKS;
        r.n += BU_BLOCK;
        r.wall = np_now() - t0;
        r.cpu = thread_cpu() - c0;
    } while (r.wall < secs);
    bu_sink = acc;
    return r;
}

/* The sweep kernel, model only: NP_SWEEP_ROWS rows of one x cell a call, walking the cells of z = 0x0080. */
static bu_rate bu_kernel(bu_unit *b, double secs)
{
    bu_rate r = { 0, 0, 0 };
    size_t n = (size_t)NP_SWEEP_ROWS * NP_SWEEP_ROW;
    int32_t *code = malloc(n * b->f.n_out * sizeof *code);
    double *ref = malloc(n * b->f.n_out * sizeof *ref);
    uint64_t acc = 0;
    uint32_t call = 0;
    double t0 = np_now(), c0 = thread_cpu();
    while (code && ref) {
        uint16_t x0 = (uint16_t)(call % 256u * 256u), y0 = (uint16_t)(call / 256u % (65536u / NP_SWEEP_ROWS) * NP_SWEEP_ROWS);
        b->u->sweep_rows(&b->cfg, x0, y0, 0x0080, NP_SWEEP_ROWS, NP_SWEEP_MODEL, code, ref);
        acc += (uint32_t)code[call % n];
        call++;
        r.n += n;
        r.wall = np_now() - t0;
        r.cpu = thread_cpu() - c0;
        if (r.wall >= secs)
            break;
    }
    bu_sink = acc;
    free(code);
    free(ref);
    return r;
}

/* The np_pipe at one input a clock, output always ready; n = cycles. */
static bu_rate bu_pipe(bu_unit *b, double secs)
{
    bu_rate r = { 0, 0, 0 };
    np_pipe p;
    if (b->u->pipe_init(&p, &b->cfg) != 0)
        return r;
    void *sig = calloc(1, p.sig_size);
    np_pipe_port port;
    memset(&port, 0, sizeof port);
    port.in_valid = 1;
    port.out_ready = 1;
    port.in_sig = sig;
    uint64_t acc = 0;
    size_t pt = 0;
    double t0 = np_now(), c0 = thread_cpu();
    while (sig) {
        for (unsigned c = 0; c < 1024; c++, r.n++, pt = (pt + 1) % BU_N) {
            uint64_t a[NP_UNIT_MAX_FIELDS];
            for (unsigned k = 0; k < b->f.n_in; k++)
                a[k] = *bu_word(b, pt, k);
            b->u->sig_set_in(sig, a);
            np_pipe_eval(&p, &port);
            if (port.out_valid) {
                uint64_t o[NP_UNIT_MAX_FIELDS];
                b->u->sig_get_out(&b->cfg, port.out_sig, o);
                acc += o[0];
            }
            np_pipe_clock(&p, &port);
        }
        r.wall = np_now() - t0;
        r.cpu = thread_cpu() - c0;
        if (r.wall >= secs)
            break;
    }
    bu_sink = acc;
    free(sig);
    np_pipe_free(&p);
    return r;
}

/* A stream unit's stream model fed its spans back to back, output always ready; n = cycles. */
static bu_rate bu_stream(bu_unit *b, double secs)
{
    bu_rate r = { 0, 0, 0 };
    const np_unit_stream *st = b->u->stream;
    void *state = calloc(1, st->state_size);
    if (!state || st->init(state, &b->cfg) != 0) {
        free(state);
        return r;
    }
    uint64_t acc = 0;
    size_t d = 0;
    double t0 = np_now(), c0 = thread_cpu();
    for (;;) {
        for (unsigned c = 0; c < 1024; c++, r.n++) {
            np_unit_stream_port port;
            memset(&port, 0, sizeof port);
            port.in_valid = 1;
            port.in = b->desc[d];
            port.out_ready = 1;
            st->eval(state, &port);
            if (port.out_valid)
                acc += port.out[0];
            if (port.in_ready)
                d = (d + 1) % b->n_desc;
            st->clock(state, &port);
        }
        r.wall = np_now() - t0;
        r.cpu = thread_cpu() - c0;
        if (r.wall >= secs)
            break;
    }
    bu_sink = acc;
    st->free(state);
    free(state);
    return r;
}

/* --- The table --- */

static void bu_cell(bu_rate r, double stb)
{
    if (r.n == 0)
        printf(" %17s", "-");
    else if (stb > 0)
        printf(" %9.2f %6.2fx", bu_per_cpu(r) * 1e-6, bu_per_cpu(r) / stb);
    else
        printf(" %9.2f %7s", bu_per_cpu(r) * 1e-6, "");
}

static void bu_free(bu_unit *b)
{
    free(b->in);
    free(b->out);
    free(b->desc);
    memset(b, 0, sizeof *b);
}

/* One unit's row; 0, or -1 with err. */
static int bu_row(const np_unit *u, const char *spec, float *fx, float *fy, float *fz, double secs, double stb,
                  char *err, size_t errlen)
{
    bu_unit b;
    memset(&b, 0, sizeof b);
    b.u = u;
    b.fx = fx;
    b.fy = fy;
    b.fz = fz;
    if (np_unit_configure(u, &b.cfg, spec, err, errlen) != 0)
        return -1;
    u->fields(&b.cfg, &b.f);
    b.in = malloc((size_t)BU_N * b.f.n_in * sizeof *b.in);
    b.out = malloc((size_t)BU_BLOCK * b.f.n_out * sizeof *b.out);
    if (!b.in || !b.out) {
        bu_free(&b);
        return np_errf(err, errlen, "out of memory");
    }
    int rc = u->stream ? bu_points_stream(&b) : bu_is_noise(&b.f) ? (bu_points_noise(&b), 0)
                                                                  : bu_points_vectors(&b, err, errlen);
    if (rc != 0) {
        if (u->stream)
            np_errf(err, errlen, "unit %s: no spans for the bench", u->name);
        bu_free(&b);
        return -1;
    }
    char what[32];
    bu_what(&b, what, sizeof what);
    bu_rate one = bu_run(bu_blk_eval, &b, secs);
    bu_rate batch = bu_run(bu_blk_batch, &b, secs);
    bu_rate kernel = { 0, 0, 0 };
    if (u->sweep_rows)
        kernel = bu_kernel(&b, secs);
    bu_rate ref = bu_run(bu_blk_ref, &b, secs);
    bu_rate cyc = u->stream ? bu_stream(&b, secs) : bu_pipe(&b, secs);
    printf("%-9s %-16s", u->name, what);
    bu_cell(one, stb);
    bu_cell(batch, stb);
    bu_cell(kernel, stb);
    bu_cell(ref, stb);
    bu_cell(cyc, stb);
    printf("  %s\n", u->eval_n ? "eval_n" : "generic");
    fflush(stdout);
    bu_free(&b);
    return 0;
}

int np_bench_units(double secs, const char *only, const char *spec)
{
    if (only && !np_unit_find(only)) {
        char names[1024];
        np_vec_unit_names(names, sizeof names);
        np_err("bench", "--unit %s: unknown unit (units: %s)", only, names);
        return NP_EXIT_USAGE;
    }
    if (spec && !*spec)
        spec = NULL;
    if (only && spec) { /* a bad configuration is refused before anything is measured */
        np_unit_cfg c;
        char err[512];
        if (np_unit_configure(np_unit_find(only), &c, spec, err, sizeof err) != 0) {
            np_err("bench", "--config %s: %s", spec, err);
            return NP_EXIT_USAGE;
        }
    }
    size_t n_units = 0;
    while (np_unit_at(n_units))
        n_units++;
    float *fx = malloc(3 * (size_t)BU_N * sizeof *fx);
    if (!fx) {
        np_err("bench", "out of memory");
        return NP_EXIT_USAGE;
    }
    float *fy = fx + BU_N, *fz = fy + BU_N;
    for (size_t p = 0; p < BU_N; p++) { /* the noise units' x, y, z as stb's floats, word / 256 */
        uint64_t v = next_input(p);
        fx[p] = (float)(uint16_t)v / 256.0f;
        fy[p] = (float)(uint16_t)(v >> 16) / 256.0f;
        fz[p] = (float)(uint16_t)(v >> 32) / 256.0f;
    }
    double load[1] = { 0 };
    int have_load = getloadavg(load, 1) == 1;
    printf("\nevery unit, %s configuration, %u evaluations, one thread, about %.2f s per figure;\n"
           "M evaluations per CPU second (cycle model: M cycles) and x stb, the ratio to stb_perlin_noise3\n"
           "on the noise units' points in this run; load average %.2f at the start\n",
           spec ? spec : "default", (unsigned)BU_N, secs, have_load ? load[0] : -1.0);
    printf("%-9s %-16s %17s %17s %17s %17s %17s  %s\n", "unit", "evaluation", "per input", "batch",
           "kernel", "reference", "cycle model", "batch path");
    bu_unit s;
    memset(&s, 0, sizeof s);
    s.fx = fx;
    s.fy = fy;
    s.fz = fz;
    double stb = 0.0;
#ifdef BU_HAVE_STB
    bu_rate rs = bu_run(bu_blk_stb, &s, secs);
    stb = bu_per_cpu(rs);
    printf("%-9s %-16s", "stb", "3-D point, float");
    bu_cell(rs, stb);
    printf("\n");
#else
    printf("stb_perlin_noise3: not built (no <stb/stb_perlin.h>; Debian libstb-dev): no ratios\n");
#endif
    np_progress pg;
    np_progress_start(&pg, "bench units", only ? 1 : n_units);
    int rc = NP_EXIT_OK;
    const np_unit *u;
    for (size_t i = 0, done = 0; (u = np_unit_at(i)) != NULL; i++) {
        if (only && strcmp(u->name, only) != 0)
            continue;
        char err[512];
        if (bu_row(u, spec, fx, fy, fz, secs, stb, err, sizeof err) != 0) {
            np_err("bench", "%s", err);
            rc = NP_EXIT_USAGE;
        }
        np_progress_update(&pg, ++done);
    }
    np_progress_end(&pg);
    if (have_load && getloadavg(load, 1) == 1)
        printf("load average %.2f at the end; kernel: rows of a z slice (model only), not the points above\n", load[0]);
    free(fx);
    return rc;
}
