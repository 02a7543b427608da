/* SPDX-License-Identifier: MIT */
/*
 * The part of an np_unit entry every single-model unit file binds the same way.
 * Each such file (unit_classic.c, unit_simplex.c, unit_wave.c, unit_hatch.c,
 * unit_aacount.c) defines its callbacks as statics under these names, so the
 * entry names what is the unit's own (name, summary, tolerance, optional parts)
 * and this one list says what every unit must provide; a new unit copies nothing.
 */
#ifndef UNIT_ENTRY_H
#define UNIT_ENTRY_H

#include "np_unit.h"

/* Keys, configuration check, fields, the bit-exact model and its float
 * reference with its error bound, the pipeline and its signals, the boundary
 * inputs, the datapath, the trace, the conformance configurations. */
#define NP_UNIT_MODEL_ENTRY                                                                                     \
    .keys = keys, .cfg_check = cfg_check, .fields = fields, .eval = eval, .ref = ref,                          \
    .error_bound_lsb = error_bound, .pipe_init = pipe_init, .sig_set_in = sig_set_in,                          \
    .sig_get_out = sig_get_out, .boundary = boundary, .datapath = datapath, .trace = trace,                    \
    .conformance_configs = conformance_configs

#endif
