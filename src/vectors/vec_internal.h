/* SPDX-License-Identifier: MIT */
/*
 * vec_internal.h - what the vector file's reader (vec_read.c) and writer
 * (vec_write.c) share with vec_pack.c: hex digit tables, column declarations
 * and packed words. Not installed; np__vec_ names are private to np_tools.
 */
#ifndef NP_VEC_INTERNAL_H
#define NP_VEC_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "np_vec.h"

/* Hex digit value + 1, 0 for a character that is not a hex digit. */
extern const unsigned char np__vec_hexval1[256];
extern const char np__vec_hexdigit[16];

/* Hex digits of a bits-wide field: ceil(bits / 4). */
unsigned np__vec_hex_digits(unsigned bits);
/* "NAME KIND BITS FORMAT": a column as a "# field" header line declares it. */
void np__vec_col_decl(const np_vec_col *c, char *buf, size_t len);
/*
 * The unit's registers for the header's configuration (np_unit.regs) as
 * '# reg' lines declare them, "NAME HEX FORMAT", into lines[0..max) of
 * len bytes each; returns the count (0: no register block).
 */
unsigned np__vec_reg_lines(const np_vec_header *h, char (*lines)[96], unsigned max);
unsigned np__vec_sum_bits(const unsigned *bits, unsigned n);
/*
 * Packed words: {vals[0], ..., vals[n-1]} (vals[k] is bits[k] wide, vals[0]
 * most significant) as ceil(total/4) hex digits at p; returns the digit count.
 */
unsigned np__vec_pack_hex(char *p, const uint64_t *vals, const unsigned *bits, unsigned n);
/* Its inverse for a token of exactly nd = ceil(total/4) hex digits: 0, or -1 when bits above the total are set. */
int np__vec_unpack_hex(const char *tok, unsigned nd, const unsigned *bits, unsigned n,
                       uint64_t *vals);

#endif /* NP_VEC_INTERNAL_H */
