/* SPDX-License-Identifier: MIT */
#include "np_hashn.h"

#include <stdatomic.h>
#include <stddef.h>
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

/*
 * The fast path (np_hashn.h, "Tables"): chunk q of the stream is bit planes
 * 3q .. 3q+2, stream bits 3nq .. 3nq + 3n - 1, which are exactly lookups
 * nq .. nq + n - 1 (3n bits, n lookups; the last chunk has planes 6 and 7
 * only and the stream's padding). tab[q][idx] = (the sum of chunk q's
 * lookups) mod 64 at the point whose planes 3q..3q+2 of coordinate a are
 * idx's bits 3a..3a+2, built from np_hashn_stream's own stream_bit.
 */
enum { CHUNK_PLANES = 3, N_CHUNKS = 3, TAB_BITS_MAX = CHUNK_PLANES * NP_HASHN_MAX_DIMS };

static uint8_t tab2[N_CHUNKS][1u << (CHUNK_PLANES * 2u)], tab4[N_CHUNKS][1u << (CHUNK_PLANES * 4u)],
    tab5[N_CHUNKS][1u << TAB_BITS_MAX];
static atomic_int tabs_ready;
static atomic_flag tabs_lock = ATOMIC_FLAG_INIT;

static void tab_build(unsigned n, uint8_t *tab, size_t stride)
{
    for (unsigned q = 0; q < N_CHUNKS; q++)
        for (unsigned idx = 0; idx < (1u << (CHUNK_PLANES * n)); idx++) {
            uint8_t c[NP_HASHN_MAX_DIMS];
            for (unsigned a = 0; a < n; a++)
                c[a] = (uint8_t)(((idx >> (CHUNK_PLANES * a)) & 7u) << (CHUNK_PLANES * q));
            unsigned sum = 0, l_end = n * (q + 1u) < np_hashn_lookups(n) ? n * (q + 1u) : np_hashn_lookups(n);
            for (unsigned l = n * q; l < l_end; l++) {
                unsigned m = LOOKUP_BITS * l;
                sum += np_hash_bit_patterns[stream_bit(n, c, m) << 2 | stream_bit(n, c, m + 1u) << 1 |
                                            stream_bit(n, c, m + 2u)];
            }
            tab[q * stride + idx] = (uint8_t)(sum & HASH_MASK);
        }
}

/* Built once, by the first caller (every thread sees them complete: acquire / release). */
static void tabs_init(void)
{
    if (atomic_load_explicit(&tabs_ready, memory_order_acquire))
        return;
    while (atomic_flag_test_and_set_explicit(&tabs_lock, memory_order_acquire))
        ;
    if (!atomic_load_explicit(&tabs_ready, memory_order_relaxed)) {
        tab_build(2, &tab2[0][0], sizeof tab2[0]);
        tab_build(4, &tab4[0][0], sizeof tab4[0]);
        tab_build(5, &tab5[0][0], sizeof tab5[0]);
        atomic_store_explicit(&tabs_ready, 1, memory_order_release);
    }
    atomic_flag_clear_explicit(&tabs_lock, memory_order_release);
}

/* Planes s..s+2 of every coordinate, coordinate a at bits 3a..3a+2. */
static unsigned gather(unsigned n, const uint8_t *c, unsigned s)
{
    unsigned idx = 0;
    for (unsigned a = 0; a < n; a++)
        idx |= (unsigned)((c[a] >> s) & 7u) << (CHUNK_PLANES * a);
    return idx;
}

uint8_t np_hashn_table(unsigned n, const uint8_t *c)
{
    if (n == 3u)
        return np_hash6_fast(c[0], c[1], c[2]);
    tabs_init();
    const uint8_t *t0, *t1, *t2;
    switch (n) {
    case 2: t0 = tab2[0], t1 = tab2[1], t2 = tab2[2]; break;
    case 4: t0 = tab4[0], t1 = tab4[1], t2 = tab4[2]; break;
    default: t0 = tab5[0], t1 = tab5[1], t2 = tab5[2]; break;
    }
    return (uint8_t)((t0[gather(n, c, 0)] + t1[gather(n, c, 3)] + t2[gather(n, c, 6)]) & HASH_MASK);
}

uint8_t np_hashn(unsigned n, const uint8_t *c)
{
    if (n == 3u)
        return np_hash6(c[0], c[1], c[2]);
    return np_hashn_table(n, c);
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
