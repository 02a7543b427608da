/* SPDX-License-Identifier: MIT */
/*
 * test_journal.c - the journal file (np_jfile.h) on its own: CRC-32 known
 * answers, round trip, torn last line, torn multi-line record, a damaged
 * middle line (refused with its line number), binding mismatches, and
 * resume after a kill, simulated by cutting the file at every byte and done
 * for real with SIGKILL; the way in of a run's journal (np_jfile_open_run,
 * np_jfile_bind) that the sweep and the search share.
 */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "np_crc32.h"
#include "np_jfile.h"
#include "np_test.h"

static const char magic[] = "noisepipe-test-journal 1";
static const char *const binds[] = { "unit=classic3", "config=out_bits=8 s_frac=12 lerp_frac=11",
                                     "z=0x0000" };
enum { N_BINDS = 3 };

static void tmp_path(char *buf, size_t len, const char *name)
{
    snprintf(buf, len, "test_journal.%ld.%s", (long)getpid(), name);
    unlink(buf);
}

/* The records read back: "part ..." lines open a record, any other line commits it. */
typedef struct got {
    unsigned n_lines, n_records;
    char last[NP_JFILE_TEXT_MAX];
    unsigned next;  /* for in-order checks: the record number expected next */
    int in_order;   /* every "rec K" line had K == next */
} got;

static int collect(void *ctx, const np_jfile_info *info, char *text, uint64_t lineno, char *err,
                   size_t errlen)
{
    got *g = ctx;
    (void)info;
    (void)lineno;
    g->n_lines++;
    snprintf(g->last, sizeof g->last, "%s", text);
    if (strncmp(text, "part ", 5) == 0)
        return NP_JFILE_OPEN;
    if (strncmp(text, "bad", 3) == 0) {
        snprintf(err, errlen, "a line the handler refuses");
        return -1;
    }
    unsigned k;
    if (sscanf(text, "rec %u", &k) == 1) {
        g->in_order &= k == g->next;
        g->next = k + 1u;
    }
    g->n_records++;
    return NP_JFILE_COMMIT;
}

static size_t file_size(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (size_t)sb.st_size : 0u;
}

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = file_size(path) + 1u;
    char *t = malloc(cap);
    *n = t ? fread(t, 1, cap - 1u, f) : 0u;
    if (t)
        t[*n] = '\0';
    fclose(f);
    return t;
}

static void put_file(const char *path, const char *text, size_t n)
{
    FILE *f = fopen(path, "wb");
    fwrite(text, 1, n, f);
    fclose(f);
}

static void append_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "ab");
    fputs(text, f);
    fclose(f);
}

/* A journal with k records "rec 0" .. "rec k-1", the odd ones preceded by an open "part" line. */
static int make(const char *path, unsigned k, char *err, size_t errlen)
{
    np_jfile jf;
    if (np_jfile_create(&jf, path, magic, binds, N_BINDS, 0, err, errlen) != NP_JFILE_OK)
        return -1;
    for (unsigned i = 0; i < k; i++) {
        if (i & 1u)
            np_jfile_add(&jf, "part of %u", i);
        np_jfile_add(&jf, "rec %u", i);
        if (np_jfile_commit(&jf, i + 1u == k, err, errlen) != 0)
            return -1;
    }
    return np_jfile_close(&jf);
}

static int t_crc_kat(void)
{
    NP_CHECK(np_crc32(0, "123456789", 9) == 0xcbf43926u, "check value %08x",
             (unsigned)np_crc32(0, "123456789", 9));
    NP_CHECK(np_crc32(0, "", 0) == 0, "empty");
    NP_CHECK(np_crc32(np_crc32(0, "1234", 4), "56789", 5) == 0xcbf43926u, "continued");
    for (uint32_t i = 0; i < 256; i++) {
        uint32_t c = i;
        for (int b = 0; b < 8; b++)
            c = c & 1u ? 0xedb88320u ^ (c >> 1) : c >> 1;
        NP_CHECK(np_crc32_table[i] == c, "table[%u] = %08x, want %08x", (unsigned)i,
                 (unsigned)np_crc32_table[i], (unsigned)c);
    }
    return 0;
}

