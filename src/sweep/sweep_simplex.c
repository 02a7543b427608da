/* SPDX-License-Identifier: MIT */
/*
 * simplex3's sweep kernel (np_unit.sweep_rows): rows of 256 inputs at one
 * (y, z), the bit-exact model through its batch loop (np_simplex_eval_n,
 * vectorised across the row) and the float reference through a row form of
 * np_ref_simplex3 that gives the very same doubles (test
 * sweep.simplex_kernel_*), also vectorised across the row.
 *
 * The reference row. np_ref_simplex3 (src/ref/ref_simplex.c) per input, in
 * its order of operations, with three changes that change no bit:
 *  - floor(x + s) is kept as a double fi (an integer < 2^10) instead of an
 *    int64_t: i + j + k and x - i are then exact double operations on the
 *    same integers, and the hash reads (int32_t)fi's low 8 bits;
 *  - the hash and gradient come from the 32-bit tables (np_hash.h; == the
 *    bit loop for every argument, fast.hash_exhaustive), and the gradient
 *    g = p + (q + r) of Appendix B is formed with the unused term as +0.0
 *    (two-term gradients: p + (q + 0) == p + q except for the sign of a zero
 *    result);
 *  - a corner outside the kernel (t < 0) leaves f and df unchanged by a
 *    select instead of a `continue`.
 * Why the sign of a zero g changes nothing: f and df start at +0.0 and only
 * ever have terms added (df: 8 t^4 G_a - 64 t^3 g d_a, itself +0.0 - (+-0.0)
 * = +0.0 when it is zero); under round-to-nearest x + (+-0) == x for x != 0
 * and +0 + (+-0) == +0, so a sum that starts at +0.0 is never -0.0 and a
 * term's zero sign cannot show in it. Every other operation is the
 * reference's, in its order, with -ffp-contract=off (no FMA) in every clone.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "np_hash.h"
#include "np_simplex.h"
#include "np_sweep.h"

/* Appendix B's gradient of index h as selectors: p, q, r axes and signs; q/r unused -> coefficient 0. */
typedef struct ref_grad_sel {
    double sp, sq, sr; /* +-1.0, or 0.0 for an unused q or r */
    uint32_t rot;      /* b = h & 3: which axis p is (1: x, 2: y, 0 or 3: z) */
} ref_grad_sel;

NP_SWEEP_INLINE double pick(uint32_t rot, double a1, double a2, double a0)
{
    return rot == 1u ? a1 : rot == 2u ? a2 : a0;
}

