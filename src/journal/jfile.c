/* SPDX-License-Identifier: MIT */
/* The journal file (np_jfile.h): checksummed lines, bindings, torn tails. */
#include "np_jfile.h"
#include "np_outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "np_common.h"
#include "np_crc32.h"

enum { CRC_SUFFIX = 11 }; /* " *" + 8 hex digits + newline */

/* The message into err; returns rc (np_errf with a result other than -1). */
#define fail(err, errlen, rc, ...) (np_errf((err), (errlen), __VA_ARGS__), (rc))

/* Split "TEXT *crc" and check the CRC: 0 (TEXT left NUL-terminated in line), or -1. */
static int line_crc_ok(char *line)
{
    size_t n = strlen(line);
    if (n < CRC_SUFFIX - 1u || line[n - 10u] != ' ' || line[n - 9u] != '*')
        return -1;
    uint32_t c = 0;
    for (const char *p = line + n - 8u; *p; p++) {
        int d = *p >= '0' && *p <= '9' ? *p - '0' : *p >= 'a' && *p <= 'f' ? *p - 'a' + 10 : -1;
        if (d < 0)
            return -1;
        c = c << 4 | (uint32_t)d;
    }
    line[n - 10u] = '\0';
    return np_crc32(0, line, n - 10u) == c ? 0 : -1;
}

/* A binding line: its first word holds a '='. */
static int is_binding(const char *text)
{
    const char *eq = strchr(text, '=');
    const char *sp = strchr(text, ' ');
    return eq && eq != text && (!sp || eq < sp);
}

/* Bytes of the key of "KEY=VALUE" (the whole text when it has no '='). */
static size_t key_len(const char *b)
{
    const char *eq = strchr(b, '=');
    return eq ? (size_t)(eq - b) : strlen(b);
}

const char *np_jfile_binding(const np_jfile_info *info, const char *key)
{
    size_t n = strlen(key);
    for (unsigned k = 0; k < info->n_bind; k++)
        if (key_len(info->bind[k]) == n && memcmp(info->bind[k], key, n) == 0)
            return info->bind[k] + n + 1u;
    return NULL;
}

void np_jfile_binds_init(np_jfile_binds *b) { b->n = 0; }

int np_jfile_bind(np_jfile_binds *b, const char *fmt, ...)
{
    if (b->n == NP_JFILE_MAX_BINDINGS)
        return -1;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(b->text[b->n], NP_JFILE_TEXT_MAX, fmt, ap);
    va_end(ap);
    if (n < 0 || n >= NP_JFILE_TEXT_MAX || !is_binding(b->text[b->n]))
        return -1;
    b->ptr[b->n] = b->text[b->n];
    b->n++;
    return 0;
}

/* The file's bindings against bind[0..n_bind): the first difference, named. */
static int check_bindings(const char *path, const np_jfile_info *info, const char *const *bind,
                          unsigned n_bind, char *err, size_t errlen)
{
    for (unsigned k = 0; k < n_bind; k++) {
        size_t kl = key_len(bind[k]);
        char key[64];
        snprintf(key, sizeof key, "%.*s", (int)(kl < sizeof key ? kl : sizeof key - 1u), bind[k]);
        const char *v = np_jfile_binding(info, key);
        if (!v)
            return fail(err, errlen, NP_JFILE_MISMATCH, "journal %s binds no %s, this run is '%s'",
                        path, key, bind[k]);
        if (strcmp(v, bind[k] + kl + 1u) != 0)
            return fail(err, errlen, NP_JFILE_MISMATCH,
                        "journal %s was written for '%s=%s', this run is '%s'", path, key, v,
                        bind[k]);
    }
    for (unsigned f = 0; f < info->n_bind; f++) {
        unsigned k = 0;
        while (k < n_bind && (key_len(bind[k]) != key_len(info->bind[f]) ||
                              memcmp(bind[k], info->bind[f], key_len(bind[k])) != 0))
            k++;
        if (k == n_bind)
            return fail(err, errlen, NP_JFILE_MISMATCH,
                        "journal %s was written for '%s', which this run does not bind", path,
                        info->bind[f]);
    }
    return NP_JFILE_OK;
}

