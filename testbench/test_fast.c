/* SPDX-License-Identifier: MIT */
/*
 * The fast paths against the specification (issue 13): the table-driven
 * hash and gradient decode (np_hash.h) against the seed's bit loop, every
 * argument.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_classic.h"
#include "np_hash.h"
#include "np_ref.h"
#include "np_ref_fast.h"
#include "np_rng.h"
#include "np_simplex.h"
#include "np_sweep.h"
#include "np_simplex32.h"
#include "np_unit.h"
#include "np_test.h"

enum { CHUNK = 4096 };

/* Random 8.8 words; one time in four a boundary fraction in a random or wrapping cell. */
static uint16_t rand_word(np_rng *r)
{
    static const uint8_t fr[] = { 0x00, 0x01, 0x7f, 0x80, 0x81, 0xfe, 0xff };
    uint64_t w = np_rng_next(r);
    if ((w & 3u) != 0)
        return (uint16_t)(w >> 16);
    uint8_t cell = (w & 4u) ? 0xff : (uint8_t)(w >> 24);
    return (uint16_t)(cell << 8 | fr[(w >> 40) % sizeof fr]);
}

typedef struct inputs {
    uint16_t x[CHUNK], y[CHUNK], z[CHUNK];
} inputs;

static const char *const classic_path_name[NP_CLASSIC_BATCH_PATHS] = { "generic", "int32", "avx2" };

/*
 * Classic: batch == per input over `chunks` chunks of random inputs, for the
 * batch path `path` (np_classic_eval_n itself when path is
 * NP_CLASSIC_BATCH_PATHS); returns mismatches, or UINT64_MAX when the path
 * does not apply here.
 */
static uint64_t classic_random(unsigned path, const np_classic_cfg *cfg, np_rng *r, unsigned chunks)
{
    static inputs in;
    static int32_t out[CHUNK];
    uint64_t bad = 0;
    for (unsigned c = 0; c < chunks; c++) {
        for (unsigned n = 0; n < CHUNK; n++) {
            in.x[n] = rand_word(r);
            in.y[n] = rand_word(r);
            in.z[n] = rand_word(r);
        }
        /* An odd count leaves a tail after the vector steps. */
        size_t count = CHUNK - (c & 7u);
        if (path == NP_CLASSIC_BATCH_PATHS)
            np_classic_eval_n(cfg, in.x, in.y, in.z, out, count);
        else if (np_classic_eval_n_path(path, cfg, in.x, in.y, in.z, out, count) != 0)
            return UINT64_MAX;
        for (unsigned n = 0; n < count; n++) {
            int32_t want = np_classic_eval(cfg, in.x[n], in.y[n], in.z[n]);
            if (out[n] != want && ++bad <= 5)
                NP_CHECK(out[n] == want, "path %u N=%u WS=%u WL=%u (0x%04x, 0x%04x, 0x%04x): batch %d, eval %d",
                         path, cfg->out_bits, cfg->s_frac, cfg->lerp_frac, in.x[n], in.y[n], in.z[n], out[n],
                         want);
        }
    }
    return bad;
}

/*
 * 2^20 random inputs at the default (the int32 and AVX2 paths) and three
 * others (the generic path), through np_classic_eval_n and through each path
 * that applies; the default's specialised paths must apply (AVX2 where the
 * CPU has it).
 */
static int t_classic_batch_random(void)
{
    np_rng r;
    np_rng_seed(&r, 0x6661737431ull);
    np_classic_cfg cfgs[4] = { np_classic_cfg_default(8), np_classic_cfg_default(16),
                               { 8, 6, 6 }, { 12, 24, 10 } };
    for (unsigned k = 0; k < 4; k++) {
        NP_CHECK(np_classic_cfg_check(&cfgs[k]) == NULL, "config %u", k);
        unsigned chunks = k == 0 ? 256u : 32u;
        for (unsigned path = 0; path <= NP_CLASSIC_BATCH_PATHS; path++) {
            uint64_t bad = classic_random(path, &cfgs[k], &r, chunks);
            const char *name = path == NP_CLASSIC_BATCH_PATHS ? "np_classic_eval_n" : classic_path_name[path];
            if (bad == UINT64_MAX) {
                NP_CHECK(k != 0 || path != NP_CLASSIC_BATCH_INT32, "the int32 path must apply to the default");
                printf("classic3 N=%u WS=%u WL=%u %s: does not apply here\n", cfgs[k].out_bits, cfgs[k].s_frac,
                       cfgs[k].lerp_frac, name);
                continue;
            }
            printf("classic3 N=%u WS=%u WL=%u %s: about %u random inputs, %llu mismatches\n", cfgs[k].out_bits,
                   cfgs[k].s_frac, cfgs[k].lerp_frac, name, chunks * CHUNK, (unsigned long long)bad);
        }
    }
    return 0;
}

