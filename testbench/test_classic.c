/* SPDX-License-Identifier: MIT */
/* The classic noise unit: bit-exact model, float reference, cycle-accurate model. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "np_classic.h"
#include "np_pipe_drive.h"
#include "np_ref.h"
#include "np_rng.h"
#include "np_test.h"
#include "np_widths.h"
#include "np_unit.h"

extern const np_unit np_unit_classic3;

static uint16_t rnd16(np_rng *r) { return (uint16_t)(np_rng_next(r) >> 48); }

static int kat(void)
{
    /*
     * Pinned outputs of the default 8-bit unit (s8 Q2.6). Any change to any
     * bit of the model shows here. The float reference value is beside each
     * for the reader; the test checks the faithful bound on those too.
     */
    static const struct { uint16_t x, y, z; int8_t f; } k[] = {
#include "classic3_kat.inc"
    };
    np_classic_cfg cfg = np_classic_cfg_default(8);
    unsigned n = sizeof k / sizeof k[0];
    for (unsigned i = 0; i < n; i++) {
        int32_t f = np_classic_eval(&cfg, k[i].x, k[i].y, k[i].z);
        NP_CHECK(f == k[i].f, "(%04x,%04x,%04x) = %d, want %d", k[i].x, k[i].y, k[i].z, f, k[i].f);
        double ref = np_ref_classic3_q88(k[i].x, k[i].y, k[i].z);
        NP_CHECK(fabs(f - ref * 64.0) <= 1.0, "(%04x,%04x,%04x) ref %.6f", k[i].x, k[i].y, k[i].z, ref);
    }
    printf("%u pinned outputs match\n", n);
    return 0;
}

static int lattice_points_zero(void)
{
    /* At a lattice point every corner-0 offset is 0 and every s is 0: noise is exactly 0. */
    np_classic_cfg cfg = np_classic_cfg_default(8);
    unsigned n = 0;
    for (unsigned i = 0; i < 256; i += 3)
        for (unsigned j = 0; j < 256; j += 5)
            for (unsigned k = 0; k < 256; k += 7, n++) {
                uint16_t x = (uint16_t)(i << 8), y = (uint16_t)(j << 8), z = (uint16_t)(k << 8);
                NP_CHECK(np_classic_eval(&cfg, x, y, z) == 0, "model at lattice point %u,%u,%u", i, j, k);
                NP_CHECK(np_ref_classic3_q88(x, y, z) == 0.0, "ref at lattice point %u,%u,%u", i, j, k);
            }
    printf("%u lattice points give exactly 0 in the model and the reference\n", n);
    return 0;
}

static int ref_properties(void)
{
    np_rng r;
    np_rng_seed(&r, 7);
    double maxabs = 0.0, maxjump = 0.0;
    for (unsigned n = 0; n < 200000; n++) {
        /* 28-bit dyadic inputs in [0, 256): x + 256 and z - 256 are exact. */
        double x = (double)(np_rng_next(&r) >> 36) * 0x1p-20;
        double y = (double)(np_rng_next(&r) >> 36) * 0x1p-20;
        double z = (double)(np_rng_next(&r) >> 36) * 0x1p-20;
        double v = np_ref_classic3(x, y, z);
        maxabs = fmax(maxabs, fabs(v));
        /* The tile repeats every 256 on each axis, also for negative inputs. */
        NP_CHECK(np_ref_classic3(x + 256.0, y, z - 256.0) == v, "period at %g %g %g", x, y, z);
        /* Continuity across a cell face and across the wrap (value is C1). */
        double face = floor(x) + 1.0;
        double jump = fabs(np_ref_classic3(face - 0x1p-30, y, z) - np_ref_classic3(face, y, z));
        maxjump = fmax(maxjump, jump);
    }
    double wrapjump = fabs(np_ref_classic3(256.0 - 0x1p-30, 17.3, 99.9) - np_ref_classic3(0.0, 17.3, 99.9));
    printf("reference: max |noise| %.6f over 2e5 random points (bound 1.5); "
           "max jump across a cell face %.3g; across the wrap %.3g\n",
           maxabs, maxjump, wrapjump);
    NP_CHECK(maxabs <= 1.5, "bound 1.5 exceeded: %g", maxabs);
    NP_CHECK(maxjump < 1e-7 && wrapjump < 1e-7, "discontinuity");
    /* q88 entry point is the real one at x/256. */
    NP_CHECK(np_ref_classic3_q88(0x1234, 0xabcd, 0xff01) ==
                 np_ref_classic3(0x1234 / 256.0, 0xabcd / 256.0, 0xff01 / 256.0), "q88");
    return 0;
}