/* The whole file, NUL-terminated, in *text. */
static int slurp(const char *path, char **text, size_t *size, char *err, size_t errlen)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return fail(err, errlen, errno == ENOENT ? NP_JFILE_MISSING : NP_JFILE_BAD,
                    "cannot read journal %s: %s", path, strerror(errno));
    struct stat sb;
    if (fstat(fd, &sb) != 0) {
        close(fd);
        return fail(err, errlen, NP_JFILE_BAD, "cannot read journal %s: %s", path, strerror(errno));
    }
    size_t n = (size_t)sb.st_size, got = 0;
    char *t = malloc(n + 1u);
    if (!t) {
        close(fd);
        return fail(err, errlen, NP_JFILE_BAD, "cannot read journal %s: out of memory", path);
    }
    while (got < n) {
        ssize_t r = read(fd, t + got, n - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0) {
            int e = errno;
            free(t);
            close(fd);
            return fail(err, errlen, NP_JFILE_BAD, "cannot read journal %s: %s", path,
                        r < 0 ? strerror(e) : "short read");
        }
        got += (size_t)r;
    }
    close(fd);
    t[n] = '\0';
    *text = t;
    *size = n;
    return NP_JFILE_OK;
}

/* The first line is not magic: an older format of the same kind, or not a journal of this kind. */
static int bad_magic(const char *path, const char *line, const char *magic, char *err, size_t errlen)
{
    const char *sp = strrchr(magic, ' ');
    size_t kind = sp ? (size_t)(sp - magic) + 1u : 0u;
    if (kind && strncmp(line, magic, kind) == 0)
        return fail(err, errlen, NP_JFILE_BAD,
                    "journal %s has format '%.80s'; this noisepipe reads '%s' (start a new journal)",
                    path, line, magic);
    return fail(err, errlen, NP_JFILE_BAD, "%s is not a journal of this kind (its first line is not '%s')",
                path, magic);
}

int np_jfile_read(const char *path, const char *magic, const char *const *bind, unsigned n_bind,
                  np_jfile_line_fn fn, void *ctx, np_jfile_info *info, char *err, size_t errlen)
{
    memset(info, 0, sizeof *info);
    char *text = NULL;
    size_t size = 0;
    int rc = slurp(path, &text, &size, err, errlen);
    if (rc != NP_JFILE_OK)
        return rc;
    int header = 1;
    size_t at = 0;
    while (at < size && rc == NP_JFILE_OK) {
        char *nl = memchr(text + at, '\n', size - at);
        if (!nl)
            break; /* a torn last line */
        *nl = '\0';
        char *line = text + at;
        uint64_t lineno = ++info->lines;
        at = (size_t)(nl - text) + 1u;
        if (lineno == 1) {
            if (strcmp(line, magic) != 0)
                rc = bad_magic(path, line, magic, err, errlen);
            info->good_end = at;
            continue;
        }
        if (line_crc_ok(line) != 0) {
            rc = fail(err, errlen, NP_JFILE_BAD,
                      "%s:%llu: malformed or damaged line (bad checksum): the journal cannot be trusted",
                      path, (unsigned long long)lineno);
            break;
        }
        if (header && is_binding(line)) {
            if (info->n_bind == NP_JFILE_MAX_BINDINGS)
                rc = fail(err, errlen, NP_JFILE_BAD, "%s:%llu: more than %d bindings", path,
                          (unsigned long long)lineno, NP_JFILE_MAX_BINDINGS);
            else
                snprintf(info->bind[info->n_bind++], NP_JFILE_TEXT_MAX, "%s", line);
            info->good_end = at;
            continue;
        }
        if (header) {
            header = 0;
            if (bind && (rc = check_bindings(path, info, bind, n_bind, err, errlen)) != NP_JFILE_OK)
                break;
        }
        char msg[512];
        int v = fn ? fn(ctx, info, line, lineno, msg, sizeof msg) : NP_JFILE_COMMIT;
        if (v < 0) {
            rc = fail(err, errlen, NP_JFILE_BAD, "%s:%llu: %s", path, (unsigned long long)lineno, msg);
            break;
        }
        if (v == NP_JFILE_COMMIT) {
            info->records++;
            info->good_end = at;
        }
    }
    if (rc == NP_JFILE_OK && info->lines == 0)
        rc = fail(err, errlen, NP_JFILE_BAD, "journal %s is empty%s", path,
                  size ? " but for a torn first line" : "");
    if (rc == NP_JFILE_OK && header && bind)
        rc = check_bindings(path, info, bind, n_bind, err, errlen);
    info->torn_bytes = size - info->good_end;
    free(text);
    return rc;
}