/* Written, read back, appended to, read again; the text is what np_jfile.h says. */
static int t_round_trip(void)
{
    char path[256], err[1024];
    tmp_path(path, sizeof path, "rt");
    NP_CHECK(make(path, 5, err, sizeof err) == 0, "%s", err);
    size_t n;
    char *text = slurp(path, &n);
    NP_CHECK(text && strncmp(text, "noisepipe-test-journal 1\nunit=classic3 *", 40) == 0, "head: %.60s",
             text ? text : "");
    /* One line checked by hand: CRC-32 of "rec 0". */
    char want[64];
    snprintf(want, sizeof want, "\nrec 0 *%08x\n", (unsigned)np_crc32(0, "rec 0", 5));
    NP_CHECK(text && strstr(text, want), "no line '%s'", want + 1);
    free(text);

    np_jfile jf;
    np_jfile_info info;
    got g = { 0, 0, "", 0, 1 };
    NP_CHECK(np_jfile_resume(&jf, path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err) ==
                 NP_JFILE_OK, "%s", err);
    NP_CHECK(g.n_records == 5 && g.n_lines == 7 && g.in_order && info.records == 5 &&
                 info.torn_bytes == 0 && info.lines == 11,
             "records %u lines %u torn %llu", g.n_records, g.n_lines,
             (unsigned long long)info.torn_bytes);
    NP_CHECK(info.n_bind == 3 && strcmp(np_jfile_binding(&info, "z"), "0x0000") == 0 &&
                 strcmp(np_jfile_binding(&info, "config"), "out_bits=8 s_frac=12 lerp_frac=11") == 0 &&
                 np_jfile_binding(&info, "seed") == NULL,
             "bindings");
    np_jfile_add(&jf, "rec 5");
    NP_CHECK(np_jfile_commit(&jf, 1, err, sizeof err) == 0 && jf.syncs == 1, "%s", err);
    NP_CHECK(np_jfile_close(&jf) == 0, "close");
    got h = { 0, 0, "", 0, 1 };
    NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, collect, &h, &info, err, sizeof err) == NP_JFILE_OK &&
                 h.n_records == 6 && h.in_order && strcmp(h.last, "rec 5") == 0,
             "after the append: %u records, last '%s'", h.n_records, h.last);
    /* Not resuming over it: refused unless replacing. */
    NP_CHECK(np_jfile_create(&jf, path, magic, binds, N_BINDS, 0, err, sizeof err) == NP_JFILE_EXISTS,
             "an existing journal is not overwritten");
    NP_CHECK(np_jfile_create(&jf, path, magic, binds, 2, 1, err, sizeof err) == NP_JFILE_OK, "%s", err);
    np_jfile_close(&jf);
    NP_CHECK(np_jfile_read(path, magic, binds, 2, NULL, NULL, &info, err, sizeof err) == NP_JFILE_OK &&
                 info.records == 0 && info.n_bind == 2,
             "replaced: %s", err);
    NP_CHECK(np_jfile_read("test_journal.no.such.file", magic, binds, N_BINDS, NULL, NULL, &info, err,
                           sizeof err) == NP_JFILE_MISSING,
             "a missing file");
    /* Lines the format cannot hold are refused when added. */
    char longline[NP_JFILE_TEXT_MAX + 2];
    memset(longline, 'x', sizeof longline - 1u);
    longline[sizeof longline - 1u] = '\0';
    np_jfile_none(&jf);
    NP_CHECK(np_jfile_add(&jf, "%s", longline) != 0 && np_jfile_add(&jf, "a\nb") != 0, "too long, newline");
    np_jfile_close(&jf);
    unlink(path);
    return 0;
}

