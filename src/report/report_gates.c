/* SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "np_report.h"

/*
 * Calibration (docs/cost-model.md has the commands; the CTest case
 * report.cost_model_calibration re-measures with Yosys and fails when the
 * model is more than 25 % from a measurement):
 *   adders 4, 9, 16, 24 bits: 34, 84.5, 156, 240 (narrow ones cost less
 *     per bit; 35 / 51 levels for 16 / 24: 2w + 3)
 *   16-bit comparator 126 (7.9 per bit, 16 levels)
 *   16-bit 2:1 mux 48.5 (3.0 per bit, 3 levels)
 *   12-bit conditional negate 70.5 (5.9 per bit, 23 levels)
 *   8x8 multiplier 550 (8.6 per pp bit, 47 levels), 13x13 signed 1643.5
 *     (9.7 per pp bit, 72 levels), 2.8 (a + b) levels; per stage of the
 *     synthesised RTL (report gates --synth, docs/cost-model.md) narrow
 *     multipliers cost less per pp bit: 10.2 a b - 8.0 (a + b)
 *   3 -> 6 bit pattern lookup 16 alone, but nothing beyond the adder it feeds
 *     (hash6: 448 against 415.8 for its seven adders): 0
 *   D flip-flop 4, with its load enable 7.03 per bit (dffe16 112.5): 7.0
 *   incrementer 8 / 16 bits 35.5 / 67, comparison with a constant 16 bits
 *     23.5 (1.5), squarers 8, 11, 16, 23 bits 359, 857, 1950.5, 4327.5
 *     (Yosys builds the whole a x a array: the cost per a^2 bit grows)
 *   the carry out of a 10-bit sum alone (carry10) 52
 * The per-bit slopes and the per-operator edges (add, inc, carry, sqr) are
 * the values that put every stage of the synthesised classic3 (five
 * configurations) and simplex3 (four) closest to Yosys (largest deviation
 * 8.9 %, docs/cost-model.md "Model against synthesis, per stage").
 */
const np_cost_model np_cost_default = {
    .add_bit = 9.6,
    .add_edge = 6.0,
    .cmp_bit = 7.9,
    .mul_pp = 10.2,
    .mul_edge = 8.0,
    .smul_edge = 14.0,
    .mux2_bit = 3.0,
    .neg_bit = 5.9,
    .lut_bit = 0.0,
    .rom_bit = 0.33,
    .ff_bit = 7.0,
    .inc_bit = 4.0,
    .inc_edge = 4.0,
    .cmpk_bit = 1.5,
    .sqr_pp = 9.0,
    .sqr_edge = 27.1,
    .carry_bit = 4.8,
    .add_d0 = 3.0,
    .mul_d = 2.8,
    .mux_d = 3.0,
    .lut_d = 5.0,
};

static double clog2(unsigned k)
{
    unsigned l = 0;
    while ((1u << l) < k)
        l++;
    return (double)l;
}

double np_cost_op_gates(const np_cost_model *m, const np_op *op)
{
    double a = (double)op->a, b = (double)op->b, per;
    switch (op->kind) {
    case NP_OP_ADD: per = m->add_bit * a - m->add_edge; break;
    case NP_OP_CMP: per = m->cmp_bit * a; break;
    case NP_OP_MUL:
        per = m->mul_pp * a * b - m->mul_edge * (a + b);
        if (per < 1.5 * a * b)
            per = 1.5 * a * b;
        break;
    case NP_OP_SMUL:
        per = m->mul_pp * a * b - m->mul_edge * (a + b);
        if (per < 1.5 * a * b)
            per = 1.5 * a * b;
        per += m->smul_edge * (a + b);
        break;
    case NP_OP_MULLO: /* the partial-product bits under bit a: a b - b (b - 1) / 2 */
        per = m->mul_pp * (a * b - b * (b - 1.0) / 2.0) - m->mul_edge * (a + b);
        if (per < 1.5 * (a * b - b * (b - 1.0) / 2.0))
            per = 1.5 * (a * b - b * (b - 1.0) / 2.0);
        break;
    case NP_OP_MUX: per = m->mux2_bit * a * (b > 1 ? b - 1.0 : 0.0); break;
    case NP_OP_NEG: per = m->neg_bit * a; break;
    case NP_OP_LUT: per = m->lut_bit * ldexp(1.0, (int)op->a) * b; break;
    case NP_OP_ROM: per = m->rom_bit * ldexp(1.0, (int)op->a) * b; break;
    case NP_OP_REG: per = m->ff_bit * a; break;
    case NP_OP_INC: per = m->inc_bit * a - m->inc_edge; break;
    case NP_OP_CMPK: per = m->cmpk_bit * a; break;
    case NP_OP_SQR: per = m->sqr_pp * a * a - m->sqr_edge * a; break;
    case NP_OP_CARRY: per = m->carry_bit * a; break;
    default: per = 0.0; break;
    }
    if (per < 0.0) /* a 0-bit operator (inc_edge, add_edge: an incrementer of 1 bit is an inverter) */
        per = 0.0;
    return per * (double)op->count;
}

