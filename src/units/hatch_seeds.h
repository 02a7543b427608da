/* SPDX-License-Identifier: MIT */
/*
 * hatch_seeds.h - the seed sets of the hatching unit (seed 003, Szécsi &
 * Szirányi, RPTAM §4): de Bruijn sequences B(4, K) and their bit patterns.
 *
 * A seed set of N = 4^K seeds is two N-bit words b_u, b_v. Bit j of the
 * pattern (j = 0 first after the binary point) is bit N-1-j of the word, so
 * seed i is, per axis, exactly
 *
 *     s_i = rotl_N(b, i) / (2^N - 1)            (a rational, not a dyadic fraction)
 *
 * and D s_i = frac(2 s_i) = s_{i+1}: the recursive nesting of §4. The u and v
 * bits form base-4 digits d_j = 2 b_u,j + b_v,j (PIN bit order,
 * design/scene-pipeline.md). When d_0 .. d_{N-1} is a cyclic de Bruijn
 * sequence B(4, K), the first K digits of the seeds run through every K-digit
 * string once: one seed in each cell of the 2^K x 2^K grid (np_seeds_cells
 * checks it exactly, in integers).
 *
 * Quality is the minimum toroidal distance between two seeds (the spacing),
 * computed exactly in integers: squared distances are (du^2 + dv^2) / (2^N-1)^2
 * with du, dv < 2^63, so the numerator fits 128 bits; only the final square
 * root is a double.
 */
#ifndef NP_HATCH_SEEDS_H
#define NP_HATCH_SEEDS_H

#include <stddef.h>
#include <stdint.h>

#include "np_fixed.h"
#include "np_hatch.h"

#ifdef __cplusplus
extern "C" {
#endif

struct np_rng;

enum { NP_SEEDS_KMAX = 3, NP_SEEDS_NMAX = 64 };

typedef struct np_seedset {
    unsigned K;          /* order: N = 4^K seeds, 1 <= K <= 3 */
    unsigned n;          /* N */
    uint64_t bu, bv;     /* the N-bit patterns (bit N-1 first after the point) */
} np_seedset;

/* rotl of an n-bit word by i (the unit's np_hatch_rotl). */
static inline uint64_t np_seed_rotl(uint64_t b, unsigned i, unsigned n) { return np_hatch_rotl(b, i, n); }

/* N = 4^K. */
unsigned np_seeds_n(unsigned K);

/* digits[0..N) (values 0..3) -> the set's bit patterns (PIN d = 2 b_u + b_v). */
void np_seeds_from_digits(unsigned K, const uint8_t *digits, np_seedset *s);
/* The set's digits (inverse of np_seeds_from_digits). */
void np_seeds_to_digits(const np_seedset *s, uint8_t *digits);

/* The lexicographically least de Bruijn sequence B(4, K) (Fredricksen-Kessler-Maiorana). */
void np_seeds_fkm(unsigned K, uint8_t *digits);

/* Is digits[0..N) a cyclic de Bruijn sequence B(4, K) (every K-window once)? 1 or 0. */
int np_seeds_is_debruijn(unsigned K, const uint8_t *digits);

/*
 * The cell proof: for every seed i the exact cell (floor(2^K s_iu),
 * floor(2^K s_iv)) from the rationals, counted into cells[2^K * 2^K] (row v,
 * column u; may be NULL). Returns the number of cells that do not hold
 * exactly one seed (0: one seed per cell).
 */
unsigned np_seeds_cells(const np_seedset *s, unsigned *cells);

/*
 * Minimum toroidal distance between two seeds: the exact squared numerator
 * (du^2 + dv^2 in units of 1/(2^N-1)) in *num2 (may be NULL), the distance
 * as a double returned; the pair in *pi, *pj (may be NULL).
 */
double np_seeds_spacing(const np_seedset *s, np_u128 *num2, unsigned *pi, unsigned *pj);

/* Seed i's coordinate on one axis as a double (display only). */
double np_seeds_coord(uint64_t b, unsigned i, unsigned n);

/*
 * The number of cyclic de Bruijn sequences B(4, K) by the BEST theorem:
 * (4!)^(4^(K-1)) / 4^K, as a double (exact for K <= 2: 20,736).
 */
double np_seeds_best_count(unsigned K);

/*
 * Enumerate every cyclic B(4, K) sequence once (Eulerian circuits of the
 * de Bruijn graph of order K-1, each rotated to start after its window 0^K),
 * calling fn(digits, user) for each; fn returns nonzero to stop. Returns how
 * many were visited. Practical for K <= 2 only (K = 3: ~1.9e20).
 */
uint64_t np_seeds_enumerate(unsigned K, int (*fn)(const uint8_t *digits, void *user), void *user);

/*
 * A uniformly random cyclic B(4, K) sequence: a random spanning arborescence
 * toward node 0 (Wilson's algorithm) and random orders of the other exit
 * edges (the BEST construction), then the circuit it fixes.
 */
void np_seeds_random(unsigned K, struct np_rng *rng, uint8_t *digits);

/* The shipped set called name (np_hatch_sets, rtl_model/np_hatch.h: the unit's `set` key), or NULL. */
const np_hatch_set *np_seeds_find(const char *name);
/* A shipped set's patterns as an np_seedset. */
np_seedset np_seeds_of(const np_hatch_set *hs);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_HATCH_SEEDS_H */
