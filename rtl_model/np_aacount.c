/* SPDX-License-Identifier: MIT */
/* The sample-count unit aacount: bit-exact model, cycle models, datapath (np_aacount.h). */
#include "np_aacount.h"

#include <string.h>

/* The paper's Fig. 3, B[b][a], used literally. */
static const uint8_t bayer2[2][2] = { { 0, 2 }, { 3, 1 } };
static const uint8_t bayer3[3][3] = { { 2, 6, 3 }, { 5, 0, 8 }, { 1, 7, 4 } };
static const uint8_t bayer4[4][4] = { { 1, 8, 2, 10 }, { 12, 4, 14, 6 }, { 3, 11, 0, 9 }, { 15, 7, 13, 5 } };

unsigned np_aacount_bayer(unsigned m, unsigned a, unsigned b)
{
    switch (m) {
    case 2: return bayer2[b][a];
    case 3: return bayer3[b][a];
    case 4: return bayer4[b][a];
    default: return 0;
    }
}

uint16_t np_aacount_mask(unsigned m, unsigned s)
{
    uint16_t mask = 0;
    for (unsigned b = 0; b < m; b++)
        for (unsigned a = 0; a < m; a++)
            if (np_aacount_bayer(m, a, b) < s)
                mask = (uint16_t)(mask | (1u << (b * m + a)));
    return mask;
}

np_aacount_cfg np_aacount_cfg_default(void)
{
    np_aacount_cfg c;
    memset(&c, 0, sizeof c);
    c.m = 3;
    c.depth = c.normal = c.luma = 1;
    c.luma_taps = 4;
    c.c_d = 1000000u;
    c.c_n = 4u * 8u;  /* c_n = 8 */
    c.c_s = 16u * 8u; /* c_s = 8 */
    c.t_min = 16;
    c.t_edge = 32;
    return c;
}

const char *np_aacount_cfg_check(const np_aacount_cfg *cfg)
{
    if (cfg->m < 1 || cfg->m > NP_AAC_M_MAX)
        return "m must be 1..4";
    if (cfg->luma_taps != 4 && cfg->luma_taps != 5)
        return "luma_taps must be 4 or 5";
    if (cfg->tile != 0 && cfg->tile != NP_AAC_TILE)
        return "tile must be 0 or 6";
    if (np_aacount_bus_bits(cfg) > 8u * 64u)
        return "the window bus exceeds the 512 bits of a vector line (m=4 with depth and normal: 808 bits); "
               "np_aacount_eval takes it, the registry does not";
    return NULL;
}

/* --- Host: threshold registers --- */

void np_aacount_regs_compute(const np_aacount_cfg *cfg, np_aacount_regs *r)
{
    memset(r, 0, sizeof *r);
    unsigned n = (unsigned)cfg->m * cfg->m;
    uint64_t c2 = (uint64_t)cfg->c_n * cfg->c_n;
    r->nd = (uint32_t)(c2 * c2); /* C <= 255: C^4 < 2^32 */
    for (unsigned j = 1; j < NP_AAC_N_MAX; j++) {
        /* depth: v >= floor(j n^2 2^48 / c_d) + 1; j n^2 2^48 < 2^60 */
        if (cfg->c_d == 0) {
            r->vd[j] = NP_AAC_VD_NEVER;
        } else {
            uint64_t q = (((uint64_t)j * n * n) << 48) / cfg->c_d + 1u;
            r->vd[j] = q < NP_AAC_VD_NEVER ? q : NP_AAC_VD_NEVER;
        }
        /* normal: a_j = (C^2 - 16 j^2) / C^2 > 0, or never */
        uint64_t t = 16u * (uint64_t)j * j;
        if (c2 > t) {
            r->na[j] = (uint32_t)((c2 - t) * (c2 - t));
            r->na_on[j] = 1;
        }
        /* luma: C_s r > 255 * 16 j  iff  r >= floor(4080 j / C_s) + 1 */
        if (cfg->c_s == 0) {
            r->rs[j] = 256;
        } else {
            uint32_t q = 4080u * j / cfg->c_s + 1u;
            r->rs[j] = (uint16_t)(q < 256u ? q : 256u);
        }
    }
    r->t_min = cfg->t_min;
    r->t_edge = cfg->t_edge;
}

/* --- Stages (the bit-exact model is the same four functions in a row) --- */

static unsigned n_of(const np_aacount_cfg *c) { return (unsigned)c->m * c->m; }

