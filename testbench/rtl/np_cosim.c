/* SPDX-License-Identifier: MIT */
#include "np_cosim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_aacount.h"
#include "np_classic.h"
#include "np_pipe.h"
#include "np_rng.h"
#include "np_simplex.h"
#include "np_stream.h"
#include "np_unit.h"
#include "unit_span.h"
#include "np_wave.h"
#include "unit_ndim.h"

/* Densities of a traffic phase, out of 256 (as src/vecdrive.c). */
static const unsigned density[4] = { 0, 32, 128, 224 };
enum { PHASE_MIN = 16, PHASE_SPAN = 256 };

struct np_cosim {
    int simplex, wave, aacount;
    const np_unit *unit;         /* a registry unit (np_cosim_open_spec), else NULL */
    const np_unit_stream *stream; /* its stream model, when it is a stream unit (texel, fdiff), else NULL */
    void *sstate;                /* the stream model's state */
    np_unit_stream_port sport;
    const np_tex_regs *tregs;    /* a span unit's texture registers (the RTL's register inputs) */
    uint64_t s_cycles, s_accepted, s_delivered;
    np_unit_cfg ucfg;            /* its configuration (the pipe keeps it by reference) */
    np_unit_fields uf;
    void *usig;                  /* its input bundle, the pipe's sig_size bytes */
    np_classic_cfg ccfg;
    np_aacount_cfg acfg;
    np_aacount_regs aregs; /* the host's registers of acfg: the stimulus aims lumas at them */
    np_wave_unit wu;
    np_simplex_cfg scfg;
    np_pipe pipe;
    np_pipe_port port;
    np_rng rng;
    uint64_t left;
    unsigned p_bubble, p_stall;
    int pending;                 /* an input is presented and not yet accepted */
    union {
        np_classic_sig c;
        np_simplex_sig s;
        np_wave_sig w;
        np_aacount_sig a;
    } in;
    uint64_t bubbles, stalls;
};

np_cosim *np_cosim_open(const char *unit, const unsigned *p, unsigned np, int in_reg, int out_skid,
                        uint64_t seed, char *err, unsigned errn)
{
    np_cosim *c = calloc(1, sizeof *c);
    const char *bad = NULL;
    int rc = -1;
    if (!c) {
        snprintf(err, errn, "out of memory");
        return NULL;
    }
    if (strcmp(unit, "classic3") == 0 && np == 3) {
        c->ccfg.out_bits = p[0];
        c->ccfg.s_frac = p[1];
        c->ccfg.lerp_frac = p[2];
        bad = np_classic_cfg_check(&c->ccfg);
        if (!bad)
            rc = np_classic_pipe_init(&c->pipe, &c->ccfg);
    } else if (strcmp(unit, "simplex3") == 0 && np == 6) {
        c->simplex = 1;
        c->scfg.out_bits = p[0];
        c->scfg.dout_bits = p[1];
        c->scfg.deriv = p[2];
        c->scfg.t_frac = p[3];
        c->scfg.p_frac = p[4];
        c->scfg.k_frac = p[5];
        bad = np_simplex_cfg_check(&c->scfg);
        if (!bad)
            rc = np_simplex_pipe_init(&c->pipe, &c->scfg);
    } else if (strcmp(unit, "wave") == 0 && np == 6) {
        c->wave = 1;
        c->wu.c = np_wave_cfg_default();
        c->wu.c.trains = p[0];
        c->wu.c.irr = p[1];
        c->wu.c.cap = p[2];
        c->wu.c.rom_log2 = p[3];
        c->wu.c.normals = p[4];
        c->wu.c.fold = p[5];
        bad = np_wave_cfg_check(&c->wu.c);
        if (!bad) {
            if (np_wave_has_jac(&c->wu.c))
                np_wave_regs_test_jac(1, c->wu.c.trains, &c->wu.r);
            else
                np_wave_regs_test(1, c->wu.c.trains, &c->wu.r);
            bad = np_wave_regs_check(&c->wu.c, &c->wu.r);
        }
        if (!bad)
            rc = np_wave_pipe_init(&c->pipe, &c->wu);
    } else if (strcmp(unit, "aacount") == 0 && np == 10) {
        c->aacount = 1;
        c->acfg = np_aacount_cfg_default();
        c->acfg.m = (uint8_t)p[0];
        c->acfg.depth = (uint8_t)p[1];
        c->acfg.normal = (uint8_t)p[2];
        c->acfg.luma = (uint8_t)p[3];
        c->acfg.luma_taps = (uint8_t)p[4];
        c->acfg.c_d = p[5];
        c->acfg.c_n = (uint8_t)p[6];
        c->acfg.c_s = (uint16_t)p[7];
        c->acfg.t_min = (uint8_t)p[8];
        c->acfg.t_edge = (uint8_t)p[9];
        if (p[0] > 255 || p[1] > 1 || p[2] > 1 || p[3] > 1 || p[6] > 255 || p[7] > 65535 || p[8] > 255 || p[9] > 255)
            bad = "aacount: a value out of its key's range (depth, normal, luma 0/1; c_n, t_min, t_edge u8; c_s u16)";
        else
            bad = np_aacount_cfg_check(&c->acfg);
        if (!bad) {
            np_aacount_regs_compute(&c->acfg, &c->aregs);
            rc = np_aacount_pipe_init(&c->pipe, &c->acfg);
        }
    } else {
        bad = "unknown unit or wrong number of configuration values";
    }
    if (bad || rc != 0) {
        snprintf(err, errn, "%s", bad ? bad : "out of memory");
        free(c);
        return NULL;
    }
    c->pipe.in_reg = in_reg != 0;
    c->pipe.out_skid = out_skid != 0;
    np_pipe_reset(&c->pipe);
    np_rng_seed(&c->rng, seed);
    return c;
}

