/* SPDX-License-Identifier: MIT */
/*
 * np_vec.h - golden test vectors: the file format with its one reader and
 * one writer (vecfile.c), the case generator (vecgen.c), the driver that
 * runs vectors through a unit's cycle-accurate model (vecdrive.c) and the
 * verifier (verify.c). Everything works on any np_unit; the format is
 * specified in docs/vectors.md.
 *
 * A vector line is a list of columns. Each column is one field of the unit
 * in one role ("kind"):
 *
 *   NP_VEC_IN   an input field           x       ceil(bits/4) hex digits
 *   NP_VEC_OUT  expected output (model)  f       ceil(bits/4) hex digits
 *   NP_VEC_REF  float reference value    f.ref   16 hex digits, binary64 bits
 *   NP_VEC_GOT  a device's result        f.got   ceil(bits/4) hex digits
 *
 * A text line holds every IN, then every OUT, then every REF column, then
 * (only when a device appended them) every GOT column.
 */
#ifndef NP_VEC_H
#define NP_VEC_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "np_fixed.h"
#include "np_rng.h"
#include "np_unit.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_VEC_VERSION = 1,     /* "# noisepipe vectors 1" */
    NP_VEC_KINDS = 4,
    NP_VEC_MAX_COLS = NP_VEC_KINDS * NP_UNIT_MAX_FIELDS,
    NP_VEC_REF_BITS = 64,   /* binary64 bit pattern */
    NP_VEC_ERRLEN = 512
};

typedef enum np_vec_kind { NP_VEC_IN, NP_VEC_OUT, NP_VEC_REF, NP_VEC_GOT } np_vec_kind;

/* Column masks for np_vec_columns(). */
enum {
    NP_VEC_M_IN = 1u << NP_VEC_IN,
    NP_VEC_M_OUT = 1u << NP_VEC_OUT,
    NP_VEC_M_REF = 1u << NP_VEC_REF,
    NP_VEC_M_GOT = 1u << NP_VEC_GOT
};

typedef enum np_vec_format {
    NP_VEC_TEXT,     /* vector lines, '#' header */
    NP_VEC_READMEMH, /* packed words {valid, in..., out...}, '//' header */
    NP_VEC_COE,      /* the same words as a Xilinx .coe, ';' header */
    NP_VEC_RESULTS   /* GOT columns only, one line per transaction, '//' header */
} np_vec_format;

/* The low bits set, 1 <= bits <= 64 (NP_MASK stops at 63). */
static inline uint64_t np_vec_mask(unsigned bits) { return bits >= 64 ? ~(uint64_t)0 : NP_MASK(bits); }

/* "classic3, simplex3": the registered units, for messages. */
void np_vec_unit_names(char *buf, size_t len);

/* "text" "readmemh" "coe" "results" -> format; -1 when unknown. */
int np_vec_format_parse(const char *name, np_vec_format *fmt);

/* Everything a file's header says. */
typedef struct np_vec_header {
    const np_unit *unit;
    np_unit_cfg cfg;
    np_unit_fields fields;
    char cfg_text[256];  /* np_unit_cfg_format(): every key, in the table's order */
    uint64_t seed;       /* generator seed (valid when has_seed) */
    int has_seed;
    unsigned level;      /* 1 or 2; 0 when the file does not say */
    uint64_t count;      /* transactions in the file */
    int has_got;         /* text lines carry GOT columns */
    char sources[128];   /* optional "# sources ..." comment; "" for none */
} np_vec_header;

/*
 * Header for unit u configured by spec ("k=v,k=v"; NULL = defaults). Seed,
 * level and count are left 0 for the caller. 0, or -1 with a message in err.
 */
int np_vec_header_init(np_vec_header *h, const np_unit *u, const char *spec, char *err,
                       size_t errlen);

typedef struct np_vec_col {
    char name[24];    /* "x", "f", "f.ref", "f.got" */
    np_vec_kind kind;
    unsigned field;   /* index into fields.in (IN) or fields.out (the others) */
    unsigned bits;    /* hardware width; NP_VEC_REF_BITS for REF */
    unsigned digits;  /* hex digits: ceil(bits / 4) */
    char format[32];  /* "u16 Q8.8", "binary64" */
} np_vec_col;

