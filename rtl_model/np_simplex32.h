/* SPDX-License-Identifier: MIT */
/*
 * np_simplex32.h - simplex3's rounded products at the default widths with
 * the derivative (N = ND = 16, WT = 24, WP = 22, WK = 22) in int32, shared by
 * the batch model's int32 and AVX2 paths (np_simplex.c) and the sweep
 * kernel's int32 model row (src/sweep/sweep_simplex.c); internal, not
 * installed. Test: fast.simplex32_exhaustive.
 */
#ifndef NP_SIMPLEX32_H
#define NP_SIMPLEX32_H

#include <stdint.h>

/*
 * The default configuration with the derivative (N = ND = 16, WT = 24,
 * WP = 22, WK = 22) runs in int32 lanes, so that a vector holds 8 (AVX2) or
 * 16 (AVX-512) inputs and no 64-bit multiply (vpmullq) is needed:
 * np_simplex.h's signals all fit 32 bits at these widths, only some of its
 * rounded products do not (T^2, tau2^2, tau2 T up to 2^47; tau4 gd and
 * tau3 gd up to 2^37; 5q D up to 2^40). Each such product is formed from
 * 32-bit partial products, one operand split as a = ah 2^k + al
 * (ah = floor(a / 2^k), 0 <= al < 2^k), with
 *   floor((A + floor(B / C)) / D) == floor((A C + B) / (C D))
 * for integers A, B and C, D > 0: exact identities, so every value is
 * np_simplex.h's. fast.simplex32_exhaustive compares each helper with
 * np_simplex.h's 64-bit form over its operands' whole ranges (every T,
 * every tau2, ...); fast.simplex_kernel_* compare every code of the sweep's
 * row, fast.simplex_batch_paths every code of each batch path.
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
 * NP_SIMPLEX32_PRODUCTS(P, T, ASR, MULC, ATTR) defines the helpers below, named
 * P##tau2 etc., on lanes of type T: int32_t here (m32_tau2, ...), and in
 * np_simplex.c's AVX2 path a GCC vector of eight int32 lanes (v8_tau2, ...),
 * whose +, -, *, & and >> act on each lane as on an int32_t (* keeps the low
 * 32 bits: every product below is < 2^31 in magnitude, so that is the
 * product). ASR(v, sh) is floor(v / 2^sh), MULC(d, c) is c d for
 * c in {-1, 0, +1} (a multiply, or a sign operation), ATTR a function
 * attribute (the vector form's target). One text, so the paths cannot drift
 * apart.
 *
 * tau2 = floor((T^2 + 2^21) / 2^22) (np_simplex_tau2, WT = 24) for
 * 0 <= T < 2^23: T = th 2^11 + tl, T^2 = th^2 2^22 + th tl 2^12 + tl^2, so
 * tau2 = th^2 + floor((th tl + floor((tl^2 + 2^21) / 2^12)) / 2^10);
 * th^2 < 2^24, th tl < 2^23, tl^2 + 2^21 < 2^23.
 *
 * tau4 = floor((tau2^2 + 2^23) / 2^24) (np_simplex_tau4, WT = 24) for
 * 0 <= tau2 < 2^24: tau2 = a 2^12 + b, tau2^2 = a^2 2^24 + a b 2^13 + b^2,
 * tau4 = a^2 + floor((a b + floor((b^2 + 2^23) / 2^13)) / 2^11).
 *
 * tau3 = floor((tau2 T + 2^22) / 2^23) (np_simplex_tau3) for tau2 < 2^24,
 * T < 2^23: tau2 T = a th 2^23 + a tl 2^12 + b th 2^11 + b tl, so
 * tau3 = a th + floor((2 a tl + b th + floor((b tl + 2^22) / 2^11)) / 2^12);
 * a th < 2^24, 2 a tl < 2^24, b th < 2^24, b tl + 2^22 < 2^24.
 *
 * mul_rq11(p, g) = floor((p g + 2^10) / 2^11) = np_shr_round_half_up(p g, 11)
 * for signed p and g with |floor(p / 2^11) g| < 2^30 and |g| < 2^19:
 * p = ph 2^11 + pl (0 <= pl < 2^11), the result is
 * ph g + floor((pl g + 2^10) / 2^11). Used for fterm and qterm (tau4 gd,
 * tau3 gd from Q.33 to WP = 22 bits: |ph gd| < 2^13 4608) and mterm (5q D,
 * np_simplex_mterm's shift of 11: |ph D| < 2^16.6 2^11).
 *
 * eterm(c, tau4) = floor((c tau4 + 2) / 4) = np_simplex_eterm: G_a tau4 from
 * Q.24 to Q.22, c in {-1, 0, 1}.
 *
 * The value-only default (N = 16, WT = 23, WP = 20, WK = 22) in the same
 * way; its ranges: T, tau2, tau4 < 2^23; |fterm| <= 2^23 4608 / 2^12 + 1
 * < 2^23.2; |S| < 2^25.2; Kf' S < 2^47.7 (64-bit).
 * tau2_23 = floor((T^2 + 2^22) / 2^23) (np_simplex_tau2, WT = 23): with
 * T = th 2^11 + tl and th^2 = 2 floor(th^2 / 2) + (th^2 mod 2),
 * T^2 + 2^22 = floor(th^2 / 2) 2^23 + 2^12 ((th^2 mod 2) 2^10 + th tl) + tl^2 + 2^22,
 * so tau2_23 = floor(th^2 / 2)
 *            + floor(((th^2 mod 2) 2^10 + th tl + floor((tl^2 + 2^22) / 2^12)) / 2^11);
 * th^2 < 2^24, th tl < 2^23, tl^2 + 2^22 < 2^23.
 * tau4_23 = floor((tau2^2 + 2^22) / 2^23) (np_simplex_tau4, WT = 23) for
 * tau2 < 2^23: tau2 = a 2^12 + b (a < 2^11), tau2^2 = 2 a^2 2^23 + a b 2^13 + b^2,
 * tau4_23 = 2 a^2 + floor((a b + floor((b^2 + 2^22) / 2^13)) / 2^10);
 * a b < 2^23, b^2 + 2^22 < 2^25.
 * mul_rq12(p, g) = floor((p g + 2^11) / 2^12): mul_rq11's split at 2^12, for
 * fterm (tau4 gd from Q.32 to WP = 20 bits; |floor(p / 2^12) g| < 2^11 4608,
 * |pl g| < 2^12 4608).
 */