/* A: sums over the window; luma extremes. */
static void stage_a(const np_aacount_cfg *c, np_aacount_sig *s)
{
    unsigned n = n_of(c);
    if (s->from_bus) {
        np_aacount_bus_unpack(c, s->bus, &s->w);
        s->from_bus = 0;
    }
    s->sum_d = 0;
    s->sum_d2 = 0;
    s->nbar[0] = s->nbar[1] = s->nbar[2] = 0;
    s->any_n = 0;
    for (unsigned i = 0; i < n; i++) {
        if (c->depth) {
            uint64_t d = s->w.d[i] & NP_MASK(NP_AAC_DEPTH_BITS);
            s->sum_d += (uint32_t)d;
            s->sum_d2 += d * d;
        }
        if (c->normal)
            for (unsigned k = 0; k < 3; k++) {
                s->nbar[k] += s->w.nrm[i][k];
                if (s->w.nrm[i][k] != 0)
                    s->any_n = 1;
            }
    }
    s->lmax = s->lmin = 0;
    if (c->luma) {
        unsigned first = c->luma_taps == 5 ? 0u : 1u;
        s->lmax = s->lmin = s->w.luma[first];
        for (unsigned i = first + 1; i < NP_AAC_LUMAS; i++) {
            uint8_t l = s->w.luma[i];
            s->lmax = l > s->lmax ? l : s->lmax;
            s->lmin = l < s->lmin ? l : s->lmin;
        }
    }
}

/* Sample i's dot with nbar (s21) and |n|^2 (u16): stage V's lane, the serial unit's pass-2 beat. */
static void cone_lane(np_aacount_sig *s, unsigned i)
{
    int32_t dot = 0;
    uint32_t nn = 0;
    for (unsigned k = 0; k < 3; k++) {
        int32_t e = s->w.nrm[i][k];
        dot += s->nbar[k] * e;
        nn += (uint32_t)(e * e);
    }
    s->dot[i] = dot;
    s->nn2[i] = nn;
}

/* Sample i's p, q and the running least p/q (stage P's comparison, by u80 cross products; ties keep the earlier). */
static void cone_min(np_aacount_sig *s, unsigned i)
{
    s->p[i] = (uint64_t)((int64_t)s->dot[i] * s->dot[i]);
    s->q[i] = (uint64_t)s->nb2 * s->nn2[i];
    if (s->nn2[i] == 0)
        return; /* no surface: not in the cone */
    if (!s->have_min || (np_u128)s->p[i] * s->qmin < (np_u128)s->pmin * s->q[i]) {
        s->pmin = s->p[i];
        s->qmin = s->q[i];
        s->have_min = 1;
    }
}

/* V: the exact variance numerator; dots and norms; luma range and gate. */
static void stage_v(const np_aacount_cfg *c, const np_aacount_regs *rg, np_aacount_sig *s)
{
    unsigned n = n_of(c);
    s->v = 0;
    if (c->depth)
        s->v = (uint64_t)n * s->sum_d2 - (uint64_t)s->sum_d * s->sum_d; /* both < 2^56, v >= 0 */
    s->nb2 = 0;
    if (c->normal) {
        for (unsigned k = 0; k < 3; k++)
            s->nb2 += (uint32_t)(s->nbar[k] * s->nbar[k]);
        for (unsigned i = 0; i < n; i++)
            cone_lane(s, i);
    }
    s->r = 0;
    s->gate = 0;
    if (c->luma) {
        s->r = (uint8_t)(s->lmax - s->lmin);
        /* k_s = 0 when r < t_min or r < lmax t_edge (256 r < t_edge lmax, exact) */
        s->gate = !(s->r < rg->t_min || 256u * s->r < (unsigned)rg->t_edge * s->lmax);
    }
}

/* P: p, q per sample and the least p/q; depth and luma counts. */
static void stage_p(const np_aacount_cfg *c, const np_aacount_regs *rg, np_aacount_sig *s)
{
    unsigned n = n_of(c);
    s->have_min = 0;
    s->pmin = s->qmin = 0;
    if (c->normal)
        for (unsigned i = 0; i < n; i++)
            cone_min(s, i);
    s->sd = 0;
    if (c->depth) {
        s->sd = 1;
        for (unsigned j = 1; j < n; j++)
            s->sd = (uint8_t)(s->sd + (s->v >= rg->vd[j]));
    }
    s->ss = 0;
    if (c->luma) {
        s->ss = 1;
        for (unsigned j = 1; j < n && s->gate; j++)
            s->ss = (uint8_t)(s->ss + (s->r >= rg->rs[j]));
    }
}

