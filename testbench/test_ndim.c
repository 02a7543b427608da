/* SPDX-License-Identifier: MIT */
/*
 * Noise in n = 2..5 dimensions (issue 18, docs/noise-nd.md): the n-D hash
 * and gradient, the sorting networks, n = 3 against the 3-D units bit for
 * bit, the error against the float reference (random, faces, extremes,
 * wrap and a local search around the worst), continuity at the kernel
 * edge, and the cycle models against the bit-exact models.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_classicn.h"
#include "np_hashn.h"
#include "np_pipe_drive.h"
#include "np_ref.h"
#include "np_refn.h"
#include "np_rng.h"
#include "np_simplex.h"
#include "np_simplexn.h"
#include "np_test.h"
#include "np_unit.h"

static uint16_t word(np_rng *r) { return (uint16_t)(np_rng_next(r) >> 48); }

/* ---- hash and gradient ---- */

static int hash3_is_seed(void)
{
    uint64_t diff = 0;
    for (uint32_t v = 0; v < (1u << 24); v++) {
        uint8_t c[3] = { (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16) };
        diff += np_hashn_stream(3, c) != np_hash6(c[0], c[1], c[2]);
    }
    printf("n = 3: the generic bit-stream hash differs from np_hash6 at %llu of 2^24 points\n", (unsigned long long)diff);
    NP_CHECK(diff == 0, "%llu differences", (unsigned long long)diff);
    return 0;
}

/*
 * np_hashn_table against the bit stream: n = 2 at all 2^16 points; for
 * n = 2..5 every entry of every table (chunk q's planes set to each index,
 * the other planes random) and 10^6 random points; n = 3 the same (there the
 * table is np_hash6_fast: hash3_is_seed and fast.hash_exhaustive cover it).
 */
static int hash_tables(void)
{
    np_rng r;
    np_rng_seed(&r, 0x6861736874ULL);
    uint64_t diff = 0, pts = 0;
    for (uint32_t v = 0; v < (1u << 16); v++, pts++) {
        uint8_t c[2] = { (uint8_t)v, (uint8_t)(v >> 8) };
        diff += np_hashn_table(2, c) != np_hashn_stream(2, c);
    }
    for (unsigned n = 2; n <= 5; n++) {
        uint64_t d0 = diff;
        for (unsigned q = 0; q < 3; q++)
            for (uint32_t idx = 0; idx < (1u << (3u * n)); idx++, pts++) {
                uint8_t c[5];
                uint64_t w = np_rng_next(&r);
                for (unsigned a = 0; a < n; a++) {
                    unsigned mine = (idx >> (3u * a) & 7u) << (3u * q), keep = (7u << (3u * q)) & 255u;
                    c[a] = (uint8_t)(((unsigned)(w >> (8u * a)) & ~keep) | (mine & 255u));
                }
                diff += np_hashn_table(n, c) != np_hashn_stream(n, c);
            }
        for (unsigned k = 0; k < 1000000; k++, pts++) {
            uint64_t w = np_rng_next(&r);
            uint8_t c[5] = { (uint8_t)w, (uint8_t)(w >> 8), (uint8_t)(w >> 16), (uint8_t)(w >> 24), (uint8_t)(w >> 32) };
            diff += np_hashn_table(n, c) != np_hashn_stream(n, c);
        }
        printf("n = %u: table hash against the bit stream: %llu differences (every table entry, 10^6 random)\n", n,
               (unsigned long long)(diff - d0));
    }
    printf("%llu points, %llu differences\n", (unsigned long long)pts, (unsigned long long)diff);
    NP_CHECK(diff == 0, "%llu points where np_hashn_table differs from np_hashn_stream", (unsigned long long)diff);
    return 0;
}

