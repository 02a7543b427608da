/* SPDX-License-Identifier: MIT */
/*
 * link_host.c - the host side of the USB link (docs/usb-protocol.md,
 * sections 3, 4 and 7): the vectors to stream, the journal of verified
 * ranges, the protocol engine that verifies every result bit for bit, and
 * the in-process loopback transport to the board emulator.
 */
#include "np_link.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "np_cli.h"
#include "np_rng.h"

/* ------------------------------------------------------------------------- */
/* Vectors. */

int np_link_job_init(np_link_job *j, const np_unit *u, const void *cfg, uint64_t n)
{
    memset(j, 0, sizeof *j);
    j->unit = u;
    memcpy(&j->cfg, cfg, sizeof j->cfg);
    u->fields(&j->cfg, &j->fields);
    np_unit_cfg_format(u, &j->cfg, j->cfg_text, sizeof j->cfg_text);
    np_link_layout_init(&j->lay, &j->fields);
    j->n = n;
    size_t m = n ? (size_t)n : 1u;
    j->in = malloc(m * j->lay.in_stride);
    j->want = malloc(m * j->lay.out_stride);
    if (!j->in || !j->want) {
        np_link_job_free(j);
        return -1;
    }
    return 0;
}

void np_link_job_set(np_link_job *j, uint64_t i, const uint64_t *in, const uint64_t *want)
{
    const np_link_layout *l = &j->lay;
    np_link_pack(j->in + i * l->in_stride, in, l->in_lane, l->n_in, l->in_stride);
    np_link_pack(j->want + i * l->out_stride, want, l->out_lane, l->n_out, l->out_stride);
}

/* FNV-1a, 64 bits: identity, not security (a journal is refused for other vectors). */
static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const uint8_t *b = p;
    for (size_t k = 0; k < n; k++)
        h = (h ^ b[k]) * 0x100000001b3u;
    return h;
}

void np_link_job_seal(np_link_job *j)
{
    uint64_t h = 0xcbf29ce484222325u;
    uint8_t n8[8];
    h = fnv1a(h, j->unit->name, strlen(j->unit->name) + 1u);
    h = fnv1a(h, j->cfg_text, strlen(j->cfg_text) + 1u);
    np_link_put64(n8, j->n);
    h = fnv1a(h, n8, sizeof n8);
    h = fnv1a(h, j->in, (size_t)j->n * j->lay.in_stride);
    h = fnv1a(h, j->want, (size_t)j->n * j->lay.out_stride);
    j->hash = h;
}

int np_link_job_random(np_link_job *j, const np_unit *u, const void *cfg, uint64_t n,
                       uint64_t seed)
{
    if (np_link_job_init(j, u, cfg, n) != 0)
        return -1;
    np_rng r;
    np_rng_seed(&r, seed);
    uint64_t in[NP_UNIT_MAX_FIELDS] = { 0 }, out[NP_UNIT_MAX_FIELDS] = { 0 };
    for (uint64_t i = 0; i < n; i++) {
        for (unsigned k = 0; k < j->fields.n_in; k++) {
            unsigned b = j->fields.in[k].bits;
            in[k] = np_rng_next(&r) & np_link_mask(b);
        }
        u->eval(&j->cfg, in, out);
        np_link_job_set(j, i, in, out);
    }
    np_link_job_seal(j);
    return 0;
}

void np_link_job_free(np_link_job *j)
{
    free(j->in);
    free(j->want);
    free(j->line);
    j->in = j->want = NULL;
    j->line = NULL;
}

/* ------------------------------------------------------------------------- */
/* Journal. */

static const char journal_magic[] = "# noisepipe stream journal 1";

static void bit_set(uint8_t *bm, uint64_t i) { bm[i >> 3] = (uint8_t)(bm[i >> 3] | 1u << (i & 7u)); }

static int pend_add(np_journal *jn, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Append one line "TEXT *crc\n" to the pending buffer. */
static int pend_add(np_journal *jn, const char *fmt, ...)
{
    char line[1024];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(line, sizeof line - 16, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= sizeof line - 16)
        return -1;
    n += snprintf(line + n, 16, " *%08x\n", (unsigned)np_link_crc32(0, line, (size_t)n));
    if (jn->pend_len + (size_t)n > jn->pend_cap) {
        size_t cap = jn->pend_cap ? 2 * jn->pend_cap : 4096;
        while (cap < jn->pend_len + (size_t)n)
            cap *= 2;
        char *t = realloc(jn->pend, cap);
        if (!t)
            return -1;
        jn->pend = t;
        jn->pend_cap = cap;
    }
    memcpy(jn->pend + jn->pend_len, line, (size_t)n);
    jn->pend_len += (size_t)n;
    return 0;
}

static int write_all(int fd, const char *p, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        p += w;
        n -= (size_t)w;
    }
    return 0;
}

