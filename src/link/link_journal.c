/* SPDX-License-Identifier: MIT */
/*
 * link_journal.c - the host's journal of verified ranges (docs/usb-protocol.md,
 * section 11; the format in np_link.h): E and R records in a journal file
 * (np_jfile.h) bound to the unit, its configuration and the vectors' hash.
 */
#include "np_link.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "np_common.h"

static const char journal_magic[] = "# noisepipe stream journal 2";
enum { MAX_BINDINGS = 6 };

static void bit_set(uint8_t *bm, uint64_t i) { bm[i >> 3] = (uint8_t)(bm[i >> 3] | 1u << (i & 7u)); }

/* Append f to the growing list *a of *n entries (room for *cap). 0, or -1 when out of memory. */
static int fail_push(np_journal_fail **a, size_t *n, size_t *cap, const np_journal_fail *f)
{
    if (*n == *cap) {
        size_t c = *cap ? 2 * *cap : 64;
        np_journal_fail *t = realloc(*a, c * sizeof *t);
        if (!t)
            return -1;
        *a = t;
        *cap = c;
    }
    (*a)[(*n)++] = *f;
    return 0;
}

static int fail_add(np_journal *jn, const np_journal_fail *f)
{
    return fail_push(&jn->fails, &jn->n_fails, &jn->cap_fails, f);
}

static int parse_hex_u64(const char **s, uint64_t *v)
{
    char *end;
    while (**s == ' ')
        (*s)++;
    if (!**s)
        return -1;
    errno = 0;
    unsigned long long x = strtoull(*s, &end, 16);
    if (errno || end == *s || (*end && *end != ' '))
        return -1;
    *v = (uint64_t)x;
    *s = end;
    return 0;
}

/* What a journal of job j is bound to. */
typedef struct bindings {
    char text[MAX_BINDINGS][NP_JFILE_TEXT_MAX];
    const char *ptr[MAX_BINDINGS];
    unsigned n;
} bindings;

static void bindings_of(const np_link_job *j, const np_link_target *t, bindings *b)
{
    snprintf(b->text[0], NP_JFILE_TEXT_MAX, "unit=%s", j->unit->name);
    snprintf(b->text[1], NP_JFILE_TEXT_MAX, "config=%s", j->cfg_text);
    snprintf(b->text[2], NP_JFILE_TEXT_MAX, "count=%llu", (unsigned long long)j->n);
    snprintf(b->text[3], NP_JFILE_TEXT_MAX, "vectors=%016llx", (unsigned long long)j->hash);
    b->n = 4;
    if (t) {
        snprintf(b->text[4], NP_JFILE_TEXT_MAX, "size=%s", t->size);
        snprintf(b->text[5], NP_JFILE_TEXT_MAX, "target=%s", t->target);
        b->n = 6;
    }
    for (unsigned k = 0; k < b->n; k++)
        b->ptr[k] = b->text[k];
}

/* Reading back: E lines wait for the R line that commits them. */
typedef struct reader {
    np_journal *jn;
    np_journal_fail *pend;
    size_t n_pend, cap_pend;
} reader;