#define NP_SIMPLEX32_PRODUCTS(P, T, ASR, MULC, ATTR)                                 \
    ATTR static inline T P##tau2(T t)                                            \
    {                                                                            \
        T th = t >> 11, tl = t & 2047;                                           \
        return th * th + ((th * tl + ((tl * tl + (1 << 21)) >> 12)) >> 10);      \
    }                                                                            \
    ATTR static inline T P##tau4(T tau2)                                         \
    {                                                                            \
        T a = tau2 >> 12, b = tau2 & 4095;                                       \
        return a * a + ((a * b + ((b * b + (1 << 23)) >> 13)) >> 11);            \
    }                                                                            \
    ATTR static inline T P##tau3(T tau2, T t)                                    \
    {                                                                            \
        T a = tau2 >> 12, b = tau2 & 4095, th = t >> 11, tl = t & 2047;         \
        return a * th + ((2 * a * tl + b * th + ((b * tl + (1 << 22)) >> 11)) >> 12); \
    }                                                                            \
    ATTR static inline T P##mul_rq11(T p, T g)                                   \
    {                                                                            \
        T ph = ASR(p, 11), pl = p & 2047;                                        \
        return ph * g + ASR(pl * g + (1 << 10), 11);                             \
    }                                                                            \
    ATTR static inline T P##eterm(T c, T tau4) { return ASR(MULC(tau4, c) + 2, 2); }     \
    ATTR static inline T P##tau2_23(T t)                                         \
    {                                                                            \
        T th = t >> 11, tl = t & 2047, th2 = th * th;                            \
        return (th2 >> 1) + ((((th2 & 1) << 10) + th * tl + ((tl * tl + (1 << 22)) >> 12)) >> 11); \
    }                                                                            \
    ATTR static inline T P##tau4_23(T tau2)                                      \
    {                                                                            \
        T a = tau2 >> 12, b = tau2 & 4095;                                       \
        return 2 * a * a + ((a * b + ((b * b + (1 << 22)) >> 13)) >> 10);       \
    }                                                                            \
    ATTR static inline T P##mul_rq12(T p, T g)                                   \
    {                                                                            \
        T ph = ASR(p, 12), pl = p & 4095;                                        \
        return ph * g + ASR(pl * g + (1 << 11), 12);                             \
    }

/* The shifts of t, tau2 (>= 0) and of the non-negative partial sums are exact either way. */
#define NP_SIMPLEX32_MULC(d, c) ((c) * (d))
NP_SIMPLEX32_PRODUCTS(m32_, int32_t, m32_asr, NP_SIMPLEX32_MULC, )

#endif /* NP_SIMPLEX32_H */
