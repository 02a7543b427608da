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
    const np_span_ctx *t = cv;
    const np_texel_cfg *cfg = t->cfg;
    np_texel_sig *s = sig_of(sv);
    const unsigned sh = NP_TEX_FC - cfg->weight_frac;
    for (unsigned o = 0; o < t->r->n_oct; o++) {
        np_tex_lattice(np_tex_cell(s->u[o][0]), np_tex_cell(s->u[o][1]), np_tex_cell(s->u[o][2]), s->n[o]);
        for (unsigned a = 0; a < 3; a++)
            s->w[o][a] = (uint32_t)np_shr_round_half_up_u(np_tex_frac(s->u[o][a]), sh);
    }
    s->qx = s->qin;
}

/* lerp: a 2^WT + w (b - a), exact. */
static np_s128 lerp(unsigned wt, uint32_t w, np_s128 a, np_s128 b)
{
    return np_add128(np_shl128(a, wt), np_mul128((np_s128)w, np_add128(b, -a)));
}

static void stage_i1(const void *cv, void *sv)
{
    const np_span_ctx *t = cv;
    const np_texel_cfg *cfg = t->cfg;
    np_texel_sig *s = sig_of(sv);
    for (unsigned o = 0; o < t->r->n_oct; o++)
        for (unsigned p = 0; p < 4; p++)
            s->l1[o][p] = lerp(cfg->weight_frac, s->w[o][0], (np_s128)s->n[o][2 * p],
                               (np_s128)s->n[o][2 * p + 1]);
}

static void stage_i2(const void *cv, void *sv)
{
    const np_span_ctx *t = cv;
    const np_texel_cfg *cfg = t->cfg;
    np_texel_sig *s = sig_of(sv);
    for (unsigned o = 0; o < t->r->n_oct; o++)
        for (unsigned p = 0; p < 2; p++)
            s->l2[o][p] = lerp(cfg->weight_frac, s->w[o][1], s->l1[o][2 * p], s->l1[o][2 * p + 1]);
}

static void stage_i3(const void *cv, void *sv)
{
    const np_span_ctx *t = cv;
    const np_texel_cfg *cfg = t->cfg;
    np_texel_sig *s = sig_of(sv);
    for (unsigned o = 0; o < t->r->n_oct; o++)
        s->l3[o] = lerp(cfg->weight_frac, s->w[o][2], s->l2[o][0], s->l2[o][1]);
}

static void stage_a(const void *cv, void *sv)
{
    const np_span_ctx *t = cv;
    const np_texel_cfg *cfg = t->cfg;
    np_texel_sig *s = sig_of(sv);
    const unsigned F = t->F, W = t->W;
    const unsigned nf = NP_TEX_LAT_FRAC + 3u * cfg->weight_frac + NP_TEX_AMP_FRAC;
    for (unsigned o = 0; o < t->r->n_oct; o++)
        s->N[o] = np_tex_to_index(np_mul128((np_s128)t->r->oct[o].amp, s->l3[o]), nf, F, W);
    s->q = np_tex_to_index(s->qx, np_tex_q_frac(t->r), F, W);
}

static void stage_s(const void *cv, void *sv)
{
    const np_span_ctx *t = cv;
    np_texel_sig *s = sig_of(sv);
    np_s128 x = s->q;
    for (unsigned o = 0; o < t->r->n_oct; o++)
        x = np_wrap_s128(np_add128(x, s->N[o]), t->W);
    s->head.x = x;
}

const np_stage_desc np_texel_stages[NP_TEXEL_STAGES] = {
    { "L", stage_l },   { "I1", stage_i1 }, { "I2", stage_i2 },
    { "I3", stage_i3 }, { "A", stage_a },   { "S", stage_s },
    { "C1", np_span_stage_c1 }, { "C2", np_span_stage_c2 }, { "C3", np_span_stage_c3 },
};

/* --- Front end: span set-up and the DDAs --- */