static int hash_distribution(void)
{
    /* Enumerate n = 2 (2^16 points) and n = 3 (2^24) and compare with the convolution. */
    for (unsigned n = 2; n <= 3; n++) {
        double conv[64], cnt[64] = { 0 };
        np_hashn_tile_counts(n, conv);
        for (uint32_t v = 0; v < (1u << (8u * n)); v++) {
            uint8_t c[3] = { (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16) };
            cnt[np_hashn(n, c)] += 1.0;
        }
        for (unsigned h = 0; h < 64; h++)
            NP_CHECK(cnt[h] == conv[h], "n=%u h=%u: enumerated %.0f, convolution %.0f", n, h, cnt[h], conv[h]);
    }
    for (unsigned n = 2; n <= 5; n++) {
        double lo, hi, tot, chi;
        np_hashn_tile_summary(n, &lo, &hi, &tot, &chi);
        printf("n = %u: %u lookups, %.0f points, counts %.0f .. %.0f against a uniform %.0f (max/min %.3f, "
               "chi2 %.4g)\n", n, np_hashn_lookups(n), tot, lo, hi, tot / 64, hi / lo, chi);
        NP_CHECK(tot == ldexp(1.0, (int)(8u * n)), "n=%u: total %.0f", n, tot);
        if (n == 3)
            NP_CHECK(lo == 101724.0 && hi == 461608.0, "n=3: %.0f..%.0f, docs/classic3.md says 101724..461608", lo,
                     hi);
    }
    return 0;
}

/*
 * The cost model prices the hash's adder tree and bank at the low
 * np_gradn_index_bits(n) bits of h (np_classicn_datapath): no higher bit may
 * change a coefficient, and the top one of them must (else the count is loose).
 */
static int grad_index_bits(void)
{
    for (unsigned n = 2; n <= 5; n++) {
        unsigned b = np_gradn_index_bits(n), top_matters = 0;
        for (unsigned h = 0; h < 64; h++) {
            int8_t c[5], lo[5], flip[5];
            np_gradn_decode(n, (uint8_t)h, c);
            np_gradn_decode(n, (uint8_t)(h & ((1u << b) - 1u)), lo);
            np_gradn_decode(n, (uint8_t)(h ^ (1u << (b - 1u))), flip);
            NP_CHECK(memcmp(c, lo, n) == 0, "n=%u h=%u: a bit above bit %u changes the gradient", n, h, b - 1u);
            top_matters |= memcmp(c, flip, n) != 0;
        }
        NP_CHECK(top_matters, "n=%u: bit %u of h never changes the gradient (index bits %u too many)", n, b - 1u, b);
    }
    return 0;
}

static int grad_sets(void)
{
    np_rng r;
    np_rng_seed(&r, 18);
    for (unsigned n = 2; n <= 5; n++) {
        unsigned distinct = 0, maxk = 0, maxn2 = 0;
        int8_t seen[64][5];
        for (unsigned h = 0; h < 64; h++) {
            int8_t c[5];
            np_gradn_decode(n, (uint8_t)h, c);
            unsigned k = 0, n2 = 0;
            for (unsigned a = 0; a < n; a++) {
                NP_CHECK(c[a] >= -1 && c[a] <= 1, "n=%u h=%u", n, h);
                k += c[a] != 0;
                n2 += (unsigned)(c[a] * c[a]);
            }
            maxk = k > maxk ? k : maxk;
            maxn2 = n2 > maxn2 ? n2 : maxn2;
            int dup = 0;
            for (unsigned e = 0; e < distinct; e++)
                dup |= memcmp(seen[e], c, n) == 0;
            if (!dup)
                memcpy(seen[distinct++], c, n);
            if (n == 3) {
                np_grad g = np_grad_decode((uint8_t)h);
                NP_CHECK(c[0] == g.cx && c[1] == g.cy && c[2] == g.cz, "h=%u", h);
            }
            /* The reference's gradient, written out separately, is the same linear function. */
            double d[5], dot = 0.0;
            for (unsigned a = 0; a < n; a++) {
                d[a] = (double)(int64_t)(np_rng_next(&r) >> 40) / 1e6;
                dot += c[a] * d[a];
            }
            NP_CHECK(np_ref_gradn(n, h, d) == dot || fabs(np_ref_gradn(n, h, d) - dot) < 1e-9, "n=%u h=%u", n, h);
        }
        printf("n = %u: %u distinct gradients, at most %u non-zero coefficients, |G|^2 <= %u\n", n, distinct, maxk,
               maxn2);
        NP_CHECK(maxk == np_gradn_max_terms(n) && maxn2 == np_gradn_max_norm2(n), "n=%u", n);
        NP_CHECK(distinct == (n == 2 ? 8u : n == 3 ? 20u : 32u), "n=%u: %u gradients", n, distinct);
    }
    return 0;
}

/* ---- ranking ---- */

static void rank_def(unsigned n, const int32_t *v, uint8_t *order)
{
    for (unsigned a = 0; a < n; a++) {
        unsigned r = 0;
        for (unsigned b = 0; b < n; b++)
            r += v[b] > v[a] || (v[b] == v[a] && b < a);
        order[r] = (uint8_t)a;
    }
}

