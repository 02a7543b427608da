/* SPDX-License-Identifier: MIT */
/*
 * np_span.h - what every span unit shares: the span port, the span
 * statistics, the colour stages, and the one span sequencer that turns a
 * unit's engine into a bit-exact span model and a cycle-accurate model.
 *
 * A span unit reads a span descriptor (np_span, np_texture.h) and writes one
 * pixel per clock for it. What differs between units is the engine: how the
 * state is loaded for a span (and what that costs in set-up clocks), how it
 * steps from pixel k to k + 1 (and which re-set-ups that needs), and the
 * pipeline that turns the engine's current pixel into a colour. An engine
 * supplies exactly that (np_span_engine); the sequencer below does the rest,
 * for every engine alike:
 *
 *   np_fdiff  forward differences: a set-up per span and per cell change,
 *             three additions per pixel, then the colour stages C1 C2 C3;
 *   np_texel  per pixel: the span front end's set-up, DDA steps, then the
 *             nine-stage pipeline L I1 I2 I3 A S C1 C2 C3.
 *
 * --- Port (one cycle; the testbench drives it like RTL) ---
 * The testbench sets in_valid/in and out_ready, calls np_span_sim_eval (the
 * model drives in_ready, out_valid, out), consumes the output if out_valid &&
 * out_ready, then calls np_span_sim_clock. A descriptor transfers when
 * in_valid && in_ready. For an engine without a descriptor buffer (prefetch
 * NULL) in_ready is high only while the unit is idle (a span's descriptor is
 * read after the previous span's last pixel has issued). With one (np_fdiff,
 * np_texel) in_ready is high while the buffer is empty: a descriptor is taken
 * while a span waits for its set-up or steps, and one accepted in the clock
 * the previous span's last pixel issues begins in that same clock. (The
 * reference RTL of the sequencer, rtl_model/verilog/np_span_seq.v, is this
 * clock for clock.)
 *
 * --- Timing (the same for every engine) ---
 * 1 clock to accept a descriptor; then the set-up clocks begin() returns;
 * then one pixel per clock into the engine's pipeline (n_stages deep),
 * except for the set-up clocks advance() returns after a pixel; output
 * backpressure holds the pixel at the pipeline's input (a set-up stall
 * counts down one per clock whether or not the pipeline could take a
 * pixel). An empty span
 * (n = 0) costs its accepting clock and nothing else. With no gaps and no
 * backpressure a run of spans therefore takes
 *   spans + set-up cycles + pixels + n_stages   clocks
 * (tests fdiff.cycle_count and fdiff.texel_cycle_vs_model check it).
 * An engine with prefetch (np_fdiff) reads the next descriptor into its
 * buffer while a span steps and begins it in the clock the last pixel of
 * the previous span issues: spans read while the unit was busy cost no
 * accepting clock, and the set-up clocks are only those the engine could
 * not hide behind stepping (the engine's stall, not its set-up work).
 *
 * --- Engine state and signal bundle (conventions) ---
 * An engine's state begins with an np_span_ctx: the context its pipeline
 * stages are called with (the unit configuration, the registers and the
 * index format). Its signal bundle begins with an np_span_sig: the pixel's
 * position and colour and the colour stages' signals, so the sequencer and
 * the shared colour stages find them at a known place.
 */
#ifndef NP_SPAN_H
#define NP_SPAN_H

#include <stddef.h>
#include <stdint.h>

#include "np_datapath.h"
#include "np_fixed.h"
#include "np_pipe.h"
#include "np_texture.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Counts of the work a span unit did (bit-exact and cycle model alike). */
typedef struct np_span_counts {
    uint64_t spans;           /* descriptors, empty ones included */
    uint64_t pixels;
    uint64_t span_setups;     /* set-ups at a span's first pixel */
    uint64_t cell_setups;     /* set-ups on a cell change (forward differences) */
    uint64_t interval_setups; /* set-ups after K steps (forward differences) */
    uint64_t setup_cycles;    /* the stall the set-ups cost */
} np_span_counts;

/* The cycle model's statistics. */
typedef struct np_span_stats {
    uint64_t cycles;
    uint64_t setup_stalls; /* clocks the engine spent in set-up */
    uint64_t out_stalls;   /* clocks the engine held a pixel its pipeline could not take */
    uint64_t idle;         /* clocks the unit waited for a descriptor */
    np_span_counts counts;
} np_span_stats;

/* The port: descriptor in (valid/ready), pixel out (valid/ready). */
typedef struct np_span_port {
    int in_valid;
    const np_span *in;
    int out_ready;
    int in_ready;
    int out_valid;
    np_tex_pixel out;
} np_span_port;

/* What an engine's pipeline stages are called with (np_stage_fn's cfg). */
typedef struct np_span_ctx {
    const void *cfg;        /* the unit's configuration (np_fdiff_cfg, np_texel_cfg) */
    const np_tex_regs *r;
    unsigned F, W, fw;      /* index x: s(W) QI.F; colour weight bits Fw */
    /*
     * The clock of the current begin / advance / prefetch call (set by the
     * sequencer: the cycle model's clock, or the bit-exact model's own count
     * of a span run alone). An engine that overlaps its set-ups with stepping
     * times them against it; the others ignore it.
     */
    uint64_t now;
    int timed;              /* the cycle model runs the engine: time its set-ups (the bit-exact model does not) */
} np_span_ctx;