double np_cost_op_delay(const np_cost_model *m, const np_op *op)
{
    if (op->count == 0)
        return 0.0;
    double a = (double)op->a, b = (double)op->b;
    switch (op->kind) {
    case NP_OP_ADD: return 2.0 * a + m->add_d0;
    case NP_OP_CMP: return a;
    case NP_OP_MUL:
    case NP_OP_SMUL:
    case NP_OP_MULLO: return m->mul_d * (a + b);
    case NP_OP_MUX: return m->mux_d * clog2(op->b);
    case NP_OP_NEG: return 2.0 * a;
    case NP_OP_LUT: return m->lut_d;
    case NP_OP_ROM: return 2.0 * a + m->lut_d;
    case NP_OP_INC: return 2.0 * a + m->add_d0;
    case NP_OP_CMPK: return a;
    case NP_OP_CARRY: return 2.0 * a;
    case NP_OP_SQR: return m->mul_d * 2.0 * a;
    default: return 0.0;
    }
}

/* Levels of ops a stage may chain (np_op.level). */
enum { LEVELS = 16 };

int np_unit_cost_compute(const np_unit *u, const void *cfg, const np_cost_model *m, np_unit_cost *c,
                         char *err, size_t errlen)
{
    memset(c, 0, sizeof *c);
    c->unit = u;
    if (!u->datapath) {
        snprintf(err, errlen, "unit %s declares no datapath", u->name);
        return -1;
    }
    np_unit_cfg_format(u, cfg, c->cfg, sizeof c->cfg);
    c->n_ops = u->datapath(cfg, c->ops, NP_REPORT_MAX_OPS);
    if (c->n_ops > NP_REPORT_MAX_OPS) {
        snprintf(err, errlen, "unit %s declares %zu ops (max %d)", u->name, c->n_ops, NP_REPORT_MAX_OPS);
        return -1;
    }
    if (u->timing) {
        /* Stages in declaration order; latency, throughput and set-ups from the unit's schedule. */
        if (u->timing(cfg, &c->timing, err, errlen) != 0)
            return -1;
        c->has_timing = 1;
        for (size_t i = 0; i < c->n_ops; i++) {
            unsigned k = 0;
            while (k < c->n_stages && strcmp(c->st[k].name, c->ops[i].stage) != 0)
                k++;
            if (k == c->n_stages) {
                if (k == NP_REPORT_MAX_STAGES) {
                    snprintf(err, errlen, "unit %s declares more than %d stages", u->name, NP_REPORT_MAX_STAGES);
                    return -1;
                }
                snprintf(c->st[k].name, sizeof c->st[k].name, "%s", c->ops[i].stage);
                c->n_stages++;
            }
        }
        c->latency = c->timing.latency;
        c->throughput = c->timing.throughput;
    } else {
        /* Stages and latency come from the cycle-accurate model itself. */
        np_pipe p;
        if (u->pipe_init(&p, cfg) != 0) {
            snprintf(err, errlen, "out of memory");
            return -1;
        }
        c->latency = np_pipe_latency(&p);
        c->n_stages = p.depth < NP_REPORT_MAX_STAGES ? p.depth : NP_REPORT_MAX_STAGES;
        for (unsigned k = 0; k < c->n_stages; k++)
            snprintf(c->st[k].name, sizeof c->st[k].name, "%s", p.stages[k].name);
        np_pipe_free(&p);
        c->throughput = 1.0; /* every unit modelled on np_pipe accepts one input per clock */
    }
    for (unsigned k = 0; k < c->n_stages; k++) {
        c->st[k].clocks = 1;
        for (unsigned j = 0; c->has_timing && j < c->timing.n_multi && j < NP_UNIT_MAX_MULTI; j++)
            if (strcmp(c->timing.multi[j].stage, c->st[k].name) == 0 && c->timing.multi[j].clocks > 1)
                c->st[k].clocks = c->timing.multi[j].clocks;
    }
    double level_delay[NP_REPORT_MAX_STAGES][LEVELS];
    memset(level_delay, 0, sizeof level_delay);
    for (size_t i = 0; i < c->n_ops; i++) {
        const np_op *op = &c->ops[i];
        unsigned k = 0;
        while (k < c->n_stages && strcmp(c->st[k].name, op->stage) != 0)
            k++;
        if (k == c->n_stages) {
            snprintf(err, errlen, "unit %s: op in unknown stage '%s'", u->name, op->stage);
            return -1;
        }
        double g = np_cost_op_gates(m, op);
        if (op->kind == NP_OP_REG) {
            c->st[k].reg_bits += op->a * op->count;
            c->st[k].regs += g;
        } else {
            c->st[k].logic += g;
        }
        unsigned lv = op->level < LEVELS ? op->level : LEVELS - 1u;
        double d = np_cost_op_delay(m, op);
        if (d > level_delay[k][lv])
            level_delay[k][lv] = d;
    }
    for (unsigned k = 0; k < c->n_stages; k++) {
        for (unsigned lv = 0; lv < LEVELS; lv++)
            c->st[k].delay += level_delay[k][lv];
        c->st[k].delay /= (double)c->st[k].clocks;
        c->logic += c->st[k].logic;
        c->regs += c->st[k].regs;
        c->reg_bits += c->st[k].reg_bits;
        if (c->st[k].delay > c->crit) {
            c->crit = c->st[k].delay;
            snprintf(c->crit_stage, sizeof c->crit_stage, "%s", c->st[k].name);
        }
    }
    c->total = c->logic + c->regs;
    return 0;
}

