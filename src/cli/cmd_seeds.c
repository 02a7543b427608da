/* SPDX-License-Identifier: MIT */
/* noisepipe seeds - de Bruijn seed sets of the hatching unit (seed 003; src/units/hatch_seeds.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hatch_seeds.h"
#include "np_common.h"
#include "np_cmd.h"
#include "np_rng.h"
#include "np_vec.h"

static const char usage[] =
    "usage: noisepipe seeds --order K [--all | --search [--seconds S | --count C] [--seed X] | --digits D]\n"
    "       noisepipe seeds --set NAME\n"
    "                       [--list]\n"
    "\n"
    "Seed sets of the hatching unit (docs/hatch.md): a de Bruijn sequence B(4, K) of N = 4^K\n"
    "base-4 digits d_j = 2 b_u,j + b_v,j gives the bit patterns b_u, b_v of N seeds\n"
    "s_i = rotl(b, i) / (2^N - 1). For each set it prints the digits, b_u and b_v, the exact\n"
    "proof that one seed lies in each cell of the 2^K x 2^K grid, and the minimum toroidal\n"
    "seed spacing (exact in integers).\n"
    "\n"
    "  --order K     1, 2 or 3 (4, 16 or 64 seeds); without a mode: the lexicographic (FKM) set\n"
    "  --all         every cyclic B(4, K) (Eulerian circuits; K <= 2: 20,736 at K = 2, checked\n"
    "                against the BEST theorem): worst / median / best spacing and the best sets\n"
    "  --search      random Eulerian circuits (uniform, BEST construction) for --seconds S\n"
    "                (default 10), or exactly --count C of them (reproducible on any machine),\n"
    "                from --seed X (default 1); prints the best set found\n"
    "  --digits D    the set of the N digits D (0..3), which must be a B(4, K)\n"
    "  --set NAME    a shipped set: fkm16, best16, fkm64, best64\n"
    "  --list        also list every seed (u, v) and its cell\n"
    "\n"
    "Exit status: 0; 1 when a set is not de Bruijn or the cell proof fails; 2 on bad usage.\n";

static const char *cmd = "seeds";

static void print_digits(const uint8_t *d, unsigned n)
{
    for (unsigned j = 0; j < n; j++)
        putchar('0' + d[j]);
}

/* Print one set's report; 0 if the proof holds, 1 if not. */
static int report_set(const char *title, const np_seedset *s, int list)
{
    uint8_t d[NP_SEEDS_NMAX];
    unsigned cells[NP_SEEDS_NMAX], pi, pj, side = 1u << s->K;
    np_seeds_to_digits(s, d);
    int db = np_seeds_is_debruijn(s->K, d);
    unsigned bad = np_seeds_cells(s, cells);
    double sp = np_seeds_spacing(s, NULL, &pi, &pj);
    printf("%s: B(4,%u), N = %u seeds\n  digits  ", title, s->K, s->n);
    print_digits(d, s->n);
    printf("\n  b_u = 0x%0*llX  b_v = 0x%0*llX\n", (int)(s->n / 4u), (unsigned long long)s->bu, (int)(s->n / 4u),
           (unsigned long long)s->bv);
    printf("  de Bruijn: %s; one seed per cell of the %ux%u grid: %s", db ? "yes" : "NO", side, side,
           bad ? "NO" : "yes (exact)");
    if (bad)
        printf(" (%u cells without exactly one seed)", bad);
    printf("\n  s_0 = (%.4f, %.4f)\n", np_seeds_coord(s->bu, 0, s->n), np_seeds_coord(s->bv, 0, s->n));
    printf("  minimum toroidal spacing %.4f (seeds %u and %u)\n", sp, pi, pj);
    if (list)
        for (unsigned i = 0; i < s->n; i++) {
            double u = np_seeds_coord(s->bu, i, s->n), v = np_seeds_coord(s->bv, i, s->n);
            printf("    s_%-2u = (%.6f, %.6f)  cell (%u, %u)\n", i, u, v, (unsigned)(u * side),
                   (unsigned)(v * side));
        }
    return db && !bad ? 0 : 1;
}

typedef struct all_stats {
    unsigned K, n;
    double *sp;
    uint64_t count, cap;
    double best;
    uint8_t best_digits[8][NP_SEEDS_NMAX];
    unsigned n_best_kept;
    uint64_t n_best;
    uint64_t not_db;
} all_stats;

