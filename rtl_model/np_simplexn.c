/* SPDX-License-Identifier: MIT */
#include "np_simplexn.h"

#include <math.h>
#include <string.h>

/*
 * The constants of np_simplexn.h. Bounds are rounded up. For n != 3:
 * max over s in [0, 1/2] of (1/2 - s)^4 sqrt(s) is at s = 1/18,
 * (4/9)^4 sqrt(1/2) / 3 = 0.00919676; smax = (n + 1) sqrt(K) 0.00919676,
 * fmax = A smax, gmax = sqrt(K / 2) (|G.d| <= |G| |d|, |d|^2 < 1/2 where
 * T > 0). n = 3: np_simplex.h's BOUND_* and OUTPUT RANGE.
 */
/*
 * edge2: the longest edge of the (Kuhn) simplex of the rational lattice,
 * squared, from its vertices A_c - c G (1) (docs/noise-nd.md: 0.66846,
 * 1.0, 1.20404, 1.50137); a point of the simplex is at most that far from
 * each corner. fcmax: sqrt(K) 0.00919676 (n != 3), simplex3's RANGE_FC.
 */
static const np_simplexn_geom geoms[4] = {
    { 2, 216, 592, 1024, 1024, 4, 216, 20, 1u << 19, 1, 10, 12, 1, 12, 0.5, 0.5, 1.0, 0.039019, 0.46823, 0.6685,
      0.013007 },
    { 3, 1, 3, 6, 1536, 6, 256, 23, 7077888u, 5, 9, 8388608u, 12301875u, 8, 0.6, 0.84375, 4.0249224, 1.6981,
      0.347438, 1.0, 0.42451 },
    { 4, 141, 460, 1024, 1024, 4, 141, 20, 1u << 19, 1, 10, 6, 1, 6, 0.5, 0.5, 1.2248, 0.07965, 0.47790, 1.2041,
      0.015930 },
    { 5, 121, 419, 1024, 1024, 4, 121, 20, 1u << 19, 1, 10, 4, 1, 4, 0.5, 0.5, 1.5812, 0.12339, 0.49356, 1.5014,
      0.020565 },
};

const np_simplexn_geom *np_simplexn_geom_of(unsigned n)
{
    return n >= 2u && n <= NP_SIMPLEXN_MAX ? &geoms[n - 2u] : NULL;
}

/*
 * Default widths. n = 3: np_simplex_cfg_default(N, N, 0) (WT = N + 7,
 * WP = N + 4, WK = N + 6). n != 3: WT = WP = N + x with x the smallest that
 * keeps the bound <= 0.625 LSB (ndim.error_bound_defaults prints them):
 * x = 9 (n = 2), 9 (n = 4), 9 (n = 5).
 */
static unsigned umin(unsigned a, unsigned b) { return a < b ? a : b; }

np_simplexn_cfg np_simplexn_cfg_default(unsigned dims, unsigned out_bits)
{
    np_simplexn_cfg c;
    c.dims = dims;
    c.out_bits = out_bits;
    if (dims == 3u) {
        c.t_frac = umin(out_bits + 7u, NP_SIMPLEXN_WT_MAX);
        c.p_frac = umin(out_bits + 4u, NP_SIMPLEXN_WP_MAX);
        c.k_frac = umin(out_bits + 6u, NP_SIMPLEXN_WK_MAX);
    } else {
        c.t_frac = umin(out_bits + 9u, NP_SIMPLEXN_WT_MAX);
        c.p_frac = umin(out_bits + 9u, NP_SIMPLEXN_WP_MAX);
        c.k_frac = 0u;
    }
    return c;
}

const char *np_simplexn_cfg_check(const np_simplexn_cfg *cfg)
{
    if (!np_simplexn_geom_of(cfg->dims))
        return "dims must be 2..5";
    if (cfg->out_bits < NP_SIMPLEXN_OUT_MIN || cfg->out_bits > NP_SIMPLEXN_OUT_MAX)
        return "out_bits must be 8..20";
    if (cfg->t_frac < 1u || cfg->t_frac > NP_SIMPLEXN_WT_MAX)
        return "t_frac must be 1..30";
    if (cfg->p_frac < 1u || cfg->p_frac > NP_SIMPLEXN_WP_MAX)
        return "p_frac must be 1..32";
    if (cfg->dims == 3u ? (cfg->k_frac < 1u || cfg->k_frac > NP_SIMPLEXN_WK_MAX) : cfg->k_frac != 0u)
        return cfg->dims == 3u ? "k_frac must be 1..26" : "k_frac must be 0 (Kf = A is exact) for dims != 3";
    return NULL;
}

double np_simplexn_error_bound_lsb(const np_simplexn_cfg *cfg)
{
    const np_simplexn_geom *g = np_simplexn_geom_of(cfg->dims);
    double e = np_pow2i(-(int)cfg->t_frac - 1), p = np_pow2i(-(int)cfg->p_frac - 1);
    double k = g->kf_den == 1u ? 0.0 : np_pow2i(-(int)cfg->k_frac - 1);
    double kf = (double)g->kf_num / (double)g->kf_den;
    double e4 = e * (2.0 * g->tau0 * g->tau0 + e) + e;
    double ef = (double)(g->n + 1u) * (e4 * g->gmax + p);
    return 0.5 + np_pow2i((int)cfg->out_bits) * (kf * ef + k * (g->smax + ef));
}