/* --- Pipelining to a target clock (--levels) --- */

/*
 * Stages whose every adder updates its own register in one clock (DDAs,
 * forward differences, accumulators): cut points cannot go inside such a
 * loop, so each of its operators must fit the clock by itself.
 */
static int recurrence_stage(const char *unit, const char *stage)
{
    static const char *const rec[][2] = { { "fdiff", "X" }, { "texel", "D" } };
    for (size_t i = 0; i < sizeof rec / sizeof rec[0]; i++)
        if (strcmp(rec[i][0], unit) == 0 && strcmp(rec[i][1], stage) == 0)
            return 1;
    return 0;
}

/* Bits an operator's result carries across a cut: its declared output, else its operand widths. */
static unsigned op_bits(const np_op *op)
{
    unsigned w = op->out ? op->out : (op->kind == NP_OP_MUL ? op->a + op->b : op->a);
    return w * op->count;
}

/* Bits one cut inside an operator holds: a ripple adder its operands' upper parts and the low sum; a
 * multiplier's array its carry-save rows. */
static unsigned inner_bits(const np_op *op)
{
    switch (op->kind) {
    case NP_OP_ADD: return (2u * op->a + 1u) * op->count;
    case NP_OP_MUL:
    case NP_OP_SMUL:
    case NP_OP_MULLO: return 2u * (op->a + op->b) * op->count;
    default: return op->a * op->count;
    }
}