/* C: normal count against the registers; s = max; the mask. */
static void stage_c(const np_aacount_cfg *c, const np_aacount_regs *rg, np_aacount_sig *s)
{
    unsigned n = n_of(c);
    s->sn = 0;
    if (c->normal) {
        s->sn = 1;
        if (s->nb2 == 0) {
            if (s->any_n && rg->nd != 0)
                s->sn = (uint8_t)n; /* normals that cancel (PIN) */
        } else if (s->have_min) {
            np_u128 lhs = (np_u128)s->pmin * rg->nd; /* u72 */
            for (unsigned j = 1; j < n; j++)
                s->sn = (uint8_t)(s->sn + (rg->na_on[j] && lhs < (np_u128)rg->na[j] * s->qmin));
        }
    }
    uint8_t m = 1;
    m = s->sd > m ? s->sd : m;
    m = s->sn > m ? s->sn : m;
    m = s->ss > m ? s->ss : m;
    s->s = m;
    s->mask = np_aacount_mask(c->m, m);
}

void np_aacount_sig_in(np_aacount_sig *s, const np_aacount_win *w)
{
    memset(s, 0, sizeof *s);
    s->w = *w;
}

void np_aacount_sig_in_bus(np_aacount_sig *s, const uint64_t *words)
{
    memset(s, 0, sizeof *s);
    memcpy(s->bus, words, sizeof s->bus);
    s->from_bus = 1;
}

void np_aacount_sig_out(const np_aacount_sig *s, np_aacount_out *o)
{
    o->s = s->s;
    o->sd = s->sd;
    o->sn = s->sn;
    o->ss = s->ss;
    o->mask = s->mask;
}

void np_aacount_eval_regs(const np_aacount_cfg *cfg, const np_aacount_regs *r, const np_aacount_win *w,
                          np_aacount_out *o)
{
    np_aacount_sig s;
    np_aacount_sig_in(&s, w);
    stage_a(cfg, &s);
    stage_v(cfg, r, &s);
    stage_p(cfg, r, &s);
    stage_c(cfg, r, &s);
    np_aacount_sig_out(&s, o);
}

void np_aacount_eval(const np_aacount_cfg *cfg, const np_aacount_win *w, np_aacount_out *o)
{
    np_aacount_regs r;
    np_aacount_regs_compute(cfg, &r);
    np_aacount_eval_regs(cfg, &r, w, o);
}

/* --- Resolve and tile --- */

uint32_t np_aacount_rom(unsigned s)
{
    return (uint32_t)((((uint32_t)1 << NP_AAC_ROM_FRAC) + s - 1u) / s);
}

uint8_t np_aacount_resolve(uint32_t sum, unsigned s)
{
    uint64_t x = (uint64_t)sum * np_aacount_rom(s); /* u12 x u18 */
    return (uint8_t)((x + ((uint64_t)1 << (NP_AAC_ROM_FRAC - 1u))) >> NP_AAC_ROM_FRAC);
}

void np_aacount_tile_max(uint8_t *s, unsigned w, unsigned h)
{
    for (unsigned ty = 0; ty < h; ty += NP_AAC_TILE)
        for (unsigned tx = 0; tx < w; tx += NP_AAC_TILE) {
            unsigned ye = ty + NP_AAC_TILE < h ? ty + NP_AAC_TILE : h;
            unsigned xe = tx + NP_AAC_TILE < w ? tx + NP_AAC_TILE : w;
            uint8_t m = 0;
            for (unsigned y = ty; y < ye; y++)
                for (unsigned x = tx; x < xe; x++)
                    m = s[(size_t)y * w + x] > m ? s[(size_t)y * w + x] : m;
            for (unsigned y = ty; y < ye; y++)
                for (unsigned x = tx; x < xe; x++)
                    s[(size_t)y * w + x] = m;
        }
}

/* --- The window bus --- */

unsigned np_aacount_bus_bits(const np_aacount_cfg *cfg)
{
    unsigned beat = (cfg->depth ? NP_AAC_DEPTH_BITS : 0u) + (cfg->normal ? 3u * NP_AAC_NRM_BITS : 0u);
    return n_of(cfg) * beat + (cfg->luma ? NP_AAC_LUMAS * NP_AAC_LUMA_BITS : 0u);
}

static void bus_put(uint64_t *words, unsigned *pos, uint64_t v, unsigned bits)
{
    for (unsigned b = 0; b < bits; b++, (*pos)++)
        if (v >> b & 1u)
            words[*pos / 64u] |= (uint64_t)1 << (*pos % 64u);
}

/*
 * The field of bits (1..64) at bit *pos of the bus, LSB first, from the one
 * or two words it lies in (never a word past the field's last bit).
 */