void np_jfile_none(np_jfile *jf)
{
    memset(jf, 0, sizeof *jf);
    jf->fd = -1;
}

static int open_for(np_jfile *jf, const char *path, int flags, char *err, size_t errlen)
{
    np_jfile_none(jf);
    if (strlen(path) >= sizeof jf->path)
        return fail(err, errlen, NP_JFILE_BAD, "journal path too long");
    snprintf(jf->path, sizeof jf->path, "%s", path);
    jf->fd = open(path, flags | O_CLOEXEC, 0666);
    if (jf->fd < 0) {
        if (errno == EEXIST)
            return fail(err, errlen, NP_JFILE_EXISTS, "journal %s exists", path);
        return fail(err, errlen, NP_JFILE_BAD, "cannot %s journal %s: %s",
                    flags & O_CREAT ? "create" : "append to", path, strerror(errno));
    }
    jf->last_sync = np_now();
    return NP_JFILE_OK;
}

int np_jfile_resume(np_jfile *jf, const char *path, const char *magic, const char *const *bind,
                    unsigned n_bind, np_jfile_line_fn fn, void *ctx, np_jfile_info *info, char *err,
                    size_t errlen)
{
    np_jfile_none(jf);
    int rc = np_jfile_read(path, magic, bind, n_bind, fn, ctx, info, err, errlen);
    if (rc == NP_JFILE_OK)
        rc = open_for(jf, path, O_WRONLY | O_APPEND, err, errlen);
    if (rc != NP_JFILE_OK)
        return rc;
    if (info->torn_bytes) {
        fprintf(stderr,
                "noisepipe: journal %s: dropping an incomplete last record (%llu bytes), a write "
                "cut short; it is done again\n",
                path, (unsigned long long)info->torn_bytes);
        if (ftruncate(jf->fd, (off_t)info->good_end) != 0) {
            rc = fail(err, errlen, NP_JFILE_BAD, "%s: cannot cut off the torn last record: %s", path,
                      strerror(errno));
            np_jfile_close(jf);
        }
    }
    return rc;
}

int np_jfile_open_run(np_jfile *jf, const char *path, const char *magic, const np_jfile_binds *b,
                      int resume, np_jfile_line_fn fn, void *ctx, char *err, size_t errlen)
{
    int rc = NP_JFILE_MISSING;
    np_jfile_none(jf);
    if (resume) {
        np_jfile_info *info = malloc(sizeof *info); /* 16 KiB of bindings: not on the stack */
        if (!info)
            return np_errf(err, errlen, "out of memory");
        rc = np_jfile_resume(jf, path, magic, b->ptr, b->n, fn, ctx, info, err, errlen);
        free(info);
        if (rc == NP_JFILE_MISMATCH) {
            size_t n = strlen(err);
            snprintf(err + n, errlen - n, ": not resuming (use another journal file)");
        }
    }
    if (rc == NP_JFILE_MISSING) {
        rc = np_jfile_create(jf, path, magic, b->ptr, b->n, 0, err, errlen);
        if (rc == NP_JFILE_EXISTS)
            np_errf(err, errlen, "journal %s exists: pass --resume to continue it, or remove it", path);
    }
    return rc == NP_JFILE_OK ? 0 : -1;
}

/*
 * Creation is atomic: the header is written and synced under a temporary
 * name beside the journal, then published at path with link(2) (which, like
 * O_EXCL, fails when path exists) or, with replace, rename(2). A kill at any
 * moment leaves either no journal or one with its whole header, never an
 * empty or half-written one that a resume would refuse.
 */