/* The head of every span unit's signal bundle (formats as np_texture.h). */
typedef struct np_span_sig {
    np_tex_pixel pix;       /* x, y: set at issue; rgb: C3 */
    np_s128 x;              /* colour index s(W) QI.F, before C1 */
    unsigned seg;           /* C1: u8 */
    uint32_t cw;            /* C1: u(Fw+1) Q1.Fw */
    int64_t prod[3];        /* C2: s(10+Fw) Q9.Fw */
} np_span_sig;

/* The colour stages C1 (split), C2 (mix), C3 (round) on np_span_sig: the last three stages of every engine. */
enum { NP_SPAN_COLOUR_STAGES = 3 };
extern const np_stage_desc np_span_colour_stages[NP_SPAN_COLOUR_STAGES];
/* The same three as np_stage_fn, for an engine's stage table. */
void np_span_stage_c1(const void *ctx, void *sig);
void np_span_stage_c2(const void *ctx, void *sig);
void np_span_stage_c3(const void *ctx, void *sig);

/*
 * A span engine. State and bundle are opaque blocks of core_size and
 * sig_size bytes (conventions above). counts is never NULL.
 */
typedef struct np_span_engine {
    const char *name;
    size_t core_size, sig_size;
    const np_stage_desc *stages; /* the pixel pipeline, ending with np_span_colour_stages */
    unsigned n_stages;
    /* Initialise the state for configuration cfg and registers r (both kept by reference). */
    void (*init)(void *core, const void *cfg, const np_tex_regs *r);
    /* Load a span; returns the set-up clocks before its first pixel (0 for an empty span). */
    unsigned (*begin)(void *core, const np_span *sp, np_span_counts *counts);
    /* Step from pixel k to k + 1; returns the set-up clocks needed first (0: none, or the span ended). */
    unsigned (*advance)(void *core, np_span_counts *counts);
    /* The current pixel's inputs into a cleared bundle (the sequencer sets pix.x, pix.y). */
    void (*issue)(const void *core, void *sig);
    /*
     * Optional (NULL: begin and advance k times): place the state at pixel
     * k of span sp directly, with the same bits as the sequential steps
     * (a vector generator evaluating one pixel at a time uses it).
     */
    void (*seek)(void *core, const np_span *sp, uint32_t k);
    /* The unit's datapath declaration for cfg and registers r (np_datapath.h): up to max ops, returns the count. */
    size_t (*datapath)(const void *cfg, const np_tex_regs *r, np_op *ops, size_t max);
    /*
     * Optional (NULL: a descriptor is read only when the engine is idle):
     * the engine has a one-deep descriptor buffer. The sequencer accepts the
     * next descriptor while a span is stepping and calls prefetch with it, so
     * the engine can start that span's set-up in the background; begin is
     * then called for it in the clock the previous span's last pixel issues
     * (no accepting clock) and returns only the set-up clocks that remain.
     */
    void (*prefetch)(void *core, const np_span *sp);
} np_span_engine;

static inline const np_span_ctx *np_span_ctx_of(const void *core) { return (const np_span_ctx *)core; }

/* Optional per-pixel observation of the bit-exact model: the state and bundle of pixel k. */
typedef void (*np_span_probe_fn)(const void *pctx, const void *core, const void *sig, uint32_t k);

/*
 * The bit-exact model for one span: out[0..n) receives the pixels, counts
 * (may be NULL) is incremented. core is an initialised state, sig a bundle of sig_size
 * bytes (scratch). Preconditions: the configuration, np_tex_regs_check and
 * np_span_check pass.
 */
void np_span_run(const np_span_engine *e, void *core, void *sig, const np_span *sp, np_tex_pixel *out,
                 np_span_counts *counts, np_span_probe_fn probe, const void *pctx);

/* --- The cycle-accurate model (the sequencer) --- */

typedef struct np_span_sim {
    const np_span_engine *eng;
    void *core;          /* the engine's state (core_size bytes, owned) */
    np_pipe pipe;        /* the engine's pixel pipeline */
    void *pending;       /* the bundle offered to the pipeline this cycle (owned) */
    np_pipe_port pport;
    np_span sp;          /* the span in the engine */
    uint32_t k;          /* its current pixel */
    int busy;            /* a span is in the engine */
    np_span next;        /* the descriptor buffer (engines with prefetch) */
    int has_next;
    unsigned stall;      /* set-up clocks left before pixel k can issue */
    np_span_stats stats;
} np_span_sim;

/* cfg and r must outlive the model. 0, or -1 when out of memory. */
int np_span_sim_init(np_span_sim *m, const np_span_engine *e, const void *cfg, const np_tex_regs *r);
void np_span_sim_free(np_span_sim *m);
void np_span_sim_reset(np_span_sim *m);
void np_span_sim_eval(np_span_sim *m, np_span_port *p);
void np_span_sim_clock(np_span_sim *m, const np_span_port *p);
/* Nothing in flight: no span in the engine, the pipeline empty. */
int np_span_sim_idle(const np_span_sim *m);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_SPAN_H */
