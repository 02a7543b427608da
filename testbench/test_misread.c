/* SPDX-License-Identifier: MIT */
/*
 * test_misread.c - do the checked-in golden vector sets catch an RTL built
 * from a plausible misreading of the spec? Each case evaluates deliberately
 * misread variants of a unit's bit-exact model (below) on every vector of
 * the unit's checked-in sets ($readmemh files, vectors/<unit>/) and counts
 * the vectors whose expected output the variant misses. The spec's own model
 * must miss none; every misreading must be caught by at least one of the
 * sets at non-default configurations (the default set alone misses some:
 * the table printed says which).
 *
 * simplex3 misreadings (np_simplex.h):
 *   e_neg_after   e_a = -round(tau4) instead of round(-tau4) (sign after rounding)
 *   wrap          intermediates wrapped to the nominal widths of the table
 *                 (fc, q, m, e s(WP+1), S s(WP+2), Q s(WP+3)) instead of never
 *   kd_3kf        Kd' = 3 Kf' instead of round(Kd 2^WK)
 *   tau_rounded   tau3 = round(tau2 * round(T to WT bits)) (tau rounded first)
 * classic3 misreadings (np_classic.h):
 *   neg9          the H stage negates the s9 offsets in 9 bits (-(-256) wraps).
 *                 INVISIBLE at the output, and the case checks that it is: an
 *                 offset is -256 only on the far side of an axis whose fraction
 *                 is 0, where that corner's interpolation weight s(0) is exactly
 *                 0 (lerp = a + s (b - a) = a). The wrong g is still in the
 *                 register (classic.signal_widths sees g's range), so the RTL
 *                 negates in 10 bits.
 *   s_ws_bits     s held in WS bits (1.0 wraps to 0) instead of u(WS+1)
 *   ties_away     interpolators round ties away from zero (sign after rounding)
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_simplex.h"
#include "np_test.h"

/* ------------------------------------------------------------ vector files */

typedef struct vecset {
    char config[512];
    size_t n;
    uint16_t (*in)[3];
    uint64_t (*out)[4]; /* output fields, out[k] for output k */
} vecset;

/* Bits [lo, lo + n) of a hex word held as 64-bit limbs, little end first. */
static uint64_t bits_of(const uint64_t *w, unsigned lo, unsigned n)
{
    uint64_t v = 0;
    for (unsigned b = 0; b < n; b++)
        v |= ((w[(lo + b) / 64u] >> ((lo + b) % 64u)) & 1u) << b;
    return v;
}

/* Read a $readmemh set; widths[k] of the nout outputs, from the LSB end: last output first. */
static int read_set(const char *path, unsigned nout, const unsigned *widths, vecset *s)
{
    FILE *f = fopen(path, "r");
    char line[480];
    size_t cap = 0;
    memset(s, 0, sizeof *s);
    if (!f)
        return -1;
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "// config ", 10) == 0) {
            snprintf(s->config, sizeof s->config, "%s", line + 10);
            s->config[strcspn(s->config, "\n")] = 0;
        }
        if (line[0] == '/' || line[0] == '\n')
            continue;
        uint64_t w[4] = { 0, 0, 0, 0 };
        size_t len = strcspn(line, " \r\n");
        for (size_t i = 0; i < len; i++) {
            char c = line[len - 1 - i];
            uint64_t d = (uint64_t)(c <= '9' ? c - '0' : (c | 0x20) - 'a' + 10);
            w[i / 16u] |= d << (4u * (i % 16u));
        }
        if (s->n == cap) {
            cap = cap ? 2 * cap : 4096;
            s->in = realloc(s->in, cap * sizeof *s->in);
            s->out = realloc(s->out, cap * sizeof *s->out);
            if (!s->in || !s->out) {
                fclose(f);
                return -1;
            }
        }
        unsigned pos = 0;
        for (unsigned k = nout; k-- > 0;) {
            s->out[s->n][k] = bits_of(w, pos, widths[k]);
            pos += widths[k];
        }
        for (unsigned a = 3; a-- > 0;) {
            s->in[s->n][a] = (uint16_t)bits_of(w, pos, 16);
            pos += 16;
        }
        s->n++;
    }
    fclose(f);
    return 0;
}