/*
 * A whole x cell, 2^24 inputs (x cell 0xff, every y, z = 0xff80: every axis
 * wraps), default widths: each specialised path that applies == per input;
 * and the outputs take many values.
 */
static int t_classic_batch_block(void)
{
    static inputs in;
    static int32_t out[NP_CLASSIC_BATCH_PATHS][CHUNK];
    np_classic_cfg cfg = np_classic_cfg_default(8);
    uint64_t bad[NP_CLASSIC_BATCH_PATHS] = { 0 }, seen[4] = { 0 };
    int ran[NP_CLASSIC_BATCH_PATHS] = { 0 };
    for (uint32_t base = 0; base < (1u << 24); base += CHUNK) {
        for (unsigned n = 0; n < CHUNK; n++) {
            uint32_t k = base + n;
            in.x[n] = (uint16_t)(0xff00u | (k & 0xffu));
            in.y[n] = (uint16_t)(k >> 8);
            in.z[n] = 0xff80;
        }
        for (unsigned p = NP_CLASSIC_BATCH_INT32; p < NP_CLASSIC_BATCH_PATHS; p++)
            ran[p] = np_classic_eval_n_path(p, &cfg, in.x, in.y, in.z, out[p], CHUNK) == 0;
        for (unsigned n = 0; n < CHUNK; n++) {
            int32_t want = np_classic_eval(&cfg, in.x[n], in.y[n], in.z[n]);
            seen[(uint32_t)(want + 128) >> 6 & 3u] |= 1ull << ((uint32_t)(want + 128) & 63u);
            for (unsigned p = NP_CLASSIC_BATCH_INT32; p < NP_CLASSIC_BATCH_PATHS; p++)
                if (ran[p] && out[p][n] != want && ++bad[p] <= 5)
                    NP_CHECK(out[p][n] == want, "%s (0x%04x, 0x%04x, 0x%04x): batch %d, eval %d",
                             classic_path_name[p], in.x[n], in.y[n], in.z[n], out[p][n], want);
        }
    }
    unsigned values = 0;
    for (unsigned k = 0; k < 4; k++)
        values += (unsigned)__builtin_popcountll(seen[k]);
    NP_CHECK(ran[NP_CLASSIC_BATCH_INT32], "the int32 path must apply to the default");
    for (unsigned p = NP_CLASSIC_BATCH_INT32; p < NP_CLASSIC_BATCH_PATHS; p++)
        printf("x cell 0xff, z = 0xff80, %s: %s\n", classic_path_name[p],
               ran[p] ? "2^24 inputs compared" : "does not apply here");
    printf("x cell 0xff, z = 0xff80: %llu + %llu mismatches (int32 + avx2), %u distinct outputs\n",
           (unsigned long long)bad[NP_CLASSIC_BATCH_INT32], (unsigned long long)bad[NP_CLASSIC_BATCH_AVX2], values);
    NP_CHECK(values > 100, "the block should exercise most output codes");
    return 0;
}

static int same_out(const np_simplex_out *a, const np_simplex_out *b)
{
    return a->f == b->f && a->df[0] == b->df[0] && a->df[1] == b->df[1] && a->df[2] == b->df[2];
}

static uint64_t simplex_check(const np_simplex_cfg *cfg, const inputs *in, const np_simplex_out *out,
                              unsigned count)
{
    uint64_t bad = 0;
    for (unsigned n = 0; n < count; n++) {
        np_simplex_out want;
        np_simplex_eval(cfg, in->x[n], in->y[n], in->z[n], &want);
        if (!same_out(&out[n], &want) && ++bad <= 5)
            NP_CHECK(same_out(&out[n], &want),
                     "deriv=%u WT=%u (0x%04x, 0x%04x, 0x%04x): batch f=%d df=(%d,%d,%d), eval f=%d df=(%d,%d,%d)",
                     cfg->deriv, cfg->t_frac, in->x[n], in->y[n], in->z[n], out[n].f, out[n].df[0],
                     out[n].df[1], out[n].df[2], want.f, want.df[0], want.df[1], want.df[2]);
    }
    return bad;
}

