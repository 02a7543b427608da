/* SPDX-License-Identifier: MIT */
/*
 * np_outfile.h - the one way every command writes an output file (-o), and
 * what happens to unfinished outputs when the run is interrupted.
 *
 * What is at the path decides how it is written (docs/bad-input.md):
 *
 *   path                      written how
 *   ------------------------  -----------------------------------------------
 *   NULL or "-"               standard output, streamed
 *   nothing there, or a       a temporary PATH.tmpPID in the same folder,
 *     regular file            renamed over PATH when complete (atomic: a
 *                             reader never sees half a file; a failed or
 *                             interrupted run leaves PATH as it was)
 *   a FIFO or a character     opened and streamed to directly (a simulator
 *     device                  reading a pipe, /dev/null, /dev/stdout)
 *   a symbolic link           resolved; its final target is written by the
 *                             rules above (the link itself stays a link)
 *   a directory, socket or    refused: -1 with a message naming the path
 *     block device
 *
 * Every write error (a full disk, /dev/full, a closed pipe) is reported by
 * np_outfile_close, never lost: the commands turn it into exit status 2.
 *
 * Interruption: np_interrupt_install() catches SIGINT, SIGTERM and SIGHUP.
 * The handler removes every temporary file still open (np_outfile keeps a
 * table of them), writes the note set by np_interrupt_note() (what was kept
 * and how to resume) and ends the process with 128 + the signal number
 * (130 for SIGINT, 143 for SIGTERM). Journals stay consistent because they
 * are append-only, line by line, each line checked on resume.
 */
#ifndef NP_OUTFILE_H
#define NP_OUTFILE_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { NP_OUTFILE_PATH_MAX = 4096 };

typedef struct np_outfile {
    FILE *f;                               /* write here */
    char path[NP_OUTFILE_PATH_MAX];        /* as given ("-" for standard output) */
    char target[NP_OUTFILE_PATH_MAX];      /* what is written: path, or a link's final target */
    char tmp[NP_OUTFILE_PATH_MAX + 32];    /* the temporary file when atomic, else "" */
    int atomic;                            /* 1: temporary + rename */
    int is_stdout;                         /* 1: standard output (never closed) */
    int slot;                              /* index in the interrupt table, or -1 */
    char err[NP_OUTFILE_PATH_MAX + 256];   /* message after a -1 */
} np_outfile;

/* Open path for writing ("w" or "wb"); 0, or -1 with o->err naming the path. */
int np_outfile_open(np_outfile *o, const char *path, const char *mode);

/*
 * Finish: flush and check for write errors; with commit != 0 rename the
 * temporary file into place, with commit == 0 (an aborted run) remove it.
 * 0, or -1 with o->err ("PATH: write error: No space left on device").
 */
int np_outfile_close(np_outfile *o, int commit);

/* Catch SIGINT/SIGTERM/SIGHUP as above (idempotent). */
void np_interrupt_install(void);

/*
 * The line the interrupt handler prints (after "noisepipe: interrupted: "),
 * e.g. "journal sweep.jnl keeps 12 finished blocks; run again with --resume".
 * Copied into a static buffer; NULL clears it.
 */
void np_interrupt_note(const char *note);

/* Register or forget a temporary file the handler must remove (np_outfile does this itself). */
int np_interrupt_track(const char *tmp_path);
void np_interrupt_untrack(int slot);

/*
 * Check standard output at the end of a command: 0, or -1 after a message on
 * stderr when anything written to it was lost (`verify > /dev/full`).
 */
int np_stdout_check(const char *cmd);

/* mkdir -p: dir and the folders above it that are missing. 0, or -1 with errno set. */
int np_mkdir_p(const char *dir);

/*
 * A new private folder "$TMPDIR/<stem>-XXXXXX" (/tmp when TMPDIR is unset or
 * empty) into dir[size]; 0, or -1 with a message naming the parent in err.
 */
int np_tempdir(char *dir, size_t size, const char *stem, char *err, size_t errlen);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_OUTFILE_H */
