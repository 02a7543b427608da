/* SPDX-License-Identifier: MIT */
/*
 * The sample-count unit aacount (rtl_model/np_aacount.h) in the unit
 * registry. One transaction is one window on the window bus: inputs w0, w1,
 * ... (64 bits each, the last one narrower) in the bus layout of
 * np_aacount_bus_pack; outputs s, mask and the count of each built metric.
 * Metrics a configuration does not build have no bits on the bus, no output
 * column and no gates.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_aacount.h"
#include "np_ref.h"
#include "np_unit.h"
#include "unit_entry.h"
#include "unit_aacount.h"

typedef struct aac_cfg {
    np_aacount_cfg c;
} aac_cfg;
_Static_assert(sizeof(aac_cfg) <= NP_UNIT_CFG_MAX, "configuration block too large");

static const np_unit_key keys[] = {
    NP_UNIT_KEY("m", aac_cfg, c.m, 1, NP_AAC_M_MAX, 3, "m x m samples per pixel, n = m^2"),
    NP_UNIT_KEY("depth", aac_cfg, c.depth, 0, 1, 1, "1: the depth-variance metric k_d is built"),
    NP_UNIT_KEY("normal", aac_cfg, c.normal, 0, 1, 1, "1: the normal-cone metric k_n is built"),
    NP_UNIT_KEY("luma", aac_cfg, c.luma, 0, 1, 1, "1: the luma-range metric k_s is built"),
    NP_UNIT_KEY("luma_taps", aac_cfg, c.luma_taps, 4, 5, 4, "4: the four neighbours (paper); 5: and the centre (FXAA)"),
    NP_UNIT_KEY("tile", aac_cfg, c.tile, 0, NP_AAC_TILE, 0, "0, or 6: each s becomes its 6 x 6 tile's maximum"),
    NP_UNIT_KEY("serial", aac_cfg, c.serial, 0, 1, 0, "0: parallel, a window a clock; 1: serial, a beat a clock"),
    NP_UNIT_KEY("c_d", aac_cfg, c.c_d, 0, 4294967295u, 1000000u, "c_d, u32: k_d = c_d Var(d / 2^24)"),
    NP_UNIT_KEY("c_n", aac_cfg, c.c_n, 0, 255, 32, "4 c_n, u8 Q6.2: k_n = c_n sqrt(1 - min|cos|) (32: c_n = 8)"),
    NP_UNIT_KEY("c_s", aac_cfg, c.c_s, 0, 65535, 128, "16 c_s, u16 Q12.4: k_s = c_s r, r on [0, 1] (128: c_s = 8)"),
    NP_UNIT_KEY("t_min", aac_cfg, c.t_min, 0, 255, 16, "t_min in luma codes: t_min = value / 255 (PIN 16)"),
    NP_UNIT_KEY("t_edge", aac_cfg, c.t_edge, 0, 255, 32, "t_edge, u8 Q0.8 (PIN 32 = 1/8)"),
    NP_UNIT_KEY_END,
};

static const char *cfg_check(const void *cfg) { return np_aacount_cfg_check(&((const aac_cfg *)cfg)->c); }

static unsigned n_words(const np_aacount_cfg *c) { return (np_aacount_bus_bits(c) + 63u) / 64u; }

static void fields(const void *cfg, np_unit_fields *f)
{
    const np_aacount_cfg *c = &((const aac_cfg *)cfg)->c;
    unsigned bits = np_aacount_bus_bits(c), nw = n_words(c);
    memset(f, 0, sizeof *f);
    f->n_in = nw;
    for (unsigned i = 0; i < nw; i++) {
        char name[16], fmt[32];
        unsigned w = i + 1u < nw ? 64u : bits - 64u * i;
        snprintf(name, sizeof name, "w%u", i);
        snprintf(fmt, sizeof fmt, "bus[%u:%u]", 64u * i + w - 1u, 64u * i);
        np_unit_set_field(&f->in[i], name, w, 0, 0, fmt);
    }
    f->n_out = 2;
    np_unit_set_field(&f->out[0], "s", NP_AAC_S_BITS, 0, 0, "u5 samples");
    np_unit_set_field(&f->out[1], "mask", NP_AAC_MASK_BITS, 0, 0, "u16 bit b*m+a");
    if (c->depth)
        np_unit_set_field(&f->out[f->n_out++], "sd", NP_AAC_S_BITS, 0, 0, "u5 depth count");
    if (c->normal)
        np_unit_set_field(&f->out[f->n_out++], "sn", NP_AAC_S_BITS, 0, 0, "u5 normal count");
    if (c->luma)
        np_unit_set_field(&f->out[f->n_out++], "ss", NP_AAC_S_BITS, 0, 0, "u5 luma count");
}

static void put_out(const np_aacount_cfg *c, unsigned s, unsigned mask, unsigned sd, unsigned sn, unsigned ss,
                    uint64_t *o64, double *od)
{
    unsigned v[5], k = 0;
    v[k++] = s;
    v[k++] = mask;
    if (c->depth)
        v[k++] = sd;
    if (c->normal)
        v[k++] = sn;
    if (c->luma)
        v[k++] = ss;
    for (unsigned i = 0; i < k; i++) {
        if (o64)
            o64[i] = v[i];
        if (od)
            od[i] = (double)v[i];
    }
}

static void eval(const void *cfg, const uint64_t *in, uint64_t *out)
{
    const np_aacount_cfg *c = &((const aac_cfg *)cfg)->c;
    np_aacount_win w;
    np_aacount_out o;
    np_aacount_bus_unpack(c, in, &w);
    np_aacount_eval(c, &w, &o);
    put_out(c, o.s, o.mask, o.sd, o.sn, o.ss, out, NULL);
}

/* np_unit.eval_n: the threshold registers computed once per call (eval computes them per pixel). */
static void eval_n(const void *cfg, const uint64_t *in, uint64_t *out, size_t n)
{
    const np_aacount_cfg *c = &((const aac_cfg *)cfg)->c;
    np_aacount_regs r;
    np_unit_fields f;
    np_aacount_regs_compute(c, &r);
    fields(cfg, &f);
    for (size_t i = 0; i < n; i++) {
        uint64_t a[NP_UNIT_MAX_FIELDS] = { 0 }, b[NP_UNIT_MAX_FIELDS] = { 0 };
        np_aacount_win w;
        np_aacount_out o;
        for (unsigned k = 0; k < f.n_in; k++)
            a[k] = in[k * n + i];
        np_aacount_bus_unpack(c, a, &w);
        np_aacount_eval_regs(c, &r, &w, &o);
        put_out(c, o.s, o.mask, o.sd, o.sn, o.ss, b, NULL);
        for (unsigned k = 0; k < f.n_out; k++)
            out[k * n + i] = b[k];
    }
}