/* Random inputs at both defaults (the constant-width loops) and two others. */
static int t_simplex_batch_random(void)
{
    static inputs in;
    static np_simplex_out out[CHUNK];
    np_rng r;
    np_rng_seed(&r, 0x6661737432ull);
    np_simplex_cfg cfgs[4] = { np_simplex_cfg_default(16, 16, 1), np_simplex_cfg_default(16, 16, 0),
                               np_simplex_cfg_default(8, 10, 1), np_simplex_cfg_default(20, 20, 1) };
    for (unsigned k = 0; k < 4; k++) {
        uint64_t bad = 0;
        unsigned chunks = k < 2 ? 128u : 16u;
        for (unsigned c = 0; c < chunks; c++) {
            for (unsigned n = 0; n < CHUNK; n++) {
                in.x[n] = rand_word(&r);
                in.y[n] = rand_word(&r);
                in.z[n] = rand_word(&r);
            }
            np_simplex_eval_n(&cfgs[k], in.x, in.y, in.z, out, CHUNK);
            bad += simplex_check(&cfgs[k], &in, out, CHUNK);
        }
        printf("simplex3 N=%u ND=%u deriv=%u: %u random inputs, %llu mismatches\n", cfgs[k].out_bits,
               cfgs[k].dout_bits, cfgs[k].deriv, chunks * CHUNK, (unsigned long long)bad);
    }
    return 0;
}

/* A whole x cell, 2^24 inputs (x cell 0x80, z = 0x7fc1), default with derivative: batch == per input. */
static int t_simplex_batch_block(void)
{
    static inputs in;
    static np_simplex_out out[CHUNK];
    np_simplex_cfg cfg = np_simplex_cfg_default(16, 16, 1);
    uint64_t bad = 0, nonzero = 0;
    for (uint32_t base = 0; base < (1u << 24); base += CHUNK) {
        for (unsigned n = 0; n < CHUNK; n++) {
            uint32_t k = base + n;
            in.x[n] = (uint16_t)(0x8000u | (k & 0xffu));
            in.y[n] = (uint16_t)(k >> 8);
            in.z[n] = 0x7fc1;
        }
        np_simplex_eval_n(&cfg, in.x, in.y, in.z, out, CHUNK);
        bad += simplex_check(&cfg, &in, out, CHUNK);
        for (unsigned n = 0; n < CHUNK; n++)
            nonzero += out[n].f != 0 && out[n].df[2] != 0;
    }
    printf("x cell 0x80, z = 0x7fc1: 2^24 inputs, %llu mismatches, %llu with f and df/dz non-zero\n",
           (unsigned long long)bad, (unsigned long long)nonzero);
    NP_CHECK(nonzero > (1u << 23), "most outputs should be non-zero");
    return 0;
}

static const char *const simplex_path_name[NP_SIMPLEX_BATCH_PATHS] = { "generic", "widths", "int32", "avx2", "avx512" };

/* Words next to the input's edges and to cells of the 8.8 grid. */
static const uint16_t simplex_edge_words[] = { 0x0000, 0x0001, 0x0002, 0x00ff, 0x0100, 0x0101, 0x017f,
                                               0x0180, 0x02ff, 0x7fff, 0x8000, 0x8001, 0xfeff, 0xff00,
                                               0xff01, 0xff7f, 0xff80, 0xfffd, 0xfffe, 0xffff };
enum { EDGE_N = sizeof simplex_edge_words / sizeof simplex_edge_words[0] };

/*
 * Adversarial input number k (any k): the EDGE_N^3 triples of the edge words
 * first, then in turn
 *  - skewed cell boundaries: 4a + b + c within 1 of a multiple of 768 on a
 *    random axis a (the cell decision), the other words random;
 *  - rank ties: two or three offsets equal (the same word on two axes, or
 *    two words 256 m apart), the simplex decision;
 *  - all three words within 8 of 0 or of 0xffff (the wrap).
 */
