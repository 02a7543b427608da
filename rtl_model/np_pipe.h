/* SPDX-License-Identifier: MIT */
/*
 * np_pipe.h - a generic cycle-accurate pipeline with a valid/ready handshake.
 *
 * A unit describes its pipeline as a list of stages. Each stage is the
 * combinational logic between two register banks; it reads and writes the
 * unit's "signal bundle" (one struct type holding every signal of the unit).
 * Register R_k holds the bundle after stages 0..k have been applied, so a
 * unit with D stages has D register banks and a latency of D clocks: an input
 * accepted in cycle c is presented on the output in cycle c + D when nothing
 * stalls. (Which fields of the bundle a real register bank must keep is the
 * gate report's business; the model copies the whole bundle.)
 *
 * Handshake, per cycle (AXI-stream style, both sides sample at the edge):
 *   - upstream drives in_valid and the input bundle; the pipe answers in_ready;
 *     the input transfers at the edge when in_valid && in_ready.
 *   - the pipe drives out_valid and the output bundle; downstream drives
 *     out_ready; the output transfers at the edge when out_valid && out_ready.
 * Backpressure propagates combinationally from out_ready back to in_ready
 * through the bank valid bits (a bank may load when it is empty or when its
 * content moves on in the same cycle), so bubbles are squeezed out and the
 * pipe accepts one input per clock whenever downstream is ready. An RTL
 * version with a long chain would cut this ready path with skid buffers; the
 * transfer sequence seen at the ports would be the same.
 *
 * A testbench cycle is: fill the port's inputs, np_pipe_eval() (combinational
 * outputs), consume the output if it transfers, then np_pipe_clock() (edge).
 */
#ifndef NP_PIPE_H
#define NP_PIPE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Combinational logic of one stage, applied in place to a signal bundle. */
typedef void (*np_stage_fn)(const void *cfg, void *sig);

typedef struct np_stage_desc {
    const char *name; /* for traces and reports, e.g. "L", "I1m" */
    np_stage_fn fn;
} np_stage_desc;

typedef struct np_pipe_port {
    /* Driven by the testbench before np_pipe_eval(). */
    int in_valid;
    const void *in_sig; /* bundle with the unit's input fields set */
    int out_ready;
    /* Driven by the model in np_pipe_eval(). */
    int in_ready;
    int out_valid;
    const void *out_sig; /* valid until the next np_pipe_clock() */
} np_pipe_port;

typedef struct np_pipe_stats {
    uint64_t cycles;       /* clock edges */
    uint64_t accepted;     /* input transfers */
    uint64_t delivered;    /* output transfers */
    uint64_t out_stalls;   /* cycles with out_valid && !out_ready */
    uint64_t in_bubbles;   /* cycles with in_ready && !in_valid */
} np_pipe_stats;

typedef struct np_pipe {
    const void *cfg;
    const np_stage_desc *stages;
    unsigned depth;
    size_t sig_size;
    unsigned char *regs;  /* depth banks of sig_size bytes */
    unsigned char *valid; /* depth valid bits */
    unsigned char *moves; /* scratch: bank k transfers onward this cycle */
    np_pipe_stats stats;
} np_pipe;

/* 0 on success, -1 when out of memory. cfg is kept by reference. */
int np_pipe_init(np_pipe *p, const np_stage_desc *stages, unsigned depth, size_t sig_size,
                 const void *cfg);
void np_pipe_free(np_pipe *p);
/* Empty every bank and clear the statistics (synchronous reset). */
void np_pipe_reset(np_pipe *p);
static inline unsigned np_pipe_latency(const np_pipe *p) { return p->depth; }
/* Number of banks holding valid data. */
unsigned np_pipe_occupancy(const np_pipe *p);

void np_pipe_eval(np_pipe *p, np_pipe_port *port);
void np_pipe_clock(np_pipe *p, const np_pipe_port *port);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_PIPE_H */