unsigned np_texel_span_setup_cycles(const np_texel_cfg *cfg, const np_tex_regs *r)
{
    const np_tex_sched *front = np_tex_regs_diagonal(r) ? &np_tex_sched_octave_diag : &np_tex_sched_octave;
    return np_tex_sched_cycles(&np_texel_sched_quad, cfg->setup_mults, cfg->mult_lat) +
           r->n_oct * np_tex_sched_cycles(front, cfg->setup_mults, cfg->mult_lat);
}

/* The quadric's set-up: M_q s, M_q ds (18 products); s.M_q s, s.M_q ds, ds.M_q ds, b.s, b.ds (15); sum, round. */
const np_tex_sched np_texel_sched_quad = { "quadric", 2, 2, { 18, 15 } };

static void front_init(void *core, const void *cfg, const np_tex_regs *r)
{
    np_texel_front *f = core;
    const np_texel_cfg *c = cfg;
    memset(f, 0, sizeof *f);
    f->ctx.cfg = c;
    f->ctx.r = r;
    f->ctx.F = np_texel_frac(c);
    f->ctx.W = np_texel_width(c);
    f->ctx.fw = c->w_frac;
}

static unsigned front_begin(void *core, const np_span *sp, np_span_counts *cnt)
{
    np_texel_front *f = core;
    const np_tex_regs *r = f->ctx.r;
    f->sp = *sp;
    f->k = 0;
    cnt->spans++;
    if (sp->n == 0)
        return 0;
    const unsigned cycles = np_texel_span_setup_cycles(f->ctx.cfg, r);
    for (unsigned o = 0; o < r->n_oct; o++) {
        np_tex_oct_span os;
        np_tex_octave_span(r, o, sp->s, sp->ds, &os);
        memcpy(f->u[o], os.u, sizeof os.u);
        memcpy(f->du[o], os.du, sizeof os.du);
    }
    memcpy(f->s, sp->s, sizeof f->s);
    np_s128 q[3];
    np_tex_quadric_exact(r, sp->s, sp->ds, q);
    f->q = q[0];
    f->dq = q[1];
    f->d2q = q[2];
    cnt->span_setups++;
    cnt->setup_cycles += cycles;
    if (!f->ctx.timed)
        return cycles;
    /* Timing: what remains of a prefetched span's set-up, or all of it from the next clock. */
    const uint64_t first = f->ctx.now + 1u;
    uint64_t done = f->fetched ? f->fe_done : (first > f->fe_free ? first : f->fe_free) + cycles;
    f->fetched = 0;
    f->fe_free = done;
    return done > first ? (unsigned)(done - first) : 0u;
}

static void front_prefetch(void *core, const np_span *sp)
{
    np_texel_front *f = core;
    if (sp->n == 0)
        return;
    uint64_t start = f->ctx.now + 1u;
    if (f->fe_free > start)
        start = f->fe_free;
    f->fe_done = start + np_texel_span_setup_cycles(f->ctx.cfg, f->ctx.r);
    f->fe_free = f->fe_done;
    f->fetched = 1;
}

/* One DDA step of every coordinate; no set-up ever follows. */
static unsigned front_advance(void *core, np_span_counts *cnt)
{
    (void)cnt;
    np_texel_front *f = core;
    if (++f->k >= f->sp.n)
        return 0;
    for (unsigned o = 0; o < f->ctx.r->n_oct; o++)
        for (unsigned a = 0; a < 3; a++)
            f->u[o][a] = np_tex_dda(f->u[o][a], f->du[o][a]);
    for (unsigned a = 0; a < 3; a++)
        f->s[a] += f->sp.ds[a];
    /* The quadric's forward differences (in hardware in parallel, on the old values). */
    f->q = np_add128(f->q, f->dq);
    f->dq = np_add128(f->dq, f->d2q);
    return 0;
}

static void front_issue(const void *core, void *sig)
{
    const np_texel_front *f = core;
    np_texel_sig *s = sig;
    for (unsigned o = 0; o < f->ctx.r->n_oct; o++)
        memcpy(s->u[o], f->u[o], sizeof s->u[o]);
    memcpy(s->s, f->s, sizeof s->s);
    s->qin = f->q;
}

