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
