#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Print the polynomial coefficients of np_math.c (docs/math.md).

Standard library only (fractions, decimal): every coefficient is an exact
Taylor coefficient, computed with 80 significant digits and rounded once to
the nearest binary64 (Python's float() of a decimal string is correctly
rounded). For each series the script also prints the first neglected term at
the end of the reduced interval, relative to the function value there: that
is the truncation part of the error budget in np_math.h.

    python3 src/ref/np_math_coeffs.py
"""
from decimal import Decimal, getcontext
from fractions import Fraction
import math

getcontext().prec = 80


def dec_atan_inv(n):
    """atan(1/n) by its Taylor series, n >= 2."""
    x = Decimal(1) / n
    x2 = x * x
    term, total, k = x, Decimal(0), 0
    while abs(term) > Decimal(10) ** -85:
        total += term / (2 * k + 1) * (1 if k % 2 == 0 else -1)
        term *= x2
        k += 1
    return total


PI = 16 * dec_atan_inv(5) - 4 * dec_atan_inv(239)           # Machin


def dec_ln2():
    """ln 2 = 2 atanh(1/3)."""
    x = Decimal(1) / 3
    x2 = x * x
    term, total, k = x, Decimal(0), 0
    while term > Decimal(10) ** -85:
        total += term / (2 * k + 1)
        term *= x2
        k += 1
    return 2 * total


LN2 = dec_ln2()


def fact(n):
    return Decimal(math.factorial(n))


def bernoulli(n):
    """B_0..B_n as Fractions (B_1 = -1/2)."""
    b = [Fraction(0)] * (n + 1)
    for m in range(n + 1):
        b[m] = Fraction(1) if m == 0 else -sum(
            Fraction(math.comb(m + 1, k)) * b[k] for k in range(m)) / (m + 1)
    return b


def dbl(d):
    return float(str(d))


def emit(name, d):
    f = dbl(d)
    print(f"#define {name} {f.hex()} /* {f!r} */")


def emit_split(name, d):
    hi = dbl(d)
    lo = dbl(d - Decimal(hi))                  # Decimal(float) is exact
    print(f"#define {name}_HI {hi.hex()} /* {hi!r} */")
    print(f"#define {name}_LO {lo.hex()} /* {lo!r} */")


def rel(term, value):
    return f"2^{math.log2(abs(float(term / value))):.1f}"


# sin(pi/2 r) = sum_k (-1)^k (pi/2)^(2k+1) r^(2k+1) / (2k+1)!, |r| <= 1/2.
H = PI / 2
print("/* sin(pi/2 r): r^1 coefficient split hi+lo, then r^3 .. r^17 */")
emit_split("NP__SIN_A1", H)
for k in range(1, 9):
    emit(f"NP__SIN_A{2 * k + 1}", (-1) ** k * H ** (2 * k + 1) / fact(2 * k + 1))
x = H / 2
print(f"/* first neglected term at r = 1/2: {rel(x ** 19 / fact(19), Decimal(math.sin(float(x))))} of sin */")

print("/* cos(pi/2 r): r^2 coefficient split hi+lo, then r^4 .. r^18 */")
emit_split("NP__COS_B2", H ** 2 / 2)
for k in range(2, 10):
    emit(f"NP__COS_B{2 * k}", (-1) ** k * H ** (2 * k) / fact(2 * k))
print(f"/* first neglected term at r = 1/2: {rel(x ** 20 / fact(20), Decimal(math.cos(float(x))))} of cos */")

# 2^f = 1 + f ln2 + sum_{n>=2} (ln2)^n f^n / n!, |f| <= 1/2.
print("/* 2^f: f^1 coefficient ln 2 split hi+lo, then f^2 .. f^14 */")
emit_split("NP__LN2", LN2)
for n in range(2, 15):
    emit(f"NP__EXP2_C{n}", LN2 ** n / fact(n))
u = LN2 / 2
print(f"/* first neglected term at f = 1/2: {rel(u ** 15 / fact(15), Decimal(2).sqrt())} of 2^f "
      f"(at f = -1/2: {rel(u ** 15 / fact(15), 1 / Decimal(2).sqrt())}) */")

# log2(m) = (2/ln2) atanh(s) = (2/ln2) sum_n s^(2n+1)/(2n+1), s = (m-1)/(m+1), |s| <= 3-2sqrt2.
K = 2 / LN2
print("/* log2(m) = K atanh(s): K = 2/ln2 split hi+lo, then K/(2n+1) for s^3 .. s^21 */")
emit_split("NP__LOG2_K", K)
for n in range(1, 11):
    emit(f"NP__LOG2_D{2 * n + 1}", K / (2 * n + 1))
smax = 3 - 2 * Decimal(2).sqrt()
print(f"/* first neglected term at |s| = 3-2sqrt2: {rel(smax ** 22 / 23, Decimal(1))} of the s^1 term */")

# tanh x = sum_n 2^(2n) (2^(2n)-1) B_(2n) x^(2n-1) / (2n)!, |x| <= 1/2.
B = bernoulli(40)
print("/* tanh x = x + x^3 P(x^2) for |x| < 1/2: coefficients of x^3 .. x^35 */")
for n in range(2, 19):
    c = Fraction(2 ** (2 * n) * (2 ** (2 * n) - 1)) * B[2 * n] / math.factorial(2 * n)
    emit(f"NP__TANH_T{2 * n - 1}", Decimal(c.numerator) / Decimal(c.denominator))
n = 19
c = Fraction(2 ** (2 * n) * (2 ** (2 * n) - 1)) * B[2 * n] / math.factorial(2 * n)
t37 = Decimal(c.numerator) / Decimal(c.denominator) * Decimal("0.5") ** 37
print(f"/* first neglected term at x = 1/2: {rel(t37, Decimal(math.tanh(0.5)))} of tanh */")