static int in_cell_matches_eval(void)
{
    /* The hoisted form (cell set-up once, points after) is the same function. */
    np_classic_cfg cfg = np_classic_cfg_default(8);
    np_rng r;
    np_rng_seed(&r, 11);
    for (unsigned n = 0; n < 20000; n++) {
        uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
        np_classic_cell cell;
        np_classic_cell_setup((uint8_t)(x >> 8), (uint8_t)(y >> 8), (uint8_t)(z >> 8), &cell);
        int32_t a = np_classic_eval_in_cell(&cfg, &cell, (uint8_t)x, (uint8_t)y, (uint8_t)z);
        NP_CHECK(a == np_classic_eval(&cfg, x, y, z), "%04x %04x %04x", x, y, z);
        uint8_t h[8];
        for (unsigned c = 0; c < 8; c++)
            h[c] = np_hash6((uint8_t)((x >> 8) + (c & 1u)), (uint8_t)((y >> 8) + (c >> 1 & 1u)),
                            (uint8_t)((z >> 8) + (c >> 2 & 1u)));
        double rv = np_ref_classic3_in_cell(h, (x & 255) / 256.0, (y & 255) / 256.0, (z & 255) / 256.0);
        NP_CHECK(rv == np_ref_classic3_q88(x, y, z), "ref in cell %04x %04x %04x", x, y, z);
    }
    puts("hoisted model and reference equal the plain ones on 20000 random inputs");
    return 0;
}

/* The output bundle carries the inputs and the bit-exact model's value. */
static int classic_check(const void *cfg, const void *in, const void *out, uint64_t n)
{
    const np_classic_sig *i = in, *o = out;
    int32_t want = np_classic_eval(cfg, i->x, i->y, i->z);
    int ok = o->out == want && o->x == i->x && o->y == i->y && o->z == i->z;
    NP_CHECK(ok, "transaction %llu: got %d want %d", (unsigned long long)n, o->out, want);
    return ok;
}

/*
 * Drive the pipe with n inputs from a seeded generator, an input bubble with
 * probability pb/16 and an output stall with probability ps/16 each cycle
 * (np_pipe_drive.h: outputs against the bit-exact model, in order, the
 * latency exact on every unstalled transaction).
 */
static int drive_pipe(const np_classic_cfg *cfg, uint64_t n, unsigned pb, unsigned ps, uint64_t seed,
                      uint64_t *cycles_out)
{
    np_pipe p;
    if (np_classic_pipe_init(&p, cfg) != 0)
        return 1;
    np_pipe_dut d = { &p, &np_unit_classic3, 3, 16, classic_check, cfg };
    np_pipe_drive_result res = np_pipe_drive_random(&d, n, pb, ps, seed);
    printf("%llu transactions in %llu cycles (bubbles %u/16, stalls %u/16): %llu mismatches, "
           "%llu unstalled ones all at latency %u\n",
           (unsigned long long)res.transactions, (unsigned long long)res.cycles, pb, ps,
           (unsigned long long)res.mismatches, (unsigned long long)res.exact, np_pipe_latency(&p));
    if (cycles_out)
        *cycles_out = res.cycles;
    np_pipe_free(&p);
    return 0;
}

