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

static const np_test_case cases[] = {
    { "seeds_fkm16", t_seeds_fkm16 },
    { "seeds_fkm64", t_seeds_fkm64 },
    { "seeds_all16", t_seeds_all16 },
    { "seeds_shipped", t_seeds_shipped },
    { "seeds_random", t_seeds_random },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