static uint64_t bus_get(const uint64_t *words, unsigned *pos, unsigned bits)
{
    const unsigned w = *pos / 64u, s = *pos % 64u;
    uint64_t v = words[w] >> s;
    if (s + bits > 64u)
        v |= words[w + 1u] << (64u - s);
    *pos += bits;
    return bits >= 64u ? v : v & ((UINT64_C(1) << bits) - 1u);
}

void np_aacount_bus_pack(const np_aacount_cfg *cfg, const np_aacount_win *w, uint64_t *words)
{
    unsigned nw = (np_aacount_bus_bits(cfg) + 63u) / 64u, pos = 0;
    memset(words, 0, nw * sizeof words[0]);
    for (unsigned i = 0; i < n_of(cfg); i++) {
        if (cfg->depth)
            bus_put(words, &pos, w->d[i], NP_AAC_DEPTH_BITS);
        if (cfg->normal)
            for (unsigned k = 0; k < 3; k++)
                bus_put(words, &pos, (uint8_t)w->nrm[i][k], NP_AAC_NRM_BITS);
    }
    if (cfg->luma)
        for (unsigned k = 0; k < NP_AAC_LUMAS; k++)
            bus_put(words, &pos, w->luma[k], NP_AAC_LUMA_BITS);
}

void np_aacount_bus_unpack(const np_aacount_cfg *cfg, const uint64_t *words, np_aacount_win *w)
{
    unsigned pos = 0;
    memset(w, 0, sizeof *w);
    for (unsigned i = 0; i < n_of(cfg); i++) {
        if (cfg->depth)
            w->d[i] = (uint32_t)bus_get(words, &pos, NP_AAC_DEPTH_BITS);
        if (cfg->normal)
            for (unsigned k = 0; k < 3; k++)
                w->nrm[i][k] = (int8_t)np_sext(bus_get(words, &pos, NP_AAC_NRM_BITS), NP_AAC_NRM_BITS);
    }
    if (cfg->luma)
        for (unsigned k = 0; k < NP_AAC_LUMAS; k++)
            w->luma[k] = (uint8_t)bus_get(words, &pos, NP_AAC_LUMA_BITS);
}

/* --- Parallel cycle model --- */

/*
 * The pipe's stages read the threshold registers, which the host loads from
 * the keys; the model recomputes them from cfg (the same integers every time).
 */
static void pa(const void *cfg, void *sig) { stage_a(cfg, sig); }
static void pv(const void *cfg, void *sig)
{
    np_aacount_regs r;
    np_aacount_regs_compute(cfg, &r);
    stage_v(cfg, &r, sig);
}
static void pp(const void *cfg, void *sig)
{
    np_aacount_regs r;
    np_aacount_regs_compute(cfg, &r);
    stage_p(cfg, &r, sig);
}
static void pc(const void *cfg, void *sig)
{
    np_aacount_regs r;
    np_aacount_regs_compute(cfg, &r);
    stage_c(cfg, &r, sig);
}

static const np_stage_desc stages[NP_AAC_PIPE_STAGES] = { { "A", pa }, { "V", pv }, { "P", pp }, { "C", pc } };

int np_aacount_pipe_init(np_pipe *p, const np_aacount_cfg *cfg)
{
    return np_pipe_init(p, stages, NP_AAC_PIPE_STAGES, sizeof(np_aacount_sig), cfg);
}

/* --- Serial cycle model --- */

void np_aacount_serial_init(np_aacount_serial *u, const np_aacount_cfg *cfg)
{
    memset(u, 0, sizeof *u);
    u->cfg = cfg;
    np_aacount_regs_compute(cfg, &u->regs);
}

unsigned np_aacount_serial_latency(const np_aacount_cfg *cfg) { return 2u * n_of(cfg); }

/* Pass 2, one beat: that beat's dot, norm, p, q and the running least ratio (stage V's lane, stage P's compare). */
static void serial_cmp_beat(const np_aacount_cfg *c, np_aacount_sig *s, unsigned i)
{
    if (!c->normal)
        return;
    cone_lane(s, i);
    cone_min(s, i);
}

