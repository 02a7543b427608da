/* SPDX-License-Identifier: MIT */
/*
 * np_search.h - the adversarial error search (docs/search.md): the bit-exact
 * model against the float reference on the inputs most likely to break the
 * 1 LSB contract, for a unit with inputs x, y, z (u16 each), on all cores;
 * also for a unit of n = 2, 4 or 5 u16 inputs (the n-D noise units), each
 * class below taken over n axes as docs/search.md, "n inputs", says: 12^n
 * extremes (7^5 at n = 5), faces of every size (2..n words or fractions
 * equal), worst rounding from the fine output's distance to a tie when the
 * unit has no classes of its own, the climb's combinations of -2..+2 (n <= 3)
 * or -1..+1 (n >= 4). A 3-input unit's inputs and results are unchanged.
 *
 * Input classes, each a share of the budget N (after the extremes, of every
 * 16 chunks 6 random, 6 rounding, 2 faces, 2 lattice; the last quarter of N
 * is the climb):
 *   extremes     every combination of 12 per-axis words (0, 1, 0xff, 0x100,
 *                0x7fff, 0x8000, ..., 0xffff: the cell wrap at 256 and the
 *                input ends), then the unit's boundary table (np_unit.boundary);
 *   lattice      random cells; each axis on a lattice point or 1 LSB beside
 *                it (fraction 0xff, 0x00 or 0x01) with probability 1/2 (a
 *                cell face), all three 1 time in 8, the others random;
 *   faces        offsets equal in pairs or all three (x = y, y = z, x = z,
 *                x = y = z, then 1 or 2 LSB off), and the unit's own faces
 *                (np_unit.adversarial, NP_ADV_FACES: the skew boundaries of
 *                simplex3);
 *   rounding     the unit's inputs where the internal roundings are worst,
 *                derived from the configuration's formats
 *                (np_unit.adversarial, NP_ADV_ROUNDING); random when the
 *                unit has none;
 *   random       uniform words from the seeded generator;
 *   hill-climb   from the W worst inputs found so far, steepest ascent over
 *                the neighbours (each axis +-1..+-256 alone, every
 *                combination of -2..+2 over the three axes), moved while the
 *                objective grows, a random kick (+-16 per axis around the
 *                best point) when none does, in rounds from the new W worst
 *                until the climb's share (N / 4) is spent.
 *
 * The climb's objective, which also ranks the W worst: the datapath's error
 * before the output rounding, when the unit gives a finer-output
 * configuration (np_unit.fine_cfg), else the output error. The output
 * error is a staircase (it moves by whole LSB steps of the model); the
 * error before the last rounding is what the internal roundings add up to,
 * and an input over 1 LSB is one where it is large and the last rounding
 * goes the same way.
 *
 * Error of an input: per output field e = |c - r 2^F| in that field's LSB
 * (np_sweep_error: c the model's code, r the reference); the input's error
 * is its largest field error. Over tolerance: !(e <= unit->tolerance_lsb).
 *
 * Determinism: the inputs are cut into chunks of NP_SEARCH_CHUNK; chunk k's
 * class and inputs depend only on (seed, k), one thread computes it, and the
 * chunks' statistics are merged in chunk order; every maximum and the worst
 * list break ties by the smaller input (x, then y, then z). Chunks run in
 * waves of NP_SEARCH_WAVE, all of a wave before the next. The climbs start
 * from that list, each climb in one thread, merged in start order. So the
 * result is the same bits for any thread count and any journal resume.
 */
#ifndef NP_SEARCH_H
#define NP_SEARCH_H

#include <stddef.h>
#include <stdint.h>

#include "np_unit.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_SEARCH_CHUNK = 4096, /* inputs per chunk */
    NP_SEARCH_WORST = 8,    /* W: worst inputs kept, and climbed from */
    NP_SEARCH_WAVE = 8,     /* chunks per wave (stop_early looks between waves) */
    NP_SEARCH_CLASSES = 6,
    NP_SEARCH_MIN_IN = 2,   /* inputs of a unit the search runs: 2..5 u16 words (x, y, z, w, v) */
    NP_SEARCH_MAX_IN = 5
};