/* Columns of the kinds in mask, in line order. Returns how many (<= NP_VEC_MAX_COLS). */
unsigned np_vec_columns(const np_vec_header *h, unsigned mask, np_vec_col *cols);

/* One transaction. REF words hold binary64 bit patterns (np_vec_ref_value). */
typedef struct np_vec_rec {
    uint64_t index; /* 0-based transaction number = $readmemh address */
    uint64_t line;  /* line in the file it was read from; 0 when generated */
    uint64_t w[NP_VEC_KINDS][NP_UNIT_MAX_FIELDS];
} np_vec_rec;

double np_vec_ref_value(uint64_t bits);
uint64_t np_vec_ref_bits(double v);

/*
 * The bit-exact model's output words (out) and the float reference's binary64
 * bit patterns (ref) for the input words in: what OUT and REF columns hold.
 */
void np_vec_compute(const np_vec_header *h, const uint64_t *in, uint64_t *out, uint64_t *ref);

/* --- Reading (vecfile.c) --- */

/* A line source: a file or stdin, one reused buffer (no per-line allocation). */
typedef struct np_vec_lines {
    FILE *f;
    int own;
    const char *name; /* path as given, or "<stdin>" */
    char *buf;
    size_t cap;
    uint64_t lineno;
    char err[NP_VEC_ERRLEN]; /* the last error, "FILE:LINE: field F: ..." */
} np_vec_lines;

typedef struct np_vec_reader {
    np_vec_lines L;
    np_vec_header h;
    np_vec_col cols[NP_VEC_MAX_COLS];
    unsigned n_cols;  /* columns per line (with GOT columns when h.has_got) */
    int pending;      /* L.buf holds the first vector line, met by the header parser */
    uint64_t n;       /* vectors read */
    uint64_t count_line;
    char hint[96];    /* said after a wrong field count */
} np_vec_reader;

/*
 * Open a vector file ("-" = stdin), parse and check its header, configure the
 * unit from it, and decide whether lines carry device results (from the
 * header's "got" fields, else from the first vector line). 0, or -1 with
 * r->L.err set (missing/empty file, missing header, unknown unit, bad
 * configuration, field declarations that do not match the unit).
 */
int np_vec_open(np_vec_reader *r, const char *path);
/* Next transaction: 1, 0 at the end (after checking the header's count), -1 with r->L.err. */
int np_vec_read(np_vec_reader *r, np_vec_rec *rec);
/* np_vec_read as an np_vec_source_fn (reader is an np_vec_reader *). */
int np_vec_read_source(void *reader, np_vec_rec *rec);
void np_vec_close(np_vec_reader *r);

/*
 * A device's results file: per transaction one line with the GOT columns,
 * or, for units with several outputs, one packed word {out...} as
 * $writememh writes it. Blank lines, '#' and '//' comments and an "@addr"
 * line that names the next transaction are allowed.
 */
typedef struct np_vec_results {
    np_vec_lines L;
    const np_vec_header *h;
    np_vec_col cols[NP_UNIT_MAX_FIELDS];
    unsigned n_cols;
    unsigned packed_digits; /* digits of a packed {out...} word */
    uint64_t n;
} np_vec_results;

int np_vec_results_open(np_vec_results *rr, const char *path, const np_vec_header *h);
/* Fill rec->w[NP_VEC_GOT]: 1, 0 at the end (after checking the count against h), -1 with err. */
int np_vec_results_read(np_vec_results *rr, np_vec_rec *rec);
void np_vec_results_close(np_vec_results *rr);

/* --- Writing (vecfile.c) --- */

typedef struct np_vec_writer {
    FILE *f;
    np_vec_format fmt;
    const np_vec_header *h;
    np_vec_col cols[NP_VEC_MAX_COLS];
    unsigned n_cols;
    unsigned word_bits; /* READMEMH/COE: 1 + every IN and OUT width */
    uint64_t n;         /* transactions written */
    int atomic;         /* writing tmp, renamed to path on success */
    char path[4096], tmp[4096 + 32];
    char line[NP_VEC_MAX_COLS * 17 + 320]; /* longest line or packed word */
    char err[NP_VEC_ERRLEN];
} np_vec_writer;

