/* SPDX-License-Identifier: MIT */
/* The simplex unit's cycle-accurate model, and its datapath declaration against the model. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "simplex_test.h"
#include "np_pipe_drive.h"
#include "np_report.h"
#include "np_widths.h"

/* ------------------------------------------------------------------------ */

/* The output bundle carries the inputs and the bit-exact model's four values. */
static int simplex_check(const void *cfg, const void *in, const void *out, uint64_t n)
{
    const np_simplex_sig *i = in, *o = out;
    np_simplex_out want;
    np_simplex_eval(cfg, i->x, i->y, i->z, &want);
    int ok = o->f == want.f && o->df[0] == want.df[0] && o->df[1] == want.df[1] && o->df[2] == want.df[2] &&
             o->x == i->x && o->y == i->y && o->z == i->z;
    NP_CHECK(ok, "transaction %llu: got %d %d %d %d want %d %d %d %d", (unsigned long long)n, o->f, o->df[0],
             o->df[1], o->df[2], want.f, want.df[0], want.df[1], want.df[2]);
    return ok;
}

/*
 * Drive the pipe with n inputs, an input bubble with probability pb/16 and
 * an output stall with probability ps/16 each cycle (np_pipe_drive.h:
 * outputs against the bit-exact model, in order, the latency exact on every
 * unstalled transaction).
 */
static void drive_pipe(const np_simplex_cfg *cfg, uint64_t n, unsigned pb, unsigned ps, uint64_t seed)
{
    np_pipe p;
    NP_CHECK(np_simplex_pipe_init(&p, cfg) == 0, "pipe init");
    unsigned lat = np_pipe_latency(&p);
    NP_CHECK(lat == np_simplex_stage_count(cfg), "latency %u", lat);
    np_pipe_dut d = { &p, &np_unit_simplex3, 3, 16, simplex_check, cfg };
    np_pipe_drive_result res = np_pipe_drive_random(&d, n, pb, ps, seed);
    printf("deriv=%u: %llu transactions in %llu cycles (bubbles %u/16, stalls %u/16): %llu mismatches, "
           "%llu unstalled ones all at latency %u\n",
           cfg->deriv, (unsigned long long)res.transactions, (unsigned long long)res.cycles, pb, ps,
           (unsigned long long)res.mismatches, (unsigned long long)res.exact, lat);
    np_pipe_free(&p);
}

int simplex_cycle_vs_model_1e6(void)
{
    np_simplex_cfg cfg = default_cfg();
    drive_pipe(&cfg, 1000000, 4, 4, 1);  /* bubbles and stalls, 1/4 each */
    drive_pipe(&cfg, 100000, 12, 1, 2);  /* mostly bubbles */
    drive_pipe(&cfg, 100000, 1, 12, 3);  /* mostly stalls */
    drive_pipe(&cfg, 100000, 0, 0, 4);   /* full throughput */
    np_simplex_cfg f8 = np_simplex_cfg_default(8, 8, 0);
    drive_pipe(&f8, 200000, 3, 3, 5);    /* f only: 9 stages */
    NP_CHECK(NP_SIMPLEX_STAGES_D == 10 && NP_SIMPLEX_STAGES_F == 9, "latency changed: update docs/simplex3.md");
    return 0;
}


/* ------------------------------------------------------------------------ */
/*
 * The datapath declaration (np_simplex_datapath, which the gate report
 * prices) against the model, as classic.datapath_widths does: trace every
 * declared signal over the boundary table, the extremes and random inputs;
 * a declared width must hold the traced range, and may be wider than needed
 * by at most NP_WIDTH_MARGIN bits (the margin covers values the range
 * argument allows but the inputs do not reach, e.g. |D_a|^2 <= 1536^2 while
 * |D_a| <= 1280 in practice).
 */
enum { NP_WIDTH_MARGIN = 1, DP_MAX_OPS = 160 };

/*
 * The modular forms the declaration prices, on one input after RK and CH:
 * U mod 2^12 from the input word mod 2^11, the cell mod 8 and n mod 16;
 * D from U's top nibble; 683 n as four shift-adds.
 */
