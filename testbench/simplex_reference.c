/* SPDX-License-Identifier: MIT */
/* The simplex unit's float reference: against the Appendix B transcription, the analytic
 * derivative against central differences, the jumps of the reference across simplex faces. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "simplex_test.h"

/* ------------------------------------------------------------------------ */

/* The reference's derivative against the transcription's of the last J_noise(): largest difference, equal components. */
static void deriv_cmp(const double g[3], double *maxdd, uint64_t *same)
{
    for (unsigned a = 0; a < 3; a++) {
        double d = fabs(g[a] - J_dK[a]);
        NP_CHECK(d <= 1e-12, "derivative %u: ref %.17g, transcription %.17g", a, g[a], J_dK[a]);
        *maxdd = fmax(*maxdd, d);
        *same += g[a] == J_dK[a];
    }
}

int simplex_ref_vs_appendix_b(void)
{
    /*
     * Random real points of several scales (negative and large included),
     * 8.8 grid points, integers, and points on the faces x = y, y = z, x = z,
     * x = y = z and on skewed-cell faces; reference and transcription must
     * agree to 1e-12 (they are written with the same operations in the same
     * order, so they are expected to agree exactly).
     */
    np_rng r;
    np_rng_seed(&r, 0x5eed);
    static const double scale[] = { 1.0, 10.0, 300.0, 1e4, 1e6 };
    double maxd = 0.0, maxdd = 0.0, maxdd88 = 0.0;
    uint64_t n = 0, same = 0, dsame = 0, dsame88 = 0;
    for (unsigned it = 0; it < 1500000; it++) {
        double p[3];
        unsigned kind = it % 10u;
        double sc = scale[(it / 10u) % 5u];
        for (unsigned a = 0; a < 3; a++)
            p[a] = (2.0 * rnd01(&r) - 1.0) * sc;
        switch (kind) {
        case 0: case 1: case 2: break;                                   /* random, both signs */
        case 3: for (unsigned a = 0; a < 3; a++) p[a] = floor(p[a] * 256.0) / 256.0; break; /* 8.8 grid, any sign */
        case 4: for (unsigned a = 0; a < 3; a++) p[a] = floor(p[a]); break;                /* integers */
        case 5: p[1] = p[0]; break;                                      /* x = y: u = v */
        case 6: p[2] = p[1]; break;                                      /* v = w */
        case 7: p[2] = p[0]; break;                                      /* u = w */
        case 8: p[1] = p[2] = p[0]; break;                               /* u = v = w */
        default: {                                                       /* on a skewed-cell face: x' integer */
            double s = (p[0] + p[1] + p[2]) / 3;
            p[0] = floor(p[0] + s) - s;
            break;
        }
        }
        double g[3], a = np_ref_simplex3(p[0], p[1], p[2], g), b = J_noise(p[0], p[1], p[2]);
        double d = fabs(a - b);
        NP_CHECK(d <= 1e-12, "(%.17g, %.17g, %.17g): ref %.17g appendix B %.17g", p[0], p[1], p[2], a, b);
        maxd = fmax(maxd, d);
        same += a == b;
        n++;
        deriv_cmp(g, &maxdd, &dsame);
    }
    /* The 8.8 domain of the unit, with the q88 entry point. */
    for (unsigned it = 0; it < 500000; it++) {
        uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
        if (it < 65536u)
            x = y = z = (uint16_t)it; /* the whole diagonal */
        double g[3], a = np_ref_simplex3_q88(x, y, z, g), b = J_noise(x / 256.0, y / 256.0, z / 256.0);
        NP_CHECK(fabs(a - b) <= 1e-12, "(%04x,%04x,%04x)", x, y, z);
        maxd = fmax(maxd, fabs(a - b));
        same += a == b;
        n++;
        deriv_cmp(g, &maxdd88, &dsame88);
    }
    printf("reference vs Appendix B transcription: %llu inputs (scales 1..1e6, both signs, 8.8 grid, "
           "integers, faces), f: max |difference| %.3g, %llu bit-identical\n",
           (unsigned long long)n, maxd, (unsigned long long)same);
    printf("derivative (not in Appendix B) vs the transcription's own 8t^4 G - 64t^3 g d: max |difference| %.3g "
           "over all, %.3g on the 8.8 inputs; %llu of %llu components bit-identical\n",
           maxdd, maxdd88, (unsigned long long)(dsame + dsame88), (unsigned long long)(3 * n));
    NP_CHECK(same == n, "f is not bit-identical to the transcription at %llu inputs", (unsigned long long)(n - same));
    return 0;
}


