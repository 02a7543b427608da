/* SPDX-License-Identifier: MIT */
/*
 * vec_read.c - the vector file format's one reader and its device results
 * reader: header lines, columns, every message naming FILE:LINE and, for a
 * field, its column. docs/vectors.md is the specification.
 */
#include "np_vec.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

#include "np_common.h"
#include "vec_internal.h"

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
    if (L->lineno == 1 && n >= 3 && (unsigned char)b[0] == 0xef && (unsigned char)b[1] == 0xbb &&
        (unsigned char)b[2] == 0xbf)
        return lerr(L, "the file starts with a UTF-8 byte-order mark (an editor's BOM): save it as plain text "
                       "without one (e.g. sed -i '1s/^\\xEF\\xBB\\xBF//' FILE)");
    while (n > 0 && (b[n - 1] == '\n' || b[n - 1] == '\r' || b[n - 1] == ' ' || b[n - 1] == '\t'))
        n--;
    b[n] = '\0';
    if (memchr(b, '\r', (size_t)n))
        return lerr(L, "carriage return inside a line: the file has CR-only (classic Mac) line endings; "
                       "convert them to LF (tr '\\r' '\\n' < FILE)");
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
        unsigned d = np__vec_hexval1[(unsigned char)tok[k]];
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
 * parse_cols_checked finds and names the first fault; parse_cols below is
 * the one pass that well-formed lines take, falling back to it on any doubt.
 */