static void simplex_adversarial(np_rng *r, uint32_t k, uint16_t w[3])
{
    if (k < EDGE_N * EDGE_N * EDGE_N) {
        w[0] = simplex_edge_words[k % EDGE_N];
        w[1] = simplex_edge_words[k / EDGE_N % EDGE_N];
        w[2] = simplex_edge_words[k / (EDGE_N * EDGE_N)];
        return;
    }
    uint64_t v = np_rng_next(r);
    unsigned a = (unsigned)(v % 3u), b = (a + 1u) % 3u, c = (a + 2u) % 3u;
    switch (k % 3u) {
    case 0: { /* SX = 4 w[a] + w[b] + w[c] = 768 m + delta: solve for w[b] */
        w[a] = (uint16_t)(v >> 8);
        w[c] = (uint16_t)(v >> 24);
        int32_t base = 4 * (int32_t)w[a] + w[c], delta = (int32_t)(v >> 40 & 3u) - 1; /* -1, 0, 1, 2 */
        int32_t m = (base + 767) / 768 + (int32_t)(v >> 44 & 63u) % 86;
        int32_t wb = 768 * m + (delta > 1 ? 0 : delta) - base;
        w[b] = wb >= 0 && wb <= 0xffff ? (uint16_t)wb : (uint16_t)(v >> 48);
        break;
    }
    case 1: /* ties: w[a] = w[b] (+ 256 m), sometimes all three */
        w[a] = (uint16_t)(v >> 8);
        w[b] = (uint16_t)(w[a] + ((v >> 24 & 3u) == 0 ? 0u : (unsigned)(v >> 26 & 0xffu) << 8));
        w[c] = (v >> 34 & 1u) ? w[a] : (uint16_t)(v >> 40);
        break;
    default: /* near 0 and 0xffff on every axis */
        for (unsigned i = 0; i < 3; i++) {
            unsigned e = (unsigned)(v >> (8u + 5u * i) & 31u);
            w[i] = (uint16_t)(e < 16u ? e & 7u : 0xfff8u | (e & 7u));
        }
        break;
    }
}

/*
 * Every batch path against np_simplex_eval, at the two defaults and two
 * other configurations: random inputs (a quarter of them boundary
 * fractions, wrapping cells) and the adversarial ones above, counts that
 * leave a tail after the vector steps; through each path that applies and
 * through np_simplex_eval_n. At both defaults WIDTHS and INT32 must apply,
 * AVX2 and AVX512 where the CPU has them.
 */
static int t_simplex_batch_paths(void)
{
    static inputs in;
    static np_simplex_out out[CHUNK];
    np_simplex_cfg cfgs[4] = { np_simplex_cfg_default(16, 16, 1), np_simplex_cfg_default(16, 16, 0),
                               np_simplex_cfg_default(8, 10, 1), np_simplex_cfg_default(20, 20, 1) };
    const uint32_t adv_n = EDGE_N * EDGE_N * EDGE_N + 3u * 16384u;
    for (unsigned k = 0; k < 4; k++) {
        for (unsigned path = 0; path <= NP_SIMPLEX_BATCH_PATHS; path++) {
            np_rng r;
            np_rng_seed(&r, 0x6661737434ull);
            unsigned chunks = k < 2 ? 64u : 8u;
            uint64_t bad = 0, total = 0;
            int applies = 1;
            uint32_t adv = 0;
            for (unsigned c = 0; applies && (c < chunks || adv < adv_n); c++) {
                for (unsigned n = 0; n < CHUNK; n++) {
                    if (c < chunks) {
                        in.x[n] = rand_word(&r);
                        in.y[n] = rand_word(&r);
                        in.z[n] = rand_word(&r);
                    } else {
                        uint16_t w[3];
                        simplex_adversarial(&r, adv++, w);
                        in.x[n] = w[0];
                        in.y[n] = w[1];
                        in.z[n] = w[2];
                    }
                }
                unsigned count = CHUNK - (c & 7u);
                if (path == NP_SIMPLEX_BATCH_PATHS)
                    np_simplex_eval_n(&cfgs[k], in.x, in.y, in.z, out, count);
                else
                    applies = np_simplex_eval_n_path(path, &cfgs[k], in.x, in.y, in.z, out, count) == 0;
                if (applies) {
                    bad += simplex_check(&cfgs[k], &in, out, count);
                    total += count;
                }
            }
            const char *name = path == NP_SIMPLEX_BATCH_PATHS ? "np_simplex_eval_n" : simplex_path_name[path];
            if (!applies) {
                NP_CHECK(k >= 2 || (path != NP_SIMPLEX_BATCH_WIDTHS && path != NP_SIMPLEX_BATCH_INT32),
                         "the %s path must apply to both defaults", name);
                printf("simplex3 N=%u ND=%u deriv=%u %s: does not apply here\n", cfgs[k].out_bits,
                       cfgs[k].dout_bits, cfgs[k].deriv, name);
                continue;
            }
            printf("simplex3 N=%u ND=%u deriv=%u %s: %llu inputs (%u random chunks, then adversarial), %llu mismatches\n",
                   cfgs[k].out_bits, cfgs[k].dout_bits, cfgs[k].deriv, name, (unsigned long long)total, chunks,
                   (unsigned long long)bad);
        }
    }
    return 0;
}

