/* SPDX-License-Identifier: MIT */
/*
 * The fast paths against the specification (issue 13): the table-driven
 * hash and gradient decode (np_hash.h) against the seed's bit loop, every
 * argument.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "np_classic.h"
#include "np_hash.h"
#include "np_rng.h"
#include "np_simplex.h"
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

/* Classic: batch == per input over `chunks` chunks of random inputs; returns mismatches. */
static uint64_t classic_random(const np_classic_cfg *cfg, np_rng *r, unsigned chunks)
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
        np_classic_eval_n(cfg, in.x, in.y, in.z, out, CHUNK);
        for (unsigned n = 0; n < CHUNK; n++) {
            int32_t want = np_classic_eval(cfg, in.x[n], in.y[n], in.z[n]);
            if (out[n] != want && ++bad <= 5)
                NP_CHECK(out[n] == want, "N=%u WS=%u WL=%u (0x%04x, 0x%04x, 0x%04x): batch %d, eval %d",
                         cfg->out_bits, cfg->s_frac, cfg->lerp_frac, in.x[n], in.y[n], in.z[n], out[n], want);
        }
    }
    return bad;
}

/* 2^20 random inputs at the default (the int32 path) and three others (the generic path). */
static int t_classic_batch_random(void)
{
    np_rng r;
    np_rng_seed(&r, 0x6661737431ull);
    np_classic_cfg cfgs[4] = { np_classic_cfg_default(8), np_classic_cfg_default(16),
                               { 8, 6, 6 }, { 12, 24, 10 } };
    for (unsigned k = 0; k < 4; k++) {
        NP_CHECK(np_classic_cfg_check(&cfgs[k]) == NULL, "config %u", k);
        uint64_t bad = classic_random(&cfgs[k], &r, k == 0 ? 256u : 32u);
        printf("classic3 N=%u WS=%u WL=%u: %u random inputs, %llu mismatches\n", cfgs[k].out_bits,
               cfgs[k].s_frac, cfgs[k].lerp_frac, (k == 0 ? 256u : 32u) * CHUNK, (unsigned long long)bad);
    }
    return 0;
}

/*
 * A whole x cell, 2^24 inputs (x cell 0xff, every y, z = 0xff80: every axis
 * wraps), default widths: batch == per input; and the outputs take many values.
 */
static int t_classic_batch_block(void)
{
    static inputs in;
    static int32_t out[CHUNK];
    np_classic_cfg cfg = np_classic_cfg_default(8);
    uint64_t bad = 0, seen[4] = { 0 };
    for (uint32_t base = 0; base < (1u << 24); base += CHUNK) {
        for (unsigned n = 0; n < CHUNK; n++) {
            uint32_t k = base + n;
            in.x[n] = (uint16_t)(0xff00u | (k & 0xffu));
            in.y[n] = (uint16_t)(k >> 8);
            in.z[n] = 0xff80;
        }
        np_classic_eval_n(&cfg, in.x, in.y, in.z, out, CHUNK);
        for (unsigned n = 0; n < CHUNK; n++) {
            int32_t want = np_classic_eval(&cfg, in.x[n], in.y[n], in.z[n]);
            seen[(uint32_t)(want + 128) >> 6 & 3u] |= 1ull << ((uint32_t)(want + 128) & 63u);
            if (out[n] != want && ++bad <= 5)
                NP_CHECK(out[n] == want, "(0x%04x, 0x%04x, 0x%04x): batch %d, eval %d", in.x[n], in.y[n],
                         in.z[n], out[n], want);
        }
    }
    unsigned values = 0;
    for (unsigned k = 0; k < 4; k++)
        values += (unsigned)__builtin_popcountll(seen[k]);
    printf("x cell 0xff, z = 0xff80: 2^24 inputs, %llu mismatches, %u distinct outputs\n",
           (unsigned long long)bad, values);
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

static const np_test_case cases[] = {
    { "hash_exhaustive", t_hash_exhaustive },
    { "grad_table", t_grad_table },
    { "classic_batch_random", t_classic_batch_random },
    { "classic_batch_block", t_classic_batch_block },
    { "simplex_batch_random", t_simplex_batch_random },
    { "simplex_batch_block", t_simplex_batch_block },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
