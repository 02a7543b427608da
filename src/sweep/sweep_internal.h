/* SPDX-License-Identifier: MIT */
/* sweep_internal.h - what the sweep (sweep.c) shares with the search (search.c); not installed. */
#ifndef NP_SWEEP_INTERNAL_H
#define NP_SWEEP_INTERNAL_H

#include "np_jfile.h"
#include "np_unit.h"

/*
 * The bindings of a run's journal (np_jfile.h) that name what it measures:
 * unit=NAME and config=TEXT (np_unit_cfg_format, canonical). The sweep's
 * journal adds z=, the search's seed= and n=. 0, or -1 (too long).
 */
int np_sweep_bind_unit(np_jfile_binds *b, const np_unit *u, const void *cfg);

/* NULL when every input of f is u16 and its outputs are 1..32-bit words the error measure reads, else why not. */
const char *np_sweep_fields_check(const np_unit_fields *f, const char *who, const char *in_names);

#endif /* NP_SWEEP_INTERNAL_H */