static int fail_add(np_journal *jn, const np_journal_fail *f)
{
    if (jn->n_fails == jn->cap_fails) {
        size_t cap = jn->cap_fails ? 2 * jn->cap_fails : 64;
        np_journal_fail *t = realloc(jn->fails, cap * sizeof *t);
        if (!t)
            return -1;
        jn->fails = t;
        jn->cap_fails = cap;
    }
    jn->fails[jn->n_fails++] = *f;
    return 0;
}

/* Split "TEXT *crc" and check the CRC: 0, or -1. Leaves TEXT NUL-terminated in line. */
static int line_crc_ok(char *line)
{
    char *star = strrchr(line, '*');
    if (!star || star == line || star[-1] != ' ' || strlen(star + 1) != 8)
        return -1;
    char *end;
    unsigned long c = strtoul(star + 1, &end, 16);
    if (*end)
        return -1;
    star[-1] = '\0';
    return np_link_crc32(0, line, strlen(line)) == (uint32_t)c ? 0 : -1;
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

typedef struct journal_file {
    uint64_t hash, n;
    char unit[64], cfg[NP_LINK_CFG_BYTES];
    int have_j;
    off_t good_end; /* end of the last complete record */
    int torn;       /* something follows it: a kill mid-append */
} journal_file;

/*
 * Read the journal at fd into jn (bitmap sized for jf->n once the J line is
 * seen, unless jn->checked is already set up for the job). 0, or -1 with err.
 */
static int journal_read(np_journal *jn, int fd, const char *path, journal_file *jf, char *err,
                        size_t errlen)
{
    struct stat sb;
    memset(jf, 0, sizeof *jf);
    if (fstat(fd, &sb) != 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    size_t size = (size_t)sb.st_size;
    char *text = malloc(size + 1u);
    if (!text) {
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    size_t got = 0;
    while (got < size) {
        ssize_t r = pread(fd, text + got, size - got, (off_t)got);
        if (r <= 0) {
            snprintf(err, errlen, "%s: read error: %s", path, r < 0 ? strerror(errno) : "short read");
            free(text);
            return -1;
        }
        got += (size_t)r;
    }
    text[size] = '\0';
    int rc = -1;
    uint64_t lineno = 0;
    np_journal_fail *pend = NULL; /* E lines waiting for their R line */
    size_t n_pend = 0, cap_pend = 0;
    size_t at = 0;
    while (at < size) {
        char *nl = memchr(text + at, '\n', size - at);
        if (!nl) {
            jf->torn = 1; /* a kill mid-write: ignored, cut off before appending */
            break;
        }
        *nl = '\0';
        char *line = text + at;
        lineno++;
        at = (size_t)(nl - text) + 1u;
        if (lineno == 1) {
            if (strcmp(line, journal_magic) != 0) {
                snprintf(err, errlen, "%s is not a noisepipe stream journal", path);
                goto out;
            }
            jf->good_end = (off_t)at;
            continue;
        }
        if (line_crc_ok(line) != 0) {
            snprintf(err, errlen, "%s:%llu: damaged line (bad CRC): the journal cannot be trusted", path,
                     (unsigned long long)lineno);
            goto out;
        }
        const char *s = line + 1;
        if (line[0] == 'J' && !jf->have_j) {
            int off = 0;
            if (parse_hex_u64(&s, &jf->hash) != 0 || parse_hex_u64(&s, &jf->n) != 0 ||
                sscanf(s, " %63s %n", jf->unit, &off) != 1) {
                snprintf(err, errlen, "%s:%llu: malformed J line", path, (unsigned long long)lineno);
                goto out;
            }
            snprintf(jf->cfg, sizeof jf->cfg, "%s", s + off);
            jf->have_j = 1;
            if (!jn->checked) {
                jn->n = jf->n;
                jn->checked = calloc((size_t)(jf->n / 8u + 1u), 1);
                if (!jn->checked) {
                    snprintf(err, errlen, "%s: out of memory", path);
                    goto out;
                }
            } else if (jf->n != jn->n) {
                rc = 1; /* another job: the caller words the message */
                goto out;
            }
        } else if (line[0] == 'E' && jf->have_j) {
            np_journal_fail f;
            memset(&f, 0, sizeof f);
            if (parse_hex_u64(&s, &f.index) != 0) {
                snprintf(err, errlen, "%s:%llu: malformed E line", path, (unsigned long long)lineno);
                goto out;
            }
            if (n_pend == cap_pend) {
                size_t cap = cap_pend ? 2 * cap_pend : 64;
                np_journal_fail *t = realloc(pend, cap * sizeof *t);
                if (!t) {
                    snprintf(err, errlen, "%s: out of memory", path);
                    goto out;
                }
                pend = t;
                cap_pend = cap;
            }
            for (unsigned k = 0; k < NP_UNIT_MAX_FIELDS && *s; k++)
                if (parse_hex_u64(&s, &f.got[k]) != 0)
                    break;
            pend[n_pend++] = f;
        } else if (line[0] == 'R' && jf->have_j) {
            uint64_t first, count, errs;
            if (parse_hex_u64(&s, &first) != 0 || parse_hex_u64(&s, &count) != 0 ||
                parse_hex_u64(&s, &errs) != 0 || count == 0 || first >= jn->n ||
                count > jn->n - first || errs != n_pend) {
                snprintf(err, errlen, "%s:%llu: malformed R line", path, (unsigned long long)lineno);
                goto out;
            }
            for (uint64_t i = first; i < first + count; i++) {
                if (np_journal_has(jn, i)) {
                    snprintf(err, errlen, "%s:%llu: vector %llu is journaled twice: the journal cannot be trusted",
                             path, (unsigned long long)lineno, (unsigned long long)i);
                    goto out;
                }
                bit_set(jn->checked, i);
            }
            for (size_t k = 0; k < n_pend; k++) {
                if (pend[k].index < first || pend[k].index - first >= count || fail_add(jn, &pend[k]) != 0) {
                    snprintf(err, errlen, "%s:%llu: E line outside its range", path, (unsigned long long)lineno);
                    goto out;
                }
            }
            jn->n_checked += count;
            jn->n_errors += errs;
            n_pend = 0;
        } else {
            snprintf(err, errlen, "%s:%llu: unexpected line", path, (unsigned long long)lineno);
            goto out;
        }
        if (line[0] != 'E')
            jf->good_end = (off_t)at; /* a record ends with its R line */
    }
    if ((size_t)jf->good_end < size)
        jf->torn = 1; /* E lines without their R line, or a partial line: cut off */
    if (lineno == 0 && !jf->torn) {
        snprintf(err, errlen, "%s is empty", path);
        goto out;
    }
    if (!jf->have_j) {
        snprintf(err, errlen, "%s: no J line: not a usable journal", path);
        goto out;
    }
    rc = 0;
out:
    free(pend);
    free(text);
    return rc;
}

static void journal_reset_counts(np_journal *jn)
{
    if (jn->checked)
        memset(jn->checked, 0, (size_t)(jn->n / 8u + 1u));
    jn->n_checked = jn->n_errors = 0;
    jn->n_fails = 0;
}

int np_journal_open(np_journal *jn, const char *path, const np_link_job *j, int resume,
                    char *err, size_t errlen)
{
    memset(jn, 0, sizeof *jn);
    jn->fd = -1;
    jn->n = j->n;
    jn->n_out = j->fields.n_out;
    jn->sync_interval = 0.25;
    jn->checked = calloc((size_t)(j->n / 8u + 1u), 1);
    if (!jn->checked) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    if (!path)
        return 0;
    if (strlen(path) >= sizeof jn->path) {
        snprintf(err, errlen, "journal path too long");
        return -1;
    }
    snprintf(jn->path, sizeof jn->path, "%s", path);
    char want_desc[512];
    snprintf(want_desc, sizeof want_desc, "%016llx, %llu vectors of %s %s", (unsigned long long)j->hash,
             (unsigned long long)j->n, j->unit->name, j->cfg_text);
    if (resume) {
        int fd = open(path, O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            snprintf(err, errlen, "cannot resume from journal %s: %s", path, strerror(errno));
            return -1;
        }
        journal_file jf;
        int rc = journal_read(jn, fd, path, &jf, err, errlen);
        if (rc == 0 && (jf.hash != j->hash || jf.n != j->n || strcmp(jf.unit, j->unit->name) != 0 ||
                        strcmp(jf.cfg, j->cfg_text) != 0))
            rc = 1;
        if (rc == 1)
            snprintf(err, errlen,
                     "journal %s belongs to other vectors (%016llx, %llu vectors of %s %s); these are %s",
                     path, (unsigned long long)jf.hash, (unsigned long long)jf.n, jf.unit, jf.cfg, want_desc);
        if (rc != 0) {
            close(fd);
            return -1;
        }
        if (jf.torn && ftruncate(fd, jf.good_end) != 0) {
            snprintf(err, errlen, "%s: cannot cut off the torn last line: %s", path, strerror(errno));
            close(fd);
            return -1;
        }
        if (lseek(fd, 0, SEEK_END) < 0) {
            snprintf(err, errlen, "%s: %s", path, strerror(errno));
            close(fd);
            return -1;
        }
        jn->fd = fd;
        jn->prior_checked = jn->n_checked;
        jn->prior_errors = jn->n_errors;
        jn->last_sync = np_now();
        return 0;
    }
    /* A fresh journal; an unfinished one is not thrown away. */
    int old = open(path, O_RDONLY | O_CLOEXEC);
    if (old >= 0) {
        np_journal probe;
        memset(&probe, 0, sizeof probe);
        journal_file jf;
        char perr[512];
        struct stat sb;
        int empty = fstat(old, &sb) == 0 && sb.st_size == 0;
        int rc = empty ? 0 : journal_read(&probe, old, path, &jf, perr, sizeof perr);
        close(old);
        int unfinished = !empty && rc == 0 && probe.n_checked > 0 && probe.n_checked < jf.n;
        uint64_t had = probe.n_checked;
        free(probe.checked);
        free(probe.fails);
        if (!empty && rc != 0) {
            snprintf(err, errlen, "%s exists and is not a usable journal (%s); not overwriting it", path, perr);
            return -1;
        }
        if (unfinished) {
            snprintf(err, errlen,
                     "journal %s holds %llu verified vectors of an unfinished stream: continue it with --resume, or delete it",
                     path, (unsigned long long)had);
            return -1;
        }
    }
    jn->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0666);
    if (jn->fd < 0) {
        snprintf(err, errlen, "cannot create journal %s: %s", path, strerror(errno));
        return -1;
    }
    journal_reset_counts(jn);
    jn->pend_len = 0;
    size_t ml = strlen(journal_magic);
    if (write_all(jn->fd, journal_magic, ml) != 0 || write_all(jn->fd, "\n", 1) != 0 ||
        pend_add(jn, "J %016llx %llx %s %s", (unsigned long long)j->hash, (unsigned long long)j->n,
                 j->unit->name, j->cfg_text) != 0 ||
        write_all(jn->fd, jn->pend, jn->pend_len) != 0 || fdatasync(jn->fd) != 0) {
        snprintf(err, errlen, "cannot write journal %s: %s", path, strerror(errno));
        close(jn->fd);
        jn->fd = -1;
        return -1;
    }
    jn->pend_len = 0;
    jn->last_sync = np_now();
    return 0;
}

int np_journal_append(np_journal *jn, uint64_t first, uint64_t count,
                      const np_journal_fail *fails, size_t n_fails, char *err, size_t errlen)
{
    for (uint64_t i = first; i < first + count; i++)
        bit_set(jn->checked, i);
    jn->n_checked += count;
    jn->n_errors += n_fails;
    for (size_t k = 0; k < n_fails; k++)
        if (fail_add(jn, &fails[k]) != 0) {
            snprintf(err, errlen, "out of memory");
            return -1;
        }
    if (jn->fd < 0)
        return 0;
    jn->pend_len = 0;
    for (size_t k = 0; k < n_fails; k++) {
        char words[NP_UNIT_MAX_FIELDS * 18] = "";
        size_t at = 0;
        for (unsigned w = 0; w < jn->n_out; w++)
            at += (size_t)snprintf(words + at, sizeof words - at, " %llx", (unsigned long long)fails[k].got[w]);
        if (pend_add(jn, "E %llx%s", (unsigned long long)fails[k].index, words) != 0)
            goto bad;
    }
    if (pend_add(jn, "R %llx %llx %llx", (unsigned long long)first, (unsigned long long)count,
                 (unsigned long long)n_fails) != 0)
        goto bad;
    /* One write: a kill leaves either the whole record or a torn last line. */
    if (write_all(jn->fd, jn->pend, jn->pend_len) != 0)
        goto bad;
    double t = np_now();
    if (t - jn->last_sync >= jn->sync_interval)
        return np_journal_sync(jn, err, errlen);
    return 0;
bad:
    snprintf(err, errlen, "cannot write journal %s: %s", jn->path, errno ? strerror(errno) : "line too long");
    return -1;
}

int np_journal_sync(np_journal *jn, char *err, size_t errlen)
{
    if (jn->fd < 0)
        return 0;
    if (fdatasync(jn->fd) != 0) {
        snprintf(err, errlen, "cannot sync journal %s: %s", jn->path, strerror(errno));
        return -1;
    }
    jn->last_sync = np_now();
    jn->syncs++;
    return 0;
}

void np_journal_close(np_journal *jn)
{
    if (jn->fd >= 0) {
        char err[4608];
        np_journal_sync(jn, err, sizeof err); /* best effort: the caller synced already */
        close(jn->fd);
    }
    jn->fd = -1;
    free(jn->checked);
    free(jn->fails);
    free(jn->pend);
    jn->checked = NULL;
    jn->fails = NULL;
    jn->pend = NULL;
}

/* ------------------------------------------------------------------------- */
/* Host engine. */

typedef enum host_state {
    H_HELLO,     /* HELLO due */
    H_WAIT_INFO, /* dropping stale IN bytes until INFO with our nonce */
    H_CONFIG,    /* CONFIG due */
    H_WAIT_ACK,
    H_STREAM,    /* DATA out, RESULT in */
    H_WAIT_BYE,
    H_DONE,
    H_FAULT
} host_state;

typedef struct outstanding {
    uint32_t seq;
    uint64_t tag;
    unsigned count;
} outstanding;

struct np_host {
    const np_link_job *j;
    np_journal *jn;
    np_host_opts o;
    np_link_rx rx;
    host_state state;
    uint32_t tx_seq, rx_expect;
    unsigned frame_records, window;
    uint64_t cursor;
    outstanding *out;
    unsigned out_head, out_n, out_cap;
    int stopping;
    np_link_fault fault;
    char msg[1024];
    np_host_stats st;
    np_journal_fail *fbuf;
    size_t fbuf_cap;
};

const char *np_link_fault_name(np_link_fault f)
{
    static const char *const names[] = {
        "none", "timeout", "device gone", "stalled endpoint", "USB error", "corrupted frame",
        "short frame", "lost or repeated frame", "board error", "configuration refused", "journal",
    };
    return (unsigned)f < sizeof names / sizeof names[0] ? names[f] : "?";
}

static void vfault(np_host *h, np_link_fault f, const char *fmt, va_list ap)
{
    if (h->fault != NP_FAULT_NONE)
        return;
    h->fault = f;
    h->state = H_FAULT;
    vsnprintf(h->msg, sizeof h->msg, fmt, ap);
}

void np_host_fault(np_host *h, np_link_fault f, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfault(h, f, fmt, ap);
    va_end(ap);
}

np_host *np_host_new(const np_link_job *j, np_journal *jn, const np_host_opts *o)
{
    np_host *h = calloc(1, sizeof *h);
    if (!h)
        return NULL;
    h->j = j;
    h->jn = jn;
    h->o = *o;
    if (!h->o.nonce) {
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        uint64_t s = (uint64_t)ts.tv_nsec ^ (uint64_t)ts.tv_sec << 30 ^ (uint64_t)getpid() << 48;
        h->o.nonce = np_splitmix64(&s) | 1u;
    }
    if (np_link_rx_init(&h->rx, NP_LINK_MAX_PAYLOAD) != 0) {
        free(h);
        return NULL;
    }
    return h;
}

void np_host_free(np_host *h)
{
    if (!h)
        return;
    np_link_rx_free(&h->rx);
    free(h->out);
    free(h->fbuf);
    free(h);
}

/* "vectors 2048..4095" of an outstanding frame. */
static void range_text(char *buf, size_t len, uint64_t tag, unsigned count)
{
    snprintf(buf, len, "vectors %llu..%llu", (unsigned long long)tag,
             (unsigned long long)(tag + count - 1u));
}

void np_host_outstanding(const np_host *h, char *buf, size_t len)
{
    if (h->out_n == 0) {
        snprintf(buf, len, "no DATA frame outstanding");
        return;
    }
    const outstanding *a = &h->out[h->out_head];
    const outstanding *z = &h->out[(h->out_head + h->out_n - 1u) % h->out_cap];
    snprintf(buf, len, "%u DATA frame%s outstanding (vectors %llu..%llu)", h->out_n,
             h->out_n == 1 ? "" : "s", (unsigned long long)a->tag,
             (unsigned long long)(z->tag + z->count - 1u));
}

static const char *waiting_for(const np_host *h)
{
    switch (h->state) {
    case H_WAIT_INFO: return "INFO (the answer to HELLO)";
    case H_WAIT_ACK: return "CONFIG_ACK";
    case H_WAIT_BYE: return "BYE_ACK";
    default: return "RESULT";
    }
}

void np_host_timeout(np_host *h, double seconds)
{
    char outs[128], part[160] = "";
    np_host_outstanding(h, outs, sizeof outs);
    size_t pend = np_link_rx_pending(&h->rx);
    if (pend)
        snprintf(part, sizeof part, "; %zu bytes of an unfinished frame arrived before the silence (a short frame?)", pend);
    np_host_fault(h, NP_FAULT_TIMEOUT,
                  "timeout: the board sent nothing for %.1f s while the host waited for %s; %s%s",
                  seconds, waiting_for(h), outs, part);
}

int np_host_waiting(const np_host *h)
{
    return h->state == H_WAIT_INFO || h->state == H_WAIT_ACK || h->state == H_WAIT_BYE ||
           (h->state == H_STREAM && h->out_n > 0);
}

int np_host_done(const np_host *h) { return h->state == H_DONE; }
np_link_fault np_host_get_fault(const np_host *h) { return h->fault; }
const char *np_host_fault_msg(const np_host *h) { return h->msg; }
const np_host_stats *np_host_get_stats(const np_host *h) { return &h->st; }
int np_host_complete(const np_host *h) { return h->jn->n_checked == h->j->n; }
unsigned np_host_frame_records(const np_host *h) { return h->frame_records; }

static size_t emit(np_host *h, uint8_t *buf, unsigned type, uint64_t tag, unsigned count, unsigned len)
{
    np_link_hdr hd = { NP_LINK_VERSION, type, h->tx_seq++, tag, count, len };
    size_t n = np_link_seal(buf, &hd);
    h->st.frames_out++;
    h->st.bytes_out += n;
    return n;
}

size_t np_host_pull(np_host *h, uint8_t *buf, size_t cap)
{
    if (cap < NP_LINK_MAX_FRAME)
        return 0;
    const np_link_job *j = h->j;
    switch (h->state) {
    case H_HELLO:
        h->tx_seq = 0;
        h->state = H_WAIT_INFO;
        return emit(h, buf, NP_LINK_HELLO, h->o.nonce, 0, 0);
    case H_CONFIG: {
        np_link_config c;
        memset(&c, 0, sizeof c);
        snprintf(c.unit, sizeof c.unit, "%s", j->unit->name);
        snprintf(c.cfg, sizeof c.cfg, "%s", j->cfg_text);
        c.lay = j->lay;
        size_t len = np_link_config_encode(np_link_payload(buf), &c);
        if (!len) {
            np_host_fault(h, NP_FAULT_CONFIG, "unit name or configuration text too long for CONFIG");
            return 0;
        }
        h->state = H_WAIT_ACK;
        return emit(h, buf, NP_LINK_CONFIG, 0, 0, (unsigned)len);
    }
    case H_STREAM: {
        if (h->out_n >= h->window)
            return 0;
        while (h->cursor < j->n && np_journal_has(h->jn, h->cursor))
            h->cursor++;
        if (h->stopping || h->cursor == j->n) {
            if (h->out_n)
                return 0;
            h->state = H_WAIT_BYE;
            return emit(h, buf, NP_LINK_BYE, 0, 0, 0);
        }
        uint64_t first = h->cursor, end = first;
        while (end < j->n && end - first < h->frame_records && !np_journal_has(h->jn, end))
            end++;
        unsigned count = (unsigned)(end - first);
        unsigned len = count * j->lay.in_stride;
        memcpy(np_link_payload(buf), j->in + first * j->lay.in_stride, len);
        outstanding *slot = &h->out[(h->out_head + h->out_n) % h->out_cap];
        slot->seq = h->tx_seq;
        slot->tag = first;
        slot->count = count;
        h->out_n++;
        h->cursor = end;
        h->st.sent += count;
        if (h->st.t_first_data == 0)
            h->st.t_first_data = np_now();
        return emit(h, buf, NP_LINK_DATA, first, count, len);
    }
    default:
        return 0;
    }
}

/* INFO with our nonce: the session is open. */
static void on_info(np_host *h, const np_link_rx_ev *ev)
{
    np_link_info *in = &h->st.info;
    if (np_link_info_decode(ev->payload, ev->h.len, in) != 0) {
        np_host_fault(h, NP_FAULT_CORRUPT, "malformed INFO payload from the board");
        return;
    }
    if (in->version != NP_LINK_VERSION) {
        np_host_fault(h, NP_FAULT_CONFIG, "the board speaks protocol version %u; this host speaks %d",
                      (unsigned)in->version, NP_LINK_VERSION);
        return;
    }
    const np_link_layout *l = &h->j->lay;
    unsigned fr = h->o.frame_records ? h->o.frame_records : NP_LINK_MAX_COUNT;
    if (fr > in->max_payload / l->in_stride)
        fr = in->max_payload / l->in_stride;
    if (fr > NP_LINK_MAX_PAYLOAD / l->out_stride)
        fr = NP_LINK_MAX_PAYLOAD / l->out_stride;
    if (fr == 0) {
        np_host_fault(h, NP_FAULT_CONFIG, "the board's max_payload (%u bytes) holds no %u-byte record",
                      (unsigned)in->max_payload, l->in_stride);
        return;
    }
    h->frame_records = fr;
    h->window = h->o.window && h->o.window < in->window ? h->o.window : in->window;
    h->out_cap = h->window;
    h->out = calloc(h->out_cap, sizeof *h->out);
    h->fbuf_cap = fr;
    h->fbuf = calloc(fr, sizeof *h->fbuf);
    if (!h->out || !h->fbuf) {
        np_host_fault(h, NP_FAULT_USB, "out of memory");
        return;
    }
    h->rx_expect = 1;
    h->state = H_CONFIG;
}

static void config_refused(np_host *h, const np_link_error *e)
{
    char offers[1024] = "";
    size_t at = 0;
    const np_link_info *in = &h->st.info;
    if (in->n_slots == 0)
        snprintf(offers, sizeof offers, " (it says it offers any configuration)");
    for (uint32_t k = 0; k < in->n_slots && at < sizeof offers; k++)
        at += (size_t)snprintf(offers + at, sizeof offers - at, "%s slot %u: %s %s", k ? ";" : " it offers:",
                               (unsigned)k, in->slot[k].unit, in->slot[k].cfg);
    np_host_fault(h, NP_FAULT_CONFIG, "the board '%s' does not run %s %s: %s (%s)%s", in->board_id,
                  h->j->unit->name, h->j->cfg_text, np_link_errcode_name(e->code), e->msg, offers);
}

/* A RESULT: must answer the oldest outstanding DATA frame; verify every record. */
static void on_result(np_host *h, const np_link_rx_ev *ev)
{
    const np_link_job *j = h->j;
    const np_link_layout *l = &j->lay;
    char want[64], got[64];
    if (h->out_n == 0) {
        np_host_fault(h, NP_FAULT_SEQ, "RESULT seq %u for vectors %llu.. arrived, but no DATA frame is outstanding",
                      (unsigned)ev->h.seq, (unsigned long long)ev->h.tag);
        return;
    }
    outstanding *o = &h->out[h->out_head];
    if (ev->h.tag != o->tag || ev->h.count != o->count) {
        range_text(want, sizeof want, o->tag, o->count);
        range_text(got, sizeof got, ev->h.tag, ev->h.count ? ev->h.count : 1u);
        np_host_fault(h, NP_FAULT_SEQ, "the board answered %s (RESULT seq %u), but the oldest outstanding DATA frame holds %s",
                      got, (unsigned)ev->h.seq, want);
        return;
    }
    if (ev->h.len != o->count * l->out_stride) {
        range_text(want, sizeof want, o->tag, o->count);
        np_host_fault(h, NP_FAULT_SHORT, "short frame from the board: RESULT seq %u (%s) carries %u bytes for %u records of %u bytes",
                      (unsigned)ev->h.seq, want, ev->h.len, o->count, l->out_stride);
        return;
    }
    size_t nf = 0;
    const uint8_t *g = ev->payload;
    const uint8_t *w = j->want + o->tag * l->out_stride;
    for (unsigned i = 0; i < o->count; i++, g += l->out_stride, w += l->out_stride) {
        if (memcmp(g, w, l->out_stride) == 0)
            continue;
        np_journal_fail *f = &h->fbuf[nf++];
        memset(f, 0, sizeof *f);
        f->index = o->tag + i;
        /* The whole record: pad bytes count too (section 5). */
        np_link_unpack(g, f->got, l->out_lane, l->n_out);
        for (unsigned k = l->n_out; k < NP_UNIT_MAX_FIELDS; k++)
            f->got[k] = 0;
        if (h->o.on_fail)
            h->o.on_fail(h->o.fail_ctx, f->index, f->got);
    }
    char err[512];
    if (np_journal_append(h->jn, o->tag, o->count, h->fbuf, nf, err, sizeof err) != 0) {
        np_host_fault(h, NP_FAULT_JOURNAL, "%s", err);
        return;
    }
    h->st.verified += o->count;
    h->st.errors += nf;
    h->st.t_last_result = np_now();
    h->out_head = (h->out_head + 1u) % h->out_cap;
    h->out_n--;
    if (h->o.max_errors && h->jn->n_errors >= h->o.max_errors)
        h->stopping = 1;
    if (h->o.on_progress)
        h->o.on_progress(h->o.fail_ctx, h->st.verified);
}

static void on_frame(np_host *h, const np_link_rx_ev *ev)
{
    const np_link_hdr *hd = &ev->h;
    if (h->state == H_WAIT_INFO) {
        if (hd->type == NP_LINK_INFO && hd->tag == h->o.nonce && hd->seq == 0) {
            h->st.frames_in++;
            on_info(h, ev);
        } else {
            h->st.stale_bytes += NP_LINK_OVERHEAD + (uint64_t)hd->len; /* an earlier session's */
        }
        return;
    }
    h->st.frames_in++;
    char outs[128];
    if (hd->seq != h->rx_expect) {
        np_host_outstanding(h, outs, sizeof outs);
        np_host_fault(h, NP_FAULT_SEQ,
                      "lost or repeated frame from the board: %s seq %u arrived, seq %u was expected (%s)",
                      np_link_type_name(hd->type), (unsigned)hd->seq, (unsigned)h->rx_expect, outs);
        return;
    }
    h->rx_expect++;
    if (hd->type == NP_LINK_ERROR) {
        np_link_error e;
        if (np_link_error_decode(ev->payload, hd->len, &e) != 0) {
            np_host_fault(h, NP_FAULT_CORRUPT, "malformed ERROR payload from the board");
            return;
        }
        if (h->state == H_WAIT_ACK && (e.code == NP_LINK_E_NO_SUCH_CONFIG || e.code == NP_LINK_E_BAD_LAYOUT)) {
            config_refused(h, &e);
            return;
        }
        np_host_outstanding(h, outs, sizeof outs);
        np_host_fault(h, NP_FAULT_BOARD,
                      "the board reported ERROR %s (code %u, detail %u) expecting host frame seq %llu: %s; %s",
                      np_link_errcode_name(e.code), (unsigned)e.code, (unsigned)e.detail,
                      (unsigned long long)hd->tag, e.msg[0] ? e.msg : "(no message)", outs);
        return;
    }
    switch (h->state) {
    case H_WAIT_ACK:
        if (hd->type == NP_LINK_CONFIG_ACK) {
            np_link_ack *a = &h->st.ack;
            if (np_link_ack_decode(ev->payload, hd->len, a) != 0 || a->in_stride != h->j->lay.in_stride ||
                a->out_stride != h->j->lay.out_stride) {
                np_host_fault(h, NP_FAULT_CONFIG, "the board's CONFIG_ACK does not confirm the record layout (strides %u/%u, host %u/%u)",
                              a->in_stride, a->out_stride, h->j->lay.in_stride, h->j->lay.out_stride);
                return;
            }
            h->state = H_STREAM;
            return;
        }
        break;
    case H_STREAM:
        if (hd->type == NP_LINK_RESULT) {
            on_result(h, ev);
            return;
        }
        break;
    case H_WAIT_BYE:
        if (hd->type == NP_LINK_BYE_ACK) {
            if (np_link_bye_decode(ev->payload, hd->len, &h->st.bye) == 0)
                h->st.have_bye = 1;
            h->state = H_DONE;
            return;
        }
        break;
    default:
        break;
    }
    np_host_fault(h, NP_FAULT_SEQ, "unexpected %s frame (seq %u) from the board while waiting for %s",
                  np_link_type_name(hd->type), (unsigned)hd->seq, waiting_for(h));
}

static void on_stream_error(np_host *h, np_link_rx_event e, const np_link_rx_ev *ev)
{
    if (h->state == H_WAIT_INFO)
        return; /* stale bytes of an earlier session: hunting */
    char what[160] = "";
    if (ev->h.type == NP_LINK_RESULT && h->out_n && ev->h.tag == h->out[h->out_head].tag) {
        char r[64];
        range_text(r, sizeof r, ev->h.tag, ev->h.count ? ev->h.count : 1u);
        snprintf(what, sizeof what, " (%s)", r);
    }
    switch (e) {
    case NP_RX_SHORT:
        np_host_fault(h, NP_FAULT_SHORT,
                      "short frame from the board: %s seq %u%s was cut off after %zu of its %u payload bytes (the next frame's header follows)",
                      np_link_type_name(ev->h.type), (unsigned)ev->h.seq, what, ev->short_at, ev->h.len);
        break;
    case NP_RX_BAD_CRC:
        np_host_fault(h, NP_FAULT_CORRUPT,
                      "corrupted frame from the board: %s seq %u%s fails its payload CRC (computed %08x, the frame says %08x)",
                      np_link_type_name(ev->h.type), (unsigned)ev->h.seq, what, (unsigned)ev->crc_got,
                      (unsigned)ev->crc_want);
        break;
    case NP_RX_BAD_VERSION:
        np_host_fault(h, NP_FAULT_CONFIG, "the board sent a protocol version %u frame; this host speaks %d",
                      ev->h.version, NP_LINK_VERSION);
        break;
    case NP_RX_BAD_LENGTH:
        np_host_fault(h, NP_FAULT_CORRUPT, "corrupted frame header from the board: payload length %u", ev->h.len);
        break;
    default:
        np_host_fault(h, NP_FAULT_CORRUPT,
                      "corrupted stream from the board: no valid frame header where frame seq %u must start",
                      (unsigned)h->rx_expect);
        break;
    }
}

int np_host_push(np_host *h, const uint8_t *p, size_t n)
{
    h->st.bytes_in += n;
    while (h->state != H_FAULT) {
        np_link_rx_ev ev;
        np_link_rx_event e = np_link_rx_step(&h->rx, &p, &n, &ev);
        if (e == NP_RX_MORE)
            break;
        if (e == NP_RX_FRAME)
            on_frame(h, &ev);
        else
            on_stream_error(h, e, &ev);
    }
    if (h->state == H_WAIT_INFO)
        h->st.stale_bytes = h->rx.discarded;
    return h->state == H_FAULT ? -1 : 0;
}

/* ------------------------------------------------------------------------- */
/* Loopback transport: host and emulator in one process. */

static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

int np_link_loopback(np_host *h, np_board *b, np_loop_opts *o)
{
    size_t cap = NP_LINK_MAX_FRAME;
    uint8_t *obuf = malloc(cap), *ibuf = malloc(cap);
    if (!obuf || !ibuf) {
        free(obuf);
        free(ibuf);
        np_host_fault(h, NP_FAULT_USB, "out of memory");
        return 0;
    }
    double timeout = o->timeout > 0 ? o->timeout : 2.0;
    size_t olen = 0, ooff = 0;
    double last = np_now();
    uint64_t results0 = h->st.verified;
    uint64_t frames0 = h->st.frames_in;
    int stopped = 0;
    o->board_cpu = 0;
    while (h->state != H_DONE && h->state != H_FAULT) {
        int progress = 0;
        if (ooff == olen) {
            olen = np_host_pull(h, obuf, cap);
            ooff = 0;
        }
        if (ooff < olen) {
            size_t m = olen - ooff;
            if (o->chunk && m > o->chunk)
                m = o->chunk;
            double t0 = thread_cpu();
            size_t k = np_board_rx(b, obuf + ooff, m);
            o->board_cpu += thread_cpu() - t0;
            ooff += k;
            progress |= k > 0;
        }
        size_t want = o->chunk ? o->chunk : cap;
        double t0 = thread_cpu();
        size_t m = np_board_tx(b, ibuf, want);
        o->board_cpu += thread_cpu() - t0;
        if (m) {
            np_host_push(h, ibuf, m);
            progress = 1;
        }
        if (o->stop_after && h->st.frames_in - frames0 >= o->stop_after && h->st.verified > results0) {
            stopped = 1;
            break;
        }
        if (progress) {
            last = np_now();
            continue;
        }
        if (!np_host_waiting(h) && ooff == olen) {
            np_host_fault(h, NP_FAULT_USB, "internal: the session stalled with nothing to wait for");
            break;
        }
        if (np_now() - last > timeout) {
            np_host_timeout(h, timeout);
            break;
        }
        struct timespec ts = { 0, 1000000 };
        nanosleep(&ts, NULL);
    }
    free(obuf);
    free(ibuf);
    return stopped;
}