static int sorting_networks(void)
{
    np_rng r;
    np_rng_seed(&r, 5);
    for (unsigned n = 2; n <= 5; n++) {
        uint64_t tried = 0;
        /* Every vector over {0, 1, 2} (ties in pairs, triples, all) and random ones over a small range. */
        unsigned total = 1;
        for (unsigned a = 0; a < n; a++)
            total *= 3u;
        for (unsigned v = 0; v < total + 100000u; v++) {
            int32_t x[5];
            unsigned t = v;
            for (unsigned a = 0; a < n; a++) {
                x[a] = v < total ? (int32_t)(t % 3u) : (int32_t)np_rng_below(&r, 5) - 2;
                t /= 3u;
            }
            uint8_t o1[5], o2[5];
            np_simplexn_rank(n, x, o1);
            rank_def(n, x, o2);
            NP_CHECK(memcmp(o1, o2, n) == 0, "n=%u: network and definition differ", n);
            if (n == 3) {
                uint8_t hi, lo;
                np_simplex_rank(x[0], x[1], x[2], &hi, &lo);
                NP_CHECK(o1[0] == hi && o1[2] == lo, "n=3: Appendix B's hi=%u lo=%u, network %u %u", hi, lo, o1[0],
                         o1[2]);
            }
            tried++;
        }
        const uint8_t(*pairs)[2];
        printf("n = %u: %u comparators, %llu rankings (every tie pattern over {0,1,2}) as the definition%s\n", n,
               np_simplexn_network(n, &pairs), (unsigned long long)tried, n == 3 ? " and Appendix B's" : "");
    }
    return 0;
}

/* ---- n = 3 against the 3-D units ---- */

static void simplex3_inputs(np_rng *r, uint64_t k, uint16_t x[3])
{
    if (k < 40) { /* simplex3's boundary table */
        uint64_t in[64][NP_UNIT_MAX_FIELDS];
        np_unit_cfg c;
        const np_unit *u = np_unit_find("simplex3");
        np_unit_cfg_default(u, &c);
        u->boundary(&c, in, 64);
        for (unsigned a = 0; a < 3; a++)
            x[a] = (uint16_t)in[k][a];
        return;
    }
    for (unsigned a = 0; a < 3; a++)
        x[a] = word(r);
    if (k % 4 == 1) /* a face: two words equal */
        x[np_rng_below(r, 3)] = x[(k / 4) % 3];
    if (k % 8 == 3) /* extremes */
        x[np_rng_below(r, 3)] = (k & 16) ? 0xffff : 0;
}

static int simplex3_bit_exact(void)
{
    static const unsigned cfgs[][4] = { { 16, 23, 20, 22 }, { 8, 15, 12, 14 }, { 8, 8, 8, 8 }, { 20, 30, 32, 26 },
                                        { 12, 4, 6, 3 } };
    for (unsigned k = 0; k < sizeof cfgs / sizeof cfgs[0]; k++) {
        np_simplexn_cfg cn = { 3, cfgs[k][0], cfgs[k][1], cfgs[k][2], cfgs[k][3] };
        NP_CHECK(np_simplexn_cfg_check(&cn) == NULL, "cfg %u", k);
        np_simplex_cfg c3 = np_simplex_cfg_default(cfgs[k][0], 16, k & 1u);
        c3.t_frac = cn.t_frac;
        c3.p_frac = cn.p_frac;
        c3.k_frac = cn.k_frac;
        np_rng r;
        np_rng_seed(&r, 100 + k);
        uint64_t diff = 0, n = k == 0 ? 2000000u : 300000u;
        for (uint64_t i = 0; i < n; i++) {
            uint16_t x[3];
            simplex3_inputs(&r, i, x);
            np_simplex_out o;
            np_simplex_eval(&c3, x[0], x[1], x[2], &o);
            int32_t f = np_simplexn_eval(&cn, x);
            if (f != o.f && diff++ < 5)
                NP_CHECK(0, "(%04x %04x %04x): n-D %d, simplex3 %d", x[0], x[1], x[2], f, o.f);
        }
        double b3 = np_simplex_error_bound_lsb(&c3, 0), bn = np_simplexn_error_bound_lsb(&cn);
        printf("N=%u WT=%u WP=%u WK=%u deriv=%u: %llu inputs (boundary table, faces, extremes, random), %llu "
               "differ; bound %.4f (simplex3's %.4f)\n", cn.out_bits, cn.t_frac, cn.p_frac, cn.k_frac, c3.deriv,
               (unsigned long long)n, (unsigned long long)diff, bn, b3);
        NP_CHECK(diff == 0, "%llu differences", (unsigned long long)diff);
        /* simplex3 rounds Kf up to 8 digits in its bound; the n-D one uses the exact quotient. */
        NP_CHECK(fabs(b3 - bn) <= 1e-6 * b3, "bounds %.6f %.6f", b3, bn);
    }
    uint16_t x[3] = { 0x1234, 0x5678, 0x9abc };
    NP_CHECK(np_ref_simplexn_q88(3, x) == np_ref_simplex3_q88(x[0], x[1], x[2], NULL), "reference n = 3");
    return 0;
}