/* Optimal networks (Knuth, TAOCP 5.3.4); ndim.sorting_networks checks them by the 0-1 principle. */
static const uint8_t net2[][2] = { { 0, 1 } };
static const uint8_t net3[][2] = { { 0, 2 }, { 0, 1 }, { 1, 2 } };
static const uint8_t net4[][2] = { { 0, 1 }, { 2, 3 }, { 0, 2 }, { 1, 3 }, { 1, 2 } };
static const uint8_t net5[][2] = { { 0, 1 }, { 3, 4 }, { 2, 4 }, { 2, 3 }, { 0, 3 },
                                   { 0, 2 }, { 1, 4 }, { 1, 3 }, { 1, 2 } };

unsigned np_simplexn_network(unsigned n, const uint8_t (**pairs)[2])
{
    switch (n) {
    case 2: *pairs = net2; return 1;
    case 3: *pairs = net3; return 3;
    case 4: *pairs = net4; return 5;
    default: *pairs = net5; return 9;
    }
}

void np_simplexn_rank(unsigned n, const int32_t *off, uint8_t *order)
{
    const uint8_t(*pairs)[2];
    unsigned m = np_simplexn_network(n, &pairs);
    int32_t v[NP_SIMPLEXN_MAX];
    for (unsigned a = 0; a < n; a++) {
        v[a] = off[a];
        order[a] = (uint8_t)a;
    }
    for (unsigned k = 0; k < m; k++) {
        unsigned i = pairs[k][0], j = pairs[k][1];
        /* j's element goes first when it is larger, or equal with the lower axis. */
        int swap = v[j] > v[i] || (v[j] == v[i] && order[j] < order[i]);
        if (swap) {
            int32_t tv = v[i];
            uint8_t to = order[i];
            v[i] = v[j];
            order[i] = order[j];
            v[j] = tv;
            order[j] = to;
        }
    }
}

/* --- Stages (the bit-exact model runs them in order on one bundle) --- */

static const np_simplexn_geom *geom(const void *cfgv) { return np_simplexn_geom_of(((const np_simplexn_cfg *)cfgv)->dims); }

static void stage_sk(const void *cfgv, void *sv)
{
    const np_simplexn_geom *g = geom(cfgv);
    np_simplexn_sig *s = sv;
    uint32_t sum = 0;
    for (unsigned a = 0; a < g->n; a++)
        sum += s->x[a];
    for (unsigned a = 0; a < g->n; a++) {
        s->sk[a] = np_simplexn_skew(g, s->x[a], sum);
        s->cell[a] = np_simplexn_cell(g, s->sk[a]);
    }
}

static void stage_rk(const void *cfgv, void *sv)
{
    const np_simplexn_geom *g = geom(cfgv);
    np_simplexn_sig *s = sv;
    uint32_t nsum = 0;
    for (unsigned a = 0; a < g->n; a++)
        nsum += s->cell[a];
    for (unsigned a = 0; a < g->n; a++)
        s->off[a] = np_simplexn_offset(g, s->x[a], s->cell[a], nsum);
    np_simplexn_rank(g->n, s->off, s->order);
}

static void stage_ch(const void *cfgv, void *sv)
{
    const np_simplexn_geom *g = geom(cfgv);
    np_simplexn_sig *s = sv;
    unsigned mask = 0;
    for (unsigned c = 0; c <= g->n; c++) {
        if (c > 0)
            mask |= 1u << s->order[c - 1u];
        uint8_t pt[NP_SIMPLEXN_MAX] = { 0 };
        int32_t gd = 0;
        for (unsigned a = 0; a < g->n; a++) {
            s->d[c][a] = np_simplexn_corner_d(g, s->off[a], mask >> a & 1u, c);
            pt[a] = (uint8_t)((s->cell[a] + (mask >> a & 1u)) & NP_MASK(NP_HASHN_COORD));
        }
        s->h[c] = np_hashn(g->n, pt);
        np_gradn_decode(g->n, s->h[c], s->g[c]);
        for (unsigned a = 0; a < g->n; a++)
            gd += s->g[c][a] * s->d[c][a];
        s->gd[c] = gd;
    }
}

static void stage_kt(const void *cfgv, void *sv)
{
    const np_simplexn_geom *g = geom(cfgv);
    np_simplexn_sig *s = sv;
    for (unsigned c = 0; c <= g->n; c++) {
        uint32_t r2 = 0;
        for (unsigned a = 0; a < g->n; a++)
            r2 += (uint32_t)(s->d[c][a] * s->d[c][a]);
        s->r2[c] = r2;
        s->t[c] = np_simplexn_kernel_t(g, r2);
    }
}

static void stage_p2(const void *cfgv, void *sv)
{
    const np_simplexn_geom *g = geom(cfgv);
    np_simplexn_sig *s = sv;
    for (unsigned c = 0; c <= g->n; c++)
        s->tau2[c] = np_simplexn_tau2(g, cfgv, s->t[c]);
}

static void stage_p4(const void *cfgv, void *sv)
{
    const np_simplexn_geom *g = geom(cfgv);
    np_simplexn_sig *s = sv;
    for (unsigned c = 0; c <= g->n; c++)
        s->tau4[c] = np_simplexn_tau4(cfgv, s->tau2[c]);
}

