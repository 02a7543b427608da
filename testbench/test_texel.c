/* SPDX-License-Identifier: MIT */
/*
 * The per-pixel scanline texturing unit np_texel: with exact weights it is
 * the forward-difference unit's exact polynomial rounded once, its error
 * stays within its bound, its cycle model (the span sequencer with
 * np_texel_engine) gives the bit-exact model's pixels at its predicted
 * cycle count, and its datapath declaration holds the traced signals.
 * (CTest names: fdiff.texel_*.)
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_fdiff.h"
#include "np_rng.h"
#include "np_test.h"
#include "np_texel.h"
#include "span_test.h"

static int texel_exact_weights(void)
{
    /* With WT = 32 the per-pixel unit is the exact polynomial rounded once: equal to the FD set-up's n0. */
    np_rng g;
    np_rng_seed(&g, 31);
    np_tex_regs r = span_multi_regs(&g, 2);
    np_texel_cfg tc = np_texel_cfg_default();
    tc.weight_frac = 32;
    np_fdiff_cfg fc = np_fdiff_cfg_default();
    fc.guard = tc.guard;
    unsigned bad = 0, n = 0;
    double worst_ratio = 0;
    for (unsigned it = 0; it < 3000; it++) {
        np_span sp = span_rand(&g);
        if (sp.n == 0)
            continue;
        np_tex_pixel a[300], b[300];
        np_s128 nt[2][300], nf[2][300];
        uint16_t set[300];
        np_texel_probe pt = { NULL, { nt[0], nt[1] } };
        np_fdiff_probe pf = { NULL, { nf[0], nf[1] }, set };
        np_texel_span(&tc, &r, &sp, a, NULL, &pt);
        np_fdiff_span(&fc, &r, &sp, b, NULL, &pf);
        for (uint32_t k = 0; k < sp.n; k++)
            for (unsigned o = 0; o < 2; o++)
                if (set[k] & (1u << o)) {
                    n++;
                    bad += nt[o][k] != nf[o][k];
                }
        /* And WT = 16 against exact weights: within the per-pixel bound. */
        np_texel_cfg t16 = tc;
        t16.weight_frac = 16;
        np_texel_probe p16 = { NULL, { nf[0], nf[1] } };
        np_texel_span(&t16, &r, &sp, b, NULL, &p16);
        double bound = np_texel_error_bound_index(&t16, &r) * ldexp(1.0, (int)np_texel_frac(&t16));
        for (uint32_t k = 0; k < sp.n; k++) {
            double d = 0;
            for (unsigned o = 0; o < 2; o++)
                d += fabs((double)(nf[o][k] - nt[o][k]));
            worst_ratio = fmax(worst_ratio, d / bound);
        }
    }
    printf("%u set-up pixels: per-pixel unit (WT = 32) == forward-difference set-up value: %u mismatches; "
           "WT = 16: worst |error| / bound = %.3f\n",
           n, bad, worst_ratio);
    NP_CHECK(bad == 0 && n > 1000, "%u mismatches of %u", bad, n);
    NP_CHECK(worst_ratio <= 1.0, "WT = 16 exceeds its bound (%.3f)", worst_ratio);
    return 0;
}

static int texel_cycle_vs_model(void)
{
    np_rng g;
    np_rng_seed(&g, 32);
    np_tex_regs r = span_multi_regs(&g, 3);
    np_texel_cfg cfg = np_texel_cfg_default();
    enum { NS = 120 };
    np_span sp[NS];
    np_tex_pixel *want = calloc(NS * 300, sizeof *want);
    size_t nw = 0;
    np_span_counts cnt;
    memset(&cnt, 0, sizeof cnt);
    for (unsigned i = 0; i < NS; i++) {
        sp[i] = span_rand(&g);
        np_texel_span(&cfg, &r, &sp[i], want + nw, &cnt, NULL);
        nw += sp[i].n;
    }
    for (int traffic = 0; traffic < 2; traffic++) {
        span_drive_result d;
        NP_CHECK(span_drive(&np_texel_engine, &cfg, &r, sp, NS, want, nw, &g, traffic ? span_traffic_thirds : NULL,
                            10000000u, &d) == 0,
                 "init");
        uint64_t pred = NS + cnt.setup_cycles + cnt.pixels + NP_TEXEL_STAGES;
        printf("texel, traffic %d: %zu pixels in %llu cycles (no-traffic prediction %llu), %zu mismatches\n", traffic,
               d.got, (unsigned long long)d.stats.cycles, (unsigned long long)pred, d.bad);
        NP_CHECK(d.got == nw && d.bad == 0, "got %zu of %zu, %zu mismatches", d.got, nw, d.bad);
        if (!traffic)
            NP_CHECK(d.stats.cycles == pred, "cycles %llu != %llu", (unsigned long long)d.stats.cycles,
                     (unsigned long long)pred);
    }
    free(want);
    return 0;
}