int np_aacount_serial_clock(np_aacount_serial *u, int in_valid, const np_aacount_win *w)
{
    const np_aacount_cfg *c = u->cfg;
    unsigned n = n_of(c);
    u->cycles++;
    u->out_valid = 0;
    /* pass 2: one beat; the last one also counts and writes the result register */
    if (u->cmp_busy) {
        serial_cmp_beat(c, &u->cmp, u->cbeat);
        if (++u->cbeat == n) {
            /* depth and luma counts (stage_p without its normal loop), then stage_c */
            np_aacount_sig t = u->cmp;
            uint8_t normal = c->normal;
            np_aacount_cfg c2 = *c;
            c2.normal = 0;
            stage_p(&c2, &u->regs, &t);
            c2.normal = normal;
            t.have_min = u->cmp.have_min;
            t.pmin = u->cmp.pmin;
            t.qmin = u->cmp.qmin;
            stage_c(&c2, &u->regs, &t);
            np_aacount_sig_out(&t, &u->out);
            u->out_valid = 1;
            u->cmp_busy = 0;
        }
    }
    /* hand a full accumulator to pass 2 */
    if (u->acc_full && !u->cmp_busy) {
        u->cmp = u->acc;
        u->cmp.have_min = 0;
        u->cmp.pmin = u->cmp.qmin = 0;
        u->cmp_busy = 1;
        u->cbeat = 0;
        u->acc_full = 0;
    }
    /* pass 1: one beat into the sums and the normal buffer */
    if (in_valid && !u->acc_full) {
        np_aacount_sig *s = &u->acc;
        unsigned i = u->beat;
        if (i == 0) {
            np_aacount_sig_in(s, w); /* the lumas ride on the first beat */
            memset(s->w.d, 0, sizeof s->w.d);
            memset(s->w.nrm, 0, sizeof s->w.nrm);
        }
        s->w.d[i] = w->d[i];
        memcpy(s->w.nrm[i], w->nrm[i], sizeof s->w.nrm[i]);
        if (c->depth) {
            uint64_t d = w->d[i] & NP_MASK(NP_AAC_DEPTH_BITS);
            s->sum_d += (uint32_t)d;
            s->sum_d2 += d * d;
        }
        if (c->normal)
            for (unsigned k = 0; k < 3; k++) {
                s->nbar[k] += w->nrm[i][k];
                s->any_n = (uint8_t)(s->any_n | (w->nrm[i][k] != 0));
            }
        if (++u->beat == n) {
            /* the window's sums are complete: variance, |nbar|^2 and the luma range (stage V's window part) */
            np_aacount_sig t = *s;
            stage_a(c, &t); /* lumas only; the sums equal the accumulated ones */
            s->lmax = t.lmax;
            s->lmin = t.lmin;
            np_aacount_cfg c2 = *c;
            c2.normal = 0;
            stage_v(&c2, &u->regs, s);
            s->nb2 = 0;
            for (unsigned k = 0; k < 3; k++)
                s->nb2 += (uint32_t)(s->nbar[k] * s->nbar[k]);
            u->beat = 0;
            u->acc_full = 1;
        }
        return 1;
    }
    return 0;
}

/* --- Datapath declaration --- */

/* Widths from the window's extremes (the trace reaches them: the boundary windows). */
typedef struct aac_widths {
    unsigned sum_d, sum_d2, v, nbar, dot, nb2, nn2, p, q;
} aac_widths;

static aac_widths widths_of(const np_aacount_cfg *c)
{
    int64_t n = (int64_t)n_of(c), dmax = (int64_t)NP_MASK(NP_AAC_DEPTH_BITS);
    aac_widths w;
    w.sum_d = np_bits_for_range(0, n * dmax, 0);
    w.sum_d2 = np_bits_for_range(0, n * dmax * dmax, 0);
    /* v = n^2 Var <= n^2 (range / 2)^2, reached with half the samples at 0 and half at dmax (n even);
     * for n odd the maximum is (n^2 - 1)/4 dmax^2 */
    int64_t vmax = (n * n - (n & 1)) / 4 * dmax * dmax;
    w.v = np_bits_for_range(0, vmax, 0);
    w.nbar = np_bits_for_range(-128 * n, 127 * n, 1);
    w.dot = np_bits_for_range(-3 * 128 * 128 * n, 3 * 128 * 128 * n, 1);
    w.nb2 = np_bits_for_range(0, 3 * 128 * 128 * n * n, 0);
    w.nn2 = np_bits_for_range(0, 3 * 128 * 128, 0);
    w.p = np_bits_for_range(0, (3 * 128 * 128 * n) * (3 * 128 * 128 * n), 0);
    w.q = w.p;
    return w;
}

/*
 * A product with the constant k (a bits times k): shift-adds of k's canonical
 * signed digits, lowest first, one adder per digit after the first (a power of
 * two, or 0, is wiring). Each adder is a + 1 bits wide: the new term x 2^pos
 * spans bits pos .. pos + a - 1, the partial sum's bits below pos pass through
 * untouched, and its top is below pos + a (canonical digits are never
 * adjacent: the sum of the lower ones is under 2^(pos - 1 + a + 1)).
 */