/* A torn last line: not a record, reported, cut off on resume; the next append is whole. */
static int t_torn_last_line(void)
{
    char path[256], err[1024];
    tmp_path(path, sizeof path, "torn");
    NP_CHECK(make(path, 4, err, sizeof err) == 0, "%s", err);
    size_t whole = file_size(path);
    append_text(path, "rec 4 *1234"); /* a kill in the middle of the write */
    np_jfile jf;
    np_jfile_info info;
    got g = { 0, 0, "", 0, 1 };
    NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err) == NP_JFILE_OK,
             "%s", err);
    NP_CHECK(g.n_records == 4 && info.torn_bytes == 11 && info.good_end == whole, "read: %u records, %llu torn",
             g.n_records, (unsigned long long)info.torn_bytes);
    NP_CHECK(file_size(path) == whole + 11u, "np_jfile_read changed the file");
    got h = { 0, 0, "", 0, 1 };
    NP_CHECK(np_jfile_resume(&jf, path, magic, binds, N_BINDS, collect, &h, &info, err, sizeof err) == NP_JFILE_OK,
             "%s", err);
    NP_CHECK(file_size(path) == whole, "the torn line was not cut off: %zu bytes, want %zu", file_size(path), whole);
    np_jfile_add(&jf, "rec 4");
    np_jfile_commit(&jf, 1, err, sizeof err);
    np_jfile_close(&jf);
    got k = { 0, 0, "", 0, 1 };
    NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, collect, &k, &info, err, sizeof err) == NP_JFILE_OK &&
                 k.n_records == 5 && k.in_order && info.torn_bytes == 0,
             "after the resume: %u records", k.n_records);
    unlink(path);
    return 0;
}

/* A record's opening line whole, its committing line missing: the whole record is torn. */
static int t_torn_record(void)
{
    char path[256], err[1024], line[64];
    tmp_path(path, sizeof path, "record");
    NP_CHECK(make(path, 3, err, sizeof err) == 0, "%s", err);
    size_t whole = file_size(path);
    snprintf(line, sizeof line, "part of 3 *%08x\n", (unsigned)np_crc32(0, "part of 3", 9));
    append_text(path, line);
    np_jfile jf;
    np_jfile_info info;
    got g = { 0, 0, "", 0, 1 };
    NP_CHECK(np_jfile_resume(&jf, path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err) == NP_JFILE_OK,
             "%s", err);
    NP_CHECK(g.n_records == 3 && info.torn_bytes == strlen(line) && file_size(path) == whole,
             "%u records, %llu torn bytes", g.n_records, (unsigned long long)info.torn_bytes);
    np_jfile_close(&jf);
    unlink(path);
    return 0;
}

/*
 * A damaged whole line in the middle: refused with its line number, never
 * skipped (a tampered file or a bad disk: what follows cannot be trusted).
 */
static int t_corrupt_middle(void)
{
    char path[256], err[1024];
    tmp_path(path, sizeof path, "bad");
    NP_CHECK(make(path, 6, err, sizeof err) == 0, "%s", err);
    size_t n;
    char *text = slurp(path, &n);
    char *at = text ? strstr(text, "rec 2") : NULL;
    NP_CHECK(at != NULL, "no rec 2");
    if (!at)
        return 1;
    at[4] = '7'; /* "rec 7": one digit changed, the checksum no longer fits */
    put_file(path, text, n);
    np_jfile_info info;
    got g = { 0, 0, "", 0, 1 };
    int rc = np_jfile_read(path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err);
    printf("damaged line: %s\n", err);
    char want[300];
    snprintf(want, sizeof want, "%s:8: ", path); /* magic, 3 bindings, rec 0, part, rec 1, rec 2 */
    NP_CHECK(rc == NP_JFILE_BAD && strstr(err, want) && strstr(err, "damaged"), "%s", err);
    /* The checksum itself damaged, or missing: the same. */
    at[4] = '2';
    char *star = strstr(at, " *");
    star[2] = star[2] == '0' ? '1' : '0';
    put_file(path, text, n);
    NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err) == NP_JFILE_BAD &&
                 strstr(err, want),
             "%s", err);
    unlink(path);
    NP_CHECK(make(path, 1, err, sizeof err) == 0, "%s", err);
    append_text(path, "rec 1\n");
    NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err) == NP_JFILE_BAD &&
                 strstr(err, ":6: "),
             "no checksum: %s", err);
    /* A line the caller's handler refuses: its message, with file and line. */
    unlink(path);
    np_jfile jf;
    np_jfile_create(&jf, path, magic, binds, N_BINDS, 0, err, sizeof err);
    np_jfile_add(&jf, "bad record");
    np_jfile_commit(&jf, 0, err, sizeof err);
    np_jfile_close(&jf);
    NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err) == NP_JFILE_BAD &&
                 strstr(err, ":5: a line the handler refuses"),
             "%s", err);
    free(text);
    unlink(path);
    return 0;
}