/* The pipeline's signals, stage by stage, for random pixels and the extremes (fractions, s48 ends). */
static void texel_trace(const void *vcfg, unsigned ci, const np_tex_regs *r, np_rng *g, span_dp_check *c)
{
    const np_texel_cfg *cfg = vcfg;
    np_texel_front front;
    np_texel_engine.init(&front, cfg, r);
    const np_span_ctx *ctx = np_span_ctx_of(&front);
    for (unsigned n = 0; n < 20000; n++) {
        np_texel_sig s;
        memset(&s, 0, sizeof s);
        for (unsigned o = 0; o < r->n_oct; o++)
            for (int a = 0; a < 3; a++) /* every 16th pixel: fractions at their extremes */
                s.u[o][a] = n % 16u == 0 ? ((np_rng_next(g) & 0xff00000000ull) | (n & 32u ? 0xffffffffu : 0u))
                                         : np_rng_next(g) & NP_MASK(NP_TEX_U_BITS);
        for (int a = 0; a < 3; a++)
            s.s[a] = n % 16u == 1 ? (n & 32u ? -((int64_t)1 << 47) : ((int64_t)1 << 47) - 1)
                                  : np_sext(np_rng_next(g), NP_TEX_S_BITS);
        for (unsigned k = 0; k < NP_TEXEL_STAGES; k++) {
            np_texel_stages[k].fn(ctx, &s);
            np_texel_trace(cfg, r, k, &s, c->t, c->nt);
        }
        /* The windows suffice: the rounding reads nothing above them. */
        const unsigned F = np_texel_frac(cfg), W = np_texel_width(cfg);
        NP_CHECK(np_tex_to_index(np_wrap_s128(s.qx, np_texel_q_window(cfg)), NP_TEX_Q_EXACT_FRAC, F, W) == s.q,
                 "cfg %u: quadric window too narrow", ci);
        const unsigned nf = NP_TEX_LAT_FRAC + 3u * cfg->weight_frac + NP_TEX_AMP_FRAC;
        for (unsigned o = 0; o < r->n_oct; o++)
            NP_CHECK(np_tex_to_index(np_wrap_s128(np_mul128((np_s128)r->oct[o].amp, s.l3[o]),
                                                  np_texel_al_window(cfg)),
                                     nf, F, W) == s.N[o],
                     "cfg %u: amplitude product window too narrow", ci);
    }
}

static int texel_datapath_widths(void)
{
    /* I, Fw, G, WT: the default, 8 weight bits, narrow, the widest, the narrowest. */
    static const char *const specs[] = {
        "idx_int=10,w_frac=12,guard=20,weight_frac=16", "idx_int=10,w_frac=12,guard=20,weight_frac=8",
        "idx_int=4,w_frac=8,guard=4,weight_frac=24", "idx_int=1,w_frac=24,guard=40,weight_frac=32",
        "idx_int=11,w_frac=1,guard=0,weight_frac=1",
    };
    return span_dp_widths("texel", specs, sizeof specs / sizeof specs[0], 41, texel_trace);
}

static const np_test_case cases[] = {
    { "texel_exact_weights", texel_exact_weights },
    { "texel_cycle_vs_model", texel_cycle_vs_model },
    { "texel_datapath_widths", texel_datapath_widths },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
