/* SPDX-License-Identifier: MIT */
#include "np_classic.h"

#include <stddef.h>

/*
 * Input word ruler (each of x, y, z):
 *   15            8 7             0
 *  +---------------+---------------+
 *  |  cell (u8)    | fraction u8   |
 *  +---------------+---------------+
 */
enum { POS_IN_FRAC = 0, SIZE_IN_FRAC = 8, POS_IN_CELL = 8, SIZE_IN_CELL = 8 };

static uint8_t in_cell(uint16_t x) { return (uint8_t)((x >> POS_IN_CELL) & NP_MASK(SIZE_IN_CELL)); }
static uint8_t in_frac(uint16_t x) { return (uint8_t)((x >> POS_IN_FRAC) & NP_MASK(SIZE_IN_FRAC)); }

np_classic_cfg np_classic_cfg_default(unsigned out_bits)
{
    np_classic_cfg c;
    c.out_bits = out_bits;
    c.s_frac = out_bits - 2u + 6u;
    if (c.s_frac > NP_CLASSIC_WS_MAX)
        c.s_frac = NP_CLASSIC_WS_MAX;
    c.lerp_frac = out_bits - 2u + 5u;
    return c;
}

const char *np_classic_cfg_check(const np_classic_cfg *cfg)
{
    if (cfg->out_bits < NP_CLASSIC_OUT_MIN || cfg->out_bits > NP_CLASSIC_OUT_MAX)
        return "out_bits must be 2..16";
    if (cfg->s_frac < NP_CLASSIC_WS_MIN || cfg->s_frac > NP_CLASSIC_WS_MAX)
        return "s_frac must be 1..24";
    if (cfg->lerp_frac < np_classic_out_frac(cfg) || cfg->lerp_frac > NP_CLASSIC_WL_MAX)
        return "lerp_frac must be out_bits-2..30";
    return NULL;
}

/* 2^e for small |e|, exact, without libm. */
static double pow2i(int e)
{
    double r = 1.0;
    for (; e > 0; e--)
        r *= 2.0;
    for (; e < 0; e++)
        r *= 0.5;
    return r;
}

double np_classic_error_bound_lsb(const np_classic_cfg *cfg)
{
    int f = (int)np_classic_out_frac(cfg);
    double es = cfg->s_frac >= NP_CLASSIC_SNUM_BITS ? 0.0 : 3.0 * pow2i(f - (int)cfg->s_frac);
    double el = pow2i(f - (int)cfg->lerp_frac - 1);
    return 0.5 + 3.0 * (es + el);
}

void np_classic_cell_setup(uint8_t i, uint8_t j, uint8_t k, np_classic_cell *cell)
{
    for (unsigned c = 0; c < 8; c++) {
        uint8_t ci = (uint8_t)(i + (c & 1u)), cj = (uint8_t)(j + ((c >> 1) & 1u)),
                ck = (uint8_t)(k + ((c >> 2) & 1u)); /* wrap mod 256 */
        cell->g[c] = np_grad_decode(np_hash6(ci, cj, ck));
    }
}

int32_t np_classic_eval(const np_classic_cfg *cfg, uint16_t x, uint16_t y, uint16_t z)
{
    np_classic_cell cell;
    np_classic_cell_setup(in_cell(x), in_cell(y), in_cell(z), &cell);
    return np_classic_eval_in_cell(cfg, &cell, in_frac(x), in_frac(y), in_frac(z));
}

/* --- Pipeline stages: the same primitives, split at the register banks. --- */

static np_classic_sig *sig_of(void *s) { return (np_classic_sig *)s; }

