/* SPDX-License-Identifier: MIT */
#include "np_ref.h"

#include <math.h>

#include "np_hash.h"
#include "np_ref_fast.h"

/* Low 8 bits of an integer-valued double's two's complement: Appendix B's b() reads these. */
static uint8_t low8(int64_t n) { return (uint8_t)((uint64_t)n & 255u); }

double np_ref_simplex3(double x, double y, double z, double grad[3])
{
    /* noise(): skew, cell, unskew, rank; Appendix B's expressions in its order. */
    double s = (x + y + z) / 3;
    int64_t i = (int64_t)floor(x + s), j = (int64_t)floor(y + s), k = (int64_t)floor(z + s);
    s = (double)(i + j + k) / 6.;
    double u = x - (double)i + s, v = y - (double)j + s, w = z - (double)k + s;
    int hi = u >= w ? u >= v ? 0 : 1 : v >= w ? 1 : 2;
    int lo = u < w ? u < v ? 0 : 1 : v < w ? 1 : 2;
    const int step[4] = { hi, 3 - hi - lo, lo, 0 }; /* the axis K(a) increments after corner c */
    int a_off[3] = { 0, 0, 0 };
    double f = 0.0, df[3] = { 0.0, 0.0, 0.0 };
    for (unsigned c = 0; c < 4; c++) {
        /* K(): corner offset A, relative point, kernel. */
        double sa = (a_off[0] + a_off[1] + a_off[2]) / 6.;
        double d[3] = { u - a_off[0] + sa, v - a_off[1] + sa, w - a_off[2] + sa };
        double t = .6 - d[0] * d[0] - d[1] * d[1] - d[2] * d[2];
        unsigned h = np_hash6_fast(low8(i + a_off[0]), low8(j + a_off[1]), low8(k + a_off[2]));
        a_off[step[c]]++;
        if (t < 0)
            continue; /* K() returns 0; the sum's order is unchanged by adding 0 */
        double g = np_ref_grad_fast(h, d[0], d[1], d[2]); /* == np_ref_grad, every bit */
        double t2 = t * t;
        f += 8 * t2 * t2 * g;
        if (grad) {
            /* d/dp [8 t^4 (G.d)] = 8 t^4 G - 64 t^3 (G.d) d, with t = .6 - |d|^2. */
            double t3 = t2 * t, t4 = t2 * t2;
            const double *gc = np_ref_grad_coef[h]; /* Appendix B's coefficients (np_ref_fast.h) */
            for (unsigned a = 0; a < 3; a++)
                df[a] += 8 * t4 * gc[a] - 64 * t3 * g * d[a];
        }
    }
    if (grad)
        for (unsigned a = 0; a < 3; a++)
            grad[a] = df[a];
    return f;
}

double np_ref_simplex3_q88(uint16_t x, uint16_t y, uint16_t z, double grad[3])
{
    return np_ref_simplex3(x / 256.0, y / 256.0, z / 256.0, grad);
}
