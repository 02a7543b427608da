/* SPDX-License-Identifier: MIT */
/*
 * vec_pack.c - the vector file format's columns and packed words: which
 * columns a unit's file has (np_vec_columns), how a "# field" line declares
 * one, the fields concatenated into one hex word for $readmemh and .coe, and
 * the hex digit tables the reader and the writer share (vec_internal.h).
 * docs/vectors.md is the specification.
 */
#include "np_vec.h"

#include <string.h>

#include "vec_internal.h"

static const char *const kind_name[NP_VEC_KINDS] = { "in", "out", "ref", "got" };
static const char *const kind_suffix[NP_VEC_KINDS] = { "", "", ".ref", ".got" };

/* Hex digit value + 1, 0 for a character that is not a hex digit. */
const unsigned char np__vec_hexval1[256] = {
    ['0'] = 1,  ['1'] = 2,  ['2'] = 3,  ['3'] = 4,  ['4'] = 5,  ['5'] = 6,  ['6'] = 7,
    ['7'] = 8,  ['8'] = 9,  ['9'] = 10, ['a'] = 11, ['b'] = 12, ['c'] = 13, ['d'] = 14,
    ['e'] = 15, ['f'] = 16, ['A'] = 11, ['B'] = 12, ['C'] = 13, ['D'] = 14, ['E'] = 15,
    ['F'] = 16,
};
const char np__vec_hexdigit[16] = "0123456789abcdef";

void np_vec_unit_names(char *buf, size_t len)
{
    size_t at = 0;
    buf[0] = '\0';
    const np_unit *u;
    for (size_t i = 0; (u = np_unit_at(i)) != NULL && at < len; i++)
        at += (size_t)snprintf(buf + at, len - at, "%s%s", i ? ", " : "", u->name);
}

unsigned np__vec_hex_digits(unsigned bits) { return (bits + 3u) / 4u; }

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
            c->digits = np__vec_hex_digits(c->bits);
            snprintf(c->format, sizeof c->format, "%s", kind == NP_VEC_REF ? "binary64" : f->format);
        }
    }
    return n;
}

/* "NAME KIND BITS FORMAT": a column as a "# field" header line declares it. */
void np__vec_col_decl(const np_vec_col *c, char *buf, size_t len)
{
    snprintf(buf, len, "%.23s %s %u %.31s", c->name, kind_name[c->kind], c->bits, c->format);
}

unsigned np__vec_reg_lines(const np_vec_header *h, char (*lines)[96], unsigned max)
{
    np_unit_reg regs[NP_UNIT_MAX_REGS];
    if (!h->unit->regs)
        return 0;
    size_t n = h->unit->regs(&h->cfg, regs, NP_UNIT_MAX_REGS);
    if (n > NP_UNIT_MAX_REGS)
        n = NP_UNIT_MAX_REGS;
    if (n > max)
        n = max;
    for (size_t k = 0; k < n; k++)
        snprintf(lines[k], 96, "%.15s %0*llx %.23s", regs[k].name, (int)np__vec_hex_digits(regs[k].bits),
                 (unsigned long long)regs[k].value, regs[k].format);
    return (unsigned)n;
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

unsigned np__vec_sum_bits(const unsigned *bits, unsigned n)
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
unsigned np__vec_pack_hex(char *p, const uint64_t *vals, const unsigned *bits, unsigned n)
{
    uint64_t limb[PACK_LIMBS] = { 0 };
    unsigned pos = 0;
    for (unsigned k = n; k-- > 0;) {
        limbs_put(limb, pos, bits[k], vals[k]);
        pos += bits[k];
    }
    unsigned nd = np__vec_hex_digits(pos);
    for (unsigned d = 0; d < nd; d++)
        p[nd - 1u - d] = np__vec_hexdigit[limbs_get(limb, 4u * d, 4u)];
    return nd;
}

/*
 * Inverse of pack_hex for a token of exactly ceil(total/4) hex digits that
 * the caller checked: 0, or -1 when bits above the total are set.
 */
int np__vec_unpack_hex(const char *tok, unsigned nd, const unsigned *bits, unsigned n,
                      uint64_t *vals)
{
    uint64_t limb[PACK_LIMBS] = { 0 };
    unsigned total = np__vec_sum_bits(bits, n);
    for (unsigned d = 0; d < nd; d++)
        limbs_put(limb, 4u * d, 4u, (uint64_t)(np__vec_hexval1[(unsigned char)tok[nd - 1u - d]] - 1u));
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
