/* SPDX-License-Identifier: MIT */
/*
 * np_synth.h - `noisepipe report gates --synth`: the reference RTL
 * (rtl_model/verilog/) synthesised with Yosys + ABC to NAND2 equivalents per
 * pipeline stage, beside the cost model's estimate (docs/cost-model.md,
 * "Synthesis per stage").
 */
#ifndef NP_SYNTH_H
#define NP_SYNTH_H

#include <stdio.h>

#include "np_report.h"
#include "np_unit.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct np_synth_stage {
    char name[16];
    unsigned dff;  /* flip-flops left in the stage's bank after synthesis */
    double gates;  /* NAND2 equivalents of the cells only this bank's input cone holds (flip-flops included) */
} np_synth_stage;

typedef struct np_synth_result {
    unsigned n_stages;
    np_synth_stage st[NP_REPORT_MAX_STAGES];
    double shared;   /* cells outside every single bank's cone: valid bits, handshake, options, shared logic */
    double total;    /* the whole design */
    unsigned dff;    /* all flip-flops */
} np_synth_result;

/* np_synth_run's flags. */
enum {
    NP_SYNTH_PER_STAGE = 1, /* ABC on each bank's input cone alone (--per-stage) */
    NP_SYNTH_ABC_FULL = 2   /* ABC's unbounded default script (--abc-full); else the SAT sweep is bounded */
};

/* 1 when unit u has reference RTL that --synth can synthesise (with --unit). */
int np_synth_has_rtl(const np_unit *u);
/* 1 when a run without --unit synthesises u (classic3, simplex3: not the by-name units). */
int np_synth_in_default_set(const np_unit *u);
/*
 * The units a run synthesises, one a call: with only (--unit) that unit, else the
 * default set, in registry order from *i (0 before the first call); NULL after the last.
 */
const np_unit *np_synth_unit_next(const np_unit *only, size_t *i);

/*
 * Synthesise u's RTL (files in rtl_dir) at configuration cfg with the
 * stages of model c (np_unit_cost_compute); flags: NP_SYNTH_PER_STAGE (ABC on
 * each bank's input cone alone, docs/cost-model.md, "--per-stage"),
 * NP_SYNTH_ABC_FULL (ABC's unbounded default script). 0; -1 with a message in err;
 * -2 when yosys cannot be run (message in err).
 */
int np_synth_run(const np_unit *u, const void *cfg, const np_unit_cost *c, const char *rtl_dir, int flags,
                 np_synth_result *r, char *err, size_t errlen);

/*
 * Markdown: per stage the model's logic, registers and total beside Yosys's,
 * and model / Yosys. Returns the largest |model / Yosys - 1| over the stages.
 */
double np_synth_print(FILE *f, const np_unit_cost *c, const np_synth_result *r);

/*
 * The command: `noisepipe report gates --synth [--unit U] [--config K=V,...]
 * [--rtl DIR] [--per-stage] [--abc-full] [--tolerance PCT]` (flags: NP_SYNTH_*). Every unit with RTL (or U), each at its
 * default or at --config. NP_EXIT_USAGE when yosys is absent or the input is
 * bad; NP_EXIT_FAIL when a stage is more than PCT % from synthesis.
 */
int np_report_gates_synth(const np_unit *only, const char *spec, const char *rtl_dir, int flags,
                          double tolerance_pct);

/*
 * --rtl-param NAME=V,...: RTL parameters of u that are not configuration keys
 * (IN_REG, OUT_SKID; classic3's S_TABLE, HASH_SERIAL, LERP_SERIAL: docs/rtl.md), set for
 * the following np_synth_run calls (NULL clears them). With any set, the
 * report prints Yosys per stage beside the as-built circuit's model, labelled
 * (the cost model declares no variant). 0; -1 with a message in err.
 */
int np_synth_set_rtl_params(const np_unit *u, const char *spec, char *err, size_t errlen);

/*
 * What `report fpga` (np_fpga.h) shares with --synth: u's top module (NULL
 * without RTL); the Yosys script's head for u at cfg (read_verilog of its
 * files in rtl_dir, chparam of every key and of --rtl-param): 0, or -1 with a
 * message in err (no RTL, a file unreadable); the stage whose bank holds
 * register reg ("r1_k" -> "H"; NULL when no bank does); the --rtl-param set
 * ("" when none); the clocks per result the --rtl-param variant takes (0: the
 * as-built circuit's, the cost model's throughput).
 */
const char *np_synth_rtl_top(const np_unit *u);
int np_synth_write_rtl(FILE *f, const np_unit *u, const void *cfg, const char *rtl_dir, char *err, size_t errlen);
const char *np_synth_stage_of(const np_unit *u, const char *reg);
const char *np_synth_rtl_param_spec(void);
unsigned np_synth_rtl_clocks_per_result(const np_unit *u);

/*
 * What report dims (report_dims.c) needs to cache syntheses: the model's
 * stage as np_synth_print compares it (without its valid bit); a key (16 hex
 * digits) over u's RTL files by name and content, its includes, the chparam
 * line of cfg and the flow (flags, ABC's script): equal keys, equal netlists.
 * 0, or -1 with a message in err.
 */
double np_synth_model_stage(const np_stage_cost *m);
int np_synth_key(const np_unit *u, const void *cfg, const char *rtl_dir, int flags, char key[17], char *err,
                 size_t errlen);

/* The RTL folder compiled in (the source tree's rtl_model/verilog). */
const char *np_synth_default_rtl_dir(void);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_SYNTH_H */