static void free_set(vecset *s)
{
    free(s->in);
    free(s->out);
}

/* ------------------------------------------------------------ simplex3 variants */

enum { S_SPEC, S_E_NEG_AFTER, S_WRAP, S_KD_3KF, S_TAU_ROUNDED, S_VARIANTS };
static const char *const s_names[S_VARIANTS] = { "spec", "e_neg_after", "wrap", "kd_3kf", "tau_rounded" };

static int64_t maybe_wrap(int variant, int64_t v, unsigned n) { return variant == S_WRAP ? np_wrap_s(v, n) : v; }

static void simplex_variant(const np_simplex_cfg *cfg, int variant, const uint16_t in[3], uint64_t out[4])
{
    uint32_t cell[3];
    int32_t off[3];
    for (unsigned a = 0; a < 3; a++)
        cell[a] = np_simplex_cell(np_simplex_skew(in[a], in[(a + 1u) % 3u], in[(a + 2u) % 3u]));
    uint32_t n = cell[0] + cell[1] + cell[2];
    for (unsigned a = 0; a < 3; a++)
        off[a] = np_simplex_offset(in[a], cell[a], n);
    uint8_t hi, lo;
    np_simplex_rank(off[0], off[1], off[2], &hi, &lo);
    unsigned wp = cfg->p_frac;
    int64_t s = 0, qs[3] = { 0, 0, 0 };
    for (unsigned c = 0; c < 4; c++) {
        unsigned mask = np_simplex_corner_mask(hi, lo, c);
        int32_t d[3];
        for (unsigned a = 0; a < 3; a++)
            d[a] = np_simplex_corner_d(off[a], mask >> a & 1u, c);
        np_grad g = np_grad_decode(np_simplex_corner_hash(cell, mask));
        int32_t gd = np_simplex_gdot(g, d);
        uint32_t t = np_simplex_kernel_t(np_simplex_r2(d));
        uint32_t tau2 = np_simplex_tau2(cfg, t);
        uint32_t tau4 = np_simplex_tau4(cfg, tau2);
        s = maybe_wrap(variant, s + maybe_wrap(variant, np_simplex_fterm(cfg, tau4, gd), wp + 1u), wp + 2u);
        if (!cfg->deriv)
            continue;
        uint32_t tau3 = np_simplex_tau3(tau2, t);
        if (variant == S_TAU_ROUNDED) {
            /* T (u23 Q0.23) rounded to WT fraction bits first; exact when WT >= 23. */
            uint64_t tw = NP_SIMPLEX_T_BITS > cfg->t_frac
                              ? np_shr_round_half_up_u(t, NP_SIMPLEX_T_BITS - cfg->t_frac)
                              : (uint64_t)t << (cfg->t_frac - NP_SIMPLEX_T_BITS);
            tau3 = (uint32_t)np_shr_round_half_up_u((uint64_t)tau2 * tw, cfg->t_frac);
        }
        int64_t q = maybe_wrap(variant, np_simplex_qterm(cfg, tau3, gd), wp + 1u);
        const int coef[3] = { g.cx, g.cy, g.cz };
        for (unsigned a = 0; a < 3; a++) {
            int64_t e = variant == S_E_NEG_AFTER ? coef[a] * np_simplex_requant((int64_t)tau4, cfg->t_frac, wp)
                                                 : np_simplex_eterm(cfg, tau4, coef[a]);
            e = maybe_wrap(variant, e, wp + 1u);
            int64_t m = maybe_wrap(variant, np_simplex_mterm(q, d[a]), wp + 1u);
            qs[a] = maybe_wrap(variant, qs[a] + e - m, wp + 3u);
        }
    }
    int64_t kf = np_simplex_kf(cfg);
    int64_t kd = variant == S_KD_3KF ? 3 * kf : np_simplex_kd(cfg);
    out[0] = np_trunc_u((uint64_t)(int64_t)np_simplex_out_f(cfg, kf, s), cfg->out_bits);
    for (unsigned a = 0; a < 3; a++)
        out[1 + a] = cfg->deriv ? np_trunc_u((uint64_t)(int64_t)np_simplex_out_d(cfg, kd, qs[a]), cfg->dout_bits) : 0;
}