static void check_modular(const np_simplex_sig *s, int after_ch)
{
    const uint16_t in[3] = { s->x, s->y, s->z };
    uint32_t n16 = (s->cell[0] + s->cell[1] + s->cell[2]) & 15u;
    for (unsigned a = 0; a < 3; a++) {
        uint32_t nn = s->sk[a] >> 8, n11 = ((nn << 2) + nn) * 2u + nn, n683 = ((n11 << 5) - n11) * 2u + nn;
        NP_CHECK(n683 == 683u * nn, "683 n as shift-adds");
        uint32_t x6 = 2u * ((2u * (in[a] & 0x7ffu) + (in[a] & 0x7ffu)) & 0x7ffu);  /* 6a mod 2^12 */
        uint32_t i3 = (2u * (s->cell[a] & 7u) + (s->cell[a] & 7u)) & 7u;            /* 3i mod 8 */
        uint32_t top = (n16 - 2u * i3) & 15u;
        int32_t u = (int32_t)np_sext((x6 + 256u * top) & 0xfffu, 12);
        NP_CHECK(u == s->off[a], "U mod 2^12 at (%04x,%04x,%04x): %d, model %d", s->x, s->y, s->z, u, s->off[a]);
        if (!after_ch)
            continue;
        for (unsigned c = 0; c < 4; c++) {
            unsigned am = np_simplex_corner_mask(s->hi, s->lo, c) >> a & 1u;
            uint32_t k = ((uint32_t)c - 6u * am) & 15u;
            int32_t d = (int32_t)np_sext(((uint32_t)s->off[a] + 256u * k) & 0xfffu, 12);
            NP_CHECK(d == s->d[c][a], "D nibble at (%04x,%04x,%04x)", s->x, s->y, s->z);
        }
    }
}

/* Trace every declared signal of cfg over n random inputs plus the boundary table; 0 or the failures. */
static int trace_widths(const np_simplex_cfg *cfg, unsigned nrand, uint64_t seed, int print)
{
    int before = np_test_failures;
    np_op ops[DP_MAX_OPS];
    size_t nops = np_simplex_datapath(cfg, ops, DP_MAX_OPS);
    NP_CHECK(nops <= DP_MAX_OPS && nops <= NP_REPORT_MAX_OPS, "declaration too long: %zu ops", nops);
    if (nops > DP_MAX_OPS)
        return 1;
    const np_stage_desc *tab = np_simplex_stage_table(cfg);
    unsigned nst = np_simplex_stage_count(cfg);
    for (size_t i = 0; i < nops; i++) {
        unsigned k = 0;
        while (k < nst && strcmp(tab[k].name, ops[i].stage) != 0)
            k++;
        NP_CHECK(k < nst, "op in unknown stage %s", ops[i].stage);
        NP_CHECK(ops[i].level < 8, "%s: level %u (the report sums 8 levels)", ops[i].stage, ops[i].level);
    }
    np_trace t[DP_MAX_OPS];
    size_t nt = np_widths_traces(ops, nops, t);
    uint64_t (*b)[NP_UNIT_MAX_FIELDS] = NULL;
    size_t nb = np_unit_simplex3.boundary(NULL, NULL, 0);
    b = malloc(nb * sizeof *b);
    NP_CHECK(b != NULL, "out of memory");
    if (!b)
        return 1;
    np_unit_simplex3.boundary(NULL, b, nb);
    np_rng r;
    np_rng_seed(&r, seed);
    for (size_t it = 0; it < nb + nrand; it++) {
        np_simplex_sig s;
        memset(&s, 0, sizeof s);
        if (it < nb) {
            s.x = (uint16_t)b[it][0];
            s.y = (uint16_t)b[it][1];
            s.z = (uint16_t)b[it][2];
        } else {
            s.x = rnd16(&r);
            s.y = rnd16(&r);
            s.z = rnd16(&r);
        }
        for (unsigned k = 0; k < nst; k++) {
            tab[k].fn(cfg, &s);
            np_simplex_trace(cfg, k, &s, t, nt);
            if (strcmp(tab[k].name, "CH") == 0 && (it & 15u) == 0)
                check_modular(&s, 1);
        }
    }
    free(b);
    char what[64];
    snprintf(what, sizeof what, "t_frac=%u p_frac=%u", cfg->t_frac, cfg->p_frac);
    np_widths_judge(ops, nops, t, NP_WIDTH_MARGIN, what, print);
    return np_test_failures - before;
}

