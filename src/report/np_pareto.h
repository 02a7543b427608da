/* SPDX-License-Identifier: MIT */
/* np_pareto.h - error against cost over a unit's internal widths (report_pareto.c). */
#ifndef NP_PARETO_H
#define NP_PARETO_H

#include <stdint.h>
#include <stdio.h>

#include "np_report.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * One swept key of a unit (np_unit_key): its range is the key table's unless
 * narrowed here (lo..hi inside the table's; 0..0: the table's whole range).
 */
typedef struct np_dse_axis {
    const char *key;
    unsigned lo, hi;
} np_dse_axis;

/* A two-key design space of one unit around a base configuration. */
typedef struct np_dse_space {
    const char *unit;
    const char *base;    /* e.g. "out_bits=8" */
    np_dse_axis axis[2];
    int claim_10k;       /* 1: check the seed's "under 10K gates" claim (classic3 only) */
} np_dse_space;

extern const np_dse_space np_dse_spaces[]; /* terminated by unit == NULL */

typedef struct np_dse_point {
    unsigned v1, v2;
    char cfg[128];
    double gates, crit, bound;
    double max_err, cr_pct;  /* the search's: largest output error (LSB), correctly rounded share */
    unsigned latency;
    int pareto;
    int verdict;             /* np_search_verdict */
    uint64_t tried;          /* inputs the search evaluated */
    uint16_t cex[3];         /* the input of max_err: the counterexample when not faithful */
    char cex_field[16];      /* its worst output field, */
    double cex_out, cex_true; /* the model's output and the true value there, in that field's LSB */
} np_dse_point;

typedef struct np_dse_result {
    const np_dse_space *space;
    const np_unit *unit;
    np_dse_axis axis[2]; /* the ranges swept: the space's, or the key table's */
    uint64_t samples, seed; /* the search's budget and seed for every configuration */
    size_t n;
    np_dse_point *pts;
} np_dse_result;

/*
 * Run the sweep: an adversarial search (np_search.h) of samples inputs
 * (at least NP_SEARCH_CHUNK) per configuration, stopped at the first wave
 * holding a counterexample. 0, or -1 with err (an unknown unit or key, a
 * range outside the key's).
 */
int np_dse_run(const np_dse_space *sp, uint64_t samples, uint64_t seed, np_dse_result *res, char *err,
               size_t errlen);
void np_dse_free(np_dse_result *res);

void np_dse_write_md(FILE *f, const np_dse_result *r, const char *svg_name);
void np_dse_write_json(FILE *f, const np_dse_result *r);
void np_dse_write_svg(FILE *f, const np_dse_result *r);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_PARETO_H */