static void stage_m(const void *cfgv, void *sv)
{
    const np_simplexn_geom *g = geom(cfgv);
    np_simplexn_sig *s = sv;
    for (unsigned c = 0; c <= g->n; c++)
        s->fc[c] = np_simplexn_fterm(g, cfgv, s->tau4[c], s->gd[c]);
}

static void stage_a(const void *cfgv, void *sv)
{
    const np_simplexn_geom *g = geom(cfgv);
    np_simplexn_sig *s = sv;
    s->s = 0;
    for (unsigned c = 0; c <= g->n; c++)
        s->s += s->fc[c];
}

static void stage_o(const void *cfgv, void *sv)
{
    np_simplexn_sig *s = sv;
    s->f = np_simplexn_out(cfgv, np_simplexn_kf(geom(cfgv), cfgv), s->s);
}

const np_stage_desc np_simplexn_stages[NP_SIMPLEXN_STAGES] = {
    { "SK", stage_sk }, { "RK", stage_rk }, { "CH", stage_ch }, { "KT", stage_kt }, { "P2", stage_p2 },
    { "P4", stage_p4 }, { "M", stage_m },   { "A", stage_a },   { "O", stage_o },
};

int32_t np_simplexn_eval(const np_simplexn_cfg *cfg, const uint16_t *x)
{
    np_simplexn_sig s;
    memset(&s, 0, sizeof s);
    memcpy(s.x, x, cfg->dims * sizeof x[0]);
    for (unsigned k = 0; k < NP_SIMPLEXN_STAGES; k++)
        np_simplexn_stages[k].fn(cfg, &s);
    return s.f;
}

int np_simplexn_pipe_init(np_pipe *p, const np_simplexn_cfg *cfg)
{
    return np_pipe_init(p, np_simplexn_stages, NP_SIMPLEXN_STAGES, sizeof(np_simplexn_sig), cfg);
}

/* --- Datapath declaration --- */

static unsigned ubits(uint64_t v) { return np_bits_for_range(0, (int64_t)v, 0); }
static unsigned sbits(uint64_t v) { return np_bits_for_range(-(int64_t)v, (int64_t)v, 1); }
static unsigned clog2(unsigned v)
{
    unsigned b = 0;
    while ((1u << b) < v)
        b++;
    return b;
}

/* Trailing zero bits of k mod 2^w (w when k mod 2^w is 0): the low bits a product by k never sets. */
static unsigned ctz_below(uint64_t k, unsigned w)
{
    unsigned z = 0;
    while (z < w && ((k >> z) & 1u) == 0u)
        z++;
    return z;
}

/*
 * count adders of an out-bit sum (modulo 2^out) whose operands' lowest set
 * bits are at most lo: below lo the sum is one operand's bits (wiring).
 */
static void span_add(np_dp *d, const char *stage, const char *sig, unsigned count, unsigned lo, unsigned out,
                     unsigned sig_out, int sgn, unsigned level)
{
    if (out > lo)
        np_dp_op(d, stage, sig, NP_OP_ADD, count, out - lo, 0, sig_out, sgn, level);
}

/*
 * count adder trees of m operands of w live bits (modulo 2^w) from level0; the
 * last adder's output is the traced signal sig of out bits (the full width,
 * when its low bits are constant zeros). Returns the first free level.
 */
static unsigned tree_live(np_dp *d, const char *stage, const char *sig, unsigned count, unsigned m, unsigned w,
                          unsigned out, int sgn, unsigned level0)
{
    unsigned lv = level0;
    while (m > 1u) {
        unsigned adders = m / 2u;
        m -= adders;
        np_dp_op(d, stage, m == 1u ? sig : NULL, NP_OP_ADD, count * adders, w, 0, m == 1u ? out : 0u, sgn, lv++);
    }
    return lv;
}

/* count adder trees of m operands of w bits (modulo 2^w) from level0; returns the first free level. */
static unsigned tree(np_dp *d, const char *stage, const char *sig, unsigned count, unsigned m, unsigned w, int sgn,
                     unsigned level0)
{
    return tree_live(d, stage, sig, count, m, w, w, sgn, level0);
}

/*
 * A multiply by the constant k (its canonical signed digits) with each adder priced over the bits where its two
 * operands overlap: the CSD digit at position p makes an operand of bits
 * [p, p + win); below the higher operand's lowest bit the sum is the lower
 * operand's bits (wiring); from the narrower operand's top up to the sum's
 * the bits are the wider operand's and a carry (an incrementer; priced as a
 * full adder there, SK was 1.14-1.24 times Yosys's count); a sum is kept to
 * out bits (modulo 2^out). When the
 * result's bits below unread are never read (a divider's (v M) >> sh), the
 * last adder only carries there (a carry chain). Adjacent partial sums are
 * paired, as the RTL's shift-add chain's tree. Returns the levels it takes.
 */
