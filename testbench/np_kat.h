/* SPDX-License-Identifier: MIT */
/*
 * np_kat.h - known-answer tables of any registered unit, as C initializer
 * rows that a unit's test #includes (testbench/<unit>_kat.inc). One generator
 * for every unit: testbench/gen_kat.c prints a table, and the conformance
 * test (conformance.kat) regenerates the checked-in one from the command
 * recorded in its first line and compares byte for byte.
 *
 * A row is { inputs (hex), outputs of configuration [0] (the default),
 * outputs of [1], ... (decimal, signed fields sign-extended) }, then a
 * comment with an optional note and the float reference of [0]:
 *   { 0x0080, 0x0080, 0x0080,   16 }, / * cell centre; ref +0.250000 * /
 * Inputs are either the unit's boundary table then seeded random ones, or
 * (--inputs FILE) the inputs and notes of an existing table, for a table
 * whose inputs were chosen and annotated by hand.
 */
#ifndef NP_KAT_H
#define NP_KAT_H

#include <stddef.h>
#include <stdio.h>

enum { NP_KAT_MAX_CONFIGS = 4, NP_KAT_MAX_ROWS = 512, NP_KAT_ROWS = 96, NP_KAT_SEED = 2024 };

typedef struct np_kat_spec {
    const char *unit;
    const char *configs[NP_KAT_MAX_CONFIGS]; /* [0] is the default ("") */
    unsigned n_configs;
    const char *inputs; /* a table to take the inputs and notes from, or NULL */
    unsigned rows;      /* rows when generated (no inputs table) */
    char argv_text[512]; /* the gen_kat arguments, as recorded in the table's first line */
} np_kat_spec;

/*
 * Parse gen_kat's arguments: UNIT [--config SPEC]... [--inputs FILE] [-n ROWS].
 * dir, when not NULL, is prefixed to a relative --inputs path. 0, or -1 with err.
 */
int np_kat_parse(int argc, char **argv, const char *dir, np_kat_spec *s, char *err, size_t errlen);

/* The directory part of path ("." when it has none). */
void np_kat_dir_of(const char *path, char *dir, size_t len);

/* Write the table of s to out. 0, or -1 with err. */
int np_kat_write(const np_kat_spec *s, FILE *out, char *err, size_t errlen);

/*
 * Regenerate the table at path from the command in its first line and
 * compare it with the file byte for byte. 0 identical; 1 different (err
 * names the first differing line); -1 error (err).
 */
int np_kat_check(const char *path, char *err, size_t errlen);

#endif /* NP_KAT_H */
