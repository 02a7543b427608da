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
 * pipe accepts one input per clock whenever downstream is ready.
 *
 * Two options (fields of np_pipe, set after np_pipe_init; both 0 by default,
 * which is the pipe above, bit for bit and cycle for cycle). The reference
 * RTL (rtl_model/verilog/np_pipe_in_reg.v, np_pipe_skid.v) has the same two:
 *   in_reg   an input register: one more bank in front of stage 0 that holds
 *            the port's bundle as it came in, with the same load rule.
 *            Latency + 1. in_ready = !in_valid_reg | (bank 0 loads): the ready
 *            path is one bank longer and still combinational.
 *   out_skid a two-entry skid buffer after the last bank (a main register
 *            that drives the output port and a skid register that catches
 *            the transfer already under way when out_ready drops). Latency
 *            + 1, full throughput. The last bank sees "ready" = !skid_valid,
 *            a register: no combinational path from out_ready to in_ready.
 * The order of transfers at the ports is unchanged by either option.
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
    unsigned char *regs;  /* depth bundles of sig_size bytes, bank k in bundle slot[k] */
    unsigned *slot;       /* which bundle each bank holds: a transfer passes the bundle on, no copy */
    int copy_banks;       /* 1: copy each bundle from bank to bank instead (the former model; same
                             bits and cycles, slower; for the bench's comparison and the tests) */
    unsigned char *valid; /* depth valid bits */
    unsigned char *moves; /* scratch: bank k transfers onward this cycle */
    np_pipe_stats stats;
    /* Options (see above); set after np_pipe_init, before use. */
    int in_reg, out_skid;
    unsigned char *opt;   /* 3 bundles: input register, skid main, skid spare */
    unsigned char in_v, main_v, skid_v;
    unsigned char core_in_ready; /* scratch: bank 0 loads this cycle */
} np_pipe;

/* 0 on success, -1 when out of memory. cfg is kept by reference. */
int np_pipe_init(np_pipe *p, const np_stage_desc *stages, unsigned depth, size_t sig_size,
                 const void *cfg);
void np_pipe_free(np_pipe *p);
/* Empty every bank and clear the statistics (synchronous reset). */
void np_pipe_reset(np_pipe *p);
static inline unsigned np_pipe_latency(const np_pipe *p)
{
    return p->depth + (p->in_reg ? 1u : 0u) + (p->out_skid ? 1u : 0u);
}
/* Number of banks holding valid data. */
unsigned np_pipe_occupancy(const np_pipe *p);

void np_pipe_eval(np_pipe *p, np_pipe_port *port);
void np_pipe_clock(np_pipe *p, const np_pipe_port *port);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_PIPE_H */