static int classic3_bit_exact(void)
{
    for (unsigned nb = 2; nb <= 16; nb += 2) {
        np_classic_cfg c3 = np_classic_cfg_default(nb);
        np_classicn_cfg cn = np_classicn_cfg_default(3, nb);
        NP_CHECK(cn.s_frac == c3.s_frac && cn.lerp_frac == c3.lerp_frac, "defaults differ at N=%u", nb);
        if (nb == 10) { /* a narrow one and an exact s-curve too */
            cn.s_frac = c3.s_frac = 24;
            cn.lerp_frac = c3.lerp_frac = 8;
        }
        np_rng r;
        np_rng_seed(&r, nb);
        uint64_t diff = 0, n = nb == 8 ? 2000000u : 200000u;
        for (uint64_t i = 0; i < n; i++) {
            uint16_t x[3];
            for (unsigned a = 0; a < 3; a++)
                x[a] = word(&r);
            if (i % 7 == 0)
                x[np_rng_below(&r, 3)] = (i & 8) ? 0xffff : (uint16_t)(x[0] & 0xff00);
            int32_t a3 = np_classic_eval(&c3, x[0], x[1], x[2]), an = np_classicn_eval(&cn, x);
            if (a3 != an && diff++ < 5)
                NP_CHECK(0, "N=%u (%04x %04x %04x): n-D %d classic3 %d", nb, x[0], x[1], x[2], an, a3);
        }
        NP_CHECK(diff == 0, "N=%u: %llu differ", nb, (unsigned long long)diff);
        NP_CHECK(fabs(np_classic_error_bound_lsb(&c3) - np_classicn_error_bound_lsb(&cn)) < 1e-12, "bound N=%u", nb);
        printf("N=%u WS=%u WL=%u: %llu inputs, %llu differ from classic3\n", nb, cn.s_frac, cn.lerp_frac,
               (unsigned long long)n, (unsigned long long)diff);
    }
    uint16_t x[3] = { 0x1234, 0x5678, 0x9abc };
    NP_CHECK(np_ref_classicn_q88(3, x) == np_ref_classic3_q88(x[0], x[1], x[2]), "reference n = 3");
    return 0;
}

static int classic3_same_datapath(void)
{
    for (unsigned nb = 4; nb <= 16; nb += 4) {
        np_classic_cfg c3 = np_classic_cfg_default(nb);
        np_classicn_cfg cn = np_classicn_cfg_default(3, nb);
        np_op a[256], b[256];
        size_t na = np_classic_datapath(&c3, a, 256), nn = np_classicn_datapath(&cn, b, 256);
        NP_CHECK(na == nn, "N=%u: %zu ops, n-D %zu", nb, na, nn);
        for (size_t i = 0; i < na && i < nn; i++) {
            int same = strcmp(a[i].stage, b[i].stage) == 0 && a[i].kind == b[i].kind && a[i].count == b[i].count &&
                       a[i].a == b[i].a && a[i].b == b[i].b && a[i].out == b[i].out && a[i].level == b[i].level &&
                       ((a[i].signal == NULL) == (b[i].signal == NULL)) &&
                       (!a[i].signal || strcmp(a[i].signal, b[i].signal) == 0);
            NP_CHECK(same, "N=%u op %zu (%s %s): classic3 %u x %u,%u n-D %u x %u,%u", nb, i, a[i].stage,
                     a[i].signal ? a[i].signal : "-", a[i].count, a[i].a, a[i].b, b[i].count, b[i].a, b[i].b);
        }
        printf("N=%u: the n-D declaration at n = 3 is classic3's, %zu ops\n", nb, na);
    }
    return 0;
}

