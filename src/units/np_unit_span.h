/* SPDX-License-Identifier: MIT */
/*
 * np_unit_span.h - the span-engine interface the registry exports.
 *
 * The renderer, the G-buffer and the reports run a span unit (np_unit.span)
 * without knowing which one it is: they hand its engine span descriptors and
 * the scene's registers and read pixels and counts back. What they need for
 * that is the interface every span engine implements, not any one unit's
 * configuration:
 *   np_span, np_tex_regs, np_tex_pixel   the descriptor, the texture's
 *                                        registers and a pixel (np_texture.h,
 *                                        with the texture model every span
 *                                        unit shares: front end, colour stages);
 *   np_span_engine, np_span_counts       the engine a unit supplies and its
 *                                        work counts;
 *   np_span_run, np_span_sim             the one sequencer: bit-exact model
 *                                        and cycle-accurate model of any engine
 *                                        (np_span.h).
 * A unit's own configuration stays behind the registry: a client holds it as
 * an opaque np_unit_cfg and passes np_unit_span_cfg() to the engine. A third
 * span unit (testbench/test_toy_span.c) plugs in by filling np_unit_span.
 */
#ifndef NP_UNIT_SPAN_H
#define NP_UNIT_SPAN_H

#include "np_span.h"
#include "np_unit.h"

#endif /* NP_UNIT_SPAN_H */