static int record_line(void *ctx, const np_jfile_info *info, char *line, uint64_t lineno, char *err,
                       size_t errlen)
{
    reader *rd = ctx;
    np_journal *jn = rd->jn;
    const char *s = line + 1;
    (void)lineno;
    if (!jn->checked) { /* a probe of a journal of any vectors: sized by its own count */
        const char *c = np_jfile_binding(info, "count");
        uint64_t n;
        if (!c || np_parse_u64(c, 0, UINT64_MAX, &n) != 0)
            return np_errf(err, errlen, "no usable count= binding");
        jn->n = n;
        jn->checked = calloc((size_t)(n / 8u + 1u), 1);
        if (!jn->checked)
            return np_errf(err, errlen, "out of memory");
    }
    if (line[0] == 'E') {
        np_journal_fail f;
        memset(&f, 0, sizeof f);
        if (parse_hex_u64(&s, &f.index) != 0)
            return np_errf(err, errlen, "malformed E line");
        for (unsigned k = 0; k < NP_UNIT_MAX_FIELDS && *s; k++)
            if (parse_hex_u64(&s, &f.got[k]) != 0)
                break;
        if (fail_push(&rd->pend, &rd->n_pend, &rd->cap_pend, &f) != 0)
            return np_errf(err, errlen, "out of memory");
        return NP_JFILE_OPEN;
    }
    if (line[0] == 'R') {
        uint64_t first, count, errs;
        if (parse_hex_u64(&s, &first) != 0 || parse_hex_u64(&s, &count) != 0 ||
            parse_hex_u64(&s, &errs) != 0 || count == 0 || first >= jn->n ||
            count > jn->n - first || errs != rd->n_pend)
            return np_errf(err, errlen, "malformed R line");
        for (uint64_t i = first; i < first + count; i++) {
            if (np_journal_has(jn, i))
                return np_errf(err, errlen, "vector %llu is journaled twice: the journal cannot be trusted",
                            (unsigned long long)i);
            bit_set(jn->checked, i);
        }
        for (size_t k = 0; k < rd->n_pend; k++)
            if (rd->pend[k].index < first || rd->pend[k].index - first >= count ||
                fail_add(jn, &rd->pend[k]) != 0)
                return np_errf(err, errlen, "E line outside its range");
        jn->n_checked += count;
        jn->n_errors += errs;
        rd->n_pend = 0;
        return NP_JFILE_COMMIT;
    }
    return np_errf(err, errlen, "unexpected line");
}

/* Read the journal at path into jn through record_line: np_jfile_read or np_jfile_resume. */
static int read_journal(np_journal *jn, const char *path, const bindings *b, int resume, char *err,
                        size_t errlen)
{
    np_jfile_info *info = malloc(sizeof *info);
    if (!info)
        return np_errf(err, errlen, "out of memory");
    reader rd = { jn, NULL, 0, 0 };
    int rc = resume ? np_jfile_resume(&jn->file, path, journal_magic, b->ptr, b->n, record_line,
                                      &rd, info, err, errlen)
                    : np_jfile_read(path, journal_magic, NULL, 0, record_line, &rd, info, err, errlen);
    free(rd.pend);
    free(info);
    return rc;
}

/*
 * Not resuming over an existing file: never thrown away without force (it
 * may hold verified vectors of these or other vectors, of this target or
 * another), and never anything that is not a usable journal.
 */
static int fresh_start_ok(const char *path, int force, char *err, size_t errlen)
{
    struct stat sb;
    if (stat(path, &sb) != 0 || (S_ISREG(sb.st_mode) && sb.st_size == 0))
        return 0;
    if (!S_ISREG(sb.st_mode))
        return np_errf(err, errlen, "journal %s exists and is not a regular file; not overwriting it", path);
    np_journal probe;
    memset(&probe, 0, sizeof probe);
    np_jfile_none(&probe.file);
    char perr[1024];
    int rc = read_journal(&probe, path, NULL, 0, perr, sizeof perr);
    uint64_t had = probe.n_checked, n = probe.n;
    free(probe.checked);
    free(probe.fails);
    if (rc != NP_JFILE_OK)
        return np_errf(err, errlen, "%s exists and is not a usable journal (%s); not overwriting it", path, perr);
    if (force)
        return 0;
    if (had > 0 && had < n)
        return np_errf(err, errlen,
                       "journal %s holds %llu verified vectors of an unfinished stream: continue it with --resume, "
                       "or start over with --force",
                       path, (unsigned long long)had);
    return np_errf(err, errlen,
                   "journal %s exists (%llu of %llu vectors verified): continue it with --resume, or start over "
                   "with --force",
                   path, (unsigned long long)had, (unsigned long long)n);
}