static const np_unit *cosim_unit_find(const char *name)
{
    if (strcmp(name, np_unit_simplexn3.name) == 0)
        return &np_unit_simplexn3;
    return np_unit_find(name);
}

/*
 * A stream unit (a span unit: texel, fdiff): its stream model (np_unit.stream,
 * np_span_sim behind it) with descriptors from its random_desc, 1 in 16 of
 * them made empty (n = 0), and the registers of the spec's texture.
 */
/* What both opens share: the cosim, its unit configured from spec, its fields within np_cosim's. */
static np_cosim *cosim_new(const np_unit *u, const char *spec, char *err, unsigned errn)
{
    np_cosim *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(err, errn, "out of memory");
        return NULL;
    }
    c->unit = u;
    if (np_unit_configure_all(u, &c->ucfg, spec, err, errn) != 0) {
        free(c);
        return NULL;
    }
    u->fields(&c->ucfg, &c->uf);
    if (c->uf.n_in > NP_COSIM_INS || c->uf.n_out > NP_COSIM_OUTS) {
        snprintf(err, errn, "%s: %u inputs, %u outputs: more than np_cosim carries", u->name, c->uf.n_in,
                 c->uf.n_out);
        free(c);
        return NULL;
    }
    return c;
}

static np_cosim *cosim_open_stream(const np_unit *u, const char *spec, uint64_t seed, char *err, unsigned errn)
{
    const char *t = strstr(spec, "texture=");
    char name[80];
    unsigned tex = 0;
    size_t len = t ? strcspn(t + 8, ",") : 0;
    if (!t || len == 0 || len >= sizeof name) {
        snprintf(err, errn, "%s: the spec must name its texture (texture=NAME)", u->name);
        return NULL;
    }
    memcpy(name, t + 8, len);
    name[len] = 0;
    const char *tn;
    while ((tn = np_ut_texture_name(tex)) != NULL && strcmp(tn, name) != 0)
        tex++;
    if (!tn) {
        snprintf(err, errn, "%s: no texture '%s'", u->name, name);
        return NULL;
    }
    np_cosim *c = cosim_new(u, spec, err, errn);
    if (!c)
        return NULL;
    c->stream = u->stream;
    c->tregs = np_ut_regs(tex);
    if (c->stream->n_desc > NP_COSIM_INS) {
        snprintf(err, errn, "%s: %u descriptor fields: more than np_cosim carries", u->name, c->stream->n_desc);
        free(c);
        return NULL;
    }
    if (!(c->sstate = calloc(1, c->stream->state_size)) || c->stream->init(c->sstate, &c->ucfg) != 0) {
        snprintf(err, errn, "out of memory");
        free(c->sstate);
        free(c);
        return NULL;
    }
    np_rng_seed(&c->rng, seed);
    return c;
}