/* The input classes (index into np_search_stats.cls_n / cls_max). */
enum { NP_SC_EXTREME, NP_SC_LATTICE, NP_SC_FACE, NP_SC_ROUNDING, NP_SC_RANDOM, NP_SC_CLIMB };
extern const char *const np_search_class_name[NP_SEARCH_CLASSES];

/* One input (the unit's n words; the rest 0) and its error (largest over the fields, LSB). */
typedef struct np_search_pt {
    uint16_t in[NP_SEARCH_MAX_IN];
    double err;
} np_search_pt;

typedef struct np_search_stats {
    uint64_t n;                              /* inputs evaluated */
    uint64_t over;                           /* inputs with a field over tolerance */
    uint64_t cr;                             /* outputs correctly rounded (every field of every input) */
    unsigned n_out;
    np_search_pt fmax[NP_UNIT_MAX_FIELDS];   /* per field: max error and where (err -1: none) */
    uint64_t fover[NP_UNIT_MAX_FIELDS];      /* per field: inputs over tolerance */
    uint64_t cls_n[NP_SEARCH_CLASSES];       /* inputs per class */
    double cls_max[NP_SEARCH_CLASSES];       /* max error per class (-1: none) */
    unsigned n_worst;
    np_search_pt worst[NP_SEARCH_WORST];     /* distinct inputs, largest climb objective first */
} np_search_stats;

typedef struct np_search_opts {
    const np_unit *unit;
    const void *cfg;
    uint64_t n;          /* budget: inputs evaluated in all (>= NP_SEARCH_CHUNK) */
    uint64_t seed;
    unsigned threads;    /* 0: one per online CPU */
    const char *journal; /* NULL: none */
    int resume;
    int progress;        /* np_progress on stderr */
    /*
     * Stop at the first wave (NP_SEARCH_WAVE chunks) that holds an input
     * over tolerance, without the climb: the verdict is then known, and
     * the statistics are those of the waves run (still the same bits for
     * any thread count).
     */
    int stop_early;
} np_search_opts;

/* The verdict in the project's words (PRODUCT.md, Claims). */
typedef enum np_search_verdict {
    NP_SEARCH_PROVED,          /* "faithful (proved)": bound <= 1 LSB, none over found */
    NP_SEARCH_NO_COUNTER,      /* "no counterexample in N adversarial inputs" */
    NP_SEARCH_COUNTEREXAMPLE   /* "not faithful, counterexample (x, y, z)" */
} np_search_verdict;

typedef struct np_search_result {
    np_search_stats total;
    np_search_verdict verdict;
    double bound;        /* unit->error_bound_lsb(cfg) */
    unsigned dims;       /* the unit's inputs (0 is read as 3: a result filled in by hand) */
    np_search_pt worst;  /* the input of the largest output error (the counterexample when over) */
    uint64_t chunks, chunks_resumed;
    unsigned threads;
    double seconds;
} np_search_result;

/* The same statistics, bit for bit (doubles compared as bit patterns). */
int np_search_stats_equal(const np_search_stats *a, const np_search_stats *b);

/* NULL when the search can run unit u (inputs x, y, z of 16 bits), else why not. */
const char *np_search_unit_check(const np_unit *u, const void *cfg);

/*
 * Run the search. 0 on success (whatever it found: see res->verdict); -1
 * on bad input (budget below one chunk, a journal for another run, I/O
 * error, out of memory) with a message in err.
 */
int np_search_run(const np_search_opts *o, np_search_result *res, char *err, size_t errlen);

/*
 * The verdict as text: "faithful (proved)", "no counterexample in N
 * adversarial inputs", "not faithful, counterexample (0xXXXX, 0xYYYY, 0xZZZZ)".
 */
void np_search_verdict_text(const np_search_result *res, char *buf, size_t len);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_SEARCH_H */