/* Total gates of cfg as the gate report prices it. */
static double priced_total(const np_simplex_cfg *cfg, unsigned *reg_bits)
{
    np_unit_cfg uc;
    char spec[160], err[256];
    snprintf(spec, sizeof spec, "out_bits=%u,dout_bits=%u,deriv=%u,t_frac=%u,p_frac=%u,k_frac=%u", cfg->out_bits,
             cfg->dout_bits, cfg->deriv, cfg->t_frac, cfg->p_frac, cfg->k_frac);
    NP_CHECK(np_unit_configure(&np_unit_simplex3, &uc, spec, err, sizeof err) == 0, "%s", err);
    np_unit_cost c;
    NP_CHECK(np_unit_cost_compute(&np_unit_simplex3, &uc, &np_cost_default, &c, err, sizeof err) == 0, "%s", err);
    *reg_bits = c.reg_bits;
    return c.total;
}

int simplex_datapath_widths(void)
{
    static const unsigned defaults[][3] = { { 16, 16, 1 }, { 16, 16, 0 }, { 8, 8, 1 }, { 12, 6, 0 },
                                            { 20, 20, 1 }, { 4, 5, 1 } };
    enum { N_DEF = sizeof defaults / sizeof defaults[0] };
    np_simplex_cfg cfgs[N_DEF + 2];
    for (unsigned c = 0; c < N_DEF; c++)
        cfgs[c] = np_simplex_cfg_default(defaults[c][0], defaults[c][1], defaults[c][2]);
    cfgs[N_DEF] = (np_simplex_cfg){ 8, 8, 1, 8, 8, 8 };       /* narrow: every fraction width 8 */
    cfgs[N_DEF + 1] = (np_simplex_cfg){ 16, 16, 0, 12, 10, 9 }; /* narrow, f only */
    for (unsigned c = 0; c < N_DEF + 2; c++) {
        const np_simplex_cfg *cfg = &cfgs[c];
        if (c == 0)
            printf("default unit (out_bits=16 dout_bits=16 deriv=1 t_frac=%u p_frac=%u k_frac=%u), "
                   "1e5 random inputs and the %zu boundary inputs:\n",
                   cfg->t_frac, cfg->p_frac, cfg->k_frac, np_unit_simplex3.boundary(NULL, NULL, 0));
        int bad = trace_widths(cfg, c == 0 ? 100000u : 40000u, 40u + c, c == 0);
        printf("out=%2u dout=%2u deriv=%u t_frac=%2u p_frac=%2u k_frac=%2u: %s\n", cfg->out_bits, cfg->dout_bits,
               cfg->deriv, cfg->t_frac, cfg->p_frac, cfg->k_frac, bad ? "FAILED" : "every width holds, margin <= 1");
    }

    /* deriv = 0 leaves the derivative datapath out: no derivative signal, fewer gates and register bits. */
    static const char *const dsig[] = { "tau3p", "tau3", "qp", "q", "e", "q5", "mp", "m", "em", "qs", "dprod", "df" };
    for (unsigned c = 0; c < N_DEF + 2; c++) {
        np_simplex_cfg d1 = cfgs[c], d0 = cfgs[c];
        d1.deriv = 1;
        d0.deriv = 0;
        np_op ops[DP_MAX_OPS];
        size_t n0 = np_simplex_datapath(&d0, ops, DP_MAX_OPS);
        for (size_t i = 0; i < n0 && i < DP_MAX_OPS; i++) {
            NP_CHECK(strcmp(ops[i].stage, "M2") != 0, "deriv=0 declares an M2 op");
            for (unsigned k = 0; ops[i].signal && k < sizeof dsig / sizeof dsig[0]; k++)
                NP_CHECK(strcmp(ops[i].signal, dsig[k]) != 0, "deriv=0 declares %s", dsig[k]);
        }
        unsigned r1, r0;
        double g1 = priced_total(&d1, &r1), g0 = priced_total(&d0, &r0);
        NP_CHECK(g0 < g1 && r0 < r1, "deriv=0 (%.0f gates, %u bits) not below deriv=1 (%.0f, %u)", g0, r0, g1, r1);
        if (c == 0) {
            np_simplex_cfg f16 = np_simplex_cfg_default(16, 16, 0);
            unsigned rf;
            double gf = priced_total(&f16, &rf);
            printf("priced: deriv=1 %.0f gates (%u register bits); deriv=0 same widths %.0f (%u); "
                   "deriv=0 own default %.0f (%u)\n", g1, r1, g0, r0, gf, rf);
            NP_CHECK(gf < g1, "f-only default not below deriv=1");
        }
    }
    puts("every declared signal width holds its traced range, within a margin of 1 bit (8 configurations); "
         "deriv=0 declares no derivative operator and prices below deriv=1");
    return 0;
}

