/* SPDX-License-Identifier: MIT */
#include <math.h>

#include "np_hashn.h"
#include "np_ref.h"
#include "np_refn.h"
#include "np_simplexn.h"

double np_ref_gradn(unsigned n, unsigned h, const double *d)
{
    if (n == 3u)
        return np_ref_grad(h, d[0], d[1], d[2]);
    double g = 0.0;
    if (n == 2u) {
        if ((h >> 2 & 1u) == 0u) /* an axis: b0 which, b1 the sign */
            g = (h >> 1 & 1u) ? -d[h & 1u] : d[h & 1u];
        else /* a diagonal: sign of axis a = bit a */
            g = ((h & 1u) ? -d[0] : d[0]) + ((h >> 1 & 1u) ? -d[1] : d[1]);
    } else if (n == 4u) { /* b1 b0: the zero axis; signs b2, b3, b4 to the others in order */
        unsigned bit = 2u;
        for (unsigned a = 0; a < 4u; a++)
            if (a != (h & 3u)) {
                g += (h >> bit & 1u) ? -d[a] : d[a];
                bit++;
            }
    } else { /* 5: the diagonals, sign of axis a = bit a */
        for (unsigned a = 0; a < n; a++)
            g += (h >> a & 1u) ? -d[a] : d[a];
    }
    return g;
}

static uint8_t low8(int64_t v) { return (uint8_t)((uint64_t)v & 255u); }

double np_ref_simplexn(unsigned n, const double *x)
{
    if (n == 3u)
        return np_ref_simplex3(x[0], x[1], x[2], NULL);
    const np_simplexn_geom *g = np_simplexn_geom_of(n);
    double q = (double)g->q, p = (double)g->p, gs = (double)g->p / (double)g->l, sum = 0.0;
    int64_t i[NP_SIMPLEXN_MAX], si = 0;
    double u[NP_SIMPLEXN_MAX];
    for (unsigned a = 0; a < n; a++)
        sum += x[a];
    /* skew by F = p/q: the cell floor(x_a + F sum) */
    for (unsigned a = 0; a < n; a++) {
        i[a] = (int64_t)floor((q * x[a] + p * sum) / q);
        si += i[a];
    }
    /* unskew by G = p/l: the offset from corner 0 */
    for (unsigned a = 0; a < n; a++)
        u[a] = x[a] - (double)i[a] + gs * (double)si;
    /* rank: decreasing u, ties to the lower axis */
    unsigned order[NP_SIMPLEXN_MAX];
    for (unsigned a = 0; a < n; a++) {
        unsigned r = 0;
        for (unsigned b = 0; b < n; b++)
            if (u[b] > u[a] || (u[b] == u[a] && b < a))
                r++;
        order[r] = a;
    }
    double f = 0.0;
    int a_off[NP_SIMPLEXN_MAX] = { 0 };
    for (unsigned c = 0; c <= n; c++) {
        if (c > 0)
            a_off[order[c - 1u]] = 1;
        double d[NP_SIMPLEXN_MAX], r2 = 0.0;
        uint8_t pt[NP_SIMPLEXN_MAX] = { 0 };
        for (unsigned a = 0; a < n; a++) {
            d[a] = u[a] - a_off[a] + gs * c;
            r2 += d[a] * d[a];
            pt[a] = low8(i[a] + a_off[a]);
        }
        double t = g->r2 - r2;
        if (t <= 0.0)
            continue;
        double t2 = t * t;
        f += (double)g->amp * t2 * t2 * np_ref_gradn(n, np_hashn(n, pt), d);
    }
    return f;
}

double np_ref_simplexn_q88(unsigned n, const uint16_t *x)
{
    double v[NP_SIMPLEXN_MAX];
    for (unsigned a = 0; a < n; a++)
        v[a] = x[a] / 256.0;
    return np_ref_simplexn(n, v);
}
