/* SPDX-License-Identifier: MIT */
/*
 * np_jfile.h - the journal file: an append-only text file of checksummed
 * lines, bound to what it describes, that a killed process leaves readable.
 * The exhaustive sweep (np_sweep.h), the adversarial search (np_search.h)
 * and the USB link's host (np_link.h) keep their journals in it;
 * docs/sweep.md, docs/search.md and docs/usb-protocol.md give their record
 * lines.
 *
 *   MAGIC                              the kind and format version, e.g.
 *                                      "noisepipe-sweep-journal 2" (no checksum:
 *                                      it is compared whole)
 *   KEY=VALUE *crc                     bindings: what the journal describes
 *   ...                                (unit=classic3, config=..., z=0x0000)
 *   RECORD TEXT *crc                   records, appended in the order they complete
 *   ...
 *
 * Every line after the first ends with " *" and the CRC-32 (np_crc32.h) of
 * the text before " *", as 8 lowercase hex digits. A binding is a line of the
 * header block whose first word holds a '='; the first line that is not one
 * starts the records, so a record's first word holds no '='.
 *
 * A record is one line, or several lines of which the last commits the
 * record (the caller's line handler says which). A write appends whole
 * records in one write(2); a kill can leave only a torn tail: a last line
 * without its newline, or lines of a record whose committing line is
 * missing. Reading:
 *   - the torn tail is not handed on as records and is reported in
 *     info->torn_bytes; resuming cuts it off with a note on stderr;
 *   - a whole line whose checksum fails is refused with its line number (a
 *     tampered file or a bad disk: nothing after it can be trusted, so it is
 *     not skipped);
 *   - the bindings are checked against the caller's, key by key: the first
 *     expected binding that is missing or has another value is named, and so
 *     is a binding the caller does not know.
 */
#ifndef NP_JFILE_H
#define NP_JFILE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_JFILE_TEXT_MAX = 1024,   /* a line's text, without " *crc" and newline, at most */
    NP_JFILE_MAX_BINDINGS = 16
};

/* Results (negative: an error, message in err). */
enum {
    NP_JFILE_OK = 0,
    NP_JFILE_BAD = -1,      /* I/O error, not a journal, damaged or malformed line */
    NP_JFILE_MISSING = -2,  /* np_jfile_read/resume: the file does not exist */
    NP_JFILE_EXISTS = -3,   /* np_jfile_create without replace: the file exists */
    NP_JFILE_MISMATCH = -4  /* the bindings are not the caller's */
};

/* A line handler's verdict on a record line. */
enum {
    NP_JFILE_OPEN = 0,  /* the line belongs to a record that a later line commits */
    NP_JFILE_COMMIT = 1 /* the line ends a record */
};

typedef struct np_jfile_info {
    unsigned n_bind;                                   /* the file's bindings ... */
    char bind[NP_JFILE_MAX_BINDINGS][NP_JFILE_TEXT_MAX]; /* ... "KEY=VALUE", in file order */
    uint64_t lines;       /* whole lines read, the first one included */
    uint64_t records;     /* records committed */
    uint64_t good_end;    /* bytes up to the end of the last committed record (or the header) */
    uint64_t torn_bytes;  /* bytes after good_end: the torn tail */
} np_jfile_info;

/* A run's bindings, built with np_jfile_bind: ptr[0..n) is what np_jfile_create/read take. */
typedef struct np_jfile_binds {
    unsigned n;
    char text[NP_JFILE_MAX_BINDINGS][NP_JFILE_TEXT_MAX];
    const char *ptr[NP_JFILE_MAX_BINDINGS];
} np_jfile_binds;

/* No bindings yet. */
void np_jfile_binds_init(np_jfile_binds *b);