static int all_cb(const uint8_t *digits, void *user)
{
    all_stats *a = user;
    np_seedset s;
    if (!np_seeds_is_debruijn(a->K, digits))
        a->not_db++;
    np_seeds_from_digits(a->K, digits, &s);
    double sp = np_seeds_spacing(&s, NULL, NULL, NULL);
    if (a->count < a->cap)
        a->sp[a->count] = sp;
    a->count++;
    /* Ties are decided on the 4-decimal figure: the exact values of the best sets are equal by symmetry. */
    if (sp > a->best + 1e-12) {
        a->best = sp;
        a->n_best = 0;
        a->n_best_kept = 0;
    }
    if (sp > a->best - 1e-12) {
        if (a->n_best_kept < 8u)
            memcpy(a->best_digits[a->n_best_kept++], digits, a->n);
        a->n_best++;
    }
    return 0;
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

static int run_all(unsigned K, int list)
{
    all_stats a;
    memset(&a, 0, sizeof a);
    a.K = K;
    a.n = np_seeds_n(K);
    a.cap = 100000;
    a.best = -1.0;
    a.sp = malloc(sizeof(double) * a.cap);
    if (!a.sp) {
        np_err(cmd, "out of memory");
        return NP_EXIT_FAIL;
    }
    uint64_t n = np_seeds_enumerate(K, all_cb, &a);
    double expect = np_seeds_best_count(K);
    printf("all B(4,%u): %llu cyclic sequences enumerated (Eulerian circuits), BEST theorem: %.0f; %s\n", K,
           (unsigned long long)n, expect, (double)n == expect && !a.not_db ? "equal, every one de Bruijn" : "MISMATCH");
    qsort(a.sp, (size_t)a.count, sizeof(double), cmp_double);
    /* The median of an even count: the upper of the middle two (both printed). */
    double med = a.sp[a.count / 2u], med_lo = a.sp[(a.count - 1u) / 2u];
    printf("minimum toroidal spacing: worst %.4f, median %.4f, best %.4f (%llu sequences at the best)\n", a.sp[0], med,
           a.sp[a.count - 1u], (unsigned long long)a.n_best);
    printf("  (median: the upper of the middle two, %.6f; the lower is %.6f)\n", med, med_lo);
    int rc = 0;
    for (unsigned k = 0; k < a.n_best_kept; k++) {
        np_seedset s;
        char title[32];
        np_seeds_from_digits(K, a.best_digits[k], &s);
        snprintf(title, sizeof title, "best #%u", k + 1u);
        rc |= report_set(title, &s, list);
    }
    free(a.sp);
    return (double)n == expect && !a.not_db && !rc ? NP_EXIT_OK : NP_EXIT_FAIL;
}

static int run_search(unsigned K, double seconds, uint64_t count, uint64_t seed, int list)
{
    np_rng g;
    np_rng_seed(&g, seed);
    np_progress pr;
    uint8_t d[NP_SEEDS_NMAX], best_d[NP_SEEDS_NMAX];
    unsigned n = np_seeds_n(K);
    double best = -1.0, t0 = np_now();
    uint64_t tries = 0, ms = (uint64_t)(seconds * 1000.0);
    if (count)
        np_progress_start(&pr, "seeds search (circuits)", count);
    else
        np_progress_start(&pr, "seeds search (ms)", ms);
    for (;;) {
        for (unsigned k = 0; k < 256u && (!count || tries < count); k++) {
            np_seedset s;
            np_seeds_random(K, &g, d);
            np_seeds_from_digits(K, d, &s);
            double sp = np_seeds_spacing(&s, NULL, NULL, NULL);
            tries++;
            if (sp > best) {
                best = sp;
                memcpy(best_d, d, n);
            }
        }
        double el = np_now() - t0;
        if (count) {
            np_progress_update(&pr, tries);
            if (tries >= count)
                break;
            continue;
        }
        np_progress_update(&pr, (uint64_t)(el * 1000.0) < ms ? (uint64_t)(el * 1000.0) : ms);
        if (el >= seconds)
            break;
    }
    np_progress_end(&pr);
    printf("random search over B(4,%u): %llu uniform random Eulerian circuits in %.1f s (--seed %llu)\n", K,
           (unsigned long long)tries, np_now() - t0, (unsigned long long)seed);
    np_seedset s;
    np_seeds_from_digits(K, best_d, &s);
    return report_set("best found", &s, list) ? NP_EXIT_FAIL : NP_EXIT_OK;
}

int np_cmd_seeds(int argc, char **argv)
{
    uint64_t K = 0, seed = 1, count = 0;
    double seconds = 10.0;
    const char *v, *digits = NULL, *setname = NULL;
    int all = 0, search = 0, list = 0;
    for (int i = 1; i < argc; i++) {
        int r;
        if (np_vec_is_help(argv[i])) {
            fputs(usage, stdout);
            return NP_EXIT_OK;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--order", &v)) != 0) {
            if (r < 0 || np_vec_opt_u64(cmd, "--order", v, 1, NP_SEEDS_KMAX, &K) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--seed", &v)) != 0) {
            if (r < 0 || np_vec_opt_u64(cmd, "--seed", v, 0, UINT64_MAX, &seed) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--seconds", &v)) != 0) {
            if (r < 0 || np_vec_opt_double(cmd, "--seconds", v, &seconds) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--count", &v)) != 0) {
            if (r < 0 || np_vec_opt_u64(cmd, "--count", v, 1, UINT64_MAX, &count) != 0)
                return NP_EXIT_USAGE;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--digits", &v)) != 0) {
            if (r < 0)
                return NP_EXIT_USAGE;
            digits = v;
        } else if ((r = np_vec_opt(cmd, argc, argv, &i, "--set", &v)) != 0) {
            if (r < 0)
                return NP_EXIT_USAGE;
            setname = v;
        } else if (strcmp(argv[i], "--all") == 0) {
            all = 1;
        } else if (strcmp(argv[i], "--search") == 0) {
            search = 1;
        } else if (strcmp(argv[i], "--list") == 0) {
            list = 1;
        } else {
            np_err(cmd, "unknown option '%s' (noisepipe seeds --help)", argv[i]);
            return NP_EXIT_USAGE;
        }
    }
    if (setname) {
        const np_hatch_set *ns = np_seeds_find(setname);
        if (!ns) {
            np_err(cmd, "--set '%s': expected fkm16, best16, fkm64 or best64", setname);
            return NP_EXIT_USAGE;
        }
        printf("shipped set %s (%s), recorded spacing %.4f\n", ns->name, ns->origin, ns->spacing);
        np_seedset s = np_seeds_of(ns);
        return report_set(ns->name, &s, list) ? NP_EXIT_FAIL : NP_EXIT_OK;
    }
    if (K == 0) {
        np_err(cmd, "--order K is required (1, 2 or 3)");
        return NP_EXIT_USAGE;
    }
    if (all + search + (digits != NULL) > 1) {
        np_err(cmd, "--all, --search and --digits exclude each other");
        return NP_EXIT_USAGE;
    }
    unsigned n = np_seeds_n((unsigned)K);
    if (digits) {
        uint8_t d[NP_SEEDS_NMAX];
        if (strlen(digits) != n) {
            np_err(cmd, "--digits: expected %u digits for --order %llu, got %zu", n, (unsigned long long)K,
                   strlen(digits));
            return NP_EXIT_USAGE;
        }
        for (unsigned j = 0; j < n; j++) {
            if (digits[j] < '0' || digits[j] > '3') {
                np_err(cmd, "--digits: character %u is '%c', expected 0..3", j + 1u, digits[j]);
                return NP_EXIT_USAGE;
            }
            d[j] = (uint8_t)(digits[j] - '0');
        }
        np_seedset s;
        np_seeds_from_digits((unsigned)K, d, &s);
        return report_set("given", &s, list) ? NP_EXIT_FAIL : NP_EXIT_OK;
    }
    if (all) {
        if (K > 2) {
            np_err(cmd, "--all: B(4,3) has %.3g sequences; use --search", np_seeds_best_count(3));
            return NP_EXIT_USAGE;
        }
        return run_all((unsigned)K, list);
    }
    if (search)
        return run_search((unsigned)K, seconds, count, seed, list);
    uint8_t d[NP_SEEDS_NMAX];
    np_seedset s;
    np_seeds_fkm((unsigned)K, d);
    np_seeds_from_digits((unsigned)K, d, &s);
    return report_set("lexicographic (FKM)", &s, list) ? NP_EXIT_FAIL : NP_EXIT_OK;
}
