/* SPDX-License-Identifier: MIT */
/* np_report_runtime.h - `noisepipe report runtime` (report_runtime.c): error against run time on scenes. */
#ifndef NP_REPORT_RUNTIME_H
#define NP_REPORT_RUNTIME_H

#include "np_render_tools.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Error against run time over each unit's sweeps (np_unit_span.sweeps) on
 * the scenes, with plots and images, into dir (docs/plots). NP_EXIT_*.
 */
int np_report_runtime(const char *dir, const char *const *scenes, unsigned n_scenes, unsigned repeat,
                      np_render_spec_fn spec, const void *ctx);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_REPORT_RUNTIME_H */
