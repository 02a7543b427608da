/* SPDX-License-Identifier: MIT */
#include "np_classicn.h"

#include <string.h>

/* Input word ruler as in np_classic.c: bits 15..8 the cell, 7..0 the fraction. */
enum { POS_IN_FRAC = 0, SIZE_IN_FRAC = 8, POS_IN_CELL = 8, SIZE_IN_CELL = 8 };

static uint8_t in_cell(uint16_t x) { return (uint8_t)((x >> POS_IN_CELL) & NP_MASK(SIZE_IN_CELL)); }
static uint8_t in_frac(uint16_t x) { return (uint8_t)((x >> POS_IN_FRAC) & NP_MASK(SIZE_IN_FRAC)); }

np_classicn_cfg np_classicn_cfg_default(unsigned dims, unsigned out_bits)
{
    np_classicn_cfg c;
    c.dims = dims;
    c.out_bits = out_bits;
    unsigned f = out_bits - np_classicn_int_bits(dims);
    c.s_frac = f + (dims <= 3u ? 6u : 7u);
    if (c.s_frac > NP_CLASSICN_WS_MAX)
        c.s_frac = NP_CLASSICN_WS_MAX;
    c.lerp_frac = f + 5u;
    return c;
}

const char *np_classicn_cfg_check(const np_classicn_cfg *cfg)
{
    if (cfg->dims < 2u || cfg->dims > NP_CLASSICN_MAX)
        return "dims must be 2..5";
    if (cfg->out_bits < NP_CLASSICN_OUT_MIN || cfg->out_bits > NP_CLASSICN_OUT_MAX)
        return "out_bits must be 4..16";
    if (cfg->s_frac < 1u || cfg->s_frac > NP_CLASSICN_WS_MAX)
        return "s_frac must be 1..24";
    if (cfg->lerp_frac < np_classicn_out_frac(cfg) || cfg->lerp_frac > NP_CLASSICN_WL_MAX)
        return "lerp_frac must be out_bits-I..30";
    return NULL;
}

double np_classicn_error_bound_lsb(const np_classicn_cfg *cfg)
{
    int f = (int)np_classicn_out_frac(cfg);
    double n = (double)cfg->dims;
    double es = cfg->s_frac >= NP_CLASSICN_SNUM_BITS ? 0.0 : n * np_pow2i(f - (int)cfg->s_frac);
    double el = np_pow2i(f - (int)cfg->lerp_frac - 1);
    return 0.5 + n * (es + el);
}

/* --- Primitives: the classic3 ones (np_classic.h), with the configuration's widths --- */

static uint32_t scurve(const np_classicn_cfg *cfg, uint32_t u2, uint8_t u)
{
    uint32_t num = u2 * (uint32_t)(768u - 2u * u); /* u24 Q0.24, exact */
    return (uint32_t)np_shr_round_half_up_u(num, NP_CLASSICN_SNUM_BITS - cfg->s_frac);
}

/* round(a + product) to WL bits; a has fa fraction bits, the product fa + WS. */
static int64_t lerp_add(const np_classicn_cfg *cfg, int64_t a, unsigned fa, int64_t prod)
{
    int64_t sum = np_shl(a, cfg->s_frac) + prod;
    unsigned f = fa + cfg->s_frac;
    return f >= cfg->lerp_frac ? np_shr_round_half_up(sum, f - cfg->lerp_frac) : np_shl(sum, cfg->lerp_frac - f);
}

/* --- Stages --- */

static const np_classicn_cfg *ccfg(const void *c) { return c; }

static void stage_l(const void *cfgv, void *sv)
{
    unsigned n = ccfg(cfgv)->dims;
    np_classicn_sig *s = sv;
    for (unsigned c = 0; c < (1u << n); c++) {
        uint8_t pt[NP_CLASSICN_MAX] = { 0 };
        for (unsigned a = 0; a < n; a++)
            pt[a] = (uint8_t)(in_cell(s->x[a]) + (c >> a & 1u)); /* wrap mod 256 */
        s->h[c] = np_hashn(n, pt);
    }
    for (unsigned a = 0; a < n; a++) {
        uint32_t f = in_frac(s->x[a]);
        s->s2[a] = f * f;
    }
}

