/* SPDX-License-Identifier: MIT */
/*
 * test_hatch.c - the hatching unit (seed 003, docs/hatch.md): seed sets
 * (de Bruijn, cell proof, spacing), the bit-exact model against the float
 * reference, nesting, coverage lists, zoom and the stiff cases.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hatch_seeds.h"
#include "np_hatch.h"
#include "np_ref.h"
#include "np_rng.h"
#include "np_test.h"

/* --- seed sets --- */

static double round4(double v) { return floor(v * 1e4 + 0.5) / 1e4; }

/* FKM B(4,2): the design's pattern 0x0A5F / 0x23B3, s_0 = (0.041, 0.139), spacing 0.1154. */
static int t_seeds_fkm16(void)
{
    uint8_t d[NP_SEEDS_NMAX];
    np_seedset s;
    np_seeds_fkm(2, d);
    np_seeds_from_digits(2, d, &s);
    char txt[17];
    for (unsigned j = 0; j < 16; j++)
        txt[j] = (char)('0' + d[j]);
    txt[16] = '\0';
    printf("FKM B(4,2) %s b_u 0x%04llX b_v 0x%04llX\n", txt, (unsigned long long)s.bu, (unsigned long long)s.bv);
    NP_CHECK(strcmp(txt, "0010203112132233") == 0, "digits %s", txt);
    NP_CHECK(s.bu == 0x0A5Fu && s.bv == 0x23B3u, "patterns");
    NP_CHECK(np_seeds_is_debruijn(2, d), "de Bruijn");
    double u0 = np_seeds_coord(s.bu, 0, 16), v0 = np_seeds_coord(s.bv, 0, 16);
    printf("s_0 = (%.4f, %.4f)\n", u0, v0);
    NP_CHECK(fabs(u0 - 0.041) < 5e-4 && fabs(v0 - 0.139) < 6e-4, "s_0");
    NP_CHECK(np_seeds_cells(&s, NULL) == 0, "one seed per cell");
    double sp = np_seeds_spacing(&s, NULL, NULL, NULL);
    printf("FKM B(4,2) spacing %.4f\n", sp);
    NP_CHECK(round4(sp) == 0.1154, "spacing %.6f", sp);
    /* D s_i = frac(2 s_i) = s_{i+1}, exactly: rotl by one more bit. */
    for (unsigned i = 0; i < 16; i++) {
        uint64_t w = np_seed_rotl(s.bu, i, 16), w1 = np_seed_rotl(s.bu, (i + 1u) % 16u, 16);
        /* frac(2 W/(2^N-1)) = (2W mod (2^N-1)) / (2^N-1) */
        NP_CHECK((2u * w) % 0xFFFFu == w1, "D s_%u", i);
    }
    return 0;
}

static int t_seeds_fkm64(void)
{
    uint8_t d[NP_SEEDS_NMAX];
    np_seedset s;
    np_seeds_fkm(3, d);
    NP_CHECK(np_seeds_is_debruijn(3, d), "de Bruijn");
    np_seeds_from_digits(3, d, &s);
    NP_CHECK(np_seeds_cells(&s, NULL) == 0, "one seed per cell of 8x8");
    double sp = np_seeds_spacing(&s, NULL, NULL, NULL);
    printf("FKM B(4,3) b_u 0x%016llX b_v 0x%016llX spacing %.4f\n", (unsigned long long)s.bu,
           (unsigned long long)s.bv, sp);
    NP_CHECK(round4(sp) == 0.0291, "spacing %.6f", sp);
    np_seeds_fkm(1, d);
    NP_CHECK(np_seeds_is_debruijn(1, d) && d[0] == 0 && d[3] == 3, "B(4,1) = 0123");
    return 0;
}

typedef struct all_acc {
    double *sp;
    size_t n;
    uint64_t not_db, bad_cells;
} all_acc;

static int all_cb(const uint8_t *digits, void *user)
{
    all_acc *a = user;
    np_seedset s;
    if (!np_seeds_is_debruijn(2, digits))
        a->not_db++;
    np_seeds_from_digits(2, digits, &s);
    if (np_seeds_cells(&s, NULL))
        a->bad_cells++;
    if (a->n < 20736u)
        a->sp[a->n] = np_seeds_spacing(&s, NULL, NULL, NULL);
    a->n++;
    return 0;
}

