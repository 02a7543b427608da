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
    for (unsigned k = 0; k < NP_SEEDS_SHIPPED; k++) {
        const np_seedset_named *ns = &np_seeds_shipped[k];
        uint8_t d[NP_SEEDS_NMAX];
        np_seeds_to_digits(&ns->s, d);
        double sp = np_seeds_spacing(&ns->s, NULL, NULL, NULL);
        printf("%-7s N=%2u spacing %.4f (recorded %.4f) %s\n", ns->name, ns->s.n, sp, ns->spacing, ns->origin);
        NP_CHECK(ns->s.n == np_seeds_n(ns->s.K), "%s N", ns->name);
        NP_CHECK(np_seeds_is_debruijn(ns->s.K, d), "%s de Bruijn", ns->name);
        NP_CHECK(np_seeds_cells(&ns->s, NULL) == 0, "%s cells", ns->name);
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
    const np_seedset_named *ns = np_seeds_find(set);
    np_hatch_cfg_layers(&c, ns->s.n, ns->s.bu, ns->s.bv);
    c.layers = 4;
    c.fade = fade;
    c.guard = guard;
    c.lanes = 1;
    /* Stroke length 4 / sqrt N and width 0.48 / sqrt N of a seed tile at m = 0 (Q8.8 inverses). */
    c.inv_u = ns->s.n == 64u ? 2048u : 1024u;
    c.inv_v = ns->s.n == 64u ? 17067u : 8533u;
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
                    for (unsigned i = 0; i < c.n; i++) {
                        np_hatch_seed_sig z;
                        np_hatch_seed(&c, &s, l, i, &z);
                        double e = fabs(z.alpha / 1073741824.0 - ra[l * c.n + i]);
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
    for (unsigned k = 0; k < NP_SEEDS_SHIPPED; k++) {
        const np_seedset_named *ns = &np_seeds_shipped[k];
        np_hatch_cfg c = cfg_of(ns->name, 0, 9);
        unsigned n = c.n;
        np_u128 D = n == 64 ? (np_u128)~(uint64_t)0 : (((np_u128)1 << n) - 1u);
        for (unsigned l = 0; l < 4; l++) {
            unsigned per_tile[4] = { 0, 0, 0, 0 };
            for (unsigned i = 0; i < n; i++) {
                uint64_t wu = np_seed_rotl(c.bu[l], i, n), wv = np_seed_rotl(c.bv[l], i, n);
                for (unsigned w = 0; w < 4; w++) {
                    unsigned wx = w & 1u, wy = w >> 1;
                    np_u128 pu = (np_u128)wu + wx * D, pv = (np_u128)wv + wy * D; /* s_i + w, over D */
                    int coincide = 0;
                    for (unsigned j = 0; j < n && !coincide; j++) {
                        np_u128 su = 2 * (np_u128)np_seed_rotl(c.bu[l], j, n) % (2 * D);
                        np_u128 sv = 2 * (np_u128)np_seed_rotl(c.bv[l], j, n) % (2 * D);
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
               c.n / 4u);
        if (np_test_failures)
            return 1;
    }
    printf("%u points checked\n", checked);
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
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
