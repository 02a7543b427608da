/* SPDX-License-Identifier: MIT */
/*
 * np_math.h - deterministic elementary functions for the float references
 * (design/scene-pipeline.md, "Deterministic maths for references";
 * docs/math.md has the derivations and the measured errors).
 *
 * libm's sin, tanh, log2, exp2 are not correctly rounded and differ between
 * libm versions, so a reference built on them could change a golden vector
 * when the C library changes. These functions use only IEEE binary64 +, -, *,
 * / (round to nearest even), and the exact operations floor, frexp, ldexp and
 * sign manipulation. Built with -ffp-contract=off -fno-fast-math (no FMA
 * contraction, no reassociation), they return the same bits on every
 * conforming machine and compiler; testbench/math_kat.inc pins them.
 *
 * Error bounds. "ulp" is the unit in the last place of the true value's
 * binade in binary64: 2^(e-52) for a true value in [2^e, 2^(e+1)), and
 * 2^-1074 for true values below 2^-1022 (subnormal results). Each bound holds
 * over the whole finite domain and is asserted by testbench/test_math.c
 * (math.*_bound) against a 64-bit-mantissa long double oracle on 10^6+ points
 * per function, including random doubles of every exponent and the
 * adversarial points listed in docs/math.md. None of the functions is claimed
 * to be correctly rounded: the bound is "< 1 ulp" (faithful), the measured
 * maxima in docs/math.md are lower.
 *
 * Special values. A NaN argument is returned unchanged (same bits, no
 * arithmetic on it). An invalid operation (sin or cos of an infinity, log2 of
 * a negative number or of -inf) returns the canonical quiet NaN
 * NP_MATH_NAN_BITS = 0x7ff8000000000000, the same on every machine (0.0/0.0
 * is negative on x86 and positive on ARM, so it is never used).
 */
#ifndef NP_MATH_H
#define NP_MATH_H

#ifdef __cplusplus
extern "C" {
#endif

#define NP_MATH_NAN_BITS 0x7ff8000000000000ull

/*
 * sin(2 pi t) and cos(2 pi t): the argument in turns.
 *   t:      any binary64; |t| >= 2^52 is an integer number of turns.
 *   result: within 1 ulp of the true value for every finite t (< 1 ulp;
 *           relative, also next to the zeros, because the reduction to a
 *           quarter turn is exact: there is no absolute-error caveat).
 * Exact: sin(k/4) and cos(k/4) are exactly 0, +1 or -1 for every integer k;
 * zeros are +0 except that sin(-t) = -sin(t) bit for bit (so sin(-0) = -0,
 * sin(-1/2) = -0), and cos(-t) = cos(t) bit for bit. sin(t + 1/4) = cos(t)
 * and sin(t + 1/2) = -sin(t) (nonzero results) whenever t >= 0 and the sum is
 * exact. +-inf gives the canonical NaN.
 */
double np_sin_turns(double t);
double np_cos_turns(double t);
/* Both at once; *s and *c are bit for bit np_sin_turns(t) and np_cos_turns(t). */
void np_sincos_turns(double t, double *s, double *c);

/*
 * tanh(x).
 *   result: within 1 ulp of the true value for every finite x (< 1 ulp).
 * Pieces: |x| < 1/2 odd Taylor polynomial (no cancellation); 1/2 <= |x| < 22
 * (1 - E)/(1 + E), E = e^(-2|x|) in double-double; |x| >= 22 exactly 1 (the
 * true value is within 2^-63 of 1). tanh(-x) = -tanh(x) bit for bit;
 * tanh(+-0) = +-0, tanh(+-inf) = +-1.
 */
double np_tanh(double x);

/*
 * log2(x).
 *   domain: x >= 0 (subnormals included).
 *   result: within 1 ulp of the true value (< 1 ulp); log2(2^k) = k exactly
 *           for every k in [-1074, 1023], so log2(1) = +0.
 * log2(+-0) = -inf, log2(+inf) = +inf, log2(x < 0) and log2(-inf) = canonical NaN.
 */
double np_log2(double x);

/*
 * 2^x.
 *   result: within 1 ulp of the true value (< 1 ulp; subnormal results in
 *           units of 2^-1074); 2^k exact for every integer k in [-1074, 1023].
 * x >= 1024 gives +inf (2^1024 overflows), x <= -1075 gives +0 (2^-1075 is
 * half the smallest subnormal and rounds to even 0); exp2(-inf) = +0,
 * exp2(+inf) = +inf, exp2(+-0) = 1.
 */
double np_exp2(double x);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_MATH_H */