static void const_mul(np_dp *d, const char *stage, unsigned count, unsigned a, uint64_t k, unsigned level)
{
    unsigned terms = 0;
    for (unsigned pos = 0; k && pos < 64; pos++, k >>= 1)
        if (k & 1u) {
            terms++;
            k = (k & 2u) ? k + 1u : k - 1u; /* digit -1 or +1 */
        }
    if (terms > 1u)
        np_dp_op(d, stage, NULL, NP_OP_ADD, count * (terms - 1u), a + 1u, 0, 0, 0, level);
}

/* Bits of k (0 for 0) and its trailing zero bits (0 for 0). */
static unsigned ubits64(uint64_t k)
{
    unsigned b = 0;
    while (k >> b)
        b++;
    return b;
}

static unsigned tzeros64(uint64_t k)
{
    unsigned t = 0;
    while (k && !(k >> t & 1u))
        t++;
    return t;
}

/*
 * The declaration of what np_aacount.v builds (report gates --synth compares
 * it stage by stage): the threshold registers are constants of the
 * configuration there (np_aacount_regs_compute at elaboration), so each
 * comparison with a threshold is a comparison with a constant, one that can
 * never hold (vd[j] beyond v's range, rs[j] = 256, na_on[j] = 0) is left out,
 * and the normal test's products with nd and na[j] are constant products.
 * d^2, sum_d^2, |nbar|^2, |n|^2 and dot^2 are squarers; each count is the
 * RTL's chain of conditional increments. The resolve (np_aacount_resolve) is
 * the renderer's, after the unit: no stage here.
 */
