/* SPDX-License-Identifier: MIT */
/*
 * np_report.h - gate and latency estimates from a unit's datapath
 * declaration (np_datapath.h), priced by the cost model of
 * docs/cost-model.md, and the error-against-cost design-space sweep.
 */
#ifndef NP_REPORT_H
#define NP_REPORT_H

#include <stdio.h>

#include "np_datapath.h"
#include "np_unit.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The cost model: NAND2 equivalents and gate delays (NAND/NOT levels) per
 * operator, calibrated with Yosys 0.23 + ABC (abc -g NAND; stat -tech cmos,
 * transistors / 4; ltp -noff for levels) on testbench/cost_calib.v.
 */
typedef struct np_cost_model {
    double add_bit;   /* ripple-carry adder of w bits: add_bit w - add_edge */
    double add_edge;
    double cmp_bit;   /* magnitude comparator, per bit */
    double mul_pp;    /* array multiplier a x b: mul_pp a b - mul_edge (a + b) (at least 1.5 a b: the AND array) */
    double mul_edge;
    double smul_edge; /* signed x signed multiplier a x b: the mul formula + smul_edge (a + b) (the sign rows) */
    double mux2_bit;  /* 2:1 multiplexer, per bit (a k:1 mux is k - 1 of them) */
    double neg_bit;   /* conditional negate, per bit */
    double lut_bit;   /* fixed-function lookup logic, per stored bit (2^a * b) */
    double rom_bit;   /* ROM, per stored bit */
    double ff_bit;    /* D flip-flop with its load enable (every pipeline bank holds under a stall) */
    double inc_bit;   /* adding a constant (an incrementer: half adders), w bits: inc_bit w - inc_edge */
    double inc_edge;
    double cmpk_bit;  /* comparison with a constant, per bit */
    double sqr_pp;    /* squarer a x a: sqr_pp a^2 - sqr_edge a */
    double sqr_edge;
    double carry_bit; /* the carry out of a sum whose sum bits are not read, per bit */
    /* delays, in gate levels: add 2w + add_d0; cmp w; mul mul_d * (a + b); mux levels per 2:1 */
    double add_d0, mul_d, mux_d, lut_d;
} np_cost_model;

extern const np_cost_model np_cost_default;

double np_cost_op_gates(const np_cost_model *m, const np_op *op);
double np_cost_op_delay(const np_cost_model *m, const np_op *op);

enum { NP_REPORT_MAX_STAGES = 32, NP_REPORT_MAX_OPS = 128 };

typedef struct np_stage_cost {
    char name[16];
    double logic;     /* NAND2 equivalents of the stage's operators */
    unsigned reg_bits;
    double regs;      /* NAND2 equivalents of the register bank after the stage */
    double delay;     /* critical path through the stage per clock, gate levels */
    unsigned clocks;  /* clocks the stage takes (1; a pipelined engine: its depth) */
} np_stage_cost;

typedef struct np_unit_cost {
    const np_unit *unit;
    char cfg[256];
    unsigned n_stages;
    np_stage_cost st[NP_REPORT_MAX_STAGES];
    size_t n_ops;
    np_op ops[NP_REPORT_MAX_OPS];
    double logic, regs, total;
    unsigned reg_bits;
    unsigned latency;      /* clocks, from the cycle-accurate model */
    double throughput;     /* results per clock */
    double crit;           /* gate levels of the slowest stage */
    char crit_stage[16];
    int has_timing;        /* the unit's own timing (np_unit.timing): note and set-ups below */
    np_unit_timing timing;
} np_unit_cost;

/*
 * Price unit u in configuration cfg: 0, or -1 with a message in err (no
 * datapath declared, an op naming a stage the pipe does not have, ...).
 */
int np_unit_cost_compute(const np_unit *u, const void *cfg, const np_cost_model *m, np_unit_cost *c,
                         char *err, size_t errlen);

void np_report_gates_md(FILE *f, const np_unit_cost *c, size_t n, const char *title);

/*
 * Pipelining to a target clock of `levels` gate levels (issue 14; a
 * report-level retiming estimate, not a synthesis): per stage, the cut
 * points that bring every clock's path within levels, the register bits the
 * cuts add and the clocks they add to the latency; a stage that cannot meet
 * it is named with the reason (an operator alone deeper than the target
 * inside a one-clock recurrence, which retiming cannot cut).
 */
typedef struct np_stage_retime {
    double path;        /* the stage's whole path (levels), all its clocks */
    unsigned clocks;    /* clocks it takes now */
    unsigned cuts;      /* pipeline registers to add */
    unsigned bits;      /* register bits they add */
    double per_clock;   /* the longest path between registers after the cuts */
    int meets;
    char why[200];      /* when it does not */
} np_stage_retime;
void np_report_retime(const np_unit_cost *c, unsigned levels, np_stage_retime *r);
void np_report_levels_md(FILE *f, const np_unit_cost *c, size_t n, unsigned levels);
enum { NP_REPORT_LEVELS_DEFAULT = 40 };
void np_report_gates_json(FILE *f, const np_unit_cost *c, size_t n);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_REPORT_H */
