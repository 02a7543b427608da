/* SPDX-License-Identifier: MIT */
/* Output files and interruption (np_outfile.h). */
#include "np_outfile.h"
#include "np_common.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* --- The table of temporary files the interrupt handler removes --- */

enum { N_SLOTS = 32, NOTE_MAX = 1024 };
static char slot_path[N_SLOTS][NP_OUTFILE_PATH_MAX + 32];
static volatile sig_atomic_t slot_used[N_SLOTS];
/* Two note buffers: np_interrupt_note writes the one the handler is not reading, then makes it
 * current with one store of note_cur (-1: no note). A signal that lands while a note is being
 * written prints the previous one, whole: with one buffer, emptied while it was rewritten, a
 * SIGINT in that window printed no note at all (usb.interrupt failed so once under load). */
static char note_buf[2][NOTE_MAX];
static volatile sig_atomic_t note_cur = -1;

int np_interrupt_track(const char *tmp_path)
{
    if (strlen(tmp_path) >= sizeof slot_path[0])
        return -1;
    for (int i = 0; i < N_SLOTS; i++)
        if (!slot_used[i]) {
            memcpy(slot_path[i], tmp_path, strlen(tmp_path) + 1);
            slot_used[i] = 1; /* after the path is complete: the handler reads it only then */
            return i;
        }
    return -1; /* full: the file is still written correctly, only not removed on a signal */
}

void np_interrupt_untrack(int slot)
{
    if (slot >= 0 && slot < N_SLOTS)
        slot_used[slot] = 0;
}

void np_interrupt_note(const char *note)
{
    if (!note) {
        note_cur = -1;
        return;
    }
    int next = note_cur == 0 ? 1 : 0;
    snprintf(note_buf[next], sizeof note_buf[next], "%s", note);
    atomic_signal_fence(memory_order_seq_cst); /* the text is whole before it becomes current */
    note_cur = next;
}

static void put(const char *s) { ssize_t r = write(2, s, strlen(s)); (void)r; }

static void put_uint(unsigned v)
{
    char b[16];
    int i = (int)sizeof b;
    b[--i] = '\0';
    do {
        b[--i] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v && i > 0);
    put(b + i);
}

/* Async-signal-safe: unlink, write and _exit only. */
static void on_signal(int sig)
{
    unsigned removed = 0;
    for (int i = 0; i < N_SLOTS; i++)
        if (slot_used[i] && unlink(slot_path[i]) == 0)
            removed++;
    put("\nnoisepipe: interrupted by ");
    put(sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP");
    put("; removed ");
    put_uint(removed);
    put(" unfinished output file(s); no output was replaced");
    int cur = note_cur;
    if (cur == 0 || cur == 1) {
        put("; ");
        put(note_buf[cur]);
    }
    put("\n");
    _exit(128 + sig);
}

void np_interrupt_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigfillset(&sa.sa_mask); /* one handler at a time */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
}

/* --- Output files --- */

static int fail(np_outfile *o, const char *what)
{
    snprintf(o->err, sizeof o->err, "%.4000s: %.200s", o->path, what);
    return -1;
}

/*
 * Follow symbolic links from o->path to the final target (which need not
 * exist yet); o->target gets it. 0, or -1 with o->err.
 */
static int resolve(np_outfile *o)
{
    char cur[NP_OUTFILE_PATH_MAX];
    snprintf(cur, sizeof cur, "%s", o->path);
    for (int hop = 0; hop < 40; hop++) {
        struct stat st;
        if (lstat(cur, &st) != 0 || !S_ISLNK(st.st_mode)) {
            snprintf(o->target, sizeof o->target, "%s", cur);
            return 0;
        }
        char link[NP_OUTFILE_PATH_MAX];
        ssize_t n = readlink(cur, link, sizeof link - 1);
        if (n < 0)
            return fail(o, strerror(errno));
        link[n] = '\0';
        if (link[0] == '/') {
            snprintf(cur, sizeof cur, "%s", link);
        } else {
            /* relative to the folder that holds the link */
            char *slash = strrchr(cur, '/');
            size_t dir = slash ? (size_t)(slash - cur) + 1u : 0u;
            if (dir + (size_t)n >= sizeof cur)
                return fail(o, "symbolic link target too long");
            memmove(cur + dir, link, (size_t)n + 1u);
        }
    }
    return fail(o, "too many levels of symbolic links");
}