static void stage_h(const void *cfgv, void *sv)
{
    const np_classicn_cfg *cfg = cfgv;
    unsigned n = cfg->dims;
    np_classicn_sig *s = sv;
    int16_t d[2][NP_CLASSICN_MAX];
    for (unsigned a = 0; a < n; a++) {
        uint8_t u = in_frac(s->x[a]);
        d[0][a] = (int16_t)u;
        d[1][a] = (int16_t)(u - 256);
        s->s[a] = scurve(cfg, s->s2[a], u);
    }
    for (unsigned c = 0; c < (1u << n); c++) {
        int8_t coef[NP_CLASSICN_MAX];
        np_gradn_decode(n, s->h[c], coef);
        int32_t g = 0;
        for (unsigned a = 0; a < n; a++)
            g += coef[a] * d[c >> a & 1u][a];
        s->g[c] = (int16_t)g;
    }
}

/* Level lvl (0-based) multiply: pairs along axis lvl of the previous level's values. */
static void stage_im(const void *cfgv, void *sv, unsigned lvl)
{
    unsigned n = ccfg(cfgv)->dims, cnt = 1u << (n - 1u - lvl);
    np_classicn_sig *s = sv;
    for (unsigned p = 0; p < cnt; p++) {
        int64_t a = lvl == 0 ? s->g[2 * p] : s->l[2 * p], b = lvl == 0 ? s->g[2 * p + 1] : s->l[2 * p + 1];
        s->opa[p] = a;
        s->prod[p] = (int64_t)s->s[lvl] * (b - a);
    }
}

static void stage_ia(const void *cfgv, void *sv, unsigned lvl)
{
    const np_classicn_cfg *cfg = cfgv;
    unsigned n = cfg->dims, cnt = 1u << (n - 1u - lvl);
    np_classicn_sig *s = sv;
    for (unsigned p = 0; p < cnt; p++)
        s->l[p] = lerp_add(cfg, s->opa[p], lvl == 0 ? NP_CLASSICN_FRAC_IN : cfg->lerp_frac, s->prod[p]);
}

#define LEVEL(k)                                                                  \
    static void stage_i##k##m(const void *c, void *s) { stage_im(c, s, k - 1u); } \
    static void stage_i##k##a(const void *c, void *s) { stage_ia(c, s, k - 1u); }
LEVEL(1)
LEVEL(2)
LEVEL(3)
LEVEL(4)
LEVEL(5)

static void stage_o(const void *cfgv, void *sv)
{
    const np_classicn_cfg *cfg = cfgv;
    np_classicn_sig *s = sv;
    int64_t r = np_shr_round_half_up(s->l[0], cfg->lerp_frac - np_classicn_out_frac(cfg));
    s->out = (int32_t)np_sat_s(r, cfg->out_bits);
}

#define IM(k) { "I" #k "m", stage_i##k##m }, { "I" #k "a", stage_i##k##a }
static const np_stage_desc st2[] = { { "L", stage_l }, { "H", stage_h }, IM(1), IM(2), { "O", stage_o } };
static const np_stage_desc st3[] = { { "L", stage_l }, { "H", stage_h }, IM(1), IM(2), IM(3), { "O", stage_o } };
static const np_stage_desc st4[] = { { "L", stage_l }, { "H", stage_h }, IM(1), IM(2), IM(3), IM(4), { "O", stage_o } };
static const np_stage_desc st5[] = { { "L", stage_l }, { "H", stage_h }, IM(1), IM(2), IM(3), IM(4), IM(5),
                                     { "O", stage_o } };

const np_stage_desc *np_classicn_stage_table(unsigned dims)
{
    switch (dims) {
    case 2: return st2;
    case 3: return st3;
    case 4: return st4;
    default: return st5;
    }
}

int32_t np_classicn_eval(const np_classicn_cfg *cfg, const uint16_t *x)
{
    np_classicn_sig s;
    memset(&s, 0, sizeof s);
    memcpy(s.x, x, cfg->dims * sizeof x[0]);
    const np_stage_desc *st = np_classicn_stage_table(cfg->dims);
    for (unsigned k = 0; k < np_classicn_stage_count(cfg->dims); k++)
        st[k].fn(cfg, &s);
    return s.out;
}

int np_classicn_pipe_init(np_pipe *p, const np_classicn_cfg *cfg)
{
    return np_pipe_init(p, np_classicn_stage_table(cfg->dims), np_classicn_stage_count(cfg->dims),
                        sizeof(np_classicn_sig), cfg);
}