static void ref(const void *cfg, const uint64_t *in, double *out)
{
    const np_aacount_cfg *c = &((const aac_cfg *)cfg)->c;
    np_aacount_win w;
    np_ref_aacount_counts r;
    np_aacount_bus_unpack(c, in, &w);
    np_ref_aacount(c, &w, &r);
    put_out(c, r.s, r.mask, r.sd, r.sn, r.ss, NULL, out);
}

static double error_bound(const void *cfg)
{
    (void)cfg;
    return 0.0; /* exact integers against an exact rational reference */
}

static size_t datapath(const void *cfg, np_op *ops, size_t max)
{
    return np_aacount_datapath(&((const aac_cfg *)cfg)->c, ops, max);
}

static int pipe_init(np_pipe *p, const void *cfg) { return np_aacount_pipe_init(p, &((const aac_cfg *)cfg)->c); }

/* The pipe's input is the window bus itself; stage A wires it into the fields. */
static void sig_set_in(void *sig, const uint64_t *in) { np_aacount_sig_in_bus(sig, in); }

static void sig_get_out(const void *cfg, const void *sig, uint64_t *out)
{
    const np_aacount_cfg *c = &((const aac_cfg *)cfg)->c;
    const np_aacount_sig *s = sig;
    put_out(c, s->s, s->mask, s->sd, s->sn, s->ss, out, NULL);
}

