/* SPDX-License-Identifier: MIT */
/* np_cli.h - what every noisepipe command shares: exit codes, messages, progress. */
#ifndef NP_CLI_H
#define NP_CLI_H

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

/* Parse a whole decimal or 0x-hex unsigned number; 0, or -1 if malformed/out of [lo, hi]. */
int np_parse_u64(const char *s, uint64_t lo, uint64_t hi, uint64_t *out);

/*
 * Progress line on stderr, only when stderr is a terminal; rate-limited to
 * a few updates per second. done/total in items; label e.g. "sweep".
 */
typedef struct np_progress {
    const char *label;
    uint64_t total;
    double start, last;
    int tty;
} np_progress;

void np_progress_start(np_progress *p, const char *label, uint64_t total);
void np_progress_update(np_progress *p, uint64_t done);
void np_progress_end(np_progress *p);

/* Monotonic wall-clock seconds. */
double np_now(void);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_CLI_H */