/* --- Datapath declaration (np_classic_datapath's, n-D) --- */

/* The traced signals of the interpolation levels: difference, product, sum, value. */
static const char *const names[NP_CLASSICN_MAX][4] = {
    { "diff1", "prod1", "sum1", "l1" }, { "diff2", "prod2", "sum2", "l2" }, { "diff3", "prod3", "sum3", "l3" },
    { "diff4", "prod4", "sum4", "l4" }, { "diff5", "prod5", "sum5", "l5" }
};

/*
 * count adder trees of m operands, priced at w bits below the last level and
 * wl at it; the last level's signal sig traced at out bits. The first free level.
 */
static unsigned tree(np_dp *d, const char *stage, const char *sig, unsigned count, unsigned m, unsigned w,
                     unsigned wl, unsigned out, int sgn, unsigned level0)
{
    unsigned lv = level0;
    while (m > 1u) {
        unsigned adders = m / 2u;
        m -= adders;
        np_dp_op(d, stage, m == 1u ? sig : NULL, NP_OP_ADD, count * adders, m == 1u ? wl : w, 0, m == 1u ? out : 0u,
                 m == 1u ? sgn : 0, lv++);
    }
    return lv;
}

/* Smallest v with b < 2^v (integer bits besides the sign of a value bounded by b). */
static unsigned int_bits(double b)
{
    unsigned v = 0;
    while (b >= np_pow2i((int)v))
        v++;
    return v;
}

