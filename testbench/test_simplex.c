/* SPDX-License-Identifier: MIT */
/*
 * The simplex noise unit: float reference against Appendix B, analytic
 * derivative against central differences, bit-exact model (pinned outputs,
 * accuracy, stability cases), cycle-accurate model.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "np_ref.h"
#include "np_report.h"
#include "np_rng.h"
#include "np_simplex.h"
#include "np_test.h"
#include "np_unit.h"

extern const np_unit np_unit_simplex3;

/* ------------------------------------------------------------------------ */
/*
 * Appendix B of the seed, transcribed line by line from the Java class
 * Noise3 and kept verbatim as far as C allows, independent of everything
 * under test (its own bit table, its own gradient, its own hash). Two
 * changes, both forced by C: (1) Java evaluates the operands of
 * K(hi) + K(3-hi-lo) + K(lo) + K(0) left to right and K() has side effects
 * on A[], C leaves the order unspecified, so the four calls are sequenced
 * explicitly; (2) Java's N>>B & 1 on a negative int is an arithmetic shift,
 * C's is implementation-defined, so b(N,B) shifts the unsigned bit pattern
 * (the same bits 0..7: two's complement).
 */
static int J_i, J_j, J_k, J_A[] = { 0, 0, 0 };
static double J_u, J_v, J_w;
static const int J_T[] = { 0x15, 0x38, 0x32, 0x2c, 0x0d, 0x13, 0x07, 0x2a };

static int J_b1(int N, int B) { return (int)((unsigned)N >> B & 1u); }
static int J_b(int i, int j, int k, int B) { return J_T[J_b1(i, B) << 2 | J_b1(j, B) << 1 | J_b1(k, B)]; }
static int J_shuffle(int i, int j, int k)
{
    return J_b(i, j, k, 0) + J_b(j, k, i, 1) + J_b(k, i, j, 2) + J_b(i, j, k, 3) + J_b(j, k, i, 4) +
           J_b(k, i, j, 5) + J_b(i, j, k, 6) + J_b(j, k, i, 7);
}

/* Appendix B's gradient term of K(): p + q + r or p + q or p + r, by the bits of h. */
static double J_grad(int h, double x, double y, double z)
{
    int b5 = h >> 5 & 1, b4 = h >> 4 & 1, b3 = h >> 3 & 1, b2 = h >> 2 & 1, b = h & 3;
    double p = b == 1 ? x : b == 2 ? y : z, q = b == 1 ? y : b == 2 ? z : x, r = b == 1 ? z : b == 2 ? x : y;
    p = (b5 == b3 ? -p : p);
    q = (b5 == b4 ? -q : q);
    r = (b5 != (b4 ^ b3) ? -r : r);
    return p + (b == 0 ? q + r : b2 == 0 ? q : r);
}

/*
 * Not in Appendix B (which returns the value only): the analytic derivative
 * of K(), d/dp 8 t^4 g = 8 t^4 G - 64 t^3 g d, from the transcription's own
 * terms (G_a = J_grad at the unit vector a), written left to right as a
 * reader of Appendix B would; summed over the four K() calls in their order.
 */
static double J_dK[3];

static double J_K(int a)
{
    double s = (J_A[0] + J_A[1] + J_A[2]) / 6.;
    double x = J_u - J_A[0] + s, y = J_v - J_A[1] + s, z = J_w - J_A[2] + s, t = .6 - x * x - y * y - z * z;
    int h = J_shuffle(J_i + J_A[0], J_j + J_A[1], J_k + J_A[2]);
    J_A[a]++;
    if (t < 0)
        return 0;
    double g = J_grad(h, x, y, z), d[3] = { x, y, z };
    for (int e = 0; e < 3; e++)
        J_dK[e] += 8 * t * t * t * t * J_grad(h, e == 0, e == 1, e == 2) - 64 * t * t * t * g * d[e];
    t *= t;
    return 8 * t * t * g;
}

static double J_noise(double x, double y, double z)
{
    double s = (x + y + z) / 3;
    J_i = (int)floor(x + s);
    J_j = (int)floor(y + s);
    J_k = (int)floor(z + s);
    s = (J_i + J_j + J_k) / 6.;
    J_u = x - J_i + s;
    J_v = y - J_j + s;
    J_w = z - J_k + s;
    J_A[0] = J_A[1] = J_A[2] = 0;
    J_dK[0] = J_dK[1] = J_dK[2] = 0;
    int hi = J_u >= J_w ? J_u >= J_v ? 0 : 1 : J_v >= J_w ? 1 : 2;
    int lo = J_u < J_w ? J_u < J_v ? 0 : 1 : J_v < J_w ? 1 : 2;
    double k0 = J_K(hi);
    double k1 = J_K(3 - hi - lo);
    double k2 = J_K(lo);
    double k3 = J_K(0);
    return k0 + k1 + k2 + k3;
}

/* ------------------------------------------------------------------------ */

static uint16_t rnd16(np_rng *r) { return (uint16_t)(np_rng_next(r) >> 48); }
static double rnd01(np_rng *r) { return (double)(np_rng_next(r) >> 11) * 0x1p-53; }
/* Three words in a fixed order (an initializer list's order of evaluation is unspecified). */
static void rnd3(np_rng *r, uint16_t in[3])
{
    for (unsigned a = 0; a < 3; a++)
        in[a] = rnd16(r);
}

static np_simplex_cfg default_cfg(void) { return np_simplex_cfg_default(16, 16, 1); }

/* 2^n as a double, exact. */
static double p2(unsigned n) { return ldexp(1.0, (int)n); }

/* Model and reference at one input, errors in output LSB (f, dfdx, dfdy, dfdz). */
typedef struct errs {
    double e[4];      /* |model - 2^F ref| */
    int cr[4];        /* model == floor(2^F ref + 1/2) */
    np_simplex_out o; /* the model's outputs */
    double ref[4];    /* the reference's values */
} errs;

static void measure(const np_simplex_cfg *cfg, uint16_t x, uint16_t y, uint16_t z, errs *r)
{
    double g[3];
    np_simplex_eval(cfg, x, y, z, &r->o);
    r->ref[0] = np_ref_simplex3_q88(x, y, z, g);
    for (unsigned a = 0; a < 3; a++)
        r->ref[1 + a] = g[a];
    unsigned nf = cfg->deriv ? 4u : 1u;
    for (unsigned k = 0; k < 4; k++) {
        r->e[k] = 0.0;
        r->cr[k] = 1;
    }
    for (unsigned k = 0; k < nf; k++) {
        double scale = p2(k == 0 ? np_simplex_f_frac(cfg) : np_simplex_d_frac(cfg));
        double want = r->ref[k] * scale;
        int32_t got = k == 0 ? r->o.f : r->o.df[k - 1];
        r->e[k] = fabs((double)got - want);
        r->cr[k] = (double)got == floor(want + 0.5);
    }
}

/* Running maximum of errors over a set of inputs. */
typedef struct emax {
    double e[4];
    uint64_t n, cr[4];
    uint16_t at[4][3];
} emax;

static void emax_add(emax *m, const errs *r, uint16_t x, uint16_t y, uint16_t z)
{
    for (unsigned k = 0; k < 4; k++) {
        if (r->e[k] > m->e[k] || m->n == 0) {
            m->e[k] = r->e[k];
            m->at[k][0] = x;
            m->at[k][1] = y;
            m->at[k][2] = z;
        }
        m->cr[k] += (uint64_t)r->cr[k];
    }
    m->n++;
}

static const char *const FIELD[4] = { "f", "dfdx", "dfdy", "dfdz" };

static void emax_print(const char *what, const emax *m, int deriv)
{
    printf("%s: %llu inputs, max error f %.4f", what, (unsigned long long)m->n, m->e[0]);
    if (deriv)
        printf(", dfdx %.4f, dfdy %.4f, dfdz %.4f", m->e[1], m->e[2], m->e[3]);
    printf(" LSB\n");
}

/* Every field within 1 LSB (and within the argument's bound). */
static void emax_check(const char *what, const emax *m, const np_simplex_cfg *cfg)
{
    double bf = np_simplex_error_bound_lsb(cfg, 0), bd = np_simplex_error_bound_lsb(cfg, 1);
    unsigned nf = cfg->deriv ? 4u : 1u;
    for (unsigned k = 0; k < nf; k++) {
        double b = k == 0 ? bf : bd;
        NP_CHECK(m->e[k] <= b && m->e[k] <= 1.0, "%s: %s error %.4f LSB at (%04x,%04x,%04x), bound %.4f", what,
                 FIELD[k], m->e[k], m->at[k][0], m->at[k][1], m->at[k][2], b);
    }
}

/* ------------------------------------------------------------------------ */
/*
 * Local configurations. Every input is, relative to its skewed cell,
 * one of 25,165,824 configurations (U, V, W) (offsets from corner 0 in units
 * of 1/1536): U = V = W = 4n (mod 6) with n = i + j + k, and the skewed
 * offsets U + (U+V+W)/3 etc. in [0, 1536). The enumeration below visits all
 * of them; input_of() maps one back to an 8.8 input in cell (i0, i0, i0+dn).
 */
typedef void (*config_fn)(void *ctx, int32_t u, int32_t v, int32_t w);

