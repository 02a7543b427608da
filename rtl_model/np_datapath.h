/* SPDX-License-Identifier: MIT */
/*
 * np_datapath.h - a unit's datapath as data: per pipeline stage, the
 * operators with their widths, and the pipeline register bits.
 *
 * One source of truth: each unit writes its declaration next to its model
 * (e.g. np_classic_datapath() in np_classic.c). The gate and latency report
 * (src/report/report_gates.c) prices it with a documented cost model, and a test
 * traces the model's signals over vectors and fails when a declared width is
 * narrower than the model needs, or wider by more than the stated margin.
 */
#ifndef NP_DATAPATH_H
#define NP_DATAPATH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum np_op_kind {
    NP_OP_ADD,  /* adder or subtractor, ripple carry: a = width */
    NP_OP_CMP,  /* magnitude comparator: a = width */
    NP_OP_MUL,  /* array multiplier: a x b bits */
    NP_OP_MUX,  /* b:1 multiplexer of a bits */
    NP_OP_NEG,  /* conditional negate (XOR + increment): a = width */
    NP_OP_LUT,  /* fixed-function lookup (logic, no storage): a index bits -> b bits */
    NP_OP_ROM,  /* read-only memory: 2^a words of b bits */
    NP_OP_REG,  /* pipeline register: a bits (stage = the bank after that stage) */
    NP_OP_INC,  /* adding a constant (half an LSB to round, +1, constant - x): a = width */
    NP_OP_CMPK, /* comparison with a constant (saturation, clamps): a = width */
    NP_OP_SQR,  /* squarer x * x: a = the operand's width */
    NP_OP_CARRY, /* the carry out of an a-bit sum whose sum bits are not read (a majority chain) */
    NP_OP_MULLO, /* multiplier keeping the product's low a bits only (modulo 2^a): a x b, a >= b */
    NP_OP_SMUL,  /* signed x signed array multiplier (both operands two's complement): a x b bits */
    NP_OP_KINDS
} np_op_kind;

typedef struct np_op {
    const char *stage;  /* the stage name of the unit's np_stage_desc */
    const char *signal; /* the signal produced (traced by the width check), or NULL */
    np_op_kind kind;
    unsigned count;     /* identical instances */
    unsigned a, b;      /* widths, meaning per kind */
    unsigned out;       /* width of the produced signal (0 when not a traced signal) */
    int out_signed;     /* the produced signal is two's complement */
    unsigned level;     /* critical path: ops of one level work in parallel, levels in series */
} np_op;

/*
 * A declaration under construction: writes up to max ops, counts them all
 * (so a caller can size its array from the returned count).
 */
typedef struct np_dp {
    np_op *ops;
    size_t max, n;
} np_dp;

static inline void np_dp_op(np_dp *d, const char *stage, const char *signal, np_op_kind kind, unsigned count,
                            unsigned a, unsigned b, unsigned out, int out_signed, unsigned level)
{
    if (d->n < d->max) {
        np_op *o = &d->ops[d->n];
        o->stage = stage;
        o->signal = signal;
        o->kind = kind;
        o->count = count;
        o->a = a;
        o->b = b;
        o->out = out;
        o->out_signed = out_signed;
        o->level = level;
    }
    d->n++;
}

/*
 * An adder tree summing m operands of w bits (modulo 2^w) from level0 on:
 * ceil(log2 m) levels; signal names the last adder's output. Returns the
 * first free level after it.
 */
static inline unsigned np_dp_add_tree(np_dp *d, const char *stage, const char *signal, unsigned m, unsigned w,
                                      int out_signed, unsigned level0)
{
    unsigned lv = level0;
    while (m > 1) {
        unsigned adders = m / 2u;
        m -= adders;
        np_dp_op(d, stage, m == 1 ? signal : NULL, NP_OP_ADD, adders, w, 0, m == 1 ? w : 0, out_signed, lv++);
    }
    return lv;
}

/* Bits needed to hold every value of [lo, hi] (signed when lo < 0 or forced). */
static inline unsigned np_bits_for_range(int64_t lo, int64_t hi, int is_signed)
{
    unsigned n = 1;
    if (is_signed || lo < 0) {
        while (n < 64 && !(lo >= -((int64_t)1 << (n - 1)) && hi <= ((int64_t)1 << (n - 1)) - 1))
            n++;
    } else {
        while (n < 63 && hi > ((int64_t)1 << n) - 1)
            n++;
    }
    return n;
}

/*
 * A traced signal's observed range. Signals wider than 64 bits are traced by
 * their width instead (np_trace_add_wide): wide = the most bits a value
 * needed as a two's complement number, wide_neg = a negative value was seen.
 */
typedef struct np_trace {
    const char *signal;
    int64_t lo, hi;
    uint64_t samples;
    unsigned wide;
    int wide_neg;
} np_trace;

/* Widen a trace to include v. */
static inline void np_trace_add(np_trace *t, int64_t v)
{
    if (t->samples == 0 || v < t->lo)
        t->lo = v;
    if (t->samples == 0 || v > t->hi)
        t->hi = v;
    t->samples++;
}

/*
 * Widen a trace by a value that needs sbits bits as a two's complement
 * number (neg: it is negative); for values beyond int64_t.
 */
static inline void np_trace_add_wide(np_trace *t, unsigned sbits, int neg)
{
    if (sbits > t->wide)
        t->wide = sbits;
    t->wide_neg |= neg;
    t->samples++;
}

/* Bits the traced range needs in a signal of the given signedness. */
static inline unsigned np_trace_need(const np_trace *t, int is_signed)
{
    unsigned n = np_bits_for_range(t->lo, t->hi, is_signed);
    if (t->wide) {
        /* A non-negative value of s bits signed needs s - 1 bits unsigned. */
        unsigned w = (is_signed || t->wide_neg) ? t->wide : (t->wide > 1u ? t->wide - 1u : 1u);
        if (w > n)
            n = w;
    }
    return n;
}

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_DATAPATH_H */
