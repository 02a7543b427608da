/* SPDX-License-Identifier: MIT */
/*
 * vecfile.c - the vector file format: its one reader, one results reader and
 * one writer (text, $readmemh, .coe, results). docs/vectors.md is the
 * specification; every message names FILE:LINE and, for a field, its column.
 */
#include "np_vec.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#include "np_cli.h"

static const char *const kind_name[NP_VEC_KINDS] = { "in", "out", "ref", "got" };
static const char *const kind_suffix[NP_VEC_KINDS] = { "", "", ".ref", ".got" };

/* Hex digit value + 1, 0 for a character that is not a hex digit. */
static const unsigned char hexval1[256] = {
    ['0'] = 1,  ['1'] = 2,  ['2'] = 3,  ['3'] = 4,  ['4'] = 5,  ['5'] = 6,  ['6'] = 7,
    ['7'] = 8,  ['8'] = 9,  ['9'] = 10, ['a'] = 11, ['b'] = 12, ['c'] = 13, ['d'] = 14,
    ['e'] = 15, ['f'] = 16, ['A'] = 11, ['B'] = 12, ['C'] = 13, ['D'] = 14, ['E'] = 15,
    ['F'] = 16,
};
static const char hexdigit[16] = "0123456789abcdef";

void np_vec_unit_names(char *buf, size_t len)
{
    size_t at = 0;
    buf[0] = '\0';
    for (size_t i = 0; np_units[i] && at < len; i++)
        at += (size_t)snprintf(buf + at, len - at, "%s%s", i ? ", " : "", np_units[i]->name);
}

static unsigned hex_digits(unsigned bits) { return (bits + 3u) / 4u; }

int np_vec_format_parse(const char *name, np_vec_format *fmt)
{
    static const char *const names[] = { "text", "readmemh", "coe", "results" };
    for (unsigned k = 0; k < sizeof names / sizeof names[0]; k++)
        if (strcmp(name, names[k]) == 0) {
            *fmt = (np_vec_format)k;
            return 0;
        }
    return -1;
}

double np_vec_ref_value(uint64_t bits)
{
    double v;
    _Static_assert(sizeof v == sizeof bits, "binary64 double");
    memcpy(&v, &bits, sizeof v);
    return v;
}

uint64_t np_vec_ref_bits(double v)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    return bits;
}

void np_vec_compute(const np_vec_header *h, const uint64_t *in, uint64_t *out, uint64_t *ref)
{
    double r[NP_UNIT_MAX_FIELDS];
    h->unit->eval(&h->cfg, in, out);
    h->unit->ref(&h->cfg, in, r);
    for (unsigned k = 0; k < h->fields.n_out; k++)
        ref[k] = np_vec_ref_bits(r[k]);
}

/* np_vec_header_init; all: spec gives every key exactly once (a '# config' line, np_unit_configure_all). */
static int header_init(np_vec_header *h, const np_unit *u, const char *spec, int all, char *err, size_t errlen)
{
    memset(h, 0, sizeof *h);
    h->unit = u;
    if ((all ? np_unit_configure_all : np_unit_configure)(u, &h->cfg, spec, err, errlen) != 0)
        return -1;
    np_unit_cfg_format(u, &h->cfg, h->cfg_text, sizeof h->cfg_text);
    u->fields(&h->cfg, &h->fields);
    return 0;
}

int np_vec_header_init(np_vec_header *h, const np_unit *u, const char *spec, char *err, size_t errlen)
{
    return header_init(h, u, spec, 0, err, errlen);
}

unsigned np_vec_columns(const np_vec_header *h, unsigned mask, np_vec_col *cols)
{
    unsigned n = 0;
    for (unsigned kind = 0; kind < NP_VEC_KINDS; kind++) {
        if (!(mask & (1u << kind)))
            continue;
        unsigned nf = kind == NP_VEC_IN ? h->fields.n_in : h->fields.n_out;
        for (unsigned k = 0; k < nf; k++, n++) {
            const np_field *f = kind == NP_VEC_IN ? &h->fields.in[k] : &h->fields.out[k];
            np_vec_col *c = &cols[n];
            snprintf(c->name, sizeof c->name, "%s%s", f->name, kind_suffix[kind]);
            c->kind = (np_vec_kind)kind;
            c->field = k;
            c->bits = kind == NP_VEC_REF ? NP_VEC_REF_BITS : f->bits;
            c->digits = hex_digits(c->bits);
            snprintf(c->format, sizeof c->format, "%s", kind == NP_VEC_REF ? "binary64" : f->format);
        }
    }
    return n;
}