np_cosim *np_cosim_open_spec(const char *unit, const char *spec, int in_reg, int out_skid, uint64_t seed, char *err,
                             unsigned errn)
{
    const np_unit *u = cosim_unit_find(unit);
    if (!u) {
        snprintf(err, errn, "%s: not a unit of the registry (noisepipe units)", unit);
        return NULL;
    }
    if (u->stream)
        return cosim_open_stream(u, spec, seed, err, errn);
    if (!u->pipe_init || !u->sig_set_in || !u->sig_get_out) {
        snprintf(err, errn, "%s: no one-input-one-output cycle model (np_pipe) to co-simulate", unit);
        return NULL;
    }
    np_cosim *c = cosim_new(u, spec, err, errn);
    if (!c)
        return NULL;
    for (unsigned k = 0; k < c->uf.n_out; k++)
        if (c->uf.out[k].bits > 32) {
            snprintf(err, errn, "%s: output %s is wider than 32 bits", unit, c->uf.out[k].name);
            free(c);
            return NULL;
        }
    if (u->pipe_init(&c->pipe, &c->ucfg) != 0 || !(c->usig = calloc(1, c->pipe.sig_size))) {
        snprintf(err, errn, "out of memory");
        np_pipe_free(&c->pipe);
        free(c);
        return NULL;
    }
    c->pipe.in_reg = in_reg != 0;
    c->pipe.out_skid = out_skid != 0;
    np_pipe_reset(&c->pipe);
    np_rng_seed(&c->rng, seed);
    return c;
}

int np_cosim_spec_is(const np_cosim *c, const char *spec, char *err, unsigned errn)
{
    np_unit_cfg other;
    char a[512], b[512];
    if (!c->unit) {
        snprintf(err, errn, "not a registry unit");
        return -1;
    }
    if (np_unit_configure_all(c->unit, &other, spec, err, errn) != 0)
        return -1;
    np_unit_cfg_format(c->unit, &c->ucfg, a, sizeof a);
    np_unit_cfg_format(c->unit, &other, b, sizeof b);
    if (strcmp(a, b) != 0) {
        snprintf(err, errn, "the model's configuration is %s, not %s", a, b);
        return -1;
    }
    return 0;
}

unsigned np_cosim_inputs(const np_cosim *c) { return c->stream ? c->stream->n_desc : c->unit ? c->uf.n_in : 0u; }

const struct np_tex_regs *np_cosim_tex_regs(const np_cosim *c) { return c->stream ? c->tregs : NULL; }

unsigned np_cosim_in_bits(const np_cosim *c, unsigned k) { return c->unit && k < c->uf.n_in ? c->uf.in[k].bits : 0u; }

void np_cosim_close(np_cosim *c)
{
    if (!c)
        return;
    if (c->stream) {
        c->stream->free(c->sstate);
        free(c->sstate);
        free(c);
        return;
    }
    np_pipe_free(&c->pipe);
    free(c->usig);
    free(c);
}

const struct np_wave_regs *np_cosim_wave_regs(const np_cosim *c) { return c->wave ? &c->wu.r : NULL; }

int np_cosim_is_wave(const np_cosim *c) { return c->wave; }

int np_cosim_is_aacount(const np_cosim *c) { return c->aacount; }

unsigned np_cosim_aac_bus_bits(const np_cosim *c) { return c->aacount ? np_aacount_bus_bits(&c->acfg) : 0u; }

unsigned np_cosim_outputs(const np_cosim *c)
{
    if (c->unit)
        return c->uf.n_out;
    if (c->wave)
        return 3u + 3u * c->wu.c.normals + c->wu.c.fold;
    if (c->aacount)
        return 5u;
    return c->simplex ? 4u : 1u;
}

unsigned np_cosim_out_bits(const np_cosim *c, unsigned k)
{
    if (c->unit)
        return k < c->uf.n_out ? c->uf.out[k].bits : 0u;
    if (c->wave)
        return k < 3 ? 16u : (c->wu.c.normals && k < 6) ? 20u : 1u;
    if (c->aacount)
        return k == 1 ? (unsigned)NP_AAC_MASK_BITS : (unsigned)NP_AAC_S_BITS;
    if (!c->simplex)
        return c->ccfg.out_bits;
    return k == 0 ? c->scfg.out_bits : c->scfg.dout_bits;
}

