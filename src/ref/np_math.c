/* SPDX-License-Identifier: MIT */
/*
 * np_math.c - deterministic sin/cos in turns, tanh, log2, exp2 (np_math.h;
 * docs/math.md). Only IEEE +, -, *, / in round to nearest and the exact
 * operations floor, frexp, ldexp, fabs, signbit: no libm transcendental.
 *
 * Error-free transformations (Knuth, Dekker; valid without FMA and without
 * overflow or underflow of the intermediate products, which every use below
 * respects or states):
 *   np__two_sum(a, b)      s + e == a + b exactly, s = fl(a + b)
 *   np__fast_two_sum(a, b) the same when |a| >= |b| (or a == 0)
 *   np__two_prod(a, b)     p + e == a * b exactly, p = fl(a * b)
 * A double-double value hi + lo carries about 106 bits.
 */
#include "np_math.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

_Static_assert(sizeof(double) == 8, "binary64 double");
/*
 * Every double operation must round to binary64 (no x87 extended
 * intermediates), or the bits differ. FLT_EVAL_METHOD 0 and 1 evaluate double
 * as double; 16 (GCC with AVX512-FP16) only widens _Float16. 2 (x87) and -1
 * (indeterminable) are refused.
 */
#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD < 0 || FLT_EVAL_METHOD == 2
#error "np_math needs double evaluated as binary64 (FLT_EVAL_METHOD 0 or 1, e.g. SSE2 on x86)"
#endif