static int parse_cols_checked(np_vec_lines *L, char *s, const np_vec_col *cols, unsigned n,
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

/*
 * One pass over the line: each token's hex digits are accumulated while it
 * is scanned (np__vec_hexval1 is 0 for a non-digit, NUL included). Exactly
 * n tokens of exactly c->digits digits each, in range: the values are
 * stored and the line is done. Anything else goes to parse_cols_checked,
 * which parses the line again and says what is wrong (same values, same
 * messages).
 */
static int parse_cols(np_vec_lines *L, char *s, const np_vec_col *cols, unsigned n,
                      uint64_t (*w)[NP_UNIT_MAX_FIELDS], const char *extra_hint)
{
    const unsigned char *p = (const unsigned char *)s;
    for (unsigned k = 0; k < n; k++) {
        const np_vec_col *c = &cols[k];
        while (*p == ' ' || *p == '\t')
            p++;
        const unsigned char *tok = p;
        uint64_t acc = 0;
        unsigned d;
        while ((d = np__vec_hexval1[*p]) != 0) {
            acc = acc << 4 | (uint64_t)(d - 1u);
            p++;
        }
        if ((size_t)(p - tok) != c->digits || (*p != '\0' && *p != ' ' && *p != '\t') ||
            (acc & ~np_vec_mask(c->bits)) != 0)
            return parse_cols_checked(L, s, cols, n, w, extra_hint);
        w[c->kind][c->field] = acc;
    }
    while (*p == ' ' || *p == '\t')
        p++;
    return *p == '\0' ? 0 : parse_cols_checked(L, s, cols, n, w, extra_hint);
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
    hdr_line reg[NP_UNIT_MAX_REGS + 1];
    unsigned n_reg;
    uint64_t first_line; /* first non-blank line */
    int first_slashes;   /* it starts with "//": a $readmemh or results file */
    int first_coe;       /* it starts with "memory_initialization_radix" or a ";" comment: a Xilinx .coe file */
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
    if (strcmp(key, "reg") == 0) {
        if (hs->n_reg == NP_UNIT_MAX_REGS + 1)
            return lerr(&r->L, "too many '# reg' lines (at most %u)", NP_UNIT_MAX_REGS);
        hdr_line *g = &hs->reg[hs->n_reg++];
        g->line = r->L.lineno;
        normalize(g->text, sizeof g->text, rest);
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
        np__vec_col_decl(&cols[k], want, sizeof want);
        if (strcmp(hs->field[k].text, want) != 0)
            return hdr_err(r, hs->field[k].line,
                           "field %s: header declares '%s', but unit %s (%s) has '%s'",
                           cols[k].name, hs->field[k].text, r->h.unit->name, r->h.cfg_text, want);
    }
    if (hs->n_field > n_all)
        return hdr_err(r, hs->field[n_all].line, "field: '%s' is not a field of unit %s",
                       hs->field[n_all].text, r->h.unit->name);
    if (hs->n_field != n_base && hs->n_field != n_all) {
        np__vec_col_decl(&cols[hs->n_field], want, sizeof want);
        return hdr_err(r, at, "missing header line '# field %s'", want);
    }
    r->h.has_got = hs->n_field == n_all;
    return 0;
}

/*
 * Check the '# reg' lines against the registers the configuration holds
 * (np_unit.regs): each one, in order, exactly as the writer prints it, and
 * none missing or extra, so the registers a testbench loads from the file are
 * the ones the expected outputs were computed with.
 */
static int header_regs(np_vec_reader *r, const hdr_state *hs)
{
    char want[NP_UNIT_MAX_REGS][96];
    unsigned n = np__vec_reg_lines(&r->h, want, NP_UNIT_MAX_REGS);
    for (unsigned k = 0; k < n && k < hs->n_reg; k++)
        if (strcmp(hs->reg[k].text, want[k]) != 0) {
            const char *sp = strchr(want[k], ' ');
            return hdr_err(r, hs->reg[k].line, "register %.*s: header says '%s', but unit %s (%s) holds '%s'",
                           (int)(sp ? sp - want[k] : (ptrdiff_t)strlen(want[k])), want[k], hs->reg[k].text,
                           r->h.unit->name, r->h.cfg_text, want[k]);
        }
    if (hs->n_reg > n)
        return hdr_err(r, hs->reg[n].line, "reg: '%s' is not a register of unit %s (%s)%s", hs->reg[n].text,
                       r->h.unit->name, r->h.cfg_text, n ? "" : ", which has no register block");
    if (hs->n_reg < n)
        return hdr_err(r, hs->n_reg ? hs->reg[hs->n_reg - 1].line : hs->config.line,
                       "missing header line '# reg %s' (unit %s (%s) has %u registers; the file gives %u)",
                       want[hs->n_reg], r->h.unit->name, r->h.cfg_text, n, hs->n_reg);
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
                       : hs->first_coe   ? " (this is a Xilinx .coe export, for initialising a block RAM;"
                                           " give the text vector file it was written from)"
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
    if (header_regs(r, hs) != 0)
        return -1;
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
            hs.first_coe = s[0] == ';' || strncmp(s, "memory_initialization_radix", 27) == 0;
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
    rr->packed_digits = np__vec_hex_digits(bits);
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
        if (!np__vec_hexval1[(unsigned char)s[k]])
            return lerr(&rr->L, "packed results word: non-hex digit '%c' in '%s'", s[k], s);
    if (np__vec_unpack_hex(s, rr->packed_digits, bits, rr->n_cols, rec->w[NP_VEC_GOT]) != 0)
        return lerr(&rr->L, "packed results word '%s' out of range for %u bits", s,
                    np__vec_sum_bits(bits, rr->n_cols));
    return 0;
}

/*
 * A comment line of a results file. The header that `device --format
 * results` writes ("// unit U", "// config ...", "// seed S", "// level L",
 * "// count N", "// reg NAME HEX FORMAT") must describe the vectors being checked: results of another
 * unit, configuration or vector set are refused, naming the line. Other
 * comments, and results files without a header, are accepted.
 */
static int results_header_line(np_vec_results *rr, const char *s)
{
    while (*s == ' ')
        s++;
    const np_vec_header *h = rr->h;
    char want[320];
    const char *key = NULL, *val = NULL;
    static const char *const keys[] = { "unit ", "config ", "seed ", "level ", "count " };
    for (unsigned k = 0; k < sizeof keys / sizeof keys[0] && !key; k++)
        if (strncmp(s, keys[k], strlen(keys[k])) == 0) {
            key = keys[k];
            val = s + strlen(keys[k]);
        }
    if (!key && strncmp(s, "reg ", 4) == 0) {
        /* A register line (np_unit.regs): the register of that name must hold that value and format. */
        char regs[NP_UNIT_MAX_REGS][96], got[96];
        unsigned n = np__vec_reg_lines(h, regs, NP_UNIT_MAX_REGS);
        normalize(got, sizeof got, s + 4);
        size_t nl = strcspn(got, " ");
        for (unsigned k = 0; k < n; k++)
            if (strncmp(regs[k], got, nl) == 0 && regs[k][nl] == ' ') {
                if (strcmp(regs[k], got) == 0)
                    return 0;
                return lerr(&rr->L, "register %.*s: the results are for '%s', the vectors for '%s': results of "
                            "other registers", (int)nl, got, got, regs[k]);
            }
        return lerr(&rr->L, "reg: '%s' is not a register of unit %s (%s)", got, h->unit->name, h->cfg_text);
    }
    if (!key)
        return 0;
    if (strcmp(key, "unit ") == 0)
        snprintf(want, sizeof want, "%s", h->unit->name);
    else if (strcmp(key, "config ") == 0)
        snprintf(want, sizeof want, "%s", h->cfg_text);
    else if (strcmp(key, "seed ") == 0 && h->has_seed)
        snprintf(want, sizeof want, "%llu", (unsigned long long)h->seed);
    else if (strcmp(key, "level ") == 0 && h->level)
        snprintf(want, sizeof want, "%u", h->level);
    else if (strcmp(key, "count ") == 0)
        snprintf(want, sizeof want, "%llu", (unsigned long long)h->count);
    else
        return 0; /* the vectors do not say: nothing to compare */
    size_t n = strlen(val);
    while (n && val[n - 1] == ' ')
        n--;
    if (strlen(want) != n || strncmp(val, want, n) != 0)
    {
        int kl = (int)strlen(key) - 1;
        return lerr(&rr->L, "field '%.*s': the results are for %.*s %.*s, the vectors for %.*s %s: results of "
                    "other vectors", kl, key, kl, key, (int)n, val, kl, key, want);
    }
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
        if (*s == '#' || (s[0] == '/' && s[1] == '/')) {
            if (results_header_line(rr, s + (*s == '#' ? 1 : 2)) != 0)
                return -1;
            continue;
        }
        if (*s == '\0')
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