/* ---- error against the reference ---- */

typedef struct meas {
    double worst;
    uint16_t at[5];
    uint64_t inputs;
} meas;

static double lsb_of(unsigned fam, unsigned n, unsigned nb)
{
    return ldexp(1.0, -(int)(fam == 0 ? nb : nb - np_classicn_int_bits(n)));
}

/* |model - reference| in output LSB at x, for family fam (0 simplex, 1 classic). */
static double err_at(unsigned fam, const void *cfg, unsigned n, const uint16_t *x)
{
    if (fam == 0) {
        const np_simplexn_cfg *c = cfg;
        return fabs(np_simplexn_eval(c, x) * lsb_of(0, n, c->out_bits) - np_ref_simplexn_q88(n, x)) /
               lsb_of(0, n, c->out_bits);
    }
    const np_classicn_cfg *c = cfg;
    return fabs(np_classicn_eval(c, x) * lsb_of(1, n, c->out_bits) - np_ref_classicn_q88(n, x)) /
           lsb_of(1, n, c->out_bits);
}

static void note(meas *m, double e, const uint16_t *x, unsigned n)
{
    m->inputs++;
    if (e > m->worst) {
        m->worst = e;
        memcpy(m->at, x, n * sizeof x[0]);
    }
}

/*
 * Inputs of class k: 0 random; 1 a face (a pair of words equal); 2 a
 * triple; 3 every word equal (the main diagonal); 4 extremes (words 0,
 * 0xffff and one step in); 5 the cell wrap (0x7fxx / 0x80xx); 6 a skew
 * boundary (the simplex's skewed cell changes: q X_a + p sum X a multiple of
 * 256 q, found by stepping X_a); 7 fractions where the classic s-curve's
 * rounding is worst (u with u^2 (768 - 2u) mod 2^(24 - WS) nearest half).
 */
static void class_input(np_rng *r, unsigned k, unsigned n, uint16_t *x)
{
    for (unsigned a = 0; a < n; a++)
        x[a] = word(r);
    unsigned a = (unsigned)np_rng_below(r, n), b = (a + 1u + (unsigned)np_rng_below(r, n - 1u)) % n;
    switch (k) {
    case 1: x[b] = x[a]; break;
    case 2:
        x[b] = x[a];
        if (n >= 3)
            x[(b + 1u) % n == a ? (b + 2u) % n : (b + 1u) % n] = x[a];
        break;
    case 3:
        for (unsigned e = 0; e < n; e++)
            x[e] = x[a];
        break;
    case 4:
        for (unsigned e = 0; e < n; e++)
            if (np_rng_below(r, 2))
                x[e] = (uint16_t)(np_rng_below(r, 2) ? 0xffff - np_rng_below(r, 2) : np_rng_below(r, 2));
        break;
    case 5:
        for (unsigned e = 0; e < n; e++)
            x[e] = (uint16_t)((np_rng_below(r, 2) ? 0x7f00 : 0x8000) | (x[e] & 0xff));
        break;
    case 6: {
        const np_simplexn_geom *g = np_simplexn_geom_of(n);
        uint32_t sum = 0;
        for (unsigned e = 0; e < n; e++)
            sum += x[e];
        uint32_t c0 = np_simplexn_cell(g, np_simplexn_skew(g, x[a], sum));
        for (unsigned s = 0; s < 2048u && x[a] < 0xffff; s++) {
            x[a]++;
            sum++;
            if (np_simplexn_cell(g, np_simplexn_skew(g, x[a], sum)) != c0)
                break;
        }
        break;
    }
    default: break;
    }
}

/* Local search: single-axis steps of +-1..+-64 from the worst, keeping improvements. */
static void local_search(unsigned fam, const void *cfg, unsigned n, np_rng *r, meas *m, unsigned steps)
{
    uint16_t x[5];
    memcpy(x, m->at, sizeof x);
    double cur = m->worst;
    for (unsigned s = 0; s < steps; s++) {
        uint16_t y[5];
        memcpy(y, x, sizeof y);
        unsigned a = (unsigned)np_rng_below(r, n);
        int d = (int)np_rng_below(r, 64) + 1;
        y[a] = (uint16_t)(y[a] + (np_rng_below(r, 2) ? d : -d));
        double e = err_at(fam, cfg, n, y);
        note(m, e, y, n);
        if (e >= cur) {
            cur = e;
            memcpy(x, y, sizeof x);
        }
    }
}