/* Pixel k placed directly: u0 + k du (mod 256) and s + k ds, the values the DDAs reach. */
static void front_seek(void *core, const np_span *sp, uint32_t k)
{
    np_texel_front *f = core;
    const np_tex_regs *r = f->ctx.r;
    f->sp = *sp;
    f->k = k;
    for (unsigned o = 0; o < r->n_oct; o++) {
        np_tex_oct_span os;
        np_tex_octave_span(r, o, sp->s, sp->ds, &os);
        for (unsigned a = 0; a < 3; a++) {
            f->du[o][a] = os.du[a];
            f->u[o][a] = np_trunc_u(os.u[a] + (uint64_t)k * (uint64_t)os.du[a], NP_TEX_U_BITS);
        }
    }
    for (unsigned a = 0; a < 3; a++)
        f->s[a] = sp->s[a] + (int64_t)k * sp->ds[a];
    np_s128 q[3];
    np_tex_quadric_exact(r, f->s, sp->ds, q);
    f->q = q[0];
    f->dq = q[1];
    f->d2q = q[2];
}

static size_t front_datapath(const void *cfg, const np_tex_regs *r, np_op *ops, size_t max)
{
    return np_texel_datapath(cfg, r, ops, max);
}

const np_span_engine np_texel_engine = {
    .name = "texel",
    .core_size = sizeof(np_texel_front),
    .sig_size = sizeof(np_texel_sig),
    .stages = np_texel_stages,
    .n_stages = NP_TEXEL_STAGES,
    .init = front_init,
    .begin = front_begin,
    .advance = front_advance,
    .issue = front_issue,
    .seek = front_seek,
    .datapath = front_datapath,
    .prefetch = front_prefetch,
};

static void probe_pixel(const void *pctx, const void *core, const void *sig, uint32_t k)
{
    const np_texel_probe *probe = pctx;
    const np_texel_sig *s = sig;
    if (probe->x)
        probe->x[k] = s->head.x;
    for (unsigned o = 0; o < np_span_ctx_of(core)->r->n_oct; o++)
        if (probe->noise[o])
            probe->noise[o][k] = s->N[o];
}

void np_texel_span(const np_texel_cfg *cfg, const np_tex_regs *r, const np_span *sp,
                   np_tex_pixel *out, np_span_counts *counts, const np_texel_probe *probe)
{
    np_texel_front f;
    np_texel_sig sig;
    front_init(&f, cfg, r);
    np_span_run(&np_texel_engine, &f, &sig, sp, out, counts, probe ? probe_pixel : NULL, probe);
}

/* --- Datapath declaration --- */

/* Bits carried along every pipeline stage besides the data: pixel x and y. */
enum { SIDE_BITS = 2 * NP_TEX_XY_BITS };

