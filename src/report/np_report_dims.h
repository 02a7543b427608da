/* SPDX-License-Identifier: MIT */
/* np_report_dims.h - `noisepipe report dims`: noise in n = 2..5 dimensions, cost against n (report_dims.c). */
#ifndef NP_REPORT_DIMS_H
#define NP_REPORT_DIMS_H

/*
 * Markdown on stdout (dir NULL), or dir/dims.md and dir/dims.svg. Returns
 * an exit status (np_common.h: 0, or 2 with a message on stderr).
 */
int np_report_dims(const char *dir);

#endif /* NP_REPORT_DIMS_H */