/* ------------------------------------------------------------ classic3 variants */

enum { C_SPEC, C_NEG9, C_S_WS_BITS, C_TIES_AWAY, C_VARIANTS };
static const char *const c_names[C_VARIANTS] = { "spec", "neg9", "s_ws_bits", "ties_away" };

/* Round v / 2^sh to nearest, ties away from zero (the misreading: sign, round, sign). */
static int64_t round_ties_away(int64_t v, unsigned sh)
{
    return v < 0 ? -np_shr_round_half_up(-v, sh) : np_shr_round_half_up(v, sh);
}

static int64_t c_lerp(const np_classic_cfg *cfg, int variant, uint32_t s, int64_t a, int64_t b, unsigned fa)
{
    int64_t sum = np_shl(a, cfg->s_frac) + (int64_t)s * (b - a);
    unsigned f = fa + cfg->s_frac;
    if (f < cfg->lerp_frac)
        return np_shl(sum, cfg->lerp_frac - f);
    return variant == C_TIES_AWAY ? round_ties_away(sum, f - cfg->lerp_frac)
                                  : np_shr_round_half_up(sum, f - cfg->lerp_frac);
}

/* A 9-bit negate: -(-256) wraps to -256. */
static int64_t neg_term(int variant, int coef, int64_t d)
{
    int64_t v = coef * d;
    return variant == C_NEG9 && coef < 0 ? np_wrap_s(v, 9) : v;
}

static void classic_variant(const np_classic_cfg *cfg, int variant, const uint16_t in[3], uint64_t out[4])
{
    uint8_t i = (uint8_t)(in[0] >> 8), j = (uint8_t)(in[1] >> 8), k = (uint8_t)(in[2] >> 8);
    uint8_t fr[3] = { (uint8_t)in[0], (uint8_t)in[1], (uint8_t)in[2] };
    np_classic_cell cell;
    np_classic_cell_setup(i, j, k, &cell);
    int64_t g[8];
    for (unsigned c = 0; c < 8; c++) {
        int64_t d[3];
        for (unsigned a = 0; a < 3; a++)
            d[a] = (c >> a & 1u) ? (int64_t)fr[a] - 256 : (int64_t)fr[a];
        g[c] = neg_term(variant, cell.g[c].cx, d[0]) + neg_term(variant, cell.g[c].cy, d[1]) +
               neg_term(variant, cell.g[c].cz, d[2]);
    }
    uint32_t s[3];
    for (unsigned a = 0; a < 3; a++) {
        s[a] = np_classic_scurve(cfg, fr[a]);
        if (variant == C_S_WS_BITS)
            s[a] = (uint32_t)np_trunc_u(s[a], cfg->s_frac);
    }
    int64_t l1[4], l2[2];
    for (unsigned p = 0; p < 4; p++)
        l1[p] = c_lerp(cfg, variant, s[0], g[2 * p], g[2 * p + 1], NP_CLASSIC_FRAC_IN);
    for (unsigned p = 0; p < 2; p++)
        l2[p] = c_lerp(cfg, variant, s[1], l1[2 * p], l1[2 * p + 1], cfg->lerp_frac);
    int64_t l3 = c_lerp(cfg, variant, s[2], l2[0], l2[1], cfg->lerp_frac);
    out[0] = np_trunc_u((uint64_t)(int64_t)np_classic_output(cfg, l3), cfg->out_bits);
    out[1] = out[2] = out[3] = 0;
}

/* ------------------------------------------------------------ cases */

/* The checked-in sets of each unit: the default first, then the non-default ones. */
static const char *const c3_sets[] = { "classic3-l1-seed1", "classic3-l1-seed1-cheap", "classic3-l1-seed1-wide_l" };
static const char *const s3_sets[] = { "simplex3-l1-seed1", "simplex3-l1-seed1-t1", "simplex3-l1-seed1-coarse" };
enum { NSETS = 3 };

