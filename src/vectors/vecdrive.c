/* SPDX-License-Identifier: MIT */
/*
 * vecdrive.c - runs transactions through a unit's cycle-accurate model
 * (np_pipe) like an RTL testbench: each cycle drive the inputs, evaluate,
 * sample the output, clock. Shared by `verify` (the scoreboard) and
 * `device` (the stand-in device).
 *
 * Handshake rules the driver keeps (AXI-stream): once in_valid is raised
 * with a transaction, it stays raised with the same transaction until the
 * pipe accepts it; bubbles are only inserted between transactions.
 */
#include "np_vec.h"
#include "np_vec_stream.h"

#include <stdlib.h>
#include <string.h>

/* Random traffic: phases of 16..271 cycles, each with its own bubble and stall density. */
typedef struct traffic {
    int on;
    np_rng rng;
    uint64_t left;           /* cycles left in this phase */
    unsigned p_bubble, p_stall; /* out of 256 */
} traffic;

/* Densities of a phase, out of 256: none, light, half, heavy. */
static const unsigned density[4] = { 0, 32, 128, 224 };

enum {
    PHASE_MIN = 16,
    PHASE_SPAN = 256,
    WATCHDOG_BASE = 4096 /* cycles without a transfer before the pipe is declared stuck */
};

static void traffic_cycle(traffic *t, int *bubble, int *stall)
{
    *bubble = *stall = 0;
    if (!t->on)
        return;
    if (t->left == 0) {
        uint64_t r = np_rng_next(&t->rng);
        t->left = PHASE_MIN + (r % PHASE_SPAN);
        t->p_bubble = density[(r >> 8) & 3u];
        t->p_stall = density[(r >> 10) & 3u];
    }
    t->left--;
    uint64_t r = np_rng_next(&t->rng);
    *bubble = (unsigned)(r & 255u) < t->p_bubble;
    *stall = (unsigned)((r >> 8) & 255u) < t->p_stall;
}

/* A transaction between its fetch from the source and its output. */
typedef struct slot {
    np_vec_rec rec;
    uint64_t in_cycle;  /* cycle of the input transfer */
    uint64_t stalls_at; /* output-stall cycles counted before it */
} slot;

/* The testbench state of one run. */
typedef struct bench {
    const np_vec_header *h;
    np_pipe pipe;
    np_pipe_port port;
    void *in_sig;
    slot *ring; /* accepted and in flight (<= latency) + the one presented */
    uint64_t cap, head, tail; /* head: oldest in flight; tail: next to accept */
    int presented, eof;
    uint64_t cycle, stall_cycles, bubbles, last_transfer;
} bench;

static int bench_init(bench *b, const np_vec_header *h, char *err, size_t errlen)
{
    memset(b, 0, sizeof *b);
    b->h = h;
    if (h->unit->pipe_init(&b->pipe, &h->cfg) != 0) {
        snprintf(err, errlen, "cannot build the cycle model of %s: out of memory", h->unit->name);
        return -1;
    }
    b->cap = (uint64_t)np_pipe_latency(&b->pipe) + 1u;
    b->ring = calloc((size_t)b->cap, sizeof *b->ring);
    b->in_sig = calloc(1, b->pipe.sig_size);
    if (!b->ring || !b->in_sig) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    return 0;
}

static void bench_free(bench *b)
{
    np_pipe_free(&b->pipe);
    free(b->ring);
    free(b->in_sig);
}

/* Present the next transaction unless one is waiting or this cycle is a bubble. */
static int bench_fetch(bench *b, np_vec_source_fn source, void *ctx, int bubble)
{
    if (b->presented || b->eof)
        return 0;
    if (bubble) {
        b->bubbles++;
        return 0;
    }
    slot *s = &b->ring[b->tail % b->cap];
    int r = source(ctx, &s->rec);
    if (r < 0)
        return -1;
    if (r == 0) {
        b->eof = 1;
        return 0;
    }
    b->h->unit->sig_set_in(b->in_sig, s->rec.w[NP_VEC_IN]);
    b->presented = 1;
    return 0;
}