void np_report_retime(const np_unit_cost *c, unsigned levels, np_stage_retime *r)
{
    const double N = (double)levels;
    for (unsigned k = 0; k < c->n_stages; k++) {
        np_stage_retime *t = &r[k];
        memset(t, 0, sizeof *t);
        t->clocks = c->st[k].clocks;
        t->path = c->st[k].delay * (double)t->clocks;
        double dl[LEVELS] = { 0 };
        unsigned bl[LEVELS] = { 0 };
        const np_op *deep[LEVELS] = { NULL };
        for (size_t i = 0; i < c->n_ops; i++) {
            const np_op *op = &c->ops[i];
            if (strcmp(op->stage, c->st[k].name) != 0 || op->kind == NP_OP_REG || op->count == 0)
                continue;
            unsigned lv = op->level < LEVELS ? op->level : LEVELS - 1u;
            double d = np_cost_op_delay(&np_cost_default, op);
            if (d > dl[lv]) {
                dl[lv] = d;
                deep[lv] = op;
            }
            bl[lv] += op_bits(op);
        }
        t->meets = 1;
        if (recurrence_stage(c->unit->name, c->st[k].name)) {
            /* Feed-forward retiming cannot enter the loops: each level must fit the clock on its own. */
            for (unsigned lv = 0; lv < LEVELS; lv++)
                if (dl[lv] > t->per_clock)
                    t->per_clock = dl[lv];
            for (unsigned lv = 0; lv < LEVELS && t->meets; lv++)
                if (dl[lv] > N) {
                    t->meets = 0;
                    snprintf(t->why, sizeof t->why,
                             "a one-clock recurrence: its %u-bit adder (%s) is %.0f levels as a ripple adder; "
                             "needs a carry-lookahead (about %.0f levels) or carry-save accumulator",
                             deep[lv]->a, deep[lv]->signal ? deep[lv]->signal : "the loop", dl[lv],
                             2.0 * ceil(log2((double)deep[lv]->a)) + 4.0);
                }
            /* The levels between the loops may still be cut. */
            double acc = 0;
            for (unsigned lv = 0; lv < LEVELS; lv++) {
                if (acc > 0 && acc + dl[lv] > N) {
                    t->cuts++;
                    t->bits += bl[lv > 0 ? lv - 1u : 0];
                    acc = 0;
                }
                acc += dl[lv];
            }
            continue;
        }
        /* Budget: N per clock over the clocks the stage already takes. */
        const double budget = N;
        double acc = 0, worst = 0;
        for (unsigned lv = 0; lv < LEVELS; lv++) {
            double d = dl[lv] / (double)t->clocks; /* a multi-clock stage is already pipelined that deep */
            if (d <= 0)
                continue;
            if (acc > 0 && acc + d > budget) {
                t->cuts++;
                t->bits += bl[lv > 0 ? lv - 1u : 0];
                worst = acc > worst ? acc : worst;
                acc = 0;
            }
            if (d > budget) {
                unsigned inner = (unsigned)ceil(d / budget) - 1u;
                t->cuts += inner;
                t->bits += inner * inner_bits(deep[lv]);
                d -= (double)inner * budget;
                worst = budget > worst ? budget : worst;
            }
            acc += d;
        }
        t->per_clock = acc > worst ? acc : worst;
    }
}

void np_report_levels_md(FILE *f, const np_unit_cost *c, size_t n, unsigned levels)
{
    fprintf(f, "\n# Pipelined to %u gate levels per clock\n\n", levels);
    fprintf(f, "A retiming estimate from the declarations (`--levels %u`; not a synthesis): per stage the cut points "
               "that bring every clock's path within %u levels, the register bits they add (a cut between operators "
               "holds the results crossing it; a cut inside a ripple adder its operands' upper parts and the low sum, "
               "inside a multiplier its carry-save rows) and the clocks they add to the latency. A stage whose every "
               "adder updates its own register (a DDA, a forward difference) is a one-clock loop: retiming cannot cut "
               "inside it.\n\n",
            levels, levels);
    fprintf(f, "| unit | stage | path now (levels) | clocks now | cuts | added register bits | added gates | per "
               "clock after | meets %u |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n",
            levels);
    for (size_t i = 0; i < n; i++) {
        np_stage_retime r[NP_REPORT_MAX_STAGES];
        np_report_retime(&c[i], levels, r);
        unsigned cuts = 0, bits = 0, fail = 0;
        for (unsigned k = 0; k < c[i].n_stages; k++) {
            if (r[k].path <= 0)
                continue;
            fprintf(f, "| %s | %s | %.0f | %u | %u | %u | %.0f | %.0f | %s |\n", c[i].unit->name, c[i].st[k].name,
                    r[k].path, r[k].clocks, r[k].cuts, r[k].bits, np_cost_default.ff_bit * r[k].bits, r[k].per_clock,
                    r[k].meets ? "yes" : "**no**");
            cuts += r[k].cuts;
            bits += r[k].bits;
            fail += !r[k].meets;
        }
        fprintf(f, "| %s | **all** | | | **%u** | **%u** | **%.0f** (%.1f %% of %.0f) | | %s |\n", c[i].unit->name,
                cuts, bits, np_cost_default.ff_bit * bits, 100.0 * np_cost_default.ff_bit * bits / c[i].total,
                c[i].total, fail ? "**no**" : "yes");
    }
    for (size_t i = 0; i < n; i++) {
        np_stage_retime r[NP_REPORT_MAX_STAGES];
        np_report_retime(&c[i], levels, r);
        for (unsigned k = 0; k < c[i].n_stages; k++)
            if (!r[k].meets)
                fprintf(f, "\n- **%s %s cannot meet %u levels:** %s.\n", c[i].unit->name, c[i].st[k].name, levels,
                        r[k].why);
    }
    fprintf(f, "\nThe added latency is the cuts on the path from input to output (a pipeline's stages in series); "
               "a set-up engine's cuts (fdiff SU, texel FE) lengthen its multipliers' pipeline instead (`mult_lat`), "
               "which the set-up schedules then pay per level.\n");
}

