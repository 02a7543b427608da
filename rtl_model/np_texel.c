/* SPDX-License-Identifier: MIT */
#include "np_texel.h"

#include <stddef.h>
#include <string.h>

np_texel_cfg np_texel_cfg_default(void)
{
    np_texel_cfg c;
    c.idx_int = 10;
    c.w_frac = 12;
    c.guard = 20; /* nothing accumulates: a few bits below the weight's suffice */
    c.weight_frac = 16;
    c.setup_mults = 2;
    c.mult_lat = 2;
    return c;
}

const char *np_texel_cfg_check(const np_texel_cfg *c)
{
    if (c->idx_int < NP_TEX_IDX_INT_MIN || c->idx_int > 11)
        return "idx_int must be 1..11";
    if (c->w_frac < NP_TEX_W_FRAC_MIN || c->w_frac > NP_TEX_W_FRAC_MAX)
        return "w_frac must be 1..24";
    if (c->weight_frac < NP_TEXEL_WT_MIN || c->weight_frac > NP_TEXEL_WT_MAX)
        return "weight_frac must be 1..32";
    if (np_texel_width(c) > 127)
        return "guard too large: 1 + idx_int + w_frac + guard must be <= 127";
    /* Exact rounding of amp * l3 (20 + 3 WT fraction bits) needs that - F + W <= 128. */
    if (20u + 3u * c->weight_frac + 1u + c->idx_int > 128u)
        return "weight_frac and idx_int too large together (20 + 3 weight_frac + 1 + idx_int <= 128)";
    if (c->setup_mults < 1 || c->setup_mults > 64)
        return "setup_mults must be 1..64";
    if (c->mult_lat < 1 || c->mult_lat > 16)
        return "mult_lat must be 1..16";
    return NULL;
}

double np_texel_error_bound_index(const np_texel_cfg *c, const np_tex_regs *r)
{
    double b = (double)(r->n_oct + 1u) * np_pow2i(-(int)np_texel_frac(c) - 1);
    for (unsigned o = 0; o < r->n_oct; o++) {
        double a = (double)r->oct[o].amp * np_pow2i(-NP_TEX_AMP_FRAC);
        b += (a < 0 ? -a : a) * 3.0 * (63.0 / 64.0) * np_pow2i(-(int)c->weight_frac - 1);
    }
    return b;
}

/* --- Stages --- */

static np_texel_sig *sig_of(void *s) { return (np_texel_sig *)s; }

static void stage_l(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    const unsigned sh = NP_TEX_FC - t->cfg->weight_frac;
    for (unsigned o = 0; o < t->r->n_oct; o++) {
        np_tex_lattice(np_tex_cell(s->u[o][0]), np_tex_cell(s->u[o][1]), np_tex_cell(s->u[o][2]), s->n[o]);
        for (unsigned a = 0; a < 3; a++)
            s->w[o][a] = (uint32_t)np_shr_round_half_up_u(np_tex_frac(s->u[o][a]), sh);
    }
    const int64_t zero[3] = { 0, 0, 0 };
    np_s128 q[3];
    np_tex_quadric_exact(t->r, s->s, zero, q);
    s->qx = q[0];
}

/* lerp: a 2^WT + w (b - a), exact. */
static np_s128 lerp(unsigned wt, uint32_t w, np_s128 a, np_s128 b)
{
    return np_add128(np_shl128(a, wt), np_mul128((np_s128)w, np_add128(b, -a)));
}

static void stage_i1(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    for (unsigned o = 0; o < t->r->n_oct; o++)
        for (unsigned p = 0; p < 4; p++)
            s->l1[o][p] = lerp(t->cfg->weight_frac, s->w[o][0], (np_s128)s->n[o][2 * p],
                               (np_s128)s->n[o][2 * p + 1]);
}