size_t np_classicn_datapath(const np_classicn_cfg *cfg, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    unsigned n = cfg->dims, nc = 1u << n, ws = cfg->s_frac, wl = cfg->lerp_frac, nb = cfg->out_bits;
    unsigned f = np_classicn_out_frac(cfg), sw = ws + 1u, lookups = np_hashn_lookups(n);
    unsigned gb = np_bits_for_range(-(int64_t)np_gradn_max_terms(n) * 256, (int64_t)np_gradn_max_terms(n) * 256, 1);
    /*
     * L: cell + 1 (n 8-bit incrementers), the lookups, an adder tree per
     * corner; u * u per axis (a squarer). The gradient reads only the hash's
     * low hb bits (np_gradn_index_bits: 3 at n = 2, 5 at n = 4, 5): the tree
     * is a sum mod 2^hb and the bank holds hb bits a corner (Yosys drops the
     * rest; classic2's L was 31 % over synthesis with 6-bit adders). The
     * traced h keeps the index's 6 bits (the value np_hashn specifies).
     */
    unsigned hb = np_gradn_index_bits(n);
    np_dp_op(&d, "L", NULL, NP_OP_INC, n, 8, 0, 0, 0, 0);
    np_dp_op(&d, "L", NULL, NP_OP_LUT, nc * lookups, 3, hb, 0, 0, 1);
    tree(&d, "L", "h", nc, lookups, hb, hb, 6, 0, 2);
    np_dp_op(&d, "L", "s2", NP_OP_SQR, n, 8, 0, 16, 0, 0);
    np_dp_op(&d, "L", NULL, NP_OP_REG, 1, n * 8 + nc * hb + n * 16 + 1, 0, 0, 0, 0);
    /*
     * H: the sum over n axes of G_ca d_ca. n = 3 is classic3's circuit: a
     * 3:1 select of the offset for each of p, q, r, a 10-bit negate, two
     * additions (np_classic_datapath). np_classicn.v at n = 2, 4, 5 adds,
     * subtracts or skips each axis's s9 offset as its coefficient in
     * {-1, 0, 1} says: a 10-bit conditional negate per axis, whose zero case
     * folds into its XOR stage (no select; measured per corner alone: 235-248
     * NAND2 at n = 2, 624-628 at n = 4, 616-622 at n = 5, against 218, 516
     * and 674 so declared, and 326, 732, 944 with a 3:1 select per axis).
     */
    /*
     * At n = 5 every coefficient is +-1, so g_c's bit 0 is the parity of the
     * u_a's bits 0 at every corner: one XOR tree and one flip-flop for all 2^n
     * corners (Yosys merges them: classic5's H bank 31 bits under the
     * declaration); the negates and the sums start at bit 1.
     */
    unsigned lsb = n == 5u ? 1u : 0u;
    if (n == 3u)
        np_dp_op(&d, "H", NULL, NP_OP_MUX, nc * n, 9, 3, 0, 0, 0);
    np_dp_op(&d, "H", NULL, NP_OP_NEG, nc * n, 10 - lsb, 0, 0, 0, 1);
    if (lsb)
        for (unsigned m = n, lv = 1; m > 1u; lv++) { /* the shared parity: n - 1 XORs as 2:1 selects of one bit */
            unsigned x = m / 2u;
            m -= x;
            np_dp_op(&d, "H", NULL, NP_OP_MUX, x, 1, 2, 0, 0, lv);
        }
    tree(&d, "H", "g", nc, n, 10 - lsb, gb - lsb, gb, 1, 2); /* the traced g keeps its word's gb bits */
    /* S second half: 768 - 2u (a constant minus x: an incrementer), the product, + half an LSB. */
    np_dp_op(&d, "H", NULL, NP_OP_INC, n, 10, 0, 0, 0, 0);
    np_dp_op(&d, "H", "snum", NP_OP_MUL, n, 16, 10, NP_CLASSICN_SNUM_BITS, 0, 1);
    if (ws < NP_CLASSICN_SNUM_BITS)
        np_dp_op(&d, "H", "s", NP_OP_INC, n, sw, 0, sw, 0, 2);
    np_dp_op(&d, "H", NULL, NP_OP_REG, 1, nc * (gb - lsb) + lsb + n * sw + 1, 0, 0, 0, 0);
    /* I: n levels; |l_m| <= m/2 + (n - m), the operands of level m are level m - 1's (|g| <= n). */
    static const char *const mst[NP_CLASSICN_MAX] = { "I1m", "I2m", "I3m", "I4m", "I5m" };
    static const char *const ast[NP_CLASSICN_MAX] = { "I1a", "I2a", "I3a", "I4a", "I5a" };
    /*
     * n = 4: the last level and the output are declared from the proved
     * |noise| <= 2 (I = 3), which the traced inputs do not approach (largest
     * |f| seen 1.02): two bits over the traced range, more than the width
     * check's margin, so those three signals are declared untraced (NULL).
     */
    int last_traced = n != 4u;
    unsigned vi_last = 0, zin = 0;
    for (unsigned lvl = 0; lvl < n; lvl++) {
        unsigned cnt = nc >> (lvl + 1u);
        double opb = lvl == 0 ? (double)n : 0.5 * lvl + (double)(n - lvl);
        unsigned vi = int_bits(0.5 * (lvl + 1u) + (double)(n - lvl - 1u));
        unsigned af = lvl == 0 ? NP_CLASSICN_FRAC_IN : wl;
        unsigned ai = 1u + int_bits(opb), di = 1u + int_bits(2.0 * opb); /* sign + integer bits */
        unsigned dw = af + di, pw = dw + ws, sumw = af + ws + 1u + vi, vw = wl + 1u + vi;
        unsigned later = sw * (n - 1u - lvl);
        /*
         * np_classic_datapath's rules, level by level: constant-zero low
         * bits (level 1 widening, 8 + WS < WL, leaves zout of them; a level
         * drops WS) are priced out (effective fractions afe, wle; the traced
         * widths stay the words'); the bank keeps prod without the low bits
         * the rounding never reads; the sum's adder spans only the bits above
         * prod's low WS; the rounding is an incrementer (of bits sh..WS-1,
         * or of the kept bits and the round bit when sh > WS, or the adder's
         * carry-in when sh == WS); the last level's bits under O's round bit
         * only carry (a comparator's chain).
         */
        unsigned zout = lvl == 0 ? (wl > af + ws ? wl - af - ws : 0u) : (zin > ws ? zin - ws : 0u);
        unsigned afe = af - zin, wle = wl - zout;
        unsigned dwe = afe + di, pwe = dwe + ws, sumwe = afe + ws + 1u + vi, vwe = wle + 1u + vi;
        unsigned sh = afe + ws > wle ? afe + ws - wle : 0u;
        unsigned dead = sh == 0u ? 0u : (sh - 1u < ws ? sh - 1u : ws);
        unsigned unread = lvl + 1u == n && wl > f + 1u + zout ? wl - f - 1u - zout : 0u;
        np_dp_op(&d, mst[lvl], names[lvl][0], NP_OP_ADD, cnt, dwe, 0, dw, 1, 0);
        np_dp_op(&d, mst[lvl], names[lvl][1], NP_OP_MUL, cnt, sw, dwe, pw, 1, 1);
        np_dp_op(&d, mst[lvl], NULL, NP_OP_REG, 1, cnt * (pwe - dead + afe + ai) + later + 1, 0, 0, 0, 0);
        int named = last_traced || lvl + 1u < n;
        np_dp_op(&d, ast[lvl], named ? names[lvl][2] : NULL, NP_OP_ADD, cnt, sumwe - ws - unread, 0,
                 named ? sumw : 0u, 1, 0);
        if (unread > 0u)
            np_dp_op(&d, ast[lvl], NULL, NP_OP_CMP, cnt, unread, 0, 0, 0, 0);
        const char *lname = named ? names[lvl][3] : NULL;
        if (sh > 0u && sh < ws)
            np_dp_op(&d, ast[lvl], lname, NP_OP_INC, cnt, ws - sh + 1u, 0, named ? vw : 0u, 1, 1);
        else if (sh > ws)
            np_dp_op(&d, ast[lvl], lname, NP_OP_INC, cnt, vwe + 1u, 0, named ? vw : 0u, 1, 1);
        else
            np_dp_op(&d, ast[lvl], lname, NP_OP_REG, 0, 0, 0, named ? vw : 0u, 1, 1); /* wiring or carry-in */
        np_dp_op(&d, ast[lvl], NULL, NP_OP_REG, 1, cnt * (vwe - unread) + later + 1, 0, 0, 0, 0);
        vi_last = vi;
        zin = zout;
    }
    /*
     * O: round to Q(I).F, an incrementer over the kept bits (sign, vi, F)
     * and the round bit. |noise| <= n/2: the rounded word leaves sN only at
     * n = 3 (vi = 1, I = 2), by the carry into +2.0, which classic3 folds into
     * the incrementer (np_classic_datapath); at n = 2, 4, 5 it never does.
     * So the saturation costs no gate. Without rounding (WL == F): wiring.
     */
    if (wl > f)
        np_dp_op(&d, "O", last_traced ? "f" : NULL, NP_OP_INC, 1, f + 2u + vi_last, 0, last_traced ? nb : 0u, 1, 0);
    else
        np_dp_op(&d, "O", last_traced ? "f" : NULL, NP_OP_REG, 0, 0, 0, last_traced ? nb : 0u, 1, 0);
    np_dp_op(&d, "O", NULL, NP_OP_REG, 1, nb + 1, 0, 0, 0, 0);
    return d.n;
}

