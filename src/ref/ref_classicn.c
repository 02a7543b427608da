/* SPDX-License-Identifier: MIT */
#include <math.h>

#include "np_hashn.h"
#include "np_ref.h"
#include "np_refn.h"

enum { MAXN = 5, CORNERS = 32 };

static double s_curve(double t) { return t * t * (3.0 - 2.0 * t); }
static double lerp(double t, double a, double b) { return a + t * (b - a); }

double np_ref_classicn(unsigned n, const double *x)
{
    if (n == 3u)
        return np_ref_classic3(x[0], x[1], x[2]);
    unsigned cell[MAXN];
    double u[MAXN], v[CORNERS];
    for (unsigned a = 0; a < n; a++) {
        double fl = floor(x[a]), m = fmod(fl, 256.0);
        cell[a] = (unsigned)(m < 0 ? m + 256.0 : m);
        u[a] = x[a] - fl;
    }
    for (unsigned c = 0; c < (1u << n); c++) {
        uint8_t pt[MAXN] = { 0 };
        double d[MAXN] = { 0 };
        for (unsigned a = 0; a < n; a++) {
            pt[a] = (uint8_t)((cell[a] + (c >> a & 1u)) & 255u);
            d[a] = (c >> a & 1u) ? u[a] - 1.0 : u[a];
        }
        v[c] = np_ref_gradn(n, np_hashn(n, pt), d);
    }
    /* level m interpolates along axis m the pairs (2p, 2p + 1) of level m - 1 */
    for (unsigned a = 0; a < n; a++) {
        double s = s_curve(u[a]);
        for (unsigned p = 0; p < (1u << (n - 1u - a)); p++)
            v[p] = lerp(s, v[2 * p], v[2 * p + 1]);
    }
    return v[0];
}

double np_ref_classicn_q88(unsigned n, const uint16_t *x)
{
    double v[MAXN];
    for (unsigned a = 0; a < n; a++)
        v[a] = x[a] / 256.0;
    return np_ref_classicn(n, v);
}
