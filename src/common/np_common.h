/* SPDX-License-Identifier: MIT */
/*
 * np_common.h - the common layer (src/common/, under every other src/ folder
 * and depending on none: docs/architecture.md): exit codes, messages, numbers
 * typed by people, progress, time. Output files and folders: np_outfile.h;
 * the seeded generator: np_rng.h.
 */
#ifndef NP_COMMON_H
#define NP_COMMON_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_EXIT_OK = 0,    /* success */
    NP_EXIT_FAIL = 1,  /* a check failed */
    NP_EXIT_USAGE = 2  /* bad usage or bad input */
};

/* "noisepipe CMD: message" on stderr. */
void np_err(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* A library function's error: the message into err[errlen] (the caller prints it); returns -1. */
int np_errf(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/*
 * Numbers typed by people or read from headers (docs/bad-input.md). Each is
 * 0, or -1 if malformed or outside [lo, hi]. None accepts a sign, blanks, a
 * suffix or an overflowing value.
 *   np_parse_u64        decimal digits only ("010" is ten, "0x5" is refused);
 *   np_parse_u64_hex    hex digits only, at most max_digits (a field documented as
 *                       hex of that width, e.g. a $readmemh @address);
 *   np_parse_u64_or_0x  decimal, or 0x followed by hex digits, for the options
 *                       documented so (sweep --z).
 */
int np_parse_u64(const char *s, uint64_t lo, uint64_t hi, uint64_t *out);
int np_parse_u64_hex(const char *s, unsigned max_digits, uint64_t lo, uint64_t hi, uint64_t *out);
int np_parse_u64_or_0x(const char *s, uint64_t lo, uint64_t hi, uint64_t *out);

/*
 * Progress on stderr: by default only when stderr is a terminal (one line,
 * rewritten a few times a second). `noisepipe --progress CMD` (or the option
 * anywhere after the command) forces it, as a line every 5 s when stderr is a
 * log; `--quiet` stops it. done/total in items; label e.g. "sweep".
 */
enum { NP_PROGRESS_AUTO = 0, NP_PROGRESS_ALWAYS = 1, NP_PROGRESS_NEVER = 2 };
void np_progress_set_mode(int mode);
typedef struct np_progress {
    const char *label;
    uint64_t total;
    double start, last;
    int tty; /* 0: silent, 1: terminal line, 2: log lines */
} np_progress;

void np_progress_start(np_progress *p, const char *label, uint64_t total);
void np_progress_update(np_progress *p, uint64_t done);
void np_progress_end(np_progress *p);

/* Monotonic wall-clock seconds. */
double np_now(void);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_COMMON_H */