static void trace1(np_trace *t, size_t n, const char *name, int64_t v)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].signal && strcmp(t[i].signal, name) == 0)
            np_trace_add(&t[i], v);
}

void np_classicn_trace(const np_classicn_cfg *cfg, unsigned k, const np_classicn_sig *s, np_trace *t, size_t n)
{
    unsigned dims = cfg->dims, nc = 1u << dims;
    if (k == 0) {
        for (unsigned c = 0; c < nc; c++)
            trace1(t, n, "h", s->h[c]);
        for (unsigned a = 0; a < dims; a++)
            trace1(t, n, "s2", s->s2[a]);
    } else if (k == 1) {
        for (unsigned c = 0; c < nc; c++)
            trace1(t, n, "g", s->g[c]);
        for (unsigned a = 0; a < dims; a++) {
            trace1(t, n, "snum", (int64_t)s->s2[a] * (768 - 2 * (int64_t)in_frac(s->x[a])));
            trace1(t, n, "s", s->s[a]);
        }
    } else if (k < np_classicn_stage_count(dims) - 1u) {
        unsigned lvl = (k - 2u) / 2u, cnt = nc >> (lvl + 1u), mul = (k - 2u) % 2u == 0u;
        for (unsigned p = 0; p < cnt; p++) {
            if (mul) {
                int64_t b = lvl == 0 ? s->g[2 * p + 1] : s->l[2 * p + 1];
                trace1(t, n, names[lvl][0], b - s->opa[p]);
                trace1(t, n, names[lvl][1], s->prod[p]);
            } else {
                trace1(t, n, names[lvl][2], np_shl(s->opa[p], cfg->s_frac) + s->prod[p]);
                trace1(t, n, names[lvl][3], s->l[p]);
            }
        }
    } else
        trace1(t, n, "f", s->out);
}