static void trace(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n)
{
    np_aacount_trace(&((const aac_cfg *)cfg)->c, k, sig, t, n);
}

static const char *const conformance_configs[] = { "m=2", "m=4,normal=0", "m=4,depth=0,luma_taps=5",
                                                   "serial=1", "depth=0,normal=0", NULL };

/*
 * Hand-annotated windows. Each is built as a window and put on the bus of the
 * configuration (a metric left out drops its fields).
 */
enum { N_BOUNDARY = 12 };

static void boundary_win(const np_aacount_cfg *c, unsigned k, np_aacount_win *w)
{
    unsigned n = (unsigned)c->m * c->m;
    memset(w, 0, sizeof *w);
    if (n < 1 || n > NP_AAC_N_MAX)
        return;
    switch (k) {
    case 0: /* all zero: no surface, black: s = 1 */
        break;
    case 1: /* flat face facing the viewer, flat luma: s = 1 */
        for (unsigned i = 0; i < n; i++) {
            w->d[i] = 0x800000u;
            w->nrm[i][2] = 127;
        }
        memset(w->luma, 100, sizeof w->luma);
        break;
    case 2: /* the largest variance: half the samples at 0, half at 2^24 - 1 (v at its bound) */
        for (unsigned i = 0; i < n; i++)
            w->d[i] = i < n / 2u ? 0u : 0xffffffu;
        break;
    case 3: /* every field at its extreme: d = 2^24 - 1, normals (-128,-128,-128): sum_d, sum_d2, nbar, dot, p, q at their bounds; identical normals: sn = 1 */
        for (unsigned i = 0; i < n; i++) {
            w->d[i] = 0xffffffu;
            w->nrm[i][0] = w->nrm[i][1] = w->nrm[i][2] = -128;
        }
        memset(w->luma, 255, sizeof w->luma);
        break;
    case 4: /* depths near 2^24 - 1 differing by one LSB: v = n - 1 exactly */
        for (unsigned i = 0; i < n; i++)
            w->d[i] = 0xffffffu;
        w->d[0] = 0xfffffeu;
        break;
    case 5: /* normals that cancel: nbar = 0 with surfaces present: sn = n */
        for (unsigned i = 0; i < n; i++)
            w->nrm[i][2] = i < n / 2u ? 100 : -100;
        if (n & 1u)
            w->nrm[n - 1][2] = 0;
        break;
    case 6: /* identical quantised normals with |n| != 1: sn = 1, never NaN */
        for (unsigned i = 0; i < n; i++) {
            w->nrm[i][0] = 3;
            w->nrm[i][1] = -5;
            w->nrm[i][2] = 7;
        }
        break;
    case 7: /* a right-angle crease: half the normals +x, half +z */
        for (unsigned i = 0; i < n; i++) {
            w->nrm[i][0] = i & 1u ? 127 : 0;
            w->nrm[i][2] = i & 1u ? 0 : 127;
        }
        break;
    case 8: /* luma range exactly t_min = 16 with lmax = 128: 8 r < lmax gates (r = 16, 8 r = 128 = lmax: not below: fires) */
        w->luma[0] = 120;
        w->luma[1] = 112;
        w->luma[2] = 128;
        w->luma[3] = 115;
        w->luma[4] = 120;
        break;
    case 9: /* luma range one below t_min: gated, ss = 1 */
        w->luma[1] = 113;
        w->luma[2] = 128;
        w->luma[3] = 115;
        w->luma[4] = 120;
        w->luma[0] = 120;
        break;
    case 10: /* the full luma range: 0 and 255 (r = 255) */
        w->luma[1] = 0;
        w->luma[2] = 255;
        w->luma[3] = 40;
        w->luma[4] = 200;
        break;
    case 11: /* the centre alone differs: counts only with luma_taps = 5 */
        memset(w->luma, 30, sizeof w->luma);
        w->luma[0] = 250;
        break;
    default:
        break;
    }
}

