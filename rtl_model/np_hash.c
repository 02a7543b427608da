/* SPDX-License-Identifier: MIT */
#include "np_hash.h"

const uint8_t np_hash_bit_patterns[8] = { 0x15, 0x38, 0x32, 0x2c, 0x0d, 0x13, 0x07, 0x2a };

/* Bit positions of the 6-bit gradient index (see the ruler in np_hash.h). */
enum {
    POS_HASH_ROT = 0, SIZE_HASH_ROT = 2, /* b1 b0: which axis is p */
    POS_HASH_TWO = 2,                    /* b2: two-term gradient keeps q (0) or r (1) */
    POS_HASH_S3 = 3, POS_HASH_S4 = 4, POS_HASH_S5 = 5, /* octant bits */
    SIZE_HASH = 6
};

static unsigned bit_of(unsigned v, unsigned pos) { return (v >> pos) & 1u; }

/* b(a,b,c,B) of the seed. */
static unsigned pattern(uint8_t a, uint8_t b, uint8_t c, unsigned bit)
{
    unsigned idx = (bit_of(a, bit) << 2) | (bit_of(b, bit) << 1) | bit_of(c, bit);
    return np_hash_bit_patterns[idx];
}

uint8_t np_hash6(uint8_t i, uint8_t j, uint8_t k)
{
    unsigned sum = 0;
    for (unsigned bit = 0; bit < 8; bit++) {
        /* The argument order rotates (i,j,k) -> (j,k,i) -> (k,i,j) with bit mod 3. */
        switch (bit % 3u) {
        case 0: sum += pattern(i, j, k, bit); break;
        case 1: sum += pattern(j, k, i, bit); break;
        default: sum += pattern(k, i, j, bit); break;
        }
    }
    return (uint8_t)(sum & ((1u << SIZE_HASH) - 1u));
}

np_grad np_grad_decode(uint8_t h)
{
    unsigned b = (unsigned)(h >> POS_HASH_ROT) & ((1u << SIZE_HASH_ROT) - 1u);
    unsigned b2 = bit_of(h, POS_HASH_TWO);
    unsigned b3 = bit_of(h, POS_HASH_S3), b4 = bit_of(h, POS_HASH_S4), b5 = bit_of(h, POS_HASH_S5);
    /* Axis index (0 = x, 1 = y, 2 = z) that p, q and r select. */
    unsigned ap = b == 1 ? 0u : b == 2 ? 1u : 2u;
    unsigned aq = b == 1 ? 1u : b == 2 ? 2u : 0u;
    unsigned ar = b == 1 ? 2u : b == 2 ? 0u : 1u;
    int sp = b5 == b3 ? -1 : 1;
    int sq = b5 == b4 ? -1 : 1;
    int sr = b5 != (b4 ^ b3) ? -1 : 1;
    int useq = b == 0 || b2 == 0;
    int user = b == 0 || b2 == 1;
    int c[3] = { 0, 0, 0 };
    c[ap] += sp;
    if (useq)
        c[aq] += sq;
    if (user)
        c[ar] += sr;
    np_grad g = { (int8_t)c[0], (int8_t)c[1], (int8_t)c[2] };
    return g;
}

/*
 * --- The fast path's tables (np_hash.h), as constant expressions of the
 * same definitions, so that they are built by the compiler, not typed in.
 *
 * PAT(idx): entry idx of np_hash_bit_patterns, from the eight 6-bit
 * patterns packed into one 48-bit constant (entry idx at bits 6 idx).
 */
#define PACKED_PATTERNS                                                                            \
    ((uint64_t)0x15 | (uint64_t)0x38 << 6 | (uint64_t)0x32 << 12 | (uint64_t)0x2c << 18 |         \
     (uint64_t)0x0d << 24 | (uint64_t)0x13 << 30 | (uint64_t)0x07 << 36 | (uint64_t)0x2a << 42)
