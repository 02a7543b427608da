/* SPDX-License-Identifier: MIT */
/*
 * np_unit.h - the registry of hardware units.
 *
 * Every tool (vectors, verify, device, sweep, bench, reports) works on a unit
 * through this one interface, so a new unit plugs into all of them by filling
 * in one np_unit and adding it to np_units[] (units.c), or, for a unit that
 * lives outside the library (a test's), by np_unit_register() at run time.
 * docs/adding-a-unit.md lists the files a new unit brings.
 *
 * Words: every input and output field travels as a uint64_t holding the
 * field's hardware bits, masked to its width (a signed field is its two's
 * complement bit pattern). np_unit_field_value() turns an output word into
 * the real value it stands for.
 */
#ifndef NP_UNIT_H
#define NP_UNIT_H

#include <stddef.h>
#include <stdint.h>

#include "np_datapath.h"
#include "np_pipe.h"

#ifdef __cplusplus
extern "C" {
#endif

struct np_scene;
struct np_unit_timing;

enum { NP_UNIT_MAX_FIELDS = 8, NP_UNIT_CFG_MAX = 256 };

/* Storage for any unit's configuration block (aligned for any struct). */
typedef union np_unit_cfg {
    unsigned char bytes[NP_UNIT_CFG_MAX];
    long double align_ld;
    uint64_t align_u64;
    void *align_p;
} np_unit_cfg;

typedef struct np_field {
    char name[16];   /* "x", "f" */
    unsigned bits;   /* hardware width, 1..64 */
    int is_signed;   /* two's complement */
    unsigned frac;   /* fraction bits: value = word / 2^frac */
    char format[32]; /* human text, e.g. "u16 Q8.8", "s8 Q2.6" */
} np_field;

typedef struct np_unit_fields {
    unsigned n_in, n_out;
    np_field in[NP_UNIT_MAX_FIELDS];
    np_field out[NP_UNIT_MAX_FIELDS];
} np_unit_fields;

typedef struct np_unit {
    const char *name;    /* as typed on the command line, e.g. "classic3" */
    const char *summary; /* one line */
    /* Configuration: an opaque block of at most NP_UNIT_CFG_MAX bytes. */
    void (*cfg_default)(void *cfg);
    /* Set one "key=value"; 0, or -1 with a message naming key and range in err. */
    int (*cfg_set)(void *cfg, const char *key, const char *value, char *err, size_t errlen);
    /* "key=value key=value", every key, in a fixed order (goes in file headers). */
    void (*cfg_format)(const void *cfg, char *buf, size_t len);
    /* NULL when consistent, else a message. */
    const char *(*cfg_check)(const void *cfg);
    void (*fields)(const void *cfg, np_unit_fields *f);
    /* Bit-exact model. */
    void (*eval)(const void *cfg, const uint64_t *in, uint64_t *out);
    /* Float reference: the real value of each output field. */
    void (*ref)(const void *cfg, const uint64_t *in, double *out);
    /* Accuracy contract: max |output - reference| in output LSB (per field). */
    double tolerance_lsb;
    /* Guaranteed bound of the unit's error argument, in LSB (for reports). */
    double (*error_bound_lsb)(const void *cfg);
    /* Cycle-accurate model (np_pipe); the bundle is the pipe's signal struct. */
    int (*pipe_init)(np_pipe *p, const void *cfg);
    void (*sig_set_in)(void *sig, const uint64_t *in);
    void (*sig_get_out)(const void *cfg, const void *sig, uint64_t *out); /* masked words */
    /*
     * Hand-annotated boundary cases (the annotations are in the unit's
     * source) for the vector generator: writes up to max inputs, n_in words
     * each; returns the full count even when it is larger than max.
     */
    size_t (*boundary)(const void *cfg, uint64_t (*in)[NP_UNIT_MAX_FIELDS], size_t max);
    /*
     * Optional (NULL: the sweep calls eval and ref per input): the exhaustive
     * sweep's fast path (np_sweep.h) for a unit with inputs x, y, z (u16 each).
     * For the 256 * rows inputs (x0 + t, y0 + r, z), 0 <= t < 256,
     * 0 <= r < rows, where x0 is a multiple of 256, rows a power of two <= 256
     * and y0 a multiple of rows, writes at index i = (f * rows + r) * 256 + t
     * (f: output field):
     *   if what & NP_SWEEP_MODEL: code[i] = the model's output as a signed
     *     integer in output LSB (the field's word, sign-extended if signed);
     *   if what & NP_SWEEP_REF: ref[i] = the float reference's value.
     * It must give exactly eval's bits and ref's doubles (testbench/test_sweep.c
     * proves it for classic3: a unit that adds a kernel adds such a test).
     */
    void (*sweep_rows)(const void *cfg, uint16_t x0, uint16_t y0, uint16_t z, unsigned rows,
                       unsigned what, int32_t *code, double *ref);
    /*
     * Optional (NULL: not in the gate report): the datapath declaration of
     * np_datapath.h for cfg; writes up to max ops, returns the full count.
     */
    size_t (*datapath)(const void *cfg, np_op *ops, size_t max);
    /*
     * Optional (NULL: a one-input-one-output unit): a stream unit, which reads
     * a descriptor and writes a run of beats (the scanline texturing units: a
     * span in, its pixels out). Transactions are then beats, and the unit's
     * cycle-accurate model is this stream model; see np_stream.h.
     */
    const struct np_unit_stream *stream;
    /*
     * Optional (NULL: the timing is np_pipe's: latency = pipe depth, one
     * result per clock, the declaration's stages are the pipe's): the timing
     * of a unit whose cycle-accurate model is not one np_pipe (a stream unit),
     * from the unit's own schedule; the gate report's stages are then the
     * declaration's, in order. 0, or -1 with a message in err.
     */
    int (*timing)(const void *cfg, struct np_unit_timing *t, char *err, size_t errlen);
    /*
     * Optional (NULL: no scene uses the unit): configure cfg (from the
     * defaults) for what scene sc needs. 1: the scene uses the unit and cfg
     * is set; 0: it does not; -1 with a message in err.
     */
    int (*cfg_scene)(void *cfg, const struct np_scene *sc, char *err, size_t errlen);
    /*
     * Optional (NULL: the declared widths are checked by the unit's own
     * test): widen each trace in t[0..n) whose signal stage k of the pipe
     * (pipe_init's stage k) produces, from the signal bundle sig just after
     * that stage ran. The conformance test (testbench/conformance.c) runs
     * the stages over the generator's cases and checks every declared
     * width (datapath) against what it traced.
     */
    void (*trace)(const void *cfg, unsigned k, const void *sig, np_trace *t, size_t n);
    /*
     * Optional (NULL: the default only): further configurations, as
     * "key=value,..." specs, NULL-terminated, on which the conformance test
     * runs its checks besides the default (narrow, wide, parts left out).
     */
    const char *const *conformance_configs;
} np_unit;

/* A set-up the unit stalls for (np_unit_timing). */
typedef struct np_unit_setup {
    char what[48];      /* e.g. "cell (per octave, on a cell change)" */
    unsigned products;  /* multiplications it issues */
    unsigned cycles;    /* the stall, clocks */
} np_unit_setup;

enum { NP_UNIT_MAX_SETUPS = 6, NP_UNIT_MAX_MULTI = 4 };

typedef struct np_unit_timing {
    unsigned latency;     /* clocks from accepting an input (a stream unit: a descriptor) to its first result */
    double throughput;    /* results per clock at the peak rate */
    char throughput_note[96]; /* what the peak rate holds for, e.g. "inside a cell" */
    /* Stages that take several clocks (a pipelined engine): the path per clock is the stage's / clocks. */
    unsigned n_multi;
    struct {
        const char *stage;
        unsigned clocks;
    } multi[NP_UNIT_MAX_MULTI];
    unsigned n_setup;
    np_unit_setup setup[NP_UNIT_MAX_SETUPS];
} np_unit_timing;

/* The built-in units, NULL-terminated. Tools that list units use np_unit_at(), which also sees registered ones. */
extern const np_unit *const np_units[];

/*
 * Runtime registration: add unit u (which must outlive every use; its name
 * must be new) behind the built-in units, so that np_unit_find, np_unit_at
 * and every tool built on them (vectors, verify, device, conformance, gate
 * report) see it. For a test or an embedding program that brings its own
 * unit; at most NP_UNIT_MAX_REGISTERED. 0, or -1 when the name is taken,
 * the unit lacks a required entry or the table is full.
 *
 * Not synchronised: register every unit before any thread that reads the
 * registry starts (the sweep's workers only read it).
 */
enum { NP_UNIT_MAX_REGISTERED = 16 };
int np_unit_register(const np_unit *u);
/* Every unit, built-in first then registered, by index from 0; NULL past the last. */
const np_unit *np_unit_at(size_t i);
/* The unit called name (built-in or registered), or NULL. */
const np_unit *np_unit_find(const char *name);

/* Real value of an output word of field f. */
double np_unit_field_value(const np_field *f, uint64_t word);

/* For units' cfg_set: a whole decimal number in [lo, hi]; 0, or -1 if malformed or out of range. */
int np_unit_parse_uint(const char *v, unsigned lo, unsigned hi, unsigned *out);

/* For units' fields(): fill one field description. */
void np_unit_set_field(np_field *f, const char *name, unsigned bits, int sgn, unsigned frac, const char *fmt);

/* Configure u from "key=value[,key=value...]" (NULL or "" = defaults). */
int np_unit_configure(const np_unit *u, void *cfg, const char *spec, char *err, size_t errlen);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_UNIT_H */