/* Smallest |t| over the four corners (Appendix B's K()). */
static double min_abs_t(double x, double y, double z)
{
    double s = (x + y + z) / 3;
    double i = floor(x + s), j = floor(y + s), k = floor(z + s);
    s = (i + j + k) / 6.;
    double u = x - i + s, v = y - j + s, w = z - k + s;
    int hi = u >= w ? u >= v ? 0 : 1 : v >= w ? 1 : 2;
    int lo = u < w ? u < v ? 0 : 1 : v < w ? 1 : 2;
    int st[4] = { hi, 3 - hi - lo, lo, 0 }, A[3] = { 0, 0, 0 };
    double m = 1.0;
    for (unsigned c = 0; c < 4; c++) {
        double sa = (A[0] + A[1] + A[2]) / 6., d0 = u - A[0] + sa, d1 = v - A[1] + sa, d2 = w - A[2] + sa;
        m = fmin(m, fabs(.6 - d0 * d0 - d1 * d1 - d2 * d2));
        A[st[c]]++;
    }
    return m;
}

int simplex_deriv_vs_central_diff(void)
{
    /*
     * Analytic derivative against (f(p + h e_a) - f(p - h e_a)) / 2h with
     * h = 1e-5, at points at least 1e-3 (skewed) from every simplex and cell
     * face and with |t| >= 1e-3 at every corner: the truncation error is
     * h^2 |f'''| / 6 < 1e-8 there and the rounding error ~1e-16 / h = 1e-11.
     */
    np_rng r;
    np_rng_seed(&r, 42);
    const double h = 1e-5, margin = 1e-3;
    double maxd = 0.0, maxg = 0.0;
    unsigned n = 0, skipped = 0;
    while (n < 300000) {
        double sc = (n % 3u == 0) ? 256.0 : (n % 3u == 1 ? 8.0 : 2000.0);
        double x = (2.0 * rnd01(&r) - 1.0) * sc, y = (2.0 * rnd01(&r) - 1.0) * sc, z = (2.0 * rnd01(&r) - 1.0) * sc;
        if (n % 5u == 0) { /* the unit's own 8.8 grid */
            x = rnd16(&r) / 256.0;
            y = rnd16(&r) / 256.0;
            z = rnd16(&r) / 256.0;
        }
        if (face_distance(x, y, z) < margin || min_abs_t(x, y, z) < margin) {
            skipped++;
            continue;
        }
        double g[3];
        np_ref_simplex3(x, y, z, g);
        const double p[3] = { x, y, z };
        for (unsigned a = 0; a < 3; a++) {
            double pp[3] = { p[0], p[1], p[2] }, pm[3] = { p[0], p[1], p[2] };
            pp[a] += h;
            pm[a] -= h;
            double cd = (np_ref_simplex3(pp[0], pp[1], pp[2], NULL) - np_ref_simplex3(pm[0], pm[1], pm[2], NULL)) / (2 * h);
            double d = fabs(cd - g[a]);
            NP_CHECK(d <= 1e-7, "(%.17g,%.17g,%.17g) d/d%c analytic %.12g central %.12g", x, y, z, "xyz"[a], g[a], cd);
            maxd = fmax(maxd, d);
            maxg = fmax(maxg, fabs(g[a]));
        }
        n++;
    }
    printf("analytic derivative vs central differences (h = 1e-5): %u points (%u skipped near faces or t = 0), "
           "max |difference| %.3g (max |df| %.4f)\n",
           n, skipped, maxd, maxg);
    return 0;
}


/* ------------------------------------------------------------------------ */