/* ---- polynomial coefficients: the output of `python3 src/ref/np_math_coeffs.py` ---- */
/* sin(pi/2 r): r^1 coefficient split hi+lo, then r^3 .. r^17 */
#define NP__SIN_A1_HI 0x1.921fb54442d18p+0 /* 1.5707963267948966 */
#define NP__SIN_A1_LO 0x1.1a62633145c07p-54 /* 6.123233995736766e-17 */
#define NP__SIN_A3 -0x1.4abbce625be53p-1 /* -0.6459640975062463 */
#define NP__SIN_A5 0x1.466bc6775aae2p-4 /* 0.07969262624616705 */
#define NP__SIN_A7 -0x1.32d2cce62bd86p-8 /* -0.004681754135318688 */
#define NP__SIN_A9 0x1.50783487ee782p-13 /* 0.00016044118478735983 */
#define NP__SIN_A11 -0x1.e3074fde8871fp-19 /* -3.598843235212085e-06 */
#define NP__SIN_A13 0x1.e8f434d018d63p-25 /* 5.692172921967927e-08 */
#define NP__SIN_A15 -0x1.6fadb9f155744p-31 /* -6.688035109811468e-10 */
#define NP__SIN_A17 0x1.aaec32af93359p-38 /* 6.0669357311061955e-12 */
/* first neglected term at r = 1/2: 2^-62.9 of sin */
/* cos(pi/2 r): r^2 coefficient split hi+lo, then r^4 .. r^18 */
#define NP__COS_B2_HI 0x1.3bd3cc9be45dep+0 /* 1.2337005501361697 */
#define NP__COS_B2_LO 0x1.692b71366cc04p-54 /* 7.831619385924639e-17 */
#define NP__COS_B4 0x1.03c1f081b5ac4p-2 /* 0.25366950790104803 */
#define NP__COS_B6 -0x1.55d3c7e3cbffap-6 /* -0.02086348076335296 */
#define NP__COS_B8 0x1.e1f506891babbp-11 /* 0.0009192602748394266 */
#define NP__COS_B10 -0x1.a6d1f2a204a8cp-16 /* -2.5202042373060607e-05 */
#define NP__COS_B12 0x1.f9d38a3763cc3p-22 /* 4.710874778818172e-07 */
#define NP__COS_B14 -0x1.b6e24f44b128fp-28 /* -6.386603083791852e-09 */
#define NP__COS_B16 0x1.20c62c2f2d7f5p-34 /* 6.565963114979473e-11 */
#define NP__COS_B18 -0x1.2a0c591af8314p-41 /* -5.294400200734623e-13 */
/* first neglected term at r = 1/2: 2^-67.5 of cos */
/* 2^f: f^1 coefficient ln 2 split hi+lo, then f^2 .. f^14 */
#define NP__LN2_HI 0x1.62e42fefa39efp-1 /* 0.6931471805599453 */
#define NP__LN2_LO 0x1.abc9e3b39803fp-56 /* 2.3190468138462996e-17 */
#define NP__EXP2_C2 0x1.ebfbdff82c58fp-3 /* 0.24022650695910072 */
#define NP__EXP2_C3 0x1.c6b08d704a0c0p-5 /* 0.05550410866482158 */
#define NP__EXP2_C4 0x1.3b2ab6fba4e77p-7 /* 0.009618129107628477 */
#define NP__EXP2_C5 0x1.5d87fe78a6731p-10 /* 0.0013333558146428443 */
#define NP__EXP2_C6 0x1.430912f86c787p-13 /* 0.0001540353039338161 */
#define NP__EXP2_C7 0x1.ffcbfc588b0c7p-17 /* 1.5252733804059841e-05 */
#define NP__EXP2_C8 0x1.62c0223a5c824p-20 /* 1.321548679014431e-06 */
#define NP__EXP2_C9 0x1.b5253d395e7c4p-24 /* 1.01780860092397e-07 */
#define NP__EXP2_C10 0x1.e4cf5158b8ecap-28 /* 7.054911620801123e-09 */
#define NP__EXP2_C11 0x1.e8cac7351bb25p-32 /* 4.4455382718708116e-10 */
#define NP__EXP2_C12 0x1.c3bd650fc2986p-36 /* 2.5678435993488206e-11 */
#define NP__EXP2_C13 0x1.816193166d0f9p-40 /* 1.3691488853904128e-12 */
#define NP__EXP2_C14 0x1.314964d5878a9p-44 /* 6.778726354822545e-14 */
/* first neglected term at f = 1/2: 2^-63.7 of 2^f (at f = -1/2: 2^-62.7) */
/* log2(m) = K atanh(s): K = 2/ln2 split hi+lo, then K/(2n+1) for s^3 .. s^21 */
#define NP__LOG2_K_HI 0x1.71547652b82fep+1 /* 2.8853900817779268 */
#define NP__LOG2_K_LO 0x1.777d0ffda0d24p-55 /* 4.0710547481862066e-17 */
#define NP__LOG2_D3 0x1.ec709dc3a03fdp-1 /* 0.9617966939259756 */
#define NP__LOG2_D5 0x1.2776c50ef9bfep-1 /* 0.5770780163555853 */
#define NP__LOG2_D7 0x1.a61762a7aded9p-2 /* 0.4121985831111324 */
#define NP__LOG2_D9 0x1.484b13d7c02a9p-2 /* 0.3205988979753252 */
#define NP__LOG2_D11 0x1.0c9a84994022dp-2 /* 0.2623081892525388 */
#define NP__LOG2_D13 0x1.c68f568d31760p-3 /* 0.22195308321368667 */
#define NP__LOG2_D15 0x1.89f3b1694cffep-3 /* 0.19235933878519512 */
#define NP__LOG2_D17 0x1.5b9ac9b743f0dp-3 /* 0.16972882833987804 */
#define NP__LOG2_D19 0x1.3703c1f4d0ffep-3 /* 0.15186263588304877 */
#define NP__LOG2_D21 0x1.1964ec6fc9491p-3 /* 0.1373995277037108 */
/* first neglected term at |s| = 3-2sqrt2: 2^-60.5 of the s^1 term */
/* tanh x = x + x^3 P(x^2) for |x| < 1/2: coefficients of x^3 .. x^35 */
#define NP__TANH_T3 -0x1.5555555555555p-2 /* -0.3333333333333333 */
#define NP__TANH_T5 0x1.1111111111111p-3 /* 0.13333333333333333 */
#define NP__TANH_T7 -0x1.ba1ba1ba1ba1cp-5 /* -0.05396825396825397 */
#define NP__TANH_T9 0x1.664f4882c10fap-6 /* 0.021869488536155203 */
#define NP__TANH_T11 -0x1.226e355e6c23dp-7 /* -0.008863235529902197 */
#define NP__TANH_T13 0x1.d6d3d0e157de0p-9 /* 0.003592128036572481 */
#define NP__TANH_T15 -0x1.7da36452b75e3p-10 /* -0.0014558343870513183 */
#define NP__TANH_T17 0x1.3558248036744p-11 /* 0.000590027440945586 */
#define NP__TANH_T19 -0x1.f57d7734d1664p-13 /* -0.00023912911424355248 */
#define NP__TANH_T21 0x1.967e18afcafadp-14 /* 9.691537956929451e-05 */
#define NP__TANH_T23 -0x1.497d8eea25259p-15 /* -3.927832388331683e-05 */
#define NP__TANH_T25 0x1.0b132d39a6050p-16 /* 1.5918905069328964e-05 */
#define NP__TANH_T27 -0x1.b0f72d3ee24e9p-18 /* -6.451689215655431e-06 */
#define NP__TANH_T29 0x1.5ef2da474e5b7p-19 /* 2.6147711512907546e-06 */
#define NP__TANH_T31 -0x1.1c77df95c1c0dp-20 /* -1.0597268320104654e-06 */
#define NP__TANH_T33 0x1.cd299de4ae6bbp-22 /* 4.294911078273806e-07 */
#define NP__TANH_T35 -0x1.75cde6563fed9p-23 /* -1.7406618963571648e-07 */
/* first neglected term at x = 1/2: 2^-59.6 of tanh */