/* A random 8.8 input word: uniform, or with the fraction at an edge (1/4). */
static uint16_t random_word(np_rng *r)
{
    static const uint16_t edge[8] = { 0x00, 0x01, 0x7f, 0x80, 0x81, 0xaa, 0xfe, 0xff };
    uint64_t v = np_rng_next(r);
    uint16_t w = (uint16_t)(v & 0xffffu);
    if (((v >> 16) & 3u) == 0)
        w = (uint16_t)((w & 0xff00u) | edge[(v >> 18) & 7u]);
    return w;
}

/*
 * A random wave transaction: uniform fields, with a quarter of each at an
 * edge: v at the box's sides (0 .. 9, V - 10 .. V + 1), t near 0 or 2^32,
 * g around 0, gcap and 0x7fff, the phase shift at a quarter turn.
 */
static void random_wave(np_rng *r, const np_wave_regs *w, uint32_t in[NP_COSIM_WAVE_INS])
{
    uint64_t a = np_rng_next(r), b = np_rng_next(r), e = np_rng_next(r);
    in[0] = (uint32_t)(a & 0xffffu);
    in[1] = (uint32_t)((a >> 16) & 0xffffu);
    in[2] = (uint32_t)(a >> 32);
    in[3] = (uint32_t)b;
    in[4] = (uint32_t)((b >> 32) & 0xffffu);
    in[5] = (uint32_t)((b >> 48) & 0xffffu);
    in[6] = (uint32_t)(e & 0xffu);
    in[7] = (uint32_t)((e >> 8) & 0x7fffu);
    if (((e >> 23) & 3u) == 0)
        in[5] = (uint32_t)(((e >> 25) & 1u) ? ((e >> 26) % 10u) : (uint32_t)w->width - 10u + (uint32_t)((e >> 26) % 12u)) & 0xffffu;
    if (((e >> 30) & 3u) == 0)
        in[2] = ((e >> 32) & 1u) ? (uint32_t)((e >> 33) & 7u) : UINT32_MAX - (uint32_t)((e >> 33) & 7u);
    if (((e >> 36) & 3u) == 0) {
        static const uint32_t gv[6] = { 0u, 1u, 16384u, 0x7fffu, 0u, 0u };
        unsigned q = (unsigned)((e >> 38) % 6u);
        in[7] = q < 4 ? gv[q] : (uint32_t)w->gcap - 1u + (q - 4u) * 2u;
    }
    if (((e >> 41) & 3u) == 0)
        in[3] = (uint32_t)((e >> 43) & 3u) << 30;
}

/* A uniform value in [0, 2^k), k <= 32. */
static uint32_t random_bits(np_rng *r, unsigned k) { return k ? (uint32_t)(np_rng_next(r) >> (64u - k)) : 0u; }

/*
 * A registry unit's input words: each field a random word of its width (a
 * u16 Q8.8 field: random_word, fractions at their edges), then, for
 * several fields, a tie: two fields equal (1/8 of the inputs) or all of
 * them (1/64), where an n-D simplex's ranking falls back on its tie rule.
 */
static void random_fields(np_rng *r, const np_unit_fields *f, uint64_t in[NP_COSIM_INS])
{
    for (unsigned a = 0; a < f->n_in; a++) {
        const np_field *d = &f->in[a];
        in[a] = d->bits == 16 && d->frac == 8 && !d->is_signed ? random_word(r)
              : d->bits >= 64                                ? np_rng_next(r)
                                                             : np_rng_next(r) >> (64u - d->bits);
    }
    if (f->n_in < 2)
        return;
    const uint64_t e = np_rng_next(r);
    const unsigned a = (unsigned)((e >> 6) % f->n_in), b = (unsigned)((e >> 9) % (f->n_in - 1u));
    if ((e & 63u) == 0) {
        for (unsigned k = 0; k < f->n_in; k++)
            if (f->in[k].bits == f->in[0].bits)
                in[k] = in[0];
    } else if ((e & 7u) == 0) {
        const unsigned bb = b >= a ? b + 1u : b; /* another field than a */
        if (f->in[a].bits == f->in[bb].bits)
            in[bb] = in[a];
    }
}