static int cmp_d(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* Every B(4,2): 20,736 (= BEST), each one seed per cell; spacing 0.0138 / 0.0810 / 0.1668, 8 at the best. */
static int t_seeds_all16(void)
{
    static double sp[20736];
    all_acc a = { sp, 0, 0, 0 };
    uint64_t n = np_seeds_enumerate(2, all_cb, &a);
    printf("enumerated %llu, BEST theorem %.0f, not de Bruijn %llu, cell proof failed %llu\n", (unsigned long long)n,
           np_seeds_best_count(2), (unsigned long long)a.not_db, (unsigned long long)a.bad_cells);
    NP_CHECK(n == 20736u && np_seeds_best_count(2) == 20736.0, "count");
    NP_CHECK(a.not_db == 0 && a.bad_cells == 0, "every one de Bruijn with one seed per cell");
    if (n != 20736u)
        return 1;
    qsort(sp, 20736, sizeof(double), cmp_d);
    unsigned at_best = 0;
    for (unsigned k = 0; k < 20736u; k++)
        at_best += sp[k] > sp[20735] - 1e-12;
    printf("worst %.4f median %.4f (upper of %.6f, %.6f) best %.4f, %u at the best\n", sp[0], sp[10368], sp[10367],
           sp[10368], sp[20735], at_best);
    NP_CHECK(round4(sp[0]) == 0.0138, "worst");
    NP_CHECK(round4(sp[10368]) == 0.0810, "median");
    NP_CHECK(round4(sp[20735]) == 0.1668 && at_best == 8u, "best");
    return 0;
}

/* The shipped sets: de Bruijn, one seed per cell, spacing as recorded; best64 beats the design's 0.0573. */
static int t_seeds_shipped(void)
{
    for (unsigned k = 0; k < NP_HATCH_SETS; k++) {
        const np_hatch_set *ns = &np_hatch_sets[k];
        np_seedset ss = np_seeds_of(ns);
        uint8_t d[NP_SEEDS_NMAX];
        np_seeds_to_digits(&ss, d);
        double sp = np_seeds_spacing(&ss, NULL, NULL, NULL);
        printf("%-7s N=%2u spacing %.4f (recorded %.4f) %s\n", ns->name, ns->n, sp, ns->spacing, ns->origin);
        NP_CHECK(ns->n == np_seeds_n(ns->K), "%s N", ns->name);
        NP_CHECK(np_seeds_is_debruijn(ns->K, d), "%s de Bruijn", ns->name);
        NP_CHECK(np_seeds_cells(&ss, NULL) == 0, "%s cells", ns->name);
        NP_CHECK(round4(sp) == ns->spacing, "%s spacing %.6f", ns->name, sp);
        NP_CHECK(np_seeds_find(ns->name) == ns, "%s by name", ns->name);
    }
    NP_CHECK(np_seeds_find("best64")->spacing >= 0.0573, "best64 at least the design's search");
    NP_CHECK(np_seeds_find("best16")->spacing == 0.1668, "best16 is one of the 8 best");
    /* The cell proof can fail: a pattern that is not de Bruijn (all seeds in a few cells). */
    np_seedset bad = { 2, 16, 0x00FFu, 0x0F0Fu };
    unsigned cells[NP_SEEDS_NMAX];
    unsigned nbad = np_seeds_cells(&bad, cells);
    printf("a non-de Bruijn pattern: %u cells without exactly one seed\n", nbad);
    NP_CHECK(nbad > 0, "proof must fail");
    return 0;
}

/* Random circuits: always de Bruijn; the same seed gives the same sequence; B(4,3) reaches 0.0573 quickly. */
static int t_seeds_random(void)
{
    np_rng g, h;
    np_rng_seed(&g, 7);
    np_rng_seed(&h, 7);
    double best = 0.0;
    for (unsigned k = 0; k < 20000u; k++) {
        uint8_t d[NP_SEEDS_NMAX], e[NP_SEEDS_NMAX];
        np_seeds_random(3, &g, d);
        np_seeds_random(3, &h, e);
        NP_CHECK(memcmp(d, e, 64) == 0, "deterministic");
        NP_CHECK(np_seeds_is_debruijn(3, d), "circuit %u de Bruijn", k);
        np_seedset s;
        np_seeds_from_digits(3, d, &s);
        double sp = np_seeds_spacing(&s, NULL, NULL, NULL);
        best = sp > best ? sp : best;
        if (np_test_failures)
            return 1;
    }
    printf("20,000 random B(4,3) circuits: best spacing %.4f\n", best);
    NP_CHECK(best >= 0.0573, "best %.4f", best);
    /* K = 2: the walk reaches every one of the 20,736 sequences' spacings' range. */
    for (unsigned k = 0; k < 2000u; k++) {
        uint8_t d[NP_SEEDS_NMAX];
        np_seeds_random(2, &g, d);
        NP_CHECK(np_seeds_is_debruijn(2, d), "B(4,2) circuit %u", k);
    }
    return 0;
}


/* --- the bit-exact model against the float reference --- */

/* A configuration from a shipped set: the PIN layers, default stroke sizes (hatch_cfg_from_set). */
static np_hatch_cfg cfg_of(const char *set, unsigned fade, unsigned guard)
{
    np_hatch_cfg c;
    memset(&c, 0, sizeof c);
    const np_hatch_set *ns = np_seeds_find(set);
    c.set = (unsigned)(ns - np_hatch_sets);
    c.rot = NP_HATCH_ROT_PIN;
    c.layers = 4;
    c.fade = fade;
    c.guard = guard;
    c.lanes = 1;
    /* Stroke length 4 / sqrt N and width 0.48 / sqrt N of a seed tile at m = 0 (Q8.8 inverses). */
    c.inv_u = ns->n == 64u ? 2048u : 1024u;
    c.inv_v = ns->n == 64u ? 17067u : 8533u;
    return c;
}

/* A random point: x anywhere mod 2, tone, and a level fraction m with the host's 2^-m and 1 - m. */
typedef struct pt {
    uint64_t xu, xv;
    uint32_t tone, pm, om;
} pt;

static void m_words(uint32_t m16, uint32_t *pm, uint32_t *om)
{
    *om = 65536u - m16;
    *pm = (uint32_t)floor(65536.0 * exp2(-(double)m16 / 65536.0) + 0.5);
}

static pt rand_pt(np_rng *g)
{
    pt p;
    p.xu = np_rng_next(g) & NP_MASK(33);
    p.xv = np_rng_next(g) & NP_MASK(33);
    p.tone = (uint32_t)np_rng_below(g, 256);
    m_words((uint32_t)np_rng_below(g, 65536), &p.pm, &p.om);
    return p;
}

/* Max |model - reference| in output LSB over n random points of cfg; the worst input printed. */
static double max_err(const np_hatch_cfg *c, np_rng *g, unsigned n, pt *worst)
{
    double e = 0;
    for (unsigned k = 0; k < n; k++) {
        pt p = rand_pt(g);
        double ref = np_ref_hatch(c, p.xu, p.xv, p.tone, p.pm, p.om, NULL);
        uint32_t out = np_hatch_eval(c, p.xu, p.xv, p.tone, p.pm, p.om, NULL);
        double d = fabs((double)out - ref);
        if (d > e) {
            e = d;
            if (worst)
                *worst = p;
        }
    }
    return e;
}

/* A = round(tone 2^30 / 255) for every tone: within 2^-31 of tone / 255; 0 and 255 exact. */
static int t_tone_exact(void)
{
    np_hatch_cfg c = cfg_of("best16", 0, 9);
    double worst = 0;
    for (uint32_t t = 0; t < 256u; t++) {
        np_hatch_sig s;
        np_hatch_eval(&c, 0, 0, t, 65536, 65536, &s);
        double e = fabs((double)s.A / 1073741824.0 - t / 255.0);
        worst = e > worst ? e : worst;
        NP_CHECK(e <= ldexp(1.0, -31), "tone %u", t);
        for (unsigned l = 0; l < 4; l++) {
            double al = 4.0 * s.A - (double)l * 1073741824.0;
            al = al < 0 ? 0 : (al > 1073741824.0 ? 1073741824.0 : al);
            NP_CHECK(s.al[l] == (uint32_t)al, "layer tone %u", l);
        }
    }
    printf("|A - tone/255| <= %.3g (bound 2^-31 = %.3g)\n", worst, ldexp(1.0, -31));
    np_hatch_sig s0, s1;
    np_hatch_eval(&c, 0, 0, 255, 65536, 65536, &s1);
    np_hatch_eval(&c, 0, 0, 0, 65536, 65536, &s0);
    NP_CHECK(s1.A == 1u << 30 && s0.A == 0, "tone 0 and 1 exact");
    return 0;
}

/* Every seed's alpha against the reference's: the error budget of the bound (da). */
static int t_alpha_error(void)
{
    static const char *const sets[] = { "best16", "best64" };
    np_rng g;
    np_rng_seed(&g, 11);
    for (unsigned si = 0; si < 2; si++)
        for (unsigned fade = 0; fade < 2; fade++) {
            np_hatch_cfg c = cfg_of(sets[si], fade, 9);
            double worst = 0, ra[256];
            unsigned nz = 0;
            for (unsigned k = 0; k < 20000u; k++) {
                pt p = rand_pt(&g);
                np_ref_hatch(&c, p.xu, p.xv, p.tone, p.pm, p.om, ra);
                np_hatch_sig s;
                memset(&s, 0, sizeof s);
                s.xu = p.xu;
                s.xv = p.xv;
                s.tone = p.tone;
                s.pm = p.pm;
                s.om = p.om;
                np_hatch_setup(&c, &s);
                for (unsigned l = 0; l < c.layers; l++)
                    for (unsigned i = 0; i < np_hatch_n(&c); i++) {
                        np_hatch_seed_sig z;
                        np_hatch_seed(&c, &s, l, i, &z);
                        double e = fabs(z.alpha / 1073741824.0 - ra[l * np_hatch_n(&c) + i]);
                        worst = e > worst ? e : worst;
                        nz += z.alpha != 0;
                    }
            }
            printf("%s fade=%u: max |alpha - alpha_ref| = %.3g (2^%.2f) over %u nonzero alphas\n", sets[si], fade,
                   worst, log2(worst), nz);
            double bound = np_hatch_alpha_bound(&c, 65536u);
            printf("  bound da = %.3g (2^%.2f)\n", bound, log2(bound));
            NP_CHECK(worst <= bound, "alpha error %.3g over the bound %.3g", worst, bound);
        }
    return 0;
}

/* The unit within 1 LSB of the reference on random points, both sets and both fadings. */
static int t_model_vs_ref(void)
{
    static const char *const sets[] = { "fkm16", "best16", "fkm64", "best64" };
    np_rng g;
    np_rng_seed(&g, 3);
    for (unsigned si = 0; si < 4; si++)
        for (unsigned fade = 0; fade < 2; fade++) {
            np_hatch_cfg c = cfg_of(sets[si], fade, 9);
            pt w = { 0, 0, 0, 0, 0 };
            double e = max_err(&c, &g, 20000u, &w);
            printf("%-6s fade=%u guard=9: max |out - ref| = %.4f LSB over 20,000 points (worst xu=%09llx xv=%09llx tone=%u pm=%05x om=%05x)\n",
                   sets[si], fade, e, (unsigned long long)w.xu, (unsigned long long)w.xv, w.tone, w.pm, w.om);
            NP_CHECK(e <= 1.0, "%s fade %u: %.4f LSB", sets[si], fade, e);
        }
    return 0;
}

/*
 * 256 serial blends (64 seeds x 4 layers, every stroke covering the point):
 * the colour register's guard bits. Strokes as large as the tile (1/(F e) =
 * 1/2: |Q| <= 0.71 everywhere), the layer tones set at the seed stages' input
 * (any al in [0, 1] is legal there) to small random values so c stays near
 * 1/2 after 256 blends. Against the exact product of the model's own alphas
 * (long double), so only the blend roundings count: the floor loses < 1 ulp
 * per blend, |out - 255 c| < 1/2 + 255 * 256 * 2^-F, <= 1 for F >= 17: 9 guard
 * bits over the 8-bit output. The search shows 9 holds and 8 fails.
 */
static double blend256(unsigned guard, np_rng *g, unsigned trials, unsigned *fails, double *worst_c)
{
    np_hatch_cfg c = cfg_of("best64", 0, guard);
    c.inv_u = c.inv_v = 128;
    double worst = 0;
    *fails = 0;
    for (unsigned k = 0; k < trials; k++) {
        np_hatch_sig s;
        memset(&s, 0, sizeof s);
        s.xu = np_rng_next(g) & NP_MASK(33);
        s.xv = np_rng_next(g) & NP_MASK(33);
        s.pm = 65536;
        s.om = 65536;
        np_hatch_setup(&c, &s);
        for (unsigned l = 0; l < 4; l++)
            s.al[l] = (uint32_t)np_rng_below(g, 1u << 22); /* < 2^-8 */
        long double ce = 1.0L;
        for (unsigned l = 0; l < 4; l++)
            for (unsigned i = 0; i < 64; i++) {
                np_hatch_seed_sig z;
                np_hatch_seed(&c, &s, l, i, &z);
                NP_CHECK(z.alpha != 0, "stroke %u/%u covers the point", l, i);
                ce *= 1.0L - (long double)z.alpha / 1073741824.0L;
            }
        np_hatch_output(&c, &s);
        double e = fabs((double)s.out - (double)(255.0L * ce));
        if (e > 1.0)
            ++*fails;
        if (e > worst) {
            worst = e;
            *worst_c = (double)ce;
        }
    }
    return worst;
}

static int t_guard_bits(void)
{
    unsigned fails[12], first_ok = 99;
    double worst[12], wc = 0;
    for (unsigned guard = 4; guard < 12; guard++) {
        np_rng g;
        np_rng_seed(&g, 99); /* the same 4,000 points for every width */
        worst[guard] = blend256(guard, &g, 4000u, &fails[guard], &wc);
        printf("guard %2u (F = %2u): max |out - exact| = %.4f LSB over 4,000 x 256 blends, %u over 1 LSB (bound %.4f)\n",
               guard, 8 + guard, worst[guard], fails[guard], 0.5 + 255.0 * 256.0 * ldexp(1.0, -(int)(8 + guard)));
        if (fails[guard] == 0 && first_ok == 99)
            first_ok = guard;
    }
    printf("fewest guard bits within 1 LSB: %u (proof: 9)\n", first_ok);
    NP_CHECK(first_ok == 9u, "fewest guard bits %u", first_ok);
    NP_CHECK(fails[8] > 0, "8 guard bits must fail");
    for (unsigned guard = 9; guard < 12; guard++)
        NP_CHECK(fails[guard] == 0, "guard %u", guard);
    return 0;
}

/*
 * Nesting (§5.3), exhaustive for every shipped set and layer pattern: for
 * every seed i and every dense tile w in {0,1}^2 (x_s mod 2: one sparse tile),
 * the dense instance s_i + w coincides with a sparse seed 2 s_j (mod 2) iff
 * the model's survival bit is set, at the instance and at random points of
 * its cell; and each dense tile keeps exactly N/4 survivors. All in integers
 * (units of 1/(2^N - 1)). The unit sees the level only through x_s mod 2, so
 * this holds at every level (np_hatch_xs: test zoom_identical).
 */
static int t_nesting(void)
{
    np_rng g;
    np_rng_seed(&g, 5);
    unsigned checked = 0;
    for (unsigned k = 0; k < NP_HATCH_SETS; k++) {
        const np_hatch_set *ns = &np_hatch_sets[k];
        np_hatch_cfg c = cfg_of(ns->name, 0, 9);
        unsigned n = np_hatch_n(&c);
        np_u128 D = n == 64 ? (np_u128)~(uint64_t)0 : (((np_u128)1 << n) - 1u);
        for (unsigned l = 0; l < 4; l++) {
            unsigned per_tile[4] = { 0, 0, 0, 0 };
            uint64_t lbu, lbv;
            np_hatch_layer_b(&c, l, &lbu, &lbv);
            for (unsigned i = 0; i < n; i++) {
                uint64_t wu = np_seed_rotl(lbu, i, n), wv = np_seed_rotl(lbv, i, n);
                for (unsigned w = 0; w < 4; w++) {
                    unsigned wx = w & 1u, wy = w >> 1;
                    np_u128 pu = (np_u128)wu + wx * D, pv = (np_u128)wv + wy * D; /* s_i + w, over D */
                    int coincide = 0;
                    for (unsigned j = 0; j < n && !coincide; j++) {
                        np_u128 su = 2 * (np_u128)np_seed_rotl(lbu, j, n) % (2 * D);
                        np_u128 sv = 2 * (np_u128)np_seed_rotl(lbv, j, n) % (2 * D);
                        coincide = su == pu && sv == pv;
                    }
                    /* Points of the instance's cell: floor(x - s_i + 1/2) = w; the instance itself first. */
                    for (unsigned t = 0; t < 9; t++) {
                        double du = t ? (double)np_rng_below(&g, 1000) / 1000.0 - 0.4995 : 0.0;
                        double dv = t ? (double)np_rng_below(&g, 1000) / 1000.0 - 0.4995 : 0.0;
                        uint64_t xu = ((uint64_t)((pu << 32) / D) + (uint64_t)(int64_t)(du * 4294967296.0)) & NP_MASK(33);
                        uint64_t xv = ((uint64_t)((pv << 32) / D) + (uint64_t)(int64_t)(dv * 4294967296.0)) & NP_MASK(33);
                        np_hatch_sig s;
                        memset(&s, 0, sizeof s);
                        s.xu = xu;
                        s.xv = xv;
                        s.pm = s.om = 65536;
                        np_hatch_setup(&c, &s);
                        np_hatch_seed_sig z;
                        np_hatch_seed(&c, &s, l, i, &z);
                        NP_CHECK(((z.du >> 32) & 1u) == wx && ((z.dv >> 32) & 1u) == wy, "%s l%u i%u w%u: tile", ns->name, l, i, w);
                        NP_CHECK((int)z.surv == coincide, "%s l%u i%u w%u: survival %u, coincidence %d", ns->name, l, i,
                                 w, z.surv, coincide);
                        checked++;
                    }
                    per_tile[w] += (unsigned)coincide;
                }
            }
            for (unsigned w = 0; w < 4; w++)
                NP_CHECK(per_tile[w] == n / 4u, "%s layer %u tile %u: %u survivors", ns->name, l, w, per_tile[w]);
        }
        printf("%s: survival iff coincidence for every seed, tile and layer; N/4 = %u survivors per tile\n", ns->name,
               n / 4u);
        if (np_test_failures)
            return 1;
    }
    printf("%u points checked\n", checked);
    return 0;
}

/* Pinned outputs (testbench/hatch_kat.inc; conformance.hatch.kat regenerates it): any change to a bit shows here. */
static int t_kat(void)
{
    static const struct {
        uint64_t xu, xv;
        uint32_t tone, pm, om;
        unsigned c0, c1, c2, c3;
    } k[] = {
#include "hatch_kat.inc"
    };
    np_hatch_cfg cf[4] = { cfg_of("best16", 0, 9), cfg_of("best64", 0, 9), cfg_of("fkm16", 1, 9), cfg_of("fkm64", 0, 9) };
    cf[3].layers = 1;
    cf[3].rot = NP_HATCH_ROT_90;
    unsigned n = sizeof k / sizeof k[0];
    for (unsigned i = 0; i < n; i++)
        for (unsigned j = 0; j < 4; j++) {
            const unsigned want[4] = { k[i].c0, k[i].c1, k[i].c2, k[i].c3 };
            uint32_t c = np_hatch_eval(&cf[j], k[i].xu, k[i].xv, k[i].tone, k[i].pm, k[i].om, NULL);
            NP_CHECK(c == want[j], "row %u config %u: %u, want %u", i, j, c, want[j]);
            double ref = np_ref_hatch(&cf[j], k[i].xu, k[i].xv, k[i].tone, k[i].pm, k[i].om, NULL);
            NP_CHECK(fabs(c - ref) <= 1.0, "row %u config %u: ref %.4f", i, j, ref);
        }
    printf("%u rows x 4 configurations pinned\n", n);
    return 0;
}

/* --- coverage lists (§6.1) --- */

/* n random points with m in [0, 1) (2^-m >= 1/2): the coverage unit's outputs equal brute force's, bit for bit. */
static unsigned cover_check(const np_hatch_cfg *c, unsigned n, uint64_t seed, const char *what)
{
    np_hatch_cover cv;
    int rc = np_hatch_cover_build(c, &cv);
    NP_CHECK(rc == 0, "%s: a list over %d entries", what, NP_HATCH_COVER_MAX);
    if (rc != 0) {
        np_hatch_cover_free(&cv);
        return 1;
    }
    np_rng g;
    np_rng_seed(&g, seed);
    unsigned bad = 0, nz_max = 0;
    for (unsigned k = 0; k < n; k++) {
        pt p = rand_pt(&g);
        np_hatch_sig s;
        uint32_t b = np_hatch_eval(c, p.xu, p.xv, p.tone, p.pm, p.om, &s);
        uint32_t v = np_hatch_eval_cover(c, &cv, p.xu, p.xv, p.tone, p.pm, p.om, NULL);
        nz_max = s.nz > nz_max ? s.nz : nz_max;
        if (b != v && ++bad <= 5)
            fprintf(stderr, "%s: xu=%09llx xv=%09llx tone=%u pm=%05x om=%05x => coverage %u brute force %u\n", what,
                    (unsigned long long)p.xu, (unsigned long long)p.xv, p.tone, p.pm, p.om, v, b);
    }
    printf("%s: %u points, coverage = brute force on %u; lists %u x %u texels, mean %.3f, max %u entries; at most %u nonzero alphas at a point\n",
           what, n, n - bad, cv.t, cv.t, cv.mean_len, cv.max_len, nz_max);
    NP_CHECK(bad == 0, "%s: %u differ", what, bad);
    np_hatch_cover_free(&cv);
    return bad;
}

static int t_cover_identical16(void)
{
    np_hatch_cfg c = cfg_of("best16", 0, 9);
    cover_check(&c, 1000000u, 21, "best16 4 x 16");
    return 0;
}

static int t_cover_identical64(void)
{
    np_hatch_cfg c = cfg_of("best64", 0, 9);
    cover_check(&c, 1000000u, 22, "best64 4 x 64");
    return 0;
}

/* Every layer at 0, 45, 90 degrees and 1e-4 rad (R = [[16384, 2], [-2, 16384]]): the lists stay conservative. */
static int t_cover_rotations(void)
{
    static const unsigned rots[] = { NP_HATCH_ROT_0, NP_HATCH_ROT_45, NP_HATCH_ROT_90, NP_HATCH_ROT_1E4 };
    static const char *const names[] = { "0 deg", "45 deg", "90 deg", "1e-4 rad" };
    for (unsigned k = 0; k < 4; k++)
        for (unsigned si = 0; si < 2; si++) {
            np_hatch_cfg c = cfg_of(si ? "best64" : "best16", si, 9);
            c.rot = rots[k];
            char what[64];
            snprintf(what, sizeof what, "%s %s fade=%u", si ? "best64" : "best16", names[k], si);
            cover_check(&c, 100000u, 30u + k, what);
        }
    return 0;
}

/*
 * Cycles per point for brute force (B: layers N / P) and coverage lists
 * (C: sum over layers of ceil(len / P), at least 1; the mean over seed space
 * is the mean over texels) beside the paper's Table 1 (GeForce 780, 1920 x
 * 1200, ms per frame), and the units x clock an iterative unit needs to
 * draw C64 in 1.81 ms.
 */
static double mean_cycles(const np_hatch_cfg *c, const np_hatch_cover *cv, unsigned *maxc)
{
    double sum = 0;
    *maxc = 0;
    for (unsigned tv = 0; tv < cv->t; tv++)
        for (unsigned tu = 0; tu < cv->t; tu++) {
            unsigned cyc = 0;
            for (unsigned l = 0; l < c->layers; l++) {
                unsigned len = cv->len[((size_t)l * cv->t + tv) * cv->t + tu];
                cyc += (len + c->lanes - 1u) / c->lanes;
            }
            cyc = cyc ? cyc : 1u;
            *maxc = cyc > *maxc ? cyc : *maxc;
            sum += cyc;
        }
    return sum / ((double)cv->t * cv->t);
}

static int t_cover_table1(void)
{
    static const double paper_b[2] = { 4.80, 16.6 }, paper_c[2] = { 1.66, 1.81 };
    const double pixels = 1920.0 * 1200.0;
    printf("| set | B cycles/point | C cycles/point mean (max) | list mean (max) | B/C ours | paper B, C ms | paper B/C |\n");
    double c64 = 0;
    for (unsigned si = 0; si < 2; si++) {
        np_hatch_cfg c = cfg_of(si ? "best64" : "best16", 0, 9);
        np_hatch_cover cv;
        NP_CHECK(np_hatch_cover_build(&c, &cv) == 0, "lists");
        unsigned maxc;
        double b = (double)(c.layers * np_hatch_n(&c)), mc = mean_cycles(&c, &cv, &maxc);
        printf("| %s | %.0f | %.2f (%u) | %.3f (%u) | %.2fx | %.2f, %.2f | %.2fx |\n", si ? "4 x 64" : "4 x 16", b, mc,
               maxc, cv.mean_len, cv.max_len, b / mc, paper_b[si], paper_c[si], paper_b[si] / paper_c[si]);
        NP_CHECK(mc < b && cv.max_len <= NP_HATCH_COVER_MAX, "coverage cheaper");
        if (si)
            c64 = mc;
        np_hatch_cover_free(&cv);
    }
    /* C64 at 1.81 ms: pixels x mean cycles / (units x clock) = 1.81e-3 s. */
    double rate = pixels * c64 / 1.81e-3;
    printf("C64 in 1.81 ms at 1920x1200: %.3g point-cycles/s, e.g. %.1f units at 1 GHz or %.0f units at 500 MHz (P = 1)\n",
           rate, rate / 1e9, rate / 5e8 + 0.5);
    for (unsigned p = 2; p <= 16; p *= 2) {
        np_hatch_cfg c = cfg_of("best64", 0, 9);
        c.lanes = p;
        np_hatch_cover cv;
        np_hatch_cover_build(&c, &cv);
        unsigned maxc;
        double mc = mean_cycles(&c, &cv, &maxc);
        printf("  P = %2u lanes: B64 %u, C64 %.2f (max %u) cycles/point\n", p, c.layers * 64u / p, mc, maxc);
        np_hatch_cover_free(&cv);
    }
    return 0;
}

/* --- zoom and the stiff cases --- */

/*
 * A UV point in [0, 2) whose bits from the units bit down to 2^-96 repeat a
 * 20-bit pattern (truncated): 2^z P mod 2 has the same 33 bits at the binary
 * point as P for z = 20, 40, 60.
 */
static np_u128 periodic_uv(uint32_t pattern20)
{
    np_u128 v = 0;
    for (unsigned k = 0; k <= 96u; k++) /* k: the bit of weight 2^-k */
        if ((pattern20 >> (19u - k % 20u)) & 1u)
            v |= (np_u128)1 << (96u - k);
    return v;
}

/*
 * Zoom in by 2^z toward a point P of UV: the window's pixels are
 * P + i 2^-12 2^-z and the level floor(M) drops by z. The host's x_s
 * (np_hatch_xs, 128-bit) is then the same word for every z (P chosen with a
 * 20-bit period), so the image is bit-identical at 2^0, 2^20, 2^40, 2^60.
 * A double x_uv (what a float pipeline holds) keeps 53 bits of P: the
 * seed-space position is wrong from some zoom on, and the image breaks.
 */
static int t_zoom_identical(void)
{
    np_hatch_cfg c = cfg_of("best64", 0, 9);
    enum { W = 64 };
    static uint8_t img[4][W * W];
    np_u128 pu = periodic_uv(0xB7E15u), pv = periodic_uv(0x4C3A9u);
    np_u128 dx = (np_u128)1 << (96 - 8); /* 2^-8 UV per pixel at zoom 2^0: the window is a quarter tile */
    static const unsigned zooms[4] = { 0, 20, 40, 60 };
    unsigned double_bad[4] = { 0, 0, 0, 0 };
    /* P as a double: its top 53 bits (P < 2: bits 2^0 .. 2^-52). */
    double pud = ldexp((double)(uint64_t)(pu >> 44), -52), pvd = ldexp((double)(uint64_t)(pv >> 44), -52);
    for (unsigned zi = 0; zi < 4; zi++) {
        unsigned z = zooms[zi];
        int level = -(int)z;
        for (unsigned j = 0; j < W; j++)
            for (unsigned i = 0; i < W; i++) {
                np_u128 xu = pu + (np_u128)i * (dx >> z), xv = pv + (np_u128)j * (dx >> z);
                uint64_t su = np_hatch_xs(xu, level), sv = np_hatch_xs(xv, level);
                img[zi][j * W + i] = (uint8_t)np_hatch_eval(&c, su, sv, 120, 0xB505, 0x8000, NULL);
                /* The double pipeline: x_uv in double, x_s = 2^-level x_uv mod 2, truncated to Q1.32. */
                double xd = pud + (double)i * ldexp(1.0, -8 - (int)z), yd = pvd + (double)j * ldexp(1.0, -8 - (int)z);
                uint64_t du = (uint64_t)(fmod(ldexp(xd, (int)z), 2.0) * 4294967296.0) & NP_MASK(33);
                uint64_t dv = (uint64_t)(fmod(ldexp(yd, (int)z), 2.0) * 4294967296.0) & NP_MASK(33);
                double_bad[zi] += du != su || dv != sv;
            }
        unsigned diff = 0;
        for (unsigned k = 0; k < W * W; k++)
            diff += img[zi][k] != img[0][k];
        printf("zoom 2^%-2u (floor(M) = %3d): %u of %u pixels differ from zoom 2^0; a double x_uv gets x_s wrong at %u\n",
               z, level, diff, W * W, double_bad[zi]);
        NP_CHECK(diff == 0, "zoom 2^%u: %u pixels differ", z, diff);
    }
    NP_CHECK(double_bad[0] == 0 && double_bad[3] > W * W / 2, "the double path breaks only at deep zoom");
    unsigned ink = 0;
    for (unsigned k = 0; k < W * W; k++)
        ink += img[0][k] < 255;
    printf("%u of %u pixels carry ink\n", ink, W * W);
    NP_CHECK(ink > 0 && ink < W * W, "a window with strokes and paper");
    return 0;
}

/* Deep zoom: floor(M) = -60 and -64 (the host's limit); x_s is the exact truncation of 2^60 x_uv mod 2. */
static int t_stiff_deep_zoom(void)
{
    np_rng g;
    np_rng_seed(&g, 60);
    for (unsigned k = 0; k < 100000u; k++) {
        np_u128 x = ((np_u128)np_rng_next(&g) << 64) | np_rng_next(&g);
        for (int level = -64; level <= 31; level += 19) {
            /* The exact value: floor(x 2^-96 2^-level 2^32) mod 2^33 = bits [64 + level, 97 + level) of x. */
            uint64_t want = 0;
            for (unsigned b = 0; b < 33u; b++) {
                unsigned src = (unsigned)(64 + level) + b;
                if (src < 128u && ((x >> src) & 1u))
                    want |= (uint64_t)1 << b;
            }
            NP_CHECK(np_hatch_xs(x, level) == want, "level %d", level);
        }
        if (np_test_failures)
            return 1;
    }
    printf("x_s at floor(M) = -64 .. 31: the 33 bits of 2^-floor(M) x_uv at the binary point, 100,000 x_uv each\n");
    return 0;
}

/*
 * The level seam: zooming out, level L at m = 1 - 2^-16 (strokes twice their
 * size, the strokes that do not survive at alpha 2^-16) meets level L + 1 at
 * m = 0. The same UV points: within 1 LSB of each other.
 */
static int t_stiff_level_seam(void)
{
    np_rng g;
    np_rng_seed(&g, 77);
    unsigned same = 0, n = 20000, worst = 0;
    for (unsigned si = 0; si < 2; si++) {
        np_hatch_cfg c = cfg_of(si ? "best64" : "best16", 0, 9);
        for (unsigned k = 0; k < n; k++) {
            np_u128 x = ((np_u128)np_rng_next(&g) << 64) | np_rng_next(&g);
            np_u128 y = ((np_u128)np_rng_next(&g) << 64) | np_rng_next(&g);
            uint32_t tone = (uint32_t)np_rng_below(&g, 256);
            uint32_t pm, om;
            m_words(65535u, &pm, &om);
            uint32_t a = np_hatch_eval(&c, np_hatch_xs(x, 0), np_hatch_xs(y, 0), tone, pm, om, NULL);
            uint32_t b = np_hatch_eval(&c, np_hatch_xs(x, 1), np_hatch_xs(y, 1), tone, 0x10000, 0x10000, NULL);
            unsigned d = a > b ? a - b : b - a;
            worst = d > worst ? d : worst;
            same += a == b;
        }
    }
    printf("level seam (m = 1 - 2^-16 at L vs m = 0 at L + 1): max difference %u LSB, %u of %u identical\n", worst, same,
           2 * n);
    NP_CHECK(worst <= 1u, "seam %u LSB", worst);
    return 0;
}

/*
 * 256 serial blends (64 seeds x 4 layers). Through the seed stages with
 * small layer tones (blend256: c stays near 1/2, so every blend's rounding
 * counts): at the default 9 guard bits no output is over 1 LSB from the exact
 * product of the alphas. Through the whole unit with strokes as large as the
 * tile and every layer on: all 256 alphas nonzero, within 1 LSB of the
 * reference (there c goes to black: the PIN tone ranges put layers 0-2 at
 * full tone before layer 3 starts).
 */
static int t_stiff_256_blends(void)
{
    np_rng g;
    np_rng_seed(&g, 2560);
    unsigned fails;
    double wc = 0, w = blend256(9, &g, 10000u, &fails, &wc);
    printf("seed stages, guard 9: max |out - exact| %.4f LSB over 10,000 x 256 blends (c = %.3f there), %u over 1 LSB\n",
           w, wc, fails);
    NP_CHECK(fails == 0 && w <= 0.5 + 255.0 * 256.0 * ldexp(1.0, -17), "within the bound");
    np_hatch_cfg c = cfg_of("best64", 0, 9);
    c.inv_u = c.inv_v = 128;
    double worst = 0;
    unsigned all = 0;
    for (unsigned k = 0; k < 4000u; k++) {
        pt p = rand_pt(&g);
        p.tone = 193u + (uint32_t)np_rng_below(&g, 63); /* every layer on */
        np_hatch_sig s;
        uint32_t out = np_hatch_eval(&c, p.xu, p.xv, p.tone, p.pm, p.om, &s);
        double ref = np_ref_hatch(&c, p.xu, p.xv, p.tone, p.pm, p.om, NULL);
        worst = fabs(out - ref) > worst ? fabs(out - ref) : worst;
        all += s.nz == 256u;
    }
    printf("whole unit: max |out - ref| %.4f LSB over 4,000 points, all 256 alphas nonzero at %u\n", worst, all);
    NP_CHECK(worst <= 1.0 && all == 4000u, "256 blends");
    return 0;
}

/*
 * A seed at a tile corner: FKM 16-seed set (b_u = 0x0A5F, b_v = 0x23B3),
 * s_0 = (0.041, 0.139). Its stroke crosses x_u = 0, where x_s wraps mod 2:
 * the alpha at s_0 - t and s_0 + t along u (one layer at 0 degrees, so the
 * profile is even) agree to the datapath's rounding, and every point of a
 * grid around the corner is within 1 LSB of the reference.
 */
static int t_stiff_tile_corner(void)
{
    np_hatch_cfg c = cfg_of("fkm16", 0, 9);
    c.layers = 1;
    c.rot = NP_HATCH_ROT_0;
    uint64_t su = np_hatch_seed_st(0x0A5F, 16) + 1u, sv = np_hatch_seed_st(0x23B3, 16) + 1u; /* ceil of s_0 */
    printf("s_0 = (%.4f, %.4f)\n", (double)(uint32_t)su / 4294967296.0, (double)(uint32_t)sv / 4294967296.0);
    double worst_sym = 0;
    for (unsigned k = 1; k < 400u; k++) {
        uint64_t t = (uint64_t)k << 21; /* up to 0.195 of a tile: across x_u = 0 */
        np_hatch_seed_sig za, zb;
        np_hatch_sig s;
        memset(&s, 0, sizeof s);
        s.tone = 255;
        s.pm = s.om = 65536;
        s.xu = (su - t) & NP_MASK(33);
        s.xv = sv;
        np_hatch_setup(&c, &s);
        np_hatch_seed(&c, &s, 0, 0, &za);
        memset(&s, 0, sizeof s);
        s.tone = 255;
        s.pm = s.om = 65536;
        s.xu = (su + t) & NP_MASK(33);
        s.xv = sv;
        np_hatch_setup(&c, &s);
        np_hatch_seed(&c, &s, 0, 0, &zb);
        double d = fabs((double)za.alpha - (double)zb.alpha) / 1073741824.0;
        worst_sym = d > worst_sym ? d : worst_sym;
        NP_CHECK(za.surv == zb.surv, "same instance on both sides of x_u = 0");
    }
    printf("alpha(s_0 - t) vs alpha(s_0 + t) across x_u = 0: max difference %.3g\n", worst_sym);
    NP_CHECK(worst_sym <= np_hatch_alpha_bound(&c, 65536u), "symmetry");
    double worst = 0;
    for (int j = -20; j <= 20; j++)
        for (int i = -20; i <= 20; i++) {
            uint64_t xu = (uint64_t)((int64_t)su + (int64_t)i * (1 << 22)) & NP_MASK(33);
            uint64_t xv = (uint64_t)((int64_t)sv + (int64_t)j * (1 << 22)) & NP_MASK(33);
            uint32_t out = np_hatch_eval(&c, xu, xv, 255, 0xB505, 0x8000, NULL);
            double ref = np_ref_hatch(&c, xu, xv, 255, 0xB505, 0x8000, NULL);
            worst = fabs(out - ref) > worst ? fabs(out - ref) : worst;
        }
    printf("41 x 41 points around the corner seed: max |out - ref| %.4f LSB\n", worst);
    NP_CHECK(worst <= 1.0, "corner");
    return 0;
}

/* frac(x_s - s_i + eta) = 1/2 exactly in the datapath (r = 0, the seed itself): Q = 0, profile 1, alpha = tone part. */
static int t_stiff_frac_half(void)
{
    for (unsigned si = 0; si < NP_HATCH_SETS; si++) {
        np_hatch_cfg c = cfg_of(np_hatch_sets[si].name, 0, 9);
        uint64_t bu, bv;
        np_hatch_layer_b(&c, 0, &bu, &bv);
        unsigned n = np_hatch_n(&c);
        for (unsigned i = 0; i < n; i++) {
            uint64_t stu = np_hatch_seed_st(np_seed_rotl(bu, i, n), n), stv = np_hatch_seed_st(np_seed_rotl(bv, i, n), n);
            np_hatch_sig s;
            memset(&s, 0, sizeof s);
            s.xu = (stu + 1u) & NP_MASK(33);
            s.xv = (stv + 1u) & NP_MASK(33);
            s.tone = 255;
            s.pm = s.om = 65536;
            np_hatch_setup(&c, &s);
            np_hatch_seed_sig z;
            np_hatch_seed(&c, &s, 0, i, &z);
            NP_CHECK((z.du & NP_MASK(32)) == 0x80000000u && z.ru == 0 && z.Qu == 0 && z.Qv == 0, "%s seed %u: r = 0",
                     np_hatch_sets[si].name, i);
            NP_CHECK(z.profile == 1u << 30 && z.alpha == 1u << 30, "%s seed %u: alpha 1", np_hatch_sets[si].name, i);
            NP_CHECK(s.c == 0, "black");
        }
    }
    printf("every seed of every set: frac = 1/2 exactly, r = 0, Q = 0, profile = alpha = 1, c = 0\n");
    return 0;
}

/* Tone 0: white whatever the point and level (exact); tone 1: within 1 LSB of the reference, black at the seeds. */
static int t_stiff_tone_0_1(void)
{
    np_rng g;
    np_rng_seed(&g, 1);
    double worst = 0;
    for (unsigned si = 0; si < NP_HATCH_SETS; si++) {
        np_hatch_cfg c = cfg_of(np_hatch_sets[si].name, si & 1u, 9);
        for (unsigned k = 0; k < 5000u; k++) {
            pt p = rand_pt(&g);
            NP_CHECK(np_hatch_eval(&c, p.xu, p.xv, 0, p.pm, p.om, NULL) == 255u, "tone 0 is paper");
            uint32_t out = np_hatch_eval(&c, p.xu, p.xv, 255, p.pm, p.om, NULL);
            double ref = np_ref_hatch(&c, p.xu, p.xv, 255, p.pm, p.om, NULL);
            worst = fabs(out - ref) > worst ? fabs(out - ref) : worst;
        }
    }
    printf("tone 0: 255 at 20,000 points; tone 1: max |out - ref| %.4f LSB\n", worst);
    NP_CHECK(worst <= 1.0, "tone 1");
    return 0;
}

/*
 * A 64-frame zoom across 8 levels (M = 8 - f/8): every stroke centre of the
 * coarsest level, 2^8 (s_i + w), stays a stroke centre at every finer level
 * (seed i + 8 - floor(M) there, r = 0 at the same UV point: fixed in UV), and
 * its level alpha never drops while zooming in (counted).
 */
static int t_zoom_sequence(void)
{
    np_hatch_cfg c = cfg_of("best16", 0, 9);
    unsigned n = np_hatch_n(&c);
    uint64_t bu, bv;
    np_hatch_layer_b(&c, 0, &bu, &bv);
    np_u128 D = ((np_u128)1 << n) - 1u;
    unsigned strokes = 0, drops = 0, moved = 0;
    for (unsigned i = 0; i < n; i++)
        for (unsigned w = 0; w < 4; w++) {
            /* The centre in UV, Q32.96, rounded down: 2^8 (W_i / D + w). */
            np_u128 cu = (((np_u128)np_seed_rotl(bu, i, n) << 96) / D + ((np_u128)(w & 1u) << 96)) << 8;
            np_u128 cv = (((np_u128)np_seed_rotl(bv, i, n) << 96) / D + ((np_u128)(w >> 1) << 96)) << 8;
            uint32_t prev = 0;
            for (unsigned f = 0; f < 64; f++) {
                unsigned mq = 8u * 8u - f; /* M in eighths */
                int level = (int)(mq / 8u);
                uint32_t m16 = (mq % 8u) * 8192u, pm, om;
                m_words(m16, &pm, &om);
                unsigned idx = (i + 8u - (unsigned)level) % n;
                np_hatch_sig s;
                memset(&s, 0, sizeof s);
                s.xu = np_hatch_xs(cu, level);
                s.xv = np_hatch_xs(cv, level);
                s.tone = 255;
                s.pm = pm;
                s.om = om;
                np_hatch_setup(&c, &s);
                np_hatch_seed_sig z;
                np_hatch_seed(&c, &s, 0, idx, &z);
                moved += z.ru < -2 || z.ru > 2 || z.rv < -2 || z.rv > 2;
                drops += z.am < prev;
                prev = z.am;
            }
            strokes++;
        }
    printf("%u strokes over 64 frames (8 levels): %u frames with a centre off its UV point, %u alpha drops\n", strokes,
           moved, drops);
    NP_CHECK(moved == 0 && drops == 0, "fixed strokes, no drop");
    return 0;
}

static const np_test_case cases[] = {
    { "seeds_fkm16", t_seeds_fkm16 },
    { "seeds_fkm64", t_seeds_fkm64 },
    { "seeds_all16", t_seeds_all16 },
    { "seeds_shipped", t_seeds_shipped },
    { "seeds_random", t_seeds_random },
    { "tone_exact", t_tone_exact },
    { "alpha_error", t_alpha_error },
    { "model_vs_ref", t_model_vs_ref },
    { "guard_bits", t_guard_bits },
    { "nesting", t_nesting },
    { "kat", t_kat },
    { "cover_identical16", t_cover_identical16 },
    { "cover_identical64", t_cover_identical64 },
    { "cover_rotations", t_cover_rotations },
    { "cover_table1", t_cover_table1 },
    { "zoom_identical", t_zoom_identical },
    { "zoom_sequence", t_zoom_sequence },
    { "stiff_deep_zoom", t_stiff_deep_zoom },
    { "stiff_level_seam", t_stiff_level_seam },
    { "stiff_256_blends", t_stiff_256_blends },
    { "stiff_tile_corner", t_stiff_tile_corner },
    { "stiff_frac_half", t_stiff_frac_half },
    { "stiff_tone_0_1", t_stiff_tone_0_1 },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