/* Bindings: another value, one missing, one unknown; another magic. Each named. */
static int t_binding_mismatch(void)
{
    char path[256], err[1024];
    tmp_path(path, sizeof path, "bind");
    NP_CHECK(make(path, 2, err, sizeof err) == 0, "%s", err);
    np_jfile jf;
    np_jfile_info info;
    const char *other_z[] = { "unit=classic3", "config=out_bits=8 s_frac=12 lerp_frac=11", "z=0x0001" };
    int rc = np_jfile_resume(&jf, path, magic, other_z, 3, NULL, NULL, &info, err, sizeof err);
    printf("other z: %s\n", err);
    NP_CHECK(rc == NP_JFILE_MISMATCH && strstr(err, "'z=0x0000'") && strstr(err, "'z=0x0001'") && jf.fd < 0,
             "%s", err);
    const char *other_cfg[] = { "unit=classic3", "config=out_bits=8 s_frac=10 lerp_frac=11", "z=0x0001" };
    rc = np_jfile_read(path, magic, other_cfg, 3, NULL, NULL, &info, err, sizeof err);
    NP_CHECK(rc == NP_JFILE_MISMATCH && strstr(err, "s_frac=12") && !strstr(err, "z="),
             "the first mismatch is named: %s", err);
    const char *more[] = { "unit=classic3", "config=out_bits=8 s_frac=12 lerp_frac=11", "z=0x0000",
                           "seed=1" };
    rc = np_jfile_read(path, magic, more, 4, NULL, NULL, &info, err, sizeof err);
    printf("missing binding: %s\n", err);
    NP_CHECK(rc == NP_JFILE_MISMATCH && strstr(err, "no seed"), "%s", err);
    rc = np_jfile_read(path, magic, binds, 2, NULL, NULL, &info, err, sizeof err);
    printf("unknown binding: %s\n", err);
    NP_CHECK(rc == NP_JFILE_MISMATCH && strstr(err, "'z=0x0000'") && strstr(err, "does not bind"), "%s", err);
    /* Order does not matter. */
    const char *shuffled[] = { "z=0x0000", "unit=classic3", "config=out_bits=8 s_frac=12 lerp_frac=11" };
    NP_CHECK(np_jfile_read(path, magic, shuffled, 3, NULL, NULL, &info, err, sizeof err) == NP_JFILE_OK, "%s",
             err);
    rc = np_jfile_read(path, "noisepipe-test-journal 2", binds, N_BINDS, NULL, NULL, &info, err, sizeof err);
    printf("older format: %s\n", err);
    NP_CHECK(rc == NP_JFILE_BAD && strstr(err, "format"), "%s", err);
    rc = np_jfile_read(path, "# something else 1", binds, N_BINDS, NULL, NULL, &info, err, sizeof err);
    NP_CHECK(rc == NP_JFILE_BAD && strstr(err, "not a journal"), "%s", err);
    /* A header cut short: the binding it lost is named. */
    unlink(path);
    put_file(path, "noisepipe-test-journal 1\n", 25);
    rc = np_jfile_read(path, magic, binds, N_BINDS, NULL, NULL, &info, err, sizeof err);
    NP_CHECK(rc == NP_JFILE_MISMATCH && strstr(err, "no unit"), "%s", err);
    put_file(path, "", 0);
    NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, NULL, NULL, &info, err, sizeof err) == NP_JFILE_BAD &&
                 strstr(err, "empty"),
             "%s", err);
    unlink(path);
    return 0;
}