size_t np_texel_datapath(const np_texel_cfg *cfg, const np_tex_regs *r, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    const unsigned no = r->n_oct, wt = cfg->weight_frac, F = np_texel_frac(cfg), W = np_texel_width(cfg);
    const unsigned P = cfg->setup_mults, Lm = cfg->mult_lat;
    const unsigned wb = wt < NP_TEX_FC ? wt + 1u : NP_TEX_FC;  /* weight: u(WT+1) Q1.WT (exact u32 at WT = 32) */
    const unsigned qw = np_texel_q_window(cfg, r), alw = np_texel_al_window(cfg);
    const unsigned l1 = NP_TEX_LAT_FRAC + wt, l2 = l1 + wt, l3 = l2 + wt; /* u6 Q0.6 times 2^WT per level */
    const unsigned side = SIDE_BITS + 1u;                     /* x, y and the valid bit */
    /* Texture registers (written by the host between frames). */
    np_dp_op(&d, "T", NULL, NP_OP_REG, 1, np_tex_reg_bits(r), 0, 0, 0, 0);
    /*
     * FE: the span set-up on an engine of P multipliers: per octave
     * (np_tex_sched_octave) M s + o and M ds (s24 x s48 products, exact sums
     * of three < 2^72: s73), rounded once to u40 / s40 (an adder over the 16
     * + 40 bits it keeps); the quadric (np_texel_sched_quad): M_q s and M_q ds
     * (s48 x s48, rows s97), then s.(M_q s) etc. (s48 x the s97 rows, kept
     * modulo 2^qw: only the window is read), so one multiplier of 48 x
     * min(97, qw) covers every product; its accumulator, the rows' register
     * file (6 x s97) and q, dq, d2q (qw each).
     */
    /* Rows M_q s: s(k_bits + 48 + 1) (s97 with the default s48 quadric); narrow operand s48 or k_bits. */
    const unsigned kb = np_tex_k_bits(r), aw = kb > NP_TEX_S_BITS ? kb : NP_TEX_S_BITS;
    const unsigned ms = kb + NP_TEX_S_BITS + 1u, qm = ms < qw ? ms : qw;
    const unsigned fe_prod = aw + qm, fe_sum = fe_prod + 1u;
    np_dp_op(&d, "FE", NULL, NP_OP_MUL, P, aw, qm, 0, 0, 0);
    np_dp_op(&d, "FE", NULL, NP_OP_ADD, P, fe_sum, 0, 0, 0, 1);
    np_dp_op(&d, "FE", NULL, NP_OP_ADD, 1, np_tex_m_frac(r) + NP_TEX_U_BITS, 0, 0, 0, 2);
    np_dp_op(&d, "FE", NULL, NP_OP_REG, 1, P * Lm * fe_prod + P * fe_sum + 6u * ms + 3u * qw + 16u, 0, 0, 0, 0);
    /*
     * D: one DDA step per pixel: u += du (u40, mod 256) per octave and axis, s += ds; the quadric's two
     * forward-difference adders q += dq, dq += d2q (qw bits: exact modulo 2^qw); the pixel counter; the
     * descriptor buffer and the next span's set-up results (u, du per octave, q, dq, d2q).
     */
    np_dp_op(&d, "D", "u", NP_OP_ADD, 3u * no, NP_TEX_U_BITS, 0, NP_TEX_U_BITS, 0, 0);
    np_dp_op(&d, "D", "s", NP_OP_ADD, 3, NP_TEX_S_BITS, 0, NP_TEX_S_BITS, 1, 0);
    np_dp_op(&d, "D", NULL, NP_OP_ADD, 2, qw, 0, 0, 0, 0);
    np_dp_op(&d, "D", NULL, NP_OP_ADD, 1, NP_TEX_N_BITS, 0, 0, 0, 0);
    np_dp_op(&d, "D", NULL, NP_OP_CMP, 1, NP_TEX_N_BITS, 0, 0, 0, 1);
    const unsigned desc = 3u * (NP_TEX_S_BITS + NP_TEX_DS_BITS) + NP_TEX_N_BITS + SIDE_BITS;
    np_dp_op(&d, "D", NULL, NP_OP_REG, 1,
             3u * no * (NP_TEX_U_BITS + NP_TEX_DU_BITS) + 3u * (NP_TEX_S_BITS + NP_TEX_DS_BITS) + 3u * qw +
                 2u * NP_TEX_N_BITS + side + desc + 3u * no * (NP_TEX_U_BITS + NP_TEX_DU_BITS) + 3u * qw,
             0, 0, 0, 0);
    /* L: 8 corner hashes per octave; the weights rounded to WT bits; the quadric's window registered. */
    np_tex_dp_lattice(&d, "L", no, 0);
    if (wt < NP_TEX_FC)
        np_dp_op(&d, "L", "w", NP_OP_ADD, 3u * no, wb, 0, wb, 0, 0);
    else
        np_dp_op(&d, "L", "w", NP_OP_REG, 0, 0, 0, wb, 0, 0);
    np_dp_op(&d, "L", "qx", NP_OP_REG, 0, 0, 0, qw, 1, 0);
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
        np_tex_trace128(t, n, "qx", np_wrap_s128(s->qx, np_texel_q_window(cfg, r)));
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
        np_tex_trace128(t, n, "x", s->head.x);
        break;
    case 8:
        np_tex_trace_colour(r, s->head.seg, s->head.cw, s->head.prod, s->head.pix.rgb, cfg->w_frac, t, n);
        break;
    default:
        break;
    }
}
