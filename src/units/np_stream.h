/* SPDX-License-Identifier: MIT */
/*
 * np_stream.h - stream units in the unit registry (np_unit.stream): units
 * whose hardware reads a descriptor and writes a run of beats, such as the
 * scanline texturing units (a span descriptor in, its pixels out). Their
 * golden vectors use the one vector format (np_vec.h, docs/vectors.md):
 *
 *   - a transaction is one beat. Its input fields are the descriptor's
 *     fields (the first n_desc) followed by the beat index "k"; its outputs
 *     are the beat's. np_unit.eval and np_unit.ref give one beat: a pure
 *     function of the descriptor and k.
 *   - a descriptor with B beats is the run of consecutive transactions with
 *     its fields and k = 0, 1, ..., B - 1. A testbench sends the descriptor
 *     once and compares the B beats in order. A run may also start at k0 > 0
 *     (a long descriptor sampled near its end): the testbench then sends the
 *     descriptor with its length cut to k0 + m and ignores the first k0 beats.
 *
 * The vector machinery writes and drives them (np_stream_generate and
 * np_stream_drive, src/vectors/np_vec_stream.h); this header is the unit's
 * side only: the stream model's port and description.
 */
#ifndef NP_STREAM_H
#define NP_STREAM_H

#include <stddef.h>
#include <stdint.h>

#include "np_rng.h"
#include "np_unit.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The stream model's ports for one cycle (AXI-stream style, as np_pipe_port). */
typedef struct np_unit_stream_port {
    int in_valid;
    const uint64_t *in;                  /* descriptor words (n_desc fields) */
    int out_ready;
    int in_ready;                        /* driven by the model */
    int out_valid;                       /* driven by the model */
    uint64_t out[NP_UNIT_MAX_FIELDS];    /* the beat's output words, masked */
} np_unit_stream_port;

typedef struct np_unit_stream {
    unsigned n_desc;      /* input fields of the descriptor; field n_desc is k */
    unsigned length_field;/* the descriptor field that holds its number of beats */
    /* Beats of the descriptor desc (desc[length_field], possibly a function of it). */
    uint64_t (*beats)(const void *cfg, const uint64_t *desc);
    /* Hand-annotated descriptors (annotations in the unit's source): up to max, returns the full count. */
    size_t (*descriptors)(const void *cfg, uint64_t (*desc)[NP_UNIT_MAX_FIELDS], size_t max);
    /* A random, valid descriptor. */
    void (*random_desc)(const void *cfg, np_rng *rng, uint64_t *desc);
    /* The cycle-accurate stream model: state of state_size bytes; cfg outlives it. */
    size_t state_size;
    int (*init)(void *state, const void *cfg);
    void (*free)(void *state);
    void (*eval)(void *state, np_unit_stream_port *p);
    void (*clock)(void *state, const np_unit_stream_port *p);
    int (*idle)(const void *state);
    /* Clocks so far, and the clocks of those the unit stalled for set-up (for reports). */
    void (*counters)(const void *state, uint64_t *cycles, uint64_t *setup_stalls);
} np_unit_stream;

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_STREAM_H */