static unsigned const_mul_span(np_dp *d, const char *stage, const char *sig, unsigned count, uint64_t k,
                               unsigned win, unsigned out, unsigned unread, int sgn, unsigned level)
{
    unsigned lo[64], hi[64], m = 0;
    for (unsigned p = 0; k && m < 64u; p++, k >>= 1)
        if (k & 1u) {
            lo[m] = p;
            hi[m] = p + win < out ? p + win : out;
            m++;
            k = (k & 2u) ? k + 1u : k - 1u;
        }
    unsigned lv = level;
    while (m > 1u) {
        unsigned j = 0;
        for (unsigned i = 0; i + 1u < m; i += 2u) {
            unsigned l = lo[i] > lo[i + 1u] ? lo[i] : lo[i + 1u];
            unsigned h = (hi[i] > hi[i + 1u] ? hi[i] : hi[i + 1u]) + 1u;
            h = h < out ? h : out;
            int last = m == 2u;
            unsigned carry = last && unread > l ? (unread < h ? unread : h) - l : 0u, a0 = l + carry;
            /* above the narrower operand's top, the wider one's bits and a carry: an incrementer */
            unsigned ot = hi[i] < hi[i + 1u] ? hi[i] : hi[i + 1u];
            ot = ot > a0 ? ot : a0;
            if (carry)
                np_dp_op(d, stage, NULL, NP_OP_CARRY, count, carry, 0, 0, 0, lv);
            if (ot > a0)
                np_dp_op(d, stage, last ? sig : NULL, NP_OP_ADD, count, ot - a0, 0, last ? out : 0u, sgn, lv);
            if (h > ot)
                np_dp_op(d, stage, last && ot == a0 ? sig : NULL, NP_OP_INC, count, h - ot, 0, last && ot == a0 ? out : 0u,
                         sgn, lv);
            lo[j] = lo[i] < lo[i + 1u] ? lo[i] : lo[i + 1u];
            hi[j++] = h;
        }
        if (m & 1u) {
            lo[j] = lo[m - 1u];
            hi[j++] = hi[m - 1u];
        }
        m = j;
        lv++;
    }
    return lv - level;
}

/*
 * The divider floor(v / q) for 0 <= v <= vmax as (v M) >> sh: the smallest
 * sh with M = ceil(2^sh / q) exact over the range (checked here, on every
 * value). The 3-D unit's is M = 683, sh = 11.
 */
static uint64_t div_magic(uint32_t q, uint32_t vmax, unsigned *sh)
{
    for (unsigned s = 0; s < 40u; s++) {
        uint64_t m = (((uint64_t)1 << s) + q - 1u) / q;
        uint32_t v = 0;
        for (; v <= vmax; v++)
            if (((uint64_t)v * m) >> s != v / q)
                break;
        if (v > vmax) {
            *sh = s;
            return m;
        }
    }
    *sh = 0;
    return 0;
}