static uint64_t for_each_config(config_fn fn, void *ctx)
{
    uint64_t n = 0;
    for (int32_t res = 0; res < 6; res += 2)
        for (int32_t u = -516 + res; u <= 1536; u += 6)
            for (int32_t v = -516 + res; v <= 1536; v += 6) {
                /*
                 * W range from the skewed-offset constraints 0 <= 3u + (u+v+w) < 4608
                 * (and alike for v and w), then every w = res (mod 6) in it.
                 */
                int32_t lo = -4 * u - v, hi = 4608 - 4 * u - v;
                if (-u - 4 * v > lo)
                    lo = -u - 4 * v;
                if (4608 - u - 4 * v < hi)
                    hi = 4608 - u - 4 * v;
                if (-(u + v) / 4 - 1 > lo)
                    lo = -(u + v) / 4 - 1;
                if ((4608 - u - v) / 4 + 1 < hi)
                    hi = (4608 - u - v) / 4 + 1;
                int32_t w0 = lo - ((lo - res) % 6 + 6) % 6;
                for (int32_t w = w0; w <= hi; w += 6) {
                    int32_t s3 = (u + v + w) / 3; /* exact: u + v + w = 0 mod 6 */
                    int32_t su = u + s3, sv = v + s3, sw = w + s3;
                    if (su < 0 || su >= 1536 || sv < 0 || sv >= 1536 || sw < 0 || sw >= 1536)
                        continue;
                    fn(ctx, u, v, w);
                    n++;
                }
            }
    return n;
}

/*
 * An 8.8 input whose local configuration is (U, V, W): X = (U + 1536 i - 256 n) / 6
 * with the cell (i0, i0, i0 + dn) chosen so that the division is exact.
 * Returns 0 when no input in range has it (not the case for i0 in 30..200).
 */
static int input_of(int32_t u, int32_t v, int32_t w, int32_t i0, uint16_t in[3])
{
    for (int32_t dn = 0; dn < 6; dn++) {
        int32_t cell[3] = { i0, i0, i0 + dn }, n = 3 * i0 + dn, off[3] = { u, v, w };
        int ok = 1;
        for (unsigned a = 0; a < 3 && ok; a++) {
            int32_t num = off[a] + 1536 * cell[a] - 256 * n;
            if (num % 6 != 0 || num < 0 || num / 6 > 0xffff)
                ok = 0;
            else
                in[a] = (uint16_t)(num / 6);
        }
        if (ok)
            return 1;
    }
    return 0;
}

/* The front end of the model (primitives of stages SK and RK) on one input. */
static void front_end(uint16_t x, uint16_t y, uint16_t z, uint32_t cell[3], int32_t off[3])
{
    const uint16_t in[3] = { x, y, z };
    for (unsigned a = 0; a < 3; a++)
        cell[a] = np_simplex_cell(np_simplex_skew(in[a], in[(a + 1u) % 3u], in[(a + 2u) % 3u]));
    uint32_t n = cell[0] + cell[1] + cell[2];
    for (unsigned a = 0; a < 3; a++)
        off[a] = np_simplex_offset(in[a], cell[a], n);
}

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

static int ref_vs_appendix_b(void)
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