static int cycle_vs_model(void)
{
    np_classic_cfg cfg = np_classic_cfg_default(8);
    drive_pipe(&cfg, 1000000, 4, 4, 1, NULL);
    drive_pipe(&cfg, 200000, 12, 1, 2, NULL);  /* mostly bubbles */
    drive_pipe(&cfg, 200000, 1, 12, 3, NULL);  /* mostly stalls */
    np_classic_cfg wide = np_classic_cfg_default(16);
    drive_pipe(&wide, 200000, 3, 3, 4, NULL);
    return 0;
}

static int cycle_throughput(void)
{
    /* No bubbles, no stalls: n results in n + latency cycles, one per clock. */
    np_classic_cfg cfg = np_classic_cfg_default(8);
    uint64_t cycles = 0;
    drive_pipe(&cfg, 100000, 0, 0, 5, &cycles);
    NP_CHECK(cycles == 100000 + NP_CLASSIC_STAGES, "cycles %llu", (unsigned long long)cycles);
    NP_CHECK(NP_CLASSIC_STAGES == 9, "latency changed: update docs/classic3.md");
    return 0;
}

static int cycle_reset(void)
{
    np_classic_cfg cfg = np_classic_cfg_default(8);
    np_pipe p;
    NP_CHECK(np_classic_pipe_init(&p, &cfg) == 0, "init");
    np_classic_sig in;
    memset(&in, 0, sizeof in);
    np_pipe_port port = { 1, &in, 0, 0, 0, NULL };
    for (int c = 0; c < 20; c++) { /* fill, output blocked */
        np_pipe_eval(&p, &port);
        np_pipe_clock(&p, &port);
    }
    NP_CHECK(np_pipe_occupancy(&p) == NP_CLASSIC_STAGES, "full under backpressure: %u", np_pipe_occupancy(&p));
    np_pipe_eval(&p, &port);
    NP_CHECK(!port.in_ready, "full pipe must refuse input");
    NP_CHECK(p.stats.accepted == NP_CLASSIC_STAGES, "accepted exactly the depth");
    np_pipe_reset(&p);
    NP_CHECK(np_pipe_occupancy(&p) == 0, "reset empties");
    np_pipe_eval(&p, &port);
    NP_CHECK(port.in_ready && !port.out_valid, "after reset: ready, nothing valid");
    np_pipe_free(&p);
    puts("backpressure fills the pipe and stops input; reset empties it");
    return 0;
}

static int signal_widths(void)
{
    /*
     * Run the pipeline stages on random and boundary inputs and check every
     * signal against its declared width (np_classic.h): g s11, s u(WS+1),
     * l1/l2/l3 s(WL+3), out sN, for several configurations.
     */
    static const unsigned outs[] = { 8, 12, 16 };
    np_rng r;
    np_rng_seed(&r, 99);
    for (unsigned c = 0; c < 3; c++) {
        np_classic_cfg cfg = np_classic_cfg_default(outs[c]);
        int64_t mg = 0, ml = 0;
        uint32_t ms = 0;
        for (unsigned n = 0; n < 300000; n++) {
            np_classic_sig s;
            memset(&s, 0, sizeof s);
            uint64_t v = np_rng_next(&r);
            s.x = (uint16_t)v;
            s.y = (uint16_t)(v >> 16);
            s.z = (uint16_t)(v >> 32);
            if (n < 4096) { /* fractions 0 and 255 on every axis, all cells of a diagonal */
                s.x = (uint16_t)((n & 0xff) << 8 | ((n >> 8) & 1u ? 0xff : 0));
                s.y = (uint16_t)((n & 0xff) << 8 | ((n >> 9) & 1u ? 0xff : 0));
                s.z = (uint16_t)((n & 0xff) << 8 | ((n >> 10) & 1u ? 0xff : 0x80));
            }
            for (unsigned k = 0; k < NP_CLASSIC_STAGES; k++)
                np_classic_stages[k].fn(&cfg, &s);
            for (unsigned k = 0; k < 8; k++) {
                NP_CHECK(np_fits_s(s.g[k], NP_CLASSIC_G_BITS), "g %d", s.g[k]);
                mg = s.g[k] > mg ? s.g[k] : (-s.g[k] > mg ? -s.g[k] : mg);
            }
            for (unsigned k = 0; k < 3; k++) {
                NP_CHECK(np_fits_u(s.s[k], cfg.s_frac + 1u), "s %u", s.s[k]);
                NP_CHECK(s.s[k] <= (1u << cfg.s_frac), "s above 1.0");
                ms = s.s[k] > ms ? s.s[k] : ms;
            }
            int64_t ls[7] = { s.l1[0], s.l1[1], s.l1[2], s.l1[3], s.l2[0], s.l2[1], s.l3 };
            for (unsigned k = 0; k < 7; k++) {
                NP_CHECK(np_fits_s(ls[k], cfg.lerp_frac + 3u), "l %lld", (long long)ls[k]);
                ml = ls[k] > ml ? ls[k] : (-ls[k] > ml ? -ls[k] : ml);
            }
            NP_CHECK(np_fits_s(s.out, cfg.out_bits), "out %d", s.out);
            NP_CHECK(s.out == np_classic_eval(&cfg, s.x, s.y, s.z), "stages == model");
        }
        printf("out_bits=%u: max |g| %lld (s11 limit 1024), max s %u (limit %u), max |l| %.4f (limit 4)\n",
               cfg.out_bits, (long long)mg, ms, 1u << cfg.s_frac, (double)ml / (double)(1u << cfg.lerp_frac));
    }
    return 0;
}