static int run_unit(int simplex)
{
    const char *const *sets = simplex ? s3_sets : c3_sets;
    unsigned nvar = simplex ? S_VARIANTS : C_VARIANTS;
    const char *const *names = simplex ? s_names : c_names;
    uint64_t missed[S_VARIANTS][NSETS];
    memset(missed, 0, sizeof missed);
    for (unsigned si = 0; si < NSETS; si++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s/%s.memh", NP_VEC_DIR, simplex ? "simplex3" : "classic3", sets[si]);
        np_simplex_cfg sc;
        np_classic_cfg cc;
        unsigned widths[4], nout;
        vecset vs;
        /* The config line decides the widths: read it first with a dummy layout. */
        unsigned w0[1] = { 1 };
        NP_CHECK(read_set(path, 1, w0, &vs) == 0, "cannot read %s", path);
        if (vs.n == 0)
            return 1;
        if (simplex) {
            NP_CHECK(sscanf(vs.config, "out_bits=%u dout_bits=%u deriv=%u t_frac=%u p_frac=%u k_frac=%u",
                            &sc.out_bits, &sc.dout_bits, &sc.deriv, &sc.t_frac, &sc.p_frac, &sc.k_frac) == 6,
                     "%s: config '%s'", path, vs.config);
            nout = sc.deriv ? 4u : 1u;
            widths[0] = sc.out_bits;
            widths[1] = widths[2] = widths[3] = sc.dout_bits;
        } else {
            NP_CHECK(sscanf(vs.config, "out_bits=%u s_frac=%u lerp_frac=%u", &cc.out_bits, &cc.s_frac,
                            &cc.lerp_frac) == 3, "%s: config '%s'", path, vs.config);
            nout = 1;
            widths[0] = cc.out_bits;
        }
        free_set(&vs);
        NP_CHECK(read_set(path, nout, widths, &vs) == 0, "cannot read %s", path);
        for (size_t t = 0; t < vs.n; t++)
            for (unsigned v = 0; v < nvar; v++) {
                uint64_t o[4];
                if (simplex)
                    simplex_variant(&sc, (int)v, vs.in[t], o);
                else
                    classic_variant(&cc, (int)v, vs.in[t], o);
                int differs = 0;
                for (unsigned k = 0; k < nout; k++)
                    differs |= o[k] != vs.out[t][k];
                missed[v][si] += (uint64_t)differs;
            }
        printf("%-28s %6zu vectors  config %s\n", sets[si], vs.n, vs.config);
        free_set(&vs);
    }
    printf("vectors whose expected output each variant misses (a misreading is caught where > 0):\n");
    printf("  %-12s", "variant");
    for (unsigned si = 0; si < NSETS; si++)
        printf(" %28s", sets[si]);
    printf("\n");
    for (unsigned v = 0; v < nvar; v++) {
        printf("  %-12s", names[v]);
        uint64_t caught_nondefault = 0;
        for (unsigned si = 0; si < NSETS; si++) {
            printf(" %28llu", (unsigned long long)missed[v][si]);
            if (si > 0)
                caught_nondefault += missed[v][si];
        }
        printf("\n");
        if (v == 0)
            for (unsigned si = 0; si < NSETS; si++)
                NP_CHECK(missed[0][si] == 0, "the spec's model misses %llu vectors of %s",
                         (unsigned long long)missed[0][si], sets[si]);
        else if (!simplex && v == C_NEG9)
            for (unsigned si = 0; si < NSETS; si++)
                NP_CHECK(missed[v][si] == 0, "neg9 should be invisible at the output, but %s catches it",
                         sets[si]);
        else
            NP_CHECK(caught_nondefault > 0, "misreading %s is caught by no non-default set", names[v]);
    }
    return 0;
}

static int case_simplex3(void) { return run_unit(1); }
static int case_classic3(void) { return run_unit(0); }

static const np_test_case cases[] = {
    { "classic3", case_classic3 },
    { "simplex3", case_simplex3 },
    { NULL, NULL },
};
NP_TEST_MAIN(cases)
