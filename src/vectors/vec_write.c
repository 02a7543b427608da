/* SPDX-License-Identifier: MIT */
/*
 * vec_write.c - the vector file format's one writer: text, $readmemh, .coe
 * and results files, written to a temporary file and renamed into place.
 * docs/vectors.md is the specification.
 */
#include "np_vec.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "vec_internal.h"

/* ------------------------------------------------------------------------- */
/* Writer. */

static int werr(np_vec_writer *w, const char *what)
{
    snprintf(w->err, sizeof w->err, "%.300s: %.80s: %.100s", w->out.is_stdout ? "<stdout>" : w->out.path, what,
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
    char regs[NP_UNIT_MAX_REGS][96];
    unsigned n_regs = np__vec_reg_lines(h, regs, NP_UNIT_MAX_REGS);
    for (unsigned k = 0; k < n_regs; k++)
        fprintf(f, "%s reg %s\n", c, regs[k]);
    if (h->has_seed)
        fprintf(f, "%s seed %llu\n", c, (unsigned long long)h->seed);
    if (h->level)
        fprintf(f, "%s level %u\n", c, h->level);
    fprintf(f, "%s count %llu\n", c, (unsigned long long)h->count);
    for (unsigned k = 0; k < w->n_cols; k++) {
        char decl[256];
        np__vec_col_decl(&w->cols[k], decl, sizeof decl);
        fprintf(f, "%s field %s\n", c, decl);
    }
    if (h->sources[0])
        fprintf(f, "%s sources %s\n", c, h->sources);
    if (is_packed(w->fmt)) {
        char ruler[NP_VEC_MAX_COLS * 32];
        word_ruler(w, ruler, sizeof ruler);
        fprintf(f, "%s word %u bits = %u hex digits per transaction, MSB first: %s\n", c,
                w->word_bits, np__vec_hex_digits(w->word_bits), ruler);
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
    w->word_bits = np__vec_sum_bits(bits, word_layout(w, bits));
    if (np_outfile_open(&w->out, path, "w") != 0) {
        snprintf(w->err, sizeof w->err, "cannot write %.400s", w->out.err);
        return -1;
    }
    w->f = w->out.f;
    write_header(w);
    return 0;
}

/* Write v as exactly nd hex digits at p (nd <= 16). */
static void put_hex(char *p, uint64_t v, unsigned nd)
{
    for (unsigned k = nd; k-- > 0; v >>= 4)
        p[k] = np__vec_hexdigit[v & 15u];
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
        p += np__vec_pack_hex(p, vals, bits, n);
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
                 w->out.is_stdout ? "<stdout>" : w->out.path, (unsigned long long)w->n,
                 (unsigned long long)w->h->count);
        rc = -1;
    }
    if (np_outfile_close(&w->out, commit && rc == 0) != 0 && rc == 0) {
        snprintf(w->err, sizeof w->err, "%.400s", w->out.err);
        rc = -1;
    }
    w->f = NULL;
    return rc;
}