/*
 * A kill can stop a write after any byte: cut a journal at every byte and
 * resume. Each time the records read are exactly the whole ones before the
 * cut, in order, none counted twice, and the next append makes a valid file.
 */
static int t_cut_every_byte(void)
{
    char path[256], full[256], err[1024];
    tmp_path(path, sizeof path, "cut");
    tmp_path(full, sizeof full, "full");
    NP_CHECK(make(full, 6, err, sizeof err) == 0, "%s", err);
    size_t n;
    char *text = slurp(full, &n);
    if (!text)
        return 1;
    size_t header = 0;
    for (unsigned k = 0; k < 4; k++)
        header = (size_t)(strchr(text + header, '\n') - text) + 1u;
    unsigned checked = 0;
    for (size_t cut = header; cut <= n; cut++) {
        /* Records wholly before the cut: each ends with a "rec K" line. */
        unsigned want = 0;
        for (const char *p = text; (p = strstr(p, "\nrec ")) && (size_t)(p - text) < cut; p++) {
            const char *e = strchr(p + 1, '\n');
            want += (size_t)(e - text) < cut;
        }
        put_file(path, text, cut);
        np_jfile jf;
        np_jfile_info info;
        got g = { 0, 0, "", 0, 1 };
        int rc = np_jfile_resume(&jf, path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err);
        NP_CHECK(rc == NP_JFILE_OK && g.n_records == want && g.in_order,
                 "cut at %zu: rc %d, %u records, want %u: %s", cut, rc, g.n_records, want, err);
        np_jfile_add(&jf, "rec %u", want);
        np_jfile_commit(&jf, 0, err, sizeof err);
        np_jfile_close(&jf);
        got h = { 0, 0, "", 0, 1 };
        NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, collect, &h, &info, err, sizeof err) == NP_JFILE_OK &&
                     h.n_records == want + 1u && h.in_order && info.torn_bytes == 0,
                 "cut at %zu, appended: %u records: %s", cut, h.n_records, err);
        checked++;
    }
    printf("%u cuts of a %zu-byte journal: each resumed to the whole records before it\n", checked, n);
    free(text);
    unlink(path);
    unlink(full);
    return 0;
}

/* For real: a writer killed with SIGKILL at a random moment leaves a prefix that resumes. */
static int t_kill_resume(void)
{
    char path[256], err[1024];
    tmp_path(path, sizeof path, "kill");
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    for (int trial = 0; trial < 4; trial++) {
        unlink(path);
        pid_t pid = fork();
        if (pid == 0) {
            np_jfile jf;
            if (np_jfile_create(&jf, path, magic, binds, N_BINDS, 0, err, sizeof err) != NP_JFILE_OK)
                _exit(2);
            for (unsigned i = 0;; i++) {
                if (i & 1u)
                    np_jfile_add(&jf, "part of %u", i);
                np_jfile_add(&jf, "rec %u", i);
                np_jfile_commit(&jf, 0, err, sizeof err);
            }
        }
        long us = 2000L + (long)((now.tv_nsec / 1000 + trial * 7919) % 20000);
        struct timespec ts = { 0, us * 1000L };
        nanosleep(&ts, NULL);
        kill(pid, SIGKILL);
        int st;
        waitpid(pid, &st, 0);
        /* A kill during creation can leave the child's unpublished header (np_jfile_create's PATH.tmpPID). */
        char stray[300];
        snprintf(stray, sizeof stray, "%s.tmp%ld", path, (long)pid);
        unlink(stray);
        if (access(path, F_OK) != 0) {
            printf("trial %d: killed after %ld us, before the journal existed\n", trial, us);
            continue;
        }
        np_jfile jf;
        np_jfile_info info;
        got g = { 0, 0, "", 0, 1 };
        int rc = np_jfile_resume(&jf, path, magic, binds, N_BINDS, collect, &g, &info, err, sizeof err);
        NP_CHECK(rc == NP_JFILE_OK && g.in_order, "trial %d: %s", trial, err);
        np_jfile_add(&jf, "rec %u", g.n_records);
        np_jfile_commit(&jf, 1, err, sizeof err);
        np_jfile_close(&jf);
        got h = { 0, 0, "", 0, 1 };
        NP_CHECK(np_jfile_read(path, magic, binds, N_BINDS, collect, &h, &info, err, sizeof err) == NP_JFILE_OK &&
                     h.in_order && h.n_records == g.n_records + 1u,
                 "trial %d after the resume: %s", trial, err);
        printf("trial %d: killed after %ld us with %u records; resumed and appended one: %u in order\n", trial,
               us, g.n_records, h.n_records);
    }
    unlink(path);
    return 0;
}

