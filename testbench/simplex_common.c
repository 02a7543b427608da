/* SPDX-License-Identifier: MIT */
/* What the simplex unit's test files share (simplex_test.h). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "simplex_test.h"

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
double J_dK[3];

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

double J_noise(double x, double y, double z)
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


void measure(const np_simplex_cfg *cfg, uint16_t x, uint16_t y, uint16_t z, errs *r)
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


void emax_add(emax *m, const errs *r, uint16_t x, uint16_t y, uint16_t z)
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

const char *const FIELD[4] = { "f", "dfdx", "dfdy", "dfdz" };

void emax_print(const char *what, const emax *m, int deriv)
{
    printf("%s: %llu inputs, max error f %.4f", what, (unsigned long long)m->n, m->e[0]);
    if (deriv)
        printf(", dfdx %.4f, dfdy %.4f, dfdz %.4f", m->e[1], m->e[2], m->e[3]);
    printf(" LSB\n");
}

/* Every field within 1 LSB (and within the argument's bound). */
void emax_check(const char *what, const emax *m, const np_simplex_cfg *cfg)
{
    double bf = np_simplex_error_bound_lsb(cfg, 0), bd = np_simplex_error_bound_lsb(cfg, 1);
    unsigned nf = cfg->deriv ? 4u : 1u;
    for (unsigned k = 0; k < nf; k++) {
        double b = k == 0 ? bf : bd;
        NP_CHECK(m->e[k] <= b && m->e[k] <= 1.0, "%s: %s error %.4f LSB at (%04x,%04x,%04x), bound %.4f", what,
                 FIELD[k], m->e[k], m->at[k][0], m->at[k][1], m->at[k][2], b);
    }
}


uint64_t for_each_config(config_fn fn, void *ctx)
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
int input_of(int32_t u, int32_t v, int32_t w, int32_t i0, uint16_t in[3])
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
void front_end(uint16_t x, uint16_t y, uint16_t z, uint32_t cell[3], int32_t off[3])
{
    const uint16_t in[3] = { x, y, z };
    for (unsigned a = 0; a < 3; a++)
        cell[a] = np_simplex_cell(np_simplex_skew(in[a], in[(a + 1u) % 3u], in[(a + 2u) % 3u]));
    uint32_t n = cell[0] + cell[1] + cell[2];
    for (unsigned a = 0; a < 3; a++)
        off[a] = np_simplex_offset(in[a], cell[a], n);
}

/* Skewed fractional offsets and the smallest distance to a simplex or cell face, in skewed units. */
double face_distance(double x, double y, double z)
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