/* All 2^24 lattice points: np_hash6_fast == np_hash6 (the two-nibble-table claim). */
static int t_hash_exhaustive(void)
{
    uint64_t bad = 0, hist[64] = { 0 };
    for (unsigned i = 0; i < 256; i++)
        for (unsigned j = 0; j < 256; j++)
            for (unsigned k = 0; k < 256; k++) {
                uint8_t a = np_hash6((uint8_t)i, (uint8_t)j, (uint8_t)k);
                uint8_t b = np_hash6_fast((uint8_t)i, (uint8_t)j, (uint8_t)k);
                hist[b & 63u]++;
                if (a != b) {
                    bad++;
                    NP_CHECK(a == b, "(%u, %u, %u): spec %u, table %u", i, j, k, a, b);
                }
            }
    unsigned used = 0;
    for (unsigned h = 0; h < 64; h++)
        used += hist[h] != 0;
    printf("2^24 lattice points: %llu mismatches; %u of 64 hash values occur\n",
           (unsigned long long)bad, used);
    NP_CHECK(used == 64, "every 6-bit value should occur (a constant table would pass nothing)");
    return 0;
}

/* All 64 indices: np_grad_fast == np_grad_decode, and 2 or 3 non-zero coefficients. */
static int t_grad_table(void)
{
    unsigned nz3 = 0;
    for (unsigned h = 0; h < 64; h++) {
        np_grad a = np_grad_decode((uint8_t)h), b = np_grad_fast((uint8_t)h);
        NP_CHECK(a.cx == b.cx && a.cy == b.cy && a.cz == b.cz, "h=%u: spec (%d,%d,%d), table (%d,%d,%d)", h,
                 a.cx, a.cy, a.cz, b.cx, b.cy, b.cz);
        unsigned nz = (unsigned)(b.cx != 0) + (unsigned)(b.cy != 0) + (unsigned)(b.cz != 0);
        NP_CHECK(nz == 2 || nz == 3, "h=%u: %u non-zero coefficients", h, nz);
        nz3 += nz == 3;
    }
    printf("64 gradient indices equal; %u with three terms\n", nz3);
    NP_CHECK(nz3 == 16, "b == 0 (16 of 64 indices) has three terms");
    return 0;
}

/*
 * simplex3's sweep kernel == eval/ref per input (np_sweep_rows_generic): every
 * code and every reference double bit for bit, on `calls` kernel calls of
 * NP_SWEEP_ROWS rows starting at (x0 + 256 i, y0 + 8 i) for a given z.
 */
static uint64_t simplex_kernel_check(const char *config, uint16_t xcell, uint16_t z, unsigned y_first,
                                     unsigned y_end, np_rng *r, unsigned random_calls)
{
    const np_unit *u = np_unit_find("simplex3");
    np_unit_cfg cfg;
    char err[256];
    NP_CHECK(u && np_unit_configure(u, &cfg, config, err, sizeof err) == 0, "configure %s", config ? config : "default");
    if (!u || !u->sweep_rows) {
        NP_CHECK(u && u->sweep_rows, "simplex3 has a sweep kernel");
        return 1;
    }
    np_unit_fields f;
    u->fields(&cfg, &f);
    size_t n = (size_t)f.n_out * NP_SWEEP_ROWS * NP_SWEEP_ROW;
    int32_t *c1 = malloc(n * sizeof *c1), *c2 = malloc(n * sizeof *c2);
    double *r1 = malloc(n * sizeof *r1), *r2 = malloc(n * sizeof *r2);
    uint64_t bad = 0;
    unsigned calls = random_calls ? random_calls : (y_end - y_first) / NP_SWEEP_ROWS;
    for (unsigned k = 0; c1 && c2 && r1 && r2 && k < calls; k++) {
        uint16_t x0, y0, zz;
        if (random_calls) {
            uint64_t w = np_rng_next(r);
            x0 = (uint16_t)(w & 0xff00u);
            y0 = (uint16_t)(w >> 16);
            zz = (uint16_t)(w >> 32);
        } else {
            x0 = (uint16_t)(xcell << 8);
            y0 = (uint16_t)(y_first + k * NP_SWEEP_ROWS);
            zz = z;
        }
        unsigned what = NP_SWEEP_MODEL | NP_SWEEP_REF;
        u->sweep_rows(&cfg, x0, y0, zz, NP_SWEEP_ROWS, what, c1, r1);
        np_sweep_rows_generic(u, &cfg, x0, y0, zz, NP_SWEEP_ROWS, what, c2, r2);
        for (size_t i = 0; i < n; i++)
            if ((c1[i] != c2[i] || memcmp(&r1[i], &r2[i], sizeof r1[i]) != 0) && ++bad <= 5) {
                size_t t = i % NP_SWEEP_ROW, row = i / NP_SWEEP_ROW % NP_SWEEP_ROWS,
                       fld = i / ((size_t)NP_SWEEP_ROW * NP_SWEEP_ROWS);
                NP_CHECK(0, "%s field %zu at (0x%04zx, 0x%04zx, 0x%04x): kernel %d %.17g, per input %d %.17g",
                         config ? config : "default", fld, x0 + t, y0 + row, zz, c1[i], r1[i], c2[i], r2[i]);
            }
    }
    free(c1);
    free(c2);
    free(r1);
    free(r2);
    return bad;
}