size_t np_simplexn_datapath(const np_simplexn_cfg *cfg, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    const np_simplexn_geom *g = np_simplexn_geom_of(cfg->dims);
    unsigned n = g->n, nc = n + 1u, wt = cfg->t_frac, wp = cfg->p_frac, wk = cfg->k_frac, nb = cfg->out_bits;
    unsigned kmax = np_gradn_max_terms(n), lookups = np_hashn_lookups(n);
    /* SK. sum X <= n 65535; SX = q X + p sum <= l 65535; nn = SX >> 8; the cell = floor(nn / q). */
    unsigned sumw = 16u + clog2(n), skw = ubits((uint64_t)g->l * 65535u);
    uint32_t nnmax = (uint32_t)(((uint64_t)g->l * 65535u) >> 8);
    unsigned cellw = ubits(nnmax / g->q), sh;
    uint64_t magic = div_magic(g->q, nnmax, &sh);
    unsigned lv = tree(&d, "SK", NULL, 1, n, sumw, 0, 0);
    /*
     * The constant multiplies' adders span only their operands' overlap
     * (const_mul_span); the divider's low sh bits only carry. With every
     * adder at the full result width SK was 1.78 (n = 2) and 1.95 (n = 4)
     * times Yosys's count.
     */
    unsigned lq = const_mul_span(&d, "SK", NULL, n, g->q, 16u, skw, 0, 0, 0);
    unsigned lp = const_mul_span(&d, "SK", NULL, 1, g->p, sumw, skw, 0, 0, lv);
    lv = (lv + lp > lq ? lv + lp : lq);
    /* SX's low 8 bits reach nn only by their carry (nn = SX >> 8). */
    np_dp_op(&d, "SK", NULL, NP_OP_CARRY, n, 8, 0, 0, 0, lv);
    np_dp_op(&d, "SK", "sk", NP_OP_ADD, n, skw - 8u, 0, skw, 0, lv++);
    lv += const_mul_span(&d, "SK", NULL, n, magic, ubits(nnmax), ubits(nnmax * magic), sh, 0, lv);
    /* The bank: RK reads X_a only as WX X_a mod 2^12: X_a's low 12 - ctz(WX) bits (10, or 11 at n = 3); the cells. */
    unsigned xw = 12u;
    for (uint64_t wx = g->wx; xw > 0u && (wx & 1u) == 0u; wx >>= 1)
        xw--;
    np_dp_op(&d, "SK", NULL, NP_OP_REG, 1, n * (xw + cellw) + 1u, 0, 0, 0, 0);
    /*
     * RK. n_sum (n - 1 adders), U = wx X - W i + wc n_sum mod 2^12 (s12:
     * |U| < W, W <= 1536 < 2048); the cells + 1 for the far corners; then the
     * sorting network on (U, axis).
     *
     * Live widths (as simplex3's declaration, docs/cost-model.md): U's low tz
     * bits are 0 at every input (tz = the fewest trailing zeros of wx, W and
     * wc mod 2^12: 2 at n = 2, 1 at n = 3, 0 at n = 4, 5), and so are every
     * corner's D and G . D; R2 and T then have 2 tz. Yosys drops those
     * constant flip-flops and the logic on them, so the operators below are
     * priced at the live widths (the traced signals keep their full widths).
     * The constant multiplies are shift-adds whose adders span only their
     * operands' overlap (const_mul_span), and so do U's two adders: bit p of
     * a sum is wiring below the higher of its operands' lowest bits.
     */
    enum { OFFW = 12, HBITS = 6 };
    unsigned tz = ctz_below(g->wx, OFFW), lo_w = ctz_below(g->w, OFFW), lo_c = ctz_below(g->wc, OFFW);
    tz = tz < lo_w ? tz : lo_w;
    tz = tz < lo_c ? tz : lo_c;
    unsigned uw = OFFW - tz, axw = clog2(n); /* U's live bits; an axis index's */
    unsigned nsw = cellw + clog2(n);
    lv = tree(&d, "RK", NULL, 1, n, nsw, 0, 0);
    unsigned lw = const_mul_span(&d, "RK", NULL, 1, g->wc, nsw, OFFW, 0, 1, lv);
    unsigned lx = const_mul_span(&d, "RK", NULL, n, g->wx, xw, OFFW, 0, 1, 0);
    unsigned li = const_mul_span(&d, "RK", NULL, n, g->w, cellw, OFFW, 0, 1, 0);
    lv = lv + lw > lx ? lv + lw : lx;
    lv = lv > li ? lv : li;
    unsigned lo_x = ctz_below(g->wx, OFFW);
    span_add(&d, "RK", NULL, n, lo_x > lo_w ? lo_x : lo_w, OFFW, 0, 0, lv++);
    unsigned lo_xw = lo_x < lo_w ? lo_x : lo_w;
    span_add(&d, "RK", "off", n, lo_xw > lo_c ? lo_xw : lo_c, OFFW, OFFW, 1, lv++);
    np_dp_op(&d, "RK", NULL, NP_OP_INC, n, NP_HASHN_COORD, 0, 0, 0, 0); /* cell + 1 mod 256 */
    /*
     * The network: a comparator of the first layer sees constant axes (its
     * inputs' own, i < j), so its tie-break is wiring and it compares U alone;
     * later ones compare (U, axis) and select both.
     */
    /*
     * Only the ranking (the axes) is kept: a comparator's U outputs are
     * selected only where a later comparator reads them (none after the last
     * layer), and a comparator whose inputs are both untouched sees constant
     * axes: its axis outputs are its compare bit and its inverse (wiring).
     * (Every output selected at full width, RK was 1.14-1.17 times Yosys's.)
     */
    const uint8_t(*pairs)[2];
    unsigned ncmp = np_simplexn_network(n, &pairs), plv[NP_SIMPLEXN_MAX] = { 0 }, depth = 0;
    unsigned cmp_u[16] = { 0 }, cmp_ua[16] = { 0 }, mux_u[16] = { 0 }, mux_a[16] = { 0 };
    /*
     * Each position's possible axes (a bit set): where every axis one input
     * can hold is below every axis of the other, the tie-break is a constant
     * and the comparator compares U alone (n = 4's second layer: {0,1}
     * against {2,3}); an axis output is selected on the bits where its
     * possible axes differ.
     */
    unsigned axes[NP_SIMPLEXN_MAX];
    for (unsigned a = 0; a < n; a++)
        axes[a] = 1u << a;
    for (unsigned k = 0; k < ncmp; k++) {
        unsigned i = pairs[k][0], j = pairs[k][1], l = (plv[i] > plv[j] ? plv[i] : plv[j]) + 1u;
        plv[i] = plv[j] = l;
        depth = l > depth ? l : depth;
        int later_i = 0, later_j = 0;
        for (unsigned q = k + 1u; q < ncmp; q++) {
            later_i |= pairs[q][0] == i || pairs[q][1] == i;
            later_j |= pairs[q][0] == j || pairs[q][1] == j;
        }
        unsigned lo_i = ctz_below(axes[i], 8), hi_i = 31u - (unsigned)__builtin_clz(axes[i]);
        unsigned lo_j = ctz_below(axes[j], 8), hi_j = 31u - (unsigned)__builtin_clz(axes[j]);
        int consts = (axes[i] & (axes[i] - 1u)) == 0u && (axes[j] & (axes[j] - 1u)) == 0u;
        if (hi_i < lo_j || hi_j < lo_i)
            cmp_u[l - 1u]++;
        else
            cmp_ua[l - 1u]++;
        unsigned u = axes[i] | axes[j], vary = 0, first = ctz_below(u, 8);
        for (unsigned a = first + 1u; a < n; a++)
            if ((u >> a) & 1u)
                vary |= a ^ first;
        if (!consts) /* two constants: the outputs are the compare bit and its inverse */
            mux_a[l - 1u] += 2u * (unsigned)__builtin_popcount(vary);
        mux_u[l - 1u] += (unsigned)later_i + (unsigned)later_j;
        axes[i] = axes[j] = u;
    }
    for (unsigned k = 0; k < depth; k++) {
        if (cmp_u[k])
            np_dp_op(&d, "RK", NULL, NP_OP_CMP, cmp_u[k], uw, 0, 0, 0, lv + 2u * k);
        if (cmp_ua[k])
            np_dp_op(&d, "RK", NULL, NP_OP_CMP, cmp_ua[k], uw + axw, 0, 0, 0, lv + 2u * k);
        if (mux_u[k])
            np_dp_op(&d, "RK", NULL, NP_OP_MUX, mux_u[k], uw, 2, 0, 0, lv + 2u * k + 1u);
        if (mux_a[k])
            np_dp_op(&d, "RK", NULL, NP_OP_MUX, mux_a[k], 1, 2, 0, 0, lv + 2u * k + 1u);
    }
    np_dp_op(&d, "RK", NULL, NP_OP_REG, 1, n * uw + n * axw + 2u * n * NP_HASHN_COORD + 1u, 0, 0, 0, 0);
    /*
     * CH, per corner c = 0..n: the mask (the first c axes of the ranking: a
     * decoder, as in 3-D not counted), D = U - W A + wc c (corner 0: U),
     * |D| < 1.6 W (|d_a| < 1 + n G): s12. D differs from U only from bit
     * dlo_c = min(ctz W, ctz (wc c)) on: one adder over those bits, its
     * constant picked by the mask bit (simplex3's D[11:8]). The corner's
     * cells (cell or cell + 1: corners 1..n-1 select, corner n is all
     * cell + 1), the hash (lookups and a six-bit adder tree), -D beside the
     * hash, then per axis a 3:1 select of D, -D, 0 and the sum over n axes,
     * |gd| <= K |D|max.
     */
    /* |gd| <= |G| |d| W <= sqrt(K edge2) W (n = 3: sqrt(3) 1536 = 2660, simplex3's s13). */
    unsigned gdw = sbits((uint64_t)ceil(sqrt((double)kmax * g->edge2) * g->w));
    unsigned gdl = gdw - tz, dshare = OFFW;
    np_dp_op(&d, "CH", NULL, NP_OP_MUX, (n - 1u) * n, NP_HASHN_COORD, 2, 0, 0, 0);
    /*
     * D = U + K with K = wc c - W A one of two constants, equal below ctz W:
     * there a constant added to U (an incrementer's cost, bits [lo, ctz W)),
     * a full adder only from ctz W up, where the mask bit picks K's bits.
     * (Priced as full adders over [lo, 12) CH was 1.21 times Yosys's count
     * at n = 5, where wc = 121 is odd: 12-bit adders for what is mostly a
     * constant's.)
     */
    for (unsigned c = 1; c <= n; c++) {
        unsigned lo = ctz_below(((uint64_t)g->wc * c) & 0xfffu, OFFW);
        lo = lo < lo_w ? lo : lo_w;
        dshare = lo < dshare ? lo : dshare;
        if (lo < lo_w)
            np_dp_op(&d, "CH", NULL, NP_OP_INC, n, lo_w - lo, 0, 0, 0, 0);
        span_add(&d, "CH", "d", n, lo_w, OFFW, OFFW, 1, 0);
    }
    np_dp_op(&d, "CH", NULL, NP_OP_LUT, nc * lookups, 3, HBITS, 0, 0, 1);
    unsigned lh = tree(&d, "CH", "h", nc, lookups, HBITS, 0, 2);
    /* A coefficient of G is 1, -1 or 0: a 3:1 select of D, -D, 0; 2:1 where no gradient of n has a zero (n = 5). */
    unsigned sel = 2u;
    for (unsigned h = 0; h < 64u && sel == 2u; h++) {
        int8_t coef[NP_SIMPLEXN_MAX];
        np_gradn_decode(n, (uint8_t)h, coef);
        for (unsigned a = 0; a < n; a++)
            if (coef[a] == 0)
                sel = 3u;
    }
    np_dp_op(&d, "CH", NULL, NP_OP_NEG, nc * n, uw, 0, 0, 0, 2);
    np_dp_op(&d, "CH", NULL, NP_OP_MUX, nc * n, uw, sel, 0, 0, lh);
    tree_live(&d, "CH", "gd", nc, n, gdl, gdw, 1, lh + 1u);
    /* D's bits below dshare equal U's at every corner: one register holds their live bits for the nc corners. */
    unsigned dreg = n * ((dshare > tz ? dshare - tz : 0u) + nc * (OFFW - (dshare > tz ? dshare : tz)));
    np_dp_op(&d, "CH", NULL, NP_OP_REG, 1, dreg + nc * gdl + 1u, 0, 0, 0, 0);
    /*
     * KT: per corner and axis |D_a| (a negate of the live bits), its square
     * (|D_a| < 2^11: 11 - tz live bits), their sum (R2 <= edge2 W^2), k R2,
     * Tv - k R2, the clamp; R2 and T at 2 tz fewer bits.
     */
    uint64_t r2max = (uint64_t)ceil(g->edge2 * (double)g->w * (double)g->w);
    unsigned r2w = ubits(r2max), tdw = sbits((uint64_t)g->k * r2max > g->tv ? (uint64_t)g->k * r2max : g->tv);
    unsigned tw = ubits(g->tv), tl = tw - 2u * tz;
    /*
     * T's bit 2 tz can be a constant too: (D / 2^tz)^2 = D / 2^tz mod 2, so
     * R2 / 4^tz = sum_a D_a / 2^tz mod 2, and sum_a U_a = wx sum X - W sum i
     * + n wc n_sum while corner c adds the constant n wc c - W c (c axes
     * carry the mask). When wx, W and n wc are 0 mod 2^(tz + 1) (n = 4), a
     * corner's R2 / 4^tz has a fixed parity, and if Tv / 4^tz - k times it
     * is even, T's bit 2 tz is 0 (the clamp's 0 too). ABC's SAT sweep
     * proves it: Yosys's KT bank at n = 4 has 151 flip-flops, the model had
     * 160, and P2's squarer priced at 20 bits was 1.16 times Yosys's count.
     */
    int even_t = (((g->wx >> tz) | (g->w >> tz) | (((uint64_t)n * g->wc) >> tz)) & 1u) == 0u;
    for (unsigned c = 0; c <= n && even_t; c++) {
        uint64_t pc = (((uint64_t)n * g->wc * c - (uint64_t)g->w * c) >> tz) & 1u;
        if ((((uint64_t)g->tv >> (2u * tz)) - (uint64_t)g->k * pc) & 1u)
            even_t = 0;
    }
    if (even_t)
        tl--;
    np_dp_op(&d, "KT", NULL, NP_OP_NEG, nc * n, uw, 0, 0, 0, 0);
    np_dp_op(&d, "KT", NULL, NP_OP_SQR, nc * n, OFFW - 1u - tz, 0, 2u * OFFW, 0, 1); /* |d_a|^2: squarers */
    lv = tree_live(&d, "KT", "r2", nc, n, r2w - 2u * tz, r2w, 0, 2);
    lv += const_mul_span(&d, "KT", NULL, nc, g->k, r2w - 2u * tz, tdw - 2u * tz, 0, 0, lv);
    np_dp_op(&d, "KT", NULL, NP_OP_INC, nc, tdw - 2u * tz, 0, 0, 1, lv++); /* a constant minus k R2 */
    np_dp_op(&d, "KT", "t", NP_OP_MUX, nc, tl, 2, tw, 0, lv);
    np_dp_op(&d, "KT", NULL, NP_OP_REG, 1, nc * (tl + gdl) + 1u, 0, 0, 0, 0);
    /*
     * P2, P4: squarers; roundings are incrementers (as simplex3); the largest
     * words are at T = Tv. The RTL holds tau2 and tau4 at WT bits (r4_tau2,
     * r5_tau4), and no synthesis can see that their values stay below
     * t2w, t4w bits (that needs T <= Tv, a range, not a constant bit): the
     * banks, P4's squarer and M's multiplier are WT bits wide, as Yosys
     * builds them. (Priced at t2w = 24, t4w = 23, n = 2, 4, 5's P4 and M were
     * 0.89-0.94 of Yosys's count; n = 3's WT = t2w = 23 was right.)
     */
    uint64_t t2 = np_simplexn_tau2(g, cfg, g->tv), t4 = np_simplexn_tau4(cfg, (uint32_t)t2);
    unsigned t2w = ubits(t2), t4w = ubits(t4), rt2 = wt > t2w ? wt : t2w, rt4 = wt > t4w ? wt : t4w;
    np_dp_op(&d, "P2", NULL, NP_OP_SQR, nc, tl, 0, 2u * tw, 0, 0);
    np_dp_op(&d, "P2", "tau2", NP_OP_INC, nc, t2w + 1u, 0, t2w, 0, 1);
    np_dp_op(&d, "P2", NULL, NP_OP_REG, 1, nc * (rt2 + gdl) + 1u, 0, 0, 0, 0);
    np_dp_op(&d, "P4", NULL, NP_OP_SQR, nc, rt2, 0, 2u * t2w, 0, 0);
    np_dp_op(&d, "P4", "tau4", NP_OP_INC, nc, t4w + 1u, 0, t4w, 0, 1);
    np_dp_op(&d, "P4", NULL, NP_OP_REG, 1, nc * (rt4 + gdl) + 1u, 0, 0, 0, 0);
    /*
     * M: fc = round(tau4 gd): |tau^4 G.d| <= fcmax where T > 0, plus tau4's
     * error e4 times |gd| <= gmax and fc's own rounding (ERROR BOUND).
     */
    double e = np_pow2i(-(int)wt - 1), e4 = e * (2.0 * g->tau0 * g->tau0 + e) + e;
    uint64_t fcmax = (uint64_t)ceil((g->fcmax + e4 * g->gmax) * np_pow2i((int)wp)) + 1u;
    unsigned fcw = sbits(fcmax);
    /*
     * The RTL holds fc at FW = WP + GDW - GDF + 1 bits and S at FW + 3 (the
     * header's bound at every configuration, np_simplexn.v), wider than the
     * error argument's fcw; Yosys cannot narrow them, so M's rounding and
     * bank, A and O are priced at the RTL's widths (the traced fc keeps fcw).
     */
    unsigned rfw = wp + gdw - g->gdf + 1u;
    np_dp_op(&d, "M", NULL, NP_OP_MUL, nc, rt4, gdl, t4w + gdw, 1, 0);
    if (wt + g->gdf > wp)
        np_dp_op(&d, "M", "fc", NP_OP_INC, nc, rfw + 1u, 0, fcw, 1, 1);
    np_dp_op(&d, "M", NULL, NP_OP_REG, 1, nc * rfw + 1u, 0, 0, 0, 0);
    /*
     * A: the sum of n + 1 terms, |S| <= smax + errors < (n + 1) max |fc|:
     * s(fcw + ceil log2 (n+1)); the RTL's FW + 3. A sum of two s(w) words
     * is s(w + 1): the tree's adders grow one bit a level up to FW + 3 (the
     * bits above are the operands' sign copies). When Kf' is one digit 2^p
     * (n = 5: A = 4), O's product is S << p and its rounding adds
     * 2^(shift - 1): S's bits below shift - 1 - p are never read (Yosys's A
     * bank at n = 5 has 26 flip-flops for the RTL's 32 bits), so they are
     * no register and the last adder only carries there. (With every
     * adder at FW + 3 and S whole, A was 1.09-1.16 times Yosys's count.)
     */
    unsigned sw = rfw + 3u;
    uint64_t kf = (uint64_t)np_simplexn_kf(g, cfg);
    unsigned shift = wk + wp > nb ? wk + wp - nb : 0u, dead = 0;
    if (kf && (kf & (kf - 1u)) == 0u) {
        unsigned p = ctz_below(kf, 64);
        dead = shift > p + 1u ? shift - 1u - p : 0u;
    }
    for (unsigned m = nc, l = 0; m > 1u; l++) {
        unsigned adders = m / 2u, w = rfw + l + 1u < sw ? rfw + l + 1u : sw;
        m -= adders;
        if (m == 1u && dead > 0u && dead < w) {
            np_dp_op(&d, "A", NULL, NP_OP_CARRY, adders, dead, 0, 0, 0, l);
            np_dp_op(&d, "A", NULL, NP_OP_ADD, adders, w - dead, 0, 0, 1, l);
        } else {
            np_dp_op(&d, "A", NULL, NP_OP_ADD, adders, w, 0, 0, 1, l);
        }
    }
    np_dp_op(&d, "A", NULL, NP_OP_REG, 1, sw - dead + 1u, 0, 0, 0, 0);
    /*
     * O: Kf' S as shift-adds whose adders span their operands' overlap and
     * whose bits under the rounding's round bit only carry (as simplex3's O);
     * the rounding (an incrementer above them); the saturation as simplex3
     * prices it: one check that the bits from the output's sign bit up are
     * all equal, and a 2:1 select of the word or the largest value.
     */
    unsigned pw = sw + ubits(kf);
    lv = const_mul_span(&d, "O", NULL, 1, kf, sw, pw, shift > 0u ? shift - 1u : 0u, 1, 0);
    if (shift > 0u)
        np_dp_op(&d, "O", NULL, NP_OP_INC, 1, pw - shift + 1u, 0, 0, 1, lv++);
    np_dp_op(&d, "O", NULL, NP_OP_CMPK, 1, pw - shift - nb + 1u, 0, 0, 0, lv++);
    np_dp_op(&d, "O", NULL, NP_OP_MUX, 1, nb, 2, 0, 1, lv); /* the port sN: untraced, see np_simplexn.h */
    np_dp_op(&d, "O", NULL, NP_OP_REG, 1, nb + 1u, 0, 0, 0, 0);
    return d.n;
}