/* One row of np_ref_simplex3 at (x0 + t) / 256, y / 256, z / 256, t < 256; f and grad into ref[k * stride + t]. */
NP_SWEEP_INLINE void ref_row(uint16_t x0, uint16_t yw, uint16_t zw, const int deriv, double *restrict rf,
                             double *restrict rdx, double *restrict rdy, double *restrict rdz)
{
    const double y = (double)yw / 256.0, z = (double)zw / 256.0;
    for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
        double x = (double)(uint16_t)(x0 + t) / 256.0;
        double s = (x + y + z) / 3;
        double fi = floor(x + s), fj = floor(y + s), fk = floor(z + s);
        s = (fi + fj + fk) / 6.;
        double u = x - fi + s, v = y - fj + s, w = z - fk + s;
        int hi = u >= w ? u >= v ? 0 : 1 : v >= w ? 1 : 2;
        int lo = u < w ? u < v ? 0 : 1 : v < w ? 1 : 2;
        int mid = 3 - hi - lo;
        uint32_t ci = (uint32_t)(int32_t)fi, cj = (uint32_t)(int32_t)fj, ck = (uint32_t)(int32_t)fk;
        double f = 0.0, df0 = 0.0, df1 = 0.0, df2 = 0.0;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC unroll 4
#endif
        for (unsigned c = 0; c < 4; c++) {
            /* corner offsets: 0, e_hi, e_hi + e_mid, (1,1,1) */
            int c1 = c >= 1u, c2 = c >= 2u, c3 = c >= 3u;
            uint32_t a0 = (uint32_t)((c1 & (hi == 0)) + (c2 & (mid == 0)) + (c3 & (lo == 0)));
            uint32_t a1 = (uint32_t)((c1 & (hi == 1)) + (c2 & (mid == 1)) + (c3 & (lo == 1)));
            uint32_t a2 = (uint32_t)((c1 & (hi == 2)) + (c2 & (mid == 2)) + (c3 & (lo == 2)));
            double sa = (double)(a0 + a1 + a2) / 6.;
            double d0 = u - (double)a0 + sa, d1 = v - (double)a1 + sa, d2 = w - (double)a2 + sa;
            double tt = .6 - d0 * d0 - d1 * d1 - d2 * d2;
            uint32_t h = np_hash6_fast32((ci + a0) & 255u, (cj + a1) & 255u, (ck + a2) & 255u);
            uint32_t b5 = h >> 5 & 1u, b4 = h >> 4 & 1u, b3 = h >> 3 & 1u, b2 = h >> 2 & 1u, rot = h & 3u;
            double sp = b5 == b3 ? -1.0 : 1.0;
            double sq = (rot == 0u || b2 == 0u) ? (b5 == b4 ? -1.0 : 1.0) : 0.0;
            double sr = (rot == 0u || b2 != 0u) ? (b5 != (b4 ^ b3) ? -1.0 : 1.0) : 0.0;
            double p = sp * pick(rot, d0, d1, d2), q = sq * pick(rot, d1, d2, d0), r = sr * pick(rot, d2, d0, d1);
            double g = p + (q + r);
            double t2 = tt * tt;
            int in = !(tt < 0);
            f = in ? f + 8 * t2 * t2 * g : f;
            if (deriv) {
                double t3 = t2 * tt, t4 = t2 * t2;
                /* grad_coef: the coefficient of each axis (p on its axis, q, r on theirs) */
                double gx = pick(rot, sp, sr, sq), gy = pick(rot, sq, sp, sr), gz = pick(rot, sr, sq, sp);
                df0 = in ? df0 + (8 * t4 * gx - 64 * t3 * g * d0) : df0;
                df1 = in ? df1 + (8 * t4 * gy - 64 * t3 * g * d1) : df1;
                df2 = in ? df2 + (8 * t4 * gz - 64 * t3 * g * d2) : df2;
            }
        }
        rf[t] = f;
        if (deriv) {
            rdx[t] = df0;
            rdy[t] = df1;
            rdz[t] = df2;
        }
    }
}

/* The row with and without the derivative, each compiled without a branch on it (so it vectorises). */
NP_SWEEP_CLONES static void ref_row_d(uint16_t x0, uint16_t y, uint16_t z, double *rf, double *rdx, double *rdy,
                                      double *rdz)
{
    ref_row(x0, y, z, 1, rf, rdx, rdy, rdz);
}

NP_SWEEP_CLONES static void ref_row_f(uint16_t x0, uint16_t y, uint16_t z, double *rf)
{
    ref_row(x0, y, z, 0, rf, NULL, NULL, NULL);
}

void np_sweep_simplex3_rows(const np_simplex_cfg *cfg, uint16_t x0, uint16_t y0, uint16_t z, unsigned rows,
                            unsigned what, int32_t *code, double *ref)
{
    unsigned nf = cfg->deriv ? 4u : 1u;
    for (unsigned r = 0; r < rows; r++) {
        uint16_t y = (uint16_t)(y0 + r);
        if (what & NP_SWEEP_MODEL) {
            uint16_t xs[NP_SWEEP_ROW], ys[NP_SWEEP_ROW], zs[NP_SWEEP_ROW];
            np_simplex_out o[NP_SWEEP_ROW];
            for (unsigned t = 0; t < NP_SWEEP_ROW; t++) {
                xs[t] = (uint16_t)(x0 + t);
                ys[t] = y;
                zs[t] = z;
            }
            np_simplex_eval_n(cfg, xs, ys, zs, o, NP_SWEEP_ROW);
            for (unsigned k = 0; k < nf; k++) {
                int32_t *dst = code + ((size_t)k * rows + r) * NP_SWEEP_ROW;
                for (unsigned t = 0; t < NP_SWEEP_ROW; t++)
                    dst[t] = k == 0 ? o[t].f : o[t].df[k - 1u];
            }
        }
        if (what & NP_SWEEP_REF) {
            double *b = ref + (size_t)r * NP_SWEEP_ROW;
            size_t fs = (size_t)rows * NP_SWEEP_ROW;
            if (cfg->deriv)
                ref_row_d(x0, y, z, b, b + fs, b + 2 * fs, b + 3 * fs);
            else
                ref_row_f(x0, y, z, b);
        }
    }
}
