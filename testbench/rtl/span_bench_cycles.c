/* SPDX-License-Identifier: MIT */
/*
 * span_bench_cycles - the cycle count the span-unit bench (testbench/rtl/rtl_texel_tb.v, built for
 * texel or, with -DNP_TB_FDIFF, for fdiff) takes on a golden set, from the C cycle model: the
 * bench's traffic (runs, descriptors cut to k0 + m as scanline y = run, bubbles and stalls 2/8 from
 * its xorshift32 with seed 1, three reset clocks) replayed on np_span_sim with the unit's engine at
 * the default keys. The CTest pin of the RTL's count (+cycles) is checked against this.
 *
 *   span_bench_cycles UNIT TEXTURE FILE     (UNIT: texel or fdiff)
 *
 * Prints "UNIT: R runs, C cycles"; exit status 2 on bad usage or input.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_fdiff.h"
#include "np_span.h"
#include "np_texel.h"
#include "unit_span.h"

enum { MAX_RUNS = 65536, BUBBLE = 2, STALL = 2, RESET_CLOCKS = 3 };

/* The bench's generator (rtl_texel_tb.v's xorshift). */
static uint32_t xorshift32(uint32_t s)
{
    uint32_t x = s ^ (s << 13);
    x ^= x >> 17;
    return x ^ (x << 5);
}

/* Sign-extend the low w bits of v. */
static int64_t sext(unsigned long long v, unsigned w)
{
    const uint64_t m = (uint64_t)1 << (w - 1u);
    const uint64_t t = (uint64_t)v & (((uint64_t)1 << w) - 1u);
    return (int64_t)(t ^ m) - (int64_t)m;
}

static np_span runs[MAX_RUNS];
static uint32_t r_k0[MAX_RUNS], r_m[MAX_RUNS];

int main(int argc, char **argv)
{
    if (argc != 4 || (strcmp(argv[1], "texel") != 0 && strcmp(argv[1], "fdiff") != 0)) {
        fprintf(stderr, "usage: span_bench_cycles texel|fdiff TEXTURE FILE\n");
        return 2;
    }
    const int fdiff = strcmp(argv[1], "fdiff") == 0;
    unsigned tex = 0;
    const char *name;
    while ((name = np_ut_texture_name(tex)) != NULL && strcmp(name, argv[2]) != 0)
        tex++;
    if (!name) {
        fprintf(stderr, "span_bench_cycles: no built-in texture '%s'\n", argv[2]);
        return 2;
    }
    FILE *f = fopen(argv[3], "r");
    if (!f) {
        fprintf(stderr, "span_bench_cycles: cannot open %s\n", argv[3]);
        return 2;
    }
    /* Runs, as the bench groups them: the same descriptor with k = k0, k0 + 1, ... */
    char line[1024];
    size_t nr = 0;
    np_span prev;
    uint32_t prev_k = 0;
    memset(&prev, 0, sizeof prev);
    while (fgets(line, sizeof line, f)) {
        unsigned long long h[8];
        if (line[0] == '#')
            continue;
        if (sscanf(line, "%llx %llx %llx %llx %llx %llx %llx %llx", &h[0], &h[1], &h[2], &h[3], &h[4], &h[5], &h[6],
                   &h[7]) != 8) {
            fprintf(stderr, "span_bench_cycles: %s: a line without the 8 input fields\n", argv[3]);
            fclose(f);
            return 2;
        }
        np_span sp;
        memset(&sp, 0, sizeof sp);
        for (unsigned a = 0; a < 3; a++) {
            sp.s[a] = sext(h[a], NP_TEX_S_BITS);
            sp.ds[a] = sext(h[3 + a], NP_TEX_DS_BITS);
        }
        sp.n = (uint32_t)h[6];
        const uint32_t k = (uint32_t)h[7];
        if (nr > 0 && memcmp(sp.s, prev.s, sizeof sp.s) == 0 && memcmp(sp.ds, prev.ds, sizeof sp.ds) == 0 &&
            sp.n == prev.n && k == prev_k + 1u) {
            r_m[nr - 1]++;
        } else {
            if (nr == MAX_RUNS) {
                fprintf(stderr, "span_bench_cycles: %s: more than %d runs\n", argv[3], MAX_RUNS);
                fclose(f);
                return 2;
            }
            runs[nr] = sp;
            r_k0[nr] = k;
            r_m[nr] = 1;
            nr++;
        }
        prev = sp;
        prev_k = k;
    }
    fclose(f);
    if (nr == 0) {
        fprintf(stderr, "span_bench_cycles: no vectors in %s\n", argv[3]);
        return 2;
    }
    for (size_t i = 0; i < nr; i++) {
        runs[i].n = r_k0[i] + r_m[i];
        runs[i].y = (uint16_t)i;
        runs[i].x0 = 0;
    }
    const np_fdiff_cfg fc = np_fdiff_cfg_default();
    const np_texel_cfg tc = np_texel_cfg_default();
    np_span_sim sim;
    if (np_span_sim_init(&sim, fdiff ? &np_fdiff_engine : &np_texel_engine, fdiff ? (const void *)&fc : (const void *)&tc,
                         np_ut_regs(tex)) != 0) {
        fprintf(stderr, "span_bench_cycles: out of memory\n");
        return 2;
    }
    /* The bench: both sides change after the clock edge; edge c is cycle c, the first 3 in reset. */
    uint32_t rng = 1;
    int in_valid = 0, out_ready = 0;
    size_t sent = 0, orun = 0;
    uint32_t opix = 0;
    uint64_t cycles = 0;
    np_span cur;
    memset(&cur, 0, sizeof cur);
    for (;;) {
        cycles++;
        if (cycles <= RESET_CLOCKS)
            continue;
        np_span_port p;
        memset(&p, 0, sizeof p);
        p.in_valid = in_valid;
        p.in = &cur;
        p.out_ready = out_ready;
        np_span_sim_eval(&sim, &p);
        if (p.out_valid && out_ready && ++opix >= r_k0[orun] + r_m[orun]) {
            orun++;
            opix = 0;
        }
        int next_valid = in_valid;
        if (in_valid && p.in_ready) {
            sent++;
            next_valid = 0;
        }
        np_span_sim_clock(&sim, &p);
        if (sent < nr && (!in_valid || p.in_ready)) {
            rng = xorshift32(rng);
            next_valid = (rng & 7u) >= BUBBLE;
            if (next_valid)
                cur = runs[sent];
        }
        rng = xorshift32(rng);
        const int next_ready = ((rng >> 3) & 7u) >= STALL;
        if (orun == nr && sent == nr)
            break;
        in_valid = next_valid;
        out_ready = next_ready;
    }
    np_span_sim_free(&sim);
    printf("%s: %zu runs, %llu cycles\n", argv[1], nr, (unsigned long long)cycles);
    return 0;
}