/* Veltkamp's splitter 2^27 + 1: a = hi + lo with hi, lo of 26 bits each. */
#define NP__SPLITTER 134217729.0
/* The nearest double to sqrt(1/2): where log2 centres the mantissa (any value near it works). */
#define NP__SQRT1_2 0x1.6a09e667f3bcdp-1
/* sin: below this |r| the kernel runs on r 2^NP__SIN_TINY_SCALE (its two_prod would underflow). */
#define NP__SIN_TINY 0x1p-900
#define NP__SIN_TINY_SCALE 200
/* tanh: below this the odd Taylor polynomial, at and above it (1 - E)/(1 + E). */
#define NP__TANH_POLY_MAX 0.5
/* tanh: at and above this |tanh x| rounds to 1 (1 - tanh 22 < 2^-62). */
#define NP__TANH_ONE 22.0
/* exp2: x >= 1024 overflows; below -1080 the result is 0 (anything <= -1075 rounds to 0). */
#define NP__EXP2_OVERFLOW 1024.0
#define NP__EXP2_ZERO (-1080.0)

static double np__nan(void)
{
    uint64_t bits = NP_MATH_NAN_BITS;
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

static void np__two_sum(double a, double b, double *s, double *e)
{
    double sum = a + b;
    double bb = sum - a;
    *e = (a - (sum - bb)) + (b - bb);
    *s = sum;
}

static void np__fast_two_sum(double a, double b, double *s, double *e)
{
    double sum = a + b;
    *e = b - (sum - a);
    *s = sum;
}

static void np__split(double a, double *hi, double *lo)
{
    double c = NP__SPLITTER * a;
    *hi = c - (c - a);
    *lo = a - *hi;
}

static void np__two_prod(double a, double b, double *p, double *e)
{
    double ah, al, bh, bl;
    double prod = a * b;
    np__split(a, &ah, &al);
    np__split(b, &bh, &bl);
    *e = ((ah * bh - prod) + ah * bl + al * bh) + al * bl;
    *p = prod;
}

/*
 * sin(pi/2 r) for |r| <= 1/2 (r exact, in quarter turns).
 * (pi/2) r is a double-double product (two_prod with pi/2 hi, plus r * lo);
 * the rest r^3 (A3 + r^2 (A5 + ... + r^2 A17)), whose size is at most 0.103
 * of the result, is added to the low part; one final rounding. Taylor
 * truncation 2^-62.9 relative. Odd in r bit for bit (every step is
 * sign-symmetric in round to nearest). Needs |r| >= 2^-900 for two_prod to
 * stay exact (no underflow); np_sincos_turns scales smaller r by 2^200 and the
 * result back by 2^-200 (exact for normal results; a subnormal result is
 * rounded a second time, to the 2^-1074 grid: < 1 ulp as np_math.h counts).
 */
static double np__sin_kernel(double r)
{
    double ph, pl;
    np__two_prod(r, NP__SIN_A1_HI, &ph, &pl);
    double z = r * r;
    double p = NP__SIN_A17;
    p = NP__SIN_A15 + z * p;
    p = NP__SIN_A13 + z * p;
    p = NP__SIN_A11 + z * p;
    p = NP__SIN_A9 + z * p;
    p = NP__SIN_A7 + z * p;
    p = NP__SIN_A5 + z * p;
    p = NP__SIN_A3 + z * p;
    double tail = (r * z) * p;
    return ph + ((pl + r * NP__SIN_A1_LO) + tail);
}

/*
 * cos(pi/2 r) for |r| <= 1/2, result in [0.707, 1].
 * 1 - (pi^2/8) r^2 in double-double: r^2 exact (two_prod), times B2 as
 * double-double, subtracted from 1 with fast_two_sum (B2 r^2 <= 0.309 < 1);
 * then r^4 (B4 + ... + r^2 B18) (at most 0.016) into the low part; one final
 * rounding. Taylor truncation 2^-67.5 relative. Even in r bit for bit.
 */
static double np__cos_kernel(double r)
{
    double zh, zl, bh, bl, w, we;
    np__two_prod(r, r, &zh, &zl);
    np__two_prod(NP__COS_B2_HI, zh, &bh, &bl);
    bl += NP__COS_B2_HI * zl + NP__COS_B2_LO * zh;
    np__fast_two_sum(1.0, -bh, &w, &we);
    double p = NP__COS_B18;
    p = NP__COS_B16 + zh * p;
    p = NP__COS_B14 + zh * p;
    p = NP__COS_B12 + zh * p;
    p = NP__COS_B10 + zh * p;
    p = NP__COS_B8 + zh * p;
    p = NP__COS_B6 + zh * p;
    p = NP__COS_B4 + zh * p;
    double tail = (zh * zh) * p;
    return w + ((we - bl) + tail);
}

/*
 * Exact reduction of a turn count (why no bit is lost):
 *   a = |t|. f = a - floor(a) is exact: for a < 2^53 the unit of a's last
 *   place is a power of two <= 1, so the integer floor(a) is a multiple of it
 *   and a - floor(a), a multiple of that unit below min(a, 1), fits in 53
 *   bits; for a >= 2^52 every double is an integer and f = 0.
 *   q = 4 f is exact (scaling by a power of two; q < 4 cannot overflow).
 *   n = floor(q), r = q - n in [0, 1) is exact by the same argument; when
 *   r > 1/2, r - 1 is exact (Sterbenz: 1/2 <= r <= 1) and n becomes n + 1.
 * So a = integer + (n + r)/4 exactly with |r| <= 1/2 (a tie r = 1/2 stays in
 * quadrant n), and 2 pi a = n pi/2 + (pi/2) r + 2 pi integer.
 * The quadrant picks a kernel and a sign; sin is then made odd (applied to
 * |t|, negated for t < 0) and cos even. Zeros are normalised to +0 before the
 * sign of t is applied.
 */
void np_sincos_turns(double t, double *s, double *c)
{
    if (isnan(t)) {
        *s = t;
        *c = t;
        return;
    }
    if (isinf(t)) {
        *s = np__nan();
        *c = np__nan();
        return;
    }
    double a = fabs(t);
    double f = a - floor(a);
    double q = 4.0 * f;
    double n = floor(q);
    double r = q - n;
    if (r > 0.5) {
        r -= 1.0;
        n += 1.0;
    }
    unsigned quadrant = (unsigned)n & 3u; /* n in 0..4 */
    double sk = np__sin_kernel(r), ck = np__cos_kernel(r);
    /*
     * Tiny r can only be r = 4|t| (n = 0). The kernel on r 2^200 (< 2^-700:
     * its r^3 part is 0, (pi/2) r^3/6 is below 2^-1700 of the value anyway)
     * forms (pi/2) r 2^200 without underflow; ldexp scales it back.
     */
    if (fabs(r) < NP__SIN_TINY)
        sk = ldexp(np__sin_kernel(ldexp(r, NP__SIN_TINY_SCALE)), -NP__SIN_TINY_SCALE);
    double sv, cv;
    switch (quadrant) {
    case 0: sv = sk; cv = ck; break;
    case 1: sv = ck; cv = -sk; break;
    case 2: sv = -sk; cv = -ck; break;
    default: sv = -ck; cv = sk; break;
    }
    sv = sv + 0.0; /* -0 + +0 = +0 in round to nearest; nonzero values unchanged */
    cv = cv + 0.0;
    *s = signbit(t) ? -sv : sv;
    *c = cv;
}

double np_sin_turns(double t)
{
    double s, c;
    np_sincos_turns(t, &s, &c);
    return s;
}

double np_cos_turns(double t)
{
    double s, c;
    np_sincos_turns(t, &s, &c);
    return c;
}

/*
 * 2^(yh + yl) = 2^k (hi + lo), the shared core of exp2 and tanh.
 * Preconditions: yh finite, |yh| <= 1100, |yl| <= 2^-40 (a rounding tail).
 * Reduction on |yh|, so that no bit is lost: for yh >= 0, k = floor(yh) and
 * f = yh - k is exact (as in the turn reduction), f > 1/2 moves to f - 1
 * (exact, Sterbenz) and k + 1; for yh < 0 the same on -yh, negated.
 * (yh - floor(yh) would not be exact for yh in (-1, 0): yh + 1 rounds.)
 * So yh = k + f exactly with |f| <= 1/2.
 * 2^g, g = f + yl: 1 + g ln2 with g ln2 in double-double (two_prod of f and
 * ln2 hi, plus f ln2_lo + yl ln2), plus g^2 (C2 + g (C3 + ... + g C14)),
 * Taylor, truncation 2^-62.7 relative; the polynomial part is at most 0.06
 * of the result, so its rounding errors stay below 2^-56 relative.
 * Output normalised: hi = fl(hi + lo), so hi + lo in [0.70, 1.42] and
 * |lo| <= 1/2 ulp(hi); ldexp(hi, k) is 2^(yh + yl) rounded once when normal.
 */
static int np__exp2_kernel(double yh, double yl, double *hi, double *lo)
{
    double ay = fabs(yh);
    double k = floor(ay);
    double f = ay - k;
    if (f > 0.5) {
        f -= 1.0;
        k += 1.0;
    }
    if (signbit(yh)) {
        k = -k;
        f = -f;
    }
    double ph, pl, s, se;
    np__two_prod(f, NP__LN2_HI, &ph, &pl);
    pl += f * NP__LN2_LO + yl * NP__LN2_HI;
    double g = f + yl;
    double p = NP__EXP2_C14;
    p = NP__EXP2_C13 + g * p;
    p = NP__EXP2_C12 + g * p;
    p = NP__EXP2_C11 + g * p;
    p = NP__EXP2_C10 + g * p;
    p = NP__EXP2_C9 + g * p;
    p = NP__EXP2_C8 + g * p;
    p = NP__EXP2_C7 + g * p;
    p = NP__EXP2_C6 + g * p;
    p = NP__EXP2_C5 + g * p;
    p = NP__EXP2_C4 + g * p;
    p = NP__EXP2_C3 + g * p;
    p = NP__EXP2_C2 + g * p;
    double tail = (g * g) * p;
    np__fast_two_sum(1.0, ph, &s, &se); /* |ph| <= 0.35 */
    np__fast_two_sum(s, se + (pl + tail), hi, lo);
    return (int)k;
}

/*
 * 2^x = ldexp(hi, k): one rounding of the double-double to 53 bits
 * (error <= 1/2 ulp + the kernel's 2^-56 relative), then an exact scaling for
 * normal results. For subnormal results ldexp rounds a second time to the
 * 2^-1074 grid: <= 1/2 unit of 2^-1074 plus the first rounding (2^-53 of the
 * value), still < 1 ulp as np_math.h counts it. Integers x = k give hi = 1,
 * lo = 0 and ldexp(1, k) = 2^k exactly. lo is not needed here (hi is already
 * the rounded sum); tanh uses it.
 */
double np_exp2(double x)
{
    if (isnan(x))
        return x;
    if (x >= NP__EXP2_OVERFLOW)
        return HUGE_VAL;
    if (x < NP__EXP2_ZERO)
        return 0.0;
    double hi, lo;
    int k = np__exp2_kernel(x, 0.0, &hi, &lo);
    return ldexp(hi, k);
}

/*
 * log2 x = e + log2 m, x = m 2^e with m in [sqrt(1/2), sqrt 2) from frexp
 * (exact, subnormals included). log2 m = K atanh(s), K = 2/ln 2,
 * s = (m - 1)/(m + 1), |s| <= 3 - 2 sqrt 2 = 0.1716.
 *   m - 1 is exact (Sterbenz); m + 1 = d + de exactly (two_sum);
 *   s = sh + sl with sh = fl((m-1)/d) and sl = (m - 1 - sh (d + de))/d, whose
 *   numerator is computed exactly up to the sh*de product (two_prod and
 *   Sterbenz): s to about 2^-100 relative.
 *   K (sh + sl) in double-double (two_prod with K hi), plus
 *   sh^3 (D3 + s^2 (D5 + ... + s^2 D21)), D(2n+1) = K/(2n+1), at most
 *   s^2/3 <= 0.0098 of the linear term; truncation 2^-60.5 relative.
 *   e + that: two_sum with the high part, one final rounding. m = 1 gives
 *   s = 0 and the result is e exactly.
 */
double np_log2(double x)
{
    if (isnan(x))
        return x;
    if (x < 0.0)
        return np__nan();
    if (x == 0.0)
        return -HUGE_VAL;
    if (isinf(x))
        return x;
    int e;
    double m = frexp(x, &e);
    if (m < NP__SQRT1_2) {
        m *= 2.0;
        e -= 1;
    }
    double f = m - 1.0;
    double d, de, p, pe;
    np__two_sum(m, 1.0, &d, &de);
    double sh = f / d;
    np__two_prod(sh, d, &p, &pe);
    double sl = (((f - p) - pe) - sh * de) / d;
    double lh, ll;
    np__two_prod(NP__LOG2_K_HI, sh, &lh, &ll);
    double z = sh * sh;
    double poly = NP__LOG2_D21;
    poly = NP__LOG2_D19 + z * poly;
    poly = NP__LOG2_D17 + z * poly;
    poly = NP__LOG2_D15 + z * poly;
    poly = NP__LOG2_D13 + z * poly;
    poly = NP__LOG2_D11 + z * poly;
    poly = NP__LOG2_D9 + z * poly;
    poly = NP__LOG2_D7 + z * poly;
    poly = NP__LOG2_D5 + z * poly;
    poly = NP__LOG2_D3 + z * poly;
    ll += (NP__LOG2_K_HI * sl + NP__LOG2_K_LO * sh) + (sh * z) * poly;
    double h, l;
    np__two_sum((double)e, lh, &h, &l);
    return h + (l + ll);
}

/*
 * tanh on a = |x|, then the sign of x (so tanh(-x) = -tanh(x) bit for bit).
 *   a < 1/2: a + a^3 (T3 + a^2 (T5 + ... + a^2 T35)), Taylor (alternating,
 *     truncation 2^-59.6 relative at a = 1/2); the polynomial part is at most
 *     a^2/3 <= 0.084 of the result, so no cancellation. Subnormal a give a.
 *   1/2 <= a < 22: E = e^(-2a) = 2^(-a K), K = 2/ln 2; -a K as a double-double
 *     (two_prod), the exp2 kernel gives E = 2^k (eh + el) with k in [-64, -1]
 *     (scaling eh, el by 2^k is exact: they stay normal); then
 *     (1 - E)/(1 + E) in double-double (fast_two_sum, E <= e^-1) and one
 *     corrected division. 1 - E loses no accuracy: a relative error of E is
 *     amplified by E/(1 - E) <= 0.59 (at a = 1/2, E = e^-1).
 *   a >= 22: 1.
 */
double np_tanh(double x)
{
    if (isnan(x))
        return x;
    double a = fabs(x), r;
    if (a < NP__TANH_POLY_MAX) {
        double z = a * a;
        double p = NP__TANH_T35;
        p = NP__TANH_T33 + z * p;
        p = NP__TANH_T31 + z * p;
        p = NP__TANH_T29 + z * p;
        p = NP__TANH_T27 + z * p;
        p = NP__TANH_T25 + z * p;
        p = NP__TANH_T23 + z * p;
        p = NP__TANH_T21 + z * p;
        p = NP__TANH_T19 + z * p;
        p = NP__TANH_T17 + z * p;
        p = NP__TANH_T15 + z * p;
        p = NP__TANH_T13 + z * p;
        p = NP__TANH_T11 + z * p;
        p = NP__TANH_T9 + z * p;
        p = NP__TANH_T7 + z * p;
        p = NP__TANH_T5 + z * p;
        p = NP__TANH_T3 + z * p;
        r = a + (a * z) * p;
    } else if (a < NP__TANH_ONE) {
        double yh, yl, eh, el, nh, nl, dh, dl, qp, qe;
        np__two_prod(-a, NP__LOG2_K_HI, &yh, &yl);
        yl += -a * NP__LOG2_K_LO;
        int k = np__exp2_kernel(yh, yl, &eh, &el);
        eh = ldexp(eh, k);
        el = ldexp(el, k);
        np__fast_two_sum(1.0, -eh, &nh, &nl);
        nl -= el;
        np__fast_two_sum(1.0, eh, &dh, &dl);
        dl += el;
        double q = nh / dh;
        np__two_prod(q, dh, &qp, &qe);
        double rem = (((nh - qp) - qe) + nl) - q * dl;
        r = q + rem / dh;
    } else {
        r = 1.0;
    }
    return signbit(x) ? -r : r;
}