static void stage_i2(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    for (unsigned o = 0; o < t->r->n_oct; o++)
        for (unsigned p = 0; p < 2; p++)
            s->l2[o][p] = lerp(t->cfg->weight_frac, s->w[o][1], s->l1[o][2 * p], s->l1[o][2 * p + 1]);
}

static void stage_i3(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    for (unsigned o = 0; o < t->r->n_oct; o++)
        s->l3[o] = lerp(t->cfg->weight_frac, s->w[o][2], s->l2[o][0], s->l2[o][1]);
}

static void stage_a(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    const unsigned F = np_texel_frac(t->cfg), W = np_texel_width(t->cfg);
    const unsigned nf = NP_TEX_LAT_FRAC + 3u * t->cfg->weight_frac + NP_TEX_AMP_FRAC;
    for (unsigned o = 0; o < t->r->n_oct; o++)
        s->N[o] = np_tex_to_index(np_mul128((np_s128)t->r->oct[o].amp, s->l3[o]), nf, F, W);
    s->q = np_tex_to_index(s->qx, NP_TEX_Q_EXACT_FRAC, F, W);
}

static void stage_s(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    const unsigned W = np_texel_width(t->cfg);
    np_s128 x = s->q;
    for (unsigned o = 0; o < t->r->n_oct; o++)
        x = np_wrap_s128(np_add128(x, s->N[o]), W);
    s->x = x;
}

static void stage_c1(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    np_tex_colour_split(t->r, s->x, np_texel_frac(t->cfg), t->cfg->w_frac, &s->seg, &s->cw);
}

static void stage_c2(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    np_tex_colour_mix(t->r, s->seg, s->cw, t->cfg->w_frac, s->prod);
}

static void stage_c3(const void *cv, void *sv)
{
    const np_texel_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    np_tex_colour_round(s->prod, t->cfg->w_frac, s->rgb);
}

const np_stage_desc np_texel_stages[NP_TEXEL_STAGES] = {
    { "L", stage_l },   { "I1", stage_i1 }, { "I2", stage_i2 },
    { "I3", stage_i3 }, { "A", stage_a },   { "S", stage_s },
    { "C1", stage_c1 }, { "C2", stage_c2 }, { "C3", stage_c3 },
};

/* --- Front end: span set-up and the DDAs --- */

unsigned np_texel_span_setup_cycles(const np_texel_cfg *cfg, const np_tex_regs *r)
{
    const np_tex_sched *front = np_tex_regs_diagonal(r) ? &np_tex_sched_octave_diag : &np_tex_sched_octave;
    return r->n_oct * np_tex_sched_cycles(front, cfg->setup_mults, cfg->mult_lat);
}

static unsigned front_begin(const np_texel_ctx *t, const np_span *sp, uint64_t u[][3], int64_t du[][3],
                            int64_t s[3], np_texel_counts *cnt)
{
    cnt->spans++;
    if (sp->n == 0)
        return 0;
    const unsigned cycles = np_texel_span_setup_cycles(t->cfg, t->r);
    for (unsigned o = 0; o < t->r->n_oct; o++) {
        np_tex_oct_span os;
        np_tex_octave_span(t->r, o, sp->s, sp->ds, &os);
        memcpy(u[o], os.u, sizeof os.u);
        memcpy(du[o], os.du, sizeof os.du);
    }
    memcpy(s, sp->s, 3 * sizeof s[0]);
    cnt->span_setups++;
    cnt->setup_cycles += cycles;
    return cycles;
}

static void front_load(const np_texel_ctx *t, const np_span *sp, uint32_t k, const uint64_t u[][3],
                       const int64_t s[3], np_texel_sig *sig)
{
    memset(sig, 0, sizeof *sig);
    sig->px = (uint16_t)(sp->x0 + k);
    sig->py = sp->y;
    for (unsigned o = 0; o < t->r->n_oct; o++)
        memcpy(sig->u[o], u[o], sizeof sig->u[o]);
    memcpy(sig->s, s, sizeof sig->s);
}