int np_outfile_open(np_outfile *o, const char *path, const char *mode)
{
    memset(o, 0, sizeof *o);
    o->slot = -1;
    if (!path || strcmp(path, "-") == 0) {
        snprintf(o->path, sizeof o->path, "-");
        o->f = stdout;
        o->is_stdout = 1;
        return 0;
    }
    if (strlen(path) >= sizeof o->path) {
        snprintf(o->err, sizeof o->err, "%.64s...: path too long", path);
        return -1;
    }
    snprintf(o->path, sizeof o->path, "%s", path);
    if (resolve(o) != 0)
        return -1;
    struct stat st;
    int exists = stat(o->target, &st) == 0;
    if (!exists && errno != ENOENT)
        return fail(o, strerror(errno));
    if (exists && (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode))) {
        /* Stream to it: a pipe's reader or a device sees every byte as it is written. */
        int fd = open(o->target, O_WRONLY | O_CLOEXEC);
        if (fd < 0 || !(o->f = fdopen(fd, mode))) {
            int e = errno;
            if (fd >= 0)
                close(fd);
            return fail(o, strerror(e));
        }
        return 0;
    }
    if (exists && !S_ISREG(st.st_mode))
        return fail(o, S_ISDIR(st.st_mode)    ? "is a directory; give a file name"
                       : S_ISSOCK(st.st_mode) ? "is a socket; give a file name"
                       : S_ISBLK(st.st_mode)  ? "is a block device; refusing to write to it"
                                              : "is not a regular file, FIFO or character device");
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp%ld", o->target, (long)getpid());
    o->atomic = 1;
    int fd = open(o->tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) {
        int e = errno;
        o->tmp[0] = '\0';
        o->atomic = 0;
        return fail(o, e == ENOENT ? "cannot create: the folder does not exist" : strerror(e));
    }
    o->slot = np_interrupt_track(o->tmp);
    if (!(o->f = fdopen(fd, mode))) {
        int e = errno;
        close(fd);
        np_outfile_close(o, 0);
        return fail(o, strerror(e));
    }
    setvbuf(o->f, NULL, _IOFBF, (size_t)1 << 16);
    return 0;
}

int np_outfile_close(np_outfile *o, int commit)
{
    int rc = 0;
    if (o->is_stdout) {
        if (fflush(stdout) != 0 || ferror(stdout))
            rc = fail(o, "write error on standard output");
        o->f = NULL;
        return rc;
    }
    if (o->f) {
        int bad = ferror(o->f);
        int e = errno;
        if (fflush(o->f) != 0) {
            bad = 1;
            e = errno;
        }
        if (fclose(o->f) != 0 && !bad) {
            bad = 1;
            e = errno;
        }
        o->f = NULL;
        if (bad) {
            char m[160];
            snprintf(m, sizeof m, "write error: %s", strerror(e));
            rc = fail(o, m);
        }
    }
    if (o->atomic) {
        if (commit && rc == 0 && rename(o->tmp, o->target) != 0) {
            char m[200];
            snprintf(m, sizeof m, "cannot rename the finished file into place: %s", strerror(errno));
            rc = fail(o, m);
        }
        if (!commit || rc != 0)
            unlink(o->tmp);
        np_interrupt_untrack(o->slot);
        o->slot = -1;
        o->atomic = 0;
    }
    return rc;
}

int np_stdout_check(const char *cmd)
{
    if (fflush(stdout) == 0 && !ferror(stdout))
        return 0;
    np_err(cmd, "standard output: write error: %s", strerror(errno));
    return -1;
}

int np_mkdir_p(const char *dir)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return -1;
            *p = '/';
        }
    if (mkdir(buf, 0777) != 0 && errno != EEXIST)
        return -1;
    return 0;
}

int np_tempdir(char *dir, size_t size, const char *stem, char *err, size_t errlen)
{
    const char *tmp = getenv("TMPDIR");
    if (!tmp || !*tmp)
        tmp = "/tmp";
    if ((size_t)snprintf(dir, size, "%s/%s-XXXXXX", tmp, stem) >= size || !mkdtemp(dir)) {
        snprintf(err, errlen, "cannot create a temporary folder in %s: %s", tmp, strerror(errno));
        return -1;
    }
    return 0;
}
