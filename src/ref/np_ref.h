/* SPDX-License-Identifier: MIT */
/*
 * np_ref.h - float (double precision) references of the hardware units.
 *
 * Each reference is the same mathematical function as its unit, computed in
 * double from the exact input value, with no fixed-point anywhere. The
 * library is built with -ffp-contract=off and without -ffast-math, so every
 * result is identical across compilers and machines (IEEE-754 binary64,
 * round to nearest even, each operation rounded once).
 */
#ifndef NP_REF_H
#define NP_REF_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Classic 3-D gradient noise (Perlin, "Noise Hardware"): lattice tile of
 * 256, the table-free hash np_hash6, the Appendix B gradient written out in
 * double (independently of np_grad_decode), the s-curve 3t^2 - 2t^3 and seven
 * linear interpolations a + s (b - a). Any real input; |result| <= 1.5.
 */
double np_ref_classic3(double x, double y, double z);

/* The same at a u16 Q8.8 input: x/256, y/256, z/256. */
double np_ref_classic3_q88(uint16_t x, uint16_t y, uint16_t z);

/*
 * The same within one cell: h[c] the corner hashes (corner c = 4cz + 2cy + cx)
 * and (u, v, w) in [0, 1) the position in the cell. np_ref_classic3 is this
 * function after the lattice step; sweeps call it directly to hoist the hash.
 */
double np_ref_classic3_in_cell(const uint8_t h[8], double u, double v, double w);

/* Appendix B's gradient of 6-bit index h at (x, y, z), in double. */
double np_ref_grad(unsigned h, double x, double y, double z);

/*
 * 3-D simplex noise with analytic derivative (Perlin, "Noise Hardware",
 * Appendix B), computed with Appendix B's operations in Appendix B's order:
 * skew s = (x+y+z)/3, cell floor(x+s) etc., unskew (i+j+k)/6, the hi/lo
 * ranking rule with its ties, K() with t = .6 - x*x - y*y - z*z, 8 t^4 times
 * the gradient, the four corners summed left to right. The hash is np_hash6
 * on the corner's integer coordinates mod 256: Appendix B passes unbounded
 * ints (i + A[0], ...) to shuffle, whose b() reads bits 0..7 only (two's
 * complement bits, also for negative ints), which is hashing i mod 256.
 * The gradient is np_ref_grad (Appendix B's, in double).
 *
 * If grad is not NULL it receives (df/dx, df/dy, df/dz), the analytic
 * derivative inside the simplex: sum over corners with t > 0 of
 * 8 t^4 G - 64 t^3 (G . d) d (G = the gradient's coefficients). The
 * function is discontinuous across simplex faces (the kernel radius^2 0.6
 * exceeds the distance to the far face), so there the derivative is the one
 * of the simplex that Appendix B's ranking picks.
 *
 * Any real input with |x|, |y|, |z| <= 2^30; |f| < 0.348 (see np_simplex.h).
 */
double np_ref_simplex3(double x, double y, double z, double grad[3]);

/* The same at a u16 Q8.8 input: x/256, y/256, z/256 (the simplex3 unit's domain). */
double np_ref_simplex3_q88(uint16_t x, uint16_t y, uint16_t z, double grad[3]);


/*
 * --- The scanline texture model (Kameya & Hart, "Bresenham Noise"; units
 * np_fdiff and np_texel, rtl_model/np_texture.h) ---
 *
 * f(s) = q(s) + sum_i a_i n(M_i s + o_i), colour = c(f), all in double.
 * Lattice value noise: the value at lattice point (i, j, k) is
 * np_hash6(i mod 256, j mod 256, k mod 256) / 64, and n is its trilinear
 * interpolation, written as the seed's equations 9-11 (three levels of
 * linear interpolation), independently of the units' polynomial forms.
 */
enum { NP_REF_MAX_OCTAVES = 8, NP_REF_CMAP_MAX = 256 };

typedef struct np_ref_octave {
    double m[3][3]; /* T(s) = m s + o */
    double o[3];
    double amp;     /* a_i */
} np_ref_octave;

typedef struct np_ref_colormap {
    double f0, f1;  /* domain: one period (repeat) or the clamped range */
    unsigned n;     /* entries, 2..256 */
    int repeat;     /* 1: c is periodic in f with period f1 - f0 (n segments); 0: clamped (n - 1 segments) */
    double c[NP_REF_CMAP_MAX][3]; /* entries, in 8-bit units (0..255) */
} np_ref_colormap;

typedef struct np_ref_texture {
    double quad[10]; /* A B C D E F G H I J of equation 2 */
    unsigned n_oct;
    np_ref_octave oct[NP_REF_MAX_OCTAVES];
    np_ref_colormap cmap;
} np_ref_texture;

/* Lattice value at integer point (i, j, k): np_hash6 of each mod 256, / 64; in [0, 63/64]. */
double np_ref_lattice_value(int64_t i, int64_t j, int64_t k);

/* Trilinear lattice value noise at (x, y, z), any real input; in [0, 63/64]. */
double np_ref_value_noise(double x, double y, double z);

/* The quadric of equation 2 at s. */
double np_ref_quadric(const double k[10], const double s[3]);

/* f(s); if noise is not NULL, noise[i] receives n(T_i(s)) (before the amplitude). */
double np_ref_texture_f(const np_ref_texture *t, const double s[3], double *noise);

/* The colour map's table index x = S (f - f0) before wrapping or clamping (S: segments per unit f). */
double np_ref_colour_index(const np_ref_colormap *c, double f);

/* c(f) in 8-bit units (0..255, not rounded). */
void np_ref_colour(const np_ref_colormap *c, double f, double rgb[3]);

/*
 * The sample count of the aacount unit (rtl_model/np_aacount.h) as an exact
 * rational computation from the paper's definitions: k_d, k_n and k_s as
 * exact fractions, ceil and clamp to 1..n, the paper's index matrices for the
 * mask. No threshold register, no running minimum: the depth variance from the
 * pairwise differences, the normal test as "for every sample" in __int128
 * (src/ref/ref_aacount.c). Metrics the configuration leaves out count 0.
 */
struct np_aacount_cfg;
struct np_aacount_win;
typedef struct np_ref_aacount_counts {
    unsigned s, mask, sd, sn, ss;
} np_ref_aacount_counts;
void np_ref_aacount(const struct np_aacount_cfg *cfg, const struct np_aacount_win *w, np_ref_aacount_counts *out);

/*
 * The hatching unit (ref_hatch.c, docs/hatch.md): 255 c for the point whose
 * input words are xu, xv (Q1.32), tone (unorm8), pm, om (Q1.16), with the
 * configuration's patterns, rotations and stroke sizes as their exact values.
 * Seeds are the exact rationals rotl(b, i) / (2^N - 1) and x_s - s_i is
 * formed exactly in 128-bit integers (parity and fraction), so no input is
 * rounded before the double arithmetic. alpha (may be NULL) receives each
 * seed's alpha, layer-major ([l * N + i]). cfg is an np_hatch_cfg.
 */
struct np_hatch_cfg;
double np_ref_hatch(const struct np_hatch_cfg *cfg, uint64_t xu, uint64_t xv, uint32_t tone, uint32_t pm, uint32_t om,
                    double *alpha);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NP_REF_H */
