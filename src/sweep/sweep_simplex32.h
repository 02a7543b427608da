/* SPDX-License-Identifier: MIT */
/*
 * sweep_simplex32.h - simplex3's rounded products at the default widths with
 * the derivative (N = ND = 16, WT = 24, WP = 22, WK = 22) in int32, for the
 * sweep kernel's int32 model row (sweep_simplex.c); not installed. Test:
 * fast.simplex32_exhaustive.
 */
#ifndef NP_SWEEP_SIMPLEX32_H
#define NP_SWEEP_SIMPLEX32_H

#include <stdint.h>

/*
 * The model row for the default configuration with the derivative
 * (N = ND = 16, WT = 24, WP = 22, WK = 22) runs in int32 lanes, so that a vector
 * holds 16 inputs (AVX-512) and no 64-bit multiply (vpmullq) is needed:
 * np_simplex.h's signals all fit 32 bits at these widths, only some of its
 * rounded products do not (T^2, tau2^2, tau2 T up to 2^47; tau4 gd and
 * tau3 gd up to 2^37; 5q D up to 2^40). Each such product is formed from
 * 32-bit partial products, one operand split as a = ah 2^k + al
 * (ah = floor(a / 2^k), 0 <= al < 2^k), with
 *   floor((A + floor(B / C)) / D) == floor((A C + B) / (C D))
 * for integers A, B and C, D > 0: exact identities, so every value is
 * np_simplex.h's. fast.simplex32_exhaustive compares each helper with
 * np_simplex.h's 64-bit form over its operands' whole ranges (every T,
 * every tau2, ...); fast.simplex_kernel_* compare every code of the row.
 * Only Kf' S and Kd' Q (four per input) stay 64-bit.
 *
 * Ranges at these widths (s12 D, s14 gd, u23 T: np_simplex.h):
 *   T < 2^23; tau2, tau3, tau4 < 2^24 (round(tau^k 2^24), tau < 0.85);
 *   |fterm|, |qterm| <= 2^24 * 4608 / 2^11 + 1 < 2^25.2 (|gd| <= 3 * 1536);
 *   |5q| < 2^27.6; |mterm| <= |5q| |D| / 2^11 + 1 <= 2^27.6; |eterm| <= 2^22;
 *   S = sum of 4 fterms: |S| < 2^27.2; Q_a = sum of 4 (eterm - mterm):
 *   |Q_a| < 4 (2^22 + 2^27.6) < 2^29.7. All below 2^31.
 */

/* v >> sh, arithmetic (floor(v / 2^sh)), without implementation-defined behaviour (np_asr in 32 bits). */
static inline int32_t m32_asr(int32_t v, unsigned sh)
{
    uint32_t u = (uint32_t)v, sign = 0u - (u >> 31);
    return (int32_t)((u >> sh) | (sign & ~(~0u >> sh)));
}

/*
 * tau2 = floor((T^2 + 2^21) / 2^22) (np_simplex_tau2, WT = 24) for
 * 0 <= T < 2^23: T = th 2^11 + tl, T^2 = th^2 2^22 + th tl 2^12 + tl^2, so
 * tau2 = th^2 + floor((th tl + floor((tl^2 + 2^21) / 2^12)) / 2^10);
 * th^2 < 2^24, th tl < 2^23, tl^2 + 2^21 < 2^23.
 */
static inline int32_t m32_tau2(int32_t t)
{
    int32_t th = t >> 11, tl = t & 2047;
    return th * th + ((th * tl + ((tl * tl + (1 << 21)) >> 12)) >> 10);
}

/*
 * tau4 = floor((tau2^2 + 2^23) / 2^24) (np_simplex_tau4, WT = 24) for
 * 0 <= tau2 < 2^24: tau2 = a 2^12 + b, tau2^2 = a^2 2^24 + a b 2^13 + b^2,
 * tau4 = a^2 + floor((a b + floor((b^2 + 2^23) / 2^13)) / 2^11).
 */
static inline int32_t m32_tau4(int32_t tau2)
{
    int32_t a = tau2 >> 12, b = tau2 & 4095;
    return a * a + ((a * b + ((b * b + (1 << 23)) >> 13)) >> 11);
}

/*
 * tau3 = floor((tau2 T + 2^22) / 2^23) (np_simplex_tau3) for tau2 < 2^24,
 * T < 2^23: tau2 T = a th 2^23 + a tl 2^12 + b th 2^11 + b tl, so
 * tau3 = a th + floor((2 a tl + b th + floor((b tl + 2^22) / 2^11)) / 2^12);
 * a th < 2^24, 2 a tl < 2^24, b th < 2^24, b tl + 2^22 < 2^24.
 */
static inline int32_t m32_tau3(int32_t tau2, int32_t t)
{
    int32_t a = tau2 >> 12, b = tau2 & 4095, th = t >> 11, tl = t & 2047;
    return a * th + ((2 * a * tl + b * th + ((b * tl + (1 << 22)) >> 11)) >> 12);
}

/*
 * floor((p g + 2^10) / 2^11) = np_shr_round_half_up(p g, 11) for signed p
 * and g with |floor(p / 2^11) g| < 2^30 and |g| < 2^19: p = ph 2^11 + pl
 * (0 <= pl < 2^11), the result is ph g + floor((pl g + 2^10) / 2^11).
 * Used for fterm and qterm (tau4 gd, tau3 gd from Q.33 to WP = 22 bits:
 * |ph gd| < 2^13 4608) and mterm (5q D, np_simplex_mterm's shift of 11:
 * |ph D| < 2^16.6 2^11).
 */
static inline int32_t m32_mul_rq11(int32_t p, int32_t g)
{
    int32_t ph = m32_asr(p, 11), pl = p & 2047;
    return ph * g + m32_asr(pl * g + (1 << 10), 11);
}

#endif /* NP_SWEEP_SIMPLEX32_H */
