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