/* "NAME KIND BITS FORMAT": a column as a "# field" header line declares it. */
static void col_decl(const np_vec_col *c, char *buf, size_t len)
{
    snprintf(buf, len, "%.23s %s %u %.31s", c->name, kind_name[c->kind], c->bits, c->format);
}

/* ------------------------------------------------------------------------- */
/* Packed words: fields concatenated MSB-first, as $readmemh and .coe hold them. */

enum { PACK_LIMBS = (1 + 2 * NP_UNIT_MAX_FIELDS * 64) / 64 + 2 };

/* OR v (masked to bits, 1..64) into bits [pos, pos + bits) of the little-endian limbs. */
static void limbs_put(uint64_t *limb, unsigned pos, unsigned bits, uint64_t v)
{
    unsigned q = pos / 64u, r = pos % 64u;
    v &= np_vec_mask(bits);
    limb[q] |= v << r;
    if (r != 0 && r + bits > 64u)
        limb[q + 1u] |= v >> (64u - r);
}

static uint64_t limbs_get(const uint64_t *limb, unsigned pos, unsigned bits)
{
    unsigned q = pos / 64u, r = pos % 64u;
    uint64_t v = limb[q] >> r;
    if (r != 0 && r + bits > 64u)
        v |= limb[q + 1u] << (64u - r);
    return v & np_vec_mask(bits);
}

static unsigned sum_bits(const unsigned *bits, unsigned n)
{
    unsigned t = 0;
    for (unsigned k = 0; k < n; k++)
        t += bits[k];
    return t;
}

/*
 * Write {vals[0], ..., vals[n-1]} (vals[k] is bits[k] wide, vals[0] most
 * significant) as ceil(total/4) hex digits at p; returns the digit count.
 */
static unsigned pack_hex(char *p, const uint64_t *vals, const unsigned *bits, unsigned n)
{
    uint64_t limb[PACK_LIMBS] = { 0 };
    unsigned pos = 0;
    for (unsigned k = n; k-- > 0;) {
        limbs_put(limb, pos, bits[k], vals[k]);
        pos += bits[k];
    }
    unsigned nd = hex_digits(pos);
    for (unsigned d = 0; d < nd; d++)
        p[nd - 1u - d] = hexdigit[limbs_get(limb, 4u * d, 4u)];
    return nd;
}

/*
 * Inverse of pack_hex for a token of exactly ceil(total/4) hex digits that
 * the caller checked: 0, or -1 when bits above the total are set.
 */