/*
 * The int32 forms of simplex3's rounded products (np_simplex32.h) ==
 * np_simplex.h's 64-bit ones at the default widths with the derivative:
 * tau2 and tau3(tau2(T), T) for every T < 2^23, tau4 for every tau2 < 2^24,
 * tau3 on 2^22 random (tau2, T) pairs besides, fterm/qterm (tau gd) for
 * every tau < 2^24 at 16 gd from the extremes +-4608 in and random ones,
 * eterm (G_a tau4) for every tau4 < 2^24 and G_a in {-1, 0, 1}, and mterm
 * (5q D) for every D in s12 at 4096 q from the extremes of |q| < 2^25.2; and
 * the value-only default's (WT = 23, WP = 20) tau2, tau4 and fterm alike.
 */
static int t_simplex32_exhaustive(void)
{
    const np_simplex_cfg cfg = np_simplex_cfg_default(16, 16, 1);
    NP_CHECK(cfg.t_frac == 24 && cfg.p_frac == 22 && cfg.k_frac == 22, "default widths WT/WP/WK = 24/22/22 (%u/%u/%u)",
             cfg.t_frac, cfg.p_frac, cfg.k_frac);
    uint64_t bad = 0, n = 0;
    for (int32_t t = 0; t < (1 << 23); t++, n += 2) {
        uint32_t tau2 = np_simplex_tau2(&cfg, (uint32_t)t);
        bad += (uint32_t)m32_tau2(t) != tau2;
        bad += (uint32_t)m32_tau3((int32_t)tau2, t) != np_simplex_tau3(tau2, (uint32_t)t);
    }
    for (int32_t a = 0; a < (1 << 24); a++, n++)
        bad += (uint32_t)m32_tau4(a) != np_simplex_tau4(&cfg, (uint32_t)a);
    np_rng r;
    np_rng_seed(&r, 0x73696d3332ull);
    for (unsigned k = 0; k < (1u << 22); k++, n++) {
        uint64_t w = np_rng_next(&r);
        uint32_t a = (uint32_t)(w & 0xffffffu), t = (uint32_t)(w >> 24 & 0x7fffffu);
        bad += (uint32_t)m32_tau3((int32_t)a, (int32_t)t) != np_simplex_tau3(a, t);
    }
    int32_t gds[16] = { -4608, -4607, -4097, -2048, -1, 0, 1, 2047, 2048, 4096, 4607, 4608 };
    for (unsigned k = 12; k < 16; k++)
        gds[k] = (int32_t)(np_rng_next(&r) % 9217u) - 4608;
    for (int32_t a = 0; a < (1 << 24); a++)
        for (unsigned k = 0; k < 16; k++, n += 2) {
            bad += m32_mul_rq11(a, gds[k]) != np_simplex_fterm(&cfg, (uint32_t)a, gds[k]);
            bad += m32_mul_rq11(a, gds[k]) != np_simplex_qterm(&cfg, (uint32_t)a, gds[k]);
        }
    for (int32_t a = 0; a < (1 << 24); a++)
        for (int32_t c = -1; c <= 1; c++, n++)
            bad += m32_eterm(c, a) != np_simplex_eterm(&cfg, (uint32_t)a, c);
    const int32_t qmax = 37748737; /* 2^24 4608 / 2^11 + 1 > |q| */
    for (unsigned k = 0; k < 4096; k++) {
        int32_t q = k < 8 ? (k & 1 ? -1 : 1) * (qmax - (int32_t)(k >> 1)) : k < 16 ? (int32_t)k - 12
                  : (int32_t)(np_rng_next(&r) % (2u * (uint32_t)qmax + 1u)) - qmax;
        for (int32_t d = -2048; d < 2048; d++, n++)
            bad += m32_mul_rq11(4 * q + q, d) != np_simplex_mterm(q, d);
    }
    /* the value-only default (WT = 23, WP = 20): every T, every tau2 < 2^23, every tau4 < 2^23 at the 16 gd */
    const np_simplex_cfg cf = np_simplex_cfg_default(16, 16, 0);
    NP_CHECK(cf.t_frac == 23 && cf.p_frac == 20 && cf.k_frac == 22, "value-only widths WT/WP/WK = 23/20/22 (%u/%u/%u)",
             cf.t_frac, cf.p_frac, cf.k_frac);
    for (int32_t t = 0; t < (1 << 23); t++, n += 2) {
        bad += (uint32_t)m32_tau2_23(t) != np_simplex_tau2(&cf, (uint32_t)t);
        bad += (uint32_t)m32_tau4_23(t) != np_simplex_tau4(&cf, (uint32_t)t);
    }
    for (int32_t a = 0; a < (1 << 23); a++)
        for (unsigned k = 0; k < 16; k++, n++)
            bad += m32_mul_rq12(a, gds[k]) != np_simplex_fterm(&cf, (uint32_t)a, gds[k]);
    NP_CHECK(bad == 0, "%llu of %llu int32 products differ from np_simplex.h's", (unsigned long long)bad,
             (unsigned long long)n);
    printf("simplex3 int32 products (WT/WP = 24/22 and 23/20): %llu compared, %llu differ\n", (unsigned long long)n,
           (unsigned long long)bad);
    return 0;
}