static int error_bound_configs(void)
{
    /*
     * The error argument of np_classic.h, measured: for each configuration the
     * max error over random inputs stays within the guaranteed bound; the
     * cheap ones show the bound is not vacuous (errors above 1 LSB appear).
     */
    static const np_classic_cfg cfgs[] = {
        { 8, 12, 11 }, { 8, 8, 8 }, { 8, 24, 6 }, { 8, 4, 6 }, { 8, 6, 6 }, { 12, 16, 15 }, { 16, 20, 19 },
    };
    np_rng r;
    np_rng_seed(&r, 3);
    double worst_cheap = 0.0;
    for (unsigned c = 0; c < sizeof cfgs / sizeof cfgs[0]; c++) {
        const np_classic_cfg *cfg = &cfgs[c];
        NP_CHECK(np_classic_cfg_check(cfg) == NULL, "cfg %u invalid", c);
        double scale = (double)(1u << np_classic_out_frac(cfg)), maxe = 0.0;
        unsigned cr = 0, n = 300000;
        for (unsigned i = 0; i < n; i++) {
            uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
            double ref = np_ref_classic3_q88(x, y, z) * scale;
            int32_t f = np_classic_eval(cfg, x, y, z);
            maxe = fmax(maxe, fabs(f - ref));
            cr += (double)f == floor(ref + 0.5);
        }
        double bound = np_classic_error_bound_lsb(cfg);
        printf("out_bits=%2u s_frac=%2u lerp_frac=%2u: max error %.4f LSB (bound %.4f), correctly rounded %.3f%%\n",
               cfg->out_bits, cfg->s_frac, cfg->lerp_frac, maxe, bound, 100.0 * cr / n);
        NP_CHECK(maxe <= bound, "measured error above the argument's bound");
        if (bound <= 1.0)
            NP_CHECK(maxe <= 1.0, "faithful config not faithful");
        if (cfg->s_frac <= 6)
            worst_cheap = fmax(worst_cheap, maxe);
    }
    NP_CHECK(worst_cheap > 1.0, "cheap configurations should show errors above 1 LSB (got %.3f)", worst_cheap);
    return 0;
}