static int unpack_hex(const char *tok, unsigned nd, const unsigned *bits, unsigned n,
                      uint64_t *vals)
{
    uint64_t limb[PACK_LIMBS] = { 0 };
    unsigned total = sum_bits(bits, n);
    for (unsigned d = 0; d < nd; d++)
        limbs_put(limb, 4u * d, 4u, (uint64_t)(hexval1[(unsigned char)tok[nd - 1u - d]] - 1u));
    unsigned spare = 4u * nd - total; /* pad bits of the top digit */
    if (spare && limbs_get(limb, total, spare) != 0)
        return -1;
    unsigned pos = 0;
    for (unsigned k = n; k-- > 0;) {
        vals[k] = limbs_get(limb, pos, bits[k]);
        pos += bits[k];
    }
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Line source. */

static int lerr(np_vec_lines *L, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Record "NAME:LINE: message" (or "NAME: message" before the first line); returns -1. */
static int lerr(np_vec_lines *L, const char *fmt, ...)
{
    char msg[NP_VEC_ERRLEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (L->lineno)
        snprintf(L->err, sizeof L->err, "%.200s:%llu: %.280s", L->name, (unsigned long long)L->lineno,
                 msg);
    else
        snprintf(L->err, sizeof L->err, "%.200s: %.300s", L->name, msg);
    return -1;
}

static int lines_open(np_vec_lines *L, const char *path)
{
    memset(L, 0, sizeof *L);
    if (strcmp(path, "-") == 0) {
        L->f = stdin;
        L->name = "<stdin>";
        return 0;
    }
    L->name = path;
    L->f = fopen(path, "r");
    if (!L->f)
        return lerr(L, "cannot open: %s", strerror(errno));
    L->own = 1;
    return 0;
}

static void lines_close(np_vec_lines *L)
{
    if (L->own && L->f)
        fclose(L->f);
    free(L->buf);
    L->f = NULL;
    L->buf = NULL;
}

/*
 * Next line, without its line end and surrounding blanks, in *s (valid until
 * the next call): 1, 0 at the end of the input, -1 on a read error or a NUL
 * byte. The buffer is reused, so a long file costs no allocation per line.
 */
static int lines_next(np_vec_lines *L, char **s)
{
    ssize_t n = getline(&L->buf, &L->cap, L->f);
    if (n < 0) {
        if (ferror(L->f))
            return lerr(L, "read error: %s", strerror(errno));
        return 0;
    }
    L->lineno++;
    char *b = L->buf;
    if (memchr(b, '\0', (size_t)n))
        return lerr(L, "NUL byte in line: not a text file");
    while (n > 0 && (b[n - 1] == '\n' || b[n - 1] == '\r' || b[n - 1] == ' ' || b[n - 1] == '\t'))
        n--;
    b[n] = '\0';
    while (*b == ' ' || *b == '\t')
        b++;
    *s = b;
    return 1;
}

static int is_blank(char c) { return c == ' ' || c == '\t'; }

/* Count the blank-separated tokens of s. */
static unsigned count_tokens(const char *s)
{
    unsigned n = 0;
    while (*s) {
        while (is_blank(*s))
            s++;
        if (!*s)
            break;
        n++;
        while (*s && !is_blank(*s))
            s++;
    }
    return n;
}

/* Column names "x y z f f.ref" for messages. */
static void col_names(const np_vec_col *cols, unsigned n, char *buf, size_t len)
{
    size_t at = 0;
    buf[0] = '\0';
    for (unsigned k = 0; k < n && at < len; k++) {
        int w = snprintf(buf + at, len - at, "%s%s", k ? " " : "", cols[k].name);
        if (w < 0)
            break;
        at += (size_t)w;
    }
}

/* Parse one hex token of column c into *v: width, digits, then range. */
static int parse_hex(np_vec_lines *L, const np_vec_col *c, const char *tok, size_t len,
                     uint64_t *v)
{
    int shown = len > 40 ? 40 : (int)len;
    if (len != c->digits)
        return lerr(L, "field %s: wrong width: %zu hex digits in '%.*s', expected %u (%s)",
                    c->name, len, shown, tok, c->digits, c->format);
    uint64_t acc = 0;
    for (size_t k = 0; k < len; k++) {
        unsigned d = hexval1[(unsigned char)tok[k]];
        if (d == 0)
            return lerr(L, "field %s: non-hex digit '%c' in '%.*s'", c->name, tok[k], shown, tok);
        acc = acc << 4 | (uint64_t)(d - 1u);
    }
    if (acc & ~np_vec_mask(c->bits))
        return lerr(L, "field %s: value %.*s out of range for %u bits (%s): at most %llx", c->name,
                    shown, tok, c->bits, c->format, (unsigned long long)np_vec_mask(c->bits));
    *v = acc;
    return 0;
}

/*
 * Parse a line of exactly n columns into w[kind][field]. extra_hint, when
 * not NULL, is said after a too-many-fields or truncated-line message.
 */
static int parse_cols(np_vec_lines *L, char *s, const np_vec_col *cols, unsigned n,
                      uint64_t (*w)[NP_UNIT_MAX_FIELDS], const char *extra_hint)
{
    unsigned k = 0;
    char names[NP_VEC_MAX_COLS * 24];
    for (;;) {
        while (is_blank(*s))
            s++;
        if (!*s)
            break;
        char *tok = s;
        while (*s && !is_blank(*s))
            s++;
        if (k == n) {
            col_names(cols, n, names, sizeof names);
            return lerr(L, "too many fields: %u, expected %u (%s)%s", k + count_tokens(tok), n,
                        names, extra_hint ? extra_hint : "");
        }
        const np_vec_col *c = &cols[k++];
        if (parse_hex(L, c, tok, (size_t)(s - tok), &w[c->kind][c->field]) != 0)
            return -1;
    }
    if (k < n) {
        col_names(cols, n, names, sizeof names);
        return lerr(L, "field %s: missing: truncated line has %u fields, expected %u (%s)%s",
                    cols[k].name, k, n, names, extra_hint ? extra_hint : "");
    }
    return 0;
}

/* ------------------------------------------------------------------------- */
/* Vector file reader. */

typedef struct hdr_line {
    uint64_t line; /* 0: not seen */
    char text[256];
} hdr_line;

/* What the header parser collected, before the unit is known. */
typedef struct hdr_state {
    hdr_line version, unit, config, seed, level, count;
    hdr_line field[NP_VEC_MAX_COLS + 1];
    unsigned n_field;
    uint64_t first_line; /* first non-blank line */
    int first_slashes;   /* it starts with "//": a $readmemh or results file */
} hdr_state;

/* Copy s into dst with every run of blanks made one space. */
static void normalize(char *dst, size_t len, const char *s)
{
    size_t at = 0;
    while (*s && at + 1 < len) {
        if (is_blank(*s)) {
            while (is_blank(*s))
                s++;
            if (*s)
                dst[at++] = ' ';
            continue;
        }
        dst[at++] = *s++;
    }
    dst[at] = '\0';
}

/* One "# key value" line of the header; unknown keys are comments. */
static int header_line(np_vec_reader *r, hdr_state *hs, const char *s)
{
    static const struct {
        const char *key;
        size_t off;
    } keys[] = {
        { "noisepipe", offsetof(hdr_state, version) }, { "unit", offsetof(hdr_state, unit) },
        { "config", offsetof(hdr_state, config) },     { "seed", offsetof(hdr_state, seed) },
        { "level", offsetof(hdr_state, level) },       { "count", offsetof(hdr_state, count) },
    };
    char key[16];
    size_t n = 0;
    while (is_blank(*s))
        s++;
    while (s[n] && !is_blank(s[n]) && n < sizeof key - 1)
        n++;
    memcpy(key, s, n);
    key[n] = '\0';
    const char *rest = s + n;
    while (is_blank(*rest))
        rest++;
    if (strcmp(key, "field") == 0) {
        if (hs->n_field == NP_VEC_MAX_COLS + 1)
            return lerr(&r->L, "too many '# field' lines (at most %u)", NP_VEC_MAX_COLS);
        hdr_line *f = &hs->field[hs->n_field++];
        f->line = r->L.lineno;
        normalize(f->text, sizeof f->text, rest);
        return 0;
    }
    for (unsigned k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        if (strcmp(key, keys[k].key) != 0)
            continue;
        hdr_line *h = (hdr_line *)((char *)hs + keys[k].off);
        if (h->line)
            return lerr(&r->L, "second '# %s' line (the first is line %llu)", key,
                        (unsigned long long)h->line);
        h->line = r->L.lineno;
        normalize(h->text, sizeof h->text, rest);
        return 0;
    }
    return 0; /* a comment */
}

/* Record an error at line `at` (a header line, or where the missing one was due). */
static int hdr_err(np_vec_reader *r, uint64_t at, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int hdr_err(np_vec_reader *r, uint64_t at, const char *fmt, ...)
{
    char msg[NP_VEC_ERRLEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    r->L.lineno = at;
    return lerr(&r->L, "%s", msg);
}

/* Check the field declarations against the unit's columns; sets h.has_got if declared. */
static int header_fields(np_vec_reader *r, const hdr_state *hs, uint64_t at)
{
    np_vec_col cols[NP_VEC_MAX_COLS];
    unsigned n_base = np_vec_columns(&r->h, NP_VEC_M_IN | NP_VEC_M_OUT | NP_VEC_M_REF, cols);
    unsigned n_all = np_vec_columns(&r->h, NP_VEC_M_IN | NP_VEC_M_OUT | NP_VEC_M_REF | NP_VEC_M_GOT, cols);
    char want[256];
    for (unsigned k = 0; k < n_all && k < hs->n_field; k++) {
        col_decl(&cols[k], want, sizeof want);
        if (strcmp(hs->field[k].text, want) != 0)
            return hdr_err(r, hs->field[k].line,
                           "field %s: header declares '%s', but unit %s (%s) has '%s'",
                           cols[k].name, hs->field[k].text, r->h.unit->name, r->h.cfg_text, want);
    }
    if (hs->n_field > n_all)
        return hdr_err(r, hs->field[n_all].line, "field: '%s' is not a field of unit %s",
                       hs->field[n_all].text, r->h.unit->name);
    if (hs->n_field != n_base && hs->n_field != n_all) {
        col_decl(&cols[hs->n_field], want, sizeof want);
        return hdr_err(r, at, "missing header line '# field %s'", want);
    }
    r->h.has_got = hs->n_field == n_all;
    return 0;
}

/* Resolve what the header lines say: unit, configuration, count, seed, level, fields. */
static int header_finish(np_vec_reader *r, const hdr_state *hs, uint64_t at)
{
    char err[NP_VEC_ERRLEN];
    unsigned ver;
    if (!hs->version.line)
        return hdr_err(r, at, "missing header: expected '# noisepipe vectors %d' before the first vector%s",
                       NP_VEC_VERSION,
                       hs->first_slashes ? " (this looks like a $readmemh export or a results file;"
                                           " give the text vector file)"
                                         : "");
    if (strncmp(hs->version.text, "results", 7) == 0)
        return hdr_err(r, hs->version.line, "this is a device results file, not a vector file");
    if (sscanf(hs->version.text, "vectors %u", &ver) != 1 || ver != NP_VEC_VERSION)
        return hdr_err(r, hs->version.line, "unsupported header '# noisepipe %s' (this is version %d)",
                       hs->version.text, NP_VEC_VERSION);
    if (!hs->unit.line)
        return hdr_err(r, at, "missing header line '# unit NAME'");
    const np_unit *u = np_unit_find(hs->unit.text);
    if (!u) {
        char known[256];
        np_vec_unit_names(known, sizeof known);
        return hdr_err(r, hs->unit.line, "unknown unit '%s' (units: %s)", hs->unit.text, known);
    }
    if (!hs->config.line)
        return hdr_err(r, at, "missing header line '# config KEY=VALUE ...'");
    if (header_init(&r->h, u, hs->config.text, 1, err, sizeof err) != 0)
        return hdr_err(r, hs->config.line, "bad config '%s' for unit %s: %s", hs->config.text, u->name, err);
    if (!hs->count.line)
        return hdr_err(r, at, "missing header line '# count N'");
    if (np_parse_u64(hs->count.text, 0, UINT64_MAX, &r->h.count) != 0)
        return hdr_err(r, hs->count.line, "bad count '%s'", hs->count.text);
    r->count_line = hs->count.line;
    if (hs->seed.line) {
        if (np_parse_u64(hs->seed.text, 0, UINT64_MAX, &r->h.seed) != 0)
            return hdr_err(r, hs->seed.line, "bad seed '%s'", hs->seed.text);
        r->h.has_seed = 1;
    }
    if (hs->level.line) {
        uint64_t lv;
        if (np_parse_u64(hs->level.text, 1, 2, &lv) != 0)
            return hdr_err(r, hs->level.line, "bad level '%s' (1 or 2)", hs->level.text);
        r->h.level = (unsigned)lv;
    }
    return header_fields(r, hs, at);
}

int np_vec_open(np_vec_reader *r, const char *path)
{
    memset(r, 0, sizeof *r);
    if (lines_open(&r->L, path) != 0)
        return -1;
    hdr_state hs;
    memset(&hs, 0, sizeof hs);
    char *s = NULL;
    int rc;
    while ((rc = lines_next(&r->L, &s)) == 1) {
        if (*s == '\0')
            continue;
        if (!hs.first_line) {
            hs.first_line = r->L.lineno;
            hs.first_slashes = s[0] == '/' && s[1] == '/';
        }
        if (*s != '#') {
            r->pending = 1;
            break;
        }
        if (header_line(r, &hs, s + 1) != 0)
            return -1;
    }
    if (rc < 0)
        return -1;
    if (!hs.first_line) {
        r->L.lineno = 0;
        return lerr(&r->L, "empty file: no header and no vectors");
    }
    uint64_t at = r->L.lineno; /* first vector line, or the last line */
    if (header_finish(r, &hs, at) != 0)
        return -1;
    unsigned n_base = np_vec_columns(&r->h, NP_VEC_M_IN | NP_VEC_M_OUT | NP_VEC_M_REF, r->cols);
    /* Undeclared device results: decided by the first vector line. */
    if (!r->h.has_got && r->pending && count_tokens(s) == n_base + r->h.fields.n_out)
        r->h.has_got = 1;
    r->n_cols = np_vec_columns(&r->h,
                               NP_VEC_M_IN | NP_VEC_M_OUT | NP_VEC_M_REF | (r->h.has_got ? NP_VEC_M_GOT : 0u),
                               r->cols);
    if (r->h.has_got)
        snprintf(r->hint, sizeof r->hint, "; every line must carry the device's results");
    else
        snprintf(r->hint, sizeof r->hint, ", or %u with the device's results",
                 r->n_cols + r->h.fields.n_out);
    return 0;
}

int np_vec_read(np_vec_reader *r, np_vec_rec *rec)
{
    for (;;) {
        char *s = r->L.buf;
        if (r->pending) {
            r->pending = 0;
            while (is_blank(*s))
                s++;
        } else {
            int rc = lines_next(&r->L, &s);
            if (rc < 0)
                return -1;
            if (rc == 0) {
                if (r->n != r->h.count)
                    return lerr(&r->L, "truncated file: it ends after %llu vectors, but the header (line %llu) declares %llu",
                                (unsigned long long)r->n, (unsigned long long)r->count_line,
                                (unsigned long long)r->h.count);
                return 0;
            }
        }
        if (*s == '\0' || *s == '#')
            continue;
        if (r->n == r->h.count)
            return lerr(&r->L, "more vectors than the header's count %llu (line %llu)",
                        (unsigned long long)r->h.count, (unsigned long long)r->count_line);
        if (parse_cols(&r->L, s, r->cols, r->n_cols, rec->w, r->hint) != 0)
            return -1;
        rec->index = r->n++;
        rec->line = r->L.lineno;
        return 1;
    }
}

int np_vec_read_source(void *reader, np_vec_rec *rec) { return np_vec_read(reader, rec); }

void np_vec_close(np_vec_reader *r) { lines_close(&r->L); }

/* ------------------------------------------------------------------------- */
/* Device results reader. */

int np_vec_results_open(np_vec_results *rr, const char *path, const np_vec_header *h)
{
    memset(rr, 0, sizeof *rr);
    rr->h = h;
    rr->n_cols = np_vec_columns(h, NP_VEC_M_GOT, rr->cols);
    unsigned bits = 0;
    for (unsigned k = 0; k < rr->n_cols; k++)
        bits += rr->cols[k].bits;
    rr->packed_digits = hex_digits(bits);
    return lines_open(&rr->L, path);
}

/* A packed {out...} word of a unit with several outputs. */
static int results_packed(np_vec_results *rr, const char *s, np_vec_rec *rec)
{
    unsigned bits[NP_UNIT_MAX_FIELDS];
    size_t len = strlen(s);
    for (unsigned k = 0; k < rr->n_cols; k++)
        bits[k] = rr->cols[k].bits;
    for (size_t k = 0; k < len; k++)
        if (!hexval1[(unsigned char)s[k]])
            return lerr(&rr->L, "packed results word: non-hex digit '%c' in '%s'", s[k], s);
    if (unpack_hex(s, rr->packed_digits, bits, rr->n_cols, rec->w[NP_VEC_GOT]) != 0)
        return lerr(&rr->L, "packed results word '%s' out of range for %u bits", s,
                    sum_bits(bits, rr->n_cols));
    return 0;
}

int np_vec_results_read(np_vec_results *rr, np_vec_rec *rec)
{
    char *s;
    for (;;) {
        int rc = lines_next(&rr->L, &s);
        if (rc < 0)
            return -1;
        if (rc == 0) {
            if (rr->n != rr->h->count)
                return lerr(&rr->L, "results end after %llu transactions, but the vectors have %llu",
                            (unsigned long long)rr->n, (unsigned long long)rr->h->count);
            return 0;
        }
        if (*s == '\0' || *s == '#' || (s[0] == '/' && s[1] == '/'))
            continue;
        if (*s == '@') {
            uint64_t a;
            if (np_parse_u64_hex(s + 1, 16, 0, UINT64_MAX, &a) != 0 || a != rr->n)
                return lerr(&rr->L, "address '%s': only the next transaction's address (@%llx) is allowed",
                            s, (unsigned long long)rr->n);
            continue;
        }
        if (rr->n == rr->h->count)
            return lerr(&rr->L, "more results than vectors (%llu)", (unsigned long long)rr->h->count);
        if (rr->n_cols > 1 && count_tokens(s) == 1 && strlen(s) == rr->packed_digits)
            rc = results_packed(rr, s, rec);
        else
            rc = parse_cols(&rr->L, s, rr->cols, rr->n_cols, rec->w, NULL);
        if (rc != 0)
            return -1;
        rr->n++;
        return 1;
    }
}

void np_vec_results_close(np_vec_results *rr) { lines_close(&rr->L); }

/* ------------------------------------------------------------------------- */
/* Writer. */

static int werr(np_vec_writer *w, const char *what)
{
    snprintf(w->err, sizeof w->err, "%.300s: %.80s: %.100s", w->atomic ? w->path : "<stdout>", what,
             strerror(errno));
    return -1;
}

static int is_packed(np_vec_format fmt) { return fmt == NP_VEC_READMEMH || fmt == NP_VEC_COE; }

/* Bits of the packed word {1'b1 valid, IN..., OUT...}: lists it in bits[]; returns the count. */
static unsigned word_layout(const np_vec_writer *w, unsigned *bits)
{
    bits[0] = 1;
    for (unsigned k = 0; k < w->n_cols; k++)
        bits[k + 1u] = w->cols[k].bits;
    return w->n_cols + 1u;
}

/* "[56] valid [55:40] x ..." */
static void word_ruler(const np_vec_writer *w, char *buf, size_t len)
{
    unsigned pos = w->word_bits, at = 0;
    for (unsigned k = 0; k <= w->n_cols && at < len; k++) {
        unsigned b = k ? w->cols[k - 1u].bits : 1u;
        const char *name = k ? w->cols[k - 1u].name : "valid";
        int n = b == 1 ? snprintf(buf + at, len - at, "%s[%u] %s", k ? " " : "", pos - 1u, name)
                       : snprintf(buf + at, len - at, "%s[%u:%u] %s", k ? " " : "", pos - 1u,
                                  pos - b, name);
        if (n < 0)
            break;
        at += (unsigned)n;
        pos -= b;
    }
}

static void write_header(np_vec_writer *w)
{
    const np_vec_header *h = w->h;
    const char *c = w->fmt == NP_VEC_TEXT ? "#" : w->fmt == NP_VEC_COE ? ";" : "//";
    FILE *f = w->f;
    fprintf(f, "%s noisepipe %s %d\n", c, w->fmt == NP_VEC_RESULTS ? "results" : "vectors",
            NP_VEC_VERSION);
    fprintf(f, "%s unit %s\n%s config %s\n", c, h->unit->name, c, h->cfg_text);
    if (h->has_seed)
        fprintf(f, "%s seed %llu\n", c, (unsigned long long)h->seed);
    if (h->level)
        fprintf(f, "%s level %u\n", c, h->level);
    fprintf(f, "%s count %llu\n", c, (unsigned long long)h->count);
    for (unsigned k = 0; k < w->n_cols; k++) {
        char decl[256];
        col_decl(&w->cols[k], decl, sizeof decl);
        fprintf(f, "%s field %s\n", c, decl);
    }
    if (h->sources[0])
        fprintf(f, "%s sources %s\n", c, h->sources);
    if (is_packed(w->fmt)) {
        char ruler[NP_VEC_MAX_COLS * 32];
        word_ruler(w, ruler, sizeof ruler);
        fprintf(f, "%s word %u bits = %u hex digits per transaction, MSB first: %s\n", c,
                w->word_bits, hex_digits(w->word_bits), ruler);
    }
    if (w->fmt == NP_VEC_COE)
        fputs("memory_initialization_radix=16;\nmemory_initialization_vector=\n", f);
}

int np_vec_writer_open(np_vec_writer *w, const char *path, np_vec_format fmt,
                       const np_vec_header *h)
{
    memset(w, 0, sizeof *w);
    w->fmt = fmt;
    w->h = h;
    unsigned mask = fmt == NP_VEC_TEXT ? NP_VEC_M_IN | NP_VEC_M_OUT | NP_VEC_M_REF |
                                             (h->has_got ? NP_VEC_M_GOT : 0u)
                    : fmt == NP_VEC_RESULTS ? NP_VEC_M_GOT
                                            : NP_VEC_M_IN | NP_VEC_M_OUT;
    w->n_cols = np_vec_columns(h, mask, w->cols);
    unsigned bits[NP_VEC_MAX_COLS + 1];
    w->word_bits = sum_bits(bits, word_layout(w, bits));
    if (!path || strcmp(path, "-") == 0) {
        w->f = stdout;
    } else {
        if (strlen(path) >= sizeof w->path) {
            snprintf(w->err, sizeof w->err, "%.64s...: path too long", path);
            return -1;
        }
        snprintf(w->path, sizeof w->path, "%s", path);
        snprintf(w->tmp, sizeof w->tmp, "%s.tmp%ld", path, (long)getpid());
        w->atomic = 1;
        int fd = open(w->tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd < 0 || !(w->f = fdopen(fd, "w"))) {
            snprintf(w->err, sizeof w->err, "cannot write %.300s: %.100s", path, strerror(errno));
            if (fd >= 0) {
                close(fd);
                unlink(w->tmp);
            }
            return -1;
        }
        setvbuf(w->f, NULL, _IOFBF, (size_t)1 << 16);
    }
    write_header(w);
    return 0;
}

/* Write v as exactly nd hex digits at p (nd <= 16). */
static void put_hex(char *p, uint64_t v, unsigned nd)
{
    for (unsigned k = nd; k-- > 0; v >>= 4)
        p[k] = hexdigit[v & 15u];
}

int np_vec_writer_put(np_vec_writer *w, const np_vec_rec *rec)
{
    char *p = w->line;
    if (is_packed(w->fmt)) {
        uint64_t vals[NP_VEC_MAX_COLS + 1];
        unsigned bits[NP_VEC_MAX_COLS + 1];
        unsigned n = word_layout(w, bits);
        vals[0] = 1; /* valid */
        for (unsigned k = 0; k < w->n_cols; k++)
            vals[k + 1u] = rec->w[w->cols[k].kind][w->cols[k].field];
        p += pack_hex(p, vals, bits, n);
        if (w->fmt == NP_VEC_COE)
            *p++ = w->n + 1u == w->h->count ? ';' : ',';
    } else {
        for (unsigned k = 0; k < w->n_cols; k++) {
            const np_vec_col *c = &w->cols[k];
            put_hex(p, rec->w[c->kind][c->field] & np_vec_mask(c->bits), c->digits);
            p += c->digits;
            *p++ = ' ';
        }
        p--; /* the last blank */
    }
    *p++ = '\n';
    w->n++;
    if (fwrite(w->line, 1, (size_t)(p - w->line), w->f) != (size_t)(p - w->line))
        return werr(w, "write error");
    return 0;
}

int np_vec_writer_close(np_vec_writer *w, int commit)
{
    int rc = 0;
    if (commit && w->n != w->h->count) {
        snprintf(w->err, sizeof w->err, "%.300s: wrote %llu transactions, but the header says %llu",
                 w->atomic ? w->path : "<stdout>", (unsigned long long)w->n,
                 (unsigned long long)w->h->count);
        rc = -1;
    }
    if (!w->atomic) {
        if ((fflush(w->f) != 0 || ferror(w->f)) && rc == 0)
            rc = werr(w, "write error");
        return rc;
    }
    int bad = ferror(w->f);
    if ((fclose(w->f) != 0 || bad) && rc == 0)
        rc = werr(w, "write error");
    w->f = NULL;
    if (commit && rc == 0 && rename(w->tmp, w->path) != 0)
        rc = werr(w, "cannot rename the finished file into place");
    if (!commit || rc != 0)
        unlink(w->tmp);
    return rc;
}