/* A whole x cell (2^24 inputs), x cell 0xff at z = 0xfff1 (the input words wrap), default config. */
static int t_simplex_kernel_block(void)
{
    uint64_t bad = simplex_kernel_check(NULL, 0xff, 0xfff1, 0, 65536, NULL, 0);
    printf("simplex3 sweep kernel, x cell 0xff, z = 0xfff1: 2^24 inputs, %llu mismatching inputs\n",
           (unsigned long long)bad);
    return 0;
}

/*
 * Random kernel calls (x cell, y, z random) in four configurations, with the
 * reference row's selects in each form (masked `?:` and bit patterns,
 * np_sweep_simplex3_force_bits), whichever the CPU would pick.
 */
static int t_simplex_kernel_random(void)
{
    static const char *const configs[] = { NULL, "deriv=0", "out_bits=8,dout_bits=10", "t_frac=12,p_frac=10" };
    np_rng r;
    np_rng_seed(&r, 0x6661737433ull);
    for (int bits = 0; bits <= 1; bits++) {
        np_sweep_simplex3_force_bits(bits);
        for (unsigned k = 0; k < 4; k++) {
            uint64_t bad = simplex_kernel_check(configs[k], 0, 0, 0, 0, &r, 200);
            printf("simplex3 sweep kernel, %s, reference selects %s: 200 random calls (409600 inputs), %llu mismatches\n",
                   configs[k] ? configs[k] : "default", bits ? "on bits" : "as ?:", (unsigned long long)bad);
        }
    }
    np_sweep_simplex3_force_bits(-1);
    return 0;
}

/*
 * The cycle models without bundle copies (np_pipe rotates bank slots) against
 * the copying model: two pipes of the same unit driven by the same random
 * valid/ready streams must agree every cycle on in_ready, out_valid and the
 * whole output bundle, and end with the same statistics.
 */
static uint64_t pipe_pair(const char *unit, const char *config, int in_reg, int out_skid, uint64_t cycles)
{
    const np_unit *u = np_unit_find(unit);
    np_unit_cfg cfg;
    char err[256];
    if (!u || np_unit_configure(u, &cfg, config, err, sizeof err) != 0) {
        NP_CHECK(0, "configure %s", unit);
        return 1;
    }
    np_pipe a, b;
    if (u->pipe_init(&a, &cfg) != 0 || u->pipe_init(&b, &cfg) != 0) {
        NP_CHECK(0, "pipe_init %s", unit);
        return 1;
    }
    b.copy_banks = 1;
    a.in_reg = b.in_reg = in_reg;
    a.out_skid = b.out_skid = out_skid;
    unsigned char *in = calloc(1, a.sig_size);
    np_rng r;
    np_rng_seed(&r, 0x70697065ull);
    uint64_t bad = 0, delivered = 0;
    np_pipe_port pa, pb;
    memset(&pa, 0, sizeof pa);
    memset(&pb, 0, sizeof pb);
    for (uint64_t c = 0; in && c < cycles; c++) {
        uint64_t w = np_rng_next(&r);
        uint64_t v[NP_UNIT_MAX_FIELDS] = { w & 0xffffu, w >> 16 & 0xffffu, w >> 32 & 0xffffu };
        u->sig_set_in(in, v);
        pa.in_valid = pb.in_valid = (w >> 48 & 3u) != 0;
        pa.out_ready = pb.out_ready = (w >> 50 & 3u) != 0;
        pa.in_sig = pb.in_sig = in;
        np_pipe_eval(&a, &pa);
        np_pipe_eval(&b, &pb);
        int same = pa.in_ready == pb.in_ready && pa.out_valid == pb.out_valid &&
                   (!pa.out_valid || memcmp(pa.out_sig, pb.out_sig, a.sig_size) == 0);
        if (!same && ++bad <= 5)
            NP_CHECK(same, "%s in_reg=%d out_skid=%d cycle %llu: rotating and copying pipes differ", unit, in_reg,
                     out_skid, (unsigned long long)c);
        delivered += pa.out_valid && pa.out_ready;
        np_pipe_clock(&a, &pa);
        np_pipe_clock(&b, &pb);
    }
    NP_CHECK(memcmp(&a.stats, &b.stats, sizeof a.stats) == 0, "%s: statistics differ", unit);
    NP_CHECK(delivered > cycles / 4, "%s: %llu outputs in %llu cycles", unit, (unsigned long long)delivered,
             (unsigned long long)cycles);
    free(in);
    np_pipe_free(&a);
    np_pipe_free(&b);
    return bad;
}

