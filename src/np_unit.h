/* SPDX-License-Identifier: MIT */
/*
 * np_unit.h - the registry of hardware units.
 *
 * Every tool (vectors, verify, device, sweep, bench, reports) works on a unit
 * through this one interface, so a new unit plugs into all of them by filling
 * in one np_unit and adding it to np_units[] (units.c).
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

#include "np_pipe.h"

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
} np_unit;

extern const np_unit *const np_units[]; /* NULL-terminated */
const np_unit *np_unit_find(const char *name);

/* Real value of an output word of field f. */
double np_unit_field_value(const np_field *f, uint64_t word);

/* Configure u from "key=value[,key=value...]" (NULL or "" = defaults). */
int np_unit_configure(const np_unit *u, void *cfg, const char *spec, char *err, size_t errlen);

#endif /* NP_UNIT_H */
