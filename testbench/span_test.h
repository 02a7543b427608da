/* SPDX-License-Identifier: MIT */
/*
 * span_test.h - what the span units' test programs share (test_fdiff.c,
 * test_texel.c, test_texture.c, the conformance test's width check and the
 * toy span unit): register and span fixtures, and one driver that runs spans through an engine's
 * cycle-accurate model (np_span_sim) like an RTL testbench and compares
 * every pixel with its bit-exact model.
 */
#ifndef SPAN_TEST_H
#define SPAN_TEST_H

#include <stddef.h>
#include <stdint.h>

#include "np_rng.h"
#include "np_span.h"
#include "np_texture.h"
#include "np_unit.h"

/*
 * The "grey ramp" registers: one octave, identity transform, a' = 1
 * (x = n), a clamped two-entry map black..white (colour = 255 n).
 */
np_tex_regs span_ramp_regs(void);
/* A descriptor from dyadic values (exact in Q15.32). */
np_span span_mk(uint16_t y, uint16_t x0, uint32_t n, const double s[3], const double ds[3]);
/* n_oct octaves with random near-diagonal transforms over the ramp, an 8-entry repeating map. */
np_tex_regs span_multi_regs(np_rng *g, unsigned n_oct);
/* A random span: empty, one pixel or up to 299, coordinates up to +-32, steps up to 1/2. */
np_span span_rand(np_rng *g);
/* Registers over their full formats: variant 0 a 256-entry repeating table, 1 a clamped one of 2..255 entries. */
np_tex_regs span_wide_regs(np_rng *g, unsigned n_oct, int variant);

/*
 * ns random spans (span_rand, from g) into sp, and their pixels by engine
 * e's bit-exact model (np_span_run, configuration cfg, registers r) one
 * after the other into want (NULL: not kept); cnt is cleared, then counts
 * them. Returns the pixels.
 */
size_t span_rand_run(const np_span_engine *e, const void *cfg, const np_tex_regs *r, np_rng *g, np_span *sp,
                     size_t ns, np_tex_pixel *want, np_span_counts *cnt);

/*
 * Traffic at the ports, one call per cycle: in_valid (only asked when a
 * descriptor is waiting) and out_ready, from g and a state the driver keeps.
 */
typedef void (*span_traffic_fn)(np_rng *g, int *state, int waiting, int *in_valid, int *out_ready);
/* Gaps of 1 in 4 between descriptors; output-stall phases (none, 1 in 2, 7 in 8) changing 1 in 64 cycles. */
void span_traffic_phases(np_rng *g, int *state, int waiting, int *in_valid, int *out_ready);
/* Gaps and output stalls, 1 in 3 cycles each. */
void span_traffic_thirds(np_rng *g, int *state, int waiting, int *in_valid, int *out_ready);

typedef struct span_drive_result {
    size_t got, bad;    /* pixels out; those differing from want (or past its end) */
    np_span_stats stats;
} span_drive_result;

/*
 * Run sp[0..ns) through engine e's cycle-accurate model with traffic (NULL:
 * none, every cycle valid and ready) until idle or max_cycles; every pixel
 * out is compared with want[0..nw) in order (want NULL: not compared).
 * 0, or -1 when the model cannot be built.
 */
int span_drive(const np_span_engine *e, const void *cfg, const np_tex_regs *r, const np_span *sp, size_t ns,
               const np_tex_pixel *want, size_t nw, np_rng *g, span_traffic_fn traffic, uint64_t max_cycles,
               span_drive_result *res);

#endif /* SPAN_TEST_H */
