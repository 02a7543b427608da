/* SPDX-License-Identifier: MIT */
/*
 * np_report_scan.h - the scanline probe of `noisepipe report runtime` (report_scan.c;
 * the seed's figures 10 and 11): two units' internals side by side, so a
 * report and not the renderer, which sees a unit only through the registry.
 */
#ifndef NP_REPORT_SCAN_H
#define NP_REPORT_SCAN_H

#include <stddef.h>

#include "np_fdiff.h"
#include "np_render.h"

/*
 * The noise along one scanline (the seed's figures 10 and 11): for every
 * pixel of the spans on row y, the forward-difference unit's noise
 * accumulators against the per-pixel unit's (exact weights, WT = 32, the
 * same F), i.e. the forward differences' drift alone:
 *   sum[i]  = (sum_o N_fd - sum_o N_px) / (2^F S)   in units of f
 *   last[i] = (N_fd - N_px) of the last octave / (2^F a'), in noise units (0..1)
 * and the pixels where a set-up happened (any octave; the last octave).
 * Samples are ordered by x. Arrays are malloc'd; free with np_render_scan_free.
 */
typedef struct np_render_scan {
    size_t n;
    double *x, *sum, *last, *ref_sum; /* ref_sum: the reference's sum a_i n_i, for scale */
    size_t n_edge_any, n_edge_last;
    double *edge_any, *edge_last;
} np_render_scan;

int np_render_scanline(const np_render_frame *fr, const np_fdiff_cfg *cfg, unsigned y, np_render_scan *s);
void np_render_scan_free(np_render_scan *s);

#endif /* NP_REPORT_SCAN_H */