static int clamp_int(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

/*
 * A random aacount window, each of its three parts drawn in one of eight
 * modes (a fresh choice per part and window):
 *   depth   uniform; all equal (v = 0); each 0 or 2^24 - 1 (v up to its
 *           maximum); near 0 or near 2^24 - 1; and, half the windows, a base
 *           plus noise in [0, 2^k), k = 0..24, which walks v across every
 *           threshold vd[j] of any c_d
 *   normals uniform s8 (-128 included); all (0,0,0) (no surface); all equal;
 *           cancelling pairs (nbar = 0, odd n: the last one (0,0,0)); and,
 *           half, a base plus noise of 2^k, k = 0..8 (the cone from 0 to
 *           wide), with some samples (1/8, or 1/2) background
 *   lumas   uniform; all equal; each 0 or 255; aimed at a threshold: the
 *           range r at t_min - 1 or t_min, at rs[j] - 1 or rs[j], or lmax at
 *           the edge of the gate 256 r >= t_edge lmax; and, half, a base plus
 *           noise of 2^k, k = 0..8
 */
static void random_window(np_cosim *c, uint64_t bus[NP_COSIM_AAC_WORDS])
{
    const np_aacount_cfg *a = &c->acfg;
    np_rng *r = &c->rng;
    const unsigned n = (unsigned)a->m * a->m;
    const uint32_t dmax = (1u << NP_AAC_DEPTH_BITS) - 1u;
    np_aacount_win w;
    memset(&w, 0, sizeof w);
    const uint64_t e = np_rng_next(r);
    const unsigned dm = (unsigned)(e & 7u), nm = (unsigned)((e >> 3) & 7u), lm = (unsigned)((e >> 6) & 7u);

    /* depth */
    unsigned k = (unsigned)((e >> 9) % 25u);
    uint32_t base = random_bits(r, 24);
    if (dm == 3) /* near an end of the range */
        base = (e >> 14) & 1u ? dmax - random_bits(r, 8) : random_bits(r, 8);
    for (unsigned i = 0; i < n; i++) {
        uint32_t d;
        switch (dm) {
        case 0: d = random_bits(r, 24); break;
        case 1: d = base; break;
        case 2: d = random_bits(r, 1) ? dmax : 0u; break;
        case 3: d = (uint32_t)clamp_int((int)base + (int)random_bits(r, 4) - 8, 0, (int)dmax); break;
        default: {
            uint64_t v = (uint64_t)base + random_bits(r, k);
            d = v > dmax ? dmax : (uint32_t)v;
        }
        }
        w.d[i] = d;
    }

    /* normals */
    int nb[3];
    do {
        for (unsigned q = 0; q < 3; q++)
            nb[q] = (int)random_bits(r, 8) - 128;
    } while (nb[0] == 0 && nb[1] == 0 && nb[2] == 0);
    k = (unsigned)((e >> 15) % 9u);
    for (unsigned i = 0; i < n; i++)
        for (unsigned q = 0; q < 3; q++) {
            int v;
            switch (nm) {
            case 0: v = (int)random_bits(r, 8) - 128; break;
            case 1: v = 0; break;
            case 2: v = nb[q]; break;
            case 3: v = i + 1 == n && (n & 1u) ? 0 : (i & 1u) ? -(int)w.nrm[i - 1][q] : clamp_int(nb[q], -127, 127); break;
            default: v = clamp_int(nb[q] + (int)random_bits(r, k) - (k ? (1 << (k - 1)) : 0), -128, 127);
            }
            w.nrm[i][q] = (int8_t)v;
        }
    if (nm >= 4) /* background samples */
        for (unsigned i = 0; i < n; i++)
            if (random_bits(r, nm == 7 ? 1 : 3) == 0)
                w.nrm[i][0] = w.nrm[i][1] = w.nrm[i][2] = 0;

    /* lumas: index 0 the centre, 1..4 the neighbours */
    k = (unsigned)((e >> 19) % 9u);
    unsigned lb = random_bits(r, 8);
    for (unsigned q = 0; q < NP_AAC_LUMAS; q++) {
        int v;
        switch (lm) {
        case 0: v = (int)random_bits(r, 8); break;
        case 1: v = (int)lb; break;
        case 2: v = random_bits(r, 1) ? 255 : 0; break;
        case 3: v = (int)lb; break; /* set below */
        default: v = clamp_int((int)lb + (int)random_bits(r, k) - (k ? (1 << (k - 1)) : 0), 0, 255);
        }
        w.luma[q] = (uint8_t)v;
    }
    if (lm == 3) {
        /* aim the range r = lmax - lmin of the compared taps at a threshold */
        unsigned sel = (unsigned)((e >> 23) % 3u), lo_tap = a->luma_taps == 5 ? 0u : 1u;
        int rr, lmax;
        if (sel == 0) {
            rr = (int)a->t_min - (int)((e >> 25) & 1u);
        } else if (sel == 1 && n > 1) {
            unsigned j = 1u + (unsigned)((e >> 26) % (n - 1u));
            rr = (int)c->aregs.rs[j] - (int)((e >> 25) & 1u);
        } else {
            rr = (int)random_bits(r, 8);
        }
        rr = clamp_int(rr, 0, 255);
        if (sel == 2 && a->t_edge) /* lmax at the gate's edge: 256 rr against t_edge lmax */
            lmax = 256 * rr / a->t_edge + (int)((e >> 25) & 1u);
        else
            lmax = rr + (int)random_bits(r, 8);
        lmax = clamp_int(lmax, rr, 255);
        const int lmin = lmax - rr;
        for (unsigned q = 0; q < NP_AAC_LUMAS; q++)
            w.luma[q] = (uint8_t)(lmin + (int)(random_bits(r, 8) % (unsigned)(rr + 1)));
        /* two distinct compared taps carry the extremes */
        unsigned t0 = lo_tap + (unsigned)((e >> 30) % (NP_AAC_LUMAS - lo_tap));
        unsigned t1 = lo_tap + (t0 - lo_tap + 1u + (unsigned)((e >> 33) % (NP_AAC_LUMAS - lo_tap - 1u))) % (NP_AAC_LUMAS - lo_tap);
        w.luma[t0] = (uint8_t)lmin;
        w.luma[t1] = (uint8_t)lmax;
        if (lo_tap == 1)
            w.luma[0] = (uint8_t)random_bits(r, 8); /* the centre is not compared */
    }

    memset(bus, 0, NP_COSIM_AAC_WORDS * sizeof bus[0]);
    np_aacount_bus_pack(a, &w, bus);
}

void np_cosim_drive(np_cosim *c, np_cosim_cycle *cy, int traffic)
{
    int bubble = 0, stall = 0;
    if (traffic) {
        if (c->left == 0) {
            uint64_t r = np_rng_next(&c->rng);
            c->left = PHASE_MIN + (r % PHASE_SPAN);
            c->p_bubble = density[(r >> 8) & 3u];
            c->p_stall = density[(r >> 10) & 3u];
        }
        c->left--;
        uint64_t r = np_rng_next(&c->rng);
        bubble = (unsigned)(r & 255u) < c->p_bubble;
        stall = (unsigned)((r >> 8) & 255u) < c->p_stall;
    }
    if (!c->pending) {
        if (bubble) {
            cy->in_valid = 0;
        } else {
            cy->in_valid = 1;
            if (c->stream) {
                uint64_t d[NP_UNIT_MAX_FIELDS] = { 0 };
                c->stream->random_desc(&c->ucfg, &c->rng, d);
                if (np_rng_below(&c->rng, 16) == 0)
                    d[c->stream->length_field] = 0; /* an empty span: accepted, no pixels */
                for (unsigned k = 0; k < c->stream->n_desc; k++)
                    cy->in[k] = d[k];
            } else if (c->unit) {
                random_fields(&c->rng, &c->uf, cy->in);
            } else if (c->wave) {
                random_wave(&c->rng, &c->wu.r, cy->win);
            } else if (c->aacount) {
                random_window(c, cy->bus);
            } else {
                cy->x = random_word(&c->rng);
                cy->y = random_word(&c->rng);
                cy->z = random_word(&c->rng);
            }
            c->pending = 1;
        }
    }
    cy->out_ready = !stall;
}

void np_cosim_eval(np_cosim *c, np_cosim_cycle *cy)
{
    if (c->stream) {
        c->sport.in_valid = cy->in_valid;
        c->sport.in = cy->in;
        c->sport.out_ready = cy->out_ready;
        c->stream->eval(c->sstate, &c->sport);
        cy->in_ready = c->sport.in_ready;
        cy->out_valid = c->sport.out_valid;
        memset(cy->out, 0, sizeof cy->out);
        if (cy->out_valid)
            for (unsigned k = 0; k < c->uf.n_out; k++)
                cy->out[k] = (uint32_t)c->sport.out[k];
        return;
    }
    /* Only the inputs change: the rest of the bundle stays as calloc left it (the stages write banks, never in_sig). */
    if (c->unit) {
        c->unit->sig_set_in(c->usig, cy->in);
    } else if (c->aacount) {
        np_aacount_sig_in_bus(&c->in.a, cy->bus); /* stage A unpacks the bus, as the RTL's bank A reads it */
    } else if (c->wave) {
        np_wave_in *w = &c->in.w.in;
        w->i = (uint16_t)cy->win[0];
        w->j = (uint16_t)cy->win[1];
        w->t = cy->win[2];
        w->ph = cy->win[3];
        w->u = (uint16_t)cy->win[4];
        w->v = (uint16_t)cy->win[5];
        w->r = (uint8_t)cy->win[6];
        w->g = (uint16_t)cy->win[7];
    } else if (c->simplex) {
        c->in.s.x = cy->x;
        c->in.s.y = cy->y;
        c->in.s.z = cy->z;
    } else {
        c->in.c.x = cy->x;
        c->in.c.y = cy->y;
        c->in.c.z = cy->z;
    }
    c->port.in_valid = cy->in_valid;
    c->port.in_sig = c->unit ? c->usig : (const void *)&c->in;
    c->port.out_ready = cy->out_ready;
    np_pipe_eval(&c->pipe, &c->port);
    cy->in_ready = c->port.in_ready;
    cy->out_valid = c->port.out_valid;
    memset(cy->out, 0, sizeof cy->out);
    if (!cy->out_valid)
        return;
    if (c->unit) {
        uint64_t w[NP_UNIT_MAX_FIELDS] = { 0 };
        c->unit->sig_get_out(&c->ucfg, c->port.out_sig, w);
        for (unsigned k = 0; k < c->uf.n_out; k++)
            cy->out[k] = (uint32_t)w[k];
    } else if (c->aacount) {
        const np_aacount_sig *s = c->port.out_sig;
        cy->out[0] = s->s;
        cy->out[1] = s->mask;
        cy->out[2] = s->sd;
        cy->out[3] = s->sn;
        cy->out[4] = s->ss;
    } else if (c->wave) {
        const np_wave_sig *s = c->port.out_sig;
        unsigned k = 0;
        cy->out[k++] = (uint16_t)s->out.y;
        cy->out[k++] = (uint16_t)s->out.dx;
        cy->out[k++] = (uint16_t)s->out.dz;
        if (c->wu.c.normals) {
            cy->out[k++] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->jac.nx, 20);
            cy->out[k++] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->jac.ny, 20);
            cy->out[k++] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->jac.nz, 20);
        }
        if (c->wu.c.fold)
            cy->out[k++] = s->jac.fold;
    } else if (c->simplex) {
        const np_simplex_sig *s = c->port.out_sig;
        cy->out[0] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->f, c->scfg.out_bits);
        for (unsigned a = 0; a < 3; a++)
            cy->out[1 + a] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->df[a], c->scfg.dout_bits);
    } else {
        const np_classic_sig *s = c->port.out_sig;
        cy->out[0] = (uint32_t)np_trunc_u((uint64_t)(int64_t)s->out, c->ccfg.out_bits);
    }
}

void np_cosim_accept(np_cosim *c, const np_cosim_cycle *cy)
{
    if (cy->in_valid && cy->in_ready)
        c->pending = 0;
    if (!cy->in_valid && cy->in_ready)
        c->bubbles++;
    if (cy->out_valid && !cy->out_ready)
        c->stalls++;
}

void np_cosim_clock(np_cosim *c, const np_cosim_cycle *cy)
{
    np_cosim_accept(c, cy);
    if (c->stream) {
        c->s_cycles++;
        c->s_accepted += cy->in_valid && cy->in_ready;
        c->s_delivered += cy->out_valid && cy->out_ready;
        c->stream->clock(c->sstate, &c->sport);
        return;
    }
    np_pipe_clock(&c->pipe, &c->port);
}

void np_cosim_counts(const np_cosim *c, uint64_t counts[5])
{
    counts[0] = c->stream ? c->s_cycles : c->pipe.stats.cycles;
    counts[1] = c->stream ? c->s_accepted : c->pipe.stats.accepted;
    counts[2] = c->stream ? c->s_delivered : c->pipe.stats.delivered;
    counts[3] = c->bubbles;
    counts[4] = c->stalls;
}