int np_journal_open(np_journal *jn, const char *path, const np_link_job *j, int resume,
                    char *err, size_t errlen)
{
    return np_journal_open_bound(jn, path, j, NULL, resume, 0, err, errlen);
}

int np_journal_open_bound(np_journal *jn, const char *path, const np_link_job *j,
                          const np_link_target *t, int resume, int force, char *err, size_t errlen)
{
    memset(jn, 0, sizeof *jn);
    np_jfile_none(&jn->file);
    jn->n = j->n;
    jn->n_out = j->fields.n_out;
    jn->sync_interval = 0.25;
    jn->checked = calloc((size_t)(j->n / 8u + 1u), 1);
    if (!jn->checked)
        return np_errf(err, errlen, "out of memory");
    if (!path)
        return 0;
    bindings b;
    bindings_of(j, t, &b);
    if (resume) {
        int rc = read_journal(jn, path, &b, 1, err, errlen);
        if (rc == NP_JFILE_MISSING)
            return np_errf(err, errlen, "cannot resume from journal %s: %s", path, strerror(ENOENT));
        if (rc == NP_JFILE_MISMATCH) {
            size_t n = strlen(err);
            const char *whose = strstr(err, "'target=") ? "another target: the results of one are never taken for another's"
                                : strstr(err, "'size=") ? "another vector file"
                                                        : "other vectors";
            snprintf(err + n, errlen - n, ": it belongs to %s, not resuming", whose);
        }
        if (rc != NP_JFILE_OK)
            return -1;
        jn->prior_checked = jn->n_checked;
        jn->prior_errors = jn->n_errors;
        return 0;
    }
    if (fresh_start_ok(path, force, err, errlen) != 0)
        return -1;
    return np_jfile_create(&jn->file, path, journal_magic, b.ptr, b.n, 1, err, errlen) == NP_JFILE_OK ? 0 : -1;
}

int np_journal_append(np_journal *jn, uint64_t first, uint64_t count,
                      const np_journal_fail *fails, size_t n_fails, char *err, size_t errlen)
{
    for (uint64_t i = first; i < first + count; i++)
        bit_set(jn->checked, i);
    jn->n_checked += count;
    jn->n_errors += n_fails;
    for (size_t k = 0; k < n_fails; k++)
        if (fail_add(jn, &fails[k]) != 0)
            return np_errf(err, errlen, "out of memory");
    if (jn->file.fd < 0)
        return 0;
    for (size_t k = 0; k < n_fails; k++) {
        char words[NP_UNIT_MAX_FIELDS * 18] = "";
        size_t at = 0;
        for (unsigned w = 0; w < jn->n_out; w++)
            at += (size_t)snprintf(words + at, sizeof words - at, " %llx", (unsigned long long)fails[k].got[w]);
        if (np_jfile_add(&jn->file, "E %llx%s", (unsigned long long)fails[k].index, words) != 0)
            goto bad;
    }
    if (np_jfile_add(&jn->file, "R %llx %llx %llx", (unsigned long long)first, (unsigned long long)count,
                     (unsigned long long)n_fails) != 0)
        goto bad;
    return np_jfile_commit(&jn->file, np_now() - jn->file.last_sync >= jn->sync_interval, err, errlen);
bad:
    np_jfile_discard(&jn->file);
    return np_errf(err, errlen, "cannot write journal %s: %s", jn->file.path, errno ? strerror(errno) : "line too long");
}

int np_journal_sync(np_journal *jn, char *err, size_t errlen) { return np_jfile_sync(&jn->file, err, errlen); }

void np_journal_close(np_journal *jn)
{
    if (jn->file.fd >= 0) {
        char err[4608];
        np_jfile_sync(&jn->file, err, sizeof err); /* best effort: the caller synced already */
    }
    np_jfile_close(&jn->file);
    free(jn->checked);
    free(jn->fails);
    jn->checked = NULL;
    jn->fails = NULL;
}
