/* SPDX-License-Identifier: MIT */
/*
 * np_pipe_drive.h - the random-traffic driver of a unit's np_pipe, shared by
 * the unit tests that drive a model's pipe directly (test_classic, test_simplex):
 * n random inputs, an input bubble with probability pb/16 and an output stall
 * with probability ps/16 each cycle; every output is checked, in order,
 * against what its input must give, an output whose path never stalled must
 * appear exactly `latency` cycles after its input was accepted (never
 * sooner otherwise), at most 64 transactions are in flight and the
 * occupancy never exceeds the latency.
 */
#ifndef NP_PIPE_DRIVE_H
#define NP_PIPE_DRIVE_H

#include <stdint.h>

#include "np_pipe.h"
#include "np_rng.h"
#include "np_unit.h"

typedef struct np_pipe_dut {
    np_pipe *pipe;       /* initialised, empty */
    const np_unit *unit; /* its sig_set_in makes an input bundle from n_in random words */
    unsigned n_in, in_bits; /* each word the top in_bits of one np_rng draw, in field order */
    /* 1 when out is what in must give (the bit-exact model's outputs, the inputs carried); else 0 after a message. */
    int (*check)(const void *cfg, const void *in, const void *out, uint64_t n);
    const void *cfg; /* the model's configuration, as the pipe's stages see it */
} np_pipe_dut;

typedef struct np_pipe_drive_result {
    uint64_t transactions, cycles, mismatches, exact; /* exact: unstalled ones, each at the latency */
} np_pipe_drive_result;

/* Drive d->pipe as above (seeded by seed); the checks are NP_CHECKs. */
np_pipe_drive_result np_pipe_drive_random(const np_pipe_dut *d, uint64_t n, unsigned pb, unsigned ps,
                                          uint64_t seed);

#endif /* NP_PIPE_DRIVE_H */
