/* SPDX-License-Identifier: MIT */
/*
 * np_rng.h - the project's own seeded generator: xoshiro256** seeded through
 * splitmix64 (Blackman & Vigna). Never rand(): its sequence differs between C
 * libraries, and golden vectors must not. Pinned by known-answer tests.
 */
#ifndef NP_RNG_H
#define NP_RNG_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct np_rng {
    uint64_t s[4];
} np_rng;

static inline uint64_t np_splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static inline void np_rng_seed(np_rng *r, uint64_t seed)
{
    uint64_t st = seed;
    for (int i = 0; i < 4; i++)
        r->s[i] = np_splitmix64(&st);
}

static inline uint64_t np_rotl64(uint64_t x, unsigned k) { return (x << k) | (x >> (64u - k)); }

static inline uint64_t np_rng_next(np_rng *r)
{
    uint64_t *s = r->s;
    uint64_t result = np_rotl64(s[1] * 5u, 7) * 9u;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = np_rotl64(s[3], 45);
    return result;
}

/* Uniform in [0, n), n >= 1, without modulo bias (Lemire's method). */
static inline uint64_t np_rng_below(np_rng *r, uint64_t n)
{
    for (;;) {
        __uint128_t m = (__uint128_t)np_rng_next(r) * n;
        uint64_t lo = (uint64_t)m;
        if (lo >= n || lo >= (0u - n) % n)
            return (uint64_t)(m >> 64);
    }
}

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_RNG_H */