static const char *kind_name(np_op_kind k)
{
    static const char *const n[NP_OP_KINDS] = { "add", "cmp", "mul", "mux", "neg", "lut", "rom", "reg",
                                                                "inc", "cmpk", "sqr", "carry", "mullo", "smul" };
    return k < NP_OP_KINDS ? n[k] : "?";
}

static void op_text(const np_op *op, char *buf, size_t len)
{
    switch (op->kind) {
    case NP_OP_MUL: snprintf(buf, len, "%u x mul %ux%u", op->count, op->a, op->b); break;
    case NP_OP_MULLO: snprintf(buf, len, "%u x mullo %ux%u", op->count, op->a, op->b); break;
    case NP_OP_SMUL: snprintf(buf, len, "%u x smul %ux%u", op->count, op->a, op->b); break;
    case NP_OP_MUX: snprintf(buf, len, "%u x mux %u:1 of %u", op->count, op->b, op->a); break;
    case NP_OP_LUT: snprintf(buf, len, "%u x lut %u->%u", op->count, op->a, op->b); break;
    case NP_OP_ROM: snprintf(buf, len, "%u x rom %ux%u", op->count, 1u << op->a, op->b); break;
    default: snprintf(buf, len, "%u x %s %u", op->count, kind_name(op->kind), op->a); break;
    }
}

/* Results per clock as a person reads it: "1 / clock", "4 / clock", or "1 / 9 clocks" for a serial unit. */
static void fmt_throughput(char *buf, size_t len, double t)
{
    if (t >= 1.0 || t <= 0.0)
        snprintf(buf, len, "%.0f / clock", t);
    else
        snprintf(buf, len, "1 / %.3g clocks", 1.0 / t);
}

void np_report_gates_md(FILE *f, const np_unit_cost *c, size_t n, const char *title)
{
    fprintf(f, "# %s\n\n", title);
    fprintf(f, "Generated by `noisepipe report gates`; do not edit (the test `report.docs_fresh` "
               "fails when this copy is stale). Cost model: [cost-model.md](cost-model.md). "
               "Gates are NAND2 equivalents; delays are gate levels.\n\n");
    fprintf(f, "| unit | configuration | logic | registers (bits) | total | latency | throughput | critical path |\n");
    fprintf(f, "| --- | --- | ---: | ---: | ---: | ---: | ---: | --- |\n");
    for (size_t i = 0; i < n; i++) {
        char tp[32];
        fmt_throughput(tp, sizeof tp, c[i].throughput);
        fprintf(f, "| %s | `%s` | %.0f | %.0f (%u) | **%.0f** | %u clocks | %s | %.0f levels (%s) |\n",
                c[i].unit->name, c[i].cfg, c[i].logic, c[i].regs, c[i].reg_bits, c[i].total,
                c[i].latency, tp, c[i].crit, c[i].crit_stage);
    }
    for (size_t i = 0; i < n; i++) {
        const np_unit_cost *u = &c[i];
        fprintf(f, "\n## %s (`%s`)\n\n", u->unit->name, u->cfg);
        fprintf(f, "| stage | operators | logic | register bits | registers | path (levels) |\n");
        fprintf(f, "| --- | --- | ---: | ---: | ---: | ---: |\n");
        for (unsigned k = 0; k < u->n_stages; k++) {
            fprintf(f, "| %s | ", u->st[k].name);
            int first = 1;
            for (size_t o = 0; o < u->n_ops; o++) {
                const np_op *op = &u->ops[o];
                if (strcmp(op->stage, u->st[k].name) != 0 || op->kind == NP_OP_REG || op->count == 0)
                    continue;
                char t[64];
                op_text(op, t, sizeof t);
                fprintf(f, "%s%s%s%s", first ? "" : ", ", t, op->signal ? " → " : "", op->signal ? op->signal : "");
                first = 0;
            }
            fprintf(f, " | %.0f | %u | %.0f | %.0f |\n", u->st[k].logic, u->st[k].reg_bits, u->st[k].regs,
                    u->st[k].delay);
        }
        fprintf(f, "| **total** | | **%.0f** | **%u** | **%.0f** | max %.0f |\n", u->logic, u->reg_bits,
                u->regs, u->crit);
        for (unsigned k = 0; k < u->n_stages; k++)
            if (u->st[k].clocks > 1)
                fprintf(f, "\nStage %s is pipelined over %u clocks: its path is per clock (the whole / %u).\n",
                        u->st[k].name, u->st[k].clocks, u->st[k].clocks);
        if (u->has_timing) {
            const np_unit_timing *t = &u->timing;
            fprintf(f, "\nLatency %u clocks from a descriptor to its first result; throughput %g per clock %s.\n",
                    t->latency, t->throughput, t->throughput_note);
            if (t->n_setup) {
                fprintf(f, "\n| set-up | products | stall (clocks) |\n| --- | ---: | ---: |\n");
                for (unsigned j = 0; j < t->n_setup && j < NP_UNIT_MAX_SETUPS; j++)
                    fprintf(f, "| %s | %u | %u |\n", t->setup[j].what, t->setup[j].products, t->setup[j].cycles);
            }
        }
    }
}

