/* SPDX-License-Identifier: MIT */
/*
 * np_hashn.h - the table-free lattice hash and the multiply-free gradient of
 * Perlin, "Noise Hardware" (shared/seeds/002) extended to n = 2..5
 * dimensions. The seed defines them for n = 3 only (np_hash.h); for n = 3
 * these functions ARE np_hash6 and np_grad_decode (they call them).
 *
 * HASH. The 3-D hash sums eight lookups of the seed's table T (8 entries of
 * 6 bits, indexed by 3 bits); lookup B reads bit B of the three coordinates,
 * rotated by B: (i,j,k), (j,k,i), (k,i,j), (i,j,k), ... That is one stream
 * of the 24 coordinate bits, bit plane after bit plane, each plane's
 * coordinates rotated by the plane number, cut into triples:
 *
 *   stream position m = n*B + r  (B = 0..7 the bit plane, r = 0..n-1)
 *   holds bit B of coordinate c_((B + r) mod n)
 *   lookup l = 0 .. ceil(8n/3)-1 reads stream bits 3l, 3l+1, 3l+2 as the
 *   index 4*s[3l] + 2*s[3l+1] + s[3l+2] of T (bits past 8n are 0)
 *   h = (sum of the lookups) mod 64
 *
 * For n = 3 this is the seed's hash exactly (ndim.hash3_is_seed checks it
 * over all 2^24 points). For n = 2 there are 6 lookups (the last reads one
 * coordinate bit and two 0s), n = 4 has 11 (the last: two bits and a 0),
 * n = 5 has 14 (the last: one bit). Every coordinate bit is read by exactly
 * one lookup, so over a tile (all 256^n points) the lookups are independent
 * and the distribution of h is the mod-64 convolution of the lookups' own
 * distributions (each uniform over the T entries its bits reach):
 * np_hashn_tile_counts() computes it exactly for any n (docs/noise-nd.md
 * prints it; ndim.hash_distribution checks it against enumeration for n = 2
 * and n = 3).
 *
 * Hardware: ceil(8n/3) lookups 3 -> 6 (fixed logic, as in 3-D; a padded
 * lookup is smaller logic, priced as a full one) and an adder tree of
 * ceil(8n/3) - 1 six-bit adders whose carries out of bit 5 are dropped.
 *
 * GRADIENT. Coefficients in {-1, 0, +1} from the 6-bit index h, a select
 * and a conditional negate per axis, no multiplier. Every sign bit has the
 * same polarity: 1 gives -1, 0 gives +1. Axis a is input field a (x, y, z,
 * w, v):
 *   n = 2: b2 = 0: an axis, (+-1, 0) or (0, +-1): b0 picks the axis,
 *          b1 the sign (1 = negative); b2 = 1: a diagonal (+-1, +-1),
 *          sign of axis a = bit a (1 = negative). 8 gradients, b5..b3
 *          unused.
 *   n = 3: Appendix B (np_grad_decode): 12 two-term, 8 three-term.
 *   n = 4: 2 b1 + b0 = the axis whose coefficient is 0; the other three axes,
 *          in increasing order, take the signs b2, b3, b4 (1 = negative).
 *          32 gradients, each twice (b5 unused): the 4-D set of three-term
 *          gradients (every permutation of (0, +-1, +-1, +-1)).
 *   n = 5: every axis non-zero, sign of axis a = bit a (1 = negative):
 *          the 32 diagonals (+-1, ..., +-1), each twice (b5 unused).
 *          (A zero axis among five would need h mod 5: not a power of two.)
 * The largest |G|_2 is sqrt(2), sqrt(3), sqrt(3), sqrt(5) for n = 2..5 and
 * the largest number of non-zero coefficients K = 2, 3, 3, 5.
 */
#ifndef NP_HASHN_H
#define NP_HASHN_H

#include <stdint.h>

#include "np_hash.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    NP_HASHN_MIN_DIMS = 2,
    NP_HASHN_MAX_DIMS = 5,
    NP_HASHN_BITS = 6,   /* the index h */
    NP_HASHN_COORD = 8   /* each coordinate is read mod 256 */
};

/* Lookups of the n-D hash: ceil(8n / 3) (8 for n = 3). */
static inline unsigned np_hashn_lookups(unsigned n) { return (8u * n + 2u) / 3u; }

/*
 * 6-bit index (u6) of the lattice point c[0..n) (each u8), n = 2..5: n = 3
 * np_hash6, the others np_hashn_table (the same bits as np_hashn_stream).
 */
uint8_t np_hashn(unsigned n, const uint8_t *c);

/*
 * The specification: the same by the generic bit stream above, for n = 3 as
 * well (the tests compare it with np_hash6 over all 2^24 points, and with
 * np_hashn_table).
 */
uint8_t np_hashn_stream(unsigned n, const uint8_t *c);

/*
 * Tables: the fast path, np_hashn_stream's bits (ndim.hash_tables checks
 * every entry of every table, and random points). Every lookup reads bits of
 * one group of three bit planes (3n stream bits are exactly n lookups, and
 * every plane is n stream bits), so h is the sum mod 64 of three partial
 * sums, each a function of planes 0..2, 3..5 and 6..7 of the n coordinates:
 * three tables of 2^(3n) u6 entries per n (n = 5: 3 x 32 KB), built at the
 * first call (thread-safe). n = 3: np_hash6_fast.
 */
uint8_t np_hashn_table(unsigned n, const uint8_t *c);

/*
 * Gradient coefficients of index h in n dimensions: coef[0..n) in {-1, 0, 1}.
 * n = 3: np_grad_decode's (cx, cy, cz).
 */
void np_gradn_decode(unsigned n, uint8_t h, int8_t *coef);

/*
 * The low bits of h that np_gradn_decode reads: 3 at n = 2 (h[2:0]), 6 at
 * n = 3 (Appendix B's fields), 5 at n = 4 and 5 (h[4:0]). Only these bits of
 * the hash reach a gradient, so the hash's adder tree (a sum mod 64) needs
 * only its low bits' part: a sum mod 2^b (the carries go upward only).
 * ndim.grad_index_bits checks that no higher bit changes a coefficient.
 */
static inline unsigned np_gradn_index_bits(unsigned n) { return n == 2u ? 3u : n == 3u ? 6u : 5u; }

/* Largest number of non-zero coefficients K and largest |G|^2 of the n-D set. */
unsigned np_gradn_max_terms(unsigned n);
unsigned np_gradn_max_norm2(unsigned n);

/*
 * Exact counts of each 6-bit index over all 256^n lattice points of a tile
 * (the convolution above), count[64]; the total is 2^(8n) (exact in double
 * up to 2^53, so n <= 5 is exact with 2^40).
 */
void np_hashn_tile_counts(unsigned n, double count[64]);

/* Of those counts: the fewest, the most, the total and chi^2 against uniform (63 degrees of freedom). */
void np_hashn_tile_summary(unsigned n, double *fewest, double *most, double *total, double *chi2);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_HASHN_H */