/*
 * Start writing h->count transactions in format fmt to path (NULL or "-" =
 * stdout; a file is written to a temporary name and renamed into place by
 * np_vec_writer_close, so a failed run leaves no partial file behind), and
 * write the header. 0, or -1 with w->err.
 */
int np_vec_writer_open(np_vec_writer *w, const char *path, np_vec_format fmt,
                       const np_vec_header *h);
/* Write one transaction. 0, or -1 with w->err. */
int np_vec_writer_put(np_vec_writer *w, const np_vec_rec *rec);
/*
 * Finish: commit != 0 checks that exactly h->count transactions were written,
 * flushes and renames into place; commit == 0 discards the temporary file.
 * 0, or -1 with w->err (then nothing is left at path).
 */
int np_vec_writer_close(np_vec_writer *w, int commit);

/* --- Generation (vecgen.c) --- */

enum { NP_VEC_L1_RANDOM = 1024, NP_VEC_L2_RANDOM = 1000000 };

typedef enum np_vecgen_src {
    NP_VECGEN_BOUNDARY, /* unit->boundary; level 2 adds each case's +-1 neighbours per field */
    NP_VECGEN_WALK,     /* one field walks its bit patterns, the others hold a background */
    NP_VECGEN_STEP,     /* every field takes the same walking pattern together */
    NP_VECGEN_PAIR,     /* level 2: two fields cross their walking patterns */
    NP_VECGEN_RANDOM,   /* weighted random, from np_rng */
    NP_VECGEN_NSRC
} np_vecgen_src;

typedef struct np_vecgen {
    const np_vec_header *h;
    unsigned level;
    uint64_t (*bnd)[NP_UNIT_MAX_FIELDS]; /* the unit's boundary table */
    size_t n_bnd;
    unsigned pat_w;                       /* widest input field */
    uint64_t space[NP_VECGEN_NSRC];       /* index space per source */
    uint64_t count[NP_VECGEN_NSRC];       /* cases per source */
    np_vecgen_src src;                    /* cursor */
    uint64_t i;
    uint64_t seq;                         /* transactions produced */
    np_rng rng;                           /* for NP_VECGEN_RANDOM */
} np_vecgen;

/*
 * Prepare the cases of a level (1 or 2) for header h: n_random random cases
 * (UINT64_MAX = the level's default). 0, or -1 with err (no memory).
 */
int np_vecgen_init(np_vecgen *g, const np_vec_header *h, unsigned level, uint64_t seed,
                   uint64_t n_random, char *err, size_t errlen);
uint64_t np_vecgen_total(const np_vecgen *g);
/* Next case with OUT and REF computed: 1, or 0 when done. */
int np_vecgen_next(np_vecgen *g, np_vec_rec *rec);
void np_vecgen_free(np_vecgen *g);

/* One file the generator writes: path (NULL or "-" = stdout) in format fmt. */
typedef struct np_vec_output {
    const char *path;
    np_vec_format fmt;
} np_vec_output;

enum { NP_VEC_MAX_OUTPUTS = 4 };

/*
 * Generate the cases once and write them to every output (at most
 * NP_VEC_MAX_OUTPUTS; each file appears only when all are complete). Sets
 * h's seed, level, count and sources. 0, or -1 with err.
 */
int np_vec_generate(np_vec_header *h, unsigned level, uint64_t seed, uint64_t n_random,
                    const np_vec_output *outs, unsigned n_outs, char *err, size_t errlen);

/* --- Driving the cycle-accurate model (vecdrive.c) --- */

/* Where a transaction spent its time in the pipe. */
typedef struct np_vec_timing {
    unsigned latency; /* the pipe's, in clocks */
    uint64_t clocks;  /* from the input transfer to the output transfer */
    uint64_t stalls; /* output-stall cycles in between: each can hold it one clock */
} np_vec_timing;