size_t np_aacount_datapath(const np_aacount_cfg *c, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    unsigned n = n_of(c), lanes = c->serial ? 1u : n;
    aac_widths w = widths_of(c);
    np_aacount_regs r;
    np_aacount_regs_compute(c, &r);
    unsigned lv, regs, live;
    /* A: the sums (parallel: adder trees over n lanes; serial: one accumulator each) */
    regs = 1;
    if (c->depth) {
        np_dp_op(&d, "A", "d2", NP_OP_SQR, lanes, 24, 0, 48, 0, 0);
        if (c->serial) {
            np_dp_op(&d, "A", "sum_d", NP_OP_ADD, 1, w.sum_d, 0, w.sum_d, 0, 1);
            np_dp_op(&d, "A", "sum_d2", NP_OP_ADD, 1, w.sum_d2, 0, w.sum_d2, 0, 1);
        } else {
            np_dp_add_tree(&d, "A", "sum_d", n, w.sum_d, 0, 1);
            np_dp_add_tree(&d, "A", "sum_d2", n, w.sum_d2, 0, 1);
        }
        regs += w.sum_d + w.sum_d2;
    }
    if (c->normal) {
        if (c->serial)
            np_dp_op(&d, "A", "nbar", NP_OP_ADD, 3, w.nbar, 0, w.nbar, 1, 0);
        else
            for (unsigned k = 0; k < 3; k++)
                np_dp_add_tree(&d, "A", "nbar", n, w.nbar, 1, 0);
        np_dp_op(&d, "A", NULL, NP_OP_CMPK, lanes, 24, 0, 0, 0, 0); /* any normal: a sample's 24 bits not 0 */
        /* the normals wait for nbar: the serial unit's two n x 24 buffers, the parallel one's pipeline */
        np_dp_op(&d, "A", NULL, NP_OP_REG, c->serial ? 2u : 1u, n * 24u, 0, 0, 0, 0);
        regs += 3u * w.nbar + 1u;
    }
    if (c->luma) {
        unsigned taps = c->luma_taps;
        np_dp_op(&d, "A", NULL, NP_OP_CMP, 2u * (taps - 1u), 8, 0, 0, 0, 0);
        np_dp_op(&d, "A", NULL, NP_OP_MUX, 2u * (taps - 1u), 8, 2, 0, 0, 1);
        regs += 16u;
    }
    np_dp_op(&d, "A", NULL, NP_OP_REG, 1, regs, 0, 0, 0, 0);
    /* V: v = n sum_d2 - sum_d^2; dots and norms; luma range and gate */
    regs = 1;
    if (c->depth) {
        const_mul(&d, "V", 1, w.sum_d2, n, 0); /* n sum_d2: 9 x = 8 x + x; 4 x, 16 x wiring */
        np_dp_op(&d, "V", NULL, NP_OP_SQR, 1, w.sum_d, 0, 0, 0, 0);
        np_dp_op(&d, "V", "v", NP_OP_ADD, 1, w.v, 0, w.v, 0, 1);
        regs += w.v;
    }
    if (c->normal) {
        /* |nbar|^2: each component's magnitude (a conditional negation; |nbar_k| <= 128 n fits
         * w.nbar - 1 bits), squared unsigned */
        np_dp_op(&d, "V", NULL, NP_OP_NEG, 3, w.nbar - 1u, 0, 0, 0, 0);
        np_dp_op(&d, "V", NULL, NP_OP_SQR, 3, w.nbar - 1u, 0, 0, 0, 1);
        lv = np_dp_add_tree(&d, "V", "nb2", 3, w.nb2, 0, 2);
        (void)lv;
        /* per sample: dot = nbar . n, three signed x signed products (s(w.nbar) x s8) */
        np_dp_op(&d, "V", NULL, NP_OP_SMUL, 3u * lanes, w.nbar, 8, 0, 1, 0);
        np_dp_op(&d, "V", NULL, NP_OP_ADD, 2u * lanes, w.dot, 0, 0, 1, 1);
        np_dp_op(&d, "V", "dot", NP_OP_REG, 0, 0, 0, w.dot, 1, 2); /* wiring: the second adder's output */
        /* nn2 = |n|^2: each s8's magnitude (0..128) squared; bit 7 of a magnitude is set only at 128,
         * whose square is a single bit (2^14), so the squarer is 7 bits wide */
        np_dp_op(&d, "V", NULL, NP_OP_NEG, 3u * lanes, 8, 0, 0, 0, 0);
        np_dp_op(&d, "V", NULL, NP_OP_SQR, 3u * lanes, 7, 0, 0, 0, 1);
        np_dp_op(&d, "V", NULL, NP_OP_ADD, 2u * lanes, w.nn2, 0, 0, 0, 2);
        np_dp_op(&d, "V", "nn2", NP_OP_REG, 0, 0, 0, w.nn2, 0, 3);
        regs += w.nb2 + lanes * (w.dot + w.nn2);
    }
    if (c->luma) {
        np_dp_op(&d, "V", "r", NP_OP_ADD, 1, 8, 0, 8, 0, 0);
        const_mul(&d, "V", 1, 8, r.t_edge, 0);             /* t_edge lmax */
        np_dp_op(&d, "V", NULL, NP_OP_CMPK, 1, 8, 0, 0, 0, 1); /* r < t_min */
        np_dp_op(&d, "V", NULL, NP_OP_CMP, 1, 16, 0, 0, 0, 1); /* 256 r < t_edge lmax */
        regs += 9u;
    }
    np_dp_op(&d, "V", NULL, NP_OP_REG, 1, regs, 0, 0, 0, 0);
    /* P: squares, the least ratio (a comparison tree, or a running one), the counts */
    regs = 1;
    if (c->normal) {
        np_dp_op(&d, "P", "p", NP_OP_SQR, lanes, w.dot, 0, w.p, 0, 0);
        np_dp_op(&d, "P", "q", NP_OP_MUL, lanes, w.nb2, w.nn2, w.q, 0, 0);
        np_dp_op(&d, "P", NULL, NP_OP_CMPK, lanes, w.nn2, 0, 0, 0, 0); /* a sample with a normal: nn2 != 0 */
        /* the least ratio: a tree of n - 1 comparisons (serial: one running comparison) */
        unsigned items = c->serial ? 2u : n;
        for (unsigned k = 0; items > 1u; k++) {
            unsigned here = items / 2u;
            np_dp_op(&d, "P", NULL, NP_OP_MUL, 2u * here, w.p, w.q, 0, 0, 1u + 3u * k);
            np_dp_op(&d, "P", NULL, NP_OP_CMP, here, w.p + w.q, 0, 0, 0, 2u + 3u * k);
            np_dp_op(&d, "P", NULL, NP_OP_MUX, here, w.p + w.q, 2, 0, 0, 3u + 3u * k);
            items -= here;
        }
        np_dp_op(&d, "P", NULL, NP_OP_CMPK, 1, w.nb2, 0, 0, 0, 0); /* nbar = 0 */
        regs += w.p + w.q + 2u;
    }
    if (c->depth) {
        live = 0;
        for (unsigned j = 1; j < n; j++)
            live += r.vd[j] < ((uint64_t)1 << w.v);
        np_dp_op(&d, "P", NULL, NP_OP_CMPK, live, w.v, 0, 0, 0, 0);
        np_dp_op(&d, "P", NULL, NP_OP_INC, live, 5, 0, 0, 0, 1); /* the count: a conditional +1 a threshold */
        np_dp_op(&d, "P", NULL, NP_OP_MUX, live, 5, 2, 0, 0, 2);
        regs += 5u;
    }
    if (c->luma) {
        live = 0;
        for (unsigned j = 1; j < n; j++)
            live += r.rs[j] < 256u;
        np_dp_op(&d, "P", NULL, NP_OP_CMPK, live, 8, 0, 0, 0, 0);
        np_dp_op(&d, "P", NULL, NP_OP_INC, live, 5, 0, 0, 0, 1);
        np_dp_op(&d, "P", NULL, NP_OP_MUX, live, 5, 2, 0, 0, 2);
        regs += 5u;
    }
    np_dp_op(&d, "P", NULL, NP_OP_REG, 1, regs, 0, 0, 0, 0);
    /* C: the normal thresholds (pmin nd < na[j] qmin, constant products, u72), the max of three counts, the mask */
    if (c->normal) {
        /*
         * Each comparison pmin nd < na[j] qmin is over the products' live bits: below
         * both constants' trailing zeros both sides are 0 (no logic); between the two
         * counts only one side has bits, which enter as "not all 0" (a comparison with
         * the constant 0); above, a comparator up to the wider product's top.
         */
        live = 0;
        const_mul(&d, "C", 1, w.p, r.nd, 0);
        unsigned tz_d = tzeros64(r.nd), top_d = w.p + ubits64(r.nd);
        for (unsigned j = 1; j < n; j++)
            if (r.na_on[j]) {
                const_mul(&d, "C", 1, w.q, r.na[j], 0);
                unsigned tz_a = tzeros64(r.na[j]), top_a = w.q + ubits64(r.na[j]);
                unsigned top = top_d > top_a ? top_d : top_a;
                unsigned hi_tz = tz_d > tz_a ? tz_d : tz_a, lo_tz = tz_d > tz_a ? tz_a : tz_d;
                np_dp_op(&d, "C", NULL, NP_OP_CMP, 1, top - hi_tz, 0, 0, 0, 1);
                if (hi_tz > lo_tz)
                    np_dp_op(&d, "C", NULL, NP_OP_CMPK, 1, hi_tz - lo_tz, 0, 0, 0, 1);
                live++;
            }
        np_dp_op(&d, "C", NULL, NP_OP_INC, live, 5, 0, 0, 0, 2);
        np_dp_op(&d, "C", NULL, NP_OP_MUX, live, 5, 2, 0, 0, 3);
    }
    np_dp_op(&d, "C", NULL, NP_OP_CMP, 2, 5, 0, 0, 0, 3);
    /* s <= n: the u5 output port carries np_bits_for_range(0, n) of them */
    np_dp_op(&d, "C", "s", NP_OP_MUX, 2, 5, 2, np_bits_for_range(0, (int64_t)n, 0), 0, 4);
    np_dp_op(&d, "C", NULL, NP_OP_LUT, 1, 5, n, 0, 0, 5);
    np_dp_op(&d, "C", NULL, NP_OP_REG, 1, 5u * 4u + 16u + 1u, 0, 0, 0, 0);
    return d.n;
}