/* This cycle's output transfer, if any, handed to sink with its transaction. NP_DRIVE_*. */
static int bench_deliver(bench *b, np_vec_sink_fn sink, void *ctx, char *err, size_t errlen)
{
    if (!(b->port.out_valid && b->port.out_ready))
        return NP_DRIVE_DONE;
    if (b->head == b->tail) {
        snprintf(err, errlen, "cycle %llu: the pipe delivered an output with no transaction in flight",
                 (unsigned long long)b->cycle);
        return NP_DRIVE_MODEL;
    }
    const slot *s = &b->ring[b->head++ % b->cap];
    uint64_t out[NP_UNIT_MAX_FIELDS];
    np_vec_timing tm = { np_pipe_latency(&b->pipe), b->cycle - s->in_cycle,
                         b->stall_cycles - s->stalls_at };
    b->h->unit->sig_get_out(&b->h->cfg, b->port.out_sig, out);
    b->last_transfer = b->cycle;
    return sink(ctx, &s->rec, out, &tm) ? NP_DRIVE_STOPPED : NP_DRIVE_DONE;
}

/* This cycle's input transfer, if any: the presented transaction is in flight from now. */
static void bench_accept(bench *b)
{
    if (!(b->port.in_valid && b->port.in_ready))
        return;
    slot *s = &b->ring[b->tail++ % b->cap];
    s->in_cycle = b->cycle;
    s->stalls_at = b->stall_cycles;
    b->presented = 0;
    b->last_transfer = b->cycle;
}

/* A pipe that holds more than it has banks, or makes no transfer for too long. */
static int bench_stuck(const bench *b, char *err, size_t errlen)
{
    unsigned lat = np_pipe_latency(&b->pipe);
    uint64_t in_flight = b->tail - b->head;
    int over = in_flight > lat;
    if (!over && b->cycle - b->last_transfer <= WATCHDOG_BASE + 64u * (uint64_t)lat)
        return 0;
    snprintf(err, errlen, "cycle %llu: the pipe %s (%llu transactions in flight, latency %u)",
             (unsigned long long)b->cycle,
             over ? "holds more transactions than it has register banks" : "made no transfer for too long",
             (unsigned long long)in_flight, lat);
    return 1;
}

int np_vec_drive(const np_vec_header *h, np_vec_source_fn source, void *src_ctx,
                 np_vec_sink_fn sink, void *sink_ctx, int traffic_on, uint64_t seed,
                 np_vec_drive_stats *st, char *err, size_t errlen)
{
    /* Stream units run their own cycle model (span descriptors in, pixels out). */
    if (h->unit->stream)
        return np_stream_drive(h, source, src_ctx, sink, sink_ctx, traffic_on, seed, st, err, errlen);
    bench b;
    traffic t = { .on = traffic_on };
    int rc = NP_DRIVE_DONE;
    np_rng_seed(&t.rng, seed);
    memset(st, 0, sizeof *st);
    if (bench_init(&b, h, err, errlen) != 0) {
        bench_free(&b);
        return NP_DRIVE_MODEL;
    }
    /* One clock per iteration: drive, evaluate, sample, clock. */
    for (;;) {
        int bubble, stall;
        traffic_cycle(&t, &bubble, &stall);
        if (bench_fetch(&b, source, src_ctx, bubble) != 0) {
            rc = NP_DRIVE_BAD_INPUT;
            break;
        }
        if (b.eof && !b.presented && b.head == b.tail)
            break;
        b.port.in_valid = b.presented;
        b.port.in_sig = b.in_sig;
        b.port.out_ready = !stall;
        np_pipe_eval(&b.pipe, &b.port);
        if ((rc = bench_deliver(&b, sink, sink_ctx, err, errlen)) != NP_DRIVE_DONE)
            break;
        bench_accept(&b);
        if (b.port.out_valid && !b.port.out_ready)
            b.stall_cycles++;
        np_pipe_clock(&b.pipe, &b.port);
        b.cycle++;
        if (bench_stuck(&b, err, errlen)) {
            rc = NP_DRIVE_MODEL;
            break;
        }
    }
    st->latency = np_pipe_latency(&b.pipe);
    st->cycles = b.cycle;
    st->accepted = b.tail;
    st->delivered = b.head;
    st->bubbles = b.bubbles;
    st->stalls = b.stall_cycles;
    bench_free(&b);
    return rc;
}