/* The declared output width of signal sig (0 when not declared). */
static unsigned declared_width(const np_op *ops, size_t n, const char *sig)
{
    for (size_t i = 0; i < n; i++)
        if (ops[i].signal && ops[i].out && strcmp(ops[i].signal, sig) == 0)
            return ops[i].out;
    return 0;
}

/* 1 when signal sig's last operator is a multiplexer (O's saturation). */
static int declared_saturation(const np_op *ops, size_t n, const char *sig)
{
    for (size_t i = 0; i < n; i++)
        if (ops[i].signal && strcmp(ops[i].signal, sig) == 0 && ops[i].kind == NP_OP_MUX)
            return 1;
    return 0;
}

/*
 * The reference RTL (rtl_model/verilog/np_simplex3.v) holds M..O at the
 * declaration's widths when TIGHT (WT >= 9 and WP >= 9): e, e_a - m_a, S,
 * Q_a, q and m in WP + 1 bits, fc in WP, 5q in WP + 3, and it leaves O's
 * saturation out. Every configuration of the key ranges with WT, WP >= 9
 * must have declared widths within those (the declaration's range argument
 * is then the RTL's) and no saturation; below the threshold some do not
 * (the RTL then keeps its never-wrapping widths and the saturation).
 */
int simplex_rtl_widths(void)
{
    static const char *const sig[] = { "fc", "q", "e", "m", "em", "s", "qs", "q5" };
    static const unsigned extra[] = { 0, 1, 1, 1, 1, 1, 1, 3 };
    enum { NS = sizeof sig / sizeof sig[0] };
    np_op ops[DP_MAX_OPS];
    unsigned long checked = 0, tight_at_default = 0, beyond = 0;
    for (unsigned wt = 1; wt <= 30; wt++)
        for (unsigned wp = 1; wp <= 32; wp++) {
            int tight = wt >= 9 && wp >= 9;
            np_simplex_cfg cfg = { 16, 16, 1, wt, wp, 22 };
            size_t n = np_simplex_datapath(&cfg, ops, DP_MAX_OPS);
            NP_CHECK(n <= DP_MAX_OPS, "%zu ops", n);
            int fits = 1;
            for (unsigned k = 0; k < NS; k++) {
                unsigned w = declared_width(ops, n, sig[k]);
                NP_CHECK(w > 0, "no width declared for %s", sig[k]);
                if (w > wp + extra[k])
                    fits = 0;
                NP_CHECK(!tight || w <= wp + extra[k], "t_frac=%u p_frac=%u: %s declared %u bits, the RTL holds %u",
                         wt, wp, sig[k], w, wp + extra[k]);
            }
            beyond += !fits;
            if (!tight)
                continue;
            for (unsigned wk = 1; wk <= 26; wk++)
                for (unsigned nb = 4; nb <= 20; nb++)
                    for (unsigned nd = 5; nd <= 20; nd++) {
                        np_simplex_cfg c = { nb, nd, 1, wt, wp, wk };
                        size_t m = np_simplex_datapath(&c, ops, DP_MAX_OPS);
                        NP_CHECK(!declared_saturation(ops, m, "f") && !declared_saturation(ops, m, "df"),
                                 "out_bits=%u dout_bits=%u t_frac=%u p_frac=%u k_frac=%u: the declaration "
                                 "saturates, the RTL (TIGHT) does not", nb, nd, wt, wp, wk);
                        checked++;
                    }
        }
    np_simplex_cfg d = np_simplex_cfg_default(16, 16, 1);
    size_t n = np_simplex_datapath(&d, ops, DP_MAX_OPS);
    for (unsigned k = 0; k < NS; k++)
        tight_at_default += declared_width(ops, n, sig[k]) == d.p_frac + extra[k];
    printf("%lu configurations with t_frac, p_frac >= 9: every M..A width within the RTL's, no saturation; "
           "%u of %u widths equal at the default; %lu (t_frac, p_frac) pairs need wider words\n",
           checked, (unsigned)tight_at_default, (unsigned)NS, beyond);
    NP_CHECK(beyond > 0, "no configuration needs the never-wrapping widths: TIGHT's threshold is not needed");
    NP_CHECK(tight_at_default == NS, "the default's declared widths are not the RTL's");
    return 0;
}