/* Add the binding "KEY=VALUE" that fmt formats. 0, or -1 (no room, too long, not KEY=VALUE). */
int np_jfile_bind(np_jfile_binds *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The value of binding key in info, or NULL. */
const char *np_jfile_binding(const np_jfile_info *info, const char *key);

/*
 * Called for each record line, text without " *crc" (the handler may modify
 * it), lineno counting from 1 at the magic line. Returns NP_JFILE_OPEN,
 * NP_JFILE_COMMIT, or -1 with a message in err (the reader prefixes
 * "PATH:LINE: ").
 */
typedef int (*np_jfile_line_fn)(void *ctx, const np_jfile_info *info, char *text, uint64_t lineno,
                                char *err, size_t errlen);

typedef struct np_jfile {
    int fd;               /* -1: not open */
    char path[4096];
    char *pend;           /* lines of the record being appended */
    size_t pend_len, pend_cap;
    double last_sync;     /* np_now() of the last sync */
    uint64_t syncs;
} np_jfile;

/*
 * Read and check the journal at path without changing it: the first line
 * must be magic, the bindings those of bind[0..n_bind) ("KEY=VALUE" each;
 * bind NULL: not checked, the file's are in info), every record line is
 * handed to fn (NULL: each line is a record). NP_JFILE_OK, or a negative
 * result with a message in err.
 */
int np_jfile_read(const char *path, const char *magic, const char *const *bind, unsigned n_bind,
                  np_jfile_line_fn fn, void *ctx, np_jfile_info *info, char *err, size_t errlen);

/*
 * np_jfile_read with bindings checked, then open the journal for appending:
 * a torn tail is cut off, with a note on stderr. NP_JFILE_OK (jf open), or
 * a negative result with a message in err (jf closed).
 */
int np_jfile_resume(np_jfile *jf, const char *path, const char *magic, const char *const *bind,
                    unsigned n_bind, np_jfile_line_fn fn, void *ctx, np_jfile_info *info, char *err,
                    size_t errlen);

/*
 * A run's journal (the sweep's, the search's): with resume, np_jfile_resume,
 * a missing file started afresh; without, np_jfile_create of a file that
 * must not exist. The messages name the file and say what to do: an
 * existing file without resume ("pass --resume to continue it, or remove
 * it"), bindings of another run (": not resuming (use another journal
 * file)" after the binding named). 0 (jf open), or -1 with err (jf closed).
 */
int np_jfile_open_run(np_jfile *jf, const char *path, const char *magic, const np_jfile_binds *b,
                      int resume, np_jfile_line_fn fn, void *ctx, char *err, size_t errlen);

/*
 * Start a journal: magic and bindings, written and synced under a temporary
 * name and then published at path in one step (link(2), or rename(2) with
 * replace), so a kill leaves no journal or a whole header, never an empty
 * file. replace: replace an existing file (the caller checked it may); else
 * an existing file is NP_JFILE_EXISTS and left alone.
 */
int np_jfile_create(np_jfile *jf, const char *path, const char *magic, const char *const *bind,
                    unsigned n_bind, int replace, char *err, size_t errlen);

/* jf closed, nothing pending: a journal that lives in memory only (np_jfile_commit does nothing). */
void np_jfile_none(np_jfile *jf);

/* Format one line of the record being appended (kept until np_jfile_commit). 0, or -1 (too long, no memory). */
int np_jfile_add(np_jfile *jf, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Drop the pending lines (after an np_jfile_add that failed). */
void np_jfile_discard(np_jfile *jf);

/*
 * Append the pending lines in one write(2), then fdatasync when sync is set.
 * 0, or -1 with err. The pending lines are dropped either way.
 */
int np_jfile_commit(np_jfile *jf, int sync, char *err, size_t errlen);

/* fdatasync now. 0, or -1 with err. */
int np_jfile_sync(np_jfile *jf, char *err, size_t errlen);

/* Close (no sync: the caller syncs what must be durable). 0, or -1 when close(2) failed. */
int np_jfile_close(np_jfile *jf);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_JFILE_H */