int np_jfile_create(np_jfile *jf, const char *path, const char *magic, const char *const *bind,
                    unsigned n_bind, int replace, char *err, size_t errlen)
{
    char tmp[sizeof jf->path];
    if (strlen(path) + 24 >= sizeof tmp)
        return fail(err, errlen, NP_JFILE_BAD, "journal path too long");
    if (!replace && access(path, F_OK) == 0)
        return fail(err, errlen, NP_JFILE_EXISTS, "journal %s exists", path);
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
    int rc = open_for(jf, tmp, O_WRONLY | O_CREAT | O_APPEND | O_TRUNC, err, errlen);
    if (rc != NP_JFILE_OK)
        return rc;
    int slot = np_interrupt_track(tmp); /* removed if a signal ends the run right here */
    /* The magic line carries no checksum: add it whole, then strip the suffix. */
    if (np_jfile_add(jf, "%s", magic) != 0)
        goto bad;
    jf->pend_len -= CRC_SUFFIX;
    jf->pend[jf->pend_len++] = '\n';
    for (unsigned k = 0; k < n_bind; k++)
        if (!is_binding(bind[k]) || np_jfile_add(jf, "%s", bind[k]) != 0)
            goto bad;
    if (np_jfile_commit(jf, 1, err, errlen) != 0)
        goto fail_io;
    if (replace ? rename(tmp, path) != 0 : link(tmp, path) != 0) {
        int e = errno;
        np_interrupt_untrack(slot);
        np_jfile_close(jf);
        unlink(tmp);
        if (e == EEXIST)
            return fail(err, errlen, NP_JFILE_EXISTS, "journal %s exists", path);
        return fail(err, errlen, NP_JFILE_BAD, "cannot create journal %s: %s", path, strerror(e));
    }
    if (!replace)
        unlink(tmp);
    np_interrupt_untrack(slot);
    snprintf(jf->path, sizeof jf->path, "%s", path);
    return NP_JFILE_OK;
bad:
    np_interrupt_untrack(slot);
    np_jfile_close(jf);
    unlink(tmp);
    return fail(err, errlen, NP_JFILE_BAD, "cannot write journal %s: bad or too long header line", path);
fail_io:
    np_interrupt_untrack(slot);
    np_jfile_close(jf);
    unlink(tmp);
    return NP_JFILE_BAD;
}

int np_jfile_add(np_jfile *jf, const char *fmt, ...)
{
    char line[NP_JFILE_TEXT_MAX + CRC_SUFFIX + 1];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(line, NP_JFILE_TEXT_MAX + 1, fmt, ap);
    va_end(ap);
    if (n < 0 || n > NP_JFILE_TEXT_MAX || memchr(line, '\n', (size_t)n))
        return -1;
    n += snprintf(line + n, CRC_SUFFIX + 1, " *%08x\n", (unsigned)np_crc32(0, line, (size_t)n));
    if (jf->pend_len + (size_t)n > jf->pend_cap) {
        size_t cap = jf->pend_cap ? 2 * jf->pend_cap : 4096;
        while (cap < jf->pend_len + (size_t)n)
            cap *= 2;
        char *t = realloc(jf->pend, cap);
        if (!t)
            return -1;
        jf->pend = t;
        jf->pend_cap = cap;
    }
    memcpy(jf->pend + jf->pend_len, line, (size_t)n);
    jf->pend_len += (size_t)n;
    return 0;
}

void np_jfile_discard(np_jfile *jf) { jf->pend_len = 0; }

int np_jfile_commit(np_jfile *jf, int sync, char *err, size_t errlen)
{
    const char *p = jf->pend;
    size_t n = jf->pend_len;
    jf->pend_len = 0;
    if (jf->fd < 0)
        return 0;
    /* One write: a kill leaves either the whole record or a torn tail. */
    while (n > 0) {
        ssize_t w = write(jf->fd, p, n);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            return fail(err, errlen, -1, "cannot write journal %s: %s", jf->path, strerror(errno));
        }
        p += w;
        n -= (size_t)w;
    }
    return sync ? np_jfile_sync(jf, err, errlen) : 0;
}

int np_jfile_sync(np_jfile *jf, char *err, size_t errlen)
{
    if (jf->fd < 0)
        return 0;
    if (fdatasync(jf->fd) != 0)
        return fail(err, errlen, -1, "cannot sync journal %s: %s", jf->path, strerror(errno));
    jf->last_sync = np_now();
    jf->syncs++;
    return 0;
}

int np_jfile_close(np_jfile *jf)
{
    int rc = 0;
    if (jf->fd >= 0)
        rc = close(jf->fd) == 0 ? 0 : -1;
    jf->fd = -1;
    free(jf->pend);
    jf->pend = NULL;
    jf->pend_len = jf->pend_cap = 0;
    return rc;
}