static void measure(unsigned fam, unsigned n, unsigned nb, uint64_t per_class, const char *what)
{
    np_simplexn_cfg cs = np_simplexn_cfg_default(n, nb);
    np_classicn_cfg cc = np_classicn_cfg_default(n, nb);
    const void *cfg = fam == 0 ? (const void *)&cs : (const void *)&cc;
    double bound = fam == 0 ? np_simplexn_error_bound_lsb(&cs) : np_classicn_error_bound_lsb(&cc);
    meas m = { 0.0, { 0 }, 0 };
    np_rng r;
    np_rng_seed(&r, 1000u * n + nb + 77u * fam);
    for (unsigned k = 0; k < 8; k++)
        for (uint64_t i = 0; i < (k == 0 ? 4u * per_class : per_class); i++) {
            uint16_t x[5];
            class_input(&r, k, n, x);
            note(&m, err_at(fam, cfg, n, x), x, n);
        }
    local_search(fam, cfg, n, &r, &m, (unsigned)per_class);
    printf("%s%u N=%u (%s): %llu inputs, max error %.4f LSB at (%04x %04x %04x %04x %04x), bound %.4f\n",
           fam == 0 ? "simplex" : "classic", n, nb, what, (unsigned long long)m.inputs, m.worst, m.at[0], m.at[1],
           n > 2 ? m.at[2] : 0, n > 3 ? m.at[3] : 0, n > 4 ? m.at[4] : 0, bound);
    NP_CHECK(bound < 1.0, "%u-D N=%u: the default's bound %.4f is not faithful", n, nb, bound);
    NP_CHECK(m.worst <= bound, "%u-D N=%u: error %.4f above the bound %.4f", n, nb, m.worst, bound);
}

static int error_simplex(void)
{
    for (unsigned n = 2; n <= 5; n++)
        for (unsigned nb = 8; nb <= 16; nb += 8)
            measure(0, n, nb, 60000, "random, faces, triples, diagonal, extremes, wrap, skew boundaries, local");
    return 0;
}

static int error_classic(void)
{
    for (unsigned n = 2; n <= 5; n++)
        for (unsigned nb = 8; nb <= 16; nb += 8)
            measure(1, n, nb, n == 5 ? 20000 : 40000, "random, faces, triples, diagonal, extremes, wrap, local");
    return 0;
}

static int error_bound_defaults(void)
{
    for (unsigned n = 2; n <= 5; n++)
        for (unsigned nb = 8; nb <= 20; nb++) {
            np_simplexn_cfg c = np_simplexn_cfg_default(n, nb);
            double b = np_simplexn_error_bound_lsb(&c);
            NP_CHECK(np_simplexn_cfg_check(&c) == NULL && b < 1.0, "simplex n=%u N=%u: bound %.4f", n, nb, b);
            if (nb == 8 || nb == 16 || nb == 20)
                printf("simplex n=%u N=%u WT=%u WP=%u WK=%u: bound %.4f LSB\n", n, nb, c.t_frac, c.p_frac, c.k_frac, b);
        }
    for (unsigned n = 2; n <= 5; n++)
        for (unsigned nb = 4; nb <= 16; nb++) {
            np_classicn_cfg c = np_classicn_cfg_default(n, nb);
            double b = np_classicn_error_bound_lsb(&c);
            NP_CHECK(np_classicn_cfg_check(&c) == NULL && b < 1.0, "classic n=%u N=%u: bound %.4f", n, nb, b);
            if (nb == 8 || nb == 16)
                printf("classic n=%u N=%u WS=%u WL=%u: bound %.4f LSB\n", n, nb, c.s_frac, c.lerp_frac, b);
        }
    return 0;
}

/* ---- continuity at the kernel edge (the tuning criterion) and the output range ---- */

/*
 * Points on the faces where the simplex changes (u_a = u_b: x_a = x_b) and
 * where the skewed cell changes (x'_a an integer), in reals, and the
 * reference's jump across them at distance 1e-9: a continuous function
 * moves by about its slope times 2e-9 (< 1e-7); a kernel that reaches past
 * its simplex's faces jumps by up to its value there. n = 3 keeps Appendix
 * B's r^2 = 0.6, which reaches past them (np_ref.h): the test expects a
 * jump there, so it can tell the two apart.
 */
