/* SPDX-License-Identifier: MIT */
/*
 * np_widths.h - a datapath declaration (np_datapath.h) judged against the
 * ranges traced from its model, shared by the conformance test and the unit
 * tests that trace their own signals: every declared signal must have been
 * traced, its declared width must hold the traced range, and it may be wider
 * than the range needs by at most margin bits (the margin covers values the
 * range argument allows but the inputs do not reach).
 */
#ifndef NP_WIDTHS_H
#define NP_WIDTHS_H

#include <stddef.h>

#include "np_datapath.h"

/* One trace per op that produces a traced signal (signal and out set), in op order; returns how many. */
size_t np_widths_traces(const np_op *ops, size_t n_ops, np_trace *t);

/*
 * Judge the traces t (from np_widths_traces on ops) with NP_CHECKs whose
 * messages start with what (e.g. the configuration); print != 0 prints one
 * line per signal. Returns the number of signals that fail.
 */
unsigned np_widths_judge(const np_op *ops, size_t n_ops, const np_trace *t, unsigned margin, const char *what,
                         int print);

#endif /* NP_WIDTHS_H */
