/* SPDX-License-Identifier: MIT */
/* np_report_dims.h - `noisepipe report dims`: noise in n = 2..5 dimensions, cost against n (report_dims.c). */
#ifndef NP_REPORT_DIMS_H
#define NP_REPORT_DIMS_H

#include "np_unit.h"

/*
 * `report dims --synth`: the n-D RTL synthesised (np_synth_run) beside the
 * cost model, per stage and per added dimension. only: synthesise only this
 * unit (classicN, simplexN; simplex3 means np_simplexn.v at DIMS = 3), NULL
 * every one; the others are shown from the cache when it holds them. The
 * cache is dir/synth-cache/<unit>.txt, one file a synthesis, reused while
 * its key (np_synth_key: the RTL, the parameters, the flow) is unchanged.
 * tolerance_pct >= 0: exit 1 when a shown stage is further from Yosys.
 */
typedef struct np_report_dims_synth {
    const np_unit *only;
    const char *rtl_dir; /* NULL: np_synth_default_rtl_dir() */
    int flags;           /* NP_SYNTH_PER_STAGE, NP_SYNTH_ABC_FULL */
    double tolerance_pct;
} np_report_dims_synth;

/*
 * Markdown on stdout (dir NULL), or dir/dims.md and dir/dims.svg; with synth
 * (which needs dir), dir/dims-synth.md as well. Returns an exit status
 * (np_common.h: 0; 1 over synth's tolerance; 2 with a message on stderr).
 */
int np_report_dims(const char *dir, const np_report_dims_synth *synth);

#endif /* NP_REPORT_DIMS_H */