static size_t boundary(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max)
{
    const np_aacount_cfg *c = &((const aac_cfg *)cfg)->c;
    for (unsigned k = 0; k < N_BOUNDARY && k < max; k++) {
        np_aacount_win w;
        boundary_win(c, k, &w);
        memset(in[k], 0, sizeof in[k]);
        np_aacount_bus_pack(c, &w, in[k]);
    }
    return N_BOUNDARY;
}

/* Timing: the parallel pipe's, or the serial unit's schedule (n clocks a window). */
static int timing(const void *cfg, np_unit_timing *t, char *err, size_t errlen)
{
    const np_aacount_cfg *c = &((const aac_cfg *)cfg)->c;
    unsigned n = (unsigned)c->m * c->m;
    (void)err;
    (void)errlen;
    memset(t, 0, sizeof *t);
    if (c->serial) {
        t->latency = np_aacount_serial_latency(c);
        t->throughput = 1.0 / (double)n;
        snprintf(t->throughput_note, sizeof t->throughput_note, "(a window of n beats, one beat a clock)");
        t->n_multi = 2;
        t->multi[0].stage = "A";
        t->multi[0].clocks = n;
        t->multi[1].stage = "P";
        t->multi[1].clocks = n;
    } else {
        t->latency = NP_AAC_PIPE_STAGES;
        t->throughput = 1.0;
        snprintf(t->throughput_note, sizeof t->throughput_note, "(a window a clock)");
    }
    return 0;
}

/* --- From a scene (unit_aacount.h) --- */

static uint32_t sat_key(double v, double hi)
{
    if (!(v > 0.0))
        return 0;
    double r = floor(v + 0.5);
    return (uint32_t)(r > hi ? hi : r);
}

void np_aacount_cfg_scene(const np_aacount_scene *a, unsigned m, double depth_range, np_aacount_cfg *c)
{
    *c = np_aacount_cfg_default();
    c->m = (uint8_t)m;
    c->depth = (uint8_t)(a->have_cd != 0);
    c->normal = (uint8_t)(a->have_cn != 0);
    c->luma = (uint8_t)(a->have_cs != 0);
    c->luma_taps = (uint8_t)(a->luma_taps ? a->luma_taps : 4u);
    c->tile = (uint8_t)a->tile;
    double range = depth_range, code = 16777215.0;
    /* k_d = c_d Var(z) = c_d Var(d) (range / (2^24 - 1))^2 = key Var(d / 2^24) */
    c->c_d = a->have_cd ? sat_key(a->c_d * range * range * (16777216.0 / code) * (16777216.0 / code), 4294967295.0)
                        : 0u;
    c->c_n = (uint8_t)(a->have_cn ? sat_key(4.0 * a->c_n, 255.0) : 0u);
    c->c_s = (uint16_t)(a->have_cs ? sat_key(16.0 * a->c_s, 65535.0) : 0u);
    /* r / 255 < t_min iff r < ceil(255 t_min) for integer r (the 1e-9 absorbs 16/255 * 255 = 16.000...04) */
    double tm = ceil(255.0 * a->t_min - 1e-9);
    c->t_min = (uint8_t)(tm < 0.0 ? 0.0 : tm > 255.0 ? 255.0 : tm);
    c->t_edge = (uint8_t)sat_key(256.0 * a->t_edge, 255.0);
}

/*
 * The registry's hook: a scene with an "aa" section uses the unit, at its m,
 * with the metrics it enables (the others are not built: no bus bits, no
 * gates). The parallel variant; the gate report prices the serial one too.
 */
static int cfg_scene(void *cfg, const np_unit_scene *sc, char *err, size_t errlen)
{
    if (!sc->aa)
        return 0;
    aac_cfg *c = cfg;
    np_aacount_cfg_scene(sc->aa, sc->aa->m ? sc->aa->m : 3u, 1.0, &c->c);
    const char *why = np_aacount_cfg_check(&c->c);
    if (why) {
        snprintf(err, errlen, "aa: %s", why);
        return -1;
    }
    return 1;
}

/* --- The adaptive count for the renderer (np_unit_samples) --- */

_Static_assert((int)NP_UNIT_WIN_SAMPLES == (int)NP_AAC_N_MAX && (int)NP_UNIT_WIN_LUMAS == (int)NP_AAC_LUMAS,
               "window shapes differ");