/* --- Trace --- */

static void tr(np_trace *t, size_t n, const char *name, int64_t v)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].signal && strcmp(t[i].signal, name) == 0)
            np_trace_add(&t[i], v);
}

void np_aacount_trace(const np_aacount_cfg *cfg, unsigned k, const np_aacount_sig *s, np_trace *t, size_t n)
{
    unsigned nn = n_of(cfg);
    switch (k) {
    case 0:
        if (cfg->depth) {
            tr(t, n, "sum_d", s->sum_d);
            tr(t, n, "sum_d2", (int64_t)s->sum_d2);
            for (unsigned i = 0; i < nn; i++)
                tr(t, n, "d2", (int64_t)s->w.d[i] * s->w.d[i]);
        }
        if (cfg->normal)
            for (unsigned c = 0; c < 3; c++)
                tr(t, n, "nbar", s->nbar[c]);
        break;
    case 1:
        if (cfg->depth)
            tr(t, n, "v", (int64_t)s->v);
        if (cfg->normal) {
            tr(t, n, "nb2", s->nb2);
            for (unsigned i = 0; i < nn; i++) {
                tr(t, n, "dot", s->dot[i]);
                tr(t, n, "nn2", s->nn2[i]);
            }
        }
        if (cfg->luma)
            tr(t, n, "r", s->r);
        break;
    case 2:
        if (cfg->normal)
            for (unsigned i = 0; i < nn; i++) {
                tr(t, n, "p", (int64_t)s->p[i]);
                tr(t, n, "q", (int64_t)s->q[i]);
            }
        break;
    case 3:
        tr(t, n, "s", s->s);
        break;
    default:
        break;
    }
}
