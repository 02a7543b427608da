/* SPDX-License-Identifier: MIT */
/*
 * np_hash.h - the table-free lattice hash and the multiply-free gradient of
 * Perlin, "Noise Hardware" (shared/seeds/002, "The new pseudo-random
 * generator primitive" and Appendix B). Shared by every noise unit.
 *
 * Hash: for a lattice point (i, j, k), each coordinate an 8-bit unsigned
 * integer (u8; callers wrap to the tile of 256 before calling),
 *
 *   h = ( b(i,j,k,0) + b(j,k,i,1) + b(k,i,j,2) + b(i,j,k,3)
 *       + b(j,k,i,4) + b(k,i,j,5) + b(i,j,k,6) + b(j,k,i,7) ) mod 64
 *
 *   b(a,b,c,B) = T[ 4*bit_B(a) + 2*bit_B(b) + bit_B(c) ]
 *   T = { 0x15, 0x38, 0x32, 0x2c, 0x0d, 0x13, 0x07, 0x2a }
 *
 * Hardware: eight 3-input 8-entry lookups of 6 bits (fixed logic, no RAM)
 * and a tree of seven 6-bit adders whose carries out of bit 5 are dropped.
 *
 * Gradient (Appendix B, which the issue and the seed's Java reference
 * define; the prose table in the seed orders the rotations differently and
 * is not used): with bits b5..b0 of h, b = h & 3,
 *
 *   p = b==1 ? x : b==2 ? y : z
 *   q = b==1 ? y : b==2 ? z : x
 *   r = b==1 ? z : b==2 ? x : y
 *   p = -p if b5 == b3;  q = -q if b5 == b4;  r = -r if b5 != (b4 ^ b3)
 *   g = p + (b == 0 ? q + r : (b2 == 0 ? q : r))
 *
 * Bit ruler of the 6-bit index h (np_hash.c names each field POS_/SIZE_):
 *
 *      5    4    3     2      1   0
 *   +----+----+----+-------+--------+
 *   | s5 | s4 | s3 |  two  |  rot   |   rot: which axis p is; two: q or r kept
 *   +----+----+----+-------+--------+   s5..s3: the octant (signs)
 *
 * So g = cx*x + cy*y + cz*z with coefficients in {-1, 0, +1}: a select and a
 * conditional negate per term (a mux and an XOR/increment in hardware) and
 * two additions. No multiplier.
 */
#ifndef NP_HASH_H
#define NP_HASH_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * NP_BATCH_CLONES on a batch loop of a model (np_classic_eval_n,
 * np_simplex_eval_n): GCC compiles it for x86-64, x86-64-v3 (AVX2) and
 * x86-64-v4 (AVX-512) and the loader picks one by the CPU (the sweep's
 * NP_SWEEP_CLONES, src/sweep/np_sweep.h). Integer results cannot differ
 * between clones; -DNP_SWEEP_NO_CLONES builds the baseline only.
 */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(NP_SWEEP_NO_CLONES) && !defined(__SANITIZE_ADDRESS__)
#define NP_BATCH_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define NP_BATCH_CLONES
#endif

/* The eight 6-bit bit patterns of the seed. */
extern const uint8_t np_hash_bit_patterns[8];

/* 6-bit gradient index (u6) of lattice point (i, j, k), each u8. */
uint8_t np_hash6(uint8_t i, uint8_t j, uint8_t k);

/*
 * Gradient coefficients decoded from a 6-bit index: the gradient of index h
 * applied to (x, y, z) is cx*x + cy*y + cz*z, each c in {-1, 0, +1}.
 * Exactly two or three coefficients are non-zero.
 */
typedef struct np_grad {
    int8_t cx, cy, cz;
} np_grad;

np_grad np_grad_decode(uint8_t h);

/*
 * The fast path: the same two functions as tables, inline. np_hash6 and
 * np_grad_decode above are the specification (the bit loop of the seed);
 * these give the same result for every argument (test fast.hash_exhaustive
 * checks all 2^24 lattice points and all 64 indices).
 *
 * Why two 4 KB tables give the hash: the term of bit B,
 * b(., ., ., B), reads only bit B of i, j and k, so the terms of bits 0..3
 * depend only on the low nibbles of (i, j, k) and those of bits 4..7 only on
 * the high nibbles; and a sum mod 64 is the sum mod 64 of two partial sums.
 *   lo[(i & 15) << 8 | (j & 15) << 4 | (k & 15)] = (terms of bits 0..3) mod 64
 *   hi[(i >> 4) << 8 | (j >> 4) << 4 | (k >> 4)] = (terms of bits 4..7) mod 64
 *   np_hash6(i, j, k) = (lo[.] + hi[.]) mod 64                     (u6)
 * The tables are built at compile time from the seed's eight patterns
 * (np_hash.c); nothing is computed at run time.
 */
extern const uint8_t np_hash6_lo[4096];
extern const uint8_t np_hash6_hi[4096];
extern const np_grad np_grad_table[64];

static inline uint8_t np_hash6_fast(uint8_t i, uint8_t j, uint8_t k)
{
    unsigned lo = ((unsigned)(i & 15u) << 8) | ((unsigned)(j & 15u) << 4) | (k & 15u);
    unsigned hi = ((unsigned)(i >> 4) << 8) | ((unsigned)(j >> 4) << 4) | (unsigned)(k >> 4);
    return (uint8_t)((np_hash6_lo[lo] + np_hash6_hi[hi]) & 63u);
}

/*
 * The same tables in 32-bit words, for loops that the compiler vectorises
 * across inputs (vector gathers load 32-bit elements): np_hash6_lo32[n] ==
 * np_hash6_lo[n] etc., and np_grad_packed32[h] holds np_grad_decode(h) as
 * (cx + 1) | (cy + 1) << 2 | (cz + 1) << 4 (np_grad_unpack).
 */
extern const uint32_t np_hash6_lo32[4096];
extern const uint32_t np_hash6_hi32[4096];
extern const uint32_t np_grad_packed32[64];

static inline uint32_t np_hash6_fast32(uint32_t i, uint32_t j, uint32_t k)
{
    uint32_t lo = (i & 15u) << 8 | (j & 15u) << 4 | (k & 15u);
    uint32_t hi = (i >> 4 & 15u) << 8 | (j >> 4 & 15u) << 4 | (k >> 4 & 15u);
    return (np_hash6_lo32[lo] + np_hash6_hi32[hi]) & 63u;
}

/* Coefficient of axis a (0, 1, 2) from a packed gradient: -1, 0 or +1. */
static inline int32_t np_grad_unpack(uint32_t packed, unsigned a)
{
    return (int32_t)(packed >> (2u * a) & 3u) - 1;
}

/* np_grad_decode(h) for a u6 h, as one table load. */
static inline np_grad np_grad_fast(uint8_t h) { return np_grad_table[h & 63u]; }

/*
 * Fixed-point gradient contribution: cx*dx + cy*dy + cz*dz with dx, dy, dz
 * the corner-relative vector in s9 Q1.8 (value = word / 256, range
 * [-256, 255]). Result s11 Q2.8, range [-768, 768]: exact, never overflows.
 */
static inline int16_t np_grad_apply_q8(np_grad g, int16_t dx, int16_t dy, int16_t dz)
{
    return (int16_t)(g.cx * dx + g.cy * dy + g.cz * dz);
}

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_HASH_H */