/* Next transaction to drive: 1, 0 at the end, -1 on bad input (message is the source's). */
typedef int (*np_vec_source_fn)(void *ctx, np_vec_rec *rec);
/* One output of the pipe, in order, with its transaction: 0 to go on, 1 to stop. */
typedef int (*np_vec_sink_fn)(void *ctx, const np_vec_rec *rec, const uint64_t *out,
                              const np_vec_timing *t);

typedef struct np_vec_drive_stats {
    unsigned latency;
    uint64_t cycles, accepted, delivered, bubbles, stalls;
} np_vec_drive_stats;

enum { NP_DRIVE_DONE = 0, NP_DRIVE_STOPPED = 1, NP_DRIVE_BAD_INPUT = -1, NP_DRIVE_MODEL = -2 };

/*
 * Run every transaction of source through h's cycle-accurate model (a fresh
 * pipe) and hand each output to sink in order. traffic != 0 inserts random
 * input bubbles and output stalls drawn from np_rng seeded with seed, in
 * phases of random length and density (none, light, half, heavy), so the pipe
 * runs empty, full and backpressured; traffic == 0 streams one input per clock
 * with the output always ready. Returns NP_DRIVE_*; NP_DRIVE_MODEL (a pipe
 * that delivers an output nobody sent, or makes no progress) and out-of-memory
 * put a message in err.
 */
int np_vec_drive(const np_vec_header *h, np_vec_source_fn source, void *src_ctx,
                 np_vec_sink_fn sink, void *sink_ctx, int traffic, uint64_t seed,
                 np_vec_drive_stats *st, char *err, size_t errlen);

/* --- Verification (verify.c) --- */

enum { NP_VEC_HIST_HALF = 32 }; /* 1/8-LSB bins on each side of 0: +-4 LSB */

/* Error of one output field against the float reference, in output LSB. */
typedef struct np_vec_acc {
    uint64_t n;
    uint64_t rounded;     /* output == round-half-up(ref * 2^frac), saturated */
    double max_abs;       /* max |output - ref| */
    uint64_t max_index;   /* the vector where it happened */
    uint64_t below, above; /* errors < -4 LSB, >= +4 LSB */
    uint64_t bin[2 * NP_VEC_HIST_HALF]; /* bin k: [(k - HALF)/8, (k - HALF + 1)/8) */
} np_vec_acc;

typedef struct np_verify_opts {
    const char *cmd;      /* for messages: "verify", "run" */
    uint64_t max_errors;  /* stop after this many failing vectors; 0 = never */
    double tolerance;     /* LSB; < 0 = the unit's tolerance_lsb */
    int traffic;          /* random bubbles and stalls on the cycle model */
    uint64_t seed;        /* for the traffic */
    const char *results;  /* device results file, or NULL */
} np_verify_opts;

/*
 * Verify the vector file at path ("-" = stdin), TestFloat style, printing to
 * out one line per failing vector, the error summary and a one-line verdict.
 * Every vector's expected outputs and reference are recomputed from its
 * inputs; the outputs checked are the device's (--results file or GOT
 * columns) or else the cycle-accurate model's. Bad input goes to stderr.
 * Returns NP_EXIT_OK, NP_EXIT_FAIL or NP_EXIT_USAGE.
 */
int np_verify(const char *path, const np_verify_opts *o, FILE *out);

/* --- Command-line helpers shared by vectors, verify, device and run (vec_cli.c) --- */

/*
 * If argv[*i] is option name, as "--name VALUE" or "--name=VALUE": set *val,
 * advance *i past it and return 1. 0 when it is another argument; -1 (after
 * a message) when the value is missing.
 */
int np_vec_opt(const char *cmd, int argc, char **argv, int *i, const char *name,
               const char **val);
int np_vec_is_help(const char *arg);
/* Parse an option value, with a message naming the option on failure: 0 or -1. */
int np_vec_opt_u64(const char *cmd, const char *name, const char *val, uint64_t lo,
                   uint64_t hi, uint64_t *out);
int np_vec_opt_double(const char *cmd, const char *name, const char *val, double *out);
/* The unit named by name configured by spec, as a header; message and -1 on failure. */
int np_vec_opt_header(const char *cmd, const char *name, const char *spec, np_vec_header *h);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_VEC_H */
