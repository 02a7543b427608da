/* SPDX-License-Identifier: MIT */
/*
 * np_vec_stream.h - golden vectors of stream units (np_unit.stream,
 * np_stream.h): the stream counterparts of np_vec_generate and np_vec_drive,
 * with the same contracts, for the vectors, verify and device commands to
 * call when unit->stream is set (vec_stream.c; the format: np_stream.h).
 */
#ifndef NP_VEC_STREAM_H
#define NP_VEC_STREAM_H

#include <stddef.h>
#include <stdint.h>

#include "np_stream.h"
#include "np_vec.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The vectors of a stream unit, in the order: the unit's descriptors (every
 * beat of a descriptor of at most NP_STREAM_FULL beats; of a longer one the
 * first and the last NP_STREAM_EDGE beats, as two runs), then random
 * descriptors (level 1: 8, level 2: 4096, or n_random), every beat. Sets h's
 * seed, level, count and sources. Same contract as np_vec_generate.
 */
enum { NP_STREAM_FULL = 128, NP_STREAM_EDGE = 32, NP_STREAM_L1_RANDOM = 8, NP_STREAM_L2_RANDOM = 4096 };
int np_stream_generate(np_vec_header *h, unsigned level, uint64_t seed, uint64_t n_random,
                       const np_vec_output *outs, unsigned n_outs, char *err, size_t errlen);

/*
 * Run the transactions of source through the stream model like an RTL
 * testbench and hand every beat to sink, in order, with its transaction.
 * Runs of beats (above) become descriptors; the beats before a run's first k
 * are produced by the model and not handed on. traffic != 0 inserts random
 * gaps between descriptors and output stalls (np_rng seeded with seed).
 * Timing given to sink: clocks from the descriptor's transfer to the beat's;
 * latency is set to the same value (a stream's beats have no fixed latency;
 * the stream model's cycle count is checked by the unit's own tests).
 * Same contract and return values as np_vec_drive.
 */
int np_stream_drive(const np_vec_header *h, np_vec_source_fn source, void *src_ctx, np_vec_sink_fn sink,
                    void *sink_ctx, int traffic, uint64_t seed, np_vec_drive_stats *st, char *err, size_t errlen);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_VEC_STREAM_H */