static double face_jump(unsigned n, np_rng *r, int cell_face)
{
    const np_simplexn_geom *g = np_simplexn_geom_of(n);
    double x[5], Fs = (double)g->p / (double)g->q, G = (double)g->p / (double)g->l;
    unsigned a = (unsigned)np_rng_below(r, n), b = (a + 1u) % n;
    if (cell_face) { /* skewed point with x'_a an integer, unskewed */
        double xs[5], s = 0.0;
        for (unsigned e = 0; e < n; e++) {
            xs[e] = (double)np_rng_below(r, 1u << 20) / 4096.0;
            s += xs[e];
        }
        s -= xs[a] - floor(xs[a]);
        xs[a] = floor(xs[a]);
        for (unsigned e = 0; e < n; e++)
            x[e] = xs[e] - G * s;
        (void)Fs;
    } else {
        for (unsigned e = 0; e < n; e++)
            x[e] = (double)np_rng_below(r, 1u << 20) / 4096.0;
        x[b] = x[a];
    }
    double lo[5], hi[5];
    memcpy(lo, x, sizeof lo);
    memcpy(hi, x, sizeof hi);
    lo[a] -= 1e-9;
    hi[a] += 1e-9;
    return fabs(np_ref_simplexn(n, hi) - np_ref_simplexn(n, lo));
}

static int kernel_continuity(void)
{
    np_rng r;
    np_rng_seed(&r, 31);
    for (unsigned n = 2; n <= 5; n++) {
        double worst[2] = { 0.0, 0.0 };
        for (int cf = 0; cf <= 1; cf++)
            for (unsigned i = 0; i < 200000u; i++) {
                double j = face_jump(n, &r, cf);
                worst[cf] = j > worst[cf] ? j : worst[cf];
            }
        printf("n = %u (r^2 = %.3g): largest jump across simplex faces %.3g, across skewed cell faces %.3g "
               "(1e-9 either side, 2e5 points each)\n", n, np_simplexn_geom_of(n)->r2, worst[0], worst[1]);
        if (n == 3)
            NP_CHECK(worst[0] > 1e-4 || worst[1] > 1e-4, "n = 3 with r^2 = 0.6 should jump");
        else
            NP_CHECK(worst[0] < 1e-7 && worst[1] < 1e-7, "n = %u: a jump of %.3g / %.3g", n, worst[0], worst[1]);
    }
    return 0;
}

/* The largest |f| over random inputs and the cell centres, against the amplitude's bound. */
static int output_range(void)
{
    np_rng r;
    np_rng_seed(&r, 77);
    for (unsigned n = 2; n <= 5; n++) {
        const np_simplexn_geom *g = np_simplexn_geom_of(n);
        double big = 0.0, cbig = 0.0;
        for (unsigned i = 0; i < 400000u; i++) {
            uint16_t x[5];
            for (unsigned a = 0; a < n; a++)
                x[a] = word(&r);
            double f = fabs(np_ref_simplexn_q88(n, x)), c = fabs(np_ref_classicn_q88(n, x));
            big = f > big ? f : big;
            cbig = c > cbig ? c : cbig;
        }
        printf("n = %u: A = %u, |f| bound %.4f (< 1/2), largest |f| seen %.4f (of 4e5 random); classic: bound %.1f, "
               "largest seen %.4f\n", n, g->amp, g->fmax, big, 0.5 * n, cbig);
        NP_CHECK(g->fmax < 0.5 && big <= g->fmax, "n=%u: %.4f", n, big);
        NP_CHECK(cbig <= 0.5 * n, "classic n=%u: %.4f", n, cbig);
    }
    return 0;
}

/* ---- cycle models ---- */

static int sx_check(const void *cfg, const void *in, const void *out, uint64_t k)
{
    const np_simplexn_cfg *c = cfg;
    const np_simplexn_sig *i = in, *o = out;
    int32_t want = np_simplexn_eval(c, i->x);
    int ok = o->f == want && memcmp(o->x, i->x, sizeof o->x) == 0;
    NP_CHECK(ok, "transaction %llu: got %d want %d", (unsigned long long)k, o->f, want);
    return ok;
}

static int cl_check(const void *cfg, const void *in, const void *out, uint64_t k)
{
    const np_classicn_cfg *c = cfg;
    const np_classicn_sig *i = in, *o = out;
    int32_t want = np_classicn_eval(c, i->x);
    int ok = o->out == want && memcmp(o->x, i->x, sizeof o->x) == 0;
    NP_CHECK(ok, "transaction %llu: got %d want %d", (unsigned long long)k, o->out, want);
    return ok;
}