_Static_assert(sizeof(np_aacount_regs) <= NP_UNIT_CFG_MAX, "register block too large");

static void win_of(const np_unit_window *u, np_aacount_win *w)
{
    memcpy(w->d, u->d, sizeof w->d);
    memcpy(w->nrm, u->nrm, sizeof w->nrm);
    memcpy(w->luma, u->luma, sizeof w->luma);
}

static void aa_cfg_scene(void *cfg, const np_unit_scene *sc, unsigned m, double depth_range)
{
    np_aacount_cfg_scene(sc->aa, m, depth_range, &((aac_cfg *)cfg)->c);
}

static void aa_set_m(void *cfg, unsigned m) { ((aac_cfg *)cfg)->c.m = (uint8_t)m; }

static void aa_regs(const void *cfg, void *regs) { np_aacount_regs_compute(&((const aac_cfg *)cfg)->c, regs); }

static void aa_count(const void *cfg, const void *regs, const np_unit_window *uw, np_unit_count *o)
{
    np_aacount_win w;
    np_aacount_out r;
    win_of(uw, &w);
    np_aacount_eval_regs(&((const aac_cfg *)cfg)->c, regs, &w, &r);
    o->s = r.s;
    o->sd = r.sd;
    o->sn = r.sn;
    o->ss = r.ss;
}

static int aa_count_pipe(const void *cfg, void (*window)(const void *ctx, size_t i, np_unit_window *w),
                         const void *ctx, size_t n, const uint8_t *want, uint64_t *cycles, int *mismatch)
{
    np_pipe pipe;
    np_aacount_sig *sig = malloc(sizeof *sig);
    if (!sig || np_aacount_pipe_init(&pipe, &((const aac_cfg *)cfg)->c) != 0) {
        free(sig);
        return -1;
    }
    size_t in = 0, out = 0;
    while (out < n) {
        np_pipe_port port;
        memset(&port, 0, sizeof port);
        if (in < n) {
            np_unit_window uw;
            np_aacount_win w;
            window(ctx, in, &uw);
            win_of(&uw, &w);
            np_aacount_sig_in(sig, &w);
            port.in_valid = 1;
            port.in_sig = sig;
        }
        port.out_ready = 1;
        np_pipe_eval(&pipe, &port);
        if (port.out_valid) {
            const np_aacount_sig *o = port.out_sig;
            *mismatch |= o->s != want[out];
            out++;
        }
        if (port.in_valid && port.in_ready)
            in++;
        np_pipe_clock(&pipe, &port);
    }
    *cycles = pipe.stats.cycles;
    np_pipe_free(&pipe);
    free(sig);
    return 0;
}

static unsigned aa_serial_latency(const void *cfg) { return np_aacount_serial_latency(&((const aac_cfg *)cfg)->c); }

static void aa_post(const void *cfg, uint8_t *s, unsigned w, unsigned h)
{
    if (((const aac_cfg *)cfg)->c.tile)
        np_aacount_tile_max(s, w, h);
}

/*
 * The sample order (the paper's B_m) and the resolve, one definition for the
 * G-buffer renderer too; the count with its registers, cycle model and tile
 * maximum for the adaptive renderer (regs: an np_aacount_regs).
 */
static const np_unit_samples samples = {
    .mask = np_aacount_mask,
    .resolve = np_aacount_resolve,
    .cfg_scene = aa_cfg_scene,
    .set_m = aa_set_m,
    .regs = aa_regs,
    .count = aa_count,
    .count_pipe = aa_count_pipe,
    .serial_latency = aa_serial_latency,
    .post = aa_post,
};

const np_unit np_unit_aacount = {
    .name = "aacount",
    .summary = "adaptive supersampling sample count: depth variance, normal cone, luma range (Hollaender et al.)",
    NP_UNIT_MODEL_ENTRY,
    .tolerance_lsb = 0.0,
    .timing = timing,
    .cfg_scene = cfg_scene,
    .eval_n = eval_n,
    .samples = &samples,
};
