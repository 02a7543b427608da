/* SPDX-License-Identifier: MIT */
/*
 * np_fixed.h - fixed-point primitives shared by every hardware model.
 *
 * Conventions used throughout rtl_model/:
 *   - A signal is held in the smallest exact-width C type that contains it
 *     and is masked (unsigned) or sign-extended (signed) back to its hardware
 *     width after every operation that could leave it.
 *   - "sN" is an N-bit two's-complement signal, "uN" an N-bit unsigned one.
 *   - "Qm.n" is a fixed-point format with m integer and n fraction bits. A
 *     format is always written together with its width and signedness, for
 *     example "s11 Q2.8" (signed, 11 bits = 1 sign + 2 integer + 8 fraction,
 *     value = word / 2^8) or "u8 Q0.8" (unsigned, value = word / 2^8).
 *   - Every widening is an explicit cast.
 *   - Each rounding or saturation rule exists once, here, as a named function.
 *
 * Platform assumptions are checked at compile time below; signed right shifts
 * are avoided entirely (np_asr() is written with unsigned operations), so the
 * models do not depend on implementation-defined behaviour.
 */
#ifndef NP_FIXED_H
#define NP_FIXED_H

#include <stdint.h>
#include <limits.h>

_Static_assert((-1 & 3) == 3, "two's complement integers required");
_Static_assert(sizeof(int64_t) == 8 && CHAR_BIT == 8, "8-bit bytes, 64-bit int64_t");

/* NP_MASK(n): the low n bits set, 0 <= n <= 63. */
#define NP_MASK(n) ((uint64_t)(((uint64_t)1 << (n)) - 1u))

/* Keep the low n bits of an unsigned word (0 <= n <= 63). */
static inline uint64_t np_trunc_u(uint64_t v, unsigned n) { return v & NP_MASK(n); }

/*
 * Reinterpret the low n bits of v as an n-bit two's-complement value and
 * sign-extend it (1 <= n <= 63). This is what a hardware wire of width n
 * holding a signed value means.
 */
static inline int64_t np_sext(uint64_t v, unsigned n)
{
    uint64_t m = (uint64_t)1 << (n - 1u);
    uint64_t t = v & NP_MASK(n);
    return (int64_t)(t ^ m) - (int64_t)m;
}

/* Wrap a signed value to an n-bit two's-complement signal (hardware overflow). */
static inline int64_t np_wrap_s(int64_t v, unsigned n) { return np_sext((uint64_t)v, n); }

/*
 * Arithmetic shift right by sh (0 <= sh <= 62): floor(v / 2^sh), exact for
 * every int64_t v. Written with unsigned operations so that no signed shift
 * (implementation-defined in C) is ever performed.
 */
static inline int64_t np_asr(int64_t v, unsigned sh)
{
    uint64_t u = (uint64_t)v;
    uint64_t sign = (uint64_t)0 - (u >> 63);          /* all ones if v < 0 */
    return (int64_t)((u >> sh) | (sign & ~(~(uint64_t)0 >> sh)));
}

/*
 * Shift left by sh (0 <= sh <= 62) without signed-overflow UB. Caller
 * guarantees |v| * 2^sh fits in int64_t.
 */
static inline int64_t np_shl(int64_t v, unsigned sh) { return (int64_t)((uint64_t)v << sh); }

/*
 * Round to nearest, ties toward +infinity, while dropping sh fraction bits:
 * returns floor(v / 2^sh + 1/2). In hardware: add the constant 2^(sh-1),
 * then drop the low sh bits (one adder, no sticky logic).
 * Error bound: |result - v/2^sh| <= 1/2 (in units of the result's LSB), with
 * equality only on exact ties. sh == 0 returns v unchanged (exact).
 * Precondition: v + 2^(sh-1) does not overflow int64_t (0 <= sh <= 62).
 */
static inline int64_t np_shr_round_half_up(int64_t v, unsigned sh)
{
    if (sh == 0)
        return v;
    return np_asr(v + ((int64_t)1 << (sh - 1u)), sh);
}

/* Unsigned version of np_shr_round_half_up: floor(v / 2^sh + 1/2). */
static inline uint64_t np_shr_round_half_up_u(uint64_t v, unsigned sh)
{
    if (sh == 0)
        return v;
    return (v + ((uint64_t)1 << (sh - 1u))) >> sh;
}

/*
 * Saturate v to an n-bit two's-complement range [-2^(n-1), 2^(n-1) - 1]
 * (1 <= n <= 63). Exact inside the range; clamps outside it.
 */
static inline int64_t np_sat_s(int64_t v, unsigned n)
{
    int64_t hi = (int64_t)(NP_MASK(n - 1u));
    int64_t lo = -hi - 1;
    return v > hi ? hi : (v < lo ? lo : v);
}

/* Saturate v to an n-bit unsigned range [0, 2^n - 1] (0 <= n <= 62). */
static inline int64_t np_sat_u(int64_t v, unsigned n)
{
    int64_t hi = (int64_t)NP_MASK(n);
    return v > hi ? hi : (v < 0 ? 0 : v);
}

/* Does v fit an n-bit two's-complement signal? Used by width checks. */
static inline int np_fits_s(int64_t v, unsigned n) { return np_sat_s(v, n) == v; }

/* Does v fit an n-bit unsigned signal? */
static inline int np_fits_u(int64_t v, unsigned n) { return v >= 0 && np_sat_u(v, n) == v; }

#endif /* NP_FIXED_H */
