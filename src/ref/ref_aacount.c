/* SPDX-License-Identifier: MIT */
/*
 * The exact rational reference of the aacount unit's sample count (np_ref.h).
 * Written from the paper's formulas, not from the model: every quantity is an
 * exact fraction in __int128, each metric's ceil(k) found directly.
 */
#include "np_aacount.h"
#include "np_ref.h"

typedef __int128 i128;

/* The paper's Fig. 3, transcribed again (rows b, columns a). */
static const int ref_b2[4] = { 0, 2, 3, 1 };
static const int ref_b3[9] = { 2, 6, 3, 5, 0, 8, 1, 7, 4 };
static const int ref_b4[16] = { 1, 8, 2, 10, 12, 4, 14, 6, 3, 11, 0, 9, 15, 7, 13, 5 };

static unsigned clampn(i128 k, unsigned n)
{
    if (k < 1)
        return 1;
    if (k > (i128)n)
        return n;
    return (unsigned)k;
}

/* ceil(a / b) for a >= 0, b > 0 */
static i128 ceil_div(i128 a, i128 b) { return (a + b - 1) / b; }

/*
 * k_d = c_d (sum d^2 / n - (sum d / n)^2) / 2^48 = c_d S / (n^2 2^48), with
 * n^2 Var = S = sum over pairs i < j of (d_i - d_j)^2.
 */
static unsigned ref_depth(const np_aacount_cfg *c, const np_aacount_win *w, unsigned n)
{
    i128 pairs = 0;
    for (unsigned i = 0; i < n; i++)
        for (unsigned j = i + 1; j < n; j++) {
            i128 e = (i128)w->d[i] - (i128)w->d[j];
            pairs += e * e;
        }
    i128 num = (i128)c->c_d * pairs, den = (i128)n * n * ((i128)1 << 48);
    return clampn(ceil_div(num, den), n);
}

/*
 * k_n = c sqrt(1 - mu), c = C/4, mu = min over surface samples of
 * |nbar . n_i| / (|nbar| |n_i|). ceil(k_n) = the least j >= 0 with k_n <= j:
 * k_n <= j iff 1 - j^2/c^2 <= mu, i.e. (when a = 1 - 16 j^2 / C^2 > 0) for
 * every sample a^2 <= (nbar . n_i)^2 / (|nbar|^2 |n_i|^2).
 */
static unsigned ref_normal(const np_aacount_cfg *c, const np_aacount_win *w, unsigned n)
{
    long long nb[3] = { 0, 0, 0 };
    int any = 0;
    for (unsigned i = 0; i < n; i++)
        for (unsigned k = 0; k < 3; k++) {
            nb[k] += w->nrm[i][k];
            any |= w->nrm[i][k] != 0;
        }
    i128 C = c->c_n;
    if (!any || C == 0)
        return 1;
    i128 nb2 = (i128)nb[0] * nb[0] + (i128)nb[1] * nb[1] + (i128)nb[2] * nb[2];
    if (nb2 == 0)
        return n; /* the mean normal vanishes: PIN k_n = n */
    for (unsigned j = 0; j < n; j++) {
        i128 a_num = C * C - 16 * (i128)j * j; /* a = a_num / C^2 */
        if (a_num <= 0)
            return clampn(j, n);
        int all = 1;
        for (unsigned i = 0; i < n && all; i++) {
            i128 dot = 0, nn = 0;
            for (unsigned k = 0; k < 3; k++) {
                dot += (i128)nb[k] * w->nrm[i][k];
                nn += (i128)w->nrm[i][k] * w->nrm[i][k];
            }
            if (nn == 0)
                continue;
            /* a^2 <= dot^2 / (nb2 nn)  <=>  a_num^2 nb2 nn <= dot^2 C^4 */
            if (a_num * a_num * nb2 * nn > dot * dot * C * C * C * C)
                all = 0;
        }
        if (all)
            return clampn(j, n);
    }
    return n;
}

/*
 * k_s on the [0, 1] scale: r/255 < max(t_min/255, (lmax/255)(t_edge/256))
 * gives 0; otherwise k_s = (C_s/16)(r/255).
 */
static unsigned ref_luma(const np_aacount_cfg *c, const np_aacount_win *w)
{
    int lo = 255, hi = 0;
    for (unsigned i = c->luma_taps == 5 ? 0u : 1u; i < 5; i++) {
        lo = w->luma[i] < lo ? w->luma[i] : lo;
        hi = w->luma[i] > hi ? w->luma[i] : hi;
    }
    i128 r = hi - lo;
    /* r < t_min  or  r < hi t_edge / 256 */
    if (r < c->t_min || 256 * r < (i128)hi * c->t_edge)
        return 0;
    return 2; /* marker: not gated */
}

void np_ref_aacount(const np_aacount_cfg *c, const np_aacount_win *w, np_ref_aacount_counts *o)
{
    unsigned m = c->m, n = m * m;
    o->sd = o->sn = o->ss = 0;
    if (c->depth)
        o->sd = ref_depth(c, w, n);
    if (c->normal)
        o->sn = ref_normal(c, w, n);
    if (c->luma) {
        if (ref_luma(c, w) == 0) {
            o->ss = 1;
        } else {
            int lo = 255, hi = 0;
            for (unsigned i = c->luma_taps == 5 ? 0u : 1u; i < 5; i++) {
                lo = w->luma[i] < lo ? w->luma[i] : lo;
                hi = w->luma[i] > hi ? w->luma[i] : hi;
            }
            o->ss = clampn(ceil_div((i128)c->c_s * (hi - lo), 16 * 255), n);
        }
    }
    unsigned s = 1;
    s = o->sd > s ? o->sd : s;
    s = o->sn > s ? o->sn : s;
    s = o->ss > s ? o->ss : s;
    o->s = s;
    const int *b = m == 2 ? ref_b2 : m == 3 ? ref_b3 : m == 4 ? ref_b4 : NULL;
    o->mask = 0;
    for (unsigned i = 0; i < n; i++)
        if ((b ? b[i] : 0) < (int)s)
            o->mask |= 1u << i;
}