int simplex_reference_face_jump(void)
{
    /*
     * The reference's own discontinuity: points exactly on a simplex face
     * u' = v' (etc.) or on a skewed-cell face (x' integer), in random cells,
     * crossed with +-1e-9 along one axis. Two simplices meet there and differ
     * in one corner; the kernel radius^2 0.6 exceeds that corner's distance,
     * so its term does not vanish and f jumps.
     */
    np_rng r;
    np_rng_seed(&r, 99);
    static const char *const what[5] = { "u'=v' face", "v'=w' face", "u'=w' face", "u'=v'=w' line", "cell face x'" };
    double scale_f = p2(16), scale_d = p2(14);
    for (unsigned kind = 0; kind < 5; kind++) {
        double mj = 0.0, mjd = 0.0, sum = 0.0;
        unsigned n = 300000, over = 0;
        for (unsigned it = 0; it < n; it++) {
            double sk[3], ci[3]; /* skewed offsets in the cell, and the cell */
            for (unsigned a = 0; a < 3; a++)
                sk[a] = rnd01(&r);
            unsigned ax = 0;
            switch (kind) {
            case 0: sk[1] = sk[0]; ax = 0; break;
            case 1: sk[2] = sk[1]; ax = 1; break;
            case 2: sk[2] = sk[0]; ax = 2; break;
            case 3: sk[1] = sk[2] = sk[0]; ax = (unsigned)(it % 3u); break;
            default: sk[0] = 0.0; ax = 0; break;
            }
            for (unsigned a = 0; a < 3; a++)
                ci[a] = (double)(np_rng_next(&r) % 200u) + 20.0;
            double sum3 = 0.0, p[3];
            for (unsigned a = 0; a < 3; a++)
                sum3 += ci[a] + sk[a];
            for (unsigned a = 0; a < 3; a++)
                p[a] = ci[a] + sk[a] - sum3 / 6.0; /* unskew */
            double pp[3] = { p[0], p[1], p[2] }, pm[3] = { p[0], p[1], p[2] }, gp[3], gm[3];
            pp[ax] += 1e-9;
            pm[ax] -= 1e-9;
            double j = fabs(np_ref_simplex3(pp[0], pp[1], pp[2], gp) - np_ref_simplex3(pm[0], pm[1], pm[2], gm));
            double jd = fmax(fabs(gp[0] - gm[0]), fmax(fabs(gp[1] - gm[1]), fabs(gp[2] - gm[2])));
            mj = fmax(mj, j);
            mjd = fmax(mjd, jd);
            sum += j;
            over += j * scale_f > 1.0;
        }
        printf("reference jump across the %-14s: max jump of f %.3e = %.1f LSB (s16 Q-1.16), mean %.2e; "
               "> 1 LSB at %.1f%% of points; derivative jump up to %.3e = %.1f LSB (s16 Q1.14)\n",
               what[kind], mj, mj * scale_f, sum / n, 100.0 * over / n, mjd, mjd * scale_d);
        if (kind == 3) /* the diagonal: no jump (faces_uvw says why); what remains is 2e-9 of travel */
            NP_CHECK(mj < 1e-7 && mjd < 1e-6, "jump on the diagonal");
        else
            NP_CHECK(mj > 1e-4 && mj < 0.01, "jump %.3g outside (1e-4, 1e-2)", mj);
    }
    /*
     * The unit on the 8.8 grid across u = v: adjacent inputs (X = Y + 1 and
     * X = Y - 1, i.e. either side of the tie X = Y); the unit's step between
     * them follows the reference's step to within 2 LSB (each side within 1).
     */
    np_simplex_cfg cfg = default_cfg();
    double maxstep_ref = 0.0, maxdev = 0.0;
    for (unsigned it = 0; it < 200000; it++) {
        uint16_t y = rnd16(&r), z = rnd16(&r);
        if (y == 0 || y == 0xffff)
            continue;
        np_simplex_out a, b;
        np_simplex_eval(&cfg, (uint16_t)(y + 1u), y, z, &a);
        np_simplex_eval(&cfg, (uint16_t)(y - 1u), y, z, &b);
        double ra = np_ref_simplex3_q88((uint16_t)(y + 1u), y, z, NULL) * scale_f;
        double rb = np_ref_simplex3_q88((uint16_t)(y - 1u), y, z, NULL) * scale_f;
        maxstep_ref = fmax(maxstep_ref, fabs(ra - rb));
        double dev = fabs((double)(a.f - b.f) - (ra - rb));
        maxdev = fmax(maxdev, dev);
        NP_CHECK(dev <= 2.0, "unit step %d vs reference step %.2f", a.f - b.f, ra - rb);
    }
    printf("the unit across u = v on the 8.8 grid (X = Y -+ 1, 2e5 points): reference step up to %.1f LSB, "
           "the unit's step differs from it by at most %.3f LSB\n",
           maxstep_ref, maxdev);
    return 0;
}