static int cfg_validation(void)
{
    np_classic_cfg c = np_classic_cfg_default(8);
    NP_CHECK(np_classic_cfg_check(&c) == NULL, "default valid");
    NP_CHECK(c.s_frac == 12 && c.lerp_frac == 11, "default 8-bit widths");
    c.out_bits = 17;
    NP_CHECK(np_classic_cfg_check(&c) != NULL, "out_bits 17");
    c = np_classic_cfg_default(8);
    c.s_frac = 25;
    NP_CHECK(np_classic_cfg_check(&c) != NULL, "s_frac 25");
    c = np_classic_cfg_default(8);
    c.lerp_frac = 5;
    NP_CHECK(np_classic_cfg_check(&c) != NULL, "lerp_frac below output fraction");
    c = np_classic_cfg_default(16);
    NP_CHECK(np_classic_cfg_check(&c) == NULL && c.s_frac == 20 && c.lerp_frac == 19, "16-bit default");
    for (unsigned n = 2; n <= 16; n++) {
        c = np_classic_cfg_default(n);
        NP_CHECK(np_classic_cfg_check(&c) == NULL, "default %u valid", n);
        NP_CHECK(np_classic_error_bound_lsb(&c) < 1.0, "default %u faithful by argument", n);
    }
    puts("configuration checks pass; every default width 2..16 is faithful by the argument");
    return 0;
}

/*
 * The datapath declaration (np_classic_datapath, which the gate report
 * prices) against the model: trace every declared signal over random and
 * boundary inputs; a declared width must hold the traced range, and may be
 * wider than needed by at most NP_WIDTH_MARGIN bits (the margin covers the
 * extreme values that random inputs do not reach but the error argument
 * allows, e.g. |l| up to 3 while traces see about 2.3).
 */
enum { NP_WIDTH_MARGIN = 1 };

static int datapath_widths(void)
{
    static const np_classic_cfg cfgs[] = { { 8, 12, 11 }, { 8, 6, 6 }, { 12, 16, 15 }, { 16, 20, 19 }, { 8, 24, 10 } };
    np_rng r;
    np_rng_seed(&r, 5);
    for (unsigned c = 0; c < sizeof cfgs / sizeof cfgs[0]; c++) {
        const np_classic_cfg *cfg = &cfgs[c];
        np_op ops[64];
        size_t nops = np_classic_datapath(cfg, ops, 64);
        NP_CHECK(nops <= 64, "declaration too long");
        np_trace t[64];
        size_t nt = np_widths_traces(ops, nops, t);
        for (unsigned n = 0; n < 400000; n++) {
            np_classic_sig s;
            memset(&s, 0, sizeof s);
            uint64_t v = np_rng_next(&r);
            if (n < 8192) { /* fractions 0 / 1 / 0x80 / 0xff in every mix, cells along a diagonal */
                static const uint8_t fr[4] = { 0x00, 0x01, 0x80, 0xff };
                s.x = (uint16_t)((n >> 6 & 0xffu) << 8 | fr[n & 3u]);
                s.y = (uint16_t)((n >> 6 & 0xffu) << 8 | fr[n >> 2 & 3u]);
                s.z = (uint16_t)((n >> 5 & 0xffu) << 8 | fr[n >> 4 & 3u]);
            } else {
                s.x = (uint16_t)v;
                s.y = (uint16_t)(v >> 16);
                s.z = (uint16_t)(v >> 32);
            }
            for (unsigned k = 0; k < NP_CLASSIC_STAGES; k++) {
                np_classic_stages[k].fn(cfg, &s);
                np_classic_trace(cfg, k, &s, t, nt);
            }
        }
        char what[64];
        snprintf(what, sizeof what, "cfg %u", c);
        np_widths_judge(ops, nops, t, NP_WIDTH_MARGIN, what, c == 0);
    }
    puts("every declared signal width holds its traced range, within a margin of 1 bit (5 configurations)");
    return 0;
}

static const np_test_case cases[] = {
    { "datapath_widths", datapath_widths },
    { "kat", kat },
    { "lattice_points_zero", lattice_points_zero },
    { "ref_properties", ref_properties },
    { "in_cell_matches_eval", in_cell_matches_eval },
    { "cycle_vs_model", cycle_vs_model },
    { "cycle_throughput", cycle_throughput },
    { "cycle_reset", cycle_reset },
    { "signal_widths", signal_widths },
    { "error_bound_configs", error_bound_configs },
    { "cfg_validation", cfg_validation },
    { NULL, NULL },
};
NP_TEST_MAIN(cases)
