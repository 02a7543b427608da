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

#ifdef __cplusplus
extern "C" {
#endif

/* C11's _Static_assert is static_assert in C++ (public headers compile as both). */
#ifdef __cplusplus
#define NP_STATIC_ASSERT(c, msg) static_assert(c, msg)
#else
#define NP_STATIC_ASSERT(c, msg) _Static_assert(c, msg)
#endif
NP_STATIC_ASSERT((-1 & 3) == 3, "two's complement integers required");
NP_STATIC_ASSERT(sizeof(int64_t) == 8 && CHAR_BIT == 8, "8-bit bytes, 64-bit int64_t");

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

/*
 * 2^e as a double, exact for |e| <= 1022, without libm: error bounds and
 * LSB weights (rtl_model is libc only).
 */
static inline double np_pow2i(int e)
{
    double r = 1.0;
    for (; e > 0; e--)
        r *= 2.0;
    for (; e < 0; e++)
        r *= 0.5;
    return r;
}

/* Does v fit an n-bit two's-complement signal? Used by width checks. */
static inline int np_fits_s(int64_t v, unsigned n) { return np_sat_s(v, n) == v; }

/* Does v fit an n-bit unsigned signal? */
static inline int np_fits_u(int64_t v, unsigned n) { return v >= 0 && np_sat_u(v, n) == v; }


/*
 * --- 128-bit containers (added for the texture units, np_fdiff / np_texel) ---
 *
 * Some set-up datapaths are wider than 64 bits (a 32-bit-fraction coordinate
 * cubed is 96 fraction bits). They are modelled in GCC/Clang's 128-bit
 * integers, a compiler type (no library), with the same conventions: a
 * signal of width n <= 128 is held sign-extended (np_sext128) and every
 * rounding rule below exists once.
 *
 * Modular exactness: products and sums of two's-complement words taken mod
 * 2^128 (unsigned arithmetic, never signed overflow) give the low 128 bits of
 * the true integer result. np_round_wrap128 then extracts the low n bits of a
 * rounded right shift, which depend only on those low bits when sh + n <= 128.
 * A datapath that needs only the low n bits of its result (a wrapping
 * accumulator) can thus be computed exactly without 256-bit arithmetic.
 */
#if !defined(__SIZEOF_INT128__)
#error "noisepipe's models need the compiler's 128-bit integers (__int128: GCC or Clang on a 64-bit target)"
#endif
__extension__ typedef __int128 np_s128; /* __extension__: no -pedantic warning */
__extension__ typedef unsigned __int128 np_u128;

/* NP_MASK128(n): the low n bits set, 0 <= n <= 127. */
#define NP_MASK128(n) ((np_u128)(((np_u128)1 << (n)) - 1u))

/* The low n bits of v as an n-bit two's-complement value (1 <= n <= 128). */
static inline np_s128 np_sext128(np_u128 v, unsigned n)
{
    if (n >= 128)
        return (np_s128)v;
    np_u128 m = (np_u128)1 << (n - 1u);
    np_u128 t = v & NP_MASK128(n);
    return (np_s128)(t ^ m) - (np_s128)m;
}

/* Arithmetic shift right (0 <= sh <= 127): floor(v / 2^sh), no signed shift. */
static inline np_s128 np_asr128(np_s128 v, unsigned sh)
{
    np_u128 u = (np_u128)v;
    np_u128 sign = (np_u128)0 - (u >> 127);
    if (sh == 0)
        return v;
    return (np_s128)((u >> sh) | (sign & ~(~(np_u128)0 >> sh)));
}

/* Shift left by sh (0 <= sh <= 127), modulo 2^128 (no signed-overflow UB). */
static inline np_s128 np_shl128(np_s128 v, unsigned sh) { return (np_s128)((np_u128)v << sh); }

/*
 * Round to nearest, ties toward +infinity, dropping sh fraction bits, and
 * keep an n-bit two's-complement result: the low n bits of
 * floor(V / 2^sh + 1/2), where V is the true (unbounded) integer whose low
 * 128 bits are v. Exact for every V when sh + n <= 128 (precondition).
 * In hardware: add 2^(sh-1), drop sh bits, drop the carry out of bit n-1.
 * Error bound: |result - V / 2^sh| <= 1/2 result LSB (modulo 2^n).
 */
static inline np_s128 np_round_wrap128(np_u128 v, unsigned sh, unsigned n)
{
    np_u128 t = sh == 0 ? v : (v + ((np_u128)1 << (sh - 1u))) >> sh;
    return np_sext128(t, n);
}

/* Wrap a value to an n-bit two's-complement signal (1 <= n <= 128). */
static inline np_s128 np_wrap_s128(np_s128 v, unsigned n) { return np_sext128((np_u128)v, n); }

/* Modular product and sum (mod 2^128) of two's-complement words. */
static inline np_s128 np_mul128(np_s128 a, np_s128 b) { return (np_s128)((np_u128)a * (np_u128)b); }
static inline np_s128 np_add128(np_s128 a, np_s128 b) { return (np_s128)((np_u128)a + (np_u128)b); }

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_FIXED_H */