/* Skewed fractional offsets and the smallest distance to a simplex or cell face, in skewed units. */
static double face_distance(double x, double y, double z)
{
    double s = (x + y + z) / 3, f[3] = { x + s, y + s, z + s };
    double m = 1.0;
    for (unsigned a = 0; a < 3; a++) {
        f[a] -= floor(f[a]);
        m = fmin(m, fmin(f[a], 1.0 - f[a]));
    }
    m = fmin(m, fmin(fabs(f[0] - f[1]), fmin(fabs(f[1] - f[2]), fabs(f[0] - f[2]))));
    return m;
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

static int deriv_vs_central_diff(void)
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

typedef struct kat_row {
    uint16_t x, y, z;
    int32_t f, dfdx, dfdy, dfdz; /* default unit: f s16, df s16 Q1.14 */
    int32_t f8;                  /* out_bits=8 deriv=0: f s8 */
} kat_row;

static const kat_row KAT[] = {
#include "simplex3_kat.inc"
};

/* The KAT inputs: the unit's boundary table, then seeded random ones. */
static unsigned kat_inputs(uint16_t (*in)[3], unsigned max)
{
    uint64_t b[64][NP_UNIT_MAX_FIELDS];
    np_unit_cfg ucfg;
    np_unit_cfg_default(&np_unit_simplex3, &ucfg);
    size_t nb = np_unit_simplex3.boundary(&ucfg, b, 64);
    unsigned n = 0;
    for (size_t i = 0; i < nb && i < 64 && n < max; i++, n++)
        for (unsigned a = 0; a < 3; a++)
            in[n][a] = (uint16_t)b[i][a];
    np_rng r;
    np_rng_seed(&r, 2024);
    while (n < max) {
        for (unsigned a = 0; a < 3; a++)
            in[n][a] = rnd16(&r);
        n++;
    }
    return n;
}

static int print_kat(void)
{
    /* Regenerates simplex3_kat.inc (not a test): test_simplex print_kat > simplex3_kat.inc */
    uint16_t in[96][3];
    unsigned n = kat_inputs(in, 96);
    np_simplex_cfg c = default_cfg(), c8 = np_simplex_cfg_default(8, 8, 0);
    printf("/* Generated by `test_simplex print_kat`: the boundary table of unit simplex3, then seeded\n"
           " * random inputs. x, y, z, then f dfdx dfdy dfdz of the default unit (s16 Q-1.16, s16 Q1.14)\n"
           " * and f of out_bits=8 deriv=0 (s8 Q-1.8). Reference values in the comments. */\n");
    for (unsigned i = 0; i < n; i++) {
        np_simplex_out o, o8;
        double g[3];
        np_simplex_eval(&c, in[i][0], in[i][1], in[i][2], &o);
        np_simplex_eval(&c8, in[i][0], in[i][1], in[i][2], &o8);
        double f = np_ref_simplex3_q88(in[i][0], in[i][1], in[i][2], g);
        printf("{ 0x%04x, 0x%04x, 0x%04x, %6d, %6d, %6d, %6d, %4d }, /* %+.6f %+.6f %+.6f %+.6f */\n",
               in[i][0], in[i][1], in[i][2], o.f, o.df[0], o.df[1], o.df[2], o8.f, f, g[0], g[1], g[2]);
    }
    return 0;
}

static int kat(void)
{
    uint16_t in[96][3];
    unsigned n = kat_inputs(in, 96);
    unsigned nk = sizeof KAT / sizeof KAT[0];
    NP_CHECK(nk == n, "KAT has %u rows, expected %u (regenerate with print_kat)", nk, n);
    np_simplex_cfg c = default_cfg(), c8 = np_simplex_cfg_default(8, 8, 0);
    for (unsigned i = 0; i < nk && i < n; i++) {
        const kat_row *k = &KAT[i];
        NP_CHECK(k->x == in[i][0] && k->y == in[i][1] && k->z == in[i][2], "row %u inputs", i);
        np_simplex_out o, o8;
        np_simplex_eval(&c, k->x, k->y, k->z, &o);
        np_simplex_eval(&c8, k->x, k->y, k->z, &o8);
        NP_CHECK(o.f == k->f && o.df[0] == k->dfdx && o.df[1] == k->dfdy && o.df[2] == k->dfdz,
                 "(%04x,%04x,%04x) = %d %d %d %d, pinned %d %d %d %d", k->x, k->y, k->z, o.f, o.df[0], o.df[1],
                 o.df[2], k->f, k->dfdx, k->dfdy, k->dfdz);
        NP_CHECK(o8.f == k->f8, "(%04x,%04x,%04x) 8-bit f = %d, pinned %d", k->x, k->y, k->z, o8.f, k->f8);
        errs e;
        measure(&c, k->x, k->y, k->z, &e);
        for (unsigned f = 0; f < 4; f++)
            NP_CHECK(e.e[f] <= 1.0, "(%04x,%04x,%04x) %s %.3f LSB from the reference", k->x, k->y, k->z, FIELD[f], e.e[f]);
    }
    printf("%u pinned outputs (4 fields of the default unit + 8-bit f) match\n", nk);
    return 0;
}

static int random_1e7(void)
{
    np_simplex_cfg cfg = default_cfg();
    np_rng r;
    np_rng_seed(&r, 10000000);
    emax m;
    memset(&m, 0, sizeof m);
    const uint64_t n = 10000000;
    for (uint64_t i = 0; i < n; i++) {
        uint64_t v = np_rng_next(&r);
        uint16_t x = (uint16_t)v, y = (uint16_t)(v >> 16), z = (uint16_t)(v >> 32);
        errs e;
        measure(&cfg, x, y, z, &e);
        emax_add(&m, &e, x, y, z);
    }
    printf("default unit (out_bits=16 dout_bits=16 t_frac=%u p_frac=%u k_frac=%u), %llu random inputs:\n",
           cfg.t_frac, cfg.p_frac, cfg.k_frac, (unsigned long long)n);
    for (unsigned k = 0; k < 4; k++)
        printf("  %-4s max error %.4f LSB (bound %.4f) at (%04x,%04x,%04x), correctly rounded %.4f%%\n", FIELD[k],
               m.e[k], np_simplex_error_bound_lsb(&cfg, k > 0), m.at[k][0], m.at[k][1], m.at[k][2],
               100.0 * (double)m.cr[k] / (double)n);
    emax_check("random", &m, &cfg);
    return 0;
}

/* ------------------------------------------------------------------------ */

/*
 * Drive the pipe with n inputs, an input bubble with probability pb/16 and
 * an output stall with probability ps/16 each cycle; check every output
 * against the bit-exact model, in order, and that an output whose path never
 * stalled appears exactly `latency` cycles after its input was accepted.
 */
static void drive_pipe(const np_simplex_cfg *cfg, uint64_t n, unsigned pb, unsigned ps, uint64_t seed)
{
    enum { QN = 64 };
    np_pipe p;
    NP_CHECK(np_simplex_pipe_init(&p, cfg) == 0, "pipe init");
    np_rng r;
    np_rng_seed(&r, seed);
    static struct { np_simplex_sig in; uint64_t cycle, stalls; } q[QN];
    uint64_t sent = 0, got = 0, cycle = 0, stalls = 0, exact = 0, bad = 0;
    np_simplex_sig in;
    memset(&in, 0, sizeof in);
    np_pipe_port port;
    memset(&port, 0, sizeof port);
    int have = 0;
    unsigned lat = np_pipe_latency(&p);
    NP_CHECK(lat == np_simplex_stage_count(cfg), "latency %u", lat);
    while (got < n) {
        if (!have && sent < n) {
            memset(&in, 0, sizeof in);
            in.x = rnd16(&r);
            in.y = rnd16(&r);
            in.z = rnd16(&r);
            have = 1;
        }
        uint64_t coin = np_rng_next(&r);
        port.in_valid = have && (coin & 15u) >= pb;
        port.in_sig = &in;
        port.out_ready = ((coin >> 4) & 15u) >= ps;
        np_pipe_eval(&p, &port);
        if (port.out_valid && !port.out_ready)
            stalls++;
        if (port.out_valid && port.out_ready) {
            const np_simplex_sig *o = port.out_sig;
            unsigned slot = (unsigned)(got % QN);
            np_simplex_out want;
            np_simplex_eval(cfg, q[slot].in.x, q[slot].in.y, q[slot].in.z, &want);
            if (o->f != want.f || o->df[0] != want.df[0] || o->df[1] != want.df[1] || o->df[2] != want.df[2] ||
                o->x != q[slot].in.x || o->y != q[slot].in.y || o->z != q[slot].in.z) {
                bad++;
                NP_CHECK(0, "transaction %llu: got %d %d %d %d want %d %d %d %d", (unsigned long long)got, o->f,
                         o->df[0], o->df[1], o->df[2], want.f, want.df[0], want.df[1], want.df[2]);
            }
            if (q[slot].stalls == stalls) {
                NP_CHECK(cycle - q[slot].cycle == lat, "transaction %llu latency %llu, want %u",
                         (unsigned long long)got, (unsigned long long)(cycle - q[slot].cycle), lat);
                exact++;
            } else {
                NP_CHECK(cycle - q[slot].cycle >= lat, "transaction faster than the latency");
            }
            got++;
        }
        if (port.in_valid && port.in_ready) {
            unsigned slot = (unsigned)(sent % QN);
            NP_CHECK(sent - got < QN, "more than %d in flight", QN);
            q[slot].in = in;
            q[slot].cycle = cycle;
            q[slot].stalls = stalls;
            sent++;
            have = 0;
        }
        np_pipe_clock(&p, &port);
        cycle++;
        NP_CHECK(np_pipe_occupancy(&p) <= lat, "occupancy");
    }
    printf("deriv=%u: %llu transactions in %llu cycles (bubbles %u/16, stalls %u/16): %llu mismatches, "
           "%llu unstalled ones all at latency %u\n",
           cfg->deriv, (unsigned long long)got, (unsigned long long)cycle, pb, ps, (unsigned long long)bad,
           (unsigned long long)exact, lat);
    NP_CHECK(p.stats.accepted == n && p.stats.delivered == n, "stats count");
    np_pipe_free(&p);
}

static int cycle_vs_model_1e6(void)
{
    np_simplex_cfg cfg = default_cfg();
    drive_pipe(&cfg, 1000000, 4, 4, 1);  /* bubbles and stalls, 1/4 each */
    drive_pipe(&cfg, 100000, 12, 1, 2);  /* mostly bubbles */
    drive_pipe(&cfg, 100000, 1, 12, 3);  /* mostly stalls */
    drive_pipe(&cfg, 100000, 0, 0, 4);   /* full throughput */
    np_simplex_cfg f8 = np_simplex_cfg_default(8, 8, 0);
    drive_pipe(&f8, 200000, 3, 3, 5);    /* f only: 9 stages */
    NP_CHECK(NP_SIMPLEX_STAGES_D == 10 && NP_SIMPLEX_STAGES_F == 9, "latency changed: update docs/simplex3.md");
    return 0;
}

/* ------------------------------------------------------------------------ */
/*
 * Simplex faces on the 8.8 grid: u = v exactly when X = Y (then i = j), and
 * so on. Each face case measures the error at the tie itself and one input
 * step either side, and counts the ties where the two simplices meeting
 * there differ by more than 2 LSB in the reference (so that choosing the
 * other simplex than Appendix B's rule would show as an error).
 */
typedef enum { FACE_UV, FACE_VW, FACE_UW, FACE_UVW } face_kind;

static void face_point(face_kind k, np_rng *r, uint16_t in[3], unsigned *step_axis)
{
    uint16_t a = rnd16(r), b = rnd16(r);
    switch (k) {
    case FACE_UV: in[0] = in[1] = a; in[2] = b; *step_axis = 0; break;
    case FACE_VW: in[1] = in[2] = a; in[0] = b; *step_axis = 1; break;
    case FACE_UW: in[0] = in[2] = a; in[1] = b; *step_axis = 2; break;
    default: in[0] = in[1] = in[2] = a; *step_axis = (unsigned)(np_rng_next(r) % 3u); break;
    }
}

static int face_case(face_kind k, const char *name)
{
    np_simplex_cfg cfg = default_cfg();
    np_rng r;
    np_rng_seed(&r, 77 + (uint64_t)k);
    emax on, side;
    memset(&on, 0, sizeof on);
    memset(&side, 0, sizeof side);
    unsigned n = k == FACE_UVW ? 65536u : 200000u, decisive = 0, ties_same = 0;
    double maxjump = 0.0;
    uint16_t jat[3] = { 0, 0, 0 };
    for (unsigned it = 0; it < n; it++) {
        uint16_t in[3];
        unsigned ax;
        face_point(k, &r, in, &ax);
        if (k == FACE_UVW)
            in[0] = in[1] = in[2] = (uint16_t)it; /* the whole diagonal */
        uint32_t cell[3];
        int32_t off[3];
        front_end(in[0], in[1], in[2], cell, off);
        NP_CHECK((k == FACE_UV && off[0] == off[1]) || (k == FACE_VW && off[1] == off[2]) ||
                     (k == FACE_UW && off[0] == off[2]) || (k == FACE_UVW && off[0] == off[1] && off[1] == off[2]),
                 "not on the face");
        /* Appendix B's ranking in double at the same point gives the same simplex as the exact one. */
        {
            double px = in[0] / 256.0, py = in[1] / 256.0, pz = in[2] / 256.0, s3 = (px + py + pz) / 3;
            double fi = floor(px + s3), fj = floor(py + s3), fk = floor(pz + s3), s6 = (fi + fj + fk) / 6.;
            double u = px - fi + s6, v = py - fj + s6, w = pz - fk + s6;
            int jhi = u >= w ? u >= v ? 0 : 1 : v >= w ? 1 : 2;
            int jlo = u < w ? u < v ? 0 : 1 : v < w ? 1 : 2;
            uint8_t hi, lo;
            np_simplex_rank(off[0], off[1], off[2], &hi, &lo);
            NP_CHECK(hi == jhi && lo == jlo, "(%04x,%04x,%04x): rank %u,%u, Appendix B %d,%d", in[0], in[1], in[2], hi,
                     lo, jhi, jlo);
            ties_same += hi == jhi && lo == jlo;
        }
        if (k == FACE_UVW) {
            /* The six simplices around the diagonal differ only in corners e_a and e_a + e_b: all out of reach. */
            static const unsigned masks[6] = { 1, 2, 4, 3, 5, 6 };
            for (unsigned m = 0; m < 6; m++) {
                int32_t d[3];
                unsigned c = (masks[m] == 3 || masks[m] == 5 || masks[m] == 6) ? 2u : 1u;
                for (unsigned a = 0; a < 3; a++)
                    d[a] = np_simplex_corner_d(off[a], masks[m] >> a & 1u, c);
                NP_CHECK(np_simplex_kernel_t(np_simplex_r2(d)) == 0, "diagonal corner %u in reach", masks[m]);
            }
        }
        errs e;
        measure(&cfg, in[0], in[1], in[2], &e);
        emax_add(&on, &e, in[0], in[1], in[2]);
        /* The reference's two one-sided limits at the tie (1e-9 along the step axis). */
        double p[3] = { in[0] / 256.0, in[1] / 256.0, in[2] / 256.0 }, pp[3], pm[3];
        memcpy(pp, p, sizeof p);
        memcpy(pm, p, sizeof p);
        pp[ax] += 1e-9;
        pm[ax] -= 1e-9;
        double jump = fabs(np_ref_simplex3(pp[0], pp[1], pp[2], NULL) - np_ref_simplex3(pm[0], pm[1], pm[2], NULL)) *
                      p2(np_simplex_f_frac(&cfg));
        if (jump > maxjump) {
            maxjump = jump;
            memcpy(jat, in, sizeof jat);
        }
        decisive += jump > 2.0;
        for (int s = -1; s <= 1; s += 2) {
            uint16_t q[3] = { in[0], in[1], in[2] };
            q[ax] = (uint16_t)(q[ax] + s);
            measure(&cfg, q[0], q[1], q[2], &e);
            emax_add(&side, &e, q[0], q[1], q[2]);
        }
    }
    printf("%s: %u tie inputs, the exact ranking equals Appendix B's at %u; the reference's one-sided limits "
           "(+-1e-9 across the face) differ by up to %.3g LSB of f (at (%04x,%04x,%04x)), by more than 2 LSB at "
           "%u of them\n",
           name, n, ties_same, maxjump, jat[0], jat[1], jat[2], decisive);
    emax_print("  on the face", &on, 1);
    emax_print("  one step either side", &side, 1);
    emax_check(name, &on, &cfg);
    emax_check(name, &side, &cfg);
    if (k == FACE_UVW) {
        /* On the diagonal the corners in which the six simplices differ are at |d|^2 >= 2/3 > 0.6. */
        NP_CHECK(maxjump < 1e-3, "jump %.3g LSB on the diagonal", maxjump);
        printf("  on u = v = w the choice of simplex does not matter: every corner in which the six simplices "
               "differ has t < 0 (|d|^2 >= 2/3), so f and df are continuous there\n");
    } else {
        NP_CHECK(decisive > 0, "no decisive tie: the case cannot tell the simplex choice");
    }
    return 0;
}

static int faces_uv(void) { return face_case(FACE_UV, "faces_uv (X = Y)"); }
static int faces_vw(void) { return face_case(FACE_VW, "faces_vw (Y = Z)"); }
static int faces_uw(void) { return face_case(FACE_UW, "faces_uw (X = Z)"); }
static int faces_uvw(void) { return face_case(FACE_UVW, "faces_uvw (X = Y = Z)"); }

/* ------------------------------------------------------------------------ */

typedef struct tz_ctx {
    int32_t tmin_pos, tmax_neg;   /* smallest T > 0 and largest T <= 0 (T before the clamp) */
    int32_t at_pos[4], at_neg[4]; /* U, V, W, corner */
    uint64_t hist_zero;           /* configurations with some corner at T == 0 (none expected) */
} tz_ctx;

static void tz_visit(void *ctxv, int32_t u, int32_t v, int32_t w)
{
    tz_ctx *c = ctxv;
    uint8_t hi, lo;
    np_simplex_rank(u, v, w, &hi, &lo);
    const int32_t off[3] = { u, v, w };
    for (unsigned k = 0; k < 4; k++) {
        unsigned mask = np_simplex_corner_mask(hi, lo, k);
        int32_t d[3];
        for (unsigned a = 0; a < 3; a++)
            d[a] = np_simplex_corner_d(off[a], mask >> a & 1u, k);
        int32_t td = NP_SIMPLEX_T_VERTEX - NP_SIMPLEX_R2_SCALE * (int32_t)np_simplex_r2(d);
        if (td == 0)
            c->hist_zero++;
        if (td > 0 && td < c->tmin_pos) {
            c->tmin_pos = td;
            c->at_pos[0] = u, c->at_pos[1] = v, c->at_pos[2] = w, c->at_pos[3] = (int32_t)k;
        }
        if (td <= 0 && td > c->tmax_neg) {
            c->tmax_neg = td;
            c->at_neg[0] = u, c->at_neg[1] = v, c->at_neg[2] = w, c->at_neg[3] = (int32_t)k;
        }
    }
}

/* The model's T of corner k at an input (stages SK..KT). */
static uint32_t corner_tau2(const np_simplex_cfg *cfg, const uint16_t in[3], unsigned k, int32_t *t_unclamped)
{
    np_simplex_sig s;
    memset(&s, 0, sizeof s);
    s.x = in[0];
    s.y = in[1];
    s.z = in[2];
    for (unsigned st = 0; st < 5; st++) /* SK RK CH KT P2 */
        np_simplex_stages_d[st].fn(cfg, &s);
    *t_unclamped = NP_SIMPLEX_T_VERTEX - NP_SIMPLEX_R2_SCALE * (int32_t)s.r2[k];
    return s.tau2[k];
}

static int kernel_t_zero(void)
{
    /*
     * Over every local configuration: the T values nearest 0. T = 0 (t
     * exactly 0) is unreachable from 8.8 inputs (np_simplex.h says why), so
     * the case takes the nearest T on either side, at a corner, maps it to an
     * input in several cells, and measures the error there and one input
     * step either side on every axis.
     */
    tz_ctx c = { INT32_MAX, INT32_MIN, { 0 }, { 0 }, 0 };
    uint64_t nconf = for_each_config(tz_visit, &c);
    NP_CHECK(nconf == 25165824u, "local configurations %llu", (unsigned long long)nconf);
    NP_CHECK(c.hist_zero == 0, "t exactly 0 reached at %llu configurations", (unsigned long long)c.hist_zero);
    printf("%llu local configurations; t = 0 reached 0 times; nearest: T = %d (t = %+.3g) at U,V,W = %d,%d,%d "
           "corner %d; T = %d (t = %+.3g) at %d,%d,%d corner %d\n",
           (unsigned long long)nconf, c.tmin_pos, c.tmin_pos / (45.0 * 262144.0), c.at_pos[0], c.at_pos[1],
           c.at_pos[2], c.at_pos[3], c.tmax_neg, c.tmax_neg / (45.0 * 262144.0), c.at_neg[0], c.at_neg[1],
           c.at_neg[2], c.at_neg[3]);
    np_simplex_cfg cfg = default_cfg();
    emax at, side;
    memset(&at, 0, sizeof at);
    memset(&side, 0, sizeof side);
    for (int which = 0; which < 2; which++) {
        const int32_t *cf = which ? c.at_neg : c.at_pos;
        int32_t want = which ? c.tmax_neg : c.tmin_pos;
        for (int32_t i0 = 30; i0 < 200; i0 += 7) {
            uint16_t in[3];
            if (!input_of(cf[0], cf[1], cf[2], i0, in)) {
                NP_CHECK(0, "no input for the configuration in cell %d", i0);
                continue;
            }
            int32_t t;
            uint32_t tau2 = corner_tau2(&cfg, in, (unsigned)cf[3], &t);
            NP_CHECK(t == want, "input (%04x,%04x,%04x) has T %d, want %d", in[0], in[1], in[2], t, want);
            NP_CHECK(tau2 == 0, "tau2 %u at T = %d", tau2, t);
            if (i0 == 30)
                printf("  T = %d at input (%04x,%04x,%04x): tau2 = %u\n", t, in[0], in[1], in[2], tau2);
            errs e;
            measure(&cfg, in[0], in[1], in[2], &e);
            emax_add(&at, &e, in[0], in[1], in[2]);
            for (unsigned a = 0; a < 3; a++)
                for (int s = -1; s <= 1; s += 2) {
                    uint16_t q[3] = { in[0], in[1], in[2] };
                    q[a] = (uint16_t)(q[a] + s);
                    measure(&cfg, q[0], q[1], q[2], &e);
                    emax_add(&side, &e, q[0], q[1], q[2]);
                }
        }
    }
    emax_print("  at the T nearest 0", &at, 1);
    emax_print("  one input step either side", &side, 1);
    emax_check("kernel_t_zero", &at, &cfg);
    emax_check("kernel_t_zero", &side, &cfg);
    /* The support test on exact T: a tiny positive T still gives a zero term, continuously. */
    NP_CHECK(np_simplex_kernel_t((uint32_t)(NP_SIMPLEX_T_VERTEX / 5)) == 3u, "T of R2 = 1415577");
    NP_CHECK(np_simplex_kernel_t((uint32_t)(NP_SIMPLEX_T_VERTEX / 5 + 1)) == 0u, "clamp");
    return 0;
}

/* ------------------------------------------------------------------------ */

static int extremes_0_and_max(void)
{
    /* Each axis at 0, 1, 0xfffe, 0xffff with the others random, and the 8 corners of the domain. */
    np_simplex_cfg cfg = default_cfg();
    np_rng r;
    np_rng_seed(&r, 5);
    static const uint16_t ext[4] = { 0x0000, 0x0001, 0xfffe, 0xffff };
    for (unsigned a = 0; a < 3; a++) {
        emax m;
        memset(&m, 0, sizeof m);
        for (unsigned it = 0; it < 100000; it++) {
            uint16_t in[3];
            rnd3(&r, in);
            in[a] = ext[it % 4u];
            errs e;
            measure(&cfg, in[0], in[1], in[2], &e);
            emax_add(&m, &e, in[0], in[1], in[2]);
        }
        char what[64];
        snprintf(what, sizeof what, "%c at 0, 1, 0xfffe, 0xffff", "xyz"[a]);
        emax_print(what, &m, 1);
        emax_check(what, &m, &cfg);
    }
    emax m;
    memset(&m, 0, sizeof m);
    for (unsigned c = 0; c < 8; c++) {
        uint16_t in[3] = { (c & 1u) ? 0xffff : 0, (c & 2u) ? 0xffff : 0, (c & 4u) ? 0xffff : 0 };
        errs e;
        measure(&cfg, in[0], in[1], in[2], &e);
        emax_add(&m, &e, in[0], in[1], in[2]);
        printf("  (%04x,%04x,%04x): f %d dfdx %d dfdy %d dfdz %d; reference %+.6f %+.6f %+.6f %+.6f\n", in[0], in[1],
               in[2], e.o.f, e.o.df[0], e.o.df[1], e.o.df[2], e.ref[0], e.ref[1], e.ref[2], e.ref[3]);
    }
    emax_print("the 8 corners of the domain", &m, 1);
    emax_check("corners", &m, &cfg);
    /* The origin: corner 0 sits on the point (G.d = 0), the others are out of reach: f = 0 exactly. */
    np_simplex_out o;
    np_simplex_eval(&cfg, 0, 0, 0, &o);
    NP_CHECK(o.f == 0 && np_ref_simplex3_q88(0, 0, 0, NULL) == 0.0, "f at the origin");
    return 0;
}

/* ------------------------------------------------------------------------ */

typedef struct mag_ctx {
    double bf, bd; /* adversarial-gradient bounds */
    int32_t at_f[3];
} mag_ctx;

static void mag_visit(void *ctxv, int32_t u, int32_t v, int32_t w)
{
    mag_ctx *c = ctxv;
    uint8_t hi, lo;
    np_simplex_rank(u, v, w, &hi, &lo);
    const int32_t off[3] = { u, v, w };
    double sf = 0.0, sd[3] = { 0.0, 0.0, 0.0 };
    for (unsigned k = 0; k < 4; k++) {
        unsigned mask = np_simplex_corner_mask(hi, lo, k);
        double d[3];
        for (unsigned a = 0; a < 3; a++)
            d[a] = np_simplex_corner_d(off[a], mask >> a & 1u, k) / 1536.0;
        double t = .6 - d[0] * d[0] - d[1] * d[1] - d[2] * d[2];
        if (t <= 0)
            continue;
        double t3 = t * t * t, t4 = t3 * t, ad[3] = { fabs(d[0]), fabs(d[1]), fabs(d[2]) };
        /* max over the 20 gradients of |G.d| is |d|_1 (all three coefficients, signs aligned) */
        sf += 8 * t4 * (ad[0] + ad[1] + ad[2]);
        /* of |8t^4 G_a - 64t^3 (G.d) d_a|: |8t^4 - 64t^3 d_a^2| + 64t^3 |d_a| (|d_b| + |d_c|) */
        for (unsigned a = 0; a < 3; a++)
            sd[a] += fabs(8 * t4 - 64 * t3 * d[a] * d[a]) + 64 * t3 * ad[a] * (ad[(a + 1) % 3] + ad[(a + 2) % 3]);
    }
    if (sf > c->bf) {
        c->bf = sf;
        c->at_f[0] = u, c->at_f[1] = v, c->at_f[2] = w;
    }
    for (unsigned a = 0; a < 3; a++)
        c->bd = fmax(c->bd, sd[a]);
}

/* Widen an observed |max| and check a signal against its width. */
#define WIDTH_S(v, bits, mx)                                                                     \
    do {                                                                                         \
        NP_CHECK(np_fits_s((int64_t)(v), (bits)), "%s = %lld does not fit s%u", #v, (long long)(v), (unsigned)(bits)); \
        if (llabs((long long)(v)) > (mx))                                                        \
            (mx) = llabs((long long)(v));                                                        \
    } while (0)
#define WIDTH_U(v, bits, mx)                                                                     \
    do {                                                                                         \
        NP_CHECK(np_fits_u((int64_t)(v), (bits)), "%s = %lld does not fit u%u", #v, (long long)(v), (unsigned)(bits)); \
        if ((long long)(v) > (mx))                                                               \
            (mx) = (long long)(v);                                                               \
    } while (0)

enum { W_SK, W_CELL, W_OFF, W_D, W_GD, W_R2, W_T, W_TAU2, W_TAU3, W_TAU4, W_FC, W_Q, W_E, W_M, W_EM, W_S, W_QS, W_F, W_DF, W_N };
static const char *const W_NAME[W_N] = { "SX u19", "cell u9", "U s12", "D s12", "gd s14", "R2 u22", "T u23",
                                         "tau2 u(WT)", "tau3 u(WT)", "tau4 u(WT)", "fc s(WP+1)", "q s(WP+1)",
                                         "e s(WP+1)", "m s(WP+1)", "e-m s(WP+1)", "S s(WP+2)", "Q s(WP+3)",
                                         "f sN", "df sND" };

/* Run every stage on one input and check every signal against its declared width. */
static void check_widths(const np_simplex_cfg *cfg, uint16_t x, uint16_t y, uint16_t z, long long mx[W_N])
{
    np_simplex_sig s;
    memset(&s, 0, sizeof s);
    s.x = x;
    s.y = y;
    s.z = z;
    for (unsigned k = 0; k < NP_SIMPLEX_STAGES_D; k++)
        np_simplex_stages_d[k].fn(cfg, &s);
    unsigned wt = cfg->t_frac, wp = cfg->p_frac;
    for (unsigned a = 0; a < 3; a++) {
        WIDTH_U(s.sk[a], NP_SIMPLEX_SKEW_BITS, mx[W_SK]);
        WIDTH_U(s.cell[a], NP_SIMPLEX_CELL_BITS, mx[W_CELL]);
        WIDTH_S(s.off[a], NP_SIMPLEX_OFF_BITS, mx[W_OFF]);
        WIDTH_S(s.qs[a], wp + 3u, mx[W_QS]);
        WIDTH_S(s.df[a], cfg->dout_bits, mx[W_DF]);
    }
    for (unsigned c = 0; c < 4; c++) {
        WIDTH_S(s.gd[c], NP_SIMPLEX_GD_BITS, mx[W_GD]);
        WIDTH_U(s.r2[c], NP_SIMPLEX_R2_BITS, mx[W_R2]);
        WIDTH_U(s.t[c], NP_SIMPLEX_T_BITS, mx[W_T]);
        WIDTH_U(s.tau2[c], wt, mx[W_TAU2]);
        WIDTH_U(s.tau3[c], wt, mx[W_TAU3]);
        WIDTH_U(s.tau4[c], wt, mx[W_TAU4]);
        WIDTH_S(s.fc[c], wp + 1u, mx[W_FC]);
        WIDTH_S(s.q[c], wp + 1u, mx[W_Q]);
        for (unsigned a = 0; a < 3; a++) {
            WIDTH_S(s.d[c][a], NP_SIMPLEX_OFF_BITS, mx[W_D]);
            NP_CHECK(s.d[c][a] >= -NP_SIMPLEX_UNIT && s.d[c][a] <= NP_SIMPLEX_UNIT, "|D| > 1536");
            WIDTH_S(s.e[c][a], wp + 1u, mx[W_E]);
            WIDTH_S(s.m[c][a], wp + 1u, mx[W_M]);
            WIDTH_S(s.e[c][a] - s.m[c][a], wp + 1u, mx[W_EM]);
        }
        NP_CHECK(s.r2[c] <= (uint32_t)NP_SIMPLEX_UNIT * NP_SIMPLEX_UNIT, "R2 > 1536^2");
    }
    WIDTH_S(s.s, wp + 2u, mx[W_S]);
    WIDTH_S(s.f, cfg->out_bits, mx[W_F]);
    /* The saturation never acts: the rounded value before it already fits. */
    int64_t rf = np_simplex_requant(np_simplex_kf(cfg) * s.s, cfg->k_frac + cfg->p_frac, np_simplex_f_frac(cfg));
    NP_CHECK(np_fits_s(rf, cfg->out_bits), "f saturated: %lld", (long long)rf);
    for (unsigned a = 0; a < 3; a++) {
        int64_t rd = np_simplex_requant(np_simplex_kd(cfg) * s.qs[a], cfg->k_frac + cfg->p_frac, np_simplex_d_frac(cfg));
        NP_CHECK(np_fits_s(rd, cfg->dout_bits), "df saturated: %lld", (long long)rd);
    }
}

static int max_magnitude(void)
{
    /* 1. The output formats: adversarial-gradient bounds over every local configuration. */
    mag_ctx c;
    memset(&c, 0, sizeof c);
    uint64_t nconf = for_each_config(mag_visit, &c);
    printf("over all %llu local configurations, any gradients: |f| <= %.6f (at U,V,W = %d,%d,%d), "
           "|df_a| <= %.6f\n",
           (unsigned long long)nconf, c.bf, c.at_f[0], c.at_f[1], c.at_f[2], c.bd);
    NP_CHECK(c.bf < 0.5, "f does not fit Q-1: bound %.6f", c.bf);
    NP_CHECK(c.bd < 2.0, "df does not fit Q1: bound %.6f", c.bd);
    NP_CHECK(fabs(c.bf - 0.347438) < 1e-6 && fabs(c.bd - 1.740774) < 1e-6, "bounds differ from np_simplex.h");

    /* 2. What the unit produces: random inputs and every exact cell centre (U = V = W = 384). */
    np_simplex_cfg cfg = default_cfg();
    long long mx[W_N];
    memset(mx, 0, sizeof mx);
    np_rng r;
    np_rng_seed(&r, 31);
    int32_t best_f = 0, best_d = 0;
    uint16_t at_f[3] = { 0, 0, 0 }, at_d[3] = { 0, 0, 0 };
    for (unsigned it = 0; it < 300000; it++) {
        uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
        check_widths(&cfg, x, y, z, mx);
    }
    /* cells (i, j, k) with i + j + k = 0 mod 3 have an input exactly at the centre U = V = W = 384 */
    unsigned ncentre = 0;
    for (int32_t i = 0; i < 256; i++)
        for (int32_t j = 0; j < 256; j++)
            for (int32_t k = (3 - (i + j) % 3) % 3; k < 256; k += 3) {
                int32_t n = i + j + k, num[3] = { 384 + 1536 * i - 256 * n, 384 + 1536 * j - 256 * n,
                                                  384 + 1536 * k - 256 * n };
                if (num[0] < 0 || num[1] < 0 || num[2] < 0 || num[0] > 6 * 0xffff || num[1] > 6 * 0xffff ||
                    num[2] > 6 * 0xffff)
                    continue;
                uint16_t in[3] = { (uint16_t)(num[0] / 6), (uint16_t)(num[1] / 6), (uint16_t)(num[2] / 6) };
                np_simplex_out o;
                np_simplex_eval(&cfg, in[0], in[1], in[2], &o);
                ncentre++;
                if (abs(o.f) > best_f) {
                    best_f = abs(o.f);
                    memcpy(at_f, in, sizeof in);
                }
            }
    check_widths(&cfg, at_f[0], at_f[1], at_f[2], mx);
    /* the largest |df| over the random inputs */
    np_rng_seed(&r, 31);
    for (unsigned it = 0; it < 1000000; it++) {
        uint16_t in[3];
            rnd3(&r, in);
        np_simplex_out o;
        np_simplex_eval(&cfg, in[0], in[1], in[2], &o);
        for (unsigned a = 0; a < 3; a++)
            if (abs(o.df[a]) > best_d) {
                best_d = abs(o.df[a]);
                memcpy(at_d, in, sizeof in);
            }
        if (abs(o.f) > best_f) {
            best_f = abs(o.f);
            memcpy(at_f, in, sizeof in);
        }
    }
    printf("largest |f| the unit produced: %d = %.6f at (%04x,%04x,%04x) (of 1e6 random inputs and %u exact "
           "cell centres); largest |df| %d = %.6f at (%04x,%04x,%04x)\n",
           best_f, best_f / p2(np_simplex_f_frac(&cfg)), at_f[0], at_f[1], at_f[2], ncentre, best_d,
           best_d / p2(np_simplex_d_frac(&cfg)), at_d[0], at_d[1], at_d[2]);
    NP_CHECK(best_f / p2(np_simplex_f_frac(&cfg)) <= c.bf + 1e-4, "f above the bound");
    NP_CHECK(best_d / p2(np_simplex_d_frac(&cfg)) <= c.bd + 1e-3, "df above the bound");

    /* 3. Every intermediate against its declared width, also at other widths. */
    static const unsigned cfgs[][3] = { { 16, 16, 1 }, { 8, 8, 1 }, { 20, 20, 1 }, { 4, 5, 1 }, { 12, 6, 0 } };
    for (unsigned ci = 1; ci < 5; ci++) {
        np_simplex_cfg k = np_simplex_cfg_default(cfgs[ci][0], cfgs[ci][1], cfgs[ci][2]);
        k.deriv = 1; /* trace every signal */
        long long m2[W_N];
        memset(m2, 0, sizeof m2);
        for (unsigned it = 0; it < 50000; it++) {
            uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
            check_widths(&k, x, y, z, m2);
        }
        check_widths(&k, at_f[0], at_f[1], at_f[2], m2);
        check_widths(&k, at_d[0], at_d[1], at_d[2], m2);
    }
    printf("every signal within its width over 3e5 random inputs and the extremes (default unit; 5e4 each at 4 other widths):\n");
    for (unsigned w = 0; w < W_N; w++) {
        double scale = 1.0;
        if (w >= W_TAU2 && w <= W_TAU4)
            scale = p2(cfg.t_frac);
        else if (w >= W_FC && w <= W_QS)
            scale = p2(cfg.p_frac);
        else if (w == W_F)
            scale = p2(np_simplex_f_frac(&cfg));
        else if (w == W_DF)
            scale = p2(np_simplex_d_frac(&cfg));
        printf("  %-12s max |word| %12lld", W_NAME[w], mx[w]);
        if (scale != 1.0)
            printf("  = %.6f", (double)mx[w] / scale);
        printf("\n");
    }
    NP_CHECK(np_simplex_kf(&cfg) < (1ll << cfg.k_frac) && np_simplex_kd(&cfg) < (1ll << (cfg.k_frac + 2u)),
             "constants");
    return 0;
}

/* ------------------------------------------------------------------------ */

static int reference_face_jump(void)
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

/* ------------------------------------------------------------------------ */

static int wrap(void)
{
    np_simplex_cfg cfg = default_cfg();
    np_rng r;
    np_rng_seed(&r, 256);
    /* 1. The skewed lattice mod 256: (128,128,128) = 0x8000 per word is a period, bit for bit. */
    unsigned same = 0, n = 500000;
    for (unsigned it = 0; it < n; it++) {
        uint16_t x = (uint16_t)(rnd16(&r) & 0x7fffu), y = (uint16_t)(rnd16(&r) & 0x7fffu),
                 z = (uint16_t)(rnd16(&r) & 0x7fffu);
        np_simplex_out a, b;
        np_simplex_eval(&cfg, x, y, z, &a);
        np_simplex_eval(&cfg, (uint16_t)(x + 0x8000u), (uint16_t)(y + 0x8000u), (uint16_t)(z + 0x8000u), &b);
        int eq = a.f == b.f && a.df[0] == b.df[0] && a.df[1] == b.df[1] && a.df[2] == b.df[2];
        NP_CHECK(eq, "(%04x,%04x,%04x) vs +0x8000", x, y, z);
        same += (unsigned)eq;
    }
    printf("unit: outputs at (x,y,z) and (x,y,z) + 0x8000 identical at %u of %u inputs (cells i and i + 256 "
           "hash alike)\n",
           same, n);
    /* 2. The unit against the Appendix B transcription (unbounded ints) in cells 256..511. */
    double maxe = 0.0;
    for (unsigned it = 0; it < 300000; it++) {
        uint16_t x = (uint16_t)(rnd16(&r) | 0x8000u), y = (uint16_t)(rnd16(&r) | 0x8000u),
                 z = (uint16_t)(rnd16(&r) | 0x8000u);
        np_simplex_out o;
        np_simplex_eval(&cfg, x, y, z, &o);
        double j = J_noise(x / 256.0, y / 256.0, z / 256.0) * p2(16);
        maxe = fmax(maxe, fabs(o.f - j));
        NP_CHECK(fabs(o.f - j) <= 1.0, "(%04x,%04x,%04x): unit %d, Appendix B %.3f", x, y, z, o.f, j);
    }
    printf("unit vs Appendix B (hash on unbounded ints) with every cell index >= 256: max f error %.4f LSB\n", maxe);
    /* 3. The reference: periodic under skewed translations by 256, also into negative coordinates. */
    double m1 = 0.0, m2 = 0.0;
    for (unsigned it = 0; it < 200000; it++) {
        double x = rnd01(&r) * 256.0, y = rnd01(&r) * 256.0, z = rnd01(&r) * 256.0;
        double f = np_ref_simplex3(x, y, z, NULL);
        if (face_distance(x, y, z) < 1e-9)
            continue; /* a translation's rounding could cross a face */
        m1 = fmax(m1, fabs(f - np_ref_simplex3(x - 128.0, y - 128.0, z - 128.0, NULL)));
        m1 = fmax(m1, fabs(f - np_ref_simplex3(x + 384.0, y + 384.0, z + 384.0, NULL)));
        /* skewed (256, 0, 0) unskewed: (256 - 256/6, -256/6, -256/6) */
        m2 = fmax(m2, fabs(f - np_ref_simplex3(x + 640.0 / 3.0, y - 128.0 / 3.0, z - 128.0 / 3.0, NULL)));
    }
    printf("reference: |f(p) - f(p + k (128,128,128))| <= %.3g (k = -1, 3); "
           "|f(p) - f(p + (640/3, -128/3, -128/3))| <= %.3g\n",
           m1, m2);
    NP_CHECK(m1 < 1e-12 && m2 < 1e-9, "reference not periodic under skewed translations by 256");
    /* 4. No tiling at 256 along an axis: the seam where an input word wraps. */
    double seam_unit = 0.0, seam_ref = 0.0, cont = 0.0;
    for (unsigned it = 0; it < 100000; it++) {
        uint16_t y = rnd16(&r), z = rnd16(&r);
        np_simplex_out a, b;
        np_simplex_eval(&cfg, 0xffff, y, z, &a);
        np_simplex_eval(&cfg, 0x0000, y, z, &b);
        seam_unit = fmax(seam_unit, fabs((double)(a.f - b.f)));
        double yy = y / 256.0, zz = z / 256.0;
        double r256 = np_ref_simplex3(256.0, yy, zz, NULL), r0 = np_ref_simplex3(0.0, yy, zz, NULL);
        seam_ref = fmax(seam_ref, fabs(r256 - r0) * p2(16));
        if (face_distance(256.0, yy, zz) > 1.0 / 512)
            cont = fmax(cont, fabs(np_ref_simplex3(255.99609375, yy, zz, NULL) - r256) * p2(16));
    }
    printf("input wrap 0xffff -> 0x0000 on x: the unit's f jumps by up to %.0f LSB; the reference's "
           "|f(256,y,z) - f(0,y,z)| is up to %.0f LSB, while f(256 - 1/256) to f(256) moves at most %.1f LSB "
           "(away from faces): the unit computes f on [0,256)^3 and does not tile at 256\n",
           seam_unit, seam_ref, cont);
    NP_CHECK(seam_ref > 100.0, "the function unexpectedly tiles at 256");
    return 0;
}

/* ------------------------------------------------------------------------ */

static int div3_exhaustive(void)
{
    for (uint32_t n = 0; n < 2048; n++)
        NP_CHECK(np_simplex_div3(n) == n / 3u, "div3(%u) = %u", n, np_simplex_div3(n));
    /* and the skewed cell over every value of 4x + y + z */
    for (uint32_t sx = 0; sx <= 6u * 65535u; sx++)
        NP_CHECK(np_simplex_cell(sx) == sx / NP_SIMPLEX_SKEW_CELL, "cell(%u)", sx);
    puts("floor(n/3) = (683 n) >> 11 for n < 2048; cell = floor(SX/768) for every SX 0..393210");
    return 0;
}

static int deriv_off_same_f(void)
{
    /* With the same widths, omitting the derivative datapath changes no bit of f. */
    np_simplex_cfg d = default_cfg(), f = d;
    f.deriv = 0;
    np_rng r;
    np_rng_seed(&r, 8);
    for (unsigned it = 0; it < 300000; it++) {
        uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
        np_simplex_out a, b;
        np_simplex_eval(&d, x, y, z, &a);
        np_simplex_eval(&f, x, y, z, &b);
        NP_CHECK(a.f == b.f && b.df[0] == 0 && b.df[1] == 0 && b.df[2] == 0, "(%04x,%04x,%04x)", x, y, z);
    }
    /* and the f-only default is faithful on its own */
    np_simplex_cfg f16 = np_simplex_cfg_default(16, 16, 0);
    emax m;
    memset(&m, 0, sizeof m);
    for (unsigned it = 0; it < 1000000; it++) {
        uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
        errs e;
        measure(&f16, x, y, z, &e);
        emax_add(&m, &e, x, y, z);
    }
    printf("deriv=0 with the deriv=1 widths: f bit-identical on 3e5 inputs; f-only default (t_frac=%u p_frac=%u "
           "k_frac=%u, bound %.4f LSB): ",
           f16.t_frac, f16.p_frac, f16.k_frac, np_simplex_error_bound_lsb(&f16, 0));
    emax_print("f", &m, 0);
    emax_check("f only", &m, &f16);
    return 0;
}

static int error_bound_configs(void)
{
    /*
     * The error argument of np_simplex.h, measured: the max error over random
     * inputs stays within the bound for each configuration; cheap ones exceed
     * 1 LSB (so the check can fail).
     */
    static const np_simplex_cfg cfgs[] = {
        { 16, 16, 1, 24, 22, 22 }, { 8, 8, 1, 16, 14, 13 }, { 12, 12, 1, 20, 18, 17 }, { 20, 20, 1, 27, 26, 26 },
        { 16, 16, 1, 18, 22, 22 }, { 16, 16, 1, 24, 15, 22 }, { 16, 16, 1, 24, 22, 12 }, { 8, 8, 1, 8, 8, 8 },
    };
    np_rng r;
    np_rng_seed(&r, 3);
    double worst_cheap = 0.0;
    for (unsigned c = 0; c < sizeof cfgs / sizeof cfgs[0]; c++) {
        const np_simplex_cfg *cfg = &cfgs[c];
        NP_CHECK(np_simplex_cfg_check(cfg) == NULL, "cfg %u invalid", c);
        emax m;
        memset(&m, 0, sizeof m);
        for (unsigned i = 0; i < 200000; i++) {
            uint16_t x = rnd16(&r), y = rnd16(&r), z = rnd16(&r);
            errs e;
            measure(cfg, x, y, z, &e);
            emax_add(&m, &e, x, y, z);
        }
        double bf = np_simplex_error_bound_lsb(cfg, 0), bd = np_simplex_error_bound_lsb(cfg, 1);
        double ed = fmax(m.e[1], fmax(m.e[2], m.e[3]));
        printf("out=%2u dout=%2u t_frac=%2u p_frac=%2u k_frac=%2u: f %.4f LSB (bound %.4f, CR %.2f%%), "
               "df %.4f LSB (bound %.4f, CR %.2f%%)\n",
               cfg->out_bits, cfg->dout_bits, cfg->t_frac, cfg->p_frac, cfg->k_frac, m.e[0], bf,
               100.0 * (double)m.cr[0] / (double)m.n, ed, bd, 100.0 * (double)m.cr[1] / (double)m.n);
        NP_CHECK(m.e[0] <= bf && ed <= bd, "measured error above the argument's bound");
        if (bf > 1.0 || bd > 1.0)
            worst_cheap = fmax(worst_cheap, fmax(m.e[0], ed));
        else
            NP_CHECK(m.e[0] <= 1.0 && ed <= 1.0, "faithful config not faithful");
    }
    NP_CHECK(worst_cheap > 1.0, "cheap configurations should show errors above 1 LSB (got %.3f)", worst_cheap);
    for (unsigned o = NP_SIMPLEX_OUT_MIN; o <= NP_SIMPLEX_OUT_MAX; o++)
        for (unsigned d = NP_SIMPLEX_DOUT_MIN; d <= NP_SIMPLEX_OUT_MAX; d++)
            for (unsigned dv = 0; dv < 2; dv++) {
                np_simplex_cfg k = np_simplex_cfg_default(o, d, dv);
                NP_CHECK(np_simplex_cfg_check(&k) == NULL, "default %u %u %u invalid", o, d, dv);
                NP_CHECK(np_simplex_error_bound_lsb(&k, 0) < 1.0, "default %u %u %u: f not faithful by argument", o, d, dv);
                if (dv)
                    NP_CHECK(np_simplex_error_bound_lsb(&k, 1) < 1.0, "default %u %u: df not faithful by argument", o, d);
            }
    puts("every default configuration (out_bits 4..20, dout_bits 5..20, deriv 0/1) is faithful by the argument");
    return 0;
}

static int registry(void)
{
    /* The unit through the registry: configuration keys, fields, words, pipe. */
    const np_unit *u = np_unit_find("simplex3");
    NP_CHECK(u == &np_unit_simplex3, "simplex3 registered");
    np_unit_cfg cfg;
    char err[256];
    NP_CHECK(np_unit_configure(u, &cfg, "", err, sizeof err) == 0, "defaults: %s", err);
    char buf[256];
    np_unit_cfg_format(u, &cfg, buf, sizeof buf);
    puts(buf);
    NP_CHECK(strcmp(buf, "out_bits=16 dout_bits=16 deriv=1 t_frac=24 p_frac=22 k_frac=22") == 0, "default format");
    np_unit_fields f;
    u->fields(&cfg, &f);
    NP_CHECK(f.n_in == 3 && f.n_out == 4, "fields");
    NP_CHECK(strcmp(f.out[0].format, "s16 Q-1.16") == 0 && strcmp(f.out[3].format, "s16 Q1.14") == 0 &&
                 strcmp(f.out[2].name, "dfdy") == 0, "formats %s %s", f.out[0].format, f.out[3].format);
    uint64_t in[3] = { 0x1234, 0x5678, 0x9abc }, out[4];
    double rv[4];
    u->eval(&cfg, in, out);
    u->ref(&cfg, in, rv);
    for (unsigned k = 0; k < 4; k++)
        NP_CHECK(fabs(np_unit_field_value(&f.out[k], out[k]) - rv[k]) <= ldexp(1.0, -(int)f.out[k].frac),
                 "field %u", k);
    NP_CHECK(np_unit_configure(u, &cfg, "deriv=0,out_bits=8", err, sizeof err) == 0, "%s", err);
    np_unit_cfg_format(u, &cfg, buf, sizeof buf);
    puts(buf);
    u->fields(&cfg, &f);
    NP_CHECK(f.n_out == 1 && f.out[0].bits == 8, "deriv=0 fields");
    NP_CHECK(np_unit_configure(u, &cfg, "t_frac=20,out_bits=12", err, sizeof err) == 0, "%s", err);
    np_unit_cfg_format(u, &cfg, buf, sizeof buf);
    NP_CHECK(strstr(buf, "t_frac=20") != NULL, "hand-set width kept: %s", buf);
    NP_CHECK(np_unit_configure(u, &cfg, "out_bits=21", err, sizeof err) != 0, "out_bits 21 accepted");
    NP_CHECK(np_unit_configure(u, &cfg, "deriv=2", err, sizeof err) != 0, "deriv 2 accepted");
    NP_CHECK(np_unit_configure(u, &cfg, "bogus=1", err, sizeof err) != 0, "unknown key accepted");
    size_t nb = u->boundary(&cfg, NULL, 0);
    NP_CHECK(nb > 20, "boundary table");
    printf("registry: simplex3 configures, formats, evaluates; %zu boundary inputs\n", nb);
    return 0;
}

/* ------------------------------------------------------------------------ */
/*
 * The datapath declaration (np_simplex_datapath, which the gate report
 * prices) against the model, as classic.datapath_widths does: trace every
 * declared signal over the boundary table, the extremes and random inputs;
 * a declared width must hold the traced range, and may be wider than needed
 * by at most NP_WIDTH_MARGIN bits (the margin covers values the range
 * argument allows but the inputs do not reach, e.g. |D_a|^2 <= 1536^2 while
 * |D_a| <= 1280 in practice).
 */
enum { NP_WIDTH_MARGIN = 1, DP_MAX_OPS = 160 };

/*
 * The modular forms the declaration prices, on one input after RK and CH:
 * U mod 2^12 from the input word mod 2^11, the cell mod 8 and n mod 16;
 * D from U's top nibble; 683 n as four shift-adds.
 */
static void check_modular(const np_simplex_sig *s, int after_ch)
{
    const uint16_t in[3] = { s->x, s->y, s->z };
    uint32_t n16 = (s->cell[0] + s->cell[1] + s->cell[2]) & 15u;
    for (unsigned a = 0; a < 3; a++) {
        uint32_t nn = s->sk[a] >> 8, n11 = ((nn << 2) + nn) * 2u + nn, n683 = ((n11 << 5) - n11) * 2u + nn;
        NP_CHECK(n683 == 683u * nn, "683 n as shift-adds");
        uint32_t x6 = 2u * ((2u * (in[a] & 0x7ffu) + (in[a] & 0x7ffu)) & 0x7ffu);  /* 6a mod 2^12 */
        uint32_t i3 = (2u * (s->cell[a] & 7u) + (s->cell[a] & 7u)) & 7u;            /* 3i mod 8 */
        uint32_t top = (n16 - 2u * i3) & 15u;
        int32_t u = (int32_t)np_sext((x6 + 256u * top) & 0xfffu, 12);
        NP_CHECK(u == s->off[a], "U mod 2^12 at (%04x,%04x,%04x): %d, model %d", s->x, s->y, s->z, u, s->off[a]);
        if (!after_ch)
            continue;
        for (unsigned c = 0; c < 4; c++) {
            unsigned am = np_simplex_corner_mask(s->hi, s->lo, c) >> a & 1u;
            uint32_t k = ((uint32_t)c - 6u * am) & 15u;
            int32_t d = (int32_t)np_sext(((uint32_t)s->off[a] + 256u * k) & 0xfffu, 12);
            NP_CHECK(d == s->d[c][a], "D nibble at (%04x,%04x,%04x)", s->x, s->y, s->z);
        }
    }
}

/* Trace every declared signal of cfg over n random inputs plus the boundary table; 0 or the failures. */
static int trace_widths(const np_simplex_cfg *cfg, unsigned nrand, uint64_t seed, int print)
{
    int before = np_test_failures;
    np_op ops[DP_MAX_OPS];
    size_t nops = np_simplex_datapath(cfg, ops, DP_MAX_OPS);
    NP_CHECK(nops <= DP_MAX_OPS && nops <= NP_REPORT_MAX_OPS, "declaration too long: %zu ops", nops);
    if (nops > DP_MAX_OPS)
        return 1;
    const np_stage_desc *tab = np_simplex_stage_table(cfg);
    unsigned nst = np_simplex_stage_count(cfg);
    np_trace t[DP_MAX_OPS];
    size_t nt = 0;
    for (size_t i = 0; i < nops; i++) {
        unsigned k = 0;
        while (k < nst && strcmp(tab[k].name, ops[i].stage) != 0)
            k++;
        NP_CHECK(k < nst, "op in unknown stage %s", ops[i].stage);
        NP_CHECK(ops[i].level < 8, "%s: level %u (the report sums 8 levels)", ops[i].stage, ops[i].level);
        if (ops[i].signal && ops[i].out) {
            t[nt].signal = ops[i].signal;
            t[nt].samples = 0;
            t[nt].lo = t[nt].hi = 0;
            nt++;
        }
    }
    uint64_t (*b)[NP_UNIT_MAX_FIELDS] = NULL;
    size_t nb = np_unit_simplex3.boundary(NULL, NULL, 0);
    b = malloc(nb * sizeof *b);
    NP_CHECK(b != NULL, "out of memory");
    if (!b)
        return 1;
    np_unit_simplex3.boundary(NULL, b, nb);
    np_rng r;
    np_rng_seed(&r, seed);
    for (size_t it = 0; it < nb + nrand; it++) {
        np_simplex_sig s;
        memset(&s, 0, sizeof s);
        if (it < nb) {
            s.x = (uint16_t)b[it][0];
            s.y = (uint16_t)b[it][1];
            s.z = (uint16_t)b[it][2];
        } else {
            s.x = rnd16(&r);
            s.y = rnd16(&r);
            s.z = rnd16(&r);
        }
        for (unsigned k = 0; k < nst; k++) {
            tab[k].fn(cfg, &s);
            np_simplex_trace(cfg, k, &s, t, nt);
            if (strcmp(tab[k].name, "CH") == 0 && (it & 15u) == 0)
                check_modular(&s, 1);
        }
    }
    free(b);
    if (print)
        printf("  %-6s %9s %-36s %5s\n", "signal", "declared", "traced range", "needs");
    for (size_t i = 0, ti = 0; i < nops; i++) {
        if (!(ops[i].signal && ops[i].out))
            continue;
        np_trace *tr = &t[ti++];
        unsigned need = np_bits_for_range(tr->lo, tr->hi, ops[i].out_signed);
        NP_CHECK(tr->samples > 0, "signal %s never traced", tr->signal);
        NP_CHECK(need <= ops[i].out, "t_frac=%u p_frac=%u: %s declared %u bits, needs %u ([%lld, %lld])", cfg->t_frac,
                 cfg->p_frac, tr->signal, ops[i].out, need, (long long)tr->lo, (long long)tr->hi);
        NP_CHECK(ops[i].out <= need + NP_WIDTH_MARGIN, "t_frac=%u p_frac=%u: %s declared %u bits, needs only %u",
                 cfg->t_frac, cfg->p_frac, tr->signal, ops[i].out, need);
        if (print) {
            char range[64];
            snprintf(range, sizeof range, "[%lld, %lld]", (long long)tr->lo, (long long)tr->hi);
            printf("  %-6s %8u%s %-36s %5u\n", tr->signal, ops[i].out, ops[i].out_signed ? "s" : "u", range, need);
        }
    }
    return np_test_failures - before;
}

/* Total gates of cfg as the gate report prices it. */
static double priced_total(const np_simplex_cfg *cfg, unsigned *reg_bits)
{
    np_unit_cfg uc;
    char spec[160], err[256];
    snprintf(spec, sizeof spec, "out_bits=%u,dout_bits=%u,deriv=%u,t_frac=%u,p_frac=%u,k_frac=%u", cfg->out_bits,
             cfg->dout_bits, cfg->deriv, cfg->t_frac, cfg->p_frac, cfg->k_frac);
    NP_CHECK(np_unit_configure(&np_unit_simplex3, &uc, spec, err, sizeof err) == 0, "%s", err);
    np_unit_cost c;
    NP_CHECK(np_unit_cost_compute(&np_unit_simplex3, &uc, &np_cost_default, &c, err, sizeof err) == 0, "%s", err);
    *reg_bits = c.reg_bits;
    return c.total;
}

static int datapath_widths(void)
{
    static const unsigned defaults[][3] = { { 16, 16, 1 }, { 16, 16, 0 }, { 8, 8, 1 }, { 12, 6, 0 },
                                            { 20, 20, 1 }, { 4, 5, 1 } };
    enum { N_DEF = sizeof defaults / sizeof defaults[0] };
    np_simplex_cfg cfgs[N_DEF + 2];
    for (unsigned c = 0; c < N_DEF; c++)
        cfgs[c] = np_simplex_cfg_default(defaults[c][0], defaults[c][1], defaults[c][2]);
    cfgs[N_DEF] = (np_simplex_cfg){ 8, 8, 1, 8, 8, 8 };       /* narrow: every fraction width 8 */
    cfgs[N_DEF + 1] = (np_simplex_cfg){ 16, 16, 0, 12, 10, 9 }; /* narrow, f only */
    for (unsigned c = 0; c < N_DEF + 2; c++) {
        const np_simplex_cfg *cfg = &cfgs[c];
        if (c == 0)
            printf("default unit (out_bits=16 dout_bits=16 deriv=1 t_frac=%u p_frac=%u k_frac=%u), "
                   "1e5 random inputs and the %zu boundary inputs:\n",
                   cfg->t_frac, cfg->p_frac, cfg->k_frac, np_unit_simplex3.boundary(NULL, NULL, 0));
        int bad = trace_widths(cfg, c == 0 ? 100000u : 40000u, 40u + c, c == 0);
        printf("out=%2u dout=%2u deriv=%u t_frac=%2u p_frac=%2u k_frac=%2u: %s\n", cfg->out_bits, cfg->dout_bits,
               cfg->deriv, cfg->t_frac, cfg->p_frac, cfg->k_frac, bad ? "FAILED" : "every width holds, margin <= 1");
    }

    /* deriv = 0 leaves the derivative datapath out: no derivative signal, fewer gates and register bits. */
    static const char *const dsig[] = { "tau3p", "tau3", "qp", "q", "e", "q5", "mp", "m", "em", "qs", "dprod", "df" };
    for (unsigned c = 0; c < N_DEF + 2; c++) {
        np_simplex_cfg d1 = cfgs[c], d0 = cfgs[c];
        d1.deriv = 1;
        d0.deriv = 0;
        np_op ops[DP_MAX_OPS];
        size_t n0 = np_simplex_datapath(&d0, ops, DP_MAX_OPS);
        for (size_t i = 0; i < n0 && i < DP_MAX_OPS; i++) {
            NP_CHECK(strcmp(ops[i].stage, "M2") != 0, "deriv=0 declares an M2 op");
            for (unsigned k = 0; ops[i].signal && k < sizeof dsig / sizeof dsig[0]; k++)
                NP_CHECK(strcmp(ops[i].signal, dsig[k]) != 0, "deriv=0 declares %s", dsig[k]);
        }
        unsigned r1, r0;
        double g1 = priced_total(&d1, &r1), g0 = priced_total(&d0, &r0);
        NP_CHECK(g0 < g1 && r0 < r1, "deriv=0 (%.0f gates, %u bits) not below deriv=1 (%.0f, %u)", g0, r0, g1, r1);
        if (c == 0) {
            np_simplex_cfg f16 = np_simplex_cfg_default(16, 16, 0);
            unsigned rf;
            double gf = priced_total(&f16, &rf);
            printf("priced: deriv=1 %.0f gates (%u register bits); deriv=0 same widths %.0f (%u); "
                   "deriv=0 own default %.0f (%u)\n", g1, r1, g0, r0, gf, rf);
            NP_CHECK(gf < g1, "f-only default not below deriv=1");
        }
    }
    puts("every declared signal width holds its traced range, within a margin of 1 bit (8 configurations); "
         "deriv=0 declares no derivative operator and prices below deriv=1");
    return 0;
}

static const np_test_case cases[] = {
    { "ref_vs_appendix_b", ref_vs_appendix_b },
    { "deriv_vs_central_diff", deriv_vs_central_diff },
    { "kat", kat },
    { "random_1e7", random_1e7 },
    { "cycle_vs_model_1e6", cycle_vs_model_1e6 },
    { "faces_uv", faces_uv },
    { "faces_vw", faces_vw },
    { "faces_uw", faces_uw },
    { "faces_uvw", faces_uvw },
    { "kernel_t_zero", kernel_t_zero },
    { "extremes_0_and_max", extremes_0_and_max },
    { "max_magnitude", max_magnitude },
    { "reference_face_jump", reference_face_jump },
    { "wrap", wrap },
    { "div3_exhaustive", div3_exhaustive },
    { "deriv_off_same_f", deriv_off_same_f },
    { "error_bound_configs", error_bound_configs },
    { "registry", registry },
    { "datapath_widths", datapath_widths },
    { "print_kat", print_kat }, /* generator of simplex3_kat.inc, not registered as a test */
    { NULL, NULL },
};

NP_TEST_MAIN(cases)