#define PAT(idx) ((unsigned)(PACKED_PATTERNS >> (6u * (unsigned)(idx))) & 63u)
/* b(a, b, c, B) of the seed, on nibbles: bit B of each (B = 0..3 of the nibble). */
#define BT(a, b, c, B) PAT(4u * (((a) >> (B)) & 1u) + 2u * (((b) >> (B)) & 1u) + (((c) >> (B)) & 1u))
/* Nibbles of a table index n = I << 8 | J << 4 | K. */
#define NI(n) (((unsigned)(n) >> 8) & 15u)
#define NJ(n) (((unsigned)(n) >> 4) & 15u)
#define NK(n) ((unsigned)(n) & 15u)
/*
 * Bits 0..3: rotations (i,j,k), (j,k,i), (k,i,j), (i,j,k) (bit mod 3 = 0, 1, 2, 0).
 * Bits 4..7: rotations (j,k,i), (k,i,j), (i,j,k), (j,k,i) (bit mod 3 = 1, 2, 0, 1),
 * each reading bit B - 4 of the high nibble.
 */
#define LO(n)                                                                                      \
    (uint8_t)((BT(NI(n), NJ(n), NK(n), 0u) + BT(NJ(n), NK(n), NI(n), 1u) +                         \
               BT(NK(n), NI(n), NJ(n), 2u) + BT(NI(n), NJ(n), NK(n), 3u)) & 63u)
#define HI(n)                                                                                      \
    (uint8_t)((BT(NJ(n), NK(n), NI(n), 0u) + BT(NK(n), NI(n), NJ(n), 1u) +                         \
               BT(NI(n), NJ(n), NK(n), 2u) + BT(NJ(n), NK(n), NI(n), 3u)) & 63u)
#define R4(f, b) f((b)), f((b) + 1u), f((b) + 2u), f((b) + 3u)
#define R16(f, b) R4(f, (b)), R4(f, (b) + 4u), R4(f, (b) + 8u), R4(f, (b) + 12u)
#define R64(f, b) R16(f, (b)), R16(f, (b) + 16u), R16(f, (b) + 32u), R16(f, (b) + 48u)
#define R256(f, b) R64(f, (b)), R64(f, (b) + 64u), R64(f, (b) + 128u), R64(f, (b) + 192u)
#define R1024(f, b) R256(f, (b)), R256(f, (b) + 256u), R256(f, (b) + 512u), R256(f, (b) + 768u)
#define R4096(f) R1024(f, 0u), R1024(f, 1024u), R1024(f, 2048u), R1024(f, 3072u)

const uint8_t np_hash6_lo[4096] = { R4096(LO) };
const uint8_t np_hash6_hi[4096] = { R4096(HI) };
const uint32_t np_hash6_lo32[4096] = { R4096(LO) };
const uint32_t np_hash6_hi32[4096] = { R4096(HI) };

/*
 * np_grad_decode as a constant expression of h: axis ap/aq/ar of p/q/r,
 * their signs, and which of q, r are used; coefficient of axis a is the sum
 * of the signs of the terms that select it.
 */
#define GB(h, pos) (((unsigned)(h) >> (pos)) & 1u)
#define GROT(h) ((unsigned)(h) & 3u)
#define GAP(h) (GROT(h) == 1u ? 0u : GROT(h) == 2u ? 1u : 2u)
#define GAQ(h) (GROT(h) == 1u ? 1u : GROT(h) == 2u ? 2u : 0u)
#define GAR(h) (GROT(h) == 1u ? 2u : GROT(h) == 2u ? 0u : 1u)
#define GSP(h) (GB(h, 5) == GB(h, 3) ? -1 : 1)
#define GSQ(h) (GB(h, 5) == GB(h, 4) ? -1 : 1)
#define GSR(h) (GB(h, 5) != (GB(h, 4) ^ GB(h, 3)) ? -1 : 1)
#define GUQ(h) (GROT(h) == 0u || GB(h, 2) == 0u)
#define GUR(h) (GROT(h) == 0u || GB(h, 2) == 1u)
#define GC(h, a)                                                                                   \
    (int8_t)((GAP(h) == (a) ? GSP(h) : 0) + (GUQ(h) && GAQ(h) == (a) ? GSQ(h) : 0) +                \
             (GUR(h) && GAR(h) == (a) ? GSR(h) : 0))
#define GRAD(h) { GC(h, 0u), GC(h, 1u), GC(h, 2u) }

const np_grad np_grad_table[64] = { R64(GRAD, 0u) };

/* The same, packed into a u6 word: 2 bits per coefficient, c + 1 at bit 2a. */
#define GPACK(h)                                                                                   \
    (uint32_t)((unsigned)(GC(h, 0u) + 1) | (unsigned)(GC(h, 1u) + 1) << 2 | (unsigned)(GC(h, 2u) + 1) << 4)
const uint32_t np_grad_packed32[64] = { R64(GPACK, 0u) };