static void front_step(const np_texel_ctx *t, const np_span *sp, uint64_t u[][3], const int64_t du[][3],
                       int64_t s[3])
{
    for (unsigned o = 0; o < t->r->n_oct; o++)
        for (unsigned a = 0; a < 3; a++)
            u[o][a] = np_tex_dda(u[o][a], du[o][a]);
    for (unsigned a = 0; a < 3; a++)
        s[a] += sp->ds[a];
}

void np_texel_span(const np_texel_cfg *cfg, const np_tex_regs *r, const np_span *sp,
                   np_tex_pixel *out, np_texel_counts *counts, const np_texel_probe *probe)
{
    np_texel_ctx t = { cfg, r };
    np_texel_counts dummy;
    np_texel_counts *cnt = counts ? counts : &dummy;
    uint64_t u[NP_TEX_MAX_OCTAVES][3];
    int64_t du[NP_TEX_MAX_OCTAVES][3], s[3];
    np_texel_sig sig;
    memset(&dummy, 0, sizeof dummy);
    front_begin(&t, sp, u, du, s, cnt);
    for (uint32_t k = 0; k < sp->n; k++) {
        front_load(&t, sp, k, u, s, &sig);
        for (unsigned st = 0; st < NP_TEXEL_STAGES; st++)
            np_texel_stages[st].fn(&t, &sig);
        out[k].x = sig.px;
        out[k].y = sig.py;
        memcpy(out[k].rgb, sig.rgb, sizeof sig.rgb);
        if (probe) {
            if (probe->x)
                probe->x[k] = sig.x;
            for (unsigned o = 0; o < r->n_oct; o++)
                if (probe->noise[o])
                    probe->noise[o][k] = sig.N[o];
        }
        cnt->pixels++;
        front_step(&t, sp, u, du, s);
    }
}

/* --- Cycle-accurate model --- */

int np_texel_sim_init(np_texel_sim *m, const np_texel_cfg *cfg, const np_tex_regs *r)
{
    memset(m, 0, sizeof *m);
    m->ctx.cfg = cfg;
    m->ctx.r = r;
    return np_pipe_init(&m->pipe, np_texel_stages, NP_TEXEL_STAGES, sizeof(np_texel_sig), &m->ctx);
}

void np_texel_sim_free(np_texel_sim *m) { np_pipe_free(&m->pipe); }

void np_texel_sim_reset(np_texel_sim *m)
{
    np_pipe_reset(&m->pipe);
    m->busy = 0;
    m->stall = 0;
    m->k = 0;
    memset(&m->stats, 0, sizeof m->stats);
}

void np_texel_sim_eval(np_texel_sim *m, np_texel_port *p)
{
    p->in_ready = !m->busy;
    m->pport.in_valid = m->busy && m->stall == 0;
    if (m->pport.in_valid)
        front_load(&m->ctx, &m->sp, m->k, m->u, m->s, &m->pending);
    m->pport.in_sig = &m->pending;
    m->pport.out_ready = p->out_ready;
    np_pipe_eval(&m->pipe, &m->pport);
    p->out_valid = m->pport.out_valid;
    if (p->out_valid) {
        const np_texel_sig *o = m->pport.out_sig;
        p->out.x = o->px;
        p->out.y = o->py;
        memcpy(p->out.rgb, o->rgb, sizeof p->out.rgb);
    }
}

void np_texel_sim_clock(np_texel_sim *m, const np_texel_port *p)
{
    np_texel_stats *st = &m->stats;
    st->cycles++;
    int issued = m->pport.in_valid && m->pport.in_ready;
    np_pipe_clock(&m->pipe, &m->pport);
    if (m->busy) {
        if (m->stall > 0) {
            m->stall--;
            st->setup_stalls++;
        } else if (issued) {
            st->counts.pixels++;
            m->k++;
            if (m->k >= m->sp.n)
                m->busy = 0;
            else
                front_step(&m->ctx, &m->sp, m->u, m->du, m->s);
        } else {
            st->out_stalls++;
        }
    } else if (p->in_valid) {
        m->sp = *p->in;
        m->k = 0;
        m->stall = front_begin(&m->ctx, &m->sp, m->u, m->du, m->s, &st->counts);
        m->busy = m->sp.n > 0;
    } else {
        st->idle++;
    }
}