static void trace1(np_trace *t, size_t n, const char *name, int64_t v)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].signal && strcmp(t[i].signal, name) == 0)
            np_trace_add(&t[i], v);
}

void np_simplexn_trace(const np_simplexn_cfg *cfg, unsigned k, const np_simplexn_sig *s, np_trace *t, size_t n)
{
    unsigned dims = cfg->dims;
    switch (k) {
    case 0:
        for (unsigned a = 0; a < dims; a++)
            trace1(t, n, "sk", s->sk[a]);
        break;
    case 1:
        for (unsigned a = 0; a < dims; a++)
            trace1(t, n, "off", s->off[a]);
        break;
    case 2:
        for (unsigned c = 0; c <= dims; c++) {
            for (unsigned a = 0; a < dims; a++)
                trace1(t, n, "d", s->d[c][a]);
            trace1(t, n, "h", s->h[c]);
            trace1(t, n, "gd", s->gd[c]);
        }
        break;
    case 3:
        for (unsigned c = 0; c <= dims; c++) {
            trace1(t, n, "r2", s->r2[c]);
            trace1(t, n, "t", s->t[c]);
        }
        break;
    case 4:
        for (unsigned c = 0; c <= dims; c++)
            trace1(t, n, "tau2", s->tau2[c]);
        break;
    case 5:
        for (unsigned c = 0; c <= dims; c++)
            trace1(t, n, "tau4", s->tau4[c]);
        break;
    case 6:
        for (unsigned c = 0; c <= dims; c++)
            trace1(t, n, "fc", s->fc[c]);
        break;
    default: break;
    }
}