/*
 * A run's way in (np_jfile_open_run, np_jfile_bind): a binding that is not
 * KEY=VALUE, too long, or one too many is refused; a missing file is
 * started with resume, an existing one refused without it, resumed with it
 * (its records handed on), refused naming the binding for another run.
 */
static int t_open_run(void)
{
    char path[256], err[1024], big[NP_JFILE_TEXT_MAX + 8];
    tmp_path(path, sizeof path, "open_run");
    np_jfile_binds b;
    np_jfile_binds_init(&b);
    memset(big, 'v', sizeof big - 1u);
    big[sizeof big - 1u] = '\0';
    NP_CHECK(np_jfile_bind(&b, "no key here") != 0 && np_jfile_bind(&b, "k=%s", big) != 0 && b.n == 0,
             "a binding without KEY= or too long was taken");
    for (unsigned k = 0; k < NP_JFILE_MAX_BINDINGS; k++)
        NP_CHECK(np_jfile_bind(&b, "k%u=%u", k, k) == 0, "binding %u refused", k);
    NP_CHECK(np_jfile_bind(&b, "one=too many") != 0, "binding %d taken", NP_JFILE_MAX_BINDINGS + 1);
    np_jfile_binds_init(&b);
    for (unsigned k = 0; k < N_BINDS; k++)
        np_jfile_bind(&b, "%s", binds[k]);

    np_jfile jf;
    got g = { 0, 0, "", 0, 1 };
    NP_CHECK(np_jfile_open_run(&jf, path, magic, &b, 1, collect, &g, err, sizeof err) == 0, "%s", err);
    np_jfile_add(&jf, "rec 0");
    NP_CHECK(np_jfile_commit(&jf, 1, err, sizeof err) == 0 && np_jfile_close(&jf) == 0, "%s", err);
    NP_CHECK(np_jfile_open_run(&jf, path, magic, &b, 0, collect, &g, err, sizeof err) != 0 &&
                 strstr(err, "exists: pass --resume") && jf.fd < 0,
             "an existing journal was started again: %s", err);
    NP_CHECK(np_jfile_open_run(&jf, path, magic, &b, 1, collect, &g, err, sizeof err) == 0 && g.n_records == 1,
             "resumed %u records: %s", g.n_records, err);
    np_jfile_close(&jf);
    np_jfile_binds_init(&b);
    np_jfile_bind(&b, "%s", binds[0]);
    np_jfile_bind(&b, "%s", binds[1]);
    np_jfile_bind(&b, "z=0x0001");
    NP_CHECK(np_jfile_open_run(&jf, path, magic, &b, 1, collect, &g, err, sizeof err) != 0 &&
                 strstr(err, "'z=0x0000', this run is 'z=0x0001': not resuming") && jf.fd < 0,
             "a journal of another z was resumed: %s", err);
    printf("another z: %s\n", err);
    unlink(path);
    return 0;
}

static const np_test_case cases[] = {
    { "crc_kat", t_crc_kat },
    { "round_trip", t_round_trip },
    { "torn_last_line", t_torn_last_line },
    { "torn_record", t_torn_record },
    { "corrupt_middle", t_corrupt_middle },
    { "binding_mismatch", t_binding_mismatch },
    { "cut_every_byte", t_cut_every_byte },
    { "kill_resume", t_kill_resume },
    { "open_run", t_open_run },
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