int np_texel_sim_idle(const np_texel_sim *m) { return !m->busy && np_pipe_occupancy(&m->pipe) == 0; }

/* --- Datapath declaration --- */

/* Bits carried along every pipeline stage besides the data: pixel x and y. */
enum { SIDE_BITS = 2 * NP_TEX_XY_BITS };

size_t np_texel_datapath(const np_texel_cfg *cfg, const np_tex_regs *r, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    const unsigned no = r->n_oct, wt = cfg->weight_frac, F = np_texel_frac(cfg), W = np_texel_width(cfg);
    const unsigned P = cfg->setup_mults, Lm = cfg->mult_lat;
    const unsigned wb = wt < NP_TEX_FC ? wt + 1u : NP_TEX_FC;  /* weight: u(WT+1) Q1.WT (exact u32 at WT = 32) */
    const unsigned qw = np_texel_q_window(cfg), alw = np_texel_al_window(cfg);
    const unsigned l1 = NP_TEX_LAT_FRAC + wt, l2 = l1 + wt, l3 = l2 + wt; /* u6 Q0.6 times 2^WT per level */
    const unsigned side = SIDE_BITS + 1u;                     /* x, y and the valid bit */
    /* Texture registers (written by the host between frames). */
    np_dp_op(&d, "T", NULL, NP_OP_REG, 1, np_tex_reg_bits(r), 0, 0, 0, 0);
    /*
     * FE: the span set-up on an engine of P multipliers (np_tex_sched_octave):
     * M s + o and M ds (s24 x s48 products, exact sums of three < 2^72: s73),
     * rounded once to u40 / s40 (an adder over the 16 + 40 bits it keeps).
     */
    const unsigned fe_prod = NP_TEX_M_BITS + NP_TEX_S_BITS, fe_sum = fe_prod + 1u;
    np_dp_op(&d, "FE", NULL, NP_OP_MUL, P, NP_TEX_M_BITS, NP_TEX_S_BITS, 0, 0, 0);
    np_dp_op(&d, "FE", NULL, NP_OP_ADD, P, fe_sum, 0, 0, 0, 1);
    np_dp_op(&d, "FE", NULL, NP_OP_ADD, 1, NP_TEX_M_FRAC + NP_TEX_U_BITS, 0, 0, 0, 2);
    np_dp_op(&d, "FE", NULL, NP_OP_REG, 1, P * Lm * fe_prod + P * fe_sum + 16u, 0, 0, 0, 0); /* + stall counter */
    /* D: one DDA step per pixel: u += du (u40, mod 256) per octave and axis, s += ds; the pixel counter. */
    np_dp_op(&d, "D", "u", NP_OP_ADD, 3u * no, NP_TEX_U_BITS, 0, NP_TEX_U_BITS, 0, 0);
    np_dp_op(&d, "D", "s", NP_OP_ADD, 3, NP_TEX_S_BITS, 0, NP_TEX_S_BITS, 1, 0);
    np_dp_op(&d, "D", NULL, NP_OP_ADD, 1, NP_TEX_N_BITS, 0, 0, 0, 0);
    np_dp_op(&d, "D", NULL, NP_OP_CMP, 1, NP_TEX_N_BITS, 0, 0, 0, 1);
    np_dp_op(&d, "D", NULL, NP_OP_REG, 1,
             3u * no * (NP_TEX_U_BITS + NP_TEX_DU_BITS) + 3u * (NP_TEX_S_BITS + NP_TEX_DS_BITS) +
                 2u * NP_TEX_N_BITS + side,
             0, 0, 0, 0);
    /* L: 8 corner hashes per octave; the weights rounded to WT bits; the exact quadric (window of qw bits). */
    np_tex_dp_lattice(&d, "L", no, 0);
    if (wt < NP_TEX_FC)
        np_dp_op(&d, "L", "w", NP_OP_ADD, 3u * no, wb, 0, wb, 0, 0);
    else
        np_dp_op(&d, "L", "w", NP_OP_REG, 0, 0, 0, wb, 0, 0);
    /*
     * The quadric q'(s) at Q.88 (np_tex_quadric_exact with ds = 0): M_q s (9
     * products s48 x s48, rows summed: |.| < 3 2^94, s97), b.s (3 products),
     * s.(M_q s) (3 products, kept modulo 2^qw: only the window is read), sums.
     */
    const unsigned ms = 2u * NP_TEX_S_BITS + 1u;
    np_dp_op(&d, "L", NULL, NP_OP_MUL, 12, NP_TEX_K_BITS, NP_TEX_S_BITS, 0, 0, 0);
    np_dp_op(&d, "L", NULL, NP_OP_ADD, 6, ms, 0, 0, 0, 1);
    np_dp_op(&d, "L", NULL, NP_OP_ADD, 2, ms, 0, 0, 0, 2);
    np_dp_op(&d, "L", NULL, NP_OP_MUL, 3, NP_TEX_S_BITS, ms < qw ? ms : qw, 0, 0, 3);
    np_dp_op(&d, "L", NULL, NP_OP_ADD, 2, qw, 0, 0, 0, 4);
    np_dp_op(&d, "L", NULL, NP_OP_ADD, 1, qw, 0, 0, 0, 5);
    np_dp_op(&d, "L", "qx", NP_OP_ADD, 1, qw, 0, qw, 1, 6);
    np_dp_op(&d, "L", NULL, NP_OP_REG, 1, no * (8u * NP_TEX_LAT_FRAC + 3u * wb) + qw + side, 0, 0, 0, 0);
    /* I1 I2 I3: l = a 2^WT + w (b - a), exact: 4, 2, 1 lerps per octave. */
    np_dp_op(&d, "I1", "d1", NP_OP_ADD, 4u * no, NP_TEX_LAT_FRAC + 1u, 0, NP_TEX_LAT_FRAC + 1u, 1, 0);
    np_dp_op(&d, "I1", "p1", NP_OP_MUL, 4u * no, wb, NP_TEX_LAT_FRAC + 1u, l1 + 1u, 1, 1);
    np_dp_op(&d, "I1", "l1", NP_OP_ADD, 4u * no, l1, 0, l1, 0, 2);
    np_dp_op(&d, "I1", NULL, NP_OP_REG, 1, no * (4u * l1 + 2u * wb) + qw + side, 0, 0, 0, 0);
    np_dp_op(&d, "I2", "d2", NP_OP_ADD, 2u * no, l1 + 1u, 0, l1 + 1u, 1, 0);
    np_dp_op(&d, "I2", "p2", NP_OP_MUL, 2u * no, wb, l1 + 1u, l2 + 1u, 1, 1);
    np_dp_op(&d, "I2", "l2", NP_OP_ADD, 2u * no, l2, 0, l2, 0, 2);
    np_dp_op(&d, "I2", NULL, NP_OP_REG, 1, no * (2u * l2 + wb) + qw + side, 0, 0, 0, 0);
    np_dp_op(&d, "I3", "d3", NP_OP_ADD, no, l2 + 1u, 0, l2 + 1u, 1, 0);
    np_dp_op(&d, "I3", "p3", NP_OP_MUL, no, wb, l2 + 1u, l3 + 1u, 1, 1);
    np_dp_op(&d, "I3", "l3", NP_OP_ADD, no, l3, 0, l3, 0, 2);
    np_dp_op(&d, "I3", NULL, NP_OP_REG, 1, no * l3 + qw + side, 0, 0, 0, 0);
    /* A: a' l3 (s32 x u(l3), kept modulo 2^alw), rounded once to F bits; the quadric rounded to F bits. */
    np_dp_op(&d, "A", "al", NP_OP_MUL, no, NP_TEX_AMP_BITS, l3, alw, 1, 0);
    np_dp_op(&d, "A", "N", NP_OP_ADD, no, W + 1u, 0, W, 1, 1);
    np_dp_op(&d, "A", "q", NP_OP_ADD, 1, W + 1u, 0, W, 1, 0);
    np_dp_op(&d, "A", NULL, NP_OP_REG, 1, (no + 1u) * W + side, 0, 0, 0, 0);
    /* S: x = Q + sum N (mod 2^W), an adder tree. */
    np_dp_add_tree(&d, "S", "x", no + 1u, W, 1, 0);
    np_dp_op(&d, "S", NULL, NP_OP_REG, 1, W + side, 0, 0, 0, 0);
    np_tex_dp_colour(&d, r, F, W, cfg->w_frac, 0, SIDE_BITS);
    return d.n;
}