static void drive(unsigned fam, unsigned n, uint64_t count, unsigned pb, unsigned ps, uint64_t seed)
{
    static const char *const names[2][6] = { { "", "", "simplex2", "simplex3", "simplex4", "simplex5" },
                                             { "", "", "classic2", "classic3", "classic4", "classic5" } };
    np_simplexn_cfg cs = np_simplexn_cfg_default(n, 16);
    np_classicn_cfg cc = np_classicn_cfg_default(n, 8);
    np_pipe p;
    int rc = fam == 0 ? np_simplexn_pipe_init(&p, &cs) : np_classicn_pipe_init(&p, &cc);
    NP_CHECK(rc == 0, "pipe init");
    if (rc != 0)
        return;
    const np_unit *u = np_unit_find(names[fam][n]);
    np_pipe_dut d = { &p, u, n, 16, fam == 0 ? sx_check : cl_check, fam == 0 ? (const void *)&cs : (const void *)&cc };
    np_pipe_drive_result res = np_pipe_drive_random(&d, count, pb, ps, seed);
    printf("%s%u: %llu transactions in %llu cycles (bubbles %u/16, stalls %u/16): %llu mismatches, %llu unstalled "
           "ones all at latency %u\n", fam == 0 ? "simplex" : "classic", n, (unsigned long long)res.transactions,
           (unsigned long long)res.cycles, pb, ps, (unsigned long long)res.mismatches, (unsigned long long)res.exact,
           np_pipe_latency(&p));
    NP_CHECK(res.transactions == count && res.mismatches == 0, "%llu mismatches", (unsigned long long)res.mismatches);
    np_pipe_free(&p);
}

/* The n = 3 pipes use simplex3's and classic3's sig_set_in: their bundles differ, so n = 3 runs only n-D units' own. */
static int cycle_simplex_1e6(void)
{
    for (unsigned n = 2; n <= 5; n += n == 2 ? 2u : 1u) {
        drive(0, n, 1000000, 4, 4, n);
        drive(0, n, 100000, 0, 0, 10u + n);
    }
    return 0;
}

static int cycle_classic_1e6(void)
{
    for (unsigned n = 2; n <= 5; n += n == 2 ? 2u : 1u) {
        drive(1, n, 1000000, 4, 4, n);
        drive(1, n, 100000, 0, 0, 10u + n);
    }
    return 0;
}

static int registry(void)
{
    static const char *const names[] = { "simplex2", "simplex4", "simplex5", "classic2", "classic4", "classic5" };
    for (unsigned i = 0; i < 6; i++) {
        const np_unit *u = np_unit_find(names[i]);
        NP_CHECK(u != NULL, "%s not registered", names[i]);
        if (!u)
            continue;
        np_unit_cfg c;
        char err[256], txt[256];
        NP_CHECK(np_unit_configure(u, &c, NULL, err, sizeof err) == 0, "%s: %s", names[i], err);
        np_unit_fields f;
        u->fields(&c, &f);
        unsigned n = (unsigned)(names[i][7] - '0');
        NP_CHECK(f.n_in == n && f.n_out == 1, "%s: %u inputs", names[i], f.n_in);
        NP_CHECK(np_unit_configure(u, &c, "dims=3", err, sizeof err) != 0, "%s: dims is fixed", names[i]);
        np_unit_cfg_format(u, &c, txt, sizeof txt);
        printf("%s: %s\n", names[i], txt);
    }
    NP_CHECK(np_unit_find("simplex3") && np_unit_find("classic3"), "the 3-D units keep their names");
    return 0;
}

static const np_test_case cases[] = {
    { "hash3_is_seed", hash3_is_seed },
    { "hash_tables", hash_tables },
    { "hash_distribution", hash_distribution },
    { "grad_sets", grad_sets },
    { "grad_index_bits", grad_index_bits },
    { "sorting_networks", sorting_networks },
    { "simplex3_bit_exact", simplex3_bit_exact },
    { "classic3_bit_exact", classic3_bit_exact },
    { "classic3_same_datapath", classic3_same_datapath },
    { "error_bound_defaults", error_bound_defaults },
    { "error_simplex", error_simplex },
    { "error_classic", error_classic },
    { "kernel_continuity", kernel_continuity },
    { "output_range", output_range },
    { "cycle_simplex_1e6", cycle_simplex_1e6 },
    { "cycle_classic_1e6", cycle_classic_1e6 },
    { "registry", registry },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
