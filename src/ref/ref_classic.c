/* SPDX-License-Identifier: MIT */
#include "np_ref.h"

#include <math.h>

#include "np_ref_fast.h"

#include "np_hash.h"

double np_ref_grad(unsigned h, double x, double y, double z)
{
    /* Transcribed from the seed's Appendix B, K(). */
    unsigned b5 = h >> 5 & 1u, b4 = h >> 4 & 1u, b3 = h >> 3 & 1u, b2 = h >> 2 & 1u, b = h & 3u;
    double p = b == 1 ? x : b == 2 ? y : z;
    double q = b == 1 ? y : b == 2 ? z : x;
    double r = b == 1 ? z : b == 2 ? x : y;
    p = (b5 == b3 ? -p : p);
    q = (b5 == b4 ? -q : q);
    r = (b5 != (b4 ^ b3) ? -r : r);
    return p + (b == 0 ? q + r : b2 == 0 ? q : r);
}

static double s_curve(double t) { return t * t * (3.0 - 2.0 * t); }
static double lerp(double t, double a, double b) { return a + t * (b - a); }

double np_ref_classic3_in_cell(const uint8_t h[8], double u, double v, double w)
{
    double g[8];
    for (unsigned c = 0; c < 8; c++)
        g[c] = np_ref_grad_fast(h[c], (c & 1u) ? u - 1.0 : u, (c & 2u) ? v - 1.0 : v,
                           (c & 4u) ? w - 1.0 : w);
    double sx = s_curve(u), sy = s_curve(v), sz = s_curve(w);
    double a = lerp(sx, g[0], g[1]), b = lerp(sx, g[2], g[3]);
    double c0 = lerp(sy, a, b);
    a = lerp(sx, g[4], g[5]);
    b = lerp(sx, g[6], g[7]);
    double c1 = lerp(sy, a, b);
    return lerp(sz, c0, c1);
}

double np_ref_classic3(double x, double y, double z)
{
    double fx = floor(x), fy = floor(y), fz = floor(z);
    /* Cell index mod 256; fmod of an integral double is exact. */
    double mi = fmod(fx, 256.0), mj = fmod(fy, 256.0), mk = fmod(fz, 256.0);
    unsigned i = (unsigned)(mi < 0 ? mi + 256.0 : mi), j = (unsigned)(mj < 0 ? mj + 256.0 : mj),
             k = (unsigned)(mk < 0 ? mk + 256.0 : mk);
    uint8_t h[8];
    for (unsigned c = 0; c < 8; c++)
        h[c] = np_hash6_fast((uint8_t)((i + (c & 1u)) & 255u), (uint8_t)((j + (c >> 1 & 1u)) & 255u),
                        (uint8_t)((k + (c >> 2 & 1u)) & 255u));
    return np_ref_classic3_in_cell(h, x - fx, y - fy, z - fz);
}

/*
 * At a Q8.8 word w the value w / 256 is exact, floor() of it is w >> 8 (a cell
 * < 256, so fmod by 256 leaves it) and w / 256 - floor is (w & 255) / 256,
 * both exact: the same cell, hashes and doubles as np_ref_classic3(w / 256),
 * without floor and fmod (sweep.kernel_ref_cell compares every bit).
 */
double np_ref_classic3_q88(uint16_t x, uint16_t y, uint16_t z)
{
    unsigned i = (unsigned)x >> 8, j = (unsigned)y >> 8, k = (unsigned)z >> 8;
    uint8_t h[8];
    for (unsigned c = 0; c < 8; c++)
        h[c] = np_hash6_fast((uint8_t)((i + (c & 1u)) & 255u), (uint8_t)((j + (c >> 1 & 1u)) & 255u),
                             (uint8_t)((k + (c >> 2 & 1u)) & 255u));
    return np_ref_classic3_in_cell(h, (double)(x & 255u) / 256.0, (double)(y & 255u) / 256.0,
                                   (double)(z & 255u) / 256.0);
}
