/* SPDX-License-Identifier: MIT */
/*
 * The per-pixel scanline texturing unit np_texel: with exact weights it is
 * the forward-difference unit's exact polynomial rounded once, its error
 * stays within its bound, its cycle model (the span sequencer with
 * np_texel_engine) gives the bit-exact model's pixels at its predicted
 * cycle count. (CTest names: fdiff.texel_*; its declared widths are checked
 * by conformance.texel.datapath_widths through np_unit_span.trace.)
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
    np_span_counts cnt;
    size_t nw = span_rand_run(&np_texel_engine, &cfg, &r, &g, sp, NS, want, &cnt);
    for (int traffic = 0; traffic < 2; traffic++) {
        span_drive_result d;
        NP_CHECK(span_drive(&np_texel_engine, &cfg, &r, sp, NS, want, nw, &g, traffic ? span_traffic_thirds : NULL,
                            10000000u, &d) == 0,
                 "init");
        /*
         * No traffic: the timing rules of np_span.h with the descriptor buffer,
         * written out. A span read while the unit is idle begins in that
         * clock; the next one is read the clock after and its set-up starts on
         * the front end once that is free; it begins in the clock the previous
         * span's last pixel issues (an empty one ends there, and the one after
         * it is read, idle, in the next clock).
         */
        const uint64_t S = np_texel_span_setup_cycles(&cfg, &r);
        uint64_t clk = 0, fe_free = 0, pend = 0; /* pend: the buffered span's set-up end (0: none) */
        for (unsigned i = 0; i < NS; i++) {
            uint64_t begin_clk = clk, done;
            if (pend) {
                done = pend;
            } else {
                done = (clk + 1u > fe_free ? clk + 1u : fe_free) + (sp[i].n ? S : 0u);
            }
            pend = 0;
            if (sp[i].n == 0) {
                clk = begin_clk + 1u; /* idle: the next descriptor is read in the next clock */
                continue;
            }
            fe_free = done;
            uint64_t first = done > begin_clk + 1u ? done : begin_clk + 1u;
            uint64_t last = first + sp[i].n - 1u;
            if (i + 1u < NS && sp[i + 1u].n) { /* read into the buffer the clock after this span began */
                uint64_t st = begin_clk + 2u > fe_free ? begin_clk + 2u : fe_free;
                pend = st + S;
                fe_free = pend;
            } else if (i + 1u < NS) {
                pend = 0;
            }
            clk = last; /* the next span begins in this clock */
        }
        uint64_t pred = clk + 1u + NP_TEXEL_STAGES;
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

static const np_test_case cases[] = {
    { "texel_exact_weights", texel_exact_weights },
    { "texel_cycle_vs_model", texel_cycle_vs_model },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
