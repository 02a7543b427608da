/* SPDX-License-Identifier: MIT */
/*
 * ref_hatch.c - float reference of the hatching unit (np_ref.h, docs/hatch.md):
 * Algorithm 1 of Szécsi & Szirányi with exact rational seeds.
 */
#include "np_hatch.h"
#include "np_ref.h"

/*
 * x - s_i + 1/2 (mod 2) for x = xw / 2^32 and s = W / D, D = 2^N - 1, exactly:
 * E = xw D + 2^31 D - W 2^32 (+ 2^33 D to keep it non-negative) over 2^32 D.
 * The parity is floor(E / (2^32 D)) mod 2, the fraction (E mod 2^32 D) / (2^32 D).
 */
static double exact_frac(uint64_t xw, uint64_t w, unsigned n, unsigned *parity)
{
    np_u128 d = n >= 64u ? (np_u128)~(uint64_t)0 : (((np_u128)1 << n) - 1u);
    np_u128 unit = d << 32, per = d << 33;
    np_u128 e = (np_u128)xw * d + (d << 31) + per - ((np_u128)w << 32);
    e %= per;
    *parity = e >= unit;
    np_u128 fr = e % unit;
    return (double)fr / (double)unit;
}

static double clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }
static double smooth(double t) { return t * t * (3.0 - 2.0 * t); }

double np_ref_hatch(const struct np_hatch_cfg *cfg, uint64_t xu, uint64_t xv, uint32_t tone, uint32_t pm, uint32_t om,
                    double *alpha)
{
    unsigned n = np_hatch_n(cfg);
    double a = (double)(tone & 0xFFu) / 255.0;
    double oms = (double)(om > 65536u ? 65536u : om) / 65536.0, m = 1.0 - oms;
    double p = (double)pm / 65536.0;
    double ku = p * (double)cfg->inv_u / 256.0, kv = p * (double)cfg->inv_v / 256.0;
    double c = 1.0;
    for (unsigned l = 0; l < cfg->layers; l++) {
        double al = clamp01(4.0 * a - (double)l);
        int16_t r[2][2];
        uint64_t bu, bv;
        np_hatch_layer_r(cfg, l, r);
        np_hatch_layer_b(cfg, l, &bu, &bv);
        double r00 = r[0][0] / 16384.0, r01 = r[0][1] / 16384.0;
        double r10 = r[1][0] / 16384.0, r11 = r[1][1] / 16384.0;
        for (unsigned i = 0; i < n; i++) {
            uint64_t wu = np_hatch_rotl(bu, i, n), wv = np_hatch_rotl(bv, i, n);
            unsigned pu, pv;
            double ru = exact_frac(xu, wu, n, &pu) - 0.5, rv = exact_frac(xv, wv, n, &pv) - 0.5;
            int surv = pu == (wu & 1u) && pv == (wv & 1u);
            double Qu = 2.0 * (r00 * ru + r01 * rv) * ku, Qv = 2.0 * (r10 * ru + r11 * rv) * kv;
            double y = 0.0;
            if (Qu > -1.0 && Qu < 1.0 && Qv > -1.0 && Qv < 1.0) {
                double u2 = Qu * Qu, v2 = Qv * Qv, u4 = u2 * u2;
                y = (1.0 - u4 * u4) * (1.0 - v2 * v2);
            }
            double at, am;
            if (cfg->fade == NP_HATCH_FADE_ONE_BY_ONE) {
                at = smooth(clamp01((double)(n + 1u) * al - (double)i));
                am = surv ? 1.0 : 1.0 - smooth(clamp01((double)(n + 1u) * m - (double)i));
            } else {
                at = al;
                am = surv ? 1.0 : oms;
            }
            double al_i = at * am * y;
            if (alpha)
                alpha[l * n + i] = al_i;
            c *= 1.0 - al_i;
        }
    }
    return 255.0 * c;
}
