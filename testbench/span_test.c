/* SPDX-License-Identifier: MIT */
/* Fixtures and the cycle-model driver of the span units' tests (span_test.h). */
#include "span_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_test.h"

np_tex_regs span_ramp_regs(void)
{
    np_tex_regs r;
    memset(&r, 0, sizeof r);
    r.n_oct = 1;
    for (int a = 0; a < 3; a++)
        r.oct[0].m[a][a] = 1 << NP_TEX_M_FRAC;
    r.oct[0].amp = 1 << NP_TEX_AMP_FRAC;
    r.cmap_n = 2;
    r.cmap_repeat = 0;
    memset(r.cmap[1], 255, 3);
    return r;
}

np_span span_mk(uint16_t y, uint16_t x0, uint32_t n, const double s[3], const double ds[3])
{
    np_span sp;
    memset(&sp, 0, sizeof sp);
    sp.y = y;
    sp.x0 = x0;
    sp.n = n;
    for (int a = 0; a < 3; a++) {
        sp.s[a] = (int64_t)ldexp(s[a], NP_TEX_FC);
        sp.ds[a] = (int64_t)ldexp(ds[a], NP_TEX_FC);
    }
    return sp;
}

np_tex_regs span_multi_regs(np_rng *g, unsigned n_oct)
{
    np_tex_regs r = span_ramp_regs();
    r.n_oct = n_oct;
    r.cmap_n = 8;
    r.cmap_repeat = 1;
    for (unsigned k = 0; k < 8; k++)
        for (int ch = 0; ch < 3; ch++)
            r.cmap[k][ch] = (uint8_t)np_rng_below(g, 256);
    for (unsigned o = 0; o < n_oct; o++) {
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                r.oct[o].m[a][b] = (int32_t)(a == b ? (1 << (16 + o)) : (int32_t)np_rng_below(g, 1u << 15) - (1 << 14));
        r.oct[o].amp = (int32_t)((1u << (14 + 2)) >> o);
        r.oct[o].o[0] = (int64_t)np_rng_below(g, (uint64_t)1 << 40);
    }
    r.k[0] = 3 << 24;
    r.k[7] = -(5 << 22);
    r.k[9] = 1 << 20;
    return r;
}

np_span span_rand(np_rng *g)
{
    np_span sp;
    memset(&sp, 0, sizeof sp);
    sp.y = (uint16_t)np_rng_below(g, 1024);
    sp.x0 = (uint16_t)np_rng_below(g, 1024);
    uint64_t kind = np_rng_below(g, 8);
    sp.n = kind == 0 ? 0 : kind == 1 ? 1 : (uint32_t)np_rng_below(g, 300);
    for (int a = 0; a < 3; a++) {
        sp.s[a] = (int64_t)np_rng_below(g, (uint64_t)1 << 38) - ((int64_t)1 << 37);
        sp.ds[a] = np_asr((int64_t)np_rng_below(g, (uint64_t)1 << 32) - ((int64_t)1 << 31), (unsigned)np_rng_below(g, 8));
    }
    return sp;
}

np_tex_regs span_wide_regs(np_rng *g, unsigned n_oct, int variant)
{
    np_tex_regs r;
    memset(&r, 0, sizeof r);
    for (int i = 0; i < 10; i++)
        r.k[i] = np_sext(np_rng_next(g), NP_TEX_K_BITS);
    r.n_oct = n_oct;
    for (unsigned o = 0; o < n_oct; o++) {
        for (int a = 0; a < 3; a++) {
            for (int b = 0; b < 3; b++)
                r.oct[o].m[a][b] = (int32_t)np_sext(np_rng_next(g), NP_TEX_M_BITS);
            r.oct[o].o[a] = np_sext(np_rng_next(g), NP_TEX_O_BITS);
        }
        r.oct[o].amp = o == 0 ? INT32_MIN : (int32_t)np_rng_next(g);
    }
    r.cmap_repeat = variant == 0;
    r.cmap_n = variant == 0 ? 256 : 2u + (unsigned)np_rng_below(g, 254);
    for (unsigned k = 0; k < r.cmap_n; k++)
        for (int ch = 0; ch < 3; ch++)
            r.cmap[k][ch] = (uint8_t)(k % 7u == 0 ? (k & 8u ? 255u : 0u) : np_rng_below(g, 256));
    return r;
}

size_t span_rand_run(const np_span_engine *e, const void *cfg, const np_tex_regs *r, np_rng *g, np_span *sp,
                     size_t ns, np_tex_pixel *want, np_span_counts *cnt)
{
    np_tex_pixel scratch[300]; /* span_rand: at most 299 pixels */
    void *core = calloc(1, e->core_size), *sig = calloc(1, e->sig_size);
    size_t nw = 0;
    memset(cnt, 0, sizeof *cnt);
    for (size_t i = 0; i < ns && core && sig; i++) {
        sp[i] = span_rand(g);
        e->init(core, cfg, r);
        np_span_run(e, core, sig, &sp[i], want ? want + nw : scratch, cnt, NULL, NULL);
        nw += sp[i].n;
    }
    free(core);
    free(sig);
    return nw;
}

void span_traffic_phases(np_rng *g, int *state, int waiting, int *in_valid, int *out_ready)
{
    if (np_rng_below(g, 64) == 0)
        *state = (int)np_rng_below(g, 3);
    *in_valid = waiting && np_rng_below(g, 4) != 0;
    *out_ready = *state == 0 ? 1 : *state == 1 ? np_rng_below(g, 2) == 0 : np_rng_below(g, 8) == 0;
}

void span_traffic_thirds(np_rng *g, int *state, int waiting, int *in_valid, int *out_ready)
{
    (void)state;
    *in_valid = waiting && np_rng_below(g, 3) != 0;
    *out_ready = np_rng_below(g, 3) != 0;
}

int span_drive(const np_span_engine *e, const void *cfg, const np_tex_regs *r, const np_span *sp, size_t ns,
               const np_tex_pixel *want, size_t nw, np_rng *g, span_traffic_fn traffic, uint64_t max_cycles,
               span_drive_result *res)
{
    np_span_sim m;
    memset(res, 0, sizeof *res);
    if (np_span_sim_init(&m, e, cfg, r) != 0)
        return -1;
    size_t next = 0;
    int state = 0;
    while ((next < ns || !np_span_sim_idle(&m)) && m.stats.cycles < max_cycles) {
        np_span_port p;
        memset(&p, 0, sizeof p);
        if (traffic)
            traffic(g, &state, next < ns, &p.in_valid, &p.out_ready);
        else {
            p.in_valid = next < ns;
            p.out_ready = 1;
        }
        p.in = next < ns ? &sp[next] : NULL;
        np_span_sim_eval(&m, &p);
        if (p.out_valid && p.out_ready) {
            if (want && (res->got >= nw || memcmp(&p.out, &want[res->got], sizeof p.out) != 0))
                res->bad++;
            res->got++;
        }
        if (p.in_valid && p.in_ready)
            next++;
        np_span_sim_clock(&m, &p);
    }
    res->stats = m.stats;
    np_span_sim_free(&m);
    return 0;
}