static int t_pipe_no_copy(void)
{
    static const struct { const char *unit, *config; } v[] = {
        { "classic3", NULL }, { "simplex3", NULL }, { "simplex3", "deriv=0" },
    };
    for (unsigned i = 0; i < 3; i++)
        for (int opt = 0; opt < 4; opt++) {
            uint64_t bad = pipe_pair(v[i].unit, v[i].config, opt & 1, opt >> 1, 200000);
            printf("%s%s%s in_reg=%d out_skid=%d: 200000 random cycles, %llu differing cycles\n", v[i].unit,
                   v[i].config ? " " : "", v[i].config ? v[i].config : "", opt & 1, opt >> 1,
                   (unsigned long long)bad);
        }
    return 0;
}

/*
 * The per-input references' branch-free gradient (np_ref_fast.h) against
 * Appendix B's transcription np_ref_grad: every h, on points with signed
 * zeros, halves, ones and random values; every result's bits (-0.0
 * included). The coefficient table against np_ref_grad at the unit vectors,
 * its zeros +0.0.
 */
static int t_ref_grad_fast(void)
{
    static const double pick[] = { 0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 0x1p-30, -0.75, 0.125 };
    enum { NP_ = sizeof pick / sizeof pick[0] };
    np_rng r;
    np_rng_seed(&r, 0x6772616466ull);
    uint64_t bad = 0, n = 0;
    for (unsigned h = 0; h < 64; h++) {
        for (unsigned a = 0; a < NP_ * NP_ * NP_ + 4096u; a++, n++) {
            double x, y, z;
            if (a < NP_ * NP_ * NP_) {
                x = pick[a % NP_];
                y = pick[a / NP_ % NP_];
                z = pick[a / (NP_ * NP_)];
            } else {
                x = (double)(int32_t)(uint32_t)np_rng_next(&r) / 0x1p31;
                y = (double)(int32_t)(uint32_t)np_rng_next(&r) / 0x1p31;
                z = (double)(int32_t)(uint32_t)np_rng_next(&r) / 0x1p31;
            }
            double want = np_ref_grad(h, x, y, z), got = np_ref_grad_fast(h, x, y, z);
            if (memcmp(&want, &got, sizeof want) != 0 && ++bad <= 5)
                NP_CHECK(0, "h=%u at (%a, %a, %a): np_ref_grad %a, fast %a", h, x, y, z, want, got);
        }
        for (unsigned a = 0; a < 3; a++) {
            double want = np_ref_grad(h, a == 0, a == 1, a == 2), got = np_ref_grad_coef[h][a];
            NP_CHECK(want == got && (got != 0.0 || !signbit(got)), "h=%u axis %u: coefficient %g, Appendix B %g", h,
                     a, got, want);
        }
    }
    printf("np_ref_grad_fast: %llu (h, point) pairs, %llu differing results\n", (unsigned long long)n,
           (unsigned long long)bad);
    return 0;
}

static const np_test_case cases[] = {
    { "ref_grad_fast", t_ref_grad_fast },
    { "hash_exhaustive", t_hash_exhaustive },
    { "grad_table", t_grad_table },
    { "classic_batch_random", t_classic_batch_random },
    { "classic_batch_block", t_classic_batch_block },
    { "simplex_batch_random", t_simplex_batch_random },
    { "simplex_batch_block", t_simplex_batch_block },
    { "simplex_batch_paths", t_simplex_batch_paths },
    { "simplex_kernel_block", t_simplex_kernel_block },
    { "simplex_kernel_random", t_simplex_kernel_random },
    { "simplex32_exhaustive", t_simplex32_exhaustive },
    { "pipe_no_copy", t_pipe_no_copy },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