void np_report_gates_json(FILE *f, const np_unit_cost *c, size_t n)
{
    fprintf(f, "{\n  \"generator\": \"noisepipe report gates\",\n  \"units\": [\n");
    for (size_t i = 0; i < n; i++) {
        const np_unit_cost *u = &c[i];
        fprintf(f, "    {\n      \"unit\": \"%s\",\n      \"config\": \"%s\",\n", u->unit->name, u->cfg);
        fprintf(f, "      \"logic_gates\": %.1f,\n      \"register_bits\": %u,\n      \"register_gates\": %.1f,\n",
                u->logic, u->reg_bits, u->regs);
        fprintf(f, "      \"total_gates\": %.1f,\n      \"latency_clocks\": %u,\n      \"results_per_clock\": %.0f,\n",
                u->total, u->latency, u->throughput);
        fprintf(f, "      \"critical_path_levels\": %.1f,\n      \"critical_stage\": \"%s\",\n", u->crit,
                u->crit_stage);
        if (u->has_timing) {
            const np_unit_timing *t = &u->timing;
            fprintf(f, "      \"throughput_note\": \"%s\",\n      \"setups\": [", t->throughput_note);
            for (unsigned j = 0; j < t->n_setup && j < NP_UNIT_MAX_SETUPS; j++)
                fprintf(f, "%s\n        { \"what\": \"%s\", \"products\": %u, \"stall_clocks\": %u }",
                        j ? "," : "", t->setup[j].what, t->setup[j].products, t->setup[j].cycles);
            fprintf(f, " ],\n");
        }
        fprintf(f, "      \"stages\": [\n");
        for (unsigned k = 0; k < u->n_stages; k++) {
            fprintf(f, "        { \"name\": \"%s\", \"logic_gates\": %.1f, \"register_bits\": %u, "
                       "\"register_gates\": %.1f, \"path_levels\": %.1f, \"clocks\": %u, \"ops\": [",
                    u->st[k].name, u->st[k].logic, u->st[k].reg_bits, u->st[k].regs, u->st[k].delay,
                    u->st[k].clocks);
            int first = 1;
            for (size_t o = 0; o < u->n_ops; o++) {
                const np_op *op = &u->ops[o];
                if (strcmp(op->stage, u->st[k].name) != 0 || op->count == 0)
                    continue;
                fprintf(f, "%s\n          { \"kind\": \"%s\", \"count\": %u, \"a\": %u, \"b\": %u, "
                           "\"signal\": %s%s%s, \"out_bits\": %u, \"level\": %u }",
                        first ? "" : ",", kind_name(op->kind), op->count, op->a, op->b,
                        op->signal ? "\"" : "", op->signal ? op->signal : "null", op->signal ? "\"" : "",
                        op->out, op->level);
                first = 0;
            }
            fprintf(f, " ] }%s\n", k + 1 < u->n_stages ? "," : "");
        }
        fprintf(f, "      ]\n    }%s\n", i + 1 < n ? "," : "");
    }
    fprintf(f, "  ]\n}\n");
}