/* L: corner hashes; S first half: squares of the fractions. */
static void stage_l(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_classic_sig *s = sig_of(sv);
    uint8_t i = in_cell(s->x), j = in_cell(s->y), k = in_cell(s->z);
    for (unsigned c = 0; c < 8; c++)
        s->h[c] = np_hash6((uint8_t)(i + (c & 1u)), (uint8_t)(j + ((c >> 1) & 1u)),
                           (uint8_t)(k + ((c >> 2) & 1u)));
    const uint16_t in[3] = { s->x, s->y, s->z };
    for (unsigned a = 0; a < 3; a++) {
        uint32_t f = in_frac(in[a]);
        s->s2[a] = f * f;
    }
}

/* H: gradient decode and contribution; S second half: the s-curve. */
static void stage_h(const void *cfgv, void *sv)
{
    const np_classic_cfg *cfg = cfgv;
    np_classic_sig *s = sig_of(sv);
    const uint16_t in[3] = { s->x, s->y, s->z };
    int16_t d[2][3];
    for (unsigned a = 0; a < 3; a++) {
        d[0][a] = (int16_t)in_frac(in[a]);
        d[1][a] = (int16_t)(in_frac(in[a]) - 256);
        uint32_t num = s->s2[a] * (uint32_t)(768u - 2u * in_frac(in[a]));
        s->s[a] = (uint32_t)np_shr_round_half_up_u(num, NP_CLASSIC_SNUM_BITS - cfg->s_frac);
    }
    for (unsigned c = 0; c < 8; c++)
        s->g[c] = np_grad_apply_q8(np_grad_decode(s->h[c]), d[c & 1u][0], d[(c >> 1) & 1u][1],
                                   d[(c >> 2) & 1u][2]);
}

static void stage_i1m(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_classic_sig *s = sig_of(sv);
    for (unsigned p = 0; p < 4; p++)
        s->prod[p] = np_classic_lerp_mul(s->s[0], s->g[2 * p], s->g[2 * p + 1]);
}

static void stage_i1a(const void *cfgv, void *sv)
{
    np_classic_sig *s = sig_of(sv);
    for (unsigned p = 0; p < 4; p++)
        s->l1[p] = np_classic_lerp_add(cfgv, s->g[2 * p], NP_CLASSIC_FRAC_IN, s->prod[p]);
}

static void stage_i2m(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_classic_sig *s = sig_of(sv);
    for (unsigned p = 0; p < 2; p++)
        s->prod[p] = np_classic_lerp_mul(s->s[1], s->l1[2 * p], s->l1[2 * p + 1]);
}

static void stage_i2a(const void *cfgv, void *sv)
{
    const np_classic_cfg *cfg = cfgv;
    np_classic_sig *s = sig_of(sv);
    for (unsigned p = 0; p < 2; p++)
        s->l2[p] = np_classic_lerp_add(cfg, s->l1[2 * p], cfg->lerp_frac, s->prod[p]);
}

static void stage_i3m(const void *cfgv, void *sv)
{
    (void)cfgv;
    np_classic_sig *s = sig_of(sv);
    s->prod[0] = np_classic_lerp_mul(s->s[2], s->l2[0], s->l2[1]);
}

static void stage_i3a(const void *cfgv, void *sv)
{
    const np_classic_cfg *cfg = cfgv;
    np_classic_sig *s = sig_of(sv);
    s->l3 = np_classic_lerp_add(cfg, s->l2[0], cfg->lerp_frac, s->prod[0]);
}

static void stage_o(const void *cfgv, void *sv)
{
    np_classic_sig *s = sig_of(sv);
    s->out = np_classic_output(cfgv, s->l3);
}

const np_stage_desc np_classic_stages[NP_CLASSIC_STAGES] = {
    { "L", stage_l },     { "H", stage_h },     { "I1m", stage_i1m },
    { "I1a", stage_i1a }, { "I2m", stage_i2m }, { "I2a", stage_i2a },
    { "I3m", stage_i3m }, { "I3a", stage_i3a }, { "O", stage_o },
};

int np_classic_pipe_init(np_pipe *p, const np_classic_cfg *cfg)
{
    return np_pipe_init(p, np_classic_stages, NP_CLASSIC_STAGES, sizeof(np_classic_sig), cfg);
}