void np_texel_trace(const np_texel_cfg *cfg, const np_tex_regs *r, unsigned k, const np_texel_sig *s,
                    np_trace *t, size_t n)
{
    const unsigned wt = cfg->weight_frac;
    switch (k) {
    case 0:
        for (unsigned o = 0; o < r->n_oct; o++)
            for (unsigned a = 0; a < 3; a++) {
                np_tex_trace(t, n, "u", (int64_t)s->u[o][a]);
                np_tex_trace(t, n, "w", s->w[o][a]);
            }
        for (unsigned o = 0; o < r->n_oct; o++)
            for (unsigned c = 0; c < 8; c++)
                np_tex_trace(t, n, "n", s->n[o][c]);
        for (unsigned a = 0; a < 3; a++)
            np_tex_trace(t, n, "s", s->s[a]);
        np_tex_trace128(t, n, "qx", np_wrap_s128(s->qx, np_texel_q_window(cfg)));
        break;
    case 1:
        for (unsigned o = 0; o < r->n_oct; o++)
            for (unsigned p = 0; p < 4; p++) {
                np_s128 a = s->n[o][2 * p], b = s->n[o][2 * p + 1];
                np_tex_trace128(t, n, "d1", b - a);
                np_tex_trace128(t, n, "p1", s->l1[o][p] - np_shl128(a, wt));
                np_tex_trace128(t, n, "l1", s->l1[o][p]);
            }
        break;
    case 2:
        for (unsigned o = 0; o < r->n_oct; o++)
            for (unsigned p = 0; p < 2; p++) {
                np_s128 a = s->l1[o][2 * p], b = s->l1[o][2 * p + 1];
                np_tex_trace128(t, n, "d2", b - a);
                np_tex_trace128(t, n, "p2", s->l2[o][p] - np_shl128(a, wt));
                np_tex_trace128(t, n, "l2", s->l2[o][p]);
            }
        break;
    case 3:
        for (unsigned o = 0; o < r->n_oct; o++) {
            np_s128 a = s->l2[o][0], b = s->l2[o][1];
            np_tex_trace128(t, n, "d3", b - a);
            np_tex_trace128(t, n, "p3", s->l3[o] - np_shl128(a, wt));
            np_tex_trace128(t, n, "l3", s->l3[o]);
        }
        break;
    case 4:
        for (unsigned o = 0; o < r->n_oct; o++) {
            np_tex_trace128(t, n, "al", np_wrap_s128(np_mul128((np_s128)r->oct[o].amp, s->l3[o]), np_texel_al_window(cfg)));
            np_tex_trace128(t, n, "N", s->N[o]);
        }
        np_tex_trace128(t, n, "q", s->q);
        break;
    case 5:
        np_tex_trace128(t, n, "x", s->x);
        break;
    case 8:
        np_tex_trace_colour(r, s->seg, s->cw, s->prod, s->rgb, cfg->w_frac, t, n);
        break;
    default:
        break;
    }
}
