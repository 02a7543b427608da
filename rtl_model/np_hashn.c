/* SPDX-License-Identifier: MIT */
#include "np_hashn.h"

#include <string.h>

enum { LOOKUP_BITS = 3, HASH_MASK = 63 };

/* Stream bit m of the n-D hash (np_hashn.h): bit B of coordinate (B + r) mod n, m = n B + r; 0 past 8n. */
static unsigned stream_bit(unsigned n, const uint8_t *c, unsigned m)
{
    if (m >= NP_HASHN_COORD * n)
        return 0u;
    unsigned plane = m / n, r = m % n;
    return (unsigned)(c[(plane + r) % n] >> plane) & 1u;
}

uint8_t np_hashn_stream(unsigned n, const uint8_t *c)
{
    unsigned sum = 0;
    for (unsigned l = 0; l < np_hashn_lookups(n); l++) {
        unsigned m = LOOKUP_BITS * l;
        unsigned idx = stream_bit(n, c, m) << 2 | stream_bit(n, c, m + 1u) << 1 | stream_bit(n, c, m + 2u);
        sum += np_hash_bit_patterns[idx];
    }
    return (uint8_t)(sum & HASH_MASK);
}

uint8_t np_hashn(unsigned n, const uint8_t *c)
{
    if (n == 3u)
        return np_hash6(c[0], c[1], c[2]);
    return np_hashn_stream(n, c);
}

void np_gradn_decode(unsigned n, uint8_t h, int8_t *coef)
{
    unsigned b = h;
    memset(coef, 0, n);
    switch (n) {
    case 2:
        if ((b >> 2 & 1u) == 0u) {
            coef[b & 1u] = (int8_t)((b >> 1 & 1u) ? -1 : 1);
        } else {
            coef[0] = (int8_t)((b & 1u) ? -1 : 1);
            coef[1] = (int8_t)((b >> 1 & 1u) ? -1 : 1);
        }
        break;
    case 3: {
        np_grad g = np_grad_decode(h);
        coef[0] = g.cx;
        coef[1] = g.cy;
        coef[2] = g.cz;
        break;
    }
    case 4: {
        unsigned zero = b & 3u, s = 2u;
        for (unsigned a = 0; a < 4u; a++)
            if (a != zero)
                coef[a] = (int8_t)((b >> s++ & 1u) ? -1 : 1);
        break;
    }
    default: /* 5 */
        for (unsigned a = 0; a < n; a++)
            coef[a] = (int8_t)((b >> a & 1u) ? -1 : 1);
        break;
    }
}

unsigned np_gradn_max_terms(unsigned n) { return n == 2u ? 2u : n == 5u ? 5u : 3u; }
unsigned np_gradn_max_norm2(unsigned n) { return np_gradn_max_terms(n); }

void np_hashn_tile_counts(unsigned n, double count[64])
{
    double acc[64], next[64];
    memset(acc, 0, sizeof acc);
    acc[0] = 1.0;
    unsigned total = NP_HASHN_COORD * n;
    for (unsigned l = 0; l < np_hashn_lookups(n); l++) {
        /* The lookup's bits that exist (the others are 0): 2^live equally likely indices. */
        unsigned first = LOOKUP_BITS * l, live = total - first < LOOKUP_BITS ? total - first : LOOKUP_BITS;
        double lk[64];
        memset(lk, 0, sizeof lk);
        for (unsigned v = 0; v < (1u << live); v++) {
            unsigned idx = v << (LOOKUP_BITS - live); /* the padded low bits are 0 */
            lk[np_hash_bit_patterns[idx]] += 1.0;
        }
        memset(next, 0, sizeof next);
        for (unsigned a = 0; a < 64u; a++)
            if (acc[a] != 0.0)
                for (unsigned t = 0; t < 64u; t++)
                    if (lk[t] != 0.0)
                        next[(a + t) & HASH_MASK] += acc[a] * lk[t];
        memcpy(acc, next, sizeof acc);
    }
    memcpy(count, acc, sizeof acc);
}

void np_hashn_tile_summary(unsigned n, double *fewest, double *most, double *total, double *chi2)
{
    double c[64], lo = 0.0, hi = 0.0, tot = 0.0, chi = 0.0;
    np_hashn_tile_counts(n, c);
    for (unsigned h = 0; h < 64u; h++) {
        lo = h == 0 || c[h] < lo ? c[h] : lo;
        hi = c[h] > hi ? c[h] : hi;
        tot += c[h];
    }
    for (unsigned h = 0; h < 64u; h++)
        chi += (c[h] - tot / 64.0) * (c[h] - tot / 64.0) / (tot / 64.0);
    *fewest = lo;
    *most = hi;
    *total = tot;
    *chi2 = chi;
}
