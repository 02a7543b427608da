/* SPDX-License-Identifier: MIT */
/*
 * np_sweep.h - the exhaustive error sweep: every (x, y) input of one z slice
 * of a unit with inputs x, y, z (u16 each; 2^32 inputs), the bit-exact model
 * against the float reference, on all cores, with a resumable journal.
 *
 * Work is cut into blocks: block i is the x cell i, the 2^24 inputs with
 * x >> 8 == i. A block is computed by one thread, rows of 256 inputs (one x
 * cell row at one y) in increasing y, so its statistics depend on nothing but
 * the block. A run's statistics are the blocks' merged in increasing block
 * order, so they are the same bits whatever the thread count, and whatever
 * blocks came from a journal (the journal keeps each block's statistics
 * exactly: counts in decimal, doubles in C99 hex).
 *
 * Per input, with r = ref * 2^F the reference in output LSB (F the output
 * field's fraction bits, an exact scaling) and c the model's output code:
 *   error               e = |c - r|  (double: exact when r is within a factor of
 *                       two of c (Sterbenz), else one rounding, relative 2^-53)
 *   correctly rounded   c == floor(r + 1/2), tested exactly as
 *                       c - 1/2 <= r < c + 1/2 (round half up, as the hardware)
 *   over tolerance      !(e <= unit->tolerance_lsb)  (a NaN counts as over)
 * A unit with several output fields: e is the largest field error, and the
 * input is correctly rounded when every field is.
 */
#ifndef NP_SWEEP_H
#define NP_SWEEP_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "np_unit.h"
#include "np_unit_sweep.h"

#ifdef __cplusplus
extern "C" {
#endif


/*
 * One output's error in output LSB (the definitions above): code the model's
 * output in LSB, ref the reference's value, scale = 2^F. *cr = 1 when the
 * output is the correctly rounded one.
 */
static inline double np_sweep_error(int32_t code, double ref, double scale, unsigned char *cr)
{
    double r = ref * scale, c = (double)code;
    *cr = (unsigned char)((r >= c - 0.5) & (r < c + 0.5));
    return fabs(c - r);
}

enum {
    NP_SWEEP_CELLS = 256,          /* blocks per slice: x cells */
    NP_SWEEP_ROWS = 8,             /* rows per kernel call (a power of two) */
    NP_SWEEP_HIST_PER_LSB = 8,     /* histogram bins of 1/8 LSB ... */
    NP_SWEEP_HIST_BINS = 33        /* ... over [0, 4) LSB, and the last one: >= 4 LSB */
};
#define NP_SWEEP_BLOCK_INPUTS ((uint64_t)1 << 24)

typedef struct np_sweep_stats {
    uint64_t n;       /* inputs checked */
    uint64_t cr;      /* correctly rounded */
    uint64_t over;    /* error over the unit's tolerance */
    double max_err;   /* LSB; -1 when n == 0 */
    uint16_t max_x, max_y; /* the input of max_err: smallest x, then smallest y */
    double sum, sum2; /* sum of e and of e^2 (for the mean and the RMS) */
    uint64_t hist[NP_SWEEP_HIST_BINS];
} np_sweep_stats;

void np_sweep_stats_init(np_sweep_stats *s);
/*
 * into += from. Counts, histogram and maximum do not depend on the order of
 * merges; sum and sum2 are double additions, so a caller that wants the same
 * bits every time merges in a fixed order (np_sweep_run: block order).
 */
void np_sweep_stats_merge(np_sweep_stats *into, const np_sweep_stats *from);
/* Same statistics, bit for bit (doubles compared as bit patterns). */
int np_sweep_stats_equal(const np_sweep_stats *a, const np_sweep_stats *b);

/* NULL when the sweep can run unit u with configuration cfg, else why not. */
const char *np_sweep_unit_check(const np_unit *u, const void *cfg);

/*
 * np_unit.sweep_rows' contract, done the plain way: u->eval and u->ref per
 * input. The reference every fast kernel is tested against.
 */
void np_sweep_rows_generic(const np_unit *u, const void *cfg, uint16_t x0, uint16_t y0,
                           uint16_t z, unsigned rows, unsigned what, int32_t *code,
                           double *ref);


/*
 * Statistics of one block (x cell xcell of slice z) in the calling thread;
 * use_kernel = 0 forces np_sweep_rows_generic. 0, or -1 when out of memory.
 */
int np_sweep_block(const np_unit *u, const void *cfg, uint16_t z, unsigned xcell, int use_kernel,
                   np_sweep_stats *out);

typedef struct np_sweep_opts {
    const np_unit *unit;
    const void *cfg;
    uint16_t z;               /* the slice, u16 (Q8.8 for classic3) */
    unsigned x_first, x_end;  /* blocks x_first <= i < x_end (0 <= x_first < x_end <= 256) */
    unsigned threads;         /* 0: one per online CPU */
    const char *journal;      /* NULL: none */
    int resume;               /* continue the journal (or start it when missing) */
    int use_kernel;           /* use u->sweep_rows when the unit has one */
    int progress;             /* np_progress line on stderr when it is a terminal */
} np_sweep_opts;

typedef struct np_sweep_result {
    np_sweep_stats total;     /* blocks x_first..x_end-1, merged in block order */
    unsigned blocks;          /* x_end - x_first */
    unsigned blocks_resumed;  /* taken from the journal */
    unsigned threads;         /* threads that computed */
    int kernel;               /* the unit's fast kernel was used */
    uint64_t computed;        /* inputs computed by this run */
    double seconds;           /* wall time of this run */
} np_sweep_result;

/*
 * Run a sweep. 0 on success (whatever the errors found: look at res->total);
 * -1 on bad input (journal for another unit/config/slice, corrupt journal,
 * I/O error, out of memory), with a message in err.
 */
int np_sweep_run(const np_sweep_opts *o, np_sweep_result *res, char *err, size_t errlen);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_SWEEP_H */
